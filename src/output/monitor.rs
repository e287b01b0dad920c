//! Per-step monitors, `postProcessing/<name>/<startTime>/<name>.dat`, in the layout of
//! OpenFOAM's function objects: a `# ` header line naming the columns, then one
//! whitespace-separated row per call. A run continued from a later start time writes into its
//! own `<startTime>` directory, so no earlier record is touched; a run started again from the
//! same start time replaces that run's file.
//!
//! The file is created without following a link anywhere below the case ([`SafeDir`]): a
//! link in the way is refused, never written through.
//!
//! Rows are buffered and flushed at least once a second (and when the monitor is dropped), so
//! `tail -f` and a plotting script see progress without a system call per step.

use super::output_error::OutputError;
use super::safe_dir::SafeDir;
use super::time_name::format_general;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Significant digits of monitor values: enough for charts and convergence checks, short
/// enough to read (`%.12g`).
const VALUE_DIGITS: usize = 12;
const FLUSH_INTERVAL: Duration = Duration::from_secs(1);

/// An open monitor file.
pub struct Monitor {
    path: PathBuf,
    out: BufWriter<File>,
    columns: usize,
    last_flush: Instant,
}

impl Monitor {
    /// Creates `<case>/postProcessing/<name>/<start_time_name>/<name>.dat` with its header.
    /// Column names must be single words (the file is whitespace-separated).
    pub fn create(
        case_dir: &Path,
        name: &str,
        start_time_name: &str,
        columns: &[&str],
    ) -> Result<Self, OutputError> {
        let dir = case_dir
            .join("postProcessing")
            .join(name)
            .join(start_time_name);
        let path = dir.join(format!("{name}.dat"));
        if name.is_empty() || name.contains(['/', '\\']) {
            return Err(OutputError::invalid(
                &path,
                "monitor name must be a plain word",
            ));
        }
        if columns.is_empty() {
            return Err(OutputError::invalid(
                &path,
                "a monitor needs at least one column",
            ));
        }
        if let Some(bad) = columns
            .iter()
            .find(|c| c.is_empty() || c.chars().any(char::is_whitespace))
        {
            return Err(OutputError::invalid(
                &path,
                format!("column name `{bad}` must be one word without spaces"),
            ));
        }
        let file = SafeDir::open_case(case_dir)?
            .create_dir_all(&["postProcessing", name, start_time_name])?
            .create_file(format!("{name}.dat"))?;
        let mut out = BufWriter::new(file);
        writeln!(out, "# {}", columns.join("\t"))
            .and_then(|_| out.flush())
            .map_err(|e| OutputError::io(&path, "cannot write", e))?;
        Ok(Monitor {
            path,
            out,
            columns: columns.len(),
            last_flush: Instant::now(),
        })
    }

    /// Appends one row; `values` must have one value per column.
    pub fn row(&mut self, values: &[f64]) -> Result<(), OutputError> {
        if values.len() != self.columns {
            return Err(OutputError::invalid(
                &self.path,
                format!(
                    "monitor row has {} values for {} columns",
                    values.len(),
                    self.columns
                ),
            ));
        }
        let io_err = |e| OutputError::io(&self.path, "cannot write", e);
        for (i, v) in values.iter().enumerate() {
            let separator = if i == 0 { "" } else { "\t" };
            write!(self.out, "{separator}{}", format_value(*v)).map_err(io_err)?;
        }
        self.out.write_all(b"\n").map_err(io_err)?;
        if self.last_flush.elapsed() >= FLUSH_INTERVAL {
            self.flush()?;
        }
        Ok(())
    }

    /// Pushes buffered rows to the file now.
    pub fn flush(&mut self) -> Result<(), OutputError> {
        self.last_flush = Instant::now();
        self.out
            .flush()
            .map_err(|e| OutputError::io(&self.path, "cannot write", e))
    }

    /// The monitor's file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

impl Drop for Monitor {
    fn drop(&mut self) {
        let _ = self.out.flush();
    }
}

/// A monitor value as `%.12g` (`0.1`, `1.5e-07`, `nan`, `inf`), which numpy and Python read.
pub fn format_value(v: f64) -> String {
    format_general(v, VALUE_DIGITS)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_support::ScratchDir;
    use std::fs;

    #[test]
    fn header_and_rows_follow_the_function_object_layout() {
        let case = ScratchDir::new("monitor");
        let mut m =
            Monitor::create(case.path(), "fluidStats", "0", &["Time", "deltaT", "Co"]).unwrap();
        m.row(&[0.1, 1e-4, 0.5]).unwrap();
        m.row(&[0.2, 2.5e-7, f64::NAN]).unwrap();
        assert!(m.row(&[1.0]).is_err());
        let path = m.path().to_path_buf();
        drop(m);
        assert!(path.ends_with("postProcessing/fluidStats/0/fluidStats.dat"));
        let text = fs::read_to_string(&path).unwrap();
        assert_eq!(
            text,
            "# Time\tdeltaT\tCo\n0.1\t0.0001\t0.5\n0.2\t2.5e-07\tnan\n"
        );
    }

    #[test]
    fn a_continued_run_writes_a_new_start_time_directory() {
        let case = ScratchDir::new("monitor-restart");
        let mut first = Monitor::create(case.path(), "m", "0", &["Time"]).unwrap();
        first.row(&[0.5]).unwrap();
        drop(first);
        let mut second = Monitor::create(case.path(), "m", "0.5", &["Time"]).unwrap();
        second.row(&[0.6]).unwrap();
        second.flush().unwrap();
        let first = fs::read_to_string(case.path().join("postProcessing/m/0/m.dat")).unwrap();
        let second = fs::read_to_string(case.path().join("postProcessing/m/0.5/m.dat")).unwrap();
        assert_eq!(first, "# Time\n0.5\n");
        assert_eq!(second, "# Time\n0.6\n");
    }

    #[test]
    fn bad_names_are_refused() {
        let case = ScratchDir::new("monitor-bad");
        assert!(Monitor::create(case.path(), "m", "0", &["mean U"]).is_err());
        assert!(Monitor::create(case.path(), "a/b", "0", &["t"]).is_err());
        assert!(Monitor::create(case.path(), "m", "0", &[]).is_err());
    }
}
