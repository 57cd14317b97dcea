//! The paper's scenes are their files: each paper scene's two embedded
//! files (derived and printed readings) agree on parameters, conditions and
//! domain; the conditions accept and refuse as the files' headers state;
//! the functions of (2.12) and (3.3) agree with the files' energy and
//! dynamics; and the new sections' rules.
//!
//! References: the files' headers (parameter signs, 0 ≤ b < a), the energy
//! (2.11) differentiated (dual numbers) for Π̃', the `[dynamics]` θ̈ for
//! (3.3), and the committed proof `proofs/roots-2.12.json` for the text of
//! (2.12).

use crate::common::{assert_bad_input, Rng};
use detach::number::scalar::{Dual, Scalar};
use detach::scene::file::{EMBEDDED, SHIPPED};
use detach::scene::{Angle, FileScene, Scene, SceneId, Variant};
use inari::Interval;
use std::path::Path;

fn scenes_dir() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes")
}

fn file_of(id: SceneId, v: Variant, overrides: &[(&str, &str)]) -> Result<Scene, String> {
    let o: Vec<(String, String)> = overrides
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    Scene::file_of(id, v, &o)
        .map(|s| s.0)
        .map_err(|e| e.to_string())
}

fn file(s: &Scene) -> &FileScene {
    match s {
        Scene::File(f) => f,
        _ => panic!("a scene file"),
    }
}

fn iv(lo: f64, hi: f64) -> Interval {
    Interval::try_from((lo, hi)).unwrap()
}

/// `x` and `y` agree as points: within `1e-12·max(1, |x|, |y|)`.
fn close(x: f64, y: f64) -> bool {
    (x - y).abs() <= 1e-12 * x.abs().max(y.abs()).max(1.0)
}

/// Sample θ in the open domain (0, π) or (−π, π), θ̇ in [−10, 10].
fn samples(id: SceneId, n: usize) -> Vec<(f64, f64)> {
    let mut r = Rng(0x5eed_0000 + id as u64);
    (0..n)
        .map(|_| {
            let t = match id {
                SceneId::ViscousDisc => -3.1 + 6.2 * r.unit(),
                _ => 0.02 + 3.1 * r.unit(),
            };
            (t, -10.0 + 20.0 * r.unit())
        })
        .collect()
}

/// Every file of `scenes/` is embedded with its text; each loads by name;
/// `Scene::by_name` and `--scene` keep their names (the paper's scenes run
/// the built-in models, the file forms come through `Scene::file_of`).
#[test]
fn every_scene_file_is_embedded_and_loads_by_name() {
    let mut on_disk = 0;
    for entry in std::fs::read_dir(scenes_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("toml") {
            continue;
        }
        on_disk += 1;
        let name = path.file_stem().unwrap().to_str().unwrap();
        let (_, text) = EMBEDDED
            .iter()
            .find(|(n, _)| *n == name)
            .unwrap_or_else(|| panic!("{name} is not embedded"));
        assert_eq!(*text, std::fs::read_to_string(&path).unwrap(), "{name}");
        let f = FileScene::shipped(name, &[]).unwrap().unwrap();
        assert_eq!(f.name, name);
    }
    assert_eq!(on_disk, EMBEDDED.len());
    assert!(FileScene::shipped("no-such-scene", &[]).is_none());
    for id in SceneId::ALL {
        assert_eq!(Scene::by_name(id.name(), &[]).unwrap().0.id(), Some(id));
        for v in Variant::ALL {
            let s = file_of(id, v, &[]).unwrap();
            let want = match v {
                Variant::Derived => id.name().to_string(),
                Variant::Printed => format!("{}-printed", id.name()),
            };
            assert_eq!(s.name(), want);
        }
        let printed = format!("{}-printed", id.name());
        assert!(Scene::by_name(&printed, &[]).is_err(), "{printed}");
    }
    for (name, _) in SHIPPED {
        assert!(Scene::by_name(name, &[]).unwrap().0.id().is_none());
    }
}

