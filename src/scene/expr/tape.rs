//! The flattened tape: evaluation over any [`Scalar`], its text for proofs,
//! and the analysis of parameter-only operations.

use super::graph::Node;
use super::parse::Func;
use super::{THETA, THETA_DOT};
use crate::number::scalar::{is_defined, Known, Scalar};
use inari::{DecInterval, Decoration, Interval};
use std::collections::HashMap;

/// A compiled tape: each entry is one operation on earlier entries.
#[derive(Clone, Debug)]
pub struct Program {
    pub(super) tape: Vec<Node>,
    pub(super) consts: Vec<Interval>,
    pub(super) const_text: Vec<String>,
    pub(super) outputs: Vec<u32>,
    /// Per entry: whether it depends on θ̇.
    pub(super) on_dot: Vec<bool>,
    /// Per entry: its degree in θ̇ when it is a polynomial in θ̇ with θ-only
    /// coefficients (written so: see [`Program::theta_dot_degree`]).
    pub(super) degree: Vec<Option<u32>>,
    /// How the outputs are evaluated.
    pub(super) plan: Plan,
}

/// `sin(a)` and `cos(a)` both on the tape: the first of the two computes
/// both slots, the second is skipped.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Fused {
    Alone,
    SinCos { a: u32, sin: u32, cos: u32 },
    Done,
}

/// The `sin`/`cos` pairs among the entries `needed`.
fn fuse_sin_cos(tape: &[Node], needed: &[bool]) -> Vec<Fused> {
    let mut fused = vec![Fused::Alone; tape.len()];
    let mut sin_of: HashMap<u32, u32> = HashMap::new();
    for (j, node) in tape.iter().enumerate() {
        if let (true, Node::Call(Func::Sin, a)) = (needed[j], *node) {
            sin_of.insert(a, j as u32);
        }
    }
    for (j, node) in tape.iter().enumerate() {
        if let (true, Node::Call(Func::Cos, a)) = (needed[j], *node) {
            if let Some(&sin) = sin_of.get(&a) {
                let cos = j as u32;
                let (first, second) = (sin.min(cos), sin.max(cos));
                fused[first as usize] = Fused::SinCos { a, sin, cos };
                fused[second as usize] = Fused::Done;
            }
        }
    }
    fused
}

/// Slots of θ, θ̇, `sin θ` and `cos θ`; the constants follow.
pub(super) const THETA_SLOT: u32 = 0;
pub(super) const THETA_DOT_SLOT: u32 = 1;
pub(super) const SIN_SLOT: u32 = 2;
pub(super) const COS_SLOT: u32 = 3;
pub(super) const FIRST_CONST: u32 = 4;

/// How a [`Program`] is evaluated: slots `[θ, θ̇, sin θ, cos θ, constants…,
/// results…]`, the constants copied in as the plan lifted them, `sin θ` and
/// `cos θ` taken from the caller or computed once, and one operation per
/// result in tape order (no dispatch on variables or constants, `sin`/`cos`
/// pairs as one operation). In an evaluation plan a result's slot is reused
/// once the last operation reading it is done, so the slot array stays
/// small (filling it is part of every evaluation).
#[derive(Clone, Debug)]
pub(super) struct Plan {
    /// Copied into the slots from [`FIRST_CONST`] on, each lifted once for
    /// every scalar ([`Scalar::lift_known`]).
    pub(super) consts: Vec<Known>,
    pub(super) ops: Vec<Step>,
    /// Whether `sin θ` and `cos θ` are read.
    pub(super) trig: [bool; 2],
    /// Per tape entry: its slot (`u32::MAX` when no output needs it); in a
    /// plan that reuses slots, only where the entry was computed.
    pub(super) slot: Vec<u32>,
    /// Per output: its slot.
    pub(super) outputs: Vec<u32>,
    /// Slots in all.
    pub(super) len: usize,
}

/// One operation of a [`Plan`] on earlier slots, its result in slot `to`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Step {
    pub(super) op: Op,
    pub(super) to: u32,
}

