//! Parallel, deterministic spreading of particle quantities onto grid arrays.
//!
//! Spreading is a scatter: two particles may add to the same sample. The particles are cut into
//! chunks of [`PARTICLES_PER_CHUNK`] consecutive particles (a count that does not depend on the
//! thread count); each chunk adds its particles, in order, into its own partial array covering
//! only the padded indices its stencils touch, and each grid value is then the sum of the
//! partials, taken in chunk order:
//!
//! ```text
//! target[i] = Σ_k partial_k[i],   partial_k[i] = Σ_{p ∈ chunk k} w_p(i) value_p   (in order)
//! ```
//!
//! The result is therefore the same for any number of threads (bit-identical), and differs from
//! a serial pass over all particles only by the summation's round-off. The DEM keeps the
//! particles sorted by cell, so a chunk covers a thin slab of the grid and its partial is small.

use rayon::prelude::*;

/// Particles per chunk: large enough to amortise a chunk's partial array, small enough to give
/// every thread several chunks.
pub const PARTICLES_PER_CHUNK: usize = 512;

/// Grid values per block of the final reduction.
const REDUCTION_BLOCK: usize = 1024;

/// One chunk's partial arrays: `fields` arrays over the padded indices `lo..hi`, field-major.
#[derive(Clone, Debug, Default)]
pub struct ChunkPartial {
    lo: usize,
    hi: usize,
    fields: usize,
    values: Vec<f64>,
}

impl ChunkPartial {
    /// Makes the partial hold `fields` zero arrays over the padded indices `lo..hi` (an empty
    /// range when `lo >= hi`); no allocation once the capacity suffices.
    pub fn reset(&mut self, lo: usize, hi: usize, fields: usize) {
        let (lo, hi) = if lo < hi { (lo, hi) } else { (0, 0) };
        self.lo = lo;
        self.hi = hi;
        self.fields = fields;
        self.values.clear();
        self.values.resize(fields * (hi - lo), 0.0);
    }

    /// The first padded index this chunk holds.
    #[inline]
    pub fn base(&self) -> usize {
        self.lo
    }

    /// Fields `f` and `g` (`f ≠ g`) over `lo..hi`, both writable.
    #[inline]
    pub fn field_pair_mut(&mut self, f: usize, g: usize) -> (&mut [f64], &mut [f64]) {
        assert_ne!(f, g);
        let span = self.hi - self.lo;
        let (lo, hi) = (f.min(g), f.max(g));
        let (head, tail) = self.values.split_at_mut(hi * span);
        let (a, b) = (&mut head[lo * span..(lo + 1) * span], &mut tail[..span]);
        if f < g {
            (a, b)
        } else {
            (b, a)
        }
    }

    /// Field `f` over `lo..hi` (index it with `i − base()`).
    #[inline]
    pub fn field_mut(&mut self, f: usize) -> &mut [f64] {
        let span = self.hi - self.lo;
        &mut self.values[f * span..(f + 1) * span]
    }
}

/// The per-chunk partial arrays, kept between steps (no allocation once sized).
#[derive(Clone, Debug, Default)]
pub struct ChunkedScatter {
    chunks: Vec<ChunkPartial>,
}

impl ChunkedScatter {
    pub fn new() -> Self {
        Self::default()
    }

    /// The partials of the chunks of `count` particles (chunk `k` holds particles
    /// `k·PARTICLES_PER_CHUNK ..`), for a caller that fills each with [`ChunkPartial::reset`]
    /// and its particles' deposits in order.
    pub fn partials_mut(&mut self, count: usize) -> &mut [ChunkPartial] {
        self.chunks
            .resize_with(count.div_ceil(PARTICLES_PER_CHUNK), ChunkPartial::default);
        &mut self.chunks
    }

    /// Spreads the quantities of `count` particles into `fields` partial arrays per chunk.
    /// `range(p)` gives the padded indices `lo..hi` particle `p` may touch; `deposit(p, chunk)`
    /// adds particle `p`'s contributions to the chunk's fields.
    pub fn spread<R, D>(&mut self, count: usize, fields: usize, range: R, deposit: D)
    where
        R: Fn(usize) -> (usize, usize) + Sync,
        D: Fn(usize, &mut ChunkPartial) + Sync,
    {
        self.partials_mut(count)
            .par_iter_mut()
            .enumerate()
            .for_each(|(k, chunk)| {
                let first = k * PARTICLES_PER_CHUNK;
                let last = (first + PARTICLES_PER_CHUNK).min(count);
                let (mut lo, mut hi) = (usize::MAX, 0);
                for p in first..last {
                    let (a, b) = range(p);
                    lo = lo.min(a);
                    hi = hi.max(b);
                }
                chunk.reset(lo, hi, fields);
                for p in first..last {
                    deposit(p, chunk);
                }
            });
    }

    /// `target = Σ_k partial_k` of field `f`, the chunks summed in order (overwrites all of
    /// `target`; zero where no chunk reached).
    pub fn reduce_into(&self, f: usize, target: &mut [f64]) {
        let chunks = &self.chunks;
        target
            .par_chunks_mut(REDUCTION_BLOCK)
            .enumerate()
            .for_each(|(block, out)| {
                out.iter_mut().for_each(|x| *x = 0.0);
                let start = block * REDUCTION_BLOCK;
                let end = start + out.len();
                for chunk in chunks {
                    let lo = chunk.lo.max(start);
                    let hi = chunk.hi.min(end);
                    if lo >= hi {
                        continue;
                    }
                    let span = chunk.hi - chunk.lo;
                    let field = &chunk.values[f * span..(f + 1) * span];
                    for i in lo..hi {
                        out[i - start] += field[i - chunk.lo];
                    }
                }
            });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A seeded linear congruential generator (no external crate needed).
    fn lcg(state: &mut u64) -> u64 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        *state >> 33
    }

    #[test]
    fn matches_a_serial_scatter_and_is_thread_count_independent() {
        // 3000 particles adding values of mixed sign to 3 neighbouring indices of a 500-array,
        // in two fields.
        let mut state = 7u64;
        let n = 3000;
        let index: Vec<usize> = (0..n).map(|_| (lcg(&mut state) % 498) as usize).collect();
        let value: Vec<f64> = (0..n)
            .map(|_| (lcg(&mut state) % 10_000) as f64 * 1e-3 - 5.0)
            .collect();
        let mut serial = [vec![0.0; 500], vec![0.0; 500]];
        for p in 0..n {
            for s in 0..3 {
                serial[0][index[p] + s] += value[p];
                serial[1][index[p] + s] += 2.0 * value[p];
            }
        }
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut scatter = ChunkedScatter::new();
                scatter.spread(
                    n,
                    2,
                    |p| (index[p], index[p] + 3),
                    |p, chunk| {
                        let base = chunk.base();
                        for f in 0..2 {
                            let t = chunk.field_mut(f);
                            for s in 0..3 {
                                t[index[p] + s - base] += (f + 1) as f64 * value[p];
                            }
                        }
                    },
                );
                let mut out = [vec![f64::NAN; 500], vec![f64::NAN; 500]];
                scatter.reduce_into(0, &mut out[0]);
                scatter.reduce_into(1, &mut out[1]);
                out
            })
        };
        let one = run(1);
        let three = run(3);
        for f in 0..2 {
            for i in 0..500 {
                assert_eq!(
                    one[f][i].to_bits(),
                    three[f][i].to_bits(),
                    "field {f} index {i}"
                );
                assert!(
                    (one[f][i] - serial[f][i]).abs() < 1e-12,
                    "{} vs {}",
                    one[f][i],
                    serial[f][i]
                );
            }
        }
    }
}
