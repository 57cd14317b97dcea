//! Exact arithmetic behind the [`Scalar`] trait, and identity proofs.
//!
//! [`Q`] is a `Copy` handle into a per-thread arena holding either a GMP
//! rational or, in a symbolic run, a rational function of variables
//! ([`symbolic::Frac`]), so the crate's generic formulas (and [`Dual`]
//! numbers on top of them) evaluate exactly in both. Only the field
//! operations exist: `sin`, `cos`, `sqrt` and `ln` panic, so angles enter
//! through `(sin θ, cos θ) = (2t, 1 − t²)/(1 + t²)`, `t = tan(θ/2)` (see
//! [`angle`]), with t itself a sampled quantity.
//!
//! **Identity proofs.** A check describes an identity as a closure that
//! draws its quantities (parameters, `t`, velocities, path coefficients,
//! weights of combined identities) from an [`Rng`] and returns both sides.
//! [`identity_test`] runs it once with every draw a fresh variable: the
//! sides become rational functions `P₁/Q₁`, `P₂/Q₂` with integer
//! coefficients, and they are equal iff the cleared difference
//! `P₁Q₂ − P₂Q₁` is the zero polynomial, which exact polynomial arithmetic
//! decides. Such an identity holds at every point where both sides are
//! defined; in θ it holds for every θ ∈ (−π, π) (t real), and since
//! `t ↦ (sin θ, cos θ)` covers the circle but one point, it is the same as
//! the identity in `sin θ`, `cos θ` modulo `sin²θ + cos²θ − 1`.
//!
//! When the sides differ, the same closure is run at random rational
//! points (`k/2¹⁰`, `k` uniform in `[1, 2³⁰]`, from a fixed seed so that
//! reports are reproducible) until one where they differ exactly is
//! found, for the report. Only when the symbolic run goes beyond a
//! [`Limit`] (coefficient overflow, too many variables or terms) does
//! agreement at [`POINTS`] random points stand in, reported as such
//! (`random-test`): by the Schwartz–Zippel lemma its probability of
//! missing a difference is at most `(d/2³⁰)⁸` for a cleared difference of
//! total degree d, with d ≤ [`DEGREE_BOUND`] asserted, not proved.

use super::symbolic::{self, Frac, Limit, MAX_VARS};
use crate::number::scalar::{Dual, Scalar};
use crate::scene::Angle;
use inari::Interval;
use rug::Rational;
use std::cell::RefCell;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// What a handle stands for.
#[derive(Clone, Debug)]
enum Value {
    /// A rational number.
    Num(Rational),
    /// A rational function of the variables of a symbolic run.
    Sym(Frac),
    /// A symbolic computation that went beyond a [`Limit`].
    Beyond(Limit),
}

thread_local! {
    static ARENA: RefCell<Vec<Value>> = const { RefCell::new(Vec::new()) };
}

/// An exact rational, or in a symbolic run a rational function of the
/// variables (handle into a per-thread arena).
#[derive(Clone, Copy)]
pub struct Q(u32);

/// Equality of the values (not of the handles); for rational functions,
/// identical equality (a computation beyond a limit equals nothing).
impl PartialEq for Q {
    fn eq(&self, o: &Q) -> bool {
        if self.0 == o.0 {
            return true;
        }
        match (self.value(), o.value()) {
            (Value::Num(a), Value::Num(b)) => a == b,
            _ => matches!((*self - *o).value(), Value::Sym(f) if f.is_zero()),
        }
    }
}

