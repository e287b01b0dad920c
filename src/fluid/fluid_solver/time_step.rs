//! The fluid's time step: the explicit (`Euler`, `RK3`) and Chebyshev (`EulerRKC`) schemes,
//! each stage's hook and projection, and the bulk-velocity correction.

use super::{FluidSolver, PredictedVelocity, StepReport};
use crate::fluid::boundary_conditions::FaceCondition;
use crate::fluid::chebyshev_diffusion::{chebyshev_stage, StageTerms};
use crate::fluid::chebyshev_stages::ChebyshevStages;
use crate::fluid::ghost_fill::{
    extrapolate_outlets, fill_component_ghosts, fill_fixed_faces, fill_velocity_ghosts,
};
use crate::fluid::momentum::{accumulate_tendency, add_scaled, frozen_tendency, MomentumTerms};
use crate::fluid::projection::{divergence_rhs, subtract_gradient};
use rayon::prelude::*;

impl FluidSolver {
    /// Advances by `dt` with the configured scheme.
    pub fn step(&mut self, dt: f64) -> StepReport {
        self.step_with(dt, &mut |_| {})
    }

    /// Advances by `dt`, calling `hook` on each stage's predicted velocity before it is
    /// projected.
    ///
    /// Per stage `s` (coefficients `a_s, b_s` of [`TimeScheme::stages`](crate::fluid::TimeScheme::stages)):
    /// 1. `q ← a_s q + Δt F(u)` (advection, diffusion, body force, sources);
    /// 2. `u* = u + b_s q`, then the hook, then zero-gradient outlet faces;
    /// 3. `∇²p = ∇·u* / τ` with `τ = b_s Δt`, solved exactly;
    /// 4. `u = u* − τ ∇p`, and `q ← q − Δt ∇p` so later stages carry the pressure too.
    ///
    /// Then `meanVelocityForce` corrects the bulk velocity.
    pub fn step_with(
        &mut self,
        dt: f64,
        hook: &mut dyn FnMut(PredictedVelocity<'_>),
    ) -> StepReport {
        self.velocity_changes();
        if self.settings.scheme.is_chebyshev() {
            return self.step_chebyshev(dt, hook);
        }
        let stages = self.settings.scheme.stages();
        let t0 = self.time;
        let h = self.grid.h;
        let force = self.total_body_force();
        for (s, &(a, b, c_end)) in stages.iter().enumerate() {
            fill_velocity_ghosts(&self.layout, &self.bc, &mut self.u);
            let terms = MomentumTerms {
                layout: &self.layout,
                h,
                nu: self.settings.nu,
                force,
                source: self.source.as_ref(),
                ranges: &self.momentum_ranges,
                convection: self.settings.convection,
            };
            accumulate_tendency(&mut self.q, &self.u, &terms, a, dt);
            add_scaled(&mut self.u, &self.q, b, &self.layout, &self.momentum_ranges);
            let tau = b * dt;
            hook(PredictedVelocity {
                body_force: force,
                grid: &self.grid,
                layout: &self.layout,
                time: t0 + c_end * dt,
                tau,
                pressure: &self.p,
                incremental_pressure: &[],
                velocity: &mut self.u,
                mass_source: self.mass_source.as_deref_mut(),
                components: [true; 3],
            });
            extrapolate_outlets(&self.layout, &self.bc, &mut self.u);
            fill_velocity_ghosts(&self.layout, &self.bc, &mut self.u);
            divergence_rhs(&mut self.p, &self.u, &self.layout, h, &self.bc, tau);
            subtract_mass_source(&mut self.p, self.mass_source.as_deref(), tau);
            self.poisson.solve(&mut self.p);
            self.accumulate_impulse_pressure(s);
            subtract_gradient(
                &mut self.u,
                &self.p,
                tau,
                &self.layout,
                h,
                &self.bc,
                &self.corrected_ranges,
            );
            if s + 1 < stages.len() {
                subtract_gradient(
                    &mut self.q,
                    &self.p,
                    dt,
                    &self.layout,
                    h,
                    &self.bc,
                    &self.corrected_ranges,
                );
            }
        }
        self.finish_step(t0, dt)
    }

    /// The incremental projection of the Chebyshev step, into the
    /// increment's storage `phi`: `∇²φ = ∇·u*/τ` (less the mass source), `u = u* − τ∇φ`,
    /// `p ← p + φ`.
    pub(super) fn project_increment(&mut self, phi: &mut [f64], tau: f64) {
        let h = self.grid.h;
        divergence_rhs(phi, &self.u, &self.layout, h, &self.bc, tau);
        subtract_mass_source(phi, self.mass_source.as_deref(), tau);
        self.poisson.solve(phi);
        subtract_gradient(
            &mut self.u,
            phi,
            tau,
            &self.layout,
            h,
            &self.bc,
            &self.corrected_ranges,
        );
        self.p
            .par_iter_mut()
            .zip(&phi[..])
            .for_each(|(p, f)| *p += f);
    }

    /// The `EulerRKC` step:
    /// 1. `N = −∇·(uⁿuⁿ) + f + s − ∇pⁿ`, frozen over the step;
    /// 2. `s` Runge–Kutta–Chebyshev stages of `u' = ν∇²u + N` from `Y₀ = uⁿ`
    ///    ([`ChebyshevStages`], `s` from `Δt · 4ν Σ 1/h²`), the hook on each stage's velocity
    ///    (a constrained face then holds its constraint in every Laplacian that reads it),
    ///    one component through all its stages after another (each call hands the hook one
    ///    component; then one call hands none, with the mass source to set);
    /// 3. `∇²φ = ∇·u*/Δt`, `u = u* − Δt ∇φ`, `p ← p + φ` (incremental: at a steady state
    ///    `N + ν∇²u = 0`, every stage is `uⁿ` and `φ = 0`, whatever `Δt`).
    pub(super) fn step_chebyshev(
        &mut self,
        dt: f64,
        hook: &mut dyn FnMut(PredictedVelocity<'_>),
    ) -> StepReport {
        let t0 = self.time;
        let h = self.grid.h;
        let force = self.total_body_force();
        let nu = self.settings.nu;
        let method = ChebyshevStages::for_step(dt * self.diffusion_spectral_radius());
        let work = self
            .chebyshev
            .as_mut()
            .expect("set_scheme prepares the Chebyshev registers");
        fill_velocity_ghosts(&self.layout, &self.bc, &mut self.u);
        let terms = MomentumTerms {
            layout: &self.layout,
            h,
            nu,
            force,
            source: self.source.as_ref(),
            ranges: &self.momentum_ranges,
            convection: self.settings.convection,
        };
        frozen_tendency(&mut self.q, &self.u, &terms, &self.p);
        let terms = StageTerms {
            layout: &self.layout,
            h,
            nu,
            ranges: &self.momentum_ranges,
            frozen: &self.q,
        };
        // The stages do not couple the components (the hook's forced faces of a component
        // read that component only): each is taken through all its stages in turn, so that
        // its three arrays stay in the last-level cache from one stage to the next.
        for c in 0..3 {
            fill_fixed_faces(&self.layout, &self.bc, &mut work.register, c);
            for stage in method.stages() {
                // register: Y_{j−2} → Y_j; then u holds Y_j and the register Y_{j−1}.
                chebyshev_stage(&mut work.register, &self.u[c], &terms, c, &stage, dt);
                // Both registers' fixed boundary faces hold the conditions (the stage writes
                // momentum faces only): the hook may read them.
                std::mem::swap(&mut self.u[c], &mut work.register);
                hook(PredictedVelocity {
                    body_force: force,
                    grid: &self.grid,
                    layout: &self.layout,
                    time: t0 + stage.time * dt,
                    tau: dt,
                    pressure: &[],
                    incremental_pressure: &self.p,
                    velocity: &mut self.u,
                    mass_source: None,
                    components: std::array::from_fn(|d| d == c),
                });
                fill_component_ghosts(&self.layout, &self.bc, &mut self.u[c], c);
            }
        }
        // Only the last stage's velocity is projected: its mass source.
        if let Some(mass_source) = self.mass_source.as_deref_mut() {
            hook(PredictedVelocity {
                body_force: force,
                grid: &self.grid,
                layout: &self.layout,
                time: t0 + dt,
                tau: dt,
                pressure: &[],
                incremental_pressure: &self.p,
                velocity: &mut self.u,
                mass_source: Some(mass_source),
                components: [false; 3],
            });
        }
        let mut phi = std::mem::take(&mut work.increment);
        self.project_increment(&mut phi, dt);
        if let Some(work) = self.chebyshev.as_mut() {
            work.increment = phi;
        }
        self.stages_taken = method.count;
        self.finish_step(t0, dt)
    }

    /// `p̄ ← p̄ + w_s p_s` after stage `s`'s projection (`p̄ = w_0 p_0` at the first), with
    /// the weights of [`TimeScheme::stage_pressure_weight`]; nothing for the one-stage
    /// schemes, whose `p̄` is `p`.
    pub(super) fn accumulate_impulse_pressure(&mut self, stage: usize) {
        if self.impulse_pressure.is_empty() {
            return;
        }
        let scheme = self.settings.scheme;
        let weight = scheme.stage_pressure_weight(stage);
        let first = stage == 0;
        self.impulse_pressure
            .par_iter_mut()
            .zip(&self.p[..])
            .for_each(|(mean, p)| *mean = if first { 0.0 } else { *mean } + weight * p);
        if stage + 1 == scheme.projections() {
            self.impulse_generation = Some(self.generation);
        }
    }

    /// The body force of the settings plus the `meanVelocityForce` gradient, m/s².
    pub(super) fn total_body_force(&self) -> [f64; 3] {
        let mut force = self.settings.body_force;
        if let Some(d) = &self.drive {
            force[d.direction] += d.gradient;
        }
        force
    }

    /// `4ν Σ 1/h_d²` over the directions along which the Laplacian acts (not `Empty`, nor
    /// periodic with one cell): a bound on the magnitude of the most negative eigenvalue of
    /// the discrete `ν∇²`.
    pub(super) fn diffusion_spectral_radius(&self) -> f64 {
        let active = self.active();
        let (h, n) = (self.grid.h, self.grid.n);
        let acts = |d: usize| {
            active[d] && !(n[d] == 1 && matches!(self.bc.face(d, 0), FaceCondition::Periodic))
        };
        4.0 * self.settings.nu
            * (0..3)
                .filter(|&d| acts(d))
                .map(|d| 1.0 / (h[d] * h[d]))
                .sum::<f64>()
    }

    /// Chebyshev stages of the last `EulerRKC` step (0 for the other schemes).
    pub fn chebyshev_stages_taken(&self) -> usize {
        self.stages_taken
    }

    /// `meanVelocityForce`: raise the driving gradient by `δG` and add `Δt δG` to every
    /// face of the driven component.
    pub(super) fn correct_bulk_velocity(&mut self, dt: f64) {
        let d = self.drive.as_ref().expect("called with a drive").direction;
        let bulk = self.mean_component(d);
        let drive = self.drive.as_mut().expect("called with a drive");
        let dg = drive.increment(bulk, dt);
        drive.gradient += dg;
        let shift = dt * dg;
        let r = self.momentum_ranges[d];
        let l = &self.layout;
        let plane = l.plane_len();
        let d0 = l.dims[0];
        self.u[d]
            .par_chunks_mut(plane)
            .enumerate()
            .for_each(|(k, up)| {
                if k < r[2].0 || k > r[2].1 {
                    return;
                }
                for j in r[1].0..=r[1].1 {
                    for i in r[0].0..=r[0].1 {
                        up[j * d0 + i] += shift;
                    }
                }
            });
    }

    /// The end of every scheme's step: the new time, the bulk-velocity correction of
    /// `meanVelocityForce`, and the ghost layers of the final velocity.
    pub(super) fn finish_step(&mut self, t0: f64, dt: f64) -> StepReport {
        self.time = t0 + dt;
        if self.drive.is_some() {
            self.correct_bulk_velocity(dt);
        }
        fill_velocity_ghosts(&self.layout, &self.bc, &mut self.u);
        StepReport {
            dt,
            time: self.time,
            driving_gradient: self.drive.as_ref().map(|d| d.gradient),
        }
    }
}

/// `rhs ← rhs − q/τ`: the projection then leaves `∇·u = q`.
fn subtract_mass_source(rhs: &mut [f64], q: Option<&[f64]>, tau: f64) {
    if let Some(q) = q {
        let inv = 1.0 / tau;
        rhs.par_iter_mut().zip(q).for_each(|(r, q)| *r -= q * inv);
    }
}
