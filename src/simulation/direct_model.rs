//! The direct model of a run (paper §2.1): the resolved spheres, their coupling to the
//! fluid, their motion, and the phases of its step (`step.rs` calls them in order).

use super::particles::Particles;
use crate::coupling::direct::{
    DirectCoupling, DirectSettings, MotionSettings, ParticleMotion, SedimentationReport,
};
use crate::fluid::{FluidSolver, StepReport};
use crate::output::RestartState;
use crate::Vec3;

/// The hydrodynamic loads of one step, summed over the particles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HydrodynamicReport {
    /// Total force and torque on all particles, N and N·m.
    pub force: Vec3,
    pub torque: Vec3,
    /// Mean force per particle along the fluid's bulk flow over `6π μ r U` (paper eq. 19),
    /// `U` the bulk (superficial) velocity, `r` the mean radius: the porous-media `K`.
    pub drag_coefficient: f64,
}

/// `model direct`: the spheres, their no-slip forcing and stress integral, and their motion
/// (lubrication, virtual mass, periodic-settling drive).
pub struct DirectModel {
    pub particles: Particles,
    pub coupling: DirectCoupling,
    pub motion: ParticleMotion,
    /// Sum of the last hydrodynamic loads, for the monitor.
    pub loads: Option<HydrodynamicReport>,
    /// Settling velocity and momentum after the last step (free spheres).
    pub settling: Option<SedimentationReport>,
}

impl DirectModel {
    /// The model for `particles` in `fluid` (density `rho`, kg/m³), continuing from
    /// `restart` when given. Enables the fluid's mass source and sets the drive that carries
    /// a periodic suspension's weight.
    pub fn new(
        fluid: &mut FluidSolver,
        particles: Particles,
        (settings, motion): (DirectSettings, MotionSettings),
        rho: f64,
        restart: Option<&RestartState>,
    ) -> Result<Self, String> {
        let mut coupling = DirectCoupling::new(fluid, settings);
        let nu = fluid.settings().nu;
        let mut motion = ParticleMotion::new(
            motion,
            fluid.grid(),
            fluid.boundary_conditions(),
            &particles.dem,
            rho,
            nu,
        )
        .map_err(|e| format!("constant/couplingProperties: {e}"))?;
        if let Some(state) = restart {
            if let Some(shell) = state.array(DirectCoupling::RESTART_NAME) {
                coupling.restore_shell_state(shell)?;
            }
            if let Some(build) = state.array(DirectCoupling::BUILD_RESTART_NAME) {
                coupling.restore_build_state(build)?;
            }
            if let Some(throats) = state.array(DirectCoupling::THROAT_RESTART_NAME) {
                coupling.restore_throat_state(throats)?;
            }
            if let Some(m) = state.array(ParticleMotion::RESTART_NAME) {
                motion.restore_state(m)?;
            }
        }
        // periodic sedimentation: the mean pressure gradient that carries the mixture
        fluid.set_body_force(motion.fluid_body_force().into());
        Ok(DirectModel {
            particles,
            coupling,
            motion,
            loads: None,
            settling: None,
        })
    }

    /// The forced faces for the spheres where they are now, moving as they move
    /// (`v = v_p + ω_p × (x − x_p)`, paper eq. 2's condition on the particle surface).
    pub fn place_spheres(&mut self) {
        self.coupling.set_particles(self.particles.dem.particles());
    }

    /// Paper eq. 2 with no-slip on every sphere: each stage of the fluid's scheme, its
    /// predicted velocity forced to the spheres' rigid motion before it is projected.
    pub fn advance_fluid_with_no_slip(&mut self, fluid: &mut FluidSolver, dt: f64) -> StepReport {
        let coupling = &mut self.coupling;
        fluid.step_with(dt, &mut |stage| coupling.impose(stage))
    }

    /// Paper eq. 4–6: force and torque on every sphere from the stress integral over its
    /// surface (with `f_h0`), plus lubrication below the grid's reach and the virtual mass
    /// split off (`ParticleMotion::set_loads`), handed to the DEM as its external loads for
    /// the coming particle step. `rho` the fluid density, kg/m³.
    pub fn apply_hydrodynamic_loads(&mut self, fluid: &FluidSolver, rho: f64, dt: f64) {
        let loads = self.coupling.compute_loads(fluid, rho);
        self.motion.set_loads(
            &mut self.particles.dem,
            loads.iter().map(|l| (l.force, l.torque)),
            dt,
        );
        let mut report = HydrodynamicReport {
            force: Vec3::zeros(),
            torque: Vec3::zeros(),
            drag_coefficient: 0.0,
        };
        for load in loads.iter() {
            for i in 0..3 {
                report.force[i] += load.force[i];
                report.torque[i] += load.torque[i];
            }
        }
        let spheres = self.coupling.spheres();
        if let (Some(drive), false) = (fluid.mean_velocity_force(), spheres.is_empty()) {
            let radius = spheres.iter().map(|s| s.radius).sum::<f64>() / spheres.len() as f64;
            let mu = rho * fluid.settings().nu;
            report.drag_coefficient = report.force[drive.direction]
                / spheres.len() as f64
                / (6.0 * std::f64::consts::PI * mu * radius * drive.ubar);
        }
        self.loads = Some(report);
    }

    /// Free spheres: measures the settling velocity and the mixture's momentum after the
    /// step, and corrects the periodic-settling drive so that the mixture's momentum stays
    /// zero (`ParticleMotion::hold_zero_momentum`).
    pub fn hold_mixture_momentum(&mut self, fluid: &mut FluidSolver, dt: f64) {
        let p = self.particles.dem.particles();
        if p.fixed.iter().all(|&f| f) {
            return;
        }
        let mean = Vec3::from_fn(|c, _| fluid.mean_component(c));
        let report = self.motion.sedimentation(mean, p);
        let body = self.motion.hold_zero_momentum(report.momentum, dt);
        fluid.set_body_force(body.into());
        self.settling = Some(report);
    }

    /// The model's arrays of the restart state.
    pub fn restart_arrays(&self) -> Vec<(&'static str, Vec<f64>)> {
        vec![
            (DirectCoupling::RESTART_NAME, self.coupling.shell_state()),
            (
                DirectCoupling::BUILD_RESTART_NAME,
                self.coupling.build_state(),
            ),
            (
                DirectCoupling::THROAT_RESTART_NAME,
                self.coupling.throat_state(),
            ),
            (ParticleMotion::RESTART_NAME, self.motion.restart_state()),
        ]
    }
}
