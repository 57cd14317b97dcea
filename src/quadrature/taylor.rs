//! Truncated Taylor series in one variable with interval coefficients.
//!
//! `Taylor { c }` stands for `Σ c[k] t^k`. Seeded with θ = `[x, 1, 0, …]`, a
//! scene formula evaluated in this arithmetic gives enclosures of
//! `f^(k)(ξ)/k!` for every `ξ ∈ x`: at a point `x` the Taylor coefficients,
//! over an interval `x` the bound a Lagrange remainder needs. The recurrences
//! are the classical ones of automatic differentiation (Moore; Griewank).
//!
//! The arithmetic is only valid where the formula is analytic on `x`; callers
//! check that first (a `com` decorated evaluation on `x`) and reject any
//! result that is not a bounded, non-empty enclosure.

use crate::number::elementary;
use crate::number::scalar::Scalar;
use inari::{const_interval, Interval};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Number of coefficients: the series are exact up to `t^(N−1)`.
pub const N: usize = 11;

const ZERO: Interval = const_interval!(0.0, 0.0);
const ONE: Interval = const_interval!(1.0, 1.0);

fn int(n: usize) -> Interval {
    Interval::try_from((n as f64, n as f64)).expect("small integers are exact")
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Taylor {
    pub c: [Interval; N],
}

impl Taylor {
    pub fn constant(x: Interval) -> Self {
        let mut c = [ZERO; N];
        c[0] = x;
        Taylor { c }
    }

    /// The independent variable around `x`: `x + t`.
    pub fn variable(x: Interval) -> Self {
        let mut c = [ZERO; N];
        c[0] = x;
        c[1] = ONE;
        Taylor { c }
    }

    /// Every coefficient is a bounded, non-empty interval.
    pub fn is_finite(&self) -> bool {
        self.c.iter().all(|x| x.is_common_interval())
    }

    /// (a_k) ↦ (a_k·k): the coefficients of `t·f'(t)`.
    fn scaled_derivative(&self) -> [Interval; N] {
        let mut d = [ZERO; N];
        for (k, dk) in d.iter_mut().enumerate().skip(1) {
            *dk = self.c[k] * int(k);
        }
        d
    }
}

impl Add for Taylor {
    type Output = Taylor;
    fn add(mut self, r: Taylor) -> Taylor {
        for (a, b) in self.c.iter_mut().zip(r.c) {
            *a += b;
        }
        self
    }
}

impl Sub for Taylor {
    type Output = Taylor;
    fn sub(mut self, r: Taylor) -> Taylor {
        for (a, b) in self.c.iter_mut().zip(r.c) {
            *a -= b;
        }
        self
    }
}

impl Neg for Taylor {
    type Output = Taylor;
    fn neg(mut self) -> Taylor {
        for a in self.c.iter_mut() {
            *a = -*a;
        }
        self
    }
}

/// Is the series a constant (all higher coefficients exactly zero)?
fn is_const(x: &Taylor) -> bool {
    x.c[1..].iter().all(|c| *c == ZERO)
}

impl Mul for Taylor {
    type Output = Taylor;
    fn mul(self, r: Taylor) -> Taylor {
        // Constants are common (parameters): a scaling is N products, not N²/2.
        if is_const(&r) {
            let mut out = self;
            for a in out.c.iter_mut() {
                *a *= r.c[0];
            }
            return out;
        }
        if is_const(&self) {
            return r * self;
        }
        let mut c = [ZERO; N];
        for (k, ck) in c.iter_mut().enumerate() {
            let mut s = ZERO;
            for j in 0..=k {
                s += self.c[j] * r.c[k - j];
            }
            *ck = s;
        }
        Taylor { c }
    }
}

impl Div for Taylor {
    type Output = Taylor;
    fn div(self, r: Taylor) -> Taylor {
        if is_const(&r) {
            let mut out = self;
            for a in out.c.iter_mut() {
                *a /= r.c[0];
            }
            return out;
        }
        // q·r = a: q_k = (a_k − Σ_{j≥1} r_j q_{k−j}) / r_0
        let mut q = [ZERO; N];
        for k in 0..N {
            let mut s = self.c[k];
            for j in 1..=k {
                s -= r.c[j] * q[k - j];
            }
            q[k] = s / r.c[0];
        }
        Taylor { c: q }
    }
}

impl Scalar for Taylor {
    fn lift(x: Interval) -> Self {
        Taylor::constant(x)
    }
    fn int(n: i32) -> Self {
        Taylor::constant(<Interval as Scalar>::int(n))
    }
    fn sqr(self) -> Self {
        if is_const(&self) {
            return Taylor::constant(self.c[0].sqr());
        }
        let mut c = [ZERO; N];
        for (k, ck) in c.iter_mut().enumerate() {
            let mut s = ZERO;
            for j in 0..k.div_ceil(2) {
                s += self.c[j] * self.c[k - j];
            }
            s = s + s;
            if k % 2 == 0 {
                s += self.c[k / 2].sqr();
            }
            *ck = s;
        }
        Taylor { c }
    }
    fn sqrt(self) -> Self {
        // s² = a: s_k = (a_k − Σ_{1≤j<k} s_j s_{k−j}) / (2 s_0)
        let mut s = [ZERO; N];
        s[0] = self.c[0].sqrt();
        let two_s0 = s[0] + s[0];
        for k in 1..N {
            let mut acc = self.c[k];
            for j in 1..k {
                acc -= s[j] * s[k - j];
            }
            s[k] = acc / two_s0;
        }
        Taylor { c: s }
    }
    fn sin(self) -> Self {
        self.sin_cos().0
    }
    fn cos(self) -> Self {
        self.sin_cos().1
    }
    fn sin_cos(self) -> (Self, Self) {
        // k s_k = Σ_{j=1..k} j u_j c_{k−j},  k c_k = −Σ j u_j s_{k−j}
        let (mut s, mut c) = ([ZERO; N], [ZERO; N]);
        (s[0], c[0]) = elementary::sin_cos(self.c[0]);
        let du = self.scaled_derivative();
        for k in 1..N {
            let (mut a, mut b) = (ZERO, ZERO);
            for j in 1..=k {
                a += du[j] * c[k - j];
                b += du[j] * s[k - j];
            }
            s[k] = a / int(k);
            c[k] = -(b / int(k));
        }
        (Taylor { c: s }, Taylor { c })
    }
    fn ln(self) -> Self {
        // u·l' = u': k l_k u_0 = k u_k − Σ_{j=1}^{k−1} j l_j u_{k−j}
        let mut l = [ZERO; N];
        l[0] = elementary::ln(self.c[0]);
        for k in 1..N {
            let mut acc = self.c[k] * int(k);
            for (j, lj) in l.iter().enumerate().take(k).skip(1) {
                acc -= *lj * int(j) * self.c[k - j];
            }
            l[k] = acc / (self.c[0] * int(k));
        }
        Taylor { c: l }
    }
    fn tan(self) -> Self {
        // t' = (1 + t²) u': k t_k = Σ_{j=1..k} j u_j w_{k−j}, w = 1 + t²
        let (mut t, mut w) = ([ZERO; N], [ZERO; N]);
        t[0] = elementary::tan(self.c[0]);
        w[0] = ONE + t[0].sqr();
        let du = self.scaled_derivative();
        for k in 1..N {
            let mut a = ZERO;
            for j in 1..=k {
                a += du[j] * w[k - j];
            }
            t[k] = a / int(k);
            let mut sq = ZERO;
            for j in 0..=k {
                sq += t[j] * t[k - j];
            }
            w[k] = sq;
        }
        Taylor { c: t }
    }
    /// `±u` where the sign of `u_0` is fixed; otherwise `abs` is not
    /// analytic on the argument and every higher coefficient is unbounded.
    fn abs(self) -> Self {
        let x = self.c[0];
        if x.inf() > 0.0 {
            self
        } else if x.sup() < 0.0 {
            -self
        } else {
            let mut c = [Interval::ENTIRE; N];
            c[0] = x.abs();
            Taylor { c }
        }
    }
    fn abs_slope(self) -> Self {
        Taylor::constant(<Interval as Scalar>::abs_slope(self.c[0]))
    }
    fn exp(self) -> Self {
        // e' = e·u': k e_k = Σ_{j=1..k} j u_j e_{k−j}
        let mut e = [ZERO; N];
        e[0] = self.c[0].exp();
        let du = self.scaled_derivative();
        for k in 1..N {
            let mut a = ZERO;
            for j in 1..=k {
                a += du[j] * e[k - j];
            }
            e[k] = a / int(k);
        }
        Taylor { c: e }
    }
    fn atan(self) -> Self {
        // w·a' = u', w = 1 + u²: k a_k w_0 = k u_k − Σ_{j=1}^{k−1} j a_j w_{k−j}
        let w = Taylor::int(1) + self.sqr();
        let mut a = [ZERO; N];
        a[0] = self.c[0].atan();
        for k in 1..N {
            let mut acc = self.c[k] * int(k);
            for (j, aj) in a.iter().enumerate().take(k).skip(1) {
                acc -= *aj * int(j) * w.c[k - j];
            }
            a[k] = acc / (w.c[0] * int(k));
        }
        Taylor { c: a }
    }
    /// A constant where the sign of `u_0` is fixed; otherwise `sign` jumps
    /// on the argument and every higher coefficient is unbounded.
    fn sign(self) -> Self {
        let x = self.c[0];
        if x.inf() > 0.0 || x.sup() < 0.0 {
            Taylor::constant(x.sign())
        } else {
            let mut c = [Interval::ENTIRE; N];
            c[0] = x.sign();
            Taylor { c }
        }
    }
    fn sign_slope(self) -> Self {
        Taylor::constant(<Interval as Scalar>::sign_slope(self.c[0]))
    }
    /// The smaller series where the two are apart on the argument; otherwise
    /// `min` may have a kink there and every higher coefficient is unbounded.
    fn min(self, other: Self) -> Self {
        let (a, b) = (self.c[0], other.c[0]);
        if a.sup() < b.inf() {
            self
        } else if b.sup() < a.inf() {
            other
        } else {
            let mut c = [Interval::ENTIRE; N];
            c[0] = a.min(b);
            Taylor { c }
        }
    }
    fn max(self, other: Self) -> Self {
        -((-self).min(-other))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pt(x: f64) -> Interval {
        Interval::try_from((x, x)).unwrap()
    }

    /// Coefficients of known series at a point, against closed forms.
    #[test]
    fn series_of_known_functions() {
        let x = Taylor::variable(pt(0.5));
        let close = |a: Interval, b: f64| (a.mid() - b).abs() <= 1e-12 * (1.0 + b.abs());
        // 1/(1 − t) around 0.5 in t: 1/(0.5 − t) = 2 Σ (2t)^k
        let inv = Taylor::int(1) / (Taylor::int(1) - x);
        for k in 0..N {
            assert!(close(inv.c[k], 2f64.powi(k as i32 + 1)), "{k}");
        }
        // sin: c_k = sin(0.5 + kπ/2)/k!
        let (s, c) = x.sin_cos();
        let mut fact = 1.0;
        for k in 0..N {
            if k > 0 {
                fact *= k as f64;
            }
            let phase = 0.5 + k as f64 * std::f64::consts::FRAC_PI_2;
            assert!(close(s.c[k], phase.sin() / fact), "sin {k}");
            assert!(close(c.c[k], phase.cos() / fact), "cos {k}");
        }
        // ln(0.5 + t): c_k = (−1)^{k+1} 2^k / k
        let l = x.ln();
        for k in 1..N {
            let e = (-1f64).powi(k as i32 + 1) * 2f64.powi(k as i32) / k as f64;
            assert!(close(l.c[k], e), "ln {k}");
        }
        // exp(0.5 + t): e^0.5/k!; atan(0.5 + t): atan(0.5), then 1/(1 + x²) =
        // 0.8 and −x/(1 + x²)² = −0.32 (by hand, x = 0.5).
        let e = x.exp();
        let mut fact = 1.0;
        for k in 0..N {
            if k > 0 {
                fact *= k as f64;
            }
            assert!(close(e.c[k], 0.5f64.exp() / fact), "exp {k}");
        }
        let a = x.atan();
        assert!(close(a.c[0], 0.5f64.atan()) && close(a.c[1], 0.8) && close(a.c[2], -0.32));
        // tan(atan(u)) = u.
        let r = x.atan().tan() - x;
        assert!(r.c.iter().all(|c| c.mag() < 1e-9));
        // sqrt and sqr are inverse; tan = sin/cos.
        let r = x.sqrt().sqr() - x;
        assert!(r.c.iter().all(|c| c.mag() < 1e-13));
        let d = x.tan() - s / c;
        assert!(d.c.iter().all(|c| c.mag() < 1e-9));
    }
}
