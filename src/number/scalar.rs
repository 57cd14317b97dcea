//! One scalar trait for every formula: `f64` (drawing, uncertified baselines),
//! [`Interval`] and [`DecInterval`] (certified enclosures, the decorated form
//! tracking where a formula may be undefined) and [`Dual`] (value plus the
//! gradient in (θ, θ̇), for mean-value forms, Newton steps and mechanics checks).
//!
//! Scene formulas are written once against [`Scalar`]; evaluating on a point, on
//! a box, or with derivatives is the same code.

use inari::{DecInterval, Decoration, Interval};
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
    /// A small integer, exact in every implementation.
    fn int(n: i32) -> Self;
    fn sqr(self) -> Self;
    fn sqrt(self) -> Self;
    fn sin(self) -> Self;
    fn cos(self) -> Self;
    fn ln(self) -> Self;
    fn tan(self) -> Self;
    /// `(sin, cos)` together; duals reuse both for the derivatives.
    fn sin_cos(self) -> (Self, Self) {
        (self.sin(), self.cos())
    }
}

impl Scalar for f64 {
    fn lift(x: Interval) -> Self {
        x.mid()
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
    fn sin_cos(self) -> (Self, Self) {
        f64::sin_cos(self)
    }
}

impl Scalar for Interval {
    fn lift(x: Interval) -> Self {
        x
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
}

impl Scalar for DecInterval {
    fn lift(x: Interval) -> Self {
        DecInterval::new(x)
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
    fn decorated_division_by_zero_is_not_defined() {
        let x = DecInterval::new(Interval::try_from((-1.0, 1.0)).unwrap());
        assert!(!is_defined(<DecInterval as Scalar>::int(1) / x));
        let y = DecInterval::new(Interval::try_from((1.0, 2.0)).unwrap());
        assert!(is_defined(<DecInterval as Scalar>::int(1) / y));
    }
}
