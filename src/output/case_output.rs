//! The output of one case as the time loop sees it: time directories, the collection file
//! kept in step with them, and `purgeWrite`.
//!
//! ```no_run
//! # use fsim::output::*; use fsim::grid::Grid; use std::path::Path;
//! # fn run(grid: &Grid, u: &[[f64; 3]], p: &[f64]) -> Result<(), OutputError> {
//! let mut output = CaseOutput::open(Path::new("cavity"), 6, 0, 0.0)?;
//! let dir = output.begin(0.1)?;
//! write_fluid(dir.dir(), grid, "fsim t = 0.1", &[
//!     CellData::Vector("U", u),
//!     CellData::Scalar("p", p),
//! ])?;
//! RestartHeader::new(0.1, 100, 1e-3).write(dir.dir(), RESTART_FILE_NAME, &[("p", p)])?;
//! output.commit(dir)?; // now `cavity/0.1/` exists, whole, and `cavity/cavity.pvd` lists it
//! # Ok(()) }
//! ```

use super::collection::{collection_path, rebuild_collection, write_collection};
use super::fluid_vti::write_fluid_vti;
use super::fluid_vtk::{write_fluid_vtk, CellData};
use super::output_error::OutputError;
use super::safe_dir::{first_link_below, symlink_refused, EntryKind, SafeDir};
use super::time_directory::{
    latest_time, purge_write, remove_partial_time_directories, time_value, TimeDirectory, TimeEntry,
};
use super::time_name::time_name;
use crate::grid::Grid;
use std::collections::VecDeque;
use std::path::{Path, PathBuf};

/// The fluid as legacy VTK in each time directory: the file meshio reads.
pub const FLUID_VTK_FILE_NAME: &str = "fluid.vtk";
/// The fluid as XML ImageData in each time directory: the file ParaView's collection reader
/// opens (collection part 0).
pub const FLUID_VTI_FILE_NAME: &str = "fluid.vti";
/// The particle file of each time directory (collection part 1).
pub const PARTICLE_FILE_NAME: &str = "particles.vtu";
/// The restart state of each time directory.
pub const RESTART_FILE_NAME: &str = "restart.bin";

/// Files listed in the collection, in part order.
const COLLECTION_PARTS: [&str; 2] = [FLUID_VTI_FILE_NAME, PARTICLE_FILE_NAME];

/// Writes the fluid twice into time directory `dir`: `fluid.vtk` (legacy, for meshio) and
/// `fluid.vti` (XML, for ParaView's `.pvd` reader); pyvista reads either. No single format
/// serves all three readers without a much larger file (see [`super::write_fluid_vti`]).
/// The two files are written at once, on two of rayon's workers: each streams its fields
/// (a computed field is computed once per file), and one after the other the second core
/// waited for the whole write.
pub fn write_fluid(
    dir: &SafeDir,
    grid: &Grid,
    title: &str,
    fields: &[CellData],
) -> Result<(), OutputError> {
    let (legacy, xml) = rayon::join(
        || write_fluid_vtk(dir, FLUID_VTK_FILE_NAME, grid, title, fields),
        || write_fluid_vti(dir, FLUID_VTI_FILE_NAME, grid, fields),
    );
    legacy.and(xml)
}

