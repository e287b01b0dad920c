//! The drag-law model (paper §2.2): the closures' terminal velocities, Ergun and fluidized beds, the §3.3 benchmark, DPMFoam cases.
//!
//! One test binary per area (`cargo test --release --test drag_law`), its modules one topic each.

#[path = "../support/mod.rs"]
mod support;

mod benchmark;
mod case;
mod closures;
mod figures;
mod forces;
mod goldschmidt;
