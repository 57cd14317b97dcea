//! How numbers are written into proof files: exact doubles as hexadecimal
//! floats, claimed bounds as short decimals rounded outward.

use crate::number::param::enclose_decimal;

/// The exact C99 hexadecimal form of a double (`0x1.8p+1` = 3); `inf`/`-inf`.
pub fn hex(x: f64) -> String {
    if x.is_infinite() {
        return if x > 0.0 { "inf".into() } else { "-inf".into() };
    }
    let sign = if x.is_sign_negative() { "-" } else { "" };
    let bits = x.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i64;
    let frac = bits & ((1u64 << 52) - 1);
    let digits = format!("{frac:013x}");
    let digits = digits.trim_end_matches('0');
    let dot = if digits.is_empty() { "" } else { "." };
    match exp {
        0 if frac == 0 => format!("{sign}0x0p+0"),
        0 => format!("{sign}0x0{dot}{digits}p-1022"),
        _ => format!("{sign}0x1{dot}{digits}p{:+}", exp - 1023),
    }
}

/// Which way a decimal bound may err.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Round {
    /// The decimal is `≤ x` (a lower bound stays a lower bound).
    Down,
    /// The decimal is `≥ x`.
    Up,
}

/// `x` as a decimal with `digits` significant digits, rounded so that the
/// exact rational it denotes lies on the `dir` side of `x`. A checker compares
/// through the decimal's enclosure, so the enclosure (not only the rational)
/// is kept on that side.
pub fn decimal(x: f64, digits: usize, dir: Round) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let s = format!("{:.*e}", digits.saturating_sub(1), x);
    let (mant, exp) = s.split_once('e').expect("exponent form");
    let exp: i32 = exp.parse().expect("integer exponent");
    let negative = mant.starts_with('-');
    let mut m: i128 = mant
        .trim_start_matches('-')
        .replace('.', "")
        .parse()
        .expect("digits");
    if negative {
        m = -m;
    }
    let shift = exp - (digits as i32 - 1);
    let text = |m: i128| format!("{m}e{shift}");
    // A few steps of one unit in the last digit always suffice.
    for _ in 0..4 {
        let enc = enclose_decimal("bound", &text(m)).expect("a decimal we wrote");
        let ok = match dir {
            Round::Down => enc.sup() <= x,
            Round::Up => enc.inf() >= x,
        };
        if ok {
            return tidy(&text(m));
        }
        m += if dir == Round::Down { -1 } else { 1 };
    }
    unreachable!("outward decimal of {x} not found")
}

/// `x` with `places` digits after the point, rounded toward `dir` from the
/// exact value of the double, so a printed lower bound stays below `x` and
/// an upper bound above it (`format!("{:.6}")` rounds to nearest).
pub fn fixed(x: f64, places: usize, dir: Round) -> String {
    let Some(exact) = rug::Rational::from_f64(x) else {
        return format!("{x}");
    };
    let scaled = exact * rug::Integer::from(rug::Integer::u_pow_u(10, places as u32));
    let n = match dir {
        Round::Down => scaled.floor(),
        Round::Up => scaled.ceil(),
    };
    let n = n.numer().clone();
    let sign = if n < 0 { "-" } else { "" };
    let digits = n.abs().to_string();
    let digits = format!("{digits:0>width$}", width = places + 1);
    let (whole, frac) = digits.split_at(digits.len() - places);
    if places == 0 {
        format!("{sign}{whole}")
    } else {
        format!("{sign}{whole}.{frac}")
    }
}

/// An area for a table, rounded outward in the direction `dir` (a lower
/// bound down, an upper bound up): six decimals, or six significant digits
/// when tiny or huge (a window one ulp wide has areas near 1e-17).
pub fn area_text(x: f64, dir: Round) -> String {
    if x == 0.0 || (1e-3..1e9).contains(&x.abs()) {
        fixed(x + 0.0, 6, dir)
    } else {
        decimal(x, 6, dir)
    }
}

