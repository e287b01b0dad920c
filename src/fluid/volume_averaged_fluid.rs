//! The volume-averaged Navier–Stokes equations of the drag-law model (paper eq. 7–9), advanced
//! on the staggered grid and storage of a [`FluidSolver`] (its velocity `u` is the
//! *interstitial* fluid velocity, its pressure the kinematic `p/ρ`).
//!
//! With fluid fraction `ε` (cells), face fraction `ε_f` (mean of the two cells), the particle
//! reaction `s` (m/s², from paper eq. 13, 16) and, for the semi-implicit source, the
//! coefficient `K` (1/s) of the drag's velocity dependence, fsim solves
//!
//! ```text
//! ∂(εu)/∂t + ∇·(εuu) = −c ∇p + ν ∇·(ε∇u) + c g + s + K (uⁿ − uⁿ⁺¹),    ∂ε/∂t + ∇·(εu) = 0,
//! ```
//!
//! with `c = ε` in the paper's form (paper eq. 7, "model A": the particles feel the pressure
//! gradient themselves, paper eq. 10) or `c = 1` in DPMFoam's form ("model B":
//! `fvm::ddt(alphac, Uc)` with `−∇p + g` undivided in its `UcEqn.H`/`pEqn.H`; the particles'
//! `gravity` force carries their buoyancy and they feel no pressure gradient). In DPMFoam's
//! non-conservative writing `ε ∂u/∂t + εu·∇u` is the same operator by continuity. Two
//! simplifications against paper eq. 7–8: the viscous stress is `ν∇·(ε∇u)` (the transposed
//! and `−⅔∇·u` parts of `T_ij` are dropped; they vanish where ε is uniform), and advection is
//! first-order upwind (the bed's drag dominates; DPMFoam's tutorials use `linearUpwind`).
//!
//! One step (explicit Euler for advection and diffusion, implicit in `K`):
//! 1. predictor `A_f u*_f = ε_fⁿ uⁿ/Δt + K uⁿ + [−∇·(εuu) + ν∇·(ε∇u)]ⁿ + c g + s` with
//!    `A_f = ε_fⁿ⁺¹/Δt + K`;
//! 2. pressure: `u = u* − (c/A_f) ∇p` and `∇·(ε_f uⁿ⁺¹) = −(εⁿ⁺¹ − εⁿ)/Δt` give
//!    `∇·(β ∇p) = ∇·(ε_f u*) + (εⁿ⁺¹ − εⁿ)/Δt` with `β = ε_f c / A_f`, solved by
//!    [`VariablePoisson`] (preconditioned CG);
//! 3. correction `u = u* − (c/A_f) ∇p`.
//!
//! The pressure includes the fluid's weight (as DPMFoam's `p`), so `g` also serves as a
//! uniform driving acceleration for periodic porous-media flows.
//!
//! In a fully periodic box the pressure is periodic and cannot hold up the mixture's weight,
//! so the whole suspension would free-fall. A uniform kinematic mean pressure gradient `G`
//! (set by the coupling, [`VolumeAveragedFluid::set_mean_pressure_gradient`]) stands for the
//! non-periodic part of the pressure: the body acceleration `c g` becomes `c (g − G)`. With
//! `G = (ρ_mix/ρ_f) g`, `ρ_mix = (M_fluid + M_particles)/V_box`, fluid and particles together
//! feel no net external force (in the paper's form the particles' share `−V_p ρ_f G` of paper
//! eq. 10 is added by the coupling).

use super::boundary_conditions::{BoundaryConditions, FaceCondition};
use super::fluid_solver::FluidSolver;
use super::ghost_fill::{extrapolate_outlets, fill_velocity_ghosts};
use super::padded_layout::PaddedLayout;
use super::projection::subtract_gradient;
use super::variable_poisson::{Convergence, PcgReport, VariablePoisson};
use super::volume_averaged_viscosity::{face_diffusivities, ViscousReport, ViscousSolve};
use crate::grid::Grid;
use rayon::prelude::*;

/// Which volume-averaged momentum equation the fluid solves (see the module notes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VolumeAveragedForm {
    /// Paper eq. 7: `−ε∇p + εg`; particles feel `−V∇p` (paper eq. 10).
    Paper,
    /// DPMFoam v1912: `−∇p + g`; particles feel no pressure gradient.
    DpmFoam,
}

impl VolumeAveragedForm {
    pub fn name(self) -> &'static str {
        match self {
            VolumeAveragedForm::Paper => "paper",
            VolumeAveragedForm::DpmFoam => "DPMFoam",
        }
    }
}

/// What one volume-averaged step did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeAveragedReport {
    pub pressure: PcgReport,
    /// `max |∇·(ε_f u) + ∂ε/∂t|` after the step, 1/s (the discrete continuity error).
    pub continuity_error: f64,
    /// The implicit viscous solves (zero with the explicit viscous term).
    pub viscous: ViscousReport,
}

