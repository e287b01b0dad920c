//! No-slip on spheres on the staggered grid: sharp-interface direct forcing.
//!
//! # The choice
//!
//! The paper imposes `v = v_p + ω_p × (x − x_p)` by setting the velocity samples inside each
//! sphere (a staircase: the effective surface wanders by up to half a cell, a first-order
//! error that changes erratically with the sphere's position). fsim keeps that for the
//! samples inside and adds, for every *forcing face* (a face outside all spheres with a
//! neighbour of the same component inside one), the linear interpolation of Fadlun, Verzicco,
//! Orlandi & Mohd-Yusof (J. Comput. Phys. 161, 35–60, 2000) along the grid line that crosses
//! the surface:
//!
//! ```text
//!   inside    forcing face f      f₂ (fluid)
//!     o----x-------o-----------------o          x: surface, distance δ from f along the line
//!          w       u_f = w + (u_f₂ − w) δ / (δ + h)
//! ```
//!
//! with `w` the rigid velocity at the crossing. The surface then sits where the sphere is to
//! `O(h²)` and the velocity is second order; the interpolation weight `δ/(δ+h) ∈ [0, ½)`
//! never amplifies. Of the lines through a forcing face that cross the surface, the one most
//! nearly normal to it is used. Where `f₂` is itself in a sphere or forced (a gap narrower
//! than about two cells) the face takes `w` (staircase fallback).
//!
//! Against the alternatives (measured in `docs/direct_model.md`): the pure staircase gives
//! first-order, position-dependent drag; Uhlmann's (J. Comput. Phys. 209, 448–476, 2005)
//! regularised-delta forcing smears the surface over three cells and needs an empirical
//! radius retraction; volume-fraction weighting is first order at the surface.
//!
//! # Time stepping
//!
//! The forcing acts in [`FluidSolver::step_with`](crate::fluid::FluidSolver::step_with)'s
//! hook, on each stage's predicted velocity, before the projection. The projection then
//! subtracts `τ∇p`; the hook pre-compensates with the pressure of the previous projection
//! (`u_f* = target + τ ∂p`), so that once the flow is steady the forced faces hold their
//! targets exactly and the steady state does not depend on `Δt` (the explicit schemes).
//! `RK3CN`'s incremental projection needs no compensation (its increment vanishes at steady
//! state); there the forcing faces are constraint rows of the implicit viscous solve itself
//! ([`super::ImplicitForcing`]), so that its steady state does not depend on `Δt` either.

use super::rigid_sphere::RigidSphere;
use crate::fluid::{BoundaryConditions, FaceCondition, PaddedLayout};
use crate::grid::Grid;

/// A face inside a sphere: it moves with the sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InteriorFace {
    /// Padded index of the face.
    pub slot: usize,
    /// Cell-centred (unpadded) indices of the cells below and above the face along its
    /// component, for the pressure compensation.
    pub cells: [usize; 2],
    /// Rigid velocity (this component) at the face, m/s.
    pub target: f64,
}

/// A fluid face next to a sphere: `u = w + Σ_k a_k (u_k − w)` over the next one or two
/// fluid faces `k` along the interpolation line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForcingFace {
    pub slot: usize,
    pub cells: [usize; 2],
    /// The next two fluid faces along the interpolation line, away from the sphere (the
    /// second equals the first for the linear stencil).
    pub neighbours: [usize; 2],
    pub neighbour_cells: [[usize; 2]; 2],
    /// Interpolation weights: linear `[δ/(δ+h), 0]`, quadratic
    /// `[2δ/(δ+h), −δ/(δ+2h)]`; `[0, 0]` for the staircase fallback.
    pub weights: [f64; 2],
    /// Rigid velocity (this component) where the line crosses the surface, m/s.
    pub wall: f64,
}

/// A cell all of whose six faces are forced: its divergence is set by the forcing, not by
/// the projection (it gets a mass source).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosedCell {
    /// Unpadded cell index.
    pub cell: usize,
    /// Padded slots of its low and high face per component (periodic wraps resolved).
    pub faces: [[usize; 2]; 3],
}

