//! User expressions compiled to a tape with shared subexpressions.
//!
//! A scene file gives parameters (already enclosed), named definitions in any
//! order and output expressions, written in the language of
//! `proofs/FORMAT.md` ("Expressions") with the variables `theta` and
//! `theta_dot`. Each text is parsed to postfix steps, lowered into one
//! hash-consed DAG (the same operation on the same operands is one node, and a
//! definition is one node wherever it is named), and the nodes the outputs
//! need are flattened into a tape evaluated over any [`Scalar`].
//!
//! Nothing is rewritten or folded: every node is one operation of the text,
//! left-associative, in the order written, so an interval evaluation of the
//! tape gives the enclosure the checker computes for the same text.

use crate::number::param::{enclose_decimal, ParamError};
use crate::number::scalar::{is_defined, Scalar};
use inari::{DecInterval, Interval};
use std::collections::{HashMap, HashSet};
use std::fmt;

mod factor;
pub use factor::FactorOf;

/// Longest expression text accepted (as in `proofs/FORMAT.md`).
pub const MAX_EXPR_LEN: usize = 10_000;
/// Deepest nesting of parentheses, calls and unary minus accepted.
pub const MAX_DEPTH: usize = 100;

const FUNCTIONS: [&str; 11] = [
    "sqrt", "sin", "cos", "tan", "ln", "abs", "atan", "exp", "sign", "min", "max",
];
const THETA: &str = "theta";
const THETA_DOT: &str = "theta_dot";
/// Names a parameter or definition may not take besides the functions: the
/// variables, also under the names `t`, `w` a proof file binds them to,
/// `pi`, and `inf`, reserved in proof files (where `"inf"` is an unbounded end).
const RESERVED: [&str; 6] = ["t", "w", "pi", "inf", THETA, THETA_DOT];

/// A mistake in one expression or name: `key` is the definition, parameter
/// or output name, `offset` the 1-based character position when there is one.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExprError {
    pub key: String,
    pub offset: Option<usize>,
    pub message: String,
}

impl fmt::Display for ExprError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.offset {
            Some(n) => write!(f, "`{}` at character {n}: {}", self.key, self.message),
            None => write!(f, "`{}`: {}", self.key, self.message),
        }
    }
}

impl std::error::Error for ExprError {}

/// A mistake inside one text: byte offset (if any) and message.
type Fail = (Option<usize>, String);

fn error(key: &str, text: &str, (at, message): Fail) -> ExprError {
    // Byte offsets always fall on character boundaries (the lexer only steps
    // over ASCII), so counting the characters before one is exact.
    let offset = at.map(|b| text.get(..b).map_or(b, |s| s.chars().count()) + 1);
    ExprError {
        key: key.to_string(),
        offset,
        message,
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Tok<'a> {
    Num(&'a str),
    Name(&'a str),
    Plus,
    Minus,
    Star,
    Slash,
    Caret,
    LParen,
    RParen,
    Comma,
}

fn describe(t: Tok) -> String {
    match t {
        Tok::Num(s) => format!("number {s}"),
        Tok::Name(s) => format!("name `{s}`"),
        Tok::Plus => "'+'".into(),
        Tok::Minus => "'-'".into(),
        Tok::Star => "'*'".into(),
        Tok::Slash => "'/'".into(),
        Tok::Caret => "'^'".into(),
        Tok::LParen => "'('".into(),
        Tok::RParen => "')'".into(),
        Tok::Comma => "','".into(),
    }
}

/// Tokens with their byte offsets; the lexical rules of the checker's
/// lexer (an `e` not followed by digits ends the number before it).
fn lex(text: &str) -> Result<Vec<(Tok<'_>, usize)>, Fail> {
    let b = text.as_bytes();
    let digits = |mut j: usize| {
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
        }
        j
    };
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let start = i;
        let tok = match b[i] {
            b' ' | b'\t' | b'\n' | b'\r' => {
                i += 1;
                continue;
            }
            b'+' => Tok::Plus,
            b'-' => Tok::Minus,
            b'*' => Tok::Star,
            b'/' => Tok::Slash,
            b'^' => Tok::Caret,
            b'(' => Tok::LParen,
            b')' => Tok::RParen,
            b',' => Tok::Comma,
            // Digits with an optional point, at least one digit before or
            // after it (`1`, `1.5`, `1.`, `.5`), as FORMAT.md's `number`.
            b'0'..=b'9' | b'.' => {
                i = digits(i);
                if b.get(i) == Some(&b'.') {
                    let j = digits(i + 1);
                    if i == start && j == i + 1 {
                        return Err((Some(i), "digits expected before or after '.'".into()));
                    }
                    i = j;
                }
                if matches!(b.get(i), Some(b'e' | b'E')) {
                    let mut j = i + 1;
                    if matches!(b.get(j), Some(b'+' | b'-')) {
                        j += 1;
                    }
                    let k = digits(j);
                    if k > j {
                        i = k;
                    }
                }
                out.push((Tok::Num(&text[start..i]), start));
                continue;
            }
            c if c.is_ascii_alphabetic() => {
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                    i += 1;
                }
                out.push((Tok::Name(&text[start..i]), start));
                continue;
            }
            _ => {
                let ch = text[i..].chars().next().unwrap_or('?');
                return Err((Some(i), format!("unexpected character {ch:?}")));
            }
        };
        out.push((tok, start));
        i += 1;
    }
    Ok(out)
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Func {
    Sqrt,
    Sin,
    Cos,
    Tan,
    Ln,
    Abs,
    Atan,
    Exp,
    Sign,
    /// `min(a, b)` and `max(a, b)`: the two functions of two arguments.
    Min,
    Max,
}

impl Func {
    fn name(self) -> &'static str {
        match self {
            Func::Sqrt => "sqrt",
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Ln => "ln",
            Func::Abs => "abs",
            Func::Atan => "atan",
            Func::Exp => "exp",
            Func::Sign => "sign",
            Func::Min => "min",
            Func::Max => "max",
        }
    }

    fn of(name: &str) -> Option<Func> {
        Some(match name {
            "sqrt" => Func::Sqrt,
            "sin" => Func::Sin,
            "cos" => Func::Cos,
            "tan" => Func::Tan,
            "ln" => Func::Ln,
            "abs" => Func::Abs,
            "atan" => Func::Atan,
            "exp" => Func::Exp,
            "sign" => Func::Sign,
            "min" => Func::Min,
            "max" => Func::Max,
            _ => return None,
        })
    }
}

