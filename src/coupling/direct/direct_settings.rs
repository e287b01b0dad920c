//! The direct model's settings in `constant/couplingProperties`.

use super::field_sampler::Interpolation;
use super::stress_integral::StressIntegral;
use crate::case::control_dict::choice;
use crate::case::{CaseError, Coupling};

/// Settings of `model direct;`, read from the optional sub-dictionary `direct`:
///
/// ```text
/// model direct;
/// direct
/// {
///     interpolation   cubic;  // cubic | linear: grid → quadrature nodes of the stress
///                             // integral (linear: half the cost, for suspensions)
///     fixedParticles  no;     // yes: every particle is held in place (porous media)
///     rebuildDistance 0;      // cells a sphere may move before its forced faces are
///                             // rebuilt (between builds they follow it); 0: every step
/// }
/// ```
///
/// Unknown keywords in `direct` are errors (this is fsim's own file: a misspelt setting must
/// not pass silently).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DirectSettings {
    /// The stress integral: its interpolation from the case, its surface the default's.
    pub integral: StressIntegral,
    /// Hold every particle fixed (flow through a fixed array).
    pub fixed_particles: bool,
    /// Distance (cells) a sphere may move from where its forced faces were built before
    /// they are rebuilt ([`super::ImmersedBoundary::follow`]).
    pub rebuild_distance: f64,
}

const KEYWORDS: [&str; 3] = ["interpolation", "fixedParticles", "rebuildDistance"];

use super::tuning::MAX_REBUILD_DISTANCE;

impl DirectSettings {
    /// From the case's coupling file; the defaults when it has no `direct` dictionary.
    pub fn from_coupling(coupling: &Coupling) -> Result<Self, CaseError> {
        let mut settings = DirectSettings::default();
        let Some(dict) = coupling.dict.as_ref() else {
            return Ok(settings);
        };
        let Some(d) = dict.opt_dict("direct")? else {
            return Ok(settings);
        };
        for entry in d.entries() {
            if !KEYWORDS.contains(&entry.keyword()) {
                return Err(CaseError::at(
                    entry.value_loc(),
                    format!(
                        "unknown keyword '{}' in direct; expected one of {}",
                        entry.keyword(),
                        KEYWORDS.join(", ")
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
                        "rebuildDistance must be between 0 and {MAX_REBUILD_DISTANCE} cells, \
                         got {distance}"
                    ),
                ));
            }
            settings.rebuild_distance = distance;
        }
        Ok(settings)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::parse_dict;

    fn settings(text: &str) -> Result<DirectSettings, CaseError> {
        let dict = parse_dict(text, "constant/couplingProperties").unwrap();
        DirectSettings::from_coupling(&Coupling::new(Some(dict), true)?)
    }

    #[test]
    fn reads_the_direct_dictionary_and_rejects_unknown_keywords() {
        let s = settings("model direct;").unwrap();
        assert_eq!(s, DirectSettings::default());
        assert_eq!(s.integral.surface_offset, 3.0);
        let s = settings(
            "model direct; direct { interpolation linear; fixedParticles yes; \
             rebuildDistance 0.1; }",
        )
        .unwrap();
        assert_eq!(s.rebuild_distance, 0.1);
        assert_eq!(s.integral.surface_offset, 3.0);
        assert_eq!(s.integral.interpolation, Interpolation::Linear);
        assert!(s.fixed_particles);
        let e = settings("model direct; direct { surfaceOffset 2; }").unwrap_err();
        assert!(
            e.to_string().contains("unknown keyword 'surfaceOffset'"),
            "{e}"
        );
        let e = settings("model direct; direct { rebuildDistance 0.8; }").unwrap_err();
        assert!(e.to_string().contains("between 0 and 0.5"), "{e}");
        let e = settings("model direct; direct { interpolation quintic; }").unwrap_err();
        assert!(e.to_string().contains("quintic"), "{e}");
    }
}
