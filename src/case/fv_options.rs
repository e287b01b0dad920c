//! `system/fvOptions` (or `constant/fvOptions`): the momentum sources fsim supports.

use super::control_dict::{at_value, choice};
use super::dictionary::{Dict, EntryBody};
use super::error::CaseError;

/// `meanVelocityForce`: a uniform body force adjusted every step so that the mean velocity
/// over the domain stays at `ubar` (OpenFOAM's fvOption of that name), to drive periodic flows.
#[derive(Clone, Debug, PartialEq)]
pub struct MeanVelocityForce {
    /// The source's name (its dictionary keyword).
    pub name: String,
    /// The velocity field it acts on (`U.air`).
    pub field: String,
    /// Target mean velocity, m/s.
    pub ubar: [f64; 3],
    /// Under-relaxation of the force correction (1: full correction each step).
    pub relaxation: f64,
}

/// Reads every source of the file; `velocity` is the case's velocity field name.
pub fn read_fv_options(d: &Dict, velocity: &str) -> Result<Vec<MeanVelocityForce>, CaseError> {
    let mut sources = Vec::new();
    for entry in d.entries() {
        let EntryBody::Dict(source) = &entry.body else {
            continue;
        };
        if entry.keyword() == "FoamFile" {
            continue;
        }
        entry.mark_used();
        let kind = source.get_word("type")?;
        if kind != "meanVelocityForce" {
            return Err(at_value(
                source,
                "type",
                format!(
                    "expected an fvOption fsim supports (meanVelocityForce), found '{kind}' in source '{}'",
                    entry.keyword()
                ),
            ));
        }
        if !source.get_bool_or("active", true)? {
            continue;
        }
        // Older versions keep the settings in `<type>Coeffs` (or `<name>Coeffs`).
        let coeffs = match source.opt_dict("meanVelocityForceCoeffs")? {
            Some(c) => c,
            None => source
                .opt_dict(&format!("{}Coeffs", entry.keyword()))?
                .unwrap_or(source),
        };
        choice(coeffs, "selectionMode", &["all"], None)?;
        let fields = coeffs.get_tokens("fields")?;
        let names: Vec<String> = match fields {
            [item] => match item.as_list() {
                Some(list) => list.iter().map(|i| i.to_string()).collect(),
                None => vec![item.to_string()],
            },
            _ => Vec::new(),
        };
        if names.len() != 1 || names[0] != velocity {
            return Err(at_value(
                coeffs,
                "fields",
                format!(
                    "expected 'fields ({velocity});' for meanVelocityForce, the case's velocity"
                ),
            ));
        }
        let ubar = coeffs.get_vector("Ubar")?;
        let relaxation = coeffs.get_scalar_or("relaxation", 1.0)?;
        if !(relaxation > 0.0 && relaxation <= 1.0) {
            return Err(at_value(
                coeffs,
                "relaxation",
                format!("expected 'relaxation' in (0, 1], found {relaxation}"),
            ));
        }
        sources.push(MeanVelocityForce {
            name: entry.keyword().to_string(),
            field: velocity.to_string(),
            ubar,
            relaxation,
        });
    }
    Ok(sources)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::parse_dict;

    #[test]
    fn current_and_coeffs_forms() {
        let d = parse_dict(
            "a { type meanVelocityForce; selectionMode all; fields (U.air); Ubar (1 0 0); }\n\
             b { type meanVelocityForce; meanVelocityForceCoeffs { selectionMode all; fields (U.air); Ubar (0 2 0); relaxation 0.5; } }",
            "system/fvOptions",
        )
        .unwrap();
        let s = read_fv_options(&d, "U.air").unwrap();
        assert_eq!(s[0].ubar, [1.0, 0.0, 0.0]);
        assert_eq!((s[1].ubar, s[1].relaxation), ([0.0, 2.0, 0.0], 0.5));
        let d = parse_dict(
            "drive { type meanVelocityForce; driveCoeffs { selectionMode all; fields (U); Ubar (3 0 0); } }",
            "system/fvOptions",
        )
        .unwrap();
        assert_eq!(read_fv_options(&d, "U").unwrap()[0].ubar, [3.0, 0.0, 0.0]);
        let d = parse_dict("s { type scalarSemiImplicitSource; }", "system/fvOptions").unwrap();
        let e = read_fv_options(&d, "U").unwrap_err();
        assert!(e.message.contains("scalarSemiImplicitSource"));
    }
}