/// Label of a face outside every sphere.
const FLUID: u32 = 0;
/// Label of a forcing face (inside faces hold `sphere index + 1`).
const FORCING: u32 = u32::MAX;

/// The forced faces of every velocity component for a set of spheres, rebuilt by
/// [`ImmersedBoundary::update`] whenever they move, and imposed by
/// [`ImmersedBoundary::impose`] in each stage of the fluid step.
///
/// Works on any box: faces the momentum equation does not advance (boundary faces) are
/// never forced, periodic images of a sphere are found by wrapping indices.
pub struct ImmersedBoundary {
    grid: Grid,
    layout: PaddedLayout,
    periodic: [bool; 3],
    /// Advanced face slots per component and direction (inclusive), as the fluid solver's.
    ranges: [[(usize, usize); 3]; 3],
    labels: [Vec<u32>; 3],
    touched: [Vec<usize>; 3],
    interior: [Vec<InteriorFace>; 3],
    forcing: [Vec<ForcingFace>; 3],
    /// Cells with every face forced, and those of the previous update (their mass source
    /// is cleared at the next imposition).
    closed: Vec<ClosedCell>,
    previous_closed: Vec<usize>,
    /// Scratch of the closed-cell search: a mark per cell (0 outside the search) and the
    /// cells next to forced faces.
    cell_marks: Vec<u8>,
    near_cells: Vec<usize>,
    /// Scratch: candidate forcing faces `(unwrapped lattice index, slot)`.
    candidates: Vec<([isize; 3], usize)>,
    /// Quadratic (two fluid faces) rather than linear forcing stencil.
    quadratic: bool,
}

impl ImmersedBoundary {
    /// An empty boundary (no spheres) for a grid and its fluid conditions.
    pub fn new(grid: &Grid, bc: &BoundaryConditions) -> Self {
        let layout = PaddedLayout::new(grid.n);
        let periodic = std::array::from_fn(|d| matches!(bc.face(d, 0), FaceCondition::Periodic));
        let ranges =
            std::array::from_fn(|c| std::array::from_fn(|d| bc.momentum_range(grid.n, c, d)));
        ImmersedBoundary {
            grid: grid.clone(),
            labels: std::array::from_fn(|_| vec![FLUID; layout.len]),
            layout,
            periodic,
            ranges,
            touched: Default::default(),
            interior: Default::default(),
            forcing: Default::default(),
            closed: Vec::new(),
            previous_closed: Vec::new(),
            cell_marks: vec![0; grid.cell_count()],
            near_cells: Vec::new(),
            candidates: Vec::new(),
            quadratic: true,
        }
    }

    /// Chooses the forcing stencil: quadratic through the wall and two fluid faces
    /// (default), or linear through the wall and one; applies from the next update.
    pub fn set_quadratic(&mut self, quadratic: bool) {
        self.quadratic = quadratic;
    }

    /// Cells whose six faces are all forced.
    pub fn closed_cells(&self) -> &[ClosedCell] {
        &self.closed
    }

    /// Faces inside spheres, per component.
    pub fn interior_faces(&self, c: usize) -> &[InteriorFace] {
        &self.interior[c]
    }

    /// Forcing faces, per component.
    pub fn forcing_faces(&self, c: usize) -> &[ForcingFace] {
        &self.forcing[c]
    }

    /// Total number of forced faces (interior and forcing, all components).
    pub fn forced_count(&self) -> usize {
        (0..3)
            .map(|c| self.interior[c].len() + self.forcing[c].len())
            .sum()
    }

    /// Whether the face of component `c` at padded index `slot` lies inside a sphere.
    pub fn is_inside(&self, c: usize, slot: usize) -> bool {
        let l = self.labels[c][slot];
        l != FLUID && l != FORCING
    }

