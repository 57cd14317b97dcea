//! The level-synchronous paving loop every method shares.
//!
//! A level's open boxes are processed independently (in parallel), then the
//! tree grows by one level in a fixed order, so the tree is the same whatever
//! the thread count. One level is three steps: the θ-slabs its boxes share
//! ([`share_slabs`], or the slabs at their θ-ends, [`LastEnd`]), whether
//! the budget takes the level's refinements ([`schedule`]), and the level
//! written into the tree ([`Tree::grow`]). What a method adds —
//! how it steers, which subtree it gives an undecided box — is behind
//! [`Refine`].

use super::bisection::Bisection;
use super::labels::Scope;
use super::level::{
    make_room, par_each_mut, refill, serial, Done, Labels, Local, Open, Outcome, Plan, Span,
    Subtrees, Work, PAR_MIN,
};
use super::tree::Tree;
use super::{
    BudgetStop, ConstraintSet, Label, LevelFlow, PaveOptions, PaveStats, Paving, PhaseBox,
    SlabEnds, StopReason,
};
use inari::Interval;
use rayon::prelude::*;
use std::mem::size_of;
use std::sync::Arc;

/// A refinement method: where bisection stops, and what it does with a box
/// left undecided by the natural labels beyond bisecting it.
pub(super) trait Refine<S: ConstraintSet>: Sync {
    /// The engine computes each θ-slab once per level for all the boxes
    /// that need it. Otherwise a fresh box computes its own slab with the
    /// end data the monotone test needs (the slab at its lower θ-end
    /// shared with the box before it, [`LastEnd`]).
    const SHARED_SLABS: bool = true;

    fn scope(&self) -> &Scope<'_, S>;
    /// Where bisection stops: `natural`'s grid, which [`Refine::choose_axis`]
    /// and [`Refine::at_ulp_limit`] follow; `None` for a method with a rule
    /// of its own, which then overrides both.
    fn grid(&self) -> Option<&Bisection>;
    /// The axis to bisect an undecided box along, if any.
    fn choose_axis(&self, b: &PhaseBox) -> Option<u8> {
        self.grid().and_then(|g| g.choose_axis(b))
    }
    /// The box is above the resolution but one ulp wide along such an axis.
    fn at_ulp_limit(&self, b: &PhaseBox) -> bool {
        self.grid().is_some_and(|g| g.at_ulp_limit(b))
    }
    /// A fresh box divided in θ before any interval work, at most `levels`
    /// levels down (`levels` ≥ 1): the θ-subtree appended to `out`, whose
    /// open boxes are [`Local::Settled`] where the method will not divide
    /// them further. False, `out` as it was, to evaluate it now.
    fn split_unevaluated(&self, _b: &PhaseBox, _levels: u32, _out: &mut Vec<Local>) -> bool {
        false
    }
    /// A subtree for an undecided box, instead of bisecting it, appended to
    /// `out`; false, `out` as it was, for none. `ends`: the slab's end
    /// data when computed with the slab.
    fn subtree(
        &self,
        o: &Open<S::Slab>,
        slab: &S::Slab,
        ends: Option<&[SlabEnds]>,
        labels: &Labels,
        work: &mut Work,
        out: &mut Vec<Local>,
    ) -> bool;
}

/// What is left unrefined, hence why refinement stopped.
#[derive(Default)]
struct Left {
    /// The caller asked to stop (the progress callback).
    interrupted: bool,
    /// A refinement did not fit in the budget.
    budget: bool,
    /// An undecided box above the resolution could not be split.
    ulp_limit: bool,
    /// Some leaf is undecided.
    undecided: bool,
}

impl Left {
    fn stop(&self) -> StopReason {
        if self.interrupted {
            StopReason::Interrupted
        } else if self.budget {
            StopReason::Budget
        } else if self.ulp_limit {
            StopReason::DoublePrecisionLimit
        } else if self.undecided {
            StopReason::Resolution
        } else {
            StopReason::AllDecided
        }
    }
}

