//! Writing inside the case without following a symbolic link (docs/security.md, "Writes").
//!
//! Every file and directory fsim writes, renames or deletes is reached from an open
//! descriptor of the case directory, one path component at a time, with `O_NOFOLLOW`
//! (`openat`, `mkdirat`, `renameat`, `unlinkat`), never by a path the kernel resolves
//! again. A link planted in the case, before the run or while it runs, therefore cannot send a
//! write, a truncation or a deletion outside the case: the operation is refused with an error
//! naming the link. The case directory itself is opened as the user named it (it may be a
//! link: the user chose it).
//!
//! Refused rather than replaced: a link where fsim writes is either a mistake or an attack,
//! and replacing it would silently drop what the user may have meant (a `postProcessing`
//! kept on another disk); the error tells what to change. Hand-written on `rustix` rather
//! than `cap-std`: `cap-std` follows links as long as they stay inside the directory, while
//! fsim follows none below the case.

use super::output_error::OutputError;
use rustix::fs::{AtFlags, FileType, Mode, OFlags, RenameFlags};
use rustix::io::Errno;
use std::ffi::{OsStr, OsString};
use std::fs::File;
use std::io::{Read, Write};
use std::os::fd::OwnedFd;
use std::os::unix::ffi::OsStrExt;
use std::path::{Component, Path, PathBuf};

/// Permission bits of the directories fsim creates (before the umask), as `mkdir -p`.
const DIR_MODE: u32 = 0o777;
/// Permission bits of the files fsim creates (before the umask), as `File::create`.
const FILE_MODE: u32 = 0o666;

/// An open directory inside the case (or the case directory itself): every file and
/// directory below it is created, opened, renamed and removed relative to its descriptor,
/// without following a link.
#[derive(Debug)]
pub struct SafeDir {
    fd: OwnedFd,
    path: PathBuf,
}

/// What an entry of a directory is, seen without following a link.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EntryKind {
    File,
    Dir,
    Symlink,
    /// A FIFO, socket or device.
    Other,
}

impl EntryKind {
    fn of(file_type: FileType) -> Self {
        match file_type {
            FileType::RegularFile => EntryKind::File,
            FileType::Directory => EntryKind::Dir,
            FileType::Symlink => EntryKind::Symlink,
            _ => EntryKind::Other,
        }
    }
}

/// The error for a link found where fsim writes: one line naming the link.
pub fn symlink_refused(path: &Path) -> OutputError {
    OutputError::invalid(
        path,
        "is a symbolic link; fsim writes only inside the case and never through a link, so \
         it refuses to write there (remove the link, or put a real directory or file in its \
         place)",
    )
}

/// A single path component, as every name handed to [`SafeDir`] must be: not empty, no `/`,
/// not `.` or `..` (which would leave the directory).
fn check_name(dir: &Path, name: &OsStr) -> Result<(), OutputError> {
    let bytes = name.as_bytes();
    if bytes.is_empty() || bytes.contains(&b'/') || bytes == b"." || bytes == b".." {
        return Err(OutputError::invalid(
            &dir.join(name),
            "not a plain file name (fsim writes one path component at a time)",
        ));
    }
    Ok(())
}

impl SafeDir {
    /// Opens the case directory as the user named it (a link there is followed: the user
    /// chose it); everything below it is then reached without following links.
    pub fn open_case(case_dir: &Path) -> Result<Self, OutputError> {
        let fd = rustix::fs::open(
            case_dir,
            OFlags::RDONLY | OFlags::DIRECTORY | OFlags::CLOEXEC,
            Mode::empty(),
        )
        .map_err(|e| OutputError::io(case_dir, "cannot open case directory", e.into()))?;
        Ok(SafeDir {
            fd,
            path: case_dir.to_path_buf(),
        })
    }

    /// The directory's path, as the case directory was named plus the components below it
    /// (for messages; never used to open anything).
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// `path()/name`, for messages.
    pub fn join(&self, name: impl AsRef<OsStr>) -> PathBuf {
        self.path.join(name.as_ref())
    }

