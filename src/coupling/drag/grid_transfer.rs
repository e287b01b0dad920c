//! Particle ↔ grid transfer on the staggered grid (paper eq. 13–16).
//!
//! Each velocity component lives on its own faces, ε on the cell centres. A particle at `x`
//! reads a component from the 8 nearest samples of that component (paper eq. 14) with the
//! trilinear weights `w = Π_d (1 − |x_d − x_d^q| / h_d)` (paper eq. 15), and its reaction
//! force goes back to the same samples with the same weights (paper eq. 13, 16); its volume
//! goes to the 8 nearest cell centres the same way ("the same method is used to evaluate the
//! local average volume fraction", after paper eq. 16). [`Stencil::Cell`] is DPMFoam's
//! choice instead: the particle's own cell (its cell-centred velocity, the mean of the
//! cell's two faces per component; its whole volume and force in that cell).
//!
//! Every stencil is a tensor product of two samples per axis whose weights sum to 1. Near a
//! boundary the reading stencil uses the boundary faces and ghost values (so a velocity read
//! next to a no-slip wall goes to the wall's value); the writing stencil folds any weight that
//! would land outside the unknowns onto the nearest unknown, so volume and momentum are
//! conserved exactly.

use super::drag_law_settings::Stencil;
use crate::fluid::{BoundaryConditions, FaceCondition, PaddedLayout};
use crate::grid::{fast_floor, Grid};
use crate::Vec3;

/// Reading or writing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Purpose {
    Read,
    Write,
}

/// Interpolation and spreading between particles and the staggered grid.
#[derive(Clone, Debug)]
pub struct GridTransfer {
    grid: Grid,
    layout: PaddedLayout,
    periodic: [bool; 3],
    empty: [bool; 3],
    momentum_ranges: [[(usize, usize); 3]; 3],
}

impl GridTransfer {
    pub fn new(
        grid: &Grid,
        bc: &BoundaryConditions,
        momentum_ranges: &[[(usize, usize); 3]; 3],
    ) -> Self {
        GridTransfer {
            grid: grid.clone(),
            layout: PaddedLayout::new(grid.n),
            periodic: std::array::from_fn(|d| matches!(bc.face(d, 0), FaceCondition::Periodic)),
            empty: std::array::from_fn(|d| matches!(bc.face(d, 0), FaceCondition::Empty)),
            momentum_ranges: *momentum_ranges,
        }
    }

    /// Cell volume `h₀ h₁ h₂`, m³.
    pub fn cell_volume(&self) -> f64 {
        self.grid.h.iter().product()
    }

    /// `x` in cell units from the origin, `(x_d − o_d)/h_d`.
    #[inline(always)]
    fn cell_units(&self, x: Vec3) -> [f64; 3] {
        let (o, h) = (&self.grid.origin, &self.grid.h);
        [
            (x[0] - o[0]) / h[0],
            (x[1] - o[1]) / h[1],
            (x[2] - o[2]) / h[2],
        ]
    }

    /// The two sample indices (unpadded, possibly outside `0..n`) and weights along an axis of
    /// `n` cells at `xi` (cell units), for samples on that axis's faces or on the cell centres.
    #[inline(always)]
    fn axis_samples(stencil: Stencil, on_faces: bool, n: isize, xi: f64) -> ([isize; 2], [f64; 2]) {
        match stencil {
            Stencil::Trilinear => {
                let s = if on_faces { xi } else { xi - 0.5 };
                let i0 = fast_floor(s);
                let t = s - i0 as f64;
                ([i0, i0 + 1], [1.0 - t, t])
            }
            Stencil::Cell => {
                let m = fast_floor(xi).clamp(0, n - 1);
                if on_faces {
                    ([m, m + 1], [0.5, 0.5])
                } else {
                    ([m, m], [1.0, 0.0])
                }
            }
        }
    }

