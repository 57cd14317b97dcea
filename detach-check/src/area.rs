//! Exact sums of leaf areas.
//!
//! FORMAT.md certifies "the sum, rounded down (up), of the exact areas of the
//! leaves". A leaf's area `(t_hi − t_lo)·(w_hi − w_lo)` is a dyadic rational,
//! written exactly as at most eight doubles with error-free transformations
//! (TwoSum, then TwoProduct by fused multiply-add); these are added into a
//! fixed-point accumulator spanning the whole double range, so the sum is
//! exact and is rounded once at the end. A leaf whose terms would underflow
//! or overflow (never the case for boxes of ordinary size) is added as an
//! outward-rounded interval instead, which keeps the bound sound.

use inari::Interval;

/// Limbs of the accumulator: bit 0 is 2⁻¹⁰⁷⁴; 2304 bits hold any sum of up to
/// 2⁶⁴ doubles.
const LIMBS: usize = 36;

/// An exact sum of doubles plus an interval for inexactly added leaves.
#[derive(Clone, Debug)]
pub struct AreaSum {
    limbs: [u64; LIMBS],
    rest: Interval,
}

/// A leaf's area as an exact sum of doubles, or an enclosure when that is
/// not possible.
#[derive(Clone, Copy, Debug)]
pub enum LeafArea {
    Exact([f64; 8], usize),
    Enclosed(Interval),
}

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// Exact `a·b = p + q` when the product neither overflows nor is so small
/// that its error term underflows.
fn two_prod(a: f64, b: f64) -> Option<(f64, f64)> {
    if a == 0.0 || b == 0.0 {
        return Some((0.0, 0.0));
    }
    let p = a * b;
    // |a·b| ≥ 2⁻⁹⁶⁹ keeps the error term a normal-or-exact double.
    if !p.is_finite() || p.abs() < f64::from_bits((1023 - 969) << 52) {
        return None;
    }
    Some((p, a.mul_add(b, -p)))
}

fn iv(a: f64, b: f64) -> Interval {
    Interval::try_from((a, b)).unwrap_or(Interval::ENTIRE)
}

impl LeafArea {
    /// The area of `[t0, t1] × [w0, w1]` (with `t0 < t1`, `w0 < w1`, finite).
    pub fn of(t: (f64, f64), w: (f64, f64)) -> Self {
        let exact = || -> Option<([f64; 8], usize)> {
            let (s1, e1) = two_sum(t.1, -t.0);
            let (s2, e2) = two_sum(w.1, -w.0);
            if !s1.is_finite() || !s2.is_finite() {
                return None;
            }
            let mut out = [0.0; 8];
            let mut n = 0;
            for (a, b) in [(s1, s2), (s1, e2), (e1, s2), (e1, e2)] {
                let (p, q) = two_prod(a, b)?;
                for x in [p, q] {
                    if x != 0.0 {
                        out[n] = x;
                        n += 1;
                    }
                }
            }
            Some((out, n))
        };
        match exact() {
            Some((a, n)) => LeafArea::Exact(a, n),
            None => {
                LeafArea::Enclosed((iv(t.1, t.1) - iv(t.0, t.0)) * (iv(w.1, w.1) - iv(w.0, w.0)))
            }
        }
    }
}

impl Default for AreaSum {
    fn default() -> Self {
        AreaSum {
            limbs: [0; LIMBS],
            rest: iv(0.0, 0.0),
        }
    }
}

impl AreaSum {
    /// Adds a leaf's area.
    pub fn add(&mut self, a: &LeafArea) {
        match a {
            LeafArea::Exact(xs, n) => {
                for &x in xs.iter().take(*n) {
                    self.add_f64(x);
                }
            }
            LeafArea::Enclosed(i) => self.rest += *i,
        }
    }

