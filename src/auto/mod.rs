//! `model auto`: fsim picks the coupling model and its grid for the accuracy the user asks
//! (`tolerance` in `constant/couplingProperties`), from an error model and a cost model
//! fitted to the validation studies (`tools/fit_auto_model.py`,
//! docs/user-guide/choosing-a-model.md).

mod candidate;
mod choice;
mod model_fit;
mod scene;

pub use candidate::{Candidate, Verdict};
pub use choice::{choose, Choice};
pub use model_fit::{direct_error, drag_law_error};
pub use scene::Scene;
