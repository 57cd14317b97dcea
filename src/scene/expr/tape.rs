//! The flattened tape: evaluation over any [`Scalar`], its text for proofs,
//! and the analysis of parameter-only operations.

use super::graph::Node;
use super::parse::Func;
use super::{THETA, THETA_DOT};
use crate::number::scalar::{is_defined, Scalar};
use inari::{DecInterval, Interval};
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
    /// Per entry: whether it is half of a `sin`/`cos` pair on one operand.
    fused: Vec<Fused>,
}

/// `sin(a)` and `cos(a)` both on the tape: the first of the two computes
/// both slots, the second is skipped.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Fused {
    Alone,
    SinCos { a: u32, sin: u32, cos: u32 },
    Done,
}

fn fuse_sin_cos(tape: &[Node]) -> Vec<Fused> {
    let mut fused = vec![Fused::Alone; tape.len()];
    let mut sin_of: HashMap<u32, u32> = HashMap::new();
    for (j, node) in tape.iter().enumerate() {
        if let Node::Call(Func::Sin, a) = *node {
            sin_of.insert(a, j as u32);
        }
    }
    for (j, node) in tape.iter().enumerate() {
        if let Node::Call(Func::Cos, a) = *node {
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
        let fused = fuse_sin_cos(&tape);
        Program {
            tape,
            consts,
            const_text,
            outputs,
            fused,
            on_dot,
            degree,
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
        // Small tapes (every shipped scene's) evaluate without allocating.
        const STACK: usize = 96;
        if self.tape.len() <= STACK {
            let mut slots = [T::int(0); STACK];
            self.eval_into(theta, trig, theta_dot, &mut slots[..self.tape.len()], out);
        } else {
            let mut slots = vec![T::int(0); self.tape.len()];
            self.eval_into(theta, trig, theta_dot, &mut slots, out);
        }
    }

    /// [`Program::eval`] into `slots` (one per tape entry). `sin` and `cos`
    /// of the same operand are computed together ([`Scalar::sin_cos`]: the
    /// same enclosures, one kernel call, and duals reuse both).
    fn eval_into<T: Scalar>(
        &self,
        theta: T,
        trig: Option<(T, T)>,
        theta_dot: T,
        slots: &mut [T],
        out: &mut [T],
    ) {
        assert_eq!(out.len(), self.outputs.len(), "one slot per output");
        for (j, &node) in self.tape.iter().enumerate() {
            match self.fused[j] {
                Fused::Alone => {}
                Fused::Done => continue,
                Fused::SinCos { a, sin, cos } => {
                    let (sv, cv) = match (trig, self.tape[a as usize]) {
                        (Some(sc), Node::Theta) => sc,
                        _ => slots[a as usize].sin_cos(),
                    };
                    slots[sin as usize] = sv;
                    slots[cos as usize] = cv;
                    continue;
                }
            }
            // Operands are earlier entries, already computed.
            let s = |a: u32| slots[a as usize];
            let v = match node {
                Node::Const(k) => T::lift(self.consts[k as usize]),
                Node::Theta => theta,
                Node::ThetaDot => theta_dot,
                Node::Neg(a) => -s(a),
                Node::Add(a, b) => s(a) + s(b),
                Node::Sub(a, b) => s(a) - s(b),
                Node::Mul(a, b) => s(a) * s(b),
                Node::Div(a, b) => s(a) / s(b),
                Node::Sqr(a) => s(a).sqr(),
                Node::Pown(a, n) => s(a).pown(n),
                Node::Call(f @ (Func::Sin | Func::Cos), a)
                    if trig.is_some() && self.tape[a as usize] == Node::Theta =>
                {
                    let (sv, cv) = trig.expect("checked");
                    if f == Func::Sin {
                        sv
                    } else {
                        cv
                    }
                }
                Node::Call(f, a) => {
                    let x = s(a);
                    match f {
                        Func::Sqrt => x.sqrt(),
                        Func::Sin => x.sin(),
                        Func::Cos => x.cos(),
                        Func::Tan => x.tan(),
                        Func::Ln => x.ln(),
                        Func::Abs => x.abs(),
                        Func::Atan => x.atan(),
                        Func::Exp => x.exp(),
                        Func::Sign => x.sign(),
                        Func::Min | Func::Max => unreachable!("two arguments: Call2"),
                    }
                }
                Node::Call2(f, a, b) => match f {
                    Func::Min => s(a).min(s(b)),
                    _ => s(a).max(s(b)),
                },
            };
            slots[j] = v;
        }
        for (o, &i) in out.iter_mut().zip(&self.outputs) {
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
        let mut slots = vec![DecInterval::ENTIRE; self.tape.len()];
        let mut out = vec![DecInterval::ENTIRE; self.outputs.len()];
        let (t, w) = (DecInterval::new(theta), DecInterval::new(theta_dot));
        self.eval_into(t, None, w, &mut slots, &mut out);
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
