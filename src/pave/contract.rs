//! `contract`: on every new θ-slab, the exact θ̇-partition of each quadratic
//! constraint into certainly in / certainly out / undecided, recorded as
//! splits at the contraction points; removed parts are verified leaves.
//! Where the points go is steered in f64 ([`Steer`]); every removed part is
//! labelled by the natural extension or, with the slab's end data, by the
//! checker's monotone and convex tests.

use super::bisection::Bisection;
use super::certify::{certify, CERTIFY_LEAVES, CERTIFY_LEAVES_MONOTONE};
use super::engine::Refine;
use super::labels::{with_w, Labels, Scope, Tentative, UNGUIDED};
use super::level::{Local, Open, Work};
use super::{ConstraintSet, PhaseBox, SlabEnds, MAX_CONSTRAINTS};
use crate::number::scalar::is_defined;
use crate::scene::Quadratic;
use inari::{DecInterval, Interval};

/// A free end's guard piece is this fraction of the part (inverse).
const GUARD: f64 = 32.0;

/// Relative inward steps tried to place a contraction point so the removed
/// part verifies.
const SHRINK: [f64; 5] = [
    1.0 / (1u64 << 40) as f64,
    1.0 / (1u64 << 26) as f64,
    1.0 / (1u64 << 16) as f64,
    1.0 / 256.0,
    1.0 / 16.0,
];

/// Natural labels; each new θ-slab contracted.
pub(super) struct Contract<'a, S: ConstraintSet> {
    pub scope: Scope<'a, S>,
    pub grid: Bisection,
}

impl<S: ConstraintSet> Refine<S> for Contract<'_, S> {
    fn scope(&self) -> &Scope<'_, S> {
        &self.scope
    }
    fn grid(&self) -> Option<&Bisection> {
        Some(&self.grid)
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
        contract_fresh(
            &self.scope,
            |b| self.grid.choose_axis(b).is_some(),
            o,
            slab,
            ends,
            work,
            out,
        )
    }
}

/// The contraction of a box whose slab is new at this level (none for
/// one that shares its parent's, already contracted), appended to `out`
/// as [`contract`] does. `ends`: the slab's end data if computed with it,
/// else computed here. `refinable`: an undecided part is refined further
/// (else it is an undecided leaf).
#[allow(clippy::too_many_arguments)]
pub(super) fn contract_fresh<S: ConstraintSet>(
    scope: &Scope<'_, S>,
    refinable: impl Fn(&PhaseBox) -> bool,
    o: &Open<S::Slab>,
    slab: &S::Slab,
    ends: Option<&[SlabEnds]>,
    work: &mut Work,
    out: &mut Vec<Local>,
) -> bool {
    if !o.fresh {
        return false;
    }
    let computed = ends
        .is_none()
        .then(|| scope.slab_ends(o.bx.theta_interval(), work))
        .flatten();
    let ends = ends.or(computed.as_deref());
    contract(scope, refinable, slab, &o.bx, ends, work, out)
}

/// The θ̇-range `[lo, hi]` of `b` cut at `cuts` (sorted, inside), every
/// piece labelled and decided for the relevant constraints; `None` if
/// one is not.
#[allow(clippy::too_many_arguments)]
fn verified_pieces<S: ConstraintSet>(
    scope: &Scope<'_, S>,
    slab: &S::Slab,
    ends: Option<&[SlabEnds]>,
    b: &PhaseBox,
    lo: f64,
    hi: f64,
    cuts: &[f64],
    work: &mut Work,
) -> Option<Vec<Local>> {
    let mut t = Vec::with_capacity(2 * cuts.len() + 1);
    let mut from = lo;
    for to in cuts.iter().copied().chain(std::iter::once(hi)) {
        let labels = scope.label(slab, ends, &with_w(b, from, to), work, true);
        if scope.decided_mask(&labels) & scope.relevant != scope.relevant {
            return None;
        }
        if to < hi {
            t.push(Local::At(1, to));
        }
        t.push(Local::Leaf(labels));
        from = to;
    }
    Some(t)
}

