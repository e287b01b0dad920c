//! Contact models: their configuration (filled by a case loader) and the force kernel.
//!
//! Two families, in the forms of the two reference codes:
//!
//! * **Hertzian spring-slider-dashpot**, OpenFOAM's `pairSpringSliderDashpot` and
//!   `wallSpringSliderDashpot` (lagrangian/intermediate, `PairCollision`), as used by DPMFoam:
//!   normal force `F_n = (k_N δ^b − η_N u·n) n` with `k_N = 4/3 √R E*`,
//!   `η_N = α √(M k_N) δ^{1/4}` (Tsuji et al. 1992 damping), tangential spring
//!   `k_T = 8 √(R δ) G*`, tangential damping `η_T = η_N`, Coulomb limit `μ |F_n|`.
//!   For a pair of equal materials `E* = E / (2(1−ν²))`, `G* = E / (4(1+ν)(2−ν))`;
//!   against a wall `1/E* = (1−ν_p²)/E_p + (1−ν_w²)/E_w`,
//!   `G* = 1 / (2((2+ν_p−ν_p²)/E_p + (2+ν_w−ν_w²)/E_w))`, `R = r_p`, `M = m_p`.
//! * **Linear spring-dashpot with tangential history**, LAMMPS `pair_style gran/hooke/history`
//!   (Cundall & Strack 1979; Silbert et al. 2001, Phys. Rev. E 64, 051302):
//!   `F_n = k_n δ n − c_n (u·n) n`, `F_t = −(k_t ξ + c_t u_t)` capped at `μ |F_n|`.
//!   LAMMPS takes a damping rate `γ_n` with `c_n = M γ_n`; fsim takes the restitution
//!   coefficient `e` and sets, per pair, `c_n = 2 a √(k_n M) / √(π² + a²)` with `a = −ln e`,
//!   the exact result for a linear damped oscillator (contact time `t_c = π / ω_d`,
//!   `e = exp(−c_n t_c / 2M)`), so every pair restitutes with `e` whatever its masses.
//!   `c_t = tangential_damping_ratio · c_n` (LAMMPS' default ratio is ½).
//!
//! Normal forces are not clipped at zero (neither reference code clips), so a damped contact
//! pulls slightly just before separation.
//!
//! The tangential spring `ξ` accumulates the sliding displacement `ξ += u_t Δt`. What happens
//! when the spring exceeds the Coulomb limit is the [`TangentialRule`].

use std::f64::consts::PI;

use crate::Vec3;

/// What the tangential spring does when `|F_t|` would exceed `μ |F_n|`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum TangentialRule {
    /// Textbook Cundall–Strack slider: the force is capped at `μ|F_n|` and the spring is
    /// shortened so that spring plus dashpot give exactly the cap (LAMMPS' rule). The result
    /// converges as the step shrinks. Default, because it is physically consistent and
    /// independent of the step size.
    #[default]
    CappedSpring,
    /// OpenFOAM's `pairSpringSliderDashpot` rule: on sliding the force is `−μ|F_n| û_t` and the
    /// spring is reset to zero, so the mean friction depends on the step size. The wall model
    /// keeps its spring over the contact as the pair model does (`WallSpringSliderDashpot`
    /// finds the contact's `WallCollisionRecord` again each step). Choose it to match DPMFoam.
    DpmFoamReset,
}

/// Particle–particle model, as `pairCollisionCoeffs` would set it.
#[derive(Clone, Debug, PartialEq)]
pub enum PairModel {
    /// `pairSpringSliderDashpot`. `youngs_modulus`/`poissons_ratio` are the particle
    /// material's (`constantProperties` in DPMFoam).
    SpringSliderDashpot {
        youngs_modulus: f64,
        poissons_ratio: f64,
        alpha: f64,
        b: f64,
        mu: f64,
        collision_resolution_steps: f64,
        tangential: TangentialRule,
    },
    /// Linear spring-dashpot with history (`gran/hooke/history`).
    LinearSpringDashpot {
        kn: f64,
        restitution: f64,
        kt: f64,
        mu: f64,
        tangential_damping_ratio: f64,
        collision_resolution_steps: f64,
    },
}

