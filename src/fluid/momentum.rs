//! Momentum tendency on the MAC grid: conservative central advection, 7-point diffusion,
//! body force.
//!
//! For component `c` at one of its faces (paper eq. 2, Harlow & Welch's divergence form):
//!
//! `F = −Σ_d δ_d( ū_c^d ū_d^c ) + ν Σ_d δ_d² u_c + f_c + s_c`
//!
//! where along its own direction the flux `(ū_c)²` is taken at the two neighbouring cell
//! centres, and along a transverse direction `d` the flux `ū_c^d ū_d^c` at the two edges,
//! each factor the mean of the two nearest samples. This is second order, conserves momentum
//! and (for a divergence-free field) kinetic energy.

use super::padded_layout::PaddedLayout;
use rayon::prelude::*;

/// Everything fixed during one tendency evaluation.
pub(crate) struct MomentumTerms<'a> {
    pub layout: &'a PaddedLayout,
    pub h: [f64; 3],
    pub nu: f64,
    /// Uniform body force per unit mass, m/s².
    pub force: [f64; 3],
    /// Optional per-face source per component (padded layout), m/s².
    pub source: Option<&'a [Vec<f64>; 3]>,
    /// Momentum ranges `[c][d]`, inclusive padded indices.
    pub ranges: &'a [[(usize, usize); 3]; 3],
}

/// `q ← a q + Δt F(u)` on the momentum faces of every component (`a = 0` overwrites `q`).
pub(crate) fn accumulate_tendency(
    q: &mut [Vec<f64>; 3],
    u: &[Vec<f64>; 3],
    t: &MomentumTerms,
    a: f64,
    dt: f64,
) {
    for (c, qc) in q.iter_mut().enumerate() {
        accumulate_component(qc, u, t, c, a, dt);
    }
}

fn accumulate_component(
    qc: &mut [f64],
    u: &[Vec<f64>; 3],
    t: &MomentumTerms,
    c: usize,
    a: f64,
    dt: f64,
) {
    let layout = t.layout;
    let plane = layout.plane_len();
    let (d1, d2) = ((c + 1) % 3, (c + 2) % 3);
    let s = layout.stride;
    let (sc, s1, s2) = (s[c] as isize, s[d1] as isize, s[d2] as isize);
    let own = &u[c][..];
    let (v1, v2) = (&u[d1][..], &u[d2][..]);
    let inv_h = [1.0 / t.h[0], 1.0 / t.h[1], 1.0 / t.h[2]];
    let (ic, i1, i2) = (inv_h[c], inv_h[d1], inv_h[d2]);
    let inv_h2 = [
        inv_h[0] * inv_h[0],
        inv_h[1] * inv_h[1],
        inv_h[2] * inv_h[2],
    ];
    let nu = t.nu;
    let force = t.force[c];
    let source = t.source.map(|s| &s[c][..]);
    let r = t.ranges[c];
    let d0 = layout.dims[0];
    if r[0].0 > r[0].1 || r[1].0 > r[1].1 {
        return;
    }
    let len = r[0].1 - r[0].0 + 1;
    qc.par_chunks_mut(plane).enumerate().for_each(|(k, qp)| {
        if k < r[2].0 || k > r[2].1 {
            return;
        }
        for j in r[1].0..=r[1].1 {
            let row = j * d0 + r[0].0;
            let base = (k * plane + row) as isize;
            // Every stencil point as a slice of the row's length, so the inner loop runs
            // over `0..len` without bounds checks.
            let sl = |arr, off| shifted(arr, base + off, len);
            let q0 = sl(own, 0);
            let (qpc, qmc) = (sl(own, sc), sl(own, -sc));
            let (qp1, qm1) = (sl(own, s1), sl(own, -s1));
            let (qp2, qm2) = (sl(own, s2), sl(own, -s2));
            let (a1, b1, c1, e1) = (sl(v1, s1), sl(v1, s1 - sc), sl(v1, 0), sl(v1, -sc));
            let (a2, b2, c2, e2) = (sl(v2, s2), sl(v2, s2 - sc), sl(v2, 0), sl(v2, -sc));
            let src = source.map(|s| sl(s, 0));
            let out = &mut qp[row..row + len];
            let rhs = |i: usize| -> f64 {
                let q = q0[i];
                // Own direction: (ū_c)² at the two cell centres.
                let hi = 0.5 * (q + qpc[i]);
                let lo = 0.5 * (qmc[i] + q);
                // Transverse directions: ū_c ū_d at the two edges.
                let adv = (hi * hi - lo * lo) * ic
                    + 0.25 * ((q + qp1[i]) * (a1[i] + b1[i]) - (qm1[i] + q) * (c1[i] + e1[i])) * i1
                    + 0.25 * ((q + qp2[i]) * (a2[i] + b2[i]) - (qm2[i] + q) * (c2[i] + e2[i])) * i2;
                let lap = (qpc[i] - 2.0 * q + qmc[i]) * inv_h2[c]
                    + (qp1[i] - 2.0 * q + qm1[i]) * inv_h2[d1]
                    + (qp2[i] - 2.0 * q + qm2[i]) * inv_h2[d2];
                -adv + nu * lap + force
            };
            match (src, a == 0.0) {
                (None, true) => {
                    for i in 0..len {
                        out[i] = dt * rhs(i);
                    }
                }
                (None, false) => {
                    for i in 0..len {
                        out[i] = a * out[i] + dt * rhs(i);
                    }
                }
                (Some(s), true) => {
                    for i in 0..len {
                        out[i] = dt * (rhs(i) + s[i]);
                    }
                }
                (Some(s), false) => {
                    for i in 0..len {
                        out[i] = a * out[i] + dt * (rhs(i) + s[i]);
                    }
                }
            }
        }
    });
}

/// The `len` values of `arr` from `start` on.
#[inline(always)]
fn shifted(arr: &[f64], start: isize, len: usize) -> &[f64] {
    &arr[start as usize..][..len]
}

/// `u ← u + b q` on the momentum faces.
pub(crate) fn add_scaled(
    u: &mut [Vec<f64>; 3],
    q: &[Vec<f64>; 3],
    b: f64,
    layout: &PaddedLayout,
    ranges: &[[(usize, usize); 3]; 3],
) {
    let plane = layout.plane_len();
    let d0 = layout.dims[0];
    for c in 0..3 {
        let r = ranges[c];
        u[c].par_chunks_mut(plane)
            .zip(q[c].par_chunks(plane))
            .enumerate()
            .for_each(|(k, (up, qp))| {
                if k < r[2].0 || k > r[2].1 {
                    return;
                }
                for j in r[1].0..=r[1].1 {
                    let row = j * d0;
                    let (lo, hi) = (row + r[0].0, row + r[0].1 + 1);
                    if lo < hi {
                        for (x, y) in up[lo..hi].iter_mut().zip(&qp[lo..hi]) {
                            *x += b * y;
                        }
                    }
                }
            });
    }
}
