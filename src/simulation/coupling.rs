//! The coupling model of a run, owning its state.

use super::direct_model::DirectModel;
use super::drag_law_model::DragLawModel;
use super::particles::Particles;
use crate::case::CouplingModel;

/// The particles and the model that couples them to the fluid.
pub enum Coupling {
    /// The fluid alone (`model none`), or beside a cloud that feels gravity and the fluid's
    /// buoyancy only.
    None { particles: Option<Box<Particles>> },
    /// Resolved spheres (paper §2.1).
    Direct(Box<DirectModel>),
    /// Unresolved particles with a drag closure (paper §2.2).
    DragLaw(Box<DragLawModel>),
}

impl Coupling {
    /// The model's name as a case gives it.
    pub fn model(&self) -> CouplingModel {
        match self {
            Coupling::None { .. } => CouplingModel::None,
            Coupling::Direct(_) => CouplingModel::Direct,
            Coupling::DragLaw(_) => CouplingModel::DragLaw,
        }
    }

    /// The particles, when there are any.
    pub fn particles(&self) -> Option<&Particles> {
        match self {
            Coupling::None { particles } => particles.as_deref(),
            Coupling::Direct(m) => Some(&m.particles),
            Coupling::DragLaw(m) => Some(&m.particles),
        }
    }

    /// The direct model, when it runs.
    pub fn direct(&self) -> Option<&DirectModel> {
        match self {
            Coupling::Direct(m) => Some(m),
            _ => None,
        }
    }

    /// The drag-law model, when it runs.
    pub fn drag_law(&self) -> Option<&DragLawModel> {
        match self {
            Coupling::DragLaw(m) => Some(m),
            _ => None,
        }
    }
}
