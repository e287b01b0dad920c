//! Freely moving spheres in the direct model: what the coupled step adds to the stress
//! integral before the DEM moves the particles.
//!
//! One fluid step `Δt` of the coupled scheme (explicit, staggered in the manner of the
//! paper's §2.1):
//!
//! ```text
//! spheres ← DEM particles (x_p, v_p, ω_p at t)           (DirectCoupling::set_particles)
//! fluid   ← t → t+Δt with no-slip on every sphere        (FluidSolver::step_with)
//! F_h, T_h ← stress integral at t+Δt (paper eq. 4–6)      (DirectCoupling::compute_loads)
//! F_ext   ← F_h + F_lub (lubrication below the grid's reach, ParticleMotion::set_loads)
//! DEM     ← t → t+Δt in collision sub-steps, with F_ext, T_h held fixed and, in each
//!           sub-step, gravity with buoyancy m (1 − ρ_f/ρ_p) g and the contacts
//!           (paper eq. 1: m dv/dt = f_g + f_h0 + f_h + f_n + f_t)
//! ```
//!
//! In a fully periodic box the mean pressure gradient of [`SettlingDrive`] is the fluid's
//! body force; the stress integral returns its share on each particle (`f_h0`). The momentum
//! balance of the mixture then holds as well as the stress integral equals the reaction the
//! no-slip forcing exerts on the fluid: a force error `ε` on each of `N` spheres makes the
//! whole mixture accelerate at `N ε / M`. The mean pressure gradient of a periodic box is,
//! by definition, whatever keeps the mixture from accelerating, so fsim adds a correction
//! `b_c` to the analytic drive, as OpenFOAM's `meanVelocityForce` corrects its gradient to
//! hold a bulk velocity: after each step, with the mixture momentum `Mⁿ`,
//!
//! ```text
//! b_cⁿ⁺¹ = b_cⁿ − [(Mⁿ − Mⁿ⁻¹) + ½ Mⁿ] / (ρ_f V Δt)
//! ```
//!
//! (the first term cancels the current rate of change, the second returns `M` to zero by
//! half each step). `b_c` over the analytic drive is reported (`driveCorrection` in the
//! sedimentation monitor): it measures the momentum defect of the stress integral
//! (docs/numerics.md, "Sedimentation in a periodic box").
//!
//! Stability: the hydrodynamic force is lagged by one step. Its added-mass part
//! (`−m_a dv/dt`, from the fluid carried inside and near the sphere, whose velocity the
//! no-slip imposition changes at once) then feeds the particle's last acceleration back with
//! the gain `−m_a/m_p`: the plain explicit coupling diverges, alternating in sign, once
//! `m_a > m_p`, i.e. for particles not much heavier than the fluid. fsim splits a virtual
//! mass `m_v = C_v ρ_f V` off the hydrodynamic force (Schwarz, Kempe & Fröhlich, J. Comput.
//! Phys. 281, 2015): with `a⁻` the particle's acceleration over the previous step,
//!
//! ```text
//! (m_p + m_v) dv/dt = F_h + m_v a⁻ + m_p g (1 − ρ_f/ρ_p)          (contacts act on m_p alone)
//! ```
//!
//! whose feedback gain is `(m_v − m_a)/(m_p + m_v)`, below one in magnitude for any
//! `m_v > (m_a − m_p)/2`; the steady state is unchanged (`a⁻ → 0`). The DEM keeps the bare
//! mass, so the external force handed to it is
//! `F_ext = [m_p F_h + m_p m_v a⁻ − m_v m_p g (1 − ρ_f/ρ_p)]/(m_p + m_v)`; the torque likewise
//! with `I_v = C_v (ρ_f/ρ_p) I_p`. `virtualMass C_v;` in `constant/couplingProperties`
//! (default [`DEFAULT_VIRTUAL_MASS`]; 0: the plain explicit coupling).
//!
//! [`ParticleMotion::new`] refuses free particles lighter than [`MIN_DENSITY_RATIO`] times
//! the fluid, twice the lightest shown stable (thresholds per scheme: docs/direct_model.md,
//! "Time stepping").

// Plain indexed loops over the particle arrays, by design.
#![allow(clippy::needless_range_loop)]

use crate::Vec3;
use std::collections::HashMap;

use super::lubrication::{Lubrication, LubricationBox, LubricationReport};
use super::response_time::coupling_step_bound;
use super::settling_drive::{fluid_mean_velocity, mixture_momentum, SettlingDrive};
use super::tuning::{DRIVE_MOMENTUM_GAIN, LUBRICATION_CUTOFF_CELLS};
use crate::fluid::{BoundaryConditions, FaceCondition};
use crate::grid::Grid;
use crate::particles::{Dem, ParticleState};

