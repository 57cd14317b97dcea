//! The labels a scene file's proof states, confirmed on the author's text.
//!
//! A scene file whose regions are quadratic in θ̇ is paved through its
//! coefficients `c₂θ̇² + c₁θ̇ + c₀`, while its proof states the regions as
//! written ([`super::statement`]), and a checker evaluates that text: `U/V`
//! as a quotient, not as `(c₂/V)θ̇² + (c₀/V)`. The two forms enclose the same
//! function differently, so each decided label is proved again here on the
//! text as written, by the checker's own tests (FORMAT.md, "Claim `paving`":
//! natural value, monotone test, convex test) on the leaf box with slack,
//! and a label none of them confirms is stated undecided. A proof never gains
//! a label here; it loses one only where the two forms' enclosures differ.
//!
//! The slack is the pavers' ([`crate::pave::THETA_SLACK_ULPS`],
//! [`crate::pave::labels::THETA_DOT_SLACK_ULPS`]): every box and every end a
//! test evaluates on is widened by that many ulps (θ̇ not across 0, which is
//! exact in any rounding), so a checker a few ulps looser than inari, whose
//! enclosures of the leaf still lie inside ours, confirms the same labels.

use crate::number::scalar::{is_continuous, is_defined, DualN};
use crate::pave::labels::THETA_DOT_SLACK_ULPS;
use crate::pave::{Label, Paving, PhaseBox, THETA_SLACK_ULPS};
use crate::scene::FileScene;
use inari::{DecInterval, Interval};

/// A paving whose decided labels the stated text confirms.
pub struct Confirmed {
    pub paving: Paving,
    /// Labels the paver proved that the stated text does not confirm (now
    /// undecided), counted per leaf and constraint.
    pub undecided: usize,
}

/// `[lo, hi]` widened by `ulps` at each end; ends at 0 stay when `keep_zero`.
fn widened(lo: f64, hi: f64, ulps: u32, keep_zero: bool) -> Interval {
    let (mut a, mut z) = (lo, hi);
    for _ in 0..ulps {
        if !(keep_zero && a == 0.0) {
            a = a.next_down();
        }
        if !(keep_zero && z == 0.0) {
            z = z.next_up();
        }
    }
    Interval::try_from((a, z)).unwrap_or(Interval::ENTIRE)
}

/// The θ-range of `[lo, hi]` with slack.
fn theta_range(lo: f64, hi: f64) -> Interval {
    widened(lo, hi, THETA_SLACK_ULPS, false)
}

/// The θ̇-range of `[lo, hi]` with slack.
fn theta_dot_range(lo: f64, hi: f64) -> Interval {
    widened(lo, hi, THETA_DOT_SLACK_ULPS, true)
}

/// The value `v` is defined and proves the label (in: `sup < 0`, out: `inf > 0`).
fn holds(v: DecInterval, want_in: bool) -> bool {
    is_defined(v)
        && v.interval().is_some_and(|i| {
            if want_in {
                i.sup() < 0.0
            } else {
                i.inf() > 0.0
            }
        })
}

/// The two regions' stated expressions on one box.
struct Stated<'a> {
    file: &'a FileScene,
}

