//! Certified trajectories of the shipped scenes against an independent
//! reference: `tests/data/motion-reference.json`, written by
//! `tests/data/motion_reference.py` (mpmath's Taylor integrator at 50
//! digits, checked there against a second method), and the CLI's `flow`.

use crate::common::{assert_bad_input, json};
use detach::motion::{flow, FlowRequest, Stop, Until};
use detach::scene::{Scene, Variant};
use rug::ops::Pow;
use rug::Rational;
use serde_json::Value;

fn reference() -> Value {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/motion-reference.json"
    );
    let text = std::fs::read_to_string(path).expect("tests/data/motion-reference.json");
    serde_json::from_str(&text).expect("the reference is JSON")
}

fn params(case: &Value) -> Vec<(String, String)> {
    case["params"]
        .as_object()
        .map(|m| {
            m.iter()
                .map(|(k, v)| (k.clone(), v.as_str().unwrap().to_string()))
                .collect()
        })
        .unwrap_or_default()
}

/// `x` contains the decimal text `r` exactly (compared as rationals).
fn contains_text(x: inari::Interval, r: &str) -> bool {
    let (mant, exp) = r.split_once(['e', 'E']).unwrap_or((r, "0"));
    let neg = mant.starts_with('-');
    let mant = mant.trim_start_matches(['-', '+']);
    let (int, frac) = mant.split_once('.').unwrap_or((mant, ""));
    let digits: rug::Integer = format!("{int}{frac}").parse().unwrap();
    let e: i32 = exp.parse::<i32>().unwrap() - frac.len() as i32;
    let ten = rug::Integer::from(10);
    let mut q = Rational::from(digits);
    if e >= 0 {
        q *= Rational::from(ten.pow(e as u32));
    } else {
        q /= Rational::from(ten.pow((-e) as u32));
    }
    if neg {
        q = -q;
    }
    Rational::from_f64(x.inf()).unwrap() <= q && q <= Rational::from_f64(x.sup()).unwrap()
}

#[test]
fn tubes_of_the_shipped_scenes_contain_the_reference_trajectories() {
    let data = reference();
    let cases = data["trajectories"].as_array().expect("trajectories");
    assert!(cases.len() >= 8, "every scene, two starts each");
    for case in cases {
        let name = case["scene"].as_str().unwrap();
        let (scene, _) = Scene::by_name(name, &params(case)).unwrap();
        let file = scene.reading(Variant::Derived);
        for p in case["points"].as_array().unwrap() {
            let t = p["t"].as_str().unwrap();
            let mut request = FlowRequest::parse(
                case["theta0"].as_str().unwrap(),
                case["theta_dot0"].as_str().unwrap(),
                t,
            )
            .unwrap();
            request.until = vec![];
            let tube = flow(file, &request).unwrap();
            assert_eq!(
                tube.stop,
                Stop::End,
                "{name} {case} to {t}: {:?}",
                tube.stop
            );
            for (i, key) in ["theta", "theta_dot"].iter().enumerate() {
                let r = p[key].as_str().unwrap();
                assert!(
                    contains_text(tube.end[i], r),
                    "{name} from {} to t = {t}: {key} {:?} ∌ {r}",
                    case["theta0"],
                    tube.end[i]
                );
                // A point start loses a few digits over 2 s (measured ≤ 2e-11,
                // docs/motion.md); steps sized by the midpoint's coefficients
                // alone, the remainder over the a-priori box unchecked, gave
                // 1.8e-9 on the rod.
                let w = tube.end[i].wid();
                assert!(w < 1e-10, "{name} to {t}: {key} width {w:e}");
            }
        }
    }
}