/// Both readings of each paper scene declare the same parameters (names,
/// defaults, in order) and domain; Ω₀ = Ω exactly for the smooth disc (§2),
/// and an energy exactly for the conservative discs (§2, §3).
#[test]
fn paper_readings_declare_the_same_parameters_and_domain() {
    for id in SceneId::ALL {
        let names = |s: &Scene| {
            file(s)
                .params
                .specs
                .iter()
                .map(|p| (p.name, p.default))
                .collect::<Vec<_>>()
        };
        let d = file_of(id, Variant::Derived, &[]).unwrap();
        let p = file_of(id, Variant::Printed, &[]).unwrap();
        assert_eq!(names(&d), names(&p), "{id}");
        assert_eq!(names(&d).len(), id.params().len(), "{id}");
        let (x, y) = (d.domain(), p.domain());
        assert_eq!((x.theta, x.theta_dot), (y.theta, y.theta_dot), "{id}");
        let probe = Angle::new(1.0_f64);
        for s in [&d, &p] {
            assert_eq!(
                s.omega0_is_omega(Variant::Derived),
                id == SceneId::SmoothDisc,
                "{id}"
            );
            assert_eq!(
                s.energy(&probe, 0.5).is_some(),
                id != SceneId::ViscousDisc,
                "{id}"
            );
        }
    }
}

