//! Writes the drag-law model's curves of the paper's Fig. 2 (porous-media drag K against φ)
//! and Fig. 3 (mean sedimentation velocity against φ) as CSV; `tools/drag_law_figures.py`
//! draws them.
//!
//! ```text
//! cargo run --release --example drag_law_figures -- OUTDIR [closure]
//! ```
//!
//! Writes `OUTDIR/drag_law_porous_media.csv` and `OUTDIR/drag_law_sedimentation.csv`
//! (closure: `paper` by default, any name of `DragClosure::NAMES`).

mod study;

use fsim::coupling::drag::DragClosure;

fn main() {
    let mut args = std::env::args().skip(1);
    let out = std::path::PathBuf::from(args.next().unwrap_or_else(|| ".".to_string()));
    let closure = DragClosure::from_name(&args.next().unwrap_or_else(|| "paper".into()), "closure")
        .unwrap_or_else(|e| {
            eprintln!("drag_law_figures: {e}");
            std::process::exit(2)
        });
    std::fs::create_dir_all(&out).expect("output directory");
    let phis: Vec<f64> = (1..=11).map(|i| 0.05 * i as f64).collect();
    let porous = study::porous_media(&phis, closure, 400);
    std::fs::write(
        out.join("drag_law_porous_media.csv"),
        study::porous_csv(&porous, closure),
    )
    .expect("write CSV");
    let settling_phis: Vec<f64> = (1..=8).map(|i| 0.05 * i as f64).collect();
    let settling = study::sedimentation(&settling_phis, closure, 4, 600);
    std::fs::write(
        out.join("drag_law_sedimentation.csv"),
        study::sedimentation_csv(&settling, closure),
    )
    .expect("write CSV");
    for r in &porous {
        println!(
            "phi {:.3}: K drag law {:.4}, Sangani {:.4}, Ergun {:.4} ({} cells per side)",
            r.phi, r.k_drag_law, r.k_sangani, r.k_ergun, r.cells
        );
    }
    for r in &settling {
        println!(
            "phi {:.3}: v/V0 {:.4}, Richardson-Zaki {:.4} ({} particles)",
            r.phi, r.v_over_v0, r.richardson_zaki, r.particles
        );
    }
}