    /// What `name` is, without following a link; `None` when there is nothing of that name.
    pub fn kind(&self, name: impl AsRef<OsStr>) -> Result<Option<EntryKind>, OutputError> {
        let name = name.as_ref();
        check_name(&self.path, name)?;
        match rustix::fs::statat(&self.fd, name, AtFlags::SYMLINK_NOFOLLOW) {
            Ok(stat) => Ok(Some(EntryKind::of(FileType::from_raw_mode(stat.st_mode)))),
            Err(Errno::NOENT) => Ok(None),
            Err(e) => Err(OutputError::io(
                &self.join(name),
                "cannot inspect",
                e.into(),
            )),
        }
    }

    /// The error for a failed operation on `name`: a link in the way is named as such.
    fn error(&self, name: &OsStr, what: &str, e: Errno) -> OutputError {
        if let Ok(Some(EntryKind::Symlink)) = self.kind(name) {
            return symlink_refused(&self.join(name));
        }
        OutputError::io(&self.join(name), what, e.into())
    }

    /// Opens the existing subdirectory `name`; a link is refused.
    pub fn open_dir(&self, name: impl AsRef<OsStr>) -> Result<SafeDir, OutputError> {
        let name = name.as_ref();
        check_name(&self.path, name)?;
        let flags = OFlags::RDONLY | OFlags::DIRECTORY | OFlags::NOFOLLOW | OFlags::CLOEXEC;
        let fd = rustix::fs::openat(&self.fd, name, flags, Mode::empty())
            .map_err(|e| self.error(name, "cannot open directory", e))?;
        Ok(SafeDir {
            fd,
            path: self.join(name),
        })
    }

    /// Creates the new subdirectory `name` and opens it; an entry of that name (a link
    /// included) is an error.
    pub fn create_dir(&self, name: impl AsRef<OsStr>) -> Result<SafeDir, OutputError> {
        let name = name.as_ref();
        check_name(&self.path, name)?;
        rustix::fs::mkdirat(&self.fd, name, Mode::from_raw_mode(DIR_MODE))
            .map_err(|e| self.error(name, "cannot create directory", e))?;
        self.open_dir(name)
    }

    /// Opens the subdirectory `names[0]/names[1]/…`, creating what is missing, as
    /// `mkdir -p`; a link anywhere along it is refused.
    pub fn create_dir_all(&self, names: &[&str]) -> Result<SafeDir, OutputError> {
        let mut dir = self.try_clone()?;
        for name in names {
            dir = match dir.kind(name)? {
                None => match dir.create_dir(name) {
                    // made by someone else meanwhile: open it (still without following)
                    Err(_) if dir.kind(name)? == Some(EntryKind::Dir) => dir.open_dir(name)?,
                    other => other?,
                },
                Some(_) => dir.open_dir(name)?,
            };
        }
        Ok(dir)
    }

    /// A second descriptor of the same directory.
    pub fn try_clone(&self) -> Result<SafeDir, OutputError> {
        Ok(SafeDir {
            fd: self
                .fd
                .try_clone()
                .map_err(|e| OutputError::io(&self.path, "cannot open directory", e))?,
            path: self.path.clone(),
        })
    }

    /// Creates file `name` for writing, replacing a file of that name: the old one is
    /// unlinked and a new one created (`O_EXCL`), so neither a link nor a second hard link
    /// of the old file is ever written through. A link or a directory there is refused.
    pub fn create_file(&self, name: impl AsRef<OsStr>) -> Result<File, OutputError> {
        let name = name.as_ref();
        match self.kind(name)? {
            None => {}
            Some(EntryKind::Symlink) => return Err(symlink_refused(&self.join(name))),
            Some(EntryKind::Dir) => {
                return Err(OutputError::invalid(
                    &self.join(name),
                    "is a directory where fsim writes a file",
                ))
            }
            Some(_) => rustix::fs::unlinkat(&self.fd, name, AtFlags::empty())
                .map_err(|e| self.error(name, "cannot replace file", e))?,
        }
        let flags =
            OFlags::WRONLY | OFlags::CREATE | OFlags::EXCL | OFlags::NOFOLLOW | OFlags::CLOEXEC;
        let fd = rustix::fs::openat(&self.fd, name, flags, Mode::from_raw_mode(FILE_MODE))
            .map_err(|e| self.error(name, "cannot create file", e))?;
        Ok(File::from(fd))
    }

