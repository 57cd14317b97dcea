//! Compiled expressions and their evaluation: decorated intervals and
//! forward-mode dual numbers over them.
//!
//! An expression is compiled once into a flat list of operations in the
//! order written; every operation writes one slot, and its operands are
//! earlier slots. A definition is one slot, so it is evaluated once per box.

use inari::{DecInterval, Decoration, Interval};
use std::cell::Cell;
use std::collections::HashMap;

use super::encoding::decimal_enclosure;
use super::expr::{self, Emit};
// `Op` is part of what a compiled program is: its users import it here too.
pub use super::ops::Op;
use super::ops::{is_name, operands, FUNCTIONS};

/// Numbers an expression can be evaluated over.
pub trait Num: Copy {
    fn constant(x: DecInterval) -> Self;
    fn add(self, o: Self) -> Self;
    fn sub(self, o: Self) -> Self;
    fn mul(self, o: Self) -> Self;
    fn div(self, o: Self) -> Self;
    fn neg(self) -> Self;
    fn sqr(self) -> Self;
    fn pown(self, n: i32) -> Self;
    fn sqrt(self) -> Self;
    fn sin(self) -> Self;
    fn cos(self) -> Self;
    fn tan(self) -> Self;
    fn ln(self) -> Self;
    fn abs(self) -> Self;
    /// The derivative of `abs` at the points of `self`: ±1 where the sign is
    /// fixed; where `self` contains 0 the derivative does not exist, so the
    /// result is `[-1, 1]` decorated `trv`.
    fn sign(self) -> Self;
    fn atan(self) -> Self;
    fn exp(self) -> Self;
    /// The function `sign`: −1, 0 or 1 by the sign of `self`.
    fn signum(self) -> Self;
    /// The derivative of `signum`: `[0, 0]` where the sign is fixed; where
    /// `self` contains 0 there is none (a jump): the whole line, `trv`.
    fn signum_slope(self) -> Self;
    fn min(self, o: Self) -> Self;
    fn max(self, o: Self) -> Self;
}

/// The exact point interval `[x, x]` (x a small integer), decorated `com`.
pub fn exact(x: f64) -> DecInterval {
    Interval::try_from((x, x))
        .map(DecInterval::new)
        .unwrap_or(DecInterval::NAI)
}

/// `x^k` as the language evaluates it: `sqr` for 2, `pown` otherwise.
fn lang_pow<T: Num>(x: T, k: i32) -> T {
    if k == 2 {
        x.sqr()
    } else {
        x.pown(k)
    }
}

/// How much looser than tightest a stand-in checker rounds: tests use it to
/// show that a verdict does not rest on the last bit (`proofs/FORMAT.md`,
/// "Intervals", says which operations must be tightest).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Looseness {
    /// Ulps added at each end of the basic operations' results (`+ − × ÷`,
    /// `x^2`, `sqrt`, the steps of root pieces).
    pub basic: u32,
    /// Whether exact results of the basic operations (a point, an end at 0)
    /// move too, as they do for a checker that is not tightest.
    pub exact_too: bool,
    /// Ulps added at each end of the functions' results (`sin`, `cos`,
    /// `tan`, `ln`, `atan`, `exp`, `x^n` for n ≥ 3), exact or not.
    pub functions: u32,
}

thread_local! {
    static LOOSENESS: Cell<Looseness> = const {
        Cell::new(Looseness { basic: 0, exact_too: false, functions: 0 })
    };
    /// Operations applied, and how many may be ([`with_work_bound`]).
    static WORK_DONE: Cell<u64> = const { Cell::new(0) };
    static WORK_BOUND: Cell<u64> = const { Cell::new(u64::MAX) };
    /// A statement asked for more than [`MAX_OPS`] operations.
    static TOO_MANY_OPS: Cell<bool> = const { Cell::new(false) };
}

/// Why a check was cut short by a limit rather than failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Cut {
    /// More operations applied than the bound.
    Work,
    /// A statement of more than [`MAX_OPS`] operations.
    Statement,
}

