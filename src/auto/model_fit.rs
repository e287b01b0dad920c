//! The error and cost models of `model auto`, fitted by `tools/fit_auto_model.py` to the
//! studies of docs/figures (2026-12-05; the fit's scatter is in
//! docs/user-guide/choosing-a-model.md). Each is a rule of thumb with a stated validity, not
//! a bound.

/// Direct model: the relative error of a particle's force or settling velocity,
/// `e = A (h/r)^p (1 + (G/g)^q)`, `g` the gap between neighbours in cells at the mean
/// spacing of a simple cubic array of the same φ. Fitted to the settling sphere and the
/// porous K at φ = 0.01–0.45, r/h ≥ 2.9 (58 points: 81 % within a factor 2).
const DIRECT_A: f64 = 0.3265;
const DIRECT_P: f64 = 2.284;
const DIRECT_G: f64 = 2.05;
const DIRECT_Q: f64 = 2.6;

/// The gap between neighbours, in cells, at the mean spacing `d (π/(6φ))^⅓` of solid
/// fraction `phi` (infinite without particles).
pub fn gap_cells(phi: f64, r_over_h: f64) -> f64 {
    if phi <= 0.0 {
        return f64::INFINITY;
    }
    ((std::f64::consts::PI / (6.0 * phi)).cbrt() - 1.0) * 2.0 * r_over_h
}

/// The direct model's predicted relative error at `r_over_h` cells per radius and solid
/// fraction `phi`.
pub fn direct_error(r_over_h: f64, phi: f64) -> f64 {
    let g = gap_cells(phi, r_over_h);
    let crowding = if g > 0.0 {
        1.0 + (DIRECT_G / g).powf(DIRECT_Q)
    } else {
        f64::INFINITY
    };
    DIRECT_A * r_over_h.powf(-DIRECT_P) * crowding
}

/// Drag-law model, fixed arrays: `|K/K_exact − 1|` of the paper's closure on a grid of about
/// 2r against Zick & Homsy's exact K of the simple cubic array (Fig. 2's drag-law study).
const DRAG_FIXED: [(f64, f64); 10] = [
    (0.05, 0.492),
    (0.10, 0.549),
    (0.15, 0.570),
    (0.20, 0.518),
    (0.25, 0.454),
    (0.30, 0.395),
    (0.35, 0.337),
    (0.40, 0.273),
    (0.45, 0.198),
    (0.50, 0.099),
];

/// Drag-law model, free suspensions: `|v/v_exact − 1|` of the mean settling velocity on a
/// grid of 2.2 d against the random hard-sphere suspension (Fig. 3's drag-law study).
const DRAG_FREE: [(f64, f64); 6] = [
    (0.049, 0.214),
    (0.101, 0.260),
    (0.150, 0.334),
    (0.200, 0.272),
    (0.249, 0.162),
    (0.300, 0.091),
];

/// The drag-law model's predicted relative error at solid fraction `phi`, for fixed or free
/// particles: the table's linear interpolation, its end values beyond it.
pub fn drag_law_error(phi: f64, fixed: bool) -> f64 {
    let table: &[(f64, f64)] = if fixed { &DRAG_FIXED } else { &DRAG_FREE };
    let (first, last) = (table[0], table[table.len() - 1]);
    if phi <= first.0 {
        return first.1;
    }
    if phi >= last.0 {
        return last.1;
    }
    for w in table.windows(2) {
        let ((x0, y0), (x1, y1)) = (w[0], w[1]);
        if phi <= x1 {
            return y0 + (y1 - y0) * (phi - x0) / (x1 - x0);
        }
    }
    last.1
}

/// Wall time on one thread, `t0 + steps (c + a cells + b particles (r/h)²)` for the direct
/// model (86 runs, 99 % within a factor 2) and `t0 + steps (a cells + b particles)` for the
/// drag law (68 runs, 91 %), s.
pub struct CostModel {
    pub start: f64,
    pub per_step: f64,
    pub per_cell_step: f64,
    pub per_particle_step: f64,
}

pub const DIRECT_COST: CostModel = CostModel {
    start: 0.164,
    per_step: 719.4e-6,
    per_cell_step: 160.4e-9,
    per_particle_step: 54.2e-6,
};

pub const DRAG_LAW_COST: CostModel = CostModel {
    start: 0.501,
    per_step: 0.0,
    per_cell_step: 882e-9,
    per_particle_step: 2724e-9,
};

impl CostModel {
    /// Predicted wall time (s) on one thread; `weight` multiplies the particle term (the
    /// direct model's (r/h)²).
    pub fn time(&self, steps: f64, cells: f64, particles: f64, weight: f64) -> f64 {
        self.start
            + steps
                * (self.per_step
                    + self.per_cell_step * cells
                    + self.per_particle_step * particles * weight)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_error_models_reproduce_their_data() {
        // the settling sphere at r/h = 8 (phi 0.046) was 0.32 %, at 4: 2.08 %
        assert!((direct_error(8.0, 0.046) / 0.0032 - 1.0).abs() < 1.0);
        assert!((direct_error(4.0, 0.046) / 0.0208 - 1.0).abs() < 1.0);
        // crowding: phi = 0.45 at r/h 4 (gap 0.44 cells) was 32 %
        assert!(direct_error(4.28, 0.45) > 0.1);
        assert!(direct_error(4.0, 0.0).is_finite());
        // the tables: their points, and between them
        assert_eq!(drag_law_error(0.45, true), 0.198);
        assert!((drag_law_error(0.125, true) - 0.5595).abs() < 1e-12);
        assert_eq!(drag_law_error(0.6, true), 0.099);
        assert_eq!(drag_law_error(0.01, false), 0.214);
    }
}
