//! Certified boxes found with the paver: a box where two constraints `{g < 0}`
//! are proved to disagree (in one, out of the other), or carry given labels.

use crate::pave::{pave, ConstraintSet, Label, PaveOptions, PerConstraint, PhaseBox};
use inari::{DecInterval, Interval};
use serde_json::json;

/// Two constraints given by one function of (θ, θ̇) boxes.
pub struct PairSet<F> {
    pub f: F,
}

impl<F: Fn(Interval, Interval) -> [DecInterval; 2] + Sync> ConstraintSet for PairSet<F> {
    type Slab = Interval;
    fn names(&self) -> Vec<String> {
        vec!["first".into(), "second".into()]
    }
    fn slab(&self, theta: Interval) -> Interval {
        theta
    }
    fn enclose(&self, theta: &Interval, theta_dot: Interval) -> PerConstraint<DecInterval> {
        PerConstraint::new(&(self.f)(*theta, theta_dot)).expect("two constraints")
    }
}

/// A leaf with its two labels.
#[derive(Clone, Copy, Debug)]
pub struct Found {
    pub bx: PhaseBox,
    pub labels: [Label; 2],
}

impl Found {
    pub fn json(&self) -> serde_json::Value {
        let l = |x: Label| match x {
            Label::ProvedIn => "inside (sup g < 0 proved)",
            Label::ProvedOut => "outside (inf g > 0 proved)",
            Label::Undecided => "undecided",
            Label::Undefined => "undefined",
        };
        json!({
            "box": {"theta": self.bx.theta, "theta_dot": self.bx.theta_dot},
            "first": l(self.labels[0]),
            "second": l(self.labels[1]),
        })
    }
}

/// Paves `window` (resolution `eps` of it) and returns the first leaf, in
/// tree order, whose labels satisfy `want`.
pub fn find_leaf<F>(
    f: F,
    window: PhaseBox,
    eps: f64,
    want: impl Fn([Label; 2]) -> bool,
) -> Option<Found>
where
    F: Fn(Interval, Interval) -> [DecInterval; 2] + Sync,
{
    let set = PairSet { f };
    let opts = PaveOptions {
        eps,
        max_boxes: 200_000,
    };
    let p = pave(&set, window, opts, |_, _, _| {}).ok()?;
    p.leaves
        .iter()
        .map(|l| Found {
            bx: l.bx,
            labels: [l.labels[0], l.labels[1]],
        })
        .find(|l| want(l.labels))
}

/// A leaf proved inside one constraint and outside the other.
pub fn find_difference<F>(f: F, window: PhaseBox, eps: f64) -> Option<Found>
where
    F: Fn(Interval, Interval) -> [DecInterval; 2] + Sync,
{
    find_leaf(f, window, eps, |l| {
        matches!(
            l,
            [Label::ProvedIn, Label::ProvedOut] | [Label::ProvedOut, Label::ProvedIn]
        )
    })
}

/// Re-checks a found box with a fresh evaluation on the whole box.
pub fn labels_on<F>(f: &F, bx: PhaseBox) -> [Label; 2]
where
    F: Fn(Interval, Interval) -> [DecInterval; 2],
{
    let [a, b] = f(bx.theta_interval(), bx.theta_dot_interval());
    [Label::from_enclosure(a), Label::from_enclosure(b)]
}

pub fn window(theta: [f64; 2], theta_dot: [f64; 2]) -> PhaseBox {
    PhaseBox { theta, theta_dot }
}
