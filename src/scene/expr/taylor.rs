//! Taylor-mode evaluation of a one-output tape along the solution of
//! θ̈ = F(θ, θ̇): the Taylor coefficients of θ(t) and θ̇(t) at t = 0, each
//! entry's series extended by one degree per pass from the lower degrees
//! (O(order²) operations per entry, not O(order³) as series arithmetic
//! re-run at each degree would be).
//!
//! Every operation is checked to be analytic on the range of its operands
//! (degree 0 of the series): a division by a range containing 0, `sqrt` or
//! `ln` of a range reaching 0, `tan` over a pole, and `abs`, `sign`, `min`,
//! `max` where they switch branch make the evaluation fail with
//! [`NotAnalytic`]. Evaluated over a box, the coefficients then enclose
//! those of every solution through the box, which is what a Taylor
//! remainder over an a-priori enclosure needs.

use super::tape::{Op, Plan, Program, COS_SLOT, FIRST_CONST, SIN_SLOT, THETA_DOT_SLOT, THETA_SLOT};
use crate::number::scalar::{DualN, Scalar};
use inari::Interval;

/// A Taylor coefficient: a scalar whose range (the value part of a dual)
/// can be read, to test that an operation is analytic there.
pub trait Coefficient: Scalar {
    fn range(&self) -> Interval;
}

impl Coefficient for Interval {
    fn range(&self) -> Interval {
        *self
    }
}

impl<const N: usize> Coefficient for DualN<Interval, N> {
    fn range(&self) -> Interval {
        self.value
    }
}

/// The operation that is not analytic on its operands' range.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NotAnalytic(pub &'static str);

impl std::fmt::Display for NotAnalytic {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "θ̈ is not analytic there ({})", self.0)
    }
}

/// One operation on slots, as [`Op`] with the auxiliary series the
/// recurrences need in slots of their own.
#[derive(Clone, Copy, Debug)]
enum Rec {
    One,
    Copy(u32),
    Neg(u32),
    Add(u32, u32),
    Sub(u32, u32),
    Mul(u32, u32),
    Div(u32, u32),
    Sqr(u32),
    Sqrt(u32),
    Exp(u32),
    Ln(u32),
    /// `sin x` to the step's slot, `cos x` to `cos`.
    SinCos {
        x: u32,
        cos: u32,
    },
    /// `sin x` to `sin`, `cos x` to the step's slot.
    CosSin {
        x: u32,
        sin: u32,
    },
    /// `tan x`, and `1 + tan² x` in `sec2`.
    Tan {
        x: u32,
        sec2: u32,
    },
    /// `atan x`, and `1 + x²` in `den`.
    Atan {
        x: u32,
        den: u32,
    },
    Abs(u32),
    Sign(u32),
    Min(u32, u32),
    Max(u32, u32),
}

/// A [`Program`]'s one output as Taylor recurrences.
#[derive(Clone, Debug)]
pub struct TaylorTape {
    consts: Vec<Interval>,
    trig: bool,
    steps: Vec<(Rec, u32)>,
    output: u32,
    len: usize,
}

/// The Taylor coefficients of θ(t) and θ̇(t), degree 0 to the order asked.
#[derive(Clone, Debug)]
pub struct OdeSeries<T> {
    pub theta: Vec<T>,
    pub theta_dot: Vec<T>,
}

