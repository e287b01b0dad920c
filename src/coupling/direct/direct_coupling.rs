//! The direct model's state in a run: the spheres, their forced faces, and their loads.

use super::tuning::{
    COARSE_CELLS_PER_RADIUS, MIN_CELLS_PER_RADIUS, WALL_TRILINEAR_CLEARANCE_CELLS,
};
use crate::Vec3;
use std::collections::HashMap;
use std::sync::Mutex;

use rayon::prelude::*;

use super::close_pairs::{ClosePairs, PeriodicBox};
use super::direct_settings::DirectSettings;
use super::field_brick::FieldBrick;
use super::field_sampler::{FieldSampler, Interpolation};
use super::field_view::{periodic_directions, FieldView};
use super::immersed_boundary::ImmersedBoundary;
use super::rigid_sphere::RigidSphere;
use super::sphere_quadrature::{SphereQuadrature, SphereQuadratureFamily};
use super::stress_integral::{
    shell_momentum, stress_integral_force, HydrodynamicLoad, ShellMomentum, StressIntegral,
};
use crate::fluid::{FluidSolver, PredictedVelocity};
use crate::grid::Grid;
use crate::particles::ParticleState;

/// Resolved coupling (paper §2.1) for one run. Each fluid step:
///
/// 1. [`DirectCoupling::set_particles`] (or [`DirectCoupling::set_spheres`]): the spheres at
///    their current positions and velocities; the forced faces are rebuilt;
/// 2. `fluid.step_with(dt, &mut |stage| coupling.impose(stage))`: no-slip on every sphere
///    in every stage ([`ImmersedBoundary`]);
/// 3. [`DirectCoupling::compute_loads`]: force and torque on every sphere from the stress
///    integral ([`stress_integral_force`]), in the order of the spheres handed in step 1, for
///    the DEM's external loads.
pub struct DirectCoupling {
    settings: DirectSettings,
    boundary: ImmersedBoundary,
    h: f64,
    /// The box's low corner, lengths and which directions are periodic (for the gaps
    /// between spheres).
    origin: [f64; 3],
    length: [f64; 3],
    periodic: [bool; 3],
    /// Scratch of [`Self::surface_offsets`]: the pair search, the spheres' nearest gaps, the
    /// offsets and each sphere's interpolation.
    pairs: ClosePairs,
    gaps: Vec<f64>,
    offsets: Vec<f64>,
    interpolations: Vec<Interpolation>,
    /// Scratch of [`Self::compute_loads`]: each sphere's load and shell momentum, in the
    /// order of [`Self::spatial_order`].
    sphere_results: Vec<(HydrodynamicLoad, ShellMomentum)>,
    /// Scratch of [`Self::set_particles`]: the DEM's particles as spheres.
    particle_spheres: Vec<RigidSphere>,
    /// The spheres and their ids, ordered by id (whatever order the caller hands them in:
    /// the DEM re-sorts its particles, and the forced faces name spheres by index).
    spheres: Vec<RigidSphere>,
    ids: Vec<u64>,
    /// The caller's index of each sphere above.
    order: Vec<usize>,
    /// The caller's spheres in id order (scratch of [`Self::set_spheres`]).
    sorted: Vec<RigidSphere>,
    /// Surface quadrature and shell rules per distinct radius (bit pattern of the radius).
    quadratures: HashMap<u64, (SphereQuadrature, SphereQuadratureFamily)>,
    /// Shell momentum at the last load evaluation, per particle id, with its time and the
    /// surface offset it was taken with (a changed surface has no rate).
    previous_shell: HashMap<u64, (f64, f64, ShellMomentum)>,
    loads: Vec<HydrodynamicLoad>,
    /// One brick per worker thread: the fields around the sphere whose loads it computes.
    bricks: Vec<Mutex<FieldBrick>>,
    /// The order in which the loads visit the spheres (scratch of [`Self::compute_loads`]).
    spatial_order: Vec<usize>,
    /// Whether the forced faces have been built once.
    built: bool,
    /// Whether the last [`Self::set_spheres`] rebuilt them (else they followed the spheres).
    last_rebuilt: bool,
    /// Where the forced faces of a restarted run were built ([`Self::build_state`]), until
    /// the first [`Self::set_spheres`] builds them there.
    restored_build: Option<Vec<f64>>,
    /// The throats' state of a restarted run, applied to the restored build.
    restored_throats: Option<Vec<f64>>,
}