/// Default virtual-mass coefficient `C_v`.
pub use super::tuning::DEFAULT_VIRTUAL_MASS;
/// Lowest particle-to-fluid density ratio the coupling accepts (the lightest tried stable
/// with the virtual mass was 0.1).
pub use super::tuning::MIN_DENSITY_RATIO;

/// Settings of the moving spheres in `constant/couplingProperties`:
///
/// ```text
/// virtualMass     2;       // C_v: virtual mass C_v ρ_f V split off the lagged force
///                          // (0: the paper's plain explicit coupling)
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionSettings {
    /// `virtualMass C_v;` at the top level of the file (stabilises the explicit coupling).
    pub virtual_mass: f64,
}

impl Default for MotionSettings {
    fn default() -> Self {
        MotionSettings {
            virtual_mass: DEFAULT_VIRTUAL_MASS,
        }
    }
}

/// What the settling monitor records after a step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SedimentationReport {
    /// Solid fraction of the free particles.
    pub phi: f64,
    /// Mean particle velocity, m/s.
    pub particle_velocity: Vec3,
    /// Mean fluid velocity over the fluid volume, m/s.
    pub fluid_velocity: Vec3,
    /// Settling velocity along gravity in the frame of zero volume flux, m/s (positive:
    /// falling).
    pub settling_velocity: f64,
    /// Total momentum of fluid and particles, kg m/s.
    pub momentum: Vec3,
    /// Momentum scale `Σ m_i |v_i|`, kg m/s (to judge the total against).
    pub momentum_scale: f64,
    /// The imposed excess mean pressure gradient, Pa/m (zero without a drive).
    pub drive_gradient: Vec3,
    /// The momentum-holding correction over the analytic drive, `|b_c| / |b|`.
    pub drive_correction: f64,
}

/// Lubrication, the periodic-settling drive and the settling monitor of one run.
pub struct ParticleMotion {
    lubrication: Lubrication,
    lubrication_box: LubricationBox,
    drive: Option<SettlingDrive>,
    fluid_density: f64,
    gravity: Vec3,
    box_volume: f64,
    /// Scratch of [`Self::set_loads`]: the particles' forces and torques.
    forces: Vec<Vec3>,
    torques: Vec<Vec3>,
    last_lubrication: LubricationReport,
    virtual_mass: f64,
    /// Velocity and angular velocity of each particle (by id) at the start of the last step,
    /// with that step's size.
    previous: HashMap<u64, (Vec3, Vec3)>,
    previous_dt: f64,
    /// The drive's correction `b_c` (m/s²) and the mixture momentum after the last step.
    correction: Vec3,
    last_momentum: Option<Vec3>,
    /// The largest step the explicit coupling takes, s ([`coupling_step_bound`]).
    step_bound: f64,
}

impl ParticleMotion {
    /// For the particles of `dem` in a fluid of density `rho` (kg/m³) and viscosity `nu`
    /// (m²/s) on `grid` with conditions `bc`. Fails for free particles lighter than
    /// [`MIN_DENSITY_RATIO`] times the fluid.
    pub fn new(
        settings: MotionSettings,
        grid: &Grid,
        bc: &BoundaryConditions,
        dem: &Dem,
        rho: f64,
        nu: f64,
    ) -> Result<Self, String> {
        let p = dem.particles();
        if let Some(i) =
            (0..p.len()).find(|&i| !p.fixed[i] && p.density[i] < MIN_DENSITY_RATIO * rho)
        {
            return Err(format!(
                "particle {} has density {} kg/m3, {:.3} times the fluid's: the direct model's \
                 explicit coupling is not known to be stable for free particles lighter than \
                 {MIN_DENSITY_RATIO} times the fluid (added mass); fix the particles \
                 (fixedParticles yes) or use model dragLaw",
                p.id[i],
                p.density[i],
                p.density[i] / rho
            ));
        }
        let length = grid.length();
        let hi = Vec3::from_fn(|a, _| grid.origin[a] + length[a]);
        let periodic: [bool; 3] =
            std::array::from_fn(|a| matches!(bc.faces[2 * a], FaceCondition::Periodic));
        let walls: [bool; 6] =
            std::array::from_fn(|f| matches!(bc.faces[f], FaceCondition::Wall { .. }));
        let h = grid.h.iter().cloned().fold(0.0, f64::max);
        let lubrication = Lubrication::new(rho * nu, LUBRICATION_CUTOFF_CELLS * h);
        let box_volume = length[0] * length[1] * length[2];
        let gravity = dem.config().gravity;
        Ok(ParticleMotion {
            lubrication,
            lubrication_box: LubricationBox {
                lo: grid.origin.into(),
                hi,
                periodic,
                walls,
            },
            drive: SettlingDrive::new(p, rho, gravity, periodic, box_volume),
            fluid_density: rho,
            gravity,
            box_volume,
            forces: Vec::new(),
            torques: Vec::new(),
            last_lubrication: LubricationReport::default(),
            virtual_mass: settings.virtual_mass,
            previous: HashMap::new(),
            previous_dt: 0.0,
            correction: Vec3::zeros(),
            last_momentum: None,
            step_bound: coupling_step_bound(p, rho * nu),
        })
    }

