//! The box the particles live in: six faces, each a wall, a rebound patch or periodic.

use super::particle_state::ParticleState;
use crate::Vec3;

/// What one face of the box does to particles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FaceCondition {
    /// Soft contact with the configured [`super::WallModel`], at the sphere surface.
    Wall,
    /// OpenFOAM's `rebound` patch interaction (`localInteraction`/`standardWallInteraction`):
    /// when the particle *centre* crosses the face (OpenFOAM tracks centres), its position is
    /// mirrored back and, with the outward normal `n` and `U_n = U·n`, `U_t = U − U_n n`:
    /// `U ← U − (1+e) U_n n` if `U_n > 0`, then `U ← U − μ U_t`.
    Rebound { e: f64, mu: f64 },
    /// Particles leaving through this face re-enter through the opposite one, and contacts act
    /// across it. The opposite face must be periodic too.
    Periodic,
}

/// An axis-aligned box `[lo, hi]` with the condition of each face in the order
/// `x−, x+, y−, y+, z−, z+` (face `2·axis + side`).
#[derive(Clone, Debug, PartialEq)]
pub struct DomainBox {
    pub lo: Vec3,
    pub hi: Vec3,
    pub faces: [FaceCondition; 6],
    /// The axes along which the case is two-dimensional (OpenFOAM's `empty` patches on both
    /// faces): particles sit on the mid-plane and move in it only, as OpenFOAM constrains
    /// parcels (`constrainToMeshCentre`, `constrainDirection`).
    pub planar: [bool; 3],
    /// The velocity of each [`FaceCondition::Wall`] face that the wall model measures contacts
    /// against (OpenFOAM's `PairCollision` takes the fluid's boundary value there: a moving
    /// wall's `fixedValue`); zero for a wall at rest.
    pub wall_velocity: [Vec3; 6],
}

impl DomainBox {
    /// A box whose six faces are all walls.
    pub fn walled(lo: impl Into<Vec3>, hi: impl Into<Vec3>) -> Self {
        Self::uniform(lo, hi, FaceCondition::Wall)
    }

    /// A box whose six faces share one condition.
    pub fn uniform(lo: impl Into<Vec3>, hi: impl Into<Vec3>, face: FaceCondition) -> Self {
        DomainBox {
            lo: lo.into(),
            hi: hi.into(),
            faces: [face; 6],
            planar: [false; 3],
            wall_velocity: [Vec3::zeros(); 6],
        }
    }

    pub fn length(&self) -> Vec3 {
        Vec3::new(
            self.hi[0] - self.lo[0],
            self.hi[1] - self.lo[1],
            self.hi[2] - self.lo[2],
        )
    }

    /// Puts the particles on the mid-plane of each [`Self::planar`] axis, with no velocity
    /// along it.
    pub fn constrain_to_plane(&self, particles: &mut ParticleState) {
        for a in (0..3).filter(|&a| self.planar[a]) {
            let centre = 0.5 * (self.lo[a] + self.hi[a]);
            for i in 0..particles.len() {
                particles.position[i][a] = centre;
                particles.velocity[i][a] = 0.0;
            }
        }
    }

    /// 1 along a free axis, 0 along a [`Self::planar`] one: the velocity's factor.
    pub(crate) fn free_axes(&self) -> Vec3 {
        Vec3::from_fn(|a, _| if self.planar[a] { 0.0 } else { 1.0 })
    }

    pub fn is_periodic(&self, axis: usize) -> bool {
        self.faces[2 * axis] == FaceCondition::Periodic
    }

    /// `1/L` on periodic axes and 0 elsewhere, so that the minimum image
    /// `d − L round(d/L)` leaves non-periodic axes untouched without a branch.
    pub(crate) fn inverse_periodic_length(&self) -> Vec3 {
        let l = self.length();
        let mut inv = Vec3::zeros();
        for a in 0..3 {
            if self.is_periodic(a) {
                inv[a] = 1.0 / l[a];
            }
        }
        inv
    }
}

/// Minimum-image separation on periodic axes (`inv_l` from `inverse_periodic_length`).
#[inline(always)]
pub(crate) fn minimum_image(d: Vec3, length: Vec3, inv_l: Vec3) -> Vec3 {
    Vec3::new(
        d[0] - length[0] * nearest_integer(d[0] * inv_l[0]),
        d[1] - length[1] * nearest_integer(d[1] * inv_l[1]),
        d[2] - length[2] * nearest_integer(d[2] * inv_l[2]),
    )
}

/// `s.round()` for the small |s| met here, by a truncating cast: `f64::round` is a libm call
/// on the baseline x86-64 target, too slow for the pair loop (docs/benchmarks/dem.md).
#[inline(always)]
fn nearest_integer(s: f64) -> f64 {
    (s + 0.5f64.copysign(s)) as i64 as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn minimum_image_wraps_only_periodic_axes() {
        let mut b = DomainBox::walled(Vec3::zeros(), [1.0, 2.0, 4.0]);
        b.faces[0] = FaceCondition::Periodic;
        b.faces[1] = FaceCondition::Periodic;
        let inv = b.inverse_periodic_length();
        assert_eq!(inv, Vec3::new(1.0, 0.0, 0.0));
        let d = minimum_image(Vec3::new(0.9, 1.9, -3.9), b.length(), inv);
        assert!((d[0] + 0.1).abs() < 1e-15);
        assert_eq!(d[1], 1.9);
        assert_eq!(d[2], -3.9);
        for s in [-2.5, -1.5, -0.7, -0.5, -0.2, 0.0, 0.3, 0.5, 0.51, 1.49, 2.5] {
            assert_eq!(nearest_integer(s), f64::round(s), "{s}");
        }
    }
}
