//! The sample cases under `tests/cases/` load into the typed case the solver expects.

use std::path::{Path, PathBuf};

use fsim::case::{
    BoxFace, Case, CouplingModel, InternalField, PatchType, PressureBc, StartFrom, VelocityBc,
    WriteControl,
};

fn sample(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/cases")
        .join(name)
}

fn load(name: &str) -> Case {
    Case::load(&sample(name)).unwrap_or_else(|e| panic!("{}", e.report()))
}

#[test]
fn periodic_box() {
    let c = load("periodicBox");
    let l = 2.0 * std::f64::consts::PI;
    assert_eq!(c.mesh.grid.n, [16, 16, 16]);
    for a in 0..3 {
        assert!((c.mesh.grid.h[a] - l / 16.0).abs() < 1e-15);
        assert!(c.mesh.is_periodic(a));
    }
    assert_eq!(c.transport.phase, "");
    assert_eq!((c.transport.rho, c.transport.nu), (1.0, 0.01));
    assert_eq!(c.fields.velocity_name, "U");
    assert!(c.fields.u_bc.iter().all(|b| *b == VelocityBc::Cyclic));
    // `cyclic` in 0/p is the patch group of all six cyclic patches.
    assert!(c.fields.p_bc.iter().all(|b| *b == PressureBc::Cyclic));
    assert_eq!(c.gravity, [0.0; 3]);
    assert_eq!(c.coupling.model, CouplingModel::None);
    assert_eq!(c.control.write_control, WriteControl::RunTime);
    assert!(c.warnings.is_empty(), "{:#?}", c.warnings);
}

#[test]
fn channel_with_walls_and_mean_velocity_force() {
    let c = load("channel");
    let g = &c.mesh.grid;
    assert_eq!(g.n, [8, 16, 4]);
    for (h, want) in g.h.iter().zip([0.00625; 3]) {
        assert!((h - want).abs() < 1e-15, "{h}");
    }
    assert_eq!(c.transport.phase, "air");
    assert_eq!((c.transport.rho, c.transport.nu), (1.2, 1e-5));
    assert_eq!(c.fields.velocity_name, "U.air");
    let walls = c.mesh.patch_index("walls").unwrap();
    assert_eq!(c.mesh.patch_on(BoxFace::YMin).kind, PatchType::Wall);
    assert_eq!(c.mesh.patch_on(BoxFace::YMax).name, "walls");
    assert_eq!(c.fields.u_bc[walls], VelocityBc::NoSlip);
    assert_eq!(c.fields.p_bc[walls], PressureBc::FixedFluxPressure);
    assert!(c.mesh.is_periodic(0) && !c.mesh.is_periodic(1) && c.mesh.is_periodic(2));
    assert_eq!(c.mean_velocity_forces.len(), 1);
    assert_eq!(c.mean_velocity_forces[0].ubar, [0.01, 0.0, 0.0]);
    assert_eq!(c.mean_velocity_forces[0].field, "U.air");
    assert_eq!(c.control.start_from, StartFrom::LatestTime);
    assert!(c.control.adjust_time_step);
    assert_eq!((c.control.max_co, c.control.max_delta_t), (0.5, 0.1));
    assert_eq!(c.fields.time, "0");
    assert_eq!(c.coupling.model, CouplingModel::None);
    assert!(c.warnings.is_empty(), "{:#?}", c.warnings);
}

#[test]
fn constraint_patches_may_be_left_to_set_constraint_types() {
    // OpenFOAM's caseDicts/setConstraintTypes gives cyclic, empty and symmetry patches their
    // own condition; fsim does the same when a field includes it.
    let dir =
        std::env::temp_dir().join(format!("fsim-case-load-constraints-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    for sub in ["system", "constant", "0"] {
        std::fs::create_dir_all(dir.join(sub)).unwrap();
    }
    let cavity = sample("cavity");
    for f in [
        "system/controlDict",
        "system/blockMeshDict",
        "constant/transportProperties",
    ] {
        std::fs::copy(cavity.join(f), dir.join(f)).unwrap();
    }
    let field = |value: &str, wall: &str| {
        format!(
            "internalField uniform {value};\nboundaryField\n{{\n    movingWall {{ {wall} }}\n    \
             fixedWalls {{ {wall} }}\n    #includeEtc \"caseDicts/setConstraintTypes\"\n}}\n"
        )
    };
    std::fs::write(dir.join("0/U"), field("(0 0 0)", "type noSlip;")).unwrap();
    std::fs::write(dir.join("0/p"), field("0", "type zeroGradient;")).unwrap();
    let case = Case::load(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    let case = case.unwrap_or_else(|e| panic!("{}", e.report()));
    let empty = case.mesh.patch_index("frontAndBack").unwrap();
    assert_eq!(case.fields.u_bc[empty], VelocityBc::Empty);
    assert_eq!(case.fields.p_bc[empty], PressureBc::Empty);
}

#[test]
fn lid_driven_cavity() {
    let c = load("cavity");
    assert_eq!(c.mesh.grid.n, [20, 20, 1]);
    assert!((c.mesh.grid.h[0] - 0.005).abs() < 1e-15);
    assert!((c.mesh.grid.h[2] - 0.01).abs() < 1e-15);
    let lid = c.mesh.patch_index("movingWall").unwrap();
    assert_eq!(c.mesh.patch_on(BoxFace::YMax).name, "movingWall");
    assert_eq!(c.fields.u_bc[lid], VelocityBc::FixedValue([1.0, 0.0, 0.0]));
    assert_eq!(c.mesh.patch_on(BoxFace::ZMin).kind, PatchType::Empty);
    assert_eq!(c.fields.u, InternalField::Uniform([0.0; 3]));
    assert_eq!(c.control.write_control, WriteControl::TimeStep);
    assert_eq!(c.control.write_interval, 20.0);
    // writeFormat, writePrecision, writeCompression, timeFormat: one note (runTimeModifiable
    // is read)
    assert_eq!(c.warnings.len(), 1, "{:#?}", c.warnings);
    assert!(c.control.run_time_modifiable);
    let line = c.summary();
    assert!(
        line.contains("grid 20x20x1 = 400 cells, h = (0.005 0.005 0.01) m"),
        "{line}"
    );
    assert!(!line.contains('\n'));
}

#[test]
fn an_included_file_header_does_not_become_a_patch() {
    // `boundaryField { #include "include/walls" }` where the included file has a FoamFile
    // header of its own, as OpenFOAM tutorials often have.
    let dir = std::env::temp_dir().join(format!("fsim-case-load-include-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    copy(&sample("cavity"), &dir);
    std::fs::create_dir_all(dir.join("0/include")).unwrap();
    std::fs::write(
        dir.join("0/include/walls"),
        "FoamFile { version 2.0; format ascii; class dictionary; object walls; }\n\
         fixedWalls { type noSlip; }\n",
    )
    .unwrap();
    let u = std::fs::read_to_string(dir.join("0/U")).unwrap();
    let u = u.replace(
        "    fixedWalls\n    {\n        type            noSlip;\n    }\n",
        "    #include \"include/walls\"\n",
    );
    std::fs::write(dir.join("0/U"), u).unwrap();
    let case = Case::load(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    let case = case.unwrap_or_else(|e| panic!("{}", e.report()));
    let walls = case.mesh.patch_index("fixedWalls").unwrap();
    assert_eq!(case.fields.u_bc[walls], VelocityBc::NoSlip);
}

fn copy(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        if e.path().is_dir() {
            copy(&e.path(), &to.join(e.file_name()));
        } else {
            std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
        }
    }
}