/// Paves `root` with `method`; arguments already checked.
///
/// A level whose refinements do not all fit in the budget ends the run:
/// [`Overflow`] says what the asked ε needs, and [`super::budget`] finds a
/// coarser resolution that fits. Only at the root is a paving kept: the
/// root alone, the coarsest one there is.
///
/// A `progress` that asks to stop ends the run at that level: its boxes are
/// labelled and kept as leaves, a valid paving coarser than asked.
pub(super) fn pave<S: ConstraintSet, R: Refine<S>, F: LevelFlow>(
    method: &R,
    root: PhaseBox,
    opts: PaveOptions,
    names: Vec<String>,
    mut progress: impl FnMut(u32, usize, usize) -> F,
) -> Result<Paving, Overflow> {
    let Run {
        tree,
        mut stats,
        left,
        peak,
        bite,
    } = grow_levels(method, root, opts, &mut progress)?;
    let stop = left.stop();
    let (nodes, leaves, assembly) = tree.into_preorder(root);
    let peak = peak.max(assembly);
    let bytes =
        nodes.capacity() * size_of::<super::Node>() + leaves.capacity() * size_of::<super::Leaf>();
    stats.bytes_per_leaf = bytes as f64 / leaves.len().max(1) as f64;
    stats.peak_bytes_per_leaf = peak as f64 / leaves.len().max(1) as f64;
    Ok(Paving {
        root,
        names,
        eps: opts.eps,
        nodes,
        leaves,
        complete: !matches!(stop, StopReason::Budget | StopReason::Interrupted),
        stop,
        budget: bite,
        same_as: method.scope().same_as.clone(),
        stats,
    })
}

/// A finished run of the level loop.
struct Run {
    tree: Tree,
    stats: PaveStats,
    left: Left,
    peak: usize,
    /// What the asked ε needs, when the budget stopped the root's level.
    bite: Option<BudgetStop>,
}

/// A run the budget stopped below the root: what the asked ε needs, the
/// work done and the most memory held.
pub(super) struct Overflow {
    pub budget: BudgetStop,
    pub stats: PaveStats,
    pub peak: usize,
}

