//! Validation of the DEM engine against analytic collision results.

use fsim::Vec3;
use std::f64::consts::PI;

use fsim::particles::{
    random_packing, Dem, DemConfig, DomainBox, FaceCondition, PairModel, ParticleState,
    TangentialRule, WallModel,
};

const D: f64 = 1e-3;
const RHO: f64 = 2500.0;

fn mass() -> f64 {
    RHO * PI * D * D * D / 6.0
}

fn config(pair: PairModel, wall: WallModel) -> DemConfig {
    let mut c = DemConfig::new(pair, wall);
    c.gravity = Vec3::repeat(0.0);
    c
}

fn index_of(dem: &Dem, id: u64) -> usize {
    dem.particles().id.iter().position(|&i| i == id).unwrap()
}

/// Two equal spheres meet head on with relative speed `v`; returns (measured restitution,
/// measured contact time).
fn head_on(pair: PairModel, v: f64, h_over_tc: f64, periodic_across: bool) -> (f64, f64) {
    // no wall model here: faces rebound (never reached) unless periodic
    let mut dom = DomainBox::uniform(
        [0.0; 3],
        [0.01; 3],
        FaceCondition::Rebound { e: 1.0, mu: 0.0 },
    );
    let mut p = ParticleState::default();
    if periodic_across {
        // the spheres meet across the x faces
        dom.faces = [FaceCondition::Periodic; 6];
        p.push(1, [0.0096, 0.005, 0.005], D, RHO);
        p.push(2, [0.0004 + 0.0002, 0.005, 0.005], D, RHO);
        p.velocity[0] = Vec3::new(0.5 * v, 0.0, 0.0);
        p.velocity[1] = Vec3::new(-0.5 * v, 0.0, 0.0);
    } else {
        p.push(1, [0.0043, 0.005, 0.005], D, RHO);
        p.push(2, [0.0057, 0.005, 0.005], D, RHO);
        p.velocity[0] = Vec3::new(0.5 * v, 0.0, 0.0);
        p.velocity[1] = Vec3::new(-0.5 * v, 0.0, 0.0);
    }
    let mut dem = Dem::new(config(pair, WallModel::None), dom, p).unwrap();
    let h = dem.collision_time_step() * h_over_tc;
    let mut contact_steps = 0usize;
    let mut touched = false;
    for _ in 0..2_000_000 {
        dem.step(h);
        let f = dem.particles().contact_force[0][0];
        if f != 0.0 {
            contact_steps += 1;
            touched = true;
        } else if touched {
            break;
        }
    }
    assert!(touched);
    let (a, b) = (index_of(&dem, 1), index_of(&dem, 2));
    let u = dem.particles().velocity[a][0] - dem.particles().velocity[b][0];
    (-u / v, contact_steps as f64 * h)
}

/// Linear model: the restitution measured equals the one given, ±1%.
#[test]
fn head_on_linear_restitution_matches_input() {
    for e in [0.3, 0.5, 0.8, 0.95] {
        let model = PairModel::LinearSpringDashpot {
            kn: 1000.0,
            restitution: e,
            kt: 2.0 / 7.0 * 1000.0,
            mu: 0.5,
            tangential_damping_ratio: 0.5,
            collision_resolution_steps: 50.0,
        };
        // at the default sub-step t_c/50 the onset of contact inside a step costs ~1.5%;
        // at t_c/250 the error is well inside 1%
        let (coarse, _) = head_on(model.clone(), 1.0, 1.0, false);
        let (measured, _) = head_on(model.clone(), 1.0, 0.2, false);
        eprintln!("linear e = {e}: measured {measured:.6} (h = t_c/250), {coarse:.6} (h = t_c/50)");
        assert!(
            (measured - e).abs() < 0.01 * e,
            "e = {e}, measured {measured}"
        );
        // through a periodic boundary too
        let (measured, _) = head_on(model, 0.4, 0.2, true);
        assert!(
            (measured - e).abs() < 0.01 * e,
            "periodic: e = {e}, measured {measured}"
        );
    }
}

