//! Time directories `<case>/<timeName>/`: written whole or not at all, listed, purged.
//!
//! A write goes into a hidden sibling `<case>/.<timeName>.partial/`; its files are flushed to
//! disk (`fsync`), then the directory is renamed to `<case>/<timeName>/` in one step, so a
//! reader, or a run continued with `startFrom latestTime`, never sees half a time directory.
//! A crash leaves only the hidden partial directory, which no listing takes for a time (its name
//! is not a number) and which [`remove_partial_time_directories`] deletes at the next start.
//!
//! When `<case>/<timeName>/` already exists (the `0/` directory of initial conditions, or a run
//! restarted from an earlier time that writes the same time again), its other files are kept
//! and each new file replaces its namesake by a rename, which is atomic per file.

use super::output_error::OutputError;
use std::collections::VecDeque;
use std::fs;
use std::path::{Path, PathBuf};

/// Suffix of the hidden directory a time is written into before it is renamed.
const PARTIAL_SUFFIX: &str = ".partial";
/// Suffix of a time directory being deleted by [`purge_write`].
const PURGE_SUFFIX: &str = ".purge";

/// A time directory under construction. Files go into [`TimeDirectory::path`]; nothing is
/// visible under the final name before [`TimeDirectory::commit`]. Dropped without commit, it
/// removes its partial directory.
#[derive(Debug)]
pub struct TimeDirectory {
    case_dir: PathBuf,
    name: String,
    partial: PathBuf,
    committed: bool,
}

impl TimeDirectory {
    /// Starts writing time `time_name` of the case: creates the empty hidden directory
    /// `<case>/.<time_name>.partial/`, removing a stale one left by a crash.
    pub fn begin(case_dir: &Path, time_name: &str) -> Result<Self, OutputError> {
        let is_time =
            looks_numeric(time_name) && time_name.parse::<f64>().is_ok_and(f64::is_finite);
        if !is_time {
            return Err(OutputError::invalid(
                &case_dir.join(time_name),
                "a time directory name must be a finite number",
            ));
        }
        let partial = case_dir.join(format!(".{time_name}{PARTIAL_SUFFIX}"));
        if partial.exists() {
            fs::remove_dir_all(&partial).map_err(|e| {
                OutputError::io(&partial, "cannot remove stale partial time directory", e)
            })?;
        }
        fs::create_dir_all(&partial)
            .map_err(|e| OutputError::io(&partial, "cannot create time directory", e))?;
        Ok(TimeDirectory {
            case_dir: case_dir.to_path_buf(),
            name: time_name.to_string(),
            partial,
            committed: false,
        })
    }

    /// The directory to write files into now (the hidden partial one).
    pub fn path(&self) -> &Path {
        &self.partial
    }

    /// Where file `file_name` is written now.
    pub fn file(&self, file_name: &str) -> PathBuf {
        self.partial.join(file_name)
    }

    /// Name of the time, e.g. `0.25`.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The directory's name once committed: `<case>/<timeName>`.
    pub fn final_path(&self) -> PathBuf {
        self.case_dir.join(&self.name)
    }

    /// Makes the time directory visible: flushes every file to disk, then renames the partial
    /// directory to its final name (or moves its files into an existing directory of that name).
    pub fn commit(mut self) -> Result<PathBuf, OutputError> {
        let final_path = self.final_path();
        let entries = read_dir_paths(&self.partial)?;
        for file in &entries {
            sync_file(file)?;
        }
        sync_dir(&self.partial)?;
        if final_path.exists() {
            for file in &entries {
                let target = final_path.join(file.file_name().expect("entry has a name"));
                if target.is_dir() {
                    fs::remove_dir_all(&target)
                        .map_err(|e| OutputError::io(&target, "cannot replace directory", e))?;
                }
                fs::rename(file, &target)
                    .map_err(|e| OutputError::io(&target, "cannot move file into place", e))?;
            }
            sync_dir(&final_path)?;
            fs::remove_dir(&self.partial).map_err(|e| {
                OutputError::io(&self.partial, "cannot remove emptied partial directory", e)
            })?;
        } else {
            fs::rename(&self.partial, &final_path)
                .map_err(|e| OutputError::io(&final_path, "cannot rename time directory", e))?;
        }
        sync_dir(&self.case_dir)?;
        self.committed = true;
        Ok(final_path)
    }
}

