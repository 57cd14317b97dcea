//! The bisection tree while it is built: one node array per level, each
//! allocated once at the size the level's schedule asks for and written in
//! parallel through disjoint shares carved from it; the flat preorder tree of
//! a [`super::Paving`] is assembled from the levels at the end.
//!
//! A leaf keeps only its labels: its box is replayed from the root and the
//! splits when the tree is assembled, exactly as the paving computed it.

use super::level::{
    par_each_mut, refill, serial, Done, Labels, Local, Open, Outcome, Plan, Subtrees, PAR_MIN,
};
use super::{Leaf, Node, PhaseBox};
use rayon::prelude::*;
use std::mem::size_of;

/// A node of the tree under construction. The children of a split are
/// entries `a` and `a + 1` of the same level's array, or of the next
/// level's when `next` (the entry of a box refined at that level).
#[derive(Clone, Copy)]
enum Building {
    /// Box `k` of the next level's frontier, until that level replaces the
    /// entry with the box's own.
    Open(u32),
    Leaf(Labels),
    Split {
        axis: u8,
        next: bool,
        a: u32,
    },
    SplitAt {
        axis: u8,
        next: bool,
        a: u32,
        at: f64,
    },
}

const _: () = assert!(size_of::<Building>() == 16);

pub(super) struct Tree {
    /// `levels[0]` holds the root's entry; `levels[l + 1]` the nodes that
    /// paving level `l` adds.
    levels: Vec<Vec<Building>>,
    /// Per level, where runs of whole shares start (every [`SCAN`]-th
    /// box's first node): sizes are computed run by run.
    cuts: Vec<Vec<u32>>,
    /// Each box's first node and first open box in its level, and its own
    /// entry: per-level bookkeeping, reused (its pages are touched once).
    offsets: Vec<[usize; 2]>,
    own: Vec<Building>,
    nodes: usize,
    leaves: usize,
}

impl Tree {
    pub fn new() -> Tree {
        Tree {
            levels: vec![vec![Building::Open(0)]],
            cuts: vec![vec![0]],
            offsets: Vec::new(),
            own: Vec::new(),
            nodes: 1,
            leaves: 0,
        }
    }

    /// Nodes so far, the root and every split's two children.
    pub fn nodes(&self) -> usize {
        self.nodes
    }

    /// Leaves so far.
    pub fn leaves(&self) -> usize {
        self.leaves
    }

    /// Memory held by the levels and their bookkeeping.
    pub fn bytes(&self) -> usize {
        let levels: usize = self
            .levels
            .iter()
            .map(|l| l.capacity() * size_of::<Building>())
            .sum();
        levels
            + self.offsets.capacity() * size_of::<[usize; 2]>()
            + self.own.capacity() * size_of::<Building>()
    }

    /// Adds the level `plan` makes of `frontier` (processed into `done`;
    /// the subtrees and slabs of both are taken): every box's new nodes and
    /// open boxes, and its own entry in the level above. The open boxes are
    /// written to `next`.
    pub fn grow<Sl: Send + Sync>(
        &mut self,
        frontier: &mut [Open<Sl>],
        done: &mut [Done<Sl>],
        subtrees: &Subtrees,
        plan: &[Plan],
        next: &mut Vec<Open<Sl>>,
    ) {
        let (total, cuts) = prefix_sums(plan, &mut self.offsets);
        let mut nodes = Vec::new();
        refill(&mut nodes, total[0], PAR_MIN, |_| Building::Open(0));
        refill(next, total[2], PAR_MIN, |_| Open {
            bx: PhaseBox {
                theta: [0.0; 2],
                theta_dot: [0.0; 2],
            },
            slab: None,
            fresh: false,
            settled: false,
        });
        let boxes = frontier.len();
        refill(&mut self.own, boxes, PAR_MIN, |_| Building::Open(0));
        let shares = Shares {
            boxes: frontier,
            done,
            subtrees,
            plan,
            offsets: &self.offsets,
            own: &mut self.own,
            nodes: &mut nodes,
            opens: next,
        };
        if boxes < PAR_MIN {
            shares.fill();
        } else {
            shares.fill_par();
        }
        // Each open box's entry in the level above, now that it is known.
        let own = &self.own;
        let above = self.levels.last_mut().expect("the root's level");
        par_each_mut(above, |e| {
            if let Building::Open(k) = *e {
                *e = own[k as usize];
            }
        });
        self.levels.push(nodes);
        self.cuts.push(cuts);
        self.nodes += total[0];
        self.leaves += total[1];
    }

