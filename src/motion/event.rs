//! Certified events: the first time a watched function g(θ, θ̇) of the
//! state changes sign along every solution from a start set.
//!
//! In one step, a bisection of the step's time proves g of its starting
//! sign up to a time a; a point time b after a where g has the other sign
//! proves a crossing in [a, b] (g∘x is continuous); dg/dt = ∇g·f of one
//! sign over the states of [a, b] proves it unique and transversal. So the
//! event lies in [a, b], and no earlier one exists.

use super::flow::sign;
use super::lohner::{StepData, Stepper, Vector};
use crate::number::scalar::Dual;
use crate::scene::file::FileScene;
use inari::{DecInterval, Decoration, Interval};

/// A function of the state whose sign change is an event.
pub trait Watched {
    /// The event's kind as reported (`U=0`, `N=0`, `domain`, …).
    fn kind(&self) -> &str;
    /// An enclosure of g over the box, `None` where g may be undefined or
    /// discontinuous there.
    fn value(&self, x: Vector) -> Option<Interval>;
    /// An enclosure of dg/dt = ∇g·f over the box, given f over it.
    fn slope(&self, x: Vector, f: Vector) -> Option<Interval>;
}

/// One certified event.
#[derive(Clone, Debug)]
pub struct Event {
    pub kind: String,
    /// Every solution from the start set crosses once in this time window,
    /// and not before it.
    pub time: Interval,
    pub theta: Interval,
    pub theta_dot: Interval,
    /// An enclosure of dg/dt at the crossing (of one sign: transversal).
    pub slope: Interval,
    /// In the step's own time: `[a0, b0]` where dg/dt has one sign and
    /// `[a, b]` where g changes sign, `[a0, b0, a, b]` (what a proof states).
    pub(crate) local: [f64; 4],
    /// Which of the run's watched functions crosses (its index).
    pub(crate) watch: usize,
}

/// What a step shows of one watched function.
#[derive(Clone, Debug)]
pub enum Crossing {
    /// g keeps its sign over the whole step (proved).
    None,
    Found(Event),
    /// g may reach 0 at the step's end and the other sign is not shown
    /// within the step.
    Unresolved,
    Undecided(String),
}

/// Pieces of a step no narrower than this fraction of it.
const FINEST: f64 = 1.0 / (1u64 << 44) as f64;

fn tau(a: f64, b: f64) -> Interval {
    Interval::try_from((a, b)).expect("a ≤ b, both finite")
}

