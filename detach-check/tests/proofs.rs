//! Hand-made proof files with known verdicts: each VALID file is true by
//! hand computation, each mutation makes a check fail.

use detach_check::{check_bytes, check_str, Report, Verdict};
use serde_json::{json, Value};

fn run(v: &Value) -> Report {
    match check_str(&v.to_string()) {
        Ok(r) => r,
        Err(e) => panic!("unreadable: {e}"),
    }
}

fn assert_valid(v: &Value) {
    let r = run(v);
    assert_eq!(r.verdict, Verdict::Valid, "{}", r.claim);
}

fn assert_invalid(v: &Value, needle: &str) {
    match run(v).verdict {
        Verdict::Invalid(msg) => assert!(msg.contains(needle), "message {msg:?} lacks {needle:?}"),
        Verdict::Valid | Verdict::Unchecked(_) => panic!("expected INVALID ({needle})"),
    }
}

fn assert_unreadable(v: &Value) {
    assert!(check_str(&v.to_string()).is_err(), "expected unreadable");
}

/// Standard base64 with padding (written here independently of the checker).
fn b64(bytes: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = c.len();
        let v = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= n {
                s.push(char::from(A[(v >> (18 - 6 * k) & 63) as usize]));
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// Packs a string of '0'/'1' (spaces ignored) into bytes, MSB first.
fn pack(bits: &str) -> Vec<u8> {
    let bits: Vec<u8> = bits.bytes().filter(|&c| c != b' ').collect();
    bits.chunks(8)
        .map(|c| {
            c.iter()
                .enumerate()
                .fold(0u8, |acc, (i, &b)| acc | (u8::from(b == b'1') << (7 - i)))
        })
        .collect()
}

fn f64_bits(x: f64) -> String {
    format!("{:064b}", x.to_bits())
}

// ---------------------------------------------------------------- paving

/// `t − 0.75 < 0` on [0,1]², tree: split t at 0.5; lower leaf in (it is
/// [0,0.5]×[0,1], where t − 0.75 ≤ −0.25), upper leaf undecided. Inner area
/// exactly 0.5, outer exactly 1.
fn paving(bits: &str, leaves: u64, nodes: u64, inner: &str, outer: &str) -> Value {
    json!({
        "format": "detach-proof/1",
        "claim": "paving",
        "statement": {
            "scene": "test", "variant": "half",
            "parameters": { "c": "0.75" },
            "definitions": [["g", "t - c"]],
            "constraints": [ { "name": "S", "expr": "g" } ],
            "domain": { "t": ["0", "1"], "w": ["0", "1"] },
            "root_box": { "t": ["0x0p+0", "0x1p+0"], "w": ["0x0p+0", "0x1p+0"] },
            "leaves": leaves,
            "areas": [ { "set": "S", "literals": { "S": "in" }, "inner": inner, "outer": outer } ]
        },
        "evidence": { "encoding": "tree/1", "nodes": nodes, "body": b64(&pack(bits)) }
    })
}

const GOOD: &str = "100 0 01 0 00";

#[test]
fn paving_valid() {
    let r = run(&paving(GOOD, 2, 3, "0.5", "1"));
    assert_eq!(r.verdict, Verdict::Valid);
    assert_eq!((r.checked, r.unit), (2, "leaves"));
    assert!(r.claim.contains("test/half"));
    // The same tree with an explicit split point 0.5 and a w split below.
    let explicit = format!("11 0 {} 101 0 01 0 01 0 00", f64_bits(0.5));
    assert_valid(&paving(&explicit, 3, 5, "0.5", "1"));
    // Body bits 1000 0100 0(000 0000) are the bytes 0x84 0x00.
    assert_eq!(b64(&pack(GOOD)), "hAA=");
}

#[test]
fn paving_wrong_label() {
    assert_invalid(&paving("100 0 01 0 01", 2, 3, "0.5", "1"), "leaf 2");
    assert_invalid(&paving("100 0 10 0 00", 2, 3, "0", "1"), "claimed out");
}

#[test]
fn paving_claimed_bounds() {
    assert_invalid(
        &paving(GOOD, 2, 3, "0.5000000000000001", "1"),
        "claimed inner",
    );
    assert_invalid(
        &paving(GOOD, 2, 3, "0.5", "0.9999999999999999"),
        "claimed outer",
    );
    // c = 0.7: [0, 0.5] in, [0.5, 0.75] undecided, [0.75, 1] out
    // (t − 0.7 ≥ 0.05): inner 0.5, outer 0.75.
    let mut v = paving("100 0 01 100 0 00 0 10", 3, 5, "0.5", "0.75");
    v["statement"]["parameters"]["c"] = json!("0.7");
    assert_valid(&v);
    v["statement"]["areas"][0]["outer"] = json!("0.7499999999999999");
    assert_invalid(&v, "claimed outer");
}

#[test]
fn paving_uncovered_area_counts_as_outer() {
    // R = [0,1]×[0,0.5] inside D = [0,1]²: 0.5 of D is outside R.
    let mut v = paving(GOOD, 2, 3, "0.25", "1");
    v["statement"]["root_box"]["w"] = json!(["0x0p+0", "0x1p-1"]);
    assert_valid(&v);
    v["statement"]["areas"][0]["outer"] = json!("0.99");
    assert_invalid(&v, "claimed outer");
}

#[test]
fn paving_split_point_outside() {
    let bad = format!("11 0 {} 0 01 0 00", f64_bits(1.5));
    assert_invalid(&paving(&bad, 2, 3, "0", "1"), "split point");
    let bad = format!("11 0 {} 0 01 0 00", f64_bits(0.0));
    assert_invalid(&paving(&bad, 2, 3, "0", "1"), "split point");
    let bad = format!("11 1 {} 0 01 0 00", f64_bits(f64::NAN));
    assert_invalid(&paving(&bad, 2, 3, "0", "1"), "split point");
}

#[test]
fn paving_counts_and_padding() {
    assert_invalid(&paving(GOOD, 3, 3, "0.5", "1"), "leaves");
    assert_invalid(&paving(GOOD, 2, 4, "0.5", "1"), "nodes");
    assert_invalid(&paving(GOOD, 2, 2, "0.5", "1"), "nodes");
    // A set padding bit, and a whole extra byte.
    assert_invalid(
        &paving("100 0 01 0 00 0000001", 2, 3, "0.5", "1"),
        "bits after",
    );
    assert_invalid(
        &paving("100 0 01 0 00 0000000 00000000", 2, 3, "0.5", "1"),
        "bits after",
    );
    // Truncated: the second leaf's label is missing.
    assert_invalid(&paving("100 0 01 0", 2, 3, "0.5", "1"), "ends inside");
}

#[test]
fn paving_root_box_must_lie_in_domain() {
    let mut v = paving(GOOD, 2, 3, "0.5", "1");
    v["statement"]["root_box"]["t"] = json!(["-0x1p-60", "0x1p+0"]);
    assert_invalid(&v, "root_box");
    // pi is enclosed: the double 0x1.921fb54442d18p+1 = 3.14159265358979311…
    // is below π = 3.14159265358979323…, the next double above it is not.
    let mut v = paving(GOOD, 2, 3, "0", "4");
    v["statement"]["domain"]["t"] = json!(["0", "pi"]);
    v["statement"]["root_box"]["t"] = json!(["0x0p+0", "0x1.921fb54442d19p+1"]);
    assert_invalid(&v, "root_box");
    v["statement"]["root_box"]["t"] = json!(["0x0p+0", "0x1.921fb54442d18p+1"]);
    assert!(!matches!(run(&v).verdict, Verdict::Invalid(m) if m.contains("root_box")));
}

#[test]
fn paving_unreadable() {
    let good = paving(GOOD, 2, 3, "0.5", "1");
    let mut v = good.clone();
    v["format"] = json!("detach-proof/2");
    assert_unreadable(&v);
    let mut v = good.clone();
    v["evidence"]["body"] = json!("iAA");
    assert_unreadable(&v);
    let mut v = good.clone();
    v["statement"]["constraints"][0]["expr"] = json!("t - d");
    assert_unreadable(&v);
    let mut v = good.clone();
    v["statement"]["root_box"]["t"] = json!(["0x0p+0", "0x1.00000000000008p+0"]);
    assert_unreadable(&v);
    let mut v = good.clone();
    v["statement"]["leaves"] = json!(-2);
    assert_unreadable(&v);
    let mut v = good;
    v["statement"]["areas"][0]["literals"] = json!({ "T": "in" });
    assert_unreadable(&v);
    // Duplicate keys would let a reader and the checker see different values.
    let text = paving(GOOD, 2, 3, "0.5", "1")
        .to_string()
        .replace("\"c\":\"0.75\"", "\"c\":\"0.75\",\"c\":\"0.25\"");
    assert!(check_str(&text).is_err());
    assert!(check_bytes(b"\xff\xfe").is_err());
}

// ----------------------------------------------------------------- roots

/// f = t² − 2 on (0, 2): exclude [0, 1.25] (f ≤ −0.4375), newton on
/// [1.25, 1.5] at 1.375 (f' = 2t ∈ [2.5, 3], N ⊂ [1.411, 1.419]), exclude
/// [1.5, 2] (f ≥ 0.25). √2 = 1.41421… lies in the claimed [1.41, 1.42].
fn roots() -> Value {
    json!({
        "format": "detach-proof/1",
        "claim": "roots",
        "statement": {
            "equation": "sqrt2",
            "parameters": { "two": "2" },
            "definitions": [],
            "variable": "t",
            "function": "t^2 - two",
            "domain": { "lo": "0", "hi": "two" },
            "roots": [ { "lo": "1.41", "hi": "1.42", "status": "unique" } ],
            "complete": true
        },
        "evidence": { "pieces": [
            { "lo": "0x0p+0", "hi": "0x1.4p+0", "kind": "exclude" },
            { "lo": "0x1.4p+0", "hi": "0x1.8p+0", "kind": "newton", "point": "0x1.6p+0" },
            { "lo": "0x1.8p+0", "hi": "0x1p+1", "kind": "exclude" }
        ] }
    })
}

#[test]
fn roots_valid() {
    let r = run(&roots());
    assert_eq!(r.verdict, Verdict::Valid);
    assert_eq!((r.checked, r.unit), (3, "pieces"));
    // Mean-value exclusion on [0, 1.25] at 0.625: −1.609 + [0, 2.5]·[−0.625, 0.625] < 0.
    let mut v = roots();
    v["evidence"]["pieces"][0] =
        json!({ "lo": "0x0p+0", "hi": "0x1.4p+0", "kind": "exclude_mv", "point": "0x1.4p-1" });
    assert_valid(&v);
    // Unbounded domain: the last piece [1.5, inf] has f ≥ 0.25.
    let mut v = roots();
    v["statement"]["domain"]["hi"] = json!("inf");
    v["evidence"]["pieces"][2]["hi"] = json!("inf");
    assert_valid(&v);
    // An undecided piece inside an undecided claimed enclosure.
    let mut v = roots();
    v["statement"]["roots"][0] = json!({ "lo": "1.25", "hi": "1.5", "status": "undecided" });
    v["statement"]["complete"] = json!(false);
    v["evidence"]["pieces"][1] = json!({ "lo": "0x1.4p+0", "hi": "0x1.8p+0", "kind": "undecided" });
    assert_valid(&v.clone());
    v["statement"]["complete"] = json!(true);
    assert_invalid(&v, "complete");
}

#[test]
fn roots_invalid_mutations() {
    // √2 ≈ 1.41421 is not in [1.415, 1.42]: N cannot lie inside.
    let mut v = roots();
    v["statement"]["roots"][0]["lo"] = json!("1.415");
    assert_invalid(&v, "piece 2");
    // An exclude piece across the root.
    let mut v = roots();
    v["evidence"]["pieces"][1] = json!({ "lo": "0x1.4p+0", "hi": "0x1.8p+0", "kind": "exclude" });
    assert_invalid(&v, "contains 0");
    // A gap between pieces.
    let mut v = roots();
    v["evidence"]["pieces"][0]["hi"] = json!("0x1.3p+0");
    assert_invalid(&v, "ends at");
    // Not covering the domain.
    let mut v = roots();
    v["evidence"]["pieces"][2]["hi"] = json!("0x1.cp+0");
    assert_invalid(&v, "below the domain");
    // A second claimed root nobody proves.
    let mut v = roots();
    v["statement"]["roots"]
        .as_array_mut()
        .unwrap()
        .push(json!({ "lo": "1.8", "hi": "1.9", "status": "unique" }));
    assert_invalid(&v, "root 2");
    // Newton point outside its piece.
    let mut v = roots();
    v["evidence"]["pieces"][1]["point"] = json!("0x1.cp+0");
    assert_invalid(&v, "outside the piece");
    // Newton on a piece where f' has both signs: [0, 1.5], f' ∋ 0.
    let mut v = roots();
    v["evidence"]["pieces"] = json!([
        { "lo": "0x0p+0", "hi": "0x1.8p+0", "kind": "newton", "point": "0x1.6p+0" },
        { "lo": "0x1.8p+0", "hi": "0x1p+1", "kind": "exclude" }
    ]);
    assert_invalid(&v, "f' contains 0");
    // A claimed unique root outside the open domain (0, 1.3).
    let mut v = roots();
    v["statement"]["domain"]["hi"] = json!("1.3");
    assert_invalid(&v, "open domain");
    // Roots out of order.
    let mut v = roots();
    v["statement"]["roots"] = json!([
        { "lo": "1.41", "hi": "1.42", "status": "unique" },
        { "lo": "0.5", "hi": "0.6", "status": "undecided" }
    ]);
    v["statement"]["complete"] = json!(false);
    assert_invalid(&v, "disjoint");
}

#[test]
fn roots_unreadable() {
    let mut v = roots();
    v["evidence"]["pieces"][1]["kind"] = json!("bisect");
    assert_unreadable(&v);
    let mut v = roots();
    v["evidence"]["pieces"][1]
        .as_object_mut()
        .unwrap()
        .remove("point");
    assert_unreadable(&v);
    let mut v = roots();
    v["statement"]["function"] = json!("x^2 - 2");
    assert_unreadable(&v);
    let mut v = roots();
    v["evidence"]["pieces"][0]["hi"] = json!("inf");
    assert_unreadable(&v);
}

// ---------------------------------------------------------------- kappa0

/// p = μ(1 − μ)(1 + μ), p' = 1 − 3μ², p'' = −6μ, μ* = 1/√3,
/// κ₀ = p(μ*)/2 = 1/(3√3) = √3/9 = 0.19245008972987525…
fn kappa0(lo: &str, hi: &str) -> Value {
    json!({
        "format": "detach-proof/1",
        "claim": "kappa0",
        "statement": {
            "equation": "2.10",
            "variable": "mu",
            "parameters": {},
            "definitions": [],
            "p": "mu*(1 - mu)*(1 + mu)",
            "kappa0": { "lo": lo, "hi": hi }
        },
        "evidence": {
            "b": "0x1p+0",
            "derivative_pieces": [
                { "lo": "0x0p+0", "hi": "0x1p-1", "kind": "exclude_mv", "point": "0x1p-2" },
                { "lo": "0x1p-1", "hi": "0x1.4p-1", "kind": "newton", "point": "0x1.279a74590331cp-1" },
                { "lo": "0x1.4p-1", "hi": "0x1.8p-1", "kind": "exclude_mv", "point": "0x1.6p-1" },
                { "lo": "0x1.8p-1", "hi": "0x1p+0", "kind": "exclude" }
            ],
            "peak_point": "0x1.279a74590331cp-1"
        }
    })
}

#[test]
fn kappa0_valid() {
    let r = run(&kappa0("0.19245008972987", "0.19245008972988"));
    assert_eq!(r.verdict, Verdict::Valid, "{r:?}");
    assert_eq!(r.checked, 4);
}

#[test]
fn kappa0_invalid() {
    assert_invalid(&kappa0("0.1925", "0.2"), "kappa0 lo");
    assert_invalid(&kappa0("0.1", "0.19245008972987"), "kappa0 hi");
    // Two newton pieces, or none.
    let mut v = kappa0("0.19", "0.2");
    v["evidence"]["derivative_pieces"][2] =
        json!({ "lo": "0x1.4p-1", "hi": "0x1.8p-1", "kind": "newton", "point": "0x1.6p-1" });
    assert_invalid(&v, "piece 3");
    let mut v = kappa0("0.19", "0.2");
    v["evidence"]["derivative_pieces"][1]["kind"] = json!("exclude_mv");
    assert_invalid(&v, "piece 2");
    // Not starting at 0.
    let mut v = kappa0("0.19", "0.2");
    v["evidence"]["derivative_pieces"][0]["lo"] = json!("0x1p-10");
    assert_invalid(&v, "piece 1 starts");
    // b = 0.75: p(0.75) = 0.328… > 0 and p' is not negative on [0.75, ∞)
    // as enclosed, so the tail is not proved.
    let mut v = kappa0("0.19", "0.2");
    v["evidence"]["b"] = json!("0x1.8p-1");
    v["evidence"]["derivative_pieces"]
        .as_array_mut()
        .unwrap()
        .pop();
    assert_invalid(&v, "[b, +inf]");
    // A peak point outside N.
    let mut v = kappa0("0.19", "0.2");
    v["evidence"]["peak_point"] = json!("0x1.2p-1");
    assert_invalid(&v, "peak point");
}
