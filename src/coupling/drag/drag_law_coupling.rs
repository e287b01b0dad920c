//! The drag-law model's step (paper §2.2), in DPMFoam's order:
//!
//! ```text
//! particle forces   fluid velocity, ε and ∇p read at each particle (paper eq. 14–15);
//!                   drag from the closure (paper eq. 11–12), pressure-gradient force
//!                   (paper eq. 10); the reaction −f_d spread back to the faces
//!                   (paper eq. 13, 16)
//! evolve the cloud  DEM sub-steps with those forces held (the caller)
//! update ε          particle volumes spread to the cells; ε ≥ 1 − alphaMax or the run stops
//! fluid             momentum predictor with the source, variable-coefficient pressure
//!                   correction (VolumeAveragedFluid)
//! ```
//!
//! Forces on one particle of mass `m`, volume `V`, with the fluid's `ρ`, the fluid's gravity
//! `g_f` and the cloud's `g` (the DEM applies `m (1 − ρ/ρ_p) g` itself):
//! - paper's form: `f_h = f_d − V ρ (∇p − g_f)`, which with the DEM's buoyant weight is
//!   paper eq. 10 plus `m g` (`p` includes the fluid's weight, so `−Vρ∇p` holds the buoyancy);
//! - DPMFoam's form: `f_h = f_d` (its `gravity` force carries the buoyancy).
//!
//! In a box periodic on all six faces with gravity, the pressure is periodic and cannot carry
//! the mixture's weight; [`DragLawCoupling::carry_mixture_weight`] (called by case runs)
//! imposes the uniform kinematic gradient `G = (ρ_mix/ρ_f) g` that does, with
//! `ρ_mix = (ρ_f (V_box − V_s) + Σ m)/V_box`. The fluid's body
//! acceleration becomes `c (g − G)`, and in the paper's form each particle also feels the mean
//! part of its pressure-gradient force (paper eq. 10), `−V ρ_f G`. Then the external forces on
//! fluid and particles sum to zero in both forms: DPMFoam's `ρ_f V_box (g − G) + Σ (m − ρ_f V) g`,
//! the paper's `ρ_f (V_box − V_s)(g − G) + Σ m g − ρ_f V_s G`, both `(M_f + M_p) g − ρ_f V_box G`.
//!
//! The drag `f_d = β (u − v)` is integrated as OpenFOAM's `Euler` scheme for `U` does: implicit
//! in the particle's velocity over the fluid step, with `F` the other forces held:
//! `f_d = (β (u − vⁿ) − x F)/(1 + x)`, `x = Δt β / m` (`analytical`: the factor `1/(1 + x)`
//! becomes `(1 − e^−x)/x`). That is exactly `β (u − vⁿ⁺¹)` for the particle's implicit Euler
//! velocity, stable for any `Δt`, and its steady state is the root of `β (u − v) + F = 0`.
//! Unlike DPMFoam, `F` includes the particle's last contact force besides
//! `m(1 − ρ/ρ_p) g + f_p`: for a particle resting on others (`F ≈ 0`) DPMFoam's rule adds
//! `x` times the particle's weight to its drag per integration step, fsim's does not; for a
//! free particle the two are the same. DPMFoam integrates in several such steps per fluid
//! step (its collision sub-cycles' moves, cut into `maxCo` segments), fsim in one: the two
//! part by about `x²` (README, drag-law model). The fluid gets exactly `−f_d` (momentum
//! conservation), plus with the semi-implicit source `K (uⁿ − uⁿ⁺¹)` with `K = Σ w β /(ρ V_cell)`
//! (OpenFOAM's `SU − Sp(UCoeff) U` treatment), which vanishes in a steady state.
//!
//! DPMFoam's explicit coupled forces `F_e` ([`super::FluidForces`]: pressure gradient,
//! virtual mass, lift) join `F` in that balance and, negated, the fluid's source beside `−f_d`
//! (DPMFoam's `dUTrans`). With `virtualMass` the fluid-step forces move the particle through
//! `massEff = m (1 + Cvm ρ/ρ_p)`: `x = Δt β / massEff`, and the DEM gets the load
//! `(f_d + F_e + m_b g)/(1 + r) − m_b g` (`m_b g` the buoyant weight it adds itself), while its
//! contact forces still divide by `m`, as DPMFoam's `CollidingParcel` does; `F` carries the
//! contact force times `1 + r` accordingly.

use super::cell_point_interpolation::CellPointInterpolation;
use super::chunked_scatter::{ChunkedScatter, PARTICLES_PER_CHUNK};
use super::drag_closure::{Convention, DragInput};
use super::drag_law_settings::DragLawSettings;
use super::grid_transfer::{GridTransfer, SampleStencil};
use crate::fluid::{FluidSolver, VolumeAveragedFluid, VolumeAveragedForm, VolumeAveragedReport};
use crate::particles::{Dem, ParticleState};
use crate::Vec3;
use rayon::prelude::*;
use std::f64::consts::PI;

/// The momentum the particles and the fluid exchanged in one step, and the bed's state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ExchangeReport {
    /// `Σ (f_d + F_e)` over the particles (drag and DPMFoam's explicit coupled forces), N.
    pub drag_on_particles: Vec3,
    /// `ρ V_cell Σ_faces s`, the explicit reaction the fluid received, N.
    pub drag_on_fluid: Vec3,
    /// `Σ f_h` (drag, pressure-gradient force of either form, virtual mass and lift), N.
    pub hydrodynamic_force: Vec3,
    /// Smallest cell ε.
    pub min_fluid_fraction: f64,
}

