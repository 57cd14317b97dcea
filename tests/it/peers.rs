//! The peer comparison of `cargo bench --bench peers`: log–log matching of
//! speed–accuracy curves, checked against closed forms; and the method
//! names it takes.

#[path = "../../benches/peers/compare.rs"]
mod compare;

use compare::{cost_exponent, peer_curves, speedup, x_at};
use detach::pave::{pave_scene, run_method, Method, PaveOptions};
use detach::scene::{Scene, SceneId, Variant};

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

/// A peer file as `codac_peer.py` writes it: curves grouped by problem
/// and method, runs missing a field skipped.
#[test]
fn peer_curves_group_runs_by_problem_and_method() {
    let doc: serde_json::Value = serde_json::from_str(
        r#"{"peer":"codac","version":"test","runs":[
            {"problem":"omega_2_8","method":"sep","time_s":10.0,"undecided_area":5.0,"boxes":100},
            {"problem":"omega_2_8","method":"sivia","time_s":1.0,"undecided_area":6.0},
            {"problem":"omega_2_8","method":"sep","time_s":100.0,"undecided_area":0.01,"boxes":1000000},
            {"problem":"omega0_1_11","method":"sep","undecided_area":9.0},
            {"problem":"omega0_1_11","method":"sep","time_s":1.0,"undecided_area":9.0}]}"#,
    )
    .unwrap();
    let c = peer_curves(&doc);
    assert_eq!(c.len(), 3);
    assert_eq!(
        (c[0].problem.as_str(), c[0].label.as_str()),
        ("omega_2_8", "codac sep")
    );
    assert_eq!(c[0].time_area, vec![(10.0, 5.0), (100.0, 0.01)]);
    assert_eq!(c[0].area_boxes, vec![(5.0, 100.0), (0.01, 1e6)]);
    assert_eq!(c[1].label, "codac sivia");
    assert_eq!(c[2].time_area, vec![(1.0, 9.0)]);
}

/// Interpolation in log–log space: between (100 boxes, area 5) and
/// (10⁶ boxes, area 0.01) the box count at area u is, in closed form,
/// exp(ln 100 + s·(ln 10⁶ − ln 100)) with s = (ln u − ln 5)/(ln 0.01 − ln 5).
#[test]
fn x_at_interpolates_log_log_and_refuses_outside() {
    let pts = [(1e6, 0.01), (100.0, 5.0)];
    for u in [5.0f64, 1.0, 0.3, 0.01] {
        let s = (u.ln() - 5f64.ln()) / (0.01f64.ln() - 5f64.ln());
        let want = (100f64.ln() + s * (1e6f64.ln() - 100f64.ln())).exp();
        let got = x_at(&pts, u).unwrap();
        assert!((got - want).abs() <= 1e-9 * want, "{u}: {got} vs {want}");
    }
    assert_eq!(x_at(&pts, 6.0), None);
    assert_eq!(x_at(&pts, 0.001), None);
    assert_eq!(x_at(&[(1.0, 1.0)], 1.0), None);
}

/// Two power laws t = c·(1/U)^k: the speed-up is the ratio of the constants
/// at every U, and the fitted exponent is k.
#[test]
fn speedup_and_cost_exponent_on_power_laws() {
    let law = |c: f64, k: f64| -> Vec<(f64, f64)> {
        [0.1, 0.03, 0.01, 0.003, 0.001]
            .iter()
            .map(|&u: &f64| (c * (1.0 / u).powf(k), u))
            .collect()
    };
    let (ours, theirs) = (law(1e-4, 1.0), law(5e-3, 1.5));
    for u in [0.03, 0.01, 0.005, 0.002] {
        let want = 50.0 * (1.0f64 / u).powf(0.5);
        let got = speedup(&ours, &theirs, u).unwrap();
        assert!((got - want).abs() <= 1e-9 * want, "{u}: {got} vs {want}");
    }
    assert!((cost_exponent(&ours, 0.001, 0.1).unwrap() - 1.0).abs() < 1e-12);
    assert!((cost_exponent(&theirs, 0.001, 0.1).unwrap() - 1.5).abs() < 1e-12);
    assert_eq!(cost_exponent(&ours, 0.5, 1.0), None);
}
