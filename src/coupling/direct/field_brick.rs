//! The fluid's fields around one sphere, copied into one small block of memory.

use super::field_sampler::{
    sample_stored, stencil_span, stored_range, FieldSampler, Interpolation, LatticeGeometry,
    StoredFields, PRESSURE,
};
use super::field_view::FieldView;
use crate::grid::fast_floor;
use crate::Vec3;

/// The velocity and pressure samples that the stencils of points within `reach` of a centre
/// read ([`FieldBrick::gather`]), copied with the periodic wraps resolved.
///
/// The stress integral and the shell of one sphere read some 1,100 points, each 32 corner
/// samples of four fields. From the whole grid's arrays (20 MB for the benchmark) these
/// corners scatter over the last-level cache; from the brick (about 110 kB at r/h = 2.5,
/// three cells out) they are near one another, with plain strides and no wraps. Every point
/// within `reach` reads the same samples as from the [`FieldView`], so the results are
/// the same bit for bit (tested).
#[derive(Clone, Debug, Default)]
pub struct FieldBrick {
    geometry: LatticeGeometry,
    nu: f64,
    cell_size: f64,
    /// Lattice index of the block's first node per axis (unwrapped along a periodic axis).
    first: [isize; 3],
    dims: [usize; 3],
    stride: [usize; 3],
    /// Samples per field.
    volume: usize,
    /// The four fields (velocity components, then the pressure), each `volume` samples, x
    /// fastest. A node outside a field's stored samples (beyond a wall) is NaN: no stencil
    /// reads it.
    data: Vec<f64>,
    /// Scratch of [`Self::gather`]: the source offset of each node along each axis.
    axis_sources: [Vec<usize>; 3],
    /// Scratch of [`Self::gather`]: the runs `i0..i1` of x-nodes whose sources follow one
    /// another (a periodic wrap splits a row in two), copied as slices.
    x_runs: Vec<(usize, usize)>,
    /// Scratch of [`Self::gather`]: the row copies planned.
    copies: Vec<RowCopy>,
}

/// Which nodes of each x-row of a brick the stencils of points in the ball read: in a fully
/// periodic box, those within the ball's chord widened by the stencil's reach (a little
/// over half the block's nodes at the benchmark: the block's corners and the rows beyond
/// the ball are never read, and copying them from the last-level cache was half the cost);
/// next to a wall, where stencils shift, the whole row.
struct RowSpans {
    clip: bool,
    /// Node positions along y and z of the rows (the field's lattice), the centre, reach.
    y0: f64,
    z0: f64,
    centre: Vec3,
    reach: f64,
    /// How far (m) from a point its stencil's nodes lie at most, with slack.
    stencil: f64,
    h: [f64; 3],
    /// 1 / h along x.
    per_hx: f64,
    /// x: the origin, the lattice offset (cells) of the field's nodes, the brick's first node.
    origin_x: f64,
    x_offset: f64,
    first_x: isize,
    half: isize,
    nodes: isize,
    dims_x: usize,
}

impl RowSpans {
    fn new(
        brick: &FieldBrick,
        field: usize,
        centre: Vec3,
        reach: f64,
        interpolation: Interpolation,
    ) -> Self {
        let g = &brick.geometry;
        // faces along the field's own axis, cell centres along the others
        let offset = |d: usize| if field == d { 0.0 } else { 0.5 };
        let node = |d: usize| g.origin[d] + (brick.first[d] as f64 + offset(d)) * g.h[d];
        let nodes = interpolation.nodes() as isize;
        let hmax = g.h.iter().cloned().fold(0.0, f64::max);
        RowSpans {
            clip: g.periodic == [true; 3],
            y0: node(1),
            z0: node(2),
            centre,
            reach,
            stencil: (nodes as f64 / 2.0 + 0.5) * hmax,
            h: g.h,
            per_hx: 1.0 / g.h[0],
            origin_x: g.origin[0],
            x_offset: offset(0),
            first_x: brick.first[0],
            half: nodes / 2 - 1,
            nodes,
            dims_x: brick.dims[0],
        }
    }

