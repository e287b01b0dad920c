//! What the direct model can resolve, checked before the run (and by `-dry-run`).
//!
//! `fsimFoam` takes the warnings from here; the errors it reports through
//! `DirectCoupling::check_particles` (r/h, size) and the DEM loader (overlaps, with the
//! positions file's line), which run on the same particles. The errors below serve callers of
//! the library.
//!
//! - Errors (the run cannot be meaningful): a sphere with fewer than two cells per radius
//!   (`r/h < 2`: the staircase of cut cells is coarser than the sphere and the stress
//!   integral has no resolved shell to sit on; the drag-law model is the tool there), a
//!   sphere wider than the box along some axis (it overlaps its own periodic image or the
//!   walls), two spheres overlapping beyond the DEM's tolerance.
//! - Warnings (the run goes on, less accurate): surface gaps between spheres, or between a
//!   sphere and a wall, narrower than `2h` (the paper's §3.1: denser media need finer grids;
//!   the lubrication correction takes over below its cut-off), and fixed spheres with
//!   nothing to drive the flow through them (no `meanVelocityForce`, no inlet, no moving
//!   wall: the fluid stays at rest and every force is zero).

use super::close_pairs::{ClosePairs, PeriodicBox};
use crate::grid::Grid;
use crate::particles::ParticleState;

pub use super::tuning::{MIN_CELLS_PER_RADIUS, RESOLVED_GAP_CELLS};

/// The findings of [`check_resolution`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ResolutionReport {
    pub errors: Vec<String>,
    pub warnings: Vec<String>,
    /// Smallest `r/h` over the spheres (`h`: the coarsest spacing).
    pub min_cells_per_radius: f64,
    /// Smallest surface gap (pairs and walls) over `h`; `INFINITY` when none is near.
    pub min_gap_cells: f64,
}

