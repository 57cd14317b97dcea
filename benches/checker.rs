//! Per-leaf checking time on a large paving: `cargo bench --bench checker`.
//! The labels are found with the checker's own evaluator; the point here is
//! timing, the verdicts are tested elsewhere.

use detach::check::{check_str, eval_on_box, Verdict};
use inari::Interval;
use serde_json::json;

fn params() -> Vec<(String, String)> {
    [("a", "1"), ("b", "0.5"), ("g", "9.81"), ("mu", "0.3")]
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect()
}

fn defs() -> Vec<(String, String)> {
    [
        ("h", "a + b*sin(t)"),
        ("h1", "b*cos(t)"),
        ("h2", "-(b*sin(t))"),
        ("den", "1 + h1^2"),
    ]
    .iter()
    .map(|(k, v)| (k.to_string(), v.to_string()))
    .collect()
}

const CONS: [&str; 2] = ["(-h2*w^2 - g)/den", "(g + h2*w^2)*h - mu*h^2*w*h1 - 0.1"];

/// A full tree of the given depth; splits alternate t and w, or are all on t
/// (every leaf then has its own θ-interval, so nothing is reused).
fn build(
    depth: u32,
    only_t: bool,
    t: (f64, f64),
    w: (f64, f64),
    bits: &mut Vec<bool>,
    leaves: &mut u64,
) {
    if depth == 0 {
        bits.push(false);
        for c in CONS {
            let v = eval_on_box(
                &params(),
                &defs(),
                c,
                Interval::try_from(t).unwrap(),
                Interval::try_from(w).unwrap(),
            )
            .unwrap();
            let i = v.interval().unwrap();
            let def = v.decoration() >= inari::Decoration::Def;
            let label = if def && i.sup() < 0.0 {
                [false, true]
            } else if def && i.inf() > 0.0 {
                [true, false]
            } else {
                [false, false]
            };
            bits.extend(label);
        }
        *leaves += 1;
        return;
    }
    let axis_w = !only_t && depth % 2 == 1;
    bits.extend([true, false, axis_w]);
    if axis_w {
        let m = 0.5 * w.0 + 0.5 * w.1;
        build(depth - 1, only_t, t, (w.0, m), bits, leaves);
        build(depth - 1, only_t, t, (m, w.1), bits, leaves);
    } else {
        let m = 0.5 * t.0 + 0.5 * t.1;
        build(depth - 1, only_t, (t.0, m), w, bits, leaves);
        build(depth - 1, only_t, (m, t.1), w, bits, leaves);
    }
}

fn b64(bytes: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let v = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            s.push(if k <= c.len() {
                char::from(A[(v >> (18 - 6 * k) & 63) as usize])
            } else {
                '='
            });
        }
    }
    s
}

fn main() {
    for only_t in [false, true] {
        time(only_t);
    }
}

fn time(only_t: bool) {
    let depth = 18;
    let (t, w) = ((-3.0, 3.0), (-10.0, 10.0));
    let mut bits = Vec::new();
    let mut leaves = 0;
    build(depth, only_t, t, w, &mut bits, &mut leaves);
    let bytes: Vec<u8> = bits
        .chunks(8)
        .map(|c| {
            c.iter()
                .enumerate()
                .fold(0u8, |a, (i, &b)| a | (u8::from(b) << (7 - i)))
        })
        .collect();
    let p: serde_json::Map<String, serde_json::Value> =
        params().into_iter().map(|(k, v)| (k, json!(v))).collect();
    let d: Vec<_> = defs().into_iter().map(|(k, v)| json!([k, v])).collect();
    let proof = json!({
        "format": "detach-proof/1", "claim": "paving",
        "statement": {
            "scene": "speed", "variant": "grid", "parameters": p, "definitions": d,
            "constraints": [ { "name": "A", "expr": CONS[0] }, { "name": "B", "expr": CONS[1] } ],
            "domain": { "t": ["-3", "3"], "w": ["-10", "10"] },
            "root_box": { "t": ["-0x1.8p+1", "0x1.8p+1"], "w": ["-0x1.4p+3", "0x1.4p+3"] },
            "leaves": leaves,
            "areas": [ { "set": "A and B", "literals": { "A": "in", "B": "in" } },
                       { "set": "A, not B", "literals": { "A": "in", "B": "out" } } ]
        },
        "evidence": { "encoding": "tree/1", "nodes": 2 * leaves - 1, "body": b64(&bytes) }
    })
    .to_string();
    let r = check_str(&proof).unwrap();
    assert_eq!(r.verdict, Verdict::Valid);
    println!(
        "{}: {} leaves in {:.3} s: {:.2} µs per leaf ({} kB proof)",
        if only_t {
            "distinct θ per leaf"
        } else {
            "grid"
        },
        r.checked,
        r.seconds,
        r.seconds / r.checked as f64 * 1e6,
        proof.len() / 1000
    );
}
