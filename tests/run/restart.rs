//! `startFrom latestTime` continues an interrupted run exactly: 0 → T in one run equals
//! 0 → T/2 then latestTime → T, bit for bit, in every file of the final time directory.

use crate::support::*;
use std::fs;

/// The names of the time directories of `case`, sorted as text.
fn times(case: &std::path::Path) -> Vec<String> {
    listing(case)
        .into_iter()
        .filter(|n| n.parse::<f64>().is_ok())
        .collect()
}

fn assert_restart_is_exact(tutorial: &str, end: &str, half: &str, threads: &str) {
    let scratch = Scratch::new(&format!("restart-{tutorial}"));
    let whole = copy_tutorial(tutorial, &scratch.0, "whole");
    let split = copy_tutorial(tutorial, &scratch.0, "split");
    for case in [&whole, &split] {
        set_entry(&case.join("system/controlDict"), "endTime", end);
        set_entry(&case.join("system/controlDict"), "writeInterval", half);
    }

    let out = fsim(&whole, &["-threads", threads]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );

    let control = split.join("system/controlDict");
    set_entry(&control, "endTime", half);
    let out = fsim(&split, &["-threads", threads]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(!split.join(end).exists());
    set_entry(&control, "endTime", end);
    set_entry(&control, "startFrom", "latestTime");
    let out = fsim(&split, &["-threads", threads]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // The continued run's monitor starts at its own start time, as OpenFOAM's do.
    assert!(split.join("postProcessing/fluid").join(half).is_dir());

    for file in ["restart.bin", "fluid.vtk", "fluid.vti"] {
        let a = fs::read(whole.join(end).join(file)).unwrap();
        let b = fs::read(split.join(end).join(file)).unwrap();
        assert!(a == b, "{tutorial}: {end}/{file} differs after a restart");
    }
    assert_eq!(times(&whole), times(&split));
}

#[test]
fn fixed_step_taylor_green_restarts_bit_for_bit() {
    assert_restart_is_exact("taylorGreen", "1", "0.5", "2");
}

#[test]
fn adaptive_step_driven_channel_restarts_bit_for_bit() {
    // adjustTimeStep with maxCo, adjustableRunTime writes, meanVelocityForce state.
    assert_restart_is_exact("channel", "10", "5", "1");
}

/// A finished run continued with `startFrom latestTime` has nothing left to do: `-dry-run`
/// says so instead of planning a sliver of a step (the saved time can sit a rounding error
/// below `endTime`), and a real run adds no time directory.
#[test]
fn finished_run_continued_plans_no_step() {
    let scratch = Scratch::new("restart-finished");
    let case = copy_tutorial("cavity", &scratch.0, "cavity");
    let control = case.join("system/controlDict");
    // twenty steps of 0.005 sum to just above 0.1 in binary: the saved time is off endTime
    set_entry(&control, "endTime", "0.1");
    set_entry(&control, "writeInterval", "0.1");
    let out = fsim(&case, &[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    set_entry(&control, "startFrom", "latestTime");
    let out = fsim(&case, &["-dry-run"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let plan = String::from_utf8_lossy(&out.stdout);
    assert!(plan.contains("Steps   : none"), "{plan}");
    let before = listing(&case);
    let out = fsim(&case, &[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        listing(&case).iter().filter(|n| n.starts_with('0')).count(),
        before.iter().filter(|n| n.starts_with('0')).count()
    );
}

/// OpenFOAM's `startFrom firstTime` and `latestTime` start at their directory's own time,
/// from the fields in it, when it holds no fsim restart state (a directory OpenFOAM wrote or
/// a user prepared); a latest directory with neither is refused before anything is written;
/// with no `startFrom` the default is OpenFOAM's, `latestTime`.
#[test]
fn first_and_latest_time_start_at_their_directory() {
    let scratch = Scratch::new("start-from");
    for (start_from, dirs) in [
        ("firstTime", &["0.2", "0.3"][..]),
        ("latestTime", &["0.1", "0.2"][..]),
        ("", &["0.1", "0.2"][..]),
    ] {
        let label = if start_from.is_empty() {
            "default"
        } else {
            start_from
        };
        let case = copy_tutorial("cavity", &scratch.0, label);
        for d in dirs {
            fs::create_dir_all(case.join(d)).unwrap();
            for field in ["U", "p"] {
                fs::copy(case.join("0").join(field), case.join(d).join(field)).unwrap();
            }
        }
        fs::remove_dir_all(case.join("0")).unwrap();
        let control = case.join("system/controlDict");
        if start_from.is_empty() {
            let text = fs::read_to_string(&control).unwrap();
            let kept: Vec<&str> = text
                .lines()
                .filter(|l| !l.starts_with("startFrom"))
                .collect();
            fs::write(&control, kept.join("\n") + "\n").unwrap();
        } else {
            set_entry(&control, "startFrom", start_from);
        }
        set_entry(&control, "endTime", "0.25");
        set_entry(&control, "writeInterval", "0.05");
        let out = fsim(&case, &[]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{label}: {stderr}");
        let times = times(&case);
        // started at 0.2 (its restart state and VTK files added beside U and p), ran to
        // 0.25; never from 0, which is not written
        assert!(times.contains(&"0.25".to_string()), "{label}: {times:?}");
        assert!(!times.contains(&"0".to_string()), "{label}: {times:?}");
        assert!(case.join("0.2/restart.bin").exists(), "{label}");
        assert!(case.join("0.2/U").exists(), "{label}: the inputs stay");
        assert_eq!(times.len(), dirs.len() + 1, "{label}: {times:?}");
    }
    let case = copy_tutorial("cavity", &scratch.0, "unreadable");
    fs::create_dir_all(case.join("0.5")).unwrap();
    fs::write(case.join("0.5/notes.txt"), "not a time's fields").unwrap();
    set_entry(&case.join("system/controlDict"), "startFrom", "latestTime");
    refused(
        &case,
        "the latest time directory '0.5' holds neither U nor fsim's restart.bin",
    );
}

/// `purgeWrite N` deletes only the oldest of the directories this run wrote, as OpenFOAM's
/// `Time::writeObject` does: never the start time's (the initial conditions) nor an earlier
/// run's times.
#[test]
fn purge_write_spares_the_inputs_and_earlier_runs() {
    let scratch = Scratch::new("purge-write");
    let case = copy_tutorial("cavity", &scratch.0, "cavity");
    let control = case.join("system/controlDict");
    set_entry(&control, "endTime", "0.1");
    set_entry(&control, "writeInterval", "0.05");
    set_entry(&control, "purgeWrite", "1");
    let out = fsim(&case, &[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(times(&case), ["0", "0.1"]);
    assert!(case.join("0/U").exists() && case.join("0/p").exists());
    // continued: 0.1 is the earlier run's, the start of this one; 0.15 is purged by 0.2
    set_entry(&control, "startFrom", "latestTime");
    set_entry(&control, "endTime", "0.2");
    let out = fsim(&case, &[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(times(&case), ["0", "0.1", "0.2"]);
}

/// `adjustableRunTime` without `adjustTimeStep` keeps the fixed step and writes as
/// `runTime` does, at the step nearest each write time (OpenFOAM adjusts the step to write
/// times only within its adjustable step).
#[test]
fn adjustable_run_time_with_a_fixed_step_keeps_the_step() {
    let scratch = Scratch::new("adjustable-fixed");
    let case = copy_tutorial("cavity", &scratch.0, "cavity");
    let control = case.join("system/controlDict");
    set_entry(&control, "deltaT", "0.003");
    set_entry(&control, "endTime", "0.03");
    set_entry(&control, "writeControl", "adjustableRunTime");
    set_entry(&control, "writeInterval", "0.01");
    let out = fsim(&case, &[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let times = times(&case);
    // OpenFOAM: 0.009 and 0.021; fsim also lands on endTime (0.03, a last step of 0.003)
    assert_eq!(times, ["0", "0.009", "0.021", "0.03"]);
}
