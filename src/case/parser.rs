//! The OpenFOAM dictionary grammar, read with nom.
//!
//! ```text
//! file      = body EOF
//! body      = { entry | directive | '$'name [';'] | ';' | value }      (values only stand
//!                                                                        alone at top level)
//! entry     = key ( '{' body '}' | token* ';' )
//! key       = word | '"' pattern '"'
//! token     = number | count '(' token* ')' | count '{' token '}' | '(' token* ')'
//!           | '{' body '}' | '[' dims ']' | '"' string '"' | '#{' code '#}'
//!           | '#'word | '$'name | word
//! ```
//!
//! The lexemes (comments, numbers, words, strings) are nom parsers; the structure above is a
//! recursive descent over them that keeps a stack of the dictionaries being built, so that a
//! `$var` macro is replaced by its value as soon as it is read, seeing exactly the entries
//! written above it in this and the enclosing scopes (OpenFOAM's rule).
//!
//! Two lexical traps of the format are handled here. A number must end at a word boundary:
//! `inflow`, `nanoParticle`, `e5x` and `1st` are words (nom's `double` would take `inf`, `nan`
//! or `1` from them; [`recognize_float`] reads no `inf`/`nan` and the boundary is checked). A
//! count before a list (`3((0 0 0) …)`, `8\n(`) is read before a plain number, but only when
//! the `(` follows the count directly or on a later line: `(0 (1 0 0))`, a time/value table
//! row, stays a number and a vector.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use nom::bytes::complete::{tag, take_until, take_while, take_while1};
use nom::character::complete::{multispace1, not_line_ending};
use nom::number::complete::recognize_float;
use nom::IResult;

use super::dictionary::{Dict, Entry, EntryBody, Key};
use super::error::CaseError;
use super::packed;
use super::quote::quote;
use super::source::{Location, SourceFile};
use super::value::{Dimensions, Item, Value};

mod directives;
mod invariants;
mod macros;

#[doc(hidden)]
pub use invariants::check_parser_invariants;
use macros::balanced_brace_end;

/// Deepest nesting of lists and dictionaries accepted (keeps recursion bounded).
const MAX_DEPTH: usize = 200;
/// Deepest `#include` chain accepted (catches a file including itself).
const MAX_INCLUDE_DEPTH: usize = 16;
/// Most tokens that `$macro` copies may create in one read (catches exponential macros).
const MAX_MACRO_TOKENS: usize = 50_000_000;

type Nom<'a, O> = IResult<&'a str, O, nom::error::Error<&'a str>>;

/// Reads and parses a dictionary file (plain or gzip). `case_dir` shapes the file names shown
/// in messages and resolves `$FOAM_CASE` and `<case>` in `#include` paths.
pub fn read_dict_file(path: &Path, case_dir: Option<&Path>) -> Result<Dict, CaseError> {
    let file = Arc::new(SourceFile::read(path, case_dir)?);
    parse_source(file, case_dir)
}

/// [`read_dict_file`], with the files its `#include`s name, in the order met (nested ones
/// too): those read, and a required one found missing. On an error, those met before it.
/// What `runTimeModifiable` watches besides the file itself, as OpenFOAM's `#include` adds
/// a watch on the file it reads.
pub fn read_dict_file_with_includes(
    path: &Path,
    case_dir: Option<&Path>,
) -> (Result<Dict, CaseError>, Vec<PathBuf>) {
    match SourceFile::read(path, case_dir) {
        Ok(file) => parse_with(Arc::new(file), case_dir, true),
        Err(e) => (Err(e), Vec::new()),
    }
}

/// Parses dictionary text held in memory; `display` names it in messages. `#include` is
/// refused there (there is no directory to resolve it from).
pub fn parse_dict(text: &str, display: &str) -> Result<Dict, CaseError> {
    // An empty path marks text without a file: `#include` has no directory to resolve from.
    let file = Arc::new(SourceFile::from_text(
        PathBuf::new(),
        display.to_string(),
        text.to_string(),
    ));
    parse_source(file, None)
}

fn parse_source(file: Arc<SourceFile>, case_dir: Option<&Path>) -> Result<Dict, CaseError> {
    parse_with(file, case_dir, true).0
}

/// The dictionary, and the files its `#include`s named ([`read_dict_file_with_includes`]).
/// `pack`: whether numeric lists are read packed (off only to compare with the general path).
fn parse_with(
    file: Arc<SourceFile>,
    case_dir: Option<&Path>,
    pack: bool,
) -> (Result<Dict, CaseError>, Vec<PathBuf>) {
    let mut ctx = Ctx {
        stack: vec![Dict::new(String::new(), Location::new(&file, 0))],
        case_dir: case_dir.map(Path::to_path_buf),
        depth: 0,
        include_depth: 0,
        macro_tokens: 0,
        pack,
        included: Vec::new(),
    };
    let text = file.text();
    let src = Src {
        file: &file,
        text: &text,
    };
    let read = ctx.body(&src, &text, None).map(|rest| {
        debug_assert!(rest.is_empty());
        release_if_large(&file, text.len());
        ctx.stack.pop().expect("top-level dictionary")
    });
    (read, ctx.included)
}

/// Files at least this long let their text go once parsed (a message reads them again).
const RELEASE_BYTES: usize = 1 << 20;

fn release_if_large(file: &SourceFile, len: usize) {
    if len >= RELEASE_BYTES {
        file.release_text();
    }
}

/// The file being read.
struct Src<'a> {
    file: &'a Arc<SourceFile>,
    /// Its text, held for the whole read.
    text: &'a str,
}

impl Src<'_> {
    fn loc(&self, rest: &str) -> Location {
        Location::new(self.file, self.text.len() - rest.len())
    }

    fn err(&self, rest: &str, message: impl Into<String>) -> CaseError {
        CaseError::at(&self.loc(rest), message)
    }
}