    /// How far beyond the stencil's reach row `j` (`axis` 1) or plane `k` (`axis` 2) lies
    /// from the centre, squared (0 within it).
    #[inline]
    fn away_squared(&self, axis: usize, index: usize) -> f64 {
        let node = if axis == 1 { self.y0 } else { self.z0 } + index as f64 * self.h[axis];
        let away = ((node - self.centre[axis]).abs() - self.stencil).max(0.0);
        away * away
    }

    /// The nodes `i0..i1` of a row that stencils read, from its rows' and plane's
    /// [`Self::away_squared`].
    #[inline]
    fn span(&self, away_squared: f64) -> (usize, usize) {
        if !self.clip {
            return (0, self.dims_x);
        }
        let left = self.reach * self.reach - away_squared;
        if left < 0.0 {
            return (0, 0);
        }
        let chord = left.sqrt();
        // the lattice coordinate of a point, and the first and last nodes its stencil reads
        // (one node of slack either side), relative to the brick's first node
        let t = |x: f64| (x - self.origin_x) * self.per_hx - self.x_offset;
        let lo = fast_floor(t(self.centre[0] - chord)) - self.half - 1 - self.first_x;
        let hi = fast_floor(t(self.centre[0] + chord)) - self.half + self.nodes - self.first_x;
        let clamp = |i: isize| i.clamp(0, self.dims_x as isize) as usize;
        (clamp(lo), clamp(hi + 1))
    }
}

/// Copies a few samples (a row of a brick, some ten): four at a time in registers, where
/// a call to `memcpy` costs more than the copy.
#[inline]
fn copy_short(to: &mut [f64], from: &[f64]) {
    let mut to = to.chunks_exact_mut(4);
    let mut from = from.chunks_exact(4);
    for (a, b) in (&mut to).zip(&mut from) {
        let b: [f64; 4] = b.try_into().expect("four");
        a.copy_from_slice(&b);
    }
    for (a, b) in to.into_remainder().iter_mut().zip(from.remainder()) {
        *a = *b;
    }
}

/// Marks a node outside a field's stored samples in [`FieldBrick::axis_sources`].
const OUTSIDE: usize = usize::MAX;

impl FieldBrick {
    /// An empty brick (its memory grows at the first gather and is kept).
    pub fn new() -> Self {
        Self::default()
    }

    /// Copies from `view` the samples that `interpolation`'s stencils read at points within
    /// `reach` of `centre`.
    pub fn gather(
        &mut self,
        view: &FieldView,
        centre: Vec3,
        reach: f64,
        interpolation: Interpolation,
    ) {
        self.geometry = view.geometry();
        self.nu = view.nu;
        self.cell_size = view.cell_size();
        for d in 0..3 {
            let (first, last) = stencil_span(&self.geometry, d, centre[d], reach, interpolation);
            self.first[d] = first;
            self.dims[d] = (last - first + 1) as usize;
        }
        self.stride = [1, self.dims[0], self.dims[0] * self.dims[1]];
        self.volume = self.dims.iter().product();
        self.data.resize(4 * self.volume, 0.0);
        // First the copies of all four fields are planned, each source row prefetched as it
        // is planned; then they are made. Made row by row as planned, each row waited for
        // its own cache misses (from the last-level cache: half the copy's time).
        self.copies.clear();
        for field in 0..4 {
            for d in 0..3 {
                let periodic = self.geometry.periodic[d];
                let (lo, hi) = stored_range(field, d, self.geometry.n[d]);
                let first = self.first[d];
                let sources = &mut self.axis_sources[d];
                sources.clear();
                sources.extend((0..self.dims[d] as isize).map(|i| {
                    let m = first + i;
                    if periodic || (lo..=hi).contains(&m) {
                        view.axis_offset(field, d, m)
                    } else {
                        OUTSIDE
                    }
                }));
            }
            let source = view.samples(field);
            let rows = RowSpans::new(self, field, centre, reach, interpolation);
            let [xs, ys, zs] = &self.axis_sources;
            let runs = &mut self.x_runs;
            runs.clear();
            for (i, &x) in xs.iter().enumerate() {
                if x == OUTSIDE {
                    continue;
                }
                match runs.last_mut() {
                    Some((_, end)) if *end == i && xs[i - 1] + 1 == x => *end = i + 1,
                    _ => runs.push((i, i + 1)),
                }
            }
            let d0 = self.dims[0];
            let block = field * self.volume;
            for (k, &z) in zs.iter().enumerate() {
                if z == OUTSIDE {
                    continue;
                }
                let dz2 = rows.away_squared(2, k);
                for (j, &y) in ys.iter().enumerate() {
                    if y == OUTSIDE {
                        continue;
                    }
                    let (i0, i1) = rows.span(dz2 + rows.away_squared(1, j));
                    let row = block + (k * self.dims[1] + j) * d0;
                    let yz = y + z;
                    for &(a, b) in runs.iter() {
                        let (lo, hi) = (a.max(i0), b.min(i1));
                        if lo < hi {
                            let from = xs[lo] + yz;
                            let span = &source[from..from + (hi - lo)];
                            prefetch(span);
                            self.copies.push(RowCopy {
                                field,
                                from,
                                to: row + lo,
                                len: hi - lo,
                            });
                        }
                    }
                }
            }
        }
        // NaN wherever nothing is copied (one fill: row by row, the small fills cost more
        // than the copies)
        self.data.fill(f64::NAN);
        let sources: [&[f64]; 4] = std::array::from_fn(|f| view.samples(f));
        for c in &self.copies {
            copy_short(
                &mut self.data[c.to..c.to + c.len],
                &sources[c.field][c.from..c.from + c.len],
            );
        }
    }
}