/// The volume-averaged fluid's own state and work arrays (the velocity and pressure stay in
/// the [`FluidSolver`]). Padded arrays use the solver's [`PaddedLayout`].
pub struct VolumeAveragedFluid {
    form: VolumeAveragedForm,
    gravity: [f64; 3],
    /// Uniform kinematic mean pressure gradient `G`, m/s² (zero unless set).
    mean_pressure_gradient: [f64; 3],
    nu: f64,
    grid: Grid,
    layout: PaddedLayout,
    bc: BoundaryConditions,
    momentum_ranges: [[(usize, usize); 3]; 3],
    corrected_ranges: [[(usize, usize); 3]; 3],
    /// Cell fluid fraction after and before the particles' last move, padded with
    /// zero-gradient (or periodic) ghosts.
    eps: Vec<f64>,
    eps_old: Vec<f64>,
    /// Explicit particle source `s`, m/s², per face (padded).
    source: [Vec<f64>; 3],
    /// Implicit drag coefficient `K`, 1/s, per face (padded).
    coefficient: [Vec<f64>; 3],
    /// `A_f` of the last step, per face.
    diagonal: [Vec<f64>; 3],
    /// Face pressure gradient `∇p` of the last step, m/s², per face.
    gradient: [Vec<f64>; 3],
    predicted: [Vec<f64>; 3],
    poisson: VariablePoisson,
    rhs: Vec<f64>,
    p_work: Vec<f64>,
    outlet_pressure: Option<f64>,
    /// Inlet faces whose velocity is superficial (DPMFoam's `interstitialInletVelocity`: the
    /// face carries `U_in/ε_f`, so the volume flux is `U_in` whatever the bed next to it).
    superficial_inlets: [bool; 6],
    /// When the pressure CG stops (default `‖r‖₂ ≤ 10⁻¹⁰ ‖f‖₂`; a case's `pFinal` solver
    /// sets OpenFOAM's test).
    pub convergence: Convergence,
    pub max_iterations: usize,
    /// The implicit viscous term's solve (`EulerImplicit`, backward Euler); `None`: explicit.
    viscous: Option<ViscousSolve>,
}

impl VolumeAveragedFluid {
    /// The volume-averaged model on `fluid`'s grid and conditions, `ε = 1` everywhere.
    /// Fails when outlets fix different pressures (the CG solves for `p − p_out`).
    pub fn new(
        fluid: &FluidSolver,
        form: VolumeAveragedForm,
        gravity: [f64; 3],
    ) -> Result<Self, String> {
        let grid = fluid.grid().clone();
        let layout = fluid.layout().clone();
        let bc = fluid.boundary_conditions().clone();
        let mut outlet_pressure = None;
        for d in 0..3 {
            for side in 0..2 {
                if let Some(p) = bc.outlet_pressure(d, side) {
                    match outlet_pressure {
                        Some(q) if q != p => {
                            return Err(format!(
                                "the drag-law model needs one outlet pressure, got {q} and {p}"
                            ))
                        }
                        _ => outlet_pressure = Some(p),
                    }
                }
            }
        }
        let axes = std::array::from_fn(|d| bc.pressure_axis(d));
        let poisson = VariablePoisson::new(grid.n, grid.h, axes);
        let zeros = || [(); 3].map(|_| vec![0.0; layout.len]);
        let cells = grid.cell_count();
        Ok(VolumeAveragedFluid {
            form,
            gravity,
            mean_pressure_gradient: [0.0; 3],
            nu: fluid.settings().nu,
            momentum_ranges: std::array::from_fn(|c| {
                std::array::from_fn(|d| bc.momentum_range(grid.n, c, d))
            }),
            corrected_ranges: std::array::from_fn(|c| {
                std::array::from_fn(|d| bc.corrected_range(grid.n, c, d))
            }),
            eps: vec![1.0; layout.len],
            eps_old: vec![1.0; layout.len],
            source: zeros(),
            coefficient: zeros(),
            diagonal: zeros(),
            gradient: zeros(),
            predicted: zeros(),
            poisson,
            rhs: vec![0.0; cells],
            p_work: vec![0.0; cells],
            outlet_pressure,
            superficial_inlets: [false; 6],
            convergence: Convergence::Relative(1e-10),
            max_iterations: 500,
            viscous: None,
            grid,
            layout,
            bc,
        })
    }

    pub fn form(&self) -> VolumeAveragedForm {
        self.form
    }

    /// Treats the viscous term implicitly (`true`, the `EulerImplicit` scheme: backward Euler
    /// as OpenFOAM's `Euler` with `fvm::laplacian`; no viscous bound on `Δt`) or explicitly
    /// (`false`, the default). Backward Euler damps the stiff viscous modes; Crank–Nicolson
    /// does not (`(1 − a)/(1 + a) → −1`), and with walls or a varying ε the pressure
    /// splitting makes them grow (docs/numerics.md, "The drag-law model").
    pub fn set_implicit_viscosity(&mut self, on: bool) {
        if !on {
            self.viscous = None;
        } else if self.viscous.is_none() {
            self.viscous = Some(ViscousSolve::new(
                &self.layout,
                &self.bc,
                &self.momentum_ranges,
            ));
        }
    }

    /// Whether the viscous term is implicit.
    pub fn implicit_viscosity(&self) -> bool {
        self.viscous.is_some()
    }