    /// The periodic-settling drive, when the box needs one.
    pub fn drive(&self) -> Option<&SettlingDrive> {
        self.drive.as_ref()
    }

    /// The largest step the explicit coupling of the free spheres takes, s (infinite when
    /// every sphere is fixed): [`coupling_step_bound`].
    pub fn step_bound(&self) -> f64 {
        self.step_bound
    }

    /// The fluid's body force per unit mass, m/s² (the drive's with its correction, or zero).
    pub fn fluid_body_force(&self) -> Vec3 {
        match self.drive {
            Some(d) => {
                let b = d.fluid_acceleration();
                Vec3::from_fn(|a, _| b[a] + self.correction[a])
            }
            None => Vec3::zeros(),
        }
    }

    /// Updates the drive's correction from the mixture's `momentum` after a step of `dt`
    /// (module documentation) and returns the fluid's new body force.
    pub fn hold_zero_momentum(&mut self, momentum: Vec3, dt: f64) -> Vec3 {
        if self.drive.is_some() && dt > 0.0 {
            let previous = self.last_momentum.unwrap_or(Vec3::zeros());
            let scale = 1.0 / (self.fluid_density * self.box_volume * dt);
            for a in 0..3 {
                self.correction[a] -=
                    (momentum[a] - previous[a] + DRIVE_MOMENTUM_GAIN * momentum[a]) * scale;
            }
            self.last_momentum = Some(momentum);
        }
        self.fluid_body_force()
    }

    /// Sets the DEM's external loads for the coming step `dt`: the hydrodynamic `loads`
    /// (force, torque; index order of [`Dem::particles`]) plus the lubrication correction,
    /// with the virtual mass split off (module documentation).
    pub fn set_loads(
        &mut self,
        dem: &mut Dem,
        loads: impl Iterator<Item = (Vec3, Vec3)>,
        dt: f64,
    ) -> LubricationReport {
        let n = dem.particles().len();
        self.forces.clear();
        self.forces.resize(n, Vec3::zeros());
        self.last_lubrication = self.lubrication.add_forces(
            dem.particles(),
            &self.lubrication_box,
            dt,
            &mut self.forces,
        );
        let mut torques = std::mem::take(&mut self.torques);
        torques.clear();
        torques.resize(n, Vec3::zeros());
        for (i, (f, t)) in loads.take(n).enumerate() {
            for a in 0..3 {
                self.forces[i][a] += f[a];
            }
            torques[i] = t;
        }
        if self.virtual_mass > 0.0 {
            self.split_virtual_mass(dem.particles(), &mut torques, dt);
        }
        let (f_ext, t_ext) = dem.external_loads_mut();
        f_ext.copy_from_slice(&self.forces);
        t_ext.copy_from_slice(&torques);
        self.torques = torques;
        self.last_lubrication
    }

    /// Turns the hydrodynamic loads in `self.forces`, `torques` into the external loads that
    /// give the virtual-mass update with the DEM's bare masses, and records the velocities.
    fn split_virtual_mass(&mut self, p: &ParticleState, torques: &mut [Vec3], dt: f64) {
        let (rho_f, c_v, g) = (self.fluid_density, self.virtual_mass, self.gravity);
        let span = self.previous_dt;
        for i in 0..p.len() {
            if p.fixed[i] {
                continue;
            }
            let m = p.mass(i);
            let ratio = rho_f / p.density[i];
            let m_v = c_v * ratio * m;
            let inertia = p.moment_of_inertia(i);
            let i_v = c_v * ratio * inertia;
            let (v, w) = (p.velocity[i], p.angular_velocity[i]);
            let (a_prev, alpha_prev) = match self.previous.get(&p.id[i]) {
                Some((v0, w0)) if span > 0.0 => (
                    Vec3::from_fn(|a, _| (v[a] - v0[a]) / span),
                    Vec3::from_fn(|a, _| (w[a] - w0[a]) / span),
                ),
                _ => (Vec3::zeros(), Vec3::zeros()),
            };
            for a in 0..3 {
                let weight = m * g[a] * (1.0 - ratio);
                self.forces[i][a] =
                    (m * self.forces[i][a] + m * m_v * a_prev[a] - m_v * weight) / (m + m_v);
                torques[i][a] =
                    (inertia * torques[i][a] + inertia * i_v * alpha_prev[a]) / (inertia + i_v);
            }
            self.previous.insert(p.id[i], (v, w));
        }
        self.previous_dt = dt;
    }

