//! Failures found during a run stop it with exit code 1 and a message that names what
//! failed and where (docs/user-guide/command-line.md, "Exit codes"): a particle that leaves
//! the box, an overlap beyond `MAX_OVERLAP`, a diverging velocity. Each test provokes its
//! failure just past the edge and checks that a run just short of it finishes.

use crate::support::*;
use fsim::simulation::MAX_OVERLAP;
use std::fs;
use std::path::Path;
use std::process::Output;

/// The `fsimFoam: error:` line of a run.
fn error_line(out: &Output) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr);
    stderr
        .lines()
        .find(|l| l.starts_with("fsimFoam: error:"))
        .unwrap_or_else(|| panic!("no error line in {stderr}"))
        .to_string()
}

/// The time directories of `case` other than `0`: each whole (its files all there), and no
/// partial directory left beside them.
fn assert_whole_times(case: &Path, files: &[&str]) -> Vec<String> {
    let names = listing(case);
    assert!(
        names.iter().all(|n| !n.starts_with('.')),
        "a partial directory was left: {names:?}"
    );
    let times: Vec<String> = names
        .into_iter()
        .filter(|n| n.parse::<f64>().is_ok() && n != "0")
        .collect();
    for t in &times {
        for file in files {
            assert!(case.join(t).join(file).is_file(), "{t}/{file} missing");
        }
    }
    times
}

fn replace(file: &Path, from: &str, to: &str) {
    let text = fs::read_to_string(file).unwrap();
    assert!(text.contains(from), "{} lacks {from}", file.display());
    fs::write(file, text.replacen(from, to, 1)).unwrap();
}

/// settlingInLiquid's bead (d = 1 mm, at x = 10 mm in a 20 mm wide box with rebound faces,
/// no collision model: one DEM sub-step per fluid step of 0.2 ms) started along x at `ux`
/// m/s, for 2 ms. Past about 0.03 m per step (10 mm to the x+ face, 20 mm back) a rebound
/// mirrors the centre beyond the x− face.
fn fast_bead(tag: &str, ux: f64) -> (Scratch, std::path::PathBuf, Output) {
    let scratch = Scratch::new(tag);
    let case = copy_tutorial("settlingInLiquid", &scratch.0, "bead");
    replace(
        &case.join("constant/kinematicCloudProperties"),
        "U0              (0 0 0);",
        &format!("U0              ({ux} 0 0);"),
    );
    let control = case.join("system/controlDict");
    set_entry(&control, "endTime", "0.002");
    set_entry(&control, "writeInterval", "0.001");
    let out = fsim(&case, &["-threads", "1"]);
    (scratch, case, out)
}

#[test]
fn a_particle_leaving_the_box_stops_the_run() {
    // 250 m/s (drag slows the bead within the step) stays in the box, bouncing
    let (_s, _case, out) = fast_bead("inside", 250.0);
    assert_eq!(out.status.code(), Some(0), "{}", error_line(&out));
    let (_s, case, out) = fast_bead("leaves", 270.0);
    assert_eq!(out.status.code(), Some(1), "{}", error_line(&out));
    let line = error_line(&out);
    for part in [
        "particle 0 (id 0) left the domain at t = 0.0002 s (step 1)",
        "beyond the x-min rebound face (x = 0 m)",
        "m per collision sub-step",
        "lower deltaT",
    ] {
        assert!(line.contains(part), "'{line}' lacks '{part}'");
    }
    // the centre, 0.4 mm beyond the face
    let x: f64 = line
        .split("its centre (")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no centre in '{line}'"));
    assert!((-1e-3..0.0).contains(&x), "{x}");
    assert!(assert_whole_times(&case, &["particles.vtu"]).is_empty());
}

