//! The drag-law model's two validation curves of the paper (§3.1–3.2), for
//! `examples/drag_law_figures` and its test:
//!
//! - Fig. 2: the non-dimensional drag `K = f_h / (6 π μ r U)` (paper eq. 19, `U` the
//!   superficial mean velocity) of a simple cubic array of fixed spheres against the solid
//!   fraction φ, at `h ≈ 2r` (the box of one sphere has `round(L/2r)` cells), driven by a
//!   uniform pressure gradient `G` at Re ≪ 1; with Sangani & Acrivos (paper eq. 17) and
//!   Ergun/Wen–Yu (paper eq. 18).
//! - Fig. 3: the mean sedimentation velocity of a simple cubic lattice of free spheres in a
//!   periodic box against φ, relative to the zero-volume-flux frame and to the isolated
//!   sphere's terminal velocity `V₀` under the same closure, with Richardson & Zaki (paper
//!   eq. 21, n = 4.65).

use fsim::coupling::drag::{Convention, DragClosure, DragInput, DragLawCoupling, DragLawSettings};
use fsim::fluid::{BoundaryConditions, FluidSettings, FluidSolver};
use fsim::grid::Grid;
use fsim::particles::{
    Dem, DemConfig, DomainBox, FaceCondition as ParticleFace, PairModel, ParticleState, WallModel,
};
use fsim::simulation::DragLawModel;
use fsim::Vec3;
use std::f64::consts::PI;

const RHO: f64 = 1000.0;
const NU: f64 = 1e-6;
const RADIUS: f64 = 1e-4;

/// One row of Fig. 2.
pub struct PorousRow {
    pub phi: f64,
    pub cells: usize,
    pub k_drag_law: f64,
    pub k_sangani: f64,
    pub k_ergun: f64,
}

/// One row of Fig. 3.
pub struct SedimentationRow {
    pub phi: f64,
    pub particles: usize,
    pub v_over_v0: f64,
    pub richardson_zaki: f64,
}

/// Sangani & Acrivos (1982) for the simple cubic array (paper eq. 17).
pub fn k_sangani(phi: f64) -> f64 {
    1.0 / (1.0 - 1.7601 * phi.cbrt() + phi - 1.5593 * phi * phi + 3.9799 * phi.powf(8.0 / 3.0)
        - 3.0734 * phi.powf(10.0 / 3.0))
}

/// Paper eq. 18, as docs/numerics.md reads the garbled OCR copy: `(1 − φ)^−4.7` below
/// φ = 0.2, `(25/3) φ/(1 − φ)³` above.
pub fn k_ergun(phi: f64) -> f64 {
    if phi < 0.2 {
        (1.0 - phi).powf(-4.7)
    } else {
        25.0 / 3.0 * phi / (1.0 - phi).powi(3)
    }
}

fn periodic_dem(particles: ParticleState, length: f64, gravity: f64) -> Dem {
    let mut config = DemConfig::new(PairModel::linear(0.05, 0.5, 0.0), WallModel::None);
    config.gravity = Vec3::new(0.0, 0.0, -gravity);
    config.fluid_density = RHO;
    let domain = DomainBox::uniform([0.0; 3], [length; 3], ParticleFace::Periodic);
    Dem::new(config, domain, particles).expect("a valid cloud")
}

fn periodic_fluid(n: usize, length: f64) -> FluidSolver {
    let grid = Grid::new([n; 3], [length / n as f64; 3], [0.0; 3]);
    FluidSolver::new(grid, BoundaryConditions::periodic(), FluidSettings::new(NU)).unwrap()
}

/// Mean of `ε_f w` over the z faces: the superficial velocity along z.
fn superficial_z(coupling: &DragLawCoupling, fluid: &FluidSolver) -> f64 {
    let l = fluid.layout();
    let eps = coupling.fluid.fluid_fraction();
    let w = &fluid.velocity()[2];
    let n = l.n;
    let mut sum = 0.0;
    for k in 1..=n[2] {
        for j in 1..=n[1] {
            for i in 1..=n[0] {
                let f = l.index(i, j, k);
                sum += 0.5 * (eps[f] + eps[f - l.stride[2]]) * w[f];
            }
        }
    }
    sum / (n[0] * n[1] * n[2]) as f64
}

