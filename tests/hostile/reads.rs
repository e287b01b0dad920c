//! Bounded reads, finite numbers and bounded messages (docs/security.md, "Reads" and
//! "Numbers and messages"): each test gives a copied tutorial one hostile file or value and
//! checks that fsimFoam refuses it with exit code 2 and one short error line naming the file
//! or entry, within seconds, under a 1 GiB address-space limit (so that an unbounded read
//! fails the test instead of the machine), and without writing into the case.

use crate::support::*;
use std::fs;
use std::io::Write;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Address space the child may use: an unbounded read fails under it rather than swapping.
const MEMORY_LIMIT: u64 = 1 << 30;

/// Time after which a child is killed (the test then fails): a blocked or endless run.
const KILL_AFTER: Duration = Duration::from_secs(30);

/// Time within which a refusal must come (generous for a loaded machine).
const REFUSED_WITHIN: Duration = Duration::from_secs(10);

/// Most bytes a refusal may print on stderr (notes included).
const STDERR_BYTES: usize = 4096;

/// What a run gave: exit code (`None` when killed), stderr, time taken.
pub(crate) struct Run {
    pub(crate) code: Option<i32>,
    pub(crate) stderr: String,
    pub(crate) elapsed: Duration,
}

impl Run {
    /// The `fsimFoam: error:` lines.
    pub(crate) fn errors(&self) -> Vec<&str> {
        self.stderr
            .lines()
            .filter(|l| l.starts_with("fsimFoam: error:"))
            .collect()
    }
}

