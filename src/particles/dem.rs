//! The DEM engine: Newton–Euler for every particle (paper eq. 1) with gravity, buoyancy, the
//! hydrodynamic load set by the coupling, and soft-sphere contacts.
//!
//! Integration is velocity Verlet (kick–drift–kick), the scheme of both reference codes
//! (OpenFOAM's `CollidingCloud` "symplectic leapfrog" and LAMMPS' `fix nve/sphere`):
//!
//! ```text
//! v ← v + Δt/2 · F/m        ω ← ω + Δt/2 · T/I
//! x ← x + Δt · v
//! F, T ← contacts(x, v)     (velocity-dependent forces see the half-step velocity)
//! v ← v + Δt/2 · F/m        ω ← ω + Δt/2 · T/I
//! ```
//!
//! It is second order, symplectic for conservative forces (energy does not drift during free
//! flight: under constant gravity it is conserved exactly up to rounding) and needs one force
//! evaluation per step; symplectic Euler has the same cost but is first order in position.
//! `F = F_contact + F_external + m g (1 − ρ_f/ρ_p)`: gravity with buoyancy.

// Hot loops are plain indexed loops over contiguous arrays, by design.
#![allow(clippy::needless_range_loop)]

use std::f64::consts::PI;

use rayon::prelude::*;

use super::contact_model::ContactLaw;
use super::contact_work::{evaluate_chunk, ContactContext, ContactWork};
use super::dem_config::{
    validate_config, validate_domain, validate_particles, validate_walls, DemConfig,
};
use super::dem_error::DemError;
use super::domain_box::{minimum_image, DomainBox};
use super::motion::{Gather, Motion, Moving};
use super::neighbour_list::{wall_mask, ContactHistory, NeighbourList, CHUNK};
use super::particle_state::ParticleState;
use crate::Vec3;

mod collision_step;
mod free_flight;
mod monitors;
pub use monitors::{OverlapPartner, WorstOverlap};

/// Every array needed to continue a run bit for bit: particles in their current order (with
/// the last contact forces, which the next half-kick uses), the positions at the last list
/// rebuild (the lists are rebuilt from them identically), and the contact springs by id.
#[derive(Clone, Debug, PartialEq)]
pub struct DemSnapshot {
    pub particles: ParticleState,
    pub reference_position: Vec<Vec3>,
    pub history: ContactHistory,
    pub time: f64,
    pub steps: u64,
}

/// The DEM engine. Particle indices change at each list rebuild (cell sort); use `id`.
pub struct Dem {
    config: DemConfig,
    domain: DomainBox,
    particles: ParticleState,
    pair_law: ContactLaw,
    wall_law: Option<ContactLaw>,
    lists: NeighbourList,
    radius: Vec<f64>,
    inv_mass: Vec<f64>,
    inv_inertia: Vec<f64>,
    cell_size: f64,
    /// Per-particle sums of the pair loads (force, torque per unit radius) added by the
    /// particle's own block, and by the block before it (see `NeighbourList`).
    acc_own: Vec<[f64; 6]>,
    acc_prev: Vec<[f64; 6]>,
    time: f64,
    steps: u64,
    rebuilds: u64,
    /// Outer steps taken by [`Dem::free_flight`].
    contact_free_steps: u64,
    /// Each particle's acceleration under its constant loads, for the free-flight test.
    acceleration: Vec<Vec3>,
    /// Tests compare the free-flight step against the sub-steps it replaces.
    #[cfg(test)]
    never_free_flight: bool,
    scratch3: Vec<Vec3>,
    scratch1: Vec<f64>,
}

impl Dem {
    /// Validates everything, sorts the particles by cell, builds the lists and evaluates the
    /// initial contact forces.
    pub fn new(
        config: DemConfig,
        domain: DomainBox,
        mut particles: ParticleState,
    ) -> Result<Self, DemError> {
        validate_config(&config)?;
        validate_domain(&domain)?;
        validate_walls(&config, &domain)?;
        domain.constrain_to_plane(&mut particles);
        validate_particles(&particles, &domain, config.overlap_tolerance)?;
        let mut dem = Dem::assemble(config, domain, particles)?;
        // input index of each sorted particle, for error messages
        let input_index: Vec<u32> = {
            dem.lists
                .sort(&dem.domain, dem.cell_size, &dem.particles.position);
            dem.lists.order.clone()
        };
        dem.check_crowding()?;
        dem.apply_order();
        dem.build_lists();
        dem.check_overlaps(&input_index)?;
        dem.compute_contact_forces(0.0);
        Ok(dem)
    }

    /// Restarts from a snapshot taken by [`Dem::snapshot`] with the same config and box.
    pub fn restore(
        config: DemConfig,
        domain: DomainBox,
        snapshot: &DemSnapshot,
    ) -> Result<Self, DemError> {
        validate_config(&config)?;
        validate_domain(&domain)?;
        validate_walls(&config, &domain)?;
        if snapshot.reference_position.len() != snapshot.particles.len() {
            return Err(DemError::InconsistentArrays);
        }
        let mut dem = Dem::assemble(config, domain, snapshot.particles.clone())?;
        // The lists were built from the reference positions, in this very order: rebuild them
        // from those, so pair order and therefore summation order are identical.
        let mut current = std::mem::replace(
            &mut dem.particles.position,
            snapshot.reference_position.clone(),
        );
        dem.lists
            .sort(&dem.domain, dem.cell_size, &dem.particles.position);
        // a restart state is read from the case, as untrusted as its positions file
        dem.check_crowding()?;
        let identity = dem
            .lists
            .order
            .iter()
            .enumerate()
            .all(|(k, &o)| k == o as usize);
        if !identity {
            // A snapshot not taken by this engine (or edited): sort it now. The run stays
            // correct, only the bit-for-bit continuation is lost.
            current = dem
                .lists
                .order
                .iter()
                .map(|&o| current[o as usize])
                .collect();
            dem.apply_order();
        }
        dem.build_lists();
        dem.particles.position = current;
        dem.lists
            .import_history(&dem.particles.id, &snapshot.history);
        dem.time = snapshot.time;
        dem.steps = snapshot.steps;
        Ok(dem)
    }

    fn assemble(
        config: DemConfig,
        domain: DomainBox,
        particles: ParticleState,
    ) -> Result<Self, DemError> {
        validate_particles(&particles, &domain, f64::INFINITY)?;
        let d_max = particles.diameter.iter().cloned().fold(0.0, f64::max);
        let skin = config.skin_fraction * d_max.max(f64::MIN_POSITIVE);
        let cell_size = if d_max > 0.0 { d_max + skin } else { 0.0 };
        let l = domain.length();
        // The minimum-image convention matters only for pair contacts: a fixed array of one
        // sphere per periodic cell (porous media) has none.
        for a in 0..3 {
            if config.pair_collisions && domain.is_periodic(a) && l[a] < 2.0 * cell_size {
                return Err(DemError::PeriodicTooShort {
                    axis: a,
                    length: l[a],
                    needed: 2.0 * cell_size,
                });
            }
        }
        let pair_law = ContactLaw::from_pair(&config.pair_model);
        let wall_law = ContactLaw::from_wall(&config.wall_model);
        let lists = NeighbourList {
            skin,
            ..Default::default()
        };
        let mut dem = Dem {
            config,
            domain,
            particles,
            pair_law,
            wall_law,
            lists,
            radius: Vec::new(),
            inv_mass: Vec::new(),
            inv_inertia: Vec::new(),
            cell_size,
            acc_own: Vec::new(),
            acc_prev: Vec::new(),
            time: 0.0,
            steps: 0,
            rebuilds: 0,
            contact_free_steps: 0,
            acceleration: Vec::new(),
            #[cfg(test)]
            never_free_flight: false,
            scratch3: Vec::new(),
            scratch1: Vec::new(),
        };
        dem.refresh_derived();
        Ok(dem)
    }

