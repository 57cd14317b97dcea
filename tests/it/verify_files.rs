//! `detach verify` and `--scene-file` on hostile files (issue: the checker
//! must not be crashed, hung or fooled by a file): pipes and devices refused
//! unread, a manifest that fails closed and stays inside its folder, an
//! empty folder that is nothing to check, names printed escaped. The
//! checker's own bombs are in `detach-check/tests/hostile_files.rs`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::Duration;
use wait_timeout::ChildExt;

/// A fresh scratch folder holding a copy of the committed kappa0 proof.
fn folder(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("detach-verify-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("proofs/kappa0.json");
    std::fs::copy(src, d.join("kappa0.json")).unwrap();
    d
}

/// `detach ARGS`, killed (and the test failed) after 20 s: a pipe must
/// never be waited on.
fn detach(args: &[&str]) -> (Option<i32>, String, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_detach"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    if child
        .wait_timeout(Duration::from_secs(20))
        .unwrap()
        .is_none()
    {
        let _ = child.kill();
        let _ = child.wait();
        panic!("detach {args:?} still running after 20 s");
    }
    let Output {
        status,
        stdout,
        stderr,
    } = child.wait_with_output().unwrap();
    let s = |b: Vec<u8>| String::from_utf8_lossy(&b).into_owned();
    (status.code(), s(stdout), s(stderr))
}

fn mkfifo(path: &Path) {
    assert!(Command::new("mkfifo").arg(path).status().unwrap().success());
}

/// The SHA-256 line of `kappa0.json` in `dir`, by `sha256sum` (another
/// implementation than detach's).
fn sha256sum_line(dir: &Path) -> String {
    let out = Command::new("sha256sum")
        .arg("kappa0.json")
        .current_dir(dir)
        .output()
        .unwrap();
    String::from_utf8(out.stdout).unwrap()
}

fn verify(dir: &Path) -> (Option<i32>, String, String) {
    detach(&["verify", dir.to_str().unwrap()])
}

#[test]
fn a_good_manifest_passes() {
    let d = folder("good");
    std::fs::write(d.join("MANIFEST.sha256"), sha256sum_line(&d)).unwrap();
    let (code, out, _) = verify(&d);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.ends_with("1 valid, 0 invalid, 0 unreadable\n"), "{out}");
    let _ = std::fs::remove_dir_all(&d);
}

/// A manifest with a 0xFF byte, one that is a folder, a pipe or unreadable,
/// a name outside the folder, a wrong hash: never exit 0, one line saying why.
#[test]
fn the_manifest_fails_closed() {
    let line = {
        let d = folder("line");
        let l = sha256sum_line(&d);
        let _ = std::fs::remove_dir_all(&d);
        l
    };
    let hash = line[..64].to_string();
    let mut ff = line.clone().into_bytes();
    ff.push(0xFF);
    let text = |name: &str| format!("{hash}  {name}\n").into_bytes();
    // (case, manifest bytes or None for a special file made by `special`,
    // exit code, what the output says)
    let cases: Vec<(&str, Option<Vec<u8>>, i32, &str)> = vec![
        ("ff", Some(ff), 2, "not UTF-8"),
        ("folder", None, 2, "a directory, not a regular file"),
        ("fifo", None, 2, "a named pipe, not a regular file"),
        (
            "outside",
            Some(text("../../etc/passwd")),
            2,
            "must be a file of the folder",
        ),
        (
            "absolute",
            Some(text("/etc/passwd")),
            2,
            "must be a file of the folder",
        ),
        (
            "wrong-hash",
            Some(format!("{}  kappa0.json\n", "0".repeat(64)).into_bytes()),
            1,
            "SHA-256 differs",
        ),
        (
            "missing-file",
            Some(text("gone.json")),
            2,
            "gone.json: cannot read",
        ),
    ];
    let special = |name: &str, m: &Path| match name {
        "folder" => std::fs::create_dir(m).unwrap(),
        _ => mkfifo(m),
    };
    for (name, bytes, code, needle) in cases {
        let d = folder(name);
        let m = d.join("MANIFEST.sha256");
        match bytes {
            Some(b) => std::fs::write(&m, b).unwrap(),
            None => special(name, &m),
        }
        let (got, out, err) = verify(&d);
        assert_eq!(got, Some(code), "{name}: {out}{err}");
        assert!(out.contains(needle), "{name}: `{needle}` not in {out}");
        assert!(!err.contains("panicked"), "{name}: {err}");
        let _ = std::fs::remove_dir_all(&d);
    }
}

