//! The drag-law model's options, read from DPMFoam's `constant/kinematicCloudProperties` (and
//! fsim's optional `dragLawCoeffs` in `constant/couplingProperties`); [`DragLawOptions::settings`]
//! gives the coupling code's [`DragLawSettings`].
//!
//! What each DPMFoam keyword becomes (the full list, with the keywords fsim refuses, is in
//! docs/user-guide/dpmfoam-compatibility.md):
//!
//! * `solution.coupled` must be `true` (two-way coupling: the particles' reaction force and
//!   volume enter the fluid); one-way coupling is refused. `cellValueSourceCorrection on` is
//!   refused; `maxCo` is noted as unused.
//! * `solution.sourceTerms.schemes.U explicit|semiImplicit c` → [`SourceTreatment`], with
//!   `c = 1`: DPMFoam scales the particles' momentum source by `c`
//!   (`KinematicCloud::scaleSources`), which fsim does not, so another `c` is refused.
//! * `solution.interpolationSchemes.U.<phase>` → [`DragLawOptions::velocity_interpolation`]:
//!   `cell` (the value of the particle's cell) or `cellPoint` (OpenFOAM's cell-and-point
//!   interpolation, [`crate::coupling::drag::CellPointInterpolation`]); fsim's
//!   `trilinear` (paper eq. 14–15) only through `dragLawCoeffs`. `rho.<phase>`, `mu.<phase>`
//!   and `alpha.<phase>` may name any of OpenFOAM's schemes: the first two are constants of
//!   fsim's fluid, and ε at a particle follows [`VoidFraction`].
//! * `solution.averagingMethod basic|dual` → [`VoidFraction`]: `basic` is DPMFoam's own rule
//!   (a particle's volume counts in its cell only, which DPMFoam applies whatever this keyword
//!   says: the keyword is read by MPPICFoam's models); `dual`, OpenFOAM's averaging on the dual
//!   (point) mesh, is taken as fsim's closest equivalent, the trilinear weights of paper
//!   eq. 15 applied to the volume as the paper says after paper eq. 16 (noted). Absent:
//!   `basic`, as DPMFoam does. `moment` is refused.
//! * `solution.integrationSchemes.U Euler|analytical` → [`ParticleIntegration`] (noted: fsim
//!   integrates with its own scheme).
//! * `constantProperties.alphaMax` → [`DragLawOptions::alpha_max`]: the fluid fraction never
//!   drops below `1 − alphaMax` (DPMFoam's `alphacMin`).
//! * `subModels.particleForces` (read by [`super::particle_forces`]): exactly one drag
//!   closure ([`DragClosure`], by the names of [`DragClosure::NAMES`]: OpenFOAM's four and
//!   fsim's own, or `nonSphereDrag { phi …; }`), `gravity`, `pressureGradient`,
//!   `virtualMass { Cvm …; }` and one lift force (`SaffmanMeiLiftForce`,
//!   `TomiyamaLift { sigma …; }`), computed as [`crate::coupling::drag::FluidForces`] says.
//!   In DPMFoam's form `pressureGradient` is DPMFoam's `m (ρ_c/ρ_p) DU_c/Dt`; in the paper's
//!   form every particle feels `−V ∇p` (paper eq. 10) instead. Other OpenFOAM forces are
//!   refused; an unknown name is an error with a spelling hint.
//! * `solution.interpolationSchemes.DUcDt` and `.curlUcDt` (DPMFoam's names of the fields
//!   the pressure-gradient and virtual-mass forces and the lift forces read): `cell` or
//!   `cellPoint`; absent (DPMFoam would stop): `cell`, noted.
//!
//! fsim's own `dragLawCoeffs { form DPMFoam|paper; velocityInterpolation
//! cell|cellPoint|trilinear; voidFraction cell|trilinear; fixedParticles no|yes; }` in
//! `constant/couplingProperties` chooses the equations and overrides the interpolation and the
//! ε rule, so that the same case runs with DPMFoam's choices or with the paper's;
//! `fixedParticles yes` holds every particle in place (a fixed bed, porous media), as
//! `direct { fixedParticles yes; }` does for the direct model. DPMFoam has no such switch, so
//! it is fsim's own keyword, beside the model's other settings.

use super::control_dict::{at_value, choice};
use super::dictionary::Dict;
use super::error::CaseError;
use super::particle_forces::ParticleForces;
use super::transport::Transport;
use crate::coupling::drag::{DragClosure, DragLawSettings, FluidForces, Stencil};
use crate::fluid::VolumeAveragedForm;

/// How the fluid velocity is taken at a particle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// OpenFOAM's `cell`: the value of the cell holding the particle.
    Cell,
    /// OpenFOAM's `cellPoint`: linear inside the tetrahedra of the cell's decomposition, from
    /// the cell value and the point values (averages of the surrounding cells).
    CellPoint,
    /// fsim's `trilinear`: trilinear from the 8 nearest cell centres (paper eq. 14–15).
    Trilinear,
}

