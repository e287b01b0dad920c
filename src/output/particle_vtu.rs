//! Particles as an XML UnstructuredGrid (`.vtu`) of VERTEX cells, one per particle, with point
//! data; written by vtkio (inline base64, little-endian, as every XML reader expects).
//!
//! `.vtu` because meshio reads it (not `.vtp`), and pyvista and ParaView read it too. An empty
//! particle set is still a valid file with zero points and zero cells.

use super::fluid_vtk::validate_name;
use super::output_error::OutputError;
use super::safe_dir::SafeDir;
use crate::Vec3;
use std::io::Write;
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataArray, DataSet, ElementType,
    UnstructuredGridPiece, Version, VertexNumbers, Vtk,
};

/// A named per-particle array.
#[derive(Clone, Copy, Debug)]
pub enum PointData<'a> {
    Int(&'a str, &'a [i64]),
    Scalar(&'a str, &'a [f64]),
    Vector(&'a str, &'a [Vec3]),
}

impl PointData<'_> {
    fn name(&self) -> &str {
        match self {
            PointData::Int(n, _) | PointData::Scalar(n, _) | PointData::Vector(n, _) => n,
        }
    }

    fn len(&self) -> usize {
        match self {
            PointData::Int(_, v) => v.len(),
            PointData::Scalar(_, v) => v.len(),
            PointData::Vector(_, v) => v.len(),
        }
    }
}

/// The standard particle output of fsim (issue 3, item 5), by borrowed slices so the DEM
/// engine hands its own arrays over without copying them into a new structure.
#[derive(Clone, Copy, Debug)]
pub struct ParticleFields<'a> {
    pub positions: &'a [Vec3],
    pub id: &'a [i64],
    /// Diameter, metres.
    pub d: &'a [f64],
    /// Velocity, m/s.
    pub velocity: &'a [Vec3],
    /// Angular velocity, rad/s.
    pub omega: &'a [Vec3],
    /// Hydrodynamic force on each particle, N.
    pub hydrodynamic_force: &'a [Vec3],
    /// Sum of contact forces on each particle, N.
    pub contact_force: &'a [Vec3],
}

impl ParticleFields<'_> {
    /// Writes the particles with arrays named `id`, `d`, `U`, `omega`, `F_hydro`, `F_contact`
    /// to file `name` of `dir`.
    pub fn write(&self, dir: &SafeDir, name: &str) -> Result<(), OutputError> {
        write_particles_vtu(
            dir,
            name,
            self.positions,
            &[
                PointData::Int("id", self.id),
                PointData::Scalar("d", self.d),
                PointData::Vector("U", self.velocity),
                PointData::Vector("omega", self.omega),
                PointData::Vector("F_hydro", self.hydrodynamic_force),
                PointData::Vector("F_contact", self.contact_force),
            ],
        )
    }
}

/// Writes particles at `positions` with `data` (each array one value per particle) to file
/// `name` of `dir`, conventionally `<time>/particles.vtu`.
pub fn write_particles_vtu(
    dir: &SafeDir,
    name: &str,
    positions: &[Vec3],
    data: &[PointData],
) -> Result<(), OutputError> {
    let path = &dir.join(name);
    let count = positions.len();
    for array in data {
        validate_name(path, array.name())?;
        if array.len() != count {
            return Err(OutputError::invalid(
                path,
                format!(
                    "particle array `{}` has {} values for {} particles",
                    array.name(),
                    array.len(),
                    count
                ),
            ));
        }
    }
    let point = data
        .iter()
        .map(|array| {
            let (elem, buffer) = match array {
                PointData::Int(_, v) => (
                    ElementType::Scalars {
                        num_comp: 1,
                        lookup_table: None,
                    },
                    v.to_vec().into(),
                ),
                PointData::Scalar(_, v) => (
                    ElementType::Scalars {
                        num_comp: 1,
                        lookup_table: None,
                    },
                    v.to_vec().into(),
                ),
                PointData::Vector(_, v) => (
                    ElementType::Vectors,
                    v.iter().flatten().copied().collect::<Vec<f64>>().into(),
                ),
            };
            Attribute::DataArray(DataArray {
                name: array.name().to_string(),
                elem,
                data: buffer,
            })
        })
        .collect();
    let piece = UnstructuredGridPiece {
        points: positions
            .iter()
            .flatten()
            .copied()
            .collect::<Vec<f64>>()
            .into(),
        cells: Cells {
            cell_verts: VertexNumbers::XML {
                connectivity: (0..count as u64).collect(),
                offsets: (1..=count as u64).collect(),
            },
            types: vec![CellType::Vertex; count],
        },
        data: Attributes {
            point,
            cell: Vec::new(),
        },
    };
    let vtk = Vtk {
        version: Version::new_xml(1, 0),
        byte_order: ByteOrder::LittleEndian,
        title: String::new(),
        file_path: None,
        data: DataSet::inline(piece),
    };
    let mut xml = Vec::new();
    vtk.write_xml(&mut xml)
        .map_err(|e| OutputError::invalid(path, format!("cannot write particle file: {e}")))?;
    if count == 0 {
        xml = declare_empty_piece(xml);
    }
    let io_err = |e| OutputError::io(path, "cannot write particle file", e);
    let mut file = dir.create_file(name)?;
    file.write_all(&xml).map_err(io_err)?;
    Ok(())
}

