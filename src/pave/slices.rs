//! `slices`: the contraction with θ-only refinement: an adaptive 1-D
//! subdivision in θ that equidistributes the undecided area (a slab is
//! split while the band its quadratics' end-point roots predict is above
//! ε² of the domain's area), then one contraction per final slab whose cuts
//! are placed at those roots and verified by the monotone test.
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
use super::{ConstraintSet, PerConstraint, PhaseBox, SlabEnds, MAX_CONSTRAINTS};
use std::cell::Cell;
use std::sync::atomic::{AtomicU64, Ordering};

/// Steering coefficients at one θ.
type SteerAt = Option<PerConstraint<[f64; 3]>>;

/// Numbers each paving's steering apart, for [`LAST_STEER`].
static STEERINGS: AtomicU64 = AtomicU64::new(0);

thread_local! {
    /// The steering coefficients this thread computed last: (paving, θ's
    /// bits, value). A box's lower θ-end is mostly the upper end of the box
    /// before it in the level, computed just before.
    static LAST_STEER: Cell<(u64, u64, SteerAt)> = const { Cell::new((u64::MAX, 0, None)) };
}

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
    /// This paving's number in [`LAST_STEER`].
    steering: u64,
}

impl<'a, S: ConstraintSet> Slices<'a, S> {
    pub fn new(scope: Scope<'a, S>, root: PhaseBox, eps: f64) -> Self {
        Slices {
            scope,
            min_width: eps * (root.theta[1] - root.theta[0]) * eps,
            slab_area: eps.powi(2)
                * (root.theta[1] - root.theta[0])
                * (root.theta_dot[1] - root.theta_dot[0]),
            min_height: eps * (root.theta_dot[1] - root.theta_dot[0]),
            steering: STEERINGS.fetch_add(1, Ordering::Relaxed),
        }
    }

    /// [`ConstraintSet::steer_at`], reusing this thread's last value at
    /// the same θ.
    fn steer_at(&self, t: f64) -> SteerAt {
        let key = (self.steering, t.to_bits());
        let (id, bits, last) = LAST_STEER.get();
        if (id, bits) == key {
            return last;
        }
        let now = self.scope.set.steer_at(t);
        LAST_STEER.set((key.0, key.1, now));
        now
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

    /// Slabs are refined while their undecided area is above the threshold
    /// (equidistributed), down to the width floor.
    fn wide(&self, b: &PhaseBox) -> bool {
        let (h, k) = (b.theta[1] - b.theta[0], b.theta_dot[1] - b.theta_dot[0]);
        h > self.min_width && h * k > self.slab_area
    }

    /// An estimate (steering only) of the undecided area a fresh slab would
    /// leave, from the roots of its quadratics in f64 at θ's two ends and
    /// middle; the full box where their number changes.
    fn estimated_band(&self, b: &PhaseBox) -> f64 {
        let [t0, t1] = b.theta;
        let [w0, w1] = b.theta_dot;
        let full = (t1 - t0) * (w1 - w0);
        // At most two roots per constraint, at each of the three points.
        let mut per_end = [[0.0f64; 2 * MAX_CONSTRAINTS]; 3];
        let mut count = [0usize; 3];
        for (k, t) in [t0, 0.5 * t0 + 0.5 * t1, t1].into_iter().enumerate() {
            let Some(qs) = self.steer_at(t) else {
                return full;
            };
            for i in self.scope.relevant_own() {
                if let Some(&[c2, c1, c0]) = qs.get(i) {
                    for r in roots(c2, c1, c0).filter(|r| w0 < *r && *r < w1) {
                        per_end[k][count[k]] = r;
                        count[k] += 1;
                    }
                }
            }
            per_end[k][..count[k]].sort_by(f64::total_cmp);
        }
        let n = count[0];
        if count.iter().any(|&c| c != n) {
            return full;
        }
        let band: f64 = (0..n)
            .map(|j| {
                let r = per_end.iter().map(|e| e[j]);
                r.clone().fold(f64::NEG_INFINITY, f64::max) - r.fold(f64::INFINITY, f64::min)
            })
            .sum();
        band * (t1 - t0)
    }
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
    /// band is above the threshold.
    fn split_unevaluated(&self, b: &PhaseBox) -> bool {
        self.choose_axis(b).is_some() && self.estimated_band(b) > self.slab_area
    }

    fn subtree(
        &self,
        o: &Open<S::Slab>,
        slab: &S::Slab,
        ends: Option<PerConstraint<SlabEnds>>,
        _labels: &Labels,
        work: &mut Work,
    ) -> Option<Vec<Local>> {
        // (A slab still too coarse was split before this.)
        let t = contract_fresh(
            &self.scope,
            |b| {
                self.choose_axis(b).is_some()
                    || (self.in_column(b) && self.leading_may_vanish(slab))
            },
            o,
            slab,
            ends,
            work,
        );
        if t.is_some() || !self.in_column(&o.bx) {
            return t;
        }
        // A column the contraction removes nothing from: the part as one
        // leaf if the slab's tests decide it, else its two halves in θ̇
        // (they share the slab).
        let ends = ends.or_else(|| {
            work.slabs += 3;
            self.scope.set.slab_ends(o.bx.theta_interval())
        });
        let labels = self.scope.label(slab, ends.as_deref(), &o.bx, work, true);
        let all = self.scope.relevant;
        Some(if self.scope.decided_mask(&labels) & all == all {
            vec![Local::Leaf(labels)]
        } else {
            vec![Local::Mid(1), Local::Open, Local::Open]
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pave::SceneConstraints;
    use crate::scene::{Scene, SceneId, Variant};

    fn slices<'a>(set: &'a SceneConstraints<'a>) -> Slices<'a, SceneConstraints<'a>> {
        let scope = Scope {
            set,
            n: 2,
            same_as: vec![None, None],
            relevant: 0b11,
        };
        let root = PhaseBox {
            theta: [-3.0, 3.0],
            theta_dot: [-10.0, 10.0],
        };
        Slices::new(scope, root, 1e-3)
    }

    /// Two pavings steering on one thread at the same θ each get their own
    /// scene's coefficients, reused or not.
    #[test]
    fn the_reused_steering_is_the_pavings_own() {
        let (viscous, smooth) = (
            Scene::default_of(SceneId::ViscousDisc),
            Scene::default_of(SceneId::SmoothDisc),
        );
        let sets = [&viscous, &smooth].map(|scene| SceneConstraints {
            scene,
            variant: Variant::Derived,
        });
        let [a, b] = [slices(&sets[0]), slices(&sets[1])];
        let coefficients = |s: SteerAt| s.map(|q| q.to_vec());
        for t in [0.3, 0.3, 1.1, 0.3] {
            for s in [&a, &b, &b, &a] {
                let direct = coefficients(s.scope.set.steer_at(t));
                assert!(direct.is_some());
                assert_eq!(coefficients(s.steer_at(t)), direct, "θ = {t}");
            }
        }
        assert_ne!(coefficients(a.steer_at(0.3)), coefficients(b.steer_at(0.3)));
    }
}