/// An operation on slots; one variant per function, so that evaluating
/// it is one dispatch.
#[derive(Clone, Copy, Debug)]
pub(super) enum Op {
    Neg(u32),
    Add(u32, u32),
    Sub(u32, u32),
    Mul(u32, u32),
    Div(u32, u32),
    Sqr(u32),
    Pown(u32, u32),
    Sqrt(u32),
    Sin(u32),
    Cos(u32),
    Tan(u32),
    Ln(u32),
    Abs(u32),
    Atan(u32),
    Exp(u32),
    Sign(u32),
    Min(u32, u32),
    Max(u32, u32),
    /// `sin` and `cos` of one operand ([`Scalar::sin_cos`]: the same
    /// enclosures, one kernel call, and duals reuse both): `sin` to the
    /// step's slot, `cos` to this one.
    SinCos {
        x: u32,
        cos: u32,
    },
}

impl Op {
    fn of(node: Node, s: impl Fn(u32) -> u32) -> Op {
        match node {
            Node::Neg(a) => Op::Neg(s(a)),
            Node::Add(a, b) => Op::Add(s(a), s(b)),
            Node::Sub(a, b) => Op::Sub(s(a), s(b)),
            Node::Mul(a, b) => Op::Mul(s(a), s(b)),
            Node::Div(a, b) => Op::Div(s(a), s(b)),
            Node::Sqr(a) => Op::Sqr(s(a)),
            Node::Pown(a, n) => Op::Pown(s(a), n),
            Node::Call(f, a) => {
                let a = s(a);
                match f {
                    Func::Sqrt => Op::Sqrt(a),
                    Func::Sin => Op::Sin(a),
                    Func::Cos => Op::Cos(a),
                    Func::Tan => Op::Tan(a),
                    Func::Ln => Op::Ln(a),
                    Func::Abs => Op::Abs(a),
                    Func::Atan => Op::Atan(a),
                    Func::Exp => Op::Exp(a),
                    Func::Sign => Op::Sign(a),
                    Func::Min | Func::Max => unreachable!("two arguments: Call2"),
                }
            }
            Node::Call2(Func::Min, a, b) => Op::Min(s(a), s(b)),
            Node::Call2(_, a, b) => Op::Max(s(a), s(b)),
            Node::Const(_) | Node::Theta | Node::ThetaDot => {
                unreachable!("variables and constants have their slots")
            }
        }
    }

    /// The slots read.
    fn reads(self) -> [Option<u32>; 2] {
        match self {
            Op::Add(a, b)
            | Op::Sub(a, b)
            | Op::Mul(a, b)
            | Op::Div(a, b)
            | Op::Min(a, b)
            | Op::Max(a, b) => [Some(a), Some(b)],
            Op::Neg(a)
            | Op::Sqr(a)
            | Op::Pown(a, _)
            | Op::Sqrt(a)
            | Op::Sin(a)
            | Op::Cos(a)
            | Op::Tan(a)
            | Op::Ln(a)
            | Op::Abs(a)
            | Op::Atan(a)
            | Op::Exp(a)
            | Op::Sign(a)
            | Op::SinCos { x: a, .. } => [Some(a), None],
        }
    }

    /// The same operation on renamed slots.
    fn map(self, f: impl Fn(u32) -> u32) -> Op {
        match self {
            Op::Neg(a) => Op::Neg(f(a)),
            Op::Add(a, b) => Op::Add(f(a), f(b)),
            Op::Sub(a, b) => Op::Sub(f(a), f(b)),
            Op::Mul(a, b) => Op::Mul(f(a), f(b)),
            Op::Div(a, b) => Op::Div(f(a), f(b)),
            Op::Min(a, b) => Op::Min(f(a), f(b)),
            Op::Max(a, b) => Op::Max(f(a), f(b)),
            Op::Sqr(a) => Op::Sqr(f(a)),
            Op::Pown(a, n) => Op::Pown(f(a), n),
            Op::Sqrt(a) => Op::Sqrt(f(a)),
            Op::Sin(a) => Op::Sin(f(a)),
            Op::Cos(a) => Op::Cos(f(a)),
            Op::Tan(a) => Op::Tan(f(a)),
            Op::Ln(a) => Op::Ln(f(a)),
            Op::Abs(a) => Op::Abs(f(a)),
            Op::Atan(a) => Op::Atan(f(a)),
            Op::Exp(a) => Op::Exp(f(a)),
            Op::Sign(a) => Op::Sign(f(a)),
            Op::SinCos { x, cos } => Op::SinCos {
                x: f(x),
                cos: f(cos),
            },
        }
    }
}