/// The level loop.
fn grow_levels<S: ConstraintSet, R: Refine<S>, F: LevelFlow>(
    method: &R,
    root: PhaseBox,
    opts: PaveOptions,
    progress: &mut impl FnMut(u32, usize, usize) -> F,
) -> Result<Run, Overflow> {
    let set = method.scope().set;
    let mut tree = Tree::new();
    let mut frontier: Vec<Open<S::Slab>> = vec![Open {
        bx: root,
        slab: None,
        fresh: true,
        settled: false,
    }];
    let mut stats = PaveStats::default();
    let mut left = Left::default();
    let mut level = 0u32;
    let mut peak = 0usize;
    // Open boxes per level (for the estimate of what ε needs).
    let mut opens = Vec::new();
    let mut bite = None;
    // Per-level buffers, reused (their pages are touched once): this
    // level's results and plan, and the next level's frontier (the buffer
    // of the level before).
    let (mut done, mut plan, mut next) = (Vec::new(), Vec::new(), Vec::new());
    let mut subtrees = Subtrees::default();

    while !frontier.is_empty() {
        let stop_here = !progress(level, frontier.len(), tree.leaves()).go_on();
        opens.push(frontier.len());
        let shared = if R::SHARED_SLABS {
            share_slabs(set, &mut frontier)
        } else {
            0
        };
        // Visited in fixed runs of boxes, each run in order with its own
        // [`LastEnd`]: the work counted is the same on any thread count.
        make_room(&mut done, frontier.len());
        let boxes = &frontier[..];
        let room = opts.max_boxes.saturating_sub(tree.leaves());
        let levels = division_levels(level, frontier.len(), room);
        let run = run_length(level);
        let visit = |(r, buf)| visit_run(method, (boxes, run), levels, r, buf);
        let runs = subtrees.reset(frontier.len().div_ceil(run));
        if serial(frontier.len(), PAR_MIN_HEAVY) && run == VISIT_RUN {
            done.extend(runs.iter_mut().enumerate().flat_map(visit));
        } else {
            done.par_extend(runs.par_iter_mut().enumerate().flat_map_iter(visit));
        }
        stats.slab_evaluations += shared as u64;
        let work = |k: usize| {
            let d = &done[k];
            [d.work.evals, d.work.slabs, d.slab.is_some() as u64]
        };
        let add = |a: [u64; 3], b: [u64; 3]| std::array::from_fn(|i| a[i] + b[i]);
        let [evals, slabs, own_slabs] = par_fold(done.len(), [0; 3], work, add);
        stats.box_evaluations += evals;
        stats.slab_evaluations += slabs;

        let demand = if stop_here {
            refill(&mut plan, done.len(), PAR_MIN, |_| Plan::LEAF);
            left.interrupted = true;
            None
        } else {
            schedule(
                method,
                &frontier,
                (&done, &subtrees),
                &tree,
                opts.max_boxes,
                &mut left,
                &mut plan,
            )
        };
        // Everything held at this point: the tree and its bookkeeping, both
        // frontiers, this level's results and plan, and the slabs computed
        // for it.
        let slabs_held = (shared + own_slabs as usize) * (size_of::<S::Slab>() + 16);
        let held = |tree: &Tree, opens: usize, done: usize, plan: usize| {
            tree.bytes()
                + opens * size_of::<Open<S::Slab>>()
                + done * size_of::<Done<S::Slab>>()
                + subtrees.bytes()
                + plan * size_of::<Plan>()
                + slabs_held
        };
        if let Some(needed) = demand {
            let budget = BudgetStop::new(opts, level, &opens, tree.leaves(), needed);
            if level > 0 {
                let held = held(
                    &tree,
                    frontier.capacity() + next.capacity(),
                    done.capacity(),
                    plan.capacity(),
                );
                return Err(Overflow {
                    budget,
                    stats,
                    peak: peak.max(held),
                });
            }
            // The root alone.
            plan.fill(Plan::LEAF);
            left.budget = true;
            bite = Some(budget);
        }
        tree.grow(&mut frontier, &mut done, &subtrees, &plan, &mut next);
        peak = peak.max(held(
            &tree,
            frontier.capacity() + next.capacity(),
            done.capacity(),
            plan.capacity(),
        ));
        // Emptied off the main thread (the drops release slabs); the
        // buffers are reused.
        par_clear(&mut done);
        par_clear(&mut frontier);
        std::mem::swap(&mut frontier, &mut next);
        if !frontier.is_empty() {
            level += 1;
        }
    }
    stats.depth = level;
    Ok(Run {
        tree,
        stats,
        left,
        peak,
        bite,
    })
}

impl BudgetStop {
    /// At level `level`, where `opens` boxes were open per level so far
    /// and `leaves` leaves made, the budget could not take the `needed`
    /// leaves the level asked for (open boxes counted as leaves).
    fn new(opts: PaveOptions, level: u32, opens: &[usize], leaves: usize, needed: usize) -> Self {
        // Levels at the resolution: two per halving of each axis (slices
        // halve θ alone down to ε²: as many).
        let depth = 2.0 * (1.0 / opts.eps).log2().ceil().clamp(0.0, 1100.0);
        let d = (depth - f64::from(level)).max(0.0);
        let n = *opens.last().expect("a level") as f64;
        // Growth per level of the open boxes over the last four levels: of
        // the 2n boxes a level makes, g·n stay open and (2 − g)·n are leaves.
        let back = (opens.len() - 1).min(4);
        let g = if back == 0 {
            2.0
        } else {
            (n / opens[opens.len() - 1 - back] as f64)
                .powf(1.0 / back as f64)
                .clamp(1.0, 2.0)
        };
        let series = if g == 1.0 {
            d
        } else {
            (g.powf(d) - 1.0) / (g - 1.0)
        };
        let estimate = leaves as f64 + n * ((2.0 - g) * series + g.powf(d));
        BudgetStop {
            option: "max_boxes",
            max_boxes: opts.max_boxes,
            leaves_needed_at_least: needed,
            leaves_needed_estimate: estimate.max(needed as f64).min(f64::MAX),
            complete_at_eps: None,
        }
    }
}

