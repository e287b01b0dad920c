//! The DEM engine's settings ([`DemConfig`]) and the checks of settings, box and particles
//! that [`Dem::new`](super::Dem::new) makes before anything runs: each names the keyword or
//! the particle at fault.

use super::contact_model::{PairModel, WallModel};
use super::dem_error::DemError;
use super::domain_box::{DomainBox, FaceCondition};
use super::neighbour_list::wall_distance;
use super::particle_state::ParticleState;
use crate::Vec3;

/// Engine settings besides the particles and the box.
#[derive(Clone, Debug, PartialEq)]
pub struct DemConfig {
    pub pair_model: PairModel,
    pub wall_model: WallModel,
    /// Gravitational acceleration, m/s².
    pub gravity: Vec3,
    /// Density of the surrounding fluid for buoyancy, kg/m³ (0 in vacuum).
    pub fluid_density: f64,
    /// Verlet skin as a fraction of the largest diameter.
    pub skin_fraction: f64,
    /// Largest initial overlap accepted, as a fraction of the (smaller) diameter.
    pub overlap_tolerance: f64,
    /// Optional upper bound on the collision sub-step, s (DPMFoam's rule alone gives one
    /// huge sub-step when everything is at rest).
    pub max_substep: Option<f64>,
    /// Whether particles collide with each other (DPMFoam's `collisionModel none` turns
    /// pair contacts off: then particles pass through each other and `pair_model` is unused).
    pub pair_collisions: bool,
}

impl DemConfig {
    /// Defaults: gravity `(0, 0, −9.81)` m/s², no fluid, skin 0.1 d_max, initial overlaps up
    /// to 0.1% of d accepted, no cap on the collision sub-step.
    pub fn new(pair_model: PairModel, wall_model: WallModel) -> Self {
        DemConfig {
            pair_model,
            wall_model,
            gravity: Vec3::new(0.0, 0.0, -9.81),
            fluid_density: 0.0,
            skin_fraction: 0.1,
            overlap_tolerance: 1e-3,
            max_substep: None,
            pair_collisions: true,
        }
    }
}

fn check(
    keyword: &'static str,
    value: f64,
    ok: bool,
    expected: &'static str,
) -> Result<(), DemError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(DemError::BadCoefficient {
            keyword,
            value,
            expected,
        })
    }
}

/// Material and spring-slider coefficients shared by DPMFoam's pair and wall models.
fn check_spring_slider(
    youngs_modulus: f64,
    poissons_ratio: f64,
    alpha: f64,
    b: f64,
    mu: f64,
    collision_resolution_steps: f64,
) -> Result<(), DemError> {
    check_material(youngs_modulus, poissons_ratio, "")?;
    check("alpha", alpha, alpha >= 0.0, ">= 0")?;
    check("b", b, b > 0.0, "> 0")?;
    check("mu", mu, mu >= 0.0, ">= 0")?;
    check_resolution(collision_resolution_steps)
}

/// Young's modulus and Poisson's ratio; `whose` qualifies the expectation (" (particle)").
fn check_material(youngs_modulus: f64, poissons_ratio: f64, whose: &str) -> Result<(), DemError> {
    let (e_expected, nu_expected) = if whose.is_empty() {
        ("> 0", "in (-1, 0.5)")
    } else {
        ("> 0 (particle)", "in (-1, 0.5) (particle)")
    };
    check(
        "youngsModulus",
        youngs_modulus,
        youngs_modulus > 0.0,
        e_expected,
    )?;
    check(
        "poissonsRatio",
        poissons_ratio,
        poissons_ratio > -1.0 && poissons_ratio < 0.5,
        nu_expected,
    )
}

fn check_resolution(collision_resolution_steps: f64) -> Result<(), DemError> {
    check(
        "collisionResolutionSteps",
        collision_resolution_steps,
        collision_resolution_steps >= 1.0,
        ">= 1",
    )
}

/// Coefficients of the linear spring-dashpot, shared by the pair and wall models.
fn check_linear(
    kn: f64,
    restitution: f64,
    kt: f64,
    mu: f64,
    tangential_damping_ratio: f64,
    collision_resolution_steps: f64,
) -> Result<(), DemError> {
    check("kn", kn, kn > 0.0, "> 0")?;
    check(
        "restitution",
        restitution,
        restitution > 0.0 && restitution <= 1.0,
        "in (0, 1]",
    )?;
    check("kt", kt, kt >= 0.0, ">= 0")?;
    check("mu", mu, mu >= 0.0, ">= 0")?;
    check(
        "tangentialDampingRatio",
        tangential_damping_ratio,
        tangential_damping_ratio >= 0.0,
        ">= 0",
    )?;
    check_resolution(collision_resolution_steps)
}

