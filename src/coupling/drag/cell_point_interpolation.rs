//! OpenFOAM's `cellPoint` interpolation of the fluid velocity at a particle, on fsim's
//! uniform staggered grid, so that a DPMFoam case asking for it gets it.
//!
//! OpenFOAM (`interpolationCellPoint`, `volPointInterpolation`, v1912) interpolates linearly
//! inside the tetrahedron of the particle's cell that holds it. A cell is split into one
//! pyramid per face (apex at the cell centre), each face into two triangles, so a hexahedron
//! has 12 tetrahedra with the corners `(x_c, p_a, p_b, p_d)`:
//!
//! `u(x) = λ_c u_c + λ_a u_a + λ_b u_b + λ_d u_d`, `λ` the barycentric coordinates of `x`.
//!
//! - `u_c`: the cell-centred velocity (on the staggered grid the mean of the cell's two faces
//!   per component, as for the `cell` interpolation).
//! - `u_p` at an interior point: the inverse-distance weighted mean of the cells around it
//!   (on a uniform grid, the plain mean of 8 cells; periodic directions wrap).
//! - `u_p` at a boundary point: the inverse-distance weighted mean of the boundary faces
//!   around it, over every boundary plane it lies on (`w = 1/|x_p − x_f|`). A boundary face
//!   holds the condition's value: the normal component is the staggered face velocity, a
//!   tangential one the mean of the cell and its ghost (zero at a no-slip wall, the cell's
//!   value at a symmetry plane or a zero-gradient outlet, the inlet's value at an inlet).
//!   At a symmetry plane the normal component is zero, which is OpenFOAM's point constraint.
//!
//! Which diagonal splits a face into triangles follows, in OpenFOAM, the point order of the
//! face (its base point). fsim takes the diagonal through the face's corner nearest the
//! origin for every face. Both choices are exact for linear fields and differ by
//! `O(h² ∇²u)` inside a cell.
//!
//! The point values are refreshed once per step ([`CellPointInterpolation::update`]); a sample
//! then reads 4 values per component ([`CellPointInterpolation::sample`]).
//!
//! A cell-centred field (DPMFoam's `DUcDt` and `curlUcDt`) is interpolated the same way
//! ([`CellPointInterpolation::update_cells`]), its boundary faces taking the value of the cell
//! inside (zero gradient: fsim does not evaluate OpenFOAM's boundary values of the derived
//! fields, which at a no-slip wall are those of the wall's own motion).

use crate::Vec3;
use rayon::prelude::*;

use crate::fluid::{BoundaryConditions, FaceCondition, PaddedLayout};
use crate::grid::Grid;

/// Cell-point interpolation of the velocity (see the module docs).
#[derive(Clone, Debug)]
pub struct CellPointInterpolation {
    grid: Grid,
    layout: PaddedLayout,
    periodic: [bool; 3],
    empty: [bool; 3],
    /// The cell-centred velocity `[u, v, w]` per padded cell (ghost cells included where a
    /// component's faces exist), and the point velocities at the `(n₀+1)(n₁+1)(n₂+1)` points,
    /// x fastest: one read per sample vertex.
    cell: Vec<[f64; 3]>,
    point: Vec<[f64; 3]>,
    /// The boundary points' means as fixed weighted terms (they depend on the grid only):
    /// per point and component `3 p + c`, the range `term_start[3p + c]..term_start[3p + c + 1]`
    /// of `terms` and the weights' sum; an empty range marks an interior point.
    term_start: Vec<u32>,
    terms: Vec<PointTerm>,
    term_weight: Vec<f64>,
}

/// One boundary face in a boundary point's inverse-distance mean: the staggered face
/// `velocity[c][a]` (`b == NORMAL_FACE`), or the mean of the cell-centred values at padded
/// cells `a` and `b` (a tangential component: the cell and its ghost).
#[derive(Clone, Copy, Debug)]
struct PointTerm {
    a: u32,
    b: u32,
    /// The padded cell inside the boundary face (for a cell-centred field).
    inside: u32,
    w: f64,
}

const NORMAL_FACE: u32 = u32::MAX;

