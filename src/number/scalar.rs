//! One scalar trait for every formula: `f64` (drawing, uncertified baselines),
//! [`Interval`] and [`DecInterval`] (certified enclosures, the decorated form
//! tracking where a formula may be undefined) and [`Dual`] (value plus the
//! gradient in (θ, θ̇), for mean-value forms, Newton steps and mechanics checks).
//!
//! Scene formulas are written once against [`Scalar`]; evaluating on a point, on
//! a box, or with derivatives is the same code.

use inari::{const_dec_interval, const_interval, DecInterval, Decoration, Interval};
use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// The arithmetic a scene formula may use. Deliberately small: no ordering,
/// no `is_nan`, nothing an interval cannot honestly provide.
pub trait Scalar:
    Copy
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// A constant known as an enclosure. `f64` takes its midpoint (uncertified
    /// paths only); interval types keep the whole enclosure.
    fn lift(x: Interval) -> Self;
    /// [`Scalar::lift`] of a constant lifted once for every scalar
    /// ([`Known`]): the same value, copied instead of computed.
    fn lift_known(k: &Known) -> Self {
        Self::lift(k.interval)
    }
    /// A small integer, exact in every implementation.
    fn int(n: i32) -> Self;
    fn sqr(self) -> Self;
    fn sqrt(self) -> Self;
    fn sin(self) -> Self;
    fn cos(self) -> Self;
    fn ln(self) -> Self;
    fn tan(self) -> Self;
    fn abs(self) -> Self;
    /// The derivative of `abs` at `self`, for duals: `1` where `self > 0`,
    /// `-1` where `self < 0`. Where `self` may be 0 there is no derivative:
    /// interval types return `[-1, 1]` (every slope of `abs` there, so a dual's
    /// gradient stays an enclosure of the Clarke gradient) and decorated ones
    /// mark it `trv`, so a check for `≥ dac` on a derivative fails.
    fn abs_slope(self) -> Self;
    fn atan(self) -> Self;
    fn exp(self) -> Self;
    /// −1, 0 or 1 by the sign of `self` (0 at 0).
    fn sign(self) -> Self;
    /// The derivative of `sign`: `0` where `self` has a fixed sign; where it
    /// may be 0 there is none (a jump), so interval types return the whole
    /// line (decorated `trv`): nothing is concluded from it.
    fn sign_slope(self) -> Self;
    fn min(self, other: Self) -> Self;
    fn max(self, other: Self) -> Self;
    /// `self^n`, the language's `x^n`. The default multiplies left to right,
    /// `((x·x)·x)·…`, `n − 1` products (`x^0 = 1`, `x^1 = x`); interval types
    /// override it with the tightest enclosure (`inari`'s `pown`).
    fn pown(self, n: u32) -> Self {
        if n == 0 {
            return Self::int(1);
        }
        let mut p = self;
        for _ in 1..n {
            p = p * self;
        }
        p
    }
    /// `(sin, cos)` together; duals reuse both for the derivatives.
    fn sin_cos(self) -> (Self, Self) {
        (self.sin(), self.cos())
    }
}

/// A constant in the forms the scalars lift it to, each computed once: what
/// a compiled formula lifts at every evaluation ([`Scalar::lift_known`]).
#[derive(Clone, Copy, Debug)]
pub struct Known {
    pub interval: Interval,
    /// `DecInterval::lift(interval)`.
    pub decorated: DecInterval,
    /// `f64::lift(interval)`, the midpoint.
    pub mid: f64,
}

impl Known {
    /// The exact 0, lifted as [`Scalar::int`] gives it: a dual constant's
    /// gradient.
    pub const ZERO: Known = Known {
        interval: const_interval!(0.0, 0.0),
        decorated: const_dec_interval!(0.0, 0.0),
        mid: 0.0,
    };

    pub fn new(interval: Interval) -> Known {
        Known {
            interval,
            decorated: <DecInterval as Scalar>::lift(interval),
            mid: <f64 as Scalar>::lift(interval),
        }
    }
}

