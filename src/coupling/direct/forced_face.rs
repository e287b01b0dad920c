//! The forced faces of the direct forcing, as the fluid step imposes them, and the labels
//! that mark them on the grid ([`super::ImmersedBoundary`] builds and imposes them).

/// A face inside a sphere: it moves with the sphere. Indices are `u32` (a grid has fewer
/// than 2³² slots, checked in
/// [`ImmersedBoundary::new`](super::ImmersedBoundary::new)): the lists are rebuilt every step
/// and are the direct model's largest after the fields (24 bytes a face instead of 40).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InteriorFace {
    /// Padded index of the face.
    pub slot: u32,
    /// Cell-centred (unpadded) indices of the cells below and above the face along its
    /// component, for the pressure compensation.
    pub cells: [u32; 2],
    /// Rigid velocity (this component) at the face, m/s.
    pub target: f64,
    /// Index of the sphere the face is in (fills the padding: the face stays 24 bytes).
    pub sphere: u32,
}

/// A fluid face next to a sphere: `u = w + Σ_k a_k (u_k − w)` over the next one or two
/// fluid faces `k` along the interpolation line. Indices as in [`InteriorFace`] (64 bytes a
/// face instead of 96).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForcingFace {
    pub slot: u32,
    pub cells: [u32; 2],
    /// The next two fluid faces along the interpolation line, away from the sphere (the
    /// second equals the first for the linear stencil).
    pub neighbours: [u32; 2],
    pub neighbour_cells: [[u32; 2]; 2],
    /// Interpolation weights: linear `[δ/(δ+h), 0]`, quadratic
    /// `[2δ/(δ+h), −δ/(δ+2h)]`, a gap's `[L₁, 0]` ([`GapFace`]); `[0, 0]` for the staircase
    /// fallback.
    pub weights: [f64; 2],
    /// Rigid velocity (this component) where the line crosses the surface, m/s.
    pub wall: f64,
    /// The sphere the line crosses and the line's direction from the face, packed by
    /// `ForcingLine` (fills the padding: the face stays 64 bytes).
    pub line: u32,
}

/// A forcing face in a gap: beyond its fluid face `f₁` the next face is forced and the one
/// after lies inside a sphere (the same or another), so the quadratic stencil has no second
/// fluid face. Instead of falling back to linear, the face takes the quadratic through its
/// own wall (at `−δ` along the line), `f₁` (at `h`) and the far wall (at `s`, where the line
/// enters the other sphere):
///
/// ```text
///   u_f = L_w w + L₁ u₁ + L_s w_s,   L₁ = δ s / ((h + δ)(s − h)),   L_s = −δ h / ((s + δ)(s − h))
/// ```
///
/// exact for the parabolic profile of flow through a narrow gap, where the linear stencil
/// sets the face too slow (it over-resists the gap). The face keeps `L₁` as its stencil
/// weight; this adds `L_s (w_s − w)` after it. `s − h` is at least `h` (the far wall lies
/// beyond the forced face `f₂`), so the weights stay bounded: `0 ≤ L₁ ≤ 1`, `−⅓ ≤ L_s ≤ 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GapFace {
    /// The face's index in its component's forcing list.
    pub face: u32,
    /// The sphere the line enters beyond the gap.
    pub sphere: u32,
    /// Distance `s` from the face along the line, away from its own sphere, to that
    /// sphere's surface, m.
    pub distance: f64,
    /// `L_s`.
    pub weight: f64,
    /// Rigid velocity (this component) of that sphere where the line enters it, m/s.
    pub wall: f64,
}

impl GapFace {
    /// `(L₁, L_s)` for a face at `delta` from its own wall and `distance` from the far one,
    /// on a line of spacing `h`.
    pub(super) fn weights(delta: f64, distance: f64, h: f64) -> (f64, f64) {
        let beyond = distance - h;
        (
            delta * distance / ((h + delta) * beyond),
            -delta * h / ((distance + delta) * beyond),
        )
    }
}

/// The interpolation line of a [`ForcingFace`]: the sphere it crosses and its direction
/// from the face towards the sphere, `e_d · step`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ForcingLine {
    pub sphere: usize,
    pub d: usize,
    /// −1 or +1.
    pub step: isize,
}

impl ForcingLine {
    /// Spheres a packed line can name (three bits hold the direction).
    pub(super) const MAX_SPHERES: usize = 1 << 29;

    pub(super) fn pack(self) -> u32 {
        ((self.sphere as u32) << 3) | (2 * self.d as u32) | u32::from(self.step > 0)
    }

    pub fn unpack(packed: u32) -> Self {
        ForcingLine {
            sphere: (packed >> 3) as usize,
            d: ((packed & 7) / 2) as usize,
            step: if packed & 1 == 1 { 1 } else { -1 },
        }
    }
}

/// A cell all of whose six faces are forced: its divergence is set by the forcing, not by
/// the projection (it gets a mass source).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosedCell {
    /// Unpadded cell index.
    pub cell: usize,
    /// Padded slots of its low and high face per component (periodic wraps resolved).
    pub faces: [[usize; 2]; 3],
}

/// Label of a face outside every sphere.
pub(super) const FLUID: u32 = 0;
/// Label of a forcing face (inside faces hold `sphere index + 1`).
pub(super) const FORCING: u32 = u32::MAX;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gap_weights_are_the_quadratic_through_both_walls_and_the_fluid_face() {
        let mut rng = crate::particles::SplitMix64::new(17);
        let h = 0.37;
        for _ in 0..200 {
            let delta = h * rng.next_f64();
            let distance = h * (2.0 + rng.next_f64());
            let (fluid, far) = GapFace::weights(delta, distance, h);
            let own = 1.0 - fluid - far;
            let [a, b, c] = [0; 3].map(|_| 2.0 * rng.next_f64() - 1.0);
            let q = |s: f64| a + b * s + c * s * s;
            let value = own * q(-delta) + fluid * q(h) + far * q(distance);
            assert!((value - q(0.0)).abs() < 1e-12, "δ {delta}, s {distance}");
            assert!((0.0..=1.0).contains(&fluid) && (-1.0 / 3.0..=0.0).contains(&far));
        }
        // On its own wall the face is the wall's.
        assert_eq!(GapFace::weights(0.0, 2.5 * h, h), (0.0, -0.0));
    }
}
