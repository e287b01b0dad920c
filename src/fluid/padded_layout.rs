//! Memory layout of the solver's padded arrays.
//!
//! Every velocity component is stored in an array of `(n₀+2)(n₁+2)(n₂+2)` values, x fastest:
//! `index = i + (n₀+2)(j + (n₁+2) k)` with padded indices `i ∈ [0, n₀+1]`. Padded cell `i`
//! (1 ≤ i ≤ n₀) is grid cell `i−1`; slots 0 and `n₀+1` are the ghost layers a later domain
//! decomposition exchanges.
//!
//! A face-normal component shares the indices of the cell whose *low* face it sits on: `u` at
//! padded `(i, j, k)` is at `x = origin + (i−1) h₀`, `y, z` at the cell centre. So along its own
//! direction `u` has the boundary faces at slot 1 (`x = 0`) and slot `n₀+1` (`x = L`), the
//! latter living in the ghost layer.

/// Shape and strides of a padded (one ghost layer per side) array.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PaddedLayout {
    /// Interior cells per direction.
    pub n: [usize; 3],
    /// Padded extent per direction, `n + 2`.
    pub dims: [usize; 3],
    /// Linear stride per direction: `[1, dims₀, dims₀ dims₁]`.
    pub stride: [usize; 3],
    /// Total length of a padded array.
    pub len: usize,
}

impl PaddedLayout {
    pub fn new(n: [usize; 3]) -> Self {
        let dims = [n[0] + 2, n[1] + 2, n[2] + 2];
        PaddedLayout {
            n,
            dims,
            stride: [1, dims[0], dims[0] * dims[1]],
            len: dims[0] * dims[1] * dims[2],
        }
    }

    /// Linear index of padded `(i, j, k)`.
    #[inline]
    pub fn index(&self, i: usize, j: usize, k: usize) -> usize {
        i + self.dims[0] * (j + self.dims[1] * k)
    }

    /// Values in one padded k-plane.
    #[inline]
    pub fn plane_len(&self) -> usize {
        self.dims[0] * self.dims[1]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strides_match_index() {
        let l = PaddedLayout::new([4, 3, 2]);
        assert_eq!(l.dims, [6, 5, 4]);
        assert_eq!(l.len, 120);
        assert_eq!(l.index(1, 0, 0), l.stride[0]);
        assert_eq!(l.index(0, 1, 0), l.stride[1]);
        assert_eq!(l.index(0, 0, 1), l.stride[2]);
        assert_eq!(l.plane_len(), 30);
    }
}
