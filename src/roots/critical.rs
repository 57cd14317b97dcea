//! The critical curve κ_crit(α) of (2.9), α ∈ [0, 1], and a certified atlas of
//! the (α, κ) plane.
//!
//! With `s = tan(θ/2)`, (2.9) reads `κ = G(s, α)`,
//! `G = f_r/sin³θ = (1 − s²)(e² s⁴ − d²)/(8 s³)`, `d = 1 − α`, `e = 1 + α`.
//!
//! **Unimodality lemma** (α ∈ [0, 1]): `8 s⁴ G'(s) = q(s²)`,
//! `q(u) = e² u²(1 − 3u) + d²(3 − u)`. On (0, 1/3] both terms are ≥ 0 and
//! not both 0 (q > 0 on (0, 1/3) — also at α = 1); on [1/3, 3]
//! `q'(u) = e² u(2 − 9u) − d² < 0`; on [3, ∞) both terms are ≤ 0, the first
//! < 0. So q has exactly one positive root u_c, G' > 0 on (0, √u_c) and
//! G' < 0 beyond: G is strictly unimodal on (0, ∞), with maximum
//! κ_crit(α) = G(√u_c, α). Limits: G → −∞ as s → 0+ when α < 1 (→ 0 when
//! α = 1) and as s → ∞; G(1, α) = 0, so κ_crit ≥ 0.
//!
//! Hence, for κ > 0: κ > κ_crit(α) ⇒ no root; κ < κ_crit(α) ⇒ exactly two
//! roots, one on each monotone branch, both simple (`P(s) = 8s³(κ − G)`,
//! `P' = −8 s³ G' ≠ 0` there). For α = 1 this is (2.10) and κ_crit(1) = κ₀.
//!
//! **Monotonicity in α**: `∂G/∂α = (1 − s²)(2e s⁴ + 2d)/(8 s³) ≥ 0` for
//! s ∈ (0, 1], α ∈ [0, 1]; and G ≤ 0 for s ≥ 1. So κ_crit is non-decreasing
//! and on an α-box [α₁, α₂]: `κ_crit(α₁) ≤ κ_crit(α) ≤ κ_crit(α₂)`.
//! κ_crit(α₁) is bounded below by `G(s₀, α₁)` at chosen points s₀ (and by
//! 0 = G(1, α₁)), evaluated in intervals; κ_crit(α₂) above by branch and bound
//! over s-boxes of [0, 1] with the natural and mean-value forms and
//! `G ≤ (1 − s²) e² s/8` (valid on (0, 1], bounded as s → 0).

use super::isolate::point;
use super::kappa0::{prove_kappa0, Bound};
use crate::number::scalar::{Dual, Scalar};
use inari::{const_interval, Interval};
use serde::Serialize;

/// `G(s, α)` generic in s, with α an enclosure.
pub fn g<T: Scalar>(s: T, alpha: Interval) -> T {
    let a = T::lift(alpha);
    let (d, e) = (T::int(1) - a, T::int(1) + a);
    let s2 = s.sqr();
    (T::int(1) - s2) * (e.sqr() * s2.sqr() - d.sqr()) / (T::int(8) * s2 * s)
}

/// Upper enclosure of sup G over `s ∈ S ⊂ [0, 1]`, `α ∈ A`: the natural
/// extension ∩ the mean-value form ∩ the bound `(1 − s²) e² s/8`.
fn g_sup(s: Interval, alpha: Interval) -> f64 {
    let one = const_interval!(1.0, 1.0);
    let e = one + alpha;
    let bound = ((one - s.sqr()) * e.sqr() * s / const_interval!(8.0, 8.0)).sup();
    if s.inf() <= 0.0 {
        return bound;
    }
    let natural = g(s, alpha);
    let m = point(s.mid());
    let dual = g(Dual::variable(s, 0), alpha);
    let mean_value = g(m, alpha) + dual.grad[0] * (s - m);
    let v = natural.intersection(mean_value);
    if v.is_empty() {
        bound
    } else {
        v.sup().min(bound)
    }
}

/// A certified band for κ_crit on one α-box.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct BandCell {
    pub alpha: Bound,
    /// `lower ≤ κ_crit(α) ≤ upper` for every α in the box.
    pub lower: f64,
    pub upper: f64,
    /// sup of q' over u ∈ [1/3, 3] (< 0 confirms the unimodality lemma).
    pub lemma_q_prime_sup: f64,
    pub lemma_ok: bool,
    pub boxes: usize,
}

