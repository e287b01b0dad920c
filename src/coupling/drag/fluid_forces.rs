//! DPMFoam's particle forces besides drag and gravity (OpenFOAM v1912 `particleForces`), their
//! coefficients and how DPMFoam splits them.
//!
//! On a particle of mass `m`, density `ρ_p`, volume `V = m/ρ_p`, in a fluid of density `ρ_c`:
//! - `pressureGradient`: `F = m (ρ_c/ρ_p) DU_c/Dt`, the fluid's material acceleration
//!   `DU_c/Dt = ∂U_c/∂t + (U_c·∇)U_c` at the particle (OpenFOAM's `PressureGradientForce`);
//! - `virtualMass { Cvm …; }`: `F = Cvm m (ρ_c/ρ_p) DU_c/Dt` explicit, and the added mass
//!   `Cvm m ρ_c/ρ_p` in the particle's inertia (`massAdd`): together
//!   `Cvm m (ρ_c/ρ_p) (DU_c/Dt − dv/dt)` (`VirtualMassForce`);
//! - lift: `F = V ρ_c C_l ((U_c − v) × ω)`, `ω = ∇ × U_c` (`LiftForce`), `C_l` from
//!   Saffman (1965) and Mei (1992) ([`saffman_mei_cl`]) or Tomiyama et al. (2002)
//!   ([`tomiyama_cl`]).
//!
//! All three are DPMFoam's *coupled explicit* sources (`calcCoupled`'s `Su`): they enter the
//! particle's balance with the drag held implicit, and their negative goes to the fluid's
//! explicit source. Gravity is non-coupled (not returned to the fluid). The particle's
//! velocity integrates `(m + m_add) dv/dt = β (U_c − v) + F_coupled + m (1 − ρ_c/ρ_p) g`;
//! contact forces move it through `m` alone (`CollidingParcel::move` divides them by
//! `mass()`, not by the effective mass).

use std::f64::consts::PI;

/// OpenFOAM's `ROOTVSMALL` for doubles, added where its formulas add it.
const ROOT_VSMALL: f64 = 1e-150;

/// The lift coefficient model (`SaffmanMeiLiftForce` or `TomiyamaLift`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LiftModel {
    /// Saffman (1965) with Mei's (1992) correction for finite Reynolds numbers.
    SaffmanMei,
    /// Tomiyama, Tamai, Zun & Hosokawa (2002), for bubbles and drops of surface tension
    /// `sigma` (N/m).
    Tomiyama { sigma: f64 },
}

impl LiftModel {
    /// DPMFoam's name in `particleForces`.
    pub fn name(self) -> &'static str {
        match self {
            LiftModel::SaffmanMei => "SaffmanMeiLiftForce",
            LiftModel::Tomiyama { .. } => "TomiyamaLift",
        }
    }
}

/// DPMFoam's forces besides drag and gravity, as the case lists them.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FluidForces {
    /// DPMFoam's `pressureGradient` (`m ρ_c/ρ_p DU_c/Dt`; DPMFoam's form only: the paper's
    /// form gives every particle `−V ∇p` instead).
    pub pressure_gradient: bool,
    /// `virtualMass`'s `Cvm`.
    pub virtual_mass: Option<f64>,
    /// The lift force, if any.
    pub lift: Option<LiftModel>,
    /// `interpolationSchemes { DUcDt cellPoint; }` (else `cell`).
    pub acceleration_cell_point: bool,
    /// `interpolationSchemes { curlUcDt cellPoint; }` (else `cell`; DPMFoam's field name).
    pub curl_cell_point: bool,
}

impl FluidForces {
    /// Whether a force reads `DU_c/Dt`.
    pub fn needs_acceleration(&self) -> bool {
        self.pressure_gradient || self.virtual_mass.is_some()
    }

    /// Whether a force reads `∇ × U_c`.
    pub fn needs_curl(&self) -> bool {
        self.lift.is_some()
    }

    /// The factor `k` of the explicit force `k m (ρ_c/ρ_p) DU_c/Dt`: 1 for `pressureGradient`
    /// plus `Cvm` for `virtualMass` (DPMFoam adds the two forces when both are listed).
    pub fn acceleration_factor(&self) -> f64 {
        f64::from(u8::from(self.pressure_gradient)) + self.virtual_mass.unwrap_or(0.0)
    }

    /// The added mass over the particle's mass, `Cvm ρ_c/ρ_p` (`massEff = m (1 + this)`).
    pub fn added_mass_ratio(&self, rho_c: f64, rho_p: f64) -> f64 {
        self.virtual_mass.map_or(0.0, |cvm| cvm * rho_c / rho_p)
    }

