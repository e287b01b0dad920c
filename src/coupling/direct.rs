//! Resolved coupling (paper §2.1): declares and re-exports the direct model's parts.

mod close_pairs;
mod lubrication;
mod particle_motion;
mod resolution_check;
mod settling_drive;

pub use close_pairs::{ClosePairs, PeriodicBox};
pub use lubrication::{Lubrication, LubricationBox, LubricationReport};
pub use particle_motion::{
    LubricationSettings, ParticleMotion, SedimentationReport, MIN_DENSITY_RATIO,
};
pub use resolution_check::{
    check_resolution, ResolutionReport, MIN_CELLS_PER_RADIUS, RESOLVED_GAP_CELLS,
};
pub use settling_drive::{fluid_mean_velocity, mixture_momentum, SettlingDrive};
