//! Conditions on the six faces of the box, and what they imply for each unknown.

use super::spectral_poisson::{AxisKind, PressureBoundary};
use crate::grid::Grid;

/// Condition on one face of the box; faces ordered x-, x+, y-, y+, z-, z+.
///
/// Velocities are in m/s; the outlet pressure is kinematic (`p/ρ`, m²/s²), as the solver's.
#[derive(Clone, Debug, PartialEq)]
pub enum FaceCondition {
    /// Cyclic pair: both faces of a direction must be periodic.
    Periodic,
    /// No-slip wall moving with `velocity` (zero for `noSlip`, the lid of a cavity otherwise).
    /// Its normal component must be zero.
    Wall { velocity: [f64; 3] },
    /// `symmetry`, `symmetryPlane`, `slip`: zero normal velocity, zero shear.
    Slip,
    /// Fixed velocity, zero normal pressure gradient (`fixedValue` U, `fixedFluxPressure` p).
    Inlet { velocity: [f64; 3] },
    /// Fixed pressure, zero-gradient velocity (`fixedValue`/`totalPressure` p).
    Outlet { pressure: f64 },
    /// A 2-D direction: one cell, no variation, no velocity along it (both faces).
    Empty,
}

/// The six face conditions of the box, ordered x-, x+, y-, y+, z-, z+.
#[derive(Clone, Debug, PartialEq)]
pub struct BoundaryConditions {
    pub faces: [FaceCondition; 6],
}

impl BoundaryConditions {
    /// Every face periodic.
    pub fn periodic() -> Self {
        BoundaryConditions {
            faces: std::array::from_fn(|_| FaceCondition::Periodic),
        }
    }

    /// The same conditions with every wall and inlet at rest: what the ghosts of a velocity
    /// *difference* obey (the fill is affine in the velocity, so the difference of two filled
    /// fields is the difference field filled with these conditions).
    pub fn at_rest(&self) -> Self {
        BoundaryConditions {
            faces: self.faces.clone().map(|f| match f {
                FaceCondition::Wall { .. } => FaceCondition::Wall { velocity: [0.0; 3] },
                FaceCondition::Inlet { .. } => FaceCondition::Inlet { velocity: [0.0; 3] },
                other => other,
            }),
        }
    }

    /// Condition on the low (`side = 0`) or high (`side = 1`) face of direction `d`.
    #[inline]
    pub fn face(&self, d: usize, side: usize) -> &FaceCondition {
        &self.faces[2 * d + side]
    }

    /// Checks the conditions against the grid: pairs that must match, one cell across an
    /// `Empty` direction, zero normal velocity on walls, and at least one cell everywhere.
    pub fn validate(&self, grid: &Grid) -> Result<(), String> {
        const NAMES: [&str; 6] = ["x-", "x+", "y-", "y+", "z-", "z+"];
        for d in 0..3 {
            if grid.n[d] == 0 {
                return Err(format!("direction {d} has zero cells"));
            }
            let (lo, hi) = (self.face(d, 0), self.face(d, 1));
            let lo_p = matches!(lo, FaceCondition::Periodic);
            let hi_p = matches!(hi, FaceCondition::Periodic);
            if lo_p != hi_p {
                return Err(format!(
                    "faces {} and {} must both be periodic or neither",
                    NAMES[2 * d],
                    NAMES[2 * d + 1]
                ));
            }
            let lo_e = matches!(lo, FaceCondition::Empty);
            let hi_e = matches!(hi, FaceCondition::Empty);
            if lo_e != hi_e {
                return Err(format!(
                    "faces {} and {} must both be empty or neither",
                    NAMES[2 * d],
                    NAMES[2 * d + 1]
                ));
            }
            if lo_e && grid.n[d] != 1 {
                return Err(format!(
                    "an empty direction ({} / {}) must have exactly one cell, not {}",
                    NAMES[2 * d],
                    NAMES[2 * d + 1],
                    grid.n[d]
                ));
            }
            for side in 0..2 {
                if let FaceCondition::Wall { velocity } = self.face(d, side) {
                    if velocity[d] != 0.0 {
                        return Err(format!(
                            "wall {} moves through itself (normal velocity {})",
                            NAMES[2 * d + side],
                            velocity[d]
                        ));
                    }
                }
            }
        }
        Ok(())
    }

