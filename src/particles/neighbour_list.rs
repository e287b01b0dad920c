//! Verlet neighbour lists built from linked cells, with the contact history they carry.
//!
//! Layout (all contiguous, rebuilt together):
//! * a *half* pair list in compressed rows: particle `i` owns the partners
//!   `partner[row_start[i]..row_start[i+1]]`, all with index `> i`, so each pair is stored
//!   and evaluated once;
//! * per pair: the tangential spring `history` (from the owner's side);
//! * a *block* partition of the (cell-sorted) particles for the parallel force pass: blocks of
//!   `block` consecutive indices, sized so that nearly every partner lies in its owner's
//!   block or the next one. A block owns the per-particle sums of its own particles and the
//!   "from the previous block" sums of the next block, so even blocks run in parallel, then
//!   odd blocks, each scattering straight into sums nobody else touches. The few remaining
//!   *far* pairs (across the periodic seam, or spanning more than a block) write their load
//!   into `far_load` and are gathered through the reverse rows
//!   `far_rev[far_rev_start[j]..far_rev_start[j+1]]`. Every sum is added in an order fixed by
//!   the lists alone, so 1 and 2 threads give the same bits;
//! * a wall list: for each particle, the wall faces within reach, with their history.
//!
//! Lists hold every pair closer than `r_i + r_j + skin`; they stay valid until some particle
//! has moved more than `skin/2` from its `reference` position.

use std::collections::HashMap;

use rayon::prelude::*;

use super::cell_grid::CellGrid;
use super::domain_box::{minimum_image, DomainBox, FaceCondition};
use crate::Vec3;

/// Particles per parallel work unit of the per-particle passes.
pub(crate) const CHUNK: usize = 512;

/// The smallest block of the force pass.
const MIN_BLOCK: usize = 256;

#[derive(Clone, Debug, Default)]
pub(crate) struct NeighbourList {
    pub(crate) skin: f64,
    pub(crate) grid: CellGrid,
    pub(crate) cell_of: Vec<u32>,
    pub(crate) cell_start: Vec<u32>,
    pub(crate) order: Vec<u32>,
    pub(crate) row_start: Vec<u32>,
    pub(crate) partner: Vec<u32>,
    pub(crate) history: Vec<Vec3>,
    /// Particles per block of the force pass (see the module doc).
    pub(crate) block: usize,
    /// The far pairs, ascending, and their loads: force on the owner (0..3) and torque per
    /// unit radius `−n × F_t` (3..6).
    pub(crate) far_pair: Vec<u32>,
    pub(crate) far_load: Vec<[f64; 6]>,
    /// For each particle, the far pairs in which it is the partner (indices into `far_pair`).
    pub(crate) far_rev_start: Vec<u32>,
    pub(crate) far_rev: Vec<u32>,
    pub(crate) wall_start: Vec<u32>,
    pub(crate) wall_face: Vec<u8>,
    pub(crate) wall_history: Vec<Vec3>,
    pub(crate) wall_force: Vec<Vec3>,
    pub(crate) wall_torque: Vec<Vec3>,
    pub(crate) reference: Vec<Vec3>,
    pub(crate) carry_pairs: Vec<(u32, u32, Vec3)>,
    pub(crate) carry_walls: Vec<(u32, u8, Vec3)>,
    pub(crate) inverse: Vec<u32>,
}

/// Contact history keyed by particle ids, to carry springs across reordering and restarts.
/// Pair keys are `(smaller id, larger id)` and the spring is stored from the smaller id's side.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactHistory {
    pub pairs: Vec<(u64, u64, Vec3)>,
    pub walls: Vec<(u64, u8, Vec3)>,
}

impl NeighbourList {
    /// Sorts particles by cell: returns nothing, leaves the permutation in `self.order`.
    pub(crate) fn sort(&mut self, domain: &DomainBox, cell_size: f64, positions: &[Vec3]) {
        // about two cells per particle at most
        self.grid = CellGrid::new(domain, cell_size, 2 * positions.len() + 64);
        self.grid.counting_sort(
            positions,
            &mut self.cell_of,
            &mut self.cell_start,
            &mut self.order,
        );
    }

