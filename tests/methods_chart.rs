//! `detach methods`: runs every method listed in `Method::ALL`, writes the
//! table, JSON and chart, and reads the peers' file when there is one.

use detach::pave::{pave_scene, run_method, Method, PaveOptions};
use detach::scene::{Scene, SceneId, Variant};
use std::process::Command;

fn detach() -> Command {
    Command::new(env!("CARGO_BIN_EXE_detach"))
}

#[test]
fn every_method_name_round_trips_and_natural_is_the_baseline() {
    for m in Method::ALL {
        assert_eq!(m.name().parse::<Method>().unwrap(), m);
    }
    assert!("nope".parse::<Method>().is_err());
    let s = Scene::default_of(SceneId::SmoothDisc);
    let opts = PaveOptions {
        eps: 1.0 / 64.0,
        max_boxes: 100_000,
    };
    let (_, a) = run_method(
        &s,
        Variant::Derived,
        &s.domain(),
        None,
        Method::Natural,
        opts,
    )
    .unwrap();
    let b = pave_scene(&s, Variant::Derived, opts, |_, _, _| {}).unwrap();
    assert_eq!(a.leaves, b.leaves);
}

#[test]
fn methods_writes_table_json_and_chart_with_peers() {
    let dir = std::env::temp_dir().join(format!("detach-methods-{}", std::process::id()));
    let peers = dir.join("peers.json");
    std::fs::create_dir_all(&dir).unwrap();
    // A tiny peer file: one curve per problem.
    std::fs::write(
        &peers,
        r#"{"peer":"codac","version":"test","runs":[
            {"problem":"omega_2_8","method":"sep","time_s":10.0,"undecided_area":5.0,"boxes":100},
            {"problem":"omega_2_8","method":"sep","time_s":100.0,"undecided_area":0.01,"boxes":1000000},
            {"problem":"omega0_1_11","method":"sep","time_s":1.0,"undecided_area":9.0}]}"#,
    )
    .unwrap();
    let out = detach()
        .args([
            "methods",
            "--eps",
            "0.00390625",
            "--eps",
            "0.0009765625",
            "--out",
        ])
        .arg(&dir)
        .arg("--peers")
        .arg(&peers)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let table = String::from_utf8(out.stdout).unwrap();
    for m in Method::ALL {
        assert!(table.contains(m.name()), "{table}");
    }
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("methods.json")).unwrap()).unwrap();
    let runs = json["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 2 * 2 * Method::ALL.len());
    for r in runs {
        let u = r["undecided_area"].as_f64().unwrap();
        assert!(u > 0.0 && u < 2.0 * std::f64::consts::PI * 20.0);
        assert!(r["leaves"].as_u64().unwrap() > 0);
    }
    // Finer ε, smaller undecided area.
    assert!(runs[1]["undecided_area"].as_f64() < runs[0]["undecided_area"].as_f64());
    // The peer curve spans the detach points of Ω (2.8): a ratio is reported.
    assert!(!json["ratios"].as_array().unwrap().is_empty());
    // Whole-process times are recorded beside the paving call's.
    for r in runs {
        let p = r["process_s"].as_f64().unwrap();
        assert!(p.is_finite() && p > 0.0);
    }
    // Undecided area at equal leaf count: the peer's by log–log
    // interpolation between (100 boxes, 5.0) and (10⁶ boxes, 0.01), in
    // closed form here.
    let eq = json["equal_leaf_count"].as_array().unwrap();
    assert!(!eq.is_empty());
    for e in eq {
        assert_eq!(e["problem"], "omega_2_8");
        let n = e["leaves"].as_f64().unwrap();
        let s = (n.ln() - 100f64.ln()) / (1e6f64.ln() - 100f64.ln());
        let want = (5f64.ln() + s * (0.01f64.ln() - 5f64.ln())).exp();
        let got = e["peer_undecided_area"].as_f64().unwrap();
        assert!((got - want).abs() <= 1e-9 * want, "{got} vs {want}");
    }
    for f in ["methods.svg", "methods.png"] {
        assert!(std::fs::metadata(dir.join(f)).unwrap().len() > 1000, "{f}");
    }
    let svg = std::fs::read_to_string(dir.join("methods.svg")).unwrap();
    assert!(svg.contains("codac sep") && svg.contains("detach natural"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_input_exits_2() {
    for args in [
        vec!["methods", "--eps", "0"],
        vec!["methods", "--method", "nope"],
        vec!["methods", "--repeat", "0"],
    ] {
        let out = detach().args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
    }
}
