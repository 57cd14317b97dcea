//! Exact rational arithmetic behind the [`Scalar`] trait, and identity tests.
//!
//! [`Q`] is a `Copy` handle to a GMP rational kept in a per-thread arena, so
//! the crate's generic formulas (and [`Dual`] numbers on
//! top of them) evaluate exactly. Only the field operations exist: `sin`,
//! `cos`, `sqrt` and `ln` panic, so angles enter through rational
//! `(sin θ, cos θ) = (2t, 1 − t²)/(1 + t²)`, `t = tan(θ/2)` (see [`angle`]).
//!
//! **Identity tests.** Two rational functions `P₁/Q₁`, `P₂/Q₂` of the sampled
//! variables agree identically iff `D = P₁Q₂ − P₂Q₁` is the zero polynomial.
//! If not, by the Schwartz–Zippel lemma a point drawn uniformly from `Sⁿ`
//! is a zero of D with probability at most `deg D/|S|`. The sampled values
//! are `k/2¹⁰`, `k` uniform in `[1, 2³⁰]` (|S| = 2³⁰), drawn by a fixed-seed
//! generator so that reports are reproducible; the formulas checked here
//! clear to polynomials of total degree well below [`DEGREE_BOUND`] = 200, so
//! agreement at `n` independent points leaves a probability at most
//! `(200/2³⁰)ⁿ` that the formulas differ (n = 8: below 10⁻⁵³).

use crate::number::scalar::{Dual, Scalar};
use crate::scene::Angle;
use inari::Interval;
use rug::Rational;
use std::cell::RefCell;
use std::ops::{Add, Div, Mul, Neg, Sub};

thread_local! {
    static ARENA: RefCell<Vec<Rational>> = const { RefCell::new(Vec::new()) };
}

/// An exact rational (handle into a per-thread arena).
#[derive(Clone, Copy)]
pub struct Q(u32);

/// Equality of the values (not of the handles).
impl PartialEq for Q {
    fn eq(&self, o: &Q) -> bool {
        self.0 == o.0 || self.get() == o.get()
    }
}

impl Q {
    pub fn new(r: Rational) -> Q {
        ARENA.with(|a| {
            let mut a = a.borrow_mut();
            a.push(r);
            Q((a.len() - 1) as u32)
        })
    }
    pub fn get(self) -> Rational {
        ARENA.with(|a| a.borrow()[self.0 as usize].clone())
    }
    pub fn ratio(n: i64, d: i64) -> Q {
        Q::new(Rational::from((n, d)))
    }
    /// An exact double as a rational.
    pub fn from_f64(x: f64) -> Q {
        Q::new(Rational::from_f64(x).expect("finite"))
    }
    pub fn is_zero(self) -> bool {
        ARENA.with(|a| a.borrow()[self.0 as usize] == 0)
    }
    pub fn signum(self) -> i32 {
        ARENA.with(|a| a.borrow()[self.0 as usize].cmp0() as i32)
    }
    /// Short decimal text (for reports): the rational rounded to 12 digits.
    pub fn text(self) -> String {
        let r = self.get();
        let f = rug::Float::with_val(80, &r);
        format!("{}", f.to_f64())
    }
    fn bin(self, o: Q, f: impl Fn(&Rational, &Rational) -> Rational) -> Q {
        let r = ARENA.with(|a| {
            let a = a.borrow();
            f(&a[self.0 as usize], &a[o.0 as usize])
        });
        Q::new(r)
    }
}

impl std::fmt::Debug for Q {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "{}", self.get())
    }
}

