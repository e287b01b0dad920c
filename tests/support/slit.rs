//! A sphere between two plane no-slip walls (y = 0 and y = 2l, periodic along x and z with
//! period `L`), in lattice units (h = 1, ν = 1, `EulerRKC`): for `tests/direct/walls.rs` and
//! `examples/wall_slit_drag.rs`.
#![allow(dead_code)]

use super::box_case::{step, BoxCase};
use fsim::coupling::direct::{DirectCoupling, DirectSettings, RigidSphere};
use fsim::fluid::{BoundaryConditions, FaceCondition, FluidSettings, FluidSolver, TimeScheme};
use fsim::grid::Grid;
use fsim::Vec3;

/// Faxén's drag factor for a sphere midway between two walls, `λ = a/l` (Happel & Brenner,
/// *Low Reynolds number hydrodynamics*, 1965, eq. 7-4.39).
pub fn faxen_midway(lambda: f64) -> f64 {
    1.0 / (1.0 - 1.004 * lambda + 0.418 * lambda.powi(3) + 0.21 * lambda.powi(4)
        - 0.169 * lambda.powi(5))
}

/// `K(L)` at two lateral periods, extrapolated as `K∞ + c/L²` (a confined Stokeslet's far
/// field is a two-dimensional dipole).
pub fn without_images(k: [f64; 2], lateral: [usize; 2]) -> f64 {
    let [a, b] = lateral.map(|l| (l * l) as f64);
    (b * k[1] - a * k[0]) / (b - a)
}

/// The fluid between walls `2 l` cells apart moving at `wall_velocity` along x, period
/// `lateral` cells along x and z.
pub fn slit_fluid(l: usize, lateral: usize, wall_velocity: f64) -> FluidSolver {
    let grid = Grid::new([lateral, 2 * l, lateral], [1.0; 3], [0.0; 3]);
    let mut bc = BoundaryConditions::periodic();
    for side in [2, 3] {
        bc.faces[side] = FaceCondition::Wall {
            velocity: [wall_velocity, 0.0, 0.0],
        };
    }
    let settings = FluidSettings {
        nu: 1.0,
        scheme: TimeScheme::EulerRKC,
        body_force: [0.0; 3],
        convection: true,
    };
    FluidSolver::new(grid, bc, settings).unwrap()
}

/// A sphere of `radius` cells held still, off the grid's symmetry lines, with its surface
/// `gap` cells above the lower wall (midway when `None`), the walls and the bulk moving at
/// `−U` (`meanVelocityForce` holds it, so that the sphere drives no net flow; U = 0.01,
/// Re = 2aU/ν ≤ 0.16): a case run as `fsimFoam` runs it (`box_case.rs`). The drag over
/// `6πμaU` after `steps` steps of `dt`, or, when `None`, once it changes by less than 10⁻⁶ a
/// step.
pub fn slit_drag(
    radius: f64,
    l: usize,
    lateral: usize,
    gap: Option<f64>,
    dt: f64,
    steps: Option<usize>,
) -> f64 {
    let speed = 0.01;
    let centre = [
        0.5 * lateral as f64 + 0.13,
        gap.map_or(l as f64, |g| radius + g),
        0.5 * lateral as f64 + 0.21,
    ];
    let case = BoxCase {
        cells: [lateral, 2 * l, lateral],
        h: 1.0,
        walls: [false, true, false],
        wall_velocity: [-speed, 0.0, 0.0],
        fluid: (1.0, 1.0),
        gravity: [0.0; 3],
        scheme: TimeScheme::EulerRKC,
        initial_velocity: [-speed, 0.0, 0.0],
        mean_velocity: Some([-speed, 0.0, 0.0]),
        coupling: "model direct; direct { fixedParticles yes; }".to_string(),
        spheres: vec![centre],
        diameter: 2.0 * radius,
        rho_p: 2.0,
        kn: 1.0,
    };
    let mut sim = case.simulation();
    let mut last = f64::INFINITY;
    for n in 1.. {
        step(&mut sim, dt);
        let loads = sim.coupling.direct().and_then(|m| m.loads).unwrap();
        let k = loads.drag_coefficient;
        let done = match steps {
            Some(total) => n == total,
            None => (k - last).abs() < 1e-6,
        };
        if done {
            return k;
        }
        last = k;
    }
    unreachable!("the loop returns")
}

/// A sphere of `radius` cells pulled toward the lower of two resting walls `2 l` cells
/// apart (period `lateral`) at `speed` from a surface gap of `from` cells, steps of `dt`;
/// the normal drag over `6πμaU` as the gap reaches each of `at` (cells, descending). A
/// sphere moved at a prescribed speed is not a case (fsimFoam's spheres are free or fixed),
/// so this one drives the fluid's stages and the stress integral itself.
pub fn approach_drag(
    [radius, speed, dt]: [f64; 3],
    l: usize,
    lateral: usize,
    from: f64,
    at: &[f64],
) -> Vec<f64> {
    let mut fluid = slit_fluid(l, lateral, 0.0);
    let mut coupling = DirectCoupling::new(&mut fluid, DirectSettings::default());
    let stokes = 6.0 * std::f64::consts::PI * radius * speed;
    let mut drag = Vec::with_capacity(at.len());
    for step in 0.. {
        if drag.len() == at.len() {
            break;
        }
        let gap = from - speed * dt * step as f64;
        let sphere = RigidSphere {
            centre: Vec3::new(
                0.5 * lateral as f64 + 0.13,
                radius + gap,
                0.5 * lateral as f64 + 0.21,
            ),
            radius,
            velocity: Vec3::new(0.0, -speed, 0.0),
            angular_velocity: Vec3::repeat(0.0),
        };
        coupling.set_spheres(&[sphere], &[0]);
        fluid.step_with(dt, &mut |stage| coupling.impose(stage));
        let k = coupling.compute_loads(&fluid, 1.0)[0].force[1] / stokes;
        if gap <= at[drag.len()] + 1e-9 {
            drag.push(k);
        }
    }
    drag
}
