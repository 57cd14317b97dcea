//! One text evaluated over an exact scalar: how a claim evaluates a formula
//! of a scene file (a printed reading's region, θ̈, Φ, …) instead of writing
//! it again.
//!
//! Exact arithmetic has only the field operations, so θ enters only through
//! `sin(theta)` and `cos(theta)`, whose values the caller gives (as exact
//! rationals from `t = tan(θ/2)`), `tan(theta/2) = sin θ/(1 + cos θ)`, and
//! the logarithms `ln(tan(theta/2))` and `ln(sin(theta))` where the caller
//! gives them ([`ExactTheta`]); a literal is its decimal value, built from
//! small integers by the field operations (exact in an exact scalar); `x^n`
//! is [`Scalar::pown`]. Any other use of θ, `pi` or a function has no exact
//! value and is an error naming the text. Over intervals or `f64` the same
//! evaluation is an enclosure or an approximation of the text's value.

use super::parse::{parse, Func, Step};
use super::{error, ExprError, THETA, THETA_DOT};
use crate::number::scalar::Scalar;

/// The value of a decimal literal (`12.5`, `1e-3`, `2.5E+2`) built from
/// integers of at most nine digits by the field operations: exact in an
/// exact scalar.
pub fn decimal<T: Scalar>(text: &str) -> T {
    let (mantissa, exponent) = match text.find(['e', 'E']) {
        Some(i) => (&text[..i], text[i + 1..].parse::<i64>().unwrap_or(0)),
        None => (text, 0),
    };
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let digits: Vec<u8> = int.bytes().chain(frac.bytes()).collect();
    let mut value = T::int(0);
    for chunk in digits.chunks(9) {
        let text = std::str::from_utf8(chunk).expect("ASCII digits");
        let n: i32 = text.parse().expect("at most nine digits");
        value = value * T::int(10).pown(chunk.len() as u32) + T::int(n);
    }
    let scale = exponent - frac.len() as i64;
    let ten = T::int(10).pown(scale.unsigned_abs() as u32);
    if scale < 0 {
        value / ten
    } else {
        value * ten
    }
}

/// θ in an exact evaluation: `sin θ`, `cos θ`, and for texts that take
/// them (§3's v_x of (3.1)) the logarithms `ln(tan(theta/2))` and
/// `ln(sin(theta))`, given as values: in an identity proof they are
/// symbols of their own, and an identity that holds for independent symbols
/// holds for the true values.
#[derive(Clone, Copy, Debug)]
pub struct ExactTheta<T> {
    pub sin: T,
    pub cos: T,
    /// `(ln tan(θ/2), ln sin θ)`.
    pub logs: Option<(T, T)>,
}

impl<T> ExactTheta<T> {
    /// θ as its sine and cosine alone.
    pub fn trig(sin: T, cos: T) -> ExactTheta<T> {
        ExactTheta {
            sin,
            cos,
            logs: None,
        }
    }
}

/// An operand on the stack: θ and the forms of it that the logarithms take
/// stay symbolic until arithmetic needs a value.
#[derive(Clone, Copy)]
enum Item<T> {
    Theta,
    /// `theta/2`.
    HalfTheta,
    /// `tan(theta/2)`, as a value `sin θ/(1 + cos θ)`.
    TanHalf,
    /// A value, and whether it is the literal `2` or `sin(theta)`.
    Value(T, Form),
}

#[derive(Clone, Copy, PartialEq)]
enum Form {
    Plain,
    Two,
    SinTheta,
}

/// `text` (under the name `key` in errors) evaluated with each name's
/// value from `name` (`theta_dot` is a name like any other); `name` returns
/// `None` for a name it has no value for (θ itself, `pi`, an unknown name),
/// and errors of its own as they are.
pub fn eval_exact<T: Scalar>(
    key: &str,
    text: &str,
    theta: &ExactTheta<T>,
    name: &mut dyn FnMut(&str) -> Option<Result<T, ExprError>>,
) -> Result<T, ExprError> {
    let steps = parse(key, text)?;
    let fail = |msg: String| error(key, text, (None, msg));
    let internal = || fail("internal: malformed expression".into());
    let value = |item: Option<Item<T>>| -> Result<T, ExprError> {
        match item {
            Some(Item::Value(x, _)) => Ok(x),
            Some(Item::TanHalf) => Ok(theta.sin / (T::int(1) + theta.cos)),
            Some(Item::Theta | Item::HalfTheta) => Err(fail(format!(
                "{THETA} enters other than as sin({THETA}), cos({THETA}) or \
                 ln(tan({THETA}/2)), which has no exact value"
            ))),
            None => Err(internal()),
        }
    };
    let mut stack: Vec<Item<T>> = Vec::new();
    for step in &steps {
        let item = match *step {
            Step::Num(_, t) => {
                let form = if t == "2" { Form::Two } else { Form::Plain };
                Item::Value(decimal(t), form)
            }
            Step::Name(n, at) => match name(n) {
                Some(x) => Item::Value(x?, Form::Plain),
                None if n == THETA => Item::Theta,
                None => {
                    let why = if n == THETA_DOT {
                        "has no value given"
                    } else {
                        "has no exact value here"
                    };
                    return Err(error(key, text, (Some(at), format!("`{n}` {why}"))));
                }
            },
            Step::Call(f) => {
                let x = stack.pop();
                match (f, x) {
                    (Func::Sin, Some(Item::Theta)) => Item::Value(theta.sin, Form::SinTheta),
                    (Func::Cos, Some(Item::Theta)) => Item::Value(theta.cos, Form::Plain),
                    (Func::Tan, Some(Item::HalfTheta)) => Item::TanHalf,
                    (Func::Ln, Some(Item::TanHalf | Item::Value(_, Form::SinTheta))) => {
                        let Some((ln_tan_half, ln_sin)) = theta.logs else {
                            let msg = format!("`ln` has no exact value: give ln(tan({THETA}/2)) and ln(sin({THETA}))");
                            return Err(fail(msg));
                        };
                        let l = match x {
                            Some(Item::TanHalf) => ln_tan_half,
                            _ => ln_sin,
                        };
                        Item::Value(l, Form::Plain)
                    }
                    (Func::Min | Func::Max, _) => {
                        return Err(fail(format!("`{}` has no exact value", f.name())));
                    }
                    _ => {
                        let msg = format!(
                            "`{}` has no exact value here (only sin({THETA}), cos({THETA}), tan({THETA}/2) and their logarithms)",
                            f.name()
                        );
                        return Err(fail(msg));
                    }
                }
            }
            Step::Neg => Item::Value(-value(stack.pop())?, Form::Plain),
            Step::Pow(n) => Item::Value(value(stack.pop())?.pown(n), Form::Plain),
            Step::Div => {
                let b = stack.pop();
                let a = stack.pop();
                match (a, b) {
                    (Some(Item::Theta), Some(Item::Value(_, Form::Two))) => Item::HalfTheta,
                    _ => Item::Value(value(a)? / value(b)?, Form::Plain),
                }
            }
            Step::Add | Step::Sub | Step::Mul => {
                let b = value(stack.pop())?;
                let a = value(stack.pop())?;
                let v = match *step {
                    Step::Add => a + b,
                    Step::Sub => a - b,
                    _ => a * b,
                };
                Item::Value(v, Form::Plain)
            }
        };
        stack.push(item);
    }
    let result = value(stack.pop())?;
    if stack.is_empty() {
        Ok(result)
    } else {
        Err(internal())
    }
}
