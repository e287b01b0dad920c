//! The direct model between plane walls, the long version of `tests/direct/walls.rs`.
//!
//! ```text
//! cargo run --release --example wall_slit_drag -- faxen   # midway, against Faxén
//! cargo run --release --example wall_slit_drag -- near    # parallel, near one wall
//! cargo run --release --example wall_slit_drag -- approach R L LAT FROM TO DT EVERY [U]
//! ```
//!
//! `faxen`: a sphere held still between walls `2l` apart that move at `−U` (the sphere's
//! frame of one moving parallel to them), periodic along x and z with period `L`;
//! λ = a/l = 1/4 and 1/3 at r/h = 4 and 8, each at two periods extrapolated as `K∞ + c/L²`,
//! against Faxén's `1/(1 − 1.004λ + 0.418λ³ + 0.21λ⁴ − 0.169λ⁵)` (Happel & Brenner 1965,
//! eq. 7-4.39). `near`: the same with the sphere's surface 0.375–1 radius from the lower
//! wall at r/h = 4 and 8 (L = 16 a). `approach`: a sphere of `R` cells pulled toward the
//! lower of two resting walls `2L` cells apart (period `LAT`) at `U` (default 10⁻³) from a
//! surface gap of `FROM` to `TO` cells at step `DT`, the normal drag printed every `EVERY`
//! cells. h = 1, ν = 1; minutes per run.

#[path = "../tests/support/box_case.rs"]
mod box_case;
#[path = "../tests/support/slit.rs"]
mod slit;

use slit::{approach_drag, faxen_midway, slit_drag, without_images};

fn faxen() {
    println!("| λ | r/h | K(L₁) | K(L₂) | K∞ | Faxén | error |");
    println!("|---|---|---|---|---|---|---|");
    for (lambda_inverse, r) in [(4, 4), (3, 4), (3, 8)] {
        let l = lambda_inverse * r;
        let lateral = [8 * l, 32 * l / 3];
        let dt = r as f64 / 4.0;
        let k = lateral.map(|lat| slit_drag(r as f64, l, lat, None, dt, None));
        let extrapolated = without_images(k, lateral);
        let exact = faxen_midway(1.0 / lambda_inverse as f64);
        println!(
            "| 1/{lambda_inverse} | {r} | {:.5} (L = {}) | {:.5} (L = {}) | {extrapolated:.5} | {exact:.5} | {:+.2} % |",
            k[0],
            lateral[0],
            k[1],
            lateral[1],
            100.0 * (extrapolated / exact - 1.0)
        );
    }
}

fn near() {
    println!("| gap / a | r/h = 4 | r/h = 8 | difference |");
    println!("|---|---|---|---|");
    for gap_over_radius in [0.375, 0.4375, 0.5, 0.625, 0.75, 1.0] {
        let coarse = slit_drag(4.0, 12, 64, Some(4.0 * gap_over_radius), 1.0, None);
        let fine = slit_drag(8.0, 24, 128, Some(8.0 * gap_over_radius), 2.0, None);
        println!(
            "| {gap_over_radius} | {coarse:.5} | {fine:.5} | {:+.2} % |",
            100.0 * (coarse / fine - 1.0)
        );
    }
}

/// The normal drag of a sphere of `radius` cells pulled toward the lower wall at `speed`
/// (walls at rest, `2l` cells apart, period `lateral`) from a surface gap of `from` to `to`
/// cells, printed every `every` cells.
fn approach(
    radius: f64,
    l: usize,
    lateral: usize,
    [from, to]: [f64; 2],
    dt: f64,
    every: f64,
    speed: f64,
) {
    let count = ((from - to) / every).round() as usize;
    let gaps: Vec<f64> = (1..=count).map(|i| from - every * i as f64).collect();
    let drag = approach_drag([radius, speed, dt], l, lateral, from, &gaps);
    for (gap, k) in gaps.iter().zip(drag) {
        println!("gap/a {:.4}  K {k:.4}", gap / radius);
    }
}

fn main() {
    match std::env::args().nth(1).as_deref() {
        Some("faxen") => faxen(),
        Some("near") => near(),
        Some("approach") => {
            let a: Vec<f64> = std::env::args()
                .skip(2)
                .map(|x| x.parse().unwrap())
                .collect();
            let speed = a.get(7).copied().unwrap_or(1e-3);
            approach(
                a[0],
                a[1] as usize,
                a[2] as usize,
                [a[3], a[4]],
                a[5],
                a[6],
                speed,
            );
        }
        _ => eprintln!("usage: wall_slit_drag faxen | near"),
    }
}