/// θ-slabs of boxes just split in θ (fresh boxes are exactly those without
/// a slab), each computed once per level; boxes split in θ̇ share their
/// parent's slab. Returns how many were computed.
fn share_slabs<S: ConstraintSet>(set: &S, frontier: &mut [Open<S::Slab>]) -> usize {
    let mut missing = Vec::new();
    distinct(&mut missing, frontier.len(), |k| {
        let o = &frontier[k];
        o.slab.is_none().then(|| slab_key(&o.bx))
    });
    let fresh: Vec<Arc<S::Slab>> = par_map(&missing, PAR_MIN_HEAVY, |&(lo, hi)| {
        let th = Interval::try_from((f64::from_bits(lo), f64::from_bits(hi)))
            .expect("ordered endpoints");
        Arc::new(set.slab(th))
    });
    par_each_mut(frontier, |o| {
        if o.slab.is_none() {
            let k = missing
                .binary_search(&slab_key(&o.bx))
                .expect("every missing slab computed");
            o.slab = Some(fresh[k].clone());
        }
    });
    missing.len()
}

/// The slabs at the θ-ends of the box visited last, where the next box of
/// its level mostly starts: two slots, each written in place, the upper
/// end's becoming the next box's lower end's.
struct LastEnd<Sl> {
    slots: [Option<(u64, Sl)>; 2],
    /// The slot of the last box's upper end.
    upper: usize,
}

impl<Sl> Default for LastEnd<Sl> {
    fn default() -> Self {
        LastEnd {
            slots: [None, None],
            upper: 0,
        }
    }
}

impl<Sl> LastEnd<Sl> {
    /// The slabs at `t0` and `t1` (`end` computes one not kept), and the
    /// number computed.
    fn ends(
        &mut self,
        t0: f64,
        t1: f64,
        end: impl Fn(f64) -> Option<Sl>,
    ) -> ([Option<&Sl>; 2], u64) {
        let (lo, hi) = (self.upper, 1 - self.upper);
        let kept = matches!(&self.slots[lo], Some((b, _)) if *b == t0.to_bits());
        let mut computed = 0;
        if !kept {
            self.slots[lo] = end(t0).map(|s| (t0.to_bits(), s));
            computed += u64::from(self.slots[lo].is_some());
        }
        self.slots[hi] = end(t1).map(|s| (t1.to_bits(), s));
        computed += u64::from(self.slots[hi].is_some());
        self.upper = hi;
        fn slab<Sl>(s: &Option<(u64, Sl)>) -> Option<&Sl> {
            s.as_ref().map(|(_, s)| s)
        }
        let [a, b] = &self.slots;
        let pair = if lo == 0 {
            [slab(a), slab(b)]
        } else {
            [slab(b), slab(a)]
        };
        (pair, computed)
    }
}

/// Processes run `r` (of `run` boxes) of a level's `boxes` in order, with
/// its own [`LastEnd`], its subtrees kept in `buf`.
fn visit_run<'a, S: ConstraintSet, R: Refine<S>>(
    method: &'a R,
    (boxes, run): (&'a [Open<S::Slab>], usize),
    levels: u32,
    r: usize,
    buf: &'a mut Vec<Local>,
) -> impl Iterator<Item = Done<S::Slab>> + 'a {
    let mut last = LastEnd::default();
    let ks = r * run..boxes.len().min((r + 1) * run);
    ks.map(move |k| visit(method, &boxes[k], levels, &mut last, (r, &mut *buf)))
}

