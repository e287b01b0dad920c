//! The state of a run between two steps, built from a validated case: the fluid with its
//! boundary conditions and driving, the time axis, and the coupling model with its particles.
//!
//! Everything a case asks for is checked here, before the first step: a boundary condition
//! the solver cannot honour, a time scheme it does not know, a fixed `deltaT` above the
//! scheme's stability bound (paper eq. 3) all stop the run with exit code 2.

use super::case_settings::{
    boundary_conditions, check_direct_resolution, drag_law, fluid_scheme, mean_velocity_force,
};
use super::coupling::Coupling;
use super::direct_model::DirectModel;
use super::drag_law_model::DragLawModel;
use super::particles::Particles;
use super::restart::restore_particles;
use super::step_size::coupling_step_warning;
use crate::case::{Case, Cloud, ControlDict, CouplingModel, InternalField};
use crate::coupling::direct::{periodic_directions, DirectCoupling};
use crate::coupling::drag::DragLawCoupling;
use crate::error::FsimError;
use crate::fluid::{FluidSettings, FluidSolver};
use crate::grid::Grid;
use crate::output::{RestartState, TimeEntry};
use crate::particles::Dem;
use crate::time_control::{TimeControl, WriteControl};

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
    /// collapsing Courant step is judged (`step_size.rs`).
    pub(super) largest_dt: f64,
    /// Fluid density, kg/m³ (the solver works with kinematic pressure p/ρ).
    pub rho: f64,
    /// The particles and the model that couples them to the fluid.
    pub coupling: Coupling,
    /// What the grid does not resolve well and where the step is held (`model direct`), for
    /// `-dry-run` and the log.
    pub warnings: Vec<String>,
    /// Wall time of the last step's phases.
    pub phase_times: PhaseTimes,
}

/// Wall time of the phases of one step, s: the fluid (predictor, projections, and with
/// `model direct` the no-slip imposition inside each stage), the coupling (the forced faces of
/// the moved spheres, the stress integral, lubrication) and the particles (the DEM; with the
/// drag law, the particles' forces too).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PhaseTimes {
    pub fluid: f64,
    pub coupling: f64,
    pub particles: f64,
}

