//! Certified equilibria and singular points (`detach singular`) against
//! independent references: closed forms evaluated with MPFR at 256 bits
//! (derived in `tests/data/painleve_singular.py`), mpmath roots, and small
//! scenes whose points are known exactly.

use crate::common::{assert_bad_input, detach, json};
use detach::api::{ParamRequest, Problem, Variant};
use detach::inari::Interval;
use detach::motion::singular::{
    find, scan, Direction, Options, Point, PointKind, PointType, Report, ScanOptions,
};
use rug::ops::Pow;
use rug::Float;

const BITS: u32 = 256;

fn f(x: f64) -> Float {
    Float::with_val(BITS, x)
}

/// A decimal text exactly, at 256 bits.
fn dec(t: &str) -> Float {
    Float::with_val(BITS, Float::parse(t).unwrap())
}

fn contains(x: Interval, v: &Float) -> bool {
    *v >= x.inf() && *v <= x.sup()
}

fn run(name: &str, params: &[(&str, &str)]) -> Report {
    let p = Problem::load(name, params).unwrap();
    find(
        p.scene.reading(Variant::Derived),
        &p.scene.domain(),
        &Options::default(),
    )
    .unwrap()
}

fn of_kind(r: &Report, kind: PointKind) -> Vec<&Point> {
    r.points.iter().filter(|p| p.kind == kind).collect()
}

/// The rod's singular points at friction `mu` (l = 1, g = 9.81): tan θ =
/// (3μ ∓ √(9μ² − 16))/2, θ̇ = ±√(g/(l sin θ)); eigenvalues of the
/// triangular DG: λ₁ = l V'(θ) θ̇ (across), λ₂ = 6 l sin θ θ̇ (cos θ − μ sin θ)
/// (along). Returned as (θ, θ̇, λ₁, λ₂, lower root).
fn rod_points(mu: &str) -> Vec<[Float; 4]> {
    let (mu, g, l) = (dec(mu), dec("9.81"), dec("1"));
    let disc = (Float::with_val(BITS, 9) * mu.clone().pow(2u32) - 16u32).sqrt();
    let mut out = Vec::new();
    for sign in [-1i32, 1] {
        let t: Float = (Float::with_val(BITS, 3) * &mu + disc.clone() * sign) / 2u32;
        let th = t.atan();
        let (s, c) = (th.clone().sin(), th.clone().cos());
        for ws in [1i32, -1] {
            let w = (g.clone() / (l.clone() * &s)).sqrt() * ws;
            // V' = -6 sin cos - 3 μ (cos² - sin²)
            let dv = Float::with_val(BITS, -6) * &s * &c
                - Float::with_val(BITS, 3) * &mu * (c.clone().pow(2u32) - s.clone().pow(2u32));
            let l1 = l.clone() * dv * &w;
            let l2 = Float::with_val(BITS, 6) * &l * &s * &w * (c.clone() - mu.clone() * &s);
            out.push([th.clone(), w, l1, l2]);
        }
    }
    out
}

#[test]
fn the_rod_at_mu_1_5_has_four_singular_points_of_the_derived_types() {
    let r = run("painleve-rod", &[("mu", "1.5")]);
    assert!(r.undecided.is_empty(), "{:?}", r.undecided);
    let sing = of_kind(&r, PointKind::Singular);
    assert_eq!(sing.len(), 4);
    for (i, [th, w, l1, l2]) in rod_points("1.5").iter().enumerate() {
        let p = sing
            .iter()
            .find(|p| contains(p.theta, th) && contains(p.theta_dot, w))
            .unwrap_or_else(|| panic!("closed form {i} ({th}, {w}) not enclosed"));
        assert!(p.theta.wid() < 1e-9 && p.theta_dot.wid() < 1e-9);
        // Lower root of V: a node, stable for θ̇ > 0 (both eigenvalues
        // have the sign of -θ̇); upper root: a saddle.
        let expected = match (i < 2, *w > 0) {
            (true, true) => PointType::StableNode,
            (true, false) => PointType::UnstableNode,
            (false, _) => PointType::Saddle,
        };
        assert_eq!(p.point_type, expected, "point {i}");
        let e = p.eigenvalues.expect("real eigenvalues");
        assert!(
            contains(e[0], l1) && contains(e[1], l2),
            "{e:?} vs {l1}, {l2}"
        );
        assert_eq!(p.directions, Some([Direction::Across, Direction::Along]));
        // |λ₁| = 7.34 < |λ₂| = 8.69 at the node (mpmath, painleve_singular.py).
        if i < 2 {
            assert_eq!(p.slow_direction(), Some(Direction::Across));
        }
    }
    // One equilibrium, tan θ = 1/μ (where V = 1): a saddle, eigenvalues
    // ±√(3 g √(1 + μ²)/l).
    let eq = of_kind(&r, PointKind::Equilibrium);
    assert_eq!(eq.len(), 1);
    let th = (Float::with_val(BITS, 1) / dec("1.5")).atan();
    assert!(contains(eq[0].theta, &th));
    assert_eq!(eq[0].point_type, PointType::Saddle);
    let lam = (Float::with_val(BITS, 3) * dec("9.81") * (dec("1") + dec("2.25")).sqrt()).sqrt();
    let e = eq[0].eigenvalues.unwrap();
    assert!(contains(e[0], &(-lam.clone())) && contains(e[1], &lam));
}