/// Parameter sets accepted (`true`) and refused: the files' `[conditions]`
/// decide as their headers state (m, a, A, C, g > 0; 0 ≤ b < a; μ ≥ 0; the
/// momenta and c₀ any sign), on enclosures: touching or overlapping
/// enclosures of `b < a` cannot be decided and are refused.
#[test]
fn conditions_accept_and_refuse_as_the_headers_state() {
    type Case = (&'static [(&'static str, &'static str)], bool);
    let viscous: &[Case] = &[
        (&[], true),
        (&[("b", "0")], true),
        (&[("b", "0.999")], true),
        (&[("b", "1")], false),
        (&[("b", "1.5")], false),
        (&[("b", "-0.1")], false),
        (&[("a", "0"), ("b", "0")], false),
        (&[("a", "-1")], false),
        (&[("a", "0.1"), ("b", "0.1000000000000000000001")], false),
        (&[("a", "0.1000000000000000000001"), ("b", "0.1")], false),
        (&[("a", "1e-300"), ("b", "1e-301")], true),
        (&[("m", "0")], false),
        (&[("C", "-0.3")], false),
        (&[("mu", "0")], true),
        (&[("mu", "-0.1")], false),
        (&[("g", "0")], false),
    ];
    let disc: &[Case] = &[
        (&[], true),
        (&[("m", "0")], false),
        (&[("m", "-1")], false),
        (&[("a", "-1")], false),
        (&[("A", "0")], false),
        (&[("C", "0")], false),
        (&[("C", "1e-300")], true),
        (&[("g", "-9.81")], false),
        (&[("p_phi", "-3"), ("p_psi", "0")], true),
    ];
    let mut refused = 0;
    for id in SceneId::ALL {
        let cases = match id {
            SceneId::ViscousDisc => viscous,
            _ => disc,
        };
        for (case, accepted) in cases {
            for v in Variant::ALL {
                let got = file_of(id, v, case);
                assert_eq!(got.is_ok(), *accepted, "{id} {v} {case:?}: {:?}", got.err());
                refused += usize::from(!accepted);
            }
        }
        // c0 is any number for the disc on ice.
        if id == SceneId::IceDisc {
            assert!(file_of(id, Variant::Derived, &[("c0", "-7")]).is_ok());
        }
    }
    assert!(refused >= 30, "{refused}");
    // The messages name the condition, its text and the values read.
    let e = file_of(SceneId::ViscousDisc, Variant::Derived, &[("b", "1")]).unwrap_err();
    for needle in [
        "scenes/viscous-disc.toml",
        "conditions.centre_of_mass_inside_disc",
        "`b < a` does not hold with b = 1, a = 1",
    ] {
        assert!(e.contains(needle), "{needle} not in {e}");
    }
    let e = file_of(
        SceneId::ViscousDisc,
        Variant::Printed,
        &[("a", "0.1"), ("b", "0.1000000000000000000001")],
    )
    .unwrap_err();
    assert!(
        e.contains("cannot be decided") && e.contains("margin"),
        "{e}"
    );
    let e = file_of(SceneId::SmoothDisc, Variant::Derived, &[("A", "0")]).unwrap_err();
    assert!(e.contains("`A > 0` does not hold with A = 0"), "{e}");
}

/// The functions of (2.12) and (3.3) in the disc files against the files'
/// own mechanics: Π̃' (`potential_slope`) is the θ-derivative of the energy
/// at θ̇ = 0 (dual numbers), `eq_2_12` is sin³θ·Π̃', `eq_3_3` is sin³θ·θ̈
/// of `[dynamics]`, at 400 points; (2.12)'s text is the committed proof's.
#[test]
fn functions_agree_with_the_energy_and_dynamics() {
    let proof: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("proofs/roots-2.12.json"),
        )
        .unwrap(),
    )
    .unwrap();
    let stated = proof["statement"]["function"]
        .as_str()
        .unwrap()
        .replace("(t)", "(theta)");
    for id in [SceneId::SmoothDisc, SceneId::IceDisc] {
        let s = file_of(id, Variant::Derived, &[]).unwrap();
        let f = file(&s);
        let slope = f.function("potential_slope").unwrap();
        let eq212 = f.function("eq_2_12").unwrap();
        assert_eq!(eq212.text, stated, "{id}: (2.12) as the proof states it");
        for (t, _) in samples(id, 400) {
            let sin3 = t.sin().powi(3);
            let de = s
                .energy(
                    &Angle::new(Dual::<f64>::variable(t, 0)),
                    Dual::<f64>::int(0),
                )
                .unwrap()
                .grad[0];
            let tol = |x: f64| 1e-9 * (1.0 + x.abs());
            let pi_slope = slope.eval(t);
            let v0 = de;
            if id == SceneId::SmoothDisc {
                // (2.11) at θ̇ = 0 is Π̃ itself.
                assert!(
                    (pi_slope - v0).abs() <= tol(v0),
                    "{id} Π̃' at {t}: {pi_slope} vs {v0}"
                );
            }
            let e212 = eq212.eval(t);
            assert!(
                (e212 - sin3 * pi_slope).abs() <= tol(e212),
                "{id} (2.12) at {t}"
            );
            if id == SceneId::IceDisc {
                let e33 = f.function("eq_3_3").unwrap().eval(t);
                let acc = s.acceleration(Variant::Derived, &Angle::new(t), 0.0);
                assert!((e33 - sin3 * acc).abs() <= tol(e33), "{id} (3.3) at {t}");
            }
        }
    }
}

const BASE: &str = r#"
name = "t"
[domain]
theta = ["0", "1"]
theta_dot = ["-1", "1"]
[parameters]
m = "2"
k = "0.1"
[regions]
omega = "theta_dot^2*m - 1 < 0"
"#;

fn with(extra: &str) -> Result<FileScene, String> {
    FileScene::parse(&format!("{BASE}{extra}"), &[])
}