    /// The predictor in words, for the log.
    pub fn predictor_name(&self) -> &'static str {
        if self.implicit_viscosity() {
            "EulerImplicit predictor: implicit viscous term"
        } else {
            "explicit Euler predictor"
        }
    }
    pub fn gravity(&self) -> [f64; 3] {
        self.gravity
    }
    /// The uniform kinematic mean pressure gradient `G` (m/s²) added to the periodic pressure.
    pub fn mean_pressure_gradient(&self) -> [f64; 3] {
        self.mean_pressure_gradient
    }
    /// Sets `G`: the fluid's body acceleration becomes `c (g − G)` (see the module notes).
    pub fn set_mean_pressure_gradient(&mut self, gradient: [f64; 3]) {
        self.mean_pressure_gradient = gradient;
    }
    pub fn layout(&self) -> &PaddedLayout {
        &self.layout
    }
    pub fn grid(&self) -> &Grid {
        &self.grid
    }
    pub fn boundary_conditions(&self) -> &BoundaryConditions {
        &self.bc
    }
    /// Padded index ranges where component `c`'s momentum is advanced (per direction).
    pub fn momentum_ranges(&self) -> &[[(usize, usize); 3]; 3] {
        &self.momentum_ranges
    }

    /// Marks inlet faces (order x−, x+, y−, y+, z−, z+) whose velocity is superficial.
    pub fn set_superficial_inlets(&mut self, faces: [bool; 6]) {
        self.superficial_inlets = faces;
    }

    /// Ghost layers and boundary faces from the conditions, then superficial inlets divided
    /// by the face's ε.
    fn fill_ghosts(&self, u: &mut [Vec<f64>; 3]) {
        fill_velocity_ghosts(&self.layout, &self.bc, u);
        for d in 0..3 {
            for side in 0..2 {
                if !self.superficial_inlets[2 * d + side] {
                    continue;
                }
                if !matches!(self.bc.face(d, side), FaceCondition::Inlet { .. }) {
                    continue;
                }
                let l = &self.layout;
                let slot = if side == 0 { 1 } else { l.n[d] + 1 };
                let cell = if side == 0 { 1 } else { l.n[d] };
                let (d1, d2) = ((d + 1) % 3, (d + 2) % 3);
                let s = l.stride;
                for b in 1..=l.n[d2] {
                    for c in 1..=l.n[d1] {
                        let base = c * s[d1] + b * s[d2];
                        u[d][base + slot * s[d]] /= self.eps[base + cell * s[d]];
                    }
                }
            }
        }
    }

    /// Fluid fraction per cell, padded (ghosts filled).
    pub fn fluid_fraction(&self) -> &[f64] {
        &self.eps
    }

    /// Fluid fraction per cell into `out`, unpadded x-fastest.
    pub fn cell_fluid_fraction(&self, out: &mut [f64]) {
        let [n0, n1, n2] = self.grid.n;
        for k in 0..n2 {
            for j in 0..n1 {
                let base = self.layout.index(1, j + 1, k + 1);
                out[n0 * (j + n1 * k)..n0 * (j + 1 + n1 * k)]
                    .copy_from_slice(&self.eps[base..base + n0]);
            }
        }
    }

    /// The new fluid fraction (unpadded cells) after the particles moved; the previous one
    /// becomes `εⁿ`.
    pub fn advance_fluid_fraction(&mut self, cells: &[f64]) {
        std::mem::swap(&mut self.eps, &mut self.eps_old);
        self.store_cells(cells);
    }

    /// Sets `εⁿ = εⁿ⁺¹` from unpadded cells (at start and on restart).
    pub fn reset_fluid_fraction(&mut self, cells: &[f64]) {
        self.store_cells(cells);
        self.eps_old.copy_from_slice(&self.eps);
    }

    fn store_cells(&mut self, cells: &[f64]) {
        let [n0, n1, n2] = self.grid.n;
        assert_eq!(cells.len(), n0 * n1 * n2);
        for k in 0..n2 {
            for j in 0..n1 {
                let base = self.layout.index(1, j + 1, k + 1);
                self.eps[base..base + n0]
                    .copy_from_slice(&cells[n0 * (j + n1 * k)..n0 * (j + 1 + n1 * k)]);
            }
        }
        fill_cell_ghosts(&self.layout, &self.bc, &mut self.eps);
    }

    /// Explicit source `s` (m/s²) and implicit coefficient `K` (1/s) per face, padded: the
    /// coupling zeroes and fills them before each step.
    pub fn sources_mut(&mut self) -> (&mut [Vec<f64>; 3], &mut [Vec<f64>; 3]) {
        (&mut self.source, &mut self.coefficient)
    }
    pub fn source(&self) -> &[Vec<f64>; 3] {
        &self.source
    }
    pub fn coefficient(&self) -> &[Vec<f64>; 3] {
        &self.coefficient
    }

    /// Face pressure gradient `∇p` (kinematic, m/s²) on the corrected faces, padded.
    pub fn pressure_gradient(&self) -> &[Vec<f64>; 3] {
        &self.gradient
    }

    /// Recomputes [`Self::pressure_gradient`] from the fluid's pressure (after a restart).
    pub fn update_pressure_gradient(&mut self, fluid: &FluidSolver) {
        for g in self.gradient.iter_mut() {
            g.iter_mut().for_each(|x| *x = 0.0);
        }
        subtract_gradient(
            &mut self.gradient,
            fluid.pressure(),
            -1.0,
            &self.layout,
            self.grid.h,
            &self.bc,
            &self.corrected_ranges,
        );
    }

    /// `Δt` bound of the predictor: `1/(Σ|u|_max/h + 2ν Σ 1/h²)` with the explicit viscous
    /// term, `1/(Σ|u|_max/h)` (upwind advection) with the implicit one: a Fourier mode of the 1-D
    /// scheme is multiplied by `(1 − Co(1 − e^{−iθ}))/(1 + a)`, `a ≥ 0`, of modulus at most 1
    /// when `Co ≤ 1`.
    pub fn stability_bound(&self, fluid: &FluidSolver) -> f64 {
        let speed = fluid.max_speed();
        let viscous = if self.implicit_viscosity() { 0.0 } else { 2.0 };
        let mut rate = 0.0;
        for d in 0..3 {
            if !matches!(self.bc.face(d, 0), FaceCondition::Empty) {
                let h = self.grid.h[d];
                rate += speed[d] / h + viscous * self.nu / (h * h);
            }
        }
        if rate > 0.0 {
            1.0 / rate
        } else {
            f64::INFINITY
        }
    }

    /// The explicit viscous part of the bound alone, `1/(2ν Σ 1/h²)`.
    #[cfg(test)]
    fn stability_bound_explicit_viscous(&self) -> f64 {
        let rate: f64 = (0..3)
            .filter(|&d| !matches!(self.bc.face(d, 0), FaceCondition::Empty))
            .map(|d| 2.0 * self.nu / (self.grid.h[d] * self.grid.h[d]))
            .sum();
        1.0 / rate
    }

    /// The face coefficient `c` of the pressure gradient and gravity (ε_f or 1).
    #[inline]
    fn pressure_factor(&self, eps_face: f64) -> f64 {
        match self.form {
            VolumeAveragedForm::Paper => eps_face,
            VolumeAveragedForm::DpmFoam => 1.0,
        }
    }

    /// Advances `fluid` by `dt` (see the module notes); `εⁿ⁺¹` and the sources must be set:
    /// [`Self::predict_momentum`], then [`Self::correct_pressure`].
    pub fn step(&mut self, fluid: &mut FluidSolver, dt: f64) -> VolumeAveragedReport {
        self.predict_momentum(fluid, dt);
        self.correct_pressure(fluid, dt)
    }

    /// Paper eq. 7's momentum equation without the new pressure: `u*` on the momentum faces
    /// from `uⁿ`, `εⁿ`, `εⁿ⁺¹`, the particles' source and the body force (step 1 of the
    /// module notes).
    pub fn predict_momentum(&mut self, fluid: &mut FluidSolver, dt: f64) {
        self.fill_ghosts(fluid.velocity_mut());
        if let Some(v) = self.viscous.as_mut() {
            v.reset_report();
        }
        self.predict(fluid.velocity(), dt);
        {
            let u = fluid.velocity_mut();
            for c in 0..3 {
                let r = self.momentum_ranges[c];
                for k in r[2].0..=r[2].1 {
                    for j in r[1].0..=r[1].1 {
                        let a = self.layout.index(r[0].0, j, k);
                        let b = self.layout.index(r[0].1, j, k);
                        if r[0].0 <= r[0].1 {
                            u[c][a..=b].copy_from_slice(&self.predicted[c][a..=b]);
                        }
                    }
                }
            }
            extrapolate_outlets(&self.layout, &self.bc, u);
        }
        self.fill_ghosts(fluid.velocity_mut());
    }

    /// Paper eq. 7's continuity, `∇·(ε u) = −∂ε/∂t`: the pressure that makes the predicted
    /// velocity meet it, and the velocity corrected by its gradient (steps 2–3); the fluid's
    /// time moves on by `dt`.
    pub fn correct_pressure(&mut self, fluid: &mut FluidSolver, dt: f64) -> VolumeAveragedReport {
        let t0 = fluid.time();
        let pressure = self.solve_pressure(fluid, dt);
        self.correct(fluid);
        fluid.set_time(t0 + dt);
        let continuity_error = self.continuity_error(fluid.velocity(), dt);
        VolumeAveragedReport {
            pressure,
            continuity_error,
            viscous: self
                .viscous
                .as_ref()
                .map(|v| v.report())
                .unwrap_or_default(),
        }
    }

    /// Step 1: `A_f` on every face and `predicted = u*` on the momentum faces; with
    /// the implicit viscous term, `predicted = u* + (c/A_f) ∇pⁿ`, the velocity the pressure equation
    /// corrects: the predictor holds the last pressure gradient and the correction removes it
    /// with the new one, `uⁿ⁺¹ = u* − (c/A_f) ∇(pⁿ⁺¹ − pⁿ)` — the incremental pressure
    /// correction (Goda 1979), stable with the implicit viscous term, its steady state the
    /// explicit scheme's — while the pressure solve keeps the whole `p` (and a case's
    /// `pFinal` test its meaning).
    fn predict(&mut self, u: &[Vec<f64>; 3], dt: f64) {
        let l = &self.layout;
        let s = l.stride;
        let h = self.grid.h;
        // The implicit share θ of the viscous term: 1 (backward Euler) or 0.
        let implicit = self.implicit_viscosity();
        let theta = if implicit { 1.0 } else { 0.0 };
        // ν times the explicit share of the viscous term (exactly ν when explicit).
        let nu_explicit = (1.0 - theta) * self.nu;
        let coupling: [f64; 3] = std::array::from_fn(|d| theta * self.nu / (h[d] * h[d]));
        let (eps, eps_old) = (&self.eps[..], &self.eps_old[..]);
        let form = self.form;
        // Body acceleration `g − G` (G = 0 unless the box is fully periodic).
        let gravity: [f64; 3] =
            std::array::from_fn(|c| self.gravity[c] - self.mean_pressure_gradient[c]);
        let plane = l.plane_len();
        for c in 0..3 {
            let r = self.momentum_ranges[c];
            let sc = s[c];
            let uc = &u[c][..];
            let (src, kc) = (&self.source[c][..], &self.coefficient[c][..]);
            // A_f on every face of the padded interior (boundary faces included: the
            // pressure equation needs β there for outlets).
            let dims = l.dims;
            self.diagonal[c]
                .par_chunks_mut(plane)
                .enumerate()
                .for_each(|(k, dk)| {
                    // Slots 1..=n, and n + 1 along the component's own direction.
                    let top = |d: usize| dims[d] - 2 + usize::from(d == c);
                    if k == 0 || k > top(2) {
                        return;
                    }
                    for j in 1..=top(1) {
                        for i in 1..=top(0) {
                            let f = i + dims[0] * j;
                            let g = f + k * plane;
                            let ef = 0.5 * (eps[g] + eps[g - sc]);
                            dk[f] = ef / dt + kc[g];
                        }
                    }
                });
            let diag = &self.diagonal[c][..];
            let old_gradient = &self.gradient[c][..];
            // The explicit predictor writes u* itself, the implicit one its right-hand side.
            let target = match self.viscous.as_mut() {
                Some(v) => &mut v.rhs,
                None => &mut self.predicted[c],
            };
            target
                .par_chunks_mut(plane)
                .enumerate()
                .for_each(|(k, pk)| {
                    if k < r[2].0 || k > r[2].1 {
                        return;
                    }
                    for j in r[1].0..=r[1].1 {
                        for i in r[0].0..=r[0].1 {
                            let f = l.index(i, j, k);
                            let ef_old = 0.5 * (eps_old[f] + eps_old[f - sc]);
                            let ef_new = 0.5 * (eps[f] + eps[f - sc]);
                            let mut tendency = 0.0;
                            for d in 0..3 {
                                let sd = s[d];
                                let (e_lo, e_hi) = face_diffusivities(eps_old, f, c, d, s);
                                let (m_lo, up_lo, m_hi, up_hi);
                                if d == c {
                                    m_hi = e_hi * 0.5 * (uc[f] + uc[f + sc]);
                                    m_lo = e_lo * 0.5 * (uc[f - sc] + uc[f]);
                                    up_hi = if m_hi > 0.0 { uc[f] } else { uc[f + sc] };
                                    up_lo = if m_lo > 0.0 { uc[f - sc] } else { uc[f] };
                                } else {
                                    let ud = &u[d][..];
                                    m_lo = e_lo * 0.5 * (ud[f] + ud[f - sc]);
                                    m_hi = e_hi * 0.5 * (ud[f + sd] + ud[f + sd - sc]);
                                    up_lo = if m_lo > 0.0 { uc[f - sd] } else { uc[f] };
                                    up_hi = if m_hi > 0.0 { uc[f] } else { uc[f + sd] };
                                }
                                tendency -= (m_hi * up_hi - m_lo * up_lo) / h[d];
                                tendency += nu_explicit
                                    * (e_hi * (uc[f + sd] - uc[f]) - e_lo * (uc[f] - uc[f - sd]))
                                    / (h[d] * h[d]);
                            }
                            let factor = match form {
                                VolumeAveragedForm::Paper => ef_new,
                                VolumeAveragedForm::DpmFoam => 1.0,
                            };
                            let rhs = ef_old * uc[f] / dt
                                + kc[f] * uc[f]
                                + tendency
                                + factor * gravity[c]
                                + src[f];
                            pk[f - k * plane] = if implicit {
                                rhs - factor * old_gradient[f]
                            } else {
                                rhs / diag[f]
                            };
                        }
                    }
                });
            if let Some(v) = self.viscous.as_mut() {
                // u* from uⁿ (its ghosts filled), then HbyA = u* + (c/A_f) ∇pⁿ.
                let x = &mut self.predicted[c];
                x.copy_from_slice(uc);
                v.solve(c, x, diag, eps_old, coupling);
                for k in r[2].0..=r[2].1 {
                    for j in r[1].0..=r[1].1 {
                        for i in r[0].0..=r[0].1 {
                            let f = l.index(i, j, k);
                            let factor = match form {
                                VolumeAveragedForm::Paper => 0.5 * (eps[f] + eps[f - sc]),
                                VolumeAveragedForm::DpmFoam => 1.0,
                            };
                            x[f] += factor / diag[f] * old_gradient[f];
                        }
                    }
                }
            }
        }
    }

    /// Step 2: `∇·(β∇p) = ∇·(ε_f u*) + (εⁿ⁺¹ − εⁿ)/Δt` for `p − p_out`.
    fn solve_pressure(&mut self, fluid: &mut FluidSolver, dt: f64) -> PcgReport {
        let n = self.grid.n;
        let l = &self.layout;
        // β on the solver's faces: face m along d is padded slot m + 1.
        for d in 0..3 {
            let mut m = n;
            m[d] += 1;
            let sd = l.stride[d];
            for k in 0..m[2] {
                for j in 0..m[1] {
                    for i in 0..m[0] {
                        let f = l.index(i + 1, j + 1, k + 1);
                        let ef = 0.5 * (self.eps[f] + self.eps[f - sd]);
                        let beta = ef * self.pressure_factor(ef) / self.diagonal[d][f];
                        let fi = self.poisson.face_index(d, i, j, k);
                        self.poisson.beta_mut()[d][fi] = beta;
                    }
                }
            }
        }
        self.superficial_divergence(fluid.velocity(), dt, false);
        let shift = self.outlet_pressure.unwrap_or(0.0);
        for (w, p) in self.p_work.iter_mut().zip(fluid.pressure()) {
            *w = p - shift;
        }
        let report = self.poisson.solve_to(
            &self.rhs,
            &mut self.p_work,
            self.convergence,
            self.max_iterations,
        );
        for (p, w) in fluid.pressure_mut().iter_mut().zip(&self.p_work) {
            *p = w + shift;
        }
        report
    }

    /// `rhs = ∇·(ε_f u) + (εⁿ⁺¹ − εⁿ)/Δt` per cell, unpadded; with `max_only`, returns only
    /// its largest magnitude.
    fn superficial_divergence(&mut self, u: &[Vec<f64>; 3], dt: f64, max_only: bool) -> f64 {
        let l = &self.layout;
        let [n0, n1, _] = self.grid.n;
        let s = l.stride;
        let h = self.grid.h;
        let (eps, eps_old) = (&self.eps[..], &self.eps_old[..]);
        let face = |c: usize, f: usize| 0.5 * (eps[f] + eps[f - s[c]]) * u[c][f];
        let mut largest = 0.0f64;
        let rhs = &mut self.rhs;
        let maxima: Vec<f64> = rhs
            .par_chunks_mut(n0 * n1)
            .enumerate()
            .map(|(k, plane)| {
                let mut m = 0.0f64;
                for j in 0..n1 {
                    for i in 0..n0 {
                        let f = l.index(i + 1, j + 1, k + 1);
                        let mut div = (eps[f] - eps_old[f]) / dt;
                        for c in 0..3 {
                            div += (face(c, f + s[c]) - face(c, f)) / h[c];
                        }
                        if max_only {
                            m = m.max(div.abs());
                        } else {
                            plane[i + n0 * j] = div;
                        }
                    }
                }
                m
            })
            .collect();
        for m in maxima {
            largest = largest.max(m);
        }
        largest
    }

    /// Step 3: `u = u* − (c/A_f) ∇p` on the corrected faces.
    fn correct(&mut self, fluid: &mut FluidSolver) {
        self.update_pressure_gradient(fluid);
        let l = &self.layout;
        let s = l.stride;
        let plane = l.plane_len();
        let eps = &self.eps[..];
        let form = self.form;
        let u = fluid.velocity_mut();
        for c in 0..3 {
            let r = self.corrected_ranges[c];
            let (g, a) = (&self.gradient[c][..], &self.diagonal[c][..]);
            u[c].par_chunks_mut(plane).enumerate().for_each(|(k, uk)| {
                if k < r[2].0 || k > r[2].1 {
                    return;
                }
                for j in r[1].0..=r[1].1 {
                    for i in r[0].0..=r[0].1 {
                        let f = l.index(i, j, k);
                        let factor = match form {
                            VolumeAveragedForm::Paper => 0.5 * (eps[f] + eps[f - s[c]]),
                            VolumeAveragedForm::DpmFoam => 1.0,
                        };
                        uk[f - k * plane] -= factor / a[f] * g[f];
                    }
                }
            });
        }
        self.fill_ghosts(u);
    }

    /// The superficial mean velocity along `d`, `⟨ε u⟩_d = Σ_faces ε_f u_f / N_faces` over the
    /// faces where component `d` is advanced: the `U` of paper eq. 19.
    pub fn superficial_mean(&self, u: &[Vec<f64>; 3], d: usize) -> f64 {
        let l = &self.layout;
        let sd = l.stride[d];
        let r = self.momentum_ranges[d];
        let eps = &self.eps[..];
        let (mut sum, mut count) = (0.0, 0usize);
        for k in r[2].0..=r[2].1 {
            for j in r[1].0..=r[1].1 {
                for i in r[0].0..=r[0].1 {
                    let f = l.index(i, j, k);
                    sum += 0.5 * (eps[f] + eps[f - sd]) * u[d][f];
                    count += 1;
                }
            }
        }
        sum / count as f64
    }

    /// `meanVelocityForce` on the volume-averaged equations: holds the *superficial* mean
    /// `⟨ε u⟩_d` at `Ubar` (paper eq. 19's `U`, the same quantity the direct model's drive
    /// holds, so that one `Ubar` means one flow rate in both models). After the step the gap
    /// `δ = relaxation (Ubar − ⟨ε u⟩_d)` raises the driving gradient by `δG = δ/Δt` (a
    /// uniform mean pressure gradient: the body acceleration `c (g − G)` of paper eq. 7 gains
    /// `c δG` along `d`, and in the paper's form each particle feels `V ρ δG` of paper eq. 10),
    /// and closes the gap at once by `u_f += δ/ε_f` on every face along `d`: a uniform
    /// superficial flux, so `∇·(ε_f u) + ∂ε/∂t` is unchanged (continuity holds exactly).
    /// (DPMFoam's fvOption holds the plain mean of the interstitial `Uc` instead; the two
    /// differ by about the factor ε.) Returns the driving gradient `G_drive`, m/s².
    pub fn hold_superficial_velocity(
        &mut self,
        fluid: &mut FluidSolver,
        drive: &mut super::MeanVelocityForce,
        dt: f64,
    ) -> f64 {
        let d = drive.direction;
        let bulk = self.superficial_mean(fluid.velocity(), d);
        let dg = drive.increment(bulk, dt);
        drive.gradient += dg;
        // G is the mean of ∂p/∂x: a driving gradient along +d is a negative mean gradient.
        self.mean_pressure_gradient[d] -= dg;
        let shift = dt * dg;
        let l = &self.layout;
        let sd = l.stride[d];
        let r = self.momentum_ranges[d];
        let eps = &self.eps[..];
        let u = fluid.velocity_mut();
        for k in r[2].0..=r[2].1 {
            for j in r[1].0..=r[1].1 {
                for i in r[0].0..=r[0].1 {
                    let f = l.index(i, j, k);
                    u[d][f] += shift / (0.5 * (eps[f] + eps[f - sd]));
                }
            }
        }
        self.fill_ghosts(u);
        drive.gradient
    }

    /// `max |∇·(ε_f u) + ∂ε/∂t|` for the current velocity.
    pub fn continuity_error(&mut self, u: &[Vec<f64>; 3], dt: f64) -> f64 {
        self.superficial_divergence(u, dt, true)
    }

    /// Bytes of the model's own arrays per cell.
    pub fn bytes_per_cell(&self) -> f64 {
        let padded = self.layout.len * 8;
        let viscous = if self.viscous.is_some() {
            ViscousSolve::PADDED_ARRAYS
        } else {
            0
        };
        let total =
            (2 + 5 * 3 + viscous) * padded + 2 * self.rhs.len() * 8 + 9 * self.rhs.len() * 8;
        total as f64 / self.grid.cell_count() as f64
    }
}