/// An operation on constants alone done once, when every scalar evaluating
/// the tape gets the same value from the result as from the operation:
/// arithmetic only (the functions' kernels differ between scalar types),
/// decorated `com` (bounded, defined: a constant lifts to `com`, and a
/// dual's gradient of it is exactly 0), and the midpoint of the enclosure,
/// which `f64` lifts, bit for bit the `f64` result. `x` holds each operand
/// as (enclosure, its `f64` value).
fn fold(node: Node, x: impl Fn(u32) -> Option<(Interval, f64)>) -> Option<(Interval, f64)> {
    let d = |a: u32| x(a).map(|(i, _)| DecInterval::new(i));
    let p = |a: u32| x(a).map(|(_, p)| p);
    let (v, q) = match node {
        Node::Neg(a) => (-d(a)?, -p(a)?),
        Node::Add(a, b) => (d(a)? + d(b)?, p(a)? + p(b)?),
        Node::Sub(a, b) => (d(a)? - d(b)?, p(a)? - p(b)?),
        Node::Mul(a, b) => (d(a)? * d(b)?, p(a)? * p(b)?),
        Node::Div(a, b) => (d(a)? / d(b)?, p(a)? / p(b)?),
        Node::Sqr(a) => (Scalar::sqr(d(a)?), Scalar::sqr(p(a)?)),
        Node::Pown(a, n) => (Scalar::pown(d(a)?, n), Scalar::pown(p(a)?, n)),
        _ => return None,
    };
    let v = v.interval().filter(|_| v.decoration() == Decoration::Com)?;
    (<f64 as Scalar>::lift(v).to_bits() == q.to_bits()).then_some((v, q))
}

impl Plan {
    /// The plan of `tape` for `outputs`. An evaluation plan (`fold`) does
    /// operations on constants alone here ([`fold`]), keeps only what the
    /// outputs need and reuses slots; otherwise every entry gets its own
    /// slot and keeps its value to the end.
    pub(super) fn new(tape: &[Node], consts: &[Interval], outputs: &[u32], fold: bool) -> Plan {
        let mut plan = Plan::unshared(tape, consts, outputs, fold);
        if fold {
            plan.reuse_slots();
        }
        plan
    }

