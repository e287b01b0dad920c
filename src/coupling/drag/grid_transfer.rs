//! Particle ↔ grid transfer on the staggered grid (paper eq. 13–16).
//!
//! Each velocity component lives on its own faces, ε on the cell centres. A particle at `x`
//! reads a component from the 8 nearest samples of that component with the trilinear weights
//! of eq. 15, `w = Π_d (1 − |x_d − x_d^q| / h_d)` (eq. 14), and its reaction force goes back
//! to the same samples with the same weights (eq. 13, 16); its volume goes to the 8 nearest
//! cell centres the same way ("the same method is used to evaluate the local average volume
//! fraction"). [`Stencil::Cell`] is DPMFoam's choice instead: the particle's own cell (its
//! cell-centred velocity, the mean of the cell's two faces per component; its whole volume
//! and force in that cell).
//!
//! Every stencil is a tensor product of two samples per axis whose weights sum to 1. Near a
//! boundary the reading stencil uses the boundary faces and ghost values (so a velocity read
//! next to a no-slip wall goes to the wall's value); the writing stencil folds any weight that
//! would land outside the unknowns onto the nearest unknown, so volume and momentum are
//! conserved exactly.

use super::drag_law_settings::Stencil;
use crate::fluid::{BoundaryConditions, FaceCondition, PaddedLayout};
use crate::grid::Grid;

/// Which samples a stencil addresses: a velocity component's faces or the cell centres.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Samples {
    Face(usize),
    Cell,
}

/// Reading or writing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Purpose {
    Read,
    Write,
}

/// Two padded slots and their weights along one axis (`None` when the stencil is dropped).
type AxisStencil = Option<([usize; 2], [f64; 2])>;

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

    /// The two samples and weights along axis `d` for position `x_d`.
    #[inline(always)]
    fn axis(
        &self,
        samples: Samples,
        stencil: Stencil,
        purpose: Purpose,
        d: usize,
        x: f64,
    ) -> AxisStencil {
        let n = self.grid.n[d];
        let h = self.grid.h[d];
        let on_faces = samples == Samples::Face(d);
        if on_faces && self.empty[d] {
            // No velocity across an empty direction.
            return None;
        }
        let xi = (x - self.grid.origin[d]) / h;
        let (index, weight): ([isize; 2], [f64; 2]) = match stencil {
            Stencil::Trilinear => {
                let s = if on_faces { xi } else { xi - 0.5 };
                let i0 = fast_floor(s);
                let t = s - i0 as f64;
                ([i0, i0 + 1], [1.0 - t, t])
            }
            Stencil::Cell => {
                let m = fast_floor(xi).clamp(0, n as isize - 1);
                if on_faces {
                    ([m, m + 1], [0.5, 0.5])
                } else {
                    ([m, m], [1.0, 0.0])
                }
            }
        };
        let ni = n as isize;
        let slot = |i: isize| -> usize {
            if self.empty[d] {
                return 1;
            }
            if self.periodic[d] {
                return (i.rem_euclid(ni) + 1) as usize;
            }
            match (on_faces, purpose) {
                // Boundary faces hold the conditions' values.
                (true, Purpose::Read) => (i.clamp(0, ni) + 1) as usize,
                // Ghost cells hold the conditions' mirror values.
                (false, Purpose::Read) if samples != Samples::Cell => {
                    (i.clamp(-1, ni) + 1) as usize
                }
                (false, _) => (i.clamp(0, ni - 1) + 1) as usize,
                (true, Purpose::Write) => unreachable!("handled below"),
            }
        };
        if on_faces && purpose == Purpose::Write && !self.periodic[d] {
            let Samples::Face(c) = samples else {
                unreachable!()
            };
            let (lo, hi) = self.momentum_ranges[c][d];
            if lo > hi {
                return None;
            }
            let fold = |i: isize| ((i + 1).clamp(lo as isize, hi as isize)) as usize;
            return Some(([fold(index[0]), fold(index[1])], weight));
        }
        Some(([slot(index[0]), slot(index[1])], weight))
    }

    /// Calls `f(padded index, weight)` for the 8 samples of the stencil at `x`.
    #[inline]
    fn for_each_sample(
        &self,
        samples: Samples,
        stencil: Stencil,
        purpose: Purpose,
        x: [f64; 3],
        f: impl FnMut(usize, f64),
    ) {
        let ax: [AxisStencil; 3] =
            std::array::from_fn(|d| self.axis(samples, stencil, purpose, d, x[d]));
        self.for_each_in(&ax, f);
    }

    /// Calls `f(padded index, weight)` for the samples of a precomputed tensor stencil.
    #[inline]
    fn for_each_in(&self, ax: &[AxisStencil; 3], mut f: impl FnMut(usize, f64)) {
        let (Some(a0), Some(a1), Some(a2)) = (ax[0], ax[1], ax[2]) else {
            return;
        };
        for c in 0..2 {
            for b in 0..2 {
                let wbc = a1.1[b] * a2.1[c];
                if wbc == 0.0 {
                    continue;
                }
                for a in 0..2 {
                    let w = a0.1[a] * wbc;
                    if w != 0.0 {
                        f(self.layout.index(a0.0[a], a1.0[b], a2.0[c]), w);
                    }
                }
            }
        }
    }

    /// The staggered vector field `faces` (padded, ghosts filled) at `x` (eq. 14).
    pub fn interpolate_faces(
        &self,
        faces: &[Vec<f64>; 3],
        x: [f64; 3],
        stencil: Stencil,
    ) -> [f64; 3] {
        std::array::from_fn(|c| {
            let mut v = 0.0;
            self.for_each_sample(Samples::Face(c), stencil, Purpose::Read, x, |i, w| {
                v += w * faces[c][i]
            });
            v
        })
    }

    /// Two staggered fields at `x` with one stencil evaluation (the velocity and the pressure
    /// gradient a particle reads).
    pub fn interpolate_faces_pair(
        &self,
        a: &[Vec<f64>; 3],
        b: &[Vec<f64>; 3],
        x: [f64; 3],
        stencil: Stencil,
    ) -> ([f64; 3], [f64; 3]) {
        let mut va = [0.0; 3];
        let mut vb = [0.0; 3];
        for c in 0..3 {
            let ax: [AxisStencil; 3] = std::array::from_fn(|d| {
                self.axis(Samples::Face(c), stencil, Purpose::Read, d, x[d])
            });
            self.for_each_in(&ax, |i, w| {
                va[c] += w * a[c][i];
                vb[c] += w * b[c][i];
            });
        }
        (va, vb)
    }

    /// Adds `value[c] · w` to `target` and `other · w` to `second` on the momentum faces of
    /// each component, one stencil evaluation for both (the reaction and, for the
    /// semi-implicit source, the drag coefficient).
    pub fn spread_to_faces_pair(
        &self,
        target: &mut [Vec<f64>; 3],
        value: [f64; 3],
        second: &mut [Vec<f64>; 3],
        other: f64,
        x: [f64; 3],
        stencil: Stencil,
    ) {
        for c in 0..3 {
            let ax: [AxisStencil; 3] = std::array::from_fn(|d| {
                self.axis(Samples::Face(c), stencil, Purpose::Write, d, x[d])
            });
            let (t, o) = (&mut target[c], &mut second[c]);
            let v = value[c];
            self.for_each_in(&ax, |i, w| {
                t[i] += w * v;
                o[i] += w * other;
            });
        }
    }

    /// The cell field `cells` (padded, ghosts filled) at `x`.
    pub fn interpolate_cells(&self, cells: &[f64], x: [f64; 3], stencil: Stencil) -> f64 {
        let mut v = 0.0;
        self.for_each_sample(Samples::Cell, stencil, Purpose::Read, x, |i, w| {
            v += w * cells[i]
        });
        v
    }

    /// Adds `value[c] · w` to the momentum faces of each component `c` (eq. 16 without the
    /// `−1/h³`, which the caller applies).
    pub fn spread_to_faces(
        &self,
        target: &mut [Vec<f64>; 3],
        x: [f64; 3],
        value: [f64; 3],
        stencil: Stencil,
    ) {
        for c in 0..3 {
            if value[c] == 0.0 {
                continue;
            }
            let t = &mut target[c];
            self.for_each_sample(Samples::Face(c), stencil, Purpose::Write, x, |i, w| {
                t[i] += w * value[c]
            });
        }
    }

    /// Adds `value · w` to the cells (padded array) around `x`.
    pub fn spread_to_cells(&self, target: &mut [f64], x: [f64; 3], value: f64, stencil: Stencil) {
        self.for_each_sample(Samples::Cell, stencil, Purpose::Write, x, |i, w| {
            target[i] += w * value
        });
    }
}

