//! The label tests: every label a paving writes is one the proof checker
//! recomputes on that leaf, by the natural interval extension, the monotone
//! test ([`monotone_label`]) or the convex test ([`convex_label`]).
//! [`centred_label`] (a centred form) only steers: it says a box is worth
//! certifying by a few extra splits, never a label.

pub(super) use super::level::Labels;
use super::level::Work;
use super::{ConstraintSet, Label, PerConstraint, PhaseBox, SlabEnds, MAX_CONSTRAINTS};
use crate::number::scalar::{is_defined, Dual};
use crate::scene::Quadratic;
use inari::{DecInterval, Interval};

/// What the contraction's steering expects of a part, per relevant own
/// constraint in [`Scope::relevant_own`] order: `Some(true)` in,
/// `Some(false)` out, `None` its boundary crosses the part.
pub(super) type Tentative = [Option<bool>; MAX_CONSTRAINTS];

/// No guess: every relevant constraint tested, `in` tried first.
pub(super) const UNGUIDED: Tentative = [Some(true); MAX_CONSTRAINTS];

/// The constraints a paving labels: how many, which are copies of another,
/// and which decide whether a box is refined.
pub(super) struct Scope<'a, S: ConstraintSet> {
    pub set: &'a S,
    pub n: usize,
    pub same_as: Vec<Option<usize>>,
    pub relevant: u8,
}

impl<S: ConstraintSet> Scope<'_, S> {
    /// Labels by the natural extension: one enclosure per constraint, over
    /// the θ̇-range with slack ([`with_slack`]).
    pub fn natural(&self, slab: &S::Slab, b: &PhaseBox, work: &mut Work) -> Labels {
        work.evals += 1;
        let mut labels = Labels::filled(Label::ProvedOut, self.n);
        for (l, g) in labels.iter_mut().zip(
            self.set
                .enclose(slab, with_slack(b).theta_dot_interval())
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
    pub fn label(
        &self,
        slab: &S::Slab,
        ends: Option<&[SlabEnds]>,
        b: &PhaseBox,
        work: &mut Work,
        convex: bool,
    ) -> Labels {
        self.label_expecting(slab, ends, b, work, convex, &UNGUIDED)
    }

    /// [`Scope::label`] on a part the steering has classified (`tentative`,
    /// with the slab's end data): the monotone test tries the expected label
    /// first, and a constraint whose boundary the steering puts across the
    /// part gets no test of its own (its f64 roots place a zero inside,
    /// which no test decides): it stays undecided unless the natural
    /// enclosure, run for another constraint, decides it.
    pub fn label_expecting(
        &self,
        slab: &S::Slab,
        ends: Option<&[SlabEnds]>,
        b: &PhaseBox,
        work: &mut Work,
        convex: bool,
        tentative: &Tentative,
    ) -> Labels {
        let Some(ends) = ends else {
            return self.natural(slab, b, work);
        };
        let mut labels = Labels::filled(Label::Undecided, self.n);
        let mut tried = 0u8;
        for (k, i) in self.relevant_own().enumerate() {
            let Some(expect_in) = tentative[k] else {
                continue;
            };
            tried |= 1 << i;
            if let Some(e) = ends.get(i) {
                labels[i] = monotone_label_expecting(e, b, expect_in);
                if convex && !labels[i].is_decided() {
                    labels[i] = convex_label(e, b);
                }
            }
        }
        if tried == 0 {
            return labels;
        }
        work.evals += 1;
        self.copy_aliases(&mut labels);
        let tried = self.with_copies(tried) & self.relevant;
        if self.decided_mask(&labels) & tried != tried {
            let nat = self.natural(slab, b, work);
            for (l, n) in labels.iter_mut().zip(nat) {
                if !l.is_decided() {
                    *l = n;
                }
            }
        }
        labels
    }

    /// The slab's end data over `theta`, computed here (its three
    /// evaluations counted).
    pub fn slab_ends(&self, theta: Interval, work: &mut Work) -> Option<PerConstraint<SlabEnds>> {
        work.slabs += 3;
        self.set.slab_ends(theta)
    }

    fn copy_aliases(&self, labels: &mut Labels) {
        for (i, s) in self.same_as.iter().enumerate() {
            if let Some(j) = *s {
                labels[i] = labels[j];
            }
        }
    }

    /// The constraints `labels` decide (bit `i` = constraint `i`).
    pub fn decided_mask(&self, labels: &Labels) -> u8 {
        (0..self.n)
            .filter(|&i| labels[i].is_decided())
            .fold(0, |m, i| m | 1 << i)
    }

    /// Some relevant constraint is left undecided.
    pub fn undecided(&self, labels: &Labels) -> bool {
        self.decided_mask(labels) & self.relevant != self.relevant
    }

    /// Constraints computed (not copies of another).
    pub fn own(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.n).filter(|&i| self.same_as[i].is_none())
    }

    /// Own constraints whose labels matter (themselves or through a copy).
    pub fn relevant_own(&self) -> impl Iterator<Item = usize> + '_ {
        self.own()
            .filter(|&i| self.with_copies(1 << i) & self.relevant != 0)
    }

    /// A mask over own constraints extended to their copies.
    pub fn with_copies(&self, m: u8) -> u8 {
        (0..self.n).fold(m, |acc, i| match self.same_as[i] {
            Some(j) if m >> j & 1 == 1 => acc | 1 << i,
            _ => acc,
        })
    }
}

