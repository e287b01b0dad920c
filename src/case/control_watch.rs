//! `runTimeModifiable`: `system/controlDict` read again when it changes during a run.

use super::control_dict::ControlDict;
use super::dictionary::Dict;
use super::error::CaseError;
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

/// How old a change must be before it is read. File times tick coarsely (a few ms on
/// Linux), so two writes close together can share one; a file read while such writes are
/// under way could leave the last unseen. A change is read once it is this old, by when any
/// later write bears a later time.
const SETTLE: Duration = Duration::from_millis(100);

/// Watches a case's `system/controlDict` by its modification time, as OpenFOAM's
/// `timeStamp` file checking does, between two steps (OpenFOAM's `Time::run`).
///
/// Files the dictionary `#include`s are not watched: touch the controlDict itself.
#[derive(Debug)]
pub struct ControlDictWatch {
    case_dir: PathBuf,
    path: PathBuf,
    /// The modification time last seen (`None`: the file could not be looked at).
    seen: Option<SystemTime>,
}

impl ControlDictWatch {
    /// Watches `case_dir/system/controlDict` from its present state on.
    pub fn new(case_dir: &Path) -> Self {
        let path = case_dir.join("system/controlDict");
        ControlDictWatch {
            seen: modified(&path),
            case_dir: case_dir.to_path_buf(),
            path,
        }
    }

    /// The file's settings when it has changed since the last look: `Ok` when it reads as a
    /// controlDict, else the error at its place (the run keeps the settings it has, and the
    /// next change is read again). `None` while it is unchanged, changed less than
    /// a tenth of a second ago (while a write may be under way), or missing for a moment
    /// (an editor replacing it).
    pub fn changed(&mut self) -> Option<Result<ControlDict, CaseError>> {
        let stamp = modified(&self.path)?;
        if self.seen == Some(stamp) {
            return None;
        }
        // (a time in the future, a clock's skew, counts as settled)
        if SystemTime::now()
            .duration_since(stamp)
            .is_ok_and(|age| age < SETTLE)
        {
            return None;
        }
        self.seen = Some(stamp);
        let read = Dict::read(&self.path, Some(&self.case_dir))
            .and_then(|dict| ControlDict::from_dict(&dict, &mut Vec::new()));
        Some(read)
    }
}

fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    const CONTROL: &str = "endTime 1; deltaT 0.01; writeControl timeStep; writeInterval 10;";

    /// Writes `text` as the controlDict with a modification time `seconds` after the epoch
    /// (a rewrite within the file system's clock tick must still be seen as a change).
    fn write(path: &Path, text: &str, seconds: u64) {
        fs::write(path, text).unwrap();
        let file = fs::File::options().write(true).open(path).unwrap();
        file.set_modified(SystemTime::UNIX_EPOCH + Duration::from_secs(seconds))
            .unwrap();
    }

    #[test]
    fn a_changed_file_is_read_once_and_a_broken_one_reports_its_place() {
        let dir = std::env::temp_dir().join(format!("fsim-watch-{}", std::process::id()));
        fs::create_dir_all(dir.join("system")).unwrap();
        let path = dir.join("system/controlDict");
        write(&path, CONTROL, 1_000);
        let mut watch = ControlDictWatch::new(&dir);
        assert!(watch.changed().is_none());

        write(&path, &CONTROL.replace("endTime 1", "endTime 2"), 1_001);
        let control = watch.changed().expect("a change").expect("a valid file");
        assert_eq!(control.end_time, 2.0);
        assert!(watch.changed().is_none(), "one change is read once");

        write(&path, &format!("{CONTROL}\nstopAt now;"), 1_002);
        let e = watch.changed().expect("a change").unwrap_err();
        assert_eq!((e.line, e.col), (2, 8), "{e}");

        // a change of a moment ago waits until it has settled (unless this thread stalled)
        let written = std::time::Instant::now();
        fs::write(&path, CONTROL).unwrap();
        let early = watch.changed();
        if written.elapsed() < SETTLE {
            assert!(early.is_none());
            std::thread::sleep(SETTLE);
            assert_eq!(watch.changed().unwrap().unwrap().end_time, 1.0);
        }

        fs::remove_file(&path).unwrap();
        assert!(watch.changed().is_none(), "a missing file is no change");
        write(&path, &format!("{CONTROL} stopAt writeNow;"), 1_003);
        let control = watch.changed().unwrap().unwrap();
        assert_eq!(control.stop_at, crate::case::StopAt::WriteNow);
        fs::remove_dir_all(&dir).unwrap();
    }
}
