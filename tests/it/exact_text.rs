//! A scene file's text evaluated as written over an exact scalar
//! (`FileScene::exact`), the way the paper's claims read the printed
//! formulas: literals are their decimal values, the value lies in the
//! compiled tape's certified enclosure of the same text, and whatever has no
//! exact value is a clear error, never a guess.

use detach::claims::exact::Q;
use detach::inari::{interval, Interval};
use detach::number::scalar::Scalar;
use detach::scene::file::EMBEDDED;
use detach::scene::{decimal, Angle, ExactPoint, ExactTheta, FileScene};
use rug::{Integer, Rational};

/// Every text of a file that the compiled scene also evaluates, with that
/// evaluation at (θ, θ̇) over intervals.
fn compiled_keys(f: &FileScene) -> Vec<String> {
    let mut keys = vec!["regions.omega".to_string(), "regions.omega0".to_string()];
    if f.has_dynamics() {
        keys.push("dynamics.theta_ddot".into());
        if f.energy(&Angle::new(0.5), 0.0).is_some() {
            keys.push("dynamics.energy".into());
        }
    }
    keys.extend(f.functions.iter().map(|g| format!("functions.{}", g.name)));
    keys
}

fn compiled(f: &FileScene, key: &str, theta: Interval, w: Interval) -> Interval {
    match key {
        "regions.omega" => f.regions_at(theta, w)[0],
        "regions.omega0" => f.regions_at(theta, w)[1],
        "dynamics.theta_ddot" => f.acceleration(theta, w),
        "dynamics.energy" => f.energy(&Angle::new(theta), w).unwrap(),
        k => f.function(&k["functions.".len()..]).unwrap().eval(theta),
    }
}

fn params<T: Scalar>(f: &FileScene, value: impl Fn(&str, Interval) -> T) -> Vec<(&'static str, T)> {
    f.params
        .specs
        .iter()
        .zip(&f.params.values)
        .map(|(s, p)| (s.name, value(&p.text, p.value)))
        .collect()
}

fn file(name: &str) -> FileScene {
    FileScene::shipped(name, &[])
        .expect("embedded")
        .expect("a shipped scene compiles")
}

#[test]
fn decimal_literals_are_their_exact_rationals() {
    // Each reference written by hand as numerator/denominator.
    let big = Integer::from_str_radix("123456789012345678905", 10).unwrap();
    let cases = [
        ("9.81", Rational::from((981, 100))),
        ("0.1", Rational::from((1, 10))),
        ("1e-3", Rational::from((1, 1000))),
        ("2.5E+2", Rational::from(250)),
        (".5", Rational::from((1, 2))),
        ("7", Rational::from(7)),
        ("12345678901234567890.5", Rational::from((big, 10))),
    ];
    for (text, want) in cases {
        assert_eq!(decimal::<Q>(text).get(), want, "{text}");
    }
}

/// At rational points `tan(θ/2) = t`, every text the compiled scene
/// evaluates gives, over exact rationals with the parameters' decimal
/// values, a value inside the tape's interval enclosure at θ = 2·atan(t):
/// the two evaluators read the same text. The ice disc's texts that reach
/// the logarithms of (3.1) are compared over intervals instead, with the
/// logarithms' enclosures given.
#[test]
fn file_texts_evaluate_exactly_inside_their_compiled_enclosures() {
    let mut compared = 0;
    for (name, _) in EMBEDDED {
        let f = file(name);
        let pq = params(&f, |t, _| decimal::<Q>(t));
        let pi = params(&f, |_, x| x);
        for (tn, td) in [(1i32, 3i32), (1, 2), (2, 3), (3, 1), (-1, 2)] {
            let t = Q::ratio(tn.into(), td.into());
            let (s, c) = (
                Q::int(2) * t / (Q::int(1) + t * t),
                (Q::int(1) - t * t) / (Q::int(1) + t * t),
            );
            let ti = Interval::try_from((f64::from(tn), f64::from(tn))).unwrap()
                / Interval::try_from((f64::from(td), f64::from(td))).unwrap();
            let theta = interval!(2.0, 2.0).unwrap() * ti.atan();
            let in_domain = |x: Interval| {
                let d = f.domain.theta;
                x.subset(d[0].convex_hull(d[1]))
            };
            if !in_domain(theta) {
                continue;
            }
            for (wn, w) in [
                (Q::ratio(3, 2), interval!(1.5, 1.5).unwrap()),
                (Q::int(-2), interval!(-2.0, -2.0).unwrap()),
            ] {
                for key in compiled_keys(&f) {
                    let want = compiled(&f, &key, theta, w);
                    let exact = f.exact(
                        &key,
                        &ExactPoint {
                            theta: ExactTheta::trig(s, c),
                            theta_dot: wn,
                            values: &pq,
                        },
                    );
                    match exact {
                        Ok(v) => {
                            let v = v.get();
                            let (lo, hi) = (
                                Rational::from_f64(want.inf()).unwrap(),
                                Rational::from_f64(want.sup()).unwrap(),
                            );
                            assert!(
                                lo <= v && v <= hi,
                                "{name} {key} at t = {tn}/{td}: {v} outside {want:?}"
                            );
                        }
                        Err(e) => {
                            // Only (3.1)'s logarithms are out of exact reach:
                            // compare over intervals with them given.
                            assert!(
                                name.starts_with("ice-disc") && e.message.contains("`ln`"),
                                "{name} {key}: {e}"
                            );
                            let an = Angle::new(theta);
                            let half = theta / interval!(2.0, 2.0).unwrap();
                            let logs = Some(((half.sin() / half.cos()).ln(), an.sin.ln()));
                            let at = ExactPoint {
                                theta: ExactTheta {
                                    sin: an.sin,
                                    cos: an.cos,
                                    logs,
                                },
                                theta_dot: w,
                                values: &pi,
                            };
                            let v = f.exact(&key, &at).unwrap();
                            assert!(!v.disjoint(want), "{name} {key}: {v:?} vs {want:?}");
                        }
                    }
                    compared += 1;
                }
            }
        }
    }
    // 7 files, several points each: a test that compared nothing would pass.
    assert!(compared > 150, "{compared}");
}