/// Particle–wall model for faces with [`super::FaceCondition::Wall`].
#[derive(Clone, Debug, PartialEq)]
pub enum WallModel {
    /// No soft wall contact; then no face may be a `Wall` (use `Rebound` or `Periodic` faces).
    None,
    /// `wallSpringSliderDashpot`. `youngs_modulus`/`poissons_ratio` are the wall's;
    /// the particle's come from `particle_*`.
    SpringSliderDashpot {
        youngs_modulus: f64,
        poissons_ratio: f64,
        particle_youngs_modulus: f64,
        particle_poissons_ratio: f64,
        alpha: f64,
        b: f64,
        mu: f64,
        collision_resolution_steps: f64,
        tangential: TangentialRule,
    },
    /// A linear spring-dashpot against a wall of infinite mass and radius (LAMMPS
    /// `fix wall/gran hooke/history`).
    LinearSpringDashpot {
        kn: f64,
        restitution: f64,
        kt: f64,
        mu: f64,
        tangential_damping_ratio: f64,
        collision_resolution_steps: f64,
    },
}

impl PairModel {
    /// The Hertzian model with OpenFOAM's usual `b = 1.5` and the default tangential rule.
    pub fn hertz(
        youngs_modulus: f64,
        poissons_ratio: f64,
        alpha: f64,
        mu: f64,
        collision_resolution_steps: f64,
    ) -> Self {
        PairModel::SpringSliderDashpot {
            youngs_modulus,
            poissons_ratio,
            alpha,
            b: 1.5,
            mu,
            collision_resolution_steps,
            tangential: TangentialRule::default(),
        }
    }

    /// The linear model with LAMMPS' defaults `k_t = 2/7 k_n`, `c_t = c_n / 2`.
    pub fn linear(kn: f64, restitution: f64, mu: f64) -> Self {
        PairModel::LinearSpringDashpot {
            kn,
            restitution,
            kt: 2.0 / 7.0 * kn,
            mu,
            tangential_damping_ratio: 0.5,
            collision_resolution_steps: 50.0,
        }
    }
}

/// The force law with its material constants resolved, shared by pairs and walls.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum ContactLaw {
    Hertz {
        e_star: f64,
        g_star: f64,
        alpha: f64,
        b: f64,
        mu: f64,
        rule: TangentialRule,
    },
    Linear {
        kn: f64,
        kt: f64,
        damping: f64,
        tangential_damping_ratio: f64,
        mu: f64,
    },
}

/// OpenFOAM's `VSMALL` for doubles: below this the tangential spring counts as unloaded.
const VSMALL: f64 = 1.0e-300;

/// `c_n / √(k_n M) = 2a / √(π² + a²)`, `a = −ln e`, for the linear model.
pub(crate) fn linear_damping_factor(restitution: f64) -> f64 {
    let a = -restitution.ln();
    2.0 * a / (PI * PI + a * a).sqrt()
}

/// Contact duration of the linear model, `t_c = √((π² + a²) M / k_n)`.
pub(crate) fn linear_contact_time(kn: f64, restitution: f64, m_eff: f64) -> f64 {
    let a = -restitution.ln();
    ((PI * PI + a * a) * m_eff / kn).sqrt()
}

impl ContactLaw {
    pub(crate) fn from_pair(model: &PairModel) -> Self {
        match *model {
            PairModel::SpringSliderDashpot {
                youngs_modulus: e,
                poissons_ratio: nu,
                alpha,
                b,
                mu,
                tangential,
                ..
            } => ContactLaw::Hertz {
                e_star: e / (2.0 * (1.0 - nu * nu)),
                g_star: e / (4.0 * (1.0 + nu) * (2.0 - nu)),
                alpha,
                b,
                mu,
                rule: tangential,
            },
            PairModel::LinearSpringDashpot {
                kn,
                restitution,
                kt,
                mu,
                tangential_damping_ratio,
                ..
            } => ContactLaw::Linear {
                kn,
                kt,
                damping: linear_damping_factor(restitution),
                tangential_damping_ratio,
                mu,
            },
        }
    }

