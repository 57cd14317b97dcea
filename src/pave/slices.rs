//! `slices`: the contraction with θ-only refinement: an adaptive 1-D
//! subdivision in θ that equidistributes the undecided area (a slab whose
//! quadratics' roots predict a band above ε² of the domain's area is cut
//! into about as many parts as that band needs, [`parts`]), then one
//! contraction per final slab whose cuts are placed at those roots and
//! verified by the monotone test.
//!
//! A slab at the width floor that the contraction removes nothing from (a
//! vertical line where a quadratic's θ̇² coefficient is 0, as θ = π/2 for
//! `cos(θ)·(θ̇² + g·cos(θ))`, or where its two roots meet) would stay one
//! undecided column of the full height; it is bisected in θ̇ instead, each
//! part labelled by the natural, then the monotone and convex tests, down
//! to ε of the domain's height, as `natural` refines. So is what the
//! contraction leaves undecided on a slab where a θ̇² coefficient may be 0.

use super::bisection::Bisection;
use super::contract::{contract_fresh, roots};
use super::engine::Refine;
use super::labels::{Labels, Scope};
use super::level::{Local, Open, Work};
use super::{ConstraintSet, PhaseBox, SlabEnds, MAX_CONSTRAINTS};

/// Adaptive θ-slabs, each contracted in θ̇.
pub(super) struct Slices<'a, S: ConstraintSet> {
    pub scope: Scope<'a, S>,
    /// The width floor in θ (ε² of the domain's, which bounds the depth at
    /// vertical tangents); θ̇ is never bisected.
    pub min_width: f64,
    /// The undecided area per slab it refines down to.
    pub slab_area: f64,
    /// The height floor of θ̇-bisection in a column (ε of the domain's).
    pub min_height: f64,
}

/// The roots of the relevant quadratics at one θ inside a θ̇-window,
/// sorted, in f64 (steering only); `None` where the set has no
/// coefficients there.
type RootsAt = Option<([f64; 2 * MAX_CONSTRAINTS], usize)>;

impl<'a, S: ConstraintSet> Slices<'a, S> {
    pub fn new(scope: Scope<'a, S>, root: PhaseBox, eps: f64) -> Self {
        Slices {
            scope,
            min_width: eps * (root.theta[1] - root.theta[0]) * eps,
            slab_area: eps.powi(2)
                * (root.theta[1] - root.theta[0])
                * (root.theta_dot[1] - root.theta_dot[0]),
            min_height: eps * (root.theta_dot[1] - root.theta_dot[0]),
        }
    }

    /// A box that θ-refinement has left (its slab at the width floor) and
    /// that is still above the height floor: bisected in θ̇ if undecided.
    fn in_column(&self, b: &PhaseBox) -> bool {
        self.choose_axis(b).is_none()
            && b.theta_dot[1] - b.theta_dot[0] > self.min_height
            && b.can_split(1)
    }

    /// A relevant quadratic's θ̇² coefficient may be 0 on the slab.
    fn leading_may_vanish(&self, slab: &S::Slab) -> bool {
        self.scope.relevant_own().any(|i| {
            self.scope
                .set
                .quadratic(slab, i)
                .is_some_and(|q| q.c2.interval().is_none_or(|c| c.contains(0.0)))
        })
    }

    /// Some relevant quadratic's coefficients are continuous on the slab.
    /// Otherwise the monotone and convex tests do not apply (they need the
    /// value continuous, [`super::SlabEnds::smooth`], whose decorations are
    /// the slab's: the same operations), and a column's parts, as those
    /// where a coefficient is undefined, are labelled without the slab's
    /// end data, which each part would compute again.
    fn some_continuous(&self, slab: &S::Slab) -> bool {
        self.scope.relevant_own().any(|i| {
            self.scope
                .set
                .quadratic(slab, i)
                .is_some_and(|q| q.is_continuous())
        })
    }

    /// Slabs are refined while their undecided area is above the threshold
    /// (equidistributed), down to the width floor.
    fn wide(&self, b: &PhaseBox) -> bool {
        let (h, k) = (b.theta[1] - b.theta[0], b.theta_dot[1] - b.theta_dot[0]);
        h > self.min_width && h * k > self.slab_area
    }

