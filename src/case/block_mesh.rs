//! `system/blockMeshDict`: one axis-aligned hex block of uniform cells and the patches on its
//! six faces, turned into a [`Grid`].

use std::borrow::Cow;
use std::fmt;

use super::control_dict::at_value;
use super::dictionary::Dict;
use super::error::CaseError;
use super::source::Location;
use super::value::{Item, ListView};
use crate::grid::Grid;

/// The six faces of the box, in this order everywhere in fsim: x-, x+, y-, y+, z-, z+.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BoxFace {
    XMin,
    XMax,
    YMin,
    YMax,
    ZMin,
    ZMax,
}

impl BoxFace {
    pub const ALL: [BoxFace; 6] = [
        BoxFace::XMin,
        BoxFace::XMax,
        BoxFace::YMin,
        BoxFace::YMax,
        BoxFace::ZMin,
        BoxFace::ZMax,
    ];

    /// Position in [`BoxFace::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// The direction normal to the face (0 = x).
    pub fn axis(self) -> usize {
        self.index() / 2
    }

    /// Whether this is the high side of its axis.
    pub fn is_max(self) -> bool {
        self.index() % 2 == 1
    }

    pub fn opposite(self) -> BoxFace {
        BoxFace::ALL[self.index() ^ 1]
    }

    /// The face's corners in OpenFOAM's local hex numbering, ordered so that the normal
    /// points out of the block.
    fn local_vertices(self) -> [usize; 4] {
        match self {
            BoxFace::XMin => [0, 4, 7, 3],
            BoxFace::XMax => [1, 2, 6, 5],
            BoxFace::YMin => [0, 1, 5, 4],
            BoxFace::YMax => [3, 7, 6, 2],
            BoxFace::ZMin => [0, 3, 2, 1],
            BoxFace::ZMax => [4, 5, 6, 7],
        }
    }
}

impl fmt::Display for BoxFace {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names = ["x-", "x+", "y-", "y+", "z-", "z+"];
        write!(f, "{}", names[self.index()])
    }
}

/// The patch types fsim supports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PatchType {
    Wall,
    Patch,
    Cyclic,
    Symmetry,
    SymmetryPlane,
    Empty,
}

impl PatchType {
    pub const NAMES: [&'static str; 6] = [
        "wall",
        "patch",
        "cyclic",
        "symmetry",
        "symmetryPlane",
        "empty",
    ];

    pub fn parse(word: &str) -> Option<PatchType> {
        Some(match word {
            "wall" => PatchType::Wall,
            "patch" => PatchType::Patch,
            "cyclic" => PatchType::Cyclic,
            "symmetry" => PatchType::Symmetry,
            "symmetryPlane" => PatchType::SymmetryPlane,
            "empty" => PatchType::Empty,
            _ => return None,
        })
    }

    pub fn name(self) -> &'static str {
        match self {
            PatchType::Wall => "wall",
            PatchType::Patch => "patch",
            PatchType::Cyclic => "cyclic",
            PatchType::Symmetry => "symmetry",
            PatchType::SymmetryPlane => "symmetryPlane",
            PatchType::Empty => "empty",
        }
    }

    /// Whether a field boundary condition is implied by the patch (constraint types).
    pub fn is_constraint(self) -> bool {
        !matches!(self, PatchType::Wall | PatchType::Patch)
    }
}

/// A named patch covering some of the box faces.
#[derive(Clone, Debug)]
pub struct Patch {
    pub name: String,
    pub kind: PatchType,
    /// The box faces it covers (possibly none).
    pub faces: Vec<BoxFace>,
    /// For a cyclic patch: the patch on the opposite faces (itself when it covers both).
    pub neighbour: Option<String>,
    /// The patch groups it belongs to, as OpenFOAM has them: its `inGroups`, then its type's
    /// own group (every type but `patch`: `wall`, `cyclic`, `empty`, `symmetry`, …).
    pub groups: Vec<String>,
    /// Where the patch is defined.
    pub loc: Location,
}

/// The typed `system/blockMeshDict`.
#[derive(Clone, Debug)]
pub struct BlockMesh {
    pub grid: Grid,
    pub patches: Vec<Patch>,
    /// For each face in [`BoxFace::ALL`] order, the index of its patch in `patches`.
    pub face_patch: [usize; 6],
}