    /// Opens file `name` for reading; a link is refused.
    pub fn open_file(&self, name: impl AsRef<OsStr>) -> Result<File, OutputError> {
        let name = name.as_ref();
        check_name(&self.path, name)?;
        let flags = OFlags::RDONLY | OFlags::NOFOLLOW | OFlags::CLOEXEC;
        let fd = rustix::fs::openat(&self.fd, name, flags, Mode::empty())
            .map_err(|e| self.error(name, "cannot open file", e))?;
        Ok(File::from(fd))
    }

    /// The names in the directory (without `.` and `..`) and what each is.
    pub fn entries(&self) -> Result<Vec<(OsString, EntryKind)>, OutputError> {
        let list_err = |e: Errno| OutputError::io(&self.path, "cannot list", e.into());
        let mut entries = Vec::new();
        for entry in rustix::fs::Dir::read_from(&self.fd).map_err(list_err)? {
            let entry = entry.map_err(list_err)?;
            let name = OsStr::from_bytes(entry.file_name().to_bytes());
            if name == "." || name == ".." {
                continue;
            }
            let kind = match entry.file_type() {
                FileType::Unknown => match self.kind(name)? {
                    Some(kind) => kind,
                    None => continue,
                },
                file_type => EntryKind::of(file_type),
            };
            entries.push((name.to_os_string(), kind));
        }
        Ok(entries)
    }

    /// Renames `from` to `to`, both in this directory. Neither is followed if a link: a link
    /// at `from` is moved as a link, and a link at `to` would be replaced, so callers check
    /// `to` first and refuse.
    pub fn rename(
        &self,
        from: impl AsRef<OsStr>,
        to: impl AsRef<OsStr>,
    ) -> Result<(), OutputError> {
        let (from, to) = (from.as_ref(), to.as_ref());
        check_name(&self.path, from)?;
        check_name(&self.path, to)?;
        rustix::fs::renameat(&self.fd, from, &self.fd, to)
            .map_err(|e| self.error(to, &format!("cannot rename {} to it", from.display()), e))
    }

    /// Swaps `a` and `b` in one step (Linux `renameat2(RENAME_EXCHANGE)`); `Ok(false)` when
    /// the file system or kernel cannot, and nothing changed.
    pub fn exchange(
        &self,
        a: impl AsRef<OsStr>,
        b: impl AsRef<OsStr>,
    ) -> Result<bool, OutputError> {
        let (a, b) = (a.as_ref(), b.as_ref());
        check_name(&self.path, a)?;
        check_name(&self.path, b)?;
        match rustix::fs::renameat_with(&self.fd, a, &self.fd, b, RenameFlags::EXCHANGE) {
            Ok(()) => Ok(true),
            Err(Errno::INVAL | Errno::NOSYS | Errno::NOTSUP) => Ok(false),
            Err(e) => Err(self.error(b, &format!("cannot swap {} with it", a.display()), e)),
        }
    }

    /// Deletes `name` and, if it is a directory, everything in it; links are removed, never
    /// followed. Nothing of that name is no error.
    pub fn remove_all(&self, name: impl AsRef<OsStr>) -> Result<(), OutputError> {
        let name = name.as_ref();
        match self.kind(name)? {
            None => Ok(()),
            Some(EntryKind::Dir) => {
                let inner = self.open_dir(name)?;
                for (entry, _) in inner.entries()? {
                    inner.remove_all(&entry)?;
                }
                rustix::fs::unlinkat(&self.fd, name, AtFlags::REMOVEDIR)
                    .map_err(|e| self.error(name, "cannot remove directory", e))
            }
            Some(_) => rustix::fs::unlinkat(&self.fd, name, AtFlags::empty())
                .map_err(|e| self.error(name, "cannot remove", e)),
        }
    }