    pub(crate) fn from_wall(model: &WallModel) -> Option<Self> {
        match *model {
            WallModel::None => None,
            WallModel::SpringSliderDashpot {
                youngs_modulus: ew,
                poissons_ratio: nw,
                particle_youngs_modulus: ep,
                particle_poissons_ratio: np,
                alpha,
                b,
                mu,
                tangential,
                ..
            } => Some(ContactLaw::Hertz {
                e_star: 1.0 / ((1.0 - np * np) / ep + (1.0 - nw * nw) / ew),
                g_star: 1.0 / (2.0 * ((2.0 + np - np * np) / ep + (2.0 + nw - nw * nw) / ew)),
                alpha,
                b,
                mu,
                rule: tangential,
            }),
            WallModel::LinearSpringDashpot {
                kn,
                restitution,
                kt,
                mu,
                tangential_damping_ratio,
                ..
            } => Some(ContactLaw::Linear {
                kn,
                kt,
                damping: linear_damping_factor(restitution),
                tangential_damping_ratio,
                mu,
            }),
        }
    }

    /// Force on body A at one contact, and its tangential part.
    ///
    /// `n` is the unit normal from B to A, `delta > 0` the overlap, `r_eff` and `m_eff` the
    /// reduced radius and mass, `u_n = (v_A − v_B)·n`, `slip` the tangential velocity of A's
    /// contact point relative to B's: `u − u_n n − (r_A ω_A + r_B ω_B) × n`.
    /// `xi` is the tangential spring, updated in place.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn force(
        &self,
        n: Vec3,
        delta: f64,
        r_eff: f64,
        m_eff: f64,
        u_n: f64,
        slip: Vec3,
        dt: f64,
        xi: &mut Vec3,
    ) -> (Vec3, Vec3) {
        match self {
            ContactLaw::Hertz { .. } => self.hertz_force(n, delta, r_eff, m_eff, u_n, slip, dt, xi),
            ContactLaw::Linear { .. } => {
                self.linear_force(n, delta, r_eff, m_eff, u_n, slip, dt, xi)
            }
        }
    }

    /// [`ContactLaw::force`] for a law known to be `Hertz` (the pair loop is specialised per law).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn hertz_force(
        &self,
        n: Vec3,
        delta: f64,
        r_eff: f64,
        m_eff: f64,
        u_n: f64,
        slip: Vec3,
        dt: f64,
        xi: &mut Vec3,
    ) -> (Vec3, Vec3) {
        let ContactLaw::Hertz {
            e_star,
            g_star,
            alpha,
            b,
            mu,
            rule,
        } = *self
        else {
            unreachable!("hertz_force on a linear law")
        };
        let k_n = 4.0 / 3.0 * r_eff.sqrt() * e_star;
        let sqrt_delta = delta.sqrt();
        let eta_n = alpha * (m_eff * k_n).sqrt() * sqrt_delta.sqrt();
        // δ^b with the usual b = 1.5 as δ√δ (bit-identical to powf is not needed).
        let delta_b = if b == 1.5 {
            delta * sqrt_delta
        } else {
            delta.powf(b)
        };
        let f_n_mag = k_n * delta_b - eta_n * u_n;
        let f_n = n * f_n_mag;
        let mut x = Vec3::new(
            xi[0] + slip[0] * dt,
            xi[1] + slip[1] * dt,
            xi[2] + slip[2] * dt,
        );
        if rule == TangentialRule::CappedSpring {
            x = x - (n * x.dot(&n));
        }
        let x_mag = x.norm();
        let mut f_t = Vec3::zeros();
        if x_mag > VSMALL {
            let k_t = 8.0 * (r_eff * delta).sqrt() * g_star;
            let eta_t = eta_n;
            let limit = mu * f_n_mag.abs();
            match rule {
                TangentialRule::DpmFoamReset => {
                    if k_t * x_mag > limit {
                        let s = slip.norm();
                        // û_t; when the contact point is momentarily at rest the spring
                        // direction is the only one defined.
                        let dir = if s > VSMALL {
                            slip * (1.0 / s)
                        } else {
                            x * (1.0 / x_mag)
                        };
                        f_t = dir * (-limit);
                        x = Vec3::zeros();
                    } else {
                        f_t = Vec3::new(
                            -k_t * x[0] - eta_t * slip[0],
                            -k_t * x[1] - eta_t * slip[1],
                            -k_t * x[2] - eta_t * slip[2],
                        );
                    }
                }
                TangentialRule::CappedSpring => {
                    f_t = Vec3::new(
                        -k_t * x[0] - eta_t * slip[0],
                        -k_t * x[1] - eta_t * slip[1],
                        -k_t * x[2] - eta_t * slip[2],
                    );
                    // squared test: no square root while the contact sticks
                    let f_t_sq = f_t.dot(&f_t);
                    if f_t_sq > limit * limit {
                        let f_t_mag = f_t_sq.sqrt();
                        f_t *= limit / f_t_mag;
                        // spring such that −k_T ξ − η_T u_t equals the capped force
                        let inv_k = 1.0 / k_t;
                        x = Vec3::new(
                            -(f_t[0] + eta_t * slip[0]) * inv_k,
                            -(f_t[1] + eta_t * slip[1]) * inv_k,
                            -(f_t[2] + eta_t * slip[2]) * inv_k,
                        );
                    }
                }
            }
        }
        *xi = x;
        (
            Vec3::new(f_n[0] + f_t[0], f_n[1] + f_t[1], f_n[2] + f_t[2]),
            f_t,
        )
    }

    /// [`ContactLaw::force`] for a law known to be `Linear`.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn linear_force(
        &self,
        n: Vec3,
        delta: f64,
        r_eff: f64,
        m_eff: f64,
        u_n: f64,
        slip: Vec3,
        dt: f64,
        xi: &mut Vec3,
    ) -> (Vec3, Vec3) {
        let _ = r_eff;
        let ContactLaw::Linear {
            kn,
            kt,
            damping,
            tangential_damping_ratio,
            mu,
        } = *self
        else {
            unreachable!("linear_force on a Hertz law")
        };
        let c_n = damping * (kn * m_eff).sqrt();
        let f_n_mag = kn * delta - c_n * u_n;
        let c_t = tangential_damping_ratio * c_n;
        // LAMMPS gran/hooke/history: accumulate, then drop the normal component.
        let mut x = Vec3::new(
            xi[0] + slip[0] * dt,
            xi[1] + slip[1] * dt,
            xi[2] + slip[2] * dt,
        );
        x = x - (n * x.dot(&n));
        let mut f_t = Vec3::new(
            -(kt * x[0] + c_t * slip[0]),
            -(kt * x[1] + c_t * slip[1]),
            -(kt * x[2] + c_t * slip[2]),
        );
        let f_t_sq = f_t.dot(&f_t);
        let limit = mu * f_n_mag.abs();
        // squared test: no square root while the contact sticks
        if f_t_sq > limit * limit {
            let f_t_mag = f_t_sq.sqrt();
            if kt > 0.0 && x.dot(&x) > 0.0 {
                let ratio = limit / f_t_mag;
                let damp = c_t / kt;
                x = Vec3::new(
                    ratio * (x[0] + damp * slip[0]) - damp * slip[0],
                    ratio * (x[1] + damp * slip[1]) - damp * slip[1],
                    ratio * (x[2] + damp * slip[2]) - damp * slip[2],
                );
                f_t *= ratio;
            } else {
                f_t = if f_t_mag > 0.0 {
                    f_t * (limit / f_t_mag)
                } else {
                    Vec3::zeros()
                };
                x = Vec3::zeros();
            }
        }
        *xi = x;
        let f_n = n * f_n_mag;
        (
            Vec3::new(f_n[0] + f_t[0], f_n[1] + f_t[1], f_n[2] + f_t[2]),
            f_t,
        )
    }
}
