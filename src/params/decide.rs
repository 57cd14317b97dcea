//! One set on one parameter box: proved non-empty (a witness phase box),
//! proved empty (a phase split tree, a reason per leaf), or undecided.
//!
//! Every label is the paver's ([`crate::pave::ConstraintSet`]): the same
//! enclosures, with the same θ slack, that a paving proof states; the
//! scene is evaluated with the varying parameters as intervals, so a label
//! holds for every parameter of the box.

use super::model::{EmptyReason, SetStatus};
use crate::number::elementary::CrDec;
use crate::number::scalar::DualTheta;
use crate::pave::{
    monotone_label, with_slack, CellSpec, ConstraintSet, FileRegions, Label, Node, PhaseBox,
    SceneConstraints, SlabEnds,
};
use crate::scene::expr::Program;
use crate::scene::Quadratic;
use crate::scene::{Constraints, Domain, Scene, Variant};
use inari::{DecInterval, Interval};
use std::cell::RefCell;
use std::collections::HashMap;

/// Budgets of one decision.
#[derive(Clone, Copy, Debug)]
pub struct DecideOptions {
    /// Most phase boxes evaluated while looking for a witness on lines of
    /// constant θ (cheap: one θ-slab per line).
    pub line_boxes: usize,
    /// Most phase boxes evaluated while looking for a witness in the plane.
    pub witness_boxes: usize,
    /// Most leaves of an emptiness tree.
    pub empty_leaves: usize,
}

impl Default for DecideOptions {
    fn default() -> Self {
        DecideOptions {
            line_boxes: 4_000,
            witness_boxes: 1_500,
            empty_leaves: 200_000,
        }
    }
}

/// Doubles by which [`empty_root`] reaches beyond each end of the domain's
/// enclosure: a checker whose rounding is looser (FORMAT.md, "Accuracy")
/// encloses an end such as `pi/2` a few doubles wider, and the proof's
/// phase box must still contain it.
pub const EMPTY_ROOT_SLACK: u32 = 64;

/// The box an emptiness tree starts from: the domain's hull (the outer ends
/// of its ends' enclosures, which contains the domain for every parameter
/// of the box) widened by [`EMPTY_ROOT_SLACK`] doubles at each end, so that
/// the leaves cover the domain for any conforming checker (a leaf may reach
/// a little outside the domain; its reason must hold there too).
pub fn empty_root(domain: &Domain) -> PhaseBox {
    let out = |mut x: f64, up: bool| {
        for _ in 0..EMPTY_ROOT_SLACK {
            x = if up { x.next_up() } else { x.next_down() };
        }
        x
    };
    PhaseBox {
        theta: [
            out(domain.theta[0].inf(), false),
            out(domain.theta[1].sup(), true),
        ],
        theta_dot: [
            out(domain.theta_dot[0].inf(), false),
            out(domain.theta_dot[1].sup(), true),
        ],
    }
}

/// A scene's two constraints on phase boxes, and its factor rules.
pub struct Regions<'a> {
    scene: &'a Scene,
    variant: Variant,
    factors: Vec<Factor>,
    /// Ω₀ is written as the same expression as Ω: one function.
    same: bool,
    /// Factor signs by (factor, θ-range): boxes of one θ-range share them.
    signs: RefCell<HashMap<(usize, u64, u64), Option<bool>>>,
    /// θ-slab coefficients by θ-range, for a scene whose regions are
    /// quadratic in θ̇: the searches visit each θ-range with many θ̇-ranges
    /// (and every set of a parameter box shares them), and the slab is
    /// where nearly all the time goes.
    slabs: RefCell<HashMap<(u64, u64), Constraints<DecInterval>>>,
}

/// Constraint `constraint` is constraint `other` times or divided by the
/// θ̇-free `program`.
struct Factor {
    constraint: usize,
    other: usize,
    program: Program,
}

