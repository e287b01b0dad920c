//! The outer step in which no contact can act: one velocity-Verlet step without contact
//! detection instead of the collision sub-steps.
//!
//! Within an outer step the loads on a particle are constant (gravity, buoyancy, the
//! coupling's load), so while no pair and no wall can meet, each particle moves as
//!
//! `x(t) = x + v t + a t²/2`,  `a = f_ext/m + g (1 − ρ_f/ρ_p)`,
//!
//! which one kick–drift–kick step of the whole `Δt` gives exactly: the sub-steps would add
//! nothing but the cost of looking for contacts. A pair `(i, j)` cannot meet within `Δt` when
//! its surface gap exceeds the most its relative displacement can be,
//!
//! `g_ij > |v_i − v_j| Δt + |a_i − a_j| Δt²/2`,
//!
//! checked for every listed pair. A pair not in the lists was at least `skin` apart at the
//! last build, and each particle has moved at most `δ` since, so its gap is at least
//! `skin − 2δ`; with `c_v`, `c_a` the centres of the velocities' and accelerations' bounding
//! boxes, `|v_i − v_j| ≤ 2 max_k |v_k − c_v|` (and the same for `a`) bounds its closing. Every
//! particle against every wall face (its surface) and rebound face (its centre): the distance
//! against its own approach to the face.

use super::Dem;
use crate::particles::domain_box::{minimum_image, FaceCondition};
use crate::particles::neighbour_list::{wall_distance, wall_normal, CHUNK};
use crate::Vec3;
use rayon::prelude::*;

/// What one pass over the particles gathers for the test of [`Dem::contact_free`].
#[derive(Clone, Copy)]
struct Extent {
    /// Component-wise bounds of the velocities and accelerations.
    v_lo: Vec3,
    v_hi: Vec3,
    a_lo: Vec3,
    a_hi: Vec3,
    /// Largest squared displacement since the last list build.
    moved2: f64,
}

impl Extent {
    fn empty() -> Self {
        Extent {
            v_lo: Vec3::repeat(f64::INFINITY),
            v_hi: Vec3::repeat(f64::NEG_INFINITY),
            a_lo: Vec3::repeat(f64::INFINITY),
            a_hi: Vec3::repeat(f64::NEG_INFINITY),
            moved2: 0.0,
        }
    }

    fn merge(self, o: Extent) -> Extent {
        Extent {
            v_lo: self.v_lo.inf(&o.v_lo),
            v_hi: self.v_hi.sup(&o.v_hi),
            a_lo: self.a_lo.inf(&o.a_lo),
            a_hi: self.a_hi.sup(&o.a_hi),
            moved2: self.moved2.max(o.moved2),
        }
    }
}

impl Dem {
    /// Whether no pair and no wall can come into contact within an outer step of `dt`
    /// (module doc), so that [`Dem::free_flight`] takes the step exactly.
    pub(super) fn contact_free(&mut self, dt: f64) -> bool {
        #[cfg(test)]
        if self.never_free_flight {
            return false;
        }
        // a contact acting now (the last evaluation's loads) ends the test at once: in a bed
        // the first particles read decide it
        let zero = Vec3::zeros();
        let p = &self.particles;
        if p.is_empty()
            || p.contact_force
                .par_chunks(CHUNK)
                .any(|f| f.iter().any(|f| *f != zero))
        {
            return false;
        }
        let mut accelerations = std::mem::take(&mut self.acceleration);
        self.accelerations(&mut accelerations);
        let free = self.contact_free_with(&accelerations, dt);
        self.acceleration = accelerations;
        free
    }

    fn contact_free_with(&self, accelerations: &[Vec3], dt: f64) -> bool {
        let extent = self.extent(accelerations);
        let reach = |v: f64, a: f64| v * dt + 0.5 * a * dt * dt;
        let half_range = |lo: Vec3, hi: Vec3| 0.5 * (hi - lo).norm();
        let (dv, da) = (
            half_range(extent.v_lo, extent.v_hi),
            half_range(extent.a_lo, extent.a_hi),
        );
        // pairs outside the lists: gap ≥ skin − 2δ, closing ≤ 2 (dv Δt + da Δt²/2)
        let skin = self.lists.skin;
        if self.config.pair_collisions && skin - 2.0 * extent.moved2.sqrt() <= 2.0 * reach(dv, da) {
            return false;
        }
        self.faces_apart(accelerations, dt) && self.listed_pairs_apart(accelerations, dt)
    }

    /// `a = f_ext/m + g (1 − ρ_f/ρ_p)` of each particle (zero for fixed ones) into `out`.
    fn accelerations(&self, out: &mut Vec<Vec3>) {
        let p = &self.particles;
        let (g, rho_f) = (self.config.gravity, self.config.fluid_density);
        out.resize(p.len(), Vec3::zeros());
        out.par_iter_mut().enumerate().for_each(|(i, a)| {
            *a = {
                let inv_m = self.inv_mass[i];
                if inv_m == 0.0 {
                    Vec3::zeros()
                } else {
                    p.external_force[i] * inv_m + g * (1.0 - rho_f / p.density[i])
                }
            }
        });
    }

