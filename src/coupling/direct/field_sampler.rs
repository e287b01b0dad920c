//! Sampling staggered fields at arbitrary points: values and gradients by tensor Lagrange
//! interpolation (trilinear or tricubic). The stencils are shared by the whole-grid
//! [`FieldView`](super::FieldView) and the per-sphere [`FieldBrick`](super::FieldBrick),
//! which differ only in where the samples are stored.

use crate::grid::fast_floor;
use crate::Vec3;

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
            "linear" => Some(Interpolation::Linear),
            "cubic" => Some(Interpolation::Cubic),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Interpolation::Linear => "linear",
            Interpolation::Cubic => "cubic",
        }
    }

    /// Stencil nodes per direction.
    pub(super) fn nodes(self) -> usize {
        match self {
            Interpolation::Linear => 2,
            Interpolation::Cubic => 4,
        }
    }

    /// Weights and derivative weights (per unit spacing) at fraction `f` from the stencil's
    /// first node (the stencil's nodes are `0..nodes`).
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

/// Reading a fluid state at points: what the stress integral and the shell momentum need.
pub trait FieldSampler {
    /// The velocity `u`, its gradient `g[i][j] = ∂u_i/∂x_j` when `gradient` (else zero) and
    /// the kinematic pressure when `pressure` (else zero) at `x`, from one placement of the
    /// stencils.
    fn sample(
        &self,
        x: Vec3,
        interpolation: Interpolation,
        gradient: bool,
        pressure: bool,
    ) -> ([f64; 3], [[f64; 3]; 3], f64);

    /// Kinematic viscosity, m²/s.
    fn nu(&self) -> f64;

    /// The largest cell size, m.
    fn cell_size(&self) -> f64;

    /// Velocity and its gradient at `x`.
    fn velocity_and_gradient(
        &self,
        x: Vec3,
        interpolation: Interpolation,
    ) -> ([f64; 3], [[f64; 3]; 3]) {
        let (u, g, _) = self.sample(x, interpolation, true, false);
        (u, g)
    }

    /// Velocity, its gradient and the kinematic pressure at `x` (what the stress needs).
    fn velocity_gradient_and_pressure(
        &self,
        x: Vec3,
        interpolation: Interpolation,
    ) -> ([f64; 3], [[f64; 3]; 3], f64) {
        self.sample(x, interpolation, true, true)
    }

    /// Kinematic pressure at `x`.
    fn pressure_at(&self, x: Vec3, interpolation: Interpolation) -> f64 {
        self.sample(x, interpolation, false, true).2
    }

    /// Velocity at `x`.
    fn velocity_at(&self, x: Vec3, interpolation: Interpolation) -> Vec3 {
        self.sample(x, interpolation, false, false).0.into()
    }
}

/// The lattices the fields sit on: cells of size `h` from `origin`, `n` per axis. Velocity
/// component `c` sits on faces along `c` and at cell centres along the other axes; the
/// pressure at cell centres.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct LatticeGeometry {
    pub origin: [f64; 3],
    pub h: [f64; 3],
    pub n: [usize; 3],
    pub periodic: [bool; 3],
}

/// Field index of the pressure (the velocity components are 0, 1 and 2).
pub(super) const PRESSURE: usize = 3;

/// Lattice indices stored along a bounded axis `d` for `field`: the boundary faces of the
/// normal component, the ghost layers of the tangential ones, the cells of the pressure.
#[inline]
pub(super) fn stored_range(field: usize, d: usize, n: usize) -> (isize, isize) {
    let n = n as isize;
    if field == PRESSURE {
        (0, n - 1)
    } else if field == d {
        (0, n)
    } else {
        (-1, n)
    }
}

/// Where samples are stored, as the stencils read them.
pub(super) trait StoredFields {
    fn geometry(&self) -> LatticeGeometry;

    /// The samples of `field` (velocity component or [`PRESSURE`]).
    fn samples(&self, field: usize) -> &[f64];

    /// Offset in [`Self::samples`] along axis `d` of a stencil node at lattice index `m`:
    /// unwrapped along a periodic axis, within [`stored_range`] along a bounded one.
    fn axis_offset(&self, field: usize, d: usize, m: isize) -> usize;
}

/// [`FieldSampler::sample`] on stored samples.
#[inline]
pub(super) fn sample_stored<S: StoredFields>(
    source: &S,
    x: Vec3,
    interpolation: Interpolation,
    gradient: bool,
    pressure: bool,
) -> ([f64; 3], [[f64; 3]; 3], f64) {
    let geometry = source.geometry();
    let placement = Placement::new(&geometry, x, interpolation);
    match interpolation {
        Interpolation::Linear => fields::<S, 2>(source, &geometry, &placement, gradient, pressure),
        Interpolation::Cubic => fields::<S, 4>(source, &geometry, &placement, gradient, pressure),
    }
}

#[inline]
fn fields<S: StoredFields, const N: usize>(
    source: &S,
    geometry: &LatticeGeometry,
    placement: &Placement,
    gradient: bool,
    pressure: bool,
) -> ([f64; 3], [[f64; 3]; 3], f64) {
    let mut u = [0.0; 3];
    let mut g = [[0.0; 3]; 3];
    for c in 0..3 {
        (u[c], g[c]) = field::<S, N>(source, geometry, placement, c, gradient);
    }
    let p = if pressure {
        field::<S, N>(source, geometry, placement, PRESSURE, false).0
    } else {
        0.0
    };
    (u, g, p)
}