/// `inGroups (a b);` (also `List<word> 2(a b)`): the groups a patch is put in.
fn in_groups(pd: &Dict) -> Result<Vec<String>, CaseError> {
    if pd.lookup("inGroups").is_none() {
        return Ok(Vec::new());
    }
    let tokens = pd.get_tokens("inGroups")?;
    let list = tokens.last().and_then(|t| t.as_list()).ok_or_else(|| {
        at_value(
            pd,
            "inGroups",
            "expected a list of group names, as (wall)".to_string(),
        )
    })?;
    list.iter()
        .map(|item| {
            item.as_word().map(str::to_string).ok_or_else(|| {
                CaseError::at(
                    &item.loc,
                    format!("expected a group name, found {}", item.describe()),
                )
            })
        })
        .collect()
}

/// A patch's groups: those it was put in, then its type's own (OpenFOAM's `polyPatch` adds
/// the type to `inGroups` for every type but `patch`).
pub(crate) fn groups_of(kind: PatchType, mut groups: Vec<String>) -> Vec<String> {
    if kind != PatchType::Patch && !groups.iter().any(|g| g == kind.name()) {
        groups.push(kind.name().to_string());
    }
    groups
}

impl BlockMesh {
    /// The patch on a box face.
    pub fn patch_on(&self, face: BoxFace) -> &Patch {
        &self.patches[self.face_patch[face.index()]]
    }

    /// Index of the patch named `name`.
    pub fn patch_index(&self, name: &str) -> Option<usize> {
        self.patches.iter().position(|p| p.name == name)
    }

    /// Whether direction `axis` is periodic (cyclic on both faces).
    pub fn is_periodic(&self, axis: usize) -> bool {
        self.patch_on(BoxFace::ALL[2 * axis]).kind == PatchType::Cyclic
    }

    /// Whether the case is two-dimensional along `axis` (`empty` on both faces: OpenFOAM
    /// solves in the other directions only).
    pub fn is_planar(&self, axis: usize) -> bool {
        (0..2).all(|side| self.patch_on(BoxFace::ALL[2 * axis + side]).kind == PatchType::Empty)
    }

    /// Reads and validates the dictionary.
    pub fn from_dict(d: &Dict) -> Result<BlockMesh, CaseError> {
        // settings that move or rescale OpenFOAM's points: ignoring them would build
        // another box
        for (keyword, what) in [
            ("prescale", "a scaling before the transform"),
            ("transform", "a rotation or translation of the points"),
            ("units", "the vertices' unit"),
        ] {
            if d.contains(keyword) {
                return Err(at_value(
                    d,
                    keyword,
                    format!(
                        "'{keyword}' ({what}) is not supported by fsim: give the vertices \
                         in place, scaled by 'scale' or 'convertToMeters' only"
                    ),
                ));
            }
        }
        if d.contains("boundary") && d.contains("patches") {
            return Err(at_value(
                d,
                "patches",
                "both 'boundary' and the old 'patches': OpenFOAM reads 'patches' and ignores \
                 'boundary'; keep one"
                    .to_string(),
            ));
        }
        let scale = match (d.opt_scalar("scale")?, d.opt_scalar("convertToMeters")?) {
            (Some(s), _) => ("scale", s),
            (None, Some(s)) => ("convertToMeters", s),
            (None, None) => ("scale", 1.0),
        };
        if scale.1.is_nan() || scale.1 <= 0.0 {
            return Err(at_value(
                d,
                scale.0,
                format!(
                    "expected a positive factor for '{}', found {}",
                    scale.0, scale.1
                ),
            ));
        }
        let scale = scale.1;
        let vertices = read_vertices(d)?;
        let block = read_block(d, vertices.len())?;
        let corners: Vec<[f64; 3]> = block
            .labels
            .iter()
            .map(|&l| vertices[l].map(|x| x * scale))
            .collect();
        let (lo, hi) = check_box(&corners, &block)?;
        for keyword in ["edges", "mergePatchPairs"] {
            if let Some(e) = d.lookup(keyword) {
                let non_empty = e
                    .as_tokens()
                    .is_some_and(|t| t.iter().any(|i| i.as_list().is_none_or(|l| !l.is_empty())));
                if non_empty {
                    let what = if keyword == "edges" {
                        "curved edges"
                    } else {
                        "merged patch pairs"
                    };
                    return Err(CaseError::at(
                        e.value_loc(),
                        format!(
                            "expected an empty '{keyword}' list: fsim has one box block, no {what}"
                        ),
                    ));
                }
            }
        }
        let n = block.cells;
        let grid = Grid::new(n, [0, 1, 2].map(|a| (hi[a] - lo[a]) / n[a] as f64), lo);
        let (patches, face_patch) = read_patches(d, &block)?;
        let mesh = BlockMesh {
            grid,
            patches,
            face_patch,
        };
        mesh.check_patches(d)?;
        Ok(mesh)
    }

