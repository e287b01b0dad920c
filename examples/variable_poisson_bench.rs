//! Variable-coefficient pressure solve `∇·(β∇p) = f`: CG iterations and wall time per solve
//! with the spectral (constant mean-β) preconditioner against the multigrid V-cycle, on
//! smooth `β ∈ [0.4, 1]`, a packed-bed surface (β = 0.36 below mid-height, 1 above) and a
//! 100× checkerboard jump (blocks of n/4 cells), walls in x, a wall below and an outlet
//! (fixed pressure) above in y, periodic z; seeded random right-hand side, tolerance 1e-10.
//!
//! `cargo run --release --example variable_poisson_bench [-- n ...]` (default 32 64 128).

use fsim::fluid::{
    comparison_beta, seeded_uniform, AxisKind, Preconditioner, PressureBoundary, VariablePoisson,
};
use std::time::Instant;

fn main() {
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let sizes = if sizes.is_empty() {
        vec![32, 64, 128]
    } else {
        sizes
    };
    use PressureBoundary::*;
    let walls = AxisKind::Bounded {
        low: Neumann,
        high: Neumann,
    };
    let axes = [
        walls,
        AxisKind::Bounded {
            low: Neumann,
            high: Dirichlet,
        },
        AxisKind::Periodic,
    ];
    println!("| n | case | spectral iterations | spectral s/solve | multigrid iterations | multigrid s/solve |");
    println!("|---|---|---|---|---|---|");
    for &size in &sizes {
        let n = [size; 3];
        let h = [1.0 / size as f64; 3];
        let len = size * size * size;
        for case in ["smooth", "bed", "jump"] {
            let cells = comparison_beta(case, n, 3);
            let mut next = seeded_uniform(5);
            let f: Vec<f64> = (0..len).map(|_| next() - 0.5).collect();
            let mut row = format!("| {size}³ | {case} |");
            for kind in [Preconditioner::Spectral, Preconditioner::Multigrid] {
                let mut solver = VariablePoisson::with_preconditioner(n, h, axes, kind);
                solver.set_beta_harmonic(&cells);
                let mut p = vec![0.0; len];
                // One untimed solve to warm caches and the thread pool.
                solver.solve(&f, &mut p, 1e-10, 5000);
                let repeats = if size <= 32 { 5 } else { 1 };
                let start = Instant::now();
                let mut report = None;
                for _ in 0..repeats {
                    p.iter_mut().for_each(|x| *x = 0.0);
                    report = Some(solver.solve(&f, &mut p, 1e-10, 5000));
                }
                let seconds = start.elapsed().as_secs_f64() / repeats as f64;
                let report = report.expect("at least one solve");
                assert!(report.converged, "{kind:?} {case} {size}: {report:?}");
                row += &format!(" {} | {:.3} |", report.iterations, seconds);
            }
            println!("{row}");
        }
    }
}
