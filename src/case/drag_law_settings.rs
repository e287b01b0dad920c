//! The drag-law model's settings, read from DPMFoam's `constant/kinematicCloudProperties` (and
//! fsim's optional `dragLawCoeffs` in `constant/couplingProperties`), typed for the coupling
//! code.
//!
//! What each DPMFoam keyword becomes (the full list, with the keywords fsim refuses, is in the
//! README, section "DPMFoam cases"):
//!
//! * `solution.coupled` → [`DragLawSettings::coupled`]: two-way coupling (the particles'
//!   reaction force and volume enter the fluid) or one-way.
//! * `solution.sourceTerms.schemes.U explicit|semiImplicit c` → [`SourceTreatment`]. OpenFOAM
//!   reads `c` as an under-relaxation factor that only steady clouds use; fsim's clouds are
//!   transient, so any `c` is accepted and a value other than 1 is noted.
//! * `solution.interpolationSchemes.U.<phase>` → [`DragLawSettings::velocity_interpolation`]:
//!   `cell` (the value of the particle's cell) or `cellPoint` (OpenFOAM's cell-and-point
//!   interpolation); fsim's `trilinear` (paper eq. 14–15) only through `dragLawCoeffs`.
//!   `rho.<phase>` and `mu.<phase>` are constants of fsim's fluid, so any of OpenFOAM's schemes is
//!   accepted for them (interpolating a constant gives the constant).
//! * `solution.averagingMethod basic|dual` → [`VoidFraction`]: `basic` is DPMFoam's own rule
//!   (a particle's volume counts in its cell only, which DPMFoam applies whatever this keyword
//!   says: the keyword is read by MPPICFoam's models); `dual`, OpenFOAM's averaging on the dual
//!   (point) mesh, is taken as fsim's closest equivalent, the trilinear spreading of paper
//!   eq. 16. Absent: `basic`, as DPMFoam does.
//! * `solution.integrationSchemes.U Euler|analytical` → [`ParticleIntegration`].
//! * `constantProperties.alphaMax` → [`DragLawSettings::alpha_max`]: the fluid fraction never
//!   drops below `1 − alphaMax` (DPMFoam's `alphacMin`).
//! * `subModels.particleForces`: one drag closure ([`DragModel`]), `gravity`,
//!   `pressureGradient`. DPMFoam's `pressureGradient` force is `m (ρ_c/ρ_p) DU_c/Dt`, the
//!   fluid's material acceleration at the particle, which equals −∇p/ρ_c + ν∇²u_c + g for the
//!   fluid (paper eq. 10 up to the viscous term).
//!
//! fsim's own `dragLawCoeffs { velocityInterpolation cell|cellPoint|trilinear; voidFraction
//! cell|trilinear; }` in `constant/couplingProperties` overrides the interpolation and the ε
//! rule, so that the same case runs with DPMFoam's choices or with the paper's.

use super::control_dict::{at_value, choice};
use super::dictionary::{Dict, Entry};
use super::error::CaseError;

/// The drag closures fsim knows: OpenFOAM v1912's four, as DPMFoam computes them, and the
/// modern ones CFD-DEM codes offer (fsim's own keywords).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DragModel {
    /// `sphereDrag`: the single-sphere law (Schiller–Naumann form), no ε dependence.
    Sphere,
    /// `WenYuDrag`: Wen & Yu (1966), the single-sphere law times `ε^-2.65`.
    WenYu,
    /// `ErgunWenYuDrag`: Ergun (1952) for `ε < 0.8`, Wen & Yu above (the paper's eq. 11–12).
    ErgunWenYu,
    /// `PlessisMasliyahDrag`: du Plessis & Masliyah (1988).
    PlessisMasliyah,
    /// `DiFeliceDrag` (fsim): Di Felice (1994).
    DiFelice,
    /// `BeetstraDrag` (fsim): Beetstra, van der Hoef & Kuipers (2007).
    Beetstra,
    /// `TennetiDrag` (fsim): Tenneti, Garg & Subramaniam (2011).
    Tenneti,
    /// `KochHillDrag` (fsim): Koch & Hill (2001).
    KochHill,
    /// `GidaspowDrag` (fsim): Gidaspow (1994), Ergun below ε = 0.8, Wen & Yu above.
    Gidaspow,
}

