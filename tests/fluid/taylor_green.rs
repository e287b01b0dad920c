//! Taylor–Green and Beltrami vortices in a periodic box: exact decay rates and the order of
//! the velocity error.

use fsim::fluid::{BoundaryConditions, FluidSettings, FluidSolver, TimeScheme};
use fsim::grid::Grid;
use std::f64::consts::PI;

fn periodic_box(n: [usize; 3], nu: f64, scheme: TimeScheme) -> FluidSolver {
    let l = 2.0 * PI;
    let h = [l / n[0] as f64, l / n[1] as f64, l / n[2] as f64];
    let grid = Grid::new(n, h, [0.0; 3]);
    let settings = FluidSettings {
        nu,
        scheme,
        body_force: [0.0; 3],
        convection: true,
    };
    FluidSolver::new(grid, BoundaryConditions::periodic(), settings).unwrap()
}

/// 2-D Taylor–Green vortex `u = sin x cos y e^{−2νt}`, `v = −cos x sin y e^{−2νt}`: an exact
/// Navier–Stokes solution whose kinetic energy decays as `e^{−4νt}`.
fn taylor_green(c: usize, x: [f64; 3], decay: f64) -> f64 {
    match c {
        0 => x[0].sin() * x[1].cos() * decay,
        1 => -x[0].cos() * x[1].sin() * decay,
        _ => 0.0,
    }
}

/// Runs to `t_end` in equal steps no larger than `dt_max` and the stability bound.
fn run(solver: &mut FluidSolver, t_end: f64, dt_max: f64) -> f64 {
    let dt_target = dt_max.min(0.9 * solver.stability_bound());
    let steps = (t_end / dt_target).ceil() as usize;
    let dt = t_end / steps as f64;
    let mut worst_div: f64 = 0.0;
    for _ in 0..steps {
        solver.step(dt);
        worst_div = worst(worst_div, solver.diagnostics(dt).divergence);
    }
    worst_div
}

#[test]
fn taylor_green_energy_decays_at_exact_rate_on_32_cubed() {
    let nu = 0.1;
    let t_end = 2.5;
    for scheme in [TimeScheme::Euler, TimeScheme::RK3] {
        let mut s = periodic_box([32, 32, 32], nu, scheme);
        s.set_velocity(|c, x| taylor_green(c, x, 1.0));
        let e0 = s.diagnostics(0.0).kinetic_energy;
        let div = run(&mut s, t_end, 1.0);
        let e1 = s.diagnostics(0.0).kinetic_energy;
        let rate = -(e1 / e0).ln() / t_end;
        let exact = 4.0 * nu;
        let rel = (rate - exact).abs() / exact;
        eprintln!("Taylor–Green 32³ {}: KE decay rate {rate:.6} vs exact {exact:.6}, rel. error {rel:.2e}, max divergence {div:.1e}", scheme.name());
        assert!(rel < 0.01, "{scheme:?}: decay-rate error {rel:e}");
        assert!(div < 1e-10, "{scheme:?}: divergence {div:e}");
    }
}

/// The Taylor–Green vortex in `[0, π]² × one cell`, with slip walls on all four sides: the
/// vortex has zero normal velocity and zero shear there, so it stays exact; tests the slip
/// condition and the cosine-transform pressure solve.
#[test]
fn taylor_green_in_a_slip_walled_box_decays_at_exact_rate() {
    use fsim::fluid::FaceCondition;
    let (n, nu, t_end) = (32, 0.1, 2.5);
    let h = PI / n as f64;
    let grid = Grid::new([n, n, 1], [h; 3], [0.0; 3]);
    let bc = BoundaryConditions {
        faces: [
            FaceCondition::Slip,
            FaceCondition::Slip,
            FaceCondition::Slip,
            FaceCondition::Slip,
            FaceCondition::Empty,
            FaceCondition::Empty,
        ],
    };
    let settings = FluidSettings {
        nu,
        scheme: TimeScheme::RK3,
        body_force: [0.0; 3],
        convection: true,
    };
    let mut s = FluidSolver::new(grid, bc, settings).unwrap();
    s.set_velocity(|c, x| taylor_green(c, x, 1.0));
    let e0 = s.diagnostics(0.0).kinetic_energy;
    let div = run(&mut s, t_end, 1.0);
    let rate = -(s.diagnostics(0.0).kinetic_energy / e0).ln() / t_end;
    let rel = (rate / (4.0 * nu) - 1.0).abs();
    eprintln!(
        "Taylor–Green in a slip box 32²: KE decay-rate error {rel:.2e}, divergence {div:.1e}"
    );
    assert!(rel < 0.01, "decay-rate error {rel}");
    assert!(div < 1e-10, "divergence {div:e}");
}