/// The drag-law model: settings, the volume-averaged fluid, the transfer and per-particle
/// work arrays (no allocation per step once sized).
pub struct DragLawCoupling {
    pub settings: DragLawSettings,
    pub fluid: VolumeAveragedFluid,
    transfer: GridTransfer,
    /// The velocity's cell-point interpolation, when the settings ask for it.
    cell_point: Option<CellPointInterpolation>,
    /// Solid volume per cell, padded (ghosts unused), then the new ε.
    solid: Vec<f64>,
    cells: Vec<f64>,
    /// Per particle: drag force and coefficient β of the last force evaluation.
    drag: Vec<Vec3>,
    beta: Vec<f64>,
    hydro: Vec<Vec3>,
    /// Per particle: the stencils spreading the reaction (computed with the forces) and the
    /// volume (computed at the new positions).
    write_faces: Vec<[SampleStencil; 3]>,
    write_cells: Vec<SampleStencil>,
    /// Deterministic parallel spreading of the reaction (3 source + 3 coefficient fields) and
    /// of the volume.
    face_scatter: ChunkedScatter,
    cell_scatter: ChunkedScatter,
    /// Cell-centred pressure gradient, padded (ghosts filled), used in a fully periodic box.
    cell_gradient: [Vec<f64>; 3],
    /// DPMFoam's fluid fields at cell centres, padded (interior filled), computed once per
    /// step when a force reads them: `DU_c/Dt` and `∇ × U_c`.
    acceleration: Vec<[f64; 3]>,
    curl: Vec<[f64; 3]>,
    /// Their cell-point interpolations, when the case asks for them.
    acceleration_cell_point: Option<CellPointInterpolation>,
    curl_cell_point: Option<CellPointInterpolation>,
    /// Per particle: the explicit coupled force (pressure gradient, virtual mass, lift) and
    /// the load handed to the DEM (see [`Self::particle_forces`]).
    explicit: Vec<Vec3>,
    load: Vec<Vec3>,
    pub last: ExchangeReport,
    /// The fluid's report of the last step.
    pub last_fluid: Option<VolumeAveragedReport>,
    /// What the grid lets happen before the run (`overfill_warning`), for `-dry-run` and
    /// the log.
    pub warnings: Vec<String>,
}

impl DragLawCoupling {
    /// The model for `fluid` and the particles of `dem`: checks the particle size against the
    /// grid (no particle larger than two cells) and the initial ε against `alphaMax`. A fresh
    /// run then calls [`Self::initialise_pressure`], a continued one [`Self::restore`].
    pub fn new(settings: DragLawSettings, fluid: &FluidSolver, dem: &Dem) -> Result<Self, String> {
        if !(settings.alpha_max > 0.0 && settings.alpha_max <= 1.0) {
            return Err(format!(
                "alphaMax = {}: expected a value in (0, 1]",
                settings.alpha_max
            ));
        }
        let grid = fluid.grid().clone();
        let bc = fluid.boundary_conditions().clone();
        let h_min = (0..3)
            .filter(|&d| !matches!(bc.face(d, 0), crate::fluid::FaceCondition::Empty))
            .map(|d| grid.h[d])
            .fold(f64::INFINITY, f64::min);
        let p = dem.particles();
        if let Some(i) = (0..p.len()).find(|&i| p.diameter[i] > 2.0 * h_min) {
            return Err(format!(
                "particle {} (id {}) has d = {} m, larger than two cells (h = {} m): the \
                 drag-law model averages over cells about the particle size or coarser; use \
                 a coarser mesh or the direct model",
                i, p.id[i], p.diameter[i], h_min
            ));
        }
        let va = VolumeAveragedFluid::new(fluid, settings.form, settings.gravity.into())?;
        let transfer = GridTransfer::new(&grid, &bc, va.momentum_ranges());
        let settings_cell_point = settings.cell_point;
        let forces = settings.forces;
        let len = va.layout().len;
        let mut coupling = DragLawCoupling {
            settings,
            fluid: va,
            transfer,
            cell_point: settings_cell_point.then(|| CellPointInterpolation::new(&grid, &bc)),
            solid: vec![0.0; len],
            cells: vec![0.0; grid.cell_count()],
            drag: Vec::new(),
            beta: Vec::new(),
            hydro: Vec::new(),
            write_faces: Vec::new(),
            write_cells: Vec::new(),
            face_scatter: ChunkedScatter::new(),
            cell_scatter: ChunkedScatter::new(),
            cell_gradient: [(); 3].map(|_| vec![0.0; len]),
            acceleration: vec![[0.0; 3]; if forces.needs_acceleration() { len } else { 0 }],
            curl: vec![[0.0; 3]; if forces.needs_curl() { len } else { 0 }],
            acceleration_cell_point: (forces.needs_acceleration()
                && forces.acceleration_cell_point)
                .then(|| CellPointInterpolation::new(&grid, &bc)),
            curl_cell_point: (forces.needs_curl() && forces.curl_cell_point)
                .then(|| CellPointInterpolation::new(&grid, &bc)),
            explicit: Vec::new(),
            load: Vec::new(),
            last_fluid: None,
            last: ExchangeReport::default(),
            warnings: Vec::new(),
        };
        coupling.compute_fluid_fraction(dem.particles())?;
        coupling.fluid.reset_fluid_fraction(&coupling.cells);
        let empty =
            std::array::from_fn(|d| matches!(bc.face(d, 0), crate::fluid::FaceCondition::Empty));
        let settings = &coupling.settings;
        coupling.warnings.extend(overfill_warning(
            &grid,
            empty,
            p,
            settings.alpha_max,
            settings.averaging,
        ));
        Ok(coupling)
    }

    /// Imposes the mean pressure gradient `G` of `mean_pressure_gradient` (the settings'
    /// gravity taken as the physical one) and returns it: zero unless every face is periodic
    /// and gravity is non-zero. Case runs call it; a caller that drives a periodic box through
    /// the fluid's gravity (a porous-media flow, a study holding the weight itself) does not.
    pub fn carry_mixture_weight(&mut self, dem: &Dem) -> Vec3 {
        let g = mean_pressure_gradient(
            self.fluid.grid(),
            self.fluid.boundary_conditions(),
            dem.particles(),
            self.settings.rho,
            self.settings.gravity,
        );
        self.fluid.set_mean_pressure_gradient(g.into());
        g
    }

    /// Re-establishes `εⁿ` and `∇p` after a restart (the velocity and pressure come from the
    /// restart file; ε is a function of the saved positions, so this is bit-identical).
    pub fn restore(&mut self, fluid: &FluidSolver, dem: &Dem) -> Result<(), String> {
        self.compute_fluid_fraction(dem.particles())?;
        self.fluid.reset_fluid_fraction(&self.cells);
        self.fluid.update_pressure_gradient(fluid);
        Ok(())
    }

