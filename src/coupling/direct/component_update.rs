//! The rebuild of one velocity component's forced faces (see
//! [`ImmersedBoundary::update`](super::ImmersedBoundary::update)): the faces inside the
//! spheres, the candidate forcing faces next to them, and each forcing face's stencil.

use super::face_lattice::FaceLattice;
use super::forced_face::{
    ForcingFace, ForcingLine, GapFace, InteriorFace, ThroatFace, FLUID, FORCING, THROAT,
};
use super::rigid_sphere::RigidSphere;
use crate::Vec3;
use rayon::prelude::*;

/// A candidate forcing face, 8 bytes: the interior face it neighbours (index into the
/// sites) and the direction `2 d + (step > 0)` from it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Candidate {
    site: u32,
    direction: u8,
}

/// The forced faces of one component, rebuilt (see
/// [`ImmersedBoundary::update`](super::ImmersedBoundary::update)).
pub(super) struct ComponentUpdate<'a> {
    pub(super) lattice: FaceLattice<'a>,
    pub(super) labels: &'a mut Vec<u32>,
    pub(super) touched: &'a mut Vec<u32>,
    pub(super) interior: &'a mut Vec<InteriorFace>,
    pub(super) forcing: &'a mut Vec<ForcingFace>,
    pub(super) gaps: &'a mut Vec<GapFace>,
    pub(super) throats: &'a mut Vec<ThroatFace>,
    /// Scratch: the throats' targets of the last build by slot.
    pub(super) carried: &'a mut Vec<(u32, f64)>,
    pub(super) candidates: &'a mut Vec<Candidate>,
    pub(super) sites: &'a mut Vec<[i32; 3]>,
    /// Per sphere, where its interior faces start in the lists (and their total last).
    pub(super) offsets: &'a mut Vec<usize>,
}

impl ComponentUpdate<'_> {
    pub(super) fn run(&mut self, spheres: &[RigidSphere], quadratic: bool, open_throats: bool) {
        for &slot in self.touched.iter() {
            self.labels[slot as usize] = FLUID;
        }
        self.touched.clear();
        self.carried.clear();
        let forcing = &self.forcing[..];
        self.carried.extend(
            self.throats
                .iter()
                .map(|t| (forcing[t.face as usize].slot, t.target)),
        );
        self.carried.sort_unstable_by_key(|&(slot, _)| slot);
        self.interior.clear();
        self.forcing.clear();
        self.gaps.clear();
        self.throats.clear();
        self.sites.clear();
        self.candidates.clear();
        self.mark_interior(spheres);
        self.mark_candidates();
        self.build_forcing(spheres, quadratic);
        if quadratic {
            self.find_gaps(spheres);
        }
        self.find_throats(spheres);
        // Driven, a throat's face answers the pressure: it leaves its cells open.
        if open_throats {
            for t in self.throats.iter() {
                self.labels[self.forcing[t.face as usize].slot as usize] = THROAT;
            }
        }
    }

    /// Faces inside a sphere (the first sphere in order that holds them). The spheres'
    /// faces are found in parallel, each sphere's into its own stretch of the lists in
    /// sphere order; one pass in that order then labels them and drops a face already
    /// taken by an earlier sphere (overlapping spheres, or a sphere wider than a periodic
    /// box): the lists the spheres one after another would give.
    fn mark_interior(&mut self, spheres: &[RigidSphere]) {
        let lat = &self.lattice;
        self.offsets.clear();
        self.offsets.push(0);
        self.offsets.par_extend(spheres.par_iter().map(|s| {
            let mut count = 0;
            visit_inside(lat, s, |_, _| count += 1);
            count
        }));
        for k in 1..self.offsets.len() {
            self.offsets[k] += self.offsets[k - 1];
        }
        let total = self.offsets[spheres.len()];
        let unset = InteriorFace {
            slot: 0,
            cells: [0; 2],
            target: 0.0,
            sphere: 0,
        };
        self.interior.resize(total, unset);
        self.sites.resize(total, [0; 3]);
        fill_inside(
            lat,
            spheres,
            0,
            self.offsets,
            &mut self.interior[..],
            &mut self.sites[..],
        );
        // Labels in sphere order; a face already labelled is dropped, the rest closed up.
        let mut kept = 0;
        for i in 0..total {
            let f = self.interior[i];
            let slot = f.slot as usize;
            if self.labels[slot] != FLUID {
                continue;
            }
            self.labels[slot] = f.sphere + 1;
            self.touched.push(slot as u32);
            self.interior[kept] = f;
            self.sites[kept] = self.sites[i];
            kept += 1;
        }
        self.interior.truncate(kept);
        self.sites.truncate(kept);
    }

    /// Fluid faces next to an interior face (along any axis) become forcing faces.
    fn mark_candidates(&mut self) {
        let lat = &self.lattice;
        for (site, m) in self.sites.iter().enumerate() {
            let here = lat
                .site(m.map(|v| v as isize))
                .expect("an interior face is an advanced face");
            for d in 0..3 {
                for step in [-1isize, 1] {
                    let Some(q) = lat.adjacent(here, d, step) else {
                        continue;
                    };
                    let slot = lat.layout.index(q[0], q[1], q[2]);
                    if self.labels[slot] == FLUID {
                        self.labels[slot] = FORCING;
                        self.touched.push(slot as u32);
                        self.candidates.push(Candidate {
                            site: site as u32,
                            direction: (2 * d) as u8 + u8::from(step > 0),
                        });
                    }
                }
            }
        }
    }

    /// The interpolation stencil of every candidate forcing face, in parallel over the
    /// candidates and in their order (each reads only the labels, final by now).
    fn build_forcing(&mut self, spheres: &[RigidSphere], quadratic: bool) {
        let (lat, labels, sites) = (&self.lattice, &self.labels[..], &self.sites[..]);
        const CHUNK: usize = 1024;
        self.forcing.par_extend(
            self.candidates
                .par_iter()
                .with_min_len(CHUNK)
                .map(|candidate| forcing_face(lat, labels, sites, candidate, spheres, quadratic)),
        );
    }

    /// The forcing faces whose linear stencil is a gap's (see [`GapFace`]), in list order.
    fn find_gaps(&mut self, spheres: &[RigidSphere]) {
        let (lat, labels, forcing) = (&self.lattice, &self.labels[..], &self.forcing[..]);
        const CHUNK: usize = 1024;
        self.gaps.par_extend(
            forcing
                .par_iter()
                .enumerate()
                .with_min_len(CHUNK)
                .filter_map(|(i, f)| gap_face(lat, labels, spheres, i, f)),
        );
    }

    /// The staircase forcing faces in throats (see [`ThroatFace`]), in list order, each
    /// with its target of the last build if it was in a throat then.
    fn find_throats(&mut self, spheres: &[RigidSphere]) {
        let (lat, labels, forcing) = (&self.lattice, &self.labels[..], &self.forcing[..]);
        const CHUNK: usize = 1024;
        self.throats.par_extend(
            forcing
                .par_iter()
                .enumerate()
                .with_min_len(CHUNK)
                .filter_map(|(i, f)| throat_face(lat, labels, spheres, i, f)),
        );
        ThroatFace::take_targets(self.throats, forcing, self.carried);
    }
}

