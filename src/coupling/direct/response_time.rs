//! The step bound of the explicit coupling of free spheres.
//!
//! The hydrodynamic force reaches a free sphere one step late (`particle_motion.rs`). Over
//! a step of a sizeable fraction of the sphere's Stokes response time
//!
//! ```text
//! τ_p = ρ_p d² / (18 μ)
//! ```
//!
//! that lag turns into an oscillation of the sphere's velocity, which the fluid's own bounds
//! (Courant, viscous) do not see: in a Stokes flow they lie orders of magnitude higher.
//! fsim holds an adjustable step to [`RESPONSE_STEP_FRACTION`] of the shortest `τ_p`, below
//! the measured onset of the oscillation (docs/direct_model.md, "Known limits"; the step
//! before a write time may stretch by 1 % to land on it), and warns about a fixed step above
//! it.

pub use super::tuning::RESPONSE_STEP_FRACTION;
use crate::particles::ParticleState;

/// The shortest Stokes response time `ρ_p d²/(18 μ)` (s) over the free particles of `p` in a
/// fluid of dynamic viscosity `mu` (Pa s); infinite when every particle is fixed.
pub fn shortest_response_time(p: &ParticleState, mu: f64) -> f64 {
    (0..p.len())
        .filter(|&i| !p.fixed[i])
        .map(|i| p.density[i] * p.diameter[i] * p.diameter[i] / (18.0 * mu))
        .fold(f64::INFINITY, f64::min)
}

/// The largest step the explicit coupling of `p` takes (s):
/// [`RESPONSE_STEP_FRACTION`] of [`shortest_response_time`].
pub fn coupling_step_bound(p: &ParticleState, mu: f64) -> f64 {
    RESPONSE_STEP_FRACTION * shortest_response_time(p, mu)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shortest time over the free particles, whatever a fixed one has.
    #[test]
    fn the_lightest_smallest_free_particle_sets_the_bound() {
        let mut p = ParticleState::default();
        // (diameter, density, fixed)
        for (i, (d, rho, fixed)) in [
            (2e-3, 2000.0, false),
            (1e-3, 3000.0, false),
            (1e-4, 1000.0, true),
        ]
        .into_iter()
        .enumerate()
        {
            p.push(i as u64, [0.0; 3], d, rho);
            p.fixed[i] = fixed;
        }
        let mu = 1.0;
        // 3000 · 10⁻⁶ / 18
        let expected = 3000.0 * 1e-6 / 18.0;
        assert!((shortest_response_time(&p, mu) / expected - 1.0).abs() < 1e-12);
        assert!((coupling_step_bound(&p, mu) / (0.25 * expected) - 1.0).abs() < 1e-12);
        p.fixed.iter_mut().for_each(|f| *f = true);
        assert_eq!(coupling_step_bound(&p, mu), f64::INFINITY);
    }
}
