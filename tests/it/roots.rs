//! Certified roots against independent references: closed forms, the
//! tan-half-angle polynomial, the θ → π − θ symmetry, f64 scans.

use detach::inari::{const_interval, Interval};
use detach::number::param::enclose_decimal;
use detach::roots::equations::{Eq29, Eq29TanHalf, PotentialSlope};
use detach::roots::isolate::point;
use detach::roots::{
    isolate, prove_kappa0, solve_2_10, solve_2_12, solve_2_9, Budget, RealFn, RootStatus,
};
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
    let Scene::Smooth(disc) = Scene::default_of(SceneId::SmoothDisc) else {
        unreachable!()
    };
    let r = solve_2_12(&disc, &Budget::default());
    assert!(r.complete);
    let f = |x: f64| PotentialSlope(&disc).eval(x);
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
        let f = Eq29 { kappa: k, alpha: a };
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
