//! What a case asks of the solvers, read into their settings: the fluid's time scheme, its
//! boundary conditions and driving, the drag-law model, and the direct model's resolution
//! warnings. Every condition the solvers cannot honour is an input error here.

use crate::case::{
    Case, Cloud, CouplingModel, PatchType, PressureBc, PressureSolverControls, StartFrom,
    VelocityBc,
};
use crate::coupling::direct::{check_resolution, DirectSettings, PeriodicBox};
use crate::coupling::drag::DragLawCoupling;
use crate::error::FsimError;
use crate::fluid::{
    BoundaryConditions, Convergence, FaceCondition, FluidSolver, MeanVelocityForce, TimeScheme,
};
use crate::particles::Dem;
use crate::Vec3;

/// `fsim { timeScheme EulerImplicit; }`: the drag-law predictor with its viscous term implicit.
const DRAG_LAW_IMPLICIT: &str = "EulerImplicit";

/// The fluid's scheme from `fsim { timeScheme …; }`, and whether the drag-law predictor takes
/// its viscous term implicitly. The drag-law model steps the fluid with its own
/// volume-averaged predictor: there the scheme names its viscous term (`Euler`, the default,
/// or `EulerImplicit`), and the resolved solver is built with `Euler`, which needs no stage
/// storage.
pub(super) fn fluid_scheme(case: &Case) -> Result<(TimeScheme, bool), FsimError> {
    let drag_law_case =
        case.coupling.model == CouplingModel::DragLaw && case.cloud_properties.is_some();
    if drag_law_case && !case.convection {
        return Err(FsimError::input(
            "system/fvSolution: fsim { convection off; } is for the resolved fluid (model none \
             or direct); the drag-law model's predictor keeps its advection (DPMFoam's UcEqn)",
        ));
    }
    Ok(match (&case.time_scheme, drag_law_case) {
        (None, true) => (TimeScheme::Euler, false),
        (Some(name), true) => match name.as_str() {
            "Euler" => (TimeScheme::Euler, false),
            DRAG_LAW_IMPLICIT => (TimeScheme::Euler, true),
            other => {
                return Err(case
                    .time_scheme_error(format!(
                        "the drag-law model runs timeScheme Euler (explicit viscous term, the \
                         default) or {DRAG_LAW_IMPLICIT} (implicit viscous term), not '{other}'"
                    ))
                    .into())
            }
        },
        (None, false) => (TimeScheme::default(), false),
        (Some(name), false) => {
            let scheme = TimeScheme::from_name(name).ok_or_else(|| {
                let hint = if name == DRAG_LAW_IMPLICIT {
                    " (EulerImplicit is the drag-law model's)"
                } else {
                    ""
                };
                let names: Vec<&str> = TimeScheme::ALL.iter().map(|s| s.name()).collect();
                case.time_scheme_error(format!(
                    "unknown fsim timeScheme '{name}'; expected one of {}{hint}",
                    names.join(", ")
                ))
            })?;
            (scheme, false)
        }
    })
}

/// The drag-law model of a case with `model dragLaw` and a cloud (`None` otherwise).
pub(super) fn drag_law(
    case: &Case,
    cloud: &Cloud,
    fluid: &FluidSolver,
    dem: &Dem,
    implicit_viscosity: bool,
) -> Result<Option<DragLawCoupling>, FsimError> {
    let Some(read) = &cloud.drag_law else {
        return Ok(None);
    };
    let settings = read.settings(&case.transport, case.gravity);
    let mut coupling = DragLawCoupling::new(settings, fluid, dem)
        .map_err(|e| FsimError::input(format!("drag-law model: {e}")))?;
    coupling.fluid.set_implicit_viscosity(implicit_viscosity);
    let superficial = std::array::from_fn(|face| {
        matches!(
            case.fields.u_bc[case.mesh.face_patch[face]],
            VelocityBc::InterstitialInletVelocity { .. }
        )
    });
    coupling.fluid.set_superficial_inlets(superficial);
    // DPMFoam's stopping test for its final pressure corrector (case/pressure_solver.rs).
    if let Some(fv_solution) = &case.fv_solution {
        if let Some(c) = PressureSolverControls::from_fv_solution(fv_solution)? {
            coupling.fluid.convergence = Convergence::OpenFoam {
                tolerance: c.tolerance,
                rel_tol: c.rel_tol,
            };
            if let Some(max) = c.max_iter {
                coupling.fluid.max_iterations = max;
            }
        }
    }
    // A box periodic on all faces cannot hold the mixture's weight with its periodic pressure.
    coupling.carry_mixture_weight(dem);
    Ok(Some(coupling))
}

