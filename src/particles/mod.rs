//! Discrete-element (DEM) particle engine shared by both coupling models: particle state,
//! velocity-Verlet integration with collision sub-cycling, DPMFoam's Hertzian and LAMMPS'
//! linear contact models, linked-cell Verlet lists, random packings.
//!
//! A loader fills the plain types ([`ParticleState`], [`PairModel`], [`WallModel`],
//! [`DomainBox`], [`DemConfig`]); [`Dem::new`] validates them and owns the particles. Each
//! fluid step, the coupling writes the hydrodynamic loads through
//! [`Dem::external_loads_mut`] and calls [`Dem::advance`], which sub-cycles by DPMFoam's rule.
//! Particle indices change when the lists are rebuilt (cell sort); `id` names a particle.
//!
//! From a DPMFoam `constant/kinematicCloudProperties` (OpenFOAM v1912 keywords):
//!
//! | DPMFoam | fsim |
//! |---|---|
//! | `constantProperties { rho0; youngsModulus; poissonsRatio; }` | `ParticleState::density`; `PairModel::SpringSliderDashpot { youngs_modulus, poissons_ratio }` and `WallModel::SpringSliderDashpot { particle_youngs_modulus, particle_poissons_ratio }` |
//! | `pairSpringSliderDashpotCoeffs { alpha; b; mu; collisionResolutionSteps; }` | `PairModel::SpringSliderDashpot { alpha, b, mu, collision_resolution_steps, tangential: TangentialRule::DpmFoamReset }` for DPMFoam's friction |
//! | `wallSpringSliderDashpotCoeffs { youngsModulus; poissonsRatio; alpha; b; mu; collisionResolutionSteps; }` | `WallModel::SpringSliderDashpot { youngs_modulus, poissons_ratio, … }` (the wall's material) |
//! | `useEquivalentSize yes`, `cohesionEnergyDensity` ≠ 0 | not supported (a loader should stop) |
//! | `wall` patch with `collisionModel pairCollision` | `FaceCondition::Wall` |
//! | `wall` patch with `standardWallInteraction`/`localInteraction` `rebound { e; mu; }` and no collision model | `FaceCondition::Rebound { e, mu }` |
//! | `cyclic` patch pair | `FaceCondition::Periodic` on both faces |
//! | `U0` of `manualInjection` | `ParticleState::velocity` |
//!
//! The linear model has no DPMFoam counterpart; it follows LAMMPS `gran/hooke/history`
//! with the restitution coefficient instead of a damping rate.
//!
//! ```
//! use fsim::particles::*;
//! let mut p = ParticleState::default();
//! p.push(1, [0.004, 0.005, 0.005], 1e-3, 2500.0);
//! p.push(2, [0.006, 0.005, 0.005], 1e-3, 2500.0);
//! p.velocity[0] = Vec3::new(0.5, 0.0, 0.0);
//! let wall = WallModel::LinearSpringDashpot {
//!     kn: 200.0, restitution: 0.5, kt: 200.0 * 2.0 / 7.0, mu: 0.5,
//!     tangential_damping_ratio: 0.5, collision_resolution_steps: 50.0,
//! };
//! let config = DemConfig::new(PairModel::linear(200.0, 0.5, 0.5), wall);
//! let mut dem = Dem::new(config, DomainBox::walled(Vec3::zeros(), [0.01; 3]), p).unwrap();
//! for _ in 0..100 {
//!     dem.advance(1e-4); // one fluid step, several collision sub-steps
//! }
//! let (translational, rotational) = dem.kinetic_energy();
//! assert!(translational + rotational > 0.0);
//! assert!(dem.max_overlap_ratio() < 0.05);
//! ```

mod cell_grid;
mod contact_model;
mod contact_work;
mod dem;
mod dem_config;
mod dem_error;
mod domain_box;
mod motion;
mod neighbour_list;
mod particle_state;
mod random_packing;
mod snapshot_arrays;

pub use crate::Vec3;
pub use contact_model::{PairModel, TangentialRule, WallModel};
pub use dem::{sphere_volume, Dem, DemSnapshot, OverlapPartner, WorstOverlap};
pub use dem_config::DemConfig;
pub use dem_error::{DemError, FACE_NAMES};
pub use domain_box::{DomainBox, FaceCondition};
pub use neighbour_list::ContactHistory;
pub use particle_state::ParticleState;
pub use random_packing::{random_packing, random_packing_sizes, PackingError, SplitMix64};
pub use snapshot_arrays::DEM_RESTART_NAMES;
