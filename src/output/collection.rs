//! The collection file `<case>/<caseName>.pvd` that opens a whole run as one time series in
//! ParaView and pyvista (ParaView Data format: one `<DataSet timestep part file>` per file).
//!
//! vtkio does not write `.pvd`; it is a few lines of XML, written here. Parts: the fluid is
//! part 0, the particles part 1, so ParaView groups both files of a time into one multiblock.
//! The file is rewritten whole after every write (temporary file, `fsync`, rename) and rebuilt
//! from the time directories at start, so a continued run lists the whole series. The file
//! is written in the case directory without following a link ([`SafeDir`]); a link in its
//! place is refused.

use super::output_error::OutputError;
use super::safe_dir::{symlink_refused, EntryKind, SafeDir};
use super::time_directory::list_time_directories;
use std::fmt::Write as _;
use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// One file of the series.
#[derive(Clone, Debug, PartialEq)]
pub struct CollectionEntry {
    pub time: f64,
    pub part: usize,
    /// Path relative to the case directory, `/`-separated (`0.25/fluid.vtk`).
    pub file: String,
}

/// `<case>/<caseName>.pvd`, the case name being the case directory's own name, as OpenFOAM
/// names its case (`.` is resolved to the current directory's name).
pub fn collection_path(case_dir: &Path) -> Result<PathBuf, OutputError> {
    let absolute = fs::canonicalize(case_dir)
        .map_err(|e| OutputError::io(case_dir, "cannot resolve case directory", e))?;
    let name = absolute
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("case");
    Ok(case_dir.join(format!("{name}.pvd")))
}

/// Writes `entries` (in the order given) to `path` atomically; `path` is a file directly in
/// the case directory, as [`collection_path`] gives.
pub fn write_collection(path: &Path, entries: &[CollectionEntry]) -> Result<(), OutputError> {
    let mut xml = String::from(
        "<?xml version=\"1.0\"?>\n\
         <VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n",
    );
    for entry in entries {
        // `{}` gives the shortest decimal that reads back as the same f64.
        writeln!(
            xml,
            "    <DataSet timestep=\"{}\" group=\"\" part=\"{}\" file=\"{}\"/>",
            entry.time,
            entry.part,
            escape_xml(&entry.file)
        )
        .expect("writing to a String cannot fail");
    }
    xml.push_str("  </Collection>\n</VTKFile>\n");

    let (Some(parent), Some(file_name)) = (path.parent(), path.file_name()) else {
        return Err(OutputError::invalid(path, "not a file name"));
    };
    let parent = if parent.as_os_str().is_empty() {
        Path::new(".")
    } else {
        parent
    };
    let case = SafeDir::open_case(parent)?;
    if case.kind(file_name)? == Some(EntryKind::Symlink) {
        return Err(symlink_refused(path));
    }
    let temporary = format!(".{}.tmp", file_name.to_string_lossy());
    let io_err = |e| OutputError::io(path, "cannot write collection file", e);
    {
        let mut file = case.create_file(&temporary)?;
        file.write_all(xml.as_bytes()).map_err(io_err)?;
        file.sync_all().map_err(io_err)?;
    }
    case.rename(&temporary, file_name)?;
    case.sync()
}

/// Lists, for every time directory of the case in time order, each of `part_files` that
/// exists there; `part_files[i]` becomes part `i`.
pub fn rebuild_collection(
    case_dir: &Path,
    part_files: &[&str],
) -> Result<Vec<CollectionEntry>, OutputError> {
    let mut entries = Vec::new();
    for time in list_time_directories(case_dir)? {
        for (part, file) in part_files.iter().enumerate() {
            if case_dir.join(&time.name).join(file).is_file() {
                entries.push(CollectionEntry {
                    time: time.value,
                    part,
                    file: format!("{}/{}", time.name, file),
                });
            }
        }
    }
    Ok(entries)
}

fn escape_xml(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_support::ScratchDir;

    #[test]
    fn rebuild_lists_existing_files_in_time_order() {
        let case = ScratchDir::new("pvd");
        for (time, files) in [
            ("0", &["U.air"][..]),
            ("0.1", &["fluid.vtk", "particles.vtu"][..]),
            ("1e-05", &["fluid.vtk"][..]),
            ("0.25", &["fluid.vtk", "particles.vtu"][..]),
        ] {
            let dir = case.path().join(time);
            fs::create_dir_all(&dir).unwrap();
            for f in files {
                fs::write(dir.join(f), "").unwrap();
            }
        }
        fs::create_dir_all(case.path().join(".0.3.partial")).unwrap();
        fs::write(case.path().join(".0.3.partial/fluid.vtk"), "").unwrap();
        let entries = rebuild_collection(case.path(), &["fluid.vtk", "particles.vtu"]).unwrap();
        let files: Vec<_> = entries
            .iter()
            .map(|e| (e.time, e.part, e.file.as_str()))
            .collect();
        assert_eq!(
            files,
            [
                (1e-5, 0, "1e-05/fluid.vtk"),
                (0.1, 0, "0.1/fluid.vtk"),
                (0.1, 1, "0.1/particles.vtu"),
                (0.25, 0, "0.25/fluid.vtk"),
                (0.25, 1, "0.25/particles.vtu"),
            ]
        );

        let path = collection_path(case.path()).unwrap();
        assert!(path.to_str().unwrap().ends_with(".pvd"));
        write_collection(&path, &entries).unwrap();
        let xml = fs::read_to_string(&path).unwrap();
        assert!(xml.contains(
            "<DataSet timestep=\"0.00001\" group=\"\" part=\"0\" file=\"1e-05/fluid.vtk\"/>"
        ));
        assert_eq!(xml.matches("<DataSet ").count(), 5);
        assert!(xml.ends_with("</Collection>\n</VTKFile>\n"));
        let leftovers: Vec<_> = fs::read_dir(case.path())
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_str().unwrap().ends_with(".tmp"))
            .collect();
        assert!(leftovers.is_empty());
    }

    #[test]
    fn file_names_are_escaped() {
        assert_eq!(escape_xml("a&b<\"c\">"), "a&amp;b&lt;&quot;c&quot;&gt;");
    }
}
