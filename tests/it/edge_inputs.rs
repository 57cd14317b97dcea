//! The built binary on edge inputs: one-ulp windows,
//! budgets, closed pipes, provably empty cells, odd but valid inputs.

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::common;

use common::{detach, json};

fn assert_bad_input(args: &[&str], needle: &str) {
    let err = common::assert_bad_input(args, needle);
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
}

/// Natural bisection down to the ulp (slices, the default, refines in θ
/// only where its prediction asks).
const ULP_WINDOW: [&str; 9] = [
    "pave",
    "--method",
    "natural",
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

#[test]
fn windows_accept_pi_and_decimals_within_rounding_of_pi() {
    let full = json(&["pave", "--scene", "smooth-disc", "--eps", "0.1", "--json"]);
    for hi in ["3.1415926535897932", "pi", "3.14159265358979323846264338"] {
        let arg = format!("0:{hi}");
        let out = detach(&[
            "pave",
            "--scene",
            "smooth-disc",
            "--eps",
            "0.1",
            "--theta",
            &arg,
            "--json",
        ]);
        assert_eq!(out.status.code(), Some(0), "{hi}");
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        // the same paving as the whole domain
        assert_eq!(v["domain"], full["domain"], "{hi}");
        assert_eq!(v["leaves"], full["leaves"], "{hi}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.contains("clipped"), hi != "pi", "{hi}: {err}");
    }
    let v = json(&[
        "pave",
        "--scene",
        "viscous-disc",
        "--eps",
        "0.1",
        "--theta",
        "-pi:pi/2",
        "--json",
    ]);
    assert_eq!(v["domain"]["theta"][0], -std::f64::consts::PI);
    let hi = v["domain"]["theta"][1].as_f64().unwrap();
    // the largest double not above π/2 (π/2 rounded down)
    assert_eq!(hi, std::f64::consts::FRAC_PI_2);
    // provably outside: refused
    assert_bad_input(
        &["pave", "--scene", "smooth-disc", "--theta", "0:3.1416"],
        "inside the scene's domain",
    );
    assert_bad_input(
        &["pave", "--scene", "smooth-disc", "--theta", "0:2pi"],
        "pi/N",
    );
}

#[test]
fn counts_and_numbers_are_read_as_written() {
    let v = json(&[
        "pave",
        "--scene",
        "ice-disc",
        "--max-boxes",
        "1e3",
        "--json",
    ]);
    assert_eq!(v["max_boxes"], 1000);
    assert!(v["leaves"].as_u64().unwrap() <= 1000);
    // negative numbers reach our validators, with our words
    for (args, needle) in [
        (
            vec!["pave", "--scene", "ice-disc", "--max-boxes", "-1"],
            "negative",
        ),
        (
            vec!["pave", "--scene", "ice-disc", "--max-boxes", "1.5"],
            "integer",
        ),
        (
            vec!["tangency", "--k-max", "-3"],
            "--k-max must be between 1 and 17",
        ),
        (vec!["critical-curve", "--alpha-boxes", "-8"], "negative"),
        (
            vec!["critical-curve", "--kappa-max", "-1"],
            "--kappa-max must be positive",
        ),
        (
            vec![
                "roots",
                "--equation",
                "2.10",
                "--max-evaluations",
                "-5",
                "--kappa",
                "0.1",
            ],
            "negative",
        ),
    ] {
        let out = detach(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("unexpected argument"), "{args:?}: {err}");
    }
    assert_bad_input(
        &["pave", "--scene", "smooth-disc", "--param", "A=1e400"],
        "too large",
    );
    // a budget beyond the memory budget is refused before any work
    assert_bad_input(
        &["pave", "--scene", "smooth-disc", "--max-boxes", "1e12"],
        "memory budget",
    );
}

#[test]
fn kappa_under_and_overflow_are_said_plainly() {
    for p in ["p_phi=1e-160", "p_phi=1e-170"] {
        let out = detach(&[
            "roots",
            "--equation",
            "2.9",
            "--scene",
            "smooth-disc",
            "--param",
            "p_psi=0",
            "--param",
            p,
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{p}: {err}");
        assert!(err.contains("overflows the range of doubles"), "{p}: {err}");
        assert!(!err.contains("both zero"), "{p}: {err}");
        assert!(err.len() < 200, "{p}: {err}");
    }
    assert_bad_input(
        &[
            "roots",
            "--equation",
            "2.9",
            "--scene",
            "smooth-disc",
            "--param",
            "p_psi=0",
            "--param",
            "p_phi=0",
        ],
        "both zero",
    );
}

#[test]
fn roots_tables_read_as_words() {
    let out = detach(&["roots", "--equation", "2.10", "--kappa", "0.1"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("exactly 2 roots, all simple"), "{text}");
    assert!(!text.contains("root(s)"));
    let out = detach(&["roots", "--equation", "2.10", "--kappa", "0.3"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("no root"), "{text}");
    assert!(!text.contains("exactly 0"), "{text}");
    assert!(!text.contains("-0e0"), "{text}");
    // at κ₀ itself the double root is undecided, in words
    let out = detach(&[
        "roots",
        "--equation",
        "2.10",
        "--kappa",
        "0.19245008972987525",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(!text.contains("possiblemultipleroot"), "{text}");
    assert!(!text.contains("domainedge"), "{text}");
}

#[test]
fn a_scene_named_twice_is_paved_once() {
    let dir = std::env::temp_dir().join(format!("detach-twice-{}", std::process::id()));
    let out = detach(&[
        "atlas",
        "--scene",
        "ice-disc",
        "--scene",
        "ice-disc",
        "--eps",
        "0.05",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(v["scenes"].as_array().unwrap().len(), 1);
    assert_eq!(v["detach"]["version"], env!("CARGO_PKG_VERSION"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn underflow_is_reported_not_silent() {
    for args in [
        vec![
            "pave",
            "--scene",
            "smooth-disc",
            "--variant",
            "printed",
            "--param",
            "A=1e-200",
            "--eps",
            "0.1",
        ],
        vec!["pave", "--scene", "smooth-disc", "--theta", "1e-300:1e-299"],
    ] {
        let mut j = args.clone();
        j.push("--json");
        let v = json(&j);
        let w = v["warnings"][0].as_str().unwrap_or_default();
        assert!(w.contains("under- or overflowed"), "{args:?}: {v}");
        assert!(v["undefined_area"].as_f64().unwrap() > 0.0);
        let out = detach(&args);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains("warning: every leaf is undefined"), "{text}");
        assert!(!text.contains("0000000000"), "no 300-digit numbers: {text}");
    }
    // an ordinary paving has no warning
    let v = json(&["pave", "--scene", "ice-disc", "--eps", "0.05", "--json"]);
    assert!(v.get("warnings").is_none());
}

#[test]
fn version_and_parameters_are_recorded() {
    let out = detach(&["--version"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.starts_with(&format!("detach {} (commit ", env!("CARGO_PKG_VERSION"))),
        "{text}"
    );
    let v = json(&["pave", "--scene", "ice-disc", "--eps", "0.1", "--json"]);
    assert_eq!(v["detach"]["version"], env!("CARGO_PKG_VERSION"));
    assert!(v["detach"]["commit"].as_str().is_some());
    assert_eq!(v["params"]["c0"], "0");
    let v = json(&["roots", "--equation", "2.10", "--kappa", "0.1", "--json"]);
    assert_eq!(v["detach"]["version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(v["arguments"]["kappa"], "0.1");
    let dir = std::env::temp_dir().join(format!("detach-prov-{}", std::process::id()));
    let d = dir.to_str().unwrap();
    detach(&["tangency", "--k-max", "2", "--out", d]);
    detach(&[
        "critical-curve",
        "--alpha-boxes",
        "8",
        "--kappa-boxes",
        "8",
        "--out",
        d,
    ]);
    for (f, key, val) in [
        ("tangency.json", "k_max", serde_json::json!(2)),
        ("critical-curve.json", "alpha_boxes", serde_json::json!(8)),
    ] {
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join(f)).unwrap()).unwrap();
        assert_eq!(v["detach"]["version"], env!("CARGO_PKG_VERSION"), "{f}");
        assert_eq!(v["arguments"][key], val, "{f}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Parses a C99 hexadecimal float (`[-]0x1.<hex>p<exp>`, `[-]0x0.<hex>p-1022`)
/// exactly; written here independently of the exporter.
fn parse_hex(s: &str) -> f64 {
    let (neg, body) = match s.strip_prefix('-') {
        Some(b) => (true, b),
        None => (false, s),
    };
    let body = body.strip_prefix("0x").expect("0x");
    let (mant, exp) = body.split_once('p').expect("p");
    let (int, frac) = mant.split_once('.').unwrap_or((mant, ""));
    let exp: i32 = exp.parse().unwrap();
    // value = (int·16^len + frac) · 16^-len · 2^exp, built from exact integers
    let digits = format!("{int}{frac}");
    let m = u128::from_str_radix(&digits, 16).unwrap();
    let shift = exp - 4 * frac.len() as i32;
    // m < 2^57 here, so m as f64 is exact; scale by powers of two exactly
    let mut x = m as f64;
    let mut k = shift;
    while k > 0 {
        let step = k.min(1000);
        x *= 2f64.powi(step);
        k -= step;
    }
    while k < 0 {
        let step = (-k).min(1000);
        // split large negative scalings so no intermediate underflows early
        let s1 = step / 2;
        x *= 2f64.powi(-s1);
        x *= 2f64.powi(-(step - s1));
        k += step;
    }
    if neg {
        -x
    } else {
        x
    }
}

#[test]
fn leaves_export_round_trips_exactly() {
    let dir = std::env::temp_dir().join(format!("detach-leaves-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("leaves.csv");
    let out = detach(&[
        "pave",
        "--method",
        "natural",
        "--scene",
        "ice-disc",
        "--eps",
        "0.02",
        "--leaves",
        file.to_str().unwrap(),
        "--json",
    ]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let text = std::fs::read_to_string(&file).unwrap();
    let mut lines = text.lines();
    let first = lines.next().unwrap();
    assert!(
        first.starts_with("# detach ")
            && first.contains("scene ice-disc")
            && first.contains("p_phi=2.5"),
        "{first}"
    );
    assert_eq!(
        lines.next().unwrap(),
        "theta_lo,theta_hi,theta_dot_lo,theta_dot_hi,theta_lo_hex,theta_hi_hex,\
         theta_dot_lo_hex,theta_dot_hi_hex,omega,omega0"
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len() as u64, v["leaves"].as_u64().unwrap());
    // the same paving through the library, leaf by leaf
    let (scene, _) = detach::scene::Scene::build(detach::scene::SceneId::IceDisc, &[]).unwrap();
    let paving = detach::pave::pave_scene(
        &scene,
        detach::scene::Variant::Derived,
        detach::pave::PaveOptions {
            eps: 0.02,
            max_boxes: 4_000_000,
        },
        |_, _, _| {},
    )
    .unwrap();
    assert_eq!(paving.leaves.len(), rows.len());
    let word = |l: detach::pave::Label| match l {
        detach::pave::Label::ProvedIn => "in",
        detach::pave::Label::ProvedOut => "out",
        detach::pave::Label::Undecided => "undecided",
        detach::pave::Label::Undefined => "undefined",
    };
    let (mut ins, mut outs) = (0, 0);
    for (row, leaf) in rows.iter().zip(&paving.leaves) {
        assert_eq!(row.len(), 10);
        let ends = [
            leaf.bx.theta[0],
            leaf.bx.theta[1],
            leaf.bx.theta_dot[0],
            leaf.bx.theta_dot[1],
        ];
        for k in 0..4 {
            let dec: f64 = row[k].parse().unwrap();
            let hex = parse_hex(row[4 + k]);
            assert_eq!(dec.to_bits(), ends[k].to_bits(), "{row:?}");
            assert_eq!(hex.to_bits(), ends[k].to_bits(), "{row:?}");
        }
        assert_eq!(row[8], word(leaf.labels[0]));
        assert_eq!(row[9], word(leaf.labels[1]));
        ins += (row[8] == "in") as usize;
        outs += (row[9] == "out") as usize;
    }
    assert!(ins > 0 && outs > 0);
    eprintln!(
        "leaves export: {} bytes for {} leaves ({:.0} bytes per leaf)",
        text.len(),
        rows.len(),
        text.len() as f64 / rows.len() as f64
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn ice_omega0_inside_omega_leaves_its_paradox_cell_without_a_box() {
    // §3 subcase 1 (p_φ = p_ψ = 0): Ω₀ ⊂ Ω (paper-checks S3.sub1), so no
    // box of Ω̄∩Ω₀ may be proved; the paving bounds it from above only.
    let cell = |args: &[&str]| {
        let out = detach(args);
        assert!(out.status.success());
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        v["regions"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["name"] == "not_omega_and_omega0")
            .cloned()
            .unwrap()
    };
    let zero = cell(&[
        "pave", "--scene", "ice-disc", "--param", "p_phi=0", "--param", "p_psi=0", "--eps", "0.02",
        "--json",
    ]);
    assert_eq!(zero["inner_area"].as_f64(), Some(0.0));
    assert!(zero["outer_area"].as_f64().unwrap() < 0.5);
    let other = cell(&["pave", "--scene", "ice-disc", "--eps", "0.02", "--json"]);
    assert!(other.get("empty").is_none());
    assert!(other["outer_area"].as_f64().unwrap() > 0.0);
}

#[test]
fn ice_omega0_is_decided_next_to_theta_pi() {
    // ln tg(θ/2) through tan(θ/2) stays defined up to θ = π (a form through
    // ln(1 + cos θ) left the whole last θ-column, 0.01 of the window,
    // undefined). Only the sliver whose labels would rest on the last bits
    // of θ (θ/2 within ulps of tan's pole; slabs are widened by
    // THETA_SLACK_ULPS) stays undefined: a positive area far below a column.
    let out = detach(&[
        "pave", "--scene", "ice-disc", "--theta", "3.09:pi", "--eps", "0.01", "--json",
    ]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let undefined = v["undefined_area"].as_f64().unwrap();
    assert!(undefined > 0.0 && undefined < 1e-3, "{undefined}");
    let omega0 = v["regions"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["name"] == "omega0")
        .cloned()
        .unwrap();
    let (inner, outer) = (
        omega0["inner_area"].as_f64().unwrap(),
        omega0["outer_area"].as_f64().unwrap(),
    );
    assert!(inner > 1.0 && outer - inner < 1e-3, "[{inner}, {outer}]");
}

/// `slices` (the default) in a window two ulps wide in θ: its slabs cannot
/// be split, so it says it stopped at the limit of double precision, not at
/// the resolution asked for.
#[test]
fn slices_at_the_ulp_limit_says_so() {
    let v = json(&[
        "pave",
        "--scene",
        "viscous-disc",
        "--theta",
        "1.5:1.5000000000000004",
        "--theta-dot",
        "4.42:4.46",
        "--eps",
        "1e-300",
        "--json",
    ]);
    assert_eq!(v["method"], "slices");
    assert_eq!(v["stop"], "double_precision_limit");
}
