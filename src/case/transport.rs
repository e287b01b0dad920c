//! `constant/transportProperties`: the fluid's density and kinematic viscosity.

use super::control_dict::at_value;
use super::dictionary::Dict;
use super::error::CaseError;

/// The continuous phase.
///
/// Pressures in `0/p` are kinematic (p/ρ, m²/s²) in both forms, as in OpenFOAM's
/// incompressible solvers and DPMFoam.
#[derive(Clone, Debug, PartialEq)]
pub struct Transport {
    /// The phase name (`air` for `U.air`); empty in the plain icoFoam form (`U`).
    pub phase: String,
    /// Density, kg/m³ (1 in the icoFoam form, which has none).
    pub rho: f64,
    /// Kinematic viscosity, m²/s.
    pub nu: f64,
}

impl Transport {
    /// Reads the DPMFoam form (`continuousPhase air; rho.air 1.2; nu 1e-05;`, or `nu.air`
    /// in place of `nu`) or the plain
    /// icoFoam form (`nu [0 2 -1 0 0 0 0] 0.01;`).
    pub fn from_dict(d: &Dict) -> Result<Transport, CaseError> {
        let phase = d.get_word_or("continuousPhase", "")?;
        let rho = if phase.is_empty() {
            d.get_scalar_or("rho", 1.0)?
        } else {
            d.get_scalar(&format!("rho.{phase}"))?
        };
        let rho_key = if phase.is_empty() {
            "rho".to_string()
        } else {
            format!("rho.{phase}")
        };
        if rho.is_nan() || rho <= 0.0 {
            return Err(at_value(
                d,
                &rho_key,
                format!("expected a positive density for '{rho_key}', found {rho}"),
            ));
        }
        // DPMFoam v1912 reads `nu`; `nu.<phase>` is accepted when `nu` is absent.
        let phase_nu = format!("nu.{phase}");
        let nu_key = if !phase.is_empty() && !d.contains("nu") && d.contains(&phase_nu) {
            phase_nu.as_str()
        } else {
            "nu"
        };
        d.check_dimensions(
            &rho_key,
            [1.0, -3.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            "kg/m³, a density",
        )?;
        d.check_dimensions(
            nu_key,
            [0.0, 2.0, -1.0, 0.0, 0.0, 0.0, 0.0],
            "m²/s, a kinematic viscosity",
        )?;
        let nu = d.get_scalar(nu_key)?;
        if nu.is_nan() || nu <= 0.0 {
            return Err(at_value(
                d,
                nu_key,
                format!("expected a positive kinematic viscosity for '{nu_key}', found {nu}"),
            ));
        }
        if let Some(model) = d.opt_word("transportModel")? {
            if model != "Newtonian" {
                return Err(at_value(
                    d,
                    "transportModel",
                    format!("expected transportModel Newtonian (fsim's fluid is Newtonian), found {model}"),
                ));
            }
        }
        Ok(Transport { phase, rho, nu })
    }

    /// The velocity field's name: `U.<phase>`, or `U` without a phase.
    pub fn velocity_name(&self) -> String {
        if self.phase.is_empty() {
            "U".to_string()
        } else {
            format!("U.{}", self.phase)
        }
    }

    /// Dynamic viscosity μ = ρ ν.
    pub fn mu(&self) -> f64 {
        self.rho * self.nu
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::parse_dict;

    #[test]
    fn both_forms() {
        let d = parse_dict("continuousPhase air; rho.air 1.2; nu 1e-05;", "t").unwrap();
        let t = Transport::from_dict(&d).unwrap();
        assert_eq!((t.phase.as_str(), t.rho, t.nu), ("air", 1.2, 1e-5));
        assert_eq!(t.velocity_name(), "U.air");
        assert!((t.mu() - 1.2e-5).abs() < 1e-20);
        let d = parse_dict("nu [0 2 -1 0 0 0 0] 0.01;", "t").unwrap();
        let t = Transport::from_dict(&d).unwrap();
        assert_eq!((t.phase.as_str(), t.rho, t.nu), ("", 1.0, 0.01));
        assert_eq!(t.velocity_name(), "U");
        let d = parse_dict("continuousPhase air; rho.air 1.2; nu.air 2e-05;", "t").unwrap();
        assert_eq!(Transport::from_dict(&d).unwrap().nu, 2e-5);
        // both: DPMFoam's `nu` wins (nu.air is then listed as ignored by the case)
        let d = parse_dict(
            "continuousPhase air; rho.air 1.2; nu 1e-5; nu.air 2e-5;",
            "t",
        )
        .unwrap();
        assert_eq!(Transport::from_dict(&d).unwrap().nu, 1e-5);
        let d = parse_dict("continuousPhase air; rho.air 1.2; nu.air -2e-05;", "t").unwrap();
        let e = Transport::from_dict(&d).unwrap_err();
        assert!(e.message.contains("'nu.air'"), "{e}");
        let d = parse_dict("continuousPhase air; rho.air 1.2;", "t").unwrap();
        assert!(Transport::from_dict(&d)
            .unwrap_err()
            .message
            .contains("'nu'"));
    }

    #[test]
    fn negative_viscosity_points_at_the_value() {
        let d = parse_dict("continuousPhase air;\nrho.air 1.2;\nnu   -1e-5;", "t").unwrap();
        let e = Transport::from_dict(&d).unwrap_err();
        assert_eq!((e.line, e.col), (3, 6));
        assert!(e.message.contains("positive kinematic viscosity"));
        // Past the dimension set, in both the current and the old (`nu nu [..] x`) form.
        let d = parse_dict("nu [0 2 -1 0 0 0 0] -0.01;", "t").unwrap();
        let e = Transport::from_dict(&d).unwrap_err();
        assert_eq!((e.line, e.col), (1, 21), "{e}");
        let d = parse_dict("rho [1 -3 0 0 0 0 0] 0;\nnu nu [0 2 -1 0 0 0 0] 1;", "t").unwrap();
        let e = Transport::from_dict(&d).unwrap_err();
        assert_eq!((e.line, e.col), (1, 22), "{e}");
        assert!(e.message.contains("positive density"), "{e}");
    }
}