    /// Whether a fresh run starts from the projected initial field: in the paper's form, yes;
    /// in DPMFoam's form the first cloud evolution sees the case's field as given, as
    /// DPMFoam's does (DPMFoam projects only in its first pressure correction).
    pub fn projects_initial_field(&self) -> bool {
        self.settings.form == VolumeAveragedForm::Paper
    }

    /// The pressure of the initial velocity and ε (so that the first particle forces see the
    /// fluid's weight in it): one step taken and undone but for `p` and `∇p`.
    pub fn initialise_pressure(&mut self, fluid: &mut FluidSolver, dt: f64) {
        let saved = fluid.velocity().clone();
        let t = fluid.time();
        self.fluid.step(fluid, dt);
        *fluid.velocity_mut() = saved;
        fluid.set_time(t);
    }

    /// `ε = 1 − (solid volume)/(cell volume)` from the particles, into `self.cells`; fails
    /// below `1 − alphaMax` naming the cell.
    fn compute_fluid_fraction(&mut self, p: &ParticleState) -> Result<f64, String> {
        let stencil = self.settings.averaging;
        let transfer = &self.transfer;
        let n = p.len();
        self.write_cells.resize(n, SampleStencil::default());
        let (position, diameter) = (&p.position, &p.diameter);
        // Per chunk: the stencils, then the volumes into the chunk's partial (chunked_scatter.rs).
        self.cell_scatter
            .partials_mut(n)
            .par_iter_mut()
            .zip(self.write_cells.par_chunks_mut(PARTICLES_PER_CHUNK))
            .enumerate()
            .for_each(|(k, (partial, stencils))| {
                let first = k * PARTICLES_PER_CHUNK;
                let (mut lo, mut hi) = (usize::MAX, 0);
                for (j, st) in stencils.iter_mut().enumerate() {
                    transfer.cell_stencil(position[first + j], stencil, st);
                    let (a, b) = st.index_range();
                    lo = lo.min(a);
                    hi = hi.max(b);
                }
                partial.reset(lo, hi, 1);
                let base = partial.base();
                let solid = partial.field_mut(0);
                for (j, st) in stencils.iter().enumerate() {
                    let d = diameter[first + j];
                    st.scatter(solid, base, PI * d * d * d / 6.0);
                }
            });
        self.cell_scatter.reduce_into(0, &mut self.solid);
        let grid = self.fluid.grid();
        let [n0, n1, n2] = grid.n;
        let l = self.fluid.layout();
        let inv_volume = 1.0 / self.transfer.cell_volume();
        let floor = 1.0 - self.settings.alpha_max;
        let mut min = f64::INFINITY;
        let mut worst = [0usize; 3];
        for k in 0..n2 {
            for j in 0..n1 {
                for i in 0..n0 {
                    let eps = 1.0 - self.solid[l.index(i + 1, j + 1, k + 1)] * inv_volume;
                    self.cells[i + n0 * (j + n1 * k)] = eps;
                    if eps < min {
                        min = eps;
                        worst = [i, j, k];
                    }
                }
            }
        }
        if min < floor || min <= 0.0 {
            return Err(self.overfill_report(p, min, worst));
        }
        self.last.min_fluid_fraction = min;
        Ok(min)
    }

    /// The stop of [`Self::compute_fluid_fraction`]: the worst cell `worst` (fluid fraction
    /// `min`), how many cells are beyond the limit, the particles that fill the worst cell
    /// (a few named), and the grid that would hold them.
    fn overfill_report(&self, p: &ParticleState, min: f64, worst: [usize; 3]) -> String {
        let floor = 1.0 - self.settings.alpha_max;
        let beyond = self
            .cells
            .iter()
            .filter(|&&e| e < floor || e <= 0.0)
            .count();
        let l = self.fluid.layout();
        let index = l.index(worst[0] + 1, worst[1] + 1, worst[2] + 1);
        let inside: Vec<usize> = (0..p.len().min(self.write_cells.len()))
            .filter(|&i| self.write_cells[i].weight_at(index) > 0.0)
            .collect();
        let named: Vec<String> = inside
            .iter()
            .take(4)
            .map(|&i| p.id[i].to_string())
            .collect();
        let more = match inside.len() {
            n if n > named.len() => format!(" and {} more", n - named.len()),
            _ => String::new(),
        };
        let solid = (1.0 - min) * self.transfer.cell_volume();
        let grid = self.fluid.grid();
        let empty = std::array::from_fn(|d| {
            matches!(
                self.fluid.boundary_conditions().face(d, 0),
                crate::fluid::FaceCondition::Empty
            )
        });
        let s = &self.settings;
        let fix = match coarser_grid(grid, empty, p, s.alpha_max, s.averaging) {
            Some(fix) => format!("use cells of {fix}, or raise alphaMax"),
            None => "use a coarser mesh or raise alphaMax".to_string(),
        };
        format!(
            "the fluid fraction of cell ({} {} {}) is {min:.6}, below 1 − alphaMax = {floor} \
             (alphaMax {}), in {beyond} cell(s): particles {}{more} (id) put {solid:.3e} m³ \
             of solid in that cell of {:.3e} m³ ({} averaging); {fix}",
            worst[0],
            worst[1],
            worst[2],
            s.alpha_max,
            named.join(", "),
            self.transfer.cell_volume(),
            s.averaging.averaging_method(),
        )
    }

