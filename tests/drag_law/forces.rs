//! DPMFoam's forces besides drag through the drag-law model's step: the added mass in a
//! particle's start from rest, a light particle rising with virtual mass, the lift of a
//! particle in a shear flow, and the fluid acceleration the pressure-gradient and
//! virtual-mass forces read.

use fsim::coupling::drag::{
    saffman_mei_cl, sphere_drag, DragClosure, DragInput, DragLawCoupling, DragLawSettings,
    FluidForces, LiftModel, Stencil,
};
use fsim::fluid::{FluidSolver, PaddedLayout, VolumeAveragedForm};
use fsim::particles::{Dem, PairModel, ParticleState};
use fsim::simulation::DragLawModel;
use fsim::Vec3;
use std::f64::consts::PI;

use crate::closures::{dem, fluid, G, NU, RHO};

/// Water in a box of cells `h`, periodic in x and y, closed by walls along z.
fn water(n: [usize; 3], h: f64) -> FluidSolver {
    fluid(n, h, None)
}

/// One particle of diameter `d`, density `rho_p` at `x` in a box `hi`, gravity `g` along −z
/// with water's buoyancy; `held` in place or free.
fn one_particle(x: [f64; 3], d: f64, rho_p: f64, hi: [f64; 3], g: f64, held: bool) -> Dem {
    let mut particles = ParticleState::with_capacity(1);
    particles.push(0, x, d, rho_p);
    particles.fixed[0] = held;
    dem(particles, hi, g, PairModel::linear(1.0, 0.5, 0.0))
}

/// [`water`] with the face velocities `u(slot)` (`[u_x, u_y, u_z]` of the faces at each padded
/// slot, ghosts included).
fn moving_water(n: [usize; 3], h: f64, u: impl Fn([usize; 3]) -> [f64; 3]) -> FluidSolver {
    let mut fluid = water(n, h);
    let l = PaddedLayout::new(n);
    let v = fluid.velocity_mut();
    for k in 0..l.dims[2] {
        for j in 0..l.dims[1] {
            for i in 0..l.dims[0] {
                let value = u([i, j, k]);
                for c in 0..3 {
                    v[c][l.index(i, j, k)] = value[c];
                }
            }
        }
    }
    fluid
}

/// A particle held at rest, without gravity, in the box of [`water`]`([6, 6, 12], 1e-3)`.
fn held_bead(d: f64, rho_p: f64) -> Dem {
    one_particle(
        [2.5e-3, 2.5e-3, 6.3e-3],
        d,
        rho_p,
        [6e-3, 6e-3, 12e-3],
        0.0,
        true,
    )
}

/// DPMFoam's form with `sphereDrag` and `forces`, the particle's own cell for every transfer.
fn dpmfoam(forces: FluidForces) -> DragLawSettings {
    let mut s = DragLawSettings::paper(RHO, NU, Vec3::new(0.0, 0.0, -G));
    s.closure = Some(DragClosure::SphereDrag);
    s.form = VolumeAveragedForm::DpmFoam;
    s.interpolation = Stencil::Cell;
    s.averaging = Stencil::Cell;
    s.semi_implicit = true;
    s.forces = forces;
    s
}

fn virtual_mass(cvm: f64) -> FluidForces {
    FluidForces {
        virtual_mass: Some(cvm),
        pressure_gradient: true,
        ..FluidForces::default()
    }
}

/// The vertical velocity after one step of `dt` from rest in still water.
fn first_velocity(rho_p: f64, forces: FluidForces, dt: f64) -> f64 {
    let (h, d) = (1e-3, 5e-4);
    let mut fluid = water([6, 6, 12], h);
    let cloud = one_particle(
        [2.5e-3, 2.5e-3, 6.5e-3],
        d,
        rho_p,
        [6e-3, 6e-3, 12e-3],
        G,
        false,
    );
    let coupling = DragLawCoupling::new(dpmfoam(forces), &fluid, &cloud).unwrap();
    let mut model = DragLawModel::start(coupling, cloud, &mut fluid, dt);
    model.step(&mut fluid, dt).unwrap();
    model.particles.dem.particles().velocity[0][2]
}

