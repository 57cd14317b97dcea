//! Rigorous interval `sin`, `cos`, `tan` and `ln` from correctly rounded point
//! values (CORE-MATH, through the `core-math` crate).
//!
//! CORE-MATH's results are proved correctly rounded, so the true value lies
//! within half an ulp of the returned double: one ulp down and one ulp up from
//! it is an enclosure, whatever the rounding direction. That is a few times
//! cheaper than MPFR's directed-rounding calls inside `inari`.
//!
//! Over an interval argument the extrema (of `sin`, `cos`) and poles (of `tan`)
//! inside it are found with interval arithmetic on an enclosure of π
//! ([`Interval::PI`], never a double): every kπ/2 point the interval *may*
//! contain is accounted for. When unsure — unbounded or huge arguments, a
//! possible pole of `tan`, an argument of `ln` reaching 0 — the functions fall
//! back to `inari`'s own.

use crate::number::scalar::{Known, Scalar};
use inari::{const_interval, DecInterval, Interval};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Above this magnitude the argument reduction by an enclosure of π gets too
/// loose to be useful: use `inari` (MPFR's exact reduction) instead.
const MAX_ARG: f64 = 1048576.0; // 2^20

fn next_up(x: f64) -> f64 {
    if x.is_nan() || x == f64::INFINITY {
        return x;
    }
    if x == 0.0 {
        return f64::from_bits(1);
    }
    let b = x.to_bits();
    f64::from_bits(if x > 0.0 { b + 1 } else { b - 1 })
}

fn next_down(x: f64) -> f64 {
    -next_up(-x)
}

/// An enclosure of a point value known to within half an ulp.
fn widen(y: f64) -> (f64, f64) {
    (next_down(y), next_up(y))
}

fn hull(lo: f64, hi: f64) -> Interval {
    Interval::try_from((lo, hi)).expect("ordered finite bounds")
}

/// The integers `k` with `u.inf ≤ k ≤ u.sup`, as `(first, count)`, counting at
/// most 2 (2 means "two or more").
fn integers_in(u: Interval) -> (f64, u8) {
    let (lo, hi) = (u.inf().ceil(), u.sup().floor());
    if lo > hi {
        (lo, 0)
    } else if lo == hi {
        (lo, 1)
    } else {
        (lo, 2)
    }
}

fn is_even(k: f64) -> bool {
    k.rem_euclid(2.0) == 0.0
}

/// Finite, bounded and small enough for the reduction here.
fn in_range(x: Interval) -> bool {
    !x.is_empty() && x.inf() >= -MAX_ARG && x.sup() <= MAX_ARG
}

const MINUS_ONE_ONE: Interval = const_interval!(-1.0, 1.0);

/// Clips an enclosure of a sine or cosine to [−1, 1].
fn unit(lo: f64, hi: f64) -> Interval {
    hull(lo.max(-1.0), hi.min(1.0))
}

/// The range of sin or cos over `x = [a, b]` from the correctly rounded
/// values at the ends: the hull of their enclosures and of the extrema inside.
/// `extrema` maps `x` to the interval of indices k of the extrema it may hold
/// (a maximum for even k, a minimum for odd k).
fn range_from(x: Interval, va: f64, vb: f64, extrema: impl Fn(Interval) -> Interval) -> Interval {
    let (a, b) = (x.inf(), x.sup());
    let (la, ha) = widen(va);
    let (lb, hb) = if a == b { (la, ha) } else { widen(vb) };
    let (k, n) = if a == b {
        (0.0, 0)
    } else {
        integers_in(extrema(x))
    };
    let (mut lo, mut hi) = (la.min(lb), ha.max(hb));
    match n {
        0 => {}
        1 if is_even(k) => hi = 1.0,
        1 => lo = -1.0,
        _ => return MINUS_ONE_ONE,
    }
    unit(lo, hi)
}

/// sin over `x`: extrema at π/2 + kπ, k ∈ (x − π/2)/π.
fn sin_from(x: Interval, sa: f64, sb: f64) -> Interval {
    range_from(x, sa, sb, |x| {
        (x - Interval::FRAC_PI_2) * Interval::FRAC_1_PI
    })
}

/// cos over `x`: extrema at kπ, k ∈ x/π.
fn cos_from(x: Interval, ca: f64, cb: f64) -> Interval {
    range_from(x, ca, cb, |x| x * Interval::FRAC_1_PI)
}

