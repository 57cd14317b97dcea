//! Text encodings of numbers and bits: base64, exact hexadecimal doubles,
//! decimal text, and a most-significant-bit-first bit reader.

use inari::Interval;
use std::str::FromStr;

/// Longest decimal text accepted. Bounds the exact rational arithmetic done
/// when enclosing it.
const MAX_DECIMAL_LEN: usize = 1000;
/// Largest decimal exponent magnitude accepted, for the same reason.
const MAX_DECIMAL_EXP: i64 = 10_000;

/// Decodes standard base64 (RFC 4648 alphabet, `=` padding required, no
/// whitespace). Non-canonical encodings (nonzero unused bits before the
/// padding) are rejected, so every byte string has exactly one spelling.
pub fn base64_decode(s: &str) -> Result<Vec<u8>, String> {
    fn value(c: u8) -> Option<u32> {
        match c {
            b'A'..=b'Z' => Some(u32::from(c - b'A')),
            b'a'..=b'z' => Some(u32::from(c - b'a') + 26),
            b'0'..=b'9' => Some(u32::from(c - b'0') + 52),
            b'+' => Some(62),
            b'/' => Some(63),
            _ => None,
        }
    }
    let bytes = s.as_bytes();
    if !bytes.len().is_multiple_of(4) {
        return Err(format!(
            "base64 length {} is not a multiple of 4",
            bytes.len()
        ));
    }
    let mut out = Vec::with_capacity(bytes.len() / 4 * 3);
    let groups = bytes.len() / 4;
    for (g, chunk) in bytes.chunks_exact(4).enumerate() {
        let last = g + 1 == groups;
        let pad = chunk.iter().rev().take_while(|&&c| c == b'=').count();
        if pad > 2 || (pad > 0 && !last) {
            return Err(format!("misplaced base64 padding in group {}", g + 1));
        }
        let mut acc: u32 = 0;
        for &c in &chunk[..4 - pad] {
            let v =
                value(c).ok_or_else(|| format!("invalid base64 character {:?}", char::from(c)))?;
            acc = (acc << 6) | v;
        }
        match pad {
            0 => out.extend_from_slice(&[(acc >> 16) as u8, (acc >> 8) as u8, acc as u8]),
            1 => {
                // 18 bits carry 2 bytes; the 2 low bits must be zero.
                if acc & 0x3 != 0 {
                    return Err("non-canonical base64 (nonzero padding bits)".into());
                }
                out.extend_from_slice(&[(acc >> 10) as u8, (acc >> 2) as u8]);
            }
            _ => {
                // 12 bits carry 1 byte; the 4 low bits must be zero.
                if acc & 0xf != 0 {
                    return Err("non-canonical base64 (nonzero padding bits)".into());
                }
                out.push((acc >> 4) as u8);
            }
        }
    }
    Ok(out)
}