/// One step of an expression in postfix order (operands before operators).
#[derive(Clone, Debug)]
enum Step<'a> {
    /// A literal's enclosure and its text.
    Num(Interval, &'a str),
    /// A name and its byte offset.
    Name(&'a str, usize),
    Neg,
    Add,
    Sub,
    Mul,
    Div,
    Pow(u32),
    Call(Func),
}

/// Recursive descent over the grammar of FORMAT.md; recursion is bounded by
/// the nesting depth, which is limited, and the output is flat.
struct Parser<'a> {
    toks: Vec<(Tok<'a>, usize)>,
    pos: usize,
    depth: usize,
    /// Byte length of the text: the offset of "end of expression".
    end: usize,
    steps: Vec<Step<'a>>,
}

impl<'a> Parser<'a> {
    fn peek(&self) -> Option<Tok<'a>> {
        self.toks.get(self.pos).map(|t| t.0)
    }

    /// Byte offset of the current token (or the end).
    fn at(&self) -> usize {
        self.toks.get(self.pos).map_or(self.end, |t| t.1)
    }

    fn enter(&mut self, at: usize) -> Result<(), Fail> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err((Some(at), format!("nested more than {MAX_DEPTH} deep")));
        }
        Ok(())
    }

    fn expect_close(&mut self, what: &str) -> Result<(), Fail> {
        if self.peek() == Some(Tok::RParen) {
            self.pos += 1;
            return Ok(());
        }
        let found = self.peek().map_or("end of expression".into(), describe);
        Err((
            Some(self.at()),
            format!("')' expected {what}, found {found}"),
        ))
    }

    fn expr(&mut self) -> Result<(), Fail> {
        self.term()?;
        loop {
            let step = match self.peek() {
                Some(Tok::Plus) => Step::Add,
                Some(Tok::Minus) => Step::Sub,
                _ => return Ok(()),
            };
            self.pos += 1;
            self.term()?;
            self.steps.push(step);
        }
    }

    fn term(&mut self) -> Result<(), Fail> {
        self.unary()?;
        loop {
            let step = match self.peek() {
                Some(Tok::Star) => Step::Mul,
                Some(Tok::Slash) => Step::Div,
                _ => return Ok(()),
            };
            self.pos += 1;
            self.unary()?;
            self.steps.push(step);
        }
    }

    fn unary(&mut self) -> Result<(), Fail> {
        if self.peek() == Some(Tok::Minus) {
            let at = self.at();
            self.pos += 1;
            self.enter(at)?;
            self.unary()?;
            self.depth -= 1;
            self.steps.push(Step::Neg);
            return Ok(());
        }
        self.power()
    }

    fn power(&mut self) -> Result<(), Fail> {
        self.atom()?;
        if self.peek() != Some(Tok::Caret) {
            return Ok(());
        }
        self.pos += 1;
        let at = self.at();
        let n = match self.peek() {
            Some(Tok::Num(t)) if t.bytes().all(|c| c.is_ascii_digit()) => t
                .parse::<i32>()
                .ok()
                .and_then(|n| u32::try_from(n).ok())
                .ok_or_else(|| (Some(at), format!("exponent {t} too large")))?,
            _ => {
                let msg = "'^' must be followed by a non-negative integer literal";
                return Err((Some(at), msg.into()));
            }
        };
        self.pos += 1;
        if self.peek() == Some(Tok::Caret) {
            let msg = "x^a^b is ambiguous; write (x^a)^b";
            return Err((Some(self.at()), msg.into()));
        }
        self.steps.push(Step::Pow(n));
        Ok(())
    }

    fn atom(&mut self) -> Result<(), Fail> {
        let at = self.at();
        let Some(tok) = self.peek() else {
            return Err((Some(at), "unexpected end of expression".into()));
        };
        self.pos += 1;
        match tok {
            Tok::Num(t) => {
                let x = enclose_decimal("", t).map_err(|e| {
                    let why = match e {
                        ParamError::TooLarge { .. } => "is too large for double precision",
                        ParamError::TooSmall { .. } => {
                            "is too small for double precision (nonzero, below 4.9e-324)"
                        }
                        _ => "is not a finite decimal number",
                    };
                    (Some(at), format!("{t} {why}"))
                })?;
                self.steps.push(Step::Num(x, t));
            }
            Tok::LParen => {
                self.enter(at)?;
                self.expr()?;
                self.depth -= 1;
                self.expect_close("to close the '('")?;
            }
            Tok::Name(n) => match Func::of(n) {
                Some(f) => {
                    let open = self.at();
                    if self.peek() != Some(Tok::LParen) {
                        return Err((Some(open), format!("'(' expected after {n}")));
                    }
                    self.pos += 1;
                    self.enter(open)?;
                    self.expr()?;
                    if matches!(f, Func::Min | Func::Max) {
                        if self.peek() != Some(Tok::Comma) {
                            let msg = format!("',' expected: {n} takes two arguments");
                            return Err((Some(self.at()), msg));
                        }
                        self.pos += 1;
                        self.expr()?;
                    }
                    self.depth -= 1;
                    self.expect_close(&format!("to close {n}("))?;
                    self.steps.push(Step::Call(f));
                }
                None if self.peek() == Some(Tok::LParen) => {
                    return Err((Some(at), format!("unknown function `{n}`")));
                }
                None => self.steps.push(Step::Name(n, at)),
            },
            t => return Err((Some(at), format!("unexpected {}", describe(t)))),
        }
        Ok(())
    }
}

/// Parses one text into postfix steps; errors carry `key`.
fn parse<'a>(key: &str, text: &'a str) -> Result<Vec<Step<'a>>, ExprError> {
    if text.len() > MAX_EXPR_LEN {
        let msg = format!("expression longer than {MAX_EXPR_LEN} characters");
        return Err(error(key, text, (None, msg)));
    }
    let toks = lex(text).map_err(|e| error(key, text, e))?;
    if toks.is_empty() {
        return Err(error(key, text, (None, "empty expression".into())));
    }
    let mut p = Parser {
        toks,
        pos: 0,
        depth: 0,
        end: text.len(),
        steps: Vec::new(),
    };
    p.expr().map_err(|e| error(key, text, e))?;
    if let Some(t) = p.peek() {
        let msg = match t {
            Tok::RParen => "')' without a matching '('".to_string(),
            t => format!("unexpected {}", describe(t)),
        };
        return Err(error(key, text, (Some(p.at()), msg)));
    }
    Ok(p.steps)
}

/// True when `s` is a name of the grammar: a letter, then letters, digits, `_`.
fn is_name(s: &str) -> bool {
    let mut c = s.chars();
    matches!(c.next(), Some(f) if f.is_ascii_alphabetic())
        && c.all(|x| x.is_ascii_alphanumeric() || x == '_')
}

fn check_name(name: &str, declared: &HashSet<&str>) -> Result<(), ExprError> {
    let fail = |message: String| ExprError {
        key: name.to_string(),
        offset: None,
        message,
    };
    if !is_name(name) {
        return Err(fail(
            "not a valid name (a letter, then letters, digits or '_')".into(),
        ));
    }
    if RESERVED.contains(&name) || FUNCTIONS.contains(&name) {
        return Err(fail("the name is reserved".into()));
    }
    if declared.contains(name) {
        return Err(fail("the name is declared twice".into()));
    }
    Ok(())
}

/// One operation; operands are indices of earlier nodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Node {
    /// Index into the constant table.
    Const(u32),
    Theta,
    ThetaDot,
    Neg(u32),
    Add(u32, u32),
    Sub(u32, u32),
    Mul(u32, u32),
    Div(u32, u32),
    /// `x^2`, the interval square.
    Sqr(u32),
    /// `x^n`, n ≠ 2.
    Pown(u32, u32),
    Call(Func, u32),
    /// `min(a, b)`, `max(a, b)`.
    Call2(Func, u32, u32),
}

impl Node {
    fn operands(self) -> [Option<u32>; 2] {
        match self {
            Node::Const(_) | Node::Theta | Node::ThetaDot => [None, None],
            Node::Add(a, b)
            | Node::Sub(a, b)
            | Node::Mul(a, b)
            | Node::Div(a, b)
            | Node::Call2(_, a, b) => [Some(a), Some(b)],
            Node::Neg(a) | Node::Sqr(a) | Node::Pown(a, _) | Node::Call(_, a) => [Some(a), None],
        }
    }

    /// The same operation on renamed operands (constants left alone).
    fn map(self, f: impl Fn(u32) -> u32) -> Node {
        match self {
            Node::Const(_) | Node::Theta | Node::ThetaDot => self,
            Node::Neg(a) => Node::Neg(f(a)),
            Node::Add(a, b) => Node::Add(f(a), f(b)),
            Node::Sub(a, b) => Node::Sub(f(a), f(b)),
            Node::Mul(a, b) => Node::Mul(f(a), f(b)),
            Node::Div(a, b) => Node::Div(f(a), f(b)),
            Node::Sqr(a) => Node::Sqr(f(a)),
            Node::Pown(a, n) => Node::Pown(f(a), n),
            Node::Call(g, a) => Node::Call(g, f(a)),
            Node::Call2(g, a, b) => Node::Call2(g, f(a), f(b)),
        }
    }
}

/// A coefficient of a polynomial in θ̇ while it is built: exact 0 and 1 stay
/// symbolic so that they never become operations.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Coef {
    Zero,
    One,
    Node(u32),
}

/// Coefficients of θ̇⁰, θ̇¹, θ̇².
type Poly = [Coef; 3];

/// Hash-consed nodes: node ids are in topological order by construction.
#[derive(Default)]
struct Dag {
    nodes: Vec<Node>,
    index: HashMap<Node, u32>,
    consts: Vec<Interval>,
    /// Per constant: text that encloses to it exactly (a literal, a
    /// parameter's name, `pi`), for [`Program::render`].
    const_text: Vec<String>,
    const_index: HashMap<(u64, u64), u32>,
}

