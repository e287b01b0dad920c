//! Steady Stokes flow through fixed spheres in a fully periodic box, solved directly (no
//! time stepping) with the direct model's forcing rows and restarted GMRES: the porous-media
//! validation of paper §3.1, for the tests. Not product code:
//! `fsimFoam` reaches steady states by time stepping.
#![allow(dead_code)]
// Component loops index several per-component arrays at once.
#![allow(clippy::needless_range_loop)]

use fsim::coupling::direct::{ImmersedBoundary, RigidSphere};
use fsim::fluid::{AxisKind, BoundaryConditions, PaddedLayout, SpectralPoisson};
use fsim::grid::Grid;

/// A steady periodic Stokes flow.
#[derive(Clone, Debug)]
pub struct SteadyStokesFlow {
    /// Velocity on the faces, padded layout (ghosts not filled).
    pub velocity: [Vec<f64>; 3],
    /// Periodic part of the kinematic pressure, cell-centred.
    pub pressure: Vec<f64>,
    /// The uniform body force (mean pressure gradient `−∇⟨p⟩/ρ`) that drives the flow, m/s².
    pub body_force: [f64; 3],
    pub report: GmresReport,
}

/// Steady Stokes flow `−ν∇²u + ∇p = G + f`, `∇·u = 0` on a fully periodic MAC grid with
/// fixed spheres, at a prescribed mean (superficial) velocity `U`.
///
/// The forcing `f` lives on the forced faces of [`ImmersedBoundary`] and is the unknown:
/// `u = U + S(f − ⟨f⟩)` with `S` the periodic discrete Stokes solution operator (per
/// component an FFT Poisson solve `−ν∇²v = f − ⟨f⟩`, then the projection of `v`; on a
/// periodic MAC grid the Laplacian commutes with the discrete gradient and divergence, so
/// this is the exact discrete Stokes solve). The forced faces' rows (`u = target` inside,
/// `u = w + a (u₂ − w)` on forcing faces, plus a far wall's term in a gap, and in a throat
/// the walls' line plus `(k/ν)(G − ∂p)`) form a
/// non-symmetric system for `f`, solved by
/// GMRES; the driving gradient is `G = −⟨f⟩` (the forces on the spheres balance it).
/// The steady state this finds is the one the time-stepped explicit schemes converge to
/// with the same forced faces ([`ImmersedBoundary`]), reached in tens of solves instead of
/// thousands of steps.
pub struct PeriodicStokesArray {
    grid: Grid,
    layout: PaddedLayout,
    nu: f64,
    boundary: ImmersedBoundary,
    poisson: SpectralPoisson,
    /// Unpadded cell index of every unknown's face and, for forcing rows, its neighbour.
    rows: Vec<Row>,
    /// Scratch: per-component face fields (unpadded), divergence, potential.
    fields: [Vec<f64>; 3],
    divergence: Vec<f64>,
    /// Cells whose faces are all forced: no continuity equation there (mass source).
    closed: Vec<bool>,
    closed_count: usize,
}

#[derive(Clone, Copy, Debug)]
struct Row {
    component: usize,
    cell: usize,
    neighbours: [usize; 2],
    weights: [f64; 2],
    target: f64,
    /// A face in a gap: its far wall's term `L_s (w_s − w)` ([`fsim::coupling::direct::GapFace`]); in a
    /// throat, the walls' line `δ/(δ+s) (w_s − w)` ([`fsim::coupling::direct::ThroatFace`]).
    gap: f64,
    /// A face in a throat: `k` (m², 0 elsewhere) and its cells below and above along its
    /// component, for the flow the pressure drives, `(k/ν)(G − ∂p)`.
    darcy: f64,
    cells: [usize; 2],
}

impl PeriodicStokesArray {
    /// A fully periodic grid, viscosity `nu` (m²/s), spheres at rest.
    pub fn new(grid: Grid, nu: f64, spheres: &[RigidSphere]) -> Self {
        Self::with_stencil(grid, nu, spheres, true)
    }

    /// As [`Self::new`], with the quadratic (`true`) or linear forcing stencil.
    pub fn with_stencil(grid: Grid, nu: f64, spheres: &[RigidSphere], quadratic: bool) -> Self {
        Self::with_options(grid, nu, spheres, quadratic, false)
    }

