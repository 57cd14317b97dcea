//! Paper checks: every claim reaches its verdict, and a deliberately wrong
//! variant (the check's mutant) changes the outcome — a check that cannot come
//! out the other way proves nothing. Reference numbers are computed by hand
//! from the closed forms quoted in each test.

use detach::claims::{self, check, Verdict};
use serde_json::Value;

/// The paper's formulas and statements by id (F: a formula, S: a
/// statement), all of which must be in the registry.
const PAPER_IDS: [&str; 49] = [
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
fn registry_holds_every_paper_id_once() {
    let ids = claims::ids();
    for id in PAPER_IDS {
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
        Some(TableError::NoRow("A.onlyN".into()))
    );
    let doubled = format!("{table}\n{}", &table[first..second]);
    assert_eq!(
        pair(&doubled, &checks).err(),
        Some(TableError::Repeated("A.onlyN".into()))
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
    // discriminant at −π/2: (μ²(a−b)⁴ − 4mgbC)/C² = (0.04 − 5.886)/0.09
    // = −5846/90 = −2923/45, as an exact rational
    let at = |side: &str| {
        let t = r.witness[side]["at_minus_pi_over_2"]["discriminant_trace2_minus_4det"]
            .as_str()
            .unwrap();
        q(t)
    };
    assert_eq!(at("side_true"), q("-2923/45"));
    // μ = 20: (400·0.0625 − 5.886)/0.09 = 19.114/0.09 = 9557/45
    assert_eq!(at("side_false"), q("9557/45"));
    // a = b = 0.5: the damping −μ(a − b)²/C vanishes, trace 0: a centre of
    // the linearisation, not a focus (the discriminant −4mgb/C < 0 alone
    // would call it one)
    let c = &r.witness["side_a_equals_b"]["at_minus_pi_over_2"];
    assert_eq!(c["d_thdd_d_theta_dot"], "0");
    assert_eq!(c["type"], "centre of the linearisation");
    assert!(r
        .correction
        .as_deref()
        .unwrap()
        .contains("a centre iff μ(a − b) = 0"));
}

/// Subcase 2 is proved, not sampled: equilibria solve G(tg(θ/2)) = c₀ with
/// G falling then rising, so 0, 1 (tangent) or 2. min G is checked against
/// mpmath (findroot of t²(1 + t²)²G' by bisection, 30 digits, defaults
/// m = a = 1, A = 0.25, g = 9.81): 0.6977163994188339 at p = 1 (t* =
/// 0.7868003501703082), −1.0635832141321968 at p = 2 (t* = 0.4630139300288331).
#[test]
fn s3_sub2_is_proved_with_its_tangent_case() {
    let r = expect("S3.sub2", Verdict::Conditional);
    assert_eq!(r.witness["balance"]["identity"], "proved");
    assert_eq!(r.witness["slope"]["identity"], "proved");
    for (i, (gmin, tstar)) in [
        (0.6977163994188339, 0.7868003501703082),
        (-1.0635832141321968, 0.4630139300288331),
    ]
    .into_iter()
    .enumerate()
    {
        let m = &r.witness["min_G"][i];
        let (g, t) = (&m["min_G"], &m["t_star"]);
        assert!(num(&g[0]) <= gmin && gmin <= num(&g[1]), "{g}");
        assert!(num(&g[1]) - num(&g[0]) < 1e-6, "{g}");
        assert!(num(&t[0]) <= tstar && tstar <= num(&t[1]), "{t}");
    }
    assert!(r
        .correction
        .as_deref()
        .unwrap()
        .contains("one degenerate equilibrium"));
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
    // a typo: U₀/V₀, hence N, (3.5) and Ω₀, are right
    let r = expect("F3.4", Verdict::Typo);
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

// ---------------------------------------------------------------- Λ̈ = U + V N

/// An exact rational from "p/q" or an integer text.
fn q(text: &str) -> rug::Rational {
    text.parse()
        .unwrap_or_else(|_| panic!("not a rational: {text}"))
}

fn ratio(n: i64, d: i64) -> rug::Rational {
    rug::Rational::from((n, d))
}

/// The report reads Λ̈ = U + V N with N a free force (V = ∂Λ̈/∂N). Each check
/// that names U or V shows them at a stated point; here they are recomputed
/// by hand from the closed forms of that reading. Under the other reading
/// (θ̈ from the contact equations) the coefficient of N is 1/m = 1 at the
/// defaults, which none of these values equals.
#[test]
fn u_and_v_are_read_one_way_in_every_check() {
    // Example 1, defaults (a, b, m, C, μ, g) = (1, 0.5, 1, 0.3, 0.8, 9.81), θ = 0,
    // θ̇ = 1: h = 1, h' = b = 1/2, h'' = 0.
    // V = 1/m + h'²/C = 1 + (1/4)/(3/10) = 11/6; U = μh²h'θ̇/C − g − h''θ̇² = 4/3 − 981/100.
    let r = expect("F1.9", Verdict::Error);
    let rd = &r.witness["reading"];
    assert_eq!(q(rd["V"].as_str().unwrap()), ratio(11, 6));
    assert_eq!(q(rd["U"].as_str().unwrap()), ratio(4, 3) - ratio(981, 100));
    // the printed coefficient of N is 1/m: the other reading
    assert_eq!(q(rd["printed_V"].as_str().unwrap()), 1);

    // §2, defaults (m, a, A, p_φ, p_ψ) = (1, 1, 1/4, 5/2, 2), sin θ = 4/5,
    // cos θ = 3/5, θ̇ = 1: V = 1/m + a²cos²θ/A = 1 + (9/25)·4 = 61/25;
    // τ = (2 − 3/2)/(1/5) = 5/2, τ' = (5/2 − 6/5)/(4/25) = 65/8,
    // U = −g + aθ̇² sin θ + aττ' cos θ = −981/100 + 4/5 + 195/16 = 1271/400.
    for id in ["F2.6", "F2.7"] {
        let r = expect(id, Verdict::Confirmed);
        let rd = &r.witness["reading"];
        assert_eq!(q(rd["V"].as_str().unwrap()), ratio(61, 25), "{id}");
        assert_eq!(q(rd["U"].as_str().unwrap()), ratio(1271, 400), "{id}");
    }
    // θ̈ of (2.5) substituted first gives U·A/(A + m a² cos²θ) = U/(mV) = 1271/976
    // a typo: the factor A/(A + m a² cos²θ) > 0 changes none of Ω, Ω₀, N
    let r = expect("F2.6route", Verdict::Typo);
    let shown = &r.witness["route_2_5_vs_U"];
    assert_eq!(q(shown["derived"].as_str().unwrap()), ratio(1271, 400));
    assert_eq!(
        q(shown["printed"].as_str().unwrap()),
        ratio(1271, 400) * ratio(25, 61)
    );

    // §3, same point, v_x = 1: V₀ = 1/m + a²cos²θ/(A + m a² sin²θ)
    // = 1 + (9/25)/(1/4 + 16/25) = 1 + 36/89 = 125/89.
    let r = expect("F3.4", Verdict::Typo);
    let rd = &r.witness["identity"]["reading"];
    assert_eq!(q(rd["V"].as_str().unwrap()), ratio(125, 89));
    assert_eq!(q(rd["printed_V"].as_str().unwrap()), 1);
}

/// The header defines every verdict and every strength, and reads U and V
/// per section: U decides Ω₀, and is the paper's Ω only in §2; V is
/// ∇Λ·M⁻¹∇Λ in §1 and §2, and the blade changes it in §3.
#[test]
fn report_defines_every_verdict_and_strength_and_u_v_per_section() {
    let md = claims::report::markdown(&claims::run(&["F1.3".into()]).unwrap());
    let head = &md[..md.find("| id |").unwrap()];
    for v in claims::Verdict::ALL {
        assert!(head.contains(&format!("| {v} | {} |", v.meaning())), "{v}");
    }
    for s in claims::Strength::ALL {
        assert!(head.contains(&format!("| {s} | {} |", s.meaning())), "{s}");
    }
    for s in [
        "the sign of U decides Ω₀",
        "that is U only on the smooth plane of §2",
        "V₀ = 1/m + a²cos²θ/(A + m a² sin²θ)",
    ] {
        assert!(head.contains(s), "{s} missing from the header");
    }
    assert!(
        !head.contains("(the paper's Ω)"),
        "U is not the paper's Ω in §1 and §3"
    );
}

/// Ω̄ ∩ Ω₀ of Example 1 is not empty: a certified box. Independent check at
/// its centre in f64 from the closed forms g_Ω = b θ̇² sin θ − g > 0 and
/// g_Ω₀ = μh²bθ̇ cos θ + C g_Ω < 0 (defaults a = 1, b = 0.5, C = 0.3, μ = 0.8).
#[test]
fn example_1_has_a_certified_point_of_nonuniqueness() {
    let r = expect("S1.nonunique", Verdict::Confirmed);
    let b = &r.witness["witness"]["box"];
    let t = 0.5 * (num(&b["theta"][0]) + num(&b["theta"][1]));
    let w = 0.5 * (num(&b["theta_dot"][0]) + num(&b["theta_dot"][1]));
    let h = 1.0 + 0.5 * t.sin();
    let g_omega = 0.5 * w * w * t.sin() - 9.81;
    let g_omega0 = 0.8 * h * h * 0.5 * w * t.cos() + 0.3 * g_omega;
    assert!(g_omega > 0.0 && g_omega0 < 0.0, "{g_omega} {g_omega0}");
}

/// The abstract's "checking only N ≥ 0 leads to wrong conclusions" rests on
/// certified points of Ω₀ outside Ω (S3.sub2's equilibrium, S1.nonunique).
#[test]
fn checking_only_n_is_shown_wrong_by_certified_points() {
    let r = expect("A.onlyN", Verdict::Confirmed);
    assert!(r.summary.contains("outside Ω"), "{}", r.summary);
    assert_eq!(r.witness["in_omega0_identity"]["identity"], "proved");
}

/// "(reversing the OZ axis)": reversing OZ reverses v_x and breaks (3.3);
/// the symmetry is a vertical mirror with the disc's axis reversed. The
/// exact difference of (3.3) is recomputed here by hand at sin θ = 4/5,
/// cos θ = 3/5, v_x = 1 and the defaults (m = a = 1, A = 1/4, p_φ = 5/2,
/// p_ψ = 2, g = 981/100).
#[test]
fn reversing_oz_is_not_the_symmetry() {
    let r = expect("S3.symOZ", Verdict::False);
    assert_eq!(r.witness["reversing_OZ_image"]["identity"], "proved");
    assert_eq!(
        r.witness["mirror_and_axis_flip_image"]["identity"],
        "proved"
    );
    let d = &r.witness["theta_ddot_3_3_under_reversing_OZ"];
    assert_eq!(d["identity"], "differ");
    // θ̈ = (−g·3/5 + τ − ττ'/4)·4/5 with τ = 5/2, τ' = 65/8; minus θ̈ at the
    // image (τ → −5/2, τ' kept, cos → −cos, v_x → −1) is −(g·3/5 + 5/2 +
    // (5/2)(65/8)/4)·4/5: they differ by 2·(5/2)·4/5 = 4 (the v_x τ term).
    let tau_tau1: rug::Rational = ratio(5, 2) * ratio(65, 8) / 4;
    let at = (ratio(-981, 100) * ratio(3, 5) + ratio(5, 2) - tau_tau1.clone()) * ratio(4, 5);
    let image = -((ratio(981, 100) * ratio(3, 5) + ratio(5, 2) + tau_tau1) * ratio(4, 5));
    assert_eq!(q(d["printed"].as_str().unwrap()), at);
    assert_eq!(q(d["derived"].as_str().unwrap()), image);
}

#[test]
fn report_names_the_paper_and_the_reading() {
    let md = claims::report::markdown(&claims::run(&["F1.3".into()]).unwrap());
    let head = &md[..md.find("| id |").unwrap()];
    for s in [
        "A. P. Ivanov",
        "Geometric representation of detachment conditions",
        "Nelineinaya Dinamika",
        "2008",
        "Λ̈ = U + V N",
        "N is a free force",
    ] {
        assert!(head.contains(s), "{s} missing from the header");
    }
}

// ---------------------------------------------------------------- added claims

#[test]
fn integrals_and_energy_theorems_confirmed() {
    for id in ["F1.6", "F2.11", "S2.integrals", "S3.integrals"] {
        expect(id, Verdict::Confirmed);
    }
}

#[test]
fn contact_without_detachment_lies_in_omega_and_omega0() {
    let r = expect("S1.contact", Verdict::Confirmed);
    // rest at θ = −π/2 (h' = 0): N = m g = 981/100, free-flight Λ̈ = −g
    let e = &r.witness["equilibrium_theta=-pi/2"];
    assert_eq!(q(e["N"].as_str().unwrap()), ratio(981, 100));
    assert_eq!(
        q(e["free_flight_lambda_ddot"].as_str().unwrap()),
        ratio(-981, 100)
    );
}

#[test]
fn the_reduction_to_nonnegative_momenta_needs_time_reversal() {
    // true with a step the paper leaves out (the time reversal): confirmed
    let r = expect("S3.symreduce", Verdict::Confirmed);
    assert!(
        r.summary.contains("a step the paper leaves out"),
        "{}",
        r.summary
    );
    assert_eq!(r.witness["time_reversal"]["identity"], "proved");
    // p_φ → −p_φ at sin θ = 4/5, cos θ = 3/5, v_x = 1 (defaults):
    // τ = 5/2 → (2 + 3/2)/(1/5) = 35/2, τ' = 65/8 → (−5/2 − 6/5)/(4/25) = −185/8;
    // (A + m a²)θ̈ = −g·3/5 + v_x τ − ττ'/4, A + m a² = 5/4.
    let th = |tau: rug::Rational, tau1: rug::Rational| {
        (ratio(-981, 100) * ratio(3, 5) + tau.clone() - tau * tau1 / 4) * ratio(4, 5)
    };
    let s = &r.witness["p_phi_sign_alone"];
    assert_eq!(
        q(s["printed"].as_str().unwrap()),
        th(ratio(5, 2), ratio(65, 8))
    );
    assert_eq!(
        q(s["derived"].as_str().unwrap()),
        th(ratio(35, 2), ratio(-185, 8))
    );
}

#[test]
fn subcase_3_portraits_against_fig_4() {
    let (got, r) = v("S3.sub3fig", false);
    assert_eq!(got, Verdict::ConfirmedOn, "{}", r.summary);
    assert_eq!(r.witness["undecided_samples"], 0);
    // subcase 2 (p_ψ = p_φ) has 0 or 2 equilibria: not a portrait of Fig. 4
    let (m, mr) = v("S3.sub3fig", true);
    assert_eq!(m, Verdict::False, "{}", mr.summary);
}

/// The band proof's α-box count, read from the committed proof file.
#[test]
fn s2_case3_states_the_boxes_its_proof_covers() {
    let text = std::fs::read_to_string("proofs/critical-band.json").unwrap();
    let proof: Value = serde_json::from_str(&text).unwrap();
    let cells = proof["statement"]["cells"].as_array().unwrap().len();
    let r = expect("S2.case3", Verdict::Confirmed);
    assert_eq!(r.witness["band_proof_alpha_boxes"], cells);
    assert!(
        r.summary.contains(&format!("covers {cells} α-boxes")),
        "{}",
        r.summary
    );
}

/// Differences are shown at short points (decimal parameters, rational
/// sin θ, cos θ, small rates), not at the identity tests' random rationals.
#[test]
fn differences_are_shown_at_short_points() {
    fn points<'a>(v: &'a Value, out: &mut Vec<&'a Value>) {
        match v {
            Value::Object(m) => {
                for (k, x) in m {
                    if k == "point" {
                        out.push(x);
                    }
                    points(x, out);
                }
            }
            Value::Array(a) => a.iter().for_each(|x| points(x, out)),
            _ => {}
        }
    }
    for r in claims::run(&[]).unwrap() {
        let mut found = Vec::new();
        points(&r.witness, &mut found);
        for p in found {
            let text = p.to_string();
            for value in text.split(['"', ',', ':', '{', '}']) {
                let digits = value.chars().filter(|c| c.is_ascii_digit()).count();
                assert!(digits <= 5, "{}: long value {value} in {text}", r.id);
            }
        }
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
