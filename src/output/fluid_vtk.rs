//! The fluid on the grid as a legacy binary VTK file: `DATASET STRUCTURED_POINTS` with
//! `CELL_DATA`, every value a big-endian `f64`.
//!
//! Why this format: meshio reads legacy `.vtk` and `.vtu` but not `.vti`; pyvista and ParaView
//! read all three; and legacy binary is the fastest of them to write
//! (docs/benchmarks/output.md). ParaView's collection reader cannot take a legacy file, so
//! the `.pvd` lists the `.vti` twin written beside it ([`super::write_fluid_vti`]).
//! Values stay `f64` so that checks can compare the file with what the solver computed to the
//! last bit; `f32` would halve the size but lose that.
//!
//! Why not vtkio's writer: it can write big-endian legacy files, but its `ImageData` keeps the
//! origin and spacing as `f32` (a cell size of `0.3/7` m would be written to 7 digits only, and
//! every cell centre read back shifted) and it takes owned buffers, so every write would copy
//! every field. The format is a five-line ASCII header and raw big-endian arrays (the VTK file
//! formats document: legacy binary data is always big-endian), written here directly. vtkio
//! reads it back in the tests.

use super::output_error::OutputError;
use super::safe_dir::SafeDir;
use crate::grid::Grid;
use std::io::{BufWriter, Write};
use std::path::Path;

/// A named cell-centred array, unpadded, x fastest (see [`crate::grid`]).
#[derive(Clone, Copy)]
pub enum CellData<'a> {
    Scalar(&'a str, &'a [f64]),
    Vector(&'a str, &'a [[f64; 3]]),
    /// A vector field of `len` cells computed cell by cell as it is written (the solver's
    /// cell-centred velocity, so that a write holds no copy of the field, which would set the
    /// run's peak memory). `Sync`: the two files of a time directory are
    /// written at once ([`super::write_fluid`]).
    ComputedVector(&'a str, usize, &'a (dyn Fn(usize) -> [f64; 3] + Sync)),
}

impl std::fmt::Debug for CellData<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "CellData({}, {} cells)", self.name(), self.len())
    }
}

impl CellData<'_> {
    pub(crate) fn name(&self) -> &str {
        match self {
            CellData::Scalar(name, _)
            | CellData::Vector(name, _)
            | CellData::ComputedVector(name, _, _) => name,
        }
    }

    fn len(&self) -> usize {
        match self {
            CellData::Scalar(_, v) => v.len(),
            CellData::Vector(_, v) => v.len(),
            CellData::ComputedVector(_, len, _) => *len,
        }
    }

    /// Values per cell.
    pub(crate) fn components(&self) -> usize {
        match self {
            CellData::Scalar(..) => 1,
            CellData::Vector(..) | CellData::ComputedVector(..) => 3,
        }
    }

    /// Streams the values (components of a cell together, cells x fastest) in the byte
    /// order `to_bytes` gives.
    pub(crate) fn write_values(
        &self,
        out: &mut impl Write,
        to_bytes: fn(f64) -> [u8; 8],
    ) -> std::io::Result<()> {
        match self {
            CellData::Scalar(_, v) => write_f64_bytes(out, v.iter().copied(), to_bytes),
            CellData::Vector(_, v) => write_f64_bytes(out, v.iter().flatten().copied(), to_bytes),
            CellData::ComputedVector(_, len, value) => {
                write_f64_bytes(out, (0..*len).flat_map(value), to_bytes)
            }
        }
    }
}

/// Writes `fields` on `grid` to file `name` of `dir` (conventionally `<time>/fluid.vtk`).
///
/// The points of the STRUCTURED_POINTS set are the cell corners, `n + 1` per direction, at
/// `origin + index · h`; the arrays are CELL_DATA, so VTK's cell `(i, j, k)` is the grid's cell
/// `(i, j, k)` with the same x-fastest order. `title` goes on the header's second line.
pub fn write_fluid_vtk(
    dir: &SafeDir,
    name: &str,
    grid: &Grid,
    title: &str,
    fields: &[CellData],
) -> Result<(), OutputError> {
    let path = &dir.join(name);
    validate_cell_data(path, grid, fields)?;
    let cells = grid.cell_count();
    let io_err = |e| OutputError::io(path, "cannot write VTK file", e);
    let file = dir.create_file(name)?;
    let mut out = BufWriter::with_capacity(1 << 20, file);
    write_header(&mut out, grid, title).map_err(io_err)?;
    writeln!(out, "CELL_DATA {cells}").map_err(io_err)?;
    for field in fields {
        let name = field.name();
        if field.components() == 1 {
            write!(out, "SCALARS {name} double 1\nLOOKUP_TABLE default\n").map_err(io_err)?;
        } else {
            writeln!(out, "VECTORS {name} double").map_err(io_err)?;
        }
        field
            .write_values(&mut out, f64::to_be_bytes)
            .map_err(io_err)?;
        out.write_all(b"\n").map_err(io_err)?;
    }
    out.flush().map_err(io_err)?;
    Ok(())
}

fn write_header(out: &mut impl Write, grid: &Grid, title: &str) -> std::io::Result<()> {
    // The title line is free text of at most 256 characters and must stay one line.
    let title: String = title
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .take(255)
        .collect();
    let [nx, ny, nz] = grid.n;
    let [ox, oy, oz] = grid.origin;
    let [hx, hy, hz] = grid.h;
    // `{}` prints the shortest decimal that reads back as the same f64.
    write!(
        out,
        "# vtk DataFile Version 3.0\n{title}\nBINARY\nDATASET STRUCTURED_POINTS\n\
         DIMENSIONS {} {} {}\nORIGIN {ox} {oy} {oz}\nSPACING {hx} {hy} {hz}\n",
        nx + 1,
        ny + 1,
        nz + 1
    )
}