    /// As [`Self::with_stencil`], with the faces of throats held to the walls' line
    /// (`rigid_throats`; the staircase for spheres at rest) or carrying the lubrication
    /// profile ([`fsim::coupling::direct::ThroatFace`]).
    pub fn with_options(
        grid: Grid,
        nu: f64,
        spheres: &[RigidSphere],
        quadratic: bool,
        rigid_throats: bool,
    ) -> Self {
        let bc = BoundaryConditions::periodic();
        let mut boundary = ImmersedBoundary::new(&grid, &bc);
        boundary.set_quadratic(quadratic);
        if !rigid_throats {
            boundary.set_throat_viscosity(nu);
        }
        boundary.update(spheres);
        let layout = PaddedLayout::new(grid.n);
        let unpad = |slot: u32| {
            let slot = slot as usize;
            let (i, j, k) = (
                slot % layout.dims[0],
                (slot / layout.dims[0]) % layout.dims[1],
                slot / layout.plane_len(),
            );
            grid.cell_index(i - 1, j - 1, k - 1)
        };
        let mut rows = Vec::new();
        for c in 0..3 {
            for f in boundary.interior_faces(c) {
                let cell = unpad(f.slot);
                rows.push(Row {
                    component: c,
                    cell,
                    neighbours: [cell; 2],
                    weights: [0.0; 2],
                    target: f.target,
                    gap: 0.0,
                    darcy: 0.0,
                    cells: [0; 2],
                });
            }
            let first = rows.len();
            let forcing = boundary.forcing_faces(c);
            for f in forcing {
                rows.push(Row {
                    component: c,
                    cell: unpad(f.slot),
                    neighbours: f.neighbours.map(unpad),
                    weights: f.weights,
                    target: f.wall,
                    gap: 0.0,
                    darcy: 0.0,
                    cells: [0; 2],
                });
            }
            for g in boundary.gap_faces(c) {
                let f = &forcing[g.face as usize];
                rows[first + g.face as usize].gap = g.weight * (g.wall - f.wall);
            }
            // Held rigid, a throat's face keeps the walls' line, as the time steps hold it.
            for t in boundary.throat_faces(c) {
                let f = &forcing[t.face as usize];
                let row = &mut rows[first + t.face as usize];
                row.gap = t.share * (t.wall - f.wall);
                if !rigid_throats {
                    row.darcy = t.darcy;
                    row.cells = f.cells.map(|cell| cell as usize);
                }
            }
        }
        let poisson = SpectralPoisson::new(grid.n, grid.h, [AxisKind::Periodic; 3]);
        let cells = grid.cell_count();
        let mut closed = vec![false; cells];
        for cc in boundary.closed_cells() {
            closed[cc.cell] = true;
        }
        let closed_count = boundary.closed_cells().len();
        PeriodicStokesArray {
            closed,
            closed_count,
            fields: std::array::from_fn(|_| vec![0.0; cells]),
            divergence: vec![0.0; cells],
            layout,
            nu,
            boundary,
            poisson,
            rows,
            grid,
        }
    }

    /// The forced faces.
    pub fn boundary(&self) -> &ImmersedBoundary {
        &self.boundary
    }

    /// Number of unknowns (forced faces).
    pub fn unknowns(&self) -> usize {
        self.rows.len()
    }

    /// `fields ← S(f − ⟨f⟩)` for forces `f` on the forced faces; returns `⟨f⟩` and leaves
    /// in `divergence` what the projection removed (`∇²φ`).
    fn stokes(&mut self, forces: &[f64]) -> [f64; 3] {
        for field in self.fields.iter_mut() {
            field.iter_mut().for_each(|v| *v = 0.0);
        }
        for (row, &f) in self.rows.iter().zip(forces) {
            self.fields[row.component][row.cell] += f;
        }
        let cells = self.grid.cell_count() as f64;
        let mut mean = [0.0; 3];
        for c in 0..3 {
            let field = &mut self.fields[c];
            mean[c] = field.iter().sum::<f64>() / cells;
            let scale = -1.0 / self.nu;
            field.iter_mut().for_each(|v| *v = (*v - mean[c]) * scale);
            self.poisson.solve(field);
        }
        // Projection: ∇²φ = ∇·v, v ← v − ∇φ.
        let n = self.grid.n;
        let h = self.grid.h;
        let stride = [1, n[0], n[0] * n[1]];
        let up = |idx: usize, d: usize| -> usize {
            let i = (idx / stride[d]) % n[d];
            if i + 1 == n[d] {
                idx + stride[d] - n[d] * stride[d]
            } else {
                idx + stride[d]
            }
        };
        let down = |idx: usize, d: usize| -> usize {
            let i = (idx / stride[d]) % n[d];
            if i == 0 {
                idx + (n[d] - 1) * stride[d]
            } else {
                idx - stride[d]
            }
        };
        // Continuity holds outside the closed cells; their sources balance the rest.
        let mut open_total = 0.0;
        for idx in 0..self.divergence.len() {
            let mut div = 0.0;
            for d in 0..3 {
                div += (self.fields[d][up(idx, d)] - self.fields[d][idx]) / h[d];
            }
            self.divergence[idx] = div;
            if !self.closed[idx] {
                open_total += div;
            }
        }
        if self.closed_count > 0 {
            let source = -open_total / self.closed_count as f64;
            for (d, &c) in self.divergence.iter_mut().zip(&self.closed) {
                if c {
                    *d = source;
                }
            }
        }
        let mut phi = self.divergence.clone();
        self.poisson.solve(&mut phi);
        for d in 0..3 {
            for idx in 0..phi.len() {
                self.fields[d][idx] -= (phi[idx] - phi[down(idx, d)]) / h[d];
            }
        }
        mean
    }