/// Hertz model without damping: the contact time equals Hertz theory, ±2%.
/// Hertz (1882); Johnson, *Contact Mechanics* (1985) §11.4:
/// δ_max = (15 M v² / (16 E* √R))^{2/5}, t_c = 2 δ_max/v ∫₀¹ dx/√(1 − x^{5/2})
/// = 2.9432 δ_max / v, with M, R the reduced mass and radius, E* = E/(2(1−ν²)) for equal
/// materials and v the approach speed.
#[test]
fn head_on_hertz_contact_time_matches_hertz_theory() {
    let (e_mod, nu) = (1e7, 0.3);
    let model = PairModel::SpringSliderDashpot {
        youngs_modulus: e_mod,
        poissons_ratio: nu,
        alpha: 0.0,
        b: 1.5,
        mu: 0.3,
        collision_resolution_steps: 50.0,
        tangential: TangentialRule::CappedSpring,
    };
    for v in [0.2, 1.0, 3.0] {
        let (e, tc) = head_on(model.clone(), v, 0.1, false);
        let e_star = e_mod / (2.0 * (1.0 - nu * nu));
        let (m, r) = (0.5 * mass(), 0.25 * D);
        let delta_max = (15.0 * m * v * v / (16.0 * e_star * r.sqrt())).powf(0.4);
        let theory = 2.9432 * delta_max / v;
        eprintln!(
            "Hertz v = {v}: t_c = {tc:.6e}, theory {theory:.6e}, ratio {:.5}, e = {e:.6}",
            tc / theory
        );
        assert!((tc / theory - 1.0).abs() < 0.02);
        assert!(
            (e - 1.0).abs() < 0.01,
            "elastic Hertz contact must restitute fully: {e}"
        );
    }
}

/// A sphere hits a floor obliquely (normal speed `vn`, tangential `vt`, no spin); returns
/// (tangential velocity after, ω_y r after, normal velocity after).
fn oblique(wall: WallModel, vn: f64, vt: f64, h_over_tc: f64) -> (f64, f64, f64) {
    let dom = DomainBox::walled([0.0; 3], [0.02, 0.01, 0.01]);
    let mut p = ParticleState::default();
    p.push(1, [0.005, 0.005, 0.5 * D + 1e-5], D, RHO);
    p.velocity[0] = Vec3::new(vt, 0.0, -vn);
    let pair = PairModel::linear(1000.0, 0.5, 0.3);
    let mut dem = Dem::new(config(pair, wall), dom, p).unwrap();
    let h = dem.collision_time_step() * h_over_tc;
    let mut touched = false;
    for _ in 0..2_000_000 {
        dem.step(h);
        if dem.particles().contact_force[0][2] != 0.0 {
            touched = true;
        } else if touched {
            break;
        }
    }
    assert!(touched);
    let p = dem.particles();
    (
        p.velocity[0][0],
        p.angular_velocity[0][1] * 0.5 * D,
        p.velocity[0][2],
    )
}

