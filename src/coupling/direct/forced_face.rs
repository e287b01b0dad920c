//! The forced faces of the direct forcing, as the fluid step imposes them, and the labels
//! that mark them on the grid ([`super::ImmersedBoundary`] builds and imposes them).

use super::tuning::THROAT_RELAXATION_GAIN;

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

/// A forcing face in a throat: its first face out along the line is inside a sphere, or
/// forced with the face after it inside one (the walls less than about two cells apart), so
/// no fluid face lies between them and the stencil falls back to the staircase. Rigid, such
/// a face closes the throat to the flow (the dense arrays' K +39 % at gaps of 1.2 cells).
/// Instead it takes the lubrication profile between the two walls: linear between their
/// velocities (Couette), plus the flow the pressure drives along the gap (Poiseuille),
/// averaged over the face's patch across the gap so that the face carries the flux through
/// it:
///
/// ```text
///   u_f = w + (δ / (δ + s)) (w_s − w) + (k / ν) (b − ∂_c p),
///   k = (1 − n_c²) / (2h) ∫ (y + a)(b' − y) dy over y ∈ [max(−h/2, −a), min(h/2, b')]
/// ```
///
/// with `δ`, `s` the distances along the line to the own and the far wall, `a`, `b'` the
/// distances from the face to the two surfaces, `n` the gap's normal (the line of centres),
/// `b` the body force and `p` the kinematic pressure of the last projection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThroatFace {
    /// The face's index in its component's forcing list.
    pub face: u32,
    /// The sphere the line enters beyond the throat.
    pub sphere: u32,
    /// Distance `s` from the face along the line, away from its own sphere, to that
    /// sphere's surface, m.
    pub distance: f64,
    /// `δ / (δ + s)`.
    pub share: f64,
    /// `k`, m².
    pub darcy: f64,
    /// Rigid velocity (this component) of that sphere where the line enters it, m/s.
    pub wall: f64,
    /// The face's value for the coming stage; carried through a build while the face stays
    /// in a throat, NaN for a face new to them until its first stage.
    pub target: f64,
}

impl ThroatFace {
    /// The pressure a face reads is the last projection's, so the throat and the
    /// projection form a loop whose gain is `k / (ν τ)` for a projection of weight `τ`.
    /// Where the gain would pass this value, the face relaxes toward its profile at the rate
    /// `gain · ν / k` over the time its stages span (so `EulerRKC`'s several stages per
    /// projection relax it once): the steady state is the profile's, whatever the step.
    pub const RELAXED_GAIN: f64 = THROAT_RELAXATION_GAIN;

    /// The target for stages whose span (s) times the loop's gain is `reach`: the profile
    /// for the own wall velocity `wall` and driving `drive` (body force less pressure
    /// gradient), relaxed from the last target (a face new to the throats starts from the
    /// walls' line: the relaxation is then the gap's viscous start-up, over about
    /// `k/(gain ν)`).
    pub fn relaxed(&self, wall: f64, drive: f64, nu: f64, reach: f64) -> f64 {
        let couette = wall + self.share * (self.wall - wall);
        let k = if nu > 0.0 { self.darcy / nu } else { 0.0 };
        let profile = couette + k * drive;
        let beta = if k > reach { reach / k } else { 1.0 };
        let last = if self.target.is_nan() {
            couette
        } else {
            self.target
        };
        last + beta * (profile - last)
    }

    /// Gives each of `throats` (faces of `forcing`) the target `by_slot` holds for its
    /// face's slot (sorted by slot), if any: the targets carried through a rebuild or a
    /// restart.
    pub(super) fn take_targets(
        throats: &mut [ThroatFace],
        forcing: &[ForcingFace],
        by_slot: &[(u32, f64)],
    ) {
        for t in throats {
            let slot = forcing[t.face as usize].slot;
            if let Ok(k) = by_slot.binary_search_by_key(&slot, |&(s, _)| s) {
                t.target = by_slot[k].1;
            }
        }
    }

