//! Certification by local subdivision, shared by `centred` and `contract`:
//! where a steering enclosure says a box is decided, a few extra splits give
//! leaves whose labels the checker confirms.

use super::labels::{point, Scope};
use super::level::{Local, Work};
use super::{ConstraintSet, PhaseBox, SlabEnds};
use inari::DecInterval;

/// Leaves one certification may add (bounds the work on a hard box).
pub(super) const CERTIFY_LEAVES: u32 = 64;
/// The same with the monotone test at hand.
pub(super) const CERTIFY_LEAVES_MONOTONE: u32 = 8;

/// A subtree whose leaves all carry labels deciding every constraint in
/// `wanted`, by bisection within `budget` leaves. θ̇ only unless `theta`:
/// what the θ̇-centred form and the contractor prove from the slab's
/// coefficients is reached by narrowing θ̇ alone (the dependency of
/// c₂θ̇² + c₁θ̇ shrinks with the width), sharing the slab; the θ-centred
/// form needs narrower θ-slabs too.
#[allow(clippy::too_many_arguments)]
pub(super) fn certify<S: ConstraintSet>(
    scope: &Scope<'_, S>,
    b: &PhaseBox,
    slab: &S::Slab,
    ends: Option<&[SlabEnds]>,
    wanted: u8,
    budget: &mut u32,
    work: &mut Work,
    theta: bool,
) -> Option<Vec<Local>> {
    let labels = scope.label(slab, ends, b, work, true);
    if scope.decided_mask(&labels) & wanted == wanted {
        return Some(vec![Local::Leaf(labels)]);
    }
    if *budget < 2 {
        return None;
    }
    let axis = if theta && b.can_split(0) && theta_dominates(scope, b, slab, wanted) {
        0
    } else if b.can_split(1) {
        1
    } else {
        return None;
    };
    *budget -= 1;
    let (lo, hi) = b.split(axis);
    let mut out = vec![Local::Mid(axis as u8)];
    if axis == 0 {
        work.slabs += 2;
        for half in [lo, hi] {
            let sl = scope.set.slab(half.theta_interval());
            out.extend(certify(
                scope, &half, &sl, None, wanted, budget, work, theta,
            )?);
        }
    } else {
        out.extend(certify(
            scope, &lo, slab, ends, wanted, budget, work, theta,
        )?);
        out.extend(certify(
            scope, &hi, slab, ends, wanted, budget, work, theta,
        )?);
    }
    Some(out)
}

/// The θ-width of the coefficients costs more than the θ̇ dependency:
/// compare the enclosure at the θ̇ midpoint with the whole one.
fn theta_dominates<S: ConstraintSet>(
    scope: &Scope<'_, S>,
    b: &PhaseBox,
    slab: &S::Slab,
    wanted: u8,
) -> bool {
    let whole = DecInterval::new(b.theta_dot_interval());
    let mid = DecInterval::new(point(b.midpoint(1)));
    let (mut coef, mut dep) = (0.0f64, 0.0f64);
    for i in scope
        .own()
        .filter(|&i| scope.with_copies(1 << i) & wanted != 0)
    {
        let Some(q) = scope.set.quadratic(slab, i) else {
            return true;
        };
        if let (Some(x), Some(y)) = (q.eval(whole).interval(), q.eval(mid).interval()) {
            coef = coef.max(y.wid());
            dep = dep.max(x.wid() - y.wid());
        }
    }
    coef >= dep
}
