//! Source files as read from disk (plain or gzip) and positions inside them.
//!
//! Every parsed token keeps a [`Location`]: the shared file plus a byte offset. Line and
//! column are computed only when an error is reported, from line starts found on first need.
//! A large file's text is let go once it is parsed ([`SourceFile::release_text`]), so that a
//! 90 MB field does not stay in memory beside its numbers; a message that needs it reads the
//! file again.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

use super::bounded_read::{
    gunzip_bounded, read_regular_file, ReadError, MAX_GZIP_EXPANDED_BYTES, MAX_TEXT_BYTES,
};
use super::error::CaseError;

/// The two bytes every gzip stream starts with (RFC 1952, §2.3.1).
const GZIP_MAGIC: [u8; 2] = [0x1f, 0x8b];

/// A file's text, with the name to show in messages.
#[derive(Debug)]
pub struct SourceFile {
    /// Path on disk (empty for text parsed from memory).
    pub path: PathBuf,
    /// Path as shown to the user: relative to the case directory when inside it.
    pub display: String,
    /// Whether the file lies inside the case directory (or was not read from disk): the
    /// text of a file outside it is never quoted in a message, so that a case cannot make
    /// fsim print a file it points at (`#include "/etc/…"`).
    pub inside_case: bool,
    /// The whole text (decompressed); `None` once released.
    text: Mutex<Option<Arc<String>>>,
    /// Byte offset of the start of every line, found on first need.
    line_starts: OnceLock<Vec<usize>>,
}

impl SourceFile {
    /// A source held in memory, shown as `display` in messages.
    pub fn from_text(path: PathBuf, display: String, text: String) -> Self {
        SourceFile {
            path,
            display,
            inside_case: true,
            text: Mutex::new(Some(Arc::new(text))),
            line_starts: OnceLock::new(),
        }
    }

    /// The whole text, read from disk again when it was released (empty when that fails,
    /// so that a message still comes out without its source line).
    pub fn text(&self) -> Arc<String> {
        let mut slot = self.text.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(text) = slot.as_ref() {
            return text.clone();
        }
        let text = Arc::new(
            read_text(&self.path, &self.display)
                .map(|(text, _)| text)
                .unwrap_or_default(),
        );
        *slot = Some(text.clone());
        text
    }

    /// Lets the text go (it is read again if a message needs it). Only a file read from disk
    /// can let it go.
    pub fn release_text(&self) {
        if !self.path.as_os_str().is_empty() {
            *self.text.lock().unwrap_or_else(|e| e.into_inner()) = None;
        }
    }

    /// Reads a file, decompressing it when its name ends in `.gz` or its content starts with
    /// the gzip magic bytes. When `path` does not exist but `path.gz` does, reads that one, as
    /// OpenFOAM does. `case_dir` only shapes the name shown in messages.
    pub fn read(path: &Path, case_dir: Option<&Path>) -> Result<SourceFile, CaseError> {
        let mut path = path.to_path_buf();
        if !path.exists() {
            let mut gz = path.clone().into_os_string();
            gz.push(".gz");
            let gz = PathBuf::from(gz);
            if gz.exists() {
                path = gz;
            }
        }
        let display = display_path(&path, case_dir);
        let inside_case = case_dir.is_none_or(|dir| inside(&path, dir));
        let source = |path, display, text| SourceFile {
            inside_case,
            ..SourceFile::from_text(path, display, text)
        };
        match read_text(&path, &display)? {
            (text, None) => Ok(source(path, display, text)),
            (text, Some(valid)) => {
                let file = Arc::new(source(path, display, text));
                // The lossy text keeps every byte before the first invalid one in place.
                Err(CaseError::at(
                    &Location::new(&file, valid),
                    "expected UTF-8 text (binary file content is not supported)",
                ))
            }
        }
    }

    fn line_starts(&self, text: &str) -> &[usize] {
        self.line_starts.get_or_init(|| {
            let mut starts = vec![0];
            starts.extend(
                text.bytes()
                    .enumerate()
                    .filter(|&(_, b)| b == b'\n')
                    .map(|(i, _)| i + 1),
            );
            starts
        })
    }

    /// 1-based line and column (in characters) of a byte offset.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let text = self.text();
        let offset = offset.min(text.len());
        let line_starts = self.line_starts(&text);
        let line = line_starts.partition_point(|&s| s <= offset) - 1;
        let start = line_starts[line];
        let col = text
            .get(start..offset)
            .map_or(offset - start, |s| s.chars().count());
        (line + 1, col + 1)
    }

    /// The text of a 1-based line, without its line break.
    pub fn line_text(&self, line: usize) -> String {
        let text = self.text();
        let line_starts = self.line_starts(&text);
        let Some(&start) = line_starts.get(line.wrapping_sub(1)) else {
            return String::new();
        };
        let end = line_starts.get(line).map_or(text.len(), |&next| next - 1);
        text.get(start..end)
            .unwrap_or("")
            .trim_end_matches('\r')
            .to_string()
    }
}