#[test]
fn the_rod_below_four_thirds_has_no_singular_point() {
    let r = run("painleve-rod", &[("mu", "1.3")]);
    assert!(r.quotient);
    assert!(r.undecided.is_empty(), "{:?}", r.undecided);
    assert!(of_kind(&r, PointKind::Singular).is_empty());
    assert_eq!(of_kind(&r, PointKind::Equilibrium).len(), 1);
}

#[test]
fn the_frictionless_rod_stands_on_an_upright_saddle() {
    // μ = 0: F(θ, 0) = -3 g cos θ/(l (1 + 3 cos² θ)), zero at θ = π/2 (the
    // domain's end); F_θ(π/2, 0) = 3 g/l, eigenvalues ±√(3 g/l).
    let r = run("painleve-rod", &[("mu", "0")]);
    assert!(r.undecided.is_empty(), "{:?}", r.undecided);
    assert_eq!(r.points.len(), 1);
    let p = &r.points[0];
    let half_pi = Float::with_val(BITS, rug::float::Constant::Pi) / 2u32;
    assert!(contains(p.theta, &half_pi) && p.theta_dot == Interval::try_from((0.0, 0.0)).unwrap());
    assert_eq!(p.point_type, PointType::Saddle);
    let lam = (Float::with_val(BITS, 3) * dec("9.81")).sqrt();
    let e = p.eigenvalues.unwrap();
    assert!(contains(e[0], &(-lam.clone())) && contains(e[1], &lam));
}

#[test]
fn the_smooth_disc_has_one_equilibrium_a_centre_at_the_root_of_eq_2_12() {
    // The root of `[functions] eq_2_12` on (0, π) at the defaults, by
    // mpmath (dps 40, sign scan on a 2000-point grid then findroot):
    // 0.4460700859846712685159299782157744168351, derivative 6.238 > 0, so
    // Π̃'' > 0 there: a minimum of the effective potential.
    let root = dec("0.4460700859846712685159299782157744168351");
    let p = Problem::load("smooth-disc", &[]).unwrap();
    let domain = p
        .scene
        .domain()
        .window(Some(["0.01", "3.13"]), None)
        .unwrap();
    let r = find(
        p.scene.reading(Variant::Derived),
        &domain,
        &Options::default(),
    )
    .unwrap();
    assert!(r.undecided.is_empty(), "{:?}", r.undecided);
    assert_eq!(r.points.len(), 1);
    assert!(contains(r.points[0].theta, &root));
    // F depends on θ̇ only through θ̇²: reversible, so a proved centre.
    assert_eq!(r.points[0].point_type, PointType::Centre);
    // Over the whole domain the ends θ = 0, π (where F is not defined)
    // stay undecided, and nothing else.
    let whole = run("smooth-disc", &[]);
    assert_eq!(whole.points.len(), 1);
    assert!(contains(whole.points[0].theta, &root));
    assert!(!whole.undecided.is_empty());
    for u in &whole.undecided {
        assert!(u.theta.sup() < 1e-6 || u.theta.inf() > 3.1, "{u:?}");
    }
}

