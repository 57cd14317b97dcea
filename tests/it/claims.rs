//! Paper checks: every claim reaches its verdict, and a deliberately wrong
//! variant (the check's mutant) changes the outcome — a check that cannot come
//! out the other way proves nothing. Reference numbers are computed by hand
//! from the closed forms quoted in each test.

use detach::claims::{self, check, Verdict};
use serde_json::Value;

/// The ids the issue fixes, all of which must be in the registry.
const ISSUE_IDS: [&str; 49] = [
    "F1.3",
    "F1.4",
    "F1.5",
    "F1.7",
    "F1.8",
    "F1.9",
    "F1.10",
    "F1.11",
    "F2.1",
    "F2.5",
    "F2.6",
    "F2.7",
    "F2.8",
    "F2.9",
    "F2.10",
    "F2.12",
    "F3.1",
    "F3.2",
    "F3.3",
    "F3.4",
    "F3.5",
    "S1.ideal",
    "S1.friction",
    "S1.12",
    "S1.12mu",
    "S1.eq",
    "S1.traj",
    "S2.omega",
    "S2.case1",
    "S2.case2",
    "S2.case3",
    "S2.case4",
    "S2.12count",
    "S2.12type",
    "S2.12inOmega",
    "S2.12components",
    "S3.omega",
    "S3.c0changes",
    "S3.c0invariant",
    "S3.c0linear",
    "S3.c0anypoint",
    "S3.forms",
    "S3.symmetry",
    "S3.sub1",
    "S3.sub2",
    "S3.sub3",
    "S2.alpha",
    "S2.case1fr",
    "F2.1",
];

fn v(id: &str, mutant: bool) -> (Verdict, claims::ClaimResult) {
    let r = check(id, mutant).expect("known id");
    (r.verdict, r)
}

fn expect(id: &str, verdict: Verdict) -> claims::ClaimResult {
    let (got, r) = v(id, false);
    assert_eq!(got, verdict, "{id}: {}", r.summary);
    let (m, mr) = v(id, true);
    assert_ne!(
        m, verdict,
        "{id}: the mutant reached the same verdict: {}",
        mr.summary
    );
    r
}

fn num(x: &Value) -> f64 {
    x.as_str()
        .map(|s| s.parse().unwrap())
        .or_else(|| x.as_f64())
        .unwrap()
}

#[test]
fn registry_holds_every_issue_id_once() {
    let ids = claims::ids();
    for id in ISSUE_IDS {
        assert!(ids.contains(&id), "{id} missing");
    }
    let mut sorted = ids.clone();
    sorted.sort();
    sorted.dedup();
    assert_eq!(sorted.len(), ids.len(), "duplicate ids");
}

/// The table and the check functions pair one to one; each way a table can
/// fail to match is refused (tables edited from the built-in one).
#[test]
fn claim_table_pairs_with_the_checks_one_to_one() {
    use claims::{pair, TableError};
    let checks = claims::checks();
    let table = claims::TABLE;
    assert_eq!(pair(table, &checks).unwrap().len(), checks.len());
    let renamed = table.replacen("id = \"F1.3\"", "id = \"F1.33\"", 1);
    assert_eq!(
        pair(&renamed, &checks).err(),
        Some(TableError::NoCheck("F1.33".into()))
    );
    let first = table.find("[[claim]]").unwrap();
    let second = first + 1 + table[first + 1..].find("[[claim]]").unwrap();
    let dropped = format!("{}{}", &table[..first], &table[second..]);
    assert_eq!(
        pair(&dropped, &checks).err(),
        Some(TableError::NoRow("F1.3".into()))
    );
    let doubled = format!("{table}\n{}", &table[first..second]);
    assert_eq!(
        pair(&doubled, &checks).err(),
        Some(TableError::Repeated("F1.3".into()))
    );
    let extra_key = table.replacen("[[claim]]\n", "[[claim]]\nverdict = \"confirmed\"\n", 1);
    assert!(matches!(
        pair(&extra_key, &checks),
        Err(TableError::Syntax(_))
    ));
}

#[test]
fn unknown_id_is_an_error() {
    assert!(claims::run(&["F9.9".into()]).is_err());
    assert_eq!(claims::run(&["F1.3".into()]).unwrap().len(), 1);
}

// ---------------------------------------------------------------- §1

#[test]
fn f1_3_f1_4_f1_8_confirmed() {
    expect("F1.3", Verdict::Confirmed);
    expect("F1.4", Verdict::Confirmed);
    expect("F1.8", Verdict::Confirmed);
}

#[test]
fn f1_5_is_a_typo() {
    expect("F1.5", Verdict::Typo);
}

