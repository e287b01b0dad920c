//! The initial fields `0/U.<phase>` (or `0/U`) and `0/p`: internal values and one boundary
//! condition per patch, checked against the patch types.

use std::path::Path;

use super::block_mesh::{BlockMesh, Patch, PatchType};
use super::dictionary::{single_token, Dict, Entry, EntryBody};
use super::error::CaseError;
use super::value::{Item, Value};

/// A field's cell values: one value for all cells, or one per cell in the grid's x-fastest
/// order.
#[derive(Clone, Debug, PartialEq)]
pub enum InternalField<T> {
    Uniform(T),
    Nonuniform(Vec<T>),
}

impl<T: Copy> InternalField<T> {
    /// The value in cell `index` (x-fastest linear index).
    pub fn value(&self, index: usize) -> T {
        match self {
            InternalField::Uniform(v) => *v,
            InternalField::Nonuniform(values) => values[index],
        }
    }

    /// All `cells` values, expanded.
    pub fn to_vec(&self, cells: usize) -> Vec<T> {
        match self {
            InternalField::Uniform(v) => vec![*v; cells],
            InternalField::Nonuniform(values) => values.clone(),
        }
    }
}

/// Velocity boundary conditions fsim supports.
#[derive(Clone, Debug, PartialEq)]
pub enum VelocityBc {
    /// u = 0 on a wall.
    NoSlip,
    /// u = value.
    FixedValue([f64; 3]),
    /// ∂u/∂n = 0.
    ZeroGradient,
    /// Periodic with the neighbour patch.
    Cyclic,
    /// Mirror: u·n = 0, ∂(u − (u·n)n)/∂n = 0.
    Symmetry,
    SymmetryPlane,
    /// u·n = 0, zero tangential stress.
    Slip,
    /// A direction with one cell (2-D case).
    Empty,
    /// Zero gradient for outflow; inflow velocity from the flux normal to the patch.
    PressureInletOutletVelocity,
    /// Zero gradient for outflow, `inlet_value` where the flow enters.
    InletOutlet {
        inlet_value: [f64; 3],
    },
    /// DPMFoam's inlet: the superficial `inlet_velocity` divided by the local fluid fraction
    /// (field `alpha`) gives the interstitial velocity.
    InterstitialInletVelocity {
        inlet_velocity: [f64; 3],
        alpha: String,
    },
}

/// Pressure boundary conditions fsim supports.
#[derive(Clone, Debug, PartialEq)]
pub enum PressureBc {
    ZeroGradient,
    /// The gradient that makes the wall flux match the velocity condition.
    FixedFluxPressure,
    /// p = value (kinematic).
    FixedValue(f64),
    /// p = p0 − ½|u|² for inflow, p0 for outflow (kinematic).
    TotalPressure {
        p0: f64,
    },
    Cyclic,
    Symmetry,
    SymmetryPlane,
    Empty,
}

const VELOCITY_TYPES: [&str; 11] = [
    "noSlip",
    "fixedValue",
    "zeroGradient",
    "cyclic",
    "symmetry",
    "symmetryPlane",
    "slip",
    "empty",
    "pressureInletOutletVelocity",
    "inletOutlet",
    "interstitialInletVelocity",
];

const PRESSURE_TYPES: [&str; 8] = [
    "zeroGradient",
    "fixedFluxPressure",
    "fixedValue",
    "totalPressure",
    "cyclic",
    "symmetry",
    "symmetryPlane",
    "empty",
];

/// The initial velocity and pressure with their boundary conditions.
#[derive(Clone, Debug, PartialEq)]
pub struct Fields {
    /// The time directory they were read from (`0`).
    pub time: String,
    /// `U.<phase>` or `U`.
    pub velocity_name: String,
    /// Cell-centred velocity, m/s.
    pub u: InternalField<[f64; 3]>,
    /// Cell-centred kinematic pressure, m²/s².
    pub p: InternalField<f64>,
    /// One condition per patch, in the order of [`BlockMesh::patches`].
    pub u_bc: Vec<VelocityBc>,
    pub p_bc: Vec<PressureBc>,
}