    /// [`Plan::new`] with every result in its own slot, kept to the end
    /// (Taylor-mode evaluation reads every entry's whole series).
    pub(super) fn unshared(
        tape: &[Node],
        consts: &[Interval],
        outputs: &[u32],
        fold: bool,
    ) -> Plan {
        let mut known: Vec<Option<(Interval, f64)>> = Vec::with_capacity(tape.len());
        for &node in tape {
            known.push(match node {
                Node::Const(k) => {
                    let c = consts[k as usize];
                    Some((c, <f64 as Scalar>::lift(c)))
                }
                n if fold => {
                    let x = |a: u32| known[a as usize];
                    self::fold(n, x)
                }
                _ => None,
            });
        }
        let mut needed = vec![!fold; tape.len()];
        for &o in outputs {
            needed[o as usize] = true;
        }
        // Operands precede their users: one backward sweep marks them all.
        for j in (0..tape.len()).rev() {
            if needed[j] && known[j].is_none() {
                for a in tape[j].operands().into_iter().flatten() {
                    needed[a as usize] = true;
                }
            }
        }
        let fused = fuse_sin_cos(tape, &needed);
        let mut slot = vec![u32::MAX; tape.len()];
        let mut plan_consts = Vec::new();
        for (j, k) in known.iter().enumerate() {
            if let (true, Some(c)) = (needed[j], k) {
                slot[j] = FIRST_CONST + plan_consts.len() as u32;
                plan_consts.push(Known::new(c.0));
            }
        }
        let mut next = FIRST_CONST + plan_consts.len() as u32;
        let mut trig = [false; 2];
        let mut ops = Vec::new();
        for (j, &node) in tape.iter().enumerate() {
            if !needed[j] || known[j].is_some() {
                continue;
            }
            let is_theta = |a: u32| tape[a as usize] == Node::Theta;
            match (fused[j], node) {
                (Fused::Done, _) => {}
                (Fused::SinCos { a, sin, cos }, _) if is_theta(a) => {
                    trig = [true, true];
                    slot[sin as usize] = SIN_SLOT;
                    slot[cos as usize] = COS_SLOT;
                }
                (Fused::SinCos { a, sin, cos }, _) => {
                    slot[sin as usize] = next;
                    slot[cos as usize] = next + 1;
                    let (x, cos) = (slot[a as usize], next + 1);
                    ops.push(Step {
                        op: Op::SinCos { x, cos },
                        to: next,
                    });
                    next += 2;
                }
                (_, Node::Theta) => slot[j] = THETA_SLOT,
                (_, Node::ThetaDot) => slot[j] = THETA_DOT_SLOT,
                (_, Node::Call(f @ (Func::Sin | Func::Cos), a)) if is_theta(a) => {
                    let k = usize::from(f == Func::Cos);
                    trig[k] = true;
                    slot[j] = [SIN_SLOT, COS_SLOT][k];
                }
                (_, node) => {
                    let op = Op::of(node, |a| slot[a as usize]);
                    slot[j] = next;
                    ops.push(Step { op, to: next });
                    next += 1;
                }
            }
        }
        Plan {
            consts: plan_consts,
            ops,
            trig,
            outputs: outputs.iter().map(|&o| slot[o as usize]).collect(),
            slot,
            len: next as usize,
        }
    }

    /// Gives each result a slot freed by a result no later operation reads
    /// (the outputs keep theirs): the values computed are the same, the
    /// slot array is as long as the most results alive at once.
    fn reuse_slots(&mut self) {
        let first = FIRST_CONST + self.consts.len() as u32;
        let index = |a: u32| (a >= first).then(|| (a - first) as usize);
        let results = self.len - first as usize;
        // Per result: the last step reading it (outputs: past every step).
        let mut last = vec![None; results];
        for (i, step) in self.ops.iter().enumerate() {
            for r in step.op.reads().into_iter().flatten().filter_map(index) {
                last[r] = Some(i);
            }
        }
        for r in self.outputs.iter().filter_map(|&o| index(o)) {
            last[r] = Some(usize::MAX);
        }
        let mut to = vec![u32::MAX; results];
        let mut free: Vec<u32> = Vec::new();
        let mut len = first;
        for (i, step) in self.ops.iter_mut().enumerate() {
            let old = *step;
            step.op = old.op.map(|a| index(a).map_or(a, |r| to[r]));
            // An operation reads before it writes: the slots of operands
            // read for the last time take its results.
            for r in old.op.reads().into_iter().flatten().filter_map(index) {
                if last[r] == Some(i) && !free.contains(&to[r]) {
                    free.push(to[r]);
                }
            }
            let mut take = |r: usize| {
                let s = free.pop().unwrap_or_else(|| {
                    len += 1;
                    len - 1
                });
                to[r] = s;
                s
            };
            step.to = take((old.to - first) as usize);
            if let (Op::SinCos { cos, .. }, Op::SinCos { cos: new, .. }) = (old.op, &mut step.op) {
                *new = take((cos - first) as usize);
            }
        }
        self.len = len as usize;
        for o in &mut self.outputs {
            if let Some(r) = index(*o) {
                *o = to[r];
            }
        }
    }

