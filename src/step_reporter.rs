//! What the time loop tells the user after each step: the log block in OpenFOAM's manner and
//! the per-step monitors in `postProcessing/fluid/` and `postProcessing/cloud/`.

use crate::error::FsimError;
use crate::output::{Log, Monitor, OutputError};
use crate::simulation::{CloudReport, Coupling, DirectModel, DragLawModel, Simulation, TakenStep};
use crate::Vec3;
use std::io::Stdout;
use std::path::Path;
use std::time::Duration;

/// Columns of the per-step fluid monitor `postProcessing/fluid/<startTime>/fluid.dat`.
const FLUID_MONITOR_COLUMNS: [&str; 14] = [
    "Time",
    "deltaT",
    "CoMax",
    "divergence",
    "kineticEnergy",
    "Ux",
    "Uy",
    "Uz",
    "drivingGradient",
    "stepWallTime",
    "step",
    "fluidWallTime",
    "couplingWallTime",
    "particleWallTime",
];

/// Columns of the per-step particle monitor `postProcessing/cloud/<startTime>/cloud.dat`.
const CLOUD_MONITOR_COLUMNS: [&str; 9] = [
    "Time",
    "particles",
    "kineticEnergy",
    "rotationalEnergy",
    "Ux",
    "Uy",
    "Uz",
    "maxOverlapOverD",
    "subSteps",
];

/// Columns of the drag-law monitor `postProcessing/dragLaw/<startTime>/dragLaw.dat`: the
/// smallest ε, the pressure drop along gravity less the fluid's weight (Pa), the drag on the
/// particles and its reaction on the fluid (N; equal and opposite), the total hydrodynamic
/// force, the mean particle velocity, the pressure CG's iterations, the continuity error, and
/// with a `meanVelocityForce` the drag coefficient `K` of paper eq. 19
/// ([`DragLawModel::drag_coefficient`]; 0 without the fvOption).
const DRAG_MONITOR_COLUMNS: [&str; 18] = [
    "Time",
    "alphaMin",
    "pressureDrop",
    "FdParticlesX",
    "FdParticlesY",
    "FdParticlesZ",
    "FdFluidX",
    "FdFluidY",
    "FdFluidZ",
    "FhX",
    "FhY",
    "FhZ",
    "UpX",
    "UpY",
    "UpZ",
    "pIterations",
    "continuityError",
    "K",
];

/// Columns of the direct model's monitor `postProcessing/direct/<startTime>/direct.dat`:
/// total hydrodynamic force and torque on the particles, and `K` (paper eq. 19, see
/// [`crate::simulation::HydrodynamicReport`]).
const DIRECT_MONITOR_COLUMNS: [&str; 8] = ["Time", "Fx", "Fy", "Fz", "Tx", "Ty", "Tz", "K"];

/// Columns of the settling monitor `postProcessing/sedimentation/<startTime>/sedimentation.dat`
/// (`model direct` with free particles): solid fraction, mean particle and fluid velocities,
/// the settling velocity along gravity in the frame of zero volume flux (positive: falling),
/// the mixture's momentum and its scale `Σ m|v|`, the imposed excess mean pressure gradient
/// (magnitude, correction included) and its momentum-holding correction over the analytic
/// value, and the lubrication pairs and smallest gap over the radius.
const SEDIMENTATION_MONITOR_COLUMNS: [&str; 17] = [
    "Time",
    "phi",
    "Vpx",
    "Vpy",
    "Vpz",
    "Ufx",
    "Ufy",
    "Ufz",
    "settlingVelocity",
    "Mx",
    "My",
    "Mz",
    "momentumScale",
    "driveGradient",
    "driveCorrection",
    "lubricationPairs",
    "minGapOverR",
];

/// The monitors a run may open, `postProcessing/<name>/<startTime>/<name>.dat` each: the
/// places checked for links before the run starts (src/output/case_output.rs).
pub const MONITOR_NAMES: [&str; 5] = ["fluid", "cloud", "dragLaw", "direct", "sedimentation"];

