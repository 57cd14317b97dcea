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
mod bisection;
mod budget;
mod centred;
mod certify;
mod contract;
mod engine;
pub mod export;
pub mod labels;
mod level;
pub mod methods;
mod natural;
mod slices;
pub mod stability;
mod tree;
pub mod undefined;

use crate::number::elementary::Cr;
use crate::number::scalar::{is_continuous, is_defined, DualTheta};
use crate::scene::{Angle, Constraints, Domain, Quadratic, Scene, Variant};
use inari::{DecInterval, Interval};
use serde::Serialize;

pub use area::{
    empty_cells, standard_cell_bounds, standard_cells, AreaBounds, CellSpec, Emptiness,
};
pub use methods::{monotone_label, pave_with, run_method, Method, MethodOptions, MethodRun};

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
    /// Splits at `p` along `axis`; `None` unless `p` lies strictly inside.
    pub fn split_at(&self, axis: usize, p: f64) -> Option<(PhaseBox, PhaseBox)> {
        let r = if axis == 0 {
            self.theta
        } else {
            self.theta_dot
        };
        if !(r[0] < p && p < r[1]) {
            return None;
        }
        let (mut lo, mut hi) = (*self, *self);
        if axis == 0 {
            lo.theta[1] = p;
            hi.theta[0] = p;
        } else {
            lo.theta_dot[1] = p;
            hi.theta_dot[0] = p;
        }
        Some((lo, hi))
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
    /// One label per constraint of the paving, in [`Paving::names`] order:
    /// `labels.len()` is the paving's constraint count.
    pub labels: PerConstraint<Label>,
}

// Sized labels cost no memory: a leaf is the box and one byte per label
// slot plus the count, as small as with bare label arrays.
const _: () = assert!(std::mem::size_of::<Leaf>() == 40);

/// A node of the bisection tree in preorder: enough to replay the paving.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Node {
    /// Bisected along axis 0 (θ) or 1 (θ̇); the two subtrees follow.
    Split(u8),
    /// Split along an axis at a recorded exact double strictly inside the
    /// box (a contraction point); the two subtrees follow.
    SplitAt(u8, f64),
    /// A leaf: index into [`Paving::leaves`].
    Leaf(u32),
}

/// One value per constraint (at most [`MAX_CONSTRAINTS`]), kept inline: the
/// per-box evaluations allocate nothing. It reads as a slice of exactly the
/// constraint count (`Deref`), so no unused slot is ever seen.
#[derive(Clone, Copy)]
pub struct PerConstraint<T> {
    items: [T; MAX_CONSTRAINTS],
    len: u8,
}

impl<T: Copy> PerConstraint<T> {
    /// The values of `items` in order; `None` for more than
    /// [`MAX_CONSTRAINTS`] or none at all.
    pub fn new(items: &[T]) -> Option<Self> {
        let first = *items.first()?;
        if items.len() > MAX_CONSTRAINTS {
            return None;
        }
        let mut buf = [first; MAX_CONSTRAINTS];
        buf[..items.len()].copy_from_slice(items);
        Some(PerConstraint {
            items: buf,
            len: items.len() as u8,
        })
    }

    /// `len` copies of `x`, for `len` in `1..=MAX_CONSTRAINTS` (the count
    /// [`pave_with`] accepts).
    pub(crate) fn filled(x: T, len: usize) -> Self {
        assert!((1..=MAX_CONSTRAINTS).contains(&len), "1 to 4 constraints");
        PerConstraint {
            items: [x; MAX_CONSTRAINTS],
            len: len as u8,
        }
    }
}

impl<T> std::ops::Deref for PerConstraint<T> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        &self.items[..usize::from(self.len)]
    }
}

impl<T> std::ops::DerefMut for PerConstraint<T> {
    fn deref_mut(&mut self) -> &mut [T] {
        &mut self.items[..usize::from(self.len)]
    }
}

impl<T> IntoIterator for PerConstraint<T> {
    type Item = T;
    type IntoIter = std::iter::Take<std::array::IntoIter<T, MAX_CONSTRAINTS>>;
    fn into_iter(self) -> Self::IntoIter {
        self.items.into_iter().take(usize::from(self.len))
    }
}