/// Runs `f` with at most `bound` operations applied; every one past it gives
/// NaI at once (no label holds on NaI, so the check ends at the next one).
/// Returns `f`'s result and the limit that cut it short, if any.
pub(crate) fn with_work_bound<R>(bound: u64, f: impl FnOnce() -> R) -> (R, Option<Cut>) {
    let old = (
        WORK_DONE.replace(0),
        WORK_BOUND.replace(bound),
        TOO_MANY_OPS.replace(false),
    );
    let r = f();
    let cut = if TOO_MANY_OPS.get() {
        Some(Cut::Statement)
    } else if WORK_DONE.get() > bound {
        Some(Cut::Work)
    } else {
        None
    };
    WORK_DONE.set(old.0);
    WORK_BOUND.set(old.1);
    TOO_MANY_OPS.set(old.2);
    (r, cut)
}

/// Runs `f` with the result of every interval operation of an expression
/// (and of the Newton and mean-value steps of root pieces) widened outward
/// by `ulps` ulps at each end (but not an exact result of a basic
/// operation: a point, an end at 0): a stand-in for a checker whose rounding
/// is correct but looser than this one's. Constants (decimals, parameters,
/// `pi`) keep their enclosures. A proof meant for any correct checker stays
/// VALID under it.
pub fn with_loose_rounding<R>(ulps: u32, f: impl FnOnce() -> R) -> R {
    with_looseness(
        Looseness {
            basic: ulps,
            exact_too: false,
            functions: ulps,
        },
        f,
    )
}

/// Runs `f` with the given looseness (see [`with_loose_rounding`]).
pub fn with_looseness<R>(l: Looseness, f: impl FnOnce() -> R) -> R {
    let old = LOOSENESS.replace(l);
    let r = f();
    LOOSENESS.set(old);
    r
}

/// `x` moved outward by `k` doubles at each end.
fn widen(x: Interval, k: u32) -> Interval {
    let (mut a, mut b) = (x.inf(), x.sup());
    for _ in 0..k {
        a = a.next_down();
        b = b.next_up();
    }
    Interval::try_from((a, b)).unwrap_or(x)
}

/// `x` widened by the current looseness of the basic operations. Unless
/// `exact_too`, a point stays a point and an end at 0 stays there: an
/// exactly representable result (`x − x`, `0·y`, `1/∞`) is exact under any
/// correct directed rounding.
pub(crate) fn loosen_i(x: Interval) -> Interval {
    let l = LOOSENESS.get();
    if l.basic == 0 || x.is_empty() {
        return x;
    }
    if l.exact_too {
        return widen(x, l.basic);
    }
    if x.inf() == x.sup() {
        return x;
    }
    let w = widen(x, l.basic);
    let a = if x.inf() == 0.0 { 0.0 } else { w.inf() };
    let b = if x.sup() == 0.0 { 0.0 } else { w.sup() };
    Interval::try_from((a, b)).unwrap_or(x)
}

fn loosen(x: DecInterval) -> DecInterval {
    match x.interval() {
        Some(i) if LOOSENESS.get().basic > 0 => DecInterval::set_dec(loosen_i(i), x.decoration()),
        _ => x,
    }
}

/// A function's value widened by the current looseness of the functions.
fn loosen_fn(x: DecInterval) -> DecInterval {
    let k = LOOSENESS.get().functions;
    match x.interval() {
        Some(i) if k > 0 && !i.is_empty() => DecInterval::set_dec(widen(i, k), x.decoration()),
        _ => x,
    }
}

