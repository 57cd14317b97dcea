//! The built binary on the inputs of the hardening audit: one-ulp windows,
//! budgets, closed pipes, provably empty cells, odd but valid inputs.

use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn detach(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_detach"))
        .args(args)
        .output()
        .expect("runs")
}

fn json(args: &[&str]) -> serde_json::Value {
    let out = detach(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON on stdout")
}

fn assert_bad_input(args: &[&str], needle: &str) {
    let out = detach(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: stderr {err}");
    assert!(err.contains(needle), "{args:?}: `{needle}` not in {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
}

const ULP_WINDOW: [&str; 7] = [
    "pave",
    "--scene",
    "viscous-disc",
    "--theta",
    "1.5:1.5000000000000004",
    "--theta-dot",
    "4.42:4.46",
];

#[test]
fn one_ulp_boxes_are_leaves_and_the_stop_reason_is_stated() {
    let start = Instant::now();
    let mut args = ULP_WINDOW.to_vec();
    args.push("--json");
    let v = json(&args);
    assert!(start.elapsed() < Duration::from_secs(10));
    // 1.5 and 1.5000000000000004 are two ulps apart: one split, then θ is
    // unsplittable; θ̇ is refined to eps as usual.
    assert_eq!(v["complete"], true);
    assert_eq!(v["stop"], "double_precision_limit");
    let leaves = v["leaves"].as_u64().unwrap();
    assert!(leaves < 10_000, "{leaves} leaves");
    assert!(v["stats"]["depth"].as_u64().unwrap() < 60);
    // the table says why
    let table = detach(&ULP_WINDOW);
    let text = String::from_utf8_lossy(&table.stdout);
    assert!(text.contains("stop: double_precision_limit"), "{text}");
    assert!(text.contains("limit of double precision"), "{text}");
}

#[test]
fn a_tiny_eps_is_bounded_by_double_precision_and_the_budget() {
    let start = Instant::now();
    let mut args = ULP_WINDOW.to_vec();
    args.extend(["--eps", "1e-300", "--json"]);
    let v = json(&args);
    assert!(start.elapsed() < Duration::from_secs(20));
    assert_eq!(v["stop"], "double_precision_limit");
    assert!(v["leaves"].as_u64().unwrap() < 100_000);
    // on a whole domain, the budget stops it
    let v = json(&[
        "pave",
        "--scene",
        "smooth-disc",
        "--eps",
        "1e-300",
        "--max-boxes",
        "20000",
        "--json",
    ]);
    assert_eq!(v["stop"], "budget");
    assert_eq!(v["complete"], false);
    assert!(v["leaves"].as_u64().unwrap() <= 20_000);
}

#[test]
fn stop_reasons_resolution_and_all_decided() {
    let v = json(&["pave", "--scene", "ice-disc", "--eps", "0.05", "--json"]);
    assert_eq!(v["stop"], "resolution");
    // a window far from every boundary is decided at once
    let v = json(&[
        "pave",
        "--scene",
        "viscous-disc",
        "--theta",
        "-0.1:0.1",
        "--theta-dot",
        "-0.5:0.5",
        "--json",
    ]);
    assert_eq!(v["stop"], "all_decided");
    assert_eq!(v["leaves"], 1);
}

#[test]
fn critical_curve_output_is_budgeted() {
    let dir = std::env::temp_dir().join(format!("detach-cc-budget-{}", std::process::id()));
    assert_bad_input(
        &[
            "critical-curve",
            "--alpha-boxes",
            "4096",
            "--kappa-boxes",
            "4096",
            "--out",
            dir.to_str().unwrap(),
        ],
        "output budget",
    );
    assert!(!dir.exists(), "nothing written when refused");
}

#[test]
fn undecided_area_is_an_upper_bound() {
    let v = json(&["pave", "--scene", "viscous-disc", "--eps", "0.01", "--json"]);
    for r in v["regions"].as_array().unwrap() {
        let (i, o, u) = (
            r["inner_area"].as_f64().unwrap(),
            r["outer_area"].as_f64().unwrap(),
            r["undecided_area"].as_f64().unwrap(),
        );
        // u ≥ o − i in exact arithmetic: o − i rounded up is at most u.
        let pt = |x: f64| inari::Interval::try_from((x, x)).unwrap();
        assert!((pt(o) - pt(i)).sup() <= u, "{r}");
        assert!(u >= 0.0);
    }
}

#[test]
fn smooth_disc_paradox_cells_are_exactly_empty() {
    for variant in ["derived", "printed"] {
        let v = json(&[
            "pave",
            "--scene",
            "smooth-disc",
            "--variant",
            variant,
            "--eps",
            "0.01",
            "--json",
        ]);
        for r in v["regions"].as_array().unwrap() {
            let name = r["name"].as_str().unwrap();
            if name == "not_omega_and_omega0" || name == "omega_and_not_omega0" {
                assert_eq!(r["outer_area"], 0.0, "{variant} {name}");
                assert_eq!(r["inner_area"], 0.0);
                assert_eq!(r["boxes"]["outer"], 0);
                assert_eq!(r["empty"], "omega0 = omega");
            } else {
                assert!(r.get("empty").is_none(), "{name}");
            }
        }
        let table = detach(&[
            "pave",
            "--scene",
            "smooth-disc",
            "--variant",
            variant,
            "--eps",
            "0.01",
        ]);
        let text = String::from_utf8_lossy(&table.stdout);
        assert_eq!(text.matches("empty (Ω₀ = Ω)").count(), 2, "{text}");
    }
    // the disc on ice has no such identity
    let v = json(&["pave", "--scene", "ice-disc", "--eps", "0.05", "--json"]);
    assert!(v["regions"][4]["outer_area"].as_f64().unwrap() > 0.0);
    assert!(v["regions"][4].get("empty").is_none());
}

#[test]
fn table_rows_line_up_with_combining_overbars() {
    let out = detach(&["pave", "--scene", "ice-disc", "--eps", "0.05"]);
    let text = String::from_utf8_lossy(&out.stdout);
    let width = |l: &str| {
        l.chars()
            .filter(|c| !('\u{0300}'..='\u{036f}').contains(c))
            .count()
    };
    let rows: Vec<&str> = text.lines().skip(1).take(7).collect();
    assert_eq!(rows.len(), 7);
    let w0 = width(rows[0]);
    for r in &rows {
        assert_eq!(width(r), w0, "{text}");
    }
}

/// Runs the binary with stdout a pipe that is closed after reading `keep`
/// bytes; returns the exit status and stderr.
fn with_closed_stdout(args: &[&str], keep: usize) -> (std::process::ExitStatus, String) {
    use std::io::Read;
    let mut child = Command::new(env!("CARGO_BIN_EXE_detach"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawns");
    let mut stdout = child.stdout.take().unwrap();
    let mut buf = vec![0u8; keep];
    let _ = stdout.read_exact(&mut buf);
    drop(stdout);
    let mut err = String::new();
    child.stderr.take().unwrap().read_to_string(&mut err).ok();
    (child.wait().unwrap(), err)
}

#[test]
fn a_closed_stdout_is_not_a_panic() {
    let dir = std::env::temp_dir().join(format!("detach-pipe-{}", std::process::id()));
    let d = dir.to_str().unwrap();
    let cases: Vec<Vec<&str>> = vec![
        vec!["scenes"],
        vec!["scenes", "--json"],
        vec!["pave", "--scene", "ice-disc", "--eps", "0.05"],
        vec!["pave", "--scene", "ice-disc", "--eps", "0.05", "--json"],
        vec!["roots", "--equation", "2.10", "--kappa", "0.1"],
        vec!["kappa0"],
        vec!["kappa0", "--json"],
        vec!["tangency", "--k-max", "2", "--out", d],
        vec![
            "critical-curve",
            "--alpha-boxes",
            "8",
            "--kappa-boxes",
            "8",
            "--out",
            d,
        ],
        vec![
            "atlas",
            "--scene",
            "smooth-disc",
            "--eps",
            "0.05",
            "--out",
            d,
        ],
    ];
    for args in &cases {
        for keep in [0, 10] {
            let (status, err) = with_closed_stdout(args, keep);
            assert!(!err.contains("panicked"), "{args:?}: {err}");
            assert!(!err.contains("Broken pipe"), "{args:?}: {err}");
            assert_eq!(status.code(), Some(0), "{args:?}: {err}");
        }
    }
    // atlas wrote its files although nobody read its table
    for f in ["smooth-disc.svg", "smooth-disc.png", "summary.json"] {
        assert!(dir.join(f).metadata().unwrap().len() > 0, "{f}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
