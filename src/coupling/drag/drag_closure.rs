//! Drag closures: the coefficient `β` (N·s/m) of one particle's drag `f_d = β (u − v)`,
//! with `u` the *interstitial* fluid velocity at the particle and `v` the particle's.
//!
//! Notation shared by every closure (SI units):
//! - `d` particle diameter, `V = π d³/6`, `ε` fluid fraction at the particle, `φ = 1 − ε`;
//! - `Re = ρ_f |u − v| d / μ_f`, the particle Reynolds number of the interstitial slip
//!   (OpenFOAM's `KinematicParcel::Re`);
//! - `Re_s = ε Re`, the one of the superficial slip `U_s = ε |u − v|`.
//!
//! Closures come in two conventions ([`Convention`]), and the coupling converts between
//! them with the standard factor `ε` (Zhou, Kuang, Chu & Yu 2010, J. Fluid Mech. 661):
//! - [`Convention::DragOnly`]: the drag *without* the mean pressure gradient, used with a
//!   separate pressure-gradient force `−V ∇p` on the particle (paper eq. 10; "model A");
//! - [`Convention::Total`]: the whole fluid force of a uniform suspension less buoyancy, for a
//!   fluid whose momentum carries `−∇p` and particles that feel no pressure gradient
//!   (DPMFoam's form, "model B"). In a uniform bed `f_total = f_drag_only / ε`.

use std::f64::consts::PI;

/// Which fluid force a closure's coefficient gives (see the module notes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Convention {
    /// Drag excluding the mean pressure gradient (paper eq. 10–12, model A).
    DragOnly,
    /// Total fluid force less buoyancy (DPMFoam's closures, model B).
    Total,
}

/// A drag closure, by its DPMFoam `particleForces` name or fsim's name for it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DragClosure {
    /// Paper eq. 11–12 (OCR-garbled; read as Wen & Yu for ε > 0.8 with the exponent −2.7 of
    /// paper eq. 12, −4.7 in paper eq. 18's K, and Ergun 1952 for ε ≤ 0.8).
    Paper,
    /// OpenFOAM v1912 `sphereDrag`: an isolated sphere, no ε.
    SphereDrag,
    /// OpenFOAM v1912 `WenYuDrag`.
    WenYu,
    /// OpenFOAM v1912 `ErgunWenYuDrag`.
    ErgunWenYu,
    /// OpenFOAM v1912 `PlessisMasliyahDrag`.
    PlessisMasliyah,
    /// Di Felice (1994), Int. J. Multiphase Flow 20, 153–159.
    DiFelice,
    /// Beetstra, van der Hoef & Kuipers (2007), AIChE J. 53, 489–501.
    Beetstra,
    /// Tenneti, Garg & Subramaniam (2011), Int. J. Multiphase Flow 37, 1072–1092.
    Tenneti,
    /// Koch & Hill (2001), Annu. Rev. Fluid Mech. 33, 619–647 (with Hill, Koch & Ladd 2001).
    KochHill,
    /// Gidaspow (1994), *Multiphase Flow and Fluidization*: Wen & Yu for ε > 0.8, Ergun below.
    Gidaspow,
    /// OpenFOAM v1912 `nonSphereDrag { phi …; }`: Haider & Levenspiel (1989), Powder Technol.
    /// 58, 63–70, for particles of sphericity `phi` in (0, 1] (no ε, like `sphereDrag`).
    NonSphere {
        /// Sphericity: the surface of the sphere of the same volume over the particle's.
        phi: f64,
    },
}

/// The fluid and particle at one particle, as a closure needs them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DragInput {
    /// Particle diameter, m.
    pub d: f64,
    /// Fluid fraction at the particle (0 < ε ≤ 1).
    pub eps: f64,
    /// Interstitial slip speed `|u − v|`, m/s.
    pub slip: f64,
    /// Fluid density, kg/m³.
    pub rho: f64,
    /// Dynamic viscosity, Pa·s.
    pub mu: f64,
}

impl DragInput {
    /// `Re = ρ |u − v| d / μ`.
    pub fn re(&self) -> f64 {
        self.rho * self.slip * self.d / self.mu
    }
    /// `Re_s = ε Re`.
    pub fn re_superficial(&self) -> f64 {
        self.eps * self.re()
    }
    /// `V = π d³ / 6`.
    pub fn volume(&self) -> f64 {
        PI * self.d.powi(3) / 6.0
    }
    /// Stokes' coefficient `3 π μ d`.
    fn stokes(&self) -> f64 {
        3.0 * PI * self.mu * self.d
    }
}

