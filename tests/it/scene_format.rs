//! The scene-file format states everything a paper scene's Rust knows: each
//! paper scene's file (embedded, in both readings) against its built-in
//! model on parameters, conditions, domain, regions, dynamics, energy and
//! the functions of (2.12) and (3.3); and the new sections' rules.
//!
//! References: the built-in models (`src/scene/{viscous,smooth,ice}.rs`)
//! and the roots code (`src/roots/equations.rs`), an independent writing of
//! the same formulas; the committed proof `proofs/roots-2.12.json` for the
//! text of (2.12).

use crate::common::{assert_bad_input, Rng};
use detach::number::scalar::Scalar;
use detach::roots::equations::{IceAcceleration, PotentialSlope};
use detach::roots::{isolate, solve_2_12, solve_3_3, Budget, RealFn};
use detach::scene::file::{Function, EMBEDDED, SHIPPED};
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

fn built_in(id: SceneId, overrides: &[(&str, &str)]) -> Result<Scene, String> {
    let o: Vec<(String, String)> = overrides
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    Scene::build(id, &o).map(|s| s.0).map_err(|e| e.to_string())
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

/// Asserts a file's value and the built-in's agree at a point and over a box
/// (enclosures of the same real overlap).
fn agree<F, G>(what: &str, file: F, rust: G, t: f64, w: f64)
where
    F: Fn(&Angle<f64>, f64, &Angle<Interval>, Interval) -> (f64, Interval),
    G: Fn(&Angle<f64>, f64, &Angle<Interval>, Interval) -> (f64, Interval),
{
    let (pt, pw) = (Angle::new(t), w);
    let (bt, bw) = (Angle::new(iv(t, t + 1e-3)), iv(w, w + 1e-3));
    let (x, xi) = file(&pt, pw, &bt, bw);
    let (y, yi) = rust(&pt, pw, &bt, bw);
    assert!(close(x, y), "{what} at ({t}, {w}): file {x}, built-in {y}");
    assert!(
        !xi.disjoint(yi),
        "{what} on a box at ({t}, {w}): file {xi:?}, built-in {yi:?}"
    );
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

/// Each paper file declares the built-in's parameters (names, defaults, in
/// order) and domain, and says Ω₀ = Ω exactly when the model does.
#[test]
fn paper_files_declare_the_built_in_parameters_and_domain() {
    for id in SceneId::ALL {
        let b = built_in(id, &[]).unwrap();
        for v in Variant::ALL {
            let s = file_of(id, v, &[]).unwrap();
            let f = file(&s);
            let names = |specs: &[detach::number::param::ParamSpec]| {
                specs
                    .iter()
                    .map(|p| (p.name, p.default))
                    .collect::<Vec<_>>()
            };
            assert_eq!(names(f.params.specs), names(id.params()), "{id} {v}");
            let (x, y) = (s.domain(), b.domain());
            assert_eq!((x.theta, x.theta_dot), (y.theta, y.theta_dot), "{id} {v}");
            assert_eq!(s.omega0_is_omega(v), b.omega0_is_omega(v), "{id} {v}");
            let probe = Angle::new(1.0_f64);
            assert_eq!(
                s.energy(&probe, 0.5).is_some(),
                b.energy(&probe, 0.5).is_some(),
                "{id} {v}"
            );
        }
    }
}

/// Parameter sets accepted and refused: the files' `[conditions]` decide as
/// the built-in checks do (signs, and b < a in intervals: touching or
/// overlapping enclosures are refused by both).
#[test]
fn conditions_accept_and_refuse_as_the_built_ins_do() {
    let viscous: &[&[(&str, &str)]] = &[
        &[],
        &[("b", "0")],
        &[("b", "0.999")],
        &[("b", "1")],
        &[("b", "1.5")],
        &[("b", "-0.1")],
        &[("a", "0"), ("b", "0")],
        &[("a", "-1")],
        &[("a", "0.1"), ("b", "0.1000000000000000000001")],
        &[("a", "0.1000000000000000000001"), ("b", "0.1")],
        &[("a", "1e-300"), ("b", "1e-301")],
        &[("m", "0")],
        &[("C", "-0.3")],
        &[("mu", "0")],
        &[("mu", "-0.1")],
        &[("g", "0")],
    ];
    let disc: &[&[(&str, &str)]] = &[
        &[],
        &[("m", "0")],
        &[("m", "-1")],
        &[("a", "-1")],
        &[("A", "0")],
        &[("C", "0")],
        &[("C", "1e-300")],
        &[("g", "-9.81")],
        &[("p_phi", "-3"), ("p_psi", "0")],
    ];
    let mut refused = 0;
    for id in SceneId::ALL {
        let cases = match id {
            SceneId::ViscousDisc => viscous,
            _ => disc,
        };
        for case in cases {
            let want = built_in(id, case);
            for v in Variant::ALL {
                let got = file_of(id, v, case);
                assert_eq!(
                    got.is_ok(),
                    want.is_ok(),
                    "{id} {v} {case:?}: file {:?}, built-in {:?}",
                    got.as_ref().err(),
                    want.as_ref().err()
                );
                refused += usize::from(got.is_err());
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

/// The energies (2.11) and (3.2) of the files against the built-ins' on
/// sample points and boxes; the viscous disc has none in either.
#[test]
fn energies_agree_with_the_built_ins() {
    for id in SceneId::ALL {
        let b = built_in(id, &[]).unwrap();
        for v in Variant::ALL {
            let s = file_of(id, v, &[]).unwrap();
            if id == SceneId::ViscousDisc {
                assert!(s.energy(&Angle::new(1.0_f64), 0.0).is_none());
                continue;
            }
            for (t, w) in samples(id, 400) {
                let e = |sc: &Scene| {
                    let sc = sc.clone();
                    move |pa: &Angle<f64>, pw: f64, ba: &Angle<Interval>, bw: Interval| {
                        (sc.energy(pa, pw).unwrap(), sc.energy(ba, bw).unwrap())
                    }
                };
                agree(&format!("{id} {v} energy"), e(&s), e(&b), t, w);
            }
        }
    }
}

/// θ̈ and the region coefficients of each file against the built-in in the
/// same reading.
#[test]
fn accelerations_and_regions_agree_with_the_built_ins() {
    for id in SceneId::ALL {
        let b = built_in(id, &[]).unwrap();
        for v in Variant::ALL {
            let s = file_of(id, v, &[]).unwrap();
            for (t, w) in samples(id, 300) {
                let acc = |sc: &Scene, v: Variant| {
                    let sc = sc.clone();
                    move |pa: &Angle<f64>, pw: f64, ba: &Angle<Interval>, bw: Interval| {
                        (sc.acceleration(v, pa, pw), sc.acceleration(v, ba, bw))
                    }
                };
                let what = format!("{id} {v} acceleration");
                agree(&what, acc(&s, Variant::Derived), acc(&b, v), t, w);
                for k in 0..6 {
                    let coef = |sc: &Scene, v: Variant| {
                        let sc = sc.clone();
                        move |pa: &Angle<f64>, _: f64, ba: &Angle<Interval>, _: Interval| {
                            (
                                coefficient(sc.constraints(v, pa), k),
                                coefficient(sc.constraints(v, ba), k),
                            )
                        }
                    };
                    let what = format!("{id} {v} coefficient {k}");
                    agree(&what, coef(&s, Variant::Derived), coef(&b, v), t, w);
                }
            }
        }
    }
}

/// `c₂, c₁, c₀` of Ω (k = 0, 1, 2), then of Ω₀ (k = 3, 4, 5).
fn coefficient<T: Scalar>(c: detach::scene::Constraints<T>, k: usize) -> T {
    let q = if k < 3 { c.omega } else { c.omega0 };
    [q.c2, q.c1, q.c0][k % 3]
}

/// A file's function as the isolator's `RealFn`.
struct Named<'a>(&'a Function);

impl RealFn for Named<'_> {
    fn eval<T: Scalar>(&self, x: T) -> T {
        self.0.eval(x)
    }
}

/// The functions of (2.12) and (3.3) in the disc files against the roots
/// code's Rust: values at points and on boxes, the roots the isolator finds
/// with them, and (2.12)'s text against the committed proof's statement.
#[test]
fn functions_agree_with_the_roots_code() {
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
        let b = built_in(id, &[]).unwrap();
        let (disc, ice) = match &b {
            Scene::Smooth(d) => (d.clone(), None),
            Scene::Ice(i) => (i.disc.clone(), Some(i.clone())),
            _ => unreachable!(),
        };
        for v in Variant::ALL {
            let s = file_of(id, v, &[]).unwrap();
            let f = file(&s);
            let slope = f.function("potential_slope").unwrap();
            let eq212 = f.function("eq_2_12").unwrap();
            assert_eq!(
                eq212.text, stated,
                "{id} {v}: (2.12) as the proof states it"
            );
            for (t, _) in samples(id, 400) {
                let named = |g: &Function| {
                    let g = g.clone();
                    move |pa: &Angle<f64>, _: f64, ba: &Angle<Interval>, _: Interval| {
                        (g.eval(pa.theta), g.eval(ba.theta))
                    }
                };
                let d = disc.clone();
                let rust_slope =
                    move |pa: &Angle<f64>, _: f64, ba: &Angle<Interval>, _: Interval| {
                        (d.reduced_potential_slope(pa), d.reduced_potential_slope(ba))
                    };
                agree(&format!("{id} {v} Π̃'"), named(slope), rust_slope, t, 0.0);
                let d = disc.clone();
                let rust_212 = move |pa: &Angle<f64>, _: f64, ba: &Angle<Interval>, _: Interval| {
                    let p = PotentialSlope(&d);
                    (p.eval(pa.theta), p.eval(ba.theta))
                };
                agree(&format!("{id} {v} (2.12)"), named(eq212), rust_212, t, 0.0);
                if let Some(ice) = &ice {
                    let eq33 = f.function("eq_3_3").unwrap();
                    let i = ice.clone();
                    let rust_33 =
                        move |pa: &Angle<f64>, _: f64, ba: &Angle<Interval>, _: Interval| {
                            let p = IceAcceleration(&i);
                            (p.eval(pa.theta), p.eval(ba.theta))
                        };
                    agree(&format!("{id} {v} (3.3)"), named(eq33), rust_33, t, 0.0);
                }
            }
            // The isolator runs on the file's function and finds the roots
            // `detach roots` finds, one for one.
            let budget = Budget::default();
            let mut problems = vec![(eq212, solve_2_12(&disc, &budget))];
            if let Some(ice) = &ice {
                problems.push((f.function("eq_3_3").unwrap(), solve_3_3(ice, &budget)));
            }
            for (g, want) in problems {
                assert!(want.complete, "{id} {}", g.name);
                let [lo, hi] = want.searched;
                let got = isolate(&Named(g), lo, hi, &budget);
                assert!(got.complete, "{id} {v} {}", g.name);
                assert_eq!(got.roots.len(), want.roots.len(), "{id} {v} {}", g.name);
                assert!(!want.roots.is_empty());
                for (x, y) in got.roots.iter().zip(&want.roots) {
                    assert!(!x.interval().disjoint(y.interval()), "{x:?} vs {y:?}");
                }
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
