//! Time schemes: low-storage (Williamson 1980) Runge–Kutta with one projection per stage.
//!
//! Every scheme is written in the two-register form
//! `q ← a_s q + Δt F(u)`, `u ← P(u + b_s q)` (stage `s`, projection `P`), so Euler, RK2 and
//! RK3 share one code path and need no storage beyond `u` and `q`. Because the projection
//! is linear and idempotent, projecting each stage equals the Runge–Kutta scheme applied to
//! the projected equations `du/dt = P F(u)`: velocity is of the scheme's order.

/// The time scheme of the momentum equation, selected by name in a case.
///
/// Default: [`TimeScheme::RK3`]. Explicit Euler with central advection is stable only below
/// `2ν/|v|²` (paper eq. 3), which collapses at high cell Reynolds number; RK3 is stable up to a
/// Courant number near √3 whatever the viscosity, and third order in time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TimeScheme {
    /// Explicit Euler, first order: the paper's scheme. Name `Euler`.
    Euler,
    /// Heun's two-stage scheme, second order. Name `RK2`.
    RK2,
    /// Williamson's three-stage low-storage scheme, third order. Name `RK3`.
    #[default]
    RK3,
    /// Semi-implicit: advection and forces by low-storage RK3, diffusion by Crank–Nicolson
    /// per stage (Spalart, Moser & Rogers, J. Comput. Phys. 96, 297–324, 1991), the viscous
    /// Helmholtz problems solved exactly by FFT/DCT/DST. Second order; no viscous time-step
    /// limit, which pays on grids finer than the particles. Not with outlets. Name `RK3CN`.
    RK3CN,
    /// Semi-implicit, one stage: advection and forces by explicit Euler, diffusion by
    /// Crank–Nicolson, `(I − ½Δt ν∇²) u* = u + Δt (N(u) + ½ ν∇²u) − Δt ∇p`; first order (the
    /// paper's Euler with the viscous part implicit). A third of `RK3CN`'s solves per step.
    /// Stable while `Δt ≤ 2ν/|v|²` (the advective half of paper eq. 3: explicit Euler with
    /// central advection is held by the viscosity, implicit or not); no `h²/ν` limit.
    /// Not with outlets. Name `EulerCN`.
    EulerCN,
    /// Explicit throughout, one projection per step: advection and forces by explicit Euler
    /// (frozen over the step), diffusion by the damped first-order Runge–Kutta–Chebyshev
    /// method with as many stages `s` as the step needs (reach `0.9 β(s)`, `β ≈ 1.53 s²`, ≥ `Δt λ_max`;
    /// [`super::ChebyshevStages`]). Each stage costs one Laplacian instead of a Helmholtz
    /// solve, and a hook constrains each stage's faces as it does an explicit stage. First
    /// order; stable while `Δt ≤ 2ν/|v|²` like `EulerCN`, and while `s` stays at most
    /// [`super::ChebyshevStages::MAX_STAGES`]. The pressure is incremental, so a steady state
    /// does not depend on `Δt`. Not with outlets. Name `EulerRKC`.
    EulerRKC,
}

/// Spalart–Moser–Rogers stage coefficients `(γ_s, ζ_s, α_s = β_s)`:
/// `(I − β_s Δt ν∇²) u* = u + Δt (γ_s N(u) + ζ_s N_old + α_s ν∇²u)`, projection weight
/// `(α_s + β_s) Δt`.
pub(crate) const SMR_STAGES: [(f64, f64, f64); 3] = [
    (8.0 / 15.0, 0.0, 4.0 / 15.0),
    (5.0 / 12.0, -17.0 / 60.0, 1.0 / 15.0),
    (3.0 / 4.0, -5.0 / 12.0, 1.0 / 6.0),
];

/// `EulerCN` in the same form: one stage `(γ, ζ, α = β) = (1, 0, ½)`.
pub(crate) const EULER_CN_STAGES: [(f64, f64, f64); 1] = [(1.0, 0.0, 0.5)];

/// Williamson's RK3 coefficients (Williamson, J. Comput. Phys. 35, 48–56, 1980).
const RK3_STAGES: [(f64, f64, f64); 3] = [
    (0.0, 1.0 / 3.0, 1.0 / 3.0),
    (-5.0 / 9.0, 15.0 / 16.0, 3.0 / 4.0),
    (-153.0 / 128.0, 8.0 / 15.0, 1.0),
];
/// Heun: `u₁ = u + Δt F₀`, `u₂ = u₁ + ½(−Δt F₀ + Δt F₁)`.
const RK2_STAGES: [(f64, f64, f64); 2] = [(0.0, 1.0, 1.0), (-1.0, 0.5, 1.0)];
const EULER_STAGES: [(f64, f64, f64); 1] = [(0.0, 1.0, 1.0)];

