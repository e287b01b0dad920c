//! DPMFoam's Goldschmidt tutorial (Debian's `openfoam-examples`, read in place when installed,
//! never copied into the repository) loads unchanged: the drag-law options, the fluid's
//! boundary conditions, the particles and the grid are those of its files. Broken copies (in a
//! scratch directory) give clear errors at the file, line and column.

use fsim::Vec3;
use std::fs;
use std::path::{Path, PathBuf};

use crate::support::*;
use fsim::case::{
    Case, Cloud, Interpolation, ParticleIntegration, SourceTreatment, VelocityBc, VoidFraction,
};
use fsim::coupling::drag::DragClosure;
use fsim::fluid::{FaceCondition, VolumeAveragedForm};
use fsim::simulation::{boundary_conditions, interstitial_inlets};

const GOLDSCHMIDT: &str =
    "/usr/share/doc/openfoam-examples/examples/lagrangian/DPMFoam/Goldschmidt";

/// The installed case, or `None` (with a note) when the examples are not installed.
fn goldschmidt() -> Option<PathBuf> {
    let dir = Path::new(GOLDSCHMIDT);
    if dir.is_dir() {
        Some(dir.to_path_buf())
    } else {
        println!(
            "note: {GOLDSCHMIDT} is absent; install Debian's openfoam-examples to run this test"
        );
        None
    }
}

#[test]
fn goldschmidt_loads_unchanged_with_its_drag_law_options() {
    let Some(dir) = goldschmidt() else { return };
    let case = Case::load(&dir).unwrap_or_else(|e| panic!("{}", e.report()));
    // blockMeshDict: (2 30 90) cells over 15 x 150 x 450 mm
    assert_eq!(case.mesh.grid.n, [2, 30, 90]);
    assert_eq!(case.mesh.grid.cell_count(), 5_400);
    for (h, want) in case.mesh.grid.h.iter().zip([0.0075, 0.005, 0.005]) {
        assert!((h - want).abs() < 1e-15, "{h}");
    }
    // transportProperties: continuousPhase air; rho.air 1.2; nu 1e-05
    assert_eq!(case.transport.phase, "air");
    assert_eq!((case.transport.rho, case.transport.nu), (1.2, 1e-5));
    // no constant/couplingProperties: the drag-law model
    assert_eq!(case.coupling.model.name(), "dragLaw");

    let cloud = Cloud::from_case(&case)
        .unwrap_or_else(|e| panic!("{}", e.report()))
        .expect("an active cloud");
    assert_eq!(cloud.particles.len(), 24_750);
    let o = cloud.drag_law.as_ref().expect("drag-law options");
    // particleForces { ErgunWenYuDrag { alphac alpha.air; } gravity; }
    assert_eq!(o.drag, DragClosure::ErgunWenYu);
    assert!(o.gravity && !o.pressure_gradient);
    // sourceTerms { schemes { U semiImplicit 1; } }; constantProperties { alphaMax 0.99; }
    assert_eq!(o.source, SourceTreatment::SemiImplicit);
    assert_eq!(o.alpha_max, 0.99);
    // interpolationSchemes { U.air cellPoint; }; no averagingMethod; integrationSchemes Euler
    assert_eq!(o.velocity_interpolation, Interpolation::CellPoint);
    assert_eq!(o.void_fraction, VoidFraction::Cell);
    assert_eq!(o.integration, ParticleIntegration::Euler);
    assert_eq!(o.form, VolumeAveragedForm::DpmFoam);
    let settings = o.settings(&case.transport, case.gravity);
    assert!(settings.semi_implicit);
    assert_eq!(settings.gravity, Vec3::new(0.0, 0.0, -9.81));

    // 0/U.air and 0/p: frontAndBack symmetry (x), walls noSlip + fixedFluxPressure (y),
    // bottom interstitialInletVelocity (0 0 1.875) + fixedFluxPressure, top
    // pressureInletOutletVelocity + fixedValue 0.
    let bc = boundary_conditions(&case).unwrap_or_else(|e| panic!("{e}"));
    let wall = FaceCondition::Wall { velocity: [0.0; 3] };
    assert_eq!(
        bc.faces,
        [
            FaceCondition::Slip,
            FaceCondition::Slip,
            wall.clone(),
            wall,
            FaceCondition::Inlet {
                velocity: [0.0, 0.0, 1.875]
            },
            FaceCondition::Outlet { pressure: 0.0 },
        ]
    );
    assert_eq!(
        interstitial_inlets(&case),
        [None, None, None, None, Some([0.0, 0.0, 1.875]), None]
    );
    let bottom = case.mesh.face_patch[4];
    assert_eq!(
        case.fields.u_bc[bottom],
        VelocityBc::InterstitialInletVelocity {
            inlet_velocity: [0.0, 0.0, 1.875],
            alpha: "alpha.air".into()
        }
    );

    // What fsim does differently is listed; turbulenceProperties.air is read, not listed.
    let notes: Vec<&String> = case.warnings.iter().chain(&cloud.warnings).collect();
    for n in &notes {
        println!("note: {n}");
    }
    let has = |s: &str| notes.iter().any(|n| n.contains(s));
    // cellPoint is done as OpenFOAM does it: nothing to list
    assert!(!has("cellPoint"));
    assert!(has(
        "patch 'top' pressureInletOutletVelocity: where the flow enters"
    ));
    assert!(has("integrationSchemes U Euler"));
    assert!(!has("turbulenceProperties") && !has("simulationType"));
    assert!(!has("alphaMax") && !has("sourceTerms") && !has("interpolationSchemes"));
}

