//! User text in messages, bounded: a case may hold a 200 MB word, and a message that
//! echoes it must stay one short line (docs/security.md, "Numbers and messages").

use std::borrow::Cow;

/// Most characters of a user value a message shows.
pub const QUOTE_CHARS: usize = 80;

/// Most characters of a whole message: a backstop for messages that echo several values
/// or a list, beyond what [`quote`] bounds (room for a path of `PATH_CHARS` and the
/// message about it).
pub const MESSAGE_CHARS: usize = 6000;

/// Longest run holding a `/` that [`bound_message`] leaves whole: a file's path, up to
/// Linux's PATH_MAX, is named in full.
const PATH_CHARS: usize = 4096;

/// Longest run of non-blank characters [`bound_message`] leaves whole: a quoted value with
/// its `…(N` marker (N up to 20 digits) and the punctuation around it.
const RUN_CHARS: usize = QUOTE_CHARS + 32;

/// `text` as a message shows it: whole up to [`QUOTE_CHARS`] characters, else its first
/// ones followed by `…(N bytes)`, N its full length, so that a message stays short
/// whatever the case holds.
pub fn quote(text: &str) -> Cow<'_, str> {
    shorten(text, QUOTE_CHARS)
}

/// `text` cut to `max` characters with `…(N bytes)` after, when longer.
fn shorten(text: &str, max: usize) -> Cow<'_, str> {
    match text.char_indices().nth(max) {
        None => Cow::Borrowed(text),
        Some((end, _)) => Cow::Owned(format!("{}…({} bytes)", &text[..end], text.len())),
    }
}

/// A whole message bounded: every run of non-blank characters longer than `RUN_CHARS`
/// (a word no message of fsim's own holds; `PATH_CHARS` for one holding a `/`, a path)
/// is quoted as [`quote`] does, then the whole is
/// cut at [`MESSAGE_CHARS`]. Applied to every message printed, so that one that forgot to
/// quote a value is bounded all the same.
pub fn bound_message(message: &str) -> Cow<'_, str> {
    // (a run that `quote` already cut, with its `…(N` and some punctuation, stays under
    // RUN_CHARS: bounding is idempotent)
    let long = |run: &str| {
        let max = if run.contains('/') {
            PATH_CHARS
        } else {
            RUN_CHARS
        };
        run.len() > max && run.chars().nth(max).is_some()
    };
    let long_run = message.split(char::is_whitespace).any(long);
    let shortened: Cow<str> = if long_run {
        let mut out = String::with_capacity(MESSAGE_CHARS);
        let mut run_start = None;
        for (i, c) in message.char_indices().chain([(message.len(), ' ')]) {
            if c.is_whitespace() {
                if let Some(start) = run_start.take() {
                    let run = &message[start..i];
                    if long(run) {
                        out.push_str(&quote(run));
                    } else {
                        out.push_str(run);
                    }
                }
                if i < message.len() {
                    out.push(c);
                }
            } else if run_start.is_none() {
                run_start = Some(i);
            }
        }
        Cow::Owned(out)
    } else {
        Cow::Borrowed(message)
    };
    match shorten(&shortened, MESSAGE_CHARS) {
        Cow::Borrowed(_) => shortened,
        Cow::Owned(cut) => Cow::Owned(cut),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_values_are_whole_and_long_ones_cut_with_their_length() {
        assert_eq!(quote("abc"), "abc");
        let long = "é".repeat(100);
        let q = quote(&long);
        assert_eq!(q, format!("{}…(200 bytes)", "é".repeat(80)));
    }

    #[test]
    fn messages_are_bounded_whatever_they_echo() {
        assert_eq!(
            bound_message("expected a number, found 'x'"),
            "expected a number, found 'x'"
        );
        let word = "w".repeat(5_000_000);
        let message = format!("found the word '{word}' here\tand there");
        let m = bound_message(&message);
        assert_eq!(
            m,
            format!(
                "found the word '{}…(5000002 bytes) here\tand there",
                "w".repeat(79)
            )
        );
        assert_eq!(bound_message(&m), m, "bounding twice changes nothing");
        let many = "ab ".repeat(10_000);
        let m = bound_message(&many);
        assert!(m.chars().count() < MESSAGE_CHARS + 30, "{}", m.len());
        assert!(m.ends_with("…(30000 bytes)"));
        // a long path is named whole, a longer run with a slash is cut
        let path = format!("/{}/constant/positions: not found", "deep/".repeat(100));
        assert_eq!(bound_message(&path), path);
        let slashes = "/".repeat(5000);
        assert!(bound_message(&slashes).ends_with("…(5000 bytes)"));
    }
}