/// Runs fsimFoam on `case` under [`MEMORY_LIMIT`], killed after [`KILL_AFTER`]; stdout and
/// stderr go to files beside the case, so that a flood of output cannot block the child.
pub(crate) fn run_limited(case: &Path, args: &[&str]) -> Run {
    let dir = case.parent().unwrap();
    let err_path = dir.join("stderr.txt");
    let mut command = Command::new(env!("CARGO_BIN_EXE_fsimFoam"));
    command
        .arg("-case")
        .arg(case)
        .args(args)
        .stdin(Stdio::null())
        .stdout(fs::File::create(dir.join("stdout.txt")).unwrap())
        .stderr(fs::File::create(&err_path).unwrap());
    // SAFETY: setrlimit is async-signal-safe; nothing else runs between fork and exec.
    unsafe {
        command.pre_exec(|| {
            let limit = libc::rlimit {
                rlim_cur: MEMORY_LIMIT,
                rlim_max: MEMORY_LIMIT,
            };
            if libc::setrlimit(libc::RLIMIT_AS, &limit) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    let start = Instant::now();
    let mut child = command.spawn().unwrap();
    let code = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status.code();
        }
        if start.elapsed() > KILL_AFTER {
            child.kill().unwrap();
            child.wait().unwrap();
            break None;
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let elapsed = start.elapsed();
    let bytes = fs::read(&err_path).unwrap();
    Run {
        code,
        stderr: String::from_utf8_lossy(&bytes[..bytes.len().min(1 << 20)]).into_owned(),
        elapsed,
    }
}

/// Runs `case` and checks the refusal: exit code 2, one short error line holding every one
/// of `expected`, a bounded stderr, within [`REFUSED_WITHIN`], the case unchanged.
pub(crate) fn assert_refused(case: &Path, args: &[&str], expected: &[&str]) -> Run {
    let before = listing(case);
    let run = run_limited(case, args);
    let shown = &run.stderr[..run.stderr.len().min(2000)];
    assert_eq!(run.code, Some(2), "after {:?}: {shown}", run.elapsed);
    let errors = run.errors();
    assert_eq!(errors.len(), 1, "{shown}");
    for part in expected {
        assert!(errors[0].contains(part), "{part:?} not in {}", errors[0]);
    }
    assert!(errors[0].len() < 400, "a long error line: {}", errors[0]);
    assert!(
        run.stderr.len() < STDERR_BYTES,
        "{} bytes of stderr",
        run.stderr.len()
    );
    assert!(
        run.elapsed < REFUSED_WITHIN,
        "refused after {:?}",
        run.elapsed
    );
    assert_eq!(listing(case), before, "the refused run wrote into the case");
    run
}

/// A copy of `tutorial` in a scratch directory.
pub(crate) fn case_of(tutorial: &str, tag: &str) -> (Scratch, PathBuf) {
    let scratch = Scratch::new(&format!("hostile-{tag}"));
    let case = copy_tutorial(tutorial, &scratch.0, "case");
    (scratch, case)
}

pub(crate) fn replace(file: &Path, from: &str, to: &str) {
    let text = fs::read_to_string(file).unwrap();
    assert!(text.contains(from), "{} lacks {from}", file.display());
    fs::write(file, text.replacen(from, to, 1)).unwrap();
}

fn mkfifo(path: &Path) {
    let name = std::ffi::CString::new(path.to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o600) }, 0);
}

#[test]
fn an_include_of_a_device_or_fifo_is_refused_unopened() {
    let (_s, case) = case_of("settlingInLiquid", "include-device");
    let control = case.join("system/controlDict");
    let text = fs::read_to_string(&control).unwrap();
    fs::write(&control, format!("{text}#include \"/dev/zero\"\n")).unwrap();
    assert_refused(
        &case,
        &[],
        &[
            "system/controlDict:",
            "/dev/zero",
            "found a character device",
            "not read",
        ],
    );
    // a FIFO would block the open itself: it must not be opened at all
    mkfifo(&case.join("system/pipe"));
    fs::write(&control, format!("{text}#include \"pipe\"\n")).unwrap();
    assert_refused(&case, &[], &["system/controlDict:", "pipe", "FIFO"]);
}

#[test]
fn a_field_linked_to_a_device_is_refused() {
    for device in ["/dev/zero", "/dev/urandom"] {
        let (_s, case) = case_of("settlingInLiquid", "field-device");
        fs::remove_file(case.join("0/p")).unwrap();
        std::os::unix::fs::symlink(device, case.join("0/p")).unwrap();
        assert_refused(&case, &[], &["0/p:", "found a character device"]);
    }
}

#[test]
fn a_control_dict_linked_to_a_device_is_refused() {
    let (_s, case) = case_of("settlingInLiquid", "control-device");
    fs::remove_file(case.join("system/controlDict")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", case.join("system/controlDict")).unwrap();
    assert_refused(&case, &[], &["system/controlDict:", "character device"]);
}

#[test]
fn a_field_that_is_a_fifo_is_refused_without_blocking() {
    let (_s, case) = case_of("settlingInLiquid", "field-fifo");
    fs::remove_file(case.join("0/p")).unwrap();
    mkfifo(&case.join("0/p"));
    assert_refused(&case, &[], &["0/p:", "FIFO"]);
}

#[test]
fn a_sparse_field_beyond_the_size_limit_is_refused_unread() {
    let (_s, case) = case_of("settlingInLiquid", "field-sparse");
    let limit = fsim::case::bounded_read::MAX_TEXT_BYTES;
    fs::File::create(case.join("0/p"))
        .unwrap()
        .set_len(limit + 1)
        .unwrap();
    assert_refused(
        &case,
        &[],
        &["0/p:", &format!("more than the {limit} bytes")],
    );
}

#[test]
fn a_positions_file_naming_a_device_is_refused() {
    let (_s, case) = case_of("settlingInLiquid", "positions-device");
    replace(
        &case.join("constant/kinematicCloudProperties"),
        "\"kinematicCloudPositions\"",
        "\"/dev/zero\"",
    );
    assert_refused(&case, &[], &["/dev/zero:", "character device"]);
}

#[test]
fn a_gzip_bomb_is_refused_past_its_expanded_limit() {
    let (_s, case) = case_of("settlingInLiquid", "gzip-bomb");
    // gzip members of 64 MiB of zeros (about 64 kB each), one past the limit's count:
    // a 0.3 MB file expanding past the limit
    let limit = fsim::case::bounded_read::MAX_GZIP_EXPANDED_BYTES;
    let block = 64 << 20;
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    enc.write_all(&vec![0u8; block]).unwrap();
    let member = enc.finish().unwrap();
    let members = limit as usize / block + 1;
    fs::remove_file(case.join("0/p")).unwrap();
    fs::write(case.join("0/p.gz"), member.repeat(members)).unwrap();
    assert_refused(
        &case,
        &[],
        &[
            "0/p.gz:",
            &format!("expands to more than the {limit} bytes"),
        ],
    );
}

#[test]
fn an_end_time_beyond_a_double_is_refused_as_inf_is() {
    let (_s, case) = case_of("settlingInLiquid", "end-time");
    set_entry(&case.join("system/controlDict"), "endTime", "1e400");
    assert_refused(
        &case,
        &[],
        &["system/controlDict:", "1e400", "out of range", "finite"],
    );
    // a field value too: refused in place, not read as infinity
    let (_s, case) = case_of("settlingInLiquid", "field-overflow");
    set_entry(&case.join("0/p"), "internalField", "uniform -1e999");
    assert_refused(&case, &[], &["0/p:", "-1e999", "out of range"]);
}

#[test]
fn tiny_write_intervals_and_time_steps_are_refused_with_the_limit_to_raise() {
    let (_s, case) = case_of("settlingInLiquid", "write-interval");
    set_entry(&case.join("system/controlDict"), "writeInterval", "1e-300");
    assert_refused(
        &case,
        &[],
        &[
            "system/controlDict:",
            "writeInterval 1e-300",
            "3.000e299 writes",
            "-maxWrites",
        ],
    );
    let (_s, case) = case_of("settlingInLiquid", "delta-t");
    set_entry(&case.join("system/controlDict"), "deltaT", "1e-300");
    assert_refused(
        &case,
        &[],
        &[
            "system/controlDict:",
            "deltaT 1e-300",
            "time steps",
            "-maxSteps",
        ],
    );
    // the limit is the user's to raise: 1500 steps pass 1000 no longer
    let (_s, case) = case_of("settlingInLiquid", "max-steps");
    assert_refused(
        &case,
        &["-maxSteps", "1000"],
        &["1.500e3 time steps", "-maxSteps"],
    );
}

#[test]
fn collision_resolution_steps_beyond_the_limit_are_refused() {
    let (_s, case) = case_of("impacts", "collision-steps");
    replace(
        &case.join("constant/kinematicCloudProperties"),
        "collisionResolutionSteps 48;",
        "collisionResolutionSteps 1e12;",
    );
    assert_refused(
        &case,
        &[],
        &[
            "constant/kinematicCloudProperties:",
            "collisionResolutionSteps",
            "10000",
        ],
    );
}

#[test]
fn a_long_bad_word_is_quoted_short() {
    let (_s, case) = case_of("settlingInLiquid", "long-word");
    let word = "x".repeat(5 << 20);
    set_entry(&case.join("system/controlDict"), "stopAt", &word);
    let run = assert_refused(
        &case,
        &[],
        &["system/controlDict:", "stopAt", "…(5242880 bytes)"],
    );
    assert!(
        run.stderr.matches("xxxxxxxxxx").count() < 30,
        "{}",
        run.stderr
    );
}

#[test]
fn a_file_outside_the_case_is_named_not_echoed() {
    let (s, case) = case_of("settlingInLiquid", "outside");
    let secret = s.0.join("secret");
    fs::write(&secret, "password hunter2;\n").unwrap();
    replace(
        &case.join("constant/kinematicCloudProperties"),
        "\"kinematicCloudPositions\"",
        &format!("\"{}\"", secret.display()),
    );
    let run = assert_refused(&case, &[], &["secret:1:", "outside the case directory"]);
    assert!(!run.stderr.contains("hunter2"), "{}", run.stderr);
}
