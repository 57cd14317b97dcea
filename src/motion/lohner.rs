//! One validated step of θ̈ = F(θ, θ̇), state x = (θ, θ̇): a Taylor method
//! with an a-priori enclosure and Lohner's QR treatment of the wrapping
//! effect.
//!
//! A step of size h from a set X = {m + A·r : r ∈ R} with hull E:
//! 1. the a-priori box B: E + [0, h]·f(B) ⊆ B, so every solution from E
//!    exists on [0, h] and stays in B (Picard–Lindelöf, the operator maps B
//!    into itself);
//! 2. the Taylor polynomial P(x₀; τ) = Σ_{k<K} x_k(x₀) τ^k and the Lagrange
//!    remainder τ^K·x_K(B) (x_K is the K-th Taylor coefficient of the
//!    solution through a state, evaluated over B: F is proved analytic there);
//! 3. the mean-value form P(x₀; τ) ∈ P(m; τ) + J(τ)·(x₀ − m), with J the
//!    Jacobian of P over hull(E ∪ {m}) from dual-number Taylor coefficients;
//! 4. x(h) ∈ m' + (J·A)·R + z with m' the midpoint of P(m; h) + remainder
//!    and z the rest; the new frame A' is the Q of a QR factorisation of
//!    mid(J·A) (columns by length), and R' = (A'⁻¹J·A)·R + A'⁻¹z with A'⁻¹
//!    enclosed in intervals.
//!
//! Every conclusion is drawn in intervals; `f64` only chooses h and the
//! frame.

use crate::number::scalar::Dual;
use crate::scene::expr::{NotAnalytic, TaylorTape};
use inari::{const_interval, Interval};

/// A vector of the state space (θ, θ̇) in intervals.
pub type Vector = [Interval; 2];
type Matrix = [[Interval; 2]; 2];

const ZERO: Interval = const_interval!(0.0, 0.0);

/// A set of states in Lohner's form: `{mid + A·r : r ∈ r}`, inside `hull`.
#[derive(Clone, Copy, Debug)]
pub struct LohnerSet {
    mid: [f64; 2],
    frame: [[f64; 2]; 2],
    r: Vector,
    /// An enclosure of the set.
    pub hull: Vector,
}

impl LohnerSet {
    /// The box `x` itself (a point, or a box of initial states).
    pub fn from_box(x: Vector) -> LohnerSet {
        let mid = [x[0].mid(), x[1].mid()];
        let r = [x[0] - point(mid[0]), x[1] - point(mid[1])];
        LohnerSet {
            mid,
            frame: [[1.0, 0.0], [0.0, 1.0]],
            r,
            hull: x,
        }
    }
}

/// `x` as an exact interval.
pub(crate) fn point(x: f64) -> Interval {
    Interval::try_from((x, x)).unwrap_or(Interval::ENTIRE)
}

fn add(a: Vector, b: Vector) -> Vector {
    [a[0] + b[0], a[1] + b[1]]
}

fn mat_vec(m: &Matrix, v: Vector) -> Vector {
    [
        m[0][0] * v[0] + m[0][1] * v[1],
        m[1][0] * v[0] + m[1][1] * v[1],
    ]
}

fn mat_mul(a: &Matrix, b: &Matrix) -> Matrix {
    std::array::from_fn(|i| std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j]))
}

fn exact_matrix(m: &[[f64; 2]; 2]) -> Matrix {
    m.map(|row| row.map(point))
}

fn bounded(v: &Vector) -> bool {
    v.iter().all(|x| x.is_common_interval())
}

fn intersect(a: Vector, b: Vector) -> Vector {
    [a[0].intersection(b[0]), a[1].intersection(b[1])]
}

/// Σ c_k τ^k by Horner's rule.
fn horner(c: &[Interval], tau: Interval) -> Interval {
    c.iter().rev().fold(ZERO, |acc, &ck| acc * tau + ck)
}

