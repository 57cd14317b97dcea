//! Paving methods and the level-synchronous engine they share.
//!
//! Every method builds the same kind of tree — midpoint splits, splits at
//! recorded exact points, labelled leaves — and every label it writes is one
//! the proof checker recomputes on that leaf: by the natural interval
//! extension or, for `contract` and `slices`, by the monotone test
//! ([`monotone_label`]: where a partial derivative keeps its sign on the
//! leaf, the extreme values are at that variable's ends) or the convex test
//! ([`convex_label`]: where ∂²g/∂θ̇² keeps its sign, the largest (smallest)
//! value is on one of the two θ̇-edges). Other enclosures
//! (centred forms, the f64 roots) only *steer*: they say where to split, or
//! that a box is worth certifying by a few extra splits, never a label.
//!
//! - `natural`: label by the natural extension, bisect undecided boxes.
//! - `centred`: natural ∩ mean-value form ∩ monotonicity in θ̇ (and, where
//!   bisection stops at the resolution, the coefficients' mean-value form in
//!   θ); a box these decide is certified by a small local subdivision.
//! - `contract`: on every new θ-slab, the exact θ̇-partition of each quadratic
//!   constraint into certainly in / certainly out / undecided, recorded as
//!   splits at the contraction points; removed parts are verified leaves.
//! - `slices`: the contraction with θ-only refinement: an adaptive 1-D
//!   subdivision in θ that equidistributes the undecided area (a slab is
//!   split while the band its quadratics' end-point roots predict is above
//!   ε² of the domain's area), then one contraction per final slab whose
//!   cuts are placed at those roots and verified by the monotone test.

use super::{
    CellSpec, ConstraintSet, Label, Leaf, Node, PaveError, PaveOptions, PaveStats, Paving,
    PerConstraint, PhaseBox, SlabEnds, StopReason, MAX_CONSTRAINTS,
};
use crate::number::scalar::{is_defined, Dual};
use crate::scene::Quadratic;
use inari::{DecInterval, Interval};
use rayon::prelude::*;
use serde::Serialize;
use std::fmt;
use std::mem::{size_of, MaybeUninit};
use std::str::FromStr;
use std::sync::Arc;

/// A paving method (`--method`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Natural interval extension and bisection.
    #[default]
    Natural,
    /// Mean-value form and monotonicity in θ̇ (and in θ at the resolution)
    /// intersected with the natural enclosure, decided boxes certified by
    /// local subdivision.
    Centred,
    /// Exact contraction of each quadratic in θ̇ on every new θ-slab.
    Contract,
    /// Adaptive θ-slabs, each split in θ̇ at its contraction points.
    Slices,
}

impl Method {
    pub const ALL: [Method; 4] = [
        Method::Natural,
        Method::Centred,
        Method::Contract,
        Method::Slices,
    ];
    pub fn name(self) -> &'static str {
        match self {
            Method::Natural => "natural",
            Method::Centred => "centred",
            Method::Contract => "contract",
            Method::Slices => "slices",
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| {
                format!(
                    "unknown method `{s}` (known: {})",
                    Method::ALL.map(|m| m.name()).join(", ")
                )
            })
    }
}

/// How to pave, beyond resolution and budget.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MethodOptions {
    pub method: Method,
    /// Constraints whose labels matter (bit `i` = constraint `i`); a box is
    /// refined only while one of these is undecided. `None`: all of them.
    pub relevant: Option<u8>,
}

impl MethodOptions {
    pub fn new(method: Method) -> Self {
        MethodOptions {
            method,
            relevant: None,
        }
    }
    /// Refines only for the constraints a region or cell uses.
    pub fn for_cell(method: Method, cell: &CellSpec) -> Self {
        let mask = cell
            .0
            .iter()
            .enumerate()
            .filter(|(_, l)| l.is_some())
            .fold(0u8, |m, (i, _)| m | 1 << i);
        MethodOptions {
            method,
            relevant: Some(mask),
        }
    }
}

type Labels = [Label; MAX_CONSTRAINTS];

/// A small subtree in preorder, produced for one box.
#[derive(Clone, Copy, Debug)]
enum Local {
    Mid(u8),
    At(u8, f64),
    Leaf(Labels),
    /// Stays open: refined at the next level.
    Open,
}

/// One box processed: its labels, outcome, work, and the slab it computed
/// for itself (which its θ̇-children share).
type Done<Sl> = (Labels, Outcome, Work, Option<Arc<Sl>>);

/// What processing one open box decided.
enum Outcome {
    Leaf,
    Split(u8),
    Tree(Vec<Local>),
}

struct Open<Sl> {
    node: u32,
    bx: PhaseBox,
    slab: Option<Arc<Sl>>,
    /// The slab was computed for this box's θ-interval at this level: the
    /// contraction has not seen it yet.
    fresh: bool,
}

/// Arena node while building; children of a split are `a` and `a + 1`.
#[derive(Clone, Copy)]
enum Building {
    Open,
    Leaf(u32),
    Split(u8, u32),
    SplitAt(u8, f64, u32),
}

/// Leaves one certification may add (bounds the work on a hard box).
const CERTIFY_LEAVES: u32 = 64;
/// The same with the monotone test at hand.
const CERTIFY_LEAVES_MONOTONE: u32 = 8;

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

struct Ctx<'a, S: ConstraintSet> {
    set: &'a S,
    root: PhaseBox,
    method: Method,
    n: usize,
    same_as: Vec<Option<usize>>,
    relevant: u8,
    min_width: [f64; 2],
    /// `slices`: the undecided area per slab it refines down to.
    slab_area: f64,
}

/// Per-box work counters.
#[derive(Default, Clone, Copy)]
struct Work {
    evals: u64,
    slabs: u64,
}

