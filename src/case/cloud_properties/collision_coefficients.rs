//! The coefficients of the collision models in `pairCollisionCoeffs`: DPMFoam's spring-slider
//! models (`pairSpringSliderDashpot`, `wallSpringSliderDashpot`) and fsim's linear ones.

use super::scalar_in;
use crate::case::control_dict::{at_value, choice};
use crate::case::dictionary::Dict;
use crate::case::error::CaseError;
use crate::particles::TangentialRule;

/// `alpha b mu collisionResolutionSteps` and fsim's `tangentialRule` of a spring-slider model.
pub(super) fn spring_slider(c: &Dict) -> Result<(f64, f64, f64, f64, TangentialRule), CaseError> {
    if c.get_bool_or("useEquivalentSize", false)? {
        return Err(at_value(
            c,
            "useEquivalentSize",
            "useEquivalentSize yes is not supported by fsim (use no)".to_string(),
        ));
    }
    let cohesion = c.get_scalar_or("cohesionEnergyDensity", 0.0)?;
    if cohesion != 0.0 {
        return Err(at_value(
            c,
            "cohesionEnergyDensity",
            format!("cohesionEnergyDensity {cohesion}: cohesion is not supported by fsim (use 0)"),
        ));
    }
    let volume_factor = c.get_scalar_or("volumeFactor", 1.0)?;
    if volume_factor != 1.0 {
        return Err(at_value(
            c,
            "volumeFactor",
            format!("volumeFactor {volume_factor} is not supported by fsim (use 1)"),
        ));
    }
    let rule = match choice(
        c,
        "tangentialRule",
        &["dpmFoamReset", "cappedSpring"],
        Some(0),
    )? {
        0 => TangentialRule::DpmFoamReset,
        _ => TangentialRule::CappedSpring,
    };
    Ok((
        scalar_in(c, "alpha", None, |x| x >= 0.0, ">= 0")?,
        scalar_in(c, "b", None, |x| x > 0.0, "> 0")?,
        scalar_in(c, "mu", None, |x| x >= 0.0, ">= 0")?,
        resolution_steps(c, None)?,
        rule,
    ))
}

/// `kn e kt mu tangentialDampingRatio collisionResolutionSteps` of a linear model.
pub(super) fn linear(c: &Dict) -> Result<[f64; 6], CaseError> {
    let kn = scalar_in(c, "kn", None, |x| x > 0.0, "> 0")?;
    Ok([
        kn,
        scalar_in(c, "e", None, |x| x > 0.0 && x <= 1.0, "in (0, 1]")?,
        scalar_in(c, "kt", Some(2.0 / 7.0 * kn), |x| x >= 0.0, ">= 0")?,
        scalar_in(c, "mu", None, |x| x >= 0.0, ">= 0")?,
        scalar_in(c, "tangentialDampingRatio", Some(0.5), |x| x >= 0.0, ">= 0")?,
        resolution_steps(c, Some(50.0))?,
    ])
}

/// Most DEM sub-steps a collision may be resolved in. Velocity Verlet's error falls as the
/// square of the steps: 10⁴ already gives 10⁻⁸ of the contact's impulse, and more only
/// multiplies the run's work (10¹² would never end).
pub const MAX_COLLISION_RESOLUTION_STEPS: f64 = 1e4;

/// `collisionResolutionSteps`: from 1 to [`MAX_COLLISION_RESOLUTION_STEPS`].
fn resolution_steps(c: &Dict, default: Option<f64>) -> Result<f64, CaseError> {
    scalar_in(
        c,
        "collisionResolutionSteps",
        default,
        |x| (1.0..=MAX_COLLISION_RESOLUTION_STEPS).contains(&x),
        "from 1 to 10000 (sub-steps per collision; more adds work, not accuracy)",
    )
}
