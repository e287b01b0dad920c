//! No-slip on spheres on the staggered grid: sharp-interface direct forcing.
//!
//! # The choice
//!
//! The paper imposes `v = v_p + ω_p × (x − x_p)` by setting the velocity samples inside each
//! sphere (a staircase: the effective surface wanders by up to half a cell, a first-order
//! error that changes erratically with the sphere's position). fsim keeps that for the
//! samples inside and adds, for every *forcing face* (a face outside all spheres with a
//! neighbour of the same component inside one), the linear interpolation of Fadlun, Verzicco,
//! Orlandi & Mohd-Yusof (J. Comput. Phys. 161, 35–60, 2000) along the grid line that crosses
//! the surface:
//!
//! ```text
//!   inside    forcing face f      f₂ (fluid)
//!     o----x-------o-----------------o          x: surface, distance δ from f along the line
//!          w       u_f = w + (u_f₂ − w) δ / (δ + h)
//! ```
//!
//! with `w` the rigid velocity at the crossing. The surface then sits where the sphere is to
//! `O(h²)` and the velocity is second order; the interpolation weight `δ/(δ+h) ∈ [0, ½)`
//! never amplifies. Of the lines through a forcing face that cross the surface, the one most
//! nearly normal to it is used. The default stencil is quadratic, through the next two fluid
//! faces ([`ImmersedBoundary::set_quadratic`]). In a gap, where the second of them is forced
//! and the face after it inside a sphere, the far wall takes its place ([`GapFace`]); where
//! no second point is found the stencil is linear, and where `f₂` above is itself in a
//! sphere or forced (a gap narrower than about two cells) the face takes the lubrication
//! profile between the two walls ([`ThroatFace`]; the walls' line when the throats are rigid).
//!
//! Against the alternatives (measured in `docs/direct_model.md`): the pure staircase gives
//! first-order, position-dependent drag; Uhlmann's (J. Comput. Phys. 209, 448–476, 2005)
//! regularised-delta forcing smears the surface over three cells and needs an empirical
//! radius retraction; volume-fraction weighting is first order at the surface.
//!
//! # Time stepping
//!
//! The forcing acts in [`FluidSolver::step_with`](crate::fluid::FluidSolver::step_with)'s
//! hook, on each stage's predicted velocity, before the projection. The projection then
//! subtracts `τ∇p`; the hook pre-compensates with the pressure of the previous projection
//! (`u_f* = target + τ ∂p`), so that once the flow is steady the forced faces hold their
//! targets exactly and the steady state does not depend on `Δt` (`Euler`, `RK3`).
//! `EulerRKC`'s incremental projection (`p ← p + φ`) adds `τ∇²pⁿ` to a closed cell's mass source, so that
//! the pressure a moving sphere covers ends harmonic there, as a full projection leaves it.

use super::component_update::{Candidate, ComponentUpdate};
use super::face_lattice::FaceLattice;
use super::forced_face::{ClosedCell, ForcingFace, ForcingLine, GapFace, InteriorFace, ThroatFace};
use super::forced_face::{FLUID, FORCING, THROAT};
use super::rigid_sphere::RigidSphere;
use crate::fluid::{BoundaryConditions, FaceCondition, PaddedLayout, SharedSamples};
use crate::grid::{nearest_image, Grid};
use rayon::prelude::*;

/// The forced faces of every velocity component for a set of spheres, rebuilt by
/// [`ImmersedBoundary::update`] whenever they move, and imposed by
/// [`ImmersedBoundary::impose`] in each stage of the fluid step.
///
/// Works on any box: faces the momentum equation does not advance (boundary faces) are
/// never forced, periodic images of a sphere are found by wrapping indices.
pub struct ImmersedBoundary {
    grid: Grid,
    layout: PaddedLayout,
    periodic: [bool; 3],
    /// Advanced face slots per component and direction (inclusive), as the fluid solver's.
    ranges: [[(usize, usize); 3]; 3],
    labels: [Vec<u32>; 3],
    /// The slots labelled at the last update, reset at the next (u32 as the lists: half the
    /// memory of usize).
    touched: [Vec<u32>; 3],
    interior: [Vec<InteriorFace>; 3],
    forcing: [Vec<ForcingFace>; 3],
    /// The forcing faces in gaps, with their far walls (quadratic stencil only).
    gaps: [Vec<GapFace>; 3],
    /// The staircase forcing faces in throats, with their far walls and targets.
    throats: [Vec<ThroatFace>; 3],
    /// Scratch of [`Self::update`]: each component's throat targets by slot, carried
    /// through the build.
    carried: [Vec<(u32, f64)>; 3],
    /// Time of each component's last stage that set the throats' targets (NaN before).
    throat_clock: [f64; 3],
    /// Kinematic viscosity of the throats' pressure-driven flow (0: rigid throats, held to
    /// the walls' line).
    throat_viscosity: f64,
    /// Cells with every face forced, and those of the previous update (their mass source
    /// is cleared at the next imposition).
    closed: Vec<ClosedCell>,
    previous_closed: Vec<usize>,
    /// Scratch of [`Self::impose`]: the mass source of each closed cell before its mean is
    /// taken off.
    closed_sources: Vec<f64>,
    /// Scratch of the closed-cell search: a mark per cell (0 outside the search) and the
    /// cells next to forced faces.
    cell_marks: Vec<u8>,
    near_cells: Vec<usize>,
    near_classes: Vec<u8>,
    queue: Vec<usize>,
    group: Vec<usize>,
    /// Scratch per component: the unwrapped lattice indices of the interior faces, and the
    /// candidate forcing faces next to them.
    candidates: [Vec<Candidate>; 3],
    sites: [Vec<[i32; 3]>; 3],
    offsets: [Vec<usize>; 3],
    /// Quadratic (two fluid faces) rather than linear forcing stencil.
    quadratic: bool,
    /// The spheres as at the last [`Self::update`] (their faces' labels and lines).
    built: Vec<RigidSphere>,
}