    /// The tree in preorder with its leaves numbered in that order, and the
    /// bytes held while assembling it. Subtree sizes give every subtree its
    /// place in the output, so large subtrees are written in parallel; the
    /// result does not depend on the thread count.
    pub fn into_preorder(self, root: PhaseBox) -> (Vec<Node>, Vec<Leaf>, usize) {
        if rayon::current_num_threads() == 1 {
            return self.into_preorder_serial(root);
        }
        let levels = self.levels;
        // Children come after their parent within one box's share of a
        // level, or in the next level: sizes from the last level up, each
        // level's runs of shares (between cuts) in parallel, each run in
        // one reverse pass.
        let mut size: Vec<Vec<u32>> = levels.iter().map(|l| vec![0u32; l.len()]).collect();
        for s in (0..levels.len()).rev() {
            let (this, below) = size.split_at_mut(s + 1);
            let (this, below) = (&mut this[s], below.first().map(|b| &b[..]));
            let mut runs = Vec::with_capacity(self.cuts[s].len());
            let mut rest = &mut this[..];
            let mut from = 0;
            for w in self.cuts[s].windows(2) {
                let (run, r) = rest.split_at_mut(w[1] as usize - w[0] as usize);
                runs.push((from, run));
                (rest, from) = (r, w[1] as usize);
            }
            runs.push((from, rest));
            let level = &levels[s][..];
            let sizes = |(from, run): (usize, &mut [u32])| {
                for i in (0..run.len()).rev() {
                    run[i] = match level[from + i] {
                        Building::Split { next, a, .. } | Building::SplitAt { next, a, .. } => {
                            let a = a as usize;
                            if next {
                                let c = below.expect("a next level");
                                1 + c[a] + c[a + 1]
                            } else {
                                1 + run[a - from] + run[a + 1 - from]
                            }
                        }
                        Building::Leaf(_) => 1,
                        Building::Open(_) => unreachable!("every box ends as a leaf or a split"),
                    };
                }
            };
            if serial(runs.len(), 2) {
                runs.into_iter().for_each(sizes);
            } else {
                runs.into_par_iter().for_each(sizes);
            }
        }
        // Every node and leaf is reachable from the root exactly once (every
        // split has two children: a tree of n nodes has (n + 1) / 2 leaves).
        assert_eq!(size[0][0] as usize, self.nodes);
        assert_eq!(self.nodes.div_ceil(2), self.leaves);
        let (mut nodes, mut leaves) = (Vec::new(), Vec::new());
        refill(&mut nodes, self.nodes, PAR_MIN, |_| Node::Leaf(0));
        refill(&mut leaves, self.leaves, PAR_MIN, |_| Leaf {
            bx: root,
            labels: Labels::filled(super::Label::Undecided, 1),
        });
        let held = assembly_bytes(&levels, &size, (&nodes, &leaves));
        let walk = Walk {
            levels: &levels,
            size: &size,
        };
        walk.write((0, 0), root, &mut nodes, &mut leaves, 0);
        (nodes, leaves, held)
    }

    /// [`Tree::into_preorder`] on one thread: one depth-first pass appends
    /// the nodes and leaves in order (subtree sizes only place the
    /// subtrees written in parallel).
    fn into_preorder_serial(self, root: PhaseBox) -> (Vec<Node>, Vec<Leaf>, usize) {
        let (mut nodes, mut leaves) = (
            Vec::with_capacity(self.nodes),
            Vec::with_capacity(self.leaves),
        );
        let walk = Walk {
            levels: &self.levels,
            size: &[],
        };
        walk.depth_first((0, 0), root, 0, |n| nodes.push(n), |l| leaves.push(l));
        // Every node and leaf is reachable from the root exactly once.
        assert_eq!((nodes.len(), leaves.len()), (self.nodes, self.leaves));
        let held = assembly_bytes(&self.levels, &[], (&nodes, &leaves));
        (nodes, leaves, held)
    }
}

