//! Ghost layers and boundary faces of the velocity from the face conditions.
//!
//! Directions are filled in the order x, y, z over the whole padded extent of the other two,
//! so edge and corner ghosts end up consistent (a y-ghost of an x-ghost is computed from the
//! already-filled x-ghost).

use super::boundary_conditions::{BoundaryConditions, FaceCondition};
use super::padded_layout::PaddedLayout;
use rayon::prelude::*;

/// Fills ghosts and fixed boundary faces of all three components (one task per component).
pub(crate) fn fill_velocity_ghosts(
    layout: &PaddedLayout,
    bc: &BoundaryConditions,
    u: &mut [Vec<f64>; 3],
) {
    u.par_iter_mut()
        .enumerate()
        .for_each(|(c, uc)| fill_component_ghosts(layout, bc, uc, c));
}

/// Fills ghosts and fixed boundary faces of component `c` alone.
pub(crate) fn fill_component_ghosts(
    layout: &PaddedLayout,
    bc: &BoundaryConditions,
    a: &mut [f64],
    c: usize,
) {
    for d in 0..3 {
        fill_axis(layout, bc, a, c, d);
    }
}

/// Sets the fixed boundary faces of component `c` alone (the normal faces of walls, inlets
/// and slip planes) as [`fill_component_ghosts`] sets them: for a work array that last held
/// another component.
pub(crate) fn fill_fixed_faces(
    layout: &PaddedLayout,
    bc: &BoundaryConditions,
    a: &mut [f64],
    c: usize,
) {
    let n = layout.n[c];
    for (side, slot) in [(0, 1), (1, n + 1)] {
        let value = match bc.face(c, side) {
            FaceCondition::Wall { velocity } | FaceCondition::Inlet { velocity } => velocity[c],
            FaceCondition::Slip => 0.0,
            _ => continue,
        };
        plane_map(layout, a, c, slot, slot, |_| value);
    }
}

/// Sets `a[dst] = f(a[src])` over the whole padded plane normal to `d`: in parallel over
/// the z-planes of the array for `d` = x and y (each such ghost lies in the z-plane of its
/// source; the x ghosts are one sample a row, strided), a plane copy for `d` = z.
fn plane_map(
    layout: &PaddedLayout,
    a: &mut [f64],
    d: usize,
    dst: usize,
    src: usize,
    f: impl Fn(f64) -> f64 + Sync,
) {
    let s = layout.stride;
    let [d0, d1, _] = layout.dims;
    match d {
        0 => a.par_chunks_mut(s[2]).for_each(|plane| {
            for j in 0..d1 {
                plane[j * s[1] + dst] = f(plane[j * s[1] + src]);
            }
        }),
        1 => a.par_chunks_mut(s[2]).for_each(|plane| {
            for i in 0..d0 {
                plane[dst * s[1] + i] = f(plane[src * s[1] + i]);
            }
        }),
        _ => {
            for i in 0..d0 * d1 {
                a[dst * s[2] + i] = f(a[src * s[2] + i]);
            }
        }
    }
}

/// Component `c` along direction `d`: ghost slots 0 and n+1, and for the normal component
/// the boundary faces (slot 1 and slot n+1).
fn fill_axis(layout: &PaddedLayout, bc: &BoundaryConditions, a: &mut [f64], c: usize, d: usize) {
    let n = layout.n[d];
    let normal = c == d;
    match bc.face(d, 0) {
        FaceCondition::Periodic | FaceCondition::Empty => plane_map(layout, a, d, 0, n, |x| x),
        FaceCondition::Wall { velocity } | FaceCondition::Inlet { velocity } => {
            let vc = velocity[c];
            if normal {
                plane_map(layout, a, d, 1, 1, |_| vc);
                plane_map(layout, a, d, 0, 1, |_| vc);
            } else {
                // Zero at the face: the ghost mirrors the interior value about `vc`.
                plane_map(layout, a, d, 0, 1, |x| 2.0 * vc - x);
            }
        }
        FaceCondition::Slip => {
            if normal {
                plane_map(layout, a, d, 1, 1, |_| 0.0);
                plane_map(layout, a, d, 0, 1, |_| 0.0);
            } else {
                plane_map(layout, a, d, 0, 1, |x| x);
            }
        }
        // Zero gradient; the normal boundary face is an unknown set by the step.
        FaceCondition::Outlet { .. } => plane_map(layout, a, d, 0, 1, |x| x),
    }
    match bc.face(d, 1) {
        FaceCondition::Periodic | FaceCondition::Empty => plane_map(layout, a, d, n + 1, 1, |x| x),
        FaceCondition::Wall { velocity } | FaceCondition::Inlet { velocity } => {
            let vc = velocity[c];
            if normal {
                plane_map(layout, a, d, n + 1, n + 1, |_| vc);
            } else {
                plane_map(layout, a, d, n + 1, n, |x| 2.0 * vc - x);
            }
        }
        FaceCondition::Slip => {
            if normal {
                plane_map(layout, a, d, n + 1, n + 1, |_| 0.0);
            } else {
                plane_map(layout, a, d, n + 1, n, |x| x);
            }
        }
        FaceCondition::Outlet { .. } => {
            if !normal {
                plane_map(layout, a, d, n + 1, n, |x| x);
            }
        }
    }
}