/// Refuses, before a run writes anything, a symbolic link where it will write: along
/// `postProcessing/<monitor>/<start_name>/<monitor>.dat` for each of `monitors`, at the
/// collection file, and under any time name from `start_time` on (the start's directory is
/// rewritten, later ones written). Why: a case from elsewhere must not make fsim write outside
/// it, and a refusal at start leaves nothing half-run; each write checks again on its own.
pub fn check_no_links_where_written(
    case_dir: &Path,
    start_time: f64,
    start_name: &str,
    monitors: &[&str],
) -> Result<(), OutputError> {
    for monitor in monitors {
        let file = Path::new("postProcessing")
            .join(monitor)
            .join(start_name)
            .join(format!("{monitor}.dat"));
        if let Some(link) = first_link_below(case_dir, &file)? {
            return Err(symlink_refused(&link));
        }
    }
    let collection = collection_path(case_dir)?;
    if let Some(name) = collection.file_name() {
        if let Some(link) = first_link_below(case_dir, Path::new(name))? {
            return Err(symlink_refused(&link));
        }
    }
    let case = SafeDir::open_case(case_dir)?;
    let mut links: Vec<(f64, String)> = Vec::new();
    for (name, kind) in case.entries()? {
        let Some(name) = name.to_str() else { continue };
        if kind != EntryKind::Symlink {
            continue;
        }
        match time_value(name) {
            Some(value) if value >= start_time || name == start_name => {
                links.push((value, name.to_string()))
            }
            _ => {}
        }
    }
    links.sort_by(|a, b| a.0.total_cmp(&b.0));
    match links.first() {
        Some((_, name)) => Err(symlink_refused(&case.join(name))),
        None => Ok(()),
    }
}

/// Writer of a case's time directories and collection file.
#[derive(Debug)]
pub struct CaseOutput {
    case_dir: PathBuf,
    time_precision: usize,
    purge_write: usize,
    collection: PathBuf,
    /// Time and name of the last committed write, to keep names distinct.
    last_written: Option<(f64, String)>,
    /// The directories this run wrote, oldest first: what `purgeWrite` may delete.
    written: VecDeque<String>,
    /// The start time's directory: it holds the initial conditions or the state the run
    /// continues from, and is never purged, though the run adds its files to it.
    start_name: String,
    /// Time of the directory begun and not yet committed.
    pending: Option<f64>,
}

/// 17 significant digits tell any two distinct f64 apart.
const MAX_TIME_PRECISION: usize = 17;

impl CaseOutput {
    /// Prepares the case for writing: removes directories left by an interrupted write, and
    /// rebuilds the collection file from the time directories already there, so a continued
    /// run's collection holds the whole series. `time_precision` and `purge_write` are those
    /// of `system/controlDict` (`purge_write == 0`: keep everything); `start_time` is the
    /// run's, whose directory `purgeWrite` never deletes.
    pub fn open(
        case_dir: &Path,
        time_precision: usize,
        purge_write: usize,
        start_time: f64,
    ) -> Result<Self, OutputError> {
        remove_partial_time_directories(case_dir)?;
        let output = CaseOutput {
            case_dir: case_dir.to_path_buf(),
            time_precision,
            purge_write,
            collection: collection_path(case_dir)?,
            last_written: None,
            written: VecDeque::new(),
            start_name: time_name(start_time, time_precision),
            pending: None,
        };
        output.refresh_collection()?;
        Ok(output)
    }

    /// Name of the directory for time `t` at the current precision.
    pub fn time_name(&self, t: f64) -> String {
        time_name(t, self.time_precision)
    }

    /// The `timePrecision` in use: the controlDict's, or more if it had to grow.
    pub fn time_precision(&self) -> usize {
        self.time_precision
    }

    /// Takes a `system/controlDict` changed during the run: its `timePrecision` (which may
    /// grow again, as in [`Self::begin`]) and `purgeWrite`, applied from the next write on.
    pub fn set_controls(&mut self, time_precision: usize, purge_write: usize) {
        self.time_precision = time_precision;
        self.purge_write = purge_write;
    }

    /// Starts the time directory of time `t`; write its files into [`TimeDirectory::dir`].
    ///
    /// As OpenFOAM does, when `t` differs from the previously written time but would get the
    /// same name, the precision grows (up to 17 digits, enough to tell any two f64 apart) so
    /// that no write overwrites the previous one; [`CaseOutput::time_precision`] tells by how
    /// much.
    pub fn begin(&mut self, t: f64) -> Result<TimeDirectory, OutputError> {
        if let Some((last_time, last_name)) = &self.last_written {
            while *last_time != t
                && time_name(t, self.time_precision) == *last_name
                && self.time_precision < MAX_TIME_PRECISION
            {
                self.time_precision += 1;
            }
        }
        let dir = TimeDirectory::begin(&self.case_dir, &self.time_name(t))?;
        self.pending = Some(t);
        Ok(dir)
    }

