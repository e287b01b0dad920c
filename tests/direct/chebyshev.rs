//! The direct model with `EulerRKC`, whose Chebyshev stages are explicit and constrained one
//! by one, so the drag does not depend on the step: porous media (fixed simple cubic array)
//! time-stepped at 1, 4 and 10 times the explicit viscous bound against the explicit RK3 run
//! and the reference K, and a `fsimFoam` run whose step follows the Courant number. (The
//! settling sphere across the same steps: `tests/direct/motion.rs`.)

use crate::driven_array::driven_array;
use crate::support::porous_reference::reference_k;
use crate::support::*;
use fsim::coupling::direct::{stress_integral_force, FieldView, StressIntegral};
use fsim::fluid::TimeScheme;
use std::f64::consts::PI;
use std::fs;
use std::path::Path;

/// K of a simple cubic array (unit cell, ν = ρ = U = 1, `n³` cells) time-stepped to
/// t = 0.1 L²/ν (K within 0.03 % of its value at 0.2 L²/ν) with `scheme` at `factor` times RK3's viscous bound:
/// `(K from the momentum balance, K from the stress integral)`.
fn time_stepped_k(phi: f64, n: usize, scheme: TimeScheme, factor: f64) -> (f64, f64) {
    let (mut fluid, mut coupling, sphere, dt) = driven_array(phi, n, scheme, factor);
    let (radius, h) = (sphere.radius, 1.0 / n as f64);
    let steps = (0.1 / dt).ceil() as usize;
    for _ in 0..steps {
        fluid.step_with(dt, &mut |stage| coupling.impose(stage));
    }
    let g = fluid.mean_velocity_force().unwrap().gradient;
    let integral = StressIntegral::default();
    let load = stress_integral_force(
        &FieldView::of(&fluid),
        &sphere,
        1.0,
        [g, 0.0, 0.0],
        &integral,
        &integral.quadrature(radius, h),
    );
    let drag = 6.0 * PI * radius;
    (g / drag, load.force[0] / drag)
}

/// φ = 0.1 at r/h = 6 (21³ cells): the steady K of EulerRKC at 1, 4 and 10 times the
/// explicit viscous bound equals the explicit RK3 run's within 1 % (momentum balance and
/// stress integral), and both are within 3 % of the reference (Sangani & Acrivos = Zick &
/// Homsy here).
#[test]
fn porous_k_does_not_depend_on_the_chebyshev_step() {
    let (phi, n) = (0.1, 21);
    let reference = reference_k(phi);
    let (k_explicit, k_stress_explicit) = time_stepped_k(phi, n, TimeScheme::RK3, 0.9);
    eprintln!("RK3 at 0.9 x its bound: K {k_explicit:.5} (stress integral {k_stress_explicit:.5}), reference {reference:.5}");
    assert!((k_explicit / reference - 1.0).abs() < 0.03);
    for factor in [1.0, 4.0, 10.0] {
        let (k, k_stress) = time_stepped_k(phi, n, TimeScheme::EulerRKC, factor);
        eprintln!(
            "EulerRKC at {factor} x the RK3 bound: K {k:.5} ({:+.4} % vs RK3), stress integral \
             {k_stress:.5} ({:+.4} %)",
            100.0 * (k / k_explicit - 1.0),
            100.0 * (k_stress / k_stress_explicit - 1.0)
        );
        assert!((k / k_explicit - 1.0).abs() < 0.01, "K {k} vs {k_explicit}");
        assert!(
            (k_stress / k_stress_explicit - 1.0).abs() < 0.01,
            "K {k_stress} vs {k_stress_explicit}"
        );
        assert!((k / reference - 1.0).abs() < 0.03, "K {k} vs {reference}");
    }
}

/// Rows of a monitor file (`#` header names the columns), as numbers.
fn monitor_rows(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let names = text
        .lines()
        .next()
        .unwrap()
        .trim_start_matches('#')
        .split_whitespace()
        .map(str::to_string)
        .collect();
    let rows = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
        .collect();
    (names, rows)
}

fn column(names: &[String], name: &str) -> usize {
    names.iter().position(|n| n == name).unwrap()
}

/// `fsimFoam` on the porousMedia tutorial at r/h = 6 with a faster flow (Ubar 0.05 m/s,
/// Re_d = 0.8), `adjustTimeStep yes; maxCo 0.5;`: with `RK3` the step is held at RK3's viscous
/// bound (the Courant number stays far below 0.5); with `EulerRKC` the step grows
/// until the Courant number reaches maxCo, several times the viscous bound, and K (steady,
/// from the stress integral) equals the RK3 run's within 1 %.
#[test]
fn fsimfoam_chebyshev_scheme_steps_by_the_courant_number() {
    let scratch = Scratch::new("chebyshev-courant");
    let mut results = Vec::new();
    for scheme in ["RK3", "EulerRKC"] {
        let case = copy_tutorial("porousMedia", &scratch.0, scheme);
        set_entry(&case.join("constant/porousParameters"), "n", "21");
        set_entry(&case.join("system/fvOptions"), "Ubar", "(0.05 0 0)");
        set_entry(&case.join("system/fvSolution"), "timeScheme", scheme);
        let control = case.join("system/controlDict");
        set_entry(&control, "endTime", "0.008");
        set_entry(&control, "writeInterval", "0.008");
        let out = fsim(&case, &["-threads", "2"]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let (names, rows) = monitor_rows(&case.join("postProcessing/fluid/0/fluid.dat"));
        let (dt, co) = (column(&names, "deltaT"), column(&names, "CoMax"));
        // The last full step (the final two are shortened to land on endTime together).
        let last = &rows[rows.len() - 3];
        let (names_d, rows_d) = monitor_rows(&case.join("postProcessing/direct/0/direct.dat"));
        let k = rows_d.last().unwrap()[column(&names_d, "K")];
        eprintln!(
            "{scheme}: {} steps, last deltaT {:.4e} s at Courant {:.3}, K {k:.5}",
            rows.len(),
            last[dt],
            last[co]
        );
        results.push((rows.len(), last[dt], last[co], k));
    }
    let explicit = results[0];
    // RK3: the viscous bound 2.51 h²/(12 ν), h = 2.8 mm / 21, ν = 1e-4 m²/s.
    let h = 0.0028 / 21.0;
    let bound = 2.51 * h * h / (12.0 * 1e-4);
    assert!(
        (explicit.1 / bound - 1.0).abs() < 1e-6,
        "RK3 step {}",
        explicit.1
    );
    assert!(explicit.2 < 0.2, "RK3 Courant {}", explicit.2);
    // EulerRKC: at maxCo, several times RK3's step.
    for semi in &results[1..] {
        assert!((semi.2 - 0.5).abs() < 0.05, "Courant {}", semi.2);
        assert!(semi.1 > 4.0 * bound, "step {} vs bound {bound}", semi.1);
        assert!(
            semi.0 * 4 < explicit.0,
            "steps {} vs {}",
            semi.0,
            explicit.0
        );
        assert!(
            (semi.3 / explicit.3 - 1.0).abs() < 0.01,
            "K {} vs {}",
            semi.3,
            explicit.3
        );
    }
}
