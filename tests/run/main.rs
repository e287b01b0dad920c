//! Running cases: controlDict's controls, restarts, -dry-run's plan, bad input and diverging runs.
//!
//! One test binary per area (`cargo test --release --test run`), its modules one topic each.

#[path = "../support/mod.rs"]
mod support;

mod control;
mod dry_run_plan;
mod errors;
mod failures;
mod restart;