/// `n` as an exact interval (every `u32` is a double).
fn exact_u32(n: u32) -> Interval {
    let x = f64::from(n);
    Interval::try_from((x, x)).expect("a u32 is an exact double")
}

/// inari's `pown` takes an `i32`; larger exponents are split as
/// `x^n = (x^(n/2))^2 · x^(n mod 2)`, still outward rounded.
fn pown_interval(x: Interval, n: u32) -> Interval {
    match i32::try_from(n) {
        Ok(k) => x.powi(k),
        Err(_) => pown_interval(x, n / 2).sqr() * x.powi((n % 2) as i32),
    }
}

fn pown_dec(x: DecInterval, n: u32) -> DecInterval {
    match i32::try_from(n) {
        Ok(k) => x.powi(k),
        Err(_) => pown_dec(x, n / 2).sqr() * x.powi((n % 2) as i32),
    }
}

/// [`Scalar::abs_slope`] of an interval: `[s, s]` for a fixed sign `s`,
/// `[-1, 1]` otherwise (empty stays empty).
fn interval_abs_slope(x: Interval) -> Interval {
    if x.is_empty() {
        x
    } else if x.inf() > 0.0 {
        const_interval!(1.0, 1.0)
    } else if x.sup() < 0.0 {
        const_interval!(-1.0, -1.0)
    } else {
        const_interval!(-1.0, 1.0)
    }
}

/// [`Scalar::sign_slope`] of an interval: `[0, 0]` for a fixed sign, the
/// whole line where it may be 0 (empty stays empty).
fn interval_sign_slope(x: Interval) -> Interval {
    if x.is_empty() {
        x
    } else if x.inf() > 0.0 || x.sup() < 0.0 {
        const_interval!(0.0, 0.0)
    } else {
        Interval::ENTIRE
    }
}

impl Scalar for f64 {
    fn lift(x: Interval) -> Self {
        x.mid()
    }
    fn lift_known(k: &Known) -> Self {
        k.mid
    }
    fn int(n: i32) -> Self {
        n as f64
    }
    fn sqr(self) -> Self {
        self * self
    }
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    fn sin(self) -> Self {
        f64::sin(self)
    }
    fn cos(self) -> Self {
        f64::cos(self)
    }
    fn ln(self) -> Self {
        f64::ln(self)
    }
    fn tan(self) -> Self {
        f64::tan(self)
    }
    fn abs(self) -> Self {
        f64::abs(self)
    }
    /// `signum`, with 0 at 0 (a subgradient; uncertified anyway).
    fn abs_slope(self) -> Self {
        if self == 0.0 {
            0.0
        } else {
            self.signum()
        }
    }
    fn pown(self, n: u32) -> Self {
        match i32::try_from(n) {
            Ok(k) => self.powi(k),
            Err(_) => self.powf(f64::from(n)),
        }
    }
    fn atan(self) -> Self {
        f64::atan(self)
    }
    fn exp(self) -> Self {
        f64::exp(self)
    }
    fn sign(self) -> Self {
        if self == 0.0 {
            0.0
        } else {
            self.signum()
        }
    }
    fn sign_slope(self) -> Self {
        0.0
    }
    fn min(self, other: Self) -> Self {
        f64::min(self, other)
    }
    fn max(self, other: Self) -> Self {
        f64::max(self, other)
    }
    fn sin_cos(self) -> (Self, Self) {
        f64::sin_cos(self)
    }
}

