//! The viscous term `ν∇·(ε∇u)` of the volume-averaged predictor, treated implicitly (the
//! drag-law model with `fsim { timeScheme EulerImplicit; }`).
//!
//! Per velocity component the predictor then solves
//!
//! ```text
//! M u* = b,    M u = A_f u − θν L_ε u,    L_ε u = Σ_d [ε_hi (u_{+d} − u) − ε_lo (u − u_{−d})] / h_d²,
//! ```
//!
//! θ = 1 (backward Euler), `A_f = ε_fⁿ⁺¹/Δt + K`, the face diffusivities those of
//! [`face_diffusivities`]. With the full diagonal `A'_f = A_f + θν Σ_d (ε_lo + ε_hi)/h_d²` a
//! row reads `A'_f u_f − θν Σ_d (ε_hi u_{+d} + ε_lo u_{−d})/h_d²`. `M` is symmetric positive
//! definite — neighbouring faces share their diffusivity, and the ghosts of walls, symmetry
//! planes and periodic or zero-gradient faces only change the diagonal — and well
//! conditioned (the off-diagonal sum of a row is below its diagonal), so conjugate gradients
//! preconditioned by `1/A'` converge in a few iterations. The ghosts are affine in the
//! velocity: the solve works on the correction from the initial guess, whose ghosts obey the
//! same conditions with every wall and inlet at rest ([`BoundaryConditions::at_rest`]).
//! Faces that are not unknowns (fixed boundary faces, outlet faces, which the predictor
//! extrapolates) keep their values.

use super::boundary_conditions::BoundaryConditions;
use super::ghost_fill::fill_component_ghosts;
use super::padded_layout::PaddedLayout;
use rayon::prelude::*;

/// Grids below this many cells solve on the calling thread: a fork-join costs more than a
/// pass over a few thousand faces.
const SERIAL_CELLS: usize = 32_768;

/// The diffusivities `(ε_lo, ε_hi)` of component `c`'s face `f` towards its neighbours along
/// direction `d` (`eps`: cell fractions, padded, ghosts filled): the cells on either side
/// along its own direction, the means of the four cells around the edges across the others.
/// A face's `ε_hi` is its upper neighbour's `ε_lo`, so `L_ε` is symmetric.
#[inline(always)]
pub(super) fn face_diffusivities(
    eps: &[f64],
    f: usize,
    c: usize,
    d: usize,
    s: [usize; 3],
) -> (f64, f64) {
    (
        lower_diffusivity(eps, f, c, d, s),
        lower_diffusivity(eps, f + s[d], c, d, s),
    )
}

/// `ε_lo` of [`face_diffusivities`]: between face `f` and face `f − s_d`.
#[inline(always)]
fn lower_diffusivity(eps: &[f64], f: usize, c: usize, d: usize, s: [usize; 3]) -> f64 {
    let sc = s[c];
    if d == c {
        eps[f - sc]
    } else {
        let sd = s[d];
        0.25 * (eps[f] + eps[f - sc] + eps[f - sd] + eps[f - sc - sd])
    }
}

/// `θν Σ_d (ε_lo + ε_hi)/h_d²` of face `f` of component `c`: what the implicit viscous term
/// adds to the diagonal `A_f`.
#[inline(always)]
fn viscous_diagonal(eps: &[f64], f: usize, c: usize, s: [usize; 3], coupling: [f64; 3]) -> f64 {
    let mut sum = 0.0;
    for d in 0..3 {
        let (lo, hi) = face_diffusivities(eps, f, c, d, s);
        sum += coupling[d] * (lo + hi);
    }
    sum
}