impl Stated<'_> {
    fn natural(&self, c: usize, t: Interval, w: Interval) -> DecInterval {
        self.file
            .regions_at(DecInterval::new(t), DecInterval::new(w))[c]
    }

    /// The checker's monotone test on the leaf `[t0, t1] × [w0, w1]`: where
    /// a partial derivative has one sign, the variable is fixed at the end
    /// where the label is hardest, and the expression evaluated there.
    fn monotone(&self, c: usize, b: [f64; 4], want_in: bool) -> bool {
        let (t, w) = (theta_range(b[0], b[1]), theta_dot_range(b[2], b[3]));
        let d = |x: Interval, k: usize| DualN::<DecInterval, 2>::variable(DecInterval::new(x), k);
        let g = self.file.regions_at(d(t, 0), d(w, 1))[c];
        if ![g.value, g.grad[0], g.grad[1]].into_iter().all(is_continuous) {
            return false;
        }
        // The end (as a leaf range, before slack) where the label is hardest.
        let end = |lo: f64, hi: f64, slope: DecInterval| -> Option<(f64, f64)> {
            let s = slope.interval()?;
            let upper = if s.inf() >= 0.0 {
                want_in
            } else if s.sup() <= 0.0 {
                !want_in
            } else {
                return None;
            };
            let e = if upper { hi } else { lo };
            Some((e, e))
        };
        let (ft, fw) = (end(b[0], b[1], g.grad[0]), end(b[2], b[3], g.grad[1]));
        if ft.is_none() && fw.is_none() {
            return false;
        }
        let (t0, t1) = ft.unwrap_or((b[0], b[1]));
        let (w0, w1) = fw.unwrap_or((b[2], b[3]));
        holds(
            self.natural(c, theta_range(t0, t1), theta_dot_range(w0, w1)),
            want_in,
        )
    }

    /// The checker's convex test: convex (concave) in θ̇ for every θ, so the
    /// label holds if it holds on the two θ̇-ends, each by its natural value
    /// or the monotone test.
    fn convex(&self, c: usize, b: [f64; 4], want_in: bool) -> bool {
        let (t, w) = (theta_range(b[0], b[1]), theta_dot_range(b[2], b[3]));
        type D2 = DualN<DualN<DecInterval, 1>, 1>;
        let td = D2::constant(DualN::constant(DecInterval::new(t)));
        let wd = D2::variable(DualN::variable(DecInterval::new(w), 0), 0);
        let g = self.file.regions_at(td, wd)[c];
        let parts = [g.value.value, g.value.grad[0], g.grad[0].value, g.grad[0].grad[0]];
        if !parts.into_iter().all(is_continuous) {
            return false;
        }
        let Some(d2) = g.grad[0].grad[0].interval() else {
            return false;
        };
        let shape = if want_in {
            d2.inf() >= 0.0
        } else {
            d2.sup() <= 0.0
        };
        shape
            && [b[2], b[3]].into_iter().all(|e| {
                let side = [b[0], b[1], e, e];
                holds(self.natural(c, t, theta_dot_range(e, e)), want_in)
                    || self.monotone(c, side, want_in)
            })
    }

    /// Whether the label `l` of constraint `c` holds on leaf `bx` by one of
    /// the checker's tests.
    fn confirms(&self, c: usize, bx: &PhaseBox, l: Label) -> bool {
        let want_in = match l {
            Label::ProvedIn => true,
            Label::ProvedOut => false,
            _ => return true,
        };
        let b = [bx.theta[0], bx.theta[1], bx.theta_dot[0], bx.theta_dot[1]];
        let (t, w) = (theta_range(b[0], b[1]), theta_dot_range(b[2], b[3]));
        holds(self.natural(c, t, w), want_in)
            || self.monotone(c, b, want_in)
            || self.convex(c, b, want_in)
    }
}

/// `paving` of `file`'s two regions with every decided label that the
/// regions as written do not confirm made undecided.
pub fn confirm_labels(file: &FileScene, paving: &Paving) -> Confirmed {
    let stated = Stated { file };
    let mut out = paving.clone();
    let mut undecided = 0;
    let n = out.names.len().min(2);
    for leaf in &mut out.leaves {
        for c in 0..n {
            if paving.same_as.get(c).copied().flatten().is_some() {
                continue;
            }
            if !stated.confirms(c, &leaf.bx, leaf.labels[c]) {
                leaf.labels[c] = Label::Undecided;
                undecided += 1;
            }
        }
        for c in 0..n {
            if let Some(Some(j)) = paving.same_as.get(c) {
                leaf.labels[c] = leaf.labels[*j];
            }
        }
    }
    Confirmed {
        paving: out,
        undecided,
    }
}
