//! The particles (paper eq. 1): contact models against analytic impacts, runs with a cloud, DPMFoam clouds.
//!
//! One test binary per area (`cargo test --release --test particles`), its modules one topic each.

#[path = "../support/mod.rs"]
mod support;

mod dpmfoam_cloud;
mod run;
mod validation;
