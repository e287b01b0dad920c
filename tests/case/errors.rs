//! Bad input: each broken case gives one error naming the file, line and column of the
//! offending text and saying what was expected. Each test copies a sample case from
//! `tests/cases/` into a fresh temporary directory, breaks one thing and loads it.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use fsim::case::{Case, CaseError};

static COUNTER: AtomicUsize = AtomicUsize::new(0);

/// A copy of a sample case in the temporary directory, removed on drop.
struct TempCase {
    dir: PathBuf,
}

impl Drop for TempCase {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let target = to.join(e.file_name());
        if e.path().is_dir() {
            copy_dir(&e.path(), &target);
        } else {
            std::fs::copy(e.path(), target).unwrap();
        }
    }
}

impl TempCase {
    fn from_sample(name: &str) -> TempCase {
        let dir = std::env::temp_dir().join(format!(
            "fsim-case-errors-{}-{}-{name}",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        let _ = std::fs::remove_dir_all(&dir);
        let sample = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/cases")
            .join(name);
        copy_dir(&sample, &dir);
        TempCase { dir }
    }

    /// Replaces the one occurrence of `from` in `file` with `to`.
    fn edit(&self, file: &str, from: &str, to: &str) -> &Self {
        let path = self.dir.join(file);
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(text.matches(from).count(), 1, "'{from}' in {file}");
        std::fs::write(&path, text.replace(from, to)).unwrap();
        self
    }

    /// The 1-based line and column where `needle` starts in `file`, plus `shift` characters.
    fn position(&self, file: &str, needle: &str, shift: usize) -> (usize, usize) {
        let text = std::fs::read_to_string(self.dir.join(file)).unwrap();
        assert_eq!(text.matches(needle).count(), 1, "'{needle}' in {file}");
        let at = text.find(needle).unwrap();
        let before = &text[..at];
        let line = before.matches('\n').count() + 1;
        let col = before.rsplit('\n').next().unwrap().chars().count() + 1 + shift;
        (line, col)
    }

    fn error(&self) -> CaseError {
        match Case::load(&self.dir) {
            Ok(_) => panic!("the broken case loaded without error"),
            Err(e) => e,
        }
    }
}

/// Asserts file, line, column and message words, and that the one-line Display starts with
/// `file:line:col:` as compilers print it.
fn check(e: &CaseError, file: &str, (line, col): (usize, usize), words: &str) {
    let shown = e.to_string();
    assert!(
        shown.starts_with(&format!("{file}:{line}:{col}: ")),
        "expected {file}:{line}:{col}, got: {shown}"
    );
    assert!(shown.contains(words), "expected '{words}' in: {shown}");
    assert!(!shown.contains('\n'));
    let excerpt = e.excerpt().unwrap();
    assert!(excerpt.contains('^'), "{excerpt}");
}

#[test]
fn missing_file() {
    let c = TempCase::from_sample("cavity");
    std::fs::remove_file(c.dir.join("constant/transportProperties")).unwrap();
    let e = c.error();
    assert_eq!(
        e.to_string(),
        "constant/transportProperties: file not found"
    );
    assert_eq!((e.line, e.col), (0, 0));
}

#[test]
fn missing_initial_time_directory_hints_at_0_orig() {
    let c = TempCase::from_sample("cavity");
    std::fs::rename(c.dir.join("0"), c.dir.join("0.orig")).unwrap();
    let e = c.error();
    assert_eq!(
        e.to_string(),
        "0/U: file not found (the case has 0.orig: copy it to 0, as the tutorial's Allrun does)"
    );
}

#[test]
fn time_scheme_errors_point_at_the_setting() {
    let c = TempCase::from_sample("cavity");
    std::fs::write(
        c.dir.join("system/fvSolution"),
        "FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }\n\
         fsim\n{\n    timeScheme  leapfrog;\n}\n",
    )
    .unwrap();
    let case = Case::load(&c.dir).unwrap();
    assert_eq!(case.time_scheme.as_deref(), Some("leapfrog"));
    let e = case.time_scheme_error("unknown fsim timeScheme 'leapfrog'");
    check(
        &e,
        "system/fvSolution",
        (4, 17),
        "unknown fsim timeScheme 'leapfrog'",
    );
}

#[test]
fn missing_case_directory() {
    let dir = std::env::temp_dir().join("fsim-case-errors-no-such-case");
    let e = Case::load(&dir).unwrap_err();
    assert!(e.to_string().contains("does not exist"), "{e}");
}

#[test]
fn unknown_patch_name_in_boundary_field() {
    let c = TempCase::from_sample("cavity");
    c.edit(
        "0/p",
        "    frontAndBack\n",
        "    inlet\n    {\n        type zeroGradient;\n    }\n    frontAndBack\n",
    );
    let e = c.error();
    check(
        &e,
        "0/p",
        c.position("0/p", "inlet", 0),
        "unknown patch 'inlet' in boundaryField",
    );
    assert!(
        e.message.contains("movingWall, fixedWalls, frontAndBack"),
        "{e}"
    );
}

#[test]
fn wrong_type() {
    let c = TempCase::from_sample("cavity");
    c.edit("constant/transportProperties", "0.01;", "abc;");
    let e = c.error();
    let at = c.position("constant/transportProperties", "abc;", 0);
    check(
        &e,
        "constant/transportProperties",
        at,
        "expected a number for 'nu', found the word 'abc'",
    );
}

#[test]
fn negative_viscosity() {
    let c = TempCase::from_sample("channel");
    c.edit("constant/transportProperties", "1e-05;", "-1e-05;");
    let e = c.error();
    let at = c.position("constant/transportProperties", "-1e-05", 0);
    check(
        &e,
        "constant/transportProperties",
        at,
        "expected a positive kinematic viscosity",
    );
}

#[test]
fn non_uniform_grading() {
    let c = TempCase::from_sample("cavity");
    c.edit(
        "system/blockMeshDict",
        "simpleGrading (1 1 1)",
        "simpleGrading (1 2 1)",
    );
    let e = c.error();
    let at = c.position("system/blockMeshDict", "(1 2 1)", 0);
    check(&e, "system/blockMeshDict", at, "fsim needs uniform cells");
}

#[test]
fn edge_grading_other_than_one() {
    let c = TempCase::from_sample("cavity");
    c.edit(
        "system/blockMeshDict",
        "simpleGrading (1 1 1)",
        "edgeGrading (1 1 1 1 2 2 2 2 1 1 1 1)",
    );
    let e = c.error();
    let at = c.position("system/blockMeshDict", "(1 1 1 1 2", 0);
    check(&e, "system/blockMeshDict", at, "fsim needs uniform cells");
}

#[test]
fn zero_cell_count() {
    let c = TempCase::from_sample("cavity");
    c.edit("system/blockMeshDict", "(20 20 1)", "(20 0 1)");
    let e = c.error();
    let at = c.position("system/blockMeshDict", "(20 0 1)", 4);
    check(
        &e,
        "system/blockMeshDict",
        at,
        "expected a cell count of at least 1, found the integer 0",
    );
}

#[test]
fn vertices_not_a_box() {
    let c = TempCase::from_sample("cavity");
    c.edit("system/blockMeshDict", "    (1 1 0)\n", "    (1.2 1 0)\n");
    let e = c.error();
    let at = c.position("system/blockMeshDict", "(0 1 2 3 4 5 6 7)", 0);
    check(
        &e,
        "system/blockMeshDict",
        at,
        "axis-aligned box in OpenFOAM's order",
    );
}

#[test]
fn vertices_in_the_wrong_order() {
    let c = TempCase::from_sample("cavity");
    c.edit(
        "system/blockMeshDict",
        "hex (0 1 2 3 4 5 6 7)",
        "hex (1 0 3 2 5 4 7 6)",
    );
    let e = c.error();
    let at = c.position("system/blockMeshDict", "(1 0 3 2 5 4 7 6)", 0);
    check(&e, "system/blockMeshDict", at, "v6 above v0");
}

#[test]
fn cyclic_without_neighbour() {
    let c = TempCase::from_sample("periodicBox");
    c.edit("system/blockMeshDict", " neighbourPatch top;", "");
    let e = c.error();
    let at = c.position("system/blockMeshDict", "bottom {", 0);
    check(
        &e,
        "system/blockMeshDict",
        at,
        "missing keyword 'neighbourPatch' for the cyclic patch 'bottom'",
    );
}

#[test]
fn cyclic_neighbour_not_opposite() {
    let c = TempCase::from_sample("periodicBox");
    c.edit(
        "system/blockMeshDict",
        "neighbourPatch top;",
        "neighbourPatch right;",
    );
    let e = c.error();
    let at = c.position("system/blockMeshDict", "bottom {", 0);
    check(
        &e,
        "system/blockMeshDict",
        at,
        "on opposite faces of the block",
    );
}

#[test]
fn missing_boundary_condition_for_a_patch() {
    let c = TempCase::from_sample("cavity");
    c.edit(
        "0/U",
        "    fixedWalls\n    {\n        type            noSlip;\n    }\n",
        "",
    );
    let e = c.error();
    let at = c.position("0/U", "boundaryField", 0);
    check(
        &e,
        "0/U",
        at,
        "missing boundary condition for patch 'fixedWalls'",
    );
}

#[test]
fn unknown_condition_type_lists_the_supported_ones() {
    let c = TempCase::from_sample("cavity");
    c.edit(
        "0/U",
        "type            noSlip;",
        "type            movingWallVelocity;",
    );
    let e = c.error();
    let at = c.position("0/U", "movingWallVelocity", 0);
    check(
        &e,
        "0/U",
        at,
        "unknown velocity boundary condition the word 'movingWallVelocity'",
    );
    assert!(
        e.message.contains("noSlip, fixedValue, zeroGradient"),
        "{e}"
    );
}

#[test]
fn condition_incompatible_with_the_patch() {
    let c = TempCase::from_sample("cavity");
    c.edit(
        "0/p",
        "    frontAndBack\n    {\n        type            empty;",
        "    frontAndBack\n    {\n        type            zeroGradient;",
    );
    let e = c.error();
    let text = std::fs::read_to_string(c.dir.join("0/p")).unwrap();
    let line = text
        .lines()
        .position(|l| l.contains("frontAndBack"))
        .unwrap()
        + 3;
    check(
        &e,
        "0/p",
        (line, 25),
        "expected empty on patch 'frontAndBack' of type empty",
    );
}

#[test]
fn empty_patch_needs_one_cell() {
    let c = TempCase::from_sample("cavity");
    c.edit("system/blockMeshDict", "(20 20 1)", "(20 20 2)");
    let e = c.error();
    let at = c.position("system/blockMeshDict", "frontAndBack", 0);
    check(
        &e,
        "system/blockMeshDict",
        at,
        "expected 1 cell in z under the empty patch 'frontAndBack'",
    );
}

#[test]
fn unsupported_write_control() {
    let c = TempCase::from_sample("cavity");
    c.edit(
        "system/controlDict",
        "writeControl    timeStep;",
        "writeControl    wallTime;",
    );
    let e = c.error();
    let at = c.position("system/controlDict", "wallTime", 0);
    check(
        &e,
        "system/controlDict",
        at,
        "expected one of timeStep, runTime, adjustableRunTime",
    );
}

#[test]
fn missing_keyword_points_at_the_dictionary_start() {
    let c = TempCase::from_sample("cavity");
    c.edit("system/controlDict", "deltaT          0.005;\n", "");
    let e = c.error();
    check(
        &e,
        "system/controlDict",
        (1, 1),
        "missing keyword 'deltaT' in the top-level dictionary",
    );
}

#[test]
fn unsupported_fv_option() {
    let c = TempCase::from_sample("channel");
    c.edit(
        "system/fvOptions",
        "type            meanVelocityForce;",
        "type            semiImplicitSource;",
    );
    let e = c.error();
    let at = c.position("system/fvOptions", "semiImplicitSource", 0);
    check(&e, "system/fvOptions", at, "found 'semiImplicitSource'");
}

#[test]
fn nonuniform_internal_field_of_the_wrong_length() {
    let c = TempCase::from_sample("cavity");
    c.edit(
        "0/p",
        "internalField   uniform 0;",
        "internalField   nonuniform List<scalar> 3(1 2 3);",
    );
    let e = c.error();
    let at = c.position("0/p", "3(1 2 3)", 0);
    check(&e, "0/p", at, "expected 400 values in 'internalField'");
}

#[test]
fn syntax_error_in_a_field_file() {
    let c = TempCase::from_sample("channel");
    c.edit(
        "0/U.air",
        "type            noSlip;",
        "type            noSlip",
    );
    let e = c.error();
    let at = c.position("0/U.air", "noSlip", 6);
    check(&e, "0/U.air", at, "expected ';' to end the entry 'type'");
}

#[test]
fn error_in_an_included_file_names_that_file() {
    let c = TempCase::from_sample("cavity");
    std::fs::write(c.dir.join("constant/viscosity"), "nu 0.01\n").unwrap();
    c.edit(
        "constant/transportProperties",
        "nu              [0 2 -1 0 0 0 0] 0.01;",
        "#include \"viscosity\"",
    );
    let e = c.error();
    check(
        &e,
        "constant/viscosity",
        (1, 8),
        "expected ';' to end the entry 'nu'",
    );
}

#[test]
fn dimension_sets_other_than_fsims_are_refused_at_the_set() {
    // the pressure in pascals: fsim (as icoFoam and DPMFoam) solves for p/ρ
    let c = TempCase::from_sample("cavity");
    c.edit("0/p", "[0 2 -2 0 0 0 0]", "[1 -1 -2 0 0 0 0]");
    let e = c.error();
    let at = c.position("0/p", "[1 -1 -2", 0);
    check(
        &e,
        "0/p",
        at,
        "'dimensions' has dimensions [1 -1 -2 0 0 0 0]: expected [0 2 -2 0 0 0 0] (m²/s², the kinematic pressure",
    );
    // a viscosity with a unit by name, which OpenFOAM would convert
    let c = TempCase::from_sample("cavity");
    c.edit(
        "constant/transportProperties",
        "[0 2 -1 0 0 0 0] 0.01",
        "[mm^2/s] 0.01",
    );
    let e = c.error();
    let at = c.position("constant/transportProperties", "[mm^2/s]", 0);
    check(
        &e,
        "constant/transportProperties",
        at,
        "'nu' gives its unit by name, [mm^2/s]",
    );
    // a dynamic viscosity's set in place of a kinematic one
    let c = TempCase::from_sample("cavity");
    c.edit(
        "constant/transportProperties",
        "[0 2 -1 0 0 0 0]",
        "[1 -1 -1 0 0 0 0]",
    );
    let e = c.error();
    assert!(
        e.message
            .contains("expected [0 2 -1 0 0 0 0] (m²/s, a kinematic viscosity)"),
        "{e}"
    );
}

#[test]
fn model_auto_needs_particles_and_is_listed() {
    let c = TempCase::from_sample("channel");
    c.edit(
        "constant/couplingProperties",
        "model           none;",
        "model           auto;",
    );
    let mut case = Case::load(&c.dir).expect("model auto loads");
    let e = fsim::auto::choose(&mut case).unwrap_err().to_string();
    assert!(
        e.contains("model auto chooses how particles and fluid are coupled"),
        "{e}"
    );
    assert!(e.contains("use model none"), "{e}");
    // the models are listed, auto with them
    c.edit(
        "constant/couplingProperties",
        "model           auto;",
        "model           resolved;",
    );
    let e = c.error().to_string();
    assert!(
        e.contains("expected one of none, direct, dragLaw, auto for 'model'"),
        "{e}"
    );
}
