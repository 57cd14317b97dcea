//! κ₀ of (2.10) and the proof, for every κ > 0, of how many positive roots
//! `2κ = μ(1 − μ)(1 + μ)` has.
//!
//! With `p(μ) = μ − μ³`: `p'(μ) = 1 − 3μ²` has exactly one root μ* on
//! [0, 1] (interval Newton) and none beyond; `p' > 0` before it and `p' < 0`
//! after, so p rises from `p(0) = 0` to `p(μ*)`, then falls through
//! `p(1) = 0` to `−∞`. Hence `κ₀ := p(μ*)/2` (= √3/9) and
//! * κ > κ₀: `p ≤ 2κ₀ < 2κ`, no root;
//! * 0 < κ < κ₀: one root on each strictly monotone branch (0, μ*) and
//!   (μ*, 1), where `p' ≠ 0`: exactly two, both simple;
//! * κ = κ₀: μ* alone, a double root (`p'(μ*) = 0`, `p''(μ*) = −6μ* ≠ 0`).
//!
//! Each step is kept as data ([`ProofStep`]) with the enclosures it rests on.

use super::isolate::{isolate, point, ulps_between, Budget, RealFn, Stats};
use crate::number::scalar::Scalar;
use inari::{const_interval, Interval};
use serde::Serialize;
use std::collections::BTreeMap;

/// A closed interval with exact double endpoints.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Bound {
    pub lo: f64,
    pub hi: f64,
}

