//! Reads one OpenFOAM dictionary file and reports how long the parse took, for measuring the
//! parser on large fields (`0/U`) and particle position lists. Run under `/usr/bin/time -f
//! '%e s %M KB'` for the peak resident memory.
//!
//! `cargo run --release --example parse_bench -- CASE/constant/kinematicCloudPositions`

use std::time::Instant;

use fsim::case::read_dict_file;

fn main() {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: parse_bench FILE");
        std::process::exit(2);
    };
    let path = std::path::Path::new(&path);
    let bytes = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
    let start = Instant::now();
    let dict = match read_dict_file(path, None) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("{}", e.report());
            std::process::exit(1);
        }
    };
    let seconds = start.elapsed().as_secs_f64();
    let elements: usize = dict
        .values
        .iter()
        .chain(
            dict.entries()
                .iter()
                .filter_map(|e| e.as_tokens())
                .flatten(),
        )
        .filter_map(|item| item.as_list().map(|l| l.len()))
        .sum();
    println!(
        "{}: {bytes} bytes, {elements} list elements, parsed in {seconds:.3} s ({:.0} MB/s)",
        path.display(),
        bytes as f64 / 1e6 / seconds
    );
}
