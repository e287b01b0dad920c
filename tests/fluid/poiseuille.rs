//! Plane Poiseuille flow between no-slip walls: steady profile against the parabola.

use fsim::fluid::{
    BoundaryConditions, FaceCondition, FluidSettings, FluidSolver, MeanVelocityForce, TimeScheme,
};
use fsim::grid::Grid;

const H: f64 = 1.0;
const NY: usize = 16;

/// Channel periodic in x (4 cells), walls at y = 0 and y = H (16 cells), one empty cell in z.
fn channel(nu: f64, body_force: [f64; 3], scheme: TimeScheme) -> FluidSolver {
    let h = H / NY as f64;
    let grid = Grid::new([4, NY, 1], [h, h, h], [0.0; 3]);
    let wall = FaceCondition::Wall { velocity: [0.0; 3] };
    let bc = BoundaryConditions {
        faces: [
            FaceCondition::Periodic,
            FaceCondition::Periodic,
            wall.clone(),
            wall,
            FaceCondition::Empty,
            FaceCondition::Empty,
        ],
    };
    FluidSolver::new(
        grid,
        bc,
        FluidSettings {
            nu,
            scheme,
            body_force,
            convection: true,
        },
    )
    .unwrap()
}

/// Max over the u samples of |u − u_exact| / u_exact(centre), and the worst divergence seen.
fn profile_error(s: &FluidSolver, exact: impl Fn(f64) -> f64) -> f64 {
    let l = s.layout();
    let h = s.grid().h[1];
    let centre = exact(0.5 * H);
    let mut err: f64 = 0.0;
    for j in 1..=NY {
        let y = (j as f64 - 0.5) * h;
        for i in 1..=4 {
            err = worst(
                err,
                (s.velocity()[0][l.index(i, j, 1)] - exact(y)).abs() / centre,
            );
        }
    }
    err
}

fn run_to(s: &mut FluidSolver, t_end: f64) -> f64 {
    let dt = 0.9 * s.stability_bound();
    let steps = (t_end / dt).ceil() as usize;
    let dt = t_end / steps as f64;
    let mut div: f64 = 0.0;
    for _ in 0..steps {
        s.step(dt);
        div = worst(div, s.diagnostics(dt).divergence);
    }
    div
}

#[test]
fn poiseuille_profile_driven_by_body_force_within_half_percent() {
    // u(y) = g y (H − y) / (2ν); steady after a few H²/ν.
    let (nu, g) = (0.1, 1.0);
    for scheme in [TimeScheme::Euler, TimeScheme::RK3] {
        let mut s = channel(nu, [g, 0.0, 0.0], scheme);
        let div = run_to(&mut s, 2.5 * H * H / nu);
        let err = profile_error(&s, |y| g * y * (H - y) / (2.0 * nu));
        eprintln!("Poiseuille (body force, 16 cells, {}): max profile error {:.3}% of centre velocity, divergence {div:.1e}", scheme.name(), 100.0 * err);
        assert!(err < 0.005, "{scheme:?}: profile error {err:e}");
        assert!(div < 1e-10, "divergence {div:e}");
    }
}

#[test]
fn poiseuille_driven_by_mean_velocity_force_reaches_bulk_velocity_and_parabola() {
    // meanVelocityForce holds U_b = 1; the steady profile is 6 U_b y(H − y)/H² and the
    // gradient that sustains it 12 ν U_b / H².
    let (nu, ubar) = (0.1, 1.0);
    let mut s = channel(nu, [0.0; 3], TimeScheme::RK3);
    s.set_mean_velocity_force(Some(MeanVelocityForce::new(0, ubar, 1.0)))
        .unwrap();
    let div = run_to(&mut s, 2.5 * H * H / nu);
    let bulk = s.mean_component(0);
    let err = profile_error(&s, |y| 6.0 * ubar * y * (H - y) / (H * H));
    let gradient = s.mean_velocity_force().unwrap().gradient;
    let exact_gradient = 12.0 * nu * ubar / (H * H);
    eprintln!(
        "Poiseuille (meanVelocityForce, 16 cells): bulk {bulk:.12}, profile error {:.3}%, gradient {gradient:.6} vs {exact_gradient:.6}, divergence {div:.1e}",
        100.0 * err
    );
    assert!((bulk - ubar).abs() < 1e-12, "bulk velocity {bulk}");
    assert!(err < 0.005, "profile error {err:e}");
    // Discretely the gradient is 2νU_b / (H²/6 + h²/4): 0.6% below the continuum at 16 cells.
    assert!(
        (gradient / exact_gradient - 1.0).abs() < 0.01,
        "gradient {gradient}"
    );
    assert!(div < 1e-10, "divergence {div:e}");
}

