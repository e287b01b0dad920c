//! No-slip inside the implicit viscous solve of the semi-implicit scheme (`RK3CN`).
//!
//! # The problem
//!
//! A stage of `RK3CN` solves, per velocity component, the Helmholtz problem
//! `A u* = r` with `A = I − κ∇²`, `κ = β_s Δt ν` (Spalart, Moser & Rogers 1991; see
//! `src/fluid/time_scheme.rs`), then projects. The direct forcing of
//! [`ImmersedBoundary`] constrains some faces: inside a sphere `u_f = U_f` (rigid motion),
//! on a forcing face the interpolation along the grid line
//!
//! ```text
//!   u_f − a₁ u_{n₁} − a₂ u_{n₂} = (1 − a₁ − a₂) w_f                                (C u = g)
//! ```
//!
//! (`n₁, n₂` the next fluid faces, `w_f` the wall velocity). Setting these faces after the
//! solve leaves the fluid faces next to them with values diffused from the *unconstrained*
//! field, an error that grows with `κ/h²` and does not vanish at steady state (drag −1.3 %
//! at the RK3 step, −4.8 % at four times it, −15 % at sixteen: `docs/direct_model.md`).
//!
//! # The constrained solve
//!
//! The stage must solve instead the system whose fluid rows are the Helmholtz rows and
//! whose forced rows are the constraints. Fluid rows never reach an interior face (a fluid
//! face with a same-component neighbour inside a sphere is by definition a forcing face), so
//! the interior faces decouple: they take `U_f` afterwards. For the forcing faces `F`, write
//! the solution as the unconstrained one plus a correction driven by unknown sources `φ` on
//! `F` only (`E` injects a vector on `F` into the grid):
//!
//! ```text
//!   u* = A⁻¹ (r + E φ) = u₀ + A⁻¹ E φ,        u₀ = A⁻¹ r.
//! ```
//!
//! Every fluid row of `A u* = r + E φ` is the Helmholtz row, whatever `φ`; `φ` is fixed by
//! the constraints, the capacitance system (Buzbee, Dorr, George & Golub, SIAM J. Numer.
//! Anal. 8, 722–736, 1971)
//!
//! ```text
//!   S φ = g − C u₀,        S = C A⁻¹ E        (|F| × |F|, non-symmetric),
//! ```
//!
//! solved by restarted GMRES ([`GmresWorkspace`]), right-preconditioned by `A_FF`, the
//! Helmholtz operator restricted to the forcing faces (an approximate inverse of `E'A⁻¹E`
//! that costs no solve: as `κ → 0` both tend to the identity, and a smooth layer of sources
//! sees about `(1 + 2κ/h²)⁻¹`, which `A_FF` inverts). Each product is one exact FFT/DCT/DST
//! Helmholtz solve on the grid (the fluid's own, [`ImplicitStage::solve_homogeneous`]), and
//! one more applies the correction. Measured (`docs/direct_model.md`): 2 to 4 products per
//! component and stage at tolerance 1e-3 for `κ/h²` from 0.05 to 1. This is Fadlun et al.'s
//! (J. Comput. Phys. 161, 35–60, 2000) prescription, forcing applied within the implicit
//! viscous step, solved exactly instead of by their approximate factorisation.
//!
//! At a steady state the projection's increment vanishes, so the forced faces hold their
//! constraints exactly and the fluid faces satisfy the steady discrete Navier–Stokes rows:
//! the steady state is the explicit schemes' (and [`super::PeriodicStokesArray`]'s),
//! independent of `Δt`. The residual of the constraints is below `tolerance` times that of
//! the unconstrained solve (K changes by at most 6e-6 relative between tolerances 1e-3 and
//! 1e-8).

use super::gmres::{GmresReport, GmresWorkspace};
use super::immersed_boundary::ImmersedBoundary;
use crate::fluid::ImplicitStage;

/// Krylov vectors kept before GMRES restarts.
const RESTART: usize = 10;

