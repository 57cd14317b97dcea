//! The adaptive bisection of the parameter box: every box decides the sets
//! its parent left undecided, and is split while one is undecided and the
//! box is above the resolution.
//!
//! The root is first split into a fixed grid of base boxes (each axis
//! halved twice); each base box is then refined on its own, level by level,
//! its boxes decided in parallel. The result does not depend on the thread
//! count, and a shard (`k` of `n`) refines the base boxes `i` with
//! `i mod n = k` alone: joining the shards' boxes in base order gives
//! exactly the boxes of one run.

use super::decide::{decide, DecideOptions, Regions};
use super::family::Family;
use super::model::{ParamAtlas, ParamLeaf, ParamNode, SetStatus};
use crate::pave::LevelFlow;
use crate::scene::Cell;
use rayon::prelude::*;

/// Each axis of the root is halved this many times into base boxes.
pub const BASE_SPLITS: u32 = 2;

/// One part of a run split over machines: base boxes `i` with `i mod n = k`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub k: usize,
    pub n: usize,
}

impl std::str::FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Shard, String> {
        let bad = || format!("expected K/N with 0 <= K < N, got `{s}`");
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let k: usize = k.trim().parse().map_err(|_| bad())?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        if n == 0 || k >= n {
            return Err(bad());
        }
        Ok(Shard { k, n })
    }
}

/// When to stop splitting parameter boxes.
#[derive(Clone, Copy, Debug)]
pub struct SearchOptions {
    /// A box is not split along an axis once its width there is at most
    /// `eps` times the root's.
    pub eps: f64,
    /// Most parameter boxes (leaves); when reached, the atlas stops early
    /// (still valid, coarser).
    pub max_boxes: usize,
    pub decide: DecideOptions,
    pub shard: Option<Shard>,
}

/// An atlas and how its search ended.
#[derive(Clone, Debug)]
pub struct AtlasRun {
    /// In a shard: the tree of the base boxes it refined only, in base
    /// order ([`AtlasRun::base`] says which base box each leaf is in).
    pub atlas: ParamAtlas,
    /// Per leaf of `atlas`, the index of its base box.
    pub base: Vec<u32>,
    /// How many base boxes the root has.
    pub base_boxes: usize,
    /// False when the box budget or an interruption stopped refinement.
    pub complete: bool,
    /// Stopped by its progress callback.
    pub interrupted: bool,
}

/// One box of the search, split or not.
struct Cand {
    bounds: Vec<[f64; 2]>,
    sets: Vec<SetStatus>,
    children: Option<(u8, f64, usize, usize)>,
    base: u32,
}

/// The base boxes of `root`, in preorder of the fixed splits: each axis
/// halved [`BASE_SPLITS`] times, axes in turn.
pub fn base_boxes(root: &[Vec<[f64; 2]>]) -> Vec<Vec<[f64; 2]>> {
    let mut boxes = root.to_vec();
    for _ in 0..BASE_SPLITS {
        for axis in 0..root[0].len() {
            boxes = boxes
                .into_iter()
                .flat_map(|b| {
                    let (lo, hi) = split(&b, axis);
                    [lo, hi]
                })
                .collect();
        }
    }
    boxes
}

fn midpoint(r: [f64; 2]) -> f64 {
    0.5 * r[0] + 0.5 * r[1]
}

fn split(b: &[[f64; 2]], axis: usize) -> (Vec<[f64; 2]>, Vec<[f64; 2]>) {
    let m = midpoint(b[axis]);
    let (mut lo, mut hi) = (b.to_vec(), b.to_vec());
    lo[axis][1] = m;
    hi[axis][0] = m;
    (lo, hi)
}