/// A field file, parsed: what `read_fields` returns besides the typed fields, so that the
/// case loader can list the ignored keywords.
pub struct FieldDicts {
    pub u: Dict,
    pub p: Dict,
}

impl Fields {
    /// Reads `<time>/<velocity_name>` and `<time>/p` under `case_dir`.
    pub fn read(
        case_dir: &Path,
        time: &str,
        velocity_name: &str,
        mesh: &BlockMesh,
        warnings: &mut Vec<String>,
    ) -> Result<(Fields, FieldDicts), CaseError> {
        let dir = case_dir.join(time);
        // OpenFOAM tutorials ship `0.orig`, copied to `0` by their Allrun scripts.
        let hint = |e: CaseError| {
            let orig = case_dir.join(format!("{time}.orig"));
            if !dir.exists() && orig.is_dir() {
                let mut e = e;
                e.message = format!(
                    "{} (the case has {time}.orig: copy it to {time}, as the tutorial's Allrun does)",
                    e.message
                );
                e
            } else {
                e
            }
        };
        let u_dict = Dict::read(&dir.join(velocity_name), Some(case_dir)).map_err(hint)?;
        let p_dict = Dict::read(&dir.join("p"), Some(case_dir)).map_err(hint)?;
        u_dict.check_dimensions(
            "dimensions",
            [0.0, 1.0, -1.0, 0.0, 0.0, 0.0, 0.0],
            "m/s, a velocity",
        )?;
        p_dict.check_dimensions(
            "dimensions",
            [0.0, 2.0, -2.0, 0.0, 0.0, 0.0, 0.0],
            "m²/s², the kinematic pressure p/ρ that icoFoam, pimpleFoam and DPMFoam solve for",
        )?;
        let cells = mesh.grid.cell_count();
        let u = internal(
            &u_dict,
            cells,
            "a vector (x y z)",
            Item::as_vector,
            vector_row,
        )?;
        let p = internal(&p_dict, cells, "a number", Item::as_scalar, scalar_row)?;
        let u_bc = conditions(&u_dict, mesh, warnings)?
            .into_iter()
            .zip(&mesh.patches)
            .map(|(d, patch)| match d {
                Some(d) => velocity_bc(d, patch, velocity_name, warnings),
                None => Ok(implied_velocity(patch.kind)),
            })
            .collect::<Result<Vec<_>, _>>()?;
        let p_bc = conditions(&p_dict, mesh, warnings)?
            .into_iter()
            .zip(&mesh.patches)
            .map(|(d, patch)| match d {
                Some(d) => pressure_bc(d, patch),
                None => Ok(implied_pressure(patch.kind)),
            })
            .collect::<Result<Vec<_>, _>>()?;
        for d in [&u_dict, &p_dict] {
            // The dimensions are fixed by the field's kind.
            d.lookup("dimensions");
        }
        let fields = Fields {
            time: time.to_string(),
            velocity_name: velocity_name.to_string(),
            u,
            p,
            u_bc,
            p_bc,
        };
        Ok((
            fields,
            FieldDicts {
                u: u_dict,
                p: p_dict,
            },
        ))
    }
}