    fn add_f64(&mut self, x: f64) {
        let bits = x.to_bits();
        let biased = (bits >> 52) & 0x7ff;
        let frac = bits & ((1u64 << 52) - 1);
        let (m, shift) = if biased == 0 {
            (frac, 0u64)
        } else {
            (frac | (1u64 << 52), biased - 1)
        };
        let limb = (shift / 64) as usize;
        let wide = u128::from(m) << (shift % 64);
        let parts = [wide as u64, (wide >> 64) as u64];
        let neg = bits >> 63 == 1;
        let mut carry = false;
        for (k, limb_ref) in self.limbs.iter_mut().enumerate().skip(limb) {
            let add = parts.get(k - limb).copied().unwrap_or(0);
            if k - limb >= 2 && !carry {
                break;
            }
            if neg {
                let (r1, b1) = limb_ref.overflowing_sub(add);
                let (r2, b2) = r1.overflowing_sub(u64::from(carry));
                *limb_ref = r2;
                carry = b1 || b2;
            } else {
                let (r1, c1) = limb_ref.overflowing_add(add);
                let (r2, c2) = r1.overflowing_add(u64::from(carry));
                *limb_ref = r2;
                carry = c1 || c2;
            }
        }
    }

    /// An interval `[RD(s), RU(s)]` around the exact part `s`, plus the
    /// enclosures of inexactly added leaves.
    pub fn bounds(&self) -> Interval {
        self.exact_bounds() + self.rest
    }

    fn exact_bounds(&self) -> Interval {
        // The exact part is a sum of positive areas, so it is never negative;
        // a set top bit would mean a bug, reported as the entire line.
        if self.limbs[LIMBS - 1] >> 63 == 1 {
            return Interval::ENTIRE;
        }
        let Some(top) = (0..LIMBS).rev().find(|&k| self.limbs[k] != 0) else {
            return iv(0.0, 0.0);
        };
        let h = top * 64 + 63 - self.limbs[top].leading_zeros() as usize; // highest set bit
        if h < 53 {
            // Fits in 53 bits: m·2⁻¹⁰⁷⁴ is an exact double.
            let m = self.limbs[0];
            let x = (m as f64) * f64::from_bits(1);
            return iv(x, x);
        }
        // Top 53 bits and whether anything below them is set.
        let lo_bit = h - 52;
        let mut m: u64 = 0;
        for b in (lo_bit..=h).rev() {
            m = (m << 1) | ((self.limbs[b / 64] >> (b % 64)) & 1);
        }
        let inexact = (0..lo_bit).any(|b| (self.limbs[b / 64] >> (b % 64)) & 1 == 1);
        // Value = m·2^(lo_bit − 1074), m in [2⁵², 2⁵³).
        let e = lo_bit as i64 - 1074;
        // 2^k for k in [-1022, 1023].
        let pow2 = |k: i64| f64::from_bits(((k + 1023).clamp(1, 2046) as u64) << 52);
        let scale = |m: u64| -> f64 {
            if e + 52 > 1023 {
                return f64::INFINITY;
            }
            // The value is ≥ 2⁻¹⁰²¹ (normal), so both steps are exact unless
            // the result overflows.
            if e < -1000 {
                (m as f64) * pow2(-1000) * pow2(e + 1000)
            } else {
                (m as f64) * pow2(e)
            }
        };
        let down = scale(m);
        let up = if inexact { scale(m + 1) } else { down };
        let down = if down.is_infinite() { f64::MAX } else { down };
        iv(down, up)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_where_floating_sums_are_not() {
        let mut s = AreaSum::default();
        // 1 + 2⁻¹⁰⁰ + 2⁻¹⁰⁰ − … kept exactly: areas 1·1 and tiny ones.
        s.add(&LeafArea::of((0.0, 1.0), (0.0, 1.0)));
        for _ in 0..4 {
            s.add(&LeafArea::of((0.0, 2f64.powi(-50)), (0.0, 2f64.powi(-50))));
        }
        let b = s.bounds();
        assert_eq!(b.inf(), 1.0);
        assert_eq!(b.sup(), 1.0 + f64::EPSILON);
        let mut s = AreaSum::default();
        s.add(&LeafArea::of((0.1, 0.7), (-0.3, 0.2)));
        let b = s.bounds();
        assert!(b.inf() <= 0.3 && 0.3 <= b.sup() && b.sup() - b.inf() <= 2.0 * f64::EPSILON);
    }
}
