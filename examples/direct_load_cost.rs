//! Cost of the direct model's per-step work for the paper's benchmark geometry (§3.3):
//! 500 spheres of r/h = 2.5 in a 24r × 72r × 24r periodic box (60 × 180 × 60 cells):
//! rebuilding the forced faces, one imposition, and the loads (stress integral and shell)
//! with trilinear and tricubic interpolation: the fastest of several repetitions (a shared
//! machine is noisy).
//!
//! `cargo run --release --example direct_load_cost [threads]`

use fsim::coupling::direct::{DirectCoupling, DirectSettings, Interpolation, RigidSphere};
use fsim::fluid::{BoundaryConditions, FluidSettings, FluidSolver};
use fsim::grid::Grid;
use fsim::particles::SplitMix64;
use fsim::Vec3;
use std::time::Instant;

fn main() {
    let threads = std::env::args()
        .nth(1)
        .and_then(|t| t.parse().ok())
        .unwrap_or(1);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(run);
}

fn run() {
    let r = 5e-5;
    let h = 0.4 * r;
    let n = [60, 180, 60];
    let grid = Grid::new(n, [h; 3], [0.0; 3]);
    let length = grid.length();
    let mut fluid = FluidSolver::new(
        grid,
        BoundaryConditions::periodic(),
        FluidSettings::new(1.5e-5),
    )
    .unwrap();
    fluid.set_velocity(|c, x| {
        if c == 1 {
            0.01 * (x[0] * 1e4).sin()
        } else {
            0.0
        }
    });
    // Random non-overlapping centres.
    let mut rng = SplitMix64::new(7);
    let mut spheres: Vec<RigidSphere> = Vec::new();
    while spheres.len() < 500 {
        let c: [f64; 3] = std::array::from_fn(|d| rng.next_f64() * length[d]);
        let clear = spheres.iter().all(|s| {
            let d2: f64 = (0..3)
                .map(|d| {
                    let mut x = c[d] - s.centre[d];
                    x -= length[d] * (x / length[d]).round();
                    x * x
                })
                .sum();
            d2 > (2.2 * r) * (2.2 * r)
        });
        if clear {
            let mut s = RigidSphere::fixed(c, r);
            s.velocity = Vec3::new(0.0, -0.01, 0.0);
            spheres.push(s);
        }
    }
    let ids: Vec<u64> = (0..500).collect();
    for interpolation in [Interpolation::Linear, Interpolation::Cubic] {
        let mut settings = DirectSettings::default();
        settings.integral.interpolation = interpolation;
        let mut coupling = DirectCoupling::new(&mut fluid, settings);
        // The fastest of several repetitions: the least disturbed by other work on a shared
        // machine.
        let mut update = f64::INFINITY;
        for _ in 0..6 {
            // Moved a little, as in a suspension: unchanged spheres are not rebuilt.
            for s in spheres.iter_mut() {
                s.centre[1] -= 1e-9;
            }
            let clock = Instant::now();
            coupling.set_spheres(&spheres, &ids);
            update = update.min(clock.elapsed().as_secs_f64());
        }
        let mut loads = f64::INFINITY;
        for _ in 0..10 {
            let clock = Instant::now();
            coupling.compute_loads(&fluid, 1.2);
            loads = loads.min(clock.elapsed().as_secs_f64());
        }
        println!(
            "{}: forced faces {}, update {update:.4} s, loads {loads:.4} s per step",
            interpolation.name(),
            coupling.boundary().forced_count()
        );
    }
    let clock = Instant::now();
    fluid.step(1e-6);
    println!(
        "one fluid step (RK3): {:.4} s",
        clock.elapsed().as_secs_f64()
    );
}
