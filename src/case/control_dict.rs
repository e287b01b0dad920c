//! `system/controlDict`: when to start and stop, the time step, and when to write.

use super::dictionary::{single_token, Dict};
use super::error::CaseError;
use super::value::Value;

/// Where a run starts (`startFrom`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StartFrom {
    /// At `startTime`.
    StartTime,
    /// At the latest time directory (continuing an interrupted run).
    LatestTime,
    /// At the earliest time directory.
    FirstTime,
}

/// When a run stops (`stopAt`), as OpenFOAM's `Time` decides at each step's end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopAt {
    /// At `endTime`.
    EndTime,
    /// After the next step, which is written.
    WriteNow,
    /// After the next step, written only if it is a write time anyway.
    NoWriteNow,
    /// At the next write time.
    NextWrite,
}

impl StopAt {
    /// Every choice, in the order the keyword's error lists them.
    pub const ALL: [StopAt; 4] = [
        StopAt::EndTime,
        StopAt::WriteNow,
        StopAt::NoWriteNow,
        StopAt::NextWrite,
    ];

    /// The keyword's word.
    pub fn name(self) -> &'static str {
        match self {
            StopAt::EndTime => "endTime",
            StopAt::WriteNow => "writeNow",
            StopAt::NoWriteNow => "noWriteNow",
            StopAt::NextWrite => "nextWrite",
        }
    }
}

/// When time directories are written (`writeControl`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WriteControl {
    /// Every `writeInterval` time steps.
    TimeStep,
    /// Every `writeInterval` seconds of simulated time, at the first step reaching it.
    RunTime,
    /// Every `writeInterval` seconds exactly: the time step is shortened to land on it.
    AdjustableRunTime,
    /// Every `writeInterval` seconds of wall-clock time since the run started.
    ClockTime,
    /// Every `writeInterval` seconds of the process's CPU time (all threads) since it started.
    CpuTime,
}

impl WriteControl {
    /// Every choice, in the order the keyword's error lists them.
    pub const ALL: [WriteControl; 5] = [
        WriteControl::TimeStep,
        WriteControl::RunTime,
        WriteControl::AdjustableRunTime,
        WriteControl::ClockTime,
        WriteControl::CpuTime,
    ];

    /// The keyword's word.
    pub fn name(self) -> &'static str {
        match self {
            WriteControl::TimeStep => "timeStep",
            WriteControl::RunTime => "runTime",
            WriteControl::AdjustableRunTime => "adjustableRunTime",
            WriteControl::ClockTime => "clockTime",
            WriteControl::CpuTime => "cpuTime",
        }
    }
}

/// The typed `system/controlDict`.
#[derive(Clone, Debug, PartialEq)]
pub struct ControlDict {
    pub start_from: StartFrom,
    pub start_time: f64,
    pub stop_at: StopAt,
    /// `endTime`; infinite when `stopAt` is not `endTime` and the file gives none.
    pub end_time: f64,
    /// Initial (or fixed) time step, seconds.
    pub delta_t: f64,
    pub write_control: WriteControl,
    /// Steps for `TimeStep`, seconds otherwise.
    pub write_interval: f64,
    /// Number of time directories kept (0: all).
    pub purge_write: usize,
    pub adjust_time_step: bool,
    /// Courant number bound used when `adjust_time_step` (default 1, as OpenFOAM).
    pub max_co: f64,
    /// Largest time step allowed when `adjust_time_step` (default: unbounded).
    pub max_delta_t: f64,
    /// Significant digits of time directory names (default 6).
    pub time_precision: usize,
    /// `runTimeModifiable`: read the file again when it changes during the run (default no,
    /// as OpenFOAM.com's `Time`; every OpenFOAM tutorial says yes).
    pub run_time_modifiable: bool,
    /// `OptimisationSwitches { writeNowSignal N; }`: the signal that makes the run write
    /// the step after it (OpenFOAM's `sigWriteNow`; off by default).
    pub write_now_signal: Option<i32>,
    /// `OptimisationSwitches { stopAtWriteNowSignal N; }`: the signal that makes the run
    /// stop as `stopAt writeNow` (OpenFOAM's `sigStopAtWriteNow`; off by default).
    pub stop_at_write_now_signal: Option<i32>,
}

