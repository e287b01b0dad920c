//! The semi-implicit schemes (RK3 or Euler advection, Crank–Nicolson diffusion: `RK3CN`,
//! `EulerCN`): accuracy in time, and steps far above the explicit viscous limit.

mod support;

use fsim::fluid::{BoundaryConditions, FaceCondition, FluidSettings, FluidSolver, TimeScheme};
use fsim::grid::Grid;
use std::f64::consts::PI;
use support::wall_channel;

fn periodic_square_with(n: usize, nu: f64, scheme: TimeScheme) -> FluidSolver {
    let h = 2.0 * PI / n as f64;
    let grid = Grid::new([n, n, 1], [h; 3], [0.0; 3]);
    let settings = FluidSettings {
        nu,
        scheme,
        body_force: [0.0; 3],
    };
    FluidSolver::new(grid, BoundaryConditions::periodic(), settings).unwrap()
}

/// Max error against the semi-discrete solution of a tiny (linear) Taylor–Green vortex,
/// `u = A sin x cos y e^{−ν λ_h t}` with `λ_h = 2 (4/h²) sin²(h/2)` the discrete Laplacian's
/// eigenvalue, so only the time error remains.
fn linear_taylor_green_time_error(dt: f64) -> f64 {
    linear_taylor_green_time_error_with(dt, TimeScheme::RK3CN)
}

fn linear_taylor_green_time_error_with(dt: f64, scheme: TimeScheme) -> f64 {
    let (n, nu, amp, t_end) = (16, 1.0, 1e-6, 1.0);
    let mut s = periodic_square_with(n, nu, scheme);
    s.set_velocity(|c, x| match c {
        0 => amp * x[0].sin() * x[1].cos(),
        1 => -amp * x[0].cos() * x[1].sin(),
        _ => 0.0,
    });
    let steps = (t_end / dt).round() as usize;
    for _ in 0..steps {
        s.step(dt);
    }
    let h = s.grid().h[0];
    let lambda = 2.0 * 4.0 / (h * h) * (0.5 * h).sin().powi(2);
    let decay = (-nu * lambda * t_end).exp();
    let l = s.layout().clone();
    let mut err: f64 = 0.0;
    for j in 1..=n {
        for i in 1..=n {
            let (x, y) = ((i as f64 - 1.0) * h, (j as f64 - 0.5) * h);
            let e = s.velocity()[0][l.index(i, j, 1)] - amp * x.sin() * y.cos() * decay;
            err = worst(err, e.abs() / amp);
        }
    }
    assert!(s.diagnostics(dt).divergence < 1e-10);
    err
}

#[test]
fn rk3cn_is_second_order_in_time() {
    let e: Vec<f64> = [0.1, 0.05, 0.025]
        .iter()
        .map(|&dt| linear_taylor_green_time_error(dt))
        .collect();
    let order = [(e[0] / e[1]).log2(), (e[1] / e[2]).log2()];
    eprintln!("RK3CN linear Taylor–Green time errors (Δt = 0.1, 0.05, 0.025): {:.3e} {:.3e} {:.3e}; orders {:.3} {:.3}", e[0], e[1], e[2], order[0], order[1]);
    assert!(order[0] >= 1.9 && order[1] >= 1.9, "orders {order:?}");
}

/// `EulerCN` (Euler advection, Crank–Nicolson diffusion, one stage): on the linear vortex
/// only its Crank–Nicolson part acts, second order; the full scheme is first order through
/// its explicit Euler advection (the paper's). Δt = 0.1 is twice RK3's viscous bound here
/// (ν Δt/h² = 0.65).
#[test]
fn euler_cn_is_stable_beyond_the_viscous_limit_and_converges_in_time() {
    let e: Vec<f64> = [0.1, 0.05, 0.025]
        .iter()
        .map(|&dt| linear_taylor_green_time_error_with(dt, TimeScheme::EulerCN))
        .collect();
    let order = [(e[0] / e[1]).log2(), (e[1] / e[2]).log2()];
    eprintln!("EulerCN linear Taylor–Green time errors (Δt = 0.1, 0.05, 0.025): {:.3e} {:.3e} {:.3e}; orders {:.3} {:.3}", e[0], e[1], e[2], order[0], order[1]);
    assert!(order[0] >= 1.9 && order[1] >= 1.9, "orders {order:?}");
    assert!(e[0] < 0.05, "error {}", e[0]);
}