impl DragClosure {
    /// Every name accepted, in the order of [`Self::from_name`]'s error message.
    pub const NAMES: [&'static str; 10] = [
        "paper",
        "sphereDrag",
        "WenYuDrag",
        "ErgunWenYuDrag",
        "PlessisMasliyahDrag",
        "DiFelice",
        "Beetstra",
        "Tenneti",
        "KochHill",
        "Gidaspow",
    ];

    /// The closure of a name; an unknown name gives a message naming `keyword` and the list.
    pub fn from_name(name: &str, keyword: &str) -> Result<Self, String> {
        let closure = match name {
            "paper" => DragClosure::Paper,
            "sphereDrag" => DragClosure::SphereDrag,
            "WenYuDrag" => DragClosure::WenYu,
            "ErgunWenYuDrag" => DragClosure::ErgunWenYu,
            "PlessisMasliyahDrag" => DragClosure::PlessisMasliyah,
            "DiFelice" => DragClosure::DiFelice,
            "Beetstra" => DragClosure::Beetstra,
            "Tenneti" => DragClosure::Tenneti,
            "KochHill" => DragClosure::KochHill,
            "Gidaspow" => DragClosure::Gidaspow,
            _ => {
                return Err(format!(
                    "{keyword} '{name}': unknown drag model (known: {})",
                    Self::NAMES.join(", ")
                ))
            }
        };
        Ok(closure)
    }

    /// The name [`Self::from_name`] accepts (`nonSphereDrag`, which needs its `phi`, is read
    /// by the case reader only).
    pub fn name(self) -> &'static str {
        match self {
            DragClosure::Paper => Self::NAMES[0],
            DragClosure::SphereDrag => Self::NAMES[1],
            DragClosure::WenYu => Self::NAMES[2],
            DragClosure::ErgunWenYu => Self::NAMES[3],
            DragClosure::PlessisMasliyah => Self::NAMES[4],
            DragClosure::DiFelice => Self::NAMES[5],
            DragClosure::Beetstra => Self::NAMES[6],
            DragClosure::Tenneti => Self::NAMES[7],
            DragClosure::KochHill => Self::NAMES[8],
            DragClosure::Gidaspow => Self::NAMES[9],
            DragClosure::NonSphere { .. } => "nonSphereDrag",
        }
    }

    /// Whether the coefficient excludes the pressure gradient or is the total force.
    pub fn convention(self) -> Convention {
        match self {
            DragClosure::Paper
            | DragClosure::DiFelice
            | DragClosure::Beetstra
            | DragClosure::Gidaspow => Convention::DragOnly,
            DragClosure::SphereDrag
            | DragClosure::WenYu
            | DragClosure::ErgunWenYu
            | DragClosure::PlessisMasliyah
            | DragClosure::Tenneti
            | DragClosure::KochHill
            | DragClosure::NonSphere { .. } => Convention::Total,
        }
    }

    /// `β` in the closure's own [`Convention`], N·s/m.
    pub fn coefficient(self, q: &DragInput) -> f64 {
        match self {
            DragClosure::Paper => paper(q),
            DragClosure::SphereDrag => sphere_drag(q),
            DragClosure::WenYu => wen_yu_drag(q),
            DragClosure::ErgunWenYu => ergun_wen_yu_drag(q),
            DragClosure::PlessisMasliyah => plessis_masliyah_drag(q),
            DragClosure::DiFelice => di_felice(q),
            DragClosure::Beetstra => beetstra(q),
            DragClosure::Tenneti => tenneti(q),
            DragClosure::KochHill => koch_hill(q),
            DragClosure::Gidaspow => gidaspow(q),
            DragClosure::NonSphere { phi } => non_sphere_drag(q, phi),
        }
    }

    /// `β` in the requested convention: `Total = DragOnly / ε`.
    pub fn coefficient_as(self, q: &DragInput, want: Convention) -> f64 {
        let beta = self.coefficient(q);
        match (self.convention(), want) {
            (a, b) if a == b => beta,
            (Convention::DragOnly, Convention::Total) => beta / q.eps,
            _ => beta * q.eps,
        }
    }
}