    fn extent(&self, acc: &[Vec3]) -> Extent {
        let p = &self.particles;
        let (length, inv_l) = (self.domain.length(), self.domain.inverse_periodic_length());
        let reference = &self.lists.reference;
        p.velocity
            .par_chunks(CHUNK)
            .enumerate()
            .map(|(c, v)| {
                let mut e = Extent::empty();
                for (k, v) in v.iter().enumerate() {
                    let i = c * CHUNK + k;
                    e.v_lo = e.v_lo.inf(v);
                    e.v_hi = e.v_hi.sup(v);
                    e.a_lo = e.a_lo.inf(&acc[i]);
                    e.a_hi = e.a_hi.sup(&acc[i]);
                    let d = minimum_image(p.position[i] - reference[i], length, inv_l);
                    e.moved2 = e.moved2.max(d.dot(&d));
                }
                e
            })
            .reduce(Extent::empty, Extent::merge)
    }

    /// No particle reaches a wall face (its surface) or a rebound face (its centre): the
    /// distance exceeds the approach `max(0, −(v − u_w)·n) Δt + |a·n| Δt²/2`.
    fn faces_apart(&self, acc: &[Vec3], dt: f64) -> bool {
        let dom = &self.domain;
        let faces: Vec<(usize, f64)> = (0..6)
            .filter_map(|f| match dom.faces[f] {
                FaceCondition::Wall if self.wall_law.is_some() => Some((f, 1.0)),
                FaceCondition::Rebound { .. } => Some((f, 0.0)),
                _ => None,
            })
            .collect();
        if faces.is_empty() {
            return true;
        }
        let p = &self.particles;
        (0..p.len()).into_par_iter().with_min_len(CHUNK).all(|i| {
            faces.iter().all(|&(f, surface)| {
                let nrm = wall_normal(f);
                let gap = wall_distance(dom, f, p.position[i]) - surface * self.radius[i];
                let approach = -(p.velocity[i] - dom.wall_velocity[f]).dot(&nrm);
                gap > approach.max(0.0) * dt + 0.5 * acc[i].dot(&nrm).abs() * dt * dt
            })
        })
    }

    /// Every listed pair's gap exceeds its closing `|Δv| Δt + |Δa| Δt²/2`.
    fn listed_pairs_apart(&self, acc: &[Vec3], dt: f64) -> bool {
        let p = &self.particles;
        let (x, v) = (&p.position, &p.velocity);
        let (length, inv_l) = (self.domain.length(), self.domain.inverse_periodic_length());
        let (row_start, partner, radius) =
            (&self.lists.row_start, &self.lists.partner, &self.radius);
        (0..p.len()).into_par_iter().with_min_len(CHUNK).all(|i| {
            (row_start[i] as usize..row_start[i + 1] as usize).all(|k| {
                let j = partner[k] as usize;
                let d = minimum_image(x[i] - x[j], length, inv_l);
                let gap = d.norm() - radius[i] - radius[j];
                gap > (v[i] - v[j]).norm() * dt + 0.5 * (acc[i] - acc[j]).norm() * dt * dt
            })
        })
    }