    /// Name of the restart array of [`Self::restart_state`].
    pub const RESTART_NAME: &'static str = "direct.motion";

    /// What a bit-identical continuation needs: the drive's correction, the last mixture
    /// momentum, the last step and each particle's velocities at its start (by id, sorted):
    /// `[b_c(3), M(3), has M, Δt, (id, v(3), ω(3))…]`.
    pub fn restart_state(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(8 + 7 * self.previous.len());
        out.extend_from_slice(self.correction.as_slice());
        out.extend_from_slice(self.last_momentum.unwrap_or(Vec3::zeros()).as_slice());
        out.push(if self.last_momentum.is_some() {
            1.0
        } else {
            0.0
        });
        out.push(self.previous_dt);
        let mut ids: Vec<&u64> = self.previous.keys().collect();
        ids.sort_unstable();
        for id in ids {
            let (v, w) = self.previous[id];
            out.push(*id as f64);
            out.extend_from_slice(v.as_slice());
            out.extend_from_slice(w.as_slice());
        }
        out
    }

    /// Restores what [`Self::restart_state`] saved.
    pub fn restore_state(&mut self, data: &[f64]) -> Result<(), String> {
        if data.len() < 8 || !(data.len() - 8).is_multiple_of(7) {
            return Err(format!(
                "restart array '{}' has {} values, not 8 + 7 per particle",
                Self::RESTART_NAME,
                data.len()
            ));
        }
        self.correction = Vec3::new(data[0], data[1], data[2]);
        self.last_momentum = (data[6] != 0.0).then_some(Vec3::new(data[3], data[4], data[5]));
        self.previous_dt = data[7];
        self.previous.clear();
        for row in data[8..].chunks_exact(7) {
            self.previous.insert(
                row[0] as u64,
                (
                    Vec3::new(row[1], row[2], row[3]),
                    Vec3::new(row[4], row[5], row[6]),
                ),
            );
        }
        Ok(())
    }

    /// The lubrication of the last [`Self::set_loads`].
    pub fn last_lubrication(&self) -> LubricationReport {
        self.last_lubrication
    }