/// Paper eq. 11–12 in the drag-only convention (used with paper eq. 10):
/// - ε > 0.8 (Wen & Yu): `β = 3 π μ d ε^−2.7 (1 + 0.15 Re_s^0.687)`, so that in a uniform bed at
///   Re ≪ 1 the total force is `K = ε^−4.7` times Stokes' (paper eq. 18, φ < 0.2);
/// - ε ≤ 0.8 (Ergun): `β = 25 π μ d (1 − ε)/ε + (1.75/6) π ρ |u − v| d²`, whose total force
///   `β/ε` at Re ≪ 1 is `K = (25/3) φ / ε³` times Stokes' (paper eq. 18, φ ≥ 0.2).
pub fn paper(q: &DragInput) -> f64 {
    if q.eps > 0.8 {
        q.stokes() * q.eps.powf(-2.7) * (1.0 + 0.15 * q.re_superficial().powf(0.687))
    } else {
        ergun_drag_only(q)
    }
}

/// Ergun (1952) per particle, drag-only: `β = 150 φ μ V /(ε d²) + 1.75 ρ |u − v| V / d`
/// (Gidaspow's `β_gs V/φ`), i.e. `25 π μ d φ/ε + (1.75/6) π ρ |u − v| d²`.
fn ergun_drag_only(q: &DragInput) -> f64 {
    let phi = 1.0 - q.eps;
    25.0 * PI * q.mu * q.d * phi / q.eps + 1.75 / 6.0 * PI * q.rho * q.slip * q.d * q.d
}

