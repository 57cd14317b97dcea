//! Lexer and recursive-descent parser of the expression language. The parser
//! emits operations straight into a [`Program`](super::eval::Program), in the order written, so
//! there is no syntax tree to walk (and no recursion beyond the nesting depth
//! of the text itself, which is bounded).
//!
//! ```text
//! expr    := term (("+" | "-") term)*
//! term    := unary (("*" | "/") unary)*
//! unary   := "-" unary | power
//! power   := atom ("^" integer)?
//! atom    := number | name | name "(" expr ")" | name "(" expr "," expr ")"
//!          | "(" expr ")"
//! number  := (digits ["." [digits]] | "." digits) [("e"|"E") ["+"|"-"] digits]
//! ```

use inari::DecInterval;

use super::encoding::{decimal_enclosure, is_decimal_text};
use super::ops::{is_name, Op, FUNCTIONS};

/// Where the parser writes what it reads: each operation as it completes
/// (operands first, in the order written), and the slot a name refers to.
/// [`super::eval::Program`] is the one implementation.
pub trait Emit {
    /// Appends an operation on earlier slots; returns its slot.
    fn emit(&mut self, op: Op) -> Result<u32, String>;
    /// The slot of a declared name (variable, parameter, definition, `pi`).
    fn slot_of(&self, name: &str) -> Option<u32>;
}

/// Longest expression text accepted.
pub const MAX_EXPR_LEN: usize = 10_000;
/// Deepest nesting of parentheses, calls and unary minus accepted.
pub const MAX_DEPTH: usize = 100;

#[derive(Clone, Debug, PartialEq)]
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

fn lex(s: &str) -> Result<Vec<Tok<'_>>, String> {
    let b = s.as_bytes();
    let mut i = 0;
    let mut out = Vec::new();
    let digits = |mut j: usize| {
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
        }
        j
    };
    while i < b.len() {
        let c = b[i];
        let tok = match c {
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
            // A number: digits with an optional point, at least one digit
            // before or after it (`1`, `1.5`, `1.`, `.5`), as decimal text.
            b'0'..=b'9' | b'.' => {
                let start = i;
                i = digits(i);
                let before = i - start;
                if i < b.len() && b[i] == b'.' {
                    let j = digits(i + 1);
                    if before == 0 && j == i + 1 {
                        return Err(format!("digits expected before or after '.' at {i}"));
                    }
                    i = j;
                }
                if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
                    let mut j = i + 1;
                    if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
                        j += 1;
                    }
                    let k = digits(j);
                    if k > j {
                        i = k;
                    }
                }
                out.push(Tok::Num(&s[start..i]));
                continue;
            }
            c if c.is_ascii_alphabetic() => {
                let start = i;
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                    i += 1;
                }
                out.push(Tok::Name(&s[start..i]));
                continue;
            }
            _ => {
                let ch = s[i..].chars().next().unwrap_or('?');
                return Err(format!("unexpected character {ch:?} at {i}"));
            }
        };
        out.push(tok);
        i += 1;
    }
    Ok(out)
}

struct Parser<'p, 'a, E: Emit> {
    toks: Vec<Tok<'a>>,
    pos: usize,
    depth: usize,
    prog: &'p mut E,
}

