//! The cloud's `subModels.particleForces` (DPMFoam's list), read for either coupling model:
//! one drag closure at most (`nonSphereDrag { phi …; }` among them), `gravity`,
//! `pressureGradient`, `virtualMass { Cvm …; }`, one lift force (`SaffmanMeiLiftForce`,
//! `TomiyamaLift { sigma …; }`); the forces fsim does not compute refused by name, an
//! unknown name an error with a spelling hint.

use super::control_dict::at_value;
use super::dictionary::{Dict, Entry};
use super::drag_law_options::{fraction_name, velocity_name};
use super::error::CaseError;
use super::quote::quote;
use crate::coupling::drag::{DragClosure, LiftModel};

/// Force names fsim does not compute, with why: OpenFOAM v1912's forces of a kinematic cloud
/// that fsim leaves out, and two names DPMFoam's kinematic cloud rejects (its error lists the
/// 14 it offers: `ErgunWenYuDrag PlessisMasliyahDrag SRF SaffmanMeiLiftForce TomiyamaLift
/// WenYuDrag gravity interface nonInertialFrame nonSphereDrag paramagnetic pressureGradient
/// sphereDrag virtualMass`).
const REFUSED_FORCES: [(&str, &str); 6] = [
    (
        "distortedSphereDrag",
        "the drag of distorting spray droplets, Liu, Mather & Reitz 1993: DPMFoam's kinematic \
         cloud does not offer it either (OpenFOAM v1912 builds it for spray parcels only, whose \
         distortion it reads; DPMFoam stops with 'Unknown particle force type')",
    ),
    (
        "TomiyamaLiftForce",
        "DPMFoam v1912 names Tomiyama's lift 'TomiyamaLift' and stops on 'TomiyamaLiftForce'; \
         write TomiyamaLift { U <velocity>; sigma <N/m>; }",
    ),
    ("paramagnetic", "a magnetic force, needing a magnetic field"),
    (
        "interface",
        "the force of a fluid interface, needing its phase-fraction field",
    ),
    (
        "nonInertialFrame",
        "the forces of a non-inertial frame: fsim's fluid is solved in an inertial frame",
    ),
    (
        "SRF",
        "the forces of a rotating frame: fsim's fluid has no single rotating frame",
    ),
];

/// The forces of `particleForces`, checked.
pub struct ParticleForces {
    pub drag: Option<DragClosure>,
    pub gravity: bool,
    pub pressure_gradient: bool,
    /// `virtualMass`'s `Cvm`.
    pub virtual_mass: Option<f64>,
    /// The lift force.
    pub lift: Option<LiftModel>,
    /// Every force listed, in file order.
    pub names: Vec<String>,
}

/// The names besides the drag closures, for messages and spelling hints.
const OTHER_FORCES: [&str; 6] = [
    "gravity",
    "pressureGradient",
    "virtualMass",
    "SaffmanMeiLiftForce",
    "TomiyamaLift",
    "nonSphereDrag",
];