/// Fig. 2 at each φ with `closure` (drag-only closures in the paper's form, total ones in
/// DPMFoam's).
pub fn porous_media(phis: &[f64], closure: DragClosure, steps: usize) -> Vec<PorousRow> {
    phis.iter()
        .map(|&phi| {
            let unit = (4.0 * PI * RADIUS.powi(3) / (3.0 * phi)).cbrt();
            let cells = ((unit / (2.0 * RADIUS)).round() as usize).max(1);
            // The contact engine needs a periodic box of a few diameters: m³ copies of the unit.
            let copies = ((4.6 * RADIUS / unit).ceil() as usize).max(1);
            let length = unit * copies as f64;
            let mut fluid = periodic_fluid(cells * copies, length);
            let mut particles = ParticleState::with_capacity(copies.pow(3));
            let mut id = 0;
            for k in 0..copies {
                for j in 0..copies {
                    for i in 0..copies {
                        let c = |m: usize| (m as f64 + 0.5) * unit;
                        particles.push(id, [c(i), c(j), c(k)], 2.0 * RADIUS, 2500.0);
                        particles.fixed[id as usize] = true;
                        id += 1;
                    }
                }
            }
            let count = particles.len() as f64;
            let dem = periodic_dem(particles, length, 0.0);
            // G small enough for Re ≪ 1: U ~ G L³/(6πμr K). G is a mean pressure gradient
            // (as fsimFoam's meanVelocityForce imposes it), not a body force: the beads then
            // read ∇p from cell centres with their ε stencil, which conserves momentum, so
            // that Σ f_h = ρ G V_box exactly (the face-staggered reading a gravity-driven box
            // takes gives beads centred on a face plane, h = L/2, a spurious share of ∇p).
            let g = 1e-3;
            let mut s = DragLawSettings::paper(RHO, NU, Vec3::zeros());
            s.closure = Some(closure);
            s.form = match closure.convention() {
                Convention::DragOnly => fsim::fluid::VolumeAveragedForm::Paper,
                Convention::Total => fsim::fluid::VolumeAveragedForm::DpmFoam,
            };
            s.semi_implicit = true;
            let h = h_of(unit, cells);
            let dt = 0.1 * h * h / NU;
            let mut coupling = DragLawCoupling::new(s, &fluid, &dem).expect("a valid set-up");
            coupling.fluid.set_mean_pressure_gradient([0.0, 0.0, -g]);
            let mut model = DragLawModel::start(coupling, dem, &mut fluid, dt);
            for _ in 0..steps {
                step(&mut fluid, &mut model, dt);
            }
            model.apply_particle_forces(&fluid, dt);
            let force = model.coupling.last.hydrodynamic_force[2] / count;
            let u = superficial_z(&model.coupling, &fluid);
            PorousRow {
                phi,
                cells,
                k_drag_law: force / (6.0 * PI * RHO * NU * RADIUS * u),
                k_sangani: k_sangani(phi),
                k_ergun: k_ergun(phi),
            }
        })
        .collect()
}

/// The cell size of `cells` cells over `length`.
fn h_of(length: f64, cells: usize) -> f64 {
    length / cells as f64
}

/// The drag-law model of `dem` in `fluid` with settings `s`, its pressure initialised for
/// steps of `dt`.
fn drag_law_model(s: DragLawSettings, fluid: &mut FluidSolver, dem: Dem, dt: f64) -> DragLawModel {
    let coupling = DragLawCoupling::new(s, fluid, &dem).expect("a valid set-up");
    DragLawModel::start(coupling, dem, fluid, dt)
}

/// One step of the drag-law model, as fsimFoam takes it.
fn step(fluid: &mut FluidSolver, model: &mut DragLawModel, dt: f64) {
    model.step(fluid, dt).expect("ε above the floor");
}

/// The isolated sphere's terminal velocity under `closure` (ε = 1), by bisection.
fn terminal_velocity(closure: DragClosure, weight: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, 10.0);
    for _ in 0..200 {
        let w = 0.5 * (lo + hi);
        let q = DragInput {
            d: 2.0 * RADIUS,
            eps: 1.0,
            slip: w,
            rho: RHO,
            mu: RHO * NU,
        };
        if closure.coefficient(&q) * w > weight {
            hi = w
        } else {
            lo = w
        }
    }
    0.5 * (lo + hi)
}