/// Parses a C99 hexadecimal floating constant `[-]0x<hex>[.<hex>]p[+-]<dec>`
/// that denotes a binary64 value exactly; `inf` / `-inf` only when
/// `allow_inf`. Anything not exactly a finite double (or an allowed infinity)
/// is an error: no rounding ever happens here.
pub fn parse_hex_f64(s: &str, allow_inf: bool) -> Result<f64, String> {
    let err = || format!("{s:?} is not an exact hexadecimal double");
    if s == "inf" || s == "-inf" {
        if !allow_inf {
            return Err(format!("{s:?}: an infinite end is not allowed here"));
        }
        return Ok(if s == "inf" {
            f64::INFINITY
        } else {
            f64::NEG_INFINITY
        });
    }
    let (neg, rest) = match s.strip_prefix('-') {
        Some(r) => (true, r),
        None => (false, s),
    };
    let rest = rest
        .strip_prefix("0x")
        .or_else(|| rest.strip_prefix("0X"))
        .ok_or_else(err)?;
    let p = rest.find(['p', 'P']).ok_or_else(err)?;
    let (mant, exp) = (&rest[..p], &rest[p + 1..]);
    let (int_part, frac_part) = match mant.find('.') {
        Some(i) => (&mant[..i], &mant[i + 1..]),
        None => (mant, ""),
    };
    if int_part.is_empty() && frac_part.is_empty() {
        return Err(err());
    }
    if !int_part
        .bytes()
        .chain(frac_part.bytes())
        .all(|c| c.is_ascii_hexdigit())
    {
        return Err(err());
    }
    // Exponent: optional sign, at least one decimal digit. Saturate: any
    // magnitude beyond the double range is rejected below anyway.
    let (eneg, edigits) = match exp.as_bytes().first() {
        Some(b'+') => (false, &exp[1..]),
        Some(b'-') => (true, &exp[1..]),
        _ => (false, exp),
    };
    if edigits.is_empty() || !edigits.bytes().all(|c| c.is_ascii_digit()) {
        return Err(err());
    }
    let mut e: i64 = 0;
    for c in edigits.bytes() {
        e = (e * 10 + i64::from(c - b'0')).min(1 << 40);
    }
    if eneg {
        e = -e;
    }
    // Significand digits without leading and trailing zeros; each dropped
    // trailing digit and each fraction digit moves the binary exponent by 4.
    let digits: Vec<u8> = int_part.bytes().chain(frac_part.bytes()).collect();
    let frac_len = i64::try_from(frac_part.len()).map_err(|_| err())?;
    e -= 4 * frac_len;
    let first = digits.iter().position(|&c| c != b'0');
    let Some(first) = first else {
        return Ok(if neg { -0.0 } else { 0.0 });
    };
    let mut last = digits.len();
    while last > first && digits[last - 1] == b'0' {
        last -= 1;
        e += 4;
    }
    let sig = &digits[first..last];
    if sig.len() > 16 {
        // More than 16 significant hex digits span more than 53 bits.
        return Err(err());
    }
    let mut m: u64 = 0;
    for &c in sig {
        let d = char::from(c).to_digit(16).ok_or_else(err)?;
        m = (m << 4) | u64::from(d);
    }
    let tz = m.trailing_zeros();
    m >>= tz;
    e += i64::from(tz);
    let bitlen = i64::from(64 - m.leading_zeros());
    if bitlen > 53 {
        return Err(err());
    }
    let top = e + bitlen - 1; // exponent of the leading bit
    let bits = if top > 1023 {
        return Err(err());
    } else if top >= -1022 {
        let frac = (m << (52 - (bitlen - 1))) & ((1u64 << 52) - 1);
        let biased = u64::try_from(top + 1023).map_err(|_| err())?;
        (biased << 52) | frac
    } else if e >= -1074 {
        m << (e + 1074)
    } else {
        return Err(err());
    };
    let v = f64::from_bits(bits);
    Ok(if neg { -v } else { v })
}

/// Checks `s` against the decimal-text grammar
/// `[+-](digits[.[digits]] | .digits)[(e|E)[+-]digits]` (at least one
/// digit before or after the point) and the size limits.
fn validate_decimal(s: &str) -> Result<(), String> {
    let err = |why: &str| format!("{s:?} is not decimal text ({why})");
    if s.len() > MAX_DECIMAL_LEN {
        return Err(err("too long"));
    }
    let b = s.as_bytes();
    let mut i = 0;
    if matches!(b.first(), Some(b'+' | b'-')) {
        i += 1;
    }
    let int_start = i;
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
    }
    let mut ndig = i - int_start;
    let mut frac_len = 0usize;
    if i < b.len() && b[i] == b'.' {
        i += 1;
        let f = i;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        frac_len = i - f;
        ndig += frac_len;
    }
    if ndig == 0 {
        return Err(err("no digits"));
    }
    let mut exp: i64 = 0;
    if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
        i += 1;
        let mut neg = false;
        if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
            neg = b[i] == b'-';
            i += 1;
        }
        let e0 = i;
        while i < b.len() && b[i].is_ascii_digit() {
            exp = (exp * 10 + i64::from(b[i] - b'0')).min(1 << 40);
            i += 1;
        }
        if i == e0 {
            return Err(err("empty exponent"));
        }
        if neg {
            exp = -exp;
        }
    }
    if i != b.len() {
        return Err(err("unexpected character"));
    }
    // The enclosure is computed from the exact rational, whose size grows
    // with the effective exponent.
    let eff = exp - i64::try_from(frac_len).unwrap_or(i64::MAX);
    if exp.abs() > MAX_DECIMAL_EXP || eff.abs() > MAX_DECIMAL_EXP {
        return Err(err("exponent out of range"));
    }
    Ok(())
}

