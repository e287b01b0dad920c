//! A sphere in rigid motion, as the direct model sees a particle.

use crate::Vec3;

/// Centre, radius and rigid-body velocity of one particle (SI units).
///
/// Every point of the sphere, and on the direct model's grid every velocity sample inside
/// it, moves with `v(x) = v_p + ω_p × (x − x_p)` (the no-slip condition of paper eq. 2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidSphere {
    /// Centre `x_p`, m.
    pub centre: Vec3,
    /// Radius, m.
    pub radius: f64,
    /// Translational velocity `v_p`, m/s.
    pub velocity: Vec3,
    /// Angular velocity `ω_p`, rad/s.
    pub angular_velocity: Vec3,
}

impl RigidSphere {
    /// A sphere at rest.
    pub fn fixed(centre: impl Into<Vec3>, radius: f64) -> Self {
        RigidSphere {
            centre: centre.into(),
            radius,
            velocity: Vec3::zeros(),
            angular_velocity: Vec3::zeros(),
        }
    }

    /// Rigid-body velocity `v_p + ω_p × (x − x_p)` at a point given relative to the centre,
    /// `rel = x − x_p` (periodic images pass their own offset).
    #[inline]
    pub fn velocity_at(&self, rel: Vec3) -> Vec3 {
        let w = self.angular_velocity;
        Vec3::new(
            self.velocity[0] + w[1] * rel[2] - w[2] * rel[1],
            self.velocity[1] + w[2] * rel[0] - w[0] * rel[2],
            self.velocity[2] + w[0] * rel[1] - w[1] * rel[0],
        )
    }

    /// Volume `4/3 π r³`.
    pub fn volume(&self) -> f64 {
        4.0 / 3.0 * std::f64::consts::PI * self.radius.powi(3)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rigid_velocity_adds_rotation() {
        let mut s = RigidSphere::fixed([1.0, 2.0, 3.0], 0.5);
        s.velocity = Vec3::new(1.0, 0.0, 0.0);
        s.angular_velocity = Vec3::new(0.0, 0.0, 2.0);
        // ω × (0, 0.5, 0) = (−1, 0, 0)
        assert_eq!(
            s.velocity_at(Vec3::new(0.0, 0.5, 0.0)),
            Vec3::new(0.0, 0.0, 0.0)
        );
        assert_eq!(
            s.velocity_at(Vec3::new(0.5, 0.0, 0.0)),
            Vec3::new(1.0, 1.0, 0.0)
        );
        assert!((s.volume() - std::f64::consts::PI / 6.0).abs() < 1e-15);
    }
}