impl<'a> Regions<'a> {
    pub fn new(scene: &'a Scene, variant: Variant) -> Regions<'a> {
        let factors = scene
            .reading(variant)
            .factors()
            .into_iter()
            .map(|f| Factor {
                constraint: f.output,
                other: f.other,
                program: f.factor,
            })
            .collect();
        Regions {
            scene,
            variant,
            factors,
            same: scene.omega0_is_omega(variant),
            signs: RefCell::new(HashMap::new()),
            slabs: RefCell::new(HashMap::new()),
        }
    }

    /// Ω's and Ω₀'s labels on a box, as the paver gives them.
    pub fn labels(&self, b: &PhaseBox) -> [Label; 2] {
        let (t, w) = (b.theta_interval(), b.theta_dot_interval());
        let e = match self.scene.reading(self.variant) {
            file if !file.is_quadratic() => {
                let s = FileRegions { file };
                s.enclose(&s.slab(t), w)
            }
            _ => {
                let s = SceneConstraints {
                    scene: self.scene,
                    variant: self.variant,
                };
                let key = (b.theta[0].to_bits(), b.theta[1].to_bits());
                let cached = self.slabs.borrow().get(&key).copied();
                let slab = cached.unwrap_or_else(|| {
                    let slab = s.slab(t);
                    self.slabs.borrow_mut().insert(key, slab);
                    slab
                });
                s.enclose(&slab, w)
            }
        };
        [Label::from_enclosure(e[0]), Label::from_enclosure(e[1])]
    }

    /// The factor's sign on a θ-range, when proved: `Some(true)` positive.
    /// Its natural enclosure, else the checker's monotone test (the factor
    /// as a constant in θ̇, with its θ-derivative and its values at the
    /// range's ends, each with the paver's θ slack).
    fn factor_sign(&self, f: &Factor, theta: [f64; 2]) -> Option<bool> {
        let index = self.factors.iter().position(|g| std::ptr::eq(f, g));
        let key = index.map(|k| (k, theta[0].to_bits(), theta[1].to_bits()));
        if let Some(s) = key.and_then(|k| self.signs.borrow().get(&k).copied()) {
            return s;
        }
        let s = self.factor_sign_uncached(f, theta);
        if let Some(k) = key {
            self.signs.borrow_mut().insert(k, s);
        }
        s
    }

    fn factor_sign_uncached(&self, f: &Factor, theta: [f64; 2]) -> Option<bool> {
        let t = Interval::try_from((theta[0], theta[1])).ok()?;
        let at = |x: Interval| -> DecInterval {
            let mut out = [CrDec(DecInterval::new(Interval::ENTIRE))];
            f.program.eval(
                CrDec(DecInterval::new(with_slack(x))),
                CrDec(zero()),
                &mut out,
            );
            out[0].0
        };
        let mut label = Label::from_enclosure(at(t));
        if !label.is_decided() && theta[0] < theta[1] {
            let mut out = [DualTheta::constant(CrDec(zero()))];
            let v = DualTheta::variable(CrDec(DecInterval::new(with_slack(t))), 0);
            f.program
                .eval(v, DualTheta::constant(CrDec(zero())), &mut out);
            let dual = DualTheta {
                value: out[0].value.0,
                grad: out[0].grad.map(|g| g.0),
            };
            let flat = DualTheta::constant(zero());
            let constant = |c0| Quadratic {
                c2: zero(),
                c1: zero(),
                c0,
            };
            let point = |x: f64| Interval::try_from((x, x)).unwrap_or(Interval::ENTIRE);
            let ends = SlabEnds::new(
                Quadratic {
                    c2: flat,
                    c1: flat,
                    c0: dual,
                },
                [constant(at(point(theta[0]))), constant(at(point(theta[1])))],
            );
            let b = PhaseBox {
                theta,
                theta_dot: [0.0, 1.0],
            };
            label = monotone_label(&ends, &b);
        }
        match label {
            Label::ProvedOut => Some(true),
            Label::ProvedIn => Some(false),
            _ => None,
        }
    }

    /// Every literal of `want` holds on the box at these parameters, by its
    /// label or by a factor rule from another literal's label (a literal
    /// `g_j` with `g_j = g_i·F` or `g_i/F` has the sign of `g_i` times
    /// F's): where a witness is looked for, never a proof by itself.
    fn implied_in(&self, b: &PhaseBox, want: &[Option<bool>; 2]) -> bool {
        let l = self.labels(b);
        let sign = |label: Label| match label {
            Label::ProvedIn => Some(-1),
            Label::ProvedOut => Some(1),
            _ => None,
        };
        (0..2).all(|c| {
            let Some(w) = want[c] else { return true };
            let ok = |s: i32| if w { s < 0 } else { s > 0 };
            if sign(l[c]).is_some_and(ok) {
                return true;
            }
            self.factors.iter().any(|f| {
                let other = if f.constraint == c {
                    f.other
                } else if f.other == c {
                    f.constraint
                } else {
                    return false;
                };
                match (sign(l[other]), self.factor_sign(f, b.theta)) {
                    (Some(s), Some(positive)) => ok(if positive { s } else { -s }),
                    _ => false,
                }
            })
        })
    }

    /// The factor rules that could empty `want` on some leaf, with the
    /// sign they need (`None`: either sign).
    fn rules_for(&self, want: &[Option<bool>; 2]) -> Vec<(&Factor, Option<bool>)> {
        self.factors
            .iter()
            .filter_map(|f| match (want[f.other], want[f.constraint]) {
                // Asked opposite signs: a positive factor contradicts them.
                (Some(a), Some(b)) if a != b => Some((f, Some(true))),
                // Both asked negative: a negative factor contradicts them.
                // (Both asked ≥ 0 is no contradiction: both vanish where
                // `other` does.)
                (Some(true), Some(true)) => Some((f, Some(false))),
                _ => None,
            })
            .collect()
    }

    /// Why the set `want` misses the box, if that can be proved.
    fn reason(
        &self,
        b: &PhaseBox,
        want: &[Option<bool>; 2],
        rules: &[(&Factor, Option<bool>)],
    ) -> Option<EmptyReason> {
        // Opposite signs of one function: no point anywhere, no evaluation.
        if self.same && want[0].is_some() && want[1].is_some() && want[0] != want[1] {
            return Some(EmptyReason::SameConstraint {
                constraint: 1,
                other: 0,
            });
        }
        let l = self.labels(b);
        for c in 0..2 {
            match (want[c], l[c]) {
                (Some(true), Label::ProvedOut) | (Some(false), Label::ProvedIn) => {
                    return Some(EmptyReason::Literal { constraint: c })
                }
                _ => {}
            }
        }
        for (f, need) in rules {
            if let Some(sign) = self.factor_sign(f, b.theta) {
                if need.is_none_or(|n| n == sign) {
                    return Some(EmptyReason::Factor {
                        constraint: f.constraint,
                        other: f.other,
                        positive: sign,
                    });
                }
            }
        }
        None
    }

    /// Every literal of `want` proved on the box.
    fn proved_in(&self, b: &PhaseBox, want: &[Option<bool>; 2]) -> bool {
        let l = self.labels(b);
        (0..2).all(|c| match want[c] {
            None => true,
            Some(true) => l[c] == Label::ProvedIn,
            Some(false) => l[c] == Label::ProvedOut,
        })
    }

    /// A factor rule applies to the set but its sign is not proved on the
    /// box's θ-range: splitting θ is what helps.
    fn factor_open(&self, b: &PhaseBox, rules: &[(&Factor, Option<bool>)]) -> bool {
        rules
            .iter()
            .any(|(f, _)| self.factor_sign(f, b.theta).is_none())
    }
}

/// Decides one set on one parameter box: `over` is the scene with the
/// box's parameters as intervals, `centre` at the box's centre (where a
/// witness is looked for before it is proved over the whole box). The
/// sets of one box share both, and with them their cached slabs.
pub fn decide(over: &Regions, centre: &Regions, cell: CellSpec, opts: DecideOptions) -> SetStatus {
    let want = [cell.0[0], cell.0[1]];
    let domain = over.scene.domain();
    let why_not_nonempty = match witness(over, centre, &domain, &want, opts) {
        Ok(witness) => return SetStatus::Nonempty { witness },
        Err(e) => e,
    };
    match prove_empty(over, &domain, &want, opts) {
        Ok((tree, reasons)) => SetStatus::Empty { tree, reasons },
        Err(why_not_empty) => SetStatus::Undecided {
            reason: format!("{why_not_nonempty}; {why_not_empty}"),
        },
    }
}

/// Which axis to split: θ while a factor's sign is open on the box but
/// proved at its middle θ (splitting θ then helps), else the wider one
/// relative to `root`.
fn split_axis(
    r: &Regions,
    b: &PhaseBox,
    root: &PhaseBox,
    rules: &[(&Factor, Option<bool>)],
) -> usize {
    let m = b.midpoint(0);
    let middle = PhaseBox {
        theta: [m, m],
        ..*b
    };
    if b.can_split(0) && r.factor_open(b, rules) && !r.factor_open(&middle, rules) {
        return 0;
    }
    let rel = |x: [f64; 2], y: [f64; 2]| (x[1] - x[0]) / (y[1] - y[0]);
    let axis = if rel(b.theta, root.theta) >= rel(b.theta_dot, root.theta_dot) {
        0
    } else {
        1
    };
    if b.can_split(axis) {
        axis
    } else {
        1 - axis
    }
}

/// A phase box on which every literal of `want` is proved for the whole
/// parameter box. Candidates come first from lines of constant θ
/// ([`witness_on_lines`]: finds thin sets), then from a breadth-first
/// search of the domain at the centre parameters that drops boxes proved
/// out of the set ([`Regions::implied_in`]); each is proved over the
/// parameter box, shrunk about its centre until it is or its centre alone
/// fails. Each search has its own budget.
fn witness(
    over: &Regions,
    centre: &Regions,
    domain: &Domain,
    want: &[Option<bool>; 2],
    opts: DecideOptions,
) -> Result<PhaseBox, String> {
    if domain.is_empty() {
        return Err("the domain is empty for some parameters of the box".into());
    }
    let inner = domain.inner_box();
    let root = PhaseBox {
        theta: inner[0],
        theta_dot: inner[1],
    };
    let mut on_lines = Tries::new(opts.line_boxes);
    if let Some(w) = witness_on_lines(over, &root, want, &mut on_lines) {
        return Ok(w);
    }
    let rules = centre.rules_for(want);
    let mut at_centre = Tries::new(opts.witness_boxes);
    let mut level = vec![root];
    while !level.is_empty() && at_centre.open() {
        let mut next = Vec::new();
        for b in level {
            at_centre.evaluated += 1;
            if centre.implied_in(&b, want) {
                if let Some(w) = at_centre.candidate(over, &b, want) {
                    return Ok(w);
                }
                if !at_centre.open() {
                    break;
                }
                continue;
            }
            if centre.reason(&b, want, &rules).is_some() || !(b.can_split(0) || b.can_split(1)) {
                continue;
            }
            let (lo, hi) = b.split(split_axis(centre, &b, &root, &rules));
            next.push(lo);
            next.push(hi);
            if !at_centre.open() {
                break;
            }
        }
        level = next;
    }
    Err(match (on_lines.candidates, at_centre.candidates) {
        (0, 0) => "no witness on lines of constant θ or at the centre of the box".into(),
        (l, c) => format!(
            "{l} witnesses on lines of constant θ and {c} at the centre, none for the whole box"
        ),
    })
}

/// What one witness search has spent: boxes evaluated, and candidates
/// found (boxes in the set, before they are proved over the parameter box).
struct Tries {
    evaluated: usize,
    candidates: usize,
    budget: usize,
}

impl Tries {
    fn new(budget: usize) -> Tries {
        Tries {
            evaluated: 0,
            candidates: 0,
            budget,
        }
    }

