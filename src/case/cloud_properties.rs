//! `constant/kinematicCloudProperties` (DPMFoam's form, OpenFOAM v1912 keywords) and
//! `constant/kinematicCloudPositions`, read into the DEM engine's plain types
//! ([`DemConfig`], [`DomainBox`], [`ParticleState`]); the keyword map is in
//! [`crate::particles`].
//!
//! What fsim reads, and what it adds of its own:
//!
//! * `solution { active; coupled; transient; }`; `active false` means no cloud.
//! * `subModels`: `dispersionModel`, `heatTransferModel`, `surfaceFilmModel`,
//!   `stochasticCollisionModel` and MPPICFoam's `packingModel`, `dampingModel`,
//!   `isotropyModel` must be `none`; `radiation off`.
//! * `constantProperties { rho0; youngsModulus; poissonsRatio; }`.
//! * `subModels.particleForces`: `gravity` (with buoyancy `1 − ρ_f/ρ_p`, as OpenFOAM's
//!   `gravity` force), one drag closure, `pressureGradient`, `virtualMass` and a lift force,
//!   checked by
//!   [`super::drag_law_options`] (an unknown or unsupported force is an error at its keyword)
//!   and kept for the coupling models (no effect with `model none`). With `model dragLaw` the
//!   drag-law options ([`DragLawOptions`]: solution schemes, `alphaMax`, forces) are read
//!   into [`Cloud::drag_law`].
//! * `injectionModels`: `manualInjection` (`positionsFile`, `U0`, `sizeDistribution`,
//!   `parcelBasisType fixed`, `nParticle 1`, `SOI` not after the start) and fsim's
//!   `randomPacking` (`box (lo) (hi); volumeFraction; sizeDistribution; U0; seed;`).
//!   `sizeDistribution` is `fixedValue { value }`, `uniform { minValue maxValue }` (uniform in
//!   d) or `normal { expectation variance minValue maxValue }` — v1912 samples
//!   `μ + variance·erf⁻¹(·)`, i.e. a normal of standard deviation `variance/√2` truncated to
//!   `[minValue, maxValue]`; the newer `{ mu sigma minValue maxValue }` form takes `sigma` as
//!   the standard deviation. Random sizes come from SplitMix64 seeded with the injection's
//!   `seed` (fsim's keyword, default 1), drawn in particle order; a random packing places
//!   its spheres with the seed `seed + 1`.
//! * `collisionModel none` (particles pass through each other; walls must then be rebound
//!   patches) or `collisionModel pairCollision` with `pairModel pairSpringSliderDashpot` or fsim's
//!   `pairLinearSpringDashpot`, `wallModel wallSpringSliderDashpot` or fsim's
//!   `wallLinearSpringDashpot` (coefficients `kn e kt mu tangentialDampingRatio
//!   collisionResolutionSteps`; `kt` defaults to `2/7 kn`, the damping ratio to ½, the steps
//!   to 50). fsim's `tangentialRule dpmFoamReset | cappedSpring;` in the spring-slider
//!   coefficients picks what the tangential spring does on sliding; DPMFoam's reset is the
//!   default for DPMFoam's own models so that the same case gives DPMFoam's forces.
//! * Walls: a `wall` patch is a soft wall when a wall model is set, else a `rebound` face with
//!   the patch interaction's `e` and `mu` (`standardWallInteraction` or `localInteraction`).
//!   `symmetry`, `symmetryPlane` and `empty` patches mirror particles (`rebound` with e = 1,
//!   μ = 0) unless `localInteraction` gives them coefficients; `cyclic` patches wrap
//!   particles; particles would escape through a plain `patch`, which fsim does not do.
//!
//! Whatever else would change the physics (cohesion, `useEquivalentSize`, parcels of several
//! particles, other injection, dispersion or force models) stops the run with the file, line
//! and column; other keywords are listed once as ignored.

