//! Certified roots against independent references: closed forms, the
//! tan-half-angle polynomial, the θ → π − θ symmetry, f64 scans.

use detach::inari::{const_interval, Interval};
use detach::number::param::enclose_decimal;
use detach::number::scalar::Scalar;
use detach::roots::cluster::bound_cluster;
use detach::roots::equations::{eq_2_10, eq_2_9, Eq29TanHalf};
use detach::roots::isolate::point;
use detach::roots::{
    isolate, prove_kappa0, solve_2_10, solve_2_12, solve_2_9, Budget, EquationRoots, RealFn,
    RootStatus,
};
use detach::scene::file::Function;
use detach::scene::{Scene, SceneId};
use proptest::prelude::*;

fn dec(t: &str) -> Interval {
    enclose_decimal("x", t).unwrap()
}

/// Roots of μ³ − μ + 2κ = 0 by the trigonometric (Viète) formula,
/// μ_k = (2/√3) cos(φ/3 − 2πk/3), cos φ = −3√3 κ, evaluated in intervals.
fn viete(kappa: Interval) -> Vec<Interval> {
    let three = const_interval!(3.0, 3.0);
    let s3 = three.sqrt();
    let phi = (-(three * s3 * kappa)).acos();
    (0..3)
        .map(|k| {
            let shift = const_interval!(2.0, 2.0) * Interval::PI * point(k as f64) / three;
            const_interval!(2.0, 2.0) / s3 * (phi / three - shift).cos()
        })
        .filter(|m| m.sup() > 0.0)
        .collect()
}

#[test]
fn eq_2_10_matches_the_trigonometric_closed_form() {
    for t in ["0.001", "0.05", "0.1", "0.15", "0.19", "0.1924"] {
        let k = dec(t);
        let r = solve_2_10(k, &Budget::default()).unwrap();
        assert!(r.complete, "κ = {t}");
        let refs = viete(k);
        assert_eq!(refs.len(), 2, "κ = {t}: {refs:?}");
        assert_eq!(r.roots.len(), 2);
        for root in &r.roots {
            let hits = refs.iter().filter(|x| !x.disjoint(root.interval())).count();
            assert_eq!(hits, 1, "κ = {t}: {root:?} vs {refs:?}");
        }
    }
    // above κ₀: the closed form has one (negative) real root; no positive root.
    let r = solve_2_10(dec("0.1925"), &Budget::default()).unwrap();
    assert!(r.complete && r.roots.is_empty());
}

#[test]
fn eq_2_9_at_alpha_one_is_eq_2_10_in_tan_half() {
    // Paper §2 case 2: with α = 1, μ = tan(θ/2) solves (2.10).
    for t in ["0.02", "0.1", "0.19"] {
        let k = dec(t);
        let th = solve_2_9(k, dec("1"), &Budget::default()).unwrap();
        let mu = solve_2_10(k, &Budget::default()).unwrap();
        assert!(th.complete && mu.complete);
        assert_eq!(th.roots.len(), mu.roots.len());
        for (a, b) in th.roots.iter().zip(&mu.roots) {
            let s = (a.interval() / const_interval!(2.0, 2.0)).tan();
            assert!(!s.disjoint(b.interval()), "{a:?} {b:?}");
        }
    }
}

#[test]
fn kappa_near_kappa0_on_both_sides_at_alpha_one() {
    let below = solve_2_9(dec("0.19245"), dec("1"), &Budget::default()).unwrap();
    assert!(below.complete && below.roots.len() == 2);
    let above = solve_2_9(dec("0.19246"), dec("1"), &Budget::default()).unwrap();
    assert!(above.complete && above.roots.is_empty());
}

#[test]
fn negative_alpha_mirrors_theta() {
    // (2.9) is invariant under θ → π − θ, α → −α (paper §2 case 4).
    for (k, a, na) in [("0.05", "0.7", "-0.7"), ("0.1", "0.95", "-0.95")] {
        let p = solve_2_9(dec(k), dec(a), &Budget::default()).unwrap();
        let n = solve_2_9(dec(k), dec(na), &Budget::default()).unwrap();
        assert!(p.complete && n.complete);
        assert_eq!(p.roots.len(), n.roots.len());
        for (x, y) in p.roots.iter().zip(n.roots.iter().rev()) {
            assert!(!(Interval::PI - x.interval()).disjoint(y.interval()));
        }
    }
}