    /// The explicit force on one particle of mass `m`, density `rho_p`, diameter `d` and
    /// velocity `v`, in fluid of density `rho_c` and viscosity `mu` moving at `u` with
    /// acceleration `du_dt` and vorticity `curl`, under the case's gravity `g` (for
    /// Tomiyama's Eötvös number): `k m (ρ_c/ρ_p) DU_c/Dt + V ρ_c C_l ((u − v) × ω)`.
    #[allow(clippy::too_many_arguments)]
    pub fn explicit_force(
        &self,
        m: f64,
        rho_p: f64,
        d: f64,
        v: [f64; 3],
        rho_c: f64,
        mu: f64,
        u: [f64; 3],
        du_dt: [f64; 3],
        curl: [f64; 3],
        g: [f64; 3],
    ) -> [f64; 3] {
        let k = self.acceleration_factor() * m * rho_c / rho_p;
        let mut f = [k * du_dt[0], k * du_dt[1], k * du_dt[2]];
        if let Some(lift) = self.lift {
            let s = [u[0] - v[0], u[1] - v[1], u[2] - v[2]];
            let slip = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
            let re = rho_c * slip * d / mu;
            let cl = match lift {
                LiftModel::SaffmanMei => {
                    let w = (curl[0] * curl[0] + curl[1] * curl[1] + curl[2] * curl[2]).sqrt();
                    saffman_mei_cl(re, rho_c * w * d * d / mu)
                }
                LiftModel::Tomiyama { sigma } => {
                    tomiyama_cl(re, eotvos(g, rho_p, rho_c, v, d, sigma))
                }
            };
            let c = m / rho_p * rho_c * cl;
            f[0] += c * (s[1] * curl[2] - s[2] * curl[1]);
            f[1] += c * (s[2] * curl[0] - s[0] * curl[2]);
            f[2] += c * (s[0] * curl[1] - s[1] * curl[0]);
        }
        f
    }
}

/// Saffman–Mei lift coefficient (OpenFOAM's `SaffmanMeiLiftForce::Cl`) of the particle
/// Reynolds number `re` and the shear one `rew = ρ_c |ω| d²/μ`: `β = Re_ω/(2 Re)`,
/// `α = 0.3314 √β`, `f = (1 − α) e^(−0.1 Re) + α`; `C_ld = 6.46 f` (Re < 40) or
/// `6.46 · 0.0524 √(β Re)`; `C_l = 3 C_ld/(2π √Re_ω)` (Saffman 1965, J. Fluid Mech. 22,
/// 385–400; Mei 1992, Int. J. Multiphase Flow 18, 145–147). With `F = V ρ_c C_l (slip × ω)` it is
/// Saffman's `1.615 μ d |slip| √Re_ω` times Mei's `f`.
pub fn saffman_mei_cl(re: f64, rew: f64) -> f64 {
    let beta = 0.5 * rew / (re + ROOT_VSMALL);
    let alpha = 0.3314 * beta.sqrt();
    let cld = if re < 40.0 {
        // (1 − α) e^(−0.1 Re) + α, written so that a vanishing Re does not cancel 1/Re's α
        let e = (-0.1 * re).exp();
        6.46 * (e - alpha * (-0.1 * re).exp_m1())
    } else {
        6.46 * 0.0524 * (beta * re).sqrt()
    };
    3.0 / (2.0 * PI * (rew + ROOT_VSMALL).sqrt()) * cld
}

/// The Eötvös number OpenFOAM's `KinematicParcel::Eo` gives a particle of velocity `v`:
/// `|g · v̂| |ρ_p − ρ_c| d²/σ` (`v̂ = v/|v|`, zero for a particle at rest).
pub fn eotvos(g: [f64; 3], rho_p: f64, rho_c: f64, v: [f64; 3], d: f64, sigma: f64) -> f64 {
    let speed = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
        .sqrt()
        .max(ROOT_VSMALL);
    let g_along = (g[0] * v[0] + g[1] * v[1] + g[2] * v[2]) / speed;
    g_along.abs() * (rho_p - rho_c).abs() * d * d / sigma.max(ROOT_VSMALL)
}

