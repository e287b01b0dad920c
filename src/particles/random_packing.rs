//! Random non-overlapping packings by random sequential addition (RSA): candidate centres are
//! drawn uniformly in the region and kept when they overlap nothing placed before.
//!
//! RSA of equal spheres jams near a solid fraction of 0.38 in an unbounded region
//! (Torquato, Uche & Stillinger 2006, Phys. Rev. E 74, 061308: φ_s ≈ 0.3841); walls lower it.
//! Denser beds come from settling an RSA packing. Overlap checks use a cell grid of side `d`
//! (a cell holds at most 8 centres), so each candidate costs O(1).

use std::fmt;

use super::dem::sphere_volume;
use crate::Vec3;

/// Why a packing could not be made.
#[derive(Clone, Debug, PartialEq)]
pub enum PackingError {
    /// Diameter, region or target out of range.
    BadInput(String),
    /// RSA stopped (too many consecutive rejected candidates) below the target.
    Unreachable {
        target: f64,
        reached: f64,
        placed: usize,
    },
}

impl fmt::Display for PackingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PackingError::BadInput(s) => write!(f, "random packing: {s}"),
            PackingError::Unreachable { target, reached, placed } => write!(
                f,
                "random packing: target solid fraction {target} is unreachable by random sequential addition; \
                 it stalled at {reached:.4} ({placed} spheres). Fill to at most that and let the bed settle"
            ),
        }
    }
}

impl std::error::Error for PackingError {}