    fn check_patches(&self, d: &Dict) -> Result<(), CaseError> {
        for p in &self.patches {
            match p.kind {
                PatchType::Empty => {
                    for &f in &p.faces {
                        let cells = self.grid.n[f.axis()];
                        let axis = ["x", "y", "z"][f.axis()];
                        if cells != 1 {
                            let why = if p.name == "defaultFaces" {
                                "faces not listed in any patch go to 'defaultFaces' of type \
                                 empty (as in blockMesh), so "
                            } else {
                                ""
                            };
                            return Err(CaseError::at(
                                &p.loc,
                                format!(
                                    "{why}expected 1 cell in {axis} under the empty patch '{}' \
                                     (face {f}), found {cells} cells",
                                    p.name
                                ),
                            ));
                        }
                        if self.patch_on(f.opposite()).kind != PatchType::Empty {
                            return Err(CaseError::at(
                                &p.loc,
                                format!(
                                    "expected face {} to be empty too, opposite the empty face {f} \
                                     of patch '{}'",
                                    f.opposite(),
                                    p.name
                                ),
                            ));
                        }
                    }
                }
                PatchType::Cyclic => self.check_cyclic(p, d)?,
                _ => {}
            }
        }
        Ok(())
    }

    fn check_cyclic(&self, p: &Patch, d: &Dict) -> Result<(), CaseError> {
        let Some(neighbour) = &p.neighbour else {
            return Err(CaseError::at(
                &p.loc,
                format!(
                    "missing keyword 'neighbourPatch' for the cyclic patch '{}'",
                    p.name
                ),
            ));
        };
        let Some(other) = self.patches.iter().find(|q| &q.name == neighbour) else {
            return Err(CaseError::at(
                &p.loc,
                format!(
                    "cyclic patch '{}' names neighbourPatch '{neighbour}', which is not a patch \
                     of {}",
                    p.name,
                    d.file()
                ),
            ));
        };
        if other.kind != PatchType::Cyclic {
            return Err(CaseError::at(
                &p.loc,
                format!(
                    "expected neighbourPatch '{neighbour}' of cyclic patch '{}' to be cyclic too, \
                     found type {}",
                    p.name,
                    other.kind.name()
                ),
            ));
        }
        if p.faces.is_empty() {
            return Err(CaseError::at(
                &p.loc,
                format!(
                    "expected cyclic patch '{}' to cover a face of the block",
                    p.name
                ),
            ));
        }
        let mut wanted: Vec<BoxFace> = p.faces.iter().map(|f| f.opposite()).collect();
        let mut have = other.faces.clone();
        if other.name == p.name {
            // One patch on both faces: it must be closed under "opposite".
            wanted.extend(p.faces.iter().copied());
            have.extend(p.faces.iter().copied());
        }
        wanted.sort_by_key(|f| f.index());
        wanted.dedup();
        have.sort_by_key(|f| f.index());
        have.dedup();
        if wanted != have {
            let faces = |fs: &[BoxFace]| {
                fs.iter()
                    .map(|f| f.to_string())
                    .collect::<Vec<_>>()
                    .join(" ")
            };
            return Err(CaseError::at(
                &p.loc,
                format!(
                    "expected cyclic patch '{}' (faces {}) and its neighbour '{neighbour}' (faces {}) \
                     on opposite faces of the block",
                    p.name,
                    faces(&p.faces),
                    faces(&other.faces)
                ),
            ));
        }
        Ok(())
    }
}

/// The one hex block: its 8 vertex labels, cell counts and where it was written.
struct Block {
    labels: [usize; 8],
    cells: [usize; 3],
    loc: Location,
    labels_loc: Location,
}

fn list_of<'a>(item: &'a Item, what: &str, keyword: &str) -> Result<ListView<'a>, CaseError> {
    item.as_list().ok_or_else(|| {
        CaseError::at(
            &item.loc,
            format!("expected {what} in '{keyword}', found {}", item.describe()),
        )
    })
}