impl CellPointInterpolation {
    pub fn new(grid: &Grid, bc: &BoundaryConditions) -> Self {
        let layout = PaddedLayout::new(grid.n);
        let points = (grid.n[0] + 1) * (grid.n[1] + 1) * (grid.n[2] + 1);
        let mut this = CellPointInterpolation {
            grid: grid.clone(),
            periodic: std::array::from_fn(|d| matches!(bc.face(d, 0), FaceCondition::Periodic)),
            empty: std::array::from_fn(|d| matches!(bc.face(d, 0), FaceCondition::Empty)),
            cell: vec![[0.0; 3]; layout.len],
            point: vec![[0.0; 3]; points],
            layout,
            term_start: Vec::new(),
            terms: Vec::new(),
            term_weight: Vec::new(),
        };
        this.build_boundary_terms();
        this
    }

    /// Fills `terms`: for every boundary point and component, the boundary faces of its
    /// inverse-distance mean in the order [`Self::point_value`] sums them (so the sums are
    /// the same bit for bit).
    fn build_boundary_terms(&mut self) {
        let n = self.grid.n;
        let points = (n[0] + 1) * (n[1] + 1) * (n[2] + 1);
        let mut start = Vec::with_capacity(3 * points + 1);
        let mut terms = Vec::new();
        let mut weight = Vec::with_capacity(3 * points);
        start.push(0u32);
        for k in 0..=n[2] {
            for j in 0..=n[1] {
                for i in 0..=n[0] {
                    for c in 0..3 {
                        let sum = self.boundary_terms([i, j, k], c, &mut |t| terms.push(t));
                        weight.push(sum);
                        start.push(u32::try_from(terms.len()).expect("fewer than 2³² terms"));
                    }
                }
            }
        }
        terms.shrink_to_fit();
        self.term_start = start;
        self.terms = terms;
        self.term_weight = weight;
    }

    /// Hands the boundary faces of point `p`'s mean for component `c` to `push` and returns
    /// the sum of their weights (none and 0 for an interior point).
    fn boundary_terms(&self, p: [usize; 3], c: usize, push: &mut dyn FnMut(PointTerm)) -> f64 {
        let l = &self.layout;
        let around: [(usize, usize, Option<bool>); 3] =
            std::array::from_fn(|d| self.cells_around(d, p[d]));
        let index = |slot: [usize; 3]| {
            u32::try_from(l.index(slot[0], slot[1], slot[2])).expect("grid below 2³² slots")
        };
        let h = self.grid.h;
        let mut weights = 0.0;
        for d in 0..3 {
            let Some(high) = around[d].2 else {
                continue;
            };
            let (a, b) = ((d + 1) % 3, (d + 2) % 3);
            let w = 1.0 / (0.25 * (h[a] * h[a] + h[b] * h[b])).sqrt();
            let faces_a = distinct(around[a].0, around[a].1);
            let faces_b = distinct(around[b].0, around[b].1);
            for &sa in faces_a.iter().flatten() {
                for &sb in faces_b.iter().flatten() {
                    let mut slot = [0usize; 3];
                    slot[a] = sa;
                    slot[b] = sb;
                    let term = if c == d {
                        // the staggered face on the boundary plane
                        slot[d] = if high { l.n[d] + 1 } else { 1 };
                        let face = index(slot);
                        slot[d] = if high { l.n[d] } else { 1 };
                        PointTerm {
                            a: face,
                            b: NORMAL_FACE,
                            inside: index(slot),
                            w,
                        }
                    } else {
                        slot[d] = if high { l.n[d] } else { 1 };
                        let inside = index(slot);
                        slot[d] = if high { l.n[d] + 1 } else { 0 };
                        PointTerm {
                            a: inside,
                            b: index(slot),
                            inside,
                            w,
                        }
                    };
                    push(term);
                    weights += w;
                }
            }
        }
        weights
    }

    /// Linear index of point `(i, j, k)`, `0 ≤ i ≤ n₀`.
    #[inline(always)]
    fn point_index(&self, i: usize, j: usize, k: usize) -> usize {
        let n = self.grid.n;
        i + (n[0] + 1) * (j + (n[1] + 1) * k)
    }

