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
    /// The advection term is evaluated (false: Stokes flow, `fsim { convection off; }`).
    pub convection: bool,
}

/// The stencil of one row of faces of component `c`: every point the tendency touches, as a
/// slice of the row's length, so inner loops over `0..len` run without bounds checks.
struct RowStencil<'a> {
    q0: &'a [f64],
    qpc: &'a [f64],
    qmc: &'a [f64],
    qp1: &'a [f64],
    qm1: &'a [f64],
    qp2: &'a [f64],
    qm2: &'a [f64],
    a1: &'a [f64],
    b1: &'a [f64],
    c1: &'a [f64],
    e1: &'a [f64],
    a2: &'a [f64],
    b2: &'a [f64],
    c2: &'a [f64],
    e2: &'a [f64],
    /// `1/h` along c, d1, d2 and `1/h²` along c, d1, d2.
    inv_h: [f64; 3],
    inv_h2: [f64; 3],
}

impl<'a> RowStencil<'a> {
    /// Component `c`'s row starting at padded linear index `base`, `len` faces long.
    #[inline(always)]
    fn new(
        u: &'a [Vec<f64>; 3],
        layout: &PaddedLayout,
        h: [f64; 3],
        c: usize,
        base: usize,
        len: usize,
    ) -> Self {
        let (d1, d2) = ((c + 1) % 3, (c + 2) % 3);
        let s = layout.stride;
        let (sc, s1, s2) = (s[c] as isize, s[d1] as isize, s[d2] as isize);
        let base = base as isize;
        let sl = |arr: &'a [f64], off: isize| -> &'a [f64] { &arr[(base + off) as usize..][..len] };
        let (own, v1, v2) = (&u[c][..], &u[d1][..], &u[d2][..]);
        RowStencil {
            q0: sl(own, 0),
            qpc: sl(own, sc),
            qmc: sl(own, -sc),
            qp1: sl(own, s1),
            qm1: sl(own, -s1),
            qp2: sl(own, s2),
            qm2: sl(own, -s2),
            a1: sl(v1, s1),
            b1: sl(v1, s1 - sc),
            c1: sl(v1, 0),
            e1: sl(v1, -sc),
            a2: sl(v2, s2),
            b2: sl(v2, s2 - sc),
            c2: sl(v2, 0),
            e2: sl(v2, -sc),
            inv_h: [1.0 / h[c], 1.0 / h[d1], 1.0 / h[d2]],
            inv_h2: [
                1.0 / (h[c] * h[c]),
                1.0 / (h[d1] * h[d1]),
                1.0 / (h[d2] * h[d2]),
            ],
        }
    }

    /// Advection `Σ_d δ_d(ū_c ū_d)` at face `i` of the row (as in [`Self::terms`]).
    #[inline(always)]
    fn advection(&self, i: usize) -> f64 {
        self.terms(i).0
    }

    /// Laplacian `Σ_d δ_d² u_c` at face `i` of the row (as in [`Self::terms`]).
    #[inline(always)]
    fn laplacian(&self, i: usize) -> f64 {
        let q = self.q0[i];
        (self.qpc[i] - 2.0 * q + self.qmc[i]) * self.inv_h2[0]
            + (self.qp1[i] - 2.0 * q + self.qm1[i]) * self.inv_h2[1]
            + (self.qp2[i] - 2.0 * q + self.qm2[i]) * self.inv_h2[2]
    }

    /// Advection `Σ_d δ_d(ū_c ū_d)` and Laplacian `Σ_d δ_d² u_c` at face `i` of the row.
    #[inline(always)]
    fn terms(&self, i: usize) -> (f64, f64) {
        let q = self.q0[i];
        // Own direction: (ū_c)² at the two cell centres.
        let hi = 0.5 * (q + self.qpc[i]);
        let lo = 0.5 * (self.qmc[i] + q);
        // Transverse directions: ū_c ū_d at the two edges.
        let adv = (hi * hi - lo * lo) * self.inv_h[0]
            + 0.25
                * ((q + self.qp1[i]) * (self.a1[i] + self.b1[i])
                    - (self.qm1[i] + q) * (self.c1[i] + self.e1[i]))
                * self.inv_h[1]
            + 0.25
                * ((q + self.qp2[i]) * (self.a2[i] + self.b2[i])
                    - (self.qm2[i] + q) * (self.c2[i] + self.e2[i]))
                * self.inv_h[2];
        let lap = (self.qpc[i] - 2.0 * q + self.qmc[i]) * self.inv_h2[0]
            + (self.qp1[i] - 2.0 * q + self.qm1[i]) * self.inv_h2[1]
            + (self.qp2[i] - 2.0 * q + self.qm2[i]) * self.inv_h2[2];
        (adv, lap)
    }
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
    let plane = t.layout.plane_len();
    let r = t.ranges[c];
    if r[0].0 > r[0].1 || r[1].0 > r[1].1 {
        return;
    }
    let wide = wide_vectors_available();
    qc.par_chunks_mut(plane).enumerate().for_each(|(k, qp)| {
        if k < r[2].0 || k > r[2].1 {
            return;
        }
        #[cfg(target_arch = "x86_64")]
        if wide {
            // SAFETY: AVX2 support was checked at run time just above.
            unsafe { accumulate_plane_avx2(qp, k, u, t, c, a, dt) };
            return;
        }
        let _ = wide;
        if t.convection {
            accumulate_plane::<true>(qp, k, u, t, c, a, dt);
        } else {
            accumulate_plane::<false>(qp, k, u, t, c, a, dt);
        }
    });
}

