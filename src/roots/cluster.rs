//! Clusters: runs of nearby undecided enclosures reported as one enclosure
//! with a certified bound on the number of roots it holds.
//!
//! Near a multiple root the isolator leaves many small undecided fragments
//! separated by gaps it proved root-free. A cluster is the hull of such a run;
//! it is a presentation of the certified pieces, not a new certificate: the
//! members are kept, and the hull holds every root any member could hold (the
//! gaps inside it are root-free).
//!
//! **Merging rule.** Two neighbouring groups of undecided enclosures (no
//! unique enclosure between them) merge when the gap between them is at most
//! [`GAP_FACTOR`] times the sum of their widths; merging repeats until no pair
//! qualifies, so the result does not depend on the order of the pieces. Near a
//! multiple root the isolator splits off root-free gaps wherever `|f|` rises
//! above rounding, a few fragment widths wide at most, so the fragments of one
//! root join; enclosures of distinct roots, separated by many times their own
//! (tolerance-sized) widths, stay apart.
//!
//! **Count bound** (roots of `f` in the hull `H = [a, b]`, counted with
//! multiplicity), from enclosures of `f`, `f'`, `f''` over `H` by nested
//! dual numbers, each decorated `≥ dac` (so `f` is C² on `H`):
//! * Rolle: if `f⁽ᵏ⁾(H) ∌ 0` (k = 1 or 2), `f` has at most `k` roots in `H`;
//! * parity: the gaps next to `H` are root-free (proved by the isolator), so
//!   the signs of `f` at points `p ≤ a` and `q ≥ b` in those gaps, with `f`
//!   continuous on `[p, q]`, give the parity of the roots in `H` when a Rolle
//!   bound holds: odd when the signs differ, even when they agree (a root
//!   changes the sign of `f` exactly when its multiplicity is odd; under the
//!   bound there are finitely many, each of multiplicity ≤ k);
//! * without a Rolle bound, opposite signs still prove at least one root.

use super::isolate::{point, RealFn, RootEnclosure};
use crate::number::scalar::{is_continuous, is_defined, DualN};
use inari::{DecInterval, Interval};
use serde::Serialize;

/// Whether the number of roots (with multiplicity) is odd or even.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Parity {
    Odd,
    Even,
}

/// One cluster of undecided enclosures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cluster {
    /// The hull of the members (exact doubles).
    pub lo: f64,
    pub hi: f64,
    /// Indices of the members in the list of enclosures (consecutive).
    pub members: Vec<usize>,
    /// Rolle: `f^(order)` excludes 0 on the hull, so at most `order` roots.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub nonzero_derivative: Option<NonzeroDerivative>,
    /// Whether `f` has opposite signs at `sign_points` (`None`: a sign not
    /// proved, or `f` not proved continuous between them).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sign_change: Option<bool>,
    /// The parity of the count, from `sign_change`, given a Rolle bound.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub parity: Option<Parity>,
    /// Points in the root-free gaps just below and above the hull where the
    /// sign of `f` is proved, with `f` there (enclosures).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sign_points: Option<[f64; 2]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sign_values: Option<[[f64; 2]; 2]>,
    /// The possible numbers of roots counted with multiplicity, when bounded.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub counts: Option<Vec<u32>>,
}

/// A derivative of `f` proved nonzero on a whole cluster.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct NonzeroDerivative {
    /// 1 for `f'`, 2 for `f''`.
    pub order: u32,
    /// Its enclosure over the hull (excludes 0).
    pub enclosure: [f64; 2],
}

impl Cluster {
    /// At most this many roots, counted with multiplicity.
    pub fn at_most(&self) -> Option<u32> {
        self.counts.as_ref().and_then(|c| c.iter().copied().max())
    }

    /// The count in words, e.g. "0 or 2 roots", "at most 2 roots".
    pub fn count_text(&self) -> String {
        match (&self.counts, self.parity) {
            (Some(c), _) if c == &[0] => "no root".into(),
            (Some(c), _) if c == &[1] => "exactly 1 root".into(),
            (Some(c), _) if c.len() == 1 => format!("exactly {} roots", c[0]),
            (Some(c), Some(_)) => {
                let words: Vec<String> = c.iter().map(u32::to_string).collect();
                format!("{} roots", words.join(" or "))
            }
            (Some(c), None) => format!("at most {} roots", c.iter().max().expect("non-empty")),
            (None, _) if self.sign_change == Some(true) => "at least 1 root".into(),
            (None, _) => "any number of roots".into(),
        }
    }
}

