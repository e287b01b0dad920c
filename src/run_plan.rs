//! `-dry-run`: what a run would do and what it would cost, without writing anything.
//!
//! The cost is measured, not modelled: the plan takes a few steps in memory exactly as the
//! run would ([`Simulation::step`]) and times them, because a rate per cell misses the
//! coupling, the cloud and the machine (docs/user-guide/command-line.md).

use crate::case::{Case, StopAt, WriteControl};
use crate::coupling::drag::terminal_velocity;
use crate::error::FsimError;
use crate::output::cpu_time_seconds;
use crate::simulation::{Coupling, PhaseTimes, Simulation};
use std::time::Instant;

/// How many steps `-dry-run` takes in memory to time the run.
const TIMED_STEPS: usize = 8;

/// The wall time after which `-dry-run` takes no more steps (the first is always taken).
const TIMING_BUDGET_SECONDS: f64 = 10.0;

/// The fluid speed a settling suspension reaches, in terminal velocities of its spheres,
/// for the plan's Courant step: 2 plans the benchmark within an eighth and errs long for
/// calmer suspensions, the side a batch's time limits want (the measured speeds:
/// docs/benchmarks/direct.md, "`-dry-run`'s plan on the benchmark").
const SETTLING_SPEED: f64 = 2.0;