impl ImmersedBoundary {
    /// An empty boundary (no spheres) for a grid and its fluid conditions.
    pub fn new(grid: &Grid, bc: &BoundaryConditions) -> Self {
        let layout = PaddedLayout::new(grid.n);
        assert!(
            u32::try_from(layout.len).is_ok(),
            "the forced-face lists index the grid with u32"
        );
        let periodic = std::array::from_fn(|d| matches!(bc.face(d, 0), FaceCondition::Periodic));
        let ranges =
            std::array::from_fn(|c| std::array::from_fn(|d| bc.momentum_range(grid.n, c, d)));
        ImmersedBoundary {
            grid: grid.clone(),
            labels: std::array::from_fn(|_| vec![FLUID; layout.len]),
            layout,
            periodic,
            ranges,
            touched: Default::default(),
            interior: Default::default(),
            forcing: Default::default(),
            gaps: Default::default(),
            throats: Default::default(),
            carried: Default::default(),
            throat_clock: [f64::NAN; 3],
            throat_viscosity: 0.0,
            closed: Vec::new(),
            previous_closed: Vec::new(),
            closed_sources: Vec::new(),
            cell_marks: vec![0; grid.cell_count()],
            near_cells: Vec::new(),
            near_classes: Vec::new(),
            queue: Vec::new(),
            group: Vec::new(),
            candidates: Default::default(),
            sites: Default::default(),
            offsets: Default::default(),
            quadratic: true,
            built: Vec::new(),
        }
    }

    /// The kinematic viscosity (m²/s) of the pressure-driven flow through throats
    /// ([`ThroatFace`]); 0 holds the throats' faces to the walls' line.
    pub fn set_throat_viscosity(&mut self, nu: f64) {
        self.throat_viscosity = nu;
    }

    /// Component `c`'s forcing faces in throats (indices into [`Self::forcing_faces`]).
    pub fn throat_faces(&self, c: usize) -> &[ThroatFace] {
        &self.throats[c]
    }

    /// Sets the targets of the throats' faces of `components` for the stage ending at
    /// `time` ([`ThroatFace::target`]): the lubrication profile driven by `body_force` less
    /// the gradient of `pressure` (kinematic, the last projection's), relaxed toward it over
    /// the time since the component's last stage (`tau` at its first) at the loop gain
    /// ([`ThroatFace::RELAXED_GAIN`]); an empty `pressure` drives by the body force alone.
    pub fn set_throat_targets(
        &mut self,
        components: [bool; 3],
        pressure: &[f64],
        body_force: [f64; 3],
        tau: f64,
        time: f64,
    ) {
        let nu = self.throat_viscosity;
        for c in (0..3).filter(|&c| components[c]) {
            let last = std::mem::replace(&mut self.throat_clock[c], time);
            let span = if time > last { time - last } else { tau };
            let reach = ThroatFace::RELAXED_GAIN * span;
            let h = self.grid.h[c];
            let forcing = &self.forcing[c];
            for t in self.throats[c].iter_mut() {
                let f = &forcing[t.face as usize];
                let gradient = if pressure.is_empty() {
                    0.0
                } else {
                    (pressure[f.cells[1] as usize] - pressure[f.cells[0] as usize]) / h
                };
                t.target = t.relaxed(f.wall, body_force[c] - gradient, nu, reach);
            }
        }
    }

    /// What a bit-identical restart needs of the throats: the components' stage clocks,
    /// then per throat face `component, slot, target`.
    pub fn throat_state(&self) -> Vec<f64> {
        let mut out = self.throat_clock.to_vec();
        for c in 0..3 {
            for t in &self.throats[c] {
                let slot = self.forcing[c][t.face as usize].slot;
                out.extend([c as f64, f64::from(slot), t.target]);
            }
        }
        out
    }

    /// Checks the shape of a [`Self::throat_state`].
    pub fn check_throat_state(data: &[f64]) -> Result<(), String> {
        if data.len() < 3 || !(data.len() - 3).is_multiple_of(3) {
            return Err(format!(
                "expected 3 clocks and rows of 3 values, got {} values",
                data.len()
            ));
        }
        match data[3..]
            .chunks_exact(3)
            .position(|row| !(0.0..3.0).contains(&row[0]))
        {
            Some(k) => Err(format!("row {k} names component {}", data[3 + 3 * k])),
            None => Ok(()),
        }
    }

    /// Restores a [`Self::throat_state`] (checked) onto the throats of the current build,
    /// face by slot; faces it does not name keep theirs.
    pub fn restore_throat_state(&mut self, data: &[f64]) {
        self.throat_clock = [data[0], data[1], data[2]];
        for c in 0..3 {
            let saved = &mut self.carried[c];
            saved.clear();
            saved.extend(
                data[3..]
                    .chunks_exact(3)
                    .filter(|row| row[0] as usize == c)
                    .map(|row| (row[1] as u32, row[2])),
            );
            saved.sort_unstable_by_key(|&(slot, _)| slot);
            ThroatFace::take_targets(&mut self.throats[c], &self.forcing[c], saved);
        }
    }

    /// Chooses the forcing stencil: quadratic through the wall and two fluid faces
    /// (default), or linear through the wall and one; applies from the next update.
    pub fn set_quadratic(&mut self, quadratic: bool) {
        self.quadratic = quadratic;
    }

    /// Cells whose six faces are all forced, or that only such faces join to them (a
    /// driven throat's face is not forced: its flux answers the pressure).
    pub fn closed_cells(&self) -> &[ClosedCell] {
        &self.closed
    }

    /// Faces inside spheres, per component.
    pub fn interior_faces(&self, c: usize) -> &[InteriorFace] {
        &self.interior[c]
    }

    /// Forcing faces, per component.
    pub fn forcing_faces(&self, c: usize) -> &[ForcingFace] {
        &self.forcing[c]
    }

    /// Component `c`'s forcing faces in gaps (indices into [`Self::forcing_faces`]).
    pub fn gap_faces(&self, c: usize) -> &[GapFace] {
        &self.gaps[c]
    }

    /// Total number of forced faces (interior and forcing, all components).
    pub fn forced_count(&self) -> usize {
        (0..3)
            .map(|c| self.interior[c].len() + self.forcing[c].len())
            .sum()
    }

    /// Whether the face of component `c` at padded index `slot` lies inside a sphere.
    pub fn is_inside(&self, c: usize, slot: usize) -> bool {
        let l = self.labels[c][slot];
        l != FLUID && l != FORCING && l != THROAT
    }

    /// The spheres the forced faces were last built for ([`Self::update`]).
    pub fn built_spheres(&self) -> &[RigidSphere] {
        &self.built
    }