impl Drop for TimeDirectory {
    fn drop(&mut self) {
        if !self.committed {
            // Best effort: a leftover is also removed at the next start.
            let _ = fs::remove_dir_all(&self.partial);
        }
    }
}

/// A numeric directory of a case: its name and the time it stands for.
#[derive(Clone, Debug, PartialEq)]
pub struct TimeEntry {
    pub name: String,
    pub value: f64,
}

/// The case's time directories (names that parse as finite numbers), sorted by time.
/// `constant`, `system`, `postProcessing` and hidden partial directories are not times.
pub fn list_time_directories(case_dir: &Path) -> Result<Vec<TimeEntry>, OutputError> {
    let mut times = Vec::new();
    let entries =
        fs::read_dir(case_dir).map_err(|e| OutputError::io(case_dir, "cannot list case", e))?;
    for entry in entries {
        let entry = entry.map_err(|e| OutputError::io(case_dir, "cannot list case", e))?;
        let Some(name) = entry.file_name().to_str().map(str::to_string) else {
            continue;
        };
        let is_dir = entry.file_type().map(|t| t.is_dir()).unwrap_or(false);
        if !is_dir || !looks_numeric(&name) {
            continue;
        }
        if let Ok(value) = name.parse::<f64>() {
            if value.is_finite() {
                times.push(TimeEntry { name, value });
            }
        }
    }
    times.sort_by(|a, b| a.value.total_cmp(&b.value));
    Ok(times)
}

/// Rust's `f64::from_str` also accepts `inf`, `NaN` and `infinity`; a time name starts with a
/// digit or a sign (hidden directories start with a point and are never times).
fn looks_numeric(name: &str) -> bool {
    name.starts_with(|c: char| c.is_ascii_digit() || c == '-' || c == '+')
}

/// The latest time directory, if any.
pub fn latest_time(case_dir: &Path) -> Result<Option<TimeEntry>, OutputError> {
    Ok(list_time_directories(case_dir)?.pop())
}

/// Removes hidden directories left by an interrupted write or purge (`.<time>.partial`,
/// `.<time>.purge`). Call once at start, before listing times. Returns what was removed.
pub fn remove_partial_time_directories(case_dir: &Path) -> Result<Vec<PathBuf>, OutputError> {
    let mut removed = Vec::new();
    for path in read_dir_paths(case_dir)? {
        let Some(name) = path.file_name().and_then(|n| n.to_str()) else {
            continue;
        };
        let Some(inner) = name.strip_prefix('.') else {
            continue;
        };
        let stem = inner
            .strip_suffix(PARTIAL_SUFFIX)
            .or_else(|| inner.strip_suffix(PURGE_SUFFIX));
        if stem.is_some_and(|s| s.parse::<f64>().is_ok()) && path.is_dir() {
            fs::remove_dir_all(&path)
                .map_err(|e| OutputError::io(&path, "cannot remove partial time directory", e))?;
            removed.push(path);
        }
    }
    Ok(removed)
}

