//! `constant/couplingProperties` (fsim's own file): which particle–fluid coupling runs.

use super::control_dict::choice;
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
    /// fsim chooses from the particle size and concentration.
    Auto,
}

impl CouplingModel {
    pub fn name(self) -> &'static str {
        match self {
            CouplingModel::None => "none",
            CouplingModel::Direct => "direct",
            CouplingModel::DragLaw => "dragLaw",
            CouplingModel::Auto => "auto",
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
        let model = match choice(&d, "model", &["none", "direct", "dragLaw", "auto"], None)? {
            0 => CouplingModel::None,
            1 => CouplingModel::Direct,
            2 => CouplingModel::DragLaw,
            _ => CouplingModel::Auto,
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