    /// Keeps the forced faces with `spheres`: rebuilt ([`Self::update`]) when the spheres
    /// are not those of the last build, or one of them has moved more than `skin` (m) from
    /// where it was built; else only refreshed ([`Self::refresh`]). Returns whether they
    /// were rebuilt.
    ///
    /// Between builds each sphere is thus imposed where it was built, with its current
    /// rigid motion: its true shape, up to `skin` behind, and its surface jumps to where it
    /// is at the next build. Like a neighbour list's skin in the DEM, the skin trades that
    /// lag for builds (the drag error per skin: docs/direct_model.md, "Between builds").
    pub fn follow(&mut self, spheres: &[RigidSphere], skin: f64) -> bool {
        let length = self.grid.length();
        let periodic = self.periodic;
        let moved_beyond = |a: &RigidSphere, b: &RigidSphere| {
            let mut d2 = 0.0;
            for d in 0..3 {
                let mut r = a.centre[d] - b.centre[d];
                if periodic[d] {
                    r = nearest_image(r, length[d]);
                }
                d2 += r * r;
            }
            a.radius != b.radius || d2 > skin * skin
        };
        let rebuild = self.built.len() != spheres.len()
            || spheres
                .iter()
                .zip(&self.built)
                .any(|(a, b)| moved_beyond(a, b));
        if rebuild {
            self.update(spheres);
        } else {
            self.refresh(spheres);
        }
        rebuild
    }

    /// Recomputes, for `spheres` (the spheres of the last [`Self::update`], in the same
    /// order, since moved), every forced face's rigid velocity from their current motion:
    /// an interior face's target at the face, a forcing face's wall velocity where its line
    /// crossed the surface at the build. Roles, lines and weights stay those of the build.
    /// Right after an update it changes nothing (the same arithmetic).
    pub fn refresh(&mut self, spheres: &[RigidSphere]) {
        assert_eq!(
            spheres.len(),
            self.built.len(),
            "a refresh keeps the spheres of the last build"
        );
        let length = self.grid.length();
        let built = &self.built;
        for c in 0..3 {
            let lattice = FaceLattice {
                grid: &self.grid,
                length,
                layout: &self.layout,
                periodic: self.periodic,
                range: self.ranges[c],
                c,
            };
            const CHUNK: usize = 4096;
            self.interior[c]
                .par_iter_mut()
                .with_min_len(CHUNK)
                .for_each(|f| {
                    f.target =
                        lattice.interior_target(f.slot as usize, &spheres[f.sphere as usize]);
                });
            self.forcing[c]
                .par_iter_mut()
                .with_min_len(CHUNK)
                .for_each(|f| {
                    let line = ForcingLine::unpack(f.line);
                    let x = lattice.slot_position(f.slot as usize);
                    let t = lattice.surface_distance(x, &built[line.sphere], line);
                    f.wall = lattice.wall_velocity(x, t, line, &spheres[line.sphere]);
                });
            // A far wall (a gap's or a throat's) at `distance` along the face's line, beyond it.
            let forcing = &self.forcing[c];
            let far_wall = |face: u32, sphere: u32, distance: f64| {
                let f = &forcing[face as usize];
                let line = ForcingLine::unpack(f.line);
                let far = ForcingLine {
                    sphere: sphere as usize,
                    d: line.d,
                    step: -line.step,
                };
                let x = lattice.slot_position(f.slot as usize);
                lattice.velocity_beyond(x, distance, far, &spheres[far.sphere])
            };
            for g in self.gaps[c].iter_mut() {
                g.wall = far_wall(g.face, g.sphere, g.distance);
            }
            for t in self.throats[c].iter_mut() {
                t.wall = far_wall(t.face, t.sphere, t.distance);
            }
        }
    }

    /// Rebuilds the forced faces for `spheres` (positions, sizes and velocities); the
    /// three components in parallel (each writes only its own lists), and within each the
    /// interior faces in parallel over the spheres and the forcing faces over the
    /// candidates, in an order that does not depend on the thread count.
    pub fn update(&mut self, spheres: &[RigidSphere]) {
        assert!(
            spheres.len() < ForcingLine::MAX_SPHERES,
            "a forcing line names at most 2²⁹ spheres"
        );
        self.built.clear();
        self.built.extend_from_slice(spheres);
        let quadratic = self.quadratic;
        let (grid, layout, periodic, ranges) =
            (&self.grid, &self.layout, self.periodic, &self.ranges);
        let [l0, l1, l2] = &mut self.labels;
        let [t0, t1, t2] = &mut self.touched;
        let [i0, i1, i2] = &mut self.interior;
        let [f0, f1, f2] = &mut self.forcing;
        let [g0, g1, g2] = &mut self.gaps;
        let [h0, h1, h2] = &mut self.throats;
        let [k0, k1, k2] = &mut self.carried;
        let [c0, c1, c2] = &mut self.candidates;
        let [s0, s1, s2] = &mut self.sites;
        let [o0, o1, o2] = &mut self.offsets;
        let length = grid.length();
        let lattice = |c: usize| FaceLattice {
            grid,
            length,
            layout,
            periodic,
            range: ranges[c],
            c,
        };
        let mut jobs = [
            ComponentUpdate {
                lattice: lattice(0),
                labels: l0,
                touched: t0,
                interior: i0,
                forcing: f0,
                gaps: g0,
                throats: h0,
                carried: k0,
                candidates: c0,
                sites: s0,
                offsets: o0,
            },
            ComponentUpdate {
                lattice: lattice(1),
                labels: l1,
                touched: t1,
                interior: i1,
                forcing: f1,
                gaps: g1,
                throats: h1,
                carried: k1,
                candidates: c1,
                sites: s1,
                offsets: o1,
            },
            ComponentUpdate {
                lattice: lattice(2),
                labels: l2,
                touched: t2,
                interior: i2,
                forcing: f2,
                gaps: g2,
                throats: h2,
                carried: k2,
                candidates: c2,
                sites: s2,
                offsets: o2,
            },
        ];
        let open_throats = self.throat_viscosity > 0.0;
        jobs.par_iter_mut()
            .for_each(|job| job.run(spheres, quadratic, open_throats));
        self.find_closed_cells();
    }

