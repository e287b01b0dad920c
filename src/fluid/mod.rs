//! Incompressible Navier–Stokes on the uniform staggered (MAC) grid of [`crate::grid`].
//!
//! Fractional-step projection (Chorin/Temam, as in Peyret & Taylor, the paper's ref. [19]):
//! a predictor `u* = uⁿ + Δt (−∇·(uu) + ν∇²u + f)`, a pressure Poisson equation
//! `∇²p = ∇·u*/Δt`, and the correction `uⁿ⁺¹ = u* − Δt ∇p`, per stage of a low-storage
//! Runge–Kutta scheme (see [`TimeScheme`]). The Poisson equation is solved exactly (to
//! round-off) by separable real transforms: FFT in periodic directions, DCT where the pressure
//! has zero normal gradient, DST where it is fixed ([`SpectralPoisson`]).
//!
//! Velocities live in padded arrays (one ghost layer per side, [`PaddedLayout`]); pressure
//! is stored unpadded in the x-fastest layout of [`crate::grid::Grid`], as kinematic pressure
//! `p/ρ` (m²/s²).
#![allow(clippy::needless_range_loop)]

mod boundary_conditions;
mod diagnostics;
mod fluid_solver;
mod ghost_fill;
mod implicit_viscosity;
mod mean_velocity_force;
mod momentum;
mod padded_layout;
mod projection;
mod spectral_poisson;
mod time_scheme;
mod variable_poisson;

pub use boundary_conditions::{BoundaryConditions, FaceCondition};
pub use diagnostics::FluidDiagnostics;
pub use fluid_solver::{FluidSettings, FluidSolver, PredictedVelocity, StepReport};
pub use mean_velocity_force::MeanVelocityForce;
pub use padded_layout::PaddedLayout;
pub use spectral_poisson::{AxisKind, PressureBoundary, SpectralPoisson};
pub use time_scheme::TimeScheme;
pub use variable_poisson::{PcgReport, VariablePoisson};
