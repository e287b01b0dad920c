//! `EulerRKC`: explicit Euler advection, diffusion by damped Runge–Kutta–Chebyshev stages,
//! one incremental projection per step (`src/fluid/chebyshev_stages.rs`). Each mode of the
//! diffusion decays by the stability polynomial; first order in time; steady states do not
//! depend on the step; steps far above the explicit viscous bound.

use crate::support::wall_channel;
use fsim::fluid::{
    BoundaryConditions, ChebyshevStages, FaceCondition, FluidSettings, FluidSolver, TimeScheme,
};
use fsim::grid::Grid;
use std::f64::consts::PI;

fn periodic_square(n: usize, nu: f64) -> FluidSolver {
    let h = 2.0 * PI / n as f64;
    let grid = Grid::new([n, n, 1], [h; 3], [0.0; 3]);
    let settings = FluidSettings {
        nu,
        scheme: TimeScheme::EulerRKC,
        body_force: [0.0; 3],
        convection: true,
    };
    FluidSolver::new(grid, BoundaryConditions::periodic(), settings).unwrap()
}

/// A tiny (linear) Taylor–Green vortex `u = A sin x cos y` on `n²` cells, ν = 1.
fn linear_vortex(n: usize) -> FluidSolver {
    let amp = 1e-6;
    let mut s = periodic_square(n, 1.0);
    s.set_velocity(|c, x| match c {
        0 => amp * x[0].sin() * x[1].cos(),
        1 => -amp * x[0].cos() * x[1].sin(),
        _ => 0.0,
    });
    s
}

/// The discrete Laplacian's eigenvalue of the vortex, `λ_h = 2 (4/h²) sin²(h/2)`, and the
/// spectral radius `4ν Σ 1/h²` (2-D) the stage count follows.
fn eigenvalues(s: &FluidSolver) -> (f64, f64) {
    let h = s.grid().h[0];
    let nu = s.settings().nu;
    (
        2.0 * 4.0 / (h * h) * (0.5 * h).sin().powi(2),
        4.0 * nu * 2.0 / (h * h),
    )
}

/// Component x at face (i, j) of the vortex's layout.
fn sample(s: &FluidSolver, i: usize, j: usize) -> f64 {
    s.velocity()[0][s.layout().index(i, j, 1)]
}

/// At 1, 5 and 30 times the explicit Euler bound the vortex decays per step by exactly the
/// stability polynomial of the stages the step took, `P_s(−Δt ν λ_h)` (to the vortex's own
/// nonlinearity, 1e-6), and the stage count is the fewest whose reach covers the step.
#[test]
fn each_mode_decays_by_the_stability_polynomial() {
    for factor in [1.0, 5.0, 30.0] {
        let mut s = linear_vortex(16);
        let (lambda, radius) = eigenvalues(&s);
        let dt = factor * 2.0 / radius;
        let method = ChebyshevStages::for_step(dt * radius);
        let expected = method.amplification(-dt * lambda);
        for step in 0..5 {
            let before = sample(&s, 3, 5);
            s.step(dt);
            let ratio = sample(&s, 3, 5) / before;
            assert_eq!(s.chebyshev_stages_taken(), method.count);
            assert!(
                (ratio / expected - 1.0).abs() < 1e-5,
                "{factor} x the bound, step {step}: decay {ratio} against P = {expected}"
            );
        }
        eprintln!(
            "EulerRKC at {factor} x the explicit bound: {} stages, decay {expected:.6} per step",
            method.count
        );
        assert!(s.diagnostics(dt).divergence < 1e-10);
    }
}

