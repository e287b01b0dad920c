//! The cloud's `subModels.particleForces` (DPMFoam's list), read for either coupling model:
//! one drag closure at most, `gravity`, `pressureGradient`; the forces fsim does not compute
//! refused by name, an unknown name an error with a spelling hint.

use super::control_dict::at_value;
use super::dictionary::{Dict, Entry};
use super::drag_law_options::{fraction_name, velocity_name};
use super::error::CaseError;
use super::quote::quote;
use crate::coupling::drag::DragClosure;

/// Forces OpenFOAM v1912 offers that fsim does not compute, with what they are.
const REFUSED_FORCES: [(&str, &str); 8] = [
    ("nonSphereDrag", "the drag of non-spherical particles"),
    ("distortedSphereDrag", "the drag of distorting droplets"),
    ("virtualMass", "the added-mass force"),
    ("SaffmanMeiLiftForce", "a lift force"),
    ("TomiyamaLiftForce", "a lift force"),
    ("paramagnetic", "a magnetic force"),
    ("nonInertialFrame", "the forces of a non-inertial frame"),
    ("SRF", "the forces of a rotating frame"),
];

/// The forces of `particleForces`, checked.
pub struct ParticleForces {
    pub drag: Option<DragClosure>,
    pub gravity: bool,
    pub pressure_gradient: bool,
    /// Every force listed, in file order.
    pub names: Vec<String>,
}

impl ParticleForces {
    /// Reads and checks `subModels.particleForces`: an unknown force, a force fsim cannot
    /// compute or a second drag closure is an error at its keyword.
    pub fn read(sub: &Dict, phase: &str) -> Result<ParticleForces, CaseError> {
        let mut forces = ParticleForces {
            drag: None,
            gravity: false,
            pressure_gradient: false,
            names: Vec::new(),
        };
        let Some(list) = sub.opt_dict("particleForces")? else {
            return Ok(forces);
        };
        let mut drag_at: Option<&Entry> = None;
        for e in list.entries() {
            let name = e.keyword();
            e.mark_used();
            forces.names.push(name.to_string());
            if let Ok(model) = DragClosure::from_name(name, "particleForces") {
                if let Some(first) = drag_at {
                    let (line, _) = first.key_loc.line_col();
                    return Err(CaseError::at(
                        &e.key_loc,
                        format!(
                            "a second drag model '{name}' (the first, '{}', is on line {line}): \
                             DPMFoam would add both forces; fsim takes one drag closure",
                            first.keyword()
                        ),
                    ));
                }
                drag_at = Some(e);
                if let Some(coeffs) = e.as_dict() {
                    if model != DragClosure::SphereDrag {
                        fraction_field(coeffs, "alphac", phase, is_openfoam(model))?;
                    }
                }
                forces.drag = Some(model);
            } else if name == "gravity" {
                forces.gravity = true;
            } else if name == "pressureGradient" {
                if let Some(coeffs) = e.as_dict() {
                    let velocity = velocity_name(phase);
                    if let Some(u) = coeffs.opt_word("U")? {
                        if u != velocity {
                            return Err(at_value(
                                coeffs,
                                "U",
                                format!(
                                    "pressureGradient U '{u}': expected the continuous phase's \
                                     velocity {velocity}"
                                ),
                            ));
                        }
                    }
                }
                forces.pressure_gradient = true;
            } else if let Some((_, why)) = REFUSED_FORCES.iter().find(|(n, _)| *n == name) {
                return Err(CaseError::at(
                    &e.key_loc,
                    format!("particle force '{name}' is not supported by fsim ({why})"),
                ));
            } else {
                let others = ["gravity", "pressureGradient"];
                let known = DragClosure::NAMES.iter().chain(&others);
                // (no hint for a name far longer than any known one: the distance would
                // cost its length times theirs)
                let nearest = known
                    .filter(|_| name.len() <= 64)
                    .map(|k| {
                        (
                            edit_distance(&name.to_ascii_lowercase(), &k.to_ascii_lowercase()),
                            *k,
                        )
                    })
                    .min()
                    .filter(|(d, _)| *d <= 3)
                    .map(|(_, k)| k);
                let drag_like = name.to_ascii_lowercase().contains("drag")
                    || nearest.is_some_and(|k| !others.contains(&k));
                let what = if drag_like {
                    "unknown drag model"
                } else {
                    "unknown particle force"
                };
                let hint = nearest.map_or(String::new(), |k| format!(" (did you mean '{k}'?)"));
                return Err(CaseError::at(
                    &e.key_loc,
                    format!(
                        "{what} '{}' in particleForces{hint}: expected a drag model ({}), \
                         gravity or pressureGradient",
                        quote(name),
                        DragClosure::NAMES.join(", ")
                    ),
                ));
            }
        }
        Ok(forces)
    }
}

