//! When to step and when to write, as `system/controlDict` says.
//!
//! `writeControl timeStep` writes every `writeInterval` steps; `runTime` writes at the step
//! that ends nearest each multiple of `writeInterval`, the first whose time plus half its size
//! reaches it (OpenFOAM's `Time::operator++`; the step size is not changed);
//! `adjustableRunTime` shortens the step that would pass a write time so that it lands on it,
//! as OpenFOAM does with `adjustTimeStep yes` (without it, the caller gives `runTime`: OpenFOAM
//! adjusts the step to write times only within its adjustable step). Steps and write times are
//! counted from time 0, not from the run's start, so that a continued run writes where an
//! uninterrupted one does (OpenFOAM.com counts from the start time, openfoam.org since 2020
//! from the case's begin time). The run ends at `endTime` (to rounding), and the final time is
//! always written so that a run can be continued from it.
//!
//! `stopAt` acts at each step's end as in OpenFOAM's `Time::operator++`: `writeNow` ends the
//! run after the next step and writes it, `noWriteNow` ends it there without a write (unless
//! the step is a write time anyway), `nextWrite` ends it at the next write time; `endTime` is
//! then not needed.
//!
//! `clockTime` and `cpuTime` write every `writeInterval` seconds of wall-clock or CPU time
//! since the run started (OpenFOAM: at the first step after each multiple).

pub use crate::case::{StopAt, WriteControl};
use crate::output::cpu_time_seconds;

/// The time axis of a run.
#[derive(Clone, Debug)]
pub struct TimeControl {
    pub time: f64,
    pub step: u64,
    pub end_time: f64,
    pub stop_at: StopAt,
    pub write_control: WriteControl,
    pub write_interval: f64,
    /// Index of the next write time for the run-time controls (`write_index · writeInterval`);
    /// for `clockTime` and `cpuTime` the multiples of `writeInterval` already passed.
    write_index: u64,
    /// Whether the next step is written whatever the write control (a `writeNowSignal`).
    write_next: bool,
    /// Wall-clock and CPU seconds at the start, for `clockTime` and `cpuTime`.
    started: std::time::Instant,
    cpu_at_start: f64,
}

/// Relative tolerance on time comparisons (of `endTime` and of `writeInterval`).
const TIME_EPS: f64 = 1e-9;

impl TimeControl {
    /// Start at `time` (step index `step`, from a restart or 0).
    pub fn new(
        time: f64,
        step: u64,
        end_time: f64,
        write_control: WriteControl,
        write_interval: f64,
    ) -> Self {
        let mut control = TimeControl {
            time,
            step,
            end_time,
            stop_at: StopAt::EndTime,
            write_control,
            write_interval,
            write_index: 0,
            write_next: false,
            started: std::time::Instant::now(),
            cpu_at_start: cpu_time_seconds(),
        };
        control.set_writes(write_control, write_interval);
        control
    }

    /// Sets `stopAt` and `endTime` (`end_time` counts only for `StopAt::EndTime`; the others
    /// run on until their step).
    pub fn set_stop(&mut self, stop_at: StopAt, end_time: f64) {
        self.stop_at = stop_at;
        self.end_time = match stop_at {
            StopAt::EndTime => end_time,
            _ => f64::INFINITY,
        };
    }

    /// Sets when to write from now on. A run-time interval's next write is its first
    /// multiple after now and after the last write time of the interval before, which
    /// `runTime` may have written a little early (OpenFOAM rescales its write index to
    /// the same end); a wall or CPU interval counts the multiples already passed.
    pub fn set_writes(&mut self, write_control: WriteControl, write_interval: f64) {
        let run_time =
            |w: WriteControl| matches!(w, WriteControl::RunTime | WriteControl::AdjustableRunTime);
        let since = if run_time(self.write_control) && self.write_index > 0 {
            self.time
                .max((self.write_index - 1) as f64 * self.write_interval)
        } else {
            self.time
        };
        self.write_control = write_control;
        self.write_interval = write_interval;
        self.write_index = match write_control {
            WriteControl::TimeStep => 0,
            WriteControl::ClockTime | WriteControl::CpuTime => {
                (self.elapsed() / write_interval).floor() as u64
            }
            _ => (since / write_interval * (1.0 + TIME_EPS)).floor() as u64 + 1,
        };
    }