/// Against the exact decay `e^{−ν λ_h t}` the error is first order in Δt (the stages are
/// consistent to first order: `P(z) = 1 + z + c_s z² + …`). On 64² cells the three steps
/// take 7, 5 and 4 stages (Δt = 0.1 is 42 times the explicit Euler bound), whose error
/// constants `½ − c_s` are within 2 % of each other (on a coarse grid one or two stages, with
/// constants 0.5 and 0.375, blur the observed order).
#[test]
fn converges_at_first_order_in_time() {
    let errors: Vec<f64> = [0.1, 0.05, 0.025]
        .iter()
        .map(|&dt| {
            let mut s = linear_vortex(64);
            let (lambda, _) = eigenvalues(&s);
            let t_end: f64 = 1.0;
            let steps = (t_end / dt).round() as usize;
            let start = sample(&s, 9, 21);
            for _ in 0..steps {
                s.step(dt);
            }
            (sample(&s, 9, 21) / start / (-lambda * t_end).exp() - 1.0).abs()
        })
        .collect();
    let order = [
        (errors[0] / errors[1]).log2(),
        (errors[1] / errors[2]).log2(),
    ];
    eprintln!(
        "EulerRKC linear Taylor–Green errors (Δt = 0.1, 0.05, 0.025): {:.3e} {:.3e} {:.3e}; \
         orders {:.3} {:.3}",
        errors[0], errors[1], errors[2], order[0], order[1]
    );
    assert!(
        order.iter().all(|&o| (0.95..1.1).contains(&o)),
        "orders {order:?}"
    );
}

fn profile(s: &FluidSolver) -> Vec<f64> {
    (1..=16)
        .map(|j| s.velocity()[0][s.layout().index(2, j, 1)])
        .collect()
}

/// Couette and Poiseuille flow at 25 times the explicit viscous bound (6 stages): Couette is
/// exact on the grid, and the Poiseuille profile is the steady discrete one, the same as
/// `RK3`'s at its own bound to round-off (the steady state does not depend on the scheme or
/// the step), with the body-force channel's 0.39 % discretisation error.
#[test]
fn walls_reach_couette_and_poiseuille_at_huge_steps() {
    let (nu, h) = (0.1, 1.0 / 16.0);
    let explicit = h * h / (4.0 * nu);
    let dt = 0.25;
    const STEPS: usize = 1600;
    let run = |lid: f64, g: f64, scheme: TimeScheme| {
        let mut s = wall_channel(lid, nu, g, scheme);
        // RK3 at 0.9 of its own bound to t = 40, where the slowest mode has decayed by
        // e^{−νπ²t} = 10⁻¹⁷
        let (dt, steps) = match scheme {
            TimeScheme::EulerRKC => (dt, STEPS),
            _ => {
                let step = 0.9 * s.stability_bound();
                (step, (40.0 / step).ceil() as usize)
            }
        };
        for _ in 0..steps {
            s.step(dt);
        }
        s
    };
    let couette = profile(&run(1.0, 0.0, TimeScheme::EulerRKC))
        .iter()
        .enumerate()
        .map(|(j, u)| (u - (j as f64 + 0.5) * h).abs())
        .fold(0.0, f64::max);
    let g = 1.0;
    let rkc = run(0.0, g, TimeScheme::EulerRKC);
    let stages = rkc.chebyshev_stages_taken();
    let (p, reference) = (profile(&rkc), profile(&run(0.0, g, TimeScheme::RK3)));
    let centre = g / (8.0 * nu);
    let mut poiseuille: f64 = 0.0;
    let mut against_rk3: f64 = 0.0;
    for j in 0..16 {
        let y = (j as f64 + 0.5) * h;
        poiseuille = poiseuille.max((p[j] - g * y * (1.0 - y) / (2.0 * nu)).abs() / centre);
        against_rk3 = against_rk3.max((p[j] - reference[j]).abs() / centre);
    }
    eprintln!(
        "EulerRKC channel at Δt = {:.0} × the explicit viscous bound ({stages} stages): Couette \
         max error {couette:.1e}, Poiseuille profile error {:.3} %, against RK3 {against_rk3:.1e}",
        dt / explicit,
        100.0 * poiseuille
    );
    assert!(stages >= 5, "{stages} stages");
    assert!(couette < 1e-10, "Couette error {couette}");
    assert!(poiseuille < 0.005, "Poiseuille error {poiseuille}");
    assert!(against_rk3 < 1e-10, "against RK3 {against_rk3}");
}

