//! Linked cells: the box cut into cells at least one interaction range wide, and a counting
//! sort of particles by cell so that particles of one cell are contiguous.

use super::domain_box::DomainBox;
use crate::Vec3;

#[derive(Clone, Debug, Default)]
pub(crate) struct CellGrid {
    lo: Vec3,
    pub(crate) n: [usize; 3],
    inv_size: Vec3,
    periodic: [bool; 3],
}

impl CellGrid {
    /// Cells no smaller than `min_size` (the largest `d_i/2 + d_j/2 + skin`), and no more than
    /// `max_cells` of them (tiny particles in a huge box would otherwise ask for more cells
    /// than memory holds; larger cells only cost efficiency, never correctness).
    pub(crate) fn new(domain: &DomainBox, min_size: f64, max_cells: usize) -> Self {
        let l = domain.length();
        let mut size = if min_size > 0.0 {
            min_size
        } else {
            l[0].max(l[1]).max(l[2])
        };
        let mut n = [1usize; 3];
        loop {
            for a in 0..3 {
                n[a] = ((l[a] / size).floor() as usize).clamp(1, 1 << 20);
            }
            if n.iter().product::<usize>() <= max_cells.max(1) {
                break;
            }
            size *= 1.25;
        }
        let mut inv_size = Vec3::zeros();
        let mut periodic = [false; 3];
        for a in 0..3 {
            inv_size[a] = n[a] as f64 / l[a];
            periodic[a] = domain.is_periodic(a);
        }
        CellGrid {
            lo: domain.lo,
            n,
            inv_size,
            periodic,
        }
    }

    /// The edges of a cell.
    pub(crate) fn cell_size(&self) -> Vec3 {
        Vec3::from_fn(|a, _| 1.0 / self.inv_size[a])
    }

    pub(crate) fn cell_count(&self) -> usize {
        self.n[0] * self.n[1] * self.n[2]
    }

    /// Cell coordinates of a point, clamped into the grid (a particle slightly through a wall
    /// or not yet wrapped still gets a valid cell).
    #[inline]
    pub(crate) fn coords(&self, x: Vec3) -> [usize; 3] {
        let mut c = [0usize; 3];
        for a in 0..3 {
            let f = ((x[a] - self.lo[a]) * self.inv_size[a]).floor();
            c[a] = if f < 0.0 {
                0
            } else {
                (f as usize).min(self.n[a] - 1)
            };
        }
        c
    }

    #[inline]
    pub(crate) fn index(&self, c: [usize; 3]) -> usize {
        c[0] + self.n[0] * (c[1] + self.n[1] * c[2])
    }

    /// Distinct neighbour coordinates along one axis: `c−1, c, c+1`, wrapped on periodic axes
    /// and cut at the ends of walled ones. With fewer than three cells on a periodic axis the
    /// wrapped neighbours coincide, so they are listed once.
    #[inline]
    fn axis_neighbours(&self, a: usize, c: usize, out: &mut [usize; 3]) -> usize {
        let n = self.n[a];
        if self.periodic[a] {
            match n {
                1 => {
                    out[0] = 0;
                    1
                }
                2 => {
                    out[0] = 0;
                    out[1] = 1;
                    2
                }
                _ => {
                    out[0] = (c + n - 1) % n;
                    out[1] = c;
                    out[2] = (c + 1) % n;
                    3
                }
            }
        } else {
            let mut k = 0;
            if c > 0 {
                out[k] = c - 1;
                k += 1;
            }
            out[k] = c;
            k += 1;
            if c + 1 < n {
                out[k] = c + 1;
                k += 1;
            }
            k
        }
    }

