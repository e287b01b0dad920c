//! The one way fsim reads a file a case names: regular files only, within a size limit.
//!
//! A case may come from anyone (docs/security.md, "Reads"): a field that is a symlink to
//! `/dev/zero`, a FIFO, a sparse file of a terabyte or a gzip bomb must be refused by name
//! instead of filling memory or blocking. [`read_regular_file`] checks the file's type and
//! size before opening it, opens it without blocking and checks again on the open file (the
//! path may have been swapped in between), and reads at most the limit; [`gunzip_bounded`]
//! limits the size gzip data expands to. docs/security.md gives the limits and their reasons.

use std::fmt;
use std::fs::{File, Metadata};
use std::io::Read;
use std::path::Path;

/// Largest case text file read (dictionary, field, positions file, include), before and
/// after gzip expansion: 1 GiB. A 10⁷-cell vector field at full precision is about 750 MB
/// and a 10⁶-particle positions file about 45 MB; any larger text would not fit the run's
/// memory beside it on the machines fsim targets.
pub const MAX_TEXT_BYTES: u64 = 1 << 30;

/// Largest size gzip text may expand to: 256 MiB. Refusing a gzip bomb costs the time to
/// expand it this far (about a second), so this limit is lower than [`MAX_TEXT_BYTES`]; a
/// larger compressed field (over 3·10⁶ cells of full-precision vectors) is read once
/// expanded with `gunzip`, as a plain file.
pub const MAX_GZIP_EXPANDED_BYTES: u64 = 256 << 20;

/// Largest restart file read: 64 GiB. fsim wrote it itself for a run of that size (8 bytes
/// per value); the limit only stops a sparse file from asking for more memory than exists,
/// and its memory is reserved fallibly, so that a smaller machine reports an error.
pub const MAX_RESTART_BYTES: u64 = 64 << 30;

/// Why a file was not read.
#[derive(Debug)]
pub enum ReadError {
    /// Nothing at that path.
    NotFound,
    /// Something that is not a regular file: its kind ("a directory", "a FIFO", …).
    NotRegular(&'static str),
    /// Larger than `limit` bytes (`size` when known from the file system).
    TooLarge { size: Option<u64>, limit: u64 },
    /// gzip data that expands past `limit` bytes.
    ExpandsTooFar { limit: u64 },
    /// The memory for the file's bytes could not be had.
    NoMemory { bytes: u64 },
    /// Any other failure of the system.
    Io(std::io::Error),
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReadError::NotFound => write!(f, "file not found"),
            ReadError::NotRegular(kind) => {
                write!(f, "expected a regular file, found {kind} (not read)")
            }
            ReadError::TooLarge {
                size: Some(size),
                limit,
            } => write!(
                f,
                "the file is {size} bytes, more than the {limit} bytes fsim reads (not read; \
                 see docs/security.md)"
            ),
            ReadError::TooLarge { size: None, limit } => write!(
                f,
                "the file holds more than the {limit} bytes fsim reads (see docs/security.md)"
            ),
            ReadError::ExpandsTooFar { limit } => write!(
                f,
                "the gzip data expands to more than the {limit} bytes fsim reads (see \
                 docs/security.md)"
            ),
            ReadError::NoMemory { bytes } => {
                write!(f, "cannot allocate {bytes} bytes to read the file")
            }
            ReadError::Io(e) => write!(f, "cannot read the file: {e}"),
        }
    }
}

/// The kind of a file that is not a regular one, as messages name it.
fn kind_of(meta: &Metadata) -> Option<&'static str> {
    use std::os::unix::fs::FileTypeExt;
    let t = meta.file_type();
    if t.is_file() {
        None
    } else if t.is_dir() {
        Some("a directory")
    } else if t.is_char_device() {
        Some("a character device")
    } else if t.is_block_device() {
        Some("a block device")
    } else if t.is_fifo() {
        Some("a FIFO (named pipe)")
    } else if t.is_socket() {
        Some("a socket")
    } else {
        Some("a special file")
    }
}

/// The kind of what stands at `path` when it exists and is not a regular file (a symlink
/// is followed), found without opening it; `None` for a regular file or nothing.
pub fn not_regular(path: &Path) -> Option<&'static str> {
    kind_of(&std::fs::metadata(path).ok()?)
}

/// Refuses what is not a regular file of at most `limit` bytes.
fn check(meta: &Metadata, limit: u64) -> Result<u64, ReadError> {
    if let Some(kind) = kind_of(meta) {
        return Err(ReadError::NotRegular(kind));
    }
    if meta.len() > limit {
        return Err(ReadError::TooLarge {
            size: Some(meta.len()),
            limit,
        });
    }
    Ok(meta.len())
}