impl<'a, E: Emit> Parser<'_, 'a, E> {
    fn peek(&self) -> Option<&Tok<'a>> {
        self.toks.get(self.pos)
    }

    fn next(&mut self) -> Option<Tok<'a>> {
        let t = self.toks.get(self.pos).cloned();
        self.pos += 1;
        t
    }

    fn enter(&mut self) -> Result<(), String> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err("expression nested too deeply".into());
        }
        Ok(())
    }

    fn expr(&mut self) -> Result<u32, String> {
        let mut l = self.term()?;
        loop {
            let op = match self.peek() {
                Some(Tok::Plus) => 0,
                Some(Tok::Minus) => 1,
                _ => return Ok(l),
            };
            self.pos += 1;
            let r = self.term()?;
            l = self.prog.emit(if op == 0 {
                Op::Add(l, r)
            } else {
                Op::Sub(l, r)
            })?;
        }
    }

    fn term(&mut self) -> Result<u32, String> {
        let mut l = self.unary()?;
        loop {
            let op = match self.peek() {
                Some(Tok::Star) => 0,
                Some(Tok::Slash) => 1,
                _ => return Ok(l),
            };
            self.pos += 1;
            let r = self.unary()?;
            l = self.prog.emit(if op == 0 {
                Op::Mul(l, r)
            } else {
                Op::Div(l, r)
            })?;
        }
    }

    fn unary(&mut self) -> Result<u32, String> {
        if self.peek() == Some(&Tok::Minus) {
            self.pos += 1;
            self.enter()?;
            let x = self.unary()?;
            self.depth -= 1;
            return self.prog.emit(Op::Neg(x));
        }
        self.power()
    }

    fn power(&mut self) -> Result<u32, String> {
        let x = self.atom()?;
        if self.peek() != Some(&Tok::Caret) {
            return Ok(x);
        }
        self.pos += 1;
        let n = match self.next() {
            Some(Tok::Num(t)) if t.bytes().all(|c| c.is_ascii_digit()) => t
                .parse::<i32>()
                .map_err(|_| format!("exponent {t} too large"))?,
            _ => return Err("'^' must be followed by a non-negative integer literal".into()),
        };
        if self.peek() == Some(&Tok::Caret) {
            return Err("x^a^b is ambiguous; write (x^a)^b".into());
        }
        self.prog
            .emit(if n == 2 { Op::Sqr(x) } else { Op::Pown(x, n) })
    }

    fn atom(&mut self) -> Result<u32, String> {
        match self.next() {
            Some(Tok::Num(t)) => {
                if !is_decimal_text(t) {
                    return Err(format!("bad number {t:?}"));
                }
                let x = decimal_enclosure(t)?;
                self.prog.emit(Op::Const(DecInterval::new(x)))
            }
            Some(Tok::LParen) => {
                self.enter()?;
                let x = self.expr()?;
                self.depth -= 1;
                match self.next() {
                    Some(Tok::RParen) => Ok(x),
                    _ => Err("')' expected".into()),
                }
            }
            Some(Tok::Name(n)) => {
                if FUNCTIONS.contains(&n) {
                    if self.next() != Some(Tok::LParen) {
                        return Err(format!("'(' expected after {n}"));
                    }
                    self.enter()?;
                    let a = self.expr()?;
                    // `min` and `max` take two arguments, the others one.
                    let b = if n == "min" || n == "max" {
                        if self.next() != Some(Tok::Comma) {
                            return Err(format!("',' expected: {n} takes two arguments"));
                        }
                        self.expr()?
                    } else {
                        a
                    };
                    self.depth -= 1;
                    if self.next() != Some(Tok::RParen) {
                        return Err(format!("')' expected to close {n}("));
                    }
                    let op = match n {
                        "sqrt" => Op::Sqrt(a),
                        "sin" => Op::Sin(a),
                        "cos" => Op::Cos(a),
                        "tan" => Op::Tan(a),
                        "ln" => Op::Ln(a),
                        "atan" => Op::Atan(a),
                        "exp" => Op::Exp(a),
                        "sign" => Op::Sign(a),
                        "min" => Op::Min(a, b),
                        "max" => Op::Max(a, b),
                        _ => Op::Abs(a),
                    };
                    return self.prog.emit(op);
                }
                if self.peek() == Some(&Tok::LParen) {
                    return Err(format!("{n} is not a function"));
                }
                debug_assert!(is_name(n));
                self.prog
                    .slot_of(n)
                    .ok_or_else(|| format!("unknown name {n:?}"))
            }
            Some(t) => Err(format!("unexpected {t:?}")),
            None => Err("unexpected end of expression".into()),
        }
    }
}

/// Parses `text` and appends its operations to `prog`; returns the slot of
/// the value. On error `prog` may hold unused operations, which is harmless
/// because the caller discards the statement.
pub fn parse_into<E: Emit>(prog: &mut E, text: &str) -> Result<u32, String> {
    if text.len() > MAX_EXPR_LEN {
        return Err("expression too long".into());
    }
    let toks = lex(text).map_err(|e| format!("in {text:?}: {e}"))?;
    let mut p = Parser {
        toks,
        pos: 0,
        depth: 0,
        prog,
    };
    let s = p.expr().map_err(|e| format!("in {text:?}: {e}"))?;
    if p.pos != p.toks.len() {
        return Err(format!("in {text:?}: unexpected {:?}", p.toks.get(p.pos)));
    }
    Ok(s)
}