    /// The padded slots of `index` along axis `d` times its stride: wrapped when periodic,
    /// slot 1 when empty, else clamped to the padded slots `lo..=hi`.
    #[inline(always)]
    fn axis_offsets(&self, d: usize, index: [isize; 2], lo: isize, hi: isize) -> [u32; 2] {
        let stride = self.layout.stride[d];
        let slot = |i: isize| -> usize {
            if self.empty[d] {
                1
            } else if self.periodic[d] {
                (i.rem_euclid(self.grid.n[d] as isize) + 1) as usize
            } else {
                (i + 1).clamp(lo, hi) as usize
            }
        };
        [
            (slot(index[0]) * stride) as u32,
            (slot(index[1]) * stride) as u32,
        ]
    }

    /// The stencils of the three velocity components at `x` and, when asked, of the cell
    /// centres, from one pass over the axes. Along axis `d`, component `d` samples its faces and
    /// the others the cell centres. Reading: boundary faces hold the conditions' values and
    /// ghost cells their mirror values; writing: weight beyond the unknowns folds onto the
    /// nearest one; cell samples stay on the cells. No velocity across an empty direction.
    #[inline(always)]
    fn face_stencils(
        &self,
        x: Vec3,
        stencil: Stencil,
        purpose: Purpose,
        faces: &mut [SampleStencil; 3],
        mut cell: Option<&mut SampleStencil>,
    ) {
        let xi = self.cell_units(x);
        let mut dropped = [false; 3];
        for d in 0..3 {
            let n = self.grid.n[d] as isize;
            let (centre, centre_weight) = Self::axis_samples(stencil, false, n, xi[d]);
            let cell_offsets = self.axis_offsets(d, centre, 1, n);
            let across = match purpose {
                Purpose::Read => self.axis_offsets(d, centre, 0, n + 1),
                Purpose::Write => cell_offsets,
            };
            if let Some(cell) = cell.as_deref_mut() {
                cell.offset[d] = cell_offsets;
                cell.weight[d] = centre_weight;
            }
            let along = if self.empty[d] {
                None
            } else {
                let (face, face_weight) = Self::axis_samples(stencil, true, n, xi[d]);
                let bounds = match purpose {
                    Purpose::Read => Some((1, n + 1)),
                    Purpose::Write => {
                        let (lo, hi) = self.momentum_ranges[d][d];
                        (self.periodic[d] || lo <= hi).then_some((lo as isize, hi as isize))
                    }
                };
                bounds.map(|(lo, hi)| (self.axis_offsets(d, face, lo, hi), face_weight))
            };
            for c in 0..3 {
                if c != d {
                    faces[c].offset[d] = across;
                    faces[c].weight[d] = centre_weight;
                } else if let Some((offsets, weight)) = along {
                    faces[c].offset[d] = offsets;
                    faces[c].weight[d] = weight;
                } else {
                    dropped[c] = true;
                }
            }
        }
        for c in 0..3 {
            if dropped[c] {
                faces[c] = SampleStencil::default();
            }
        }
    }

    /// The stencils reading each velocity component at `x` (faces and ghosts filled).
    #[inline]
    pub fn read_face_stencils(&self, x: Vec3, stencil: Stencil, out: &mut [SampleStencil; 3]) {
        self.face_stencils(x, stencil, Purpose::Read, out, None);
    }

    /// The stencils spreading each component of a force at `x` to the momentum faces, and the
    /// stencil of the cell centres (the same for reading and writing a cell field).
    #[inline]
    pub fn write_stencils(
        &self,
        x: Vec3,
        stencil: Stencil,
        faces: &mut [SampleStencil; 3],
        cell: &mut SampleStencil,
    ) {
        self.face_stencils(x, stencil, Purpose::Write, faces, Some(cell));
    }

    /// The stencil of a cell field at `x` (reading or writing: cell samples stay on the cells).
    #[inline]
    pub fn cell_stencil(&self, x: Vec3, stencil: Stencil, out: &mut SampleStencil) {
        let xi = self.cell_units(x);
        for d in 0..3 {
            let n = self.grid.n[d] as isize;
            let (centre, weight) = Self::axis_samples(stencil, false, n, xi[d]);
            out.offset[d] = self.axis_offsets(d, centre, 1, n);
            out.weight[d] = weight;
        }
    }

