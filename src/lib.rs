//! fsim: particles in a fluid at the particle scale.
//!
//! Data flows one way: case files → a validated [`case::Case`] → a simulation (grid, fluid
//! state, particles, coupling) → the time loop in [`run`] → writers in [`output`].

pub mod auto;
pub mod case;
pub mod cli;
pub mod coupling;
pub mod error;
pub mod fluid;
pub mod grid;
pub mod memory;
pub mod output;
pub mod particles;
pub mod run;
pub mod run_plan;
pub mod run_signals;
pub mod simulation;
pub mod step_reporter;
pub mod time_control;

/// The one small-vector type: positions, velocities, forces, normals (nalgebra's, as rapier
/// uses it). Fields on the grid stay contiguous `Vec<f64>` per component.
pub type Vec3 = nalgebra::Vector3<f64>;
/// 3×3 matrices (the stress tensor).
pub type Mat3 = nalgebra::Matrix3<f64>;
