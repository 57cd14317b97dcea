//! Certified isolation of the real roots of a scalar function on a closed
//! interval `[lo, hi]` with double endpoints.
//!
//! The search keeps a stack of boxes with exactly representable endpoints and,
//! for each box `X`:
//!
//! 1. **exclusion**: if the decorated enclosure `f(X)` is defined (`≥ def`)
//!    and does not contain 0, or `f` is C¹ on X (`≥ dac`) and the mean-value
//!    form `f(m) + f'(X)(X − m)` excludes 0, `X` is proved root-free;
//! 2. **interval Newton**: if `f` is continuously differentiable on `X`
//!    (value and derivative enclosures from [`Dual`] numbers decorated
//!    `≥ dac`) and `0 ∉ f'(X)`, the operator `N(X) = m − f(m)/f'(X)` is
//!    computed. `N(X) ∩ X = ∅` proves `X` root-free; `N(X)` strictly inside `X`
//!    proves exactly one root, simple, inside `N(X)` ([`RootStatus::Unique`]);
//!    a strong contraction replaces `X` by `N(X) ∩ X` (every root of `X` lies
//!    in `N(X)`);
//! 3. otherwise `X` is **bisected** at an exactly representable point slightly
//!    off centre, unless it is already narrower than the tolerance: then it
//!    becomes an [`RootStatus::Undecided`] fragment with the reason.
//!
//! Unique roots are then contracted with interval Newton until the enclosure
//! stops shrinking (a few ulp for a simple root of a tightly evaluated `f`).
//! Touching undecided fragments are merged. Nothing is ever dropped: the
//! returned enclosures together with the proved root-free parts always cover
//! `[lo, hi]`, also when the budget runs out.

use crate::number::scalar::{is_continuous, is_defined, Dual, Scalar};
use inari::{DecInterval, Interval};
use serde::Serialize;

/// A real function written once for every [`Scalar`].
pub trait RealFn {
    fn eval<T: Scalar>(&self, x: T) -> T;
}

/// How much work the isolator may spend.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Budget {
    /// Most evaluations of `f` (on any scalar type) before giving up.
    pub max_evaluations: usize,
    /// A box narrower than `min_width · max(1, |X|)` is not bisected further.
    pub min_width: f64,
}

impl Default for Budget {
    fn default() -> Self {
        Budget {
            max_evaluations: 200_000,
            min_width: 1e-11,
        }
    }
}

/// What is proved about one returned enclosure.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RootStatus {
    /// Exactly one root in the enclosure, and it is simple (`f' ≠ 0` there).
    Unique,
    /// Possibly roots (any number, including none); see the reason.
    Undecided,
}

/// Why an enclosure could not be decided.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum UndecidedReason {
    /// `f` and `f'` may both vanish on a box at the tolerance: a possible
    /// multiple root (or roots closer than the tolerance).
    PossibleMultipleRoot,
    /// `f'` excludes 0 but neither exclusion nor Newton concluded at the
    /// tolerance (e.g. a root on a split point, or too wide parameters).
    Tolerance,
    /// `f` may be undefined or not continuously differentiable on the box.
    NotSmooth,
    /// At the end of an open domain, the limit could not be separated from 0.
    DomainEdge,
    /// The evaluation budget ran out before the box was processed.
    Budget,
}

impl UndecidedReason {
    /// Words for tables (the JSON keeps the snake_case name).
    pub fn describe(self) -> &'static str {
        match self {
            UndecidedReason::PossibleMultipleRoot => "possible multiple root",
            UndecidedReason::Tolerance => "tolerance reached",
            UndecidedReason::NotSmooth => "not smooth",
            UndecidedReason::DomainEdge => "domain edge",
            UndecidedReason::Budget => "budget",
        }
    }
}

/// One root enclosure `[lo, hi]` (exact doubles) with what is proved about it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RootEnclosure {
    pub lo: f64,
    pub hi: f64,
    pub status: RootStatus,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<UndecidedReason>,
}

