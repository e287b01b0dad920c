//! The work arrays and the stage kernel of `EulerRKC`: the diffusion of a step by
//! Runge–Kutta–Chebyshev stages ([`ChebyshevStages`]) with the advection, forces and old
//! pressure gradient frozen in `N`,
//!
//! ```text
//!   Y_j = μ_j Y_{j−1} + ν_j Y_{j−2} + μ̃_j Δt (ν ∇²Y_{j−1} + N)      on the momentum faces.
//! ```
//!
//! A stage reads `Y_{j−1}` around each face and `Y_{j−2}` at the face only, so `Y_j`
//! overwrites `Y_{j−2}` in place: two velocity registers and `N`, whatever `s`. The stages
//! do not couple the components, which take them one after another: the second register
//! is one array, handed from component to component.

use super::chebyshev_stages::ChebyshevStage;
use super::padded_layout::PaddedLayout;
use rayon::prelude::*;

pub(crate) struct ChebyshevDiffusion {
    /// The second velocity register (`Y_{j−2}`, then `Y_j`) of the component whose stages
    /// run, padded. Its fixed boundary faces must be that component's before its first stage
    /// (a stage writes only momentum faces, and a hook handed the register after the swap
    /// may read them: a closed cell's divergence at a wall).
    pub register: Vec<f64>,
    /// Pressure increment of the projection, cell-centred.
    pub increment: Vec<f64>,
}

impl ChebyshevDiffusion {
    pub fn new(layout: &PaddedLayout, cells: usize) -> Self {
        ChebyshevDiffusion {
            register: vec![0.0; layout.len],
            increment: vec![0.0; cells],
        }
    }

    pub fn bytes(&self) -> usize {
        8 * (self.register.len() + self.increment.len())
    }
}

/// What a stage reads besides the registers.
pub(crate) struct StageTerms<'a> {
    pub layout: &'a PaddedLayout,
    pub h: [f64; 3],
    pub nu: f64,
    /// Momentum ranges `[c][d]`, inclusive padded indices.
    pub ranges: &'a [[(usize, usize); 3]; 3],
    /// The frozen tendency `N`, padded.
    pub frozen: &'a [Vec<f64>; 3],
}

/// One stage of component `c`: `next ← μ current + ν next + μ̃ Δt (ν∇² current + N)` on its
/// momentum faces (`next` is read only when `ν ≠ 0`). `current` has its ghosts filled.
pub(crate) fn chebyshev_stage(
    next: &mut [f64],
    current: &[f64],
    terms: &StageTerms,
    c: usize,
    stage: &ChebyshevStage,
    dt: f64,
) {
    stage_component(next, current, &terms.frozen[c], terms, c, stage, dt);
}

fn stage_component(
    out: &mut [f64],
    y: &[f64],
    frozen: &[f64],
    terms: &StageTerms,
    c: usize,
    stage: &ChebyshevStage,
    dt: f64,
) {
    let layout = terms.layout;
    let r = terms.ranges[c];
    if (0..3).any(|d| r[d].0 > r[d].1) {
        return;
    }
    let plane = layout.plane_len();
    let d0 = layout.dims[0];
    let s = layout.stride;
    let (d1, d2) = ((c + 1) % 3, (c + 2) % 3);
    let (sc, s1, s2) = (s[c], s[d1], s[d2]);
    let h = terms.h;
    let inv_h2 = [
        1.0 / (h[c] * h[c]),
        1.0 / (h[d1] * h[d1]),
        1.0 / (h[d2] * h[d2]),
    ];
    let len = r[0].1 - r[0].0 + 1;
    let (mu, nu_prev) = (stage.current, stage.previous);
    let weight = stage.tendency * dt;
    let viscous = weight * terms.nu;
    out.par_chunks_mut(plane).enumerate().for_each(|(k, op)| {
        if k < r[2].0 || k > r[2].1 {
            return;
        }
        for j in r[1].0..=r[1].1 {
            let row = j * d0 + r[0].0;
            let base = k * plane + row;
            let sl = |off: usize, minus: bool| -> &[f64] {
                let start = if minus { base - off } else { base + off };
                &y[start..start + len]
            };
            let (q0, qpc, qmc) = (&y[base..base + len], sl(sc, false), sl(sc, true));
            let (qp1, qm1, qp2, qm2) = (sl(s1, false), sl(s1, true), sl(s2, false), sl(s2, true));
            let n = &frozen[base..base + len];
            let o = &mut op[row..row + len];
            let lap = |i: usize| {
                (qpc[i] - 2.0 * q0[i] + qmc[i]) * inv_h2[0]
                    + (qp1[i] - 2.0 * q0[i] + qm1[i]) * inv_h2[1]
                    + (qp2[i] - 2.0 * q0[i] + qm2[i]) * inv_h2[2]
            };
            if nu_prev == 0.0 {
                for i in 0..len {
                    o[i] = mu * q0[i] + viscous * lap(i) + weight * n[i];
                }
            } else {
                for i in 0..len {
                    o[i] = mu * q0[i] + nu_prev * o[i] + viscous * lap(i) + weight * n[i];
                }
            }
        }
    });
}