/// How many ulps a box's θ̇-range is widened at each end before a label is
/// proved on it (as θ-slabs are, [`super::THETA_SLACK_ULPS`]): a label whose
/// box ends on a boundary (a contraction point, a turning point of a
/// quadratic) then has a margin there, and still holds for a checker whose
/// rounding is correct but a few ulps looser than ours. An end at 0 stays
/// (`θ̇ = 0` is exact in any rounding, and contraction cuts there on purpose).
pub const THETA_DOT_SLACK_ULPS: u32 = 8;

/// `lo ≤ hi` widened by [`THETA_DOT_SLACK_ULPS`] at each end, not across 0.
fn widened(lo: f64, hi: f64) -> [f64; 2] {
    [
        -ulps_away(-lo, THETA_DOT_SLACK_ULPS),
        ulps_away(hi, THETA_DOT_SLACK_ULPS),
    ]
}

/// `x` moved `n` ulps up (`next_up` `n` times), except that it stops at 0
/// (a 0 stays): on the bits of a finite double, a step up is +1 for a
/// positive one and −1 for a negative one, and the finite doubles of one
/// sign are consecutive integers, ending at ±∞.
pub(super) fn ulps_away(x: f64, n: u32) -> f64 {
    if x == 0.0 || x.is_nan() || x == f64::INFINITY {
        return x;
    }
    let bits = x.abs().to_bits();
    if x > 0.0 {
        f64::from_bits((bits + u64::from(n)).min(f64::INFINITY.to_bits()))
    } else {
        -f64::from_bits(bits.saturating_sub(u64::from(n)))
    }
}

/// `b` with its θ̇-range widened ([`widened`]): the box labels are proved on.
fn with_slack(b: &PhaseBox) -> PhaseBox {
    PhaseBox {
        theta: b.theta,
        theta_dot: widened(b.theta_dot[0], b.theta_dot[1]),
    }
}

/// `b` with its θ̇-range replaced by `[lo, hi]`.
pub(super) fn with_w(b: &PhaseBox, lo: f64, hi: f64) -> PhaseBox {
    PhaseBox {
        theta: b.theta,
        theta_dot: [lo, hi],
    }
}

