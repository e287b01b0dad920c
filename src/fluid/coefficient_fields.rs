//! Seeded coefficient fields for the variable-coefficient pressure solvers' tests.

use std::f64::consts::PI;

/// Seeded uniform numbers in [0, 1) (64-bit LCG, high bits).
pub fn seeded_uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The three coefficient fields of the preconditioner comparison (docs/numerics.md), per cell
/// (x fastest): `"smooth"` (four random Fourier modes, β in [0.4, 1]), `"bed"` (a packed-bed
/// surface, 0.36 below, 1 above) and `"jump"` (100× checkerboard blocks), for the tests.
pub fn comparison_beta(case: &str, n: [usize; 3], seed: u64) -> Vec<f64> {
    let mut next = seeded_uniform(seed);
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