/// Ghost cells of a padded cell array: wrapped on periodic directions, copied from the
/// boundary cell (zero gradient) elsewhere. Directions in the order x, y, z over the whole
/// padded extent of the others, so edges and corners are consistent.
pub(crate) fn fill_cell_ghosts(layout: &PaddedLayout, bc: &BoundaryConditions, a: &mut [f64]) {
    for d in 0..3 {
        let n = layout.n[d];
        let periodic = matches!(bc.face(d, 0), FaceCondition::Periodic);
        let (lo_src, hi_src) = if periodic { (n, 1) } else { (1, n) };
        let (d1, d2) = ((d + 1) % 3, (d + 2) % 3);
        let s = layout.stride;
        for b in 0..layout.dims[d2] {
            for c in 0..layout.dims[d1] {
                let base = c * s[d1] + b * s[d2];
                a[base] = a[base + lo_src * s[d]];
                a[base + (n + 1) * s[d]] = a[base + hi_src * s[d]];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluid::{FluidSettings, FluidSolver};

    fn column(nz: usize) -> FluidSolver {
        // Periodic in x and y, inlet at the bottom, outlet (p = 0) at the top.
        let grid = Grid::new([4, 4, nz], [0.01; 3], [0.0; 3]);
        let bc = BoundaryConditions {
            faces: [
                FaceCondition::Periodic,
                FaceCondition::Periodic,
                FaceCondition::Periodic,
                FaceCondition::Periodic,
                FaceCondition::Inlet {
                    velocity: [0.0, 0.0, 0.1],
                },
                FaceCondition::Outlet { pressure: 0.0 },
            ],
        };
        FluidSolver::new(grid, bc, FluidSettings::new(1e-5)).unwrap()
    }

    #[test]
    fn fluid_at_rest_under_gravity_is_hydrostatic_in_both_forms() {
        for form in [VolumeAveragedForm::Paper, VolumeAveragedForm::DpmFoam] {
            let grid = Grid::new([3, 3, 6], [0.1; 3], [0.0; 3]);
            let wall = FaceCondition::Wall { velocity: [0.0; 3] };
            let bc = BoundaryConditions {
                faces: std::array::from_fn(|_| wall.clone()),
            };
            let mut fluid = FluidSolver::new(grid, bc, FluidSettings::new(1e-3)).unwrap();
            let mut va = VolumeAveragedFluid::new(&fluid, form, [0.0, 0.0, -9.81]).unwrap();
            // A non-uniform but steady ε: the fluid must stay at rest, p = −g z + const.
            let cells: Vec<f64> = (0..54).map(|c| 0.5 + 0.05 * (c % 7) as f64).collect();
            va.reset_fluid_fraction(&cells);
            for _ in 0..3 {
                va.step(&mut fluid, 1e-3);
            }
            let speed = fluid.max_speed();
            assert!(speed.iter().all(|s| *s < 1e-10), "{form:?}: {speed:?}");
            let p = fluid.pressure();
            // Adjacent cells in z differ by g h = 0.981 m²/s².
            for c in 0..54 - 9 {
                assert!((p[c] - p[c + 9] - 0.981).abs() < 1e-9, "{form:?}");
            }
        }
    }

    #[test]
    fn uniform_inflow_through_a_fixed_porous_layer_conserves_superficial_flux() {
        let mut fluid = column(8);
        let mut va = VolumeAveragedFluid::new(&fluid, VolumeAveragedForm::Paper, [0.0; 3]).unwrap();
        // ε = 0.5 in the middle layers: the interstitial velocity doubles there.
        let cells: Vec<f64> = (0..128)
            .map(|c| if (2..6).contains(&(c / 16)) { 0.5 } else { 1.0 })
            .collect();
        va.reset_fluid_fraction(&cells);
        for _ in 0..200 {
            let r = va.step(&mut fluid, 2e-3);
            assert!(r.continuity_error < 1e-8, "{}", r.continuity_error);
        }
        let l = fluid.layout().clone();
        let w = &fluid.velocity()[2];
        // Face between layers 3 and 4 (both ε = 0.5): w = 0.2; at the outlet w = 0.1.
        assert!(
            (w[l.index(2, 2, 5)] - 0.2).abs() < 1e-6,
            "{}",
            w[l.index(2, 2, 5)]
        );
        assert!((w[l.index(2, 2, 9)] - 0.1).abs() < 1e-6);
    }

    #[test]
    fn implicit_viscosity_reaches_the_explicit_steady_state_at_24_times_the_viscous_step() {
        // Gravity drives a viscous fluid down a periodic column between two walls, through a
        // layer of varying ε: the steady discrete equations depend neither on Δt nor on the
        // treatment of the viscous term. (With an outlet they would: its zero-gradient
        // predictor adds (cΔt/ε)(∇p_n − ∇p_out) to the outflow, in either scheme.)
        let steady = |implicit: bool, dt: f64, steps: usize| {
            let grid = Grid::new([4, 4, 8], [0.01; 3], [0.0; 3]);
            let wall = FaceCondition::Wall { velocity: [0.0; 3] };
            let periodic = FaceCondition::Periodic;
            let bc = BoundaryConditions {
                faces: [
                    wall.clone(),
                    wall,
                    periodic.clone(),
                    periodic.clone(),
                    periodic.clone(),
                    periodic,
                ],
            };
            let mut fluid = FluidSolver::new(grid, bc, FluidSettings::new(1e-2)).unwrap();
            let mut va =
                VolumeAveragedFluid::new(&fluid, VolumeAveragedForm::Paper, [0.0, 0.0, -2.0])
                    .unwrap();
            va.set_implicit_viscosity(implicit);
            let cells: Vec<f64> = (0..128)
                .map(|c| {
                    if (2..6).contains(&(c / 16)) {
                        0.5 + 0.03 * (c % 5) as f64
                    } else {
                        1.0
                    }
                })
                .collect();
            va.reset_fluid_fraction(&cells);
            let mut last = None;
            for _ in 0..steps {
                last = Some(va.step(&mut fluid, dt));
            }
            (fluid, va.stability_bound_explicit_viscous(), last.unwrap())
        };
        // Explicit at 0.6 of its viscous bound; implicit at 24 times it (a Courant number of
        // about 0.4 in the layer).
        let (_, viscous_bound, _) = steady(false, 1e-3, 1);
        let (explicit, _, _) = steady(false, 0.6 * viscous_bound, 3000);
        let (implicit, _, report) = steady(true, 24.0 * viscous_bound, 600);
        assert!(report.continuity_error < 1e-7, "{report:?}");
        let l = explicit.layout().clone();
        let (mut worst, mut speed) = (0.0f64, 0.0f64);
        for c in 0..3 {
            for k in 1..=8 {
                for j in 1..=4 {
                    for i in 1..=4 {
                        let f = l.index(i, j, k);
                        let d = explicit.velocity()[c][f] - implicit.velocity()[c][f];
                        worst = worst.max(d.abs());
                        speed = speed.max(explicit.velocity()[c][f].abs());
                    }
                }
            }
        }
        assert!(speed > 0.01, "the column does not flow: {speed}");
        // (the implicit solve stops at 1e-6 of its right-hand side)
        assert!(
            worst < 1e-6 * speed,
            "velocity differs by {worst:e} of {speed} m/s"
        );
    }

    #[test]
    fn implicit_viscosity_decays_a_shear_wave_at_first_order_beyond_the_explicit_bound() {
        // u(y) = sin(2πy/L) in a periodic box, ε = 1: no advection, the amplitude decays as
        // exp(−ν λ t) with the discrete Laplacian's λ = (4/h²) sin²(kh/2).
        let n = 16;
        let h = 1.0 / n as f64;
        let nu = 0.01;
        let grid = Grid::new([4, n, 4], [h; 3], [0.0; 3]);
        let mut fluid = FluidSolver::new(
            grid.clone(),
            BoundaryConditions::periodic(),
            FluidSettings::new(nu),
        )
        .unwrap();
        let mut va =
            VolumeAveragedFluid::new(&fluid, VolumeAveragedForm::DpmFoam, [0.0; 3]).unwrap();
        va.set_implicit_viscosity(true);
        let k = 2.0 * std::f64::consts::PI;
        let l = fluid.layout().clone();
        for kk in 1..=4 {
            for j in 1..=n {
                for i in 1..=4 {
                    let y = (j as f64 - 0.5) * h;
                    fluid.velocity_mut()[0][l.index(i, j, kk)] = (k * y).sin();
                }
            }
        }
        let explicit_bound = h * h / (6.0 * nu);
        let lambda = 4.0 / (h * h) * (0.5 * k * h).sin().powi(2);
        let end = 120.0 * explicit_bound;
        let (j, y) = (3, 2.5 * h);
        let mut errors = Vec::new();
        for steps in [40i32, 80] {
            let mut u = fluid.velocity().clone();
            let dt = end / f64::from(steps);
            let mut run = FluidSolver::new(
                grid.clone(),
                BoundaryConditions::periodic(),
                FluidSettings::new(nu),
            )
            .unwrap();
            std::mem::swap(run.velocity_mut(), &mut u);
            for _ in 0..steps {
                va.step(&mut run, dt);
            }
            let amplitude = run.velocity()[0][l.index(2, j, 2)] / (k * y).sin();
            // The scheme's own amplification per step, 1/(1 + νΔtλ).
            let scheme = (1.0 / (1.0 + nu * dt * lambda)).powi(steps);
            assert!(
                (amplitude / scheme - 1.0).abs() < 1e-5,
                "{amplitude} vs {scheme}"
            );
            errors.push((amplitude / (-nu * lambda * end).exp() - 1.0).abs());
        }
        // First order in time (backward Euler): 3 and 1.5 times the explicit bound.
        let order = (errors[0] / errors[1]).log2();
        assert!(
            errors[0] < 0.15 && (0.9..1.1).contains(&order),
            "{errors:?}, order {order}"
        );
    }

    #[test]
    fn cell_ghosts_wrap_or_copy() {
        let l = PaddedLayout::new([3, 2, 2]);
        let bc = BoundaryConditions {
            faces: [
                FaceCondition::Periodic,
                FaceCondition::Periodic,
                FaceCondition::Slip,
                FaceCondition::Slip,
                FaceCondition::Slip,
                FaceCondition::Slip,
            ],
        };
        let mut a: Vec<f64> = (0..l.len).map(|i| i as f64).collect();
        fill_cell_ghosts(&l, &bc, &mut a);
        assert_eq!(a[l.index(0, 1, 1)], a[l.index(3, 1, 1)]);
        assert_eq!(a[l.index(4, 1, 1)], a[l.index(1, 1, 1)]);
        assert_eq!(a[l.index(1, 0, 1)], a[l.index(1, 1, 1)]);
        assert_eq!(a[l.index(1, 3, 1)], a[l.index(1, 2, 1)]);
    }
}