impl RootEnclosure {
    pub fn unique(x: Interval) -> Self {
        RootEnclosure {
            lo: x.inf(),
            hi: x.sup(),
            status: RootStatus::Unique,
            reason: None,
        }
    }
    pub fn undecided(lo: f64, hi: f64, reason: UndecidedReason) -> Self {
        RootEnclosure {
            lo,
            hi,
            status: RootStatus::Undecided,
            reason: Some(reason),
        }
    }
    pub fn interval(&self) -> Interval {
        Interval::try_from((self.lo, self.hi)).expect("ordered endpoints")
    }
    pub fn is_unique(&self) -> bool {
        self.status == RootStatus::Unique
    }
    /// Number of doubles strictly above `lo` up to `hi` (0 for a point).
    pub fn width_ulps(&self) -> u64 {
        ulps_between(self.lo, self.hi)
    }
}

/// Work done by one isolation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Stats {
    pub evaluations: usize,
    pub bisections: usize,
    pub newton_steps: usize,
}

impl std::ops::AddAssign for Stats {
    fn add_assign(&mut self, o: Stats) {
        self.evaluations += o.evaluations;
        self.bisections += o.bisections;
        self.newton_steps += o.newton_steps;
    }
}

/// The result of [`isolate`] on `[lo, hi]`.
///
/// Always: every root of `f` in `[lo, hi]` lies in one of `roots` (the rest of
/// the domain is proved root-free). `complete` adds that every enclosure is
/// [`RootStatus::Unique`], so the roots in the domain are exactly one per
/// enclosure, all simple.
#[derive(Clone, Debug, Serialize)]
pub struct Isolation {
    pub domain: [f64; 2],
    pub roots: Vec<RootEnclosure>,
    pub complete: bool,
    pub stats: Stats,
}

impl Isolation {
    pub fn unique_count(&self) -> usize {
        self.roots.iter().filter(|r| r.is_unique()).count()
    }
}

/// Distance in doubles between two finite doubles `lo ≤ hi`.
pub fn ulps_between(lo: f64, hi: f64) -> u64 {
    fn key(x: f64) -> i64 {
        let b = x.to_bits() as i64;
        if b < 0 {
            i64::MIN - b
        } else {
            b
        }
    }
    (key(hi) - key(lo)).unsigned_abs()
}

/// `[x, x]` for a finite double.
pub fn point(x: f64) -> Interval {
    Interval::try_from((x, x)).expect("finite double")
}

fn iv(lo: f64, hi: f64) -> Interval {
    Interval::try_from((lo, hi)).expect("ordered finite endpoints")
}

/// Outcome of one interval Newton step on `X`.
enum Newton {
    /// `N(X) ∩ X = ∅`: no root in X.
    NoRoot,
    /// `N(X) ⊂ int X`: exactly one root, in `N(X)`.
    Unique(Interval),
    /// Every root of X lies in this subset of X.
    Contracted(Interval),
    /// `f'(X)` may contain 0 (f is C¹ on X).
    DerivativeMayVanish,
    /// f may not be C¹ on X.
    NotSmooth,
}

struct Engine<'a, F: RealFn> {
    f: &'a F,
    stats: Stats,
}

impl<F: RealFn> Engine<'_, F> {
    fn enclose(&mut self, x: Interval) -> DecInterval {
        self.stats.evaluations += 1;
        self.f.eval(DecInterval::new(x))
    }

    fn newton(&mut self, x: Interval) -> Newton {
        self.newton_or_exclude(x).0
    }

    /// One interval Newton step on `x`; also reports whether the natural or
    /// the mean-value enclosure `f(m) + f'(X)(X − m)` already excludes 0.
    fn newton_or_exclude(&mut self, x: Interval) -> (Newton, bool) {
        self.stats.evaluations += 1;
        self.stats.newton_steps += 1;
        let y = self.f.eval(Dual::variable(DecInterval::new(x), 0));
        // The value part of the dual is the natural decorated extension.
        if is_defined(y.value) && !y.value.interval().expect("defined").contains(0.0) {
            return (Newton::NoRoot, true);
        }
        if !is_continuous(y.value) || !is_continuous(y.grad[0]) {
            return (Newton::NotSmooth, false);
        }
        let d = y.grad[0].interval().expect("checked");
        let m = x.mid();
        let fm = self.enclose(point(m));
        if !is_defined(fm) {
            return (Newton::NotSmooth, false);
        }
        let fm = fm.interval().expect("defined");
        // Mean-value form (f is C¹ on X): exclusion near flat extrema.
        let mv = fm + d * (x - point(m));
        if !mv.contains(0.0) {
            return (Newton::NoRoot, true);
        }
        if d.contains(0.0) {
            return (Newton::DerivativeMayVanish, false);
        }
        let n = point(m) - fm / d;
        if n.interior(x) {
            return (Newton::Unique(n), false);
        }
        let c = n.intersection(x);
        if c.is_empty() {
            (Newton::NoRoot, false)
        } else {
            (Newton::Contracted(c), false)
        }
    }

    /// Contracts an enclosure known to hold exactly one root until it stops
    /// shrinking.
    fn refine(&mut self, mut x: Interval) -> Interval {
        for _ in 0..100 {
            let next = match self.newton(x) {
                Newton::Unique(n) | Newton::Contracted(n) => n.intersection(x),
                _ => break,
            };
            if next.is_empty() || next.wid() >= x.wid() {
                break;
            }
            x = next;
        }
        x
    }
}