/// A copy of the installed case in a scratch directory, edited by `edit`.
fn broken_copy(tag: &str, edit: impl Fn(&Path)) -> Option<(Scratch, PathBuf)> {
    let dir = goldschmidt()?;
    let scratch = Scratch::new(tag);
    let case = scratch.0.join("Goldschmidt");
    copy_case(&dir, &case);
    edit(&case);
    Some((scratch, case))
}

fn replace(file: &Path, from: &str, to: &str) {
    let text = fs::read_to_string(file).unwrap();
    assert!(text.contains(from), "{} lacks {from}", file.display());
    fs::write(file, text.replacen(from, to, 1)).unwrap();
}

#[test]
fn unknown_drag_model_is_named_with_file_and_line() {
    let Some((_s, case)) = broken_copy("dpm-drag", |c| {
        replace(
            &c.join("constant/kinematicCloudProperties"),
            "ErgunWenYuDrag",
            "ErgunWenYuDarg",
        )
    }) else {
        return;
    };
    // fsimFoam: exit 2, the place, nothing written
    refused(
        &case,
        "fsimFoam: error: constant/kinematicCloudProperties:66:9: unknown drag model \
         'ErgunWenYuDarg'",
    );
    let case = Case::load(&case).unwrap_or_else(|e| panic!("{}", e.report()));
    let e = Cloud::from_case(&case).unwrap_err();
    assert_eq!(e.file.as_deref(), Some("constant/kinematicCloudProperties"));
    assert_eq!((e.line, e.col), (66, 9), "{e}");
    assert!(
        e.message
            .starts_with("unknown drag model 'ErgunWenYuDarg' in particleForces (did you mean"),
        "{e}"
    );
    assert!(
        e.report().contains("66 |         ErgunWenYuDarg"),
        "{}",
        e.report()
    );
}

#[test]
fn turbulence_model_is_refused_before_anything_is_written() {
    let Some((_s, case)) = broken_copy("dpm-ras", |c| {
        replace(
            &c.join("constant/turbulenceProperties.air"),
            "simulationType  laminar;",
            "simulationType  RAS;\nRAS { RASModel kEpsilon; turbulence on; }",
        )
    }) else {
        return;
    };
    let out = refused(
        &case,
        "fsimFoam: error: constant/turbulenceProperties.air:18:17: simulationType RAS: \
         fsim's fluid is laminar",
    );
    assert!(out.stdout.is_empty());
}

