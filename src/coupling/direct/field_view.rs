//! Reading the fluid's staggered fields at arbitrary points: values and gradients by tensor
//! Lagrange interpolation (trilinear or tricubic), periodic images wrapped.

use crate::fluid::{BoundaryConditions, FaceCondition, FluidSolver, PaddedLayout};
use crate::grid::{fast_floor, wrap_index, Grid};

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
        let (u, g, _) = self.sample_point(x, interpolation, true, false);
        (u, g)
    }

    /// Velocity `u`, its gradient `g[i][j] = ∂u_i/∂x_j` and the kinematic pressure at `x`
    /// (what the stress needs), from one placement of the stencils.
    pub fn velocity_gradient_and_pressure(
        &self,
        x: [f64; 3],
        interpolation: Interpolation,
    ) -> ([f64; 3], [[f64; 3]; 3], f64) {
        self.sample_point(x, interpolation, true, true)
    }

    /// Velocity at `x`.
    pub fn velocity_at(&self, x: [f64; 3], interpolation: Interpolation) -> [f64; 3] {
        self.sample_point(x, interpolation, false, false).0
    }

    /// Kinematic pressure at `x`.
    pub fn pressure_at(&self, x: [f64; 3], interpolation: Interpolation) -> f64 {
        let placement = Placement::new(self, x, interpolation);
        match interpolation {
            Interpolation::Linear => self.field_linear(&placement, None, false).0,
            Interpolation::Cubic => self.field::<4>(&placement, None, false).0,
        }
    }

    /// The velocity (with its gradient when `gradient`) and, when `pressure`, the pressure
    /// at `x`; the pressure slot is 0 otherwise.
    #[inline]
    fn sample_point(
        &self,
        x: [f64; 3],
        interpolation: Interpolation,
        gradient: bool,
        pressure: bool,
    ) -> ([f64; 3], [[f64; 3]; 3], f64) {
        let placement = Placement::new(self, x, interpolation);
        match interpolation {
            Interpolation::Linear => self.fields::<2>(&placement, gradient, pressure),
            Interpolation::Cubic => self.fields::<4>(&placement, gradient, pressure),
        }
    }

    #[inline]
    fn fields<const N: usize>(
        &self,
        placement: &Placement,
        gradient: bool,
        pressure: bool,
    ) -> ([f64; 3], [[f64; 3]; 3], f64) {
        let mut u = [0.0; 3];
        let mut g = [[0.0; 3]; 3];
        for c in 0..3 {
            (u[c], g[c]) = if N == 2 {
                self.field_linear(placement, Some(c), gradient)
            } else {
                self.field::<N>(placement, Some(c), gradient)
            };
        }
        let p = match (pressure, N) {
            (false, _) => 0.0,
            (true, 2) => self.field_linear(placement, None, false).0,
            (true, _) => self.field::<N>(placement, None, false).0,
        };
        (u, g, p)
    }

    /// [`Self::field`] for the 2-node (trilinear) stencil, by successive linear blends:
    /// along x `a = v₀ + f (v₁ − v₀)` (and `∂a/∂x = v₁ − v₀`), then y, then z.
    #[inline(always)]
    fn field_linear(
        &self,
        placement: &Placement,
        component: Option<usize>,
        gradient: bool,
    ) -> (f64, [f64; 3]) {
        let g = self.grid;
        let l = self.layout;
        let (data, stride, pad): (&[f64], [usize; 3], isize) = match component {
            Some(c) => (&self.velocity[c], l.stride, 1),
            None => (self.pressure, [1, g.n[0], g.n[0] * g.n[1]], 0),
        };
        let mut lo = [0usize; 3];
        let mut hi = [0usize; 3];
        let mut f = [0.0; 3];
        for d in 0..3 {
            let lattice = usize::from(component != Some(d));
            let axis = &placement.axes[d][lattice];
            let n = g.n[d] as isize;
            let start = axis.start;
            if self.periodic[d] {
                let next = if start + 1 == n { 0 } else { start + 1 };
                lo[d] = (start + pad) as usize * stride[d];
                hi[d] = (next + pad) as usize * stride[d];
                f[d] = axis.frac;
            } else {
                let (bottom, top) = match component {
                    None => (0, n - 1),
                    Some(c) if c == d => (0, n),
                    Some(_) => (-1, n),
                };
                let clamped = start.clamp(bottom, (top - 1).max(bottom));
                f[d] = if clamped == start {
                    axis.frac
                } else {
                    axis.t - clamped as f64
                };
                lo[d] = (clamped + pad) as usize * stride[d];
                hi[d] = (clamped + 1 + pad) as usize * stride[d];
            }
        }
        let corner = |i: usize, j: usize, k: usize| data[i + j + k];
        let blend = |a: f64, b: f64, t: f64| a + t * (b - a);
        // along x, on the four x-lines of the cell
        let v = [
            [corner(lo[0], lo[1], lo[2]), corner(hi[0], lo[1], lo[2])],
            [corner(lo[0], hi[1], lo[2]), corner(hi[0], hi[1], lo[2])],
            [corner(lo[0], lo[1], hi[2]), corner(hi[0], lo[1], hi[2])],
            [corner(lo[0], hi[1], hi[2]), corner(hi[0], hi[1], hi[2])],
        ];
        let a: [f64; 4] = std::array::from_fn(|q| blend(v[q][0], v[q][1], f[0]));
        // along y (a[0], a[1] at z low; a[2], a[3] at z high)
        let b = [blend(a[0], a[1], f[1]), blend(a[2], a[3], f[1])];
        let value = blend(b[0], b[1], f[2]);
        if !gradient {
            return (value, [0.0; 3]);
        }
        let ax: [f64; 4] = std::array::from_fn(|q| v[q][1] - v[q][0]);
        let bx = [blend(ax[0], ax[1], f[1]), blend(ax[2], ax[3], f[1])];
        let by = [a[1] - a[0], a[3] - a[2]];
        let grad = [
            blend(bx[0], bx[1], f[2]) / g.h[0],
            blend(by[0], by[1], f[2]) / g.h[1],
            (b[1] - b[0]) / g.h[2],
        ];
        (value, grad)
    }

    /// Value (and gradient when `gradient`, else zero) of velocity component `c` (or the
    /// pressure for `None`) on an `N`-node stencil per direction.
    #[inline(always)]
    fn field<const N: usize>(
        &self,
        placement: &Placement,
        component: Option<usize>,
        gradient: bool,
    ) -> (f64, [f64; 3]) {
        let g = self.grid;
        let l = self.layout;
        let (data, stride, pad): (&[f64], [usize; 3], isize) = match component {
            Some(c) => (&self.velocity[c], l.stride, 1),
            None => (self.pressure, [1, g.n[0], g.n[0] * g.n[1]], 0),
        };
        let mut w = [[0.0; N]; 3];
        let mut dw = [[0.0; N]; 3];
        // Offsets of the stencil's nodes along each axis, periodic wraps resolved.
        let mut offsets = [[0usize; N]; 3];
        for d in 0..3 {
            // Face-normal component on its own faces, everything else at cell centres.
            let lattice = usize::from(component != Some(d));
            let axis = &placement.axes[d][lattice];
            let n = g.n[d] as isize;
            let mut start = axis.start;
            if self.periodic[d] {
                for k in 0..N {
                    let m = start + k as isize;
                    let m = if m >= n { m - n } else { m };
                    offsets[d][k] = (m + pad) as usize * stride[d];
                }
                w[d].copy_from_slice(&axis.w[..N]);
                dw[d].copy_from_slice(&axis.dw[..N]);
            } else {
                // Stored samples along a bounded direction (0-based lattice indices):
                // boundary faces, and the ghost layer of the tangential components.
                let (lo, hi) = match component {
                    None => (0, n - 1),
                    Some(c) if c == d => (0, n),
                    Some(_) => (-1, n),
                };
                let top = (hi - N as isize + 1).max(lo);
                let clamped = start.clamp(lo, top);
                if clamped == start {
                    w[d].copy_from_slice(&axis.w[..N]);
                    dw[d].copy_from_slice(&axis.dw[..N]);
                } else {
                    let mut wa = [0.0; 4];
                    let mut dwa = [0.0; 4];
                    placement
                        .interpolation
                        .weights(axis.t - clamped as f64, &mut wa, &mut dwa);
                    w[d].copy_from_slice(&wa[..N]);
                    dw[d].copy_from_slice(&dwa[..N]);
                    start = clamped;
                }
                for k in 0..N {
                    offsets[d][k] = (start + k as isize + pad) as usize * stride[d];
                }
            }
        }
        let mut value = 0.0;
        let mut grad = [0.0; 3];
        if gradient {
            for b in 0..N {
                let kz = offsets[2][b];
                for a in 0..N {
                    let jy = offsets[1][a] + kz;
                    let (wyz, dy, dz) = (w[1][a] * w[2][b], dw[1][a] * w[2][b], w[1][a] * dw[2][b]);
                    let (mut v, mut gx) = (0.0, 0.0);
                    for i in 0..N {
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
        } else {
            for b in 0..N {
                let kz = offsets[2][b];
                for a in 0..N {
                    let jy = offsets[1][a] + kz;
                    let wyz = w[1][a] * w[2][b];
                    let mut v = 0.0;
                    for i in 0..N {
                        v += w[0][i] * data[offsets[0][i] + jy];
                    }
                    value += wyz * v;
                }
            }
        }
        (value, grad)
    }
}

/// Where a point sits on one axis of one lattice (faces or cell centres): the stencil's
/// first node (wrapped into the box along a periodic direction), the lattice coordinate
/// `t` (in spacings from node 0, unwrapped) and the weights at `t`.
#[derive(Clone, Copy)]
struct AxisPlacement {
    start: isize,
    t: f64,
    /// `t` less the unwrapped first node (the linear stencil's fraction).
    frac: f64,
    /// Weights at `t` (the cubic stencil only).
    w: [f64; 4],
    dw: [f64; 4],
}

/// A point's stencils on both lattices of every axis, computed once and shared by the four
/// fields (each field sits on faces along one axis at most and on centres along the others).
struct Placement {
    interpolation: Interpolation,
    /// `[axis][0: faces, 1: centres]`.
    axes: [[AxisPlacement; 2]; 3],
}

impl Placement {
    #[inline]
    fn new(view: &FieldView, x: [f64; 3], interpolation: Interpolation) -> Self {
        let g = view.grid;
        let half = interpolation.nodes() as isize / 2 - 1;
        let mut placement = Placement {
            interpolation,
            axes: [[AxisPlacement {
                start: 0,
                t: 0.0,
                frac: 0.0,
                w: [0.0; 4],
                dw: [0.0; 4],
            }; 2]; 3],
        };
        for d in 0..3 {
            let faces = (x[d] - g.origin[d]) / g.h[d];
            for lattice in 0..2 {
                let axis = &mut placement.axes[d][lattice];
                axis.t = faces - 0.5 * lattice as f64;
                // The stencil's first node: the point sits between its two middle nodes.
                let first = fast_floor(axis.t) - half;
                axis.frac = axis.t - first as f64;
                if interpolation == Interpolation::Cubic {
                    interpolation.weights(axis.frac, &mut axis.w, &mut axis.dw);
                }
                axis.start = if view.periodic[d] {
                    wrap_index(first, g.n[d] as isize)
                } else {
                    first
                };
            }
        }
        placement
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