/// SplitMix64 (Steele, Lea & Flood 2014): a small, seedable generator.
#[derive(Clone, Debug)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    pub fn new(seed: u64) -> Self {
        SplitMix64(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)` with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// Consecutive rejections after which RSA is declared stalled.
const MAX_CONSECUTIVE_REJECTIONS: usize = 200_000;

/// Centres of equal spheres of diameter `d` filling the box `[lo, hi]` (spheres entirely
/// inside) to the solid fraction `target = N π d³ / 6 / V`, with a fixed `seed`.
pub fn random_packing(
    lo: impl Into<Vec3>,
    hi: impl Into<Vec3>,
    d: f64,
    target: f64,
    seed: u64,
) -> Result<Vec<Vec3>, PackingError> {
    let (lo, hi) = (lo.into(), hi.into());
    if !(d > 0.0 && d.is_finite()) {
        return Err(PackingError::BadInput(format!(
            "diameter {d} must be positive"
        )));
    }
    if !(target > 0.0 && target < 1.0) {
        return Err(PackingError::BadInput(format!(
            "target solid fraction {target} must be in (0, 1)"
        )));
    }
    let volume = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    let wanted = (target * volume / sphere_volume(d)).round() as usize;
    random_packing_sizes(lo, hi, &vec![d; wanted], target, seed, [false; 3])
}

/// Centres for spheres of the given `diameters` (placed in that order: largest first packs
/// best) in the box `[lo, hi]`, with a fixed `seed`. Along an axis with `wrap[a]` the box is
/// one period of a periodic domain: centres fill `[lo, hi)` and spheres may cross its faces
/// (overlaps are tested with the nearest image), so the suspension is homogeneous across
/// them; along the other axes every sphere lies entirely inside. `target` is only quoted
/// back in the error when RSA stalls before placing them all.
pub fn random_packing_sizes(
    lo: Vec3,
    hi: Vec3,
    diameters: &[f64],
    target: f64,
    seed: u64,
    wrap: [bool; 3],
) -> Result<Vec<Vec3>, PackingError> {
    let mut d_max: f64 = 0.0;
    for (k, &d) in diameters.iter().enumerate() {
        if !(d > 0.0 && d.is_finite()) {
            return Err(PackingError::BadInput(format!(
                "diameter {d} of sphere {k} must be positive"
            )));
        }
        d_max = d_max.max(d);
    }
    let length = Vec3::new(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
    if diameters.is_empty() {
        return Ok(Vec::new());
    }
    if (0..3).any(|a| length[a].is_nan() || length[a] < d_max) {
        return Err(PackingError::BadInput(format!(
            "region {lo:?}–{hi:?} is narrower than the diameter {d_max}"
        )));
    }
    let volume = length[0] * length[1] * length[2];
    // linked cells of side ≥ d_max over the box: overlaps are within the 27 cells around
    let mut n = [1usize; 3];
    for a in 0..3 {
        n[a] = ((length[a] / d_max).floor() as usize).clamp(1, 1 << 10);
    }
    let cell_len = Vec3::new(
        length[0] / n[0] as f64,
        length[1] / n[1] as f64,
        length[2] / n[2] as f64,
    );
    let coord = |x: f64, a: usize| -> usize {
        (((x - lo[a]) / cell_len[a]).floor().max(0.0) as usize).min(n[a] - 1)
    };
    let mut head = vec![u32::MAX; n[0] * n[1] * n[2]];
    let mut next: Vec<u32> = Vec::with_capacity(diameters.len());
    let mut centres: Vec<Vec3> = Vec::with_capacity(diameters.len());
    let mut placed_volume = 0.0;
    let mut rng = SplitMix64::new(seed);
    for &d in diameters {
        let mut rejections = 0usize;
        loop {
            // uniform over one period along a wrapped axis, else with the sphere inside
            let mut x = Vec3::zeros();
            for a in 0..3 {
                x[a] = if wrap[a] {
                    lo[a] + rng.next_f64() * length[a]
                } else {
                    lo[a] + 0.5 * d + rng.next_f64() * (length[a] - d)
                };
            }
            let c = [coord(x[0], 0), coord(x[1], 1), coord(x[2], 2)];
            let [rx, ry, rz] = [0, 1, 2].map(|a| neighbour_cells(c[a], n[a], wrap[a]));
            let mut free = true;
            'search: for &cz in &rz.0[..rz.1] {
                for &cy in &ry.0[..ry.1] {
                    for &cx in &rx.0[..rx.1] {
                        let mut s = head[cx + n[0] * (cy + n[1] * cz)];
                        while s != u32::MAX {
                            let y = centres[s as usize];
                            let reach = 0.5 * (d + diameters[s as usize]);
                            let mut dd = 0.0;
                            for a in 0..3 {
                                let mut r = x[a] - y[a];
                                if wrap[a] {
                                    r -= length[a] * (r / length[a]).round(); // nearest image
                                }
                                dd += r * r;
                            }
                            if dd < reach * reach {
                                free = false;
                                break 'search;
                            }
                            s = next[s as usize];
                        }
                    }
                }
            }
            if free {
                let cell = c[0] + n[0] * (c[1] + n[1] * c[2]);
                next.push(head[cell]);
                head[cell] = centres.len() as u32;
                centres.push(x);
                placed_volume += sphere_volume(d);
                break;
            }
            rejections += 1;
            if rejections >= MAX_CONSECUTIVE_REJECTIONS {
                return Err(PackingError::Unreachable {
                    target,
                    reached: placed_volume / volume,
                    placed: centres.len(),
                });
            }
        }
    }
    Ok(centres)
}

/// The linked cells next to cell `c` of `n` along one axis (itself and its neighbours,
/// across the periodic faces when `wrap`), each once: the first `count` of the array.
fn neighbour_cells(c: usize, n: usize, wrap: bool) -> ([usize; 3], usize) {
    if wrap && n >= 3 {
        ([(c + n - 1) % n, c, (c + 1) % n], 3)
    } else if wrap {
        ([0, 1, 2], n)
    } else {
        let first = c.saturating_sub(1);
        let last = (c + 1).min(n - 1);
        ([first, first + 1, first + 2], last - first + 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn min_gap(c: &[Vec3], d: f64) -> f64 {
        // brute-force reference (allowed in tests only)
        let mut g = f64::INFINITY;
        for i in 0..c.len() {
            for j in 0..i {
                let r = ((c[i][0] - c[j][0]).powi(2)
                    + (c[i][1] - c[j][1]).powi(2)
                    + (c[i][2] - c[j][2]).powi(2))
                .sqrt();
                g = g.min(r - d);
            }
        }
        g
    }

    #[test]
    fn packing_hits_target_without_overlap_and_is_reproducible() {
        let (lo, hi, d) = (Vec3::zeros(), [10.0, 8.0, 12.0], 1.0);
        let c = random_packing(lo, hi, d, 0.25, 42).unwrap();
        let phi = c.len() as f64 * sphere_volume(d) / (10.0 * 8.0 * 12.0);
        assert!((phi - 0.25).abs() < 0.002, "phi = {phi}");
        assert!(min_gap(&c, d) >= 0.0);
        for x in &c {
            for a in 0..3 {
                assert!(x[a] >= lo[a] + 0.5 * d && x[a] <= hi[a] - 0.5 * d);
            }
        }
        assert_eq!(c, random_packing(lo, hi, d, 0.25, 42).unwrap());
        assert_ne!(c, random_packing(lo, hi, d, 0.25, 43).unwrap());
    }

    #[test]
    fn polydisperse_packing_has_no_overlap() {
        let mut rng = SplitMix64::new(9);
        let mut d: Vec<f64> = (0..300).map(|_| 0.5 + rng.next_f64()).collect();
        d.sort_by(|a, b| b.partial_cmp(a).unwrap());
        let (lo, hi) = (Vec3::zeros(), [8.0, 8.0, 8.0]);
        let c = random_packing_sizes(lo, Vec3::from(hi), &d, 0.0, 3, [false; 3]).unwrap();
        assert_eq!(c.len(), d.len());
        // brute-force reference (allowed in tests only)
        for i in 0..c.len() {
            for a in 0..3 {
                assert!(c[i][a] >= lo[a] + 0.5 * d[i] && c[i][a] <= hi[a] - 0.5 * d[i]);
            }
            for j in 0..i {
                let r2: f64 = (0..3).map(|a| (c[i][a] - c[j][a]).powi(2)).sum();
                assert!(r2.sqrt() >= 0.5 * (d[i] + d[j]), "{i} and {j} overlap");
            }
        }
    }

    #[test]
    fn unreachable_target_reports_the_fraction_reached() {
        let err = random_packing(Vec3::zeros(), [6.0; 3], 1.0, 0.5, 1).unwrap_err();
        match err {
            PackingError::Unreachable { reached, .. } => {
                // RSA with walls stalls below the bulk jamming limit 0.384
                assert!(reached > 0.2 && reached < 0.385, "reached {reached}");
                eprintln!("RSA stalled at {reached}");
            }
            e => panic!("unexpected {e}"),
        }
        assert!(matches!(
            random_packing(Vec3::zeros(), [0.5, 6.0, 6.0], 1.0, 0.1, 1),
            Err(PackingError::BadInput(_))
        ));
        assert!(matches!(
            random_packing(Vec3::zeros(), [6.0; 3], -1.0, 0.1, 1),
            Err(PackingError::BadInput(_))
        ));
    }

    #[test]
    fn a_wrapped_packing_is_homogeneous_across_the_periodic_faces() {
        // periodic along x and z, walls along y: centres reach the periodic faces, no two
        // spheres overlap through them (nearest image), and the y faces are kept
        let (lo, hi, d) = (Vec3::zeros(), Vec3::new(6.0, 5.0, 6.0), 1.0);
        let wrap = [true, false, true];
        let c = random_packing_sizes(lo, hi, &[d; 40], 0.0, 5, wrap).unwrap();
        assert_eq!(c.len(), 40);
        // brute-force reference (allowed in tests only)
        for i in 0..c.len() {
            assert!(c[i][1] >= 0.5 * d && c[i][1] <= hi[1] - 0.5 * d);
            for a in [0, 2] {
                assert!(c[i][a] >= 0.0 && c[i][a] < hi[a]);
            }
            for j in 0..i {
                let mut r2 = 0.0;
                for a in 0..3 {
                    let mut r = c[i][a] - c[j][a];
                    if wrap[a] {
                        r -= hi[a] * (r / hi[a]).round();
                    }
                    r2 += r * r;
                }
                assert!(
                    r2.sqrt() >= d,
                    "{i} and {j} overlap through a periodic face"
                );
            }
        }
        // spheres cross the x faces: some centres lie within a radius of them
        let near = c
            .iter()
            .filter(|x| x[0] < 0.5 * d || x[0] > hi[0] - 0.5 * d)
            .count();
        assert!(near > 0, "no sphere crosses a periodic face");
        // and a box narrower than 3 linked cells wraps too
        let c = random_packing_sizes(lo, Vec3::new(2.0, 2.0, 2.0), &[d; 2], 0.0, 1, [true; 3]);
        assert_eq!(c.unwrap().len(), 2);
    }
}
