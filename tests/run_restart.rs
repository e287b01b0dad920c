//! `startFrom latestTime` continues an interrupted run exactly: 0 → T in one run equals
//! 0 → T/2 then latestTime → T, bit for bit, in every file of the final time directory.

mod support;

use std::fs;
use support::*;

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
    let times = |case: &std::path::Path| -> Vec<String> {
        listing(case)
            .into_iter()
            .filter(|n| n.parse::<f64>().is_ok())
            .collect()
    };
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