impl Q {
    fn store(v: Value) -> Q {
        ARENA.with(|a| {
            let mut a = a.borrow_mut();
            a.push(v);
            Q((a.len() - 1) as u32)
        })
    }
    fn value(self) -> Value {
        ARENA.with(|a| a.borrow()[self.0 as usize].clone())
    }
    pub fn new(r: Rational) -> Q {
        Q::store(Value::Num(r))
    }
    /// The variable number `i` of a symbolic run.
    fn variable(i: usize) -> Q {
        Q::store(if i < MAX_VARS {
            Value::Sym(Frac::var(i))
        } else {
            Value::Beyond(Limit(format!("more than {MAX_VARS} variables")))
        })
    }
    /// The rational value (panics on a symbolic value: only numbers have one).
    pub fn get(self) -> Rational {
        match self.value() {
            Value::Num(r) => r,
            _ => panic!("a symbolic value has no rational value"),
        }
    }
    pub fn ratio(n: i64, d: i64) -> Q {
        Q::new(Rational::from((n, d)))
    }
    /// An exact double as a rational.
    pub fn from_f64(x: f64) -> Q {
        Q::new(Rational::from_f64(x).expect("finite"))
    }
    /// Zero (for a rational function: the zero function).
    pub fn is_zero(self) -> bool {
        match self.value() {
            Value::Num(r) => r == 0,
            Value::Sym(f) => f.is_zero(),
            Value::Beyond(_) => false,
        }
    }
    pub fn signum(self) -> i32 {
        self.get().cmp0() as i32
    }
    /// Short decimal text (for reports): the rational rounded to a double.
    pub fn text(self) -> String {
        let f = rug::Float::with_val(80, &self.get());
        format!("{}", f.to_f64())
    }
    /// The exact rational as `p/q` text.
    pub fn exact_text(self) -> String {
        self.get().to_string()
    }
    fn frac(v: Value) -> Result<Frac, Limit> {
        match v {
            Value::Num(r) => {
                let small = |x: &rug::Integer| {
                    x.to_i128()
                        .ok_or_else(|| Limit("coefficient overflow".into()))
                };
                Frac::ratio(small(r.numer())?, small(r.denom())?)
            }
            Value::Sym(f) => Ok(f),
            Value::Beyond(l) => Err(l),
        }
    }
    fn bin(
        self,
        o: Q,
        num: impl Fn(&Rational, &Rational) -> Rational,
        sym: impl Fn(&Frac, &Frac) -> Result<Frac, Limit>,
    ) -> Q {
        let v = match (self.value(), o.value()) {
            (Value::Num(x), Value::Num(y)) => Value::Num(num(&x, &y)),
            (x, y) => match Q::frac(x).and_then(|x| sym(&x, &Q::frac(y)?)) {
                Ok(f) => Value::Sym(f),
                Err(l) => Value::Beyond(l),
            },
        };
        Q::store(v)
    }
}

impl std::fmt::Debug for Q {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        match self.value() {
            Value::Num(r) => write!(f, "{r}"),
            Value::Sym(x) => write!(f, "{x:?}"),
            Value::Beyond(l) => write!(f, "beyond a limit: {}", l.0),
        }
    }
}

impl Add for Q {
    type Output = Q;
    fn add(self, o: Q) -> Q {
        self.bin(o, |x, y| Rational::from(x + y), Frac::add)
    }
}
impl Sub for Q {
    type Output = Q;
    fn sub(self, o: Q) -> Q {
        self.bin(o, |x, y| Rational::from(x - y), Frac::sub)
    }
}
impl Mul for Q {
    type Output = Q;
    fn mul(self, o: Q) -> Q {
        self.bin(o, |x, y| Rational::from(x * y), Frac::mul)
    }
}
impl Div for Q {
    type Output = Q;
    fn div(self, o: Q) -> Q {
        assert!(!o.is_zero(), "exact division by zero");
        self.bin(o, |x, y| Rational::from(x / y), Frac::div)
    }
}
impl Neg for Q {
    type Output = Q;
    fn neg(self) -> Q {
        Q::int(0) - self
    }
}

