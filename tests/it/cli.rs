//! The command line: bad input gets one clear line and exit code 2; good input
//! gives the documented JSON.

use crate::common;

use common::{assert_bad_input, detach, json};

#[test]
fn bad_input_is_a_clear_error_with_exit_code_2() {
    assert_bad_input(&["pave", "--scene", "brick"], "unknown scene `brick`");
    assert_bad_input(
        &["pave", "--scene", "smooth-disc", "--param", "q=1"],
        "unknown parameter `q`",
    );
    assert_bad_input(
        &["pave", "--scene", "smooth-disc", "--param", "g=NaN"],
        "not a finite decimal",
    );
    assert_bad_input(
        &["pave", "--scene", "smooth-disc", "--param", "g=inf"],
        "not a finite decimal",
    );
    assert_bad_input(
        &["pave", "--scene", "smooth-disc", "--param", "m=0"],
        "scenes/smooth-disc.toml: `conditions.m_positive`: `m > 0` does not hold with m = 0",
    );
    assert_bad_input(
        &["pave", "--scene", "viscous-disc", "--param", "m=-1"],
        "`m > 0` does not hold with m = -1",
    );
    assert_bad_input(
        &["pave", "--scene", "viscous-disc", "--param", "mu=-0.1"],
        "`mu >= 0` does not hold with mu = -0.1",
    );
    assert_bad_input(
        &["pave", "--scene", "viscous-disc", "--param", "b=2"],
        "b < a",
    );
    assert_bad_input(
        &["pave", "--scene", "viscous-disc", "--param", "mu"],
        "name=value",
    );
    assert_bad_input(&["pave", "--scene", "smooth-disc", "--eps", "0"], "--eps");
    assert_bad_input(&["pave", "--scene", "smooth-disc", "--eps", "-1"], "--eps");
    assert_bad_input(&["pave", "--scene", "smooth-disc", "--eps", "NaN"], "--eps");
    assert_bad_input(
        &["pave", "--scene", "smooth-disc", "--max-boxes", "0"],
        "max-boxes",
    );
    assert_bad_input(
        &["pave", "--scene", "smooth-disc", "--theta", "1:1"],
        "empty",
    );
    assert_bad_input(
        &["pave", "--scene", "smooth-disc", "--theta-dot", "3:-3"],
        "empty",
    );
    assert_bad_input(
        &["pave", "--scene", "smooth-disc", "--theta", "-1:1"],
        "inside the scene's domain",
    );
    assert_bad_input(&["pave", "--scene", "smooth-disc", "--theta", "1"], "LO:HI");
    // A window end is named by its option, not called a parameter.
    for (opt, end) in [("--theta", "0:abc"), ("--theta-dot", "1e400:2")] {
        let err = assert_bad_input(&["pave", "--scene", "smooth-disc", opt, end], opt);
        assert!(!err.contains("parameter"), "{err}");
    }
    assert_bad_input(&["atlas", "--scene", "nope"], "unknown scene");
    assert_bad_input(&["atlas", "--param", "zz=1"], "unknown parameter `zz`");
    assert_bad_input(&["pave"], "--scene");
}

#[test]
fn pave_json_has_the_documented_fields() {
    let out = detach(&[
        "pave",
        "--scene",
        "viscous-disc",
        "--eps",
        "0.01",
        "--param",
        "mu=0.5",
        "--json",
    ]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["scene"], "viscous-disc");
    assert_eq!(v["variant"], "derived");
    assert_eq!(v["params"]["mu"], "0.5");
    assert_eq!(v["params"]["g"], "9.81");
    assert_eq!(v["eps"], 0.01);
    assert_eq!(v["complete"], true);
    assert!(v["elapsed_s"].as_f64().unwrap() >= 0.0);
    assert!(v["domain"]["theta"][0].as_f64().unwrap() >= -std::f64::consts::PI);
    let names: Vec<&str> = v["regions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "omega",
            "omega0",
            "omega_and_omega0",
            "not_omega_and_not_omega0",
            "not_omega_and_omega0",
            "omega_and_not_omega0"
        ]
    );
    for r in v["regions"].as_array().unwrap() {
        let (i, o) = (
            r["inner_area"].as_f64().unwrap(),
            r["outer_area"].as_f64().unwrap(),
        );
        assert!(0.0 <= i && i <= o && o <= 20.0 * 2.0 * std::f64::consts::PI + 1e-9);
        let b = &r["boxes"];
        assert_eq!(
            b["outer"].as_u64().unwrap() - b["inner"].as_u64().unwrap(),
            b["undecided"].as_u64().unwrap()
        );
    }
}

