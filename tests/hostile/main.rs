//! Hostile cases: what a case from an untrusted source may try, each refused quickly, with
//! a bounded message, under a memory limit (docs/security.md).
//!
//! One test binary (`cargo test --release --test hostile`), one module per guarantee.

#[path = "../support/mod.rs"]
mod support;

mod memory;
mod reads;
mod writes;