    /// Puts a copy of entry `name` of this directory into `into` under the same name,
    /// recursively for a directory, never following a link: a file is hard-linked (copied
    /// when the file system refuses the link), a link is recreated as the same link (its
    /// target neither read nor written).
    pub fn link_into(&self, name: impl AsRef<OsStr>, into: &SafeDir) -> Result<(), OutputError> {
        let name = name.as_ref();
        match self.kind(name)? {
            None => Ok(()),
            Some(EntryKind::Dir) => {
                let from = self.open_dir(name)?;
                let to = into.create_dir(name)?;
                for (entry, _) in from.entries()? {
                    from.link_into(&entry, &to)?;
                }
                to.sync()
            }
            Some(kind) => {
                // linkat without AT_SYMLINK_FOLLOW links a link itself, not its target.
                if rustix::fs::linkat(&self.fd, name, &into.fd, name, AtFlags::empty()).is_ok() {
                    return Ok(());
                }
                match kind {
                    EntryKind::Symlink => {
                        let target = rustix::fs::readlinkat(&self.fd, name, Vec::new())
                            .map_err(|e| self.error(name, "cannot read link", e))?;
                        rustix::fs::symlinkat(target.as_c_str(), &into.fd, name)
                            .map_err(|e| into.error(name, "cannot create link", e))
                    }
                    EntryKind::File => {
                        let copy_err = |e| OutputError::io(&into.join(name), "cannot copy", e);
                        let mut source = self.open_file(name)?;
                        let mut target = into.create_file(name)?;
                        let mut buffer = vec![0u8; 1 << 16];
                        loop {
                            let n = source.read(&mut buffer).map_err(copy_err)?;
                            if n == 0 {
                                break;
                            }
                            target.write_all(&buffer[..n]).map_err(copy_err)?;
                        }
                        target.sync_all().map_err(copy_err)
                    }
                    _ => Err(OutputError::invalid(
                        &self.join(name),
                        "is a FIFO, socket or device, which fsim does not copy",
                    )),
                }
            }
        }
    }

    /// Flushes the directory's entries (creations, renames) to disk.
    pub fn sync(&self) -> Result<(), OutputError> {
        rustix::fs::fsync(&self.fd)
            .map_err(|e| OutputError::io(&self.path, "cannot flush directory to disk", e.into()))
    }

    /// Flushes every file below this directory, and the directories themselves, to disk.
    pub fn sync_all(&self) -> Result<(), OutputError> {
        for (name, kind) in self.entries()? {
            match kind {
                EntryKind::Dir => self.open_dir(&name)?.sync_all()?,
                EntryKind::File => self.open_file(&name)?.sync_all().map_err(|e| {
                    OutputError::io(&self.join(&name), "cannot flush file to disk", e)
                })?,
                _ => {}
            }
        }
        self.sync()
    }
}