/// True when the CPU runs 256-bit vector code (the hot loops are then compiled twice; the
/// operations and their order are the same, so results are bit-identical either way).
fn wide_vectors_available() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn accumulate_plane_avx2(
    qp: &mut [f64],
    k: usize,
    u: &[Vec<f64>; 3],
    t: &MomentumTerms,
    c: usize,
    a: f64,
    dt: f64,
) {
    if t.convection {
        accumulate_plane::<true>(qp, k, u, t, c, a, dt);
    } else {
        accumulate_plane::<false>(qp, k, u, t, c, a, dt);
    }
}

/// `q ← a q + Δt F` on the faces of component `c` in padded k-plane `k` (`qp`); without
/// the advection term when `ADVECT` is false (Stokes flow: only `u_c`'s own faces are read).
#[inline(always)]
fn accumulate_plane<const ADVECT: bool>(
    qp: &mut [f64],
    k: usize,
    u: &[Vec<f64>; 3],
    t: &MomentumTerms,
    c: usize,
    a: f64,
    dt: f64,
) {
    let layout = t.layout;
    let plane = layout.plane_len();
    let (nu, force) = (t.nu, t.force[c]);
    let source = t.source.map(|s| &s[c][..]);
    let r = t.ranges[c];
    let d0 = layout.dims[0];
    let len = r[0].1 - r[0].0 + 1;
    for j in r[1].0..=r[1].1 {
        let row = j * d0 + r[0].0;
        let st = RowStencil::new(u, layout, t.h, c, k * plane + row, len);
        let src = source.map(|s| &s[k * plane + row..][..len]);
        let out = &mut qp[row..row + len];
        let rhs = |i: usize| -> f64 {
            if ADVECT {
                let (adv, lap) = st.terms(i);
                -adv + nu * lap + force
            } else {
                nu * st.laplacian(i) + force
            }
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
}

/// The cells on both sides of the faces of component `c` in padded row `(·, j, k)`: cells
/// `i − 1` and `i` along `c`, wrapping at the first face of a periodic direction (the schemes
/// that read it have no outlets).
struct PressureRow {
    hi_row: usize,
    lo_row: usize,
    c: usize,
    n0: usize,
}

impl PressureRow {
    #[inline(always)]
    fn new(n: [usize; 3], c: usize, j: usize, k: usize) -> Self {
        // Unpadded offset of the cell row (·, j, k), padded j, k.
        let row_of = |j: usize, k: usize| n[0] * ((j - 1) + n[1] * (k - 1));
        let hi_row = row_of(j, k);
        let lo_row = match c {
            1 => row_of(if j >= 2 { j - 1 } else { n[1] }, k),
            2 => row_of(j, if k >= 2 { k - 1 } else { n[2] }),
            _ => hi_row,
        };
        PressureRow {
            hi_row,
            lo_row,
            c,
            n0: n[0],
        }
    }

    /// `out[i] −= (p_hi − p_lo)/h` across the faces at padded x indices `first + i`, by
    /// contiguous slices (the wrap of a periodic x only at the first face).
    #[inline(always)]
    fn subtract_gradient(&self, out: &mut [f64], pressure: &[f64], first: usize, inv_h: f64) {
        let len = out.len();
        let hi = &pressure[self.hi_row + first - 1..][..len];
        if self.c != 0 {
            let lo = &pressure[self.lo_row + first - 1..][..len];
            for i in 0..len {
                out[i] -= (hi[i] - lo[i]) * inv_h;
            }
            return;
        }
        let start = if first >= 2 {
            0
        } else {
            out[0] -= self.difference(pressure, first) * inv_h;
            1
        };
        let lo = &pressure[self.hi_row + first + start - 2..][..len - start];
        for i in start..len {
            out[i] -= (hi[i] - lo[i - start]) * inv_h;
        }
    }

    /// `p_hi − p_lo` across the face at padded x index `pi`.
    #[inline(always)]
    fn difference(&self, pressure: &[f64], pi: usize) -> f64 {
        let hi = pressure[self.hi_row + pi - 1];
        let lo = if self.c != 0 {
            pressure[self.lo_row + pi - 1]
        } else if pi >= 2 {
            pressure[self.hi_row + pi - 2]
        } else {
            pressure[self.hi_row + self.n0 - 1]
        };
        hi - lo
    }
}

/// The frozen tendency of an `EulerRKC` step on the momentum faces of every component,
///
/// `q = −∇·(uu) + f + s − ∇p`,
///
/// everything but the diffusion, which the Chebyshev stages take (the pressure's gradient is
/// in it so that the projection corrects only an increment).
pub(crate) fn frozen_tendency(
    q: &mut [Vec<f64>; 3],
    u: &[Vec<f64>; 3],
    t: &MomentumTerms,
    pressure: &[f64],
) {
    let layout = t.layout;
    let n = layout.n;
    let plane = layout.plane_len();
    let d0 = layout.dims[0];
    for (c, qc) in q.iter_mut().enumerate() {
        let r = t.ranges[c];
        if (0..3).any(|d| r[d].0 > r[d].1) {
            continue;
        }
        let force = t.force[c];
        let source = t.source.map(|s| &s[c][..]);
        let inv_h = 1.0 / t.h[c];
        let len = r[0].1 - r[0].0 + 1;
        qc.par_chunks_mut(plane).enumerate().for_each(|(k, qp)| {
            if k < r[2].0 || k > r[2].1 {
                return;
            }
            for j in r[1].0..=r[1].1 {
                let row = j * d0 + r[0].0;
                let st = RowStencil::new(u, layout, t.h, c, k * plane + row, len);
                let src = source.map(|s| &s[k * plane + row..][..len]);
                let out = &mut qp[row..row + len];
                match (src, t.convection) {
                    (Some(s), true) => {
                        for i in 0..len {
                            out[i] = force + s[i] - st.advection(i);
                        }
                    }
                    (None, true) => {
                        for i in 0..len {
                            out[i] = force - st.advection(i);
                        }
                    }
                    (Some(s), false) => {
                        for i in 0..len {
                            out[i] = force + s[i];
                        }
                    }
                    (None, false) => out.fill(force),
                }
                PressureRow::new(n, c, j, k).subtract_gradient(out, pressure, r[0].0, inv_h);
            }
        });
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::{BoundaryConditions, FluidSettings, FluidSolver, TimeScheme};
    use crate::grid::Grid;

    fn random(seed: &mut u64) -> f64 {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        (*seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }

    /// The advective term of a random divergence-free periodic field conserves momentum
    /// (`Σ F = 0` per component) and kinetic energy (`Σ u·F = 0`): the discrete divergence
    /// form is skew-symmetric when `D u = 0`.
    #[test]
    fn advection_conserves_momentum_and_energy() {
        let grid = Grid::new([8, 6, 5], [0.3, 0.5, 0.4], [0.0; 3]);
        let settings = FluidSettings {
            nu: 1.0,
            scheme: TimeScheme::Euler,
            body_force: [0.0; 3],
            convection: true,
        };
        let mut s = FluidSolver::new(grid, BoundaryConditions::periodic(), settings).unwrap();
        let mut seed = 0x2545F4914F6CDD1D;
        for c in 0..3 {
            for x in s.velocity_mut()[c].iter_mut() {
                *x = random(&mut seed);
            }
        }
        s.project();
        let layout = s.layout().clone();
        let bc = BoundaryConditions::periodic();
        let ranges =
            std::array::from_fn(|c| std::array::from_fn(|d| bc.momentum_range(layout.n, c, d)));
        let terms = MomentumTerms {
            layout: &layout,
            h: [0.3, 0.5, 0.4],
            nu: 0.0,
            force: [0.0; 3],
            source: None,
            ranges: &ranges,
            convection: true,
        };
        let mut q = [
            vec![0.0; layout.len],
            vec![0.0; layout.len],
            vec![0.0; layout.len],
        ];
        accumulate_tendency(&mut q, s.velocity(), &terms, 0.0, 1.0);
        let mut energy = 0.0;
        let mut scale = 0.0;
        for c in 0..3 {
            let mut momentum = 0.0;
            for k in 1..=5 {
                for j in 1..=6 {
                    for i in 1..=8 {
                        let p = layout.index(i, j, k);
                        momentum += q[c][p];
                        energy += s.velocity()[c][p] * q[c][p];
                        scale += (s.velocity()[c][p] * q[c][p]).abs();
                    }
                }
            }
            assert!(
                momentum.abs() < 1e-12,
                "component {c}: momentum change {momentum:e}"
            );
        }
        assert!(
            energy.abs() < 1e-12 * scale,
            "energy change {energy:e} of {scale:e}"
        );
    }

    /// The 256-bit and the baseline compilation of the kernel agree bit for bit (no fused
    /// multiply-adds are formed), so restarts and thread counts never change results.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn wide_and_baseline_kernels_agree_bit_for_bit() {
        if !wide_vectors_available() {
            return;
        }
        let layout = PaddedLayout::new([9, 7, 4]);
        let bc = BoundaryConditions::periodic();
        let ranges =
            std::array::from_fn(|c| std::array::from_fn(|d| bc.momentum_range(layout.n, c, d)));
        let mut seed = 0x9E3779B97F4A7C15;
        let u: [Vec<f64>; 3] =
            std::array::from_fn(|_| (0..layout.len).map(|_| random(&mut seed)).collect());
        let terms = MomentumTerms {
            layout: &layout,
            h: [0.3, 0.5, 0.4],
            nu: 0.01,
            force: [0.1, 0.0, -9.81],
            source: None,
            ranges: &ranges,
            convection: true,
        };
        let plane = layout.plane_len();
        for c in 0..3 {
            for k in 1..=4 {
                let mut base = vec![0.5; plane];
                let mut wide = vec![0.5; plane];
                accumulate_plane::<true>(&mut base, k, &u, &terms, c, -0.5, 0.01);
                // SAFETY: AVX2 checked above.
                unsafe { accumulate_plane_avx2(&mut wide, k, &u, &terms, c, -0.5, 0.01) };
                assert!(base
                    .iter()
                    .zip(&wide)
                    .all(|(a, b)| a.to_bits() == b.to_bits()));
            }
        }
    }

    /// Without convection the tendency is exactly `ν ∇²u + f` with the advection of the same
    /// field taken out, bit for bit the same Laplacian as with it, for the explicit stages
    /// and for `EulerRKC`'s frozen tendency (`f − ∇p` there, the Laplacian in its stages).
    #[test]
    fn convection_off_drops_exactly_the_advection() {
        let layout = PaddedLayout::new([7, 6, 5]);
        let bc = BoundaryConditions::periodic();
        let ranges =
            std::array::from_fn(|c| std::array::from_fn(|d| bc.momentum_range(layout.n, c, d)));
        let mut seed = 0x51A4_7F1E_33C2_9B05;
        let u: [Vec<f64>; 3] =
            std::array::from_fn(|_| (0..layout.len).map(|_| random(&mut seed)).collect());
        let pressure: Vec<f64> = (0..7 * 6 * 5).map(|_| random(&mut seed)).collect();
        let terms = |convection, nu| MomentumTerms {
            layout: &layout,
            h: [0.3, 0.5, 0.4],
            nu,
            force: [0.1, 0.0, -9.81],
            source: None,
            ranges: &ranges,
            convection,
        };
        let zero = || -> [Vec<f64>; 3] { std::array::from_fn(|_| vec![0.0; layout.len]) };
        let (mut with, mut without, mut advection_only) = (zero(), zero(), zero());
        accumulate_tendency(&mut with, &u, &terms(true, 0.01), 0.0, 1.0);
        accumulate_tendency(&mut without, &u, &terms(false, 0.01), 0.0, 1.0);
        // ν = 0, f = 0: the advection alone, −∇·(uu)
        let mut inviscid = terms(true, 0.0);
        inviscid.force = [0.0; 3];
        accumulate_tendency(&mut advection_only, &u, &inviscid, 0.0, 1.0);
        let (mut frozen_with, mut frozen_without) = (zero(), zero());
        frozen_tendency(&mut frozen_with, &u, &terms(true, 0.01), &pressure);
        frozen_tendency(&mut frozen_without, &u, &terms(false, 0.01), &pressure);
        let mut largest: f64 = 0.0;
        for c in 0..3 {
            for p in 0..layout.len {
                let adv = advection_only[c][p];
                largest = largest.max(adv.abs());
                let tolerance = 1e-12 * (1.0 + with[c][p].abs() + adv.abs());
                assert!(
                    (with[c][p] - adv - without[c][p]).abs() < tolerance,
                    "{c} {p}"
                );
                let frozen = frozen_with[c][p] - adv - frozen_without[c][p];
                assert!(frozen.abs() < 1e-12 * (1.0 + adv.abs()), "frozen {c} {p}");
            }
        }
        assert!(largest > 0.1, "the field must advect: {largest}");
    }
}