impl Scalar for Interval {
    fn lift(x: Interval) -> Self {
        x
    }
    fn lift_known(k: &Known) -> Self {
        k.interval
    }
    fn int(n: i32) -> Self {
        Interval::try_from((n as f64, n as f64)).expect("small integers are exact")
    }
    fn sqr(self) -> Self {
        Interval::sqr(self)
    }
    fn sqrt(self) -> Self {
        Interval::sqrt(self)
    }
    fn sin(self) -> Self {
        Interval::sin(self)
    }
    fn cos(self) -> Self {
        Interval::cos(self)
    }
    fn ln(self) -> Self {
        Interval::ln(self)
    }
    fn tan(self) -> Self {
        Interval::tan(self)
    }
    fn abs(self) -> Self {
        Interval::abs(self)
    }
    fn abs_slope(self) -> Self {
        interval_abs_slope(self)
    }
    fn pown(self, n: u32) -> Self {
        pown_interval(self, n)
    }
    fn atan(self) -> Self {
        Interval::atan(self)
    }
    fn exp(self) -> Self {
        Interval::exp(self)
    }
    fn sign(self) -> Self {
        Interval::sign(self)
    }
    fn sign_slope(self) -> Self {
        interval_sign_slope(self)
    }
    fn min(self, other: Self) -> Self {
        Interval::min(self, other)
    }
    fn max(self, other: Self) -> Self {
        Interval::max(self, other)
    }
}

impl Scalar for DecInterval {
    fn lift(x: Interval) -> Self {
        DecInterval::new(x)
    }
    fn lift_known(k: &Known) -> Self {
        k.decorated
    }
    fn int(n: i32) -> Self {
        DecInterval::new(<Interval as Scalar>::int(n))
    }
    fn sqr(self) -> Self {
        DecInterval::sqr(self)
    }
    fn sqrt(self) -> Self {
        DecInterval::sqrt(self)
    }
    fn sin(self) -> Self {
        DecInterval::sin(self)
    }
    fn cos(self) -> Self {
        DecInterval::cos(self)
    }
    fn ln(self) -> Self {
        DecInterval::ln(self)
    }
    fn tan(self) -> Self {
        DecInterval::tan(self)
    }
    fn abs(self) -> Self {
        DecInterval::abs(self)
    }
    fn abs_slope(self) -> Self {
        dec_abs_slope(self)
    }
    fn pown(self, n: u32) -> Self {
        pown_dec(self, n)
    }
    fn atan(self) -> Self {
        DecInterval::atan(self)
    }
    fn exp(self) -> Self {
        DecInterval::exp(self)
    }
    fn sign(self) -> Self {
        DecInterval::sign(self)
    }
    fn sign_slope(self) -> Self {
        match self.interval() {
            None => self,
            Some(i) => {
                let s = interval_sign_slope(i);
                let d = if s == Interval::ENTIRE || i.is_empty() {
                    Decoration::Trv
                } else {
                    self.decoration()
                };
                DecInterval::set_dec(s, d)
            }
        }
    }
    fn min(self, other: Self) -> Self {
        DecInterval::min(self, other)
    }
    fn max(self, other: Self) -> Self {
        DecInterval::max(self, other)
    }
}

/// [`Scalar::abs_slope`] decorated: a fixed sign keeps the argument's
/// decoration, a possible 0 gives `[-1, 1]` decorated `trv` (NaI stays NaI).
pub fn dec_abs_slope(x: DecInterval) -> DecInterval {
    match x.interval() {
        None => x,
        Some(i) => {
            let s = interval_abs_slope(i);
            let d = if i.is_empty() || (i.inf() <= 0.0 && i.sup() >= 0.0) {
                Decoration::Trv
            } else {
                x.decoration()
            };
            DecInterval::set_dec(s, d)
        }
    }
}

/// True when a decorated enclosure is a valid statement about every point of
/// its argument box: the formula is defined (and here also continuous) there.
pub fn is_defined(x: DecInterval) -> bool {
    x.decoration() >= Decoration::Def && x.interval().is_some_and(|i| !i.is_empty())
}

/// [`is_defined`] and also continuous on the whole argument (`≥ dac`): what a
/// derivative or a mean-value argument needs.
pub fn is_continuous(x: DecInterval) -> bool {
    x.decoration() >= Decoration::Dac && is_defined(x)
}

