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

pub use crate::case::WriteControl;

/// The time axis of a run.
#[derive(Clone, Debug)]
pub struct TimeControl {
    pub time: f64,
    pub step: u64,
    pub end_time: f64,
    pub write_control: WriteControl,
    pub write_interval: f64,
    /// Index of the next write time for the run-time controls (`write_index · writeInterval`).
    write_index: u64,
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
        let write_index = match write_control {
            WriteControl::TimeStep => 0,
            _ => (time / write_interval * (1.0 + TIME_EPS)).floor() as u64 + 1,
        };
        TimeControl {
            time,
            step,
            end_time,
            write_control,
            write_interval,
            write_index,
        }
    }

    /// True while there is time left to run.
    pub fn running(&self) -> bool {
        self.end_time - self.time > TIME_EPS * self.end_time.abs()
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

    /// Advance by `dt`; returns true when the new time is a write time (or the end).
    pub fn advance(&mut self, dt: f64) -> bool {
        self.step += 1;
        self.time += dt;
        let write = match self.write_control {
            WriteControl::TimeStep => {
                let every = self.write_interval.round().max(1.0) as u64;
                self.step.is_multiple_of(every)
            }
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
        };
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
    fn nothing_to_do_when_start_equals_end() {
        let tc = TimeControl::new(1.0, 10, 1.0, WriteControl::TimeStep, 1.0);
        assert!(!tc.running());
    }
}
