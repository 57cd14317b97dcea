//! Parameters as exact decimal text, enclosed outward.
//!
//! `g = 9.81` is the tightest interval around the rational 981/100, never the
//! double nearest to it. Validation gives one clear message per mistake.

use inari::Interval;
use std::collections::BTreeMap;
use thiserror::Error;

/// Declaration of one scene parameter.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct ParamSpec {
    pub name: &'static str,
    pub default: &'static str,
    pub meaning: &'static str,
    /// The unit the value is in (`m`, `kg`, `m/s^2`), or empty.
    pub unit: &'static str,
}

/// A parameter as entered (decimal text) and its enclosure.
#[derive(Clone, Debug)]
pub struct Param {
    pub text: String,
    pub value: Interval,
}

#[derive(Debug, Error, PartialEq)]
pub enum ParamError {
    #[error("parameter `{name}`: {}", self.reason())]
    NotDecimal { name: String, text: String },
    #[error("unknown parameter `{name}` for scene `{scene}` (known: {known})")]
    Unknown {
        name: String,
        scene: String,
        known: String,
    },
    #[error("parameter `{name}`: {}", self.reason())]
    TooLarge { name: String, text: String },
    #[error("parameter `{name}`: {}", self.reason())]
    TooSmall { name: String, text: String },
    #[error("parameter `{name}` is given twice (`{first}` and `{second}`): give it once")]
    Repeated {
        name: String,
        first: String,
        second: String,
    },
    #[error("`{0}` is not of the form name=value")]
    NotAssignment(String),
    #[error("parameter `{name}`: {reason}")]
    Invalid { name: String, reason: String },
    /// A window end (`theta`, `theta_dot`), not a parameter.
    #[error("{name}: {reason}")]
    Window { name: String, reason: String },
}

impl ParamError {
    /// What is wrong with the value, without naming it: for a caller that
    /// names the value otherwise (a window, a file's key).
    pub fn reason(&self) -> String {
        match self {
            ParamError::NotDecimal { text, .. } => {
                format!("`{text}` is not a finite decimal number (examples: 9.81, -0.5, 2e-3)")
            }
            ParamError::TooLarge { text, .. } => {
                format!("`{text}` is too large for double precision (magnitude above 1.8e308)")
            }
            ParamError::TooSmall { text, .. } => format!(
                "`{text}` is too small for double precision (nonzero, magnitude below \
                 4.9e-324): write 0 if you mean 0"
            ),
            ParamError::Invalid { reason, .. } | ParamError::Window { reason, .. } => {
                reason.clone()
            }
            other => other.to_string(),
        }
    }

    /// The same error said of the window `name` (`theta`, `theta_dot`).
    pub fn of_window(self, name: &str) -> ParamError {
        ParamError::Window {
            name: name.to_string(),
            reason: self.reason(),
        }
    }
}

/// A plain decimal literal: its sign and magnitude `0.d₁d₂… × 10^exp`, with
/// significant digits only (no leading or trailing zeros; none for zero).
struct Decimal {
    negative: bool,
    digits: Vec<u8>,
    exp: i64,
}

impl Decimal {
    fn zero(&self) -> bool {
        self.digits.is_empty()
    }
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
    let mut exp = 0;
    if let Some(e) = exponent {
        let digits = e.strip_prefix(['+', '-']).unwrap_or(e);
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) || digits.len() > 6 {
            return None;
        }
        exp = e.parse().ok()?;
    }
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let all_digits = |s: &str| s.bytes().all(|b| b.is_ascii_digit());
    if (int.is_empty() && frac.is_empty()) || !all_digits(int) || !all_digits(frac) {
        return None;
    }
    let (digits, exp) = significant(int, frac, exp);
    Some(Decimal {
        negative,
        digits,
        exp,
    })
}

/// The significant digits and exponent `e` of `int.frac × 10^exp` written as
/// `0.d₁d₂… × 10^e` (digits only, without leading or trailing zeros).
fn significant(int: &str, frac: &str, exp: i64) -> (Vec<u8>, i64) {
    let all: Vec<u8> = int.bytes().chain(frac.bytes()).collect();
    let lead = all.iter().take_while(|&&b| b == b'0').count();
    let mut digits = all[lead..].to_vec();
    while digits.last() == Some(&b'0') {
        digits.pop();
    }
    (digits, exp + int.len() as i64 - lead as i64)
}