/// An unreadable manifest (mode 000) fails too, unless run as root, who
/// reads it anyway.
#[test]
fn an_unreadable_manifest_fails() {
    use std::os::unix::fs::PermissionsExt;
    let d = folder("mode");
    let m = d.join("MANIFEST.sha256");
    std::fs::write(&m, sha256sum_line(&d)).unwrap();
    std::fs::set_permissions(&m, std::fs::Permissions::from_mode(0o000)).unwrap();
    if std::fs::read(&m).is_err() {
        let (code, out, _) = verify(&d);
        assert_eq!(code, Some(2), "{out}");
        assert!(out.contains("MANIFEST.sha256: cannot read"), "{out}");
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// A folder with no proof file: nothing to check, said, exit 2.
#[test]
fn verify_on_an_empty_folder_is_nothing_to_check() {
    let d = folder("empty");
    std::fs::remove_file(d.join("kappa0.json")).unwrap();
    let (code, out, err) = verify(&d);
    assert_eq!(code, Some(2), "{out}");
    assert!(err.contains("nothing to check"), "{err}");
    let _ = std::fs::remove_dir_all(&d);
}

/// Pipes and devices as a proof, as a `.json` link in a verified folder, as
/// a scene file: refused unread with one line, at once.
#[test]
fn pipes_and_devices_are_refused_by_verify_and_scene_file() {
    let d = folder("special");
    let fifo = d.join("pipe.json");
    mkfifo(&fifo);
    std::os::unix::fs::symlink("/dev/zero", d.join("zero.json")).unwrap();
    for (p, what) in [
        ("/dev/zero", "a device"),
        ("/dev/urandom", "a device"),
        (fifo.to_str().unwrap(), "a named pipe"),
    ] {
        let (code, out, _) = detach(&["verify", p]);
        assert_eq!(code, Some(2), "{p}: {out}");
        assert!(
            out.starts_with(&format!("UNREADABLE {p}: {what}, not a regular file\n")),
            "{out}"
        );
    }
    let (code, out, _) = verify(&d);
    assert_eq!(code, Some(2), "{out}");
    assert!(
        out.contains("VALID      ") && out.ends_with("1 valid, 0 invalid, 2 unreadable\n"),
        "{out}"
    );
    let toml = d.join("pipe.toml");
    mkfifo(&toml);
    for p in ["/dev/zero", "/dev/urandom", toml.to_str().unwrap()] {
        let (code, _, err) = detach(&["pave", "--scene-file", p]);
        assert_eq!(code, Some(2), "{p}: {err}");
        assert!(
            err.contains("not a regular file") && err.lines().count() == 1,
            "{err}"
        );
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// A scene file past its cap (1 MiB) is refused with its size, in one
/// short line; an error quoting a long expression quotes a cut of it.
#[test]
fn long_scene_files_give_short_errors() {
    let d = folder("long-scene");
    let big = d.join("big.toml");
    std::fs::write(&big, "#".repeat(2 << 20)).unwrap();
    let (code, _, err) = detach(&["pave", "--scene-file", big.to_str().unwrap()]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("larger than 1048576 bytes") && err.len() < 400,
        "{err}"
    );
    let long = d.join("long.toml");
    let expr = "theta+".repeat(150_000);
    std::fs::write(
        &long,
        format!("name = \"x\"\n[domain]\ntheta = [\"0\", \"1\"]\ntheta_dot = [\"0\", \"1\"]\n[regions]\nomega = \"{expr}\"\nomega0 = \"theta < 0\"\n"),
    )
    .unwrap();
    let (code, _, err) = detach(&["pave", "--scene-file", long.to_str().unwrap()]);
    assert_ne!(code, Some(0), "{err}");
    assert!(
        err.len() < 2000 && err.contains("bytes)"),
        "{} bytes: {}",
        err.len(),
        &err[..err.len().min(300)]
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// Escaped names: `detach verify` prints the same escaped line as
/// `detach-check` (a scene name with a newline and ESC: one verdict line).
#[test]
fn verify_prints_names_escaped() {
    let d = folder("escape");
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("proofs/atlas-viscous-disc-derived.json");
    let mut v: serde_json::Value = serde_json::from_slice(&std::fs::read(src).unwrap()).unwrap();
    v["statement"]["scene"] = "evil\nVALID      fake.json  paving\u{1b}[2K".into();
    std::fs::write(d.join("evil.json"), serde_json::to_vec(&v).unwrap()).unwrap();
    let (_, out, _) = detach(&["verify", d.join("evil.json").to_str().unwrap()]);
    assert_eq!(
        out.lines()
            .filter(|l| l.starts_with("VALID") || l.starts_with("INVALID"))
            .count(),
        1,
        "{out}"
    );
    assert!(out.bytes().all(|b| b == b'\n' || b >= 0x20), "{out:?}");
    let _ = std::fs::remove_dir_all(&d);
}