/// Oblique impact with Coulomb friction (rigid-body impulse analysis: Maw, Barber & Fawcett
/// 1976, Wear 38:101; Thornton, *Granular Dynamics, Contact Mechanics and Particle System
/// Simulations*, Springer 2015, ch. 6). For a solid sphere (I = m r²/10·4 = 2/5 m r²) hitting
/// a wall with restitution e, normal speed v_n and tangential speed v_t (no spin), the
/// contact point's slip changes by −(7/2) × (tangential impulse)/m.
///
/// * Gross sliding (friction at μF_n throughout) whenever v_t/v_n ≥ (7/2) μ (1 + e):
///   v_t' = v_t − μ(1+e) v_n, ω' r = (5/2) μ (1+e) v_n — independent of the tangential spring.
/// * Small angle, linear spring with k_t/k_n = 2/7 and no tangential damping: the tangential
///   oscillation of the contact point (effective mass 2m/7) has the same period as the normal
///   one, so for e = 1 the slip completes half a period and reverses exactly (tangential
///   restitution β = 1, Schäfer, Dippel & Wolf 1996, J. Phys. I France 6:5) provided it never
///   slides: k_t ξ ≤ μ k_n δ at all times ⇔ v_t/v_n ≤ (7/2) μ. Then the tangential impulse is
///   (4/7) m v_t: v_t' = (3/7) v_t and ω' r = (10/7) v_t.
#[test]
fn oblique_wall_impact_follows_sliding_and_sticking_limits() {
    let mu = 0.2;
    let linear = WallModel::LinearSpringDashpot {
        kn: 1000.0,
        restitution: 1.0,
        kt: 2.0 / 7.0 * 1000.0,
        mu,
        tangential_damping_ratio: 0.0,
        collision_resolution_steps: 50.0,
    };
    let vn = 1.0;
    // gross sliding: v_t/v_n = 2 ≥ 7μ = 1.4
    let (vt1, wr, vn1) = oblique(linear.clone(), vn, 2.0, 0.1);
    eprintln!("linear sliding: vt' = {vt1:.5} (1.6), ωr = {wr:.5} (1.0), vn' = {vn1:.5}");
    assert!((vt1 - (2.0 - 2.0 * mu * vn)).abs() < 0.01 * 1.6);
    assert!((wr - 5.0 * mu * vn).abs() < 0.01 * 1.0);
    assert!((vn1 - vn).abs() < 0.01);
    // sticking: v_t/v_n = 0.5 ≤ 3.5μ = 0.7
    let vt = 0.5;
    let (vt1, wr, _) = oblique(linear, vn, vt, 0.1);
    eprintln!(
        "linear sticking: vt' = {vt1:.5} ({:.5}), ωr = {wr:.5} ({:.5})",
        3.0 / 7.0 * vt,
        10.0 / 7.0 * vt
    );
    assert!((vt1 - 3.0 / 7.0 * vt).abs() < 0.01 * 3.0 / 7.0 * vt);
    assert!((wr - 10.0 / 7.0 * vt).abs() < 0.01 * 10.0 / 7.0 * vt);

    // Hertz–Mindlin with the capped spring: gross sliding limit (α = 0 ⇒ e = 1)
    let hertz = |rule| WallModel::SpringSliderDashpot {
        youngs_modulus: 1e8,
        poissons_ratio: 0.3,
        particle_youngs_modulus: 1e7,
        particle_poissons_ratio: 0.3,
        alpha: 0.0,
        b: 1.5,
        mu,
        collision_resolution_steps: 50.0,
        tangential: rule,
    };
    let (vt1, wr, vn1) = oblique(hertz(TangentialRule::CappedSpring), vn, 3.0, 0.1);
    eprintln!("Hertz capped sliding: vt' = {vt1:.5} (2.6), ωr = {wr:.5} (1.0), vn' = {vn1:.5}");
    assert!((vt1 - (3.0 - 2.0 * mu * vn)).abs() < 0.01 * 2.6);
    assert!((wr - 5.0 * mu * vn).abs() < 0.01);
    assert!((vn1 - vn).abs() < 0.01);
    // DPMFoam's rule never exceeds the Coulomb impulse and gives less in this regime, the
    // more so the finer the step (the spring restarts from zero after each slip).
    let (vt_coarse, _, _) = oblique(hertz(TangentialRule::DpmFoamReset), vn, 3.0, 1.0);
    let (vt_fine, _, _) = oblique(hertz(TangentialRule::DpmFoamReset), vn, 3.0, 0.1);
    let (i_coarse, i_fine) = (3.0 - vt_coarse, 3.0 - vt_fine);
    eprintln!("DPMFoam rule: tangential impulse/m = {i_coarse:.5} (Δt_c), {i_fine:.5} (Δt_c/10); Coulomb 0.4");
    assert!(i_coarse <= 0.4 * 1.001 && i_fine <= 0.4 * 1.001);
    assert!(i_fine < i_coarse);
}

