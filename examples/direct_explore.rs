//! Explorations of the direct model's coupled step by hand (the harness of the tests,
//! `tests/support/settler.rs`): what the time scheme, the step, the density ratio and the
//! stress integral's settings do to one sphere. Prints; asserts nothing (the tests do).
//!
//! ```text
//! cargo run --release --example direct_explore -- settling [SCHEME DT STEPS RHO_P]
//! cargo run --release --example direct_explore -- balance  [SCHEME DT STEPS]
//! ```
//!
//! `settling`: one sphere (r/h = 8, Re = 0.004) settling in a periodic box, v/U_Stokes ten
//! times along the run, against the periodic-array value (paper eq. 17). `balance`: the same
//! sphere held fixed while a uniform body force `b` drives the fluid; at steady state it
//! carries all of it, `F = ρ b L³`. Defaults: EulerRKC, 1e-4 s, 100 steps, ρ_p = 2000 kg/m³.
//! The environment's `VM` (virtual mass coefficient), `INTERP` (linear, cubic) and `OFFSET`
//! (integration surface, cells) change the settings.

#[path = "../tests/support/settler.rs"]
mod settler;

use fsim::coupling::direct::{sangani_acrivos_k, DirectSettings, Interpolation, MotionSettings};
use fsim::fluid::TimeScheme;
use settler::{stokes_velocity, Settler};

const CELLS: usize = 36;
const H: f64 = 1.25e-4;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |k: usize, default: &str| args.get(k).cloned().unwrap_or(default.to_string());
    let scheme = TimeScheme::from_name(&arg(1, "EulerRKC")).expect("SCHEME: a time scheme's name");
    let dt: f64 = arg(2, "1e-4").parse().expect("DT: a number");
    let steps: usize = arg(3, "100").parse().expect("STEPS: a whole number");
    match args.first().map(String::as_str) {
        Some("settling") => {
            let rho_p: f64 = arg(4, "2000").parse().expect("RHO_P: a number");
            settling(scheme, dt, steps, rho_p)
        }
        Some("balance") => balance(scheme, dt, steps),
        _ => eprintln!("usage: direct_explore settling|balance [SCHEME DT STEPS [RHO_P]]"),
    }
}

/// The default settings with the environment's changes.
fn settings() -> (DirectSettings, MotionSettings) {
    let var = |name: &str| std::env::var(name).ok();
    let mut direct = DirectSettings::default();
    let mut motion = MotionSettings::default();
    if let Some(c) = var("VM") {
        motion.virtual_mass = c.parse().expect("VM: a number");
    }
    if let Some(name) = var("INTERP") {
        direct.integral.interpolation =
            Interpolation::from_name(&name).expect("INTERP: linear or cubic");
    }
    if let Some(offset) = var("OFFSET") {
        direct.integral.surface_offset = offset.parse().expect("OFFSET: a number");
    }
    (direct, motion)
}

/// One sphere of 16 cells' diameter off the lattice's symmetry, in a box of 36 cells.
fn sphere(rho_p: f64, scheme: TimeScheme) -> (Settler, f64) {
    let d = 16.0 * H;
    let centre = [18.3 * H, 18.0 * H, 17.8 * H];
    let fluid = (rho_p, 1000.0, 1e-3);
    let s = Settler::with_settings([CELLS; 3], H, &[(centre, d)], fluid, scheme, settings());
    (s, d)
}

fn settling(scheme: TimeScheme, dt: f64, steps: usize, rho_p: f64) {
    let (mut s, d) = sphere(rho_p, scheme);
    let phi = std::f64::consts::PI * d.powi(3) / 6.0 / (CELLS as f64 * H).powi(3);
    println!(
        "phi {phi:.5}, eq. 17: v/U_s = 1/K = {:.5}",
        1.0 / sangani_acrivos_k(phi)
    );
    let us = stokes_velocity(d, rho_p, 1000.0, 1e-3);
    for k in 0..steps {
        s.step(dt);
        if (k + 1) % (steps / 10).max(1) == 0 {
            let r = s.report();
            println!(
                "t = {:.4e}: v/U_s = {:.5}, momentum {:.3e} of {:.3e}",
                s.time,
                r.settling_velocity / us,
                r.momentum[1],
                r.momentum_scale
            );
        }
    }
}

fn balance(scheme: TimeScheme, dt: f64, steps: usize) {
    let (mut s, _) = sphere(2000.0, scheme);
    let b = 1.0;
    s.fluid.set_body_force([0.0, b, 0.0]);
    let l3 = (CELLS as f64 * H).powi(3);
    for k in 0..steps {
        // held: the fluid steps around the sphere, which does not move
        let loads = s.fluid_step(dt);
        if (k + 1) % (steps / 10).max(1) == 0 {
            println!(
                "step {}: F/(rho b L^3) = {:.5}, <u> = {:.4e}",
                k + 1,
                loads[0].force[1] / (1000.0 * b * l3),
                s.fluid.mean_component(1)
            );
        }
    }
}
