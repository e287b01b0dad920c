//! The fluid state: velocity and pressure on the staggered grid, their settings, initial
//! fields, projection and restart arrays. The time step is in [`time_step`], the health
//! check and step rules in [`health_check`].

use super::boundary_conditions::{BoundaryConditions, FaceCondition};
use super::chebyshev_diffusion::ChebyshevDiffusion;
use super::ghost_fill::{extrapolate_outlets, fill_velocity_ghosts};
use super::mean_velocity_force::MeanVelocityForce;
use super::momentum::{accumulate_tendency, MomentumTerms};
use super::padded_layout::PaddedLayout;
use super::projection::{divergence_rhs, subtract_gradient};
use super::spectral_poisson::SpectralPoisson;
use super::staggered_transfer::{
    cell_from_faces, cells_from_faces, faces_from_cells, periodic_axes,
};
use super::time_scheme::TimeScheme;
use crate::grid::Grid;

mod health_check;
mod time_step;

use health_check::CachedReductions;

/// Physical and numerical settings of the fluid.
#[derive(Clone, Debug, PartialEq)]
pub struct FluidSettings {
    /// Kinematic viscosity ν, m²/s.
    pub nu: f64,
    /// Time scheme (default RK3).
    pub scheme: TimeScheme,
    /// Uniform body force per unit mass (gravity, an imposed mean pressure gradient), m/s².
    pub body_force: [f64; 3],
    /// The advection term `−∇·(uu)` is kept (default). Off, the momentum equation is the
    /// unsteady Stokes equation, and the advective step bounds no longer apply.
    pub convection: bool,
}

impl FluidSettings {
    /// Viscosity `nu` (m²/s), the default scheme (RK3), no body force.
    pub fn new(nu: f64) -> Self {
        FluidSettings {
            nu,
            scheme: TimeScheme::default(),
            body_force: [0.0; 3],
            convection: true,
        }
    }
}

/// The predicted velocity of a stage, handed to a hook before it is projected (the direct
/// model imposes the particles' velocity there). Only the faces the momentum equation
/// advances are current; ghost layers and boundary faces are refilled after the hook.
pub struct PredictedVelocity<'a> {
    pub grid: &'a Grid,
    pub layout: &'a PaddedLayout,
    /// Time at the end of the stage.
    pub time: f64,
    /// The body force on the fluid in this stage (its settings' plus the
    /// `meanVelocityForce` gradient), m/s².
    pub body_force: [f64; 3],
    /// The stage's projection weight: the projection subtracts `tau ∇p`.
    pub tau: f64,
    /// The pressure the coming projection will subtract `tau ∇` of, as last solved
    /// (cell-centred, unpadded; `Euler` and `RK3`): a hook that wants a face to end at `w`
    /// after the projection sets it to `w + tau ∂p` (exact once the flow is steady).
    pub pressure: &'a [f64],
    /// `EulerRKC` (empty with the others): the pressure `p` to which the step's one
    /// projection adds its increment `φ`, `∇²φ = (∇·u* − q)/τ`. A hook that sets `q` in a
    /// cell whose faces it fixes all adds `τ∇²p` there (the projection's discrete
    /// Laplacian), so that the new pressure is harmonic there as a full projection makes
    /// it; else the increment keeps the Laplacian the cell had when it closed (moving
    /// spheres cover fluid cells), and the drag drifts with it.
    pub incremental_pressure: &'a [f64],
    /// Velocity components, padded layout.
    pub velocity: &'a mut [Vec<f64>; 3],
    /// Mass source `q` per cell (1/s, unpadded), when enabled by
    /// [`FluidSolver::mass_source_mut`]: the projection makes `∇·u = q` instead of 0. A
    /// hook that fixes every face of a cell sets `q` there to the divergence it imposes
    /// (Kim, Kim & Choi, J. Comput. Phys. 171, 132–150, 2001); `Σ q` must be 0.
    pub mass_source: Option<&'a mut [f64]>,
    /// The components this call hands over predicted: a hook acts on these only (the others
    /// hold what the last call left them). All three but with `EulerRKC`, whose stages
    /// advance one component at a time (see [`FluidSolver::step_with`]).
    pub components: [bool; 3],
}