impl DirectCoupling {
    /// The coupling for `fluid` (enables the fluid's mass source, which the imposition sets
    /// in cells whose faces are all forced).
    pub fn new(fluid: &mut FluidSolver, settings: DirectSettings) -> Self {
        fluid.mass_source_mut();
        let grid = fluid.grid();
        let mut boundary = ImmersedBoundary::new(grid, fluid.boundary_conditions());
        boundary.set_throat_viscosity(fluid.settings().nu);
        DirectCoupling {
            settings,
            boundary,
            h: grid.h.iter().cloned().fold(0.0, f64::max),
            origin: grid.origin,
            length: grid.length(),
            periodic: periodic_directions(fluid.boundary_conditions()),
            pairs: ClosePairs::default(),
            gaps: Vec::new(),
            offsets: Vec::new(),
            interpolations: Vec::new(),
            sphere_results: Vec::new(),
            particle_spheres: Vec::new(),
            spheres: Vec::new(),
            ids: Vec::new(),
            order: Vec::new(),
            sorted: Vec::new(),
            quadratures: HashMap::new(),
            previous_shell: HashMap::new(),
            loads: Vec::new(),
            bricks: Vec::new(),
            spatial_order: Vec::new(),
            built: false,
            last_rebuilt: false,
            restored_build: None,
            restored_throats: None,
        }
    }

    /// Checks a case before the run: every sphere at least two cells in radius, none as
    /// large as a periodic box length (it would overlap its own image). Returns notes on
    /// what runs but deserves a word (coarse spheres, r/h < 4: drag errors of 2 % and more,
    /// docs/direct_model.md).
    pub fn check_particles(
        grid: &Grid,
        periodic: [bool; 3],
        p: &ParticleState,
    ) -> Result<Vec<String>, String> {
        let h = grid.h.iter().cloned().fold(0.0, f64::max);
        let length = grid.length();
        let mut coarse = 0;
        let mut smallest = f64::INFINITY;
        let mut thin = Vec::new();
        for i in 0..p.len() {
            let r = 0.5 * p.diameter[i];
            let resolution = r / h;
            smallest = smallest.min(resolution);
            if resolution < MIN_CELLS_PER_RADIUS {
                thin.push(i);
            }
            if resolution < COARSE_CELLS_PER_RADIUS {
                coarse += 1;
            }
            for d in 0..3 {
                if periodic[d] && 2.0 * r >= length[d] {
                    return Err(format!(
                        "particle {} (id {}) of diameter {:e} m does not fit the periodic box \
                         ({:e} m along axis {d})",
                        i + 1,
                        p.id[i],
                        2.0 * r,
                        length[d]
                    ));
                }
            }
        }
        // the cells per side that give the smallest sphere `cells` cells per radius
        let r_min = smallest * h;
        let cells_for = |cells: f64| -> String {
            let n: Vec<String> = (0..3)
                .map(|a| ((length[a] * cells / r_min).ceil() as usize).to_string())
                .collect();
            format!("h ≤ {:.3e} m, ({}) cells", r_min / cells, n.join(" "))
        };
        if !thin.is_empty() {
            thin.sort_by(|&a, &b| p.diameter[a].total_cmp(&p.diameter[b]));
            let named: Vec<String> = thin
                .iter()
                .take(3)
                .map(|&i| {
                    format!(
                        "particle {} (id {}) r/h = {:.3}",
                        i + 1,
                        p.id[i],
                        0.5 * p.diameter[i] / h
                    )
                })
                .collect();
            let more = match thin.len() - named.len() {
                0 => String::new(),
                n => format!(" and {n} more"),
            };
            return Err(format!(
                "model direct needs spheres of at least {MIN_CELLS_PER_RADIUS} cells in radius: \
                 {} of {} particle(s) have fewer (h = {h:.3e} m): {}{more}; refine the grid to \
                 {} for r/h = {MIN_CELLS_PER_RADIUS}, or to {} for r/h = \
                 {COARSE_CELLS_PER_RADIUS} (drag errors under 2 %), or use model dragLaw",
                thin.len(),
                p.len(),
                named.join(", "),
                cells_for(MIN_CELLS_PER_RADIUS),
                cells_for(COARSE_CELLS_PER_RADIUS),
            ));
        }
        let mut notes = Vec::new();
        if coarse > 0 {
            notes.push(format!(
                "model direct: {coarse} particle(s) below {COARSE_CELLS_PER_RADIUS} cells in radius (smallest \
                 r/h = {smallest:.2}); expect drag errors of 2 % and more ({} give r/h = \
                 {COARSE_CELLS_PER_RADIUS})",
                cells_for(COARSE_CELLS_PER_RADIUS)
            ));
        }
        Ok(notes)
    }