impl Bound {
    pub fn of(x: Interval) -> Bound {
        Bound {
            lo: x.inf(),
            hi: x.sup(),
        }
    }
    pub fn interval(&self) -> Interval {
        Interval::try_from((self.lo, self.hi)).expect("ordered")
    }
    pub fn width_ulps(&self) -> u64 {
        ulps_between(self.lo, self.hi)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    Proved,
    NotProved,
}

impl Verdict {
    fn from(b: bool) -> Verdict {
        if b {
            Verdict::Proved
        } else {
            Verdict::NotProved
        }
    }
}

/// One step of the proof: what it states, the certified enclosures it rests
/// on, the steps it uses, and whether the computation confirmed it.
#[derive(Clone, Debug, Serialize)]
pub struct ProofStep {
    pub id: &'static str,
    pub statement: String,
    pub enclosures: BTreeMap<String, Bound>,
    pub depends_on: Vec<&'static str>,
    pub verdict: Verdict,
}

/// The enclosure of κ₀ with its proof.
#[derive(Clone, Debug, Serialize)]
pub struct Kappa0Proof {
    /// κ₀ = max_{μ>0} p(μ)/2.
    pub kappa0: Bound,
    pub kappa0_width_ulps: u64,
    /// The unique positive root of p'.
    pub mu_star: Bound,
    /// 2κ₀ = p(μ*).
    pub max_value: Bound,
    /// √3/9 computed independently in intervals (closed form, cross-check).
    pub sqrt3_over_9: Bound,
    pub steps: Vec<ProofStep>,
    /// The claims about every κ > 0.
    pub statements: Vec<ProofStep>,
    pub stats: Stats,
}

/// `p'(μ) = 1 − 3μ²`.
pub struct DerivativeOfP;

impl RealFn for DerivativeOfP {
    fn eval<T: Scalar>(&self, mu: T) -> T {
        T::int(1) - T::int(3) * mu.sqr()
    }
}

/// `p(μ) = μ(1 − μ)(1 + μ)`, the right side of (2.10).
pub fn p(mu: Interval) -> Interval {
    let one = const_interval!(1.0, 1.0);
    mu * (one - mu) * (one + mu)
}

fn dp(mu: Interval) -> Interval {
    DerivativeOfP.eval(mu)
}

fn map(items: &[(&str, Interval)]) -> BTreeMap<String, Bound> {
    items
        .iter()
        .map(|(k, v)| (k.to_string(), Bound::of(*v)))
        .collect()
}

/// Encloses p on a narrow box around its maximum: the natural extension
/// intersected with the mean-value form `p(m) + p'(M)(M − m)`.
pub fn p_tight(m_box: Interval) -> Interval {
    let m = point(m_box.mid());
    let mean_value = p(m) + dp(m_box) * (m_box - m);
    p(m_box).intersection(mean_value)
}

/// Runs the proof. Deterministic and fast (a few hundred evaluations).
pub fn prove_kappa0() -> Kappa0Proof {
    let one = const_interval!(1.0, 1.0);
    let zero = const_interval!(0.0, 0.0);
    let tail = Interval::try_from((1.0, f64::INFINITY)).expect("valid");
    let mut steps = Vec::new();

    // S1: p' has exactly one root μ* in [0, 1], simple.
    let iso = isolate(&DerivativeOfP, 0.0, 1.0, &Budget::default());
    let s1_ok = iso.complete && iso.roots.len() == 1;
    let m = iso
        .roots
        .first()
        .map(|r| r.interval())
        .unwrap_or(Interval::try_from((0.0, 1.0)).expect("valid"));
    steps.push(ProofStep {
        id: "derivative_root",
        statement: "p'(μ) = 1 − 3μ² has exactly one root μ* in [0, 1], simple, inside M \
                    (interval Newton: N(X) ⊂ int X, 0 ∉ p''(X); the rest of [0, 1] proved root-free)"
            .into(),
        enclosures: map(&[("M", m)]),
        depends_on: vec![],
        verdict: Verdict::from(s1_ok),
    });

    // S2: p' > 0 on [0, μ*).
    let dp0 = dp(zero);
    let s2_ok = s1_ok && dp0.inf() > 0.0;
    steps.push(ProofStep {
        id: "increasing",
        statement: "p' > 0 on [0, μ*): p' is continuous, has no root there (derivative_root) \
                    and p'(0) > 0; so p is strictly increasing on [0, μ*]"
            .into(),
        enclosures: map(&[("p'(0)", dp0)]),
        depends_on: vec!["derivative_root"],
        verdict: Verdict::from(s2_ok),
    });

    // S3: p' < 0 on (μ*, ∞).
    let (dp1, dp_tail) = (dp(one), dp(tail));
    let s3_ok = s1_ok && dp1.sup() < 0.0 && dp_tail.sup() < 0.0;
    steps.push(ProofStep {
        id: "decreasing",
        statement: "p' < 0 on (μ*, ∞): no root of p' in (μ*, 1] (derivative_root), p'(1) < 0, \
                    and p'([1, +∞]) < 0; so p is strictly decreasing on [μ*, ∞)"
            .into(),
        enclosures: map(&[("p'(1)", dp1), ("p'([1, +inf])", dp_tail)]),
        depends_on: vec!["derivative_root"],
        verdict: Verdict::from(s3_ok),
    });

    // S4: max p = p(μ*) = 2κ₀.
    let pmax = p_tight(m);
    let kappa0 = pmax / const_interval!(2.0, 2.0);
    let s4_ok = s2_ok && s3_ok && pmax.inf() > 0.0;
    steps.push(ProofStep {
        id: "maximum",
        statement: "max_{μ ≥ 0} p(μ) = p(μ*) =: 2κ₀ > 0 (increasing then decreasing), \
                    enclosed by p over M (natural ∩ mean-value form)"
            .into(),
        enclosures: map(&[("p(mu*) = 2 kappa0", pmax), ("kappa0", kappa0)]),
        depends_on: vec!["increasing", "decreasing"],
        verdict: Verdict::from(s4_ok),
    });

    // S5: p(0) = p(1) = 0 and p ≤ 0 on [1, ∞).
    let (p0, p1, ptail) = (p(zero), p(one), p(tail));
    let s5_ok = p0 == zero && p1 == zero && ptail.sup() <= 0.0;
    steps.push(ProofStep {
        id: "zeros_and_tail",
        statement: "p(0) = 0, p(1) = 0 and p(μ) ≤ 0 for μ ≥ 1".into(),
        enclosures: map(&[("p(0)", p0), ("p(1)", p1), ("p([1, +inf])", ptail)]),
        depends_on: vec![],
        verdict: Verdict::from(s5_ok),
    });

    // S6: p''(μ*) ≠ 0.
    let d2 = const_interval!(-6.0, -6.0) * m;
    let s6_ok = s1_ok && d2.sup() < 0.0;
    steps.push(ProofStep {
        id: "second_derivative",
        statement: "p''(μ*) = −6μ* < 0: μ* is a strict maximum and, at κ = κ₀, a root of \
                    multiplicity exactly two"
            .into(),
        enclosures: map(&[("p''(M)", d2)]),
        depends_on: vec!["derivative_root"],
        verdict: Verdict::from(s6_ok),
    });

    // Cross-check with the closed form √3/9 (not used by the proof).
    let closed = point(3.0).sqrt() / point(9.0);
    let cross_ok = !closed.disjoint(kappa0);
    steps.push(ProofStep {
        id: "closed_form",
        statement: "cross-check: the enclosure of κ₀ meets √3/9 computed in intervals \
                    (p(1/√3) = 2√3/9)"
            .into(),
        enclosures: map(&[("sqrt(3)/9", closed), ("kappa0", kappa0)]),
        depends_on: vec![],
        verdict: Verdict::from(cross_ok),
    });

    let all = |ids: &[&str]| {
        ids.iter().all(|id| {
            steps
                .iter()
                .any(|s| s.id == *id && s.verdict == Verdict::Proved)
        })
    };
    let deps_a = vec!["increasing", "decreasing", "maximum"];
    let deps_b = vec!["increasing", "decreasing", "maximum", "zeros_and_tail"];
    let deps_c = vec!["increasing", "decreasing", "maximum", "second_derivative"];
    let statements = vec![
        ProofStep {
            id: "above_kappa0_no_root",
            statement: "for every κ > κ₀, (2.10) has no root μ > 0 (p(μ) ≤ 2κ₀ < 2κ)".into(),
            enclosures: map(&[("kappa0", kappa0)]),
            verdict: Verdict::from(all(&deps_a)),
            depends_on: deps_a,
        },
        ProofStep {
            id: "below_kappa0_two_simple_roots",
            statement: "for every κ ∈ (0, κ₀), (2.10) has exactly two roots μ > 0, \
                        μ₁ ∈ (0, μ*) and μ₂ ∈ (μ*, 1), both simple: p is continuous and \
                        strictly monotone on [0, μ*] (from 0 to 2κ₀) and on [μ*, 1] (from 2κ₀ \
                        to 0), p' ≠ 0 off μ*, and p ≤ 0 < 2κ for μ ≥ 1"
                .into(),
            enclosures: map(&[("kappa0", kappa0), ("mu*", m)]),
            verdict: Verdict::from(all(&deps_b)),
            depends_on: deps_b,
        },
        ProofStep {
            id: "at_kappa0_one_double_root",
            statement: "at κ = κ₀, μ* is the only root μ > 0 and it is double \
                        (p(μ*) = 2κ₀, p'(μ*) = 0, p''(μ*) ≠ 0, p < 2κ₀ elsewhere)"
                .into(),
            enclosures: map(&[("mu*", m)]),
            verdict: Verdict::from(all(&deps_c)),
            depends_on: deps_c,
        },
    ];
    Kappa0Proof {
        kappa0: Bound::of(kappa0),
        kappa0_width_ulps: ulps_between(kappa0.inf(), kappa0.sup()),
        mu_star: Bound::of(m),
        max_value: Bound::of(pmax),
        sqrt3_over_9: Bound::of(closed),
        steps,
        statements,
        stats: iso.stats,
    }
}

impl Kappa0Proof {
    /// Every step and statement confirmed.
    pub fn all_proved(&self) -> bool {
        self.steps
            .iter()
            .chain(&self.statements)
            .all(|s| s.verdict == Verdict::Proved)
    }