/// What one step did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepReport {
    pub dt: f64,
    /// Time after the step.
    pub time: f64,
    /// Driving gradient `−∂⟨p⟩/∂x` of `meanVelocityForce` after the step (m/s²), if any.
    pub driving_gradient: Option<f64>,
}

/// Incompressible Navier–Stokes on a uniform MAC grid, advanced by projection.
///
/// Storage, all contiguous `Vec<f64>`:
/// - `u[c]`: velocity component `c` on the faces normal to `c`, padded ([`PaddedLayout`]);
/// - `p`: kinematic pressure `p/ρ` (m²/s²) at cell centres, unpadded x-fastest (the layout of
///   [`Grid`]); after a step it is the pressure of the last stage (for Euler `pⁿ⁺¹`);
/// - `q[c]`: the Runge–Kutta register (tendency), padded;
/// - optional per-face sources `source[c]`, padded, m/s².
///
/// No allocation happens in [`FluidSolver::step`].
pub struct FluidSolver {
    grid: Grid,
    layout: PaddedLayout,
    bc: BoundaryConditions,
    settings: FluidSettings,
    u: [Vec<f64>; 3],
    p: Vec<f64>,
    /// The tendency register of the two-register schemes (`EulerRKC`'s frozen tendency).
    q: [Vec<f64>; 3],
    source: Option<[Vec<f64>; 3]>,
    /// Optional per-cell mass source of the projection (see [`PredictedVelocity`]).
    mass_source: Option<Vec<f64>>,
    poisson: SpectralPoisson,
    /// `EulerRKC`'s second velocity register (one, for the component whose stages run) and
    /// pressure increment.
    chebyshev: Option<ChebyshevDiffusion>,
    drive: Option<MeanVelocityForce>,
    time: f64,
    momentum_ranges: [[(usize, usize); 3]; 3],
    corrected_ranges: [[(usize, usize); 3]; 3],
    /// Per k-plane partial results of reductions, summed in plane order (deterministic).
    partials: Vec<[f64; 12]>,
    /// `[time, driving gradient]` as stored for restart.
    scalars: [f64; 2],
    /// Chebyshev stages of the last `EulerRKC` step.
    stages_taken: usize,
    /// Multi-stage schemes only (empty otherwise): the stage pressures of the last step
    /// weighted by their share of its pressure impulse (see [`Self::impulse_pressure`]), and
    /// the velocity generation it belongs to.
    impulse_pressure: Vec<f64>,
    impulse_generation: Option<u64>,
    /// Bumped whenever the velocity may change.
    generation: u64,
    /// What the last [`Self::diagnostics`] found besides its report, and the generation of
    /// the velocity it read.
    reductions: Option<(u64, CachedReductions)>,
}

impl FluidSolver {
    /// A fluid at rest. Fails if the conditions do not fit the grid.
    pub fn new(
        grid: Grid,
        bc: BoundaryConditions,
        settings: FluidSettings,
    ) -> Result<Self, String> {
        bc.validate(&grid)?;
        if settings.nu.is_nan() || settings.nu <= 0.0 {
            return Err(format!("viscosity must be positive, got {}", settings.nu));
        }
        let layout = PaddedLayout::new(grid.n);
        // The grid's main arrays first, each reserved so that a failure is a message (the
        // memory check before this can be beaten by other processes).
        let zeros = || crate::memory::zeros(layout.len, "the fluid's velocity arrays");
        let u = [zeros()?, zeros()?, zeros()?];
        let q = [zeros()?, zeros()?, zeros()?];
        let p = crate::memory::zeros(grid.cell_count(), "the fluid's pressure")?;
        let axes = std::array::from_fn(|d| bc.pressure_axis(d));
        let poisson = SpectralPoisson::new(grid.n, grid.h, axes);
        let momentum_ranges =
            std::array::from_fn(|c| std::array::from_fn(|d| bc.momentum_range(grid.n, c, d)));
        let corrected_ranges =
            std::array::from_fn(|c| std::array::from_fn(|d| bc.corrected_range(grid.n, c, d)));
        let mut s = FluidSolver {
            u,
            q,
            p,
            source: None,
            mass_source: None,
            poisson,
            chebyshev: None,
            drive: None,
            time: 0.0,
            momentum_ranges,
            corrected_ranges,
            partials: vec![[0.0; 12]; layout.dims[2]],
            scalars: [0.0; 2],
            stages_taken: 0,
            impulse_pressure: Vec::new(),
            impulse_generation: None,
            generation: 0,
            reductions: None,
            grid,
            layout,
            bc,
            settings,
        };
        fill_velocity_ghosts(&s.layout, &s.bc, &mut s.u);
        s.set_scheme(s.settings.scheme)?;
        s.initialise_pressure();
        Ok(s)
    }

