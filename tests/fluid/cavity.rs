//! Lid-driven cavity at Re = 100 against Ghia, Ghia & Shin (1982).
//!
//! Reference values: U. Ghia, K. N. Ghia, C. T. Shin, "High-Re solutions for incompressible
//! flow using the Navier–Stokes equations and a multigrid method", J. Comput. Phys. 48,
//! 387–411 (1982), Table I (u on the vertical centre-line) and Table II (v on the horizontal
//! centre-line), Re = 100 column.

use fsim::fluid::{BoundaryConditions, FaceCondition, FluidSettings, FluidSolver, TimeScheme};
use fsim::grid::Grid;

const GHIA_Y: [f64; 17] = [
    1.0000, 0.9766, 0.9688, 0.9609, 0.9531, 0.8516, 0.7344, 0.6172, 0.5000, 0.4531, 0.2813, 0.1719,
    0.1016, 0.0703, 0.0625, 0.0547, 0.0000,
];
const GHIA_U: [f64; 17] = [
    1.00000, 0.84123, 0.78871, 0.73722, 0.68717, 0.23151, 0.00332, -0.13641, -0.20581, -0.21090,
    -0.15662, -0.10150, -0.06434, -0.04775, -0.04192, -0.03717, 0.00000,
];
const GHIA_X: [f64; 17] = [
    1.0000, 0.9688, 0.9609, 0.9531, 0.9453, 0.9063, 0.8594, 0.8047, 0.5000, 0.2344, 0.2266, 0.1563,
    0.0938, 0.0781, 0.0703, 0.0625, 0.0000,
];
const GHIA_V: [f64; 17] = [
    0.00000, -0.05906, -0.07391, -0.08864, -0.10313, -0.16914, -0.22445, -0.24533, 0.05454,
    0.17527, 0.17507, 0.16077, 0.12317, 0.10890, 0.10091, 0.09233, 0.00000,
];

/// Cubic (4-point Lagrange) interpolation of samples `(pos, val)` sorted by position.
fn interpolate(pos: &[f64], val: &[f64], x: f64) -> f64 {
    let m = pos.len();
    let mut i = pos.partition_point(|&p| p < x).clamp(1, m - 1);
    // Stencil of 4 points around the interval [i−1, i].
    i = i.saturating_sub(2).min(m - 4);
    let mut sum = 0.0;
    for a in i..i + 4 {
        let mut w = 1.0;
        for b in i..i + 4 {
            if a != b {
                w *= (x - pos[b]) / (pos[a] - pos[b]);
            }
        }
        sum += w * val[a];
    }
    sum
}

#[test]
fn cavity_re100_centre_lines_match_ghia_within_two_percent() {
    cavity(TimeScheme::RK3, 0.5);
}

#[test]
fn cavity_re100_explicit_euler_matches_ghia_within_two_percent() {
    cavity(TimeScheme::Euler, 0.5);
}

#[test]
fn cavity_re100_chebyshev_matches_ghia_within_two_percent() {
    cavity(TimeScheme::EulerRKC, 1.0);
}

/// Runs the cavity to t = 30 (steady) with adaptive Δt at Courant number `max_co`, and
/// compares both centre-lines with Ghia et al.; error measure: max |diff| over Ghia's points
/// divided by the lid speed.
fn cavity(scheme: TimeScheme, max_co: f64) {
    let n = 64;
    let lid = 1.0;
    let nu = 0.01; // Re = U L / ν = 100
    let h = 1.0 / n as f64;
    let grid = Grid::new([n, n, 1], [h, h, h], [0.0; 3]);
    let wall = FaceCondition::Wall { velocity: [0.0; 3] };
    let bc = BoundaryConditions {
        faces: [
            wall.clone(),
            wall.clone(),
            wall,
            FaceCondition::Wall {
                velocity: [lid, 0.0, 0.0],
            },
            FaceCondition::Empty,
            FaceCondition::Empty,
        ],
    };
    let settings = FluidSettings {
        nu,
        scheme,
        body_force: [0.0; 3],
        convection: true,
    };
    let mut s = FluidSolver::new(grid, bc, settings).unwrap();
    let mut t = 0.0;
    let mut dt = 1e-3;
    let mut div: f64 = 0.0;
    while t < 30.0 {
        dt = s.adaptive_dt(dt, max_co, 1.0);
        s.step(dt);
        t += dt;
        div = worst(div, s.diagnostics(dt).divergence);
    }
    let l = s.layout().clone();
    // u on x = 0.5 (face slot n/2 + 1), with the wall values at y = 0 and y = 1.
    let mut y = vec![0.0];
    let mut u = vec![0.0];
    for j in 1..=n {
        y.push((j as f64 - 0.5) * h);
        u.push(s.velocity()[0][l.index(n / 2 + 1, j, 1)]);
    }
    y.push(1.0);
    u.push(lid);
    let mut x = vec![0.0];
    let mut v = vec![0.0];
    for i in 1..=n {
        x.push((i as f64 - 0.5) * h);
        v.push(s.velocity()[1][l.index(i, n / 2 + 1, 1)]);
    }
    x.push(1.0);
    v.push(0.0);
    assert!(
        u.iter().chain(&v).all(|x| x.is_finite()),
        "{scheme:?} blew up"
    );
    let err_u = GHIA_Y
        .iter()
        .zip(GHIA_U)
        .map(|(&yy, g)| (interpolate(&y, &u, yy) - g).abs())
        .fold(0.0, worst)
        / lid;
    let err_v = GHIA_X
        .iter()
        .zip(GHIA_V)
        .map(|(&xx, g)| (interpolate(&x, &v, xx) - g).abs())
        .fold(0.0, worst)
        / lid;
    eprintln!(
        "cavity Re=100 64×64 {} (t = {t:.1}): max |u − Ghia| / U = {:.3}%, max |v − Ghia| / U = {:.3}%, divergence {div:.1e}",
        scheme.name(),
        100.0 * err_u,
        100.0 * err_v
    );
    assert!(err_u < 0.02, "u error {err_u}");
    assert!(err_v < 0.02, "v error {err_v}");
    assert!(div < 1e-10, "divergence {div:e}");
}

/// Larger of two errors, NaN if either is (`f64::max` would drop a NaN).
fn worst(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}
