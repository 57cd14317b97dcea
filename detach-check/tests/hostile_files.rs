//! The checker on files built to exhaust it (`proofs/FORMAT.md`, "Limits and
//! files"): true proofs whose check would take memory or time out of all
//! proportion to their size end UNCHECKED, in bounded memory and time; pipes,
//! devices and links to them are refused unread; text from a file cannot
//! print a verdict line of its own. The `detach-check` binary is run with a
//! memory cap (`ulimit -v` through `sh -c`) and a timeout.

use detach_check::{check_bytes, Verdict};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("detach-check-limits-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Standard base64 with padding (RFC 4648), for tree bodies.
fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= c.len() {
                s.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// A bit string, most significant bit of each byte first.
#[derive(Default)]
struct Bits(Vec<u8>, usize);

impl Bits {
    fn push(&mut self, bits: &str) {
        for b in bits.bytes() {
            if self.1.is_multiple_of(8) {
                self.0.push(0);
            }
            if b == b'1' {
                *self.0.last_mut().unwrap() |= 0x80 >> (self.1 % 8);
            }
            self.1 += 1;
        }
    }
}

/// The complete tree of midpoint splits `depth` deep (on t, or alternating
/// t and w), every leaf labelled out: `(body, nodes, leaves)`.
fn full_tree(depth: u32, alternate: bool) -> (String, u64, u64) {
    fn walk(b: &mut Bits, level: u32, depth: u32, alternate: bool) {
        if level == depth {
            b.push("010");
            return;
        }
        b.push(if alternate && level % 2 == 1 {
            "101"
        } else {
            "100"
        });
        walk(b, level + 1, depth, alternate);
        walk(b, level + 1, depth, alternate);
    }
    let mut b = Bits::default();
    walk(&mut b, 0, depth, alternate);
    (base64(&b.0), (1u64 << (depth + 1)) - 1, 1u64 << depth)
}

/// A paving proof: `defs` definitions `d1…`, each `0*(x+x+…)` with
/// `terms` terms `x` (`t` or `t*w`), and the constraint `1 + d1 + … > 0`
/// everywhere, so every leaf of the tree is out.
fn bomb(defs: usize, terms: usize, x: &str, depth: u32, alternate: bool) -> Vec<u8> {
    serde_json::to_vec(&paving(defs, terms, x, depth, alternate)).unwrap()
}

/// The proof of [`bomb`] as JSON.
fn paving(defs: usize, terms: usize, x: &str, depth: u32, alternate: bool) -> serde_json::Value {
    let sum = vec![x; terms].join("+");
    let definitions: Vec<serde_json::Value> = (1..=defs)
        .map(|i| serde_json::json!([format!("d{i}"), format!("0*({sum})")]))
        .collect();
    let g: String = std::iter::once("1".to_string())
        .chain((1..=defs).map(|i| format!("d{i}")))
        .collect::<Vec<_>>()
        .join("+");
    let (body, nodes, leaves) = full_tree(depth, alternate);
    serde_json::json!({
        "format": "detach-proof/1",
        "claim": "paving",
        "statement": {
            "parameters": {},
            "definitions": definitions,
            "constraints": [{"name": "g", "expr": g}],
            "domain": {"t": ["0", "1"], "w": ["0", "1"]},
            "root_box": {"t": ["0x0.0p+0", "0x1.0000000000000p+0"],
                         "w": ["0x0.0p+0", "0x1.0000000000000p+0"]},
            "leaves": leaves,
            "areas": [{"set": "G", "literals": {"g": "out"}, "inner": "1", "outer": "1"}]
        },
        "evidence": {"encoding": "tree/1", "nodes": nodes, "body": body}
    })
}

/// `detach-check ARGS` with virtual memory capped at `cap_mib` MiB, killed
/// after `secs`: (exit code, stdout, seconds). Panics on a timeout.
fn run_capped(args: &[&Path], cap_mib: u64, secs: u64) -> (Option<i32>, String, f64) {
    let start = Instant::now();
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {}; exec \"$0\" \"$@\"", cap_mib * 1024))
        .arg(env!("CARGO_BIN_EXE_detach-check"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            let mut out = String::new();
            child
                .stdout
                .take()
                .unwrap()
                .read_to_string(&mut out)
                .unwrap();
            return (status.code(), out, start.elapsed().as_secs_f64());
        }
        if start.elapsed() > Duration::from_secs(secs) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("detach-check {args:?} still running after {secs} s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// The small version of each bomb is VALID: the bombs are true proofs, and
/// only their size of work makes them UNCHECKED.
#[test]
fn the_bombs_are_true_proofs() {
    for b in [bomb(2, 50, "t", 4, false), bomb(2, 50, "t*w", 4, true)] {
        assert_eq!(check_bytes(&b).unwrap().verdict, Verdict::Valid);
    }
}

/// 5·10⁵ θ-only operations over 4096 θ-intervals (about 2·10⁹ operations
/// however they are cached; each interval's values are 16 MB): UNCHECKED,
/// exit 3, in less than 1 GiB and a minute.
#[test]
fn many_theta_only_operations_end_unchecked_in_bounded_memory() {
    let d = scratch("theta");
    let f = d.join("theta-bomb.json");
    std::fs::write(&f, bomb(200, 2500, "t", 12, false)).unwrap();
    let (code, out, s) = run_capped(&[&f], 1024, 120);
    assert_eq!(code, Some(3), "{out}");
    assert!(out.starts_with("UNCHECKED  "), "{out}");
    assert!(out.contains("bound for a file of"), "{out}");
    eprintln!(
        "θ bomb: {} bytes, {s:.1} s",
        std::fs::metadata(&f).unwrap().len()
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// Operations on both variables (nothing to cache) on 2¹⁶ leaves, far more
/// work than the file's size allows: UNCHECKED, exit 3, in bounded memory.
#[test]
fn many_leaves_times_many_operations_end_unchecked() {
    let d = scratch("work");
    let f = d.join("work-bomb.json");
    std::fs::write(&f, bomb(40, 2000, "t*w", 16, true)).unwrap();
    let (code, out, s) = run_capped(&[&f], 1024, 120);
    assert_eq!(code, Some(3), "{out}");
    assert!(out.starts_with("UNCHECKED  "), "{out}");
    eprintln!(
        "work bomb: {} bytes, {s:.1} s",
        std::fs::metadata(&f).unwrap().len()
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// A file of 15 million JSON values (30 MB) is refused before it is parsed
/// (parsed, it took 1.1 GB): UNCHECKED, exit 3, in little memory.
#[test]
fn too_many_json_values_end_unchecked_before_parsing() {
    let d = scratch("values");
    let f = d.join("values.json");
    let mut text = String::from("{\"format\":\"detach-proof/1\",\"x\":[0");
    text.push_str(&",0".repeat(15_000_000));
    text.push_str("]}");
    std::fs::write(&f, text).unwrap();
    let (code, out, _) = run_capped(&[&f], 256, 60);
    assert_eq!(code, Some(3), "{out}");
    assert!(out.contains("JSON values, more than 2097152"), "{out}");
    let _ = std::fs::remove_dir_all(&d);
}

/// `detach-check ARGS` with a 10 s timeout and a 512 MiB cap: a pipe or a
/// device must be refused, not read or waited on.
fn run(args: &[&Path]) -> (Option<i32>, String) {
    let (code, out, _) = run_capped(args, 512, 10);
    (code, out)
}

/// `mkfifo path`.
fn mkfifo(path: &Path) {
    let ok = Command::new("mkfifo").arg(path).status().unwrap().success();
    assert!(ok, "mkfifo {}", path.display());
}

/// Devices, a named pipe and `.json` links to them, as arguments and inside
/// a folder: one UNREADABLE line each saying what the path is, exit 2, at
/// once (a pipe with no writer would block a plain open for ever).
#[test]
fn pipes_devices_and_links_to_them_are_refused_unread() {
    let d = scratch("special");
    let fifo = d.join("pipe.json");
    mkfifo(&fifo);
    std::os::unix::fs::symlink("/dev/zero", d.join("zero.json")).unwrap();
    std::os::unix::fs::symlink("/dev/urandom", d.join("urandom.json")).unwrap();
    std::fs::create_dir(d.join("folder.json")).unwrap();
    for (path, what) in [
        (Path::new("/dev/zero"), "a device, not a regular file"),
        (Path::new("/dev/urandom"), "a device, not a regular file"),
        (&*d.join("zero.json"), "a device, not a regular file"),
        (&*fifo, "a named pipe, not a regular file"),
    ] {
        let (code, out) = run(&[path]);
        assert_eq!(code, Some(2), "{path:?}: {out}");
        let first = out.lines().next().unwrap();
        assert!(
            first.starts_with("UNREADABLE ") && first.ends_with(what),
            "{out}"
        );
    }
    let (code, out) = run(&[&d]);
    assert_eq!(code, Some(2), "{out}");
    assert_eq!(out.matches("UNREADABLE ").count(), 4, "{out}");
    assert!(
        out.contains("folder.json: a directory, not a regular file"),
        "{out}"
    );
    assert!(out.ends_with("0 valid, 0 invalid, 4 unreadable\n"), "{out}");
    let _ = std::fs::remove_dir_all(&d);
}

/// A file past the size cap may hold a true proof: UNCHECKED, exit 3,
/// without reading it (a sparse file: no disk is used).
#[test]
fn a_file_past_the_size_cap_is_unchecked_unread() {
    let d = scratch("cap");
    let f = d.join("huge.json");
    std::fs::File::create(&f)
        .unwrap()
        .set_len(detach_check::MAX_PROOF_BYTES + 1)
        .unwrap();
    let (code, out, _) = run_capped(&[&f], 64, 10);
    assert_eq!(code, Some(3), "{out}");
    let more = format!("bytes, more than {}", detach_check::MAX_PROOF_BYTES);
    assert!(
        out.starts_with("UNCHECKED  ") && out.contains(&more),
        "{out}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// A folder without a proof file, and no file at all: nothing was checked,
/// which is said, with exit 2.
#[test]
fn an_empty_folder_is_nothing_to_check() {
    let d = scratch("empty");
    let out = Command::new(env!("CARGO_BIN_EXE_detach-check"))
        .arg(&d)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("nothing to check"), "{err}");
    let _ = std::fs::remove_dir_all(&d);
}

/// Names from a file are printed escaped: a scene name and a constraint name
/// holding a newline, a fake VALID line and ANSI escapes give one verdict
/// line (INVALID: a leaf claimed in where g = 1) and no control byte.
#[test]
fn strings_from_a_file_cannot_print_a_verdict_line() {
    let d = scratch("escape");
    let fake = "\nVALID      proofs/kappa0.json  kappa0\u{1b}[1A\u{1b}[2K\r";
    let mut p = paving(1, 1, "t", 0, false);
    p["statement"]["scene"] = format!("evil{fake}").into();
    p["statement"]["constraints"][0]["name"] = format!("g{fake}").into();
    let g = p["statement"]["constraints"][0]["name"]
        .as_str()
        .unwrap()
        .to_string();
    p["statement"]["areas"][0]["literals"] = serde_json::json!({ g: "out" });
    // The one leaf claimed in: bits 0 01, padded.
    p["evidence"]["body"] = base64(&[0b0010_0000]).into();
    let f = d.join("evil.json");
    std::fs::write(&f, serde_json::to_vec(&p).unwrap()).unwrap();
    let (code, out) = run(&[&f]);
    assert_eq!(code, Some(1), "{out}");
    let verdicts = out
        .lines()
        .filter(|l| {
            ["VALID", "INVALID", "UNREADABLE", "UNCHECKED"]
                .iter()
                .any(|w| l.starts_with(w))
        })
        .count();
    assert_eq!(verdicts, 1, "{out}");
    assert!(out.bytes().all(|b| b == b'\n' || b >= 0x20), "{out:?}");
    assert!(out.contains("evil\\nVALID"), "{out}");
    let _ = std::fs::remove_dir_all(&d);
}

/// An error that quotes its input quotes at most 200 characters of it: an
/// unknown claim of 30 MB gives a line of a few hundred bytes.
#[test]
fn an_error_quoting_a_30_mb_input_is_short() {
    let d = scratch("long");
    let f = d.join("long.json");
    let text = format!(
        "{{\"format\": \"detach-proof/1\", \"claim\": \"{}\"}}",
        "x".repeat(30 << 20)
    );
    std::fs::write(&f, text).unwrap();
    let (code, out) = run(&[&f]);
    assert_eq!(code, Some(2), "{out}");
    assert!(
        out.len() < 600 && out.contains("bytes)"),
        "{} bytes: {}",
        out.len(),
        &out[..out.len().min(600)]
    );
    let _ = std::fs::remove_dir_all(&d);
}