    /// Cells next to forced faces whose six faces are all forced. Their divergence is
    /// whatever the forcing imposes (the interpolated forcing faces do not conserve mass
    /// cell by cell): the imposition hands it to the projection as a mass source
    /// (Kim, Kim & Choi 2001), else the pressure would absorb the mismatch without end.
    fn find_closed_cells(&mut self) {
        self.previous_closed.clear();
        self.previous_closed
            .extend(self.closed.iter().map(|c| c.cell));
        self.closed.clear();
        // The cells next to forced faces ("near" cells).
        const NEAR: u8 = 1;
        const REACHED: u8 = 2;
        const CLOSED: u8 = 3;
        const GROUPED: u8 = 4;
        const POCKET: u8 = 5;
        let mut near = std::mem::take(&mut self.near_cells);
        near.clear();
        for c in 0..3 {
            let cells = self.interior[c]
                .iter()
                .map(|f| f.cells)
                .chain(self.forcing[c].iter().map(|f| f.cells));
            for pair in cells {
                for cell in pair {
                    self.cell_marks[cell as usize] = NEAR;
                }
            }
        }
        // In ascending order (the closed cells' order, hence the mass sources' sum, is
        // fixed): a scan of the marks is cheaper than sorting the lists.
        near.extend(
            self.cell_marks
                .iter()
                .enumerate()
                .filter(|(_, &m)| m != 0)
                .map(|(cell, _)| cell),
        );
        // Open near cells are reached from the open fluid through free faces (from the
        // seeds: near cells with a free face onto a cell that is not near); the open near
        // cells left unreached form pockets enclosed by forced faces: closed too.
        // Each near cell's class depends only on the forced faces and on which cells are
        // near, so the classes are found in parallel and applied in order.
        const OPEN: u8 = 0;
        const SEED: u8 = 1;
        const ALL_FORCED: u8 = 2;
        let mut classes = std::mem::take(&mut self.near_classes);
        classes.clear();
        classes.resize(near.len(), OPEN);
        let this = &*self;
        near.par_iter()
            .zip(classes.par_iter_mut())
            .for_each(|(&cell, class)| {
                let idx = this.cell_coords(cell);
                let Some(faces) = this.cell_faces_at(idx) else {
                    *class = SEED;
                    return;
                };
                let mut all_forced = true;
                let mut seed = false;
                for c in 0..3 {
                    for side in 0..2 {
                        if this.forced(c, faces[c][side]) {
                            continue;
                        }
                        all_forced = false;
                        match this.neighbour_cell_at(cell, idx, c, side) {
                            Some(next) if this.cell_marks[next] != 0 => {}
                            _ => seed = true,
                        }
                    }
                }
                *class = if all_forced {
                    ALL_FORCED
                } else if seed {
                    SEED
                } else {
                    OPEN
                };
            });
        for (&cell, &class) in near.iter().zip(&classes) {
            match class {
                ALL_FORCED => {
                    self.cell_marks[cell] = CLOSED;
                    let faces = self.cell_faces(cell).expect("a cell with six faces");
                    self.closed.push(ClosedCell { cell, faces });
                }
                SEED => self.cell_marks[cell] = REACHED,
                _ => {}
            }
        }
        // The open near cells left (few: most near cells are seeds), by connected groups
        // through free faces: a group is reached if one of its cells has a free face onto a
        // seed that the search from the seeds would go on from (one with six faces), else
        // it is a pocket. The free faces join cells both ways, so this marks what a search
        // from every seed would, at the cost of the open cells only.
        let mut stack = std::mem::take(&mut self.queue);
        let mut group = std::mem::take(&mut self.group);
        for (&start, &class) in near.iter().zip(&classes) {
            if class != OPEN || self.cell_marks[start] != NEAR {
                continue;
            }
            stack.clear();
            group.clear();
            stack.push(start);
            self.cell_marks[start] = GROUPED;
            let mut reached = false;
            while let Some(cell) = stack.pop() {
                group.push(cell);
                let idx = self.cell_coords(cell);
                let faces = self.cell_faces_at(idx).expect("an open cell has six faces");
                for c in 0..3 {
                    for side in 0..2 {
                        if self.forced(c, faces[c][side]) {
                            continue;
                        }
                        let Some(next) = self.neighbour_cell_at(cell, idx, c, side) else {
                            continue;
                        };
                        match self.cell_marks[next] {
                            NEAR => {
                                self.cell_marks[next] = GROUPED;
                                stack.push(next);
                            }
                            REACHED if !reached => reached = self.cell_faces(next).is_some(),
                            _ => {}
                        }
                    }
                }
            }
            let mark = if reached { REACHED } else { POCKET };
            for &cell in &group {
                self.cell_marks[cell] = mark;
            }
        }
        self.near_classes = classes;
        self.queue = stack;
        self.group = group;
        for &cell in &near {
            if self.cell_marks[cell] == POCKET {
                if let Some(faces) = self.cell_faces(cell) {
                    self.closed.push(ClosedCell { cell, faces });
                }
            }
            self.cell_marks[cell] = 0;
        }
        self.near_cells = near;
    }

    /// The seven-point Laplacian of the cell-centred `p` at a cell with six faces (the
    /// projection's: its face gradients are those of the pressure compensation).
    fn cell_laplacian(&self, p: &[f64], cell: usize) -> f64 {
        let idx = self.cell_coords(cell);
        (0..3)
            .map(|c| {
                let [low, high] = [0, 1].map(|side| {
                    let next = self
                        .neighbour_cell_at(cell, idx, c, side)
                        .expect("a cell with six faces has six neighbours");
                    p[next]
                });
                (high - 2.0 * p[cell] + low) / (self.grid.h[c] * self.grid.h[c])
            })
            .sum()
    }

    /// Whether the face's value is fixed by the forcing (a throat's answers the pressure).
    fn forced(&self, c: usize, slot: usize) -> bool {
        let l = self.labels[c][slot];
        l != FLUID && l != THROAT
    }

    /// Grid indices `(i, j, k)` of an unpadded cell index (the one division per cell of the
    /// closed-cell search; the faces and neighbours follow by strides).
    #[inline]
    fn cell_coords(&self, cell: usize) -> [usize; 3] {
        let n = self.grid.n;
        let column = cell / n[0];
        [cell - column * n[0], column % n[1], column / n[1]]
    }

    /// The six face slots of a cell, if the fluid advances them all (periodic wraps
    /// resolved); `None` next to a bounded face.
    fn cell_faces(&self, cell: usize) -> Option<[[usize; 2]; 3]> {
        self.cell_faces_at(self.cell_coords(cell))
    }

    fn cell_faces_at(&self, idx: [usize; 3]) -> Option<[[usize; 2]; 3]> {
        let n = self.grid.n;
        let l = &self.layout;
        let low = l.index(idx[0] + 1, idx[1] + 1, idx[2] + 1);
        let mut faces = [[0usize; 2]; 3];
        for c in 0..3 {
            let (lo, hi) = self.ranges[c][c];
            if idx[c] + 1 < lo || idx[c] + 2 > hi + usize::from(self.periodic[c]) {
                return None;
            }
            let high = if idx[c] + 1 < n[c] {
                low + l.stride[c]
            } else {
                low - (n[c] - 1) * l.stride[c]
            };
            faces[c] = [low, high];
        }
        Some(faces)
    }

    /// The cell across face `side` (0 low, 1 high) along `c` of cell `cell` at grid indices
    /// `idx`, if inside the box or wrapped.
    #[inline]
    fn neighbour_cell_at(
        &self,
        cell: usize,
        idx: [usize; 3],
        c: usize,
        side: usize,
    ) -> Option<usize> {
        let n = self.grid.n;
        let stride = [1, n[0], n[0] * n[1]][c];
        if side == 0 {
            if idx[c] == 0 {
                self.periodic[c].then(|| cell + (n[c] - 1) * stride)
            } else {
                Some(cell - stride)
            }
        } else if idx[c] + 1 == n[c] {
            self.periodic[c].then(|| cell - (n[c] - 1) * stride)
        } else {
            Some(cell + stride)
        }
    }

