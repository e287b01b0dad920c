//! Variable-coefficient pressure solve `∇·(β∇p) = f`: CG iterations and wall time per solve
//! with the spectral (constant mean-β) preconditioner against the multigrid V-cycle, on
//! smooth `β ∈ [0.4, 1]`, a packed-bed surface (β = 0.36 below mid-height, 1 above) and a
//! 100× checkerboard jump (blocks of n/4 cells), walls in x, a wall below and an outlet
//! (fixed pressure) above in y, periodic z; seeded random right-hand side, tolerance 1e-10.
//!
//! `cargo run --release --example variable_poisson_bench [-- n ...]` (default 32 64 128).

use fsim::fluid::{AxisKind, Preconditioner, PressureBoundary, VariablePoisson};
use std::f64::consts::PI;
use std::time::Instant;

/// Seeded uniform numbers in [0, 1) (64-bit LCG, high bits).
fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The three coefficient fields of the preconditioner comparison, per cell (x fastest).
fn cell_beta(case: &str, n: [usize; 3], seed: u64) -> Vec<f64> {
    let mut next = uniform(seed);
    // Four random Fourier modes of wavenumber ≤ 2 for the smooth field.
    let modes: Vec<([f64; 3], f64)> = (0..4)
        .map(|_| {
            (
                std::array::from_fn(|_| (3.0 * next()).floor()),
                2.0 * PI * next(),
            )
        })
        .collect();
    let mut beta = vec![0.0; n[0] * n[1] * n[2]];
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                let x = [
                    (i as f64 + 0.5) / n[0] as f64,
                    (j as f64 + 0.5) / n[1] as f64,
                    (k as f64 + 0.5) / n[2] as f64,
                ];
                beta[i + n[0] * (j + n[1] * k)] = match case {
                    "smooth" => {
                        let s: f64 = modes
                            .iter()
                            .map(|(q, phase)| {
                                (2.0 * PI * (q[0] * x[0] + q[1] * x[1] + q[2] * x[2]) + phase).sin()
                            })
                            .sum();
                        0.7 + 0.3 * s / 4.0
                    }
                    "bed" => {
                        if x[1] < 0.5 {
                            0.36
                        } else {
                            1.0
                        }
                    }
                    "jump" => {
                        let block = |v: f64| (v * 4.0).floor() as usize;
                        if (block(x[0]) + block(x[1]) + block(x[2])) % 2 == 1 {
                            0.01
                        } else {
                            1.0
                        }
                    }
                    _ => unreachable!(),
                };
            }
        }
    }
    beta
}

/// Face coefficients: the harmonic mean of the two cells a face joins (the cell's own
/// value on a boundary face), the series conductance across a jump.
fn set_faces(solver: &mut VariablePoisson, n: [usize; 3], cells: &[f64], axes: [AxisKind; 3]) {
    for d in 0..3 {
        let mut m = n;
        m[d] += 1;
        for k in 0..m[2] {
            for j in 0..m[1] {
                for i in 0..m[0] {
                    let idx = [i, j, k];
                    let cell = |mut c: [usize; 3], shift: isize| {
                        let v = c[d] as isize + shift;
                        c[d] = match axes[d] {
                            AxisKind::Periodic => v.rem_euclid(n[d] as isize) as usize,
                            _ => v.clamp(0, n[d] as isize - 1) as usize,
                        };
                        cells[c[0] + n[0] * (c[1] + n[1] * c[2])]
                    };
                    let lo = cell(idx, -1);
                    let hi = cell(idx, 0);
                    let fi = solver.face_index(d, i, j, k);
                    solver.beta_mut()[d][fi] = 2.0 * lo * hi / (lo + hi);
                }
            }
        }
    }
}

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
            let cells = cell_beta(case, n, 3);
            let mut next = uniform(5);
            let f: Vec<f64> = (0..len).map(|_| next() - 0.5).collect();
            let mut row = format!("| {size}³ | {case} |");
            for kind in [Preconditioner::Spectral, Preconditioner::Multigrid] {
                let mut solver = VariablePoisson::with_preconditioner(n, h, axes, kind);
                set_faces(&mut solver, n, &cells, axes);
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