impl Interpolation {
    pub fn keyword(self) -> &'static str {
        match self {
            Interpolation::Cell => "cell",
            Interpolation::CellPoint => "cellPoint",
            Interpolation::Trilinear => "trilinear",
        }
    }
}

/// How the particles' volume makes the fluid fraction ε of the cells (and how the reaction
/// force is spread back: with the same weights).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VoidFraction {
    /// DPMFoam's rule: a particle's whole volume in the cell holding its centre.
    Cell,
    /// The paper's rule (after paper eq. 16): spread to the 8 nearest cell centres with the
    /// trilinear weights of paper eq. 15.
    Trilinear,
}

impl VoidFraction {
    pub fn keyword(self) -> &'static str {
        match self {
            VoidFraction::Cell => "cell",
            VoidFraction::Trilinear => "trilinear",
        }
    }
}

/// How the drag's reaction enters the fluid momentum equation
/// (`sourceTerms { schemes { U explicit|semiImplicit 1; } }`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SourceTreatment {
    /// The whole reaction force at the old fluid velocity.
    Explicit,
    /// The part linear in the fluid velocity implicit (DPMFoam's `semiImplicit`).
    SemiImplicit,
}

/// How a particle's velocity is advanced under drag (`integrationSchemes { U …; }`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParticleIntegration {
    /// OpenFOAM's `Euler`: implicit in the drag, `v' = (v + β u Δt + a Δt)/(1 + β Δt)`.
    Euler,
    /// OpenFOAM's `analytical`: the exact exponential relaxation over the step.
    Analytical,
}

/// The drag-law model as the case states it: DPMFoam's keywords and fsim's `dragLawCoeffs`.
/// [`DragLawOptions::settings`] turns it into the coupling code's [`DragLawSettings`].
#[derive(Clone, Debug, PartialEq)]
pub struct DragLawOptions {
    /// The continuous phase's name (`air`), from `transportProperties`.
    pub phase: String,
    /// The drag closure of `particleForces` (the drag-law model needs exactly one).
    pub drag: DragClosure,
    /// Which volume-averaged equations the fluid solves: DPMFoam's (the default, so that a
    /// DPMFoam case gives DPMFoam's physics) or paper eq. 7 (`dragLawCoeffs { form
    /// paper; }`).
    pub form: VolumeAveragedForm,
    /// `gravity` listed in `particleForces` (gravity with buoyancy `1 − ρ_f/ρ_p`).
    pub gravity: bool,
    /// `pressureGradient` listed in `particleForces`.
    pub pressure_gradient: bool,
    /// DPMFoam's pressure-gradient (in DPMFoam's form), virtual-mass and lift forces, with
    /// the interpolation of the fields they read.
    pub forces: FluidForces,
    /// `sourceTerms.schemes.U`.
    pub source: SourceTreatment,
    /// `constantProperties.alphaMax`: ε ≥ 1 − alphaMax.
    pub alpha_max: f64,
    /// The fluid velocity at a particle, as the case names it.
    pub velocity_interpolation: Interpolation,
    /// ε from the particles.
    pub void_fraction: VoidFraction,
    /// `integrationSchemes.U`.
    pub integration: ParticleIntegration,
    /// `dragLawCoeffs { fixedParticles yes; }`: every particle held in place.
    pub fixed_particles: bool,
}

impl DragLawOptions {
    /// The lower bound of the fluid fraction, `1 − alphaMax` (DPMFoam's `alphacMin`).
    pub fn min_fluid_fraction(&self) -> f64 {
        1.0 - self.alpha_max
    }

    /// The coupling code's settings, with the fluid's properties and gravity from the case.
    /// `cellPoint` reads the velocity by OpenFOAM's cell-point rule and, in the paper's form,
    /// the pressure gradient trilinearly.
    pub fn settings(&self, transport: &Transport, gravity: [f64; 3]) -> DragLawSettings {
        let stencil = |trilinear: bool| {
            if trilinear {
                Stencil::Trilinear
            } else {
                Stencil::Cell
            }
        };
        DragLawSettings {
            closure: Some(self.drag),
            analytical: self.integration == ParticleIntegration::Analytical,
            form: self.form,
            interpolation: stencil(self.velocity_interpolation != Interpolation::Cell),
            cell_point: self.velocity_interpolation == Interpolation::CellPoint,
            averaging: stencil(self.void_fraction == VoidFraction::Trilinear),
            semi_implicit: self.source == SourceTreatment::SemiImplicit,
            alpha_max: self.alpha_max,
            rho: transport.rho,
            nu: transport.nu,
            gravity: gravity.into(),
            forces: self.forces,
        }
    }

