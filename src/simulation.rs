//! A case turned into a running simulation: the grid, the fluid with its boundary conditions
//! and driving, the time axis, and the particles (with `model none`, a cloud that evolves
//! beside the fluid, feeling gravity and the fluid's buoyancy only).
//!
//! Everything a case asks for is checked here, before the first step: a boundary condition
//! the solver cannot honour, a time scheme it does not know, a fixed `deltaT` above the
//! scheme's stability bound (paper eq. 3) all stop the run with exit code 2.
//!
//! This file holds the state and the phases of a step (the order is `run::take_step`'s); the
//! case is read into the solvers' settings in `case_settings`, each step's size is chosen in
//! `step_size`, and the restart state is written and read in `restart`.

use crate::case::{Case, Cloud, ControlDict, CouplingModel, InternalField};
use crate::coupling::direct::{
    periodic_directions, DirectCoupling, DirectSettings, MotionSettings, ParticleMotion,
    SedimentationReport,
};
use crate::coupling::drag::DragLawCoupling;
use crate::error::FsimError;
use crate::fluid::{FluidDiagnostics, FluidSettings, FluidSolver, StepReport};
use crate::grid::Grid;
use crate::output::{ParticleFields, TimeEntry};
use crate::particles::Dem;
use crate::time_control::{TimeControl, WriteControl};
use std::time::Instant;

mod case_settings;
mod restart;
mod step_size;

pub use case_settings::{boundary_conditions, continues, interstitial_inlets};
use case_settings::{check_direct_resolution, drag_law, fluid_scheme, mean_velocity_force};
use restart::restore_particles;
use step_size::coupling_step_warning;

/// How each step's size is chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StepSizing {
    /// `adjustTimeStep no`: controlDict's `deltaT`, which must stay under the scheme's bound.
    Fixed(f64),
    /// `adjustTimeStep yes`: from `maxCo`, never above `maxDeltaT` nor the scheme's bound.
    Adaptive { max_co: f64, max_delta_t: f64 },
}

/// The state of a run between two steps.
pub struct Simulation {
    pub fluid: FluidSolver,
    pub time: TimeControl,
    pub sizing: StepSizing,
    /// The last step taken (controlDict's `deltaT` before the first).
    pub dt: f64,
    /// The largest step taken in this run (or restored with its state), against which a
    /// collapsing Courant step is judged ([`Self::next_time_step`]).
    largest_dt: f64,
    pub model: CouplingModel,
    /// Fluid density, kg/m³ (the solver works with kinematic pressure p/ρ).
    pub rho: f64,
    /// The particles, when the case has an active cloud.
    pub particles: Option<Particles>,
    /// The drag-law model (paper §2.2), when the case runs it with a cloud.
    pub drag: Option<DragLawCoupling>,
    /// The resolved coupling (`model direct`): forced faces and hydrodynamic loads.
    pub direct: Option<DirectCoupling>,
    /// Sum of the last hydrodynamic loads, for the monitor (`model direct`).
    pub hydrodynamics: Option<HydrodynamicReport>,
    /// Freely moving spheres (`model direct`): lubrication, virtual mass, settling drive.
    pub motion: Option<ParticleMotion>,
    /// What the grid does not resolve well and where the step is held (`model direct`), for
    /// `-dry-run` and the log.
    pub warnings: Vec<String>,
    /// Wall time of the last step's phases.
    pub phase_times: PhaseTimes,
    /// Settling velocity and momentum after the last step (free spheres, `model direct`).
    pub settling: Option<SedimentationReport>,
}

/// Wall time of the phases of one step, s: the fluid (predictor, projections, and with
/// `model direct` the no-slip imposition inside each stage), the coupling (the forced faces of
/// the moved spheres, the stress integral, lubrication) and the particles (the DEM).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PhaseTimes {
    pub fluid: f64,
    pub coupling: f64,
    pub particles: f64,
}

