//! The fluid's health check and step rules: one pass over the field for divergence,
//! energy, speeds and Courant number, kept until the velocity changes, and the rules
//! that read it (OpenFOAM's adjustable step, the scheme's stability bound).

use super::FluidSolver;
use crate::fluid::boundary_conditions::FaceCondition;
use crate::fluid::diagnostics::FluidDiagnostics;
use rayon::prelude::*;

/// The reductions that a step's health check finds and the next step's rules read again
/// (the Courant rule, the scheme's bound, the sedimentation's mean): one pass over the
/// field instead of three.
#[derive(Clone, Copy, Debug)]
pub(super) struct CachedReductions {
    /// `½ max Σ|u_f|/h`.
    pub(super) courant_rate: f64,
    /// [`FluidSolver::max_speed`].
    pub(super) max_speed: [f64; 3],
    /// [`FluidSolver::mean_component`], bit for bit (the same sums in the same order).
    pub(super) mean: [f64; 3],
}

impl FluidSolver {
    /// Volume mean of component `c` (mean of the cell-centre interpolants), summed plane by
    /// plane in a fixed order so the result does not depend on the thread count.
    pub fn mean_component(&mut self, c: usize) -> f64 {
        if let Some(cached) = self.cached_reductions() {
            return cached.mean[c];
        }
        let l = &self.layout;
        let n = l.n;
        let uc = &self.u[c][..];
        let sc = l.stride[c];
        self.partials
            .par_iter_mut()
            .enumerate()
            .for_each(|(k, part)| {
                part[0] = 0.0;
                if k == 0 || k > n[2] {
                    return;
                }
                let mut sum = 0.0;
                for j in 1..=n[1] {
                    let base = l.index(0, j, k);
                    for i in 1..=n[0] {
                        sum += uc[base + i] + uc[base + i + sc];
                    }
                }
                part[0] = 0.5 * sum;
            });
        self.partials.iter().map(|p| p[0]).sum::<f64>() / self.grid.cell_count() as f64
    }

    /// Divergence, kinetic energy, mean velocity, speeds and Courant number for step `dt`.
    /// The same pass finds what [`Self::max_speed`] and [`Self::mean_component`] return,
    /// and keeps it until the velocity changes.
    pub fn diagnostics(&mut self, dt: f64) -> FluidDiagnostics {
        let l = &self.layout;
        let n = l.n;
        let s = l.stride;
        let h = self.grid.h;
        let plane = l.plane_len();
        let (ux, uy, uz) = (&self.u[0][..], &self.u[1][..], &self.u[2][..]);
        self.partials
            .par_iter_mut()
            .enumerate()
            .for_each(|(k, part)| {
                *part = [0.0; 12];
                // max_speed's: every stored value of the plane, ghosts included
                for (c, u) in [ux, uy, uz].into_iter().enumerate() {
                    part[9 + c] = largest_magnitude(&u[k * plane..(k + 1) * plane]);
                }
                if k == 0 || k > n[2] {
                    return;
                }
                // Four cells at a time, one per lane: the maxima lane by lane (a maximum
                // does not depend on the order), the sums cell by cell in mean_component's
                // order, so that the results are those of one cell after another bit for
                // bit; the lanes' divisions vectorise, one cell's do not.
                let mut peak = [[0.0; LANES]; 5];
                let mut sums = [0.0; 3];
                let add = |peak: &mut [[f64; LANES]; 5],
                           sums: &mut [f64; 3],
                           part: &mut [f64; 12],
                           p: usize,
                           lanes: usize| {
                    let group = CellGroup::at([ux, uy, uz], p, [s[1], s[2]], h);
                    for lane in 0..LANES {
                        peak[0][lane] = larger(peak[0][lane], group.divergence[lane]);
                        for c in 0..3 {
                            peak[1 + c][lane] = larger(peak[1 + c][lane], group.speed[c][lane]);
                        }
                        peak[4][lane] = larger(peak[4][lane], group.courant[lane]);
                    }
                    for lane in 0..lanes {
                        part[1] += group.energy[lane];
                        for c in 0..3 {
                            sums[c] += group.sum[c][lane];
                        }
                    }
                };
                for j in 1..=n[1] {
                    let base = l.index(0, j, k);
                    let mut i = 1;
                    while i + LANES <= n[0] + 1 {
                        add(&mut peak, &mut sums, part, base + i, LANES);
                        i += LANES;
                    }
                    // the row's last cells: the lanes past its end read the next cells'
                    // faces (the padding holds them), and their results are dropped (the
                    // maxima restored after: cheaper than a lane count in their loop,
                    // docs/benchmarks/direct.md)
                    if i <= n[0] {
                        let (kept, used) = (peak, n[0] + 1 - i);
                        add(&mut peak, &mut sums, part, base + i, used);
                        for (peak, kept) in peak.iter_mut().zip(&kept) {
                            peak[used..].copy_from_slice(&kept[used..]);
                        }
                    }
                }
                for lane in 0..LANES {
                    part[0] = larger(part[0], peak[0][lane]);
                    for c in 0..3 {
                        part[5 + c] = larger(part[5 + c], peak[1 + c][lane]);
                    }
                    part[8] = larger(part[8], peak[4][lane]);
                }
                for c in 0..3 {
                    part[2 + c] = 0.5 * sums[c];
                }
            });
        let mut total = [0.0f64; 12];
        for part in &self.partials {
            total[0] = total[0].max(part[0]);
            for c in 1..5 {
                total[c] += part[c];
            }
            for c in 5..12 {
                total[c] = total[c].max(part[c]);
            }
        }
        let cells = self.grid.cell_count() as f64;
        let h_min = self.active_h_min();
        let speed = total[5].max(total[6]).max(total[7]);
        let mean = [total[2] / cells, total[3] / cells, total[4] / cells];
        // f64::max skips NaN: a blown-up field must not report a clean divergence.
        let blown_up = !total[1].is_finite();
        let diagnostics = FluidDiagnostics {
            divergence: if blown_up {
                f64::NAN
            } else if speed > 0.0 {
                total[0] * h_min / speed
            } else {
                total[0] * h_min
            },
            max_divergence: total[0],
            kinetic_energy: total[1] / cells,
            mean_velocity: mean,
            max_speed: [total[5], total[6], total[7]],
            max_courant: total[8] * dt,
        };
        let cached = CachedReductions {
            courant_rate: total[8],
            max_speed: [total[9], total[10], total[11]],
            mean,
        };
        self.reductions = Some((self.generation, cached));
        diagnostics
    }