/// Reads a keyword that must be one of `choices`, returning the choice's index.
pub(crate) fn choice(
    dict: &Dict,
    keyword: &str,
    choices: &[&str],
    default: Option<usize>,
) -> Result<usize, CaseError> {
    let Some(entry) = dict.lookup(keyword) else {
        return default.ok_or_else(|| dict.missing(keyword));
    };
    let item = single_token(entry, "a word")?;
    let word = match &item.value {
        Value::Word(w) | Value::Str(w) => w.as_str(),
        _ => "",
    };
    choices.iter().position(|c| *c == word).ok_or_else(|| {
        CaseError::at(
            &item.loc,
            format!(
                "expected one of {} for '{keyword}', found {}",
                choices.join(", "),
                item.describe()
            ),
        )
    })
}

/// An error at the value of `keyword` (which must exist).
pub(crate) fn at_value(dict: &Dict, keyword: &str, message: String) -> CaseError {
    match dict.peek(keyword) {
        // At the value itself, past a dimension set (`nu [0 2 -1 0 0 0 0] -0.01;`).
        Some(e) => match single_token(e, "a value") {
            Ok(item) => CaseError::at(&item.loc, message),
            Err(_) => CaseError::at(e.value_loc(), message),
        },
        None => CaseError::at(&dict.loc, message),
    }
}

/// A signal number of `OptimisationSwitches` (negative or absent: none, OpenFOAM's -1). Only
/// signals a process may catch and that do not stop it otherwise are taken: 1–31 but for
/// SIGKILL (9) and SIGSTOP (19), which cannot be caught, and SIGSEGV (11).
fn signal_switch(switches: &Dict, keyword: &str) -> Result<Option<i32>, CaseError> {
    match switches.opt_integer(keyword)? {
        None => Ok(None),
        Some(n) if n < 0 => Ok(None),
        Some(n) if (1..=31).contains(&n) && ![9, 11, 19].contains(&n) => Ok(Some(n as i32)),
        Some(n) => Err(at_value(
            switches,
            keyword,
            format!(
                "expected a signal number from 1 to 31 other than 9, 11 and 19 for '{keyword}' \
                 (or -1: none), found {n}"
            ),
        )),
    }
}

/// Most time steps a run may plan without `-maxSteps`: 10⁹, some days of the cheapest
/// steps fsim takes; a plan beyond is almost always a mistyped `deltaT` or `endTime`.
pub const DEFAULT_MAX_STEPS: f64 = 1e9;

/// Most time directories a run may plan without `-maxWrites`: 10⁶, the most a directory
/// listing and a disk hold with comfort; beyond is almost always a mistyped
/// `writeInterval`.
pub const DEFAULT_MAX_WRITES: f64 = 1e6;

/// The most steps and writes a controlDict may plan (`check_plan`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanLimits {
    pub steps: f64,
    pub writes: f64,
}

impl Default for PlanLimits {
    fn default() -> Self {
        PlanLimits {
            steps: DEFAULT_MAX_STEPS,
            writes: DEFAULT_MAX_WRITES,
        }
    }
}

static PLAN_LIMITS: std::sync::OnceLock<PlanLimits> = std::sync::OnceLock::new();

/// Sets the limits every controlDict read by this process is held to (the command line's
/// `-maxSteps` and `-maxWrites`), before the case is read; only the first call counts, so
/// that a run's limits cannot change under it.
pub fn set_plan_limits(limits: PlanLimits) {
    let _ = PLAN_LIMITS.set(limits);
}

/// The limits set by [`set_plan_limits`], or the defaults.
pub fn plan_limits() -> PlanLimits {
    PLAN_LIMITS.get().copied().unwrap_or_default()
}

