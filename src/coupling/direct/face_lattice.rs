//! One velocity component's lattice of faces, as the forced-face build and refresh read it:
//! positions, periodic wraps and the padded slots of the faces the fluid advances.

use super::forced_face::ForcingLine;
use super::rigid_sphere::RigidSphere;
use crate::fluid::PaddedLayout;
use crate::grid::{nearest_image, wrap_index, Grid};
use crate::Vec3;

/// One velocity component's lattice, as the forced-face search reads it.
pub(super) struct FaceLattice<'a> {
    pub(super) grid: &'a Grid,
    /// Box lengths.
    pub(super) length: [f64; 3],
    pub(super) layout: &'a PaddedLayout,
    pub(super) periodic: [bool; 3],
    /// Advanced padded slots per direction (inclusive).
    pub(super) range: [(usize, usize); 3],
    pub(super) c: usize,
}

impl FaceLattice<'_> {
    /// Position of the sample at lattice index `m` along direction `d`.
    #[inline]
    pub(super) fn coordinate(&self, d: usize, m: isize) -> f64 {
        let g = self.grid;
        let offset = if self.c == d { 0.0 } else { 0.5 };
        g.origin[d] + (m as f64 + offset) * g.h[d]
    }

    /// Position of the sample at padded slot `slot` (its lattice index wrapped into the box).
    #[inline]
    pub(super) fn slot_position(&self, slot: usize) -> [f64; 3] {
        self.site_position(self.slot_site(slot))
    }

    /// Padded indices of padded slot `slot`.
    #[inline]
    pub(super) fn slot_site(&self, slot: usize) -> [usize; 3] {
        let dims = self.layout.dims;
        let column = slot / dims[0];
        [slot - column * dims[0], column % dims[1], column / dims[1]]
    }

    /// Rigid velocity (this component) of `sphere` at the face in slot `slot`.
    #[inline]
    pub(super) fn interior_target(&self, slot: usize, sphere: &RigidSphere) -> f64 {
        let rel = self.relative(self.slot_position(slot), sphere);
        sphere.velocity_at(rel)[self.c]
    }

    /// Distance `t ∈ [0, h]` from the face at `x` along its line to the sphere's surface:
    /// the nearer root of `|x − x_p + t step e_d| = r` (0 for a face inside).
    #[inline]
    pub(super) fn surface_distance(
        &self,
        x: [f64; 3],
        sphere: &RigidSphere,
        line: ForcingLine,
    ) -> f64 {
        let rel = self.relative(x, sphere);
        let b = line.step as f64 * rel[line.d];
        let q = rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2] - sphere.radius * sphere.radius;
        let disc = (b * b - q).max(0.0);
        (-b - disc.sqrt()).clamp(0.0, self.grid.h[line.d])
    }

    /// Distance along `step e_d` from a point at `rel` from a sphere's centre, outside it, to
    /// where the line enters the sphere (the nearer root of `|rel + s step e_d| = radius`),
    /// if it does.
    #[inline]
    pub(super) fn entry_distance(rel: Vec3, radius: f64, d: usize, step: isize) -> Option<f64> {
        let b = step as f64 * rel[d];
        let q = rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2] - radius * radius;
        let disc = b * b - q;
        (disc >= 0.0 && b < 0.0).then(|| -b - disc.sqrt())
    }

    /// Rigid velocity (this component) of `sphere` at `t` along `line` from `x`, taken at the
    /// periodic image of the sphere nearest that point (a far wall: [`super::GapFace`]).
    #[inline]
    pub(super) fn velocity_beyond(
        &self,
        mut x: [f64; 3],
        t: f64,
        line: ForcingLine,
        sphere: &RigidSphere,
    ) -> f64 {
        x[line.d] += line.step as f64 * t;
        sphere.velocity_at(self.relative(x, sphere))[self.c]
    }

    /// Rigid velocity (this component) of `sphere` at `t` from the face at `x` along its line.
    #[inline]
    pub(super) fn wall_velocity(
        &self,
        x: [f64; 3],
        t: f64,
        line: ForcingLine,
        sphere: &RigidSphere,
    ) -> f64 {
        let mut rel = self.relative(x, sphere);
        rel[line.d] += line.step as f64 * t;
        sphere.velocity_at(rel)[self.c]
    }

    /// Padded index along `d` of lattice index `m`, if the fluid advances it.
    #[inline]
    pub(super) fn axis_slot(&self, d: usize, m: isize) -> Option<usize> {
        let md = if self.periodic[d] {
            wrap_index(m, self.grid.n[d] as isize)
        } else {
            m
        };
        let slot = md + 1;
        let (lo, hi) = self.range[d];
        (slot >= lo as isize && slot <= hi as isize).then_some(slot as usize)
    }

    /// Padded indices of the face `step` (±1) along `d` from the advanced face at padded
    /// indices `site`, if the fluid advances it: [`Self::site`] of the neighbouring lattice
    /// index, without unwrapping (the wrap of a neighbour is one step around the box).
    #[inline]
    pub(super) fn adjacent(&self, site: [usize; 3], d: usize, step: isize) -> Option<[usize; 3]> {
        let n = self.grid.n[d] as isize;
        let mut v = site[d] as isize + step;
        if self.periodic[d] {
            if v < 1 {
                v += n;
            } else if v > n {
                v -= n;
            }
        }
        let (lo, hi) = self.range[d];
        let mut out = site;
        out[d] = v as usize;
        (v >= lo as isize && v <= hi as isize).then_some(out)
    }

    /// Position of the sample at padded indices `site` (what [`Self::slot_position`] gives
    /// for its slot, without the slot's divisions).
    #[inline]
    pub(super) fn site_position(&self, site: [usize; 3]) -> [f64; 3] {
        std::array::from_fn(|d| self.coordinate(d, site[d] as isize - 1))
    }

    /// Padded indices of lattice index `m`, if the fluid advances that face.
    #[inline]
    pub(super) fn site(&self, m: [isize; 3]) -> Option<[usize; 3]> {
        Some([
            self.axis_slot(0, m[0])?,
            self.axis_slot(1, m[1])?,
            self.axis_slot(2, m[2])?,
        ])
    }

    /// Cells below and above the face at padded indices `s` (unpadded indices).
    pub(super) fn cells(&self, mut s: [usize; 3]) -> [u32; 2] {
        let n = self.grid.n;
        let hi = self.grid.cell_index(
            (s[0] - 1).min(n[0] - 1),
            (s[1] - 1).min(n[1] - 1),
            (s[2] - 1).min(n[2] - 1),
        );
        // The cell below along c (periodic wrap at slot 1).
        let c = self.c;
        s[c] = if s[c] >= 2 { s[c] - 1 } else { n[c] };
        let lo = self.grid.cell_index(
            (s[0] - 1).min(n[0] - 1),
            (s[1] - 1).min(n[1] - 1),
            (s[2] - 1).min(n[2] - 1),
        );
        [lo as u32, hi as u32]
    }

    /// FaceLattice box of the samples within `margin` cells of the sphere.
    pub(super) fn bounds(&self, s: &RigidSphere, margin: isize) -> [(isize, isize); 3] {
        let g = self.grid;
        std::array::from_fn(|d| {
            let offset = if self.c == d { 0.0 } else { 0.5 };
            let lo = ((s.centre[d] - s.radius - g.origin[d]) / g.h[d] - offset).floor() as isize;
            let hi = ((s.centre[d] + s.radius - g.origin[d]) / g.h[d] - offset).ceil() as isize;
            (lo - margin, hi + margin)
        })
    }

    /// `x − x_p` for the nearest periodic image of sphere `s`.
    #[inline]
    pub(super) fn relative(&self, x: [f64; 3], s: &RigidSphere) -> Vec3 {
        Vec3::from_fn(|d, _| {
            let r = x[d] - s.centre[d];
            if self.periodic[d] {
                nearest_image(r, self.length[d])
            } else {
                r
            }
        })
    }
}
