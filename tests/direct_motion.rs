//! Freely moving spheres with the direct model, assembled from the library's parts exactly as
//! the time loop assembles them (fluid step with no-slip, stress integral, lubrication, DEM):
//! a settling sphere against the periodic-array correction (paper eq. 17), the zero momentum
//! of a settling suspension in a periodic box, and the stability limit in density ratio.

use fsim::coupling::direct::{
    sangani_acrivos_k, DirectCoupling, DirectSettings, MotionSettings, ParticleMotion,
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
    pub fn new(
        n: [usize; 3],
        h: f64,
        spheres: &[([f64; 3], f64)],
        rho_p: f64,
        rho_f: f64,
        nu: f64,
        scheme: TimeScheme,
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
        let motion =
            ParticleMotion::new(MotionSettings::default(), &grid, &bc, &dem, rho_f, nu).unwrap();
        fluid.set_body_force(motion.fluid_body_force());
        let mut direct = DirectSettings::default();
        if let Ok(name) = std::env::var("INTERP") {
            direct.integral.interpolation =
                fsim::coupling::direct::Interpolation::from_name(&name).unwrap();
        }
        if let Ok(q) = std::env::var("QUADS") {
            direct.integral.quadrangles = Some(q.parse().unwrap());
        }
        if let Ok(offset) = std::env::var("OFFSET") {
            direct.integral.surface_offset = offset.parse().unwrap();
        }
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
        let clock = std::time::Instant::now();
        self.coupling.set_particles(self.dem.particles());
        if std::env::var("TIMING").is_ok() {
            eprintln!("set_particles {:?}", clock.elapsed());
        }
        let coupling = &self.coupling;
        self.fluid
            .step_with(dt, &mut |stage| coupling.impose(stage));
        let clock = std::time::Instant::now();
        let loads = self.coupling.compute_loads(&self.fluid, self.rho).to_vec();
        if std::env::var("TIMING").is_ok() {
            eprintln!("compute_loads {:?}", clock.elapsed());
        }
        if std::env::var("TRACE").is_ok() {
            let p = self.dem.particles();
            let w = p.mass(0) * (1.0 - self.rho / p.density[0]) * 9.81;
            eprintln!(
                "  v_p {:.4e} <u> {:.4e} F_h/W {:.4} T {:.3e}",
                p.velocity[0][1],
                self.fluid.mean_component(1),
                loads[0].force[1] / w,
                loads[0].torque[2]
            );
        }
        self.motion
            .set_loads(&mut self.dem, loads.iter().map(|l| (l.force, l.torque)), dt);
        self.dem.advance(dt);
        self.time += dt;
    }

    pub fn report(&mut self) -> SedimentationReport {
        let mean = [0, 1, 2].map(|c| self.fluid.mean_component(c));
        self.motion.sedimentation(mean, self.dem.particles())
    }
}

fn stokes_velocity(d: f64, rho_p: f64, rho_f: f64, nu: f64) -> f64 {
    2.0 * (rho_p - rho_f) * 9.81 * (d / 2.0).powi(2) / (9.0 * rho_f * nu)
}

/// Terminal velocity of one sphere in a periodic box at r/h = 8, Re = 0.004.
fn settling_sphere_ratio(scheme: TimeScheme, dt: f64, steps: usize, rho_p: f64) -> Vec<f64> {
    let (n, h) = (36, 1.25e-4);
    let d = 16.0 * h;
    let (rho_f, nu) = (1000.0, 1e-3);
    let centre = [18.0 * h + 0.3 * h, 18.0 * h, 18.0 * h - 0.2 * h];
    let mut s = Settler::new([n; 3], h, &[(centre, d)], rho_p, rho_f, nu, scheme);
    let us = stokes_velocity(d, rho_p, rho_f, nu);
    let mut out = Vec::new();
    for k in 0..steps {
        s.step(dt);
        if (k + 1) % (steps / 10).max(1) == 0 {
            let r = s.report();
            out.push(r.settling_velocity / us);
            eprintln!(
                "t = {:.4e}: v/U_s = {:.5}, momentum {:.3e} of {:.3e}",
                s.time,
                r.settling_velocity / us,
                r.momentum[1],
                r.momentum_scale
            );
        }
    }
    out
}

#[test]
#[ignore]
fn explore_settling_sphere() {
    let scheme = match std::env::var("SCHEME").as_deref() {
        Ok("RK3") => TimeScheme::RK3,
        Ok("Euler") => TimeScheme::Euler,
        _ => TimeScheme::RK3CN,
    };
    let dt: f64 = std::env::var("DT")
        .map(|s| s.parse().unwrap())
        .unwrap_or(1e-4);
    let steps: usize = std::env::var("STEPS")
        .map(|s| s.parse().unwrap())
        .unwrap_or(100);
    let rho_p: f64 = std::env::var("RHOP")
        .map(|s| s.parse().unwrap())
        .unwrap_or(2000.0);
    let phi = 4.0 / 3.0 * std::f64::consts::PI * 512.0 / 36f64.powi(3);
    eprintln!("phi {phi}, 1/K = {}", 1.0 / sangani_acrivos_k(phi));
    settling_sphere_ratio(scheme, dt, steps, rho_p);
}

/// Diagnostic: a fixed sphere in a periodic box with the fluid driven by a uniform body force
/// `b`: in the steady state the sphere carries all of it, `F = ρ b L³` (exact momentum balance).
#[test]
#[ignore]
fn explore_fixed_sphere_momentum_balance() {
    let scheme = match std::env::var("SCHEME").as_deref() {
        Ok("RK3") => TimeScheme::RK3,
        Ok("Euler") => TimeScheme::Euler,
        _ => TimeScheme::RK3CN,
    };
    let dt: f64 = std::env::var("DT")
        .map(|s| s.parse().unwrap())
        .unwrap_or(1e-4);
    let steps: usize = std::env::var("STEPS")
        .map(|s| s.parse().unwrap())
        .unwrap_or(100);
    let (n, h) = (36, 1.25e-4);
    let d = 16.0 * h;
    let centre = [18.0 * h + 0.3 * h, 18.0 * h, 18.0 * h - 0.2 * h];
    let mut s = Settler::new([n; 3], h, &[(centre, d)], 2000.0, 1000.0, 1e-3, scheme);
    // hold it: zero gravity, fixed
    let b = 1.0;
    s.fluid.set_body_force([0.0, b, 0.0]);
    let l3 = (n as f64 * h).powi(3);
    for k in 0..steps {
        s.coupling.set_particles(s.dem.particles());
        let coupling = &s.coupling;
        s.fluid.step_with(dt, &mut |stage| coupling.impose(stage));
        let loads = s.coupling.compute_loads(&s.fluid, s.rho).to_vec();
        if (k + 1) % (steps / 10).max(1) == 0 {
            eprintln!(
                "step {}: F/(rho b L^3) = {:.5}, <u> = {:.4e}",
                k + 1,
                loads[0].force[1] / (1000.0 * b * l3),
                s.fluid.mean_component(1)
            );
        }
    }
}
