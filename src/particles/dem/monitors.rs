//! What the DEM reports about its particles between steps: energies, the mean velocity and
//! the worst overlap.

use rayon::prelude::*;

use super::Dem;
use crate::particles::domain_box::{minimum_image, FaceCondition};
use crate::particles::neighbour_list::{wall_distance, CHUNK};
use crate::Vec3;

impl Dem {
    /// Kinetic energy `(Σ ½ m v², Σ ½ I ω²)`, translational and rotational, J.
    pub fn kinetic_energy(&self) -> (f64, f64) {
        let p = &self.particles;
        (0..p.len())
            .into_par_iter()
            .with_min_len(CHUNK)
            .map(|i| {
                let (m, inertia) = (p.mass(i), p.moment_of_inertia(i));
                (
                    0.5 * m * p.velocity[i].dot(&p.velocity[i]),
                    0.5 * inertia * p.angular_velocity[i].dot(&p.angular_velocity[i]),
                )
            })
            .reduce(|| (0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1))
    }

    /// Potential energy of gravity with buoyancy, `−Σ m (1 − ρ_f/ρ_p) g·x`, J (meaningless
    /// along a periodic axis).
    pub fn potential_energy(&self) -> f64 {
        let p = &self.particles;
        let g = self.config.gravity;
        let rho_f = self.config.fluid_density;
        (0..p.len())
            .filter(|&i| !p.fixed[i])
            .map(|i| -p.mass(i) * (1.0 - rho_f / p.density[i]) * g.dot(&p.position[i]))
            .sum()
    }

    /// Mean velocity of the free particles, m/s.
    pub fn mean_velocity(&self) -> Vec3 {
        let p = &self.particles;
        let mut s = Vec3::zeros();
        let mut count = 0usize;
        for i in 0..p.len() {
            if !p.fixed[i] {
                for a in 0..3 {
                    s[a] += p.velocity[i][a];
                }
                count += 1;
            }
        }
        if count == 0 {
            Vec3::zeros()
        } else {
            s * (1.0 / count as f64)
        }
    }

    /// Largest overlap over the diameter: `δ / min(d_i, d_j)` for pairs, `δ / d` at walls.
    pub fn max_overlap_ratio(&self) -> f64 {
        self.worst_overlap().ratio
    }

    /// The largest overlap over the diameter and where it is (the first of equal ones, by
    /// particle index): a run that stops on it names the pair or the wall.
    pub fn worst_overlap(&self) -> WorstOverlap {
        let (length, inv_l) = (self.domain.length(), self.domain.inverse_periodic_length());
        let x = &self.particles.position;
        let lists = &self.lists;
        let radius = &self.radius;
        let domain = &self.domain;
        let periodic = inv_l != Vec3::zeros();
        let none = WorstOverlap {
            ratio: 0.0,
            particle: 0,
            with: OverlapPartner::Particle(0),
        };
        (0..self.particles.len())
            .into_par_iter()
            .with_min_len(CHUNK)
            .map(|i| {
                let mut worst = WorstOverlap {
                    particle: i,
                    ..none
                };
                for k in lists.row_start[i] as usize..lists.row_start[i + 1] as usize {
                    let j = lists.partner[k] as usize;
                    let mut d = Vec3::new(x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]);
                    if periodic {
                        d = minimum_image(d, length, inv_l);
                    }
                    // Most listed pairs are apart (overlap ≤ 0 cannot raise `worst` ≥ 0):
                    // the square root only for those in contact.
                    let reach = radius[i] + radius[j];
                    let dist2 = d.dot(&d);
                    if dist2 >= reach * reach {
                        continue;
                    }
                    let overlap = radius[i] + radius[j] - dist2.sqrt();
                    let ratio = overlap / (2.0 * radius[i].min(radius[j]));
                    if ratio > worst.ratio {
                        worst.ratio = ratio;
                        worst.with = OverlapPartner::Particle(j);
                    }
                }
                for f in 0..6 {
                    if domain.faces[f] == FaceCondition::Wall {
                        let ratio =
                            (radius[i] - wall_distance(domain, f, x[i])) / (2.0 * radius[i]);
                        if ratio > worst.ratio {
                            worst.ratio = ratio;
                            worst.with = OverlapPartner::Wall(f);
                        }
                    }
                }
                worst
            })
            .reduce(
                || none,
                |a, b| {
                    // `reduce` keeps the order of the items: ties go to the lower index
                    if b.ratio > a.ratio {
                        b
                    } else {
                        a
                    }
                },
            )
    }
}

/// The largest overlap of a cloud: `ratio` = δ over the smaller diameter (over `d` at a
/// wall), between `particle` and `with` (indices into the particle arrays).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorstOverlap {
    pub ratio: f64,
    pub particle: usize,
    pub with: OverlapPartner,
}

/// What a particle overlaps: another particle (its index) or a wall face (`2·axis + side`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum OverlapPartner {
    Particle(usize),
    Wall(usize),
}