/// Builds the atlas of `cells` over the family's box. `progress` gets
/// (level, open boxes, boxes so far) once per level, and may stop the
/// search there: the boxes of that level are leaves with the statuses they
/// inherited (valid for them, as for the larger box they came from).
pub fn search<F: LevelFlow>(
    family: &Family,
    cells: &[Cell],
    opts: &SearchOptions,
    mut progress: impl FnMut(u32, usize, usize) -> F,
) -> Result<AtlasRun, String> {
    if !(opts.eps.is_finite() && opts.eps > 0.0 && opts.eps <= 1.0) {
        return Err(format!(
            "eps must be a finite number in (0, 1], got {}",
            opts.eps
        ));
    }
    if opts.max_boxes == 0 {
        return Err("max-boxes must be at least 1".into());
    }
    let root = family.root.clone();
    let bases = base_boxes(std::slice::from_ref(&root));
    for b in &bases {
        // NaN-safe: a range that is not strictly ordered cannot be split.
        if b.iter()
            .any(|r| r[0].partial_cmp(&r[1]) != Some(std::cmp::Ordering::Less))
        {
            return Err("the parameter range is too narrow to split".into());
        }
    }
    let undecided = || SetStatus::Undecided {
        reason: "not yet decided".into(),
    };
    let mut all: Vec<Cand> = Vec::new();
    let mut open: Vec<usize> = Vec::new();
    for (i, b) in bases.iter().enumerate() {
        if opts.shard.is_some_and(|s| i % s.n != s.k) {
            continue;
        }
        all.push(Cand {
            bounds: b.clone(),
            sets: cells.iter().map(|_| undecided()).collect(),
            children: None,
            base: i as u32,
        });
        open.push(all.len() - 1);
    }
    let top: Vec<usize> = open.clone();
    let mut leaves = open.len();
    let mut complete = true;
    let mut interrupted = false;
    let mut level = 0;
    while !open.is_empty() {
        if !progress(level, open.len(), leaves).go_on() {
            (complete, interrupted) = (false, true);
            break;
        }
        let decided: Vec<Result<Vec<SetStatus>, String>> = open
            .par_iter()
            .map(|&i| decide_box(family, cells, &all[i], opts.decide))
            .collect();
        let mut next = Vec::new();
        for (&i, sets) in open.iter().zip(decided) {
            all[i].sets = sets?;
            if !all[i].sets.iter().any(is_undecided) {
                continue;
            }
            let Some(axis) = split_axis(&all[i].bounds, &root, opts.eps) else {
                continue;
            };
            if leaves >= opts.max_boxes {
                complete = false;
                continue;
            }
            let (lo, hi) = split(&all[i].bounds, axis);
            let at = lo[axis][1];
            let base = all[i].base;
            let inherit = all[i].sets.clone();
            let n = all.len();
            for bounds in [lo, hi] {
                all.push(Cand {
                    bounds,
                    sets: inherit.clone(),
                    children: None,
                    base,
                });
            }
            all[i].children = Some((axis as u8, at, n, n + 1));
            next.extend([n, n + 1]);
            leaves += 1;
        }
        open = next;
        level += 1;
    }
    Ok(assemble(
        family,
        cells,
        all,
        &top,
        bases.len(),
        complete,
        interrupted,
    ))
}

fn is_undecided(s: &SetStatus) -> bool {
    matches!(s, SetStatus::Undecided { .. })
}

/// The sets still undecided on a box, decided there; the others kept.
fn decide_box(
    family: &Family,
    cells: &[Cell],
    c: &Cand,
    opts: DecideOptions,
) -> Result<Vec<SetStatus>, String> {
    if !c.sets.iter().any(is_undecided) {
        return Ok(c.sets.clone());
    }
    let at_box = family.scene_at(&c.bounds)?;
    let centre: Vec<f64> = c.bounds.iter().map(|r| midpoint(*r)).collect();
    let at_centre = family.scene_at_point(&centre)?;
    let over = Regions::new(&at_box, family.variant);
    let centre = Regions::new(&at_centre, family.variant);
    Ok(cells
        .iter()
        .zip(&c.sets)
        .map(|(cell, s)| match s {
            SetStatus::Undecided { .. } => decide(&over, &centre, cell.spec(), opts),
            decided => decided.clone(),
        })
        .collect())
}