impl Simulation {
    /// Builds the simulation from a validated case, starting from the case's initial fields,
    /// or from the restart state of `restart` when continuing (`startFrom latestTime`).
    pub fn new(case: &Case, restart: Option<&TimeEntry>) -> Result<Self, FsimError> {
        let (scheme, implicit_viscosity) = fluid_scheme(case)?;
        let settings = FluidSettings {
            nu: case.transport.nu,
            scheme,
            body_force: [0.0; 3],
            convection: case.convection,
        };
        let mut fluid =
            FluidSolver::new(case.mesh.grid.clone(), boundary_conditions(case)?, settings)
                .map_err(|e| {
                    if crate::memory::is_allocation_failure(&e) {
                        FsimError::run(e)
                    } else {
                        FsimError::input(format!("case: {e}"))
                    }
                })?;
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
            rho: case.transport.rho,
            coupling: Coupling::None { particles: None },
            warnings: Vec::new(),
            phase_times: PhaseTimes::default(),
        };
        let model = case.coupling.model;
        let cloud = Cloud::from_case(case)?;
        if let Some(cloud) = &cloud {
            // before the DEM's arrays: the grid's are in place, the particles' are not
            let n = cloud.particles.len();
            crate::memory::check(
                crate::memory::grid_bytes(case) + n as f64 * crate::memory::BYTES_PER_PARTICLE,
                &format!("constant/kinematicCloudProperties: {n} particles with the grid"),
            )?;
        }
        if let (CouplingModel::Direct, Some(cloud)) = (model, &cloud) {
            sim.warnings = check_direct_resolution(&sim.fluid, cloud, &case.coupling.direct);
        }
        let restart_dir = restart.map(|entry| case.dir.join(&entry.name));
        let state = match &restart_dir {
            Some(dir) => Some(sim.restore(dir, control)?),
            None => {
                sim.set_initial_fields(case);
                None
            }
        };
        let restored = restart_dir.as_deref().zip(state.as_ref());
        let (particles, mut drag) = match cloud {
            Some(cloud) => {
                let (p, drag) = sim.particles_of(case, cloud, restored, implicit_viscosity)?;
                (Some(p), drag)
            }
            None => (None, None),
        };
        if state.is_none() {
            start_fluid(&mut sim.fluid, drag.as_mut(), sim.dt);
        }
        sim.coupling = match (model, particles, drag) {
            (CouplingModel::Direct, None, _) => {
                return Err(FsimError::input(
                    "constant/couplingProperties: model direct needs particles \
                     (constant/kinematicCloudProperties)",
                ))
            }
            (CouplingModel::Direct, Some(particles), _) => {
                let direct = direct_model(&mut sim.fluid, particles, case, state.as_ref())?;
                sim.warnings.extend(coupling_step_warning(
                    sim.sizing,
                    direct.motion.step_bound(),
                ));
                Coupling::Direct(Box::new(direct))
            }
            (_, Some(particles), Some(coupling)) => Coupling::DragLaw(Box::new(DragLawModel {
                particles,
                coupling,
            })),
            (_, particles, _) => Coupling::None {
                particles: particles.map(Box::new),
            },
        };
        Ok(sim)
    }

    /// The particles of `cloud`, fresh or `restored` (the restart's time directory and
    /// state), and the drag-law coupling when the case runs that model (restored to the
    /// particles' ε and the fluid's ∇p when continuing; `implicit_viscosity`: its
    /// `EulerImplicit` predictor).
    fn particles_of(
        &self,
        case: &Case,
        cloud: Cloud,
        restored: Option<(&std::path::Path, &RestartState)>,
        implicit_viscosity: bool,
    ) -> Result<(Particles, Option<DragLawCoupling>), FsimError> {
        let settings = cloud.clone();
        let particles = match restored {
            Some((dir, state)) => restore_particles(cloud, state, dir)?,
            None => {
                let mut state = cloud.particles.clone();
                // `direct { fixedParticles yes; }` or `dragLawCoeffs { fixedParticles yes; }`
                let fixed = match case.coupling.model {
                    CouplingModel::Direct => case.coupling.direct.fixed_particles,
                    CouplingModel::DragLaw => {
                        cloud.drag_law.as_ref().is_some_and(|d| d.fixed_particles)
                    }
                    CouplingModel::None => false,
                };
                if fixed {
                    state.fixed.iter_mut().for_each(|f| *f = true);
                }
                let dem = Dem::new(cloud.config.clone(), cloud.domain.clone(), state)
                    .map_err(|e| cloud.locate(&e))?;
                Particles::new(cloud, dem)
            }
        };
        let mut drag = drag_law(
            case,
            &settings,
            &self.fluid,
            &particles.dem,
            implicit_viscosity,
        )?;
        if let (Some(drag), Some(_)) = (drag.as_mut(), restored) {
            drag.restore(&self.fluid, &particles.dem)
                .map_err(FsimError::input)?;
        }
        Ok((particles, drag))
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

    /// The particles, when there are any.
    pub fn particles(&self) -> Option<&Particles> {
        self.coupling.particles()
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

    /// The hint a diverged run of the direct model gets: light spheres need the virtual mass.
    pub(super) fn virtual_mass_hint(&self) -> &'static str {
        match self.coupling {
            Coupling::Direct(_) => {
                " (with model direct: particles not much heavier than the fluid need the \
                 virtual mass, virtualMass in constant/couplingProperties)"
            }
            _ => "",
        }
    }
}

/// A fresh run's fluid: the initial field made discretely divergence-free (as the first
/// pressure correction would), and with the drag law the pressure of that field and ε for a
/// step of `dt`. Not in DPMFoam's form: its first cloud evolution sees the case's field as
/// given (a bed at rest in a column whose inlet is open), and only its first pressure
/// correction makes the flow through the column.
fn start_fluid(fluid: &mut FluidSolver, drag: Option<&mut DragLawCoupling>, dt: f64) {
    if drag.as_ref().is_none_or(|d| d.projects_initial_field()) {
        fluid.project();
    }
    if let Some(drag) = drag {
        drag.initialise_pressure(fluid, dt);
    }
}

/// The direct model of `case` for `particles` (checked against the grid: r/h, size), after
/// the fluid has started; continued from `state` when given.
fn direct_model(
    fluid: &mut FluidSolver,
    mut particles: Particles,
    case: &Case,
    state: Option<&RestartState>,
) -> Result<DirectModel, FsimError> {
    let periodic = periodic_directions(fluid.boundary_conditions());
    let notes = DirectCoupling::check_particles(fluid.grid(), periodic, particles.dem.particles())
        .map_err(|e| FsimError::input(format!("constant/kinematicCloudProperties: {e}")))?;
    particles.notes.extend(notes);
    let settings = (case.coupling.direct.clone(), case.coupling.motion);
    DirectModel::new(fluid, particles, settings, case.transport.rho, state)
        .map_err(FsimError::input)
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
