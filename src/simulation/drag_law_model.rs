//! The drag-law model of a run (paper §2.2): the unresolved particles, their coupling to the
//! volume-averaged fluid, and the phases of its step (`step.rs` calls them in DPMFoam's
//! order).

use super::particles::Particles;
use super::simulation::PhaseTimes;
use super::step::{step_drag_law, ModelStep};
use crate::coupling::drag::DragLawCoupling;
use crate::error::FsimError;
use crate::fluid::{FluidSolver, VolumeAveragedReport};
use crate::particles::Dem;

/// `model dragLaw` with a cloud: the particles and the drag-law coupling.
pub struct DragLawModel {
    pub particles: Particles,
    pub coupling: DragLawCoupling,
}

impl DragLawModel {
    /// The model of the particles of `dem` set up outside a case (tests, studies), in
    /// `fluid`, its pressure started for steps of `dt` as a fresh run starts it.
    pub fn start(
        mut coupling: DragLawCoupling,
        dem: Dem,
        fluid: &mut FluidSolver,
        dt: f64,
    ) -> Self {
        coupling.initialise_pressure(fluid, dt);
        DragLawModel {
            particles: Particles::from_dem(dem),
            coupling,
        }
    }

    /// One step of `dt` as `fsimFoam` takes it ([`step_drag_law`]).
    pub fn step(&mut self, fluid: &mut FluidSolver, dt: f64) -> Result<ModelStep, FsimError> {
        let end = fluid.time() + dt;
        step_drag_law(fluid, self, end, dt, &mut PhaseTimes::default())
    }

    /// Paper eq. 10–13: the drag (closure eq. 11–12) and pressure-gradient force on every
    /// particle from the fluid as it is (velocity, ε and ∇p read at the particle, eq.
    /// 14–15), into the DEM's external loads; their reaction gathered for the fluid (eq.
    /// 13, 16).
    pub fn apply_particle_forces(&mut self, fluid: &FluidSolver, dt: f64) {
        self.coupling
            .particle_forces(fluid, &mut self.particles.dem, dt);
    }

    /// Paper eq. 14–16's transfer of the particles' volume: ε at their new positions (a cell
    /// packed beyond `alphaMax` stops the run at `time`, s).
    pub fn update_fluid_fraction(&mut self, time: f64) -> Result<(), FsimError> {
        self.coupling
            .update_fluid_fraction(&self.particles.dem)
            .map_err(|e| FsimError::run(format!("drag-law model at t = {time} s: {e}")))
    }

    /// Paper eq. 7–9: the volume-averaged momentum predictor with the particles' reaction.
    pub fn predict_momentum(&mut self, fluid: &mut FluidSolver, dt: f64) {
        self.coupling.predict_momentum(fluid, dt);
    }

    /// Paper eq. 7's continuity: the variable-coefficient pressure correction.
    pub fn correct_pressure(&mut self, fluid: &mut FluidSolver, dt: f64) -> VolumeAveragedReport {
        self.coupling.correct_pressure(fluid, dt)
    }

    /// `meanVelocityForce` (a periodic flow through a fixed bed): the superficial mean
    /// velocity `⟨ε u⟩` held at `Ubar` by a uniform driving pressure gradient on the
    /// volume-averaged momentum equation (paper eq. 7;
    /// [`crate::fluid::VolumeAveragedFluid::hold_superficial_velocity`]). Returns the
    /// driving gradient, m/s² (`None` without the fvOption).
    pub fn hold_mean_velocity(&mut self, fluid: &mut FluidSolver, dt: f64) -> Option<f64> {
        let mut drive = fluid.mean_velocity_force()?.clone();
        let g = self
            .coupling
            .fluid
            .hold_superficial_velocity(fluid, &mut drive, dt);
        fluid
            .set_mean_velocity_force(Some(drive))
            .expect("the drive's direction was checked when it was set");
        Some(g)
    }

    /// The porous-media drag coefficient of paper eq. 19 with a `meanVelocityForce`:
    /// `K = f_h / (6 π μ r U)`, `f_h` the mean hydrodynamic force per particle along the drive
    /// (drag, paper eq. 11–12, plus in the paper's form the pressure-gradient force of paper
    /// eq. 10), `r` the mean radius, `U = Ubar` the superficial velocity the drive holds. In
    /// a fixed periodic array `Σ f_h = ρ G V_box` at steady state (the drive's force on the
    /// whole box). Zero without the fvOption or particles.
    pub fn drag_coefficient(&self, fluid: &FluidSolver) -> f64 {
        let p = self.particles.dem.particles();
        let Some(drive) = fluid.mean_velocity_force() else {
            return 0.0;
        };
        if p.is_empty() || drive.ubar == 0.0 {
            return 0.0;
        }
        let n = p.len() as f64;
        let radius = p.diameter.iter().sum::<f64>() / (2.0 * n);
        let mu = self.coupling.settings.mu();
        self.coupling.last.hydrodynamic_force[drive.direction]
            / n
            / (6.0 * std::f64::consts::PI * mu * radius * drive.ubar)
    }
}