/// The log and the monitors of one run.
pub struct StepReporter {
    pub log: Log<Stdout>,
    fluid: Monitor,
    cloud: Option<Monitor>,
    drag: Option<Monitor>,
    /// Opened at the first step that has hydrodynamic loads.
    direct: Option<Monitor>,
    /// Opened at the first step with a settling report.
    sedimentation: Option<Monitor>,
    case_dir: std::path::PathBuf,
    start_name: String,
    /// Steps with a cloud, and those of them taken in free flight.
    cloud_steps: u64,
    free_flight_steps: u64,
}

fn output_error(e: OutputError) -> FsimError {
    FsimError::run(e.to_string())
}

impl StepReporter {
    /// Opens the monitors of a run starting at time `start_name` (a continued run gets its own
    /// `<startTime>` directories, as OpenFOAM's function objects do).
    pub fn open(
        case_dir: &Path,
        start_name: &str,
        has_cloud: bool,
        has_drag: bool,
    ) -> Result<Self, FsimError> {
        let fluid = Monitor::create(case_dir, "fluid", start_name, &FLUID_MONITOR_COLUMNS)
            .map_err(output_error)?;
        let cloud = if has_cloud {
            Some(
                Monitor::create(case_dir, "cloud", start_name, &CLOUD_MONITOR_COLUMNS)
                    .map_err(output_error)?,
            )
        } else {
            None
        };
        let drag = if has_drag {
            Some(
                Monitor::create(case_dir, "dragLaw", start_name, &DRAG_MONITOR_COLUMNS)
                    .map_err(output_error)?,
            )
        } else {
            None
        };
        Ok(StepReporter {
            log: Log::stdout(),
            fluid,
            cloud,
            drag,
            direct: None,
            sedimentation: None,
            case_dir: case_dir.to_path_buf(),
            start_name: start_name.to_string(),
            cloud_steps: 0,
            free_flight_steps: 0,
        })
    }

    /// The `Time = …` block and one monitor row per phase of the step just taken.
    pub fn step(
        &mut self,
        time_name: &str,
        sim: &Simulation,
        step: &TakenStep,
        wall: Duration,
    ) -> Result<(), FsimError> {
        let TakenStep {
            dt,
            fluid,
            cloud,
            health,
            ..
        } = step;
        let (dt, cloud) = (*dt, cloud.as_ref());
        self.log.time(time_name)?;
        self.log.line(&format!(
            "Courant Number max: {:.6}\ndeltaT = {}\nProjection: divergence = {:.3e}, kinetic \
             energy = {:.6e}",
            health.max_courant, dt, health.divergence, health.kinetic_energy
        ))?;
        let stages = sim.fluid.chebyshev_stages_taken();
        if stages > 0 {
            self.log.line(&format!(
                "EulerRKC: {stages} Chebyshev stages of the diffusion"
            ))?;
        }
        if let Some(g) = fluid.driving_gradient {
            self.log
                .line(&format!("meanVelocityForce: pressure gradient = {g:.6e}"))?;
        }
        let [ux, uy, uz] = health.mean_velocity;
        self.fluid
            .row(&[
                sim.time.time,
                dt,
                health.max_courant,
                health.divergence,
                health.kinetic_energy,
                ux,
                uy,
                uz,
                fluid.driving_gradient.unwrap_or(0.0),
                wall.as_secs_f64(),
                sim.time.step as f64,
                sim.phase_times.fluid,
                sim.phase_times.coupling,
                sim.phase_times.particles,
            ])
            .map_err(output_error)?;
        if let Coupling::Direct(model) = &sim.coupling {
            self.direct_model(sim.time.time, model)?;
        }
        if let (Some(c), Some(m)) = (cloud, self.cloud.as_mut()) {
            self.cloud_steps += 1;
            self.free_flight_steps += c.free_flight as u64;
            log_cloud(&mut self.log, c)?;
            let [ux, uy, uz] = c.mean_velocity.into();
            m.row(&[
                sim.time.time,
                c.count as f64,
                c.kinetic_energy.0,
                c.kinetic_energy.1,
                ux,
                uy,
                uz,
                c.max_overlap,
                c.substeps as f64,
            ])
            .map_err(output_error)?;
        }
        if let Coupling::DragLaw(model) = &sim.coupling {
            self.drag_law_model(sim, model, cloud)?;
        }
        Ok(())
    }