/// Zero-gradient predictor on outlet faces: the boundary face takes its neighbour's value
/// (the projection then corrects it with the fixed-pressure gradient).
pub(crate) fn extrapolate_outlets(
    layout: &PaddedLayout,
    bc: &BoundaryConditions,
    u: &mut [Vec<f64>; 3],
) {
    for d in 0..3 {
        let n = layout.n[d];
        if bc.outlet_pressure(d, 0).is_some() {
            plane_map(layout, &mut u[d], d, 1, 2, |x| x);
        }
        if bc.outlet_pressure(d, 1).is_some() {
            plane_map(layout, &mut u[d], d, n + 1, n, |x| x);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ghosts_put_the_wall_velocity_on_the_face_and_wrap_periodic_directions() {
        let layout = PaddedLayout::new([4, 3, 2]);
        let bc = BoundaryConditions {
            faces: [
                FaceCondition::Periodic,
                FaceCondition::Periodic,
                FaceCondition::Wall { velocity: [0.0; 3] },
                FaceCondition::Wall {
                    velocity: [2.0, 0.0, 0.0],
                },
                FaceCondition::Slip,
                FaceCondition::Slip,
            ],
        };
        let mut u: [Vec<f64>; 3] = std::array::from_fn(|c| {
            (0..layout.len)
                .map(|i| (i * (c + 3)) as f64 * 0.01)
                .collect()
        });
        fill_velocity_ghosts(&layout, &bc, &mut u);
        for k in 1..=2 {
            for i in 1..=4 {
                // Tangential u: the mean of ghost and first cell is the wall's velocity.
                let lo = 0.5 * (u[0][layout.index(i, 0, k)] + u[0][layout.index(i, 1, k)]);
                let hi = 0.5 * (u[0][layout.index(i, 3, k)] + u[0][layout.index(i, 4, k)]);
                assert!(lo.abs() < 1e-15 && (hi - 2.0).abs() < 1e-15);
                // Normal v on both walls is zero.
                assert_eq!(u[1][layout.index(i, 1, k)], 0.0);
                assert_eq!(u[1][layout.index(i, 4, k)], 0.0);
            }
            for j in 1..=3 {
                assert_eq!(u[1][layout.index(0, j, k)], u[1][layout.index(4, j, k)]);
                assert_eq!(u[1][layout.index(5, j, k)], u[1][layout.index(1, j, k)]);
            }
        }
        // Slip in z: no normal velocity, tangential ghost mirrors the interior.
        assert_eq!(u[2][layout.index(2, 2, 1)], 0.0);
        assert_eq!(u[0][layout.index(2, 2, 0)], u[0][layout.index(2, 2, 1)]);
    }

    /// A work array that held anything gets component `c`'s fixed boundary faces as the
    /// whole ghost fill would set them, and nothing else changes.
    #[test]
    fn fixed_faces_are_those_the_ghost_fill_sets() {
        let layout = PaddedLayout::new([5, 4, 3]);
        let bc = BoundaryConditions {
            faces: [
                FaceCondition::Inlet {
                    velocity: [1.5, 0.2, 0.0],
                },
                FaceCondition::Wall {
                    velocity: [-0.5, 0.0, 0.3],
                },
                FaceCondition::Periodic,
                FaceCondition::Periodic,
                FaceCondition::Slip,
                FaceCondition::Wall { velocity: [0.0; 3] },
            ],
        };
        let mut rng = crate::particles::SplitMix64::new(17);
        let mut noise = || rng.next_f64() - 0.5;
        // Whether slot's index along every direction but `c` is interior (not a ghost, which
        // the later passes of the whole fill overwrite along the edges).
        let interior_across = |slot: usize, c: usize| {
            (0..3).filter(|&d| d != c).all(|d| {
                let along = slot / layout.stride[d] % layout.dims[d];
                (1..=layout.n[d]).contains(&along)
            })
        };
        for c in 0..3 {
            let held: Vec<f64> = (0..layout.len).map(|_| noise()).collect();
            let mut filled = held.clone();
            fill_component_ghosts(&layout, &bc, &mut filled, c);
            let mut fixed = held.clone();
            fill_fixed_faces(&layout, &bc, &mut fixed, c);
            let n = layout.n[c];
            for slot in 0..layout.len {
                let along = slot / layout.stride[c] % layout.dims[c];
                let boundary = bc.face(c, usize::from(along > 1));
                let is_fixed = (along == 1 || along == n + 1)
                    && matches!(
                        boundary,
                        FaceCondition::Wall { .. }
                            | FaceCondition::Inlet { .. }
                            | FaceCondition::Slip
                    );
                if !is_fixed {
                    assert_eq!(fixed[slot], held[slot], "component {c}, slot {slot}");
                } else if interior_across(slot, c) {
                    assert_eq!(fixed[slot], filled[slot], "component {c}, slot {slot}");
                }
            }
        }
    }
}
