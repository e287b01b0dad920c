//! Case files: the OpenFOAM dictionary parser and the typed, validated case it feeds.

pub mod dictionary;
pub mod error;
pub mod parser;
pub mod source;
pub mod value;

pub use dictionary::{Dict, Directive, Entry, EntryBody, Key};
pub use error::CaseError;
pub use parser::{check_parser_invariants, parse_dict, read_dict_file};
pub use source::{Location, SourceFile};
pub use value::{Dimensions, Item, ListView, Value};
