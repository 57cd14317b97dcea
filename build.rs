//! Records the git commit (`git rev-parse --short HEAD`) for `detach --version`
//! and the output files; "unknown" when git or the repository is absent.

use std::process::Command;

fn git(args: &[&str]) -> Option<String> {
    let out = Command::new("git").args(args).output().ok()?;
    if !out.status.success() {
        return None;
    }
    let s = String::from_utf8(out.stdout).ok()?.trim().to_string();
    (!s.is_empty()).then_some(s)
}

fn main() {
    let commit = git(&["rev-parse", "--short", "HEAD"]).unwrap_or_else(|| "unknown".into());
    println!("cargo:rustc-env=DETACH_GIT_COMMIT={commit}");
    println!("cargo:rerun-if-changed=build.rs");
    // Re-run when HEAD moves: the worktree's HEAD and the ref it points to.
    if let Some(dir) = git(&["rev-parse", "--git-dir"]) {
        let head = std::path::Path::new(&dir).join("HEAD");
        if head.exists() {
            println!("cargo:rerun-if-changed={}", head.display());
        }
    }
    if let Some(r) = git(&["rev-parse", "--symbolic-full-name", "HEAD"]) {
        if let Some(common) = git(&["rev-parse", "--git-common-dir"]) {
            let base = std::path::Path::new(&common);
            for p in [base.join(&r), base.join("packed-refs")] {
                if p.exists() {
                    println!("cargo:rerun-if-changed={}", p.display());
                }
            }
        }
    }
}
