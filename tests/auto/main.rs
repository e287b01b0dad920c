//! `model auto` (src/auto): the candidates' table, the choice and its reason, the grid it runs
//! on, and the cases it refuses.
//!
//! One test binary per area (`cargo test --release --test auto`).

#[path = "../support/mod.rs"]
mod support;

mod choice;
