//! Everything the drag-law model needs from a case, as plain values.

use super::drag_closure::DragClosure;
use super::fluid_forces::FluidForces;
use crate::fluid::VolumeAveragedForm;
use crate::Vec3;

/// How a particle reads the grid and writes back to it (paper eq. 14–16, or DPMFoam's own).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stencil {
    /// The particle's cell only: its cell-centred value when reading (DPMFoam's `cell`
    /// interpolation, and `alphac_[p.cell()]` in its drag models); its whole volume and force
    /// into that cell when writing (DPMFoam's `theta` and `UTrans`).
    Cell,
    /// Trilinear weights of the 8 nearest samples (paper eq. 15), the same weights for
    /// reading (paper eq. 14) and for spreading back (paper eq. 16).
    Trilinear,
}

impl Stencil {
    pub fn name(self) -> &'static str {
        match self {
            Stencil::Cell => "cell",
            Stencil::Trilinear => "trilinear",
        }
    }

    /// The stencil as a case names it for volume averaging (`averagingMethod`), for
    /// messages.
    pub fn averaging_method(self) -> &'static str {
        match self {
            Stencil::Cell => "basic (cell)",
            Stencil::Trilinear => "dual (trilinear)",
        }
    }
}

/// Settings of the drag-law model.
#[derive(Clone, Debug, PartialEq)]
pub struct DragLawSettings {
    /// The drag closure; `None`: no drag (`particleForces` without one).
    pub closure: Option<DragClosure>,
    /// OpenFOAM's `analytical` integration of the drag over a step (else `Euler`).
    pub analytical: bool,
    /// Which volume-averaged equations the fluid solves (paper eq. 7 or DPMFoam's).
    pub form: VolumeAveragedForm,
    /// Fluid velocity and pressure gradient at a particle.
    pub interpolation: Stencil,
    /// DPMFoam's `cellPoint`: the fluid velocity at a particle by
    /// [`super::CellPointInterpolation`] instead of `interpolation` (which still reads ∇p).
    pub cell_point: bool,
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
    pub gravity: Vec3,
    /// DPMFoam's pressure-gradient, virtual-mass and lift forces.
    pub forces: FluidForces,
}

impl DragLawSettings {
    /// The paper's choices: its closure and paper eq. 7, trilinear transfer both ways, explicit
    /// source, `alphaMax` 0.99 (fluid and gravity given).
    pub fn paper(rho: f64, nu: f64, gravity: Vec3) -> Self {
        DragLawSettings {
            closure: Some(DragClosure::Paper),
            analytical: false,
            form: VolumeAveragedForm::Paper,
            interpolation: Stencil::Trilinear,
            cell_point: false,
            averaging: Stencil::Trilinear,
            semi_implicit: false,
            alpha_max: 0.99,
            rho,
            nu,
            gravity,
            forces: FluidForces::default(),
        }
    }

    /// Dynamic viscosity `μ = ρ ν`.
    pub fn mu(&self) -> f64 {
        self.rho * self.nu
    }
}