impl Program {
    /// The recurrences of output 0 (`None` for a program of another number
    /// of outputs).
    pub fn taylor(&self) -> Option<TaylorTape> {
        if self.outputs.len() != 1 {
            return None;
        }
        let plan = Plan::unshared(&self.tape, &self.consts, &self.outputs, true);
        let mut len = plan.len as u32;
        let mut aux = || {
            len += 1;
            len - 1
        };
        let mut steps = Vec::new();
        for step in &plan.ops {
            let to = step.to;
            match step.op {
                Op::Neg(a) => steps.push((Rec::Neg(a), to)),
                Op::Add(a, b) => steps.push((Rec::Add(a, b), to)),
                Op::Sub(a, b) => steps.push((Rec::Sub(a, b), to)),
                Op::Mul(a, b) => steps.push((Rec::Mul(a, b), to)),
                Op::Div(a, b) => steps.push((Rec::Div(a, b), to)),
                Op::Sqr(a) => steps.push((Rec::Sqr(a), to)),
                Op::Pown(_, 0) => steps.push((Rec::One, to)),
                Op::Pown(a, 1) => steps.push((Rec::Copy(a), to)),
                Op::Pown(a, n) => {
                    // Left to right, as the tape's own `pown` default: the
                    // last product lands in `to`.
                    let mut p = a;
                    for i in 1..n {
                        let q = if i + 1 == n { to } else { aux() };
                        steps.push((Rec::Mul(p, a), q));
                        p = q;
                    }
                }
                Op::Sqrt(a) => steps.push((Rec::Sqrt(a), to)),
                Op::Exp(a) => steps.push((Rec::Exp(a), to)),
                Op::Ln(a) => steps.push((Rec::Ln(a), to)),
                Op::Sin(x) => steps.push((Rec::SinCos { x, cos: aux() }, to)),
                Op::Cos(x) => steps.push((Rec::CosSin { x, sin: aux() }, to)),
                Op::SinCos { x, cos } => steps.push((Rec::SinCos { x, cos }, to)),
                Op::Tan(x) => steps.push((Rec::Tan { x, sec2: aux() }, to)),
                Op::Atan(x) => steps.push((Rec::Atan { x, den: aux() }, to)),
                Op::Abs(a) => steps.push((Rec::Abs(a), to)),
                Op::Sign(a) => steps.push((Rec::Sign(a), to)),
                Op::Min(a, b) => steps.push((Rec::Min(a, b), to)),
                Op::Max(a, b) => steps.push((Rec::Max(a, b), to)),
            }
        }
        Some(TaylorTape {
            consts: plan.consts.iter().map(|k| k.interval).collect(),
            trig: plan.trig != [false, false],
            steps,
            output: plan.outputs[0],
            len: len as usize,
        })
    }
}

fn contains_zero(x: Interval) -> bool {
    x.is_empty() || (x.inf() <= 0.0 && x.sup() >= 0.0)
}

/// `Σ_{i=from}^{to} a_i b_{k−i}` (a Cauchy product's terms).
fn conv<T: Scalar>(a: &[T], b: &[T], k: usize, from: usize, to: usize) -> T {
    let mut s = T::int(0);
    for i in from..=to {
        s = s + a[i] * b[k - i];
    }
    s
}

/// `Σ_{i=1}^{to} i·a_i b_{k−i}`.
fn conv_weighted<T: Scalar>(a: &[T], b: &[T], k: usize, to: usize) -> T {
    let mut s = T::int(0);
    for i in 1..=to {
        s = s + T::int(i as i32) * a[i] * b[k - i];
    }
    s
}

impl TaylorTape {
    /// The Taylor coefficients to degree `order` of the solution of
    /// θ̈ = F(θ, θ̇) with θ(0) = `theta`, θ̇(0) = `theta_dot`: θ_{k+1} =
    /// θ̇_k/(k+1), θ̇_{k+1} = F_k/(k+1). Over boxes (or duals over boxes),
    /// each coefficient encloses that of every solution through the box.
    /// `work` is reused between calls.
    pub fn ode_series<T: Coefficient>(
        &self,
        theta: T,
        theta_dot: T,
        order: usize,
        work: &mut Vec<T>,
    ) -> Result<OdeSeries<T>, NotAnalytic> {
        let n = order + 1;
        assert!(
            order < i32::MAX as usize / 2,
            "an order that fits the recurrences"
        );
        work.clear();
        work.resize(self.len * n, T::int(0));
        let c = work.as_mut_slice();
        let at = |slot: u32| slot as usize * n;
        c[at(THETA_SLOT)] = theta;
        c[at(THETA_DOT_SLOT)] = theta_dot;
        for (i, &k) in self.consts.iter().enumerate() {
            c[at(FIRST_CONST + i as u32)] = T::lift(k);
        }
        for k in 0..order {
            if self.trig {
                self.sin_cos(c, n, k, THETA_SLOT, SIN_SLOT, COS_SLOT);
            }
            for &(rec, to) in &self.steps {
                self.step(c, n, k, rec, to)?;
            }
            let next = T::int(k as i32 + 1);
            c[at(THETA_SLOT) + k + 1] = c[at(THETA_DOT_SLOT) + k] / next;
            c[at(THETA_DOT_SLOT) + k + 1] = c[at(self.output) + k] / next;
        }
        Ok(OdeSeries {
            theta: c[at(THETA_SLOT)..at(THETA_SLOT) + n].to_vec(),
            theta_dot: c[at(THETA_DOT_SLOT)..at(THETA_DOT_SLOT) + n].to_vec(),
        })
    }

