//! `centred`: natural ∩ mean-value form ∩ monotonicity in θ̇ (and, where
//! bisection stops at the resolution, the coefficients' mean-value form in
//! θ); a box these decide is certified by a small local subdivision. The
//! centred enclosures only steer: every leaf's label is natural.

use super::bisection::Bisection;
use super::certify::{certify, CERTIFY_LEAVES};
use super::engine::Refine;
use super::labels::{centred_label, Labels, Scope};
use super::level::{Local, Open, Work};
use super::{ConstraintSet, Label, SlabEnds};

/// Natural labels, certified where a centred form decides.
pub(super) struct Centred<'a, S: ConstraintSet> {
    pub scope: Scope<'a, S>,
    pub grid: Bisection,
}

impl<S: ConstraintSet> Refine<S> for Centred<'_, S> {
    fn scope(&self) -> &Scope<'_, S> {
        &self.scope
    }
    fn grid(&self) -> Option<&Bisection> {
        Some(&self.grid)
    }

    /// When natural ∩ mean-value ∩ monotonicity decides every relevant
    /// constraint (or, at the resolution, some), certify it.
    fn subtree(
        &self,
        o: &Open<S::Slab>,
        slab: &S::Slab,
        _ends: Option<&[SlabEnds]>,
        labels: &Labels,
        work: &mut Work,
        out: &mut Vec<Local>,
    ) -> bool {
        self.certified(o, slab, labels, work)
            .map(|t| out.extend(t))
            .is_some()
    }
}

impl<S: ConstraintSet> Centred<'_, S> {
    /// The certified subtree [`Refine::subtree`] appends, if any.
    fn certified(
        &self,
        o: &Open<S::Slab>,
        slab: &S::Slab,
        labels: &Labels,
        work: &mut Work,
    ) -> Option<Vec<Local>> {
        let (scope, b) = (&self.scope, &o.bx);
        let w = b.theta_dot_interval();
        let at_resolution = self.grid.choose_axis(b).is_none();
        let mut gained = 0u8;
        for i in scope.own() {
            if labels[i] != Label::Undecided {
                continue;
            }
            let q = scope.set.quadratic(slab, i)?;
            // Without a θ̇ term, θ̇ occurs once: natural is already exact in θ̇.
            let no_w_term =
                q.c1.interval()
                    .is_some_and(|c| c.inf() == 0.0 && c.sup() == 0.0);
            if !no_w_term && centred_label(&q, w).is_decided() {
                gained |= 1 << i;
            }
        }
        gained = scope.with_copies(gained);
        let all = (scope.decided_mask(labels) | gained) & scope.relevant == scope.relevant;
        if gained & scope.relevant != 0 && (all || at_resolution) {
            let mut budget = CERTIFY_LEAVES;
            let wanted = gained & scope.relevant;
            if let Some(t) = certify(scope, b, slab, None, wanted, &mut budget, work, false) {
                return Some(t);
            }
        }
        if !at_resolution {
            return None;
        }
        // At the resolution, where bisection stops: the coefficients by their
        // mean-value form in θ (dual-number gradient), then certified by
        // splitting θ and θ̇ below the resolution.
        work.slabs += 2;
        let cc = scope.set.centred_coefficients(b.theta_interval())?;
        let mut gained = 0u8;
        for i in scope.own() {
            if labels[i] == Label::Undecided && centred_label(cc.get(i)?, w).is_decided() {
                gained |= 1 << i;
            }
        }
        let wanted = scope.with_copies(gained) & scope.relevant;
        if wanted == 0 {
            return None;
        }
        let mut budget = CERTIFY_LEAVES;
        certify(scope, b, slab, None, wanted, &mut budget, work, true)
    }
}