#[test]
fn kappa0_contains_sqrt3_over_9_two_ways() {
    let proof = prove_kappa0();
    assert!(proof.all_proved());
    let k0 = proof.kappa0.interval();
    // inari: √3/9 in intervals
    let s = point(3.0).sqrt() / point(9.0);
    assert!(!s.disjoint(k0));
    // 40-digit decimal of √3/9 (bc -l), enclosed by its two neighbouring doubles
    let d = dec("0.1924500897298752548363829268339858185492");
    assert!(d.subset(k0));
    assert!(proof.kappa0_width_ulps <= 4);
}

#[test]
fn stationary_point_of_the_default_disc_matches_an_f64_scan() {
    // Independent: f64 sign scan + bisection of Π̃' (uncertified baseline).
    let disc = Scene::default_of(SceneId::SmoothDisc);
    let eq =
        detach::roots::equations::scene_function(&disc, detach::roots::EquationId::E2_12).unwrap();
    let r = solve_2_12(eq, &Budget::default());
    assert!(r.complete);
    // Π̃' = m g a cos θ + A τ τ' (2.12) at the defaults m = a = 1, A = 0.25,
    // g = 9.81, p_φ = 2.5, p_ψ = 2, written here in f64.
    let f = |x: f64| {
        let (s, c) = x.sin_cos();
        let tau = (2.0 - 2.5 * c) / (0.25 * s);
        let tau1 = (2.5 - 2.0 * c) / (0.25 * s * s);
        9.81 * c + 0.25 * tau * tau1
    };
    let n = 20_000;
    let mut found = Vec::new();
    for i in 1..n {
        let (a, b) = (
            std::f64::consts::PI * i as f64 / n as f64,
            std::f64::consts::PI * (i + 1) as f64 / n as f64,
        );
        if f(a).signum() != f(b).signum() && b < std::f64::consts::PI {
            let (mut lo, mut hi) = (a, b);
            for _ in 0..60 {
                let m = 0.5 * (lo + hi);
                if f(m).signum() == f(lo).signum() {
                    lo = m
                } else {
                    hi = m
                }
            }
            found.push(0.5 * (lo + hi));
        }
    }
    assert_eq!(found.len(), r.roots.len());
    for (x, root) in found.iter().zip(&r.roots) {
        assert!(
            (root.lo - 1e-12..=root.hi + 1e-12).contains(x),
            "{x} {root:?}"
        );
    }
}

