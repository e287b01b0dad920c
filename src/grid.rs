//! The uniform staggered (MAC) grid: one hex block of `n[0] × n[1] × n[2]` equal cells.
//!
//! Pressure and every scalar live at cell centres; the velocity component `d` lives on the
//! faces normal to direction `d`. Cell `(i, j, k)` has its centre at
//! `origin + ((i + ½) h₀, (j + ½) h₁, (k + ½) h₂)` and the `u` sample with the same indices sits
//! on its low-x face, at `origin + (i h₀, (j + ½) h₁, (k + ½) h₂)`.
//!
//! Cell-centred arrays handed between modules (output, coupling) are contiguous, unpadded,
//! x fastest: `index = i + n₀ (j + n₁ k)`. The fluid solver may pad its own arrays with ghost
//! layers (a later domain decomposition exchanges exactly those layers).

/// Geometry of the uniform grid. Cells may be anisotropic (`h[0] ≠ h[1]`), never graded.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// Number of cells per direction.
    pub n: [usize; 3],
    /// Cell size per direction, in metres.
    pub h: [f64; 3],
    /// Position of the block's lowest corner, in metres.
    pub origin: [f64; 3],
}

impl Grid {
    pub fn new(n: [usize; 3], h: [f64; 3], origin: [f64; 3]) -> Self {
        Grid { n, h, origin }
    }

    /// Total number of cells.
    pub fn cell_count(&self) -> usize {
        self.n[0] * self.n[1] * self.n[2]
    }

    /// Domain length per direction.
    pub fn length(&self) -> [f64; 3] {
        [
            self.n[0] as f64 * self.h[0],
            self.n[1] as f64 * self.h[1],
            self.n[2] as f64 * self.h[2],
        ]
    }

    /// Cell volume.
    pub fn cell_volume(&self) -> f64 {
        self.h[0] * self.h[1] * self.h[2]
    }

    /// Linear index of cell `(i, j, k)` in an unpadded x-fastest array.
    #[inline]
    pub fn cell_index(&self, i: usize, j: usize, k: usize) -> usize {
        i + self.n[0] * (j + self.n[1] * k)
    }

    /// Centre of cell `(i, j, k)`.
    pub fn cell_centre(&self, i: usize, j: usize, k: usize) -> [f64; 3] {
        [
            self.origin[0] + (i as f64 + 0.5) * self.h[0],
            self.origin[1] + (j as f64 + 0.5) * self.h[1],
            self.origin[2] + (k as f64 + 0.5) * self.h[2],
        ]
    }
}

/// `⌊s⌋` without a libm call (exact for |s| < 2⁵³; the library `floor` is a call without
/// SSE4.1, and the particle ↔ grid hot loops run it for every particle and step).
#[inline(always)]
pub(crate) fn fast_floor(s: f64) -> isize {
    let i = s as isize;
    i - isize::from((i as f64) > s)
}

/// `i mod n` in `[0, n)`, without a division for the usual `−n ≤ i < 2n` (periodic index
/// wrapping in hot loops).
#[inline]
pub(crate) fn wrap_index(i: isize, n: isize) -> isize {
    if i < 0 {
        if i >= -n {
            i + n
        } else {
            i.rem_euclid(n)
        }
    } else if i < n {
        i
    } else if i < 2 * n {
        i - n
    } else {
        i.rem_euclid(n)
    }
}

/// `r − L round(r/L)`: the nearest periodic image of a separation `r` along a box length `L`,
/// without a libm call for the usual `|r| < 1.5 L` (the same value as `round`, which rounds
/// halves away from zero).
#[inline]
pub(crate) fn nearest_image(r: f64, length: f64) -> f64 {
    let q = r / length;
    let k = if q >= 0.5 {
        if q < 1.5 {
            1.0
        } else {
            q.round()
        }
    } else if q <= -0.5 {
        if q > -1.5 {
            -1.0
        } else {
            q.round()
        }
    } else {
        0.0
    };
    r - length * k
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn index_is_x_fastest_and_centres_are_offset_by_half_a_cell() {
        let g = Grid::new([4, 3, 2], [0.5, 1.0, 2.0], [1.0, 0.0, -1.0]);
        assert_eq!(g.cell_count(), 24);
        assert_eq!(g.cell_index(1, 0, 0), 1);
        assert_eq!(g.cell_index(0, 1, 0), 4);
        assert_eq!(g.cell_index(0, 0, 1), 12);
        assert_eq!(g.cell_centre(0, 0, 0), [1.25, 0.5, 0.0]);
        assert_eq!(g.length(), [2.0, 3.0, 4.0]);
        assert_eq!(g.cell_volume(), 1.0);
    }

    #[test]
    fn fast_floor_and_wrap_index_match_the_library() {
        for s in [-2.5, -2.0, -0.3, 0.0, 0.7, 1.0, 3.999] {
            assert_eq!(fast_floor(s), s.floor() as isize, "{s}");
        }
        for i in -25..25 {
            assert_eq!(wrap_index(i, 7), i.rem_euclid(7), "{i}");
        }
        for r in [
            -3.7, -1.5, -1.2, -0.5, -0.49, 0.0, 0.3, 0.5, 1.25, 1.75, 4.4,
        ] {
            assert_eq!(nearest_image(r, 1.0), r - (r / 1.0f64).round(), "{r}");
        }
    }
}