#[test]
fn events_of_the_shipped_scenes_contain_the_reference_crossings() {
    let data = reference();
    let events = data["events"].as_array().expect("events");
    assert!(!events.is_empty());
    for case in events {
        let name = case["scene"].as_str().unwrap();
        let (scene, _) = Scene::by_name(name, &params(case)).unwrap();
        let file = scene.reading(Variant::Derived);
        let mut request = FlowRequest::parse(
            case["theta0"].as_str().unwrap(),
            case["theta_dot0"].as_str().unwrap(),
            "3",
        )
        .unwrap();
        let (until, kind) = match case["function"].as_str().unwrap() {
            "omega" => (Until::Omega, "U=0"),
            _ => (Until::Omega0, "N=0"),
        };
        request.until = vec![until];
        let tube = flow(file, &request).unwrap();
        assert_eq!(tube.stop, Stop::Event, "{name}: {:?}", tube.stop);
        let e = &tube.events[0];
        assert_eq!(e.kind, kind);
        assert!(
            contains_text(e.time, case["time"].as_str().unwrap()),
            "{name}: {:?} vs {}",
            e.time,
            case["time"]
        );
        assert!(contains_text(e.theta, case["theta"].as_str().unwrap()));
        assert!(contains_text(
            e.theta_dot,
            case["theta_dot"].as_str().unwrap()
        ));
        assert!(
            e.time.wid() < 1e-11,
            "{name}: event width {:e}",
            e.time.wid()
        );
    }
}

#[test]
fn the_frictionless_rod_keeps_its_energy() {
    // μ = 0: E = (1/3 + cos²θ)θ̇²/2 + g sin θ (m = l = 1) is conserved; the
    // scene file has no energy, so E is written here from the mechanics.
    let (scene, _) = Scene::by_name("painleve-rod", &[("mu".into(), "0".into())]).unwrap();
    let file = scene.reading(Variant::Derived);
    let mut request = FlowRequest::parse("1.3", "1.3", "1").unwrap();
    request.until = vec![];
    let tube = flow(file, &request).unwrap();
    let g = detach::number::param::enclose_decimal("g", "9.81").unwrap();
    let energy = |th: inari::Interval, w: inari::Interval| {
        let third = inari::Interval::try_from((1.0, 1.0)).unwrap()
            / inari::Interval::try_from((3.0, 3.0)).unwrap();
        (third + th.cos().sqr()) * w.sqr() / inari::Interval::try_from((2.0, 2.0)).unwrap()
            + g * th.sin()
    };
    let e0 = energy(tube.start[0], tube.start[1]);
    for s in tube.steps() {
        let e = energy(s.end[0], s.end[1]);
        assert!(
            !e.disjoint(e0),
            "energy {e:?} at t = {} leaves {e0:?}",
            s.t0
        );
        assert!(e.wid() < 1e-9, "energy width {:e}", e.wid());
    }
    // A mutant: the rod at μ = 0.1 does not conserve it (friction works).
    let (scene, _) = Scene::by_name("painleve-rod", &[("mu".into(), "0.1".into())]).unwrap();
    let tube = flow(scene.reading(Variant::Derived), &request).unwrap();
    assert!(energy(tube.end[0], tube.end[1]).disjoint(e0));
}

#[test]
fn flow_prints_events_and_the_end_as_json() {
    let v = json(&[
        "flow",
        "--scene",
        "viscous-disc",
        "--from",
        "-1.5,1",
        "--t",
        "1",
        "--until",
        "none",
        "--json",
    ]);
    assert_eq!(v["stop"], "end time reached");
    assert_eq!(v["end"]["time"], "1");
    assert!(v["steps"].as_u64().unwrap() > 0);
    let lo: f64 = v["end"]["theta"][0].as_str().unwrap().parse().unwrap();
    let hi: f64 = v["end"]["theta"][1].as_str().unwrap().parse().unwrap();
    assert!(lo <= hi && hi - lo < 1e-10);
}

#[test]
fn flow_refuses_bad_input() {
    assert_bad_input(&["flow", "--scene", "painleve-rod", "--t", "1"], "--from");
    assert_bad_input(
        &["flow", "--scene", "painleve-rod", "--from", "1", "--t", "1"],
        "THETA,THETA_DOT",
    );
    assert_bad_input(
        &[
            "flow",
            "--scene",
            "painleve-rod",
            "--from",
            "1,0",
            "--t",
            "-1",
        ],
        "end time",
    );
    assert_bad_input(
        &[
            "flow",
            "--scene",
            "painleve-rod",
            "--from",
            "1,0",
            "--t",
            "1",
            "--until",
            "x",
        ],
        "unknown event",
    );
    assert_bad_input(
        &[
            "flow",
            "--scene",
            "viscous-disc",
            "--from",
            "nan,0",
            "--t",
            "1",
        ],
        "theta",
    );
    assert_bad_input(
        &[
            "reach",
            "--scene",
            "painleve-rod",
            "--t",
            "0.1",
            "--picture",
            "reach.pdf",
        ],
        "--picture must name a .svg or .png file",
    );
}

