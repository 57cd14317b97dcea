//! Exact sums of leaf areas.
//!
//! FORMAT.md certifies "the sum, rounded down (up), of the exact areas of the
//! leaves", the exact real sum rounded once. A leaf's area `(t_hi − t_lo)·(w_hi
//! − w_lo)` is `t_hi·w_hi − t_hi·w_lo − t_lo·w_hi + t_lo·w_lo`, four products
//! of doubles; each is an integer of at most 106 bits times a power of two no
//! smaller than 2⁻²¹⁴⁸, added exactly into a fixed-point accumulator that
//! spans every such product, so the sum is exact at any size (subnormal
//! leaves and leaves wider than the largest double included) and is rounded
//! once at the end.

use inari::Interval;

/// Bit 0 of the accumulator is 2⁻²¹⁴⁸ = (2⁻¹⁰⁷⁴)², the smallest product.
const BASE_EXP: i64 = -2148;
/// Products are below 2²⁰⁴⁸ and at most 2⁶⁶ of them are added, so the sum is
/// below 2²¹¹⁴: 4262 bits and a sign bit fit in 67 limbs.
const LIMBS: usize = 68;

/// An exact sum of leaf areas, in two's complement (terms may be negative;
/// the sum of areas is not).
#[derive(Clone, Debug)]
pub struct AreaSum {
    limbs: [u64; LIMBS],
}

/// A leaf box `[t0, t1] × [w0, w1]` (finite ends), whose area is summed.
#[derive(Clone, Copy, Debug)]
pub struct LeafArea {
    t: (f64, f64),
    w: (f64, f64),
}

/// `x = m·2^e` with `m` an integer of at most 53 bits and `e ≥ −1074`, and
/// the sign of `x`.
fn split(x: f64) -> (u64, i64, bool) {
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i64;
    let frac = bits & ((1u64 << 52) - 1);
    let neg = bits >> 63 == 1;
    if biased == 0 {
        (frac, -1074, neg)
    } else {
        (frac | (1u64 << 52), biased - 1075, neg)
    }
}

impl LeafArea {
    /// The area of `[t0, t1] × [w0, w1]` (with `t0 < t1`, `w0 < w1`, finite).
    pub fn of(t: (f64, f64), w: (f64, f64)) -> Self {
        LeafArea { t, w }
    }
}

impl Default for AreaSum {
    fn default() -> Self {
        AreaSum { limbs: [0; LIMBS] }
    }
}

impl AreaSum {
    /// Adds a leaf's area exactly.
    pub fn add(&mut self, a: &LeafArea) {
        let (t, w) = (a.t, a.w);
        for (x, y, minus) in [
            (t.1, w.1, false),
            (t.1, w.0, true),
            (t.0, w.1, true),
            (t.0, w.0, false),
        ] {
            self.add_product(x, y, minus);
        }
    }

    /// Adds (or subtracts, if `minus`) the exact product `x·y`.
    fn add_product(&mut self, x: f64, y: f64, minus: bool) {
        let (mx, ex, nx) = split(x);
        let (my, ey, ny) = split(y);
        let m = u128::from(mx) * u128::from(my);
        if m == 0 {
            return;
        }
        // e ≥ −2148, so the bit position is never negative.
        let bit = (ex + ey - BASE_EXP) as usize;
        let (limb, s) = (bit / 64, bit % 64);
        let (lo, hi) = (m as u64, (m >> 64) as u64);
        let parts = if s == 0 {
            [lo, hi, 0]
        } else {
            [lo << s, (hi << s) | (lo >> (64 - s)), hi >> (64 - s)]
        };
        let negative = minus != (nx != ny);
        let mut carry = false;
        for (k, slot) in self.limbs.iter_mut().enumerate().skip(limb) {
            let add = parts.get(k - limb).copied().unwrap_or(0);
            if k - limb >= 3 && !carry {
                break;
            }
            if negative {
                let (r1, b1) = slot.overflowing_sub(add);
                let (r2, b2) = r1.overflowing_sub(u64::from(carry));
                *slot = r2;
                carry = b1 || b2;
            } else {
                let (r1, c1) = slot.overflowing_add(add);
                let (r2, c2) = r1.overflowing_add(u64::from(carry));
                *slot = r2;
                carry = c1 || c2;
            }
        }
    }

    fn bit(&self, b: usize) -> bool {
        (self.limbs[b / 64] >> (b % 64)) & 1 == 1
    }