    /// Builds the pair and wall lists for particles already in cell order (the order of the
    /// last `sort`, whose cell tables are reused).
    pub(crate) fn build(
        &mut self,
        domain: &DomainBox,
        positions: &[Vec3],
        radius: &[f64],
        fixed: &[bool],
        wall_faces: [bool; 6],
        pairs: bool,
    ) {
        let n = positions.len();
        // cell tables for the sorted order: particle k sits in cell_of[order[k]]
        let cells: Vec<u32> = self
            .order
            .iter()
            .map(|&o| self.cell_of[o as usize])
            .collect();
        let grid = &self.grid;
        let cell_start = &self.cell_start;
        let length = domain.length();
        let inv_l = domain.inverse_periodic_length();
        let skin = self.skin;
        let periodic = inv_l != Vec3::zeros();
        let any_fixed = fixed.iter().any(|&f| f);
        let chunks: Vec<(Vec<u32>, Vec<u32>)> = (0..n.div_ceil(CHUNK))
            .into_par_iter()
            .map(|c| {
                let (p0, p1) = (c * CHUNK, ((c + 1) * CHUNK).min(n));
                let mut counts = Vec::with_capacity(p1 - p0);
                let mut list = Vec::with_capacity(8 * (p1 - p0));
                let mut nb = [0usize; 27];
                for i in p0..p1 {
                    let before = list.len();
                    let ci = cells[i] as usize;
                    let cc = [
                        ci % grid.n[0],
                        (ci / grid.n[0]) % grid.n[1],
                        ci / (grid.n[0] * grid.n[1]),
                    ];
                    let m = grid.neighbours(cc, &mut nb);
                    let xi = positions[i];
                    let fixed_i = any_fixed && fixed[i];
                    let candidates = if pairs { &nb[..m] } else { &nb[..0] };
                    for &cell in candidates {
                        // sorted order: a cell's particles are one index range, so j > i is a
                        // range start rather than a test per candidate
                        let (s, e) = (cell_start[cell] as usize, cell_start[cell + 1] as usize);
                        for j in s.max(i + 1)..e {
                            if fixed_i && fixed[j] {
                                continue;
                            }
                            let xj = positions[j];
                            let mut d = Vec3::new(xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]);
                            if periodic {
                                d = minimum_image(d, length, inv_l);
                            }
                            let cut = radius[i] + radius[j] + skin;
                            if d.dot(&d) < cut * cut {
                                list.push(j as u32);
                            }
                        }
                    }
                    // ascending partners: a fixed summation order independent of cell order
                    list[before..].sort_unstable();
                    counts.push((list.len() - before) as u32);
                }
                (counts, list)
            })
            .collect();
        self.row_start.clear();
        self.row_start.push(0);
        self.partner.clear();
        for (counts, list) in &chunks {
            for &c in counts {
                let last = *self.row_start.last().unwrap();
                self.row_start.push(last + c);
            }
            self.partner.extend_from_slice(list);
        }
        let np = self.partner.len();
        self.history.clear();
        self.history.resize(np, Vec3::zeros());

        self.block = block_size(&self.row_start, &self.partner);
        self.far_pair.clear();
        for i in 0..n {
            let limit = (i / self.block + 2) * self.block;
            for k in self.row_start[i] as usize..self.row_start[i + 1] as usize {
                if self.partner[k] as usize >= limit {
                    self.far_pair.push(k as u32);
                }
            }
        }
        self.far_load.clear();
        self.far_load.resize(self.far_pair.len(), [0.0; 6]);
        // reverse rows of the far pairs by a counting sort; ascending within each row
        self.far_rev_start.clear();
        self.far_rev_start.resize(n + 1, 0);
        for &k in &self.far_pair {
            self.far_rev_start[self.partner[k as usize] as usize + 1] += 1;
        }
        for i in 0..n {
            self.far_rev_start[i + 1] += self.far_rev_start[i];
        }
        self.far_rev.clear();
        self.far_rev.resize(self.far_pair.len(), 0);
        let mut cursor: Vec<u32> = self.far_rev_start[..n].to_vec();
        for (f, &k) in self.far_pair.iter().enumerate() {
            let slot = &mut cursor[self.partner[k as usize] as usize];
            self.far_rev[*slot as usize] = f as u32;
            *slot += 1;
        }