/// The point interval `[x, x]` (the whole line for a non-finite `x`).
pub(super) fn point(x: f64) -> Interval {
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
/// Proved on `b` with slack (`with_slack`): a derivative that ends at 0
/// on `b`, or an end value next to 0, decides nothing.
pub fn monotone_label(e: &SlabEnds, b: &PhaseBox) -> Label {
    monotone_label_expecting(e, b, true)
}

/// [`monotone_label`] trying `in` first if `expect_in`, else `out` first
/// (one evaluation fewer where the guess is right; a label is never both).
fn monotone_label_expecting(e: &SlabEnds, b: &PhaseBox, expect_in: bool) -> Label {
    if !e.smooth {
        return Label::Undecided;
    }
    let wide = with_slack(b);
    let w = wide.theta_dot_interval();
    // End k of `b` as the checker sees it, with the slack beyond it.
    let end = |k: usize| {
        let [lo, hi] = [b.theta_dot[k], wide.theta_dot[k]];
        Interval::try_from((lo.min(hi), lo.max(hi))).unwrap_or(Interval::ENTIRE)
    };
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
    for want_in in [expect_in, !expect_in] {
        // The end (0 lower, 1 upper) where g is largest for `in`, smallest for `out`.
        let pick = |sg: i32| (sg != 0).then_some(usize::from((sg > 0) == want_in));
        let q = pick(st).map_or(&e.value, |k| &e.ends[k]);
        let wv = pick(sw).map_or(w, end);
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
        // At `w` with slack, as every label ([`THETA_DOT_SLACK_ULPS`]).
        let [lo, hi] = widened(w, w);
        let around = Interval::try_from((lo, hi)).unwrap_or(Interval::ENTIRE);
        let by_value = Label::from_enclosure(DecInterval::new(e.value.eval(around)));
        by_value == want || monotone_label(e, &with_w(b, w, w)) == want
    };
    if holds_at(b.theta_dot[0]) && holds_at(b.theta_dot[1]) {
        want
    } else {
        Label::Undecided
    }
}

#[cfg(test)]
mod tests {
    use super::{monotone_label_expecting, ulps_away, widened, Scope, THETA_DOT_SLACK_ULPS};
    use crate::pave::level::Work;
    use crate::pave::{ConstraintSet, Label, PhaseBox, SceneConstraints};
    use crate::scene::{Scene, SceneId, Variant};
    use inari::Interval;

    /// θ̇-pieces of width 0.05 across [−10, 10] on the slab θ ∈ [0.7, 0.701]
    /// of the viscous disc (derived, defaults), where both boundaries cross.
    fn pieces() -> Vec<PhaseBox> {
        (0..400)
            .map(|j| PhaseBox {
                theta: [0.7, 0.701],
                theta_dot: [-10.0 + 0.05 * j as f64, -10.0 + 0.05 * (j + 1) as f64],
            })
            .collect()
    }

    /// The guess only orders the two tries: each piece gets the same label
    /// whichever side is tried first, and both labels occur (trying the
    /// guessed side alone would leave the others undecided).
    #[test]
    fn the_monotone_test_does_not_depend_on_the_guess() {
        let scene = Scene::default_of(SceneId::ViscousDisc);
        let set = SceneConstraints {
            scene: &scene,
            variant: Variant::Derived,
        };
        let theta = Interval::try_from((0.7, 0.701)).unwrap();
        let ends = set.slab_and_ends(theta).1.expect("smooth slab");
        let mut seen = [0; 2];
        for e in ends.iter() {
            for b in pieces() {
                let l = monotone_label_expecting(e, &b, true);
                assert_eq!(l, monotone_label_expecting(e, &b, false), "{b:?}");
                seen[0] += usize::from(l == Label::ProvedIn);
                seen[1] += usize::from(l == Label::ProvedOut);
            }
        }
        assert!(seen[0] > 10 && seen[1] > 10, "{seen:?}");
    }

    /// A constraint the steering calls crossed gets no test of its own (it
    /// stays undecided where a test would decide it); the others get the
    /// labels of the unguided test.
    #[test]
    fn a_crossed_boundary_is_not_tested_and_the_rest_are() {
        let scene = Scene::default_of(SceneId::ViscousDisc);
        let set = SceneConstraints {
            scene: &scene,
            variant: Variant::Derived,
        };
        let scope = Scope {
            set: &set,
            n: 2,
            same_as: vec![None, None],
            relevant: 0b11,
        };
        let theta = Interval::try_from((0.7, 0.701)).unwrap();
        let (slab, ends) = set.slab_and_ends(theta);
        let ends = ends.expect("smooth slab");
        let mut skipped_decidable = 0;
        for b in pieces() {
            let mut work = Work::default();
            let full = scope.label(&slab, Some(&ends), &b, &mut work, true);
            let none = scope.label_expecting(&slab, Some(&ends), &b, &mut work, true, &[None; 4]);
            assert!(none.iter().all(|l| *l == Label::Undecided), "{b:?}");
            let mut w = Work::default();
            let one = [Some(full[0] != Label::ProvedOut), None, None, None];
            let l = scope.label_expecting(&slab, Some(&ends), &b, &mut w, true, &one);
            assert_eq!(l[0], full[0], "{b:?}");
            // Untested, unless the natural enclosure run for the other decides it.
            let nat = scope.natural(&slab, &b, &mut w)[1];
            assert!(l[1] == Label::Undecided || l[1] == nat, "{b:?}");
            skipped_decidable += usize::from(full[1].is_decided() && !l[1].is_decided());
        }
        assert!(skipped_decidable > 10);
        // Nothing tested costs no evaluation.
        let mut work = Work::default();
        scope.label_expecting(
            &slab,
            Some(&ends),
            &pieces()[0],
            &mut work,
            true,
            &[None; 4],
        );
        assert_eq!(work.evals, 0);
    }

    /// The definition: `next_up` one ulp at a time, stopping at 0.
    fn stepped(x: f64, n: u32) -> f64 {
        (0..n).fold(x, |y, _| if y == 0.0 { y } else { y.next_up() })
    }

    #[test]
    fn ulps_away_is_stepping_one_ulp_at_a_time() {
        let tiny = f64::from_bits(3);
        let xs = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            tiny,
            -tiny,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            f64::MAX,
            -f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
            2.0f64.next_down(),
            -(2.0f64.next_down()),
            -7.25e-300,
            3.5e17,
        ];
        for x in xs {
            for n in [0, 1, 3, THETA_DOT_SLACK_ULPS] {
                let (a, b) = (ulps_away(x, n), stepped(x, n));
                assert_eq!(a.to_bits(), b.to_bits(), "{x:e} by {n}");
            }
        }
        assert!(ulps_away(f64::NAN, 8).is_nan());
        // Both ends: the lower one down, not across 0.
        assert_eq!(widened(tiny, 1.0), [0.0, stepped(1.0, 8)]);
        assert_eq!(widened(-1.0, -tiny), [-stepped(1.0, 8), -0.0]);
    }
    /// A slab's end data as the pavers compute it (undecorated first, its
    /// enclosures taken as they are where that is continuous) is the data
    /// of the decorated evaluation throughout, slab and ends widened by
    /// the θ-slack: every paper reading, on slabs where every coefficient
    /// is continuous and on slabs across θ = 0 and π, where the smooth and
    /// ice discs' coefficients are undefined.
    #[test]
    fn slab_end_data_is_that_of_the_decorated_evaluation() {
        use crate::number::elementary::CrDec;
        use crate::number::scalar::DualTheta;
        use crate::pave::{with_slack, SlabEnds};
        use crate::scene::slab::dual_constraints_continuous;
        use crate::scene::{Angle, Quadratic};
        use inari::DecInterval;
        let same = |a: Interval, b: Interval| a == b || (a.is_empty() && b.is_empty());
        let same_q = |a: &Quadratic<Interval>, b: &Quadratic<Interval>| {
            (0..3).all(|k| same(a.coefficients()[k], b.coefficients()[k]))
        };
        let (mut fast, mut decorated) = (0, 0);
        for id in SceneId::ALL {
            for v in Variant::ALL {
                let scene = Scene::default_of(id);
                let set = SceneConstraints {
                    scene: &scene,
                    variant: v,
                };
                for (lo, hi) in [(0.7, 0.701), (1.5, 1.625), (-0.25, 0.125), (3.0, 3.25)] {
                    let theta = Interval::try_from((lo, hi)).unwrap();
                    let wide = with_slack(theta);
                    match dual_constraints_continuous(&scene, v, wide) {
                        Some(_) => fast += 1,
                        None => decorated += 1,
                    }
                    let dec = |t: Interval| {
                        scene
                            .constraints(v, &Angle::new(CrDec(DecInterval::new(with_slack(t)))))
                            .map(|x| x.0)
                    };
                    let point = |x: f64| dec(Interval::try_from((x, x)).unwrap());
                    let dual = scene
                        .constraints(
                            v,
                            &Angle::new(DualTheta::variable(CrDec(DecInterval::new(wide)), 0)),
                        )
                        .map(|x| DualTheta {
                            value: x.value.0,
                            grad: [x.grad[0].0],
                        });
                    let (lo_end, hi_end) = (point(lo), point(hi));
                    let want = [
                        SlabEnds::new(dual.omega, [lo_end.omega, hi_end.omega]),
                        SlabEnds::new(dual.omega0, [lo_end.omega0, hi_end.omega0]),
                    ];
                    let (slab, got) = set.slab_and_ends(theta);
                    let want_slab = dual.map(|x| x.value);
                    let at = format!("{id:?} {v:?} θ {theta:?}");
                    for (w, g) in [want_slab.omega, want_slab.omega0]
                        .iter()
                        .zip([slab.omega, slab.omega0])
                    {
                        for (a, b) in w.coefficients().into_iter().zip(g.coefficients()) {
                            assert_eq!(a.decoration(), b.decoration(), "{at}: slab");
                            assert!(
                                same(a.interval().unwrap(), b.interval().unwrap()),
                                "{at}: slab"
                            );
                        }
                    }
                    let got = got.expect("two constraints");
                    for (w, g) in want.iter().zip(got.iter()) {
                        assert_eq!(w.smooth, g.smooth, "{at}: smooth");
                        assert!(same_q(&w.value, &g.value), "{at}: value");
                        assert!(same_q(&w.d_theta, &g.d_theta), "{at}: derivative");
                        assert!(same_q(&w.ends[0], &g.ends[0]), "{at}: lower end");
                        assert!(same_q(&w.ends[1], &g.ends[1]), "{at}: upper end");
                    }
                }
            }
        }
        assert!(
            fast > 0 && decorated > 0,
            "{fast} fast, {decorated} decorated"
        );
    }
}
