//! Exact solver of the 7-point Poisson problem on the cell centres.
//!
//! The discrete Laplacian `L = Lₓ ⊗ I ⊗ I + I ⊗ L_y ⊗ I + I ⊗ I ⊗ L_z` is a sum of 1-D
//! second differences, each diagonalised by a real orthogonal basis fixed by its boundary
//! conditions (ghost values mirrored for zero gradient, anti-mirrored for a zero value at
//! the face, wrapped for periodic):
//!
//! | condition (low, high) | basis            | transform | `θₘ`, m = 0..n−1   |
//! |-----------------------|------------------|-----------|--------------------|
//! | periodic              | cos/sin pairs    | real FFT  | `2π ⌈m/2⌉ / n`      |
//! | zero gradient, both   | `cos θ(i+½)`     | DCT-II    | `π m / n`           |
//! | fixed, both           | `sin θ(i+½)`     | DST-II    | `π (m+1) / n`       |
//! | zero gradient, fixed  | `cos θ(i+½)`     | DCT-IV    | `π (2m+1) / (2n)`   |
//! | fixed, zero gradient  | `sin θ(i+½)`     | DST-IV    | `π (2m+1) / (2n)`   |
//!
//! with eigenvalues `λₘ = −(4/h²) sin²(θₘ/2)`. So `L φ = f` is solved by transforming `f`
//! along x, y and z, dividing by `λ_a + λ_b + λ_c`, and transforming back: exact to
//! round-off, `O(N log N)`. The periodic transform is kept real by packing the half-complex
//! spectrum `[Re₀, Re₁, Im₁, Re₂, Im₂, …]`: a cosine and a sine of one wavenumber share an
//! eigenvalue, so any real basis of that pair diagonalises `L` as well.
//!
//! When every direction is periodic or zero-gradient the problem is singular; the constant
//! mode is set to zero (zero-mean solution) and the right-hand side's mean is ignored.

use super::shared_samples::SharedSamples;
use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustdct::{DctPlanner, TransformType2And3, TransformType4};
use std::sync::Arc;

/// Condition on the pressure at one end of a bounded direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PressureBoundary {
    /// Zero normal gradient at the face (walls, slip, inlets).
    Neumann,
    /// Zero value at the face (outlets; a non-zero value is moved to the right-hand side).
    Dirichlet,
}

/// The pressure's condition along one direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AxisKind {
    Periodic,
    Bounded {
        low: PressureBoundary,
        high: PressureBoundary,
    },
}

/// Lines gathered per transform batch in the strided passes: 8 doubles fill a cache line.
const LINE_BATCH: usize = 8;

/// Line-scratch workers per rayon thread (runs of planes or lines share one).
const WORKERS_PER_THREAD: usize = 4;

enum AxisTransform {
    /// One cell: every 1×1 operator is already diagonal.
    Identity,
    Fourier {
        forward: Arc<dyn RealToComplex<f64>>,
        inverse: Arc<dyn ComplexToReal<f64>>,
    },
    Cosine2(Arc<dyn TransformType2And3<f64>>),
    /// DCT-II/III of length 2 (two cells between walls, as in pseudo-2-D cases), done in
    /// place with rustdct's own butterfly arithmetic (bit-identical) but without a library
    /// call per line: the x pass of such a grid is thousands of two-point lines.
    Cosine2Pair,
    Sine2(Arc<dyn TransformType2And3<f64>>),
    Cosine4(Arc<dyn TransformType4<f64>>),
    Sine4(Arc<dyn TransformType4<f64>>),
}

/// Scratch of one worker: gathered lines and the transforms' own buffers.
struct LineWork {
    lines: Vec<f64>,
    spectrum: Vec<Complex<f64>>,
    complex_scratch: Vec<Complex<f64>>,
    /// One per axis, sized for that axis's transform.
    real_scratch: [Vec<f64>; 3],
}