    /// The staggered vector field `faces` (padded, ghosts filled) at `x` (paper eq. 14).
    pub fn interpolate_faces(&self, faces: &[Vec<f64>; 3], x: Vec3, stencil: Stencil) -> Vec3 {
        let mut st = [SampleStencil::default(); 3];
        self.read_face_stencils(x, stencil, &mut st);
        Vec3::from_fn(|c, _| st[c].gather(&faces[c]))
    }

    /// Two staggered fields at `x` with one stencil evaluation (the velocity and the pressure
    /// gradient a particle reads).
    pub fn interpolate_faces_pair(
        &self,
        a: &[Vec<f64>; 3],
        b: &[Vec<f64>; 3],
        x: Vec3,
        stencil: Stencil,
    ) -> (Vec3, Vec3) {
        let mut st = [SampleStencil::default(); 3];
        self.read_face_stencils(x, stencil, &mut st);
        (
            Vec3::from_fn(|c, _| st[c].gather(&a[c])),
            Vec3::from_fn(|c, _| st[c].gather(&b[c])),
        )
    }

    /// Adds `value[c] · w` to `target` and `other · w` to `second` on the momentum faces of
    /// each component, one stencil evaluation for both (the reaction and, for the
    /// semi-implicit source, the drag coefficient).
    pub fn spread_to_faces_pair(
        &self,
        target: &mut [Vec<f64>; 3],
        value: Vec3,
        second: &mut [Vec<f64>; 3],
        other: f64,
        x: Vec3,
        stencil: Stencil,
    ) {
        let mut st = [SampleStencil::default(); 3];
        let mut cell = SampleStencil::default();
        self.write_stencils(x, stencil, &mut st, &mut cell);
        for c in 0..3 {
            st[c].scatter(&mut target[c], 0, value[c]);
            st[c].scatter(&mut second[c], 0, other);
        }
    }

    /// The cell field `cells` (padded, ghosts filled) at `x`.
    pub fn interpolate_cells(&self, cells: &[f64], x: Vec3, stencil: Stencil) -> f64 {
        let mut st = SampleStencil::default();
        self.cell_stencil(x, stencil, &mut st);
        st.gather(cells)
    }

    /// Adds `value[c] · w` to the momentum faces of each component `c` (paper eq. 16 without
    /// the `−1/h³`, which the caller applies).
    pub fn spread_to_faces(
        &self,
        target: &mut [Vec<f64>; 3],
        x: Vec3,
        value: Vec3,
        stencil: Stencil,
    ) {
        let mut st = [SampleStencil::default(); 3];
        let mut cell = SampleStencil::default();
        self.write_stencils(x, stencil, &mut st, &mut cell);
        for c in 0..3 {
            if value[c] != 0.0 {
                st[c].scatter(&mut target[c], 0, value[c]);
            }
        }
    }

    /// Adds `value · w` to the cells (padded array) around `x`.
    pub fn spread_to_cells(&self, target: &mut [f64], x: Vec3, value: f64, stencil: Stencil) {
        let mut st = SampleStencil::default();
        self.cell_stencil(x, stencil, &mut st);
        st.scatter(target, 0, value);
    }
}

/// One particle's stencil on one sample set: the tensor product of two samples per axis
/// (weights `w = w₀[a] w₁[b] w₂[c]`, paper eq. 14–15), the samples' padded index being
/// `offset₀[a] + offset₁[b] + offset₂[c]`. Computed once per particle and step, it serves every
/// read and write of that step; zero-weight samples are skipped.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SampleStencil {
    /// Per axis, the two samples' padded slots times the layout stride.
    offset: [[u32; 2]; 3],
    /// Per axis, the two weights (all zero for a dropped stencil).
    weight: [[f64; 2]; 3],
}

