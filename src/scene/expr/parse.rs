//! Text to postfix steps: the lexer and parser of the expression grammar
//! of `proofs/FORMAT.md`, and the rules for names.

use super::{error, ExprError, Fail, FUNCTIONS, MAX_DEPTH, MAX_EXPR_LEN, RESERVED};
use crate::number::param::{enclose_decimal, ParamError};
use inari::Interval;
use std::collections::HashSet;

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
pub(super) enum Func {
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
    pub(super) fn name(self) -> &'static str {
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
pub(super) enum Step<'a> {
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
pub(super) fn parse<'a>(key: &str, text: &'a str) -> Result<Vec<Step<'a>>, ExprError> {
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

pub(super) fn check_name(name: &str, declared: &HashSet<&str>) -> Result<(), ExprError> {
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