#[test]
fn f1_7_error_with_certified_witness() {
    let r = expect("F1.7", Verdict::Error);
    // θ = 0, θ̇ = 1, defaults: h = 1, h' = 0.5, h'' = 0.
    // printed: (−9.81·0.5 − 0.8)/(2(0.3 + 0.25)) = −5.18636…; Newton: −5.705/0.55 = −10.3727…
    let p = &r.witness["printed_theta_ddot"];
    let d = &r.witness["newton_theta_ddot"];
    assert!(num(&p[0]) <= -5.186363 && -5.186364 <= num(&p[1]), "{p}");
    assert!(num(&d[0]) <= -10.372727 && -10.372728 <= num(&d[1]), "{d}");
    assert_eq!(r.witness["without_factor_2"]["identity"], "proved");
}

#[test]
fn f1_9_error_inherited_from_1_7() {
    let r = expect("F1.9", Verdict::Error);
    assert_eq!(r.witness["from_printed_1_7"]["identity"], "proved");
}

#[test]
fn f1_10_f1_11_errors_with_boxes() {
    for id in ["F1.10", "F1.11"] {
        let r = expect(id, Verdict::Error);
        let b = &r.witness["witness"]["box"];
        let th = [num(&b["theta"][0]), num(&b["theta"][1])];
        let w = [num(&b["theta_dot"][0]), num(&b["theta_dot"][1])];
        // independent check at the box centre in f64, from the closed forms
        let (a, bb, m, c, mu, g) = (1.0, 0.5, 1.0, 0.3, 0.8, 9.81f64);
        let (t, wd) = (0.5 * (th[0] + th[1]), 0.5 * (w[0] + w[1]));
        let (h, h1, h2) = (a + bb * t.sin(), bb * t.cos(), -bb * t.sin());
        let printed = if id == "F1.10" {
            0.0
        } else {
            mu * h * h * h1 * wd
        } - g * (2.0 * c + m * h1 * h1)
            - 2.0 * c * h2 * wd * wd;
        let derived = if id == "F1.10" {
            -g - h2 * wd * wd
        } else {
            mu * h * h * h1 * wd - c * g - c * h2 * wd * wd
        };
        assert!(printed * derived < 0.0, "{id}: {printed} vs {derived}");
    }
}

#[test]
fn s1_statements() {
    expect("S1.ideal", Verdict::Confirmed);
    expect("S1.friction", Verdict::Confirmed);
    expect("S1.12", Verdict::Confirmed);
    expect("S1.12mu", Verdict::Confirmed);
    expect("S1.traj", Verdict::Confirmed);
}

#[test]
fn s1_eq_focus_is_conditional() {
    let r = expect("S1.eq", Verdict::Conditional);
    // discriminant at −π/2: (μ²(a−b)⁴ − 4mgbC)/C² = (0.04 − 5.886)/0.09 = −64.9555…
    let d = num(&r.witness["side_true"]["at_minus_pi_over_2"]["discriminant_trace2_minus_4det"]);
    assert!((d + 64.955_555_555).abs() < 1e-6, "{d}");
    // μ = 20: (400·0.0625 − 5.886)/0.09 = 212.377…
    let d = num(&r.witness["side_false"]["at_minus_pi_over_2"]["discriminant_trace2_minus_4det"]);
    assert!((d - 212.377_777_777).abs() < 1e-6, "{d}");
}

// ---------------------------------------------------------------- §2

#[test]
fn section_2_formulas_confirmed() {
    for id in [
        "F2.1", "F2.5", "F2.6", "F2.7", "F2.8", "F2.9", "F2.10", "F2.12",
    ] {
        expect(id, Verdict::Confirmed);
    }
}

#[test]
fn section_2_slips() {
    let r = expect("S2.alpha", Verdict::Typo);
    assert_eq!(num(&r.witness["alpha"]), -0.5);
    expect("S2.case1fr", Verdict::Typo);
}

#[test]
fn section_2_statements() {
    for id in [
        "S2.omega",
        "S2.case1",
        "S2.case2",
        "S2.case3",
        "S2.case4",
        "S2.12inOmega",
    ] {
        expect(id, Verdict::Confirmed);
    }
}

#[test]
fn s2_12count_false_at_alpha_one() {
    let r = expect("S2.12count", Verdict::False);
    let s = r.witness["samples"].as_array().unwrap();
    let by = |pf: &str| {
        s.iter()
            .find(|x| x["p_phi"] == pf && x["p_psi"] == pf)
            .unwrap()
    };
    // p_φ = p_ψ = 1: f = 9.81 cos θ sin³θ + 4(1 − cos θ)² > 0 on (0, π) (e.g. θ = 2: −3.07 + 8.02)
    assert_eq!(by("1")["equilibria"]["count"], 0);
    assert_eq!(by("0.3")["equilibria"]["count"], 2);
}