impl Scalar for Q {
    /// Only point enclosures (exact doubles) can be lifted.
    fn lift(x: Interval) -> Self {
        assert!(
            x.inf() == x.sup(),
            "Q::lift needs an exact double, got {x:?}"
        );
        Q::from_f64(x.inf())
    }
    fn int(n: i32) -> Self {
        Q::new(Rational::from(n))
    }
    fn sqr(self) -> Self {
        self * self
    }
    fn sqrt(self) -> Self {
        panic!("sqrt is not rational")
    }
    fn sin(self) -> Self {
        panic!("sin is not rational: build angles with claims::exact::angle")
    }
    fn cos(self) -> Self {
        panic!("cos is not rational: build angles with claims::exact::angle")
    }
    fn ln(self) -> Self {
        panic!("ln is not rational")
    }
    fn tan(self) -> Self {
        panic!("tan is not rational")
    }
    fn abs(self) -> Self {
        Q::new(self.get().abs())
    }
    fn abs_slope(self) -> Self {
        assert!(!self.is_zero(), "abs has no derivative at 0");
        Q::int(if self.get() > 0 { 1 } else { -1 })
    }
    fn atan(self) -> Self {
        panic!("atan is not rational")
    }
    fn exp(self) -> Self {
        panic!("exp is not rational")
    }
    fn sign(self) -> Self {
        Q::int(if self.is_zero() {
            0
        } else if self.get() > 0 {
            1
        } else {
            -1
        })
    }
    fn sign_slope(self) -> Self {
        assert!(!self.is_zero(), "sign has no derivative at 0");
        Q::int(0)
    }
    fn min(self, other: Self) -> Self {
        if self.get() <= other.get() {
            self
        } else {
            other
        }
    }
    fn max(self, other: Self) -> Self {
        if self.get() >= other.get() {
            self
        } else {
            other
        }
    }
}

/// `(sin θ, cos θ)` for `t = tan(θ/2)`.
pub fn sin_cos_of_tan_half<T: Scalar>(t: T) -> (T, T) {
    let one = T::int(1);
    let d = one + t.sqr();
    (T::int(2) * t / d, (one - t.sqr()) / d)
}

/// The angle with `tan(θ/2) = t` (θ itself is not rational; it is never used).
pub fn angle(t: Q) -> Angle<Q> {
    let (sin, cos) = sin_cos_of_tan_half(t);
    Angle {
        theta: Q::int(0),
        sin,
        cos,
    }
}

/// θ as the variable (gradient slot 0) of a dual number: sin and cos carry
/// their derivatives `cos`, `−sin`.
pub fn angle_d<T: Scalar>(s: T, c: T) -> Angle<Dual<T>> {
    let z = T::int(0);
    Angle {
        theta: Dual::variable(z, 0),
        sin: Dual {
            value: s,
            grad: [c, z],
        },
        cos: Dual {
            value: c,
            grad: [-s, z],
        },
    }
}

/// θ as the variable of a second-order (nested) dual number.
pub fn angle_dd<T: Scalar>(s: T, c: T) -> Angle<Dual<Dual<T>>> {
    let z = T::int(0);
    let sd = Dual {
        value: s,
        grad: [c, z],
    };
    let cd = Dual {
        value: c,
        grad: [-s, z],
    };
    let zd = Dual::constant(z);
    Angle {
        theta: Dual::variable(Dual::variable(z, 0), 0),
        sin: Dual {
            value: sd,
            grad: [cd, zd],
        },
        cos: Dual {
            value: cd,
            grad: [-sd, zd],
        },
    }
}

/// `(f, f', f'')` in θ of a second-order dual.
pub fn jet2<T: Scalar>(x: Dual<Dual<T>>) -> (T, T, T) {
    (x.value.value, x.value.grad[0], x.grad[0].grad[0])
}

/// A second-order dual number in the path parameter `t`.
pub type DD = Dual<Dual<Q>>;

/// A rational constant lifted to [`DD`].
pub fn dd_const(x: Q) -> DD {
    DD::constant(Dual::constant(x))
}

/// A random rational path for identity tests: `tan(θ(t)/2) = u₀ + u₁t + u₂t²`
/// and a height `y = y₀ + y₁t + y₂t²`, taken at `t = 0`.
pub struct RationalPath {
    /// `u₀ = tan(θ(0)/2)`.
    pub u0: Q,
    /// `y₂ = ÿ(0)/2`.
    pub y2: Q,
    /// `u(t)` as a second-order dual in t at `t = 0`.
    pub u: DD,
    /// `y(t)` as a second-order dual in t at `t = 0`.
    pub y: DD,
    /// `θ̇(0)`.
    pub w: Q,
    /// `θ̈(0)`.
    pub thdd: Q,
    /// `sin θ(0)`.
    pub s: Q,
    /// `cos θ(0)`.
    pub c: Q,
}

