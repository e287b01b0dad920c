//! `constant/couplingProperties` (fsim's own file): which particle–fluid coupling runs, and
//! the direct model's settings. (The drag-law model's `dragLawCoeffs` are read with the
//! cloud, in `drag_law_options.rs`.)
//!
//! ```text
//! model           direct;     // none | direct | dragLaw | auto
//! tolerance       0.05;       // auto: the relative error accepted (docs/user-guide/
//!                             // choosing-a-model.md); fsim picks the model and grid
//! virtualMass     2;          // direct: C_v of the virtual mass split off the lagged force
//!                             // (0: the paper's plain explicit coupling)
//! direct
//! {
//!     interpolation   cubic;  // cubic | linear: grid → quadrature nodes of the stress
//!                             // integral (linear: half the cost, for suspensions)
//!     fixedParticles  no;     // yes: every particle is held in place (porous media)
//!     rebuildDistance 0;      // cells a sphere may move before its forced faces are
//!                             // rebuilt (between builds they follow it); 0: every step
//! }
//! dragLawCoeffs { … }         // dragLaw: docs/user-guide/drag-law-model.md
//! ```
//!
//! Unknown keywords in `direct` are errors (this is fsim's own file: a misspelt setting must
//! not pass silently); unknown keywords at the top level are listed as ignored.

use super::control_dict::{at_value, choice};
use super::dictionary::Dict;
use super::error::CaseError;
use crate::coupling::direct::{
    DirectSettings, Interpolation, MotionSettings, MAX_REBUILD_DISTANCE,
};

/// The coupling model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CouplingModel {
    /// Fluid only: no particles, or a cloud that feels gravity and buoyancy only.
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

/// The model, the direct model's settings (defaults unless `model direct` or `auto`), and,
/// when the file exists, its dictionary (the drag-law settings read `dragLawCoeffs` from it).
#[derive(Clone, Debug)]
pub struct Coupling {
    /// With `model auto`, `Direct` until [`crate::auto`] has chosen.
    pub model: CouplingModel,
    /// `model auto`: the relative error the user accepts (`tolerance`, default
    /// [`DEFAULT_TOLERANCE`]).
    pub auto_tolerance: Option<f64>,
    pub direct: DirectSettings,
    pub motion: MotionSettings,
    pub dict: Option<Dict>,
}

const TOP_LEVEL_KEYWORDS: [&str; 5] = [
    "model",
    "tolerance",
    "virtualMass",
    "direct",
    "dragLawCoeffs",
];

/// `model auto`'s tolerance when none is given: 5 %, between the drag law's best (a few
/// percent in dense beds) and the direct model's cheap grids.
pub const DEFAULT_TOLERANCE: f64 = 0.05;
const DIRECT_KEYWORDS: [&str; 3] = ["interpolation", "fixedParticles", "rebuildDistance"];

impl Coupling {
    /// From the file, or the default when it is absent: `dragLaw` when the case has
    /// `constant/kinematicCloudProperties` (a DPMFoam case), else `none`. Top-level keywords
    /// fsim does not know are noted in `warnings`.
    pub fn new(
        dict: Option<Dict>,
        has_cloud: bool,
        warnings: &mut Vec<String>,
    ) -> Result<Coupling, CaseError> {
        let Some(d) = dict else {
            let model = if has_cloud {
                CouplingModel::DragLaw
            } else {
                CouplingModel::None
            };
            return Ok(Coupling {
                model,
                auto_tolerance: None,
                direct: DirectSettings::default(),
                motion: MotionSettings::default(),
                dict: None,
            });
        };
        let (model, auto_tolerance) =
            match choice(&d, "model", &["none", "direct", "dragLaw", "auto"], None)? {
                0 => (CouplingModel::None, None),
                1 => (CouplingModel::Direct, None),
                2 => (CouplingModel::DragLaw, None),
                _ => (CouplingModel::Direct, Some(tolerance(&d)?)),
            };
        let (direct, motion) = match model {
            CouplingModel::Direct => (direct_settings(&d)?, motion_settings(&d)?),
            _ => (DirectSettings::default(), MotionSettings::default()),
        };
        // The other model's settings may stay in the file (to switch models by one word);
        // `dragLawCoeffs` is read (and its unknown keywords noted) with the drag-law settings.
        for e in d.entries() {
            let known = TOP_LEVEL_KEYWORDS.contains(&e.keyword()) || e.keyword() == "FoamFile";
            if !known {
                let (line, col) = e.value_loc().line_col();
                warnings.push(format!(
                    "{}:{line}:{col}: ignored keyword '{}' (fsim does not use it; expected one \
                     of {})",
                    d.file(),
                    e.keyword(),
                    TOP_LEVEL_KEYWORDS.join(", ")
                ));
            }
            e.mark_used();
            match e.as_dict() {
                Some(sub) if e.keyword() != "dragLawCoeffs" => sub.mark_all_used(),
                _ => {}
            }
        }
        Ok(Coupling {
            model,
            auto_tolerance,
            direct,
            motion,
            dict: Some(d),
        })
    }
}

/// `tolerance` of `model auto`: a relative error in (0, 1).
fn tolerance(d: &Dict) -> Result<f64, CaseError> {
    let t = d.get_scalar_or("tolerance", DEFAULT_TOLERANCE)?;
    if t > 0.0 && t < 1.0 {
        Ok(t)
    } else {
        Err(at_value(
            d,
            "tolerance",
            format!("tolerance {t}: expected a relative error in (0, 1), e.g. 0.05 for 5 %"),
        ))
    }
}