    pub fn settings(&self) -> &DirectSettings {
        &self.settings
    }

    /// The forced faces of the current spheres.
    pub fn boundary(&self) -> &ImmersedBoundary {
        &self.boundary
    }

    /// The spheres as last set, in the order of their ids.
    pub fn spheres(&self) -> &[RigidSphere] {
        &self.spheres
    }

    /// Sets the spheres (ids name them across calls, for the shell's rate of change) and
    /// brings the forced faces up to them: rebuilt when the particles are not those of the
    /// last call (the same ids) or one has moved more than `rebuildDistance` cells from
    /// where they were built, else following them ([`ImmersedBoundary::follow`]).
    ///
    /// Spheres identical to the current ones (fixed arrays) keep their forced faces. The
    /// order of the call does not matter (the spheres are kept in id order, so a DEM that
    /// re-sorts its particles costs no rebuild); the loads come back in the call's order.
    pub fn set_spheres(&mut self, spheres: &[RigidSphere], ids: &[u64]) {
        assert_eq!(spheres.len(), ids.len(), "one id per sphere");
        // The same particles in the same caller order as last time: the order holds.
        let order_holds = self.order.len() == ids.len()
            && self
                .order
                .iter()
                .zip(&self.ids)
                .all(|(&i, &id)| ids[i] == id);
        let mut same_particles = self.built && order_holds;
        if !order_holds {
            self.order.clear();
            self.order.extend(0..ids.len());
            self.order.sort_unstable_by_key(|&i| ids[i]);
            let sorted_ids: Vec<u64> = self.order.iter().map(|&i| ids[i]).collect();
            // a re-sort of the same particles keeps them
            same_particles = self.built && sorted_ids == self.ids;
            self.ids = sorted_ids;
        }
        self.sorted.clear();
        self.sorted.extend(self.order.iter().map(|&i| spheres[i]));
        if same_particles && self.spheres == self.sorted {
            self.last_rebuilt = false;
            return;
        }
        std::mem::swap(&mut self.spheres, &mut self.sorted);
        for s in &self.spheres {
            let h = self.h;
            let integral = self.settings.integral;
            self.quadratures
                .entry(s.radius.to_bits())
                .or_insert_with(|| {
                    (
                        integral.quadrature(s.radius, h),
                        integral.shell_rules(s.radius, h),
                    )
                });
        }
        let restored = !self.built && self.build_where_restored();
        self.built = true;
        self.last_rebuilt = if same_particles || restored {
            let skin = self.settings.rebuild_distance * self.h;
            self.boundary.follow(&self.spheres, skin)
        } else {
            self.boundary.update(&self.spheres);
            true
        };
    }

    /// Whether the last [`Self::set_spheres`] rebuilt the forced faces.
    pub fn last_rebuilt(&self) -> bool {
        self.last_rebuilt
    }

    /// Name of the restart array of [`Self::build_state`].
    pub const BUILD_RESTART_NAME: &'static str = "direct.build";

    /// Where the current forced faces were built, for a bit-identical restart: per sphere
    /// (in order) `id, x, y, z, r`.
    pub fn build_state(&self) -> Vec<f64> {
        let built = self.boundary.built_spheres();
        let mut out = Vec::with_capacity(5 * built.len());
        for (s, &id) in built.iter().zip(&self.ids) {
            out.push(id as f64);
            out.extend_from_slice(s.centre.as_slice());
            out.push(s.radius);
        }
        out
    }

    /// Restores what [`Self::build_state`] saved: the first [`Self::set_spheres`] builds
    /// the forced faces there (if it hands the same particles) and lets them follow the
    /// spheres from there.
    pub fn restore_build_state(&mut self, data: &[f64]) -> Result<(), String> {
        check_rows(Self::BUILD_RESTART_NAME, data, 5)?;
        self.restored_build = Some(data.to_vec());
        Ok(())
    }

    /// Name of the restart array of [`Self::throat_state`].
    pub const THROAT_RESTART_NAME: &'static str = "direct.throats";

    /// The throats' stage clocks and targets, for a bit-identical restart
    /// ([`ImmersedBoundary::throat_state`]).
    pub fn throat_state(&self) -> Vec<f64> {
        self.boundary.throat_state()
    }