/// `⌊s⌋` without a libm call (the hot loops run it 20 times per particle and step).
#[inline]
fn fast_floor(s: f64) -> isize {
    let t = s as isize;
    if (t as f64) > s {
        t - 1
    } else {
        t
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
    fn fast_floor_matches_floor() {
        for s in [-2.5, -2.0, -0.3, 0.0, 0.7, 1.0, 3.999] {
            assert_eq!(fast_floor(s), s.floor() as isize, "{s}");
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
        let x = [1.23, -0.37, 1.01];
        let v = t.interpolate_faces(&faces, x, Stencil::Trilinear);
        for c in 0..3 {
            let exact = 1.0 + 2.0 * x[0] - 3.0 * x[1] + 0.5 * x[2] + c as f64;
            assert!((v[c] - exact).abs() < 1e-12, "{c}: {} vs {exact}", v[c]);
        }
        // Spreading a unit value spreads total weight 1, for both stencils and every sample set.
        for stencil in [Stencil::Trilinear, Stencil::Cell] {
            let mut target: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; l.len]);
            t.spread_to_faces(&mut target, x, [1.0, 2.0, 3.0], stencil);
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
        let x = [0.2, 0.3, 3.9];
        t.spread_to_faces(&mut target, x, [1.0, 1.0, 1.0], Stencil::Trilinear);
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
        let at_wall = t.interpolate_faces(&faces, [1.0, 0.0, 1.0], Stencil::Trilinear);
        assert!(at_wall[0].abs() < 1e-14);
        let inside = t.interpolate_faces(&faces, [1.0, 0.5, 1.0], Stencil::Trilinear);
        assert!((inside[0] - 1.0).abs() < 1e-14);
        // The cell stencil reads the cell-centred mean of the two faces.
        let cell = t.interpolate_faces(&faces, [0.3, 0.2, 0.9], Stencil::Cell);
        assert!((cell[0] - 1.0).abs() < 1e-14);
    }
}