/// Value (and gradient when `gradient`, else zero) of `field` on an `N`-node stencil per
/// direction. Along a bounded direction the stencil is shifted inside the stored samples
/// (and extrapolates there).
#[inline(always)]
fn field<S: StoredFields, const N: usize>(
    source: &S,
    geometry: &LatticeGeometry,
    placement: &Placement,
    field: usize,
    gradient: bool,
) -> (f64, [f64; 3]) {
    let mut offsets = [[0usize; N]; 3];
    let mut frac = [0.0; 3];
    let mut w = [[0.0; N]; 3];
    let mut dw = [[0.0; N]; 3];
    for d in 0..3 {
        // Face-normal component on its own faces, everything else at cell centres.
        let axis = &placement.axes[d][usize::from(field != d)];
        let mut first = axis.first;
        frac[d] = axis.frac;
        if N == 4 {
            w[d].copy_from_slice(&axis.w[..N]);
            dw[d].copy_from_slice(&axis.dw[..N]);
        }
        if !geometry.periodic[d] {
            let (lo, hi) = stored_range(field, d, geometry.n[d]);
            let top = (hi - N as isize + 1).max(lo);
            let clamped = first.clamp(lo, top);
            if clamped != first {
                first = clamped;
                frac[d] = axis.t - clamped as f64;
                if N == 4 {
                    let (mut wa, mut dwa) = ([0.0; 4], [0.0; 4]);
                    placement.interpolation.weights(frac[d], &mut wa, &mut dwa);
                    w[d].copy_from_slice(&wa[..N]);
                    dw[d].copy_from_slice(&dwa[..N]);
                }
            }
        }
        for k in 0..N {
            offsets[d][k] = source.axis_offset(field, d, first + k as isize);
        }
    }
    let data = source.samples(field);
    if N == 2 {
        linear_blend(data, &offsets, frac, geometry.h, gradient)
    } else {
        lagrange_sum::<N>(data, &offsets, &w, &dw, geometry.h, gradient)
    }
}

/// The 2-node (trilinear) stencil by successive linear blends: along x
/// `a = v₀ + f (v₁ − v₀)` (and `∂a/∂x = v₁ − v₀`), then y, then z.
#[inline(always)]
fn linear_blend<const N: usize>(
    data: &[f64],
    offsets: &[[usize; N]; 3],
    f: [f64; 3],
    h: [f64; 3],
    gradient: bool,
) -> (f64, [f64; 3]) {
    let (lo, hi) = (
        [offsets[0][0], offsets[1][0], offsets[2][0]],
        [offsets[0][1], offsets[1][1], offsets[2][1]],
    );
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
        blend(bx[0], bx[1], f[2]) / h[0],
        blend(by[0], by[1], f[2]) / h[1],
        (b[1] - b[0]) / h[2],
    ];
    (value, grad)
}

/// The `N`-node stencil as the tensor sum `Σ w_i w_j w_k v_ijk` (and its derivatives).
#[inline(always)]
fn lagrange_sum<const N: usize>(
    data: &[f64],
    offsets: &[[usize; N]; 3],
    w: &[[f64; N]; 3],
    dw: &[[f64; N]; 3],
    h: [f64; 3],
    gradient: bool,
) -> (f64, [f64; 3]) {
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
            grad[d] /= h[d];
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

/// Where a point sits on one axis of one lattice (faces or cell centres): the stencil's
/// first node (unwrapped), the lattice coordinate `t` (in spacings from node 0) and the
/// weights at `t`.
#[derive(Clone, Copy)]
struct AxisPlacement {
    first: isize,
    t: f64,
    /// `t` less the first node (the linear stencil's fraction).
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
    fn new(geometry: &LatticeGeometry, x: Vec3, interpolation: Interpolation) -> Self {
        let half = interpolation.nodes() as isize / 2 - 1;
        let mut placement = Placement {
            interpolation,
            axes: [[AxisPlacement {
                first: 0,
                t: 0.0,
                frac: 0.0,
                w: [0.0; 4],
                dw: [0.0; 4],
            }; 2]; 3],
        };
        for d in 0..3 {
            let faces = (x[d] - geometry.origin[d]) / geometry.h[d];
            for lattice in 0..2 {
                let axis = &mut placement.axes[d][lattice];
                axis.t = faces - 0.5 * lattice as f64;
                // The stencil's first node: the point sits between its two middle nodes.
                axis.first = fast_floor(axis.t) - half;
                axis.frac = axis.t - axis.first as f64;
                if interpolation == Interpolation::Cubic {
                    interpolation.weights(axis.frac, &mut axis.w, &mut axis.dw);
                }
            }
        }
        placement
    }
}

/// The lattice indices, along one axis, of every stencil node that points within `reach`
/// of `centre` read: `(first, last)`, with a node of slack on either side for the rounding
/// of the points. Along a bounded axis the range also holds the stencils shifted inside
/// the stored samples, and nothing beyond the ghost layers.
pub(super) fn stencil_span(
    geometry: &LatticeGeometry,
    d: usize,
    centre: f64,
    reach: f64,
    interpolation: Interpolation,
) -> (isize, isize) {
    let nodes = interpolation.nodes() as isize;
    let half = nodes / 2 - 1;
    let faces = |x: f64| (x - geometry.origin[d]) / geometry.h[d];
    // lowest on the centres' lattice, highest on the faces'
    let first = fast_floor(faces(centre - reach) - 0.5) - half - 1;
    let last = fast_floor(faces(centre + reach)) - half + nodes - 1 + 1;
    if geometry.periodic[d] {
        return (first, last);
    }
    let n = geometry.n[d] as isize;
    (first.max(-1).min(n - nodes), last.min(n).max(nodes - 1))
}