    /// Imposes the rigid motion on a stage's predicted velocity (padded), so that after the
    /// coming projection `u ← u − τ∇p` the forced faces hold their targets (exactly when the
    /// pressure `p` the hook sees is the one the projection subtracts; see the module docs).
    /// `tau = 0` or an empty `pressure` imposes the targets as they are. Only the `components`
    /// named are imposed. With a `mass_source`, every [`ClosedCell`] then gets the divergence
    /// of the velocity plus `τ∇²` of the `incremental_pressure` (empty: none; see
    /// [`PredictedVelocity`](crate::fluid::PredictedVelocity)), less their mean so that the
    /// sources sum to zero; the other cells get zero.
    pub fn impose(
        &mut self,
        velocity: &mut [Vec<f64>; 3],
        components: [bool; 3],
        pressure: &[f64],
        tau: f64,
        mass_source: Option<&mut [f64]>,
        incremental_pressure: &[f64],
    ) {
        // A component's faces in chunks, in parallel (the stages of `EulerRKC` hand one
        // component at a time). SAFETY of the shared component: each forced face is written
        // by one worker only (a slot has one role: the labels of the build), and what a
        // forcing face reads are fluid faces, which no worker writes (or, for the staircase
        // fallback, its own slot); so the chunks may run in any order and give one result.
        const CHUNK: usize = 4096;
        for (c, u) in velocity.iter_mut().enumerate() {
            if !components[c] {
                continue;
            }
            let u = SharedSamples::of(u);
            let scale = tau / self.grid.h[c];
            let correction = |cells: [u32; 2]| {
                if tau == 0.0 || pressure.is_empty() {
                    0.0
                } else {
                    scale * (pressure[cells[1] as usize] - pressure[cells[0] as usize])
                }
            };
            self.interior[c].par_chunks(CHUNK).for_each(|chunk| {
                for f in chunk {
                    u.write(f.slot as usize, f.target + correction(f.cells));
                }
            });
            self.forcing[c].par_chunks(CHUNK).for_each(|chunk| {
                for f in chunk {
                    let mut value = f.wall + correction(f.cells);
                    for k in 0..2 {
                        let outer =
                            u.read(f.neighbours[k] as usize) - correction(f.neighbour_cells[k]);
                        value += f.weights[k] * (outer - f.wall);
                    }
                    u.write(f.slot as usize, value);
                }
            });
            // The far walls of the faces in gaps, after their stencils (they read no forced
            // face, so the order does not matter).
            for g in &self.gaps[c] {
                let f = &self.forcing[c][g.face as usize];
                let slot = f.slot as usize;
                u.write(slot, u.read(slot) + g.weight * (g.wall - f.wall));
            }
            // The throats' faces, at the targets of this stage (they read no face); the
            // walls' line where no stage has set one.
            for t in &self.throats[c] {
                let f = &self.forcing[c][t.face as usize];
                let target = if t.target.is_nan() {
                    t.relaxed(f.wall, 0.0, 0.0, 0.0)
                } else {
                    t.target
                };
                u.write(f.slot as usize, target + correction(f.cells));
            }
        }
        if let Some(q) = mass_source {
            // In parallel: the cells are distinct (SAFETY of the shared source: one worker
            // writes each), and the total is summed in list order.
            const CELLS: usize = 2048;
            let q = SharedSamples::of(q);
            self.previous_closed
                .par_iter()
                .with_min_len(CELLS)
                .for_each(|&cell| q.write(cell, 0.0));
            let velocity = &*velocity;
            let mut sources = std::mem::take(&mut self.closed_sources);
            sources.clear();
            let this = &*self;
            sources.par_extend(this.closed.par_iter().with_min_len(CELLS).map(|cc| {
                let divergence = closed_divergence(&this.grid, velocity, cc);
                if incremental_pressure.is_empty() {
                    divergence
                } else {
                    divergence + tau * this.cell_laplacian(incremental_pressure, cc.cell)
                }
            }));
            let total = sources.iter().fold(0.0, |t, d| t + d);
            let mean = total / this.closed.len().max(1) as f64;
            this.closed
                .par_iter()
                .zip(&sources)
                .with_min_len(CELLS)
                .for_each(|(cc, source)| q.write(cc.cell, source - mean));
            self.closed_sources = sources;
        }
    }
}

