//! What a motion pass of the DEM engine reads and writes: the half-kick and drift of one
//! particle ([`Motion`]), its contact loads ([`Gather`]) and the particle arrays it moves
//! ([`Moving`]).

use super::domain_box::{minimum_image, FaceCondition};
use super::neighbour_list::NeighbourList;
use crate::Vec3;

/// What the half-kick and the drift of one particle read, shared by the separate passes and
/// the fused gather + kick + drift pass between two sub-steps (the same arithmetic in both).
pub(super) struct Motion<'a> {
    pub(super) g: Vec3,
    pub(super) rho_f: f64,
    pub(super) h: f64,
    pub(super) half: f64,
    pub(super) lo: Vec3,
    pub(super) length: Vec3,
    pub(super) inv_l: Vec3,
    pub(super) faces: [FaceCondition; 6],
    /// [`super::DomainBox::free_axes`].
    pub(super) free: Vec3,
    pub(super) limit: f64,
    pub(super) reference: &'a [Vec3],
    pub(super) inv_m: &'a [f64],
    pub(super) inv_i: &'a [f64],
    pub(super) rho: &'a [f64],
    pub(super) fe: &'a [Vec3],
    pub(super) te: &'a [Vec3],
}

impl<'a> Motion<'a> {
    /// `1 − ρ_f/ρ_p` (no division per particle in vacuum, the usual pure-DEM case).
    #[inline(always)]
    pub(super) fn buoyancy(&self, i: usize) -> f64 {
        if self.rho_f == 0.0 {
            1.0
        } else {
            1.0 - self.rho_f / self.rho[i]
        }
    }

    /// `v += h/2 ((f + f_ext)/m + g (1 − ρ_f/ρ_p))`, `ω += h/2 (t + t_ext)/I` (free particles).
    #[inline(always)]
    pub(super) fn half_kick(&self, i: usize, f: Vec3, t: Vec3, v: &mut Vec3, w: &mut Vec3) {
        let buoy = self.buoyancy(i);
        let (inv_m, inv_i) = (self.inv_m[i], self.inv_i[i]);
        // plain arrays in the hot loop (docs/numerics.md, "Libraries")
        let (v, w): (&mut [f64; 3], &mut [f64; 3]) = (v.as_mut(), w.as_mut());
        let (f, t, fe, te): (&[f64; 3], &[f64; 3], &[f64; 3], &[f64; 3]) = (
            f.as_ref(),
            t.as_ref(),
            self.fe[i].as_ref(),
            self.te[i].as_ref(),
        );
        let (g, free): (&[f64; 3], &[f64; 3]) = (self.g.as_ref(), self.free.as_ref());
        for a in 0..3 {
            // times 1 (exact) along a free axis, 0 along a two-dimensional case's empty one
            v[a] = (v[a] + self.half * ((f[a] + fe[a]) * inv_m + g[a] * buoy)) * free[a];
            w[a] += self.half * (t[a] + te[a]) * inv_i;
        }
    }

    /// The first half-kick with contact loads `f`, `t`, the drift, the periodic wrap and the
    /// rebound faces of a free particle; whether it moved more than half the skin since the
    /// last list build.
    #[inline(always)]
    pub(super) fn kick_drift(
        &self,
        i: usize,
        f: Vec3,
        t: Vec3,
        x: &mut Vec3,
        v: &mut Vec3,
        w: &mut Vec3,
    ) -> bool {
        if self.inv_m[i] == 0.0 {
            return false;
        }
        self.half_kick(i, f, t, v, w);
        let x: &mut [f64; 3] = x.as_mut();
        for a in 0..3 {
            x[a] += self.h * v[a];
        }
        let (lo, length, faces) = (self.lo, self.length, self.faces);
        for a in 0..3 {
            match faces[2 * a] {
                FaceCondition::Periodic => {
                    let s = ((x[a] - lo[a]) / length[a]).floor();
                    if s != 0.0 {
                        x[a] -= s * length[a];
                    }
                }
                _ => {
                    for side in 0..2 {
                        if let FaceCondition::Rebound { e, mu } = faces[2 * a + side] {
                            let plane = if side == 0 { lo[a] } else { lo[a] + length[a] };
                            let outside = if side == 0 {
                                x[a] < plane
                            } else {
                                x[a] > plane
                            };
                            if outside {
                                x[a] = 2.0 * plane - x[a];
                                rebound(v, a, side, e, mu);
                            }
                        }
                    }
                }
            }
        }
        let r = self.reference[i];
        let d = minimum_image(
            Vec3::new(x[0] - r[0], x[1] - r[1], x[2] - r[2]),
            length,
            self.inv_l,
        );
        d.dot(&d) > self.limit
    }
}

/// What a particle's contact loads are gathered from: its block's sums, the far pairs' load
/// records and its wall contacts.
pub(super) struct Gather<'a> {
    pub(super) own: &'a [[f64; 6]],
    pub(super) prev: &'a [[f64; 6]],
    pub(super) lists: &'a NeighbourList,
    pub(super) radius: &'a [f64],
}

impl<'a> Gather<'a> {
    /// Force and torque on particle `i`: own rows (+), reverse rows (−) and walls.
    #[inline(always)]
    pub(super) fn loads(&self, i: usize) -> (Vec3, Vec3) {
        let lists = self.lists;
        let (a, b) = (self.own[i], self.prev[i]);
        // plain arrays in the hot loop (docs/numerics.md, "Libraries")
        let mut f = [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
        let mut t = [a[3] + b[3], a[4] + b[4], a[5] + b[5]];
        for &q in
            &lists.far_rev[lists.far_rev_start[i] as usize..lists.far_rev_start[i + 1] as usize]
        {
            let l = lists.far_load[q as usize];
            for a in 0..3 {
                f[a] -= l[a];
                t[a] += l[a + 3];
            }
        }
        let r = self.radius[i];
        t = t.map(|x| x * r);
        for m in lists.wall_start[i] as usize..lists.wall_start[i + 1] as usize {
            let (wf, wt): (&[f64; 3], &[f64; 3]) =
                (lists.wall_force[m].as_ref(), lists.wall_torque[m].as_ref());
            for a in 0..3 {
                f[a] += wf[a];
                t[a] += wt[a];
            }
        }
        (f.into(), t.into())
    }
}

/// The particle arrays a motion pass writes.
pub(super) struct Moving<'a> {
    pub(super) x: &'a mut [Vec3],
    pub(super) v: &'a mut [Vec3],
    pub(super) w: &'a mut [Vec3],
    pub(super) fc: &'a mut [Vec3],
    pub(super) tc: &'a mut [Vec3],
}

/// OpenFOAM's rebound rule on face `2a + side`, outward normal `n`:
/// `U_n = U·n`, `U_t = U − U_n n`; `U ← U − (1+e) U_n n` if `U_n > 0`; `U ← U − μ U_t`.
#[inline]
fn rebound(v: &mut Vec3, a: usize, side: usize, e: f64, mu: f64) {
    let mut n = Vec3::zeros();
    n[a] = if side == 0 { -1.0 } else { 1.0 };
    let u_n = (*v).dot(&n);
    let u_t = Vec3::new(v[0] - u_n * n[0], v[1] - u_n * n[1], v[2] - u_n * n[2]);
    if u_n > 0.0 {
        for c in 0..3 {
            v[c] -= (1.0 + e) * u_n * n[c];
        }
    }
    for c in 0..3 {
        v[c] -= mu * u_t[c];
    }
}