/// One stretch of a brick's row and where its samples come from.
#[derive(Clone, Copy, Debug, Default)]
struct RowCopy {
    field: usize,
    from: usize,
    to: usize,
    len: usize,
}

/// Asks for the cache lines of `span` ahead of their use.
#[inline]
fn prefetch(span: &[f64]) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let line = 8;
        let mut at = 0;
        while at < span.len() {
            // SAFETY: a prefetch of an address inside a live slice; it reads nothing.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(span.as_ptr().add(at) as *const i8) };
            at += line;
        }
        // SAFETY: as above, the slice's last sample.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(span.as_ptr().add(span.len() - 1) as *const i8) };
    }
}

impl StoredFields for FieldBrick {
    #[inline]
    fn geometry(&self) -> LatticeGeometry {
        self.geometry
    }

    #[inline]
    fn samples(&self, field: usize) -> &[f64] {
        &self.data[field * self.volume..(field + 1) * self.volume]
    }

    /// A node outside the block gives an offset past its end (a negative index wraps to a
    /// huge one), so reading it panics rather than reading another node.
    #[inline]
    fn axis_offset(&self, _field: usize, d: usize, m: isize) -> usize {
        let i = (m - self.first[d]) as usize;
        if i < self.dims[d] {
            i * self.stride[d]
        } else {
            usize::MAX / 4
        }
    }
}