/// Refuses a controlDict that plans more time steps or writes than `limits` allow: a run
/// that would never end, or fill the disk, is refused before it starts. The steps are
/// `(endTime − startTime)/deltaT` (with `adjustTimeStep`, at least the span over
/// `maxDeltaT`); the writes those steps over `writeInterval`, or the span over it for a
/// write interval in simulated seconds (counted so for `runTime` too, though it writes at
/// most once a step: an interval shorter than the step still costs a pass per interval).
/// Clock- and CPU-time writes and runs with no `endTime` are not planned.
fn check_plan(
    d: &Dict,
    c: &ControlDict,
    interval_key: &str,
    limits: PlanLimits,
) -> Result<(), CaseError> {
    if !c.end_time.is_finite() {
        return Ok(());
    }
    let span = c.end_time - c.start_time;
    let (step_key, step) = if c.adjust_time_step {
        ("maxDeltaT", c.max_delta_t)
    } else {
        ("deltaT", c.delta_t)
    };
    // (`0/0` when endTime is startTime: nothing planned)
    let steps = if span > 0.0 { span / step } else { 0.0 };
    let too_many = |key: &str, what: String, count: f64, limit: f64, option: &str| {
        at_value(
            d,
            key,
            format!(
                "{what} plans {count:.3e} {}, more than the limit of {limit:.0e}: check the \
                 value, or raise the limit with -{option} N",
                if option == "maxSteps" {
                    "time steps"
                } else {
                    "writes"
                }
            ),
        )
    };
    if steps > limits.steps {
        return Err(too_many(
            step_key,
            format!(
                "{step_key} {step:?} from startTime {:?} to endTime {:?}",
                c.start_time, c.end_time
            ),
            steps,
            limits.steps,
            "maxSteps",
        ));
    }
    let intervals = if span > 0.0 {
        span / c.write_interval
    } else {
        0.0
    };
    let writes = match c.write_control {
        WriteControl::TimeStep => steps / c.write_interval,
        WriteControl::RunTime | WriteControl::AdjustableRunTime => intervals,
        WriteControl::ClockTime | WriteControl::CpuTime => 0.0,
    };
    let what = format!(
        "{interval_key} {:?} ({}) from startTime {:?} to endTime {:?}",
        c.write_interval,
        c.write_control.name(),
        c.start_time,
        c.end_time
    );
    if writes > limits.writes {
        return Err(too_many(
            interval_key,
            what,
            writes,
            limits.writes,
            "maxWrites",
        ));
    }
    Ok(())
}

impl ControlDict {
    /// Reads and validates the dictionary; `notes` receives what fsim ignores on purpose.
    pub fn from_dict(d: &Dict, notes: &mut Vec<String>) -> Result<ControlDict, CaseError> {
        let start_from = match choice(
            d,
            "startFrom",
            &["startTime", "latestTime", "firstTime"],
            // OpenFOAM's default (Time::setControls)
            Some(1),
        )? {
            0 => StartFrom::StartTime,
            1 => StartFrom::LatestTime,
            _ => StartFrom::FirstTime,
        };
        let start_time = d.get_scalar_or("startTime", 0.0)?;
        let names = StopAt::ALL.map(StopAt::name);
        let stop_at = StopAt::ALL[choice(d, "stopAt", &names, Some(0))?];
        // OpenFOAM runs on without an end (endTime GREAT) when stopAt is not endTime.
        let end_time = match stop_at {
            StopAt::EndTime => d.get_scalar("endTime")?,
            _ => d.get_scalar_or("endTime", f64::INFINITY)?,
        };
        let delta_t = d.get_scalar("deltaT")?;
        if delta_t.is_nan() || delta_t <= 0.0 {
            return Err(at_value(
                d,
                "deltaT",
                format!("expected a positive time step for 'deltaT', found {delta_t}"),
            ));
        }
        if end_time.is_nan() || end_time < start_time {
            return Err(at_value(
                d,
                "endTime",
                format!("expected 'endTime' at or after startTime {start_time}, found {end_time}"),
            ));
        }
        let mut names = WriteControl::ALL.map(WriteControl::name).to_vec();
        // `adjustable` is OpenFOAM's short alias of `adjustableRunTime`.
        names.push("adjustable");
        let write_control = WriteControl::ALL
            .get(choice(d, "writeControl", &names, Some(0))?)
            .copied()
            .unwrap_or(WriteControl::AdjustableRunTime);
        // `writeFrequency` is OpenFOAM's older name of it (Time::readDict)
        let interval_key =
            if d.peek("writeInterval").is_none() && d.peek("writeFrequency").is_some() {
                "writeFrequency"
            } else {
                "writeInterval"
            };
        let mut write_interval = d.get_scalar(interval_key)?;
        if write_control == WriteControl::TimeStep
            && write_interval > 1.0
            && write_interval.fract() != 0.0
        {
            // OpenFOAM counts label(writeInterval) steps
            notes.push(format!(
                "{}: {interval_key} {write_interval} steps: {} steps, as OpenFOAM counts them",
                d.file(),
                write_interval.trunc()
            ));
            write_interval = write_interval.trunc();
        }
        let interval_ok = match write_control {
            WriteControl::TimeStep => write_interval >= 1.0,
            _ => write_interval > 0.0,
        };
        if !interval_ok {
            let what = match write_control {
                WriteControl::TimeStep => "a number of steps of at least 1",
                _ => "a positive time",
            };
            return Err(at_value(
                d,
                interval_key,
                format!("expected {what} for '{interval_key}', found {write_interval}"),
            ));
        }
        let purge_write = match d.opt_integer("purgeWrite")? {
            Some(n) if n < 0 => {
                // OpenFOAM warns and keeps everything
                notes.push(format!(
                    "{}: purgeWrite {n} is negative: 0 (every time directory is kept), as OpenFOAM \
                     takes it",
                    d.file()
                ));
                0
            }
            Some(n) => n as usize,
            None => 0,
        };
        let adjust_time_step = d.get_bool_or("adjustTimeStep", false)?;
        let max_co = d.get_scalar_or("maxCo", 1.0)?;
        if max_co.is_nan() || max_co <= 0.0 {
            return Err(at_value(
                d,
                "maxCo",
                format!("expected a positive Courant number for 'maxCo', found {max_co}"),
            ));
        }
        let max_delta_t = d.get_scalar_or("maxDeltaT", f64::INFINITY)?;
        if max_delta_t.is_nan() || max_delta_t <= 0.0 {
            return Err(at_value(
                d,
                "maxDeltaT",
                format!("expected a positive time step for 'maxDeltaT', found {max_delta_t}"),
            ));
        }
        let run_time_modifiable = d.get_bool_or("runTimeModifiable", false)?;
        let (mut write_now_signal, mut stop_at_write_now_signal) = (None, None);
        if let Some(switches) = d.opt_dict("OptimisationSwitches")? {
            write_now_signal = signal_switch(switches, "writeNowSignal")?;
            stop_at_write_now_signal = signal_switch(switches, "stopAtWriteNowSignal")?;
            if write_now_signal.is_some() && write_now_signal == stop_at_write_now_signal {
                return Err(at_value(
                    switches,
                    "stopAtWriteNowSignal",
                    "expected a signal other than writeNowSignal's".to_string(),
                ));
            }
        }
        let time_precision = d.get_label_or("timePrecision", 6)?;
        if !(1..=17).contains(&time_precision) {
            return Err(at_value(
                d,
                "timePrecision",
                format!("expected 1 to 17 digits for 'timePrecision', found {time_precision}"),
            ));
        }
        let output: Vec<&str> = [
            "writeFormat",
            "writePrecision",
            "writeCompression",
            "timeFormat",
        ]
        .into_iter()
        .filter(|key| d.lookup(key).is_some())
        .collect();
        if !output.is_empty() {
            notes.push(format!(
                "{}: {} ignored: fsim writes binary VTK at full precision and names time \
                 directories in OpenFOAM's general format",
                d.file(),
                output.join(", ")
            ));
        }
        // Every controlDict names its OpenFOAM solver; fsim is the solver here.
        d.lookup("application");
        let control = ControlDict {
            start_from,
            start_time,
            stop_at,
            end_time,
            delta_t,
            write_control,
            write_interval,
            purge_write,
            adjust_time_step,
            max_co,
            max_delta_t,
            time_precision,
            run_time_modifiable,
            write_now_signal,
            stop_at_write_now_signal,
        };
        check_plan(d, &control, interval_key, plan_limits())?;
        Ok(control)
    }