    /// Refreshes the cell-centred and point velocities from the face velocities `velocity`
    /// (padded, ghosts filled by the fluid solver).
    pub fn update(&mut self, velocity: &[Vec<f64>; 3]) {
        let l = &self.layout;
        for c in 0..3 {
            let (u, cell) = (&velocity[c], &mut self.cell);
            let s = l.stride[c];
            // Every padded cell whose high face along c exists: slots 0..=n_c along c.
            let mut hi = l.dims;
            hi[c] = l.n[c] + 1;
            for k in 0..hi[2] {
                for j in 0..hi[1] {
                    for i in 0..hi[0] {
                        let f = l.index(i, j, k);
                        cell[f][c] = if self.empty[c] {
                            0.0
                        } else {
                            0.5 * (u[f] + u[f + s])
                        };
                    }
                }
            }
        }
        self.refresh_points(|this, c, p| this.point_value(c, p, velocity));
    }

    /// Refreshes the cell and point values from a cell-centred field `cells` (padded, its
    /// interior filled): the points' values as for the velocity, each boundary face holding
    /// the value of its cell (module docs).
    pub fn update_cells(&mut self, cells: &[[f64; 3]]) {
        self.cell.copy_from_slice(cells);
        self.refresh_points(|this, c, p| this.point_value_of_cells(c, p));
    }

    /// Every point's value, component `c` of point `p` from `value(self, c, p)`, a plane of
    /// points per task.
    fn refresh_points(&mut self, value: impl Fn(&Self, usize, [usize; 3]) -> f64 + Sync) {
        let n = self.grid.n;
        let plane = (n[0] + 1) * (n[1] + 1);
        let mut point = std::mem::take(&mut self.point);
        let this = &*self;
        point
            .par_chunks_mut(plane)
            .enumerate()
            .for_each(|(k, row)| {
                for j in 0..=n[1] {
                    for i in 0..=n[0] {
                        row[i + (n[0] + 1) * j] =
                            std::array::from_fn(|c| value(this, c, [i, j, k]));
                    }
                }
            });
        self.point = point;
    }

    /// [`Self::point_value`] for a cell-centred field: a boundary face holds its cell's value.
    fn point_value_of_cells(&self, c: usize, p: [usize; 3]) -> f64 {
        self.point_mean(c, p, |t| self.cell[t.inside as usize][c])
    }

    /// Component `c` at point `p`: the mean of the 8 cells around an interior point, else the
    /// precomputed weighted mean of the boundary terms, each valued by `term`.
    fn point_mean(&self, c: usize, p: [usize; 3], term: impl Fn(&PointTerm) -> f64) -> f64 {
        let q = 3 * self.point_index(p[0], p[1], p[2]) + c;
        let (first, last) = (self.term_start[q] as usize, self.term_start[q + 1] as usize);
        if first == last {
            return self.interior_mean(c, p);
        }
        let mut sum = 0.0;
        for t in &self.terms[first..last] {
            sum += t.w * term(t);
        }
        sum / self.term_weight[q]
    }

    /// The mean of component `c` over the 8 cells around interior point `p`.
    fn interior_mean(&self, c: usize, p: [usize; 3]) -> f64 {
        let (l, cell) = (&self.layout, &self.cell);
        let around: [(usize, usize); 3] = std::array::from_fn(|d| {
            let (below, above, _) = self.cells_around(d, p[d]);
            (below, above)
        });
        let mut sum = 0.0;
        for k in [around[2].0, around[2].1] {
            for j in [around[1].0, around[1].1] {
                for i in [around[0].0, around[0].1] {
                    sum += cell[l.index(i, j, k)][c];
                }
            }
        }
        sum / 8.0
    }

    /// Along direction `d`, the padded slots of the cells around point index `p` and whether
    /// the point lies on a boundary plane (low or high).
    fn cells_around(&self, d: usize, p: usize) -> (usize, usize, Option<bool>) {
        let n = self.grid.n[d];
        if self.empty[d] {
            return (1, 1, None);
        }
        if self.periodic[d] {
            let below = if p == 0 { n } else { p };
            let above = if p == n { 1 } else { p + 1 };
            return (below, above, None);
        }
        match p {
            0 => (1, 1, Some(false)),
            _ if p == n => (n, n, Some(true)),
            _ => (p, p + 1, None),
        }
    }

    /// The velocity component `c` at point `p` (module docs): the mean of the 8 cells around
    /// an interior point, the precomputed boundary-face mean at a boundary point.
    fn point_value(&self, c: usize, p: [usize; 3], velocity: &[Vec<f64>; 3]) -> f64 {
        let cell = &self.cell;
        self.point_mean(c, p, |t| {
            if t.b == NORMAL_FACE {
                velocity[c][t.a as usize]
            } else {
                0.5 * (cell[t.a as usize][c] + cell[t.b as usize][c])
            }
        })
    }

