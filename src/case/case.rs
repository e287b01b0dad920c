//! The whole case: every file read and validated before the first step.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use super::block_mesh::{BlockMesh, BoxFace};
use super::control_dict::{time_name, ControlDict, StartFrom, StopAt, WriteControl};
use super::coupling::Coupling;
use super::dictionary::Dict;
use super::drag_law_options::fraction_name;
use super::error::CaseError;
use super::fields::Fields;
use super::fraction_field::check_fraction_field;
use super::fv_options::{read_fv_options, MeanVelocityForce};
use super::transport::Transport;
use super::turbulence::{check_laminar, turbulence_file};
use crate::output::{list_time_directories, TimeEntry, RESTART_FILE_NAME};

/// A validated case directory.
#[derive(Clone, Debug)]
pub struct Case {
    /// The case directory as given.
    pub dir: PathBuf,
    pub control: ControlDict,
    /// `system/controlDict` as parsed (its `functions` are kept for the function objects).
    pub control_dict: Dict,
    pub mesh: BlockMesh,
    pub transport: Transport,
    /// Gravity from `constant/g` (zero when the file is absent), m/s².
    pub gravity: [f64; 3],
    /// Initial fields and boundary conditions.
    pub fields: Fields,
    /// `meanVelocityForce` sources from `system/fvOptions` or `constant/fvOptions`.
    pub mean_velocity_forces: Vec<MeanVelocityForce>,
    pub coupling: Coupling,
    /// `fsim { timeScheme …; }` in `system/fvSolution`, unvalidated (the solver checks it).
    pub time_scheme: Option<String>,
    /// `fsim { convection off; }` in `system/fvSolution` turns the advection term off (the
    /// unsteady Stokes equation); on by default. `model auto` turns it off at low Re_p.
    pub convection: bool,
    /// `system/fvSolution`, when present.
    pub fv_solution: Option<Dict>,
    /// `constant/kinematicCloudProperties`, when present (read by the particle code).
    pub cloud_properties: Option<Dict>,
    /// Notes for the user: ignored keywords (each once), ignored settings.
    pub warnings: Vec<String>,
}

/// Whether a file exists, plain or gzipped.
fn exists(path: &Path) -> bool {
    path.exists() || PathBuf::from(format!("{}.gz", path.display())).exists()
}

impl Case {
    /// Reads and validates the case in `dir`; the initial fields come from the directory
    /// [`Case::initial_time_dir`] names.
    pub fn load(dir: &Path) -> Result<Case, CaseError> {
        Case::load_at(dir, None)
    }