impl DragModel {
    /// Every closure, in the order of [`DragModel::keyword`]'s list.
    pub const ALL: [DragModel; 9] = [
        DragModel::Sphere,
        DragModel::WenYu,
        DragModel::ErgunWenYu,
        DragModel::PlessisMasliyah,
        DragModel::DiFelice,
        DragModel::Beetstra,
        DragModel::Tenneti,
        DragModel::KochHill,
        DragModel::Gidaspow,
    ];

    /// The keyword naming the closure in `particleForces`.
    pub fn keyword(self) -> &'static str {
        match self {
            DragModel::Sphere => "sphereDrag",
            DragModel::WenYu => "WenYuDrag",
            DragModel::ErgunWenYu => "ErgunWenYuDrag",
            DragModel::PlessisMasliyah => "PlessisMasliyahDrag",
            DragModel::DiFelice => "DiFeliceDrag",
            DragModel::Beetstra => "BeetstraDrag",
            DragModel::Tenneti => "TennetiDrag",
            DragModel::KochHill => "KochHillDrag",
            DragModel::Gidaspow => "GidaspowDrag",
        }
    }

    pub fn from_keyword(word: &str) -> Option<DragModel> {
        DragModel::ALL.into_iter().find(|m| m.keyword() == word)
    }

    /// Whether OpenFOAM v1912 knows the closure (the others are fsim's keywords: a case using
    /// them no longer runs under DPMFoam).
    pub fn is_openfoam(self) -> bool {
        matches!(
            self,
            DragModel::Sphere
                | DragModel::WenYu
                | DragModel::ErgunWenYu
                | DragModel::PlessisMasliyah
        )
    }

    /// Whether the closure depends on the fluid fraction (all but `sphereDrag`); OpenFOAM's
    /// closures of this kind name the fraction field with `alphac`.
    pub fn uses_fluid_fraction(self) -> bool {
        self != DragModel::Sphere
    }
}

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
    /// The paper's eq. 16: spread to the 8 nearest cell centres with trilinear weights.
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

/// Everything the drag-law model needs from the case, besides the particles and the fluid.
#[derive(Clone, Debug, PartialEq)]
pub struct DragLawSettings {
    /// The continuous phase's name (`air`), from `transportProperties`.
    pub phase: String,
    /// The drag closure of `particleForces`; `None` when none is listed (no drag).
    pub drag: Option<DragModel>,
    /// `gravity` listed in `particleForces` (gravity with buoyancy `1 − ρ_f/ρ_p`).
    pub gravity: bool,
    /// `pressureGradient` listed in `particleForces`.
    pub pressure_gradient: bool,
    /// `solution.coupled`: the fluid feels the particles (two-way) or not (one-way).
    pub coupled: bool,
    /// `sourceTerms.schemes.U`.
    pub source: SourceTreatment,
    /// `constantProperties.alphaMax`: ε ≥ 1 − alphaMax.
    pub alpha_max: f64,
    /// The fluid velocity at a particle.
    pub velocity_interpolation: Interpolation,
    /// ε from the particles.
    pub void_fraction: VoidFraction,
    /// `integrationSchemes.U`.
    pub integration: ParticleIntegration,
}

impl DragLawSettings {
    /// DPMFoam's Goldschmidt choices: no drag closure yet, explicit source, cell ε,
    /// `cellPoint` velocity, `alphaMax 0.99`. For tests and programmatic set-ups.
    pub fn new(phase: &str) -> DragLawSettings {
        DragLawSettings {
            phase: phase.to_string(),
            drag: None,
            gravity: true,
            pressure_gradient: false,
            coupled: true,
            source: SourceTreatment::Explicit,
            alpha_max: 0.99,
            velocity_interpolation: Interpolation::CellPoint,
            void_fraction: VoidFraction::Cell,
            integration: ParticleIntegration::Euler,
        }
    }