    /// Restores what [`Self::throat_state`] saved, onto the faces that the restored build
    /// ([`Self::restore_build_state`]) makes.
    pub fn restore_throat_state(&mut self, data: &[f64]) -> Result<(), String> {
        ImmersedBoundary::check_throat_state(data)
            .map_err(|e| format!("{}: {e}", Self::THROAT_RESTART_NAME))?;
        self.restored_throats = Some(data.to_vec());
        Ok(())
    }

    /// Builds the forced faces where a restart says they were built, with the current
    /// spheres' velocities; false (nothing built) if the restart names other particles.
    fn build_where_restored(&mut self) -> bool {
        let Some(saved) = self.restored_build.take() else {
            return false;
        };
        let rows = saved.chunks_exact(5);
        if rows.len() != self.spheres.len()
            || rows.zip(&self.ids).any(|(row, &id)| row[0] as u64 != id)
        {
            return false;
        }
        let built: Vec<RigidSphere> = saved
            .chunks_exact(5)
            .zip(&self.spheres)
            .map(|(row, s)| RigidSphere {
                centre: Vec3::new(row[1], row[2], row[3]),
                radius: row[4],
                ..*s
            })
            .collect();
        self.boundary.update(&built);
        if let Some(throats) = self.restored_throats.take() {
            self.boundary.restore_throat_state(&throats);
        }
        true
    }

    /// The DEM's particles as spheres (same order), then as [`Self::set_spheres`].
    pub fn set_particles(&mut self, p: &ParticleState) {
        let mut spheres = std::mem::take(&mut self.particle_spheres);
        spheres.clear();
        spheres.extend((0..p.len()).map(|i| RigidSphere {
            centre: p.position[i],
            radius: 0.5 * p.diameter[i],
            velocity: p.velocity[i],
            angular_velocity: p.angular_velocity[i],
        }));
        self.set_spheres(&spheres, &p.id);
        self.particle_spheres = spheres;
    }

    /// The hook of [`FluidSolver::step_with`]: imposes no-slip on the stage's predicted
    /// velocity (pre-compensated for the coming projection: [`ImmersedBoundary::impose`]).
    pub fn impose(&mut self, stage: PredictedVelocity<'_>) {
        let PredictedVelocity {
            velocity,
            pressure,
            incremental_pressure,
            tau,
            mass_source,
            components,
            body_force,
            time,
            ..
        } = stage;
        // The throats' flow is driven by the last projection's pressure: the explicit
        // schemes hand it as `pressure`, the incremental ones as the pressure their
        // increment adds to.
        let driving = if pressure.is_empty() {
            incremental_pressure
        } else {
            pressure
        };
        self.boundary
            .set_throat_targets(components, driving, body_force, tau, time);
        self.boundary.impose(
            velocity,
            components,
            pressure,
            tau,
            mass_source,
            incremental_pressure,
        );
    }

    /// Force and torque on every sphere (order of [`Self::set_spheres`]) from the current
    /// fluid state; `rho` the fluid density (kg/m³). The body force on the fluid (its
    /// settings' plus the `meanVelocityForce` gradient) enters as `f_h0`; the shell term uses
    /// the shell momentum of the previous call (none at the first).
    pub fn compute_loads(&mut self, fluid: &FluidSolver, rho: f64) -> &[HydrodynamicLoad] {
        self.order_spatially();
        let view = FieldView::of(fluid);
        let mut body = fluid.settings().body_force;
        if let Some(d) = fluid.mean_velocity_force() {
            body[d.direction] += d.gradient;
        }
        let time = fluid.time();
        let integral = self.settings.integral;
        let with_shell = integral.surface_offset > 0.0;
        self.surface_offsets();
        let (offsets, interpolations) = (&self.offsets, &self.interpolations);
        let quadratures = &self.quadratures;
        // The brick pays with its four-lane trilinear stencils (fully periodic boxes); for
        // the tricubic ones, 64 samples a field, the copy costs what it saves
        // (docs/direct_model.md, "Cost").
        let use_brick =
            integral.interpolation == Interpolation::Linear && self.periodic == [true; 3];
        let workers = rayon::current_num_threads();
        if use_brick && self.bricks.len() != workers {
            self.bricks = (0..workers)
                .map(|_| Mutex::new(FieldBrick::new()))
                .collect();
        }
        let bricks = &self.bricks;
        let h = self.h;
        let spheres = &self.spheres;
        // In the order of the curve, so that a worker's next sphere mostly neighbours its
        // last one and finds part of its brick's samples still in the cache.
        let mut results = std::mem::take(&mut self.sphere_results);
        results.clear();
        results.par_extend(self.spatial_order.par_iter().map(|&k| {
            let (s, offset) = (&spheres[k], offsets[k]);
            let (q, shell_rules) = &quadratures[&s.radius.to_bits()];
            let integral = StressIntegral {
                surface_offset: offset,
                interpolation: interpolations[k],
            };
            let shell = with_shell.then_some(shell_rules);
            if !use_brick {
                return sphere_load(&view, s, rho, body, &integral, q, shell);
            }
            // Each worker holds its own brick: the lock is never contended.
            let worker = rayon::current_thread_index().unwrap_or(0) % bricks.len();
            let mut brick = bricks[worker].lock().expect("no worker panics holding it");
            let reach = integral.surface_radius(s.radius, h);
            brick.gather(&view, s.centre, reach, integral.interpolation);
            sphere_load(&*brick, s, rho, body, &integral, q, shell)
        }));
        self.loads.clear();
        self.loads
            .resize(self.spheres.len(), HydrodynamicLoad::default());
        for (&k, &(mut load, shell)) in self.spatial_order.iter().zip(&results) {
            let id = self.ids[k];
            if let Some((t0, offset, old)) = self.previous_shell.get(&id) {
                let span = time - t0;
                if span > 0.0 && *offset == offsets[k] {
                    for i in 0..3 {
                        load.force[i] -= rho * (shell.linear[i] - old.linear[i]) / span;
                        load.torque[i] -= rho * (shell.angular[i] - old.angular[i]) / span;
                    }
                }
            }
            if with_shell {
                self.previous_shell.insert(id, (time, offsets[k], shell));
            }
            self.loads[self.order[k]] = load;
        }
        self.sphere_results = results;
        &self.loads
    }