/// Contraction of a box on a new θ-slab: the θ̇-partition into parts
/// decided for every relevant constraint (verified leaves) and the rest
/// (open, or undecided leaves at the resolution), appended to `out`;
/// false, `out` as it was, when it removes nothing.
/// `ends`: the slab's ends and θ-derivatives, for tight bands (the
/// roots at the two ends) and labels by the checker's monotone test.
pub(super) fn contract<S: ConstraintSet>(
    scope: &Scope<'_, S>,
    refinable: impl Fn(&PhaseBox) -> bool,
    slab: &S::Slab,
    b: &PhaseBox,
    ends: Option<&[SlabEnds]>,
    work: &mut Work,
    out: &mut Vec<Local>,
) -> bool {
    // Sized up front or on the stack: growing these by pushes, and a
    // heap allocation for each, were several % of a coarse paving's
    // whole process.
    let mut steers = [Steer::NONE; MAX_CONSTRAINTS];
    let mut k = 0;
    for i in scope.relevant_own() {
        let Some(q) = scope.set.quadratic(slab, i) else {
            return false;
        };
        let steer = match ends.and_then(|e| e.get(i)) {
            Some(e) => Steer::from_ends(e),
            None => Steer::new(&q),
        };
        let Some(steer) = steer else {
            return false;
        };
        steers[k] = steer;
        k += 1;
    }
    let qs = &steers[..k];
    let [w0, w1] = b.theta_dot;
    let mut pts: Vec<f64> = Vec::with_capacity(8 * MAX_CONSTRAINTS);
    for s in qs {
        s.breakpoints(&mut pts);
    }
    // A boundary on (or next to) a window end, as θ̇² − 1 on [−1, 1]: the
    // part beside it must leave that end free, like a root inside. (Before
    // the cut at 0 joins the roots: a window end at 0 is no boundary.)
    let near = SHRINK[0] * (w1 - w0);
    let on_end = [w0, w1].map(|w| pts.iter().any(|p| (p - w).abs() <= near));
    pts.push(0.0);
    pts.retain(|p| w0 < *p && *p < w1);
    pts.sort_by(f64::total_cmp);
    pts.dedup();
    // Segments with a tentative label per relevant constraint.
    let mut segs: Vec<Seg> = Vec::with_capacity(pts.len() + 3);
    let gap = |at: f64| Seg {
        lo: at,
        hi: at,
        tentative: [None; MAX_CONSTRAINTS],
        failed: false,
        tree: None,
    };
    if on_end[0] {
        segs.push(gap(w0));
    }
    let mut lo = w0;
    for &hi in pts.iter().chain(std::iter::once(&w1)) {
        let m = 0.5 * lo + 0.5 * hi;
        let mut t = [None; MAX_CONSTRAINTS];
        for (k, s) in qs.iter().enumerate() {
            t[k] = s.tentative(m);
        }
        // A boundary that touches without crossing (a double root, as
        // θ̇² > 0 at θ̇ = 0) has the same label on both sides: not merged
        // across, so that both sides shrink off it.
        let touches = lo > w0 && qs.iter().any(|s| s.tentative(lo).is_none());
        match segs.last_mut() {
            Some(last) if last.tentative == t && !touches => last.hi = hi,
            _ => segs.push(Seg {
                lo,
                hi,
                tentative: t,
                failed: false,
                tree: None,
            }),
        }
        lo = hi;
    }
    if on_end[1] {
        segs.push(gap(w1));
    }
    let k = qs.len();
    let decided = |s: &Seg| !s.failed && s.tentative[..k].iter().all(|t| t.is_some());
    // Neighbouring decided parts with different labels meet at a boundary
    // the steering cannot resolve (one constant in θ, as θ̇ = 1/2): an
    // empty undecided part between them leaves both ends free, so both
    // shrink off it.
    let mut j = 1;
    while j < segs.len() {
        if decided(&segs[j - 1]) && decided(&segs[j]) {
            segs.insert(j, gap(segs[j].lo));
            j += 1;
        }
        j += 1;
    }
    if !segs.iter().any(decided) {
        return false;
    }
    // Verify each decided part, stepping its ends inward as needed.
    for j in 0..segs.len() {
        if !decided(&segs[j]) {
            continue;
        }
        let (lo_free, hi_free) = (j > 0, j + 1 < segs.len());
        let (a, z) = (segs[j].lo, segs[j].hi);
        let mut done = None;
        // With a free side the tentative end is a root of the bound:
        // the unshrunk part touches zero, so start shrinking at once.
        let first = if lo_free || hi_free { 1 } else { 0 };
        // With the monotone test a part fails for its shape (a turning
        // point inside), which shrinking does not mend: two steps only.
        let t = segs[j].tentative;
        let steps = match ends {
            Some(_)
                if qs
                    .iter()
                    .enumerate()
                    .any(|(k, q)| q.turns_inside(a, z) && !q.convex_for(t[k] == Some(true))) =>
            {
                0
            }
            Some(_) => 2,
            None => SHRINK.len() + 1,
        };
        for f in std::iter::once(0.0).chain(SHRINK).skip(first).take(steps) {
            let d = f * (z - a);
            let na = if lo_free && f > 0.0 { a + d } else { a };
            let nz = if hi_free && f > 0.0 { z - d } else { z };
            if !(a <= na && na < nz && nz <= z) || (lo_free && na == a && f > 0.0) {
                continue;
            }
            let bx = with_w(b, na, nz);
            let labels = scope.label_expecting(slab, ends, &bx, work, true, &t);
            if scope.decided_mask(&labels) & scope.relevant == scope.relevant {
                done = Some((na, nz, Part::Leaf(labels)));
                break;
            }
        }
        if done.is_none() && ends.is_some() {
            // Not monotone in θ̇ (a quadratic's vertex inside): split
            // there. Failing that, also a thin guard piece next to each
            // free end: over the whole part the natural ∂g/∂θ (θ̇ occurs
            // twice) may lose the sign it has next to the boundary,
            // which the guard keeps; the far part is then decided by its
            // value. (Guards only when needed: each is one more leaf.)
            let d = SHRINK[0] * (z - a);
            let na = if lo_free { a + d } else { a };
            let nz = if hi_free { z - d } else { z };
            let mut cuts: Vec<f64> = Vec::new();
            for q in qs {
                q.turning_cuts((nz - na) / 64.0, &mut cuts);
            }
            let guard = (nz - na) / GUARD;
            let guards = [(lo_free, na + guard), (hi_free, nz - guard)];
            let mut with_guards = cuts.clone();
            with_guards.extend(guards.iter().filter(|g| g.0).map(|g| g.1));
            let inside = |mut c: Vec<f64>| {
                c.retain(|v| na < *v && *v < nz);
                c.sort_by(f64::total_cmp);
                c.dedup();
                c
            };
            let (plain, guarded) = (inside(cuts), inside(with_guards));
            // Without a guard that adds a cut, the second try would
            // repeat the first.
            let tries = if guarded == plain {
                vec![plain]
            } else {
                vec![plain, guarded]
            };
            for cuts in tries {
                if cuts.is_empty() {
                    continue;
                }
                if let Some(t) = verified_pieces(scope, slab, ends, b, na, nz, &cuts, work) {
                    done = Some((na, nz, Part::Tree(t)));
                    break;
                }
            }
        }
        if done.is_none() {
            // The natural enclosure overestimates (θ̇ dependency, θ-width
            // of the coefficients): bisect the slightly shrunk part.
            let d = SHRINK[3] * (z - a);
            let na = if lo_free { a + d } else { a };
            let nz = if hi_free { z - d } else { z };
            if na < nz {
                // With the monotone test a few θ̇-splits suffice (they
                // tighten the derivatives); more only burn evaluations
                // on a slab too wide to be monotone, which θ-refinement
                // handles.
                let mut budget = if ends.is_some() {
                    CERTIFY_LEAVES_MONOTONE
                } else {
                    CERTIFY_LEAVES
                };
                let bx = with_w(b, na, nz);
                if let Some(t) = certify(
                    scope,
                    &bx,
                    slab,
                    ends,
                    scope.relevant,
                    &mut budget,
                    work,
                    false,
                ) {
                    done = Some((na, nz, Part::Tree(t)));
                }
            }
        }
        match done {
            Some((na, nz, t)) => {
                if na > a {
                    segs[j - 1].hi = na;
                }
                if nz < z {
                    segs[j + 1].lo = nz;
                }
                segs[j].lo = na;
                segs[j].hi = nz;
                segs[j].tree = Some(t);
            }
            None => segs[j].failed = true,
        }
    }
    // Drop empty parts (a gap no neighbour shrank off), then merge
    // neighbouring undecided parts (slivers left by the steps).
    segs.retain(|s| s.tree.is_some() || s.lo < s.hi);
    segs.dedup_by(|s, last| {
        let both = last.tree.is_none() && s.tree.is_none();
        if both {
            last.hi = s.hi;
            last.failed |= s.failed;
            for (l, t) in last.tentative.iter_mut().zip(s.tentative) {
                if *l != t {
                    *l = None;
                }
            }
        }
        both
    });
    let merged = segs;
    if merged.len() == 1 && merged[0].tree.is_none() {
        return false;
    }

    let last = merged.len() - 1;
    for (j, s) in merged.into_iter().enumerate() {
        if j < last {
            out.push(Local::At(1, s.hi));
        }
        match s.tree {
            Some(Part::Leaf(l)) => out.push(Local::Leaf(l)),
            Some(Part::Tree(t)) => out.extend(t),
            None => {
                let bx = with_w(b, s.lo, s.hi);
                if refinable(&bx) {
                    out.push(Local::Open);
                } else {
                    // A constraint whose boundary the steering puts across
                    // the part is not tested: its zero is inside. A part
                    // that failed verification is tested in full.
                    let t = if s.failed { UNGUIDED } else { s.tentative };
                    out.push(Local::Leaf(
                        scope.label_expecting(slab, ends, &bx, work, false, &t),
                    ));
                }
            }
        }
    }
    true
}