/// Discrete divergence of `velocity` in a closed cell.
fn closed_divergence(grid: &Grid, velocity: &[Vec<f64>; 3], cell: &ClosedCell) -> f64 {
    (0..3)
        .map(|c| (velocity[c][cell.faces[c][1]] - velocity[c][cell.faces[c][0]]) / grid.h[c])
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coupling::direct::component_update::visit_inside;
    use crate::Vec3;

    fn periodic_boundary(n: usize, h: f64) -> ImmersedBoundary {
        let grid = Grid::new([n; 3], [h; 3], [0.0; 3]);
        ImmersedBoundary::new(&grid, &BoundaryConditions::periodic())
    }

    #[test]
    fn interior_faces_fill_the_sphere_volume_and_forcing_faces_surround_it() {
        let h = 0.1;
        let mut ib = periodic_boundary(24, h);
        let mut sphere = RigidSphere::fixed([1.2, 1.23, 1.17], 0.61);
        sphere.velocity = Vec3::new(0.3, 0.0, 0.0);
        sphere.angular_velocity = Vec3::new(0.0, 0.0, 1.0);
        ib.update(&[sphere]);
        for c in 0..3 {
            // Samples inside ≈ volume / h³ (staircase error of the count ~ area/h²).
            let count = ib.interior_faces(c).len() as f64;
            let expected = sphere.volume() / (h * h * h);
            assert!(
                (count / expected - 1.0).abs() < 0.03,
                "{count} vs {expected}"
            );
            for f in ib.forcing_faces(c) {
                assert!(f.weights[0] >= 0.0 && f.weights[0] <= 1.0);
                assert!(f.weights[1] <= 0.0 && f.weights[1] >= -1.0 / 3.0);
                assert!(
                    !ib.is_inside(c, f.neighbours[0] as usize)
                        && !ib.is_inside(c, f.neighbours[1] as usize)
                );
            }
            assert!(!ib.forcing_faces(c).is_empty());
        }
        // The rigid velocity of an interior x face: 0.3 − ω (y − y_p).
        let f = ib.interior_faces(0)[0];
        assert!(f.target.abs() < 0.3 + 0.61 + 1e-12);
    }

    #[test]
    fn a_sphere_across_the_periodic_boundary_is_found_whole() {
        let h = 0.1;
        let mut a = periodic_boundary(20, h);
        let mut b = periodic_boundary(20, h);
        a.update(&[RigidSphere::fixed([1.03, 1.07, 0.98], 0.45)]);
        // The same sphere shifted by a whole number of cells, straddling the corner.
        b.update(&[RigidSphere::fixed([0.03, 0.07, 1.98], 0.45)]);
        for c in 0..3 {
            assert_eq!(a.interior_faces(c).len(), b.interior_faces(c).len());
            assert_eq!(a.forcing_faces(c).len(), b.forcing_faces(c).len());
        }
    }

    /// Spheres at seeded random positions (some across the periodic boundary) with seeded
    /// random rigid motions.
    fn random_spheres(count: usize, length: f64, radius: f64, seed: u64) -> Vec<RigidSphere> {
        let mut rng = crate::particles::SplitMix64::new(seed);
        let mut spheres: Vec<RigidSphere> = Vec::new();
        while spheres.len() < count {
            let centre = [0; 3].map(|_| rng.next_f64() * length);
            let far = spheres.iter().all(|s| {
                let d2: f64 = (0..3)
                    .map(|d| {
                        let r = s.centre[d] - centre[d];
                        let r = r - length * (r / length).round();
                        r * r
                    })
                    .sum();
                d2.sqrt() > 2.0 * radius + 0.25
            });
            if far {
                let mut s = RigidSphere::fixed(centre, radius);
                s.velocity = Vec3::from([0; 3].map(|_| rng.next_f64() - 0.5));
                s.angular_velocity = Vec3::from([0; 3].map(|_| 4.0 * rng.next_f64() - 2.0));
                spheres.push(s);
            }
        }
        spheres
    }

    /// Spheres at seeded random positions that may overlap one another.
    fn overlapping_spheres(count: usize, length: f64, radius: f64, seed: u64) -> Vec<RigidSphere> {
        let mut rng = crate::particles::SplitMix64::new(seed);
        (0..count)
            .map(|_| {
                let centre = [0; 3].map(|_| rng.next_f64() * length);
                let mut s = RigidSphere::fixed(centre, radius * (0.8 + 0.4 * rng.next_f64()));
                s.velocity = Vec3::from([0; 3].map(|_| rng.next_f64() - 0.5));
                s
            })
            .collect()
    }

    /// The interior faces found in parallel are those of the spheres one after another, a
    /// face shared by overlapping spheres going to the first: the same faces, spheres and
    /// order.
    #[test]
    fn interior_faces_go_to_the_first_sphere_that_holds_them() {
        let (n, h) = (18, 0.1);
        let mut ib = periodic_boundary(n, h);
        let spheres = overlapping_spheres(60, n as f64 * h, 0.3, 5);
        ib.update(&spheres);
        let length = ib.grid.length();
        let mut shared = 0;
        for c in 0..3 {
            let lat = FaceLattice {
                grid: &ib.grid,
                length,
                layout: &ib.layout,
                periodic: ib.periodic,
                range: ib.ranges[c],
                c,
            };
            let mut seen = std::collections::HashSet::new();
            let mut expected = Vec::new();
            for (k, s) in spheres.iter().enumerate() {
                visit_inside(&lat, s, |_, site| {
                    let slot = ib.layout.index(site[0], site[1], site[2]) as u32;
                    if seen.insert(slot) {
                        expected.push((slot, k as u32));
                    } else {
                        shared += 1;
                    }
                });
            }
            let found: Vec<(u32, u32)> = ib
                .interior_faces(c)
                .iter()
                .map(|f| (f.slot, f.sphere))
                .collect();
            assert_eq!(found, expected, "component {c}");
            assert_eq!(ib.sites[c].len(), expected.len());
        }
        assert!(shared > 100, "the spheres overlap ({shared} faces shared)");
    }

    /// The closed cells are the cells next to forced faces that no path of free faces joins
    /// to a cell with no forced face (six forced faces, or a pocket): a plain search over
    /// the whole grid agrees, on overlapping spheres that leave pockets between them, with
    /// the throats' faces held (forced) and driven (free: fewer closed cells).
    #[test]
    fn closed_cells_are_those_no_free_path_reaches() {
        let (n, h) = (16, 0.1);
        let mut ib = periodic_boundary(n, h);
        let cells = n * n * n;
        let mut pockets = 0;
        let mut closed = [0; 2];
        for (seed, driven) in (0..4).flat_map(|seed| [(seed, false), (seed, true)]) {
            ib.set_throat_viscosity(if driven { 1e-3 } else { 0.0 });
            ib.update(&overlapping_spheres(40, n as f64 * h, 0.22, 100 + seed));
            closed[usize::from(driven)] += ib.closed_cells().len();
            let faces: Vec<[[usize; 2]; 3]> = (0..cells)
                .map(|cell| ib.cell_faces(cell).unwrap())
                .collect();
            let near =
                |cell: usize| (0..3).any(|c| faces[cell][c].iter().any(|&slot| ib.forced(c, slot)));
            let mut reached: Vec<bool> = (0..cells).map(|cell| !near(cell)).collect();
            let mut stack: Vec<usize> = (0..cells).filter(|&cell| reached[cell]).collect();
            while let Some(cell) = stack.pop() {
                let idx = ib.cell_coords(cell);
                for c in 0..3 {
                    for side in 0..2 {
                        if ib.forced(c, faces[cell][c][side]) {
                            continue;
                        }
                        let next = ib.neighbour_cell_at(cell, idx, c, side).unwrap();
                        if !reached[next] {
                            reached[next] = true;
                            stack.push(next);
                        }
                    }
                }
            }
            let mut expected: Vec<usize> = (0..cells).filter(|&cell| !reached[cell]).collect();
            let mut found: Vec<usize> = ib.closed_cells().iter().map(|cc| cc.cell).collect();
            assert!(found.iter().all(|&cell| ib
                .closed_cells()
                .iter()
                .any(|cc| cc.cell == cell && cc.faces == faces[cell])));
            found.sort_unstable();
            expected.sort_unstable();
            assert_eq!(found, expected, "seed {seed}");
            pockets += found
                .iter()
                .filter(|&&cell| (0..3).any(|c| faces[cell][c].iter().any(|&s| !ib.forced(c, s))))
                .count();
        }
        assert!(pockets > 0, "the configurations hold pockets");
        assert!(
            closed[1] < closed[0],
            "driven throats open cells: {closed:?}"
        );
    }

    fn lists(ib: &ImmersedBoundary) -> Vec<(Vec<InteriorFace>, Vec<ForcingFace>)> {
        (0..3)
            .map(|c| (ib.interior_faces(c).to_vec(), ib.forcing_faces(c).to_vec()))
            .collect()
    }

    #[test]
    fn a_refresh_right_after_a_build_changes_nothing() {
        let mut ib = periodic_boundary(24, 0.1);
        let spheres = random_spheres(5, 2.4, 0.35, 11);
        ib.update(&spheres);
        let built = lists(&ib);
        ib.refresh(&spheres);
        assert!(lists(&ib) == built, "a refresh at the build changed a face");
        assert!(!ib.follow(&spheres, 0.0), "unmoved spheres need no build");
        assert!(lists(&ib) == built);
    }

    #[test]
    fn between_builds_the_faces_keep_their_geometry_and_take_the_current_motion() {
        let h = 0.1;
        let mut ib = periodic_boundary(24, h);
        let mut spheres = random_spheres(5, 2.4, 0.35, 12);
        ib.update(&spheres);
        let built = lists(&ib);
        // a move within the skin, and new rigid motions
        for (k, s) in spheres.iter_mut().enumerate() {
            s.centre[k % 3] += 0.04 * h;
            s.velocity = Vec3::new(0.3, -0.2, 0.1 * k as f64);
            s.angular_velocity = Vec3::new(1.0, 0.5, -2.0);
        }
        assert!(!ib.follow(&spheres, 0.05 * h));
        let grid = Grid::new([24; 3], [h; 3], [0.0; 3]);
        for c in 0..3 {
            let (interior, forcing) = &built[c];
            assert_eq!(ib.interior_faces(c).len(), interior.len());
            assert_eq!(ib.forcing_faces(c).len(), forcing.len());
            for (now, then) in ib.interior_faces(c).iter().zip(interior) {
                assert_eq!(
                    (now.slot, now.cells, now.sphere),
                    (then.slot, then.cells, then.sphere)
                );
                // the rigid velocity of the moved sphere at the face
                let s = &spheres[now.sphere as usize];
                let x = face_position(&PaddedLayout::new([24; 3]), &grid, c, now.slot);
                let rel: [f64; 3] = std::array::from_fn(|d| {
                    let r = x[d] - s.centre[d];
                    r - 2.4 * (r / 2.4).round()
                });
                assert!((now.target - s.velocity_at(Vec3::from(rel))[c]).abs() < 1e-12);
            }
            for (now, then) in ib.forcing_faces(c).iter().zip(forcing) {
                assert_eq!(now.weights, then.weights);
                assert_eq!(
                    (now.slot, now.neighbours, now.line),
                    (then.slot, then.neighbours, then.line)
                );
                assert!(now.wall != then.wall || now.weights == [0.0; 2]);
            }
        }
        // one sphere beyond the skin: a build, at the spheres' new positions
        spheres[2].centre[1] += 0.04 * h;
        assert!(ib.follow(&spheres, 0.05 * h));
        assert_eq!(ib.built_spheres(), &spheres[..]);
    }

    #[test]
    fn impose_sets_targets_and_interpolates() {
        let h = 0.1;
        let mut ib = periodic_boundary(16, h);
        let mut sphere = RigidSphere::fixed([0.8, 0.8, 0.8], 0.33);
        sphere.velocity = Vec3::new(1.0, -2.0, 0.5);
        ib.update(&[sphere]);
        let layout = PaddedLayout::new([16; 3]);
        let mut u: [Vec<f64>; 3] = std::array::from_fn(|_| vec![7.0; layout.len]);
        let p = vec![0.0; 16 * 16 * 16];
        ib.impose(&mut u, [true; 3], &p, 0.0, None, &[]);
        for c in 0..3 {
            let w = sphere.velocity[c];
            for f in ib.interior_faces(c) {
                assert_eq!(u[c][f.slot as usize], w);
            }
            for f in ib.forcing_faces(c) {
                let expected = w + (f.weights[0] + f.weights[1]) * (7.0 - w);
                assert!((u[c][f.slot as usize] - expected).abs() < 1e-12);
            }
        }
        // A uniform pressure gradient is pre-compensated: +τ ∂p/∂x_c.
        let grid = Grid::new([16; 3], [h; 3], [0.0; 3]);
        let p: Vec<f64> = (0..grid.cell_count())
            .map(|i| (i % 16) as f64 * 0.5)
            .collect();
        ib.impose(&mut u, [true; 3], &p, 0.2, None, &[]);
        let f = ib
            .interior_faces(0)
            .iter()
            .find(|f| f.slot % 18 > 2)
            .unwrap();
        assert!((u[0][f.slot as usize] - (1.0 + 0.2 * 0.5 / h)).abs() < 1e-12);
    }

    /// Position of the component-`c` face at padded slot `slot`, computed afresh.
    fn face_position(layout: &PaddedLayout, grid: &Grid, c: usize, slot: u32) -> [f64; 3] {
        let slot = slot as usize;
        let padded = [
            slot % layout.dims[0],
            (slot / layout.dims[0]) % layout.dims[1],
            slot / layout.plane_len(),
        ];
        std::array::from_fn(|d| {
            let offset = if d == c { 0.0 } else { 0.5 };
            grid.origin[d] + (padded[d] as f64 - 1.0 + offset) * grid.h[d]
        })
    }

    /// Distance from `x` along `step e_d` to where the line enters `sphere` (box `length`).
    fn entry(x: [f64; 3], sphere: &RigidSphere, d: usize, step: f64, length: f64) -> f64 {
        let rel: [f64; 3] = std::array::from_fn(|k| {
            let r = x[k] - sphere.centre[k];
            r - length * (r / length).round()
        });
        let b = step * rel[d];
        let q = rel.iter().map(|r| r * r).sum::<f64>() - sphere.radius * sphere.radius;
        -b - (b * b - q).sqrt()
    }

    #[test]
    fn a_face_in_a_gap_takes_the_quadratic_through_both_walls() {
        // Two spheres facing each other along x across a gap of 2.6 cells: one spinning, the
        // other translating and spinning. The fluid is at rest, so a face in the gap gets only
        // the walls' share of the quadratic through its own wall (−δ), its fluid face (h) and
        // the far wall (s).
        let (h, n) = (0.1, 32);
        let length = n as f64 * h;
        let mut ib = periodic_boundary(n, h);
        let grid = Grid::new([n; 3], [h; 3], [0.0; 3]);
        let mut a = RigidSphere::fixed([1.013, 1.621, 1.583], 0.6);
        a.angular_velocity = Vec3::new(0.5, -1.0, 0.8);
        let mut b = RigidSphere::fixed([1.013 + 1.2 + 0.26, 1.607, 1.594], 0.6);
        b.velocity = Vec3::new(0.4, 1.5, -0.5);
        b.angular_velocity = Vec3::new(-2.0, 0.3, 1.1);
        ib.update(&[a, b]);
        let built: Vec<Vec<GapFace>> = (0..3).map(|c| ib.gap_faces(c).to_vec()).collect();
        ib.refresh(&[a, b]);
        assert!(
            (0..3).all(|c| ib.gap_faces(c) == &built[c][..]),
            "a refresh at the build"
        );
        let layout = PaddedLayout::new([n; 3]);
        let p = vec![0.0; n * n * n];
        for _ in 0..2 {
            let spheres = [a, b];
            let mut u: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; layout.len]);
            ib.impose(&mut u, [true; 3], &p, 0.0, None, &[]);
            let mut checked = 0;
            for c in 0..3 {
                for g in ib.gap_faces(c) {
                    let f = &ib.forcing_faces(c)[g.face as usize];
                    let line = ForcingLine::unpack(f.line);
                    let slot = f.slot as usize;
                    let x = face_position(&layout, &grid, c, f.slot);
                    let (own, far) = (&spheres[line.sphere], &spheres[g.sphere as usize]);
                    let step = line.step as f64;
                    let delta = entry(x, own, line.d, step, length);
                    let s = entry(x, far, line.d, -step, length);
                    assert!(
                        delta <= h && s > 2.0 * h - 1e-12 && s <= 3.0 * h,
                        "{delta} {s}"
                    );
                    let own_weight = h * s / ((h + delta) * (s + delta));
                    let far_weight = -delta * h / ((s + delta) * (s - h));
                    // The walls' rigid velocities where the line crosses them.
                    let wall = |sphere: &RigidSphere, along: f64| {
                        let rel: [f64; 3] = std::array::from_fn(|k| {
                            let point = x[k] + if k == line.d { along } else { 0.0 };
                            let r = point - sphere.centre[k];
                            r - length * (r / length).round()
                        });
                        sphere.velocity_at(Vec3::from(rel))[c]
                    };
                    let expected =
                        own_weight * wall(own, step * delta) + far_weight * wall(far, -step * s);
                    assert!(
                        (u[c][slot] - expected).abs() < 1e-12,
                        "{} {expected}",
                        u[c][slot]
                    );
                    checked += 1;
                }
            }
            assert!(checked > 20, "{checked} faces in the gap");
            // Between builds the far wall takes the far sphere's current motion.
            b.velocity = Vec3::new(-0.3, 0.7, 2.0);
            ib.refresh(&[a, b]);
        }
    }

    #[test]
    fn a_throat_keeps_its_target_through_a_rebuild_and_moves_its_walls_between() {
        // Two spheres along x across a gap of 1.3 cells: faces between them have no fluid face
        // before the far wall.
        let (h, n) = (0.1, 32);
        let mut ib = periodic_boundary(n, h);
        ib.set_throat_viscosity(1e-2);
        let a = RigidSphere::fixed([1.013, 1.621, 1.583], 0.6);
        let mut b = RigidSphere::fixed([1.013 + 1.2 + 0.13, 1.607, 1.594], 0.6);
        b.velocity = Vec3::new(0.0, 0.7, 0.0);
        ib.update(&[a, b]);
        let count: usize = (0..3).map(|c| ib.throat_faces(c).len()).sum();
        assert!(count > 20, "{count} throat faces");
        // Imposed before any stage has set their targets, they take the walls' line.
        let layout = PaddedLayout::new([n; 3]);
        let mut u: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; layout.len]);
        ib.impose(&mut u, [true; 3], &[], 0.0, None, &[]);
        for c in 0..3 {
            for t in ib.throat_faces(c) {
                let f = &ib.forcing_faces(c)[t.face as usize];
                let line = f.wall + t.share * (t.wall - f.wall);
                assert_eq!(u[c][f.slot as usize], line);
            }
        }
        // Targets for a pressure rising along y and z and a body force along y.
        let mut p = vec![0.0; n * n * n];
        for (cell, v) in p.iter_mut().enumerate() {
            *v = 0.3 * ((cell / n) % n) as f64 * h + 0.1 * (cell / (n * n)) as f64 * h;
        }
        ib.set_throat_targets([true; 3], &p, [0.0, 2.0, 0.0], 1e-3, 1e-3);
        let slots = |ib: &ImmersedBoundary, c: usize| -> Vec<(u32, f64)> {
            let f = ib.forcing_faces(c);
            ib.throat_faces(c)
                .iter()
                .map(|t| (f[t.face as usize].slot, t.target))
                .collect()
        };
        let before: Vec<_> = (0..3).map(|c| slots(&ib, c)).collect();
        assert!(before.iter().flatten().all(|&(_, t)| t.is_finite()));
        // y-faces move with the far sphere's 0.7 on their walls' line, and the drive adds
        // to it: some y-target above the own wall's 0.
        assert!(before[1].iter().any(|&(_, t)| t > 0.01));
        ib.update(&[a, b]);
        assert_eq!((0..3).map(|c| slots(&ib, c)).collect::<Vec<_>>(), before);
        // Between builds the far wall follows its sphere; the targets stay until the next
        // stage sets them.
        b.velocity = Vec3::new(0.0, 0.0, 0.0);
        ib.refresh(&[a, b]);
        assert!(ib.throat_faces(1).iter().all(|t| t.wall == 0.0));
        assert_eq!((0..3).map(|c| slots(&ib, c)).collect::<Vec<_>>(), before);
        // The restart state: onto a fresh build (targets NaN), the targets come back by slot
        // and the clocks with them.
        let state = ib.throat_state();
        assert_eq!(state.len(), 3 + 3 * count);
        assert_eq!(ImmersedBoundary::check_throat_state(&state), Ok(()));
        let mut fresh = periodic_boundary(n, h);
        fresh.update(&[a, b]);
        assert!(fresh.throat_faces(0).iter().all(|t| t.target.is_nan()));
        fresh.restore_throat_state(&state);
        assert_eq!((0..3).map(|c| slots(&fresh, c)).collect::<Vec<_>>(), before);
        assert_eq!(fresh.throat_state(), state);
        assert!(ImmersedBoundary::check_throat_state(&state[..4]).is_err());
        let mut wrong = state.clone();
        wrong[3] = 3.0;
        let e = ImmersedBoundary::check_throat_state(&wrong).unwrap_err();
        assert!(e.contains("component 3"), "{e}");
    }
}