fn the_list<'a>(d: &'a Dict, keyword: &str) -> Result<ListView<'a>, CaseError> {
    let tokens = d.get_tokens(keyword)?;
    match tokens {
        [item] => list_of(item, "a list ( … )", keyword),
        [] => Err(d.missing(keyword)),
        [_, extra, ..] => Err(CaseError::at(
            &extra.loc,
            format!(
                "expected ';' to end the entry '{keyword}' after its list, found {}",
                extra.describe()
            ),
        )),
    }
}

fn read_vertices(d: &Dict) -> Result<Vec<[f64; 3]>, CaseError> {
    let list = the_list(d, "vertices")?;
    list.iter()
        .map(|item| {
            item.as_vector().ok_or_else(|| {
                let inner = item
                    .as_list()
                    .and_then(|l| l.iter().find(|x| x.as_scalar().is_none()));
                match inner {
                    Some(bad) => CaseError::at(
                        &bad.loc,
                        format!(
                            "expected a number in vertex coordinates, found {}",
                            bad.describe()
                        ),
                    ),
                    None => CaseError::at(
                        &item.loc,
                        format!(
                            "expected a vertex (x y z) in 'vertices', found {}",
                            item.describe()
                        ),
                    ),
                }
            })
        })
        .collect()
}

fn read_block(d: &Dict, vertex_count: usize) -> Result<Block, CaseError> {
    let list = the_list(d, "blocks")?;
    let items: Vec<Cow<Item>> = list.iter().collect();
    let Some(first) = items.first() else {
        return Err(at_value(
            d,
            "blocks",
            "expected one hex block in 'blocks', found an empty list".to_string(),
        ));
    };
    if first.as_word() != Some("hex") {
        return Err(CaseError::at(
            &first.loc,
            format!(
                "expected 'hex' to start the block, found {}",
                first.describe()
            ),
        ));
    }
    let mut k = 1;
    let next = |k: usize, what: &str| -> Result<&Item, CaseError> {
        items.get(k).map(|c| &**c).ok_or_else(|| {
            let last = &items[k - 1];
            CaseError::at(
                &last.loc,
                format!("expected {what} after {} in the hex block", last.describe()),
            )
        })
    };
    let labels_item = next(k, "the 8 vertex labels (0 1 2 3 4 5 6 7)")?;
    let labels_list = list_of(labels_item, "the 8 vertex labels of the hex", "blocks")?;
    if labels_list.len() != 8 {
        return Err(CaseError::at(
            &labels_item.loc,
            format!(
                "expected 8 vertex labels for a hex, found {}",
                labels_list.len()
            ),
        ));
    }
    let mut labels = [0usize; 8];
    for (slot, item) in labels.iter_mut().zip(labels_list.iter()) {
        *slot = match item.as_label() {
            Some(l) if l >= 0 && (l as usize) < vertex_count => l as usize,
            _ => {
                return Err(CaseError::at(
                    &item.loc,
                    format!(
                        "expected a vertex label from 0 to {}, found {}",
                        vertex_count.saturating_sub(1),
                        item.describe()
                    ),
                ))
            }
        };
    }
    k += 1;
    // An optional zone name stands between the labels and the cell counts.
    if next(k, "the cell counts (nx ny nz)")?.as_word().is_some() {
        k += 1;
    }
    let cells_item = next(k, "the cell counts (nx ny nz)")?;
    let cells_list = list_of(cells_item, "the cell counts (nx ny nz)", "blocks")?;
    if cells_list.len() != 3 {
        return Err(CaseError::at(
            &cells_item.loc,
            format!(
                "expected 3 cell counts (nx ny nz), found {}",
                cells_list.len()
            ),
        ));
    }
    let mut cells = [0usize; 3];
    for (slot, item) in cells.iter_mut().zip(cells_list.iter()) {
        *slot = match item.as_label() {
            Some(n) if n >= 1 => n as usize,
            _ => {
                return Err(CaseError::at(
                    &item.loc,
                    format!(
                        "expected a cell count of at least 1, found {}",
                        item.describe()
                    ),
                ))
            }
        };
    }
    check_cell_count(cells, &cells_item.loc)?;
    k += 1;
    let grading_word = next(k, "simpleGrading (1 1 1)")?;
    let expected_len = match grading_word.as_word() {
        Some("simpleGrading") => 3,
        Some("edgeGrading") => 12,
        _ => {
            return Err(CaseError::at(
                &grading_word.loc,
                format!(
                    "expected simpleGrading (1 1 1), found {}",
                    grading_word.describe()
                ),
            ))
        }
    };
    k += 1;
    let grading = next(k, "the grading (1 1 1)")?;
    let grading_list = list_of(grading, "the grading ( … )", "blocks")?;
    let uniform = grading_list.len() == expected_len
        && grading_list
            .iter()
            .all(|g| g.as_scalar().is_some_and(|x| (x - 1.0).abs() <= 1e-12));
    if !uniform {
        return Err(CaseError::at(
            &grading.loc,
            format!(
                "fsim needs uniform cells: expected {} (1 1 1{}), found {grading}",
                grading_word,
                if expected_len == 12 {
                    " 1 1 1 1 1 1 1 1 1"
                } else {
                    ""
                }
            ),
        ));
    }
    k += 1;
    if let Some(extra) = items.get(k) {
        let message = if extra.as_word() == Some("hex") {
            "expected exactly one hex block: fsim runs on a single box, found a second block"
                .to_string()
        } else {
            format!(
                "expected the end of the block list, found {}",
                extra.describe()
            )
        };
        return Err(CaseError::at(&extra.loc, message));
    }
    Ok(Block {
        labels,
        cells,
        loc: first.loc.clone(),
        labels_loc: labels_item.loc.clone(),
    })
}