use super::case::Case;
use super::control_dict::{at_value, choice};
use super::coupling::CouplingModel;
use super::dictionary::Dict;
use super::drag_law_options::DragLawOptions;
use super::error::CaseError;
use super::particle_forces::ParticleForces;
use super::source::Location;
use crate::particles::{
    random_packing_sizes, sphere_volume, DemConfig, DemError, DomainBox, PairModel, ParticleState,
    SplitMix64, WallModel,
};

mod collision_coefficients;
mod particle_positions;
mod patch_interaction;
mod size_distribution;

use collision_coefficients::{linear, spring_slider};
use particle_positions::read_box;
pub use particle_positions::read_positions;
use patch_interaction::domain_box;
use size_distribution::SizeDistribution;

/// A cloud ready for [`crate::particles::Dem::new`], with what the banner and errors need.
#[derive(Clone, Debug)]
pub struct Cloud {
    pub config: DemConfig,
    pub domain: DomainBox,
    pub particles: ParticleState,
    /// `pairModel` and `wallModel` as named in the file.
    pub pair_model_name: String,
    pub wall_model_name: String,
    /// The `particleForces` listed, in file order.
    pub forces: Vec<String>,
    /// The drag-law model's settings, when the case runs that model.
    pub drag_law: Option<DragLawOptions>,
    /// One line per injection model: name, type, count.
    pub injections: Vec<String>,
    /// Where each particle (input index) was defined: its line of the positions file, or its
    /// injection model.
    pub origins: Vec<Location>,
    /// Ignored keywords (each once) and settings without effect.
    pub warnings: Vec<String>,
}

/// Where a value was written: the entry's value, or the dictionary when absent.
fn value_loc(d: &Dict, keyword: &str) -> Location {
    d.peek(keyword)
        .map(|e| e.value_loc().clone())
        .unwrap_or_else(|| d.loc.clone())
}

/// A number with a range check, the error at its value.
fn scalar_in(
    d: &Dict,
    keyword: &str,
    default: Option<f64>,
    ok: impl Fn(f64) -> bool,
    expected: &str,
) -> Result<f64, CaseError> {
    let x = match default {
        Some(v) => d.get_scalar_or(keyword, v)?,
        None => d.get_scalar(keyword)?,
    };
    if ok(x) && x.is_finite() {
        Ok(x)
    } else {
        Err(at_value(
            d,
            keyword,
            format!("'{keyword}' = {x}: expected {expected}"),
        ))
    }
}

/// A word that must be one of `allowed`; anything else is fatal at its value (`what` says why).
fn only(d: &Dict, keyword: &str, allowed: &[&str], what: &str) -> Result<(), CaseError> {
    if let Some(e) = d.lookup(keyword) {
        let word = e
            .as_tokens()
            .and_then(|t| t.first())
            .map(|i| i.to_string())
            .unwrap_or_default();
        if !allowed.contains(&word.trim_matches('"')) {
            return Err(CaseError::at(
                e.value_loc(),
                format!("{keyword} '{word}': {what}"),
            ));
        }
    }
    Ok(())
}

