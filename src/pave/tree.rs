//! The bisection tree while it is built: one arena of nodes and one of
//! leaves, grown level by level and written in parallel, each box through
//! its own disjoint part; the flat preorder tree of a [`super::Paving`] is
//! assembled from them at the end.

use super::engine::{par_each_owned, Done, Local, Open, Outcome, Plan};
use super::{Leaf, Node, PhaseBox};
use std::mem::{size_of, MaybeUninit};
use std::sync::Arc;

/// Arena node while building; children of a split are `a` and `a + 1`.
#[derive(Clone, Copy)]
enum Building {
    Open,
    Leaf(u32),
    Split(u8, u32),
    SplitAt(u8, f64, u32),
}

pub(super) struct Tree {
    arena: Vec<Building>,
    leaves: Vec<Leaf>,
}

impl Tree {
    pub fn new() -> Tree {
        // The tree's first 256 KiB reserved at once (its pages are touched
        // only as they are written). Grown from small it was copied into
        // fresh pages at every doubling: a coarse paving's whole process
        // took 11–14 % longer (measured with glibc's malloc).
        const TREE_START: usize = 256 << 10;
        let mut arena: Vec<Building> = Vec::with_capacity(TREE_START / size_of::<Building>());
        arena.push(Building::Open);
        let leaves: Vec<Leaf> = Vec::with_capacity(TREE_START / size_of::<Leaf>());
        Tree { arena, leaves }
    }

    /// Nodes so far, the root and every split's two children.
    pub fn nodes(&self) -> usize {
        self.arena.len()
    }

    /// Leaves so far.
    pub fn leaves(&self) -> usize {
        self.leaves.len()
    }

    /// Memory of the written nodes and leaves (reserved capacity is not
    /// touched).
    pub fn bytes(&self) -> usize {
        self.arena.len() * size_of::<Building>() + self.leaves.len() * size_of::<Leaf>()
    }

    /// Adds the level `plan` makes of `frontier` (processed into `done`):
    /// every box's new nodes, leaves and open boxes, and its own entry in
    /// its parent's place. Returns the next frontier.
    pub fn grow<Sl: Send + Sync>(
        &mut self,
        frontier: &[Open<Sl>],
        done: Vec<Done<Sl>>,
        plan: &[Plan],
    ) -> Vec<Open<Sl>> {
        // Offsets of each box's share, then every box writes its share of
        // the reserved capacity itself (first touch on the workers).
        let (base_nodes, base_leaves) = (self.arena.len(), self.leaves.len());
        let mut offsets = Vec::with_capacity(plan.len());
        let mut total = [0usize; 3];
        for p in plan {
            offsets.push(total);
            total[0] += p.nodes as usize;
            total[1] += p.leaves as usize;
            total[2] += p.opens as usize;
        }
        self.arena.reserve(total[0]);
        self.leaves.reserve(total[1]);
        let mut next: Vec<Open<Sl>> = Vec::with_capacity(total[2]);
        {
            // The whole arena allocation: parents (below `base_nodes`, one
            // per box) and the new children (above) are written in place.
            let an = Shared::whole(&mut self.arena);
            let (ln, on) = (
                Shared::new(self.leaves.spare_capacity_mut()),
                Shared::new(next.spare_capacity_mut()),
            );
            par_each_owned(done, |k, d| {
                let o = &frontier[k];
                let slab = d.slab.or_else(|| o.slab.clone());
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
                    match d.outcome {
                        Outcome::Split(ax) => {
                            let t = [Local::Mid(ax), Local::Open, Local::Open];
                            f.expand(&t, &mut 0, o.node, o.bx, slab)
                        }
                        Outcome::Tree(t) => f.expand(&t, &mut 0, o.node, o.bx, slab),
                        Outcome::Leaf => unreachable!("a leaf is not refined"),
                    }
                } else {
                    f.expand(&[Local::Leaf(d.labels)], &mut 0, o.node, o.bx, None)
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
                self.arena.set_len(base_nodes + total[0]);
                self.leaves.set_len(base_leaves + total[1]);
                next.set_len(total[2]);
            }
        }
        next
    }

    /// The tree in preorder with its leaves renumbered in that order, and
    /// the bytes held while assembling it.
    pub fn into_preorder(self) -> (Vec<Node>, Vec<Leaf>, usize) {
        let (nodes, ordered) = preorder(&self.arena, &self.leaves);
        // Building, leaves in build order, subtree sizes and the output together.
        let held = self.arena.len() * (size_of::<Building>() + 8)
            + self.leaves.len() * size_of::<Leaf>()
            + nodes.capacity() * size_of::<Node>()
            + ordered.capacity() * size_of::<Leaf>();
        (nodes, ordered, held)
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
