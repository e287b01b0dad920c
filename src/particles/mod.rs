//! Discrete-element (DEM) particle engine shared by both coupling models: particle state,
//! velocity-Verlet integration with collision sub-cycling, DPMFoam's Hertzian and LAMMPS'
//! linear contact models, linked-cell Verlet lists, random packings.

mod cell_grid;
mod contact_model;
mod dem;
mod dem_error;
mod domain_box;
mod neighbour_list;
mod particle_state;
mod random_packing;
mod vec3;

pub use contact_model::{PairModel, TangentialRule, WallModel};
pub use dem::{sphere_volume, Dem, DemConfig, DemSnapshot};
pub use dem_error::DemError;
pub use domain_box::{DomainBox, FaceCondition};
pub use neighbour_list::ContactHistory;
pub use particle_state::ParticleState;
pub use random_packing::{random_packing, PackingError, SplitMix64};
pub use vec3::Vec3;