/// The hydrodynamic loads of one step, summed over the particles (`model direct`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HydrodynamicReport {
    /// Total force and torque on all particles, N and N·m.
    pub force: [f64; 3],
    pub torque: [f64; 3],
    /// Mean force per particle along the fluid's bulk flow over `6π μ r U` (paper eq. 19),
    /// `U` the bulk (superficial) velocity, `r` the mean radius: the porous-media `K`.
    pub drag_coefficient: f64,
}

/// The cloud of a run: the DEM engine and what the log says about it.
pub struct Particles {
    pub dem: Dem,
    /// `pairModel` and `wallModel` as the case names them.
    pub pair_model: String,
    pub wall_model: String,
    /// Collision sub-steps of the last fluid step.
    pub substeps: usize,
    /// Notes from reading the cloud (ignored keywords, settings without effect).
    pub notes: Vec<String>,
}

/// What the cloud did in one fluid step, for the log and the monitor.
#[derive(Clone, Copy, Debug)]
pub struct CloudReport {
    pub count: usize,
    /// `(Σ ½ m v², Σ ½ I ω²)`, J.
    pub kinetic_energy: (f64, f64),
    pub mean_velocity: [f64; 3],
    /// Largest overlap over the diameter.
    pub max_overlap: f64,
    pub substeps: usize,
}