/// An exactly representable split point of `[a, b]`, slightly off centre.
pub fn split_point(a: f64, b: f64) -> f64 {
    let m = a + (b - a) * (127.0 / 256.0);
    if a < m && m < b {
        m
    } else {
        let m = a / 2.0 + b / 2.0;
        if a < m && m < b {
            m
        } else {
            a
        }
    }
}

/// Isolates every root of `f` on `[lo, hi]` (finite doubles, `lo < hi`).
pub fn isolate<F: RealFn>(f: &F, lo: f64, hi: f64, budget: &Budget) -> Isolation {
    assert!(
        lo.is_finite() && hi.is_finite() && lo <= hi,
        "isolate needs a finite non-empty domain"
    );
    let mut eng = Engine {
        f,
        stats: Stats::default(),
    };
    let mut out: Vec<RootEnclosure> = Vec::new();
    let mut stack = vec![iv(lo, hi)];
    while let Some(x) = stack.pop() {
        if eng.stats.evaluations >= budget.max_evaluations {
            out.push(RootEnclosure::undecided(
                x.inf(),
                x.sup(),
                UndecidedReason::Budget,
            ));
            continue;
        }
        let reason = match eng.newton_or_exclude(x).0 {
            Newton::NoRoot => continue,
            Newton::Unique(n) => {
                out.push(RootEnclosure::unique(eng.refine(n)));
                continue;
            }
            Newton::Contracted(c) if c.wid() < 0.5 * x.wid() => {
                stack.push(c);
                continue;
            }
            Newton::Contracted(_) => UndecidedReason::Tolerance,
            Newton::DerivativeMayVanish => UndecidedReason::PossibleMultipleRoot,
            Newton::NotSmooth => UndecidedReason::NotSmooth,
        };
        let (a, b) = (x.inf(), x.sup());
        let m = split_point(a, b);
        if x.wid() <= budget.min_width * x.mag().max(1.0) || m == a {
            out.push(RootEnclosure::undecided(a, b, reason));
            continue;
        }
        eng.stats.bisections += 1;
        // Right half first, so the left half is processed first.
        stack.push(iv(m, b));
        stack.push(iv(a, m));
    }
    let roots = merge_undecided(out);
    let complete = roots.iter().all(|r| r.is_unique());
    Isolation {
        domain: [lo, hi],
        roots,
        complete,
        stats: eng.stats,
    }
}

