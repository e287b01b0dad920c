//! `fsimFoam -case tutorials/porousMedia` end to end: one fixed sphere per periodic cell at
//! φ = 0.1, r/h = 8, driven by meanVelocityForce; the K it monitors (stress integral three
//! cells out) matches Sangani & Acrivos (paper eq. 17) within 3 %.

use crate::support::porous_reference::sangani_acrivos_k;
use crate::support::*;
use std::fs;

#[test]
fn porous_media_tutorial_gives_the_sangani_acrivos_k() {
    let scratch = Scratch::new("porous-tutorial");
    let case = copy_tutorial("porousMedia", &scratch.0, "porousMedia");
    let out = fsim(&case, &["-threads", "2"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let monitor = fs::read_to_string(case.join("postProcessing/direct/0/direct.dat")).unwrap();
    let last: Vec<f64> = monitor
        .lines()
        .rfind(|l| !l.starts_with('#'))
        .unwrap()
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    let k = last[7];
    let reference = sangani_acrivos_k(0.1);
    assert!(
        (k / reference - 1.0).abs() < 0.03,
        "K {k} vs {reference} (Sangani & Acrivos)"
    );
    // The force per sphere balances the driving: F = ρ G L³ (G from the fluid monitor).
    let fluid = fs::read_to_string(case.join("postProcessing/fluid/0/fluid.dat")).unwrap();
    let row: Vec<f64> = fluid
        .lines()
        .rfind(|l| !l.starts_with('#'))
        .unwrap()
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    let gradient = row[8];
    let balance = 1000.0 * gradient * 0.0028f64.powi(3);
    assert!(
        (last[1] / balance - 1.0).abs() < 0.01,
        "stress integral {} N vs ρ G L³ = {balance} N",
        last[1]
    );
    assert!(case.join("0.015/particles.vtu").exists());
}

/// A `model direct` run continued from a time directory equals the uninterrupted run bit for
/// bit (the shell momenta of the force's rate term are part of the restart state).
#[test]
fn direct_run_restarts_bit_for_bit() {
    let (end, half) = ("0.0008", "0.0004");
    let scratch = Scratch::new("direct-restart");
    let whole = copy_tutorial("porousMedia", &scratch.0, "whole");
    let split = copy_tutorial("porousMedia", &scratch.0, "split");
    for case in [&whole, &split] {
        let control = case.join("system/controlDict");
        set_entry(&control, "endTime", end);
        set_entry(&control, "writeInterval", half);
        // The spheres' own (fixed) motion is trivial; a coarse grid keeps this quick.
        set_entry(&case.join("constant/porousParameters"), "n", "14");
    }
    let out = fsim(&whole, &["-threads", "2"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let control = split.join("system/controlDict");
    set_entry(&control, "endTime", half);
    let out = fsim(&split, &["-threads", "2"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    set_entry(&control, "endTime", end);
    set_entry(&control, "startFrom", "latestTime");
    let out = fsim(&split, &["-threads", "2"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for file in ["restart.bin", "particles.vtu", "fluid.vtk"] {
        let a = fs::read(whole.join(end).join(file)).unwrap();
        let b = fs::read(split.join(end).join(file)).unwrap();
        assert!(a == b, "{end}/{file} differs after a restart");
    }
    // The loads of every step after the restart, the first included, are the same.
    let rows = |path: std::path::PathBuf| -> Vec<String> {
        fs::read_to_string(path)
            .unwrap()
            .lines()
            .filter(|l| !l.starts_with('#'))
            .map(str::to_string)
            .collect()
    };
    let continued = rows(
        split
            .join("postProcessing/direct")
            .join(half)
            .join("direct.dat"),
    );
    let uninterrupted = rows(whole.join("postProcessing/direct/0/direct.dat"));
    assert!(!continued.is_empty());
    assert_eq!(
        continued[..],
        uninterrupted[uninterrupted.len() - continued.len()..]
    );
}

/// Spheres the grid cannot resolve, or larger than the periodic box, stop the run before
/// anything is written (exit 2), naming the particle.
#[test]
fn unresolvable_spheres_are_refused() {
    let scratch = Scratch::new("direct-bad-input");
    let coarse = copy_tutorial("porousMedia", &scratch.0, "coarse");
    set_entry(&coarse.join("constant/porousParameters"), "n", "6"); // r/h = 1.73
    let out = fsim(&coarse, &["-dry-run"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("at least 2 cells in radius: 1 of 1 particle(s) have fewer"),
        "{err}"
    );
    assert!(err.contains("particle 1 (id 0) r/h = 1.728"), "{err}");
    assert!(err.contains("(7 7 7) cells for r/h = 2"), "{err}");

    let large = copy_tutorial("porousMedia", &scratch.0, "large");
    set_entry(&large.join("constant/porousParameters"), "phi", "0.6"); // d = 1.05 L
    let out = fsim(&large, &["-dry-run"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("does not fit the periodic box"), "{err}");
    assert!(!large.join("postProcessing").exists());

    // r/h below 4 runs, with a note.
    let note = copy_tutorial("porousMedia", &scratch.0, "note");
    set_entry(&note.join("constant/porousParameters"), "n", "12"); // r/h = 3.46
    let out = fsim(&note, &["-dry-run"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains("below 4 cells in radius (smallest r/h = 3.46)"),
        "{err}"
    );
}
