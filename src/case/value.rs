//! The token tree of an entry's value: what stands between a keyword and its `;`.
//!
//! `internalField uniform (0 0 0);` is the stream `[Word("uniform"), List([0, 0, 0])]`.
//! Every token keeps the [`Location`] it was read at (for a macro, where the macro's value was
//! written), so that a type error can point at it. A list of plain numbers or of equal-width
//! number tuples (a field of a million vectors) is held packed, [`Value::Numbers`]: one
//! `f64` per number and one [`Location`] for the whole list; an element's own position is
//! found again by rescanning the text when a message needs it.

use std::borrow::Cow;
use std::fmt;

use super::dictionary::Dict;
use super::quote::quote;
use super::source::Location;

/// One token of a value, with where it was read.
#[derive(Clone, Debug)]
pub struct Item {
    pub value: Value,
    pub loc: Location,
}

/// The kinds of token an OpenFOAM value is made of.
#[derive(Clone, Debug)]
pub enum Value {
    /// A bare word: `uniform`, `List<vector>`, `div(phi,U)`, `on`, `inflow`.
    Word(String),
    /// A double-quoted string, unescaped.
    Str(String),
    /// A number written without a decimal point or exponent.
    Label(i64),
    /// Any other number.
    Scalar(f64),
    /// `( … )`, plain or count-prefixed (`3(…)`: the count is checked and dropped).
    List(Vec<Item>),
    /// A list whose elements are all numbers (`width` 1) or all `( … )` tuples of `width`
    /// numbers (3 for vectors), packed row by row. `labels` has bit k set when number k was
    /// written as a label (no `.`, no exponent), so that elements read back exactly as the
    /// general [`Value::List`] would give them.
    Numbers {
        width: usize,
        data: Vec<f64>,
        labels: Vec<u64>,
    },
    /// `N{value}`: `count` copies of one value, kept unexpanded.
    UniformList(usize, Box<Item>),
    /// `[0 1 -1 0 0 0 0]` or a named form such as `[m/s]`.
    Dimensions(Dimensions),
    /// `{ … }` inside a value (a list of dictionaries, `#codeStream { … }`).
    Dict(Box<Dict>),
    /// A verbatim code block `#{ … #}`, kept as text and never run.
    Code(String),
    /// A `#name` directive inside a value (`#calc`, `#codeStream`), kept, never evaluated.
    Directive(String),
}

/// A dimension set.
#[derive(Clone, Debug, PartialEq)]
pub enum Dimensions {
    /// Exponents of kg, m, s, K, mol, A, cd (5 or 7 of them).
    Exponents(Vec<f64>),
    /// A unit written by name, such as `m/s`, kept as written.
    Named(String),
}