impl RationalPath {
    /// Draws `u₀` (a `tan(θ/2)`), then `u₁, u₂, y₀, y₁, y₂` (signed), in that order.
    pub fn random(r: &mut Rng) -> RationalPath {
        let mut draw = |name: &str, tan_half: bool| {
            let q = if tan_half { r.tan_half() } else { r.signed() };
            r.named(name, q)
        };
        let (u0, u1, u2) = (draw("u0", true), draw("u1", false), draw("u2", false));
        let (y0, y1, y2) = (draw("y0", false), draw("y1", false), draw("y2", false));
        let tt = DD::variable(Dual::variable(Q::int(0), 0), 0);
        let u = dd_const(u0) + dd_const(u1) * tt + dd_const(u2) * tt.sqr();
        let y = dd_const(y0) + dd_const(y1) * tt + dd_const(y2) * tt.sqr();
        // θ̇ = 2u̇/(1 + u²) as a first-order dual in t: θ̈ is its derivative.
        let ud = Dual {
            value: u0,
            grad: [u1, Q::int(0)],
        };
        let udot = Dual {
            value: u1,
            grad: [Q::int(2) * u2, Q::int(0)],
        };
        let thd = Dual::<Q>::int(2) * udot / (Dual::<Q>::int(1) + ud.sqr());
        let (s, c) = sin_cos_of_tan_half(u0);
        RationalPath {
            u0,
            y2,
            u,
            y,
            w: thd.value,
            thdd: thd.grad[0],
            s,
            c,
        }
    }
}

/// Total degree assumed, not proved, for a cleared difference in the random
/// test that stands in when a symbolic run goes beyond a [`Limit`].
pub const DEGREE_BOUND: u64 = 200;
/// |S|: sampled values are `k/2¹⁰`, `k ∈ [1, 2³⁰]`.
pub const SAMPLE_SET_LOG2: u32 = 30;
/// Points per random test.
pub const POINTS: usize = 8;

/// Where the sampled quantities come from: random rationals drawn by a
/// fixed-seed generator (splitmix64), or in a symbolic run a fresh variable
/// for each draw.
pub struct Rng {
    state: u64,
    symbolic: bool,
    /// The draws of the current sample, in order, with their names.
    drawn: Vec<(Q, Option<String>)>,
}

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng {
            state: seed ^ 0x9e37_79b9_7f4a_7c15,
            symbolic: false,
            drawn: Vec::new(),
        }
    }
    /// Every draw a new variable.
    pub fn symbolic() -> Rng {
        Rng {
            state: 0,
            symbolic: true,
            drawn: Vec::new(),
        }
    }
    fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn draw(&mut self, number: impl FnOnce(&mut Rng) -> f64) -> Q {
        let q = if self.symbolic {
            Q::variable(self.drawn.len())
        } else {
            Q::from_f64(number(self))
        };
        self.drawn.push((q, None));
        q
    }
    /// `k/2¹⁰`, `k` uniform in `[1, 2³⁰]`.
    fn positive_f64(&mut self) -> f64 {
        let k = (self.next_u64() >> (64 - SAMPLE_SET_LOG2)) + 1;
        k as f64 / 1024.0
    }
    /// Names the draw `q` in witnesses; returns it.
    pub fn named(&mut self, name: &str, q: Q) -> Q {
        if let Some(d) = self.drawn.iter_mut().find(|d| d.0 .0 == q.0) {
            d.1 = Some(name.to_string());
        }
        q
    }
    /// A positive quantity (a parameter): `k/2¹⁰`, `k` uniform in `[1, 2³⁰]`.
    pub fn positive(&mut self) -> Q {
        self.draw(Rng::positive_f64)
    }
    /// A signed quantity (sign from an independent bit).
    pub fn signed(&mut self) -> Q {
        self.draw(|r| {
            let s = if r.next_u64() & 1 == 0 { 1.0 } else { -1.0 };
            s * r.positive_f64()
        })
    }
    /// `tan(θ/2)` for θ ∈ (0, π) away from π/2 (t ≠ 1): a value in (0, 2⁴).
    pub fn tan_half(&mut self) -> Q {
        self.draw(|r| loop {
            let k = (r.next_u64() >> (64 - SAMPLE_SET_LOG2)) + 1;
            if k != 1 << 26 {
                return k as f64 / (1u64 << 26) as f64;
            }
        })
    }
}

