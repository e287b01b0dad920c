//! Sedimentation in a fully periodic box: the mean pressure gradient that carries the
//! suspension's weight.
//!
//! In a closed container the bottom carries the weight of the whole mixture: the mean
//! pressure gradient is the mixture's hydrostatic one, `∇P = ρ_m g` with
//! `ρ_m = (1−φ) ρ_f + φ ρ_p`. A periodic box has no bottom, so that gradient must be imposed,
//! otherwise the mixture falls freely. fsim's fluid already carries its own weight in its
//! (kinematic) pressure, `p = p' + ρ_f g·x` with only `p'` computed, and the particles feel the
//! matching buoyancy `−V_i ρ_f g` in the DEM (paper eq. 1, the `f_h0` of eq. 4). What is left
//! is the excess
//!
//! ```text
//! ∇P_s = (ρ_m − ρ_f) g = (1/V) Σ_i V_i (ρ_i − ρ_f) g          (V: box volume; free particles)
//! ```
//!
//! which acts, as any mean pressure gradient does, on every volume element: on the fluid as a
//! uniform body force per unit mass `b = −∇P_s/ρ_f` (an upward push: the fluid carries the
//! particles), and on each particle as the extra buoyancy `−V_i ∇P_s` (the stress integral of
//! the periodic pressure `p'` cannot contain this linear part: the direct model adds it as
//! `ρ_f b V`, the `f_h0` of paper eq. 4, from the fluid's body force).
//!
//! Momentum balance of the mixture (hydrodynamic forces are internal and cancel):
//!
//! ```text
//! d/dt [ρ_f ∫_fluid u dV + Σ m_i v_i]
//!   = (V − V_s) ρ_f b + Σ_i [(ρ_i − ρ_f) V_i g − V_i ∇P_s]            (V_s = Σ V_i)
//!   = −(V − V_s) ∇P_s + V ∇P_s − V_s ∇P_s = 0.
//! ```
//!
//! So a suspension released from rest keeps zero total momentum: in steady settling the
//! fluid streams up through the falling particles, `(1−φ) ρ_f ⟨u_f⟩ + φ ρ_p ⟨v_p⟩ = 0`. The
//! slip velocity `⟨v_p⟩ − ⟨u_f⟩` does not depend on the frame; the settling velocity of
//! Richardson & Zaki (paper eq. 21) is measured in a container, where the volume flux
//! `j = (1−φ)⟨u_f⟩ + φ⟨v_p⟩` vanishes, and so is `v_m = ⟨v_p⟩ − j = (1−φ)(⟨v_p⟩ − ⟨u_f⟩)`
//! ([`SettlingDrive::settling_velocity`]).
//!
//! The gradient applies only when nothing else carries the weight: every axis along which
//! gravity acts is periodic and no particle is fixed (fixed spheres hold the mixture).

// Plain indexed loops over the particle arrays, by design.
#![allow(clippy::needless_range_loop)]

use crate::particles::ParticleState;
use crate::Vec3;

/// The imposed excess mean pressure gradient of periodic sedimentation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SettlingDrive {
    /// `∇P_s = (ρ_m − ρ_f) g`, Pa/m.
    pub gradient: Vec3,
    /// Fluid density ρ_f, kg/m³.
    pub fluid_density: f64,
}

impl SettlingDrive {
    /// The drive for the free particles `p` in a box of volume `box_volume` (m³) under
    /// `gravity` (m/s²); `None` when something else carries the weight (an axis of gravity
    /// is not periodic, a particle is fixed) or there is nothing to carry.
    pub fn new(
        p: &ParticleState,
        fluid_density: f64,
        gravity: Vec3,
        periodic: [bool; 3],
        box_volume: f64,
    ) -> Option<Self> {
        let carried_elsewhere = (0..3).any(|a| gravity[a] != 0.0 && !periodic[a]);
        if carried_elsewhere || p.is_empty() || p.fixed.iter().any(|&f| f) {
            return None;
        }
        let excess_mass: f64 = (0..p.len())
            .map(|i| p.mass(i) * (1.0 - fluid_density / p.density[i]))
            .sum();
        let gradient = gravity.map(|g| excess_mass * g / box_volume);
        if gradient == Vec3::zeros() {
            return None;
        }
        Some(SettlingDrive {
            gradient,
            fluid_density,
        })
    }

    /// The uniform body force per unit mass on the fluid, `b = −∇P_s/ρ_f` (m/s²).
    pub fn fluid_acceleration(&self) -> Vec3 {
        self.gradient.map(|g| -g / self.fluid_density)
    }

    /// The extra buoyancy `−V ∇P_s` (N) on a particle of volume `volume`. The direct model's
    /// stress integral already adds it, as `ρ_f b V_R` of the fluid's body force `b`
    /// (`DirectCoupling::compute_loads`); this is the term by itself, for checks.
    pub fn particle_force(&self, volume: f64) -> Vec3 {
        self.gradient.map(|g| -volume * g)
    }

    /// The settling velocity in the frame of zero volume flux (a container's), from the
    /// particles' mean velocity `v_p`, the fluid's mean over the fluid volume `u_f` and the
    /// solid fraction `phi`: `(1−φ)(v_p − u_f)`.
    pub fn settling_velocity(v_p: Vec3, u_f: Vec3, phi: f64) -> Vec3 {
        Vec3::from_fn(|a, _| (1.0 - phi) * (v_p[a] - u_f[a]))
    }
}

