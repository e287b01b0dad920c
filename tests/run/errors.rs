//! Bad input stops before anything is written, with exit code 2 and one line naming the file,
//! line and column; a run that leaves the scheme's stability region stops with exit code 1
//! and keeps its last good time directory.

use crate::support::*;
use std::fs;
use std::path::Path;

/// Breaks a copy of the cavity with `edit`, runs it, and checks exit code 2, the first
/// stderr line (which must contain each of `expect`), and that nothing was written.
fn assert_bad_input(tag: &str, edit: impl Fn(&Path), expect: &[&str]) {
    let scratch = Scratch::new(tag);
    let case = copy_tutorial("cavity", &scratch.0, "cavity");
    edit(&case);
    let before = listing(&case);
    let zero = listing(&case.join("0"));
    let out = fsim(&case, &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{tag}: {stderr}");
    let first = stderr
        .lines()
        .find(|l| l.starts_with("fsimFoam: error:"))
        .unwrap_or_else(|| panic!("{tag}: no error line in {stderr}"));
    for e in expect {
        assert!(first.contains(e), "{tag}: '{first}' lacks '{e}'");
    }
    assert_eq!(listing(&case), before, "{tag}: the case directory changed");
    if case.join("0").is_dir() {
        assert_eq!(listing(&case.join("0")), zero, "{tag}: 0/ changed");
    }
    assert!(out.stdout.is_empty(), "{tag}: the run started");
}

fn replace(file: &Path, from: &str, to: &str) {
    let text = fs::read_to_string(file).unwrap();
    assert!(text.contains(from), "{} lacks {from}", file.display());
    fs::write(file, text.replacen(from, to, 1)).unwrap();
}

#[test]
fn missing_file() {
    assert_bad_input(
        "missing",
        |c| fs::remove_file(c.join("0/p")).unwrap(),
        &["0/p"],
    );
}

#[test]
fn unknown_patch_name() {
    assert_bad_input(
        "patch",
        |c| replace(&c.join("0/U"), "fixedWalls", "fixedWall"),
        &["0/U:", "fixedWall"],
    );
}

#[test]
fn wrong_type() {
    assert_bad_input(
        "type",
        |c| replace(&c.join("constant/transportProperties"), "0.01", "fast"),
        &["constant/transportProperties:14:34:", "fast"],
    );
}

#[test]
fn negative_viscosity() {
    assert_bad_input(
        "nu",
        |c| replace(&c.join("constant/transportProperties"), "0.01", "-0.01"),
        &["constant/transportProperties:14:", "positive"],
    );
}

#[test]
fn non_uniform_grading() {
    assert_bad_input(
        "grading",
        |c| {
            replace(
                &c.join("system/blockMeshDict"),
                "simpleGrading (1 1 1)",
                "simpleGrading (2 1 1)",
            )
        },
        &["system/blockMeshDict:", "uniform"],
    );
}

#[test]
fn zero_cells() {
    assert_bad_input(
        "zero",
        |c| replace(&c.join("system/blockMeshDict"), "(64 64 1)", "(64 0 1)"),
        &["system/blockMeshDict:"],
    );
}

#[test]
fn time_step_above_the_stability_bound() {
    assert_bad_input(
        "dt",
        |c| set_entry(&c.join("system/controlDict"), "deltaT", "0.05"),
        &["stability bound", "deltaT"],
    );
}

#[test]
fn dry_run_writes_nothing() {
    let scratch = Scratch::new("dry");
    let case = copy_tutorial("cavity", &scratch.0, "cavity");
    let before = listing(&case);
    let out = fsim(&case, &["-dry-run"]);
    assert!(out.status.success());
    let plan = String::from_utf8_lossy(&out.stdout);
    for word in ["64x64x1", "Steps", "Writes", "Memory", "Run time"] {
        assert!(plan.contains(word), "plan lacks {word}: {plan}");
    }
    assert_eq!(listing(&case), before);
}

#[test]
fn leaving_the_stability_region_stops_and_keeps_the_last_good_time() {
    // Explicit Euler at a fixed step that is stable for the initial plug flow (paper eq. 3:
    // 2 nu / |v|^2 = 0.02 s at 1 cm/s) but not for the developing Poiseuille profile, whose
    // centre-line speed 1.5 cm/s lowers the bound to 0.0089 s.
    let scratch = Scratch::new("unstable");
    let case = copy_tutorial("channel", &scratch.0, "channel");
    let control = case.join("system/controlDict");
    set_entry(&control, "adjustTimeStep", "no");
    set_entry(&control, "deltaT", "0.015");
    set_entry(&control, "writeControl", "timeStep");
    set_entry(&control, "writeInterval", "10");
    replace(&case.join("system/fvOptions"), "(0.001 0 0)", "(0.01 0 0)");
    replace(&case.join("0/U.water"), "(0.001 0 0)", "(0.01 0 0)");
    fs::write(
        case.join("system/fvSolution"),
        "FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }\n\
         fsim { timeScheme Euler; }\n",
    )
    .unwrap();
    let out = fsim(&case, &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("stability bound"), "{stderr}");
    assert!(stderr.contains("may be diverging"), "{stderr}");
    let times: Vec<String> = listing(&case)
        .into_iter()
        .filter(|n| n.parse::<f64>().is_ok() && n != "0")
        .collect();
    assert!(!times.is_empty(), "no time directory was kept");
    for t in &times {
        for file in ["fluid.vtk", "fluid.vti", "restart.bin"] {
            assert!(case.join(t).join(file).is_file(), "{t}/{file} missing");
        }
    }
    assert!(
        listing(&case).iter().all(|n| !n.starts_with('.')),
        "a partial directory was left"
    );
}

#[test]
fn unknown_time_scheme() {
    assert_bad_input(
        "scheme",
        |c| {
            fs::write(
                c.join("system/fvSolution"),
                "FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }\n\
                 fsim\n{\n    timeScheme backward;\n}\n",
            )
            .unwrap()
        },
        &["system/fvSolution:4:", "backward", "RK3"],
    );
}