/// A point where the two sides differ, exactly.
#[derive(Clone, Debug)]
pub struct Point {
    /// Every sampled value (named as in [`Identity::Proved`]), exact.
    pub values: Vec<(String, String)>,
    /// The two sides and their exact difference, rounded for reading.
    pub lhs: String,
    pub rhs: String,
    pub difference: String,
}

/// What an identity test found.
#[derive(Clone, Debug)]
pub enum Identity {
    /// Proved: the two sides are equal as rational functions of the sampled
    /// variables (the cleared difference is the zero polynomial).
    Proved {
        /// The variables in the order drawn: named as the sample names
        /// them, else `x0, x1, …` by that order.
        variables: Vec<String>,
        /// Terms of the two sides (expanded parts and factors).
        terms: [usize; 2],
        /// Distinct denominator and common factors met on the way.
        factors: usize,
    },
    /// Not proved (the symbolic run went beyond `limit`); equal at
    /// `points` random rational points.
    Agree { points: usize, limit: String },
    /// The two sides differ: a nonzero cleared difference (its terms, when
    /// the symbolic run completed) and a point where they differ.
    Differ {
        terms: Option<usize>,
        point: Option<Point>,
    },
}

impl Identity {
    pub fn agrees(&self) -> bool {
        !matches!(self, Identity::Differ { .. })
    }
    pub fn proved(&self) -> bool {
        matches!(self, Identity::Proved { .. })
    }
    /// How the identity was found, for evidence texts.
    pub fn how(&self) -> &'static str {
        if self.proved() {
            "proved identity"
        } else if self.agrees() {
            "random points"
        } else {
            "NOT"
        }
    }
    pub fn json(&self) -> serde_json::Value {
        match self {
            Identity::Proved {
                variables,
                terms,
                factors,
            } => serde_json::json!({
                "identity": "proved",
                "cleared_difference": "identically zero",
                "variables": variables,
                "terms": {"printed": terms[0], "derived": terms[1]},
                "factors": factors,
            }),
            Identity::Agree { points, limit } => serde_json::json!({
                "identity": "agree",
                "not_proved": limit,
                "points": points,
                "schwartz_zippel": format!(
                    "exact agreement at {points} independent points from S^n, |S| = 2^{SAMPLE_SET_LOG2}; \
                     if deg ≤ {DEGREE_BOUND} (asserted, not proved), P(false agreement) ≤ ({DEGREE_BOUND}/2^{SAMPLE_SET_LOG2})^{points}"
                ),
            }),
            Identity::Differ { terms, point } => {
                let mut o = serde_json::json!({"identity": "differ"});
                if let Some(n) = terms {
                    o["cleared_difference_terms"] = (*n).into();
                }
                if let Some(p) = point {
                    o["point"] = p
                        .values
                        .iter()
                        .map(|(k, v)| (k.clone(), serde_json::Value::String(v.clone())))
                        .collect::<serde_json::Map<_, _>>()
                        .into();
                    o["printed"] = p.lhs.clone().into();
                    o["derived"] = p.rhs.clone().into();
                    o["printed_minus_derived"] = p.difference.clone().into();
                }
                o
            }
        }
    }
}

/// What backs a conclusion from several identities: a random test if one
/// only agrees at random points, else a proof (every one proved) or an
/// exact computation (some differ).
pub fn strength_of(ids: &[&Identity]) -> super::Strength {
    if ids.iter().any(|i| matches!(i, Identity::Agree { .. })) {
        super::Strength::RandomTest
    } else if ids.iter().all(|i| i.proved()) {
        super::Strength::Symbolic
    } else {
        super::Strength::Exact
    }
}

