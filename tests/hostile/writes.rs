//! Hostile cases, writes (docs/security.md, "Writes"): a symbolic link planted in a case where
//! fsimFoam writes, pointing outside the case, is refused with a one-line message naming the
//! link (exit 2 when found before the run, 1 when it appears during it), and nothing outside
//! the case changes.
//!
//! `cargo test --release --test hostile writes::`

use crate::support::*;
use std::collections::BTreeMap;
use std::fs;
use std::os::unix::fs::symlink;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Every file and directory below `dir` (links as their targets' text), with its bytes: what
/// must not change outside the case.
fn snapshot(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut all = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            let meta = fs::symlink_metadata(&path).unwrap();
            let key = path.strip_prefix(dir).unwrap().to_path_buf();
            if meta.is_dir() {
                all.insert(key, b"<dir>".to_vec());
                stack.push(path);
            } else if meta.is_symlink() {
                let target = fs::read_link(&path).unwrap();
                all.insert(key, target.to_string_lossy().as_bytes().to_vec());
            } else {
                all.insert(key, fs::read(&path).unwrap());
            }
        }
    }
    all
}

/// A scratch root holding `case` (the cavity tutorial, two steps, each written) and
/// `outside`, with a file `victim` there.
fn cavity(tag: &str) -> (Scratch, PathBuf, PathBuf) {
    let scratch = Scratch::new(tag);
    let case = copy_tutorial("cavity", &scratch.0, "cavity");
    let control = case.join("system/controlDict");
    set_entry(&control, "endTime", "0.01");
    set_entry(&control, "writeInterval", "0.005");
    let outside = scratch.0.join("outside");
    fs::create_dir_all(&outside).unwrap();
    fs::write(outside.join("victim"), "precious, not the case's\n").unwrap();
    (scratch, case, outside)
}

/// The only `fsimFoam: error:` line of a run; the message is one line.
fn error_line(out: &Output) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr);
    let errors: Vec<_> = stderr
        .lines()
        .filter(|l| l.starts_with("fsimFoam: error:"))
        .collect();
    assert_eq!(errors.len(), 1, "{stderr}");
    errors[0].to_string()
}

/// Runs the case; asserts the exit code, a one-line error naming `link` as a symbolic link,
/// and that `outside` is byte-for-byte as before.
fn assert_refused(case: &Path, outside: &Path, link: &Path, code: i32) {
    let before = snapshot(outside);
    let out = fsim(case, &["-threads", "1"]);
    assert_refused_output(&out, outside, &before, link, code);
}

fn assert_refused_output(
    out: &Output,
    outside: &Path,
    before: &BTreeMap<PathBuf, Vec<u8>>,
    link: &Path,
    code: i32,
) {
    let line = error_line(out);
    assert_eq!(out.status.code(), Some(code), "{line}");
    assert!(
        line.contains(&format!("{}: is a symbolic link", link.display())),
        "{line}"
    );
    assert!(!line.contains("panicked"), "{line}");
    assert_eq!(
        &snapshot(outside),
        before,
        "something changed outside the case"
    );
}

#[test]
fn a_monitor_file_linked_outside_is_refused() {
    let (_s, case, outside) = cavity("monitor-link");
    let dir = case.join("postProcessing/fluid/0");
    fs::create_dir_all(&dir).unwrap();
    let link = dir.join("fluid.dat");
    symlink(outside.join("victim"), &link).unwrap();
    assert_refused(&case, &outside, &link, 2);
    assert!(!case.join("0/fluid.vtk").exists(), "nothing half-run");
}

#[test]
fn a_post_processing_directory_linked_outside_is_refused() {
    let (_s, case, outside) = cavity("postprocessing-link");
    let link = case.join("postProcessing");
    symlink(&outside, &link).unwrap();
    assert_refused(&case, &outside, &link, 2);
}