/// The same text with one definition given a value: the definition's text
/// is not read (the claims give §3's v_x this way).
#[test]
fn a_given_definition_replaces_its_text() {
    let f = file("ice-disc-printed");
    let mut values = params(&f, |t, _| decimal::<Q>(t));
    let (s, c) = (Q::ratio(4, 5), Q::ratio(3, 5));
    let at = |values: &[(&'static str, Q)]| {
        f.exact(
            "dynamics.theta_ddot",
            &ExactPoint {
                theta: ExactTheta::trig(s, c),
                theta_dot: Q::int(0),
                values,
            },
        )
    };
    let e = at(&values).unwrap_err();
    assert!(e.message.contains("`ln` has no exact value"), "{e}");
    values.push(("vx", Q::int(1)));
    let v = at(&values).unwrap().get();
    // (3.3) by hand at the defaults m = a = 1, A = 1/4, g = 981/100,
    // p_φ = 5/2, p_ψ = 2, sin θ = 4/5, cos θ = 3/5, v_x = 1:
    // τ = (2 − 3/2)/(1/5) = 5/2, τ' = (5/2 − 6/5)/(16/100) = 65/8,
    // θ̈ = −(g·3/5 − τ + A τ τ')/(A + 1).
    let g = Rational::from((981, 100));
    let (tau, tau1) = (Rational::from((5, 2)), Rational::from((65, 8)));
    let a_big = Rational::from((1, 4));
    let want = -(g * Rational::from((3, 5)) - tau.clone() + a_big.clone() * tau * tau1)
        / (a_big + Rational::from(1));
    assert_eq!(v, want);
}

/// Whatever has no exact value is an error naming the text, not a value.
#[test]
fn what_has_no_exact_value_is_an_error_naming_the_text() {
    let base = |definition: &str| {
        format!(
            "name = \"x\"\n[domain]\ntheta = [\"0\", \"1\"]\ntheta_dot = [\"-1\", \"1\"]\n\
             [parameters]\nk = \"2\"\n[definitions]\nd = \"{definition}\"\n\
             [regions]\nomega = \"d + theta_dot < 0\"\n"
        )
    };
    let cases = [
        ("pi*k", "`pi`"),
        ("sqrt(k)", "`sqrt`"),
        ("sin(k)", "`sin` has no exact value here"),
        ("theta*k", "theta enters other than"),
        ("ln(sin(theta))", "`ln` has no exact value"),
        ("min(k, 1)", "`min`"),
        ("exp(k)", "`exp`"),
    ];
    for (text, says) in cases {
        let f = FileScene::parse(&base(text), &[]).expect("a valid file");
        let values = [("k", Q::int(2))];
        let at = ExactPoint {
            theta: ExactTheta::trig(Q::ratio(3, 5), Q::ratio(4, 5)),
            theta_dot: Q::int(1),
            values: &values,
        };
        let e = f.exact("regions.omega", &at).unwrap_err();
        assert!(e.message.contains(says), "{text}: {e}");
        assert_eq!(e.key, "definitions.d", "{text}: {e}");
    }
    // A parameter left without a value, and a key the file lacks.
    let f = FileScene::parse(&base("k*sin(theta)"), &[]).unwrap();
    let at = ExactPoint {
        theta: ExactTheta::trig(Q::ratio(3, 5), Q::ratio(4, 5)),
        theta_dot: Q::int(1),
        values: &[],
    };
    let e = f.exact("regions.omega", &at).unwrap_err();
    assert!(
        e.message.contains("parameter `k` has no value given"),
        "{e}"
    );
    let e = f.exact("dynamics.theta_ddot", &at).unwrap_err();
    assert!(e.message.contains("no such text"), "{e}");
    // and with its value, the exact 2·3/5 + 1
    let values = [("k", Q::int(2))];
    let v = f
        .exact(
            "regions.omega",
            &ExactPoint {
                values: &values,
                ..at
            },
        )
        .unwrap();
    assert_eq!(v.get(), Rational::from((11, 5)));
}
