//! What one level of the paving loop passes around: the boxes it processes,
//! what each one decided and adds to the tree, and the parallel helpers that
//! fill a level's buffers. Shared by the engine, the tree and the labels.

use super::{Label, PerConstraint, PhaseBox};
use rayon::prelude::*;
use std::sync::Arc;

/// One label per constraint.
pub(super) type Labels = PerConstraint<Label>;

/// A small subtree in preorder, produced for one box.
#[derive(Clone, Copy, Debug)]
pub(super) enum Local {
    Mid(u8),
    At(u8, f64),
    Leaf(Labels),
    /// Stays open: refined at the next level.
    Open,
    /// Stays open, and the method has already decided not to divide it
    /// before interval work: visited at the next level.
    Settled,
}

/// What processing one open box decided.
pub(super) enum Outcome {
    Leaf,
    Split(u8),
    /// A subtree, kept in the level's [`Subtrees`].
    Tree(Span),
}

impl Outcome {
    /// Some child stays open: below θ̇-splits only, it shares the box's slab.
    /// `tree`: the subtree, for [`Outcome::Tree`].
    pub fn shares_slab(&self, tree: &[Local]) -> bool {
        match self {
            Outcome::Leaf | Outcome::Split(0) => false,
            Outcome::Split(_) => true,
            Outcome::Tree(_) => tree
                .iter()
                .any(|l| matches!(l, Local::Open | Local::Settled)),
        }
    }
    /// The subtree, for [`Outcome::Tree`] (else empty).
    pub fn tree<'a>(&self, subtrees: &'a Subtrees) -> &'a [Local] {
        match *self {
            Outcome::Tree(s) => subtrees.get(s),
            _ => &[],
        }
    }
}

/// Where a box's subtree lies in its level's [`Subtrees`].
#[derive(Clone, Copy, Debug)]
pub(super) struct Span {
    run: u32,
    start: u32,
    len: u32,
}

/// A level's subtrees: boxes are visited in runs, and each run writes its
/// boxes' subtrees one after another into one buffer, kept from level to
/// level (a buffer per box was a heap allocation each, alive until the
/// tree took it, which grew and shrank the heap level by level).
#[derive(Default)]
pub(super) struct Subtrees(Vec<Vec<Local>>);

impl Subtrees {
    pub fn get(&self, s: Span) -> &[Local] {
        &self.0[s.run as usize][s.start as usize..][..s.len as usize]
    }
    /// Emptied, with one buffer for each of `runs` runs.
    pub fn reset(&mut self, runs: usize) -> &mut [Vec<Local>] {
        if self.0.len() < runs {
            self.0.resize_with(runs, Vec::new);
        }
        let bufs = &mut self.0[..runs];
        bufs.iter_mut().for_each(Vec::clear);
        bufs
    }
    /// The bytes its buffers hold.
    pub fn bytes(&self) -> usize {
        let locals: usize = self.0.iter().map(Vec::capacity).sum();
        locals * size_of::<Local>() + self.0.capacity() * size_of::<Vec<Local>>()
    }
}

impl Span {
    /// The subtree written to run `run`'s buffer `buf` from `start` on.
    pub fn of(run: usize, start: usize, buf: &[Local]) -> Span {
        Span {
            run: run as u32,
            start: start as u32,
            len: (buf.len() - start) as u32,
        }
    }
}

/// A box to process at the current level.
pub(super) struct Open<Sl> {
    pub bx: PhaseBox,
    pub slab: Option<Arc<Sl>>,
    /// The slab was computed for this box's θ-interval at this level: the
    /// contraction has not seen it yet.
    pub fresh: bool,
    /// Not to be divided before interval work ([`Local::Settled`]).
    pub settled: bool,
}

/// One box processed: its natural labels, outcome, work, and the slab it
/// computed for itself (which its θ̇-children share).
pub(super) struct Done<Sl> {
    pub labels: Labels,
    pub outcome: Outcome,
    pub work: Work,
    pub slab: Option<Arc<Sl>>,
}

/// Per-box work counters.
#[derive(Default, Clone, Copy)]
pub(super) struct Work {
    pub evals: u64,
    pub slabs: u64,
}

/// What one box adds to the tree.
#[derive(Clone, Copy, Default)]
pub(super) struct Plan {
    pub nodes: u32,
    pub leaves: u32,
    pub opens: u32,
    /// Refined (split or subtree) rather than kept as one leaf.
    pub refine: bool,
}

