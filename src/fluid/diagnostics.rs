//! Per-step monitors of the fluid.

/// What a step's monitor line reports.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FluidDiagnostics {
    /// `max |D u| · h_min / max |u|` over the cells (relative divergence; the absolute
    /// `max |D u| h_min` when the fluid is at rest).
    pub divergence: f64,
    /// `max |D u|`, 1/s.
    pub max_divergence: f64,
    /// `½ ⟨|u|²⟩`, the volume mean of the kinetic energy per unit mass, m²/s²; each
    /// component squared is averaged over the two faces of a cell.
    pub kinetic_energy: f64,
    /// Volume-mean velocity, m/s.
    pub mean_velocity: [f64; 3],
    /// Largest face speed per component, m/s.
    pub max_speed: [f64; 3],
    /// OpenFOAM's Courant number `½ Δt Σ_faces |u_f| A_f / V`, largest over cells.
    pub max_courant: f64,
}
