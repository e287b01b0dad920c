//! The viscous Helmholtz problem of one semi-implicit (`RK3CN`) stage, lent to a hook.
//!
//! The stage solves `(I − κ∇²) u* = r` per component (`κ = β Δt ν`) before the hook sees
//! `u*`. A hook that constrains faces (the direct model's forcing) cannot simply overwrite
//! them afterwards: the implicit solve has already spread the unconstrained values into the
//! neighbouring fluid faces. With this handle it can solve the constrained problem instead,
//! by adding corrections `(I − κ∇²)⁻¹ e` (homogeneous boundary values) to `u*`.

use super::implicit_viscosity::ImplicitViscosity;
use super::padded_layout::PaddedLayout;

/// The Helmholtz operator of the current semi-implicit stage (see the module docs).
pub struct ImplicitStage<'a> {
    pub(crate) solver: &'a mut ImplicitViscosity,
    pub(crate) layout: &'a PaddedLayout,
    pub(crate) ranges: &'a [[(usize, usize); 3]; 3],
    pub(crate) kappa: f64,
    pub(crate) index: usize,
}

impl ImplicitStage<'_> {
    /// `κ = β Δt ν` of the stage, m².
    pub fn kappa(&self) -> f64 {
        self.kappa
    }

    /// Index of the stage within the step (0, 1, 2).
    pub fn index(&self) -> usize {
        self.index
    }

    /// Number of unknowns (momentum faces) of component `c`: the length of its box vectors.
    pub fn box_len(&self, c: usize) -> usize {
        self.solver.dims(c).iter().product()
    }

    /// Box index of the face of component `c` at padded index `slot`, if the momentum
    /// equation advances it.
    pub fn box_index(&self, c: usize, slot: usize) -> Option<usize> {
        let l = self.layout;
        let idx = [
            slot % l.dims[0],
            (slot / l.dims[0]) % l.dims[1],
            slot / l.plane_len(),
        ];
        let r = &self.ranges[c];
        let m = self.solver.dims(c);
        let mut b = 0;
        for d in (0..3).rev() {
            if idx[d] < r[d].0 || idx[d] > r[d].1 {
                return None;
            }
            b = b * m[d] + (idx[d] - r[d].0);
        }
        Some(b)
    }

    /// Box index of the neighbour of box index `b` (component `c`) one face along `+d`
    /// (`forward`) or `−d`, wrapping in periodic directions; `None` past a boundary.
    pub fn neighbour(&self, c: usize, b: usize, d: usize, forward: bool) -> Option<usize> {
        let m = self.solver.dims(c);
        let stride = [1, m[0], m[0] * m[1]][d];
        let i = (b / stride) % m[d];
        let periodic = self.solver.periodic()[d];
        if forward {
            if i + 1 < m[d] {
                Some(b + stride)
            } else {
                periodic.then(|| b - i * stride)
            }
        } else if i > 0 {
            Some(b - stride)
        } else {
            periodic.then(|| b + (m[d] - 1) * stride)
        }
    }

    /// The stage's own box vector of component `c`, as scratch: the stage has already moved
    /// its solution into the velocity, so the box is free until the next stage fills it
    /// (saves the hook a grid-sized vector). Contents unspecified; hand it back with
    /// [`Self::return_box`] before the hook returns.
    pub fn lend_box(&mut self, c: usize) -> Vec<f64> {
        std::mem::take(&mut self.solver.work[c])
    }

    /// Gives back the vector of [`Self::lend_box`].
    pub fn return_box(&mut self, c: usize, v: Vec<f64>) {
        self.solver.work[c] = v;
    }

    /// Cell sizes of the grid.
    pub fn h(&self) -> [f64; 3] {
        self.solver.h()
    }

    /// Solves `(I − κ∇²) x = data` in place for component `c` with zero boundary values
    /// (`data` in box layout, [`Self::box_len`] long).
    pub fn solve_homogeneous(&mut self, c: usize, data: &mut [f64]) {
        self.solver.solve_component(c, self.kappa, data, false);
    }

    /// `u ← u + x` on the momentum faces of component `c` (`u` padded, `x` box layout).
    pub fn add_to_velocity(&self, c: usize, x: &[f64], u: &mut [f64]) {
        let r = &self.ranges[c];
        let m = self.solver.dims(c);
        if m.iter().product::<usize>() == 0 {
            return;
        }
        let l = self.layout;
        for k in r[2].0..=r[2].1 {
            for j in r[1].0..=r[1].1 {
                let row = l.index(r[0].0, j, k);
                let b = m[0] * ((j - r[1].0) + m[1] * (k - r[2].0));
                for i in 0..m[0] {
                    u[row + i] += x[b + i];
                }
            }
        }
    }
}