    /// Evaluates every slot (`slots.len()` is [`Plan::len`]).
    pub(super) fn run<T: Scalar>(
        &self,
        theta: T,
        trig: Option<(T, T)>,
        theta_dot: T,
        slots: &mut [T],
    ) {
        slots[THETA_SLOT as usize] = theta;
        slots[THETA_DOT_SLOT as usize] = theta_dot;
        match (trig, self.trig) {
            (_, [false, false]) => {}
            (Some((s, c)), _) => {
                slots[SIN_SLOT as usize] = s;
                slots[COS_SLOT as usize] = c;
            }
            (None, [true, true]) => {
                let (s, c) = theta.sin_cos();
                slots[SIN_SLOT as usize] = s;
                slots[COS_SLOT as usize] = c;
            }
            (None, [true, false]) => slots[SIN_SLOT as usize] = theta.sin(),
            (None, _) => slots[COS_SLOT as usize] = theta.cos(),
        }
        for (s, k) in slots[FIRST_CONST as usize..].iter_mut().zip(&self.consts) {
            *s = T::lift_known(k);
        }
        for step in &self.ops {
            // Each arm stores its own result: a result merged across arms
            // goes through the stack in parts and is reloaded whole, which
            // stalls store forwarding on every operation.
            let x = |a: u32| slots[a as usize];
            let to = step.to as usize;
            match step.op {
                Op::Neg(a) => slots[to] = -x(a),
                Op::Add(a, b) => slots[to] = x(a) + x(b),
                Op::Sub(a, b) => slots[to] = x(a) - x(b),
                Op::Mul(a, b) => slots[to] = x(a) * x(b),
                Op::Div(a, b) => slots[to] = x(a) / x(b),
                Op::Sqr(a) => slots[to] = x(a).sqr(),
                Op::Pown(a, k) => slots[to] = x(a).pown(k),
                Op::Sqrt(a) => slots[to] = x(a).sqrt(),
                Op::Sin(a) => slots[to] = x(a).sin(),
                Op::Cos(a) => slots[to] = x(a).cos(),
                Op::Tan(a) => slots[to] = x(a).tan(),
                Op::Ln(a) => slots[to] = x(a).ln(),
                Op::Abs(a) => slots[to] = x(a).abs(),
                Op::Atan(a) => slots[to] = x(a).atan(),
                Op::Exp(a) => slots[to] = x(a).exp(),
                Op::Sign(a) => slots[to] = x(a).sign(),
                Op::Min(a, b) => slots[to] = x(a).min(x(b)),
                Op::Max(a, b) => slots[to] = x(a).max(x(b)),
                Op::SinCos { x: a, cos } => {
                    let (s, c) = x(a).sin_cos();
                    slots[cos as usize] = c;
                    slots[to] = s;
                }
            }
        }
    }
}

impl Program {
    pub(super) fn new(
        tape: Vec<Node>,
        consts: Vec<Interval>,
        const_text: Vec<String>,
        outputs: Vec<u32>,
    ) -> Program {
        let mut on_dot: Vec<bool> = Vec::with_capacity(tape.len());
        let mut degree: Vec<Option<u32>> = Vec::with_capacity(tape.len());
        for &node in &tape {
            let dot = |a: u32| on_dot[a as usize];
            let deg = |a: u32| degree[a as usize];
            let d = match node {
                Node::Const(_) | Node::Theta => Some(0),
                Node::ThetaDot => Some(1),
                Node::Neg(a) => deg(a),
                Node::Add(a, b) | Node::Sub(a, b) => deg(a).zip(deg(b)).map(|(x, y)| x.max(y)),
                Node::Mul(a, b) => deg(a).zip(deg(b)).and_then(|(x, y)| x.checked_add(y)),
                Node::Div(a, b) => deg(a).filter(|_| !dot(b)),
                Node::Sqr(a) => deg(a).and_then(|x| x.checked_mul(2)),
                Node::Pown(a, n) => deg(a).and_then(|x| x.checked_mul(n)),
                Node::Call(_, a) => (!dot(a)).then_some(0),
                Node::Call2(_, a, b) => (!dot(a) && !dot(b)).then_some(0),
            };
            let o = match node {
                Node::ThetaDot => true,
                n => n.operands().into_iter().flatten().any(dot),
            };
            on_dot.push(o);
            degree.push(d);
        }
        let plan = Plan::new(&tape, &consts, &outputs, true);
        Program {
            tape,
            consts,
            const_text,
            outputs,
            on_dot,
            degree,
            plan,
        }
    }

