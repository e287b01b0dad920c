//! Unresolved coupling (paper §2.2): declares and re-exports the drag-law model's parts.