    /// Reads the options from the cloud file `cloud` (DPMFoam's `kinematicCloudProperties`)
    /// and fsim's `couplingProperties` when present; `phase` is the continuous phase's name.
    /// Settings fsim reads but that have no effect go to `notes`; settings that would change
    /// the physics in a way fsim cannot honour are errors at their place.
    pub fn read(
        cloud: &Dict,
        coupling: Option<&Dict>,
        phase: &str,
        notes: &mut Vec<String>,
    ) -> Result<DragLawOptions, CaseError> {
        let solution = cloud.get_dict("solution")?;
        // Required by DPMFoam too (cloudSolution reads it without a default).
        if !solution.get_bool("coupled")? {
            return Err(at_value(
                solution,
                "coupled",
                "coupled false (one-way coupling) is not supported by fsim's drag-law model: \
                 the fluid always feels the particles; use coupled true"
                    .to_string(),
            ));
        }
        if solution.get_bool_or("cellValueSourceCorrection", false)? {
            return Err(at_value(
                solution,
                "cellValueSourceCorrection",
                "cellValueSourceCorrection on is not supported by fsim (the fluid values a \
                 particle sees are not corrected by the sources of the same step); use off"
                    .to_string(),
            ));
        }
        if let Some(max_co) = solution.opt_scalar("maxCo")? {
            notes.push(format!(
                "{}: solution.maxCo {max_co}: not used (fsim moves particles in its collision \
                 sub-steps, not by cell-to-cell tracking)",
                place(solution, "maxCo")
            ));
        }
        let source = source_treatment(solution)?;
        let schemes = interpolation_schemes(solution, phase)?;
        let mut velocity_interpolation = schemes.velocity;
        let mut void_fraction = averaging_method(solution, notes)?;
        let integration = particle_integration(solution)?;
        if solution.peek("integrationSchemes").is_some() {
            notes.push(format!(
                "{}: integrationSchemes U {}: fsim advances the particles with its DEM \
                 integrator (velocity Verlet in the collision sub-steps), the drag included",
                place(solution, "integrationSchemes"),
                match integration {
                    ParticleIntegration::Euler => "Euler",
                    ParticleIntegration::Analytical => "analytical",
                }
            ));
        }

        let props = cloud.get_dict("constantProperties")?;
        let alpha_max = props.get_scalar("alphaMax")?;
        if !(alpha_max > 0.0 && alpha_max <= 1.0) {
            return Err(at_value(
                props,
                "alphaMax",
                format!(
                    "'alphaMax' = {alpha_max}: expected a largest particle volume fraction in \
                     (0, 1] (the fluid fraction is kept at or above 1 - alphaMax)"
                ),
            ));
        }

        let sub = cloud.get_dict("subModels")?;
        let forces = ParticleForces::read(sub, phase)?;
        let list = sub.peek("particleForces");
        let Some(drag) = forces.drag else {
            let message = format!(
                "no drag closure in particleForces: the drag-law model needs one of {}",
                DragClosure::NAMES.join(", ")
            );
            return Err(match list {
                Some(e) => CaseError::at(&e.key_loc, message),
                None => CaseError::at(&sub.loc, message),
            });
        };

        let mut form = VolumeAveragedForm::DpmFoam;
        let mut fixed_particles = false;
        if let Some(own) = coupling
            .map(|c| c.opt_dict("dragLawCoeffs"))
            .transpose()?
            .flatten()
        {
            if own.contains("form") {
                form = match choice(own, "form", &["DPMFoam", "paper"], None)? {
                    0 => VolumeAveragedForm::DpmFoam,
                    _ => VolumeAveragedForm::Paper,
                };
            }
            if own.contains("velocityInterpolation") {
                velocity_interpolation = match choice(
                    own,
                    "velocityInterpolation",
                    &["cell", "cellPoint", "trilinear"],
                    None,
                )? {
                    0 => Interpolation::Cell,
                    1 => Interpolation::CellPoint,
                    _ => Interpolation::Trilinear,
                };
            }
            if own.contains("voidFraction") {
                void_fraction = match choice(own, "voidFraction", &["cell", "trilinear"], None)? {
                    0 => VoidFraction::Cell,
                    _ => VoidFraction::Trilinear,
                };
            }
            fixed_particles = own.get_bool_or("fixedParticles", false)?;
            for (key, loc) in own.unused() {
                let (line, col) = loc.line_col();
                notes.push(format!(
                    "{}:{line}:{col}: ignored keyword 'dragLawCoeffs.{key}' (fsim does not use \
                     it)",
                    loc.file.display
                ));
            }
        }
        if form == VolumeAveragedForm::Paper && !forces.pressure_gradient {
            notes.push(format!(
                "{}: the paper form gives every particle the pressure-gradient force -V grad p \
                 (paper eq. 10), whether or not particleForces lists pressureGradient",
                cloud.file()
            ));
        }
        let fluid_forces = FluidForces {
            pressure_gradient: forces.pressure_gradient && form == VolumeAveragedForm::DpmFoam,
            virtual_mass: forces.virtual_mass,
            lift: forces.lift,
            acceleration_cell_point: schemes.acceleration == Some(Interpolation::CellPoint),
            curl_cell_point: schemes.curl == Some(Interpolation::CellPoint),
        };
        for (needed, field, scheme, force) in [
            (
                fluid_forces.needs_acceleration(),
                "DUcDt",
                schemes.acceleration,
                "pressureGradient and virtualMass read",
            ),
            (
                fluid_forces.needs_curl(),
                "curlUcDt",
                schemes.curl,
                "the lift forces read",
            ),
        ] {
            if needed && scheme.is_none() {
                notes.push(format!(
                    "{}: no interpolationSchemes entry {field} (the field {force}; DPMFoam stops \
                     without it): fsim takes the value of the particle's cell",
                    place(solution, "interpolationSchemes")
                ));
            }
        }

        Ok(DragLawOptions {
            phase: phase.to_string(),
            drag,
            form,
            gravity: forces.gravity,
            pressure_gradient: forces.pressure_gradient,
            forces: fluid_forces,
            source,
            alpha_max,
            velocity_interpolation,
            void_fraction,
            integration,
            fixed_particles,
        })
    }