const TOY: &str = r#"
name = "toy"
[domain]
theta = ["-4", "4"]
theta_dot = ["-5", "5"]
[parameters]
c = "3"
[regions]
omega = "theta - 10 < 0"
omega0 = "theta - 10 < 0"
[dynamics]
theta_ddot = "THETA_DDOT"
"#;

fn toy(theta_ddot: &str) -> Report {
    let text = TOY.replace("THETA_DDOT", theta_ddot);
    let p = Problem::from_toml(&text, "toy.toml", &[]).unwrap();
    find(
        p.scene.reading(Variant::Derived),
        &p.scene.domain(),
        &Options::default(),
    )
    .unwrap()
}

/// Catches a wrong sign of the g_θ̇ θ̇ term of DG and a trace of the wrong
/// sign: F = (1 − θ)/(θ̇ + θ − c), g depends on θ̇. The singular point is
/// (1, 2); there g = 0, DG = [[g_θ θ̇, g_θ̇ θ̇ + g], [f_θ, f_θ̇]] = [[2, 2],
/// [−1, 0]]: det 2, trace 2, discriminant −4 — an unstable focus
/// (eigenvalues 1 ± i). With +g_θ̇ θ̇ negated, det = −2 (a saddle); with the
/// trace negated, a stable focus.
#[test]
fn a_theta_dot_dependent_denominator_gives_an_unstable_focus() {
    let r = toy("(1 - theta)/(theta_dot + theta - c)");
    assert!(r.undecided.is_empty(), "{:?}", r.undecided);
    let s = of_kind(&r, PointKind::Singular);
    assert_eq!(s.len(), 1);
    assert!(contains(s[0].theta, &f(1.0)) && contains(s[0].theta_dot, &f(2.0)));
    assert_eq!(s[0].point_type, PointType::UnstableFocus);
    assert_eq!(s[0].eigenvalues, None);
    // The equilibrium (1, 0): g = −2, F_θ = −1/g = 1/2, F_θ̇ = 0: a saddle
    // with eigenvalues ±√(1/2) (not reversible: θ̇ enters linearly).
    let e = of_kind(&r, PointKind::Equilibrium);
    assert_eq!(e.len(), 1);
    assert_eq!(e[0].point_type, PointType::Saddle);
    let l = Float::with_val(BITS, 0.5).sqrt();
    let ev = e[0].eigenvalues.unwrap();
    assert!(contains(ev[0], &(-l.clone())) && contains(ev[1], &l));
}

#[test]
fn pendulums_give_centres_foci_nodes_and_saddles() {
    // θ̈ = −sin θ on [−4, 4]: centre at 0, saddles at ±π (eigenvalues ±1).
    let r = toy("-sin(theta)");
    assert!(r.undecided.is_empty() && !r.quotient);
    assert_eq!(r.points.len(), 3);
    let pi = Float::with_val(BITS, rug::float::Constant::Pi);
    for p in &r.points {
        if contains(p.theta, &f(0.0)) {
            assert_eq!(p.point_type, PointType::Centre);
        } else {
            assert!(contains(p.theta, &pi) || contains(p.theta, &(-pi.clone())));
            assert_eq!(p.point_type, PointType::Saddle);
            let e = p.eigenvalues.unwrap();
            assert!(contains(e[0], &f(-1.0)) && contains(e[1], &f(1.0)));
        }
    }
    // Light damping: trace −1/2, det 1: a stable focus; never a centre.
    let r = toy("-sin(theta) - theta_dot/2");
    let at0 = r
        .points
        .iter()
        .find(|p| contains(p.theta, &f(0.0)))
        .unwrap();
    assert_eq!(at0.point_type, PointType::StableFocus);
    // Anti-damping: an unstable focus.
    let r = toy("-sin(theta) + theta_dot/2");
    let at0 = r
        .points
        .iter()
        .find(|p| contains(p.theta, &f(0.0)))
        .unwrap();
    assert_eq!(at0.point_type, PointType::UnstableFocus);
    // Heavy damping: eigenvalues (−3 ∓ √5)/2, a stable node; the slower
    // one is (−3 + √5)/2.
    let r = toy("-sin(theta) - c*theta_dot");
    let at0 = r
        .points
        .iter()
        .find(|p| contains(p.theta, &f(0.0)))
        .unwrap();
    assert_eq!(at0.point_type, PointType::StableNode);
    let s5 = Float::with_val(BITS, 5).sqrt();
    let e = at0.eigenvalues.unwrap();
    assert!(contains(e[0], &((f(-3.0) - s5.clone()) / 2u32)));
    assert!(contains(e[1], &((f(-3.0) + s5) / 2u32)));
    assert_eq!(at0.slower, Some(1));
}

