//! `constant/couplingProperties` (fsim's own file): which particle–fluid coupling runs.

use super::control_dict::{at_value, choice};
use super::dictionary::Dict;
use super::error::CaseError;

/// The coupling model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CouplingModel {
    /// Fluid only: no particles.
    None,
    /// Resolved particles (grid finer than the particles).
    Direct,
    /// Unresolved particles with a drag closure (CFD-DEM).
    DragLaw,
}

impl CouplingModel {
    pub fn name(self) -> &'static str {
        match self {
            CouplingModel::None => "none",
            CouplingModel::Direct => "direct",
            CouplingModel::DragLaw => "dragLaw",
        }
    }
}

/// The model and, when the file exists, the whole dictionary for the model's own settings
/// (read by the coupling code; marked read here so it is not listed as ignored).
#[derive(Clone, Debug)]
pub struct Coupling {
    pub model: CouplingModel,
    pub dict: Option<Dict>,
}

impl Coupling {
    /// From the file, or the default when it is absent: `dragLaw` when the case has
    /// `constant/kinematicCloudProperties` (a DPMFoam case), else `none`.
    pub fn new(dict: Option<Dict>, has_cloud: bool) -> Result<Coupling, CaseError> {
        let Some(d) = dict else {
            let model = if has_cloud {
                CouplingModel::DragLaw
            } else {
                CouplingModel::None
            };
            return Ok(Coupling { model, dict: None });
        };
        // `model auto` (fsim choosing the model) is announced but not built yet.
        if choice(&d, "model", &["auto"], None).is_ok() {
            return Err(at_value(
                &d,
                "model",
                "model auto is not available yet in this fsim; choose direct (resolved \
                 particles) or dragLaw (CFD-DEM): docs/user-guide/direct-model.md, \
                 docs/user-guide/drag-law-model.md"
                    .to_string(),
            ));
        }
        let model = match choice(&d, "model", &["none", "direct", "dragLaw"], None)? {
            0 => CouplingModel::None,
            1 => CouplingModel::Direct,
            _ => CouplingModel::DragLaw,
        };
        // The coupling code reads the rest; `dragLawCoeffs` is read (and its unknown keywords
        // noted) with the drag-law settings.
        for e in d.entries() {
            e.mark_used();
            match e.as_dict() {
                Some(sub) if e.keyword() != "dragLawCoeffs" => sub.mark_all_used(),
                _ => {}
            }
        }
        Ok(Coupling {
            model,
            dict: Some(d),
        })
    }
}
