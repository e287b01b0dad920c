//! The direct model's settings (read from `constant/couplingProperties` by
//! [`crate::case::Coupling`]).

use super::stress_integral::StressIntegral;

/// Settings of `model direct;` (the `direct` sub-dictionary, `crate::case::Coupling`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DirectSettings {
    /// The stress integral: its interpolation from the case, its surface the default's.
    pub integral: StressIntegral,
    /// Hold every particle fixed (flow through a fixed array).
    pub fixed_particles: bool,
    /// Distance (cells) a sphere may move from where its forced faces were built before
    /// they are rebuilt ([`super::ImmersedBoundary::follow`]).
    pub rebuild_distance: f64,
}