    /// `writeControl timeStep`'s interval.
    fn steps_per_write(&self) -> u64 {
        self.write_interval.round().max(1.0) as u64
    }

    /// Writes the next step whatever the write control (OpenFOAM's `writeOnce`).
    pub fn write_next_step(&mut self) {
        self.write_next = true;
    }

    /// Whether a run that ends at the current time must still write it: the last time is
    /// always written, unless `stopAt noWriteNow` said not to.
    pub fn final_write_due(&self) -> bool {
        self.stop_at != StopAt::NoWriteNow
    }

    /// Seconds of wall-clock (`clockTime`) or CPU time (`cpuTime`) since the start; 0 for
    /// the other controls.
    fn elapsed(&self) -> f64 {
        match self.write_control {
            WriteControl::ClockTime => self.started.elapsed().as_secs_f64(),
            WriteControl::CpuTime => cpu_time_seconds() - self.cpu_at_start,
            _ => 0.0,
        }
    }

    /// True while there is time left to run.
    pub fn running(&self) -> bool {
        self.end_time == f64::INFINITY || self.end_time - self.time > TIME_EPS * self.end_time.abs()
    }

    fn next_write_time(&self) -> f64 {
        self.write_index as f64 * self.write_interval
    }

    /// The step to take from `time`, given the step the physics allows: never past `endTime`,
    /// and for `adjustableRunTime` never past the next write time.
    ///
    /// A target within a millionth of a step is reached by the full step, not a shortened one,
    /// so that a run stopped at a step boundary and continued takes exactly the steps of an
    /// uninterrupted run. A step that would leave a sliver shorter than a hundredth of itself
    /// is stretched onto the target instead.
    pub fn step_size(&self, allowed: f64) -> f64 {
        let mut target = self.end_time;
        if self.write_control == WriteControl::AdjustableRunTime {
            target = target.min(self.next_write_time());
        }
        let remaining = target - self.time;
        if (remaining - allowed).abs() <= 1e-6 * allowed {
            allowed
        } else if remaining <= allowed * 1.01 {
            remaining.max(0.0)
        } else if self.write_control == WriteControl::AdjustableRunTime && remaining < 2.0 * allowed
        {
            // Two equal steps instead of a long one and a sliver.
            0.5 * remaining
        } else {
            allowed
        }
    }

    /// Where the run will stop at steps of `dt` (for a plan): `endTime`, or for `stopAt` the
    /// end of the next step or the next write time.
    pub fn planned_end(&self, dt: f64) -> f64 {
        match (self.stop_at, self.write_control) {
            (StopAt::EndTime, _) => self.end_time,
            (StopAt::WriteNow | StopAt::NoWriteNow, _) => self.time + dt,
            (StopAt::NextWrite, WriteControl::TimeStep) => {
                let every = self.steps_per_write();
                self.time + (every - self.step % every) as f64 * dt
            }
            // a wall or CPU interval's steps are unknown before they are taken (the plan
            // counts them from its timed steps)
            (StopAt::NextWrite, WriteControl::ClockTime | WriteControl::CpuTime) => self.time + dt,
            (StopAt::NextWrite, _) => self.next_write_time(),
        }
    }

    /// Advance by `dt`; returns true when the new time is a write time (or the end, unless
    /// `stopAt noWriteNow` ends the run there).
    pub fn advance(&mut self, dt: f64) -> bool {
        let elapsed = self.elapsed();
        self.advance_with_elapsed(dt, elapsed)
    }

