//! Pairs of spheres whose surfaces are closer than a given gap, found with linked cells.
//!
//! Cells are at least `2 r_max + gap` wide (and no more than about `(2n)^{1/3}` per axis), so a pair within range lies in the same or a
//! neighbouring cell; with three or more cells along every axis the 27 neighbour cells are
//! distinct (also across periodic faces) and each pair is met once, from its lower index.
//! Smaller boxes compare all pairs. The cell arrays are kept between calls.

use crate::particles::ParticleState;
use crate::Vec3;

/// The box as a pair search sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PeriodicBox {
    pub lo: Vec3,
    pub hi: Vec3,
    pub periodic: [bool; 3],
}

/// Linked cells: the first particle of each cell and the next one in the same cell.
#[derive(Clone, Debug, Default)]
pub struct ClosePairs {
    head: Vec<usize>,
    next: Vec<usize>,
}

const NONE: usize = usize::MAX;

impl ClosePairs {
    /// Calls `visit(i, j, d, |d|, gap)` for every pair `i < j` whose surface gap is below
    /// `gap_limit`, with `d = x_j − x_i` (minimum image) and `gap = |d| − r_i − r_j`.
    pub fn visit(
        &mut self,
        p: &ParticleState,
        domain: &PeriodicBox,
        gap_limit: f64,
        visit: impl FnMut(usize, usize, Vec3, f64, f64),
    ) {
        let (position, diameter) = (&p.position, &p.diameter);
        self.visit_spheres(
            p.len(),
            |i| position[i],
            |i| diameter[i],
            domain,
            gap_limit,
            visit,
        );
    }

    /// [`Self::visit`] for `n` spheres given by their centres and diameters (inside the box
    /// along its walled axes; along a periodic one any image will do).
    pub fn visit_spheres(
        &mut self,
        n: usize,
        position: impl Fn(usize) -> Vec3,
        diameter: impl Fn(usize) -> f64,
        domain: &PeriodicBox,
        gap_limit: f64,
        mut visit: impl FnMut(usize, usize, Vec3, f64, f64),
    ) {
        if n < 2 {
            return;
        }
        let length: Vec3 = Vec3::from_fn(|a, _| domain.hi[a] - domain.lo[a]);
        let r_max = (0..n).map(&diameter).fold(0.0, f64::max) / 2.0;
        let reach = 2.0 * r_max + gap_limit.max(0.0);
        // Cells no narrower than the reach, and no more of them per axis than about
        // (2n)^(1/3): a few large spheres in a big box need no fine mesh of empty cells.
        let cap = ((2.0 * n as f64).cbrt().ceil() as usize).max(3);
        let cells: [usize; 3] =
            std::array::from_fn(|a| ((length[a] / reach).floor() as usize).clamp(1, cap));
        let mut pair = |i: usize, j: usize| {
            let mut d: Vec3 = Vec3::from_fn(|a, _| position(j)[a] - position(i)[a]);
            for a in 0..3 {
                if domain.periodic[a] {
                    d[a] -= length[a] * (d[a] / length[a]).round();
                }
            }
            let dist = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let gap = dist - 0.5 * (diameter(i) + diameter(j));
            if gap < gap_limit {
                visit(i, j, d, dist, gap);
            }
        };
        if cells.iter().any(|&c| c < 3) {
            for i in 0..n {
                for j in i + 1..n {
                    pair(i, j);
                }
            }
            return;
        }
        self.head.clear();
        self.head.resize(cells[0] * cells[1] * cells[2], NONE);
        self.next.clear();
        self.next.resize(n, NONE);
        // A centre outside the box along a periodic axis (not yet wrapped) goes to the cell
        // of its image; the gaps come from the centres as given, by the nearest image.
        let cell_of = |x: Vec3| -> [usize; 3] {
            std::array::from_fn(|a| {
                let mut s = (x[a] - domain.lo[a]) / length[a];
                if domain.periodic[a] {
                    s -= s.floor();
                }
                ((s * cells[a] as f64).floor().max(0.0) as usize).min(cells[a] - 1)
            })
        };
        let flat = |c: [usize; 3]| c[0] + cells[0] * (c[1] + cells[1] * c[2]);
        for i in (0..n).rev() {
            let k = flat(cell_of(position(i)));
            self.next[i] = self.head[k];
            self.head[k] = i;
        }
        for i in 0..n {
            let home = cell_of(position(i));
            for off in NEIGHBOURS {
                let Some(c) = neighbour(home, off, cells, domain.periodic) else {
                    continue;
                };
                let mut j = self.head[flat(c)];
                while j != NONE {
                    if j > i {
                        pair(i, j);
                    }
                    j = self.next[j];
                }
            }
        }
    }
}