/// A sample: named sampled values (for the witness) and the two sides.
pub struct Sample {
    pub point: Vec<(String, Q)>,
    pub lhs: Q,
    pub rhs: Q,
}

fn arena_len() -> usize {
    ARENA.with(|a| a.borrow().len())
}

/// Drops the values made since `mark`.
fn release(mark: usize) {
    ARENA.with(|a| a.borrow_mut().truncate(mark));
}

/// `f` run once with variables: `Ok(Ok(proof))` when the sides agree
/// identically, `Ok(Err(terms))` with the terms of the nonzero cleared
/// difference.
fn prove(f: &mut impl FnMut(&mut Rng) -> Sample) -> Result<Result<Identity, usize>, Limit> {
    let mark = arena_len();
    let mut rng = Rng::symbolic();
    let s = f(&mut rng);
    let out = (|| {
        if rng.drawn.len() > MAX_VARS {
            return Err(Limit(format!("more than {MAX_VARS} variables")));
        }
        let (l, r) = (Q::frac(s.lhs.value())?, Q::frac(s.rhs.value())?);
        let d = l.sub(&r)?;
        if !d.is_zero() {
            return Ok(Err(d.expanded().terms()));
        }
        Ok(Ok(Identity::Proved {
            variables: names(&rng.drawn, &s.point),
            terms: [l.size(), r.size()],
            factors: symbolic::factor_count(),
        }))
    })();
    release(mark);
    symbolic::clear_factors();
    out
}

/// Names of the draws: as the sample names them, else as named when drawn,
/// else `x0, x1, …` by order.
fn names(drawn: &[(Q, Option<String>)], point: &[(String, Q)]) -> Vec<String> {
    drawn
        .iter()
        .enumerate()
        .map(
            |(i, (q, name))| match point.iter().find(|(_, p)| p.0 == q.0) {
                Some((name, _)) => name.clone(),
                None => name.clone().unwrap_or_else(|| format!("x{i}")),
            },
        )
        .collect()
}

/// The first of [`POINTS`] random points (from `seed`) where the sides differ.
fn differing_point(seed: u64, f: &mut impl FnMut(&mut Rng) -> Sample) -> Option<Point> {
    let mark = arena_len();
    let mut rng = Rng::new(seed);
    let mut found = None;
    for _ in 0..POINTS {
        rng.drawn.clear();
        let s = f(&mut rng);
        if s.lhs != s.rhs {
            found = Some(Point {
                values: names(&rng.drawn, &s.point)
                    .into_iter()
                    .zip(&rng.drawn)
                    .map(|(k, v)| (k, v.0.exact_text()))
                    .collect(),
                lhs: s.lhs.text(),
                rhs: s.rhs.text(),
                difference: (s.lhs - s.rhs).text(),
            });
            break;
        }
    }
    release(mark);
    found
}

/// Proves `lhs = rhs` for the sample `f` makes: once with every draw a
/// variable (exact polynomial arithmetic); when they differ, or the run goes
/// beyond a limit, at random points from `seed` for a point where they differ.
/// Values made inside `f` do not outlive the test (and `f` runs no parallel
/// code, so no other test runs on this thread meanwhile).
pub fn identity_test(seed: u64, mut f: impl FnMut(&mut Rng) -> Sample) -> Identity {
    match prove(&mut f) {
        Ok(Ok(proved)) => proved,
        Ok(Err(terms)) => Identity::Differ {
            terms: Some(terms),
            point: differing_point(seed, &mut f),
        },
        Err(limit) => match differing_point(seed, &mut f) {
            Some(p) => Identity::Differ {
                terms: None,
                point: Some(p),
            },
            None => Identity::Agree {
                points: POINTS,
                limit: limit.0,
            },
        },
    }
}