/// What the last constrained solve did (summed over components).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ImplicitForcingReport {
    /// Helmholtz solves used (GMRES products plus one correction per component).
    pub solves: usize,
    /// Largest relative residual `‖g − C u*‖ / ‖g − C u₀‖` over the components.
    pub relative_residual: f64,
    /// Whether some component's GMRES stopped at `max_iterations` above `tolerance`: the
    /// forced faces then hold their constraints only to `relative_residual` (the run goes on
    /// and the log says so).
    pub limit_reached: bool,
    /// The GMRES settings the solve was held to (for the log's message).
    pub tolerance: f64,
    pub max_iterations: usize,
}

/// Solves the stage's Helmholtz problem with the forced faces as constraint rows (see the
/// module docs). Holds its scratch between stages: no allocation once sizes are reached.
pub struct ImplicitForcing {
    /// GMRES stops at `‖g − C u*‖ ≤ tolerance ‖g − C u₀‖`.
    pub tolerance: f64,
    /// Most GMRES products per component and stage.
    pub max_iterations: usize,
    /// Box indices of each forcing face and its two interpolation neighbours.
    rows: Vec<[usize; 3]>,
    weights: Vec<[f64; 2]>,
    rhs: Vec<f64>,
    sources: Vec<f64>,
    /// One component's box of faces (the Helmholtz solve's right-hand side and solution):
    /// the stage's own box, lent while the component is solved
    /// ([`ImplicitStage::lend_box`]), empty otherwise.
    field: Vec<f64>,
    gmres: GmresWorkspace,
    report: ImplicitForcingReport,
    /// Start from the last step's sources (else from zero).
    pub warm_start: bool,
    /// Right-precondition GMRES by the Helmholtz operator restricted to the forcing faces.
    pub preconditioned: bool,
    /// Per forcing face, the index of its six lattice neighbours among the forcing faces
    /// (`NONE` if not one), `±x, ±y, ±z`.
    links: Vec<[u32; 6]>,
    search: Vec<f64>,
    scratch: Vec<f64>,
    /// The last step's sources per stage and component, by face box index, with the
    /// stage's `κ`: the initial guess of the next step's solve, kept with `warm_start` only.
    previous: [[WarmStart; 3]; 3],
}

#[derive(Default)]
struct WarmStart {
    kappa: f64,
    faces: Vec<usize>,
    sources: Vec<f64>,
}

impl Default for ImplicitForcing {
    fn default() -> Self {
        Self::new()
    }
}

impl ImplicitForcing {
    /// Tolerance 1e-3, at most 200 products per component and stage, preconditioned, cold
    /// start (a warm start from the last step saves little and would make a restarted run
    /// differ from an uninterrupted one in the last bits).
    pub fn new() -> Self {
        ImplicitForcing {
            tolerance: 1e-3,
            max_iterations: 200,
            rows: Vec::new(),
            weights: Vec::new(),
            rhs: Vec::new(),
            sources: Vec::new(),
            field: Vec::new(),
            gmres: GmresWorkspace::new(RESTART),
            report: ImplicitForcingReport::default(),
            previous: Default::default(),
            preconditioned: true,
            warm_start: false,
            links: Vec::new(),
            search: Vec::new(),
            scratch: Vec::new(),
        }
    }

    /// The last solve's cost and residual.
    pub fn report(&self) -> ImplicitForcingReport {
        self.report
    }

