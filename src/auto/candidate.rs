//! One way to run a scene: a model on a grid, with its predicted error, steps, time and
//! memory.

use super::model_fit::{direct_error, drag_law_error, DIRECT_COST, DRAG_LAW_COST};
use super::scene::Scene;
use crate::case::coupling::CouplingModel;
use crate::coupling::direct::RESPONSE_STEP_FRACTION;

/// The direct model's candidate resolutions, cells per radius of the smallest particle.
pub const DIRECT_RESOLUTIONS: [f64; 6] = [3.0, 4.0, 6.0, 8.0, 12.0, 16.0];
/// The drag-law model's candidate cells, in diameters of the largest particle (2–4: the
/// paper's 2 and the coarser grids the model is built for).
pub const DRAG_LAW_CELLS: [f64; 3] = [2.0, 3.0, 4.0];
/// Candidates above this many cells are not run (about 7 GB for the direct model).
pub const MAX_CELLS: f64 = 5.0e7;
/// The largest particle Reynolds number of the direct model's error fit (its studies ran at
/// 0.004–0.8); above it the direct prediction is not offered.
pub const DIRECT_MAX_REYNOLDS: f64 = 1.0;

/// What becomes of a candidate.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// Its predicted error is within the tolerance.
    Meets,
    /// Its predicted error is above the tolerance.
    Inaccurate,
    /// It cannot run this case: why.
    Unavailable(String),
}

/// A model on a grid, and what it is predicted to give and cost.
#[derive(Clone, Debug)]
pub struct Candidate {
    pub model: CouplingModel,
    pub cells: [usize; 3],
    /// The largest cell side, m.
    pub h: f64,
    /// The direct model's r/h (smallest particle), or the drag law's h/d (largest).
    pub resolution: f64,
    pub error: f64,
    /// The step the candidate's bounds allow, s, and the steps to the end.
    pub step: f64,
    pub steps: f64,
    /// Predicted wall time on one thread, s, and peak memory, MB.
    pub time: f64,
    pub memory_mb: f64,
    pub verdict: Verdict,
}

/// How the time step is bounded: the case's step controls and the scheme's bound factor on
/// the viscous limit `h²/(6ν)` (paper eq. 3; infinite for a scheme without one).
#[derive(Clone, Copy, Debug)]
pub struct Stepping {
    /// The largest step the case allows: `maxDeltaT` when adjustable, else `deltaT`.
    pub cap: f64,
    pub max_co: f64,
    pub viscous_factor: f64,
}

/// The cells per side for cells of about `h` over `lengths`, and the largest cell side.
fn grid(lengths: [f64; 3], h: f64) -> ([usize; 3], f64) {
    let n = lengths.map(|l| ((l / h).round() as usize).max(1));
    let side = (0..3).map(|a| lengths[a] / n[a] as f64).fold(0.0, f64::max);
    (n, side)
}

impl Candidate {
    /// The direct model at `r_over_h` cells per radius of the smallest particle.
    pub fn direct(scene: &Scene, r_over_h: f64, stepping: Stepping, tolerance: f64) -> Self {
        let (cells, h) = grid(scene.lengths, 0.5 * scene.d_min / r_over_h);
        let resolution = 0.5 * scene.d_min / h;
        let error = direct_error(resolution, scene.phi);
        let mu = scene.nu * scene.rho_fluid;
        let mut step = stepping
            .cap
            .min(stepping.viscous_factor * h * h / (6.0 * scene.nu));
        if !scene.fixed {
            let response = scene.rho_particle * scene.d_min * scene.d_min / (18.0 * mu);
            step = step.min(RESPONSE_STEP_FRACTION * response);
        }
        if scene.velocity > 0.0 {
            step = step.min(stepping.max_co * h / scene.velocity);
        }
        let count = (cells[0] * cells[1] * cells[2]) as f64;
        let steps = (scene.duration / step).ceil();
        let time = DIRECT_COST.time(
            steps,
            count,
            scene.particles as f64,
            resolution * resolution,
        );
        let verdict = if resolution < 2.0 {
            Verdict::Unavailable(format!("r/h {resolution:.2} below 2"))
        } else if scene.reynolds > DIRECT_MAX_REYNOLDS {
            Verdict::Unavailable(format!(
                "Re_p {:.0}: the error model is fitted at Re_p <= {DIRECT_MAX_REYNOLDS}",
                scene.reynolds
            ))
        } else {
            Self::judge(count, error, tolerance)
        };
        Candidate {
            model: CouplingModel::Direct,
            cells,
            h,
            resolution,
            error,
            step,
            steps,
            time,
            memory_mb: 8.0 + 140e-6 * count,
            verdict,
        }
    }

    /// The drag-law model on cells of `h_over_d` diameters of the largest particle.
    pub fn drag_law(scene: &Scene, h_over_d: f64, stepping: Stepping, tolerance: f64) -> Self {
        let (cells, h) = grid(scene.lengths, h_over_d * scene.d_max);
        let error = drag_law_error(scene.phi, scene.fixed);
        // the explicit predictor's bound, 1/(Σ|u|/h + 2ν Σ 1/h²), and the Courant number
        let mut step = stepping.cap.min(
            1.0 / (3.0 * scene.velocity / h
                + stepping.viscous_factor.recip() * 6.0 * scene.nu / (h * h)),
        );
        if scene.velocity > 0.0 {
            step = step.min(stepping.max_co * h / scene.velocity);
        }
        let count = (cells[0] * cells[1] * cells[2]) as f64;
        let steps = (scene.duration / step).ceil();
        let time = DRAG_LAW_COST.time(steps, count, scene.particles as f64, 1.0);
        let resolution = h / scene.d_max;
        let verdict = if scene.d_max > 2.0 * h {
            Verdict::Unavailable("particles larger than two cells".into())
        } else {
            Self::judge(count, error, tolerance)
        };
        Candidate {
            model: CouplingModel::DragLaw,
            cells,
            h,
            resolution,
            error,
            step,
            steps,
            time,
            memory_mb: 9.0 + 1e-6 * (200.0 * count + 400.0 * scene.particles as f64),
            verdict,
        }
    }

    fn judge(cells: f64, error: f64, tolerance: f64) -> Verdict {
        if cells > MAX_CELLS {
            Verdict::Unavailable(format!("{cells:.2e} cells, above {MAX_CELLS:.0e}"))
        } else if error <= tolerance {
            Verdict::Meets
        } else {
            Verdict::Inaccurate
        }
    }

    /// `direct r/h 4.0` or `dragLaw h/d 2.0`.
    pub fn label(&self) -> String {
        match self.model {
            CouplingModel::Direct => format!("direct, r/h {:.1}", self.resolution),
            _ => format!("dragLaw, h/d {:.1}", self.resolution),
        }
    }
}