/// `detach reach` on the rod around the reference event of
/// `motion-reference.json` (mpmath: from (0.3, 4) U = 0 at t = 0.11587…):
/// the leaf holding the start is never "avoids" within 0.3 nor "reaches"
/// within 0.1, and an arrival window holds the reference time.
#[test]
fn reach_leaves_agree_with_the_reference_event() {
    let data = reference();
    let case = &data["events"][0];
    assert_eq!(case["theta0"], "0.3");
    assert_eq!(case["theta_dot0"], "4");
    let time = case["time"].as_str().unwrap();
    let run = |t: &str| {
        json(&[
            "reach",
            "--scene",
            "painleve-rod",
            "--param",
            "mu=0.5",
            "--theta",
            "0.25:0.35",
            "--theta-dot",
            "3.9:4.1",
            "--t",
            t,
            "--until",
            "U=0",
            "--eps",
            "0.0625",
            "--json",
        ])
    };
    let holds = |leaf: &Value| {
        let end = |k: &str, i: usize| leaf[k][i].as_str().unwrap().parse::<f64>().unwrap();
        end("theta", 0) <= 0.3
            && 0.3 <= end("theta", 1)
            && end("theta_dot", 0) <= 4.0
            && 4.0 <= end("theta_dot", 1)
    };
    let late = run("0.3");
    assert_eq!(late["complete"], true);
    let mut seen = 0;
    for leaf in late["leaves"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|l| holds(l))
    {
        seen += 1;
        assert_ne!(leaf["fate"], "avoids", "{leaf}");
        if leaf["fate"] == "reaches" {
            let w = leaf["time"].as_array().unwrap();
            let lo = w[0].as_str().unwrap();
            let hi = w[1].as_str().unwrap();
            let window =
                inari::Interval::try_from((lo.parse::<f64>().unwrap(), hi.parse::<f64>().unwrap()))
                    .unwrap();
            assert!(contains_text(window, time), "{window:?} ∌ {time}");
        }
    }
    assert!(seen >= 1);
    let area = |doc: &Value, k: &str| doc["area"][k].as_str().unwrap().parse::<f64>().unwrap();
    assert!(area(&late, "inner") > 0.01 && area(&late, "outer") <= 0.02 + 1e-12);
    let early = run("0.1");
    for leaf in early["leaves"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|l| holds(l))
    {
        assert_ne!(leaf["fate"], "reaches", "{leaf}");
    }
    for (args, message) in [
        (vec!["--t", "0.3", "--eps", "2"], "--eps"),
        (vec!["--t", "0.3", "--until", "none"], "no target"),
        (vec!["--t", "-1"], "--t"),
        (vec!["--t", "0.3", "--max-boxes", "0"], "--max-boxes"),
        (vec!["--t", "0.3", "--theta", "1"], "LO:HI"),
    ] {
        let mut all = vec!["reach", "--scene", "painleve-rod"];
        all.extend(args);
        assert_bad_input(&all, message);
    }
}

/// `detach-check`'s verdict on a proof, first word only.
fn verdict(proof: &Value) -> String {
    let text = serde_json::to_string(proof).unwrap();
    match detach::check::check_str(&text) {
        Ok(r) => format!("{:?}", r.verdict),
        Err(e) => format!("UNREADABLE {e}"),
    }
}

/// `[lo, hi]` decimal text as an exact-enough interval (outward).
fn claimed(v: &Value) -> inari::Interval {
    let end = |i: usize| v[i].as_str().unwrap().parse::<f64>().unwrap();
    inari::Interval::try_from((end(0).next_down(), end(1).next_up())).unwrap()
}

