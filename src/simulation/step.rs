//! One time step, as the paper's algorithm reads: [`Simulation::step`] chooses the step's
//! size, runs the model's phases in order, and checks the solution. Each model's step is one
//! short function of named phases ([`step_fluid_alone`], [`step_direct`], [`step_drag_law`]);
//! the phases live with the model's state (`direct_model.rs`, `drag_law_model.rs`,
//! `particles.rs`) and cite the paper's equations. Tests and studies that hold a model
//! outside a case call these functions too.

use super::coupling::Coupling;
use super::direct_model::DirectModel;
use super::drag_law_model::DragLawModel;
use super::particles::{CloudReport, Particles};
use super::simulation::{PhaseTimes, Simulation};
use crate::error::FsimError;
use crate::fluid::{FluidDiagnostics, FluidSolver, StepReport};
use std::time::Instant;

/// What one step did, for the log and the monitors.
pub struct TakenStep {
    pub dt: f64,
    pub fluid: StepReport,
    pub cloud: Option<CloudReport>,
    /// The fluid's divergence, energy, mean velocity and Courant number after the step.
    pub health: FluidDiagnostics,
    /// The step ended on a write time.
    pub write_due: bool,
}

/// What a model's step did: the fluid's report, the particles' and the fluid's diagnostics
/// after the step.
pub struct ModelStep {
    pub fluid: StepReport,
    pub cloud: Option<CloudReport>,
    pub diagnostics: FluidDiagnostics,
}

impl Simulation {
    /// One time step of the run (and of `-dry-run`'s timed steps): the step's size
    /// (controlDict, `maxCo`, the scheme's bound), the model's phases, the time axis, and the
    /// health check (a diverged run stops here, its last written time kept).
    pub fn step(&mut self) -> Result<TakenStep, FsimError> {
        let dt = self.next_time_step()?;
        self.dt = dt;
        self.largest_dt = self.largest_dt.max(dt);
        let time = self.time.time;
        let Simulation {
            fluid,
            coupling,
            phase_times: clock,
            rho,
            ..
        } = self;
        *clock = PhaseTimes::default();
        let ModelStep {
            fluid: report,
            cloud,
            diagnostics,
        } = match coupling {
            Coupling::None { particles } => {
                step_fluid_alone(fluid, particles.as_deref_mut(), dt, clock)
            }
            Coupling::Direct(model) => step_direct(fluid, model, *rho, dt, clock),
            Coupling::DragLaw(model) => step_drag_law(fluid, model, time + dt, dt, clock)?,
        };
        let write_due = self.time.advance(dt);
        let health = self.check_health(diagnostics, cloud.as_ref())?;
        Ok(TakenStep {
            dt,
            fluid: report,
            cloud,
            health,
            write_due,
        })
    }
}

/// `model none`: the fluid by its scheme's stages (paper eq. 2); a cloud beside it feels
/// gravity and buoyancy only (paper eq. 1 without `f_h`).
pub fn step_fluid_alone(
    fluid: &mut FluidSolver,
    particles: Option<&mut Particles>,
    dt: f64,
    clock: &mut PhaseTimes,
) -> ModelStep {
    let report = timed(&mut clock.fluid, || fluid.step(dt));
    let (cloud, diagnostics) = advance_beside_diagnostics(particles, fluid, dt, clock);
    ModelStep {
        fluid: report,
        cloud,
        diagnostics,
    }
}

/// The direct model (paper §2.1): the fluid with no-slip on every sphere, the stress
/// integral's loads, the spheres' motion, and the periodic settling drive.
pub fn step_direct(
    fluid: &mut FluidSolver,
    model: &mut DirectModel,
    rho: f64,
    dt: f64,
    clock: &mut PhaseTimes,
) -> ModelStep {
    timed(&mut clock.coupling, || model.place_spheres());
    let report = timed(&mut clock.fluid, || {
        model.advance_fluid_with_no_slip(fluid, dt)
    }); // paper eq. 2
    timed(&mut clock.coupling, || {
        model.apply_hydrodynamic_loads(fluid, rho, dt)
    }); // paper eq. 4–6
    let particles = Some(&mut model.particles);
    let (cloud, diagnostics) = advance_beside_diagnostics(particles, fluid, dt, clock); // paper eq. 1
    model.hold_mixture_momentum(fluid, dt);
    ModelStep {
        fluid: report,
        cloud,
        diagnostics,
    }
}

/// The drag-law model (paper §2.2) in DPMFoam's order: the particles move first, under the
/// forces of the fluid as it is; then the fluid, with the particles' ε and reaction. `end`
/// is the time the step reaches (s), for the message of a cell packed beyond `alphaMax`.
pub fn step_drag_law(
    fluid: &mut FluidSolver,
    model: &mut DragLawModel,
    end: f64,
    dt: f64,
    clock: &mut PhaseTimes,
) -> Result<ModelStep, FsimError> {
    let cloud = timed(&mut clock.particles, || {
        model.apply_particle_forces(fluid, dt); // paper eq. 10–13
        model.particles.advance(dt) // paper eq. 1
    });
    let report = timed(&mut clock.fluid, || -> Result<_, FsimError> {
        model.update_fluid_fraction(end)?; // paper eq. 14–16
        model.predict_momentum(fluid, dt); // paper eq. 7–9
        model.correct_pressure(fluid, dt); // paper eq. 7, continuity
        let driving_gradient = model.hold_mean_velocity(fluid, dt); // fvOptions
        Ok(StepReport {
            dt,
            time: fluid.time(),
            driving_gradient,
        })
    })?;
    let diagnostics = fluid.diagnostics(dt);
    Ok(ModelStep {
        fluid: report,
        cloud: Some(cloud),
        diagnostics,
    })
}

/// The particles' step (paper eq. 1, their loads already set) beside the fluid's
/// diagnostics, which read only the velocity: a cloud of a few hundred particles is one
/// chunk of the DEM's passes, so its sub-steps keep one worker busy while the diagnostics
/// take the other.
fn advance_beside_diagnostics(
    particles: Option<&mut Particles>,
    fluid: &mut FluidSolver,
    dt: f64,
    clock: &mut PhaseTimes,
) -> (Option<CloudReport>, FluidDiagnostics) {
    let seconds = &mut clock.particles;
    rayon::join(
        || particles.map(|p| timed(seconds, || p.advance(dt))),
        || fluid.diagnostics(dt),
    )
}

/// `work()`, its wall time added to `seconds`.
fn timed<T>(seconds: &mut f64, work: impl FnOnce() -> T) -> T {
    let start = Instant::now();
    let result = work();
    *seconds += start.elapsed().as_secs_f64();
    result
}