#[test]
fn channel_with_inlet_and_outlet_develops_the_parabola_and_its_pressure_drop() {
    // Uniform inflow U at x = 0, fixed pressure 0 at x = 4H, no-slip walls; Re = UH/ν = 10,
    // so the entry length (≈ 0.05 Re H + 0.6 H) is well inside the channel.
    let (nu, u_in) = (0.1, 1.0);
    let h = H / NY as f64;
    let nx = 4 * NY;
    let grid = Grid::new([nx, NY, 1], [h, h, h], [0.0; 3]);
    let wall = FaceCondition::Wall { velocity: [0.0; 3] };
    let bc = BoundaryConditions {
        faces: [
            FaceCondition::Inlet {
                velocity: [u_in, 0.0, 0.0],
            },
            FaceCondition::Outlet { pressure: 0.0 },
            wall.clone(),
            wall,
            FaceCondition::Empty,
            FaceCondition::Empty,
        ],
    };
    let mut s = FluidSolver::new(
        grid,
        bc,
        FluidSettings {
            nu,
            scheme: TimeScheme::RK3,
            body_force: [0.0; 3],
            convection: true,
        },
    )
    .unwrap();
    let div = run_to(&mut s, 15.0);
    let l = s.layout().clone();
    // Mass: what leaves through the outlet face is what enters.
    let outflow: f64 = (1..=NY)
        .map(|j| s.velocity()[0][l.index(nx + 1, j, 1)] * h)
        .sum();
    // Developed profile at x = 3H (face slot 3 NY + 1).
    let mut err: f64 = 0.0;
    for j in 1..=NY {
        let y = (j as f64 - 0.5) * h;
        let exact = 6.0 * u_in * y * (H - y) / (H * H);
        err = worst(
            err,
            (s.velocity()[0][l.index(3 * NY + 1, j, 1)] - exact).abs() / (1.5 * u_in),
        );
    }
    // Pressure gradient between the cell centres at x ≈ 2.5H and 3.5H, mid-channel.
    let p = s.pressure();
    let g = s.grid();
    let (i0, i1) = (5 * NY / 2, 7 * NY / 2);
    let jm = NY / 2;
    let dpdx = (p[g.cell_index(i1, jm, 0)] - p[g.cell_index(i0, jm, 0)]) / ((i1 - i0) as f64 * h);
    let exact = -12.0 * nu * u_in / (H * H);
    eprintln!(
        "channel inlet/outlet: outflow {outflow:.15} (inflow {}), developed profile error {:.3}%, dp/dx {dpdx:.5} vs {exact:.5}, divergence {div:.1e}",
        u_in * H,
        100.0 * err
    );
    assert!((outflow - u_in * H).abs() < 1e-12, "outflow {outflow}");
    assert!(err < 0.01, "profile error {err}");
    assert!((dpdx / exact - 1.0).abs() < 0.02, "dp/dx {dpdx}");
    assert!(div < 1e-10, "divergence {div:e}");
}

#[test]
fn fluid_at_rest_under_gravity_stays_at_rest_with_hydrostatic_pressure() {
    // Closed box, gravity along −y: the projection must balance g exactly, leaving p = g·x.
    let n = [6, 10, 4];
    let h = [0.1, 0.05, 0.2];
    let grid = Grid::new(n, h, [0.0; 3]);
    let wall = FaceCondition::Wall { velocity: [0.0; 3] };
    let bc = BoundaryConditions {
        faces: std::array::from_fn(|_| wall.clone()),
    };
    let g = [0.0, -9.81, 0.0];
    for scheme in TimeScheme::ALL {
        let mut s = FluidSolver::new(
            grid.clone(),
            bc.clone(),
            FluidSettings {
                nu: 1e-3,
                scheme,
                body_force: g,
                convection: true,
            },
        )
        .unwrap();
        for _ in 0..20 {
            s.step(1e-3);
        }
        let speed = s.diagnostics(1e-3).max_speed;
        let p = s.pressure();
        let mut slope_err: f64 = 0.0;
        for k in 0..n[2] {
            for j in 1..n[1] {
                for i in 0..n[0] {
                    let dp = (p[grid.cell_index(i, j, k)] - p[grid.cell_index(i, j - 1, k)]) / h[1];
                    slope_err = worst(slope_err, (dp - g[1]).abs());
                }
            }
        }
        eprintln!(
            "{} at rest under gravity: max speed {:.1e}, hydrostatic slope error {slope_err:.1e}",
            scheme.name(),
            speed[1]
        );
        assert!(
            speed.iter().all(|&v| v < 1e-12),
            "{scheme:?}: speeds {speed:?}"
        );
        assert!(slope_err < 1e-10, "{scheme:?}: slope error {slope_err}");
    }
}

/// Larger of two errors, NaN if either is (`f64::max` would drop a NaN).
fn worst(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}