/// `internalField uniform X;` or `internalField nonuniform List<T> N(…);`. `convert` reads
/// one value token, `from_row` one row of a packed list (and refuses a row of another width).
fn internal<T>(
    d: &Dict,
    cells: usize,
    what: &str,
    convert: impl Fn(&Item) -> Option<T>,
    from_row: impl Fn(&[f64]) -> Option<T>,
) -> Result<InternalField<T>, CaseError> {
    let entry = d.get_entry("internalField")?;
    let (kind, value) = uniform_or_not(entry)?;
    let bad = |item: &Item| {
        CaseError::at(
            &item.loc,
            format!(
                "expected {what} in 'internalField', found {}",
                item.describe()
            ),
        )
    };
    if kind == "uniform" {
        return convert(value)
            .map(InternalField::Uniform)
            .ok_or_else(|| bad(value));
    }
    let list = value.as_list().ok_or_else(|| {
        CaseError::at(
            &value.loc,
            format!(
                "expected a list of {cells} values after 'nonuniform', found {}",
                value.describe()
            ),
        )
    })?;
    if list.len() != cells {
        return Err(CaseError::at(
            &value.loc,
            format!(
                "expected {cells} values in 'internalField' (one per cell of the block), found {}",
                list.len()
            ),
        ));
    }
    let mut values = Vec::with_capacity(cells);
    if let Value::Numbers { width, data, .. } = &value.value {
        // The common case, a packed list of the right width: no token per value.
        for row in data.chunks_exact(*width) {
            match from_row(row) {
                Some(v) => values.push(v),
                None => break,
            }
        }
        if values.len() == cells {
            return Ok(InternalField::Nonuniform(values));
        }
        values.clear();
    }
    for item in list.iter() {
        values.push(convert(&item).ok_or_else(|| bad(&item))?);
    }
    Ok(InternalField::Nonuniform(values))
}

/// A packed row of one number.
fn scalar_row(row: &[f64]) -> Option<f64> {
    match row {
        [x] => Some(*x),
        _ => None,
    }
}

/// A packed row of three numbers.
fn vector_row(row: &[f64]) -> Option<[f64; 3]> {
    <[f64; 3]>::try_from(row).ok()
}

/// Splits `uniform X` / `nonuniform List<T> N(…)` into the keyword and the value token.
fn uniform_or_not(entry: &Entry) -> Result<(&'static str, &Item), CaseError> {
    let keyword = entry.keyword();
    let tokens = entry.as_tokens().ok_or_else(|| {
        CaseError::at(
            &entry.key_loc,
            format!(
                "expected 'uniform' or 'nonuniform' values for '{keyword}', found a dictionary"
            ),
        )
    })?;
    let first = tokens.first().ok_or_else(|| {
        CaseError::at(
            &entry.key_loc,
            format!("expected 'uniform' or 'nonuniform' after '{keyword}'"),
        )
    })?;
    let (kind, rest) = match first.as_word() {
        Some("uniform") => ("uniform", &tokens[1..]),
        // The list's type (`List<vector>`) is optional before the list.
        Some("nonuniform") => {
            let rest = match &tokens[1..] {
                [ty, rest @ ..] if ty.as_word().is_some_and(|w| w.starts_with("List<")) => rest,
                rest => rest,
            };
            // A count written apart from its list on the same line (`3 (1 2 3)`): the parser
            // reads it as a number, so check it against the list here.
            match rest {
                [count, list] if count.as_label().is_some() && list.as_list().is_some() => {
                    let n = list.as_list().map_or(0, |l| l.len());
                    if count.as_label() != Some(n as i64) {
                        return Err(CaseError::at(
                            &count.loc,
                            format!(
                                "expected {} elements as the count says, found a list of {n}",
                                count.as_label().unwrap_or(0)
                            ),
                        ));
                    }
                    ("nonuniform", &rest[1..])
                }
                _ => ("nonuniform", rest),
            }
        }
        _ => {
            return Err(CaseError::at(
                &first.loc,
                format!(
                    "expected 'uniform' or 'nonuniform' for '{keyword}', found {}",
                    first.describe()
                ),
            ))
        }
    };
    match rest {
        [value] => Ok((kind, value)),
        [] => Err(CaseError::at(
            &first.loc,
            format!("expected a value after '{kind}' for '{keyword}'"),
        )),
        [_, extra, ..] => Err(CaseError::at(
            &extra.loc,
            format!(
                "expected ';' to end the entry '{keyword}' after its value, found {}",
                extra.describe()
            ),
        )),
    }
}