/// The bytes held while the preorder is assembled: the levels, their
/// subtree sizes (if computed) and the output, each by capacity.
fn assembly_bytes(
    levels: &[Vec<Building>],
    size: &[Vec<u32>],
    output: (&Vec<Node>, &Vec<Leaf>),
) -> usize {
    let levels: usize = levels
        .iter()
        .map(|l| l.capacity() * size_of::<Building>())
        .sum();
    let size: usize = size.iter().map(|s| s.capacity() * size_of::<u32>()).sum();
    let (nodes, leaves) = output;
    levels + size + nodes.capacity() * size_of::<Node>() + leaves.capacity() * size_of::<Leaf>()
}

/// Subtrees of at most this many nodes are written by one thread.
const SERIAL_SUBTREE: u32 = 1 << 15;

/// The levels and their subtree sizes, read while writing the preorder.
struct Walk<'a> {
    levels: &'a [Vec<Building>],
    size: &'a [Vec<u32>],
}

impl Walk<'_> {
    /// The subtree at entry `at` (level, index), of box `bx`, in preorder:
    /// each node to `node`, each leaf to `leaf`, its leaves numbered from
    /// `leaf_base`. Needs no subtree sizes.
    fn depth_first(
        &self,
        at: (usize, u32),
        bx: PhaseBox,
        leaf_base: u32,
        mut node: impl FnMut(Node),
        mut leaf: impl FnMut(Leaf),
    ) {
        let mut l = leaf_base;
        let mut stack = vec![(at, bx)];
        while let Some(((s, i), bx)) = stack.pop() {
            node(match self.levels[s][i as usize] {
                Building::Split { axis, next, a } => {
                    let (lo, hi) = bx.split(axis as usize);
                    let c = Self::children(s, next, a);
                    stack.extend([((c.0, c.1 + 1), hi), (c, lo)]);
                    Node::Split(axis)
                }
                Building::SplitAt { axis, next, a, at } => {
                    let (lo, hi) = split_at(&bx, axis, at);
                    let c = Self::children(s, next, a);
                    stack.extend([((c.0, c.1 + 1), hi), (c, lo)]);
                    Node::SplitAt(axis, at)
                }
                Building::Leaf(labels) => {
                    leaf(Leaf { bx, labels });
                    l += 1;
                    Node::Leaf(l - 1)
                }
                Building::Open(_) => unreachable!("every box ends as a leaf or a split"),
            });
        }
    }

    /// The children of entry `e` of level `s`: their level and first index.
    fn children(s: usize, next: bool, a: u32) -> (usize, u32) {
        (s + usize::from(next), a)
    }

    /// Writes the subtree at entry `at` (level, index), of box `bx`, into
    /// `nodes` and `leaves`, numbering its leaves from `leaf_base`.
    fn write(
        &self,
        at: (usize, u32),
        bx: PhaseBox,
        nodes: &mut [Node],
        leaves: &mut [Leaf],
        leaf_base: u32,
    ) {
        let (s, i) = at;
        if self.size[s][i as usize] <= SERIAL_SUBTREE {
            let (mut n, mut l) = (0, 0);
            self.depth_first(
                at,
                bx,
                leaf_base,
                |node| {
                    nodes[n] = node;
                    n += 1;
                },
                |leaf| {
                    leaves[l] = leaf;
                    l += 1;
                },
            );
            return;
        }
        let (c, (lo, hi)) = match self.levels[s][i as usize] {
            Building::Split { axis, next, a } => {
                nodes[0] = Node::Split(axis);
                (Self::children(s, next, a), bx.split(axis as usize))
            }
            Building::SplitAt { axis, next, a, at } => {
                nodes[0] = Node::SplitAt(axis, at);
                (Self::children(s, next, a), split_at(&bx, axis, at))
            }
            _ => unreachable!("a large subtree is a split"),
        };
        let left = self.size[c.0][c.1 as usize];
        let (ln, rn) = nodes[1..].split_at_mut(left as usize);
        let (ll, rl) = leaves.split_at_mut(left.div_ceil(2) as usize);
        let right_base = leaf_base + left.div_ceil(2);
        rayon::join(
            || self.write(c, lo, ln, ll, leaf_base),
            || self.write((c.0, c.1 + 1), hi, rn, rl, right_base),
        );
    }
}