/// What one step computed: enough to enclose the solution at any time of
/// the step, not only at its end.
#[derive(Clone, Debug)]
pub struct StepData {
    /// The step, `[0, h]` in the step's own time (h may be an interval
    /// when the step ends at a time that is not a double).
    pub h: Interval,
    /// Every solution from the set stays in this box over the step.
    pub apriori: Vector,
    /// The box the Picard inclusion was proved on (`apriori` ⊆ it, and
    /// E + [0, h]·f(B) ⊆ B holds for every B between the two).
    pub(crate) apriori_outer: Vector,
    /// The set at the step's end.
    pub end: LohnerSet,
    start: LohnerSet,
    /// Taylor coefficients `0..K` at the start set's midpoint.
    at_mid: [Vec<Interval>; 2],
    /// Their derivatives in the initial state over the start's hull,
    /// `[degree][component][variable]`.
    jac: Vec<Matrix>,
    /// The K-th coefficient over the a-priori box.
    remainder: Vector,
    order: usize,
}

impl StepData {
    /// An enclosure of the states at every time of `tau ⊆ [0, h]` (the
    /// step's own time) of every solution from the start set.
    pub fn enclose(&self, tau: Interval) -> Vector {
        let tau = tau.intersection(Interval::try_from((0.0, self.h.sup())).unwrap_or(ZERO));
        let p = [horner(&self.at_mid[0], tau), horner(&self.at_mid[1], tau)];
        let tk = tau.powi(self.order as i32);
        let rem = [tk * self.remainder[0], tk * self.remainder[1]];
        let j = self.jacobian(tau);
        let spread = mat_vec(&mat_mul(&j, &exact_matrix(&self.start.frame)), self.start.r);
        intersect(add(add(p, rem), spread), self.apriori)
    }

    /// The order K of the step's Taylor method.
    pub(crate) fn order(&self) -> usize {
        self.order
    }

    /// The frame A' of the end set `{m' + A'·r}` (rows).
    pub(crate) fn end_frame(&self) -> [[f64; 2]; 2] {
        self.end.frame
    }

    /// An upper bound of the Lagrange remainder h^K·x_K(B) at the step's
    /// end: the a-priori box, not the midpoint, decides it.
    pub fn remainder_size(&self) -> f64 {
        let hk = self.h.powi(self.order as i32);
        (hk * self.remainder[0])
            .mag()
            .max((hk * self.remainder[1]).mag())
    }

    /// J(τ) = Σ_{k<K} τ^k ∂x_k/∂x₀.
    fn jacobian(&self, tau: Interval) -> Matrix {
        let mut j = [[ZERO; 2]; 2];
        for d in self.jac.iter().rev() {
            j = std::array::from_fn(|a| std::array::from_fn(|b| j[a][b] * tau + d[a][b]));
        }
        j
    }
}

/// Why a step of the size tried could not be certified.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StepFailure {
    /// No box B with E + [0, h]·f(B) ⊆ B was found.
    NoApriori,
    /// F is not analytic on the enclosures (a singular line, a kink).
    NotAnalytic(NotAnalytic),
    /// The enclosures are unbounded.
    Unbounded,
    /// The remainder h^K·x_K(B) is this large, above the bound asked for.
    RemainderAbove(f64),
}

/// The Taylor method of order K on one scene's θ̈.
pub struct Stepper<'a> {
    tape: &'a TaylorTape,
    pub order: usize,
    work: Vec<Interval>,
    work_dual: Vec<Dual<Interval>>,
    /// The series `0..=order` at the last midpoint asked for: the step
    /// size and the step both read it, for every step size tried.
    at_mid: Option<([f64; 2], [Vec<Interval>; 2])>,
    /// Steps go back in time: the solution y(τ) = x(−τ), whose Taylor
    /// coefficients are (−1)^k x_k.
    backward: bool,
}

impl<'a> Stepper<'a> {
    pub fn new(tape: &'a TaylorTape, order: usize) -> Stepper<'a> {
        Stepper {
            tape,
            order: order.max(2),
            work: Vec::new(),
            work_dual: Vec::new(),
            at_mid: None,
            backward: false,
        }
    }

    /// The same method stepping back in time.
    pub fn backward(self) -> Stepper<'a> {
        Stepper {
            backward: true,
            ..self
        }
    }

    /// −1 for the odd degrees of a backward run, else 1.
    fn flips(&self, degree: usize) -> bool {
        self.backward && degree % 2 == 1
    }

