//! Time schemes: low-storage (Williamson 1980) Runge–Kutta with one projection per stage.
//!
//! Euler and RK3 are written in the two-register form
//! `q ← a_s q + Δt F(u)`, `u ← P(u + b_s q)` (stage `s`, projection `P`), so they
//! share one code path and need no storage beyond `u` and `q`. Because the projection
//! is linear and idempotent, projecting each stage equals the Runge–Kutta scheme applied to
//! the projected equations `du/dt = P F(u)`: velocity is of the scheme's order.

/// The time scheme of the momentum equation, selected by name in a case
/// (`system/fvSolution`: `fsim { timeScheme …; }`).
///
/// Default: [`TimeScheme::RK3`]. Explicit Euler with central advection is stable only below
/// `2ν/|v|²` (paper eq. 3), which collapses at high cell Reynolds number; RK3 is stable up to a
/// Courant number near √3 whatever the viscosity, and third order in time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TimeScheme {
    /// Explicit Euler, first order: the paper's scheme. Name `Euler`.
    Euler,
    /// Williamson's three-stage low-storage scheme, third order. Name `RK3`.
    #[default]
    RK3,
    /// Explicit throughout, one projection per step: advection and forces by explicit Euler
    /// (frozen over the step), diffusion by the damped first-order Runge–Kutta–Chebyshev
    /// method with as many stages `s` as the step needs (reach `0.9 β(s)`, `β ≈ 1.53 s²`,
    /// ≥ `Δt λ_max`; [`super::ChebyshevStages`]). Each stage costs one Laplacian, and a hook
    /// constrains each stage's faces as it does an explicit stage. First order; stable while
    /// `Δt ≤ 2ν/|v|²` and while `s` stays at most [`super::ChebyshevStages::MAX_STAGES`]: no
    /// `h²/ν` limit, which pays on grids finer than the particles. The pressure is
    /// incremental, so a steady state does not depend on `Δt`. Not with outlets. Name
    /// `EulerRKC`.
    EulerRKC,
}

/// Williamson's RK3 coefficients (Williamson, J. Comput. Phys. 35, 48–56, 1980).
const RK3_STAGES: [(f64, f64, f64); 3] = [
    (0.0, 1.0 / 3.0, 1.0 / 3.0),
    (-5.0 / 9.0, 15.0 / 16.0, 3.0 / 4.0),
    (-153.0 / 128.0, 8.0 / 15.0, 1.0),
];
const EULER_STAGES: [(f64, f64, f64); 1] = [(0.0, 1.0, 1.0)];

impl TimeScheme {
    /// Every scheme, in the order the docs list them.
    pub const ALL: [TimeScheme; 3] = [TimeScheme::Euler, TimeScheme::RK3, TimeScheme::EulerRKC];

    /// The scheme a case names (exactly, as OpenFOAM matches its scheme names).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }

