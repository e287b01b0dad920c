//! Packed number lists: the fast path for `(1 2 3 …)` and `((x y z) (x y z) …)`.
//!
//! A field of a million vectors read token by token costs a [`super::Item`] (a value and a
//! [`super::Location`]) per number. Here such a list is read straight from the bytes into one
//! `Vec<f64>`, with no allocation per element. The lexical rules are the general parser's:
//! a number is `[+-]? (digits [. digits?] | . digits) ([eE] [+-]? digits)?` and must end at a
//! word boundary (`inflow`, `nanoParticle`, `1st` are words); blanks and `//`, `/* */`
//! comments may stand between numbers.
//!
//! Anything else — a word, a macro, a count-prefixed sub-list, tuples of unequal width, an
//! unclosed list — makes [`scan`] give up, and the general grammar reads the list again and
//! reports any error at its exact place. The position of an element is not stored: when a
//! message needs it, [`element_offset`] walks the list again.

use super::source::Element;

/// A list read by [`scan`].
pub(crate) struct Packed {
    /// 1 for a list of numbers, the tuple length for a list of tuples.
    pub width: usize,
    /// The numbers, row by row.
    pub data: Vec<f64>,
    /// Bit k set when number k was written as a label (no `.`, no exponent).
    pub labels: Vec<u64>,
    /// Bytes read, the closing `)` included.
    pub end: usize,
}

/// What the walk over a list meets, with its byte offset.
enum Event {
    /// The `(` of tuple `index`.
    Open { index: usize, at: usize },
    /// A number: element `index`, or number `component` of tuple `index`.
    Number {
        index: usize,
        component: Option<usize>,
        at: usize,
        value: f64,
        label: bool,
    },
}

/// Largest integer that an `f64` holds exactly (2^53): a longer label stays general.
const EXACT_INTEGER: i64 = 1 << 53;

/// Reads the list `text` starts with (at its `(`) when it is purely numeric; `expected` (the
/// count written before it, if any) sizes the storage once.
pub(crate) fn scan(text: &str, expected: Option<usize>) -> Option<Packed> {
    let mut data: Vec<f64> = Vec::new();
    let mut labels: Vec<u64> = Vec::new();
    let mut reserved = false;
    let (end, width) = walk(text, |event| {
        if let Event::Number {
            component,
            value,
            label,
            ..
        } = event
        {
            if !reserved {
                // Sized from the count, guessing vectors for tuples (the walk finds the width),
                // but never past the numbers the text can hold (each takes 2 bytes or more):
                // a count line of 10⁹ must not reserve gigabytes before the list is read.
                reserved = true;
                if let Some(n) = expected {
                    let guess = if component.is_some() { 3 } else { 1 };
                    data.reserve_exact(n.saturating_mul(guess).min(text.len() / 2));
                }
            }
            let k = data.len();
            if k.is_multiple_of(64) {
                labels.push(0);
            }
            if label {
                labels[k / 64] |= 1 << (k % 64);
            }
            data.push(value);
        }
        true
    })?;
    data.shrink_to_fit();
    Some(Packed {
        width,
        data,
        labels,
        end,
    })
}

/// The byte offset of element `e` of the packed list whose token starts at `offset` (its
/// `(`, or the count written before it); `offset` itself when the text no longer holds it.
pub fn element_offset(text: &str, offset: usize, e: Element) -> usize {
    let Some(tail) = text.get(offset..) else {
        return offset;
    };
    let b = tail.as_bytes();
    let mut start = 0;
    if b.first() != Some(&b'(') {
        // Past the count `N` to its `(`.
        while start < b.len() && !matches!(b[start], b'(' | b'/') && !b[start].is_ascii_whitespace()
        {
            start += 1;
        }
        match skip_blank(b, start) {
            Some(s) if b.get(s) == Some(&b'(') => start = s,
            _ => return offset,
        }
    }
    let mut found = None;
    walk(&tail[start..], |event| {
        let (index, component, at) = match event {
            Event::Open { index, at } => (index, None, at),
            Event::Number {
                index,
                component,
                at,
                ..
            } => (index, component, at),
        };
        if index == e.index && component == e.component {
            found = Some(at);
            return false;
        }
        index <= e.index
    });
    found.map_or(offset, |at| offset + start + at)
}

/// Walks the list at the start of `text`, telling `visit` each tuple and number until it
/// returns `false`. Gives the bytes read and the width when the list is purely numeric and
/// closed, `None` otherwise (or when stopped early).
fn walk(text: &str, mut visit: impl FnMut(Event) -> bool) -> Option<(usize, usize)> {
    let b = text.as_bytes();
    if b.first() != Some(&b'(') {
        return None;
    }
    let mut pos = 1;
    // 0 for a list of numbers, else the tuple width; `None` before the first element.
    let mut width: Option<usize> = None;
    let mut index = 0;
    loop {
        pos = skip_blank(b, pos)?;
        match *b.get(pos)? {
            b')' if index > 0 => return Some((pos + 1, width.unwrap_or(1).max(1))),
            b'(' => {
                if width == Some(0) {
                    return None;
                }
                if !visit(Event::Open { index, at: pos }) {
                    return None;
                }
                let mut p = pos + 1;
                let mut component = 0;
                loop {
                    p = skip_blank(b, p)?;
                    if b.get(p) == Some(&b')') {
                        p += 1;
                        break;
                    }
                    let (value, label, end) = number_at(text, p)?;
                    let event = Event::Number {
                        index,
                        component: Some(component),
                        at: p,
                        value,
                        label,
                    };
                    if !visit(event) {
                        return None;
                    }
                    component += 1;
                    p = end;
                }
                match width {
                    _ if component == 0 => return None,
                    None => width = Some(component),
                    Some(w) if w == component => {}
                    Some(_) => return None,
                }
                pos = p;
            }
            _ => {
                if width.is_some_and(|w| w > 0) {
                    return None;
                }
                width = Some(0);
                let (value, label, end) = number_at(text, pos)?;
                let event = Event::Number {
                    index,
                    component: None,
                    at: pos,
                    value,
                    label,
                };
                if !visit(event) {
                    return None;
                }
                pos = end;
            }
        }
        index += 1;
    }
}

