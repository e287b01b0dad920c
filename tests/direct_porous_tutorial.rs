//! `fsimFoam -case tutorials/porousMedia` end to end: one fixed sphere per periodic cell at
//! φ = 0.1, r/h = 8, driven by meanVelocityForce; the K it monitors (stress integral three
//! cells out) matches Sangani & Acrivos (paper eq. 17) within 3 %.

mod support;

use fsim::coupling::direct::sangani_acrivos_k;
use std::fs;
use support::*;

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
