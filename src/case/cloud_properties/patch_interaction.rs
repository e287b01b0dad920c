//! What each face of the box does to particles: its patch type, the collision model's walls
//! and the `patchInteractionModel` (`rebound` only).

use super::{scalar_in, value_loc};
use crate::case::block_mesh::{BoxFace, PatchType};
use crate::case::case::Case;
use crate::case::control_dict::{at_value, choice};
use crate::case::dictionary::Dict;
use crate::case::error::CaseError;
use crate::case::source::Location;
use crate::case::value::Value;
use crate::particles::{DomainBox, FaceCondition};

/// The particle condition of each box face from its patch, the collision wall model and the
/// patch interaction model.
pub(super) fn domain_box(
    case: &Case,
    sub: &Dict,
    soft_walls: bool,
) -> Result<DomainBox, CaseError> {
    let g = &case.mesh.grid;
    let length = g.length();
    let lo = g.origin;
    let hi = [lo[0] + length[0], lo[1] + length[1], lo[2] + length[2]];
    let interaction = PatchInteraction::read(sub)?;
    let mut faces = [FaceCondition::Periodic; 6];
    for face in BoxFace::ALL {
        let patch = case.mesh.patch_on(face);
        faces[face.index()] = match patch.kind {
            PatchType::Cyclic => FaceCondition::Periodic,
            PatchType::Wall if soft_walls => FaceCondition::Wall,
            kind => match interaction.rebound(&patch.name, kind)? {
                Some((e, mu)) => FaceCondition::Rebound { e, mu },
                None if kind == PatchType::Wall => {
                    return Err(CaseError::at(
                        &patch.loc,
                        format!(
                            "wall patch '{}': no wall model in pairCollisionCoeffs and no \
                             rebound patch interaction for it; particles would pass through",
                            patch.name
                        ),
                    ))
                }
                None if kind == PatchType::Patch => {
                    return Err(CaseError::at(
                        &patch.loc,
                        format!(
                            "patch '{}' (type patch): particles would escape through it, which \
                             fsim does not support; make it a wall or give it a rebound \
                             localInteraction",
                            patch.name
                        ),
                    ))
                }
                // symmetry, symmetryPlane, empty: a mirror
                None => FaceCondition::Rebound { e: 1.0, mu: 0.0 },
            },
        };
    }
    Ok(DomainBox { lo, hi, faces })
}

/// `patchInteractionModel` with its coefficients: `rebound` only.
enum PatchInteraction {
    None,
    /// `standardWallInteraction`: one rule for every wall patch.
    Standard(Option<(f64, f64)>, Location, String),
    /// `localInteraction`: `(patch name or regex, rule, where)`.
    Local(Vec<(String, Dict)>),
}

impl PatchInteraction {
    fn read(sub: &Dict) -> Result<PatchInteraction, CaseError> {
        let kind = choice(
            sub,
            "patchInteractionModel",
            &["none", "standardWallInteraction", "localInteraction"],
            Some(0),
        )?;
        Ok(match kind {
            0 => PatchInteraction::None,
            1 => {
                let c = sub.get_dict("standardWallInteractionCoeffs")?;
                let t = c.get_word("type")?;
                let rule = if t == "rebound" {
                    Some(rebound_coefficients(c)?)
                } else {
                    None
                };
                PatchInteraction::Standard(rule, value_loc(c, "type"), t)
            }
            _ => {
                let c = sub.get_dict("localInteractionCoeffs")?;
                let tokens = c.get_tokens("patches")?;
                let list = tokens
                    .first()
                    .and_then(|t| match &t.value {
                        Value::List(items) => Some(items),
                        _ => None,
                    })
                    .ok_or_else(|| {
                        at_value(
                            c,
                            "patches",
                            "expected a list ( name { type rebound; e …; mu …; } … )".to_string(),
                        )
                    })?;
                let mut rules = Vec::new();
                for pair in list.chunks(2) {
                    match pair {
                        [name, body] => {
                            let n = match &name.value {
                                Value::Word(w) | Value::Str(w) => w.clone(),
                                _ => String::new(),
                            };
                            let Some(d) = body.as_dict() else {
                                return Err(CaseError::at(
                                    &body.loc,
                                    "expected a dictionary { type …; } after the patch name",
                                ));
                            };
                            rules.push((n, d.clone()));
                        }
                        [alone] => {
                            return Err(CaseError::at(
                                &alone.loc,
                                "expected a patch name followed by { type …; }",
                            ))
                        }
                        _ => unreachable!("chunks of two"),
                    }
                }
                PatchInteraction::Local(rules)
            }
        })
    }