    /// Step part 1: the hydrodynamic force on every particle into the cloud's external loads
    /// and its reaction into the fluid's sources, from the current fluid state.
    pub fn particle_forces(&mut self, fluid: &FluidSolver, dem: &mut Dem, dt: f64) {
        let n = dem.particles().len();
        self.drag.resize(n, Vec3::zeros());
        self.beta.resize(n, 0.0);
        self.hydro.resize(n, Vec3::zeros());
        self.write_faces.resize(n, [SampleStencil::default(); 3]);
        self.explicit.resize(n, Vec3::zeros());
        self.load.resize(n, Vec3::zeros());
        self.compute_fluid_fields(fluid);
        let s = &self.settings;
        let want = match s.form {
            VolumeAveragedForm::Paper => Convention::DragOnly,
            VolumeAveragedForm::DpmFoam => Convention::Total,
        };
        let (g_cloud, rho_cloud) = (dem.config().gravity, dem.config().fluid_density);
        let (rho, mu) = (s.rho, s.mu());
        // In a fully periodic box (G set) the particles read ∇p from cell centres, averaged
        // from the two faces of each cell, with the stencil that spreads their volume into ε:
        // then Σ_p V_p ∇p(x_p) = Σ_faces (1 − ε_f) ∇p_f V_cell exactly, the counterpart of
        // the fluid's −ε_f ∇p, and with Σ_faces ∇p_f = 0 the pressure exchange conserves
        // momentum (face-staggered reading would not, by a few % of the weight).
        let cell_centred =
            s.form == VolumeAveragedForm::Paper && self.fluid.mean_pressure_gradient() != [0.0; 3];
        if cell_centred {
            let l = self.fluid.layout();
            let [n0, n1, n2] = l.n;
            let gradient = self.fluid.pressure_gradient();
            for c in 0..3 {
                let sc = l.stride[c];
                // Along a periodic direction the last cell's upper face is the first face
                // (the gradient is held on faces 1..=n only, its slot n + 1 is not filled).
                let periodic = matches!(
                    self.fluid.boundary_conditions().face(c, 0),
                    crate::fluid::FaceCondition::Periodic
                );
                let wrap = (l.n[c] - 1) * sc;
                let (g, out) = (&gradient[c], &mut self.cell_gradient[c]);
                for k in 1..=n2 {
                    for j in 1..=n1 {
                        for i in 1..=n0 {
                            let f = l.index(i, j, k);
                            let last = [i, j, k][c] == l.n[c];
                            let upper = if periodic && last { f - wrap } else { f + sc };
                            out[f] = 0.5 * (g[f] + g[upper]);
                        }
                    }
                }
                crate::fluid::fill_cell_ghosts(l, self.fluid.boundary_conditions(), out);
            }
        }
        if let Some(cp) = self.cell_point.as_mut() {
            cp.update(fluid.velocity());
        }
        let cell_point = self.cell_point.as_ref();
        let needs_read = cell_point.is_none() || s.form == VolumeAveragedForm::Paper;
        let cell_gradient = &self.cell_gradient;
        let transfer = &self.transfer;
        let velocity = fluid.velocity();
        let eps_cells = self.fluid.fluid_fraction();
        let gradient = self.fluid.pressure_gradient();
        let g_fluid = self.fluid.gravity();
        let mean_gradient = self.fluid.mean_pressure_gradient();
        let forces = s.forces;
        // Tomiyama's Eötvös number reads the case's g (OpenFOAM's `owner().g()`), listed
        // `gravity` or not
        let g_case: [f64; 3] = s.gravity.into();
        let (acceleration, curl) = (&self.acceleration, &self.curl);
        let (acceleration_cp, curl_cp) = (
            self.acceleration_cell_point.as_ref(),
            self.curl_cell_point.as_ref(),
        );
        let (grid, layout) = (self.fluid.grid(), self.fluid.layout());
        // DPMFoam's `cell` interpolation of a cell-centred field: the particle's cell
        let cell_value = |field: &[[f64; 3]], x: Vec3| -> [f64; 3] {
            let slot: [usize; 3] = std::array::from_fn(|d| {
                let s = ((x[d] - grid.origin[d]) / grid.h[d]).floor();
                (s.max(0.0) as usize).min(grid.n[d] - 1) + 1
            });
            field[layout.index(slot[0], slot[1], slot[2])]
        };
        // A cell-centred field the forces read (`DUcDt`, `curlUcDt`): zero when no force needs
        // it, else its cell-point interpolation or its cell value
        let fluid_field = |needed: bool,
                           cp: Option<&CellPointInterpolation>,
                           field: &[[f64; 3]],
                           x: Vec3|
         -> [f64; 3] {
            match cp {
                _ if !needed => [0.0; 3],
                Some(cp) => cp.sample(x).into(),
                None => cell_value(field, x),
            }
        };
        let (closure, form, interpolation, averaging, analytical) = (
            s.closure,
            s.form,
            s.interpolation,
            s.averaging,
            s.analytical,
        );
        // Particle loop in chunks: each particle writes its own slots, then the chunk spreads
        // its particles' reaction into its partial (chunked_scatter.rs). Each stencil is
        // computed once and serves every read (u, ε, ∇p) and write (source, coefficient).
        let scale = 1.0 / (rho * transfer.cell_volume());
        let semi_implicit = s.semi_implicit;
        // Fields 0–2: the source per component; 3–5: the coefficient.
        let fields = if semi_implicit { 6 } else { 3 };
        {
            let p = dem.particles();
            let (position, vel, diameter, density, fixed, contact) = (
                &p.position,
                &p.velocity,
                &p.diameter,
                &p.density,
                &p.fixed,
                &p.contact_force,
            );
            self.face_scatter
                .partials_mut(n)
                .par_iter_mut()
                .zip(self.hydro.par_chunks_mut(PARTICLES_PER_CHUNK))
                .zip(self.drag.par_chunks_mut(PARTICLES_PER_CHUNK))
                .zip(self.beta.par_chunks_mut(PARTICLES_PER_CHUNK))
                .zip(self.write_faces.par_chunks_mut(PARTICLES_PER_CHUNK))
                .zip(self.explicit.par_chunks_mut(PARTICLES_PER_CHUNK))
                .zip(self.load.par_chunks_mut(PARTICLES_PER_CHUNK))
                .enumerate()
                .for_each(
                    |(k, ((((((partial, hydro), drag), beta), write), explicit), load))| {
                        let first = k * PARTICLES_PER_CHUNK;
                        let (mut lo, mut hi) = (usize::MAX, 0);
                        for j in 0..hydro.len() {
                            let i = first + j;
                            let (hydro, drag, beta, write, explicit, load) = (
                                &mut hydro[j],
                                &mut drag[j],
                                &mut beta[j],
                                &mut write[j],
                                &mut explicit[j],
                                &mut load[j],
                            );
                            let x = position[i];
                            let mut read = [SampleStencil::default(); 3];
                            // The face stencils read u, and ∇p in the paper's form.
                            if needs_read {
                                transfer.read_face_stencils(x, interpolation, &mut read);
                            }
                            let u = match cell_point {
                                Some(cp) => cp.sample(x),
                                None => Vec3::new(
                                    read[0].gather(&velocity[0]),
                                    read[1].gather(&velocity[1]),
                                    read[2].gather(&velocity[2]),
                                ),
                            };
                            let mut cell = SampleStencil::default();
                            transfer.write_stencils(x, averaging, write, &mut cell);
                            let eps = cell.gather(eps_cells);
                            let slip =
                                Vec3::new(u[0] - vel[i][0], u[1] - vel[i][1], u[2] - vel[i][2]);
                            let speed =
                                (slip[0] * slip[0] + slip[1] * slip[1] + slip[2] * slip[2]).sqrt();
                            let d = diameter[i];
                            let q = DragInput {
                                d,
                                eps,
                                slip: speed,
                                rho,
                                mu,
                            };
                            let b = closure.map_or(0.0, |c| c.coefficient_as(&q, want));
                            let volume = q.volume();
                            let pressure = match form {
                                VolumeAveragedForm::Paper => {
                                    // ∇p is the periodic part; G its uniform mean (zero if not
                                    // fully periodic). With G, ∇p is read from cell centres with
                                    // the ε stencil: the exact adjoint of the fluid's −ε_f∇p.
                                    let gp: [f64; 3] = if cell_centred {
                                        std::array::from_fn(|c| cell.gather(&cell_gradient[c]))
                                    } else {
                                        std::array::from_fn(|c| read[c].gather(&gradient[c]))
                                    };
                                    std::array::from_fn(|a| {
                                        -volume * rho * (gp[a] + mean_gradient[a] - g_fluid[a])
                                    })
                                }
                                VolumeAveragedForm::DpmFoam => [0.0; 3],
                            };
                            let mass = density[i] * volume;
                            // DPMFoam's explicit coupled forces (pressure gradient, virtual mass,
                            // lift), from DU_c/Dt and ∇ × U_c at the particle
                            let mut fx = [0.0; 3];
                            if forces.needs_acceleration() || forces.needs_curl() {
                                let du_dt = fluid_field(
                                    forces.needs_acceleration(),
                                    acceleration_cp,
                                    acceleration,
                                    x,
                                );
                                let w = fluid_field(forces.needs_curl(), curl_cp, curl, x);
                                fx = forces.explicit_force(
                                    mass,
                                    density[i],
                                    d,
                                    vel[i].into(),
                                    rho,
                                    mu,
                                    u.into(),
                                    du_dt,
                                    w,
                                    g_case,
                                );
                            }
                            // massEff = m (1 + r), r = Cvm ρ/ρ_p: the fluid-step forces move the
                            // particle through massEff, its contacts through m (as DPMFoam)
                            let r = forces.added_mass_ratio(rho, density[i]);
                            // The fraction of the force imbalance the implicit drag relaxes in one step:
                            // 1/(1 + x) for Euler, (1 − e^−x)/x for the analytical solution.
                            let x_imp = if fixed[i] {
                                0.0
                            } else {
                                dt * b / (mass * (1.0 + r))
                            };
                            let relax = if x_imp == 0.0 {
                                1.0
                            } else if analytical {
                                -(-x_imp).exp_m1() / x_imp
                            } else {
                                1.0 / (1.0 + x_imp)
                            };
                            let buoyant = 1.0 - rho_cloud / density[i];
                            *drag = Vec3::from_fn(|a, _| {
                                let other = mass * buoyant * g_cloud[a]
                                    + pressure[a]
                                    + fx[a]
                                    + (1.0 + r) * contact[i][a];
                                relax * (b * slip[a] + other) - other
                            });
                            *beta = b;
                            *explicit = Vec3::from(fx);
                            *hydro = Vec3::from_fn(|a, _| drag[a] + pressure[a] + fx[a]);
                            // The DEM moves the particle by load/m + (1 − ρ/ρ_p) g (and its
                            // contacts by 1/m): load = (f_h + m (1 − ρ/ρ_p) g)/(1 + r) − m (1 − ρ/ρ_p) g
                            *load = Vec3::from_fn(|a, _| {
                                let weight = mass * buoyant * g_cloud[a];
                                (hydro[a] + weight) / (1.0 + r) - weight
                            });
                            for st in write.iter() {
                                let (a, b) = st.index_range();
                                lo = lo.min(a);
                                hi = hi.max(b);
                            }
                        }
                        partial.reset(lo, hi, fields);
                        let base = partial.base();
                        for j in 0..hydro.len() {
                            let (f, e, st) = (drag[j], explicit[j], &write[j]);
                            let b = if semi_implicit { beta[j] * scale } else { 0.0 };
                            for c in 0..3 {
                                // DPMFoam's dUTrans: the drag and the explicit coupled forces
                                let value = -(f[c] + e[c]) * scale;
                                if value != 0.0 && b != 0.0 {
                                    // source and coefficient share the stencil's weights
                                    let (source, coefficient) = partial.field_pair_mut(c, 3 + c);
                                    st[c].scatter_pair(source, coefficient, base, value, b);
                                } else if value != 0.0 {
                                    st[c].scatter(partial.field_mut(c), base, value);
                                } else if b != 0.0 {
                                    st[c].scatter(partial.field_mut(3 + c), base, b);
                                }
                            }
                        }
                    },
                );
        }
        {
            let (force, _) = dem.external_loads_mut();
            force.copy_from_slice(&self.load);
            let mut total = Vec3::zeros();
            for f in &self.hydro {
                for a in 0..3 {
                    total[a] += f[a];
                }
            }
            self.last.hydrodynamic_force = total;
        }
        self.spread_reaction();
    }

