//! The direct model (paper §2.1): the stress integral, porous media against exact Stokes references, walls, throats, free spheres, bad input.
//!
//! One test binary per area (`cargo test --release --test direct`), its modules one topic each.

#[path = "../support/mod.rs"]
mod support;

mod chebyshev;
mod driven_array;
mod errors;
mod motion;
mod moving;
mod porous;
mod porous_tutorial;
mod rebuild_distance;
mod stress_integral;
mod throats;
mod walls;
