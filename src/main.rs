//! `fsimFoam`: parse the command line, run the case, and exit with 0 (success), 2 (bad input,
//! nothing written) or 1 (a run that failed, its last good time kept), with a one-line
//! reason on stderr.

use fsim::cli::Options;
use fsim::error::FsimError;

/// A failed allocation ends the run with a message and exit 1, not an abort.
#[global_allocator]
static ALLOCATOR: fsim::memory::ExitOnFailure = fsim::memory::ExitOnFailure;

fn main() {
    let options = Options::from_env();
    if let Err(error) = fsim::run::run(&options) {
        eprintln!("fsimFoam: error: {error}");
        if let FsimError::Input {
            excerpt: Some(excerpt),
            ..
        } = &error
        {
            eprintln!("{excerpt}");
        }
        std::process::exit(error.exit_code());
    }
}