/// Whether the case starts from the latest time directory.
pub fn continues(case: &Case) -> bool {
    case.control.start_from == StartFrom::LatestTime
}

/// The `meanVelocityForce` of the case, along the one axis its `Ubar` points.
pub(super) fn mean_velocity_force(case: &Case) -> Result<Option<MeanVelocityForce>, FsimError> {
    match case.mean_velocity_forces.as_slice() {
        [] => Ok(None),
        [one] => {
            let axes: Vec<usize> = (0..3).filter(|&d| one.ubar[d] != 0.0).collect();
            match axes.as_slice() {
                [d] => Ok(Some(MeanVelocityForce::new(
                    *d,
                    one.ubar[*d],
                    one.relaxation,
                ))),
                _ => Err(FsimError::input(format!(
                    "fvOptions '{}': fsim drives the flow along one axis; Ubar ({} {} {}) \
                     must have exactly one non-zero component",
                    one.name, one.ubar[0], one.ubar[1], one.ubar[2]
                ))),
            }
        }
        _ => Err(FsimError::input(
            "fvOptions: fsim takes at most one meanVelocityForce".to_string(),
        )),
    }
}

/// The solver's condition on each box face, from the patch type and the `U`/`p` conditions
/// the case gives it.
///
/// DPMFoam's pairs: `noSlip` + `fixedFluxPressure` is a wall; `interstitialInletVelocity` +
/// `fixedFluxPressure` an [`FaceCondition::Inlet`] whose velocity is the *superficial*
/// `inletVelocity` (the volumetric flux per area; the interstitial velocity on the face is
/// `inletVelocity / ε`, see [`interstitial_inlets`]); `pressureInletOutletVelocity` +
/// `fixedValue` p an [`FaceCondition::Outlet`] at that pressure, which lets the flow enter as
/// well as leave (its normal velocity follows the pressure; on back-flow the tangential
/// velocity stays zero-gradient where OpenFOAM takes `inletValue`'s); `symmetry` a slip face.
pub fn boundary_conditions(case: &Case) -> Result<BoundaryConditions, FsimError> {
    let mesh = &case.mesh;
    let fields = &case.fields;
    let mut faces: [FaceCondition; 6] = std::array::from_fn(|_| FaceCondition::Periodic);
    for (face, slot) in faces.iter_mut().enumerate() {
        let index = mesh.face_patch[face];
        let patch = &mesh.patches[index];
        let (u, p) = (&fields.u_bc[index], &fields.p_bc[index]);
        let cannot = || {
            FsimError::input(format!(
                "0/{} and 0/p: fsim cannot honour U '{}' with p '{}' on patch '{}' ({})",
                fields.velocity_name,
                velocity_bc_name(u),
                pressure_bc_name(p),
                patch.name,
                patch.kind.name()
            ))
        };
        *slot = match patch.kind {
            PatchType::Cyclic => FaceCondition::Periodic,
            PatchType::Empty => FaceCondition::Empty,
            PatchType::Symmetry | PatchType::SymmetryPlane => FaceCondition::Slip,
            PatchType::Wall | PatchType::Patch => match (u, p) {
                (VelocityBc::Slip, _) => FaceCondition::Slip,
                (VelocityBc::NoSlip, PressureBc::ZeroGradient | PressureBc::FixedFluxPressure) => {
                    FaceCondition::Wall { velocity: [0.0; 3] }
                }
                (
                    VelocityBc::FixedValue(v),
                    PressureBc::ZeroGradient | PressureBc::FixedFluxPressure,
                ) => {
                    if patch.kind == PatchType::Wall {
                        FaceCondition::Wall { velocity: *v }
                    } else {
                        FaceCondition::Inlet { velocity: *v }
                    }
                }
                (
                    VelocityBc::InterstitialInletVelocity { inlet_velocity, .. },
                    PressureBc::ZeroGradient | PressureBc::FixedFluxPressure,
                ) => FaceCondition::Inlet {
                    velocity: *inlet_velocity,
                },
                (
                    VelocityBc::ZeroGradient
                    | VelocityBc::PressureInletOutletVelocity
                    | VelocityBc::InletOutlet { .. },
                    PressureBc::FixedValue(p0) | PressureBc::TotalPressure { p0 },
                ) => FaceCondition::Outlet { pressure: *p0 },
                _ => return Err(cannot()),
            },
        };
    }
    Ok(BoundaryConditions { faces })
}