/// Certified sign of f at a point: Some(±1) or None if the enclosure has 0.
fn sign_at<F: RealFn>(f: &F, x: f64) -> Option<i8> {
    let y = f.eval(point(x));
    if y.inf() > 0.0 {
        Some(1)
    } else if y.sup() < 0.0 {
        Some(-1)
    } else {
        None
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Every unique enclosure holds a certified sign change (at its endpoints,
    /// widened by at most 1e-10 where rounding hides the sign); gaps between
    /// enclosures keep one sign at sampled points; unique roots are disjoint
    /// and lie in the searched domain; the tan-half form finds the same count.
    #[test]
    fn unique_roots_hold_sign_changes_and_gaps_keep_their_sign(
        k_milli in 1u32..400, a_milli in -1000i32..=1000,
    ) {
        let (kt, at) = (format!("{}e-3", k_milli), format!("{}e-3", a_milli));
        let (k, a) = (dec(&kt), dec(&at));
        let r = solve_2_9(k, a, &Budget::default()).unwrap();
        let f = eq_2_9(k, a);
        for w in r.roots.windows(2) {
            prop_assert!(w[0].hi <= w[1].lo);
        }
        for root in &r.roots {
            prop_assert!(r.searched[0] <= root.lo && root.hi <= r.searched[1]);
            if root.status != RootStatus::Unique { continue; }
            let ok = [0.0, 1e-14, 1e-12, 1e-10].iter().any(|&w| {
                matches!((sign_at(&f, root.lo - w), sign_at(&f, root.hi + w)),
                    (Some(x), Some(y)) if x != y)
            });
            prop_assert!(ok, "no sign change across {:?} for κ={} α={}", root, kt, at);
        }
        // gaps between enclosures (and the domain ends) keep one sign
        let mut edges = vec![r.searched[0]];
        for root in &r.roots { edges.push(root.lo); edges.push(root.hi); }
        edges.push(r.searched[1]);
        for g in edges.chunks(2) {
            let (lo, hi) = (g[0], g[1]);
            let signs: Vec<i8> = (0..=64)
                // lo + (hi − lo) can round above hi: keep samples in the gap.
                .map(|i| (lo + (hi - lo) * i as f64 / 64.0).min(hi))
                .filter_map(|x| sign_at(&f, x))
                .collect();
            prop_assert!(signs.windows(2).all(|w| w[0] == w[1]),
                "sign change inside a root-free gap [{}, {}]", lo, hi);
        }
        if r.complete {
            let p = isolate(&Eq29TanHalf { kappa: k, alpha: a }, 1e-6, 1e6, &Budget::default());
            if p.complete {
                prop_assert_eq!(p.roots.len(), r.roots.len());
            }
        }
    }
}

/// 1/√3, the double root of (2.10) at κ = κ₀ (closed form: p'(μ) = 1 − 3μ² = 0).
fn inv_sqrt3() -> Interval {
    point(1.0) / point(3.0).sqrt()
}

/// The one cluster of an incomplete result near κ₀: it must contain
/// `double_root`, bound the count by 2 through f'' ≠ 0, with f'' at the
/// double root (`f2`, closed form) in the enclosure, and be the only
/// undecided part (no unique root beside it).
fn assert_one_cluster_of_at_most_two(
    r: &EquationRoots,
    double_root: Interval,
    f2: Interval,
    what: &str,
) {
    assert!(!r.complete, "{what}");
    assert_eq!(r.clusters.len(), 1, "{what}: {:?}", r.clusters);
    let c = &r.clusters[0];
    assert_eq!(
        c.members.len(),
        r.roots.len(),
        "{what}: every enclosure merged"
    );
    let hull = Interval::try_from((c.lo, c.hi)).unwrap();
    assert!(double_root.subset(hull), "{what}: {c:?}");
    assert_eq!(c.at_most(), Some(2), "{what}: {c:?}");
    let d = c.nonzero_derivative.expect("f'' ≠ 0");
    assert_eq!(d.order, 2);
    assert!(
        d.enclosure[0] <= f2.inf() && f2.sup() <= d.enclosure[1],
        "{what}: {d:?}"
    );
    // the hull holds every member: nothing certified is lost
    for &m in &c.members {
        assert!(c.lo <= r.roots[m].lo && r.roots[m].hi <= c.hi);
    }
}

#[test]
fn near_kappa0_eq_2_10_reports_one_cluster_of_at_most_two_roots() {
    let proof = prove_kappa0();
    // just above κ₀ = 0.19245008972987525…, the κ₀ enclosure itself, just below
    for (what, k) in [
        ("0.1924500897298753", dec("0.1924500897298753")),
        ("[κ₀]", proof.kappa0.interval()),
        ("0.19245008972987524", dec("0.19245008972987524")),
    ] {
        let r = solve_2_10(k, &Budget::default()).unwrap();
        // f'' = −6μ (closed form) at μ = 1/√3
        assert_one_cluster_of_at_most_two(&r, inv_sqrt3(), point(-6.0) * inv_sqrt3(), what);
        let c = &r.clusters[0];
        // f = μ − μ³ − 2κ has its maximum at 1/√3: one sign (−) at both ends
        // of any hull off 1/√3, so an even count, 0 or 2.
        assert_eq!(c.sign_change, Some(false), "{what}: {c:?}");
        assert_eq!(c.counts, Some(vec![0, 2]), "{what}");
        assert_eq!(c.count_text(), "0 or 2 roots");
    }
}

#[test]
fn near_kappa0_eq_2_9_at_alpha_one_reports_one_cluster_at_pi_over_3() {
    // α = 1: μ = tan(θ/2) solves (2.10), so the double root is θ = 2·atan(1/√3) = π/3.
    // f = κ sin³θ − cos θ (1 − cos θ)²: at θ = π/3, κ = √3/9 (by hand),
    // f'' = 3κ(2 sin θ cos²θ − sin³θ) − (−cos θ + 4cos²θ − 4sin²θ + 6cos θ sin²θ
    // − 3cos³θ) = −1/8 + 5/8 = 1/2 (κ differs from √3/9 by 10⁻¹⁶: f'' moves less).
    let pi3 = Interval::PI / const_interval!(3.0, 3.0);
    let r = solve_2_9(dec("0.1924500897298753"), dec("1"), &Budget::default()).unwrap();
    assert_one_cluster_of_at_most_two(&r, pi3, point(0.5), "(2.9), α = 1");
    assert_eq!(r.clusters[0].counts, Some(vec![0, 2]));
}

#[test]
fn away_from_kappa0_nothing_is_clustered() {
    // κ = 0.1: two simple roots (Viète); κ = 0.25 > κ₀: none.
    let two = solve_2_10(dec("0.1"), &Budget::default()).unwrap();
    assert!(two.complete && two.roots.len() == 2 && two.clusters.is_empty());
    assert_eq!(two.unique_count(), viete(dec("0.1")).len());
    let none = solve_2_10(dec("0.25"), &Budget::default()).unwrap();
    assert!(none.complete && none.roots.is_empty() && none.clusters.is_empty());
}

/// (2.10) plus `w (μ − 1/2)²` with `w ∈ [−10, 10]`: f'' = −6μ + 2w may vanish.
struct WobblySecondDerivative(Function);
impl RealFn for WobblySecondDerivative {
    fn eval<T: Scalar>(&self, mu: T) -> T {
        let w = T::lift(const_interval!(-10.0, 10.0));
        let half = T::lift(const_interval!(0.5, 0.5));
        self.0.eval(mu) + w * (mu - half).sqr()
    }
}

#[test]
fn a_derivative_not_away_from_zero_gives_no_count_bound() {
    let r = solve_2_10(dec("0.1924500897298753"), &Budget::default()).unwrap();
    let c = &r.clusters[0];
    // mutant 1: the same hull, a function whose f'' encloses 0
    let m = bound_cluster(
        &WobblySecondDerivative(eq_2_10(dec("0.1924500897298753"))),
        [r.searched[0], c.lo, c.hi, r.searched[1]],
        c.members.clone(),
    );
    assert_eq!(m.nonzero_derivative, None);
    assert_eq!(
        (m.counts.clone(), m.at_most(), m.parity),
        (None, None, None)
    );
    assert_eq!(m.count_text(), "any number of roots");
    // mutant 2: the hull stretched to μ = 0, where f'' = −6μ vanishes and
    // f' = 1 − 3μ² changes sign (and κ = 0.1 has two roots there: Viète)
    let m = bound_cluster(&eq_2_10(dec("0.1")), [0.0, 0.0, 1.0, 1.0], vec![0]);
    assert_eq!(m.nonzero_derivative, None);
    assert_eq!(m.at_most(), None);
}

#[test]
fn roots_cli_prints_one_cluster_near_kappa0() {
    let near_kappa0 = [
        "roots",
        "--equation",
        "2.10",
        "--kappa",
        "0.1924500897298753",
    ];
    let out = crate::common::detach(&near_kappa0);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let rows: Vec<&str> = text.lines().filter(|l| l.contains("cluster of")).collect();
    assert_eq!(rows.len(), 1, "{text}");
    assert!(
        rows[0].contains("0 or 2 roots (counted with multiplicity)"),
        "{text}"
    );
    assert!(
        text.contains(
            "complete: no — every root lies in the enclosures above; #1 holds 0 or 2 roots"
        ),
        "{text}"
    );
    // the JSON keeps every member
    let v = crate::common::json(&[&near_kappa0[..], &["--json"]].concat());
    let members = v["clusters"][0]["members"].as_array().unwrap();
    assert_eq!(members.len(), v["roots"].as_array().unwrap().len());
    assert!(members.len() > 1);
}