/// The first link along `relative` below the case directory (the case directory itself is
/// not looked at), or `None`; components that do not exist yet end the search. For checking
/// before a run what it will write: the writes themselves refuse a link on their own.
pub fn first_link_below(case_dir: &Path, relative: &Path) -> Result<Option<PathBuf>, OutputError> {
    let mut dir = SafeDir::open_case(case_dir)?;
    let names: Vec<&OsStr> = relative
        .components()
        .filter_map(|c| match c {
            Component::Normal(name) => Some(name),
            _ => None,
        })
        .collect();
    for (i, name) in names.iter().enumerate() {
        match dir.kind(name)? {
            None => return Ok(None),
            Some(EntryKind::Symlink) => return Ok(Some(dir.join(name))),
            Some(EntryKind::Dir) if i + 1 < names.len() => dir = dir.open_dir(name)?,
            Some(_) => return Ok(None),
        }
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_support::ScratchDir;
    use std::fs;
    use std::os::unix::fs::symlink;

    /// A case directory and, beside it, an "outside" directory with one file.
    fn case_and_outside(label: &str) -> (ScratchDir, PathBuf, PathBuf) {
        let root = ScratchDir::new(label);
        let case = root.path().join("case");
        let outside = root.path().join("outside");
        fs::create_dir_all(&case).unwrap();
        fs::create_dir_all(&outside).unwrap();
        fs::write(outside.join("victim"), "precious").unwrap();
        (root, case, outside)
    }

    #[test]
    fn a_link_in_the_way_of_a_file_is_refused_and_its_target_untouched() {
        let (_root, case, outside) = case_and_outside("safe-file");
        symlink(outside.join("victim"), case.join("out.dat")).unwrap();
        let dir = SafeDir::open_case(&case).unwrap();
        let err = dir.create_file("out.dat").unwrap_err().to_string();
        assert!(err.contains("out.dat: is a symbolic link"), "{err}");
        assert_eq!(
            fs::read_to_string(outside.join("victim")).unwrap(),
            "precious"
        );
    }

    #[test]
    fn a_link_along_a_directory_path_is_refused() {
        let (_root, case, outside) = case_and_outside("safe-dir");
        fs::create_dir(case.join("a")).unwrap();
        symlink(&outside, case.join("a/b")).unwrap();
        let dir = SafeDir::open_case(&case).unwrap();
        let err = dir
            .create_dir_all(&["a", "b", "c"])
            .unwrap_err()
            .to_string();
        assert!(err.contains("a/b: is a symbolic link"), "{err}");
        assert_eq!(
            fs::read_dir(&outside).unwrap().count(),
            1,
            "nothing new outside"
        );
        assert_eq!(
            first_link_below(&case, Path::new("a/b/c")).unwrap(),
            Some(case.join("a/b"))
        );
        assert_eq!(first_link_below(&case, Path::new("a/x/c")).unwrap(), None);
    }

    #[test]
    fn a_directory_opened_once_stays_the_one_written_even_if_swapped_for_a_link() {
        let (_root, case, outside) = case_and_outside("safe-swap");
        let dir = SafeDir::open_case(&case)
            .unwrap()
            .create_dir_all(&["postProcessing", "m"])
            .unwrap();
        // the directory is moved away and a link to the outside put in its place
        fs::rename(case.join("postProcessing"), case.join("moved")).unwrap();
        symlink(&outside, case.join("postProcessing")).unwrap();
        let mut file = dir.create_file("m.dat").unwrap();
        file.write_all(b"row\n").unwrap();
        assert_eq!(
            fs::read_to_string(case.join("moved/m/m.dat")).unwrap(),
            "row\n"
        );
        assert_eq!(
            fs::read_dir(&outside).unwrap().count(),
            1,
            "nothing new outside"
        );
        // and a new open from the case refuses the link
        let err = SafeDir::open_case(&case)
            .unwrap()
            .create_dir_all(&["postProcessing", "m"])
            .unwrap_err()
            .to_string();
        assert!(err.contains("postProcessing: is a symbolic link"), "{err}");
    }

    #[test]
    fn replacing_a_hard_linked_file_leaves_the_other_name_alone() {
        let (_root, case, outside) = case_and_outside("safe-hardlink");
        fs::hard_link(outside.join("victim"), case.join("out.dat")).unwrap();
        let dir = SafeDir::open_case(&case).unwrap();
        dir.create_file("out.dat")
            .unwrap()
            .write_all(b"new")
            .unwrap();
        assert_eq!(fs::read_to_string(case.join("out.dat")).unwrap(), "new");
        assert_eq!(
            fs::read_to_string(outside.join("victim")).unwrap(),
            "precious"
        );
    }

    #[test]
    fn remove_all_removes_links_without_following_them() {
        let (_root, case, outside) = case_and_outside("safe-remove");
        fs::create_dir_all(case.join("d/e")).unwrap();
        symlink(&outside, case.join("d/e/link")).unwrap();
        symlink(&outside, case.join("top")).unwrap();
        let dir = SafeDir::open_case(&case).unwrap();
        dir.remove_all("d").unwrap();
        dir.remove_all("top").unwrap();
        assert_eq!(fs::read_dir(&case).unwrap().count(), 0);
        assert_eq!(
            fs::read_to_string(outside.join("victim")).unwrap(),
            "precious"
        );
    }

    #[test]
    fn names_that_would_leave_the_directory_are_refused() {
        let (_root, case, _outside) = case_and_outside("safe-names");
        let dir = SafeDir::open_case(&case).unwrap();
        for bad in ["..", ".", "", "a/b"] {
            assert!(dir.create_file(bad).is_err(), "{bad:?}");
        }
    }
}
