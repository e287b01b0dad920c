//! The fluid solver: exact and published flows (Taylor–Green, Poiseuille, the lid-driven cavity), the time schemes, restart.
//!
//! One test binary per area (`cargo test --release --test fluid`), its modules one topic each.

#[path = "../support/mod.rs"]
mod support;

mod cavity;
mod chebyshev;
mod poiseuille;
mod restart;
mod taylor_green;