/// A patch value: `uniform X` only.
fn patch_value<T>(
    d: &Dict,
    keyword: &str,
    what: &str,
    convert: impl Fn(&Item) -> Option<T>,
) -> Result<T, CaseError> {
    let entry = d.get_entry(keyword)?;
    let (kind, value) = uniform_or_not(entry)?;
    if kind != "uniform" {
        return Err(CaseError::at(
            entry.value_loc(),
            format!(
                "expected 'uniform' for '{keyword}': fsim supports only uniform values on patches"
            ),
        ));
    }
    convert(value).ok_or_else(|| {
        CaseError::at(
            &value.loc,
            format!(
                "expected {what} for '{keyword}', found {}",
                value.describe()
            ),
        )
    })
}

/// The `boundaryField` dictionary of each patch: exact name first, then the patch's groups
/// (its `inGroups` and its type's: `wall`, `cyclic`, `empty`, …), then the quoted patterns,
/// last first (OpenFOAM's order).
/// A keyword naming no patch is an error; a pattern or group that matches none is noted.
/// `None` stands for a constraint patch (cyclic, empty, symmetry) left to
/// `#includeEtc "caseDicts/setConstraintTypes"`, which gives each its own type.
pub(crate) fn conditions<'a>(
    d: &'a Dict,
    mesh: &BlockMesh,
    warnings: &mut Vec<String>,
) -> Result<Vec<Option<&'a Dict>>, CaseError> {
    let bf = d.get_dict("boundaryField")?;
    let constraint_types = bf
        .directives
        .iter()
        .any(|x| x.name == "includeEtc" && x.argument.ends_with("caseDicts/setConstraintTypes"));
    let entries = bf.entries();
    let mut matched = vec![false; entries.len()];
    let mut out = Vec::with_capacity(mesh.patches.len());
    for patch in &mesh.patches {
        // a quoted key is a pattern even when it spells a name (OpenFOAM's `isLiteral`)
        let exact = entries
            .iter()
            .rposition(|e| !e.key.is_pattern() && e.keyword() == patch.name);
        let group = || {
            entries
                .iter()
                .rposition(|e| !e.key.is_pattern() && patch.groups.iter().any(|g| g == e.keyword()))
        };
        let pattern = || {
            entries
                .iter()
                .rposition(|e| e.key.pattern_matches(&patch.name))
        };
        let Some(k) = exact.or_else(group).or_else(pattern) else {
            if constraint_types && patch.kind.is_constraint() {
                out.push(None);
                continue;
            }
            return Err(CaseError::at(
                &bf.loc,
                format!(
                    "missing boundary condition for patch '{}' in 'boundaryField' (starting at line {})",
                    patch.name,
                    bf.loc.line_col().0
                ),
            ));
        };
        matched[k] = true;
        let entry = &entries[k];
        entry.mark_used();
        match &entry.body {
            EntryBody::Dict(cd) => out.push(Some(cd)),
            EntryBody::Tokens(_) => {
                return Err(CaseError::at(
                    &entry.key_loc,
                    format!(
                        "expected a dictionary {{ type …; }} for patch '{}', found a value",
                        entry.keyword()
                    ),
                ))
            }
        }
    }
    let names: Vec<&str> = mesh.patches.iter().map(|p| p.name.as_str()).collect();
    for (e, used) in entries.iter().zip(&matched) {
        if *used {
            continue;
        }
        e.mark_used();
        let is_group = (PatchType::NAMES.contains(&e.keyword()) && e.keyword() != "patch")
            || mesh
                .patches
                .iter()
                .any(|p| p.groups.iter().any(|g| g == e.keyword()));
        if e.key.is_pattern() || is_group {
            let (line, col) = e.key_loc.line_col();
            warnings.push(format!(
                "{}:{line}:{col}: '{}' in boundaryField matches no patch; ignored",
                d.file(),
                e.keyword()
            ));
        } else {
            return Err(CaseError::at(
                &e.key_loc,
                format!(
                    "unknown patch '{}' in boundaryField: expected one of the blockMeshDict patches ({})",
                    e.keyword(),
                    names.join(", ")
                ),
            ));
        }
    }
    Ok(out)
}