/// The 27 offsets of a cell's neighbourhood, itself included.
const NEIGHBOURS: [[i64; 3]; 27] = {
    let mut o = [[0i64; 3]; 27];
    let mut k = 0;
    while k < 27 {
        o[k] = [
            (k % 3) as i64 - 1,
            ((k / 3) % 3) as i64 - 1,
            (k / 9) as i64 - 1,
        ];
        k += 1;
    }
    o
};

fn neighbour(
    home: [usize; 3],
    off: [i64; 3],
    cells: [usize; 3],
    periodic: [bool; 3],
) -> Option<[usize; 3]> {
    let mut c = [0usize; 3];
    for a in 0..3 {
        let v = home[a] as i64 + off[a];
        let m = cells[a] as i64;
        c[a] = if (0..m).contains(&v) {
            v as usize
        } else if periodic[a] {
            v.rem_euclid(m) as usize
        } else {
            return None;
        };
    }
    Some(c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::particles::SplitMix64;

    /// Linked cells find exactly the pairs an all-pairs comparison finds, across periodic
    /// faces and next to walls.
    #[test]
    fn agrees_with_all_pairs() {
        for periodic in [[true; 3], [true, false, true]] {
            let mut rng = SplitMix64::new(11);
            let mut p = ParticleState::default();
            for id in 0..400 {
                let x = [rng.next_f64(), rng.next_f64(), rng.next_f64()];
                p.push(id, x, 0.02 + 0.03 * rng.next_f64(), 1000.0);
            }
            let domain = PeriodicBox {
                lo: Vec3::repeat(0.0),
                hi: Vec3::repeat(1.0),
                periodic,
            };
            let mut fast = Vec::new();
            ClosePairs::default()
                .visit(&p, &domain, 0.02, |i, j, _, _, gap| fast.push((i, j, gap)));
            // one cell per axis: all pairs
            let mut slow = Vec::new();
            let huge = 0.02;
            let mut q = p.clone();
            q.diameter[0] = 0.6; // forces fewer than 3 cells
            ClosePairs::default().visit(&q, &domain, huge, |i, j, _, _, gap| {
                if i != 0 {
                    slow.push((i, j, gap))
                }
            });
            fast.retain(|&(i, _, _)| i != 0);
            fast.sort_by_key(|a| (a.0, a.1));
            slow.sort_by_key(|a| (a.0, a.1));
            assert!(fast.len() > 20, "only {} pairs", fast.len());
            assert_eq!(fast.len(), slow.len());
            for (f, s) in fast.iter().zip(&slow) {
                assert_eq!((f.0, f.1), (s.0, s.1));
                assert!((f.2 - s.2).abs() < 1e-15);
            }
        }
    }

    /// Centres a box length or two outside a periodic box (as a caller that does not wrap
    /// them hands them) give the same pairs and gaps as the wrapped ones.
    #[test]
    fn unwrapped_centres_find_the_same_pairs() {
        let mut rng = SplitMix64::new(29);
        let n = 300;
        let diameter: Vec<f64> = (0..n).map(|_| 0.02 + 0.03 * rng.next_f64()).collect();
        let wrapped: Vec<Vec3> = (0..n)
            .map(|_| Vec3::from_fn(|_, _| rng.next_f64()))
            .collect();
        let shifted: Vec<Vec3> = wrapped
            .iter()
            .map(|x| x.map(|v| v + (rng.next_f64() * 5.0).floor() - 2.0))
            .collect();
        let domain = PeriodicBox {
            lo: Vec3::repeat(0.0),
            hi: Vec3::repeat(1.0),
            periodic: [true; 3],
        };
        let pairs = |x: &[Vec3]| {
            let mut found = Vec::new();
            ClosePairs::default().visit_spheres(
                n,
                |i| x[i],
                |i| diameter[i],
                &domain,
                0.02,
                |i, j, _, _, g| found.push((i, j, g)),
            );
            found.sort_by_key(|a| (a.0, a.1));
            found
        };
        let (a, b) = (pairs(&wrapped), pairs(&shifted));
        assert!(a.len() > 20, "only {} pairs", a.len());
        assert_eq!(a.len(), b.len());
        for (p, q) in a.iter().zip(&b) {
            assert_eq!((p.0, p.1), (q.0, q.1));
            assert!((p.2 - q.2).abs() < 1e-12, "gap {} against {}", p.2, q.2);
        }
    }
}