    /// One line for the log and `-dry-run`.
    pub fn summary(&self) -> String {
        let mut forces = vec![self.drag.name()];
        if self.pressure_gradient {
            forces.push("pressureGradient");
        }
        if self.forces.virtual_mass.is_some() {
            forces.push("virtualMass");
        }
        if let Some(lift) = self.forces.lift {
            forces.push(lift.name());
        }
        if self.gravity {
            forces.push("gravity");
        }
        format!(
            "forces {}; {} equations; source {}; U interpolation {}; void fraction {}; \
             alphaMax {}",
            forces.join(" + "),
            self.form.name(),
            match self.source {
                SourceTreatment::Explicit => "explicit",
                SourceTreatment::SemiImplicit => "semiImplicit",
            },
            self.velocity_interpolation.keyword(),
            self.void_fraction.keyword(),
            self.alpha_max
        )
    }
}

/// `file:line:col` of an entry's value.
fn place(d: &Dict, keyword: &str) -> String {
    let loc = d
        .peek(keyword)
        .map(|e| e.value_loc().clone())
        .unwrap_or_else(|| d.loc.clone());
    let (line, col) = loc.line_col();
    format!("{}:{line}:{col}", loc.file.display)
}

/// `sourceTerms { schemes { U explicit|semiImplicit c; } }`; absent: explicit.
fn source_treatment(solution: &Dict) -> Result<SourceTreatment, CaseError> {
    let Some(terms) = solution.opt_dict("sourceTerms")? else {
        return Ok(SourceTreatment::Explicit);
    };
    let Some(schemes) = terms.opt_dict("schemes")? else {
        return Ok(SourceTreatment::Explicit);
    };
    let Some(entry) = schemes.lookup("U") else {
        return Ok(SourceTreatment::Explicit);
    };
    let bad = |at: &super::source::Location| {
        CaseError::at(
            at,
            "expected 'U explicit <coefficient>;' or 'U semiImplicit <coefficient>;' in \
             sourceTerms.schemes",
        )
    };
    let tokens = entry.as_tokens().ok_or_else(|| bad(&entry.key_loc))?;
    let (kind, coefficient) = match tokens {
        [kind, c] => (kind, c),
        [first, ..] => return Err(bad(&first.loc)),
        [] => return Err(bad(&entry.key_loc)),
    };
    let treatment = match kind.as_word() {
        Some("explicit") => SourceTreatment::Explicit,
        Some("semiImplicit") => SourceTreatment::SemiImplicit,
        _ => {
            return Err(CaseError::at(
                &kind.loc,
                format!(
                    "expected explicit or semiImplicit for the U source term, found {}",
                    kind.describe()
                ),
            ))
        }
    };
    let c = coefficient
        .as_scalar()
        .ok_or_else(|| bad(&coefficient.loc))?;
    if c != 1.0 {
        return Err(CaseError::at(
            &coefficient.loc,
            format!(
                "source-term coefficient {c}: DPMFoam scales the particles' momentum source by \
                 it (KinematicCloud::scaleSources), which fsim does not; use 1"
            ),
        ));
    }
    Ok(treatment)
}

/// OpenFOAM's interpolation schemes, as written in `interpolationSchemes`.
const OPENFOAM_INTERPOLATIONS: [&str; 7] = [
    "cell",
    "cellPoint",
    "cellPointFace",
    "cellPointWallModified",
    "cellPatchConstrained",
    "cellPointPatchConstrained",
    "pointMVC",
];

/// The schemes of `interpolationSchemes` fsim reads.
struct Schemes {
    velocity: Interpolation,
    /// `DUcDt`'s and `curlUcDt`'s, when given.
    acceleration: Option<Interpolation>,
    curl: Option<Interpolation>,
}

