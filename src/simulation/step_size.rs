//! The size of each step: controlDict's `deltaT` or the `maxCo` rule, within the scheme's
//! stability bound, and the collapse of the Courant step by which a diverging run shows.

use super::coupling::Coupling;
use super::simulation::{Simulation, StepSizing};
use crate::coupling::direct::RESPONSE_STEP_FRACTION;
use crate::error::FsimError;

/// A Courant step below this fraction of the largest step taken means a velocity growing
/// without bound: a flow that develops changes its speed by orders of magnitude less within a
/// run (a diverging one collapses the step to 10⁻³⁰⁰ s before it overflows).
const COLLAPSED_STEP: f64 = 1e-8;

impl Simulation {
    /// The step to take now: controlDict's `deltaT`, or the `maxCo` rule; never above the
    /// scheme's stability bound (paper eq. 3 for the explicit Euler scheme), never past the
    /// next write time for `adjustableRunTime` nor past `endTime`.
    pub fn next_time_step(&mut self) -> Result<f64, FsimError> {
        let allowed = match self.sizing {
            StepSizing::Fixed(dt) => {
                let bound = self.stability_bound();
                if dt > bound {
                    let scheme = match self.coupling.drag_law() {
                        Some(m) if m.coupling.fluid.implicit_viscosity() => {
                            "drag-law model's EulerImplicit predictor (upwind advection: \
                             1/(Σ|u|/h))"
                                .to_string()
                        }
                        Some(_) => "drag-law model's explicit Euler predictor \
                                    (1/(Σ|u|/h + 2ν Σ1/h²))"
                            .to_string(),
                        None => {
                            let scheme = self.fluid.settings().scheme;
                            format!("{} scheme ({})", scheme.name(), scheme.bound_description())
                        }
                    };
                    // Past the first step the bound held before: the velocity has grown,
                    // which is how a diverging run at a fixed step first shows.
                    let grown = if self.time.step > 0 {
                        format!(
                            " (step {}; it held until now: the velocity has grown, the \
                             solution may be diverging{})",
                            self.time.step,
                            self.fastest_velocities()
                        )
                    } else {
                        String::new()
                    };
                    return Err(FsimError::run(format!(
                        "deltaT = {dt:e} s exceeds the stability bound {bound:e} s of the \
                         {scheme} at t = {} s{grown}; lower deltaT or set adjustTimeStep yes",
                        self.time.time
                    )));
                }
                dt
            }
            StepSizing::Adaptive {
                max_co,
                max_delta_t,
            } => {
                let previous = if self.time.step == 0 {
                    // OpenFOAM starts from deltaT and lets the Courant rule shrink it.
                    self.dt / 1.2
                } else {
                    self.dt
                };
                let allowed = self.adaptive_step(previous, max_co, max_delta_t);
                if allowed < COLLAPSED_STEP * self.largest_dt {
                    return Err(self.collapsed_step(allowed));
                }
                allowed
            }
        };
        Ok(self.time.step_size(allowed))
    }

    /// The step the flow allows now, without the adaptive rule's growth limit (1.2 times the
    /// last step) and without landing on write times or `endTime`: the step a plan of the
    /// whole run goes by (`-dry-run`), where [`Self::next_time_step`] is the one to take next.
    pub fn allowed_time_step(&mut self) -> f64 {
        match self.sizing {
            StepSizing::Fixed(dt) => dt,
            // after a step of maxDeltaT, the growth limit lies beyond maxDeltaT itself
            StepSizing::Adaptive {
                max_co,
                max_delta_t,
            } => self.adaptive_step(max_delta_t, max_co, max_delta_t),
        }
    }

    /// The `maxCo` rule's step after a step of `previous` (at most 1.2 times it), within
    /// `max_delta_t` and the scheme's stability bound.
    fn adaptive_step(&mut self, previous: f64, max_co: f64, max_delta_t: f64) -> f64 {
        match &self.coupling {
            // the drag law steps the fluid with its own predictor and bound
            Coupling::DragLaw(_) => self
                .fluid
                .courant_dt(previous, max_co, max_delta_t)
                .min(self.stability_bound()),
            // adaptive_dt holds the fluid's own bound already (3 passes over the field); free
            // spheres add their coupling's (coupling_step_bound)
            Coupling::Direct(m) => self
                .fluid
                .adaptive_dt(previous, max_co, max_delta_t)
                .min(m.motion.step_bound()),
            Coupling::None { .. } => self.fluid.adaptive_dt(previous, max_co, max_delta_t),
        }
    }

    /// The error of a Courant step that has collapsed: the velocity grows without bound, and
    /// without this the run would crawl on for thousands of vanishing steps until it is no
    /// longer finite.
    fn collapsed_step(&self, allowed: f64) -> FsimError {
        FsimError::run(format!(
            "the solution diverged at t = {} s (step {}): the step the Courant rule allows \
             fell to {allowed:e} s, {:.1e} of the largest step taken ({:e} s); the velocity \
             grows without bound{}{}",
            self.time.time,
            self.time.step,
            allowed / self.largest_dt,
            self.largest_dt,
            self.fastest_velocities(),
            self.virtual_mass_hint()
        ))
    }

    /// The bound on `Δt` of the fluid's scheme (paper eq. 3 for Euler), or of the drag-law
    /// model's explicit predictor.
    pub fn stability_bound(&self) -> f64 {
        match self.coupling.drag_law() {
            Some(m) => m.coupling.fluid.stability_bound(&self.fluid),
            None => self.fluid.stability_bound(),
        }
    }
}

/// What the log and `-dry-run` say when the explicit coupling's bound on the step
/// (`bound`, s: [`crate::coupling::direct::coupling_step_bound`]) is below what controlDict
/// asks: a fixed `deltaT` above it is taken as given, with a warning; an adjustable step is
/// held to it.
pub(super) fn coupling_step_warning(sizing: StepSizing, bound: f64) -> Option<String> {
    let response = bound / RESPONSE_STEP_FRACTION;
    match sizing {
        StepSizing::Fixed(dt) if dt > bound => Some(format!(
            "system/controlDict: deltaT = {dt:e} s is {:.2} of the shortest response time of \
             the free spheres, rho_p d^2/(18 mu) = {response:.3e} s; above {RESPONSE_STEP_FRACTION} \
             of it their explicit coupling may oscillate (docs/direct_model.md, \"Known \
             limits\"): lower deltaT to {bound:.3e} s or set adjustTimeStep yes",
            dt / response
        )),
        StepSizing::Adaptive { max_delta_t, .. } if max_delta_t > bound => Some(format!(
            "steps held to at most {bound:.3e} s, {RESPONSE_STEP_FRACTION} of the shortest response time \
             of the free spheres (rho_p d^2/(18 mu) = {response:.3e} s), below maxDeltaT = \
             {max_delta_t:e} s: above it their explicit coupling may oscillate"
        )),
        _ => None,
    }
}