    /// The steady flow at mean velocity `mean_velocity` (m/s), GMRES(120) to a relative
    /// residual `tolerance` of the forced rows or `max_iterations` Stokes solves. (On coarse
    /// grids the residual can stall near 1e-4; K has then settled to about 1e-4.)
    pub fn solve(
        &mut self,
        mean_velocity: [f64; 3],
        tolerance: f64,
        max_iterations: usize,
    ) -> SteadyStokesFlow {
        let rhs: Vec<f64> = self
            .rows
            .iter()
            .map(|r| {
                (1.0 - r.weights[0] - r.weights[1]) * (r.target - mean_velocity[r.component])
                    + r.gap
            })
            .collect();
        let mut forces = vec![0.0; rhs.len()];
        let rows = self.rows.clone();
        let report = gmres(
            &mut |f, out| {
                let mean = self.stokes(f);
                let (nu, h, divergence) = (self.nu, self.grid.h, &self.divergence);
                for (o, r) in out.iter_mut().zip(&rows) {
                    let field = &self.fields[r.component];
                    *o = field[r.cell]
                        - r.weights[0] * field[r.neighbours[0]]
                        - r.weights[1] * field[r.neighbours[1]];
                    if r.darcy > 0.0 {
                        // −(k/ν)(G − ∂p) with G = −⟨f⟩ and p = −ν ∇²φ.
                        let [lo, hi] = r.cells;
                        *o += r.darcy / nu * mean[r.component]
                            - r.darcy * (divergence[hi] - divergence[lo]) / h[r.component];
                    }
                }
            },
            &rhs,
            &mut forces,
            120,
            tolerance,
            max_iterations,
        );
        let mean = self.stokes(&forces);
        let l = &self.layout;
        let n = self.grid.n;
        let mut velocity: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; l.len]);
        for c in 0..3 {
            for k in 0..n[2] {
                for j in 0..n[1] {
                    for i in 0..n[0] {
                        velocity[c][l.index(i + 1, j + 1, k + 1)] =
                            mean_velocity[c] + self.fields[c][self.grid.cell_index(i, j, k)];
                    }
                }
            }
        }
        // −ν∇²u + ∇p = f − ⟨f⟩ with u = v − ∇φ, −ν∇²v = f − ⟨f⟩: p = −ν ∇²φ.
        let pressure = self.divergence.iter().map(|d| -self.nu * d).collect();
        SteadyStokesFlow {
            velocity,
            pressure,
            body_force: mean.map(|m| -m),
            report,
        }
    }
}

// ----- restarted GMRES (Saad & Schultz 1986) for the steady solver's non-symmetric system

/// Outcome of [`gmres`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GmresReport {
    /// Matrix–vector products used.
    pub iterations: usize,
    /// `‖b − A x‖ / ‖b‖` at return.
    pub relative_residual: f64,
}

/// Solves `A x = b` by GMRES(`restart`) from the initial `x`, until the residual falls
/// below `tolerance ‖b‖` or `max_iterations` products. `apply(v, out)` sets `out = A v`.
/// Modified Gram–Schmidt, Givens rotations; the Krylov basis (`restart + 1` vectors) is
/// allocated once per call (see [`GmresWorkspace`] to keep it across calls).
pub fn gmres(
    apply: &mut dyn FnMut(&[f64], &mut [f64]),
    b: &[f64],
    x: &mut [f64],
    restart: usize,
    tolerance: f64,
    max_iterations: usize,
) -> GmresReport {
    GmresWorkspace::new(restart).solve(apply, b, x, tolerance, max_iterations)
}