impl<'a, T> IntoIterator for &'a PerConstraint<T> {
    type Item = &'a T;
    type IntoIter = std::slice::Iter<'a, T>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

/// Equal when the values are (the same count, the same values).
impl<T: PartialEq> PartialEq for PerConstraint<T> {
    fn eq(&self, other: &Self) -> bool {
        **self == **other
    }
}

impl<T: Eq> Eq for PerConstraint<T> {}

impl<T: std::fmt::Debug> std::fmt::Debug for PerConstraint<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// A sequence of the values, as a slice.
impl<T: Serialize> Serialize for PerConstraint<T> {
    fn serialize<Se: serde::Serializer>(&self, s: Se) -> Result<Se::Ok, Se::Error> {
        s.collect_seq(self.iter())
    }
}

/// A list of constraints `{g_i < 0}` evaluated on boxes.
pub trait ConstraintSet: Sync {
    /// θ-only data shared by all boxes of one θ-slab.
    type Slab: Send + Sync;
    fn names(&self) -> Vec<String>;
    fn slab(&self, theta: Interval) -> Self::Slab;
    /// Decorated enclosures of every `g_i` over `theta × theta_dot`.
    fn enclose(&self, slab: &Self::Slab, theta_dot: Interval) -> PerConstraint<DecInterval>;
    /// For each constraint, `Some(j)` when it is by construction the same
    /// function as constraint `j < i`: the paver copies label `j` to it, and
    /// cells asking opposite signs of the two are reported exactly empty.
    fn same_as(&self) -> Vec<Option<usize>> {
        vec![None; self.names().len()]
    }
    /// Constraint `i` as `c₂θ̇² + c₁θ̇ + c₀` with coefficient enclosures over
    /// the slab, when it is one: evaluating it on a θ̇-interval must give
    /// exactly [`ConstraintSet::enclose`]'s value. Enables the centred and
    /// contraction methods (without it they fall back to natural).
    fn quadratic(&self, _slab: &Self::Slab, _i: usize) -> Option<Quadratic<DecInterval>> {
        None
    }
    /// Every constraint's coefficients over `theta`, each the natural
    /// enclosure intersected with its mean-value form in θ (tighter on
    /// narrow slabs); used by the centred method to steer.
    fn centred_coefficients(&self, _theta: Interval) -> Option<Vec<Quadratic<DecInterval>>> {
        None
    }
    /// Every constraint's coefficients over `theta` with their θ-derivatives,
    /// and at θ's two ends: what the checker's monotone test needs
    /// ([`labels::monotone_label`]). `None`: labels are natural only.
    fn slab_ends(&self, _theta: Interval) -> Option<PerConstraint<SlabEnds>> {
        None
    }
    /// [`ConstraintSet::slab`] and [`ConstraintSet::slab_ends`] together, for
    /// a set that can share their work.
    fn slab_and_ends(&self, theta: Interval) -> (Self::Slab, Option<PerConstraint<SlabEnds>>) {
        (self.slab(theta), self.slab_ends(theta))
    }
    /// The slab at the point θ ([`ConstraintSet::slab`] of `[θ, θ]`) for
    /// [`ConstraintSet::slab_and_ends_at`], if that uses it (`None`: it
    /// does not, and the engine computes none).
    fn end_slab(&self, _theta: f64) -> Option<Self::Slab> {
        None
    }
    /// [`ConstraintSet::slab_and_ends`], given the slab at θ's lower and
    /// upper end ([`ConstraintSet::end_slab`]) where already computed: the
    /// same values, without recomputing those.
    fn slab_and_ends_at(
        &self,
        theta: Interval,
        _known: [Option<&Self::Slab>; 2],
    ) -> (Self::Slab, Option<PerConstraint<SlabEnds>>) {
        self.slab_and_ends(theta)
    }
    /// Every constraint's coefficients `[c₂, c₁, c₀]` at a point θ in plain
    /// f64: steering only (where to split), never a label.
    fn steer_at(&self, _theta: f64) -> Option<PerConstraint<[f64; 3]>> {
        None
    }
}

/// One quadratic constraint on a θ-slab for the monotone test: its
/// coefficients over the slab, their θ-derivatives over the slab, and the
/// coefficients at the slab's lower and upper θ. Plain intervals: `smooth`
/// records once per slab that every one of them is continuous (`≥ dac`), so
/// the quadratic and its derivatives are continuous on any box of the slab.
#[derive(Clone, Copy, Debug)]
pub struct SlabEnds {
    pub value: Quadratic<Interval>,
    pub d_theta: Quadratic<Interval>,
    pub ends: [Quadratic<Interval>; 2],
    pub smooth: bool,
}

impl SlabEnds {
    pub fn new(
        dual: Quadratic<crate::number::scalar::DualTheta<DecInterval>>,
        ends: [Quadratic<DecInterval>; 2],
    ) -> SlabEnds {
        let value = dual.map(|d| d.value);
        let d_theta = dual.map(|d| d.grad[0]);
        let continuous = value.is_continuous() && d_theta.is_continuous();
        let i = |x: DecInterval| x.interval().unwrap_or(Interval::ENTIRE);
        SlabEnds::continuous_if(continuous, value.map(i), d_theta.map(i), ends)
    }

