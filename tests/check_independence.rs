//! The checker must not depend on the code that produces proofs: every file
//! under `src/check/` may name only `std`, `core`, `inari`, `serde_json` and
//! the checker itself.

use std::path::Path;

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).expect("src/check exists") {
        let p = e.expect("readable directory").path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The text with comments, string and char literals blanked out, so that
/// only code is inspected.
fn code_only(s: &str) -> String {
    let b: Vec<char> = s.chars().collect();
    let mut out = String::with_capacity(s.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == '/' && b.get(i + 1) == Some(&'/') {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if b[i] == '/' && b.get(i + 1) == Some(&'*') {
            i += 2;
            while i < b.len() && !(b[i] == '*' && b.get(i + 1) == Some(&'/')) {
                i += 1;
            }
            i += 2;
            out.push(' ');
        } else if b[i] == '"' {
            i += 1;
            while i < b.len() && b[i] != '"' {
                if b[i] == '\\' {
                    i += 1;
                }
                i += 1;
            }
            i += 1;
            out.push_str("\"\"");
        } else if b[i] == '\'' && b.get(i + 2) == Some(&'\'') {
            i += 3;
            out.push_str("' '");
        } else if b[i] == '\'' && b.get(i + 1) == Some(&'\\') {
            // An escaped char literal such as '\n' or '\'': skip to its close.
            i += 3;
            while i < b.len() && b[i] != '\'' {
                i += 1;
            }
            i += 1;
            out.push_str("' '");
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    out
}

/// The crate's dependencies other than the two the checker may use, plus the
/// crate itself, as they are spelled in paths.
fn forbidden_crates() -> Vec<String> {
    let toml = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml"))
        .expect("Cargo.toml");
    let mut names = vec!["detach".to_string()];
    let mut in_deps = false;
    for line in toml.lines() {
        let l = line.trim();
        if l.starts_with('[') {
            in_deps = l.ends_with("dependencies]");
            continue;
        }
        if in_deps {
            if let Some((name, _)) = l.split_once('=') {
                let name = name.trim().replace('-', "_");
                if !name.is_empty() && name != "inari" && name != "serde_json" {
                    names.push(name);
                }
            }
        }
    }
    names
}

/// Every path that starts with `crate::` (other than `crate::check`),
/// escapes `src/check` through `super::`, names another crate, or is a `use`
/// of anything but `std`, `core`, `inari`, `serde_json` and the checker.
fn violations(code: &str, depth: usize) -> Vec<String> {
    let other_crates = forbidden_crates();
    let mut bad = Vec::new();
    let toks: Vec<&str> = code
        .split(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
        .filter(|t| !t.is_empty())
        .collect();
    for t in toks {
        if !t.contains("::") {
            continue;
        }
        let t = t.trim_start_matches("::");
        let segs: Vec<&str> = t.split("::").collect();
        match segs[0] {
            "crate" => {
                if segs.get(1) != Some(&"check") {
                    bad.push(t.to_string());
                }
            }
            "super" => {
                let ups = segs.iter().take_while(|s| **s == "super").count();
                // From src/check/x.rs (depth 1) one `super` reaches check.
                if ups > depth {
                    bad.push(t.to_string());
                }
            }
            first => {
                if other_crates.iter().any(|c| c == first) {
                    bad.push(t.to_string());
                }
            }
        }
    }
    // `extern crate` and `use` of other crates of the workspace.
    for line in code.lines() {
        let l = line.trim();
        if l.starts_with("extern crate") {
            bad.push(l.to_string());
        }
        if let Some(rest) = l
            .strip_prefix("use ")
            .or_else(|| l.strip_prefix("pub use "))
        {
            let root = rest
                .trim_start_matches("::")
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .next()
                .unwrap_or("");
            let ok = [
                "std",
                "core",
                "inari",
                "serde_json",
                "crate",
                "super",
                "self",
            ];
            if !ok.contains(&root) {
                bad.push(l.to_string());
            }
        }
    }
    bad
}

#[test]
fn checker_imports_nothing_from_the_rest_of_the_crate() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/check");
    let mut files = Vec::new();
    rust_files(&root, &mut files);
    assert!(files.len() >= 5, "src/check has its modules");
    let mut all = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(f).expect("UTF-8 source");
        let rel = f.strip_prefix(&root).unwrap();
        // mod.rs is the check module itself (depth 0); x.rs is depth 1; a/b.rs depth 2.
        let depth = rel.components().count() - usize::from(rel.ends_with("mod.rs"));
        for v in violations(&code_only(&text), depth) {
            all.push(format!("{}: {v}", rel.display()));
        }
        // `#[path]` could pull in files from elsewhere.
        assert!(
            !text.contains("#[path"),
            "{}: #[path] attribute",
            rel.display()
        );
        assert!(!text.contains("include!"), "{}: include!", rel.display());
    }
    assert!(all.is_empty(), "forbidden paths:\n{}", all.join("\n"));
}

#[test]
fn the_scanner_catches_escapes() {
    let cases = [
        ("use crate::scene::Scene;", 1, true),
        ("let x = crate::pave::area(1);", 1, true),
        ("use super::super::scalar;", 1, true),
        ("use super::eval::Op;", 1, false),
        ("use crate::check::eval;", 1, false),
        ("use detach::pave;", 1, true),
        ("use rayon::prelude::*;", 1, true),
        ("// use crate::scene;\nlet s = \"crate::scene\";", 1, false),
        ("use std::fmt; use inari::Interval;", 1, false),
        (
            "fn f() -> ::std::string::String { String::new() }",
            1,
            false,
        ),
        ("let v = rayon::join(a, b);", 1, true),
        ("let v = serde::de::from(a);", 1, true),
        ("let c = '\\'';  let d = crate::roots::x;", 1, true),
        ("use super::x;", 0, true),
    ];
    for (code, depth, expect_bad) in cases {
        let v = violations(&code_only(code), depth);
        assert_eq!(!v.is_empty(), expect_bad, "{code}: {v:?}");
    }
}