impl Simulation {
    /// Builds the simulation from a validated case, starting from the case's initial fields,
    /// or from the restart state of `restart` when continuing (`startFrom latestTime`).
    pub fn new(case: &Case, restart: Option<&TimeEntry>) -> Result<Self, FsimError> {
        let grid = case.mesh.grid.clone();
        let bc = boundary_conditions(case)?;
        let (scheme, drag_law_implicit_viscosity) = fluid_scheme(case)?;
        let settings = FluidSettings {
            nu: case.transport.nu,
            scheme,
            body_force: [0.0; 3],
        };
        let mut fluid = FluidSolver::new(grid.clone(), bc, settings)
            .map_err(|e| FsimError::input(format!("case: {e}")))?;
        fluid
            .set_mean_velocity_force(mean_velocity_force(case)?)
            .map_err(|e| FsimError::input(format!("fvOptions: {e}")))?;

        let control = &case.control;
        let mut sim = Simulation {
            fluid,
            time: time_axis(control.start_time, 0, control),
            sizing: step_sizing(control),
            dt: control.delta_t,
            largest_dt: 0.0,
            model: case.coupling.model,
            rho: case.transport.rho,
            particles: None,
            drag: None,
            direct: None,
            hydrodynamics: None,
            motion: None,
            warnings: Vec::new(),
            phase_times: PhaseTimes::default(),
            settling: None,
        };
        let direct_settings = match case.coupling.model {
            CouplingModel::Direct => {
                Some(DirectSettings::from_coupling(&case.coupling).map_err(FsimError::from)?)
            }
            _ => None,
        };
        let cloud = Cloud::from_case(case)?;
        if let (Some(settings), Some(cloud)) = (&direct_settings, &cloud) {
            sim.warnings = check_direct_resolution(&sim.fluid, cloud, settings);
        }
        let mut direct_shell: Option<Vec<f64>> = None;
        let mut direct_build: Option<Vec<f64>> = None;
        let mut direct_throats: Option<Vec<f64>> = None;
        let mut motion_state: Option<Vec<f64>> = None;
        match restart {
            Some(entry) => {
                let dir = case.dir.join(&entry.name);
                let state = sim.restore(&dir, control)?;
                direct_shell = state
                    .array(DirectCoupling::RESTART_NAME)
                    .map(|a| a.to_vec());
                direct_build = state
                    .array(DirectCoupling::BUILD_RESTART_NAME)
                    .map(|a| a.to_vec());
                direct_throats = state
                    .array(DirectCoupling::THROAT_RESTART_NAME)
                    .map(|a| a.to_vec());
                motion_state = state
                    .array(ParticleMotion::RESTART_NAME)
                    .map(|a| a.to_vec());
                if let Some(cloud) = cloud {
                    let cloud_settings = cloud.clone();
                    let particles = restore_particles(cloud, &state, &dir)?;
                    sim.drag = drag_law(
                        case,
                        &cloud_settings,
                        &sim.fluid,
                        &particles.dem,
                        drag_law_implicit_viscosity,
                    )?;
                    if let Some(drag) = sim.drag.as_mut() {
                        drag.restore(&sim.fluid, &particles.dem)
                            .map_err(FsimError::input)?;
                    }
                    sim.particles = Some(particles);
                }
            }
            None => {
                sim.set_initial_fields(case);
                if let Some(cloud) = cloud {
                    let mut state = cloud.particles.clone();
                    if direct_settings.as_ref().is_some_and(|s| s.fixed_particles) {
                        state.fixed.iter_mut().for_each(|f| *f = true);
                    }
                    let dem = Dem::new(cloud.config.clone(), cloud.domain.clone(), state)
                        .map_err(|e| cloud.locate(&e))?;
                    sim.drag =
                        drag_law(case, &cloud, &sim.fluid, &dem, drag_law_implicit_viscosity)?;
                    sim.particles = Some(Particles {
                        dem,
                        pair_model: cloud.pair_model_name,
                        wall_model: cloud.wall_model_name,
                        substeps: 0,
                        notes: cloud.warnings,
                    });
                }
                // The initial field need not be discretely divergence-free: project it once,
                // as the first pressure correction would. Not in DPMFoam's form: DPMFoam's
                // first cloud evolution sees the case's field as given (a bed at rest in a
                // column whose inlet is open), and only its first pressure correction
                // makes the flow through the column.
                if sim.drag.as_ref().is_none_or(|d| d.projects_initial_field()) {
                    sim.fluid.project();
                }
                if let Some(drag) = sim.drag.as_mut() {
                    drag.initialise_pressure(&mut sim.fluid, sim.dt);
                }
            }
        }
        if let Some(settings) = direct_settings {
            if sim.particles.is_none() {
                return Err(FsimError::input(
                    "constant/couplingProperties: model direct needs particles \
                     (constant/kinematicCloudProperties)"
                        .to_string(),
                ));
            }
            if let Some(p) = sim.particles.as_mut() {
                let periodic = periodic_directions(sim.fluid.boundary_conditions());
                let notes =
                    DirectCoupling::check_particles(sim.fluid.grid(), periodic, p.dem.particles())
                        .map_err(|e| {
                            FsimError::input(format!("constant/kinematicCloudProperties: {e}"))
                        })?;
                p.notes.extend(notes);
            }
            let mut direct = DirectCoupling::new(&mut sim.fluid, settings);
            if let Some(shell) = direct_shell {
                direct
                    .restore_shell_state(&shell)
                    .map_err(FsimError::input)?;
            }
            if let Some(build) = direct_build {
                direct
                    .restore_build_state(&build)
                    .map_err(FsimError::input)?;
            }
            if let Some(throats) = direct_throats {
                direct
                    .restore_throat_state(&throats)
                    .map_err(FsimError::input)?;
            }
            sim.direct = Some(direct);
            let motion_settings =
                MotionSettings::from_coupling(&case.coupling).map_err(FsimError::from)?;
            let dem = &sim.particles.as_ref().expect("checked above").dem;
            let motion = ParticleMotion::new(
                motion_settings,
                sim.fluid.grid(),
                sim.fluid.boundary_conditions(),
                dem,
                case.transport.rho,
                case.transport.nu,
            )
            .map_err(|e| FsimError::input(format!("constant/couplingProperties: {e}")))?;
            let mut motion = motion;
            if let Some(state) = motion_state {
                motion.restore_state(&state).map_err(FsimError::input)?;
            }
            // periodic sedimentation: the mean pressure gradient that carries the mixture
            sim.fluid.set_body_force(motion.fluid_body_force());
            sim.warnings
                .extend(coupling_step_warning(sim.sizing, motion.step_bound()));
            sim.motion = Some(motion);
        }
        Ok(sim)
    }