    /// [`Self::advance`] with the wall-clock or CPU seconds since the start given.
    fn advance_with_elapsed(&mut self, dt: f64, elapsed: f64) -> bool {
        self.step += 1;
        self.time += dt;
        let write = match self.write_control {
            WriteControl::TimeStep => self.step.is_multiple_of(self.steps_per_write()),
            WriteControl::RunTime | WriteControl::AdjustableRunTime => {
                // runTime: the step nearest the write time; adjustableRunTime lands on it
                let reach = match self.write_control {
                    WriteControl::RunTime => 0.5 * dt,
                    _ => 0.0,
                };
                let mut hit = false;
                while self.time + reach >= self.next_write_time() - TIME_EPS * self.write_interval {
                    self.write_index += 1;
                    hit = true;
                }
                hit
            }
            WriteControl::ClockTime | WriteControl::CpuTime => {
                let passed = (elapsed / self.write_interval).floor() as u64;
                let hit = passed > self.write_index;
                self.write_index = self.write_index.max(passed);
                hit
            }
        };
        let write = write || std::mem::take(&mut self.write_next);
        match self.stop_at {
            StopAt::EndTime => {}
            StopAt::WriteNow => self.end_time = self.time,
            StopAt::NoWriteNow => {
                self.end_time = self.time;
                return write;
            }
            StopAt::NextWrite if write => self.end_time = self.time,
            StopAt::NextWrite => {}
        }
        write || !self.running()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(mut tc: TimeControl, allowed: f64) -> (Vec<f64>, Vec<f64>) {
        let mut times = Vec::new();
        let mut writes = Vec::new();
        while tc.running() {
            let dt = tc.step_size(allowed);
            assert!(dt > 0.0 && dt <= allowed * 1.01 + 1e-15);
            let w = tc.advance(dt);
            times.push(tc.time);
            if w {
                writes.push(tc.time);
            }
            assert!(times.len() < 100_000);
        }
        (times, writes)
    }

    #[test]
    fn time_step_control_writes_every_n_steps_and_at_the_end() {
        let tc = TimeControl::new(0.0, 0, 1.0, WriteControl::TimeStep, 3.0);
        let (times, writes) = run(tc, 0.1);
        assert_eq!(times.len(), 10);
        assert!((times.last().unwrap() - 1.0).abs() < 1e-12);
        assert_eq!(writes.len(), 4); // steps 3, 6, 9 and the end
    }

    #[test]
    fn adjustable_run_time_lands_on_every_write_time() {
        let tc = TimeControl::new(0.0, 0, 1.0, WriteControl::AdjustableRunTime, 0.25);
        let (_, writes) = run(tc, 0.07);
        assert_eq!(writes.len(), 4);
        for (w, expect) in writes.iter().zip([0.25, 0.5, 0.75, 1.0]) {
            assert!((w - expect).abs() < 1e-12, "{w} vs {expect}");
        }
    }

    #[test]
    fn run_time_control_writes_at_the_step_nearest_each_interval() {
        let tc = TimeControl::new(0.0, 0, 1.0, WriteControl::RunTime, 0.3);
        let (_, writes) = run(tc, 0.1);
        // 0.3, 0.6, 0.9 reached (to rounding) at steps 3, 6, 9; then the end.
        assert_eq!(writes.len(), 4);
        assert!((writes[0] - 0.3).abs() < 1e-12);
        assert!((writes.last().unwrap() - 1.0).abs() < 1e-12);
        // A step that does not divide the interval: OpenFOAM writes when
        // label((t + Δt/2)/interval) grows: at 0.009 (nearer 0.01 than 0.012 is), at 0.021
        // (0.018 + Δt/2 falls short of 0.02) and at the end, 0.03.
        let tc = TimeControl::new(0.0, 0, 0.03, WriteControl::RunTime, 0.01);
        let (_, writes) = run(tc, 0.003);
        let expect = [0.009, 0.021, 0.03];
        assert_eq!(writes.len(), expect.len(), "{writes:?}");
        for (w, e) in writes.iter().zip(expect) {
            assert!((w - e).abs() < 1e-12, "{writes:?}");
        }
    }

    #[test]
    fn a_restarted_time_axis_continues_where_it_stopped() {
        let tc = TimeControl::new(0.5, 5, 1.0, WriteControl::AdjustableRunTime, 0.25);
        let (_, writes) = run(tc, 0.1);
        assert_eq!(writes.len(), 2);
        assert!((writes[0] - 0.75).abs() < 1e-12);
    }

    #[test]
    fn stop_at_ends_the_run_as_openfoam_does() {
        // writeNow: one more step, written
        let mut tc = TimeControl::new(0.2, 2, 1.0, WriteControl::TimeStep, 5.0);
        tc.set_stop(StopAt::WriteNow, 1.0);
        assert!(tc.running());
        let (times, writes) = run(tc, 0.1);
        assert_eq!(times.len(), 1);
        assert_eq!(writes, times);
        // noWriteNow: one more step, not written
        let mut tc = TimeControl::new(0.2, 2, 1.0, WriteControl::TimeStep, 5.0);
        tc.set_stop(StopAt::NoWriteNow, 1.0);
        let (times, writes) = run(tc, 0.1);
        assert_eq!(times.len(), 1);
        assert!(writes.is_empty());
        // ... but a step that is a write time anyway is written
        let mut tc = TimeControl::new(0.2, 4, 1.0, WriteControl::TimeStep, 5.0);
        tc.set_stop(StopAt::NoWriteNow, 1.0);
        let (_, writes) = run(tc, 0.1);
        assert_eq!(writes.len(), 1);
        // nextWrite: on to the next write time, past endTime, which it does not need
        let mut tc = TimeControl::new(0.0, 0, 0.1, WriteControl::AdjustableRunTime, 0.25);
        tc.set_stop(StopAt::NextWrite, 0.1);
        let (times, writes) = run(tc, 0.07);
        assert_eq!(writes.len(), 1);
        assert!((writes[0] - 0.25).abs() < 1e-12);
        assert_eq!(*times.last().unwrap(), writes[0]);
        // back to endTime
        let mut tc = TimeControl::new(0.0, 0, 0.1, WriteControl::TimeStep, 1.0);
        tc.set_stop(StopAt::NextWrite, 0.1);
        tc.set_stop(StopAt::EndTime, 0.3);
        assert_eq!(run(tc, 0.1).0.len(), 3);
    }

    #[test]
    fn a_longer_interval_does_not_write_the_last_write_time_again() {
        // runTime writes 0.5 at the step ending at 0.498 (nearest); a change to 0.5 then
        // must not write at 0.504 for 0.5 again, but at 1.002 (nearer 1 than 0.996)
        let mut tc = TimeControl::new(0.0, 0, 2.0, WriteControl::RunTime, 0.25);
        let mut writes = Vec::new();
        for _ in 0..83 {
            if tc.advance(0.006) {
                writes.push(tc.time);
            }
        }
        assert!((tc.time - 0.498).abs() < 1e-9 && (writes[1] - 0.498).abs() < 1e-9);
        tc.set_writes(WriteControl::RunTime, 0.5);
        let (_, later) = run(tc, 0.006);
        assert!((later[0] - 1.002).abs() < 1e-9, "{later:?}");
    }

    #[test]
    fn new_write_settings_count_from_now() {
        let mut tc = TimeControl::new(0.0, 0, 1.0, WriteControl::AdjustableRunTime, 0.5);
        for _ in 0..3 {
            let dt = tc.step_size(0.1);
            tc.advance(dt);
        }
        // at 0.3: the next write of the new interval 0.2 is 0.4, not 0.2
        tc.set_writes(WriteControl::AdjustableRunTime, 0.2);
        let (_, writes) = run(tc, 0.1);
        let expect = [0.4, 0.6, 0.8, 1.0];
        assert_eq!(writes.len(), expect.len(), "{writes:?}");
        for (w, e) in writes.iter().zip(expect) {
            assert!((w - e).abs() < 1e-12, "{writes:?}");
        }
    }

    #[test]
    fn clock_and_cpu_time_write_at_the_first_step_past_each_interval() {
        for control in [WriteControl::ClockTime, WriteControl::CpuTime] {
            let mut tc = TimeControl::new(0.0, 0, 1.0, control, 2.0);
            // seconds since the start at each step's end
            let elapsed = [0.5, 1.9, 2.1, 2.5, 3.9, 6.3, 6.4];
            let written: Vec<bool> = elapsed
                .iter()
                .map(|&e| tc.advance_with_elapsed(0.1, e))
                .collect();
            assert_eq!(
                written,
                [false, false, true, false, false, true, false],
                "{control:?}"
            );
        }
    }

    #[test]
    fn nothing_to_do_when_start_equals_end() {
        let tc = TimeControl::new(1.0, 10, 1.0, WriteControl::TimeStep, 1.0);
        assert!(!tc.running());
    }
}