    /// The lower bound of the fluid fraction, `1 − alphaMax` (DPMFoam's `alphacMin`).
    pub fn min_fluid_fraction(&self) -> f64 {
        1.0 - self.alpha_max
    }

    /// Reads the settings from the cloud file `cloud` (DPMFoam's `kinematicCloudProperties`)
    /// and fsim's `couplingProperties` when present; `phase` is the continuous phase's name.
    /// Settings fsim reads but that have no effect go to `notes`; settings that would change
    /// the physics in a way fsim cannot honour are errors at their place.
    pub fn read(
        cloud: &Dict,
        coupling: Option<&Dict>,
        phase: &str,
        notes: &mut Vec<String>,
    ) -> Result<DragLawSettings, CaseError> {
        let solution = cloud.get_dict("solution")?;
        let coupled = solution.get_bool_or("coupled", false)?;
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
        let source = source_treatment(solution, notes)?;
        let mut velocity_interpolation = interpolation_schemes(solution, phase)?;
        let mut void_fraction = averaging_method(solution, notes)?;
        let integration = particle_integration(solution)?;

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

        if let Some(own) = coupling
            .map(|c| c.opt_dict("dragLawCoeffs"))
            .transpose()?
            .flatten()
        {
            {
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
                    void_fraction = match choice(own, "voidFraction", &["cell", "trilinear"], None)?
                    {
                        0 => VoidFraction::Cell,
                        _ => VoidFraction::Trilinear,
                    };
                }
                for (key, loc) in own.unused() {
                    let (line, col) = loc.line_col();
                    notes.push(format!(
                        "{}:{line}:{col}: ignored keyword 'dragLawCoeffs.{key}' (fsim does not \
                         use it)",
                        loc.file.display
                    ));
                }
            }
        }

