//! Outputs that a kill, a second writer or a special path cannot spoil:
//! every file detach writes goes to a temporary file and is renamed into
//! place, so a run killed at any moment leaves the previous file or the
//! complete new one; `-`, pipes and links are written as a user expects.

use crate::common::Rng;
use std::collections::BTreeMap;
use std::fs::Permissions;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};
use wait_timeout::ChildExt;

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

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("detach-out-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Every file of `dir` (recursively) with its bytes.
fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut m = BTreeMap::new();
    for n in names(dir) {
        let p = dir.join(&n);
        if p.is_dir() {
            for (k, v) in snapshot(&p) {
                m.insert(format!("{n}/{k}"), v);
            }
        } else {
            m.insert(n, std::fs::read(&p).unwrap());
        }
    }
    m
}

fn run_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_detach"))
        .current_dir(dir)
        .args(args)
        .output()
        .unwrap()
}

const PAVE: [&str; 5] = ["pave", "--scene", "ice-disc", "--eps", "0.05"];

/// The leaves CSV of `PAVE`, written to a regular file: the reference the
/// special outputs are compared with.
fn reference_leaves(dir: &Path) -> Vec<u8> {
    let o = run_in(dir, &[&PAVE[..], &["--leaves", "reference.csv"]].concat());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let bytes = std::fs::read(dir.join("reference.csv")).unwrap();
    std::fs::remove_file(dir.join("reference.csv")).unwrap();
    assert!(bytes.starts_with(b"# detach") && bytes.len() > 10_000);
    bytes
}