/// Streams values as f64 in the byte order `to_bytes` gives, through a fixed stack buffer
/// (no allocation per value).
fn write_f64_bytes(
    out: &mut impl Write,
    values: impl Iterator<Item = f64>,
    to_bytes: fn(f64) -> [u8; 8],
) -> std::io::Result<()> {
    const CHUNK: usize = 4096;
    let mut buffer = [0u8; CHUNK * 8];
    let mut filled = 0;
    for v in values {
        buffer[filled..filled + 8].copy_from_slice(&to_bytes(v));
        filled += 8;
        if filled == buffer.len() {
            out.write_all(&buffer)?;
            filled = 0;
        }
    }
    out.write_all(&buffer[..filled])
}

/// Every array has one value per cell and a valid name.
pub(crate) fn validate_cell_data(
    path: &Path,
    grid: &Grid,
    fields: &[CellData],
) -> Result<(), OutputError> {
    let cells = grid.cell_count();
    for field in fields {
        validate_name(path, field.name())?;
        if field.len() != cells {
            return Err(OutputError::invalid(
                path,
                format!(
                    "field `{}` has {} values, the grid has {} cells",
                    field.name(),
                    field.len(),
                    cells
                ),
            ));
        }
    }
    Ok(())
}

/// Legacy VTK names are whitespace-delimited tokens; XML attribute values must not need
/// escaping.
pub(crate) fn validate_name(path: &Path, name: &str) -> Result<(), OutputError> {
    let forbidden = |c: char| c.is_whitespace() || c.is_control() || "&<>\"'".contains(c);
    if name.is_empty() || name.chars().any(forbidden) {
        return Err(OutputError::invalid(
            path,
            format!("array name `{name}` must be one word without spaces or XML markup"),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_support::ScratchDir;
    use vtkio::model::{Attribute, DataSet, Extent, IOBuffer};

    fn sample(grid: &Grid) -> (Vec<f64>, Vec<[f64; 3]>) {
        let mut p = vec![0.0; grid.cell_count()];
        let mut u = vec![[0.0; 3]; grid.cell_count()];
        for k in 0..grid.n[2] {
            for j in 0..grid.n[1] {
                for i in 0..grid.n[0] {
                    let c = grid.cell_index(i, j, k);
                    let [x, y, z] = grid.cell_centre(i, j, k);
                    p[c] = x * y;
                    u[c] = [(2.0 * x).sin(), y / 3.0, -z];
                }
            }
        }
        (p, u)
    }

    #[test]
    fn vtkio_reads_back_geometry_and_values_bit_for_bit() {
        let dir = ScratchDir::new("fluid");
        let grid = Grid::new([5, 4, 3], [0.3 / 7.0, 0.25, 0.1], [-1.0, 0.5, 1e-3]);
        let (p, u) = sample(&grid);
        let path = dir.path().join("fluid.vtk");
        let fields = [CellData::Vector("U", &u), CellData::Scalar("p", &p)];
        let out = SafeDir::open_case(dir.path()).unwrap();
        write_fluid_vtk(&out, "fluid.vtk", &grid, "fsim t = 0.1", &fields).unwrap();
        let text = std::fs::read(&path).unwrap();
        assert!(text.starts_with(b"# vtk DataFile Version 3.0\nfsim t = 0.1\nBINARY\n"));
        let header = String::from_utf8_lossy(&text[..200]);
        assert!(
            header.contains("SPACING 0.04285714285714286 0.25 0.1\n"),
            "{header}"
        );

        let vtk = vtkio::Vtk::parse_legacy_be(std::fs::File::open(&path).unwrap()).unwrap();
        let DataSet::ImageData { extent, pieces, .. } = vtk.data else {
            panic!("not STRUCTURED_POINTS");
        };
        assert_eq!(extent, Extent::Dims([6, 5, 4]));
        let piece = pieces
            .into_iter()
            .next()
            .unwrap()
            .into_loaded_piece_data(None);
        let cell = piece.unwrap().data.cell;
        assert_eq!(cell.len(), 2);
        let values = |a: &Attribute| match a {
            Attribute::DataArray(d) => match &d.data {
                IOBuffer::F64(v) => (d.name.clone(), v.clone()),
                other => panic!("not f64: {other:?}"),
            },
            other => panic!("unexpected {other:?}"),
        };
        let (u_name, u_read) = values(&cell[0]);
        let (p_name, p_read) = values(&cell[1]);
        assert_eq!((u_name.as_str(), p_name.as_str()), ("U", "p"));
        assert_eq!(p_read, p);
        assert_eq!(u_read, u.iter().flatten().copied().collect::<Vec<_>>());
    }

    #[test]
    fn wrong_length_and_bad_names_are_refused_naming_the_file() {
        let dir = ScratchDir::new("fluid-bad");
        let grid = Grid::new([2, 2, 2], [1.0; 3], [0.0; 3]);
        let out = SafeDir::open_case(dir.path()).unwrap();
        let write = |fields: &[CellData]| write_fluid_vtk(&out, "fluid.vtk", &grid, "", fields);
        let err = write(&[CellData::Scalar("p", &[1.0; 7])]).unwrap_err();
        assert!(err.to_string().contains("fluid.vtk"), "{err}");
        assert!(err.to_string().contains("7 values"), "{err}");
        let err = write(&[CellData::Scalar("a b", &[1.0; 8])]).unwrap_err();
        assert!(err.to_string().contains("one word"), "{err}");
    }
}
