//! Stokes flow through a simple cubic array of fixed spheres (paper §3.1), solved to steady
//! state by the direct model's forcing ([`PeriodicStokesArray`]): K = F/(6πμrU) against
//! Zick & Homsy (1982, Table 2) and Sangani & Acrivos (paper eq. 17), and its order of
//! convergence in h. The full sweep: `cargo run --release --example porous_sweep`.

use fsim::coupling::direct::{sangani_acrivos_k, PeriodicStokesArray, RigidSphere};
use fsim::grid::Grid;
use std::f64::consts::PI;

/// K for volume fraction `phi` on `n³` cells (unit cell, ν = 1, U = 1); the sphere is off
/// the grid's symmetry points by a fraction of a cell.
fn porous_k(phi: f64, n: usize) -> f64 {
    let radius = (3.0 * phi / (4.0 * PI)).cbrt();
    let h = 1.0 / n as f64;
    let grid = Grid::new([n; 3], [h; 3], [0.0; 3]);
    let sphere = RigidSphere::fixed([0.5 + 0.1 * h, 0.5 + 0.2 * h, 0.5 + 0.3 * h], radius);
    let mut array = PeriodicStokesArray::new(grid, 1.0, &[sphere]);
    let flow = array.solve([1.0, 0.0, 0.0], 1e-4, 600);
    flow.body_force[0] / (6.0 * PI * radius)
}

#[test]
fn k_matches_sangani_acrivos_and_zick_homsy_at_r_over_h_8_and_16() {
    // (φ, cells per side, reference): r/h = n (3φ/4π)^⅓.
    let cases = [
        (0.01, 60, sangani_acrivos_k(0.01)), // r/h = 8.02
        (0.216, 21, 7.442),                  // r/h = 7.82, Zick & Homsy
        (0.343, 37, 15.4),                   // r/h = 16.1, Zick & Homsy
    ];
    for (phi, n, reference) in cases {
        let k = porous_k(phi, n);
        let error = (k / reference - 1.0).abs();
        eprintln!(
            "φ {phi}, n {n}: K {k:.4}, reference {reference:.4}, error {:.2} %",
            100.0 * error
        );
        assert!(error < 0.03, "φ {phi}: K {k} vs {reference}");
    }
}

#[test]
fn k_converges_faster_than_order_one_and_a_half() {
    let phi = 0.1;
    let reference = sangani_acrivos_k(phi);
    let errors: Vec<f64> = [14, 28, 56]
        .iter()
        .map(|&n| (porous_k(phi, n) / reference - 1.0).abs())
        .collect();
    eprintln!("φ 0.1, r/h 4, 8, 16: errors {errors:?}");
    for w in errors.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!(order >= 1.5, "order {order} ({errors:?})");
    }
}