/// controlDict `purgeWrite N`, as OpenFOAM's `Time::writeObject` applies it: of the time
/// directories this run wrote, oldest first in `written`, the oldest are deleted until `keep`
/// remain; `keep == 0` disables purging. Directories the run did not write (the initial
/// conditions, an earlier run's times) are never touched: the caller leaves them out of
/// `written`. Each victim is first renamed to a hidden `.<time>.purge` so that a crash
/// mid-delete cannot leave a half-empty directory that looks like a time. Returns the names
/// deleted.
pub fn purge_write(
    case_dir: &Path,
    written: &mut VecDeque<String>,
    keep: usize,
) -> Result<Vec<String>, OutputError> {
    let mut deleted = Vec::new();
    if keep == 0 {
        return Ok(deleted);
    }
    while written.len() > keep {
        let victim = written.pop_front().expect("more than keep >= 1");
        let path = case_dir.join(&victim);
        if !path.is_dir() {
            continue;
        }
        let doomed = case_dir.join(format!(".{victim}{PURGE_SUFFIX}"));
        fs::rename(&path, &doomed)
            .map_err(|e| OutputError::io(&path, "cannot purge time directory", e))?;
        fs::remove_dir_all(&doomed)
            .map_err(|e| OutputError::io(&doomed, "cannot purge time directory", e))?;
        deleted.push(victim);
    }
    Ok(deleted)
}

fn read_dir_paths(dir: &Path) -> Result<Vec<PathBuf>, OutputError> {
    let entries = fs::read_dir(dir).map_err(|e| OutputError::io(dir, "cannot list", e))?;
    let mut paths = Vec::new();
    for entry in entries {
        paths.push(
            entry
                .map_err(|e| OutputError::io(dir, "cannot list", e))?
                .path(),
        );
    }
    Ok(paths)
}

fn sync_file(path: &Path) -> Result<(), OutputError> {
    if path.is_dir() {
        for inner in read_dir_paths(path)? {
            sync_file(&inner)?;
        }
        return sync_dir(path);
    }
    fs::File::open(path)
        .and_then(|f| f.sync_all())
        .map_err(|e| OutputError::io(path, "cannot flush file to disk", e))
}