impl SampleStencil {
    /// Calls `visit(i, w)` for each sample with a non-zero weight, `i` its padded index, in a
    /// fixed order (x fastest).
    #[inline(always)]
    fn for_each_sample(&self, mut visit: impl FnMut(usize, f64)) {
        for c in 0..2 {
            for b in 0..2 {
                let wbc = self.weight[1][b] * self.weight[2][c];
                if wbc == 0.0 {
                    continue;
                }
                let obc = (self.offset[1][b] + self.offset[2][c]) as usize;
                for a in 0..2 {
                    let w = self.weight[0][a] * wbc;
                    if w != 0.0 {
                        visit(self.offset[0][a] as usize + obc, w);
                    }
                }
            }
        }
    }

    /// The weight the stencil gives the padded index `index` (zero if it has no sample there).
    pub fn weight_at(&self, index: usize) -> f64 {
        let mut sum = 0.0;
        self.for_each_sample(|i, w| {
            if i == index {
                sum += w
            }
        });
        sum
    }

    /// `Σ w f[i]` over the samples.
    #[inline]
    pub fn gather(&self, field: &[f64]) -> f64 {
        let mut v = 0.0;
        self.for_each_sample(|i, w| v += w * field[i]);
        v
    }

    /// `target[i − base] += w · value` over the samples (`base`: the first padded index
    /// `target` holds).
    #[inline]
    pub fn scatter(&self, target: &mut [f64], base: usize, value: f64) {
        self.for_each_sample(|i, w| target[i - base] += w * value);
    }

    /// `first[i − base] += w · a` and `second[i − base] += w · b` over the samples: two
    /// [`Self::scatter`]s with one pass over the weights (each target receives exactly what
    /// its own scatter would add).
    #[inline]
    pub fn scatter_pair(
        &self,
        first: &mut [f64],
        second: &mut [f64],
        base: usize,
        a_value: f64,
        b_value: f64,
    ) {
        self.for_each_sample(|i, w| {
            first[i - base] += w * a_value;
            second[i - base] += w * b_value;
        });
    }

    /// The padded indices `lo..hi` the samples can touch.
    #[inline]
    pub fn index_range(&self) -> (usize, usize) {
        let mut lo = 0usize;
        let mut hi = 1usize;
        for d in 0..3 {
            let [p, q] = self.offset[d];
            lo += p.min(q) as usize;
            hi += p.max(q) as usize;
        }
        (lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn transfer(bc: &BoundaryConditions, grid: &Grid) -> GridTransfer {
        let ranges =
            std::array::from_fn(|c| std::array::from_fn(|d| bc.momentum_range(grid.n, c, d)));
        GridTransfer::new(grid, bc, &ranges)
    }

    fn walls() -> BoundaryConditions {
        let wall = FaceCondition::Wall { velocity: [0.0; 3] };
        BoundaryConditions {
            faces: std::array::from_fn(|_| wall.clone()),
        }
    }

    #[test]
    fn one_pass_stencils_match_the_single_set_ones() {
        // The cell stencil from the writing pass is the cell stencil; the pair functions give
        // what two single calls give, bit for bit (seeded positions over the whole box and a
        // little beyond, walls and a periodic direction).
        let grid = Grid::new([5, 4, 6], [0.1, 0.2, 0.15], [0.3, -0.2, 0.0]);
        let mut bc = walls();
        bc.faces[0] = FaceCondition::Periodic;
        bc.faces[1] = FaceCondition::Periodic;
        let t = transfer(&bc, &grid);
        let l = PaddedLayout::new(grid.n);
        let field = |seed: usize| -> [Vec<f64>; 3] {
            std::array::from_fn(|c| {
                (0..l.len)
                    .map(|i| ((i * 7919 + c * 104729 + seed) % 1000) as f64 * 1e-3 - 0.5)
                    .collect()
            })
        };
        let (a, b) = (field(1), field(2));
        let mut state = 12345u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..200 {
            let x = Vec3::from_fn(|d, _| {
                grid.origin[d] + (1.2 * next() - 0.1) * grid.n[d] as f64 * grid.h[d]
            });
            for stencil in [Stencil::Trilinear, Stencil::Cell] {
                let mut faces = [SampleStencil::default(); 3];
                let mut cell = SampleStencil::default();
                let mut alone = SampleStencil::default();
                t.write_stencils(x, stencil, &mut faces, &mut cell);
                t.cell_stencil(x, stencil, &mut alone);
                assert_eq!(cell, alone);
                let (va, vb) = t.interpolate_faces_pair(&a, &b, x, stencil);
                assert_eq!(va, t.interpolate_faces(&a, x, stencil));
                assert_eq!(vb, t.interpolate_faces(&b, x, stencil));
                let mut one: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; l.len]);
                let mut two = one.clone();
                let (mut p, mut q) = (one.clone(), one.clone());
                t.spread_to_faces(&mut one, x, Vec3::new(1.0, -2.0, 3.0), stencil);
                t.spread_to_faces(&mut two, x, Vec3::repeat(0.5), stencil);
                t.spread_to_faces_pair(&mut p, Vec3::new(1.0, -2.0, 3.0), &mut q, 0.5, x, stencil);
                assert_eq!((one, two), (p, q));
            }
        }
    }