/// The tightest interval of doubles around a plain decimal `d` (its `text`,
/// trimmed), without MPFR, whose start-up (GMP's processor dispatch) was a
/// few % of a coarse paving's whole process. Rust's parsing rounds to the
/// nearest double x; the text compared with x's exact decimal expansion (at
/// most 767 significant digits) says whether it is x or on which side of x
/// it lies. Beyond the largest double: an infinite end.
fn tightest_enclosure(d: &Decimal, text: &str) -> Option<Interval> {
    let x: f64 = text.parse().ok()?;
    if x.is_infinite() {
        let (lo, hi) = if d.negative {
            (f64::NEG_INFINITY, f64::MIN)
        } else {
            (f64::MAX, f64::INFINITY)
        };
        return Interval::try_from((lo, hi)).ok();
    }
    let exact = format!("{:.800e}", x.abs());
    let (m, e) = exact.split_once('e')?;
    let (int, frac) = m.split_once('.').unwrap_or((m, ""));
    let (xd, xe) = significant(int, frac, e.parse().ok()?);
    // |text| against |x|: zero first, then exponents, then digits.
    let order = match (d.zero(), xd.is_empty()) {
        (true, true) => std::cmp::Ordering::Equal,
        (true, false) => std::cmp::Ordering::Less,
        (false, true) => std::cmp::Ordering::Greater,
        (false, false) => d.exp.cmp(&xe).then_with(|| d.digits.cmp(&xd)),
    };
    // The value is x, or lies between x and its neighbour away from (|text| >
    // |x|) or towards (|text| < |x|) zero.
    let (lo, hi) = match (order, d.negative) {
        (std::cmp::Ordering::Equal, _) => (x, x),
        (std::cmp::Ordering::Greater, false) | (std::cmp::Ordering::Less, true) => (x, x.next_up()),
        _ => (x.next_down(), x),
    };
    Interval::try_from((lo, hi)).ok()
}

/// Encloses decimal text outward. Rejects NaN, infinities, hex and anything
/// that is not a plain finite decimal.
pub fn enclose_decimal(name: &str, text: &str) -> Result<Interval, ParamError> {
    let not_decimal = || ParamError::NotDecimal {
        name: name.to_string(),
        text: text.to_string(),
    };
    let d = scan_decimal(text).ok_or_else(not_decimal)?;
    let x = tightest_enclosure(&d, text.trim()).ok_or_else(not_decimal)?;
    if !x.inf().is_finite() || !x.sup().is_finite() {
        // A finite decimal whose magnitude is beyond the largest double.
        return Err(if d.zero() {
            not_decimal()
        } else {
            ParamError::TooLarge {
                name: name.to_string(),
                text: text.trim().to_string(),
            }
        });
    }
    if !d.zero() && x.contains(0.0) {
        // Nonzero text whose enclosure reaches 0: a sign or a division by it
        // would be lost without a word, as an overflow would.
        return Err(ParamError::TooSmall {
            name: name.to_string(),
            text: text.trim().to_string(),
        });
    }
    Ok(x)
}