    /// DPMFoam's `DUcDt` and `curlUcDt = ∇ × U_c` at the cell centres,
    /// when a force reads them, and their cell-point interpolation when asked for. The
    /// gradient is OpenFOAM's Gauss-linear one on a uniform grid: central differences of the
    /// cell-centred velocity (the ghost cells carry the boundary values), and along a
    /// component's own direction the difference of its two faces. `DUcDt` is `(U_c·∇)U_c`:
    /// DPMFoam v1912 writes `∂U_c/∂t + (U_c·∇)U_c` but evaluates it when the cloud evolves,
    /// before the fluid is solved in the new step and after `Uc.oldTime()` was set to `Uc`,
    /// so its time derivative is zero (docs/user-guide/drag-law-model.md).
    fn compute_fluid_fields(&mut self, fluid: &FluidSolver) {
        let forces = self.settings.forces;
        let (need_a, need_c) = (forces.needs_acceleration(), forces.needs_curl());
        if !need_a && !need_c {
            return;
        }
        let l = self.fluid.layout().clone();
        let h = self.fluid.grid().h;
        let bc = self.fluid.boundary_conditions();
        let empty: [bool; 3] =
            std::array::from_fn(|d| matches!(bc.face(d, 0), crate::fluid::FaceCondition::Empty));
        let u = fluid.velocity();
        let centre = |c: usize, f: usize| {
            if empty[c] {
                0.0
            } else {
                0.5 * (u[c][f] + u[c][f + l.stride[c]])
            }
        };
        let [n0, n1, n2] = l.n;
        for k in 1..=n2 {
            for j in 1..=n1 {
                for i in 1..=n0 {
                    let f = l.index(i, j, k);
                    let uc = [centre(0, f), centre(1, f), centre(2, f)];
                    // grad[d][c] = ∂U_c/∂x_d
                    let mut grad = [[0.0; 3]; 3];
                    for d in 0..3 {
                        if empty[d] {
                            continue;
                        }
                        let sd = l.stride[d];
                        for c in 0..3 {
                            if empty[c] {
                                continue;
                            }
                            grad[d][c] = if c == d {
                                (u[c][f + sd] - u[c][f]) / h[d]
                            } else {
                                (centre(c, f + sd) - centre(c, f - sd)) / (2.0 * h[d])
                            };
                        }
                    }
                    if need_a {
                        let mut a = [0.0; 3];
                        for c in 0..3 {
                            a[c] = uc[0] * grad[0][c] + uc[1] * grad[1][c] + uc[2] * grad[2][c];
                        }
                        self.acceleration[f] = a;
                    }
                    if need_c {
                        self.curl[f] = [
                            grad[1][2] - grad[2][1],
                            grad[2][0] - grad[0][2],
                            grad[0][1] - grad[1][0],
                        ];
                    }
                }
            }
        }
        if let Some(cp) = self.acceleration_cell_point.as_mut() {
            cp.update_cells(&self.acceleration);
        }
        if let Some(cp) = self.curl_cell_point.as_mut() {
            cp.update_cells(&self.curl);
        }
    }