/// The first crossing in the step `data` (starting at `t0`) of `w`, whose
/// sign at the start is `s0`.
pub fn first_crossing(
    data: &StepData,
    w: &dyn Watched,
    s0: f64,
    t0: Interval,
    stepper: &mut Stepper,
) -> Crossing {
    let same = |x: Vector| w.value(x).and_then(sign) == Some(s0);
    if same(data.apriori) {
        return Crossing::None;
    }
    let h = data.h.sup();
    // The proved prefix [0, a]: leftmost pieces first.
    let mut a = 0.0;
    let mut stack = vec![(0.0, h)];
    let mut open = None;
    while let Some((p, q)) = stack.pop() {
        if same(data.enclose(tau(p, q))) {
            a = q;
            continue;
        }
        let m = 0.5 * (p + q);
        if q - p <= FINEST * h || m <= p || m >= q {
            open = Some((p, q));
            break;
        }
        stack.push((m, q));
        stack.push((p, m));
    }
    let Some((_, q)) = open else {
        return Crossing::None;
    };
    // The first point time after the open piece where g has the other sign.
    let other = |x: Vector| w.value(x).and_then(sign) == Some(-s0);
    let mut b = None;
    let mut d = q - a;
    let mut probe = q;
    while probe <= h {
        if other(data.enclose(tau(probe, probe))) {
            b = Some(probe);
            break;
        }
        if probe == h {
            break;
        }
        d *= 2.0;
        probe = (q + d).min(h);
    }
    let Some(mut b) = b else {
        return if !same(data.end.hull) {
            Crossing::Unresolved
        } else {
            Crossing::Undecided(format!(
                "`{}` reaches 0 without crossing it within the step (a tangency, or an \
                 enclosure too wide)",
                w.kind()
            ))
        };
    };
    // Transversal on [a, b]: one sign of dg/dt there.
    let (a0, b0) = (a, b);
    let window = data.enclose(tau(a, b));
    let mut field = |x: Vector| stepper.field(x).ok();
    let Some(slope) = field(window).and_then(|f| w.slope(window, f)) else {
        return Crossing::Undecided(format!("`{}`: no slope on the crossing window", w.kind()));
    };
    if sign(slope) != Some(-s0) {
        return Crossing::Undecided(format!(
            "`{}` may be tangent to the motion at its crossing: dg/dt ∈ [{:e}, {:e}]",
            w.kind(),
            slope.inf(),
            slope.sup()
        ));
    }
    // Narrow the window: a towards the first time some solution may have
    // crossed, b towards the last one where some may not have.
    let sign_at = |m: f64| w.value(data.enclose(tau(m, m))).and_then(sign);
    let mut ambiguous = None;
    for _ in 0..64 {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        match sign_at(m) {
            Some(s) if s == s0 => a = m,
            Some(_) => b = m,
            None => {
                ambiguous = Some(m);
                break;
            }
        }
    }
    if let Some(m) = ambiguous {
        let (mut lo, mut hi) = (a, m);
        let (mut lo2, mut hi2) = (m, b);
        for _ in 0..64 {
            let x = 0.5 * (lo + hi);
            if x <= lo || x >= hi {
                break;
            }
            if sign_at(x) == Some(s0) {
                lo = x;
            } else {
                hi = x;
            }
        }
        for _ in 0..64 {
            let x = 0.5 * (lo2 + hi2);
            if x <= lo2 || x >= hi2 {
                break;
            }
            if sign_at(x) == Some(-s0) {
                hi2 = x;
            } else {
                lo2 = x;
            }
        }
        (a, b) = (lo, hi2);
    }
    let state = data.enclose(tau(a, b));
    let slope = field(state)
        .and_then(|f| w.slope(state, f))
        .unwrap_or(slope);
    Crossing::Found(Event {
        kind: w.kind().to_string(),
        time: t0 + tau(a, b),
        theta: state[0],
        theta_dot: state[1],
        slope,
        local: [a0, b0, a, b],
        watch: 0,
    })
}

/// The expression of one region of a scene file (`{expr < 0}`): `U=0` for
/// Ω (Λ̈ at zero reaction vanishes), `N=0` for Ω₀ (the contact reaction
/// vanishes).
pub struct RegionBoundary<'a> {
    pub file: &'a FileScene,
    /// 0 for Ω, 1 for Ω₀.
    pub region: usize,
}

impl Watched for RegionBoundary<'_> {
    fn kind(&self) -> &str {
        ["U=0", "N=0"][self.region]
    }

    fn value(&self, x: Vector) -> Option<Interval> {
        let g = self
            .file
            .regions_at(DecInterval::new(x[0]), DecInterval::new(x[1]))[self.region];
        (g.decoration() >= Decoration::Dac).then(|| g.interval().unwrap_or(Interval::EMPTY))
    }

    fn slope(&self, x: Vector, f: Vector) -> Option<Interval> {
        // ∇g needs g defined and continuous on the box as well.
        self.value(x)?;
        let g = self
            .file
            .regions_at(Dual::variable(x[0], 0), Dual::variable(x[1], 1))[self.region];
        let s = g.grad[0] * f[0] + g.grad[1] * f[1];
        s.is_common_interval().then_some(s)
    }
}

/// Leaving the window `[θ lo, θ hi] × [θ̇ lo, θ̇ hi]`: g = the distance
/// to its nearest side, watched side by side.
pub struct WindowSide {
    /// 0 for θ, 1 for θ̇.
    pub axis: usize,
    /// The side's value, exact.
    pub at: Interval,
    /// True for the upper side (g = at − x), false for the lower (x − at).
    pub upper: bool,
}

impl Watched for WindowSide {
    fn kind(&self) -> &str {
        "domain"
    }

    fn value(&self, x: Vector) -> Option<Interval> {
        Some(if self.upper {
            self.at - x[self.axis]
        } else {
            x[self.axis] - self.at
        })
    }

    fn slope(&self, _: Vector, f: Vector) -> Option<Interval> {
        Some(if self.upper {
            -f[self.axis]
        } else {
            f[self.axis]
        })
    }
}