    /// The slab's coefficients `value` and their θ-derivatives `d_theta`,
    /// `continuous` on it or not, and the coefficients at its ends.
    pub fn continuous_if(
        continuous: bool,
        value: Quadratic<Interval>,
        d_theta: Quadratic<Interval>,
        ends: [Quadratic<DecInterval>; 2],
    ) -> SlabEnds {
        let smooth = continuous && ends.iter().all(Quadratic::is_continuous);
        let i = |x: DecInterval| x.interval().unwrap_or(Interval::ENTIRE);
        SlabEnds {
            value,
            d_theta,
            ends: ends.map(|q| q.map(i)),
            smooth,
        }
    }
}

/// How many ulps each θ-slab is widened at each end before its labels are
/// proved: a label then still holds for a checker whose rounding is correct
/// but a few ulps looser than ours, also beside a pole (tan(θ/2) next to
/// θ = π), where a last-bit difference in θ would change definedness.
pub const THETA_SLACK_ULPS: u32 = 8;

/// `theta` widened by [`THETA_SLACK_ULPS`] at each end (a point too).
pub(crate) fn with_slack(theta: Interval) -> Interval {
    let lo = -doubles_up(-theta.inf(), THETA_SLACK_ULPS);
    let hi = doubles_up(theta.sup(), THETA_SLACK_ULPS);
    Interval::try_from((lo, hi)).unwrap_or(theta)
}

/// `x` moved `n` doubles up, as `n` times [`f64::next_up`]: one step on
/// its bits ([`labels::ulps_away`]) where that does not reach 0, else
/// step by step (across 0).
fn doubles_up(x: f64, n: u32) -> f64 {
    if x == 0.0 || (x < 0.0 && x.abs().to_bits() <= u64::from(n)) {
        (0..n).fold(x, |y, _| y.next_up())
    } else {
        labels::ulps_away(x, n)
    }
}

/// Ω and Ω₀ of a scene file whose regions are not both of degree ≤ 2 in
/// θ̇: each box evaluates the expressions as written (natural labels; the
/// quadratic methods then refine by bisection).
pub struct FileRegions<'a> {
    pub file: &'a crate::scene::FileScene,
}

