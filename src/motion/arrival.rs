//! Arrival at the singular line: θ̈ = f/g with g a function of θ alone
//! (the rod's V), the state reaching g = 0 in finite time — the rod's
//! "dynamic jam" at its stable node.
//!
//! From a set E at time t where g has the sign σ and θ̇ the sign d:
//! - a bracket (r_near, r_far) ahead of E in the direction d holds the
//!   first zero θ₁ of g: g has the sign σ at r_near and −σ at r_far, and
//!   g' one sign from E to r_far, so g ≠ 0 from E up to θ₁;
//! - a band [a, b] ∋ θ̇ with σf > 0 at θ̇ = a and σf < 0 at θ̇ = b over the
//!   strip Θ from E to r_far: θ̈ = f/g points into the band on both faces,
//!   so θ̇ stays in it while g keeps its sign;
//! - θ then moves towards θ₁ at a speed between min |a|, |b| and max:
//!   the state reaches the line g = 0 (the solution exists until then: it
//!   stays in a compact set where θ̈ is analytic) at a time between
//!   t + |r_near − E|/max and t + |r_far − E|/min, with θ̇ in the band.
//!
//! Every conclusion is drawn in intervals; `f64` only chooses the bracket
//! and the band.

use super::event::{Event, Watched};
use super::flow::sign;
use super::lohner::{point, Vector};
use super::singular::{enclose, gradient};
use crate::number::scalar::is_continuous;
use crate::scene::expr::{Program, Quotient};
use inari::Interval;

/// The event's kind: θ̈'s denominator vanishes (the rod's V).
pub const KIND: &str = "V=0";

/// What an arrival's proof states beside the tube: exact doubles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arrival {
    /// θ̇ stays in `[band[0], band[1]]` until the arrival.
    pub band: [f64; 2],
    /// The first zero of g ahead lies in `(root[0], root[1])`.
    pub root: [f64; 2],
}

fn value(p: &Program, theta: Interval, theta_dot: Interval) -> Option<Interval> {
    let v = enclose(p, [theta, theta_dot]);
    is_continuous(v).then(|| v.interval().expect("defined"))
}

/// The sign of `p` over the box, when it is continuous there and not 0.
fn sign_of(p: &Program, theta: Interval, theta_dot: Interval) -> Option<f64> {
    value(p, theta, theta_dot).and_then(sign)
}

/// Sign tests at a point hold on the point widened by this much (relative):
/// room for a checker whose rounding is looser than ours.
const ROOM: f64 = 1.0 / (1u64 << 40) as f64;

/// `x` widened by [`ROOM`].
fn roomy(x: f64) -> Interval {
    let r = ROOM * (1.0 + x.abs());
    Interval::try_from((x - r, x + r)).unwrap_or(Interval::ENTIRE)
}

fn hull(a: f64, b: f64) -> Interval {
    Interval::try_from((a.min(b), a.max(b))).unwrap_or(Interval::ENTIRE)
}

/// The arrival at g = 0 of every solution from `e` at the exact time `t`,
/// proved as in the module's text, with `others` non-zero until then; or
/// why not.
pub fn certify(
    q: &Quotient,
    others: &[&dyn Watched],
    t: f64,
    e: Vector,
) -> Result<(Event, Arrival), String> {
    let (f, g) = (&q.numerator, &q.denominator);
    if g.reads_theta_dot() {
        return Err("θ̈'s denominator depends on θ̇".into());
    }
    let sigma =
        sign_of(g, e[0], e[1]).ok_or("θ̈'s denominator may vanish on the last certified set")?;
    let dir = sign(e[1]).ok_or("θ̇ may vanish on the last certified set")?;
    let (near_end, far_end) = if dir > 0.0 {
        (e[0].sup(), e[0].inf())
    } else {
        (e[0].inf(), e[0].sup())
    };
    // The other sign of g ahead, the nearest power-of-two distance.
    let mut delta = 2f64.powi(-44) * (1.0 + near_end.abs());
    let far = loop {
        let probe = near_end + dir * delta;
        if sign_of(g, roomy(probe), e[1]) == Some(-sigma) {
            break probe;
        }
        delta *= 2.0;
        if delta > 1.0 {
            return Err("θ̈'s denominator keeps its sign within 1 of the state".into());
        }
    };
    // Narrow the bracket by bisection at points.
    let (mut near, mut far) = (near_end, far);
    for _ in 0..80 {
        let m = 0.5 * (near + far);
        if m == near || m == far {
            break;
        }
        match sign_of(g, roomy(m), e[1]) {
            Some(s) if s == sigma => near = m,
            Some(_) => far = m,
            None => break,
        }
    }
    let strip = hull(far_end, far);
    let slope = gradient(g, [strip, e[1]])
        .map(|(_, d)| d[0])
        .filter(|d| sign(*d).is_some())
        .ok_or("θ̈'s denominator is not proved monotone up to its zero")?;
    let face = |w: f64, want: f64| {
        value(f, strip, roomy(w)).is_some_and(|v| sign(v * point(sigma)) == Some(want))
    };
    // The band: each face pushed out from E until θ̈ points inwards on it.
    let start = e[1].wid().max(2f64.powi(-44) * e[1].mag());
    let push = |from: f64, out: f64, want: f64| -> Option<f64> {
        let mut step = start;
        let mut w = from;
        for _ in 0..80 {
            if sign(point(w)) != Some(dir) {
                return None;
            }
            if face(w, want) {
                return Some(w);
            }
            w = from + out * step;
            step *= 2.0;
        }
        None
    };
    let a = push(e[1].inf(), -1.0, 1.0)
        .ok_or("no band of θ̇ is proved invariant up to the singular line (lower face)")?;
    let b = push(e[1].sup(), 1.0, -1.0)
        .ok_or("no band of θ̇ is proved invariant up to the singular line (upper face)")?;
    let band = Interval::try_from((a, b)).expect("a ≤ b");
    if gradient(f, [strip, band]).is_none() {
        return Err("θ̈'s numerator is not proved C¹ up to the singular line".into());
    }
    let region = [strip, band];
    for w in others {
        if w.value(region).and_then(sign).is_none() {
            return Err(format!(
                "`{}` may vanish before the singular line is reached",
                w.kind()
            ));
        }
    }
    let speed = band.abs();
    let lo = ((point(near) - point(near_end)) * point(dir) / point(speed.sup())).inf();
    let hi = ((point(far) - point(far_end)) * point(dir) / point(speed.inf())).sup();
    let time = point(t) + Interval::try_from((lo.max(0.0), hi)).expect("ordered");
    let theta = hull(near, far);
    Ok((
        Event {
            kind: KIND.to_string(),
            time,
            theta,
            theta_dot: band,
            slope: slope * band,
            local: [0.0; 4],
            watch: usize::MAX,
        },
        Arrival {
            band: [a, b],
            root: [theta.inf(), theta.sup()],
        },
    ))
}