    /// The velocity at `x` (clamped into the box).
    #[inline]
    pub fn sample(&self, x: Vec3) -> Vec3 {
        let (o, h, n) = (self.grid.origin, self.grid.h, self.grid.n);
        // Cell and local coordinates ξ ∈ [−1, 1] about its centre.
        let mut cell = [0usize; 3];
        let mut xi = [0.0; 3];
        for d in 0..3 {
            let s = ((x[d] - o[d]) / h[d]).clamp(0.0, n[d] as f64);
            let m = (s.floor() as usize).min(n[d] - 1);
            cell[d] = m;
            xi[d] = if self.empty[d] {
                0.0
            } else {
                2.0 * (s - m as f64) - 1.0
            };
        }
        // The pyramid: the face d, side `sign` the point is nearest in ξ.
        let mut d = 0;
        for e in 1..3 {
            if xi[e].abs() > xi[d].abs() {
                d = e;
            }
        }
        let t = xi[d].abs();
        let mut corner_weight = [0.0; 3];
        let mut corners = [0usize; 3];
        let centre_weight = 1.0 - t;
        if t > 0.0 {
            let (a, b) = if d == 0 {
                (1, 2)
            } else if d == 1 {
                (0, 2)
            } else {
                (0, 1)
            };
            let side = usize::from(xi[d] > 0.0);
            let (alpha, beta) = (xi[a] / t, xi[b] / t);
            // Triangles of the face split by its diagonal from (−1, −1) to (1, 1) in (a, b).
            let (local, weight): ([[usize; 2]; 3], [f64; 3]) = if alpha >= beta {
                (
                    [[0, 0], [1, 0], [1, 1]],
                    [
                        0.5 * (1.0 - alpha),
                        0.5 * (alpha - beta),
                        0.5 * (beta + 1.0),
                    ],
                )
            } else {
                (
                    [[0, 0], [1, 1], [0, 1]],
                    [
                        0.5 * (1.0 - beta),
                        0.5 * (alpha + 1.0),
                        0.5 * (beta - alpha),
                    ],
                )
            };
            for q in 0..3 {
                let mut p = cell;
                p[d] += side;
                p[a] += local[q][0];
                p[b] += local[q][1];
                corners[q] = self.point_index(p[0], p[1], p[2]);
                corner_weight[q] = t * weight[q];
            }
        }
        let centre = self.layout.index(cell[0] + 1, cell[1] + 1, cell[2] + 1);
        let (uc, p) = (self.cell[centre], &self.point);
        let (p0, p1, p2) = (p[corners[0]], p[corners[1]], p[corners[2]]);
        let [w0, w1, w2] = corner_weight;
        Vec3::from_fn(|c, _| centre_weight * uc[c] + w0 * p0[c] + w1 * p1[c] + w2 * p2[c])
    }
}

