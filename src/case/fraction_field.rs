//! `0/alpha.<phase>`, the fluid fraction, when a DPMFoam case has one. DPMFoam reads it if
//! present but overwrites its cell values from the particles before the first step
//! (`alphac = max(1 − θ, 1 − alphaMax)`); what it keeps are the boundary conditions, which
//! decide the fraction on the faces. fsim takes the fraction on a boundary face from the
//! adjacent cell, which is what `zeroGradient` (DPMFoam's default when the file is absent)
//! and `calculated` give; a fixed fraction on a patch would change the inflow of an
//! `interstitialInletVelocity` and is refused.

use super::block_mesh::BlockMesh;
use super::dictionary::Dict;
use super::error::CaseError;
use super::fields::{condition_type, conditions, quiet_bookkeeping};

/// Conditions fsim honours for the fluid fraction.
const FRACTION_TYPES: [&str; 7] = [
    "zeroGradient",
    "calculated",
    "cyclic",
    "symmetry",
    "symmetryPlane",
    "empty",
    "fixedValue",
];

/// Checks the boundary conditions of a fluid-fraction file against the mesh; the cell values
/// are noted as recomputed.
pub fn check_fraction_field(
    d: &Dict,
    mesh: &BlockMesh,
    notes: &mut Vec<String>,
) -> Result<(), CaseError> {
    d.lookup("dimensions");
    d.check_dimensions("dimensions", [0.0; 7], "a volume fraction, dimensionless")?;
    if let Some(e) = d.lookup("internalField") {
        let (line, col) = e.key_loc.line_col();
        notes.push(format!(
            "{}:{line}:{col}: internalField: the fluid fraction is computed from the particles \
             at the start, as DPMFoam does",
            d.file()
        ));
    }
    for (condition, patch) in conditions(d, mesh, notes)?.into_iter().zip(&mesh.patches) {
        let Some(c) = condition else { continue };
        let k = condition_type(c, patch, &FRACTION_TYPES, "fluid-fraction")?;
        if FRACTION_TYPES[k] == "fixedValue" {
            return Err(super::control_dict::at_value(
                c,
                "type",
                format!(
                    "fixedValue fluid fraction on patch '{}' is not supported by fsim: the \
                     fraction on a boundary face is the adjacent cell's (use zeroGradient or \
                     calculated)",
                    patch.name
                ),
            ));
        }
        quiet_bookkeeping(c);
    }
    Ok(())
}
