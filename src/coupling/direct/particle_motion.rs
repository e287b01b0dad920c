//! Freely moving spheres in the direct model: what the coupled step adds to the stress
//! integral before the DEM moves the particles.
//!
//! One fluid step `Δt` of the coupled scheme (explicit, staggered in the manner of the
//! paper's §2.1):
//!
//! ```text
//! spheres ← DEM particles (x_p, v_p, ω_p at t)           (DirectCoupling::set_particles)
//! fluid   ← t → t+Δt with no-slip on every sphere        (FluidSolver::step_with)
//! F_h, T_h ← stress integral at t+Δt (paper eq. 4–6)      (DirectCoupling::compute_loads)
//! F_ext   ← F_h + F_lub (lubrication below the grid's reach, ParticleMotion::set_loads)
//! DEM     ← t → t+Δt in collision sub-steps, with F_ext, T_h held fixed and, in each
//!           sub-step, gravity with buoyancy m (1 − ρ_f/ρ_p) g and the contacts
//!           (paper eq. 1: m dv/dt = f_g + f_h0 + f_h + f_n + f_t)
//! ```
//!
//! In a fully periodic box the mean pressure gradient of [`SettlingDrive`] is set as the
//! fluid's body force once at the start; the stress integral returns its share on each
//! particle (`f_h0`), so the mixture's momentum stays zero.
//!
//! Stability: the hydrodynamic force is lagged by one step. Its added-mass part
//! (`−C_m ρ_f V dv/dt`, with the fluid carried inside and near the sphere) then acts like a
//! feedback of gain `≈ C_m ρ_f/ρ_p` on the particle's acceleration: the explicit coupling
//! needs particles clearly heavier than the fluid (measured limit in `tests/direct_motion.rs`
//! and the README; Uhlmann 2005 reports ρ_p/ρ_f > 1.2 for his scheme). [`ParticleMotion::new`]
//! refuses density ratios below [`MIN_DENSITY_RATIO`].

use super::lubrication::{Lubrication, LubricationBox, LubricationReport};
use super::settling_drive::{fluid_mean_velocity, mixture_momentum, SettlingDrive};
use crate::case::{CaseError, Coupling};
use crate::fluid::{BoundaryConditions, FaceCondition};
use crate::grid::Grid;
use crate::particles::{Dem, ParticleState, Vec3};

/// Lowest particle-to-fluid density ratio the explicit coupling accepts.
pub const MIN_DENSITY_RATIO: f64 = 1.2;

/// Settings of the optional `lubrication` sub-dictionary of `constant/couplingProperties`:
///
/// ```text
/// lubrication
/// {
///     active      yes;     // no: contacts only
///     cutoff      1;       // ζ_c in cells: the correction acts below this gap
///     minGap      0.001;   // ζ_min / R_eff: saturation (surface roughness)
/// }
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LubricationSettings {
    pub active: bool,
    pub cutoff_cells: f64,
    pub min_gap_ratio: f64,
}

impl Default for LubricationSettings {
    fn default() -> Self {
        LubricationSettings {
            active: true,
            cutoff_cells: 1.0,
            min_gap_ratio: 1e-3,
        }
    }
}

const LUBRICATION_KEYWORDS: [&str; 3] = ["active", "cutoff", "minGap"];

impl LubricationSettings {
    /// From the case's coupling file; the defaults when it has no `lubrication` dictionary.
    pub fn from_coupling(coupling: &Coupling) -> Result<Self, CaseError> {
        let mut s = LubricationSettings::default();
        let Some(dict) = coupling.dict.as_ref() else {
            return Ok(s);
        };
        let Some(d) = dict.opt_dict("lubrication")? else {
            return Ok(s);
        };
        for entry in d.entries() {
            if !LUBRICATION_KEYWORDS.contains(&entry.keyword()) {
                return Err(CaseError::at(
                    entry.value_loc(),
                    format!(
                        "unknown keyword '{}' in lubrication; expected one of {}",
                        entry.keyword(),
                        LUBRICATION_KEYWORDS.join(", ")
                    ),
                ));
            }
        }
        s.active = d.get_bool_or("active", true)?;
        if let Some(c) = d.opt_scalar("cutoff")? {
            if !(c > 0.0 && c <= 8.0) {
                let loc = d.get_entry("cutoff")?.value_loc();
                return Err(CaseError::at(
                    loc,
                    format!("lubrication cutoff must be in (0, 8] cells, got {c}"),
                ));
            }
            s.cutoff_cells = c;
        }
        if let Some(m) = d.opt_scalar("minGap")? {
            if !(m > 0.0 && m < 1.0) {
                let loc = d.get_entry("minGap")?.value_loc();
                return Err(CaseError::at(
                    loc,
                    format!("lubrication minGap must be in (0, 1) (a fraction of R_eff), got {m}"),
                ));
            }
            s.min_gap_ratio = m;
        }
        Ok(s)
    }
}

/// What the settling monitor records after a step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SedimentationReport {
    /// Solid fraction of the free particles.
    pub phi: f64,
    /// Mean particle velocity, m/s.
    pub particle_velocity: Vec3,
    /// Mean fluid velocity over the fluid volume, m/s.
    pub fluid_velocity: Vec3,
    /// Settling velocity along gravity in the frame of zero volume flux, m/s (positive:
    /// falling).
    pub settling_velocity: f64,
    /// Total momentum of fluid and particles, kg m/s.
    pub momentum: Vec3,
    /// Momentum scale `Σ m_i |v_i|`, kg m/s (to judge the total against).
    pub momentum_scale: f64,
    /// The imposed excess mean pressure gradient, Pa/m (zero without a drive).
    pub drive_gradient: Vec3,
}

