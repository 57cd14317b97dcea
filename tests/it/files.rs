//! Output files survive a killed run: every file detach writes goes to a
//! temporary file and is renamed into place, so a run killed (SIGKILL) at any
//! moment leaves the previous file or the complete new one.

use crate::common::Rng;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn pave_leaves(eps: &str, path: &std::path::Path) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_detach"));
    c.args(["pave", "--scene", "ice-disc", "--eps", eps, "--leaves"])
        .arg(path)
        .stdout(Stdio::null())
        .stderr(Stdio::null());
    c
}

#[test]
fn a_killed_run_leaves_the_old_file_or_the_new_one() {
    let dir = std::env::temp_dir().join(format!("detach-kill-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (old_path, new_path, target) = (
        dir.join("old.csv"),
        dir.join("new.csv"),
        dir.join("leaves.csv"),
    );
    assert!(pave_leaves("0.004", &old_path).status().unwrap().success());
    let start = Instant::now();
    assert!(pave_leaves("0.0005", &new_path).status().unwrap().success());
    let full = start.elapsed();
    let (old, new) = (
        std::fs::read(&old_path).unwrap(),
        std::fs::read(&new_path).unwrap(),
    );
    assert_ne!(old, new);
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut outcomes = [0usize; 2];
    for _ in 0..8 {
        std::fs::write(&target, &old).unwrap();
        let mut child = pave_leaves("0.0005", &target).spawn().unwrap();
        std::thread::sleep(Duration::from_secs_f64(
            1.2 * rng.unit() * full.as_secs_f64(),
        ));
        let _ = child.kill();
        child.wait().unwrap();
        let left = std::fs::read(&target).unwrap();
        assert!(
            left == old || left == new,
            "a truncated file ({} bytes)",
            left.len()
        );
        outcomes[usize::from(left == new)] += 1;
    }
    eprintln!("old kept {}, new complete {}", outcomes[0], outcomes[1]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_unwritable_output_exits_1_with_one_message() {
    let o = Command::new(env!("CARGO_BIN_EXE_detach"))
        .args(["pave", "--scene", "ice-disc", "--eps", "0.1", "--leaves"])
        .arg("/nonexistent-detach-dir/leaves.csv")
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("cannot write /nonexistent-detach-dir/leaves.csv"),
        "{err}"
    );
}