    /// Position of the sample of component `c` (`None`: cell centre) at lattice index `m`.
    fn position(&self, c: usize, m: [isize; 3]) -> [f64; 3] {
        let g = &self.grid;
        std::array::from_fn(|d| {
            let offset = if c == d { 0.0 } else { 0.5 };
            g.origin[d] + (m[d] as f64 + offset) * g.h[d]
        })
    }

    /// Padded slot of lattice index `m` of component `c`, if the fluid advances that face.
    fn slot(&self, c: usize, m: [isize; 3]) -> Option<usize> {
        let mut s = [0usize; 3];
        for d in 0..3 {
            let n = self.grid.n[d] as isize;
            let md = if self.periodic[d] {
                m[d].rem_euclid(n)
            } else {
                m[d]
            };
            let slot = md + 1;
            let (lo, hi) = self.ranges[c][d];
            if slot < lo as isize || slot > hi as isize {
                return None;
            }
            s[d] = slot as usize;
        }
        Some(self.layout.index(s[0], s[1], s[2]))
    }

    /// Cells below and above face slot `slot` of component `c` (unpadded indices).
    fn cells(&self, c: usize, slot: usize) -> [usize; 2] {
        let l = &self.layout;
        let mut s = [
            slot % l.dims[0],
            (slot / l.dims[0]) % l.dims[1],
            slot / l.plane_len(),
        ];
        let n = self.grid.n;
        let hi = self.grid.cell_index(
            (s[0] - 1).min(n[0] - 1),
            (s[1] - 1).min(n[1] - 1),
            (s[2] - 1).min(n[2] - 1),
        );
        // The cell below along c (periodic wrap at slot 1).
        s[c] = if s[c] >= 2 { s[c] - 1 } else { n[c] };
        let lo = self.grid.cell_index(
            (s[0] - 1).min(n[0] - 1),
            (s[1] - 1).min(n[1] - 1),
            (s[2] - 1).min(n[2] - 1),
        );
        [lo, hi]
    }

    /// Lattice box of component `c` samples within `margin` cells of the sphere.
    fn bounds(&self, c: usize, s: &RigidSphere, margin: isize) -> [(isize, isize); 3] {
        let g = &self.grid;
        std::array::from_fn(|d| {
            let offset = if c == d { 0.0 } else { 0.5 };
            let lo = ((s.centre[d] - s.radius - g.origin[d]) / g.h[d] - offset).floor() as isize;
            let hi = ((s.centre[d] + s.radius - g.origin[d]) / g.h[d] - offset).ceil() as isize;
            (lo - margin, hi + margin)
        })
    }

    /// `x − x_p` for the nearest periodic image of sphere `s`.
    fn relative(&self, x: [f64; 3], s: &RigidSphere) -> [f64; 3] {
        let len = self.grid.length();
        std::array::from_fn(|d| {
            let mut r = x[d] - s.centre[d];
            if self.periodic[d] {
                r -= len[d] * (r / len[d]).round();
            }
            r
        })
    }

    /// Rebuilds the forced faces for `spheres` (positions, sizes and velocities).
    pub fn update(&mut self, spheres: &[RigidSphere]) {
        for c in 0..3 {
            for &slot in &self.touched[c] {
                self.labels[c][slot] = FLUID;
            }
            self.touched[c].clear();
            self.interior[c].clear();
            self.forcing[c].clear();
        }
        for c in 0..3 {
            self.mark_interior(c, spheres);
            self.mark_forcing(c, spheres);
        }
        self.find_closed_cells();
    }

