//! The checks after each step that stop a failed run (exit code 1, the time directories
//! written so far kept whole) and say what failed and where: a velocity no longer finite (the
//! fluid's cell or the particle), a particle centre outside the box, particles overlapping
//! beyond [`MAX_OVERLAP`]. `step_size.rs` names the fastest fluid cell and particle here too
//! when a collapsing step shows a diverging run.

use super::particles::{CloudReport, Particles};
use super::simulation::Simulation;
use crate::error::FsimError;
use crate::fluid::FluidDiagnostics;
use crate::particles::{FaceCondition, OverlapPartner, FACE_NAMES};

/// The largest overlap over the diameter a run may reach (particle–particle over the smaller
/// d, particle–wall over d): soft-sphere DEM chooses its stiffness for small overlaps, a few
/// percent of d at most, and soft contacts chosen for speed peak at 6–9 % (settlingColumn, fluidizedBed and its cost study); at 20 % Hertz's
/// small-contact assumption is gone (contact radius √(2δ/d) = 0.63 of R) and the overlaps
/// double-count a visible part of the solid volume, so the results mean nothing.
pub const MAX_OVERLAP: f64 = 0.2;

/// Where the fluid moves fastest: the cell-centred velocity of the cell, the first cell whose
/// velocity is not finite if there is one.
struct FluidPeak {
    speed: f64,
    velocity: [f64; 3],
    cell: [usize; 3],
    centre: [f64; 3],
}

impl Simulation {
    /// The step's diagnostics back, unless the run failed: a velocity that is no longer
    /// finite (the fluid's or a particle's), a particle centre outside the box along a
    /// non-periodic axis, or an overlap beyond [`MAX_OVERLAP`] (`cloud`: the step's report,
    /// whose largest overlap is looked up only when it is too large).
    pub fn check_health(
        &self,
        d: FluidDiagnostics,
        cloud: Option<&CloudReport>,
    ) -> Result<FluidDiagnostics, FsimError> {
        if !d.kinetic_energy.is_finite() || !d.max_courant.is_finite() {
            let peak = self.fluid_peak();
            return Err(FsimError::run(format!(
                "the solution diverged at t = {} s (step {}): the fluid velocity is no longer \
                 finite: U = {} m/s in cell {} at {} m (the first such cell){}",
                self.time.time,
                self.time.step,
                triple(peak.velocity),
                cell_triple(peak.cell),
                triple(peak.centre),
                self.virtual_mass_hint()
            )));
        }
        let Some(particles) = self.particles() else {
            return Ok(d);
        };
        if let Some(i) = particles.first_diverged_index() {
            let s = particles.dem.particles();
            return Err(FsimError::run(format!(
                "the solution diverged at t = {} s (step {}): particle {i} (id {}) has no \
                 finite velocity or position: U = {} m/s at {} m{}",
                self.time.time,
                self.time.step,
                s.id[i],
                triple(s.velocity[i].into()),
                triple(s.position[i].into()),
                self.virtual_mass_hint()
            )));
        }
        self.check_inside(particles)?;
        if let Some(c) = cloud.filter(|c| c.max_overlap > MAX_OVERLAP) {
            return Err(self.overlap_error(particles, c));
        }
        Ok(d)
    }

    /// Every particle centre inside the box along the axes that are neither periodic (a
    /// centre wraps there) nor planar (it sits on the mid-plane): a centre beyond a face has
    /// passed a wall or a rebound face, and the particle is lost to the run.
    fn check_inside(&self, particles: &Particles) -> Result<(), FsimError> {
        let domain = particles.dem.domain();
        let s = particles.dem.particles();
        let checked: [bool; 3] =
            std::array::from_fn(|a| !domain.is_periodic(a) && !domain.planar[a]);
        for i in 0..s.len() {
            for (a, &check) in checked.iter().enumerate() {
                if !check {
                    continue;
                }
                let x = s.position[i][a];
                let face = if x < domain.lo[a] {
                    2 * a
                } else if x > domain.hi[a] {
                    2 * a + 1
                } else {
                    continue;
                };
                return Err(self.outside_error(particles, i, face));
            }
        }
        Ok(())
    }

