//! An OpenFOAM dictionary: ordered keyword entries, with OpenFOAM's lookup rules and typed
//! accessors whose errors point at the offending value.
//!
//! Lookup follows OpenFOAM: an exact keyword first, then the quoted (regular-expression) keys,
//! the last defined first, each matching the whole keyword. Every lookup marks the entry as
//! read, so that [`Dict::unused`] can list what fsim ignored.

use std::sync::atomic::{AtomicBool, Ordering};

use regex::Regex;

use super::error::CaseError;
use super::source::Location;
use super::value::{Dimensions, Item, Value};

/// An entry's keyword: a word, or a quoted key that matches as a regular expression.
#[derive(Clone, Debug)]
pub enum Key {
    Word(String),
    /// The key as written and its compiled full-match expression.
    Pattern(String, Regex),
}

impl Key {
    /// A quoted key becomes a pattern; one that is not a valid expression stays a word.
    pub fn quoted(text: &str) -> Key {
        Key::pattern(text).unwrap_or_else(|_| Key::Word(text.to_string()))
    }

    /// A pattern matching whole names, or the expression's error (for callers that refuse
    /// an invalid one).
    pub fn pattern(text: &str) -> Result<Key, regex::Error> {
        Regex::new(&format!("^(?:{text})$")).map(|re| Key::Pattern(text.to_string(), re))
    }

    /// Whether the key names `text`: a word equal to it, a pattern matching it whole.
    pub fn matches(&self, text: &str) -> bool {
        match self {
            Key::Word(w) => w == text,
            Key::Pattern(_, re) => re.is_match(text),
        }
    }

    /// The key as written.
    pub fn as_str(&self) -> &str {
        match self {
            Key::Word(w) => w,
            Key::Pattern(p, _) => p,
        }
    }

    pub fn is_pattern(&self) -> bool {
        matches!(self, Key::Pattern(..))
    }

    /// Whether `keyword` matches this key as a whole (patterns only; words need equality).
    pub fn pattern_matches(&self, keyword: &str) -> bool {
        match self {
            Key::Word(_) => false,
            Key::Pattern(_, re) => re.is_match(keyword),
        }
    }
}

/// What follows a keyword: a sub-dictionary or a token stream ended by `;`.
#[derive(Clone, Debug)]
pub enum EntryBody {
    Dict(Dict),
    Tokens(Vec<Item>),
}

/// One keyword entry.
#[derive(Debug)]
pub struct Entry {
    pub key: Key,
    /// Where the keyword was written.
    pub key_loc: Location,
    pub body: EntryBody,
    used: AtomicBool,
}

impl Clone for Entry {
    fn clone(&self) -> Self {
        Entry {
            key: self.key.clone(),
            key_loc: self.key_loc.clone(),
            body: self.body.clone(),
            used: AtomicBool::new(self.used.load(Ordering::Relaxed)),
        }
    }
}

impl Entry {
    pub fn new(key: Key, key_loc: Location, body: EntryBody) -> Self {
        Entry {
            key,
            key_loc,
            body,
            used: AtomicBool::new(false),
        }
    }

    pub fn keyword(&self) -> &str {
        self.key.as_str()
    }

    pub fn as_dict(&self) -> Option<&Dict> {
        match &self.body {
            EntryBody::Dict(d) => Some(d),
            EntryBody::Tokens(_) => None,
        }
    }

    pub fn as_tokens(&self) -> Option<&[Item]> {
        match &self.body {
            EntryBody::Dict(_) => None,
            EntryBody::Tokens(t) => Some(t),
        }
    }

    /// Marks the entry as read by fsim.
    pub fn mark_used(&self) {
        self.used.store(true, Ordering::Relaxed);
    }

    pub fn is_used(&self) -> bool {
        self.used.load(Ordering::Relaxed)
    }

    /// Where the value starts (the keyword itself for an empty value).
    pub fn value_loc(&self) -> &Location {
        match &self.body {
            EntryBody::Dict(d) => &d.loc,
            EntryBody::Tokens(t) => t.first().map_or(&self.key_loc, |i| &i.loc),
        }
    }
}

/// A directive that fsim records but does not run (`#includeEtc`, `#includeFunc`).
#[derive(Clone, Debug)]
pub struct Directive {
    /// Without the `#`: `includeEtc`.
    pub name: String,
    /// The argument as written.
    pub argument: String,
    pub loc: Location,
}