/// The superficial inlet velocity (`inletVelocity` of an `interstitialInletVelocity`) of each
/// box face that has one. The face's [`FaceCondition::Inlet`] carries the same vector; a
/// volume-averaged fluid imposes `ε_f u·n = inletVelocity·n` there, i.e. the interstitial
/// velocity `inletVelocity / ε_f` with `ε_f` the fraction of the adjacent cell (DPMFoam's
/// `alpha.air` is zero-gradient on patches).
pub fn interstitial_inlets(case: &Case) -> [Option<[f64; 3]>; 6] {
    std::array::from_fn(|face| {
        let index = case.mesh.face_patch[face];
        match &case.fields.u_bc[index] {
            VelocityBc::InterstitialInletVelocity { inlet_velocity, .. } => Some(*inlet_velocity),
            _ => None,
        }
    })
}

fn velocity_bc_name(bc: &VelocityBc) -> &'static str {
    match bc {
        VelocityBc::NoSlip => "noSlip",
        VelocityBc::FixedValue(_) => "fixedValue",
        VelocityBc::ZeroGradient => "zeroGradient",
        VelocityBc::Cyclic => "cyclic",
        VelocityBc::Symmetry => "symmetry",
        VelocityBc::SymmetryPlane => "symmetryPlane",
        VelocityBc::Slip => "slip",
        VelocityBc::Empty => "empty",
        VelocityBc::PressureInletOutletVelocity => "pressureInletOutletVelocity",
        VelocityBc::InletOutlet { .. } => "inletOutlet",
        VelocityBc::InterstitialInletVelocity { .. } => "interstitialInletVelocity",
    }
}

fn pressure_bc_name(bc: &PressureBc) -> &'static str {
    match bc {
        PressureBc::ZeroGradient => "zeroGradient",
        PressureBc::FixedFluxPressure => "fixedFluxPressure",
        PressureBc::FixedValue(_) => "fixedValue",
        PressureBc::TotalPressure { .. } => "totalPressure",
        PressureBc::Cyclic => "cyclic",
        PressureBc::Symmetry => "symmetry",
        PressureBc::SymmetryPlane => "symmetryPlane",
        PressureBc::Empty => "empty",
    }
}

/// The direct model's resolution warnings on the case's particles (gaps narrower than 2h,
/// fixed spheres with nothing driving the flow), for `-dry-run` and the log.
pub(super) fn check_direct_resolution(
    fluid: &FluidSolver,
    cloud: &Cloud,
    settings: &DirectSettings,
) -> Vec<String> {
    let grid = fluid.grid();
    let bc = fluid.boundary_conditions();
    let length = grid.length();
    let domain = PeriodicBox {
        lo: grid.origin.into(),
        hi: Vec3::from_fn(|a, _| grid.origin[a] + length[a]),
        periodic: std::array::from_fn(|a| matches!(bc.faces[2 * a], FaceCondition::Periodic)),
    };
    let walls: [bool; 6] =
        std::array::from_fn(|f| matches!(bc.faces[f], FaceCondition::Wall { .. }));
    let mut particles = cloud.particles.clone();
    if settings.fixed_particles {
        particles.fixed.iter_mut().for_each(|f| *f = true);
    }
    let moving_wall = bc.faces.iter().any(|f| match f {
        FaceCondition::Wall { velocity } => *velocity != [0.0; 3],
        FaceCondition::Inlet { .. } => true,
        _ => false,
    });
    let driven = fluid.mean_velocity_force().is_some() || moving_wall;
    let report = check_resolution(
        grid,
        &particles,
        &domain,
        walls,
        driven,
        // overlaps are the DEM loader's to report, with the positions file's line
        f64::INFINITY,
    );
    // Its errors (r/h below 2, a sphere wider than the box) are reported, with the particle
    // named, by `DirectCoupling::check_particles` and the DEM loader; here the warnings.
    report.warnings
}