    pub fn grid(&self) -> &Grid {
        &self.grid
    }
    pub fn layout(&self) -> &PaddedLayout {
        &self.layout
    }
    pub fn boundary_conditions(&self) -> &BoundaryConditions {
        &self.bc
    }
    pub fn settings(&self) -> &FluidSettings {
        &self.settings
    }
    /// Changes the viscosity between steps.
    pub fn set_nu(&mut self, nu: f64) {
        self.settings.nu = nu;
    }
    /// Changes the uniform body force between steps.
    pub fn set_body_force(&mut self, f: [f64; 3]) {
        self.settings.body_force = f;
    }
    /// Changes the time scheme, preparing the Chebyshev stages' registers if it needs them
    /// (fails for `EulerRKC` with outlets).
    pub fn set_scheme(&mut self, scheme: TimeScheme) -> Result<(), String> {
        self.impulse_generation = None;
        if scheme.projections() > 1 {
            self.impulse_pressure.resize(self.grid.cell_count(), 0.0);
        } else {
            self.impulse_pressure = Vec::new();
        }
        if scheme.is_chebyshev() {
            if self.bc.has_outlet() {
                return Err("EulerRKC does not support outlets; use RK3 or Euler".into());
            }
            if self.chebyshev.is_none() {
                self.chebyshev = Some(ChebyshevDiffusion::new(
                    &self.layout,
                    self.grid.cell_count(),
                ));
            }
        } else {
            self.chebyshev = None;
            self.stages_taken = 0;
        }
        self.settings.scheme = scheme;
        Ok(())
    }
    pub fn time(&self) -> f64 {
        self.time
    }
    pub fn set_time(&mut self, t: f64) {
        self.time = t;
    }

    /// Velocity components on their faces, padded layout.
    pub fn velocity(&self) -> &[Vec<f64>; 3] {
        &self.u
    }
    /// Mutable velocity (padded); call [`Self::project`] after changing it.
    pub fn velocity_mut(&mut self) -> &mut [Vec<f64>; 3] {
        self.velocity_changes();
        &mut self.u
    }
    /// Kinematic pressure `p/ρ` (m²/s²) at cell centres, unpadded x-fastest layout.
    pub fn pressure(&self) -> &[f64] {
        &self.p
    }
    /// Mutable pressure (e.g. to load a case's initial `p`, divided by ρ).
    pub fn pressure_mut(&mut self) -> &mut [f64] {
        self.impulse_generation = None;
        &mut self.p
    }

    /// The pressure whose gradient, acting over the whole last step, gives the momentum the
    /// pressure exchanged in it (what a force lagged by one step must see): with several
    /// stages, `p̄ = Σ_s w_s p_s` (`TimeScheme::stage_pressure_weight`). The last
    /// stage's pressure alone holds little of the impulse the first stage gave when the
    /// spheres' velocities changed; a force read from it loses the added mass, which
    /// destabilises the explicit coupling of free spheres. The same as [`Self::pressure`]
    /// at a steady state, for the one-stage schemes, and before the first step.
    pub fn impulse_pressure(&self) -> &[f64] {
        if self.impulse_generation == Some(self.generation) {
            &self.impulse_pressure
        } else {
            &self.p
        }
    }

    /// Allocates (once) zeroed per-face source arrays, m/s², added to the body force.
    pub fn face_source_mut(&mut self) -> &mut [Vec<f64>; 3] {
        let len = self.layout.len;
        self.source
            .get_or_insert_with(|| [vec![0.0; len], vec![0.0; len], vec![0.0; len]])
    }