/// An ordered dictionary of entries.
#[derive(Clone, Debug)]
pub struct Dict {
    /// Dotted scope name (`boundaryField.inlet`); empty for a file's top level.
    pub name: String,
    /// Where the dictionary starts: its keyword, or the file's start for the top level.
    pub loc: Location,
    entries: Vec<Entry>,
    /// Values standing alone at a file's top level, such as the list of
    /// `kinematicCloudPositions` or `polyMesh/points`.
    pub values: Vec<Item>,
    /// Directives recorded but not run.
    pub directives: Vec<Directive>,
}

impl Dict {
    pub fn new(name: String, loc: Location) -> Self {
        Dict {
            name,
            loc,
            entries: Vec::new(),
            values: Vec::new(),
            directives: Vec::new(),
        }
    }

    /// All entries in the order written.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The file the dictionary was read from, as shown to the user.
    pub fn file(&self) -> &str {
        &self.loc.file.display
    }

    /// Adds an entry with OpenFOAM's `#inputMode merge` rule: a repeated keyword replaces the
    /// earlier value in place, and a repeated sub-dictionary merges into the earlier one.
    pub fn insert(&mut self, entry: Entry) {
        let existing = self
            .entries
            .iter_mut()
            .find(|e| e.key.as_str() == entry.key.as_str());
        match existing {
            Some(old) => match (&mut old.body, entry.body) {
                (EntryBody::Dict(old_dict), EntryBody::Dict(new_dict)) => {
                    for e in new_dict.entries {
                        old_dict.insert(e);
                    }
                }
                (body, new_body) => {
                    *body = new_body;
                    old.key = entry.key;
                    old.key_loc = entry.key_loc;
                }
            },
            None => self.entries.push(entry),
        }
    }

    /// Removes the entries whose keyword equals `keyword` or whose pattern matches it.
    pub fn remove(&mut self, keyword: &str) {
        self.entries
            .retain(|e| e.key.as_str() != keyword && !e.key.pattern_matches(keyword));
    }

    /// Looks a keyword up without marking it read: exact first, then patterns, last first.
    pub fn peek(&self, keyword: &str) -> Option<&Entry> {
        self.entries
            .iter()
            .rev()
            .find(|e| e.key.as_str() == keyword)
            .or_else(|| {
                self.entries
                    .iter()
                    .rev()
                    .find(|e| e.key.pattern_matches(keyword))
            })
    }

    /// Looks a keyword up and marks the entry read.
    pub fn lookup(&self, keyword: &str) -> Option<&Entry> {
        let e = self.peek(keyword)?;
        e.mark_used();
        Some(e)
    }

    pub fn contains(&self, keyword: &str) -> bool {
        self.peek(keyword).is_some()
    }

    /// Marks this dictionary and everything below it read (a dictionary kept whole for a
    /// later stage).
    pub fn mark_all_used(&self) {
        for e in &self.entries {
            e.mark_used();
            if let EntryBody::Dict(d) = &e.body {
                d.mark_all_used();
            }
        }
    }

    /// Entries never read, as `(dotted keyword, where)`, in file order; inside a read
    /// sub-dictionary its own unread entries are listed. The `FoamFile` header is skipped.
    pub fn unused(&self) -> Vec<(String, Location)> {
        let mut out = Vec::new();
        self.collect_unused("", &mut out);
        out
    }

    fn collect_unused(&self, prefix: &str, out: &mut Vec<(String, Location)>) {
        for e in &self.entries {
            if prefix.is_empty() && e.keyword() == "FoamFile" {
                continue;
            }
            let name = format!("{prefix}{}", e.keyword());
            if !e.is_used() {
                out.push((name, e.key_loc.clone()));
            } else if let EntryBody::Dict(d) = &e.body {
                d.collect_unused(&format!("{name}."), out);
            }
        }
    }

    /// "dictionary 'boundaryField.inlet'" or "the top-level dictionary".
    fn describe(&self) -> String {
        if self.name.is_empty() {
            "the top-level dictionary".to_string()
        } else {
            format!("dictionary '{}'", self.name)
        }
    }

    /// The error for a keyword that is required and absent: it points at the dictionary's
    /// start.
    pub fn missing(&self, keyword: &str) -> CaseError {
        let (line, _) = self.loc.line_col();
        CaseError::at(
            &self.loc,
            format!(
                "missing keyword '{keyword}' in {} (starting at line {line})",
                self.describe()
            ),
        )
    }