/// A file's text, decompressed when gzipped, and the offset of the first byte that is not
/// UTF-8 (the text is then lossy).
///
/// Read through [`read_regular_file`] and [`gunzip_bounded`]: only a regular file of at most
/// [`MAX_TEXT_BYTES`], expanding to at most [`MAX_GZIP_EXPANDED_BYTES`] when gzipped, since
/// a case may come from anyone.
fn read_text(path: &Path, display: &str) -> Result<(String, Option<usize>), CaseError> {
    let bytes = read_regular_file(path, MAX_TEXT_BYTES)
        .map_err(|e| CaseError::in_file(display, e.to_string()))?;
    let gzipped = path.extension().is_some_and(|e| e == "gz") || bytes.starts_with(&GZIP_MAGIC);
    let bytes = if gzipped {
        gunzip_bounded(&bytes, MAX_GZIP_EXPANDED_BYTES).map_err(|e| match e {
            ReadError::Io(e) => {
                CaseError::in_file(display, format!("cannot decompress gzip data: {e}"))
            }
            e => CaseError::in_file(display, e.to_string()),
        })?
    } else {
        bytes
    };
    match String::from_utf8(bytes) {
        Ok(text) => Ok((text, None)),
        Err(e) => {
            let valid = e.utf8_error().valid_up_to();
            Ok((
                String::from_utf8_lossy(e.as_bytes()).into_owned(),
                Some(valid),
            ))
        }
    }
}

/// A position in a source file.
#[derive(Clone, Debug)]
pub struct Location {
    pub file: Arc<SourceFile>,
    /// Byte offset into the file's text; for an element of a packed number list, the list's.
    pub offset: usize,
    /// Which element of the packed list at `offset` this is, when it is one.
    pub element: Option<Element>,
}

/// An element of a packed number list ([`super::Value::Numbers`]): its position is found
/// again by rescanning the list, so that the list needs one [`Location`] only.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Element {
    /// The element: a number, or a `( … )` tuple.
    pub index: usize,
    /// The number inside that tuple.
    pub component: Option<usize>,
}

impl Location {
    pub fn new(file: &Arc<SourceFile>, offset: usize) -> Self {
        Location {
            file: file.clone(),
            offset,
            element: None,
        }
    }

    /// Where element `i` of the list this location starts is: a packed list's element, or
    /// the number `i` of such an element.
    pub fn child(&self, i: usize) -> Location {
        let element = match self.element {
            None => Element {
                index: i,
                component: None,
            },
            Some(Element { index, .. }) => Element {
                index,
                component: Some(i),
            },
        };
        Location {
            file: self.file.clone(),
            offset: self.offset,
            element: Some(element),
        }
    }

    /// The byte offset this location names, rescanning a packed list for an element.
    pub fn resolved_offset(&self) -> usize {
        match self.element {
            None => self.offset,
            Some(e) => super::packed::element_offset(&self.file.text(), self.offset, e),
        }
    }

    /// 1-based line and column.
    pub fn line_col(&self) -> (usize, usize) {
        self.file.line_col(self.resolved_offset())
    }

    /// `file:line:col`, for messages that point at a second place.
    pub fn describe(&self) -> String {
        let (line, col) = self.line_col();
        format!("{}:{line}:{col}", self.file.display)
    }
}

/// Whether `path` lies inside `case_dir`, symlinks resolved (a symlink inside the case to a
/// file outside it is outside).
fn inside(path: &Path, case_dir: &Path) -> bool {
    match (path.canonicalize(), case_dir.canonicalize()) {
        (Ok(p), Ok(d)) => p.starts_with(d),
        _ => false,
    }
}

/// `path` relative to `case_dir` when it lies inside it, else as given.
pub fn display_path(path: &Path, case_dir: Option<&Path>) -> String {
    if let Some(dir) = case_dir {
        if let Ok(rel) = path.strip_prefix(dir) {
            return rel.display().to_string();
        }
        if let (Ok(p), Ok(d)) = (path.canonicalize(), dir.canonicalize()) {
            if let Ok(rel) = p.strip_prefix(&d) {
                return rel.display().to_string();
            }
        }
    }
    path.display().to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_and_column_count_characters_from_one() {
        let f = SourceFile::from_text(PathBuf::new(), "t".into(), "ab\nµc d\n".into());
        assert_eq!(f.line_col(0), (1, 1));
        assert_eq!(f.line_col(3), (2, 1));
        // 'd' is after a two-byte character: byte 7, character column 4.
        assert_eq!(f.line_col(7), (2, 4));
        assert_eq!(f.line_text(2), "µc d");
        assert_eq!(f.line_text(3), "");
    }

    #[test]
    fn gzip_is_detected_by_magic_bytes() {
        use std::io::Write;
        let dir = std::env::temp_dir().join(format!("fsim-source-gz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("positions");
        let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        enc.write_all(b"a 1;\n").unwrap();
        std::fs::write(&path, enc.finish().unwrap()).unwrap();
        let f = SourceFile::read(&path, Some(&dir)).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(f.text().as_str(), "a 1;\n");
        assert_eq!(f.display, "positions");
    }
}