/// Parsing state shared by a file and the files it includes.
struct Ctx {
    /// The dictionaries being built, outermost first.
    stack: Vec<Dict>,
    case_dir: Option<PathBuf>,
    depth: usize,
    include_depth: usize,
    macro_tokens: usize,
    pack: bool,
    /// The files `#include`s named: read, or required and missing.
    included: Vec<PathBuf>,
}

// ----- lexemes (nom) --------------------------------------------------------------------------

fn line_comment(i: &str) -> Nom<'_, &str> {
    let (i, _) = tag("//")(i)?;
    not_line_ending(i)
}

fn block_comment(i: &str) -> Nom<'_, &str> {
    let (i, _) = tag("/*")(i)?;
    let (i, body) = take_until("*/")(i)?;
    let (i, _) = tag("*/")(i)?;
    Ok((i, body))
}

/// Characters that can never be part of a word.
fn is_delimiter(c: char) -> bool {
    c.is_whitespace() || matches!(c, '"' | '\'' | ';' | '{' | '}' | '[' | ']' | '(' | ')')
}

/// Reads a word: OpenFOAM's word characters, with balanced parentheses allowed inside once
/// the word has started (`div(phi,U)`), and stopping before a comment.
fn word(i: &str) -> Nom<'_, &str> {
    let mut depth = 0usize;
    let mut end = 0;
    let bytes = i.as_bytes();
    for (pos, c) in i.char_indices() {
        let ok = match c {
            '(' if pos > 0 => {
                depth += 1;
                true
            }
            ')' if depth > 0 => {
                depth -= 1;
                true
            }
            '/' => !matches!(bytes.get(pos + 1), Some(b'/') | Some(b'*')),
            c => !is_delimiter(c),
        };
        if !ok {
            break;
        }
        end = pos + c.len_utf8();
    }
    if end == 0 {
        return Err(nom::Err::Error(nom::error::Error::new(
            i,
            nom::error::ErrorKind::Alpha,
        )));
    }
    Ok((&i[end..], &i[..end]))
}

/// A number that ends at a word boundary, as a label (no `.`, no exponent) or a scalar.
fn number(i: &str) -> Nom<'_, Value> {
    let (rest, text) = recognize_float(i)?;
    // A word character right after the digits makes the whole thing a word (`1st`, `0.5.1`).
    // A parenthesis ends a number (`3(` starts a counted list) though it may continue a word.
    let continues = match rest.chars().next() {
        Some('/') => !rest.starts_with("//") && !rest.starts_with("/*"),
        Some(c) => !is_delimiter(c),
        None => false,
    };
    if continues {
        return Err(nom::Err::Error(nom::error::Error::new(
            i,
            nom::error::ErrorKind::Float,
        )));
    }
    let value = if text.contains(['.', 'e', 'E']) {
        text.parse::<f64>().map(Value::Scalar)
    } else {
        Ok(text
            .parse::<i64>()
            .map(Value::Label)
            .unwrap_or_else(|_| Value::Scalar(text.parse::<f64>().unwrap_or(f64::NAN))))
    };
    match value {
        Ok(v) => Ok((rest, v)),
        Err(_) => Err(nom::Err::Error(nom::error::Error::new(
            i,
            nom::error::ErrorKind::Float,
        ))),
    }
}

/// A number beyond a double's range (`1e400`, a 400-digit integer) is refused where it is
/// written, as the words `inf` and `nan` are wherever a number is read: it would otherwise
/// be infinity, and an infinite end time or field value has no meaning.
fn out_of_range(src: &Src, at: &str, rest: &str) -> CaseError {
    let text = &at[..at.len() - rest.len()];
    src.err(
        at,
        format!(
            "the number {} is out of range: expected a finite number, at most {:e} in \
             magnitude",
            quote(text),
            f64::MAX
        ),
    )
}

fn directive_name(i: &str) -> Nom<'_, &str> {
    take_while1(|c: char| c.is_ascii_alphanumeric() || c == '_')(i)
}

fn variable_name(i: &str) -> Nom<'_, &str> {
    take_while1(|c: char| {
        c.is_alphanumeric() || matches!(c, '_' | '-' | '.' | ':' | '/' | '<' | '>')
    })(i)
}

/// A double-quoted string with backslash escapes; `None` when it is not closed.
fn quoted(i: &str) -> Option<(&str, String)> {
    let body = i.strip_prefix('"')?;
    let mut out = String::new();
    let mut chars = body.char_indices();
    while let Some((pos, c)) = chars.next() {
        match c {
            '"' => return Some((&body[pos + 1..], out)),
            '\\' => match chars.next() {
                Some((_, '"')) => out.push('"'),
                Some((_, '\\')) => out.push('\\'),
                Some((_, '\n')) => {}
                Some((_, other)) => {
                    out.push('\\');
                    out.push(other);
                }
                None => return None,
            },
            c => out.push(c),
        }
    }
    None
}

// ----- structure ------------------------------------------------------------------------------

