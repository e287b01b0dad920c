//! The particles of a run: the DEM engine, what the log says about them, and their step.

use crate::case::Cloud;
use crate::error::FsimError;
use crate::output::ParticleFields;
use crate::particles::Dem;
use crate::Vec3;

/// The cloud of a run: the DEM engine and what the log says about it.
pub struct Particles {
    pub dem: Dem,
    /// `pairModel` and `wallModel` as the case names them.
    pub pair_model: String,
    pub wall_model: String,
    /// Collision sub-steps of the last fluid step.
    pub substeps: usize,
    /// Notes from reading the cloud (ignored keywords, settings without effect).
    pub notes: Vec<String>,
}

/// What the cloud did in one fluid step, for the log and the monitor.
#[derive(Clone, Copy, Debug)]
pub struct CloudReport {
    pub count: usize,
    /// `(Σ ½ m v², Σ ½ I ω²)`, J.
    pub kinetic_energy: (f64, f64),
    pub mean_velocity: Vec3,
    /// Largest overlap over the diameter.
    pub max_overlap: f64,
    pub substeps: usize,
    /// No contact could act: one step of free flight, contact detection skipped
    /// (`particles/dem/free_flight.rs`).
    pub free_flight: bool,
}

impl Particles {
    /// The engine of `cloud` around `dem` (fresh from the case, or restored).
    pub fn new(cloud: Cloud, dem: Dem) -> Self {
        Particles {
            dem,
            pair_model: cloud.pair_model_name,
            wall_model: cloud.wall_model_name,
            substeps: 0,
            notes: cloud.warnings,
        }
    }

    /// The engine `dem` of particles built outside a case (tests, studies).
    pub fn from_dem(dem: Dem) -> Self {
        Particles {
            dem,
            pair_model: String::new(),
            wall_model: String::new(),
            substeps: 0,
            notes: Vec::new(),
        }
    }

    /// Paper eq. 1: Newton–Euler for every particle over the fluid step `dt` (gravity,
    /// buoyancy, the external loads set, contact forces), in the engine's collision
    /// sub-steps.
    pub fn advance(&mut self, dt: f64) -> CloudReport {
        let free_before = self.dem.contact_free_steps();
        self.substeps = self.dem.advance(dt);
        CloudReport {
            count: self.dem.particles().len(),
            kinetic_energy: self.dem.kinetic_energy(),
            mean_velocity: self.dem.mean_velocity(),
            max_overlap: self.dem.max_overlap_ratio(),
            substeps: self.substeps,
            free_flight: self.dem.contact_free_steps() > free_before,
        }
    }

    /// The first particle (by index) whose velocity or position is no longer finite.
    pub fn first_diverged_index(&self) -> Option<usize> {
        let s = self.dem.particles();
        (0..s.len()).find(|&i| {
            !(s.velocity[i]
                .iter()
                .chain(&s.position[i])
                .all(|v| v.is_finite()))
        })
    }

    /// Writes the particles (id, d, U, omega, F_hydro, F_contact) to file `name` of `dir`.
    pub fn write(&self, dir: &crate::output::SafeDir, name: &str) -> Result<(), FsimError> {
        let p = self.dem.particles();
        let id: Vec<i64> = p.id.iter().map(|&i| i as i64).collect();
        ParticleFields {
            positions: &p.position,
            id: &id,
            d: &p.diameter,
            velocity: &p.velocity,
            omega: &p.angular_velocity,
            hydrodynamic_force: &p.external_force,
            contact_force: &p.contact_force,
        }
        .write(dir, name)
        .map_err(|e| FsimError::run(e.to_string()))
    }
}