/// The distinct padded slots of a pair (one when both are the same).
#[inline]
fn distinct(a: usize, b: usize) -> [Option<usize>; 2] {
    if a == b {
        [Some(a), None]
    } else {
        [Some(a), Some(b)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::{fill_velocity_ghosts, BoundaryConditions, FaceCondition};

    /// A small LCG for seeded positions.
    fn lcg(state: &mut u64) -> f64 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Seeded random face velocities in a periodic box, and their interpolation.
    fn random_periodic_field(g: &Grid, seed: u64) -> ([Vec<f64>; 3], CellPointInterpolation) {
        let bc = BoundaryConditions::periodic();
        let l = PaddedLayout::new(g.n);
        let mut state = seed;
        let mut faces: [Vec<f64>; 3] =
            std::array::from_fn(|_| (0..l.len).map(|_| lcg(&mut state) - 0.5).collect());
        fill_velocity_ghosts(&l, &bc, &mut faces);
        let mut interp = CellPointInterpolation::new(g, &bc);
        interp.update(&faces);
        (faces, interp)
    }

    fn grid() -> Grid {
        Grid {
            n: [5, 6, 7],
            h: [0.3, 0.2, 0.25],
            origin: [-0.4, 0.1, 0.0],
        }
    }

    /// The linear field `u_c(x) = A_c + B_c · x` of the exactness tests.
    const A: [f64; 3] = [0.3, -1.2, 2.0];
    const B: [[f64; 3]; 3] = [[0.5, -0.2, 1.1], [2.0, 0.3, -0.7], [-1.5, 0.9, 0.4]];

    fn linear_value(x: Vec3) -> [f64; 3] {
        std::array::from_fn(|c| A[c] + B[c][0] * x[0] + B[c][1] * x[1] + B[c][2] * x[2])
    }

    /// Face velocities of the linear field.
    fn linear_faces(g: &Grid) -> [Vec<f64>; 3] {
        let l = PaddedLayout::new(g.n);
        std::array::from_fn(|c| {
            let mut u = vec![0.0; l.len];
            for k in 0..l.dims[2] {
                for j in 0..l.dims[1] {
                    for i in 0..l.dims[0] {
                        let slot = [i, j, k];
                        let x = Vec3::from_fn(|d, _| {
                            let offset = if d == c { 1.0 } else { 0.5 };
                            g.origin[d] + (slot[d] as f64 - offset) * g.h[d]
                        });
                        u[l.index(i, j, k)] = linear_value(x)[c];
                    }
                }
            }
            u
        })
    }

    /// No-slip walls at rest on all six faces.
    fn walls() -> BoundaryConditions {
        BoundaryConditions {
            faces: std::array::from_fn(|_| FaceCondition::Wall { velocity: [0.0; 3] }),
        }
    }

    /// 500 seeded samples in cells 1..n−2 (every corner point interior) equal the linear field.
    fn assert_linear_inside(interp: &CellPointInterpolation, g: &Grid, seed: u64) {
        let mut state = seed;
        for _ in 0..500 {
            let x = Vec3::from_fn(|d, _| {
                g.origin[d] + g.h[d] * (1.0 + (g.n[d] - 2) as f64 * lcg(&mut state))
            });
            let (got, want) = (interp.sample(x), linear_value(x));
            for c in 0..3 {
                assert!(
                    (got[c] - want[c]).abs() < 1e-12,
                    "{x:?} {c}: {got:?} vs {want:?}"
                );
            }
        }
    }

    #[test]
    fn linear_field_is_exact_inside_cells_away_from_the_boundary() {
        let g = grid();
        let mut interp = CellPointInterpolation::new(&g, &walls());
        interp.update(&linear_faces(&g));
        assert_linear_inside(&interp, &g, 7);
    }

    #[test]
    fn a_cell_centred_linear_field_is_exact_inside_and_zero_gradient_on_boundary_faces() {
        let g = grid();
        let l = PaddedLayout::new(g.n);
        let mut cells = vec![[0.0; 3]; l.len];
        for k in 1..=g.n[2] {
            for j in 1..=g.n[1] {
                for i in 1..=g.n[0] {
                    let x =
                        Vec3::from_fn(|d, _| g.origin[d] + ([i, j, k][d] as f64 - 0.5) * g.h[d]);
                    cells[l.index(i, j, k)] = linear_value(x);
                }
            }
        }
        let mut interp = CellPointInterpolation::new(&g, &walls());
        interp.update_cells(&cells);
        assert_linear_inside(&interp, &g, 5);
        // a corner point on three walls: its boundary faces hold the corner cell's value, so
        // the point takes it (the ghost cells, left at zero, are never read)
        let [n0, n1, n2] = g.n;
        for (p, cell) in [([0, 0, 0], [1, 1, 1]), ([n0, n1, n2], [n0, n1, n2])] {
            let point = interp.point[interp.point_index(p[0], p[1], p[2])];
            let inside = cells[l.index(cell[0], cell[1], cell[2])];
            for c in 0..3 {
                assert!((point[c] - inside[c]).abs() < 1e-14, "{p:?} {c}");
            }
        }
    }

    #[test]
    fn sample_is_the_cell_value_at_the_centre_and_the_point_value_at_a_corner() {
        let g = grid();
        let (faces, interp) = random_periodic_field(&g, 3);
        let l = PaddedLayout::new(g.n);
        let (i, j, k) = (2, 3, 4);
        let centre: [f64; 3] =
            std::array::from_fn(|d| g.origin[d] + ([i, j, k][d] as f64 + 0.5) * g.h[d]);
        let at_centre = interp.sample(Vec3::from(centre));
        let f = l.index(i + 1, j + 1, k + 1);
        for c in 0..3 {
            let want = 0.5 * (faces[c][f] + faces[c][f + l.stride[c]]);
            assert!((at_centre[c] - want).abs() < 1e-14);
        }
        // the corner (i+1, j+1, k+1) is the mean of the 8 cells around it
        let corner: [f64; 3] =
            std::array::from_fn(|d| g.origin[d] + ([i, j, k][d] as f64 + 1.0) * g.h[d]);
        let at_corner = interp.sample(Vec3::from(corner));
        for c in 0..3 {
            let mut want = 0.0;
            for dk in 0..2 {
                for dj in 0..2 {
                    for di in 0..2 {
                        let f = l.index(i + 1 + di, j + 1 + dj, k + 1 + dk);
                        want += 0.5 * (faces[c][f] + faces[c][f + l.stride[c]]) / 8.0;
                    }
                }
            }
            assert!((at_corner[c] - want).abs() < 1e-14, "{c}");
        }
    }

    #[test]
    fn interpolation_is_continuous_across_cell_faces_and_tetrahedra() {
        let g = grid();
        let (_, interp) = random_periodic_field(&g, 11);
        let mut state = 11;
        let eps = 1e-9;
        for _ in 0..2000 {
            let x = Vec3::from_fn(|d, _| {
                g.origin[d] + g.h[d] * (0.01 + (g.n[d] as f64 - 0.02) * lcg(&mut state))
            });
            let dx: [f64; 3] = std::array::from_fn(|_| (lcg(&mut state) - 0.5) * eps);
            let y = [x[0] + dx[0], x[1] + dx[1], x[2] + dx[2]];
            let (u, v) = (interp.sample(x), interp.sample(Vec3::from(y)));
            for c in 0..3 {
                // the field is piecewise linear with slopes of order 1/h
                assert!((u[c] - v[c]).abs() < 50.0 * eps / 0.2, "{x:?}: {u:?} {v:?}");
            }
        }
    }

    #[test]
    fn boundary_points_take_the_faces_values_weighted_by_inverse_distance() {
        let g = Grid {
            n: [2, 3, 4],
            h: [0.75, 0.5, 0.5],
            origin: [0.0; 3],
        };
        // x: symmetry planes; y: no-slip walls; z: periodic
        let wall = FaceCondition::Wall { velocity: [0.0; 3] };
        let bc = BoundaryConditions {
            faces: [
                FaceCondition::Slip,
                FaceCondition::Slip,
                wall.clone(),
                wall,
                FaceCondition::Periodic,
                FaceCondition::Periodic,
            ],
        };
        let l = PaddedLayout::new(g.n);
        let mut faces: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; l.len]);
        // a uniform vertical flow, w = 2
        faces[2].iter_mut().for_each(|w| *w = 2.0);
        fill_velocity_ghosts(&l, &bc, &mut faces);
        let mut interp = CellPointInterpolation::new(&g, &bc);
        interp.update(&faces);
        let w_at = |i: usize, j: usize, k: usize| interp.point[interp.point_index(i, j, k)][2];
        // interior (x = 0.75, y = 0.5): every cell around holds 2
        assert!((w_at(1, 1, 2) - 2.0).abs() < 1e-14);
        // on a symmetry plane only: its faces hold the cells' tangential value 2
        assert!((w_at(0, 1, 2) - 2.0).abs() < 1e-14);
        // on a wall only: 0
        assert!(w_at(1, 0, 2).abs() < 1e-14);
        // on the wall–symmetry edge: 2 symmetry faces (0.5 × 0.5, value 2) and 2 wall faces
        // (0.75 × 0.5, value 0) around the point, weighted by 1/|x_p − x_f|
        let (ws, ww) = (
            1.0 / (0.25f64 * 0.5).sqrt(),
            1.0 / (0.25f64 * (0.5625 + 0.25)).sqrt(),
        );
        let want = 2.0 * ws / (ws + ww);
        assert!(
            (w_at(0, 0, 2) - want).abs() < 1e-14,
            "{} {want}",
            w_at(0, 0, 2)
        );
        // the symmetry planes' normal component is zero
        faces[0].iter_mut().for_each(|u| *u = 1.0);
        fill_velocity_ghosts(&l, &bc, &mut faces);
        interp.update(&faces);
        for j in 0..=3 {
            assert_eq!(interp.point[interp.point_index(0, j, 1)][0], 0.0);
            assert_eq!(interp.point[interp.point_index(2, j, 1)][0], 0.0);
        }
    }
}