impl Ctx {
    /// Skips blanks and comments.
    fn skip<'a>(&self, src: &Src, mut i: &'a str) -> Result<&'a str, CaseError> {
        loop {
            if let Ok((rest, _)) = multispace1::<_, nom::error::Error<&str>>(i) {
                i = rest;
            } else if let Ok((rest, _)) = line_comment(i) {
                i = rest;
            } else if i.starts_with("/*") {
                match block_comment(i) {
                    Ok((rest, _)) => i = rest,
                    Err(_) => {
                        return Err(src.err(i, "expected '*/' to close the comment opened here"))
                    }
                }
            } else {
                return Ok(i);
            }
        }
    }

    fn enter(&mut self, src: &Src, i: &str) -> Result<(), CaseError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(src.err(
                i,
                format!("expected at most {MAX_DEPTH} nested lists and dictionaries"),
            ));
        }
        Ok(())
    }

    fn current(&mut self) -> &mut Dict {
        self.stack.last_mut().expect("a dictionary is open")
    }

    /// Entries up to the closing `}` (when `open` is the location of its `{`) or the end of
    /// the text; returns the text after the `}`.
    fn body<'a>(
        &mut self,
        src: &Src,
        mut i: &'a str,
        open: Option<&Location>,
    ) -> Result<&'a str, CaseError> {
        loop {
            i = self.skip(src, i)?;
            let Some(c) = i.chars().next() else {
                return match open {
                    None => Ok(i),
                    Some(open) => Err(src.err(
                        i,
                        format!(
                            "expected '}}' to close the dictionary opened at line {}",
                            open.line_col().0
                        ),
                    )),
                };
            };
            match c {
                '}' if open.is_some() => return Ok(&i[1..]),
                '}' => {
                    return Err(src.err(i, "expected a keyword, found '}' with no dictionary open"))
                }
                ';' => i = &i[1..],
                '#' if !i.starts_with("#{") => i = self.directive(src, i)?,
                '$' => i = self.merge_macro(src, i)?,
                '"' => {
                    let key_loc = src.loc(i);
                    let Some((rest, text)) = quoted(i) else {
                        return Err(src.err(i, "expected '\"' to close the string opened here"));
                    };
                    i = self.entry(src, rest, Key::quoted(&text), key_loc)?;
                }
                '(' | '0'..='9' | '-' | '+' | '.' if open.is_none() && number_or_list(i) => {
                    // A value standing alone at top level (`kinematicCloudPositions`).
                    // Like OpenFOAM reading a list file, stop after the list: some
                    // tutorial files carry stray text after it (`/ *****…//`).
                    let (_, items) = self.token(src, i)?;
                    self.current().values.extend(items);
                    return Ok("");
                }
                _ => match word(i) {
                    Ok((rest, w)) => {
                        let key_loc = src.loc(i);
                        i = self.entry(src, rest, Key::Word(w.to_string()), key_loc)?;
                    }
                    Err(_) => {
                        let expected = if open.is_some() {
                            "expected a keyword or '}'"
                        } else {
                            "expected a keyword"
                        };
                        return Err(src.err(i, format!("{expected}, found '{c}'")));
                    }
                },
            }
        }
    }

    /// The rest of an entry after its keyword: a sub-dictionary or a value up to `;`.
    fn entry<'a>(
        &mut self,
        src: &Src,
        i: &'a str,
        key: Key,
        key_loc: Location,
    ) -> Result<&'a str, CaseError> {
        let i = self.skip(src, i)?;
        if let Some(inner) = i.strip_prefix('{') {
            let open = src.loc(i);
            let name = scoped_name(&self.current().name, key.as_str());
            let (rest, dict) = self.sub_dict(src, inner, name, key_loc.clone(), &open)?;
            self.current()
                .insert(Entry::new(key, key_loc, EntryBody::Dict(dict)));
            return Ok(rest);
        }
        let mut tokens = Vec::new();
        let mut i = i;
        // Where the `;` is expected: right after the last token read.
        let mut after_last = i;
        let mut first = true;
        loop {
            if !first {
                i = self.skip(src, i)?;
            }
            first = false;
            match i.chars().next() {
                Some(';') => {
                    self.current()
                        .insert(Entry::new(key, key_loc, EntryBody::Tokens(tokens)));
                    return Ok(&i[1..]);
                }
                None | Some('}') => {
                    let at = if tokens.is_empty() { i } else { after_last };
                    return Err(src.err(
                        at,
                        format!("expected ';' to end the entry '{}'", key.as_str()),
                    ));
                }
                Some(_) => {
                    let (rest, items) = self.token(src, i)?;
                    tokens.extend(items);
                    i = rest;
                    after_last = rest;
                }
            }
        }
    }

    /// A dictionary body after its `{`, built on the scope stack so that macros inside it
    /// see the enclosing entries.
    fn sub_dict<'a>(
        &mut self,
        src: &Src,
        i: &'a str,
        name: String,
        loc: Location,
        open: &Location,
    ) -> Result<(&'a str, Dict), CaseError> {
        self.enter(src, i)?;
        self.stack.push(Dict::new(name, loc));
        let result = self.body(src, i, Some(open));
        let dict = self.stack.pop().expect("pushed above");
        self.depth -= 1;
        Ok((result?, dict))
    }

    /// One token of a value; a macro may expand to several.
    fn token<'a>(&mut self, src: &Src, i: &'a str) -> Result<(&'a str, Vec<Item>), CaseError> {
        let loc = src.loc(i);
        let c = i.chars().next().expect("caller checked for a character");
        let one = |rest, value| Ok((rest, vec![Item::new(value, loc.clone())]));
        match c {
            '(' => {
                let (rest, list) = self.list(src, i, None)?;
                one(rest, list)
            }
            '{' => {
                let name = scoped_name(&self.current().name, "{}");
                let (rest, dict) = self.sub_dict(src, &i[1..], name, loc.clone(), &loc)?;
                one(rest, Value::Dict(Box::new(dict)))
            }
            '[' => {
                let (rest, dims) = self.dimensions(src, i)?;
                one(rest, Value::Dimensions(dims))
            }
            '"' => match quoted(i) {
                Some((rest, s)) => one(rest, Value::Str(s)),
                None => Err(src.err(i, "expected '\"' to close the string opened here")),
            },
            '#' if i.starts_with("#{") => match i[2..].find("#}") {
                Some(end) => one(&i[2 + end + 2..], Value::Code(i[2..2 + end].to_string())),
                None => Err(src.err(i, "expected '#}' to close the code block opened here")),
            },
            '#' => match directive_name(&i[1..]) {
                Ok((rest, name)) if matches!(name, "calc" | "eval") => {
                    self.calculation(src, rest, name, &loc)
                }
                Ok((rest, name)) if rest.starts_with('{') => {
                    // `#name{ … }`: an expression kept as text, never evaluated.
                    let Some(end) = balanced_brace_end(rest) else {
                        return Err(
                            src.err(rest, "expected '}' to close the expression opened here")
                        );
                    };
                    let mut items =
                        vec![Item::new(Value::Directive(name.to_string()), loc.clone())];
                    items.push(Item::new(
                        Value::Code(rest[1..end].to_string()),
                        src.loc(rest),
                    ));
                    Ok((&rest[end + 1..], items))
                }
                Ok((rest, name)) => one(rest, Value::Directive(name.to_string())),
                Err(_) => Err(src.err(i, "expected a directive name after '#'")),
            },
            '$' => self.macro_value(src, i),
            ')' => Err(src.err(i, "expected a value, found ')' with no list open")),
            ']' => Err(src.err(i, "expected a value, found ']' with no dimension set open")),
            _ => {
                if let Ok((rest, value)) = number(i) {
                    if let Value::Scalar(x) = value {
                        if !x.is_finite() {
                            return Err(out_of_range(src, i, rest));
                        }
                    }
                    if let Value::Label(count) = value {
                        if let Some(r) = self.counted(src, rest, count, &loc)? {
                            return Ok(r);
                        }
                    }
                    return one(rest, value);
                }
                match word(i) {
                    Ok((rest, w)) => one(rest, Value::Word(w.to_string())),
                    Err(_) => Err(src.err(i, format!("expected a value, found '{c}'"))),
                }
            }
        }
    }

    /// A count-prefixed list `N(…)` or uniform list `N{v}` after the count, if one follows.
    #[allow(clippy::type_complexity)]
    fn counted<'a>(
        &mut self,
        src: &Src,
        after_count: &'a str,
        count: i64,
        count_loc: &Location,
    ) -> Result<Option<(&'a str, Vec<Item>)>, CaseError> {
        let next = self.skip(src, after_count)?;
        let gap = &after_count[..after_count.len() - next.len()];
        // `3(…)` or a count alone on its line with the list below (`8\n(`); a number ending a
        // line before a list (`… 90 0 0 0\n (liquid gas) 1`) is a table row, not a count.
        let list_follows = next.starts_with('(')
            && (gap.is_empty()
                || (gap.trim().is_empty()
                    && gap.contains('\n')
                    && first_on_line(src.text, count_loc.offset)));
        if count < 0 || !(list_follows || next.starts_with('{')) {
            return Ok(None);
        }
        let count = count as usize;
        if next.starts_with('(') {
            let (rest, list) = self.list(src, next, Some(count))?;
            let found = match &list {
                Value::List(items) => element_count(items),
                Value::Numbers { width, data, .. } => data.len() / width,
                _ => unreachable!("a list reads as a list"),
            };
            if found != count {
                return Err(CaseError::at(
                    count_loc,
                    format!("expected {count} elements as the count says, found a list of {found}"),
                ));
            }
            return Ok(Some((rest, vec![Item::new(list, count_loc.clone())])));
        }
        // `N{value}`: one token between the braces.
        let inner = self.skip(src, &next[1..])?;
        if inner.is_empty() || inner.starts_with('}') {
            return Err(src.err(inner, "expected the value of the uniform list N{value}"));
        }
        let (rest, mut items) = self.token(src, inner)?;
        let rest = self.skip(src, rest)?;
        if items.len() != 1 || !rest.starts_with('}') {
            return Err(src.err(rest, "expected '}' to end the uniform list N{value}"));
        }
        let item = items.pop().expect("one item");
        Ok(Some((
            &rest[1..],
            vec![Item::new(
                Value::UniformList(count, Box::new(item)),
                count_loc.clone(),
            )],
        )))
    }

    /// `( token* )`: packed when it holds numbers only ([`packed::scan`]; `count` is the
    /// count written before it), else a [`Value::List`].
    fn list<'a>(
        &mut self,
        src: &Src,
        i: &'a str,
        count: Option<usize>,
    ) -> Result<(&'a str, Value), CaseError> {
        if let Some(p) = packed::scan(i, count).filter(|_| self.pack) {
            let value = Value::Numbers {
                width: p.width,
                data: p.data,
                labels: p.labels,
            };
            return Ok((&i[p.end..], value));
        }
        let open = src.loc(i);
        self.enter(src, i)?;
        let mut items = Vec::new();
        let mut i = &i[1..];
        loop {
            i = self.skip(src, i)?;
            match i.chars().next() {
                Some(')') => {
                    self.depth -= 1;
                    return Ok((&i[1..], Value::List(items)));
                }
                None | Some(';') | Some('}') => {
                    let found = i
                        .chars()
                        .next()
                        .map_or("the end of the file".to_string(), |c| format!("'{c}'"));
                    let (line, col) = open.line_col();
                    return Err(src.err(
                        i,
                        format!(
                            "expected ')' to close the list opened at line {line} column {col}, found {found}"
                        ),
                    ));
                }
                Some(_) => {
                    let (rest, more) = self.token(src, i)?;
                    items.extend(more);
                    i = rest;
                }
            }
        }
    }

    /// `[0 1 -1 0 0 0 0]` or a named unit such as `[m/s]`.
    fn dimensions<'a>(&self, src: &Src, i: &'a str) -> Result<(&'a str, Dimensions), CaseError> {
        let (body_start, body) = match take_while::<_, _, nom::error::Error<&str>>(|c: char| {
            !matches!(c, ']' | ';' | '{' | '}' | '[')
        })(&i[1..])
        {
            Ok(r) => r,
            Err(_) => unreachable!("take_while never fails on complete input"),
        };
        if !body_start.starts_with(']') {
            return Err(src.err(
                body_start,
                "expected ']' to close the dimension set opened here",
            ));
        }
        let rest = &body_start[1..];
        let parts: Vec<&str> = body.split_whitespace().collect();
        // (`inf` and `nan` parse as f64 but are no exponents: they make the unit a name)
        let numbers: Option<Vec<f64>> = parts
            .iter()
            .map(|p| p.parse::<f64>().ok().filter(|x| x.is_finite()))
            .collect();
        let dims = match numbers {
            Some(e) if e.len() == 5 || e.len() == 7 => Dimensions::Exponents(e),
            Some(e) if !e.is_empty() => {
                return Err(src.err(
                    &i[1..],
                    format!("expected 5 or 7 dimension exponents, found {}", e.len()),
                ))
            }
            _ => Dimensions::Named(body.trim().to_string()),
        };
        Ok((rest, dims))
    }
}