/// Band on one α-box.
pub fn band_cell(alpha: Interval, s_tol: f64) -> BandCell {
    let one = const_interval!(1.0, 1.0);
    // Lower bounds: maximise G(·, α) in f64 (steering only), then evaluate
    // G in intervals at the points found. G(1, α) = 0 gives 0.
    let a1 = point(alpha.inf());
    let a2 = point(alpha.sup());
    let lower_at = |a: Interval| {
        let gf = |s: f64| g(s, point(a.inf()));
        let (mut lo_s, mut hi_s) = (1e-3, 1.0);
        for _ in 0..100 {
            let m1 = lo_s + (hi_s - lo_s) / 3.0;
            let m2 = hi_s - (hi_s - lo_s) / 3.0;
            if gf(m1) < gf(m2) {
                lo_s = m1;
            } else {
                hi_s = m2;
            }
        }
        let mut lower = g(point(1.0), a).inf().max(0.0);
        for s in [0.5 * (lo_s + hi_s), 0.5, 0.577, 0.75, 0.9] {
            lower = lower.max(g(point(s), a).inf());
        }
        lower
    };
    let lower = lower_at(a1);
    // Upper bound of κ_crit(α₂): branch and bound over s ∈ [0, 1]; boxes
    // whose bound is at most a proved lower bound of κ_crit(α₂) are dropped.
    let threshold = lower_at(a2);
    let mut upper = threshold;
    let mut stack = vec![Interval::try_from((0.0, 1.0)).expect("valid")];
    let mut boxes = 0;
    while let Some(s) = stack.pop() {
        boxes += 1;
        let ub = g_sup(s, a2);
        if ub <= threshold {
            continue;
        }
        if s.wid() <= s_tol || boxes > 1_000_000 {
            upper = upper.max(ub);
            continue;
        }
        let m = super::isolate::split_point(s.inf(), s.sup());
        stack.push(Interval::try_from((s.inf(), m)).expect("valid"));
        stack.push(Interval::try_from((m, s.sup())).expect("valid"));
    }
    // Lemma check: q'(u) = e² u (2 − 9u) − d² < 0 on [1/3, 3].
    let u = Interval::try_from((1.0, 9.0)).expect("valid") / point(3.0);
    let (d, e) = (one - alpha, one + alpha);
    let qp = e.sqr() * u * (point(2.0) - point(9.0) * u) - d.sqr();
    BandCell {
        alpha: Bound::of(alpha),
        lower,
        upper,
        lemma_q_prime_sup: qp.sup(),
        lemma_ok: qp.sup() < 0.0 && alpha.inf() >= 0.0 && alpha.sup() <= 1.0,
        boxes,
    }
}

/// What is proved on one (α, κ) box about (2.9) on θ ∈ (0, π).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum AtlasLabel {
    /// No root for every (α, κ) of the box: κ > upper bound of κ_crit.
    NoRoot,
    /// Exactly two roots, both simple: 0 < κ < lower bound of κ_crit.
    TwoSimpleRoots,
    Undecided,
}

#[derive(Clone, Copy, Debug, Serialize)]
pub struct AtlasBox {
    pub alpha: [f64; 2],
    pub kappa: [f64; 2],
    pub label: AtlasLabel,
}

/// The band, the atlas and the cross-check with κ₀.
#[derive(Clone, Debug, Serialize)]
pub struct CriticalCurve {
    pub lemma: &'static str,
    pub band: Vec<BandCell>,
    pub max_band_width: f64,
    /// The band at α = 1 exactly, and whether it contains κ₀'s enclosure.
    pub at_alpha_1: BandCell,
    pub kappa0: Bound,
    pub kappa0_inside_band_at_1: bool,
    pub kappa_max: f64,
    pub atlas: Vec<AtlasBox>,
    pub counts: AtlasCounts,
}

#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct AtlasCounts {
    pub no_root: usize,
    pub two_simple_roots: usize,
    pub undecided: usize,
}

pub const LEMMA: &str = "8s⁴G'(s) = q(s²), q(u) = e²u²(1−3u) + d²(3−u): q > 0 on (0, 1/3), \
    q' < 0 on [1/3, 3] (checked per α-box), q < 0 on [3, ∞): G is strictly unimodal in s > 0, \
    so κ > κ_crit(α) ⇒ no root, 0 < κ < κ_crit(α) ⇒ exactly two simple roots";