/// Encloses one end of a window: decimal text as [`enclose_decimal`], or
/// `pi`, `-pi`, `pi/N`, `-pi/N` (N a positive integer up to 10⁶), enclosed
/// outward.
pub fn enclose_window_end(name: &str, text: &str) -> Result<Interval, ParamError> {
    let t = text.trim();
    let (neg, body) = match t.strip_prefix('-') {
        Some(b) => (true, b.trim_start()),
        None => (false, t.strip_prefix('+').unwrap_or(t)),
    };
    let lower = body.to_ascii_lowercase();
    let pi = match lower.strip_prefix("pi").or_else(|| lower.strip_prefix('π')) {
        Some("") => Some(Interval::PI),
        Some(rest) => match rest.strip_prefix('/').map(str::trim) {
            Some(n) if !n.is_empty() && n.len() <= 7 && n.bytes().all(|b| b.is_ascii_digit()) => {
                let n: u32 = n.parse().unwrap_or(0);
                if n == 0 || n > 1_000_000 {
                    None
                } else {
                    let n = Interval::try_from((n as f64, n as f64)).ok();
                    n.map(|n| Interval::PI / n)
                }
            }
            _ => None,
        },
        None => None,
    };
    match pi {
        Some(x) if neg => Ok(-x),
        Some(x) => Ok(x),
        None if lower.contains("pi") || lower.contains('π') => Err(ParamError::Invalid {
            name: name.into(),
            reason: format!("`{t}`: use a decimal, pi, -pi, pi/N or -pi/N"),
        }),
        None => enclose_decimal(name, text),
    }
}

/// A count given on the command line: an integer, in plain or exponent form
/// (`1000`, `1e3`, `2.5e6`), at most 2⁵³. Negative, fractional and
/// non-numeric text get a one-line reason.
pub fn parse_count(text: &str) -> Result<usize, String> {
    let t = text.trim();
    if let Ok(n) = t.parse::<u64>() {
        return usize::try_from(n).map_err(|_| format!("{t} is too large"));
    }
    let bad = || format!("expected a non-negative integer such as 1000 or 1e6, got `{t}`");
    let x = enclose_decimal("count", t).map_err(|e| match e {
        ParamError::TooLarge { .. } => format!("{t} is too large"),
        _ => bad(),
    })?;
    if x.inf() < 0.0 {
        return Err(format!("must not be negative, got {t}"));
    }
    if !x.is_singleton() || x.inf().fract() != 0.0 {
        return Err(if x.inf() > 9.007_199_254_740_992e15 {
            format!("{t} is too large (at most 2^53)")
        } else {
            format!("must be an integer, got {t}")
        });
    }
    if x.inf() > 9.007_199_254_740_992e15 {
        return Err(format!("{t} is too large (at most 2^53)"));
    }
    Ok(x.inf() as usize)
}

