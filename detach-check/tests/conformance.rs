//! The conformance suite `proofs/conformance/`: every case file is checked
//! through the library and must get the verdict its manifest entry expects
//! (VALID, INVALID, or malformed = unreadable). A case file that is not
//! listed, or a listed file that is missing, fails the test too. A checker
//! as loose as FORMAT.md allows ("Accuracy") must give every verdict as
//! well, except the VALID cases marked `"tightest": true`, which only a
//! checker whose basic operations are tightest passes.

use detach_check::{check_file, with_looseness, Looseness, Verdict};
use serde_json::Value;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn suite() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../proofs/conformance")
}

/// The verdict as the manifest spells it.
fn verdict_of(path: &Path) -> (&'static str, String) {
    verdict_with(path, Looseness::default())
}

/// The verdict of a checker with the given looseness.
fn verdict_with(path: &Path, loose: Looseness) -> (&'static str, String) {
    with_looseness(loose, || verdict_raw(path))
}

fn verdict_raw(path: &Path) -> (&'static str, String) {
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
        assert!(
            c.get("tightest")
                .is_none_or(|t| t == true && expect == "VALID"),
            "{file}: tightest must be true, and only on a VALID case"
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

/// The listed cases with their expected verdicts and `tightest` marks.
fn listed_cases() -> Vec<(PathBuf, String, bool)> {
    let dir = suite();
    let text = std::fs::read_to_string(dir.join("cases.json")).expect("cases.json is readable");
    let manifest: Value = serde_json::from_str(&text).expect("cases.json is JSON");
    let cases = manifest["cases"].as_array().expect("a case list");
    cases
        .iter()
        .map(|c| {
            (
                dir.join(c["file"].as_str().expect("a file name")),
                c["expect"].as_str().expect("a verdict").to_string(),
                c.get("tightest") == Some(&Value::Bool(true)),
            )
        })
        .collect()
}

/// FORMAT.md lets `sin`, `cos`, `tan`, `ln` and `x^n` (n ≥ 3) be 4 ulps
/// looser than tightest at each end, even where the exact value is a
/// double. A checker that loose must still give every case its verdict.
#[test]
fn the_loosest_allowed_checker_gives_every_verdict() {
    let loose = Looseness {
        functions: 4,
        ..Looseness::default()
    };
    let mut failures = Vec::new();
    for (path, expect, _) in listed_cases() {
        let (got, why) = verdict_with(&path, loose);
        if got != expect {
            failures.push(format!(
                "{}: expected {expect}, got {got} {why}",
                path.display()
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A checker whose basic operations are one ulp looser than tightest, exact
/// results included (`4 − 3` no longer `[1, 1]`), rejects exactly the VALID
/// cases marked `"tightest"`: so the marks say which cases need tightness.
#[test]
fn tightest_marks_the_cases_that_need_tight_basic_operations() {
    let loose = Looseness {
        basic: 1,
        exact_too: true,
        functions: 4,
    };
    let mut wrong = Vec::new();
    let mut marked = 0;
    for (path, expect, tightest) in listed_cases() {
        marked += usize::from(tightest);
        if expect != "VALID" {
            continue;
        }
        let (got, why) = verdict_with(&path, loose);
        if (got == "VALID") == tightest {
            wrong.push(format!(
                "{}: tightest {tightest}, loose checker {got} {why}",
                path.display()
            ));
        }
    }
    assert!(marked >= 20, "only {marked} cases marked tightest");
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// The stand-in loose checker is not a no-op: functions move by 4 ulps even
/// where exact (`sin 0 = 0`), basic operations keep exact results unless
/// `exact_too`.
#[test]
fn the_loose_stand_in_widens_what_it_says() {
    use detach_check::eval_on_box;
    use inari::Interval;
    let p = Interval::try_from((0.0, 0.0)).unwrap();
    let at = |l: Looseness, e: &str| {
        with_looseness(l, || eval_on_box(&[], &[], e, p, p).unwrap())
            .interval()
            .unwrap()
    };
    let tiny = 4.0 * f64::from_bits(1);
    let functions = Looseness {
        functions: 4,
        ..Looseness::default()
    };
    assert_eq!(
        at(functions, "sin(t)"),
        Interval::try_from((-tiny, tiny)).unwrap()
    );
    assert_eq!(
        at(functions, "4 - 3"),
        Interval::try_from((1.0, 1.0)).unwrap()
    );
    let basic = Looseness {
        basic: 1,
        exact_too: true,
        functions: 0,
    };
    assert_eq!(
        at(basic, "4 - 3"),
        Interval::try_from((1.0f64.next_down(), 1.0f64.next_up())).unwrap()
    );
    assert_eq!(
        at(Looseness::default(), "sin(t) + 4 - 3"),
        Interval::try_from((1.0, 1.0)).unwrap()
    );
}

/// The `derive-*` cases come in pairs that differ in one reading of the
/// text (FORMAT.md, "What a checker evaluates") and get opposite verdicts:
/// so each case can come out the other way, and a checker that reads the
/// text the other way fails one of the two.
#[test]
fn derivation_cases_come_out_the_other_way_when_read_otherwise() {
    let dir = suite().join("cases");
    let pairs = [
        (
            "derive-definition-is-one-operand",
            "derive-definition-substituted-text",
        ),
        ("derive-square-is-sqr", "derive-square-as-product"),
        ("derive-minus-below-power", "derive-minus-above-power"),
        ("derive-left-assoc", "derive-right-assoc"),
        ("derive-pown-one-operation", "derive-pown-as-products"),
        ("derive-rewritten-by-hand", "derive-no-rewriting"),
        ("derive-rewritten-by-hand", "derive-no-rewriting-definition"),
        (
            "derive-parameters-equal-values-in",
            "derive-parameters-keep-their-names",
        ),
    ];
    let statement = |name: &str| -> Value {
        let text = std::fs::read_to_string(dir.join(format!("{name}.json"))).unwrap();
        serde_json::from_str::<Value>(&text).unwrap()["statement"].clone()
    };
    for (valid, invalid) in pairs {
        assert_eq!(verdict_of(&dir.join(format!("{valid}.json"))).0, "VALID");
        assert_eq!(
            verdict_of(&dir.join(format!("{invalid}.json"))).0,
            "INVALID"
        );
        // The two differ in the formulas or parameters only.
        let (a, b) = (statement(valid), statement(invalid));
        for key in ["domain", "root_box", "leaves", "areas"] {
            assert_eq!(a[key], b[key], "{valid} / {invalid}: {key} differs");
        }
    }
}