    /// Allocates (once) the zeroed per-cell mass source that hooks may set (see
    /// [`PredictedVelocity::mass_source`]).
    pub fn mass_source_mut(&mut self) -> &mut [f64] {
        let cells = self.grid.cell_count();
        self.mass_source.get_or_insert_with(|| vec![0.0; cells])
    }

    /// Drives the flow at a bulk velocity (`meanVelocityForce`); the direction must be
    /// periodic.
    pub fn set_mean_velocity_force(
        &mut self,
        drive: Option<MeanVelocityForce>,
    ) -> Result<(), String> {
        if let Some(d) = &drive {
            if d.direction > 2 || !matches!(self.bc.face(d.direction, 0), FaceCondition::Periodic) {
                return Err(format!(
                    "meanVelocityForce needs a periodic direction, got {}",
                    d.direction
                ));
            }
        }
        self.drive = drive;
        Ok(())
    }
    pub fn mean_velocity_force(&self) -> Option<&MeanVelocityForce> {
        self.drive.as_ref()
    }

    /// Sets every velocity sample from `f(component, position)`, then fills the boundary
    /// faces and ghosts from the conditions. Call [`Self::project`] if `f` is not discretely
    /// divergence-free.
    pub fn set_velocity(&mut self, f: impl Fn(usize, [f64; 3]) -> f64) {
        self.velocity_changes();
        let g = &self.grid;
        let l = &self.layout;
        for c in 0..3 {
            for k in 1..=l.n[2] + usize::from(c == 2) {
                for j in 1..=l.n[1] + usize::from(c == 1) {
                    for i in 1..=l.n[0] + usize::from(c == 0) {
                        let idx = [i, j, k];
                        let x: [f64; 3] = std::array::from_fn(|d| {
                            let offset = if d == c { 1.0 } else { 0.5 };
                            g.origin[d] + (idx[d] as f64 - offset) * g.h[d]
                        });
                        self.u[c][l.index(i, j, k)] = f(c, x);
                    }
                }
            }
        }
        for d in 0..3 {
            if matches!(self.bc.face(d, 0), FaceCondition::Empty) {
                self.u[d].iter_mut().for_each(|x| *x = 0.0);
            }
        }
        fill_velocity_ghosts(&self.layout, &self.bc, &mut self.u);
    }

    /// Sets the velocity from cell-centred values (unpadded x-fastest, as a case's
    /// `internalField`), interpolated to the faces to fourth order where the grid allows
    /// (see `staggered_transfer`); then the conditions fix the boundary faces. Call
    /// [`Self::project`] afterwards.
    pub fn set_cell_velocity(&mut self, cells: &[[f64; 3]]) {
        self.velocity_changes();
        faces_from_cells(&self.grid, &self.bc, &self.layout, cells, &mut self.u);
        for d in 0..3 {
            if matches!(self.bc.face(d, 0), FaceCondition::Empty) {
                self.u[d].iter_mut().for_each(|x| *x = 0.0);
            }
        }
        fill_velocity_ghosts(&self.layout, &self.bc, &mut self.u);
    }

    /// Makes the current velocity discretely divergence-free (one projection with unit
    /// weight), then sets the pressure consistent with it (see [`Self::initialise_pressure`]).
    pub fn project(&mut self) {
        self.velocity_changes();
        extrapolate_outlets(&self.layout, &self.bc, &mut self.u);
        fill_velocity_ghosts(&self.layout, &self.bc, &mut self.u);
        divergence_rhs(
            &mut self.p,
            &self.u,
            &self.layout,
            self.grid.h,
            &self.bc,
            1.0,
        );
        self.poisson.solve(&mut self.p);
        subtract_gradient(
            &mut self.u,
            &self.p,
            1.0,
            &self.layout,
            self.grid.h,
            &self.bc,
            &self.corrected_ranges,
        );
        fill_velocity_ghosts(&self.layout, &self.bc, &mut self.u);
        self.initialise_pressure();
    }