    /// A per-sample reference (one axis at a time, library `floor`) that the stencils must
    /// reproduce bit for bit.
    fn reference_axis(
        t: &GridTransfer,
        face: Option<usize>,
        stencil: Stencil,
        write: bool,
        d: usize,
        x: f64,
    ) -> Option<([usize; 2], [f64; 2])> {
        let n = t.grid.n[d];
        let on_faces = face == Some(d);
        if on_faces && t.empty[d] {
            return None;
        }
        let xi = (x - t.grid.origin[d]) / t.grid.h[d];
        let (index, weight): ([isize; 2], [f64; 2]) = match stencil {
            Stencil::Trilinear => {
                let s = if on_faces { xi } else { xi - 0.5 };
                let i0 = s.floor();
                ([i0 as isize, i0 as isize + 1], [1.0 - (s - i0), s - i0])
            }
            Stencil::Cell => {
                let m = (xi.floor() as isize).clamp(0, n as isize - 1);
                if on_faces {
                    ([m, m + 1], [0.5, 0.5])
                } else {
                    ([m, m], [1.0, 0.0])
                }
            }
        };
        let ni = n as isize;
        if on_faces && write && !t.periodic[d] {
            let (lo, hi) = t.momentum_ranges[face.unwrap()][d];
            if lo > hi {
                return None;
            }
            let fold = |i: isize| ((i + 1).clamp(lo as isize, hi as isize)) as usize;
            return Some(([fold(index[0]), fold(index[1])], weight));
        }
        let slot = |i: isize| -> usize {
            if t.empty[d] {
                1
            } else if t.periodic[d] {
                (i.rem_euclid(ni) + 1) as usize
            } else if on_faces {
                (i.clamp(0, ni) + 1) as usize
            } else if !write && face.is_some() {
                (i.clamp(-1, ni) + 1) as usize
            } else {
                (i.clamp(0, ni - 1) + 1) as usize
            }
        };
        Some(([slot(index[0]), slot(index[1])], weight))
    }

    /// `(padded index, weight)` of the reference stencil's non-zero samples, in loop order.
    fn reference_samples(
        t: &GridTransfer,
        face: Option<usize>,
        stencil: Stencil,
        write: bool,
        x: Vec3,
    ) -> Vec<(usize, f64)> {
        let ax: Vec<_> = (0..3)
            .map(|d| reference_axis(t, face, stencil, write, d, x[d]))
            .collect();
        let (Some(a0), Some(a1), Some(a2)) = (ax[0], ax[1], ax[2]) else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for c in 0..2 {
            for b in 0..2 {
                let wbc = a1.1[b] * a2.1[c];
                if wbc == 0.0 {
                    continue;
                }
                for a in 0..2 {
                    let w = a0.1[a] * wbc;
                    if w != 0.0 {
                        out.push((t.layout.index(a0.0[a], a1.0[b], a2.0[c]), w));
                    }
                }
            }
        }
        out
    }