    /// Number of outputs.
    pub fn outputs(&self) -> usize {
        self.outputs.len()
    }

    /// Tape length (operations, constants and variables included).
    pub fn len(&self) -> usize {
        self.tape.len()
    }

    /// True when the tape is empty (no outputs).
    pub fn is_empty(&self) -> bool {
        self.tape.is_empty()
    }

    /// Evaluates every output at (θ, θ̇) into `out` (length [`Self::outputs`]).
    pub fn eval<T: Scalar>(&self, theta: T, theta_dot: T, out: &mut [T]) {
        self.eval_angle(theta, None, theta_dot, out);
    }

    /// [`Program::eval`] with `(sin θ, cos θ)` already computed (as
    /// [`Scalar::sin_cos`] gives them): `sin(theta)` and `cos(theta)` on the
    /// tape take them instead of computing them again.
    pub fn eval_angle<T: Scalar>(
        &self,
        theta: T,
        trig: Option<(T, T)>,
        theta_dot: T,
        out: &mut [T],
    ) {
        // Small plans (every shipped scene's) evaluate without allocating,
        // on little more stack than they need: the slots are filled at
        // each evaluation.
        match self.plan.len {
            0..=12 => self.eval_on::<T, 12>(theta, trig, theta_dot, out),
            13..=16 => self.eval_on::<T, 16>(theta, trig, theta_dot, out),
            17..=20 => self.eval_on::<T, 20>(theta, trig, theta_dot, out),
            21..=24 => self.eval_on::<T, 24>(theta, trig, theta_dot, out),
            25..=32 => self.eval_on::<T, 32>(theta, trig, theta_dot, out),
            33..=48 => self.eval_on::<T, 48>(theta, trig, theta_dot, out),
            49..=96 => self.eval_on::<T, 96>(theta, trig, theta_dot, out),
            n => self.eval_in(theta, trig, theta_dot, &mut vec![theta; n], out),
        }
    }

    fn eval_on<T: Scalar, const N: usize>(
        &self,
        theta: T,
        trig: Option<(T, T)>,
        theta_dot: T,
        out: &mut [T],
    ) {
        let mut slots = [theta; N];
        self.eval_in(theta, trig, theta_dot, &mut slots[..self.plan.len], out);
    }

    fn eval_in<T: Scalar>(
        &self,
        theta: T,
        trig: Option<(T, T)>,
        theta_dot: T,
        slots: &mut [T],
        out: &mut [T],
    ) {
        assert_eq!(out.len(), self.plan.outputs.len(), "one slot per output");
        self.plan.run(theta, trig, theta_dot, slots);
        for (o, &i) in out.iter_mut().zip(&self.plan.outputs) {
            *o = slots[i as usize];
        }
    }

    /// The degree of output `i` in θ̇ when it is written as a polynomial in
    /// θ̇ with θ-only coefficients: divisions only by θ-only subexpressions,
    /// functions only of θ-only arguments, integer powers of polynomials.
    /// The degree is syntactic (`theta_dot - theta_dot` has degree 1). `None`
    /// otherwise, or for no such output.
    pub fn theta_dot_degree(&self, i: usize) -> Option<u32> {
        self.outputs.get(i).and_then(|&o| self.degree[o as usize])
    }

