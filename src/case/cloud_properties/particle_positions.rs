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

/// Bytes reading takes per particle: the packed numbers and the positions (24 bytes each),
/// and a source location kept twice (48 bytes each), for the errors that name a particle.
const READ_BYTES_PER_PARTICLE: f64 = 144.0;

/// Refuses (exit 2) a positions file whose declared particle count (OpenFOAM's count line
/// before the list) would not fit in memory, before its text is read: the text, what reading
/// keeps per particle and the DEM's arrays ([`crate::memory::BYTES_PER_PARTICLE`]). A file of
/// 10⁷ particles is then refused in milliseconds under a 1 GB limit, not aborted half-read.
fn check_declared_size(path: &Path, case_dir: &Path) -> Result<(), CaseError> {
    let Some((head, size)) = crate::case::bounded_read::read_head(path, 1 << 16) else {
        return Ok(());
    };
    // A count the text cannot hold (each `(x y z)` takes 7 bytes at least) is the parser's
    // to report as a count that does not match its list.
    let Some(count) = declared_count(&head).filter(|&n| n.saturating_mul(7) <= size) else {
        return Ok(());
    };
    let bytes =
        size as f64 + count as f64 * (READ_BYTES_PER_PARTICLE + crate::memory::BYTES_PER_PARTICLE);
    let shown = path
        .strip_prefix(case_dir)
        .unwrap_or(path)
        .display()
        .to_string();
    crate::memory::shortfall(bytes, &format!("{count} particles"))
        .map_or(Ok(()), |message| Err(CaseError::in_file(shown, message)))
}

/// The count line of an OpenFOAM list file: the first token after the `FoamFile` header
/// (comments skipped) when it is an integer followed by `(`.
fn declared_count(head: &[u8]) -> Option<u64> {
    let text = String::from_utf8_lossy(head);
    let mut rest: &str = &text;
    let mut depth = 0usize;
    loop {
        rest = rest.trim_start();
        if rest.is_empty() {
            return None;
        } else if let Some(r) = rest.strip_prefix("//") {
            rest = r.split_once('\n')?.1;
        } else if let Some(r) = rest.strip_prefix("/*") {
            rest = r.split_once("*/")?.1;
        } else if let Some(r) = rest.strip_prefix('{') {
            depth += 1;
            rest = r;
        } else if let Some(r) = rest.strip_prefix('}') {
            depth = depth.checked_sub(1)?;
            rest = r;
        } else if depth > 0 || rest.starts_with("FoamFile") {
            let end = rest.find(|c: char| c.is_whitespace() || "{}/".contains(c));
            rest = &rest[end.unwrap_or(rest.len()).max(1)..];
        } else {
            let digits = rest.find(|c: char| !c.is_ascii_digit())?;
            let count = rest[..digits].parse().ok()?;
            return rest[digits..]
                .trim_start()
                .starts_with('(')
                .then_some(count);
        }
    }
}

/// The centres of a positions file, `(x y z)` per particle, each optionally followed by the
/// `cellI tetFace tetPt` labels of some OpenFOAM versions; with the location of each.
pub fn read_positions(
    path: &Path,
    case_dir: &Path,
) -> Result<(Vec<[f64; 3]>, Vec<Location>), CaseError> {
    check_declared_size(path, case_dir)?;
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

#[cfg(test)]
mod tests {
    use super::declared_count;

    #[test]
    fn the_count_line_is_found_after_header_and_comments() {
        let text = "/* banner */\nFoamFile\n{\n    version 2.0; // v\n    object positions;\n}\n\
                    // a comment\n10000000\n(\n(0 0 0)\n";
        assert_eq!(declared_count(text.as_bytes()), Some(10_000_000));
        assert_eq!(declared_count(b"FoamFile { a b; }\n3 ( (0 0 0)"), Some(3));
        // no count, or a count not followed by a list: none
        assert_eq!(declared_count(b"FoamFile { a b; }\n( (0 0 0) )"), None);
        assert_eq!(declared_count(b"FoamFile { a b; }\n12 13"), None);
        // a header cut off by the window: none
        assert_eq!(declared_count(b"FoamFile { a b;"), None);
    }
}