    /// The reaction `−f_d/(ρ V_cell)` (and `β/(ρ V_cell)` for the semi-implicit source) the
    /// particle loop spread into the chunks' partials, summed into the fluid's sources in chunk
    /// order (deterministic for any thread count).
    fn spread_reaction(&mut self) {
        let scale = 1.0 / (self.settings.rho * self.transfer.cell_volume());
        let semi_implicit = self.settings.semi_implicit;
        let mut on_particles = Vec3::zeros();
        for (f, e) in self.drag.iter().zip(&self.explicit) {
            for a in 0..3 {
                on_particles[a] += f[a] + e[a];
            }
        }
        let (source, coefficient) = self.fluid.sources_mut();
        for c in 0..3 {
            self.face_scatter.reduce_into(c, &mut source[c]);
            if semi_implicit {
                self.face_scatter.reduce_into(3 + c, &mut coefficient[c]);
            } else {
                coefficient[c].iter_mut().for_each(|x| *x = 0.0);
            }
        }
        let mut on_fluid = Vec3::zeros();
        for c in 0..3 {
            on_fluid[c] = source[c].iter().sum::<f64>() / scale;
        }
        self.last.drag_on_particles = on_particles;
        self.last.drag_on_fluid = on_fluid;
    }

    /// Step part 2: ε from the particles' new positions (fails below `1 − alphaMax`).
    pub fn update_fluid_fraction(&mut self, dem: &Dem) -> Result<(), String> {
        self.compute_fluid_fraction(dem.particles())?;
        self.fluid.advance_fluid_fraction(&self.cells);
        Ok(())
    }

    /// Step part 3: the volume-averaged momentum predictor ([`VolumeAveragedFluid::predict_momentum`]).
    pub fn predict_momentum(&mut self, fluid: &mut FluidSolver, dt: f64) {
        self.fluid.predict_momentum(fluid, dt);
    }

    /// Step part 4: the pressure correction ([`VolumeAveragedFluid::correct_pressure`]).
    pub fn correct_pressure(&mut self, fluid: &mut FluidSolver, dt: f64) -> VolumeAveragedReport {
        let report = self.fluid.correct_pressure(fluid, dt);
        self.last_fluid = Some(report);
        report
    }

    /// The fluid velocity a particle at `x` reads (the interpolation stencil of the settings).
    /// With cell-point interpolation, the point values of the last force evaluation.
    pub fn fluid_velocity_at(&self, fluid: &FluidSolver, x: Vec3) -> Vec3 {
        match &self.cell_point {
            Some(cp) => cp.sample(x),
            None => {
                self.transfer
                    .interpolate_faces(fluid.velocity(), x, self.settings.interpolation)
            }
        }
    }

    /// The fluid fraction a particle at `x` reads (the averaging stencil of the settings).
    pub fn fluid_fraction_at(&self, x: Vec3) -> f64 {
        self.transfer
            .interpolate_cells(self.fluid.fluid_fraction(), x, self.settings.averaging)
    }

    /// Per particle (the cloud's current order), the drag `f_d` of the last force evaluation.
    pub fn drag_forces(&self) -> &[Vec3] {
        &self.drag
    }

    /// Cell ε, unpadded x-fastest (for output).
    pub fn cell_fluid_fraction(&self) -> Vec<f64> {
        let mut out = vec![0.0; self.fluid.grid().cell_count()];
        self.fluid.cell_fluid_fraction(&mut out);
        out
    }