impl TimeScheme {
    /// Parses a scheme name as a case spells it (`Euler`, `RK2`, `RK3`; case-insensitive).
    pub fn from_name(name: &str) -> Option<Self> {
        match name.to_ascii_lowercase().as_str() {
            "euler" => Some(TimeScheme::Euler),
            "rk2" | "heun" => Some(TimeScheme::RK2),
            "rk3" => Some(TimeScheme::RK3),
            "rk3cn" | "cranknicolson" => Some(TimeScheme::RK3CN),
            "eulercn" => Some(TimeScheme::EulerCN),
            "eulerrkc" => Some(TimeScheme::EulerRKC),
            _ => None,
        }
    }

    pub fn name(&self) -> &'static str {
        match self {
            TimeScheme::Euler => "Euler",
            TimeScheme::RK2 => "RK2",
            TimeScheme::RK3 => "RK3",
            TimeScheme::RK3CN => "RK3CN",
            TimeScheme::EulerCN => "EulerCN",
            TimeScheme::EulerRKC => "EulerRKC",
        }
    }

    /// Order of accuracy of the velocity in time.
    pub fn order(&self) -> usize {
        match self {
            TimeScheme::RK3CN => 2,
            TimeScheme::EulerRKC => 1,
            _ => self.stages().len(),
        }
    }

    /// True when diffusion is implicit (no viscous limit on Δt).
    pub fn is_semi_implicit(&self) -> bool {
        matches!(self, TimeScheme::RK3CN | TimeScheme::EulerCN)
    }

    /// True for `EulerRKC`: Chebyshev stages of the diffusion, one projection per step.
    pub fn is_chebyshev(&self) -> bool {
        matches!(self, TimeScheme::EulerRKC)
    }

    /// Whether a step keeps a tendency field between its stages (`q` of the explicit
    /// schemes, `N_old` of `RK3CN`, the frozen `N` of `EulerRKC`); `EulerCN`'s single stage
    /// does not.
    pub(crate) fn keeps_tendency(&self) -> bool {
        !matches!(self, TimeScheme::EulerCN)
    }

    /// Stage coefficients `(γ_s, ζ_s, α_s = β_s)` of a semi-implicit scheme (empty for the
    /// explicit ones): `(I − β_s Δt ν∇²) u* = u + Δt (γ_s N(u) + ζ_s N_old + α_s ν∇²u)`.
    pub(crate) fn semi_implicit_stages(&self) -> &'static [(f64, f64, f64)] {
        match self {
            TimeScheme::RK3CN => &SMR_STAGES,
            TimeScheme::EulerCN => &EULER_CN_STAGES,
            _ => &[],
        }
    }

    /// Projections per step (one pressure each).
    pub(crate) fn projections(&self) -> usize {
        if self.is_semi_implicit() {
            self.semi_implicit_stages().len()
        } else if self.is_chebyshev() {
            1
        } else {
            self.stages().len()
        }
    }

    /// The share of stage `s`'s pressure in the step's pressure impulse on the velocity:
    /// `u^{n+1}` holds `−Δt Σ_s w_s ∇p_s`, `Σ_s w_s = 1`. Semi-implicit schemes: `w_s = 2α_s`
    /// (the stage's predictor and increment act over `τ_s = 2α_s Δt`). Explicit two-register
    /// schemes, whose register carries `−Δt ∇p_s` into the later stages:
    /// `w_s = Σ_{j≥s} b_j Π_{k=s+1..j} a_k` (RK3: 1/6, 3/10, 8/15). `EulerRKC`: one projection.
    pub(crate) fn stage_pressure_weight(&self, s: usize) -> f64 {
        if self.is_semi_implicit() {
            return 2.0 * self.semi_implicit_stages()[s].2;
        }
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
    /// the fraction of the step reached at the end of the stage. For `RK3CN` the explicit
    /// part's stage times are those of RK3 (its coefficients are in `SMR_STAGES`).
    pub fn stages(&self) -> &'static [(f64, f64, f64)] {
        match self {
            TimeScheme::Euler | TimeScheme::EulerCN | TimeScheme::EulerRKC => &EULER_STAGES,
            TimeScheme::RK2 => &RK2_STAGES,
            TimeScheme::RK3 | TimeScheme::RK3CN => &RK3_STAGES,
        }
    }

    /// Largest stable `Δt` for viscosity `nu`, cell sizes `h` (directions with `active[d]`
    /// false, i.e. `Empty`, are ignored) and the largest speed of each component.
    ///
    /// Euler and RK2: paper eq. 3 generalised to anisotropic cells,
    /// `min(1 / (2ν Σ 1/h_d²), 2ν / |v|²_max)`, which is `min(h²/(6ν), 2ν/|v|²)` for cubes.
    /// RK3: its stability region reaches −2.51 on the real axis and ±√3 on the imaginary
    /// axis, so `min(2.51 / (4ν Σ 1/h_d²), √3 / Σ |v_d|_max / h_d)`.
    /// RK3CN: the advective part only, `√3 / Σ |v_d|_max / h_d`.
    /// EulerCN: the advective part of Euler's, `2ν / |v|²_max`.
    /// EulerRKC: that, and the reach of its largest stage count on the diffusion's
    /// spectrum `[−4ν Σ 1/h_d², 0]`.
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
            TimeScheme::Euler | TimeScheme::RK2 => {
                div(1.0, 2.0 * nu * inv_h2).min(div(2.0 * nu, speed2))
            }
            TimeScheme::RK3 => div(2.51, 4.0 * nu * inv_h2).min(div(3f64.sqrt(), speed_over_h)),
            TimeScheme::RK3CN => div(3f64.sqrt(), speed_over_h),
            TimeScheme::EulerCN => div(2.0 * nu, speed2),
            TimeScheme::EulerRKC => div(2.0 * nu, speed2).min(div(
                super::ChebyshevStages::reach(super::ChebyshevStages::MAX_STAGES),
                4.0 * nu * inv_h2,
            )),
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
        let smr: f64 = SMR_STAGES.iter().map(|s| s.0 + s.1).sum();
        let smr_visc: f64 = SMR_STAGES.iter().map(|s| 2.0 * s.2).sum();
        assert!((smr - 1.0).abs() < 1e-14 && (smr_visc - 1.0).abs() < 1e-14);
        let [(g, z, a)] = EULER_CN_STAGES;
        assert!(g + z == 1.0 && 2.0 * a == 1.0);
        assert_eq!(TimeScheme::from_name("EulerCN"), Some(TimeScheme::EulerCN));
        assert_eq!(TimeScheme::EulerCN.order(), 1);
        assert_eq!(
            TimeScheme::from_name("EulerRKC"),
            Some(TimeScheme::EulerRKC)
        );
        assert_eq!(TimeScheme::EulerRKC.order(), 1);
        assert!(TimeScheme::EulerRKC.is_chebyshev() && !TimeScheme::EulerRKC.is_semi_implicit());
        assert_eq!(
            TimeScheme::from_name("CrankNicolson"),
            Some(TimeScheme::RK3CN)
        );
        for scheme in [TimeScheme::Euler, TimeScheme::RK2, TimeScheme::RK3] {
            let st = scheme.stages();
            // weight of F_m in the final u: Σ_{s≥m} b_s Π_{r=m+1..s} a_r
            let total: f64 = (0..st.len()).map(|m| scheme.stage_pressure_weight(m)).sum();
            assert!((total - 1.0).abs() < 1e-14, "{scheme:?}: {total}");
            assert_eq!(st.last().unwrap().2, 1.0);
            assert_eq!(TimeScheme::from_name(scheme.name()), Some(scheme));
        }
        let rk3 = [0, 1, 2].map(|m| TimeScheme::RK3.stage_pressure_weight(m));
        for (w, exact) in rk3.iter().zip([1.0 / 6.0, 3.0 / 10.0, 8.0 / 15.0]) {
            assert!((w - exact).abs() < 1e-15, "RK3 pressure weights {rk3:?}");
        }
        let rk3cn: f64 = (0..3)
            .map(|m| TimeScheme::RK3CN.stage_pressure_weight(m))
            .sum();
        assert!((rk3cn - 1.0).abs() < 1e-14);
        assert_eq!(TimeScheme::EulerCN.stage_pressure_weight(0), 1.0);
        assert_eq!(TimeScheme::default(), TimeScheme::RK3);
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