/// The axis to split, the widest relative to the root among those above
/// the resolution; `None` when none is (or the box is one ulp wide).
fn split_axis(b: &[[f64; 2]], root: &[[f64; 2]], eps: f64) -> Option<usize> {
    (0..b.len())
        .filter(|&a| {
            let m = midpoint(b[a]);
            (b[a][1] - b[a][0]) > eps * (root[a][1] - root[a][0]) && b[a][0] < m && m < b[a][1]
        })
        .max_by(|&x, &y| {
            let rel = |a: usize| (b[a][1] - b[a][0]) / (root[a][1] - root[a][0]);
            rel(x).total_cmp(&rel(y)).then(y.cmp(&x))
        })
}

/// The preorder tree: the fixed base splits, then each base box's subtree
/// (in a shard, the base boxes it did not refine are left out).
fn assemble(
    family: &Family,
    cells: &[Cell],
    mut all: Vec<Cand>,
    top: &[usize],
    base_boxes: usize,
    complete: bool,
    interrupted: bool,
) -> AtlasRun {
    let mut tree = Vec::new();
    let mut leaves = Vec::new();
    let mut base = Vec::new();
    let dims = family.root.len();
    // The fixed splits above the base boxes, in preorder: a complete tree
    // of depth BASE_SPLITS·dims, axes in turn.
    let depth = BASE_SPLITS as usize * dims;
    let by_base: std::collections::HashMap<u32, usize> =
        top.iter().map(|&i| (all[i].base, i)).collect();
    let mut next_base = 0u32;
    /// One node of the fixed tree: a split (axis, point) or a base box.
    type Visit<'a> = dyn FnMut(Option<(u8, f64)>, Option<Vec<[f64; 2]>>) + 'a;
    fn fixed(depth: usize, at: usize, dims: usize, b: Vec<[f64; 2]>, out: &mut Visit) {
        if at == depth {
            out(None, Some(b));
            return;
        }
        let axis = at % dims;
        let (lo, hi) = split(&b, axis);
        out(Some((axis as u8, lo[axis][1])), None);
        fixed(depth, at + 1, dims, lo, out);
        fixed(depth, at + 1, dims, hi, out);
    }
    let mut order: Vec<Option<(u8, f64)>> = Vec::new();
    fixed(depth, 0, dims, family.root.clone(), &mut |s, _| {
        order.push(s)
    });
    for s in order {
        match s {
            Some((axis, at)) => tree.push(ParamNode::Split { axis, at }),
            None => {
                if let Some(&i) = by_base.get(&next_base) {
                    emit(&mut all, i, &mut tree, &mut leaves, &mut base);
                } else {
                    // A base box another shard refines: a placeholder leaf
                    // without bounds or statuses, base `u32::MAX` (the JSON
                    // and the picture leave it out).
                    tree.push(ParamNode::Leaf(leaves.len() as u32));
                    leaves.push(ParamLeaf {
                        bounds: Vec::new(),
                        sets: Vec::new(),
                    });
                    base.push(u32::MAX);
                }
                next_base += 1;
            }
        }
    }
    AtlasRun {
        atlas: ParamAtlas {
            axes: family.axes.clone(),
            sets: cells.iter().map(|c| c.name().to_string()).collect(),
            tree,
            leaves,
        },
        base,
        base_boxes,
        complete,
        interrupted,
    }
}

fn emit(
    all: &mut Vec<Cand>,
    i: usize,
    tree: &mut Vec<ParamNode>,
    leaves: &mut Vec<ParamLeaf>,
    base: &mut Vec<u32>,
) {
    match all[i].children {
        Some((axis, at, lo, hi)) => {
            tree.push(ParamNode::Split { axis, at });
            emit(all, lo, tree, leaves, base);
            emit(all, hi, tree, leaves, base);
        }
        None => {
            tree.push(ParamNode::Leaf(leaves.len() as u32));
            base.push(all[i].base);
            leaves.push(ParamLeaf {
                bounds: std::mem::take(&mut all[i].bounds),
                sets: std::mem::take(&mut all[i].sets),
            });
        }
    }
}