    /// One kick–drift–kick step of `dt` under the constant loads alone (no contact acts: see
    /// [`Dem::contact_free`], which also found every contact load zero, so the engine's
    /// kick–drift pass takes it); rebuilds the lists when a particle has moved more than half
    /// the skin.
    pub(super) fn free_flight(&mut self, dt: f64) {
        if self.kick_drift(dt) {
            self.rebuild();
        }
        let (motion, _, p) = self.motion_parts(dt);
        let zero = Vec3::zeros();
        p.v.par_chunks_mut(CHUNK)
            .zip(p.w.par_chunks_mut(CHUNK))
            .enumerate()
            .for_each(|(c, (v, w))| {
                for k in 0..v.len() {
                    let i = c * CHUNK + k;
                    if motion.inv_m[i] != 0.0 {
                        motion.half_kick(i, zero, zero, &mut v[k], &mut w[k]);
                    }
                }
            });
        self.time += dt;
        self.steps += 1;
        self.contact_free_steps += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::particles::contact_model::WallModel;
    use crate::particles::dem_config::DemConfig;
    use crate::particles::domain_box::DomainBox;
    use crate::particles::particle_state::ParticleState;
    use crate::particles::random_packing::random_packing;
    use crate::particles::{PairModel, SplitMix64};

    fn config() -> DemConfig {
        let wall = WallModel::LinearSpringDashpot {
            kn: 500.0,
            restitution: 0.5,
            kt: 1e2,
            mu: 0.3,
            tangential_damping_ratio: 0.5,
            collision_resolution_steps: 20.0,
        };
        let mut c = DemConfig::new(PairModel::linear(500.0, 0.5, 0.3), wall);
        c.fluid_density = 1000.0;
        c
    }

    /// A dilute cloud (φ 0.05) in a box periodic along x and y, walled along z, with random
    /// velocities and constant external forces: collisions and free flight both happen.
    fn cloud(seed: u64) -> (DomainBox, ParticleState) {
        let size = [0.008, 0.008, 0.012];
        let mut dom = DomainBox::walled(Vec3::zeros(), size);
        for f in 0..4 {
            dom.faces[f] = FaceCondition::Periodic;
        }
        let centres = random_packing(Vec3::zeros(), size, 1e-3, 0.05, seed).unwrap();
        let mut rng = SplitMix64::new(seed);
        let mut p = ParticleState::default();
        for (k, x) in centres.iter().enumerate() {
            p.push(k as u64, *x, 1e-3, 2500.0);
            let mut r = || 0.04 * (rng.next_f64() - 0.5);
            p.velocity[k] = Vec3::new(r(), r(), r());
            p.external_force[k] = Vec3::new(r(), r(), r()) * 1e-3;
        }
        (dom, p)
    }

    /// Free-flight steps give the trajectories of the collision sub-steps they replace, and
    /// no contact is missed: the same cloud advanced with and without them ends within
    /// rounding (a missed contact moves particles by a fraction of their size).
    #[test]
    fn free_flight_matches_the_sub_steps() {
        for seed in [1, 2, 3] {
            let (dom, p) = cloud(seed);
            let mut fast = Dem::new(config(), dom.clone(), p.clone()).unwrap();
            let mut slow = Dem::new(config(), dom, p).unwrap();
            slow.never_free_flight = true;
            let dt = 5.0 * slow.collision_time_step();
            let mut sub_steps = 0;
            for _ in 0..400 {
                fast.advance(dt);
                sub_steps += slow.advance(dt);
            }
            let free = fast.contact_free_steps();
            assert!(
                free > 40 && free < 360,
                "seed {seed}: {free} of 400 steps free: both kinds must be tested"
            );
            assert!(sub_steps > 400, "the sub-steps were not exercised");
            let (a, b) = (fast.particles(), slow.particles());
            let (length, inv_l) = (fast.domain.length(), fast.domain.inverse_periodic_length());
            let mut worst: f64 = 0.0;
            for i in 0..a.len() {
                let j = b.id.iter().position(|&id| id == a.id[i]).unwrap();
                let d = minimum_image(a.position[i] - b.position[j], length, inv_l);
                worst = worst.max(d.norm() / 1e-3);
            }
            assert!(worst < 1e-9, "seed {seed}: positions part by {worst:e} d");
        }
    }

    /// Two spheres closing at 1 m/s with a gap `g`: a step of `Δt` is never free from
    /// `Δt = g/|Δv|` on (the contact would be missed); below it, it is free when the pair is
    /// listed (`g` < skin), and, unlisted, while `Δt < skin/|Δv|` (the bound without the
    /// pair's own gap).
    #[test]
    fn a_contact_within_the_step_is_never_skipped() {
        let mut cfg = config();
        cfg.gravity = Vec3::zeros();
        let dom = DomainBox::uniform(Vec3::zeros(), [0.02; 3], FaceCondition::Periodic);
        for gap in [1e-5, 5e-5, 2e-4, 3e-3] {
            let mut p = ParticleState::default();
            p.push(1, [0.005, 0.01, 0.01], 1e-3, 2500.0);
            p.push(2, [0.006 + gap, 0.01, 0.01], 1e-3, 2500.0);
            p.velocity[0] = Vec3::new(0.5, 0.0, 0.0);
            p.velocity[1] = Vec3::new(-0.5, 0.0, 0.0);
            let mut dem = Dem::new(cfg.clone(), dom.clone(), p).unwrap();
            let skin = dem.lists.skin;
            let free_until = if gap < skin { gap } else { skin };
            assert!(
                dem.contact_free(0.999 * free_until),
                "gap {gap}: free below {free_until}"
            );
            assert!(
                !dem.contact_free(1.001 * free_until),
                "gap {gap}: not from {free_until}"
            );
            assert!(
                !dem.contact_free(1.001 * gap),
                "gap {gap}: a contact would be missed"
            );
        }
    }

    /// A wall within reach, and a rebound face the centre may cross, stop the free flight.
    #[test]
    fn walls_and_rebound_faces_are_checked() {
        let mut cfg = config();
        cfg.gravity = Vec3::new(0.0, 0.0, -10.0);
        cfg.fluid_density = 0.0;
        for rebound in [false, true] {
            let mut dom = DomainBox::walled(Vec3::zeros(), [0.01; 3]);
            if rebound {
                dom.faces[4] = FaceCondition::Rebound { e: 1.0, mu: 0.0 };
            }
            let mut p = ParticleState::default();
            // 0.1 mm above the floor (rebound: its centre 0.6 mm above), at rest
            p.push(1, [0.005, 0.005, 0.0006], 1e-3, 2500.0);
            let mut dem = Dem::new(cfg.clone(), dom, p).unwrap();
            let reach = if rebound { 6e-4 } else { 1e-4 };
            // falls g t²/2: free while that stays under the gap
            let t = (2.0 * reach / 10.0f64).sqrt();
            assert!(dem.contact_free(0.99 * t), "rebound {rebound}");
            assert!(!dem.contact_free(1.01 * t), "rebound {rebound}");
        }
    }
}