    /// The tape as text of the expression language, evaluated operation by
    /// operation exactly as [`Program::eval`] does: one definition
    /// `{prefix}{k}` per operation (variables as `t` and `w`, constants as
    /// the text they were enclosed from), and each output as a name or an
    /// atom. `prefix` must not begin any parameter's name.
    pub fn render(&self, prefix: &str) -> (Vec<(String, String)>, Vec<String>) {
        let mut text: Vec<String> = Vec::with_capacity(self.tape.len());
        let mut defs = Vec::new();
        for (j, node) in self.tape.iter().enumerate() {
            let t = |a: u32| text[a as usize].as_str();
            let body = match *node {
                Node::Const(k) => {
                    text.push(self.const_text[k as usize].clone());
                    continue;
                }
                Node::Theta => {
                    text.push("t".into());
                    continue;
                }
                Node::ThetaDot => {
                    text.push("w".into());
                    continue;
                }
                Node::Neg(a) => format!("-{}", t(a)),
                Node::Add(a, b) => format!("{} + {}", t(a), t(b)),
                Node::Sub(a, b) => format!("{} - {}", t(a), t(b)),
                Node::Mul(a, b) => format!("{}*{}", t(a), t(b)),
                Node::Div(a, b) => format!("{}/{}", t(a), t(b)),
                Node::Sqr(a) => format!("{}^2", t(a)),
                Node::Pown(a, n) => format!("{}^{n}", t(a)),
                Node::Call(f, a) => format!("{}({})", f.name(), t(a)),
                Node::Call2(f, a, b) => format!("{}({}, {})", f.name(), t(a), t(b)),
            };
            let name = format!("{prefix}{j}");
            defs.push((name.clone(), body));
            text.push(name);
        }
        let outputs = self
            .outputs
            .iter()
            .map(|&o| text[o as usize].clone())
            .collect();
        (defs, outputs)
    }
}

/// A parameter-only operation that is undefined for the parameters given.
#[derive(Clone, Debug, PartialEq)]
pub struct ConstantIssue {
    /// Proved undefined (its enclosure is empty: `1/0`, `sqrt` of a negative
    /// number, `ln` of one ≤ 0), so every formula using it is undefined
    /// everywhere; otherwise it only may be (an operand's enclosure reaches a
    /// point where the operation is undefined, e.g. it contains 0 but is not
    /// exactly 0).
    pub proved: bool,
    /// The operation as text, parameters by name.
    pub text: String,
    /// The parameters it depends on, in tape order.
    pub params: Vec<String>,
}

impl Program {
    /// Every operation evaluated once over the whole domain `theta` ×
    /// `theta_dot` in decorated intervals. An empty result from non-empty
    /// operands (a division by exactly 0, `sqrt` of a value below 0 all over
    /// the domain, ...) is proved undefined at every point. An operation on
    /// parameters alone that is not defined while its operands are, or a
    /// division by a parameter-only value that contains 0, only may be.
    /// Parameters are the constants whose text is a name other than `pi`.
    pub fn constant_issues(&self, theta: Interval, theta_dot: Interval) -> Vec<ConstantIssue> {
        // Every entry, nothing folded.
        let plan = Plan::new(&self.tape, &self.consts, &self.outputs, false);
        let (t, w) = (DecInterval::new(theta), DecInterval::new(theta_dot));
        let mut values = vec![t; plan.len];
        plan.run(t, None, w, &mut values);
        let slots: Vec<DecInterval> = plan.slot.iter().map(|&k| values[k as usize]).collect();
        let empty = |x: DecInterval| x.interval().is_none_or(|i| i.is_empty());
        let mut on_var = vec![false; self.tape.len()];
        let mut issues = Vec::new();
        let mut issue = |j: usize, proved: bool, from: u32| {
            let mut params = Vec::new();
            self.const_names(from, &mut params);
            issues.push(ConstantIssue {
                proved,
                text: self.infix(j as u32),
                params,
            });
        };
        for (j, node) in self.tape.iter().enumerate() {
            let ops = node.operands();
            on_var[j] = matches!(node, Node::Theta | Node::ThetaDot)
                || ops.iter().flatten().any(|&a| on_var[a as usize]);
            if matches!(node, Node::Const(_)) {
                continue;
            }
            if empty(slots[j]) {
                if ops.iter().flatten().all(|&a| !empty(slots[a as usize])) {
                    issue(j, true, j as u32);
                }
                continue;
            }
            // A division by a parameter-only divisor that may be 0 may fail
            // whatever the variables are.
            if let Node::Div(_, b) = *node {
                let x = slots[b as usize];
                let zero = x.interval().is_some_and(|x| x.contains(0.0));
                if on_var[j] && !on_var[b as usize] && is_defined(x) && zero {
                    issue(j, false, b);
                }
            }
            let defined_ops = ops.iter().flatten().all(|&a| is_defined(slots[a as usize]));
            if !on_var[j] && !is_defined(slots[j]) && defined_ops {
                issue(j, false, j as u32);
            }
        }
        issues
    }