impl ParticleForces {
    /// Reads and checks `subModels.particleForces`: an unknown force, a force fsim cannot
    /// compute or a second drag closure is an error at its keyword.
    pub fn read(sub: &Dict, phase: &str) -> Result<ParticleForces, CaseError> {
        let mut forces = ParticleForces {
            drag: None,
            gravity: false,
            pressure_gradient: false,
            virtual_mass: None,
            lift: None,
            names: Vec::new(),
        };
        let mut lift_at: Option<&Entry> = None;
        let Some(list) = sub.opt_dict("particleForces")? else {
            return Ok(forces);
        };
        let mut drag_at: Option<&Entry> = None;
        for e in list.entries() {
            let name = e.keyword();
            e.mark_used();
            forces.names.push(name.to_string());
            let closure = if name == "nonSphereDrag" {
                Some(non_sphere(e)?)
            } else {
                DragClosure::from_name(name, "particleForces").ok()
            };
            if let Some(model) = closure {
                if let Some(first) = drag_at {
                    return Err(second(e, first, "drag model", "drag closure"));
                }
                drag_at = Some(e);
                if let Some(coeffs) = e.as_dict() {
                    if !matches!(
                        model,
                        DragClosure::SphereDrag | DragClosure::NonSphere { .. }
                    ) {
                        fraction_field(coeffs, "alphac", phase, is_openfoam(model))?;
                    }
                }
                forces.drag = Some(model);
            } else if name == "gravity" {
                forces.gravity = true;
            } else if name == "pressureGradient" {
                fluid_velocity(e, phase)?;
                forces.pressure_gradient = true;
            } else if name == "virtualMass" {
                fluid_velocity(e, phase)?;
                let cvm = coefficient(e, "Cvm", "virtualMass { U <velocity>; Cvm 0.5; }")?;
                if !(cvm.is_finite() && cvm >= 0.0) {
                    return Err(at_value(
                        e.as_dict().expect("a coefficient was read"),
                        "Cvm",
                        format!(
                            "virtualMass Cvm {cvm}: expected a finite added-mass coefficient \
                             ≥ 0 (0.5 for a sphere)"
                        ),
                    ));
                }
                forces.virtual_mass = Some(cvm);
            } else if name == "SaffmanMeiLiftForce" || name == "TomiyamaLift" {
                if let Some(first) = lift_at {
                    return Err(second(e, first, "lift force", "lift force"));
                }
                lift_at = Some(e);
                fluid_velocity(e, phase)?;
                forces.lift = Some(if name == "TomiyamaLift" {
                    let sigma =
                        coefficient(e, "sigma", "TomiyamaLift { U <velocity>; sigma 0.07; }")?;
                    if !(sigma.is_finite() && sigma > 0.0) {
                        return Err(at_value(
                            e.as_dict().expect("a coefficient was read"),
                            "sigma",
                            format!(
                                "TomiyamaLift sigma {sigma}: expected a surface tension > 0 \
                                 (N/m)"
                            ),
                        ));
                    }
                    LiftModel::Tomiyama { sigma }
                } else {
                    LiftModel::SaffmanMei
                });
            } else if let Some((_, why)) = REFUSED_FORCES.iter().find(|(n, _)| *n == name) {
                return Err(CaseError::at(
                    &e.key_loc,
                    format!("particle force '{name}' is not supported by fsim ({why})"),
                ));
            } else {
                let others = OTHER_FORCES;
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
                        "{what} '{}' in particleForces{hint}: expected a drag model ({}, \
                         nonSphereDrag), gravity, pressureGradient, virtualMass, \
                         SaffmanMeiLiftForce or TomiyamaLift",
                        quote(name),
                        DragClosure::NAMES.join(", ")
                    ),
                ));
            }
        }
        Ok(forces)
    }
}

/// A second `kind` in `particleForces` at `e`, `first` being the one already read: DPMFoam
/// would add both, fsim takes one `takes`.
fn second(e: &Entry, first: &Entry, kind: &str, takes: &str) -> CaseError {
    let (line, _) = first.key_loc.line_col();
    CaseError::at(
        &e.key_loc,
        format!(
            "a second {kind} '{}' (the first, '{}', is on line {line}): DPMFoam would add \
             both; fsim takes one {takes}",
            e.keyword(),
            first.keyword()
        ),
    )
}

/// A force's `U` (the fluid velocity it reads, OpenFOAM's default `U`): when given, the
/// continuous phase's velocity.
fn fluid_velocity(e: &Entry, phase: &str) -> Result<(), CaseError> {
    let Some(coeffs) = e.as_dict() else {
        return Ok(());
    };
    let velocity = velocity_name(phase);
    if let Some(u) = coeffs.opt_word("U")? {
        if u != velocity {
            return Err(at_value(
                coeffs,
                "U",
                format!(
                    "{} U '{u}': expected the continuous phase's velocity {velocity}",
                    e.keyword()
                ),
            ));
        }
    }
    Ok(())
}

/// A force's required coefficient `keyword` (DPMFoam reads it without a default); `example`
/// shows the entry in the message when it is missing.
fn coefficient(e: &Entry, keyword: &str, example: &str) -> Result<f64, CaseError> {
    match e.as_dict() {
        Some(coeffs) => coeffs.get_scalar(keyword),
        None => Err(CaseError::at(
            &e.key_loc,
            format!(
                "{} needs its coefficient '{keyword}' (DPMFoam reads it without a default): \
                 write {example}",
                e.keyword()
            ),
        )),
    }
}