/// Past blanks and comments from `pos`; `None` at a comment the general parser must judge
/// (an unclosed `/*`, a `//` ending in a lone carriage return).
fn skip_blank(b: &[u8], mut pos: usize) -> Option<usize> {
    loop {
        match b.get(pos) {
            Some(b' ' | b'\t' | b'\n' | b'\r') => pos += 1,
            Some(b'/') if b.get(pos + 1) == Some(&b'/') => {
                pos += 2;
                while let Some(&c) = b.get(pos) {
                    match c {
                        b'\n' => break,
                        b'\r' if b.get(pos + 1) != Some(&b'\n') => return None,
                        _ => pos += 1,
                    }
                }
            }
            Some(b'/') if b.get(pos + 1) == Some(&b'*') => {
                let body = &b[pos + 2..];
                let close = body.windows(2).position(|w| w == b"*/")?;
                pos += 2 + close + 2;
            }
            _ => return Some(pos),
        }
    }
}

/// The number at `pos`: its value, whether it is a label, and where it ends; `None` when the
/// text there is not a number ending at a boundary the packed list accepts.
fn number_at(text: &str, pos: usize) -> Option<(f64, bool, usize)> {
    let b = text.as_bytes();
    let digits = |mut q: usize| {
        while b.get(q).is_some_and(u8::is_ascii_digit) {
            q += 1;
        }
        q
    };
    let mut q = pos;
    if matches!(b.get(q), Some(b'+' | b'-')) {
        q += 1;
    }
    let int_end = digits(q);
    let mut label = true;
    q = if b.get(int_end) == Some(&b'.') {
        label = false;
        let frac_end = digits(int_end + 1);
        if int_end == q && frac_end == int_end + 1 {
            return None;
        }
        frac_end
    } else if int_end == q {
        return None;
    } else {
        int_end
    };
    if matches!(b.get(q), Some(b'e' | b'E')) {
        label = false;
        let mut e = q + 1;
        if matches!(b.get(e), Some(b'+' | b'-')) {
            e += 1;
        }
        let exp_end = digits(e);
        if exp_end == e {
            return None;
        }
        q = exp_end;
    }
    // A word boundary the list can continue from: `1(` would start a counted list and
    // `1;`, `1st` are the general parser's to judge.
    match b.get(q) {
        Some(b' ' | b'\t' | b'\n' | b'\r' | b')') => {}
        Some(b'/') if matches!(b.get(q + 1), Some(b'/' | b'*')) => {}
        _ => return None,
    }
    let word = &text[pos..q];
    let value = if label {
        let n: i64 = word.parse().ok()?;
        if !(-EXACT_INTEGER..=EXACT_INTEGER).contains(&n) {
            return None;
        }
        n as f64
    } else {
        // beyond a double's range: left to the general parser, which refuses it in place
        word.parse().ok().filter(|x: &f64| x.is_finite())?
    };
    Some((value, label, q))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scans_numbers_and_tuples_and_refuses_the_rest() {
        let p = scan("(1 -2.5e-3 1E+05 .5 5.) x", None).unwrap();
        assert_eq!(p.width, 1);
        assert_eq!(p.data, [1.0, -2.5e-3, 1e5, 0.5, 5.0]);
        assert_eq!(p.labels, [1]);
        assert_eq!(p.end, 23);
        let p = scan("( (0 0 1) // c\n (1 /* c */ 2 3) )", Some(2)).unwrap();
        assert_eq!(p.width, 3);
        assert_eq!(p.data, [0.0, 0.0, 1.0, 1.0, 2.0, 3.0]);
        for text in [
            "()",
            "(1 inflow)",
            "(1 nanoParticle)",
            "(1st)",
            "(1e)",
            "((1 2) (1 2 3))",
            "(1 (2 3))",
            "((1 2) 3)",
            "(2(1 2))",
            "(1 $a)",
            "(1 2",
            "(1 2;",
            "((1 (2)) )",
            "(9007199254740993)",
        ] {
            assert!(scan(text, None).is_none(), "{text}");
        }
    }

    #[test]
    fn top_level_positions_are_packed() {
        let d = crate::case::parse_dict(
            "FoamFile { class vectorField; }\n3\n(\n(0 0 0)\n(1 2 3)\n(4 5 6.5)\n)\n",
            "positions",
        )
        .unwrap();
        let (width, data) = d.values[0].as_numbers().unwrap();
        assert_eq!(width, 3);
        assert_eq!(data, [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.5]);
        let row = d.values[0].as_list().unwrap().get(2).unwrap();
        assert_eq!(row.to_string(), "(4 5 6.5)");
        assert_eq!(row.loc.line_col(), (6, 1));
    }

    #[test]
    fn element_offsets_are_found_again() {
        let text = "x 2\n( (1 2 3)\n  (4 5 6) );";
        let e = |index, component| Element { index, component };
        assert_eq!(element_offset(text, 2, e(1, None)), 16);
        assert_eq!(element_offset(text, 2, e(1, Some(2))), 21);
        assert_eq!(element_offset(text, 4, e(0, Some(0))), 7);
        let text = "(1 2 3)";
        assert_eq!(element_offset(text, 0, e(2, None)), 5);
    }
}
