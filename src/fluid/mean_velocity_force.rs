//! `meanVelocityForce`: a uniform driving pressure gradient adjusted every step so that the
//! bulk velocity along one periodic direction equals a target, as OpenFOAM's fvOption does.

/// Driving of a periodic flow at a prescribed bulk velocity.
///
/// After each step the bulk (volume-mean) velocity `U_b` along `direction` is measured and
/// the driving gradient raised by `δG = relaxation (Ubar − U_b) / Δt`; the velocity is
/// corrected by `Δt δG` at once (uniform along a periodic direction, so it stays
/// divergence-free), and `G` is applied as a body force in the next step.
#[derive(Clone, Debug, PartialEq)]
pub struct MeanVelocityForce {
    /// Direction of the flow (0, 1, 2); must be periodic.
    pub direction: usize,
    /// Target bulk velocity, m/s.
    pub ubar: f64,
    /// Relaxation factor in (0, 1]; OpenFOAM's default is 1.
    pub relaxation: f64,
    /// Current driving gradient `−∂⟨p⟩/∂x_d` of the kinematic pressure, m/s².
    pub gradient: f64,
}

impl MeanVelocityForce {
    pub fn new(direction: usize, ubar: f64, relaxation: f64) -> Self {
        MeanVelocityForce {
            direction,
            ubar,
            relaxation,
            gradient: 0.0,
        }
    }

    /// Gradient increment that corrects bulk velocity `bulk` after a step of `dt`.
    pub fn increment(&self, bulk: f64, dt: f64) -> f64 {
        self.relaxation * (self.ubar - bulk) / dt
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn increment_closes_the_bulk_velocity_gap_over_one_step() {
        let drive = MeanVelocityForce::new(0, 2.0, 0.5);
        // Half the gap (relaxation 0.5) of 0.5 m/s over 0.1 s: 2.5 m/s².
        assert!((drive.increment(1.5, 0.1) - 2.5).abs() < 1e-12);
        assert_eq!(drive.gradient, 0.0);
    }
}