/// `out = (M u)` on the row of faces `f₀ .. f₀ + out.len()`; `edge[d][f]` is `θν/h_d²` times
/// the diffusivity between face `f − s_d` and face `f`. Whole-row slices, so the loop has no
/// index arithmetic or bounds checks.
#[inline(always)]
fn apply_row(
    u: &[f64],
    f0: usize,
    s: [usize; 3],
    full_diagonal: &[f64],
    edge: &[Vec<f64>; 3],
    out: &mut [f64],
) {
    let len = out.len();
    let at = |offset: usize| &u[offset..offset + len];
    let (uc, a) = (at(f0), &full_diagonal[f0..f0 + len]);
    let lo: [&[f64]; 3] = std::array::from_fn(|d| at(f0 - s[d]));
    let hi: [&[f64]; 3] = std::array::from_fn(|d| at(f0 + s[d]));
    let e_lo: [&[f64]; 3] = std::array::from_fn(|d| &edge[d][f0..f0 + len]);
    let e_hi: [&[f64]; 3] = std::array::from_fn(|d| &edge[d][f0 + s[d]..f0 + s[d] + len]);
    for t in 0..len {
        let mut off = 0.0;
        for d in 0..3 {
            off += e_hi[d][t] * hi[d][t] + e_lo[d][t] * lo[d][t];
        }
        out[t] = a[t] * uc[t] - off;
    }
}

/// What the last `ViscousSolve::solve` did, summed over components.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ViscousReport {
    /// Conjugate-gradient iterations over the three components.
    pub iterations: usize,
    /// Largest final `‖b − M u*‖₂ / ‖b‖₂` of the components.
    pub relative_residual: f64,
}

/// Work arrays and settings of the implicit viscous solve (one component at a time).
pub(super) struct ViscousSolve {
    layout: PaddedLayout,
    at_rest: BoundaryConditions,
    ranges: [[(usize, usize); 3]; 3],
    /// Right-hand side `b` of the component being solved (padded; the predictor fills it).
    pub rhs: Vec<f64>,
    r: Vec<f64>,
    z: Vec<f64>,
    p: Vec<f64>,
    q: Vec<f64>,
    /// `θν/h_d²` times the diffusivity between a face and its lower neighbour along `d`.
    edge: [Vec<f64>; 3],
    /// `A' = A_f + θν Σ_d (ε_lo + ε_hi)/h_d²` on the momentum faces.
    full_diagonal: Vec<f64>,
    /// Per k-plane partial sums, added in plane order (results independent of the threads).
    partials: Vec<[f64; 3]>,
    min_len: usize,
    /// Stop at `‖b − M u‖₂ ≤ tolerance ‖b‖₂`.
    pub tolerance: f64,
    pub max_iterations: usize,
    report: ViscousReport,
}

impl ViscousSolve {
    /// Padded arrays it holds: right-hand side, r, z, p, q, three edge arrays, `A'`.
    pub(super) const PADDED_ARRAYS: usize = 9;

    pub(super) fn new(
        layout: &PaddedLayout,
        bc: &BoundaryConditions,
        ranges: &[[(usize, usize); 3]; 3],
    ) -> Self {
        let cells: usize = layout.n.iter().product();
        let zeros = || vec![0.0; layout.len];
        ViscousSolve {
            layout: layout.clone(),
            at_rest: bc.at_rest(),
            ranges: *ranges,
            rhs: zeros(),
            r: zeros(),
            z: zeros(),
            p: zeros(),
            q: zeros(),
            edge: [zeros(), zeros(), zeros()],
            full_diagonal: zeros(),
            partials: vec![[0.0; 3]; layout.dims[2]],
            min_len: if cells < SERIAL_CELLS { usize::MAX } else { 1 },
            tolerance: 1e-6,
            max_iterations: 200,
            report: ViscousReport::default(),
        }
    }

    /// The solves since [`Self::reset_report`].
    pub(super) fn report(&self) -> ViscousReport {
        self.report
    }

    pub(super) fn reset_report(&mut self) {
        self.report = ViscousReport::default();
    }