    /// The pressure drop across the domain along `axis` less the fluid's own weight, Pa:
    /// `ρ (⟨p⟩_first − ⟨p⟩_last + g_axis (x_last − x_first))` between the first and the last
    /// cell layer (the reading of a manometer across a bed: for a fluidized bed the buoyant
    /// weight per area, for a fixed bed Ergun's drop).
    pub fn pressure_drop(&self, fluid: &FluidSolver, axis: usize) -> f64 {
        let grid = fluid.grid();
        let n = grid.n;
        let p = fluid.pressure();
        let layer = |m: usize| {
            let mut sum = 0.0;
            let mut count = 0;
            for k in 0..n[2] {
                for j in 0..n[1] {
                    for i in 0..n[0] {
                        if [i, j, k][axis] == m {
                            sum += p[i + n[0] * (j + n[1] * k)];
                            count += 1;
                        }
                    }
                }
            }
            sum / count as f64
        };
        let span = (n[axis] - 1) as f64 * grid.h[axis];
        self.settings.rho * (layer(0) - layer(n[axis] - 1) + self.settings.gravity[axis] * span)
    }

    /// The stencil names for the banner (and `G` when the box is fully periodic).
    pub fn describe(&self) -> String {
        let s = &self.settings;
        let g = self.fluid.mean_pressure_gradient();
        let mean = if g == [0.0; 3] {
            String::new()
        } else {
            format!(
                ", mean pressure gradient G = ({:.6e} {:.6e} {:.6e}) m/s² (fully periodic box)",
                g[0], g[1], g[2]
            )
        };
        format!(
            "{} drag, {} form, interpolation {}, averaging {}, {} source, alphaMax {}{mean}",
            s.closure.map_or("no", |c| c.name()),
            s.form.name(),
            if s.cell_point {
                "cellPoint"
            } else {
                s.interpolation.name()
            },
            s.averaging.name(),
            if s.semi_implicit {
                "semi-implicit"
            } else {
                "explicit"
            },
            s.alpha_max
        )
    }

    /// Total momentum of fluid and particles, kg·m/s: `ρ_f Σ_faces ε_f u_f V_cell + Σ m v`
    /// (each component over the faces where it is advanced).
    pub fn mixture_momentum(&self, fluid: &FluidSolver, dem: &Dem) -> Vec3 {
        let l = self.fluid.layout();
        let eps = self.fluid.fluid_fraction();
        let u = fluid.velocity();
        let volume = self.transfer.cell_volume();
        let mut total = Vec3::zeros();
        for (c, r) in self.fluid.momentum_ranges().iter().enumerate() {
            let sc = l.stride[c];
            let mut sum = 0.0;
            for k in r[2].0..=r[2].1 {
                for j in r[1].0..=r[1].1 {
                    for i in r[0].0..=r[0].1 {
                        let f = l.index(i, j, k);
                        sum += 0.5 * (eps[f] + eps[f - sc]) * u[c][f];
                    }
                }
            }
            total[c] = self.settings.rho * volume * sum;
        }
        let p = dem.particles();
        for i in 0..p.len() {
            let d = p.diameter[i];
            let m = p.density[i] * PI * d * d * d / 6.0;
            for a in 0..3 {
                total[a] += m * p.velocity[i][a];
            }
        }
        total
    }
}

/// The uniform kinematic mean pressure gradient `G = (ρ_mix/ρ_f) g` that carries the weight of
/// fluid and particles in a box periodic on all six faces (zero otherwise, or without gravity):
/// `ρ_mix = (ρ_f (V_box − V_s) + Σ ρ_p V)/V_box`.
pub fn mean_pressure_gradient(
    grid: &crate::grid::Grid,
    bc: &crate::fluid::BoundaryConditions,
    particles: &ParticleState,
    rho: f64,
    gravity: Vec3,
) -> Vec3 {
    let periodic = (0..3).all(|d| {
        (0..2).all(|side| matches!(bc.face(d, side), crate::fluid::FaceCondition::Periodic))
    });
    if !periodic || gravity == Vec3::zeros() {
        return Vec3::zeros();
    }
    let box_volume: f64 = (0..3).map(|d| grid.n[d] as f64 * grid.h[d]).product();
    let (mut solid, mut mass) = (0.0, 0.0);
    for i in 0..particles.len() {
        let d = particles.diameter[i];
        let v = PI * d * d * d / 6.0;
        solid += v;
        mass += particles.density[i] * v;
    }
    let rho_mix = (rho * (box_volume - solid) + mass) / box_volume;
    gravity.map(|g| rho_mix / rho * g)
}

/// How a few particles can over-fill one cell: `count` of the case's largest particles
/// sharing it put `solid` m³ in a cell of `volume` m³, beyond `alphaMax · volume`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellOverfill {
    pub count: usize,
    pub solid: f64,
    pub volume: f64,
}