#[test]
fn trajectory_proofs_check_hold_the_reference_and_fail_off_it() {
    // The reference is mpmath's (tests/data/motion_reference.py), not the
    // prover: each proof detach writes is VALID for detach-check, its
    // claimed box or window holds the reference, and the same proof with
    // the claim moved just off the reference is INVALID.
    let data = reference();
    for case in data["trajectories"].as_array().unwrap() {
        let name = case["scene"].as_str().unwrap();
        let owned = params(case);
        let pairs: Vec<(&str, &str)> = owned
            .iter()
            .map(|(k, v)| (k.as_str(), v.as_str()))
            .collect();
        let problem = detach::api::Problem::load(name, &pairs).unwrap();
        let p = &case["points"].as_array().unwrap()[0];
        let t = p["t"].as_str().unwrap();
        let mut request = FlowRequest::parse(
            case["theta0"].as_str().unwrap(),
            case["theta_dot0"].as_str().unwrap(),
            t,
        )
        .unwrap();
        request.until = vec![];
        let (_, proof) = problem.flow_with_proof(&request, t).unwrap();
        assert_eq!(verdict(&proof), "Valid", "{name} to {t}");
        let end = &proof["statement"]["end"];
        let r = p["theta"].as_str().unwrap();
        let box_t = claimed(&end["t"]);
        assert!(contains_text(box_t, r), "{name}: {box_t:?} ∌ {r}");
        assert!(
            box_t.wid() < 1e-9,
            "{name}: claimed width {:e}",
            box_t.wid()
        );
        let mut moved = proof.clone();
        let above = r.parse::<f64>().unwrap() + 1e-9;
        moved["statement"]["end"]["t"] =
            serde_json::json!([format!("{above:e}"), format!("{:e}", above + 1e-9)]);
        assert!(
            verdict(&moved).starts_with("Invalid"),
            "{name}: {}",
            verdict(&moved)
        );
    }
    for case in data["events"].as_array().unwrap() {
        let name = case["scene"].as_str().unwrap();
        let owned = params(case);
        let pairs: Vec<(&str, &str)> = owned
            .iter()
            .map(|(k, v)| (k.as_str(), v.as_str()))
            .collect();
        let problem = detach::api::Problem::load(name, &pairs).unwrap();
        let mut request = FlowRequest::parse(
            case["theta0"].as_str().unwrap(),
            case["theta_dot0"].as_str().unwrap(),
            "3",
        )
        .unwrap();
        request.until = vec![match case["function"].as_str().unwrap() {
            "omega" => Until::Omega,
            _ => Until::Omega0,
        }];
        let (_, proof) = problem.flow_with_proof(&request, "3").unwrap();
        assert_eq!(verdict(&proof), "Valid", "{name} event");
        let time = claimed(&proof["statement"]["event"]["time"]);
        let r = case["time"].as_str().unwrap();
        assert!(contains_text(time, r), "{name}: {time:?} ∌ {r}");
        let mut moved = proof.clone();
        let later = r.parse::<f64>().unwrap() + 1e-9;
        moved["statement"]["event"]["time"] =
            serde_json::json!([format!("{later:e}"), format!("{:e}", later + 1e-9)]);
        assert!(
            verdict(&moved).starts_with("Invalid"),
            "{name}: {}",
            verdict(&moved)
        );
    }
}