/// Checks the spheres `p` on `grid` in `domain` with no-slip walls `walls` (face order
/// `x−, x+, y−, y+, z−, z+`); `driven` says whether anything drives the flow (a mean
/// pressure gradient, an inlet, a moving wall), `overlap_tolerance` is the DEM's accepted
/// initial overlap over the smaller diameter.
pub fn check_resolution(
    grid: &Grid,
    p: &ParticleState,
    domain: &PeriodicBox,
    walls: [bool; 6],
    driven: bool,
    overlap_tolerance: f64,
) -> ResolutionReport {
    let h = grid.h.iter().cloned().fold(0.0, f64::max);
    let length = grid.length();
    let mut report = ResolutionReport {
        min_cells_per_radius: f64::INFINITY,
        min_gap_cells: f64::INFINITY,
        ..Default::default()
    };
    if p.is_empty() {
        return report;
    }
    let mut thin = None::<(usize, f64)>;
    let mut large = None::<(usize, usize)>;
    for i in 0..p.len() {
        let r = p.diameter[i] / 2.0;
        if r / h < report.min_cells_per_radius {
            report.min_cells_per_radius = r / h;
            thin = Some((i, r / h));
        }
        if large.is_none() {
            if let Some(a) = (0..3).find(|&a| p.diameter[i] > length[a]) {
                large = Some((i, a));
            }
        }
    }
    if let Some((i, ratio)) = thin.filter(|t| t.1 < MIN_CELLS_PER_RADIUS) {
        report.errors.push(format!(
            "particle {} (d = {:e} m): r/h = {ratio:.3} is below {MIN_CELLS_PER_RADIUS}; the \
             direct model needs at least {MIN_CELLS_PER_RADIUS} cells per radius (2.5 or more \
             recommended, h = {h:e} m): refine system/blockMeshDict or use model dragLaw",
            p.id[i], p.diameter[i]
        ));
    }
    if let Some((i, a)) = large {
        report.errors.push(format!(
            "particle {} (d = {:e} m) is larger than the box along {} (L = {:e} m)",
            p.id[i],
            p.diameter[i],
            ["x", "y", "z"][a],
            length[a]
        ));
    }
    let mut overlaps = 0usize;
    let mut worst = None::<(usize, usize, f64)>;
    // the narrow gaps: what the pair or wall is, its width
    let mut narrow: Vec<(String, f64)> = Vec::new();
    let mut counts = [0usize; 3]; // pairs, walls, own periodic images
    ClosePairs::default().visit(p, domain, RESOLVED_GAP_CELLS * h, |i, j, _, _, gap| {
        report.min_gap_cells = report.min_gap_cells.min(gap / h);
        if -gap > overlap_tolerance * p.diameter[i].min(p.diameter[j]) {
            overlaps += 1;
            if worst.is_none_or(|w| gap < w.2) {
                worst = Some((i, j, gap));
            }
        } else {
            counts[0] += 1;
            narrow.push((format!("particles {} and {}", p.id[i], p.id[j]), gap));
        }
    });
    if let Some((i, j, gap)) = worst {
        report.errors.push(format!(
            "{overlaps} pair(s) of particles overlap, the deepest particles {} and {} by {:e} m",
            p.id[i], p.id[j], -gap
        ));
    }
    for i in 0..p.len() {
        let r = p.diameter[i] / 2.0;
        for face in (0..6).filter(|&f| walls[f]) {
            let a = face / 2;
            let gap = if face % 2 == 1 {
                domain.hi[a] - p.position[i][a] - r
            } else {
                p.position[i][a] - domain.lo[a] - r
            };
            if gap < RESOLVED_GAP_CELLS * h {
                counts[1] += 1;
                report.min_gap_cells = report.min_gap_cells.min(gap / h);
                let side = ["x-", "x+", "y-", "y+", "z-", "z+"][face];
                narrow.push((format!("particle {} and the {side} wall", p.id[i]), gap));
            }
        }
        // A sphere and its own image across a periodic box: a gap the pairs do not see
        // (no lubrication either: the image moves with the sphere). Zero or less is the
        // error of a sphere that does not fit the box.
        for a in (0..3).filter(|&a| domain.periodic[a]) {
            let gap = domain.hi[a] - domain.lo[a] - 2.0 * r;
            if gap > 0.0 && gap < RESOLVED_GAP_CELLS * h {
                counts[2] += 1;
                report.min_gap_cells = report.min_gap_cells.min(gap / h);
                let axis = ["x", "y", "z"][a];
                narrow.push((
                    format!("particle {} and its periodic image along {axis}", p.id[i]),
                    gap,
                ));
            }
        }
    }
    if !narrow.is_empty() {
        narrow.sort_by(|a, b| a.1.total_cmp(&b.1));
        let named: Vec<String> = narrow
            .iter()
            .take(3)
            .map(|(what, gap)| format!("{what} ({:.2} h)", gap / h))
            .collect();
        let more = if narrow.len() > named.len() {
            format!(" and {} more", narrow.len() - named.len())
        } else {
            String::new()
        };
        let smallest = narrow[0].1;
        let fix = if smallest > 0.0 {
            let target = smallest / RESOLVED_GAP_CELLS;
            let n: Vec<String> = (0..3)
                .map(|a| ((length[a] / target).ceil() as usize).to_string())
                .collect();
            format!(
                "cells of h ≤ {target:.3e} m ({} cells) resolve the smallest",
                n.join(" ")
            )
        } else {
            "spheres in contact have no grid that resolves their gap".to_string()
        };
        report.warnings.push(format!(
            "{} particle pair(s), {} particle-wall gap(s) and {} gap(s) of a particle to its \
             own periodic image are narrower than {RESOLVED_GAP_CELLS} cells (h = {h:e} m): \
             {}{more}; the grid does not resolve the flow there (the lubrication correction \
             covers the normal force of pairs and walls below its cut-off); {fix}",
            counts[0],
            counts[1],
            counts[2],
            named.join(", "),
        ));
    }
    if !driven && p.fixed.iter().any(|&f| f) && p.fixed.iter().all(|&f| f) {
        report.warnings.push(
            "every particle is fixed and nothing drives the flow (no meanVelocityForce in \
             fvOptions, no inlet, no moving wall): the fluid stays at rest and the forces are \
             zero"
                .to_string(),
        );
    }
    report
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Vec3;

    fn grid(n: usize, l: f64) -> Grid {
        Grid::new([n; 3], [l / n as f64; 3], [0.0; 3])
    }

    fn periodic(l: f64) -> PeriodicBox {
        PeriodicBox {
            lo: Vec3::repeat(0.0),
            hi: Vec3::repeat(l),
            periodic: [true; 3],
        }
    }

    #[test]
    fn coarse_spheres_are_refused() {
        let mut p = ParticleState::default();
        p.push(7, [0.5; 3], 0.06, 2500.0); // r/h = 0.03/0.02 = 1.5
        let r = check_resolution(&grid(50, 1.0), &p, &periodic(1.0), [false; 6], true, 1e-3);
        assert_eq!(r.errors.len(), 1, "{:?}", r.errors);
        assert!(r.errors[0].contains("particle 7") && r.errors[0].contains("r/h = 1.500"));
        p.diameter[0] = 0.1; // r/h = 2.5
        let r = check_resolution(&grid(50, 1.0), &p, &periodic(1.0), [false; 6], true, 1e-3);
        assert!(r.errors.is_empty() && r.warnings.is_empty(), "{r:?}");
        assert!((r.min_cells_per_radius - 2.5).abs() < 1e-12);
    }

    #[test]
    fn sphere_larger_than_the_box_is_refused() {
        let mut p = ParticleState::default();
        p.push(1, [0.5; 3], 1.2, 2500.0);
        let r = check_resolution(&grid(50, 1.0), &p, &periodic(1.0), [false; 6], true, 1e-3);
        assert!(
            r.errors.iter().any(|e| e.contains("larger than the box")),
            "{r:?}"
        );
    }

    #[test]
    fn overlaps_are_errors_and_narrow_gaps_warnings() {
        let mut p = ParticleState::default();
        p.push(1, [0.3, 0.5, 0.5], 0.2, 2500.0);
        p.push(2, [0.5 + 0.01, 0.5, 0.5], 0.2, 2500.0); // gap 0.01 = 0.5 h
        p.push(3, [0.62, 0.5, 0.5], 0.2, 2500.0); // overlaps 2 by 0.09
        let r = check_resolution(&grid(50, 1.0), &p, &periodic(1.0), [false; 6], true, 1e-3);
        assert_eq!(r.errors.len(), 1, "{r:?}");
        assert!(r.errors[0].contains("particles 2 and 3"), "{}", r.errors[0]);
        assert_eq!(r.warnings.len(), 1, "{r:?}");
        assert!(
            r.warnings[0].contains("1 particle pair(s)")
                && r.warnings[0].contains("particles 1 and 2 (0.50 h)"),
            "{}",
            r.warnings[0]
        );
        assert!((r.min_gap_cells + 4.5).abs() < 1e-9, "{}", r.min_gap_cells);
    }

    #[test]
    fn a_sphere_close_to_its_own_periodic_image_warns() {
        let mut p = ParticleState::default();
        // gap L − d = 0.039 = 1.95 h: narrower than 2 cells
        p.push(4, [0.5; 3], 0.961, 2500.0);
        let r = check_resolution(&grid(50, 1.0), &p, &periodic(1.0), [false; 6], true, 1e-3);
        assert_eq!(r.warnings.len(), 1, "{r:?}");
        let w = &r.warnings[0];
        assert!(
            w.contains("3 gap(s) of a particle to its own periodic image"),
            "{w}"
        );
        assert!(
            w.contains("particle 4 and its periodic image along x (1.95 h)"),
            "{w}"
        );
        assert!(w.contains("(52 52 52 cells)"), "{w}");
        // 2.05 h: resolved
        p.diameter[0] = 0.959;
        let r = check_resolution(&grid(50, 1.0), &p, &periodic(1.0), [false; 6], true, 1e-3);
        assert!(r.warnings.is_empty(), "{r:?}");
    }

    #[test]
    fn wall_gaps_and_undriven_porous_media_warn() {
        let mut p = ParticleState::default();
        p.push(1, [0.5, 0.5, 0.11], 0.2, 2500.0); // 0.01 from the floor
        p.fixed[0] = true;
        let mut walls = [false; 6];
        walls[4] = true;
        let r = check_resolution(&grid(50, 1.0), &p, &periodic(1.0), walls, false, 1e-3);
        assert!(r.errors.is_empty());
        assert_eq!(r.warnings.len(), 2, "{r:?}");
        assert!(r.warnings[0].contains("1 particle-wall gap(s)"));
        assert!(r.warnings[1].contains("nothing drives the flow"));
        let r = check_resolution(&grid(50, 1.0), &p, &periodic(1.0), [false; 6], true, 1e-3);
        assert!(r.warnings.is_empty(), "{r:?}");
    }
}
