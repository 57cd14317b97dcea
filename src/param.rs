//! Parameters as exact decimal text, enclosed outward.
//!
//! `g = 9.81` is the tightest interval around the rational 981/100, never the
//! double nearest to it. Validation gives one clear message per mistake.

use inari::Interval;
use std::collections::BTreeMap;
use std::str::FromStr;
use thiserror::Error;

/// What a parameter must satisfy.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Sign {
    /// strictly positive
    Positive,
    /// zero or positive
    NonNegative,
    /// any finite value
    Any,
}

/// Declaration of one scene parameter.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct ParamSpec {
    pub name: &'static str,
    pub default: &'static str,
    pub sign: Sign,
    pub meaning: &'static str,
}

/// A parameter as entered (decimal text) and its enclosure.
#[derive(Clone, Debug)]
pub struct Param {
    pub text: String,
    pub value: Interval,
}

#[derive(Debug, Error, PartialEq)]
pub enum ParamError {
    #[error(
        "parameter `{name}`: `{text}` is not a finite decimal number (examples: 9.81, -0.5, 2e-3)"
    )]
    NotDecimal { name: String, text: String },
    #[error("parameter `{name}` must be positive, got {text}")]
    NotPositive { name: String, text: String },
    #[error("parameter `{name}` must be zero or positive, got {text}")]
    Negative { name: String, text: String },
    #[error("unknown parameter `{name}` for scene `{scene}` (known: {known})")]
    Unknown {
        name: String,
        scene: String,
        known: String,
    },
    #[error("`{0}` is not of the form name=value")]
    NotAssignment(String),
    #[error("parameter `{name}`: {reason}")]
    Invalid { name: String, reason: String },
}

/// Sign and zero-ness of a decimal literal, read from its digits.
struct Decimal {
    negative: bool,
    zero: bool,
}

fn scan_decimal(text: &str) -> Option<Decimal> {
    let t = text.trim();
    let (negative, body) = match t.as_bytes().first()? {
        b'-' => (true, &t[1..]),
        b'+' => (false, &t[1..]),
        _ => (false, t),
    };
    let (mantissa, exponent) = match body.find(['e', 'E']) {
        Some(i) => (&body[..i], Some(&body[i + 1..])),
        None => (body, None),
    };
    if let Some(e) = exponent {
        let digits = e.strip_prefix(['+', '-']).unwrap_or(e);
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) || digits.len() > 6 {
            return None;
        }
    }
    let (int, frac) = match mantissa.find('.') {
        Some(i) => (&mantissa[..i], &mantissa[i + 1..]),
        None => (mantissa, ""),
    };
    let all_digits = |s: &str| s.bytes().all(|b| b.is_ascii_digit());
    if (int.is_empty() && frac.is_empty()) || !all_digits(int) || !all_digits(frac) {
        return None;
    }
    let zero = int.bytes().chain(frac.bytes()).all(|b| b == b'0');
    Some(Decimal { negative, zero })
}

/// Encloses decimal text outward. Rejects NaN, infinities, hex and anything
/// that is not a plain finite decimal.
pub fn enclose_decimal(name: &str, text: &str) -> Result<Interval, ParamError> {
    let not_decimal = || ParamError::NotDecimal {
        name: name.to_string(),
        text: text.to_string(),
    };
    scan_decimal(text).ok_or_else(not_decimal)?;
    let x = Interval::from_str(&format!("[{}]", text.trim())).map_err(|_| not_decimal())?;
    if x.is_empty() || !x.inf().is_finite() || !x.sup().is_finite() {
        return Err(not_decimal());
    }
    Ok(x)
}

impl Param {
    /// Parses and validates one parameter against its declaration.
    pub fn parse(spec: &ParamSpec, text: &str) -> Result<Param, ParamError> {
        let value = enclose_decimal(spec.name, text)?;
        let d = scan_decimal(text).expect("checked by enclose_decimal");
        let err_text = text.trim().to_string();
        match spec.sign {
            Sign::Positive if d.negative || d.zero => {
                return Err(ParamError::NotPositive {
                    name: spec.name.into(),
                    text: err_text,
                })
            }
            Sign::NonNegative if d.negative && !d.zero => {
                return Err(ParamError::Negative {
                    name: spec.name.into(),
                    text: err_text,
                })
            }
            _ => {}
        }
        Ok(Param {
            text: text.trim().to_string(),
            value,
        })
    }
}