        // wall list
        self.wall_start.clear();
        self.wall_start.push(0);
        self.wall_face.clear();
        for i in 0..n {
            if !fixed[i] {
                for (f, &is_wall) in wall_faces.iter().enumerate() {
                    if is_wall && wall_distance(domain, f, positions[i]) < radius[i] + skin {
                        self.wall_face.push(f as u8);
                    }
                }
            }
            self.wall_start.push(self.wall_face.len() as u32);
        }
        let nw = self.wall_face.len();
        self.wall_history.clear();
        self.wall_history.resize(nw, Vec3::zeros());
        self.wall_force.clear();
        self.wall_force.resize(nw, Vec3::zeros());
        self.wall_torque.clear();
        self.wall_torque.resize(nw, Vec3::zeros());

        self.reference.clear();
        self.reference.extend_from_slice(positions);
    }

    /// Before a re-sort: remembers the non-zero springs by (old) index.
    pub(crate) fn save_history(&mut self) {
        self.carry_pairs.clear();
        self.carry_walls.clear();
        for i in 0..self.row_start.len().saturating_sub(1) {
            for k in self.row_start[i] as usize..self.row_start[i + 1] as usize {
                if self.history[k] != Vec3::zeros() {
                    self.carry_pairs
                        .push((i as u32, self.partner[k], self.history[k]));
                }
            }
            for w in self.wall_start[i] as usize..self.wall_start[i + 1] as usize {
                if self.wall_history[w] != Vec3::zeros() {
                    self.carry_walls
                        .push((i as u32, self.wall_face[w], self.wall_history[w]));
                }
            }
        }
    }

    /// After `sort` and `build`: puts the saved springs on the new pairs through the
    /// permutation (new index `k` ← old `order[k]`). Rows are sorted, so each lookup is a
    /// binary search; no hashing on the rebuild path.
    pub(crate) fn restore_saved_history(&mut self) {
        self.inverse.clear();
        self.inverse.resize(self.order.len(), 0);
        for (k, &o) in self.order.iter().enumerate() {
            self.inverse[o as usize] = k as u32;
        }
        for &(oi, oj, xi) in &self.carry_pairs {
            let (ni, nj) = (self.inverse[oi as usize], self.inverse[oj as usize]);
            let (owner, other, x) = if ni < nj {
                (ni, nj, xi)
            } else {
                (nj, ni, Vec3::new(-xi[0], -xi[1], -xi[2]))
            };
            let (s, e) = (
                self.row_start[owner as usize] as usize,
                self.row_start[owner as usize + 1] as usize,
            );
            if let Ok(k) = self.partner[s..e].binary_search(&other) {
                self.history[s + k] = x;
            }
        }
        for &(oi, face, xi) in &self.carry_walls {
            let ni = self.inverse[oi as usize] as usize;
            for w in self.wall_start[ni] as usize..self.wall_start[ni + 1] as usize {
                if self.wall_face[w] == face {
                    self.wall_history[w] = xi;
                }
            }
        }
    }

    /// The non-zero springs, keyed by ids.
    pub(crate) fn export_history(&self, ids: &[u64]) -> ContactHistory {
        let mut h = ContactHistory::default();
        for i in 0..self.row_start.len().saturating_sub(1) {
            for k in self.row_start[i] as usize..self.row_start[i + 1] as usize {
                let xi = self.history[k];
                if xi != Vec3::zeros() {
                    let (a, b) = (ids[i], ids[self.partner[k] as usize]);
                    if a < b {
                        h.pairs.push((a, b, xi));
                    } else {
                        h.pairs.push((b, a, Vec3::new(-xi[0], -xi[1], -xi[2])));
                    }
                }
            }
            for w in self.wall_start[i] as usize..self.wall_start[i + 1] as usize {
                if self.wall_history[w] != Vec3::zeros() {
                    h.walls
                        .push((ids[i], self.wall_face[w], self.wall_history[w]));
                }
            }
        }
        h
    }

    /// Puts springs back on the pairs of freshly built lists. Springs of pairs no longer in the
    /// lists are dropped (those pairs had separated by more than the skin).
    pub(crate) fn import_history(&mut self, ids: &[u64], h: &ContactHistory) {
        if h.pairs.is_empty() && h.walls.is_empty() {
            return;
        }
        let pairs: HashMap<(u64, u64), Vec3> =
            h.pairs.iter().map(|&(a, b, x)| ((a, b), x)).collect();
        let walls: HashMap<(u64, u8), Vec3> =
            h.walls.iter().map(|&(a, f, x)| ((a, f), x)).collect();
        for i in 0..self.row_start.len() - 1 {
            for k in self.row_start[i] as usize..self.row_start[i + 1] as usize {
                let (a, b) = (ids[i], ids[self.partner[k] as usize]);
                if a < b {
                    if let Some(&x) = pairs.get(&(a, b)) {
                        self.history[k] = x;
                    }
                } else if let Some(&x) = pairs.get(&(b, a)) {
                    self.history[k] = Vec3::new(-x[0], -x[1], -x[2]);
                }
            }
            for w in self.wall_start[i] as usize..self.wall_start[i + 1] as usize {
                if let Some(&x) = walls.get(&(ids[i], self.wall_face[w])) {
                    self.wall_history[w] = x;
                }
            }
        }
    }

    /// Bytes held by the lists and their per-pair arrays (capacity).
    pub(crate) fn memory_bytes(&self) -> usize {
        let v3 = std::mem::size_of::<Vec3>();
        4 * (self.cell_of.capacity()
            + self.cell_start.capacity()
            + self.order.capacity()
            + self.row_start.capacity()
            + self.partner.capacity()
            + self.far_pair.capacity()
            + self.far_rev_start.capacity()
            + self.far_rev.capacity()
            + self.wall_start.capacity())
            + self.wall_face.capacity()
            + std::mem::size_of::<(u32, u32, Vec3)>() * self.carry_pairs.capacity()
            + std::mem::size_of::<(u32, u8, Vec3)>() * self.carry_walls.capacity()
            + 4 * self.inverse.capacity()
            + v3 * (self.history.capacity()
                + 2 * self.far_load.capacity()
                + self.wall_history.capacity()
                + self.wall_force.capacity()
                + self.wall_torque.capacity()
                + self.reference.capacity())
    }
}

