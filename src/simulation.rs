//! A case turned into a running simulation, and its time step.
//!
//! - [`Simulation`]: the fluid, the time axis and the [`Coupling`], built from a validated
//!   case or a restart state;
//! - [`Coupling`]: the model and the state it owns: the fluid alone (maybe beside a passive
//!   cloud), the [`DirectModel`] (paper §2.1) or the [`DragLawModel`] (§2.2), each with its
//!   [`Particles`];
//! - [`Simulation::step`] (`step.rs`): one step of each model as a short list of named
//!   phases, the paper's equation beside each;
//! - `step_size.rs`: each step's size; `restart.rs`: the restart state; `case_settings.rs`:
//!   the case read into the solvers' settings.

mod case_settings;
mod coupling;
mod direct_model;
mod drag_law_model;
mod health;
mod particles;
mod restart;
#[allow(clippy::module_inception)]
mod simulation;
mod step;
mod step_size;

pub use case_settings::{boundary_conditions, continues, interstitial_inlets};
pub use coupling::Coupling;
pub use direct_model::{DirectModel, HydrodynamicReport};
pub use drag_law_model::DragLawModel;
pub use health::MAX_OVERLAP;
pub use particles::{CloudReport, Particles};
pub use simulation::{PhaseTimes, Simulation, StepSizing};
pub use step::{step_direct, step_drag_law, step_fluid_alone, ModelStep, TakenStep};