    /// What a run takes from `self` in place of `before` when the file changes during it
    /// (`runTimeModifiable`), one `keyword old -> new` each: OpenFOAM's `Time::readDict` and
    /// DPMFoam's `readTimeControls.H`. `startFrom` and `startTime` matter only at the start,
    /// `deltaT` only to a fixed step.
    pub fn changes_from(&self, before: &ControlDict) -> Vec<String> {
        let entries = |c: &ControlDict| -> [(&'static str, String); 11] {
            [
                ("stopAt", c.stop_at.name().to_string()),
                ("endTime", c.end_time.to_string()),
                (
                    "deltaT",
                    if c.adjust_time_step {
                        String::new()
                    } else {
                        c.delta_t.to_string()
                    },
                ),
                ("adjustTimeStep", c.adjust_time_step.to_string()),
                ("maxCo", c.max_co.to_string()),
                ("maxDeltaT", c.max_delta_t.to_string()),
                ("writeControl", c.write_control.name().to_string()),
                ("writeInterval", c.write_interval.to_string()),
                ("purgeWrite", c.purge_write.to_string()),
                ("timePrecision", c.time_precision.to_string()),
                ("runTimeModifiable", c.run_time_modifiable.to_string()),
            ]
        };
        entries(before)
            .into_iter()
            .zip(entries(self))
            .filter(|((_, old), (_, new))| old != new && !new.is_empty())
            .map(|((key, old), (_, new))| match old.is_empty() {
                true => format!("{key} {new}"),
                false => format!("{key} {old} -> {new}"),
            })
            .collect()
    }
}

/// Time directory names, as OpenFOAM writes them (one implementation, in `output`).
pub use crate::output::time_name;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::parse_dict;

