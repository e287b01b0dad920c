//! Time directories `<case>/<timeName>/`: written whole or not at all, listed, purged.
//!
//! A write goes into a hidden sibling `<case>/.<timeName>.partial/`; its files are flushed to
//! disk (`fsync`), then the directory is renamed to `<case>/<timeName>/` in one step, so a
//! reader, or a run continued with `startFrom latestTime`, never sees half a time directory.
//! A crash leaves only the hidden partial directory, which no listing takes for a time (its name
//! is not a number) and which [`remove_partial_time_directories`] deletes at the next start.
//!
//! When `<case>/<timeName>/` already exists (the `0/` directory of initial conditions, or a run
//! restarted from an earlier time that writes the same time again), its other files are first
//! hard-linked into the partial directory, which then takes the old one's place in one step
//! (`renameat2(RENAME_EXCHANGE)`), and the old one, now hidden, is deleted: a reader sees the
//! old directory or the new one, whole, and a crash leaves one of them under the time's name.
//! Where the file system cannot exchange, the old directory is renamed aside to
//! `.<timeName>.old` first, and a crash between the two renames is undone at the next start.
//!
//! Everything is done relative to the case directory's descriptor without following a link
//! ([`SafeDir`]); a time directory that is a link is refused.

use super::output_error::OutputError;
use super::safe_dir::{symlink_refused, EntryKind, SafeDir};
use std::collections::VecDeque;
use std::fs;
use std::path::{Path, PathBuf};

/// Suffix of the hidden directory a time is written into before it is renamed.
const PARTIAL_SUFFIX: &str = ".partial";
/// Suffix of a time directory being deleted by [`purge_write`].
const PURGE_SUFFIX: &str = ".purge";
/// Suffix of an existing time directory set aside while its replacement is renamed in (only
/// where the file system cannot exchange two directories in one step).
const OLD_SUFFIX: &str = ".old";

/// A time directory under construction. Files go into [`TimeDirectory::dir`]; nothing is
/// visible under the final name before [`TimeDirectory::commit`]. Dropped without commit, it
/// removes its partial directory.
#[derive(Debug)]
pub struct TimeDirectory {
    case: SafeDir,
    name: String,
    partial_name: String,
    partial: SafeDir,
    committed: bool,
}

impl TimeDirectory {
    /// Starts writing time `time_name` of the case: creates the empty hidden directory
    /// `<case>/.<time_name>.partial/`, removing a stale one left by a crash. A link under the
    /// time's name is refused now, before anything is written.
    pub fn begin(case_dir: &Path, time_name: &str) -> Result<Self, OutputError> {
        let is_time =
            looks_numeric(time_name) && time_name.parse::<f64>().is_ok_and(f64::is_finite);
        if !is_time {
            return Err(OutputError::invalid(
                &case_dir.join(time_name),
                "a time directory name must be a finite number",
            ));
        }
        let case = SafeDir::open_case(case_dir)?;
        check_time_target(&case, time_name)?;
        let partial_name = format!(".{time_name}{PARTIAL_SUFFIX}");
        // A stale one (or anything under our hidden name, a link included) is ours to remove.
        case.remove_all(&partial_name)?;
        let partial = case.create_dir(&partial_name)?;
        Ok(TimeDirectory {
            case,
            name: time_name.to_string(),
            partial_name,
            partial,
            committed: false,
        })
    }

    /// The directory to write files into now (the hidden partial one), opened without
    /// following links: write with [`SafeDir::create_file`].
    pub fn dir(&self) -> &SafeDir {
        &self.partial
    }

    /// The path of the directory files are written into now (the hidden partial one).
    pub fn path(&self) -> &Path {
        self.partial.path()
    }

    /// Where file `file_name` is written now (for messages and tests; fsim itself writes
    /// through [`TimeDirectory::dir`]).
    pub fn file(&self, file_name: &str) -> PathBuf {
        self.partial.join(file_name)
    }