/// Enclosure of sin over `x`.
pub fn sin(x: Interval) -> Interval {
    if !in_range(x) {
        return x.sin();
    }
    if x.inf() == 0.0 && x.sup() == 0.0 {
        return x;
    }
    let (a, b) = (x.inf(), x.sup());
    sin_from(x, core_math::sin(a), core_math::sin(b))
}

/// Enclosure of cos over `x`.
pub fn cos(x: Interval) -> Interval {
    if !in_range(x) {
        return x.cos();
    }
    let (a, b) = (x.inf(), x.sup());
    if a == 0.0 && b == 0.0 {
        return const_interval!(1.0, 1.0);
    }
    cos_from(x, core_math::cos(a), core_math::cos(b))
}

/// Enclosures of sin and cos over `x`, sharing the endpoint evaluations.
pub fn sin_cos(x: Interval) -> (Interval, Interval) {
    if !in_range(x) || (x.inf() == 0.0 && x.sup() == 0.0) {
        return (sin(x), cos(x));
    }
    let (a, b) = (x.inf(), x.sup());
    let (sa, ca) = core_math::sincos(a);
    let (sb, cb) = if a == b {
        (sa, ca)
    } else {
        core_math::sincos(b)
    };
    (sin_from(x, sa, sb), cos_from(x, ca, cb))
}

/// Enclosure of tan over `x`; `inari`'s whenever a pole π/2 + kπ may lie in
/// `x` (it then decides the decoration).
pub fn tan(x: Interval) -> Interval {
    tan_checked(x).unwrap_or_else(|| x.tan())
}

/// `Some` when `x` provably avoids every pole.
fn tan_checked(x: Interval) -> Option<Interval> {
    if !in_range(x) {
        return None;
    }
    let (a, b) = (x.inf(), x.sup());
    if a == 0.0 && b == 0.0 {
        return Some(x);
    }
    if integers_in((x - Interval::FRAC_PI_2) * Interval::FRAC_1_PI).1 != 0 {
        return None;
    }
    let (lo, _) = widen(core_math::tan(a));
    let (_, hi) = widen(core_math::tan(b));
    Some(hull(lo, hi))
}

/// Enclosure of ln over `x`; `inari`'s when `x` reaches 0 or infinity.
pub fn ln(x: Interval) -> Interval {
    ln_checked(x).unwrap_or_else(|| x.ln())
}

fn ln_checked(x: Interval) -> Option<Interval> {
    if x.is_empty() || x.inf() <= 0.0 || x.sup() == f64::INFINITY {
        return None;
    }
    let (a, b) = (x.inf(), x.sup());
    let exact = |v: f64| (v == 1.0).then_some(0.0);
    let lo = exact(a).unwrap_or_else(|| widen(core_math::log(a)).0);
    let hi = exact(b).unwrap_or_else(|| widen(core_math::log(b)).1);
    Some(hull(lo, hi))
}

/// Applies an everywhere-defined, continuous function to a decorated
/// interval: the decoration carries over (`com` stays `com` while bounded).
fn dec_total(x: DecInterval, f: impl Fn(Interval) -> Interval) -> DecInterval {
    match x.interval() {
        None => x,
        Some(i) if i.is_empty() => x,
        Some(i) => DecInterval::set_dec(f(i), x.decoration()),
    }
}

/// Decorated sin, as `inari`'s `DecInterval::sin` decorates it.
pub fn dec_sin(x: DecInterval) -> DecInterval {
    dec_total(x, sin)
}

/// Decorated cos.
pub fn dec_cos(x: DecInterval) -> DecInterval {
    dec_total(x, cos)
}

/// Decorated tan: defined and continuous on `x` when `x` avoids every pole;
/// otherwise `inari` decides.
pub fn dec_tan(x: DecInterval) -> DecInterval {
    match x.interval().and_then(tan_checked) {
        Some(r) => DecInterval::set_dec(r, x.decoration()),
        None => x.tan(),
    }
}

/// Decorated ln: defined and continuous where `x > 0`; otherwise `inari`
/// decides (`trv` or empty).
pub fn dec_ln(x: DecInterval) -> DecInterval {
    match x.interval().and_then(ln_checked) {
        Some(r) => DecInterval::set_dec(r, x.decoration()),
        None => x.ln(),
    }
}