/// Tomiyama et al. (2002), Chem. Eng. Sci. 57, 1849–1858, as OpenFOAM's `TomiyamaLiftForce::Cl`
/// of `Re` and the Eötvös number `eo` ([`eotvos`]): the modified number `Eo_d` with the
/// horizontal diameter `d_H = d ∛(1 + 0.163 Eo^0.757)` (Wellek et al. 1966),
/// `f = 0.00105 Eo_d³ − 0.0159 Eo_d² − 0.0204 Eo_d + 0.474`;
/// `C_l = min(0.288 tanh(0.121 Re), f)` for `Eo_d ≤ 4`, `f` for `4 < Eo_d ≤ 10`, −0.27 beyond
/// (OpenFOAM's bound 10 where the paper writes 10.7).
pub fn tomiyama_cl(re: f64, eo: f64) -> f64 {
    let ratio = (1.0 + 0.163 * eo.powf(0.757)).cbrt();
    let eod = eo * ratio * ratio;
    let f = 0.00105 * eod.powi(3) - 0.0159 * eod * eod - 0.0204 * eod + 0.474;
    if eod <= 4.0 {
        (0.288 * (0.121 * re).tanh()).min(f)
    } else if eod <= 10.0 {
        f
    } else {
        -0.27
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    #[test]
    fn saffman_mei_by_hand() {
        // Re = 1, Re_ω = 0.1: β = 0.05, α = 0.3314·0.2236068 = 0.0741033,
        // f = 0.9258967·e^−0.1 + 0.0741033 = 0.9118893, C_ld = 5.890805,
        // 3/(2π √0.1) = 1.5098764, C_l = 8.894387.
        assert!(close(saffman_mei_cl(1.0, 0.1), 8.894387, 1e-6));
        // Re = 50 ≥ 40, Re_ω = 10: β = 0.1, C_ld = 6.46·0.0524·√5 = 0.756918,
        // 3/(2π √10) = 0.1509876, C_l = 0.1142853.
        assert!(close(saffman_mei_cl(50.0, 10.0), 0.1142853, 1e-6));
        // Saffman's limit (Re → 0 at fixed Re_ω: f → 1): V ρ C_l |slip| |ω| = 1.615 μ d |slip| √Re_ω
        let (d, rho, mu, w, slip): (f64, f64, f64, f64, f64) = (1e-4, 1000.0, 1e-3, 10.0, 1e-9);
        let (re, rew) = (rho * slip * d / mu, rho * w * d * d / mu);
        let force = PI * d.powi(3) / 6.0 * rho * saffman_mei_cl(re, rew) * slip * w;
        let saffman = 1.615 * mu * d * slip * rew.sqrt();
        assert!(close(force, saffman, 1e-4), "{force} {saffman}");
        // no slip and no shear: finite
        assert!(saffman_mei_cl(0.0, 0.0).is_finite());
    }

    #[test]
    fn tomiyama_in_each_eotvos_range() {
        // Eo = 1: Eo_d = 1·1.051623² = 1.105910 ≤ 4, f = 0.433413; Re = 10:
        // 0.288 tanh 1.21 = 0.240964 < f.
        assert!(close(tomiyama_cl(10.0, 1.0), 0.240964, 2e-6));
        // Eo = 3: Eo_d = 3.708537 ≤ 4, f = 0.233224 < 0.288 tanh 4.84 = 0.287964 (Re = 40).
        assert!(close(tomiyama_cl(40.0, 3.0), 0.233224, 2e-6));
        // Eo = 5: Eo_d = 6.700104 in (4, 10]: f = −0.060639.
        assert!(close(tomiyama_cl(10.0, 5.0), -0.060639, 2e-5));
        // Eo = 12: Eo_d = 19.49 > 10: −0.27; Eo = 7.3: Eo_d = 10.54, past OpenFOAM's bound 10
        // (inside the paper's 10.7, where f would give −0.2779).
        assert_eq!(tomiyama_cl(10.0, 12.0), -0.27);
        assert_eq!(tomiyama_cl(10.0, 7.3), -0.27);
        // Eo along the particle's velocity: g ⟂ v gives 0; g ∥ v gives g Δρ d²/σ
        let g = [0.0, 0.0, -9.81];
        assert_eq!(eotvos(g, 1.2, 1000.0, [1.0, 0.0, 0.0], 1e-3, 0.07), 0.0);
        let eo = eotvos(g, 1.2, 1000.0, [0.0, 0.0, 0.3], 1e-3, 0.07);
        assert!(close(eo, 9.81 * 998.8 * 1e-6 / 0.07, 1e-12));
        assert_eq!(eotvos(g, 1.2, 1000.0, [0.0; 3], 1e-3, 0.07), 0.0);
    }

    #[test]
    fn explicit_force_adds_pressure_gradient_virtual_mass_and_lift() {
        let forces = FluidForces {
            pressure_gradient: true,
            virtual_mass: Some(0.5),
            ..FluidForces::default()
        };
        assert!(forces.needs_acceleration() && !forces.needs_curl());
        // m = 2, ρ_c/ρ_p = 0.4: (1 + 0.5)·2·0.4 = 1.2 times DU/Dt
        let f = forces.explicit_force(
            2.0,
            2500.0,
            1e-3,
            [0.0; 3],
            1000.0,
            1e-3,
            [0.0; 3],
            [1.0, -2.0, 0.5],
            [0.0; 3],
            [0.0; 3],
        );
        for (a, want) in [1.2, -2.4, 0.6].into_iter().enumerate() {
            assert!(close(f[a], want, 1e-14), "{f:?}");
        }
        assert!(close(forces.added_mass_ratio(1000.0, 2500.0), 0.2, 1e-15));
        // lift: slip (1, 0, 0), ω (0, 0, 2): slip × ω = (0, −2, 0), times V ρ_c C_l
        let lift = FluidForces {
            lift: Some(LiftModel::SaffmanMei),
            ..FluidForces::default()
        };
        let (m, rho_p, d, rho, mu) = (1e-6, 2500.0, 1e-3, 1000.0, 1e-3);
        let f = lift.explicit_force(
            m,
            rho_p,
            d,
            [0.0; 3],
            rho,
            mu,
            [1.0, 0.0, 0.0],
            [5.0; 3],
            [0.0, 0.0, 2.0],
            [0.0; 3],
        );
        let cl = saffman_mei_cl(rho * d / mu, rho * 2.0 * d * d / mu);
        assert!(close(f[1], -2.0 * m / rho_p * rho * cl, 1e-14), "{f:?}");
        assert!(f[0] == 0.0 && f[2] == 0.0, "{f:?}");
    }
}