/// The throat term of staircase forcing face `index` (`f`), if the far wall lies within two
/// faces along its line.
fn throat_face(
    lat: &FaceLattice,
    labels: &[u32],
    spheres: &[RigidSphere],
    index: usize,
    f: &ForcingFace,
) -> Option<ThroatFace> {
    if f.neighbours[0] != f.slot {
        return None;
    }
    let line = ForcingLine::unpack(f.line);
    let away = -line.step;
    let site = lat.slot_site(f.slot as usize);
    let first = lat.adjacent(site, line.d, away)?;
    let h = lat.grid.h[line.d];
    let (k, inside, faces) = match inside_at(lat, labels, Some(first)) {
        Some(k) => (k, first, 1.0),
        None => {
            if labels[lat.layout.index(first[0], first[1], first[2])] != FORCING {
                return None;
            }
            let second = lat.adjacent(first, line.d, away)?;
            (inside_at(lat, labels, Some(second))?, second, 2.0)
        }
    };
    // From the face inside: its nearest image of the sphere is the one the line enters.
    let mut rel = lat.relative(lat.site_position(inside), &spheres[k]);
    rel[line.d] -= away as f64 * faces * h;
    let distance = FaceLattice::entry_distance(rel, spheres[k].radius, line.d, away)?;
    let x = lat.site_position(site);
    let delta = lat.surface_distance(x, &spheres[line.sphere], line);
    let far = ForcingLine {
        sphere: k,
        d: line.d,
        step: away,
    };
    // The lubrication profile across the gap: the distances to both surfaces through the
    // face, and this component's share across the gap (along the line of centres).
    let own = lat.relative(x, &spheres[line.sphere]);
    let norm = |v: Vec3| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let (r_own, r_far) = (norm(own), norm(rel));
    let axis = Vec3::from_fn(|d, _| own[d] / r_own - rel[d] / r_far);
    let darcy = ThroatFace::darcy(
        (r_own - spheres[line.sphere].radius).max(0.0),
        (r_far - spheres[k].radius).max(0.0),
        axis[lat.c] / norm(axis).max(f64::MIN_POSITIVE),
        h,
    );
    Some(ThroatFace {
        face: index as u32,
        sphere: k as u32,
        distance,
        share: delta / (delta + distance).max(f64::MIN_POSITIVE),
        darcy,
        wall: lat.velocity_beyond(x, distance, far, &spheres[k]),
        target: f64::NAN,
    })
}

