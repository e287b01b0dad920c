//! Everything the drag-law model needs from a case, as plain values.

use super::drag_closure::DragClosure;
use crate::case;
use crate::fluid::VolumeAveragedForm;

/// How a particle reads the grid and writes back to it (paper eq. 14–16, or DPMFoam's own).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stencil {
    /// The particle's cell only: its cell-centred value when reading (DPMFoam's `cell`
    /// interpolation, and `alphac_[p.cell()]` in its drag models); its whole volume and force
    /// into that cell when writing (DPMFoam's `theta` and `UTrans`).
    Cell,
    /// Trilinear weights of the 8 nearest samples (paper eq. 15), the same weights for
    /// reading (eq. 14) and for spreading back (eq. 16).
    Trilinear,
}

impl Stencil {
    pub fn name(self) -> &'static str {
        match self {
            Stencil::Cell => "cell",
            Stencil::Trilinear => "trilinear",
        }
    }
}

/// Settings of the drag-law model.
#[derive(Clone, Debug, PartialEq)]
pub struct DragLawSettings {
    /// The drag closure; `None`: no drag (`particleForces` without one).
    pub closure: Option<DragClosure>,
    /// Two-way coupling (`solution.coupled`): the reaction enters the fluid.
    pub coupled: bool,
    /// OpenFOAM's `analytical` integration of the drag over a step (else `Euler`).
    pub analytical: bool,
    /// Which volume-averaged equations the fluid solves (paper's eq. 7 or DPMFoam's).
    pub form: VolumeAveragedForm,
    /// Fluid velocity and pressure gradient at a particle.
    pub interpolation: Stencil,
    /// Particle volume → ε, ε at a particle, and the reaction force → fluid.
    pub averaging: Stencil,
    /// DPMFoam's `sourceTerms { schemes { U semiImplicit 1; } }`: the drag's reaction is
    /// implicit in the fluid velocity (else explicit).
    pub semi_implicit: bool,
    /// Largest particle volume fraction (DPMFoam's `alphaMax`): ε below `1 − alphaMax` stops
    /// the run.
    pub alpha_max: f64,
    /// Fluid density, kg/m³.
    pub rho: f64,
    /// Kinematic viscosity, m²/s.
    pub nu: f64,
    /// Gravity acting on the fluid, m/s².
    pub gravity: [f64; 3],
}

impl DragLawSettings {
    /// The paper's choices: its closure and eq. 7, trilinear transfer both ways, explicit
    /// source, `alphaMax` 0.99 (fluid and gravity given).
    pub fn paper(rho: f64, nu: f64, gravity: [f64; 3]) -> Self {
        DragLawSettings {
            closure: Some(DragClosure::Paper),
            coupled: true,
            analytical: false,
            form: VolumeAveragedForm::Paper,
            interpolation: Stencil::Trilinear,
            averaging: Stencil::Trilinear,
            semi_implicit: false,
            alpha_max: 0.99,
            rho,
            nu,
            gravity,
        }
    }

    /// Dynamic viscosity `μ = ρ ν`.
    pub fn mu(&self) -> f64 {
        self.rho * self.nu
    }
}

impl DragLawSettings {
    /// The settings of a case (read by [`case::DragLawSettings`]), with the fluid's density,
    /// viscosity and gravity. The form follows `particleForces`: with `pressureGradient` the
    /// particles feel the pressure gradient, so the fluid solves the paper's eq. 7; without it
    /// DPMFoam's form (whose `gravity` force carries the buoyancy).
    pub fn from_case(
        read: &case::DragLawSettings,
        rho: f64,
        nu: f64,
        gravity: [f64; 3],
    ) -> Result<Self, String> {
        let closure = match read.drag {
            Some(model) => Some(DragClosure::from_name(model.keyword(), "particleForces")?),
            None => None,
        };
        Ok(DragLawSettings {
            closure,
            coupled: read.coupled,
            analytical: read.integration == case::ParticleIntegration::Analytical,
            form: if read.pressure_gradient {
                VolumeAveragedForm::Paper
            } else {
                VolumeAveragedForm::DpmFoam
            },
            interpolation: match read.velocity_interpolation {
                case::Interpolation::Cell => Stencil::Cell,
                // cellPoint interpolates linearly on a tetrahedral decomposition of the cell;
                // on uniform hexahedra the trilinear stencil is its counterpart.
                case::Interpolation::CellPoint | case::Interpolation::Trilinear => {
                    Stencil::Trilinear
                }
            },
            averaging: match read.void_fraction {
                case::VoidFraction::Cell => Stencil::Cell,
                case::VoidFraction::Trilinear => Stencil::Trilinear,
            },
            semi_implicit: read.source == case::SourceTreatment::SemiImplicit,
            alpha_max: read.alpha_max,
            rho,
            nu,
            gravity,
        })
    }
}