    /// Publishes a finished time directory, applies `purgeWrite`, and rewrites the collection.
    /// Returns the final path of the time directory.
    pub fn commit(&mut self, dir: TimeDirectory) -> Result<PathBuf, OutputError> {
        let name = dir.name().to_string();
        let path = dir.commit()?;
        if name != self.start_name && self.written.back() != Some(&name) {
            self.written.push_back(name.clone());
        }
        if let Some(t) = self.pending.take() {
            self.last_written = Some((t, name));
        }
        purge_write(&self.case_dir, &mut self.written, self.purge_write)?;
        self.refresh_collection()?;
        Ok(path)
    }

    /// The latest time directory of the case (for `startFrom latestTime`).
    pub fn latest_time(&self) -> Result<Option<TimeEntry>, OutputError> {
        latest_time(&self.case_dir)
    }

    /// `<case>/<caseName>.pvd`.
    pub fn collection_path(&self) -> &Path {
        &self.collection
    }

    fn refresh_collection(&self) -> Result<(), OutputError> {
        let entries = rebuild_collection(&self.case_dir, &COLLECTION_PARTS)?;
        write_collection(&self.collection, &entries)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_support::ScratchDir;
    use std::fs;

    fn write(output: &mut CaseOutput, t: f64, particles: bool) {
        let dir = output.begin(t).unwrap();
        fs::write(dir.file(FLUID_VTI_FILE_NAME), "f").unwrap();
        if particles {
            fs::write(dir.file(PARTICLE_FILE_NAME), "p").unwrap();
        }
        output.commit(dir).unwrap();
    }

    #[test]
    fn collection_follows_writes_purges_and_restarts() {
        let case = ScratchDir::new("case-output");
        fs::create_dir_all(case.path().join("0")).unwrap();
        fs::create_dir_all(case.path().join(".0.4.partial")).unwrap();
        let mut output = CaseOutput::open(case.path(), 6, 3, 0.0).unwrap();
        assert!(!case.path().join(".0.4.partial").exists());
        for step in 1..=5 {
            write(&mut output, 0.1 * step as f64, step % 2 == 1);
        }
        let xml = fs::read_to_string(output.collection_path()).unwrap();
        let files: Vec<_> = xml
            .lines()
            .filter_map(|l| l.split("file=\"").nth(1))
            .map(|f| f.trim_end_matches("\"/>"))
            .collect();
        assert_eq!(
            files,
            [
                "0.3/fluid.vti",
                "0.3/particles.vtu",
                "0.4/fluid.vti",
                "0.5/fluid.vti",
                "0.5/particles.vtu"
            ]
        );
        assert_eq!(output.latest_time().unwrap().unwrap().name, "0.5");

        // A continued run rebuilds the same series and extends it.
        drop(output);
        fs::remove_file(case.path().join(format!(
            "{}.pvd",
            fs::canonicalize(case.path()).unwrap().file_name().unwrap().to_str().unwrap()
        )))
        .unwrap();
        let mut output = CaseOutput::open(case.path(), 6, 0, 0.5).unwrap();
        write(&mut output, 0.6, false);
        let xml = fs::read_to_string(output.collection_path()).unwrap();
        assert_eq!(xml.matches("<DataSet ").count(), 6);

        // Two times that share a name at precision 6 get distinct names at precision 7.
        write(&mut output, 0.7, false);
        write(&mut output, 0.7 + 1e-7, false);
        assert_eq!(output.time_precision(), 7);
        assert_eq!(output.latest_time().unwrap().unwrap().name, "0.7000001");
        assert!(case.path().join("0.7").is_dir());
        assert!(xml.contains("timestep=\"0.6\" group=\"\" part=\"0\" file=\"0.6/fluid.vti\""));
    }
}