/// Sorts enclosures and merges touching or overlapping undecided fragments
/// (the merged reason is the most severe of the parts).
pub fn merge_undecided(mut v: Vec<RootEnclosure>) -> Vec<RootEnclosure> {
    v.sort_by(|a, b| a.lo.total_cmp(&b.lo).then(a.hi.total_cmp(&b.hi)));
    let mut out: Vec<RootEnclosure> = Vec::with_capacity(v.len());
    for r in v {
        if let Some(last) = out.last_mut() {
            if !last.is_unique() && !r.is_unique() && r.lo <= last.hi {
                last.hi = last.hi.max(r.hi);
                last.reason = last.reason.max(r.reason);
                continue;
            }
        }
        out.push(r);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// x² − 2: roots ±√2 (closed form).
    struct Sq2;
    impl RealFn for Sq2 {
        fn eval<T: Scalar>(&self, x: T) -> T {
            x.sqr() - T::int(2)
        }
    }

    /// (x² − 2)²: double roots ±√2.
    struct Sq2Squared;
    impl RealFn for Sq2Squared {
        fn eval<T: Scalar>(&self, x: T) -> T {
            (x.sqr() - T::int(2)).sqr()
        }
    }

    /// sin(x) on [1, 10]: roots π, 2π, 3π.
    struct Sin;
    impl RealFn for Sin {
        fn eval<T: Scalar>(&self, x: T) -> T {
            x.sin()
        }
    }

    /// 1/x − 1 on [−1, 2]: a pole at 0, a root at 1.
    struct Pole;
    impl RealFn for Pole {
        fn eval<T: Scalar>(&self, x: T) -> T {
            T::int(1) / x - T::int(1)
        }
    }

    #[test]
    fn simple_roots_are_unique_and_a_few_ulp_wide() {
        let r = isolate(&Sq2, -3.0, 3.0, &Budget::default());
        assert!(r.complete);
        assert_eq!(r.roots.len(), 2);
        let s2 = point(2.0).sqrt();
        for (root, sign) in r.roots.iter().zip([-1.0, 1.0]) {
            assert!(root.is_unique());
            assert!(root.width_ulps() <= 4, "{root:?}");
            // √2 enclosed independently by inari's sqrt.
            assert!(!root.interval().disjoint(point(sign) * s2));
        }
    }

    #[test]
    fn sine_roots_are_multiples_of_pi() {
        let r = isolate(&Sin, 1.0, 10.0, &Budget::default());
        assert!(r.complete);
        assert_eq!(r.roots.len(), 3);
        for (k, root) in r.roots.iter().enumerate() {
            let kpi = Interval::PI * point(k as f64 + 1.0);
            assert!(!root.interval().disjoint(kpi), "{root:?}");
            assert!(root.width_ulps() <= 8);
        }
    }

    #[test]
    fn double_roots_are_never_unique_and_stay_enclosed() {
        let r = isolate(&Sq2Squared, -3.0, 3.0, &Budget::default());
        assert!(!r.complete);
        assert!(r.roots.iter().all(|x| !x.is_unique()));
        // merged into one fragment per double root
        assert_eq!(r.roots.len(), 2, "{:?}", r.roots);
        for (root, sign) in r.roots.iter().zip([-1.0, 1.0]) {
            assert!(root.interval().contains(sign * std::f64::consts::SQRT_2));
            assert_eq!(root.reason, Some(UndecidedReason::PossibleMultipleRoot));
        }
    }

    #[test]
    fn a_pole_is_not_a_root() {
        let r = isolate(&Pole, -1.0, 2.0, &Budget::default());
        let unique: Vec<_> = r.roots.iter().filter(|x| x.is_unique()).collect();
        assert_eq!(unique.len(), 1);
        assert!(unique[0].interval().contains(1.0));
        // the pole is reported, never claimed root-free nor unique
        assert!(r
            .roots
            .iter()
            .any(|x| !x.is_unique() && x.lo <= 0.0 && 0.0 <= x.hi));
    }

    #[test]
    fn budget_exhaustion_keeps_coverage() {
        let b = Budget {
            max_evaluations: 5,
            ..Budget::default()
        };
        let r = isolate(&Sin, 1.0, 10.0, &b);
        assert!(!r.complete);
        assert!(r
            .roots
            .iter()
            .any(|x| x.reason == Some(UndecidedReason::Budget)));
        for k in 1..=3 {
            let x = std::f64::consts::PI * k as f64;
            assert!(r.roots.iter().any(|e| e.lo <= x && x <= e.hi));
        }
    }

    #[test]
    fn ulps_count_across_zero() {
        assert_eq!(ulps_between(1.0, 1.0), 0);
        assert_eq!(ulps_between(1.0, f64::from_bits(1.0f64.to_bits() + 3)), 3);
        assert_eq!(ulps_between(-0.0, 0.0), 0);
        assert_eq!(ulps_between(-f64::from_bits(1), f64::from_bits(1)), 2);
    }
}
