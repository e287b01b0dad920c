//! Resolved coupling (paper §2.1): declares and re-exports the direct model's parts.
//!
//! - [`RigidSphere`]: a particle as the fluid sees it, `v = v_p + ω_p × (x − x_p)`;
//! - [`ImmersedBoundary`]: no-slip on every sphere on the MAC grid (sharp-interface direct
//!   forcing, imposed in [`crate::fluid::FluidSolver::step_with`]'s hook);
//! - [`stress_integral_force`] with [`StressIntegral`], [`SphereQuadrature`], a
//!   [`FieldSampler`] ([`FieldView`] of the whole grid, [`FieldBrick`] around one sphere):
//!   force and torque from the stress tensor over a sphere split into quadrangles
//!   (paper eq. 4–6);
//! - [`DirectCoupling`] and [`DirectSettings`]: the model in a run (`model direct;`);
//! - [`ParticleMotion`]: freely moving spheres: [`Lubrication`] below the grid's reach, the
//!   periodic-settling [`SettlingDrive`], the settling monitor, and the step bound of their
//!   explicit coupling ([`coupling_step_bound`]);
//! - [`check_resolution`]: what the grid resolves (r/h, gaps), before the run.
//!
//! Method choices and measured accuracy: `docs/direct_model.md`. (The steady solver of the
//! porous-media validation lives with the tests: `tests/support/steady_stokes.rs`.)

// Hot loops are plain indexed loops over contiguous arrays, by design (as in `fluid`).
#![allow(clippy::needless_range_loop)]

mod close_pairs;
mod component_update;
mod direct_coupling;
mod direct_settings;
mod face_lattice;
mod field_brick;
mod field_sampler;
mod field_view;
mod forced_face;
mod immersed_boundary;
mod lubrication;
mod particle_motion;
mod resolution_check;
mod response_time;
mod rigid_sphere;
mod settling_drive;
mod sphere_quadrature;
mod stress_integral;
mod tuning;

pub use close_pairs::{ClosePairs, PeriodicBox};
pub use direct_coupling::{wall_interpolation, wall_surface_offset, DirectCoupling};
pub use direct_settings::DirectSettings;
pub use field_brick::FieldBrick;
pub use field_sampler::{FieldSampler, Interpolation};
pub use field_view::{periodic_directions, FieldView};
pub use forced_face::{ClosedCell, ForcingFace, GapFace, InteriorFace, ThroatFace};
pub use immersed_boundary::ImmersedBoundary;
pub use lubrication::{Lubrication, LubricationBox, LubricationReport};
pub use particle_motion::{
    MotionSettings, ParticleMotion, SedimentationReport, DEFAULT_VIRTUAL_MASS, MIN_DENSITY_RATIO,
};
pub use resolution_check::{
    check_resolution, ResolutionReport, MIN_CELLS_PER_RADIUS, RESOLVED_GAP_CELLS,
};
pub use response_time::{coupling_step_bound, shortest_response_time, RESPONSE_STEP_FRACTION};
pub use rigid_sphere::RigidSphere;
pub use settling_drive::{fluid_mean_velocity, mixture_momentum, SettlingDrive};
pub use sphere_quadrature::{SphereQuadrature, SphereQuadratureFamily};
pub use stress_integral::{
    shell_momentum, stress_integral_force, HydrodynamicLoad, ShellMomentum, StressIntegral,
};
pub use tuning::MAX_REBUILD_DISTANCE;