/// The condition's `type`, as an index into `types`, checked against the patch type.
pub(crate) fn condition_type(
    d: &Dict,
    patch: &Patch,
    types: &[&str],
    field: &str,
) -> Result<usize, CaseError> {
    let entry = d.get_entry("type")?;
    let item = single_token(entry, "a boundary condition type")?;
    let word = item.as_word().unwrap_or("");
    let k = types.iter().position(|t| *t == word).ok_or_else(|| {
        CaseError::at(
            &item.loc,
            format!(
                "unknown {field} boundary condition {}: expected one of {}",
                item.describe(),
                types.join(", ")
            ),
        )
    })?;
    let kind = patch.kind;
    let symmetric = matches!(kind, PatchType::Symmetry | PatchType::SymmetryPlane);
    let ok = match word {
        "cyclic" => kind == PatchType::Cyclic,
        "empty" => kind == PatchType::Empty,
        "symmetry" | "symmetryPlane" => symmetric,
        "slip" => !matches!(kind, PatchType::Cyclic | PatchType::Empty),
        _ => !kind.is_constraint(),
    };
    if !ok {
        let wanted = match kind {
            PatchType::Cyclic => "cyclic".to_string(),
            PatchType::Empty => "empty".to_string(),
            PatchType::Symmetry | PatchType::SymmetryPlane if field == "velocity" => {
                "symmetry, symmetryPlane or slip".to_string()
            }
            PatchType::Symmetry | PatchType::SymmetryPlane => {
                "symmetry or symmetryPlane".to_string()
            }
            _ => format!("a condition for a {} patch (not {word})", kind.name()),
        };
        return Err(CaseError::at(
            &item.loc,
            format!(
                "expected {wanted} on patch '{}' of type {}, found {}",
                patch.name,
                kind.name(),
                item.describe()
            ),
        ));
    }
    Ok(k)
}

/// One velocity condition. `velocity_name` (`U.air`) gives the phase whose fluid fraction
/// (`alpha.air`) an `interstitialInletVelocity` must name.
fn velocity_bc(
    d: &Dict,
    patch: &Patch,
    velocity_name: &str,
    notes: &mut Vec<String>,
) -> Result<VelocityBc, CaseError> {
    let vector = |key: &str| patch_value(d, key, "a vector (x y z)", Item::as_vector);
    let bc = match VELOCITY_TYPES[condition_type(d, patch, &VELOCITY_TYPES, "velocity")?] {
        "noSlip" => VelocityBc::NoSlip,
        "fixedValue" => VelocityBc::FixedValue(vector("value")?),
        "zeroGradient" => VelocityBc::ZeroGradient,
        "cyclic" => VelocityBc::Cyclic,
        "symmetry" => VelocityBc::Symmetry,
        "symmetryPlane" => VelocityBc::SymmetryPlane,
        "slip" => VelocityBc::Slip,
        "empty" => VelocityBc::Empty,
        "pressureInletOutletVelocity" => {
            // OpenFOAM: zero gradient where the flow leaves; where it enters, the normal part
            // from the flux and the tangential part of `inletValue` (default zero).
            if d.contains("inletValue") {
                vector("inletValue")?;
            }
            let (line, col) = d.loc.line_col();
            notes.push(format!(
                "{}:{line}:{col}: patch '{}' pressureInletOutletVelocity: where the flow enters \
                 (back-flow) fsim keeps the tangential velocity zero-gradient instead of \
                 inletValue's; the normal velocity follows the fixed pressure either way",
                d.file(),
                patch.name
            ));
            VelocityBc::PressureInletOutletVelocity
        }
        "inletOutlet" => VelocityBc::InletOutlet {
            inlet_value: vector("inletValue")?,
        },
        _ => {
            let phase = velocity_name.strip_prefix("U.").unwrap_or("");
            let expected = super::drag_law_options::fraction_name(phase);
            let alpha = d.get_word_or("alpha", "alpha")?;
            if alpha != expected {
                return Err(super::control_dict::at_value(
                    d,
                    "alpha",
                    format!(
                        "interstitialInletVelocity alpha '{alpha}': expected the continuous \
                         phase's fluid fraction {expected}"
                    ),
                ));
            }
            VelocityBc::InterstitialInletVelocity {
                inlet_velocity: vector("inletVelocity")?,
                alpha,
            }
        }
    };
    quiet_bookkeeping(d);
    Ok(bc)
}

