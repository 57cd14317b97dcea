//! A scene file's proof states the author's text (`docs/proofs.md`, "A scene
//! file's proof states the author's text"): names kept whatever their values,
//! and every stated label confirmed on that text, also for a looser checker.

use crate::common::detach;
use detach::check::{check_bytes, check_file, Verdict};
use std::path::{Path, PathBuf};

fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("detach-statement-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Two parameters of the same value, a literal equal to them, a definition,
/// and a region that is a quotient (so that the paver's quadratic form and
/// the stated text enclose it differently).
const TWINS: &str = r#"
name = "twins"
[domain]
theta = ["0", "1.5"]
theta_dot = ["-2", "2"]
[parameters]
a = "2"
b = "2"
[definitions]
q = "cos(theta)"
[regions]
omega = "b*q*theta_dot^2 + 2*cos(theta) < a"
omega0 = "(a*theta_dot^2 - 1)/(q - 0.5) < 0"
"#;

/// `pave --scene-file F --proof P` with `extra` arguments; the proof's JSON.
fn pave_proof(dir: &Path, scene: &str, extra: &[&str]) -> (PathBuf, serde_json::Value) {
    let f = dir.join("scene.toml");
    std::fs::write(&f, scene).unwrap();
    let p = dir.join(format!("proof{}.json", extra.len()));
    let mut args = vec![
        "pave",
        "--scene-file",
        f.to_str().unwrap(),
        "--eps",
        "0.01",
        "--proof",
        p.to_str().unwrap(),
    ];
    args.extend(extra);
    let out = detach(&args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json = serde_json::from_slice(&std::fs::read(&p).unwrap()).unwrap();
    (p, json)
}

/// Both checkers' verdicts on a file: `detach verify` (its exit status) and
/// the `detach-check` library, which the `detach-check` binary runs.
fn verdicts(p: &Path) -> (Option<i32>, Verdict) {
    let out = detach(&["verify", p.to_str().unwrap()]);
    (out.status.code(), check_file(p).unwrap().verdict)
}

#[test]
fn equal_parameters_and_a_literal_are_stated_as_written() {
    let dir = temp_dir("twins");
    for method in ["contract", "slices", "natural"] {
        let (p, proof) = pave_proof(&dir, TWINS, &["--method", method]);
        let st = &proof["statement"];
        assert_eq!(
            st["parameters"],
            serde_json::json!({ "a": "2", "b": "2" }),
            "{method}"
        );
        assert_eq!(st["definitions"], serde_json::json!([["q", "cos(t)"]]));
        let c = &st["constraints"];
        assert_eq!(c[0]["expr"], "(b*q*w^2 + 2*cos(t)) - (a)", "{method}");
        assert_eq!(c[1]["expr"], "(a*w^2 - 1)/(q - 0.5)", "{method}");
        assert_eq!(c[0]["meaning"], "Ω: b*q*theta_dot^2 + 2*cos(theta) < a");
        assert_eq!(verdicts(&p), (Some(0), Verdict::Valid), "{method}");
        // Some label is proved: the statement is not vacuous.
        assert!(st["areas"][0]["inner"].as_str().unwrap() != "0", "{method}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The author's text is what is checked: with `b = 3`, stating `a` where
/// the file has `b` (values 2 and 3) is refuted by both checkers.
#[test]
fn a_name_changed_in_the_statement_is_invalid() {
    let dir = temp_dir("mutated");
    let (p, proof) = pave_proof(&dir, TWINS, &["--param", "b=3"]);
    assert_eq!(verdicts(&p), (Some(0), Verdict::Valid));
    let mut bad = proof.clone();
    let e = bad["statement"]["constraints"][0]["expr"]
        .as_str()
        .unwrap()
        .replace("b*q", "a*q");
    assert_ne!(bad["statement"]["constraints"][0]["expr"], e.as_str());
    bad["statement"]["constraints"][0]["expr"] = e.into();
    let m = dir.join("mutated.json");
    std::fs::write(&m, detach::certificate::to_bytes(&bad)).unwrap();
    let (code, v) = verdicts(&m);
    assert_eq!(code, Some(1));
    assert!(matches!(v, Verdict::Invalid(_)), "{v:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The shipped rod: `l`, `m` and the literal `1` stay apart whatever their
/// values (`l = m = 1` by default; `l = 0.5` below).
#[test]
fn the_rod_is_stated_as_its_file_writes_it() {
    let dir = temp_dir("rod");
    let p = dir.join("rod.json");
    let out = detach(&[
        "pave",
        "--scene",
        "painleve-rod",
        "--param",
        "l=0.5",
        "--eps",
        "0.01",
        "--proof",
        p.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let proof: serde_json::Value = serde_json::from_slice(&std::fs::read(&p).unwrap()).unwrap();
    let st = &proof["statement"];
    assert_eq!(st["parameters"]["l"], "0.5");
    assert_eq!(st["parameters"]["m"], "1");
    assert_eq!(
        st["definitions"],
        serde_json::json!([
            ["U", "l*sin(t)*w^2 - g"],
            ["V", "1 + 3*cos(t)^2 - 3*mu*sin(t)*cos(t)"]
        ])
    );
    assert_eq!(st["constraints"][0]["expr"], "U");
    assert_eq!(st["constraints"][1]["expr"], "U/V");
    assert_eq!(verdicts(&p), (Some(0), Verdict::Valid));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Labels stated on the author's text hold for a checker 2 ulps looser per
/// operation and for the loosest one FORMAT.md allows, and the paver's
/// quadratic-form labels are not all confirmed by the text as written, so
/// the confirmation is what makes them hold (for `U/V` near `V = 0`).
#[test]
fn stated_labels_hold_for_looser_checkers() {
    let dir = temp_dir("loose");
    let loosest_allowed = detach::check::Looseness {
        functions: 4,
        ..Default::default()
    };
    let mut unconfirmed = 0;
    for method in ["contract", "slices", "natural"] {
        let (p, proof) = pave_proof(&dir, TWINS, &["--method", method]);
        let bytes = std::fs::read(&p).unwrap();
        let two = detach::check::with_loose_rounding(2, || check_bytes(&bytes).unwrap());
        let allowed =
            detach::check::with_looseness(loosest_allowed, || check_bytes(&bytes).unwrap());
        assert_eq!(two.verdict, Verdict::Valid, "{method}, 2 ulps");
        assert_eq!(allowed.verdict, Verdict::Valid, "{method}, loosest allowed");
        unconfirmed += proof["evidence"]["resolution"]["unconfirmed"]
            .as_u64()
            .unwrap();
    }
    assert!(
        unconfirmed > 0,
        "the quadratic form and the text never differ here"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `detach verify` gives every conformance case the verdict `cases.json`
/// expects (exit 0 VALID, 1 INVALID, 2 malformed), as `detach-check`'s own
/// suite does through the library: the two checkers agree on every case.
#[test]
fn detach_verify_agrees_with_the_conformance_suite() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("proofs/conformance");
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("cases.json")).unwrap()).unwrap();
    let mut failures = Vec::new();
    let cases = manifest["cases"].as_array().unwrap();
    for c in cases {
        let file = c["file"].as_str().unwrap();
        let want = match c["expect"].as_str().unwrap() {
            "VALID" => 0,
            "INVALID" => 1,
            _ => 2,
        };
        let out = detach(&["verify", dir.join(file).to_str().unwrap()]);
        if out.status.code() != Some(want) {
            failures.push(format!(
                "{file}: exit {:?}, expected {want}",
                out.status.code()
            ));
        }
    }
    assert!(cases.len() > 400);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