    /// The direct model's lines and monitor rows: the hydrodynamic loads and forced faces,
    /// the settling of free spheres.
    fn direct_model(&mut self, time: f64, model: &DirectModel) -> Result<(), FsimError> {
        if let Some(h) = &model.loads {
            if self.direct.is_none() {
                self.direct = Some(
                    Monitor::create(
                        &self.case_dir,
                        "direct",
                        &self.start_name,
                        &DIRECT_MONITOR_COLUMNS,
                    )
                    .map_err(output_error)?,
                );
            }
            self.log.line(&format!(
                "Hydrodynamic force: total ({:.6e} {:.6e} {:.6e}) N, K = {:.6}",
                h.force[0], h.force[1], h.force[2], h.drag_coefficient
            ))?;
            {
                let d = &model.coupling;
                self.log.line(&format!(
                    "Forced faces: {} ({})",
                    d.boundary().forced_count(),
                    if d.last_rebuilt() {
                        "rebuilt"
                    } else {
                        "kept, following the spheres"
                    }
                ))?;
            }
            if let Some(m) = self.direct.as_mut() {
                m.row(&[
                    time,
                    h.force[0],
                    h.force[1],
                    h.force[2],
                    h.torque[0],
                    h.torque[1],
                    h.torque[2],
                    h.drag_coefficient,
                ])
                .map_err(output_error)?;
            }
        }
        if let Some(r) = &model.settling {
            if self.sedimentation.is_none() {
                self.sedimentation = Some(
                    Monitor::create(
                        &self.case_dir,
                        "sedimentation",
                        &self.start_name,
                        &SEDIMENTATION_MONITOR_COLUMNS,
                    )
                    .map_err(output_error)?,
                );
            }
            let lubrication = model.motion.last_lubrication();
            self.log.line(&format!(
                "Sedimentation: settling velocity = {:.6e} m/s (phi = {:.4}), mixture momentum \
                 ({:.3e} {:.3e} {:.3e}) of {:.3e} kg m/s, lubrication pairs {}",
                r.settling_velocity,
                r.phi,
                r.momentum[0],
                r.momentum[1],
                r.momentum[2],
                r.momentum_scale,
                lubrication.active
            ))?;
            let g = r.drive_gradient;
            let g_norm = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
            if let Some(m) = self.sedimentation.as_mut() {
                m.row(&[
                    time,
                    r.phi,
                    r.particle_velocity[0],
                    r.particle_velocity[1],
                    r.particle_velocity[2],
                    r.fluid_velocity[0],
                    r.fluid_velocity[1],
                    r.fluid_velocity[2],
                    r.settling_velocity,
                    r.momentum[0],
                    r.momentum[1],
                    r.momentum[2],
                    r.momentum_scale,
                    g_norm,
                    r.drive_correction,
                    lubrication.active as f64,
                    if lubrication.min_gap_ratio.is_finite() {
                        lubrication.min_gap_ratio
                    } else {
                        -1.0
                    },
                ])
                .map_err(output_error)?;
            }
        }
        Ok(())
    }