struct Seg {
    lo: f64,
    hi: f64,
    tentative: Tentative,
    /// Tentatively decided but not verified: labelled in full.
    failed: bool,
    tree: Option<Part>,
}

/// A verified part: one leaf (the common case, kept off the heap) or a
/// subtree.
enum Part {
    Leaf(Labels),
    Tree(Vec<Local>),
}

/// Steering data of one quadratic: f64 bounds of the coefficients. Over the
/// coefficient box, `sup q(w) = c₂⁺w² + c₁^± w + c₀⁺` (the sign of w picks
/// the end of c₁), likewise `inf q`; their sign sets are the tentative
/// certainly-in and certainly-out θ̇-sets. Only used to choose points.
#[derive(Clone, Copy)]
struct Steer {
    c2: [f64; 2],
    c1: [f64; 2],
    c0: [f64; 2],
    /// With the slab's end data: the quadratic (midpoint coefficients
    /// c₂, c₁, c₀) at each end of the slab. Where it is monotone in θ, its
    /// value over the slab lies between the two, which is much tighter than
    /// the coefficient box.
    ends: Option<[[f64; 3]; 2]>,
    /// With the end data: ∂/∂θ of the quadratic (midpoint coefficients).
    d_theta: Option<[f64; 3]>,
}

impl Steer {
    /// A placeholder for unused slots.
    const NONE: Steer = Steer {
        c2: [0.0; 2],
        c1: [0.0; 2],
        c0: [0.0; 2],
        ends: None,
        d_theta: None,
    };
    fn new(q: &Quadratic<DecInterval>) -> Option<Steer> {
        let i = |x: DecInterval| x.interval().filter(|_| is_defined(x));
        Steer::bounded(&Quadratic {
            c2: i(q.c2)?,
            c1: i(q.c1)?,
            c0: i(q.c0)?,
        })
    }
    /// Coefficients bounded (so not empty either).
    fn bounded(q: &Quadratic<Interval>) -> Option<Steer> {
        let b = |i: Interval| {
            (i.inf().is_finite() && i.sup().is_finite()).then_some([i.inf(), i.sup()])
        };
        Some(Steer {
            c2: b(q.c2)?,
            c1: b(q.c1)?,
            c0: b(q.c0)?,
            ends: None,
            d_theta: None,
        })
    }
    fn from_ends(e: &SlabEnds) -> Option<Steer> {
        if !e.smooth {
            return None;
        }
        let mid = |x: Interval| -> Option<f64> {
            let m = x.mid();
            m.is_finite().then_some(m)
        };
        let mids = |q: &Quadratic<Interval>| Some([mid(q.c2)?, mid(q.c1)?, mid(q.c0)?]);
        Some(Steer {
            ends: Some([mids(&e.ends[0])?, mids(&e.ends[1])?]),
            d_theta: Some(mids(&e.d_theta)?),
            ..Steer::bounded(&e.value)?
        })
    }
    fn at_ends(&self, w: f64) -> Option<[f64; 2]> {
        self.ends
            .map(|e| e.map(|[c2, c1, c0]| c2 * w * w + c1 * w + c0))
    }
    /// A turning point inside (a, z) where the evaluation has a dependency
    /// (c₁ ≠ 0: θ̇ occurs twice; c₂θ̇² alone is one exact square).
    fn turns_inside(&self, a: f64, z: f64) -> bool {
        self.ends.into_iter().flatten().any(|[c2, c1, _]| {
            let v = -c1 / (2.0 * c2);
            c1 != 0.0 && a < v && v < z
        })
    }

