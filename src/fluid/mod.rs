//! Incompressible Navier–Stokes on the uniform staggered (MAC) grid of [`crate::grid`].
//!
//! Fractional-step projection (Chorin/Temam, as in Peyret & Taylor, the paper's ref. \[19\]):
//! a predictor `u* = uⁿ + Δt (−∇·(uu) + ν∇²u + f)` (paper eq. 2), a pressure Poisson equation
//! `∇²p = ∇·u*/Δt`, and the correction `uⁿ⁺¹ = u* − Δt ∇p`, once per stage of the chosen
//! [`TimeScheme`]: `Euler` (the paper's), `RK3` (default), or `EulerRKC` (diffusion by
//! Runge–Kutta–Chebyshev stages, no viscous time-step limit). Space is second order:
//! conservative central advection, 7-point diffusion. The Poisson problems are solved exactly to round-off by separable real transforms: FFT in periodic directions,
//! DCT where the pressure has zero normal gradient, DST where it is fixed
//! ([`SpectralPoisson`]). [`VariablePoisson`] solves `∇·(β∇p) = f` by conjugate gradients
//! preconditioned with the constant-coefficient spectral solve, for the drag-law model.
//!
//! Storage (see [`FluidSolver`]): velocity components on their faces in padded arrays (one
//! ghost layer per side, [`PaddedLayout`]); pressure unpadded in the x-fastest layout of
//! [`crate::grid::Grid`], as kinematic pressure `p/ρ` (m²/s²): multiply by ρ for a case whose
//! `p` is dimensional. Outlet pressures in [`FaceCondition::Outlet`] are kinematic too.
//!
//! Hooks for the coupling models: [`FluidSolver::step_with`] hands each stage's predicted
//! velocity to a closure before it is projected (the direct model imposes the particles'
//! rigid motion there; `EulerRKC` hands the components one at a time), and [`FluidSolver::face_source_mut`] holds per-face accelerations
//! (the drag-law model's reaction forces).
//!
//! A time loop uses it like this (the caller owns the rayon pool: run it inside
//! `pool.install`):
//!
//! ```
//! use fsim::fluid::{BoundaryConditions, FaceCondition, FluidSettings, FluidSolver};
//! use fsim::grid::Grid;
//!
//! let grid = Grid::new([16, 16, 1], [1.0 / 16.0; 3], [0.0; 3]);
//! let wall = FaceCondition::Wall { velocity: [0.0; 3] };
//! let lid = FaceCondition::Wall { velocity: [1.0, 0.0, 0.0] };
//! let bc = BoundaryConditions {
//!     faces: [wall.clone(), wall.clone(), wall, lid, FaceCondition::Empty, FaceCondition::Empty],
//! };
//! let mut fluid = FluidSolver::new(grid, bc, FluidSettings::new(0.01)).unwrap();
//! let mut dt = 1e-3;
//! for _ in 0..10 {
//!     dt = fluid.adaptive_dt(dt, 0.5, 0.1); // maxCo 0.5, maxDeltaT 0.1, never above the bound
//!     fluid.step(dt);
//!     let monitor = fluid.diagnostics(dt); // divergence, kinetic energy, Courant number
//!     assert!(monitor.divergence < 1e-10);
//! }
//! let mut cells = vec![[0.0; 3]; fluid.grid().cell_count()];
//! fluid.cell_velocity(&mut cells); // for output; fluid.pressure() is p/ρ at the centres
//! ```
#![allow(clippy::needless_range_loop)]

mod boundary_conditions;
mod chebyshev_diffusion;
mod chebyshev_stages;
mod coefficient_fields;
mod diagnostics;
mod fluid_solver;
mod ghost_fill;
mod mean_velocity_force;
mod momentum;
mod padded_layout;
mod projection;
mod shared_samples;
mod spectral_poisson;
mod staggered_transfer;
mod time_scheme;
mod variable_poisson;
mod volume_averaged_fluid;
mod volume_averaged_viscosity;

pub use boundary_conditions::{BoundaryConditions, FaceCondition};
pub use chebyshev_stages::{ChebyshevStage, ChebyshevStages};
pub use coefficient_fields::{comparison_beta, seeded_uniform};
pub use diagnostics::FluidDiagnostics;
pub use fluid_solver::{FluidSettings, FluidSolver, PredictedVelocity, StepReport};
#[cfg(test)]
pub(crate) use ghost_fill::fill_velocity_ghosts;
pub use mean_velocity_force::MeanVelocityForce;
pub use padded_layout::PaddedLayout;
pub(crate) use shared_samples::SharedSamples;
pub use spectral_poisson::{AxisKind, PressureBoundary, SpectralPoisson};
pub use time_scheme::TimeScheme;
pub use variable_poisson::{Convergence, PcgReport, VariablePoisson};
pub(crate) use volume_averaged_fluid::fill_cell_ghosts;
pub use volume_averaged_fluid::{VolumeAveragedFluid, VolumeAveragedForm, VolumeAveragedReport};
pub use volume_averaged_viscosity::ViscousReport;