/// A full, validated parameter set of one scene, in declaration order.
#[derive(Clone, Debug)]
pub struct ParamSet {
    pub specs: &'static [ParamSpec],
    pub values: Vec<Param>,
}

impl ParamSet {
    /// Defaults overridden by `name=value` assignments.
    pub fn build(
        scene: &str,
        specs: &'static [ParamSpec],
        overrides: &[(String, String)],
    ) -> Result<ParamSet, ParamError> {
        let mut texts: BTreeMap<&str, String> = specs
            .iter()
            .map(|s| (s.name, s.default.to_string()))
            .collect();
        for (name, text) in overrides {
            match texts.get_mut(name.as_str()) {
                Some(slot) => *slot = text.clone(),
                None => {
                    return Err(ParamError::Unknown {
                        name: name.clone(),
                        scene: scene.to_string(),
                        known: specs.iter().map(|s| s.name).collect::<Vec<_>>().join(", "),
                    })
                }
            }
        }
        let values = specs
            .iter()
            .map(|s| Param::parse(s, &texts[s.name]))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(ParamSet { specs, values })
    }

    /// The enclosure of a declared parameter. Panics on an undeclared name,
    /// which is a programming error inside a scene, not a user error.
    pub fn get(&self, name: &str) -> Interval {
        let i = self
            .specs
            .iter()
            .position(|s| s.name == name)
            .unwrap_or_else(|| panic!("scene asked for undeclared parameter {name}"));
        self.values[i].value
    }

    /// `(name, decimal text)` pairs, in declaration order.
    pub fn texts(&self) -> Vec<(&'static str, String)> {
        self.specs
            .iter()
            .zip(&self.values)
            .map(|(s, p)| (s.name, p.text.clone()))
            .collect()
    }
}

/// Splits `name=value`.
pub fn parse_assignment(s: &str) -> Result<(String, String), ParamError> {
    match s.split_once('=') {
        Some((n, v)) if !n.trim().is_empty() => Ok((n.trim().to_string(), v.trim().to_string())),
        _ => Err(ParamError::NotAssignment(s.to_string())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: ParamSpec = ParamSpec {
        name: "g",
        default: "9.81",
        sign: Sign::Positive,
        meaning: "gravity",
    };

    #[test]
    fn decimal_is_enclosed_not_rounded() {
        let x = enclose_decimal("g", "9.81").unwrap();
        // 9.81 is not a double: the enclosure is two adjacent doubles around it.
        assert!(x.inf() < x.sup());
        assert!(x.inf() <= 9.81 && 9.81 <= x.sup());
        assert_eq!(x.sup(), f64::from_bits(x.inf().to_bits() + 1));
        // an exactly representable decimal is a point
        assert!(enclose_decimal("x", "0.25").unwrap().is_singleton());
    }

    #[test]
    fn bad_text_is_rejected() {
        for t in [
            "nan", "NaN", "inf", "-inf", "", "1e", "0x10", "1.2.3", "--1", "1e999999",
        ] {
            assert!(enclose_decimal("g", t).is_err(), "{t:?} accepted");
        }
    }

    #[test]
    fn signs_are_checked_from_the_text() {
        assert!(matches!(
            Param::parse(&G, "0"),
            Err(ParamError::NotPositive { .. })
        ));
        assert!(matches!(
            Param::parse(&G, "-0.0"),
            Err(ParamError::NotPositive { .. })
        ));
        assert!(matches!(
            Param::parse(&G, "-1"),
            Err(ParamError::NotPositive { .. })
        ));
        assert!(Param::parse(&G, "1e-400").is_ok());
        let mu = ParamSpec {
            sign: Sign::NonNegative,
            ..G
        };
        assert!(Param::parse(&mu, "0").is_ok());
        assert!(Param::parse(&mu, "-0").is_ok());
        assert!(matches!(
            Param::parse(&mu, "-0.1"),
            Err(ParamError::Negative { .. })
        ));
    }
}
