//! `stopAt` and `runTimeModifiable`, as OpenFOAM's `Time`: a run stopped by its controlDict
//! at the start or while it runs, and a controlDict changed during the run.

use crate::support::*;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The time directories of `case`, by time.
fn times(case: &Path) -> Vec<f64> {
    let mut t: Vec<f64> = listing(case)
        .iter()
        .filter_map(|n| n.parse::<f64>().ok())
        .collect();
    t.sort_by(f64::total_cmp);
    t
}

/// The lid-driven cavity (64 × 64 cells, fixed step 0.005 s, a few thousand steps a second)
/// with the given controlDict entries.
fn cavity(scratch: &Scratch, name: &str, entries: &[(&str, &str)]) -> PathBuf {
    let case = copy_tutorial("cavity", &scratch.0, name);
    for (key, value) in entries {
        set_entry(&case.join("system/controlDict"), key, value);
    }
    case
}

/// Runs `case` to its end, which must succeed.
fn completed(case: &Path) -> Output {
    let out = fsim(case, &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    out
}

#[test]
fn stop_at_in_the_file_ends_the_run_after_one_step_or_at_the_next_write() {
    let scratch = Scratch::new("stop-at");
    // writeNow: one step, written
    let case = cavity(&scratch, "writeNow", &[("stopAt", "writeNow")]);
    let plan = fsim(&case, &["-dry-run"]);
    let plan = String::from_utf8_lossy(&plan.stdout);
    assert!(plan.contains("Steps   : about 1 of"), "{plan}");
    completed(&case);
    assert_eq!(times(&case), [0.0, 0.005]);
    assert!(case.join("0.005/restart.bin").exists());

    // noWriteNow: one step, not written
    let case = cavity(&scratch, "noWriteNow", &[("stopAt", "noWriteNow")]);
    let out = completed(&case);
    assert_eq!(times(&case), [0.0]);
    let log = String::from_utf8_lossy(&out.stdout);
    assert!(
        log.contains("Time = 0.005") && !log.contains("Time = 0.01\n"),
        "{log}"
    );

    // nextWrite: on past endTime to the next write time
    let case = cavity(
        &scratch,
        "nextWrite",
        &[
            ("stopAt", "nextWrite"),
            ("endTime", "0.01"),
            ("writeInterval", "0.05"),
        ],
    );
    completed(&case);
    assert_eq!(times(&case), [0.0, 0.05]);

    // nextWrite at a wall-clock write: the plan counts the steps to it at its timed cost
    let case = cavity(
        &scratch,
        "nextWriteClock",
        &[
            ("stopAt", "nextWrite"),
            ("writeControl", "clockTime"),
            ("writeInterval", "2"),
        ],
    );
    let plan = fsim(&case, &["-dry-run"]);
    let plan = String::from_utf8_lossy(&plan.stdout);
    let run_time: f64 = plan
        .split("Run time: about ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("{plan}"));
    assert!((2.0..2.2).contains(&run_time), "{plan}");
    assert!(
        plan.contains("to the first write, after 2 s of wall-clock time"),
        "{plan}"
    );
    assert!(!plan.contains("Steps   : about 1 of"), "{plan}");

    // and at a CPU-time write, at the CPU time the timed steps took
    let case = cavity(
        &scratch,
        "nextWriteCpu",
        &[
            ("stopAt", "nextWrite"),
            ("writeControl", "cpuTime"),
            ("writeInterval", "2"),
        ],
    );
    let plan = fsim(&case, &["-dry-run", "-threads", "1"]);
    let plan = String::from_utf8_lossy(&plan.stdout);
    assert!(
        plan.contains("after 2 s of CPU time on all threads"),
        "{plan}"
    );
    assert!(!plan.contains("Steps   : about 1 of"), "{plan}");
}

/// fsimFoam running on a case in the background, its log and messages into files of the
/// case; killed if a test fails before it ends.
struct Running(Child);

impl Running {
    fn start(case: &Path) -> Self {
        let child = Command::new(env!("CARGO_BIN_EXE_fsimFoam"))
            .arg("-case")
            .arg(case)
            .stdout(fs::File::create(case.join("log.out")).unwrap())
            .stderr(fs::File::create(case.join("log.err")).unwrap())
            .stdin(Stdio::null())
            .spawn()
            .unwrap();
        Running(child)
    }

    fn is_running(&mut self) -> bool {
        self.0.try_wait().unwrap().is_none()
    }

    /// Waits for the run to end; whether it succeeded.
    fn finish(mut self) -> bool {
        let mut status = None;
        wait_for("the end of the run", || {
            status = self.0.try_wait().unwrap();
            status.is_some()
        });
        status.unwrap().success()
    }
}

impl Drop for Running {
    fn drop(&mut self) {
        if self.is_running() {
            let _ = self.0.kill();
            let _ = self.0.wait();
        }
    }
}

/// Waits up to two minutes (a loaded machine) for `done`.
fn wait_for(what: &str, mut done: impl FnMut() -> bool) {
    let start = Instant::now();
    while !done() {
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "timed out waiting for {what}"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Rewrites one entry of the running case's controlDict.
fn change(case: &Path, key: &str, value: &str) {
    set_entry(&case.join("system/controlDict"), key, value);
}

fn read(case: &Path, file: &str) -> String {
    fs::read_to_string(case.join(file)).unwrap()
}

/// After the log's last `marker`, the run took exactly one step, and wrote it last.
fn assert_one_more_step_written(case: &Path, log: &str, marker: &str) {
    let after = log.rsplit(marker).next().unwrap();
    assert_eq!(after.matches("\nTime = ").count(), 1, "{after}");
    let last = after.split("\nTime = ").nth(1).unwrap();
    let last = last.lines().next().unwrap();
    assert!(case.join(last).join("restart.bin").exists(), "{last}");
    assert_eq!(*times(case).last().unwrap(), last.parse::<f64>().unwrap());
}

/// The cavity to run until stopped (endTime 10000 s, a write each 0.5 s), its controlDict's
/// text then passed through `edit`.
fn long_cavity(scratch: &Scratch, name: &str, edit: impl Fn(&str) -> String) -> PathBuf {
    let case = cavity(
        scratch,
        name,
        &[("endTime", "10000"), ("writeInterval", "0.5")],
    );
    let control = case.join("system/controlDict");
    let text = fs::read_to_string(&control).unwrap();
    fs::write(&control, edit(&text)).unwrap();
    case
}

/// A long cavity run that reads its controlDict again, once it has written 0.5.
fn modifiable_run(scratch: &Scratch, name: &str) -> (PathBuf, Running) {
    let case = cavity(
        scratch,
        name,
        &[
            ("endTime", "10000"),
            ("writeInterval", "0.5"),
            ("runTimeModifiable", "yes"),
        ],
    );
    let run = Running::start(&case);
    wait_for("the first write", || case.join("0.5").is_dir());
    (case, run)
}

#[test]
fn a_running_case_takes_its_changed_control_dict() {
    let scratch = Scratch::new("run-time-modifiable");
    let (case, mut run) = modifiable_run(&scratch, "modifiable");

    // A file that does not read: a warning at its place, and the run goes on.
    change(&case, "endTime", "10000 3");
    wait_for("the warning", || {
        read(&case, "log.err").contains("controlDict:")
    });
    let err = read(&case, "log.err");
    assert!(
        err.contains("the run goes on with the settings it had"),
        "{err}"
    );
    assert!(run.is_running());

    // A fixed step beyond the scheme's bound would stop the run: refused, the run goes on.
    change(&case, "endTime", "10000");
    change(&case, "deltaT", "0.5");
    wait_for("the second warning", || {
        read(&case, "log.err").contains("exceeds the scheme's stability bound")
    });
    assert!(run.is_running());

    // Then a new write interval, then writeNow: one more step, written, and the end.
    change(&case, "deltaT", "0.005");
    change(&case, "writeInterval", "0.25");
    // a write at an odd multiple of 0.25 s, which the old interval never gives
    let odd_quarter = |t: &f64| {
        let q = t * 4.0;
        (q - q.round()).abs() < 1e-9 && q.round() % 2.0 == 1.0
    };
    wait_for("a write at the new interval", || {
        times(&case).iter().any(odd_quarter)
    });
    change(&case, "stopAt", "writeNow");
    assert!(run.finish());
    let log = read(&case, "log.out");
    assert!(log.contains("writeInterval 0.5 -> 0.25"), "{log}");
    assert!(log.contains("stopAt endTime -> writeNow"), "{log}");
    assert!(log.trim_end().ends_with("End"), "{log}");
    assert_one_more_step_written(&case, &log, "stopAt endTime -> writeNow");
}

/// A file the controlDict `#include`s is watched as OpenFOAM watches it: `stopAt writeNow`
/// written into it stops the run after one more step, written.
#[test]
fn a_running_case_takes_a_change_of_a_file_its_control_dict_includes() {
    let scratch = Scratch::new("included-control");
    let case = long_cavity(&scratch, "included", |text| {
        let kept: Vec<&str> = text
            .lines()
            .filter(|l| !l.starts_with("stopAt") && !l.starts_with("runTimeModifiable"))
            .collect();
        format!(
            "{}\nrunTimeModifiable yes;\n#include \"runControl\"\n",
            kept.join("\n")
        )
    });
    let included = case.join("system/runControl");
    fs::write(&included, "stopAt endTime;\n").unwrap();
    let run = Running::start(&case);
    wait_for("the first write", || case.join("0.5").is_dir());
    fs::write(&included, "stopAt writeNow;\n").unwrap();
    assert!(run.finish());
    let log = read(&case, "log.out");
    assert!(log.contains("stopAt endTime -> writeNow"), "{log}");
    assert_one_more_step_written(&case, &log, "stopAt endTime -> writeNow");
}

#[test]
fn an_end_time_already_passed_ends_the_run_where_it_is_and_writes_it() {
    let scratch = Scratch::new("end-time-passed");
    let (case, run) = modifiable_run(&scratch, "passed");
    change(&case, "endTime", "0.1");
    assert!(run.finish());
    let log = read(&case, "log.out");
    assert!(log.contains("endTime 10000 -> 0.1"), "{log}");
    let at = log.rsplit("changed at t = ").next().unwrap();
    let at = at.split(':').next().unwrap();
    assert!(at.parse::<f64>().unwrap() > 0.5, "{at}");
    let last = listing(&case)
        .into_iter()
        .filter(|n| n.parse::<f64>().is_ok())
        .max_by(|a, b| {
            a.parse::<f64>()
                .unwrap()
                .total_cmp(&b.parse::<f64>().unwrap())
        });
    assert_eq!(last.as_deref(), Some(at));
    assert!(case.join(at).join("restart.bin").exists());
}

#[test]
fn without_run_time_modifiable_the_file_is_read_once() {
    let scratch = Scratch::new("not-modifiable");
    // OpenFOAM.com's default: no (the tutorial says yes)
    let case = long_cavity(&scratch, "fixed", |text| {
        let kept: Vec<&str> = text
            .lines()
            .filter(|l| !l.starts_with("runTimeModifiable"))
            .collect();
        kept.join("\n")
    });
    let mut run = Running::start(&case);
    wait_for("the first write", || case.join("0.5").is_dir());
    change(&case, "stopAt", "writeNow");
    // long enough for the change to settle and be read, were it read
    let changed = Instant::now();
    let after = times(&case).len() + 2;
    wait_for("two more writes, a second on", || {
        times(&case).len() >= after && changed.elapsed() > Duration::from_secs(1)
    });
    assert!(run.is_running(), "the run went on");
}

#[test]
fn clock_time_writes_every_interval_of_wall_time() {
    let scratch = Scratch::new("clock-time");
    let case = cavity(
        &scratch,
        "clockTime",
        &[
            ("endTime", "20"),
            ("writeControl", "clockTime"),
            ("writeInterval", "0.1"),
        ],
    );
    let start = Instant::now();
    completed(&case);
    let wall = start.elapsed().as_secs_f64();
    // 4,000 steps: at least a few tenths of a second on any machine
    let t = times(&case);
    assert_eq!((t[0], *t.last().unwrap()), (0.0, 20.0));
    let between = t.len() - 2;
    assert!(
        between >= 1 && between as f64 <= wall / 0.1 + 1.0,
        "{between} writes in {wall:.2} s: {t:?}"
    );
}

#[test]
fn a_run_stopped_by_write_now_continues_bit_for_bit() {
    let scratch = Scratch::new("write-now-continued");
    let entries = [("endTime", "0.1"), ("writeInterval", "0.05")];
    let whole = cavity(&scratch, "whole", &entries);
    let split = cavity(&scratch, "split", &entries);
    completed(&whole);
    change(&split, "stopAt", "writeNow");
    completed(&split);
    assert_eq!(times(&split), [0.0, 0.005]);
    change(&split, "stopAt", "endTime");
    change(&split, "startFrom", "latestTime");
    completed(&split);
    for file in ["restart.bin", "fluid.vtk"] {
        let a = fs::read(whole.join("0.1").join(file)).unwrap();
        let b = fs::read(split.join("0.1").join(file)).unwrap();
        assert!(a == b, "0.1/{file} differs after a stop and a restart");
    }
}

#[test]
fn signals_write_the_next_step_or_stop_the_run_as_openfoam_switches_say() {
    let scratch = Scratch::new("signals");
    let case = long_cavity(&scratch, "signals", |text| {
        format!(
            "{text}\nOptimisationSwitches\n{{\n    writeNowSignal 12;\n    \
             stopAtWriteNowSignal 10;\n}}\n"
        )
    });
    let run = Running::start(&case);
    wait_for("the first write", || case.join("0.5").is_dir());
    let pid = run.0.id() as libc::pid_t;
    let off_the_interval = |case: &Path| {
        times(case)
            .into_iter()
            .filter(|t| ((t * 2.0).round() - t * 2.0).abs() > 1e-9)
            .collect::<Vec<f64>>()
    };
    // SIGUSR2: a write of the next step, and the run goes on
    // SAFETY: a signal to the child this test started.
    assert_eq!(unsafe { libc::kill(pid, libc::SIGUSR2) }, 0);
    wait_for("the extra write", || off_the_interval(&case).len() == 1);
    wait_for("a write after it", || {
        times(&case).last() > off_the_interval(&case).first()
    });
    // SIGUSR1: the next step written, and the end
    // SAFETY: as above.
    assert_eq!(unsafe { libc::kill(pid, libc::SIGUSR1) }, 0);
    assert!(run.finish());
    let log = read(&case, "log.out");
    assert!(log.contains("signal 12: the next step is written"), "{log}");
    assert_one_more_step_written(&case, &log, "signal 10: stopAt writeNow");
}
