//! Polynomials and rational functions with integer coefficients, for exact
//! identity proofs.
//!
//! A [`Poly`] is a sparse polynomial in at most [`MAX_VARS`] variables, terms
//! sorted in decreasing lexicographic order of the exponents, no zero
//! coefficient: two polynomials are equal iff their term lists are, so the
//! zero polynomial is the empty list.
//!
//! A [`Frac`] is a rational function kept as `P · ∏ fᵢ^eᵢ`: an expanded
//! polynomial P times powers (of either sign) of *factors*, nonzero
//! polynomials interned in a per-thread table. Without a polynomial gcd,
//! denominators would multiply at every sum; with them as factors, a sum
//! only expands the factors the two terms do not share (the elementwise
//! minimum of the exponents stays outside), so the common denominators of
//! a computation (`1 + t²`, a determinant, a parameter) are kept once.
//! Since every factor is nonzero, a `Frac` is zero iff its `P` is the zero
//! polynomial: that is the identity proof.
//!
//! Coefficients are `i128` with checked arithmetic; an overflow, too many
//! variables or a product beyond [`MAX_PRODUCT_TERMS`] is a [`Limit`], not
//! a wrong answer.

use std::cell::RefCell;
use std::collections::HashMap;

/// Variables per computation.
pub const MAX_VARS: usize = 24;
/// Largest number of term products in one polynomial product.
pub const MAX_PRODUCT_TERMS: usize = 4_000_000;

/// Exponents of the variables.
pub type Mono = [u8; MAX_VARS];

/// Why a symbolic computation stopped: its result is not known.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Limit(pub String);

fn limit(what: &str) -> Limit {
    Limit(what.to_string())
}

/// A sparse polynomial with integer coefficients.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Poly(Vec<(Mono, i128)>);

fn mono_mul(a: &Mono, b: &Mono) -> Result<Mono, Limit> {
    let mut m = [0u8; MAX_VARS];
    for i in 0..MAX_VARS {
        m[i] = a[i]
            .checked_add(b[i])
            .ok_or_else(|| limit("exponent beyond 255"))?;
    }
    Ok(m)
}

fn gcd(mut a: u128, mut b: u128) -> u128 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

