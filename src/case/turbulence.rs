//! `constant/turbulenceProperties.<phase>` (or `constant/turbulenceProperties`): DPMFoam will
//! not start without it. fsim's fluid is laminar and Newtonian, so only `simulationType
//! laminar;` (with the default `laminarModel Stokes`) is accepted; RAS and LES models, or a
//! visco-elastic laminar model, would change the physics and stop the run at their value.

use super::control_dict::{at_value, choice};
use super::dictionary::Dict;
use super::error::CaseError;

/// The file's name for the phase: `turbulenceProperties.air`, or `turbulenceProperties`.
pub fn turbulence_file(phase: &str) -> String {
    if phase.is_empty() {
        "constant/turbulenceProperties".to_string()
    } else {
        format!("constant/turbulenceProperties.{phase}")
    }
}

/// Checks that the turbulence model is laminar (Stokes).
pub fn check_laminar(d: &Dict) -> Result<(), CaseError> {
    let kinds = ["laminar", "RAS", "LES", "twoPhaseTransport"];
    let kind = choice(d, "simulationType", &kinds, None)?;
    if kind != 0 {
        // The model's own sub-dictionary is part of the refused setting, not an extra note.
        if let Some(e) = d.peek(kinds[kind]) {
            e.mark_used();
            if let Some(sub) = e.as_dict() {
                sub.mark_all_used();
            }
        }
        return Err(at_value(
            d,
            "simulationType",
            format!(
                "simulationType {}: fsim's fluid is laminar (no turbulence model); use \
                 simulationType laminar",
                kinds[kind]
            ),
        ));
    }
    if let Some(laminar) = d.opt_dict("laminar")? {
        let model = choice(
            laminar,
            "laminarModel",
            &["Stokes", "Maxwell", "generalisedNewtonian"],
            Some(0),
        )?;
        if model != 0 {
            return Err(at_value(
                laminar,
                "laminarModel",
                "fsim's fluid is Newtonian: only laminarModel Stokes is supported".to_string(),
            ));
        }
        laminar.lookup("printCoeffs");
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::parse_dict;

    fn check(text: &str) -> Result<(), CaseError> {
        let d = parse_dict(text, "constant/turbulenceProperties.air").unwrap();
        check_laminar(&d)
    }

    #[test]
    fn laminar_passes_and_turbulence_models_stop_at_their_value() {
        check("simulationType laminar;").unwrap();
        check("simulationType laminar; laminar { laminarModel Stokes; }").unwrap();
        let e = check("simulationType  RAS;\nRAS { RASModel kEpsilon; }").unwrap_err();
        assert_eq!(e.file.as_deref(), Some("constant/turbulenceProperties.air"));
        assert_eq!((e.line, e.col), (1, 17), "{e}");
        assert!(
            e.message
                .starts_with("simulationType RAS: fsim's fluid is laminar"),
            "{e}"
        );
        let e = check("simulationType LES;").unwrap_err();
        assert!(e.message.contains("LES"), "{e}");
        let e = check("simulationType kOmega;").unwrap_err();
        assert!(e.message.contains("expected one of laminar, RAS"), "{e}");
        let e = check("simulationType laminar;\nlaminar { laminarModel Maxwell; }").unwrap_err();
        assert_eq!((e.line, e.col), (2, 24), "{e}");
        let e = check("").unwrap_err();
        assert!(
            e.message.contains("missing keyword 'simulationType'"),
            "{e}"
        );
        assert_eq!(turbulence_file("air"), "constant/turbulenceProperties.air");
        assert_eq!(turbulence_file(""), "constant/turbulenceProperties");
    }
}