impl Dag {
    fn push(&mut self, n: Node) -> u32 {
        if let Some(&i) = self.index.get(&n) {
            return i;
        }
        let i = self.nodes.len() as u32;
        self.nodes.push(n);
        self.index.insert(n, i);
        i
    }

    fn constant(&mut self, x: Interval, text: &str) -> u32 {
        let key = (x.inf().to_bits(), x.sup().to_bits());
        let k = match self.const_index.get(&key) {
            Some(&k) => k,
            None => {
                let k = self.consts.len() as u32;
                self.consts.push(x);
                self.const_text.push(text.to_string());
                self.const_index.insert(key, k);
                k
            }
        };
        self.push(Node::Const(k))
    }

    /// A parameter: a constant of its own, never shared with a literal or
    /// another parameter of the same value, so that it keeps its name.
    fn parameter(&mut self, x: Interval, name: &str) -> u32 {
        let k = self.consts.len() as u32;
        self.consts.push(x);
        self.const_text.push(name.to_string());
        self.push(Node::Const(k))
    }

    /// Lowers postfix steps; every name must be in `scope`.
    fn lower(&mut self, steps: &[Step], scope: &HashMap<&str, u32>) -> Result<u32, Fail> {
        let mut stack: Vec<u32> = Vec::new();
        // The parser emits well-formed postfix; a short stack is a bug, but
        // reported, not a panic.
        let internal = || (None, "internal: malformed expression".to_string());
        for step in steps {
            let node = match *step {
                Step::Num(x, text) => {
                    stack.push(self.constant(x, text));
                    continue;
                }
                Step::Name(n, at) => {
                    let id = scope
                        .get(n)
                        .ok_or_else(|| (Some(at), format!("unknown name `{n}`")))?;
                    stack.push(*id);
                    continue;
                }
                Step::Call(f @ (Func::Min | Func::Max)) => {
                    let b = stack.pop().ok_or_else(internal)?;
                    let a = stack.pop().ok_or_else(internal)?;
                    Node::Call2(f, a, b)
                }
                Step::Neg | Step::Pow(_) | Step::Call(_) => {
                    let a = stack.pop().ok_or_else(internal)?;
                    match *step {
                        Step::Neg => Node::Neg(a),
                        Step::Pow(2) => Node::Sqr(a),
                        Step::Pow(n) => Node::Pown(a, n),
                        Step::Call(f) => Node::Call(f, a),
                        _ => return Err(internal()),
                    }
                }
                Step::Add | Step::Sub | Step::Mul | Step::Div => {
                    let b = stack.pop().ok_or_else(internal)?;
                    let a = stack.pop().ok_or_else(internal)?;
                    match *step {
                        Step::Add => Node::Add(a, b),
                        Step::Sub => Node::Sub(a, b),
                        Step::Mul => Node::Mul(a, b),
                        _ => Node::Div(a, b),
                    }
                }
            };
            stack.push(self.push(node));
        }
        match stack[..] {
            [x] => Ok(x),
            _ => Err(internal()),
        }
    }

    fn coef_node(&mut self, c: Coef) -> u32 {
        match c {
            Coef::Zero => self.constant(Interval::try_from((0.0, 0.0)).expect("exact"), "0"),
            Coef::One => self.constant(Interval::try_from((1.0, 1.0)).expect("exact"), "1"),
            Coef::Node(n) => n,
        }
    }

    fn op(&mut self, n: Node) -> Coef {
        Coef::Node(self.push(n))
    }

    fn add(&mut self, a: Coef, b: Coef) -> Coef {
        match (a, b) {
            (Coef::Zero, x) | (x, Coef::Zero) => x,
            _ => {
                let (a, b) = (self.coef_node(a), self.coef_node(b));
                self.op(Node::Add(a, b))
            }
        }
    }

    fn sub(&mut self, a: Coef, b: Coef) -> Coef {
        match (a, b) {
            (x, Coef::Zero) => x,
            (Coef::Zero, x) => self.neg(x),
            _ => {
                let (a, b) = (self.coef_node(a), self.coef_node(b));
                self.op(Node::Sub(a, b))
            }
        }
    }

    fn neg(&mut self, a: Coef) -> Coef {
        match a {
            Coef::Zero => Coef::Zero,
            _ => {
                let a = self.coef_node(a);
                self.op(Node::Neg(a))
            }
        }
    }

    fn mul(&mut self, a: Coef, b: Coef) -> Coef {
        match (a, b) {
            (Coef::Zero, _) | (_, Coef::Zero) => Coef::Zero,
            (Coef::One, x) | (x, Coef::One) => x,
            (Coef::Node(a), Coef::Node(b)) => self.op(Node::Mul(a, b)),
        }
    }

    fn div(&mut self, a: Coef, b: u32) -> Coef {
        match a {
            Coef::Zero => Coef::Zero,
            _ => {
                let a = self.coef_node(a);
                self.op(Node::Div(a, b))
            }
        }
    }

    /// `p·q`, `None` if a term of degree above 2 is not exactly 0.
    fn poly_mul(&mut self, p: Poly, q: Poly) -> Option<Poly> {
        let mut r = [Coef::Zero; 3];
        for (i, &a) in p.iter().enumerate() {
            for (j, &b) in q.iter().enumerate() {
                let t = self.mul(a, b);
                if t == Coef::Zero {
                    continue;
                }
                let k = r.get_mut(i + j)?;
                let sum = (*k, t);
                *k = self.add(sum.0, sum.1);
            }
        }
        Some(r)
    }

    /// The program of the nodes `outputs` needs, in id order.
    fn program(&self, outputs: &[u32]) -> Program {
        let mut needed = vec![false; self.nodes.len()];
        for &o in outputs {
            needed[o as usize] = true;
        }
        // Operands precede their users: one backward sweep marks them all.
        for i in (0..self.nodes.len()).rev() {
            if needed[i] {
                for a in self.nodes[i].operands().into_iter().flatten() {
                    needed[a as usize] = true;
                }
            }
        }
        let mut slot = vec![u32::MAX; self.nodes.len()];
        let mut const_slot: HashMap<u32, u32> = HashMap::new();
        let mut tape = Vec::new();
        let mut consts = Vec::new();
        let mut const_text = Vec::new();
        for (i, node) in self.nodes.iter().enumerate() {
            if !needed[i] {
                continue;
            }
            let n = match *node {
                Node::Const(k) => Node::Const(*const_slot.entry(k).or_insert_with(|| {
                    consts.push(self.consts[k as usize]);
                    const_text.push(self.const_text[k as usize].clone());
                    consts.len() as u32 - 1
                })),
                n => n.map(|a| slot[a as usize]),
            };
            slot[i] = tape.len() as u32;
            tape.push(n);
        }
        let outputs = outputs.iter().map(|&o| slot[o as usize]).collect();
        Program::new(tape, consts, const_text, outputs)
    }
}

/// Definitions in an order where each comes after those it names, or the
/// first cycle found, reported on its first definition.
fn definition_order(
    refs: &[Vec<(usize, usize)>],
    definitions: &[(String, String)],
) -> Result<Vec<usize>, ExprError> {
    const NEW: u8 = 0;
    const ON_PATH: u8 = 1;
    const DONE: u8 = 2;
    let mut state = vec![NEW; refs.len()];
    let mut order = Vec::with_capacity(refs.len());
    // (definition, how many of its references have been followed)
    let mut path: Vec<(usize, usize)> = Vec::new();
    for root in 0..refs.len() {
        if state[root] != NEW {
            continue;
        }
        state[root] = ON_PATH;
        path.push((root, 0));
        while let Some(top) = path.last_mut() {
            let d = top.0;
            let Some(&(e, _)) = refs[d].get(top.1) else {
                state[d] = DONE;
                order.push(d);
                path.pop();
                continue;
            };
            top.1 += 1;
            match state[e] {
                NEW => {
                    state[e] = ON_PATH;
                    path.push((e, 0));
                }
                ON_PATH => {
                    let start = path.iter().position(|p| p.0 == e).unwrap_or(0);
                    let mut names: Vec<&str> = path[start..]
                        .iter()
                        .map(|p| definitions[p.0].0.as_str())
                        .collect();
                    names.push(&definitions[e].0);
                    // Where `e` names the next definition of the cycle.
                    let at = path
                        .get(start)
                        .and_then(|p| refs[e].get(p.1.wrapping_sub(1)))
                        .map(|r| r.1);
                    let (name, text) = &definitions[e];
                    let msg = format!("definitions form a cycle: {}", names.join(" -> "));
                    return Err(error(name, text, (at, msg)));
                }
                _ => {}
            }
        }
    }
    Ok(order)
}

