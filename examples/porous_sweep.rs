//! Steady Stokes flow through a simple cubic array of fixed spheres (paper §3.1): K against
//! the published values for a sweep of φ and r/h, as CSV on stdout.
//!
//! `cargo run --release --example porous_sweep -- [phi,...] [r/h,...]`
//! (defaults: φ = 0.01, the Zick & Homsy fractions up to 0.343 and 0.1; r/h = 4, 8, 16).
//! `LINEAR=1` selects the linear forcing stencil, for the comparison.
//!
//! Columns: `K` from the driving gradient (`F = ρ G L³`, exact momentum balance), then
//! `K_<offset>_<interpolation>` from the stress integral on the sphere (offset 0) and one,
//! two, three cells out, trilinear and tricubic: the alternatives of docs/direct_model.md.

#[path = "../tests/support/porous_reference.rs"]
mod porous_reference;
#[path = "../tests/support/steady_stokes.rs"]
mod steady_stokes;

use fsim::coupling::direct::{
    stress_integral_force, FieldView, Interpolation, RigidSphere, StressIntegral,
};
use fsim::fluid::PaddedLayout;
use fsim::grid::Grid;
use porous_reference::reference_k;
use std::f64::consts::PI;
use std::time::Instant;
use steady_stokes::PeriodicStokesArray;

fn parse(arg: Option<String>, default: &[f64]) -> Vec<f64> {
    arg.map(|s| s.split(',').map(|v| v.parse().expect("a number")).collect())
        .unwrap_or_else(|| default.to_vec())
}

const OFFSETS: [f64; 4] = [0.0, 1.0, 2.0, 3.0];
const INTERPOLATIONS: [Interpolation; 2] = [Interpolation::Linear, Interpolation::Cubic];

fn main() {
    let mut args = std::env::args().skip(1);
    let phis = parse(args.next(), &[0.01, 0.027, 0.064, 0.1, 0.125, 0.216, 0.343]);
    let resolutions = parse(args.next(), &[4.0, 8.0, 16.0]);
    let mut header =
        String::from("phi,r_over_h,cells,K,K_reference,error_percent,gmres_iterations,seconds");
    for offset in OFFSETS {
        for i in INTERPOLATIONS {
            header += &format!(",K_{offset}_{}", i.name());
        }
    }
    println!("{header}");
    for &phi in &phis {
        for &rh in &resolutions {
            let row = porous(phi, rh);
            let reference = reference_k(phi);
            let mut line = format!(
                "{phi},{:.3},{},{:.5},{reference:.5},{:.3},{},{:.2}",
                row.r_over_h,
                row.cells,
                row.k,
                100.0 * (row.k / reference - 1.0),
                row.iterations,
                row.seconds
            );
            for k in row.stress_k {
                line += &format!(",{k:.5}");
            }
            println!("{line}");
        }
    }
}

struct Row {
    k: f64,
    cells: usize,
    r_over_h: f64,
    iterations: usize,
    seconds: f64,
    stress_k: Vec<f64>,
}

/// One periodic cell of side 1 holding one sphere of volume fraction `phi`, on the grid
/// whose cell count per side gives `r/h` nearest `target_rh`; ν = 1, U = 1.
fn porous(phi: f64, target_rh: f64) -> Row {
    let radius = (3.0 * phi / (4.0 * PI)).cbrt();
    let n = (target_rh / radius).round() as usize;
    let h = 1.0 / n as f64;
    let grid = Grid::new([n; 3], [h; 3], [0.0; 3]);
    let nu = 1.0;
    let sphere = RigidSphere::fixed([0.5 + 0.1 * h, 0.5 + 0.2 * h, 0.5 + 0.3 * h], radius);
    let clock = Instant::now();
    let quadratic = std::env::var("LINEAR").is_err();
    let mut array = PeriodicStokesArray::with_stencil(grid.clone(), nu, &[sphere], quadratic);
    let flow = array.solve([1.0, 0.0, 0.0], 1e-4, 600);
    let seconds = clock.elapsed().as_secs_f64();
    let drag = 6.0 * PI * nu * radius;
    let layout = PaddedLayout::new(grid.n);
    let view = FieldView {
        grid: &grid,
        layout: &layout,
        periodic: [true; 3],
        velocity: &flow.velocity,
        pressure: &flow.pressure,
        nu,
    };
    let mut stress_k = Vec::new();
    for offset in OFFSETS {
        for interpolation in INTERPOLATIONS {
            let integral = StressIntegral {
                surface_offset: offset,
                interpolation,
            };
            let q = integral.quadrature(radius, h);
            let load = stress_integral_force(&view, &sphere, 1.0, flow.body_force, &integral, &q);
            stress_k.push(load.force[0] / drag);
        }
    }
    Row {
        k: flow.body_force[0] / drag,
        cells: n,
        r_over_h: radius / h,
        iterations: flow.report.iterations,
        seconds,
        stress_k,
    }
}