/// A decorated interval whose elementary functions are the ones of this
/// module; arithmetic is `inari`'s. Scene formulas evaluated with it give the
/// same kind of enclosure as with [`DecInterval`], a few ulps wider at most.
#[derive(Clone, Copy, Debug)]
pub struct CrDec(pub DecInterval);

/// An operator on the wrapped intervals, for [`CrDec`] and [`Cr`].
macro_rules! binop {
    ($t:ident, $tr:ident, $f:ident) => {
        impl $tr for $t {
            type Output = $t;
            fn $f(self, r: $t) -> $t {
                $t(self.0.$f(r.0))
            }
        }
    };
}
binop!(CrDec, Add, add);
binop!(CrDec, Sub, sub);
binop!(CrDec, Mul, mul);
binop!(CrDec, Div, div);

impl Neg for CrDec {
    type Output = CrDec;
    fn neg(self) -> CrDec {
        CrDec(-self.0)
    }
}

impl Scalar for CrDec {
    fn lift(x: Interval) -> Self {
        CrDec(DecInterval::new(x))
    }
    fn lift_known(k: &Known) -> Self {
        CrDec(k.decorated)
    }
    fn int(n: i32) -> Self {
        CrDec(<DecInterval as Scalar>::int(n))
    }
    fn sqr(self) -> Self {
        CrDec(self.0.sqr())
    }
    fn sqrt(self) -> Self {
        CrDec(self.0.sqrt())
    }
    fn sin(self) -> Self {
        CrDec(dec_sin(self.0))
    }
    fn cos(self) -> Self {
        CrDec(dec_cos(self.0))
    }
    fn ln(self) -> Self {
        CrDec(dec_ln(self.0))
    }
    fn tan(self) -> Self {
        CrDec(dec_tan(self.0))
    }
    // No CORE-MATH kernel is involved: `inari`'s, as for DecInterval.
    fn abs(self) -> Self {
        CrDec(<DecInterval as Scalar>::abs(self.0))
    }
    fn abs_slope(self) -> Self {
        CrDec(self.0.abs_slope())
    }
    fn pown(self, n: u32) -> Self {
        CrDec(<DecInterval as Scalar>::pown(self.0, n))
    }
    fn atan(self) -> Self {
        CrDec(self.0.atan())
    }
    fn exp(self) -> Self {
        CrDec(self.0.exp())
    }
    fn sign(self) -> Self {
        CrDec(self.0.sign())
    }
    fn sign_slope(self) -> Self {
        CrDec(<DecInterval as Scalar>::sign_slope(self.0))
    }
    fn min(self, other: Self) -> Self {
        CrDec(self.0.min(other.0))
    }
    fn max(self, other: Self) -> Self {
        CrDec(self.0.max(other.0))
    }
    fn sin_cos(self) -> (Self, Self) {
        match self.0.interval() {
            Some(i) if !i.is_empty() => {
                let (s, c) = sin_cos(i);
                let d = self.0.decoration();
                (
                    CrDec(DecInterval::set_dec(s, d)),
                    CrDec(DecInterval::set_dec(c, d)),
                )
            }
            _ => (self.sin(), self.cos()),
        }
    }
}

/// An undecorated interval whose elementary functions are the ones of this
/// module, for evaluating formulas without the cost of decorations. An
/// operation outside the part of its domain where it is continuous (a
/// division by an interval holding 0, `sqrt` below 0, `ln` at or below
/// 0, `tan` near a pole, `sign` at 0, and the slopes of `abs` and `sign`
/// at 0) gives the empty interval, which every later operation keeps: a
/// result that is not empty comes from operations each continuous on its
/// argument, so it is the enclosure [`CrDec`] gives, and its decoration
/// follows from it ([`Cr::decorated`]); an empty one asks for [`CrDec`].
#[derive(Clone, Copy, Debug)]
pub struct Cr(pub Interval);

impl Cr {
    /// The decoration a decorated evaluation gives a result that is not
    /// empty (every operation continuous on its argument, the box
    /// bounded): `com` where bounded, else `dac`. (Also `com` where an
    /// intermediate overflowed and a later operation, as `atan`, brought
    /// it back into range, where a decorated evaluation says `dac`: the
    /// formula is continuous either way.) `None` for an empty result.
    pub fn decorated(self) -> Option<DecInterval> {
        (!self.0.is_empty()).then(|| DecInterval::set_dec(self.0, inari::Decoration::Com))
    }

