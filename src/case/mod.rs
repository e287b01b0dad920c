//! Case files: the OpenFOAM dictionary parser and the typed, validated case it feeds.
//!
//! [`Case::load`] reads a case directory into typed parts ([`ControlDict`], [`BlockMesh`],
//! [`Transport`], [`Fields`], [`MeanVelocityForce`], [`Coupling`]); every error is a
//! [`CaseError`] naming file, line and column. The parser alone is [`read_dict_file`] /
//! [`parse_dict`], giving a [`Dict`] with typed accessors. A DPMFoam case's cloud is read by
//! [`Cloud::from_case`], with the drag-law model's [`DragLawOptions`]; its
//! `turbulenceProperties.<phase>` ([`turbulence`]) and `0/alpha.<phase>` ([`fraction_field`])
//! are checked by [`Case::load`].

pub mod block_mesh;
pub mod bounded_read;
#[allow(clippy::module_inception)]
pub mod case;
pub mod cloud_properties;
pub mod control_dict;
pub mod control_watch;
pub mod coupling;
pub mod dictionary;
pub mod drag_law_options;
pub mod error;
pub mod expression;
pub mod fields;
pub mod fraction_field;
pub mod fv_options;
mod packed;
pub mod parser;
pub mod particle_forces;
pub mod pressure_solver;
pub mod quote;
pub mod source;
pub mod transport;
pub mod turbulence;
pub mod value;

pub use block_mesh::{BlockMesh, BoxFace, Patch, PatchType};
pub use case::Case;
pub use cloud_properties::Cloud;
pub use control_dict::{time_name, ControlDict, StartFrom, StopAt, WriteControl};
pub use control_watch::{ControlChange, ControlDictWatch};
pub use coupling::{Coupling, CouplingModel};
pub use dictionary::{Dict, Directive, Entry, EntryBody, Key};
pub use drag_law_options::{
    DragLawOptions, Interpolation, ParticleIntegration, SourceTreatment, VoidFraction,
};
pub use error::CaseError;
pub use fields::{Fields, InternalField, PressureBc, VelocityBc};
pub use fv_options::MeanVelocityForce;
pub use parser::{
    check_parser_invariants, parse_dict, read_dict_file, read_dict_file_with_includes,
};
pub use pressure_solver::PressureSolverControls;
pub use source::{Element, Location, SourceFile};
pub use transport::Transport;
pub use value::{Dimensions, Item, ListView, Value};
