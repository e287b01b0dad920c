//! Discrete divergence (faces → cells) and gradient (cells → faces) of the projection.
//!
//! `(D u)_cell = Σ_d (u_d(high face) − u_d(low face)) / h_d` and
//! `(G p)_face = (p(high cell) − p(low cell)) / h_d`, so `D G` is the 7-point Laplacian the
//! spectral solver inverts, with the face conditions built in: no correction on faces where
//! the normal velocity is fixed (zero pressure gradient), wrap-around on periodic faces, and
//! the ghost `p_ghost = 2 p_out − p` on outlet faces (fixed pressure at the face).

use super::boundary_conditions::BoundaryConditions;
use super::padded_layout::PaddedLayout;
use rayon::prelude::*;

/// `rhs = (D u) / τ` at every cell (unpadded x-fastest `rhs`), with the known outlet
/// pressures moved to the right-hand side: `−2 p_out / h_d²` in cells next to an outlet.
pub(crate) fn divergence_rhs(
    rhs: &mut [f64],
    u: &[Vec<f64>; 3],
    layout: &PaddedLayout,
    h: [f64; 3],
    bc: &BoundaryConditions,
    tau: f64,
) {
    let [n0, n1, n2] = layout.n;
    let s = layout.stride;
    let inv = [1.0 / (h[0] * tau), 1.0 / (h[1] * tau), 1.0 / (h[2] * tau)];
    let (ux, uy, uz) = (&u[0][..], &u[1][..], &u[2][..]);
    rhs.par_chunks_mut(n0 * n1)
        .enumerate()
        .for_each(|(k, plane)| {
            for j in 0..n1 {
                let base = layout.index(1, j + 1, k + 1);
                let row = &mut plane[j * n0..(j + 1) * n0];
                let (xl, xh) = (&ux[base..base + n0], &ux[base + 1..base + 1 + n0]);
                let (yl, yh) = (&uy[base..base + n0], &uy[base + s[1]..base + s[1] + n0]);
                let (zl, zh) = (&uz[base..base + n0], &uz[base + s[2]..base + s[2] + n0]);
                for i in 0..n0 {
                    row[i] = (xh[i] - xl[i]) * inv[0]
                        + (yh[i] - yl[i]) * inv[1]
                        + (zh[i] - zl[i]) * inv[2];
                }
            }
        });
    let n = [n0, n1, n2];
    for d in 0..3 {
        for side in 0..2 {
            if let Some(p_out) = bc.outlet_pressure(d, side) {
                let value = -2.0 * p_out / (h[d] * h[d]);
                let slot = if side == 0 { 0 } else { n[d] - 1 };
                for_each_cell_in_layer(n, d, slot, |c| rhs[c] += value);
            }
        }
    }
}

/// Calls `f` with the unpadded index of every cell whose index along `d` is `slot`.
fn for_each_cell_in_layer(n: [usize; 3], d: usize, slot: usize, mut f: impl FnMut(usize)) {
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                if [i, j, k][d] == slot {
                    f(i + n[0] * (j + n[1] * k));
                }
            }
        }
    }
}

/// Where the pressure at one side of a face row comes from.
#[derive(Clone, Copy)]
enum Side {
    /// A cell row starting at this unpadded offset.
    Cell(usize),
    /// Outlet ghost `2 p_out − p`, mirroring the cell row at this offset.
    Ghost(f64, usize),
}

/// `t[i] −= f (p_hi(i) − p_lo(i))` along one row of x-contiguous faces.
fn subtract_row(t: &mut [f64], p: &[f64], lo: Side, hi: Side, f: f64) {
    let len = t.len();
    match (lo, hi) {
        (Side::Cell(a), Side::Cell(b)) => {
            let (pl, ph) = (&p[a..a + len], &p[b..b + len]);
            for i in 0..len {
                t[i] -= f * (ph[i] - pl[i]);
            }
        }
        (Side::Ghost(v, a), Side::Cell(b)) => {
            let (pl, ph) = (&p[a..a + len], &p[b..b + len]);
            for i in 0..len {
                t[i] -= f * (ph[i] - (2.0 * v - pl[i]));
            }
        }
        (Side::Cell(a), Side::Ghost(v, b)) => {
            let (pl, ph) = (&p[a..a + len], &p[b..b + len]);
            for i in 0..len {
                t[i] -= f * ((2.0 * v - ph[i]) - pl[i]);
            }
        }
        (Side::Ghost(..), Side::Ghost(..)) => unreachable!("a face has at most one boundary side"),
    }
}