/// The elements of a list token, without expanding a uniform list.
#[derive(Clone, Copy, Debug)]
pub enum ListView<'a> {
    Items(&'a [Item]),
    Repeat(usize, &'a Item),
    /// A [`Value::Numbers`] list read at `loc`: an element is built when asked for.
    Packed {
        width: usize,
        data: &'a [f64],
        labels: &'a [u64],
        loc: &'a Location,
    },
}

/// Whether bit `k` of a label bit set is on.
pub fn label_bit(labels: &[u64], k: usize) -> bool {
    labels.get(k / 64).is_some_and(|w| w >> (k % 64) & 1 == 1)
}

/// The token for number `k` of a packed list.
fn packed_number(data: &[f64], labels: &[u64], k: usize) -> Value {
    if label_bit(labels, k) {
        Value::Label(data[k] as i64)
    } else {
        Value::Scalar(data[k])
    }
}

impl<'a> ListView<'a> {
    pub fn len(&self) -> usize {
        match self {
            ListView::Items(items) => items.len(),
            ListView::Repeat(n, _) => *n,
            ListView::Packed { width, data, .. } => data.len() / width,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Element `i`: borrowed from the list, or built for a packed one (a number, or a
    /// packed tuple), located at its place in the text.
    pub fn get(&self, i: usize) -> Option<Cow<'a, Item>> {
        match *self {
            ListView::Items(items) => items.get(i).map(Cow::Borrowed),
            ListView::Repeat(n, item) => (i < n).then_some(Cow::Borrowed(item)),
            ListView::Packed {
                width,
                data,
                labels,
                loc,
            } => {
                if i >= data.len() / width {
                    return None;
                }
                let value = if width == 1 {
                    packed_number(data, labels, i)
                } else {
                    let row = i * width..(i + 1) * width;
                    let mut row_labels = vec![0u64; width.div_ceil(64)];
                    for (c, k) in row.clone().enumerate() {
                        if label_bit(labels, k) {
                            row_labels[c / 64] |= 1 << (c % 64);
                        }
                    }
                    Value::Numbers {
                        width: 1,
                        data: data[row].to_vec(),
                        labels: row_labels,
                    }
                };
                Some(Cow::Owned(Item::new(value, loc.child(i))))
            }
        }
    }

    /// The numbers of element `i` when it is a number or a tuple of numbers, without building
    /// a token: the fast way through a packed list.
    pub fn numbers(&self, i: usize) -> Option<Cow<'a, [f64]>> {
        match *self {
            ListView::Packed { width, data, .. } => {
                data.get(i * width..(i + 1) * width).map(Cow::Borrowed)
            }
            _ => {
                let item = self.get(i)?;
                if let Some(x) = item.as_scalar() {
                    return Some(Cow::Owned(vec![x]));
                }
                let list = item.as_list()?;
                let row: Option<Vec<f64>> = list.iter().map(|x| x.as_scalar()).collect();
                row.map(Cow::Owned)
            }
        }
    }

    pub fn iter(&self) -> impl Iterator<Item = Cow<'a, Item>> + 'a {
        let view = *self;
        (0..view.len()).map(move |i| view.get(i).expect("index below len"))
    }
}

impl Item {
    pub fn new(value: Value, loc: Location) -> Self {
        Item { value, loc }
    }

    /// The number, for a label or a scalar.
    pub fn as_scalar(&self) -> Option<f64> {
        match self.value {
            Value::Label(n) => Some(n as f64),
            Value::Scalar(x) => Some(x),
            _ => None,
        }
    }

    /// The integer, for a label.
    pub fn as_label(&self) -> Option<i64> {
        match self.value {
            Value::Label(n) => Some(n),
            _ => None,
        }
    }

    /// The text of a bare word.
    pub fn as_word(&self) -> Option<&str> {
        match &self.value {
            Value::Word(w) => Some(w),
            _ => None,
        }
    }

    /// The elements of a list (plain or uniform).
    pub fn as_list(&self) -> Option<ListView<'_>> {
        match &self.value {
            Value::List(items) => Some(ListView::Items(items)),
            Value::UniformList(n, item) => Some(ListView::Repeat(*n, item)),
            Value::Numbers {
                width,
                data,
                labels,
            } => Some(ListView::Packed {
                width: *width,
                data,
                labels,
                loc: &self.loc,
            }),
            _ => None,
        }
    }

    /// A packed number list as `(width, numbers)`, row by row: the way to read a large field
    /// or position list without a token per number (`None` for any other token, including a
    /// list the parser could not pack; [`ListView::numbers`] reads those row by row).
    pub fn as_numbers(&self) -> Option<(usize, &[f64])> {
        match &self.value {
            Value::Numbers { width, data, .. } => Some((*width, data)),
            _ => None,
        }
    }

    /// A list of exactly three numbers.
    pub fn as_vector(&self) -> Option<[f64; 3]> {
        if let Value::Numbers { width: 1, data, .. } = &self.value {
            return <[f64; 3]>::try_from(data.as_slice()).ok();
        }
        let list = self.as_list()?;
        if list.len() != 3 {
            return None;
        }
        let mut v = [0.0; 3];
        for (slot, item) in v.iter_mut().zip(list.iter()) {
            *slot = item.as_scalar()?;
        }
        Some(v)
    }

    /// OpenFOAM's `Switch` words: `on/off`, `yes/no`, `true/false`, `y/n`, `t/f`, `none`.
    pub fn as_bool(&self) -> Option<bool> {
        match self.as_word()? {
            "on" | "yes" | "true" | "y" | "t" => Some(true),
            "off" | "no" | "false" | "n" | "f" | "none" => Some(false),
            _ => None,
        }
    }

    /// The dictionary inside a `{ … }` token.
    pub fn as_dict(&self) -> Option<&Dict> {
        match &self.value {
            Value::Dict(d) => Some(d),
            _ => None,
        }
    }

    /// A short description of the token for "found …" in messages.
    pub fn describe(&self) -> String {
        match &self.value {
            Value::Word(w) => format!("the word '{}'", quote(w)),
            Value::Str(s) => format!("the string \"{}\"", quote(s)),
            Value::Label(n) => format!("the integer {n}"),
            Value::Scalar(x) => format!("the number {x}"),
            Value::List(items) => format!("a list of {} elements", items.len()),
            Value::Numbers { width, data, .. } => {
                format!("a list of {} elements", data.len() / width)
            }
            Value::UniformList(n, _) => format!("a uniform list of {n} elements"),
            Value::Dimensions(_) => "a dimension set".to_string(),
            Value::Dict(_) => "a dictionary".to_string(),
            Value::Code(_) => "a code block #{ … #}".to_string(),
            Value::Directive(d) => {
                format!("the directive '#{}' (fsim does not evaluate it)", quote(d))
            }
        }
    }
}

impl fmt::Display for Item {
    /// OpenFOAM's own spelling of the token, for messages and round trips.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.value {
            Value::Word(w) => write!(f, "{w}"),
            Value::Str(s) => write!(f, "{s:?}"),
            Value::Label(n) => write!(f, "{n}"),
            Value::Scalar(x) => write!(f, "{x:?}"),
            Value::List(items) => {
                write!(f, "(")?;
                for (i, item) in items.iter().enumerate() {
                    if i > 0 {
                        write!(f, " ")?;
                    }
                    write!(f, "{item}")?;
                }
                write!(f, ")")
            }
            Value::Numbers {
                width,
                data,
                labels,
            } => {
                write!(f, "(")?;
                for k in 0..data.len() {
                    let sep = match (k % width, *width > 1) {
                        (0, _) if k == 0 => "",
                        (0, true) => ") ",
                        (0, false) => " ",
                        _ => " ",
                    };
                    let open = if *width > 1 && k % width == 0 {
                        "("
                    } else {
                        ""
                    };
                    match packed_number(data, labels, k) {
                        Value::Label(n) => write!(f, "{sep}{open}{n}")?,
                        _ => write!(f, "{sep}{open}{:?}", data[k])?,
                    }
                }
                if *width > 1 && !data.is_empty() {
                    write!(f, ")")?;
                }
                write!(f, ")")
            }
            Value::UniformList(n, item) => write!(f, "{n}{{{item}}}"),
            Value::Dimensions(Dimensions::Exponents(e)) => {
                let parts: Vec<String> = e.iter().map(|x| x.to_string()).collect();
                write!(f, "[{}]", parts.join(" "))
            }
            Value::Dimensions(Dimensions::Named(s)) => write!(f, "[{s}]"),
            Value::Dict(_) => write!(f, "{{ … }}"),
            Value::Code(_) => write!(f, "#{{ … #}}"),
            Value::Directive(d) => write!(f, "#{d}"),
        }
    }
}
