//! The direct model between plane walls (tests/support/slit.rs): a sphere midway between
//! two walls against Faxén's drag, and one pulled toward a wall at two resolutions.
//!
//! Midway, in the sphere's frame the walls and the far fluid move at `−U` along x, and the
//! drag over Stokes' is Faxén's (Happel & Brenner, *Low Reynolds number hydrodynamics*,
//! 1965, eq. 7-4.39, λ = a/l):
//!
//! ```text
//!   K = 1 / (1 − 1.004 λ + 0.418 λ³ + 0.21 λ⁴ − 0.169 λ⁵)
//! ```
//!
//! The lateral images add `c/L²` (a confined Stokeslet's far field is a two-dimensional
//! dipole): two periods extrapolate it away.

use crate::support::slit::{approach_drag, faxen_midway, slit_drag, without_images};

/// Midway between walls six radii apart (λ = 1/3) at r/h = 4: within 3 % of Faxén once the
/// lateral images are extrapolated away (measured +1.6 %; at r/h = 8, +0.7 %).
#[test]
fn a_sphere_midway_between_walls_feels_faxens_drag() {
    let lateral = [64, 96];
    let k = lateral.map(|lat| slit_drag(4.0, 12, lat, None, 1.0, Some(300)));
    let drag = without_images(k, lateral);
    let exact = faxen_midway(1.0 / 3.0);
    eprintln!(
        "K(L = 64) {:.5}, K(L = 96) {:.5}, extrapolated {drag:.5}, Faxén {exact:.5}: {:+.2} %",
        k[0],
        k[1],
        100.0 * (drag / exact - 1.0)
    );
    // the images raise the drag, and fall away with the period
    assert!(k[0] > k[1] && k[1] > drag, "{k:?} → {drag}");
    assert!((drag / exact - 1.0).abs() < 0.03, "{drag} against {exact}");
}

/// A sphere pulled toward a wall at r/h = 4 against the same sphere at r/h = 8, at surface
/// gaps of 11/16 to 1/2 radius (2.75 to 2 cells at r/h = 4), walls 4.5 radii apart, period
/// 6 radii. The coarse sphere moves 10⁻⁴ cells a step (a settling sphere's order), the fine
/// one 2·10⁻³. The resistance rises as the gap closes; down to 2.5 cells it agrees within
/// 3 % (measured +2.6 % and −0.1 %), at 2.25 and 2 cells, the resolution's limit, within
/// 10 % (measured +4.1 % and +6.5 %; docs/direct_model.md, "Walls").
#[test]
fn approaching_a_wall_the_drag_rises_as_at_twice_the_resolution() {
    let gaps = [2.75, 2.5, 2.25, 2.0];
    let coarse = approach_drag([4.0, 6.4e-4, 0.157], 9, 24, 3.25, &gaps);
    let fine_gaps = gaps.map(|g| 2.0 * g);
    let fine = approach_drag([8.0, 1e-3, 2.0], 18, 48, 7.0, &fine_gaps);
    for (i, gap) in gaps.iter().enumerate() {
        eprintln!(
            "gap/a {:.4}: r/h = 4 {:.4}, r/h = 8 {:.4} ({:+.2} %)",
            gap / 4.0,
            coarse[i],
            fine[i],
            100.0 * (coarse[i] / fine[i] - 1.0)
        );
    }
    for k in [&coarse, &fine] {
        assert!(k.windows(2).all(|w| w[1] > w[0]), "not rising: {k:?}");
    }
    for (i, bound) in [0.03, 0.03, 0.1, 0.1].into_iter().enumerate() {
        let error = coarse[i] / fine[i] - 1.0;
        assert!(
            error.abs() < bound,
            "gap {}: {coarse:?} against {fine:?}",
            gaps[i]
        );
    }
}