/// How much wider than its two neighbours a gap may be and still be merged.
pub const GAP_FACTOR: f64 = 16.0;

/// Groups the undecided members of `roots` (sorted, disjoint, every gap
/// between them and to the ends of `searched` proved root-free) into clusters
/// and bounds the number of roots of `f` in each.
pub fn clusters<F: RealFn>(f: &F, roots: &[RootEnclosure], searched: [f64; 2]) -> Vec<Cluster> {
    let mut groups: Vec<Vec<usize>> = (0..roots.len())
        .filter(|&i| !roots[i].is_unique())
        .map(|i| vec![i])
        .collect();
    let hull = |g: &[usize]| (roots[g[0]].lo, roots[*g.last().expect("non-empty")].hi);
    loop {
        let mut merged: Vec<Vec<usize>> = Vec::with_capacity(groups.len());
        for g in groups.iter() {
            if let Some(last) = merged.last_mut() {
                let ((a, b), (c, d)) = (hull(last), hull(g));
                let consecutive = last.last().map(|&i| i + 1) == Some(g[0]);
                if consecutive && c - b <= GAP_FACTOR * ((b - a) + (d - c)) {
                    last.extend_from_slice(g);
                    continue;
                }
            }
            merged.push(g.clone());
        }
        let done = merged.len() == groups.len();
        groups = merged;
        if done {
            break;
        }
    }
    groups
        .into_iter()
        .map(|members| {
            let (lo, hi) = hull(&members);
            // Fragments at open domain ends may reach past `searched`.
            let below = match members[0] {
                0 => searched[0].min(lo),
                i => roots[i - 1].hi,
            };
            let above = roots
                .get(members.last().expect("non-empty") + 1)
                .map_or(searched[1].max(hi), |r| r.lo);
            bound_cluster(f, [below, lo, hi, above], members)
        })
        .collect()
}

/// Values of `f`, `f'`, `f''` over `x` by nested dual numbers.
fn second_order<F: RealFn>(f: &F, x: Interval) -> [DecInterval; 3] {
    type D1 = DualN<DecInterval, 1>;
    let v = D1::variable(DecInterval::new(x), 0);
    let y = f.eval(DualN::<D1, 1> {
        value: v,
        grad: [D1::constant(DecInterval::new(point(1.0)))],
    });
    [y.value.value, y.value.grad[0], y.grad[0].grad[0]]
}

/// A cluster with its count bound, from `f` on the hull `[lo, hi]`; `[below,
/// lo)` and `(hi, above]` must be root-free.
pub fn bound_cluster<F: RealFn>(
    f: &F,
    [below, lo, hi, above]: [f64; 4],
    members: Vec<usize>,
) -> Cluster {
    let hull = Interval::try_from((lo, hi)).expect("ordered hull");
    let derivs = second_order(f, hull);
    let smooth = derivs.iter().all(|d| is_continuous(*d));
    let nonzero_derivative = if smooth {
        (1..=2u32).find_map(|order| {
            let d = derivs[order as usize].interval().expect("continuous");
            (!d.contains(0.0)).then_some(NonzeroDerivative {
                order,
                enclosure: [d.inf(), d.sup()],
            })
        })
    } else {
        None
    };
    let signs = match (
        signed_point(f, lo, below, hi - lo),
        signed_point(f, hi, above, hi - lo),
    ) {
        (Some(p), Some(q)) => {
            let span = Interval::try_from((p.0, q.0)).expect("ordered");
            is_continuous(f.eval(DecInterval::new(span))).then_some((p, q))
        }
        _ => None,
    };
    let sign_change = signs.map(|(p, q)| (p.1.inf() > 0.0) != (q.1.inf() > 0.0));
    // Parity needs finitely many roots of finite multiplicity: a Rolle bound.
    let parity = sign_change
        .filter(|_| nonzero_derivative.is_some())
        .map(|c| if c { Parity::Odd } else { Parity::Even });
    let counts = nonzero_derivative.map(|d| {
        (0..=d.order)
            .filter(|n| match parity {
                Some(Parity::Odd) => n % 2 == 1,
                Some(Parity::Even) => n % 2 == 0,
                None => true,
            })
            .collect()
    });
    Cluster {
        lo,
        hi,
        members,
        nonzero_derivative,
        sign_change,
        parity,
        sign_points: signs.map(|(p, q)| [p.0, q.0]),
        sign_values: signs.map(|(p, q)| [p.1, q.1].map(|y| [y.inf(), y.sup()])),
        counts,
    }
}

