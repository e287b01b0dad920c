//! Fuzz target: the dictionary parser never panics, and every error it reports points inside
//! the text it was given.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    fsim::case::check_parser_invariants(&text);
});