impl FieldBrick {
    /// The trilinear stencil of the four fields at once, one field per lane (the velocity
    /// components, then the pressure): values and gradients. The operations are those of
    /// the fields one after another ([`sample_stored`]) in the same order (values, and
    /// gradients when `gradient`), so the results
    /// are the same bit for bit (tested), but on four lanes that the compiler maps onto one
    /// vector register, and with the six stencil placements shared by the fields (one after
    /// another, the fields spend most of their time in scalar index arithmetic). In a fully
    /// periodic box only: no stencil is shifted at a wall.
    #[inline]
    fn linear_lanes(&self, x: Vec3, gradient: bool) -> ([f64; 4], [[f64; 4]; 3]) {
        let g = &self.geometry;
        // Per axis: the first node's offset and the fraction on the faces (0) and centres (1).
        let mut first = [[0usize; 2]; 3];
        let mut frac = [[0.0; 2]; 3];
        for d in 0..3 {
            let faces = (x[d] - g.origin[d]) / g.h[d];
            // ⌊faces − ½⌋ from ⌊faces⌋: both subtractions are exact, so these are the floors
            // of each lattice's own coordinate.
            let node = fast_floor(faces);
            let nodes = [node, node - isize::from(faces - (node as f64) < 0.5)];
            for lattice in 0..2 {
                let t = faces - 0.5 * lattice as f64;
                frac[d][lattice] = t - nodes[lattice] as f64;
                // a node below the brick wraps to a huge index and fails too
                let i = (nodes[lattice] - self.first[d]) as usize;
                assert!(i < self.dims[d] - 1, "a stencil node outside the brick");
                first[d][lattice] = i * self.stride[d];
            }
        }
        // Lane `f` is field `f`: on the faces along axis `f`, at the centres along the others.
        let lane = |d: usize| -> ([usize; 4], [f64; 4]) {
            let lattice = |f: usize| usize::from(f != d);
            (
                std::array::from_fn(|f| first[d][lattice(f)]),
                std::array::from_fn(|f| frac[d][lattice(f)]),
            )
        };
        let (ox, fx) = lane(0);
        let (oy, fy) = lane(1);
        let (oz, fz) = lane(2);
        let [sx, sy, sz] = self.stride;
        let base: [usize; 4] = std::array::from_fn(|f| f * self.volume + ox[f] + oy[f] + oz[f]);
        let data = &self.data[..4 * self.volume];
        // SAFETY: every lane's first node is at least one node inside its field's block on
        // each axis (the asserts above), so `base[f] + sx + sy + sz` stays in field `f`.
        // The brick's x stride is 1: each x-line's two nodes are adjacent in every field.
        debug_assert_eq!(sx, 1);
        let line = |offset: usize| unsafe { Lanes::pairs_unchecked(data, base, offset) };
        let (fx, fy, fz) = (Lanes::new(fx), Lanes::new(fy), Lanes::new(fz));
        // along x, on the four x-lines of the cell (y low/high, z low/high)
        let v = [line(0), line(sy), line(sz), line(sy + sz)];
        let a: [Lanes; 4] = std::array::from_fn(|q| v[q][0].blend(v[q][1], fx));
        let b = [a[0].blend(a[1], fy), a[2].blend(a[3], fy)];
        let value = b[0].blend(b[1], fz);
        if !gradient {
            return (value.array(), [[0.0; 4]; 3]);
        }
        let ax: [Lanes; 4] = std::array::from_fn(|q| v[q][1].minus(v[q][0]));
        let bx = [ax[0].blend(ax[1], fy), ax[2].blend(ax[3], fy)];
        let by = [a[1].minus(a[0]), a[3].minus(a[2])];
        let grad = [
            bx[0].blend(bx[1], fz).per(g.h[0]).array(),
            by[0].blend(by[1], fz).per(g.h[1]).array(),
            b[1].minus(b[0]).per(g.h[2]).array(),
        ];
        (value.array(), grad)
    }
}

impl FieldSampler for FieldBrick {
    #[inline]
    fn sample(
        &self,
        x: Vec3,
        interpolation: Interpolation,
        gradient: bool,
        pressure: bool,
    ) -> ([f64; 3], [[f64; 3]; 3], f64) {
        if interpolation == Interpolation::Linear && self.geometry.periodic == [true; 3] {
            let (value, grad) = self.linear_lanes(x, gradient);
            let u = [value[0], value[1], value[2]];
            let g = std::array::from_fn(|c| [grad[0][c], grad[1][c], grad[2][c]]);
            return (u, g, if pressure { value[3] } else { 0.0 });
        }
        sample_stored(self, x, interpolation, gradient, pressure)
    }

    fn nu(&self) -> f64 {
        self.nu
    }

    fn cell_size(&self) -> f64 {
        self.cell_size
    }
}

/// The pressure is the fourth field.
const _: () = assert!(PRESSURE == 3);

/// Four `f64` lanes, one per field, in one 256-bit register where the build has AVX (this
/// project builds for x86-64-v3, .cargo/config.toml), else in an array. The operations are
/// the scalar ones lane by lane (`a + t (b − a)`, no fused multiply-add), so both give the
/// scalar stencil's results bit for bit.
#[derive(Clone, Copy)]
struct Lanes(LaneRegister);

#[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
type LaneRegister = std::arch::x86_64::__m256d;
#[cfg(not(all(target_arch = "x86_64", target_feature = "avx")))]
type LaneRegister = [f64; 4];