impl ConstraintSet for FileRegions<'_> {
    type Slab = DecInterval;
    fn names(&self) -> Vec<String> {
        vec!["omega".into(), "omega0".into()]
    }
    fn slab(&self, theta: Interval) -> DecInterval {
        DecInterval::new(with_slack(theta))
    }
    fn enclose(&self, theta: &DecInterval, theta_dot: Interval) -> PerConstraint<DecInterval> {
        let r = self.file.regions_at(*theta, DecInterval::new(theta_dot));
        PerConstraint::new(&r).expect("two constraints")
    }
    fn same_as(&self) -> Vec<Option<usize>> {
        vec![None, self.file.omega0_is_omega().then_some(0)]
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
    /// The θ-slab coefficients with correctly rounded trigonometry widened by
    /// an ulp ([`crate::number::elementary`]): enclosures at most a few ulp wider than
    /// inari's, so a checker evaluating with inari confirms every label. The
    /// slab is taken [`THETA_SLACK_ULPS`] wider at each end.
    fn slab(&self, theta: Interval) -> Self::Slab {
        crate::scene::slab::constraints_on(self.scene, self.variant, with_slack(theta))
    }
    fn enclose(&self, c: &Self::Slab, theta_dot: Interval) -> PerConstraint<DecInterval> {
        let w = DecInterval::new(theta_dot);
        PerConstraint::new(&[c.omega.eval(w), c.omega0.eval(w)]).expect("two constraints")
    }
    fn same_as(&self) -> Vec<Option<usize>> {
        if self.scene.omega0_is_omega(self.variant) {
            vec![None, Some(0)]
        } else {
            vec![None, None]
        }
    }
    fn quadratic(&self, c: &Self::Slab, i: usize) -> Option<Quadratic<DecInterval>> {
        match i {
            0 => Some(c.omega),
            1 => Some(c.omega0),
            _ => None,
        }
    }
    fn steer_at(&self, theta: f64) -> Option<PerConstraint<[f64; 3]>> {
        let c = self.scene.constraints(self.variant, &Angle::new(theta));
        PerConstraint::new(&[c.omega.coefficients(), c.omega0.coefficients()])
    }
    fn slab_ends(&self, theta: Interval) -> Option<PerConstraint<SlabEnds>> {
        self.slab_and_ends(theta).1
    }
    fn end_slab(&self, theta: f64) -> Option<Self::Slab> {
        Some(self.slab(labels::point(theta)))
    }
    /// The dual slab's values are the slab itself (the same operations on
    /// the same enclosures), so the natural slab comes free.
    fn slab_and_ends(&self, theta: Interval) -> (Self::Slab, Option<PerConstraint<SlabEnds>>) {
        self.slab_and_ends_at(theta, [None, None])
    }
    fn slab_and_ends_at(
        &self,
        theta: Interval,
        known: [Option<&Self::Slab>; 2],
    ) -> (Self::Slab, Option<PerConstraint<SlabEnds>>) {
        use crate::scene::slab::{dual_constraints_continuous, dual_constraints_on};
        let end = |k: usize, x: f64| match known[k] {
            Some(s) => Some(*s),
            None => Interval::try_from((x, x)).ok().map(|p| self.slab(p)),
        };
        let at_ends = end(0, theta.inf()).zip(end(1, theta.sup()));
        let theta = with_slack(theta);
        // Where the undecorated evaluation is continuous (mostly), its
        // enclosures are taken as they are.
        if let Some(d) = dual_constraints_continuous(self.scene, self.variant, theta) {
            let slab = d.map(|x| Cr(x.value).decorated().expect("not empty"));
            let ends = at_ends.and_then(|(lo, hi)| {
                let one = |q: Quadratic<DualTheta<Interval>>, lo, hi| {
                    SlabEnds::continuous_if(
                        true,
                        q.map(|x| x.value),
                        q.map(|x| x.grad[0]),
                        [lo, hi],
                    )
                };
                PerConstraint::new(&[
                    one(d.omega, lo.omega, hi.omega),
                    one(d.omega0, lo.omega0, hi.omega0),
                ])
            });
            return (slab, ends);
        }
        let d = dual_constraints_on(self.scene, self.variant, theta);
        let slab = d.map(|x| x.value);
        let ends = at_ends.and_then(|(lo, hi)| {
            PerConstraint::new(&[
                SlabEnds::new(d.omega, [lo.omega, hi.omega]),
                SlabEnds::new(d.omega0, [lo.omega0, hi.omega0]),
            ])
        });
        (slab, ends)
    }
    fn centred_coefficients(&self, theta: Interval) -> Option<Vec<Quadratic<DecInterval>>> {
        use crate::number::scalar::DualTheta;
        use crate::scene::Angle;
        let theta = with_slack(theta);
        let t = DecInterval::new(theta);
        let m = Interval::try_from((theta.mid(), theta.mid())).ok()?;
        let d = self
            .scene
            .constraints(self.variant, &Angle::new(DualTheta::variable(t, 0)));
        let p = self.scene.constraints_on(self.variant, m);
        // c(θ) ∈ c(m) + c'(Θ)(Θ − m) for every θ ∈ Θ (mean-value theorem,
        // c continuously differentiable where the enclosures are ≥ dac).
        let dm = DecInterval::new(theta - m);
        let one = |c: DualTheta<DecInterval>, at_m: DecInterval| -> DecInterval {
            let mv = at_m + c.grad[0] * dm;
            let ok = [c.value, c.grad[0], at_m, mv]
                .iter()
                .all(|x| is_continuous(*x));
            match (ok, c.value.interval(), mv.interval()) {
                (true, Some(a), Some(b)) if !a.intersection(b).is_empty() => {
                    DecInterval::set_dec(a.intersection(b), c.value.decoration())
                }
                _ => c.value,
            }
        };
        let q = |d: Quadratic<DualTheta<DecInterval>>, p: Quadratic<DecInterval>| Quadratic {
            c2: one(d.c2, p.c2),
            c1: one(d.c1, p.c1),
            c0: one(d.c0, p.c0),
        };
        Some(vec![q(d.omega, p.omega), q(d.omega0, p.omega0)])
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

/// What a progress callback returns: `()` to go on, or a
/// [`std::ops::ControlFlow`] whose `Break` stops refinement at that level as
/// the budget would (the paving is valid and coarser, its stop reason
/// [`StopReason::Interrupted`]).
pub trait LevelFlow {
    fn go_on(self) -> bool;
}

impl LevelFlow for () {
    fn go_on(self) -> bool {
        true
    }
}

impl LevelFlow for std::ops::ControlFlow<()> {
    fn go_on(self) -> bool {
        self.is_continue()
    }
}

/// Counts of the work done.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct PaveStats {
    pub box_evaluations: u64,
    pub slab_evaluations: u64,
    pub depth: u32,
    /// Memory of the finished tree (nodes and leaves) per leaf.
    pub bytes_per_leaf: f64,
    /// Most memory held while paving, per final leaf: the tree's levels and
    /// their bookkeeping, both frontiers, a level's results and plan and the
    /// slabs computed for it (buffers counted by capacity); then the
    /// levels, subtree sizes and output of the preorder assembly.
    pub peak_bytes_per_leaf: f64,
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
    /// The progress callback asked to stop (e.g. Ctrl-C): a valid, coarser
    /// result, as for the budget.
    Interrupted,
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
            StopReason::Interrupted => "interrupted: coarser result",
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
            StopReason::Interrupted => "interrupted",
        })
    }
}