    /// Checks the dimension set written in `keyword`'s entry (`nu [0 2 -1 0 0 0 0] 1e-5;`,
    /// `dimensions [0 1 -1 0 0 0 0];`) against `expected`, the exponents of kg, m, s, K, mol,
    /// A, cd; `meaning` says what they are. No set written, or no entry: nothing to check
    /// (fsim knows each quantity's dimensions). A set that differs is an error at it, as
    /// OpenFOAM stops on one; a unit by name (`[mm^2/s]`), which OpenFOAM converts, is refused.
    pub fn check_dimensions(
        &self,
        keyword: &str,
        expected: [f64; 7],
        meaning: &str,
    ) -> Result<(), CaseError> {
        let Some(tokens) = self.peek(keyword).and_then(Entry::as_tokens) else {
            return Ok(());
        };
        let Some(item) = tokens
            .iter()
            .find(|t| matches!(t.value, Value::Dimensions(_)))
        else {
            return Ok(());
        };
        let show = |e: &[f64]| {
            let parts: Vec<String> = e.iter().map(|x| x.to_string()).collect();
            format!("[{}]", parts.join(" "))
        };
        match &item.value {
            Value::Dimensions(Dimensions::Exponents(e)) => {
                let mut given = [0.0; 7];
                given[..e.len().min(7)].copy_from_slice(&e[..e.len().min(7)]);
                if given != expected {
                    return Err(CaseError::at(
                        &item.loc,
                        format!(
                            "'{keyword}' has dimensions {}: expected {} ({meaning})",
                            show(e),
                            show(&expected)
                        ),
                    ));
                }
                Ok(())
            }
            Value::Dimensions(Dimensions::Named(unit)) => Err(CaseError::at(
                &item.loc,
                format!(
                    "'{keyword}' gives its unit by name, [{unit}]: fsim reads SI values with \
                     exponents only; write {} and the value in SI ({meaning})",
                    show(&expected)
                ),
            )),
            _ => Ok(()),
        }
    }

    /// A required entry.
    pub fn get_entry(&self, keyword: &str) -> Result<&Entry, CaseError> {
        self.lookup(keyword).ok_or_else(|| self.missing(keyword))
    }

    /// The token stream of a required entry.
    pub fn get_tokens(&self, keyword: &str) -> Result<&[Item], CaseError> {
        let e = self.get_entry(keyword)?;
        e.as_tokens().ok_or_else(|| {
            CaseError::at(
                &e.key_loc,
                format!("expected a value ended by ';' for '{keyword}', found a dictionary"),
            )
        })
    }

    /// A required sub-dictionary.
    pub fn get_dict(&self, keyword: &str) -> Result<&Dict, CaseError> {
        let e = self.get_entry(keyword)?;
        entry_dict(e)
    }

    /// An optional sub-dictionary; a non-dictionary value under that keyword is an error.
    pub fn opt_dict(&self, keyword: &str) -> Result<Option<&Dict>, CaseError> {
        self.lookup(keyword).map(entry_dict).transpose()
    }

    /// The one value token of an entry. A leading dimension set, and the old
    /// `nu nu [0 2 -1 0 0 0 0] 0.01;` form's repeated name before it, are skipped.
    fn single(&self, keyword: &str, what: &str) -> Result<Option<&Item>, CaseError> {
        let Some(e) = self.lookup(keyword) else {
            return Ok(None);
        };
        single_token(e, what).map(Some)
    }

    fn typed<T>(
        &self,
        keyword: &str,
        what: &str,
        convert: impl Fn(&Item) -> Option<T>,
    ) -> Result<Option<T>, CaseError> {
        match self.single(keyword, what)? {
            None => Ok(None),
            Some(item) => convert(item)
                .map(Some)
                .ok_or_else(|| wrong_type(keyword, what, item)),
        }
    }

    /// An optional real number.
    pub fn opt_scalar(&self, keyword: &str) -> Result<Option<f64>, CaseError> {
        self.typed(keyword, "a number", Item::as_scalar)
    }

    /// A required real number.
    pub fn get_scalar(&self, keyword: &str) -> Result<f64, CaseError> {
        self.opt_scalar(keyword)?
            .ok_or_else(|| self.missing(keyword))
    }

    /// A real number, `default` when absent.
    pub fn get_scalar_or(&self, keyword: &str, default: f64) -> Result<f64, CaseError> {
        Ok(self.opt_scalar(keyword)?.unwrap_or(default))
    }

    /// An optional non-negative integer.
    pub fn opt_label(&self, keyword: &str) -> Result<Option<usize>, CaseError> {
        self.typed(keyword, "a non-negative integer", |i| {
            i.as_label().and_then(|n| usize::try_from(n).ok())
        })
    }

