//! Direct-model cases the grid cannot resolve or the coupling cannot run: clear errors
//! (exit 2, nothing written) or warnings (at `-dry-run` and before the run), and a coupled run
//! that diverges stops with the reason (exit 1) and keeps its last good time directory.

use crate::support::*;
use std::fs;
use std::path::{Path, PathBuf};

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
    // and it names what grew: the fluid's fastest cell and the sphere
    for part in [
        "the fluid's largest velocity is |U| = ",
        "in cell (",
        "the fastest particle's |U| = ",
        "particle 0 (id 0) at (",
    ] {
        assert!(stderr.contains(part), "{part} not in {stderr}");
    }
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

/// `tutorials/settlingSphere` at 18³ cells (r/h = 4) under `EulerRKC`, whose fluid bound
/// (the Courant step, about 10⁻² s) is far above the sphere's response time
/// `ρ_p d²/(18 μ)` = 4.44·10⁻⁴ s, with `edit` applied to system/controlDict.
fn coarse_settling_sphere(scratch: &Scratch, edit: impl Fn(&Path)) -> PathBuf {
    broken(scratch, "settlingSphere", |c| {
        replace(&c.join("system/blockMeshDict"), "(36 36 36)", "(18 18 18)");
        replace(
            &c.join("system/fvSolution"),
            "timeScheme      Euler;",
            "timeScheme      EulerRKC;",
        );
        edit(&c.join("system/controlDict"));
    })
}

/// A step above a quarter of the response time: `-dry-run` warns, for a fixed step, and
/// says the adjustable step is held.
#[test]
fn a_step_beyond_the_coupling_bound_warns() {
    let s = Scratch::new("direct-response-fixed");
    let case = coarse_settling_sphere(&s, |control| {
        set_entry(control, "adjustTimeStep", "no");
        set_entry(control, "deltaT", "1.6e-4");
    });
    assert_dry_run_warns(&case, &["deltaT = 1.6e-4 s is 0.36 of", "4.444e-4 s"]);
    let s = Scratch::new("direct-response-adjustable");
    let case = coarse_settling_sphere(&s, |control| {
        set_entry(control, "maxDeltaT", "1.6e-4");
    });
    assert_dry_run_warns(&case, &["steps held to at most 1.111e-4 s"]);
}

/// With `maxDeltaT` at 0.36 of the response time the sphere's velocity oscillated by
/// several times its settling velocity (±3 mm/s against 0.84 mm/s; docs/direct_model.md,
/// "Known limits"). Held to a quarter of it, the sphere settles steadily: over the last
/// 30 ms of 60 its velocity stays within 2 % of its mean (measured 0.57 %, the forced
/// faces changing as it crosses the grid).
#[test]
fn an_adjustable_step_is_held_to_the_coupling_bound() {
    let s = Scratch::new("direct-response-run");
    let case = coarse_settling_sphere(&s, |control| {
        set_entry(control, "maxDeltaT", "1.6e-4");
        set_entry(control, "deltaT", "1.6e-4");
        set_entry(control, "endTime", "0.06");
        set_entry(control, "writeInterval", "0.06");
    });
    let out = fsim(&case, &[]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut time = 0.0;
    let mut late = Vec::new();
    for line in stdout.lines() {
        if let Some(t) = line.strip_prefix("Time = ") {
            time = t.trim().parse().unwrap();
        } else if let Some(v) = line.trim().strip_prefix("Mean velocity = (") {
            let vy: f64 = v.split_whitespace().nth(1).unwrap().parse().unwrap();
            if time > 0.03 {
                late.push(vy);
            }
        } else if let Some(dt) = line.strip_prefix("deltaT = ") {
            let dt: f64 = dt.trim().parse().unwrap();
            // the last step before a write time may stretch by 1 % to land on it
            assert!(dt <= 1.011 * 1.1111e-4, "a step of {dt} s");
        }
    }
    assert!(late.len() > 100, "{} steps after 30 ms", late.len());
    let mean = late.iter().sum::<f64>() / late.len() as f64;
    let spread = late
        .iter()
        .map(|v| (v / mean - 1.0).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "settling at {:.5} mm/s, within {:.3} % of it",
        -1e3 * mean,
        100.0 * spread
    );
    assert!(mean < -5e-4, "settling at {mean} m/s");
    assert!(
        spread < 0.02,
        "the velocity strays {:.1} % from its mean",
        100.0 * spread
    );
}

/// Issue 40: under-resolution is reported with what fixes it. Too few cells per radius names
/// the count, the thinnest spheres and the cells for r/h = 2 and 4 (8 cells: r/h 1.78; 9 give
/// 2.0 and 18 give 4.0); narrow gaps name the pairs and the cells that resolve the smallest;
/// a sphere's gap to its own periodic image counts, and one of 2 cells does not warn.
#[test]
fn under_resolution_names_the_particles_and_the_grid_that_fixes_it() {
    let s = Scratch::new("direct-resolution-fix");
    let case = broken(&s, "settlingSphere", |c| {
        replace(&c.join("system/blockMeshDict"), "(36 36 36)", "(8 8 8)")
    });
    assert_refused(
        &case,
        &[
            "1 of 1 particle(s) have fewer",
            "(9 9 9) cells for r/h = 2",
            "(18 18 18) cells for r/h = 4",
        ],
    );
    let case = broken(&s, "sedimentation", |c| {
        set_positions(c, &[[0.005, 0.01, 0.005], [0.0066, 0.01, 0.005]]);
    });
    assert_dry_run_warns(
        &case,
        &["particles 0 and 1 (0.40 h)", "resolve the smallest"],
    );
    // one sphere per periodic cube: φ = 0.5 leaves 0.43 h to its images, φ = 0.3 at n = 28
    // leaves (L − d)/h = 28 (1 − (6·0.3/π)^⅓) = 4.3 cells
    let dense = broken(&s, "porousMedia", |c| {
        replace(
            &c.join("constant/porousParameters"),
            "phi         0.1;",
            "phi         0.5;",
        )
    });
    assert_dry_run_warns(&dense, &["its periodic image along x (0.43 h)"]);
    let fine = broken(&s, "porousMedia", |c| {
        replace(
            &c.join("constant/porousParameters"),
            "phi         0.1;",
            "phi         0.3;",
        )
    });
    let out = fsim(&fine, &["-dry-run"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("periodic image"), "{err}");
}
