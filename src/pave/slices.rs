//! `slices`: the contraction with θ-only refinement: an adaptive 1-D
//! subdivision in θ that equidistributes the undecided area (a slab is
//! split while the band its quadratics' end-point roots predict is above
//! ε² of the domain's area), then one contraction per final slab whose cuts
//! are placed at those roots and verified by the monotone test.

use super::contract::{contract_fresh, roots};
use super::engine::{Local, Open, Refine, Work};
use super::labels::{Labels, Scope};
use super::{ConstraintSet, PerConstraint, PhaseBox, SlabEnds, MAX_CONSTRAINTS};
use std::sync::Arc;

/// Adaptive θ-slabs, each contracted in θ̇.
pub(super) struct Slices<'a, S: ConstraintSet> {
    pub scope: Scope<'a, S>,
    /// The width floor in θ (ε² of the domain's, which bounds the depth at
    /// vertical tangents); θ̇ is never bisected.
    pub min_width: f64,
    /// The undecided area per slab it refines down to.
    pub slab_area: f64,
}

impl<'a, S: ConstraintSet> Slices<'a, S> {
    pub fn new(scope: Scope<'a, S>, root: PhaseBox, eps: f64) -> Self {
        Slices {
            scope,
            min_width: eps * (root.theta[1] - root.theta[0]) * eps,
            slab_area: eps.powi(2)
                * (root.theta[1] - root.theta[0])
                * (root.theta_dot[1] - root.theta_dot[0]),
        }
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
            let Some(qs) = self.scope.set.steer_at(t) else {
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
        slab: &Arc<S::Slab>,
        ends: Option<PerConstraint<SlabEnds>>,
        _labels: &Labels,
        work: &mut Work,
    ) -> Option<Vec<Local>> {
        // (A slab still too coarse was split before this.)
        contract_fresh(
            &self.scope,
            |b| self.choose_axis(b).is_some(),
            o,
            slab,
            ends,
            work,
        )
    }
}