pub(super) fn validate_config(c: &DemConfig) -> Result<(), DemError> {
    match c.pair_model {
        PairModel::SpringSliderDashpot {
            youngs_modulus,
            poissons_ratio,
            alpha,
            b,
            mu,
            collision_resolution_steps,
            ..
        } => check_spring_slider(
            youngs_modulus,
            poissons_ratio,
            alpha,
            b,
            mu,
            collision_resolution_steps,
        )?,
        PairModel::LinearSpringDashpot {
            kn,
            restitution,
            kt,
            mu,
            tangential_damping_ratio,
            collision_resolution_steps,
        } => check_linear(
            kn,
            restitution,
            kt,
            mu,
            tangential_damping_ratio,
            collision_resolution_steps,
        )?,
    }
    match c.wall_model {
        WallModel::None => {}
        WallModel::SpringSliderDashpot {
            youngs_modulus,
            poissons_ratio,
            particle_youngs_modulus,
            particle_poissons_ratio,
            alpha,
            b,
            mu,
            collision_resolution_steps,
            ..
        } => {
            check_spring_slider(
                youngs_modulus,
                poissons_ratio,
                alpha,
                b,
                mu,
                collision_resolution_steps,
            )?;
            check_material(
                particle_youngs_modulus,
                particle_poissons_ratio,
                " (particle)",
            )?;
        }
        WallModel::LinearSpringDashpot {
            kn,
            restitution,
            kt,
            mu,
            tangential_damping_ratio,
            collision_resolution_steps,
        } => check_linear(
            kn,
            restitution,
            kt,
            mu,
            tangential_damping_ratio,
            collision_resolution_steps,
        )?,
    }
    check(
        "fluidDensity",
        c.fluid_density,
        c.fluid_density >= 0.0,
        ">= 0",
    )?;
    check(
        "skinFraction",
        c.skin_fraction,
        c.skin_fraction > 0.0,
        "> 0",
    )?;
    check(
        "overlapTolerance",
        c.overlap_tolerance,
        c.overlap_tolerance >= 0.0,
        ">= 0",
    )?;
    for &g in c.gravity.iter() {
        check("g", g, true, "finite")?;
    }
    if let Some(h) = c.max_substep {
        check("maxSubstep", h, h > 0.0, "> 0")?;
    }
    Ok(())
}

pub(super) fn validate_walls(c: &DemConfig, d: &DomainBox) -> Result<(), DemError> {
    if c.wall_model == WallModel::None {
        if let Some(face) = d.faces.iter().position(|f| *f == FaceCondition::Wall) {
            return Err(DemError::WallWithoutModel { face });
        }
    }
    Ok(())
}

pub(super) fn validate_domain(d: &DomainBox) -> Result<(), DemError> {
    for a in 0..3 {
        if d.hi[a].partial_cmp(&d.lo[a]) != Some(std::cmp::Ordering::Greater)
            || !d.lo[a].is_finite()
            || !d.hi[a].is_finite()
        {
            return Err(DemError::BadDomain { lo: d.lo, hi: d.hi });
        }
        let (p0, p1) = (
            d.faces[2 * a] == FaceCondition::Periodic,
            d.faces[2 * a + 1] == FaceCondition::Periodic,
        );
        if p0 != p1 {
            return Err(DemError::UnpairedPeriodicFace {
                face: if p0 { 2 * a } else { 2 * a + 1 },
            });
        }
        for f in [2 * a, 2 * a + 1] {
            if let FaceCondition::Rebound { e, mu } = d.faces[f] {
                check("e", e, (0.0..=1.0).contains(&e), "in [0, 1]")?;
                check("mu", mu, (0.0..=1.0).contains(&mu), "in [0, 1]")?;
            }
        }
    }
    Ok(())
}

/// Per-particle checks that need no neighbours, reported with input indices.
pub(super) fn validate_particles(
    p: &ParticleState,
    domain: &DomainBox,
    tolerance: f64,
) -> Result<(), DemError> {
    if !p.is_consistent() {
        return Err(DemError::InconsistentArrays);
    }
    for i in 0..p.len() {
        let id = p.id[i];
        let d = p.diameter[i];
        if !(d > 0.0 && d.is_finite()) {
            return Err(DemError::BadDiameter {
                index: i,
                id,
                diameter: d,
            });
        }
        let rho = p.density[i];
        if !(rho > 0.0 && rho.is_finite()) {
            return Err(DemError::BadDensity {
                index: i,
                id,
                density: rho,
            });
        }
        let x = p.position[i];
        if (0..3).any(|a| !(x[a] >= domain.lo[a] && x[a] <= domain.hi[a])) {
            return Err(DemError::OutsideDomain {
                index: i,
                id,
                position: x,
            });
        }
        for f in 0..6 {
            if domain.faces[f] == FaceCondition::Wall {
                let overlap = 0.5 * d - wall_distance(domain, f, x);
                if overlap > tolerance * d {
                    return Err(DemError::WallOverlap {
                        index: i,
                        id,
                        face: f,
                        overlap_over_d: overlap / d,
                    });
                }
            }
        }
    }
    let mut ids: Vec<(u64, usize)> = p.id.iter().copied().zip(0..).collect();
    ids.sort_unstable();
    for w in ids.windows(2) {
        if w[0].0 == w[1].0 {
            return Err(DemError::DuplicateId {
                index_a: w[0].1,
                index_b: w[1].1,
                id: w[0].0,
            });
        }
    }
    Ok(())
}