    /// Entry `j` as infix text (compound operands in parentheses), cut
    /// after about 120 characters: shared definitions can make the full text
    /// exponentially long.
    fn infix(&self, j: u32) -> String {
        let mut out = String::new();
        self.write_infix(j, &mut out);
        if out.len() > 120 {
            let mut cut = 120;
            while !out.is_char_boundary(cut) {
                cut -= 1;
            }
            out.truncate(cut);
            out.push('…');
        }
        out
    }

    /// Every call appends at least one character or returns at once past
    /// the budget, so the work is bounded however deep the sharing.
    fn write_infix(&self, j: u32, out: &mut String) {
        if out.len() > 120 {
            return;
        }
        let operand = |a: u32, out: &mut String| match self.tape[a as usize] {
            Node::Const(_)
            | Node::Theta
            | Node::ThetaDot
            | Node::Call(..)
            | Node::Call2(..)
            | Node::Sqr(_)
            | Node::Pown(..) => self.write_infix(a, out),
            _ => {
                out.push('(');
                self.write_infix(a, out);
                out.push(')');
            }
        };
        match self.tape[j as usize] {
            Node::Const(k) => out.push_str(&self.const_text[k as usize]),
            Node::Theta => out.push_str(THETA),
            Node::ThetaDot => out.push_str(THETA_DOT),
            Node::Neg(a) => {
                out.push('-');
                operand(a, out);
            }
            Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) | Node::Div(a, b) => {
                operand(a, out);
                out.push_str(match self.tape[j as usize] {
                    Node::Add(..) => " + ",
                    Node::Sub(..) => " - ",
                    Node::Mul(..) => "*",
                    _ => "/",
                });
                operand(b, out);
            }
            Node::Sqr(a) => {
                operand(a, out);
                out.push_str("^2");
            }
            Node::Pown(a, n) => {
                operand(a, out);
                out.push_str(&format!("^{n}"));
            }
            Node::Call(f, a) => {
                out.push_str(f.name());
                out.push('(');
                self.write_infix(a, out);
                out.push(')');
            }
            Node::Call2(f, a, b) => {
                out.push_str(f.name());
                out.push('(');
                self.write_infix(a, out);
                out.push_str(", ");
                self.write_infix(b, out);
                out.push(')');
            }
        }
    }

    /// The parameter names entry `j` depends on, each once, in tape order.
    fn const_names(&self, j: u32, names: &mut Vec<String>) {
        let mut needed = vec![false; j as usize + 1];
        needed[j as usize] = true;
        for i in (0..=j as usize).rev() {
            if needed[i] {
                for a in self.tape[i].operands().into_iter().flatten() {
                    needed[a as usize] = true;
                }
            }
        }
        for (i, node) in self.tape[..=j as usize].iter().enumerate() {
            if let (true, Node::Const(k)) = (needed[i], node) {
                let t = &self.const_text[*k as usize];
                if t.starts_with(|c: char| c.is_ascii_alphabetic()) && t != "pi" {
                    names.push(t.clone());
                }
            }
        }
    }
}
