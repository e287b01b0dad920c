//! `runTimeModifiable`: `system/controlDict` read again when it changes during a run.

use super::bounded_read::{read_regular_file, ReadError, MAX_TEXT_BYTES};
use super::control_dict::ControlDict;
use super::error::CaseError;
use super::parser::read_dict_file_with_includes;
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

/// How old a change must be before it is read: a file caught while it is being written would
/// otherwise be read half-written.
const SETTLE: Duration = Duration::from_millis(100);

/// How long after its last change the file's text is compared on every look, not only its
/// time: file times tick coarsely (a few ms on Linux, up to 2 s on some mounted file
/// systems), so a second write within the tick of one already read keeps the same time.
const RECENT: Duration = Duration::from_secs(3);

/// A changed controlDict as read: its settings and the notes its reading gave (ignored or
/// adjusted entries), or the error at its place.
pub type ControlChange = Result<(ControlDict, Vec<String>), CaseError>;

/// Watches a case's `system/controlDict` and the files it `#include`s between two steps
/// (OpenFOAM's `Time::run`; OpenFOAM's `#include` adds a watch on the file it reads), each
/// by its modification time as OpenFOAM's `timeStamp` checking does, and by its text while
/// its change is recent. A change of any of them reads the controlDict again, and the files
/// it then includes are the ones watched.
#[derive(Debug)]
pub struct ControlDictWatch {
    case_dir: PathBuf,
    /// The controlDict first, then the files its last reading named in `#include`s.
    files: Vec<WatchedFile>,
    /// A reading put off because a file it newly included was still being written.
    put_off: bool,
}

/// One watched file as last taken.
#[derive(Debug)]
struct WatchedFile {
    path: PathBuf,
    /// The modification time of the text last taken (`None`: the file could not be read).
    seen: Option<SystemTime>,
    /// The text last taken.
    text: Vec<u8>,
}

impl WatchedFile {
    fn new(path: PathBuf) -> Self {
        WatchedFile {
            seen: modified(&path),
            text: read_watched(&path).unwrap_or_default(),
            path,
        }
    }

    /// Takes the file's present text, `stamp` its modification time now; whether it
    /// differs from the text last taken. A missing file, or one unchanged and long settled,
    /// is no change.
    fn take_change(&mut self, stamp: Option<SystemTime>) -> bool {
        let Some(stamp) = stamp else {
            return false;
        };
        if self.seen == Some(stamp) && age(stamp) >= RECENT {
            return false;
        }
        let Ok(text) = read_watched(&self.path) else {
            return false;
        };
        self.seen = Some(stamp);
        if text == self.text {
            return false;
        }
        self.text = text;
        true
    }
}

/// A watched file's bytes, read as the case's files are ([`read_regular_file`]): a device,
/// FIFO or oversized file is not read, and counts as unreadable.
fn read_watched(path: &Path) -> Result<Vec<u8>, ReadError> {
    read_regular_file(path, MAX_TEXT_BYTES)
}

impl ControlDictWatch {
    /// Watches `case_dir/system/controlDict` (and what it includes) from its present state
    /// on: create it before the case is read, so that no change made while the run starts up
    /// is missed.
    pub fn new(case_dir: &Path) -> Self {
        // A compressed controlDict is watched when it is the one there (as the case reads it).
        let plain = case_dir.join("system/controlDict");
        let gz = case_dir.join("system/controlDict.gz");
        let path = if !plain.exists() && gz.exists() {
            gz
        } else {
            plain
        };
        let mut watch = ControlDictWatch {
            case_dir: case_dir.to_path_buf(),
            files: vec![WatchedFile::new(path)],
            put_off: false,
        };
        // (a file that does not read now fails the case's own reading, with its message)
        let (_, included) = read_dict_file_with_includes(&watch.files[0].path, Some(case_dir));
        watch.follow_includes(&included);
        watch
    }

