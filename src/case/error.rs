//! The one error type of case loading: a message anchored at a file, line and column.
//!
//! Display is one line, `path:line:col: message`, as compilers print it, so that editors and
//! terminals can jump to the place. [`CaseError::excerpt`] adds the rustc-style block with the
//! offending source line and a caret under the column.

use std::fmt;

use super::quote::bound_message;
use super::source::Location;

/// An error in a case: where it is (when known) and what was expected there.
#[derive(Clone, Debug, PartialEq)]
pub struct CaseError {
    /// File as shown to the user: relative to the case directory when inside it.
    pub file: Option<String>,
    /// 1-based line; 0 when the error concerns a whole file (missing file, say).
    pub line: usize,
    /// 1-based column in characters; 0 when the error concerns a whole file.
    pub col: usize,
    /// What went wrong, saying what was expected.
    pub message: String,
    /// The source line the error points into, for the caret excerpt.
    source_line: Option<String>,
}

impl CaseError {
    /// An error at a position in a source file.
    ///
    /// In a file outside the case directory the message names the place only: its text
    /// (values quoted, the source line) is not shown, so that a case cannot make fsim print
    /// a file it points at.
    pub fn at(loc: &Location, message: impl Into<String>) -> Self {
        let (line, col) = loc.line_col();
        if !loc.file.inside_case {
            return CaseError {
                file: Some(loc.file.display.clone()),
                line,
                col,
                message: "this file, outside the case directory, does not read as fsim \
                          expects here (its text is not shown: copy it into the case for the \
                          full message)"
                    .to_string(),
                source_line: None,
            };
        }
        CaseError {
            file: Some(loc.file.display.clone()),
            line,
            col,
            message: one_line(message.into()),
            source_line: Some(loc.file.line_text(line)),
        }
    }

    /// An error about a whole file (missing, unreadable).
    pub fn in_file(file: impl Into<String>, message: impl Into<String>) -> Self {
        CaseError {
            file: Some(super::quote::quote(&file.into()).into_owned()),
            line: 0,
            col: 0,
            message: one_line(message.into()),
            source_line: None,
        }
    }

    /// An error tied to no file (a case directory that does not exist, say).
    pub fn plain(message: impl Into<String>) -> Self {
        CaseError {
            file: None,
            line: 0,
            col: 0,
            message: one_line(message.into()),
            source_line: None,
        }
    }

    /// The rustc-style excerpt: the source line and a `^` under the column, or `None` when the
    /// error has no position.
    ///
    /// ```text
    ///   --> constant/transportProperties:19:4
    ///    |
    /// 19 | nu abc;
    ///    |    ^
    /// ```
    pub fn excerpt(&self) -> Option<String> {
        let text = self.source_line.as_ref()?;
        let file = self.file.as_deref().unwrap_or("<input>");
        let number = self.line.to_string();
        let pad = " ".repeat(number.len());
        // A long line is shown as a window of EXCERPT_CHARS characters around the column
        // (a case may hold a line of megabytes), marked with … where cut.
        let col = self.col.max(1) - 1;
        let first = col.saturating_sub(EXCERPT_CHARS / 2);
        let total = text.chars().count();
        let (before, after) = (first > 0, first + EXCERPT_CHARS < total);
        // Tabs are shown as one space so that the caret stays under the column it names.
        let window: String = text
            .chars()
            .skip(first)
            .take(EXCERPT_CHARS)
            .map(|c| if c == '\t' { ' ' } else { c })
            .collect();
        let shown = format!(
            "{}{window}{}",
            if before { "…" } else { "" },
            if after { "…" } else { "" }
        );
        Some(format!(
            "{pad}--> {file}:{line}:{col}\n{pad} |\n{number} | {shown}\n{pad} | {caret}^",
            file = crate::case::quote::quote(file),
            line = self.line,
            col = self.col,
            caret = " ".repeat(col - first + usize::from(before)),
        ))
    }

    /// The one-line message followed by the excerpt, as the CLI prints it on stderr.
    pub fn report(&self) -> String {
        match self.excerpt() {
            Some(excerpt) => format!("{self}\n{excerpt}"),
            None => self.to_string(),
        }
    }
}

/// Most characters of a source line an excerpt shows, centred on the column.
const EXCERPT_CHARS: usize = 100;

/// Messages quote user text (a string with a line break, say); Display must stay one line,
/// and short whatever the text quoted ([`bound_message`]).
fn one_line(message: String) -> String {
    let message = if message.contains(['\n', '\r']) {
        message.replace('\n', "\\n").replace('\r', "\\r")
    } else {
        message
    };
    match bound_message(&message) {
        std::borrow::Cow::Borrowed(_) => message,
        std::borrow::Cow::Owned(bounded) => bounded,
    }
}

impl fmt::Display for CaseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (&self.file, self.line) {
            (Some(file), 0) => write!(f, "{file}: {}", self.message),
            (Some(file), line) => write!(f, "{file}:{line}:{}: {}", self.col, self.message),
            (None, _) => write!(f, "{}", self.message),
        }
    }
}

impl std::error::Error for CaseError {}
