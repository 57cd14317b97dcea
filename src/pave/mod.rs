//! Set inversion over phase-plane boxes with adaptive bisection (SIVIA).
//!
//! Each leaf gets one [`Label`] per constraint `{g < 0}`: proved in, proved
//! out, undecided, or undefined (the formula may be undefined somewhere on the
//! box, e.g. where it touches sin θ = 0 — such a box is never certified).
//!
//! The paving is built level by level. Every box of a level is processed
//! independently (in parallel), then split in a fixed order, so the tree is the
//! same whatever the thread count, and it can be replayed from the root box
//! with [`Paving::nodes`] (bisection choices in preorder) and the leaf labels.

pub mod area;
pub mod export;
pub mod method;

use crate::scalar::is_defined;
use crate::scene::{Constraints, Domain, Scene, Variant};
use inari::{DecInterval, Interval};
use rayon::prelude::*;
use serde::Serialize;
use std::collections::HashMap;

pub use area::{standard_cells, AreaBounds, CellSpec};

/// Most constraints one paving can carry.
pub const MAX_CONSTRAINTS: usize = 4;

/// What is proved about one constraint on one box.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Label {
    /// `sup g < 0` on the whole box, the formula defined everywhere on it.
    ProvedIn,
    /// `inf g > 0` on the whole box, the formula defined everywhere on it.
    ProvedOut,
    /// Neither could be shown at this size.
    Undecided,
    /// The formula may be undefined somewhere on the box.
    Undefined,
}

impl Label {
    pub fn is_decided(self) -> bool {
        matches!(self, Label::ProvedIn | Label::ProvedOut)
    }

    /// The claim a decorated enclosure of `g` supports.
    pub fn from_enclosure(g: DecInterval) -> Label {
        if !is_defined(g) {
            return Label::Undefined;
        }
        let x = g.interval().expect("defined implies non-empty");
        if x.sup() < 0.0 {
            Label::ProvedIn
        } else if x.inf() > 0.0 {
            Label::ProvedOut
        } else {
            Label::Undecided
        }
    }
}

/// A phase-plane box `[θ] × [θ̇]` with exact double endpoints.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PhaseBox {
    pub theta: [f64; 2],
    pub theta_dot: [f64; 2],
}

impl PhaseBox {
    pub fn theta_interval(&self) -> Interval {
        Interval::try_from((self.theta[0], self.theta[1])).expect("ordered endpoints")
    }
    pub fn theta_dot_interval(&self) -> Interval {
        Interval::try_from((self.theta_dot[0], self.theta_dot[1])).expect("ordered endpoints")
    }
    /// Exact area enclosure.
    pub fn area(&self) -> Interval {
        let w = Interval::try_from((self.theta[1], self.theta[1])).unwrap()
            - Interval::try_from((self.theta[0], self.theta[0])).unwrap();
        let h = Interval::try_from((self.theta_dot[1], self.theta_dot[1])).unwrap()
            - Interval::try_from((self.theta_dot[0], self.theta_dot[0])).unwrap();
        w * h
    }
    /// The midpoint used to split along axis 0 (θ) or 1 (θ̇), rounded to a
    /// double.
    pub fn midpoint(&self, axis: usize) -> f64 {
        let r = if axis == 0 {
            self.theta
        } else {
            self.theta_dot
        };
        0.5 * r[0] + 0.5 * r[1]
    }

    /// Whether splitting along `axis` gives two boxes of positive width: the
    /// rounded midpoint lies strictly between the endpoints. False once the
    /// box is one ulp wide there (the midpoint rounds to an endpoint).
    pub fn can_split(&self, axis: usize) -> bool {
        let r = if axis == 0 {
            self.theta
        } else {
            self.theta_dot
        };
        let mid = self.midpoint(axis);
        r[0] < mid && mid < r[1]
    }

    /// Splits at the (exactly shared) midpoint of axis 0 (θ) or 1 (θ̇). Only
    /// meaningful when [`PhaseBox::can_split`] holds (otherwise one half is
    /// degenerate); the paver never splits such a box.
    pub fn split(&self, axis: usize) -> (PhaseBox, PhaseBox) {
        let (mut lo, mut hi) = (*self, *self);
        let mid = self.midpoint(axis);
        if axis == 0 {
            lo.theta[1] = mid;
            hi.theta[0] = mid;
        } else {
            lo.theta_dot[1] = mid;
            hi.theta_dot[0] = mid;
        }
        (lo, hi)
    }
    pub fn contains(&self, theta: f64, theta_dot: f64) -> bool {
        self.theta[0] <= theta
            && theta <= self.theta[1]
            && self.theta_dot[0] <= theta_dot
            && theta_dot <= self.theta_dot[1]
    }
}