    /// `k` for a face `gap_own` and `gap_far` from the two surfaces, on a grid of
    /// spacing `h` across the gap, for a component whose share across the gap is `normal`
    /// (`n_c`).
    pub fn darcy(gap_own: f64, gap_far: f64, normal: f64, h: f64) -> f64 {
        let (lo, hi) = ((-0.5 * h).max(-gap_own), (0.5 * h).min(gap_far));
        let primitive =
            |y: f64| -y * y * y / 3.0 + 0.5 * (gap_far - gap_own) * y * y + gap_own * gap_far * y;
        let integral = (primitive(hi) - primitive(lo)).max(0.0);
        (1.0 - normal * normal) * integral / (2.0 * h)
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

/// A cell all of whose six faces are forced (a driven throat's face is not: its flux answers
/// the pressure), or that no path of free faces joins to the open fluid: its divergence is
/// set by the forcing, not by the projection (it gets a mass source).
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
/// Label of a forcing face in a throat whose flow the pressure drives, set once the build's
/// searches are done: such a face does not close a cell (its flux answers the pressure, so
/// continuity holds there; [`ThroatFace`]).
pub(super) const THROAT: u32 = u32::MAX - 1;

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

    fn throat(share: f64, darcy: f64, wall: f64) -> ThroatFace {
        ThroatFace {
            face: 0,
            sphere: 1,
            distance: 0.5,
            share,
            darcy,
            wall,
            target: f64::NAN,
        }
    }

    #[test]
    fn a_throat_face_carries_the_lubrication_flux_through_its_patch() {
        let mut rng = crate::particles::SplitMix64::new(29);
        let h = 0.41;
        for _ in 0..200 {
            let (a, b) = (2.0 * h * rng.next_f64(), 2.0 * h * rng.next_f64());
            let normal = 2.0 * rng.next_f64() - 1.0;
            // Midpoint rule over the patch [−h/2, h/2], the profile zero inside the walls.
            let m = 20_000;
            let integral: f64 = (0..m)
                .map(|i| -0.5 * h + (i as f64 + 0.5) * h / m as f64)
                .map(|y| {
                    if y > -a && y < b {
                        (y + a) * (b - y)
                    } else {
                        0.0
                    }
                })
                .sum::<f64>()
                * h
                / m as f64;
            let expected = (1.0 - normal * normal) * integral / (2.0 * h);
            let k = ThroatFace::darcy(a, b, normal, h);
            assert!(
                (k - expected).abs() < 1e-6 * h * h,
                "a {a}, b {b}: {k} vs {expected}"
            );
        }
        // A gap inside the patch: Poiseuille's flux (a + b)³/12 over the face's width h.
        let (a, b) = (0.1 * h, 0.3 * h);
        let k = ThroatFace::darcy(a, b, 0.0, h);
        assert!((k - (a + b).powi(3) / (12.0 * h)).abs() < 1e-15);
        // Across the gap (along the line of centres) the pressure drives nothing.
        assert_eq!(ThroatFace::darcy(a, b, 1.0, h), 0.0);
    }

    #[test]
    fn a_throat_face_relaxes_to_its_profile_at_a_bounded_gain() {
        let (wall, far, nu, drive) = (0.2, -0.4, 1e-3, 3.0);
        let mut t = throat(0.25, 2e-5, far);
        let couette = wall + 0.25 * (far - wall);
        let profile = couette + 2e-5 / nu * drive;
        // A face new to the throats starts from the walls' line; a step long enough moves it
        // to the profile at once.
        let tau = 1.0;
        let reach = ThroatFace::RELAXED_GAIN * tau;
        assert!((t.relaxed(wall, drive, nu, reach) - profile).abs() < 1e-15);
        // A short step moves it by ½ ν τ / k of the way, toward the same profile.
        let tau = 1e-3;
        let reach = ThroatFace::RELAXED_GAIN * tau;
        let beta = reach * nu / 2e-5;
        let first = t.relaxed(wall, drive, nu, reach);
        assert!((first - (couette + beta * (profile - couette))).abs() < 1e-15);
        t.target = first;
        for _ in 0..2000 {
            t.target = t.relaxed(wall, drive, nu, reach);
        }
        assert!((t.target - profile).abs() < 1e-9 * profile.abs());
        // Rigid throats (ν = 0): the walls' line.
        assert_eq!(
            throat(0.25, 2e-5, far).relaxed(wall, drive, 0.0, tau),
            couette
        );
    }
}