/// Lubrication, the periodic-settling drive and the settling monitor of one run.
pub struct ParticleMotion {
    lubrication: Option<Lubrication>,
    lubrication_box: LubricationBox,
    drive: Option<SettlingDrive>,
    fluid_density: f64,
    gravity: Vec3,
    box_volume: f64,
    forces: Vec<Vec3>,
    last_lubrication: LubricationReport,
}

impl ParticleMotion {
    /// For the particles of `dem` in a fluid of density `rho` (kg/m³) and viscosity `nu`
    /// (m²/s) on `grid` with conditions `bc`. Fails for free particles lighter than
    /// [`MIN_DENSITY_RATIO`] times the fluid.
    pub fn new(
        settings: LubricationSettings,
        grid: &Grid,
        bc: &BoundaryConditions,
        dem: &Dem,
        rho: f64,
        nu: f64,
    ) -> Result<Self, String> {
        let p = dem.particles();
        if let Some(i) =
            (0..p.len()).find(|&i| !p.fixed[i] && p.density[i] < MIN_DENSITY_RATIO * rho)
        {
            return Err(format!(
                "particle {} has density {} kg/m3, {:.3} times the fluid's: the direct model's \
                 explicit coupling is unstable for free particles lighter than {MIN_DENSITY_RATIO} \
                 times the fluid (added mass); fix the particles (fixedParticles yes) or use \
                 model dragLaw",
                p.id[i],
                p.density[i],
                p.density[i] / rho
            ));
        }
        let length = grid.length();
        let hi = std::array::from_fn(|a| grid.origin[a] + length[a]);
        let periodic: [bool; 3] =
            std::array::from_fn(|a| matches!(bc.faces[2 * a], FaceCondition::Periodic));
        let walls: [bool; 6] =
            std::array::from_fn(|f| matches!(bc.faces[f], FaceCondition::Wall { .. }));
        let h = grid.h.iter().cloned().fold(0.0, f64::max);
        let lubrication = settings.active.then(|| {
            let mut l = Lubrication::new(rho * nu, settings.cutoff_cells * h);
            l.min_gap_ratio = settings.min_gap_ratio;
            l
        });
        let box_volume = length[0] * length[1] * length[2];
        let gravity = dem.config().gravity;
        Ok(ParticleMotion {
            lubrication,
            lubrication_box: LubricationBox {
                lo: grid.origin,
                hi,
                periodic,
                walls,
            },
            drive: SettlingDrive::new(p, rho, gravity, periodic, box_volume),
            fluid_density: rho,
            gravity,
            box_volume,
            forces: Vec::new(),
            last_lubrication: LubricationReport::default(),
        })
    }

    /// The periodic-settling drive, when the box needs one.
    pub fn drive(&self) -> Option<&SettlingDrive> {
        self.drive.as_ref()
    }

    /// The fluid's body force per unit mass, m/s² (the drive's, or zero).
    pub fn fluid_body_force(&self) -> Vec3 {
        self.drive
            .map(|d| d.fluid_acceleration())
            .unwrap_or([0.0; 3])
    }

    /// Sets the DEM's external loads for the coming step `dt`: the hydrodynamic `forces` and
    /// `torques` (index order of [`Dem::particles`]) plus the lubrication correction.
    pub fn set_loads(
        &mut self,
        dem: &mut Dem,
        forces: impl Iterator<Item = (Vec3, Vec3)>,
        dt: f64,
    ) -> LubricationReport {
        let n = dem.particles().len();
        self.forces.clear();
        self.forces.resize(n, [0.0; 3]);
        self.last_lubrication = match self.lubrication.as_mut() {
            Some(l) => l.add_forces(dem.particles(), &self.lubrication_box, dt, &mut self.forces),
            None => LubricationReport {
                active: 0,
                min_gap_ratio: f64::INFINITY,
            },
        };
        let (f_ext, t_ext) = dem.external_loads_mut();
        for (i, (f, t)) in forces.take(n).enumerate() {
            for a in 0..3 {
                f_ext[i][a] = f[a] + self.forces[i][a];
                t_ext[i][a] = t[a];
            }
        }
        self.last_lubrication
    }

    /// The lubrication of the last [`Self::set_loads`].
    pub fn last_lubrication(&self) -> LubricationReport {
        self.last_lubrication
    }

    /// Settling velocity and momentum from the fluid's box-mean velocity and the particles.
    pub fn sedimentation(&self, box_mean_velocity: Vec3, p: &ParticleState) -> SedimentationReport {
        let free: Vec<usize> = (0..p.len()).filter(|&i| !p.fixed[i]).collect();
        let solid: f64 = free.iter().map(|&i| p.mass(i) / p.density[i]).sum();
        let phi = solid / self.box_volume;
        let mut vp = [0.0; 3];
        let mut scale = 0.0;
        for &i in &free {
            let v = p.velocity[i];
            for a in 0..3 {
                vp[a] += v[a] / free.len().max(1) as f64;
            }
            scale += p.mass(i) * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        }
        let uf = fluid_mean_velocity(self.box_volume, box_mean_velocity, p);
        let g_norm = self.gravity.iter().map(|g| g * g).sum::<f64>().sqrt();
        let settling = if g_norm > 0.0 {
            let vm = SettlingDrive::settling_velocity(vp, uf, phi);
            (0..3).map(|a| vm[a] * self.gravity[a]).sum::<f64>() / g_norm
        } else {
            0.0
        };
        SedimentationReport {
            phi,
            particle_velocity: vp,
            fluid_velocity: uf,
            settling_velocity: settling,
            momentum: mixture_momentum(self.fluid_density, self.box_volume, box_mean_velocity, p),
            momentum_scale: scale,
            drive_gradient: self.drive.map(|d| d.gradient).unwrap_or([0.0; 3]),
        }
    }
}