    /// The relevant quadratics' roots at `t` strictly inside `w`.
    fn roots_at(&self, t: f64, w: [f64; 2]) -> RootsAt {
        let qs = self.scope.set.steer_at(t)?;
        let mut at = [0.0f64; 2 * MAX_CONSTRAINTS];
        let mut n = 0;
        for i in self.scope.relevant_own() {
            if let Some(&[c2, c1, c0]) = qs.get(i) {
                for r in roots(c2, c1, c0).filter(|r| w[0] < *r && *r < w[1]) {
                    at[n] = r;
                    n += 1;
                }
            }
        }
        at[..n].sort_by(f64::total_cmp);
        Some((at, n))
    }

    /// A fresh slab's θ-division before interval work, depth-first, down
    /// `depth` more levels: a slab that can still be split and whose
    /// predicted undecided band ([`estimated_band`]) is above the threshold
    /// is split into the [`parts`] it needs, each part predicted to need
    /// one slab kept as it is; `lo` and `hi` are the roots at its ends.
    fn divide(&self, b: &PhaseBox, lo: &RootsAt, hi: &RootsAt, depth: u32, out: &mut Vec<Local>) {
        if self.choose_axis(b).is_none() {
            out.push(Local::Settled);
            return;
        }
        let m = b.midpoint(0);
        let mid = self.roots_at(m, b.theta_dot);
        let band = estimated_band(b, [lo, &mid, hi]);
        if band <= self.slab_area {
            out.push(Local::Settled);
            return;
        }
        let [j, k] = parts(band / self.slab_area);
        let off_centre = (2.0 * j != k)
            .then(|| b.theta[0] + (b.theta[1] - b.theta[0]) * (j / k))
            .and_then(|p| Some((p, b.split_at(0, p)?)))
            .filter(|&(p, _)| p != m);
        let (at, (l, h)) = match off_centre {
            Some((p, halves)) => {
                out.push(Local::At(0, p));
                (self.roots_at(p, b.theta_dot), halves)
            }
            None => {
                out.push(Local::Mid(0));
                (mid, b.split(0))
            }
        };
        for (part, [lo, hi], n) in [(l, [lo, &at], j), (h, [&at, hi], k - j)] {
            if n <= 1.0 {
                out.push(Local::Settled);
            } else if depth == 0 {
                out.push(Local::Open);
            } else {
                self.divide(&part, lo, hi, depth - 1, out);
            }
        }
    }
}

/// How a slab whose predicted band is `ratio` (> 1) times the threshold
/// is divided: into k = ⌈√ratio⌉ slabs of about the threshold's band (the
/// band grows as the width squared), split after the first j = ⌊k/2⌋ of
/// k equal parts (the midpoint for even k). `[j, k]`. Where halving alone
/// would leave some slabs at a quarter of the threshold, these stay near
/// it, so fewer slabs reach the same undecided area.
fn parts(ratio: f64) -> [f64; 2] {
    let k = ratio.sqrt().ceil();
    [(k / 2.0).floor(), k]
}

/// An estimate (steering only) of the undecided area of slab `b`, from
/// the roots of its quadratics at θ's two ends and middle: the spread of
/// each root times the width; the full box where their number changes.
fn estimated_band(b: &PhaseBox, at: [&RootsAt; 3]) -> f64 {
    let [t0, t1] = b.theta;
    let full = (t1 - t0) * (b.theta_dot[1] - b.theta_dot[0]);
    let [Some((a, n)), Some((m, nm)), Some((z, nz))] = at else {
        return full;
    };
    if nm != n || nz != n {
        return full;
    }
    let band: f64 = (0..*n)
        .map(|j| {
            let r = [a[j], m[j], z[j]];
            r.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                - r.iter().copied().fold(f64::INFINITY, f64::min)
        })
        .sum();
    band * (t1 - t0)
}

