//! One sphere settling with the direct model, by hand (the tests' harness,
//! `tests/support/settler.rs`, which runs the case as `fsimFoam` does): what the time scheme,
//! the step, the density ratio and the settings do to it. Prints; asserts nothing (the tests
//! do).
//!
//! ```text
//! cargo run --release --example direct_explore -- [SCHEME DT STEPS RHO_P]
//! ```
//!
//! One sphere (r/h = 8, Re = 0.004) settling in a periodic box of 36 cells, v/U_Stokes ten
//! times along the run, against the periodic-array value (paper eq. 17). Defaults:
//! EulerRKC, 1e-4 s, 100 steps, ρ_p = 2000 kg/m³. The environment's `VM` (virtual mass
//! coefficient) and `INTERP` (linear, cubic) change the settings.

#[path = "../tests/support/box_case.rs"]
mod box_case;
#[path = "../tests/support/settler.rs"]
mod settler;

#[path = "../tests/support/porous_reference.rs"]
mod porous_reference;

use fsim::fluid::TimeScheme;
use porous_reference::sangani_acrivos_k;
use settler::{stokes_velocity, Settler, SettlerOptions};

const CELLS: usize = 36;
const H: f64 = 1.25e-4;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |k: usize, default: &str| args.get(k).cloned().unwrap_or(default.to_string());
    let scheme = TimeScheme::from_name(&arg(0, "EulerRKC")).expect("SCHEME: a time scheme's name");
    let dt: f64 = arg(1, "1e-4").parse().expect("DT: a number");
    let steps: usize = arg(2, "100").parse().expect("STEPS: a whole number");
    let rho_p: f64 = arg(3, "2000").parse().expect("RHO_P: a number");
    let mut options = SettlerOptions::default();
    if let Ok(c) = std::env::var("VM") {
        options.virtual_mass = Some(c.parse().expect("VM: a number"));
    }
    if let Ok(name) = std::env::var("INTERP") {
        options.interpolation = match name.as_str() {
            "linear" => "linear",
            "cubic" => "cubic",
            _ => panic!("INTERP: linear or cubic"),
        };
    }
    let d = 16.0 * H;
    let centre = [18.3 * H, 18.0 * H, 17.8 * H];
    let fluid = (rho_p, 1000.0, 1e-3);
    let mut s = Settler::with_options([CELLS; 3], H, &[(centre, d)], fluid, scheme, options);
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
                s.sim.time.time,
                r.settling_velocity / us,
                r.momentum[1],
                r.momentum_scale
            );
        }
    }
}