fn pressure_bc(d: &Dict, patch: &Patch) -> Result<PressureBc, CaseError> {
    let scalar = |key: &str| patch_value(d, key, "a number", Item::as_scalar);
    let bc = match PRESSURE_TYPES[condition_type(d, patch, &PRESSURE_TYPES, "pressure")?] {
        "zeroGradient" => PressureBc::ZeroGradient,
        "fixedFluxPressure" => PressureBc::FixedFluxPressure,
        "fixedValue" => PressureBc::FixedValue(scalar("value")?),
        "totalPressure" => PressureBc::TotalPressure { p0: scalar("p0")? },
        "cyclic" => PressureBc::Cyclic,
        "symmetry" => PressureBc::Symmetry,
        "symmetryPlane" => PressureBc::SymmetryPlane,
        _ => PressureBc::Empty,
    };
    quiet_bookkeeping(d);
    Ok(bc)
}

/// The condition a constraint patch type implies.
fn implied_velocity(kind: PatchType) -> VelocityBc {
    match kind {
        PatchType::Cyclic => VelocityBc::Cyclic,
        PatchType::Empty => VelocityBc::Empty,
        PatchType::Symmetry => VelocityBc::Symmetry,
        _ => VelocityBc::SymmetryPlane,
    }
}

fn implied_pressure(kind: PatchType) -> PressureBc {
    match kind {
        PatchType::Cyclic => PressureBc::Cyclic,
        PatchType::Empty => PressureBc::Empty,
        PatchType::Symmetry => PressureBc::Symmetry,
        _ => PressureBc::SymmetryPlane,
    }
}