impl Add for Q {
    type Output = Q;
    fn add(self, o: Q) -> Q {
        self.bin(o, |x, y| Rational::from(x + y))
    }
}
impl Sub for Q {
    type Output = Q;
    fn sub(self, o: Q) -> Q {
        self.bin(o, |x, y| Rational::from(x - y))
    }
}
impl Mul for Q {
    type Output = Q;
    fn mul(self, o: Q) -> Q {
        self.bin(o, |x, y| Rational::from(x * y))
    }
}
impl Div for Q {
    type Output = Q;
    fn div(self, o: Q) -> Q {
        assert!(!o.is_zero(), "exact division by zero");
        self.bin(o, |x, y| Rational::from(x / y))
    }
}
impl Neg for Q {
    type Output = Q;
    fn neg(self) -> Q {
        Q::new(-self.get())
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
        let (u0, u1, u2) = (
            r.tan_half(),
            Q::from_f64(r.signed()),
            Q::from_f64(r.signed()),
        );
        let (y0, y1, y2) = (
            Q::from_f64(r.signed()),
            Q::from_f64(r.signed()),
            Q::from_f64(r.signed()),
        );
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

/// Upper bound assumed on the total degree of every cleared difference.
pub const DEGREE_BOUND: u64 = 200;
/// |S|: sampled values are `k/2¹⁰`, `k ∈ [1, 2³⁰]`.
pub const SAMPLE_SET_LOG2: u32 = 30;
/// Points per identity test.
pub const POINTS: usize = 8;

/// Deterministic generator (splitmix64) for the sample points.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed ^ 0x9e37_79b9_7f4a_7c15)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// `k/2¹⁰`, `k` uniform in `[1, 2³⁰]`, as an exact double.
    pub fn positive(&mut self) -> f64 {
        let k = (self.next_u64() >> (64 - SAMPLE_SET_LOG2)) + 1;
        k as f64 / 1024.0
    }
    /// A signed sample (sign from an independent bit).
    pub fn signed(&mut self) -> f64 {
        let s = if self.next_u64() & 1 == 0 { 1.0 } else { -1.0 };
        s * self.positive()
    }
    /// A positive sample as a point interval (for `Scalar::lift`).
    pub fn pos_iv(&mut self) -> Interval {
        let x = self.positive();
        Interval::try_from((x, x)).unwrap()
    }
    pub fn signed_iv(&mut self) -> Interval {
        let x = self.signed();
        Interval::try_from((x, x)).unwrap()
    }
    /// `tan(θ/2)` for θ ∈ (0, π) away from π/2 (t ≠ 1): a value in (0, 2⁴).
    pub fn tan_half(&mut self) -> Q {
        loop {
            let k = (self.next_u64() >> (64 - SAMPLE_SET_LOG2)) + 1;
            if k != 1 << 26 {
                return Q::from_f64(k as f64 / (1u64 << 26) as f64);
            }
        }
    }
}

/// What an identity test found.
#[derive(Clone, Debug)]
pub enum Identity {
    /// Equal at every sampled point.
    Agree { points: usize },
    /// A point where the two sides differ exactly.
    Differ {
        point: Vec<(String, String)>,
        lhs: String,
        rhs: String,
    },
}

impl Identity {
    pub fn agrees(&self) -> bool {
        matches!(self, Identity::Agree { .. })
    }
    pub fn json(&self) -> serde_json::Value {
        match self {
            Identity::Agree { points } => serde_json::json!({
                "identity": "agree",
                "points": points,
                "schwartz_zippel": format!(
                    "exact agreement at {points} independent points from S^n, |S| = 2^{SAMPLE_SET_LOG2}; \
                     with deg ≤ {DEGREE_BOUND}, P(false agreement) ≤ ({DEGREE_BOUND}/2^{SAMPLE_SET_LOG2})^{points}"
                ),
            }),
            Identity::Differ { point, lhs, rhs } => serde_json::json!({
                "identity": "differ",
                "point": point.iter().map(|(k, v)| (k.clone(), serde_json::Value::String(v.clone()))).collect::<serde_json::Map<_, _>>(),
                "printed": lhs,
                "derived": rhs,
            }),
        }
    }
}

/// A sample point: named values (for the witness) and the two sides.
pub struct Sample {
    pub point: Vec<(String, f64)>,
    pub lhs: Q,
    pub rhs: Q,
}

/// Runs `f` at [`POINTS`] points drawn from `seed`; stops at the first
/// difference.
pub fn identity_test(seed: u64, mut f: impl FnMut(&mut Rng) -> Sample) -> Identity {
    let mut rng = Rng::new(seed);
    for _ in 0..POINTS {
        let s = f(&mut rng);
        if s.lhs != s.rhs {
            return Identity::Differ {
                point: s
                    .point
                    .into_iter()
                    .map(|(k, v)| (k, format!("{v}")))
                    .collect(),
                lhs: s.lhs.text(),
                rhs: s.rhs.text(),
            };
        }
    }
    Identity::Agree { points: POINTS }
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

/// The verdict of formula checks by identity tests: confirmed when every
/// identity agrees, an error (with the right form) when one differs exactly.
pub(crate) fn verdict_of(ids: &[(&str, &Identity)], what: &str, right: &str) -> super::Outcome {
    let w: serde_json::Map<String, serde_json::Value> =
        ids.iter().map(|(k, i)| (k.to_string(), i.json())).collect();
    if ids.iter().all(|(_, i)| i.agrees()) {
        super::Outcome::new(
            super::Verdict::Confirmed,
            super::Strength::IdentityTest,
            format!("{what}: exact agreement at random rational points"),
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
        assert!(ok.agrees());
        let bad = identity_test(1, |r| {
            let (s, c) = sin_cos_of_tan_half(r.tan_half());
            let eps = Q::ratio(1, 1_000_000_000);
            Sample {
                point: vec![],
                lhs: (Q::int(1) + eps) * s.sqr() + c.sqr(),
                rhs: Q::int(1),
            }
        });
        assert!(!bad.agrees());
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