    /// Cuts around the θ̇ where the quadratic turns (at either end of the
    /// slab) and where its θ-derivative changes sign, `pad` to each side:
    /// the parts outside are monotone in that variable, and the narrow part
    /// around such a point is decided with little dependency.
    fn turning_cuts(&self, pad: f64, out: &mut Vec<f64>) {
        let mut turn: Vec<f64> = Vec::new();
        for [c2, c1, _] in self.ends.into_iter().flatten() {
            turn.push(-c1 / (2.0 * c2));
        }
        turn.retain(|v| v.is_finite());
        if let (Some(lo), Some(hi)) = (
            turn.iter().copied().reduce(f64::min),
            turn.iter().copied().reduce(f64::max),
        ) {
            out.extend([lo - pad, hi + pad]);
        }
        if let Some([c2, c1, c0]) = self.d_theta {
            out.extend(roots(c2, c1, c0).flat_map(|r| [r - pad, r + pad]));
        }
    }
    /// The convex test can decide a part with this tentative label: c₂ ≥ 0
    /// (in) or ≤ 0 (out) on the slab.
    fn convex_for(&self, want_in: bool) -> bool {
        if want_in {
            self.c2[0] >= 0.0
        } else {
            self.c2[1] <= 0.0
        }
    }
    fn sup_q(&self, w: f64) -> f64 {
        if let Some([a, b]) = self.at_ends(w) {
            return a.max(b);
        }
        let c1 = if w >= 0.0 { self.c1[1] } else { self.c1[0] };
        self.c2[1] * w * w + c1 * w + self.c0[1]
    }
    fn inf_q(&self, w: f64) -> f64 {
        if let Some([a, b]) = self.at_ends(w) {
            return a.min(b);
        }
        let c1 = if w >= 0.0 { self.c1[0] } else { self.c1[1] };
        self.c2[0] * w * w + c1 * w + self.c0[0]
    }
    /// Some(true): tentatively in, Some(false): out, None: undecided.
    fn tentative(&self, w: f64) -> Option<bool> {
        if self.sup_q(w) < 0.0 {
            Some(true)
        } else if self.inf_q(w) > 0.0 {
            Some(false)
        } else {
            None
        }
    }
    fn breakpoints(&self, out: &mut Vec<f64>) {
        if let Some(e) = self.ends {
            for [c2, c1, c0] in e {
                out.extend(roots(c2, c1, c0));
            }
            return;
        }
        for (a, c) in [(self.c2[1], self.c0[1]), (self.c2[0], self.c0[0])] {
            for b in self.c1 {
                out.extend(roots(a, b, c));
            }
        }
    }
}

/// Real roots of `a x² + b x + c` in f64 (steering only).
pub(super) fn roots(a: f64, b: f64, c: f64) -> impl Iterator<Item = f64> {
    let mut r = [f64::NAN; 2];
    if a == 0.0 {
        if b != 0.0 {
            r[0] = -c / b;
        }
    } else {
        let disc = b * b - 4.0 * a * c;
        if disc >= 0.0 {
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            r[0] = q / a;
            if q != 0.0 {
                r[1] = c / q;
            }
        }
    }
    r.into_iter().filter(|x| x.is_finite())
}
