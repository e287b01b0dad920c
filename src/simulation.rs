//! A case turned into a running simulation: the grid, the fluid with its boundary conditions
//! and driving, the time axis, and the particles (with `model none`, a cloud that evolves
//! beside the fluid, feeling gravity and the fluid's buoyancy only).
//!
//! Everything a case asks for is checked here, before the first step: a boundary condition
//! the solver cannot honour, a time scheme it does not know, a fixed `deltaT` above the
//! scheme's stability bound (paper eq. 3) all stop the run with exit code 2.

use crate::case::{
    Case, Cloud, CouplingModel, InternalField, PatchType, PressureBc, PressureSolverControls,
    StartFrom, VelocityBc,
};
use crate::coupling::direct::{
    check_resolution, periodic_directions, DirectCoupling, DirectSettings, MotionSettings,
    ParticleMotion, PeriodicBox, SedimentationReport,
};
use crate::coupling::drag::DragLawCoupling;
use crate::error::FsimError;
use crate::fluid::{
    BoundaryConditions, ChebyshevStages, Convergence, FaceCondition, FluidDiagnostics,
    FluidSettings, FluidSolver, MeanVelocityForce, StepReport, TimeScheme,
};
use crate::grid::Grid;
use crate::output::{ParticleFields, RestartHeader, RestartState, TimeEntry};
use crate::particles::{Dem, DemSnapshot};
use crate::time_control::TimeControl;
use std::time::Instant;