/// `interpolationSchemes`: the velocity's scheme (`cell` when absent, OpenFOAM's default for
/// a cloud), `DUcDt`'s and `curlUcDt`'s (`cell` or `cellPoint`); the density's and
/// viscosity's are checked to be OpenFOAM's names only.
fn interpolation_schemes(solution: &Dict, phase: &str) -> Result<Schemes, CaseError> {
    let mut result = Schemes {
        velocity: Interpolation::Cell,
        acceleration: None,
        curl: None,
    };
    let Some(schemes) = solution.opt_dict("interpolationSchemes")? else {
        return Ok(result);
    };
    let velocity = velocity_name(phase);
    for e in schemes.entries() {
        let field = e.keyword();
        let constant = field == format!("rho.{phase}")
            || field == format!("mu.{phase}")
            || field == format!("alpha.{phase}")
            || (phase.is_empty() && ["rho", "mu", "alpha"].contains(&field));
        let derived = field == "DUcDt" || field == "curlUcDt";
        if field != velocity && !constant && !derived {
            continue; // other fields: left to the ignored-keyword notes
        }
        e.mark_used();
        let item = super::dictionary::single_token(e, "an interpolation scheme")?;
        let word = item.as_word().unwrap_or("");
        if field == velocity || derived {
            // fsim reads these two of OpenFOAM's schemes; the velocity also fsim's trilinear
            let also = if derived {
                ""
            } else {
                " (or fsim's trilinear, set in constant/couplingProperties \
                 dragLawCoeffs.velocityInterpolation)"
            };
            let scheme = match word {
                "cell" => Interpolation::Cell,
                "cellPoint" => Interpolation::CellPoint,
                _ => {
                    return Err(CaseError::at(
                        &item.loc,
                        format!(
                            "interpolation scheme {} for {field} is not supported by fsim: \
                             expected cell or cellPoint{also}",
                            item.describe()
                        ),
                    ))
                }
            };
            match field {
                "DUcDt" => result.acceleration = Some(scheme),
                "curlUcDt" => result.curl = Some(scheme),
                _ => result.velocity = scheme,
            }
        } else if !OPENFOAM_INTERPOLATIONS.contains(&word) {
            return Err(CaseError::at(
                &item.loc,
                format!(
                    "unknown interpolation scheme {} for {field}: expected one of {}",
                    item.describe(),
                    OPENFOAM_INTERPOLATIONS.join(", ")
                ),
            ));
        }
    }
    Ok(result)
}

/// `averagingMethod basic|dual|moment` (MPPICFoam's keyword): the ε rule.
fn averaging_method(solution: &Dict, notes: &mut Vec<String>) -> Result<VoidFraction, CaseError> {
    if !solution.contains("averagingMethod") {
        return Ok(VoidFraction::Cell);
    }
    let k = choice(
        solution,
        "averagingMethod",
        &["basic", "dual", "moment"],
        None,
    )?;
    match k {
        0 => Ok(VoidFraction::Cell),
        1 => {
            notes.push(format!(
                "{}: averagingMethod dual: fsim spreads each particle's volume and reaction \
                 over the 8 nearest cell centres (paper eq. 16), its equivalent of OpenFOAM's \
                 dual-mesh averaging (DPMFoam itself counts a particle in its own cell)",
                place(solution, "averagingMethod")
            ));
            Ok(VoidFraction::Trilinear)
        }
        _ => Err(at_value(
            solution,
            "averagingMethod",
            "averagingMethod moment is not supported by fsim: expected basic (ε from the \
             particle's cell) or dual (trilinear spreading)"
                .to_string(),
        )),
    }
}

/// `integrationSchemes { U Euler|analytical; }`; absent: Euler.
fn particle_integration(solution: &Dict) -> Result<ParticleIntegration, CaseError> {
    let Some(schemes) = solution.opt_dict("integrationSchemes")? else {
        return Ok(ParticleIntegration::Euler);
    };
    if !schemes.contains("U") {
        return Ok(ParticleIntegration::Euler);
    }
    Ok(
        match choice(schemes, "U", &["Euler", "analytical"], None)? {
            0 => ParticleIntegration::Euler,
            _ => ParticleIntegration::Analytical,
        },
    )
}

/// `U.<phase>`, or `U` without a phase.
pub(crate) fn velocity_name(phase: &str) -> String {
    if phase.is_empty() {
        "U".to_string()
    } else {
        format!("U.{phase}")
    }
}