    /// Fills [`Self::spatial_order`]: the spheres' indices along the Z-order (Morton) curve
    /// through the cells that hold their centres.
    fn order_spatially(&mut self) {
        let (h, length, periodic) = (self.h, self.length, self.periodic);
        let key = |s: &RigidSphere| -> u64 {
            let cell = |d: usize| -> u64 {
                let mut x = s.centre[d] / h;
                if periodic[d] {
                    x = x.rem_euclid(length[d] / h);
                }
                (x.max(0.0) as u64).min((1 << 21) - 1)
            };
            spread_bits(cell(0)) | spread_bits(cell(1)) << 1 | spread_bits(cell(2)) << 2
        };
        let spheres = &self.spheres;
        self.spatial_order.clear();
        self.spatial_order.extend(0..spheres.len());
        self.spatial_order
            .sort_unstable_by_key(|&k| (key(&spheres[k]), k));
    }

    /// The integration surface offset (cells) per sphere: the setting, reduced where a
    /// neighbour (or the sphere's own periodic image) comes closer than `offset + 1` cells,
    /// so that the surface encloses neither the neighbour nor its forcing layer:
    /// `min(offset, max(1, gap/h − 1))`. Below a gap of two cells the integral sees the
    /// neighbour's forcing (the lubrication range, handled by the particle model).
    ///
    /// Near a bounding face (a wall, an inlet or an outlet) the surface stays inside the
    /// flow, [`wall_surface_offset`], and is read with [`wall_interpolation`]
    /// (`Self::interpolations`).
    pub fn surface_offsets(&mut self) -> &[f64] {
        let h = self.h;
        let nominal = self.settings.integral.surface_offset;
        let interpolation = self.settings.integral.interpolation;
        self.offsets.clear();
        self.interpolations.clear();
        let (lo, length, periodic) = (self.origin, self.length, self.periodic);
        // the gap (cells) between a sphere's surface and the nearest bounding face
        let wall_gap = |s: &RigidSphere| {
            (0..3)
                .filter(|&d| !periodic[d])
                .map(|d| {
                    let centre = s.centre[d] - lo[d];
                    centre.min(length[d] - centre) - s.radius
                })
                .fold(f64::INFINITY, f64::min)
                / h
        };
        if nominal == 0.0 {
            self.offsets.resize(self.spheres.len(), 0.0);
            let spheres = &self.spheres;
            self.interpolations.extend(
                spheres
                    .iter()
                    .map(|s| wall_interpolation(wall_gap(s), interpolation)),
            );
            return &self.offsets;
        }
        let spheres = &self.spheres;
        // The sphere's own periodic image first.
        self.gaps.clear();
        self.gaps.extend(spheres.iter().map(|s| {
            (0..3)
                .filter(|&d| self.periodic[d])
                .map(|d| self.length[d] - 2.0 * s.radius)
                .fold(f64::INFINITY, f64::min)
        }));
        // Gaps of (nominal + 1) h and more leave the nominal offset: only nearer pairs
        // matter, found with linked cells (a search of all pairs grows as the square of
        // the sphere count: docs/benchmarks/direct.md).
        let reach = (nominal + 1.0) * h;
        let domain = PeriodicBox {
            lo: self.origin.into(),
            hi: Vec3::from_fn(|d, _| self.origin[d] + self.length[d]),
            periodic: self.periodic,
        };
        let gaps = &mut self.gaps;
        self.pairs.visit_spheres(
            spheres.len(),
            |i| spheres[i].centre,
            |i| 2.0 * spheres[i].radius,
            &domain,
            reach + h,
            |i, j, _, dist, _| {
                // each sphere's own radius subtracted first, as a comparison with every
                // other sphere does: the same offsets bit for bit
                let (ri, rj) = (spheres[i].radius, spheres[j].radius);
                gaps[i] = gaps[i].min(dist - ri - rj);
                gaps[j] = gaps[j].min(dist - rj - ri);
            },
        );
        for (&gap, s) in self.gaps.iter().zip(spheres) {
            let wall_gap = wall_gap(s);
            let offset = nominal
                .min((gap / h - 1.0).max(1.0))
                .min(wall_surface_offset(wall_gap));
            self.offsets.push(offset);
            self.interpolations
                .push(wall_interpolation(wall_gap - offset, interpolation));
        }
        &self.offsets
    }

