//! A harness assembling the direct model's coupled step from the library's parts as the time
//! loop does (fluid step with no-slip, stress integral, lubrication and virtual mass, DEM),
//! for the tests of freely moving spheres and `examples/direct_explore.rs`.
#![allow(dead_code)]

use fsim::coupling::direct::{
    DirectCoupling, DirectSettings, HydrodynamicLoad, MotionSettings, ParticleMotion,
    SedimentationReport,
};
use fsim::fluid::{BoundaryConditions, FluidSettings, FluidSolver, TimeScheme};
use fsim::grid::Grid;
use fsim::particles::{
    Dem, DemConfig, DomainBox, FaceCondition, PairModel, ParticleState, WallModel,
};

/// A fully periodic box of `n` cells of size `h` per axis with free spheres, gravity −y.
pub struct Settler {
    pub fluid: FluidSolver,
    pub coupling: DirectCoupling,
    pub dem: Dem,
    pub motion: ParticleMotion,
    pub rho: f64,
    pub time: f64,
}

impl Settler {
    /// Spheres `(centre, diameter)` of density `rho_p` in a fluid of `rho_f` and `nu`, with
    /// the default direct-model and motion settings.
    pub fn new(
        n: [usize; 3],
        h: f64,
        spheres: &[([f64; 3], f64)],
        rho_p: f64,
        rho_f: f64,
        nu: f64,
        scheme: TimeScheme,
    ) -> Settler {
        let settings = (DirectSettings::default(), MotionSettings::default());
        Self::with_settings(n, h, spheres, (rho_p, rho_f, nu), scheme, settings)
    }

    /// As [`Self::new`], with the direct model's and the motion's settings given;
    /// `densities_and_nu` is `(rho_p, rho_f, nu)`.
    pub fn with_settings(
        n: [usize; 3],
        h: f64,
        spheres: &[([f64; 3], f64)],
        (rho_p, rho_f, nu): (f64, f64, f64),
        scheme: TimeScheme,
        (direct, motion_settings): (DirectSettings, MotionSettings),
    ) -> Settler {
        let grid = Grid::new(n, [h; 3], [0.0; 3]);
        let bc = BoundaryConditions::periodic();
        let mut settings = FluidSettings::new(nu);
        settings.scheme = scheme;
        let mut fluid = FluidSolver::new(grid.clone(), bc.clone(), settings).unwrap();
        let mut p = ParticleState::default();
        for (k, (x, d)) in spheres.iter().enumerate() {
            p.push(k as u64, *x, *d, rho_p);
        }
        let d = spheres[0].1;
        let m = rho_p * std::f64::consts::PI * d * d * d / 6.0;
        // soft contacts: only a backstop here
        let kn = 1e-3 * m / (1e-4 * 1e-4);
        let wall = WallModel::LinearSpringDashpot {
            kn,
            restitution: 0.5,
            kt: 2.0 / 7.0 * kn,
            mu: 0.3,
            tangential_damping_ratio: 0.5,
            collision_resolution_steps: 20.0,
        };
        let mut config = DemConfig::new(PairModel::linear(kn, 0.5, 0.3), wall);
        config.gravity = [0.0, -9.81, 0.0];
        config.fluid_density = rho_f;
        let length = grid.length();
        let dem = Dem::new(
            config,
            DomainBox::uniform([0.0; 3], length, FaceCondition::Periodic),
            p,
        )
        .unwrap();
        let motion = ParticleMotion::new(motion_settings, &grid, &bc, &dem, rho_f, nu).unwrap();
        fluid.set_body_force(motion.fluid_body_force());
        let coupling = DirectCoupling::new(&mut fluid, direct);
        Settler {
            fluid,
            coupling,
            dem,
            motion,
            rho: rho_f,
            time: 0.0,
        }
    }

    /// One coupled step (the order of `src/coupling/direct/particle_motion.rs`).
    pub fn step(&mut self, dt: f64) {
        let loads = self.fluid_step(dt);
        self.motion
            .set_loads(&mut self.dem, loads.iter().map(|l| (l.force, l.torque)), dt);
        self.dem.advance(dt);
        self.time += dt;
    }

    /// The fluid's part of a step: no-slip on the spheres where they are, then the
    /// stress-integral loads on them (the particles do not move).
    pub fn fluid_step(&mut self, dt: f64) -> Vec<HydrodynamicLoad> {
        self.coupling.set_particles(self.dem.particles());
        let coupling = &mut self.coupling;
        self.fluid
            .step_with(dt, &mut |stage| coupling.impose(stage));
        self.coupling.compute_loads(&self.fluid, self.rho).to_vec()
    }

    pub fn report(&mut self) -> SedimentationReport {
        let mean = [0, 1, 2].map(|c| self.fluid.mean_component(c));
        self.motion.sedimentation(mean, self.dem.particles())
    }
}

/// Stokes' terminal velocity of a sphere of diameter `d` (m/s).
pub fn stokes_velocity(d: f64, rho_p: f64, rho_f: f64, nu: f64) -> f64 {
    2.0 * (rho_p - rho_f) * 9.81 * (d / 2.0).powi(2) / (9.0 * rho_f * nu)
}
