//! What each face of the box does to particles: its patch type, the collision model's walls
//! and the `patchInteractionModel` (`rebound` only).

use super::{scalar_in, value_loc};
use crate::case::block_mesh::{BoxFace, Patch, PatchType};
use crate::case::case::Case;
use crate::case::control_dict::{at_value, choice};
use crate::case::dictionary::{Dict, Key};
use crate::case::error::CaseError;
use crate::case::fields::VelocityBc;
use crate::case::source::Location;
use crate::case::value::Value;
use crate::particles::{DomainBox, FaceCondition};
use crate::Vec3;

/// The particle condition of each box face from its patch, the collision wall model and the
/// patch interaction model.
pub(super) fn domain_box(
    case: &Case,
    sub: &Dict,
    soft_walls: bool,
    warnings: &mut Vec<String>,
) -> Result<DomainBox, CaseError> {
    let g = &case.mesh.grid;
    let length = g.length();
    let lo = g.origin;
    let hi = [lo[0] + length[0], lo[1] + length[1], lo[2] + length[2]];
    let interaction = PatchInteraction::read(sub)?;
    if let PatchInteraction::Local(rules) = &interaction {
        check_local_rules(rules, &case.mesh.patches, sub, warnings)?;
    }
    let mut faces = [FaceCondition::Periodic; 6];
    let mut wall_velocity = [[0.0; 3]; 6];
    for face in BoxFace::ALL {
        let patch = case.mesh.patch_on(face);
        faces[face.index()] = match patch.kind {
            PatchType::Cyclic => FaceCondition::Periodic,
            PatchType::Wall if soft_walls => {
                wall_velocity[face.index()] = wall_velocity_of(case, face, warnings);
                FaceCondition::Wall
            }
            kind => match interaction.rebound(patch)? {
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
    Ok(DomainBox {
        lo: lo.into(),
        hi: hi.into(),
        faces,
        planar: std::array::from_fn(|a| case.mesh.is_planar(a)),
        wall_velocity: wall_velocity.map(Vec3::from),
    })
}

/// The velocity the wall model gives a wall face: OpenFOAM's `PairCollision` takes the
/// fluid's boundary value on the face, which for `noSlip` and a uniform `fixedValue` is the
/// wall's own motion. For another condition on a wall (an inlet, a slip wall) that value
/// follows the flow; fsim keeps that wall at rest in the wall model and says so.
fn wall_velocity_of(case: &Case, face: BoxFace, warnings: &mut Vec<String>) -> [f64; 3] {
    let k = case.mesh.face_patch[face.index()];
    match case.fields.u_bc.get(k) {
        Some(VelocityBc::FixedValue(v)) => *v,
        Some(VelocityBc::NoSlip) | None => [0.0; 3],
        Some(_) => {
            let note = format!(
                "wall patch '{}': its velocity condition is neither noSlip nor a uniform \
                 fixedValue, so the wall model takes the wall at rest, where OpenFOAM's takes \
                 the fluid's velocity on it",
                case.mesh.patches[k].name
            );
            if !warnings.contains(&note) {
                warnings.push(note);
            }
            [0.0; 3]
        }
    }
}

/// `patchInteractionModel` with its coefficients: `rebound` only.
enum PatchInteraction {
    None,
    /// `standardWallInteraction`: one rule for every wall patch.
    Standard(Option<(f64, f64)>, Location, String),
    /// `localInteraction`: its `patches` entries in order.
    Local(Vec<LocalRule>),
}

/// One entry of `localInteraction`'s `patches`: the patches it names and its rule. As
/// OpenFOAM reads a `wordRe`, an unquoted word is the name itself ([`Key::Word`]), a quoted
/// string a regular expression that must match the whole name ([`Key::Pattern`]).
struct LocalRule {
    key: Key,
    rule: Dict,
}

impl LocalRule {
    /// Whether the entry names the patch: by its name or one of its groups, as OpenFOAM's
    /// `polyBoundaryMesh::indices(key, useGroups)` finds them (so `wall` names every wall).
    fn names(&self, patch: &Patch) -> bool {
        self.key.matches(&patch.name) || patch.groups.iter().any(|g| self.key.matches(g))
    }
}

/// OpenFOAM's checks of `localInteraction` (`patchInteractionDataList`): every patch that is
/// neither cyclic nor empty must be named by some entry (an error listing those that are
/// not), and an entry that names no patch is a warning.
fn check_local_rules(
    rules: &[LocalRule],
    patches: &[Patch],
    sub: &Dict,
    warnings: &mut Vec<String>,
) -> Result<(), CaseError> {
    for r in rules {
        if !patches.iter().any(|p| r.names(p)) {
            warnings.push(format!(
                "{}: localInteraction: no patch matches '{}' (patches: {})",
                sub.file(),
                r.key.as_str(),
                patches
                    .iter()
                    .map(|p| p.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
    }
    let unnamed: Vec<String> = patches
        .iter()
        .filter(|p| !matches!(p.kind, PatchType::Cyclic | PatchType::Empty))
        .filter(|p| !rules.iter().any(|r| r.names(p)))
        .map(|p| format!("'{}' ({})", p.name, p.kind.name()))
        .collect();
    if unnamed.is_empty() {
        return Ok(());
    }
    let coeffs = sub.get_dict("localInteractionCoeffs")?;
    Err(at_value(
        coeffs,
        "patches",
        format!(
            "localInteraction must name every patch that is neither cyclic nor empty, as in \
             OpenFOAM; no entry for {}",
            unnamed.join(", ")
        ),
    ))
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
                            let key = match &name.value {
                                Value::Word(w) => Key::Word(w.clone()),
                                Value::Str(s) => Key::pattern(s).map_err(|e| {
                                    CaseError::at(
                                        &name.loc,
                                        format!(
                                            "'{s}' is not a valid regular expression for \
                                             patch names: {}",
                                            last_line(&e.to_string())
                                        ),
                                    )
                                })?,
                                _ => {
                                    return Err(CaseError::at(
                                        &name.loc,
                                        "expected a patch name (a word, or a quoted regular \
                                         expression)",
                                    ))
                                }
                            };
                            let Some(d) = body.as_dict() else {
                                return Err(CaseError::at(
                                    &body.loc,
                                    "expected a dictionary { type …; } after the patch name",
                                ));
                            };
                            rules.push(LocalRule {
                                key,
                                rule: d.clone(),
                            });
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
    /// `localInteraction` the first entry that names the patch or one of its groups applies,
    /// as in OpenFOAM (`patchInteractionDataList::applyToPatch` returns the first group that
    /// holds the patch).
    fn rebound(&self, patch: &Patch) -> Result<Option<(f64, f64)>, CaseError> {
        let kind = patch.kind;
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
                for r in rules {
                    if r.names(patch) {
                        let (d, patch) = (&r.rule, &patch.name);
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

/// The last line of a message: the regex crate's errors draw the pattern above it.
fn last_line(message: &str) -> &str {
    message.lines().last().unwrap_or(message).trim()
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
        let rule = |name: &str| local.rebound(&patch(name, PatchType::Patch)).unwrap();
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
    fn an_unquoted_name_is_literal_and_a_bad_expression_is_an_error_at_it() {
        // OpenFOAM's wordRe: a word is the name itself, only a quoted string is an expression
        let local = interaction(
            "patchInteractionModel localInteraction;\n\
             localInteractionCoeffs { patches ( side.* { type rebound; e 0.5; } ); }\n",
        );
        assert_eq!(
            local.rebound(&patch("sideLeft", PatchType::Wall)).unwrap(),
            None
        );
        assert_eq!(
            local.rebound(&patch("side.*", PatchType::Wall)).unwrap(),
            Some((0.5, 0.0))
        );
        let d = Dict::parse(
            "patchInteractionModel localInteraction;\n\
             localInteractionCoeffs { patches ( top { type rebound; } \"(front|back\" \
             { type rebound; } ); }\n",
            "cloud",
        )
        .unwrap();
        let e = PatchInteraction::read(&d).err().expect("an unclosed group");
        assert!(
            e.message
                .contains("'(front|back' is not a valid regular expression")
                && e.message.contains("unclosed group"),
            "{}",
            e.message
        );
        assert_eq!((e.line, e.col), (2, 58), "{}", e.message);
    }

    fn patch(name: &str, kind: PatchType) -> Patch {
        let file = std::sync::Arc::new(crate::case::source::SourceFile::from_text(
            "blockMeshDict".into(),
            "blockMeshDict".into(),
            String::new(),
        ));
        Patch {
            name: name.to_string(),
            kind,
            faces: Vec::new(),
            neighbour: None,
            groups: crate::case::block_mesh::groups_of(kind, Vec::new()),
            loc: Location::new(&file, 0),
        }
    }

    #[test]
    fn every_patch_but_cyclic_and_empty_ones_needs_an_entry() {
        let text = "patchInteractionModel localInteraction;\n\
                    localInteractionCoeffs { patches ( top { type rebound; } \
                    \"(in|out)let\" { type rebound; } lid { type rebound; } ); }\n";
        let d = Dict::parse(text, "cloud").unwrap();
        let PatchInteraction::Local(rules) = PatchInteraction::read(&d).unwrap() else {
            panic!("localInteraction");
        };
        let mut patches = vec![
            patch("top", PatchType::Wall),
            patch("inlet", PatchType::Patch),
            patch("outlet", PatchType::Patch),
            patch("sides", PatchType::Cyclic),
            patch("frontAndBack", PatchType::Empty),
        ];
        let mut warnings = Vec::new();
        check_local_rules(&rules, &patches, &d, &mut warnings).unwrap();
        // a group names its patches: `wall` every wall, `inGroups` names too
        let groups = interaction(
            "patchInteractionModel localInteraction;\n\
             localInteractionCoeffs { patches ( bottom { type rebound; e 1; } \
             wall { type rebound; e 0.5; } inlets { type rebound; e 0.7; } ); }\n",
        );
        let mut inlet = patch("in", PatchType::Patch);
        inlet.groups.push("inlets".into());
        assert_eq!(groups.rebound(&inlet).unwrap(), Some((0.7, 0.0)));
        assert_eq!(
            groups.rebound(&patch("top", PatchType::Wall)).unwrap(),
            Some((0.5, 0.0))
        );
        // the first entry that holds the patch applies: bottom's own, before its group's
        assert_eq!(
            groups.rebound(&patch("bottom", PatchType::Wall)).unwrap(),
            Some((1.0, 0.0))
        );
        assert_eq!(
            groups.rebound(&patch("outlet", PatchType::Patch)).unwrap(),
            None
        );
        // `lid` names no patch: a warning, as OpenFOAM's "Cannot find any patch names"
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert!(
            warnings[0].contains("no patch matches 'lid'"),
            "{}",
            warnings[0]
        );
        patches.push(patch("bottom", PatchType::Wall));
        patches.push(patch("mirror", PatchType::Symmetry));
        let e = check_local_rules(&rules, &patches, &d, &mut warnings).unwrap_err();
        assert!(
            e.message
                .contains("no entry for 'bottom' (wall), 'mirror' (symmetry)"),
            "{}",
            e.message
        );
        // at the list's opening parenthesis
        assert_eq!((e.line, e.col), (2, 34), "{}", e.message);
    }

    #[test]
    fn a_rule_other_than_rebound_or_out_of_range_is_an_error_at_its_value() {
        let local = interaction(
            "patchInteractionModel localInteraction;\n\
             localInteractionCoeffs { patches ( top { type stick; } \
             bottom { type rebound; e 1.5; } ); }\n",
        );
        let e = local.rebound(&patch("top", PatchType::Wall)).unwrap_err();
        assert!(
            e.message.contains("'stick' on patch 'top'") && e.message.contains("use rebound"),
            "{}",
            e.message
        );
        assert_eq!((e.line, e.col), (2, 47), "{}", e.message);
        let e = local
            .rebound(&patch("bottom", PatchType::Wall))
            .unwrap_err();
        assert!(e.message.contains("in [0, 1]"), "{}", e.message);
    }

    #[test]
    fn the_standard_interaction_applies_to_walls_only() {
        let standard = interaction(
            "patchInteractionModel standardWallInteraction;\n\
             standardWallInteractionCoeffs { type rebound; e 0.8; mu 0.2; }\n",
        );
        assert_eq!(
            standard.rebound(&patch("walls", PatchType::Wall)).unwrap(),
            Some((0.8, 0.2))
        );
        assert_eq!(
            standard.rebound(&patch("inlet", PatchType::Patch)).unwrap(),
            None
        );
        let escape = interaction(
            "patchInteractionModel standardWallInteraction;\n\
             standardWallInteractionCoeffs { type escape; }\n",
        );
        let e = escape
            .rebound(&patch("walls", PatchType::Wall))
            .unwrap_err();
        assert!(e.message.contains("'escape'"), "{}", e.message);
        assert_eq!(e.line, 2, "{}", e.message);
        // a non-wall patch is not the standard interaction's, whatever its rule
        assert_eq!(
            escape
                .rebound(&patch("inlet", PatchType::Symmetry))
                .unwrap(),
            None
        );
        let none = interaction("patchInteractionModel none;\n");
        assert_eq!(
            none.rebound(&patch("walls", PatchType::Wall)).unwrap(),
            None
        );
    }
}