    /// Settling velocity and momentum from the fluid's box-mean velocity and the particles.
    pub fn sedimentation(&self, box_mean_velocity: Vec3, p: &ParticleState) -> SedimentationReport {
        let free: Vec<usize> = (0..p.len()).filter(|&i| !p.fixed[i]).collect();
        let solid: f64 = free.iter().map(|&i| p.mass(i) / p.density[i]).sum();
        let phi = solid / self.box_volume;
        let mut vp = Vec3::zeros();
        let mut scale = 0.0;
        for &i in &free {
            let v = p.velocity[i];
            for a in 0..3 {
                vp[a] += v[a] / free.len().max(1) as f64;
            }
            scale += p.mass(i) * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        }
        let uf = fluid_mean_velocity(self.box_volume, box_mean_velocity, p);
        let g_norm = self.gravity.iter().map(|g| g * g).sum::<f64>().sqrt();
        let settling = if g_norm > 0.0 {
            let vm = SettlingDrive::settling_velocity(vp, uf, phi);
            (0..3).map(|a| vm[a] * self.gravity[a]).sum::<f64>() / g_norm
        } else {
            0.0
        };
        SedimentationReport {
            phi,
            particle_velocity: vp,
            fluid_velocity: uf,
            settling_velocity: settling,
            momentum: mixture_momentum(self.fluid_density, self.box_volume, box_mean_velocity, p),
            momentum_scale: scale,
            drive_gradient: self
                .drive
                // the total imposed gradient, correction included: −ρ_f b
                .map(|_| self.fluid_body_force().map(|x| -self.fluid_density * x))
                .unwrap_or(Vec3::zeros()),
            drive_correction: self
                .drive
                .map(|d| {
                    let b = d.fluid_acceleration();
                    let n = |v: Vec3| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                    n(self.correction) / n(b)
                })
                .unwrap_or(0.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::BoundaryConditions;
    use crate::particles::{DemConfig, DomainBox, FaceCondition, PairModel, WallModel};

    fn one_particle(rho_p: f64, rho_f: f64) -> Dem {
        let mut p = ParticleState::default();
        p.push(1, [0.5; 3], 0.1, rho_p);
        let mut config = DemConfig::new(
            PairModel::linear(1.0, 0.5, 0.3),
            WallModel::LinearSpringDashpot {
                kn: 1.0,
                restitution: 0.5,
                kt: 0.3,
                mu: 0.3,
                tangential_damping_ratio: 0.5,
                collision_resolution_steps: 20.0,
            },
        );
        config.gravity = Vec3::new(0.0, -9.81, 0.0);
        config.fluid_density = rho_f;
        Dem::new(
            config,
            DomainBox::uniform(Vec3::zeros(), [1.0; 3], FaceCondition::Periodic),
            p,
        )
        .unwrap()
    }

    /// A model of the lagged explicit coupling: `F_h = −m_a (vⁿ − vⁿ⁻¹)/Δt − c vⁿ` with the
    /// added mass `m_a = 3 ρ_f V` (the feedback measured for the direct model). At
    /// ρ_p/ρ_f = 2 the plain coupling diverges (gain −1.5); with `C_v = 2` it settles at the
    /// terminal velocity `m g (1 − ρ_f/ρ_p)/c`.
    #[test]
    fn virtual_mass_stabilises_the_lagged_added_mass() {
        let (rho_p, rho_f) = (2000.0, 1000.0);
        let grid = Grid::new([10; 3], [0.1; 3], [0.0; 3]);
        let bc = BoundaryConditions::periodic();
        let run = |c_v: f64| -> f64 {
            let mut dem = one_particle(rho_p, rho_f);
            let settings = MotionSettings { virtual_mass: c_v };
            let mut motion = ParticleMotion::new(settings, &grid, &bc, &dem, rho_f, 1e-3).unwrap();
            let m = dem.particles().mass(0);
            let m_a = 3.0 * rho_f / rho_p * m;
            let c = m / 0.05; // relaxation time 0.05 s
            let dt = 1e-3;
            let mut v_old = 0.0;
            for _ in 0..2000 {
                let v = dem.particles().velocity[0][1];
                let f = -m_a * (v - v_old) / dt - c * v;
                v_old = v;
                motion.set_loads(
                    &mut dem,
                    std::iter::once((Vec3::new(0.0, f, 0.0), Vec3::zeros())),
                    dt,
                );
                dem.advance(dt);
                if !v.is_finite() || v.abs() > 1e3 {
                    return f64::INFINITY;
                }
            }
            dem.particles().velocity[0][1] / (-m * 9.81 * (1.0 - rho_f / rho_p) / c)
        };
        assert!(run(0.0).is_infinite(), "the plain coupling should diverge");
        let ratio = run(2.0);
        assert!(
            (ratio - 1.0).abs() < 1e-3,
            "terminal velocity ratio {ratio}"
        );
    }

    #[test]
    fn restart_state_round_trips() {
        let grid = Grid::new([10; 3], [0.1; 3], [0.0; 3]);
        let bc = BoundaryConditions::periodic();
        let mut dem = one_particle(2500.0, 1000.0);
        let mut motion =
            ParticleMotion::new(MotionSettings::default(), &grid, &bc, &dem, 1000.0, 1e-3).unwrap();
        for _ in 0..3 {
            motion.set_loads(
                &mut dem,
                std::iter::once((Vec3::new(0.0, 1e-3, 0.0), Vec3::zeros())),
                1e-3,
            );
            dem.advance(1e-3);
            motion.hold_zero_momentum(Vec3::new(0.0, 1e-9, 0.0), 1e-3);
        }
        let saved = motion.restart_state();
        let mut other =
            ParticleMotion::new(MotionSettings::default(), &grid, &bc, &dem, 1000.0, 1e-3).unwrap();
        other.restore_state(&saved).unwrap();
        assert_eq!(other.restart_state(), saved);
        assert_eq!(other.fluid_body_force(), motion.fluid_body_force());
        assert!(other.restore_state(&saved[..9]).is_err());
    }

    #[test]
    fn light_free_particles_are_refused() {
        let grid = Grid::new([10; 3], [0.1; 3], [0.0; 3]);
        let bc = BoundaryConditions::periodic();
        let dem = one_particle(150.0, 1000.0);
        let err = ParticleMotion::new(MotionSettings::default(), &grid, &bc, &dem, 1000.0, 1e-3)
            .err()
            .unwrap();
        assert!(err.contains("0.150 times the fluid's"), "{err}");
    }
}