fn settling_case(seed: u64) -> (DemConfig, DomainBox, ParticleState) {
    let hi = [6.0 * D, 6.0 * D, 14.0 * D];
    let centres = random_packing([0.0; 3], hi, D, 0.2, seed).unwrap();
    let mut p = ParticleState::with_capacity(centres.len());
    for (k, x) in centres.iter().enumerate() {
        p.push(k as u64 + 1, *x, D, RHO);
    }
    let kn = 200.0;
    let pair = PairModel::LinearSpringDashpot {
        kn,
        restitution: 0.5,
        kt: 2.0 / 7.0 * kn,
        mu: 0.5,
        tangential_damping_ratio: 0.5,
        collision_resolution_steps: 50.0,
    };
    let wall = WallModel::LinearSpringDashpot {
        kn,
        restitution: 0.5,
        kt: 2.0 / 7.0 * kn,
        mu: 0.5,
        tangential_damping_ratio: 0.5,
        collision_resolution_steps: 50.0,
    };
    let mut c = DemConfig::new(pair, wall);
    c.gravity = Vec3::new(0.0, 0.0, -9.81);
    (c, DomainBox::walled([0.0; 3], hi), p)
}

/// A packing settles under gravity to rest with overlaps under 1% of d; during the initial
/// collision-free fall the total energy never increases (beyond rounding).
#[test]
fn settling_packing_comes_to_rest_with_small_overlaps() {
    let (cfg, dom, p) = settling_case(3);
    let n = p.len();
    let mut dem = Dem::new(cfg, dom, p).unwrap();
    let h = dem.collision_time_step();
    let energy = |dem: &Dem| {
        let (kt, kr) = dem.kinetic_energy();
        kt + kr + dem.potential_energy()
    };
    let e0 = energy(&dem);
    let mut e_prev = e0;
    let mut free_steps = 0;
    while dem
        .particles()
        .contact_force
        .iter()
        .all(|f| *f == Vec3::repeat(0.0))
    {
        dem.step(h);
        let e = energy(&dem);
        if dem
            .particles()
            .contact_force
            .iter()
            .all(|f| *f == Vec3::repeat(0.0))
        {
            assert!(
                e <= e_prev + 1e-12 * e0.abs(),
                "energy rose during free fall: {e_prev} -> {e}"
            );
            free_steps += 1;
        }
        e_prev = e;
    }
    assert!(free_steps > 10, "free-fall stretch of {free_steps} steps");
    let weight_scale = n as f64 * mass() * 9.81 * D;
    let t_end = 0.6;
    let mut max_overlap: f64 = 0.0;
    while dem.time() < t_end {
        dem.step(h);
        max_overlap = max_overlap.max(dem.max_overlap_ratio());
    }
    let (kt, kr) = dem.kinetic_energy();
    let v_max = dem
        .particles()
        .velocity
        .iter()
        .map(|v| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt())
        .fold(0.0, f64::max);
    eprintln!(
        "settling: {n} particles, {} steps, free fall {free_steps} steps, KE/(N m g d) = {:.3e}, v_max = {v_max:.3e} m/s, max overlap/d = {:.3e} (final {:.3e}), rebuilds {}",
        dem.steps(),
        (kt + kr) / weight_scale,
        max_overlap,
        dem.max_overlap_ratio(),
        dem.list_rebuilds()
    );
    assert!((kt + kr) / weight_scale < 1e-6, "not at rest");
    assert!(dem.max_overlap_ratio() < 0.01);
    // impacts while falling are deeper; bounded well below a blow-up
    assert!(max_overlap < 0.05);
}

