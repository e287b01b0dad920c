//! The time loop, read like the algorithm (DPMFoam's main file in spirit):
//!
//! ```text
//! load and validate the case                  (nothing is written before this succeeds)
//! build the simulation: grid, fluid, initial or restart state
//! while time remains:
//!     choose Δt                              (controlDict, maxCo, paper eq. 3 bound)
//!     evolve the cloud  ┐ drag law (DPMFoam's order): forces from the fluid as it is
//!     evolve the fluid  ┘ (eq. 10–16), DEM sub-steps; then ε, momentum predictor,
//!                         pressure correction with the particles' reaction
//!     evolve the fluid  ┐ direct model (paper §2.1) and model none: momentum predictor and
//!     hydrodynamic loads│ projection with no-slip on every sphere where it is, force and
//!     evolve the cloud  ┘ torque by the stress integral (eq. 4–6), DEM sub-steps (model
//!                         none: gravity and buoyancy, no fluid forces)
//!     check the solution                      (a diverged run stops, keeping its last time)
//!     monitor, log
//!     write the time directory when due       (whole or not at all)
//! ```

use crate::case::{Case, InternalField};
use crate::cli::Options;
use crate::error::FsimError;
use crate::output::{
    write_fluid, Banner, CaseOutput, CellData, OutputError, PARTICLE_FILE_NAME, RESTART_FILE_NAME,
};
use crate::simulation::{continues, Simulation, StepSizing};
use crate::step_reporter::StepReporter;
use std::time::Instant;

/// Runs `fsimFoam` with the given options.
pub fn run(options: &Options) -> Result<(), FsimError> {
    let mut case = load_case(options)?;
    let threads = options.threads.unwrap_or_else(|| {
        std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(1)
    });
    if threads == 0 {
        return Err(FsimError::input("-threads must be at least 1"));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| FsimError::run(format!("cannot start {threads} threads: {e}")))?;
    pool.install(|| run_case(&mut case, options, threads))
}

/// Reads and validates every file of the case, listing the keywords fsim ignores.
fn load_case(options: &Options) -> Result<Case, FsimError> {
    let case = Case::load(&options.case)?;
    for warning in &case.warnings {
        eprintln!("fsimFoam: note: {warning}");
    }
    Ok(case)
}

fn run_case(case: &mut Case, options: &Options, threads: usize) -> Result<(), FsimError> {
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
    for note in sim.particles.iter().flat_map(|p| &p.notes) {
        eprintln!("fsimFoam: note: {note}");
    }
    for warning in &sim.warnings {
        eprintln!("fsimFoam: warning: {warning}");
    }
    check_first_step(&mut sim)?;
    if options.dry_run {
        print_plan(case, &mut sim, threads);
        return Ok(());
    }

    let mut output = CaseOutput::open(
        &case.dir,
        case.control.time_precision,
        case.control.purge_write,
    )
    .map_err(output_error)?;
    let start_name = output.time_name(sim.time.time);
    let mut reporter = StepReporter::open(
        &case.dir,
        &start_name,
        sim.particles.is_some(),
        sim.drag.is_some(),
    )?;
    reporter.log.banner(&banner(case, &sim, threads))?;
    if restart.is_none() && !case.dir.join(&start_name).join(RESTART_FILE_NAME).exists() {
        // The start time gets its VTK files and restart state too, so the series opens at t0.
        write_time(&mut output, &mut sim)?;
    }
    let start = sim.time.time;
    reporter.log.line("Starting time loop\n")?;

    while sim.time.running() {
        let clock = Instant::now();
        let dt = sim.next_time_step()?;
        let (fluid, cloud, diagnostics) = if sim.drag.is_some() {
            let cloud = sim.evolve_cloud(dt);
            let fluid = sim.evolve_fluid(dt)?;
            (fluid, cloud, sim.fluid_diagnostics())
        } else {
            let fluid = sim.evolve_fluid(dt)?;
            sim.hydrodynamic_loads();
            let (cloud, diagnostics) = sim.evolve_cloud_beside_diagnostics(dt);
            (fluid, cloud, diagnostics)
        };
        let write_due = sim.time.advance(dt);
        let health = sim.check_health(diagnostics)?;
        sim.update_sedimentation();
        let name = output.time_name(sim.time.time);
        reporter.step(
            &name,
            &sim,
            dt,
            &fluid,
            cloud.as_ref(),
            &health,
            clock.elapsed(),
        )?;
        if write_due {
            write_time(&mut output, &mut sim)?;
        }
        reporter.end_step(sim.time.time, start, case.control.end_time)?;
    }
    reporter.finish()
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
    let alpha = sim.drag.as_ref().map(|d| d.cell_fluid_fraction());
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
    write_fluid(dir.path(), &grid, &title, &fields).map_err(output_error)?;
    drop(fields);
    sim.write_particles(&dir.file(PARTICLE_FILE_NAME))?;
    sim.write_restart(&dir.file(RESTART_FILE_NAME))?;
    output.commit(dir).map_err(output_error)?;
    Ok(())
}