    /// Sets the pressure to the one the current velocity and forces imply: `∇²p = ∇·F` with
    /// `F = −∇·(uu) + ν∇²u + f` (zero normal `F` where the velocity is fixed), i.e. the pressure
    /// an explicit step would produce. `EulerRKC` corrects pressure increments, so starting
    /// from this pressure keeps a force balanced by pressure (fluid at rest under gravity)
    /// balanced from the first step. Called by [`Self::new`] and [`Self::project`].
    pub fn initialise_pressure(&mut self) {
        fill_velocity_ghosts(&self.layout, &self.bc, &mut self.u);
        let force = self.total_body_force();
        // The tendency F goes through `q`.
        for qc in self.q.iter_mut() {
            qc.iter_mut().for_each(|x| *x = 0.0);
        }
        let terms = MomentumTerms {
            layout: &self.layout,
            h: self.grid.h,
            nu: self.settings.nu,
            force,
            source: self.source.as_ref(),
            ranges: &self.momentum_ranges,
            convection: self.settings.convection,
        };
        accumulate_tendency(&mut self.q, &self.u, &terms, 0.0, 1.0);
        // The divergence reads the high boundary face, which a periodic direction shares
        // with the low one.
        for d in 0..3 {
            if matches!(self.bc.face(d, 0), FaceCondition::Periodic) {
                copy_plane(&self.layout, &mut self.q[d], d, self.layout.n[d] + 1, 1);
            }
        }
        divergence_rhs(
            &mut self.p,
            &self.q,
            &self.layout,
            self.grid.h,
            &self.bc,
            1.0,
        );
        self.poisson.solve(&mut self.p);
    }

    /// Cell-centred velocity into `out`, unpadded x-fastest, interpolated from the faces to
    /// fourth order where the grid allows (the two-point mean next to walls).
    pub fn cell_velocity(&self, out: &mut [[f64; 3]]) {
        cells_from_faces(&self.grid, &self.bc, &self.layout, &self.u, out);
    }

    /// The cell-centred velocity of one cell (unpadded x-fastest index), as
    /// [`Self::cell_velocity`] computes it: for writers that stream the field without a copy.
    pub fn cell_velocity_at(&self, index: usize) -> [f64; 3] {
        let n = self.grid.n;
        let cell = [index % n[0], (index / n[0]) % n[1], index / (n[0] * n[1])];
        let periodic = periodic_axes(&self.bc);
        cell_from_faces(&self.grid, periodic, &self.layout, &self.u, cell)
    }

