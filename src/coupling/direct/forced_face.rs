//! The forced faces of the direct forcing, as the fluid step imposes them, and the labels
//! that mark them on the grid ([`super::ImmersedBoundary`] builds and imposes them).

/// A face inside a sphere: it moves with the sphere. Indices are `u32` (a grid has fewer
/// than 2³² slots, checked in
/// [`ImmersedBoundary::new`](super::ImmersedBoundary::new)): the lists are rebuilt every step
/// and are the direct model's largest after the fields (24 bytes a face instead of 40).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InteriorFace {
    /// Padded index of the face.
    pub slot: u32,
    /// Cell-centred (unpadded) indices of the cells below and above the face along its
    /// component, for the pressure compensation.
    pub cells: [u32; 2],
    /// Rigid velocity (this component) at the face, m/s.
    pub target: f64,
    /// Index of the sphere the face is in (fills the padding: the face stays 24 bytes).
    pub sphere: u32,
}

/// A fluid face next to a sphere: `u = w + Σ_k a_k (u_k − w)` over the next one or two
/// fluid faces `k` along the interpolation line. Indices as in [`InteriorFace`] (64 bytes a
/// face instead of 96).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForcingFace {
    pub slot: u32,
    pub cells: [u32; 2],
    /// The next two fluid faces along the interpolation line, away from the sphere (the
    /// second equals the first for the linear stencil).
    pub neighbours: [u32; 2],
    pub neighbour_cells: [[u32; 2]; 2],
    /// Interpolation weights: linear `[δ/(δ+h), 0]`, quadratic
    /// `[2δ/(δ+h), −δ/(δ+2h)]`; `[0, 0]` for the staircase fallback.
    pub weights: [f64; 2],
    /// Rigid velocity (this component) where the line crosses the surface, m/s.
    pub wall: f64,
    /// The sphere the line crosses and the line's direction from the face, packed by
    /// `ForcingLine` (fills the padding: the face stays 64 bytes).
    pub line: u32,
}

/// The interpolation line of a [`ForcingFace`]: the sphere it crosses and its direction
/// from the face towards the sphere, `e_d · step`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ForcingLine {
    pub sphere: usize,
    pub d: usize,
    /// −1 or +1.
    pub step: isize,
}

impl ForcingLine {
    /// Spheres a packed line can name (three bits hold the direction).
    pub(super) const MAX_SPHERES: usize = 1 << 29;

    pub(super) fn pack(self) -> u32 {
        ((self.sphere as u32) << 3) | (2 * self.d as u32) | u32::from(self.step > 0)
    }

    pub fn unpack(packed: u32) -> Self {
        ForcingLine {
            sphere: (packed >> 3) as usize,
            d: ((packed & 7) / 2) as usize,
            step: if packed & 1 == 1 { 1 } else { -1 },
        }
    }
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
pub(super) const FLUID: u32 = 0;
/// Label of a forcing face (inside faces hold `sphere index + 1`).
pub(super) const FORCING: u32 = u32::MAX;