/// Entries OpenFOAM writes for its own bookkeeping in boundary conditions (the current patch
/// value, flux and density field names): not worth a note each.
pub(crate) fn quiet_bookkeeping(d: &Dict) {
    for key in ["value", "phi", "rho", "psi", "gamma"] {
        d.lookup(key);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// OpenFOAM's order (`GeometricBoundaryField::readField`): names, then groups (the last
    /// entry first), then patterns; a quoted name is a pattern.
    #[test]
    fn boundary_entries_match_names_then_groups_then_patterns() {
        let mesh = BlockMesh::from_dict(
            &crate::case::parse_dict(
                "vertices ((0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 1) (1 0 1) (1 1 1) (0 1 1));\n\
                 blocks (hex (0 1 2 3 4 5 6 7) (2 2 1) simpleGrading (1 1 1));\n\
                 boundary ( lid { type wall; faces ((3 7 6 2)); }\n\
                 floor { type wall; inGroups (fixedWalls); faces ((0 1 5 4)); }\n\
                 sides { type patch; faces ((0 4 7 3) (1 2 6 5)); } );",
                "system/blockMeshDict",
            )
            .unwrap(),
        )
        .unwrap();
        let field = crate::case::parse_dict(
            "boundaryField {\n\
             \"lid\" { type fixedValue; value uniform (1 0 0); }\n\
             wall { type noSlip; }\n\
             fixedWalls { type slip; }\n\
             \"s.*\" { type zeroGradient; }\n\
             sides { type fixedValue; value uniform (0 0 0); }\n\
             defaultFaces { type empty; } }",
            "0/U",
        )
        .unwrap();
        let mut notes = Vec::new();
        let found = conditions(&field, &mesh, &mut notes).unwrap();
        let kind = |name: &str| {
            let k = mesh.patch_index(name).unwrap();
            found[k].unwrap().get_word("type").unwrap()
        };
        // the quoted "lid" is a pattern: the wall group's entry comes first
        assert_eq!(kind("lid"), "noSlip");
        // of two groups, the last entry in the file
        assert_eq!(kind("floor"), "slip");
        // the name before the pattern that also matches it
        assert_eq!(kind("sides"), "fixedValue");
        assert!(notes.iter().any(|n| n.contains("'lid'")), "{notes:?}");
    }

    #[test]
    fn nonuniform_field_order_and_length() {
        let d = crate::case::parse_dict("internalField nonuniform List<scalar> 3(1 2 3);", "p")
            .unwrap();
        assert_eq!(
            internal(&d, 3, "a number", Item::as_scalar, scalar_row).unwrap(),
            InternalField::Nonuniform(vec![1.0, 2.0, 3.0])
        );
        let e = internal(&d, 4, "a number", Item::as_scalar, scalar_row).unwrap_err();
        assert!(e.message.contains("expected 4 values"), "{e}");
        let d =
            crate::case::parse_dict("internalField nonuniform List<scalar> 2 (1 2);", "p").unwrap();
        assert_eq!(
            internal(&d, 2, "a number", Item::as_scalar, scalar_row).unwrap(),
            InternalField::Nonuniform(vec![1.0, 2.0])
        );
        let d =
            crate::case::parse_dict("internalField nonuniform List<scalar> 3 (1 2);", "p").unwrap();
        let e = internal(&d, 2, "a number", Item::as_scalar, scalar_row).unwrap_err();
        assert_eq!((e.line, e.col), (1, 39), "{e}");
        let d = crate::case::parse_dict("internalField uniform (1 2 x);", "U").unwrap();
        let e = internal(&d, 4, "a vector", Item::as_vector, vector_row).unwrap_err();
        assert_eq!((e.line, e.col), (1, 23));
    }

    #[test]
    fn errors_inside_long_fields_point_at_the_element() {
        // A word at element 1000 of a scalar field.
        let mut text = String::from("internalField nonuniform List<scalar>\n2000\n(\n");
        for i in 0..2000 {
            text.push_str(if i == 1000 { "abc\n" } else { "0.5\n" });
        }
        text.push_str(");\n");
        let d = crate::case::parse_dict(&text, "p").unwrap();
        let e = internal(&d, 2000, "a number", Item::as_scalar, scalar_row).unwrap_err();
        assert_eq!((e.line, e.col), (1004, 1), "{e}");
        assert!(e.message.contains("found the word 'abc'"), "{e}");
        // A packed list of the wrong width: the first row that does not fit, found again.
        let mut text = String::from("internalField nonuniform List<vector> 3((0 0 0) (1 1 1)\n");
        text.push_str("  (2 2));\n");
        let d = crate::case::parse_dict(&text, "U").unwrap();
        let e = internal(&d, 3, "a vector", Item::as_vector, vector_row).unwrap_err();
        assert_eq!((e.line, e.col), (2, 3), "{e}");
        let d = crate::case::parse_dict("internalField nonuniform 3(1 2\n 3);", "U").unwrap();
        let e = internal(&d, 3, "a vector", Item::as_vector, vector_row).unwrap_err();
        assert_eq!((e.line, e.col), (1, 28), "{e}");
        assert!(e.message.contains("found the integer 1"), "{e}");
        let d =
            crate::case::parse_dict("internalField nonuniform 2((1 2 3)\n (4 5 6));", "p").unwrap();
        let e = internal(&d, 2, "a number", Item::as_scalar, scalar_row).unwrap_err();
        assert_eq!((e.line, e.col), (1, 28), "{e}");
        // Packed and right: the values in order.
        let d = crate::case::parse_dict(
            "internalField nonuniform List<vector> 2((1 2 3) (4 5 6));",
            "U",
        )
        .unwrap();
        assert_eq!(
            internal(&d, 2, "a vector", Item::as_vector, vector_row).unwrap(),
            InternalField::Nonuniform(vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]])
        );
    }
}