    /// The last diagnostics' reductions, if the velocity has not changed since.
    pub(super) fn cached_reductions(&self) -> Option<CachedReductions> {
        match self.reductions {
            Some((generation, cached)) if generation == self.generation => Some(cached),
            _ => None,
        }
    }

    pub(super) fn active(&self) -> [bool; 3] {
        std::array::from_fn(|d| !matches!(self.bc.face(d, 0), FaceCondition::Empty))
    }

    pub(super) fn active_h_min(&self) -> f64 {
        let a = self.active();
        (0..3)
            .filter(|&d| a[d])
            .map(|d| self.grid.h[d])
            .fold(f64::INFINITY, f64::min)
    }

    /// Largest face speed per component over every stored value (ghosts included), m/s.
    pub fn max_speed(&self) -> [f64; 3] {
        if let Some(cached) = self.cached_reductions() {
            return cached.max_speed;
        }
        std::array::from_fn(|c| {
            self.u[c]
                .par_chunks(self.layout.plane_len())
                .map(largest_magnitude)
                .reduce(|| 0.0, f64::max)
        })
    }

    /// The scheme's stability bound on `Δt` for the current velocity (paper eq. 3 for Euler;
    /// see [`TimeScheme::stability_bound`](crate::fluid::TimeScheme::stability_bound)).
    pub fn stability_bound(&self) -> f64 {
        // without advection only the viscous part bounds the step
        let speed = if self.settings.convection {
            self.max_speed()
        } else {
            [0.0; 3]
        };
        self.settings
            .scheme
            .stability_bound(self.settings.nu, self.grid.h, self.active(), speed)
    }

    /// Courant number per unit time step: `Co = Δt × courant_rate()` (OpenFOAM's definition,
    /// `½ Σ_faces |u_f| / h` per cell, largest over cells). Taken from the last
    /// [`Self::diagnostics`] when the velocity has not changed since (a time loop's health
    /// check and the next step's Courant rule read the same field), else computed.
    pub fn courant_rate(&mut self) -> f64 {
        match self.cached_reductions() {
            Some(cached) => cached.courant_rate,
            None => self.diagnostics(1.0).max_courant,
        }
    }

    /// Marks the velocity as changed (the cached Courant rate no longer holds).
    pub(super) fn velocity_changes(&mut self) {
        self.generation = self.generation.wrapping_add(1);
        self.reductions = None;
    }

