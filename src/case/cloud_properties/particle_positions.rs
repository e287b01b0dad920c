//! Where a cloud's particles are: the centres of a positions file (`manualInjection`), or
//! the box a random packing fills (fsim's `randomPacking`).

use std::path::Path;

use crate::case::control_dict::at_value;
use crate::case::dictionary::Dict;
use crate::case::error::CaseError;
use crate::case::source::Location;

/// `box (lo) (hi);` of a random packing, inside the mesh's block.
pub(super) fn read_box(m: &Dict) -> Result<([f64; 3], [f64; 3]), CaseError> {
    let tokens = m.get_tokens("box")?;
    let bad = || {
        at_value(
            m,
            "box",
            "expected two corners (xmin ymin zmin) (xmax ymax zmax) for 'box'".to_string(),
        )
    };
    let [a, b] = tokens else {
        return Err(bad());
    };
    let (lo, hi) = (
        a.as_vector().ok_or_else(bad)?,
        b.as_vector().ok_or_else(bad)?,
    );
    if (0..3).any(|k| hi[k] <= lo[k]) {
        return Err(CaseError::at(
            &b.loc,
            "box: each coordinate of the second corner must exceed the first's",
        ));
    }
    Ok((lo, hi))
}

/// The centres of a positions file, `(x y z)` per particle, each optionally followed by the
/// `cellI tetFace tetPt` labels of some OpenFOAM versions; with the location of each.
pub fn read_positions(
    path: &Path,
    case_dir: &Path,
) -> Result<(Vec<[f64; 3]>, Vec<Location>), CaseError> {
    let d = Dict::read(path, Some(case_dir))?;
    let list = match d.values.as_slice() {
        [item] => item,
        _ => {
            return Err(CaseError::at(
                &d.loc,
                "expected one list of particle positions ( (x y z) … )",
            ))
        }
    };
    // A plain positions file is read packed: one (x y z) per particle, nothing else.
    if let Some((3, data)) = list.as_numbers() {
        let positions = data.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        let locs = (0..data.len() / 3).map(|i| list.loc.child(i)).collect();
        return Ok((positions, locs));
    }
    let Some(items) = list.as_list() else {
        return Err(CaseError::at(
            &list.loc,
            format!(
                "expected a list of particle positions, found {}",
                list.describe()
            ),
        ));
    };
    let mut positions = Vec::with_capacity(items.len());
    let mut locs = Vec::with_capacity(items.len());
    let mut labels_after = usize::MAX;
    for item in items.iter() {
        if let Some(x) = item.as_vector() {
            positions.push(x);
            locs.push(item.loc.clone());
            labels_after = 0;
        } else if item.as_label().is_some() && labels_after < 3 {
            labels_after += 1;
        } else {
            return Err(CaseError::at(
                &item.loc,
                format!(
                    "expected a particle position (x y z), found {}",
                    item.describe()
                ),
            ));
        }
    }
    Ok((positions, locs))
}
