//! fsim: particles in a fluid at the particle scale.
//!
//! Data flows one way: case files → a validated [`case::Case`] → a simulation (grid, fluid
//! state, particles, coupling) → the time loop in [`run`] → writers in [`output`].

pub mod grid;
pub mod particles;