/// A compiled tape: each entry is one operation on earlier entries.
#[derive(Clone, Debug)]
pub struct Program {
    tape: Vec<Node>,
    consts: Vec<Interval>,
    const_text: Vec<String>,
    outputs: Vec<u32>,
    /// Per entry: whether it depends on θ̇.
    on_dot: Vec<bool>,
    /// Per entry: its degree in θ̇ when it is a polynomial in θ̇ with θ-only
    /// coefficients (written so: see [`Program::theta_dot_degree`]).
    degree: Vec<Option<u32>>,
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
    fn new(
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

    /// Compiles definitions (any order; each a name for one shared value)
    /// and output expressions over the given parameter enclosures.
    pub fn compile(
        params: &[(String, Interval)],
        definitions: &[(String, String)],
        outputs: &[(String, String)],
    ) -> Result<Program, ExprError> {
        let mut dag = Dag::default();
        let mut scope: HashMap<&str, u32> = HashMap::new();
        scope.insert(THETA, dag.push(Node::Theta));
        scope.insert(THETA_DOT, dag.push(Node::ThetaDot));
        scope.insert("pi", dag.constant(Interval::PI, "pi"));
        let mut declared: HashSet<&str> = HashSet::new();
        for (name, x) in params {
            check_name(name, &declared)?;
            declared.insert(name);
            scope.insert(name, dag.parameter(*x, name));
        }
        let mut def_index: HashMap<&str, usize> = HashMap::new();
        for (i, (name, _)) in definitions.iter().enumerate() {
            check_name(name, &declared)?;
            declared.insert(name);
            def_index.insert(name, i);
        }
        let parsed = definitions
            .iter()
            .map(|(name, text)| parse(name, text))
            .collect::<Result<Vec<_>, _>>()?;
        // Which definitions each one names, and where; other names must be
        // known already.
        let mut refs = Vec::with_capacity(definitions.len());
        for ((name, text), steps) in definitions.iter().zip(&parsed) {
            let mut r = Vec::new();
            for step in steps {
                if let Step::Name(n, at) = *step {
                    if let Some(&j) = def_index.get(n) {
                        r.push((j, at));
                    } else if !scope.contains_key(n) {
                        let msg = format!("unknown name `{n}`");
                        return Err(error(name, text, (Some(at), msg)));
                    }
                }
            }
            refs.push(r);
        }
        for i in definition_order(&refs, definitions)? {
            let (name, text) = &definitions[i];
            let id = dag
                .lower(&parsed[i], &scope)
                .map_err(|e| error(name, text, e))?;
            scope.insert(name, id);
        }
        let mut outs = Vec::with_capacity(outputs.len());
        for (key, text) in outputs {
            let steps = parse(key, text)?;
            let id = dag.lower(&steps, &scope).map_err(|e| error(key, text, e))?;
            outs.push(id);
        }
        Ok(dag.program(&outs))
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

    /// For an output of degree ≤ 2 in θ̇, a θ-only program with the three
    /// outputs `c2, c1, c0`: output = c2·θ̇² + c1·θ̇ + c0 as real functions.
    /// Built by polynomial arithmetic on the nodes; θ-only subexpressions
    /// are kept as they are, and exact 0 and 1 are never added or
    /// multiplied, so `A*theta_dot^2 + B*theta_dot + C` gives the nodes A, B,
    /// C themselves. A missing coefficient is the constant 0.
    pub fn quadratic(&self, i: usize) -> Option<Program> {
        self.quadratics(&[i])
    }

    /// [`Program::quadratic`] of several outputs in one program (outputs
    /// `c2, c1, c0` of each in turn), so that they share subexpressions.
    pub fn quadratics(&self, which: &[usize]) -> Option<Program> {
        self.coefficients(which, false)
    }

    /// [`Program::quadratics`] with each output's θ-only factor apart: five
    /// outputs `a, b, c2, c1, c0` per output, output = (a/b)·(c2·θ̇² + c1·θ̇ +
    /// c0) where the output is defined. The factor collects the θ̇-free
    /// operands of the products (into `a`), quotients (into `b`) and
    /// negations the output ends with (`a = b = 1` when there are none), as
    /// in `U/V` or `-(k*U)`: where the signs of `a` and `b` are known, the
    /// output's sign is that of the polynomial times theirs, and the
    /// polynomial's roots carry none of the factor's rounding (next to a zero
    /// of `V`, `U/V`'s coefficients have a large relative error, `U`'s do
    /// not).
    pub fn factored_quadratics(&self, which: &[usize]) -> Option<Program> {
        self.coefficients(which, true)
    }

    fn coefficients(&self, which: &[usize], factored: bool) -> Option<Program> {
        let mut outs = Vec::with_capacity(which.len());
        for &i in which {
            let out = *self.outputs.get(i)? as usize;
            if self.degree[out]? > 2 {
                return None;
            }
            outs.push(out);
        }
        let out = *outs.iter().max()?;
        let mut dag = Dag::default();
        let mut id: Vec<u32> = Vec::with_capacity(out + 1);
        let mut poly: Vec<Option<Poly>> = Vec::with_capacity(out + 1);
        for j in 0..=out {
            let node = self.tape[j];
            id.push(match node {
                Node::Const(k) => {
                    dag.constant(self.consts[k as usize], &self.const_text[k as usize])
                }
                n => dag.push(n.map(|a| id[a as usize])),
            });
            let p = |a: u32| poly[a as usize];
            let q = if !self.on_dot[j] {
                Some([Coef::Node(id[j]), Coef::Zero, Coef::Zero])
            } else if self.degree[j].is_none_or(|d| d > 2) {
                None
            } else {
                match node {
                    Node::ThetaDot => Some([Coef::Zero, Coef::One, Coef::Zero]),
                    Node::Neg(a) => p(a).map(|x| x.map(|c| dag.neg(c))),
                    Node::Add(a, b) => p(a)
                        .zip(p(b))
                        .map(|(x, y)| std::array::from_fn(|k| dag.add(x[k], y[k]))),
                    Node::Sub(a, b) => p(a)
                        .zip(p(b))
                        .map(|(x, y)| std::array::from_fn(|k| dag.sub(x[k], y[k]))),
                    Node::Mul(a, b) => p(a).zip(p(b)).and_then(|(x, y)| dag.poly_mul(x, y)),
                    Node::Div(a, b) => p(a).map(|x| x.map(|c| dag.div(c, id[b as usize]))),
                    Node::Sqr(a) => p(a).and_then(|x| dag.poly_mul(x, x)),
                    // x^0 is 1 whatever x's degree.
                    Node::Pown(_, 0) => Some([Coef::One, Coef::Zero, Coef::Zero]),
                    // A power of a θ̇-free polynomial: one power node.
                    Node::Pown(a, n) if self.degree[a as usize] == Some(0) => {
                        p(a).map(|x| match x[0] {
                            Coef::Node(c) => [dag.op(Node::Pown(c, n)), Coef::Zero, Coef::Zero],
                            c => [c, Coef::Zero, Coef::Zero],
                        })
                    }
                    // Degree ≥ 1 and n·degree ≤ 2: n ≤ 2 factors.
                    Node::Pown(a, n) => p(a).and_then(|x| {
                        let mut r = x;
                        for _ in 1..n {
                            r = dag.poly_mul(r, x)?;
                        }
                        Some(r)
                    }),
                    _ => None,
                }
            };
            poly.push(q);
        }
        let mut coefs = Vec::with_capacity(5 * outs.len());
        for o in outs {
            let (mut num, mut den, mut o) = (Coef::One, Coef::One, o);
            while factored && self.on_dot[o] {
                let dot = |a: u32| self.on_dot[a as usize];
                let k = |a: u32| Coef::Node(id[a as usize]);
                o = match self.tape[o] {
                    Node::Neg(a) => {
                        num = dag.neg(num);
                        a
                    }
                    Node::Mul(a, b) if !dot(a) => {
                        num = dag.mul(num, k(a));
                        b
                    }
                    Node::Mul(a, b) if !dot(b) => {
                        num = dag.mul(num, k(b));
                        a
                    }
                    Node::Div(a, b) if !dot(b) => {
                        den = dag.mul(den, k(b));
                        a
                    }
                    _ => break,
                } as usize;
            }
            let [c0, c1, c2] = poly[o]?;
            if factored {
                coefs.extend([num, den].map(|c| dag.coef_node(c)));
            }
            coefs.extend([c2, c1, c0].map(|c| dag.coef_node(c)));
        }
        Some(dag.program(&coefs))
    }
}

/// A constant expression enclosed: numbers, `pi`, parameters and functions,
/// nothing that depends on θ or θ̇ (a domain end such as `3*pi/2`). An error
/// names `key` when the text does not parse, uses a variable, or is not a
/// defined, finite real number.
pub fn enclose_constant(
    params: &[(String, Interval)],
    key: &str,
    text: &str,
) -> Result<Interval, ExprError> {
    let p = Program::compile(params, &[], &[(key.to_string(), text.to_string())])?;
    let fail = |message: &str| ExprError {
        key: key.to_string(),
        offset: None,
        message: format!("`{}` {message}", text.trim()),
    };
    if p.tape
        .iter()
        .any(|n| matches!(n, Node::Theta | Node::ThetaDot))
    {
        return Err(fail("must not depend on theta or theta_dot"));
    }
    let mut out = [DecInterval::ENTIRE];
    p.eval(DecInterval::ENTIRE, DecInterval::ENTIRE, &mut out);
    match out[0].interval() {
        Some(x) if is_defined(out[0]) && x.is_common_interval() => Ok(x),
        _ => Err(fail("is not a defined, finite number")),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::number::scalar::{Dual, DualN};
    use inari::Decoration;

    fn iv(a: f64, b: f64) -> Interval {
        Interval::try_from((a, b)).unwrap()
    }

    const PARAMS: [(&str, &str); 2] = [("g", "9.81"), ("mu", "0.5")];

    fn params() -> Vec<(String, Interval)> {
        PARAMS
            .iter()
            .map(|(n, t)| (n.to_string(), enclose_decimal(n, t).unwrap()))
            .collect()
    }

    fn pairs(list: &[(&str, &str)]) -> Vec<(String, String)> {
        list.iter()
            .map(|(a, b)| (a.to_string(), b.to_string()))
            .collect()
    }

    fn compile(defs: &[(&str, &str)], outs: &[&str]) -> Result<Program, ExprError> {
        let outs: Vec<(String, String)> = outs
            .iter()
            .enumerate()
            .map(|(i, t)| (format!("out{i}"), t.to_string()))
            .collect();
        Program::compile(&params(), &pairs(defs), &outs)
    }

    fn one(defs: &[(&str, &str)], text: &str) -> Program {
        compile(defs, &[text]).unwrap_or_else(|e| panic!("{text}: {e}"))
    }

    fn eval1<T: Scalar>(p: &Program, t: T, w: T) -> T {
        let mut out = [t];
        p.eval(t, w, &mut out);
        out[0]
    }

    /// xorshift64*: a fixed, dependency-free stream for generated cases.
    struct Rng(u64);

    impl Rng {
        fn below(&mut self, n: usize) -> usize {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 33) as usize % n
        }
    }

    /// A random expression of the grammar, written twice: with this module's
    /// variable names and with the checker's `t`, `w`.
    struct Gen<'a> {
        r: &'a mut Rng,
        names: Vec<String>,
        a: String,
        b: String,
    }

    impl Gen<'_> {
        fn put(&mut self, a: &str, b: &str) {
            let space = if self.r.below(3) == 0 { " " } else { "" };
            self.a.push_str(a);
            self.a.push_str(space);
            self.b.push_str(b);
            self.b.push_str(space);
        }
        fn same(&mut self, s: &str) {
            self.put(s, s);
        }
        fn expr(&mut self, d: usize) {
            self.term(d);
            for _ in 0..self.r.below(3) {
                let op = ["+", "-"][self.r.below(2)];
                self.same(op);
                self.term(d);
            }
        }
        fn term(&mut self, d: usize) {
            self.unary(d);
            for _ in 0..self.r.below(3) {
                let op = ["*", "/"][self.r.below(2)];
                self.same(op);
                self.unary(d);
            }
        }
        fn unary(&mut self, d: usize) {
            if self.r.below(6) == 0 {
                self.same("-");
                self.unary(d);
                return;
            }
            self.atom(d);
            if self.r.below(4) == 0 {
                let n = self.r.below(5).to_string();
                self.same("^");
                self.same(&n);
            }
        }
        fn atom(&mut self, d: usize) {
            if d == 0 || self.r.below(2) == 0 {
                let leaves = ["0", "1", "2", "0.1", "3.75", "1e-3", "2.5E+1", "12"];
                match self.r.below(6) {
                    0 => self.put("theta", "t"),
                    1 => self.put("theta_dot", "w"),
                    2 => {
                        let n = ["pi", "g", "mu"][self.r.below(3)];
                        self.same(n);
                    }
                    3 if !self.names.is_empty() => {
                        let n = self.names[self.r.below(self.names.len())].clone();
                        self.same(&n);
                    }
                    _ => {
                        let n = leaves[self.r.below(leaves.len())];
                        self.same(n);
                    }
                }
                return;
            }
            let mut two = false;
            if self.r.below(2) == 0 {
                self.same("(");
            } else {
                let f = FUNCTIONS[self.r.below(FUNCTIONS.len())];
                two = f == "min" || f == "max";
                self.same(f);
                self.same("(");
            }
            self.expr(d - 1);
            if two {
                self.same(",");
                self.expr(d - 1);
            }
            self.same(")");
        }
    }