/// Whether up to four of the largest particles (volumes `largest`, descending, diameter `d`
/// the largest) can fill one cell of spacing `h` beyond `alpha_max`, with the cell volume
/// rule `stencil`. Along an `empty` axis the cell spans the box (`length`) and a particle's
/// weight there is one.
///
/// - `Cell` (DPMFoam's `basic`): every particle puts its whole volume in the cell of its
///   centre, so `k` particles give `ε = 1 − Σ V_p / V_c` wherever their centres are in the
///   cell. Two fit when the cell's diagonal exceeds `d`, four (the alternate corners) when
///   each face diagonal does.
/// - `Trilinear` (`dual`): a particle gives a cell at most its whole volume, at the cell's
///   centre, and the weight falls off linearly to zero one spacing away along each axis;
///   two particles at least `d` apart: the best placement is searched.
///
/// Four is the bound: a cell that only five or more touching particles over-fill does so
/// only in a packing denser than a bed reaches in the cell's neighbourhood (a bed at random
/// close packing, solid fraction 0.64, puts 0.64 V_c on average in a cell, with `alphaMax`
/// well above that the fluctuation it takes grows with the count).
pub fn cell_overfill(
    h: [f64; 3],
    empty: [bool; 3],
    length: [f64; 3],
    d: f64,
    largest: &[f64],
    alpha_max: f64,
    stencil: crate::coupling::drag::Stencil,
) -> Option<CellOverfill> {
    let extent: [f64; 3] = std::array::from_fn(|a| {
        if empty[a] {
            (length[a] - d).max(0.0)
        } else {
            h[a]
        }
    });
    let cell: [f64; 3] = std::array::from_fn(|a| if empty[a] { length[a] } else { h[a] });
    let volume: f64 = cell.iter().product();
    let limit = alpha_max * volume;
    let sum = |k: usize| largest.iter().take(k).sum::<f64>();
    let candidates: Vec<(usize, f64)> = match stencil {
        crate::coupling::drag::Stencil::Cell => {
            let diagonal = extent.iter().map(|e| e * e).sum::<f64>().sqrt();
            let faces = (0..3)
                .map(|a| {
                    let (b, c) = ((a + 1) % 3, (a + 2) % 3);
                    (extent[b] * extent[b] + extent[c] * extent[c]).sqrt()
                })
                .fold(f64::INFINITY, f64::min);
            let mut c = vec![(1, sum(1))];
            if diagonal > d && largest.len() >= 2 {
                c.push((2, sum(2)));
            }
            if faces > d {
                for k in 3..=4.min(largest.len()) {
                    c.push((k, sum(k)));
                }
            }
            c
        }
        crate::coupling::drag::Stencil::Trilinear => {
            let mut c = vec![(1, sum(1))];
            if largest.len() >= 2 {
                // the tent weight of an offset `x` from the cell's centre
                let weight = |x: [f64; 3]| -> f64 {
                    (0..3)
                        .map(|a| {
                            if empty[a] {
                                if x[a].abs() <= extent[a] {
                                    1.0
                                } else {
                                    0.0
                                }
                            } else {
                                (1.0 - x[a].abs() / h[a]).max(0.0)
                            }
                        })
                        .product()
                };
                let mut best = 0.0f64;
                let steps = 24;
                for i in 0..=steps {
                    let theta = 0.5 * PI * i as f64 / steps as f64;
                    for j in 0..=steps {
                        let phi = 0.5 * PI * j as f64 / steps as f64;
                        let u = [
                            theta.sin() * phi.cos(),
                            theta.sin() * phi.sin(),
                            theta.cos(),
                        ];
                        for t in 0..=20 {
                            let t = t as f64 / 20.0;
                            let a = std::array::from_fn(|k| -t * d * u[k]);
                            let b = std::array::from_fn(|k| (1.0 - t) * d * u[k]);
                            best = best.max(weight(a) * largest[0] + weight(b) * largest[1]);
                        }
                    }
                }
                c.push((2, best));
            }
            c
        }
    };
    candidates
        .into_iter()
        .find(|&(_, solid)| solid > limit)
        .map(|(count, solid)| CellOverfill {
            count,
            solid,
            volume,
        })
}

/// The four largest particle volumes (descending) and the largest diameter of `p`.
fn largest_particles(p: &ParticleState) -> (Vec<f64>, f64) {
    let mut d: Vec<f64> = p.diameter.clone();
    d.sort_by(|a, b| b.total_cmp(a));
    d.truncate(4);
    let volumes = d.iter().map(|d| PI * d * d * d / 6.0).collect();
    (volumes, d.first().copied().unwrap_or(0.0))
}

/// The coarsest-needed grid: the spacing (scaled alike on every axis that is not empty) and
/// the cell counts at which no four of the largest particles over-fill a cell, as
/// "h ≥ … m (… cells)"; `None` when the box has no such grid.
fn coarser_grid(
    grid: &crate::grid::Grid,
    empty: [bool; 3],
    p: &ParticleState,
    alpha_max: f64,
    stencil: crate::coupling::drag::Stencil,
) -> Option<String> {
    let (largest, d) = largest_particles(p);
    let length = grid.length();
    let over = |h: [f64; 3]| cell_overfill(h, empty, length, d, &largest, alpha_max, stencil);
    let mut scale = 1.0;
    while over(std::array::from_fn(|a| grid.h[a] * scale)).is_some() {
        scale *= 1.01;
        if (0..3).any(|a| !empty[a] && grid.h[a] * scale > length[a]) {
            return None;
        }
    }
    let mut n: [usize; 3] = std::array::from_fn(|a| {
        if empty[a] {
            grid.n[a]
        } else {
            ((length[a] / (grid.h[a] * scale)).floor() as usize).max(1)
        }
    });
    // whole cells are at least as coarse; step down where a jump of the criterion needs it
    for _ in 0..8 {
        let h: [f64; 3] = std::array::from_fn(|a| length[a] / n[a] as f64);
        if over(h).is_none() {
            let coarse = (0..3)
                .filter(|&a| !empty[a])
                .map(|a| h[a])
                .fold(f64::INFINITY, f64::min);
            return Some(format!(
                "{coarse:.3e} m or more ({} {} {} cells)",
                n[0], n[1], n[2]
            ));
        }
        n = std::array::from_fn(|a| if empty[a] { n[a] } else { (n[a] - 1).max(1) });
    }
    None
}

/// The dry-run warning when the grid lets a few particles over-fill one cell
/// ([`cell_overfill`]); none when every particle is fixed (they never meet).
pub fn overfill_warning(
    grid: &crate::grid::Grid,
    empty: [bool; 3],
    p: &ParticleState,
    alpha_max: f64,
    stencil: crate::coupling::drag::Stencil,
) -> Option<String> {
    if p.is_empty() || p.fixed.iter().all(|&f| f) {
        return None;
    }
    let (largest, d) = largest_particles(p);
    let o = cell_overfill(
        grid.h,
        empty,
        grid.length(),
        d,
        &largest,
        alpha_max,
        stencil,
    )?;
    let fix = match coarser_grid(grid, empty, p, alpha_max, stencil) {
        Some(fix) => format!("cells of {fix}"),
        None => "a coarser mesh".to_string(),
    };
    let dual = match stencil {
        crate::coupling::drag::Stencil::Cell
            if cell_overfill(
                grid.h,
                empty,
                grid.length(),
                d,
                &largest,
                alpha_max,
                crate::coupling::drag::Stencil::Trilinear,
            )
            .is_none() =>
        {
            ", or averagingMethod dual"
        }
        _ => "",
    };
    Some(format!(
        "drag-law model: {} of the largest particles (d = {d:.3e} m) sharing one cell put \
         {:.3e} m³ of solid in it, {:.3} of the cell's {:.3e} m³, beyond alphaMax = {} \
         ({} averaging, h = {:.3e} m): the run stops if that many gather in one cell; use {fix}{dual}",
        o.count,
        o.solid,
        o.solid / o.volume,
        o.volume,
        alpha_max,
        stencil.averaging_method(),
        (0..3)
            .filter(|&a| !empty[a])
            .map(|a| grid.h[a])
            .fold(f64::INFINITY, f64::min),
    ))
}
