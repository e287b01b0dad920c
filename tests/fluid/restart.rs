//! Restart: N steps equal N/2 steps, save, restore into a fresh solver, N/2 steps — bit for
//! bit.

use fsim::fluid::{
    BoundaryConditions, FaceCondition, FluidSettings, FluidSolver, MeanVelocityForce, TimeScheme,
};
use fsim::grid::Grid;

/// A channel driven by meanVelocityForce with a wavy initial field: exercises walls, the
/// drive's state and every stage of the scheme.
fn solver(scheme: TimeScheme) -> FluidSolver {
    let n = [16, 12, 8];
    let h = [0.1, 1.0 / 12.0, 0.1];
    let grid = Grid::new(n, h, [0.0; 3]);
    let wall = FaceCondition::Wall { velocity: [0.0; 3] };
    let bc = BoundaryConditions {
        faces: [
            FaceCondition::Periodic,
            FaceCondition::Periodic,
            wall.clone(),
            wall,
            FaceCondition::Periodic,
            FaceCondition::Periodic,
        ],
    };
    let mut s = FluidSolver::new(
        grid,
        bc,
        FluidSettings {
            nu: 0.01,
            scheme,
            body_force: [0.0, -0.1, 0.0],
            convection: true,
        },
    )
    .unwrap();
    s.set_mean_velocity_force(Some(MeanVelocityForce::new(0, 1.0, 0.8)))
        .unwrap();
    s.set_velocity(|c, x| match c {
        0 => 4.0 * x[1] * (1.0 - x[1]) + 0.2 * (3.0 * x[2]).sin(),
        1 => 0.1 * (6.0 * x[0]).sin() * (x[1] * std::f64::consts::PI).sin(),
        _ => 0.1 * (4.0 * x[0]).cos(),
    });
    s.project();
    s
}

#[test]
fn continued_run_equals_uninterrupted_bit_for_bit() {
    for scheme in TimeScheme::ALL {
        let dt = 0.01;
        let mut whole = solver(scheme);
        for _ in 0..20 {
            whole.step(dt);
        }
        let mut first = solver(scheme);
        for _ in 0..10 {
            first.step(dt);
        }
        let saved: Vec<(String, Vec<f64>)> = first
            .restart_arrays()
            .into_iter()
            .map(|(n, a)| (n.to_string(), a.to_vec()))
            .collect();
        drop(first);
        let mut second = solver(scheme);
        for (name, data) in &saved {
            second.restore_array(name, data).unwrap();
        }
        for _ in 0..10 {
            second.step(dt);
        }
        let a = whole
            .restart_arrays()
            .into_iter()
            .map(|(n, a)| (n, a.to_vec()))
            .collect::<Vec<_>>();
        let b = second
            .restart_arrays()
            .into_iter()
            .map(|(n, a)| (n, a.to_vec()))
            .collect::<Vec<_>>();
        for ((name, x), (_, y)) in a.iter().zip(&b) {
            assert!(
                x.iter().zip(y).all(|(p, q)| p.to_bits() == q.to_bits()),
                "{scheme:?}: array {name} differs"
            );
        }
        assert!(whole.mean_velocity_force().unwrap().gradient != 0.0);
        assert!(whole.diagnostics(dt).divergence < 1e-10);
    }
}

#[test]
fn restore_rejects_wrong_names_and_lengths() {
    let mut s = solver(TimeScheme::RK3);
    assert!(s.restore_array("U.w", &[0.0]).is_err());
    assert!(s.restore_array("p", &[0.0; 3]).is_err());
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut s = solver(TimeScheme::RK3);
            for _ in 0..10 {
                s.step(0.01);
            }
            s.restart_arrays()
                .into_iter()
                .map(|(_, a)| a.to_vec())
                .collect::<Vec<_>>()
        })
    };
    let (one, two) = (run(1), run(2));
    for (a, b) in one.iter().zip(&two) {
        assert!(a.iter().zip(b).all(|(p, q)| p.to_bits() == q.to_bits()));
    }
}
