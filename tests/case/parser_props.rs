//! Property: the parser never panics and every error points inside the text, on random
//! bytes and on random mutations of the valid corpus. The fuzz target in `fuzz/` checks the
//! same contract ([`check_parser_invariants`]) for long runs; this is the short version in the
//! normal suite. `FSIM_PARSER_CASES=N` raises the number of cases.

use std::path::Path;

use fsim::case::check_parser_invariants;
use proptest::prelude::*;

fn cases() -> u32 {
    std::env::var("FSIM_PARSER_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(256)
}

fn valid_corpus() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/parser_corpus/valid");
    let mut texts: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| std::fs::read(e.unwrap().path()).ok())
        .map(|b| String::from_utf8_lossy(&b).into_owned())
        .collect();
    texts.sort();
    texts
}

/// Characters that matter to the grammar, to make mutations interesting.
const SPICE: &[&str] = &[
    "(",
    ")",
    "{",
    "}",
    "[",
    "]",
    ";",
    "\"",
    "$",
    "#",
    "#{",
    "#}",
    "/*",
    "*/",
    "//",
    "\n",
    " ",
    "3(",
    "2{",
    "$..",
    "$:",
    "#include \"x\"",
    "#eval{",
    "inf",
    "nan",
    "1e",
    "-",
    ".",
    "uniform",
    "#calc \"2*$a/3\"",
    "#eval{ sin(pi()/$b) }",
    "a 2;",
    "b -1e300;",
];

#[derive(Clone, Debug)]
enum Mutation {
    Delete(usize, usize),
    Insert(usize, usize),
    Duplicate(usize, usize, usize),
}

fn apply(text: &str, mutations: &[Mutation]) -> String {
    let mut bytes = text.as_bytes().to_vec();
    for m in mutations {
        let len = bytes.len().max(1);
        match *m {
            Mutation::Delete(at, n) => {
                let at = at % len;
                let end = (at + n % 16).min(bytes.len());
                if at < end {
                    bytes.drain(at..end);
                }
            }
            Mutation::Insert(at, which) => {
                let at = (at % len).min(bytes.len());
                let s = SPICE[which % SPICE.len()].as_bytes();
                bytes.splice(at..at, s.iter().copied());
            }
            Mutation::Duplicate(from, n, to) => {
                let from = from % len;
                let end = (from + n % 64).min(bytes.len());
                let chunk: Vec<u8> = bytes[from.min(end)..end].to_vec();
                let to = (to % len).min(bytes.len());
                bytes.splice(to..to, chunk);
            }
        }
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), any::<usize>()).prop_map(|(a, n)| Mutation::Delete(a, n)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, w)| Mutation::Insert(a, w)),
        (any::<usize>(), any::<usize>(), any::<usize>())
            .prop_map(|(f, n, t)| Mutation::Duplicate(f, n, t)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_break_the_parser(bytes in proptest::collection::vec(any::<u8>(), 0..512)) {
        check_parser_invariants(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn random_token_soup_never_breaks_the_parser(
        parts in proptest::collection::vec(0..SPICE.len() + 4, 0..64)
    ) {
        let words = ["a", "b 1;", "0.5", "x { y 2; }"];
        let text: String = parts
            .iter()
            .map(|&k| SPICE.get(k).copied().unwrap_or_else(|| words[k - SPICE.len()]))
            .collect::<Vec<_>>()
            .join(" ");
        check_parser_invariants(&text);
    }

    #[test]
    fn mutated_valid_files_never_break_the_parser(
        which in any::<usize>(),
        mutations in proptest::collection::vec(mutation(), 1..8)
    ) {
        let corpus = valid_corpus();
        let text = &corpus[which % corpus.len()];
        check_parser_invariants(&apply(text, &mutations));
    }
}