    /// Cells next to forced faces whose six faces are all forced. Their divergence is
    /// whatever the forcing imposes (the interpolated forcing faces do not conserve mass
    /// cell by cell): the imposition hands it to the projection as a mass source
    /// (Kim, Kim & Choi 2001), else the pressure would absorb the mismatch without end.
    fn find_closed_cells(&mut self) {
        self.previous_closed.clear();
        self.previous_closed
            .extend(self.closed.iter().map(|c| c.cell));
        self.closed.clear();
        // The cells next to forced faces ("near" cells).
        let mut near = std::mem::take(&mut self.near_cells);
        near.clear();
        for c in 0..3 {
            for f in &self.interior[c] {
                near.extend_from_slice(&f.cells);
            }
            for f in &self.forcing[c] {
                near.extend_from_slice(&f.cells);
            }
        }
        near.sort_unstable();
        near.dedup();
        const NEAR: u8 = 1;
        const REACHED: u8 = 2;
        const CLOSED: u8 = 3;
        for &cell in &near {
            self.cell_marks[cell] = NEAR;
        }
        // Open near cells are reached from the open fluid through free faces (a search from
        // every near cell with a free face onto a cell that is not near); the open near
        // cells left unreached form pockets enclosed by forced faces: closed too.
        let mut queue: Vec<usize> = Vec::new();
        for &cell in &near {
            let Some(faces) = self.cell_faces(cell) else {
                self.cell_marks[cell] = REACHED;
                queue.push(cell);
                continue;
            };
            let mut all_forced = true;
            let mut seed = false;
            for c in 0..3 {
                for side in 0..2 {
                    if self.forced(c, faces[c][side]) {
                        continue;
                    }
                    all_forced = false;
                    match self.neighbour_cell(cell, c, side) {
                        Some(next) if self.cell_marks[next] != 0 => {}
                        _ => seed = true,
                    }
                }
            }
            if all_forced {
                self.cell_marks[cell] = CLOSED;
                self.closed.push(ClosedCell { cell, faces });
            } else if seed {
                self.cell_marks[cell] = REACHED;
                queue.push(cell);
            }
        }
        while let Some(cell) = queue.pop() {
            let Some(faces) = self.cell_faces(cell) else {
                continue;
            };
            for c in 0..3 {
                for side in 0..2 {
                    if self.forced(c, faces[c][side]) {
                        continue;
                    }
                    if let Some(next) = self.neighbour_cell(cell, c, side) {
                        if self.cell_marks[next] == NEAR {
                            self.cell_marks[next] = REACHED;
                            queue.push(next);
                        }
                    }
                }
            }
        }
        for &cell in &near {
            if self.cell_marks[cell] == NEAR {
                if let Some(faces) = self.cell_faces(cell) {
                    self.closed.push(ClosedCell { cell, faces });
                }
            }
            self.cell_marks[cell] = 0;
        }
        self.near_cells = near;
    }

    fn forced(&self, c: usize, slot: usize) -> bool {
        self.labels[c][slot] != FLUID
    }

    /// The six face slots of a cell, if the fluid advances them all (periodic wraps
    /// resolved); `None` next to a bounded face.
    fn cell_faces(&self, cell: usize) -> Option<[[usize; 2]; 3]> {
        let n = self.grid.n;
        let l = &self.layout;
        let idx = [cell % n[0], (cell / n[0]) % n[1], cell / (n[0] * n[1])];
        let low = l.index(idx[0] + 1, idx[1] + 1, idx[2] + 1);
        let mut faces = [[0usize; 2]; 3];
        for c in 0..3 {
            let (lo, hi) = self.ranges[c][c];
            if idx[c] + 1 < lo || idx[c] + 2 > hi + usize::from(self.periodic[c]) {
                return None;
            }
            let high = if idx[c] + 1 < n[c] {
                low + l.stride[c]
            } else {
                low - (n[c] - 1) * l.stride[c]
            };
            faces[c] = [low, high];
        }
        Some(faces)
    }

    /// The cell across face `side` (0 low, 1 high) along `c`, if inside the box or wrapped.
    fn neighbour_cell(&self, cell: usize, c: usize, side: usize) -> Option<usize> {
        let n = self.grid.n;
        let mut idx = [cell % n[0], (cell / n[0]) % n[1], cell / (n[0] * n[1])];
        if side == 0 {
            if idx[c] == 0 {
                if !self.periodic[c] {
                    return None;
                }
                idx[c] = n[c] - 1;
            } else {
                idx[c] -= 1;
            }
        } else if idx[c] + 1 == n[c] {
            if !self.periodic[c] {
                return None;
            }
            idx[c] = 0;
        } else {
            idx[c] += 1;
        }
        Some(self.grid.cell_index(idx[0], idx[1], idx[2]))
    }