    /// Replaces the stage's unconstrained solution `velocity` (padded; `A u₀ = r`) by the
    /// solution of the constrained system on the forcing faces of `boundary`. Interior
    /// faces are left to [`ImmersedBoundary::impose`], which the caller runs afterwards (it
    /// then sets the forcing faces to their constraints exactly, a change of the order of
    /// the GMRES residual, and the closed cells' sources).
    pub fn solve(
        &mut self,
        boundary: &ImmersedBoundary,
        velocity: &mut [Vec<f64>; 3],
        stage: &mut ImplicitStage<'_>,
    ) {
        self.report = ImplicitForcingReport {
            tolerance: self.tolerance,
            max_iterations: self.max_iterations,
            ..Default::default()
        };
        for c in 0..3 {
            let faces = boundary.forcing_faces(c);
            if faces.is_empty() {
                continue;
            }
            let u = &velocity[c];
            self.rows.clear();
            self.weights.clear();
            self.rhs.clear();
            for f in faces {
                let index = |slot: u32| {
                    stage
                        .box_index(c, slot as usize)
                        .expect("forcing faces and their neighbours are momentum faces")
                };
                self.rows.push([
                    index(f.slot),
                    index(f.neighbours[0]),
                    index(f.neighbours[1]),
                ]);
                self.weights.push(f.weights);
                let [a1, a2] = f.weights;
                let target = (1.0 - a1 - a2) * f.wall;
                let [n1, n2] = f.neighbours.map(|n| n as usize);
                let current = u[f.slot as usize] - a1 * u[n1] - a2 * u[n2];
                self.rhs.push(target - current);
            }
            for g in boundary.gap_faces(c) {
                let f = &faces[g.face as usize];
                self.rhs[g.face as usize] += g.weight * (g.wall - f.wall);
            }
            // A throat's face holds its stage target (its row's weights are the staircase's).
            for t in boundary.throat_faces(c) {
                let f = &faces[t.face as usize];
                self.rhs[t.face as usize] += t.target - f.wall;
            }
            self.field = stage.lend_box(c);
            self.field.clear();
            self.field.resize(stage.box_len(c), 0.0);
            self.warm_start(stage, c);
            self.link_neighbours(stage, c);
            let h = stage.h();
            let coupling: [f64; 3] = std::array::from_fn(|d| stage.kappa() / (h[d] * h[d]));
            let ImplicitForcing {
                rows,
                weights,
                links,
                rhs,
                sources,
                search,
                scratch,
                field,
                gmres,
                tolerance,
                max_iterations,
                preconditioned,
                ..
            } = self;
            let preconditioned = *preconditioned;
            let cold = norm(rhs);
            let mut solves = 0;
            // The warm start's residual: rhs ← b − S φ₀.
            if sources.iter().any(|&v| v != 0.0) {
                capacitance_product(stage, c, rows, weights, sources, field, scratch);
                solves += 1;
                for (r, s) in rhs.iter_mut().zip(scratch.iter()) {
                    *r -= s;
                }
            }
            let warm = norm(rhs);
            // Right-preconditioned: S M⁻¹ z = rhs, φ = φ₀ + M⁻¹ z.
            search.clear();
            search.resize(rows.len(), 0.0);
            let mut apply = |z: &[f64], out: &mut [f64]| {
                if preconditioned {
                    restricted_helmholtz(links, coupling, z, out);
                    capacitance_product(stage, c, rows, weights, out, field, scratch);
                    out.copy_from_slice(scratch);
                } else {
                    capacitance_product(stage, c, rows, weights, z, field, out);
                }
            };
            let relative = if warm > 0.0 {
                *tolerance * cold / warm
            } else {
                1.0
            };
            let GmresReport {
                iterations,
                relative_residual,
            } = gmres.solve(&mut apply, rhs, search, relative, *max_iterations);
            solves += iterations;
            if preconditioned {
                restricted_helmholtz(links, coupling, search, scratch);
            } else {
                scratch.copy_from_slice(search);
            }
            for (s, z) in sources.iter_mut().zip(scratch.iter()) {
                *s += z;
            }
            correction(stage, c, rows, sources, field);
            stage.add_to_velocity(c, field, &mut velocity[c]);
            let relative_residual = if cold > 0.0 {
                relative_residual * warm / cold
            } else {
                0.0
            };
            stage.return_box(c, std::mem::take(&mut self.field));
            if self.warm_start {
                let warm = &mut self.previous[stage.index()][c];
                warm.kappa = stage.kappa();
                warm.faces.clear();
                warm.faces.extend(self.rows.iter().map(|r| r[0]));
                warm.sources.clear();
                warm.sources.extend_from_slice(&self.sources);
            }
            self.report.solves += solves + 1;
            self.report.relative_residual = self.report.relative_residual.max(relative_residual);
            if iterations >= *max_iterations && relative_residual > *tolerance {
                self.report.limit_reached = true;
            }
        }
    }
}