/// `123e-2` → `1.23`; keeps exponent form only for very large or small numbers.
fn tidy(t: &str) -> String {
    let (m, e) = t.split_once('e').expect("exponent form");
    let e: i32 = e.parse().expect("integer");
    let (sign, digits) = match m.strip_prefix('-') {
        Some(d) => ("-", d),
        None => ("", m),
    };
    let trimmed = digits.trim_end_matches('0');
    let e = e + (digits.len() - trimmed.len()) as i32;
    let digits = trimmed;
    let n = digits.len() as i32;
    let point = n + e; // digits before the decimal point
    if e >= 0 && point <= 21 {
        format!("{sign}{digits}{}", "0".repeat(e as usize))
    } else if point > 0 && e < 0 {
        let (a, b) = digits.split_at(point as usize);
        format!("{sign}{a}.{}", b.trim_end_matches('0'))
            .trim_end_matches('.')
            .to_string()
    } else if point <= 0 && point > -20 {
        let b = format!("{}{}", "0".repeat((-point) as usize), digits);
        format!("{sign}0.{}", b.trim_end_matches('0'))
    } else {
        format!("{sign}{digits}e{e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_forms_are_exact() {
        // Values by hand: 3 = 1.5·2¹, 0.1 = 0x1.999999999999ap-4 (IEEE 754).
        assert_eq!(hex(3.0), "0x1.8p+1");
        assert_eq!(hex(1.0), "0x1p+0");
        assert_eq!(hex(-0.5), "-0x1p-1");
        assert_eq!(hex(0.1), "0x1.999999999999ap-4");
        assert_eq!(hex(0.0), "0x0p+0");
        assert_eq!(hex(-0.0), "-0x0p+0");
        assert_eq!(hex(f64::MIN_POSITIVE / 2.0), "0x0.8p-1022");
        assert_eq!(hex(f64::INFINITY), "inf");
        assert_eq!(hex(std::f64::consts::PI), "0x1.921fb54442d18p+1");
    }

    #[test]
    fn decimals_round_outward() {
        let x = 101.32371234567;
        let d = decimal(x, 10, Round::Down);
        let u = decimal(x, 10, Round::Up);
        assert_eq!(d, "101.3237123");
        assert_eq!(u, "101.3237124");
        assert!(enclose_decimal("d", &d).unwrap().sup() <= x);
        assert!(enclose_decimal("u", &u).unwrap().inf() >= x);
        // An exactly representable value may be its own bound.
        assert_eq!(decimal(0.5, 10, Round::Down), "0.5");
        assert_eq!(decimal(-2.25, 3, Round::Up), "-2.25");
        for x in [1e-30, 3e300, -7.25e-25] {
            let (d, u) = (decimal(x, 3, Round::Down), decimal(x, 3, Round::Up));
            assert!(enclose_decimal("d", &d).unwrap().sup() <= x, "{d}");
            assert!(enclose_decimal("u", &u).unwrap().inf() >= x, "{u}");
        }
        assert_eq!(decimal(0.0, 3, Round::Up), "0");
    }

    #[test]
    fn fixed_places_round_outward_from_the_exact_double() {
        // 41.33452342101865 rounds to nearest as ...019 at 12 places; its
        // exact value lies between ...018 and ...019.
        let x = 41.33452342101865;
        assert_eq!(format!("{x:.12}"), "41.334523421019");
        assert_eq!(fixed(x, 12, Round::Down), "41.334523421018");
        assert_eq!(fixed(x, 12, Round::Up), "41.334523421019");
        // 0.1 is above 1/10 as a double: down keeps 0.100000, up gives 0.100001.
        assert_eq!(fixed(0.1, 6, Round::Down), "0.100000");
        assert_eq!(fixed(0.1, 6, Round::Up), "0.100001");
        assert_eq!(fixed(-0.1, 6, Round::Down), "-0.100001");
        assert_eq!(fixed(0.5, 6, Round::Up), "0.500000");
        assert_eq!(fixed(0.0, 3, Round::Down), "0.000");
        assert_eq!(fixed(2.5e-7, 6, Round::Up), "0.000001");
    }
}