impl Cloud {
    /// The case's cloud, or `None` when it has no `kinematicCloudProperties` or the cloud is
    /// not `active`.
    pub fn from_case(case: &Case) -> Result<Option<Cloud>, CaseError> {
        let Some(dict) = &case.cloud_properties else {
            return Ok(None);
        };
        let mut warnings = Vec::new();
        let solution = dict.get_dict("solution")?;
        if !solution.get_bool_or("active", true)? {
            warnings.push(format!(
                "{}: the cloud is not active (solution.active false): no particles",
                dict.file()
            ));
            return Ok(None);
        }
        // `coupled` is the drag-law model's to check (two-way only); with `model none` the
        // cloud feels only gravity and buoyancy, whatever it says.
        solution.get_bool_or("coupled", false)?;
        if !solution.get_bool_or("transient", true)? {
            return Err(at_value(
                solution,
                "transient",
                "a steady-state cloud (transient no) is not supported: fsim tracks particles \
                 in time"
                    .to_string(),
            ));
        }

        let props = dict.get_dict("constantProperties")?;
        let rho0 = scalar_in(props, "rho0", None, |x| x > 0.0, "> 0")?;
        let sub = dict.get_dict("subModels")?;

        // ----- forces -----
        let forces = ParticleForces::read(sub, &case.transport.phase)?.names;
        let drag_law = if case.coupling.model == CouplingModel::DragLaw {
            Some(DragLawOptions::read(
                dict,
                case.coupling.dict.as_ref(),
                &case.transport.phase,
                &mut warnings,
            )?)
        } else {
            None
        };
        let gravity = if forces.iter().any(|f| f == "gravity") {
            case.gravity
        } else {
            [0.0; 3]
        };
        let fluid_forces: Vec<&String> = forces.iter().filter(|f| *f != "gravity").collect();
        if !fluid_forces.is_empty() && case.coupling.model == CouplingModel::None {
            warnings.push(format!(
                "{}: particleForces {}: no effect with coupling model none (particles feel \
                 gravity and buoyancy only)",
                dict.file(),
                fluid_forces
                    .iter()
                    .map(|s| s.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }

        let modelled: Vec<&str> = forces
            .iter()
            .map(|f| f.as_str())
            .filter(|f| {
                [
                    "pressureGradient",
                    "virtualMass",
                    "SaffmanMeiLiftForce",
                    "TomiyamaLift",
                ]
                .contains(f)
            })
            .collect();
        if !modelled.is_empty() && case.coupling.model == CouplingModel::Direct {
            warnings.push(format!(
                "{}: particleForces {}: not added by the direct model, whose resolved fluid \
                 force already holds the pressure, added-mass and lift forces",
                dict.file(),
                modelled.join(", ")
            ));
        }

        for (keyword, what) in [
            (
                "dispersionModel",
                "particle dispersion is not supported by fsim",
            ),
            (
                "heatTransferModel",
                "heat transfer is not supported by fsim",
            ),
            (
                "surfaceFilmModel",
                "surface films are not supported by fsim",
            ),
            (
                "stochasticCollisionModel",
                "stochastic collisions are not supported by fsim",
            ),
            (
                "packingModel",
                "MPPIC packing models are not supported by fsim (use DPMFoam's cases, not \
                 MPPICFoam's)",
            ),
            (
                "dampingModel",
                "MPPIC damping models are not supported by fsim",
            ),
            (
                "isotropyModel",
                "MPPIC isotropy models are not supported by fsim",
            ),
        ] {
            only(sub, keyword, &["none"], what)?;
        }
        only(
            sub,
            "radiation",
            &["off", "no", "false", "none"],
            "radiation is not supported by fsim",
        )?;

        // ----- contact models -----
        let collision = choice(sub, "collisionModel", &["pairCollision", "none"], Some(1))?;
        // collisionModel none: particles pass through each other (the pair model is unused)
        let (pair_model, wall_model, pair_model_name, wall_model_name) = if collision == 1 {
            (
                PairModel::linear(1.0, 1.0, 0.0),
                WallModel::None,
                "none".to_string(),
                "none".to_string(),
            )
        } else {
            let coeffs = sub.get_dict("pairCollisionCoeffs")?;
            coeffs.lookup("maxInteractionDistance");
            coeffs.lookup("writeReferredParticleCloud");
            coeffs.lookup("U");
            let pair_kind = choice(
                coeffs,
                "pairModel",
                &["pairSpringSliderDashpot", "pairLinearSpringDashpot"],
                None,
            )?;
            let pair_model = if pair_kind == 0 {
                let c = coeffs.get_dict("pairSpringSliderDashpotCoeffs")?;
                // OpenFOAM's PairModel ramps the pair forces up over each parcel's first
                // forceRampTime (default −1: off); fsim does not, so it refuses a ramp
                let ramp = c.get_scalar_or("forceRampTime", -1.0)?;
                if ramp > 0.0 {
                    return Err(at_value(
                        c,
                        "forceRampTime",
                        format!(
                            "forceRampTime {ramp}: the ramp of pair forces after injection is \
                             not supported by fsim (remove it, or set -1)"
                        ),
                    ));
                }
                let (alpha, b, mu, steps, rule) = spring_slider(c)?;
                PairModel::SpringSliderDashpot {
                    youngs_modulus: scalar_in(props, "youngsModulus", None, |x| x > 0.0, "> 0")?,
                    poissons_ratio: scalar_in(
                        props,
                        "poissonsRatio",
                        None,
                        |x| x > -1.0 && x < 0.5,
                        "in (-1, 0.5)",
                    )?,
                    alpha,
                    b,
                    mu,
                    collision_resolution_steps: steps,
                    tangential: rule,
                }
            } else {
                let c = coeffs.get_dict("pairLinearSpringDashpotCoeffs")?;
                let l = linear(c)?;
                PairModel::LinearSpringDashpot {
                    kn: l[0],
                    restitution: l[1],
                    kt: l[2],
                    mu: l[3],
                    tangential_damping_ratio: l[4],
                    collision_resolution_steps: l[5],
                }
            };
            let wall_kind = choice(
                coeffs,
                "wallModel",
                &["wallSpringSliderDashpot", "wallLinearSpringDashpot", "none"],
                Some(2),
            )?;
            let wall_model = match wall_kind {
                0 => {
                    let c = coeffs.get_dict("wallSpringSliderDashpotCoeffs")?;
                    let (alpha, b, mu, steps, rule) = spring_slider(c)?;
                    let PairModel::SpringSliderDashpot {
                        youngs_modulus: pe,
                        poissons_ratio: pnu,
                        ..
                    } = pair_model
                    else {
                        return Err(at_value(
                            coeffs,
                            "wallModel",
                            "wallSpringSliderDashpot needs the particle's youngsModulus and \
                         poissonsRatio: use it with pairSpringSliderDashpot"
                                .to_string(),
                        ));
                    };
                    WallModel::SpringSliderDashpot {
                        youngs_modulus: scalar_in(c, "youngsModulus", None, |x| x > 0.0, "> 0")?,
                        poissons_ratio: scalar_in(
                            c,
                            "poissonsRatio",
                            None,
                            |x| x > -1.0 && x < 0.5,
                            "in (-1, 0.5)",
                        )?,
                        particle_youngs_modulus: pe,
                        particle_poissons_ratio: pnu,
                        alpha,
                        b,
                        mu,
                        collision_resolution_steps: steps,
                        tangential: rule,
                    }
                }
                1 => {
                    let c = coeffs.get_dict("wallLinearSpringDashpotCoeffs")?;
                    let l = linear(c)?;
                    WallModel::LinearSpringDashpot {
                        kn: l[0],
                        restitution: l[1],
                        kt: l[2],
                        mu: l[3],
                        tangential_damping_ratio: l[4],
                        collision_resolution_steps: l[5],
                    }
                }
                _ => WallModel::None,
            };
            let pair_model_name = coeffs.get_word("pairModel")?;
            let wall_model_name = coeffs.get_word_or("wallModel", "none")?;
            (pair_model, wall_model, pair_model_name, wall_model_name)
        };

        // ----- faces -----
        let domain = domain_box(case, sub, wall_model != WallModel::None, &mut warnings)?;

        // ----- injection -----
        let mut particles = ParticleState::default();
        let mut origins = Vec::new();
        let mut injections = Vec::new();
        let models = sub.get_dict("injectionModels")?;
        for e in models.entries() {
            e.mark_used();
            let name = e.keyword();
            let m = e.as_dict().ok_or_else(|| {
                CaseError::at(
                    e.value_loc(),
                    format!("expected a dictionary {{ … }} for injection model '{name}'"),
                )
            })?;
            let before = particles.len();
            let kind = choice(m, "type", &["manualInjection", "randomPacking"], None)?;
            let seed = m.get_label_or("seed", 1)? as u64;
            let u0 = m.get_vector_or("U0", [0.0; 3])?;
            if kind == 0 {
                m.get_vector("U0")?;
                only(
                    m,
                    "parcelBasisType",
                    &["fixed"],
                    "fsim tracks single particles: use parcelBasisType fixed with nParticle 1",
                )?;
                if let Some(n) = m.opt_scalar("nParticle")? {
                    if n != 1.0 {
                        return Err(at_value(
                            m,
                            "nParticle",
                            format!(
                                "nParticle {n}: fsim tracks single particles (parcels of \
                                 several particles are not supported); use nParticle 1"
                            ),
                        ));
                    }
                }
                m.lookup("massTotal");
                let soi = m.get_scalar_or("SOI", case.control.start_time)?;
                if soi < 0.0 {
                    return Err(at_value(
                        m,
                        "SOI",
                        format!(
                            "SOI {soi}: a negative start of injection makes OpenFOAM's \
                             manualInjection inject nothing; use the start time"
                        ),
                    ));
                }
                if soi > case.control.start_time {
                    return Err(at_value(
                        m,
                        "SOI",
                        format!(
                            "SOI {soi}: fsim injects every particle at the start time {}; a \
                             later start of injection is not supported",
                            case.control.start_time
                        ),
                    ));
                }
                let file = m.get_word("positionsFile")?;
                let path = case.dir.join("constant").join(&file);
                let (positions, locs) = read_positions(&path, &case.dir)?;
                let mut rng = SplitMix64::new(seed);
                let sizes = SizeDistribution::read(m)?;
                for (x, loc) in positions.into_iter().zip(locs) {
                    let id = particles.len() as u64;
                    particles.push(id, x, sizes.sample(&mut rng), rho0);
                    *particles.velocity.last_mut().expect("pushed") = u0.into();
                    origins.push(loc);
                }
            } else {
                let (lo, hi) = read_box(m)?;
                let phi = scalar_in(
                    m,
                    "volumeFraction",
                    None,
                    |x| x > 0.0 && x < 1.0,
                    "in (0, 1)",
                )?;
                let sizes = SizeDistribution::read(m)?;
                let mut rng = SplitMix64::new(seed);
                let volume = (0..3).map(|a| hi[a] - lo[a]).product::<f64>();
                check_packing(m, &domain, lo, hi, phi, volume, &sizes, &rng)?;
                let mut diameters = Vec::new();
                let mut filled = 0.0;
                loop {
                    let d = sizes.sample(&mut rng);
                    if filled + 0.5 * sphere_volume(d) > phi * volume {
                        break;
                    }
                    filled += sphere_volume(d);
                    diameters.push(d);
                }
                // largest first packs best
                diameters.sort_by(|a, b| b.total_cmp(a));
                // Along a cyclic axis that the box spans, the packing wraps across the
                // periodic faces: a homogeneous suspension, no sphere-free layer there.
                let wrap = [0, 1, 2].map(|a| {
                    let tol = 1e-9 * (domain.hi[a] - domain.lo[a]);
                    domain.is_periodic(a)
                        && (lo[a] - domain.lo[a]).abs() <= tol
                        && (hi[a] - domain.hi[a]).abs() <= tol
                });
                let centres = random_packing_sizes(
                    lo.into(),
                    hi.into(),
                    &diameters,
                    phi,
                    seed.wrapping_add(1),
                    wrap,
                )
                .map_err(|err| at_value(m, "volumeFraction", err.to_string()))?;
                for (x, d) in centres.into_iter().zip(diameters) {
                    let id = particles.len() as u64;
                    particles.push(id, x, d, rho0);
                    *particles.velocity.last_mut().expect("pushed") = u0.into();
                    origins.push(e.key_loc.clone());
                }
            }
            injections.push(format!(
                "{name} ({}): {} particles",
                m.get_word("type")?,
                particles.len() - before
            ));
        }

        let mut config = DemConfig::new(pair_model, wall_model);
        config.gravity = gravity.into();
        config.fluid_density = case.transport.rho;
        config.pair_collisions = collision == 0;

        warnings.extend(ignored_keywords(dict));
        Ok(Some(Cloud {
            config,
            domain,
            particles,
            pair_model_name,
            wall_model_name,
            forces,
            drag_law,
            injections,
            origins,
            warnings,
        }))
    }

    /// An engine error as a case error, at the particle's origin for a particle, at the cloud
    /// file for the rest.
    pub fn locate(&self, err: &DemError) -> CaseError {
        let file = self.origins.first().map(|l| l.file.display.clone());
        let at = |index: usize| self.origins.get(index);
        let place = |l: &Location| {
            let (line, col) = l.line_col();
            format!("{}:{line}:{col}", l.file.display)
        };
        match err {
            DemError::BadDiameter { index, .. }
            | DemError::BadDensity { index, .. }
            | DemError::OutsideDomain { index, .. }
            | DemError::WallOverlap { index, .. } => match at(*index) {
                Some(l) => CaseError::at(l, err.to_string()),
                None => CaseError::plain(err.to_string()),
            },
            DemError::Overlap {
                index_a, index_b, ..
            }
            | DemError::DuplicateId {
                index_a, index_b, ..
            } => match (at(*index_a), at(*index_b)) {
                (Some(a), Some(b)) => CaseError::at(
                    a,
                    format!("{err} (the other one is defined at {})", place(b)),
                ),
                _ => CaseError::plain(err.to_string()),
            },
            _ => CaseError::in_file(
                file.unwrap_or_else(|| "constant/kinematicCloudProperties".to_string()),
                err.to_string(),
            ),
        }
    }
}

/// One note per keyword of the cloud file that fsim did not read.
/// Most spheres one `randomPacking` may place (10⁷): about 4 GB of particle state and
/// hours of packing; a larger bed is a sign of a wrong box or diameter, refused before any
/// sphere is drawn.
pub const MAX_PACKED_SPHERES: f64 = 1e7;

/// Checks a random packing before it is drawn: its box lies inside the domain, and the number
/// of spheres its volume fraction implies (from the mean volume of 1000 diameters drawn from
/// the size distribution) is at most [`MAX_PACKED_SPHERES`]. Packing first would take
/// minutes, and the memory of every sphere, to find either.
#[allow(clippy::too_many_arguments)]
fn check_packing(
    m: &Dict,
    domain: &crate::particles::DomainBox,
    lo: [f64; 3],
    hi: [f64; 3],
    phi: f64,
    volume: f64,
    sizes: &SizeDistribution,
    rng: &SplitMix64,
) -> Result<(), CaseError> {
    for a in 0..3 {
        let tol = 1e-9 * (domain.hi[a] - domain.lo[a]);
        if lo[a] < domain.lo[a] - tol || hi[a] > domain.hi[a] + tol {
            return Err(at_value(
                m,
                "box",
                format!(
                    "the box reaches outside the domain along {}: [{}, {}] against the \
                     mesh's [{}, {}]",
                    ["x", "y", "z"][a],
                    lo[a],
                    hi[a],
                    domain.lo[a],
                    domain.hi[a]
                ),
            ));
        }
    }
    let mut rng = rng.clone();
    let draws = 1000;
    let mean = (0..draws)
        .map(|_| sphere_volume(sizes.sample(&mut rng)))
        .sum::<f64>()
        / draws as f64;
    let count = phi * volume / mean;
    if count.is_nan() || count > MAX_PACKED_SPHERES {
        return Err(at_value(
            m,
            "volumeFraction",
            format!(
                "volumeFraction {phi} of the box makes about {count:.3e} spheres, more than \
                 fsim packs ({MAX_PACKED_SPHERES:.0e}): check the box and the diameters"
            ),
        ));
    }
    Ok(())
}

fn ignored_keywords(d: &Dict) -> Vec<String> {
    let mut seen = std::collections::BTreeSet::new();
    let mut notes = Vec::new();
    for (key, loc) in d.unused() {
        if seen.insert(key.clone()) {
            let (line, col) = loc.line_col();
            notes.push(format!(
                "{}:{line}:{col}: ignored keyword '{key}' (fsim does not use it)",
                loc.file.display
            ));
        }
    }
    notes
}