#[test]
fn rk3cn_decays_taylor_green_at_exact_rate_beyond_the_explicit_viscous_limit() {
    for scheme in [TimeScheme::RK3CN, TimeScheme::EulerCN] {
        taylor_green_decay_beyond_the_viscous_limit(scheme);
    }
}

fn taylor_green_decay_beyond_the_viscous_limit(scheme: TimeScheme) {
    let (n, nu, t_end) = (64, 0.1, 2.5);
    let mut s = periodic_square_with(n, nu, scheme);
    s.set_velocity(|c, x| match c {
        0 => x[0].sin() * x[1].cos(),
        1 => -x[0].cos() * x[1].sin(),
        _ => 0.0,
    });
    let h = s.grid().h;
    let explicit = TimeScheme::RK3.stability_bound(nu, h, [true, true, false], [1.0, 1.0, 0.0]);
    let dt_target = 0.9 * s.stability_bound();
    let steps = (t_end / dt_target).ceil() as usize;
    let dt = t_end / steps as f64;
    let e0 = s.diagnostics(0.0).kinetic_energy;
    let mut div: f64 = 0.0;
    for _ in 0..steps {
        s.step(dt);
        div = worst(div, s.diagnostics(dt).divergence);
    }
    let rate = -(s.diagnostics(0.0).kinetic_energy / e0).ln() / t_end;
    let rel = (rate / (4.0 * nu) - 1.0).abs();
    eprintln!("{} Taylor–Green 64²: Δt = {dt:.4} = {:.2} × the explicit RK3 bound, KE decay-rate error {rel:.2e}, divergence {div:.1e}", scheme.name(), dt / explicit);
    assert!(dt > 2.0 * explicit);
    assert!(rel < 0.01, "decay-rate error {rel}");
    assert!(div < 1e-10);
}

/// The wall channel on `RK3CN`.
fn channel(lid: f64, nu: f64, g: f64) -> FluidSolver {
    wall_channel(lid, nu, g, TimeScheme::RK3CN)
}

#[test]
fn rk3cn_reaches_couette_and_poiseuille_with_huge_steps() {
    let nu = 0.1;
    let h: f64 = 1.0 / 16.0;
    let explicit = h * h / (4.0 * nu);
    // Couette: u = U y / H is exact on the grid (the wall ghost extrapolation is linear).
    let mut s = channel(1.0, nu, 0.0);
    let dt = 0.25; // no advection in these flows: only the steady state matters
    for _ in 0..400 {
        s.step(dt);
    }
    let l = s.layout().clone();
    let couette = (1..=16)
        .map(|j| (s.velocity()[0][l.index(2, j, 1)] - (j as f64 - 0.5) * h).abs())
        .fold(0.0, worst);
    // Poiseuille: the 0.39 % discretisation error of the body-force channel, as explicit.
    let g = 1.0;
    let mut p = channel(0.0, nu, g);
    for _ in 0..400 {
        p.step(dt);
    }
    let centre = g / (8.0 * nu);
    let poiseuille = (1..=16)
        .map(|j| {
            let y = (j as f64 - 0.5) * h;
            (p.velocity()[0][l.index(2, j, 1)] - g * y * (1.0 - y) / (2.0 * nu)).abs() / centre
        })
        .fold(0.0, worst);
    eprintln!(
        "RK3CN channel at Δt = {:.0} × the explicit viscous bound: Couette max error {couette:.1e}, Poiseuille profile error {:.3}%",
        dt / explicit,
        100.0 * poiseuille
    );
    assert!(couette < 1e-10, "Couette error {couette}");
    assert!(poiseuille < 0.005, "Poiseuille error {poiseuille}");
}

#[test]
fn rk3cn_rejects_outlets() {
    let grid = Grid::new([8, 8, 1], [1.0; 3], [0.0; 3]);
    let mut bc = BoundaryConditions::periodic();
    bc.faces[0] = FaceCondition::Inlet {
        velocity: [1.0, 0.0, 0.0],
    };
    bc.faces[1] = FaceCondition::Outlet { pressure: 0.0 };
    let r = FluidSolver::new(
        grid,
        bc,
        FluidSettings {
            nu: 1.0,
            scheme: TimeScheme::RK3CN,
            body_force: [0.0; 3],
        },
    );
    assert!(r.err().unwrap().contains("outlets"));
}

/// Larger of two errors, NaN if either is (`f64::max` would drop a NaN).
fn worst(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}