impl<S: ConstraintSet> Ctx<'_, S> {
    fn rel(&self, b: &PhaseBox, axis: usize) -> f64 {
        let (r, d) = if axis == 0 {
            (b.theta, self.root.theta)
        } else {
            (b.theta_dot, self.root.theta_dot)
        };
        (r[1] - r[0]) / (d[1] - d[0])
    }

    fn wide(&self, b: &PhaseBox) -> [bool; 2] {
        let (h, k) = (b.theta[1] - b.theta[0], b.theta_dot[1] - b.theta_dot[0]);
        if self.method == Method::Slices {
            // Slabs are refined while their undecided area is above the
            // threshold (equidistributed), down to a floor that bounds the
            // depth at vertical tangents.
            return [h > self.min_width[0] && h * k > self.slab_area, false];
        }
        [h > self.min_width[0], k > self.min_width[1]]
    }

    /// `slices`: a fresh slab that can still be split and whose predicted
    /// undecided band is above the threshold.
    fn slab_too_coarse(&self, b: &PhaseBox) -> bool {
        self.choose_axis(b).is_some() && self.estimated_band(b) > self.slab_area
    }

    /// `slices`: an estimate (steering only) of the undecided area a fresh
    /// slab would leave, from the roots of its quadratics in f64 at θ's two
    /// ends and middle; the full box where their number changes.
    fn estimated_band(&self, b: &PhaseBox) -> f64 {
        let [t0, t1] = b.theta;
        let [w0, w1] = b.theta_dot;
        let full = (t1 - t0) * (w1 - w0);
        // At most two roots per constraint, at each of the three points.
        let mut per_end = [[0.0f64; 2 * MAX_CONSTRAINTS]; 3];
        let mut count = [0usize; 3];
        for (k, t) in [t0, 0.5 * t0 + 0.5 * t1, t1].into_iter().enumerate() {
            let Some(qs) = self.set.steer_at(t) else {
                return full;
            };
            for i in self.relevant_own() {
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

    /// The axis to refine an undecided box along, if any. `natural`,
    /// `centred`, `contract`: the relatively wider axis, θ̇ on ties (slabs
    /// are then shared as long as possible). `slices`: θ only.
    fn choose_axis(&self, b: &PhaseBox) -> Option<u8> {
        let w = self.wide(b);
        let can = [w[0] && b.can_split(0), w[1] && b.can_split(1)];
        if self.method == Method::Slices {
            return can[0].then_some(0);
        }
        match can {
            [false, false] => None,
            [true, false] => Some(0),
            [false, true] => Some(1),
            [true, true] => Some(if self.rel(b, 0) > self.rel(b, 1) {
                0
            } else {
                1
            }),
        }
    }

    /// The box is above the resolution but one ulp wide along such an axis.
    fn at_ulp_limit(&self, b: &PhaseBox) -> bool {
        let w = self.wide(b);
        let axes: &[usize] = if self.method == Method::Slices {
            &[0]
        } else {
            &[0, 1]
        };
        axes.iter().any(|&a| w[a] && !b.can_split(a))
    }

    fn natural(&self, slab: &S::Slab, b: &PhaseBox, work: &mut Work) -> Labels {
        work.evals += 1;
        let mut labels = [Label::ProvedOut; MAX_CONSTRAINTS];
        for (l, g) in labels.iter_mut().zip(
            self.set
                .enclose(slab, b.theta_dot_interval())
                .iter()
                .copied(),
        ) {
            *l = Label::from_enclosure(g);
        }
        self.copy_aliases(&mut labels);
        labels
    }

    /// Labels the checker confirms. Without the slab's end data: natural.
    /// With it: the monotone test on the relevant constraints first (cheaper
    /// and, next to the boundary, stronger), then, if `convex`, the convex
    /// test, the natural labels only if one is left undecided; other
    /// constraints keep what natural gives, if run. (A part the contraction
    /// leaves undecided straddles the boundary, where the convex test does
    /// not decide and costs up to four evaluations: 3–4 % of a coarse
    /// paving's whole process.)
    fn label(
        &self,
        slab: &S::Slab,
        ends: Option<&[SlabEnds]>,
        b: &PhaseBox,
        work: &mut Work,
        convex: bool,
    ) -> Labels {
        let Some(ends) = ends else {
            return self.natural(slab, b, work);
        };
        let mut labels = [Label::Undecided; MAX_CONSTRAINTS];
        work.evals += 1;
        for i in self.relevant_own() {
            if let Some(e) = ends.get(i) {
                labels[i] = monotone_label(e, b);
                if convex && !labels[i].is_decided() {
                    labels[i] = convex_label(e, b);
                }
            }
        }
        self.copy_aliases(&mut labels);
        if self.undecided(&labels) {
            let nat = self.natural(slab, b, work);
            for (l, n) in labels.iter_mut().zip(nat) {
                if !l.is_decided() {
                    *l = n;
                }
            }
        }
        labels
    }

    fn copy_aliases(&self, labels: &mut Labels) {
        for (i, s) in self.same_as.iter().enumerate() {
            if let Some(j) = *s {
                labels[i] = labels[j];
            }
        }
    }

    fn decided_mask(&self, labels: &Labels) -> u8 {
        (0..self.n)
            .filter(|&i| labels[i].is_decided())
            .fold(0, |m, i| m | 1 << i)
    }

    fn undecided(&self, labels: &Labels) -> bool {
        self.decided_mask(labels) & self.relevant != self.relevant
    }

    /// Constraints computed (not copies of another).
    fn own(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.n).filter(|&i| self.same_as[i].is_none())
    }

    /// Own constraints whose labels matter (themselves or through a copy).
    fn relevant_own(&self) -> impl Iterator<Item = usize> + '_ {
        self.own()
            .filter(|&i| self.with_copies(1 << i) & self.relevant != 0)
    }

    /// A mask over own constraints extended to their copies.
    fn with_copies(&self, m: u8) -> u8 {
        (0..self.n).fold(m, |acc, i| match self.same_as[i] {
            Some(j) if m >> j & 1 == 1 => acc | 1 << i,
            _ => acc,
        })
    }

    /// `ends`: the slab's end data when computed with the slab.
    fn process(
        &self,
        o: &Open<S::Slab>,
        slab: &Arc<S::Slab>,
        ends: Option<PerConstraint<SlabEnds>>,
        labels: &Labels,
        work: &mut Work,
    ) -> Outcome {
        if !self.undecided(labels) {
            return Outcome::Leaf;
        }
        match self.method {
            Method::Natural => {}
            Method::Centred => {
                if let Some(t) = self.centred(slab, &o.bx, labels, work) {
                    return Outcome::Tree(t);
                }
            }
            Method::Contract | Method::Slices => {
                // (`slices` splits a slab still too coarse before this.)
                if o.fresh {
                    let ends = ends.or_else(|| {
                        work.slabs += 3;
                        self.set.slab_ends(o.bx.theta_interval())
                    });
                    if let Some(t) = self.contract(slab, &o.bx, ends, work) {
                        return Outcome::Tree(t);
                    }
                }
            }
        }
        match self.choose_axis(&o.bx) {
            Some(ax) => Outcome::Split(ax),
            None => Outcome::Leaf,
        }
    }

    /// Centred method: when natural ∩ mean-value ∩ monotonicity decides
    /// every relevant constraint (or, at the resolution, some), certify it.
    fn centred(
        &self,
        slab: &Arc<S::Slab>,
        b: &PhaseBox,
        labels: &Labels,
        work: &mut Work,
    ) -> Option<Vec<Local>> {
        let w = b.theta_dot_interval();
        let at_resolution = self.choose_axis(b).is_none();
        let mut gained = 0u8;
        for i in self.own() {
            if labels[i] != Label::Undecided {
                continue;
            }
            let q = self.set.quadratic(slab, i)?;
            // Without a θ̇ term, θ̇ occurs once: natural is already exact in θ̇.
            let no_w_term =
                q.c1.interval()
                    .is_some_and(|c| c.inf() == 0.0 && c.sup() == 0.0);
            if !no_w_term && centred_label(&q, w).is_decided() {
                gained |= 1 << i;
            }
        }
        gained = self.with_copies(gained);
        let all = (self.decided_mask(labels) | gained) & self.relevant == self.relevant;
        if gained & self.relevant != 0 && (all || at_resolution) {
            let mut budget = CERTIFY_LEAVES;
            if let Some(t) = self.certify(
                b,
                slab,
                None,
                gained & self.relevant,
                &mut budget,
                work,
                false,
            ) {
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
        let cc = self.set.centred_coefficients(b.theta_interval())?;
        let mut gained = 0u8;
        for i in self.own() {
            if labels[i] == Label::Undecided && centred_label(cc.get(i)?, w).is_decided() {
                gained |= 1 << i;
            }
        }
        let wanted = self.with_copies(gained) & self.relevant;
        if wanted == 0 {
            return None;
        }
        let mut budget = CERTIFY_LEAVES;
        self.certify(b, slab, None, wanted, &mut budget, work, true)
    }

    /// A subtree whose leaves all carry natural labels deciding every
    /// constraint in `wanted`, by bisection within `budget` leaves. θ̇ only
    /// unless `theta`: what the θ̇-centred form and the contractor prove
    /// from the slab's coefficients is reached by narrowing θ̇ alone (the
    /// dependency of c₂θ̇² + c₁θ̇ shrinks with the width), sharing the slab;
    /// the θ-centred form needs narrower θ-slabs too.
    #[allow(clippy::too_many_arguments)]
    fn certify(
        &self,
        b: &PhaseBox,
        slab: &S::Slab,
        ends: Option<&[SlabEnds]>,
        wanted: u8,
        budget: &mut u32,
        work: &mut Work,
        theta: bool,
    ) -> Option<Vec<Local>> {
        let labels = self.label(slab, ends, b, work, true);
        if self.decided_mask(&labels) & wanted == wanted {
            return Some(vec![Local::Leaf(labels)]);
        }
        if *budget < 2 {
            return None;
        }
        let axis = if theta && b.can_split(0) && self.theta_dominates(b, slab, wanted) {
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
                let sl = self.set.slab(half.theta_interval());
                out.extend(self.certify(&half, &sl, None, wanted, budget, work, theta)?);
            }
        } else {
            out.extend(self.certify(&lo, slab, ends, wanted, budget, work, theta)?);
            out.extend(self.certify(&hi, slab, ends, wanted, budget, work, theta)?);
        }
        Some(out)
    }

    /// The θ-width of the coefficients costs more than the θ̇ dependency:
    /// compare the enclosure at the θ̇ midpoint with the whole one.
    fn theta_dominates(&self, b: &PhaseBox, slab: &S::Slab, wanted: u8) -> bool {
        let whole = DecInterval::new(b.theta_dot_interval());
        let mid = DecInterval::new(point(b.midpoint(1)));
        let (mut coef, mut dep) = (0.0f64, 0.0f64);
        for i in self
            .own()
            .filter(|&i| self.with_copies(1 << i) & wanted != 0)
        {
            let Some(q) = self.set.quadratic(slab, i) else {
                return true;
            };
            if let (Some(x), Some(y)) = (q.eval(whole).interval(), q.eval(mid).interval()) {
                coef = coef.max(y.wid());
                dep = dep.max(x.wid() - y.wid());
            }
        }
        coef >= dep
    }

    /// The θ̇-range `[lo, hi]` of `b` cut at `cuts` (sorted, inside), every
    /// piece labelled and decided for the relevant constraints; `None` if
    /// one is not.
    #[allow(clippy::too_many_arguments)]
    fn verified_pieces(
        &self,
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
            let labels = self.label(slab, ends, &with_w(b, from, to), work, true);
            if self.decided_mask(&labels) & self.relevant != self.relevant {
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
    /// (open, or undecided leaves at the resolution). `None` when it
    /// removes nothing.
    /// `ends`: the slab's ends and θ-derivatives, for tight bands (the
    /// roots at the two ends) and labels by the checker's monotone test.
    fn contract(
        &self,
        slab: &Arc<S::Slab>,
        b: &PhaseBox,
        ends: Option<PerConstraint<SlabEnds>>,
        work: &mut Work,
    ) -> Option<Vec<Local>> {
        let ends = ends.as_deref();
        // Sized up front or on the stack: growing these by pushes, and a
        // heap allocation for each, were several % of a coarse paving's
        // whole process.
        let mut steers = [Steer::NONE; MAX_CONSTRAINTS];
        let mut k = 0;
        for i in self.relevant_own() {
            let q = self.set.quadratic(slab, i)?;
            steers[k] = match ends.and_then(|e| e.get(i)) {
                Some(e) => Steer::from_ends(e)?,
                None => Steer::new(&q)?,
            };
            k += 1;
        }
        let qs = &steers[..k];
        let [w0, w1] = b.theta_dot;
        let mut pts: Vec<f64> = Vec::with_capacity(8 * MAX_CONSTRAINTS);
        for s in qs {
            s.breakpoints(&mut pts);
        }
        pts.push(0.0);
        pts.retain(|p| w0 < *p && *p < w1);
        pts.sort_by(f64::total_cmp);
        pts.dedup();
        // Segments with a tentative label per relevant constraint.
        let mut segs: Vec<Seg> = Vec::with_capacity(pts.len() + 1);
        let mut lo = w0;
        for &hi in pts.iter().chain(std::iter::once(&w1)) {
            let m = 0.5 * lo + 0.5 * hi;
            let mut t = [None; MAX_CONSTRAINTS];
            for (k, s) in qs.iter().enumerate() {
                t[k] = s.tentative(m);
            }
            match segs.last_mut() {
                Some(last) if last.tentative == t => last.hi = hi,
                _ => segs.push(Seg {
                    lo,
                    hi,
                    tentative: t,
                    tree: None,
                }),
            }
            lo = hi;
        }
        let k = qs.len();
        let decided = |s: &Seg| s.tentative[..k].iter().all(|t| t.is_some());
        // Neighbouring decided parts with different labels cannot both be
        // right: the later one is left undecided.
        for j in 1..segs.len() {
            if decided(&segs[j - 1]) && decided(&segs[j]) {
                segs[j].tentative[0] = None;
            }
        }
        if segs.len() == 1 && !decided(&segs[0]) {
            return None;
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
                    if qs.iter().enumerate().any(|(k, q)| {
                        q.turns_inside(a, z) && !q.convex_for(t[k] == Some(true))
                    }) =>
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
                let labels = self.label(slab, ends, &bx, work, true);
                if self.decided_mask(&labels) & self.relevant == self.relevant {
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
                    if let Some(t) = self.verified_pieces(slab, ends, b, na, nz, &cuts, work) {
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
                    if let Some(t) =
                        self.certify(&bx, slab, ends, self.relevant, &mut budget, work, false)
                    {
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
                None => segs[j].tentative[0] = None,
            }
        }
        // Merge neighbouring undecided parts (slivers left by the steps).
        segs.dedup_by(|s, last| {
            let both = last.tree.is_none() && s.tree.is_none();
            if both {
                last.hi = s.hi;
            }
            both
        });
        let merged = segs;
        if merged.len() == 1 && merged[0].tree.is_none() {
            return None;
        }

        let mut out = Vec::with_capacity(2 * merged.len() + 4);
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
                    if self.choose_axis(&bx).is_some() {
                        out.push(Local::Open);
                    } else {
                        out.push(Local::Leaf(self.label(slab, ends, &bx, work, false)));
                    }
                }
            }
        }
        Some(out)
    }
}

struct Seg {
    lo: f64,
    hi: f64,
    tentative: [Option<bool>; MAX_CONSTRAINTS],
    tree: Option<Part>,
}

/// A verified part: one leaf (the common case, kept off the heap) or a
/// subtree.
enum Part {
    Leaf(Labels),
    Tree(Vec<Local>),
}

fn with_w(b: &PhaseBox, lo: f64, hi: f64) -> PhaseBox {
    PhaseBox {
        theta: b.theta,
        theta_dot: [lo, hi],
    }
}

fn point(x: f64) -> Interval {
    Interval::try_from((x, x)).unwrap_or(Interval::ENTIRE)
}

/// Natural ∩ mean-value form ∩ monotonicity range of a quadratic in θ̇ with
/// coefficient enclosures, over `w`; the label it supports.
pub fn centred_label(q: &Quadratic<DecInterval>, w: Interval) -> Label {
    let wd = DecInterval::new(w);
    let nat = q.eval(wd);
    let Some(mut e) = nat.interval().filter(|_| is_defined(nat)) else {
        return Label::from_enclosure(nat);
    };
    let dq = Quadratic {
        c2: Dual::constant(q.c2),
        c1: Dual::constant(q.c1),
        c0: Dual::constant(q.c0),
    }
    .eval(Dual::variable(wd, 1));
    let slope = dq.grad[1];
    if is_defined(slope) {
        let s = slope.interval().expect("defined");
        let m = point(0.5 * w.inf() + 0.5 * w.sup());
        let qm = q.eval(DecInterval::new(m));
        // q(w) = q(m) + q'(ξ)(w − m) for each choice of coefficients.
        let mv = qm + slope * DecInterval::new(w - m);
        if is_defined(mv) {
            e = e.intersection(mv.interval().expect("defined"));
        }
        // Monotone in θ̇ for every choice of coefficients: the range lies
        // between the values at the two ends.
        if s.inf() >= 0.0 || s.sup() <= 0.0 {
            let (a, z) = (
                q.eval(DecInterval::new(point(w.inf()))),
                q.eval(DecInterval::new(point(w.sup()))),
            );
            if let (true, true, Some(a), Some(z)) =
                (is_defined(a), is_defined(z), a.interval(), z.interval())
            {
                e = e.intersection(a.convex_hull(z));
            }
        }
    }
    if e.is_empty() {
        // Cannot happen for sound enclosures of a defined function; claim nothing.
        return Label::Undecided;
    }
    if e.sup() < 0.0 {
        Label::ProvedIn
    } else if e.inf() > 0.0 {
        Label::ProvedOut
    } else {
        Label::Undecided
    }
}

/// The proof checker's monotone test (`proofs/FORMAT.md`, paving step 3) on
/// `b` for one quadratic constraint: where ∂g/∂θ or ∂g/∂θ̇ has a constant sign
/// on the box, g is largest (smallest) at one end of that variable, so the
/// label is decided on the box reduced to those ends. The value and both
/// derivatives must be continuous (`≥ dac`), as the checker requires.
pub fn monotone_label(e: &SlabEnds, b: &PhaseBox) -> Label {
    if !e.smooth {
        return Label::Undecided;
    }
    let w = b.theta_dot_interval();
    // ∂g/∂θ = c₂'θ̇² + c₁'θ̇ + c₀', ∂g/∂θ̇ = 2c₂θ̇ + c₁ over the box.
    let g_theta = e.d_theta.eval(w);
    let two = Interval::try_from((2.0, 2.0)).expect("2 is a double");
    let g_w = two * e.value.c2 * w + e.value.c1;
    let sign = |d: Interval| {
        if d.is_empty() {
            0
        } else if d.inf() >= 0.0 {
            1
        } else if d.sup() <= 0.0 {
            -1
        } else {
            0
        }
    };
    let (st, sw) = (sign(g_theta), sign(g_w));
    if st == 0 && sw == 0 {
        return Label::Undecided;
    }
    for want_in in [true, false] {
        // The end (0 lower, 1 upper) where g is largest for `in`, smallest for `out`.
        let pick = |sg: i32| (sg != 0).then_some(usize::from((sg > 0) == want_in));
        let q = pick(st).map_or(&e.value, |k| &e.ends[k]);
        let wv = pick(sw).map_or(w, |k| point(b.theta_dot[k]));
        let v = q.eval(wv);
        if v.is_empty() {
            continue;
        }
        if want_in && v.sup() < 0.0 {
            return Label::ProvedIn;
        }
        if !want_in && v.inf() > 0.0 {
            return Label::ProvedOut;
        }
    }
    Label::Undecided
}

/// The proof checker's convex test (`proofs/FORMAT.md`, paving step 3) on
/// `b` for one quadratic constraint: where ∂²g/∂θ̇² = 2c₂ ≥ 0 on the box, g
/// is convex in θ̇ for every θ, so its largest value lies on one of θ̇'s two
/// ends (for `≤ 0`, its smallest): the label `in` (`out`) is decided by
/// both ends, each by its value or the monotone test on that end's segment.
/// A part of a slab around the quadratic's vertex is thus one leaf.
pub fn convex_label(e: &SlabEnds, b: &PhaseBox) -> Label {
    if !e.smooth {
        return Label::Undecided;
    }
    let c2 = e.value.c2;
    let want = if c2.inf() >= 0.0 {
        Label::ProvedIn
    } else if c2.sup() <= 0.0 {
        Label::ProvedOut
    } else {
        return Label::Undecided;
    };
    let holds_at = |w: f64| {
        let by_value = Label::from_enclosure(DecInterval::new(e.value.eval(point(w))));
        by_value == want || monotone_label(e, &with_w(b, w, w)) == want
    };
    if holds_at(b.theta_dot[0]) && holds_at(b.theta_dot[1]) {
        want
    } else {
        Label::Undecided
    }
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
        let b = |x: DecInterval| -> Option<[f64; 2]> {
            let i = x.interval().filter(|_| is_defined(x))?;
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
        let dec = |x: Interval| DecInterval::new(x);
        let value = Quadratic {
            c2: dec(e.value.c2),
            c1: dec(e.value.c1),
            c0: dec(e.value.c0),
        };
        let mid = |x: Interval| -> Option<f64> {
            let m = x.mid();
            m.is_finite().then_some(m)
        };
        let mids = |q: &Quadratic<Interval>| Some([mid(q.c2)?, mid(q.c1)?, mid(q.c0)?]);
        Some(Steer {
            ends: Some([mids(&e.ends[0])?, mids(&e.ends[1])?]),
            d_theta: Some(mids(&e.d_theta)?),
            ..Steer::new(&value)?
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
fn roots(a: f64, b: f64, c: f64) -> impl Iterator<Item = f64> {
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

/// Paves `root` with a method. `natural` with every constraint relevant is
/// [`super::pave`].
pub fn pave_with<S: ConstraintSet>(
    set: &S,
    root: PhaseBox,
    opts: PaveOptions,
    mo: &MethodOptions,
    mut progress: impl FnMut(u32, usize, usize),
) -> Result<Paving, PaveError> {
    if !(opts.eps.is_finite() && opts.eps > 0.0 && opts.eps <= 1.0) {
        return Err(PaveError::BadEps(opts.eps));
    }
    if opts.max_boxes == 0 {
        return Err(PaveError::BadBudget);
    }
    if !(root.theta[0] < root.theta[1] && root.theta_dot[0] < root.theta_dot[1]) {
        return Err(PaveError::EmptyDomain);
    }
    let names = set.names();
    if names.len() > MAX_CONSTRAINTS {
        return Err(PaveError::TooManyConstraints);
    }
    let n = names.len();
    let mut same_as = set.same_as();
    same_as.resize(n, None);
    for (i, s) in same_as.iter_mut().enumerate() {
        // only earlier constraints that are not aliases themselves
        if s.is_some_and(|j| j >= i) {
            *s = None;
        }
    }
    let all = ((1u16 << n) - 1) as u8;
    let mut relevant = mo.relevant.unwrap_or(all) & all;
    if relevant == 0 {
        relevant = all;
    }
    // A copy is decided exactly when its original is.
    for (i, s) in same_as.iter().enumerate() {
        if let Some(j) = *s {
            if relevant >> i & 1 == 1 {
                relevant |= 1 << j;
            }
        }
    }
    // `slices` refines by area; its width floor is ε² instead of ε.
    let theta_floor = if mo.method == Method::Slices {
        opts.eps
    } else {
        1.0
    };
    let ctx = Ctx {
        set,
        root,
        method: mo.method,
        n,
        same_as: same_as.clone(),
        relevant,
        min_width: [
            opts.eps * (root.theta[1] - root.theta[0]) * theta_floor,
            opts.eps * (root.theta_dot[1] - root.theta_dot[0]),
        ],
        slab_area: opts.eps.powi(2)
            * (root.theta[1] - root.theta[0])
            * (root.theta_dot[1] - root.theta_dot[0]),
    };

    // The tree's first 256 KiB reserved at once (its pages are touched only
    // as they are written). Grown from small it was copied into fresh pages
    // at every doubling: a coarse paving's whole process took 11–14 % longer
    // (measured with glibc's malloc).
    const TREE_START: usize = 256 << 10;
    let mut arena: Vec<Building> = Vec::with_capacity(TREE_START / size_of::<Building>());
    arena.push(Building::Open);
    let mut leaves: Vec<Leaf> = Vec::with_capacity(TREE_START / size_of::<Leaf>());
    let mut frontier: Vec<Open<S::Slab>> = vec![Open {
        node: 0,
        bx: root,
        slab: None,
        fresh: true,
    }];
    let mut stats = PaveStats::default();
    let (mut budget_hit, mut ulp_limit, mut undecided_left) = (false, false, false);
    let mut level = 0u32;
    let mut peak = 0usize;
    // Per-level bookkeeping, reused (its pages are touched once).
    let (mut order, mut plan, mut offsets): (Vec<usize>, Vec<Plan>, Vec<[usize; 3]>) =
        Default::default();

    while !frontier.is_empty() {
        progress(level, frontier.len(), leaves.len());
        // θ-slabs of boxes just split in θ (fresh boxes are exactly those
        // without a slab), each computed once per level; boxes split in θ̇
        // share their parent's slab. `slices` computes each fresh slab
        // itself, with its end data, when processing it.
        let own_slabs = mo.method == Method::Slices;
        let needs_slab = |k: usize| -> Option<(u64, u64)> {
            let o = &frontier[k];
            (o.slab.is_none() && !own_slabs).then(|| slab_key(&o.bx))
        };
        let mut missing: Vec<(u64, u64)> = if frontier.len() < PAR_MIN {
            (0..frontier.len()).filter_map(needs_slab).collect()
        } else {
            (0..frontier.len())
                .into_par_iter()
                .filter_map(needs_slab)
                .collect()
        };
        if missing.len() < PAR_MIN {
            missing.sort_unstable();
        } else {
            missing.par_sort_unstable();
        }
        missing.dedup();
        stats.slab_evaluations += missing.len() as u64;
        let fresh: Vec<Arc<S::Slab>> = par_map(&missing, PAR_MIN_HEAVY, |&(lo, hi)| {
            let th = Interval::try_from((f64::from_bits(lo), f64::from_bits(hi)))
                .expect("ordered endpoints");
            Arc::new(set.slab(th))
        });
        par_each_mut(&mut frontier, |o| {
            if o.slab.is_none() {
                // Absent only for a pre-split box (whose θ-interval no other
                // box needed).
                if let Ok(k) = missing.binary_search(&slab_key(&o.bx)) {
                    o.slab = Some(fresh[k].clone());
                }
            }
        });
        drop(fresh);

        let done: Vec<Done<S::Slab>> = par_map_range(frontier.len(), PAR_MIN_HEAVY, |k| {
            let o = &frontier[k];
            let mut work = Work::default();
            // `slices`: a fresh slab its f64 roots call too coarse is split
            // in θ without interval work (undecided as far as computed).
            if own_slabs && o.fresh && ctx.slab_too_coarse(&o.bx) {
                return (
                    [Label::Undecided; MAX_CONSTRAINTS],
                    Outcome::Split(0),
                    work,
                    None,
                );
            }
            let (slab, ends, own) = match o.slab.as_ref() {
                Some(slab) => (slab.clone(), None, None),
                None => {
                    work.slabs += 3;
                    let (slab, ends) = set.slab_and_ends(o.bx.theta_interval());
                    let slab = Arc::new(slab);
                    (slab.clone(), ends, Some(slab))
                }
            };
            let labels = ctx.natural(&slab, &o.bx, &mut work);
            let outcome = ctx.process(o, &slab, ends, &labels, &mut work);
            (labels, outcome, work, own)
        });
        let work = |(_, _, w, _): &Done<S::Slab>| [w.evals, w.slabs];
        let add = |a: [u64; 2], b: [u64; 2]| [a[0] + b[0], a[1] + b[1]];
        let [evals, slabs] = if done.len() < PAR_MIN {
            done.iter().map(work).fold([0, 0], add)
        } else {
            done.par_iter().map(work).reduce(|| [0, 0], add)
        };
        stats.box_evaluations += evals;
        stats.slab_evaluations += slabs;

        // Refinement decisions in frontier order (`slices`: largest
        // undecided area first), each adding leaves while the budget allows.
        // Only integer bookkeeping here; the tree is written in parallel.
        let counts: Vec<Plan> = par_map(&done, PAR_MIN, |(_, outcome, _, _)| Plan::of(outcome));
        let (mut want_leaves, mut want_nodes) = (0usize, 0usize);
        for c in counts.iter().filter(|c| c.refine) {
            want_leaves += c.extra();
            want_nodes += c.nodes as usize;
        }
        let room = (u32::MAX as usize).saturating_sub(arena.len() + 2 * frontier.len());
        plan.clear();
        if leaves.len() + frontier.len() + want_leaves <= opts.max_boxes && want_nodes <= room {
            // Every refinement fits, so the order does not matter: each box
            // is decided on its own, in parallel, as the loop below would.
            let per_box = |k: usize| -> (Plan, bool, bool) {
                let (labels, outcome, _, _) = &done[k];
                if counts[k].refine {
                    let undecided = matches!(outcome, Outcome::Tree(t)
                        if t.iter().any(|l| matches!(l, Local::Leaf(x) if ctx.undecided(x))));
                    (counts[k], undecided, false)
                } else if ctx.undecided(labels) {
                    (Plan::LEAF, true, ctx.at_ulp_limit(&frontier[k].bx))
                } else {
                    (Plan::LEAF, false, false)
                }
            };
            let decided: Vec<(Plan, bool, bool)> = par_map_range(done.len(), PAR_MIN, per_box);
            plan.extend(decided.iter().map(|d| d.0));
            undecided_left |= decided.iter().any(|d| d.1);
            ulp_limit |= decided.iter().any(|d| d.2);
        } else {
            order.clear();
            order.extend(0..frontier.len());
            if mo.method == Method::Slices {
                let area = |o: &Open<S::Slab>| {
                    (o.bx.theta[1] - o.bx.theta[0]) * (o.bx.theta_dot[1] - o.bx.theta_dot[0])
                };
                order.sort_by(|&a, &b| area(&frontier[b]).total_cmp(&area(&frontier[a])));
            }
            plan.resize(frontier.len(), Plan::default());
            let mut leaves_if_stopped = leaves.len() + frontier.len();
            let mut nodes_planned = 0usize;
            for &k in &order {
                let (labels, outcome, _, _) = &done[k];
                let count = counts[k];
                let extra = count.extra();
                let fits = leaves_if_stopped + extra <= opts.max_boxes
                    && nodes_planned + count.nodes as usize <= room;
                if count.refine && fits {
                    leaves_if_stopped += extra;
                    nodes_planned += count.nodes as usize;
                    plan[k] = count;
                    if let Outcome::Tree(t) = outcome {
                        undecided_left |= t
                            .iter()
                            .any(|l| matches!(l, Local::Leaf(x) if ctx.undecided(x)));
                    }
                } else {
                    plan[k] = Plan::LEAF;
                    if count.refine {
                        budget_hit = true;
                    } else if ctx.undecided(labels) {
                        undecided_left = true;
                        if ctx.at_ulp_limit(&frontier[k].bx) {
                            ulp_limit = true;
                        }
                    }
                }
            }
        }
        // Offsets of each box's share, then every box writes its share of
        // the reserved capacity itself (first touch on the workers).
        let (base_nodes, base_leaves) = (arena.len(), leaves.len());
        offsets.clear();
        let mut total = [0usize; 3];
        for p in &plan {
            offsets.push(total);
            total[0] += p.nodes as usize;
            total[1] += p.leaves as usize;
            total[2] += p.opens as usize;
        }
        arena.reserve(total[0]);
        leaves.reserve(total[1]);
        let mut next: Vec<Open<S::Slab>> = Vec::with_capacity(total[2]);
        {
            // The whole arena allocation: parents (below `base_nodes`, one
            // per box) and the new children (above) are written in place.
            let an = Shared::whole(&mut arena);
            let (ln, on) = (
                Shared::new(leaves.spare_capacity_mut()),
                Shared::new(next.spare_capacity_mut()),
            );
            par_each_owned(done, |k, (labels, outcome, _, own)| {
                let o = &frontier[k];
                let slab = own.or_else(|| o.slab.clone());
                let off = offsets[k];
                let p = plan[k];
                let mut f = Filler {
                    arena: an.part(base_nodes + off[0], p.nodes as usize),
                    arena_base: (base_nodes + off[0]) as u32,
                    leaves: ln.part(off[1], p.leaves as usize),
                    leaf_base: (base_leaves + off[1]) as u32,
                    opens: on.part(off[2], p.opens as usize),
                    used: [0; 3],
                };
                let own = if p.refine {
                    match outcome {
                        Outcome::Split(ax) => {
                            let t = [Local::Mid(ax), Local::Open, Local::Open];
                            f.expand(&t, &mut 0, o.node, o.bx, slab)
                        }
                        Outcome::Tree(t) => f.expand(&t, &mut 0, o.node, o.bx, slab),
                        Outcome::Leaf => unreachable!("a leaf is not refined"),
                    }
                } else {
                    f.expand(&[Local::Leaf(labels)], &mut 0, o.node, o.bx, None)
                };
                // Every planned slot written: what makes set_len below sound.
                assert_eq!(
                    f.used,
                    [p.nodes as usize, p.leaves as usize, p.opens as usize]
                );
                an.part(o.node as usize, 1)[0].write(own);
            });
            // SAFETY: each box wrote exactly its planned slots (asserted
            // above), the shares are disjoint and together cover `total`.
            unsafe {
                arena.set_len(base_nodes + total[0]);
                leaves.set_len(base_leaves + total[1]);
                next.set_len(total[2]);
            }
        }
        // Written elements only: reserved capacity is not touched.
        peak = peak.max(
            arena.len() * size_of::<Building>()
                + leaves.len() * size_of::<Leaf>()
                + next.capacity() * size_of::<Open<S::Slab>>()
                + missing.len() * size_of::<S::Slab>(),
        );
        // Dropping the old frontier releases slabs; do it off the main thread.
        par_each_owned(std::mem::replace(&mut frontier, next), |_, o| drop(o));
        if !frontier.is_empty() {
            level += 1;
        }
    }
    stats.depth = level;
    let stop = if budget_hit {
        StopReason::Budget
    } else if ulp_limit {
        StopReason::DoublePrecisionLimit
    } else if undecided_left {
        StopReason::Resolution
    } else {
        StopReason::AllDecided
    };

    // Preorder serialisation of the tree; leaves renumbered in that order.
    let (nodes, ordered) = preorder(&arena, &leaves);
    // Building, leaves in build order, subtree sizes and the output together.
    peak = peak.max(
        arena.len() * (size_of::<Building>() + 8)
            + leaves.len() * size_of::<Leaf>()
            + nodes.capacity() * size_of::<Node>()
            + ordered.capacity() * size_of::<Leaf>(),
    );
    drop(arena);
    drop(leaves);
    let bytes = nodes.capacity() * size_of::<Node>() + ordered.capacity() * size_of::<Leaf>();
    stats.bytes_per_leaf = bytes as f64 / ordered.len().max(1) as f64;
    stats.peak_bytes_per_leaf = peak as f64 / ordered.len().max(1) as f64;
    Ok(Paving {
        root,
        names,
        eps: opts.eps,
        nodes,
        leaves: ordered,
        complete: stop != StopReason::Budget,
        stop,
        same_as,
        stats,
    })
}

/// What one box adds to the tree.
#[derive(Clone, Copy, Default)]
struct Plan {
    nodes: u32,
    leaves: u32,
    opens: u32,
    /// Refined (split or subtree) rather than kept as one leaf.
    refine: bool,
}

impl Plan {
    const LEAF: Plan = Plan {
        nodes: 0,
        leaves: 1,
        opens: 0,
        refine: false,
    };
    fn of_tree(t: &[Local]) -> Plan {
        let mut p = Plan {
            refine: true,
            ..Plan::default()
        };
        for l in t {
            match l {
                Local::Mid(_) | Local::At(..) => p.nodes += 2,
                Local::Leaf(_) => p.leaves += 1,
                Local::Open => p.opens += 1,
            }
        }
        p
    }
    /// What a box's outcome asks for.
    fn of(outcome: &Outcome) -> Plan {
        match outcome {
            Outcome::Leaf => Plan::LEAF,
            Outcome::Split(_) => Plan {
                nodes: 2,
                leaves: 0,
                opens: 2,
                refine: true,
            },
            Outcome::Tree(t) => Plan::of_tree(t),
        }
    }
    /// Leaves (counting open boxes) it adds beyond the box itself.
    fn extra(&self) -> usize {
        (self.leaves + self.opens) as usize - 1
    }
}

/// Uninitialised capacity that boxes fill in parallel, each through its
/// own disjoint part.
struct Shared<T> {
    ptr: *mut MaybeUninit<T>,
    len: usize,
}

// SAFETY: parts handed out are disjoint (offsets from prefix sums), so no
// two threads write the same slot; `T: Send` moves values across threads.
unsafe impl<T: Send> Sync for Shared<T> {}

impl<T> Shared<T> {
    fn new(s: &mut [MaybeUninit<T>]) -> Self {
        Shared {
            ptr: s.as_mut_ptr(),
            len: s.len(),
        }
    }
    /// The whole allocation of `v`, initialised part and spare capacity.
    fn whole(v: &mut Vec<T>) -> Self {
        Shared {
            ptr: v.as_mut_ptr().cast::<MaybeUninit<T>>(),
            len: v.capacity(),
        }
    }
    /// The part `[start, start + n)`. Callers take disjoint parts.
    #[allow(clippy::mut_from_ref)]
    fn part(&self, start: usize, n: usize) -> &mut [MaybeUninit<T>] {
        assert!(start + n <= self.len, "part within the reserved capacity");
        // SAFETY: in bounds (asserted); disjoint from every other part taken
        // (each box's offsets come from one prefix sum).
        unsafe { std::slice::from_raw_parts_mut(self.ptr.add(start), n) }
    }
}

/// One box's share of the new nodes, leaves and open boxes of a level.
struct Filler<'a, Sl> {
    arena: &'a mut [MaybeUninit<Building>],
    arena_base: u32,
    leaves: &'a mut [MaybeUninit<Leaf>],
    leaf_base: u32,
    opens: &'a mut [MaybeUninit<Open<Sl>>],
    used: [usize; 3],
}

impl<Sl> Filler<'_, Sl> {
    /// Writes the local subtree rooted at node `id` (box `bx`); returns the
    /// entry of `id` itself.
    fn expand(
        &mut self,
        t: &[Local],
        pos: &mut usize,
        id: u32,
        bx: PhaseBox,
        slab: Option<Arc<Sl>>,
    ) -> Building {
        let item = t[*pos];
        *pos += 1;
        let (ax, (lo, hi)) = match item {
            Local::Leaf(labels) => {
                let i = self.used[1];
                self.used[1] += 1;
                self.leaves[i].write(Leaf { bx, labels });
                return Building::Leaf(self.leaf_base + i as u32);
            }
            Local::Open => {
                let i = self.used[2];
                self.used[2] += 1;
                self.opens[i].write(Open {
                    node: id,
                    bx,
                    fresh: slab.is_none(),
                    slab,
                });
                return Building::Open;
            }
            Local::Mid(ax) => (ax, bx.split(ax as usize)),
            Local::At(ax, p) => (
                ax,
                bx.split_at(ax as usize, p)
                    .expect("contraction points lie strictly inside"),
            ),
        };
        let i = self.used[0];
        self.used[0] += 2;
        let a = self.arena_base + i as u32;
        // Below a θ split the parent's slab no longer applies.
        let child_slab = if ax == 1 { slab } else { None };
        let l = self.expand(t, pos, a, lo, child_slab.clone());
        let h = self.expand(t, pos, a + 1, hi, child_slab);
        self.arena[i].write(l);
        self.arena[i + 1].write(h);
        match item {
            Local::At(_, p) => Building::SplitAt(ax, p, a),
            _ => Building::Split(ax, a),
        }
    }
}

/// Subtrees of at most this many nodes are written by one thread.
const SERIAL_SUBTREE: u32 = 1 << 15;

/// The tree in preorder with its leaves renumbered in that order. Subtree
/// sizes give every subtree its place in the output, so large subtrees are
/// written in parallel; the result does not depend on the thread count.
fn preorder(arena: &[Building], leaves: &[Leaf]) -> (Vec<Node>, Vec<Leaf>) {
    // Children come after their parent in the arena: sizes in one reverse pass.
    let mut size = vec![(0u32, 0u32); arena.len()];
    for i in (0..arena.len()).rev() {
        size[i] = match arena[i] {
            Building::Split(_, a) | Building::SplitAt(_, _, a) => {
                let (l, h) = (size[a as usize], size[a as usize + 1]);
                (1 + l.0 + h.0, l.1 + h.1)
            }
            _ => (1, 1),
        };
    }
    // Every node and leaf is reachable from the root exactly once.
    assert_eq!(size[0], (arena.len() as u32, leaves.len() as u32));
    let mut nodes = Vec::with_capacity(arena.len());
    let mut out = Vec::with_capacity(leaves.len());
    write_preorder(
        arena,
        leaves,
        &size,
        0,
        &mut nodes.spare_capacity_mut()[..arena.len()],
        &mut out.spare_capacity_mut()[..leaves.len()],
        0,
    );
    // SAFETY: the walk wrote one entry per node and per leaf (sizes
    // asserted above), each at its own preorder position.
    unsafe {
        nodes.set_len(arena.len());
        out.set_len(leaves.len());
    }
    (nodes, out)
}

fn write_preorder(
    arena: &[Building],
    leaves: &[Leaf],
    size: &[(u32, u32)],
    root: u32,
    nodes: &mut [MaybeUninit<Node>],
    out: &mut [MaybeUninit<Leaf>],
    leaf_base: u32,
) {
    if size[root as usize].0 <= SERIAL_SUBTREE {
        let (mut n, mut l) = (0, 0);
        let mut stack = vec![root];
        while let Some(i) = stack.pop() {
            nodes[n].write(match arena[i as usize] {
                Building::Split(ax, a) => {
                    stack.extend([a + 1, a]);
                    Node::Split(ax)
                }
                Building::SplitAt(ax, p, a) => {
                    stack.extend([a + 1, a]);
                    Node::SplitAt(ax, p)
                }
                Building::Leaf(k) => {
                    out[l].write(leaves[k as usize]);
                    l += 1;
                    Node::Leaf(leaf_base + l as u32 - 1)
                }
                Building::Open => unreachable!("every box ends as a leaf or a split"),
            });
            n += 1;
        }
        return;
    }
    let a = match arena[root as usize] {
        Building::Split(ax, a) => {
            nodes[0].write(Node::Split(ax));
            a
        }
        Building::SplitAt(ax, p, a) => {
            nodes[0].write(Node::SplitAt(ax, p));
            a
        }
        _ => unreachable!("a large subtree is a split"),
    };
    let (ln, rn) = nodes[1..].split_at_mut(size[a as usize].0 as usize);
    let (ll, rl) = out.split_at_mut(size[a as usize].1 as usize);
    let right_base = leaf_base + size[a as usize].1;
    rayon::join(
        || write_preorder(arena, leaves, size, a, ln, ll, leaf_base),
        || write_preorder(arena, leaves, size, a + 1, rn, rl, right_base),
    );
}

/// Below this many items a level's step runs on the calling thread: waking
/// the pool costs more (tens of µs per call) than the work.
const PAR_MIN: usize = 1024;
/// The same for work of a microsecond or more per item (slabs, processing).
/// The pool's first use in a process also starts its threads (about 0.2 ms
/// here): from 512 items a level has enough work to pay for it. (At 64, a
/// coarse paving's whole process was up to a quarter slower than serial.)
const PAR_MIN_HEAVY: usize = 512;

fn par_map<T: Sync, U: Send>(xs: &[T], min: usize, f: impl Fn(&T) -> U + Sync + Send) -> Vec<U> {
    par_map_range(xs.len(), min, |k| f(&xs[k]))
}

/// `f(k)` for `k` in `0..n`, in parallel from `min` items.
fn par_map_range<U: Send>(n: usize, min: usize, f: impl Fn(usize) -> U + Sync + Send) -> Vec<U> {
    if n < min {
        (0..n).map(f).collect()
    } else {
        (0..n).into_par_iter().map(f).collect()
    }
}

fn par_each_mut<T: Send>(xs: &mut [T], f: impl Fn(&mut T) + Sync + Send) {
    if xs.len() < PAR_MIN {
        xs.iter_mut().for_each(f)
    } else {
        xs.par_iter_mut().for_each(f)
    }
}

/// `f(index, item)` for every item, consuming the vector.
fn par_each_owned<T: Send>(xs: Vec<T>, f: impl Fn(usize, T) + Sync + Send) {
    if xs.len() < PAR_MIN {
        xs.into_iter().enumerate().for_each(|(k, x)| f(k, x))
    } else {
        xs.into_par_iter().enumerate().for_each(|(k, x)| f(k, x))
    }
}

fn slab_key(b: &PhaseBox) -> (u64, u64) {
    (b.theta[0].to_bits(), b.theta[1].to_bits())
}

/// One timed run of a method on a scene, summarised for charts and tables.
#[derive(Clone, Debug, Serialize)]
pub struct MethodRun {
    pub method: Method,
    pub eps: f64,
    pub leaves: usize,
    /// Outer − inner area of the region asked for (rounded up).
    pub undecided_area: f64,
    pub inner_area: f64,
    pub outer_area: f64,
    pub box_evaluations: u64,
    pub slab_evaluations: u64,
    pub bytes_per_leaf: f64,
    pub peak_bytes_per_leaf: f64,
    /// Wall time of the paving alone.
    pub seconds: f64,
    pub stop: StopReason,
}

/// Paves `domain` of a scene with `method` for the region or cell
/// `region` (an index into [`super::standard_cells`], refining only its
/// constraints; `None`: all constraints, areas of Ω) and reports the run.
pub fn run_method(
    scene: &crate::scene::Scene,
    variant: crate::scene::Variant,
    domain: &crate::scene::Domain,
    region: Option<usize>,
    method: Method,
    opts: PaveOptions,
) -> Result<(MethodRun, Paving), PaveError> {
    let cells = super::standard_cells();
    let cell = cells.get(region.unwrap_or(0)).copied().unwrap_or(cells[0]);
    let mo = match region {
        Some(_) => MethodOptions::for_cell(method, &cell),
        None => MethodOptions::new(method),
    };
    let start = std::time::Instant::now();
    let p = super::pave_scene_method(scene, variant, domain, opts, &mo, |_, _, _| {})?;
    let seconds = start.elapsed().as_secs_f64();
    let b = p.area_bounds(&cell, domain.uncovered_area_sup());
    Ok((
        MethodRun {
            method,
            eps: opts.eps,
            leaves: p.leaves.len(),
            undecided_area: b.undecided_area(),
            inner_area: b.inner_area,
            outer_area: b.outer_area,
            box_evaluations: p.stats.box_evaluations,
            slab_evaluations: p.stats.slab_evaluations,
            bytes_per_leaf: p.stats.bytes_per_leaf,
            peak_bytes_per_leaf: p.stats.peak_bytes_per_leaf,
            seconds,
            stop: p.stop,
        },
        p,
    ))
}