    /// The Taylor coefficients `0..=order` of the solution through `x`.
    pub fn series(&mut self, x: Vector, order: usize) -> Result<[Vec<Interval>; 2], NotAnalytic> {
        let s = self.tape.ode_series(x[0], x[1], order, &mut self.work)?;
        let mut out = [s.theta, s.theta_dot];
        for c in &mut out {
            for (d, ck) in c.iter_mut().enumerate() {
                if self.flips(d) {
                    *ck = -*ck;
                }
            }
        }
        Ok(out)
    }

    /// The series `0..=order` at the point `mid`, computed once per point.
    fn series_at_mid(&mut self, mid: [f64; 2]) -> Result<[Vec<Interval>; 2], NotAnalytic> {
        if let Some((at, c)) = &self.at_mid {
            if *at == mid {
                return Ok(c.clone());
            }
        }
        let c = self.series([point(mid[0]), point(mid[1])], self.order)?;
        self.at_mid = Some((mid, c.clone()));
        Ok(c)
    }

    /// f(x) = (θ̇, F) over the box `x`, F proved analytic there.
    pub fn field(&mut self, x: Vector) -> Result<Vector, NotAnalytic> {
        let [t, w] = self.series(x, 1)?;
        Ok([t[1], w[1]])
    }

    /// A box B ⊇ E + [0, h]·f(B): every solution from E stays in it on
    /// [0, h]. Returned tightened to E + [0, h]·f(B) itself, with B.
    fn apriori(&mut self, e: Vector, h: Interval) -> Result<(Vector, Vector), StepFailure> {
        let span = Interval::try_from((0.0, h.sup())).map_err(|_| StepFailure::Unbounded)?;
        let f = self.field(e).map_err(StepFailure::NotAnalytic)?;
        let mut b = add(e, [span * f[0], span * f[1]]);
        for _ in 0..6 {
            let wide = b.map(|x| {
                let d = 0.1 * x.wid() + 1e-15 * x.mag() + f64::MIN_POSITIVE;
                Interval::try_from((x.inf() - d, x.sup() + d)).unwrap_or(Interval::ENTIRE)
            });
            if !bounded(&wide) {
                return Err(StepFailure::Unbounded);
            }
            let f = self.field(wide).map_err(StepFailure::NotAnalytic)?;
            let next = add(e, [span * f[0], span * f[1]]);
            if !bounded(&next) {
                return Err(StepFailure::Unbounded);
            }
            if next[0].subset(wide[0]) && next[1].subset(wide[1]) {
                return Ok((next, wide));
            }
            b = next;
        }
        Err(StepFailure::NoApriori)
    }

    /// A step size for the set at `mid` aiming at a remainder of about
    /// `tolerance`: from the last two Taylor coefficients there.
    pub fn suggest(&mut self, set: &LohnerSet, tolerance: f64) -> Option<f64> {
        let c = self.series_at_mid(set.mid).ok()?;
        let k = self.order;
        let mag = |d: usize| c[0][d].mag().max(c[1][d].mag());
        let h = [k - 1, k]
            .iter()
            .map(|&d| {
                let a = mag(d);
                if a == 0.0 {
                    f64::INFINITY
                } else {
                    (tolerance / a).powf(1.0 / d as f64)
                }
            })
            .fold(f64::INFINITY, f64::min);
        h.is_finite().then_some(0.9 * h).or(Some(f64::INFINITY))
    }

