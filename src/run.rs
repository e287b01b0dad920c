//! The time loop, read like the algorithm (DPMFoam's main file in spirit):
//!
//! ```text
//! load and validate the case                  (nothing is written before this succeeds)
//! build the simulation: grid, fluid, initial or restart state
//! while time remains:                        (system/controlDict read again if changed)
//!     take a step                            (Simulation::step, src/simulation/step.rs:
//!                                             Δt, the model's phases, the health check)
//!     monitor, log
//!     write the time directory when due       (whole or not at all)
//! ```

use crate::case::quote::bound_message;
use crate::case::{Case, ControlChange, ControlDict, ControlDictWatch, InternalField, StopAt};
use crate::cli::Options;
use crate::error::FsimError;
use crate::output::{
    time_name, write_fluid, Banner, CaseOutput, CellData, OutputError, PARTICLE_FILE_NAME,
    RESTART_FILE_NAME,
};
use crate::run_signals::RunSignals;
use crate::simulation::{continues, Coupling, Simulation, StepSizing};
use crate::step_reporter::{StepReporter, MONITOR_NAMES};
use std::time::Instant;

/// Runs `fsimFoam` with the given options.
pub fn run(options: &Options) -> Result<(), FsimError> {
    crate::case::control_dict::set_plan_limits(options.plan_limits());
    crate::memory::set_user_limit(options.memory);
    let cores = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1);
    let threads = options.threads.unwrap_or(cores);
    check_threads(threads, cores)?;
    // From before the case is read, so that no change made while the run starts is missed.
    let watch = ControlDictWatch::new(&options.case);
    let mut case = load_case(options)?;
    let cells = case.mesh.grid.n;
    crate::memory::check(
        crate::memory::grid_bytes(&case),
        &format!(
            "system/blockMeshDict: the grid of {} x {} x {} cells",
            cells[0], cells[1], cells[2]
        ),
    )?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| FsimError::run(format!("cannot start {threads} threads: {e}")))?;
    pool.install(|| run_case(&mut case, options, threads, watch))
}

/// Most threads per core `-threads` may ask for: a thread pool is started before the case
/// runs, and thousands of threads only take memory and start-up time on cores that they share.
pub const THREADS_PER_CORE: usize = 4;

/// Refuses `-threads 0` and more than [`THREADS_PER_CORE`] threads per core (at least 8 in
/// all), before the case is read.
fn check_threads(threads: usize, cores: usize) -> Result<(), FsimError> {
    let most = (THREADS_PER_CORE * cores).max(8);
    if threads == 0 {
        return Err(FsimError::input("-threads must be at least 1"));
    }
    if threads > most {
        return Err(FsimError::input(format!(
            "-threads {threads}: more than {THREADS_PER_CORE} per core of the {cores} this \
             machine has (at most {most}); more threads than cores only share them"
        )));
    }
    Ok(())
}

/// Reads and validates every file of the case, listing the keywords fsim ignores; with
/// `model auto`, chooses the model and grid (src/auto) and prints the candidates.
fn load_case(options: &Options) -> Result<Case, FsimError> {
    let mut case = Case::load(&options.case)?;
    for warning in &case.warnings {
        eprintln!("fsimFoam: note: {}", bound_message(warning));
    }
    if case.coupling.auto_tolerance.is_some() {
        let choice = crate::auto::choose(&mut case)?;
        print!("{}", choice.report);
        for change in &choice.changes {
            eprintln!("fsimFoam: note: model auto: {}", bound_message(change));
        }
    }
    Ok(case)
}