/// What the asked resolution needs when the leaf budget stopped refinement.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BudgetStop {
    /// The option that sets the budget, by its field name (`max_boxes`); a
    /// front end names it its own way.
    #[serde(skip)]
    pub option: &'static str,
    pub max_boxes: usize,
    /// A lower bound: the leaves of the level the budget stopped, each box
    /// refined as asked (open boxes counted as one leaf each).
    pub leaves_needed_at_least: usize,
    /// An estimate, not a bound: the open boxes' growth over the last
    /// levels carried on down to the resolution.
    pub leaves_needed_estimate: f64,
    /// The resolution the paving returned is complete at: the finest power
    /// of two above ε whose paving fits (the `budget` module). `None`: not even
    /// ε = 1 fits, and the paving is the domain's box alone.
    pub complete_at_eps: Option<f64>,
}

/// The result of paving: the tree, its leaves, and whether it finished.
#[derive(Clone, Debug)]
pub struct Paving {
    pub root: PhaseBox,
    pub names: Vec<String>,
    pub eps: f64,
    pub nodes: Vec<Node>,
    pub leaves: Vec<Leaf>,
    /// False when the box budget or the caller stopped refinement.
    pub complete: bool,
    /// Why refinement stopped (`complete` unless `Budget` or `Interrupted`).
    pub stop: StopReason,
    /// When the budget stopped refinement: what the asked ε needs.
    pub budget: Option<BudgetStop>,
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
    #[error("a paving needs at least one constraint")]
    NoConstraints,
}

