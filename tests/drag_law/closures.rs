//! Acceptance tests of the drag-law model (paper §2.2), its step as fsimFoam takes it
//! (`DragLawModel::step`) on set-ups built in code: terminal
//! settling velocity for every closure, Ergun's pressure drop through a fixed bed at two
//! fluid fractions, the pressure drop of a fluidized bed, and the action–reaction balance of
//! the particle–fluid exchange at every step.

use fsim::coupling::drag::{
    Convention, DragClosure, DragInput, DragLawCoupling, DragLawSettings, Stencil,
};
use fsim::fluid::{
    BoundaryConditions, FaceCondition, FluidSettings, FluidSolver, VolumeAveragedForm,
};
use fsim::grid::Grid;
use fsim::particles::{
    Dem, DemConfig, DomainBox, FaceCondition as ParticleFace, PairModel, ParticleState, WallModel,
};
use fsim::simulation::DragLawModel;
use fsim::Vec3;
use std::f64::consts::PI;

pub(crate) const RHO: f64 = 1000.0;
pub(crate) const NU: f64 = 1e-6;
pub(crate) const G: f64 = 9.81;

/// Periodic in x and y; walls (`top_outlet`: an outlet at p = 0 on top, an inlet of `inflow`
/// m/s at the bottom) along z.
pub(crate) fn fluid(n: [usize; 3], h: f64, inflow: Option<f64>) -> FluidSolver {
    let grid = Grid::new(n, [h; 3], [0.0; 3]);
    let (bottom, top) = match inflow {
        Some(w) => (
            FaceCondition::Inlet {
                velocity: [0.0, 0.0, w],
            },
            FaceCondition::Outlet { pressure: 0.0 },
        ),
        None => (
            FaceCondition::Wall { velocity: [0.0; 3] },
            FaceCondition::Wall { velocity: [0.0; 3] },
        ),
    };
    let bc = BoundaryConditions {
        faces: [
            FaceCondition::Periodic,
            FaceCondition::Periodic,
            FaceCondition::Periodic,
            FaceCondition::Periodic,
            bottom,
            top,
        ],
    };
    FluidSolver::new(grid, bc, FluidSettings::new(NU)).unwrap()
}

pub(crate) fn dem(particles: ParticleState, hi: [f64; 3], gravity: f64, pair: PairModel) -> Dem {
    dem_in(particles, [0.0; 3], hi, gravity, pair)
}

fn dem_in(
    particles: ParticleState,
    lo: [f64; 3],
    hi: [f64; 3],
    gravity: f64,
    pair: PairModel,
) -> Dem {
    let mut config = DemConfig::new(pair, WallModel::None);
    config.gravity = Vec3::new(0.0, 0.0, -gravity);
    config.fluid_density = RHO;
    let domain = DomainBox {
        lo: Vec3::from(lo),
        hi: Vec3::from(hi),
        faces: [
            ParticleFace::Periodic,
            ParticleFace::Periodic,
            ParticleFace::Periodic,
            ParticleFace::Periodic,
            ParticleFace::Rebound { e: 0.5, mu: 0.0 },
            ParticleFace::Rebound { e: 0.5, mu: 0.0 },
        ],
        planar: [false; 3],
        wall_velocity: [Vec3::repeat(0.0); 6],
    };
    Dem::new(config, domain, particles).unwrap()
}

fn settings(closure: DragClosure, gravity: f64) -> DragLawSettings {
    let mut s = DragLawSettings::paper(RHO, NU, Vec3::new(0.0, 0.0, -gravity));
    s.closure = Some(closure);
    // Each closure in the form its convention belongs to.
    s.form = match closure.convention() {
        Convention::DragOnly => VolumeAveragedForm::Paper,
        Convention::Total => VolumeAveragedForm::DpmFoam,
    };
    s
}

/// The drag-law model of `cloud` in `fluid`, its pressure initialised for steps of `dt`.
fn model(s: DragLawSettings, fluid: &mut FluidSolver, cloud: Dem, dt: f64) -> DragLawModel {
    model_with_inlets(s, fluid, cloud, dt, [false; 6])
}

/// [`model`] with the superficial inlets (DPMFoam's `interstitialInletVelocity`) `inlets`.
fn model_with_inlets(
    s: DragLawSettings,
    fluid: &mut FluidSolver,
    cloud: Dem,
    dt: f64,
    inlets: [bool; 6],
) -> DragLawModel {
    let mut coupling = DragLawCoupling::new(s, fluid, &cloud).unwrap();
    coupling.fluid.set_superficial_inlets(inlets);
    DragLawModel::start(coupling, cloud, fluid, dt)
}

