//! `detach check-paper` at the binary level: exit codes, table, JSON, files.

use std::process::Command;

fn detach(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_detach"))
        .args(args)
        .output()
        .expect("runs")
}

#[test]
fn unknown_claim_exits_2() {
    let o = detach(&["check-paper", "--claim", "F9.9"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("unknown claim id"));
}

#[test]
fn one_claim_prints_its_row_and_writes_nothing() {
    let dir = std::env::temp_dir().join(format!("detach-claims-cli-{}", std::process::id()));
    let out = dir.to_str().unwrap();
    let o = detach(&["check-paper", "--claim", "F1.7", "--out", out]);
    assert_eq!(o.status.code(), Some(0));
    let t = String::from_utf8(o.stdout).unwrap();
    assert!(t.contains("| F1.7 |") && t.contains("**error**"), "{t}");
    assert!(!dir.join("REPORT.md").exists());
}

#[test]
fn full_run_writes_the_report_and_json() {
    let dir = std::env::temp_dir().join(format!("detach-claims-full-{}", std::process::id()));
    let out = dir.to_str().unwrap();
    // The folder is replaced as a whole: a file check-paper does not write
    // is kept, a temporary an older killed run left is dropped.
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("NOTES.md"), "mine").unwrap();
    std::fs::write(dir.join(".REPORT.1234.tmp.md"), "debris").unwrap();
    let o = detach(&["check-paper", "--json", "--out", out]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let arr = v.as_array().unwrap();
    assert_eq!(arr.len(), detach::claims::ids().len());
    for r in arr {
        for k in [
            "id", "location", "verdict", "strength", "summary", "witness",
        ] {
            assert!(r.get(k).is_some(), "{k} missing in {r}");
        }
    }
    let written = std::fs::read_to_string(dir.join("report.json")).unwrap();
    assert_eq!(
        serde_json::from_str::<serde_json::Value>(&written).unwrap(),
        v
    );
    assert!(std::fs::read_to_string(dir.join("REPORT.md"))
        .unwrap()
        .contains("## Claims not confirmed"));
    assert!(dir.join("figures/F1_10.svg").exists() && dir.join("figures/F1_10.png").exists());
    assert_figures_differ(&dir.join("figures"));
    assert_eq!(
        std::fs::read_to_string(dir.join("NOTES.md")).unwrap(),
        "mine"
    );
    assert!(!dir.join(".REPORT.1234.tmp.md").exists());
    let toml = std::fs::read_to_string(dir.join("claims.toml")).unwrap();
    assert_eq!(toml.matches("[[claim]]").count(), arr.len());
    // The summary line (on stderr under --json): the verdict counts of the
    // JSON, in order, and where the report went.
    let mut counts: Vec<(String, usize)> = Vec::new();
    for r in arr {
        let v = r["verdict"].as_str().unwrap().to_string();
        match counts.iter_mut().find(|c| c.0 == v) {
            Some(c) => c.1 += 1,
            None => counts.push((v, 1)),
        }
    }
    let err = String::from_utf8(o.stderr).unwrap();
    let line = err.lines().last().unwrap();
    assert!(
        line.starts_with(&format!("{} claims: ", arr.len())),
        "{line}"
    );
    for (v, n) in &counts {
        assert!(line.contains(&format!(" {n} {v}")), "{v}: {line}");
    }
    assert!(
        line.ends_with(&format!("wrote {}", dir.join("REPORT.md").display())),
        "{line}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn committed_claims_list_is_the_built_in_table() {
    let committed = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/paper-checks/claims.toml"
    ))
    .unwrap();
    assert_eq!(committed, detach::claims::TABLE);
}

/// No two files of a figures folder hold the same bytes: each claim's
/// picture shows what that claim is about.
fn assert_figures_differ(dir: &std::path::Path) {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let p = e.unwrap().path();
            (p.display().to_string(), std::fs::read(&p).unwrap())
        })
        .collect();
    files.sort();
    assert!(files.len() >= 2, "{}: no figures", dir.display());
    for (i, (a, x)) in files.iter().enumerate() {
        for (b, y) in &files[i + 1..] {
            assert!(x != y, "{a} and {b} are byte-identical");
        }
    }
}

#[test]
fn committed_figures_are_pairwise_different() {
    assert_figures_differ(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/paper-checks/figures"
    )));
}

/// Every committed SVG of the report keeps its spaces: text runs are split
/// at accents and subscripts, and without `xml:space="preserve"` standard
/// renderers drop the space that ends a run ("θ̈of (1.7)").
#[test]
fn committed_svgs_preserve_spaces() {
    let dir = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/paper-checks/figures"));
    let mut n = 0;
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "svg") {
            let text = std::fs::read_to_string(&p).unwrap();
            let root = &text[text.find("<svg").unwrap()..];
            let root = &root[..root.find('>').unwrap()];
            assert!(
                root.contains(r#"xml:space="preserve""#),
                "{}: {root}",
                p.display()
            );
            n += 1;
        }
    }
    assert!(n >= 15, "{n} SVGs");
}