/// impacts (beads hitting each other and the walls at 1 m/s, Hertzian contacts) with the
/// Young's modulus of the beads and walls set to `e` Pa (1e8 in the tutorial), for 5 ms.
fn soft_impacts(tag: &str, e: &str) -> (Scratch, std::path::PathBuf, Output) {
    let scratch = Scratch::new(tag);
    let case = copy_tutorial("impacts", &scratch.0, "impacts");
    let file = case.join("constant/kinematicCloudProperties");
    let text = fs::read_to_string(&file).unwrap();
    assert_eq!(text.matches("youngsModulus   1e8;").count(), 2);
    fs::write(
        &file,
        text.replace("youngsModulus   1e8;", &format!("youngsModulus   {e};")),
    )
    .unwrap();
    let out = fsim(&case, &["-threads", "1"]);
    (scratch, case, out)
}

#[test]
fn an_overlap_beyond_the_threshold_stops_the_run() {
    assert_eq!(MAX_OVERLAP, 0.2);
    // E = 1.6e5 Pa: the largest overlap is 0.197 d, the run finishes
    let (_s, case, out) = soft_impacts("soft", "1.6e5");
    assert_eq!(out.status.code(), Some(0), "{}", error_line(&out));
    assert!(case.join("0.005").is_dir());
    // E = 1.4e5 Pa: a bead reaches 0.207 d at the x+ wall
    let (_s, case, out) = soft_impacts("softer", "1.4e5");
    assert_eq!(out.status.code(), Some(1), "{}", error_line(&out));
    let line = error_line(&out);
    for part in [
        "overlaps the x-max wall by 0.207",
        "of its diameter at t = ",
        "beyond the 0.2 fsim allows",
        "stiffen them (youngsModulus",
        "collisionResolutionSteps",
    ] {
        assert!(line.contains(part), "'{line}' lacks '{part}'");
    }
    assert!(line.starts_with("fsimFoam: error: particle "), "{line}");
    let times = assert_whole_times(&case, &["particles.vtu"]);
    assert!(times.len() > 10, "{times:?}");
}

/// The channel at a fixed Euler step `dt` (s) whose bound (paper eq. 3, 2ν/|u|²) holds for
/// the initial plug flow at 1 cm/s, 0.02 s, falls below 0.0095 s at t = 3.4 s and to 0.0089 s
/// as the Poiseuille profile develops its centre-line speed of 1.5 cm/s.
fn euler_channel(tag: &str, dt: &str) -> (Scratch, std::path::PathBuf, Output) {
    let scratch = Scratch::new(tag);
    let case = copy_tutorial("channel", &scratch.0, "channel");
    let control = case.join("system/controlDict");
    set_entry(&control, "adjustTimeStep", "no");
    set_entry(&control, "deltaT", dt);
    set_entry(&control, "writeControl", "timeStep");
    set_entry(&control, "writeInterval", "100");
    replace(&case.join("system/fvOptions"), "(0.001 0 0)", "(0.01 0 0)");
    replace(&case.join("0/U.water"), "(0.001 0 0)", "(0.01 0 0)");
    fs::write(
        case.join("system/fvSolution"),
        "FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }\n\
         fsim { timeScheme Euler; }\n",
    )
    .unwrap();
    let out = fsim(&case, &["-threads", "1"]);
    (scratch, case, out)
}

#[test]
fn a_diverging_velocity_is_named_with_its_cell() {
    // 0.0095 s is just past the bound of the developed profile (0.00950 s), 0.0085 s below it
    let (_s, _case, out) = euler_channel("stable", "0.0085");
    assert_eq!(out.status.code(), Some(0), "{}", error_line(&out));
    let (_s, case, out) = euler_channel("diverging", "0.0095");
    assert_eq!(out.status.code(), Some(1), "{}", error_line(&out));
    let line = error_line(&out);
    for part in [
        "exceeds the stability bound",
        "the solution may be diverging",
        "the fluid's largest velocity is |U| = 1.45",
        "in cell (",
    ] {
        assert!(line.contains(part), "'{line}' lacks '{part}'");
    }
    // the fastest cell: on the centre line of the 16 cells across the channel, row 7 or 8
    let cell = line.split("in cell (").nth(1).unwrap();
    let j: usize = cell.split(' ').nth(1).unwrap().parse().unwrap();
    assert!(j == 7 || j == 8, "{line}");
    assert_whole_times(&case, &["fluid.vtk", "fluid.vti", "restart.bin"]);
}