    fn set_initial_fields(&mut self, case: &Case) {
        match &case.fields.u {
            InternalField::Nonuniform(cells) => self.fluid.set_cell_velocity(cells),
            InternalField::Uniform(u) => {
                self.fluid
                    .set_cell_velocity(&vec![*u; case.mesh.grid.cell_count()])
            }
        }
        self.fluid.set_time(self.time.time);
    }

    /// The grid of the fluid.
    pub fn grid(&self) -> &Grid {
        self.fluid.grid()
    }

    /// Takes the settings of a `system/controlDict` changed during the run
    /// (`runTimeModifiable`): when to stop, the step's rule, when to write. A fixed step's
    /// new `deltaT` applies from the next step; an adjustable one goes on from the last.
    pub fn apply_control(&mut self, control: &ControlDict) {
        self.sizing = step_sizing(control);
        self.time.set_stop(control.stop_at, control.end_time);
        let write_control = effective_write_control(control);
        if write_control != self.time.write_control
            || control.write_interval != self.time.write_interval
        {
            self.time.set_writes(write_control, control.write_interval);
        }
    }

    /// Advances the fluid by `dt`. Alone: momentum predictor, pressure projection, bulk
    /// driving. `model direct`: the same with no-slip on every particle at its current
    /// position and velocity in every stage. Drag-law model: ε from the particles' new
    /// positions (a cell packed beyond `alphaMax` stops the run), then the volume-averaged
    /// momentum predictor with the particles' reaction and the variable-coefficient pressure
    /// correction.
    pub fn evolve_fluid(&mut self, dt: f64) -> Result<StepReport, FsimError> {
        let clock = Instant::now();
        self.dt = dt;
        self.largest_dt = self.largest_dt.max(dt);
        self.phase_times.coupling = 0.0;
        let report = match (&mut self.drag, &mut self.direct, &self.particles) {
            (Some(drag), _, Some(p)) => {
                drag.update_fluid_fraction(&p.dem).map_err(|e| {
                    FsimError::run(format!(
                        "drag-law model at t = {} s: {e}",
                        self.time.time + dt
                    ))
                })?;
                drag.step_fluid(&mut self.fluid, dt);
                StepReport {
                    dt,
                    time: self.fluid.time(),
                    driving_gradient: None,
                }
            }
            (None, Some(direct), Some(p)) => {
                direct.set_particles(p.dem.particles());
                self.phase_times.coupling = clock.elapsed().as_secs_f64();
                self.fluid.step_with(dt, &mut |stage| direct.impose(stage))
            }
            _ => self.fluid.step(dt),
        };
        self.phase_times.fluid = clock.elapsed().as_secs_f64() - self.phase_times.coupling;
        Ok(report)
    }