impl<S: ConstraintSet> Refine<S> for Slices<'_, S> {
    /// Each fresh slab is computed with its end data, for the monotone test.
    const SHARED_SLABS: bool = false;

    fn scope(&self) -> &Scope<'_, S> {
        &self.scope
    }

    /// None: slabs are refined by their undecided area, not on a grid.
    fn grid(&self) -> Option<&Bisection> {
        None
    }

    /// θ only.
    fn choose_axis(&self, b: &PhaseBox) -> Option<u8> {
        (self.wide(b) && b.can_split(0)).then_some(0)
    }

    fn at_ulp_limit(&self, b: &PhaseBox) -> bool {
        self.wide(b) && !b.can_split(0)
    }

    /// A fresh slab that can still be split and whose predicted undecided
    /// band is above the threshold, divided up to the engine's `levels`
    /// down, each split point's roots computed once.
    fn split_unevaluated(&self, b: &PhaseBox, levels: u32, out: &mut Vec<Local>) -> bool {
        if self.choose_axis(b).is_none() {
            return false;
        }
        let [lo, hi] = b.theta.map(|t| self.roots_at(t, b.theta_dot));
        let depth = levels.max(1) - 1;
        let start = out.len();
        self.divide(b, &lo, &hi, depth, out);
        let divided = matches!(out[start], Local::Mid(_) | Local::At(..));
        if !divided {
            out.truncate(start);
        }
        divided
    }

    fn subtree(
        &self,
        o: &Open<S::Slab>,
        slab: &S::Slab,
        ends: Option<&[SlabEnds]>,
        _labels: &Labels,
        work: &mut Work,
        out: &mut Vec<Local>,
    ) -> bool {
        // (A slab still too coarse was split before this.)
        let contracted = contract_fresh(
            &self.scope,
            |b| {
                self.choose_axis(b).is_some()
                    || (self.in_column(b) && self.leading_may_vanish(slab))
            },
            o,
            slab,
            ends,
            work,
            out,
        );
        if contracted || !self.in_column(&o.bx) {
            return contracted;
        }
        // A column the contraction removes nothing from: the part as one
        // leaf if the slab's tests decide it, else its two halves in θ̇
        // (they share the slab).
        let computed = (ends.is_none() && self.some_continuous(slab))
            .then(|| self.scope.slab_ends(o.bx.theta_interval(), work))
            .flatten();
        let ends = ends.or(computed.as_deref());
        let labels = self.scope.label(slab, ends, &o.bx, work, true);
        let all = self.scope.relevant;
        if self.scope.decided_mask(&labels) & all == all {
            out.push(Local::Leaf(labels));
        } else {
            out.extend([Local::Mid(1), Local::Open, Local::Open]);
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pave::SceneConstraints;
    use crate::scene::{Scene, SceneId, Variant};

    /// The rule one box at a time, every end recomputed: split while the
    /// box can be and the roots' spread over its ends and middle, times
    /// its width, is above the slab area (the full box where their number
    /// changes), into k = ⌈√(band / slab area)⌉ equal parts' first
    /// ⌊k/2⌋ and the rest; a side of one part is kept. `Local::Settled` for
    /// a box kept.
    fn reference(s: &Slices<'_, SceneConstraints<'_>>, b: &PhaseBox, out: &mut Vec<Local>) {
        let w = b.theta_dot;
        let roots_at = |t: f64| -> Option<Vec<f64>> {
            let qs = s.scope.set.steer_at(t)?;
            let mut r: Vec<f64> = s
                .scope
                .relevant_own()
                .flat_map(|i| {
                    let [c2, c1, c0] = qs.get(i).copied().expect("a constraint");
                    roots(c2, c1, c0).collect::<Vec<_>>()
                })
                .filter(|r| w[0] < *r && *r < w[1])
                .collect();
            r.sort_by(f64::total_cmp);
            Some(r)
        };
        let [t0, t1] = b.theta;
        let full = (t1 - t0) * (w[1] - w[0]);
        let ends: Option<Vec<Vec<f64>>> =
            [t0, b.midpoint(0), t1].map(roots_at).into_iter().collect();
        let band = match ends {
            Some(e) if e[1].len() == e[0].len() && e[2].len() == e[0].len() => {
                let spread = |j: usize| {
                    let r = [e[0][j], e[1][j], e[2][j]];
                    r.iter().copied().fold(f64::MIN, f64::max)
                        - r.iter().copied().fold(f64::MAX, f64::min)
                };
                (0..e[0].len()).map(spread).sum::<f64>() * (t1 - t0)
            }
            _ => full,
        };
        if s.choose_axis(b).is_none() || band <= s.slab_area {
            out.push(Local::Settled);
            return;
        }
        let k = (band / s.slab_area).sqrt().ceil() as u64;
        let j = k / 2;
        let p = t0 + (t1 - t0) * (j as f64 / k as f64);
        let (l, h) = match b.split_at(0, p) {
            Some(halves) if k % 2 == 1 && p != b.midpoint(0) => {
                out.push(Local::At(0, p));
                halves
            }
            _ => {
                out.push(Local::Mid(0));
                b.split(0)
            }
        };
        for (part, n) in [(l, j), (h, k - j)] {
            if n == 1 {
                out.push(Local::Settled);
            } else {
                reference(s, &part, out);
            }
        }
    }

    /// What the engine makes of `split_unevaluated` level by level, each
    /// allowing `levels`: its subtrees, each open box divided again at the
    /// next level. Checks that one go makes at most 2^`levels` boxes.
    fn engine_view(
        s: &Slices<'_, SceneConstraints<'_>>,
        b: &PhaseBox,
        levels: u32,
        out: &mut Vec<Local>,
    ) {
        let mut t = Vec::new();
        if !s.split_unevaluated(b, levels, &mut t) {
            out.push(Local::Settled);
            return;
        }
        let is_split = |l: &Local| matches!(l, Local::Mid(_) | Local::At(..));
        let boxes = t.iter().filter(|l| !is_split(l)).count();
        assert!(boxes <= 1 << levels, "{boxes} boxes in {levels} levels");
        fn walk(
            s: &Slices<'_, SceneConstraints<'_>>,
            t: &[Local],
            pos: &mut usize,
            b: &PhaseBox,
            levels: u32,
            out: &mut Vec<Local>,
        ) {
            let item = t[*pos];
            *pos += 1;
            match item {
                Local::Mid(0) | Local::At(0, _) => {
                    out.push(item);
                    let (l, h) = match item {
                        Local::At(_, p) => b.split_at(0, p).expect("a point inside"),
                        _ => b.split(0),
                    };
                    walk(s, t, pos, &l, levels, out);
                    walk(s, t, pos, &h, levels, out);
                }
                Local::Open => engine_view(s, b, levels, out),
                Local::Settled => out.push(item),
                other => panic!("a θ-division holds {other:?}"),
            }
        }
        walk(s, &t, &mut 0, b, levels, out);
    }

    /// Steering a box several levels at once, each split point's roots
    /// computed once, divides it exactly as the rule applied one box at a
    /// time, on every scene's Ω and Ω₀, coarse and fine, whatever depth
    /// the engine allows.
    #[test]
    fn steering_in_one_go_divides_as_box_by_box() {
        for id in SceneId::ALL {
            let scene = Scene::default_of(id);
            let set = SceneConstraints {
                scene: &scene,
                variant: Variant::Derived,
            };
            // Not the whole period: the roots at −π, 0 and π agree, so the
            // estimate keeps the whole domain as one slab (for the
            // contraction to split).
            let d = scene.domain();
            let root = PhaseBox {
                theta: [0.1, 2.9],
                theta_dot: [d.theta_dot[0].inf(), d.theta_dot[1].sup()],
            };
            for (relevant, eps) in [(0b01, 1e-2), (0b10, 1e-2), (0b11, 2e-3)] {
                let scope = Scope {
                    set: &set,
                    n: 2,
                    same_as: vec![None, None],
                    relevant,
                };
                let s = Slices::new(scope, root, eps);
                let mut want = Vec::new();
                reference(&s, &root, &mut want);
                let splits = want
                    .iter()
                    .filter(|l| matches!(l, Local::Mid(_) | Local::At(..)))
                    .count();
                assert!(
                    splits > 1 << 6,
                    "{id:?}: {splits} splits, deeper than one go"
                );
                let off_centre = want.iter().filter(|l| matches!(l, Local::At(..))).count();
                assert!(
                    off_centre > 0 && off_centre < splits,
                    "{id:?}: {off_centre} of {splits} splits off the midpoint"
                );
                let key = |t: &[Local]| format!("{t:?}");
                for levels in [1, 3, 6, 40] {
                    let mut got = Vec::new();
                    engine_view(&s, &root, levels, &mut got);
                    assert_eq!(
                        key(&got),
                        key(&want),
                        "{id:?} relevant {relevant:b} ε {eps} levels {levels}"
                    );
                }
            }
        }
    }
}