    /// `text` read as a controlDict, its notes into `notes`.
    fn read_with(text: &str, notes: &mut Vec<String>) -> Result<ControlDict, CaseError> {
        let d = parse_dict(text, "system/controlDict").unwrap();
        ControlDict::from_dict(&d, notes)
    }

    /// `text` read as a controlDict.
    fn read(text: &str) -> Result<ControlDict, CaseError> {
        read_with(text, &mut Vec::new())
    }

    #[test]
    fn time_names_match_cpp_general_format() {
        assert_eq!(time_name(0.0, 6), "0");
        assert_eq!(time_name(0.5, 6), "0.5");
        assert_eq!(time_name(1.0, 6), "1");
        assert_eq!(time_name(0.1 + 0.2, 6), "0.3");
        assert_eq!(time_name(1e-5, 6), "1e-05");
        assert_eq!(time_name(0.0001, 6), "0.0001");
        assert_eq!(time_name(1234567.0, 6), "1.23457e+06");
        assert_eq!(time_name(100.0, 6), "100");
        assert_eq!(time_name(0.123456789, 6), "0.123457");
    }

    /// A plan of more steps or writes than the limits allow is refused at the entry that
    /// makes it, naming the count and the option that raises the limit; within them, or
    /// with no end, it passes.
    #[test]
    fn plans_beyond_the_step_and_write_limits_are_refused() {
        let limits = PlanLimits {
            steps: 1000.0,
            writes: 10.0,
        };
        let plan = |text: &str| {
            let d = parse_dict(text, "system/controlDict").unwrap();
            let c = ControlDict::from_dict(&d, &mut Vec::new()).unwrap();
            check_plan(&d, &c, "writeInterval", limits)
        };
        plan("endTime 1; deltaT 0.001; writeControl timeStep; writeInterval 100;").unwrap();
        let e = plan("endTime 1; deltaT 0.0001; writeInterval 1000;").unwrap_err();
        assert_eq!((e.line, e.col), (1, 19), "{e}");
        assert!(e.message.contains("plans 1.000e4 time steps"), "{e}");
        assert!(e.message.contains("-maxSteps N"), "{e}");
        let e =
            plan("endTime 1; deltaT 0.01; writeControl runTime; writeInterval 0.01;").unwrap_err();
        assert!(e.message.starts_with("writeInterval 0.01 (runTime)"), "{e}");
        assert!(e.message.contains("plans 1.000e2 writes"), "{e}");
        assert!(e.message.contains("-maxWrites N"), "{e}");
        // with adjustTimeStep the steps are bounded below by maxDeltaT, if any
        plan("endTime 1; deltaT 1e-300; adjustTimeStep yes; writeInterval 100;").unwrap();
        let e = plan("endTime 1; deltaT 1; adjustTimeStep yes; maxDeltaT 1e-6; writeInterval 1e6;")
            .unwrap_err();
        assert!(e.message.starts_with("maxDeltaT 1e-6"), "{e}");
        // no end planned: nothing to count
        plan("stopAt nextWrite; deltaT 1e-9; writeInterval 1;").unwrap();
        // the defaults: 10⁹ steps and 10⁶ writes
        let e = read("endTime 1; deltaT 1e-300; writeInterval 1;").unwrap_err();
        assert!(e.message.contains("more than the limit of 1e9"), "{e}");
    }

    #[test]
    fn defaults_and_choices() {
        let mut notes = Vec::new();
        let c = read_with(
            "endTime 1; deltaT 0.01; writeControl runTime; writeInterval 0.1; writeFormat binary;",
            &mut notes,
        )
        .unwrap();
        // OpenFOAM's default start (Time::setControls)
        assert_eq!(c.start_from, StartFrom::LatestTime);
        assert_eq!(c.write_control, WriteControl::RunTime);
        assert_eq!(c.time_precision, 6);
        assert_eq!(c.max_co, 1.0);
        assert_eq!(notes.len(), 1);
        let c =
            read("endTime 1; deltaT 0.01; writeControl adjustable; writeInterval 0.1;").unwrap();
        assert_eq!(c.write_control, WriteControl::AdjustableRunTime);
        let c = read("endTime 1; deltaT 0.01; writeControl clockTime; writeInterval 1;").unwrap();
        assert_eq!(c.write_control, WriteControl::ClockTime);
        let e =
            read("endTime 1; deltaT 0.01; writeControl wallTime; writeInterval 1;").unwrap_err();
        assert_eq!((e.line, e.col), (1, 38));
        assert!(e
            .message
            .contains("expected one of timeStep, runTime, adjustableRunTime"));
    }