impl AxisTransform {
    fn new(n: usize, kind: AxisKind) -> (Self, f64) {
        use PressureBoundary::*;
        if n == 1 {
            return (AxisTransform::Identity, 1.0);
        }
        let half = n as f64 / 2.0;
        match kind {
            AxisKind::Periodic => {
                let mut planner = RealFftPlanner::<f64>::new();
                (
                    AxisTransform::Fourier {
                        forward: planner.plan_fft_forward(n),
                        inverse: planner.plan_fft_inverse(n),
                    },
                    n as f64,
                )
            }
            AxisKind::Bounded { low, high } => {
                let mut planner = DctPlanner::<f64>::new();
                let t = match (low, high) {
                    (Neumann, Neumann) if n == 2 => AxisTransform::Cosine2Pair,
                    (Neumann, Neumann) => AxisTransform::Cosine2(planner.plan_dct2(n)),
                    (Dirichlet, Dirichlet) => AxisTransform::Sine2(planner.plan_dst2(n)),
                    (Neumann, Dirichlet) => AxisTransform::Cosine4(planner.plan_dct4(n)),
                    (Dirichlet, Neumann) => AxisTransform::Sine4(planner.plan_dst4(n)),
                };
                (t, half)
            }
        }
    }

    fn scratch_lens(&self) -> (usize, usize) {
        match self {
            AxisTransform::Identity | AxisTransform::Cosine2Pair => (0, 0),
            AxisTransform::Fourier { forward, inverse } => {
                (forward.get_scratch_len().max(inverse.get_scratch_len()), 0)
            }
            AxisTransform::Cosine2(t) | AxisTransform::Sine2(t) => (0, t.get_scratch_len()),
            AxisTransform::Cosine4(t) | AxisTransform::Sine4(t) => (0, t.get_scratch_len()),
        }
    }

    fn forward(&self, line: &mut [f64], w: &mut LineWork, axis: usize) {
        match self {
            AxisTransform::Identity => {}
            AxisTransform::Cosine2Pair => {
                let sum = line[0] + line[1];
                line[1] = (line[0] - line[1]) * std::f64::consts::FRAC_1_SQRT_2;
                line[0] = sum;
            }
            AxisTransform::Fourier { forward, .. } => {
                let n = line.len();
                let spec = &mut w.spectrum[..n / 2 + 1];
                // realfft uses its input as scratch: the line itself, overwritten below.
                forward
                    .process_with_scratch(
                        line,
                        spec,
                        &mut w.complex_scratch[..forward.get_scratch_len()],
                    )
                    .expect("FFT buffer lengths are fixed at planning");
                line[0] = spec[0].re;
                for m in 1..n.div_ceil(2) {
                    line[2 * m - 1] = spec[m].re;
                    line[2 * m] = spec[m].im;
                }
                if n.is_multiple_of(2) {
                    line[n - 1] = spec[n / 2].re;
                }
            }
            AxisTransform::Cosine2(t) => {
                t.process_dct2_with_scratch(line, &mut w.real_scratch[axis][..t.get_scratch_len()])
            }
            AxisTransform::Sine2(t) => {
                t.process_dst2_with_scratch(line, &mut w.real_scratch[axis][..t.get_scratch_len()])
            }
            AxisTransform::Cosine4(t) => {
                t.process_dct4_with_scratch(line, &mut w.real_scratch[axis][..t.get_scratch_len()])
            }
            AxisTransform::Sine4(t) => {
                t.process_dst4_with_scratch(line, &mut w.real_scratch[axis][..t.get_scratch_len()])
            }
        }
    }