impl Num for DecInterval {
    fn constant(x: DecInterval) -> Self {
        x
    }
    fn add(self, o: Self) -> Self {
        loosen(self + o)
    }
    fn sub(self, o: Self) -> Self {
        loosen(self - o)
    }
    fn mul(self, o: Self) -> Self {
        loosen(self * o)
    }
    fn div(self, o: Self) -> Self {
        loosen(self / o)
    }
    fn neg(self) -> Self {
        -self
    }
    fn sqr(self) -> Self {
        loosen(DecInterval::sqr(self))
    }
    fn pown(self, n: i32) -> Self {
        if n >= 3 {
            loosen_fn(self.powi(n))
        } else {
            loosen(self.powi(n))
        }
    }
    fn sqrt(self) -> Self {
        loosen(DecInterval::sqrt(self))
    }
    fn sin(self) -> Self {
        loosen_fn(DecInterval::sin(self))
    }
    fn cos(self) -> Self {
        loosen_fn(DecInterval::cos(self))
    }
    fn tan(self) -> Self {
        loosen_fn(DecInterval::tan(self))
    }
    fn ln(self) -> Self {
        loosen_fn(DecInterval::ln(self))
    }
    fn abs(self) -> Self {
        DecInterval::abs(self)
    }
    fn sign(self) -> Self {
        match self.interval() {
            Some(x) if !x.is_empty() && x.inf() > 0.0 => exact(1.0),
            Some(x) if !x.is_empty() && x.sup() < 0.0 => exact(-1.0),
            _ => Interval::try_from((-1.0, 1.0))
                .map(|i| DecInterval::set_dec(i, Decoration::Trv))
                .unwrap_or(DecInterval::NAI),
        }
    }
    fn atan(self) -> Self {
        loosen(DecInterval::atan(self))
    }
    fn exp(self) -> Self {
        loosen(DecInterval::exp(self))
    }
    fn signum(self) -> Self {
        DecInterval::sign(self)
    }
    fn signum_slope(self) -> Self {
        match self.interval() {
            Some(x) if !x.is_empty() && (x.inf() > 0.0 || x.sup() < 0.0) => {
                DecInterval::set_dec(inari::const_interval!(0.0, 0.0), self.decoration())
            }
            _ => DecInterval::set_dec(Interval::ENTIRE, Decoration::Trv),
        }
    }
    fn min(self, o: Self) -> Self {
        DecInterval::min(self, o)
    }
    fn max(self, o: Self) -> Self {
        DecInterval::max(self, o)
    }
}

/// The weight `h = (1 − s)/2` of `u` in the derivative of `min(u, w)`, with
/// `s` the derivative of `abs` at `u − w`: 1 where `u < w`, 0 where `u > w`.
fn min_weight<T: Num>(u: T, w: T) -> T {
    let one = T::constant(exact(1.0));
    one.sub(u.sub(w).sign()).div(T::constant(exact(2.0)))
}

/// A value and its derivative with respect to the one variable.
#[derive(Clone, Copy, Debug)]
pub struct Dual<T> {
    pub v: T,
    pub d: T,
}

impl<T: Num> Dual<T> {
    /// The variable itself at `x` (derivative 1).
    pub fn variable(x: T) -> Self {
        Dual {
            v: x,
            d: T::constant(exact(1.0)),
        }
    }
    fn chain(self, v: T, slope: T) -> Self {
        Dual {
            v,
            d: self.d.mul(slope),
        }
    }
}

