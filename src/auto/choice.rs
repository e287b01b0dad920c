//! `model auto`'s decision: every candidate evaluated, the cheapest whose predicted error is
//! within the tolerance run, and the case changed to run it.

use super::candidate::{Candidate, Stepping, Verdict, DIRECT_RESOLUTIONS, DRAG_LAW_CELLS};
use super::scene::Scene;
use crate::case::cloud_properties::Cloud;
use crate::case::coupling::CouplingModel;
use crate::case::Case;
use crate::error::FsimError;
use crate::grid::Grid;
use std::fmt::Write;

/// What `model auto` chose, the table of candidates and the changes it made to the case.
#[derive(Clone, Debug)]
pub struct Choice {
    pub chosen: Candidate,
    pub candidates: Vec<Candidate>,
    /// The table and the reason, as printed.
    pub report: String,
    /// The case settings changed to run the choice.
    pub changes: Vec<String>,
}

/// The share of the tolerance convection may take when `model auto` turns it off: the rest is
/// left to the grid's error, which the candidates' table predicts.
const CONVECTION_SHARE: f64 = 0.1;

/// Oseen's first inertial correction to a sphere's Stokes drag, `F = F_St (1 + 3 Re_p/16)`
/// (Oseen 1910; Proudman & Pearson 1957): the relative change of the force that dropping the
/// advection term makes at `Re_p`. An upper estimate in periodic arrays, where the
/// correction starts at `O(Re_p²)` (docs/user-guide/choosing-a-model.md).
pub fn convection_effect(reynolds: f64) -> f64 {
    3.0 * reynolds / 16.0
}

/// A scheme valid for `model` (the case's when it is one), and its factor on `h²/(6ν)`.
fn scheme(case: &Case, model: CouplingModel) -> (&'static str, f64) {
    let named = case.time_scheme.as_deref().unwrap_or("");
    match (model, named) {
        (CouplingModel::DragLaw, "EulerImplicit") => ("EulerImplicit", f64::INFINITY),
        (CouplingModel::DragLaw, _) => ("Euler", 1.0),
        (_, "Euler") => ("Euler", 1.0),
        (_, "EulerRKC") => ("EulerRKC", f64::INFINITY),
        _ => ("RK3", 1.25),
    }
}

/// The case's cloud read as `model` would read it.
fn cloud_for(case: &Case, model: CouplingModel) -> Result<Option<Cloud>, FsimError> {
    let mut trial = case.clone();
    trial.coupling.model = model;
    Ok(Cloud::from_case(&trial)?)
}