/// Calls `visit(m, site)` for every advanced face inside sphere `s`, in a fixed order: `m`
/// its lattice index (unwrapped), `site` its padded indices.
#[inline]
pub(super) fn visit_inside(
    lat: &FaceLattice,
    s: &RigidSphere,
    mut visit: impl FnMut([isize; 3], [usize; 3]),
) {
    let b = lat.bounds(s, 0);
    let r2 = s.radius * s.radius;
    for m2 in b[2].0..=b[2].1 {
        let rel2 = lat.coordinate(2, m2) - s.centre[2];
        let Some(s2) = lat.axis_slot(2, m2) else {
            continue;
        };
        for m1 in b[1].0..=b[1].1 {
            let rel1 = lat.coordinate(1, m1) - s.centre[1];
            // (rel₀² + rel₁²) + rel₂² ≥ rel₁² + rel₂² in floating point too
            // (rounding is monotone): a line outside stays outside.
            if rel1 * rel1 + rel2 * rel2 >= r2 {
                continue;
            }
            let Some(s1) = lat.axis_slot(1, m1) else {
                continue;
            };
            for m0 in b[0].0..=b[0].1 {
                let rel0 = lat.coordinate(0, m0) - s.centre[0];
                if rel0 * rel0 + rel1 * rel1 + rel2 * rel2 >= r2 {
                    continue;
                }
                let Some(s0) = lat.axis_slot(0, m0) else {
                    continue;
                };
                visit([m0, m1, m2], [s0, s1, s2]);
            }
        }
    }
}

/// The interior faces of spheres `first..` into `interior` and `sites`, sphere `k`'s at
/// `offsets[k] − offsets[first]..`: halves of the spheres in parallel.
fn fill_inside(
    lat: &FaceLattice,
    spheres: &[RigidSphere],
    first: usize,
    offsets: &[usize],
    interior: &mut [InteriorFace],
    sites: &mut [[i32; 3]],
) {
    const SPHERES: usize = 16;
    if spheres.len() > SPHERES {
        let half = spheres.len() / 2;
        let split = offsets[first + half] - offsets[first];
        let (i0, i1) = interior.split_at_mut(split);
        let (s0, s1) = sites.split_at_mut(split);
        let (a, b) = spheres.split_at(half);
        rayon::join(
            || fill_inside(lat, a, first, offsets, i0, s0),
            || fill_inside(lat, b, first + half, offsets, i1, s1),
        );
        return;
    }
    let mut next = 0;
    for (j, s) in spheres.iter().enumerate() {
        let k = first + j;
        visit_inside(lat, s, |m, site| {
            let slot = lat.layout.index(site[0], site[1], site[2]);
            sites[next] = [m[0] as i32, m[1] as i32, m[2] as i32];
            interior[next] = InteriorFace {
                slot: slot as u32,
                cells: lat.cells(site),
                target: lat.interior_target(slot, s),
                sphere: k as u32,
            };
            next += 1;
        });
    }
}

/// Sphere index of the face at padded indices `site`, if inside one.
#[inline]
fn inside_at(lat: &FaceLattice, labels: &[u32], site: Option<[usize; 3]>) -> Option<usize> {
    let s = site?;
    let l = labels[lat.layout.index(s[0], s[1], s[2])];
    (l != FLUID && l != FORCING).then(|| (l - 1) as usize)
}