    fn inverse(&self, line: &mut [f64], w: &mut LineWork, axis: usize) {
        match self {
            AxisTransform::Identity => {}
            AxisTransform::Cosine2Pair => {
                let half_0 = line[0] * 0.5;
                let frac_1 = line[1] * std::f64::consts::FRAC_1_SQRT_2;
                line[0] = half_0 + frac_1;
                line[1] = half_0 - frac_1;
            }
            AxisTransform::Fourier { inverse, .. } => {
                let n = line.len();
                let spec = &mut w.spectrum[..n / 2 + 1];
                spec[0] = Complex::new(line[0], 0.0);
                for m in 1..n.div_ceil(2) {
                    spec[m] = Complex::new(line[2 * m - 1], line[2 * m]);
                }
                if n.is_multiple_of(2) {
                    spec[n / 2] = Complex::new(line[n - 1], 0.0);
                }
                inverse
                    .process_with_scratch(
                        spec,
                        line,
                        &mut w.complex_scratch[..inverse.get_scratch_len()],
                    )
                    .expect("FFT buffer lengths are fixed at planning");
            }
            AxisTransform::Cosine2(t) => {
                t.process_dct3_with_scratch(line, &mut w.real_scratch[axis][..t.get_scratch_len()])
            }
            AxisTransform::Sine2(t) => {
                t.process_dst3_with_scratch(line, &mut w.real_scratch[axis][..t.get_scratch_len()])
            }
            AxisTransform::Cosine4(t) => {
                t.process_dct4_with_scratch(line, &mut w.real_scratch[axis][..t.get_scratch_len()])
            }
            AxisTransform::Sine4(t) => {
                t.process_dst4_with_scratch(line, &mut w.real_scratch[axis][..t.get_scratch_len()])
            }
        }
    }
}

/// The angles `θₘ` of the 1-D eigenvectors (table in the module docs).
fn axis_angles(n: usize, kind: AxisKind) -> Vec<f64> {
    use PressureBoundary::*;
    let nf = n as f64;
    let pi = std::f64::consts::PI;
    (0..n)
        .map(|m| match kind {
            AxisKind::Periodic => 2.0 * pi * m.div_ceil(2) as f64 / nf,
            AxisKind::Bounded { low, high } => match (low, high) {
                (Neumann, Neumann) => pi * m as f64 / nf,
                (Dirichlet, Dirichlet) => pi * (m + 1) as f64 / nf,
                _ => pi * (2 * m + 1) as f64 / (2.0 * nf),
            },
        })
        .collect()
}

/// Exact Poisson solver for cell-centred data on an `n₀ × n₁ × n₂` grid.
pub struct SpectralPoisson {
    n: [usize; 3],
    h: [f64; 3],
    axes: [AxisKind; 3],
    transforms: [AxisTransform; 3],
    /// `λₘ` per direction.
    eigenvalues: [Vec<f64>; 3],
    /// Product of the forward·inverse round-trip factors of the three transforms.
    round_trip: f64,
    work: Vec<LineWork>,
}

impl SpectralPoisson {
    /// Plans the transforms and allocates all scratch once.
    pub fn new(n: [usize; 3], h: [f64; 3], axes: [AxisKind; 3]) -> Self {
        let mut round_trip = 1.0;
        let transforms: [AxisTransform; 3] = std::array::from_fn(|d| {
            let (t, s) = AxisTransform::new(n[d], axes[d]);
            round_trip *= s;
            t
        });
        let eigenvalues = std::array::from_fn(|d| {
            axis_angles(n[d], axes[d])
                .into_iter()
                .map(|theta| {
                    let s = (0.5 * theta).sin();
                    -4.0 / (h[d] * h[d]) * s * s
                })
                .collect()
        });
        let nmax = n[0].max(n[1]).max(n[2]);
        let mut cs = 0;
        let mut rs = [0; 3];
        for (d, t) in transforms.iter().enumerate() {
            let (c, r) = t.scratch_lens();
            cs = cs.max(c);
            rs[d] = r;
        }
        // Line scratch per worker, not per plane or line: a worker takes a run of planes (or
        // of z-lines), a few runs per thread for balance. Each line's transform is independent
        // of the scratch it uses, so results do not depend on the split.
        let workers = n[1]
            .max(n[2])
            .min(WORKERS_PER_THREAD * rayon::current_num_threads());
        let work = (0..workers)
            .map(|_| LineWork {
                lines: vec![0.0; LINE_BATCH * nmax],
                spectrum: vec![Complex::new(0.0, 0.0); nmax / 2 + 1],
                complex_scratch: vec![Complex::new(0.0, 0.0); cs],
                real_scratch: rs.map(|r| vec![0.0; r]),
            })
            .collect();
        SpectralPoisson {
            n,
            h,
            axes,
            transforms,
            eigenvalues,
            round_trip,
            work,
        }
    }