    fn refresh_derived(&mut self) {
        let p = &self.particles;
        let n = p.len();
        self.radius.clear();
        self.inv_mass.clear();
        self.inv_inertia.clear();
        for i in 0..n {
            self.radius.push(0.5 * p.diameter[i]);
            let free = !p.fixed[i];
            self.inv_mass.push(if free { 1.0 / p.mass(i) } else { 0.0 });
            self.inv_inertia.push(if free {
                1.0 / p.moment_of_inertia(i)
            } else {
                0.0
            });
        }
    }

    fn apply_order(&mut self) {
        let order = std::mem::take(&mut self.lists.order);
        self.particles
            .permute(&order, &mut self.scratch3, &mut self.scratch1);
        self.lists.order = order;
        self.refresh_derived();
    }

    fn build_lists(&mut self) {
        let mask = if self.wall_law.is_some() {
            wall_mask(&self.domain)
        } else {
            [false; 6]
        };
        self.lists.build(
            &self.domain,
            &self.particles.position,
            &self.radius,
            &self.particles.fixed,
            mask,
            self.config.pair_collisions,
        );
        self.rebuilds += 1;
    }

    /// Re-sorts and rebuilds the lists, carrying the springs across through the permutation.
    fn rebuild(&mut self) {
        self.lists.save_history();
        self.lists
            .sort(&self.domain, self.cell_size, &self.particles.position);
        self.apply_order();
        self.build_lists();
        self.lists.restore_saved_history();
    }

    /// Before the first lists: refuses a contact cell whose particles' volume exceeds the box
    /// their spheres can reach (the cell grown by the largest diameter), `Σ V_p > Π (h_a +
    /// d_max)`. Such spheres overlap for certain; listing their pairs would cost up to the
    /// square of their count (10⁶ particles at one point: 5·10¹¹ pairs) before the overlap
    /// check could name them.
    /// Runs after a sort and before [`Dem::apply_order`]: the particles are still in the
    /// order the sort's `order` indexes.
    fn check_crowding(&self) -> Result<(), DemError> {
        let lists = &self.lists;
        let (size, d_max) = (
            lists.grid.cell_size(),
            self.particles.diameter.iter().cloned().fold(0.0, f64::max),
        );
        let room: f64 = (0..3).map(|a| size[a] + d_max).product();
        let p = &self.particles;
        for c in 0..lists.grid.cell_count() {
            let (s, e) = (
                lists.cell_start[c] as usize,
                lists.cell_start[c + 1] as usize,
            );
            if e - s < 2 {
                continue;
            }
            let members = &lists.order[s..e];
            let solid: f64 = members
                .iter()
                .map(|&o| {
                    let d = p.diameter[o as usize];
                    std::f64::consts::PI / 6.0 * d * d * d
                })
                .sum();
            if solid > room {
                let (a, b) = (members[0] as usize, members[1] as usize);
                return Err(DemError::Crowded {
                    count: e - s,
                    index_a: a,
                    index_b: b,
                    centre: p.position[a],
                    solid,
                    room,
                });
            }
        }
        Ok(())
    }