/// The block size of the force pass: the 99th percentile of the index span `j − i` of the
/// listed pairs (so at most about 1% of pairs are far), at least [`MIN_BLOCK`] particles.
/// It depends on the lists only, never on the thread count.
fn block_size(row_start: &[u32], partner: &[u32]) -> usize {
    let n = row_start.len().saturating_sub(1);
    let mut spans: Vec<u32> = Vec::with_capacity(partner.len());
    for i in 0..n {
        for &j in &partner[row_start[i] as usize..row_start[i + 1] as usize] {
            spans.push(j - i as u32);
        }
    }
    if spans.is_empty() {
        return MIN_BLOCK.max(n).max(1);
    }
    let q = (spans.len() * 99) / 100;
    let last = spans.len() - 1;
    let (_, &mut p99, _) = spans.select_nth_unstable(q.min(last));
    (p99 as usize + 1).max(MIN_BLOCK)
}

/// Distance from a point to face `f` (positive inside the box).
#[inline(always)]
pub(crate) fn wall_distance(domain: &DomainBox, f: usize, x: Vec3) -> f64 {
    let a = f / 2;
    if f.is_multiple_of(2) {
        x[a] - domain.lo[a]
    } else {
        domain.hi[a] - x[a]
    }
}

/// Unit normal of face `f` pointing into the box.
#[inline(always)]
pub(crate) fn wall_normal(f: usize) -> Vec3 {
    let mut n = Vec3::zeros();
    n[f / 2] = if f.is_multiple_of(2) { 1.0 } else { -1.0 };
    n
}

/// Which faces carry soft wall contacts.
pub(crate) fn wall_mask(domain: &DomainBox) -> [bool; 6] {
    let mut m = [false; 6];
    for (f, c) in domain.faces.iter().enumerate() {
        m[f] = *c == FaceCondition::Wall;
    }
    m
}