    /// The pressure's condition along direction `d`: periodic, or zero gradient
    /// (walls, slip, inlets, empty) / fixed value (outlets) at each end.
    pub fn pressure_axis(&self, d: usize) -> AxisKind {
        let side = |c: &FaceCondition| match c {
            FaceCondition::Outlet { .. } => PressureBoundary::Dirichlet,
            _ => PressureBoundary::Neumann,
        };
        match self.face(d, 0) {
            FaceCondition::Periodic => AxisKind::Periodic,
            lo => AxisKind::Bounded {
                low: side(lo),
                high: side(self.face(d, 1)),
            },
        }
    }

    /// Fixed kinematic pressure on face `(d, side)` if it is an outlet.
    pub fn outlet_pressure(&self, d: usize, side: usize) -> Option<f64> {
        match self.face(d, side) {
            FaceCondition::Outlet { pressure } => Some(*pressure),
            _ => None,
        }
    }

    /// Whether some face is an outlet (the schemes with a pressure increment refuse them).
    pub fn has_outlet(&self) -> bool {
        (0..3).any(|d| (0..2).any(|side| self.outlet_pressure(d, side).is_some()))
    }

    /// Padded index range (inclusive, empty when `lo > hi`) along direction `d` of the
    /// faces of component `c` where the momentum equation is advanced.
    ///
    /// Tangential directions cover the cells `1..=n`. Along its own direction a component
    /// is unknown on every face when periodic, on the interior faces `2..=n` otherwise (the
    /// boundary faces are fixed by walls, slip and inlets, or extrapolated at outlets), and
    /// nowhere across an `Empty` direction.
    pub fn momentum_range(&self, n: [usize; 3], c: usize, d: usize) -> (usize, usize) {
        if c != d {
            return (1, n[d]);
        }
        match self.face(d, 0) {
            FaceCondition::Periodic => (1, n[d]),
            FaceCondition::Empty => (1, 0),
            _ => (2, n[d]),
        }
    }

    /// Like [`Self::momentum_range`] plus the outlet faces, which the projection corrects.
    pub fn corrected_range(&self, n: [usize; 3], c: usize, d: usize) -> (usize, usize) {
        let (mut lo, mut hi) = self.momentum_range(n, c, d);
        if c == d {
            if self.outlet_pressure(d, 0).is_some() {
                lo = 1;
            }
            if self.outlet_pressure(d, 1).is_some() {
                hi = n[d] + 1;
            }
        }
        (lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cavity() -> BoundaryConditions {
        let wall = FaceCondition::Wall { velocity: [0.0; 3] };
        BoundaryConditions {
            faces: [
                wall.clone(),
                wall.clone(),
                wall.clone(),
                FaceCondition::Wall {
                    velocity: [1.0, 0.0, 0.0],
                },
                FaceCondition::Empty,
                FaceCondition::Empty,
            ],
        }
    }

    #[test]
    fn validation_rejects_mismatched_pairs_and_thick_empty_directions() {
        let g = Grid::new([8, 8, 1], [1.0; 3], [0.0; 3]);
        assert!(cavity().validate(&g).is_ok());
        let g3 = Grid::new([8, 8, 2], [1.0; 3], [0.0; 3]);
        assert!(cavity()
            .validate(&g3)
            .unwrap_err()
            .contains("exactly one cell"));
        let mut bc = BoundaryConditions::periodic();
        bc.faces[1] = FaceCondition::Slip;
        assert!(bc.validate(&g).unwrap_err().contains("periodic"));
        let mut bc = cavity();
        bc.faces[0] = FaceCondition::Wall {
            velocity: [1.0, 0.0, 0.0],
        };
        assert!(bc.validate(&g).unwrap_err().contains("normal velocity"));
    }

    #[test]
    fn ranges_follow_the_conditions() {
        let n = [8, 8, 1];
        let mut bc = cavity();
        assert_eq!(bc.momentum_range(n, 0, 0), (2, 8));
        assert_eq!(bc.momentum_range(n, 0, 1), (1, 8));
        assert!(bc.momentum_range(n, 2, 2).0 > bc.momentum_range(n, 2, 2).1);
        bc.faces[1] = FaceCondition::Outlet { pressure: 0.0 };
        assert_eq!(bc.corrected_range(n, 0, 0), (2, 9));
        assert_eq!(
            bc.pressure_axis(0),
            AxisKind::Bounded {
                low: PressureBoundary::Neumann,
                high: PressureBoundary::Dirichlet
            }
        );
        assert_eq!(
            BoundaryConditions::periodic().momentum_range(n, 1, 1),
            (1, 8)
        );
    }
}