/// The nonlinear Taylor–Green vortex (64², ν = 0.1) at 0.9 times the scheme's own bound
/// (the advective `2ν/|v|²`, here 3 times RK3's viscous bound) stays divergence-free and
/// decays at the rate its stages predict, `−ln P_s(−Δt ν λ_h)² / Δt`, within 1 %; the
/// continuous rate `4ν` differs from it by the first-order error.
#[test]
fn taylor_green_decays_at_the_predicted_rate_far_beyond_the_viscous_bound() {
    let (n, nu, t_end) = (64, 0.1, 2.5);
    let mut s = periodic_square(n, nu);
    s.set_velocity(|c, x| match c {
        0 => x[0].sin() * x[1].cos(),
        1 => -x[0].cos() * x[1].sin(),
        _ => 0.0,
    });
    let h = s.grid().h;
    let rk3 = TimeScheme::RK3.stability_bound(nu, h, [true, true, false], [1.0, 1.0, 0.0]);
    let steps = (t_end / (0.9 * s.stability_bound())).ceil() as usize;
    let dt = t_end / steps as f64;
    let (lambda, radius) = eigenvalues(&s);
    let predicted = -(ChebyshevStages::for_step(dt * radius)
        .amplification(-dt * nu * lambda)
        .powi(2))
    .ln()
        / dt;
    let e0 = s.diagnostics(0.0).kinetic_energy;
    let mut div: f64 = 0.0;
    for _ in 0..steps {
        s.step(dt);
        div = div.max(s.diagnostics(dt).divergence);
    }
    let rate = -(s.diagnostics(0.0).kinetic_energy / e0).ln() / t_end;
    eprintln!(
        "EulerRKC Taylor–Green 64²: Δt = {dt:.4} = {:.1} × RK3's bound, {} stages, decay rate \
         {rate:.5}, predicted {predicted:.5}, continuous {:.5}, divergence {div:.1e}",
        dt / rk3,
        s.chebyshev_stages_taken(),
        4.0 * nu
    );
    assert!(dt > 2.5 * rk3);
    assert!(
        (rate / predicted - 1.0).abs() < 0.01,
        "rate {rate} vs {predicted}"
    );
    assert!(div < 1e-10);
}

#[test]
fn rejects_outlets() {
    let grid = Grid::new([8, 8, 1], [1.0; 3], [0.0; 3]);
    let mut bc = BoundaryConditions::periodic();
    bc.faces[0] = FaceCondition::Inlet {
        velocity: [1.0, 0.0, 0.0],
    };
    bc.faces[1] = FaceCondition::Outlet { pressure: 0.0 };
    let settings = FluidSettings {
        nu: 1.0,
        scheme: TimeScheme::EulerRKC,
        body_force: [0.0; 3],
        convection: true,
    };
    let error = FluidSolver::new(grid, bc, settings).err().unwrap();
    assert!(error.contains("outlets"), "{error}");
}

/// The stages do not couple the components, so a step takes each component through all its
/// stages in turn (its arrays stay in the cache) and hands the hook one component a call;
/// the mass source comes in one last call that hands no component, after every stage.
#[test]
fn the_hook_gets_each_component_through_its_stages_then_the_mass_source() {
    let grid = Grid::new([8, 8, 8], [0.1; 3], [0.0; 3]);
    let settings = FluidSettings {
        nu: 1.0,
        scheme: TimeScheme::EulerRKC,
        body_force: [0.0; 3],
        convection: true,
    };
    let mut s = FluidSolver::new(grid, BoundaryConditions::periodic(), settings).unwrap();
    s.set_velocity(|c, x| (x[(c + 1) % 3] * 5.0).sin());
    s.mass_source_mut();
    let dt = 20.0 * 0.01 / 6.0; // 20 times the explicit bound h²/(6ν)
    let mut calls = Vec::new();
    s.step_with(dt, &mut |stage| {
        calls.push((stage.components, stage.mass_source.is_some()));
    });
    let stages = s.chebyshev_stages_taken();
    assert!(stages > 1, "{stages} stages");
    let mut expected: Vec<([bool; 3], bool)> = (0..3)
        .flat_map(|c| std::iter::repeat_n((std::array::from_fn(|d| d == c), false), stages))
        .collect();
    expected.push(([false; 3], true));
    assert_eq!(calls, expected);
}
