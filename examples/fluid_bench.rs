//! Throughput of the periodic projection step (Taylor–Green vortex) at 64³ and 128³ on 1 and
//! 2 threads, in cell-steps per second, and the solver's bytes per cell.
//!
//! `cargo run --release --example fluid_bench [-- scheme [n [threads]]]` (scheme: Euler, RK3,
//! EulerRKC; default Euler, the paper's single-projection step; default sizes 64 and 128,
//! threads 1 and 2).

use fsim::fluid::{BoundaryConditions, FluidSettings, FluidSolver, TimeScheme};
use fsim::grid::Grid;
use std::f64::consts::PI;
use std::time::Instant;

/// CPU seconds used by this process so far (user + system, from `/proc/self/stat`), so the
/// figures can be read on a shared machine: wall time counts other processes' load too.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let rest = stat.rsplit_once(')').map_or("", |(_, r)| r);
    let f: Vec<&str> = rest.split_whitespace().collect();
    let field = |i: usize| {
        f.get(i)
            .and_then(|x| x.parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    // rest[0] is field 3 (state); utime and stime are fields 14 and 15 (ticks of 1/100 s).
    (field(11) + field(12)) / 100.0
}

fn main() {
    let scheme = std::env::args()
        .nth(1)
        .map(|s| TimeScheme::from_name(&s).expect("scheme: Euler, RK3 or EulerRKC"))
        .unwrap_or(TimeScheme::Euler);
    println!("scheme {}", scheme.name());
    let arg = |i: usize| {
        std::env::args()
            .nth(i)
            .and_then(|a| a.parse::<usize>().ok())
    };
    let sizes = arg(2).map_or(vec![64, 128], |n| vec![n]);
    let thread_counts = arg(3).map_or(vec![1, 2], |t| vec![t]);
    for &n in &sizes {
        for &threads in &thread_counts {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let h = 2.0 * PI / n as f64;
                let grid = Grid::new([n; 3], [h; 3], [0.0; 3]);
                let settings = FluidSettings { nu: 0.01, scheme, body_force: [0.0; 3], convection: true };
                let mut s = FluidSolver::new(grid, BoundaryConditions::periodic(), settings).unwrap();
                s.set_velocity(|c, x| match c {
                    0 => x[0].sin() * x[1].cos() * x[2].cos(),
                    1 => -x[0].cos() * x[1].sin() * x[2].cos(),
                    _ => 0.0,
                });
                s.project();
                let dt = 0.5 * s.stability_bound();
                s.step(dt); // warm up
                let cells = (n * n * n) as f64;
                let start = Instant::now();
                let cpu0 = cpu_seconds();
                let mut steps = 0;
                while steps < 3 || start.elapsed().as_secs_f64() < 3.0 {
                    s.step(dt);
                    steps += 1;
                }
                let wall = start.elapsed().as_secs_f64();
                let cpu = cpu_seconds() - cpu0;
                let d = s.diagnostics(dt);
                println!(
                    "{n:>4}³ threads {threads}: {steps:>4} steps, {:8.2} ms/step, {:7.2} M cell-steps/s (wall), {:7.2} M cell-steps per CPU-second, {:6.1} bytes/cell, divergence {:.1e}",
                    1e3 * wall / steps as f64,
                    cells * steps as f64 / wall / 1e6,
                    cells * steps as f64 / cpu / 1e6,
                    s.bytes_per_cell(),
                    d.divergence
                );
            });
        }
    }
}