/// Levenshtein distance (insertions, deletions, substitutions), for spelling hints.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let above = row[j + 1];
            row[j + 1] = (above + 1)
                .min(row[j] + 1)
                .min(diagonal + usize::from(ca != *cb));
            diagonal = above;
        }
    }
    row[b.len()]
}

/// Whether OpenFOAM v1912 knows the closure (the others are fsim's names: a case using them
/// no longer runs under DPMFoam, and their `alphac` is optional).
fn is_openfoam(closure: DragClosure) -> bool {
    matches!(
        closure,
        DragClosure::SphereDrag
            | DragClosure::WenYu
            | DragClosure::ErgunWenYu
            | DragClosure::PlessisMasliyah
    )
}

/// A fraction-field name (`alphac alpha.air;`) that must be the continuous phase's;
/// `required` when OpenFOAM requires the keyword.
fn fraction_field(d: &Dict, keyword: &str, phase: &str, required: bool) -> Result<(), CaseError> {
    let expected = fraction_name(phase);
    let name = if required {
        d.get_word(keyword)?
    } else {
        match d.opt_word(keyword)? {
            Some(n) => n,
            None => return Ok(()),
        }
    };
    if name != expected {
        return Err(at_value(
            d,
            keyword,
            format!(
                "'{keyword}' names the field '{name}': expected the continuous phase's fluid \
                 fraction {expected}"
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::parse_dict;

    fn forces(list: &str) -> Result<ParticleForces, CaseError> {
        let d = parse_dict(
            &format!("particleForces\n{{\n{list}\n}}\n"),
            "constant/kinematicCloudProperties",
        )
        .unwrap();
        ParticleForces::read(&d, "air")
    }

    #[test]
    fn the_list_is_read_in_file_order() {
        let f = forces("    WenYuDrag { alphac alpha.air; }\n    gravity;\n    pressureGradient;")
            .unwrap();
        assert_eq!(f.drag, Some(DragClosure::WenYu));
        assert!(f.gravity && f.pressure_gradient);
        assert_eq!(f.names, ["WenYuDrag", "gravity", "pressureGradient"]);
        let none = parse_dict("solution {}\n", "cloud").unwrap();
        let f = ParticleForces::read(&none, "air").unwrap();
        assert!(f.drag.is_none() && !f.gravity && f.names.is_empty());
    }

    #[test]
    fn refused_unknown_and_second_closures_are_errors_at_their_keyword() {
        for (name, why) in REFUSED_FORCES {
            let e = forces(&format!("    gravity;\n    {name};"))
                .err()
                .expect(name);
            assert_eq!((e.line, e.col), (4, 5), "{}", e.message);
            assert!(e.message.contains(why), "{}", e.message);
        }
        let e = forces("    sphereDrag;\n    sphereDarg;").err().unwrap();
        assert!(
            e.message.starts_with(
                "unknown drag model 'sphereDarg' in particleForces (did you mean 'sphereDrag'?)"
            ),
            "{}",
            e.message
        );
        let e = forces("    sphereDrag;\n    WenYuDrag { alphac alpha.air; }")
            .err()
            .unwrap();
        assert!(
            e.message.contains("the first, 'sphereDrag', is on line 3"),
            "{}",
            e.message
        );
    }

    #[test]
    fn edit_distance_counts_insertions_deletions_and_substitutions() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("abc", ""), 3);
        assert_eq!(edit_distance("gravity", "gravty"), 1);
        assert_eq!(edit_distance("same", "same"), 0);
    }
}
