//! User expressions compiled to a tape with shared subexpressions.
//!
//! A scene file gives parameters (already enclosed), named definitions in any
//! order and output expressions, written in the language of
//! `proofs/FORMAT.md` ("Expressions") with the variables `theta` and
//! `theta_dot`. Each text is parsed to postfix steps, lowered into one
//! hash-consed DAG (the same operation on the same operands is one node, and a
//! definition is one node wherever it is named), and the nodes the outputs
//! need are flattened into a tape evaluated over any
//! [`Scalar`](crate::number::scalar::Scalar) (`parse`, `graph`, `tape`).
//! A text can also be evaluated over an exact scalar as it is written
//! (`exact`), for claims about a file's formulas.
//!
//! Nothing is rewritten: every node is one operation of the text,
//! left-associative, in the order written, so an interval evaluation of the
//! tape gives the enclosure the checker computes for the same text. The
//! evaluation plan only does arithmetic on constants alone once, where that
//! gives every scalar type the very value the operation would.

mod exact;
mod factor;
mod graph;
mod parse;
mod quotient;
mod tape;
mod taylor;
#[cfg(test)]
mod tests;

pub use exact::{decimal, eval_exact, ExactTheta};
pub use factor::FactorOf;
pub use quotient::Quotient;
pub use tape::{ConstantIssue, Program};
pub use taylor::{Coefficient, NotAnalytic, OdeSeries, TaylorTape};

use crate::number::scalar::is_defined;
use graph::Node;
use inari::{DecInterval, Interval};
use std::fmt;

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