    /// Solves `M x = self.rhs` for component `c` on its momentum faces. `x` (padded) holds the
    /// initial guess with its ghosts filled on entry; on exit its momentum faces hold the
    /// solution (ghosts stale). `diagonal` is `A_f` (padded), `eps` the diffusivities' cell
    /// fractions (padded, ghosts filled), `coupling[d] = θν/h_d²`.
    pub(super) fn solve(
        &mut self,
        c: usize,
        x: &mut [f64],
        diagonal: &[f64],
        eps: &[f64],
        coupling: [f64; 3],
    ) {
        let l = &self.layout;
        let s = l.stride;
        let plane = l.plane_len();
        let range = self.ranges[c];
        let min_len = self.min_len;
        // The momentum faces of a k-plane as rows: (first padded index, length).
        let len = range[0].1 + 1 - range[0].0;
        let rows = move |k: usize| {
            let inside = k >= range[2].0 && k <= range[2].1;
            (range[1].0..=range[1].1)
                .filter(move |_| inside)
                .map(move |j| l.index(range[0].0, j, k))
        };
        // A' on the momentum faces; the edges below them and above the last ones.
        for k in range[2].0..=range[2].1 {
            for j in range[1].0..=range[1].1 {
                for i in range[0].0..=range[0].1 {
                    let f = l.index(i, j, k);
                    self.full_diagonal[f] = diagonal[f] + viscous_diagonal(eps, f, c, s, coupling);
                }
            }
        }
        for d in 0..3 {
            let mut upper = range;
            upper[d].1 += 1;
            let edge = &mut self.edge[d];
            for k in upper[2].0..=upper[2].1 {
                for j in upper[1].0..=upper[1].1 {
                    for i in upper[0].0..=upper[0].1 {
                        let f = l.index(i, j, k);
                        edge[f] = coupling[d] * lower_diffusivity(eps, f, c, d, s);
                    }
                }
            }
        }
        let (edge, full_diagonal) = (&self.edge, &self.full_diagonal[..]);
        let apply =
            |u: &[f64], f0: usize, out: &mut [f64]| apply_row(u, f0, s, full_diagonal, edge, out);
        // r = b − M x, z = r / A', p = z; (r·z, b·b, r·r).
        self.p.iter_mut().for_each(|v| *v = 0.0);
        {
            let (b, xr) = (&self.rhs, &*x);
            self.r
                .par_chunks_mut(plane)
                .zip(self.z.par_chunks_mut(plane))
                .zip(self.p.par_chunks_mut(plane))
                .zip(self.partials.par_iter_mut())
                .with_min_len(min_len)
                .enumerate()
                .for_each(|(k, (((rk, zk), pk), part))| {
                    *part = [0.0; 3];
                    for f0 in rows(k) {
                        let at = f0 - k * plane;
                        let (rr, zr, pr) = (
                            &mut rk[at..at + len],
                            &mut zk[at..at + len],
                            &mut pk[at..at + len],
                        );
                        apply(xr, f0, rr);
                        let (bb, a) = (&b[f0..f0 + len], &full_diagonal[f0..f0 + len]);
                        for t in 0..len {
                            let r = bb[t] - rr[t];
                            let z = r / a[t];
                            rr[t] = r;
                            zr[t] = z;
                            pr[t] = z;
                            part[0] += r * z;
                            part[1] += bb[t] * bb[t];
                            part[2] += r * r;
                        }
                    }
                });
        }
        let [mut rz, bb, rr] = self.sum_partials();
        let bound = self.tolerance * bb.sqrt();
        let mut iterations = 0;
        let mut residual = rr.sqrt();
        while residual > bound && iterations < self.max_iterations {
            iterations += 1;
            fill_component_ghosts(l, &self.at_rest, &mut self.p, c);
            // q = M p, (p·q).
            {
                let pr = &self.p;
                self.q
                    .par_chunks_mut(plane)
                    .zip(self.partials.par_iter_mut())
                    .with_min_len(min_len)
                    .enumerate()
                    .for_each(|(k, (qk, part))| {
                        *part = [0.0; 3];
                        for f0 in rows(k) {
                            let at = f0 - k * plane;
                            let qr = &mut qk[at..at + len];
                            apply(pr, f0, qr);
                            let p = &pr[f0..f0 + len];
                            for t in 0..len {
                                part[0] += p[t] * qr[t];
                            }
                        }
                    });
            }
            let [pq, _, _] = self.sum_partials();
            if pq <= 0.0 {
                break;
            }
            let alpha = rz / pq;
            // x += α p, r −= α q, z = r / A'; (r·z, r·r).
            {
                let (pr, qr) = (&self.p, &self.q);
                x.par_chunks_mut(plane)
                    .zip(self.r.par_chunks_mut(plane))
                    .zip(self.z.par_chunks_mut(plane))
                    .zip(self.partials.par_iter_mut())
                    .with_min_len(min_len)
                    .enumerate()
                    .for_each(|(k, (((xk, rk), zk), part))| {
                        *part = [0.0; 3];
                        for f0 in rows(k) {
                            let at = f0 - k * plane;
                            let (xs, rs, zs) = (
                                &mut xk[at..at + len],
                                &mut rk[at..at + len],
                                &mut zk[at..at + len],
                            );
                            let (p, q, a) = (
                                &pr[f0..f0 + len],
                                &qr[f0..f0 + len],
                                &full_diagonal[f0..f0 + len],
                            );
                            for t in 0..len {
                                xs[t] += alpha * p[t];
                                let r = rs[t] - alpha * q[t];
                                let z = r / a[t];
                                rs[t] = r;
                                zs[t] = z;
                                part[0] += r * z;
                                part[1] += r * r;
                            }
                        }
                    });
            }
            let [rz_new, rr, _] = self.sum_partials();
            residual = rr.sqrt();
            if residual <= bound {
                break;
            }
            let beta = rz_new / rz;
            rz = rz_new;
            // p = z + β p.
            {
                let zr = &self.z;
                self.p
                    .par_chunks_mut(plane)
                    .with_min_len(min_len)
                    .enumerate()
                    .for_each(|(k, pk)| {
                        for f0 in rows(k) {
                            let at = f0 - k * plane;
                            let (ps, z) = (&mut pk[at..at + len], &zr[f0..f0 + len]);
                            for t in 0..len {
                                ps[t] = z[t] + beta * ps[t];
                            }
                        }
                    });
            }
        }
        self.report.iterations += iterations;
        let relative = if bb > 0.0 { residual / bb.sqrt() } else { 0.0 };
        self.report.relative_residual = self.report.relative_residual.max(relative);
    }