/// ABC (Beltrami) flow `u = (sin z + cos y, sin x + cos z, sin y + cos x)`: `ω = u`, so the
/// nonlinear term is a pure gradient and the flow decays as `e^{−νt}` in all three
/// directions; a genuinely 3-D test of the advection discretisation.
#[test]
fn beltrami_flow_energy_decays_at_exact_rate_on_32_cubed() {
    let nu = 0.1;
    let t_end = 2.0;
    let mut s = periodic_box([32, 32, 32], nu, TimeScheme::RK3);
    s.set_velocity(|c, x| match c {
        0 => x[2].sin() + x[1].cos(),
        1 => x[0].sin() + x[2].cos(),
        _ => x[1].sin() + x[0].cos(),
    });
    let e0 = s.diagnostics(0.0).kinetic_energy;
    let div = run(&mut s, t_end, 1.0);
    let e1 = s.diagnostics(0.0).kinetic_energy;
    let rate = -(e1 / e0).ln() / t_end;
    let exact = 2.0 * nu;
    let rel = (rate - exact).abs() / exact;
    eprintln!("Beltrami 32³ RK3: KE decay rate {rate:.6} vs exact {exact:.6}, rel. error {rel:.2e}, max divergence {div:.1e}");
    assert!(rel < 0.01, "decay-rate error {rel:e}");
    assert!(div < 1e-10, "divergence {div:e}");
}

/// Max velocity error of the 2-D Taylor–Green vortex at `t_end` on an `n × n × 1` periodic
/// grid (2-D flow in a 3-D periodic box one cell thick), RK3 with `Δt = 0.1 h`, so the time
/// error is negligible against the spatial one.
fn taylor_green_error(n: usize, nu: f64, t_end: f64) -> f64 {
    let mut s = periodic_box([n, n, 1], nu, TimeScheme::RK3);
    s.set_velocity(|c, x| taylor_green(c, x, 1.0));
    let h = 2.0 * PI / n as f64;
    let div = run(&mut s, t_end, 0.1 * h);
    assert!(div < 1e-10, "divergence {div:e}");
    let decay = (-2.0 * nu * t_end).exp();
    let g = s.grid().clone();
    let l = s.layout().clone();
    let mut err: f64 = 0.0;
    for c in 0..2 {
        for j in 1..=n {
            for i in 1..=n {
                let idx = [i, j, 1];
                let x: [f64; 3] = std::array::from_fn(|d| {
                    (idx[d] as f64 - if d == c { 1.0 } else { 0.5 }) * g.h[d]
                });
                let e = s.velocity()[c][l.index(i, j, 1)] - taylor_green(c, x, decay);
                err = worst(err, e.abs());
            }
        }
    }
    err
}

#[test]
fn taylor_green_velocity_error_is_second_order() {
    let (nu, t_end) = (0.05, 1.0);
    let e: Vec<f64> = [16, 32, 64]
        .iter()
        .map(|&n| taylor_green_error(n, nu, t_end))
        .collect();
    let order = [(e[0] / e[1]).log2(), (e[1] / e[2]).log2()];
    eprintln!("Taylor–Green (n×n×1, RK3) max velocity errors 16/32/64: {:.3e} {:.3e} {:.3e}; observed orders {:.3} {:.3}", e[0], e[1], e[2], order[0], order[1]);
    assert!(order[0] >= 1.9 && order[1] >= 1.9, "orders {order:?}");
}

/// Larger of two errors, NaN if either is (`f64::max` would drop a NaN).
fn worst(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}
