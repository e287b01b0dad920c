//! `-dry-run` plans the run from a few steps it takes in memory: the step count it plans is
//! checked against the steps the run then takes (deterministic), never against a clock.

use crate::support::{copy_tutorial, fsim, listing, set_entry, set_positions, Scratch};
use std::fs;
use std::path::Path;

/// The step count of the plan's `Steps   : about N of ...` line.
fn planned_steps(plan: &str) -> f64 {
    let line = plan
        .lines()
        .find(|l| l.starts_with("Steps   : about "))
        .unwrap_or_else(|| panic!("no step count in the plan: {plan}"));
    line["Steps   : about ".len()..]
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap()
}

/// The steps a finished run took: the rows of its fluid monitor.
fn steps_taken(case: &Path) -> f64 {
    let monitor = fs::read_to_string(case.join("postProcessing/fluid/0/fluid.dat")).unwrap();
    monitor.lines().filter(|l| !l.starts_with('#')).count() as f64
}

/// Plans `case`, checks the plan names its measured cost and wrote nothing, then runs it.
fn plan_then_run(case: &Path) -> (f64, f64) {
    let before = listing(case);
    let out = fsim(case, &["-dry-run", "-threads", "2"]);
    let plan = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for word in [
        "Timed   : ",
        "step(s) taken in memory",
        "Run time: about",
        "Memory  : ",
    ] {
        assert!(plan.contains(word), "plan lacks {word}: {plan}");
    }
    // the peak memory comes from /proc
    #[cfg(target_os = "linux")]
    assert!(plan.contains("peak after the timed steps"), "{plan}");
    assert_eq!(listing(case), before, "the dry run wrote into the case");
    let out = fsim(case, &["-threads", "2"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (planned_steps(&plan), steps_taken(case))
}

/// The porous tutorial's adaptive step grows from `deltaT` (1e-5 s) to the viscous bound
/// within its first steps; the plan reads the step after its timed steps, not `deltaT`.
#[test]
fn dry_run_plans_the_steps_of_the_porous_tutorial() {
    let scratch = Scratch::new("plan-porous");
    let case = copy_tutorial("porousMedia", &scratch.0, "porousMedia");
    let (planned, taken) = plan_then_run(&case);
    assert!(
        (planned / taken - 1.0).abs() < 0.05,
        "planned {planned} steps, the run took {taken}"
    );
}

/// Gas–solid settling (the benchmark's spheres and gas, eight of them in a 20³-cell box,
/// φ = 0.065): the flow starts at rest, and the plan takes the Courant step at twice the
/// spheres' terminal velocity, about the largest fluid speed of the benchmark's 0.1 s
/// (2.26 U_t). This calmer box reaches 1.3 U_t and takes fewer steps: the plan errs long,
/// by less than twice.
#[test]
fn dry_run_plans_a_settling_gas_suspension_on_the_long_side() {
    let scratch = Scratch::new("plan-settling");
    let case = copy_tutorial("benchmark", &scratch.0, "gas");
    let block = case.join("system/blockMeshDict");
    let mut text = fs::read_to_string(&block).unwrap();
    for (from, to) in [
        ("0.0012000000000000001", "0.0004"),
        ("0.0036000000000000003", "0.0004"),
        ("(60 180 60)", "(20 20 20)"),
    ] {
        assert!(
            text.contains(from),
            "the benchmark's blockMeshDict lacks {from}"
        );
        text = text.replace(from, to);
    }
    fs::write(&block, text).unwrap();
    // random, at least 1.1 d apart across the periodic box (seeded once, written out)
    let centres = [
        [2.49161e-4, 2.96715e-4, 3.18077e-4],
        [3.7698e-4, 2.95959e-4, 3.6893e-4],
        [1.16021e-5, 1.86249e-4, 3.77343e-4],
        [2.5959e-4, 3.6036e-4, 4.52824e-5],
        [1.87628e-4, 9.86291e-5, 2.17504e-4],
        [1.11793e-4, 3.66538e-4, 3.0629e-4],
        [6.38417e-5, 3.18859e-4, 5.5507e-5],
        [3.48562e-4, 8.37826e-5, 8.61925e-5],
    ];
    set_positions(&case, &centres);
    let control = case.join("system/controlDict");
    set_entry(&control, "endTime", "0.008");
    set_entry(&control, "writeInterval", "0.008");
    let (planned, taken) = plan_then_run(&case);
    assert!(
        planned >= taken && planned < 2.0 * taken,
        "planned {planned} steps, the run took {taken}"
    );
}
