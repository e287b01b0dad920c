//! Command line in OpenFOAM's spelling: `fsimFoam -case DIR -dry-run -threads 2`.
//!
//! OpenFOAM utilities take long options with one dash; clap wants two. [`normalise_args`]
//! rewrites the one-dash spellings of fsim's own options before clap sees them, so `-case`
//! and `--case` both work, while short clusters like `-h` keep their meaning.

use clap::Parser;
use std::path::PathBuf;

/// Particles in a fluid at the particle scale: direct (resolved) and drag-law (CFD-DEM) models
/// on OpenFOAM-style case directories.
#[derive(Parser, Debug, Clone)]
#[command(name = "fsimFoam", version, about, long_about = None)]
pub struct Options {
    /// Case directory (holds system/, constant/, 0/)
    #[arg(long = "case", value_name = "DIR", default_value = ".")]
    pub case: PathBuf,

    /// Validate the case and print the plan (grid, patches, time steps, write times, memory
    /// and run time, from a few steps timed in memory) without writing anything
    #[arg(long = "dry-run")]
    pub dry_run: bool,

    /// Number of threads (default: all cores; at most 4 per core, docs/security.md)
    #[arg(long = "threads", value_name = "N")]
    pub threads: Option<usize>,

    /// Most memory the run may need, as 4G, 512M or bytes (default: the memory available;
    /// docs/security.md)
    #[arg(long = "memory", value_name = "SIZE", value_parser = crate::memory::parse_size)]
    pub memory: Option<u64>,

    /// Most time steps controlDict may plan (default 1e9; docs/security.md)
    #[arg(long = "maxSteps", value_name = "N", value_parser = positive_count)]
    pub max_steps: Option<f64>,

    /// Most time directories controlDict may plan (default 1e6; docs/security.md)
    #[arg(long = "maxWrites", value_name = "N", value_parser = positive_count)]
    pub max_writes: Option<f64>,
}

/// A limit given on the command line: a finite number of at least 1 (`1e12` allowed).
fn positive_count(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(n) if n.is_finite() && n >= 1.0 => Ok(n),
        _ => Err("expected a finite number of at least 1".to_string()),
    }
}

impl Options {
    /// The plan limits the options give, the defaults for those not given.
    pub fn plan_limits(&self) -> crate::case::control_dict::PlanLimits {
        let default = crate::case::control_dict::PlanLimits::default();
        crate::case::control_dict::PlanLimits {
            steps: self.max_steps.unwrap_or(default.steps),
            writes: self.max_writes.unwrap_or(default.writes),
        }
    }
}

/// Long options that OpenFOAM users type with a single dash.
const LONG_OPTIONS: [&str; 8] = [
    "case",
    "dry-run",
    "threads",
    "memory",
    "maxSteps",
    "maxWrites",
    "help",
    "version",
];

/// Turn `-case` into `--case` (and `-case=DIR` into `--case=DIR`) for fsim's long options.
pub fn normalise_args<I: IntoIterator<Item = String>>(args: I) -> Vec<String> {
    args.into_iter()
        .enumerate()
        .map(|(position, arg)| {
            if position == 0 || !arg.starts_with('-') || arg.starts_with("--") {
                return arg;
            }
            let name = arg[1..].split('=').next().unwrap_or("");
            if LONG_OPTIONS.contains(&name) {
                format!("-{arg}")
            } else {
                arg
            }
        })
        .collect()
}

impl Options {
    /// Parse the process arguments; clap prints help/version or a usage error (exit 2) itself.
    pub fn from_env() -> Self {
        Options::parse_from(normalise_args(std::env::args()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(args: &[&str]) -> Result<Options, clap::Error> {
        Options::try_parse_from(normalise_args(args.iter().map(|s| s.to_string())))
    }

    #[test]
    fn openfoam_spelling_and_gnu_spelling_agree() {
        let one = parse(&["fsimFoam", "-case", "tutorials/cavity", "-threads", "2"]).unwrap();
        let two = parse(&["fsimFoam", "--case", "tutorials/cavity", "--threads=2"]).unwrap();
        assert_eq!(one.case, two.case);
        assert_eq!(one.threads, Some(2));
        assert_eq!(two.threads, Some(2));
        assert!(parse(&["fsimFoam", "-dry-run"]).unwrap().dry_run);
        assert_eq!(parse(&["fsimFoam"]).unwrap().case, PathBuf::from("."));
        let limits = parse(&["fsimFoam", "-maxSteps", "2e9", "--maxWrites=10"]).unwrap();
        assert_eq!(
            (limits.max_steps, limits.max_writes),
            (Some(2e9), Some(10.0))
        );
        assert!(parse(&["fsimFoam", "-maxSteps", "inf"]).is_err());
        assert!(parse(&["fsimFoam", "-maxWrites", "0"]).is_err());
        assert_eq!(
            parse(&["fsimFoam", "-memory", "4G"]).unwrap().memory,
            Some(4 << 30)
        );
        assert!(parse(&["fsimFoam", "-memory", "lots"]).is_err());
    }

    #[test]
    fn unknown_options_are_usage_errors() {
        let err = parse(&["fsimFoam", "-parallel"]).unwrap_err();
        assert_eq!(err.exit_code(), 2);
        let err = parse(&["fsimFoam", "-threads", "two"]).unwrap_err();
        assert_eq!(err.exit_code(), 2);
    }

    #[test]
    fn a_case_path_starting_with_a_dash_is_left_alone() {
        let args = normalise_args(["fsimFoam", "-case", "-odd"].iter().map(|s| s.to_string()));
        assert_eq!(args, vec!["fsimFoam", "--case", "-odd"]);
    }
}