    /// The partials summed in plane order.
    fn sum_partials(&self) -> [f64; 3] {
        let mut sum = [0.0; 3];
        for part in &self.partials {
            for (s, p) in sum.iter_mut().zip(part) {
                *s += p;
            }
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::boundary_conditions::FaceCondition;
    use crate::fluid::coefficient_fields::seeded_uniform;
    use crate::fluid::volume_averaged_fluid::fill_cell_ghosts;

    /// A moving wall, a wall at rest, periodic y, an inlet below and an outlet above: every
    /// kind of ghost and fixed face the solve must honour.
    fn mixed_box() -> BoundaryConditions {
        BoundaryConditions {
            faces: [
                FaceCondition::Wall {
                    velocity: [0.0, 0.3, -0.2],
                },
                FaceCondition::Wall { velocity: [0.0; 3] },
                FaceCondition::Periodic,
                FaceCondition::Periodic,
                FaceCondition::Inlet {
                    velocity: [0.1, 0.0, 0.5],
                },
                FaceCondition::Outlet { pressure: 0.0 },
            ],
        }
    }

    /// `(M x)_f` face by face from the ghost rule of the true conditions: the definition the
    /// row-wise solve must meet.
    fn row_by_definition(
        x: &[f64],
        f: usize,
        c: usize,
        s: [usize; 3],
        diagonal: &[f64],
        eps: &[f64],
        coupling: [f64; 3],
    ) -> f64 {
        let mut laplacian = 0.0;
        for d in 0..3 {
            let (lo, hi) = face_diffusivities(eps, f, c, d, s);
            laplacian += coupling[d] * (hi * (x[f + s[d]] - x[f]) - lo * (x[f] - x[f - s[d]]));
        }
        diagonal[f] * x[f] - laplacian
    }

    #[test]
    fn solution_meets_every_row_with_the_true_ghosts() {
        let n = [6, 5, 7];
        let layout = PaddedLayout::new(n);
        let bc = mixed_box();
        let ranges = std::array::from_fn(|c| std::array::from_fn(|d| bc.momentum_range(n, c, d)));
        let mut next = seeded_uniform(7);
        let h = [0.1, 0.12, 0.08];
        // θν/h² large against the diagonal (A' ≥ ε/Δt with νΔt/h² ≈ 2): a stiff case.
        let (dt, nu) = (0.01, 2.0);
        let coupling: [f64; 3] = std::array::from_fn(|d| 0.5 * nu / (h[d] * h[d]));
        let mut eps: Vec<f64> = (0..layout.len).map(|_| 0.4 + 0.6 * next()).collect();
        fill_cell_ghosts(&layout, &bc, &mut eps);
        let mut solve = ViscousSolve::new(&layout, &bc, &ranges);
        solve.tolerance = 1e-12;
        for c in 0..3 {
            let s = layout.stride;
            let mut diagonal = vec![0.0; layout.len];
            let r = ranges[c];
            for k in r[2].0..=r[2].1 {
                for j in r[1].0..=r[1].1 {
                    for i in r[0].0..=r[0].1 {
                        let f = layout.index(i, j, k);
                        let drag = 50.0 * next();
                        diagonal[f] = eps[f] / dt + drag;
                        solve.rhs[f] = 10.0 * next() - 5.0;
                    }
                }
            }
            // Initial guess: random, its ghosts from the true conditions (the outlet face
            // keeps its value, as the predictor's).
            let mut x: Vec<f64> = (0..layout.len).map(|_| next() - 0.5).collect();
            fill_component_ghosts(&layout, &bc, &mut x, c);
            solve.solve(c, &mut x, &diagonal, &eps, coupling);
            fill_component_ghosts(&layout, &bc, &mut x, c);
            let mut worst = 0.0f64;
            let mut scale = 0.0f64;
            for k in r[2].0..=r[2].1 {
                for j in r[1].0..=r[1].1 {
                    for i in r[0].0..=r[0].1 {
                        let f = layout.index(i, j, k);
                        let m = row_by_definition(&x, f, c, s, &diagonal, &eps, coupling);
                        worst = worst.max((solve.rhs[f] - m).abs());
                        scale = scale.max(solve.rhs[f].abs());
                    }
                }
            }
            assert!(
                worst < 1e-10 * scale,
                "component {c}: residual {worst:e} of {scale}"
            );
        }
        let report = solve.report();
        assert!(
            report.iterations > 3 && report.relative_residual < 1e-12,
            "{report:?}"
        );
    }

    #[test]
    fn diffusivities_are_shared_by_neighbouring_faces() {
        // ε_hi of a face is ε_lo of its upper neighbour in every direction: L_ε is symmetric.
        let layout = PaddedLayout::new([4, 3, 5]);
        let mut next = seeded_uniform(3);
        let eps: Vec<f64> = (0..layout.len).map(|_| next()).collect();
        let s = layout.stride;
        for c in 0..3 {
            for d in 0..3 {
                let f = layout.index(2, 1, 2);
                let (_, hi) = face_diffusivities(&eps, f, c, d, s);
                let (lo_next, _) = face_diffusivities(&eps, f + s[d], c, d, s);
                assert_eq!(hi, lo_next);
            }
        }
    }
}
