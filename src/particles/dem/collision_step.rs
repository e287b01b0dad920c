//! The collision sub-step: how finely the DEM divides a fluid step so that every contact is
//! resolved (DPMFoam's `nSubCycles` rule for the Hertzian models, the exact contact time for
//! the linear one).

use super::Dem;
use crate::particles::contact_model::{linear_contact_time, ContactLaw, PairModel, WallModel};
use crate::particles::domain_box::FaceCondition;

impl Dem {
    /// The collision sub-step limit.
    ///
    /// Hertzian models follow OpenFOAM's `PairSpringSliderDashpot::nSubCycles` and
    /// `WallSpringSliderDashpot::nSubCycles`:
    /// `Δt_c = 5.429675 R (ρ_max / (E* √U))^{2/5} / collisionResolutionSteps`
    /// (`5.429675 = π^{7/5} (5/4)^{2/5}`), with `R = d_min/4` and
    /// `U = 2 max_i(|v_i| + |ω_i| d_i/2)` for pairs, `R = d_min/2` and `U = max_i(…)` for walls.
    /// The linear model uses its exact contact time `t_c = √((π² + a²) M / k_n)` for the lightest
    /// pair (`M = m_min/2`; wall: `M = m_min`) divided by `collision_resolution_steps`.
    pub fn collision_time_step(&self) -> f64 {
        let p = &self.particles;
        if p.is_empty() {
            return f64::INFINITY;
        }
        let mut d_min = f64::INFINITY;
        let mut rho_max: f64 = 0.0;
        let mut u_max: f64 = 0.0;
        let mut m_min = f64::INFINITY;
        for i in 0..p.len() {
            let d = p.diameter[i];
            d_min = d_min.min(d);
            rho_max = rho_max.max(p.density[i]);
            u_max = u_max.max(p.velocity[i].norm() + p.angular_velocity[i].norm() * d / 2.0);
            m_min = m_min.min(p.mass(i));
        }
        const VSMALL: f64 = 1.0e-300;
        let hertz = |e_star: f64, r: f64, u: f64, steps: f64| {
            5.429675 * r * (rho_max / (e_star * u.sqrt() + VSMALL)).powf(0.4) / steps
        };
        let mut dt = f64::INFINITY;
        match (&self.config.pair_model, &self.pair_law) {
            _ if !self.config.pair_collisions => {}
            (
                PairModel::SpringSliderDashpot {
                    collision_resolution_steps,
                    ..
                },
                ContactLaw::Hertz { e_star, .. },
            ) => {
                dt = dt.min(hertz(
                    *e_star,
                    d_min / 4.0,
                    2.0 * u_max,
                    *collision_resolution_steps,
                ));
            }
            (
                PairModel::LinearSpringDashpot {
                    kn,
                    restitution,
                    collision_resolution_steps,
                    ..
                },
                _,
            ) => {
                dt = dt.min(
                    linear_contact_time(*kn, *restitution, 0.5 * m_min)
                        / collision_resolution_steps,
                );
            }
            _ => unreachable!("law built from the model"),
        }
        if self.domain.faces.contains(&FaceCondition::Wall) {
            match (&self.config.wall_model, &self.wall_law) {
                (
                    WallModel::SpringSliderDashpot {
                        collision_resolution_steps,
                        ..
                    },
                    Some(ContactLaw::Hertz { e_star, .. }),
                ) => {
                    dt = dt.min(hertz(
                        *e_star,
                        d_min / 2.0,
                        u_max,
                        *collision_resolution_steps,
                    ));
                }
                (
                    WallModel::LinearSpringDashpot {
                        kn,
                        restitution,
                        collision_resolution_steps,
                        ..
                    },
                    _,
                ) => {
                    dt = dt.min(
                        linear_contact_time(*kn, *restitution, m_min) / collision_resolution_steps,
                    );
                }
                _ => {}
            }
        }
        if let Some(h) = self.config.max_substep {
            dt = dt.min(h);
        }
        dt
    }

    /// Number of collision sub-steps for an outer (fluid) step: `ceil(Δt / Δt_c)`, at least 1.
    pub fn substep_count(&self, dt_outer: f64) -> usize {
        let n = (dt_outer / self.collision_time_step()).ceil();
        if n.is_finite() && n >= 1.0 {
            n as usize
        } else {
            1
        }
    }
}