/// Determinant of a small square matrix by cofactor expansion (no pivoting:
/// works for any [`Scalar`], exact in [`Q`]).
pub fn det<T: Scalar>(m: &[Vec<T>]) -> T {
    let n = m.len();
    if n == 1 {
        return m[0][0];
    }
    let mut acc = T::int(0);
    for j in 0..n {
        let minor: Vec<Vec<T>> = m[1..]
            .iter()
            .map(|row| {
                row.iter()
                    .enumerate()
                    .filter(|(k, _)| *k != j)
                    .map(|(_, x)| *x)
                    .collect()
            })
            .collect();
        let term = m[0][j] * det(&minor);
        acc = if j % 2 == 0 { acc + term } else { acc - term };
    }
    acc
}

/// Solves `M x = r` by Cramer's rule.
pub fn solve<T: Scalar>(m: &[Vec<T>], r: &[T]) -> Vec<T> {
    let d = det(m);
    (0..m.len())
        .map(|j| {
            let mj: Vec<Vec<T>> = m
                .iter()
                .zip(r)
                .map(|(row, ri)| {
                    row.iter()
                        .enumerate()
                        .map(|(k, x)| if k == j { *ri } else { *x })
                        .collect()
                })
                .collect();
            det(&mj) / d
        })
        .collect()
}

/// A decimal text (`-12.5e-3` style without exponent: digits, one dot) as
/// an exact rational.
pub fn qdec(text: &str) -> Q {
    let t = text.trim();
    let (neg, body) = match t.strip_prefix('-') {
        Some(b) => (true, b),
        None => (false, t),
    };
    let (int, frac) = body.split_once('.').unwrap_or((body, ""));
    let digits = format!("{int}{frac}");
    let num = rug::Integer::from_str_radix(&digits, 10).expect("decimal digits");
    let den = rug::Integer::from(rug::Integer::u_pow_u(10, frac.len() as u32));
    let r = Rational::from((num, den));
    Q::new(if neg { -r } else { r })
}

/// How identities that all agree were shown to.
pub fn agreement(ids: &[&Identity]) -> &'static str {
    if ids.iter().all(|i| i.proved()) {
        "proved identically (exact polynomial arithmetic)"
    } else {
        "exact agreement at random rational points (not proved)"
    }
}