#[test]
fn a_future_time_directory_linked_outside_is_refused() {
    let (_s, case, outside) = cavity("future-time-link");
    let link = case.join("0.01");
    symlink(&outside, &link).unwrap();
    assert_refused(&case, &outside, &link, 2);
    assert!(!case.join("0.005").exists(), "nothing half-run");
}

#[test]
fn a_linked_start_directory_that_would_be_rewritten_is_refused() {
    // `0/` holds the initial conditions and gets the start's VTK files and restart state:
    // as a link to a directory outside, it is refused (read, never written).
    let (_s, case, outside) = cavity("start-link");
    let elsewhere = outside.join("zero");
    fs::rename(case.join("0"), &elsewhere).unwrap();
    let link = case.join("0");
    symlink(&elsewhere, &link).unwrap();
    assert_refused(&case, &outside, &link, 2);
}

#[test]
fn the_start_directory_is_replaced_whole_and_its_links_are_kept_not_followed() {
    // A real `0/` whose initial pressure is a link to a file outside: the run rewrites `0/`
    // (adds its VTK files and restart state) and keeps the link as a link.
    let (_s, case, outside) = cavity("start-inner-link");
    fs::rename(case.join("0/p"), outside.join("p")).unwrap();
    symlink(outside.join("p"), case.join("0/p")).unwrap();
    // and a link where fsim writes a file of `0/` is replaced, its target untouched
    symlink(outside.join("victim"), case.join("0/fluid.vtk")).unwrap();
    let before = snapshot(&outside);
    let out = fsim(&case, &["-threads", "1"]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(fs::symlink_metadata(case.join("0/p")).unwrap().is_symlink());
    assert!(fs::symlink_metadata(case.join("0/fluid.vtk"))
        .unwrap()
        .is_file());
    assert!(case.join("0/restart.bin").is_file() && case.join("0/U").is_file());
    assert_eq!(
        snapshot(&outside),
        before,
        "something changed outside the case"
    );
    let hidden: Vec<_> = listing(&case)
        .into_iter()
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(hidden.is_empty(), "{hidden:?}");
}

#[test]
fn a_time_directory_linked_outside_during_the_run_is_refused() {
    // A long run writing every step; once it has written a time, it is stopped (SIGSTOP),
    // links to the outside are planted under the next time names, and it goes on.
    let (_s, case, outside) = cavity("mid-run-link");
    let control = case.join("system/controlDict");
    set_entry(&control, "endTime", "20");
    set_entry(&control, "writeInterval", "0.005");
    let before = snapshot(&outside);
    let mut child = Command::new(env!("CARGO_BIN_EXE_fsimFoam"))
        .arg("-case")
        .arg(&case)
        .args(["-threads", "1"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let pid = child.id() as libc::pid_t;
    let started = Instant::now();
    while !case.join("0.005").is_dir() {
        assert!(
            started.elapsed() < Duration::from_secs(60),
            "no write in 60 s"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    // SAFETY: signals to our own child, by its id.
    assert_eq!(unsafe { libc::kill(pid, libc::SIGSTOP) }, 0);
    let mut planted = Vec::new();
    for k in 1..=4000 {
        let name = fsim::output::time_name(k as f64 * 0.005, 6);
        let path = case.join(&name);
        if fs::symlink_metadata(&path).is_err() {
            symlink(&outside, &path).unwrap();
            planted.push(path);
        }
        if planted.len() == 20 {
            break;
        }
    }
    assert_eq!(unsafe { libc::kill(pid, libc::SIGCONT) }, 0);
    let deadline = Instant::now() + Duration::from_secs(60);
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            panic!("the run went on past the planted links");
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let out = Output {
        status,
        stdout: Vec::new(),
        stderr: {
            use std::io::Read;
            let mut text = Vec::new();
            child.stderr.take().unwrap().read_to_end(&mut text).unwrap();
            text
        },
    };
    assert_refused_output(&out, &outside, &before, &planted[0], 1);
}