/// One leaf of a paving.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Leaf {
    #[serde(rename = "box")]
    pub bx: PhaseBox,
    pub labels: [Label; MAX_CONSTRAINTS],
}

/// A node of the bisection tree in preorder: enough to replay the paving.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Node {
    /// Bisected along axis 0 (θ) or 1 (θ̇); the two subtrees follow.
    Split(u8),
    /// A leaf: index into [`Paving::leaves`].
    Leaf(u32),
}

/// A list of constraints `{g_i < 0}` evaluated on boxes.
pub trait ConstraintSet: Sync {
    /// θ-only data shared by all boxes of one θ-slab.
    type Slab: Send + Sync;
    fn names(&self) -> Vec<String>;
    fn slab(&self, theta: Interval) -> Self::Slab;
    /// Decorated enclosures of every `g_i` over `theta × theta_dot`.
    fn enclose(&self, slab: &Self::Slab, theta_dot: Interval) -> Vec<DecInterval>;
    /// For each constraint, `Some(j)` when it is by construction the same
    /// function as constraint `j < i`: the paver copies label `j` to it, and
    /// cells asking opposite signs of the two are reported exactly empty.
    fn same_as(&self) -> Vec<Option<usize>> {
        vec![None; self.names().len()]
    }
}

/// Ω and Ω₀ of a scene, in one reading of the paper.
pub struct SceneConstraints<'a> {
    pub scene: &'a Scene,
    pub variant: Variant,
}

impl ConstraintSet for SceneConstraints<'_> {
    type Slab = Constraints<DecInterval>;
    fn names(&self) -> Vec<String> {
        vec!["omega".into(), "omega0".into()]
    }
    fn slab(&self, theta: Interval) -> Self::Slab {
        self.scene.constraints_on(self.variant, theta)
    }
    fn enclose(&self, c: &Self::Slab, theta_dot: Interval) -> Vec<DecInterval> {
        let w = DecInterval::new(theta_dot);
        vec![c.omega.eval(w), c.omega0.eval(w)]
    }
    fn same_as(&self) -> Vec<Option<usize>> {
        if self.scene.omega0_is_omega(self.variant) {
            vec![None, Some(0)]
        } else {
            vec![None, None]
        }
    }
}

/// When to stop bisecting.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct PaveOptions {
    /// Resolution relative to the domain: a box is not split along an axis once
    /// its width there is at most `eps` times the domain's width.
    pub eps: f64,
    /// Most leaves; when reached, the paving stops early (still valid, coarser).
    pub max_boxes: usize,
}

impl Default for PaveOptions {
    fn default() -> Self {
        PaveOptions {
            eps: 1.0 / 1024.0,
            max_boxes: 4_000_000,
        }
    }
}

/// Counts of the work done.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct PaveStats {
    pub box_evaluations: u64,
    pub slab_evaluations: u64,
    pub depth: u32,
}

/// Why refinement stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// Every leaf is decided for every constraint: nothing left to refine.
    AllDecided,
    /// Undecided leaves remain, all at the requested resolution `eps`.
    Resolution,
    /// Some undecided leaf is above the resolution `eps` along an axis but one
    /// ulp wide there: its midpoint rounds to an endpoint, so double
    /// precision cannot split it. No budget was hit.
    DoublePrecisionLimit,
    /// The leaf budget (`max_boxes`) stopped refinement: a valid, coarser
    /// result.
    Budget,
}

impl StopReason {
    /// A short human-readable explanation.
    pub fn describe(self) -> &'static str {
        match self {
            StopReason::AllDecided => "every leaf decided",
            StopReason::Resolution => "resolution eps reached",
            StopReason::DoublePrecisionLimit => {
                "boxes one ulp wide: the resolution limit of double precision"
            }
            StopReason::Budget => "budget reached: coarser result",
        }
    }
}

impl std::fmt::Display for StopReason {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str(match self {
            StopReason::AllDecided => "all_decided",
            StopReason::Resolution => "resolution",
            StopReason::DoublePrecisionLimit => "double_precision_limit",
            StopReason::Budget => "budget",
        })
    }
}