/// Makes a directory's entries (creations, renames) durable. Only meaningful on Unix, where a
/// directory can be opened and synced; elsewhere it is a no-op.
pub(crate) fn sync_dir(dir: &Path) -> Result<(), OutputError> {
    #[cfg(unix)]
    {
        fs::File::open(dir)
            .and_then(|f| f.sync_all())
            .map_err(|e| OutputError::io(dir, "cannot flush directory to disk", e))?;
    }
    #[cfg(not(unix))]
    let _ = dir;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_support::ScratchDir;

    fn write_time(case: &Path, name: &str, content: &str) -> PathBuf {
        let dir = TimeDirectory::begin(case, name).unwrap();
        fs::write(dir.file("data.txt"), content).unwrap();
        dir.commit().unwrap()
    }

    #[test]
    fn commit_renames_and_leaves_no_partial_directory() {
        let case = ScratchDir::new("commit");
        let dir = TimeDirectory::begin(case.path(), "0.5").unwrap();
        fs::write(dir.file("a"), "x").unwrap();
        assert!(!case.path().join("0.5").exists(), "visible before commit");
        let final_path = dir.commit().unwrap();
        assert_eq!(fs::read_to_string(final_path.join("a")).unwrap(), "x");
        let hidden: Vec<_> = read_dir_paths(case.path())
            .unwrap()
            .into_iter()
            .filter(|p| p.file_name().unwrap().to_str().unwrap().starts_with('.'))
            .collect();
        assert!(hidden.is_empty(), "left behind: {hidden:?}");
    }

    #[test]
    fn dropping_without_commit_removes_the_partial_directory() {
        let case = ScratchDir::new("drop");
        {
            let dir = TimeDirectory::begin(case.path(), "1").unwrap();
            fs::write(dir.file("a"), "x").unwrap();
        }
        assert!(read_dir_paths(case.path()).unwrap().is_empty());
    }

    #[test]
    fn stale_partial_directories_are_removed_and_never_listed() {
        let case = ScratchDir::new("stale");
        let stale = case.path().join(".0.3.partial");
        fs::create_dir_all(&stale).unwrap();
        fs::write(stale.join("half"), "crash").unwrap();
        fs::create_dir_all(case.path().join(".0.2.purge")).unwrap();
        fs::create_dir_all(case.path().join(".hidden")).unwrap();
        write_time(case.path(), "0.1", "ok");
        let names: Vec<_> = list_time_directories(case.path())
            .unwrap()
            .into_iter()
            .map(|t| t.name)
            .collect();
        assert_eq!(names, ["0.1"]);
        let removed = remove_partial_time_directories(case.path()).unwrap();
        assert_eq!(removed.len(), 2);
        assert!(!stale.exists());
        assert!(case.path().join(".hidden").exists(), "not ours to remove");
        // A new write of the same time also clears a stale partial of that name.
        fs::create_dir_all(&stale).unwrap();
        fs::write(stale.join("half"), "crash").unwrap();
        let path = write_time(case.path(), "0.3", "whole");
        assert!(!stale.exists());
        assert!(!path.join("half").exists());
    }

    #[test]
    fn listing_is_numeric_sorted_and_ignores_other_entries() {
        let case = ScratchDir::new("list");
        for name in [
            "10", "2", "0", "1e-05", "0.25", "constant", "system", "inf", "nan",
        ] {
            fs::create_dir_all(case.path().join(name)).unwrap();
        }
        fs::write(case.path().join("3"), "a file, not a time").unwrap();
        let names: Vec<_> = list_time_directories(case.path())
            .unwrap()
            .into_iter()
            .map(|t| t.name)
            .collect();
        assert_eq!(names, ["0", "1e-05", "0.25", "2", "10"]);
        assert_eq!(latest_time(case.path()).unwrap().unwrap().value, 10.0);
    }

    #[test]
    fn commit_into_existing_directory_keeps_its_other_files() {
        let case = ScratchDir::new("existing");
        let zero = case.path().join("0");
        fs::create_dir_all(&zero).unwrap();
        fs::write(zero.join("U.air"), "initial conditions").unwrap();
        fs::write(zero.join("data.txt"), "old").unwrap();
        write_time(case.path(), "0", "new");
        assert_eq!(
            fs::read_to_string(zero.join("U.air")).unwrap(),
            "initial conditions"
        );
        assert_eq!(fs::read_to_string(zero.join("data.txt")).unwrap(), "new");
        assert!(!case.path().join(".0.partial").exists());
    }

    #[test]
    fn purge_write_deletes_only_the_oldest_of_what_the_run_wrote() {
        let case = ScratchDir::new("purge");
        for name in ["0", "0.1", "0.2", "0.3", "0.4", "0.5"] {
            write_time(case.path(), name, name);
        }
        // this run started from 0.2 and wrote 0.3, 0.4 and 0.5
        let mut written: VecDeque<String> = ["0.3", "0.4", "0.5"].map(String::from).into();
        assert!(
            purge_write(case.path(), &mut written, 0)
                .unwrap()
                .is_empty(),
            "0 disables"
        );
        let deleted = purge_write(case.path(), &mut written, 2).unwrap();
        assert_eq!(deleted, ["0.3"]);
        assert_eq!(written, ["0.4", "0.5"]);
        let names: Vec<_> = list_time_directories(case.path())
            .unwrap()
            .into_iter()
            .map(|t| t.name)
            .collect();
        // the initial conditions and the earlier run's times stay
        assert_eq!(names, ["0", "0.1", "0.2", "0.4", "0.5"]);
        assert_eq!(
            read_dir_paths(case.path()).unwrap().len(),
            5,
            "no hidden leftovers"
        );
        // a listed directory already gone (removed by hand) is skipped
        fs::remove_dir_all(case.path().join("0.4")).unwrap();
        written.push_back("0.6".into());
        write_time(case.path(), "0.6", "0.6");
        assert!(purge_write(case.path(), &mut written, 1).unwrap() == ["0.5"]);
    }

    #[test]
    fn non_numeric_time_names_are_refused() {
        let case = ScratchDir::new("refuse");
        assert!(TimeDirectory::begin(case.path(), "latest").is_err());
        assert!(TimeDirectory::begin(case.path(), "inf").is_err());
        assert!(
            TimeDirectory::begin(case.path(), ".5").is_err(),
            "would be hidden"
        );
    }
}