    /// As [`Case::load`], reading the fields from time directory `time` when given.
    pub fn load_at(dir: &Path, time: Option<&str>) -> Result<Case, CaseError> {
        if !dir.is_dir() {
            return Err(CaseError::plain(format!(
                "case directory '{}' does not exist",
                dir.display()
            )));
        }
        let mut warnings = Vec::new();
        let mut read_dicts: Vec<Dict> = Vec::new();
        let read = |rel: &str| Dict::read(&dir.join(rel), Some(dir));
        let optional = |rel: &str| -> Result<Option<Dict>, CaseError> {
            if exists(&dir.join(rel)) {
                read(rel).map(Some)
            } else {
                Ok(None)
            }
        };

        let control_dict = read("system/controlDict")?;
        let mut control = ControlDict::from_dict(&control_dict, &mut warnings)?;
        // Function objects are for a later stage; they are kept, not reported.
        if let Some(f) = control_dict.lookup("functions").and_then(|e| e.as_dict()) {
            f.mark_all_used();
        }

        let mesh_dict = read("system/blockMeshDict")?;
        let mesh = BlockMesh::from_dict(&mesh_dict)?;
        read_dicts.push(mesh_dict);

        let transport_dict = read("constant/transportProperties")?;
        let transport = Transport::from_dict(&transport_dict)?;
        read_dicts.push(transport_dict);

        let gravity = match optional("constant/g")? {
            Some(g) => {
                let value = g.get_vector("value")?;
                g.lookup("dimensions");
                read_dicts.push(g);
                value
            }
            None => [0.0; 3],
        };

        let time = match time {
            Some(t) => t.to_string(),
            None => {
                let name = Case::initial_time_dir(dir, &control, &transport.velocity_name())?;
                if dir.join(&name).join("lagrangian").is_dir() {
                    return Err(CaseError::plain(format!(
                        "{name}/lagrangian: the start time holds an OpenFOAM cloud's state, \
                         which fsim does not read (it would inject the particles afresh); \
                         start from a time without it"
                    )));
                }
                // OpenFOAM starts `firstTime` and `latestTime` at their directory's time (a
                // restart's own time replaces it when the solver restores one)
                if control.start_from != StartFrom::StartTime {
                    if let Ok(t) = name.parse::<f64>() {
                        control.start_time = t;
                    }
                }
                name
            }
        };
        let (fields, field_dicts) =
            Fields::read(dir, &time, &transport.velocity_name(), &mesh, &mut warnings)?;
        read_dicts.push(field_dicts.u);
        read_dicts.push(field_dicts.p);

        // DPMFoam's turbulence file: laminar only. The fluid fraction: its conditions only.
        let turbulence_file = turbulence_file(&transport.phase);
        if let Some(t) = optional(&turbulence_file)? {
            check_laminar(&t)?;
            read_dicts.push(t);
        }
        let fraction = format!("{time}/{}", fraction_name(&transport.phase));
        if let Some(alpha) = optional(&fraction)? {
            check_fraction_field(&alpha, &mesh, &mut warnings)?;
            read_dicts.push(alpha);
        }

        let mut mean_velocity_forces = Vec::new();
        let system_options = optional("system/fvOptions")?;
        let constant_options = optional("constant/fvOptions")?;
        if system_options.is_some() && constant_options.is_some() {
            // OpenFOAM's fv::options looks in constant/ first
            warnings
                .push("system/fvOptions: ignored, constant/fvOptions is read instead".to_string());
        }
        if let Some(opts) = constant_options.or(system_options) {
            mean_velocity_forces = read_fv_options(&opts, &transport.velocity_name())?;
            read_dicts.push(opts);
        }

        let cloud_properties = optional("constant/kinematicCloudProperties")?;
        let coupling = Coupling::new(
            optional("constant/couplingProperties")?,
            cloud_properties.is_some(),
            &mut warnings,
        )?;

        let fv_solution = optional("system/fvSolution")?;
        let mut convection = true;
        let time_scheme = match &fv_solution {
            Some(s) => match s.opt_dict("fsim")? {
                Some(fsim) => {
                    let scheme = fsim.opt_word("timeScheme")?;
                    convection = fsim.get_bool_or("convection", true)?;
                    for (key, loc) in fsim.unused() {
                        let (line, col) = loc.line_col();
                        warnings.push(format!(
                            "{}:{line}:{col}: ignored keyword 'fsim.{key}' (fsim does not use it)",
                            s.file()
                        ));
                    }
                    scheme
                }
                None => None,
            },
            None => None,
        };

        read_dicts.insert(0, control_dict);
        warnings.extend(unused_keywords(&read_dicts));
        let control_dict = read_dicts.remove(0);
        Ok(Case {
            dir: dir.to_path_buf(),
            control,
            control_dict,
            mesh,
            transport,
            gravity,
            fields,
            mean_velocity_forces,
            coupling,
            time_scheme,
            convection,
            fv_solution,
            cloud_properties,
            warnings,
        })
    }

    /// The time directory whose fields start the run, as OpenFOAM's `startFrom` chooses it:
    /// `startTime`'s name; for `firstTime` the earliest time directory holding the velocity
    /// file; for `latestTime` the latest time directory, or, when that holds fsim's restart
    /// state and no velocity file (a directory fsim wrote), the earliest holding the velocity
    /// file (its boundary conditions; the solver restores the state). A latest directory with
    /// neither is an error: starting elsewhere would overwrite it.
    pub fn initial_time_dir(
        dir: &Path,
        control: &ControlDict,
        velocity: &str,
    ) -> Result<String, CaseError> {
        if control.start_from == StartFrom::StartTime {
            return Ok(time_name(control.start_time, control.time_precision));
        }
        let times = list_time_directories(dir).map_err(|e| CaseError::plain(e.to_string()))?;
        let holds_velocity = |name: &str| exists(&dir.join(name).join(velocity));
        let earliest_with_velocity = || {
            times
                .iter()
                .find(|t| holds_velocity(&t.name))
                .map_or_else(|| "0".to_string(), |t| t.name.clone())
        };
        if control.start_from == StartFrom::FirstTime {
            return Ok(earliest_with_velocity());
        }
        let Some(TimeEntry { name, .. }) = times.last() else {
            return Ok("0".to_string());
        };
        if holds_velocity(name) {
            Ok(name.clone())
        } else if dir.join(name).join(RESTART_FILE_NAME).exists() {
            Ok(earliest_with_velocity())
        } else {
            Err(CaseError::plain(format!(
                "startFrom latestTime: the latest time directory '{name}' holds neither \
                 {velocity} nor fsim's {RESTART_FILE_NAME}, so the run cannot start from it \
                 (and would overwrite it from an earlier time); give it those fields, remove \
                 it, or set startFrom startTime"
            )))
        }
    }