impl Param {
    /// Parses one parameter's decimal text and encloses it (a scene's
    /// `[conditions]` then check the values).
    pub fn parse(spec: &ParamSpec, text: &str) -> Result<Param, ParamError> {
        let value = enclose_decimal(spec.name, text)?;
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
        for (i, (name, text)) in overrides.iter().enumerate() {
            if let Some((_, first)) = overrides[..i].iter().find(|(n, _)| n == name) {
                return Err(ParamError::Repeated {
                    name: name.clone(),
                    first: first.clone(),
                    second: text.clone(),
                });
            }
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

    /// `(name, "text unit")` pairs (the unit when declared), in declaration
    /// order: for labels a person reads.
    pub fn texts_with_units(&self) -> Vec<(&'static str, String)> {
        self.specs
            .iter()
            .zip(&self.values)
            .map(|(s, p)| match s.unit {
                "" => (s.name, p.text.clone()),
                u => (s.name, format!("{} {u}", p.text)),
            })
            .collect()
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

/// A double for messages: `0` for ±0, the shortest round-trip decimal for
/// moderate magnitudes, exponent form otherwise (never 300 digits).
pub fn short_num(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if (1e-4..1e16).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
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
        meaning: "gravity",
        unit: "",
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
    fn overflowing_decimals_are_too_large_not_malformed() {
        for t in ["1e400", "-1e400", "2e308"] {
            assert!(
                matches!(enclose_decimal("A", t), Err(ParamError::TooLarge { .. })),
                "{t}"
            );
        }
        let msg = enclose_decimal("A", "1e400").unwrap_err().to_string();
        assert!(msg.contains("too large"), "{msg}");
        assert!(enclose_decimal("A", "1.7e308").is_ok());
    }

    #[test]
    fn window_ends_accept_pi_forms() {
        let pi = enclose_window_end("theta", "pi").unwrap();
        assert_eq!(pi, Interval::PI);
        assert_eq!(enclose_window_end("theta", "-pi").unwrap(), -Interval::PI);
        assert_eq!(enclose_window_end("theta", " PI ").unwrap(), Interval::PI);
        let half = enclose_window_end("theta", "pi/2").unwrap();
        assert!(
            half.inf() <= std::f64::consts::FRAC_PI_2 && std::f64::consts::FRAC_PI_2 <= half.sup()
        );
        assert!(half.wid() <= 2.0 * f64::EPSILON);
        for t in ["pi/0", "pi/x", "2pi", "pie", "pi/", "pi/99999999"] {
            assert!(enclose_window_end("theta", t).is_err(), "{t}");
        }
        assert_eq!(
            enclose_window_end("theta", "0.25").unwrap(),
            enclose_decimal("theta", "0.25").unwrap()
        );
    }

    #[test]
    fn counts_accept_exponent_form() {
        assert_eq!(parse_count("1000"), Ok(1000));
        assert_eq!(parse_count("1e3"), Ok(1000));
        assert_eq!(parse_count("2.5e6"), Ok(2_500_000));
        assert_eq!(parse_count("0"), Ok(0));
        assert!(parse_count("-1").unwrap_err().contains("negative"));
        assert!(parse_count("1.5").unwrap_err().contains("integer"));
        assert!(parse_count("1e400").unwrap_err().contains("too large"));
        assert!(parse_count("1e30").unwrap_err().contains("too large"));
        assert!(parse_count("nan").is_err());
        assert!(parse_count("").is_err());
    }

    #[test]
    fn a_value_is_any_finite_decimal_whose_enclosure_is_not_zero_by_accident() {
        // Signs are the scene's `[conditions]`; a value is only checked as
        // text: 0 and negatives are values, a nonzero text whose enclosure
        // reaches 0 is refused as overflow is.
        for t in ["0", "-0.0", "-1", "5e-324"] {
            assert!(Param::parse(&G, t).is_ok(), "{t}");
        }
        assert!(matches!(
            Param::parse(&G, "1e-400"),
            Err(ParamError::TooSmall { .. })
        ));
    }

    /// Reference: inari's parsing, which rounds with MPFR.
    fn by_mpfr(text: &str) -> Interval {
        use std::str::FromStr;
        Interval::from_str(&format!("[{text}]")).unwrap()
    }

    fn ours(text: &str) -> Interval {
        tightest_enclosure(&scan_decimal(text).unwrap(), text).unwrap()
    }

    fn same(a: Interval, b: Interval) -> bool {
        a.inf().to_bits() == b.inf().to_bits() && a.sup().to_bits() == b.sup().to_bits()
    }

    #[test]
    fn decimal_enclosures_match_mpfr_at_the_edges() {
        for t in [
            "0",
            "-0.000",
            "2.5",
            "-2.5",
            "0.1",
            "9.81",
            "1e-400",
            "-1e-400",
            "1e400",
            "-1e400",
            "1.7976931348623157e308",
            "1.7976931348623158e308",
            "4.9406564584124654e-324",
            "2.4703282292062327e-324",
            "2.4703282292062328e-324",
            "9007199254740993",
            "9007199254740992",
            "+.5",
            "5.",
            "0.30000000000000004441",
            "1E+2",
        ] {
            let ours = ours(t);
            assert!(same(ours, by_mpfr(t)), "{t}: {ours:?} vs {:?}", by_mpfr(t));
        }
    }

    proptest::proptest! {
        #[test]
        fn decimal_enclosures_match_mpfr(
            neg in proptest::bool::ANY,
            int in "[0-9]{0,24}",
            frac in "[0-9]{0,24}",
            exp in proptest::option::of(-345i32..330),
        ) {
            proptest::prop_assume!(!(int.is_empty() && frac.is_empty()));
            let mut t = format!("{}{int}", if neg { "-" } else { "" });
            if !frac.is_empty() {
                t = format!("{t}.{frac}");
            }
            if let Some(e) = exp {
                t = format!("{t}e{e}");
            }
            let ours = ours(&t);
            proptest::prop_assert!(same(ours, by_mpfr(&t)), "{}: {:?} vs {:?}", t, ours, by_mpfr(&t));
        }
    }
}
