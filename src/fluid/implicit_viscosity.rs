//! Implicit viscous solve of the semi-implicit scheme: per velocity component, the
//! Helmholtz problem `(I − β Δt ν ∇²) u = r` on its momentum faces, solved exactly by the
//! same separable transforms as the pressure ([`SpectralPoisson::solve_shifted`]).
//!
//! Each component has its own boundary geometry on the MAC grid. Across a direction
//! tangential to it, the unknowns sit at cell centres: a wall or inlet fixes the value at the
//! face (DST-II after moving the wall velocity to the right-hand side), a slip wall its
//! gradient (DCT-II). Along its own direction a bounded component's unknowns are the interior
//! faces between two fixed boundary faces (DST-I, [`AxisKind::Nodes`]). Periodic directions
//! use the FFT. Outlets (zero-gradient extrapolated faces) are not supported.

use super::boundary_conditions::{BoundaryConditions, FaceCondition};
use super::spectral_poisson::{AxisKind, PressureBoundary, SpectralPoisson};
use crate::grid::Grid;
use rayon::prelude::*;

pub(crate) struct ImplicitViscosity {
    /// One solver per component; `None` for a component that is zero (empty along itself).
    solvers: [Option<SpectralPoisson>; 3],
    /// Unknowns per direction of each component (its box of momentum faces).
    dims: [[usize; 3]; 3],
    /// Right-hand side / solution per component, box layout, x fastest.
    pub work: [Vec<f64>; 3],
    /// Boundary value entering the right-hand side beside face `(d, side)` of component
    /// `c`: `2 u_wall` for a tangential component, `u_wall` for the normal one.
    boundary: [[[f64; 2]; 3]; 3],
    h: [f64; 3],
    /// Directions in which the boxes wrap around.
    periodic: [bool; 3],
    /// Pressure increment of the incremental projection, cell-centred.
    pub increment: Vec<f64>,
}

impl ImplicitViscosity {
    pub fn new(
        grid: &Grid,
        bc: &BoundaryConditions,
        ranges: &[[(usize, usize); 3]; 3],
    ) -> Result<Self, String> {
        if bc.has_outlet() {
            return Err(
                "the semi-implicit viscous scheme does not support outlets; use RK3 or Euler"
                    .into(),
            );
        }
        let mut dims = [[0usize; 3]; 3];
        let mut boundary = [[[0.0; 2]; 3]; 3];
        let mut solvers: [Option<SpectralPoisson>; 3] = [None, None, None];
        for c in 0..3 {
            let r = ranges[c];
            if (0..3).any(|d| r[d].0 > r[d].1) {
                if matches!(bc.face(c, 0), FaceCondition::Empty) {
                    continue;
                }
                return Err(format!(
                    "direction {c} needs at least two cells for the implicit viscous step"
                ));
            }
            let mut axes = [AxisKind::Periodic; 3];
            for d in 0..3 {
                dims[c][d] = r[d].1 - r[d].0 + 1;
                axes[d] = match bc.face(d, 0) {
                    FaceCondition::Periodic => AxisKind::Periodic,
                    FaceCondition::Empty => AxisKind::Bounded {
                        low: PressureBoundary::Neumann,
                        high: PressureBoundary::Neumann,
                    },
                    _ if d == c => AxisKind::Nodes,
                    _ => {
                        let kind = |f: &FaceCondition| match f {
                            FaceCondition::Slip => PressureBoundary::Neumann,
                            _ => PressureBoundary::Dirichlet,
                        };
                        AxisKind::Bounded {
                            low: kind(bc.face(d, 0)),
                            high: kind(bc.face(d, 1)),
                        }
                    }
                };
                for side in 0..2 {
                    if let FaceCondition::Wall { velocity } | FaceCondition::Inlet { velocity } =
                        bc.face(d, side)
                    {
                        boundary[c][d][side] = if d == c {
                            velocity[c]
                        } else {
                            2.0 * velocity[c]
                        };
                    }
                }
            }
            solvers[c] = Some(SpectralPoisson::new(dims[c], grid.h, axes));
        }
        let work = std::array::from_fn(|c| vec![0.0; dims[c].iter().product()]);
        Ok(ImplicitViscosity {
            solvers,
            dims,
            work,
            boundary,
            h: grid.h,
            periodic: std::array::from_fn(|d| matches!(bc.face(d, 0), FaceCondition::Periodic)),
            increment: vec![0.0; grid.cell_count()],
        })
    }

    /// Solves `(I − κ ∇²) u = work` in place for every component, `κ = β Δt ν`, the fixed
    /// boundary values included.
    pub fn solve(&mut self, kappa: f64) {
        for c in 0..3 {
            let mut w = std::mem::take(&mut self.work[c]);
            self.solve_component(c, kappa, &mut w, true);
            self.work[c] = w;
        }
    }

    /// Solves `(I − κ ∇²) u = data` in place for component `c` (its box layout, x fastest),
    /// with the fixed boundary values (`with_boundary`) or with zero ones (the homogeneous
    /// problem, for corrections). A component that is identically zero is left as it is.
    pub fn solve_component(&mut self, c: usize, kappa: f64, w: &mut [f64], with_boundary: bool) {
        let sigma = 1.0 / kappa;
        let Some(solver) = self.solvers[c].as_mut() else {
            return;
        };
        let m = self.dims[c];
        // Known boundary values: κ g / h² in the first and last layer along each d.
        for d in 0..3 {
            for side in 0..2 {
                let g = self.boundary[c][d][side];
                if g != 0.0 && with_boundary {
                    let add = kappa * g / (self.h[d] * self.h[d]);
                    let slot = if side == 0 { 0 } else { m[d] - 1 };
                    for k in 0..m[2] {
                        for j in 0..m[1] {
                            for i in 0..m[0] {
                                if [i, j, k][d] == slot {
                                    w[i + m[0] * (j + m[1] * k)] += add;
                                }
                            }
                        }
                    }
                }
            }
        }
        // (I − κL) u = r  ⇔  (L − σ) u = −σ r
        w.par_iter_mut().for_each(|x| *x *= -sigma);
        solver.solve_shifted(w, sigma);
    }

    /// Cell sizes.
    pub fn h(&self) -> [f64; 3] {
        self.h
    }

    /// Whether the boxes wrap around along each direction.
    pub fn periodic(&self) -> [bool; 3] {
        self.periodic
    }

    /// Unknowns per direction of component `c`'s box.
    pub fn dims(&self, c: usize) -> [usize; 3] {
        self.dims[c]
    }

    pub fn bytes(&self) -> usize {
        self.work.iter().map(|w| 8 * w.len()).sum::<usize>()
            + 8 * self.increment.len()
            + self
                .solvers
                .iter()
                .flatten()
                .map(|s| s.scratch_bytes())
                .sum::<usize>()
    }
}