/// One step of the drag-law model as fsimFoam takes it (`DragLawModel::step`), checking
/// action = −reaction and the pressure solve.
fn step(model: &mut DragLawModel, fluid: &mut FluidSolver, dt: f64) {
    model.step(fluid, dt).unwrap();
    let e = model.coupling.last;
    let scale = e
        .drag_on_particles
        .iter()
        .fold(1e-300f64, |m, x| m.max(x.abs()));
    for a in 0..3 {
        let imbalance = (e.drag_on_particles[a] + e.drag_on_fluid[a]).abs();
        assert!(
            imbalance <= 1e-12 * scale,
            "action {:?} vs reaction {:?}",
            e.drag_on_particles,
            e.drag_on_fluid
        );
    }
    let r = model.coupling.last_fluid.unwrap();
    assert!(r.pressure.converged, "{:?}", r.pressure);
}

/// The slip `w` with `β(ε, w) w = W` (the closure in `want`'s convention), by bisection.
fn terminal_slip(closure: DragClosure, want: Convention, d: f64, eps: f64, weight: f64) -> f64 {
    let force = |w: f64| {
        let q = DragInput {
            d,
            eps,
            slip: w,
            rho: RHO,
            mu: RHO * NU,
        };
        closure.coefficient_as(&q, want) * w - weight
    };
    let (mut lo, mut hi) = (0.0, 10.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if force(mid) > 0.0 {
            hi = mid
        } else {
            lo = mid
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn a_single_particle_settles_at_the_root_of_each_closures_force_balance() {
    // d = 0.2 mm glass (ρ_p = 2500) in water: Stokes velocity 3.3 cm/s, Re ≈ 5 at terminal
    // velocity, relaxation time ρ_p d²/(18 μ) = 5.6 ms; cells of 1 mm (h = 5d), 8×8×16.
    let (d, rho_p, h) = (2e-4, 2500.0, 1e-3);
    let volume = PI * d * d * d / 6.0;
    let weight = (rho_p - RHO) * volume * G;
    let mut summary = Vec::new();
    for name in DragClosure::NAMES {
        let closure = DragClosure::from_name(name, "dragModel").unwrap();
        let mut fluid = fluid([8, 8, 16], h, None);
        let mut particles = ParticleState::with_capacity(1);
        particles.push(0, [4.5e-3, 4.5e-3, 13e-3], d, rho_p);
        let cloud = dem(
            particles,
            [8e-3, 8e-3, 16e-3],
            G,
            PairModel::linear(1.0, 0.5, 0.0),
        );
        let mut s = settings(closure, G);
        // The particle's own cell: ε is the same wherever it falls.
        s.averaging = Stencil::Cell;
        let mut model = model(s, &mut fluid, cloud, 5e-4);
        for _ in 0..200 {
            step(&mut model, &mut fluid, 5e-4);
        }
        let x = model.particles.dem.particles().position[0];
        let v = model.particles.dem.particles().velocity[0];
        let u = model.coupling.fluid_velocity_at(&fluid, x);
        let slip = (u[2] - v[2]).abs();
        let eps = model.coupling.fluid_fraction_at(x);
        assert!((eps - (1.0 - volume / (h * h * h))).abs() < 1e-12);
        let want = closure.convention();
        let root = terminal_slip(closure, want, d, eps, weight);
        let error = (slip - root).abs() / root;
        summary.push(format!(
            "{name}: slip {slip:.6e} root {root:.6e} error {error:.2e}"
        ));
        assert!(error < 0.01, "{}", summary.join("\n"));
        assert!(v[2] < 0.0 && v[0].abs() < 1e-9 * root);
    }
    println!("{}", summary.join("\n"));
}

/// Ergun (1952): `ΔP/L = 150 μ φ² U/(ε³ d²) + 1.75 ρ φ U²/(ε³ d)`, `U` superficial.
fn ergun(phi: f64, u: f64, d: f64) -> f64 {
    let eps = 1.0 - phi;
    let mu = RHO * NU;
    150.0 * mu * phi * phi * u / (eps.powi(3) * d * d)
        + 1.75 * RHO * phi * u * u / (eps.powi(3) * d)
}

#[test]
fn fixed_bed_pressure_drop_matches_ergun_at_two_fluid_fractions() {
    // d = 1 mm spheres on a simple cubic lattice, one per cell at the cell centre, in layers
    // 4..12 of 16; water at U = 1 mm/s superficial (Re_s ≈ 1). h = 1 mm: φ = π/6 = 0.524;
    // h = 1.25 mm: φ = 0.268. Both in Ergun's branch of each closure (ε ≤ 0.8).
    let d = 1e-3;
    let u_in = 1e-3;
    for (h, closure, stencil) in [
        (1e-3, DragClosure::ErgunWenYu, Stencil::Cell),
        (1.25e-3, DragClosure::ErgunWenYu, Stencil::Trilinear),
        (1e-3, DragClosure::Paper, Stencil::Trilinear),
        (1.25e-3, DragClosure::Paper, Stencil::Cell),
    ] {
        let n = [4, 4, 16];
        let mut fluid = fluid(n, h, Some(u_in));
        let mut particles = ParticleState::with_capacity(128);
        let mut id = 0;
        for k in 4..12 {
            for j in 0..4 {
                for i in 0..4 {
                    let c = |m: usize| (m as f64 + 0.5) * h;
                    particles.push(id, [c(i), c(j), c(k)], d, 2500.0);
                    particles.fixed[id as usize] = true;
                    id += 1;
                }
            }
        }
        let hi = [4.0 * h, 4.0 * h, 16.0 * h];
        let cloud = dem(particles, hi, 0.0, PairModel::linear(1.0, 0.5, 0.0));
        let mut s = settings(closure, 0.0);
        s.averaging = stencil;
        s.interpolation = stencil;
        s.semi_implicit = true;
        let mut model = model(s, &mut fluid, cloud, 1e-3);
        for _ in 0..100 {
            step(&mut model, &mut fluid, 1e-3);
        }
        // Pressure gradient between layers 6 and 10, well inside the bed.
        let p = fluid.pressure();
        let layer = |k: usize| p[16 * k..16 * (k + 1)].iter().sum::<f64>() / 16.0;
        let measured = RHO * (layer(6) - layer(10)) / (4.0 * h);
        let phi = PI * d * d * d / 6.0 / (h * h * h);
        let expected = ergun(phi, u_in, d);
        let error = (measured - expected).abs() / expected;
        println!(
            "{} {:?} phi {phi:.4}: dp/L = {measured:.4} Pa/m, Ergun {expected:.4}, error {error:.2e}",
            closure.name(),
            stencil
        );
        assert!(error < 0.03, "{}: {measured} vs {expected}", closure.name());
    }
}

#[test]
fn fluidized_bed_pressure_drop_carries_the_buoyant_weight() {
    // 600 glass spheres (d = 1 mm, ρ_p = 2500) in water fluidized at U = 8 cm/s (Wen & Yu's
    // minimum fluidization ≈ 0.8 cm/s, terminal velocity ≈ 15 cm/s) in an 8 × 8 mm periodic
    // column 60 mm high, cells of 2 mm (h = 2d, the paper's); explicit source, linear
    // spring-dashpot contacts. The particles' distributor (their bottom face) is at z = 4 mm,
    // so the lowest cell layer stays particle-free and the pressure drop from it to the top
    // layer is the bed's alone (a plenum's reading, without the momentum-flux change of the
    // fluid entering a bed).
    // The velocity read trilinearly (the paper's) and by OpenFOAM's cellPoint.
    for cell_point in [false, true] {
        let (d, rho_p, h) = (1e-3, 2500.0, 2e-3);
        let n = [4, 4, 30];
        let count = 600;
        let u_in = 0.08;
        let mut fluid = fluid(n, h, Some(u_in));
        let mut particles = ParticleState::with_capacity(count);
        let mut id = 0;
        // A loose lattice of 5 × 5 spheres per layer, 1.6 mm apart, from z = 5 mm.
        'fill: for k in 0..100 {
            for j in 0..5 {
                for i in 0..5 {
                    if id == count as u64 {
                        break 'fill;
                    }
                    let x = [
                        0.5e-3 + 1.6e-3 * i as f64 + 0.1e-3 * (k % 2) as f64,
                        0.5e-3 + 1.6e-3 * j as f64,
                        5e-3 + 1.6e-3 * k as f64,
                    ];
                    particles.push(id, x, d, rho_p);
                    id += 1;
                }
            }
        }
        let hi = [8e-3, 8e-3, 60e-3];
        let cloud = dem_in(
            particles,
            [0.0, 0.0, 4e-3],
            hi,
            G,
            PairModel::linear(50.0, 0.5, 0.3),
        );
        let mut s = settings(DragClosure::ErgunWenYu, G);
        s.averaging = Stencil::Trilinear;
        s.cell_point = cell_point;
        let dt = 2e-3;
        // The inlet's 8 cm/s is superficial (DPMFoam's interstitialInletVelocity).
        let inlets = [false, false, false, false, true, false];
        let mut model = model_with_inlets(s, &mut fluid, cloud, dt, inlets);
        let weight = count as f64 * (rho_p - RHO) * PI * d * d * d / 6.0 * G / (8e-3 * 8e-3);
        let (mut sum, mut samples) = (0.0, 0);
        let (mut top, mut bottom) = (0.0f64, 1.0f64);
        for n_step in 0..500 {
            step(&mut model, &mut fluid, dt);
            if n_step >= 250 {
                // ρ (p₀ − p_N−1) less the water column between the two layer centres.
                let drop = model.coupling.pressure_drop(&fluid, 2);
                sum += drop;
                samples += 1;
                for x in &model.particles.dem.particles().position {
                    top = top.max(x[2]);
                    bottom = bottom.min(x[2]);
                }
            }
        }
        let mean = sum / samples as f64;
        let error = (mean - weight).abs() / weight;
        println!(
            "fluidized bed (cellPoint {cell_point}): mean pressure drop {mean:.4} Pa over t = 0.5..1 s, buoyant weight/area \
             {weight:.4} Pa, error {error:.2e}; particles between z = {bottom:.4e} and {top:.4e} m"
        );
        assert!(top < 56e-3, "the bed must stay below the top layers");
        assert!(error < 0.03, "{mean} vs {weight}");
    }
}