/// The rod's scan over `range` at a resolution of `2^-log2_eps` of it.
fn rod_scan(range: &str, log2_eps: i32) -> detach::motion::singular::Scan {
    let p = Problem::load("painleve-rod", &[]).unwrap();
    let family = p.family(vec![ParamRequest::axis(range).unwrap()]).unwrap();
    let opts = ScanOptions {
        eps: 2f64.powi(-log2_eps),
        ..ScanOptions::default()
    };
    scan(&family, &p.scene.domain(), &opts).unwrap()
}

#[test]
fn the_rod_thresholds_enclose_four_thirds_and_eight_over_three_root_three() {
    // μ_c = 8/(3√3): where |λ₁| = |λ₂| at the node; 27μ⁴ − 37μ² − 64 =
    // (μ² + 1)(27μ² − 64) (painleve_singular.py).
    let mu_c =
        Float::with_val(BITS, 8) / (Float::with_val(BITS, 3) * Float::with_val(BITS, 3).sqrt());
    // Resolutions coarse enough to be quick, fine enough that each width
    // bound below holds (the enclosures are 5.5e-5 and 4.8e-4 wide).
    let s = rod_scan("mu=1.4:1.7", 14);
    assert_eq!(s.thresholds.len(), 1, "{:?}", s.thresholds);
    let t = &s.thresholds[0];
    assert!(t.lo <= mu_c && mu_c <= t.hi, "[{}, {}]", t.lo, t.hi);
    assert!(t.width() < 1e-4, "width {}", t.width());
    let slow = |v: &[String], d: &str| {
        v.iter()
            .filter(|x| x.contains("node") && x.ends_with(&format!("slow {d}")))
            .count()
    };
    assert_eq!(slow(&t.below, "across"), 2);
    assert_eq!(slow(&t.above, "along"), 2);

    let four_thirds = Float::with_val(BITS, 4) / 3u32;
    let s = rod_scan("mu=1.2:1.45", 10);
    assert_eq!(s.thresholds.len(), 1, "{:?}", s.thresholds);
    let t = &s.thresholds[0];
    assert!(
        t.lo <= four_thirds && four_thirds <= t.hi,
        "[{}, {}]",
        t.lo,
        t.hi
    );
    assert!(t.width() < 1e-2, "width {}", t.width());
    assert_eq!(t.below, vec!["equilibrium saddle".to_string()]);
    assert_eq!(t.above.len(), 5);
}

#[test]
fn the_command_line_prints_the_points_as_json_and_refuses_bad_input() {
    let doc = json(&["singular", "--scene", "painleve-rod", "--json"]);
    let points = doc["points"].as_array().unwrap();
    assert_eq!(points.len(), 5);
    assert_eq!(doc["undecided"], 0);
    let sing: Vec<_> = points.iter().filter(|p| p["kind"] == "singular").collect();
    assert_eq!(sing.len(), 4);
    for p in &sing {
        let lo: f64 = p["theta"][0].as_str().unwrap().parse().unwrap();
        let hi: f64 = p["theta"][1].as_str().unwrap().parse().unwrap();
        assert!(lo <= hi && lo > 0.88 && hi < 1.28);
        assert_eq!(p["unique"], true);
        assert_eq!(p["eigenvalues"].as_array().unwrap().len(), 2);
    }
    assert_bad_input(&["singular", "--scene", "brick"], "unknown scene `brick`");
    assert_bad_input(
        &["singular", "--scene", "painleve-rod", "--theta", "1"],
        "LO:HI",
    );
    assert_bad_input(
        &["singular", "--scene", "painleve-rod", "--x", "mu=2:1"],
        "empty",
    );
    assert_bad_input(
        &["singular", "--scene-file", "tests/data/vertical-line.toml"],
        "no [dynamics]",
    );
    let out = detach(&["singular", "--scene", "painleve-rod", "--param", "mu=1.3"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("equilibrium"));
}
