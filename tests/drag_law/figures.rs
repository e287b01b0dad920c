//! The CSV producer of `examples/drag_law_figures` (paper Fig. 2 and 3 for the drag-law model)
//! on a few points: where the bed is one sphere per cell (uniform ε), K is the closure's own
//! (Ergun's at φ ≥ 0.2: paper eq. 18), and the lattice settles slower than an isolated sphere.

#[path = "../../examples/drag_law_figures/study.rs"]
mod study;

use fsim::coupling::drag::DragClosure;

#[test]
fn porous_media_k_and_sedimentation_csv() {
    // φ = 0.5: L = (4π/(3·0.5))^(1/3) r = 2.03 r → one cell: ε uniform, K = (25/3) φ/ε³ = 33.3.
    let rows = study::porous_media(&[0.5], DragClosure::Paper, 300);
    assert_eq!(rows[0].cells, 1);
    let k = rows[0].k_drag_law;
    assert!(
        (k - study::k_ergun(0.5)).abs() < 0.01 * study::k_ergun(0.5),
        "{k}"
    );
    let csv = study::porous_csv(&rows, DragClosure::Paper);
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines[1], "phi,cells,K_dragLaw,K_Sangani,K_Ergun");
    let fields: Vec<f64> = lines[2].split(',').map(|x| x.parse().unwrap()).collect();
    assert_eq!(fields.len(), 5);
    assert!((fields[3] - study::k_sangani(0.5)).abs() < 1e-12);

    let rows = study::sedimentation(&[0.2], DragClosure::Paper, 2, 200);
    let v = rows[0].v_over_v0;
    // Hindered settling: slower than the isolated sphere, faster than nothing.
    assert!(v > 0.05 && v < 1.0, "{v}");
    let csv = study::sedimentation_csv(&rows, DragClosure::Paper);
    assert!(csv.lines().nth(1) == Some("phi,particles,v_over_V0,RichardsonZaki"));
    assert_eq!(csv.lines().count(), 3);
}