/// Terminal velocity (m/s) of one sphere of diameter `d` and density `rho_p` in an unbounded
/// fluid of density `rho_f` and dynamic viscosity `mu` under gravity `g` (m/s²): the root
/// of the force balance `|ρ_p − ρ_f| g π d³/6 = (C_d Re / 24) 3π μ d U` with Schiller–Naumann's
/// `C_d Re` (`cd_re_schiller_naumann`), that is `U = V_Stokes · 24 / (C_d Re)(U)`. The
/// right side falls as `U` grows, so the root is unique; bisection between 0 and Stokes'
/// velocity finds it.
pub fn terminal_velocity(d: f64, rho_p: f64, rho_f: f64, mu: f64, g: f64) -> f64 {
    let stokes = (rho_p - rho_f).abs() * g * d * d / (18.0 * mu);
    let excess = |u: f64| u * cd_re_schiller_naumann(rho_f * u * d / mu) / 24.0 - stokes;
    let (mut lo, mut hi) = (0.0, stokes);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if excess(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Schiller–Naumann `C_d Re = 24 (1 + 0.15 Re^0.687)` up to `Re = 1000`, `0.44 Re` beyond (as
/// OpenFOAM's `WenYuDrag::CdRe`).
fn cd_re_schiller_naumann(re: f64) -> f64 {
    if re > 1000.0 {
        0.44 * re
    } else {
        24.0 * (1.0 + 0.15 * re.powf(0.687))
    }
}

/// OpenFOAM v1912 `sphereDrag`: `β = V (3/4) μ CdRe(Re) / d²` with
/// `CdRe = 24 (1 + Re^(2/3)/6)` for `Re ≤ 1000`, `0.424 Re` beyond (Putnam's fit). At Re → 0
/// it is Stokes' `3 π μ d`.
pub fn sphere_drag(q: &DragInput) -> f64 {
    let re = q.re();
    let cd_re = if re > 1000.0 {
        0.424 * re
    } else {
        24.0 * (1.0 + re.powf(2.0 / 3.0) / 6.0)
    };
    q.volume() * 0.75 * q.mu * cd_re / (q.d * q.d)
}

/// Haider & Levenspiel (1989) for sphericity `phi`: `C_d Re = 24 (1 + a Re^b) + c Re/(1 + d/Re)`
/// with `a = exp(2.3288 − 6.4581 φ + 2.4486 φ²)`, `b = 0.0964 + 0.5565 φ`,
/// `c = exp(4.905 − 13.8944 φ + 18.4222 φ² − 10.2599 φ³)`,
/// `d = exp(1.4681 + 12.2584 φ − 20.7322 φ² + 15.8855 φ³)` (as OpenFOAM's `NonSphereDragForce`).
pub fn cd_re_haider_levenspiel(re: f64, phi: f64) -> f64 {
    let (p2, p3) = (phi * phi, phi * phi * phi);
    let a = (2.3288 - 6.4581 * phi + 2.4486 * p2).exp();
    let b = 0.0964 + 0.5565 * phi;
    let c = (4.905 - 13.8944 * phi + 18.4222 * p2 - 10.2599 * p3).exp();
    let d = (1.4681 + 12.2584 * phi - 20.7322 * p2 + 15.8855 * p3).exp();
    // Re + ROOTVSMALL under d, as OpenFOAM: the term vanishes at Re = 0
    24.0 * (1.0 + a * re.powf(b)) + re * c / (1.0 + d / (re + 1e-150))
}

/// OpenFOAM v1912 `nonSphereDrag`: `β = V (3/4) μ CdRe(Re) / d²` with Haider & Levenspiel's
/// `CdRe` ([`cd_re_haider_levenspiel`]); `d` the volume-equivalent diameter.
pub fn non_sphere_drag(q: &DragInput, phi: f64) -> f64 {
    q.volume() * 0.75 * q.mu * cd_re_haider_levenspiel(q.re(), phi) / (q.d * q.d)
}

/// OpenFOAM v1912 `WenYuDrag`: `β = V (3/4) CdRe(ε Re) μ ε^−2.65 / (ε d²)`, `CdRe` Schiller–Naumann.
pub fn wen_yu_drag(q: &DragInput) -> f64 {
    q.volume() * 0.75 * cd_re_schiller_naumann(q.eps * q.re()) * q.mu * q.eps.powf(-2.65)
        / (q.eps * q.d * q.d)
}

/// OpenFOAM v1912 `ErgunWenYuDrag`: for `ε < 0.8`
/// `β = V (150 (1 − ε)/ε + 1.75 Re) μ / (ε d²)`, else [`wen_yu_drag`].
pub fn ergun_wen_yu_drag(q: &DragInput) -> f64 {
    if q.eps < 0.8 {
        q.volume() * (150.0 * (1.0 - q.eps) / q.eps + 1.75 * q.re()) * q.mu / (q.eps * q.d * q.d)
    } else {
        wen_yu_drag(q)
    }
}

/// OpenFOAM v1912 `PlessisMasliyahDrag`: `β = V (A (1 − ε)/ε + B Re) μ / (ε d²)` with
/// `a = (1 − ε)^(1/3)`, `A = 26.8 ε³ / (a² (1 − a) (1 − a²)² + 1e-15)`, `B = ε² / (1 − a²)²`
/// (du Plessis & Masliyah 1988).
pub fn plessis_masliyah_drag(q: &DragInput) -> f64 {
    let eps = q.eps;
    let a = (1.0 - eps).cbrt();
    let a2 = a * a;
    let big_a = 26.8 * eps.powi(3) / (a2 * (1.0 - a) * (1.0 - a2).powi(2) + 1e-15);
    let big_b = eps * eps / (1.0 - a2).powi(2);
    q.volume() * (big_a * (1.0 - eps) / eps + big_b * q.re()) * q.mu / (eps * q.d * q.d)
}

/// Di Felice (1994), drag-only:
/// `f = ½ C_d ρ (π d²/4) ε² |u − v| (u − v) ε^−χ`, `C_d = (0.63 + 4.8/√Re_s)²`,
/// `χ = 3.7 − 0.65 exp(−(1.5 − log₁₀ Re_s)²/2)`; so `β = (π/8) ρ d² ε^(2−χ) C_d |u − v|`, with
/// `C_d |u − v| = (0.63 √|u − v| + 4.8 √(μ/(ρ ε d)))²` finite at zero slip.
pub fn di_felice(q: &DragInput) -> f64 {
    let re_s = q.re_superficial();
    let chi = if re_s > 0.0 {
        3.7 - 0.65 * (-(1.5 - re_s.log10()).powi(2) / 2.0).exp()
    } else {
        3.7
    };
    let cd_slip = (0.63 * q.slip.sqrt() + 4.8 * (q.mu / (q.rho * q.eps * q.d)).sqrt()).powi(2);
    PI / 8.0 * q.rho * q.d * q.d * q.eps.powf(2.0 - chi) * cd_slip
}

/// Beetstra, van der Hoef & Kuipers (2007), drag-only: `β = 3 π μ d ε F` with
/// `F = 10φ/ε² + ε² (1 + 1.5 √φ) + 0.413 Re_s/(24 ε²) · (1/ε + 3 ε φ + 8.4 Re_s^−0.343) /
/// (1 + 10^(3φ) Re_s^−(1+4φ)/2)`.
pub fn beetstra(q: &DragInput) -> f64 {
    let (eps, phi) = (q.eps, 1.0 - q.eps);
    let re = q.re_superficial();
    let inertial = if re > 0.0 {
        0.413 * re / (24.0 * eps * eps) * (1.0 / eps + 3.0 * eps * phi + 8.4 * re.powf(-0.343))
            / (1.0 + 10f64.powf(3.0 * phi) * re.powf(-(1.0 + 4.0 * phi) / 2.0))
    } else {
        0.0
    };
    let f = 10.0 * phi / (eps * eps) + eps * eps * (1.0 + 1.5 * phi.sqrt()) + inertial;
    q.stokes() * eps * f
}

/// Tenneti, Garg & Subramaniam (2011), total: `β = 3 π μ d ε F`,
/// `F = (1 + 0.15 Re_s^0.687)/ε³ + 5.81 φ/ε³ + 0.48 φ^(1/3)/ε⁴ + φ³ Re_s (0.95 + 0.61 φ³/ε²)`.
pub fn tenneti(q: &DragInput) -> f64 {
    let (eps, phi) = (q.eps, 1.0 - q.eps);
    let re = q.re_superficial();
    let f = (1.0 + 0.15 * re.powf(0.687)) / eps.powi(3)
        + 5.81 * phi / eps.powi(3)
        + 0.48 * phi.cbrt() / eps.powi(4)
        + phi.powi(3) * re * (0.95 + 0.61 * phi.powi(3) / (eps * eps));
    q.stokes() * eps * f
}

/// Koch & Hill (2001), total: `β = 3 π μ d ε F`, `F = F₀(φ) + ½ F₃(φ) Re_s` (the ½ turns
/// `Re_s` into their radius-based number) with `F₃ = 0.0673 + 0.212 φ + 0.0232/ε⁵` and
/// `F₀ = (1 + 3√(φ/2) + (135/64) φ ln φ + 16.14 φ) / (1 + 0.681 φ − 8.48 φ² + 8.16 φ³)` for
/// `φ < 0.4`, `10 φ/ε³` beyond (as in MFiX, Benyahia et al. 2006).
pub fn koch_hill(q: &DragInput) -> f64 {
    let (eps, phi) = (q.eps, 1.0 - q.eps);
    let f0 = if phi < 0.4 {
        let log_term = if phi > 0.0 { phi * phi.ln() } else { 0.0 };
        (1.0 + 3.0 * (phi / 2.0).sqrt() + 135.0 / 64.0 * log_term + 16.14 * phi)
            / (1.0 + 0.681 * phi - 8.48 * phi * phi + 8.16 * phi.powi(3))
    } else {
        10.0 * phi / eps.powi(3)
    };
    let f3 = 0.0673 + 0.212 * phi + 0.0232 / eps.powi(5);
    q.stokes() * eps * (f0 + 0.5 * f3 * q.re_superficial())
}

/// Gidaspow (1994), drag-only: for ε > 0.8 Wen & Yu
/// `β = V (3/4) C_d ρ |u − v| ε^−2.65 / d`, `C_d = 24/Re_s (1 + 0.15 Re_s^0.687)` (0.44 for
/// `Re_s ≥ 1000`), i.e. `3 π μ d ε^−2.65 CdRe(Re_s)/24`; for ε ≤ 0.8 Ergun as [`paper`].
pub fn gidaspow(q: &DragInput) -> f64 {
    if q.eps > 0.8 {
        q.stokes() * q.eps.powf(-2.65) * cd_re_schiller_naumann(q.re_superficial()) / 24.0
    } else {
        ergun_drag_only(q)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    /// Stokes' law where Re is small; the force balance holds where it is not; a sphere
    /// lighter than the fluid rises as fast as one as much heavier sinks.
    #[test]
    fn terminal_velocity_balances_weight_and_schiller_naumann_drag() {
        let (rho_f, mu, g) = (1000.0, 1e-3, 9.81);
        // d = 10 µm, Δρ = 1500: V_Stokes = 8.2e-5 m/s, Re = 8e-4
        let stokes = 1500.0 * g * 1e-10 / (18.0 * mu);
        let slow = terminal_velocity(1e-5, 2500.0, rho_f, mu, g);
        assert!(close(slow, stokes, 2e-3), "{slow} against {stokes}");
        // seeded random spheres up to Re of a few hundred
        let mut rng = crate::particles::SplitMix64::new(11);
        for _ in 0..20 {
            let d = 1e-4 + 2e-3 * rng.next_f64();
            let rho_p = 1100.0 + 800.0 * rng.next_f64();
            let u = terminal_velocity(d, rho_p, rho_f, mu, g);
            let re = rho_f * u * d / mu;
            let weight = (rho_p - rho_f) * g * PI * d * d * d / 6.0;
            let drag = cd_re_schiller_naumann(re) / 24.0 * 3.0 * PI * mu * d * u;
            assert!(
                close(drag, weight, 1e-12),
                "d {d} rho_p {rho_p}: {drag} against {weight}"
            );
            let rising = terminal_velocity(d, 2.0 * rho_f - rho_p, rho_f, mu, g);
            assert!(close(rising, u, 1e-12));
        }
    }

    /// d = 1 mm, ρ = 1000, μ = 1e-3, |u − v| = 0.01 m/s: Re = 1000·0.01·1e-3/1e-3 = 10,
    /// 3πμd = 9.42478e-6 N·s/m, V = 5.23599e-10 m³.
    fn water(eps: f64) -> DragInput {
        DragInput {
            d: 1e-3,
            eps,
            slip: 0.01,
            rho: 1000.0,
            mu: 1e-3,
        }
    }

    #[test]
    fn sphere_drag_by_hand() {
        // Re = 10: CdRe = 24 (1 + 10^(2/3)/6) = 24 (1 + 4.641589/6) = 42.56636;
        // β = V · 0.75 · μ · CdRe / d² = 5.235988e-10 · 0.75 · 1e-3 · 42.56636 / 1e-6
        //   = 1.671577e-5.
        let b = sphere_drag(&water(0.5));
        assert!(close(b, 1.671577e-5, 1e-6), "{b}");
        // Stokes limit: 3πμd.
        let mut q = water(1.0);
        q.slip = 0.0;
        assert!(close(sphere_drag(&q), 9.424778e-6, 1e-6));
    }

    #[test]
    fn wen_yu_by_hand() {
        // ε = 0.9: εRe = 9, CdRe = 24 (1 + 0.15·9^0.687) = 24 (1 + 0.15·4.524438) = 40.28797;
        // ε^−2.65 = 1.322079; β = V·0.75·40.28797·1e-3·1.322079/(0.9·1e-6) = 2.324075e-5.
        let b = wen_yu_drag(&water(0.9));
        assert!(close(b, 2.324075e-5, 2e-6), "{b}");
        assert_eq!(ergun_wen_yu_drag(&water(0.9)), b);
        // Above εRe = 1000: CdRe = 0.44 εRe.
        let mut q = water(1.0);
        q.slip = 2.0; // Re = 2000
        let b = wen_yu_drag(&q);
        assert!(close(b, q.volume() * 0.75 * 880.0 * 1e-3 / 1e-6, 1e-12));
    }

    #[test]
    fn ergun_wen_yu_dense_branch_by_hand() {
        // ε = 0.5: 150·0.5/0.5 + 1.75·10 = 167.5;
        // β = V·167.5·1e-3/(0.5·1e-6) = 5.235988e-10·335000 = 1.754056e-4.
        let b = ergun_wen_yu_drag(&water(0.5));
        assert!(close(b, 1.754056e-4, 1e-6), "{b}");
    }

    #[test]
    fn plessis_masliyah_by_hand() {
        // ε = 0.5: a = 0.5^(1/3) = 0.793701, a² = 0.629961, 1 − a² = 0.370039;
        // A = 26.8·0.125/(0.629961·0.206299·0.136929) = 188.2510;
        // B = 0.25/0.136929 = 1.825761; A(1−ε)/ε + B Re = 188.2510 + 18.25761 = 206.5086;
        // β = V·206.5086·1e-3/(0.5·1e-6) = 2.162553e-4.
        let b = plessis_masliyah_drag(&water(0.5));
        assert!(close(b, 2.162553e-4, 2e-6), "{b}");
    }

    #[test]
    fn paper_closure_by_hand_and_its_low_re_limits() {
        // ε = 0.9: Re_s = 9, 9^0.687 = 4.524438, ε^−2.7 = 1.329062;
        // β = 9.424778e-6·1.329062·1.678666 = 2.102716e-5.
        let b = paper(&water(0.9));
        assert!(close(b, 2.102716e-5, 2e-6), "{b}");
        // ε = 0.5: 25π·1e-3·1e-3·0.5/0.5 = 7.853982e-5, (1.75/6)π·1000·0.01·1e-6 = 9.162979e-6;
        // β = 8.770280e-5.
        let b = paper(&water(0.5));
        assert!(close(b, 8.770280e-5, 1e-6), "{b}");
        // At Re → 0 the total force β/ε over 3πμd U_s (U_s = ε|u−v|) is paper eq. 18's K:
        // (25/3) φ / ε³ for ε ≤ 0.8, ε^−4.7 above.
        for (eps, k) in [(0.6, 25.0 / 3.0 * 0.4 / 0.216), (0.9, 0.9f64.powf(-4.7))] {
            let mut q = water(eps);
            q.slip = 0.0;
            let total = DragClosure::Paper.coefficient_as(&q, Convention::Total);
            assert!(close(total / (q.stokes() * eps), k, 1e-12));
        }
    }

    #[test]
    fn gidaspow_by_hand() {
        // ε = 0.9: ε^−2.65 = 1.322079, CdRe(9)/24 = 1.678666;
        // β = 9.424778e-6·1.322079·1.678666 = 2.091668e-5. Dense branch = paper's Ergun.
        let b = gidaspow(&water(0.9));
        assert!(close(b, 2.091668e-5, 2e-6), "{b}");
        assert_eq!(gidaspow(&water(0.5)), paper(&water(0.5)));
    }

    #[test]
    fn di_felice_by_hand() {
        // ε = 0.9, Re_s = 9: log₁₀ 9 = 0.954243, (1.5 − 0.954243)² / 2 = 0.148925,
        // χ = 3.7 − 0.65 e^−0.148925 = 3.7 − 0.560062 = 3.139938;
        // C_d = (0.63 + 4.8/3)² = 2.23² = 4.9729; ε^(2−χ) = 0.9^−1.139938 = 1.127615;
        // β = (π/8)·1000·1e-6·1.127615·4.9729·0.01 = 2.202066e-5.
        let b = di_felice(&water(0.9));
        assert!(close(b, 2.202066e-5, 2e-6), "{b}");
        // Zero slip stays finite: C_d |u−v| → 23.04 μ/(ρ ε d).
        let mut q = water(0.9);
        q.slip = 0.0;
        let limit = PI / 8.0 * 1e-3 * 0.9f64.powf(-1.7) * 23.04 * 1e-3 / (1000.0 * 0.9 * 1e-3);
        assert!(close(di_felice(&q), limit, 1e-12));
    }

    #[test]
    fn beetstra_by_hand() {
        // ε = 0.5, φ = 0.5, Re_s = 5: 10φ/ε² = 20; ε²(1 + 1.5√φ) = 0.25·2.060660 = 0.515165;
        // 5^−0.343 = 0.575708, numerator 2 + 0.75 + 4.835947 = 7.585947;
        // 10^1.5 = 31.62278, 5^−1.5 = 0.0894427, denominator 1 + 2.828427 = 3.828427;
        // inertial = 0.413·5/6 · 7.585947/3.828427 = 0.682010;
        // F = 21.19718; β = 9.424778e-6·0.5·21.19718 = 9.988933e-5.
        let b = beetstra(&water(0.5));
        assert!(close(b, 9.988933e-5, 2e-6), "{b}");
    }

    #[test]
    fn tenneti_by_hand() {
        // ε = 0.5, Re_s = 5: 5^0.687 = 3.021126, (1 + 0.453169)/0.125 = 11.62535;
        // 5.81·0.5/0.125 = 23.24; 0.48·0.793701/0.0625 = 6.095620;
        // 0.125·5·(0.95 + 0.61·0.125/0.25) = 0.625·1.255 = 0.784375;
        // F = 41.74554; β = 9.424778e-6·0.5·41.74554 = 1.967212e-4.
        let b = tenneti(&water(0.5));
        assert!(close(b, 1.967212e-4, 2e-6), "{b}");
    }

    #[test]
    fn koch_hill_by_hand() {
        // ε = 0.8, φ = 0.2, Re_s = 8: √0.1 = 0.316228, 0.2 ln 0.2 = −0.321888;
        // F₀ = (1 + 0.948683 − 0.678983 + 3.228)/(1 + 0.1362 − 0.3392 + 0.06528)
        //    = 4.497700/0.862280 = 5.216057;
        // F₃ = 0.0673 + 0.0424 + 0.0232/0.32768 = 0.180500; F = 5.216057 + 0.5·0.180500·8 = 5.938057;
        // β = 9.424778e-6·0.8·5.938057 = 4.477192e-5.
        let b = koch_hill(&water(0.8));
        assert!(close(b, 4.477192e-5, 2e-6), "{b}");
        // Dense branch: φ = 0.5, F₀ = 10·0.5/0.125 = 40.
        let mut q = water(0.5);
        q.slip = 0.0;
        assert!(close(koch_hill(&q), 9.424778e-6 * 0.5 * 40.0, 1e-6));
    }

    #[test]
    fn haider_levenspiel_by_hand() {
        // φ = 1: a = e^(−1.68070) = 0.186244, b = 0.6529, c = e^(−0.82710) = 0.437316,
        // d = e^(8.87980) = 7185.354; Re = 10: 10^0.6529 = 4.496763,
        // CdRe = 24 (1 + 0.837485) + 4.37316/(1 + 718.5354) = 44.099836 + 0.006078 = 44.105913
        // (sphereDrag's Putnam fit gives 42.566 there: the same sphere within 4 %).
        let hl = cd_re_haider_levenspiel(10.0, 1.0);
        assert!(close(hl, 44.105913, 2e-7), "{hl}");
        let sphere = sphere_drag(&water(1.0)) / (water(1.0).volume() * 0.75 * 1e-3 / 1e-6);
        assert!(close(hl, sphere, 0.04), "{hl} against {sphere}");
        // φ = 0.5: a = e^(−0.28810) = 0.749687, b = 0.37465, c = e^(1.28086) = 3.599743,
        // d = e^(4.39994) = 81.4458; 10^0.37465 = 2.369463,
        // CdRe = 24 (1 + 1.776355) + 35.99743/9.14458 = 66.632520 + 3.936478 = 70.568998
        let hl = cd_re_haider_levenspiel(10.0, 0.5);
        assert!(close(hl, 70.568998, 2e-7), "{hl}");
        // β = V (3/4) μ CdRe / d², and the Stokes limit 24 (Re → 0) for every φ
        let b = non_sphere_drag(&water(0.5), 0.5);
        assert!(close(
            b,
            water(0.5).volume() * 0.75 * 1e-3 * 70.568998 / 1e-6,
            2e-7
        ));
        assert!(close(cd_re_haider_levenspiel(0.0, 0.7), 24.0, 1e-12));
        let c = DragClosure::NonSphere { phi: 0.5 };
        assert_eq!(
            (c.name(), c.convention()),
            ("nonSphereDrag", Convention::Total)
        );
        assert_eq!(c.coefficient(&water(0.5)), b);
    }

    #[test]
    fn names_round_trip_and_unknown_names_are_refused() {
        for name in DragClosure::NAMES {
            let c = DragClosure::from_name(name, "dragModel").unwrap();
            assert_eq!(c.name(), name);
        }
        let e = DragClosure::from_name("SchillerNaumann", "particleForces").unwrap_err();
        assert!(e.contains("particleForces 'SchillerNaumann'") && e.contains("ErgunWenYuDrag"));
    }

    #[test]
    fn dilute_limits_agree_with_stokes() {
        // At ε → 1 and Re → 0 every closure but du Plessis & Masliyah's (a packed-bed law:
        // its A(1 − ε)/ε vanishes there) tends to 3πμd, within its fit's accuracy.
        let mut q = water(1.0 - 1e-9);
        q.slip = 1e-12;
        for name in DragClosure::NAMES {
            let c = DragClosure::from_name(name, "dragModel").unwrap();
            if c == DragClosure::PlessisMasliyah {
                continue;
            }
            let b = c.coefficient(&q) / q.stokes();
            let tol = if c == DragClosure::DiFelice {
                0.05
            } else {
                1e-3
            };
            assert!((b - 1.0).abs() < tol, "{name}: {b}");
        }
    }
}