    /// Names of the arrays [`Self::restart_arrays`] returns, in order.
    pub const RESTART_NAMES: [&'static str; 5] = ["U.x", "U.y", "U.z", "p", "scalars"];

    /// Every array a bit-identical continuation needs: the padded velocity components, the
    /// pressure, and `scalars = [time, meanVelocityForce gradient]`. The schemes keep no
    /// history between steps (the register `q` is overwritten by each step's first stage).
    pub fn restart_arrays(&mut self) -> Vec<(&'static str, &[f64])> {
        self.scalars = [self.time, self.drive.as_ref().map_or(0.0, |d| d.gradient)];
        vec![
            ("U.x", &self.u[0][..]),
            ("U.y", &self.u[1][..]),
            ("U.z", &self.u[2][..]),
            ("p", &self.p[..]),
            ("scalars", &self.scalars[..]),
        ]
    }

    /// Restores one array saved by [`Self::restart_arrays`].
    pub fn restore_array(&mut self, name: &str, data: &[f64]) -> Result<(), String> {
        self.velocity_changes();
        let target: &mut [f64] = match name {
            "U.x" => &mut self.u[0],
            "U.y" => &mut self.u[1],
            "U.z" => &mut self.u[2],
            "p" => &mut self.p,
            "scalars" => &mut self.scalars,
            _ => return Err(format!("unknown restart array '{name}'")),
        };
        if target.len() != data.len() {
            return Err(format!(
                "restart array '{name}' has {} values, expected {}",
                data.len(),
                target.len()
            ));
        }
        target.copy_from_slice(data);
        if name == "scalars" {
            self.time = self.scalars[0];
            if let Some(d) = self.drive.as_mut() {
                d.gradient = self.scalars[1];
            }
        }
        Ok(())
    }

    /// Bytes of state and work arrays per cell (velocity, pressure, register, sources,
    /// solver scratch).
    pub fn bytes_per_cell(&self) -> f64 {
        let padded = self.layout.len * 8;
        let arrays = 6 + if self.source.is_some() { 3 } else { 0 };
        let total = arrays * padded
            + self.p.len() * 8
            + self.poisson.scratch_bytes()
            + self.chebyshev.as_ref().map_or(0, |c| c.bytes())
            + self.partials.len() * 96;
        total as f64 / self.grid.cell_count() as f64
    }
}

/// `a[dst] = a[src]` over the padded plane normal to `d`.
fn copy_plane(layout: &PaddedLayout, a: &mut [f64], d: usize, dst: usize, src: usize) {
    let (d1, d2) = ((d + 1) % 3, (d + 2) % 3);
    let s = layout.stride;
    for b in 0..layout.dims[d2] {
        for c in 0..layout.dims[d1] {
            let base = c * s[d1] + b * s[d2];
            a[base + dst * s[d]] = a[base + src * s[d]];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn uniform_flow(nu: f64) -> FluidSolver {
        let grid = Grid::new([8, 8, 8], [0.1; 3], [0.0; 3]);
        let mut s =
            FluidSolver::new(grid, BoundaryConditions::periodic(), FluidSettings::new(nu)).unwrap();
        s.set_velocity(|c, _| if c == 0 { 1.0 } else { 0.0 });
        s
    }

    #[test]
    fn adaptive_step_follows_openfoam_rule_and_the_stability_bound() {
        let mut s = uniform_flow(1e-6);
        // Co per unit Δt = ½ (1 + 1) / 0.1 = 10.
        assert!((s.courant_rate() - 10.0).abs() < 1e-12);
        assert!((s.adaptive_dt(0.01, 0.5, 1.0) - 0.012).abs() < 1e-15); // grow by 20 %
        assert!((s.adaptive_dt(0.1, 0.5, 1.0) - 0.05).abs() < 1e-15); // shrink to maxCo
        assert!((s.adaptive_dt(0.04, 0.5, 1.0) - 0.045).abs() < 1e-15); // f = 1.25: 1 + 0.1 f
        assert!((s.adaptive_dt(0.01, 0.5, 0.011) - 0.011).abs() < 1e-15); // maxDeltaT
        let mut viscous = uniform_flow(1.0);
        let bound = viscous.stability_bound();
        assert!((bound - 2.51 / (4.0 * 300.0)).abs() < 1e-12); // RK3: 2.51 / (4ν Σ 1/h²)
        assert_eq!(viscous.adaptive_dt(0.01, 0.5, 1.0), bound);
    }

    /// The Courant rate the health check's diagnostics leave behind is the one a fresh
    /// evaluation gives, and every way of changing the velocity discards it.
    #[test]
    fn the_cached_courant_rate_follows_the_velocity() {
        let mut s = uniform_flow(1e-6);
        let fresh = s.diagnostics(1.0).max_courant;
        s.diagnostics(0.37);
        assert_eq!(s.courant_rate(), fresh);
        s.velocity_mut()[0].iter_mut().for_each(|x| *x *= 3.0);
        assert!((s.courant_rate() - 30.0).abs() < 1e-12);
        s.diagnostics(0.5);
        s.set_velocity(|c, _| if c == 1 { 2.0 } else { 0.0 });
        assert!((s.courant_rate() - 20.0).abs() < 1e-12);
        s.diagnostics(0.5);
        s.step(1e-3);
        assert_eq!(s.courant_rate(), s.diagnostics(1.0).max_courant);
        let saved: Vec<f64> = s.velocity()[1].iter().map(|x| 0.5 * x).collect();
        s.diagnostics(0.5);
        s.restore_array("U.y", &saved).unwrap();
        assert!((s.courant_rate() - 10.0).abs() < 1e-9);
    }

    /// The health check's pass leaves behind exactly what the separate passes of
    /// `max_speed` and `mean_component` find (a random field with walls along y, whose
    /// ghosts differ from the faces), and a change of the velocity discards it.
    #[test]
    fn the_cached_speeds_and_means_are_those_of_the_separate_passes() {
        let grid = Grid::new([9, 7, 6], [0.1, 0.12, 0.09], [0.0; 3]);
        let mut bc = BoundaryConditions::periodic();
        for side in 0..2 {
            bc.faces[2 + side] = FaceCondition::Wall {
                velocity: [0.7, 0.0, -0.4],
            };
        }
        let mut s = FluidSolver::new(grid, bc, FluidSettings::new(1e-3)).unwrap();
        let mut rng = crate::particles::SplitMix64::new(17);
        for u in s.velocity_mut().iter_mut() {
            u.iter_mut().for_each(|x| *x = 2.0 * rng.next_f64() - 1.0);
        }
        let separate = (s.max_speed(), [0, 1, 2].map(|c| s.mean_component(c)));
        s.diagnostics(0.01);
        assert!(s.cached_reductions().is_some());
        assert_eq!(
            (s.max_speed(), [0, 1, 2].map(|c| s.mean_component(c))),
            separate
        );
        s.velocity_mut()[1].iter_mut().for_each(|x| *x *= 3.0);
        assert!(s.cached_reductions().is_none());
        assert!((s.max_speed()[1] - 3.0 * separate.0[1]).abs() < 1e-12);
    }

    /// The four-lane pass gives, bit for bit, what one cell after another gives: on a
    /// random field whose rows (9 cells) end in a partial lane group, and on one with a
    /// NaN face, which must show as a blow-up.
    #[test]
    fn the_lane_diagnostics_are_those_of_one_cell_after_another() {
        let grid = Grid::new([9, 5, 3], [0.1, 0.12, 0.09], [0.0; 3]);
        let mut s = FluidSolver::new(
            grid,
            BoundaryConditions::periodic(),
            FluidSettings::new(1e-3),
        )
        .unwrap();
        let mut rng = crate::particles::SplitMix64::new(29);
        for u in s.velocity_mut().iter_mut() {
            u.iter_mut().for_each(|x| *x = 2.0 * rng.next_f64() - 1.0);
        }
        let one_by_one = |s: &FluidSolver| {
            let (l, h, u) = (s.layout(), s.grid().h, s.velocity());
            let (mut div, mut energy, mut courant) = (0.0f64, 0.0, 0.0f64);
            for k in 1..=l.n[2] {
                let mut plane = 0.0;
                for j in 1..=l.n[1] {
                    for i in 1..=l.n[0] {
                        let p = l.index(i, j, k);
                        let f = [
                            u[0][p],
                            u[0][p + 1],
                            u[1][p],
                            u[1][p + l.stride[1]],
                            u[2][p],
                            u[2][p + l.stride[2]],
                        ];
                        let d = (f[1] - f[0]) / h[0] + (f[3] - f[2]) / h[1] + (f[5] - f[4]) / h[2];
                        div = div.max(d.abs());
                        plane += 0.25 * f.iter().map(|x| x * x).sum::<f64>();
                        let co = 0.5
                            * ((f[0].abs() + f[1].abs()) / h[0]
                                + (f[2].abs() + f[3].abs()) / h[1]
                                + (f[4].abs() + f[5].abs()) / h[2]);
                        courant = courant.max(co);
                    }
                }
                energy += plane;
            }
            (div, energy / s.grid().cell_count() as f64, courant)
        };
        let expected = one_by_one(&s);
        let d = s.diagnostics(0.5);
        assert_eq!(
            (d.max_divergence, d.kinetic_energy, d.max_courant),
            (expected.0, expected.1, 0.5 * expected.2)
        );
        let p = s.layout().index(9, 5, 3);
        s.velocity_mut()[0][p] = f64::NAN;
        let d = s.diagnostics(0.5);
        assert!(d.divergence.is_nan() && d.kinetic_energy.is_nan());
        assert!(d.max_speed[0].is_finite() && d.max_courant.is_finite());
    }

    #[test]
    fn cell_velocity_and_bulk_mean_of_a_uniform_flow() {
        let mut s = uniform_flow(1e-3);
        let mut cells = vec![[0.0; 3]; 512];
        s.cell_velocity(&mut cells);
        assert!(cells.iter().all(|v| *v == [1.0, 0.0, 0.0]));
        assert_eq!(s.mean_component(0), 1.0);
        let d = s.diagnostics(0.01);
        assert!((d.kinetic_energy - 0.5).abs() < 1e-15);
        assert!((d.max_courant - 0.1).abs() < 1e-15);
        assert!(FluidSolver::new(
            s.grid().clone(),
            BoundaryConditions::periodic(),
            FluidSettings::new(-1.0)
        )
        .is_err());
    }
}
