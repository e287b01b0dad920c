//! Errors of the DEM engine: bad particles name the particle (index in the input and id),
//! bad coefficients name the keyword.

use crate::Vec3;
use std::fmt;

#[derive(Clone, Debug, PartialEq)]
pub enum DemError {
    /// Diameter zero, negative or not finite.
    BadDiameter {
        index: usize,
        id: u64,
        diameter: f64,
    },
    /// Density zero, negative or not finite.
    BadDensity { index: usize, id: u64, density: f64 },
    /// Position not finite or centre outside the box.
    OutsideDomain {
        index: usize,
        id: u64,
        position: Vec3,
    },
    /// Sphere cuts a wall face by more than the tolerance (fraction of `d`).
    WallOverlap {
        index: usize,
        id: u64,
        face: usize,
        overlap_over_d: f64,
    },
    /// Two spheres overlap by more than the tolerance (fraction of the smaller `d`).
    Overlap {
        index_a: usize,
        id_a: u64,
        index_b: usize,
        id_b: u64,
        overlap_over_d: f64,
    },
    /// Two particles share an id (contact history and restarts are keyed by id).
    DuplicateId {
        index_a: usize,
        index_b: usize,
        id: u64,
    },
    /// A model coefficient outside its valid range.
    BadCoefficient {
        keyword: &'static str,
        value: f64,
        expected: &'static str,
    },
    /// A periodic face whose opposite face is not periodic.
    UnpairedPeriodicFace { face: usize },
    /// A periodic length too short for the minimum-image convention.
    PeriodicTooShort {
        axis: usize,
        length: f64,
        needed: f64,
    },
    /// A face is a `Wall` but no wall model is configured: nothing would stop particles.
    WallWithoutModel { face: usize },
    /// More particle volume has its centres in one contact cell than fits in the box those
    /// spheres can reach: they overlap, and listing their pairs would take without bound.
    Crowded {
        count: usize,
        index_a: usize,
        index_b: usize,
        centre: Vec3,
        solid: f64,
        room: f64,
    },
    /// Particle arrays of different lengths.
    InconsistentArrays,
    /// The box is empty or inverted.
    BadDomain { lo: Vec3, hi: Vec3 },
}

/// The box faces as messages name them, in the order `x−, x+, y−, y+, z−, z+`.
pub const FACE_NAMES: [&str; 6] = ["x-min", "x-max", "y-min", "y-max", "z-min", "z-max"];

impl fmt::Display for DemError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use DemError::*;
        match self {
            BadDiameter { index, id, diameter } => {
                write!(f, "particle {index} (id {id}): diameter {diameter} must be positive and finite")
            }
            BadDensity { index, id, density } => {
                write!(f, "particle {index} (id {id}): density {density} must be positive and finite")
            }
            OutsideDomain { index, id, position } => write!(
                f,
                "particle {index} (id {id}): centre ({} {} {}) lies outside the domain",
                position[0], position[1], position[2]
            ),
            WallOverlap { index, id, face, overlap_over_d } => write!(
                f,
                "particle {index} (id {id}) cuts the {} wall by {:.3e} of its diameter (beyond the tolerance)",
                FACE_NAMES[*face], overlap_over_d
            ),
            Overlap { index_a, id_a, index_b, id_b, overlap_over_d } => write!(
                f,
                "particles {index_a} (id {id_a}) and {index_b} (id {id_b}) overlap by {:.3e} of the smaller diameter (beyond the tolerance)",
                overlap_over_d
            ),
            DuplicateId { index_a, index_b, id } => {
                write!(f, "particles {index_a} and {index_b} share the id {id}")
            }
            BadCoefficient { keyword, value, expected } => {
                write!(f, "`{keyword}` = {value}: expected {expected}")
            }
            UnpairedPeriodicFace { face } => write!(
                f,
                "the {} face is periodic but the opposite face is not",
                FACE_NAMES[*face]
            ),
            PeriodicTooShort { axis, length, needed } => write!(
                f,
                "periodic length {length} along axis {axis} is shorter than twice the largest diameter plus skin ({needed})"
            ),
            WallWithoutModel { face } => write!(
                f,
                "the {} face is a wall but no wall model is set (choose a wallModel or a rebound patch)",
                FACE_NAMES[*face]
            ),
            Crowded { count, index_a, index_b, centre, solid, room } => write!(
                f,
                "{count} particles (among them {index_a} and {index_b}) have their centres in \
                 the contact cell around ({:.4e} {:.4e} {:.4e}): their volume {solid:.3e} m³ \
                 exceeds the {room:.3e} m³ those spheres can occupy, so they overlap",
                centre[0], centre[1], centre[2]
            ),
            InconsistentArrays => write!(f, "particle arrays have different lengths"),
            BadDomain { lo, hi } => write!(f, "domain box lo {lo:?} hi {hi:?} is empty"),
        }
    }
}

impl std::error::Error for DemError {}
