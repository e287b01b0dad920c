//! The fluid's staggered fields as the solver holds them, read at arbitrary points
//! (periodic images wrapped).

use super::field_sampler::{
    sample_stored, FieldSampler, Interpolation, LatticeGeometry, StoredFields, PRESSURE,
};
use crate::fluid::{BoundaryConditions, FaceCondition, FluidSolver, PaddedLayout};
use crate::grid::{wrap_index, Grid};
use crate::Vec3;

/// Read-only view of a fluid state: the staggered velocity (padded, see [`PaddedLayout`])
/// and the kinematic pressure (cell-centred, unpadded).
///
/// Along a periodic direction every index wraps, so points of a periodic image may lie
/// outside the box. Along a bounded direction the stencil is shifted inside the stored
/// samples (boundary faces and the ghost layers the solver fills from the wall conditions).
#[derive(Clone, Copy)]
pub struct FieldView<'a> {
    pub grid: &'a Grid,
    pub layout: &'a PaddedLayout,
    pub periodic: [bool; 3],
    pub velocity: &'a [Vec<f64>; 3],
    pub pressure: &'a [f64],
    /// Kinematic viscosity, m²/s.
    pub nu: f64,
}

/// Which directions of a set of conditions are periodic.
pub fn periodic_directions(bc: &BoundaryConditions) -> [bool; 3] {
    std::array::from_fn(|d| matches!(bc.face(d, 0), FaceCondition::Periodic))
}

impl<'a> FieldView<'a> {
    /// The current state of a solver, with the pressure of the last step's impulse
    /// ([`FluidSolver::impulse_pressure`]: the loads are lagged by one step).
    pub fn of(fluid: &'a FluidSolver) -> Self {
        FieldView {
            grid: fluid.grid(),
            layout: fluid.layout(),
            periodic: periodic_directions(fluid.boundary_conditions()),
            velocity: fluid.velocity(),
            pressure: fluid.impulse_pressure(),
            nu: fluid.settings().nu,
        }
    }
}

impl StoredFields for FieldView<'_> {
    #[inline]
    fn geometry(&self) -> LatticeGeometry {
        LatticeGeometry {
            origin: self.grid.origin,
            h: self.grid.h,
            n: self.grid.n,
            periodic: self.periodic,
        }
    }

    #[inline]
    fn samples(&self, field: usize) -> &[f64] {
        if field == PRESSURE {
            self.pressure
        } else {
            &self.velocity[field]
        }
    }

    /// Velocity samples are padded by one layer (ghosts), the pressure is not.
    #[inline]
    fn axis_offset(&self, field: usize, d: usize, m: isize) -> usize {
        let n = self.grid.n;
        let m = if self.periodic[d] {
            wrap_index(m, n[d] as isize)
        } else {
            m
        };
        if field == PRESSURE {
            m as usize * [1, n[0], n[0] * n[1]][d]
        } else {
            (m + 1) as usize * self.layout.stride[d]
        }
    }
}

impl FieldSampler for FieldView<'_> {
    #[inline]
    fn sample(
        &self,
        x: Vec3,
        interpolation: Interpolation,
        gradient: bool,
        pressure: bool,
    ) -> ([f64; 3], [[f64; 3]; 3], f64) {
        sample_stored(self, x, interpolation, gradient, pressure)
    }

    fn nu(&self) -> f64 {
        self.nu
    }

    fn cell_size(&self) -> f64 {
        self.grid.h.iter().cloned().fold(0.0, f64::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::{FluidSettings, FluidSolver};

    fn periodic_solver(n: usize) -> FluidSolver {
        let grid = Grid::new([n, n + 1, n + 2], [0.1, 0.09, 0.08], [0.3, -0.2, 0.1]);
        FluidSolver::new(
            grid,
            BoundaryConditions::periodic(),
            FluidSettings::new(1.0),
        )
        .unwrap()
    }

    #[test]
    fn cubic_reproduces_cubic_polynomials_and_linear_reproduces_linear_ones() {
        let mut s = periodic_solver(12);
        // Polynomials are not periodic; sample well inside so no stencil wraps.
        let cubic = |x: Vec3| x[0].powi(3) - 2.0 * x[0] * x[1] * x[2] + x[2] * x[2];
        let linear = |x: Vec3| 1.0 + 2.0 * x[0] - x[1] + 0.5 * x[2];
        s.set_velocity(|c, x| {
            if c == 0 {
                cubic(Vec3::from(x))
            } else {
                linear(Vec3::from(x))
            }
        });
        let p: Vec<f64> = (0..s.grid().cell_count())
            .map(|idx| {
                let n = s.grid().n;
                let (i, j, k) = (idx % n[0], (idx / n[0]) % n[1], idx / (n[0] * n[1]));
                linear(Vec3::from(s.grid().cell_centre(i, j, k)))
            })
            .collect();
        s.pressure_mut().copy_from_slice(&p);
        let view = FieldView::of(&s);
        let x = Vec3::new(0.83, 0.31, 0.47);
        let (u, g) = view.velocity_and_gradient(x, Interpolation::Cubic);
        assert!((u[0] - cubic(x)).abs() < 1e-12, "{} vs {}", u[0], cubic(x));
        let exact_grad = [
            3.0 * x[0] * x[0] - 2.0 * x[1] * x[2],
            -2.0 * x[0] * x[2],
            -2.0 * x[0] * x[1] + 2.0 * x[2],
        ];
        for d in 0..3 {
            assert!((g[0][d] - exact_grad[d]).abs() < 1e-11);
        }
        for interpolation in [Interpolation::Linear, Interpolation::Cubic] {
            let (u, g) = view.velocity_and_gradient(x, interpolation);
            assert!((u[1] - linear(x)).abs() < 1e-12);
            assert!((g[2][0] - 2.0).abs() < 1e-11 && (g[2][1] + 1.0).abs() < 1e-11);
            assert!((view.pressure_at(x, interpolation) - linear(x)).abs() < 1e-12);
        }
    }

    #[test]
    fn periodic_images_read_the_same_values() {
        let mut s = periodic_solver(10);
        let l = s.grid().length();
        let o = s.grid().origin;
        let k = |d: usize, x: f64| 2.0 * std::f64::consts::PI * (x - o[d]) / l[d];
        s.set_velocity(|c, x| (k(0, x[0]) + c as f64).sin() * k(1, x[1]).cos() + k(2, x[2]).sin());
        let view = FieldView::of(&s);
        let x = Vec3::new(0.35, 0.0, 0.5);
        let shifted = [x[0] + l[0], x[1] - l[1], x[2] + 2.0 * l[2]];
        let a = view.velocity_and_gradient(x, Interpolation::Cubic);
        let b = view.velocity_and_gradient(Vec3::from(shifted), Interpolation::Cubic);
        for c in 0..3 {
            assert!((a.0[c] - b.0[c]).abs() < 1e-12);
        }
    }
}