    /// `[RD(s), RU(s)]` for the exact sum `s` (`RD` of a sum beyond the
    /// largest double is that double, `RU` is `+∞`).
    pub fn bounds(&self) -> Interval {
        let iv = |a: f64, b: f64| Interval::try_from((a, b)).unwrap_or(Interval::ENTIRE);
        // A sum of areas is never negative; a set top bit would mean a bug,
        // reported as the entire line.
        if self.limbs[LIMBS - 1] >> 63 == 1 {
            return Interval::ENTIRE;
        }
        let Some(top) = (0..LIMBS).rev().find(|&k| self.limbs[k] != 0) else {
            return iv(0.0, 0.0);
        };
        let h = top * 64 + 63 - self.limbs[top].leading_zeros() as usize; // highest set bit
                                                                          // The last bit a double keeps: 53 bits below h, but not below 2⁻¹⁰⁷⁴.
        let min_bit = (-1074 - BASE_EXP) as usize;
        if h < min_bit {
            // 0 < s < 2⁻¹⁰⁷⁴.
            return iv(0.0, f64::from_bits(1));
        }
        let lo_bit = h.saturating_sub(52).max(min_bit);
        let mut m: u64 = 0;
        for b in (lo_bit..=h).rev() {
            m = (m << 1) | u64::from(self.bit(b));
        }
        let inexact = (0..lo_bit).any(|b| self.bit(b));
        // s = m·2^e (+ the bits below), with e ≥ −1074.
        let e = lo_bit as i64 + BASE_EXP;
        // 2^k for k in [-1022, 1023].
        let pow2 = |k: i64| f64::from_bits(((k + 1023).clamp(1, 2046) as u64) << 52);
        let scale = |m: u64| -> f64 {
            if e + 52 > 1023 {
                return f64::INFINITY;
            }
            // m·2⁻¹⁰⁰⁰ is a normal double, and the result m·2^e is a double
            // (53 bits, or a subnormal when e = −1074), so both steps are exact
            // unless the result overflows.
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

    /// A leaf's `(t0, t1)` and `(w0, w1)`.
    type Leaf = ((f64, f64), (f64, f64));

    fn sum(leaves: &[Leaf]) -> Interval {
        let mut s = AreaSum::default();
        for &(t, w) in leaves {
            s.add(&LeafArea::of(t, w));
        }
        s.bounds()
    }

    #[test]
    fn exact_where_floating_sums_are_not() {
        // 1 + 4·2⁻¹⁰⁰ kept exactly: areas 1·1 and tiny ones.
        let tiny = ((0.0, 2f64.powi(-50)), (0.0, 2f64.powi(-50)));
        let b = sum(&[((0.0, 1.0), (0.0, 1.0)), tiny, tiny, tiny, tiny]);
        assert_eq!(b.inf(), 1.0);
        assert_eq!(b.sup(), 1.0 + f64::EPSILON);
        // 0.6·0.5 = 0.3 is not a double: the two neighbours of the exact
        // product of the doubles nearest 0.1, 0.7, -0.3, 0.2.
        let b = sum(&[((0.1, 0.7), (-0.3, 0.2))]);
        assert!(b.inf() <= 0.3 && 0.3 <= b.sup() && b.sup() - b.inf() <= 2.0 * f64::EPSILON);
        assert_eq!(b.sup(), b.inf().next_up());
    }

    /// Below 2⁻⁹⁶⁹, where an error-free product underflows, the sum is still
    /// rounded once: 2⁻⁹⁷⁰ + 2·2⁻¹⁰²³ = 2⁻⁹⁷⁰ + 2⁻¹⁰²² (one ulp above 2⁻⁹⁷⁰)
    /// exactly, where a running sum rounded down stays at 2⁻⁹⁷⁰.
    #[test]
    fn tiny_leaves_are_summed_exactly() {
        let a = 2f64.powi(-485);
        let u = 2f64.powi(-537); // the ulp of a
        let b = sum(&[
            ((0.0, a), (0.0, a)),
            ((a, a + u), (0.0, a / 2.0)),
            ((a, a + u), (a / 2.0, a)),
        ]);
        let want = 2f64.powi(-970) + 2f64.powi(-1022);
        assert_eq!((b.inf(), b.sup()), (want, want));
        // Two subnormal squares: 2·(2⁻¹⁰⁷⁴)² lies strictly between 0 and 2⁻¹⁰⁷⁴.
        let s = f64::from_bits(1);
        let b = sum(&[((0.0, s), (0.0, s)), ((s, 2.0 * s), (0.0, s))]);
        assert_eq!((b.inf(), b.sup()), (0.0, s));
    }

    /// A leaf wider than the largest double: (2·MAX)·2⁻¹⁰⁰ is exact.
    #[test]
    fn leaves_wider_than_the_largest_double() {
        let b = sum(&[((-f64::MAX, f64::MAX), (0.0, 2f64.powi(-100)))]);
        let want = f64::MAX * 2f64.powi(-99);
        assert_eq!((b.inf(), b.sup()), (want, want));
        let b = sum(&[((-f64::MAX, f64::MAX), (-f64::MAX, f64::MAX))]);
        assert_eq!((b.inf(), b.sup()), (f64::MAX, f64::INFINITY));
    }
}