// The rules below fix the order of every operation, so that a prover using
// the same rules obtains the same enclosures (see FORMAT.md).
impl<T: Num> Num for Dual<T> {
    fn constant(x: DecInterval) -> Self {
        Dual {
            v: T::constant(x),
            d: T::constant(exact(0.0)),
        }
    }
    fn add(self, o: Self) -> Self {
        Dual {
            v: self.v.add(o.v),
            d: self.d.add(o.d),
        }
    }
    fn sub(self, o: Self) -> Self {
        Dual {
            v: self.v.sub(o.v),
            d: self.d.sub(o.d),
        }
    }
    fn mul(self, o: Self) -> Self {
        Dual {
            v: self.v.mul(o.v),
            d: self.d.mul(o.v).add(self.v.mul(o.d)),
        }
    }
    fn div(self, o: Self) -> Self {
        let v = self.v.div(o.v);
        Dual {
            v,
            d: self.d.sub(v.mul(o.d)).div(o.v),
        }
    }
    fn neg(self) -> Self {
        Dual {
            v: self.v.neg(),
            d: self.d.neg(),
        }
    }
    fn sqr(self) -> Self {
        self.chain(self.v.sqr(), T::constant(exact(2.0)).mul(self.v))
    }
    fn pown(self, n: i32) -> Self {
        if n == 0 {
            // The value carries the decoration; the derivative is 0.
            return Dual {
                v: self.v.pown(0),
                d: T::constant(exact(0.0)),
            };
        }
        let slope = T::constant(exact(f64::from(n))).mul(lang_pow(self.v, n - 1));
        self.chain(lang_pow(self.v, n), slope)
    }
    fn sqrt(self) -> Self {
        let r = self.v.sqrt();
        let slope = T::constant(exact(1.0)).div(T::constant(exact(2.0)).mul(r));
        self.chain(r, slope)
    }
    fn sin(self) -> Self {
        self.chain(self.v.sin(), self.v.cos())
    }
    fn cos(self) -> Self {
        self.chain(self.v.cos(), self.v.sin().neg())
    }
    fn tan(self) -> Self {
        let r = self.v.tan();
        self.chain(r, T::constant(exact(1.0)).add(r.sqr()))
    }
    fn ln(self) -> Self {
        self.chain(self.v.ln(), T::constant(exact(1.0)).div(self.v))
    }
    fn abs(self) -> Self {
        self.chain(self.v.abs(), self.v.sign())
    }
    fn sign(self) -> Self {
        let s = self.v.sign();
        // Zero where the sign is fixed; inherits `trv` where it is not.
        Dual {
            v: s,
            d: s.mul(T::constant(exact(0.0))),
        }
    }
    fn atan(self) -> Self {
        let one = T::constant(exact(1.0));
        self.chain(self.v.atan(), one.div(one.add(self.v.sqr())))
    }
    fn exp(self) -> Self {
        let e = self.v.exp();
        self.chain(e, e)
    }
    fn signum(self) -> Self {
        self.chain(self.v.signum(), self.v.signum_slope())
    }
    fn signum_slope(self) -> Self {
        let s = self.v.signum_slope();
        Dual {
            v: s,
            d: s.mul(T::constant(exact(0.0))),
        }
    }
    fn min(self, o: Self) -> Self {
        let h = min_weight(self.v, o.v);
        let k = T::constant(exact(1.0)).sub(h);
        Dual {
            v: self.v.min(o.v),
            d: self.d.mul(h).add(o.d.mul(k)),
        }
    }
    fn max(self, o: Self) -> Self {
        let h = min_weight(self.v, o.v);
        let k = T::constant(exact(1.0)).sub(h);
        Dual {
            v: self.v.max(o.v),
            d: self.d.mul(k).add(o.d.mul(h)),
        }
    }
}

/// Counts `n` operations of a check done outside [`apply`] (the Taylor
/// series of a trajectory); false once past the work bound.
pub(crate) fn spend(n: u64) -> bool {
    let done = WORK_DONE.get().saturating_add(n);
    WORK_DONE.set(done);
    done <= WORK_BOUND.get()
}

/// Applies one operation to already computed slots.
#[inline]
pub fn apply<T: Num>(op: &Op, s: &[T], vars: &[T]) -> T {
    let done = WORK_DONE.get().saturating_add(1);
    WORK_DONE.set(done);
    if done > WORK_BOUND.get() {
        return T::constant(DecInterval::NAI);
    }
    // Operands always precede the slot being computed (see `Program::push`),
    // so indexing cannot fail; `get` keeps that an invariant, not a panic.
    let g = |i: u32| {
        s.get(i as usize)
            .copied()
            .unwrap_or(T::constant(DecInterval::NAI))
    };
    match *op {
        Op::Const(c) => T::constant(c),
        Op::Var(i) => vars
            .get(usize::from(i))
            .copied()
            .unwrap_or(T::constant(DecInterval::NAI)),
        Op::Neg(a) => g(a).neg(),
        Op::Add(a, b) => g(a).add(g(b)),
        Op::Sub(a, b) => g(a).sub(g(b)),
        Op::Mul(a, b) => g(a).mul(g(b)),
        Op::Div(a, b) => g(a).div(g(b)),
        Op::Sqr(a) => g(a).sqr(),
        Op::Pown(a, n) => g(a).pown(n),
        Op::Sqrt(a) => g(a).sqrt(),
        Op::Sin(a) => g(a).sin(),
        Op::Cos(a) => g(a).cos(),
        Op::Tan(a) => g(a).tan(),
        Op::Ln(a) => g(a).ln(),
        Op::Abs(a) => g(a).abs(),
        Op::Atan(a) => g(a).atan(),
        Op::Exp(a) => g(a).exp(),
        Op::Sign(a) => g(a).signum(),
        Op::Min(a, b) => g(a).min(g(b)),
        Op::Max(a, b) => g(a).max(g(b)),
    }
}

