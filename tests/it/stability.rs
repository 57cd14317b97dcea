//! `detach stability`: files, one row per case × method, and what the stress
//! cases must show at a coarse resolution.

use std::path::Path;
use std::process::Command;

fn detach() -> Command {
    Command::new(env!("CARGO_BIN_EXE_detach"))
}

fn run(out: &Path) -> serde_json::Value {
    let o = detach()
        .args(["stability", "--eps", "0.015625", "--out"])
        .arg(out)
        .output()
        .expect("runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let table = String::from_utf8_lossy(&o.stdout);
    assert!(
        table.contains("pinch k=6") && table.contains("slices"),
        "{table}"
    );
    let text = std::fs::read_to_string(out.join("stability.json")).expect("json written");
    serde_json::from_str(&text).expect("valid json")
}

#[test]
fn stability_writes_maps_table_and_shows_where_methods_fail() {
    let dir = std::env::temp_dir().join(format!("detach-stability-{}", std::process::id()));
    let doc = run(&dir);
    for scene in ["viscous-disc", "smooth-disc", "ice-disc"] {
        for ext in ["svg", "png"] {
            let f = dir.join(format!("stability-{scene}.{ext}"));
            let len = std::fs::metadata(&f).map(|m| m.len()).unwrap_or(0);
            assert!(len > 1000, "{} missing or empty", f.display());
        }
    }
    assert_eq!(doc["version"], 1);
    assert_eq!(doc["parameters"]["eps"], 0.015625);
    let cases = doc["cases"].as_array().expect("cases");
    let runs = doc["runs"].as_array().expect("runs");
    let methods = ["natural", "centred", "contract", "slices"];
    assert_eq!(cases.len(), 10);
    assert_eq!(runs.len(), cases.len() * methods.len());
    for c in cases {
        for m in methods {
            let n = runs
                .iter()
                .filter(|r| r["case"] == c["case"] && r["method"] == m)
                .count();
            assert_eq!(n, 1, "{} × {m}", c["case"]);
        }
    }
    assert_eq!(doc["maps"].as_array().map(Vec::len), Some(12));
    let row = |case: &str, m: &str| {
        runs.iter()
            .find(|r| r["case"] == case && r["method"] == m)
            .unwrap_or_else(|| panic!("{case} × {m}"))
    };
    let f = |r: &serde_json::Value, k: &str| r[k].as_f64().expect(k);
    for m in methods {
        // At sin θ = 0 every method reports undefined leaves, and the
        // feature check says every leaf touching θ = 0 is undefined.
        let s = row("sin0", m);
        assert!(f(s, "undefined_area") > 0.0, "{m}: no undefined leaf");
        // (undecided is rounded up, the undefined sum to nearest)
        assert!(f(s, "undecided_area") >= f(s, "undefined_area") * (1.0 - 1e-12));
        assert_eq!(s["feature_decided"], true, "{m} at sin θ = 0");
        // The pinch: the neck thins as κ → κ₀, so at a fixed resolution no
        // method closes the undecided area, and none does better at k = 6
        // than at k = 2.
        for k in [2, 4, 6] {
            let r = row(&format!("pinch k={k}"), m);
            assert!(f(r, "undecided_area") > 0.0, "{m}, k = {k}");
        }
        let (u2, u6) = (
            f(row("pinch k=2", m), "undecided_area"),
            f(row("pinch k=6", m), "undecided_area"),
        );
        assert!(u6 >= u2, "{m}: pinch k=6 undecided {u6} < k=2 {u2}");
        assert_eq!(row("pinch k=6", m)["feature_decided"], false, "{m}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn stability_rejects_bad_eps_with_exit_2() {
    for eps in ["0", "-1", "2", "nan"] {
        let o = detach()
            .args(["stability", "--eps", eps, "--out"])
            .arg(std::env::temp_dir().join("detach-stability-bad"))
            .output()
            .expect("runs");
        assert_eq!(o.status.code(), Some(2), "--eps {eps}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(err.trim().lines().count(), 1, "{err}");
    }
}

#[test]
fn heat_grid_is_pale_only_where_every_leaf_is_decided() {
    use detach::figures::stability::heat_grid;
    use detach::figures::Class;
    use detach::pave::{run_method, Method, PaveOptions};
    use detach::scene::{Scene, SceneId, Variant};
    let scene = Scene::default_of(SceneId::SmoothDisc);
    let opts = PaveOptions {
        eps: 1.0 / 64.0,
        max_boxes: 100_000,
    };
    let (_, p) = run_method(
        &scene,
        Variant::Derived,
        &scene.domain(),
        None,
        Method::Natural,
        opts,
    )
    .expect("paves");
    let g = heat_grid(&p, 37, 23);
    let cell_area =
        |c: &detach::pave::PhaseBox| (c.theta[1] - c.theta[0]) * (c.theta_dot[1] - c.theta_dot[0]);
    let mut undecided = 0.0;
    let mut undefined = 0.0;
    for l in &p.leaves {
        let class = Class::of_leaf(l);
        if class.is_cell() {
            continue;
        }
        let a = cell_area(&l.bx);
        if class == Class::Undefined {
            undefined += a;
        } else {
            undecided += a;
        }
        // Every grid cell this leaf's interior meets is marked.
        let mid = (
            0.5 * (l.bx.theta[0] + l.bx.theta[1]),
            0.5 * (l.bx.theta_dot[0] + l.bx.theta_dot[1]),
        );
        let col = (0..g.cols).find(|&c| {
            let b = g.cell(c, 0);
            b.theta[0] <= mid.0 && mid.0 <= b.theta[1]
        });
        let row = (0..g.rows).find(|&r| {
            let b = g.cell(0, r);
            b.theta_dot[0] <= mid.1 && mid.1 <= b.theta_dot[1]
        });
        let (col, row) = (col.expect("column"), row.expect("row"));
        assert!(g.touched[row * g.cols + col], "leaf {:?} not shown", l.bx);
    }
    assert!(undefined > 0.0 && undecided > 0.0);
    // The shares add up to the leaves' areas.
    let (mut su, mut sd) = (0.0, 0.0);
    for row in 0..g.rows {
        for col in 0..g.cols {
            let a = cell_area(&g.cell(col, row));
            su += g.undecided[row * g.cols + col] * a;
            sd += g.undefined[row * g.cols + col] * a;
        }
    }
    assert!(
        (su - undecided).abs() <= 1e-9 * (1.0 + undecided),
        "{su} vs {undecided}"
    );
    assert!(
        (sd - undefined).abs() <= 1e-9 * (1.0 + undefined),
        "{sd} vs {undefined}"
    );
}

/// The stress cases as data: ten cases; each pinch case's parameters put
/// κ = g A²/(a p²) (α = 1, p_φ = p_ψ = p) just above κ₀ = √3/9, at relative
/// distance 10⁻ᵏ, checked in 200-bit arithmetic from the decimal text (rug,
/// independent of the f64 arithmetic that placed them).
#[test]
fn stress_cases_place_the_pinch_above_kappa0() {
    use detach::pave::stability::{stress_cases, Feature};
    use rug::Float;
    let cases = stress_cases().unwrap();
    assert_eq!(cases.len(), 10);
    let prec = 200;
    let kappa0 = Float::with_val(prec, 3).sqrt() / 9u32;
    for k in [2i32, 4, 6] {
        let c = cases
            .iter()
            .find(|c| c.key == format!("pinch k={k}"))
            .expect("a pinch case");
        assert_eq!(c.feature, Feature::Neck);
        let get = |n: &str| {
            let t = &c.params.iter().find(|(m, _)| m == n).expect(n).1;
            Float::with_val(prec, Float::parse(t).unwrap())
        };
        assert_eq!(get("p_phi"), get("p_psi"));
        let kappa = get("g") * get("A").square() / (get("a") * get("p_phi").square());
        let rel = (kappa / &kappa0 - 1u32) * Float::with_val(prec, Float::u_pow_u(10, k as u32));
        assert!((rel.to_f64() - 1.0).abs() < 1e-6, "k = {k}: {rel}");
    }
}

/// Every method on the singular-line case and the maps, through the library
/// at a coarse resolution: at sin θ = 0 every method leaves undefined
/// leaves and the feature (every leaf touching θ = 0 undefined, every other
/// decided) holds; each map's Ω column is its run's own undecided area.
#[test]
fn stress_runs_score_the_singular_line_and_maps_agree() {
    use detach::pave::stability::{method_maps, run_stress_cases, stress_cases};
    use detach::pave::PaveOptions;
    let opts = PaveOptions {
        eps: 1.0 / 16.0,
        max_boxes: 100_000,
    };
    let cases = stress_cases().unwrap();
    let rows = run_stress_cases(&cases[..1], opts).unwrap();
    assert_eq!(rows.len(), 4);
    for r in &rows {
        assert_eq!((r.case.as_str(), r.region), ("sin0", "omega"));
        assert!(r.undefined_area > 0.0 && r.feature_decided, "{r:?}");
    }
    let maps = method_maps(opts).unwrap();
    assert_eq!(maps.len(), 3);
    for m in &maps {
        assert_eq!(m.runs.len(), 4);
        for ((run, _), u) in m.runs.iter().zip(&m.undecided) {
            assert_eq!(run.undecided_area, u[0], "{}", m.id.name());
        }
    }
}
