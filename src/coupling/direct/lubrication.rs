//! Normal lubrication correction for gaps narrower than the grid resolves.
//!
//! When two spheres approach, the film between them is squeezed and its pressure resists the
//! approach with a force that diverges as the gap `ζ` closes. To leading order in `ζ/R`
//! (Brenner 1961, Cox 1974; Kim & Karrila 1991, §9) the force on a sphere approaching another
//! sphere or a plane wall along the line of centres `n` is
//!
//! ```text
//! F = −6 π μ R_eff² (u_rel·n) n / ζ,      R_eff = a_i a_j / (a_i + a_j)   (wall: R_eff = a_i)
//! ```
//!
//! The grid resolves this film while it is a few cells wide; below about one cell the
//! resolved force falls short. As in Ladd & Verberg (2001, the paper's ref. \[16\]), Breugem
//! (2010) and Kempe & Fröhlich (2012, J. Fluid Mech. 709), only the part the grid misses is
//! added, with a cut-off `ζ_c` (`h`) where the correction vanishes continuously and a
//! saturation gap `ζ_min` (`10⁻³ R_eff`, Breugem's surface roughness) below which the
//! coefficient stays constant and the DEM contact takes over:
//!
//! ```text
//! c(ζ) = 6 π μ R_eff² (1/max(ζ, ζ_min) − 1/ζ_c)   for ζ < ζ_c,   0 otherwise
//! ```
//!
//! The coefficient grows without bound as `ζ_min → 0`, far beyond what an explicit force can
//! follow over a fluid step (`Δt c/m_eff` reaches 10³ in a gas). Over one step the pair's
//! relative normal velocity obeys `m_eff du/dt = −c u`, whose exact solution decays by
//! `e^{−γΔt}` with `γ = c/m_eff`; fsim applies the constant force with the same impulse,
//!
//! ```text
//! F_i = c (1 − e^{−γΔt})/(γΔt) · ((u_j − u_i)·n) n,     F_j = −F_i,
//! ```
//!
//! which equals the formula above when `γΔt ≪ 1` and can never reverse the approach (it is
//! stable for any `Δt`). Tangential and rotational lubrication (logarithmic in `ζ`) are left
//! to the resolved flow.

// Hot loops are plain indexed loops over contiguous arrays, by design.
#![allow(clippy::needless_range_loop)]

use super::close_pairs::{ClosePairs, PeriodicBox};
use super::tuning::LUBRICATION_MIN_GAP;
use crate::particles::ParticleState;
use crate::Vec3;
use std::f64::consts::PI;

/// Settings and scratch space of the lubrication correction.
#[derive(Clone, Debug)]
pub struct Lubrication {
    /// Dynamic viscosity μ = ρ_f ν, Pa s.
    pub mu: f64,
    /// Gap `ζ_c` below which the correction acts, m.
    pub cutoff: f64,
    /// Saturation gap over the pair's effective radius (`ζ_min / R_eff`).
    pub min_gap_ratio: f64,
    pairs: ClosePairs,
    /// Scratch of [`Self::add_forces`]: each particle's inverse mass (0 when fixed).
    inv_mass: Vec<f64>,
}

/// What the correction did in one call.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LubricationReport {
    /// Pairs and wall contacts inside the cut-off.
    pub active: usize,
    /// Smallest surface gap over the smaller radius (pairs and walls), `f64::INFINITY` when
    /// there is no neighbour within range.
    pub min_gap_ratio: f64,
}

/// The box as the correction sees it: periodic axes and no-slip walls.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LubricationBox {
    pub lo: Vec3,
    pub hi: Vec3,
    pub periodic: [bool; 3],
    /// No-slip walls in the face order `x−, x+, y−, y+, z−, z+`.
    pub walls: [bool; 6],
}

impl LubricationBox {
    fn periodic_box(&self) -> PeriodicBox {
        PeriodicBox {
            lo: self.lo,
            hi: self.hi,
            periodic: self.periodic,
        }
    }
}

impl Lubrication {
    /// Correction in a fluid of viscosity `mu` (Pa s), acting below the gap `cutoff` (m).
    pub fn new(mu: f64, cutoff: f64) -> Self {
        Lubrication {
            mu,
            cutoff,
            min_gap_ratio: LUBRICATION_MIN_GAP,
            pairs: ClosePairs::default(),
            inv_mass: Vec::new(),
        }
    }