    pub fn name(&self) -> &'static str {
        match self {
            TimeScheme::Euler => "Euler",
            TimeScheme::RK3 => "RK3",
            TimeScheme::EulerRKC => "EulerRKC",
        }
    }

    /// Order of accuracy of the velocity in time.
    pub fn order(&self) -> usize {
        match self {
            TimeScheme::EulerRKC => 1,
            _ => self.stages().len(),
        }
    }

    /// True for `EulerRKC`: Chebyshev stages of the diffusion, one projection per step.
    pub fn is_chebyshev(&self) -> bool {
        matches!(self, TimeScheme::EulerRKC)
    }

    /// Projections per step (one pressure each).
    pub(crate) fn projections(&self) -> usize {
        if self.is_chebyshev() {
            1
        } else {
            self.stages().len()
        }
    }

    /// The share of stage `s`'s pressure in the step's pressure impulse on the velocity:
    /// `u^{n+1}` holds `−Δt Σ_s w_s ∇p_s`, `Σ_s w_s = 1`. The two-register schemes, whose
    /// register carries `−Δt ∇p_s` into the later stages: `w_s = Σ_{j≥s} b_j Π_{k=s+1..j} a_k`
    /// (RK3: 1/6, 3/10, 8/15). `EulerRKC`: one projection.
    pub(crate) fn stage_pressure_weight(&self, s: usize) -> f64 {
        if self.is_chebyshev() {
            return 1.0;
        }
        let stages = self.stages();
        let mut weight = 0.0;
        let mut carried = 1.0;
        for (j, &(a, b, _)) in stages.iter().enumerate().skip(s) {
            if j > s {
                carried *= a;
            }
            weight += b * carried;
        }
        weight
    }

    /// Stage coefficients `(a_s, b_s, c_s)`: `q ← a_s q + Δt F`, `u ← u + b_s q`, and `c_s`
    /// the fraction of the step reached at the end of the stage.
    pub fn stages(&self) -> &'static [(f64, f64, f64)] {
        match self {
            TimeScheme::Euler | TimeScheme::EulerRKC => &EULER_STAGES,
            TimeScheme::RK3 => &RK3_STAGES,
        }
    }

    /// Largest stable `Δt` for viscosity `nu`, cell sizes `h` (directions with `active[d]`
    /// false, i.e. `Empty`, are ignored) and the largest speed of each component.
    ///
    /// Euler: paper eq. 3 generalised to anisotropic cells,
    /// `min(1 / (2ν Σ 1/h_d²), 2ν / |v|²_max)`, which is `min(h²/(6ν), 2ν/|v|²)` for cubes.
    /// RK3: its stability region reaches −2.51 on the real axis and ±√3 on the imaginary
    /// axis, so `min(2.51 / (4ν Σ 1/h_d²), √3 / Σ |v_d|_max / h_d)`.
    /// EulerRKC: Euler's advective part `2ν / |v|²_max`, and the reach of its largest stage
    /// count on the diffusion's spectrum `[−4ν Σ 1/h_d², 0]`.
    pub fn stability_bound(
        &self,
        nu: f64,
        h: [f64; 3],
        active: [bool; 3],
        max_speed: [f64; 3],
    ) -> f64 {
        let mut inv_h2 = 0.0;
        let mut speed_over_h = 0.0;
        let mut speed2 = 0.0;
        for d in 0..3 {
            if active[d] {
                inv_h2 += 1.0 / (h[d] * h[d]);
                speed_over_h += max_speed[d] / h[d];
            }
            speed2 += max_speed[d] * max_speed[d];
        }
        let div = |a: f64, b: f64| if b > 0.0 { a / b } else { f64::INFINITY };
        match self {
            TimeScheme::Euler => div(1.0, 2.0 * nu * inv_h2).min(div(2.0 * nu, speed2)),
            TimeScheme::RK3 => div(2.51, 4.0 * nu * inv_h2).min(div(3f64.sqrt(), speed_over_h)),
            TimeScheme::EulerRKC => div(2.0 * nu, speed2).min(div(
                super::ChebyshevStages::reach(super::ChebyshevStages::MAX_STAGES),
                4.0 * nu * inv_h2,
            )),
        }
    }

    /// The bound [`Self::stability_bound`] applies, in words, for messages.
    pub fn bound_description(&self) -> String {
        match self {
            TimeScheme::Euler => "paper eq. 3: min(h^2/(6 nu), 2 nu/|v|^2)".to_string(),
            TimeScheme::RK3 => "min(2.51 h^2/(12 nu), sqrt(3) / sum |v_d|/h_d)".to_string(),
            TimeScheme::EulerRKC => format!(
                "advective: 2 nu/|v|^2; diffusive: the reach of {} Chebyshev stages",
                super::ChebyshevStages::MAX_STAGES
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stage_weights_are_consistent() {
        // Expanding the two-register form, each scheme's weights of the stage tendencies must
        // sum to one (consistency), and the c_s must match the stage times.
        for scheme in TimeScheme::ALL {
            let st = scheme.stages();
            let total: f64 = (0..scheme.projections())
                .map(|m| scheme.stage_pressure_weight(m))
                .sum();
            assert!((total - 1.0).abs() < 1e-14, "{scheme:?}: {total}");
            assert_eq!(st.last().unwrap().2, 1.0);
            assert_eq!(TimeScheme::from_name(scheme.name()), Some(scheme));
        }
        let rk3 = [0, 1, 2].map(|m| TimeScheme::RK3.stage_pressure_weight(m));
        for (w, exact) in rk3.iter().zip([1.0 / 6.0, 3.0 / 10.0, 8.0 / 15.0]) {
            assert!((w - exact).abs() < 1e-15, "RK3 pressure weights {rk3:?}");
        }
        assert_eq!(TimeScheme::EulerRKC.order(), 1);
        assert!(TimeScheme::EulerRKC.is_chebyshev());
        assert_eq!(TimeScheme::default(), TimeScheme::RK3);
        // names are exact, as OpenFOAM's
        assert_eq!(TimeScheme::from_name("rk3"), None);
        assert_eq!(TimeScheme::from_name("backward"), None);
    }

    #[test]
    fn euler_bound_is_paper_eq_3_on_cubes() {
        let h = 0.01;
        let nu = 1e-3;
        let v = 0.5;
        let b = TimeScheme::Euler.stability_bound(nu, [h; 3], [true; 3], [v, 0.0, 0.0]);
        let paper = (h * h / (6.0 * nu)).min(2.0 * nu / (v * v));
        assert!((b - paper).abs() < 1e-15 * paper);
    }
}