/// The bytes of the regular file at `path` (a symlink is followed to what it names), at
/// most `limit` of them. Type and size are checked before opening, the file is opened
/// without blocking (a FIFO swapped in after the check does not hang the open) and checked
/// again through its descriptor, and at most `limit + 1` bytes are read, so that a file
/// growing meanwhile is refused too.
pub fn read_regular_file(path: &Path, limit: u64) -> Result<Vec<u8>, ReadError> {
    use std::os::unix::fs::OpenOptionsExt;
    let io = |e: std::io::Error| match e.kind() {
        std::io::ErrorKind::NotFound => ReadError::NotFound,
        _ => ReadError::Io(e),
    };
    check(&std::fs::metadata(path).map_err(io)?, limit)?;
    let file = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK | libc::O_NOCTTY)
        .open(path)
        .map_err(io)?;
    let size = check(&file.metadata().map_err(io)?, limit)?;
    read_limited(file, size, limit)
}

/// The first `max` bytes of the regular file at `path` and its size, for a look at a
/// header before the whole is read; `None` for anything [`read_regular_file`] would refuse
/// (it then says why).
pub fn read_head(path: &Path, max: u64) -> Option<(Vec<u8>, u64)> {
    use std::os::unix::fs::OpenOptionsExt;
    let file = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK | libc::O_NOCTTY)
        .open(path)
        .ok()?;
    let meta = file.metadata().ok()?;
    if !meta.is_file() {
        return None;
    }
    let mut head = Vec::new();
    file.take(max).read_to_end(&mut head).ok()?;
    Some((head, meta.len()))
}

/// At most `limit` bytes of `file`, `size` of them expected.
fn read_limited(file: File, size: u64, limit: u64) -> Result<Vec<u8>, ReadError> {
    let mut bytes = Vec::new();
    crate::memory::returning_failure(|| bytes.try_reserve_exact(size as usize))
        .map_err(|_| ReadError::NoMemory { bytes: size })?;
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(ReadError::Io)?;
    if bytes.len() as u64 > limit {
        return Err(ReadError::TooLarge { size: None, limit });
    }
    Ok(bytes)
}

/// gzip data (one or more members) expanded, refused once it expands past `limit` bytes. A
/// first pass counts the expanded bytes without keeping them, so that a gzip bomb costs
/// time in proportion to the limit but no memory; the second keeps them in a buffer
/// reserved at its exact size.
pub fn gunzip_bounded(data: &[u8], limit: u64) -> Result<Vec<u8>, ReadError> {
    let decoder = || flate2::read::MultiGzDecoder::new(data).take(limit + 1);
    let expanded = std::io::copy(&mut decoder(), &mut std::io::sink()).map_err(ReadError::Io)?;
    if expanded > limit {
        return Err(ReadError::ExpandsTooFar { limit });
    }
    let mut out = Vec::new();
    crate::memory::returning_failure(|| out.try_reserve_exact(expanded as usize))
        .map_err(|_| ReadError::NoMemory { bytes: expanded })?;
    decoder().read_to_end(&mut out).map_err(ReadError::Io)?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    fn scratch(tag: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("fsim-bounded-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn only_regular_files_within_the_limit_are_read() {
        let dir = scratch("kinds");
        let file = dir.join("f");
        std::fs::write(&file, b"12345").unwrap();
        assert_eq!(read_regular_file(&file, 5).unwrap(), b"12345");
        let e = read_regular_file(&file, 4).unwrap_err();
        assert!(
            matches!(
                e,
                ReadError::TooLarge {
                    size: Some(5),
                    limit: 4
                }
            ),
            "{e}"
        );
        let e = read_regular_file(&dir, 5).unwrap_err().to_string();
        assert!(e.contains("found a directory"), "{e}");
        let e = read_regular_file(Path::new("/dev/zero"), 5)
            .unwrap_err()
            .to_string();
        assert!(e.contains("found a character device"), "{e}");
        let link = dir.join("link");
        std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
        let e = read_regular_file(&link, 5).unwrap_err().to_string();
        assert!(e.contains("found a character device"), "{e}");
        let e = read_regular_file(&dir.join("none"), 5).unwrap_err();
        assert!(matches!(e, ReadError::NotFound));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_fifo_is_refused_without_blocking() {
        let dir = scratch("fifo");
        let fifo = dir.join("p");
        let name = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: a valid NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o600) }, 0);
        let e = read_regular_file(&fifo, 5).unwrap_err().to_string();
        assert!(e.contains("FIFO"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn gzip_is_refused_past_its_expanded_limit() {
        let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        enc.write_all(&[b'x'; 1000]).unwrap();
        let gz = enc.finish().unwrap();
        assert_eq!(gunzip_bounded(&gz, 1000).unwrap().len(), 1000);
        let e = gunzip_bounded(&gz, 999).unwrap_err();
        assert!(matches!(e, ReadError::ExpandsTooFar { limit: 999 }), "{e}");
    }
}
