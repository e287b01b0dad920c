//! Time and size of one fluid write at 128³ cells (U vector + p scalar, f64), per format.
//!
//! `cargo run --release --example bench_fluid_write [-- N [DIR]]` (default N = 128, DIR the
//! system temporary directory). Each file is written three times; the best time is reported,
//! without and with the `fsync` a time directory commit adds; then a whole time directory
//! (fluid.vtk, fluid.vti, restart.bin, commit, collection). Files are removed afterwards.

use fsim::grid::Grid;
use fsim::output::{
    write_fluid, write_fluid_vti, write_fluid_vtk, CaseOutput, CellData, RestartHeader, SafeDir,
    RESTART_FILE_NAME,
};
use std::path::Path;
use std::time::Instant;

fn main() {
    let mut args = std::env::args().skip(1);
    let n: usize = args.next().map_or(128, |s| s.parse().expect("N"));
    let dir = args
        .next()
        .map_or_else(std::env::temp_dir, std::path::PathBuf::from)
        .join(format!("fsim-bench-output-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let grid = Grid::new([n; 3], [1.0 / n as f64; 3], [0.0; 3]);
    let cells = grid.cell_count();
    let u: Vec<[f64; 3]> = (0..cells).map(|c| [c as f64, 0.5, -1.0]).collect();
    let p: Vec<f64> = (0..cells).map(|c| (c as f64).sqrt()).collect();
    let fields = [CellData::Vector("U", &u), CellData::Scalar("p", &p)];
    println!("{n}^3 cells, U + p as f64");
    println!(
        "{:<28} {:>10} {:>14} {:>9}",
        "format", "write s", "write+fsync s", "MB"
    );
    let out = SafeDir::open_case(&dir).unwrap();
    measure(&dir, "fluid.vtk", "legacy .vtk (big-endian)", |name| {
        write_fluid_vtk(&out, name, &grid, "bench", &fields).unwrap()
    });
    measure(&dir, "fluid.vti", "XML .vti (raw appended)", |name| {
        write_fluid_vti(&out, name, &grid, &fields).unwrap()
    });
    let flat_u: Vec<f64> = u.iter().flatten().copied().collect();
    measure(&dir, "restart.bin", "restart.bin (CRC-32)", |name| {
        RestartHeader::new(0.0, 0, 1.0)
            .write(&out, name, &[("U", &flat_u), ("p", &p)])
            .unwrap()
    });
    // A whole time directory as the time loop writes it: both fluid files and the restart
    // state, committed (fsync of every file, rename) and listed in the collection.
    let case = dir.join("case");
    std::fs::create_dir_all(&case).unwrap();
    let mut output = CaseOutput::open(&case, 6, 0, 0.0).unwrap();
    let mut best = f64::INFINITY;
    for step in 1..=3 {
        let start = Instant::now();
        let time = output.begin(step as f64).unwrap();
        write_fluid(time.dir(), &grid, "bench", &fields).unwrap();
        RestartHeader::new(step as f64, step, 1.0)
            .write(time.dir(), RESTART_FILE_NAME, &[("U", &flat_u), ("p", &p)])
            .unwrap();
        output.commit(time).unwrap();
        best = best.min(start.elapsed().as_secs_f64());
    }
    let bytes: u64 = std::fs::read_dir(case.join("3"))
        .unwrap()
        .map(|e| e.unwrap().metadata().unwrap().len())
        .sum();
    println!(
        "{:<28} {:>10} {best:>14.3} {:>9.1}",
        "time directory, committed",
        "",
        bytes as f64 / 1e6
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

fn measure(dir: &Path, name: &str, label: &str, write: impl Fn(&str)) {
    let path = &dir.join(name);
    let mut best = f64::INFINITY;
    let mut best_synced = f64::INFINITY;
    for _ in 0..3 {
        let _ = std::fs::remove_file(path);
        let start = Instant::now();
        write(name);
        let written = start.elapsed().as_secs_f64();
        std::fs::File::open(path).unwrap().sync_all().unwrap();
        best = best.min(written);
        best_synced = best_synced.min(start.elapsed().as_secs_f64());
    }
    let mb = std::fs::metadata(path).unwrap().len() as f64 / 1e6;
    println!("{label:<28} {best:>10.3} {best_synced:>14.3} {mb:>9.1}");
}
