//! `$name` macros and `#calc`/`#eval` arithmetic: a macro is replaced by its value as soon as
//! it is read, seeing exactly the entries written above it in this and the enclosing scopes
//! (OpenFOAM's rule); the tokens macros may create are capped (an exponential macro is an
//! error, not an exhausted memory).

use super::{quoted, variable_name, Ctx, Src, MAX_MACRO_TOKENS};
use crate::case::dictionary::{Dict, Entry, EntryBody};
use crate::case::error::CaseError;
use crate::case::expression::{evaluate, Number};
use crate::case::source::Location;
use crate::case::value::{Item, Value};
use nom::bytes::complete::take_while1;

impl Ctx {
    /// `#calc "…"` or `#eval{ … }` (or `#eval "…"`): the number it computes when its
    /// arithmetic is within [`evaluate`]'s subset and its `$var`s are numbers; otherwise the
    /// directive and its text, kept unevaluated.
    pub(super) fn calculation<'a>(
        &mut self,
        src: &Src,
        after_name: &'a str,
        name: &str,
        loc: &Location,
    ) -> Result<(&'a str, Vec<Item>), CaseError> {
        let directive = Item::new(Value::Directive(name.to_string()), loc.clone());
        let (rest, body) = if name == "eval" && after_name.starts_with('{') {
            let Some(end) = balanced_brace_end(after_name) else {
                return Err(src.err(
                    after_name,
                    "expected '}' to close the expression opened here",
                ));
            };
            (&after_name[end + 1..], after_name[1..end].to_string())
        } else {
            let text = self.skip(src, after_name)?;
            match quoted(text) {
                Some((rest, body)) => (rest, body),
                // Not the form fsim evaluates: the tokens that follow are read as usual.
                None => return Ok((after_name, vec![directive])),
            }
        };
        let value = self
            .substitute(&body)
            .and_then(|text| evaluate(&text, name == "calc"));
        Ok(match value {
            Some(Number::Int(n)) => (rest, vec![Item::new(Value::Label(n), loc.clone())]),
            Some(Number::Real(x)) => (rest, vec![Item::new(Value::Scalar(x), loc.clone())]),
            None => {
                let code = Item::new(Value::Code(body), src.loc(after_name));
                (rest, vec![directive, code])
            }
        })
    }

    /// `text` with each `$var` (or `${var}`) replaced by the number it names, or `None` when
    /// one is undefined or not a single number.
    pub(super) fn substitute(&self, text: &str) -> Option<String> {
        let mut out = String::with_capacity(text.len());
        let mut rest = text;
        while let Some(at) = rest.find('$') {
            out.push_str(&rest[..at]);
            let after = &rest[at + 1..];
            let (tail, name) = match after.strip_prefix('{') {
                Some(braced) => {
                    let end = braced.find('}')?;
                    (&braced[end + 1..], braced[..end].trim())
                }
                None => {
                    // In arithmetic, `/` divides: it does not separate scopes here.
                    let (tail, name) = take_while1::<_, _, nom::error::Error<&str>>(|c: char| {
                        c.is_alphanumeric() || matches!(c, '_' | '.' | ':')
                    })(after)
                    .ok()?;
                    (tail, name)
                }
            };
            let entry = self.resolve(name)?;
            let number = match entry.as_tokens()? {
                [item] => match item.value {
                    Value::Label(n) => n.to_string(),
                    Value::Scalar(x) => format!("{x:?}"),
                    _ => return None,
                },
                _ => return None,
            };
            // Parenthesised so that `-$a` and `2*$a` keep their meaning for negative values.
            out.push('(');
            out.push_str(&number);
            out.push(')');
            rest = tail;
        }
        out.push_str(rest);
        Some(out)
    }

    /// `$name` in a value: the value it names, copied.
    pub(super) fn macro_value<'a>(
        &mut self,
        src: &Src,
        i: &'a str,
    ) -> Result<(&'a str, Vec<Item>), CaseError> {
        let (rest, name) = self.macro_name(src, i)?;
        let entry = self
            .resolve(&name)
            .ok_or_else(|| undefined(src, i, &name))?;
        let items = match &entry.body {
            EntryBody::Tokens(t) => t.clone(),
            EntryBody::Dict(d) => vec![Item::new(Value::Dict(Box::new(d.clone())), d.loc.clone())],
        };
        self.charge(src, i, count_items(&items))?;
        Ok((rest, items))
    }

    /// `$name` where a keyword is expected: the named dictionary's entries merged in here.
    pub(super) fn merge_macro<'a>(&mut self, src: &Src, i: &'a str) -> Result<&'a str, CaseError> {
        let (rest, name) = self.macro_name(src, i)?;
        let entry = self
            .resolve(&name)
            .ok_or_else(|| undefined(src, i, &name))?;
        let EntryBody::Dict(d) = &entry.body else {
            return Err(src.err(
                i,
                format!("expected '${name}' to name a dictionary to merge here, found a value"),
            ));
        };
        let entries: Vec<Entry> = d.entries().to_vec();
        let size = entries.iter().map(entry_size).sum();
        self.charge(src, i, size)?;
        for e in entries {
            self.current().insert(e);
        }
        let after = self.skip(src, rest)?;
        Ok(after.strip_prefix(';').unwrap_or(rest))
    }

    pub(super) fn charge(&mut self, src: &Src, i: &str, tokens: usize) -> Result<(), CaseError> {
        self.macro_tokens += tokens;
        if self.macro_tokens > MAX_MACRO_TOKENS {
            return Err(src.err(
                i,
                format!("expected macros to expand to at most {MAX_MACRO_TOKENS} tokens"),
            ));
        }
        Ok(())
    }

    /// `$name` or `${name}`.
    pub(super) fn macro_name<'a>(
        &self,
        src: &Src,
        i: &'a str,
    ) -> Result<(&'a str, String), CaseError> {
        let after = &i[1..];
        if let Some(braced) = after.strip_prefix('{') {
            if let Some(end) = braced.find('}') {
                return Ok((&braced[end + 1..], braced[..end].trim().to_string()));
            }
            return Err(src.err(i, "expected '}' to close '${'"));
        }
        match variable_name(after) {
            Ok((rest, name)) => Ok((rest, name.to_string())),
            Err(_) => Err(src.err(i, "expected a variable name after '$'")),
        }
    }

    /// Finds a macro's entry with OpenFOAM's scoping: `$a` searches this dictionary then the
    /// enclosing ones; `$..a` starts one level up (one more per extra dot); `$:a.b` starts at
    /// the top; `a.b` descends into sub-dictionary `a` unless a keyword `a.b` exists.
    pub(super) fn resolve(&self, name: &str) -> Option<Entry> {
        let depth = self.stack.len();
        if let Some(path) = name.strip_prefix(':').or_else(|| name.strip_prefix('/')) {
            return self.descend_from(0, &path.replace('/', "."));
        }
        let dots = name.chars().take_while(|&c| c == '.').count();
        if dots > 0 {
            let up = dots - 1;
            let level = depth.checked_sub(1 + up)?;
            return self.descend_from(level, &name[dots..]);
        }
        for d in self.stack.iter().rev() {
            if let Some(e) = d.lookup(name) {
                return Some(e.clone());
            }
        }
        let (head, tail) = name.split_once('.')?;
        for d in self.stack.iter().rev() {
            if let Some(e) = d.lookup(head) {
                return e.as_dict().and_then(|sub| descend(sub, tail));
            }
        }
        None
    }

    /// Follows a dotted path down from the open dictionary at `level`; the path may lead into
    /// a dictionary still being read (`geometry { r 1; c $:geometry.r; }`).
    pub(super) fn descend_from(&self, level: usize, path: &str) -> Option<Entry> {
        if let Some(e) = descend(&self.stack[level], path) {
            return Some(e);
        }
        let child = self.stack.get(level + 1)?;
        let parent = &self.stack[level].name;
        let own = child
            .name
            .strip_prefix(parent.as_str())?
            .trim_start_matches('.');
        let rest = path.strip_prefix(own)?.strip_prefix('.')?;
        self.descend_from(level + 1, rest)
    }
}

