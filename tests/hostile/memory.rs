//! Memory and work estimated before they are committed (docs/security.md, "Memory and
//! work"): each test gives a copied tutorial a grid, cloud or option that would need more
//! memory or work than the machine has and checks that fsimFoam refuses it with exit code 2
//! and one short error line naming the entry, within seconds, under the 1 GiB address-space
//! limit of [`run_limited`](crate::reads), before writing anything.

use crate::reads::{assert_refused, case_of, replace};

/// The cavity tutorial with `cells` in place of its `(64 64 1)`.
fn cavity_with_cells(cells: &str, tag: &str) -> (crate::support::Scratch, std::path::PathBuf) {
    let (scratch, case) = case_of("cavity", tag);
    replace(
        &case.join("system/blockMeshDict"),
        "(64 64 1)",
        &format!("({cells})"),
    );
    (scratch, case)
}

#[test]
fn cell_counts_whose_product_overflows_are_refused() {
    let (_s, case) = cavity_with_cells("4294967296 4294967296 1", "cells-overflow");
    assert_refused(
        &case,
        &[],
        &["system/blockMeshDict:", "4294967296 4294967296 1", "limit"],
    );
}

#[test]
fn a_billion_cells_in_a_row_are_refused_before_allocating() {
    let (_s, case) = cavity_with_cells("1000000000 1 1", "cells-row");
    assert_refused(
        &case,
        &[],
        &[
            "system/blockMeshDict",
            "1000000000 x 1 x 1",
            "needs at least",
        ],
    );
}

#[test]
fn a_grid_larger_than_memory_is_refused_before_allocating() {
    let (_s, case) = cavity_with_cells("25000 25000 1", "cells-square");
    assert_refused(
        &case,
        &[],
        &[
            "system/blockMeshDict",
            "25000 x 25000 x 1",
            "needs at least",
        ],
    );
}

#[test]
fn a_memory_limit_below_the_need_is_refused_with_both() {
    let (_s, case) = case_of("cavity", "memory-limit");
    assert_refused(
        &case,
        &["-memory", "100K"],
        &["64 x 64 x 1", "needs at least", "-memory limit of 102.4 kB"],
    );
}

#[test]
fn a_positions_count_beyond_the_list_fails_fast() {
    let (_s, case) = case_of("settlingInLiquid", "positions-count");
    replace(
        &case.join("constant/kinematicCloudPositions"),
        "1\n(",
        "1000000000\n(",
    );
    assert_refused(
        &case,
        &[],
        &["constant/kinematicCloudPositions:", "1000000000 elements"],
    );
}

#[test]
fn a_packing_box_outside_the_domain_is_refused_before_packing() {
    let (_s, case) = case_of("particleSettling", "packing-outside");
    replace(
        &case.join("constant/kinematicCloudProperties"),
        "(0.0235 0.0235 0.0475)",
        "(0.0235 0.0235 4.75)",
    );
    assert_refused(
        &case,
        &[],
        &["constant/kinematicCloudProperties:", "outside the domain"],
    );
}

#[test]
fn a_packing_of_a_billion_spheres_is_refused_before_packing() {
    let (_s, case) = case_of("particleSettling", "packing-count");
    let file = case.join("constant/kinematicCloudProperties");
    replace(&file, "expectation 0.002;", "expectation 0.00002;");
    replace(&file, "minValue    0.0018;", "minValue    0.000018;");
    replace(&file, "maxValue    0.0022;", "maxValue    0.000022;");
    assert_refused(
        &case,
        &[],
        &[
            "constant/kinematicCloudProperties:",
            "volumeFraction",
            "spheres",
        ],
    );
}

#[test]
fn a_hundred_thousand_threads_are_refused() {
    let (_s, case) = case_of("cavity", "threads");
    assert_refused(
        &case,
        &["-threads", "100000"],
        &["-threads 100000", "per core"],
    );
}