    /// The interpolation each sphere's integral reads the fields with (set by
    /// [`Self::surface_offsets`]): the setting, or trilinear next to a wall.
    pub fn interpolations(&self) -> &[Interpolation] {
        &self.interpolations
    }

    /// Name of the restart array of [`Self::shell_state`].
    pub const RESTART_NAME: &'static str = "direct.shell";

    /// The shell momenta the next [`Self::compute_loads`] differences against, for a
    /// bit-identical restart: per particle (sorted by id) `id, time, offset, linear (3),
    /// angular (3)`.
    pub fn shell_state(&self) -> Vec<f64> {
        let mut ids: Vec<&u64> = self.previous_shell.keys().collect();
        ids.sort_unstable();
        let mut out = Vec::with_capacity(9 * ids.len());
        for id in ids {
            let (time, offset, m) = &self.previous_shell[id];
            out.extend_from_slice(&[*id as f64, *time, *offset]);
            out.extend_from_slice(m.linear.as_slice());
            out.extend_from_slice(m.angular.as_slice());
        }
        out
    }

    /// Restores what [`Self::shell_state`] saved.
    pub fn restore_shell_state(&mut self, data: &[f64]) -> Result<(), String> {
        check_rows(Self::RESTART_NAME, data, 9)?;
        self.previous_shell.clear();
        for row in data.chunks_exact(9) {
            let m = ShellMomentum {
                linear: Vec3::new(row[3], row[4], row[5]),
                angular: Vec3::new(row[6], row[7], row[8]),
            };
            self.previous_shell
                .insert(row[0] as u64, (row[1], row[2], m));
        }
        Ok(())
    }

    /// The loads of the last [`Self::compute_loads`].
    pub fn loads(&self) -> &[HydrodynamicLoad] {
        &self.loads
    }
}

/// The largest integration surface offset (cells) for a sphere whose surface lies `gap`
/// cells from a bounding face: the surface stays inside the flow, in whole half cells (at
/// least one), `max(1, ⌊2 gap⌋ / 2)`.
///
/// A surface beyond a wall encloses a patch of it, whose traction then enters the balance:
/// the pressure in the gap pushes the patch instead of the sphere, which is drawn in
/// (docs/direct_model.md, "Walls"). Whole half cells, so that a sphere
/// drifting along a wall keeps its surface, and its shell term (a changed surface has no
/// rate), most steps.
pub fn wall_surface_offset(gap: f64) -> f64 {
    ((2.0 * gap).floor() / 2.0).max(1.0)
}

/// The interpolation of an integration surface `clearance` cells from a bounding face:
/// `nominal`, but trilinear closer than `WALL_TRILINEAR_CLEARANCE_CELLS`: there a
/// tricubic stencil reaches the ghost layer beyond the wall, and the integral of a moving
/// sphere drifts (docs/direct_model.md, "Walls").
pub fn wall_interpolation(clearance: f64, nominal: Interpolation) -> Interpolation {
    if clearance < WALL_TRILINEAR_CLEARANCE_CELLS {
        Interpolation::Linear
    } else {
        nominal
    }
}