    /// The message of particle `i` whose centre lies beyond `face`: where, how fast, and what
    /// lets a particle through (a displacement per collision sub-step too large for the
    /// contact to stop it).
    fn outside_error(&self, particles: &Particles, i: usize, face: usize) -> FsimError {
        let domain = particles.dem.domain();
        let s = particles.dem.particles();
        let a = face / 2;
        let plane = if face.is_multiple_of(2) {
            domain.lo[a]
        } else {
            domain.hi[a]
        };
        let kind = match domain.faces[face] {
            FaceCondition::Wall => "wall",
            FaceCondition::Rebound { .. } => "rebound face",
            FaceCondition::Periodic => "periodic face",
        };
        let speed = s.velocity[i].norm();
        let sub_step = self.dt / particles.substeps.max(1) as f64;
        let fix = match domain.faces[face] {
            FaceCondition::Wall => {
                "the wall contact could not stop it: lower deltaT (or maxCo, maxDeltaT), raise \
                 collisionResolutionSteps, or stiffen the wall (youngsModulus of \
                 wallSpringSliderDashpotCoeffs, kn of wallLinearSpringDashpotCoeffs); check \
                 the particle's initial velocity and the forces on it"
            }
            _ => {
                "a rebound face mirrors a centre once per sub-step: lower deltaT (or maxCo, \
                 maxDeltaT) or raise collisionResolutionSteps; check the particle's initial \
                 velocity and the forces on it"
            }
        };
        FsimError::run(format!(
            "particle {i} (id {}) left the domain at t = {} s (step {}): its centre {} m lies \
             {:.3e} m beyond the {} {kind} ({} = {plane} m); moving at |U| = {speed:.3e} m/s it \
             travels {:.3e} m per collision sub-step, {:.3} of its diameter, so {fix}",
            s.id[i],
            self.time.time,
            self.time.step,
            triple(s.position[i].into()),
            (s.position[i][a] - plane).abs(),
            FACE_NAMES[face],
            ["x", "y", "z"][a],
            speed * sub_step,
            speed * sub_step / s.diameter[i],
        ))
    }

    /// The message of an overlap beyond [`MAX_OVERLAP`]: the pair or the particle and wall.
    fn overlap_error(&self, particles: &Particles, cloud: &CloudReport) -> FsimError {
        let worst = particles.dem.worst_overlap();
        let s = particles.dem.particles();
        let i = worst.particle;
        let what = match worst.with {
            OverlapPartner::Particle(j) => format!(
                "particles {i} (id {}) at {} m and {j} (id {}) at {} m overlap by {:.4} of the \
                 smaller diameter",
                s.id[i],
                triple(s.position[i].into()),
                s.id[j],
                triple(s.position[j].into()),
                worst.ratio
            ),
            OverlapPartner::Wall(f) => format!(
                "particle {i} (id {}) at {} m overlaps the {} wall by {:.4} of its diameter",
                s.id[i],
                triple(s.position[i].into()),
                FACE_NAMES[f],
                worst.ratio
            ),
        };
        FsimError::run(format!(
            "{what} at t = {} s (step {}), beyond the {MAX_OVERLAP} fsim allows (soft-sphere DEM \
             keeps overlaps to a few percent): the contacts are too soft for these loads or impact \
             speeds; stiffen them (youngsModulus, or kn of a linear spring model), raise \
             collisionResolutionSteps, or lower deltaT ({} collision sub-steps in this step)",
            self.time.time, self.time.step, cloud.substeps
        ))
    }

    /// Where the fluid and the particles move fastest, for the message of a run whose step
    /// collapses: "; the fluid's largest velocity …[, the fastest particle …]".
    pub(super) fn fastest_velocities(&self) -> String {
        let peak = self.fluid_peak();
        let mut text = format!(
            "; the fluid's largest velocity is |U| = {:.3e} m/s, U = {} m/s, in cell {} at {} m",
            peak.speed,
            triple(peak.velocity),
            cell_triple(peak.cell),
            triple(peak.centre)
        );
        if let Some(p) = self.particles() {
            let s = p.dem.particles();
            let fastest = (0..s.len())
                .filter(|&i| !s.fixed[i])
                .max_by(|&a, &b| s.velocity[a].norm().total_cmp(&s.velocity[b].norm()));
            if let Some(i) = fastest {
                text.push_str(&format!(
                    ", the fastest particle's |U| = {:.3e} m/s: particle {i} (id {}) at {} m",
                    s.velocity[i].norm(),
                    s.id[i],
                    triple(s.position[i].into())
                ));
            }
        }
        text
    }

    /// The cell whose cell-centred velocity is largest, or the first (x fastest) whose
    /// velocity is not finite. Only for messages: it interpolates the whole field.
    fn fluid_peak(&self) -> FluidPeak {
        let grid = self.fluid.grid();
        let mut cells = vec![[0.0; 3]; grid.cell_count()];
        self.fluid.cell_velocity(&mut cells);
        let mut best = 0;
        let mut best_speed = -1.0;
        for (index, u) in cells.iter().enumerate() {
            let speed = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
            if !speed.is_finite() {
                best = index;
                best_speed = speed;
                break;
            }
            if speed > best_speed {
                best = index;
                best_speed = speed;
            }
        }
        let n = grid.n;
        let cell = [best % n[0], (best / n[0]) % n[1], best / (n[0] * n[1])];
        FluidPeak {
            speed: if best_speed < 0.0 { 0.0 } else { best_speed },
            velocity: cells.get(best).copied().unwrap_or([0.0; 3]),
            cell,
            centre: grid.cell_centre(cell[0], cell[1], cell[2]),
        }
    }
}

/// `(x y z)` as OpenFOAM writes a vector.
fn triple(v: [f64; 3]) -> String {
    format!("({:.6e} {:.6e} {:.6e})", v[0], v[1], v[2])
}

/// `(i j k)` of a cell.
fn cell_triple(c: [usize; 3]) -> String {
    format!("({} {} {})", c[0], c[1], c[2])
}