    #[test]
    fn stop_at_and_run_time_modifiable() {
        let base = "deltaT 0.01; writeControl timeStep; writeInterval 10;";
        let c = read(&format!("{base} endTime 1;")).unwrap();
        assert_eq!(c.stop_at, StopAt::EndTime);
        assert!(!c.run_time_modifiable, "OpenFOAM.com's default");
        // without stopAt endTime the end is not needed
        let c = read(&format!("{base} stopAt nextWrite; runTimeModifiable yes;")).unwrap();
        assert_eq!(c.stop_at, StopAt::NextWrite);
        assert_eq!(c.end_time, f64::INFINITY);
        assert!(c.run_time_modifiable);
        let e = read(&format!("{base} stopAt writeNow;")).unwrap();
        assert_eq!(e.stop_at, StopAt::WriteNow);
        assert!(read(&format!("{base} stopAt endTime;")).is_err());
        let e = read(&format!("{base} endTime 1; stopAt never;")).unwrap_err();
        assert!(
            e.message.contains("expected one of endTime, writeNow"),
            "{e}"
        );
        // what a running case reports as changed
        let before = read(&format!("{base} endTime 1;")).unwrap();
        let after = read(&format!("{base} endTime 2; stopAt noWriteNow;")).unwrap();
        assert_eq!(
            after.changes_from(&before),
            ["stopAt endTime -> noWriteNow", "endTime 1 -> 2"]
        );
        assert!(before.changes_from(&before).is_empty());
    }

    #[test]
    fn write_frequency_a_fractional_step_count_and_a_negative_purge_as_openfoam_reads_them() {
        let mut notes = Vec::new();
        let c = read_with(
            "endTime 1; deltaT 0.01; writeControl runTime; writeFrequency 0.1;",
            &mut notes,
        )
        .unwrap();
        assert_eq!(c.write_interval, 0.1);
        assert!(notes.is_empty());
        // label(writeInterval) steps, with a note
        let c = read_with(
            "endTime 1; deltaT 0.01; writeControl timeStep; writeInterval 2.5; purgeWrite -1;",
            &mut notes,
        )
        .unwrap();
        assert_eq!((c.write_interval, c.purge_write), (2.0, 0));
        assert_eq!(notes.len(), 2, "{notes:?}");
        assert!(
            notes[0].contains("writeInterval 2.5 steps: 2 steps"),
            "{notes:?}"
        );
        assert!(notes[1].contains("purgeWrite -1 is negative"), "{notes:?}");
        // below one step is still refused, at the value
        let e = read_with(
            "endTime 1; deltaT 0.01; writeControl timeStep; writeInterval 0.5;",
            &mut notes,
        )
        .unwrap_err();
        assert_eq!((e.line, e.col), (1, 62), "{e}");
        assert!(
            e.message
                .contains("at least 1 for 'writeInterval', found 0.5"),
            "{e}"
        );
        let e =
            read_with("endTime 1; deltaT 0.01; writeControl timeStep;", &mut notes).unwrap_err();
        assert!(e.message.contains("writeInterval"), "{e}");
    }

    #[test]
    fn signal_switches_as_openfoam_names_them() {
        let read = |switches: &str| {
            read(&format!(
                "endTime 1; deltaT 0.01; writeControl timeStep; writeInterval 1; \
                 OptimisationSwitches {{ {switches} }}"
            ))
        };
        let c = read("writeNowSignal 12; stopAtWriteNowSignal 10;").unwrap();
        assert_eq!(
            (c.write_now_signal, c.stop_at_write_now_signal),
            (Some(12), Some(10))
        );
        let c = read("writeNowSignal -1;").unwrap();
        assert_eq!(
            (c.write_now_signal, c.stop_at_write_now_signal),
            (None, None)
        );
        for bad in ["writeNowSignal 9;", "stopAtWriteNowSignal 40;"] {
            let e = read(bad).unwrap_err();
            assert!(e.message.contains("expected a signal number"), "{e}");
        }
        let e = read("writeNowSignal 10; stopAtWriteNowSignal 10;").unwrap_err();
        assert!(e.message.contains("other than writeNowSignal's"), "{e}");
    }
}