fn split_at(bx: &PhaseBox, axis: u8, at: f64) -> (PhaseBox, PhaseBox) {
    bx.split_at(axis as usize, at)
        .expect("contraction points lie strictly inside")
}

/// Boxes per run of the prefix sums (and of the size pass's runs).
const SCAN: usize = 4096;

/// Each box's first new node and first open box in the level (one prefix
/// sum of the plan, into `offsets`), the level's totals of nodes, leaves
/// and open boxes, and the first node of every [`SCAN`]-th box. A long plan
/// is summed in parallel by runs of boxes, then the runs' starts, then each
/// run.
fn prefix_sums(plan: &[Plan], offsets: &mut Vec<[usize; 2]>) -> ([usize; 3], Vec<u32>) {
    let add = |t: [usize; 3], p: &Plan| {
        [
            t[0] + p.nodes as usize,
            t[1] + p.leaves as usize,
            t[2] + p.opens as usize,
        ]
    };
    let run_sums: Vec<[usize; 3]> = if plan.len() < PAR_MIN {
        vec![plan.iter().fold([0; 3], add)]
    } else {
        plan.par_chunks(SCAN)
            .map(|c| c.iter().fold([0; 3], add))
            .collect()
    };
    let mut starts = Vec::with_capacity(run_sums.len());
    let mut total = [0usize; 3];
    for r in &run_sums {
        starts.push(total);
        total = [total[0] + r[0], total[1] + r[1], total[2] + r[2]];
    }
    let fill = |offsets: &mut [[usize; 2]], plan: &[Plan], start: [usize; 3]| {
        let mut t = start;
        for (o, p) in offsets.iter_mut().zip(plan) {
            *o = [t[0], t[2]];
            t = add(t, p);
        }
    };
    refill(offsets, plan.len(), PAR_MIN, |_| [0usize; 2]);
    if serial(plan.len(), PAR_MIN) {
        fill(offsets, plan, starts[0]);
    } else {
        offsets
            .par_chunks_mut(SCAN)
            .zip(plan.par_chunks(SCAN).zip(starts.par_iter()))
            .for_each(|(o, (p, s))| fill(o, p, *s));
    }
    let cuts = starts.iter().map(|s| s[0] as u32).collect();
    (total, cuts)
}

/// Boxes `[k, k + n)` of a level with their shares of its storage: the new
/// nodes and open boxes of each lie at its offsets (from one prefix sum),
/// so the shares of disjoint runs of boxes are disjoint slices.
struct Shares<'a, Sl> {
    boxes: &'a mut [Open<Sl>],
    done: &'a mut [Done<Sl>],
    subtrees: &'a Subtrees,
    plan: &'a [Plan],
    /// Each box's first node and first open box in the level.
    offsets: &'a [[usize; 2]],
    own: &'a mut [Building],
    nodes: &'a mut [Building],
    opens: &'a mut [Open<Sl>],
}

/// Boxes per task when a level is filled in parallel.
const FILL_GRAIN: usize = 256;

