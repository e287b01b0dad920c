//! The fixture of the time-stepped porous-media tests: one fixed sphere in a periodic unit
//! cell, driven at bulk velocity 1 by the mean-velocity force.

use fsim::coupling::direct::{DirectCoupling, DirectSettings, RigidSphere};
use fsim::fluid::{BoundaryConditions, FluidSettings, FluidSolver, MeanVelocityForce, TimeScheme};
use fsim::grid::Grid;
use std::f64::consts::PI;

/// A fixed sphere of solid fraction `phi` off the grid's symmetry points by (0.1, 0.2, 0.3) h
/// in a periodic unit cell of `n³` cells (ν = ρ = 1), driven at bulk velocity 1: the fluid
/// on `scheme`, its coupling, the sphere and `factor` times RK3's viscous bound.
pub fn driven_array(
    phi: f64,
    n: usize,
    scheme: TimeScheme,
    factor: f64,
) -> (FluidSolver, DirectCoupling, RigidSphere, f64) {
    let radius = (3.0 * phi / (4.0 * PI)).cbrt();
    let h = 1.0 / n as f64;
    let sphere = RigidSphere::fixed([0.5 + 0.1 * h, 0.5 + 0.2 * h, 0.5 + 0.3 * h], radius);
    let grid = Grid::new([n; 3], [h; 3], [0.0; 3]);
    let mut fluid = FluidSolver::new(
        grid,
        BoundaryConditions::periodic(),
        FluidSettings::new(1.0),
    )
    .unwrap();
    let dt = factor * fluid.stability_bound();
    fluid.set_scheme(scheme).unwrap();
    fluid
        .set_mean_velocity_force(Some(MeanVelocityForce::new(0, 1.0, 1.0)))
        .unwrap();
    let mut coupling = DirectCoupling::new(&mut fluid, DirectSettings::default());
    coupling.set_spheres(&[sphere], &[0]);
    (fluid, coupling, sphere, dt)
}
