//! The porous-media case (φ = 0.1, r/h = 8) time-stepped to steady state with the direct
//! model's hook, as `fsimFoam` runs it: K from the momentum balance and from the stress
//! integral on each alternative surface, for RK3 and for RK3CN at growing steps.
//!
//! `cargo run --release --example direct_time_stepped`

use fsim::coupling::direct::{
    stress_integral_force, DirectCoupling, DirectSettings, FieldView, Interpolation, RigidSphere,
    StressIntegral,
};
use fsim::fluid::{BoundaryConditions, FluidSettings, FluidSolver, MeanVelocityForce, TimeScheme};
use fsim::grid::Grid;
use std::f64::consts::PI;
use std::time::Instant;

fn main() {
    let (phi, n) = (0.1, 28);
    let radius = (3.0 * phi / (4.0 * PI)).cbrt();
    let h = 1.0 / n as f64;
    let sphere = RigidSphere::fixed([0.5 + 0.1 * h, 0.5 + 0.2 * h, 0.5 + 0.3 * h], radius);
    let drag = 6.0 * PI * radius;
    println!(
        "scheme,dt_over_rk3_bound,steps,seconds,K_balance,surface_offset,interpolation,K_stress"
    );
    for (scheme, factor) in [
        (TimeScheme::RK3, 0.9),
        (TimeScheme::RK3CN, 1.0),
        (TimeScheme::RK3CN, 2.0),
        (TimeScheme::RK3CN, 4.0),
        (TimeScheme::RK3CN, 10.0),
        (TimeScheme::RK3CN, 16.0),
    ] {
        let grid = Grid::new([n; 3], [h; 3], [0.0; 3]);
        let mut settings = FluidSettings::new(1.0);
        settings.scheme = TimeScheme::RK3;
        let mut fluid =
            FluidSolver::new(grid.clone(), BoundaryConditions::periodic(), settings).unwrap();
        let rk3_bound = fluid.stability_bound();
        fluid.set_scheme(scheme).unwrap();
        fluid
            .set_mean_velocity_force(Some(MeanVelocityForce::new(0, 1.0, 1.0)))
            .unwrap();
        let mut coupling = DirectCoupling::new(&mut fluid, DirectSettings::default());
        coupling.set_spheres(&[sphere], &[0]);
        if let Ok(tol) = std::env::var("TOL") {
            coupling.implicit_forcing_mut().tolerance = tol.parse().unwrap();
        }
        coupling.implicit_forcing_mut().preconditioned = std::env::var("PLAIN").is_err();
        coupling.implicit_forcing_mut().warm_start = std::env::var("COLD").is_err();
        let dt = factor * rk3_bound;
        let steps = (0.2 / dt).ceil() as usize;
        let clock = Instant::now();
        let mut solves = 0;
        let mut worst: f64 = 0.0;
        for _ in 0..steps {
            fluid.step_with(dt, &mut |stage| {
                coupling.impose(stage);
                let r = coupling.implicit_forcing_report();
                solves += r.solves;
                worst = worst.max(r.relative_residual);
            });
        }
        eprintln!(
            "{} at {factor} x the RK3 bound: {:.1} Helmholtz solves per stage, worst residual {worst:.1e}",
            scheme.name(),
            solves as f64 / (3 * steps) as f64
        );
        let seconds = clock.elapsed().as_secs_f64();
        let g = fluid.mean_velocity_force().unwrap().gradient;
        let view = FieldView::of(&fluid);
        for offset in [0.0, 1.0, 2.0, 3.0] {
            for interpolation in [Interpolation::Linear, Interpolation::Cubic] {
                let integral = StressIntegral {
                    surface_offset: offset,
                    interpolation,
                    ..StressIntegral::default()
                };
                let q = integral.quadrature(radius, h);
                let load = stress_integral_force(&view, &sphere, 1.0, [g, 0.0, 0.0], &integral, &q);
                println!(
                    "{},{factor},{steps},{seconds:.1},{:.5},{offset},{},{:.5}",
                    scheme.name(),
                    g / drag,
                    interpolation.name(),
                    load.force[0] / drag
                );
            }
        }
    }
}
