//! The checker never panics: arbitrary bytes, JSON-ish text and mutations of
//! valid proof files all give a verdict or an error.

use detach::check::{check_bytes, check_str};
use proptest::prelude::*;

const PAVING: &str = r#"{"format":"detach-proof/1","claim":"paving","statement":{"scene":"s","variant":"v","parameters":{"c":"0.7"},"definitions":[["g","t - c"]],"constraints":[{"name":"S","expr":"g*w^2/(1+w^2) - ln(t+1) + sqrt(abs(sin(t)))"}],"domain":{"t":["0","1"],"w":["0","1"]},"root_box":{"t":["0x0p+0","0x1p+0"],"w":["0x0p+0","0x1p+0"]},"leaves":3,"areas":[{"set":"S","literals":{"S":"in"},"inner":"0","outer":"1"}]},"evidence":{"encoding":"tree/1","nodes":5,"body":"ggA="}}"#;

const ROOTS: &str = r#"{"format":"detach-proof/1","claim":"roots","statement":{"parameters":{"two":"2"},"definitions":[],"variable":"t","function":"t^2 - two","domain":{"lo":"0","hi":"two"},"roots":[{"lo":"1.41","hi":"1.42","status":"unique"}],"complete":true},"evidence":{"pieces":[{"lo":"0x0p+0","hi":"0x1.4p+0","kind":"exclude"},{"lo":"0x1.4p+0","hi":"0x1.8p+0","kind":"newton","point":"0x1.6p+0"},{"lo":"0x1.8p+0","hi":"inf","kind":"exclude_mv","point":"0x1p+1"}]}}"#;

const KAPPA0: &str = r#"{"format":"detach-proof/1","claim":"kappa0","statement":{"variable":"mu","parameters":{},"definitions":[],"p":"mu*(1 - mu)*(1 + mu)","kappa0":{"lo":"0.19","hi":"0.2"}},"evidence":{"b":"0x1p+0","derivative_pieces":[{"lo":"0x0p+0","hi":"0x1p-1","kind":"exclude_mv","point":"0x1p-2"},{"lo":"0x1p-1","hi":"0x1.4p-1","kind":"newton","point":"0x1.279a74590331cp-1"},{"lo":"0x1.4p-1","hi":"0x1.8p-1","kind":"exclude_mv","point":"0x1.6p-1"},{"lo":"0x1.8p-1","hi":"0x1p+0","kind":"exclude"}],"peak_point":"0x1.279a74590331cp-1"}}"#;

/// Pieces of text that make mutations reach deep into the checks.
const SNIPPETS: &[&str] = &[
    "\"",
    "{",
    "}",
    "[",
    "]",
    ",",
    ":",
    "0",
    "1e999",
    "-",
    "0x1p+1024",
    "inf",
    "nan",
    "pi",
    "t",
    "w",
    "mu",
    "(",
    ")",
    "^",
    "^2",
    "^99",
    "/",
    "*",
    "ln(",
    "tan(",
    "sqrt(-",
    "null",
    "true",
    "[[]]",
    "\\u0000",
    "====",
    "AAAA",
    "////",
    "99999999999999999999",
    "-0x0p+0",
    "\"newton\"",
    "\"undecided\"",
    "\"exclude_mv\"",
    "\"out\"",
    "\"in\"",
];

fn mutate(base: &str, cuts: &[(usize, usize, usize)]) -> String {
    let mut s: Vec<char> = base.chars().collect();
    for &(pos, del, ins) in cuts {
        if s.is_empty() {
            break;
        }
        let p = pos % s.len();
        let end = (p + del % 8).min(s.len());
        let snip: Vec<char> = SNIPPETS[ins % SNIPPETS.len()].chars().collect();
        s.splice(p..end, snip);
    }
    s.into_iter().collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1500, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
        let _ = check_bytes(&bytes);
    }

    #[test]
    fn json_ish_text(s in r#"[\{\}\[\]":,0-9a-z\.\-\+ ^*/()=]{0,200}"#) {
        let _ = check_str(&s);
    }

    #[test]
    fn mutated_valid_files(
        which in 0usize..3,
        cuts in proptest::collection::vec((any::<usize>(), any::<usize>(), any::<usize>()), 1..6),
    ) {
        let base = [PAVING, ROOTS, KAPPA0][which];
        let _ = check_str(&mutate(base, &cuts));
    }
}

#[test]
fn the_seed_files_are_proofs() {
    for f in [PAVING, ROOTS, KAPPA0] {
        let r = check_str(f).expect("readable");
        assert!(r.checked > 0, "{r:?}");
    }
}

#[test]
fn hostile_inputs() {
    // Deep JSON nesting, a deep expression, a huge leaf count, huge numbers.
    let deep = format!("{}{}", "[".repeat(100_000), "]".repeat(100_000));
    assert!(check_str(&deep).is_err());
    let deep_expr = PAVING.replace(
        "t - c",
        &format!("{}t{}", "(".repeat(5000), ")".repeat(5000)),
    );
    assert!(check_str(&deep_expr).is_err());
    let many = PAVING.replace("\"leaves\":3", "\"leaves\":18446744073709551615");
    assert!(check_str(&many).is_ok());
    let nodes = PAVING.replace("\"nodes\":5", "\"nodes\":1e400");
    assert!(check_str(&nodes).is_err());
    let big = PAVING.replace("\"0.7\"", &format!("\"{}\"", "9".repeat(5000)));
    assert!(check_str(&big).is_err());
    let pow = PAVING.replace("t - c", "t^2147483647 + w^2147483647");
    assert!(check_str(&pow).is_ok());
    let pow = PAVING.replace("t - c", "t^2147483648");
    assert!(check_str(&pow).is_err());
}