/// The weight `h = (1 − s)/2` of `u` in the derivative of `min(u, w)`, `s`
/// the slope of `abs(u − w)`: 1 where `u < w`, 0 where `u > w`.
fn min_weight<T: Scalar>(u: T, w: T) -> T {
    (T::int(1) - (u - w).abs_slope()) / T::int(2)
}

/// Forward-mode dual number: a value and its gradient with respect to the
/// first `N` of (θ, θ̇). `N = 2` (the default) carries both; `N = 1` carries
/// ∂/∂θ only, at about half the cost, for θ-slabs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DualN<T, const N: usize> {
    pub value: T,
    pub grad: [T; N],
}

/// The dual number over (θ, θ̇).
pub type Dual<T> = DualN<T, 2>;
/// The dual number over θ alone.
pub type DualTheta<T> = DualN<T, 1>;

impl<T: Scalar, const N: usize> DualN<T, N> {
    /// A constant (zero gradient).
    pub fn constant(value: T) -> Self {
        DualN {
            value,
            grad: [T::int(0); N],
        }
    }
    /// The independent variable number `index` (0 = θ, 1 = θ̇).
    pub fn variable(value: T, index: usize) -> Self {
        let mut grad = [T::int(0); N];
        grad[index] = T::int(1);
        DualN { value, grad }
    }
    fn chain(self, value: T, slope: T) -> Self {
        DualN {
            value,
            grad: self.grad.map(|g| g * slope),
        }
    }
    fn zip(self, r: Self, f: impl Fn(T, T) -> T) -> [T; N] {
        std::array::from_fn(|i| f(self.grad[i], r.grad[i]))
    }
}

impl<T: Scalar, const N: usize> Add for DualN<T, N> {
    type Output = Self;
    fn add(self, r: Self) -> Self {
        DualN {
            value: self.value + r.value,
            grad: self.zip(r, |a, b| a + b),
        }
    }
}

impl<T: Scalar, const N: usize> Sub for DualN<T, N> {
    type Output = Self;
    fn sub(self, r: Self) -> Self {
        DualN {
            value: self.value - r.value,
            grad: self.zip(r, |a, b| a - b),
        }
    }
}

// The product and quotient rules mix operations, as they should.
#[allow(clippy::suspicious_arithmetic_impl)]
impl<T: Scalar, const N: usize> Mul for DualN<T, N> {
    type Output = Self;
    fn mul(self, r: Self) -> Self {
        DualN {
            value: self.value * r.value,
            grad: self.zip(r, |a, b| a * r.value + self.value * b),
        }
    }
}

#[allow(clippy::suspicious_arithmetic_impl)]
impl<T: Scalar, const N: usize> Div for DualN<T, N> {
    type Output = Self;
    fn div(self, r: Self) -> Self {
        let value = self.value / r.value;
        // (u/v)' = (u' − (u/v)·v') / v
        DualN {
            value,
            grad: self.zip(r, |a, b| (a - value * b) / r.value),
        }
    }
}

impl<T: Scalar, const N: usize> Neg for DualN<T, N> {
    type Output = Self;
    fn neg(self) -> Self {
        DualN {
            value: -self.value,
            grad: self.grad.map(|g| -g),
        }
    }
}