impl<Sl: Send + Sync> Shares<'_, Sl> {
    /// The boxes before `m` and from `m`.
    fn split(self, m: usize) -> (Self, Self) {
        let [n0, o0] = self.offsets[0];
        let [nm, om] = self.offsets[m];
        let (boxes_a, boxes_b) = self.boxes.split_at_mut(m);
        let (done_a, done_b) = self.done.split_at_mut(m);
        let (plan_a, plan_b) = self.plan.split_at(m);
        let (off_a, off_b) = self.offsets.split_at(m);
        let (own_a, own_b) = self.own.split_at_mut(m);
        let (nodes_a, nodes_b) = self.nodes.split_at_mut(nm - n0);
        let (opens_a, opens_b) = self.opens.split_at_mut(om - o0);
        (
            Shares {
                boxes: boxes_a,
                done: done_a,
                subtrees: self.subtrees,
                plan: plan_a,
                offsets: off_a,
                own: own_a,
                nodes: nodes_a,
                opens: opens_a,
            },
            Shares {
                boxes: boxes_b,
                done: done_b,
                subtrees: self.subtrees,
                plan: plan_b,
                offsets: off_b,
                own: own_b,
                nodes: nodes_b,
                opens: opens_b,
            },
        )
    }

    fn fill_par(self) {
        let n = self.boxes.len();
        if n <= FILL_GRAIN {
            return self.fill();
        }
        let (a, b) = self.split(n / 2);
        rayon::join(|| a.fill_par(), || b.fill_par());
    }

    /// Every box writes its share, one after the other.
    fn fill(self) {
        let (mut nodes, mut opens) = (self.nodes, self.opens);
        for (k, o) in self.boxes.iter_mut().enumerate() {
            let d = &mut self.done[k];
            let p = self.plan[k];
            let (my_nodes, rest) = std::mem::take(&mut nodes).split_at_mut(p.nodes as usize);
            nodes = rest;
            let (my_opens, rest) = std::mem::take(&mut opens).split_at_mut(p.opens as usize);
            opens = rest;
            let [node_base, open_base] = self.offsets[k];
            let mut f = Filler {
                nodes: my_nodes,
                node_base: node_base as u32,
                opens: my_opens,
                open_base: open_base as u32,
                used: [0; 2],
            };
            let slab = d.slab.take().or_else(|| o.slab.take());
            let outcome = std::mem::replace(&mut d.outcome, Outcome::Leaf);
            self.own[k] = if p.refine {
                match outcome {
                    Outcome::Split(ax) => {
                        let t = [Local::Mid(ax), Local::Open, Local::Open];
                        f.expand(&t, &mut 0, o.bx, slab, true)
                    }
                    Outcome::Tree(t) => f.expand(self.subtrees.get(t), &mut 0, o.bx, slab, true),
                    Outcome::Leaf => unreachable!("a leaf is not refined"),
                }
            } else {
                Building::Leaf(d.labels)
            };
            // Every planned slot written.
            assert_eq!(f.used, [p.nodes as usize, p.opens as usize]);
        }
    }
}

/// One box's share of the new nodes and open boxes of a level.
struct Filler<'a, Sl> {
    nodes: &'a mut [Building],
    node_base: u32,
    opens: &'a mut [Open<Sl>],
    open_base: u32,
    used: [usize; 2],
}

impl<Sl> Filler<'_, Sl> {
    /// Writes the local subtree of box `bx` and returns its root entry;
    /// `next`: that entry lies in the level above (its children in this
    /// one).
    fn expand(
        &mut self,
        t: &[Local],
        pos: &mut usize,
        bx: PhaseBox,
        slab: Option<std::sync::Arc<Sl>>,
        next: bool,
    ) -> Building {
        let item = t[*pos];
        *pos += 1;
        let (axis, (lo, hi)) = match item {
            Local::Leaf(labels) => return Building::Leaf(labels),
            Local::Open | Local::Settled => {
                let i = self.used[1];
                self.used[1] += 1;
                self.opens[i] = Open {
                    bx,
                    fresh: slab.is_none(),
                    slab,
                    settled: matches!(item, Local::Settled),
                };
                return Building::Open(self.open_base + i as u32);
            }
            Local::Mid(ax) => (ax, bx.split(ax as usize)),
            Local::At(ax, p) => (ax, split_at(&bx, ax, p)),
        };
        let i = self.used[0];
        self.used[0] += 2;
        // Below a θ split the parent's slab no longer applies.
        let child_slab = if axis == 1 { slab } else { None };
        let l = self.expand(t, pos, lo, child_slab.clone(), false);
        let h = self.expand(t, pos, hi, child_slab, false);
        self.nodes[i] = l;
        self.nodes[i + 1] = h;
        let a = self.node_base + i as u32;
        match item {
            Local::At(_, at) => Building::SplitAt { axis, next, a, at },
            _ => Building::Split { axis, next, a },
        }
    }
}