/// Prints the plan of `case` (module docs), taking its first steps in `sim`.
pub fn print_plan(case: &Case, sim: &mut Simulation, threads: usize) -> Result<(), FsimError> {
    let cells = sim.grid().cell_count();
    println!("Case    : {}", case.dir.display());
    println!("Plan    : {}", case.summary());
    match &sim.coupling {
        Coupling::DragLaw(m) => println!(
            "Scheme  : volume-averaged, {}, PCG pressure ({})",
            m.coupling.fluid.predictor_name(),
            m.coupling.describe()
        ),
        _ => println!("Scheme  : {}", sim.fluid.settings().scheme.name()),
    }
    if !sim.time.running() {
        println!(
            "Steps   : none: the run already reached endTime {} s (at t = {} s)",
            sim.time.end_time, sim.time.time
        );
        return Ok(());
    }
    let start = sim.time.time;
    let timed = time_steps(sim)?;
    let count = timed.seconds.len();
    let step = timed.representative();
    let (steps, dt, why, end) = if !sim.time.running() {
        let dt = (sim.time.time - start) / count as f64;
        let why = ", all of them timed below".to_string();
        (count as f64, dt, why, sim.time.time)
    } else {
        // The run's next step fails here as it would in the run (a fixed step beyond the
        // bound, a collapsing Courant step).
        sim.next_time_step()
            .map_err(|e| FsimError::run(format!("dry run: after the timed steps: {e}")))?;
        // The step the flow allows, not the next one: that one still grows by at most 1.2
        // times a step from deltaT, or lands on a write time.
        let allowed = sim.allowed_time_step().max(f64::MIN_POSITIVE);
        let bound = sim.stability_bound();
        let settling = settling_step(case, sim).filter(|s| s.dt < allowed);
        let dt = settling.as_ref().map_or(allowed, |s| s.dt);
        let why = match &settling {
            Some(s) => format!(
                ": the Courant step at maxCo {} once the fluid moves at {SETTLING_SPEED} times \
                 the spheres' terminal velocity ({:.3e} m/s, Schiller–Naumann); the flow \
                 allows {allowed:.3e} s after the timed steps, stability bound {bound:.3e} s",
                case.control.max_co, s.terminal_velocity
            ),
            None if case.control.adjust_time_step => format!(
                ", the step the flow allows after the timed steps (stability bound \
                 {bound:.3e} s, adjusted by maxCo as the flow develops)"
            ),
            None => format!(" (deltaT; stability bound {bound:.3e} s)"),
        };
        // endTime, or where stopAt ends the run
        let (end, why) = match steps_to_clocked_write(sim, step, timed.cpu_rate) {
            Some(n) => (
                start + n * dt,
                format!(
                    "{why}; stopAt nextWrite: to the first write, after {} s of {} at the \
                     timed steps' cost",
                    sim.time.write_interval,
                    if sim.time.write_control == WriteControl::ClockTime {
                        "wall-clock time"
                    } else {
                        "CPU time on all threads"
                    }
                ),
            ),
            None => (sim.time.planned_end(dt), why),
        };
        let left = ((end - sim.time.time) / dt).ceil().max(0.0);
        (count as f64 + left, dt, why, end)
    };
    println!("Steps   : about {steps} of {dt:.3e} s from t = {start} to {end} s{why}");
    // the run's wall time, and its CPU time on every thread
    let seconds = steps * step;
    let writes = match case.control.write_control {
        WriteControl::TimeStep => steps / case.control.write_interval.max(1.0),
        WriteControl::ClockTime => seconds / case.control.write_interval,
        WriteControl::CpuTime => seconds * timed.cpu_rate / case.control.write_interval,
        WriteControl::RunTime | WriteControl::AdjustableRunTime => {
            (end - start) / case.control.write_interval
        }
    }
    .floor();
    let besides = match sim.time.stop_at {
        StopAt::EndTime | StopAt::WriteNow => "the start and the end",
        StopAt::NoWriteNow => "the start; the end is not written",
        StopAt::NextWrite => "the start; the next is the end",
    };
    println!(
        "Writes  : about {writes} time directories (+ {besides}), each about {:.1} MB",
        cells as f64 * 2.0 * 4.0 * 8.0 / 1e6
    );
    if let Some(p) = sim.particles() {
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
    let total: f64 = timed.seconds.iter().sum();
    let share = |part: f64| 100.0 * part / total.max(f64::MIN_POSITIVE);
    println!(
        "Timed   : {count} step(s) taken in memory, nothing written: {:.1} ms a step{}; \
         fluid {:.0} %, coupling {:.0} %, particles {:.0} %",
        step * 1e3,
        if count > 1 {
            format!(
                " (median after the first, which took {:.1} ms)",
                timed.seconds[0] * 1e3
            )
        } else {
            String::new()
        },
        share(timed.phases.fluid),
        share(timed.phases.coupling),
        share(timed.phases.particles)
    );
    println!(
        "Run time: about {} s on {threads} thread(s) ({steps} steps of {:.1} ms; steps \
         from rest can cost more or less than the developed flow's)",
        if seconds < 10.0 {
            format!("{seconds:.1}")
        } else {
            format!("{seconds:.0}")
        },
        step * 1e3
    );
    let fluid = sim.fluid.bytes_per_cell() * cells as f64;
    match crate::output::peak_resident_bytes() {
        Some(peak) => println!(
            "Memory  : about {:.1} MB for the fluid; the process's peak after the timed steps \
             {:.1} MB (the run's writes add some)",
            fluid / 1e6,
            peak as f64 / 1e6
        ),
        None => println!("Memory  : about {:.1} MB for the fluid", fluid / 1e6),
    }
    Ok(())
}

/// With `stopAt nextWrite` and a `clockTime` or `cpuTime` write, the run ends at its first
/// write: after `writeInterval` seconds of wall-clock time, or of CPU time at the timed
/// steps' `cpu_rate` (CPU seconds per second), at the timed `step` seconds a step. `None`
/// with other controls.
fn steps_to_clocked_write(sim: &Simulation, step: f64, cpu_rate: f64) -> Option<f64> {
    let time = &sim.time;
    if time.stop_at != StopAt::NextWrite {
        return None;
    }
    let seconds_per_step = match time.write_control {
        WriteControl::ClockTime => step,
        WriteControl::CpuTime => step * cpu_rate,
        _ => return None,
    };
    let steps = time.write_interval / seconds_per_step.max(f64::MIN_POSITIVE);
    Some(steps.ceil().max(1.0))
}

/// The plan's step for a settling suspension ([`SETTLING_SPEED`]).
struct SettlingStep {
    dt: f64,
    terminal_velocity: f64,
}

/// With `model direct`, free spheres, gravity and `adjustTimeStep`: the Courant step once
/// the fluid moves at [`SETTLING_SPEED`] times the fastest sphere's terminal velocity
/// (within `maxDeltaT`). The flow starts at rest, so the present step says nothing of it.
fn settling_step(case: &Case, sim: &Simulation) -> Option<SettlingStep> {
    let g = case.gravity.iter().map(|x| x * x).sum::<f64>().sqrt();
    let direct = sim.coupling.direct()?;
    if !case.control.adjust_time_step || g == 0.0 {
        return None;
    }
    let p = direct.particles.dem.particles();
    let (rho, mu) = (sim.rho, sim.rho * case.transport.nu);
    let terminal = (0..p.diameter.len())
        .filter(|&i| !p.fixed[i])
        .map(|i| terminal_velocity(p.diameter[i], p.density[i], rho, mu, g))
        .fold(0.0, f64::max);
    if terminal <= 0.0 {
        return None;
    }
    let h = sim.grid().h.iter().cloned().fold(f64::INFINITY, f64::min);
    let courant = case.control.max_co * h / (SETTLING_SPEED * terminal);
    Some(SettlingStep {
        dt: courant.min(case.control.max_delta_t),
        terminal_velocity: terminal,
    })
}

/// The wall time of the steps `-dry-run` takes, and of their phases summed.
struct TimedSteps {
    seconds: Vec<f64>,
    phases: PhaseTimes,
    /// The process's CPU seconds per wall-clock second over the timed steps.
    cpu_rate: f64,
}

impl TimedSteps {
    /// The median after the first step, which holds start-up work (the first build of the
    /// forced faces, the first neighbour lists); the first when it is the only one.
    fn representative(&self) -> f64 {
        let mut later: Vec<f64> = self.seconds.iter().skip(1).cloned().collect();
        if later.is_empty() {
            return self.seconds.first().cloned().unwrap_or(0.0);
        }
        later.sort_by(f64::total_cmp);
        let mid = later.len() / 2;
        if later.len() % 2 == 1 {
            later[mid]
        } else {
            0.5 * (later[mid - 1] + later[mid])
        }
    }
}

/// Takes up to [`TIMED_STEPS`] steps (within [`TIMING_BUDGET_SECONDS`] s, and not past `endTime`),
/// as the run would. A step that fails fails the dry run as it would fail the run.
fn time_steps(sim: &mut Simulation) -> Result<TimedSteps, FsimError> {
    let mut timed = TimedSteps {
        seconds: Vec::with_capacity(TIMED_STEPS),
        phases: PhaseTimes::default(),
        cpu_rate: 0.0,
    };
    let cpu = cpu_time_seconds();
    let clock = Instant::now();
    while sim.time.running()
        && timed.seconds.len() < TIMED_STEPS
        && (timed.seconds.is_empty() || clock.elapsed().as_secs_f64() < TIMING_BUDGET_SECONDS)
    {
        let step = Instant::now();
        let k = timed.seconds.len() + 1;
        sim.step()
            .map_err(|e| FsimError::run(format!("dry run: timed step {k}: {e}")))?;
        timed.seconds.push(step.elapsed().as_secs_f64());
        timed.phases.fluid += sim.phase_times.fluid;
        timed.phases.coupling += sim.phase_times.coupling;
        timed.phases.particles += sim.phase_times.particles;
    }
    timed.cpu_rate = (cpu_time_seconds() - cpu) / clock.elapsed().as_secs_f64();
    Ok(timed)
}