    pub fn n(&self) -> [usize; 3] {
        self.n
    }

    pub fn axes(&self) -> [AxisKind; 3] {
        self.axes
    }

    /// True when the constant is in the null space (no direction has a fixed value).
    pub fn is_singular(&self) -> bool {
        self.eigenvalues.iter().all(|e| e[0] == 0.0)
    }

    /// Bytes of scratch held by the solver.
    pub fn scratch_bytes(&self) -> usize {
        self.work
            .iter()
            .map(|w| {
                8 * (w.lines.len() + w.real_scratch.iter().map(Vec::len).sum::<usize>())
                    + 16 * (w.spectrum.len() + w.complex_scratch.len())
            })
            .sum()
    }

    /// Solves `L φ = f` in place: `data` holds `f` (unpadded, x fastest) on entry and `φ`
    /// on return. Singular problems return the zero-mean solution.
    pub fn solve(&mut self, data: &mut [f64]) {
        let [n0, n1, n2] = self.n;
        assert_eq!(data.len(), n0 * n1 * n2);
        let plane = n0 * n1;
        let transforms = &self.transforms;
        let work = &mut self.work[..];

        // Forward along x then y: both stay inside one k-plane.
        let planes_per_worker = n2.div_ceil(work.len());
        data.par_chunks_mut(plane * planes_per_worker)
            .zip(work.par_iter_mut())
            .for_each(|(run, w)| {
                for p in run.chunks_mut(plane) {
                    for row in p.chunks_mut(n0) {
                        transforms[0].forward(row, w, 0);
                    }
                    transform_plane_columns(&transforms[1], p, n0, n1, w, true);
                }
            });
        // Divide by the eigenvalue sum (and the transforms' round-trip factor): along z, each
        // line as soon as it is transformed and back at once, while it is in the cache.
        let divide = Spectrum {
            eigenvalues: &self.eigenvalues,
            scale: self.round_trip,
        };
        if matches!(transforms[2], AxisTransform::Identity) {
            data.par_chunks_mut(plane).enumerate().for_each(|(k, p)| {
                for j in 0..n1 {
                    let row = &mut p[j * n0..(j + 1) * n0];
                    for (i, v) in row.iter_mut().enumerate() {
                        *v = divide.apply(*v, i, j, k);
                    }
                }
            });
        } else {
            solve_z(&transforms[2], data, self.n, work, &divide);
        }
        data.par_chunks_mut(plane * planes_per_worker)
            .zip(work.par_iter_mut())
            .for_each(|(run, w)| {
                for p in run.chunks_mut(plane) {
                    transform_plane_columns(&transforms[1], p, n0, n1, w, false);
                    for row in p.chunks_mut(n0) {
                        transforms[0].inverse(row, w, 0);
                    }
                }
            });
    }

    /// `out = L φ` with the same (homogeneous) boundary conditions the solver inverts.
    pub fn apply_laplacian(&self, phi: &[f64], out: &mut [f64]) {
        let [n0, n1, _] = self.n;
        let stride = [1, n0, n0 * n1];
        let axes = self.axes;
        let h = self.h;
        out.par_chunks_mut(n0 * n1).enumerate().for_each(|(k, o)| {
            for j in 0..n1 {
                for i in 0..n0 {
                    let c = i + n0 * (j + n1 * k);
                    let idx = [i, j, k];
                    let mut acc = 0.0;
                    for d in 0..3 {
                        let (lo, hi) = neighbours(phi, c, idx[d], self.n[d], stride[d], axes[d]);
                        acc += (lo - 2.0 * phi[c] + hi) / (h[d] * h[d]);
                    }
                    o[i + n0 * j] = acc;
                }
            }
        });
    }
}