        Ok(DragLawSettings {
            phase: phase.to_string(),
            drag: forces.drag,
            gravity: forces.gravity,
            pressure_gradient: forces.pressure_gradient,
            coupled,
            source,
            alpha_max,
            velocity_interpolation,
            void_fraction,
            integration,
        })
    }

    /// One line for the log and `-dry-run`.
    pub fn summary(&self) -> String {
        let mut forces = Vec::new();
        if let Some(d) = self.drag {
            forces.push(d.keyword());
        }
        if self.pressure_gradient {
            forces.push("pressureGradient");
        }
        if self.gravity {
            forces.push("gravity");
        }
        format!(
            "forces {}; {}; source {}; U interpolation {}; void fraction {}; alphaMax {}",
            if forces.is_empty() {
                "none".to_string()
            } else {
                forces.join(" + ")
            },
            if self.coupled { "two-way" } else { "one-way" },
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
fn source_treatment(
    solution: &Dict,
    notes: &mut Vec<String>,
) -> Result<SourceTreatment, CaseError> {
    let Some(terms) = solution.opt_dict("sourceTerms")? else {
        return Ok(SourceTreatment::Explicit);
    };
    terms.lookup("resetOnStartup");
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
        let (line, col) = coefficient.loc.line_col();
        notes.push(format!(
            "{}:{line}:{col}: source-term relaxation coefficient {c}: not used (OpenFOAM \
             applies it to steady clouds only; fsim's clouds are transient)",
            coefficient.loc.file.display
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

/// `interpolationSchemes`: the velocity's scheme (`cell` when absent, OpenFOAM's default for
/// a cloud); the density's and viscosity's are checked to be OpenFOAM's names only.
fn interpolation_schemes(solution: &Dict, phase: &str) -> Result<Interpolation, CaseError> {
    let Some(schemes) = solution.opt_dict("interpolationSchemes")? else {
        return Ok(Interpolation::Cell);
    };
    let velocity = velocity_name(phase);
    let mut result = Interpolation::Cell;
    for e in schemes.entries() {
        let field = e.keyword();
        let constant = field == format!("rho.{phase}")
            || field == format!("mu.{phase}")
            || field == format!("alpha.{phase}")
            || (phase.is_empty() && ["rho", "mu", "alpha"].contains(&field));
        if field != velocity && !constant {
            continue; // other fields (DUcDt, …): left to the ignored-keyword notes
        }
        e.mark_used();
        let item = super::dictionary::single_token(e, "an interpolation scheme")?;
        let word = item.as_word().unwrap_or("");
        if field == velocity {
            result = match word {
                "cell" => Interpolation::Cell,
                "cellPoint" => Interpolation::CellPoint,
                _ => {
                    return Err(CaseError::at(
                        &item.loc,
                        format!(
                            "interpolation scheme {} for {velocity} is not supported by fsim: \
                             expected cell or cellPoint (or fsim's trilinear, set in \
                             constant/couplingProperties dragLawCoeffs.velocityInterpolation)",
                            item.describe()
                        ),
                    ))
                }
            };
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
fn velocity_name(phase: &str) -> String {
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

/// Forces OpenFOAM v1912 offers that fsim does not compute, with the reason given.
const REFUSED_FORCES: [(&str, &str); 9] = [
    (
        "nonSphereDrag",
        "the drag of non-spherical particles is not supported by fsim",
    ),
    (
        "distortedSphereDrag",
        "the drag of distorted droplets is not supported by fsim",
    ),
    (
        "virtualMass",
        "the added-mass force is not supported by fsim",
    ),
    (
        "SaffmanMeiLiftForce",
        "lift forces are not supported by fsim",
    ),
    ("TomiyamaLiftForce", "lift forces are not supported by fsim"),
    ("paramagnetic", "magnetic forces are not supported by fsim"),
    (
        "nonInertialFrame",
        "a non-inertial frame is not supported by fsim",
    ),
    ("SRF", "a rotating frame is not supported by fsim"),
    ("interface", "interface forces are not supported by fsim"),
];

/// The forces of `particleForces`, checked.
pub(crate) struct ParticleForces {
    pub drag: Option<DragModel>,
    pub gravity: bool,
    pub pressure_gradient: bool,
    /// Every force listed, in file order.
    pub names: Vec<String>,
}

impl ParticleForces {
    /// Reads and checks `subModels.particleForces`: an unknown force, a force fsim cannot
    /// compute or a second drag closure is an error at its keyword.
    pub(crate) fn read(sub: &Dict, phase: &str) -> Result<ParticleForces, CaseError> {
        let mut forces = ParticleForces {
            drag: None,
            gravity: false,
            pressure_gradient: false,
            names: Vec::new(),
        };
        let Some(list) = sub.opt_dict("particleForces")? else {
            return Ok(forces);
        };
        let mut drag_at: Option<&Entry> = None;
        for e in list.entries() {
            let name = e.keyword();
            e.mark_used();
            forces.names.push(name.to_string());
            if let Some(model) = DragModel::from_keyword(name) {
                if let Some(first) = drag_at {
                    let (line, _) = first.key_loc.line_col();
                    return Err(CaseError::at(
                        &e.key_loc,
                        format!(
                            "a second drag model '{name}' (the first, '{}', is on line {line}): \
                             DPMFoam would add both forces; fsim takes one drag closure",
                            first.keyword()
                        ),
                    ));
                }
                drag_at = Some(e);
                if let Some(coeffs) = e.as_dict() {
                    if model.uses_fluid_fraction() {
                        fraction_field(coeffs, "alphac", phase, model.is_openfoam())?;
                    }
                }
                forces.drag = Some(model);
            } else if name == "gravity" {
                forces.gravity = true;
            } else if name == "pressureGradient" {
                if let Some(coeffs) = e.as_dict() {
                    let velocity = velocity_name(phase);
                    if let Some(u) = coeffs.opt_word("U")? {
                        if u != velocity {
                            return Err(at_value(
                                coeffs,
                                "U",
                                format!(
                                    "pressureGradient U '{u}': expected the continuous phase's \
                                     velocity {velocity}"
                                ),
                            ));
                        }
                    }
                }
                forces.pressure_gradient = true;
            } else if let Some((_, why)) = REFUSED_FORCES.iter().find(|(n, _)| *n == name) {
                return Err(CaseError::at(
                    &e.key_loc,
                    format!("particle force '{name}': {why}"),
                ));
            } else {
                let drags: Vec<&str> = DragModel::ALL.iter().map(|m| m.keyword()).collect();
                let what = if name.to_ascii_lowercase().contains("drag") {
                    "unknown drag model"
                } else {
                    "unknown particle force"
                };
                return Err(CaseError::at(
                    &e.key_loc,
                    format!(
                        "{what} '{name}' in particleForces: expected a drag model ({}), \
                         gravity or pressureGradient",
                        drags.join(", ")
                    ),
                ));
            }
        }
        Ok(forces)
    }
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

    const GOLDSCHMIDT_LIKE: &str = "\
solution
{
    active true; coupled true; transient yes; cellValueSourceCorrection off;
    interpolationSchemes { rho.air cell; U.air cellPoint; mu.air cell; }
    integrationSchemes { U Euler; }
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

    fn read(text: &str) -> Result<(DragLawSettings, Vec<String>), CaseError> {
        let d = parse_dict(text, "constant/kinematicCloudProperties").unwrap();
        let mut notes = Vec::new();
        DragLawSettings::read(&d, None, "air", &mut notes).map(|s| (s, notes))
    }

    fn err(text: &str) -> CaseError {
        read(text).unwrap_err()
    }

    #[test]
    fn goldschmidt_settings() {
        let (s, notes) = read(GOLDSCHMIDT_LIKE).unwrap();
        assert_eq!(
            s,
            DragLawSettings {
                phase: "air".into(),
                drag: Some(DragModel::ErgunWenYu),
                gravity: true,
                pressure_gradient: false,
                coupled: true,
                source: SourceTreatment::SemiImplicit,
                alpha_max: 0.99,
                velocity_interpolation: Interpolation::CellPoint,
                void_fraction: VoidFraction::Cell,
                integration: ParticleIntegration::Euler,
            }
        );
        assert!(notes.is_empty(), "{notes:?}");
        assert!((s.min_fluid_fraction() - 0.01).abs() < 1e-15);
        assert_eq!(
            s.summary(),
            "forces ErgunWenYuDrag + gravity; two-way; source semiImplicit; U interpolation \
             cellPoint; void fraction cell; alphaMax 0.99"
        );
    }

    #[test]
    fn every_closure_keyword_round_trips() {
        for m in DragModel::ALL {
            assert_eq!(DragModel::from_keyword(m.keyword()), Some(m));
            let text = GOLDSCHMIDT_LIKE.replace("ErgunWenYuDrag", m.keyword());
            assert_eq!(read(&text).unwrap().0.drag, Some(m));
        }
        assert_eq!(DragModel::from_keyword("ergunWenYuDrag"), None);
    }

    #[test]
    fn unknown_drag_model_names_keyword_file_and_line() {
        let e = err(&GOLDSCHMIDT_LIKE.replace("ErgunWenYuDrag", "ErgunWenYuDrag2"));
        assert_eq!(e.file.as_deref(), Some("constant/kinematicCloudProperties"));
        assert_eq!((e.line, e.col), (13, 9), "{e}");
        assert!(
            e.message
                .starts_with("unknown drag model 'ErgunWenYuDrag2' in particleForces"),
            "{e}"
        );
        assert!(e.message.contains("PlessisMasliyahDrag"), "{e}");
        let e = err(&GOLDSCHMIDT_LIKE.replace("gravity;", "magnus;"));
        assert!(
            e.message.starts_with("unknown particle force 'magnus'"),
            "{e}"
        );
        assert_eq!((e.line, e.col), (14, 9), "{e}");
    }

    #[test]
    fn forces_fsim_cannot_compute_are_refused_at_their_keyword() {
        let e = err(&GOLDSCHMIDT_LIKE.replace("gravity;", "virtualMass { Cvm 0.5; }"));
        assert_eq!((e.line, e.col), (14, 9), "{e}");
        assert!(e.message.contains("added-mass"), "{e}");
        let e = err(&GOLDSCHMIDT_LIKE.replace("gravity;", "WenYuDrag { alphac alpha.air; }"));
        assert!(e.message.contains("a second drag model 'WenYuDrag'"), "{e}");
        assert!(e.message.contains("line 13"), "{e}");
    }

    #[test]
    fn fraction_field_must_be_the_continuous_phases() {
        let e = err(&GOLDSCHMIDT_LIKE.replace("alphac alpha.air", "alphac alpha.water"));
        assert_eq!((e.line, e.col), (13, 33), "{e}");
        let e = err(&GOLDSCHMIDT_LIKE.replace("{ alphac alpha.air; }", "{ }"));
        assert!(e.message.contains("missing keyword 'alphac'"), "{e}");
        // sphereDrag has no fraction: no keyword needed
        let text = GOLDSCHMIDT_LIKE.replace("ErgunWenYuDrag { alphac alpha.air; }", "sphereDrag;");
        assert_eq!(read(&text).unwrap().0.drag, Some(DragModel::Sphere));
    }

    #[test]
    fn solution_keywords() {
        let e = err(&GOLDSCHMIDT_LIKE.replace(
            "cellValueSourceCorrection off",
            "cellValueSourceCorrection on",
        ));
        assert!(e.message.contains("cellValueSourceCorrection on"), "{e}");
        assert_eq!(e.line, 3);
        let (s, notes) =
            read(&GOLDSCHMIDT_LIKE.replace("U semiImplicit 1;", "U explicit 0.5;")).unwrap();
        assert_eq!(s.source, SourceTreatment::Explicit);
        assert!(notes[0].contains("relaxation coefficient 0.5"), "{notes:?}");
        let e = err(&GOLDSCHMIDT_LIKE.replace("U semiImplicit 1;", "U implicit 1;"));
        assert!(e.message.contains("found the word 'implicit'"), "{e}");
        let e = err(&GOLDSCHMIDT_LIKE.replace("U.air cellPoint", "U.air cellPointFace"));
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
        let (s, _) = read(&GOLDSCHMIDT_LIKE.replace("U Euler", "U analytical")).unwrap();
        assert_eq!(s.integration, ParticleIntegration::Analytical);
    }

    #[test]
    fn alpha_max_is_required_and_checked() {
        let e = err(&GOLDSCHMIDT_LIKE.replace("alphaMax 0.99;", ""));
        assert!(e.message.contains("missing keyword 'alphaMax'"), "{e}");
        let e = err(&GOLDSCHMIDT_LIKE.replace("alphaMax 0.99", "alphaMax 1.5"));
        assert!(e.message.contains("'alphaMax' = 1.5"), "{e}");
        assert_eq!((e.line, e.col), (8, 42), "{e}");
    }

    #[test]
    fn coupling_properties_override_the_interpolation_and_void_fraction() {
        let cloud = parse_dict(GOLDSCHMIDT_LIKE, "constant/kinematicCloudProperties").unwrap();
        let coupling = parse_dict(
            "model dragLaw;\ndragLawCoeffs { velocityInterpolation trilinear; voidFraction \
             trilinear; colour red; }",
            "constant/couplingProperties",
        )
        .unwrap();
        let mut notes = Vec::new();
        let s = DragLawSettings::read(&cloud, Some(&coupling), "air", &mut notes).unwrap();
        assert_eq!(s.velocity_interpolation, Interpolation::Trilinear);
        assert_eq!(s.void_fraction, VoidFraction::Trilinear);
        assert_eq!(notes.len(), 1);
        assert!(notes[0].contains("dragLawCoeffs.colour"), "{notes:?}");
    }
}