/// `target ← target − factor (G p)` on the corrected faces of every component.
pub(crate) fn subtract_gradient(
    target: &mut [Vec<f64>; 3],
    p: &[f64],
    factor: f64,
    layout: &PaddedLayout,
    h: [f64; 3],
    bc: &BoundaryConditions,
    ranges: &[[(usize, usize); 3]; 3],
) {
    let n = layout.n;
    let plane = layout.plane_len();
    let d0 = layout.dims[0];
    // Unpadded offset of the row of padded cells (·, j, k).
    let row_of = |j: usize, k: usize| n[0] * ((j - 1) + n[1] * (k - 1));
    // The pressure row/plane below face slot `s` along `d`, with `offset(m)` the cell row for
    // cell index m (0-based) along d.
    let sides = |d: usize, s: usize, offset: &dyn Fn(usize) -> usize| -> (Side, Side) {
        let nd = n[d];
        let lo = if s >= 2 {
            Side::Cell(offset(s - 2))
        } else if let Some(v) = bc.outlet_pressure(d, 0) {
            Side::Ghost(v, offset(0))
        } else {
            Side::Cell(offset(nd - 1)) // periodic wrap
        };
        let hi = if s <= nd {
            Side::Cell(offset(s - 1))
        } else {
            Side::Ghost(bc.outlet_pressure(d, 1).unwrap_or(0.0), offset(nd - 1))
        };
        (lo, hi)
    };

    // x faces: rows are lines along the component's own direction.
    {
        let r = ranges[0];
        let f = factor / h[0];
        let nx = n[0];
        let out0 = bc.outlet_pressure(0, 0);
        let out1 = bc.outlet_pressure(0, 1);
        target[0]
            .par_chunks_mut(plane)
            .enumerate()
            .for_each(|(k, tp)| {
                if k < r[2].0 || k > r[2].1 {
                    return;
                }
                for j in r[1].0..=r[1].1 {
                    let pr = &p[row_of(j, k)..row_of(j, k) + nx];
                    let t = &mut tp[j * d0..(j + 1) * d0];
                    let (lo, hi) = (r[0].0.max(2), r[0].1.min(nx));
                    if lo <= hi {
                        let len = hi - lo + 1;
                        let (pl, ph) = (&pr[lo - 2..lo - 2 + len], &pr[lo - 1..lo - 1 + len]);
                        let t = &mut t[lo..lo + len];
                        for i in 0..len {
                            t[i] -= f * (ph[i] - pl[i]);
                        }
                    }
                    if r[0].0 == 1 {
                        let lo = match out0 {
                            Some(v) => 2.0 * v - pr[0],
                            None => pr[nx - 1],
                        };
                        t[1] -= f * (pr[0] - lo);
                    }
                    if r[0].1 == nx + 1 {
                        let hi = 2.0 * out1.unwrap_or(0.0) - pr[nx - 1];
                        t[nx + 1] -= f * (hi - pr[nx - 1]);
                    }
                }
            });
    }
    // y faces: per plane k, per face row j, contiguous along x.
    {
        let r = ranges[1];
        let f = factor / h[1];
        target[1]
            .par_chunks_mut(plane)
            .enumerate()
            .for_each(|(k, tp)| {
                if k < r[2].0 || k > r[2].1 {
                    return;
                }
                for j in r[1].0..=r[1].1 {
                    let (lo, hi) = sides(1, j, &|m| row_of(m + 1, k));
                    subtract_row(&mut tp[j * d0 + 1..j * d0 + 1 + n[0]], p, lo, hi, f);
                }
            });
    }
    // z faces: per face plane k, per row j.
    {
        let r = ranges[2];
        let f = factor / h[2];
        target[2]
            .par_chunks_mut(plane)
            .enumerate()
            .for_each(|(k, tp)| {
                if k < r[2].0 || k > r[2].1 {
                    return;
                }
                for j in r[1].0..=r[1].1 {
                    let (lo, hi) = sides(2, k, &|m| row_of(j, m + 1));
                    subtract_row(&mut tp[j * d0 + 1..j * d0 + 1 + n[0]], p, lo, hi, f);
                }
            });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::{FaceCondition, SpectralPoisson};

    /// `D G` with the face conditions built in is exactly the Laplacian the spectral solver
    /// inverts (walls, periodic and an outlet at zero pressure).
    #[test]
    fn divergence_of_gradient_is_the_solver_laplacian() {
        let n = [7, 6, 5];
        let h = [0.3, 0.5, 0.4];
        let layout = PaddedLayout::new(n);
        let wall = FaceCondition::Wall { velocity: [0.0; 3] };
        let bc = BoundaryConditions {
            faces: [
                FaceCondition::Inlet { velocity: [0.0; 3] },
                FaceCondition::Outlet { pressure: 0.0 },
                wall.clone(),
                wall,
                FaceCondition::Periodic,
                FaceCondition::Periodic,
            ],
        };
        let ranges = std::array::from_fn(|c| std::array::from_fn(|d| bc.corrected_range(n, c, d)));
        let len = n[0] * n[1] * n[2];
        let p: Vec<f64> = (0..len)
            .map(|i| ((i * 7919) % 31) as f64 / 31.0 - 0.5)
            .collect();
        let mut u = [
            vec![0.0; layout.len],
            vec![0.0; layout.len],
            vec![0.0; layout.len],
        ];
        subtract_gradient(&mut u, &p, -1.0, &layout, h, &bc, &ranges); // u = G p
                                                                       // Periodic faces: the high face (ghost slot) is the low one.
        for j in 0..layout.dims[1] {
            for i in 0..layout.dims[0] {
                let (lo, hi) = (layout.index(i, j, 1), layout.index(i, j, n[2] + 1));
                u[2][hi] = u[2][lo];
            }
        }
        let mut dgp = vec![0.0; len];
        divergence_rhs(&mut dgp, &u, &layout, h, &bc, 1.0);
        let axes = std::array::from_fn(|d| bc.pressure_axis(d));
        let solver = SpectralPoisson::new(n, h, axes);
        let mut lp = vec![0.0; len];
        solver.apply_laplacian(&p, &mut lp);
        let err = dgp
            .iter()
            .zip(&lp)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(err < 1e-12, "max |DGp − Lp| = {err:e}");
    }
}