/// The stress integral of one sphere and, with `shell` rules, its shell momentum.
fn sphere_load(
    fields: &impl FieldSampler,
    sphere: &RigidSphere,
    rho: f64,
    body: [f64; 3],
    integral: &StressIntegral,
    quadrature: &SphereQuadrature,
    shell: Option<&SphereQuadratureFamily>,
) -> (HydrodynamicLoad, ShellMomentum) {
    let load = stress_integral_force(fields, sphere, rho, body, integral, quadrature);
    let shell = shell.map_or_else(ShellMomentum::default, |rules| {
        shell_momentum(fields, sphere, integral, rules)
    });
    (load, shell)
}

/// The low 21 bits of `v`, each moved to three times its place (bit `i` to bit `3i`): one
/// axis of a three-dimensional Morton key.
fn spread_bits(v: u64) -> u64 {
    let mut v = v & 0x1f_ffff;
    v = (v | v << 32) & 0x001f_0000_0000_ffff;
    v = (v | v << 16) & 0x001f_0000_ff00_00ff;
    v = (v | v << 8) & 0x100f_00f0_0f00_f00f;
    v = (v | v << 4) & 0x10c3_0c30_c30c_30c3;
    (v | v << 2) & 0x1249_2492_4924_9249
}

/// A restart array of rows of `width` values.
fn check_rows(name: &str, data: &[f64], width: usize) -> Result<(), String> {
    if data.len().is_multiple_of(width) {
        Ok(())
    } else {
        Err(format!(
            "restart array '{name}' has {} values, not a multiple of {width}",
            data.len()
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::{BoundaryConditions, FluidSettings};
    use crate::grid::nearest_image;
    use crate::particles::SplitMix64;

    #[test]
    fn spheres_handed_in_another_order_keep_their_faces_and_get_their_own_loads() {
        let h = 0.1;
        let grid = Grid::new([16; 3], [h; 3], [0.0; 3]);
        let mut fluid = FluidSolver::new(
            grid,
            BoundaryConditions::periodic(),
            FluidSettings::new(0.1),
        )
        .unwrap();
        let mut rng = SplitMix64::new(5);
        let phase: [f64; 3] = std::array::from_fn(|_| rng.next_f64());
        fluid.set_velocity(|c, x| (x[(c + 1) % 3] * 3.0 + phase[c]).sin() + 0.3 * x[c].cos());
        let mut coupling = DirectCoupling::new(&mut fluid, DirectSettings::default());
        let mut a = RigidSphere::fixed([0.4, 0.5, 0.6], 0.25);
        a.velocity = Vec3::new(0.1, 0.0, -0.2);
        let mut b = RigidSphere::fixed([1.2, 1.1, 0.9], 0.25);
        b.angular_velocity = Vec3::new(0.0, 1.0, 0.0);
        coupling.set_spheres(&[a, b], &[7, 3]);
        assert!(coupling.last_rebuilt());
        let forward = coupling.compute_loads(&fluid, 1.0).to_vec();
        // as a DEM that re-sorted its particles hands them
        coupling.set_spheres(&[b, a], &[3, 7]);
        assert!(!coupling.last_rebuilt(), "a new order alone needs no build");
        let reversed = coupling.compute_loads(&fluid, 1.0).to_vec();
        assert_eq!(reversed, vec![forward[1], forward[0]]);
        assert!(forward[0] != forward[1]);
    }

    /// Next to a wall the surface stays inside the flow, in half cells; along a periodic
    /// direction a face is no wall.
    #[test]
    fn surface_offsets_stay_inside_the_flow_next_to_a_wall() {
        for (gap, offset) in [(0.2, 1.0), (1.0, 1.0), (1.49, 1.0), (1.5, 1.5), (2.3, 2.0)] {
            assert_eq!(wall_surface_offset(gap), offset, "gap {gap}");
        }
        let (cubic, linear) = (Interpolation::Cubic, Interpolation::Linear);
        for (clearance, expected) in [(-0.5, linear), (1.49, linear), (1.5, cubic)] {
            assert_eq!(wall_interpolation(clearance, cubic), expected);
        }
        assert_eq!(wall_interpolation(3.0, linear), linear);
        let h = 0.1;
        let wall = crate::fluid::FaceCondition::Wall { velocity: [0.0; 3] };
        let mut bc = BoundaryConditions::periodic();
        bc.faces[2] = wall.clone();
        bc.faces[3] = wall;
        let grid = Grid::new([40, 16, 20], [h; 3], [0.5, -1.0, 0.0]);
        let mut fluid = FluidSolver::new(grid, bc, FluidSettings::new(0.1)).unwrap();
        let mut coupling = DirectCoupling::new(&mut fluid, DirectSettings::default());
        let r = 0.3;
        let spheres = [
            // 1.7 cells above the lower wall at y = −1, near the periodic x faces
            RigidSphere::fixed([0.5 + 0.05, -1.0 + r + 0.17, 1.0], r),
            // 2.6 cells below the upper wall at y = 0.6
            RigidSphere::fixed([1.9, 0.6 - r - 0.26, 1.0], r),
            // midway: 5 cells from either wall
            RigidSphere::fixed([3.2, -0.2, 1.0], r),
        ];
        coupling.set_spheres(&spheres, &[0, 1, 2]);
        let offsets = coupling.surface_offsets().to_vec();
        assert_eq!(offsets, vec![1.5, 2.5, 3.0]);
        // the first two surfaces come within 0.2 and 0.1 cells of a wall, the third 2 cells
        assert_eq!(coupling.interpolations(), [linear, linear, cubic]);
        // on the spheres themselves (offset 0): 1.7, 2.6 and 5 cells from a wall
        let mut settings = DirectSettings::default();
        settings.integral.surface_offset = 0.0;
        let mut on_sphere = DirectCoupling::new(&mut fluid, settings);
        let mut closer = spheres;
        closer[1].centre[1] = 0.6 - r - 0.12; // 1.2 cells from the upper wall
        on_sphere.set_spheres(&closer, &[0, 1, 2]);
        assert_eq!(on_sphere.surface_offsets(), [0.0; 3]);
        assert_eq!(on_sphere.interpolations(), [cubic, linear, cubic]);
    }

    /// The linked-cell search gives every sphere the offset that comparing it with all
    /// others (nearest periodic images) gives, bit for bit: reduced next to a neighbour or
    /// its own image, nominal elsewhere.
    #[test]
    fn surface_offsets_agree_with_all_pairs() {
        let h = 0.05;
        let grid = Grid::new([48, 40, 44], [h; 3], [-0.3, 0.2, 0.0]);
        let length = grid.length();
        let mut fluid = FluidSolver::new(
            grid.clone(),
            BoundaryConditions::periodic(),
            FluidSettings::new(0.1),
        )
        .unwrap();
        let mut coupling = DirectCoupling::new(&mut fluid, DirectSettings::default());
        let mut rng = SplitMix64::new(23);
        let spheres: Vec<RigidSphere> = (0..40)
            .map(|_| {
                let centre = std::array::from_fn(|d| grid.origin[d] + rng.next_f64() * length[d]);
                RigidSphere::fixed(centre, 0.06 + 0.04 * rng.next_f64())
            })
            .collect();
        let ids: Vec<u64> = (0..spheres.len() as u64).collect();
        coupling.set_spheres(&spheres, &ids);
        let nominal = coupling.settings.integral.surface_offset;
        let expected: Vec<f64> = spheres
            .iter()
            .enumerate()
            .map(|(i, a)| {
                let mut gap = (0..3)
                    .map(|d| length[d] - 2.0 * a.radius)
                    .fold(f64::INFINITY, f64::min);
                for (j, b) in spheres.iter().enumerate() {
                    if j != i {
                        let dist2: f64 = (0..3)
                            .map(|d| nearest_image(a.centre[d] - b.centre[d], length[d]).powi(2))
                            .sum();
                        gap = gap.min(dist2.sqrt() - a.radius - b.radius);
                    }
                }
                nominal.min((gap / h - 1.0).max(1.0))
            })
            .collect();
        let found = coupling.surface_offsets().to_vec();
        assert_eq!(found, expected);
        let reduced = found.iter().filter(|&&o| o < nominal).count();
        assert!(
            reduced > 10 && reduced < found.len() - 10,
            "{reduced} of {} reduced",
            found.len()
        );
    }

    #[test]
    fn spread_bits_moves_each_bit_to_three_times_its_place() {
        let mut rng = SplitMix64::new(11);
        for _ in 0..1000 {
            let v = (rng.next_f64() * (1u64 << 21) as f64) as u64;
            let naive = (0..21).fold(0u64, |acc, i| acc | ((v >> i) & 1) << (3 * i));
            assert_eq!(spread_bits(v), naive, "v = {v:#x}");
        }
        assert_eq!(spread_bits(u64::MAX), 0x1249_2492_4924_9249);
    }
}