    /// What the proved statements say about (2.10) for every κ in an enclosure.
    pub fn classify(&self, kappa: Interval) -> Kappa0Class {
        let k0 = self.kappa0.interval();
        if !self.all_proved() || kappa.is_empty() {
            Kappa0Class::Undecided
        } else if kappa.inf() > k0.sup() {
            Kappa0Class::NoRoot
        } else if kappa.inf() > 0.0 && kappa.sup() < k0.inf() {
            Kappa0Class::TwoSimpleRoots
        } else {
            Kappa0Class::Undecided
        }
    }
}

/// The number of positive roots of (2.10) for all κ of an enclosure.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Kappa0Class {
    NoRoot,
    TwoSimpleRoots,
    /// The enclosure meets κ₀ (or 0).
    Undecided,
}

impl std::fmt::Display for Kappa0Class {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str(match self {
            Kappa0Class::NoRoot => "no root",
            Kappa0Class::TwoSimpleRoots => "two simple roots",
            Kappa0Class::Undecided => "undecided",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::number::param::enclose_decimal;

    #[test]
    fn kappa0_is_proved_and_a_few_ulp_wide() {
        let proof = prove_kappa0();
        assert!(proof.all_proved(), "{proof:#?}");
        assert!(proof.kappa0_width_ulps <= 4, "{:?}", proof.kappa0);
        // 40-digit decimal of √3/9 (e.g. from `bc -l`: sqrt(3)/9). Its two
        // enclosing doubles straddle √3/9, so κ₀'s enclosure must contain both.
        let d = enclose_decimal("k", "0.1924500897298752548363829268339858185492").unwrap();
        assert!(d.subset(proof.kappa0.interval()));
        // μ* = 1/√3 in closed form.
        let mu = point(1.0) / point(3.0).sqrt();
        assert!(!mu.disjoint(proof.mu_star.interval()));
        assert!(proof.mu_star.width_ulps() <= 4);
    }

    #[test]
    fn classification_of_kappa() {
        let proof = prove_kappa0();
        let k = |t: &str| enclose_decimal("k", t).unwrap();
        assert_eq!(proof.classify(k("0.19245008972988")), Kappa0Class::NoRoot);
        assert_eq!(
            proof.classify(k("0.19245008972987")),
            Kappa0Class::TwoSimpleRoots
        );
        assert_eq!(
            proof.classify(proof.kappa0.interval()),
            Kappa0Class::Undecided
        );
    }
}