    /// The same list from a [`SampleStencil`].
    fn samples_of(st: &SampleStencil) -> Vec<(usize, f64)> {
        let mut out = Vec::new();
        for c in 0..2 {
            for b in 0..2 {
                let wbc = st.weight[1][b] * st.weight[2][c];
                if wbc == 0.0 {
                    continue;
                }
                for a in 0..2 {
                    let w = st.weight[0][a] * wbc;
                    if w != 0.0 {
                        let i = (st.offset[0][a] + st.offset[1][b] + st.offset[2][c]) as usize;
                        out.push((i, w));
                    }
                }
            }
        }
        out
    }

    #[test]
    fn stencils_reproduce_the_per_sample_reference_for_every_boundary_kind() {
        // Walls, an inlet/outlet pair, periodic and empty directions; seeded positions over the
        // box and a little beyond; both stencils, reading and writing, faces and cells.
        let grid = Grid::new([4, 3, 5], [0.1, 0.2, 0.15], [0.3, -0.2, 0.0]);
        let wall = FaceCondition::Wall { velocity: [0.0; 3] };
        let cases = [
            walls(),
            BoundaryConditions {
                faces: [
                    FaceCondition::Periodic,
                    FaceCondition::Periodic,
                    wall.clone(),
                    FaceCondition::Slip,
                    FaceCondition::Inlet {
                        velocity: [0.0, 0.0, 1.0],
                    },
                    FaceCondition::Outlet { pressure: 0.0 },
                ],
            },
            BoundaryConditions {
                faces: [
                    FaceCondition::Empty,
                    FaceCondition::Empty,
                    FaceCondition::Periodic,
                    FaceCondition::Periodic,
                    wall.clone(),
                    FaceCondition::Outlet { pressure: 0.0 },
                ],
            },
        ];
        let mut state = 99u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for bc in &cases {
            let t = transfer(bc, &grid);
            for _ in 0..300 {
                let x = Vec3::from_fn(|d, _| {
                    grid.origin[d] + (1.2 * next() - 0.1) * grid.n[d] as f64 * grid.h[d]
                });
                for stencil in [Stencil::Trilinear, Stencil::Cell] {
                    let mut read = [SampleStencil::default(); 3];
                    let mut write = [SampleStencil::default(); 3];
                    let mut cell = SampleStencil::default();
                    t.read_face_stencils(x, stencil, &mut read);
                    t.write_stencils(x, stencil, &mut write, &mut cell);
                    for c in 0..3 {
                        let r = reference_samples(&t, Some(c), stencil, false, x);
                        assert_eq!(samples_of(&read[c]), r, "read {c} at {x:?}");
                        let w = reference_samples(&t, Some(c), stencil, true, x);
                        assert_eq!(samples_of(&write[c]), w, "write {c} at {x:?}");
                    }
                    let r = reference_samples(&t, None, stencil, false, x);
                    assert_eq!(samples_of(&cell), r, "cell at {x:?}");
                }
            }
        }
    }