/// Encloses decimal text by the tightest interval of doubles (IEEE 1788
/// `[text]`). Text whose value lies beyond the finite doubles is rejected.
pub fn decimal_enclosure(s: &str) -> Result<Interval, String> {
    validate_decimal(s)?;
    let x =
        Interval::from_str(&format!("[{s}]")).map_err(|_| format!("{s:?} is not decimal text"))?;
    if x.is_empty() || !x.inf().is_finite() || !x.sup().is_finite() {
        return Err(format!("{s:?} is out of the range of doubles"));
    }
    Ok(x)
}

/// True when `s` matches the decimal-text grammar (used by the expression
/// lexer, which has already split the literal off).
pub fn is_decimal_text(s: &str) -> bool {
    validate_decimal(s).is_ok()
}

/// Reads a byte string as bits, most significant bit of each byte first.
pub struct BitReader<'a> {
    bytes: &'a [u8],
    pos: u64,
}

impl<'a> BitReader<'a> {
    /// A reader positioned at the first bit.
    pub fn new(bytes: &'a [u8]) -> Self {
        BitReader { bytes, pos: 0 }
    }

    /// Total number of bits.
    pub fn len(&self) -> u64 {
        (self.bytes.len() as u64) * 8
    }

    /// The number of bits read so far.
    pub fn position(&self) -> u64 {
        self.pos
    }

    /// The next bit, or `None` at the end.
    pub fn bit(&mut self) -> Option<bool> {
        let byte = *self.bytes.get(usize::try_from(self.pos / 8).ok()?)?;
        let b = (byte >> (7 - (self.pos % 8))) & 1 == 1;
        self.pos += 1;
        Some(b)
    }

    /// The next `n ≤ 64` bits as an unsigned integer, first bit most significant.
    pub fn bits(&mut self, n: u32) -> Option<u64> {
        if n > 64 || self.len() - self.pos < u64::from(n) {
            return None;
        }
        let mut v: u64 = 0;
        for _ in 0..n {
            v = (v << 1) | u64::from(self.bit()?);
        }
        Some(v)
    }

    /// True when every bit from the current position to the end is 0.
    pub fn rest_is_zero(&self) -> bool {
        let mut r = BitReader {
            bytes: self.bytes,
            pos: self.pos,
        };
        while let Some(b) = r.bit() {
            if b {
                return false;
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_examples() {
        assert_eq!(parse_hex_f64("0x1.8p-1", false), Ok(0.75));
        assert_eq!(parse_hex_f64("0x3p-1", false), Ok(1.5));
        assert_eq!(parse_hex_f64("-0x1.4p+3", false), Ok(-10.0));
        assert_eq!(parse_hex_f64("0x0.0000000000001p-1022", false), Ok(5e-324));
        assert!(parse_hex_f64("0x1.00000000000008p+0", false).is_err());
        assert!(parse_hex_f64("0x1p+1024", false).is_err());
        assert!(parse_hex_f64("0x1p-1075", false).is_err());
        assert!(parse_hex_f64("inf", false).is_err());
        assert_eq!(parse_hex_f64("-inf", true), Ok(f64::NEG_INFINITY));
    }

    #[test]
    fn decimal_examples() {
        let x = decimal_enclosure("0.1").unwrap();
        assert!(x.inf() < x.sup() && x.inf() <= 0.1 && 0.1 <= x.sup());
        assert_eq!(decimal_enclosure("-2.5e1").unwrap().inf(), -25.0);
        assert!(decimal_enclosure("1e400").is_err());
        assert!(decimal_enclosure("1e99999").is_err());
        assert!(decimal_enclosure("inf").is_err());
        assert!(decimal_enclosure("0x1p0").is_err());
        assert!(decimal_enclosure("").is_err());
        assert!(decimal_enclosure("1,2").is_err());
    }
}