    fn generate(r: &mut Rng, names: &[String], depth: usize) -> (String, String) {
        let mut g = Gen {
            r,
            names: names.to_vec(),
            a: String::new(),
            b: String::new(),
        };
        g.expr(depth);
        (g.a, g.b)
    }

    fn same_dec(a: DecInterval, b: DecInterval) -> bool {
        a.interval() == b.interval() && a.decoration() == b.decoration()
    }

    /// The tape and the checker's evaluator give the same enclosures and
    /// decorations for random texts with shared definitions.
    #[test]
    fn agrees_with_the_checker() {
        let mut r = Rng(0x9e37_79b9_7f4a_7c15);
        let checker_params: Vec<(String, String)> = pairs(&PARAMS);
        let boxes = [
            (iv(0.25, 0.5), iv(-1.5, 2.0)),
            (iv(0.7, 0.7), iv(-0.3, -0.3)),
            (iv(-3.0, 1.0), iv(0.5, 4.0)),
        ];
        for case in 0..300 {
            let mut names = Vec::new();
            let (mut mine, mut theirs) = (Vec::new(), Vec::new());
            for k in 0..r.below(4) {
                let (a, b) = generate(&mut r, &names, 2);
                let name = format!("d{k}");
                mine.push((name.clone(), a));
                theirs.push((name.clone(), b));
                names.push(name);
            }
            let (a, b) = generate(&mut r, &names, 3);
            // Definitions in any order: give them reversed.
            mine.reverse();
            let p = Program::compile(&params(), &mine, &[("out".into(), a.clone())])
                .unwrap_or_else(|e| panic!("case {case}: {a}: {e}"));
            for &(t, w) in &boxes {
                let want = detach_check::eval_on_box(&checker_params, &theirs, &b, t, w)
                    .unwrap_or_else(|e| panic!("case {case}: {b}: {e}"));
                let got = eval1(&p, DecInterval::new(t), DecInterval::new(w));
                assert!(
                    same_dec(got, want),
                    "case {case}: {a} with {mine:?}: {got:?} vs checker {want:?}"
                );
                let plain = eval1(&p, t, w);
                assert_eq!(Some(plain), want.interval(), "case {case}: {a}");
            }
        }
    }