    /// The controlDict's settings when its text, or that of a file it includes, has changed
    /// since the last look (the run keeps its settings when it does not read, and reads the
    /// next change). `None` while they are unchanged, while one changed less than a tenth of
    /// a second ago, or while the controlDict is missing for a moment (an editor replacing
    /// it).
    pub fn changed(&mut self) -> Option<ControlChange> {
        // One look at each file's time, which both the wait and the taking go by.
        let stamps: Vec<Option<SystemTime>> =
            self.files.iter().map(|f| modified(&f.path)).collect();
        stamps[0]?;
        if stamps.iter().flatten().any(|&stamp| settling(stamp)) {
            return None;
        }
        // every file's change taken, not only the first one's
        let mut any = std::mem::take(&mut self.put_off);
        for (file, stamp) in self.files.iter_mut().zip(stamps) {
            any |= file.take_change(stamp);
        }
        if !any {
            return None;
        }
        let (read, included) =
            read_dict_file_with_includes(&self.files[0].path, Some(&self.case_dir));
        // The includes named are watched whether or not the file read, so that the next
        // change mends it (an include named before its file was written, a broken one).
        // A file newly included is taken after the reading: if it changed within the
        // settling time it may have been read half-written, or changed since; read again.
        if self.follow_includes(&included) {
            self.put_off = true;
            return None;
        }
        let mut notes = Vec::new();
        let read = read.and_then(|dict| ControlDict::from_dict(&dict, &mut notes));
        Some(read.map(|control| (control, notes)))
    }

    /// Watches the files `included` from now on, keeping the state of those already
    /// watched; whether a file newly watched is still settling.
    fn follow_includes(&mut self, included: &[PathBuf]) -> bool {
        let mut old: Vec<WatchedFile> = self.files.drain(1..).collect();
        let mut settling = false;
        for path in included {
            if self.files.iter().any(|f| &f.path == path) {
                continue;
            }
            let file = match old.iter().position(|f| &f.path == path) {
                Some(k) => old.swap_remove(k),
                None => {
                    let file = WatchedFile::new(path.clone());
                    settling |= file.seen.is_some_and(self::settling);
                    file
                }
            };
            self.files.push(file);
        }
        settling
    }
}

/// Whether a file modified at `stamp` changed less than [`SETTLE`] ago (it may be
/// half-written).
fn settling(stamp: SystemTime) -> bool {
    age(stamp) < SETTLE
}

/// Time since `stamp` (a time in the future, a clock's skew, counts as old).
fn age(stamp: SystemTime) -> Duration {
    SystemTime::now().duration_since(stamp).unwrap_or(RECENT)
}

fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    const CONTROL: &str = "endTime 1; deltaT 0.01; writeControl timeStep; writeInterval 10;";

    /// Writes `contents` at `path` with a modification time `seconds` after the epoch (long
    /// settled).
    fn write(path: &Path, contents: impl AsRef<[u8]>, seconds: u64) {
        fs::write(path, contents).unwrap();
        let file = fs::File::options().write(true).open(path).unwrap();
        file.set_modified(SystemTime::UNIX_EPOCH + Duration::from_secs(seconds))
            .unwrap();
    }

    /// A scratch case directory with its `system` folder, named after the test.
    fn scratch_case(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("fsim-watch-{name}-{}", std::process::id()));
        fs::create_dir_all(dir.join("system")).unwrap();
        dir
    }

    #[test]
    fn a_changed_file_is_read_once_and_a_broken_one_reports_its_place() {
        let dir = scratch_case("changed");
        let path = dir.join("system/controlDict");
        write(&path, CONTROL, 1_000);
        let mut watch = ControlDictWatch::new(&dir);
        assert!(watch.changed().is_none());

        write(&path, CONTROL.replace("endTime 1", "endTime 2"), 1_001);
        let (control, notes) = watch.changed().expect("a change").expect("a valid file");
        assert_eq!(control.end_time, 2.0);
        assert!(notes.is_empty());
        assert!(watch.changed().is_none(), "one change is read once");

        // a rewrite with the same time (one tick of a coarse clock) is seen while recent
        let recent = SystemTime::now() - Duration::from_secs(1);
        fs::write(&path, CONTROL.replace("endTime 1", "endTime 3")).unwrap();
        let file = fs::File::options().write(true).open(&path).unwrap();
        file.set_modified(recent).unwrap();
        assert_eq!(watch.changed().unwrap().unwrap().0.end_time, 3.0);
        fs::write(&path, CONTROL.replace("endTime 1", "endTime 4")).unwrap();
        file.set_modified(recent).unwrap();
        assert_eq!(watch.changed().unwrap().unwrap().0.end_time, 4.0);
        assert!(watch.changed().is_none());

        write(&path, format!("{CONTROL}\nstopAt now;"), 1_002);
        let e = watch.changed().expect("a change").unwrap_err();
        assert_eq!((e.line, e.col), (2, 8), "{e}");

        // the notes of the reading come with the settings
        write(&path, CONTROL.replace("10;", "10; purgeWrite -2;"), 1_003);
        let (_, notes) = watch.changed().unwrap().unwrap();
        assert_eq!(notes.len(), 1, "{notes:?}");

        // a change of a moment ago waits until it has settled (unless this thread stalled)
        let written = std::time::Instant::now();
        fs::write(&path, CONTROL).unwrap();
        let early = watch.changed();
        if written.elapsed() < SETTLE {
            assert!(early.is_none());
            std::thread::sleep(SETTLE);
            assert_eq!(watch.changed().unwrap().unwrap().0.end_time, 1.0);
        }

        fs::remove_file(&path).unwrap();
        assert!(watch.changed().is_none(), "a missing file is no change");
        write(&path, format!("{CONTROL} stopAt writeNow;"), 1_004);
        let (control, _) = watch.changed().unwrap().unwrap();
        assert_eq!(control.stop_at, crate::case::StopAt::WriteNow);
        fs::remove_dir_all(&dir).unwrap();
    }

    /// Edits of a file the controlDict `#include`s are read as OpenFOAM reads them; a file
    /// no longer included is no longer watched, and a newly included one is.
    #[test]
    fn included_files_are_watched_while_they_are_included() {
        let dir = scratch_case("include");
        let path = dir.join("system/controlDict");
        let times = dir.join("system/times");
        let other = dir.join("system/other");
        write(&times, "endTime 1;", 1_000);
        write(&other, "endTime 7;", 1_000);
        let base = "deltaT 0.01; writeControl timeStep; writeInterval 10;";
        write(&path, format!("#include \"times\"\n{base}"), 1_000);
        let mut watch = ControlDictWatch::new(&dir);
        assert!(watch.changed().is_none());

        write(&times, "endTime 2;", 1_001);
        let (control, _) = watch.changed().expect("a change").expect("a valid file");
        assert_eq!(control.end_time, 2.0);
        assert!(watch.changed().is_none(), "one change is read once");

        // a broken included file is reported at its own line and column
        write(&times, "endTime 3;\nstopAt now;", 1_002);
        let e = watch.changed().expect("a change").unwrap_err();
        assert!(e.to_string().contains("times"), "{e}");
        assert_eq!((e.line, e.col), (2, 8), "{e}");

        write(&path, format!("#include \"other\"\n{base}"), 1_003);
        assert_eq!(watch.changed().unwrap().unwrap().0.end_time, 7.0);
        write(&times, "endTime 4;", 1_004);
        assert!(watch.changed().is_none(), "no longer included");
        write(&other, "endTime 8;", 1_004);
        assert_eq!(watch.changed().unwrap().unwrap().0.end_time, 8.0);

        // An include named before its file is written: an error, then the file's creation
        // is read.
        let late = dir.join("system/late");
        write(&path, format!("#include \"late\"\n{base}"), 1_005);
        let e = watch.changed().expect("a change").unwrap_err();
        assert!(e.message.contains("file not found"), "{e}");
        write(&late, "endTime 9;", 1_006);
        assert_eq!(watch.changed().unwrap().unwrap().0.end_time, 9.0);

        // A newly included file that does not read: its mending is read.
        let fresh = dir.join("system/fresh");
        write(&fresh, "endTime 10", 1_007);
        write(&path, format!("#include \"fresh\"\n{base}"), 1_007);
        assert!(watch.changed().expect("a change").is_err());
        write(&fresh, "endTime 10;", 1_008);
        assert_eq!(watch.changed().unwrap().unwrap().0.end_time, 10.0);

        // A file newly included while it is being written: read once it has settled.
        let newest = dir.join("system/newest");
        write(&path, format!("#include \"newest\"\n{base}"), 1_009);
        let written = std::time::Instant::now();
        fs::write(&newest, "endTime 11;").unwrap();
        let early = watch.changed();
        if written.elapsed() < SETTLE {
            assert!(early.is_none(), "{early:?}");
            std::thread::sleep(SETTLE);
            assert_eq!(watch.changed().unwrap().unwrap().0.end_time, 11.0);
        }
        fs::remove_dir_all(&dir).unwrap();
    }

    /// A case whose controlDict is compressed, as OpenFOAM may write it, is watched too.
    #[test]
    fn a_compressed_control_dict_is_watched() {
        use std::io::Write;
        let dir = scratch_case("gz");
        let path = dir.join("system/controlDict.gz");
        let gzip = |text: &str| {
            let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
            enc.write_all(text.as_bytes()).unwrap();
            enc.finish().unwrap()
        };
        write(&path, gzip(CONTROL), 1_000);
        let mut watch = ControlDictWatch::new(&dir);
        assert!(watch.changed().is_none());
        write(
            &path,
            gzip(&CONTROL.replace("endTime 1", "endTime 5")),
            1_001,
        );
        assert_eq!(watch.changed().unwrap().unwrap().0.end_time, 5.0);
        fs::remove_dir_all(&dir).unwrap();
    }
}