    /// The damping coefficient `c(ζ)` (N s/m) for effective radius `r_eff` and gap `gap`.
    pub fn coefficient(&self, r_eff: f64, gap: f64) -> f64 {
        coefficient(self.mu, self.cutoff, self.min_gap_ratio, r_eff, gap)
    }

    /// Adds the correction for every pair and wall closer than the cut-off to `forces`
    /// (index order of `p`), for a fluid step `dt` (0: the plain formula, no step limit).
    pub fn add_forces(
        &mut self,
        p: &ParticleState,
        domain: &LubricationBox,
        dt: f64,
        forces: &mut [Vec3],
    ) -> LubricationReport {
        let n = p.len();
        let mut report = LubricationReport {
            active: 0,
            min_gap_ratio: f64::INFINITY,
        };
        if n == 0 || self.cutoff <= 0.0 {
            return report;
        }
        self.inv_mass.clear();
        self.inv_mass
            .extend((0..n).map(|i| if p.fixed[i] { 0.0 } else { 1.0 / p.mass(i) }));
        let inv_mass = &self.inv_mass;
        let cutoff = self.cutoff;
        let (mu, min_ratio) = (self.mu, self.min_gap_ratio);
        self.pairs
            .visit(p, &domain.periodic_box(), cutoff, |i, j, d, dist, gap| {
                let (ri, rj) = (p.diameter[i] / 2.0, p.diameter[j] / 2.0);
                report.min_gap_ratio = report.min_gap_ratio.min(gap / ri.min(rj));
                let inv_m = inv_mass[i] + inv_mass[j];
                if inv_m == 0.0 || dist == 0.0 {
                    return;
                }
                let normal = scale(d, 1.0 / dist);
                let approach = dot(sub(p.velocity[j], p.velocity[i]), normal);
                let c = damped(
                    coefficient(mu, cutoff, min_ratio, ri * rj / (ri + rj), gap),
                    inv_m,
                    dt,
                );
                report.active += 1;
                for a in 0..3 {
                    let f = c * approach * normal[a];
                    forces[i][a] += f;
                    forces[j][a] -= f;
                }
            });
        for i in 0..n {
            if inv_mass[i] == 0.0 {
                continue;
            }
            let r = p.diameter[i] / 2.0;
            for face in 0..6 {
                if !domain.walls[face] {
                    continue;
                }
                let (axis, upper) = (face / 2, face % 2 == 1);
                let x = p.position[i][axis];
                let gap = if upper {
                    domain.hi[axis] - x - r
                } else {
                    x - domain.lo[axis] - r
                };
                if gap >= self.cutoff {
                    continue;
                }
                report.min_gap_ratio = report.min_gap_ratio.min(gap / r);
                // normal from the particle towards the wall
                let sign = if upper { 1.0 } else { -1.0 };
                let approach = -sign * p.velocity[i][axis];
                let c = damped(self.coefficient(r, gap), inv_mass[i], dt);
                report.active += 1;
                forces[i][axis] += c * approach * sign;
            }
        }
        report
    }
}

/// `c(ζ) = 6 π μ R_eff² (1/max(ζ, ζ_min) − 1/ζ_c)` below the cut-off, else 0 (N s/m).
fn coefficient(mu: f64, cutoff: f64, min_gap_ratio: f64, r_eff: f64, gap: f64) -> f64 {
    if gap >= cutoff {
        return 0.0;
    }
    let zeta = gap.max(min_gap_ratio * r_eff);
    (6.0 * PI * mu * r_eff * r_eff * (1.0 / zeta - 1.0 / cutoff)).max(0.0)
}

/// The coefficient that gives, as a constant force over `dt`, the impulse of the exact decay
/// of the relative velocity: `c (1 − e^{−γΔt})/(γΔt)`, `γ = c/m_eff`.
fn damped(c: f64, inv_m_eff: f64, dt: f64) -> f64 {
    let x = c * inv_m_eff * dt;
    if x < 1e-8 {
        c
    } else {
        c * (-(-x).exp_m1()) / x
    }
}

fn sub(a: Vec3, b: Vec3) -> Vec3 {
    Vec3::new(a[0] - b[0], a[1] - b[1], a[2] - b[2])
}

fn scale(a: Vec3, s: f64) -> Vec3 {
    Vec3::new(a[0] * s, a[1] * s, a[2] * s)
}

fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn periodic_box(l: f64) -> LubricationBox {
        LubricationBox {
            lo: Vec3::zeros(),
            hi: Vec3::repeat(l),
            periodic: [true; 3],
            walls: [false; 6],
        }
    }

    fn two_spheres(a: f64, gap: f64, speed: f64) -> ParticleState {
        let mut p = ParticleState::default();
        p.push(1, [0.5, 0.5, 0.5], 2.0 * a, 2500.0);
        p.push(2, [0.5 + 2.0 * a + gap, 0.5, 0.5], 2.0 * a, 2500.0);
        // approaching each other at `speed` in total
        p.velocity[0] = Vec3::new(speed / 2.0, 0.0, 0.0);
        p.velocity[1] = Vec3::new(-speed / 2.0, 0.0, 0.0);
        p
    }

    /// Equal spheres: `F = 6πμ (a/2)² U (1/ζ − 1/ζ_c)`, i.e. `(3/2) π μ a² U/ζ` less the
    /// resolved part (Brenner 1961 to leading order).
    #[test]
    fn pair_force_matches_the_asymptotic_formula() {
        let (mu, a, u) = (1.8e-5, 0.05, 0.01);
        let mut lub = Lubrication::new(mu, 0.01);
        for gap in [1e-3, 3e-3, 5e-3] {
            let p = two_spheres(a, gap, u);
            let mut f = vec![Vec3::zeros(); 2];
            let report = lub.add_forces(&p, &periodic_box(1.0), 0.0, &mut f);
            let expected = 1.5 * PI * mu * a * a * u * (1.0 / gap - 1.0 / 0.01);
            assert_eq!(report.active, 1);
            assert!(
                (f[0][0] + expected).abs() < 1e-12 * expected,
                "{f:?} vs {expected}"
            );
            assert_eq!(f[1][0], -f[0][0]);
            assert!((report.min_gap_ratio - gap / a).abs() < 1e-9);
        }
    }

    #[test]
    fn vanishes_at_the_cutoff_and_saturates_below_the_minimum_gap() {
        let lub = Lubrication::new(1e-3, 0.01);
        assert_eq!(lub.coefficient(0.1, 0.01), 0.0);
        assert_eq!(lub.coefficient(0.1, 0.02), 0.0);
        let small = lub.coefficient(0.1, 0.5e-4);
        assert_eq!(small, lub.coefficient(0.1, 1e-4));
        assert_eq!(small, lub.coefficient(0.1, -1e-3));
        assert!((small - 6.0 * PI * 1e-3 * 0.01 * (1e4 - 100.0)).abs() < 1e-9 * small);
    }

    /// Sphere approaching a plane wall: `F = 6πμ a² U (1/ζ − 1/ζ_c)`.
    #[test]
    fn wall_force_matches_the_asymptotic_formula() {
        let (mu, a, gap, u) = (1e-3, 0.01, 1e-4, 0.02);
        let mut p = ParticleState::default();
        p.push(1, [0.5, 0.5, a + gap], 2.0 * a, 1000.0);
        p.velocity[0] = Vec3::new(0.0, 0.0, -u);
        let mut domain = periodic_box(1.0);
        domain.periodic[2] = false;
        domain.walls[4] = true;
        domain.walls[5] = true;
        let mut lub = Lubrication::new(mu, 1e-3);
        let mut f = vec![Vec3::zeros()];
        let report = lub.add_forces(&p, &domain, 0.0, &mut f);
        let expected = 6.0 * PI * mu * a * a * u * (1.0 / gap - 1.0 / 1e-3);
        assert_eq!(report.active, 1);
        assert!((f[0][2] - expected).abs() < 1e-12 * expected);
    }

    /// The step-limited force takes out at most the whole approach in one step, and tends to
    /// the formula as `Δt → 0`.
    #[test]
    fn step_limited_force_never_reverses_the_approach() {
        let (mu, a, gap, u) = (1.8e-5, 50e-6, 1e-8, 0.05);
        let mut lub = Lubrication::new(mu, 20e-6);
        let p = two_spheres(a, gap, u);
        let m_eff = p.mass(0) / 2.0;
        for dt in [1e-9, 1e-6, 1e-4, 1e-2] {
            let mut f = vec![Vec3::zeros(); 2];
            lub.add_forces(&p, &periodic_box(1.0), dt, &mut f);
            let dv = -f[0][0] * dt / m_eff; // change of relative approach speed
            assert!(dv > 0.0 && dv <= u * (1.0 + 1e-12), "dt {dt}: dv {dv}");
        }
        let c = lub.coefficient(a / 2.0, gap);
        let mut f = vec![Vec3::zeros(); 2];
        lub.add_forces(&p, &periodic_box(1.0), 1e-15, &mut f);
        assert!((f[0][0] + c * u).abs() < 1e-6 * c * u);
    }
}