/// Fig. 3 at each φ: `per_side³` spheres on a simple cubic lattice (slightly staggered so the
/// lattice is not a fixed point), settling from rest for `steps` steps; the velocity is the
/// mean over the last half.
pub fn sedimentation(
    phis: &[f64],
    closure: DragClosure,
    per_side: usize,
    steps: usize,
) -> Vec<SedimentationRow> {
    let rho_p = 2500.0;
    let g = 9.81;
    let volume = 4.0 / 3.0 * PI * RADIUS.powi(3);
    let v0 = terminal_velocity(closure, (rho_p - RHO) * volume * g);
    phis.iter()
        .map(|&phi| {
            let spacing = (volume / phi).cbrt();
            let length = spacing * per_side as f64;
            let cells = ((length / (2.0 * RADIUS)).round() as usize).max(1);
            let mut particles = ParticleState::with_capacity(per_side.pow(3));
            let mut id = 0;
            for k in 0..per_side {
                for j in 0..per_side {
                    for i in 0..per_side {
                        let wobble =
                            0.05 * spacing * (((i * 7 + j * 3 + k * 5) % 5) as f64 / 4.0 - 0.5);
                        particles.push(
                            id,
                            [
                                (i as f64 + 0.5) * spacing + wobble,
                                (j as f64 + 0.5) * spacing,
                                (k as f64 + 0.5) * spacing,
                            ],
                            2.0 * RADIUS,
                            rho_p,
                        );
                        id += 1;
                    }
                }
            }
            let count = particles.len();
            let mut fluid = periodic_fluid(cells, length);
            let dem = periodic_dem(particles, length, g);
            // The fluid carries the mean pressure gradient that holds the suspension's
            // buoyant weight, so the whole box does not accelerate.
            let hold = phi * (rho_p - RHO) / RHO * g;
            let mut s = DragLawSettings::paper(RHO, NU, Vec3::new(0.0, 0.0, hold));
            s.closure = Some(closure);
            s.form = match closure.convention() {
                Convention::DragOnly => fsim::fluid::VolumeAveragedForm::Paper,
                Convention::Total => fsim::fluid::VolumeAveragedForm::DpmFoam,
            };
            s.semi_implicit = true;
            let h = h_of(length, cells);
            let dt = (0.1 * h * h / NU).min(0.2 * h / v0);
            let mut model = drag_law_model(s, &mut fluid, dem, dt);
            let (mut sum, mut samples) = (0.0, 0);
            for k in 0..steps {
                step(&mut fluid, &mut model, dt);
                if k >= steps / 2 {
                    let vp = model.particles.dem.mean_velocity()[2];
                    // Zero-volume-flux frame: subtract j = ⟨ε u⟩ + φ v_p.
                    let j = superficial_z(&model.coupling, &fluid) + phi * vp;
                    sum += vp - j;
                    samples += 1;
                }
            }
            SedimentationRow {
                phi,
                particles: count,
                v_over_v0: -(sum / samples as f64) / v0,
                richardson_zaki: (1.0 - phi).powf(4.65),
            }
        })
        .collect()
}

/// The CSV text of Fig. 2.
pub fn porous_csv(rows: &[PorousRow], closure: DragClosure) -> String {
    let mut out = format!("# drag-law model ({}), simple cubic array, h = 2r\nphi,cells,K_dragLaw,K_Sangani,K_Ergun\n", closure.name());
    for r in rows {
        out += &format!(
            "{},{},{},{},{}\n",
            r.phi, r.cells, r.k_drag_law, r.k_sangani, r.k_ergun
        );
    }
    out
}

/// The CSV text of Fig. 3.
pub fn sedimentation_csv(rows: &[SedimentationRow], closure: DragClosure) -> String {
    let mut out = format!("# drag-law model ({}), periodic simple cubic lattice, h = 2r\nphi,particles,v_over_V0,RichardsonZaki\n", closure.name());
    for r in rows {
        out += &format!(
            "{},{},{},{}\n",
            r.phi, r.particles, r.v_over_v0, r.richardson_zaki
        );
    }
    out
}