/// Most cells a block may have, ghost layers included (10¹²).
///
/// The product of the counts, and every array index the solvers derive from it (ghost
/// layers, faces), is then computed without overflow; the memory such a grid needs is checked
/// against what the machine has later (src/memory.rs), with the whole model known.
pub const MAX_CELLS: u128 = 1_000_000_000_000;

/// Refuses cell counts whose product, with a ghost layer on each side, exceeds
/// [`MAX_CELLS`]: an overflowing product would otherwise make a small or absurd grid.
fn check_cell_count(cells: [usize; 3], loc: &Location) -> Result<(), CaseError> {
    let padded = cells
        .iter()
        .map(|&n| n as u128 + 2)
        .fold(1u128, u128::saturating_mul);
    if padded > MAX_CELLS {
        let product = cells
            .iter()
            .map(|&n| n as u128)
            .fold(1u128, u128::saturating_mul);
        return Err(CaseError::at(
            loc,
            format!(
                "cell counts ({} {} {}) make {:.3e} cells, more than fsim's limit of \
                 {:.0e} (with ghost layers): use fewer cells",
                cells[0], cells[1], cells[2], product as f64, MAX_CELLS as f64
            ),
        ));
    }
    Ok(())
}

/// Checks that the block's corners form an axis-aligned box in OpenFOAM's vertex order and
/// returns its lowest and highest corners.
fn check_box(c: &[[f64; 3]], block: &Block) -> Result<([f64; 3], [f64; 3]), CaseError> {
    let lo = c[0];
    let hi = c[6];
    let extent = (0..3).map(|a| (hi[a] - lo[a]).abs()).fold(0.0, f64::max);
    let tol = 1e-9 * extent.max(f64::MIN_POSITIVE);
    for a in 0..3 {
        if hi[a] - lo[a] <= tol || hi[a].is_nan() || lo[a].is_nan() {
            return Err(CaseError::at(
                &block.labels_loc,
                format!(
                    "expected the hex vertices to form a box with v6 above v0 in x, y and z \
                     (OpenFOAM's order: v1 along +x, v3 along +y, v4 along +z), found v0 = {} and v6 = {}",
                    show(lo),
                    show(hi)
                ),
            ));
        }
    }
    for (k, corner) in c.iter().enumerate() {
        // Local vertex k sits at the high side of x for 1, 2, 5, 6; of y for 2, 3, 6, 7; of z
        // for 4..7.
        let high = [
            matches!(k, 1 | 2 | 5 | 6),
            matches!(k, 2 | 3 | 6 | 7),
            k >= 4,
        ];
        let want: [f64; 3] = [0, 1, 2].map(|a| if high[a] { hi[a] } else { lo[a] });
        if (0..3).any(|a| (corner[a] - want[a]).abs() > tol) {
            return Err(CaseError::at(
                &block.labels_loc,
                format!(
                    "expected the hex vertices to form an axis-aligned box in OpenFOAM's order: \
                     vertex {} (position {k} in the hex) is at {}, expected {}",
                    block.labels[k],
                    show(*corner),
                    show(want)
                ),
            ));
        }
    }
    let _ = &block.loc;
    Ok((lo, hi))
}

