//! `stopAt` and `runTimeModifiable`, as OpenFOAM's `Time`: a run stopped by its controlDict
//! at the start or while it runs, and a controlDict changed during the run.

mod support;

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};
use support::*;

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

#[test]
fn stop_at_in_the_file_ends_the_run_after_one_step_or_at_the_next_write() {
    let scratch = Scratch::new("stop-at");
    // writeNow: one step, written
    let case = cavity(&scratch, "writeNow", &[("stopAt", "writeNow")]);
    let plan = fsim(&case, &["-dry-run"]);
    let plan = String::from_utf8_lossy(&plan.stdout);
    assert!(plan.contains("Steps   : about 1 of"), "{plan}");
    let out = fsim(&case, &[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(times(&case), [0.0, 0.005]);
    assert!(case.join("0.005/restart.bin").exists());

    // noWriteNow: one step, not written
    let case = cavity(&scratch, "noWriteNow", &[("stopAt", "noWriteNow")]);
    let out = fsim(&case, &[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
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
    let out = fsim(&case, &[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(times(&case), [0.0, 0.05]);
}

/// fsimFoam on `case` in the background, its log and messages into files of the case.
fn spawn(case: &Path) -> Child {
    Command::new(env!("CARGO_BIN_EXE_fsimFoam"))
        .arg("-case")
        .arg(case)
        .stdout(fs::File::create(case.join("log.out")).unwrap())
        .stderr(fs::File::create(case.join("log.err")).unwrap())
        .stdin(Stdio::null())
        .spawn()
        .unwrap()
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

#[test]
fn a_running_case_takes_its_changed_control_dict() {
    let scratch = Scratch::new("run-time-modifiable");
    let case = cavity(
        &scratch,
        "modifiable",
        &[
            ("endTime", "10000"),
            ("writeInterval", "0.5"),
            ("runTimeModifiable", "yes"),
        ],
    );
    let mut run = spawn(&case);
    wait_for("the first write", || case.join("0.5").is_dir());

    // A file that does not read: a warning at its place, and the run goes on.
    change(&case, "endTime", "10000 3");
    wait_for("the warning", || {
        fs::read_to_string(case.join("log.err"))
            .unwrap()
            .contains("system/controlDict:")
    });
    let err = fs::read_to_string(case.join("log.err")).unwrap();
    assert!(
        err.contains("the run goes on with the settings it had"),
        "{err}"
    );
    assert!(run.try_wait().unwrap().is_none(), "the run went on");

    // Then a new write interval, then writeNow: one more step, written, and the end.
    change(&case, "endTime", "10000");
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
    let status = {
        let mut status = None;
        wait_for("the end of the run", || {
            status = run.try_wait().unwrap();
            status.is_some()
        });
        status.unwrap()
    };
    assert!(status.success());
    let log = fs::read_to_string(case.join("log.out")).unwrap();
    assert!(log.contains("writeInterval 0.5 -> 0.25"), "{log}");
    assert!(log.contains("stopAt endTime -> writeNow"), "{log}");
    assert!(log.trim_end().ends_with("End"), "{log}");
    let last = *times(&case).last().unwrap();
    assert!(last < 10000.0);
    let name = listing(&case)
        .into_iter()
        .find(|n| n.parse::<f64>().ok() == Some(last))
        .unwrap();
    assert!(case.join(&name).join("restart.bin").exists());
    // the step after the change is the last
    let after = log.rsplit("stopAt endTime -> writeNow").next().unwrap();
    assert_eq!(after.matches("\nTime = ").count(), 1, "{after}");
}

#[test]
fn without_run_time_modifiable_the_file_is_read_once() {
    let scratch = Scratch::new("not-modifiable");
    let case = cavity(
        &scratch,
        "fixed",
        &[("endTime", "10000"), ("writeInterval", "0.5")],
    );
    // OpenFOAM.com's default: no (the tutorial says yes)
    let control = case.join("system/controlDict");
    let text = fs::read_to_string(&control).unwrap();
    let kept: Vec<&str> = text
        .lines()
        .filter(|l| !l.starts_with("runTimeModifiable"))
        .collect();
    fs::write(&control, kept.join("\n")).unwrap();
    let mut run = spawn(&case);
    wait_for("the first write", || case.join("0.5").is_dir());
    change(&case, "stopAt", "writeNow");
    // long enough for the change to settle and be read, were it read
    let changed = Instant::now();
    let after = times(&case).len() + 2;
    wait_for("two more writes, a second on", || {
        times(&case).len() >= after && changed.elapsed() > Duration::from_secs(1)
    });
    assert!(run.try_wait().unwrap().is_none(), "the run went on");
    run.kill().unwrap();
    run.wait().unwrap();
}

#[test]
fn clock_time_writes_every_interval_of_wall_time() {
    let scratch = Scratch::new("clock-time");
    let case = cavity(
        &scratch,
        "clockTime",
        &[
            ("endTime", "10"),
            ("writeControl", "clockTime"),
            ("writeInterval", "0.2"),
        ],
    );
    let start = Instant::now();
    let out = fsim(&case, &[]);
    let wall = start.elapsed().as_secs_f64();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // 2,000 steps: at least a few tenths of a second on any machine
    let t = times(&case);
    assert_eq!((t[0], *t.last().unwrap()), (0.0, 10.0));
    let between = t.len() - 2;
    assert!(
        between >= 1 && between as f64 <= wall / 0.2 + 1.0,
        "{between} writes in {wall:.2} s: {t:?}"
    );
}
