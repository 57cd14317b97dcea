//! Export of every leaf of a paving as CSV, exact and loadable anywhere.
//!
//! One header line, then one line per leaf in the paving's leaf order:
//!
//! ```text
//! theta_lo,theta_hi,theta_dot_lo,theta_dot_hi,theta_lo_hex,theta_hi_hex,theta_dot_lo_hex,theta_dot_hi_hex,omega,omega0
//! ```
//!
//! The first four columns are shortest round-trip decimals (they parse back
//! to the same double in any correct parser); the `_hex` columns are the same
//! doubles as C99 hexadecimal floats (`0x1.921fb54442d18p+1`, Python's
//! `float.hex` spelling: `float.fromhex`, Julia `parse(Float64, …)`, C
//! `strtod`). The last columns are one label per constraint: `in`
//! (proved inside, `sup g < 0`), `out` (proved outside, `inf g > 0`),
//! `undecided`, or `undefined` (the formula may be undefined on the box).

use super::{Label, Paving};
use std::io::{self, Write};

/// The CSV's comment line: what wrote it and for which problem. `run`
/// says how (`derived, method slices`), `params` are `(name, text)` pairs.
pub fn provenance(scene: &str, run: &str, params: &[(&str, String)], paving: &Paving) -> String {
    let params: Vec<String> = params.iter().map(|(n, t)| format!("{n}={t}")).collect();
    let r = &paving.root;
    format!(
        "detach {}; scene {scene} ({run}); {}; theta in [{:?}, {:?}], theta_dot in [{:?}, {:?}]; eps {}",
        crate::LONG_VERSION,
        params.join(" "),
        r.theta[0],
        r.theta[1],
        r.theta_dot[0],
        r.theta_dot[1],
        paving.eps
    )
}

/// The C99 hexadecimal spelling of a double, exact (as Python's
/// `float.hex`): `0x1.<13 hex digits>p±e` for normal numbers,
/// `0x0.<13 hex digits>p-1022` for subnormals, `0x0.0p+0` for zero.
/// Infinities and NaN are spelled `inf`, `-inf` and `nan`.
pub fn hex_float(x: f64) -> String {
    if x.is_nan() {
        return "nan".into();
    }
    let sign = if x.is_sign_negative() { "-" } else { "" };
    if x.is_infinite() {
        return format!("{sign}inf");
    }
    let bits = x.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i64;
    let mant = bits & ((1u64 << 52) - 1);
    match (exp, mant) {
        (0, 0) => format!("{sign}0x0.0p+0"),
        (0, m) => format!("{sign}0x0.{m:013x}p-1022"),
        (e, m) => format!("{sign}0x1.{m:013x}p{:+}", e - 1023),
    }
}

/// The CSV word of a label.
pub fn label_word(l: Label) -> &'static str {
    match l {
        Label::ProvedIn => "in",
        Label::ProvedOut => "out",
        Label::Undecided => "undecided",
        Label::Undefined => "undefined",
    }
}

/// Writes every leaf (format in the module docs). The constraint columns are
/// named after [`Paving::names`].
pub fn write_leaves_csv<W: Write>(paving: &Paving, provenance: &str, mut w: W) -> io::Result<()> {
    // One comment line first: what wrote the file, and for which problem.
    writeln!(w, "# {}", provenance.replace('\n', " "))?;
    write!(
        w,
        "theta_lo,theta_hi,theta_dot_lo,theta_dot_hi,\
         theta_lo_hex,theta_hi_hex,theta_dot_lo_hex,theta_dot_hi_hex"
    )?;
    for name in &paving.names {
        write!(w, ",{name}")?;
    }
    writeln!(w)?;
    for leaf in &paving.leaves {
        let b = &leaf.bx;
        let ends = [b.theta[0], b.theta[1], b.theta_dot[0], b.theta_dot[1]];
        // `{:?}` is Rust's shortest round-trip decimal.
        write!(w, "{:?},{:?},{:?},{:?}", ends[0], ends[1], ends[2], ends[3])?;
        for x in ends {
            write!(w, ",{}", hex_float(x))?;
        }
        for l in leaf.labels.iter() {
            write!(w, ",{}", label_word(*l))?;
        }
        writeln!(w)?;
    }
    w.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_floats_match_the_c99_spelling() {
        assert_eq!(hex_float(1.0), "0x1.0000000000000p+0");
        assert_eq!(hex_float(-1.5), "-0x1.8000000000000p+0");
        assert_eq!(hex_float(std::f64::consts::PI), "0x1.921fb54442d18p+1");
        assert_eq!(hex_float(0.0), "0x0.0p+0");
        assert_eq!(hex_float(-0.0), "-0x0.0p+0");
        assert_eq!(hex_float(f64::MIN_POSITIVE), "0x1.0000000000000p-1022");
        assert_eq!(hex_float(5e-324), "0x0.0000000000001p-1022");
        assert_eq!(hex_float(f64::MAX), "0x1.fffffffffffffp+1023");
        assert_eq!(hex_float(0.1), "0x1.999999999999ap-4");
    }
}