/// Processes one open box: natural labels, then, while a relevant
/// constraint is undecided, the method's subtree or a bisection. A fresh
/// slab the method calls too coarse is divided in θ before any interval
/// work (undecided as far as computed), at most `levels` levels down.
fn visit<S: ConstraintSet, R: Refine<S>>(
    method: &R,
    o: &Open<S::Slab>,
    levels: u32,
    last: &mut LastEnd<S::Slab>,
    (run, buf): (usize, &mut Vec<Local>),
) -> Done<S::Slab> {
    let scope = method.scope();
    let mut work = Work::default();
    let start = buf.len();
    if o.fresh && !o.settled && method.split_unevaluated(&o.bx, levels, buf) {
        return Done {
            labels: Labels::filled(Label::Undecided, scope.n),
            outcome: Outcome::Tree(Span::of(run, start, buf)),
            work,
            slab: None,
        };
    }
    let mut own = None;
    let (slab, ends) = match o.slab.as_deref() {
        Some(slab) => (slab, None),
        None => {
            // The slabs at its θ-ends: the lower one mostly kept from the
            // box before, the upper one kept for the box after.
            let [t0, t1] = o.bx.theta;
            let (known, computed) = last.ends(t0, t1, |t| scope.set.end_slab(t));
            work.slabs += 1 + computed;
            let (slab, ends) = scope.set.slab_and_ends_at(o.bx.theta_interval(), known);
            (&*own.insert(slab), ends)
        }
    };
    let labels = scope.natural(slab, &o.bx, &mut work);
    let outcome = if !scope.undecided(&labels) {
        Outcome::Leaf
    } else if method.subtree(o, slab, ends.as_deref(), &labels, &mut work, buf) {
        Outcome::Tree(Span::of(run, start, buf))
    } else {
        match method.choose_axis(&o.bx) {
            Some(ax) => Outcome::Split(ax),
            None => Outcome::Leaf,
        }
    };
    // Kept (and allocated) only for children that share it.
    let shares = outcome.shares_slab(&buf[start..]);
    let slab = own.filter(|_| shares).map(Arc::new);
    Done {
        labels,
        outcome,
        work,
        slab,
    }
}

/// Every box of a level that asks is refined when the budget takes them
/// all: records what is left unrefined and returns `None`. Otherwise
/// returns the leaves the level asked for (open boxes counted). `done`:
/// what each box of `frontier` decided, its subtree in `subtrees`.
fn schedule<S: ConstraintSet, R: Refine<S>>(
    method: &R,
    frontier: &[Open<S::Slab>],
    (done, subtrees): (&[Done<S::Slab>], &Subtrees),
    tree: &Tree,
    max_boxes: usize,
    left: &mut Left,
    plan: &mut Vec<Plan>,
) -> Option<usize> {
    let scope = method.scope();
    refill(plan, done.len(), PAR_MIN, |k| {
        Plan::of(&done[k].outcome, subtrees)
    });
    let counts = &plan[..];
    let want = |k: usize| match counts[k] {
        c if c.refine => [c.extra(), c.nodes as usize],
        _ => [0, 0],
    };
    let [want_leaves, want_nodes] = par_fold(counts.len(), [0, 0], want, |a, b| {
        [a[0] + b[0], a[1] + b[1]]
    });
    let room = (u32::MAX as usize).saturating_sub(tree.nodes() + 2 * frontier.len());
    let needed = tree.leaves() + frontier.len() + want_leaves;
    if needed > max_boxes || want_nodes > room {
        return Some(needed);
    }
    let undecided_leaf = |t: &[Local]| {
        t.iter()
            .any(|l| matches!(l, Local::Leaf(x) if scope.undecided(x)))
    };
    // What is left undecided, found in parallel.
    let left_by = |k: usize| -> [bool; 2] {
        let d = &done[k];
        if counts[k].refine {
            // A subtree left undecided on a slab that cannot be split
            // further stopped at the limit of double precision.
            let undecided = undecided_leaf(d.outcome.tree(subtrees));
            [undecided, undecided && method.at_ulp_limit(&frontier[k].bx)]
        } else if scope.undecided(&d.labels) {
            [true, method.at_ulp_limit(&frontier[k].bx)]
        } else {
            [false, false]
        }
    };
    let [undecided, ulp_limit] = par_fold(done.len(), [false, false], left_by, |a, b| {
        [a[0] | b[0], a[1] | b[1]]
    });
    left.undecided |= undecided;
    left.ulp_limit |= ulp_limit;
    None
}

