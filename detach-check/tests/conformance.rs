//! The conformance suite `proofs/conformance/`: every case file is checked
//! through the library and must get the verdict its manifest entry expects
//! (VALID, INVALID, or malformed = unreadable). A case file that is not
//! listed, or a listed file that is missing, fails the test too.

use detach_check::{check_file, Verdict};
use serde_json::Value;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn suite() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../proofs/conformance")
}

/// The verdict as the manifest spells it.
fn verdict_of(path: &Path) -> (&'static str, String) {
    match check_file(path) {
        Err(e) => ("malformed", e.0),
        Ok(r) => match r.verdict {
            Verdict::Valid => ("VALID", String::new()),
            Verdict::Invalid(why) => ("INVALID", why),
            Verdict::Unchecked(why) => ("UNCHECKED", why),
        },
    }
}

#[test]
fn every_case_gets_its_expected_verdict() {
    let dir = suite();
    let text = std::fs::read_to_string(dir.join("cases.json")).expect("cases.json is readable");
    let manifest: Value = serde_json::from_str(&text).expect("cases.json is JSON");
    assert_eq!(manifest["format"], "detach-conformance/1");
    let cases = manifest["cases"].as_array().expect("a case list");

    let mut listed = BTreeSet::new();
    let mut failures = Vec::new();
    for c in cases {
        let file = c["file"].as_str().expect("a file name");
        let expect = c["expect"].as_str().expect("an expected verdict");
        assert!(
            ["VALID", "INVALID", "malformed"].contains(&expect),
            "{file}: unknown verdict {expect:?}"
        );
        assert!(
            c["rule"].as_str().is_some_and(|r| !r.is_empty()),
            "{file}: no rule"
        );
        assert!(listed.insert(file.to_string()), "{file} is listed twice");
        let path = dir.join(file);
        if !path.is_file() {
            failures.push(format!("{file}: listed but missing"));
            continue;
        }
        let (got, why) = verdict_of(&path);
        if got != expect {
            failures.push(format!("{file}: expected {expect}, got {got} {why}"));
        }
    }

    let mut present = BTreeSet::new();
    for e in std::fs::read_dir(dir.join("cases")).expect("the cases folder") {
        let name = e.expect("an entry").file_name();
        present.insert(format!("cases/{}", name.to_string_lossy()));
    }
    for f in present.difference(&listed) {
        failures.push(format!("{f}: not listed in cases.json"));
    }
    assert!(cases.len() >= 300, "only {} cases", cases.len());
    assert!(
        failures.is_empty(),
        "{} of {} cases fail:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}
