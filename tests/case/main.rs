//! Reading cases: the dictionary parser (corpus, properties, OpenFOAM tutorials), the typed case and its errors.
//!
//! One test binary per area (`cargo test --release --test case`), its modules one topic each.

mod errors;
mod load;
mod openfoam_examples;
mod parser_corpus;
mod parser_props;