/// Elements of a counted list: a word followed by a dictionary is one element (the
/// `name { … }` entries of `polyMesh/boundary`).
fn element_count(items: &[Item]) -> usize {
    let mut n = 0;
    let mut k = 0;
    while k < items.len() {
        let pair = items[k].as_word().is_some()
            && items
                .get(k + 1)
                .is_some_and(|next| next.as_dict().is_some());
        k += if pair { 2 } else { 1 };
        n += 1;
    }
    n
}

/// Whether only blanks stand between the start of the line and byte `offset`.
fn first_on_line(text: &str, offset: usize) -> bool {
    text[..offset]
        .rsplit('\n')
        .next()
        .is_some_and(|line| line.trim().is_empty())
}

/// Whether top-level text starts a bare value: a list, or a count before a list.
fn number_or_list(i: &str) -> bool {
    if i.starts_with('(') {
        return true;
    }
    match number(i) {
        Ok((rest, Value::Label(_))) => rest.trim_start().starts_with('('),
        _ => false,
    }
}

fn scoped_name(parent: &str, key: &str) -> String {
    if parent.is_empty() {
        key.to_string()
    } else {
        format!("{parent}.{key}")
    }
}

impl Dict {
    /// Reads a dictionary file; see [`read_dict_file`].
    pub fn read(path: &Path, case_dir: Option<&Path>) -> Result<Dict, CaseError> {
        read_dict_file(path, case_dir)
    }