/// `alpha.<phase>`, or `alpha` without a phase.
pub(crate) fn fraction_name(phase: &str) -> String {
    if phase.is_empty() {
        "alpha".to_string()
    } else {
        format!("alpha.{phase}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::parse_dict;
    use crate::Vec3;

    const GOLDSCHMIDT_LIKE: &str = "\
solution
{
    active true; coupled true; transient yes; cellValueSourceCorrection off;
    interpolationSchemes { rho.air cell; U.air cell; mu.air cell; }
    sourceTerms { schemes { U semiImplicit 1; } }
}
constantProperties { rho0 2526; alphaMax 0.99; }
subModels
{
    particleForces
    {
        ErgunWenYuDrag { alphac alpha.air; }
        gravity;
    }
}
";

    fn read(text: &str) -> Result<(DragLawOptions, Vec<String>), CaseError> {
        read_with(text, None)
    }

    fn read_with(
        text: &str,
        coupling: Option<&str>,
    ) -> Result<(DragLawOptions, Vec<String>), CaseError> {
        let d = parse_dict(text, "constant/kinematicCloudProperties").unwrap();
        let c = coupling.map(|c| parse_dict(c, "constant/couplingProperties").unwrap());
        let mut notes = Vec::new();
        DragLawOptions::read(&d, c.as_ref(), "air", &mut notes).map(|s| (s, notes))
    }

    fn err(text: &str) -> CaseError {
        read(text).unwrap_err()
    }

    #[test]
    fn goldschmidt_like_options_and_their_coupling_settings() {
        let (s, notes) = read(GOLDSCHMIDT_LIKE).unwrap();
        assert_eq!(
            s,
            DragLawOptions {
                phase: "air".into(),
                drag: DragClosure::ErgunWenYu,
                form: VolumeAveragedForm::DpmFoam,
                gravity: true,
                pressure_gradient: false,
                forces: FluidForces::default(),
                source: SourceTreatment::SemiImplicit,
                alpha_max: 0.99,
                velocity_interpolation: Interpolation::Cell,
                void_fraction: VoidFraction::Cell,
                integration: ParticleIntegration::Euler,
                fixed_particles: false,
            }
        );
        assert!(notes.is_empty(), "{notes:?}");
        assert!((s.min_fluid_fraction() - 0.01).abs() < 1e-15);
        assert_eq!(
            s.summary(),
            "forces ErgunWenYuDrag + gravity; DPMFoam equations; source semiImplicit; U \
             interpolation cell; void fraction cell; alphaMax 0.99"
        );
        let transport = Transport {
            phase: "air".into(),
            rho: 1.2,
            nu: 1e-5,
        };
        let engine = s.settings(&transport, [0.0, 0.0, -9.81]);
        assert_eq!(
            engine,
            DragLawSettings {
                closure: Some(DragClosure::ErgunWenYu),
                analytical: false,
                form: VolumeAveragedForm::DpmFoam,
                interpolation: Stencil::Cell,
                cell_point: false,
                averaging: Stencil::Cell,
                semi_implicit: true,
                alpha_max: 0.99,
                rho: 1.2,
                nu: 1e-5,
                gravity: Vec3::new(0.0, 0.0, -9.81),
                forces: FluidForces::default(),
            }
        );
        // cellPoint: the cell-point rule for the velocity, no note
        let (s, notes) =
            read(&GOLDSCHMIDT_LIKE.replace("U.air cell;", "U.air cellPoint;")).unwrap();
        assert_eq!(s.velocity_interpolation, Interpolation::CellPoint);
        assert!(s.settings(&transport, [0.0; 3]).cell_point);
        assert!(!notes.iter().any(|n| n.contains("cellPoint")), "{notes:?}");
    }

    #[test]
    fn every_closure_name_round_trips() {
        for name in DragClosure::NAMES {
            let text = GOLDSCHMIDT_LIKE.replace("ErgunWenYuDrag", name);
            assert_eq!(read(&text).unwrap().0.drag.name(), name);
        }
        // fsim's own closures need no alphac; if given it must be the phase's
        let text = GOLDSCHMIDT_LIKE.replace("ErgunWenYuDrag { alphac alpha.air; }", "DiFelice;");
        assert_eq!(read(&text).unwrap().0.drag, DragClosure::DiFelice);
    }

    #[test]
    fn unknown_drag_model_names_keyword_file_and_line() {
        for wrong in ["ErgunWenYuDrag2", "ergunWenYuDrag"] {
            let e = err(&GOLDSCHMIDT_LIKE.replace("ErgunWenYuDrag", wrong));
            assert_eq!(e.file.as_deref(), Some("constant/kinematicCloudProperties"));
            assert_eq!((e.line, e.col), (12, 9), "{e}");
            assert!(
                e.message
                    .starts_with(&format!("unknown drag model '{wrong}' in particleForces")),
                "{e}"
            );
            assert!(e.message.contains("PlessisMasliyahDrag"), "{e}");
        }
        let e = err(&GOLDSCHMIDT_LIKE.replace("ErgunWenYuDrag", "ErgunWenYuDarg"));
        assert!(
            e.message.starts_with(
                "unknown drag model 'ErgunWenYuDarg' in particleForces (did you mean \
                 'ErgunWenYuDrag'?)"
            ),
            "{e}"
        );
        let e = err(&GOLDSCHMIDT_LIKE.replace("gravity;", "gravty;"));
        assert!(
            e.message.starts_with(
                "unknown particle force 'gravty' in particleForces (did you mean 'gravity'?)"
            ),
            "{e}"
        );
        let e = err(&GOLDSCHMIDT_LIKE.replace("gravity;", "magnus;"));
        assert!(
            e.message.starts_with("unknown particle force 'magnus'"),
            "{e}"
        );
        assert_eq!((e.line, e.col), (13, 9), "{e}");
    }

    #[test]
    fn forces_fsim_cannot_compute_are_refused_at_their_keyword() {
        let e = err(&GOLDSCHMIDT_LIKE.replace("gravity;", "SRF;"));
        assert_eq!((e.line, e.col), (13, 9), "{e}");
        assert!(e.message.contains("rotating frame"), "{e}");
        let e = err(&GOLDSCHMIDT_LIKE.replace("gravity;", "WenYuDrag { alphac alpha.air; }"));
        assert!(e.message.contains("a second drag model 'WenYuDrag'"), "{e}");
        assert!(e.message.contains("line 12"), "{e}");
        let e = err(&GOLDSCHMIDT_LIKE.replace("ErgunWenYuDrag { alphac alpha.air; }", ""));
        assert!(
            e.message.starts_with("no drag closure in particleForces"),
            "{e}"
        );
        assert_eq!(e.line, 10, "{e}");
        let e =
            err(&GOLDSCHMIDT_LIKE.replace("gravity;", "gravity; pressureGradient { U U.water; }"));
        assert!(
            e.message
                .contains("expected the continuous phase's velocity U.air"),
            "{e}"
        );
    }

    #[test]
    fn dpmfoam_forces_become_the_coupling_s_fluid_forces() {
        let text = GOLDSCHMIDT_LIKE
            .replace(
                "gravity;",
                "gravity; pressureGradient { U U.air; } virtualMass { U U.air; Cvm 0.5; } \
                 SaffmanMeiLiftForce { U U.air; }",
            )
            .replace("U.air cell;", "U.air cell; DUcDt cellPoint; curlUcDt cell;");
        let (s, notes) = read(&text).unwrap();
        assert!(notes.is_empty(), "{notes:?}");
        assert!(s.pressure_gradient);
        assert_eq!(
            s.forces,
            FluidForces {
                pressure_gradient: true,
                virtual_mass: Some(0.5),
                lift: Some(crate::coupling::drag::LiftModel::SaffmanMei),
                acceleration_cell_point: true,
                curl_cell_point: false,
            }
        );
        assert!(s.summary().starts_with(
            "forces ErgunWenYuDrag + pressureGradient + virtualMass + SaffmanMeiLiftForce + \
             gravity;"
        ));
        let transport = Transport {
            phase: "air".into(),
            rho: 1.2,
            nu: 1e-5,
        };
        assert_eq!(s.settings(&transport, [0.0; 3]).forces, s.forces);
        // the paper form keeps its own −V ∇p: DPMFoam's pressureGradient is not added
        let (s, _) = read_with(&text, Some("dragLawCoeffs { form paper; }")).unwrap();
        assert!(s.pressure_gradient && !s.forces.pressure_gradient);
        // missing DUcDt / curlUcDt entries (DPMFoam stops): the cell's value, noted
        let (s, notes) = read(&text.replace(" DUcDt cellPoint; curlUcDt cell;", "")).unwrap();
        assert!(!s.forces.acceleration_cell_point && !s.forces.curl_cell_point);
        assert_eq!(notes.len(), 2, "{notes:?}");
        assert!(
            notes[0].contains("no interpolationSchemes entry DUcDt"),
            "{notes:?}"
        );
        assert!(
            notes[1].contains("no interpolationSchemes entry curlUcDt"),
            "{notes:?}"
        );
        let e = err(&text.replace("DUcDt cellPoint", "DUcDt cellPointFace"));
        assert!(e.message.contains("for DUcDt is not supported"), "{e}");
    }

    #[test]
    fn fraction_field_must_be_the_continuous_phases() {
        let e = err(&GOLDSCHMIDT_LIKE.replace("alphac alpha.air", "alphac alpha.water"));
        assert_eq!((e.line, e.col), (12, 33), "{e}");
        let e = err(&GOLDSCHMIDT_LIKE.replace("{ alphac alpha.air; }", "{ }"));
        assert!(e.message.contains("missing keyword 'alphac'"), "{e}");
        // sphereDrag has no fraction: no keyword needed
        let text = GOLDSCHMIDT_LIKE.replace("ErgunWenYuDrag { alphac alpha.air; }", "sphereDrag;");
        assert_eq!(read(&text).unwrap().0.drag, DragClosure::SphereDrag);
    }

    #[test]
    fn solution_keywords() {
        let e = err(&GOLDSCHMIDT_LIKE.replace(
            "cellValueSourceCorrection off",
            "cellValueSourceCorrection on",
        ));
        assert!(e.message.contains("cellValueSourceCorrection on"), "{e}");
        assert_eq!(e.line, 3);
        let e = err(&GOLDSCHMIDT_LIKE.replace("coupled true;", ""));
        assert!(e.message.contains("missing keyword 'coupled'"), "{e}");
        let e = err(&GOLDSCHMIDT_LIKE.replace("coupled true", "coupled false"));
        assert!(e.message.contains("one-way coupling"), "{e}");
        assert_eq!((e.line, e.col), (3, 26), "{e}");
        let (s, _) = read(&GOLDSCHMIDT_LIKE.replace("U semiImplicit 1;", "U explicit 1;")).unwrap();
        assert_eq!(s.source, SourceTreatment::Explicit);
        // DPMFoam scales the source by the coefficient; fsim does not, so it refuses one
        let e = err(&GOLDSCHMIDT_LIKE.replace("U semiImplicit 1;", "U explicit 0.5;"));
        assert!(
            e.message
                .contains("source-term coefficient 0.5: DPMFoam scales"),
            "{e}"
        );
        assert_eq!(e.line, 5, "{e}");
        let e = err(&GOLDSCHMIDT_LIKE.replace("U semiImplicit 1;", "U implicit 1;"));
        assert!(e.message.contains("found the word 'implicit'"), "{e}");
        let e = err(&GOLDSCHMIDT_LIKE.replace("U.air cell", "U.air cellPointFace"));
        assert!(e.message.contains("cellPointFace"), "{e}");
        let e = err(&GOLDSCHMIDT_LIKE.replace("mu.air cell", "mu.air cubic"));
        assert!(e.message.contains("unknown interpolation scheme"), "{e}");
        let text = GOLDSCHMIDT_LIKE.replace(
            "cellValueSourceCorrection off;",
            "cellValueSourceCorrection off; averagingMethod dual; maxCo 0.3;",
        );
        let (s, notes) = read(&text).unwrap();
        assert_eq!(s.void_fraction, VoidFraction::Trilinear);
        assert_eq!(notes.len(), 2, "{notes:?}");
        let e = err(&text.replace("averagingMethod dual", "averagingMethod moment"));
        assert!(e.message.contains("moment"), "{e}");
        let text = GOLDSCHMIDT_LIKE.replace(
            "sourceTerms",
            "integrationSchemes { U analytical; } sourceTerms",
        );
        let (s, notes) = read(&text).unwrap();
        assert_eq!(s.integration, ParticleIntegration::Analytical);
        assert!(
            notes[0].contains("integrationSchemes U analytical"),
            "{notes:?}"
        );
    }

    #[test]
    fn alpha_max_is_required_and_checked() {
        let e = err(&GOLDSCHMIDT_LIKE.replace("alphaMax 0.99;", ""));
        assert!(e.message.contains("missing keyword 'alphaMax'"), "{e}");
        let e = err(&GOLDSCHMIDT_LIKE.replace("alphaMax 0.99", "alphaMax 1.5"));
        assert!(e.message.contains("'alphaMax' = 1.5"), "{e}");
        assert_eq!((e.line, e.col), (7, 42), "{e}");
    }

    #[test]
    fn coupling_properties_choose_the_form_interpolation_and_void_fraction() {
        let (s, notes) = read_with(
            GOLDSCHMIDT_LIKE,
            Some(
                "model dragLaw;\ndragLawCoeffs { form paper; velocityInterpolation trilinear; \
                 voidFraction trilinear; colour red; }",
            ),
        )
        .unwrap();
        assert_eq!(s.form, VolumeAveragedForm::Paper);
        assert_eq!(s.velocity_interpolation, Interpolation::Trilinear);
        assert_eq!(s.void_fraction, VoidFraction::Trilinear);
        assert_eq!(notes.len(), 2, "{notes:?}");
        assert!(notes[0].contains("dragLawCoeffs.colour"), "{notes:?}");
        assert!(
            notes[1].contains("the paper form gives every particle"),
            "{notes:?}"
        );
        let e = read_with(GOLDSCHMIDT_LIKE, Some("dragLawCoeffs { form DPM; }")).unwrap_err();
        assert!(e.message.contains("expected one of DPMFoam, paper"), "{e}");
    }

    #[test]
    fn fixed_particles_is_the_drag_law_block_s_own_switch() {
        assert!(!read(GOLDSCHMIDT_LIKE).unwrap().0.fixed_particles);
        let (s, notes) = read_with(
            GOLDSCHMIDT_LIKE,
            Some("dragLawCoeffs { fixedParticles yes; }"),
        )
        .unwrap();
        assert!(s.fixed_particles);
        assert!(notes.is_empty(), "{notes:?}");
        // the direct model's block is not the drag-law model's
        let (s, _) = read_with(
            GOLDSCHMIDT_LIKE,
            Some("direct { fixedParticles yes; } dragLawCoeffs { }"),
        )
        .unwrap();
        assert!(!s.fixed_particles);
        assert!(read_with(
            GOLDSCHMIDT_LIKE,
            Some("dragLawCoeffs { fixedParticles 3; }")
        )
        .is_err());
    }
}
