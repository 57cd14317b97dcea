//! The checker trusts inari and serde_json and nothing else. Cargo itself
//! reads the manifest (`cargo metadata`), so inline and target-specific
//! tables, renames and inherited workspace dependencies all count: any other
//! dependency of any kind, one renamed or not from crates.io (a path to the
//! prover's crate, a git fork), or a build script fails. The sources must not
//! name the `detach` crate or pull in files from elsewhere.

use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::process::Command;

/// What the checker may depend on (serde only if serde_json's derive is wanted).
const ALLOWED: [&str; 3] = ["inari", "serde", "serde_json"];

const CRATES_IO: &str = "registry+https://github.com/rust-lang/crates.io-index";

fn manifest_dir() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// This package as `cargo metadata --no-deps` describes it.
fn this_package() -> Value {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| env!("CARGO").into());
    let out = Command::new(cargo)
        .args([
            "metadata",
            "--offline",
            "--no-deps",
            "--format-version",
            "1",
        ])
        .arg("--manifest-path")
        .arg(manifest_dir().join("Cargo.toml"))
        .output()
        .expect("cargo runs");
    assert!(
        out.status.success(),
        "cargo metadata failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let meta: Value = serde_json::from_slice(&out.stdout).expect("cargo metadata prints JSON");
    meta["packages"]
        .as_array()
        .expect("a package list")
        .iter()
        .find(|p| p["name"] == env!("CARGO_PKG_NAME"))
        .cloned()
        .expect("this package among the workspace's")
}

/// Everything in a package's metadata that widens the trusted base.
fn violations(pkg: &Value) -> Vec<String> {
    let mut bad = Vec::new();
    for d in pkg["dependencies"].as_array().expect("a dependency list") {
        let name = d["name"].as_str().unwrap_or("?");
        let kind = d["kind"].as_str().unwrap_or("normal");
        if !ALLOWED.contains(&name) {
            bad.push(format!("{kind} dependency {name}"));
        }
        if !d["rename"].is_null() {
            bad.push(format!("{name} renamed to {}", d["rename"]));
        }
        if d["source"].as_str() != Some(CRATES_IO) {
            let from = d.get("path").unwrap_or(&d["source"]);
            bad.push(format!("{name} not from crates.io but {from}"));
        }
    }
    for t in pkg["targets"].as_array().expect("a target list") {
        if t["kind"]
            .as_array()
            .is_some_and(|k| k.contains(&json!("custom-build")))
        {
            bad.push(format!("build script {}", t["src_path"]));
        }
    }
    bad
}

#[test]
fn depends_on_inari_and_serde_json_only() {
    let pkg = this_package();
    let bad = violations(&pkg);
    assert!(
        bad.is_empty(),
        "the checker's trusted base grew:\n{}",
        bad.join("\n")
    );
    let names: Vec<&str> = pkg["dependencies"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|d| d["name"].as_str())
        .collect();
    assert!(names.contains(&"inari") && names.contains(&"serde_json"));
}

#[test]
fn the_metadata_test_catches_widening() {
    let dep = |name: &str| json!({"name": name, "kind": null, "rename": null, "source": CRATES_IO});
    let lib = json!({"kind": ["lib"], "src_path": "src/lib.rs"});
    let pkg =
        |deps: Vec<Value>, targets: Vec<Value>| json!({"dependencies": deps, "targets": targets});
    assert!(violations(&pkg(
        vec![dep("inari"), dep("serde_json")],
        vec![lib.clone()]
    ))
    .is_empty());
    let mut dev = dep("rayon");
    dev["kind"] = json!("dev");
    let mut renamed = dep("serde_json");
    renamed["rename"] = json!("json");
    let mut path = dep("inari");
    path["source"] = Value::Null;
    path["path"] = json!("/src/detach");
    let build = json!({"kind": ["custom-build"], "src_path": "build.rs"});
    for p in [
        pkg(vec![dep("rayon")], vec![lib.clone()]),
        pkg(vec![dep("detach")], vec![lib.clone()]),
        pkg(vec![dev], vec![lib.clone()]),
        pkg(vec![renamed], vec![lib.clone()]),
        pkg(vec![path], vec![lib.clone()]),
        pkg(vec![dep("inari")], vec![lib.clone(), build]),
    ] {
        assert_eq!(violations(&p).len(), 1, "{p}");
    }
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).expect("a readable source folder") {
        let p = e.expect("a readable entry").path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// Without `detach` among the dependencies no `detach::` path compiles; this
/// scan says so by name, and stops `#[path]` and `include!` from compiling
/// the prover's files as the checker's own.
#[test]
fn sources_name_nothing_of_detach() {
    let mut files = Vec::new();
    rust_files(&manifest_dir().join("src"), &mut files);
    assert!(files.len() >= 10, "the checker's modules: {files:?}");
    let mut bad = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(f).expect("UTF-8 source");
        for (i, line) in text.lines().enumerate() {
            // Comments may mention detach (the prover) freely.
            let code = line.split("//").next().unwrap_or("");
            let names_detach = code.match_indices("detach::").any(|(at, _)| {
                !code[..at]
                    .chars()
                    .next_back()
                    .is_some_and(|c| c.is_alphanumeric() || c == '_')
            });
            if names_detach
                || code.contains("extern crate")
                || code.contains("#[path")
                || code.contains("include!")
            {
                bad.push(format!("{}:{}: {}", f.display(), i + 1, line.trim()));
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}