    #[test]
    fn trilinear_reproduces_linear_fields_and_weights_sum_to_one() {
        let grid = Grid::new([6, 5, 4], [0.1, 0.2, 0.3], [1.0, -1.0, 0.5]);
        let bc = BoundaryConditions::periodic();
        let t = transfer(&bc, &grid);
        let l = PaddedLayout::new(grid.n);
        // u_c = a + b·x at each component's own sample positions (interior, away from the wrap).
        let mut faces: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; l.len]);
        for c in 0..3 {
            for k in 0..l.dims[2] {
                for j in 0..l.dims[1] {
                    for i in 0..l.dims[0] {
                        let idx = [i, j, k];
                        let pos: [f64; 3] = std::array::from_fn(|d| {
                            let off = if d == c { 1.0 } else { 0.5 };
                            grid.origin[d] + (idx[d] as f64 - off) * grid.h[d]
                        });
                        faces[c][l.index(i, j, k)] =
                            1.0 + 2.0 * pos[0] - 3.0 * pos[1] + 0.5 * pos[2] + c as f64;
                    }
                }
            }
        }
        let x = Vec3::new(1.23, -0.37, 1.01);
        let v = t.interpolate_faces(&faces, x, Stencil::Trilinear);
        for c in 0..3 {
            let exact = 1.0 + 2.0 * x[0] - 3.0 * x[1] + 0.5 * x[2] + c as f64;
            assert!((v[c] - exact).abs() < 1e-12, "{c}: {} vs {exact}", v[c]);
        }
        // Spreading a unit value spreads total weight 1, for both stencils and every sample set.
        for stencil in [Stencil::Trilinear, Stencil::Cell] {
            let mut target: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; l.len]);
            t.spread_to_faces(&mut target, x, Vec3::new(1.0, 2.0, 3.0), stencil);
            for c in 0..3 {
                let s: f64 = target[c].iter().sum();
                assert!((s - (c + 1) as f64).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn spreading_near_walls_conserves_and_stays_on_unknowns() {
        let grid = Grid::new([4, 4, 4], [1.0; 3], [0.0; 3]);
        let bc = walls();
        let t = transfer(&bc, &grid);
        let l = PaddedLayout::new(grid.n);
        let mut target: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; l.len]);
        let mut cells = vec![0.0; l.len];
        // A particle in the corner cell, closer to the walls than half a cell.
        let x = Vec3::new(0.2, 0.3, 3.9);
        t.spread_to_faces(&mut target, x, Vec3::new(1.0, 1.0, 1.0), Stencil::Trilinear);
        t.spread_to_cells(&mut cells, x, 1.0, Stencil::Trilinear);
        for c in 0..3 {
            let s: f64 = target[c].iter().sum();
            assert!((s - 1.0).abs() < 1e-14);
            // Only faces the momentum equation advances receive anything.
            let r = bc.momentum_range(grid.n, c, c);
            for k in 0..l.dims[2] {
                for j in 0..l.dims[1] {
                    for i in 0..l.dims[0] {
                        let v = target[c][l.index(i, j, k)];
                        let along = [i, j, k][c];
                        if v != 0.0 {
                            assert!(along >= r.0 && along <= r.1);
                        }
                    }
                }
            }
        }
        assert!((cells.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        // The cell stencil puts the whole volume in the particle's cell (padded (1,1,4)).
        let mut cells = vec![0.0; l.len];
        t.spread_to_cells(&mut cells, x, 1.0, Stencil::Cell);
        assert_eq!(cells[l.index(1, 1, 4)], 1.0);
    }

    #[test]
    fn reading_next_to_a_wall_uses_the_ghosts() {
        // Tangential u = 1 everywhere inside, wall ghosts mirror it to −1: at the wall (y = 0)
        // the trilinear value is the wall's 0, half a cell in it is 1.
        let grid = Grid::new([2, 2, 2], [1.0; 3], [0.0; 3]);
        let bc = walls();
        let t = transfer(&bc, &grid);
        let l = PaddedLayout::new(grid.n);
        let mut faces: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; l.len]);
        for k in 0..l.dims[2] {
            for j in 0..l.dims[1] {
                for i in 0..l.dims[0] {
                    faces[0][l.index(i, j, k)] = if j == 0 || k == 0 || j == 3 || k == 3 {
                        -1.0
                    } else {
                        1.0
                    };
                }
            }
        }
        let at_wall = t.interpolate_faces(&faces, Vec3::new(1.0, 0.0, 1.0), Stencil::Trilinear);
        assert!(at_wall[0].abs() < 1e-14);
        let inside = t.interpolate_faces(&faces, Vec3::new(1.0, 0.5, 1.0), Stencil::Trilinear);
        assert!((inside[0] - 1.0).abs() < 1e-14);
        // The cell stencil reads the cell-centred mean of the two faces.
        let cell = t.interpolate_faces(&faces, Vec3::new(0.3, 0.2, 0.9), Stencil::Cell);
        assert!((cell[0] - 1.0).abs() < 1e-14);
    }
}