    /// Every form of FORMAT.md's `number` (digits before or after the point,
    /// or both) is read as the checker reads it, and a point without digits
    /// is refused by both.
    #[test]
    fn numbers_are_read_as_the_checker_reads_them() {
        let (t, w) = (iv(0.25, 0.5), iv(-1.5, 2.0));
        for text in [
            "1.",
            ".5",
            "2.e1",
            ".5e-1",
            "0.1",
            "3e2",
            "X - .1*2.",
            "1.E+2",
        ] {
            let p = one(&[], &text.replace('X', "theta"));
            let want = detach_check::eval_on_box(&[], &[], &text.replace('X', "t"), t, w)
                .unwrap_or_else(|e| panic!("{text}: {e}"));
            assert!(
                same_dec(eval1(&p, DecInterval::new(t), DecInterval::new(w)), want),
                "{text}"
            );
        }
        for text in [".", ".e1", "1 + .", "1.2.3", "1..2"] {
            let mine = Program::compile(&params(), &[], &[("out".into(), text.into())]);
            let theirs = detach_check::eval_on_box(&[], &[], text, t, w);
            assert!(
                mine.is_err() && theirs.is_err(),
                "{text}: {mine:?} / {theirs:?}"
            );
        }
    }

    /// Fixed expressions against a direct evaluation in inari.
    #[test]
    fn fixed_expressions_by_hand() {
        let (t, w) = (iv(0.25, 0.5), iv(-1.5, 2.0));
        let g = enclose_decimal("g", "9.81").unwrap();
        let p = one(&[], "-g + 2*theta_dot^2*sin(theta) - theta/3^3");
        let three = iv(3.0, 3.0);
        let want = -g + iv(2.0, 2.0) * w.sqr() * t.sin() - t / three.powi(3);
        assert_eq!(eval1(&p, t, w), want);
        // -x^2 is -(x^2); left-associative subtraction and division.
        let p = one(&[], "-theta_dot^2 - 1 - theta / 2 / theta_dot");
        let want = -w.sqr() - iv(1.0, 1.0) - t / iv(2.0, 2.0) / w;
        assert_eq!(eval1(&p, t, w), want);
        // A decimal literal is the tightest enclosure of its value.
        let p = one(&[], "0.1");
        assert_eq!(eval1(&p, t, w), enclose_decimal("x", "0.1").unwrap());
        assert!(eval1(&p, t, w).inf() < eval1(&p, t, w).sup());
    }

    #[test]
    fn shared_subexpressions_are_one_node() {
        let count = |p: &Program, f: Func| {
            p.tape
                .iter()
                .filter(|n| matches!(n, Node::Call(g, _) if *g == f))
                .count()
        };
        // theta, sin, theta_dot, *, +, sqr, -
        let p = one(&[("s", "sin(theta)")], "s*theta_dot + s - s^2");
        assert_eq!(count(&p, Func::Sin), 1);
        assert_eq!(p.len(), 7);
        // theta, sin, +
        let p = one(&[], "sin(theta) + sin(theta)");
        assert_eq!(p.len(), 3);
        // Across outputs and definitions alike.
        let p = compile(&[("c", "cos(theta)")], &["cos(theta)*2", "c*2", "c"]).unwrap();
        assert_eq!(count(&p, Func::Cos), 1);
        assert_eq!(p.len(), 4);
        // Different operand order is a different operation (no rewriting).
        let p = one(&[], "theta*theta_dot + theta_dot*theta");
        assert_eq!(p.len(), 5);
        // Unused definitions are not on the tape.
        assert_eq!(one(&[("u", "ln(theta)")], "theta").len(), 1);
    }

    #[test]
    fn degree_in_theta_dot() {
        let deg = |defs: &[(&str, &str)], text: &str| one(defs, text).theta_dot_degree(0);
        assert_eq!(deg(&[], "theta_dot^2*sin(theta)"), Some(2));
        assert_eq!(deg(&[], "1/theta_dot"), None);
        assert_eq!(deg(&[], "sin(theta_dot)"), None);
        assert_eq!(deg(&[], "(theta_dot+1)^3"), Some(3));
        let x = [("x", "theta_dot^2 + theta_dot*g")];
        assert_eq!(deg(&x, "x/(theta+1)"), Some(2));
        assert_eq!(deg(&x, "(theta+1)/x"), None);
        assert_eq!(deg(&[], "abs(theta_dot)"), None);
        assert_eq!(deg(&[], "sqrt(theta^2 + 1)*mu"), Some(0));
        assert_eq!(deg(&[], "theta_dot*theta_dot*theta_dot^0"), Some(2));
        assert_eq!(deg(&[], "-theta_dot - theta_dot*theta"), Some(1));
        assert_eq!(one(&[], "1").theta_dot_degree(1), None);
    }

    /// `c2, c1, c0` of the quadratic output 0 of `p` at θ, from its values
    /// at θ̇ = −1, 0, 1 (c0 = f(0), c1 = (f(1) − f(−1))/2,
    /// c2 = (f(1) + f(−1))/2 − f(0)), each with a tolerance for f64 rounding.
    fn sampled_coefficients(p: &Program, theta: f64) -> [(f64, f64); 3] {
        let f = |w: f64| eval1(p, theta, w);
        let (f0, f1, fm) = (f(0.0), f(1.0), f(-1.0));
        [(f1 + fm) / 2.0 - f0, (f1 - fm) / 2.0, f0]
            .map(|c| (c, 1e-12 * (1.0 + c.abs() + f1.abs() + fm.abs())))
    }

    /// The three coefficients in f64 against the original at θ̇ = −1, 0, 1
    /// ([`sampled_coefficients`]).
    #[test]
    fn quadratic_coefficients_reproduce_the_function() {
        let defs = [
            ("x", "(theta_dot + sin(theta))^2*cos(theta)"),
            ("y", "theta_dot*(1 + theta)/(2 + theta)"),
        ];
        let texts = [
            "x - y + 3/(1+theta^2) - (2*theta_dot - 1)*(theta_dot+theta)",
            "-(theta_dot*mu - g)^2/g",
            "theta_dot",
            "-theta_dot",
            "theta_dot^0*theta + theta_dot^1",
            "ln(theta + 4)",
            "(theta_dot*theta)^2 - theta_dot/theta",
        ];
        for text in texts {
            let p = one(&defs, text);
            let q = p.quadratic(0).unwrap_or_else(|| panic!("{text}"));
            assert_eq!(q.outputs(), 3);
            assert!(q.tape.iter().all(|n| *n != Node::ThetaDot), "{text}");
            for theta in [0.5, -1.25, 2.0, 0.375] {
                let mut c = [0.0; 3];
                q.eval(theta, f64::NAN, &mut c);
                for (k, (want, tol)) in sampled_coefficients(&p, theta).into_iter().enumerate() {
                    assert!(
                        (c[k] - want).abs() <= tol,
                        "{text} θ={theta}: {c:?} vs {want}"
                    );
                }
            }
        }
        assert!(one(&[], "theta_dot^3").quadratic(0).is_none());
        assert!(one(&[], "abs(theta_dot)").quadratic(0).is_none());
        assert!(one(&[], "theta").quadratic(1).is_none());
    }

    /// The factored form (a/b)·(c2·θ̇² + c1·θ̇ + c0) reproduces the function
    /// (against it at θ̇ = 0, 1, −1 as in the test above), a and b are θ̇-free, and
    /// the quadratic of `U/V`, `-(k*U)`, `3*U*W/(l*V)` is U's own, bit for
    /// bit: none of the factor's rounding reaches it.
    #[test]
    fn factored_quadratics_take_theta_only_factors_apart() {
        let defs = [
            ("U", "sin(theta)*theta_dot^2 - g"),
            ("V", "1 + 3*cos(theta)^2 - 3*mu*sin(theta)*cos(theta)"),
            ("W", "cos(theta) - mu*sin(theta)"),
        ];
        let cases = [
            ("U/V", true),
            ("-(U/V)", true),
            ("-(mu*U)", true),
            ("3*U*W/(g*V)", true),
            ("U*W", true),
            ("U", false),
            ("U/V - 1", false),
            ("(theta_dot - 1)*(theta_dot + V)", false),
        ];
        let u = one(&defs, "U").quadratic(0).unwrap();
        for (text, peeled) in cases {
            let p = one(&defs, text);
            let q = p.factored_quadratics(&[0]).unwrap();
            assert_eq!(q.outputs(), 5);
            assert!(q.tape.iter().all(|n| *n != Node::ThetaDot), "{text}");
            for theta in [0.5, -1.25, 2.0, 0.375] {
                let mut c = [0.0; 5];
                q.eval(theta, f64::NAN, &mut c);
                for (k, (want, tol)) in sampled_coefficients(&p, theta).into_iter().enumerate() {
                    let got = c[0] / c[1] * c[k + 2];
                    assert!((got - want).abs() <= tol, "{text} θ={theta}: {c:?}");
                }
                if peeled {
                    let t = iv(theta, theta);
                    let mut got = [t; 5];
                    q.eval(t, Interval::ENTIRE, &mut got);
                    let mut want = [t; 3];
                    u.eval(t, Interval::ENTIRE, &mut want);
                    assert_eq!(got[2..], want, "{text} θ={theta}");
                    // The factor itself has no quotient at its top.
                    assert!(q.tape.iter().all(|n| !matches!(n, Node::Div(..))), "{text}");
                }
            }
        }
        // No factor: a = b = 1 exactly, and the quadratic is the unfactored one.
        let t = iv(0.5, 0.75);
        let plain = one(&defs, "U/V - 1");
        let (mut got, mut want) = ([t; 5], [t; 3]);
        plain
            .factored_quadratics(&[0])
            .unwrap()
            .eval(t, t, &mut got);
        plain.quadratic(0).unwrap().eval(t, t, &mut want);
        assert_eq!(got[..2], [iv(1.0, 1.0); 2]);
        assert_eq!(got[2..], want);
    }

