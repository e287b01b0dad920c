//! The `#` directives where a keyword is expected: `#include` and its optional forms, and
//! the directives fsim keeps without acting on them.

use super::{directive_name, quoted, release_if_large, word, Ctx, Src, MAX_INCLUDE_DEPTH};
use crate::case::bounded_read::not_regular;
use crate::case::dictionary::Directive;
use crate::case::error::CaseError;
use crate::case::quote::quote;
use crate::case::source::{Location, SourceFile};
use crate::case::value::{Item, Value};
use nom::character::complete::not_line_ending;
use std::path::{Path, PathBuf};
use std::sync::Arc;

impl Ctx {
    /// A directive where a keyword is expected.
    pub(super) fn directive<'a>(&mut self, src: &Src, i: &'a str) -> Result<&'a str, CaseError> {
        let loc = src.loc(i);
        let Ok((rest, name)) = directive_name(&i[1..]) else {
            return Err(src.err(i, "expected a directive name after '#'"));
        };
        match name {
            "include" | "includeIfPresent" | "sinclude" => {
                let optional = name != "include";
                let (rest, arg) = self.directive_argument(src, rest, name)?;
                self.include(src, &loc, &arg, optional)?;
                Ok(rest)
            }
            "includeEtc" | "includeFunc" | "includeFuncIfPresent" => {
                let (rest, arg) = if name == "includeEtc" {
                    self.directive_argument(src, rest, name)?
                } else {
                    // `#includeFunc` takes the rest of its line (`#includeFunc mag(U)`).
                    let (rest, line) =
                        not_line_ending::<_, nom::error::Error<&str>>(rest).unwrap_or((rest, ""));
                    (rest, line.trim().to_string())
                };
                self.current().directives.push(Directive {
                    name: name.to_string(),
                    argument: arg,
                    loc,
                });
                Ok(rest)
            }
            "inputMode" => Ok(self.directive_argument(src, rest, name)?.0),
            "remove" => {
                let rest = self.skip(src, rest)?;
                let (rest, items) = if rest.starts_with('(') || rest.starts_with('$') {
                    self.token(src, rest)?
                } else {
                    let (r, w) = self.directive_argument(src, rest, name)?;
                    (r, vec![Item::new(Value::Word(w), loc.clone())])
                };
                let mut names = Vec::new();
                for item in &items {
                    match &item.value {
                        Value::List(_) | Value::Numbers { .. } => {
                            let list = item.as_list().expect("a list");
                            names.extend(list.iter().map(|x| x.to_string()))
                        }
                        Value::Word(w) | Value::Str(w) => names.push(w.clone()),
                        _ => names.push(item.to_string()),
                    }
                }
                for n in names {
                    self.current().remove(&n);
                }
                Ok(rest)
            }
            other => Err(CaseError::at(
                &loc,
                format!(
                    "unknown directive '#{other}' (expected #include, #includeIfPresent, \
                     #includeEtc, #includeFunc, #inputMode or #remove here)"
                ),
            )),
        }
    }

    /// A directive's one argument: a quoted string or a word.
    pub(super) fn directive_argument<'a>(
        &self,
        src: &Src,
        i: &'a str,
        name: &str,
    ) -> Result<(&'a str, String), CaseError> {
        let i = self.skip(src, i)?;
        if i.starts_with('"') {
            return quoted(i)
                .ok_or_else(|| src.err(i, "expected '\"' to close the string opened here"));
        }
        match word(i) {
            Ok((rest, w)) => Ok((rest, w.to_string())),
            Err(_) => Err(src.err(i, format!("expected a file name or word after '#{name}'"))),
        }
    }

    /// `#include "file"`: the file's entries are read into the current dictionary. The path
    /// is relative to the including file; `$FOAM_CASE` and `<case>` name the case directory.
    pub(super) fn include(
        &mut self,
        src: &Src,
        loc: &Location,
        arg: &str,
        optional: bool,
    ) -> Result<(), CaseError> {
        let case = self.case_dir.clone().unwrap_or_else(|| PathBuf::from("."));
        let expanded = if let Some(rest) = arg.strip_prefix("$FOAM_CASE") {
            format!("{}{rest}", case.display())
        } else if let Some(rest) = arg.strip_prefix("<case>") {
            format!("{}{rest}", case.display())
        } else if let Some(rest) = arg.strip_prefix("<system>") {
            format!("{}/system{rest}", case.display())
        } else if let Some(rest) = arg.strip_prefix("<constant>") {
            format!("{}/constant{rest}", case.display())
        } else {
            arg.to_string()
        };
        if src.file.path.as_os_str().is_empty() {
            return Err(CaseError::at(
                loc,
                format!(
                    "cannot include \"{}\": the text was not read from a file",
                    quote(arg)
                ),
            ));
        }
        let path = Path::new(&expanded);
        let path = if path.is_absolute() {
            path.to_path_buf()
        } else {
            src.file
                .path
                .parent()
                .unwrap_or_else(|| Path::new(""))
                .join(path)
        };
        let gz = PathBuf::from(format!("{}.gz", path.display()));
        // Only regular files: a device such as /dev/zero would never end, a FIFO would
        // block. Something else at the path is refused by its kind and never opened, nor
        // watched (docs/security.md, "Reads").
        for candidate in [&path, &gz] {
            if let Some(kind) = not_regular(candidate) {
                return Err(CaseError::at(
                    loc,
                    format!(
                        "cannot include \"{}\": expected a regular file, found {kind} (not read)",
                        quote_path(candidate)
                    ),
                ));
            }
        }
        if !path.is_file() && !gz.is_file() {
            if optional {
                return Ok(());
            }
            // watched all the same: its creation mends the dictionary
            self.included.push(path.clone());
            return Err(CaseError::at(
                loc,
                format!("cannot include \"{}\": file not found", quote(arg)),
            ));
        }
        if self.include_depth >= MAX_INCLUDE_DEPTH {
            return Err(CaseError::at(
                loc,
                format!("expected at most {MAX_INCLUDE_DEPTH} nested #include (does a file include itself?)"),
            ));
        }
        let file = Arc::new(SourceFile::read(&path, self.case_dir.as_deref())?);
        self.included
            .push(if path.is_file() { path.clone() } else { gz });
        let text = file.text();
        let inner = Src {
            file: &file,
            text: &text,
        };
        let had_header = self.current().contains("FoamFile");
        self.include_depth += 1;
        let result = self.body(&inner, &text, None);
        self.include_depth -= 1;
        if result.is_ok() {
            release_if_large(&file, text.len());
        }
        // An included file's own header is not an entry of the dictionary it lands in.
        if self.stack.len() > 1 && !had_header {
            self.current().remove("FoamFile");
        }
        result.map(|_| ())
    }
}

/// A path quoted for a message, bounded as every user value is.
fn quote_path(path: &Path) -> String {
    quote(&path.to_string_lossy()).into_owned()
}