impl Poly {
    pub fn zero() -> Poly {
        Poly(Vec::new())
    }
    pub fn constant(c: i128) -> Poly {
        if c == 0 {
            Poly::zero()
        } else {
            Poly(vec![([0; MAX_VARS], c)])
        }
    }
    /// The variable number `i` (`i < MAX_VARS`).
    pub fn var(i: usize) -> Poly {
        let mut m = [0; MAX_VARS];
        m[i] = 1;
        Poly(vec![(m, 1)])
    }
    pub fn is_zero(&self) -> bool {
        self.0.is_empty()
    }
    /// Number of terms.
    pub fn terms(&self) -> usize {
        self.0.len()
    }
    /// The constant value, if the polynomial is one.
    pub fn as_constant(&self) -> Option<i128> {
        match self.0.as_slice() {
            [] => Some(0),
            [(m, c)] if m.iter().all(|&e| e == 0) => Some(*c),
            _ => None,
        }
    }
    pub fn neg(&self) -> Result<Poly, Limit> {
        self.0
            .iter()
            .map(|(m, c)| {
                c.checked_neg()
                    .map(|c| (*m, c))
                    .ok_or_else(|| limit("coefficient overflow"))
            })
            .collect::<Result<_, _>>()
            .map(Poly)
    }
    pub fn add(&self, o: &Poly) -> Result<Poly, Limit> {
        let (a, b) = (&self.0, &o.0);
        let mut out = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                std::cmp::Ordering::Greater => {
                    out.push(a[i]);
                    i += 1;
                }
                std::cmp::Ordering::Less => {
                    out.push(b[j]);
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    let c = a[i]
                        .1
                        .checked_add(b[j].1)
                        .ok_or_else(|| limit("coefficient overflow"))?;
                    if c != 0 {
                        out.push((a[i].0, c));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        out.extend_from_slice(&b[j..]);
        Ok(Poly(out))
    }
    pub fn mul(&self, o: &Poly) -> Result<Poly, Limit> {
        let (a, b) = if self.0.len() <= o.0.len() {
            (&self.0, &o.0)
        } else {
            (&o.0, &self.0)
        };
        if a.len().saturating_mul(b.len()) > MAX_PRODUCT_TERMS {
            return Err(limit("polynomial product beyond the term budget"));
        }
        let term = |x: &(Mono, i128), y: &(Mono, i128)| -> Result<(Mono, i128), Limit> {
            Ok((
                mono_mul(&x.0, &y.0)?,
                x.1.checked_mul(y.1)
                    .ok_or_else(|| limit("coefficient overflow"))?,
            ))
        };
        // A monomial times a sorted list stays sorted (lex order is a
        // monomial order).
        if a.len() == 1 {
            return b
                .iter()
                .map(|y| term(&a[0], y))
                .collect::<Result<_, _>>()
                .map(Poly);
        }
        let mut all = Vec::with_capacity(a.len() * b.len());
        for x in a {
            for y in b {
                all.push(term(x, y)?);
            }
        }
        all.sort_unstable_by_key(|t| std::cmp::Reverse(t.0));
        let mut out: Vec<(Mono, i128)> = Vec::with_capacity(all.len());
        for (m, c) in all {
            match out.last_mut() {
                Some(last) if last.0 == m => {
                    last.1 = last
                        .1
                        .checked_add(c)
                        .ok_or_else(|| limit("coefficient overflow"))?;
                }
                _ => out.push((m, c)),
            }
        }
        out.retain(|t| t.1 != 0);
        Ok(Poly(out))
    }
    pub fn pow(&self, k: u32) -> Result<Poly, Limit> {
        let mut p = Poly::constant(1);
        for _ in 0..k {
            p = p.mul(self)?;
        }
        Ok(p)
    }
    /// The largest monomial dividing every term (`self` nonzero).
    fn mono_gcd(&self) -> Mono {
        let mut mono = self.0[0].0;
        for (m, _) in &self.0 {
            for i in 0..MAX_VARS {
                mono[i] = mono[i].min(m[i]);
            }
        }
        mono
    }
    /// `self / x^mono`, `x^mono` dividing every term.
    fn shift_down(&self, mono: &Mono) -> Poly {
        Poly(
            self.0
                .iter()
                .map(|(m, c)| {
                    let mut e = *m;
                    for i in 0..MAX_VARS {
                        e[i] -= mono[i];
                    }
                    (e, *c)
                })
                .collect(),
        )
    }
    /// `self = sign · content · primitive`, the primitive part with
    /// coefficient gcd 1 and a positive leading coefficient (`self` nonzero).
    fn split(&self) -> Result<(i128, i128, Poly), Limit> {
        let content = self.0.iter().fold(0, |g, t| gcd(g, t.1.unsigned_abs()));
        let content = i128::try_from(content).map_err(|_| limit("coefficient overflow"))?;
        let sign = self.0[0].1.signum();
        let prim = self
            .0
            .iter()
            .map(|(m, c)| {
                (c / content)
                    .checked_mul(sign)
                    .map(|c| (*m, c))
                    .ok_or_else(|| limit("coefficient overflow"))
            })
            .collect::<Result<_, _>>()?;
        Ok((sign, content, Poly(prim)))
    }
}

/// Interned factors of the current computation.
struct Table {
    polys: Vec<Poly>,
    index: HashMap<Poly, u32>,
}

thread_local! {
    static TABLE: RefCell<Table> = RefCell::new(Table { polys: Vec::new(), index: HashMap::new() });
}

fn intern(p: Poly) -> u32 {
    TABLE.with(|t| {
        let mut t = t.borrow_mut();
        if let Some(&i) = t.index.get(&p) {
            return i;
        }
        let i = t.polys.len() as u32;
        t.polys.push(p.clone());
        t.index.insert(p, i);
        i
    })
}

fn factor(i: u32) -> Poly {
    TABLE.with(|t| t.borrow().polys[i as usize].clone())
}

/// Forgets every factor: no [`Frac`] made before may be used afterwards.
pub fn clear_factors() {
    TABLE.with(|t| {
        let mut t = t.borrow_mut();
        t.polys.clear();
        t.index.clear();
    })
}

/// Number of interned factors.
pub fn factor_count() -> usize {
    TABLE.with(|t| t.borrow().polys.len())
}

/// Factor exponents, sorted by factor, none zero.
type Exps = Vec<(u32, i32)>;

fn merge(a: &Exps, b: &Exps, f: impl Fn(i32, i32) -> i32) -> Exps {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        let (k, x, y) = if j == b.len() || (i < a.len() && a[i].0 < b[j].0) {
            i += 1;
            (a[i - 1].0, a[i - 1].1, 0)
        } else if i == a.len() || b[j].0 < a[i].0 {
            j += 1;
            (b[j - 1].0, 0, b[j - 1].1)
        } else {
            i += 1;
            j += 1;
            (a[i - 1].0, a[i - 1].1, b[j - 1].1)
        };
        let e = f(x, y);
        if e != 0 {
            out.push((k, e));
        }
    }
    out
}

/// A rational function `num · ∏ factor^exponent`.
#[derive(Clone, Debug)]
pub struct Frac {
    num: Poly,
    exps: Exps,
}

impl Frac {
    pub fn int(n: i128) -> Frac {
        Frac {
            num: Poly::constant(n),
            exps: Vec::new(),
        }
    }
    /// `p/q`, `q > 0`.
    pub fn ratio(p: i128, q: i128) -> Result<Frac, Limit> {
        Frac::int(p).div(&Frac::int(q))
    }
    pub fn var(i: usize) -> Frac {
        Frac {
            num: Poly::var(i),
            exps: Vec::new(),
        }
    }
    pub fn is_zero(&self) -> bool {
        self.num.is_zero()
    }
    /// The expanded part (the cleared numerator when the factors are
    /// denominators).
    pub fn expanded(&self) -> &Poly {
        &self.num
    }
    /// Terms of the expanded part and of each factor.
    pub fn size(&self) -> usize {
        self.num.terms()
            + self
                .exps
                .iter()
                .map(|(k, _)| factor(*k).terms())
                .sum::<usize>()
    }
    fn zero() -> Frac {
        Frac::int(0)
    }
    pub fn neg(&self) -> Result<Frac, Limit> {
        Ok(Frac {
            num: self.num.neg()?,
            exps: self.exps.clone(),
        })
    }
    pub fn mul(&self, o: &Frac) -> Result<Frac, Limit> {
        let num = self.num.mul(&o.num)?;
        if num.is_zero() {
            return Ok(Frac::zero());
        }
        Ok(Frac {
            num,
            exps: merge(&self.exps, &o.exps, |x, y| x + y),
        }
        .tidy())
    }
    /// `self / o`; `o` must not be zero.
    pub fn div(&self, o: &Frac) -> Result<Frac, Limit> {
        assert!(!o.is_zero(), "symbolic division by the zero polynomial");
        let o = o.clone().tidy();
        // o's expanded part becomes factors: its content and its primitive part
        let (sign, content, prim) = o.num.split()?;
        let mut den: Exps = Vec::new();
        if content != 1 {
            den.push((intern(Poly::constant(content)), 1));
        }
        if prim.as_constant() != Some(1) {
            den.push((intern(prim), 1));
        }
        den.sort_unstable();
        let num = if sign < 0 {
            self.num.neg()?
        } else {
            self.num.clone()
        };
        let all = merge(&o.exps, &den, |x, y| x + y);
        Ok(Frac {
            num,
            exps: merge(&self.exps, &all, |x, y| x - y),
        }
        .tidy())
    }
    /// Moves a monomial dividing every term of the expanded part into the
    /// factors, where it cancels against the variables' exponents.
    fn tidy(mut self) -> Frac {
        if self.num.is_zero() {
            return Frac::zero();
        }
        let mono = self.num.mono_gcd();
        if mono.iter().all(|&e| e == 0) {
            return self;
        }
        self.num = self.num.shift_down(&mono);
        let mut vars: Exps = mono
            .iter()
            .enumerate()
            .filter(|(_, &e)| e > 0)
            .map(|(i, &e)| (intern(Poly::var(i)), i32::from(e)))
            .collect();
        vars.sort_unstable();
        self.exps = merge(&self.exps, &vars, |x, y| x + y);
        self
    }
    pub fn add(&self, o: &Frac) -> Result<Frac, Limit> {
        if self.is_zero() {
            return Ok(o.clone());
        }
        if o.is_zero() {
            return Ok(self.clone());
        }
        // common part: the smaller exponent of each factor
        let common = merge(&self.exps, &o.exps, |x, y| x.min(y));
        let expand = |f: &Frac| -> Result<Poly, Limit> {
            let mut p = f.num.clone();
            for (k, e) in merge(&f.exps, &common, |x, y| x - y) {
                p = p.mul(&factor(k).pow(e as u32)?)?;
            }
            Ok(p)
        };
        let sum = expand(self)?.add(&expand(o)?)?;
        Ok(Frac {
            num: sum,
            exps: common,
        }
        .tidy())
    }
    pub fn sub(&self, o: &Frac) -> Result<Frac, Limit> {
        self.add(&o.neg()?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn x(i: usize) -> Frac {
        Frac::var(i)
    }

    #[test]
    fn binomial_square_is_proved_and_a_wrong_one_refused() {
        // (x + y)² = x² + 2xy + y² holds; (x + y)² = x² + y² does not (the
        // difference is 2xy).
        let s = x(0).add(&x(1)).unwrap();
        let lhs = s.mul(&s).unwrap();
        let two = Frac::int(2);
        let rhs = x(0)
            .mul(&x(0))
            .unwrap()
            .add(&two.mul(&x(0)).unwrap().mul(&x(1)).unwrap())
            .unwrap()
            .add(&x(1).mul(&x(1)).unwrap())
            .unwrap();
        assert!(lhs.sub(&rhs).unwrap().is_zero());
        let wrong = x(0)
            .mul(&x(0))
            .unwrap()
            .add(&x(1).mul(&x(1)).unwrap())
            .unwrap();
        let d = lhs.sub(&wrong).unwrap();
        assert!(!d.is_zero());
        // 2xy: the monomial is a factor, the expanded part is the constant 2
        assert_eq!(d.expanded().as_constant(), Some(2));
    }

    #[test]
    fn rational_functions_cancel_through_shared_factors() {
        // 1/(x+1) + x/(x+1) = 1 and x/(x(x+1)) − 1/(x+1) = 0
        let x1 = x(0).add(&Frac::int(1)).unwrap();
        let a = Frac::int(1).div(&x1).unwrap();
        let b = x(0).div(&x1).unwrap();
        assert!(a.add(&b).unwrap().sub(&Frac::int(1)).unwrap().is_zero());
        let c = x(0).div(&x(0).mul(&x1).unwrap()).unwrap();
        assert!(c.sub(&a).unwrap().is_zero());
        // 1/(x+1) ≠ 1/(x+2)
        let x2 = x(0).add(&Frac::int(2)).unwrap();
        assert!(!a.sub(&Frac::int(1).div(&x2).unwrap()).unwrap().is_zero());
    }

    #[test]
    fn overflow_is_a_limit_not_a_result() {
        let big = Frac::int(i128::MAX / 2 + 1);
        assert!(big.mul(&Frac::int(2)).is_err());
        assert!(big.add(&big).is_err());
    }
}