fn run_case(
    case: &mut Case,
    options: &Options,
    threads: usize,
    watch: ControlDictWatch,
) -> Result<(), FsimError> {
    let output_error = |e: OutputError| FsimError::run(e.to_string());
    let restart = if continues(case) {
        crate::output::latest_time(&case.dir)
            .map_err(output_error)?
            .filter(|t| case.dir.join(&t.name).join(RESTART_FILE_NAME).exists())
    } else {
        None
    };
    let mut sim = Simulation::new(case, restart.as_ref())?;
    // The initial field now lives on the solver's faces; free the case's copy (24 B/cell).
    case.fields.u = InternalField::Uniform([0.0; 3]);
    let case = &*case;
    for note in sim.particles().iter().flat_map(|p| &p.notes) {
        eprintln!("fsimFoam: note: {}", bound_message(note));
    }
    // the drag-law model's notes on what its grid lets happen (a cell that a few particles
    // can over-fill)
    let drag_law_warnings = sim.coupling.drag_law().map(|m| &m.coupling.warnings);
    for warning in sim
        .warnings
        .iter()
        .chain(drag_law_warnings.into_iter().flatten())
    {
        eprintln!("fsimFoam: warning: {}", bound_message(warning));
    }
    check_first_step(&mut sim)?;
    if options.dry_run {
        return crate::run_plan::print_plan(case, &mut sim, threads);
    }

    // Nothing is written yet: a symbolic link where the run would write is bad input.
    crate::output::check_no_links_where_written(
        &case.dir,
        sim.time.time,
        &time_name(sim.time.time, case.control.time_precision),
        &MONITOR_NAMES,
    )
    .map_err(|e| FsimError::input(e.to_string()))?;
    let mut output = CaseOutput::open(
        &case.dir,
        case.control.time_precision,
        case.control.purge_write,
        sim.time.time,
    )
    .map_err(output_error)?;
    let start_name = output.time_name(sim.time.time);
    let mut reporter = StepReporter::open(
        &case.dir,
        &start_name,
        sim.particles().is_some(),
        sim.coupling.drag_law().is_some(),
    )?;
    reporter.log.banner(&banner(case, &sim, threads))?;
    if restart.is_none() && !case.dir.join(&start_name).join(RESTART_FILE_NAME).exists() {
        // The start time gets its VTK files and restart state too, so the series opens at t0.
        write_time(&mut output, &mut sim)?;
    }
    // The time last written: the start's directory holds its state by now.
    let mut written = sim.time.time;
    let start = sim.time.time;
    reporter.log.line("Starting time loop\n")?;

    let mut control = case.control.clone();
    let mut watch = control.run_time_modifiable.then_some(watch);
    let signals = RunSignals::install(control.write_now_signal, control.stop_at_write_now_signal)
        .map_err(FsimError::run)?;
    // The plan's limits hold while running too: clock- and CPU-time writes, and steps that
    // an adjustable time step shrank, could not be counted before the start.
    let limits = crate::case::control_dict::plan_limits();
    let (mut steps, mut writes) = (0.0, 0.0);
    while sim.time.running() {
        take_signals(&signals, &mut sim, &mut reporter)?;
        // As OpenFOAM's Time::run: read a changed controlDict only while running (a stop
        // is final), and look again whether to go on.
        if let Some(changed) = watch.as_mut().and_then(ControlDictWatch::changed) {
            take_new_controls(changed, &mut control, &mut sim, &mut output, &mut reporter)?;
            if !control.run_time_modifiable {
                watch = None;
            }
            if !sim.time.running() {
                break;
            }
        }
        steps += 1.0;
        if steps > limits.steps {
            return Err(beyond_limit(steps - 1.0, "time steps", "maxSteps", written));
        }
        let clock = Instant::now();
        let step = sim.step()?;
        let name = output.time_name(sim.time.time);
        reporter.step(&name, &sim, &step, clock.elapsed())?;
        if step.write_due {
            writes += 1.0;
            if writes > limits.writes {
                return Err(beyond_limit(writes - 1.0, "writes", "maxWrites", written));
            }
            write_time(&mut output, &mut sim)?;
            written = sim.time.time;
        }
        reporter.end_step(sim.time.time, start, sim.time.planned_end(step.dt))?;
    }
    // An endTime lowered during the run to a time already passed ends it where it is: that
    // time is written too (the last time always is, unless stopAt noWriteNow says not to).
    if written != sim.time.time && sim.time.final_write_due() {
        write_time(&mut output, &mut sim)?;
    }
    reporter.finish()
}

/// A run stopped at `-maxSteps` or `-maxWrites` (exit 1): its last written time is kept.
fn beyond_limit(count: f64, what: &str, option: &str, written: f64) -> FsimError {
    FsimError::run(format!(
        "the run has made {count:.0} {what}, the limit: stopped with time {written:?} the \
         last written (raise the limit with -{option} N; docs/security.md, \"Memory and work\")"
    ))
}

/// Takes a `system/controlDict` changed during the run (`runTimeModifiable`), or says why
/// not: a file that does not read leaves the settings as they were, and the run goes on.
fn take_new_controls(
    changed: ControlChange,
    control: &mut ControlDict,
    sim: &mut Simulation,
    output: &mut CaseOutput,
    reporter: &mut StepReporter,
) -> Result<(), FsimError> {
    let now = output.time_name(sim.time.time);
    let bound = sim.stability_bound();
    let refused = match changed {
        Err(e) => e.to_string(),
        // A run stopped by its own controlDict would lose what it computed since its last
        // write.
        Ok((new, _)) if !new.adjust_time_step && new.delta_t > bound => format!(
            "system/controlDict: deltaT {} exceeds the scheme's stability bound {bound:.4e} s \
             now",
            new.delta_t
        ),
        Ok((new, notes)) => {
            for note in notes {
                eprintln!("fsimFoam: note: {}", bound_message(&note));
                reporter.log.line(&format!("note: {note}"))?;
            }
            let changes = new.changes_from(control);
            let what = if changes.is_empty() {
                "nothing that a running case reads".to_string()
            } else {
                changes.join(", ")
            };
            reporter.log.line(&format!(
                "system/controlDict changed at t = {now}: {what}\n"
            ))?;
            sim.apply_control(&new);
            output.set_controls(new.time_precision, new.purge_write);
            *control = new;
            return Ok(());
        }
    };
    let message = format!("{refused}; the run goes on with the settings it had (t = {now})");
    eprintln!("fsimFoam: warning: {}", bound_message(&message));
    reporter.log.line(&format!("warning: {message}\n"))?;
    Ok(())
}