    fn check_overlaps(&self, input_index: &[u32]) -> Result<(), DemError> {
        let (length, inv_l) = (self.domain.length(), self.domain.inverse_periodic_length());
        let x = &self.particles.position;
        for i in 0..self.particles.len() {
            for k in self.lists.row_start[i] as usize..self.lists.row_start[i + 1] as usize {
                let j = self.lists.partner[k] as usize;
                let d = minimum_image(
                    Vec3::new(x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]),
                    length,
                    inv_l,
                );
                let overlap = self.radius[i] + self.radius[j] - d.dot(&d).sqrt();
                let d_min = 2.0 * self.radius[i].min(self.radius[j]);
                if overlap > self.config.overlap_tolerance * d_min {
                    let (a, b) = (input_index[i] as usize, input_index[j] as usize);
                    let (a, b, ia, ib) = if a < b { (a, b, i, j) } else { (b, a, j, i) };
                    return Err(DemError::Overlap {
                        index_a: a,
                        id_a: self.particles.id[ia],
                        index_b: b,
                        id_b: self.particles.id[ib],
                        overlap_over_d: overlap / d_min,
                    });
                }
            }
        }
        Ok(())
    }

    // ----- accessors -----

    pub fn particles(&self) -> &ParticleState {
        &self.particles
    }

    /// The hydrodynamic loads, for the coupling to set before [`Dem::advance`]. Index order is
    /// that of [`Dem::particles`] at this moment.
    pub fn external_loads_mut(&mut self) -> (&mut [Vec3], &mut [Vec3]) {
        (
            &mut self.particles.external_force,
            &mut self.particles.external_torque,
        )
    }

    pub fn config(&self) -> &DemConfig {
        &self.config
    }

    pub fn domain(&self) -> &DomainBox {
        &self.domain
    }

    pub fn time(&self) -> f64 {
        self.time
    }

    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Number of neighbour-list builds so far (including the initial one).
    pub fn list_rebuilds(&self) -> u64 {
        self.rebuilds
    }

    /// Outer steps in which no contact could act, taken in one step without contact
    /// detection ([`Dem::advance`]).
    pub fn contact_free_steps(&self) -> u64 {
        self.contact_free_steps
    }

    /// Number of pairs in the neighbour list.
    pub fn pair_count(&self) -> usize {
        self.lists.partner.len()
    }

    /// Bytes held by particle arrays, derived arrays and lists (capacity).
    pub fn memory_bytes(&self) -> usize {
        self.particles.memory_bytes()
            + 8 * (self.radius.capacity() + self.inv_mass.capacity() + self.inv_inertia.capacity())
            + self.lists.memory_bytes()
            + 24 * (self.scratch3.capacity() + self.acceleration.capacity())
            + 48 * (self.acc_own.capacity() + self.acc_prev.capacity())
            + 8 * self.scratch1.capacity()
    }

    // ----- restart -----

    pub fn snapshot(&self) -> DemSnapshot {
        DemSnapshot {
            particles: self.particles.clone(),
            reference_position: self.lists.reference.clone(),
            history: self.lists.export_history(&self.particles.id),
            time: self.time,
            steps: self.steps,
        }
    }

    // ----- time stepping (the collision sub-step: dem/collision_step.rs) -----

    /// Advances by one outer step `dt_outer` in equal sub-steps (external loads held fixed);
    /// returns the number of sub-steps taken. A step in which no contact can act is one
    /// step without contact detection (`dem/free_flight.rs`): exact under constant loads.
    pub fn advance(&mut self, dt_outer: f64) -> usize {
        if self.contact_free(dt_outer) {
            self.free_flight(dt_outer);
            return 1;
        }
        let n = self.substep_count(dt_outer);
        let h = dt_outer / n as f64;
        // `step` n times, with each sub-step's last pass fused with the next one's first.
        let mut rebuild = self.kick_drift(h);
        for s in 0..n {
            if rebuild {
                self.rebuild();
            }
            self.evaluate_contacts(h);
            if s + 1 < n {
                rebuild = self.gather_kick_drift(h);
            } else {
                self.gather_contacts(Some(h));
            }
            self.time += h;
            self.steps += 1;
        }
        n
    }

    /// One velocity-Verlet step of size `h`. Three passes over the particles: half-kick +
    /// drift + displacement check fused; pair forces; gather + half-kick fused (the
    /// engine is memory-bound, so each pass streams as few arrays as it can).
    pub fn step(&mut self, h: f64) {
        if self.kick_drift(h) {
            self.rebuild();
        }
        self.evaluate_contacts(h);
        self.gather_contacts(Some(h));
        self.time += h;
        self.steps += 1;
    }

    /// The engine split for a motion pass: what it reads ([`Motion`], [`Gather`]) and the
    /// particle arrays it writes ([`Moving`]).
    fn motion_parts(&mut self, h: f64) -> (Motion<'_>, Gather<'_>, Moving<'_>) {
        let dom = &self.domain;
        let p = &mut self.particles;
        let motion = Motion {
            g: self.config.gravity,
            rho_f: self.config.fluid_density,
            h,
            half: 0.5 * h,
            lo: dom.lo,
            length: dom.length(),
            inv_l: dom.inverse_periodic_length(),
            faces: dom.faces,
            free: dom.free_axes(),
            limit: 0.25 * self.lists.skin * self.lists.skin,
            reference: &self.lists.reference,
            inv_m: &self.inv_mass,
            inv_i: &self.inv_inertia,
            rho: &p.density,
            fe: &p.external_force,
            te: &p.external_torque,
        };
        let gather = Gather {
            own: &self.acc_own,
            prev: &self.acc_prev,
            lists: &self.lists,
            radius: &self.radius,
        };
        let moving = Moving {
            x: &mut p.position,
            v: &mut p.velocity,
            w: &mut p.angular_velocity,
            fc: &mut p.contact_force,
            tc: &mut p.contact_torque,
        };
        (motion, gather, moving)
    }

    /// `v += h/2 a`, `ω += h/2 α`, `x += h v`, periodic wrap and rebound faces; returns whether
    /// some particle has moved more than half the skin since the last list build.
    fn kick_drift(&mut self, h: f64) -> bool {
        let (motion, _, p) = self.motion_parts(h);
        let (fc, tc) = (&*p.fc, &*p.tc);
        p.x.par_chunks_mut(CHUNK)
            .zip(p.v.par_chunks_mut(CHUNK))
            .zip(p.w.par_chunks_mut(CHUNK))
            .enumerate()
            .map(|(c, ((x, v), w))| {
                let base = c * CHUNK;
                let mut moved = false;
                for k in 0..x.len() {
                    let i = base + k;
                    moved |= motion.kick_drift(i, fc[i], tc[i], &mut x[k], &mut v[k], &mut w[k]);
                }
                moved
            })
            .reduce(|| false, |a, b| a | b)
    }

    /// Evaluates every contact at the current positions and velocities into
    /// `contact_force`/`contact_torque`; `dt` advances the tangential springs.
    fn compute_contact_forces(&mut self, dt: f64) {
        self.evaluate_contacts(dt);
        self.gather_contacts(None);
    }

    /// Pass 1: each listed pair and wall contact once. Blocks of particles run in parallel;
    /// each scatters its pair loads into the sums it owns (its own particles, and the
    /// "from the previous block" sums of the next block), far pairs into their load records.
    /// The loop is specialised per contact law and for boxes without periodic axes.
    fn evaluate_contacts(&mut self, dt: f64) {
        let n = self.particles.len();
        let pair_law = self.pair_law;
        let wall_law = self.wall_law;
        let lists = &mut self.lists;
        let p = &self.particles;
        let ctx = ContactContext {
            x: &p.position,
            v: &p.velocity,
            w: &p.angular_velocity,
            radius: &self.radius,
            inv_m: &self.inv_mass,
            row_start: &lists.row_start,
            partner: &lists.partner,
            wall_start: &lists.wall_start,
            wall_face: &lists.wall_face,
            domain: &self.domain,
            length: self.domain.length(),
            inv_l: self.domain.inverse_periodic_length(),
            wall_law,
            dt,
        };
        let block = lists.block.max(1);
        // every entry is overwritten by its owning block before it is added to
        self.acc_own.resize(n, [0.0; 6]);
        self.acc_prev.resize(n, [0.0; 6]);
        // Nobody owns the first block's "previous" sums: keep them zero (a block size that
        // grew at the last rebuild would otherwise leave stale loads there).
        self.acc_prev[..block.min(n)].fill([0.0; 6]);
        let mut own: Vec<_> = self.acc_own.chunks_mut(block).collect();
        let mut next: Vec<Option<&mut [[f64; 6]]>> =
            self.acc_prev.chunks_mut(block).skip(1).map(Some).collect();
        next.push(None);
        let mut work = Vec::with_capacity(n.div_ceil(block));
        {
            let (mut hist, mut far) = (&mut lists.history[..], &mut lists.far_load[..]);
            let (mut whist, mut wforce, mut wtorque) = (
                &mut lists.wall_history[..],
                &mut lists.wall_force[..],
                &mut lists.wall_torque[..],
            );
            let mut far_done = 0;
            for (b, (own, next)) in own.drain(..).zip(next.drain(..)).enumerate() {
                let (p0, p1) = (b * block, ((b + 1) * block).min(n));
                let np = (ctx.row_start[p1] - ctx.row_start[p0]) as usize;
                let nw = (ctx.wall_start[p1] - ctx.wall_start[p0]) as usize;
                let far_end = lists.far_pair[far_done..]
                    .partition_point(|&k| k < ctx.row_start[p1])
                    + far_done;
                let (h0, h1) = std::mem::take(&mut hist).split_at_mut(np);
                let (f0, f1) = std::mem::take(&mut far).split_at_mut(far_end - far_done);
                let (wh0, wh1) = std::mem::take(&mut whist).split_at_mut(nw);
                let (wf0, wf1) = std::mem::take(&mut wforce).split_at_mut(nw);
                let (wt0, wt1) = std::mem::take(&mut wtorque).split_at_mut(nw);
                (hist, far, whist, wforce, wtorque) = (h1, f1, wh1, wf1, wt1);
                far_done = far_end;
                work.push(ContactWork {
                    p0,
                    p1,
                    block,
                    hist: h0,
                    far: f0,
                    whist: wh0,
                    wforce: wf0,
                    wtorque: wt0,
                    own,
                    next,
                });
            }
        }
        let periodic = ctx.inv_l != Vec3::zeros();
        let ctx = &ctx;
        let run = |wk: &mut ContactWork| match (periodic, pair_law) {
            (true, ContactLaw::Linear { .. }) => {
                evaluate_chunk::<true, _>(wk, ctx, &|n, d, r, m, u, s, dt, xi| {
                    pair_law.linear_force(n, d, r, m, u, s, dt, xi)
                })
            }
            (false, ContactLaw::Linear { .. }) => {
                evaluate_chunk::<false, _>(wk, ctx, &|n, d, r, m, u, s, dt, xi| {
                    pair_law.linear_force(n, d, r, m, u, s, dt, xi)
                })
            }
            (true, ContactLaw::Hertz { .. }) => {
                evaluate_chunk::<true, _>(wk, ctx, &|n, d, r, m, u, s, dt, xi| {
                    pair_law.hertz_force(n, d, r, m, u, s, dt, xi)
                })
            }
            (false, ContactLaw::Hertz { .. }) => {
                evaluate_chunk::<false, _>(wk, ctx, &|n, d, r, m, u, s, dt, xi| {
                    pair_law.hertz_force(n, d, r, m, u, s, dt, xi)
                })
            }
        };
        if rayon::current_num_threads() == 1 {
            work.iter_mut().for_each(run);
        } else {
            work.par_iter_mut().for_each(run);
        }
    }

    /// Pass 2: each particle gathers its own rows (+), reverse rows (−) and walls into
    /// `contact_force`/`contact_torque`, then, within a step, takes its second half-kick.
    fn gather_contacts(&mut self, kick: Option<f64>) {
        let (motion, gather, p) = self.motion_parts(kick.unwrap_or(0.0));
        p.fc.par_chunks_mut(CHUNK)
            .zip(p.tc.par_chunks_mut(CHUNK))
            .zip(p.v.par_chunks_mut(CHUNK))
            .zip(p.w.par_chunks_mut(CHUNK))
            .enumerate()
            .for_each(|(c, (((fo, to), v), w))| {
                let base = c * CHUNK;
                for k in 0..fo.len() {
                    let i = base + k;
                    let (f, t) = gather.loads(i);
                    fo[k] = f;
                    to[k] = t;
                    if kick.is_some() && motion.inv_m[i] != 0.0 {
                        motion.half_kick(i, f, t, &mut v[k], &mut w[k]);
                    }
                }
            });
    }

    /// Between two sub-steps of one outer step: pass 2 of the first (gather and second
    /// half-kick) and pass 0 of the next (first half-kick, drift, checks) in one sweep, each
    /// particle's arithmetic exactly that of [`Self::gather_contacts`] then
    /// [`Self::kick_drift`] (so the result is bit-identical), streaming the particle arrays
    /// once instead of twice. Returns whether the lists need rebuilding.
    fn gather_kick_drift(&mut self, h: f64) -> bool {
        let (motion, gather, p) = self.motion_parts(h);
        p.fc.par_chunks_mut(CHUNK)
            .zip(p.tc.par_chunks_mut(CHUNK))
            .zip(p.x.par_chunks_mut(CHUNK))
            .zip(p.v.par_chunks_mut(CHUNK))
            .zip(p.w.par_chunks_mut(CHUNK))
            .enumerate()
            .map(|(c, ((((fo, to), x), v), w))| {
                let base = c * CHUNK;
                let mut moved = false;
                for k in 0..fo.len() {
                    let i = base + k;
                    let (f, t) = gather.loads(i);
                    fo[k] = f;
                    to[k] = t;
                    if motion.inv_m[i] != 0.0 {
                        motion.half_kick(i, f, t, &mut v[k], &mut w[k]);
                    }
                    moved |= motion.kick_drift(i, f, t, &mut x[k], &mut v[k], &mut w[k]);
                }
                moved
            })
            .reduce(|| false, |a, b| a | b)
    }
}

