//! Direct-model cases the grid cannot resolve or the coupling cannot run: clear errors
//! (exit 2, nothing written) or warnings (at `-dry-run` and before the run), and a coupled run
//! that diverges stops with the reason (exit 1) and keeps its last good time directory.

mod support;

use std::fs;
use std::path::{Path, PathBuf};
use support::*;

fn replace(file: &Path, from: &str, to: &str) {
    let text = fs::read_to_string(file).unwrap();
    assert!(text.contains(from), "{} lacks {from}", file.display());
    fs::write(file, text.replacen(from, to, 1)).unwrap();
}

/// A copy of `tutorials/<name>` with `edit` applied.
fn broken(scratch: &Scratch, name: &str, edit: impl Fn(&Path)) -> PathBuf {
    let case = copy_tutorial(name, &scratch.0, name);
    edit(&case);
    case
}

/// Runs the case and checks exit code 2, an error line containing each of `expect`, and
/// that nothing was written.
fn assert_refused(case: &Path, expect: &[&str]) {
    let before = listing(case);
    let zero = listing(&case.join("0"));
    let out = fsim(case, &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    let first = stderr
        .lines()
        .find(|l| l.starts_with("fsimFoam: error:"))
        .unwrap_or_else(|| panic!("no error line in {stderr}"));
    for e in expect {
        assert!(first.contains(e), "'{first}' lacks '{e}'");
    }
    assert_eq!(listing(case), before, "the case directory changed");
    assert_eq!(listing(&case.join("0")), zero, "0/ changed");
}

/// `-dry-run` prints a warning containing each of `expect` (stderr) and exits 0.
fn assert_dry_run_warns(case: &Path, expect: &[&str]) {
    let out = fsim(case, &["-dry-run"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    let line = stderr
        .lines()
        .find(|l| l.starts_with("fsimFoam: warning:") && expect.iter().all(|e| l.contains(e)))
        .unwrap_or_else(|| panic!("no warning with {expect:?} in {stderr}"));
    assert!(!line.is_empty());
}

#[test]
fn fewer_than_two_cells_per_radius() {
    let s = Scratch::new("direct-coarse");
    // 36 → 8 cells: h = 0.5625 mm for r = 1 mm, r/h = 1.78
    let case = broken(&s, "settlingSphere", |c| {
        replace(&c.join("system/blockMeshDict"), "(36 36 36)", "(8 8 8)")
    });
    assert_refused(&case, &["r/h = 1.778", "at least 2 cells in radius"]);
}

#[test]
fn sphere_larger_than_the_box() {
    let s = Scratch::new("direct-large");
    let case = broken(&s, "settlingSphere", |c| {
        replace(
            &c.join("constant/kinematicCloudProperties"),
            "value 0.002;",
            "value 0.005;",
        )
    });
    // the DEM loader finds it first: a sphere wider than the periodic box
    assert_refused(&case, &["periodic length", "largest diameter"]);
}

#[test]
fn overlapping_spheres() {
    let s = Scratch::new("direct-overlap");
    let case = broken(&s, "sedimentation", |c| {
        let file = c.join("constant/kinematicCloudPositions");
        let text = fs::read_to_string(&file).unwrap();
        let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
        let first = lines
            .iter()
            .position(|l| l.starts_with('(') && l.len() > 2)
            .unwrap();
        // the second sphere a third of a diameter from the first
        let xyz: Vec<f64> = lines[first]
            .trim_matches(|ch| ch == '(' || ch == ')')
            .split_whitespace()
            .map(|v| v.parse().unwrap())
            .collect();
        lines[first + 1] = format!("({} {} {})", xyz[0] + 0.0005, xyz[1], xyz[2]);
        fs::write(&file, lines.join("\n") + "\n").unwrap();
    });
    assert_refused(&case, &["overlap"]);
}

#[test]
fn narrow_gaps_warn_at_dry_run() {
    let s = Scratch::new("direct-gap");
    let case = broken(&s, "sedimentation", |c| {
        // two spheres (d = 1.5 mm, h = 0.25 mm) 0.1 mm = 0.4 h apart
        set_positions(c, &[[0.005, 0.01, 0.005], [0.0066, 0.01, 0.005]]);
    });
    assert_dry_run_warns(&case, &["narrower than 2 cells", "0.40 h"]);
}

#[test]
fn fixed_spheres_without_driving_warn() {
    let s = Scratch::new("direct-undriven");
    let case = broken(&s, "settlingSphere", |c| {
        replace(
            &c.join("constant/couplingProperties"),
            "model           direct;",
            "model           direct;\ndirect { fixedParticles yes; }",
        )
    });
    assert_dry_run_warns(&case, &["nothing drives the flow"]);
}

#[test]
fn light_particles_are_refused() {
    let s = Scratch::new("direct-light");
    let case = broken(&s, "settlingSphere", |c| {
        replace(
            &c.join("constant/kinematicCloudProperties"),
            "rho0            2000;",
            "rho0            150;",
        )
    });
    assert_refused(&case, &["0.150 times the fluid's"]);
}

/// Without the virtual mass the explicit coupling of a sphere a fifth as dense as the liquid
/// diverges within a millisecond (the added-mass instability): the run stops with the
/// reason, exit 1, and keeps the time directories it wrote whole.
#[test]
fn added_mass_instability_stops_and_keeps_the_last_good_time() {
    let s = Scratch::new("direct-diverge");
    let case = broken(&s, "settlingSphere", |c| {
        replace(
            &c.join("constant/kinematicCloudProperties"),
            "rho0            2000;",
            "rho0            200;",
        );
        replace(
            &c.join("constant/couplingProperties"),
            "model           direct;",
            "model           direct;\nvirtualMass     0;\ndirect { interpolation linear; }",
        );
        set_entry(&c.join("system/controlDict"), "endTime", "0.003");
        set_entry(&c.join("system/controlDict"), "writeInterval", "0.0002");
    });
    let out = fsim(&case, &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("diverged"),
        "no divergence message in {stderr}"
    );
    // The Courant step collapses as the velocity grows: the run stops there, within tens of
    // steps of the onset, not 1,200 vanishing steps later when the velocity overflows.
    assert!(
        stderr.contains("the step the Courant rule allows fell to"),
        "{stderr}"
    );
    let step: usize = stderr
        .split("(step ")
        .nth(1)
        .and_then(|rest| rest.split(')').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no step in {stderr}"));
    assert!(step < 200, "stopped at step {step}");
    let times: Vec<String> = listing(&case)
        .into_iter()
        .filter(|n| n.parse::<f64>().is_ok())
        .collect();
    assert!(times.contains(&"0".to_string()), "{times:?}");
    for t in &times {
        assert!(
            case.join(t).join("fluid.vti").exists() || t == "0",
            "{t} incomplete"
        );
    }
}