fn show(p: [f64; 3]) -> String {
    format!("({} {} {})", p[0], p[1], p[2])
}

/// Which box face a quad of vertex labels is.
fn match_face(quad: &Item, block: &Block) -> Result<BoxFace, CaseError> {
    let list = quad.as_list().filter(|l| l.len() == 4).ok_or_else(|| {
        CaseError::at(
            &quad.loc,
            format!(
                "expected a face of 4 vertex labels (a b c d), found {}",
                quad.describe()
            ),
        )
    })?;
    let mut labels = Vec::with_capacity(4);
    for item in list.iter() {
        match item.as_label() {
            Some(l) if l >= 0 => labels.push(l as usize),
            _ => {
                return Err(CaseError::at(
                    &item.loc,
                    format!("expected a vertex label, found {}", item.describe()),
                ))
            }
        }
    }
    labels.sort_unstable();
    for face in BoxFace::ALL {
        let mut own: Vec<usize> = face
            .local_vertices()
            .iter()
            .map(|&k| block.labels[k])
            .collect();
        own.sort_unstable();
        if own == labels {
            return Ok(face);
        }
    }
    Err(CaseError::at(
        &quad.loc,
        format!(
            "expected a face of the hex block, found {quad}, which is not one of its six faces"
        ),
    ))
}