/// `out` refilled with the keys `keys(k)` gives for `k` in `0..n`, sorted
/// and each once: what a level computes once for all its boxes. In
/// parallel from [`PAR_MIN`].
fn distinct<K, I>(out: &mut Vec<K>, n: usize, keys: impl Fn(usize) -> I + Sync + Send)
where
    K: Ord + Send,
    I: IntoIterator<Item = K>,
    I::IntoIter: Send,
{
    out.clear();
    if serial(n, PAR_MIN) {
        out.extend((0..n).flat_map(keys));
    } else {
        out.par_extend((0..n).into_par_iter().flat_map_iter(keys));
    }
    if serial(out.len(), PAR_MIN) {
        out.sort_unstable();
    } else {
        out.par_sort_unstable();
    }
    out.dedup();
}

fn slab_key(b: &PhaseBox) -> (u64, u64) {
    (b.theta[0].to_bits(), b.theta[1].to_bits())
}

/// The same for work of a microsecond or more per item (slabs, processing).
/// The pool's first use in a process also starts its threads (about 0.2 ms
/// here): from 512 items a level has enough work to pay for it. (At 64, a
/// coarse paving's whole process was up to a quarter slower than serial.)
const PAR_MIN_HEAVY: usize = 512;

/// The boxes one level's θ-divisions before interval work may make at
/// most: the budget and an interruption are heeded between levels, so a
/// level must stay short and its memory small.
const DIVISION_BOXES: usize = 1 << 20;

/// Levels the root is divided at most before interval work: the boxes it
/// leaves open are the next level's, one run each, shared by the threads,
/// and each is divided as deep as [`DIVISION_BOXES`] allows, so that most
/// final slabs of a paving are visited in one level, in order, and share
/// the slabs where they meet.
const ROOT_LEVELS: u32 = 6;

/// How many levels down each of level `level`'s `boxes` fresh boxes may
/// be divided before interval work (at least one: a single split), so
/// that the level makes at most [`DIVISION_BOXES`] boxes and no more than
/// the budget's `room`; the root at most [`ROOT_LEVELS`].
fn division_levels(level: u32, boxes: usize, room: usize) -> u32 {
    let levels = (DIVISION_BOXES.min(room) / boxes.max(1)).max(2).ilog2();
    if level == 0 {
        levels.min(ROOT_LEVELS)
    } else {
        levels
    }
}

/// Boxes per run on level `level`: one on the root's open boxes (each a
/// division of its own), else [`VISIT_RUN`].
fn run_length(level: u32) -> usize {
    if level == 1 {
        1
    } else {
        VISIT_RUN
    }
}

/// Boxes visited in order by one thread, sharing end slabs ([`LastEnd`]).
const VISIT_RUN: usize = 256;

fn par_map<T: Sync, U: Send>(xs: &[T], min: usize, f: impl Fn(&T) -> U + Sync + Send) -> Vec<U> {
    if serial(xs.len(), min) {
        xs.iter().map(f).collect()
    } else {
        xs.par_iter().map(f).collect()
    }
}

/// Empties `v`, dropping its items in parallel; its buffer stays.
fn par_clear<T: Send>(v: &mut Vec<T>) {
    if serial(v.len(), PAR_MIN) {
        v.clear();
    } else {
        v.par_drain(..).for_each(drop);
    }
}

/// `f(k)` for `k` in `0..n` combined by `op` (associative, `zero` its
/// identity), in parallel from [`PAR_MIN`] items.
fn par_fold<T: Copy + Send + Sync>(
    n: usize,
    zero: T,
    f: impl Fn(usize) -> T + Sync + Send,
    op: impl Fn(T, T) -> T + Sync + Send,
) -> T {
    if serial(n, PAR_MIN) {
        (0..n).map(f).fold(zero, op)
    } else {
        (0..n).into_par_iter().map(f).reduce(|| zero, op)
    }
}