/// `[conditions]`: each comparison decided on the enclosures, `<=`/`>=`
/// holding at equality of exact values; refusals name the condition.
#[test]
fn conditions_are_decided_on_enclosures() {
    let cond = |c: &str| with(&format!("[conditions]\nc = \"{c}\"\n"));
    for ok in [
        "m > 1",
        "m >= 2",
        "m ≥ 2",
        "m <= 2",
        "2*m < 4.1",
        "0 < k",
        "sqrt(m) > 1.41",
    ] {
        let f = cond(ok).unwrap_or_else(|e| panic!("{ok}: {e}"));
        assert_eq!(f.conditions, [("c".to_string(), ok.to_string())]);
    }
    for (bad, needle) in [
        ("m > 2", "`conditions.c`: `m > 2` does not hold with m = 2"),
        ("m < 2", "does not hold"),
        ("k*10 < 0.9", "does not hold"),
        ("k*10 < 1", "cannot be decided"),
        ("k > 0.1", "cannot be decided with k = 0.1"),
        ("k*10 >= 1", "cannot be decided"),
        ("m", "is not one comparison"),
        ("m = 2", "is not one comparison"),
        ("1 < m < 3", "is not one comparison"),
        ("m < theta", "must not depend on theta"),
        ("m < q", "unknown name `q`"),
        ("ln(m - 2) < 1", "not a defined"),
    ] {
        let e = cond(bad).err().unwrap_or_else(|| panic!("{bad} accepted"));
        assert!(e.contains(needle), "{bad}: `{needle}` not in {e}");
    }
    // Over a parameter box: decided for the whole box, or refused.
    let text = format!("{BASE}[conditions]\nc = \"m > 1\"\n");
    let at = |lo, hi| FileScene::parse_enclosed(&text, &[], &[("m".into(), iv(lo, hi))]);
    assert!(at(1.5, 3.0).is_ok());
    let e = at(0.5, 3.0).err().unwrap();
    assert!(e.contains("cannot be decided with m ∈ [0.5, 3]"), "{e}");
    // Written order is kept, and the first refusal is the one reported.
    let e = with("[conditions]\nz = \"m > 5\"\na = \"m > 6\"\n")
        .err()
        .unwrap();
    assert!(e.contains("conditions.z"), "{e}");
}

/// `[functions]` and `energy`: compiled with the definitions, refused when
/// a function reads θ̇, reuses a name, or does not parse.
#[test]
fn functions_and_energy_are_compiled_or_refused() {
    let f = with(
        "[definitions]\nh = \"m*sin(theta)\"\n[functions]\nf = \"h + k\"\n\
         [dynamics]\ntheta_ddot = \"-h\"\nenergy = \"theta_dot^2/2 - m*cos(theta)\"\n",
    )
    .unwrap();
    let x = f.function("f").unwrap().eval(0.5_f64);
    assert!(close(x, 2.0 * 0.5_f64.sin() + 0.1), "{x}");
    let e = f.energy(&Angle::new(0.5_f64), 2.0).unwrap();
    assert!(close(e, 2.0 - 2.0 * 0.5_f64.cos()), "{e}");
    assert!(with("").unwrap().functions.is_empty());
    for (bad, needle) in [
        (
            "[functions]\nf = \"theta_dot*m\"\n",
            "must not depend on theta_dot",
        ),
        ("[functions]\nm = \"theta\"\n", "also a parameter"),
        (
            "[definitions]\nh = \"theta\"\n[functions]\nh = \"theta\"\n",
            "also a definition",
        ),
        ("[functions]\nsin = \"theta\"\n", "reserved"),
        (
            "[functions]\nf = \"theta +\"\n",
            "`functions.f` at character",
        ),
        (
            "[dynamics]\ntheta_ddot = \"0\"\nenergy = \"theta_dot^\"\n",
            "`dynamics.energy` at character",
        ),
        ("[functions]\nf = 2\n", "expected a string"),
    ] {
        let e = with(bad).err().unwrap_or_else(|| panic!("{bad} accepted"));
        assert!(e.contains(needle), "{bad}: `{needle}` not in {e}");
    }
}

/// Through the CLI: a scene file whose condition fails is refused with
/// exit 2 and the condition named, before any work.
#[test]
fn a_failed_condition_is_a_usage_error() {
    let path = scenes_dir().join("viscous-disc.toml");
    let p = path.to_str().unwrap();
    assert_bad_input(
        &["area", "--scene-file", p, "--param", "b=2"],
        "`conditions.centre_of_mass_inside_disc`: `b < a` does not hold with b = 2, a = 1",
    );
}
