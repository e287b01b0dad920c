//! Reading the fluid's staggered fields at arbitrary points: values and gradients by tensor
//! Lagrange interpolation (trilinear or tricubic), periodic images wrapped.

use crate::fluid::{BoundaryConditions, FaceCondition, FluidSolver, PaddedLayout};
use crate::grid::Grid;

/// Interpolation of grid samples to a point (paper eq. 6 evaluates the stress at the
/// quadrangles' corners, between grid nodes).
///
/// Both are tensor products of 1-D Lagrange polynomials on each field's own staggered
/// lattice; the gradient is the exact derivative of the interpolant.
/// - `Linear`: 2 nodes per direction (trilinear, paper eq. 15): value `O(h²)`, gradient
///   `O(h)`.
/// - `Cubic`: 4 nodes per direction (tricubic): value `O(h⁴)`, gradient `O(h³)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Interpolation {
    Linear,
    #[default]
    Cubic,
}

impl Interpolation {
    /// `linear` or `cubic`.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "linear" | "trilinear" => Some(Interpolation::Linear),
            "cubic" | "tricubic" => Some(Interpolation::Cubic),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Interpolation::Linear => "linear",
            Interpolation::Cubic => "cubic",
        }
    }

    fn nodes(self) -> usize {
        match self {
            Interpolation::Linear => 2,
            Interpolation::Cubic => 4,
        }
    }

    /// Weights and derivative weights (per unit spacing) at fraction `f` from node `first`
    /// + `shift` (the stencil's nodes are `0..nodes` relative to `first`).
    #[inline]
    fn weights(self, f: f64, w: &mut [f64; 4], dw: &mut [f64; 4]) {
        match self {
            Interpolation::Linear => {
                *w = [1.0 - f, f, 0.0, 0.0];
                *dw = [-1.0, 1.0, 0.0, 0.0];
            }
            Interpolation::Cubic => {
                // Nodes at −1, 0, 1, 2 relative to the cell holding the point; here `f` is
                // measured from node 0 of the stencil, so shift by one.
                let g = f - 1.0;
                let f2 = g * g;
                *w = [
                    -g * (g - 1.0) * (g - 2.0) / 6.0,
                    (g + 1.0) * (g - 1.0) * (g - 2.0) / 2.0,
                    -(g + 1.0) * g * (g - 2.0) / 2.0,
                    (g + 1.0) * g * (g - 1.0) / 6.0,
                ];
                *dw = [
                    -(3.0 * f2 - 6.0 * g + 2.0) / 6.0,
                    (3.0 * f2 - 4.0 * g - 1.0) / 2.0,
                    -(3.0 * f2 - 2.0 * g - 2.0) / 2.0,
                    (3.0 * f2 - 1.0) / 6.0,
                ];
            }
        }
    }
}

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
    /// The current state of a solver.
    pub fn of(fluid: &'a FluidSolver) -> Self {
        FieldView {
            grid: fluid.grid(),
            layout: fluid.layout(),
            periodic: periodic_directions(fluid.boundary_conditions()),
            velocity: fluid.velocity(),
            pressure: fluid.pressure(),
            nu: fluid.settings().nu,
        }
    }

    /// Velocity `u` and its gradient `g[i][j] = ∂u_i/∂x_j` at `x`.
    pub fn velocity_and_gradient(
        &self,
        x: [f64; 3],
        interpolation: Interpolation,
    ) -> ([f64; 3], [[f64; 3]; 3]) {
        let mut u = [0.0; 3];
        let mut g = [[0.0; 3]; 3];
        for c in 0..3 {
            let (value, grad) = self.sample(Some(c), x, interpolation);
            u[c] = value;
            g[c] = grad;
        }
        (u, g)
    }

    /// Velocity at `x`.
    pub fn velocity_at(&self, x: [f64; 3], interpolation: Interpolation) -> [f64; 3] {
        std::array::from_fn(|c| self.sample(Some(c), x, interpolation).0)
    }

    /// Kinematic pressure at `x`.
    pub fn pressure_at(&self, x: [f64; 3], interpolation: Interpolation) -> f64 {
        self.sample(None, x, interpolation).0
    }

    /// Value and gradient of velocity component `c` (or the pressure for `None`).
    fn sample(
        &self,
        component: Option<usize>,
        x: [f64; 3],
        interpolation: Interpolation,
    ) -> (f64, [f64; 3]) {
        let nodes = interpolation.nodes();
        let g = self.grid;
        let mut w = [[0.0; 4]; 3];
        let mut dw = [[0.0; 4]; 3];
        let mut first = [0isize; 3];
        for d in 0..3 {
            let offset = if component == Some(d) { 0.0 } else { 0.5 };
            let t = (x[d] - g.origin[d]) / g.h[d] - offset;
            let n = g.n[d] as isize;
            // The stencil's first node: the point sits between its two middle nodes.
            let mut start = t.floor() as isize - (nodes as isize / 2 - 1);
            if !self.periodic[d] {
                // Stored samples along a bounded direction (0-based lattice indices).
                let (lo, hi) = match component {
                    None => (0, n - 1),
                    Some(c) if c == d => (0, n),
                    Some(_) => (-1, n),
                };
                let top = (hi - nodes as isize + 1).max(lo);
                start = start.clamp(lo, top);
            }
            first[d] = start;
            interpolation.weights(t - start as f64, &mut w[d], &mut dw[d]);
        }
        let data: &[f64] = match component {
            Some(c) => &self.velocity[c],
            None => self.pressure,
        };
        let l = self.layout;
        let (stride1, stride2) = match component {
            Some(_) => (l.stride[1], l.stride[2]),
            None => (g.n[0], g.n[0] * g.n[1]),
        };
        let stride = [1, stride1, stride2];
        // Offsets of the stencil's nodes along each axis, periodic wraps resolved once.
        let mut offsets = [[0usize; 4]; 3];
        for d in 0..3 {
            let n = g.n[d] as isize;
            for k in 0..nodes {
                let m = first[d] + k as isize;
                let m = if self.periodic[d] { m.rem_euclid(n) } else { m };
                let slot = match component {
                    Some(_) => (m + 1) as usize,
                    None => m as usize,
                };
                offsets[d][k] = slot * stride[d];
            }
        }
        let mut value = 0.0;
        let mut grad = [0.0; 3];
        for b in 0..nodes {
            let kz = offsets[2][b];
            for a in 0..nodes {
                let jy = offsets[1][a] + kz;
                let (wyz, dy, dz) = (w[1][a] * w[2][b], dw[1][a] * w[2][b], w[1][a] * dw[2][b]);
                let (mut v, mut gx) = (0.0, 0.0);
                for i in 0..nodes {
                    let f = data[offsets[0][i] + jy];
                    v += w[0][i] * f;
                    gx += dw[0][i] * f;
                }
                value += wyz * v;
                grad[0] += wyz * gx;
                grad[1] += dy * v;
                grad[2] += dz * v;
            }
        }
        for d in 0..3 {
            grad[d] /= g.h[d];
        }
        (value, grad)
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
        let cubic = |x: [f64; 3]| x[0].powi(3) - 2.0 * x[0] * x[1] * x[2] + x[2] * x[2];
        let linear = |x: [f64; 3]| 1.0 + 2.0 * x[0] - x[1] + 0.5 * x[2];
        s.set_velocity(|c, x| if c == 0 { cubic(x) } else { linear(x) });
        let p: Vec<f64> = (0..s.grid().cell_count())
            .map(|idx| {
                let n = s.grid().n;
                let (i, j, k) = (idx % n[0], (idx / n[0]) % n[1], idx / (n[0] * n[1]));
                linear(s.grid().cell_centre(i, j, k))
            })
            .collect();
        s.pressure_mut().copy_from_slice(&p);
        let view = FieldView::of(&s);
        let x = [0.83, 0.31, 0.47];
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
        let x = [0.35, 0.0, 0.5];
        let shifted = [x[0] + l[0], x[1] - l[1], x[2] + 2.0 * l[2]];
        let a = view.velocity_and_gradient(x, Interpolation::Cubic);
        let b = view.velocity_and_gradient(shifted, Interpolation::Cubic);
        for c in 0..3 {
            assert!((a.0[c] - b.0[c]).abs() < 1e-12);
        }
    }
}