/// A Courant step below this fraction of the largest step taken means a velocity growing
/// without bound: a flow that develops changes its speed by orders of magnitude less within a
/// run (a diverging one collapses the step to 10⁻³⁰⁰ s before it overflows).
const COLLAPSED_STEP: f64 = 1e-8;

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
    /// What the grid does not resolve well (`model direct`), for `-dry-run` and the log.
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
    /// The constrained viscous solve of the step's last stage (semi-implicit schemes).
    pub constrained_solve: Option<crate::coupling::direct::ImplicitForcingReport>,
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
        if !matches!(
            case.coupling.model,
            CouplingModel::None | CouplingModel::Direct | CouplingModel::DragLaw
        ) {
            return Err(FsimError::input(format!(
                "constant/couplingProperties: model '{}' is not available yet in this fsim \
                 (models none, direct and dragLaw run)",
                case.coupling.model.name()
            )));
        }
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
        let sizing = if control.adjust_time_step {
            StepSizing::Adaptive {
                max_co: control.max_co,
                max_delta_t: control.max_delta_t,
            }
        } else {
            StepSizing::Fixed(control.delta_t)
        };
        let write_control = control.write_control;

        let mut sim = Simulation {
            fluid,
            time: TimeControl::new(
                control.start_time,
                0,
                control.end_time,
                write_control,
                control.write_interval,
            ),
            sizing,
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
        let mut motion_state: Option<Vec<f64>> = None;
        match restart {
            Some(entry) => {
                let dir = case.dir.join(&entry.name);
                let state = sim.restore(&dir, write_control, control)?;
                direct_shell = state
                    .array(DirectCoupling::RESTART_NAME)
                    .map(|a| a.to_vec());
                direct_build = state
                    .array(DirectCoupling::BUILD_RESTART_NAME)
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

    fn restore(
        &mut self,
        time_dir: &std::path::Path,
        write_control: crate::case::WriteControl,
        control: &crate::case::ControlDict,
    ) -> Result<RestartState, FsimError> {
        let path = time_dir.join(crate::output::RESTART_FILE_NAME);
        let state = RestartState::read(&path).map_err(|e| FsimError::input(e.to_string()))?;
        for name in FluidSolver::RESTART_NAMES {
            let data = state.array(name).ok_or_else(|| {
                FsimError::input(format!("{}: no array '{name}'", path.display()))
            })?;
            self.fluid
                .restore_array(name, data)
                .map_err(|e| FsimError::input(format!("{}: {e}", path.display())))?;
        }
        let header = &state.header;
        self.time = TimeControl::new(
            header.time,
            header.step,
            control.end_time,
            write_control,
            control.write_interval,
        );
        self.dt = header.delta_t;
        self.largest_dt = header.delta_t;
        Ok(state)
    }

    /// The grid of the fluid.
    pub fn grid(&self) -> &Grid {
        self.fluid.grid()
    }

    /// The step to take now: controlDict's `deltaT`, or the `maxCo` rule; never above the
    /// scheme's stability bound (paper eq. 3 for the explicit Euler scheme), never past the
    /// next write time for `adjustableRunTime` nor past `endTime`.
    pub fn next_time_step(&mut self) -> Result<f64, FsimError> {
        let allowed = match self.sizing {
            StepSizing::Fixed(dt) => {
                let bound = self.stability_bound();
                if dt > bound {
                    let scheme = match &self.drag {
                        Some(drag) if drag.fluid.implicit_viscosity() => {
                            "drag-law model's EulerImplicit predictor (upwind advection: \
                             1/(Σ|u|/h))"
                                .to_string()
                        }
                        Some(_) => "drag-law model's explicit Euler predictor \
                                    (1/(Σ|u|/h + 2ν Σ1/h²))"
                            .to_string(),
                        None => {
                            let scheme = self.fluid.settings().scheme;
                            let bound = match scheme {
                                TimeScheme::RK3CN => {
                                    "advective: sqrt(3) / sum |v_d|/h_d".to_string()
                                }
                                TimeScheme::EulerCN => "advective: 2 nu/|v|^2".to_string(),
                                TimeScheme::EulerRKC => format!(
                                    "advective: 2 nu/|v|^2; diffusive: the reach of {} \
                                     Chebyshev stages",
                                    ChebyshevStages::MAX_STAGES
                                ),
                                _ => "paper eq. 3: min(h^2/(6 nu), 2 nu/|v|^2)".to_string(),
                            };
                            format!("{} scheme ({bound})", scheme.name())
                        }
                    };
                    // Past the first step the bound held before: the velocity has grown,
                    // which is how a diverging run at a fixed step first shows.
                    let grown = if self.time.step > 0 {
                        format!(
                            " (step {}; it held until now: the velocity has grown, the \
                             solution may be diverging)",
                            self.time.step
                        )
                    } else {
                        String::new()
                    };
                    return Err(FsimError::run(format!(
                        "deltaT = {dt:e} s exceeds the stability bound {bound:e} s of the \
                         {scheme} at t = {} s{grown}; lower deltaT or set adjustTimeStep yes",
                        self.time.time
                    )));
                }
                dt
            }
            StepSizing::Adaptive {
                max_co,
                max_delta_t,
            } => {
                let previous = if self.time.step == 0 {
                    // OpenFOAM starts from deltaT and lets the Courant rule shrink it.
                    self.dt / 1.2
                } else {
                    self.dt
                };
                let allowed = self.adaptive_step(previous, max_co, max_delta_t);
                if allowed < COLLAPSED_STEP * self.largest_dt {
                    return Err(self.collapsed_step(allowed));
                }
                allowed
            }
        };
        Ok(self.time.step_size(allowed))
    }

    /// The step the flow allows now, without the adaptive rule's growth limit (1.2 times the
    /// last step) and without landing on write times or `endTime`: the step a plan of the
    /// whole run goes by (`-dry-run`), where [`Self::next_time_step`] is the one to take next.
    pub fn allowed_time_step(&mut self) -> f64 {
        match self.sizing {
            StepSizing::Fixed(dt) => dt,
            // after a step of maxDeltaT, the growth limit lies beyond maxDeltaT itself
            StepSizing::Adaptive {
                max_co,
                max_delta_t,
            } => self.adaptive_step(max_delta_t, max_co, max_delta_t),
        }
    }

    /// The `maxCo` rule's step after a step of `previous` (at most 1.2 times it), within
    /// `max_delta_t` and the scheme's stability bound.
    fn adaptive_step(&mut self, previous: f64, max_co: f64, max_delta_t: f64) -> f64 {
        match self.drag {
            // the drag law steps the fluid with its own predictor and bound
            Some(_) => self
                .fluid
                .courant_dt(previous, max_co, max_delta_t)
                .min(self.stability_bound()),
            // adaptive_dt holds the fluid's own bound already (3 passes over the field)
            None => self.fluid.adaptive_dt(previous, max_co, max_delta_t),
        }
    }

    /// The error of a Courant step that has collapsed: the velocity grows without bound, and
    /// without this the run would crawl on for thousands of vanishing steps until it is no
    /// longer finite.
    fn collapsed_step(&self, allowed: f64) -> FsimError {
        FsimError::run(format!(
            "the solution diverged at t = {} s (step {}): the step the Courant rule allows \
             fell to {allowed:e} s, {:.1e} of the largest step taken ({:e} s); the velocity \
             grows without bound{}",
            self.time.time,
            self.time.step,
            allowed / self.largest_dt,
            self.largest_dt,
            if self.direct.is_some() && self.particles.is_some() {
                " (with model direct: particles not much heavier than the fluid need the \
                 virtual mass, virtualMass in constant/couplingProperties)"
            } else {
                ""
            }
        ))
    }

    /// The bound on `Δt` of the fluid's scheme (paper eq. 3 for Euler), or of the drag-law
    /// model's explicit predictor.
    pub fn stability_bound(&self) -> f64 {
        match &self.drag {
            Some(drag) => drag.fluid.stability_bound(&self.fluid),
            None => self.fluid.stability_bound(),
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
        let constrained = direct.implicit_forcing_report();
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
            constrained_solve: (constrained.solves > 0).then_some(constrained),
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

    /// Writes the restart state (every array a bit-identical continuation needs).
    pub fn write_restart(&mut self, path: &std::path::Path) -> Result<(), FsimError> {
        let header = RestartHeader::new(self.time.time, self.time.step, self.dt);
        let cloud = self
            .particles
            .as_ref()
            .map(|p| p.dem.snapshot().to_arrays())
            .unwrap_or_default();
        let shell = self.direct.as_ref().map(|d| d.shell_state());
        let build = self.direct.as_ref().map(|d| d.build_state());
        let motion = self.motion.as_ref().map(|m| m.restart_state());
        let mut arrays = self.fluid.restart_arrays();
        arrays.extend(cloud.iter().map(|(name, v)| (*name, v.as_slice())));
        if let Some(shell) = &shell {
            arrays.push((DirectCoupling::RESTART_NAME, shell.as_slice()));
        }
        if let Some(build) = &build {
            arrays.push((DirectCoupling::BUILD_RESTART_NAME, build.as_slice()));
        }
        if let Some(motion) = &motion {
            arrays.push((ParticleMotion::RESTART_NAME, motion.as_slice()));
        }
        header
            .write(path, &arrays)
            .map_err(|e| FsimError::run(e.to_string()))
    }
}

/// The engine continued from the DEM arrays of a restart state (same config and box, from the
/// case).
fn restore_particles(
    cloud: Cloud,
    state: &RestartState,
    time_dir: &std::path::Path,
) -> Result<Particles, FsimError> {
    let path = time_dir.join(crate::output::RESTART_FILE_NAME);
    let snapshot = DemSnapshot::from_arrays(|name| state.array(name))
        .map_err(|e| FsimError::input(format!("{}: {e}", path.display())))?;
    let dem = Dem::restore(cloud.config, cloud.domain, &snapshot)
        .map_err(|e| FsimError::input(format!("{}: {e}", path.display())))?;
    Ok(Particles {
        dem,
        pair_model: cloud.pair_model_name,
        wall_model: cloud.wall_model_name,
        substeps: 0,
        notes: cloud.warnings,
    })
}

/// `fsim { timeScheme EulerImplicit; }`: the drag-law predictor with its viscous term implicit.
const DRAG_LAW_IMPLICIT: &str = "EulerImplicit";

/// The fluid's scheme from `fsim { timeScheme …; }`, and whether the drag-law predictor takes
/// its viscous term implicitly. The drag-law model steps the fluid with its own
/// volume-averaged predictor: there the scheme names its viscous term (`Euler`, the default,
/// or `EulerImplicit`), and the resolved solver is built with `Euler`, which needs no stage
/// storage.
fn fluid_scheme(case: &Case) -> Result<(TimeScheme, bool), FsimError> {
    let drag_law_case =
        case.coupling.model == CouplingModel::DragLaw && case.cloud_properties.is_some();
    Ok(match (&case.time_scheme, drag_law_case) {
        (None, true) => (TimeScheme::Euler, false),
        (Some(name), true) => match name.as_str() {
            "Euler" => (TimeScheme::Euler, false),
            DRAG_LAW_IMPLICIT => (TimeScheme::Euler, true),
            other => {
                return Err(case
                    .time_scheme_error(format!(
                        "the drag-law model runs timeScheme Euler (explicit viscous term, the \
                         default) or {DRAG_LAW_IMPLICIT} (implicit viscous term), not '{other}'"
                    ))
                    .into())
            }
        },
        (None, false) => (TimeScheme::default(), false),
        (Some(name), false) => {
            let scheme = TimeScheme::from_name(name).ok_or_else(|| {
                let hint = if name == DRAG_LAW_IMPLICIT {
                    " (EulerImplicit is the drag-law model's)"
                } else {
                    ""
                };
                case.time_scheme_error(format!(
                    "unknown fsim timeScheme '{name}'; expected one of Euler, RK2, RK3, RK3CN, \
                     EulerCN, EulerRKC{hint}"
                ))
            })?;
            (scheme, false)
        }
    })
}

/// The drag-law model of a case with `model dragLaw` and a cloud (`None` otherwise).
fn drag_law(
    case: &Case,
    cloud: &Cloud,
    fluid: &FluidSolver,
    dem: &Dem,
    implicit_viscosity: bool,
) -> Result<Option<DragLawCoupling>, FsimError> {
    let Some(read) = &cloud.drag_law else {
        return Ok(None);
    };
    if !case.mean_velocity_forces.is_empty() {
        return Err(FsimError::input(
            "fvOptions: meanVelocityForce is not supported with the drag-law model (drive the \
             flow with an inlet, or with constant/g)",
        ));
    }
    let settings = read.settings(&case.transport, case.gravity);
    let mut coupling = DragLawCoupling::new(settings, fluid, dem)
        .map_err(|e| FsimError::input(format!("drag-law model: {e}")))?;
    coupling.fluid.set_implicit_viscosity(implicit_viscosity);
    let superficial = std::array::from_fn(|face| {
        matches!(
            case.fields.u_bc[case.mesh.face_patch[face]],
            VelocityBc::InterstitialInletVelocity { .. }
        )
    });
    coupling.fluid.set_superficial_inlets(superficial);
    // DPMFoam's stopping test for its final pressure corrector (case/pressure_solver.rs).
    if let Some(fv_solution) = &case.fv_solution {
        if let Some(c) = PressureSolverControls::from_fv_solution(fv_solution)? {
            coupling.fluid.convergence = Convergence::OpenFoam {
                tolerance: c.tolerance,
                rel_tol: c.rel_tol,
            };
            if let Some(max) = c.max_iter {
                coupling.fluid.max_iterations = max;
            }
        }
    }
    // A box periodic on all faces cannot hold the mixture's weight with its periodic pressure.
    coupling.carry_mixture_weight(dem);
    Ok(Some(coupling))
}

/// Whether the case starts from the latest time directory.
pub fn continues(case: &Case) -> bool {
    case.control.start_from == StartFrom::LatestTime
}

/// The `meanVelocityForce` of the case, along the one axis its `Ubar` points.
fn mean_velocity_force(case: &Case) -> Result<Option<MeanVelocityForce>, FsimError> {
    match case.mean_velocity_forces.as_slice() {
        [] => Ok(None),
        [one] => {
            let axes: Vec<usize> = (0..3).filter(|&d| one.ubar[d] != 0.0).collect();
            match axes.as_slice() {
                [d] => Ok(Some(MeanVelocityForce::new(
                    *d,
                    one.ubar[*d],
                    one.relaxation,
                ))),
                _ => Err(FsimError::input(format!(
                    "fvOptions '{}': fsim drives the flow along one axis; Ubar ({} {} {}) \
                     must have exactly one non-zero component",
                    one.name, one.ubar[0], one.ubar[1], one.ubar[2]
                ))),
            }
        }
        _ => Err(FsimError::input(
            "fvOptions: fsim takes at most one meanVelocityForce".to_string(),
        )),
    }
}

/// The solver's condition on each box face, from the patch type and the `U`/`p` conditions
/// the case gives it.
///
/// DPMFoam's pairs: `noSlip` + `fixedFluxPressure` is a wall; `interstitialInletVelocity` +
/// `fixedFluxPressure` an [`FaceCondition::Inlet`] whose velocity is the *superficial*
/// `inletVelocity` (the volumetric flux per area; the interstitial velocity on the face is
/// `inletVelocity / ε`, see [`interstitial_inlets`]); `pressureInletOutletVelocity` +
/// `fixedValue` p an [`FaceCondition::Outlet`] at that pressure, which lets the flow enter as
/// well as leave (its normal velocity follows the pressure; on back-flow the tangential
/// velocity stays zero-gradient where OpenFOAM takes `inletValue`'s); `symmetry` a slip face.
pub fn boundary_conditions(case: &Case) -> Result<BoundaryConditions, FsimError> {
    let mesh = &case.mesh;
    let fields = &case.fields;
    let mut faces: [FaceCondition; 6] = std::array::from_fn(|_| FaceCondition::Periodic);
    for (face, slot) in faces.iter_mut().enumerate() {
        let index = mesh.face_patch[face];
        let patch = &mesh.patches[index];
        let (u, p) = (&fields.u_bc[index], &fields.p_bc[index]);
        let cannot = || {
            FsimError::input(format!(
                "0/{} and 0/p: fsim cannot honour U '{}' with p '{}' on patch '{}' ({})",
                fields.velocity_name,
                velocity_bc_name(u),
                pressure_bc_name(p),
                patch.name,
                patch.kind.name()
            ))
        };
        *slot = match patch.kind {
            PatchType::Cyclic => FaceCondition::Periodic,
            PatchType::Empty => FaceCondition::Empty,
            PatchType::Symmetry | PatchType::SymmetryPlane => FaceCondition::Slip,
            PatchType::Wall | PatchType::Patch => match (u, p) {
                (VelocityBc::Slip, _) => FaceCondition::Slip,
                (VelocityBc::NoSlip, PressureBc::ZeroGradient | PressureBc::FixedFluxPressure) => {
                    FaceCondition::Wall { velocity: [0.0; 3] }
                }
                (
                    VelocityBc::FixedValue(v),
                    PressureBc::ZeroGradient | PressureBc::FixedFluxPressure,
                ) => {
                    if patch.kind == PatchType::Wall {
                        FaceCondition::Wall { velocity: *v }
                    } else {
                        FaceCondition::Inlet { velocity: *v }
                    }
                }
                (
                    VelocityBc::InterstitialInletVelocity { inlet_velocity, .. },
                    PressureBc::ZeroGradient | PressureBc::FixedFluxPressure,
                ) => FaceCondition::Inlet {
                    velocity: *inlet_velocity,
                },
                (
                    VelocityBc::ZeroGradient
                    | VelocityBc::PressureInletOutletVelocity
                    | VelocityBc::InletOutlet { .. },
                    PressureBc::FixedValue(p0) | PressureBc::TotalPressure { p0 },
                ) => FaceCondition::Outlet { pressure: *p0 },
                _ => return Err(cannot()),
            },
        };
    }
    Ok(BoundaryConditions { faces })
}

/// The superficial inlet velocity (`inletVelocity` of an `interstitialInletVelocity`) of each
/// box face that has one. The face's [`FaceCondition::Inlet`] carries the same vector; a
/// volume-averaged fluid imposes `ε_f u·n = inletVelocity·n` there, i.e. the interstitial
/// velocity `inletVelocity / ε_f` with `ε_f` the fraction of the adjacent cell (DPMFoam's
/// `alpha.air` is zero-gradient on patches).
pub fn interstitial_inlets(case: &Case) -> [Option<[f64; 3]>; 6] {
    std::array::from_fn(|face| {
        let index = case.mesh.face_patch[face];
        match &case.fields.u_bc[index] {
            VelocityBc::InterstitialInletVelocity { inlet_velocity, .. } => Some(*inlet_velocity),
            _ => None,
        }
    })
}

fn velocity_bc_name(bc: &VelocityBc) -> &'static str {
    match bc {
        VelocityBc::NoSlip => "noSlip",
        VelocityBc::FixedValue(_) => "fixedValue",
        VelocityBc::ZeroGradient => "zeroGradient",
        VelocityBc::Cyclic => "cyclic",
        VelocityBc::Symmetry => "symmetry",
        VelocityBc::SymmetryPlane => "symmetryPlane",
        VelocityBc::Slip => "slip",
        VelocityBc::Empty => "empty",
        VelocityBc::PressureInletOutletVelocity => "pressureInletOutletVelocity",
        VelocityBc::InletOutlet { .. } => "inletOutlet",
        VelocityBc::InterstitialInletVelocity { .. } => "interstitialInletVelocity",
    }
}

fn pressure_bc_name(bc: &PressureBc) -> &'static str {
    match bc {
        PressureBc::ZeroGradient => "zeroGradient",
        PressureBc::FixedFluxPressure => "fixedFluxPressure",
        PressureBc::FixedValue(_) => "fixedValue",
        PressureBc::TotalPressure { .. } => "totalPressure",
        PressureBc::Cyclic => "cyclic",
        PressureBc::Symmetry => "symmetry",
        PressureBc::SymmetryPlane => "symmetryPlane",
        PressureBc::Empty => "empty",
    }
}

/// The direct model's resolution warnings on the case's particles (gaps narrower than 2h,
/// fixed spheres with nothing driving the flow), for `-dry-run` and the log.
fn check_direct_resolution(
    fluid: &FluidSolver,
    cloud: &Cloud,
    settings: &DirectSettings,
) -> Vec<String> {
    let grid = fluid.grid();
    let bc = fluid.boundary_conditions();
    let length = grid.length();
    let domain = PeriodicBox {
        lo: grid.origin,
        hi: std::array::from_fn(|a| grid.origin[a] + length[a]),
        periodic: std::array::from_fn(|a| matches!(bc.faces[2 * a], FaceCondition::Periodic)),
    };
    let walls: [bool; 6] =
        std::array::from_fn(|f| matches!(bc.faces[f], FaceCondition::Wall { .. }));
    let mut particles = cloud.particles.clone();
    if settings.fixed_particles {
        particles.fixed.iter_mut().for_each(|f| *f = true);
    }
    let moving_wall = bc.faces.iter().any(|f| match f {
        FaceCondition::Wall { velocity } => *velocity != [0.0; 3],
        FaceCondition::Inlet { .. } => true,
        _ => false,
    });
    let driven = fluid.mean_velocity_force().is_some() || moving_wall;
    let report = check_resolution(
        grid,
        &particles,
        &domain,
        walls,
        driven,
        // overlaps are the DEM loader's to report, with the positions file's line
        f64::INFINITY,
    );
    // Its errors (r/h below 2, a sphere wider than the box) are reported, with the particle
    // named, by `DirectCoupling::check_particles` and the DEM loader; here the warnings.
    report.warnings
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