/// The verdict of formula checks by identity tests: confirmed when every
/// identity agrees, an error (with the right form) when one differs exactly.
pub(crate) fn verdict_of(ids: &[(&str, &Identity)], what: &str, right: &str) -> super::Outcome {
    let w: serde_json::Map<String, serde_json::Value> =
        ids.iter().map(|(k, i)| (k.to_string(), i.json())).collect();
    if ids.iter().all(|(_, i)| i.agrees()) {
        let all: Vec<&Identity> = ids.iter().map(|(_, i)| *i).collect();
        super::Outcome::new(
            super::Verdict::Confirmed,
            strength_of(&all),
            format!("{what}: {}", agreement(&all)),
            w.into(),
        )
    } else {
        let bad: Vec<&str> = ids
            .iter()
            .filter(|(_, i)| !i.agrees())
            .map(|(k, _)| *k)
            .collect();
        super::Outcome::new(
            super::Verdict::Error,
            super::Strength::Exact,
            format!("{what}: exact difference ({})", bad.join(", ")),
            w.into(),
        )
        .correct(right.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimal_text_is_exact() {
        assert_eq!(qdec("9.81").get(), Rational::from((981, 100)));
        assert_eq!(qdec("-0.125").get(), Rational::from((-1, 8)));
        assert_eq!(qdec("3").get(), Rational::from(3));
    }

    #[test]
    fn cramer_solves_exactly() {
        // [[2, 1], [1, 3]] x = [3, 5] → x = (4/5, 7/5)
        let q = |n: i64| Q::ratio(n, 1);
        let x = solve(&[vec![q(2), q(1)], vec![q(1), q(3)]], &[q(3), q(5)]);
        assert_eq!(x[0].get(), Rational::from((4, 5)));
        assert_eq!(x[1].get(), Rational::from((7, 5)));
    }

    #[test]
    fn identity_test_separates_close_formulas() {
        // sin²θ + cos²θ = 1 holds; (1 + 10⁻⁹) sin²θ + cos²θ = 1 does not.
        let ok = identity_test(1, |r| {
            let (s, c) = sin_cos_of_tan_half(r.tan_half());
            Sample {
                point: vec![],
                lhs: s.sqr() + c.sqr(),
                rhs: Q::int(1),
            }
        });
        assert!(ok.proved());
        let bad = identity_test(1, |r| {
            let t = r.tan_half();
            let (s, c) = sin_cos_of_tan_half(t);
            let eps = Q::ratio(1, 1_000_000_000);
            Sample {
                point: vec![("t".into(), t)],
                lhs: (Q::int(1) + eps) * s.sqr() + c.sqr(),
                rhs: Q::int(1),
            }
        });
        // The difference 10⁻⁹ sin²θ clears to 4·t² (over 10⁹(1 + t²)²): one
        // term; at the point found the sides differ exactly.
        match bad {
            Identity::Differ {
                terms: Some(1),
                point: Some(p),
            } => {
                let t = Rational::from_str_radix(&p.values[0].1, 10).unwrap();
                let s: Rational = Rational::from(2 * &t) / (1 + t.clone().square());
                let lhs = Rational::from((1_000_000_001, 1_000_000_000)) * s.clone().square()
                    + (Rational::from(1) - s.square());
                assert_ne!(lhs, 1);
            }
            other => panic!("not refused as expected: {other:?}"),
        }
    }

    /// sin²θ + cos²θ = 1 in the variables s, c themselves is not an identity
    /// of rational functions: it holds on the circle only, which the tan-half
    /// parametrisation supplies.
    #[test]
    fn the_circle_comes_from_the_parametrisation() {
        let free = identity_test(2, |r| {
            let (s, c) = (r.signed(), r.signed());
            Sample {
                point: vec![],
                lhs: s.sqr() + c.sqr(),
                rhs: Q::int(1),
            }
        });
        assert!(!free.agrees());
    }

    #[test]
    fn binomial_identities_in_two_variables() {
        let square = |wrong: bool| {
            identity_test(3, move |r| {
                let (x, y) = (r.signed(), r.signed());
                let rhs = if wrong {
                    x.sqr() + y.sqr()
                } else {
                    x.sqr() + Q::int(2) * x * y + y.sqr()
                };
                Sample {
                    point: vec![("x".into(), x), ("y".into(), y)],
                    lhs: (x + y).sqr(),
                    rhs,
                }
            })
        };
        match square(false) {
            Identity::Proved { variables, .. } => assert_eq!(variables, ["x", "y"]),
            other => panic!("(x + y)² = x² + 2xy + y² not proved: {other:?}"),
        }
        // (x + y)² − x² − y² = 2xy: one term
        assert!(matches!(
            square(true),
            Identity::Differ {
                terms: Some(1),
                point: Some(_)
            }
        ));
    }

    /// Beyond the variable budget the test says it only sampled.
    #[test]
    fn too_many_variables_fall_back_to_sampling() {
        let id = identity_test(4, |r| {
            let xs: Vec<Q> = (0..symbolic::MAX_VARS + 1).map(|_| r.signed()).collect();
            let sum = xs.iter().fold(Q::int(0), |a, x| a + *x);
            Sample {
                point: vec![],
                lhs: sum.sqr(),
                rhs: sum * sum,
            }
        });
        assert!(matches!(id, Identity::Agree { points: POINTS, .. }));
        assert!(id.agrees() && !id.proved());
    }

    #[test]
    fn jets_give_exact_derivatives() {
        // d/dθ and d²/dθ² of sin θ cos θ = ½ sin 2θ: cos 2θ and −2 sin 2θ
        let (s, c) = sin_cos_of_tan_half(Q::ratio(1, 3));
        let an = angle_dd(s, c);
        let (v, d1, d2) = jet2(an.sin * an.cos);
        assert_eq!(v.get(), (s * c).get());
        assert_eq!(d1.get(), (c.sqr() - s.sqr()).get());
        assert_eq!(d2.get(), (Q::int(-4) * s * c).get());
    }
}