#[cfg(not(all(target_arch = "x86_64", target_feature = "avx")))]
impl Lanes {
    /// `[data[base[f] + offset] in lane f, data[base[f] + offset + 1] in lane f]`.
    ///
    /// # Safety
    /// Every `base[f] + offset + 1` is inside `data`.
    #[inline(always)]
    unsafe fn pairs_unchecked(data: &[f64], base: [usize; 4], offset: usize) -> [Self; 2] {
        // SAFETY: the caller's.
        let at = |next: usize| {
            Self::new(std::array::from_fn(|f| unsafe {
                *data.get_unchecked(base[f] + offset + next)
            }))
        };
        [at(0), at(1)]
    }
}

#[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
impl Lanes {
    /// `[data[base[f] + offset] in lane f, data[base[f] + offset + 1] in lane f]`: the four
    /// fields' adjacent pairs by four 16-byte loads and a 4 × 2 transpose in registers
    /// (eight single loads and their inserts each otherwise).
    ///
    /// # Safety
    /// Every `base[f] + offset + 1` is inside `data`.
    #[inline(always)]
    unsafe fn pairs_unchecked(data: &[f64], base: [usize; 4], offset: usize) -> [Self; 2] {
        use std::arch::x86_64::{
            _mm256_castpd128_pd256, _mm256_insertf128_pd, _mm256_unpackhi_pd, _mm256_unpacklo_pd,
            _mm_loadu_pd,
        };
        // SAFETY: the caller's (two samples from each base), and AVX as below.
        unsafe {
            let pair = |f: usize| _mm_loadu_pd(data.as_ptr().add(base[f] + offset));
            // [f0 x0, f0 x1, f2 x0, f2 x1] and [f1 x0, f1 x1, f3 x0, f3 x1]
            let even = _mm256_insertf128_pd::<1>(_mm256_castpd128_pd256(pair(0)), pair(2));
            let odd = _mm256_insertf128_pd::<1>(_mm256_castpd128_pd256(pair(1)), pair(3));
            [
                Lanes(_mm256_unpacklo_pd(even, odd)),
                Lanes(_mm256_unpackhi_pd(even, odd)),
            ]
        }
    }

    #[inline(always)]
    fn new(v: [f64; 4]) -> Self {
        use std::arch::x86_64::_mm256_set_pd;
        // SAFETY (here and below): the build enables AVX (the cfg of this impl).
        Lanes(unsafe { _mm256_set_pd(v[3], v[2], v[1], v[0]) })
    }

    /// `self + t (other − self)`.
    #[inline(always)]
    fn blend(self, other: Self, t: Self) -> Self {
        use std::arch::x86_64::{_mm256_add_pd, _mm256_mul_pd, _mm256_sub_pd};
        Lanes(unsafe { _mm256_add_pd(self.0, _mm256_mul_pd(t.0, _mm256_sub_pd(other.0, self.0))) })
    }

    #[inline(always)]
    fn minus(self, other: Self) -> Self {
        Lanes(unsafe { std::arch::x86_64::_mm256_sub_pd(self.0, other.0) })
    }

    /// `self / h`.
    #[inline(always)]
    fn per(self, h: f64) -> Self {
        use std::arch::x86_64::{_mm256_div_pd, _mm256_set1_pd};
        Lanes(unsafe { _mm256_div_pd(self.0, _mm256_set1_pd(h)) })
    }

    #[inline(always)]
    fn array(self) -> [f64; 4] {
        let mut out = [0.0; 4];
        // SAFETY: AVX as above; an unaligned store of four lanes into four f64s.
        unsafe { std::arch::x86_64::_mm256_storeu_pd(out.as_mut_ptr(), self.0) };
        out
    }
}

#[cfg(not(all(target_arch = "x86_64", target_feature = "avx")))]
impl Lanes {
    #[inline(always)]
    fn new(v: [f64; 4]) -> Self {
        Lanes(v)
    }

    /// `self + t (other − self)`.
    #[inline(always)]
    fn blend(self, other: Self, t: Self) -> Self {
        Lanes(std::array::from_fn(|f| {
            self.0[f] + t.0[f] * (other.0[f] - self.0[f])
        }))
    }

    #[inline(always)]
    fn minus(self, other: Self) -> Self {
        Lanes(std::array::from_fn(|f| self.0[f] - other.0[f]))
    }

