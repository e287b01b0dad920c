//! Resolved coupling (paper §2.1): declares and re-exports the direct model's parts.