/// Evaluates the candidates of `case` (`model auto`), changes the case to run the chosen one
/// (model, grid, scheme, step control) and says what it did; a case no candidate can run
/// within the tolerance is refused with the table.
pub fn choose(case: &mut Case) -> Result<Choice, FsimError> {
    let tolerance = case.coupling.auto_tolerance.unwrap_or(0.05);
    let direct_cloud = cloud_for(case, CouplingModel::Direct);
    let drag_cloud = cloud_for(case, CouplingModel::DragLaw);
    let unavailable =
        |r: &Result<Option<Cloud>, FsimError>| r.as_ref().err().map(|e| first_line(&e.to_string()));
    let (direct_unavailable, drag_unavailable) =
        (unavailable(&direct_cloud), unavailable(&drag_cloud));
    let drag_fixed = matches!(&drag_cloud,
        Ok(Some(c)) if c.drag_law.as_ref().is_some_and(|o| o.fixed_particles));
    let cloud = match (direct_cloud, drag_cloud) {
        (Ok(Some(c)), _) | (_, Ok(Some(c))) => c,
        (Err(e), _) => return Err(e),
        _ => {
            return Err(FsimError::input(
                "constant/couplingProperties: model auto chooses how particles and fluid are \
                 coupled, and this case has no particles (no active \
                 constant/kinematicCloudProperties); use model none",
            ))
        }
    };
    let mut scene = Scene::from_case(case, &cloud)?;
    scene.fixed |= drag_fixed;
    let control = &case.control;
    let cap = if control.adjust_time_step {
        control.max_delta_t
    } else {
        control.delta_t
    };
    let stepping = |model| Stepping {
        cap,
        max_co: if control.adjust_time_step {
            control.max_co
        } else {
            1.0
        },
        viscous_factor: scheme(case, model).1,
    };
    let mut candidates = Vec::new();
    for &r_over_h in &DIRECT_RESOLUTIONS {
        let mut c = Candidate::direct(&scene, r_over_h, stepping(CouplingModel::Direct), tolerance);
        if let Some(why) = &direct_unavailable {
            c.verdict = Verdict::Unavailable(why.clone());
        }
        if !candidates
            .iter()
            .any(|o: &Candidate| o.model == c.model && o.cells == c.cells)
        {
            candidates.push(c);
        }
    }
    for &h_over_d in &DRAG_LAW_CELLS {
        let mut c = Candidate::drag_law(
            &scene,
            h_over_d,
            stepping(CouplingModel::DragLaw),
            tolerance,
        );
        if let Some(why) = &drag_unavailable {
            c.verdict = Verdict::Unavailable(why.clone());
        }
        // coarse grids of small domains coincide: one candidate per grid
        if !candidates
            .iter()
            .any(|o: &Candidate| o.model == c.model && o.cells == c.cells)
        {
            candidates.push(c);
        }
    }
    let chosen = candidates
        .iter()
        .filter(|c| c.verdict == Verdict::Meets)
        .min_by(|a, b| a.time.total_cmp(&b.time))
        .cloned();
    let mut report = table(&scene, &candidates, tolerance);
    let Some(chosen) = chosen else {
        let best = candidates
            .iter()
            .filter(|c| !matches!(c.verdict, Verdict::Unavailable(_)))
            .min_by(|a, b| a.error.total_cmp(&b.error));
        let hint = best.map_or(String::new(), |b| {
            format!(
                "; the smallest predicted error is {:.1} % ({}, about {})",
                100.0 * b.error,
                b.label(),
                duration(b.time)
            )
        });
        return Err(FsimError::input(format!(
            "constant/couplingProperties: model auto finds no candidate within tolerance \
             {tolerance}{hint}: raise tolerance, or choose the model and grid yourself\n{report}"
        )));
    };
    let other = candidates
        .iter()
        .filter(|c| c.model != chosen.model && !matches!(c.verdict, Verdict::Unavailable(_)))
        .min_by(|a, b| a.error.total_cmp(&b.error));
    let _ = write!(
        report,
        "chosen: {} on {}x{}x{} cells: the cheapest candidate within {:.3} % ({:.2} % \
         predicted, about {} on one thread)",
        chosen.label(),
        chosen.cells[0],
        chosen.cells[1],
        chosen.cells[2],
        100.0 * tolerance,
        100.0 * chosen.error,
        duration(chosen.time)
    );
    if let Some(o) = other {
        let _ = write!(
            report,
            "; the {} model's best is {:.2} % ({}, about {})",
            o.model.name(),
            100.0 * o.error,
            o.label(),
            duration(o.time)
        );
    }
    report.push('\n');
    let changes = apply(case, &chosen, &scene, tolerance)?;
    Ok(Choice {
        chosen,
        candidates,
        report,
        changes,
    })
}