    fn mark_interior(&mut self, c: usize, spheres: &[RigidSphere]) {
        for (k, s) in spheres.iter().enumerate() {
            let b = self.bounds(c, s, 1);
            let r2 = s.radius * s.radius;
            for m2 in b[2].0..=b[2].1 {
                for m1 in b[1].0..=b[1].1 {
                    for m0 in b[0].0..=b[0].1 {
                        let m = [m0, m1, m2];
                        let x = self.position(c, m);
                        let rel = [x[0] - s.centre[0], x[1] - s.centre[1], x[2] - s.centre[2]];
                        if rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2] >= r2 {
                            continue;
                        }
                        let Some(slot) = self.slot(c, m) else {
                            continue;
                        };
                        if self.labels[c][slot] != FLUID {
                            continue;
                        }
                        self.labels[c][slot] = k as u32 + 1;
                        self.touched[c].push(slot);
                        let cells = self.cells(c, slot);
                        self.interior[c].push(InteriorFace {
                            slot,
                            cells,
                            target: s.velocity_at(rel)[c],
                        });
                    }
                }
            }
        }
    }

    /// Sphere index of the face at lattice index `m`, if inside one.
    fn inside_at(&self, c: usize, m: [isize; 3]) -> Option<usize> {
        let slot = self.slot(c, m)?;
        let l = self.labels[c][slot];
        (l != FLUID && l != FORCING).then(|| (l - 1) as usize)
    }

    fn mark_forcing(&mut self, c: usize, spheres: &[RigidSphere]) {
        let mut candidates = std::mem::take(&mut self.candidates);
        candidates.clear();
        let h_max = self.grid.h.iter().cloned().fold(0.0, f64::max);
        for s in spheres {
            let b = self.bounds(c, s, 2);
            // A face with a neighbour inside this sphere lies within one cell of its surface
            // (faces near other spheres are found from those).
            let reach = (s.radius + h_max) * (s.radius + h_max);
            for m2 in b[2].0..=b[2].1 {
                for m1 in b[1].0..=b[1].1 {
                    for m0 in b[0].0..=b[0].1 {
                        let m = [m0, m1, m2];
                        let x = self.position(c, m);
                        let rel = [x[0] - s.centre[0], x[1] - s.centre[1], x[2] - s.centre[2]];
                        if rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2] >= reach {
                            continue;
                        }
                        let Some(slot) = self.slot(c, m) else {
                            continue;
                        };
                        if self.labels[c][slot] != FLUID {
                            continue;
                        }
                        let near = (0..3).any(|d| {
                            [-1, 1].iter().any(|&step| {
                                let mut q = m;
                                q[d] += step;
                                self.inside_at(c, q).is_some()
                            })
                        });
                        if near {
                            self.labels[c][slot] = FORCING;
                            self.touched[c].push(slot);
                            candidates.push((m, slot));
                        }
                    }
                }
            }
        }
        for &(m, slot) in &candidates {
            let x = self.position(c, m);
            // The line most nearly normal to the surface among those crossing it.
            let mut best: Option<(f64, usize, isize, usize)> = None;
            for d in 0..3 {
                for step in [-1isize, 1] {
                    let mut q = m;
                    q[d] += step;
                    if let Some(k) = self.inside_at(c, q) {
                        let rel = self.relative(x, &spheres[k]);
                        let norm = (rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2]).sqrt();
                        // Outward direction along the line is −step.
                        let score = -(step as f64) * rel[d] / norm.max(f64::MIN_POSITIVE);
                        if best.is_none_or(|b| score > b.0) {
                            best = Some((score, d, step, k));
                        }
                    }
                }
            }
            let (_, d, step, k) = best.expect("a candidate has an inside neighbour");
            let s = &spheres[k];
            let h = self.grid.h[d];
            let rel = self.relative(x, s);
            // Distance t from x towards the inside neighbour (direction step·e_d) to the
            // surface: |rel + t step e_d| = r, the smaller root.
            let b = step as f64 * rel[d];
            let q = rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2] - s.radius * s.radius;
            let disc = (b * b - q).max(0.0);
            let t = (-b - disc.sqrt()).clamp(0.0, h);
            let mut crossing = rel;
            crossing[d] += step as f64 * t;
            let wall = s.velocity_at(crossing)[c];
            let mut outer = m;
            outer[d] -= step;
            let mut outer2 = outer;
            outer2[d] -= step;
            let free = |q: [isize; 3]| self.slot(c, q).filter(|&n| self.labels[c][n] == FLUID);
            let cells = self.cells(c, slot);
            let face = match (free(outer), free(outer2)) {
                (Some(n1), Some(n2)) if self.quadratic => ForcingFace {
                    slot,
                    cells,
                    neighbours: [n1, n2],
                    neighbour_cells: [self.cells(c, n1), self.cells(c, n2)],
                    weights: [2.0 * t / (t + h), -t / (t + 2.0 * h)],
                    wall,
                },
                (Some(n1), _) => ForcingFace {
                    slot,
                    cells,
                    neighbours: [n1, n1],
                    neighbour_cells: [self.cells(c, n1); 2],
                    weights: [t / (t + h), 0.0],
                    wall,
                },
                (None, _) => ForcingFace {
                    slot,
                    cells,
                    neighbours: [slot, slot],
                    neighbour_cells: [cells, cells],
                    weights: [0.0, 0.0],
                    wall,
                },
            };
            self.forcing[c].push(face);
        }
        self.candidates = candidates;
    }

    /// Imposes the rigid motion on a stage's predicted velocity (padded), so that after the
    /// coming projection `u ← u − τ∇p` the forced faces hold their targets (exactly when the
    /// pressure `p` the hook sees is the one the projection subtracts; see the module docs).
    /// `tau = 0` or an empty `pressure` imposes the targets as they are. With a `mass_source`, every
    /// [`ClosedCell`] gets the divergence the imposed faces give it (less their mean, so that
    /// the sources sum to zero), the others zero.
    pub fn impose(
        &self,
        velocity: &mut [Vec<f64>; 3],
        pressure: &[f64],
        tau: f64,
        mass_source: Option<&mut [f64]>,
    ) {
        for c in 0..3 {
            let u = &mut velocity[c];
            let scale = tau / self.grid.h[c];
            let correction = |cells: [usize; 2]| {
                if tau == 0.0 || pressure.is_empty() {
                    0.0
                } else {
                    scale * (pressure[cells[1]] - pressure[cells[0]])
                }
            };
            for f in &self.interior[c] {
                u[f.slot] = f.target + correction(f.cells);
            }
            for f in &self.forcing[c] {
                let mut value = f.wall + correction(f.cells);
                for k in 0..2 {
                    let outer = u[f.neighbours[k]] - correction(f.neighbour_cells[k]);
                    value += f.weights[k] * (outer - f.wall);
                }
                u[f.slot] = value;
            }
        }
        if let Some(q) = mass_source {
            for &cell in &self.previous_closed {
                q[cell] = 0.0;
            }
            let mut total = 0.0;
            for cc in &self.closed {
                let div = self.divergence(velocity, cc);
                q[cc.cell] = div;
                total += div;
            }
            let mean = total / self.closed.len().max(1) as f64;
            for cc in &self.closed {
                q[cc.cell] -= mean;
            }
        }
    }

    /// Discrete divergence of `velocity` in a closed cell.
    pub fn divergence(&self, velocity: &[Vec<f64>; 3], cell: &ClosedCell) -> f64 {
        (0..3)
            .map(|c| {
                (velocity[c][cell.faces[c][1]] - velocity[c][cell.faces[c][0]]) / self.grid.h[c]
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn periodic_boundary(n: usize, h: f64) -> ImmersedBoundary {
        let grid = Grid::new([n; 3], [h; 3], [0.0; 3]);
        ImmersedBoundary::new(&grid, &BoundaryConditions::periodic())
    }

    #[test]
    fn interior_faces_fill_the_sphere_volume_and_forcing_faces_surround_it() {
        let h = 0.1;
        let mut ib = periodic_boundary(24, h);
        let mut sphere = RigidSphere::fixed([1.2, 1.23, 1.17], 0.61);
        sphere.velocity = [0.3, 0.0, 0.0];
        sphere.angular_velocity = [0.0, 0.0, 1.0];
        ib.update(&[sphere]);
        for c in 0..3 {
            // Samples inside ≈ volume / h³ (staircase error of the count ~ area/h²).
            let count = ib.interior_faces(c).len() as f64;
            let expected = sphere.volume() / (h * h * h);
            assert!(
                (count / expected - 1.0).abs() < 0.03,
                "{count} vs {expected}"
            );
            for f in ib.forcing_faces(c) {
                assert!(f.weights[0] >= 0.0 && f.weights[0] <= 1.0);
                assert!(f.weights[1] <= 0.0 && f.weights[1] >= -1.0 / 3.0);
                assert!(!ib.is_inside(c, f.neighbours[0]) && !ib.is_inside(c, f.neighbours[1]));
            }
            assert!(!ib.forcing_faces(c).is_empty());
        }
        // The rigid velocity of an interior x face: 0.3 − ω (y − y_p).
        let f = ib.interior_faces(0)[0];
        assert!(f.target.abs() < 0.3 + 0.61 + 1e-12);
    }

    #[test]
    fn a_sphere_across_the_periodic_boundary_is_found_whole() {
        let h = 0.1;
        let mut a = periodic_boundary(20, h);
        let mut b = periodic_boundary(20, h);
        a.update(&[RigidSphere::fixed([1.03, 1.07, 0.98], 0.45)]);
        // The same sphere shifted by a whole number of cells, straddling the corner.
        b.update(&[RigidSphere::fixed([0.03, 0.07, 1.98], 0.45)]);
        for c in 0..3 {
            assert_eq!(a.interior_faces(c).len(), b.interior_faces(c).len());
            assert_eq!(a.forcing_faces(c).len(), b.forcing_faces(c).len());
        }
    }

    #[test]
    fn impose_sets_targets_and_interpolates() {
        let h = 0.1;
        let mut ib = periodic_boundary(16, h);
        let mut sphere = RigidSphere::fixed([0.8, 0.8, 0.8], 0.33);
        sphere.velocity = [1.0, -2.0, 0.5];
        ib.update(&[sphere]);
        let layout = PaddedLayout::new([16; 3]);
        let mut u: [Vec<f64>; 3] = std::array::from_fn(|_| vec![7.0; layout.len]);
        let p = vec![0.0; 16 * 16 * 16];
        ib.impose(&mut u, &p, 0.0, None);
        for c in 0..3 {
            let w = sphere.velocity[c];
            for f in ib.interior_faces(c) {
                assert_eq!(u[c][f.slot], w);
            }
            for f in ib.forcing_faces(c) {
                let expected = w + (f.weights[0] + f.weights[1]) * (7.0 - w);
                assert!((u[c][f.slot] - expected).abs() < 1e-12);
            }
        }
        // A uniform pressure gradient is pre-compensated: +τ ∂p/∂x_c.
        let grid = Grid::new([16; 3], [h; 3], [0.0; 3]);
        let p: Vec<f64> = (0..grid.cell_count())
            .map(|i| (i % 16) as f64 * 0.5)
            .collect();
        ib.impose(&mut u, &p, 0.2, None);
        let f = ib
            .interior_faces(0)
            .iter()
            .find(|f| f.slot % 18 > 2)
            .unwrap();
        assert!((u[0][f.slot] - (1.0 + 0.2 * 0.5 / h)).abs() < 1e-12);
    }
}