/// The forcing face of `candidate`: the line most nearly normal to the surface among those
/// that cross it, and the stencil along it.
fn forcing_face(
    lat: &FaceLattice,
    labels: &[u32],
    sites: &[[i32; 3]],
    candidate: &Candidate,
    spheres: &[RigidSphere],
    quadratic: bool,
) -> ForcingFace {
    let mut m = sites[candidate.site as usize].map(|v| v as isize);
    let d = usize::from(candidate.direction / 2);
    m[d] += if candidate.direction % 2 == 1 { 1 } else { -1 };
    let site = lat.site(m).expect("a candidate is an advanced face");
    let slot = lat.layout.index(site[0], site[1], site[2]);
    // From the wrapped index, as [`ImmersedBoundary::refresh`] does: the same rounding.
    let x = lat.site_position(site);
    let mut best: Option<(f64, usize, isize, usize)> = None;
    for d in 0..3 {
        for step in [-1isize, 1] {
            if let Some(k) = inside_at(lat, labels, lat.adjacent(site, d, step)) {
                let rel = lat.relative(x, &spheres[k]);
                let norm = (rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2]).sqrt();
                // Outward direction along the line is −step.
                let score = -(step as f64) * rel[d] / norm.max(f64::MIN_POSITIVE);
                if best.is_none_or(|b| score > b.0) {
                    best = Some((score, d, step, k));
                }
            }
        }
    }
    let (_, d, step, k) = best.expect("a candidate has an inside neighbour");
    let line = ForcingLine { sphere: k, d, step };
    let h = lat.grid.h[d];
    let t = lat.surface_distance(x, &spheres[k], line);
    let wall = lat.wall_velocity(x, t, line, &spheres[k]);
    // The two faces outward along the line, as (slot, padded indices) when fluid.
    let outer = lat.adjacent(site, d, -step);
    let outer2 = outer.and_then(|s| lat.adjacent(s, d, -step));
    let free = |site: Option<[usize; 3]>| {
        let s = site?;
        let n = lat.layout.index(s[0], s[1], s[2]);
        (labels[n] == FLUID).then_some((n as u32, s))
    };
    let cells = lat.cells(site);
    let slot = slot as u32;
    let (neighbours, neighbour_cells, weights) = match (free(outer), free(outer2)) {
        (Some((n1, s1)), Some((n2, s2))) if quadratic => (
            [n1, n2],
            [lat.cells(s1), lat.cells(s2)],
            [2.0 * t / (t + h), -t / (t + 2.0 * h)],
        ),
        (Some((n1, s1)), _) => {
            let gap = quadratic.then(|| far_wall(lat, labels, spheres, s1, line));
            let weight = match gap.flatten() {
                Some((_, distance)) => GapFace::weights(t, distance, h).0,
                None => t / (t + h),
            };
            ([n1, n1], [lat.cells(s1); 2], [weight, 0.0])
        }
        (None, _) => ([slot, slot], [cells, cells], [0.0, 0.0]),
    };
    ForcingFace {
        slot,
        cells,
        neighbours,
        neighbour_cells,
        weights,
        wall,
        line: line.pack(),
    }
}

/// The sphere a forcing face's line enters beyond a gap (see [`GapFace`]): past the face's
/// fluid face `outer`, the next face is forced and the one after inside a sphere. That
/// sphere and the distance from the face to where the line enters it.
fn far_wall(
    lat: &FaceLattice,
    labels: &[u32],
    spheres: &[RigidSphere],
    outer: [usize; 3],
    line: ForcingLine,
) -> Option<(usize, f64)> {
    let away = -line.step;
    let forced = lat.adjacent(outer, line.d, away)?;
    if labels[lat.layout.index(forced[0], forced[1], forced[2])] != FORCING {
        return None;
    }
    let inside = lat.adjacent(forced, line.d, away);
    let k = inside_at(lat, labels, inside)?;
    // From the face inside (three faces out): its nearest image of the sphere is the one
    // the line enters, where the face's own may be another (a sphere facing its own image).
    let h = lat.grid.h[line.d];
    let mut rel = lat.relative(lat.site_position(inside?), &spheres[k]);
    rel[line.d] -= away as f64 * 3.0 * h;
    // It enters between the forced face and the face inside, two to three cells out (the
    // forced face lies outside every sphere, and a sphere is convex); the floor at 2h holds
    // the weights' bounds against rounding.
    let distance = FaceLattice::entry_distance(rel, spheres[k].radius, line.d, away)?;
    Some((k, distance.max(2.0 * h)))
}

/// The gap term of forcing face `index` (`f`), if its stencil is a gap's: the same search
/// as [`forcing_face`]'s, from the same position.
fn gap_face(
    lat: &FaceLattice,
    labels: &[u32],
    spheres: &[RigidSphere],
    index: usize,
    f: &ForcingFace,
) -> Option<GapFace> {
    if f.neighbours[0] != f.neighbours[1] || f.neighbours[0] == f.slot {
        return None;
    }
    let line = ForcingLine::unpack(f.line);
    let site = lat.slot_site(f.slot as usize);
    let outer = lat.adjacent(site, line.d, -line.step)?;
    let x = lat.site_position(site);
    let (k, distance) = far_wall(lat, labels, spheres, outer, line)?;
    let t = lat.surface_distance(x, &spheres[line.sphere], line);
    let far = ForcingLine {
        sphere: k,
        d: line.d,
        step: -line.step,
    };
    Some(GapFace {
        face: index as u32,
        sphere: k as u32,
        distance,
        weight: GapFace::weights(t, distance, lat.grid.h[line.d]).1,
        wall: lat.velocity_beyond(x, distance, far, &spheres[k]),
    })
}