/// `direct { … }`: the defaults without it.
fn direct_settings(dict: &Dict) -> Result<DirectSettings, CaseError> {
    let mut settings = DirectSettings::default();
    let Some(d) = dict.opt_dict("direct")? else {
        return Ok(settings);
    };
    for entry in d.entries() {
        if !DIRECT_KEYWORDS.contains(&entry.keyword()) {
            return Err(CaseError::at(
                entry.value_loc(),
                format!(
                    "unknown keyword '{}' in direct; expected one of {}",
                    entry.keyword(),
                    DIRECT_KEYWORDS.join(", ")
                ),
            ));
        }
    }
    if d.contains("interpolation") {
        let names = ["cubic", "linear"];
        let k = choice(d, "interpolation", &names, None)?;
        settings.integral.interpolation =
            Interpolation::from_name(names[k]).expect("listed names parse");
    }
    settings.fixed_particles = d.get_bool_or("fixedParticles", false)?;
    if let Some(distance) = d.opt_scalar("rebuildDistance")? {
        if !(0.0..=MAX_REBUILD_DISTANCE).contains(&distance) {
            let loc = d.get_entry("rebuildDistance")?.value_loc();
            return Err(CaseError::at(
                loc,
                format!(
                    "rebuildDistance must be between 0 and {MAX_REBUILD_DISTANCE} cells, got \
                     {distance}"
                ),
            ));
        }
        settings.rebuild_distance = distance;
    }
    Ok(settings)
}

/// `virtualMass C_v;`: the default without it.
fn motion_settings(dict: &Dict) -> Result<MotionSettings, CaseError> {
    let mut s = MotionSettings::default();
    if let Some(c) = dict.opt_scalar("virtualMass")? {
        if !(0.0..=10.0).contains(&c) {
            let loc = dict.get_entry("virtualMass")?.value_loc();
            return Err(CaseError::at(
                loc,
                format!("virtualMass must be between 0 and 10, got {c}"),
            ));
        }
        s.virtual_mass = c;
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::parse_dict;

    fn coupling(text: &str) -> Result<(Coupling, Vec<String>), CaseError> {
        let dict = parse_dict(text, "constant/couplingProperties").unwrap();
        let mut warnings = Vec::new();
        Coupling::new(Some(dict), true, &mut warnings).map(|c| (c, warnings))
    }

    #[test]
    fn reads_the_direct_settings_and_rejects_unknown_keywords() {
        let (c, notes) = coupling("model direct;").unwrap();
        assert_eq!(c.direct, DirectSettings::default());
        assert_eq!(c.direct.integral.surface_offset, 3.0);
        assert!(notes.is_empty());
        let (c, _) = coupling(
            "model direct; virtualMass 0; direct { interpolation linear; fixedParticles yes; \
             rebuildDistance 0.1; }",
        )
        .unwrap();
        assert_eq!(c.direct.rebuild_distance, 0.1);
        assert_eq!(c.direct.integral.interpolation, Interpolation::Linear);
        assert!(c.direct.fixed_particles);
        assert_eq!(c.motion.virtual_mass, 0.0);
        let e = coupling("model direct; direct { surfaceOffset 2; }").unwrap_err();
        assert!(
            e.to_string().contains("unknown keyword 'surfaceOffset'"),
            "{e}"
        );
        let e = coupling("model direct; direct { rebuildDistance 0.8; }").unwrap_err();
        assert!(e.to_string().contains("between 0 and 0.5"), "{e}");
        let e = coupling("model direct; direct { interpolation quintic; }").unwrap_err();
        assert!(e.to_string().contains("quintic"), "{e}");
        let e = coupling("model direct; virtualMass 11;").unwrap_err();
        assert!(e.to_string().contains("between 0 and 10"), "{e}");
        // another model's settings are not read, a misspelt top-level keyword is noted
        let (c, notes) =
            coupling("model dragLaw; direct { surfaceOffset 2; } virtulMass 1;").unwrap();
        assert_eq!(c.direct, DirectSettings::default());
        assert_eq!(notes.len(), 1, "{notes:?}");
        assert!(
            notes[0].contains("ignored keyword 'virtulMass'"),
            "{notes:?}"
        );
    }

    #[test]
    fn model_auto_reads_its_tolerance_and_the_direct_settings() {
        let (c, notes) = coupling("model auto;").unwrap();
        assert_eq!(c.auto_tolerance, Some(DEFAULT_TOLERANCE));
        assert!(notes.is_empty(), "{notes:?}");
        let (c, _) =
            coupling("model auto; tolerance 0.01; direct { fixedParticles yes; }").unwrap();
        assert_eq!(c.auto_tolerance, Some(0.01));
        assert!(
            c.direct.fixed_particles,
            "auto may choose direct: its settings are read"
        );
        for bad in ["0", "1", "-0.1"] {
            let e = coupling(&format!("model auto; tolerance {bad};")).unwrap_err();
            assert!(
                e.to_string()
                    .contains("expected a relative error in (0, 1)"),
                "{e}"
            );
        }
        let (c, _) = coupling("model direct; tolerance 0.01;").unwrap();
        assert_eq!(c.auto_tolerance, None);
    }
}