/// Paves `root` for every constraint of `set` with the natural method.
/// `progress` is called once per level with (level, open boxes, leaves so
/// far).
pub fn pave<S: ConstraintSet, F: LevelFlow>(
    set: &S,
    root: PhaseBox,
    opts: PaveOptions,
    progress: impl FnMut(u32, usize, usize) -> F,
) -> Result<Paving, PaveError> {
    methods::pave_with(
        set,
        root,
        opts,
        &MethodOptions::new(Method::Natural),
        progress,
    )
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
                    if !b.can_split(ax as usize) {
                        return None;
                    }
                    let (lo, hi) = b.split(ax as usize);
                    stack.push(hi);
                    stack.push(lo);
                }
                Node::SplitAt(ax, p) => {
                    let (lo, hi) = b.split_at(ax as usize, p)?;
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
pub fn pave_scene<F: LevelFlow>(
    scene: &Scene,
    variant: Variant,
    opts: PaveOptions,
    progress: impl FnMut(u32, usize, usize) -> F,
) -> Result<Paving, PaveError> {
    pave_scene_in(scene, variant, &scene.domain(), opts, progress)
}

/// Paves Ω and Ω₀ of a scene over a window of the phase plane.
pub fn pave_scene_in<F: LevelFlow>(
    scene: &Scene,
    variant: Variant,
    domain: &Domain,
    opts: PaveOptions,
    progress: impl FnMut(u32, usize, usize) -> F,
) -> Result<Paving, PaveError> {
    match scene.reading(variant) {
        file if !file.is_quadratic() => {
            pave(&FileRegions { file }, root_box(domain)?, opts, progress)
        }
        _ => pave(
            &SceneConstraints { scene, variant },
            root_box(domain)?,
            opts,
            progress,
        ),
    }
}

/// The largest double box inside a non-empty domain: where pavings start.
fn root_box(domain: &Domain) -> Result<PhaseBox, PaveError> {
    if domain.is_empty() {
        return Err(PaveError::EmptyDomain);
    }
    let b = domain.inner_box();
    Ok(PhaseBox {
        theta: b[0],
        theta_dot: b[1],
    })
}

/// [`pave_scene_in`] with a method.
pub fn pave_scene_method<F: LevelFlow>(
    scene: &Scene,
    variant: Variant,
    domain: &Domain,
    opts: PaveOptions,
    mo: &MethodOptions,
    progress: impl FnMut(u32, usize, usize) -> F,
) -> Result<Paving, PaveError> {
    match scene.reading(variant) {
        file if !file.is_quadratic() => {
            pave_with(&FileRegions { file }, root_box(domain)?, opts, mo, progress)
        }
        _ => pave_with(
            &SceneConstraints { scene, variant },
            root_box(domain)?,
            opts,
            mo,
            progress,
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::{doubles_up, with_slack, THETA_SLACK_ULPS};
    use inari::Interval;
    use proptest::prelude::*;

    fn stepped(x: f64, n: u32) -> f64 {
        (0..n).fold(x, |y, _| y.next_up())
    }

    /// Bit for bit (the sign of a zero too) what `next_up` gives step by
    /// step: around 0, the subnormals, the largest doubles and ∞.
    #[test]
    fn doubles_up_is_next_up_repeated_at_the_edges() {
        let tiny = f64::from_bits(1);
        let edges = [
            0.0,
            -0.0,
            tiny,
            -tiny,
            f64::from_bits(5),
            -f64::from_bits(5),
            f64::from_bits(8),
            -f64::from_bits(8),
            -f64::from_bits(9),
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            1.0,
            -1.0,
            f64::MAX,
            -f64::MAX,
            f64::MAX.next_down().next_down(),
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for x in edges {
            for n in [0, 1, 2, 7, 8, 9, 20] {
                let (got, want) = (doubles_up(x, n), stepped(x, n));
                assert_eq!(
                    got.to_bits(),
                    want.to_bits(),
                    "{x:e} up {n}: {got:e} vs {want:e}"
                );
            }
        }
        assert!(doubles_up(f64::NAN, 8).is_nan());
    }

    proptest! {
        #[test]
        fn doubles_up_is_next_up_repeated(bits in any::<u64>(), n in 0u32..40) {
            let x = f64::from_bits(bits);
            prop_assume!(!x.is_nan());
            prop_assert_eq!(doubles_up(x, n).to_bits(), stepped(x, n).to_bits());
        }

        /// The slack is `next_down` and `next_up` applied eight times.
        #[test]
        fn the_slack_is_eight_doubles_each_way(
            a in -4.0f64..4.0,
            w in 0.0f64..1e-3,
            tiny in any::<bool>(),
        ) {
            // Next to 0 as well: slab ends that are subnormal or 0.
            let lo = if tiny { a * 1e-310 } else { a };
            let theta = Interval::try_from((lo, lo + w)).unwrap();
            let (mut l, mut h) = (theta.inf(), theta.sup());
            for _ in 0..THETA_SLACK_ULPS {
                (l, h) = (l.next_down(), h.next_up());
            }
            let got = with_slack(theta);
            prop_assert_eq!(
                (got.inf().to_bits(), got.sup().to_bits()),
                (l.to_bits(), h.to_bits())
            );
        }
    }
}