/// The result of paving: the tree, its leaves, and whether it finished.
#[derive(Clone, Debug)]
pub struct Paving {
    pub root: PhaseBox,
    pub names: Vec<String>,
    pub eps: f64,
    pub nodes: Vec<Node>,
    pub leaves: Vec<Leaf>,
    /// False when the box budget stopped refinement.
    pub complete: bool,
    /// Why refinement stopped (`complete` is `stop != Budget`).
    pub stop: StopReason,
    /// Per constraint, `Some(j)` if it is the same function as constraint `j`
    /// ([`ConstraintSet::same_as`]); its labels are copies of `j`'s.
    pub same_as: Vec<Option<usize>>,
    pub stats: PaveStats,
}

#[derive(Debug, thiserror::Error, PartialEq)]
pub enum PaveError {
    #[error("eps must be a finite number in (0, 1], got {0}")]
    BadEps(f64),
    #[error("max-boxes must be at least 1")]
    BadBudget,
    #[error("the domain is empty")]
    EmptyDomain,
    #[error("at most {MAX_CONSTRAINTS} constraints can be paved at once")]
    TooManyConstraints,
}

/// Arena node used while building.
enum Building {
    Open,
    Leaf(u32),
    Split(u8, usize, usize),
}

/// Paves `root` for every constraint of `set`. `progress` is called once per
/// level with (level, open boxes, leaves so far).
pub fn pave<S: ConstraintSet>(
    set: &S,
    root: PhaseBox,
    opts: PaveOptions,
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
    let mut same_as = set.same_as();
    same_as.resize(names.len(), None);
    for (i, s) in same_as.iter_mut().enumerate() {
        // only earlier constraints that are not aliases themselves
        if s.is_some_and(|j| j >= i) {
            *s = None;
        }
    }
    let min_width = [
        opts.eps * (root.theta[1] - root.theta[0]),
        opts.eps * (root.theta_dot[1] - root.theta_dot[0]),
    ];
    let rel = |b: &PhaseBox, axis: usize| {
        let r = if axis == 0 { b.theta } else { b.theta_dot };
        (r[1] - r[0])
            / (if axis == 0 {
                root.theta[1] - root.theta[0]
            } else {
                root.theta_dot[1] - root.theta_dot[0]
            })
    };
    // Above the resolution along each axis.
    let wide = |b: &PhaseBox| {
        [
            b.theta[1] - b.theta[0] > min_width[0],
            b.theta_dot[1] - b.theta_dot[0] > min_width[1],
        ]
    };
    // Split the relatively wider axis; θ̇ on ties, so slabs (and their cached
    // trigonometry) are shared as long as possible. An axis where the box is
    // one ulp wide cannot be split.
    let choose_axis = |b: &PhaseBox| -> Option<u8> {
        let w = wide(b);
        let can = [w[0] && b.can_split(0), w[1] && b.can_split(1)];
        match can {
            [false, false] => None,
            [true, false] => Some(0),
            [false, true] => Some(1),
            [true, true] => Some(if rel(b, 0) > rel(b, 1) { 0 } else { 1 }),
        }
    };

    let mut arena: Vec<(PhaseBox, Building)> = vec![(root, Building::Open)];
    let mut leaves: Vec<Leaf> = Vec::new();
    let mut frontier: Vec<usize> = vec![0];
    let mut cache: HashMap<(u64, u64), S::Slab> = HashMap::new();
    let mut stats = PaveStats::default();
    let (mut budget_hit, mut ulp_limit, mut undecided_left) = (false, false, false);
    let mut level = 0u32;

    while !frontier.is_empty() {
        progress(level, frontier.len(), leaves.len());
        // θ-slabs of this level not yet cached, computed once each.
        let mut missing: Vec<(u64, u64)> = frontier
            .iter()
            .map(|&i| slab_key(&arena[i].0))
            .filter(|k| !cache.contains_key(k))
            .collect();
        missing.sort_unstable();
        missing.dedup();
        stats.slab_evaluations += missing.len() as u64;
        let fresh: Vec<_> = missing
            .par_iter()
            .map(|&(lo, hi)| {
                let th = Interval::try_from((f64::from_bits(lo), f64::from_bits(hi))).unwrap();
                ((lo, hi), set.slab(th))
            })
            .collect();
        cache.extend(fresh);

        let labelled: Vec<[Label; MAX_CONSTRAINTS]> = frontier
            .par_iter()
            .map(|&i| {
                let b = &arena[i].0;
                let slab = &cache[&slab_key(b)];
                let mut labels = [Label::ProvedOut; MAX_CONSTRAINTS];
                for (l, g) in labels
                    .iter_mut()
                    .zip(set.enclose(slab, b.theta_dot_interval()))
                {
                    *l = Label::from_enclosure(g);
                }
                for (i, s) in same_as.iter().enumerate() {
                    if let Some(j) = *s {
                        labels[i] = labels[j];
                    }
                }
                labels
            })
            .collect();
        stats.box_evaluations += frontier.len() as u64;

        // Splits in frontier order, each adding one leaf, while the budget allows.
        let open_after = frontier.len();
        let mut next = Vec::new();
        let mut leaves_if_stopped = leaves.len() + open_after;
        for (&i, labels) in frontier.iter().zip(&labelled) {
            let undecided = labels[..names.len()].iter().any(|l| !l.is_decided());
            let axis = if undecided {
                choose_axis(&arena[i].0)
            } else {
                None
            };
            match axis {
                Some(ax) if leaves_if_stopped < opts.max_boxes => {
                    leaves_if_stopped += 1;
                    let (lo, hi) = arena[i].0.split(ax as usize);
                    let (a, b) = (arena.len(), arena.len() + 1);
                    arena.push((lo, Building::Open));
                    arena.push((hi, Building::Open));
                    arena[i].1 = Building::Split(ax, a, b);
                    next.extend([a, b]);
                }
                other => {
                    if other.is_some() {
                        budget_hit = true;
                    } else if undecided {
                        undecided_left = true;
                        let b = &arena[i].0;
                        let w = wide(b);
                        if (w[0] && !b.can_split(0)) || (w[1] && !b.can_split(1)) {
                            ulp_limit = true;
                        }
                    }
                    arena[i].1 = Building::Leaf(leaves.len() as u32);
                    leaves.push(Leaf {
                        bx: arena[i].0,
                        labels: *labels,
                    });
                }
            }
        }
        frontier = next;
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
    let mut nodes = Vec::with_capacity(arena.len());
    let mut ordered = Vec::with_capacity(leaves.len());
    let mut stack = vec![0usize];
    while let Some(i) = stack.pop() {
        match arena[i].1 {
            Building::Split(ax, a, b) => {
                nodes.push(Node::Split(ax));
                stack.push(b);
                stack.push(a);
            }
            Building::Leaf(l) => {
                nodes.push(Node::Leaf(ordered.len() as u32));
                ordered.push(leaves[l as usize]);
            }
            Building::Open => unreachable!("every box ends as a leaf or a split"),
        }
    }
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

fn slab_key(b: &PhaseBox) -> (u64, u64) {
    (b.theta[0].to_bits(), b.theta[1].to_bits())
}

impl Paving {
    /// Rebuilds the leaf boxes from the root box and the split sequence alone;
    /// a replay of the tree, independent of how it was built.
    pub fn replay_boxes(&self) -> Option<Vec<PhaseBox>> {
        let mut out = vec![None; self.leaves.len()];
        let mut stack = vec![self.root];
        for node in &self.nodes {
            let b = stack.pop()?;
            match *node {
                Node::Split(ax) => {
                    let (lo, hi) = b.split(ax as usize);
                    stack.push(hi);
                    stack.push(lo);
                }
                Node::Leaf(i) => *out.get_mut(i as usize)? = Some(b),
            }
        }
        if !stack.is_empty() {
            return None;
        }
        out.into_iter().collect()
    }
}

/// Paves Ω and Ω₀ of a scene over its whole domain.
pub fn pave_scene(
    scene: &Scene,
    variant: Variant,
    opts: PaveOptions,
    progress: impl FnMut(u32, usize, usize),
) -> Result<Paving, PaveError> {
    pave_scene_in(scene, variant, &scene.domain(), opts, progress)
}

/// Paves Ω and Ω₀ of a scene over a window of the phase plane.
pub fn pave_scene_in(
    scene: &Scene,
    variant: Variant,
    domain: &Domain,
    opts: PaveOptions,
    progress: impl FnMut(u32, usize, usize),
) -> Result<Paving, PaveError> {
    if domain.is_empty() {
        return Err(PaveError::EmptyDomain);
    }
    let b = domain.inner_box();
    let root = PhaseBox {
        theta: b[0],
        theta_dot: b[1],
    };
    pave(&SceneConstraints { scene, variant }, root, opts, progress)
}