    /// Name of the time, e.g. `0.25`.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The directory's name once committed: `<case>/<timeName>`.
    pub fn final_path(&self) -> PathBuf {
        self.case.join(&self.name)
    }

    /// Makes the time directory visible: flushes every file to disk, then renames the partial
    /// directory to its final name in one step, or, if a directory of that name exists, adds
    /// the old one's other files to it and swaps the two in one step (module documentation).
    pub fn commit(mut self) -> Result<PathBuf, OutputError> {
        let final_path = self.final_path();
        match check_time_target(&self.case, &self.name)? {
            None => {
                self.partial.sync_all()?;
                self.case.rename(&self.partial_name, &self.name)?;
            }
            Some(_) => {
                let old = self.case.open_dir(&self.name)?;
                for (entry, _) in old.entries()? {
                    if self.partial.kind(&entry)?.is_none() {
                        old.link_into(&entry, &self.partial)?;
                    }
                }
                self.partial.sync_all()?;
                if self.case.exchange(&self.partial_name, &self.name)? {
                    // the old directory is now the hidden one
                    self.case.sync()?;
                    self.case.remove_all(&self.partial_name)?;
                } else {
                    replace_by_two_renames(&self.case, &self.partial_name, &self.name)?;
                }
            }
        }
        self.case.sync()?;
        self.committed = true;
        Ok(final_path)
    }
}

/// Replaces directory `name` by directory `partial_name` where the file system cannot swap
/// them in one step: the old one is renamed aside to `.<name>.old`, the new one renamed in,
/// the old one deleted; [`remove_partial_time_directories`] undoes a crash in between.
fn replace_by_two_renames(
    case: &SafeDir,
    partial_name: &str,
    name: &str,
) -> Result<(), OutputError> {
    let aside = format!(".{name}{OLD_SUFFIX}");
    case.remove_all(&aside)?;
    case.rename(name, &aside)?;
    case.rename(partial_name, name)?;
    case.sync()?;
    case.remove_all(&aside)
}

/// What is under the time's name now: nothing, or a directory (to be replaced whole); a link
/// or anything else is refused.
fn check_time_target(case: &SafeDir, name: &str) -> Result<Option<EntryKind>, OutputError> {
    match case.kind(name)? {
        None => Ok(None),
        Some(EntryKind::Dir) => Ok(Some(EntryKind::Dir)),
        Some(EntryKind::Symlink) => Err(symlink_refused(&case.join(name))),
        Some(_) => Err(OutputError::invalid(
            &case.join(name),
            "exists and is not a directory, where fsim writes this time's directory",
        )),
    }
}

