//! The direct model's tuning constants, in one place. Each is a measured choice, not a
//! user setting: the line says where its value comes from, and `docs/direct_model.md`
//! holds the measurements. A change here moves validated figures (`docs/validation.md`).

/// Distance from a sphere's surface to its stress-integration surface, in cells. Three
/// cells out, read tricubically, was the most accurate on the exact Stokes references
/// (docs/direct_model.md, "The stress integral"); neighbours and walls pull it closer.
pub const SURFACE_OFFSET_CELLS: f64 = 3.0;

/// Edge of the integration surface's quadrangles, in cells: as accurate as half a cell
/// three cells out, at a quarter of the cost (docs/direct_model.md, "The stress integral").
pub const QUADRATURE_EDGE_CELLS: f64 = 1.0;

/// An integration surface closer to a bounding face than this (cells) is read trilinearly:
/// a tricubic stencil there reaches the ghost layer and a sphere settling onto a floor sped
/// up instead of slowing (docs/direct_model.md, "Walls").
pub const WALL_TRILINEAR_CLEARANCE_CELLS: f64 = 1.5;

/// Loop gain of the throats' relaxation toward their lubrication profile: at 1 `RK3`
/// diverged on a dense array (φ = 0.343, r/h = 3.9), at ½ every scheme held
/// (docs/direct_model.md, "Throats: gaps under two cells").
pub const THROAT_RELAXATION_GAIN: f64 = 0.5;

/// The share of the shortest Stokes response time `ρ_p d²/(18 μ)` a step of free spheres
/// may take: below the lowest onset of oscillation measured, 0.27 τ_p
/// (docs/direct_model.md, "Known limits").
pub const RESPONSE_STEP_FRACTION: f64 = 0.25;

/// Share of a settling suspension's momentum the periodic drive removes per step: with
/// the rate term it returns the mixture's momentum to zero by half each step
/// (`particle_motion.rs`; tests/direct/motion.rs holds the drive's correction).
pub const DRIVE_MOMENTUM_GAIN: f64 = 0.5;

/// Default virtual-mass coefficient `C_v`: the plain lagged coupling diverges below
/// ρ_p/ρ_f ≈ 0.3–1.3 (by scheme); with 2 both schemes held at ρ_p/ρ_f = 0.1
/// (docs/direct_model.md, "Time stepping").
pub const DEFAULT_VIRTUAL_MASS: f64 = 2.0;

/// Free spheres lighter than this times the fluid are refused: the lightest measured stable
/// with the virtual mass was 0.1.
pub const MIN_DENSITY_RATIO: f64 = 0.2;

/// Gap below which the lubrication correction acts, in cells: the grid resolves the
/// squeeze flow down to about one cell (Kempe & Fröhlich 2012, Breugem 2010).
pub const LUBRICATION_CUTOFF_CELLS: f64 = 1.0;

/// The lubrication force saturates at this gap over the pair's effective radius (surface
/// roughness, Breugem 2010).
pub const LUBRICATION_MIN_GAP: f64 = 1e-3;

/// Fewest cells per radius the direct model accepts: below it the staircase is coarser
/// than the sphere and the stress integral has no resolved shell.
pub const MIN_CELLS_PER_RADIUS: f64 = 2.0;

/// Spheres below this many cells per radius get a note: expect drag errors of 2 % and more
/// (docs/direct_model.md, "Porous media: K against the literature").
pub const COARSE_CELLS_PER_RADIUS: f64 = 4.0;

/// Narrowest gap, in cells, the grid is taken to resolve (the paper's §3.1: denser media
/// need finer grids); narrower gaps get a warning.
pub const RESOLVED_GAP_CELLS: f64 = 2.0;

/// The largest `rebuildDistance`, cells: beyond half a cell a face's role would lag the
/// surface by more than the forcing's own reach.
pub const MAX_REBUILD_DISTANCE: f64 = 0.5;
