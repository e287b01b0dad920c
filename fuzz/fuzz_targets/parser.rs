//! Fuzz target: the dictionary parser never panics, and every error it reports points inside
//! the text it was given (`fsim::case::check_parser_invariants`).
//!
//! Run from `fuzz/` (only a stable toolchain is needed; libFuzzer needs nightly flags, which
//! `RUSTC_BOOTSTRAP=1` unlocks), with a scratch corpus directory first so that the seeds in
//! `corpus/parser/` stay as committed:
//!
//! ```text
//! RUSTC_BOOTSTRAP=1 cargo fuzz run -s none parser SCRATCH_DIR corpus/parser -- -max_total_time=600
//! ```
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    fsim::case::check_parser_invariants(&text);
});