    /// One step of size `h` from `set`, refused when the remainder exceeds
    /// `max_remainder` (before the costlier Jacobian is computed).
    pub fn step(
        &mut self,
        set: &LohnerSet,
        h: Interval,
        max_remainder: f64,
    ) -> Result<StepData, StepFailure> {
        let k = self.order;
        let e = set.hull;
        let (b, outer) = self.apriori(e, h)?;
        let rem = self.series(b, k).map_err(StepFailure::NotAnalytic)?;
        let remainder = [rem[0][k], rem[1][k]];
        let hk = h.powi(k as i32);
        let size = (hk * remainder[0]).mag().max((hk * remainder[1]).mag());
        if size > max_remainder {
            return Err(StepFailure::RemainderAbove(size));
        }
        let m = [point(set.mid[0]), point(set.mid[1])];
        // Degrees 0..K−1 of the order-K series are those of order K − 1.
        let mut at_mid = self
            .series_at_mid(set.mid)
            .map_err(StepFailure::NotAnalytic)?;
        // The mean-value form needs the Jacobian on the segment from m to
        // every state of the set: over hull(E ∪ {m}).
        let around = [e[0].convex_hull(m[0]), e[1].convex_hull(m[1])];
        let jac = self.jacobians(around, k - 1)?;
        for c in &mut at_mid {
            c.truncate(k);
        }
        let s = add(
            [horner(&at_mid[0], h), horner(&at_mid[1], h)],
            [hk * remainder[0], hk * remainder[1]],
        );
        if !bounded(&s) || !bounded(&remainder) {
            return Err(StepFailure::Unbounded);
        }
        let mid = [s[0].mid(), s[1].mid()];
        let z = [s[0] - point(mid[0]), s[1] - point(mid[1])];
        let data = StepData {
            h,
            apriori: b,
            apriori_outer: outer,
            end: *set,
            start: *set,
            at_mid,
            jac,
            remainder,
            order: k,
        };
        let j = data.jacobian(h);
        let c = mat_mul(&j, &exact_matrix(&set.frame));
        let direct = add(add([point(mid[0]), point(mid[1])], mat_vec(&c, set.r)), z);
        let (frame, inverse) = qr_frame(&c, &set.r);
        let r = add(mat_vec(&mat_mul(&inverse, &c), set.r), mat_vec(&inverse, z));
        let framed = add(
            [point(mid[0]), point(mid[1])],
            mat_vec(&exact_matrix(&frame), r),
        );
        let hull = intersect(intersect(direct, framed), b);
        if !bounded(&hull) || !bounded(&r) || hull.iter().any(|x| x.is_empty()) {
            return Err(StepFailure::Unbounded);
        }
        Ok(StepData {
            end: LohnerSet {
                mid,
                frame,
                r,
                hull,
            },
            ..data
        })
    }

    /// `∂x_k/∂x₀` over `x`, `k = 0..=order`.
    fn jacobians(&mut self, x: Vector, order: usize) -> Result<Vec<Matrix>, StepFailure> {
        let s = self
            .tape
            .ode_series(
                Dual::variable(x[0], 0),
                Dual::variable(x[1], 1),
                order,
                &mut self.work_dual,
            )
            .map_err(StepFailure::NotAnalytic)?;
        Ok((0..=order)
            .map(|d| {
                let j = [s.theta[d].grad, s.theta_dot[d].grad];
                if self.flips(d) {
                    j.map(|row| row.map(|x| -x))
                } else {
                    j
                }
            })
            .collect())
    }
}

/// The new frame: Q of mid(C) with its longer column (weighted by the
/// radius of r) first, and an enclosure of Q⁻¹.
fn qr_frame(c: &Matrix, r: &Vector) -> ([[f64; 2]; 2], Matrix) {
    let m = c.map(|row| row.map(|x| x.mid()));
    let weight = [
        r[0].rad().max(f64::MIN_POSITIVE),
        r[1].rad().max(f64::MIN_POSITIVE),
    ];
    let len = |j: usize| (m[0][j] * weight[j]).hypot(m[1][j] * weight[j]);
    let first = if len(1) > len(0) { 1 } else { 0 };
    let (x, y) = (m[0][first], m[1][first]);
    let n = x.hypot(y);
    let frame = if n.is_finite() && n > 0.0 {
        let (cs, sn) = (x / n, y / n);
        [[cs, -sn], [sn, cs]]
    } else {
        [[1.0, 0.0], [0.0, 1.0]]
    };
    // Q⁻¹ = adj(Q)/det(Q), in intervals: Q is only nearly orthogonal.
    let q = exact_matrix(&frame);
    let det = q[0][0] * q[1][1] - q[0][1] * q[1][0];
    let inverse = [
        [q[1][1] / det, -q[0][1] / det],
        [-q[1][0] / det, q[0][0] / det],
    ];
    (frame, inverse)
}
