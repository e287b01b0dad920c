//! Steady Stokes flow through a simple cubic array of fixed spheres (paper §3.1): K against
//! the published values for a sweep of φ and r/h, as CSV on stdout.
//!
//! `cargo run --release --example porous_sweep -- [phi,...] [r/h,...]`
//! (defaults: the Zick & Homsy fractions up to 0.343 and φ = 0.01, 0.1; r/h = 4, 8, 16).

use fsim::coupling::direct::{reference_k, PeriodicStokesArray, RigidSphere};
use fsim::grid::Grid;
use std::time::Instant;

fn parse(arg: Option<String>, default: &[f64]) -> Vec<f64> {
    arg.map(|s| s.split(',').map(|v| v.parse().expect("a number")).collect())
        .unwrap_or_else(|| default.to_vec())
}

fn main() {
    let mut args = std::env::args().skip(1);
    let phis = parse(args.next(), &[0.01, 0.027, 0.064, 0.1, 0.125, 0.216, 0.343]);
    let resolutions = parse(args.next(), &[4.0, 8.0, 16.0]);
    println!("phi,r_over_h,cells,K,K_reference,error_percent,gmres_iterations,seconds");
    for &phi in &phis {
        for &rh in &resolutions {
            let (k, cells, r_over_h, iterations, seconds) = porous_k(phi, rh);
            let reference = reference_k(phi);
            println!(
                "{phi},{r_over_h:.3},{cells},{k:.5},{reference:.5},{:.3},{iterations},{seconds:.2}",
                100.0 * (k / reference - 1.0)
            );
        }
    }
}

/// K of one periodic cell of side 1 holding one sphere of volume fraction `phi` on the
/// grid whose cell count per side gives `r/h` nearest `target_rh`.
fn porous_k(phi: f64, target_rh: f64) -> (f64, usize, f64, usize, f64) {
    let radius = (3.0 * phi / (4.0 * std::f64::consts::PI)).cbrt();
    let n = (target_rh / radius).round() as usize;
    let h = 1.0 / n as f64;
    let grid = Grid::new([n; 3], [h; 3], [0.0; 3]);
    let nu = 1.0;
    let sphere = RigidSphere::fixed([0.5 + 0.1 * h, 0.5 + 0.2 * h, 0.5 + 0.3 * h], radius);
    let clock = Instant::now();
    // LINEAR=1 selects the linear forcing stencil, for the comparison.
    let quadratic = std::env::var("LINEAR").is_err();
    let mut array = PeriodicStokesArray::with_stencil(grid, nu, &[sphere], quadratic);
    let flow = array.solve([1.0, 0.0, 0.0], 1e-4, 600);
    let k = flow.body_force[0] / (6.0 * std::f64::consts::PI * nu * radius * 1.0);
    (
        k,
        n,
        radius / h,
        flow.report.iterations,
        clock.elapsed().as_secs_f64(),
    )
}