/// Byte index of the `}` closing the `{` that `i` starts with.
pub(super) fn balanced_brace_end(i: &str) -> Option<usize> {
    let mut depth = 0usize;
    for (pos, c) in i.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    return Some(pos);
                }
            }
            _ => {}
        }
    }
    None
}

/// Follows a dotted path `a.b.c` down from `dict`.
pub(super) fn descend(dict: &Dict, path: &str) -> Option<Entry> {
    if let Some(e) = dict.lookup(path) {
        return Some(e.clone());
    }
    let (head, tail) = path.split_once('.')?;
    dict.lookup(head)?.as_dict().and_then(|d| descend(d, tail))
}

pub(super) fn undefined(src: &Src, i: &str, name: &str) -> CaseError {
    src.err(
        i,
        format!(
            "undefined variable '${name}': expected it to be defined above, in this or an \
             enclosing dictionary"
        ),
    )
}

pub(super) fn count_items(items: &[Item]) -> usize {
    items
        .iter()
        .map(|item| match &item.value {
            Value::List(inner) => 1 + count_items(inner),
            Value::Numbers { data, .. } => 1 + data.len(),
            Value::Dict(d) => 1 + d.entries().iter().map(entry_size).sum::<usize>(),
            _ => 1,
        })
        .sum()
}

pub(super) fn entry_size(e: &Entry) -> usize {
    match &e.body {
        EntryBody::Tokens(t) => 1 + count_items(t),
        EntryBody::Dict(d) => 1 + d.entries().iter().map(entry_size).sum::<usize>(),
    }
}