/// vtkio 0.7.0-rc2 leaves out `NumberOfPoints` and `NumberOfCells` when both are zero, and
/// meshio then refuses the file (`KeyError: 'NumberOfPoints'`); the VTK XML format requires
/// them. Put them back on the (only) piece.
fn declare_empty_piece(xml: Vec<u8>) -> Vec<u8> {
    const BARE: &[u8] = b"<Piece>";
    const DECLARED: &[u8] = b"<Piece NumberOfPoints=\"0\" NumberOfCells=\"0\">";
    match xml.windows(BARE.len()).position(|w| w == BARE) {
        Some(at) => [&xml[..at], DECLARED, &xml[at + BARE.len()..]].concat(),
        None => xml,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_support::ScratchDir;
    use std::path::Path;
    use vtkio::model::IOBuffer;

    fn read_back(path: &Path) -> UnstructuredGridPiece {
        let vtk = vtkio::Vtk::import(path).unwrap();
        let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
            panic!("not an unstructured grid");
        };
        pieces
            .into_iter()
            .next()
            .unwrap()
            .into_loaded_piece_data(None)
            .unwrap()
    }

    #[test]
    fn particles_read_back_with_all_arrays() {
        let dir = ScratchDir::new("particles");
        let path = dir.path().join("particles.vtu");
        let positions = [
            Vec3::new(0.1, 0.2, 0.3),
            Vec3::new(1.0, -2.0, 3.5),
            Vec3::new(1e-5, 0.0, 7.0),
        ];
        let id = [7, 3, 11];
        let d = [1e-4, 2e-4, 1.5e-4];
        let velocity = [
            Vec3::new(1.0, 2.0, 3.0),
            Vec3::new(0.0, 0.0, -1.0),
            Vec3::new(0.5, 0.5, 0.5),
        ];
        let omega = [Vec3::new(0.0, 0.0, 9.0); 3];
        let hydro = [Vec3::new(1e-9, 2e-9, 3e-9); 3];
        let contact = [Vec3::new(-1e-6, 0.0, 0.0); 3];
        ParticleFields {
            positions: &positions,
            id: &id,
            d: &d,
            velocity: &velocity,
            omega: &omega,
            hydrodynamic_force: &hydro,
            contact_force: &contact,
        }
        .write(&SafeDir::open_case(dir.path()).unwrap(), "particles.vtu")
        .unwrap();
        let piece = read_back(&path);
        assert_eq!(piece.num_points(), 3);
        assert_eq!(piece.cells.types, vec![CellType::Vertex; 3]);
        let names: Vec<_> = piece
            .data
            .point
            .iter()
            .map(|a| a.name().to_string())
            .collect();
        assert_eq!(names, ["id", "d", "U", "omega", "F_hydro", "F_contact"]);
        let Attribute::DataArray(ids) = &piece.data.point[0] else {
            panic!()
        };
        assert_eq!(ids.data, IOBuffer::I64(id.to_vec()));
        let Attribute::DataArray(u) = &piece.data.point[2] else {
            panic!()
        };
        assert_eq!(
            u.data,
            IOBuffer::F64(velocity.iter().flatten().copied().collect())
        );
        assert_eq!(
            piece.points,
            IOBuffer::F64(positions.iter().flatten().copied().collect())
        );
    }

    #[test]
    fn empty_particle_set_is_a_valid_file() {
        let dir = ScratchDir::new("particles-empty");
        let path = dir.path().join("particles.vtu");
        ParticleFields {
            positions: &[],
            id: &[],
            d: &[],
            velocity: &[],
            omega: &[],
            hydrodynamic_force: &[],
            contact_force: &[],
        }
        .write(&SafeDir::open_case(dir.path()).unwrap(), "particles.vtu")
        .unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(
            text.contains("<Piece NumberOfPoints=\"0\" NumberOfCells=\"0\">"),
            "{text}"
        );
        let piece = read_back(&path);
        assert_eq!(piece.num_points(), 0);
        assert!(piece.cells.types.is_empty());
    }

    #[test]
    fn mismatched_lengths_are_refused() {
        let dir = ScratchDir::new("particles-bad");
        let err = write_particles_vtu(
            &SafeDir::open_case(dir.path()).unwrap(),
            "particles.vtu",
            &[Vec3::zeros(); 2],
            &[PointData::Scalar("d", &[1.0])],
        )
        .unwrap_err();
        assert!(
            err.to_string().contains("1 values for 2 particles"),
            "{err}"
        );
    }
}