/// Largest number of operations in one statement.
pub const MAX_OPS: usize = 1 << 20;

/// A compiled statement: variables, parameters, definitions and any number
/// of expressions, all in one slot list.
#[derive(Clone, Debug)]
pub struct Program {
    ops: Vec<Op>,
    /// Bit i set when the slot depends on variable i.
    deps: Vec<u8>,
    names: HashMap<String, u32>,
}

impl Program {
    /// A program over the given variables (at most 8), with `pi` defined.
    pub fn new(vars: &[&str]) -> Result<Self, String> {
        let mut p = Program {
            ops: Vec::new(),
            deps: Vec::new(),
            names: HashMap::new(),
        };
        if vars.len() > 8 {
            return Err("too many variables".into());
        }
        for (i, v) in vars.iter().enumerate() {
            p.check_new_name(v)?;
            let s = p.push(Op::Var(i as u8))?;
            p.names.insert((*v).to_string(), s);
        }
        let pi = p.push(Op::Const(DecInterval::PI))?;
        p.names.insert("pi".into(), pi);
        Ok(p)
    }

    fn check_new_name(&self, name: &str) -> Result<(), String> {
        if !is_name(name) {
            return Err(format!("{name:?} is not a valid name"));
        }
        // `inf` is reserved so that an unbounded end `"inf"` reads one way only.
        if FUNCTIONS.contains(&name) || name == "pi" || name == "inf" {
            return Err(format!("{name:?} is reserved"));
        }
        if self.names.contains_key(name) {
            return Err(format!("name {name:?} is used twice"));
        }
        Ok(())
    }

    /// Appends an operation; its operands must be earlier slots.
    pub(crate) fn push(&mut self, op: Op) -> Result<u32, String> {
        if self.ops.len() >= MAX_OPS {
            TOO_MANY_OPS.set(true);
            return Err("statement too large".into());
        }
        let me = self.ops.len() as u32;
        let mut dep = match op {
            Op::Var(i) => 1u8 << (i & 7),
            _ => 0,
        };
        for a in operands(&op).into_iter().flatten() {
            if a >= me {
                return Err("internal: operand after its use".into());
            }
            dep |= self.deps[a as usize];
        }
        self.ops.push(op);
        self.deps.push(dep);
        Ok(me)
    }

    /// The slot a name refers to.
    pub(crate) fn lookup(&self, name: &str) -> Option<u32> {
        self.names.get(name).copied()
    }

    /// Declares parameters (name → decimal text, or `[lo,hi]` for a
    /// parameter box: every value from lo to hi, ends `-inf`/`inf` allowed),
    /// in the order given.
    pub fn add_parameters(&mut self, params: &[(String, String)]) -> Result<(), String> {
        for (name, text) in params {
            self.check_new_name(name)?;
            let x = parameter_enclosure(text).map_err(|e| format!("parameter {name}: {e}"))?;
            let s = self.push(Op::Const(DecInterval::new(x)))?;
            self.names.insert(name.clone(), s);
        }
        Ok(())
    }

    /// Declares a definition; it may use everything declared before it.
    pub fn define(&mut self, name: &str, text: &str) -> Result<(), String> {
        self.check_new_name(name)?;
        let s = self
            .compile(text)
            .map_err(|e| format!("definition {name}: {e}"))?;
        self.names.insert(name.to_string(), s);
        Ok(())
    }

    /// Compiles an expression and returns the slot of its value.
    pub fn compile(&mut self, text: &str) -> Result<u32, String> {
        expr::parse_into(self, text)
    }

    /// Compiles an expression that must not depend on any variable.
    pub fn compile_constant(&mut self, text: &str) -> Result<u32, String> {
        let s = self.compile(text)?;
        if self.deps[s as usize] != 0 {
            return Err(format!("{text:?} must not depend on a variable"));
        }
        Ok(s)
    }