#[test]
fn s2_12type_and_components_false() {
    expect("S2.12type", Verdict::False);
    let r = expect("S2.12components", Verdict::False);
    assert!(r.summary.contains("(2, 2)"), "{}", r.summary);
}

// ---------------------------------------------------------------- §3

#[test]
fn section_3_formulas() {
    for id in ["F3.1", "F3.2", "F3.3", "F3.5"] {
        expect(id, Verdict::Confirmed);
    }
    let r = expect("F3.4", Verdict::Error);
    // V₀(θ = 1) = 1 + cos²1/(0.25 + sin²1) = 1.30470168…
    let d = &r.witness["V0_newton_euler"];
    assert!(
        num(&d[0]) <= 1.304_701_69 && 1.304_701_68 <= num(&d[1]),
        "{d}"
    );
    assert_eq!(r.witness["identity"]["U0_over_V0"]["identity"], "proved");
}

#[test]
fn section_3_statements() {
    for id in [
        "S3.omega",
        "S3.c0linear",
        "S3.symmetry",
        "S3.sub1",
        "S3.sub3",
    ] {
        expect(id, Verdict::Confirmed);
    }
    expect("S3.c0changes", Verdict::Conditional);
    expect("S3.sub2", Verdict::ConfirmedOn);
    let r = expect("S3.c0invariant", Verdict::Conditional);
    // g(A + m a² sin²θ*)/((A + m a²) a sin θ*) = 9.81·0.61/(1.25·0.6) = 7.9788
    let b = num(&r.witness["side_extra"]["boundary_theta_dot_squared"]);
    assert!((b - 7.9788).abs() < 1e-9, "{b}");
    let r = expect("S3.c0anypoint", Verdict::False);
    assert_eq!(num(&r.witness["tau"]), 0.0);
}

#[test]
fn s3_forms_classifies_and_the_mutant_sees_fewer() {
    let (got, r) = v("S3.forms", false);
    assert_eq!(got, Verdict::NotCheckable);
    let forms = r.witness["forms"].as_object().unwrap();
    assert!(forms.len() >= 2, "{forms:?}");
    assert_eq!(r.witness["undecided_samples"], 0);
    let (_, m) = v("S3.forms", true);
    assert!(m.witness["forms"].as_object().unwrap().len() < forms.len());
}

#[test]
fn report_is_deterministic_and_complete() {
    let a = claims::run(&[]).unwrap();
    let b = claims::run(&[]).unwrap();
    let (ja, jb) = (claims::report::json(&a), claims::report::json(&b));
    assert_eq!(ja, jb);
    assert_eq!(a.len(), claims::ids().len());
    let md = claims::report::markdown(&a);
    for r in &a {
        assert!(md.contains(&format!("| {} |", r.id)));
    }
}

/// The identity witnesses (objects with a string `identity`) inside `x`.
fn identities<'a>(x: &'a Value, at: &str, out: &mut Vec<(String, &'a Value)>) {
    match x {
        Value::Object(m) => {
            if m.get("identity").is_some_and(Value::is_string) {
                out.push((at.to_string(), x));
            }
            for (k, v) in m {
                identities(v, &format!("{at}/{k}"), out);
            }
        }
        Value::Array(a) => a.iter().for_each(|v| identities(v, at, out)),
        _ => {}
    }
}

/// Every identity of every check, and of its mutant, is either proved (the
/// cleared difference is the zero polynomial) or refused with a rational
/// point where the two sides differ: none is only sampled at random points.
#[test]
fn identities_are_proved_or_refused_with_a_point() {
    let mut proved = 0;
    for id in claims::ids() {
        for mutant in [false, true] {
            let r = check(id, mutant).unwrap();
            let mut found = Vec::new();
            identities(&r.witness, id, &mut found);
            for (at, i) in found {
                match i["identity"].as_str() {
                    Some("proved") => {
                        assert_eq!(i["cleared_difference"], "identically zero", "{at}");
                        proved += 1;
                    }
                    Some("differ") => {
                        assert!(i["point"].is_object(), "{at} (mutant {mutant}): no point");
                        assert_ne!(num(&i["printed_minus_derived"]), 0.0, "{at}");
                    }
                    other => panic!("{at} (mutant {mutant}): {other:?}"),
                }
            }
        }
    }
    // 45 identities of the unmutated checks are proved, and most survive
    // their claim's mutant
    assert!(proved > 45, "{proved} proved");
}