impl ImplicitForcing {
    /// The initial sources: the same stage's of the last step on the faces that were
    /// forcing faces then, scaled by the ratio of the `κ`s (the sources are `A u* − r` on
    /// the forced rows, which grow with `Δt`); zero on new faces. Leaves `field` zeroed.
    fn warm_start(&mut self, stage: &ImplicitStage<'_>, c: usize) {
        let warm = &self.previous[stage.index()][c];
        self.sources.clear();
        self.sources.resize(self.rows.len(), 0.0);
        if warm.faces.is_empty() || !self.warm_start {
            return;
        }
        let scale = stage.kappa() / warm.kappa;
        for (&b, &s) in warm.faces.iter().zip(&warm.sources) {
            self.field[b] = s;
        }
        for (row, s) in self.rows.iter().zip(self.sources.iter_mut()) {
            *s = scale * self.field[row[0]];
        }
        for &b in &warm.faces {
            self.field[b] = 0.0;
        }
    }
}

impl ImplicitForcing {
    /// Fills `links` for the forcing faces in `rows` (and sizes `scratch`). Marks the
    /// forcing faces in `field` (forcing index + 1; `field` is zero on entry and on exit).
    fn link_neighbours(&mut self, stage: &ImplicitStage<'_>, c: usize) {
        for (i, row) in self.rows.iter().enumerate() {
            self.field[row[0]] = (i + 1) as f64;
        }
        self.links.clear();
        for row in &self.rows {
            let mut link = [NONE; 6];
            for d in 0..3 {
                for (side, forward) in [false, true].into_iter().enumerate() {
                    if let Some(b) = stage.neighbour(c, row[0], d, forward) {
                        let mark = self.field[b];
                        if mark > 0.0 {
                            link[2 * d + side] = mark as u32 - 1;
                        }
                    }
                }
            }
            self.links.push(link);
        }
        for row in &self.rows {
            self.field[row[0]] = 0.0;
        }
        self.scratch.resize(self.rows.len(), 0.0);
    }
}

/// No neighbour among the forcing faces.
const NONE: u32 = u32::MAX;

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// `out = A_FF v`: the Helmholtz operator `I − κ∇²` restricted to the forcing faces (the
/// rows and columns of `A` on `F`), an approximate inverse of `E' A⁻¹ E` that needs no
/// solve: `out_i = (1 + 2 Σ_d κ/h_d²) v_i − Σ_d κ/h_d² Σ_± v_{i±d}` over neighbours in `F`.
fn restricted_helmholtz(links: &[[u32; 6]], coupling: [f64; 3], v: &[f64], out: &mut [f64]) {
    let diagonal = 1.0 + 2.0 * (coupling[0] + coupling[1] + coupling[2]);
    for (i, link) in links.iter().enumerate() {
        let mut x = diagonal * v[i];
        for (k, &j) in link.iter().enumerate() {
            if j != NONE {
                x -= coupling[k / 2] * v[j as usize];
            }
        }
        out[i] = x;
    }
}

/// `out = S φ = C A⁻¹ E φ` (one homogeneous Helmholtz solve into `field`).
fn capacitance_product(
    stage: &mut ImplicitStage<'_>,
    c: usize,
    rows: &[[usize; 3]],
    weights: &[[f64; 2]],
    phi: &[f64],
    field: &mut [f64],
    out: &mut [f64],
) {
    correction(stage, c, rows, phi, field);
    for (i, row) in rows.iter().enumerate() {
        let [a1, a2] = weights[i];
        out[i] = field[row[0]] - a1 * field[row[1]] - a2 * field[row[2]];
    }
}

/// `field = A⁻¹ E φ` for component `c`: the sources on the forcing faces, then one
/// homogeneous Helmholtz solve.
fn correction(
    stage: &mut ImplicitStage<'_>,
    c: usize,
    rows: &[[usize; 3]],
    phi: &[f64],
    field: &mut [f64],
) {
    field.iter_mut().for_each(|v| *v = 0.0);
    for (row, p) in rows.iter().zip(phi) {
        field[row[0]] += p;
    }
    stage.solve_homogeneous(c, field);
}
