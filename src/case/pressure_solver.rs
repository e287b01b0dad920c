//! The pressure solver's stopping test from `system/fvSolution`, as DPMFoam reads it.
//!
//! DPMFoam solves `p` with `nCorrectors` PISO correctors per step: every corrector but the
//! last with the `p` entry of `solvers`, the last with `pFinal`. fsim's drag-law model makes
//! one pressure solve per step, the one that leaves the step's velocity divergence-free, so it
//! takes the final corrector's entry: `pFinal` (keywords may be quoted patterns, as
//! `"(p|kinematicCloud:theta)Final"`), or `p` when there is none. Of that entry fsim uses
//! `tolerance` (default 1e-6), `relTol` (default 0) and `maxIter` (default: fsim's 500), with
//! OpenFOAM's normalised residual ([`crate::fluid::Convergence::OpenFoam`]); `solver`,
//! `smoother`, `preconditioner` and the rest name OpenFOAM's own solvers (fsim always runs its
//! preconditioned conjugate gradients).

use super::dictionary::Dict;
use super::error::CaseError;

/// The stopping test of the pressure solve.
#[derive(Clone, Debug, PartialEq)]
pub struct PressureSolverControls {
    /// Which entry of `solvers` it came from (`pFinal` or `p`).
    pub entry: String,
    pub tolerance: f64,
    pub rel_tol: f64,
    pub max_iter: Option<usize>,
}

impl PressureSolverControls {
    /// The controls of `solvers { pFinal | p { … } }` in `fv_solution`; `None` without such
    /// an entry (fsim then keeps its own test). Negative numbers are refused at their place.
    pub fn from_fv_solution(fv_solution: &Dict) -> Result<Option<Self>, CaseError> {
        let Some(solvers) = fv_solution.opt_dict("solvers")? else {
            return Ok(None);
        };
        let Some((entry, dict)) = ["pFinal", "p"].into_iter().find_map(|name| {
            solvers
                .peek(name)
                .map(|_| (name, solvers.opt_dict(name).transpose()))
        }) else {
            return Ok(None);
        };
        let dict = dict.expect("peeked")?;
        let number = |key: &str, default: f64| -> Result<f64, CaseError> {
            let value = dict.get_scalar_or(key, default)?;
            if value < 0.0 || !value.is_finite() {
                let loc = dict.peek(key).expect("read above").value_loc();
                return Err(CaseError::at(
                    loc,
                    format!("'{key}' of the pressure solver must be a number ≥ 0, got {value}"),
                ));
            }
            Ok(value)
        };
        let tolerance = number("tolerance", 1e-6)?;
        let rel_tol = number("relTol", 0.0)?;
        let max_iter = dict.opt_label("maxIter")?;
        // The names of OpenFOAM's solvers and smoothers say nothing fsim can honour.
        dict.mark_all_used();
        Ok(Some(PressureSolverControls {
            entry: entry.to_string(),
            tolerance,
            rel_tol,
            max_iter,
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::parse_dict;

    fn controls(text: &str) -> Result<Option<PressureSolverControls>, CaseError> {
        let dict = parse_dict(text, "system/fvSolution").unwrap();
        PressureSolverControls::from_fv_solution(&dict)
    }

    #[test]
    fn final_entry_first_then_p_then_none() {
        // Goldschmidt's form: quoted patterns, pFinal with relTol 0.
        let c = controls(
            "solvers { \"(p|kinematicCloud:theta)\" { solver GAMG; tolerance 1e-06; \
             relTol 0.01; } \"(p|kinematicCloud:theta)Final\" { solver GAMG; \
             tolerance 1e-07; relTol 0; maxIter 50; } }",
        )
        .unwrap()
        .unwrap();
        assert_eq!(c.entry, "pFinal");
        assert_eq!((c.tolerance, c.rel_tol, c.max_iter), (1e-7, 0.0, Some(50)));
        // fsim's tutorials' form: pFinal copies p by macro and overrides relTol.
        let c = controls(
            "solvers { p { solver GAMG; tolerance 1e-6; relTol 0.01; } \
             pFinal { $p; relTol 0; } }",
        )
        .unwrap()
        .unwrap();
        assert_eq!((c.tolerance, c.rel_tol, c.max_iter), (1e-6, 0.0, None));
        let c = controls("solvers { p { solver PCG; relTol 0.05; } }")
            .unwrap()
            .unwrap();
        assert_eq!(c.entry, "p");
        assert_eq!((c.tolerance, c.rel_tol), (1e-6, 0.05));
        assert!(controls("solvers { U { tolerance 1e-5; } }")
            .unwrap()
            .is_none());
        assert!(controls("PIMPLE { nCorrectors 2; }").unwrap().is_none());
    }

    #[test]
    fn a_negative_tolerance_is_refused_at_its_place() {
        let e = controls("solvers\n{\n    pFinal { tolerance -1e-6; }\n}\n").unwrap_err();
        let report = e.report();
        assert!(report.contains("system/fvSolution:3:"), "{report}");
        assert!(report.contains("tolerance"), "{report}");
    }
}