/// settlingColumn with a positions file of `n` particles, each line written by `line(i)`.
fn column_with_positions(
    n: usize,
    tag: &str,
    line: impl Fn(usize) -> String,
) -> (crate::support::Scratch, std::path::PathBuf) {
    use std::io::Write;
    let (scratch, case) = case_of("settlingColumn", tag);
    let file = std::fs::File::create(case.join("constant/kinematicCloudPositions")).unwrap();
    let mut out = std::io::BufWriter::new(file);
    write!(
        out,
        "FoamFile\n{{\n    format ascii;\n    class vectorField;\n}}\n{n}\n(\n"
    )
    .unwrap();
    for i in 0..n {
        out.write_all(line(i).as_bytes()).unwrap();
    }
    out.write_all(b")\n").unwrap();
    out.flush().unwrap();
    (scratch, case)
}

#[test]
fn ten_million_particles_are_refused_before_their_file_is_read() {
    // a real 10⁷-line file (300 MB): reading it whole took 0.9 GB and aborted under the limit
    let (_s, case) = column_with_positions(10_000_000, "positions-1e7", |i| {
        let (a, b, c) = (i % 215, (i / 215) % 215, i / (215 * 215));
        format!(
            "({:.6} {:.6} {:.6})\n",
            1e-4 * a as f64,
            1e-4 * b as f64,
            1e-4 * c as f64
        )
    });
    assert_refused(
        &case,
        &[],
        &[
            "constant/kinematicCloudPositions:",
            "10000000 particles",
            "needs at least",
        ],
    );
}

#[test]
fn particles_piled_at_one_point_are_refused_before_their_pairs_are_listed() {
    // 10⁵ particles at one point would list 5·10⁹ pairs before the overlap check names two
    let (_s, case) = column_with_positions(100_000, "positions-pile", |_| {
        "(0.00334184 0.00327871 0.00406729)\n".to_string()
    });
    assert_refused(
        &case,
        &[],
        &[
            "constant/kinematicCloudPositions:",
            "100000 particles (among them 0 and 1)",
            "so they overlap",
        ],
    );
}

#[test]
fn an_allocation_beyond_the_estimate_ends_the_run_with_a_message() {
    // 2400 x 2400 cells: the estimate (a lower bound, 0.86 GB) fits under the 1 GiB limit,
    // the solver's scratch then does not; Rust's own handler aborted (SIGABRT, exit 134)
    let (_s, case) = cavity_with_cells("2400 2400 1", "allocation");
    let before = std::fs::read_dir(&case).unwrap().count();
    let run = crate::reads::run_limited(&case, &[]);
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    let errors = run.errors();
    assert_eq!(errors.len(), 1, "{}", run.stderr);
    assert!(
        errors[0].contains("out of memory: an allocation of"),
        "{}",
        errors[0]
    );
    assert!(!run.stderr.contains("backtrace"), "{}", run.stderr);
    assert_eq!(
        std::fs::read_dir(&case).unwrap().count(),
        before,
        "a directory was left"
    );
}

#[test]
fn clock_time_writes_stop_at_the_write_limit() {
    // a write every nanosecond of wall clock is one every step: not countable before the run
    let (_s, case) = case_of("cavity", "clock-writes");
    let control = case.join("system/controlDict");
    replace(
        &control,
        "writeControl    runTime;",
        "writeControl    clockTime;",
    );
    replace(&control, "writeInterval   5;", "writeInterval   1e-9;");
    let run = crate::reads::run_limited(&case, &["-maxWrites", "5"]);
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    let errors = run.errors();
    assert_eq!(errors.len(), 1, "{}", run.stderr);
    assert!(errors[0].contains("5 writes, the limit"), "{}", errors[0]);
    assert!(errors[0].contains("-maxWrites"), "{}", errors[0]);
    let times = std::fs::read_dir(&case)
        .unwrap()
        .filter(|e| {
            let name = e.as_ref().unwrap().file_name();
            name.to_str().unwrap().parse::<f64>().is_ok()
        })
        .count();
    assert_eq!(times, 6, "the start and five writes");
}
