//! Taylor series of the solution of θ̈ = F(θ, θ̇) through a state, by the
//! recurrences of `proofs/FORMAT.md` ("Claim `trajectory`", series rules),
//! over any number type of the evaluator (intervals, or dual numbers for
//! the Jacobian). A coefficient below `dac` anywhere makes the result
//! undefined, which the caller tests on the outputs (decorations spread).

use super::eval::{exact, spend, Num, Op, Program};
use inari::DecInterval;

fn k_of<T: Num>(k: usize) -> T {
    T::constant(exact(k as f64))
}

fn zero<T: Num>() -> T {
    T::constant(exact(0.0))
}

fn nai<T: Num>() -> T {
    T::constant(DecInterval::NAI)
}

/// `x` made undefined where `cond` is (`cond − cond` is `[0, 0]` or `trv`).
fn guard<T: Num>(x: T, cond: T) -> T {
    x.add(cond.sub(cond))
}

/// Σ_{i=lo}^{k} w(i)·a_i·b_{k−i}, with w(i) = i when `weighted`.
fn conv<T: Num>(a: &[T], b: &[T], k: usize, lo: usize, hi: usize, weighted: bool) -> T {
    let mut acc = zero::<T>();
    for i in lo..=hi {
        let term = a[i].mul(b[k - i]);
        acc = acc.add(if weighted { term.mul(k_of(i)) } else { term });
    }
    spend(3 * (hi + 1).saturating_sub(lo) as u64);
    acc
}

/// The coefficients 0..=order of θ and θ̇ of the solution through `x0`;
/// `f` is the slot of F in `prog` (variables t, w).
pub fn ode_series<T: Num>(prog: &Program, f: u32, x0: [T; 2], order: usize) -> [Vec<T>; 2] {
    let ops = prog.ops();
    let n = ops.len();
    let mut s: Vec<Vec<T>> = vec![Vec::with_capacity(order + 1); n];
    // Companions: cos for sin, sin for cos, (sin, cos) for tan, 1 + u² for
    // atan, the partial powers for x^n.
    let mut aux: Vec<Vec<Vec<T>>> = vec![Vec::new(); n];
    let mut th = vec![x0[0]];
    let mut w = vec![x0[1]];
    for k in 0..=order {
        for i in 0..n {
            let g = |j: u32| &s[j as usize];
            let c = match ops[i] {
                Op::Const(c) => {
                    if k == 0 {
                        T::constant(c)
                    } else {
                        zero()
                    }
                }
                Op::Var(0) => th[k],
                Op::Var(_) => w[k],
                Op::Neg(a) => g(a)[k].neg(),
                Op::Add(a, b) => g(a)[k].add(g(b)[k]),
                Op::Sub(a, b) => g(a)[k].sub(g(b)[k]),
                Op::Mul(a, b) => conv(g(a), g(b), k, 0, k, false),
                Op::Sqr(a) => conv(g(a), g(a), k, 0, k, false),
                Op::Div(a, b) => {
                    let (u, v) = (g(a), g(b));
                    let q = &s[i];
                    let mut acc = u[k];
                    for j in 1..=k {
                        acc = acc.sub(v[j].mul(q[k - j]));
                    }
                    spend(2 * k as u64);
                    acc.div(v[0])
                }
                Op::Pown(a, p) => pown_coef(g(a), &mut aux[i], k, p),
                Op::Sqrt(a) => {
                    let u = g(a);
                    let r = &s[i];
                    if k == 0 {
                        guard(u[0].sqrt(), u[0].sign())
                    } else {
                        let mut acc = u[k];
                        for j in 1..k {
                            acc = acc.sub(r[j].mul(r[k - j]));
                        }
                        spend(2 * k as u64);
                        acc.div(k_of::<T>(2).mul(r[0]))
                    }
                }
                Op::Sin(a) | Op::Cos(a) | Op::Tan(a) => {
                    let u = g(a).clone();
                    trig_coef(&u, &mut aux[i], k);
                    let (sn, cs) = (&aux[i][0], &aux[i][1]);
                    match ops[i] {
                        Op::Sin(_) => sn[k],
                        Op::Cos(_) => cs[k],
                        _ => {
                            let q = &s[i];
                            let mut acc = sn[k];
                            for j in 1..=k {
                                acc = acc.sub(cs[j].mul(q[k - j]));
                            }
                            spend(2 * k as u64);
                            acc.div(cs[0])
                        }
                    }
                }
                Op::Ln(a) => {
                    let u = g(a);
                    let l = &s[i];
                    if k == 0 {
                        guard(u[0].ln(), u[0].sign())
                    } else {
                        let sum = conv(l, u, k, 1, k - 1, true);
                        u[k].sub(sum.div(k_of(k))).div(u[0])
                    }
                }
                Op::Exp(a) => {
                    let u = g(a);
                    if k == 0 {
                        u[0].exp()
                    } else {
                        conv(u, &s[i], k, 1, k, true).div(k_of(k))
                    }
                }
                Op::Atan(a) => {
                    let u = g(a).clone();
                    let d = if k == 0 {
                        T::constant(exact(1.0)).add(u[0].mul(u[0]))
                    } else {
                        conv(&u, &u, k, 0, k, false)
                    };
                    if aux[i].is_empty() {
                        aux[i].push(Vec::new());
                    }
                    aux[i][0].push(d);
                    let d = &aux[i][0];
                    if k == 0 {
                        u[0].atan()
                    } else {
                        let sum = conv(&s[i], d, k, 1, k - 1, true);
                        u[k].sub(sum.div(k_of(k))).div(d[0])
                    }
                }
                Op::Abs(a) => {
                    let u = g(a);
                    u[k].mul(u[0].sign())
                }
                Op::Sign(a) => {
                    let u = g(a);
                    if k == 0 {
                        u[0].signum()
                    } else {
                        u[0].signum_slope()
                    }
                }
                Op::Min(a, b) | Op::Max(a, b) => {
                    let (u, v) = (g(a), g(b));
                    let one = T::constant(exact(1.0));
                    let h = one.sub(u[0].sub(v[0]).sign()).div(k_of(2));
                    let (wu, wv) = match ops[i] {
                        Op::Min(..) => (h, one.sub(h)),
                        _ => (one.sub(h), h),
                    };
                    u[k].mul(wu).add(v[k].mul(wv))
                }
            };
            if !spend(1) {
                s[i].push(nai());
            } else {
                s[i].push(c);
            }
        }
        if k < order {
            let next = k_of::<T>(k + 1);
            th.push(w[k].div(next));
            w.push(s[f as usize][k].div(next));
        }
    }
    [th, w]
}