    /// The operations, in evaluation order.
    pub fn ops(&self) -> &[Op] {
        &self.ops
    }

    /// The variable-dependence mask of each slot.
    pub fn deps(&self) -> &[u8] {
        &self.deps
    }

    /// Operands of slot `i`.
    pub fn operands(&self, i: usize) -> [Option<u32>; 2] {
        self.ops.get(i).map(operands).unwrap_or([None, None])
    }

    /// Evaluates every slot on the given variable values.
    pub fn eval<T: Num>(&self, vars: &[T], out: &mut Vec<T>) {
        out.clear();
        out.reserve(self.ops.len());
        for op in &self.ops {
            let v = apply(op, out, vars);
            out.push(v);
        }
    }

    /// Evaluates every slot and returns the value of slot `s`.
    pub fn value<T: Num>(&self, vars: &[T], s: u32) -> T {
        let mut out = Vec::new();
        self.eval(vars, &mut out);
        out.get(s as usize)
            .copied()
            .unwrap_or(T::constant(DecInterval::NAI))
    }

    /// Gives the parameter `name` the enclosure `x`: one compiled statement
    /// then serves every box of a parameter split tree.
    pub(crate) fn set_parameter(&mut self, name: &str, x: Interval) -> Result<(), String> {
        let s = self
            .lookup(name)
            .ok_or_else(|| format!("unknown parameter {name:?}"))?;
        match self.ops.get_mut(s as usize) {
            Some(op @ Op::Const(_)) => {
                *op = Op::Const(DecInterval::new(x));
                Ok(())
            }
            _ => Err(format!("{name:?} is not a parameter")),
        }
    }
}

impl Emit for Program {
    fn emit(&mut self, op: Op) -> Result<u32, String> {
        self.push(op)
    }
    fn slot_of(&self, name: &str) -> Option<u32> {
        self.lookup(name)
    }
}

/// True when the decorated value is defined on the whole argument (`≥ def`).
pub fn defined(x: DecInterval) -> bool {
    x.decoration() >= Decoration::Def && x.interval().is_some_and(|i| !i.is_empty())
}

/// True when the decorated value is defined and continuous (`≥ dac`).
pub fn continuous(x: DecInterval) -> bool {
    x.decoration() >= Decoration::Dac && x.interval().is_some_and(|i| !i.is_empty())
}

/// Short text for an enclosure in messages: `[a, b] (dec)`.
pub fn show(x: DecInterval) -> String {
    match x.interval() {
        None => "NaI".into(),
        Some(i) if i.is_empty() => "empty".into(),
        Some(i) => format!("[{:e}, {:e}] ({:?})", i.inf(), i.sup(), x.decoration()),
    }
}

/// Short text for an interval in messages.
pub fn show_i(i: Interval) -> String {
    if i.is_empty() {
        "empty".into()
    } else {
        format!("[{:e}, {:e}]", i.inf(), i.sup())
    }
}

/// The enclosure of a parameter: decimal text, or a box `[lo,hi]` whose ends
/// are decimal text (`-inf` for lo, `inf` for hi allowed) with lo ≤ hi.
pub fn parameter_enclosure(text: &str) -> Result<Interval, String> {
    let Some(inner) = text.strip_prefix('[').and_then(|t| t.strip_suffix(']')) else {
        return decimal_enclosure(text);
    };
    let (a, b) = inner
        .split_once(',')
        .ok_or_else(|| format!("parameter box {text:?} must be [lo,hi]"))?;
    let lo = match a {
        "-inf" => f64::NEG_INFINITY,
        t => decimal_enclosure(t)?.inf(),
    };
    let hi = match b {
        "inf" => f64::INFINITY,
        t => decimal_enclosure(t)?.sup(),
    };
    // NaN cannot occur (both ends come from enclosures or ±inf).
    if lo > hi || lo == f64::INFINITY || hi == f64::NEG_INFINITY {
        return Err(format!("parameter box {text:?} is empty"));
    }
    Interval::try_from((lo, hi)).map_err(|_| format!("parameter box {text:?} is not an interval"))
}