    /// `A*theta_dot^2 + B*theta_dot + C` gives A, B, C themselves.
    #[test]
    fn quadratic_of_the_canonical_form_is_bit_identical() {
        let defs = [
            ("A", "sin(theta)*2.5 - mu"),
            ("B", "cos(theta) - 0.1"),
            ("C", "ln(theta + 3)/g"),
        ];
        let direct = compile(&defs, &["A", "B", "C"]).unwrap();
        let t = iv(0.1, 0.35);
        let mut want = [t; 3];
        direct.eval(t, t, &mut want);
        for text in [
            "A*theta_dot^2 + B*theta_dot + C",
            "(sin(theta)*2.5 - mu)*theta_dot^2 + (cos(theta) - 0.1)*theta_dot + ln(theta + 3)/g",
        ] {
            let q = one(&defs, text).quadratic(0).unwrap();
            let mut got = [t; 3];
            q.eval(t, Interval::ENTIRE, &mut got);
            assert_eq!(got, want, "{text}");
            // The same tape: nothing beyond A, B, C and what they need.
            assert_eq!(q.len(), direct.len(), "{text}");
        }
        // Missing terms are exact zeros; θ̇ alone has coefficient exactly 1.
        let q = one(&defs, "theta_dot + C").quadratic(0).unwrap();
        let mut got = [t; 3];
        q.eval(t, t, &mut got);
        assert_eq!(got[0], iv(0.0, 0.0));
        assert_eq!(got[1], iv(1.0, 1.0));
        assert_eq!(got[2], want[2]);
    }

    fn err(defs: &[(&str, &str)], text: &str) -> ExprError {
        match compile(defs, &[text]) {
            Ok(_) => panic!("{text:?} compiled"),
            Err(e) => e,
        }
    }

    #[test]
    fn errors_name_the_key_and_position() {
        let e = err(&[], "1 + foo");
        assert_eq!((e.key.as_str(), e.offset), ("out0", Some(5)));
        assert!(e.message.contains("unknown name `foo`"), "{e}");
        assert_eq!(e.to_string(), "`out0` at character 5: unknown name `foo`");
        let e = err(&[("a", "theta + bar")], "a");
        assert_eq!((e.key.as_str(), e.offset), ("a", Some(9)));
        let e = err(&[], "2*foo(theta)");
        assert_eq!(e.offset, Some(3));
        assert!(e.message.contains("unknown function"), "{e}");
        // Positions count characters, not bytes.
        let e = err(&[], "1 + θ");
        assert_eq!(e.offset, Some(5));
        let e = err(&[], "theta^2^3");
        assert_eq!(e.offset, Some(8));
        let e = err(&[], "theta^-1");
        assert_eq!(e.offset, Some(7));
        assert!(err(&[], "theta^1.5").message.contains("integer"));
        assert!(err(&[], "theta^99999999999").message.contains("too large"));
        let e = err(&[], "(theta+1");
        assert_eq!(e.offset, Some(9));
        let e = err(&[], "theta+1)");
        assert_eq!(e.offset, Some(8));
        assert!(e.message.contains("')'"));
        for blank in ["", "  \t\n"] {
            let e = err(&[], blank);
            assert_eq!((e.offset, e.message.as_str()), (None, "empty expression"));
            assert_eq!(e.to_string(), "`out0`: empty expression");
        }
        assert!(err(&[], "1 +").offset == Some(4));
        assert!(err(&[], "sin theta").message.contains("'('"));
        assert_eq!(err(&[], ". + 1").offset, Some(1));
        assert!(err(&[], "1e999").message.contains("too large"));
        assert!(err(&[], "1e99999999").message.contains("decimal"));
    }

    #[test]
    fn length_and_depth_limits() {
        let long = format!("1{}", "+1".repeat(5000));
        assert_eq!(long.len(), 10_001);
        let e = err(&[], &long);
        assert!(e.message.contains("longer than 10000"), "{e}");
        assert!(compile(&[], &[&long[..9_999]]).is_ok());
        for open in ["(", "sin(", "abs(("] {
            let per = open.matches('(').count();
            let nest = |n: usize| format!("{}1{}", open.repeat(n), ")".repeat(n * per));
            assert!(compile(&[], &[&nest(100 / per)]).is_ok(), "{open}");
            let e = err(&[], &nest(100 / per + 1));
            assert!(e.message.contains("nested"), "{e}");
            assert!(e.offset.is_some());
        }
        assert!(compile(&[], &[&format!("{}1", "-".repeat(100))]).is_ok());
        let e = err(&[], &format!("{}1", "-".repeat(101)));
        assert_eq!(e.offset, Some(101));
    }

    #[test]
    fn cycles_and_names() {
        let e = err(&[("a", "b + 1"), ("b", "c*2"), ("c", "theta - a")], "a");
        assert_eq!(e.key, "a");
        assert!(e.message.contains("a -> b -> c -> a"), "{e}");
        assert_eq!(e.offset, Some(1));
        let e = err(&[("x", "1"), ("s", "x*s")], "x");
        assert!(e.message.contains("s -> s"), "{e}");
        assert_eq!((e.key.as_str(), e.offset), ("s", Some(3)));
        // Reserved and repeated names.
        for bad in ["t", "w", "pi", "theta", "theta_dot", "sin", "abs"] {
            let e = err(&[(bad, "1")], "1");
            assert_eq!(e.key, bad);
            let p = vec![(bad.to_string(), iv(1.0, 1.0))];
            let e = Program::compile(&p, &[], &[]).unwrap_err();
            assert_eq!(e.key, bad);
            assert!(e.message.contains("reserved"));
        }
        assert_eq!(err(&[("g", "1")], "1").key, "g");
        assert_eq!(err(&[("a", "1"), ("a", "2")], "1").key, "a");
        assert_eq!(err(&[("2a", "1")], "1").key, "2a");
        assert_eq!(err(&[("a-b", "1")], "1").key, "a-b");
        // Case-sensitive names: `G` is not `g`.
        assert!(err(&[], "G").message.contains("unknown name"));
        assert!(compile(&[("G", "2*g"), ("T", "theta")], &["G*T"]).is_ok());
    }

    /// Token soups and arbitrary bytes: always a result, never a panic.
    #[test]
    fn garbage_never_panics() {
        let mut r = Rng(12345);
        let atoms = [
            "theta",
            "theta_dot",
            "(",
            ")",
            "+",
            "-",
            "*",
            "/",
            "^",
            "2",
            "1.5",
            "e",
            "1e",
            "sin",
            "abs",
            "pi",
            "g",
            "a",
            "b",
            " ",
            ".",
            "_",
            "θ",
            "\u{0}",
            "9e99999",
            "^^",
            ",",
        ];
        let mut oks = 0;
        for _ in 0..400 {
            let mut soup = || {
                let mut s = String::new();
                for _ in 0..1 + r.below(6) {
                    s.push_str(atoms[r.below(atoms.len())]);
                }
                s
            };
            let defs = vec![("a".to_string(), soup()), ("b".to_string(), soup())];
            let outs = vec![("o".to_string(), soup())];
            let _ = Program::compile(&params(), &defs, &outs);
            if Program::compile(&params(), &[], &[("o".into(), soup())]).is_ok() {
                oks += 1;
            }
            let bytes: Vec<u8> = (0..r.below(24)).map(|_| r.below(256) as u8).collect();
            let text = String::from_utf8_lossy(&bytes).into_owned();
            let _ = Program::compile(&[], &[], &[("o".into(), text)]);
        }
        assert!(oks > 0 && oks < 400, "{oks}");
    }