/// Patches from `boundary` (current form) or `patches` (older form), plus `defaultFaces`.
fn read_patches(d: &Dict, block: &Block) -> Result<(Vec<Patch>, [usize; 6]), CaseError> {
    let mut patches: Vec<Patch> = Vec::new();
    let mut owner: [Option<usize>; 6] = [None; 6];
    let assign = |patches: &mut Vec<Patch>,
                  owner: &mut [Option<usize>; 6],
                  p: Patch,
                  quads: Vec<&Item>|
     -> Result<(), CaseError> {
        if let Some(prev) = patches.iter().find(|q| q.name == p.name) {
            return Err(CaseError::at(
                &p.loc,
                format!(
                    "expected each patch name once, found '{}' again (first at {})",
                    p.name,
                    prev.loc.describe()
                ),
            ));
        }
        let index = patches.len();
        let mut p = p;
        for quad in quads {
            let face = match_face(quad, block)?;
            if let Some(other) = owner[face.index()] {
                return Err(CaseError::at(
                    &quad.loc,
                    format!(
                        "expected each block face in one patch, found face {face} already in patch '{}'",
                        patches.get(other).map_or(p.name.as_str(), |q| q.name.as_str())
                    ),
                ));
            }
            owner[face.index()] = Some(index);
            p.faces.push(face);
        }
        patches.push(p);
        Ok(())
    };
    let patch_type = |item: &Item| -> Result<PatchType, CaseError> {
        item.as_word().and_then(PatchType::parse).ok_or_else(|| {
            CaseError::at(
                &item.loc,
                format!(
                    "expected a patch type ({}), found {}",
                    PatchType::NAMES.join(", "),
                    item.describe()
                ),
            )
        })
    };
    let quads_of = |item: &Item, name: &str| -> Result<Vec<Item>, CaseError> {
        let list = item.as_list().ok_or_else(|| {
            CaseError::at(
                &item.loc,
                format!(
                    "expected the faces of patch '{name}' as a list ( (a b c d) … ), found {}",
                    item.describe()
                ),
            )
        })?;
        Ok(list.iter().map(Cow::into_owned).collect())
    };
    if d.contains("boundary") {
        let list = the_list(d, "boundary")?;
        let items: Vec<Cow<Item>> = list.iter().collect();
        let mut k = 0;
        while k < items.len() {
            let name_item = &items[k];
            let name = name_item.as_word().ok_or_else(|| {
                CaseError::at(
                    &name_item.loc,
                    format!(
                        "expected a patch name followed by {{ … }}, found {}",
                        name_item.describe()
                    ),
                )
            })?;
            let Some(pd) = items.get(k + 1).and_then(|i| i.as_dict()) else {
                return Err(CaseError::at(
                    &name_item.loc,
                    format!("expected a dictionary {{ type …; faces …; }} after the patch name '{name}'"),
                ));
            };
            let type_entry = pd.get_entry("type")?;
            let kind = patch_type(super::dictionary::single_token(type_entry, "a patch type")?)?;
            let quads = match pd.lookup("faces") {
                Some(_) => {
                    let tokens = pd.get_tokens("faces")?;
                    match tokens {
                        [item] => quads_of(item, name)?,
                        _ => return Err(pd.missing("faces")),
                    }
                }
                None => Vec::new(),
            };
            let neighbour = if kind == PatchType::Cyclic {
                pd.opt_word("neighbourPatch")?
            } else {
                None
            };
            if neighbour.as_deref() == Some(name) {
                // OpenFOAM's cyclicPolyPatch stops on it too
                return Err(at_value(
                    pd,
                    "neighbourPatch",
                    format!(
                        "cyclic patch '{name}' names itself as neighbourPatch: give each side \
                         its own patch, each naming the other"
                    ),
                ));
            }
            // Transform settings do not change fsim's patches.
            for quiet in ["transform", "matchTolerance"] {
                pd.lookup(quiet);
            }
            let p = Patch {
                name: name.to_string(),
                kind,
                faces: Vec::new(),
                neighbour,
                groups: groups_of(kind, in_groups(pd)?),
                loc: name_item.loc.clone(),
            };
            assign(&mut patches, &mut owner, p, quads.iter().collect())?;
            k += 2;
        }
    } else if d.contains("patches") {
        let list = the_list(d, "patches")?;
        let items: Vec<Cow<Item>> = list.iter().collect();
        for chunk in items.chunks(3) {
            let kind = patch_type(&chunk[0])?;
            let name_item = chunk.get(1).map(|c| &**c).ok_or_else(|| {
                CaseError::at(&chunk[0].loc, "expected a patch name after the patch type")
            })?;
            let name = name_item.as_word().ok_or_else(|| {
                CaseError::at(
                    &name_item.loc,
                    format!("expected a patch name, found {}", name_item.describe()),
                )
            })?;
            let faces_item = chunk.get(2).map(|c| &**c).ok_or_else(|| {
                CaseError::at(
                    &name_item.loc,
                    format!("expected the faces of patch '{name}' after its name"),
                )
            })?;
            let quads = quads_of(faces_item, name)?;
            let p = Patch {
                name: name.to_string(),
                kind,
                faces: Vec::new(),
                // The old form has no neighbour keyword: a cyclic patch holds both faces.
                neighbour: (kind == PatchType::Cyclic).then(|| name.to_string()),
                groups: groups_of(kind, Vec::new()),
                loc: name_item.loc.clone(),
            };
            assign(&mut patches, &mut owner, p, quads.iter().collect())?;
        }
    }
    if owner.iter().any(Option::is_none) {
        // blockMesh puts unlisted faces in `defaultFaces` of type `empty`, unless
        // `defaultPatch { name …; type …; }` says otherwise.
        let (name, kind, loc) = match d.opt_dict("defaultPatch")? {
            Some(dp) => {
                let name = dp.get_word_or("name", "defaultFaces")?;
                let kind = patch_type(super::dictionary::single_token(
                    dp.get_entry("type")?,
                    "a patch type",
                )?)?;
                (name, kind, dp.loc.clone())
            }
            None => {
                let loc = d
                    .peek("boundary")
                    .or_else(|| d.peek("patches"))
                    .or_else(|| d.peek("blocks"))
                    .map_or(d.loc.clone(), |e| e.key_loc.clone());
                ("defaultFaces".to_string(), PatchType::Empty, loc)
            }
        };
        let index = patches.len();
        let mut p = Patch {
            name,
            kind,
            faces: Vec::new(),
            neighbour: None,
            groups: groups_of(kind, Vec::new()),
            loc,
        };
        for face in BoxFace::ALL {
            if owner[face.index()].is_none() {
                owner[face.index()] = Some(index);
                p.faces.push(face);
            }
        }
        patches.push(p);
    }
    let face_patch = owner.map(|o| o.expect("every face assigned above"));
    Ok((patches, face_patch))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::parse_dict;

    const BOX: &str =
        "scale 0.5;\nvertices ((0 0 0) (2 0 0) (2 1 0) (0 1 0) (0 0 4) (2 0 4) (2 1 4) (0 1 4));\n\
                       blocks (hex (0 1 2 3 4 5 6 7) (4 2 1) simpleGrading (1 1 1));\n";

    fn mesh(extra: &str) -> Result<BlockMesh, CaseError> {
        BlockMesh::from_dict(&parse_dict(&format!("{BOX}{extra}"), "system/blockMeshDict").unwrap())
    }

    #[test]
    fn box_gives_grid_and_default_empty_faces() {
        let m = mesh(
            "boundary ( left { type cyclic; neighbourPatch right; faces ((0 4 7 3)); }\n\
             right { type cyclic; neighbourPatch left; faces ((1 2 6 5)); }\n\
             walls { type wall; faces ((0 1 5 4) (3 7 6 2)); } );",
        )
        .unwrap();
        assert_eq!(m.grid.n, [4, 2, 1]);
        assert_eq!(m.grid.h, [0.25, 0.25, 2.0]);
        assert_eq!(m.grid.origin, [0.0; 3]);
        assert_eq!(m.patch_on(BoxFace::XMax).name, "right");
        assert_eq!(m.patch_on(BoxFace::YMax).name, "walls");
        assert_eq!(m.patch_on(BoxFace::ZMin).name, "defaultFaces");
        assert_eq!(m.patch_on(BoxFace::ZMax).kind, PatchType::Empty);
        assert!(m.is_periodic(0));
        assert!(!m.is_periodic(1));
    }

    #[test]
    fn patches_join_their_in_groups_and_their_types_group() {
        let m = mesh(
            "boundary ( lid { type patch; inGroups (movingWalls wall); faces ((3 7 6 2)); }\n\
             floor { type wall; inGroups List<word> 1(fixed); faces ((0 1 5 4)); }\n\
             sides { type symmetry; faces ((0 4 7 3) (1 2 6 5)); } );",
        )
        .unwrap();
        let groups = |name: &str| m.patches[m.patch_index(name).unwrap()].groups.clone();
        assert_eq!(groups("lid"), ["movingWalls", "wall"]);
        assert_eq!(groups("floor"), ["fixed", "wall"]);
        assert_eq!(groups("sides"), ["symmetry"]);
        assert_eq!(groups("defaultFaces"), ["empty"]);
        let e =
            mesh("boundary ( lid { type patch; inGroups (3); faces ((3 7 6 2)); } );").unwrap_err();
        assert!(e.message.contains("expected a group name"), "{}", e.message);
    }

    #[test]
    fn point_transforms_both_patch_lists_and_a_self_neighbour_are_refused() {
        for (extra, words) in [
            ("prescale 0.001;", "'prescale' (a scaling before the transform)"),
            (
                "transform { type translation; translation (1 0 0); }",
                "'transform' (a rotation or translation of the points)",
            ),
            ("units mm;", "'units' (the vertices' unit)"),
            (
                "boundary ( per { type cyclic; neighbourPatch per; faces ((0 4 7 3) (1 2 6 5)); } );",
                "cyclic patch 'per' names itself as neighbourPatch",
            ),
            (
                "boundary ( w { type wall; faces ((0 1 5 4)); } );\npatches ( wall w2 ((3 7 6 2)) );",
                "OpenFOAM reads 'patches' and ignores 'boundary'",
            ),
        ] {
            let e = mesh(extra).unwrap_err();
            assert!(e.message.contains(words), "{extra}: {}", e.message);
            assert!(e.line >= 4, "{extra}: at the keyword's value, line {}", e.line);
        }
    }

    #[test]
    fn old_patches_form_and_errors() {
        let m = mesh("patches ( cyclic per ((0 4 7 3) (1 2 6 5)) wall w ((0 1 5 4)) patch top ((3 7 6 2)) );")
            .unwrap();
        assert_eq!(m.patch_on(BoxFace::XMin).name, "per");
        assert_eq!(m.patch_on(BoxFace::YMax).kind, PatchType::Patch);
        // Default faces are empty; fine since nz = 1.
        let e = mesh("patches ( cyclic per ((0 4 7 3)) );").unwrap_err();
        assert!(e.message.contains("opposite faces"), "{e}");
        let e = mesh("boundary ( a { type wall; faces ((0 1 2 4)); } );").unwrap_err();
        assert!(e.message.contains("not one of its six faces"), "{e}");
        // Default empty faces on a direction with 4 cells are refused.
        let e = mesh("boundary ( a { type wall; faces ((0 3 2 1) (4 5 6 7)); } );").unwrap_err();
        assert!(e.message.contains("expected 1 cell in x"), "{e}");
    }
}