impl Plan {
    pub const LEAF: Plan = Plan {
        nodes: 0,
        leaves: 1,
        opens: 0,
        refine: false,
    };
    pub fn of_tree(t: &[Local]) -> Plan {
        let mut p = Plan {
            refine: true,
            ..Plan::default()
        };
        for l in t {
            match l {
                Local::Mid(_) | Local::At(..) => p.nodes += 2,
                Local::Leaf(_) => p.leaves += 1,
                Local::Open | Local::Settled => p.opens += 1,
            }
        }
        p
    }
    /// What a box's outcome asks for.
    pub fn of(outcome: &Outcome, subtrees: &Subtrees) -> Plan {
        match outcome {
            Outcome::Leaf => Plan::LEAF,
            Outcome::Split(_) => Plan {
                nodes: 2,
                leaves: 0,
                opens: 2,
                refine: true,
            },
            Outcome::Tree(s) => Plan::of_tree(subtrees.get(*s)),
        }
    }
    /// Leaves (counting open boxes) it adds beyond the box itself.
    pub fn extra(&self) -> usize {
        (self.leaves + self.opens) as usize - 1
    }
}

/// Below this many items a level's step runs on the calling thread: waking
/// the pool costs more (tens of µs per call) than the work.
pub(super) const PAR_MIN: usize = 1024;

/// Whether `n` items run on the calling thread: fewer than `min`, or a pool
/// of one thread (where handing work to it only adds a switch per call).
pub(super) fn serial(n: usize, min: usize) -> bool {
    n < min || rayon::current_num_threads() == 1
}

/// `v` holding `f(k)` for `k` in `0..n`, written in parallel from `min`
/// items (so a new buffer's pages are first touched by the
/// pool's threads). A buffer too small is replaced, not grown: nothing
/// is copied, and one never allocated gets exactly `n`.
pub(super) fn refill<T: Send>(
    v: &mut Vec<T>,
    n: usize,
    min: usize,
    f: impl Fn(usize) -> T + Sync + Send,
) {
    make_room(v, n);
    extend(v, 0..n, min, f);
}

/// `v` emptied, with room for `n` items (see [`refill`]).
pub(super) fn make_room<T>(v: &mut Vec<T>, n: usize) {
    v.clear();
    if v.capacity() < n {
        // At least double: a buffer that grows level by level is replaced
        // every other level, not at each (its fresh pages cost faults).
        let cap = n.max(2 * v.capacity());
        *v = Vec::new();
        *v = Vec::with_capacity(cap);
    }
}

/// `f(k)` for `k` in `ks` appended to `v`, in parallel from `min` items.
pub(super) fn extend<T: Send>(
    v: &mut Vec<T>,
    ks: std::ops::Range<usize>,
    min: usize,
    f: impl Fn(usize) -> T + Sync + Send,
) {
    if serial(ks.len(), min) {
        v.extend(ks.map(f));
    } else {
        v.par_extend(ks.into_par_iter().map(f));
    }
}

pub(super) fn par_each_mut<T: Send>(xs: &mut [T], f: impl Fn(&mut T) + Sync + Send) {
    if serial(xs.len(), PAR_MIN) {
        xs.iter_mut().for_each(f)
    } else {
        xs.par_iter_mut().for_each(f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pave::Label;

    /// A box's slab is kept exactly when a child stays open below it: the
    /// θ̇-halves of a split or the open parts of a subtree share it; a
    /// θ-split's halves have slabs of their own.
    #[test]
    fn a_slab_is_kept_only_for_children_that_share_it() {
        let leaf = Local::Leaf(Labels::filled(Label::ProvedIn, 1));
        let trees = [
            vec![Local::At(1, 0.5), leaf, leaf],
            vec![Local::At(1, 0.5), leaf, Local::Open],
            vec![Local::Mid(1), Local::Open, Local::Open],
            vec![Local::Mid(0), Local::Settled, leaf],
        ];
        // Kept in one run's buffer, one after another, as the engine does.
        let mut subtrees = Subtrees::default();
        let buf = &mut subtrees.reset(2)[1];
        let spans: Vec<Span> = trees
            .iter()
            .map(|t| {
                let start = buf.len();
                buf.extend_from_slice(t);
                Span::of(1, start, buf)
            })
            .collect();
        let mut cases = vec![
            (Outcome::Leaf, false),
            (Outcome::Split(0), false),
            (Outcome::Split(1), true),
        ];
        cases.extend(
            spans
                .iter()
                .zip([false, true, true, true])
                .map(|(s, k)| (Outcome::Tree(*s), k)),
        );
        for (k, (outcome, kept)) in cases.iter().enumerate() {
            let tree = outcome.tree(&subtrees);
            assert_eq!(outcome.shares_slab(tree), *kept, "case {k}");
            if k >= 3 {
                assert_eq!(format!("{tree:?}"), format!("{:?}", trees[k - 3]));
            }
        }
    }
}