    /// Degree `k` of `sin x` and `cos x`: s' = c·x', c' = −s·x'.
    fn sin_cos<T: Scalar>(&self, c: &mut [T], n: usize, k: usize, x: u32, s: u32, co: u32) {
        let (x, s, co) = (x as usize * n, s as usize * n, co as usize * n);
        if k == 0 {
            let (sv, cv) = c[x].sin_cos();
            c[s] = sv;
            c[co] = cv;
            return;
        }
        let kk = T::int(k as i32);
        let sk = conv_weighted(&c[x..x + n], &c[co..co + n], k, k) / kk;
        let ck = -conv_weighted(&c[x..x + n], &c[s..s + n], k, k) / kk;
        c[s + k] = sk;
        c[co + k] = ck;
    }

    /// Degree `k` of one operation's result from degrees `0..=k` of its
    /// operands and `0..k` of itself.
    fn step<T: Coefficient>(
        &self,
        c: &mut [T],
        n: usize,
        k: usize,
        rec: Rec,
        to: u32,
    ) -> Result<(), NotAnalytic> {
        let s = |slot: u32| slot as usize * n;
        let f = s(to);
        let v = match rec {
            Rec::One => {
                if k == 0 {
                    T::int(1)
                } else {
                    T::int(0)
                }
            }
            Rec::Copy(a) => c[s(a) + k],
            Rec::Neg(a) => -c[s(a) + k],
            Rec::Add(a, b) => c[s(a) + k] + c[s(b) + k],
            Rec::Sub(a, b) => c[s(a) + k] - c[s(b) + k],
            Rec::Mul(a, b) => conv(&c[s(a)..s(a) + n], &c[s(b)..s(b) + n], k, 0, k),
            Rec::Sqr(a) => {
                let a = &c[s(a)..s(a) + n];
                // 2·Σ_{i < k−i} a_i a_{k−i} + a_{k/2}² for even k.
                let half = if k == 0 {
                    T::int(0)
                } else {
                    conv(a, a, k, 0, (k - 1) / 2)
                };
                let mid = if k.is_multiple_of(2) {
                    a[k / 2].sqr()
                } else {
                    T::int(0)
                };
                T::int(2) * half + mid
            }
            Rec::Div(a, b) => {
                if k == 0 && contains_zero(c[s(b)].range()) {
                    return Err(NotAnalytic("a division by a range containing 0"));
                }
                // b·f = a: f_k = (a_k − Σ_{i=1}^{k} b_i f_{k−i}) / b_0.
                let sum = if k == 0 {
                    T::int(0)
                } else {
                    conv(&c[s(b)..s(b) + n], &c[f..f + n], k, 1, k)
                };
                (c[s(a) + k] - sum) / c[s(b)]
            }
            Rec::Sqrt(a) => {
                if k == 0 {
                    if c[s(a)].range().is_empty() || c[s(a)].range().inf() <= 0.0 {
                        return Err(NotAnalytic("sqrt of a range reaching 0"));
                    }
                    c[s(a)].sqrt()
                } else {
                    // f² = a: f_k = (a_k − Σ_{i=1}^{k−1} f_i f_{k−i}) / (2 f_0).
                    let sum = if k == 1 {
                        T::int(0)
                    } else {
                        conv(&c[f..f + n], &c[f..f + n], k, 1, k - 1)
                    };
                    (c[s(a) + k] - sum) / (T::int(2) * c[f])
                }
            }
            Rec::Exp(a) => {
                if k == 0 {
                    c[s(a)].exp()
                } else {
                    // f' = f·a'.
                    conv_weighted(&c[s(a)..s(a) + n], &c[f..f + n], k, k) / T::int(k as i32)
                }
            }
            Rec::Ln(a) => {
                if k == 0 {
                    if c[s(a)].range().is_empty() || c[s(a)].range().inf() <= 0.0 {
                        return Err(NotAnalytic("ln of a range reaching 0"));
                    }
                    c[s(a)].ln()
                } else {
                    // a·f' = a': k a_0 f_k = k a_k − Σ_{i=1}^{k−1} i f_i a_{k−i}.
                    let sum = conv_weighted(&c[f..f + n], &c[s(a)..s(a) + n], k, k - 1);
                    let kk = T::int(k as i32);
                    (kk * c[s(a) + k] - sum) / (kk * c[s(a)])
                }
            }
            Rec::SinCos { x, cos } => {
                self.sin_cos(c, n, k, x, to, cos);
                return Ok(());
            }
            Rec::CosSin { x, sin } => {
                self.sin_cos(c, n, k, x, sin, to);
                return Ok(());
            }
            Rec::Tan { x, sec2 } => {
                let w = s(sec2);
                if k == 0 {
                    let t = c[s(x)].tan();
                    if !t.range().is_common_interval() {
                        return Err(NotAnalytic("tan over a pole"));
                    }
                    c[f] = t;
                    c[w] = T::int(1) + t.sqr();
                    return Ok(());
                }
                // f' = (1 + f²)·x'.
                let fk = conv_weighted(&c[s(x)..s(x) + n], &c[w..w + n], k, k) / T::int(k as i32);
                c[f + k] = fk;
                c[w + k] = conv(&c[f..f + n], &c[f..f + n], k, 0, k);
                return Ok(());
            }
            Rec::Atan { x, den } => {
                let h = s(den);
                if k == 0 {
                    c[h] = T::int(1) + c[s(x)].sqr();
                    c[f] = c[s(x)].atan();
                    return Ok(());
                }
                // (1 + x²)·f' = x': k h_0 f_k = k x_k − Σ_{i=1}^{k−1} i f_i h_{k−i}.
                c[h + k] = conv(&c[s(x)..s(x) + n], &c[s(x)..s(x) + n], k, 0, k);
                let sum = conv_weighted(&c[f..f + n], &c[h..h + n], k, k - 1);
                let kk = T::int(k as i32);
                (kk * c[s(x) + k] - sum) / (kk * c[h])
            }
            Rec::Abs(a) => match sign_of(c[s(a)].range()) {
                Some(true) => c[s(a) + k],
                Some(false) => -c[s(a) + k],
                None => return Err(NotAnalytic("abs of a range containing 0")),
            },
            Rec::Sign(a) => match (sign_of(c[s(a)].range()), k) {
                (None, _) => return Err(NotAnalytic("sign of a range containing 0")),
                (Some(p), 0) => T::int(if p { 1 } else { -1 }),
                (Some(_), _) => T::int(0),
            },
            Rec::Min(a, b) | Rec::Max(a, b) => {
                let (x, y) = (c[s(a)].range(), c[s(b)].range());
                if x.is_empty() || y.is_empty() {
                    return Err(NotAnalytic("min or max of an empty range"));
                }
                let a_below = x.sup() < y.inf();
                let b_below = y.sup() < x.inf();
                if !a_below && !b_below {
                    return Err(NotAnalytic("min or max of overlapping ranges"));
                }
                let take_a = a_below == matches!(rec, Rec::Min(..));
                c[if take_a { s(a) } else { s(b) } + k]
            }
        };
        c[f + k] = v;
        Ok(())
    }
}

/// `Some(true)` for a range above 0, `Some(false)` below, `None` otherwise.
fn sign_of(x: Interval) -> Option<bool> {
    if x.is_empty() {
        None
    } else if x.inf() > 0.0 {
        Some(true)
    } else if x.sup() < 0.0 {
        Some(false)
    } else {
        None
    }
}
