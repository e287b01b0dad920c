//! Unresolved coupling (paper §2.2): declares and re-exports the drag-law model's parts.
// Component loops index several per-component arrays at once.
#![allow(clippy::needless_range_loop)]

mod cell_point_interpolation;
mod chunked_scatter;
mod drag_closure;
mod drag_law_coupling;
mod drag_law_settings;
mod fluid_forces;
mod grid_transfer;

pub use cell_point_interpolation::CellPointInterpolation;
pub use chunked_scatter::{ChunkPartial, ChunkedScatter, PARTICLES_PER_CHUNK};
pub use drag_closure::{
    beetstra, cd_re_haider_levenspiel, di_felice, ergun_wen_yu_drag, gidaspow, koch_hill,
    non_sphere_drag, paper, plessis_masliyah_drag, sphere_drag, tenneti, terminal_velocity,
    wen_yu_drag, Convention, DragClosure, DragInput,
};
pub use drag_law_coupling::{DragLawCoupling, ExchangeReport};
pub use drag_law_settings::{DragLawSettings, Stencil};
pub use fluid_forces::{eotvos, saffman_mei_cl, tomiyama_cl, FluidForces, LiftModel};
pub use grid_transfer::{GridTransfer, SampleStencil};
