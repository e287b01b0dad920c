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
    qc.par_chunks_mut(plane).enumerate().for_each(|(k, qp)| {
        if k < r[2].0 || k > r[2].1 {
            return;
        }
        for j in r[1].0..=r[1].1 {
            let row = j * d0;
            for i in r[0].0..=r[0].1 {
                let p = (k * plane + row + i) as isize;
                let at = |arr: &[f64], off: isize| arr[(p + off) as usize];
                let q0 = at(own, 0);
                // Own direction: (ū_c)² at the two cell centres.
                let hi = 0.5 * (q0 + at(own, sc));
                let lo = 0.5 * (at(own, -sc) + q0);
                let mut adv = (hi * hi - lo * lo) * ic;
                // Transverse directions: ū_c ū_d at the two edges.
                adv += (0.5 * (q0 + at(own, s1)) * 0.5 * (at(v1, s1) + at(v1, s1 - sc))
                    - 0.5 * (at(own, -s1) + q0) * 0.5 * (at(v1, 0) + at(v1, -sc)))
                    * i1;
                adv += (0.5 * (q0 + at(own, s2)) * 0.5 * (at(v2, s2) + at(v2, s2 - sc))
                    - 0.5 * (at(own, -s2) + q0) * 0.5 * (at(v2, 0) + at(v2, -sc)))
                    * i2;
                let lap = (at(own, sc) - 2.0 * q0 + at(own, -sc)) * inv_h2[c]
                    + (at(own, s1) - 2.0 * q0 + at(own, -s1)) * inv_h2[d1]
                    + (at(own, s2) - 2.0 * q0 + at(own, -s2)) * inv_h2[d2];
                let mut f = -adv + nu * lap + force;
                if let Some(src) = source {
                    f += src[p as usize];
                }
                let slot = &mut qp[row + i];
                *slot = if a == 0.0 { dt * f } else { a * *slot + dt * f };
            }
        }
    });
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
                    for i in r[0].0..=r[0].1 {
                        up[row + i] += b * qp[row + i];
                    }
                }
            });
    }
}