/// Total momentum of fluid and particles (kg m/s): `ρ_f V ⟨u⟩_box + Σ (m_i − ρ_f V_i) v_i`.
///
/// The grid's fluid fills the whole box, the particles' interiors included, where the
/// direct model makes it move with the particle; `⟨u⟩_box` is its volume mean, so the
/// interior share `ρ_f V_i v_i` is taken back out of each particle's term.
pub fn mixture_momentum(
    fluid_density: f64,
    box_volume: f64,
    box_mean_velocity: Vec3,
    p: &ParticleState,
) -> Vec3 {
    let mut m = box_mean_velocity.map(|u| fluid_density * box_volume * u);
    for i in 0..p.len() {
        let excess = p.mass(i) * (1.0 - fluid_density / p.density[i]);
        for a in 0..3 {
            m[a] += excess * p.velocity[i][a];
        }
    }
    m
}

/// Mean fluid velocity over the fluid volume (m/s) from the box mean: the particles'
/// interiors move with the particles, `⟨u⟩_f = (V⟨u⟩_box − Σ V_i v_i)/(V − Σ V_i)`.
pub fn fluid_mean_velocity(box_volume: f64, box_mean_velocity: Vec3, p: &ParticleState) -> Vec3 {
    let mut sum = box_mean_velocity.map(|u| u * box_volume);
    let mut solid = 0.0;
    for i in 0..p.len() {
        let v = p.mass(i) / p.density[i];
        solid += v;
        for a in 0..3 {
            sum[a] -= v * p.velocity[i][a];
        }
    }
    sum.map(|s| s / (box_volume - solid))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cloud(n: usize, d: f64, rho: f64) -> ParticleState {
        let mut p = ParticleState::default();
        for i in 0..n {
            p.push(i as u64, [0.1 * i as f64, 0.0, 0.0], d, rho);
        }
        p
    }

    /// The drive's forces and the DEM's weight with buoyancy sum to zero over the mixture:
    /// the momentum balance of the module documentation, evaluated term by term.
    #[test]
    fn forces_on_the_mixture_balance() {
        let (rho_f, rho_p, d, n, volume) = (1.2, 1500.0, 1e-4, 50, 4e-9);
        let g = [0.0, -9.81, 0.0];
        let p = cloud(n, d, rho_p);
        let drive = SettlingDrive::new(&p, rho_f, Vec3::from(g), [true; 3], volume).unwrap();
        let vp = std::f64::consts::PI * d * d * d / 6.0;
        let phi = n as f64 * vp / volume;
        let expected = phi * (rho_p - rho_f) * g[1];
        assert!((drive.gradient[1] - expected).abs() < 1e-12 * expected.abs());
        let f: Vec<Vec3> = (0..n).map(|_| drive.particle_force(vp)).collect();
        let weight: f64 = (0..n)
            .map(|i| p.mass(i) * (1.0 - rho_f / rho_p) * g[1] + f[i][1])
            .sum();
        let fluid = rho_f * (volume - n as f64 * vp) * drive.fluid_acceleration()[1];
        assert!(
            (weight + fluid).abs() < 1e-12 * (n as f64 * p.mass(0) * 9.81),
            "net {}",
            weight + fluid
        );
        // each particle keeps (1−φ) of its buoyant weight
        let each = p.mass(0) * (1.0 - rho_f / rho_p) * g[1] + f[0][1];
        let kept = (1.0 - phi) * p.mass(0) * (1.0 - rho_f / rho_p) * g[1];
        assert!((each - kept).abs() < 1e-12 * kept.abs());
    }

    #[test]
    fn none_when_something_else_carries_the_weight() {
        let g = [0.0, 0.0, -9.81];
        let mut p = cloud(3, 1e-3, 2500.0);
        assert!(SettlingDrive::new(&p, 1000.0, Vec3::from(g), [true, true, false], 1.0).is_none());
        assert!(SettlingDrive::new(&p, 1000.0, Vec3::zeros(), [true; 3], 1.0).is_none());
        assert!(SettlingDrive::new(&p, 2500.0, Vec3::from(g), [true; 3], 1.0).is_none());
        p.fixed[1] = true;
        assert!(SettlingDrive::new(&p, 1000.0, Vec3::from(g), [true; 3], 1.0).is_none());
    }

    /// Fluid streaming up through falling particles at zero total momentum: the momentum is
    /// zero, and the container-frame velocity is (1−φ) times the slip.
    #[test]
    fn momentum_and_frames() {
        let (rho_f, rho_p, volume) = (1000.0, 2500.0, 1.0);
        let mut p = cloud(10, 0.2, rho_p);
        let vp: f64 = (0..10).map(|i| p.mass(i) / rho_p).sum();
        let phi = vp / volume;
        let v = -0.01;
        for i in 0..10 {
            p.velocity[i] = Vec3::new(0.0, 0.0, v);
        }
        // zero momentum: (1−φ) ρ_f u_f + φ ρ_p v = 0
        let u_f = -phi * rho_p * v / ((1.0 - phi) * rho_f);
        let box_mean = ((1.0 - phi) * u_f + phi * v) * 1.0;
        let m = mixture_momentum(rho_f, volume, Vec3::new(0.0, 0.0, box_mean), &p);
        assert!(m[2].abs() < 1e-12 * rho_p * vp * v.abs(), "{m:?}");
        let uf = fluid_mean_velocity(volume, Vec3::new(0.0, 0.0, box_mean), &p);
        assert!((uf[2] - u_f).abs() < 1e-14);
        let vm = SettlingDrive::settling_velocity(Vec3::new(0.0, 0.0, v), uf, phi);
        let j = (1.0 - phi) * u_f + phi * v;
        assert!((vm[2] - (v - j)).abs() < 1e-14);
    }
}