/// Coefficient `k` of sin u and cos u into `aux[0]`, `aux[1]`.
fn trig_coef<T: Num>(u: &[T], aux: &mut Vec<Vec<T>>, k: usize) {
    if aux.is_empty() {
        aux.push(Vec::new());
        aux.push(Vec::new());
    }
    if aux[0].len() > k {
        return;
    }
    let (sn, cs) = if k == 0 {
        (u[0].sin(), u[0].cos())
    } else {
        let s = conv(u, &aux[1], k, 1, k, true).div(k_of(k));
        let c = conv(u, &aux[0], k, 1, k, true).div(k_of(k)).neg();
        (s, c)
    };
    aux[0].push(sn);
    aux[1].push(cs);
}

/// Coefficient `k` of u^p by repeated products: `aux[j]` holds u^(j+2).
fn pown_coef<T: Num>(u: &[T], aux: &mut Vec<Vec<T>>, k: usize, p: i32) -> T {
    match p {
        0 => {
            if k == 0 {
                u[0].pown(0)
            } else {
                zero()
            }
        }
        1 => u[k],
        p if (2..=64).contains(&p) => {
            let p = p as usize;
            while aux.len() < p - 1 {
                aux.push(Vec::new());
            }
            for j in 0..p - 1 {
                let c = {
                    let prev: &[T] = if j == 0 { u } else { &aux[j - 1] };
                    conv(prev, u, k, 0, k, false)
                };
                aux[j].push(c);
            }
            aux[p - 2][k]
        }
        _ => nai(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use inari::{interval, DecInterval};

    #[test]
    fn the_oscillator_series_is_cos_and_sin() {
        // θ̈ = −θ from (1, 0): θ = cos τ = Σ (−1)^n τ^{2n}/(2n)! (closed form).
        let mut p = Program::new(&["t", "w"]).unwrap();
        let f = p.compile("-t").unwrap();
        let one = DecInterval::new(interval!(1.0, 1.0).unwrap());
        let zero = DecInterval::new(interval!(0.0, 0.0).unwrap());
        let [th, _] = ode_series(&p, f, [one, zero], 8);
        let fact = [1.0, 1.0, 2.0, 6.0, 24.0, 120.0, 720.0, 5040.0, 40320.0];
        for (k, c) in th.iter().enumerate() {
            let want = match k % 4 {
                0 => 1.0 / fact[k],
                2 => -1.0 / fact[k],
                _ => 0.0,
            };
            let x = c.interval().unwrap();
            assert!(
                x.contains(want) && x.wid() < 1e-15,
                "θ_{k} = {x:?}, want {want}"
            );
        }
    }

    #[test]
    fn sine_of_a_line_has_the_closed_form_coefficients() {
        // u = a + τ (θ̈ = 0 from (a, 1)): sin(u) has coefficients
        // sin(a), cos(a), −sin(a)/2, −cos(a)/6 (Taylor of sin at a).
        let mut p = Program::new(&["t", "w"]).unwrap();
        let f = p.compile("0*sin(t)").unwrap();
        let a = 0.7_f64;
        let x = DecInterval::new(interval!(a, a).unwrap());
        let one = DecInterval::new(interval!(1.0, 1.0).unwrap());
        // The series of F = 0·sin t is 0; read sin t's slot from a second
        // evaluation with F = sin t and θ̈ taken as its value is not the
        // point here: integrate θ̈ = sin(t)·0 and compare sin's companion.
        let [th, w] = ode_series(&p, f, [x, one], 3);
        assert!(th[1].interval().unwrap().contains(1.0));
        assert!(w[1].interval().unwrap().contains(0.0));
        let mut q = Program::new(&["t", "w"]).unwrap();
        let g = q.compile("sin(t)").unwrap();
        // θ̈ = sin θ: w_1 = sin(a), w_2 = cos(a)·θ_1/2 = cos(a)/2 at w_0 = 1.
        let [_, w] = ode_series(&q, g, [x, one], 2);
        assert!(w[1].interval().unwrap().contains(a.sin()));
        let want = a.cos() / 2.0;
        let got = w[2].interval().unwrap();
        assert!((got.mid() - want).abs() < 1e-15, "{got:?} vs {want}");
    }
}