/// Acts on the signals that came since the last step: OpenFOAM's `writeNowSignal` writes
/// the next step, `stopAtWriteNowSignal` makes the run stop as `stopAt writeNow`.
fn take_signals(
    signals: &RunSignals,
    sim: &mut Simulation,
    reporter: &mut StepReporter,
) -> Result<(), FsimError> {
    let caught = signals.caught();
    if caught.write_now {
        sim.time.write_next_step();
        reporter.log.line(&format!(
            "signal {}: the next step is written\n",
            signals.write_now.unwrap_or(-1)
        ))?;
    }
    if caught.stop_at_write_now {
        let end = sim.time.end_time;
        sim.time.set_stop(StopAt::WriteNow, end);
        reporter.log.line(&format!(
            "signal {}: stopAt writeNow (the next step is written and ends the run)\n",
            signals.stop_at_write_now.unwrap_or(-1)
        ))?;
    }
    Ok(())
}

/// A fixed `deltaT` above the scheme's bound for the initial field is bad input (exit 2),
/// found before anything is written.
fn check_first_step(sim: &mut Simulation) -> Result<(), FsimError> {
    if let StepSizing::Fixed(_) = sim.sizing {
        sim.next_time_step()
            .map_err(|e| FsimError::input(e.to_string()))?;
    }
    Ok(())
}

/// Writes the current time directory: fluid fields for ParaView and meshio, restart state.
fn write_time(output: &mut CaseOutput, sim: &mut Simulation) -> Result<(), FsimError> {
    let output_error = |e: OutputError| FsimError::run(e.to_string());
    let grid = sim.grid().clone();
    let dir = output.begin(sim.time.time).map_err(output_error)?;
    let title = format!("fsim t = {}", output.time_name(sim.time.time));
    // The drag-law model's fluid fraction ε (DPMFoam's alpha.<phase>).
    let alpha = sim
        .coupling
        .drag_law()
        .map(|m| m.coupling.cell_fluid_fraction());
    // Velocity and pressure are read in place: a copy would add 24 and 8 B/cell to the
    // run's peak memory (the cell-centred velocity is interpolated as it is written).
    let fluid = &sim.fluid;
    let velocity = |cell: usize| fluid.cell_velocity_at(cell);
    let mut fields = vec![
        CellData::ComputedVector("U", grid.cell_count(), &velocity),
        CellData::Scalar("p", fluid.pressure()),
    ];
    if let Some(alpha) = &alpha {
        fields.push(CellData::Scalar("alpha", alpha));
    }
    write_fluid(dir.dir(), &grid, &title, &fields).map_err(output_error)?;
    drop(fields);
    if let Some(particles) = sim.particles() {
        particles.write(dir.dir(), PARTICLE_FILE_NAME)?;
    }
    sim.write_restart(dir.dir(), RESTART_FILE_NAME)?;
    output.commit(dir).map_err(output_error)?;
    Ok(())
}

fn banner(case: &Case, sim: &Simulation, threads: usize) -> Banner {
    let mut extra = vec![
        (
            "Scheme".to_string(),
            match &sim.coupling {
                Coupling::DragLaw(m) => format!(
                    "volume-averaged ({}, PCG pressure)",
                    m.coupling.fluid.predictor_name()
                ),
                _ => sim.fluid.settings().scheme.name().to_string(),
            },
        ),
        ("nu".to_string(), format!("{:e} m2/s", case.transport.nu)),
    ];
    if let Some(m) = sim.coupling.drag_law() {
        extra.push(("Drag law".to_string(), m.coupling.describe()));
    }
    if let Some(p) = sim.particles() {
        extra.push((
            "Particles".to_string(),
            format!(
                "{} (pairModel {}, wallModel {})",
                p.dem.particles().len(),
                p.pair_model,
                p.wall_model
            ),
        ));
    }
    Banner {
        exec: std::env::args().collect::<Vec<_>>().join(" "),
        case: case.dir.clone(),
        model: case.coupling.model.name().to_string(),
        threads,
        grid: sim.grid().clone(),
        extra,
    }
}