    /// `model direct`: force and torque on every particle from the stress integral over
    /// its surface (paper eq. 4–6), handed to the DEM as external loads for the coming
    /// cloud step. Other models: nothing.
    pub fn hydrodynamic_loads(&mut self) {
        let (Some(direct), Some(p)) = (&mut self.direct, &mut self.particles) else {
            return;
        };
        let clock = Instant::now();
        let loads = direct.compute_loads(&self.fluid, self.rho);
        match self.motion.as_mut() {
            // plus lubrication and the virtual mass (ParticleMotion)
            Some(motion) => {
                motion.set_loads(
                    &mut p.dem,
                    loads.iter().map(|l| (l.force, l.torque)),
                    self.dt,
                );
            }
            None => {
                let (force, torque) = p.dem.external_loads_mut();
                for (k, load) in loads.iter().enumerate() {
                    force[k] = load.force;
                    torque[k] = load.torque;
                }
            }
        }
        let mut report = HydrodynamicReport {
            force: [0.0; 3],
            torque: [0.0; 3],
            drag_coefficient: 0.0,
        };
        for load in loads.iter() {
            for i in 0..3 {
                report.force[i] += load.force[i];
                report.torque[i] += load.torque[i];
            }
        }
        let spheres = direct.spheres();
        if let (Some(drive), false) = (self.fluid.mean_velocity_force(), spheres.is_empty()) {
            let d = drive.direction;
            let bulk = drive.ubar;
            let radius = spheres.iter().map(|s| s.radius).sum::<f64>() / spheres.len() as f64;
            let mu = self.rho * self.fluid.settings().nu;
            report.drag_coefficient = report.force[d]
                / spheres.len() as f64
                / (6.0 * std::f64::consts::PI * mu * radius * bulk);
        }
        self.hydrodynamics = Some(report);
        self.phase_times.coupling += clock.elapsed().as_secs_f64();
    }

    /// Measures the settling velocity and the mixture's momentum of the free spheres after a
    /// step into [`Simulation::settling`], and corrects the periodic-settling drive so that
    /// the mixture's momentum stays zero (`model direct` with free particles).
    pub fn update_sedimentation(&mut self) {
        let (Some(motion), Some(p)) = (&mut self.motion, &self.particles) else {
            return;
        };
        if p.dem.particles().fixed.iter().all(|&f| f) {
            return;
        }
        let mean = [0, 1, 2].map(|c| self.fluid.mean_component(c));
        let report = motion.sedimentation(mean, p.dem.particles());
        let body = motion.hold_zero_momentum(report.momentum, self.dt);
        self.fluid.set_body_force(body);
        self.settling = Some(report);
    }

    /// Advances the cloud by the fluid step `dt` in the engine's collision sub-steps; `None`
    /// without particles. With the drag-law model the hydrodynamic forces come first, from
    /// the fluid as it is (DPMFoam's order: the cloud moves before the fluid).
    pub fn evolve_cloud(&mut self, dt: f64) -> Option<CloudReport> {
        let p = self.particles.as_mut()?;
        let clock = Instant::now();
        if let Some(drag) = self.drag.as_mut() {
            drag.particle_forces(&self.fluid, &mut p.dem, dt);
        }
        let report = advance_cloud(p, dt);
        self.phase_times.particles = clock.elapsed().as_secs_f64();
        Some(report)
    }

    /// [`Self::evolve_cloud`] for a cloud whose loads are already set (`model direct`, after
    /// [`Self::hydrodynamic_loads`]), with the fluid's diagnostics of the step found beside
    /// it for [`Self::check_health`]. The cloud reads only the particles and their
    /// loads, the diagnostics only the velocity. A cloud of a few hundred particles is one
    /// chunk of the DEM's passes, so its sub-steps (about 100 per fluid step in
    /// tutorials/benchmark) keep one worker busy while the diagnostics take the other.
    pub fn evolve_cloud_beside_diagnostics(
        &mut self,
        dt: f64,
    ) -> (Option<CloudReport>, FluidDiagnostics) {
        assert!(
            self.drag.is_none(),
            "the drag law's cloud reads the fluid it steps beside"
        );
        let (particles, fluid, step) = (&mut self.particles, &mut self.fluid, self.dt);
        let seconds = &mut self.phase_times.particles;
        rayon::join(
            || {
                let p = particles.as_mut()?;
                let clock = Instant::now();
                let report = advance_cloud(p, dt);
                *seconds = clock.elapsed().as_secs_f64();
                Some(report)
            },
            || fluid.diagnostics(step),
        )
    }