    /// `(e, mu)` of the rebound rule for a patch, `None` when no rule applies. Under
    /// `localInteraction` the first entry whose name or regular expression matches the whole
    /// patch name applies, as in OpenFOAM (`patchInteractionDataList::applyToPatch` returns
    /// the first group that holds the patch).
    fn rebound(&self, patch: &str, kind: PatchType) -> Result<Option<(f64, f64)>, CaseError> {
        match self {
            PatchInteraction::None => Ok(None),
            PatchInteraction::Standard(rule, loc, t) => {
                if kind != PatchType::Wall {
                    return Ok(None);
                }
                match rule {
                    Some(r) => Ok(Some(*r)),
                    None => Err(CaseError::at(
                        loc,
                        format!("patch interaction '{t}' is not supported by fsim (use rebound)"),
                    )),
                }
            }
            PatchInteraction::Local(rules) => {
                for (name, d) in rules {
                    let matches = name == patch
                        || regex::Regex::new(&format!("^(?:{name})$"))
                            .map(|r| r.is_match(patch))
                            .unwrap_or(false);
                    if matches {
                        let t = d.get_word("type")?;
                        if t != "rebound" {
                            return Err(at_value(
                                d,
                                "type",
                                format!(
                                    "patch interaction '{t}' on patch '{patch}' is not \
                                     supported by fsim (use rebound)"
                                ),
                            ));
                        }
                        return rebound_coefficients(d).map(Some);
                    }
                }
                Ok(None)
            }
        }
    }
}

/// `e` and `mu` of a rebound rule (OpenFOAM's defaults 1 and 0).
fn rebound_coefficients(d: &Dict) -> Result<(f64, f64), CaseError> {
    Ok((
        scalar_in(d, "e", Some(1.0), |x| (0.0..=1.0).contains(&x), "in [0, 1]")?,
        scalar_in(
            d,
            "mu",
            Some(0.0),
            |x| (0.0..=1.0).contains(&x),
            "in [0, 1]",
        )?,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn interaction(text: &str) -> PatchInteraction {
        let d = Dict::parse(text, "cloud").unwrap_or_else(|e| panic!("{}", e.message));
        PatchInteraction::read(&d).unwrap_or_else(|e| panic!("{}", e.message))
    }

    #[test]
    fn local_rules_match_names_and_regexes_and_the_first_match_wins() {
        let local = interaction(
            r#"
            patchInteractionModel localInteraction;
            localInteractionCoeffs
            {
                patches
                (
                    "(front|back)" { type rebound; e 0.9; mu 0.1; }
                    back           { type rebound; e 0.5; }
                    "side.*"       { type rebound; }
                );
            }
            "#,
        );
        let rule = |patch: &str| local.rebound(patch, PatchType::Patch).unwrap();
        assert_eq!(rule("front"), Some((0.9, 0.1)));
        // both of the first two rules match `back`: the first applies (OpenFOAM's order)
        assert_eq!(rule("back"), Some((0.9, 0.1)));
        // OpenFOAM's defaults, e 1 and mu 0
        assert_eq!(rule("sideLeft"), Some((1.0, 0.0)));
        // a regex matches the whole name only
        assert_eq!(rule("frontWall"), None);
        assert_eq!(rule("top"), None);
    }

    #[test]
    fn a_rule_other_than_rebound_or_out_of_range_is_an_error_at_its_value() {
        let local = interaction(
            "patchInteractionModel localInteraction;\n\
             localInteractionCoeffs { patches ( top { type stick; } \
             bottom { type rebound; e 1.5; } ); }\n",
        );
        let e = local.rebound("top", PatchType::Wall).unwrap_err();
        assert!(
            e.message.contains("'stick' on patch 'top'") && e.message.contains("use rebound"),
            "{}",
            e.message
        );
        assert_eq!((e.line, e.col), (2, 47), "{}", e.message);
        let e = local.rebound("bottom", PatchType::Wall).unwrap_err();
        assert!(e.message.contains("in [0, 1]"), "{}", e.message);
    }

    #[test]
    fn the_standard_interaction_applies_to_walls_only() {
        let standard = interaction(
            "patchInteractionModel standardWallInteraction;\n\
             standardWallInteractionCoeffs { type rebound; e 0.8; mu 0.2; }\n",
        );
        assert_eq!(
            standard.rebound("walls", PatchType::Wall).unwrap(),
            Some((0.8, 0.2))
        );
        assert_eq!(standard.rebound("inlet", PatchType::Patch).unwrap(), None);
        let escape = interaction(
            "patchInteractionModel standardWallInteraction;\n\
             standardWallInteractionCoeffs { type escape; }\n",
        );
        let e = escape.rebound("walls", PatchType::Wall).unwrap_err();
        assert!(e.message.contains("'escape'"), "{}", e.message);
        assert_eq!(e.line, 2, "{}", e.message);
        // a non-wall patch is not the standard interaction's, whatever its rule
        assert_eq!(escape.rebound("inlet", PatchType::Symmetry).unwrap(), None);
        let none = interaction("patchInteractionModel none;\n");
        assert_eq!(none.rebound("walls", PatchType::Wall).unwrap(), None);
    }
}