impl Drop for TimeDirectory {
    fn drop(&mut self) {
        if !self.committed {
            // Best effort: a leftover is also removed at the next start.
            let _ = self.case.remove_all(&self.partial_name);
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
/// `constant`, `system`, `postProcessing` and hidden partial directories are not times, nor
/// is a link.
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
        if !is_dir {
            continue;
        }
        if let Some(value) = time_value(&name) {
            times.push(TimeEntry { name, value });
        }
    }
    times.sort_by(|a, b| a.value.total_cmp(&b.value));
    Ok(times)
}

/// The time a directory name stands for, if it is a time name: a finite number.
pub fn time_value(name: &str) -> Option<f64> {
    if !looks_numeric(name) {
        return None;
    }
    name.parse::<f64>().ok().filter(|v| v.is_finite())
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

/// Cleans up after an interrupted write or purge. Call once at start, before listing times.
/// Removes `.<time>.partial` and `.<time>.purge`; a `.<time>.old` (a replaced directory set
/// aside) is renamed back when `<time>` is missing (the crash came between the two renames),
/// else removed. Links under these hidden names are removed, never followed. Returns what was
/// removed.
pub fn remove_partial_time_directories(case_dir: &Path) -> Result<Vec<PathBuf>, OutputError> {
    let case = SafeDir::open_case(case_dir)?;
    let mut removed = Vec::new();
    for (name, kind) in case.entries()? {
        let Some(name) = name.to_str() else {
            continue;
        };
        let Some(inner) = name.strip_prefix('.') else {
            continue;
        };
        if !matches!(kind, EntryKind::Dir | EntryKind::Symlink) {
            continue;
        }
        if let Some(stem) = inner.strip_suffix(OLD_SUFFIX) {
            if time_value(stem).is_some() {
                if kind == EntryKind::Dir && case.kind(stem)?.is_none() {
                    case.rename(name, stem)?;
                } else {
                    case.remove_all(name)?;
                    removed.push(case.join(name));
                }
            }
            continue;
        }
        let stem = inner
            .strip_suffix(PARTIAL_SUFFIX)
            .or_else(|| inner.strip_suffix(PURGE_SUFFIX));
        if stem.is_some_and(|s| s.parse::<f64>().is_ok()) {
            case.remove_all(name)?;
            removed.push(case.join(name));
        }
    }
    case.sync()?;
    Ok(removed)
}

/// controlDict `purgeWrite N`, as OpenFOAM's `Time::writeObject` applies it: of the time
/// directories this run wrote, oldest first in `written`, the oldest are deleted until `keep`
/// remain; `keep == 0` disables purging. Directories the run did not write (the initial
/// conditions, an earlier run's times) are never touched: the caller leaves them out of
/// `written`. Each victim is first renamed to a hidden `.<time>.purge` so that a crash
/// mid-delete cannot leave a half-empty directory that looks like a time; nothing is followed
/// if a link took a victim's place. Returns the names deleted.
pub fn purge_write(
    case_dir: &Path,
    written: &mut VecDeque<String>,
    keep: usize,
) -> Result<Vec<String>, OutputError> {
    let mut deleted = Vec::new();
    if keep == 0 || written.len() <= keep {
        return Ok(deleted);
    }
    let case = SafeDir::open_case(case_dir)?;
    while written.len() > keep {
        let victim = written.pop_front().expect("more than keep >= 1");
        if case.kind(&victim)? != Some(EntryKind::Dir) {
            continue;
        }
        let doomed = format!(".{victim}{PURGE_SUFFIX}");
        case.remove_all(&doomed)?;
        case.rename(&victim, &doomed)?;
        case.remove_all(&doomed)?;
        deleted.push(victim);
    }
    Ok(deleted)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_support::ScratchDir;
    use std::os::unix::fs::{symlink, MetadataExt};

    /// No hidden entry (partial, purge or swapped-out directory) is left in `case`.
    fn assert_nothing_hidden(case: &Path) {
        let hidden: Vec<_> = read_dir_paths(case)
            .unwrap()
            .into_iter()
            .filter(|p| p.file_name().unwrap().to_str().unwrap().starts_with('.'))
            .collect();
        assert!(hidden.is_empty(), "left behind: {hidden:?}");
    }

    fn read_dir_paths(dir: &Path) -> Result<Vec<PathBuf>, std::io::Error> {
        fs::read_dir(dir)?.map(|e| e.map(|e| e.path())).collect()
    }

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
        assert_nothing_hidden(case.path());
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
    fn an_existing_directory_is_replaced_whole_and_keeps_its_links_as_links() {
        let case = ScratchDir::new("existing-swap");
        let outside = ScratchDir::new("existing-swap-outside");
        fs::write(outside.path().join("U.air"), "shared").unwrap();
        let zero = case.path().join("0");
        fs::create_dir_all(zero.join("uniform")).unwrap();
        fs::write(zero.join("uniform/time"), "t").unwrap();
        symlink(outside.path().join("U.air"), zero.join("U.air")).unwrap();
        // a link where fsim writes is replaced by the new file, its target untouched
        symlink(outside.path().join("U.air"), zero.join("data.txt")).unwrap();
        // a reader holding the old directory open keeps seeing the old one whole
        let old = fs::File::open(&zero).unwrap();
        let old_inode = old.metadata().unwrap().ino();
        write_time(case.path(), "0", "new");
        // one directory took the old one's place, rather than files renamed into it
        assert_ne!(fs::metadata(&zero).unwrap().ino(), old_inode);
        assert_eq!(old.metadata().unwrap().nlink(), 0, "the old one is deleted");
        assert_eq!(fs::read_to_string(zero.join("data.txt")).unwrap(), "new");
        assert!(fs::symlink_metadata(zero.join("U.air"))
            .unwrap()
            .is_symlink());
        assert_eq!(fs::read_to_string(zero.join("uniform/time")).unwrap(), "t");
        assert_eq!(
            fs::read_to_string(outside.path().join("U.air")).unwrap(),
            "shared"
        );
        assert_nothing_hidden(case.path());
        drop(old);
    }

    #[test]
    fn a_link_under_a_time_name_is_refused_before_anything_is_written() {
        let case = ScratchDir::new("time-link");
        let outside = ScratchDir::new("time-link-outside");
        symlink(outside.path(), case.path().join("0.05")).unwrap();
        let err = TimeDirectory::begin(case.path(), "0.05")
            .unwrap_err()
            .to_string();
        assert!(err.contains("0.05: is a symbolic link"), "{err}");
        // a link planted after begin is refused at commit
        let dir = TimeDirectory::begin(case.path(), "0.1").unwrap();
        fs::write(dir.file("a"), "x").unwrap();
        symlink(outside.path(), case.path().join("0.1")).unwrap();
        let err = dir.commit().unwrap_err().to_string();
        assert!(err.contains("0.1: is a symbolic link"), "{err}");
        assert_eq!(fs::read_dir(outside.path()).unwrap().count(), 0);
        assert!(!case.path().join(".0.1.partial").exists());
    }

    #[test]
    fn the_fallback_replaces_by_two_renames_and_leaves_nothing_hidden() {
        let case = ScratchDir::new("two-renames");
        fs::create_dir_all(case.path().join("0")).unwrap();
        fs::write(case.path().join("0/U"), "old").unwrap();
        fs::create_dir_all(case.path().join(".0.partial")).unwrap();
        fs::write(case.path().join(".0.partial/U"), "new").unwrap();
        let dir = SafeDir::open_case(case.path()).unwrap();
        replace_by_two_renames(&dir, ".0.partial", "0").unwrap();
        assert_eq!(fs::read_to_string(case.path().join("0/U")).unwrap(), "new");
        assert_eq!(read_dir_paths(case.path()).unwrap().len(), 1);
    }

    #[test]
    fn a_crash_between_the_two_renames_of_the_fallback_is_undone_at_start() {
        let case = ScratchDir::new("old-aside");
        // set aside, the new one not yet renamed in: the old one comes back
        fs::create_dir_all(case.path().join(".0.old")).unwrap();
        fs::write(case.path().join(".0.old/U"), "initial").unwrap();
        fs::create_dir_all(case.path().join(".0.partial")).unwrap();
        // renamed in, the old one not yet deleted: the old one goes
        fs::create_dir_all(case.path().join(".0.5.old")).unwrap();
        fs::create_dir_all(case.path().join("0.5")).unwrap();
        let removed = remove_partial_time_directories(case.path()).unwrap();
        assert_eq!(removed.len(), 2, "{removed:?}");
        assert_eq!(
            fs::read_to_string(case.path().join("0/U")).unwrap(),
            "initial"
        );
        let mut names: Vec<_> = read_dir_paths(case.path())
            .unwrap()
            .into_iter()
            .map(|p| p.file_name().unwrap().to_str().unwrap().to_string())
            .collect();
        names.sort();
        assert_eq!(names, ["0", "0.5"]);
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