    /// `self / h`.
    #[inline(always)]
    fn per(self, h: f64) -> Self {
        Lanes(self.0.map(|e| e / h))
    }

    #[inline(always)]
    fn array(self) -> [f64; 4] {
        self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::{BoundaryConditions, FaceCondition, FluidSettings, FluidSolver};
    use crate::grid::Grid;
    use crate::particles::SplitMix64;

    fn uniform(rng: &mut SplitMix64, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * rng.next_f64()
    }

    fn solver(bc: BoundaryConditions, seed: u64) -> FluidSolver {
        let grid = Grid::new([14, 11, 12], [0.1, 0.1, 0.1], [0.3, -0.2, 0.1]);
        let mut s = FluidSolver::new(grid, bc, FluidSettings::new(1.0)).unwrap();
        let mut rng = SplitMix64::new(seed);
        for c in 0..3 {
            for v in s.velocity_mut()[c].iter_mut() {
                *v = uniform(&mut rng, -1.0, 1.0);
            }
        }
        for p in s.pressure_mut().iter_mut() {
            *p = uniform(&mut rng, -1.0, 1.0);
        }
        s
    }

    /// Random points within `reach` of `centre`, and some on the sphere of radius `reach`.
    fn points(rng: &mut SplitMix64, centre: [f64; 3], reach: f64) -> Vec<[f64; 3]> {
        (0..400)
            .map(|k| {
                let mut n = [0.0; 3];
                let mut norm = 0.0;
                while norm < 1e-3 {
                    n = [0; 3].map(|_| uniform(rng, -1.0, 1.0));
                    norm = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                }
                let r = if k % 4 == 0 {
                    reach
                } else {
                    reach * uniform(rng, 0.0, 1.0)
                };
                std::array::from_fn(|d| centre[d] + r * n[d] / norm)
            })
            .collect()
    }

    fn assert_same_samples(bc: BoundaryConditions, centres: &[[f64; 3]], seed: u64) {
        let s = solver(bc, seed);
        let view = FieldView::of(&s);
        let mut brick = FieldBrick::new();
        let mut rng = SplitMix64::new(seed + 1);
        for &centre in centres {
            for interpolation in [Interpolation::Linear, Interpolation::Cubic] {
                let reach = 0.37;
                brick.gather(&view, Vec3::from(centre), reach, interpolation);
                for x in points(&mut rng, centre, reach) {
                    let a = view.sample(Vec3::from(x), interpolation, true, true);
                    let b = brick.sample(Vec3::from(x), interpolation, true, true);
                    assert_eq!(a, b, "{interpolation:?} at {x:?} (centre {centre:?})");
                    assert_eq!(
                        view.pressure_at(Vec3::from(x), interpolation),
                        brick.pressure_at(Vec3::from(x), interpolation)
                    );
                    // a linear brick serves the linear shell too
                    if interpolation == Interpolation::Cubic {
                        let a = view.velocity_at(Vec3::from(x), Interpolation::Linear);
                        assert_eq!(a, brick.velocity_at(Vec3::from(x), Interpolation::Linear));
                    }
                }
            }
        }
    }

    #[test]
    fn a_brick_reads_what_the_whole_grid_reads_in_a_periodic_box() {
        // inside, across the low and the high faces of the box, and a periodic image
        let centres = [
            [0.95, 0.35, 0.72],
            [0.32, -0.15, 0.12],
            [1.65, 0.86, 1.25],
            [0.95 + 1.4, 0.35 - 1.1, 0.72 + 2.4],
        ];
        assert_same_samples(BoundaryConditions::periodic(), &centres, 7);
    }

    #[test]
    fn a_brick_reads_what_the_whole_grid_reads_next_to_walls() {
        // walls along y: the stencils shift inside the stored samples there, even for
        // points beyond the wall
        let mut bc = BoundaryConditions::periodic();
        for side in 0..2 {
            bc.faces[2 + side] = FaceCondition::Wall { velocity: [0.0; 3] };
        }
        let centres = [[0.95, -0.12, 0.72], [0.4, 0.83, 0.3], [1.1, 0.35, 1.2]];
        assert_same_samples(bc, &centres, 11);
    }
}