fn banner(case: &Case, sim: &Simulation, threads: usize) -> Banner {
    let mut extra = vec![
        (
            "Scheme".to_string(),
            if let Some(d) = &sim.drag {
                format!(
                    "volume-averaged ({}, PCG pressure)",
                    d.fluid.predictor_name()
                )
            } else {
                sim.fluid.settings().scheme.name().to_string()
            },
        ),
        ("nu".to_string(), format!("{:e} m2/s", case.transport.nu)),
    ];
    if let Some(d) = &sim.drag {
        extra.push(("Drag law".to_string(), d.describe()));
    }
    if let Some(p) = &sim.particles {
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

/// `-dry-run`: what the run would do, and roughly what it would cost.
fn print_plan(case: &Case, sim: &mut Simulation, threads: usize) {
    let grid = sim.grid().clone();
    let cells = grid.cell_count();
    println!("Case    : {}", case.dir.display());
    println!("Plan    : {}", case.summary());
    match &sim.drag {
        Some(d) => println!(
            "Scheme  : volume-averaged, {}, PCG pressure ({})",
            d.fluid.predictor_name(),
            d.describe()
        ),
        None => println!("Scheme  : {}", sim.fluid.settings().scheme.name()),
    }
    if !sim.time.running() {
        println!(
            "Steps   : none: the run already reached endTime {} s (at t = {} s)",
            case.control.end_time, sim.time.time
        );
        return;
    }
    let span = case.control.end_time - sim.time.time;
    let dt = sim
        .next_time_step()
        .unwrap_or(sim.dt)
        .max(f64::MIN_POSITIVE);
    let bound = sim.stability_bound();
    let steps = (span / dt).ceil().max(0.0);
    println!(
        "Steps   : about {steps} of {dt:e} s from t = {} to {} s (stability bound {bound:e} s{})",
        sim.time.time,
        case.control.end_time,
        if case.control.adjust_time_step {
            ", adjusted by maxCo as the flow develops"
        } else {
            ""
        }
    );
    let writes = match case.control.write_control {
        crate::case::WriteControl::TimeStep => steps / case.control.write_interval.max(1.0),
        _ => span / case.control.write_interval,
    }
    .floor();
    println!(
        "Writes  : about {writes} time directories (+ the start and the end), each about {:.1} MB",
        cells as f64 * 2.0 * 4.0 * 8.0 / 1e6
    );
    let memory = sim.fluid.bytes_per_cell() * cells as f64;
    println!("Memory  : about {:.1} MB for the fluid", memory / 1e6);
    if let Some(p) = &sim.particles {
        let n = p.dem.particles().len();
        let bytes = p.dem.memory_bytes() as f64;
        println!(
            "Cloud   : {n} particles; pairModel {}, wallModel {}; {} collision sub-steps per \
             step now; memory about {:.1} MB ({:.0} bytes per particle)",
            p.pair_model,
            p.wall_model,
            p.dem.substep_count(dt),
            bytes / 1e6,
            bytes / n.max(1) as f64
        );
    }
    // tools/bench (README, 128³): about 20 million cell-stages per second on one thread,
    // 1.8 times that on two; each stage is one predictor and one projection.
    let stage_rate = 20.0e6 * (threads as f64).powf(0.85);
    let stages = sim.fluid.settings().scheme.stages().len() as f64;
    let rate = stage_rate / stages;
    println!(
        "Run time: about {:.0} s for the fluid on {threads} thread(s) (at {:.0} million \
         cell-steps/s)",
        steps * cells as f64 / rate,
        rate / 1e6
    );
}
