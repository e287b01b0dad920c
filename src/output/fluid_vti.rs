//! The fluid on the grid as a VTK XML ImageData file (`.vti`) with raw appended `f64` cell
//! data: the file the collection (`.pvd`) lists, because ParaView's collection reader (5.11,
//! VTK 9.2, as Debian ships it) opens XML files only, and crashes on a legacy `.vtk` entry.
//! meshio does not read `.vti`; it reads the legacy twin written beside it
//! ([`super::write_fluid_vtk`]).
//!
//! Written directly rather than with vtkio: vtkio writes inline base64 only (several times
//! slower than raw bytes: docs/benchmarks/output.md) and keeps origin and spacing as `f32`.
//!
//! Layout: an XML header whose `DataArray`s point (`offset`) into the `<AppendedData
//! encoding="raw">` block after `_`; each array there is a `UInt64` byte count followed by its
//! values, little-endian (`byte_order="LittleEndian"`, `header_type="UInt64"`).

use super::fluid_vtk::{validate_cell_data, CellData};
use super::output_error::OutputError;
use super::safe_dir::SafeDir;
use crate::grid::Grid;
use std::io::{BufWriter, Write};

/// Writes `fields` on `grid` to file `name` of `dir` (conventionally `<time>/fluid.vti`). Same
/// arguments and same cell order as [`super::write_fluid_vtk`].
pub fn write_fluid_vti(
    dir: &SafeDir,
    name: &str,
    grid: &Grid,
    fields: &[CellData],
) -> Result<(), OutputError> {
    let path = &dir.join(name);
    validate_cell_data(path, grid, fields)?;
    let [nx, ny, nz] = grid.n;
    let [ox, oy, oz] = grid.origin;
    let [hx, hy, hz] = grid.h;
    let extent = format!("0 {nx} 0 {ny} 0 {nz}");
    let first = |vector: bool| {
        fields
            .iter()
            .find(|f| (f.components() == 3) == vector)
            .map(|f| f.name().to_string())
    };
    let mut active = String::new();
    if let Some(name) = first(false) {
        active.push_str(&format!(" Scalars=\"{name}\""));
    }
    if let Some(name) = first(true) {
        active.push_str(&format!(" Vectors=\"{name}\""));
    }
    // `{}` prints the shortest decimal that reads back as the same f64.
    let mut header = format!(
        "<?xml version=\"1.0\"?>\n\
         <VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n\
         \x20 <ImageData WholeExtent=\"{extent}\" Origin=\"{ox} {oy} {oz}\" Spacing=\"{hx} {hy} {hz}\">\n\
         \x20   <Piece Extent=\"{extent}\">\n\
         \x20     <CellData{active}>\n"
    );
    let mut offset = 0usize;
    for field in fields {
        let components = field.components();
        header.push_str(&format!(
            "        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{components}\" \
             format=\"appended\" offset=\"{offset}\"/>\n",
            field.name()
        ));
        offset += 8 + 8 * components * grid.cell_count();
    }
    header.push_str(
        "      </CellData>\n    </Piece>\n  </ImageData>\n  <AppendedData encoding=\"raw\">\n   _",
    );

    let io_err = |e| OutputError::io(path, "cannot write VTK file", e);
    let file = dir.create_file(name)?;
    let mut out = BufWriter::with_capacity(1 << 20, file);
    out.write_all(header.as_bytes()).map_err(io_err)?;
    for field in fields {
        let bytes = 8 * field.components() * grid.cell_count();
        out.write_all(&(bytes as u64).to_le_bytes())
            .map_err(io_err)?;
        field
            .write_values(&mut out, f64::to_le_bytes)
            .map_err(io_err)?;
    }
    out.write_all(b"\n  </AppendedData>\n</VTKFile>\n")
        .map_err(io_err)?;
    out.flush().map_err(io_err)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_support::ScratchDir;

    /// Decodes the appended block by hand: the header offsets must point at a byte count
    /// followed by exactly the values written.
    #[test]
    fn appended_arrays_are_where_the_header_says() {
        let dir = ScratchDir::new("vti");
        let grid = Grid::new([3, 2, 2], [0.3 / 7.0, 0.5, 1.0], [-1.0, 0.0, 2.0]);
        let p: Vec<f64> = (0..12).map(|i| i as f64 * 0.1 - 0.35).collect();
        let u: Vec<[f64; 3]> = (0..12).map(|i| [i as f64, -(i as f64), 1e-300]).collect();
        let path = dir.path().join("fluid.vti");
        write_fluid_vti(
            &SafeDir::open_case(dir.path()).unwrap(),
            "fluid.vti",
            &grid,
            &[CellData::Vector("U", &u), CellData::Scalar("p", &p)],
        )
        .unwrap();
        let bytes = std::fs::read(&path).unwrap();
        let text = String::from_utf8_lossy(&bytes);
        assert!(text.contains(
            "WholeExtent=\"0 3 0 2 0 2\" Origin=\"-1 0 2\" Spacing=\"0.04285714285714286 0.5 1\""
        ));
        assert!(text.contains("<CellData Scalars=\"p\" Vectors=\"U\">"));
        let marker = b"<AppendedData encoding=\"raw\">\n   _";
        let start = bytes
            .windows(marker.len())
            .position(|w| w == marker)
            .unwrap()
            + marker.len();
        let array_at = |offset: usize| {
            let at = start + offset;
            let count = u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap()) as usize;
            bytes[at + 8..at + 8 + count]
                .chunks_exact(8)
                .map(|b| f64::from_le_bytes(b.try_into().unwrap()))
                .collect::<Vec<_>>()
        };
        assert!(
            text.contains("Name=\"U\" NumberOfComponents=\"3\" format=\"appended\" offset=\"0\"")
        );
        assert_eq!(array_at(0), u.iter().flatten().copied().collect::<Vec<_>>());
        let p_offset = 8 + 8 * 36;
        assert!(text.contains(&format!(
            "Name=\"p\" NumberOfComponents=\"1\" format=\"appended\" offset=\"{p_offset}\""
        )));
        assert_eq!(array_at(p_offset), p);
        assert!(text.ends_with("\n  </AppendedData>\n</VTKFile>\n"));
    }

    #[test]
    fn wrong_length_is_refused() {
        let dir = ScratchDir::new("vti-bad");
        let grid = Grid::new([2, 2, 2], [1.0; 3], [0.0; 3]);
        let err = write_fluid_vti(
            &SafeDir::open_case(dir.path()).unwrap(),
            "f.vti",
            &grid,
            &[CellData::Scalar("p", &[0.0])],
        )
        .unwrap_err();
        assert!(err.to_string().contains("f.vti"), "{err}");
    }
}