impl<T: Scalar, const N: usize> Scalar for DualN<T, N> {
    fn lift(x: Interval) -> Self {
        Self::constant(T::lift(x))
    }
    fn lift_known(k: &Known) -> Self {
        DualN {
            value: T::lift_known(k),
            grad: [T::lift_known(&Known::ZERO); N],
        }
    }
    fn int(n: i32) -> Self {
        Self::constant(T::int(n))
    }
    fn sqr(self) -> Self {
        self.chain(self.value.sqr(), T::int(2) * self.value)
    }
    fn sqrt(self) -> Self {
        let r = self.value.sqrt();
        self.chain(r, T::int(1) / (T::int(2) * r))
    }
    fn sin(self) -> Self {
        self.sin_cos().0
    }
    fn cos(self) -> Self {
        self.sin_cos().1
    }
    fn ln(self) -> Self {
        self.chain(self.value.ln(), T::int(1) / self.value)
    }
    fn tan(self) -> Self {
        let t = self.value.tan();
        self.chain(t, T::int(1) + t.sqr())
    }
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = self.value.sin_cos();
        (self.chain(s, c), self.chain(c, -s))
    }
    /// Chain rule with [`Scalar::abs_slope`]: where the value may be 0 the
    /// gradient is `g·[-1, 1]` (the hull of ±g), decorated `trv` over
    /// decorated intervals, so it is never taken for a derivative.
    fn abs(self) -> Self {
        self.chain(self.value.abs(), self.value.abs_slope())
    }
    /// The slope of `abs` is piecewise constant: gradient `slope·0`, which
    /// is 0 and inherits `trv` where the slope is undefined.
    fn abs_slope(self) -> Self {
        let s = self.value.abs_slope();
        DualN {
            value: s,
            grad: [s * T::int(0); N],
        }
    }
    fn atan(self) -> Self {
        self.chain(
            self.value.atan(),
            T::int(1) / (T::int(1) + self.value.sqr()),
        )
    }
    fn exp(self) -> Self {
        let e = self.value.exp();
        self.chain(e, e)
    }
    /// Chain rule with [`Scalar::sign_slope`]: 0 where the sign is fixed,
    /// the whole line (`trv`) where it may jump.
    fn sign(self) -> Self {
        self.chain(self.value.sign(), self.value.sign_slope())
    }
    fn sign_slope(self) -> Self {
        let s = self.value.sign_slope();
        DualN {
            value: s,
            grad: [s * T::int(0); N],
        }
    }
    /// `u'·h + w'·(1 − h)` with `h = (1 − s)/2`, `s` the slope of
    /// `abs(u − w)`: `u'` where `u < w`, `w'` where `u > w` (exactly), and
    /// where they may meet every combination of the two (`trv`).
    fn min(self, other: Self) -> Self {
        let h = min_weight(self.value, other.value);
        let k = T::int(1) - h;
        DualN {
            value: self.value.min(other.value),
            grad: self.zip(other, |a, b| a * h + b * k),
        }
    }
    /// As `min`, the weights swapped.
    fn max(self, other: Self) -> Self {
        let h = min_weight(self.value, other.value);
        let k = T::int(1) - h;
        DualN {
            value: self.value.max(other.value),
            grad: self.zip(other, |a, b| a * k + b * h),
        }
    }
    /// Chain rule with slope `n·x^(n−1)` (`x^(n−1)` by `sqr` when n − 1 = 2,
    /// as the checker's duals do); `x^0` keeps the value's decoration and
    /// has gradient 0.
    fn pown(self, n: u32) -> Self {
        if n == 0 {
            return DualN {
                value: self.value.pown(0),
                grad: [T::int(0); N],
            };
        }
        let lower = if n == 3 {
            self.value.sqr()
        } else {
            self.value.pown(n - 1)
        };
        let value = if n == 2 {
            self.value.sqr()
        } else {
            self.value.pown(n)
        };
        self.chain(value, T::lift(exact_u32(n)) * lower)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dual_derivatives_match_closed_forms() {
        // d/dx [x² sin x / ln x] at x = 2, closed form by hand.
        let x = Dual::<f64>::variable(2.0, 0);
        let f = x.sqr() * x.sin() / x.ln();
        let (s, c, l) = (2f64.sin(), 2f64.cos(), 2f64.ln());
        let expect = (2.0 * 2.0 * s + 4.0 * c) / l - 4.0 * s / (2.0 * l * l);
        assert!((f.grad[0] - expect).abs() < 1e-12);
        assert_eq!(f.grad[1], 0.0);
        // d/dx tan x = 1/cos²x.
        let t = Dual::<f64>::variable(0.7, 0).tan();
        assert!((t.grad[0] - 1.0 / 0.7f64.cos().powi(2)).abs() < 1e-12);
    }

    #[test]
    fn powers_and_abs() {
        let x = Interval::try_from((-2.0, 3.0)).unwrap();
        // Tightest: x³ = [-8, 27], not x·x·x = [-18, 27].
        assert_eq!(
            <Interval as Scalar>::pown(x, 3),
            Interval::try_from((-8.0, 27.0)).unwrap()
        );
        assert_eq!(
            <Interval as Scalar>::pown(x, 0),
            Interval::try_from((1.0, 1.0)).unwrap()
        );
        assert_eq!(2f64.pown(10), 1024.0);
        // Duals: d/dx x⁴ = 4x³ at x = 1.5.
        let d = Dual::<f64>::variable(1.5, 0).pown(4);
        assert_eq!((d.value, d.grad[0]), (5.0625, 13.5));
        let a = Dual::<f64>::variable(-1.5, 1).abs();
        assert_eq!((a.value, a.grad[1]), (1.5, -1.0));
        let z = DecInterval::new(x);
        assert_eq!(z.abs_slope().decoration(), Decoration::Trv);
        assert_eq!(
            <DecInterval as Scalar>::abs(z).decoration(),
            Decoration::Com
        );
    }

    #[test]
    fn decorated_division_by_zero_is_not_defined() {
        let x = DecInterval::new(Interval::try_from((-1.0, 1.0)).unwrap());
        assert!(!is_defined(<DecInterval as Scalar>::int(1) / x));
        let y = DecInterval::new(Interval::try_from((1.0, 2.0)).unwrap());
        assert!(is_defined(<DecInterval as Scalar>::int(1) / y));
    }

    /// A constant lifted once ([`Known`]) is, for every scalar, bit for bit
    /// what lifting its enclosure gives (the tape copies these lifts).
    #[test]
    fn known_constants_lift_as_their_enclosures() {
        use crate::number::elementary::CrDec;
        let bits = |x: Interval| (x.inf().to_bits(), x.sup().to_bits());
        let dec = |x: DecInterval| (x.interval().map(bits), x.decoration());
        let cases = [
            (0.1f64.next_down(), 0.1),
            (1.0, 2.0),
            (-3.0, -3.0),
            (0.0, 0.0),
            (-0.25, 1e300),
            (-f64::MAX, f64::MAX),
        ];
        for (lo, hi) in cases {
            let x = Interval::try_from((lo, hi)).unwrap();
            let k = Known::new(x);
            assert_eq!(f64::lift_known(&k).to_bits(), f64::lift(x).to_bits());
            assert_eq!(bits(Interval::lift_known(&k)), bits(x));
            let d = DecInterval::lift_known(&k);
            assert_eq!(dec(d), dec(DecInterval::lift(x)), "{x:?}");
            assert_eq!(dec(CrDec::lift_known(&k).0), dec(CrDec::lift(x).0));
            let (a, b) = (
                DualTheta::<CrDec>::lift_known(&k),
                DualTheta::<CrDec>::lift(x),
            );
            assert_eq!(dec(a.value.0), dec(b.value.0));
            assert_eq!(dec(a.grad[0].0), dec(b.grad[0].0));
            let (a, b) = (Dual::<f64>::lift_known(&k), Dual::<f64>::lift(x));
            assert_eq!(a.value.to_bits(), b.value.to_bits());
            assert_eq!(a.grad.map(f64::to_bits), b.grad.map(f64::to_bits));
            let (a, b) = (Dual::<Interval>::lift_known(&k), Dual::<Interval>::lift(x));
            assert_eq!(a.grad.map(bits), b.grad.map(bits));
        }
        // The gradient's 0 is `int(0)` of each scalar.
        let zero = Known::ZERO;
        assert_eq!(f64::lift_known(&zero).to_bits(), 0f64.to_bits());
        assert_eq!(bits(Interval::lift_known(&zero)), bits(Interval::int(0)));
        let int0 = <DecInterval as Scalar>::int(0);
        assert_eq!(dec(DecInterval::lift_known(&zero)), dec(int0));
    }
}