    /// One line for `-dry-run`: grid, patches, fluid, time and coupling.
    pub fn summary(&self) -> String {
        let g = &self.mesh.grid;
        let faces: Vec<String> = BoxFace::ALL
            .iter()
            .map(|&f| {
                let p = self.mesh.patch_on(f);
                format!("{f} {} ({})", p.name, p.kind.name())
            })
            .collect();
        let write = match self.control.write_control {
            WriteControl::TimeStep => format!("every {} steps", self.control.write_interval),
            WriteControl::RunTime | WriteControl::AdjustableRunTime => {
                format!("every {} s", self.control.write_interval)
            }
            WriteControl::ClockTime => {
                format!("every {} s of wall time", self.control.write_interval)
            }
            WriteControl::CpuTime => format!("every {} s of CPU time", self.control.write_interval),
        };
        let phase = if self.transport.phase.is_empty() {
            String::new()
        } else {
            format!(" {}", self.transport.phase)
        };
        format!(
            "grid {}x{}x{} = {} cells, h = ({} {} {}) m; patches: {}; fluid{phase}: \
             rho = {} kg/m3, nu = {} m2/s; t = {} .. {}, deltaT = {} s{}; write {write}; \
             coupling {}",
            g.n[0],
            g.n[1],
            g.n[2],
            g.cell_count(),
            short(g.h[0]),
            short(g.h[1]),
            short(g.h[2]),
            faces.join(", "),
            short(self.transport.rho),
            short(self.transport.nu),
            short(self.control.start_time),
            match self.control.stop_at {
                StopAt::EndTime => format!("{} s", short(self.control.end_time)),
                stop => format!("stopAt {}", stop.name()),
            },
            short(self.control.delta_t),
            if self.control.adjust_time_step {
                format!(" (adjustable, maxCo {})", self.control.max_co)
            } else {
                String::new()
            },
            self.coupling.model.name(),
        )
    }

    /// An error located at the `fsim { timeScheme …; }` value of `system/fvSolution`, for the
    /// solver's own check of the scheme's name.
    pub fn time_scheme_error(&self, message: impl Into<String>) -> CaseError {
        let at = self
            .fv_solution
            .as_ref()
            .and_then(|s| s.peek("fsim"))
            .and_then(|e| e.as_dict())
            .and_then(|f| f.peek("timeScheme"))
            .map(|e| e.value_loc().clone());
        match at {
            Some(loc) => CaseError::at(&loc, message),
            None => CaseError::in_file("system/fvSolution", message),
        }
    }
}

/// A number with 6 significant digits, as OpenFOAM prints it.
fn short(x: f64) -> String {
    time_name(x, 6)
}

/// One note per ignored keyword and file, at its first place, with the number of times seen
/// (`phi` in every patch is one note).
fn unused_keywords(dicts: &[Dict]) -> Vec<String> {
    let mut notes = Vec::new();
    for d in dicts {
        let mut seen: BTreeMap<String, (String, usize)> = BTreeMap::new();
        let mut order = Vec::new();
        for (key, loc) in d.unused() {
            let leaf = key.rsplit('.').next().unwrap_or(&key).to_string();
            let (line, col) = loc.line_col();
            let place = format!("{}:{line}:{col}", loc.file.display);
            match seen.get_mut(&leaf) {
                Some((_, n)) => *n += 1,
                None => {
                    order.push(leaf.clone());
                    seen.insert(leaf, (place, 1));
                }
            }
        }
        for leaf in order {
            let (place, n) = &seen[&leaf];
            let times = if *n > 1 {
                format!(", {n} times")
            } else {
                String::new()
            };
            notes.push(format!(
                "{place}: ignored keyword '{leaf}' (fsim does not use it{times})"
            ));
        }
    }
    notes
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::parse_dict;

    #[test]
    fn a_case_can_be_shared_between_threads() {
        fn shareable<T: Send + Sync>() {}
        shareable::<Case>();
        shareable::<CaseError>();
    }

    #[test]
    fn an_ignored_keyword_is_noted_once_per_file() {
        let d = parse_dict(
            "a { phi phi.air; type x; }\nb { phi phi.air; type y; }\nc 1;",
            "0/U.air",
        )
        .unwrap();
        for k in ["a", "b"] {
            d.get_dict(k).unwrap().get_word("type").unwrap();
        }
        let notes = unused_keywords(&[d]);
        assert_eq!(
            notes,
            [
                "0/U.air:1:5: ignored keyword 'phi' (fsim does not use it, 2 times)",
                "0/U.air:3:1: ignored keyword 'c' (fsim does not use it)",
            ]
        );
    }
}
