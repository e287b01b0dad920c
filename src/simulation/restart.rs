//! The restart state of a run: written at each time directory, read back when a case
//! continues (`startFrom latestTime`) so that the continuation is bit-identical.

use super::coupling::Coupling;
use super::particles::Particles;
use super::simulation::{time_axis, Simulation};
use crate::case::Cloud;
use crate::error::FsimError;
use crate::fluid::FluidSolver;
use crate::output::{RestartHeader, RestartState};
use crate::particles::{Dem, DemSnapshot};

impl Simulation {
    /// Restores the fluid and the time axis from the restart state in `time_dir`, and
    /// returns the state for the particles and the coupling.
    pub(super) fn restore(
        &mut self,
        time_dir: &std::path::Path,
        control: &crate::case::ControlDict,
    ) -> Result<RestartState, FsimError> {
        let path = time_dir.join(crate::output::RESTART_FILE_NAME);
        let state = RestartState::read(&path).map_err(|e| FsimError::input(e.to_string()))?;
        for name in FluidSolver::RESTART_NAMES {
            let data = state.array(name).ok_or_else(|| {
                FsimError::input(format!("{}: no array '{name}'", path.display()))
            })?;
            self.fluid
                .restore_array(name, data)
                .map_err(|e| FsimError::input(format!("{}: {e}", path.display())))?;
        }
        let header = &state.header;
        self.time = time_axis(header.time, header.step, control);
        self.dt = header.delta_t;
        self.largest_dt = header.delta_t;
        Ok(state)
    }

    /// Writes the restart state (every array a bit-identical continuation needs) to file
    /// `name` of `dir`.
    pub fn write_restart(
        &mut self,
        dir: &crate::output::SafeDir,
        name: &str,
    ) -> Result<(), FsimError> {
        let header = RestartHeader::new(self.time.time, self.time.step, self.dt);
        let cloud = self
            .coupling
            .particles()
            .map(|p| p.dem.snapshot().to_arrays())
            .unwrap_or_default();
        let model = match &self.coupling {
            Coupling::Direct(direct) => direct.restart_arrays(),
            _ => Vec::new(),
        };
        let mut arrays = self.fluid.restart_arrays();
        arrays.extend(cloud.iter().map(|(name, v)| (*name, v.as_slice())));
        arrays.extend(model.iter().map(|(name, v)| (*name, v.as_slice())));
        header
            .write(dir, name, &arrays)
            .map_err(|e| FsimError::run(e.to_string()))
    }
}

/// The engine continued from the DEM arrays of a restart state (same config and box, from the
/// case).
pub(super) fn restore_particles(
    cloud: Cloud,
    state: &RestartState,
    time_dir: &std::path::Path,
) -> Result<Particles, FsimError> {
    let path = time_dir.join(crate::output::RESTART_FILE_NAME);
    let snapshot = DemSnapshot::from_arrays(|name| state.array(name))
        .map_err(|e| FsimError::input(format!("{}: {e}", path.display())))?;
    let dem = Dem::restore(cloud.config.clone(), cloud.domain.clone(), &snapshot)
        .map_err(|e| FsimError::input(format!("{}: {e}", path.display())))?;
    Ok(Particles::new(cloud, dem))
}