/// Values of the two neighbours of cell `c` along one direction, ghosts included.
#[inline]
fn neighbours(phi: &[f64], c: usize, i: usize, n: usize, s: usize, kind: AxisKind) -> (f64, f64) {
    let ghost = |b: PressureBoundary| match b {
        PressureBoundary::Neumann => phi[c],
        PressureBoundary::Dirichlet => -phi[c],
    };
    let lo = if i > 0 {
        phi[c - s]
    } else {
        match kind {
            AxisKind::Periodic => phi[c + (n - 1) * s],
            AxisKind::Bounded { low, .. } => ghost(low),
        }
    };
    let hi = if i + 1 < n {
        phi[c + s]
    } else {
        match kind {
            AxisKind::Periodic => phi[c - (n - 1) * s],
            AxisKind::Bounded { high, .. } => ghost(high),
        }
    };
    (lo, hi)
}

/// Transforms the `n₀` columns (lines along y, stride `n₀`) of one k-plane, gathering
/// `LINE_BATCH` columns at a time so every cache line read is used whole.
fn transform_plane_columns(
    t: &AxisTransform,
    p: &mut [f64],
    n0: usize,
    n1: usize,
    w: &mut LineWork,
    forward: bool,
) {
    if matches!(t, AxisTransform::Identity) {
        return;
    }
    let mut lines = std::mem::take(&mut w.lines);
    let mut i0 = 0;
    while i0 < n0 {
        let b = LINE_BATCH.min(n0 - i0);
        for j in 0..n1 {
            for bb in 0..b {
                lines[bb * n1 + j] = p[i0 + bb + n0 * j];
            }
        }
        for bb in 0..b {
            let line = &mut lines[bb * n1..(bb + 1) * n1];
            if forward {
                t.forward(line, w, 1);
            } else {
                t.inverse(line, w, 1);
            }
        }
        for j in 0..n1 {
            for bb in 0..b {
                p[i0 + bb + n0 * j] = lines[bb * n1 + j];
            }
        }
        i0 += b;
    }
    w.lines = lines;
}

/// The division of the transformed right-hand side by the operator's eigenvalues.
struct Spectrum<'a> {
    eigenvalues: &'a [Vec<f64>; 3],
    /// The transforms' round-trip factor.
    scale: f64,
}

impl Spectrum<'_> {
    /// The mode `(i, j, k)`'s coefficient `v` divided by its eigenvalue (zero for a zero
    /// eigenvalue: the constant mode of a singular problem).
    #[inline]
    fn apply(&self, v: f64, i: usize, j: usize, k: usize) -> f64 {
        let ev = self.eigenvalues;
        let ejk = ev[1][j] + ev[2][k];
        let denom = (ev[0][i] + ejk) * self.scale;
        if denom == 0.0 {
            0.0
        } else {
            v / denom
        }
    }
}

/// Along z: each line transformed, divided by the eigenvalues and transformed back, each
/// worker a run of `j`s (their samples are disjoint between workers).
fn solve_z(
    t: &AxisTransform,
    data: &mut [f64],
    n: [usize; 3],
    work: &mut [LineWork],
    divide: &Spectrum,
) {
    if matches!(t, AxisTransform::Identity) {
        return;
    }
    let n1 = n[1];
    // SAFETY of the shared field: worker `j` touches exactly the indices `i + n₀ (j + n₁ k)`,
    // disjoint between workers.
    let shared = SharedSamples::of(data);
    let per_worker = n1.div_ceil(work.len());
    work.par_iter_mut().enumerate().for_each(|(wi, w)| {
        let mut lines = std::mem::take(&mut w.lines);
        for j in wi * per_worker..((wi + 1) * per_worker).min(n1) {
            solve_z_lines(t, shared, n, j, &mut lines, w, divide);
        }
        w.lines = lines;
    });
}

