//! The operations of the expression language (`proofs/FORMAT.md`,
//! "Expressions"): what the parser ([`super::expr`]) emits and the
//! evaluator ([`super::eval`]) applies. Both depend on this module and not
//! on each other's internals.

use inari::DecInterval;

/// Function names of the expression language.
pub const FUNCTIONS: [&str; 11] = [
    "sqrt", "sin", "cos", "tan", "ln", "abs", "atan", "exp", "sign", "min", "max",
];

/// One operation; operands are indices of earlier slots.
#[derive(Clone, Copy, Debug)]
pub enum Op {
    /// A constant enclosure (literal, parameter, `pi`).
    Const(DecInterval),
    /// Variable number `i`.
    Var(u8),
    Neg(u32),
    Add(u32, u32),
    Sub(u32, u32),
    Mul(u32, u32),
    Div(u32, u32),
    /// `x^2`.
    Sqr(u32),
    /// `x^n`, n ≠ 2.
    Pown(u32, i32),
    Sqrt(u32),
    Sin(u32),
    Cos(u32),
    Tan(u32),
    Ln(u32),
    Abs(u32),
    Atan(u32),
    Exp(u32),
    /// The function `sign` (−1, 0 or 1).
    Sign(u32),
    Min(u32, u32),
    Max(u32, u32),
}

/// The operands of an operation (earlier slots).
pub fn operands(op: &Op) -> [Option<u32>; 2] {
    match *op {
        Op::Const(_) | Op::Var(_) => [None, None],
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
        | Op::Sign(a) => [Some(a), None],
    }
}

/// True when `s` is a name of the grammar: a letter, then letters, digits, `_`.
pub fn is_name(s: &str) -> bool {
    let mut c = s.chars();
    matches!(c.next(), Some(f) if f.is_ascii_alphabetic())
        && c.all(|x| x.is_ascii_alphanumeric() || x == '_')
}