    /// An optional integer of either sign.
    pub fn opt_integer(&self, keyword: &str) -> Result<Option<i64>, CaseError> {
        self.typed(keyword, "an integer", |i| i.as_label())
    }

    /// A required non-negative integer.
    pub fn get_label(&self, keyword: &str) -> Result<usize, CaseError> {
        self.opt_label(keyword)?
            .ok_or_else(|| self.missing(keyword))
    }

    pub fn get_label_or(&self, keyword: &str, default: usize) -> Result<usize, CaseError> {
        Ok(self.opt_label(keyword)?.unwrap_or(default))
    }

    /// An optional word (a quoted string is accepted too).
    pub fn opt_word(&self, keyword: &str) -> Result<Option<String>, CaseError> {
        self.typed(keyword, "a word", |i| match &i.value {
            Value::Word(w) | Value::Str(w) => Some(w.clone()),
            _ => None,
        })
    }

    pub fn get_word(&self, keyword: &str) -> Result<String, CaseError> {
        self.opt_word(keyword)?.ok_or_else(|| self.missing(keyword))
    }

    pub fn get_word_or(&self, keyword: &str, default: &str) -> Result<String, CaseError> {
        Ok(self
            .opt_word(keyword)?
            .unwrap_or_else(|| default.to_string()))
    }

    /// An optional switch (`on/off/yes/no/true/false/none`).
    pub fn opt_bool(&self, keyword: &str) -> Result<Option<bool>, CaseError> {
        self.typed(
            keyword,
            "a switch (on/off, yes/no, true/false)",
            Item::as_bool,
        )
    }

    pub fn get_bool(&self, keyword: &str) -> Result<bool, CaseError> {
        self.opt_bool(keyword)?.ok_or_else(|| self.missing(keyword))
    }

    pub fn get_bool_or(&self, keyword: &str, default: bool) -> Result<bool, CaseError> {
        Ok(self.opt_bool(keyword)?.unwrap_or(default))
    }

    /// An optional vector `(x y z)`.
    pub fn opt_vector(&self, keyword: &str) -> Result<Option<[f64; 3]>, CaseError> {
        self.typed(keyword, "a vector (x y z)", Item::as_vector)
    }

    pub fn get_vector(&self, keyword: &str) -> Result<[f64; 3], CaseError> {
        self.opt_vector(keyword)?
            .ok_or_else(|| self.missing(keyword))
    }

    pub fn get_vector_or(&self, keyword: &str, default: [f64; 3]) -> Result<[f64; 3], CaseError> {
        Ok(self.opt_vector(keyword)?.unwrap_or(default))
    }
}

fn entry_dict(e: &Entry) -> Result<&Dict, CaseError> {
    e.as_dict().ok_or_else(|| {
        CaseError::at(
            e.value_loc(),
            format!(
                "expected a dictionary {{ … }} for '{}', found a value",
                e.keyword()
            ),
        )
    })
}

/// The single value token of an entry (see [`Dict::get_scalar`]).
pub fn single_token<'a>(e: &'a Entry, what: &str) -> Result<&'a Item, CaseError> {
    let keyword = e.keyword();
    let tokens = e.as_tokens().ok_or_else(|| {
        CaseError::at(
            &e.key_loc,
            format!("expected {what} for '{keyword}', found a dictionary"),
        )
    })?;
    let mut rest = tokens;
    if let [first, second, ..] = rest {
        if first.as_word() == Some(keyword) && matches!(second.value, Value::Dimensions(_)) {
            rest = &rest[1..];
        }
    }
    if let [first, ..] = rest {
        if matches!(first.value, Value::Dimensions(_)) {
            rest = &rest[1..];
        }
    }
    match rest {
        [] => Err(CaseError::at(
            &e.key_loc,
            format!("expected {what} for '{keyword}', found nothing before ';'"),
        )),
        // An unevaluated `#calc "…"` or `#codeStream { … }`: the caller's type check then
        // says that fsim does not evaluate it, pointing at the directive.
        [item, ..] if matches!(item.value, Value::Directive(_)) => Ok(item),
        [item] => Ok(item),
        [_, extra, ..] => Err(CaseError::at(
            &extra.loc,
            format!(
                "expected ';' to end the entry '{keyword}' after its value, found {}",
                extra.describe()
            ),
        )),
    }
}

/// "expected a number for 'nu', found the word 'abc'", at the value.
pub fn wrong_type(keyword: &str, what: &str, item: &Item) -> CaseError {
    CaseError::at(
        &item.loc,
        format!("expected {what} for '{keyword}', found {}", item.describe()),
    )
}