/// The `n₀` lines along z at `j`, `LINE_BATCH` at a time (see [`solve_z`]).
fn solve_z_lines(
    t: &AxisTransform,
    shared: SharedSamples,
    n: [usize; 3],
    j: usize,
    lines: &mut [f64],
    w: &mut LineWork,
    divide: &Spectrum,
) {
    let [n0, n1, n2] = n;
    let mut i0 = 0;
    while i0 < n0 {
        let b = LINE_BATCH.min(n0 - i0);
        for k in 0..n2 {
            let base = i0 + n0 * (j + n1 * k);
            for bb in 0..b {
                lines[bb * n2 + k] = shared.read(base + bb);
            }
        }
        for bb in 0..b {
            let line = &mut lines[bb * n2..(bb + 1) * n2];
            t.forward(line, w, 2);
            for (k, v) in line.iter_mut().enumerate() {
                *v = divide.apply(*v, i0 + bb, j, k);
            }
            t.inverse(line, w, 2);
        }
        for k in 0..n2 {
            let base = i0 + n0 * (j + n1 * k);
            for bb in 0..b {
                shared.write(base + bb, lines[bb * n2 + k]);
            }
        }
        i0 += b;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use PressureBoundary::*;

    /// Seeded xorshift so the right-hand sides are reproducible.
    fn random_field(len: usize, seed: u64) -> Vec<f64> {
        let mut s = seed;
        (0..len)
            .map(|_| {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
            .collect()
    }

    fn max_abs(a: &[f64]) -> f64 {
        a.iter().fold(0.0, |m, x| m.max(x.abs()))
    }

    /// Solves `L φ = f` for a random `f` and checks `L φ` gives `f` back (minus its mean when
    /// singular): the solver inverts exactly the operator the projection uses.
    fn check_exact(n: [usize; 3], axes: [AxisKind; 3]) {
        let h = [0.7, 1.1, 0.9];
        let mut solver = SpectralPoisson::new(n, h, axes);
        let len = n[0] * n[1] * n[2];
        let mut f = random_field(len, 0x9E3779B97F4A7C15 ^ len as u64);
        if solver.is_singular() {
            let mean = f.iter().sum::<f64>() / len as f64;
            f.iter_mut().for_each(|x| *x -= mean);
        }
        let mut phi = f.clone();
        solver.solve(&mut phi);
        let mut lphi = vec![0.0; len];
        solver.apply_laplacian(&phi, &mut lphi);
        let err: Vec<f64> = lphi.iter().zip(&f).map(|(a, b)| a - b).collect();
        let rel = max_abs(&err) / max_abs(&f);
        assert!(rel < 1e-12, "n={n:?} axes={axes:?}: residual {rel:e}");
    }

    /// The in-place two-point DCT-II/III gives rustdct's planned transform bit for bit, and a
    /// two-cell walled axis is solved exactly.
    #[test]
    fn two_point_cosine_pair_is_the_library_transform() {
        let planned = AxisTransform::Cosine2(DctPlanner::<f64>::new().plan_dct2(2));
        let (pair, scale) = AxisTransform::new(
            2,
            AxisKind::Bounded {
                low: Neumann,
                high: Neumann,
            },
        );
        assert!(matches!(pair, AxisTransform::Cosine2Pair) && scale == 1.0);
        let scratch = planned.scratch_lens().1;
        let mut w = LineWork {
            lines: Vec::new(),
            spectrum: Vec::new(),
            complex_scratch: Vec::new(),
            real_scratch: [vec![0.0; scratch], Vec::new(), Vec::new()],
        };
        for (k, pair_of) in random_field(64, 7).chunks(2).enumerate() {
            let (mut a, mut b) = ([pair_of[0], pair_of[1]], [pair_of[0], pair_of[1]]);
            if k % 2 == 0 {
                planned.forward(&mut a, &mut w, 0);
                pair.forward(&mut b, &mut w, 0);
            } else {
                planned.inverse(&mut a, &mut w, 0);
                pair.inverse(&mut b, &mut w, 0);
            }
            assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
        }
        let walls = AxisKind::Bounded {
            low: Neumann,
            high: Neumann,
        };
        let top = AxisKind::Bounded {
            low: Neumann,
            high: Dirichlet,
        };
        check_exact([2, 6, 9], [walls, walls, top]);
    }

    #[test]
    fn periodic_neumann_dirichlet_and_mixed_are_exact() {
        let p = AxisKind::Periodic;
        let b = |low, high| AxisKind::Bounded { low, high };
        check_exact([16, 12, 10], [p, p, p]);
        check_exact([15, 9, 7], [p, p, p]); // odd lengths: no Nyquist entry
        check_exact([16, 12, 10], [b(Neumann, Neumann); 3]);
        check_exact([16, 12, 10], [b(Dirichlet, Dirichlet); 3]);
        check_exact(
            [16, 12, 10],
            [b(Neumann, Dirichlet), b(Dirichlet, Neumann), p],
        );
        check_exact([12, 16, 1], [b(Neumann, Neumann), b(Dirichlet, Neumann), p]);
        check_exact([8, 1, 6], [p, b(Neumann, Neumann), b(Dirichlet, Dirichlet)]);
        // Tiny lines, where the transforms take their special small-size paths.
        check_exact(
            [2, 3, 2],
            [b(Neumann, Dirichlet), b(Dirichlet, Dirichlet), p],
        );
        check_exact([3, 2, 2], [b(Dirichlet, Neumann), b(Neumann, Neumann), p]);
        check_exact([2, 2, 3], [p, p, b(Neumann, Neumann)]);
        check_exact(
            [64, 40, 1],
            [
                b(Dirichlet, Dirichlet),
                b(Dirichlet, Dirichlet),
                b(Neumann, Neumann),
            ],
        );
    }

    #[test]
    fn manufactured_mixed_solution_is_recovered() {
        // φ = cos(π x/Lx) sin(3π y/(2Ly)) cos(2π z/Lz): zero gradient at x = 0, Lx;
        // zero at y = 0, zero gradient at y = Ly; periodic in z. The discrete problem built
        // from L φ is solved back to φ exactly.
        let n = [20, 14, 12];
        let h = [0.05, 0.1, 0.2];
        let axes = [
            AxisKind::Bounded {
                low: Neumann,
                high: Neumann,
            },
            AxisKind::Bounded {
                low: Dirichlet,
                high: Neumann,
            },
            AxisKind::Periodic,
        ];
        let mut solver = SpectralPoisson::new(n, h, axes);
        let l = [n[0] as f64 * h[0], n[1] as f64 * h[1], n[2] as f64 * h[2]];
        let pi = std::f64::consts::PI;
        let mut phi = vec![0.0; n[0] * n[1] * n[2]];
        for k in 0..n[2] {
            for j in 0..n[1] {
                for i in 0..n[0] {
                    let x = (i as f64 + 0.5) * h[0];
                    let y = (j as f64 + 0.5) * h[1];
                    let z = (k as f64 + 0.5) * h[2];
                    phi[i + n[0] * (j + n[1] * k)] = (pi * x / l[0]).cos()
                        * (1.5 * pi * y / l[1]).sin()
                        * (2.0 * pi * z / l[2]).cos();
                }
            }
        }
        let mut rhs = vec![0.0; phi.len()];
        solver.apply_laplacian(&phi, &mut rhs);
        solver.solve(&mut rhs);
        let err = rhs
            .iter()
            .zip(&phi)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(err < 1e-12, "error {err:e}");
    }
}