#[test]
fn dash_is_standard_output_for_every_file_option() {
    let d = scratch("dash");
    let csv = reference_leaves(&d);
    // --leaves -: the CSV alone on stdout, the table on stderr, no file `-`.
    let o = run_in(&d, &[&PAVE[..], &["--leaves", "-"]].concat());
    assert!(o.status.success());
    assert_eq!(o.stdout, csv);
    assert!(String::from_utf8_lossy(&o.stderr).contains("inner area"));
    // --proof - (pave and roots): a proof the independent checker accepts.
    for args in [
        &[&PAVE[..], &["--proof", "-"]].concat()[..],
        &[
            "roots",
            "--equation",
            "2.10",
            "--kappa",
            "0.1",
            "--proof",
            "-",
        ],
    ] {
        let o = run_in(&d, args);
        assert!(
            o.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let report = detach::check::check_bytes(&o.stdout).expect("a proof on stdout");
        assert_eq!(report.verdict, detach::check::Verdict::Valid, "{args:?}");
        assert!(String::from_utf8_lossy(&o.stderr).contains("wrote standard output"));
    }
    assert_eq!(names(&d), Vec::<String>::new(), "a file was written");
    // Two outputs on stdout are refused before any work.
    for (args, needle) in [
        (
            &["--leaves", "-", "--proof", "-"][..],
            "--leaves and --proof both",
        ),
        (
            &["--leaves", "-", "--json"][..],
            "--json and --leaves - both",
        ),
    ] {
        let o = run_in(&d, &[&PAVE[..], args].concat());
        assert_eq!(o.status.code(), Some(2));
        assert!(String::from_utf8_lossy(&o.stderr).contains(needle));
        assert!(o.stdout.is_empty());
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_named_pipe_is_written_in_place_and_stays_a_pipe() {
    let d = scratch("fifo");
    let csv = reference_leaves(&d);
    let fifo = d.join("leaves.csv");
    let c = std::ffi::CString::new(fifo.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: a valid path; creates a named pipe.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o644) }, 0);
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    let mut child = Command::new(env!("CARGO_BIN_EXE_detach"))
        .current_dir(&d)
        .args([&PAVE[..], &["--leaves", "leaves.csv"]].concat())
        .stdout(Stdio::null())
        .spawn()
        .unwrap();
    match child.wait_timeout(Duration::from_secs(60)).unwrap() {
        Some(status) => assert!(status.success()),
        None => {
            let _ = child.kill();
            panic!("detach blocked writing a named pipe");
        }
    }
    // Checked before joining: a pipe replaced by a file blocks its reader.
    use std::os::unix::fs::FileTypeExt;
    assert!(
        std::fs::symlink_metadata(&fifo)
            .unwrap()
            .file_type()
            .is_fifo(),
        "the pipe was replaced"
    );
    assert_eq!(reader.join().unwrap(), csv, "the reader got other bytes");
    assert_eq!(names(&d), ["leaves.csv"]);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_symlinked_output_is_written_through_and_modes_are_kept() {
    use std::os::unix::fs::PermissionsExt;
    let d = scratch("link");
    let csv = reference_leaves(&d);
    std::fs::create_dir(d.join("data")).unwrap();
    std::fs::write(d.join("data/leaves.csv"), "old").unwrap();
    std::fs::set_permissions(d.join("data/leaves.csv"), Permissions::from_mode(0o640)).unwrap();
    std::os::unix::fs::symlink("data/leaves.csv", d.join("link.csv")).unwrap();
    let o = run_in(&d, &[&PAVE[..], &["--leaves", "link.csv"]].concat());
    assert!(o.status.success());
    assert!(std::fs::symlink_metadata(d.join("link.csv"))
        .unwrap()
        .is_symlink());
    assert_eq!(std::fs::read(d.join("data/leaves.csv")).unwrap(), csv);
    let mode = std::fs::metadata(d.join("data/leaves.csv"))
        .unwrap()
        .permissions()
        .mode();
    assert_eq!(mode & 0o7777, 0o640, "mode {mode:o}");
    assert_eq!(names(&d.join("data")), ["leaves.csv"]);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_file_size_limit_is_a_message_and_exit_1() {
    let d = scratch("ulimit");
    std::fs::write(d.join("leaves.csv"), "old").unwrap();
    let o = Command::new("sh")
        .current_dir(&d)
        .arg("-c")
        .arg(format!(
            "ulimit -f 8; exec '{}' pave --scene ice-disc --eps 0.01 --leaves leaves.csv",
            env!("CARGO_BIN_EXE_detach")
        ))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("cannot write leaves.csv") && err.contains("ulimit -f"),
        "{err}"
    );
    assert_eq!(std::fs::read(d.join("leaves.csv")).unwrap(), b"old");
    assert_eq!(names(&d), ["leaves.csv"], "a temporary was left");
    let _ = std::fs::remove_dir_all(&d);
}

/// Several processes writing one file at once: the file is always one
/// writer's whole output (same-PID writers are tested in `files::tests`).
#[test]
fn concurrent_writers_never_tear_a_file() {
    let d = scratch("writers");
    let eps = ["0.05", "0.04", "0.03", "0.02"];
    let whole: Vec<Vec<u8>> = eps
        .iter()
        .map(|e| {
            let o = run_in(
                &d,
                &["pave", "--scene", "ice-disc", "--eps", e, "--leaves", "-"],
            );
            assert!(o.status.success());
            o.stdout
        })
        .collect();
    for _ in 0..3 {
        let children: Vec<_> = eps
            .iter()
            .map(|e| {
                Command::new(env!("CARGO_BIN_EXE_detach"))
                    .current_dir(&d)
                    .args([
                        "pave", "--scene", "ice-disc", "--eps", e, "--leaves", "same.csv",
                    ])
                    .stdout(Stdio::null())
                    .spawn()
                    .unwrap()
            })
            .collect();
        for mut c in children {
            assert!(c.wait().unwrap().success());
        }
        let got = std::fs::read(d.join("same.csv")).unwrap();
        assert!(whole.contains(&got), "torn: {} bytes", got.len());
        assert_eq!(names(&d), ["same.csv"]);
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// `prove` killed (SIGTERM, SIGKILL) at several moments: the folder is the
/// old one or the new one, whole, and `verify` passes; after SIGTERM no
/// temporary is left.
#[test]
fn a_killed_prove_leaves_the_old_folder_or_the_new_one() {
    let d = scratch("prove");
    let out = d.join("proofs");
    let prove = |what: &[&str]| {
        let o = run_in(&d, &[&["prove", "--out", "proofs"][..], what].concat());
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    };
    // The new folder: every headline proof; the old: kappa0 alone. A file
    // prove does not write is kept by both.
    prove(&[]);
    std::fs::write(out.join("NOTES.md"), "mine").unwrap();
    let new = snapshot(&out);
    std::fs::remove_dir_all(&out).unwrap();
    prove(&["kappa0"]);
    std::fs::write(out.join("NOTES.md"), "mine").unwrap();
    let old = snapshot(&out);
    assert!(old.len() == 3 && new.len() > 10, "{:?}", old.keys());
    let start = Instant::now();
    prove(&[]);
    let full = start.elapsed().as_secs_f64();
    let mut seen = [0usize; 2];
    for signal in [libc::SIGTERM, libc::SIGKILL] {
        for k in 0..8 {
            std::fs::remove_dir_all(&out).unwrap();
            prove(&["kappa0"]);
            std::fs::write(out.join("NOTES.md"), "mine").unwrap();
            let mut child = Command::new(env!("CARGO_BIN_EXE_detach"))
                .current_dir(&d)
                .args(["prove", "--out", "proofs"])
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .unwrap();
            std::thread::sleep(Duration::from_secs_f64(full * f64::from(k) / 6.0));
            // SAFETY: signals our own child.
            unsafe { libc::kill(child.id() as libc::pid_t, signal) };
            let status = child.wait().unwrap();
            let left = snapshot(&out);
            assert!(left == old || left == new, "a mix: {:?}", left.keys());
            seen[usize::from(left == new)] += 1;
            let v = run_in(&d, &["verify", "proofs"]);
            assert!(v.status.success(), "{}", String::from_utf8_lossy(&v.stdout));
            if signal == libc::SIGTERM {
                // 143 once the handler is in place; killed by the signal
                // itself before (nothing written yet); 0 if it finished.
                use std::os::unix::process::ExitStatusExt;
                let code = status.code().or(status.signal().map(|s| 128 + s));
                assert!(matches!(code, Some(143) | Some(0)), "{status:?}");
                assert_eq!(names(&d), ["proofs"], "a temporary was left");
            }
            // What SIGKILL leaves beside the folder is hidden and harmless.
            for n in names(&d).iter().filter(|n| *n != "proofs") {
                assert!(n.starts_with(".proofs.") && n.ends_with(".tmp"), "{n}");
                std::fs::remove_dir_all(d.join(n)).unwrap();
            }
        }
    }
    eprintln!("old folder kept {}, new folder whole {}", seen[0], seen[1]);
    assert!(seen[0] > 0, "no kill landed before the swap");
    let _ = std::fs::remove_dir_all(&d);
}

/// A temporary a killed run of an older detach left in the folder is neither
/// listed in the next manifest nor kept: `verify` passes.
#[test]
fn a_leftover_temporary_is_not_listed_nor_kept() {
    let d = scratch("leftover");
    let out = d.join("proofs");
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join(".kappa0.4242.tmp.json"), "{\"partial").unwrap();
    let o = run_in(&d, &["prove", "--out", "proofs", "kappa0"]);
    assert!(o.status.success());
    assert_eq!(names(&out), ["MANIFEST.sha256", "kappa0.json"]);
    let manifest = std::fs::read_to_string(out.join("MANIFEST.sha256")).unwrap();
    assert_eq!(manifest.lines().count(), 1, "{manifest}");
    assert!(run_in(&d, &["verify", "proofs"]).status.success());
    // The current folder is refused as an output folder.
    let o = run_in(&out, &["prove", "--out", ".", "kappa0"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("current folder"));
    let _ = std::fs::remove_dir_all(&d);
}
