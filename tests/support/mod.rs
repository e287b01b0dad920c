//! Helpers for tests that run `fsimFoam` on copies of the tutorials, and shared fluid set-ups.
#![allow(dead_code)]

pub mod box_case;
pub mod porous_reference;
pub mod settler;
pub mod slit;
pub mod steady_stokes;

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A scratch directory removed when dropped.
pub struct Scratch(pub PathBuf);

impl Scratch {
    pub fn new(tag: &str) -> Self {
        let dir = std::env::temp_dir().join(format!(
            "fsim-test-{tag}-{}-{:?}",
            std::process::id(),
            std::thread::current().id()
        ));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

fn copy_tree(src: &Path, dst: &Path) {
    fs::create_dir_all(dst).unwrap();
    for entry in fs::read_dir(src).unwrap() {
        let entry = entry.unwrap();
        let name = entry.file_name();
        let name = name.to_string_lossy();
        // Outputs of an earlier run in the tutorial folder are not inputs.
        if name.starts_with("fluid.vt") || name == "restart.bin" || name == "particles.vtu" {
            continue;
        }
        let to = dst.join(&*name);
        if entry.file_type().unwrap().is_dir() {
            copy_tree(&entry.path(), &to);
        } else {
            fs::copy(entry.path(), to).unwrap();
        }
    }
}

/// Copies the input folders (`system`, `constant`, `0`) of any case directory `src` to `dst`.
pub fn copy_case(src: &Path, dst: &Path) {
    for sub in ["system", "constant", "0"] {
        if src.join(sub).is_dir() {
            copy_tree(&src.join(sub), &dst.join(sub));
        }
    }
}

/// Copies the input folders of `tutorials/<name>` to `<dir>/<as_name>`.
pub fn copy_tutorial(name: &str, dir: &Path, as_name: &str) -> PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tutorials")
        .join(name);
    let case = dir.join(as_name);
    for sub in ["system", "constant", "0"] {
        copy_tree(&src.join(sub), &case.join(sub));
    }
    case
}

/// Replaces the particle list of `constant/kinematicCloudPositions` in `case` with
/// `centres` (m), keeping the file's header.
pub fn set_positions(case: &Path, centres: &[[f64; 3]]) {
    let file = case.join("constant/kinematicCloudPositions");
    let text = fs::read_to_string(&file).unwrap();
    let head = &text[..text.find("\n(").unwrap()];
    let list: String = centres
        .iter()
        .map(|x| format!("({} {} {})\n", x[0], x[1], x[2]))
        .collect();
    fs::write(&file, format!("{head}\n(\n{list})\n")).unwrap();
}

/// Sets `keyword value;` in a dictionary file, replacing the entry or appending it.
pub fn set_entry(file: &Path, keyword: &str, value: &str) {
    let text = fs::read_to_string(file).unwrap();
    let mut found = false;
    let mut out: Vec<String> = text
        .lines()
        .map(|line| {
            let first = line.split_whitespace().next();
            if first == Some(keyword) && line.trim_end().ends_with(';') && !found {
                found = true;
                format!("{keyword} {value};")
            } else {
                line.to_string()
            }
        })
        .collect();
    if !found {
        out.push(format!("{keyword} {value};"));
    }
    fs::write(file, out.join("\n") + "\n").unwrap();
}

/// Runs fsimFoam on `case` with extra arguments.
pub fn fsim(case: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fsimFoam"))
        .arg("-case")
        .arg(case)
        .args(args)
        .output()
        .unwrap()
}

/// Names of the entries of a directory, sorted.
pub fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Runs fsimFoam on `case`, which must refuse it as bad input before writing anything: exit
/// code 2, `expected` in the standard error, the case directory unchanged. Returns the output.
#[allow(dead_code)] // not every test binary that includes this module refuses a case
pub fn refused(case: &Path, expected: &str) -> Output {
    let before = listing(case);
    let out = fsim(case, &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains(expected), "{stderr}");
    assert_eq!(listing(case), before, "the refused run wrote into the case");
    out
}

/// Channel periodic in x, walls in y (the top one moving at `lid`), empty z, 4 × 16 cells of
/// 1/16, body force `g` along x.
pub fn wall_channel(
    lid: f64,
    nu: f64,
    g: f64,
    scheme: fsim::fluid::TimeScheme,
) -> fsim::fluid::FluidSolver {
    use fsim::fluid::{BoundaryConditions, FaceCondition, FluidSettings, FluidSolver};
    let ny = 16;
    let h = 1.0 / ny as f64;
    let grid = fsim::grid::Grid::new([4, ny, 1], [h; 3], [0.0; 3]);
    let bc = BoundaryConditions {
        faces: [
            FaceCondition::Periodic,
            FaceCondition::Periodic,
            FaceCondition::Wall { velocity: [0.0; 3] },
            FaceCondition::Wall {
                velocity: [lid, 0.0, 0.0],
            },
            FaceCondition::Empty,
            FaceCondition::Empty,
        ],
    };
    let settings = FluidSettings {
        nu,
        scheme,
        body_force: [g, 0.0, 0.0],
        convection: true,
    };
    FluidSolver::new(grid, bc, settings).unwrap()
}
