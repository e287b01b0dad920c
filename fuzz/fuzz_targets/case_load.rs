//! Fuzz target: loading a whole case (every dictionary and field, the cloud with its
//! injection) never panics, whatever the files hold (issue 41; docs/security.md).
//!
//! The input is a case in one text: each file starts with a line `@@ <path>`, one of
//! [`FILES`] (other names are skipped, so nothing is written outside the scratch case). The
//! seeds in `corpus/case_load/` are tutorials in this form. Run from `fuzz/` with a scratch
//! corpus directory first so that the seeds stay as committed:
//!
//! ```text
//! RUSTC_BOOTSTRAP=1 cargo fuzz run -s none case_load SCRATCH_DIR corpus/case_load -- -max_total_time=600
//! ```
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};

/// The files a case may hold, as the fuzzer may write them.
const FILES: [&str; 14] = [
    "system/controlDict",
    "system/blockMeshDict",
    "system/fvSolution",
    "system/fvOptions",
    "system/fvSchemes",
    "constant/transportProperties",
    "constant/couplingProperties",
    "constant/kinematicCloudProperties",
    "constant/g",
    "constant/porousParameters",
    "constant/kinematicCloudPositions",
    "constant/positions",
    "0/U",
    "0/p",
];

static RUN: AtomicU64 = AtomicU64::new(0);

fn scratch() -> PathBuf {
    let n = RUN.fetch_add(1, Ordering::Relaxed);
    std::env::temp_dir().join(format!("fsim-fuzz-case-{}-{n}", std::process::id()))
}

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let dir = scratch();
    for d in ["system", "constant", "0"] {
        std::fs::create_dir_all(dir.join(d)).unwrap();
    }
    let mut current: Option<&str> = None;
    let mut body = String::new();
    let mut flush = |name: Option<&str>, body: &mut String| {
        if let Some(name) = name {
            std::fs::write(dir.join(name), body.as_bytes()).unwrap();
        }
        body.clear();
    };
    for line in text.split_inclusive('\n') {
        if let Some(name) = line.strip_prefix("@@ ") {
            flush(current, &mut body);
            current = FILES.iter().copied().find(|f| *f == name.trim());
        } else {
            body.push_str(line);
        }
    }
    flush(current, &mut body);
    if let Ok(case) = fsim::case::Case::load(&dir) {
        let _ = fsim::case::cloud_properties::Cloud::from_case(&case);
    }
    let _ = std::fs::remove_dir_all(&dir);
});
