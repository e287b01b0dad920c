//! The parser's contract as a check: shared by the fuzz target and the property test.

use super::parse_dict;
use crate::case::dictionary::Dict;

/// Parses `text` and panics if the parser breaks its contract: it must not panic, and an
/// error must point inside the text (line within the file, column within that line or just
/// past its end). Every accessor is also tried on every keyword of a parsed result. Shared by
/// the fuzz target (`fuzz/`) and the property test.
#[doc(hidden)]
pub fn check_parser_invariants(text: &str) {
    match parse_dict(text, "fuzz") {
        Err(e) => {
            let lines: Vec<&str> = text.split('\n').collect();
            assert!(
                e.line >= 1 && e.line <= lines.len(),
                "line {} outside the text: {e}",
                e.line
            );
            // A lone carriage return is not a line break: it counts as a column.
            let width = lines[e.line - 1].chars().count();
            assert!(
                e.col >= 1 && e.col <= width + 1,
                "column {} outside line {}: {e}",
                e.col,
                e.line
            );
            assert!(e.excerpt().is_some());
            assert!(
                !e.to_string().contains('\n'),
                "message is not one line: {e}"
            );
        }
        Ok(dict) => exercise(&dict),
    }
}

fn exercise(dict: &Dict) {
    for e in dict.entries() {
        let k = e.keyword();
        let _ = dict.get_scalar(k);
        let _ = dict.get_label(k);
        let _ = dict.get_word(k);
        let _ = dict.get_bool(k);
        let _ = dict.get_vector(k);
        if let Ok(sub) = dict.get_dict(k) {
            exercise(sub);
        }
        if let Some(tokens) = e.as_tokens() {
            for t in tokens {
                let _ = t.to_string();
                if let Some(list) = t.as_list() {
                    let _ = list.iter().take(4).count();
                }
            }
        }
    }
    let _ = dict.unused();
}