/// Changes `case` to run `chosen`: the model, the block's cells (domain and patches kept),
/// a scheme the model takes, convection off where it is below a tenth of the `tolerance`
/// (direct model), and an adjustable step when a fixed `deltaT` is above the candidate's
/// bound.
fn apply(
    case: &mut Case,
    chosen: &Candidate,
    scene: &Scene,
    tolerance: f64,
) -> Result<Vec<String>, FsimError> {
    let mut changes = Vec::new();
    case.coupling.model = chosen.model;
    let grid = &case.mesh.grid;
    if grid.n != chosen.cells {
        if !scene.uniform_fields {
            return Err(FsimError::input(format!(
                "model auto chose {} on {}x{}x{} cells, but the initial fields are not \
                 uniform and cannot be moved to another grid: set blocks to ({} {} {}) in \
                 system/blockMeshDict, or choose the model yourself",
                chosen.label(),
                chosen.cells[0],
                chosen.cells[1],
                chosen.cells[2],
                chosen.cells[0],
                chosen.cells[1],
                chosen.cells[2]
            )));
        }
        let length = grid.length();
        let h = [0, 1, 2].map(|a| length[a] / chosen.cells[a] as f64);
        changes.push(format!(
            "grid {}x{}x{} instead of blockMeshDict's {}x{}x{} (the same domain and patches)",
            chosen.cells[0], chosen.cells[1], chosen.cells[2], grid.n[0], grid.n[1], grid.n[2]
        ));
        case.mesh.grid = Grid::new(chosen.cells, h, grid.origin);
    }
    let (name, _) = scheme(case, chosen.model);
    if case.time_scheme.as_deref().unwrap_or("RK3") != name {
        changes.push(format!(
            "timeScheme {name} (the {} model's)",
            chosen.model.name()
        ));
        case.time_scheme = Some(name.to_string());
    }
    let effect = convection_effect(scene.reynolds);
    if chosen.model == CouplingModel::Direct
        && case.convection
        && effect <= CONVECTION_SHARE * tolerance
    {
        changes.push(format!(
            "convection off (the unsteady Stokes equation): at Re_p {:.2e} advection changes \
             the force by about 3 Re_p/16 = {:.2e} %, within a tenth of the tolerance",
            scene.reynolds,
            100.0 * effect
        ));
        case.convection = false;
    }
    let control = &mut case.control;
    if !control.adjust_time_step && control.delta_t > chosen.step {
        changes.push(format!(
            "adjustTimeStep yes with maxDeltaT {:e} s: deltaT {:e} s is above the chosen \
             grid's bound ({:.3e} s)",
            control.delta_t, control.delta_t, chosen.step
        ));
        control.adjust_time_step = true;
        control.max_delta_t = control.delta_t;
        control.delta_t = chosen.step;
    }
    Ok(changes)
}

/// The candidates as a table.
fn table(scene: &Scene, candidates: &[Candidate], tolerance: f64) -> String {
    let mut t = format!(
        "model auto: tolerance {:.3} % on the particles' force or settling velocity; {} \
         particle(s), phi {:.3} where they are, {}, Re_p {:.2e}\n  {:<18} {:>14} {:>11} {:>9} {:>10} {:>9}  {}\n",
        100.0 * tolerance,
        scene.particles,
        scene.phi,
        if scene.fixed { "held in place" } else { "free" },
        scene.reynolds,
        "candidate",
        "cells",
        "error",
        "steps",
        "time",
        "memory",
        "verdict"
    );
    for c in candidates {
        let verdict = match &c.verdict {
            Verdict::Meets => "within tolerance".to_string(),
            Verdict::Inaccurate => "error above tolerance".to_string(),
            Verdict::Unavailable(why) => format!("not available: {why}"),
        };
        let _ = writeln!(
            t,
            "  {:<18} {:>14} {:>10.2}% {:>9.0} {:>10} {:>7.0}MB  {}",
            c.label(),
            format!("{}x{}x{}", c.cells[0], c.cells[1], c.cells[2]),
            100.0 * c.error,
            c.steps,
            duration(c.time),
            c.memory_mb,
            verdict
        );
    }
    t
}

fn duration(seconds: f64) -> String {
    if seconds < 120.0 {
        format!("{seconds:.1} s")
    } else if seconds < 7200.0 {
        format!("{:.0} min", seconds / 60.0)
    } else {
        format!("{:.1} h", seconds / 3600.0)
    }
}

fn first_line(text: &str) -> String {
    let line = text.lines().next().unwrap_or("");
    line.chars().take(160).collect()
}