/// A point between `from` and `limit` (the root-free side of the hull),
/// stepping away from `from` by `width`, 2·`width`, …, where `f` has a proved
/// sign; with that enclosure.
fn signed_point<F: RealFn>(f: &F, from: f64, limit: f64, width: f64) -> Option<(f64, Interval)> {
    let mut step = width.max(f64::MIN_POSITIVE);
    for _ in 0..64 {
        let x = if limit < from {
            (from - step).max(limit)
        } else {
            (from + step).min(limit)
        };
        let y = f.eval(DecInterval::new(point(x)));
        if is_defined(y) {
            let y = y.interval().expect("defined");
            if !y.contains(0.0) {
                return Some((x, y));
            }
        }
        if x == limit || !x.is_finite() {
            return None;
        }
        step *= 2.0;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::number::scalar::Scalar;
    use crate::roots::isolate::UndecidedReason::Tolerance;

    /// x − 1: one simple root at 1.
    struct Line;
    impl RealFn for Line {
        fn eval<T: Scalar>(&self, x: T) -> T {
            x - T::int(1)
        }
    }

    /// (x − 1)² + 1: no real root, f'' = 2.
    struct Above;
    impl RealFn for Above {
        fn eval<T: Scalar>(&self, x: T) -> T {
            (x - T::int(1)).sqr() + T::int(1)
        }
    }

    fn und(lo: f64, hi: f64) -> RootEnclosure {
        RootEnclosure::undecided(lo, hi, Tolerance)
    }

    #[test]
    fn small_gaps_merge_wide_gaps_and_unique_roots_separate() {
        let e = 2f64.powi(-40);
        let roots = [
            und(0.5, 0.5 + e),
            // gap 100 e > 16·(e + 5 e), the group it would join: stays apart
            und(0.5 + 101.0 * e, 0.5 + 102.0 * e),
            // gap 3 e ≤ 16·(e + e): merges with the previous one
            und(0.5 + 105.0 * e, 0.5 + 106.0 * e),
            RootEnclosure::unique(point(0.75)),
            // adjacent to the previous undecided one but past a unique root
            und(0.75 + e, 0.75 + 2.0 * e),
        ];
        let c = clusters(&Line, &roots, [0.0, 2.0]);
        let members: Vec<_> = c.iter().map(|c| c.members.clone()).collect();
        assert_eq!(members, vec![vec![0], vec![1, 2], vec![4]]);
        assert_eq!((c[1].lo, c[1].hi), (0.5 + 101.0 * e, 0.5 + 106.0 * e));
    }

    #[test]
    fn a_sign_change_with_a_nonzero_slope_is_exactly_one_root() {
        let c = clusters(&Line, &[und(0.75, 1.25)], [0.0, 2.0]);
        let d = c[0].nonzero_derivative.expect("f' = 1");
        assert_eq!((d.order, d.enclosure), (1, [1.0, 1.0]));
        assert_eq!(c[0].parity, Some(Parity::Odd));
        assert_eq!(c[0].counts, Some(vec![1]));
        assert_eq!(c[0].count_text(), "exactly 1 root");
    }

    #[test]
    fn one_sign_and_a_nonzero_curvature_is_zero_or_two_roots() {
        let c = clusters(&Above, &[und(0.75, 1.25)], [0.0, 2.0]);
        let d = c[0].nonzero_derivative.expect("f'' = 2");
        assert_eq!((d.order, d.enclosure), (2, [2.0, 2.0]));
        assert_eq!(c[0].counts, Some(vec![0, 2]));
        // one hull width out: f(0.25) = f(1.75) = 1.5625 > 0
        assert_eq!(c[0].sign_points, Some([0.25, 1.75]));
        assert_eq!(c[0].sign_values, Some([[1.5625, 1.5625]; 2]));
    }
}
