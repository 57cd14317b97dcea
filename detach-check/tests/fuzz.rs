//! The checker never panics: arbitrary bytes, JSON-ish text and mutations of
//! valid proof files all give a verdict or an error.

use detach_check::{check_bytes, check_str};

/// Inputs per property: as many as a property-testing crate's default
/// budget would draw, from a fixed seed so that a failure replays.
const CASES: u64 = 1500;

/// SplitMix64: a small generator of our own, since the checker's tests may
/// depend on nothing beyond its two dependencies.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// Runs `case` on `CASES` seeds; a panic names the seed that made it.
fn each_case(property: u64, mut case: impl FnMut(&mut Rng)) {
    for i in 0..CASES {
        let seed = property << 32 | i;
        let mut rng = Rng(seed);
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| case(&mut rng)));
        assert!(
            r.is_ok(),
            "the checker panicked on the input of seed {seed}"
        );
    }
}

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

/// The characters of JSON-ish text: brackets, quotes, digits, letters,
/// operators.
const JSON_ISH: &[u8] = br#"{}[]":,0123456789abcdefghijklmnopqrstuvwxyz.-+ ^*/()="#;

#[test]
fn random_bytes() {
    each_case(1, |rng| {
        let bytes: Vec<u8> = (0..rng.below(300)).map(|_| rng.next() as u8).collect();
        let _ = check_bytes(&bytes);
    });
}

#[test]
fn json_ish_text() {
    each_case(2, |rng| {
        let text: String = (0..rng.below(201))
            .map(|_| char::from(JSON_ISH[rng.below(JSON_ISH.len())]))
            .collect();
        let _ = check_str(&text);
    });
}

#[test]
fn mutated_valid_files() {
    each_case(3, |rng| {
        let base = [PAVING, ROOTS, KAPPA0][rng.below(3)];
        let cuts: Vec<(usize, usize, usize)> = (0..1 + rng.below(5))
            .map(|_| {
                (
                    rng.next() as usize,
                    rng.next() as usize,
                    rng.next() as usize,
                )
            })
            .collect();
        let _ = check_str(&mutate(base, &cuts));
    });
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