    /// Gradients through the tape against derivatives by hand.
    #[test]
    fn dual_derivatives() {
        let p = one(
            &[("x", "theta_dot*theta")],
            "x*sin(theta) + theta_dot^3/(1+theta^2) - abs(theta - 2)*mu",
        );
        let (t, w) = (0.7, 1.3);
        let f = eval1(&p, Dual::variable(t, 0), Dual::variable(w, 1));
        let q = 1.0 + t * t;
        let dt = w * t * t.cos() + w * t.sin() - w.powi(3) * 2.0 * t / (q * q) + 0.5;
        let dw = t * t.sin() + 3.0 * w * w / q;
        assert!((f.grad[0] - dt).abs() < 1e-12, "{} vs {dt}", f.grad[0]);
        assert!((f.grad[1] - dw).abs() < 1e-12, "{} vs {dw}", f.grad[1]);
        // Over intervals the gradient encloses the point derivative.
        let pt = |x: f64| iv(x, x);
        let fi = eval1(&p, Dual::variable(pt(t), 0), Dual::variable(pt(w), 1));
        assert!(fi.grad[0].contains(dt) && fi.grad[1].contains(dw));
        // Nested duals: d²/dθ² θ^5 = 20θ³.
        let p = one(&[], "theta^5");
        let x = DualN {
            value: DualN::<f64, 1>::variable(t, 0),
            grad: [DualN::<f64, 1>::constant(1.0)],
        };
        let y = eval1(&p, x, x);
        assert!((y.grad[0].grad[0] - 20.0 * t.powi(3)).abs() < 1e-12);
    }

    /// abs where its argument may be 0: the gradient is the hull of ±g and
    /// is never decorated as a derivative.
    #[test]
    fn abs_has_no_derivative_at_zero() {
        let p = one(&[], "abs(3*theta)");
        let at = |a: f64, b: f64| {
            let x = DecInterval::new(iv(a, b));
            eval1(&p, Dual::variable(x, 0), Dual::variable(x, 1))
        };
        let f = at(-1.0, 2.0);
        assert_eq!(f.value.interval(), Some(iv(0.0, 6.0)));
        assert_eq!(f.value.decoration(), Decoration::Com);
        assert_eq!(f.grad[0].interval(), Some(iv(-3.0, 3.0)));
        assert_eq!(f.grad[0].decoration(), Decoration::Trv);
        let f = at(-2.0, -1.0);
        assert_eq!(f.grad[0].interval(), Some(iv(-3.0, -3.0)));
        assert_eq!(f.grad[0].decoration(), Decoration::Com);
    }

    /// atan, exp, sign, min, max over intervals against closed forms (the
    /// doubles nearest π/4 = atan(1) and e = exp(1), mpmath to 20 digits:
    /// 0.78539816339744830962, 2.7182818284590452354), and their parse errors.
    #[test]
    fn new_functions_enclose_their_values() {
        let at = |text: &str, t: Interval, w: Interval| eval1(&one(&[], text), t, w);
        let p = |x: f64| iv(x, x);
        let a = at("atan(theta)", p(1.0), p(0.0));
        assert!(a.contains(std::f64::consts::FRAC_PI_4) && a.wid() <= 2.0 * f64::EPSILON);
        let e = at("exp(theta_dot)", p(0.0), p(1.0));
        assert!(e.contains(std::f64::consts::E) && e.wid() <= 4.0 * f64::EPSILON);
        assert_eq!(at("exp(theta)", iv(0.0, 0.0), p(0.0)), p(1.0));
        assert_eq!(at("sign(theta)", iv(-1.0, 2.0), p(0.0)), iv(-1.0, 1.0));
        assert_eq!(at("sign(theta)", iv(0.5, 2.0), p(0.0)), p(1.0));
        assert_eq!(at("sign(theta)", p(0.0), p(0.0)), p(0.0));
        let (t, w) = (iv(0.0, 1.0), iv(0.5, 2.0));
        assert_eq!(at("min(theta, theta_dot)", t, w), iv(0.0, 1.0));
        assert_eq!(at("max(theta, theta_dot)", t, w), iv(0.5, 2.0));
        assert_eq!(at("max(theta, 2*theta_dot) - 1", p(3.0), p(1.0)), p(2.0));
        assert!(err(&[], "min(theta)").message.contains("',' expected"));
        assert!(err(&[], "sign(theta, 1)").message.contains("')' expected"));
        assert!(err(&[], "max(1, 2, 3)").message.contains("')' expected"));
        assert_eq!(err(&[("exp", "1")], "1").key, "exp");
        // Two-argument calls render and re-parse to the same value.
        let q = one(&[], "min(theta, theta_dot*2) + max(1, sign(theta))");
        let (defs, outs) = q.render("q");
        assert!(
            defs.iter().any(|(_, b)| b.starts_with("min(t, q")),
            "{defs:?}"
        );
        assert_eq!(outs.len(), 1);
    }

    /// Derivatives by hand: at (0.7, 1.3), d/dθ and d/dθ̇ of
    /// atan(θ)·exp(θ̇) + min(θ, θ̇) − max(θ², θ̇) are exp(1.3)/1.49 + 1 and
    /// atan(0.7)·exp(1.3) − 1 (min picks θ, max picks θ̇). Where min's
    /// arguments may meet, and where sign may jump, no derivative is claimed.
    #[test]
    fn new_functions_have_derivatives_where_they_exist() {
        let p = one(
            &[],
            "atan(theta)*exp(theta_dot) + min(theta, theta_dot) - max(theta^2, theta_dot) + sign(theta)",
        );
        let (t, w) = (0.7f64, 1.3f64);
        let f = eval1(&p, Dual::variable(t, 0), Dual::variable(w, 1));
        let dt = w.exp() / (1.0 + t * t) + 1.0;
        let dw = t.atan() * w.exp() - 1.0;
        assert!((f.grad[0] - dt).abs() < 1e-12, "{} vs {dt}", f.grad[0]);
        assert!((f.grad[1] - dw).abs() < 1e-12, "{} vs {dw}", f.grad[1]);
        let pt = |x: f64| iv(x, x);
        let fi = eval1(&p, Dual::variable(pt(t), 0), Dual::variable(pt(w), 1));
        assert!(fi.grad[0].contains(dt) && fi.grad[1].contains(dw));
        // Over boxes where the kinks and the jump may lie.
        let dec = |a: f64, b: f64| DecInterval::new(iv(a, b));
        let m = one(&[], "min(theta, theta_dot)");
        let g = eval1(
            &m,
            Dual::variable(dec(0.0, 1.0), 0),
            Dual::variable(dec(0.5, 1.5), 1),
        );
        assert_eq!(g.grad[0].decoration(), Decoration::Trv);
        assert!(g.grad[0].interval().unwrap().contains(0.0));
        assert!(g.grad[0].interval().unwrap().contains(1.0));
        let s = one(&[], "sign(theta)");
        let g = eval1(
            &s,
            Dual::variable(dec(-1.0, 1.0), 0),
            Dual::variable(dec(0.0, 0.0), 1),
        );
        assert_eq!(g.grad[0].decoration(), Decoration::Trv);
        let g = eval1(
            &s,
            Dual::variable(iv(-1.0, 1.0), 0),
            Dual::variable(iv(0.0, 0.0), 1),
        );
        assert_eq!(g.grad[0], Interval::ENTIRE);
        let g = eval1(
            &s,
            Dual::variable(iv(1.0, 2.0), 0),
            Dual::variable(iv(0.0, 0.0), 1),
        );
        assert_eq!(g.grad[0], iv(0.0, 0.0));
    }
}
