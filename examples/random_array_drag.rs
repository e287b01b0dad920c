//! Steady Stokes flow through a random array of fixed spheres in a periodic cube: the mean
//! drag per sphere against Koch & Hill's fit to lattice-Boltzmann data for random arrays,
//! as CSV on stdout. A diagnostic of how the direct model resolves the gaps of a random
//! configuration (the Richardson–Zaki sweeps, docs/richardson_zaki.md).
//!
//! `cargo run --release --example random_array_drag -- [phi,...] [r/h,...] [N] [seed]`
//! (defaults: φ = 0.1, 0.2, 0.3; r/h = 3, 4.5, 6; 27 spheres; seed 1).
//!
//! `F = ρ G V / (N 6π μ a U)` from the driving gradient (exact momentum balance), `U` the
//! superficial velocity; Koch & Hill (2001, Annu. Rev. Fluid Mech. 33, 619–647, their fit
//! for φ < 0.4 to Ladd's and Hill, Koch & Ladd's simulations):
//! `F = (1 + 3√(φ/2) + (135/64) φ ln φ + 16.14 φ) / (1 + 0.681 φ − 8.48 φ² + 8.16 φ³)`.

#[path = "../tests/support/steady_stokes.rs"]
mod steady_stokes;

use fsim::coupling::direct::RigidSphere;
use fsim::grid::Grid;
use std::f64::consts::PI;
use std::time::Instant;
use steady_stokes::PeriodicStokesArray;

fn parse(arg: Option<String>, default: &[f64]) -> Vec<f64> {
    arg.map(|s| s.split(',').map(|v| v.parse().expect("a number")).collect())
        .unwrap_or_else(|| default.to_vec())
}

fn koch_hill(phi: f64) -> f64 {
    (1.0 + 3.0 * (phi / 2.0).sqrt() + 135.0 / 64.0 * phi * phi.ln() + 16.14 * phi)
        / (1.0 + 0.681 * phi - 8.48 * phi * phi + 8.16 * phi * phi * phi)
}

/// A small LCG: seeded positions.
fn uniform(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*state >> 11) as f64 / (1u64 << 53) as f64
}

/// `count` centres in the unit periodic cube, no two closer than `reach` (random sequential
/// addition).
fn packing(count: usize, reach: f64, seed: u64) -> Vec<[f64; 3]> {
    let mut state = seed.wrapping_mul(0x9E3779B97F4A7C15) | 1;
    let mut centres: Vec<[f64; 3]> = Vec::new();
    let mut tries = 0;
    while centres.len() < count {
        tries += 1;
        assert!(tries < 10_000_000, "could not place {count} spheres");
        let x = [
            uniform(&mut state),
            uniform(&mut state),
            uniform(&mut state),
        ];
        let clear = centres.iter().all(|c| {
            let d2: f64 = (0..3)
                .map(|a| {
                    let d = (x[a] - c[a]).abs();
                    let d = d.min(1.0 - d);
                    d * d
                })
                .sum();
            d2 >= reach * reach
        });
        if clear {
            centres.push(x);
        }
    }
    centres
}

fn main() {
    let mut args = std::env::args().skip(1);
    let phis = parse(args.next(), &[0.1, 0.2, 0.3]);
    let resolutions = parse(args.next(), &[3.0, 4.5, 6.0]);
    let count: usize = args.next().map_or(27, |s| s.parse().expect("a count"));
    let seed: u64 = args.next().map_or(1, |s| s.parse().expect("a seed"));
    println!("phi,r_over_h,cells,spheres,F,F_koch_hill,ratio,gmres_iterations,seconds");
    for &phi in &phis {
        let radius = (3.0 * phi / (4.0 * PI * count as f64)).cbrt();
        for &rh in &resolutions {
            let n = (rh / radius).round() as usize;
            let h = 1.0 / n as f64;
            // surfaces at least half a cell apart, as the sedimentation sweep packs them
            let centres = packing(count, 2.0 * radius + 0.5 * h, seed);
            let spheres: Vec<RigidSphere> = centres
                .iter()
                .map(|&c| RigidSphere::fixed(c, radius))
                .collect();
            let grid = Grid::new([n; 3], [h; 3], [0.0; 3]);
            let clock = Instant::now();
            let mut array = PeriodicStokesArray::new(grid, 1.0, &spheres);
            let flow = array.solve([1.0, 0.0, 0.0], 1e-4, 600);
            let f = flow.body_force[0] / (count as f64 * 6.0 * PI * radius);
            let reference = koch_hill(phi);
            println!(
                "{phi},{:.3},{n},{count},{f:.4},{reference:.4},{:.4},{},{:.1}",
                radius / h,
                f / reference,
                flow.report.iterations,
                clock.elapsed().as_secs_f64()
            );
        }
    }
}