    /// The (up to 27) distinct cells adjacent to `c`, itself included; returns the count.
    #[inline]
    pub(crate) fn neighbours(&self, c: [usize; 3], out: &mut [usize; 27]) -> usize {
        let (mut xs, mut ys, mut zs) = ([0; 3], [0; 3], [0; 3]);
        let nx = self.axis_neighbours(0, c[0], &mut xs);
        let ny = self.axis_neighbours(1, c[1], &mut ys);
        let nz = self.axis_neighbours(2, c[2], &mut zs);
        let mut k = 0;
        for &z in &zs[..nz] {
            for &y in &ys[..ny] {
                for &x in &xs[..nx] {
                    out[k] = self.index([x, y, z]);
                    k += 1;
                }
            }
        }
        k
    }

    /// Counting sort by cell. On return `order[k]` is the particle placed at sorted position
    /// `k` (stable: equal cells keep their input order) and the particles of cell `c` are
    /// sorted positions `cell_start[c]..cell_start[c+1]`.
    pub(crate) fn counting_sort(
        &self,
        positions: &[Vec3],
        cell_of: &mut Vec<u32>,
        cell_start: &mut Vec<u32>,
        order: &mut Vec<u32>,
    ) {
        let nc = self.cell_count();
        cell_of.clear();
        cell_of.extend(positions.iter().map(|&x| self.index(self.coords(x)) as u32));
        cell_start.clear();
        cell_start.resize(nc + 1, 0);
        for &c in cell_of.iter() {
            cell_start[c as usize + 1] += 1;
        }
        for c in 0..nc {
            cell_start[c + 1] += cell_start[c];
        }
        order.clear();
        order.resize(positions.len(), 0);
        // Fill positions per cell with a running cursor; cell_start is restored afterwards.
        let mut cursor: Vec<u32> = cell_start[..nc].to_vec();
        for (p, &c) in cell_of.iter().enumerate() {
            let slot = &mut cursor[c as usize];
            order[*slot as usize] = p as u32;
            *slot += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::particles::domain_box::FaceCondition;

    #[test]
    fn counting_sort_groups_by_cell_and_is_stable() {
        let b = DomainBox::walled(Vec3::zeros(), [4.0, 1.0, 1.0]);
        let g = CellGrid::new(&b, 1.0, 1000);
        assert_eq!(g.n, [4, 1, 1]);
        let x = [
            Vec3::new(3.5, 0.5, 0.5),
            Vec3::new(0.5, 0.5, 0.5),
            Vec3::new(3.2, 0.5, 0.5),
            Vec3::new(1.5, 0.5, 0.5),
            Vec3::new(-0.1, 0.5, 0.5),
        ];
        let (mut c, mut s, mut o) = (Vec::new(), Vec::new(), Vec::new());
        g.counting_sort(&x, &mut c, &mut s, &mut o);
        assert_eq!(o, vec![1, 4, 3, 0, 2]);
        assert_eq!(s, vec![0, 2, 3, 3, 5]);
    }

    #[test]
    fn cell_count_is_capped() {
        let b = DomainBox::walled(Vec3::zeros(), [1.0; 3]);
        let g = CellGrid::new(&b, 1e-6, 1000);
        assert!(g.cell_count() <= 1000 && g.cell_count() >= 500, "{:?}", g.n);
        let g = CellGrid::new(&b, 0.0, 1000);
        assert_eq!(g.n, [1, 1, 1]);
    }

    #[test]
    fn neighbour_cells_are_distinct_when_periodic_axis_is_short() {
        let mut b = DomainBox::walled(Vec3::zeros(), [2.0, 5.0, 1.0]);
        for f in [0, 1, 4, 5] {
            b.faces[f] = FaceCondition::Periodic;
        }
        let g = CellGrid::new(&b, 1.0, 1000);
        assert_eq!(g.n, [2, 5, 1]);
        let mut out = [0; 27];
        let k = g.neighbours([0, 0, 0], &mut out);
        // x: {0,1}; y walled at the low end: {0,1}; z: {0}
        assert_eq!(k, 4);
        let k = g.neighbours([1, 2, 0], &mut out);
        assert_eq!(k, 6);
        let mut v = out[..k].to_vec();
        v.sort();
        v.dedup();
        assert_eq!(v.len(), 6);
    }
}