    /// Parses text; see [`parse_dict`].
    pub fn parse(text: &str, display: &str) -> Result<Dict, CaseError> {
        parse_dict(text, display)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Dict {
        parse_dict(text, "test").unwrap_or_else(|e| panic!("{}", e.report()))
    }

    fn err(text: &str) -> CaseError {
        parse_dict(text, "test").expect_err("expected a parse error")
    }

    /// `text` read without packing numeric lists: one token per number.
    fn parse_general(text: &str) -> Dict {
        let file = Arc::new(SourceFile::from_text(
            PathBuf::new(),
            "test".to_string(),
            text.to_string(),
        ));
        parse_with(file, None, false)
            .0
            .unwrap_or_else(|e| panic!("{}", e.report()))
    }

    /// SplitMix64 (Steele, Lea & Flood 2014): seeded numbers for the tests.
    struct SplitMix(u64);

    impl SplitMix {
        fn next(&mut self) -> u64 {
            self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            z ^ (z >> 31)
        }

        fn below(&mut self, n: u64) -> u64 {
            self.next() % n
        }
    }

    /// A number in one of the textual forms OpenFOAM files use.
    fn random_number(rng: &mut SplitMix) -> String {
        let digits = rng.below(100_000);
        let small = rng.below(100);
        let sign = ["", "-", "+"][rng.below(3) as usize];
        match rng.below(8) {
            0 => format!("{sign}{digits}"),
            1 => format!("{sign}{small}.{digits}e-{}", rng.below(12)),
            2 => format!("{sign}{small}E+{:02}", rng.below(20)),
            3 => format!("{sign}.{digits}"),
            4 => format!("{sign}{digits}."),
            5 => format!("{sign}{small}.{digits}"),
            6 => format!("{sign}{digits}e{}", rng.below(5)),
            _ => format!("{sign}0"),
        }
    }

    /// Blanks and comments between numbers.
    fn random_gap(rng: &mut SplitMix) -> &'static str {
        [" ", "  ", "\t", "\n", "\r\n", " // note\n", " /* (1 x) */ "][rng.below(7) as usize]
    }