    /// `f(x)` where `continuous` holds, else empty.
    fn only_if(x: Interval, continuous: bool, f: impl Fn(Interval) -> Interval) -> Cr {
        Cr(if continuous { f(x) } else { Interval::EMPTY })
    }
}

binop!(Cr, Add, add);
binop!(Cr, Sub, sub);
binop!(Cr, Mul, mul);

/// Only where the divisor cannot be 0.
impl Div for Cr {
    type Output = Cr;
    fn div(self, r: Cr) -> Cr {
        Cr::only_if(self.0, !r.0.contains(0.0), |x| x / r.0)
    }
}

impl Neg for Cr {
    type Output = Cr;
    fn neg(self) -> Cr {
        Cr(-self.0)
    }
}

impl Scalar for Cr {
    fn lift(x: Interval) -> Self {
        Cr(x)
    }
    fn lift_known(k: &Known) -> Self {
        Cr(k.interval)
    }
    fn int(n: i32) -> Self {
        Cr(<Interval as Scalar>::int(n))
    }
    fn sqr(self) -> Self {
        Cr(self.0.sqr())
    }
    fn sqrt(self) -> Self {
        Cr::only_if(self.0, self.0.inf() >= 0.0, Interval::sqrt)
    }
    fn sin(self) -> Self {
        Cr(sin(self.0))
    }
    fn cos(self) -> Self {
        Cr(cos(self.0))
    }
    fn ln(self) -> Self {
        Cr(ln_checked(self.0).unwrap_or(Interval::EMPTY))
    }
    fn tan(self) -> Self {
        Cr(tan_checked(self.0).unwrap_or(Interval::EMPTY))
    }
    // No CORE-MATH kernel is involved: `inari`'s, as for CrDec.
    fn abs(self) -> Self {
        Cr(self.0.abs())
    }
    fn abs_slope(self) -> Self {
        let fixed = !self.0.contains(0.0);
        Cr::only_if(self.0, fixed, <Interval as Scalar>::abs_slope)
    }
    fn pown(self, n: u32) -> Self {
        Cr(<Interval as Scalar>::pown(self.0, n))
    }
    fn atan(self) -> Self {
        Cr(self.0.atan())
    }
    fn exp(self) -> Self {
        Cr(self.0.exp())
    }
    fn sign(self) -> Self {
        Cr::only_if(self.0, !self.0.contains(0.0), Interval::sign)
    }
    fn sign_slope(self) -> Self {
        let fixed = !self.0.contains(0.0);
        Cr::only_if(self.0, fixed, <Interval as Scalar>::sign_slope)
    }
    fn min(self, other: Self) -> Self {
        Cr(self.0.min(other.0))
    }
    fn max(self, other: Self) -> Self {
        Cr(self.0.max(other.0))
    }
    fn sin_cos(self) -> (Self, Self) {
        if self.0.is_empty() {
            return (self, self);
        }
        let (s, c) = sin_cos(self.0);
        (Cr(s), Cr(c))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(a: f64, b: f64) -> Interval {
        Interval::try_from((a, b)).unwrap()
    }

    #[test]
    fn ulp_steps() {
        assert_eq!(next_up(1.0), 1.0 + f64::EPSILON);
        assert_eq!(next_down(1.0), 1.0 - f64::EPSILON / 2.0);
        assert_eq!(next_up(-0.0), f64::from_bits(1));
        assert_eq!(next_down(0.0), -f64::from_bits(1));
    }

    #[test]
    fn extrema_inside_are_included() {
        assert_eq!(sin(iv(1.0, 2.0)).sup(), 1.0);
        assert_eq!(sin(iv(4.0, 5.0)).inf(), -1.0);
        assert_eq!(cos(iv(-0.5, 0.5)).sup(), 1.0);
        assert_eq!(cos(iv(3.0, 3.5)).inf(), -1.0);
        assert_eq!(sin(iv(0.0, 7.0)), MINUS_ONE_ONE);
    }

    #[test]
    fn fallbacks() {
        assert_eq!(tan(iv(1.0, 2.0)), iv(1.0, 2.0).tan());
        assert_eq!(ln(iv(0.0, 2.0)), iv(0.0, 2.0).ln());
        let big = iv(1e10, 1e10 + 1.0);
        assert_eq!(sin(big), big.sin());
        assert!(dec_ln(DecInterval::new(iv(-1.0, 2.0))).decoration() < inari::Decoration::Def);
    }
}