#[test]
fn boundary_conditions_fsim_cannot_honour_are_refused() {
    // a fixed velocity against a fixed pressure on the inlet
    let Some((_s, case)) = broken_copy("dpm-bc", |c| {
        replace(
            &c.join("0/p"),
            "    bottom\n    {\n        type            fixedFluxPressure;",
            "    bottom\n    {\n        type            fixedValue;",
        )
    }) else {
        return;
    };
    refused(&case, "fsim cannot honour U 'interstitialInletVelocity'");
    let loaded = Case::load(&case).unwrap_or_else(|e| panic!("{}", e.report()));
    let e = boundary_conditions(&loaded).unwrap_err().to_string();
    assert!(
        e.contains(
            "0/U.air and 0/p: fsim cannot honour U 'interstitialInletVelocity' with p \
             'fixedValue' on patch 'bottom'"
        ),
        "{e}"
    );
    // a boundary condition fsim does not know
    replace(&case.join("0/p"), "fixedValue;", "fixedFluxPressure;");
    replace(
        &case.join("0/U.air"),
        "interstitialInletVelocity",
        "flowRateInletVelocity",
    );
    let e = Case::load(&case).unwrap_err();
    assert_eq!((e.file.as_deref(), e.line), (Some("0/U.air"), 39), "{e}");
    assert!(
        e.message.contains("unknown velocity boundary condition"),
        "{e}"
    );
    // the inlet's fraction field must be the continuous phase's
    replace(
        &case.join("0/U.air"),
        "flowRateInletVelocity",
        "interstitialInletVelocity",
    );
    replace(
        &case.join("0/U.air"),
        "alpha           alpha.air;",
        "alpha alpha.water;",
    );
    let e = Case::load(&case).unwrap_err();
    assert!(e
        .message
        .contains("expected the continuous phase's fluid fraction alpha.air"));
    assert_eq!((e.line, e.col), (43, 15), "{e}");
    // a fixed fluid fraction on a patch (0/alpha.air)
    replace(
        &case.join("0/U.air"),
        "alpha alpha.water;",
        "alpha alpha.air;",
    );
    fs::write(
        case.join("0/alpha.air"),
        "FoamFile { version 2.0; format ascii; class volScalarField; object alpha.air; }\n\
         dimensions [0 0 0 0 0 0 0];\ninternalField uniform 1;\nboundaryField\n{\n\
         \x20   bottom { type fixedValue; value uniform 1; }\n\
         \x20   \"(top|walls)\" { type zeroGradient; }\n\
         \x20   frontAndBack { type symmetry; }\n}\n",
    )
    .unwrap();
    let e = Case::load(&case).unwrap_err();
    assert_eq!((e.file.as_deref(), e.line), (Some("0/alpha.air"), 6), "{e}");
    assert!(
        e.message
            .contains("fixedValue fluid fraction on patch 'bottom'"),
        "{e}"
    );
    // zeroGradient everywhere loads, its cell values noted as recomputed
    replace(
        &case.join("0/alpha.air"),
        "type fixedValue;",
        "type calculated;",
    );
    let loaded = Case::load(&case).unwrap_or_else(|e| panic!("{}", e.report()));
    assert!(loaded
        .warnings
        .iter()
        .any(|w| w.starts_with("0/alpha.air:3:1: internalField: the fluid fraction is computed")));
}

/// The acceptance test: the installed tutorial, copied unchanged but for `endTime`,
/// runs its first 0.02 s (1000 steps) under fsimFoam without error.
#[test]
fn goldschmidt_runs_its_first_1000_steps_under_fsimfoam() {
    let Some((_s, case)) = broken_copy("dpm-run", |c| {
        replace(
            &c.join("system/controlDict"),
            "endTime         5;",
            "endTime         0.02;",
        )
    }) else {
        return;
    };
    let out = fsim(&case, &["-threads", "2"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    // writeInterval 0.01 (runTime): the start, 0.01 and 0.02, each whole
    for t in ["0.01", "0.02"] {
        for f in ["fluid.vtk", "particles.vtu", "restart.bin"] {
            assert!(case.join(t).join(f).is_file(), "{t}/{f} missing");
        }
    }
    let monitor = fs::read_to_string(case.join("postProcessing/cloud/0/cloud.dat")).unwrap();
    let header: Vec<&str> = monitor.lines().next().unwrap()[1..]
        .split_whitespace()
        .collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<f64>> = monitor
        .lines()
        .skip(1)
        .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 1000);
    assert!(rows.iter().all(|r| r[column("particles")] == 24_750.0));
    assert!(rows.iter().flatten().all(|x| x.is_finite()));
    // The bed starts at rest and falls, held back by the 1.875 m/s inflow's drag: after
    // 0.02 s its mean velocity is downwards and slower than free fall with buoyancy
    // (g t (1 - 1.2/2526) = 0.1961 m/s). DPMFoam v1912 gives -0.124 m/s here.
    let last = rows.last().unwrap();
    assert!((last[column("Time")] - 0.02).abs() < 1e-12);
    let w = last[column("Uz")];
    assert!(w < -0.05 && w > -0.1961, "mean vertical velocity {w}");
}
