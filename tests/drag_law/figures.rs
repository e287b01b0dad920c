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

/// Edits `file` (under `case`): each `from` must be there once.
fn edit(case: &std::path::Path, file: &str, pairs: &[(&str, &str)]) {
    let path = case.join(file);
    let mut text = std::fs::read_to_string(&path).unwrap();
    for (from, to) in pairs {
        assert_eq!(text.matches(from).count(), 1, "{file}: '{from}'");
        text = text.replace(from, to);
    }
    std::fs::write(&path, text).unwrap();
}

/// The porousMedia tutorial as a drag-law case (`dragLawCoeffs { fixedParticles yes; }`,
/// `meanVelocityForce` holding the superficial velocity `ubar`) on the example's own array:
/// `copies³` unit cells of side `unit`, `cells` cells per unit, the example's fluid and
/// sphere, paper closure and form, trilinear transfer, semi-implicit source; `steps` steps
/// of `dt`. Returns K, the last row of `postProcessing/dragLaw/0/dragLaw.dat`.
fn draglaw_case_k(
    dir: &std::path::Path,
    name: &str,
    geometry: (f64, usize, usize),
    ubar: f64,
    dt: f64,
    steps: usize,
) -> f64 {
    use crate::support::{copy_tutorial, fsim, set_entry, set_positions};
    let (unit, cells, copies) = geometry;
    let case = copy_tutorial("porousMedia", dir, name);
    let n = cells * copies;
    edit(
        &case,
        "system/blockMeshDict",
        &[
            (
                "convertToMeters $L;",
                &format!("convertToMeters {};", unit * copies as f64),
            ),
            ("($n $n $n)", &format!("({n} {n} {n})")),
        ],
    );
    let mut centres = Vec::new();
    let c = |m: usize| (m as f64 + 0.5) * unit;
    for k in 0..copies {
        for j in 0..copies {
            for i in 0..copies {
                centres.push([c(i), c(j), c(k)]);
            }
        }
    }
    set_positions(&case, &centres);
    edit(
        &case,
        "constant/kinematicCloudProperties",
        &[
            (
                "    transient       yes;\n",
                "    transient       yes;\n    sourceTerms { schemes { U semiImplicit 1; } }\n",
            ),
            (
                "    rho0            2500;\n",
                "    rho0 2500;\n    alphaMax 0.99;\n",
            ),
            (
                "    particleForces\n    {\n",
                "    particleForces\n    {\n        paper;\n",
            ),
            (
                "#calc \"2 * $L * cbrt(3 * $phi / (4 * pi))\"",
                &format!("{}", 2.0 * 1e-4),
            ),
        ],
    );
    edit(
        &case,
        "constant/couplingProperties",
        &[(
            "model           direct;",
            "model dragLaw;\ndragLawCoeffs { form paper; fixedParticles yes; \
             velocityInterpolation trilinear; voidFraction trilinear; }",
        )],
    );
    set_entry(&case.join("constant/transportProperties"), "nu", "1e-06");
    edit(
        &case,
        "system/fvSolution",
        &[("timeScheme      RK3;", "timeScheme Euler;")],
    );
    edit(
        &case,
        "system/fvOptions",
        &[("(0.001 0 0)", &format!("({ubar} 0 0)"))],
    );
    let control = case.join("system/controlDict");
    set_entry(&control, "adjustTimeStep", "no");
    set_entry(&control, "deltaT", &format!("{dt}"));
    set_entry(&control, "endTime", &format!("{}", dt * steps as f64));
    set_entry(&control, "writeControl", "timeStep");
    set_entry(&control, "writeInterval", &format!("{steps}"));
    let out = fsim(&case, &["-threads", "1"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let monitor =
        std::fs::read_to_string(case.join("postProcessing/dragLaw/0/dragLaw.dat")).unwrap();
    let last = monitor.lines().last().unwrap();
    last.split_whitespace().last().unwrap().parse().unwrap()
}

/// Fig. 2 by `fsimFoam` (the porousMedia case with `model dragLaw`, what
/// `tools/figures/fig2_k_vs_phi_draglaw.toml` runs) against the example's library set-up,
/// `study::porous_media` (paper eq. 19's K of the same array, grid, fluid and closure, driven
/// by a uniform gradient): the case's `meanVelocityForce` holds the example's own superficial
/// velocity, so the closure sees the same Reynolds number. The example's box of `copies³` unit
/// cells and the tutorial's single cell give the same K. Measured: within 3e-12 relative (the
/// same discrete equations, both converged after 400 steps); held to 1e-9.
#[test]
fn draglaw_case_gives_the_example_s_k() {
    use std::f64::consts::PI;
    let scratch = crate::support::Scratch::new("draglaw-porous");
    let (r, nu, rho, g, steps) = (1e-4, 1e-6, 1000.0, 1e-3, 400);
    // φ = 0.1: 2 cells per unit (ε uniform, the sphere on a node); φ = 0.3: one cell per unit.
    for phi in [0.1, 0.3] {
        let example = study::porous_media(&[phi], DragClosure::Paper, steps)[0].k_drag_law;
        let unit = (4.0 * PI * r * r * r / (3.0 * phi)).cbrt();
        let cells = ((unit / (2.0 * r)).round() as usize).max(1);
        let copies = ((4.6 * r / unit).ceil() as usize).max(1);
        // The example's superficial velocity: its force per sphere ρ G L³ over 6π μ r K.
        let u = rho * g * unit.powi(3) / (6.0 * PI * rho * nu * r * example);
        let h = unit / cells as f64;
        let dt = 0.1 * h * h / nu;
        // The example's copies³ unit cells, and the tutorial's one (what the study runs).
        for copies in [copies, 1] {
            let name = format!("phi{phi}-{copies}");
            let k = draglaw_case_k(&scratch.0, &name, (unit, cells, copies), u, dt, steps);
            let error = (k - example).abs() / example;
            println!(
                "phi {phi}, {copies}^3 unit cells: K fsimFoam {k:.8}, example {example:.8}, \
                 relative {error:.2e}"
            );
            assert!(
                error < 1e-9,
                "phi {phi}, {copies}^3 unit cells: K {k} against the example's {example}"
            );
        }
    }
}