/// Volume of a sphere of diameter `d`.
pub fn sphere_volume(d: f64) -> f64 {
    PI * d * d * d / 6.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::particles::contact_model::{PairModel, TangentialRule, WallModel};
    use crate::particles::domain_box::FaceCondition;
    use crate::particles::random_packing::random_packing;

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * a.abs().max(b.abs()).max(1e-300)
    }

    fn hertz_pair(rule: TangentialRule) -> PairModel {
        PairModel::SpringSliderDashpot {
            youngs_modulus: 1e7,
            poissons_ratio: 0.35,
            alpha: 0.12,
            b: 1.5,
            mu: 0.3,
            collision_resolution_steps: 12.0,
            tangential: rule,
        }
    }

    fn two_particles(xa: impl Into<Vec3>, xb: impl Into<Vec3>, da: f64, db: f64) -> ParticleState {
        let mut p = ParticleState::default();
        p.push(1, xa, da, 2500.0);
        p.push(2, xb, db, 1500.0);
        p
    }

    fn lenient(pair: PairModel, wall: WallModel) -> DemConfig {
        let mut c = DemConfig::new(pair, wall);
        c.gravity = Vec3::zeros();
        c.overlap_tolerance = 1.0;
        c
    }

    /// Same forces as DPMFoam for the same pair: OpenFOAM v1912
    /// `PairSpringSliderDashpot::evaluatePair`, written out by hand:
    /// E* = E/(2(1−ν²)), G* = E/(2(1+ν)) / (2(2−ν)), R = d_A d_B / (2(d_A + d_B)),
    /// M = m_A m_B/(m_A + m_B), k_N = 4/3 √R E*, η_N = α √(M k_N) δ^{1/4},
    /// F_N = r̂ (k_N δ^b − η_N U_AB·r̂) with r̂ = (x_A − x_B)/|x_A − x_B|,
    /// U_slip = U_AB − (U_AB·r̂) r̂ − (d_A/2 ω_A + d_B/2 ω_B) × r̂, ξ = U_slip Δt (fresh contact),
    /// k_T = 8 √(R δ) G*, η_T = η_N; if k_T|ξ| > μ|F_N|: F_T = −μ|F_N| Û_slip, else
    /// F_T = −k_T ξ − η_T U_slip; torque on A = (d_A/2 · −r̂) × F_T, on B = (d_B/2 · r̂) × −F_T.
    #[test]
    fn pair_force_matches_dpmfoam_formulas() {
        let (da, db) = (2e-3, 1.5e-3);
        let cases: [(f64, Vec3, Vec3, Vec3, f64); 4] = [
            // (overlap, U_A − U_B, ω_A, ω_B, Δt)
            (
                1e-5,
                Vec3::new(0.0, 0.0, -0.2),
                Vec3::zeros(),
                Vec3::zeros(),
                1e-6,
            ),
            (
                3e-5,
                Vec3::new(0.05, -0.01, -0.1),
                Vec3::new(10.0, 0.0, -3.0),
                Vec3::new(0.0, 5.0, 1.0),
                1e-6,
            ),
            (
                2e-5,
                Vec3::new(0.3, 0.2, 0.05),
                Vec3::zeros(),
                Vec3::new(0.0, 0.0, 40.0),
                1e-4,
            ),
            (
                5e-6,
                Vec3::new(0.001, 0.0, 0.3),
                Vec3::new(1.0, 1.0, 0.0),
                Vec3::zeros(),
                1e-7,
            ),
        ];
        let (e, nu, alpha, b, mu) = (1e7f64, 0.35f64, 0.12f64, 1.5f64, 0.3f64);
        let mut slid = 0;
        let mut stuck = 0;
        for (delta, u, wa, wb, dt) in cases {
            let dir = Vec3::new(0.3f64, -0.5, 0.81);
            let rhat = dir * (1.0 / dir.norm());
            let sep = 0.5 * (da + db) - delta;
            let xb = [0.01, 0.01, 0.01];
            let xa = Vec3::new(
                xb[0] + sep * rhat[0],
                xb[1] + sep * rhat[1],
                xb[2] + sep * rhat[2],
            );
            let mut p = two_particles(xa, Vec3::from(xb), da, db);
            p.velocity[0] = u;
            p.angular_velocity[0] = wa;
            p.angular_velocity[1] = wb;
            let domain = DomainBox::uniform(Vec3::zeros(), [0.02; 3], FaceCondition::Periodic);
            let mut dem = Dem::new(
                lenient(hertz_pair(TangentialRule::DpmFoamReset), WallModel::None),
                domain,
                p,
            )
            .unwrap();
            dem.compute_contact_forces(dt);
            let ia = dem.particles.id.iter().position(|&i| i == 1).unwrap();
            let ib = 1 - ia;

            // hand evaluation
            let e_star = e / (2.0 * (1.0 - nu * nu));
            let g_star = e / (2.0 * (1.0 + nu)) / (2.0 * (2.0 - nu));
            let r = 0.5 * da * db / (da + db);
            let ma = 2500.0 * PI * da.powi(3) / 6.0;
            let mb = 1500.0 * PI * db.powi(3) / 6.0;
            let m = ma * mb / (ma + mb);
            let kn = 4.0 / 3.0 * r.sqrt() * e_star;
            let eta_n = alpha * (m * kn).sqrt() * delta.powf(0.25);
            let un = u.dot(&rhat);
            let fn_mag = kn * delta.powf(b) - eta_n * un;
            let f_n = rhat * fn_mag;
            let spin = Vec3::new(
                da / 2.0 * wa[0] + db / 2.0 * wb[0],
                da / 2.0 * wa[1] + db / 2.0 * wb[1],
                da / 2.0 * wa[2] + db / 2.0 * wb[2],
            );
            let c = spin.cross(&rhat);
            let slip = Vec3::new(
                u[0] - un * rhat[0] - c[0],
                u[1] - un * rhat[1] - c[1],
                u[2] - un * rhat[2] - c[2],
            );
            let xi = slip * dt;
            let kt = 8.0 * (r * delta).sqrt() * g_star;
            let f_t = if kt * xi.norm() > mu * fn_mag.abs() {
                slid += 1;
                slip * (-mu * fn_mag.abs() / slip.norm())
            } else {
                stuck += 1;
                Vec3::new(
                    -kt * xi[0] - eta_n * slip[0],
                    -kt * xi[1] - eta_n * slip[1],
                    -kt * xi[2] - eta_n * slip[2],
                )
            };
            let f_a = Vec3::new(f_n[0] + f_t[0], f_n[1] + f_t[1], f_n[2] + f_t[2]);
            let t_a = (rhat * (-da / 2.0)).cross(&f_t);
            let t_b = (rhat * (db / 2.0)).cross(&(f_t * (-1.0)));
            let fa = dem.particles.contact_force[ia];
            let fb = dem.particles.contact_force[ib];
            let ta = dem.particles.contact_torque[ia];
            let tb = dem.particles.contact_torque[ib];
            let scale_f = f_a.norm();
            for k in 0..3 {
                assert!(
                    (fa[k] - f_a[k]).abs() < 1e-12 * scale_f,
                    "F_A {fa:?} vs {f_a:?}"
                );
                assert!((fb[k] + f_a[k]).abs() < 1e-12 * scale_f, "F_B {fb:?}");
                assert!(
                    (ta[k] - t_a[k]).abs() < 1e-12 * scale_f * da + 1e-300,
                    "T_A {ta:?} vs {t_a:?}"
                );
                assert!(
                    (tb[k] - t_b[k]).abs() < 1e-12 * scale_f * db + 1e-300,
                    "T_B {tb:?} vs {t_b:?}"
                );
            }
        }
        assert!(
            slid > 0 && stuck > 0,
            "both branches exercised: slid {slid}, stuck {stuck}"
        );
    }

    /// OpenFOAM v1912 `WallSpringSliderDashpot::evaluateWall`, by hand:
    /// 1/E* = (1−ν_p²)/E_p + (1−ν_w²)/E_w, k_N = 4/3 √r E*, G* = 1/(2((2+ν_p−ν_p²)/E_p + (2+ν_w−ν_w²)/E_w)),
    /// η_N = α √(m k_N) δ^{1/4}, U_slip = U − (U·n)n + ω × (−r n), ξ += U_slip Δt (the spring
    /// kept from step to step in the contact's `WallCollisionRecord`, zeroed when it slides),
    /// k_T = 8 √(r δ) G*, slide test and torque as for pairs. Two evaluations of the same
    /// contact: the second sees the first's spring.
    #[test]
    fn wall_force_matches_dpmfoam_formulas() {
        let (ep, np, ew, nw, alpha, b, mu) =
            (1e7f64, 0.35f64, 2e8f64, 0.3f64, 0.1f64, 1.5f64, 0.25f64);
        let wall = WallModel::SpringSliderDashpot {
            youngs_modulus: ew,
            poissons_ratio: nw,
            particle_youngs_modulus: ep,
            particle_poissons_ratio: np,
            alpha,
            b,
            mu,
            collision_resolution_steps: 12.0,
            tangential: TangentialRule::DpmFoamReset,
        };
        let d = 2e-3;
        for (delta, v, w, dt) in [
            (
                2e-5,
                Vec3::new(0.01, 0.0, -0.3),
                Vec3::new(0.0, 2.0, 0.0),
                1e-6,
            ),
            (1e-5, Vec3::new(0.5, 0.2, -0.1), Vec3::zeros(), 1e-5),
        ] {
            let mut p = ParticleState::default();
            p.push(9, [0.01, 0.01, d / 2.0 - delta], d, 2500.0);
            p.velocity[0] = v;
            p.angular_velocity[0] = w;
            let mut dem = Dem::new(
                lenient(hertz_pair(TangentialRule::DpmFoamReset), wall.clone()),
                DomainBox::walled(Vec3::zeros(), [0.02; 3]),
                p,
            )
            .unwrap();
            let r = d / 2.0;
            let m = 2500.0 * PI * d.powi(3) / 6.0;
            let e_star = 1.0 / ((1.0 - np * np) / ep + (1.0 - nw * nw) / ew);
            let kn = 4.0 / 3.0 * r.sqrt() * e_star;
            let g_star = 1.0 / (2.0 * ((2.0 + np - np * np) / ep + (2.0 + nw - nw * nw) / ew));
            let n = Vec3::new(0.0, 0.0, 1.0);
            let eta_n = alpha * (m * kn).sqrt() * delta.powf(0.25);
            let fn_mag = kn * delta.powf(b) - eta_n * v.dot(&n);
            let c = w.cross(&(n * (-r)));
            let slip = Vec3::new(v[0] + c[0], v[1] + c[1], 0.0);
            let kt = 8.0 * (r * delta).sqrt() * g_star;
            let mut xi = Vec3::zeros();
            let mut slid = Vec::new();
            for _ in 0..2 {
                dem.compute_contact_forces(dt);
                xi = Vec3::new(xi[0] + slip[0] * dt, xi[1] + slip[1] * dt, 0.0);
                let f_t = if kt * xi.norm() > mu * fn_mag.abs() {
                    xi = Vec3::zeros();
                    slid.push(true);
                    slip * (-mu * fn_mag.abs() / slip.norm())
                } else {
                    slid.push(false);
                    Vec3::new(
                        -kt * xi[0] - eta_n * slip[0],
                        -kt * xi[1] - eta_n * slip[1],
                        0.0,
                    )
                };
                let f = Vec3::new(f_t[0], f_t[1], fn_mag);
                let t = (n * (-r)).cross(&f_t);
                let (fo, to) = (
                    dem.particles.contact_force[0],
                    dem.particles.contact_torque[0],
                );
                for k in 0..3 {
                    assert!((fo[k] - f[k]).abs() < 1e-12 * f.norm(), "{fo:?} vs {f:?}");
                    assert!(
                        (to[k] - t[k]).abs() < 1e-12 * f.norm() * r,
                        "{to:?} vs {t:?}"
                    );
                }
            }
            // the first contact sticks, its spring doubled at the second evaluation; the
            // second slides at once
            assert_eq!(
                slid,
                if dt == 1e-6 {
                    [false, false]
                } else {
                    [true, true]
                }
            );
        }
    }

    /// A moving wall (OpenFOAM's wall data: the fluid's velocity on the face) acts on a
    /// particle as the wall at rest acts on the particle moving relative to it.
    #[test]
    fn a_moving_wall_acts_through_the_relative_velocity() {
        let wall = WallModel::SpringSliderDashpot {
            youngs_modulus: 2e8,
            poissons_ratio: 0.3,
            particle_youngs_modulus: 1e7,
            particle_poissons_ratio: 0.35,
            alpha: 0.1,
            b: 1.5,
            mu: 0.25,
            collision_resolution_steps: 12.0,
            tangential: TangentialRule::DpmFoamReset,
        };
        let d = 2e-3;
        let loads = |v: Vec3, uw: Vec3| {
            let mut p = ParticleState::default();
            p.push(9, [0.01, 0.01, d / 2.0 - 2e-5], d, 2500.0);
            p.velocity[0] = v;
            p.angular_velocity[0] = Vec3::new(0.0, 3.0, 0.0);
            let mut dom = DomainBox::walled(Vec3::zeros(), [0.02; 3]);
            dom.wall_velocity[4] = uw;
            let mut dem = Dem::new(
                lenient(hertz_pair(TangentialRule::DpmFoamReset), wall.clone()),
                dom,
                p,
            )
            .unwrap();
            dem.compute_contact_forces(1e-6);
            (
                dem.particles.contact_force[0],
                dem.particles.contact_torque[0],
            )
        };
        let uw = Vec3::new(0.5, -0.2, 0.0);
        let moving = loads(Vec3::new(0.01, 0.0, -0.3), uw);
        let relative = loads(Vec3::new(0.01 - uw[0], 0.0 - uw[1], -0.3), Vec3::zeros());
        assert_eq!(moving, relative);
        // the wall drags the particle its way
        assert!(moving.0[0] > 0.0 && moving.0[1] < 0.0, "{moving:?}");
        assert_ne!(moving, loads(Vec3::new(0.01, 0.0, -0.3), Vec3::zeros()));
    }

    /// DPMFoam's sub-cycle count, by hand (`PairSpringSliderDashpot::nSubCycles`):
    /// Δt_c = 5.429675 (d_min/4) (ρ_max/(E* √(2 U_max)))^{0.4} / N, n = ceil(Δt/Δt_c).
    #[test]
    fn substeps_follow_the_dpmfoam_rule() {
        let mut p = two_particles([0.005, 0.01, 0.01], [0.015, 0.01, 0.01], 1e-3, 2e-3);
        p.velocity[0] = Vec3::new(0.3, 0.0, 0.4);
        p.angular_velocity[1] = Vec3::new(0.0, 100.0, 0.0);
        let mut dom = DomainBox::walled(Vec3::zeros(), [0.02; 3]);
        dom.faces = [FaceCondition::Periodic; 6];
        let dem = Dem::new(
            lenient(hertz_pair(TangentialRule::CappedSpring), WallModel::None),
            dom,
            p,
        )
        .unwrap();
        let e_star = 1e7 / (2.0 * (1.0 - 0.35f64 * 0.35));
        let u_max = 2.0 * f64::max(0.5, 100.0 * 1e-3);
        let dtc = 5.429675 * (1e-3 / 4.0) * (2500.0 / (e_star * u_max.sqrt())).powf(0.4) / 12.0;
        assert!(close(dem.collision_time_step(), dtc, 1e-12));
        let dt = 1e-4;
        assert_eq!(dem.substep_count(dt), (dt / dtc).ceil() as usize);
        assert!(dem.substep_count(dt) > 1);
    }

    #[test]
    fn bad_input_names_the_particle_or_keyword() {
        let wall = WallModel::LinearSpringDashpot {
            kn: 1e3,
            restitution: 0.5,
            kt: 0.0,
            mu: 0.0,
            tangential_damping_ratio: 0.0,
            collision_resolution_steps: 20.0,
        };
        let cfg = DemConfig::new(PairModel::linear(1e3, 0.5, 0.3), wall);
        let dom = DomainBox::walled(Vec3::zeros(), [0.01; 3]);
        let mut p = ParticleState::default();
        for k in 0..4 {
            p.push(
                100 + k,
                [0.002 + 0.002 * k as f64, 0.005, 0.005],
                1e-3,
                2500.0,
            );
        }
        let run = |p: &ParticleState, c: &DemConfig| {
            Dem::new(c.clone(), dom.clone(), p.clone()).err().unwrap()
        };

        let mut q = p.clone();
        q.diameter[2] = -1e-3;
        let e = run(&q, &cfg);
        assert_eq!(
            e,
            DemError::BadDiameter {
                index: 2,
                id: 102,
                diameter: -1e-3
            }
        );
        assert!(e.to_string().contains("particle 2 (id 102)"), "{e}");
        q.diameter[2] = 0.0;
        assert!(matches!(
            run(&q, &cfg),
            DemError::BadDiameter { index: 2, .. }
        ));

        let mut q = p.clone();
        q.position[3] = Vec3::new(0.005, 0.011, 0.005);
        let e = run(&q, &cfg);
        assert!(
            matches!(
                e,
                DemError::OutsideDomain {
                    index: 3,
                    id: 103,
                    ..
                }
            ),
            "{e}"
        );
        assert!(e.to_string().contains("outside the domain"));

        let mut q = p.clone();
        q.position[3] = Vec3::new(0.0062, 0.005, 0.0052); // 0.8e-3 from particle 2: overlap 0.2 d
        let e = run(&q, &cfg);
        match &e {
            DemError::Overlap {
                index_a: 2,
                id_a: 102,
                index_b: 3,
                id_b: 103,
                overlap_over_d,
            } => {
                // centres 0.2√2 mm apart, d = 1 mm
                assert!((overlap_over_d - (1.0 - 0.2f64.hypot(0.2))).abs() < 1e-9)
            }
            other => panic!("expected overlap error, got {other}"),
        }
        assert!(
            e.to_string()
                .contains("particles 2 (id 102) and 3 (id 103) overlap"),
            "{e}"
        );

        let mut q = p.clone();
        q.position[0][2] = 0.0003;
        let e = run(&q, &cfg);
        assert!(
            matches!(
                e,
                DemError::WallOverlap {
                    index: 0,
                    id: 100,
                    face: 4,
                    ..
                }
            ),
            "{e}"
        );
        let no_wall_model = DemConfig::new(PairModel::linear(1e3, 0.5, 0.3), WallModel::None);
        let e = run(&p, &no_wall_model);
        assert_eq!(e, DemError::WallWithoutModel { face: 0 });
        assert!(e.to_string().contains("no wall model"), "{e}");

        let mut q = p.clone();
        q.id[3] = 101;
        assert_eq!(
            run(&q, &cfg),
            DemError::DuplicateId {
                index_a: 1,
                index_b: 3,
                id: 101
            }
        );

        let bad = DemConfig::new(PairModel::linear(1e3, 1.5, 0.3), WallModel::None);
        // the coefficient is reported before the missing wall model
        let e = run(&p, &bad);
        assert!(e.to_string().contains("`restitution` = 1.5"), "{e}");

        let mut dom2 = dom.clone();
        dom2.faces[0] = FaceCondition::Periodic;
        assert_eq!(
            Dem::new(cfg.clone(), dom2, p.clone()).err().unwrap(),
            DemError::UnpairedPeriodicFace { face: 0 }
        );
    }

    /// A snapshot whose particles are not in cell order (edited, or written by another tool)
    /// is sorted on restore and gives the same contact forces.
    #[test]
    fn restore_sorts_a_shuffled_snapshot() {
        let centres = random_packing(Vec3::zeros(), [0.006; 3], 1e-3, 0.3, 5).unwrap();
        let mut p = ParticleState::default();
        for (k, x) in centres.iter().enumerate() {
            p.push(k as u64, *x, 1e-3, 2500.0);
            p.velocity[k] = Vec3::new(0.0, 0.0, -0.2);
        }
        let wall = WallModel::LinearSpringDashpot {
            kn: 500.0,
            restitution: 0.5,
            kt: 1e2,
            mu: 0.3,
            tangential_damping_ratio: 0.5,
            collision_resolution_steps: 30.0,
        };
        let cfg = DemConfig::new(PairModel::linear(500.0, 0.5, 0.3), wall);
        let dom = DomainBox::walled(Vec3::zeros(), [0.006; 3]);
        let mut dem = Dem::new(cfg.clone(), dom.clone(), p).unwrap();
        let h = dem.collision_time_step();
        for _ in 0..3000 {
            dem.step(h);
        }
        let mut snap = dem.snapshot();
        let n = snap.particles.len();
        let reversed: Vec<u32> = (0..n as u32).rev().collect();
        let (mut s3, mut s1) = (Vec::new(), Vec::new());
        snap.particles.permute(&reversed, &mut s3, &mut s1);
        snap.reference_position.reverse();
        let mut again = Dem::restore(cfg, dom, &snap).unwrap();
        again.compute_contact_forces(0.0);
        dem.compute_contact_forces(0.0);
        let force_of = |d: &Dem, id: u64| {
            let i = d.particles.id.iter().position(|&x| x == id).unwrap();
            d.particles.contact_force[i]
        };
        let mut touching = 0;
        for id in 0..n as u64 {
            let (a, b) = (force_of(&dem, id), force_of(&again, id));
            let scale_f = a.norm().max(1e-12);
            for k in 0..3 {
                assert!(
                    (a[k] - b[k]).abs() <= 1e-9 * scale_f,
                    "id {id}: {a:?} vs {b:?}"
                );
            }
            touching += (a.norm() > 0.0) as usize;
        }
        assert!(touching > n / 4, "{touching} of {n} particles touch");
    }

    #[test]
    fn the_worst_overlap_names_its_pair() {
        // d = 0.1: ids 1, 2 overlap by 0.05 d; ids 3, 4 by 0.3 d across the periodic x faces
        let mut p = ParticleState::default();
        p.push(1, [0.3, 0.5, 0.5], 0.1, 2500.0);
        p.push(2, [0.395, 0.5, 0.5], 0.1, 2500.0);
        p.push(3, [0.965, 0.2, 0.5], 0.1, 2500.0);
        p.push(4, [0.035, 0.2, 0.5], 0.1, 2500.0);
        let dom = DomainBox::uniform(Vec3::zeros(), [1.0; 3], FaceCondition::Periodic);
        let dem = Dem::new(
            lenient(PairModel::linear(1e3, 0.5, 0.3), WallModel::None),
            dom,
            p,
        )
        .unwrap();
        let worst = dem.worst_overlap();
        assert!((worst.ratio - 0.3).abs() < 1e-9, "{worst:?}");
        let ids = match worst.with {
            OverlapPartner::Particle(j) => [dem.particles.id[worst.particle], dem.particles.id[j]],
            OverlapPartner::Wall(f) => panic!("wall {f}"),
        };
        assert!(ids == [3, 4] || ids == [4, 3], "{ids:?}");
        assert_eq!(dem.max_overlap_ratio(), worst.ratio);
    }

    #[test]
    fn an_empty_cloud_steps_and_reports_zeros() {
        let cfg = DemConfig::new(PairModel::linear(1e3, 0.5, 0.3), WallModel::None);
        let mut dem = Dem::new(
            cfg,
            DomainBox::uniform(Vec3::zeros(), [1.0; 3], FaceCondition::Periodic),
            ParticleState::default(),
        )
        .unwrap();
        assert_eq!(dem.advance(1e-3), 1);
        assert_eq!(dem.kinetic_energy(), (0.0, 0.0));
        assert_eq!(dem.max_overlap_ratio(), 0.0);
        assert_eq!(dem.mean_velocity(), Vec3::zeros());
    }

    #[test]
    fn without_pair_collisions_particles_pass_through_each_other() {
        // two overlapping spheres approaching head-on: with collisions off they keep their
        // velocities exactly (no force, one sub-step per outer step); with collisions on
        // the same input is rejected as overlapping
        let mut p = two_particles([0.004, 0.005, 0.005], [0.0045, 0.005, 0.005], 1e-3, 1e-3);
        p.velocity[0] = Vec3::new(0.1, 0.0, 0.0);
        p.velocity[1] = Vec3::new(-0.1, 0.0, 0.0);
        let mut cfg = DemConfig::new(PairModel::linear(1e3, 0.5, 0.3), WallModel::None);
        cfg.gravity = Vec3::zeros();
        let domain = DomainBox::uniform(Vec3::zeros(), [0.01; 3], FaceCondition::Periodic);
        assert!(matches!(
            Dem::new(cfg.clone(), domain.clone(), p.clone()),
            Err(DemError::Overlap { .. })
        ));
        cfg.pair_collisions = false;
        let mut dem = Dem::new(cfg, domain, p).unwrap();
        for _ in 0..20 {
            assert_eq!(dem.advance(1e-3), 1);
        }
        let q = dem.particles();
        for i in 0..2 {
            let v = if q.id[i] == 1 { 0.1 } else { -0.1 };
            assert_eq!(q.velocity[i], Vec3::new(v, 0.0, 0.0));
            assert_eq!(q.contact_force[i], Vec3::zeros());
        }
        assert_eq!(dem.pair_count(), 0);
    }

    #[test]
    fn rebound_face_applies_openfoam_rule() {
        let mut dom = DomainBox::uniform(Vec3::zeros(), [0.01; 3], FaceCondition::Periodic);
        dom.faces[4] = FaceCondition::Rebound { e: 0.6, mu: 0.2 };
        dom.faces[5] = FaceCondition::Rebound { e: 0.6, mu: 0.2 };
        let mut p = ParticleState::default();
        p.push(1, [0.005, 0.005, 0.0004], 1e-3, 2500.0);
        p.velocity[0] = Vec3::new(0.3, 0.0, -1.0);
        let mut dem = Dem::new(
            lenient(PairModel::linear(1e3, 0.5, 0.3), WallModel::None),
            dom,
            p,
        )
        .unwrap();
        dem.step(1e-3); // centre goes to z = −0.0006, is mirrored to +0.0006
        let p = dem.particles();
        assert!(close(p.position[0][2], 0.0006, 1e-9));
        // U_n = 1 (outward); U ← U − 1.6·U_n n − 0.2·U_t
        assert!(close(p.velocity[0][2], 0.6, 1e-12));
        assert!(close(p.velocity[0][0], 0.24, 1e-12));
    }

    /// A two-dimensional case (empty faces along y): OpenFOAM puts parcels on the mid-plane
    /// with no velocity across it and keeps them there (`constrainToMeshCentre`,
    /// `constrainDirection`), whatever the loads along y; in the plane they move freely.
    #[test]
    fn a_planar_axis_keeps_particles_on_the_mid_plane() {
        let mut dom =
            DomainBox::uniform(Vec3::zeros(), [0.01, 0.001, 0.01], FaceCondition::Periodic);
        dom.faces[2] = FaceCondition::Rebound { e: 1.0, mu: 0.0 };
        dom.faces[3] = FaceCondition::Rebound { e: 1.0, mu: 0.0 };
        dom.planar = [false, true, false];
        let mut p = ParticleState::default();
        p.push(1, [0.005, 0.0003, 0.005], 1e-3, 2500.0);
        p.velocity[0] = Vec3::new(0.1, 0.3, 0.0);
        let mut config = lenient(PairModel::linear(1e3, 0.5, 0.3), WallModel::None);
        config.gravity = Vec3::new(0.0, -9.81, -9.81);
        let mut dem = Dem::new(config, dom, p).unwrap();
        assert_eq!(dem.particles().position[0][1], 0.0005);
        assert_eq!(dem.particles().velocity[0][1], 0.0);
        for _ in 0..10 {
            dem.external_loads_mut().0[0] = Vec3::new(0.0, 1e-6, 0.0);
            dem.advance(1e-3);
        }
        let p = dem.particles();
        assert_eq!((p.position[0][1], p.velocity[0][1]), (0.0005, 0.0));
        assert!(close(p.velocity[0][0], 0.1, 1e-12));
        assert!(
            close(p.velocity[0][2], -9.81 * 0.01, 1e-9),
            "{:?}",
            p.velocity[0]
        );
    }

    /// Every overlapping pair (brute-force O(N²) reference, tests only) is in the lists after
    /// many steps with rebuilds, periodic axes included.
    #[test]
    fn lists_contain_every_contact_and_threads_do_not_change_bits() {
        let mut dom = DomainBox::walled(Vec3::zeros(), [0.008, 0.008, 0.012]);
        for f in 0..4 {
            dom.faces[f] = FaceCondition::Periodic;
        }
        let centres = random_packing(Vec3::zeros(), [0.008, 0.008, 0.012], 1e-3, 0.3, 7).unwrap();
        let mut p = ParticleState::default();
        for (k, x) in centres.iter().enumerate() {
            p.push(k as u64, *x, 1e-3, 2500.0);
            p.velocity[k] = Vec3::new(
                0.1 * ((k % 7) as f64 - 3.0),
                0.05 * ((k % 5) as f64 - 2.0),
                -0.1,
            );
        }
        let wall = WallModel::LinearSpringDashpot {
            kn: 500.0,
            restitution: 0.5,
            kt: 1e2,
            mu: 0.3,
            tangential_damping_ratio: 0.5,
            collision_resolution_steps: 30.0,
        };
        let cfg = DemConfig::new(PairModel::linear(500.0, 0.5, 0.3), wall);
        let run = |threads: usize| run_on_threads(threads, &cfg, &dom, &p, 1500, |_, _| {});
        let dem = run(2);
        assert!(dem.list_rebuilds() > 2, "rebuilds {}", dem.list_rebuilds());
        let q = dem.particles();
        let (l, inv) = (dom.length(), dom.inverse_periodic_length());
        let mut listed = std::collections::HashSet::new();
        for i in 0..q.len() {
            for k in dem.lists.row_start[i] as usize..dem.lists.row_start[i + 1] as usize {
                listed.insert((i, dem.lists.partner[k] as usize));
            }
        }
        let mut contacts = 0;
        for i in 0..q.len() {
            for j in i + 1..q.len() {
                let d = minimum_image(
                    Vec3::new(
                        q.position[i][0] - q.position[j][0],
                        q.position[i][1] - q.position[j][1],
                        q.position[i][2] - q.position[j][2],
                    ),
                    l,
                    inv,
                );
                if d.norm() < 1e-3 {
                    contacts += 1;
                    assert!(
                        listed.contains(&(i, j)),
                        "contact {i}-{j} missing from the list"
                    );
                }
            }
        }
        assert!(contacts > 10, "contacts {contacts}");
        let one = run(1);
        assert_eq!(one.particles(), dem.particles());
    }

    /// The block-scattered force pass on a fully periodic box large enough for several blocks
    /// and pairs across the seams (far pairs): contact forces balance to round-off (a load
    /// routed to the wrong sum would break it) and 1 and 2 threads give the same bits.
    #[test]
    fn block_scatter_balances_forces_across_blocks_and_seams() {
        let size = [0.02, 0.02, 0.02];
        let mut dom = DomainBox::walled(Vec3::zeros(), size);
        dom.faces = [FaceCondition::Periodic; 6];
        let centres = random_packing(Vec3::zeros(), size, 1e-3, 0.3, 11).unwrap();
        let mut rng = crate::particles::SplitMix64::new(5);
        let mut p = ParticleState::default();
        for (k, x) in centres.iter().enumerate() {
            p.push(k as u64, *x, 1e-3, 2500.0);
            p.velocity[k] = Vec3::new(
                2.0 * (rng.next_f64() - 0.5),
                2.0 * (rng.next_f64() - 0.5),
                2.0 * (rng.next_f64() - 0.5),
            );
        }
        let mut cfg = DemConfig::new(PairModel::linear(500.0, 0.5, 0.3), WallModel::None);
        cfg.gravity = Vec3::zeros();
        // the balance every step, across rebuilds that change the block size
        let mut sizes = std::collections::BTreeSet::new();
        let mut any_far = false;
        let dem = run_on_threads(2, &cfg, &dom, &p, 300, |step, probe| {
            sizes.insert(probe.lists.block);
            any_far |= !probe.lists.far_pair.is_empty();
            let f = &probe.particles().contact_force;
            let net: f64 = (0..3)
                .map(|a| f.iter().map(|x| x[a]).sum::<f64>().powi(2))
                .sum::<f64>()
                .sqrt();
            let scale_f: f64 = f.iter().map(|x| (*x).norm()).sum();
            assert!(
                net <= 1e-12 * scale_f.max(1e-300),
                "step {step}: net {net} of {scale_f}"
            );
        });
        assert!(sizes.len() > 1, "block size never changed: {sizes:?}");
        let n = dem.particles().len();
        let smallest = *sizes.iter().next().unwrap();
        assert!(n / smallest >= 3, "{n} particles, blocks {sizes:?}");
        assert!(any_far, "no far pairs");
        let f = &dem.particles().contact_force;
        let total = Vec3::from_fn(|a, _| f.iter().map(|x| x[a]).sum());
        let scale_f: f64 = f.iter().map(|x| (*x).norm()).sum();
        assert!(scale_f > 0.0, "no contacts");
        assert!(
            total.norm() < 1e-12 * scale_f,
            "net force {total:?} of {scale_f}"
        );
        let one = run_on_threads(1, &cfg, &dom, &p, 300, |_, _| {});
        assert_eq!(one.particles(), dem.particles());
    }

    /// `steps` collision steps of the largest stable size on a pool of `threads` threads,
    /// calling `each(step, &dem)` after every step.
    fn run_on_threads(
        threads: usize,
        cfg: &DemConfig,
        dom: &DomainBox,
        p: &ParticleState,
        steps: usize,
        mut each: impl FnMut(usize, &Dem) + Send,
    ) -> Dem {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut dem = Dem::new(cfg.clone(), dom.clone(), p.clone()).unwrap();
            let h = dem.collision_time_step();
            for step in 0..steps {
                dem.step(h);
                each(step, &dem);
            }
            dem
        })
    }
}