/// The Krylov basis and Hessenberg matrix of GMRES(`restart`), kept between solves so that
/// a solve in every time step allocates nothing once the sizes have been reached.
#[derive(Debug, Default)]
pub struct GmresWorkspace {
    restart: usize,
    basis: Vec<Vec<f64>>,
    hessenberg: Vec<Vec<f64>>,
    cs: Vec<f64>,
    sn: Vec<f64>,
    g: Vec<f64>,
    y: Vec<f64>,
    work: Vec<f64>,
}

impl GmresWorkspace {
    /// A workspace for GMRES restarted every `restart` products.
    pub fn new(restart: usize) -> Self {
        let m = restart.max(1);
        GmresWorkspace {
            restart: m,
            basis: vec![Vec::new(); m + 1],
            hessenberg: vec![vec![0.0; m]; m + 1],
            cs: vec![0.0; m],
            sn: vec![0.0; m],
            g: vec![0.0; m + 1],
            y: vec![0.0; m],
            work: Vec::new(),
        }
    }

    /// As [`gmres`]. An initial `x` of zeros costs no product.
    pub fn solve(
        &mut self,
        apply: &mut dyn FnMut(&[f64], &mut [f64]),
        b: &[f64],
        x: &mut [f64],
        tolerance: f64,
        max_iterations: usize,
    ) -> GmresReport {
        let n = b.len();
        let m = self.restart;
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(p, q)| p * q).sum::<f64>();
        let b_norm = dot(b, b).sqrt();
        if b_norm == 0.0 {
            x.iter_mut().for_each(|v| *v = 0.0);
            return GmresReport {
                iterations: 0,
                relative_residual: 0.0,
            };
        }
        for v in self.basis.iter_mut() {
            v.resize(n, 0.0);
        }
        self.work.resize(n, 0.0);
        let GmresWorkspace {
            basis,
            hessenberg,
            cs,
            sn,
            g,
            y,
            work,
            ..
        } = self;
        let mut iterations = 0;
        loop {
            if x.iter().all(|&v| v == 0.0) {
                work.iter_mut().for_each(|v| *v = 0.0);
            } else {
                apply(x, work);
            }
            for i in 0..n {
                basis[0][i] = b[i] - work[i];
            }
            let beta = dot(&basis[0], &basis[0]).sqrt();
            if beta <= tolerance * b_norm || iterations >= max_iterations {
                return GmresReport {
                    iterations,
                    relative_residual: beta / b_norm,
                };
            }
            basis[0].iter_mut().for_each(|v| *v /= beta);
            g.iter_mut().for_each(|v| *v = 0.0);
            g[0] = beta;
            let mut k_used = 0;
            for k in 0..m {
                let (head, tail) = basis.split_at_mut(k + 1);
                apply(&head[k], &mut tail[0]);
                iterations += 1;
                for (j, v) in head.iter().enumerate() {
                    let hjk = dot(&tail[0], v);
                    hessenberg[j][k] = hjk;
                    for i in 0..n {
                        tail[0][i] -= hjk * v[i];
                    }
                }
                let norm = dot(&tail[0], &tail[0]).sqrt();
                hessenberg[k + 1][k] = norm;
                if norm > 0.0 {
                    tail[0].iter_mut().for_each(|v| *v /= norm);
                }
                for j in 0..k {
                    let t = cs[j] * hessenberg[j][k] + sn[j] * hessenberg[j + 1][k];
                    hessenberg[j + 1][k] = -sn[j] * hessenberg[j][k] + cs[j] * hessenberg[j + 1][k];
                    hessenberg[j][k] = t;
                }
                let (a, c) = (hessenberg[k][k], hessenberg[k + 1][k]);
                let r = a.hypot(c);
                cs[k] = if r == 0.0 { 1.0 } else { a / r };
                sn[k] = if r == 0.0 { 0.0 } else { c / r };
                hessenberg[k][k] = r;
                hessenberg[k + 1][k] = 0.0;
                g[k + 1] = -sn[k] * g[k];
                g[k] *= cs[k];
                k_used = k + 1;
                if g[k + 1].abs() <= tolerance * b_norm
                    || iterations >= max_iterations
                    || norm == 0.0
                {
                    break;
                }
            }
            // Back substitution for the update y, then x += V y.
            for j in (0..k_used).rev() {
                let s: f64 = (j + 1..k_used).map(|l| hessenberg[j][l] * y[l]).sum();
                y[j] = (g[j] - s) / hessenberg[j][j];
            }
            for (j, yj) in y[..k_used].iter().enumerate() {
                for i in 0..n {
                    x[i] += yj * basis[j][i];
                }
            }
        }
    }
}