#[test]
fn a_budget_is_reported_and_the_result_kept() {
    let out = detach(&[
        "pave",
        "--scene",
        "ice-disc",
        "--max-boxes",
        "100",
        "--json",
    ]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["complete"], false);
    assert!(v["leaves"].as_u64().unwrap() <= 100);
    let table = detach(&["pave", "--scene", "ice-disc", "--max-boxes", "100"]);
    assert!(String::from_utf8_lossy(&table.stdout).contains("budget reached"));
}

#[test]
fn atlas_writes_pictures_and_summary() {
    let dir = std::env::temp_dir().join(format!("detach-atlas-{}", std::process::id()));
    let out = detach(&[
        "atlas",
        "--out",
        dir.to_str().unwrap(),
        "--scene",
        "smooth-disc",
        "--eps",
        "0.02",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for f in ["smooth-disc.svg", "smooth-disc.png", "summary.json"] {
        assert!(dir.join(f).metadata().unwrap().len() > 0, "{f}");
    }
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(v["scenes"][0]["scene"], "smooth-disc");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn scenes_lists_every_scene_with_defaults() {
    let out = detach(&["scenes", "--json"]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let names: Vec<&str> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        ["viscous-disc", "smooth-disc", "ice-disc", "painleve-rod"]
    );
    assert_eq!(v[2]["params"][7]["name"], "c0");
    assert_eq!(v[0]["params"][4]["default"], "0.8");
}

#[test]
fn roots_bad_input_is_a_clear_error_with_exit_code_2() {
    assert_bad_input(
        &[
            "roots",
            "--equation",
            "2.9",
            "--kappa",
            "0",
            "--alpha",
            "0.5",
        ],
        "κ must be positive",
    );
    assert_bad_input(
        &[
            "roots",
            "--equation",
            "2.9",
            "--kappa",
            "-1",
            "--alpha",
            "0.5",
        ],
        "κ must be positive",
    );
    assert_bad_input(
        &[
            "roots",
            "--equation",
            "2.9",
            "--kappa",
            "NaN",
            "--alpha",
            "0.5",
        ],
        "not a finite decimal",
    );
    assert_bad_input(
        &[
            "roots",
            "--equation",
            "2.9",
            "--kappa",
            "0.1",
            "--alpha",
            "1.5",
        ],
        "α must lie in [-1, 1]",
    );
    assert_bad_input(
        &["roots", "--equation", "7", "--kappa", "0.1"],
        "unknown equation",
    );
    assert_bad_input(
        &["roots", "--equation", "2.12", "--scene", "brick"],
        "unknown scene",
    );
}

#[test]
fn roots_json_reads_back_and_brackets_the_closed_form() {
    // (2.10) is μ³ − μ + 2κ = 0; for κ = 0.1 the positive roots are
    // (2/√3) cos(φ/3 − 2πk/3), cos φ = −3√3 κ, k = 0 and 1 (trigonometric form).
    let out = detach(&["roots", "--equation", "2.10", "--kappa", "0.1", "--json"]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["equation"], "2.10");
    assert_eq!(v["complete"], true);
    let phi = (-3.0 * 3f64.sqrt() * 0.1).acos();
    let mut expect: Vec<f64> = [0.0, 1.0]
        .iter()
        .map(|k| 2.0 / 3f64.sqrt() * (phi / 3.0 - 2.0 * std::f64::consts::PI * k / 3.0).cos())
        .collect();
    expect.sort_by(f64::total_cmp);
    let roots = v["roots"].as_array().unwrap();
    assert_eq!(roots.len(), 2);
    for (r, e) in roots.iter().zip(expect) {
        let (lo, hi) = (r["lo"].as_f64().unwrap(), r["hi"].as_f64().unwrap());
        assert_eq!(r["status"], "unique");
        assert!(
            lo - 1e-14 <= e && e <= hi + 1e-14 && hi - lo < 1e-13,
            "{lo} {hi} {e}"
        );
    }
}

/// docs/cli.md is what `docs/gen-cli.sh` makes from this binary's help:
/// the reference cannot drift from clap's definitions.
#[test]
fn cli_reference_matches_the_help() {
    let root = env!("CARGO_MANIFEST_DIR");
    let out = std::process::Command::new("bash")
        .arg(format!("{root}/docs/gen-cli.sh"))
        .args([env!("CARGO_BIN_EXE_detach"), "-"])
        .output()
        .expect("runs bash");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let committed = std::fs::read_to_string(format!("{root}/docs/cli.md")).unwrap();
    assert!(
        String::from_utf8_lossy(&out.stdout) == committed,
        "docs/cli.md is stale: run docs/gen-cli.sh"
    );
}

/// Inputs the roots command refuses as usage errors (exit 2, one line): a
/// missing or out-of-range κ or α, an equation that takes none of the given
/// inputs, a scene without the equation, an unknown parameter.
#[test]
fn roots_refuses_incomplete_or_misplaced_input() {
    for (args, needle) in [
        (
            &["roots", "--equation", "2.9", "--kappa", "0.1"][..],
            "needs --alpha",
        ),
        (
            &["roots", "--equation", "2.10", "--kappa", "-1"],
            "κ must be positive",
        ),
        (&["roots", "--equation", "2.10"], "needs --kappa"),
        (&["roots", "--equation", "2.11"], "unknown equation"),
        (
            &["roots", "--equation", "3.3", "--scene", "smooth-disc"],
            "needs scene ice-disc",
        ),
        (
            &["roots", "--equation", "2.12", "--param", "zz=1"],
            "unknown parameter `zz`",
        ),
    ] {
        let err = assert_bad_input(args, needle);
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    }
}

/// The documented fields of `roots --json` for (2.10) at κ = 0.1: two
/// unique roots (the closed form above has two positive roots), each
/// `lo ≤ hi`, and κ recorded as the text given.
#[test]
fn roots_json_has_the_documented_fields() {
    let v = json(&["roots", "--equation", "2.10", "--kappa", "0.1", "--json"]);
    assert_eq!(v["variable"], "mu");
    let roots = v["roots"].as_array().unwrap();
    assert_eq!(roots.len(), 2);
    for r in roots {
        assert_eq!(r["status"], "unique");
        assert!(r["lo"].as_f64().unwrap() <= r["hi"].as_f64().unwrap());
    }
    assert_eq!(v["parameters"][0]["text"], "0.1");
}

/// critical-curve and tangency write their picture and JSON files, and
/// refuse a grid that is not a power of two, a figure below 400x300 and an
/// unknown format.
#[test]
fn root_maps_write_their_files_and_refuse_bad_figures() {
    let dir = std::env::temp_dir().join(format!("detach-root-maps-{}", std::process::id()));
    let cc = dir.join("cc");
    let t = dir.join("t");
    let cc_args = [
        "critical-curve",
        "--out",
        cc.to_str().unwrap(),
        "--alpha-boxes",
        "8",
        "--kappa-boxes",
        "8",
    ];
    assert!(detach(&cc_args).status.success());
    let t_args = ["tangency", "--out", t.to_str().unwrap(), "--k-max", "2"];
    assert!(detach(&t_args).status.success());
    for f in [
        "cc/critical-curve.svg",
        "cc/critical-curve.png",
        "cc/critical-curve.json",
        "t/tangency.svg",
        "t/tangency.png",
        "t/tangency.json",
    ] {
        let len = std::fs::metadata(dir.join(f)).map(|m| m.len()).unwrap_or(0);
        assert!(len > 100, "{f} missing or empty");
    }
    let mut bad = cc_args.to_vec();
    bad[4] = "3";
    assert_bad_input(&bad, "power of two");
    for (extra, needle) in [
        (["--size", "10x10"], "width must be in [400, 8192]"),
        (["--format", "pdf"], "PDF output is not supported"),
        (["--format", "gif"], "unknown format `gif`"),
    ] {
        let mut bad = t_args.to_vec();
        bad.extend(extra);
        assert_bad_input(&bad, needle);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `area` refuses at once a width binary64 cannot certify, naming every set
/// that cannot reach it and the digits all of them can: asking for those
/// digits then succeeds.
#[test]
fn area_refuses_places_below_binary64_rounding() {
    let err = assert_bad_input(
        &["area", "--scene", "viscous-disc", "--digits", "14"],
        "below what binary64 arithmetic certifies",
    );
    for set in ["Ω (omega)", "Ω₀ (omega0)", "Ω∩Ω̄₀ (omega_and_not_omega0)"] {
        assert!(err.contains(set), "{err}");
    }
    assert!(err.starts_with("detach: --digits: "), "{err}");
    let digits = err
        .split("ask for at most ")
        .nth(1)
        .map(str::trim)
        .unwrap_or_else(|| panic!("{err}"));
    assert_eq!(digits, "12", "{err}");
    let out = detach(&["area", "--scene", "viscous-disc", "--digits", digits]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `detach area` says why a set is empty, as its `--json` does: the rod's
/// paradox cells at μ = 0.5 < 4/3 and the smooth disc's are proved empty by
/// a paving of the domain (the rod's Ω₀, `U/V < 0`, is not its Ω, `U < 0`,
/// so "Ω₀ = Ω" would be false of it).
#[test]
fn area_says_why_a_set_is_empty() {
    for args in [
        &[
            "area",
            "--scene",
            "painleve-rod",
            "--param",
            "mu=0.5",
            "--digits",
            "6",
        ][..],
        &["area", "--scene", "smooth-disc", "--digits", "6"][..],
    ] {
        let out = detach(args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8(out.stdout).unwrap();
        let report = json(&[args, &["--json"]].concat());
        let proved = report["regions"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|r| r["empty"] == "proved empty")
            .count();
        assert_eq!(proved, 2, "{report}");
        assert_eq!(
            text.matches("0 (empty: proved empty)").count(),
            proved,
            "{text}"
        );
        assert!(!text.contains("Ω₀ = Ω"), "{text}");
    }
}

/// A round-joined path (a polyline, or a phase band whose stroke is the
/// certified band's own width in pixels: data, not style).
const BAND: &str = "stroke-linejoin=\"round\"";

/// Every `attr="…"` number of an SVG outside its `<defs>` (the hatching
/// texture keeps its fine spacing), on lines that are phase bands or not,
/// sorted.
fn svg_numbers_of(svg: &str, attr: &str, bands: bool) -> Vec<f64> {
    let key = format!("{attr}=\"");
    let body = match (svg.find("<defs>"), svg.find("</defs>")) {
        (Some(a), Some(b)) => format!("{}{}", &svg[..a], &svg[b..]),
        _ => svg.to_string(),
    };
    let mut v: Vec<f64> = body
        .lines()
        .filter(|l| l.contains(BAND) == bands)
        .flat_map(|l| l.split(&key).skip(1))
        .map(|s| s[..s.find('"').unwrap()].parse().unwrap())
        .collect();
    v.sort_by(f64::total_cmp);
    v
}

fn svg_numbers(svg: &str, attr: &str) -> Vec<f64> {
    svg_numbers_of(svg, attr, false)
}

/// `--size` twice the default in both directions doubles every font size
/// and line width: the text and lines grow with the canvas (they stayed at
/// the default's size before, unreadable on a poster).
#[test]
fn atlas_text_and_lines_grow_with_size() {
    let dir = std::env::temp_dir().join(format!("detach-atlas-size-{}", std::process::id()));
    let svg = |size: &str| {
        let d = dir.join(size);
        let out = detach(&[
            "atlas",
            "--out",
            d.to_str().unwrap(),
            "--scene",
            "smooth-disc",
            "--eps",
            "0.1",
            "--format",
            "svg",
            "--size",
            size,
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        std::fs::read_to_string(d.join("smooth-disc.svg")).unwrap()
    };
    let (small, large) = (svg("1200x800"), svg("2400x1600"));
    for attr in ["font-size", "stroke-width"] {
        let (a, b) = (svg_numbers(&small, attr), svg_numbers(&large, attr));
        assert!(!a.is_empty(), "{attr}");
        assert_eq!(a.len(), b.len(), "{attr}");
        for (x, y) in a.iter().zip(&b) {
            assert!(
                (y - 2.0 * x).abs() <= 0.02,
                "{attr}: {x} at 1200x800, {y} at 2400x1600"
            );
        }
    }
    // Round-joined strokes (polylines and bands) are never thinner than
    // the scaled one-pixel line.
    for (svg, least) in [(&small, 1.0), (&large, 2.0)] {
        let w = svg_numbers_of(svg, "stroke-width", true);
        assert!(!w.is_empty() && w[0] >= least - 0.005, "{w:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `summary.json` describes every scene pictured in its folder: a second
/// scene is added, a repeated one replaced, one whose pictures are gone
/// dropped; a file that is not a summary stops the run before any work.
#[test]
fn atlas_summary_merges_per_scene() {
    let dir = std::env::temp_dir().join(format!("detach-atlas-merge-{}", std::process::id()));
    let out = dir.to_str().unwrap();
    let run = |scene: &str, eps: &str| {
        let o = detach(&[
            "atlas", "--out", out, "--scene", scene, "--eps", eps, "--format", "svg",
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    };
    let listed = || -> Vec<(String, f64)> {
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap())
                .unwrap();
        v["scenes"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| {
                (
                    s["scene"].as_str().unwrap().to_string(),
                    s["eps"].as_f64().unwrap(),
                )
            })
            .collect()
    };
    let e = |s: &str, eps: f64| (s.to_string(), eps);
    run("smooth-disc", "0.1");
    run("viscous-disc", "0.1");
    assert_eq!(listed(), [e("smooth-disc", 0.1), e("viscous-disc", 0.1)]);
    run("smooth-disc", "0.05");
    assert_eq!(listed(), [e("smooth-disc", 0.05), e("viscous-disc", 0.1)]);
    std::fs::remove_file(dir.join("viscous-disc.svg")).unwrap();
    run("smooth-disc", "0.1");
    assert_eq!(listed(), [e("smooth-disc", 0.1)]);
    std::fs::write(dir.join("summary.json"), "not json").unwrap();
    let o = detach(&["atlas", "--out", out, "--scene", "ice-disc", "--eps", "0.1"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("is not a summary"));
    assert!(
        !dir.join("ice-disc.svg").exists(),
        "no work before the check"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// The table's box columns carry the JSON's names: `outer boxes` is
/// `boxes.outer` (it was headed `not out`).
#[test]
fn pave_table_names_its_box_counts_as_the_json_does() {
    let args = ["pave", "--scene", "viscous-disc", "--eps", "0.05"];
    let table = String::from_utf8(detach(&args).stdout).unwrap();
    let head = table.lines().nth(1).unwrap();
    assert!(
        head.contains("inner boxes") && head.contains("outer boxes"),
        "{head}"
    );
    let v = json(&[&args[..], &["--json"]].concat());
    let row: Vec<&str> = table.lines().nth(2).unwrap().split_whitespace().collect();
    let b = &v["regions"][0]["boxes"];
    let n = row.len();
    assert_eq!(row[n - 3], b["inner"].to_string());
    assert_eq!(row[n - 2], b["outer"].to_string());
    assert_eq!(row[n - 1], b["undecided"].to_string());
}

/// The library alone (`default-features = false`) depends on none of the
/// command line's crates, nor on `nalgebra` (tests only), by `cargo tree`.
#[test]
fn the_library_alone_builds_without_the_command_line_crates() {
    let tree = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO"))
            .args(["tree", "--offline", "-p", "detach", "-e", "normal"])
            .args(["--prefix", "none", "--format", "{p}"])
            .args(args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .expect("cargo tree runs");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8(out.stdout).unwrap();
        let names: Vec<String> = text
            .lines()
            .filter_map(|l| l.split_whitespace().next().map(String::from))
            .collect();
        names
    };
    let cli = ["clap", "indicatif", "sha2"];
    let full = tree(&[]);
    for c in cli {
        assert!(
            full.iter().any(|n| n == c),
            "{c} missing from the default build"
        );
    }
    let lib = tree(&["--no-default-features"]);
    for c in cli.iter().chain(&["nalgebra"]) {
        assert!(!lib.iter().any(|n| n == c), "{c} in the library's tree");
    }
    assert!(lib.iter().any(|n| n == "inari"), "{lib:?}");
}