    /// Next time step under `adjustTimeStep yes`, by OpenFOAM's rule (setDeltaT): with
    /// `f = maxCo / Co` at the old step, `Δt = min(min(f, 1 + 0.1 f, 1.2) Δt_old, maxDeltaT)`
    /// (shrink at once, grow by at most 20 %), and never above the scheme's stability bound.
    /// `dt_old` is the last step (or the case's `deltaT` at start).
    pub fn adaptive_dt(&mut self, dt_old: f64, max_co: f64, max_dt: f64) -> f64 {
        self.courant_dt(dt_old, max_co, max_dt)
            .min(self.stability_bound())
    }

    /// [`Self::adaptive_dt`] without the scheme's bound (for a model that steps the fluid with
    /// its own scheme and bound: the drag law's).
    pub fn courant_dt(&mut self, dt_old: f64, max_co: f64, max_dt: f64) -> f64 {
        let co = self.courant_rate() * dt_old;
        let f = if co > 0.0 { max_co / co } else { f64::INFINITY };
        let factor = f.min(1.0 + 0.1 * f).min(1.2);
        (factor * dt_old).min(max_dt)
    }
}

/// Cells (or samples) per lane group of the reductions: four `f64` fill one AVX register.
const LANES: usize = 4;

/// What [`FluidSolver::diagnostics`] reads from [`LANES`] consecutive cells, one per lane,
/// each lane computed as for one cell alone.
struct CellGroup {
    /// `|∇·u|`.
    divergence: [f64; LANES],
    /// `¼ Σ u_f²` over the six faces.
    energy: [f64; LANES],
    /// Per component, the sum of the two faces' values, and the larger magnitude.
    sum: [[f64; LANES]; 3],
    speed: [[f64; LANES]; 3],
    /// `½ Σ_d (|u_low| + |u_high|) / h_d`.
    courant: [f64; LANES],
}

impl CellGroup {
    /// The cells whose low faces sit at padded index `p..p + LANES` of the components `u`
    /// (`strides`: the y and z strides).
    #[inline(always)]
    fn at(u: [&[f64]; 3], p: usize, strides: [usize; 2], h: [f64; 3]) -> Self {
        let lanes = |c: usize, offset: usize| -> [f64; LANES] {
            u[c][p + offset..p + offset + LANES]
                .try_into()
                .expect("LANES samples")
        };
        let f = [
            lanes(0, 0),
            lanes(0, 1),
            lanes(1, 0),
            lanes(1, strides[0]),
            lanes(2, 0),
            lanes(2, strides[1]),
        ];
        let mut group = CellGroup {
            divergence: [0.0; LANES],
            energy: [0.0; LANES],
            sum: [[0.0; LANES]; 3],
            speed: [[0.0; LANES]; 3],
            courant: [0.0; LANES],
        };
        for lane in 0..LANES {
            let f: [f64; 6] = std::array::from_fn(|q| f[q][lane]);
            let div = (f[1] - f[0]) / h[0] + (f[3] - f[2]) / h[1] + (f[5] - f[4]) / h[2];
            group.divergence[lane] = div.abs();
            group.energy[lane] = 0.25
                * (f[0] * f[0]
                    + f[1] * f[1]
                    + f[2] * f[2]
                    + f[3] * f[3]
                    + f[4] * f[4]
                    + f[5] * f[5]);
            for c in 0..3 {
                group.sum[c][lane] = f[2 * c] + f[2 * c + 1];
                // from 0 as the running maximum was: a NaN face must not hide the other
                group.speed[c][lane] = larger(larger(0.0, f[2 * c].abs()), f[2 * c + 1].abs());
            }
            group.courant[lane] = 0.5
                * ((f[0].abs() + f[1].abs()) / h[0]
                    + (f[2].abs() + f[3].abs()) / h[1]
                    + (f[4].abs() + f[5].abs()) / h[2]);
        }
        group
    }
}

/// `max |x|` over `values` skipping NaN (0 if none), lane by lane and then across the
/// lanes: the maximum does not depend on the order, and one chain of compares would wait on
/// each other.
fn largest_magnitude(values: &[f64]) -> f64 {
    let mut peak = [0.0; LANES];
    let mut chunks = values.chunks_exact(LANES);
    for chunk in &mut chunks {
        for lane in 0..LANES {
            peak[lane] = larger(peak[lane], chunk[lane].abs());
        }
    }
    let tail = chunks
        .remainder()
        .iter()
        .fold(0.0, |m, x| larger(m, x.abs()));
    peak.iter().fold(tail, |m, &x| larger(m, x))
}

/// `max(m, x)` skipping a NaN `x` as `f64::max` does, but a plain compare-and-select: the
/// reductions over the whole field then vectorise (`f64::max`'s NaN handling does not).
#[inline(always)]
fn larger(m: f64, x: f64) -> f64 {
    if x > m {
        x
    } else {
        m
    }
}