/// The top of the κ range from decimal text: the largest double not above
/// it, so the grid stays inside the range asked; `None` unless that double
/// is positive.
pub fn kappa_max_below(text: &str) -> Result<Option<f64>, crate::number::param::ParamError> {
    let k = crate::number::param::enclose_decimal("kappa_max", text)?;
    Ok((k.inf() > 0.0).then_some(k.inf()))
}

/// Computes the band on `n_alpha` α-boxes of [0, 1] and the atlas with
/// `n_kappa` κ-boxes of (0, κ_max]. Both counts should be powers of two
/// (exact box edges).
pub fn critical_curve(n_alpha: usize, n_kappa: usize, kappa_max: f64) -> CriticalCurve {
    let s_tol = 1e-7;
    let edge = |i: usize| i as f64 / n_alpha as f64;
    let band: Vec<BandCell> = (0..n_alpha)
        .map(|i| {
            band_cell(
                Interval::try_from((edge(i), edge(i + 1))).expect("valid"),
                s_tol,
            )
        })
        .collect();
    let max_band_width = band.iter().map(|c| c.upper - c.lower).fold(0.0, f64::max);
    let at_alpha_1 = band_cell(point(1.0), 1e-9);
    let k0 = prove_kappa0();
    let kk = k0.kappa0.interval();
    let kappa0_inside_band_at_1 = at_alpha_1.lower <= kk.inf() && kk.sup() <= at_alpha_1.upper;
    let mut atlas = Vec::with_capacity(n_alpha * n_kappa);
    let mut counts = AtlasCounts::default();
    for c in &band {
        for j in 0..n_kappa {
            let (k_lo, k_hi) = (
                kappa_max * j as f64 / n_kappa as f64,
                kappa_max * (j + 1) as f64 / n_kappa as f64,
            );
            let label = if !c.lemma_ok {
                AtlasLabel::Undecided
            } else if k_lo > c.upper {
                AtlasLabel::NoRoot
            } else if k_hi < c.lower {
                // κ ∈ (0, k_hi] (κ > 0 by definition, also in the first box)
                AtlasLabel::TwoSimpleRoots
            } else {
                AtlasLabel::Undecided
            };
            match label {
                AtlasLabel::NoRoot => counts.no_root += 1,
                AtlasLabel::TwoSimpleRoots => counts.two_simple_roots += 1,
                AtlasLabel::Undecided => counts.undecided += 1,
            }
            atlas.push(AtlasBox {
                alpha: [c.alpha.lo, c.alpha.hi],
                kappa: [k_lo, k_hi],
                label,
            });
        }
    }
    CriticalCurve {
        lemma: LEMMA,
        band,
        max_band_width,
        at_alpha_1,
        kappa0: k0.kappa0,
        kappa0_inside_band_at_1,
        kappa_max,
        atlas,
        counts,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::roots::{solve_2_9, Budget};

    #[test]
    fn band_at_alpha_one_contains_kappa0() {
        // κ_crit(1) = κ₀ = √3/9 (closed form of (2.10)).
        let c = band_cell(point(1.0), 1e-9);
        let k0 = point(3.0).sqrt() / point(9.0);
        assert!(c.lower <= k0.inf() && k0.sup() <= c.upper, "{c:?}");
        assert!(c.upper - c.lower < 1e-8, "{c:?}");
    }

    #[test]
    fn band_agrees_with_the_isolator() {
        // Independent check by isolation of (2.9) itself on either side of the band.
        let a = Interval::try_from((0.5, 0.5)).unwrap();
        let c = band_cell(a, 1e-7);
        assert!(c.lemma_ok);
        let below = point(c.lower * 0.99);
        let above = point(c.upper * 1.01);
        let r = solve_2_9(below, a, &Budget::default()).unwrap();
        assert!(r.complete && r.roots.len() == 2, "{r:?}");
        let r = solve_2_9(above, a, &Budget::default()).unwrap();
        assert!(r.complete && r.roots.is_empty(), "{r:?}");
    }

    #[test]
    fn small_atlas_is_consistent() {
        let cc = critical_curve(16, 16, 0.25);
        assert!(cc.kappa0_inside_band_at_1);
        assert!(cc.band.iter().all(|c| c.lemma_ok && c.lower <= c.upper));
        // κ_crit increases with α (∂G/∂α > 0 for s < 1): the bands must allow it.
        for w in cc.band.windows(2) {
            assert!(w[0].lower <= w[1].upper);
        }
        assert!(cc.counts.no_root > 0 && cc.counts.two_simple_roots > 0);
    }
}