    /// Writes the particles (id, d, U, omega, F_hydro, F_contact) to `path`, when there are any.
    pub fn write_particles(&self, path: &std::path::Path) -> Result<(), FsimError> {
        let Some(particles) = &self.particles else {
            return Ok(());
        };
        let p = particles.dem.particles();
        let id: Vec<i64> = p.id.iter().map(|&i| i as i64).collect();
        ParticleFields {
            positions: &p.position,
            id: &id,
            d: &p.diameter,
            velocity: &p.velocity,
            omega: &p.angular_velocity,
            hydrodynamic_force: &p.external_force,
            contact_force: &p.contact_force,
        }
        .write(path)
        .map_err(|e| FsimError::run(e.to_string()))
    }

    /// Divergence, energy, mean velocity and Courant number of the last step (for
    /// [`Self::check_health`]).
    pub fn fluid_diagnostics(&mut self) -> FluidDiagnostics {
        self.fluid.diagnostics(self.dt)
    }

    /// The last step's diagnostics ([`Self::fluid_diagnostics`], or those of
    /// [`Self::evolve_cloud_beside_diagnostics`]) back, unless the run diverged: a velocity
    /// that is no longer finite.
    pub fn check_health(&self, d: FluidDiagnostics) -> Result<FluidDiagnostics, FsimError> {
        if !d.kinetic_energy.is_finite() || !d.max_courant.is_finite() {
            return Err(FsimError::run(format!(
                "the solution diverged at t = {} s (step {}): the velocity is no longer finite",
                self.time.time, self.time.step
            )));
        }
        if let Some(p) = &self.particles {
            let s = p.dem.particles();
            if let Some(i) = (0..s.len()).find(|&i| {
                !(s.velocity[i]
                    .iter()
                    .chain(&s.position[i])
                    .all(|v| v.is_finite()))
            }) {
                return Err(FsimError::run(format!(
                    "the solution diverged at t = {} s (step {}): particle {} has no finite \
                     velocity or position{}",
                    self.time.time,
                    self.time.step,
                    s.id[i],
                    if self.direct.is_some() {
                        " (with model direct: particles not much heavier than the fluid need \
                         the virtual mass, virtualMass in constant/couplingProperties)"
                    } else {
                        ""
                    }
                )));
            }
        }
        Ok(d)
    }
}

/// The cloud's DEM step over one fluid step `dt` (its loads already set), and its report.
fn advance_cloud(p: &mut Particles, dt: f64) -> CloudReport {
    p.substeps = p.dem.advance(dt);
    CloudReport {
        count: p.dem.particles().len(),
        kinetic_energy: p.dem.kinetic_energy(),
        mean_velocity: p.dem.mean_velocity(),
        max_overlap: p.dem.max_overlap_ratio(),
        substeps: p.substeps,
    }
}

/// The time axis from `time` (step index `step`) as `control` sets it.
pub(super) fn time_axis(time: f64, step: u64, control: &ControlDict) -> TimeControl {
    let mut axis = TimeControl::new(
        time,
        step,
        control.end_time,
        effective_write_control(control),
        control.write_interval,
    );
    axis.set_stop(control.stop_at, control.end_time);
    axis
}

/// The step rule of `adjustTimeStep`, `maxCo`, `maxDeltaT` and `deltaT`.
fn step_sizing(control: &ControlDict) -> StepSizing {
    if control.adjust_time_step {
        StepSizing::Adaptive {
            max_co: control.max_co,
            max_delta_t: control.max_delta_t,
        }
    } else {
        StepSizing::Fixed(control.delta_t)
    }
}

/// OpenFOAM fits the step to the write times only within its adjustable step
/// (`Time::adjustDeltaT`, reached through setDeltaT.H): with a fixed step,
/// adjustableRunTime writes as runTime does.
fn effective_write_control(control: &ControlDict) -> WriteControl {
    match control.write_control {
        WriteControl::AdjustableRunTime if !control.adjust_time_step => WriteControl::RunTime,
        w => w,
    }
}