    fn open(&self) -> bool {
        self.evaluated < self.budget && self.candidates < MAX_CANDIDATES
    }

    /// The candidate `b` tried over the parameter box.
    fn candidate(
        &mut self,
        over: &Regions,
        b: &PhaseBox,
        want: &[Option<bool>; 2],
    ) -> Option<PhaseBox> {
        self.candidates += 1;
        prove_about(over, b, want)
    }
}

/// Lines θ = const through the domain, at 1/2, then 1/4 and 3/4, … of its
/// θ-range (each level halves the spacing, up to [`LINE_LEVELS`]): on each,
/// the θ̇-intervals proved in the set for the whole parameter box, by
/// bisection of θ̇ alone (every box of a line shares one θ-slab). The widest
/// becomes a candidate as wide in θ as the lines' spacing. A set that is
/// thin in θ̇ (a band along a curve, which moves with the parameters)
/// crosses many lines, where a search of the whole plane must split it to
/// its thinness in both axes before a box fits, and a box found at the
/// centre parameters must then also fit the band's other positions.
fn witness_on_lines(
    over: &Regions,
    root: &PhaseBox,
    want: &[Option<bool>; 2],
    tries: &mut Tries,
) -> Option<PhaseBox> {
    let width = root.theta[1] - root.theta[0];
    for level in 1..=LINE_LEVELS {
        let n = 1u32 << level;
        for k in (1..n).step_by(2) {
            let theta = root.theta[0] + width * (f64::from(k) / f64::from(n));
            let Some(run) = widest_run(over, theta, root, want, tries) else {
                if !tries.open() {
                    return None;
                }
                continue;
            };
            let h = width / f64::from(2 * n);
            let b = PhaseBox {
                theta: [
                    (theta - h).max(root.theta[0]),
                    (theta + h).min(root.theta[1]),
                ],
                theta_dot: run,
            };
            if let Some(w) = tries.candidate(over, &b, want) {
                return Some(w);
            }
            if !tries.open() {
                return None;
            }
        }
    }
    None
}

/// Levels of lines [`witness_on_lines`] tries: 2^LINE_LEVELS − 1 lines.
const LINE_LEVELS: u32 = 8;

/// θ̇-pieces narrower than the domain's θ̇-range over 2^this are not split.
const LINE_DEPTH: u32 = 14;

/// The widest θ̇-interval on the line θ = `theta` that is a union of
/// adjacent pieces each proved in the set for the whole parameter box.
fn widest_run(
    over: &Regions,
    theta: f64,
    root: &PhaseBox,
    want: &[Option<bool>; 2],
    tries: &mut Tries,
) -> Option<[f64; 2]> {
    let rules = over.rules_for(want);
    let finest = (root.theta_dot[1] - root.theta_dot[0]) / f64::from(1u32 << LINE_DEPTH);
    let mut inside: Vec<[f64; 2]> = Vec::new();
    let mut stack = vec![root.theta_dot];
    while let Some(w) = stack.pop() {
        if tries.evaluated >= tries.budget {
            break;
        }
        tries.evaluated += 1;
        let b = PhaseBox {
            theta: [theta, theta],
            theta_dot: w,
        };
        if over.proved_in(&b, want) {
            inside.push(w);
            continue;
        }
        let m = b.midpoint(1);
        if over.reason(&b, want, &rules).is_some()
            || w[1] - w[0] <= finest
            || !(w[0] < m && m < w[1])
        {
            continue;
        }
        stack.push([m, w[1]]);
        stack.push([w[0], m]);
    }
    // Depth first, low half first: the pieces come in increasing θ̇.
    let mut runs: Vec<[f64; 2]> = Vec::new();
    for w in inside {
        match runs.last_mut() {
            Some(r) if r[1] == w[0] => r[1] = w[1],
            _ => runs.push(w),
        }
    }
    runs.into_iter()
        .max_by(|x, y| (x[1] - x[0]).total_cmp(&(y[1] - y[0])))
}

/// Most candidates one witness search tries over the parameter box.
const MAX_CANDIDATES: usize = 16;

/// The candidate `b` shrunk about its centre until the
/// set's literals are proved on it for the whole parameter box.
fn prove_about(over: &Regions, b: &PhaseBox, want: &[Option<bool>; 2]) -> Option<PhaseBox> {
    let c = [b.midpoint(0), b.midpoint(1)];
    let point = PhaseBox {
        theta: [c[0], c[0]],
        theta_dot: [c[1], c[1]],
    };
    // Every box about the centre contains it: nothing to shrink towards.
    if !over.proved_in(&point, want) {
        return None;
    }
    let mut h = [
        0.5 * (b.theta[1] - b.theta[0]),
        0.5 * (b.theta_dot[1] - b.theta_dot[0]),
    ];
    for _ in 0..64 {
        let w = PhaseBox {
            theta: [(c[0] - h[0]).max(b.theta[0]), (c[0] + h[0]).min(b.theta[1])],
            theta_dot: [
                (c[1] - h[1]).max(b.theta_dot[0]),
                (c[1] + h[1]).min(b.theta_dot[1]),
            ],
        };
        if w.theta[0] < w.theta[1] && w.theta_dot[0] < w.theta_dot[1] && over.proved_in(&w, want) {
            return Some(w);
        }
        h = [0.5 * h[0], 0.5 * h[1]];
    }
    None
}

/// A split tree of the domain's hull, each leaf with a reason the set
/// misses it for every parameter of the box. Gives up at a leaf whose
/// centre has no reason (no leaf containing that point ever will: the
/// enclosures only widen with the box) or when the budget runs out.
fn prove_empty(
    over: &Regions,
    domain: &Domain,
    want: &[Option<bool>; 2],
    opts: DecideOptions,
) -> Result<(Vec<Node>, Vec<EmptyReason>), String> {
    let root = empty_root(domain);
    let rules = over.rules_for(want);
    let mut nodes = Vec::new();
    let mut reasons = Vec::new();
    let mut stack = vec![root];
    while let Some(b) = stack.pop() {
        if let Some(r) = over.reason(&b, want, &rules) {
            nodes.push(Node::Leaf(reasons.len() as u32));
            reasons.push(r);
            continue;
        }
        let c = [b.midpoint(0), b.midpoint(1)];
        let point = PhaseBox {
            theta: [c[0], c[0]],
            theta_dot: [c[1], c[1]],
        };
        if over.reason(&point, want, &rules).is_none() {
            return Err(format!(
                "not empty at θ = {:.6}, θ̇ = {:.6} for some parameters of the box (no reason holds there)",
                c[0], c[1]
            ));
        }
        if reasons.len() + stack.len() >= opts.empty_leaves {
            return Err(format!(
                "emptiness not proved within {} leaves",
                opts.empty_leaves
            ));
        }
        if !(b.can_split(0) || b.can_split(1)) {
            return Err("emptiness not proved down to one-ulp boxes".into());
        }
        let axis = split_axis(over, &b, &root, &rules);
        let (lo, hi) = b.split(axis);
        nodes.push(Node::Split(axis as u8));
        stack.push(hi);
        stack.push(lo);
    }
    Ok((nodes, reasons))
}

/// `prove_empty` over `domain` at the scene's own parameters: a tree
/// from `empty_root(domain)`.
pub fn empty_tree(
    scene: &Scene,
    variant: Variant,
    domain: &Domain,
    cell: crate::scene::Cell,
    opts: DecideOptions,
) -> Option<(Vec<Node>, Vec<EmptyReason>)> {
    let spec = cell.spec();
    let want = [spec.0[0], spec.0[1]];
    prove_empty(&Regions::new(scene, variant), domain, &want, opts).ok()
}

fn zero() -> DecInterval {
    DecInterval::new(inari::const_interval!(0.0, 0.0))
}
