//! Free spheres settling in a fully periodic box, run as `fsimFoam` runs a case
//! (`box_case.rs`: [`Simulation::step`], with no-slip, stress integral, lubrication and
//! virtual mass, DEM, settling drive). For the tests of freely moving spheres and
//! `examples/direct_explore.rs`.
#![allow(dead_code)]

use super::box_case::{step, BoxCase};
use fsim::coupling::direct::SedimentationReport;
use fsim::fluid::{FluidSolver, TimeScheme};
use fsim::simulation::Simulation;

/// A fully periodic box of `n` cells of size `h` per axis with free spheres, gravity −y.
pub struct Settler {
    pub sim: Simulation,
}

/// The direct model's settings a settler's case may give (`constant/couplingProperties`).
#[derive(Clone, Copy, Debug)]
pub struct SettlerOptions {
    /// `direct { interpolation …; }`: `"cubic"` or `"linear"`.
    pub interpolation: &'static str,
    /// `virtualMass`; the default when `None`.
    pub virtual_mass: Option<f64>,
}

impl Default for SettlerOptions {
    fn default() -> Self {
        SettlerOptions {
            interpolation: "cubic",
            virtual_mass: None,
        }
    }
}

impl Settler {
    /// Spheres `(centre, diameter)` of density `rho_p` in a fluid of `rho_f` and `nu`, with
    /// the default direct-model settings.
    pub fn new(
        n: [usize; 3],
        h: f64,
        spheres: &[([f64; 3], f64)],
        rho_p: f64,
        rho_f: f64,
        nu: f64,
        scheme: TimeScheme,
    ) -> Settler {
        let options = SettlerOptions::default();
        Self::with_options(n, h, spheres, (rho_p, rho_f, nu), scheme, options)
    }

    /// As [`Self::new`] with the direct model's `options`; `densities_and_nu` is
    /// `(rho_p, rho_f, nu)`.
    pub fn with_options(
        n: [usize; 3],
        h: f64,
        spheres: &[([f64; 3], f64)],
        (rho_p, rho_f, nu): (f64, f64, f64),
        scheme: TimeScheme,
        options: SettlerOptions,
    ) -> Settler {
        let d = spheres[0].1;
        assert!(
            spheres.iter().all(|s| s.1 == d),
            "one diameter for every sphere"
        );
        let m = rho_p * std::f64::consts::PI * d * d * d / 6.0;
        let virtual_mass = options
            .virtual_mass
            .map_or(String::new(), |c| format!("virtualMass {c:e};\n"));
        let case = BoxCase {
            cells: n,
            h,
            walls: [false; 3],
            wall_velocity: [0.0; 3],
            fluid: (rho_f, nu),
            gravity: [0.0, -9.81, 0.0],
            scheme,
            initial_velocity: [0.0; 3],
            mean_velocity: None,
            coupling: format!(
                "model direct;\n{virtual_mass}direct {{ interpolation {}; }}\n",
                options.interpolation
            ),
            spheres: spheres.iter().map(|s| s.0).collect(),
            diameter: d,
            rho_p,
            // soft contacts: only a backstop here
            kn: 1e-3 * m / (1e-4 * 1e-4),
        };
        Settler {
            sim: case.simulation(),
        }
    }

    /// One step of `dt` as `fsimFoam` takes it.
    pub fn step(&mut self, dt: f64) {
        step(&mut self.sim, dt);
    }

    /// The fluid (its scheme may be changed before the first step).
    pub fn fluid(&mut self) -> &mut FluidSolver {
        &mut self.sim.fluid
    }

    /// The settling monitor after the last step.
    pub fn report(&self) -> SedimentationReport {
        let direct = self.sim.coupling.direct().expect("model direct");
        direct.settling.expect("a step was taken")
    }
}

/// Stokes' terminal velocity of a sphere of diameter `d` (m/s).
pub fn stokes_velocity(d: f64, rho_p: f64, rho_f: f64, nu: f64) -> f64 {
    2.0 * (rho_p - rho_f) * 9.81 * (d / 2.0).powi(2) / (9.0 * rho_f * nu)
}