    #[test]
    fn packed_lists_read_as_the_general_path_does() {
        let mut rng = SplitMix(20261123);
        for width in [1usize, 3, 9] {
            let n = 500;
            let mut text = format!("a\n{n}\n(");
            for _ in 0..n {
                text.push_str(random_gap(&mut rng));
                if width > 1 {
                    text.push('(');
                }
                for c in 0..width {
                    if c > 0 {
                        text.push_str(random_gap(&mut rng));
                    }
                    text.push_str(&random_number(&mut rng));
                }
                if width > 1 {
                    text.push(')');
                }
            }
            text.push_str("\n);\nb (1 2 3);\n");
            let packed = parse(&text);
            let general = parse_general(&text);
            let p = &packed.get_tokens("a").unwrap()[0];
            let g = &general.get_tokens("a").unwrap()[0];
            assert!(
                matches!(p.value, Value::Numbers { width: w, .. } if w == width),
                "{width}: {}",
                &text[..200]
            );
            assert!(matches!(g.value, Value::List(_)));
            assert_eq!(p.to_string(), g.to_string());
            let (pl, gl) = (p.as_list().unwrap(), g.as_list().unwrap());
            assert_eq!(pl.len(), n);
            assert_eq!(gl.len(), n);
            for i in 0..n {
                let (pi, gi) = (pl.get(i).unwrap(), gl.get(i).unwrap());
                assert_eq!(pi.to_string(), gi.to_string(), "element {i}");
                assert_eq!(pi.loc.line_col(), gi.loc.line_col(), "element {i}");
                let (pn, gn) = (pl.numbers(i).unwrap(), gl.numbers(i).unwrap());
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&pn), bits(&gn), "element {i}");
                if width == 1 {
                    assert_eq!(pi.as_label(), gi.as_label(), "element {i}");
                } else {
                    let (pr, gr) = (pi.as_list().unwrap(), gi.as_list().unwrap());
                    for c in 0..width {
                        let (pc, gc) = (pr.get(c).unwrap(), gr.get(c).unwrap());
                        assert_eq!(pc.as_label(), gc.as_label(), "element {i}.{c}");
                        assert_eq!(pc.loc.line_col(), gc.loc.line_col(), "element {i}.{c}");
                    }
                }
            }
        }
    }

    #[test]
    fn errors_in_and_after_numeric_lists_name_the_place() {
        // A word among numbers: the list is read by the general grammar, and a typed read
        // points at the word.
        let mut text = String::from("a (\n");
        for i in 0..2000 {
            text.push_str(if i == 1000 { "abc\n" } else { "1.5 2\n" });
        }
        text.push_str(");\n");
        let d = parse(&text);
        let list = d.get_tokens("a").unwrap()[0].as_list().unwrap();
        let bad = (0..list.len())
            .map(|i| list.get(i).unwrap())
            .find(|x| x.as_scalar().is_none())
            .unwrap();
        assert_eq!(bad.loc.line_col(), (1002, 1));
        // A missing `)`: at the `;`, naming where the list opened.
        let text = format!("x 1;\nb 3 ( 1 2\n   3 {};\n", "4 ".repeat(10));
        let e = err(&text);
        assert_eq!((e.line, e.col), (3, 26), "{e}");
        assert!(e.message.contains("opened at line 2 column 5"), "{e}");
        // A count that disagrees with a packed list.
        let e = err("b 3(1 2);");
        assert_eq!((e.line, e.col), (1, 3), "{e}");
        assert!(e.message.contains("expected 3 elements"), "{e}");
    }

    #[test]
    fn a_released_text_is_read_again_for_messages() {
        let dir = std::env::temp_dir().join(format!("fsim-parser-release-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("big");
        let rows = (RELEASE_BYTES / 20) + 10;
        let mut text = String::from("a (\n");
        for i in 0..rows {
            text.push_str(&format!("({i} 0.5 -1e-3)\n"));
        }
        text.push_str(");\nb abc;\n");
        std::fs::write(&path, &text).unwrap();
        let d = read_dict_file(&path, Some(&dir)).unwrap();
        let e = d.get_scalar("b").unwrap_err();
        assert_eq!((e.line, e.col), (rows + 3, 3), "{e}");
        assert_eq!(
            e.excerpt().unwrap().lines().nth(2).unwrap().trim_end(),
            format!("{} | b abc;", rows + 3)
        );
        let list = d.get_tokens("a").unwrap()[0].as_list().unwrap();
        let row = list.get(rows - 1).unwrap();
        assert_eq!(row.loc.line_col(), (rows + 1, 1));
        let last = row.as_list().unwrap().get(2).unwrap();
        let col = format!("({} 0.5 ", rows - 1).len() + 1;
        assert_eq!(last.loc.line_col(), (rows + 1, col));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn header_comments_and_nested_dictionaries() {
        let d = parse(
            "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n\
             // a comment\n/* block\n comment */ application icoFoam;\n\
             sub { inner { x 1.5; } y -2; }\n",
        );
        assert_eq!(d.get_word("application").unwrap(), "icoFoam");
        let sub = d.get_dict("sub").unwrap();
        assert_eq!(sub.get_dict("inner").unwrap().get_scalar("x").unwrap(), 1.5);
        assert_eq!(sub.get_scalar("y").unwrap(), -2.0);
        assert_eq!(sub.get_dict("inner").unwrap().name, "sub.inner");
    }

    /// A number beyond a double's range is refused where it is written, as `inf` is where
    /// a number is read: in an entry, in a packed list, as a long integer, from `#calc`.
    #[test]
    fn numbers_beyond_a_double_are_refused_in_place() {
        for (text, col, shown) in [
            ("endTime 1e400;", 9, "1e400"),
            ("x -1.5E+999;", 3, "-1.5E+999"),
            ("l (1 2 1e309);", 8, "1e309"),
            ("v ((0 0 0) (1 1e999 1));", 15, "1e999"),
        ] {
            let e = err(text);
            assert_eq!((e.line, e.col), (1, col), "{text}: {e}");
            assert!(
                e.message
                    .contains(&format!("the number {shown} is out of range")),
                "{e}"
            );
        }
        let digits = format!("n {};", "9".repeat(400));
        let e = err(&digits);
        assert!(e.message.contains("…(400 bytes) is out of range"), "{e}");
        // (#calc and #eval leave an infinite result unevaluated, which no accessor takes)
        assert!(parse("a 1e300; b #calc \"$a*$a\";")
            .get_scalar("b")
            .is_err());
        // underflow is zero, as OpenFOAM reads it; inf in a dimension set is no exponent
        assert_eq!(parse("x 1e-400;").get_scalar("x").unwrap(), 0.0);
        assert!(matches!(
            parse("d [inf 0 0 0 0 0 0];")
                .peek("d")
                .unwrap()
                .as_tokens()
                .unwrap()[0]
                .value,
            Value::Dimensions(Dimensions::Named(_))
        ));
    }

    /// An excerpt shows a window of a long line around the column, the caret under it.
    #[test]
    fn excerpts_of_long_lines_are_windows() {
        let text = format!("a {} );", "y".repeat(1_000_000));
        let e = err(&text);
        let excerpt = e.excerpt().unwrap();
        assert!(excerpt.len() < 500, "{} bytes", excerpt.len());
        let lines: Vec<&str> = excerpt.lines().collect();
        let caret = lines[3].chars().position(|c| c == '^').unwrap();
        assert_eq!(lines[2].chars().nth(caret), Some(')'), "{excerpt}");
    }

    #[test]
    fn numbers_do_not_swallow_words() {
        let d = parse("a inflow; b nanoParticle; c infinity; d e5x; e 1st; f 1e-5; g -3; h .5;");
        for (k, w) in [
            ("a", "inflow"),
            ("b", "nanoParticle"),
            ("c", "infinity"),
            ("d", "e5x"),
            ("e", "1st"),
        ] {
            assert_eq!(d.get_word(k).unwrap(), w);
        }
        assert_eq!(d.get_scalar("f").unwrap(), 1e-5);
        assert_eq!(d.get_scalar("g").unwrap(), -3.0);
        assert_eq!(d.get_scalar("h").unwrap(), 0.5);
        assert!(d.get_label("g").is_err());
    }

    #[test]
    fn count_prefixed_and_uniform_lists() {
        let d = parse(
            "a 3((0 0 0)(1 1 1)(2 2 2));\nb List<vector> 2((1 2 3) (4 5 6));\nc 4{0.5};\n\
             d table ((0 (1 0 0)) (1 (2 0 0)));\ne List<scalar>\n2\n(\n7\n8\n);",
        );
        let a = &d.get_tokens("a").unwrap()[0];
        assert_eq!(a.as_list().unwrap().len(), 3);
        assert_eq!(
            a.as_list().unwrap().get(2).unwrap().as_vector(),
            Some([2.0; 3])
        );
        let b = d.get_tokens("b").unwrap();
        assert_eq!(b[0].as_word(), Some("List<vector>"));
        assert_eq!(
            b[1].as_list().unwrap().get(1).unwrap().as_vector(),
            Some([4.0, 5.0, 6.0])
        );
        let c = d.get_tokens("c").unwrap()[0].as_list().unwrap();
        assert_eq!(c.len(), 4);
        assert_eq!(c.get(3).unwrap().as_scalar(), Some(0.5));
        // A table row: a number, then a vector (not a count-prefixed list).
        let row = d.get_tokens("d").unwrap()[1]
            .as_list()
            .unwrap()
            .get(0)
            .unwrap();
        let row = row.as_list().unwrap();
        assert_eq!(row.get(0).unwrap().as_label(), Some(0));
        assert_eq!(row.get(1).unwrap().as_vector(), Some([1.0, 0.0, 0.0]));
        assert_eq!(d.get_tokens("e").unwrap()[1].as_list().unwrap().len(), 2);
    }

    #[test]
    fn dimensions_and_dimensioned_scalars() {
        let d = parse("nu [0 2 -1 0 0 0 0] 0.01;\nold nu [0 2 -1 0 0 0 0] 1e-3;\nold2 old2 [0 2 -1 0 0 0 0] 2;\nu [m/s] 3;");
        assert_eq!(d.get_scalar("nu").unwrap(), 0.01);
        assert!(d.get_scalar("old").is_err());
        assert_eq!(d.get_scalar("old2").unwrap(), 2.0);
        assert_eq!(d.get_scalar("u").unwrap(), 3.0);
        match &d.get_tokens("u").unwrap()[0].value {
            Value::Dimensions(Dimensions::Named(n)) => assert_eq!(n, "m/s"),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn macros_follow_scopes() {
        let d = parse(
            "U0 (1 0 0);\ninternalField uniform $U0;\n\
             boundaryField { inlet { type fixedValue; value $internalField; }\n\
             outlet { $inlet; type zeroGradient; } }\n\
             geo { L 2; sub { x $..L; y $..L; z ${L}; } }\nw $geo.L;\nw2 $:geo.L;",
        );
        let inlet = d
            .get_dict("boundaryField")
            .unwrap()
            .get_dict("inlet")
            .unwrap();
        let v = inlet.get_tokens("value").unwrap();
        assert_eq!(v[0].as_word(), Some("uniform"));
        assert_eq!(v[1].as_vector(), Some([1.0, 0.0, 0.0]));
        let outlet = d
            .get_dict("boundaryField")
            .unwrap()
            .get_dict("outlet")
            .unwrap();
        assert_eq!(outlet.get_word("type").unwrap(), "zeroGradient");
        assert!(outlet.contains("value"));
        let sub = d.get_dict("geo").unwrap().get_dict("sub").unwrap();
        for k in ["x", "y", "z"] {
            assert_eq!(sub.get_scalar(k).unwrap(), 2.0, "{k}");
        }
        assert_eq!(d.get_scalar("w").unwrap(), 2.0);
        assert_eq!(d.get_scalar("w2").unwrap(), 2.0);
        let e = err("a $nothing;");
        assert_eq!((e.line, e.col), (1, 3));
        assert!(e.message.contains("undefined variable '$nothing'"));
    }

    #[test]
    fn regex_keys_match_whole_keyword_last_first_after_exact() {
        let d = parse("\".*\" { t a; }\n\"(top|bottom)\" { t b; }\ntop { t c; }\n");
        assert_eq!(d.get_dict("top").unwrap().get_word("t").unwrap(), "c");
        assert_eq!(d.get_dict("bottom").unwrap().get_word("t").unwrap(), "b");
        assert_eq!(d.get_dict("topx").unwrap().get_word("t").unwrap(), "a");
    }

    #[test]
    fn booleans_strings_code_and_directives() {
        let d = parse(
            "a on; b off; c yes; d no; e true; f false; g none;\n\
             s \"a;b\\\"c\";\ncode #{ x = 1; #};\n\
             x #calc \"$a*2\";\n#includeEtc \"caseDicts/setConstraintTypes\"\n\
             #inputMode merge\nfunctions { #includeFunc mag(U)\n }\n",
        );
        let want = [true, false, true, false, true, false, false];
        for (k, w) in ["a", "b", "c", "d", "e", "f", "g"].iter().zip(want) {
            assert_eq!(d.get_bool(k).unwrap(), w);
        }
        assert_eq!(d.get_word("s").unwrap(), "a;b\"c");
        assert!(matches!(
            d.get_tokens("code").unwrap()[0].value,
            Value::Code(_)
        ));
        assert!(matches!(
            d.get_tokens("x").unwrap()[0].value,
            Value::Directive(_)
        ));
        assert_eq!(d.directives[0].name, "includeEtc");
        let f = d.get_dict("functions").unwrap();
        assert_eq!(f.directives[0].argument, "mag(U)");
    }

    #[test]
    fn missing_semicolon_points_after_the_value() {
        let e = err("a 1;\nnu 0.01\n}");
        assert_eq!((e.line, e.col), (2, 8), "{e}");
        assert!(e.message.contains("expected ';' to end the entry 'nu'"));
        let e = err("d { type wall }");
        assert_eq!((e.line, e.col), (1, 14), "{e}");
        assert_eq!(
            e.to_string(),
            "test:1:14: expected ';' to end the entry 'type'"
        );
        let excerpt = e.excerpt().unwrap();
        assert!(excerpt.ends_with("|              ^"), "{excerpt}");
    }

    #[test]
    fn unused_entries_are_listed() {
        let d = parse("FoamFile { version 2; }\na 1; b 2; c { x 1; y 2; } e { z 1; }");
        d.get_scalar("a").unwrap();
        d.get_dict("c").unwrap().get_scalar("x").unwrap();
        let unused: Vec<String> = d.unused().into_iter().map(|(k, _)| k).collect();
        assert_eq!(unused, ["b", "c.y", "e"]);
    }

    #[test]
    fn top_level_values_are_kept() {
        let d = parse("FoamFile { class vectorField; }\n2\n(\n(0 0 0)\n(1 2 3)\n)\n");
        assert_eq!(d.values.len(), 1);
        assert_eq!(
            d.values[0].as_list().unwrap().get(1).unwrap().as_vector(),
            Some([1.0, 2.0, 3.0])
        );
    }

    #[test]
    fn messages_quoting_line_breaks_stay_one_line() {
        let e = err("#include \"a\nb\"");
        assert_eq!(e.to_string().lines().count(), 1, "{e}");
        assert!(e.message.contains("a\\nb"), "{e}");
    }

    #[test]
    fn fuzz_findings_hold_the_contract() {
        // A lone carriage return is a column, not a line break (found by cargo fuzz).
        check_parser_invariants("a [c\n\r\r\r\r\r");
        let e = err("a [c\n\r\r\r");
        assert_eq!((e.line, e.col), (2, 4), "{e}");
        // A quoted line break inside an error message (found by cargo fuzz).
        check_parser_invariants("#include \"\u{fffd}\n}\n#include \"x\"\n");
    }

    #[test]
    fn calc_and_eval_give_numbers_when_they_can() {
        let d = parse(
            "L 10; n 7; r 2.0;\nhalf #calc \"$L/2\";\ncells #calc \"$n/2\";\n\
             y #eval{ $r*sin(degToRad(30)) };\nz #eval \"${n}/2\";\n\
             v ( 0 #calc \"-$L\" 0 );\nw #calc \"vector(1, 2, 3)\";\nu #eval{ $nothing + 1 };",
        );
        assert_eq!(d.get_label("half").unwrap(), 5);
        assert_eq!(d.get_label("cells").unwrap(), 3);
        assert!((d.get_scalar("y").unwrap() - 1.0).abs() < 1e-12);
        assert_eq!(d.get_scalar("z").unwrap(), 3.5);
        assert_eq!(d.get_vector("v").unwrap(), [0.0, -10.0, 0.0]);
        // Outside the subset: kept, and a typed read says fsim does not evaluate it.
        let e = d.get_scalar("w").unwrap_err();
        assert!(
            e.message.contains("'#calc' (fsim does not evaluate it)"),
            "{e}"
        );
        assert!(d.get_scalar("u").is_err());
        // The result sits where the directive was written.
        let half = &d.get_tokens("half").unwrap()[0];
        assert_eq!(half.loc.line_col(), (2, 6));
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_crash() {
        let text = format!("a {};", "(".repeat(10_000));
        let e = err(&text);
        assert!(e.message.contains("nested"), "{e}");
    }

    /// The files `#include`s name are listed, nested ones too, in the order met; an optional
    /// include of a missing file names none, a required one does (and fails the read, with
    /// the files met before it).
    #[test]
    fn the_files_included_are_listed_in_the_order_met() {
        let dir = std::env::temp_dir().join(format!("fsim-parser-included-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        std::fs::write(
            dir.join("top"),
            "#include \"sub/a\"\n#includeIfPresent \"none\"\nc 3;\n",
        )
        .unwrap();
        std::fs::write(dir.join("sub/a"), "a 1;\n#include \"b\"\n").unwrap();
        std::fs::write(dir.join("sub/b"), "b 2;\n").unwrap();
        std::fs::write(
            dir.join("broken"),
            "#include \"sub/b\"\n#include \"later\"\n",
        )
        .unwrap();
        let (read, included) = read_dict_file_with_includes(&dir.join("top"), Some(&dir));
        let (broken, met) = read_dict_file_with_includes(&dir.join("broken"), Some(&dir));
        let _ = std::fs::remove_dir_all(&dir);
        let d = read.unwrap_or_else(|e| panic!("{}", e.report()));
        assert_eq!(included, vec![dir.join("sub/a"), dir.join("sub/b")]);
        assert!(d.contains("a") && d.contains("b") && d.contains("c"));
        assert!(broken.unwrap_err().message.contains("file not found"));
        assert_eq!(met, vec![dir.join("sub/b"), dir.join("later")]);
    }
}
