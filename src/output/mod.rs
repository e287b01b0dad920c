//! Everything fsim writes: time directories with VTK fields and restart state, the collection
//! file at the case root, monitors in `postProcessing/`, and the OpenFOAM-style log.

mod case_output;
mod collection;
mod fluid_vti;
mod fluid_vtk;
mod log;
mod monitor;
mod output_error;
mod particle_vtu;
mod restart_state;
mod safe_dir;
mod time_directory;
mod time_name;

pub use case_output::{
    check_no_links_where_written, write_fluid, CaseOutput, FLUID_VTI_FILE_NAME,
    FLUID_VTK_FILE_NAME, PARTICLE_FILE_NAME, RESTART_FILE_NAME,
};
pub use collection::{collection_path, rebuild_collection, write_collection, CollectionEntry};
pub use fluid_vti::write_fluid_vti;
pub use fluid_vtk::{write_fluid_vtk, CellData};
pub use log::{cpu_time_seconds, peak_resident_bytes, Banner, Log};
pub use monitor::{format_value, Monitor};
pub use output_error::OutputError;
pub use particle_vtu::{write_particles_vtu, ParticleFields, PointData};
pub use restart_state::{RestartHeader, RestartState};
pub use safe_dir::{first_link_below, symlink_refused, EntryKind, SafeDir};
pub use time_directory::{
    latest_time, list_time_directories, purge_write, remove_partial_time_directories, time_value,
    TimeDirectory, TimeEntry,
};
pub use time_name::{format_general, time_name, DEFAULT_TIME_PRECISION};

#[cfg(test)]
pub(crate) mod test_support;