/// Saving and restoring mid-run continues bit for bit.
#[test]
fn restart_mid_run_continues_bit_for_bit() {
    let (cfg, dom, mut p) = settling_case(11);
    for k in 0..p.len() {
        let s = (k as f64 * 0.618).fract() - 0.5;
        p.velocity[k] = Vec3::new(0.3 * s, -0.2 * s, 0.1);
    }
    let mut dem = Dem::new(cfg.clone(), dom.clone(), p).unwrap();
    let h = dem.collision_time_step();
    for _ in 0..15000 {
        dem.step(h);
    }
    let snap = dem.snapshot();
    assert!(
        snap.history.pairs.len() > 50,
        "contact-rich: {} springs",
        snap.history.pairs.len()
    );
    let rebuilds_before = dem.list_rebuilds();
    for _ in 0..3000 {
        dem.step(h);
    }
    assert!(
        dem.list_rebuilds() > rebuilds_before,
        "a rebuild happens after the restart point"
    );
    let mut again = Dem::restore(cfg, dom, &snap).unwrap();
    for _ in 0..3000 {
        again.step(h);
    }
    assert_eq!(again.particles(), dem.particles());
    assert_eq!(again.snapshot(), dem.snapshot());
}

/// Sub-cycling: with a fluid step 20× longer than the contact, `advance` splits it by
/// DPMFoam's rule and the elastic Hertz collision still restitutes fully (±1%).
#[test]
fn advance_subcycles_a_long_fluid_step() {
    let model = PairModel::SpringSliderDashpot {
        youngs_modulus: 1e7,
        poissons_ratio: 0.3,
        alpha: 0.0,
        b: 1.5,
        mu: 0.3,
        collision_resolution_steps: 12.0,
        tangential: TangentialRule::DpmFoamReset,
    };
    let dom = DomainBox::uniform([0.0; 3], [0.01; 3], FaceCondition::Periodic);
    let mut p = ParticleState::default();
    p.push(1, [0.0040, 0.005, 0.005], D, RHO);
    p.push(2, [0.0060, 0.005, 0.005], D, RHO);
    p.velocity[0] = Vec3::new(0.5, 0.0, 0.0);
    p.velocity[1] = Vec3::new(-0.5, 0.0, 0.0);
    let mut dem = Dem::new(config(model, WallModel::None), dom, p).unwrap();
    // the spheres meet after 1 ms and touch for ~0.1 ms; across the periodic boundary they
    // would meet again only after another 8 ms
    let dt_fluid = 2e-3;
    let n = dem.substep_count(dt_fluid);
    assert!(n >= 100, "sub-steps {n}");
    assert_eq!(dem.advance(dt_fluid), n);
    let (a, b) = (index_of(&dem, 1), index_of(&dem, 2));
    let u = dem.particles().velocity[a][0] - dem.particles().velocity[b][0];
    eprintln!("{n} sub-steps, restitution {:.5}", -u);
    assert!((-u - 1.0).abs() < 0.01);
}

/// DPMFoam's Hertzian damping η_N = α √(M k_N) δ^{1/4} (Tsuji, Tanaka & Ishida 1992, Powder
/// Technol. 71:239) makes the restitution independent of the impact speed: the equation of
/// motion in δ/δ_max and t/t_c has no speed left in it. Measured at three speeds: equal
/// within 1%, and below 1.
#[test]
fn hertz_damping_gives_speed_independent_restitution() {
    let model = PairModel::SpringSliderDashpot {
        youngs_modulus: 1e7,
        poissons_ratio: 0.3,
        alpha: 0.3,
        b: 1.5,
        mu: 0.3,
        collision_resolution_steps: 50.0,
        tangential: TangentialRule::CappedSpring,
    };
    let e: Vec<f64> = [0.1, 0.5, 2.0]
        .iter()
        .map(|&v| head_on(model.clone(), v, 0.1, false).0)
        .collect();
    eprintln!("alpha = 0.3: restitution {e:?}");
    assert!(e.iter().all(|&x| x < 0.95 && x > 0.3));
    assert!((e[0] - e[2]).abs() < 0.01 * e[1] && (e[1] - e[2]).abs() < 0.01 * e[1]);
}