#[test]
fn added_mass_slows_the_start_from_rest_to_g_times_the_density_difference_over_the_effective_density(
) {
    // From rest in still water the drag and the fluid's acceleration vanish:
    // (m + Cvm m ρ/ρ_p) dv/dt = m (1 − ρ/ρ_p) g, dv/dt = g (ρ_p − ρ)/(ρ_p + Cvm ρ).
    let dt = 1e-6;
    for rho_p in [2500.0, 100.0] {
        for cvm in [0.5, 1.0] {
            let want = -G * (rho_p - RHO) / (rho_p + cvm * RHO);
            let got = first_velocity(rho_p, virtual_mass(cvm), dt) / dt;
            assert!(
                (got - want).abs() < 1e-3 * want.abs(),
                "ρ_p {rho_p} Cvm {cvm}: {got} against {want}"
            );
        }
        // without virtual mass: g (1 − ρ/ρ_p)
        let plain = first_velocity(rho_p, FluidForces::default(), dt) / dt;
        let want = -G * (1.0 - RHO / rho_p);
        assert!((plain - want).abs() < 1e-3 * want.abs(), "{plain} {want}");
    }
}

#[test]
fn a_light_particle_rises_with_virtual_mass_to_its_terminal_velocity_without_blowing_up() {
    // d = 0.2 mm, ρ_p = 100 in water, Cvm 0.5: the added mass is 5 times the particle's own,
    // the relaxation time (m + m_add)/β about 1 ms, steps of 1 ms (Δt β/m ≈ 6: the particle
    // alone, without its added mass, would be relaxed 6-fold in a step). It must rise, stay
    // bounded and settle where sphereDrag balances the buoyant weight. Its slip, not its
    // velocity: it drags the water of its cell up (by 10 % of its velocity after 60 ms), and
    // that water, still speeding up, keeps it 1.5 % short of the balance.
    let (h, d, rho_p, dt) = (1e-3, 2e-4, 100.0, 1e-3);
    let mut fluid = water([8, 8, 40], h);
    let cloud = one_particle(
        [4.5e-3, 4.5e-3, 4.5e-3],
        d,
        rho_p,
        [8e-3, 8e-3, 40e-3],
        G,
        false,
    );
    let coupling = DragLawCoupling::new(dpmfoam(virtual_mass(0.5)), &fluid, &cloud).unwrap();
    let mut model = DragLawModel::start(coupling, cloud, &mut fluid, dt);
    let volume = PI * d * d * d / 6.0;
    let weight = (RHO - rho_p) * volume * G;
    // the slip w with β(w) w = buoyant weight
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        let q = DragInput {
            d,
            eps: 1.0,
            slip: mid,
            rho: RHO,
            mu: RHO * NU,
        };
        if sphere_drag(&q) * mid > weight {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let terminal = 0.5 * (lo + hi);
    let mut history = Vec::new();
    for step in 0..120 {
        model.step(&mut fluid, dt).unwrap();
        let v = model.particles.dem.particles().velocity[0];
        if step == 0 {
            // implicit Euler from rest in still water: v = Δt W/(m + m_add + Δt β(0))
            let mass_eff = (rho_p + 0.5 * RHO) * volume;
            let beta = 3.0 * PI * RHO * NU * d;
            let want = dt * weight / (mass_eff + dt * beta);
            assert!((v[2] - want).abs() < 1e-9 * want, "{} against {want}", v[2]);
        }
        history.push(v[2]);
        assert!(
            v[2].is_finite() && v[2] > 0.0 && v[2] < 1.2 * terminal,
            "step {step}: v {v:?}, terminal {terminal}: {history:?}"
        );
    }
    let p = model.particles.dem.particles();
    let (x, v) = (p.position[0], p.velocity[0][2]);
    let slip = v - model.coupling.fluid_velocity_at(&fluid, x)[2];
    assert!(
        (slip - terminal).abs() < 0.025 * terminal,
        "slip {slip} against {terminal}: {history:?}"
    );
}

#[test]
fn saffman_mei_lift_of_a_held_particle_in_a_linear_shear() {
    // u = (S z, 0, 0): ω = ∇ × u = (0, S, 0); a particle held at rest has slip (S z, 0, 0)
    // and slip × ω = (0, 0, S² z): the lift V ρ C_l S² z pushes it up (towards faster fluid).
    let (h, d, s_rate) = (1e-3, 5e-4, 20.0);
    let fluid = moving_water([6, 6, 12], h, |[_, _, k]| {
        [s_rate * (k as f64 - 0.5) * h, 0.0, 0.0]
    });
    let mut cloud = held_bead(d, 2500.0);
    let lift = FluidForces {
        lift: Some(LiftModel::SaffmanMei),
        ..FluidForces::default()
    };
    let mut coupling = DragLawCoupling::new(dpmfoam(lift), &fluid, &cloud).unwrap();
    coupling.particle_forces(&fluid, &mut cloud, 1e-4);
    // the particle's cell (k = 6, centre z = 6.5 mm) gives u and ω
    let z = 6.5e-3;
    let slip = s_rate * z;
    let mu = RHO * NU;
    let cl = saffman_mei_cl(RHO * slip * d / mu, RHO * s_rate * d * d / mu);
    let want = PI * d * d * d / 6.0 * RHO * cl * s_rate * s_rate * z;
    let f = coupling.last.hydrodynamic_force;
    assert!((f[2] - want).abs() < 1e-9 * want, "{f:?} against {want}");
    assert!(f[0] > 0.0 && f[1].abs() < 1e-12 * want);
    // the fluid receives the lift's reaction with the drag's
    let e = coupling.last;
    for a in 0..3 {
        assert!((e.drag_on_particles[a] + e.drag_on_fluid[a]).abs() < 1e-12 * f[0]);
    }
}

#[test]
fn pressure_gradient_and_virtual_mass_read_the_convective_acceleration() {
    // u = (a, 0, S x): (u·∇)u = (0, 0, a S), uniform; a held particle feels
    // (1 + Cvm) m (ρ/ρ_p) a S along z besides its drag, DPMFoam's explicit coupled force.
    let (h, d, rho_p, a, s_rate) = (1e-3, 5e-4, 2500.0, 0.05, 20.0);
    let fluid = moving_water([6, 6, 12], h, |[i, _, _]| {
        [a, 0.0, s_rate * (i as f64 - 0.5) * h]
    });
    let mut cloud = held_bead(d, rho_p);
    let mut coupling = DragLawCoupling::new(dpmfoam(virtual_mass(0.5)), &fluid, &cloud).unwrap();
    coupling.particle_forces(&fluid, &mut cloud, 1e-4);
    let m = rho_p * PI * d * d * d / 6.0;
    let want = 1.5 * m * RHO / rho_p * a * s_rate;
    let explicit = coupling.last.hydrodynamic_force - coupling.drag_forces()[0];
    assert!(
        (explicit[2] - want).abs() < 1e-9 * want,
        "{explicit:?} against {want}"
    );
    assert!(explicit[0].abs() < 1e-12 * want && explicit[1].abs() < 1e-12 * want);
}

#[test]
fn the_time_derivative_of_the_fluid_acceleration_is_dpmfoams_zero() {
    // The water goes from rest to a uniform u = (0.1, 0, 0) between two force evaluations
    // 10 ms apart: DPMFoam's DUcDt has no time derivative (its ddt is evaluated after
    // Uc.oldTime() = Uc), and a uniform flow has no convective acceleration, so pressureGradient
    // and virtualMass add nothing (with the time derivative they would add 1.5 m (ρ/ρ_p) 10 m/s²).
    let (h, d, rho_p, dt) = (1e-3, 5e-4, 2500.0, 1e-2);
    let mut fluid = water([6, 6, 12], h);
    let mut cloud = held_bead(d, rho_p);
    let mut coupling = DragLawCoupling::new(dpmfoam(virtual_mass(0.5)), &fluid, &cloud).unwrap();
    coupling.particle_forces(&fluid, &mut cloud, dt);
    fluid.velocity_mut()[0].iter_mut().for_each(|u| *u = 0.1);
    coupling.particle_forces(&fluid, &mut cloud, dt);
    let explicit = coupling.last.hydrodynamic_force - coupling.drag_forces()[0];
    let m = rho_p * PI * d * d * d / 6.0;
    assert!(
        explicit.norm() <= 1e-9 * m * 10.0,
        "{explicit:?}: the fluid's change in time entered DUcDt"
    );
}