    /// The drag-law model's lines and monitor row: ε, the pressure drop, the exchanged
    /// momentum, the pressure solve.
    fn drag_law_model(
        &mut self,
        sim: &Simulation,
        model: &DragLawModel,
        cloud: Option<&CloudReport>,
    ) -> Result<(), FsimError> {
        let d = &model.coupling;
        if let Some(m) = self.drag.as_mut() {
            let e = &d.last;
            let g = d.settings.gravity;
            let axis = if g == Vec3::zeros() {
                2
            } else {
                (0..3)
                    .max_by(|&a, &b| g[a].abs().total_cmp(&g[b].abs()))
                    .unwrap_or(2)
            };
            // Measured against the flow that holds the bed up: upstream (the side gravity
            // points to) minus downstream.
            let drop = d.pressure_drop(&sim.fluid, axis) * if g[axis] > 0.0 { -1.0 } else { 1.0 };
            let up = cloud.map_or(Vec3::zeros(), |c| c.mean_velocity);
            let (iterations, continuity) = d.last_fluid.map_or((0.0, 0.0), |r| {
                (r.pressure.iterations as f64, r.continuity_error)
            });
            self.log.line(&format!(
                "Drag law: alpha min = {:.6}, pressure drop = {:.6e} Pa, p CG iterations = \
                 {iterations}, continuity error = {continuity:.3e}",
                e.min_fluid_fraction, drop
            ))?;
            let k = model.drag_coefficient(&sim.fluid);
            if sim.fluid.mean_velocity_force().is_some() {
                let f = e.hydrodynamic_force;
                self.log.line(&format!(
                    "Hydrodynamic force: total ({:.6e} {:.6e} {:.6e}) N, K = {k:.6}",
                    f[0], f[1], f[2]
                ))?;
            }
            if let Some(v) = d
                .last_fluid
                .map(|r| r.viscous)
                .filter(|_| d.fluid.implicit_viscosity())
            {
                self.log.line(&format!(
                    "Viscous term (implicit): U CG iterations = {}, residual = {:.3e}",
                    v.iterations, v.relative_residual
                ))?;
            }
            m.row(&[
                sim.time.time,
                e.min_fluid_fraction,
                drop,
                e.drag_on_particles[0],
                e.drag_on_particles[1],
                e.drag_on_particles[2],
                e.drag_on_fluid[0],
                e.drag_on_fluid[1],
                e.drag_on_fluid[2],
                e.hydrodynamic_force[0],
                e.hydrodynamic_force[1],
                e.hydrodynamic_force[2],
                up[0],
                up[1],
                up[2],
                iterations,
                continuity,
                k,
            ])
            .map_err(output_error)?;
        }
        Ok(())
    }

    /// Closes the step's block (`ExecutionTime = …`) and redraws the progress bar.
    pub fn end_step(&mut self, time: f64, start: f64, end: f64) -> Result<(), FsimError> {
        self.log.execution_time()?;
        self.log.progress(time, start, end);
        Ok(())
    }

    /// Flushes the monitors and ends the log, after the count of free-flight steps.
    pub fn finish(mut self) -> Result<(), FsimError> {
        if self.cloud_steps > 0 {
            self.log.line(&format!(
                "Free flight: {} of {} steps (no pair or wall could meet within them: one step \
                 each, contact detection skipped)\n",
                self.free_flight_steps, self.cloud_steps
            ))?;
        }
        self.fluid.flush().map_err(output_error)?;
        for m in self
            .cloud
            .iter_mut()
            .chain(self.drag.iter_mut())
            .chain(self.direct.iter_mut())
            .chain(self.sedimentation.iter_mut())
        {
            m.flush().map_err(output_error)?;
        }
        self.log.end()?;
        Ok(())
    }
}

/// The cloud's lines of the step log, in the manner of DPMFoam's.
fn log_cloud(log: &mut Log<std::io::Stdout>, c: &CloudReport) -> std::io::Result<()> {
    let [ux, uy, uz] = c.mean_velocity.into();
    let steps = if c.free_flight {
        "free flight (no contact possible)".to_string()
    } else {
        format!("{} collision sub-steps", c.substeps)
    };
    log.line(&format!(
        "Cloud: {} particles, {steps}\n    Linear kinetic energy = {:.6e}\n    \
         Rotational kinetic energy = {:.6e}\n    Mean velocity = ({:.6e} {:.6e} {:.6e})\n    \
         Max overlap / d = {:.4e}",
        c.count, c.kinetic_energy.0, c.kinetic_energy.1, ux, uy, uz, c.max_overlap
    ))
}