/// `nonSphereDrag { phi …; }`: the sphericity, in (0, 1] as OpenFOAM requires.
fn non_sphere(e: &Entry) -> Result<DragClosure, CaseError> {
    let phi = coefficient(e, "phi", "nonSphereDrag { phi 0.8; }")?;
    if !(phi > 0.0 && phi <= 1.0) {
        return Err(at_value(
            e.as_dict().expect("a coefficient was read"),
            "phi",
            format!(
                "nonSphereDrag phi {phi}: expected a sphericity in (0, 1] (the surface of the \
                 sphere of the particle's volume over the particle's surface; 1 is a sphere)"
            ),
        ));
    }
    Ok(DragClosure::NonSphere { phi })
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
        for (entries, says) in [
            (
                "    sphereDrag;\n    WenYuDrag { alphac alpha.air; }",
                "the first, 'sphereDrag', is on line 3",
            ),
            (
                "    sphereDrag;\n    nonSphereDrag { phi 0.5; }",
                "a second drag model 'nonSphereDrag'",
            ),
            (
                "    SaffmanMeiLiftForce;\n    TomiyamaLift { sigma 0.07; }",
                "a second lift force 'TomiyamaLift'",
            ),
            (
                "    virtualMas { Cvm 0.5; }",
                "(did you mean 'virtualMass'?)",
            ),
        ] {
            let e = forces(entries).err().expect(entries);
            assert!(e.message.contains(says), "{entries}: {}", e.message);
        }
    }

    #[test]
    fn dpmfoam_forces_and_their_coefficients() {
        let f = forces(
            "    nonSphereDrag { phi 0.8; }\n    pressureGradient { U U.air; }\n    \
             virtualMass { U U.air; Cvm 0.5; }\n    TomiyamaLift { U U.air; sigma 0.07; }",
        )
        .unwrap();
        assert_eq!(f.drag, Some(DragClosure::NonSphere { phi: 0.8 }));
        assert!(f.pressure_gradient);
        assert_eq!(f.virtual_mass, Some(0.5));
        assert_eq!(f.lift, Some(LiftModel::Tomiyama { sigma: 0.07 }));
        let f = forces("    SaffmanMeiLiftForce;\n    nonSphereDrag { phi 1; }").unwrap();
        assert_eq!(f.lift, Some(LiftModel::SaffmanMei));
        assert_eq!(f.drag, Some(DragClosure::NonSphere { phi: 1.0 }));
        // bad values: an error at the value, file:line:col
        for (list, col, what) in [
            (
                "    nonSphereDrag { phi 0; }",
                25,
                "nonSphereDrag phi 0: expected a sphericity",
            ),
            (
                "    nonSphereDrag { phi 1.5; }",
                25,
                "nonSphereDrag phi 1.5",
            ),
            (
                "    virtualMass { Cvm -0.5; }",
                23,
                "virtualMass Cvm -0.5: expected",
            ),
            (
                "    TomiyamaLift { sigma 0; }",
                26,
                "TomiyamaLift sigma 0: expected",
            ),
        ] {
            let e = forces(list).err().expect(list);
            assert_eq!(e.file.as_deref(), Some("constant/kinematicCloudProperties"));
            assert_eq!((e.line, e.col), (3, col), "{}", e.message);
            assert!(e.message.starts_with(what), "{}", e.message);
        }
        // coefficients DPMFoam reads without a default
        let e = forces("    virtualMass;").err().unwrap();
        assert!(
            e.message.contains("needs its coefficient 'Cvm'"),
            "{}",
            e.message
        );
        let e = forces("    TomiyamaLift { U U.air; }").err().unwrap();
        assert!(e.message.contains("sigma"), "{}", e.message);
        let e = forces("    SaffmanMeiLiftForce { U U.water; }")
            .err()
            .unwrap();
        assert!(e
            .message
            .contains("expected the continuous phase's velocity U.air"));
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