/// `detach reach --proof` around the reference event of
/// `tests/data/motion-reference.json`: the file checks VALID on its own,
/// claims no more than the run proved, and a claim changed against the
/// evidence — more reaching area, or a T before the reference event at
/// τ ≈ 0.2071 — is INVALID.
#[test]
fn reach_proofs_check_and_fail_when_mutated() {
    let dir = std::env::temp_dir().join(format!("detach-reach-proof-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("reach.json");
    let args = [
        "reach",
        "--scene",
        "painleve-rod",
        "--param",
        "mu=0.5",
        "--theta",
        "0.25:0.35",
        "--theta-dot",
        "3.9:4.1",
        "--t",
        "0.3",
        "--until",
        "U=0",
        "--eps",
        "0.0625",
        "--json",
        "--proof",
        path.to_str().unwrap(),
    ];
    let run = json(&args);
    let bytes = std::fs::read(&path).unwrap();
    let verdict = |b: &[u8]| detach::check::check_bytes(b).unwrap().verdict;
    assert_eq!(verdict(&bytes), detach::check::Verdict::Valid);
    let proof: Value = serde_json::from_slice(&bytes).unwrap();
    let num = |v: &Value| v.as_str().unwrap().parse::<f64>().unwrap();
    let (inner, outer) = (
        num(&proof["statement"]["area"]["inner"]),
        num(&proof["statement"]["area"]["outer"]),
    );
    // Both are bounds of exact sums over the same or fewer leaves, each
    // rounded in its own order: they may differ in the last digits.
    let (run_inner, run_outer) = (num(&run["area"]["inner"]), num(&run["area"]["outer"]));
    assert!(
        inner > 0.0 && inner <= run_inner * (1.0 + 1e-12),
        "{inner} vs {run_inner}"
    );
    assert!(
        outer >= run_outer * (1.0 - 1e-12) && outer <= 0.02 + 1e-12,
        "{outer} vs {run_outer}"
    );
    let mutated = |f: &dyn Fn(&mut Value)| {
        let mut p = proof.clone();
        f(&mut p);
        verdict(&serde_json::to_vec(&p).unwrap())
    };
    let more = format!("{:e}", 1.5 * inner);
    assert!(matches!(
        mutated(&|p| p["statement"]["area"]["inner"] = Value::from(more.as_str())),
        detach::check::Verdict::Invalid(_)
    ));
    assert!(matches!(
        mutated(&|p| p["statement"]["time"] = Value::from("0.1")),
        detach::check::Verdict::Invalid(_)
    ));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn arrivals_at_the_rods_singular_line_hold_the_reference_and_their_proofs_check() {
    // Reference: tests/data/arrival_reference.py (Runge–Kutta in the
    // desingularised time, 30 digits, extrapolated; not detach's code). At
    // μ = 1.5 each start runs into the stable node on V = 0 in finite time.
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/arrival-reference.json"
    );
    let data: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let owned = params(&data);
    let pairs: Vec<(&str, &str)> = owned
        .iter()
        .map(|(k, v)| (k.as_str(), v.as_str()))
        .collect();
    let problem = detach::api::Problem::load("painleve-rod", &pairs).unwrap();
    for case in data["arrivals"].as_array().unwrap() {
        let from = [
            case["theta0"].as_str().unwrap(),
            case["theta_dot0"].as_str().unwrap(),
        ];
        let mut request = FlowRequest::parse(from[0], from[1], "1").unwrap();
        request.until = vec![Until::Singular];
        let (tube, proof) = problem.flow_with_proof(&request, "1").unwrap();
        assert!(
            matches!(tube.stop, Stop::Arrival),
            "{from:?}: {:?}",
            tube.stop
        );
        let e = &tube.events[0];
        let r = case["time"].as_str().unwrap();
        assert!(contains_text(e.time, r), "{from:?}: {:?} ∌ {r}", e.time);
        assert!(e.time.wid() < 1e-10, "{from:?}: width {:e}", e.time.wid());
        assert!(contains_text(e.theta, case["theta"].as_str().unwrap()));
        assert!(contains_text(
            e.theta_dot,
            case["theta_dot"].as_str().unwrap()
        ));
        assert!(e.theta_dot.wid() < 1e-5, "{:?}", e.theta_dot);

        assert_eq!(verdict(&proof), "Valid", "{from:?}");
        let time = claimed(&proof["statement"]["arrival"]["time"]);
        assert!(contains_text(time, r), "{from:?}: {time:?} ∌ {r}");
        // Mutants: a window after the reference time, a band that misses
        // the node's θ̇ (its faces no longer bracket θ̈'s sign change), a
        // bracket with V of one sign across it.
        let later = r.parse::<f64>().unwrap() + 1e-9;
        let mut moved = proof.clone();
        moved["statement"]["arrival"]["time"] =
            serde_json::json!([format!("{later:e}"), format!("{:e}", later + 1e-9)]);
        let hex = |x: f64| Value::String(detach::certificate::numbers::hex(x));
        let band = &proof["evidence"]["arrival"]["band"];
        let node: f64 = case["theta_dot"].as_str().unwrap().parse().unwrap();
        let mut narrow = proof.clone();
        narrow["evidence"]["arrival"]["band"][0] = hex(node + 1e-9);
        let mut short = proof.clone();
        short["evidence"]["arrival"]["root"][1] = proof["evidence"]["arrival"]["root"][0].clone();
        short["evidence"]["arrival"]["root"][0] = hex(0.8);
        for (what, p) in [("window", moved), ("band", narrow), ("bracket", short)] {
            assert!(
                verdict(&p).starts_with("Invalid"),
                "{what}: {} ({band})",
                verdict(&p)
            );
        }
    }
}
