//! The checker's expression language, number encodings and decorations,
//! against values worked out by hand.

use detach_check::{base64_decode, decimal_enclosure, eval_on_box, parse_hex_f64};
use inari::{Decoration, Interval};

fn iv(a: f64, b: f64) -> Interval {
    Interval::try_from((a, b)).unwrap()
}

fn at(expr: &str, t: f64, w: f64) -> Interval {
    eval_on_box(&[], &[], expr, iv(t, t), iv(w, w))
        .unwrap()
        .interval()
        .unwrap()
}

fn bad(expr: &str) -> bool {
    eval_on_box(&[], &[], expr, iv(0.0, 1.0), iv(0.0, 1.0)).is_err()
}

/// The functions added with the scene files' `atan exp sign min max`:
/// the doubles nearest π/4 = atan(1) and e = exp(1) (mpmath, 20 digits:
/// 0.78539816339744830962, 2.7182818284590452354) lie in tight enclosures;
/// `min`/`max` take exactly two arguments.
#[test]
fn atan_exp_sign_min_max() {
    let a = at("atan(t)", 1.0, 0.0);
    assert!(a.contains(std::f64::consts::FRAC_PI_4) && a.wid() <= 2.0 * f64::EPSILON);
    let e = at("exp(w)", 0.0, 1.0);
    assert!(e.contains(std::f64::consts::E) && e.wid() <= 4.0 * f64::EPSILON);
    assert_eq!(at("sign(t - w)", 1.0, 4.0), iv(-1.0, -1.0));
    assert_eq!(at("sign(t - w)", 4.0, 4.0), iv(0.0, 0.0));
    assert_eq!(at("min(t, w) + max(t, 2*w)", 1.0, 4.0), iv(9.0, 9.0));
    let s = eval_on_box(&[], &[], "sign(t)", iv(-1.0, 1.0), iv(0.0, 0.0)).unwrap();
    assert_eq!(s.interval(), Some(iv(-1.0, 1.0)));
    assert!(
        s.decoration() < Decoration::Dac,
        "sign is not continuous at 0"
    );
    for text in ["min(t)", "max(t, w, 1)", "abs(t, w)", "min t, w", "t, w"] {
        assert!(bad(text), "{text}");
    }
}

#[test]
fn precedence_and_associativity() {
    assert_eq!(at("2 - 3 - 4", 0.0, 0.0), iv(-5.0, -5.0));
    assert_eq!(at("8 / 4 / 2", 0.0, 0.0), iv(1.0, 1.0));
    assert_eq!(at("2 + 3 * 4", 0.0, 0.0), iv(14.0, 14.0));
    assert_eq!(at("-2^2", 0.0, 0.0), iv(-4.0, -4.0));
    assert_eq!(at("(-2)^2", 0.0, 0.0), iv(4.0, 4.0));
    assert_eq!(at("2*3^2", 0.0, 0.0), iv(18.0, 18.0));
    assert_eq!(at("(2^3)^2", 0.0, 0.0), iv(64.0, 64.0));
    assert_eq!(at("--t", 3.0, 0.0), iv(3.0, 3.0));
    assert_eq!(at("t - -w", 3.0, 2.0), iv(5.0, 5.0));
    assert_eq!(at("t^0", 3.0, 0.0), iv(1.0, 1.0));
    assert_eq!(at("w^3", -2.0, -2.0), iv(-8.0, -8.0));
    assert_eq!(at("1e2 + 2.5E-1", 0.0, 0.0), iv(100.25, 100.25));
    // Literals follow the decimal-text grammar: a digit before or after the point.
    assert_eq!(at("1. + .5 + 5.e-1", 0.0, 0.0), iv(2.0, 2.0));
    assert_eq!(at("abs(t - w)", 1.0, 4.0), iv(3.0, 3.0));
}

#[test]
fn parse_errors() {
    for e in [
        "",
        "t +",
        "(t",
        "t)",
        "2^3^2",
        "t^-1",
        "t^1.5",
        "t^w",
        "2t",
        ".",
        "1.2.3",
        "sin t",
        "sin()",
        "foo(t)",
        "x",
        "T",
        "t w",
        "t ** 2",
        "cosh(t)",
        "t^99999999999",
        "pi(1)",
        "t # w",
        "t\u{00b2}",
    ] {
        assert!(bad(e), "{e:?} should not parse");
    }
    let deep = format!("{}t{}", "(".repeat(500), ")".repeat(500));
    assert!(bad(&deep));
    let negs = format!("{}t", "-".repeat(500));
    assert!(bad(&negs));
    // A long flat sum is fine: no recursion per term.
    let long = vec!["t"; 3000].join("+");
    assert_eq!(at(&long, 1.0, 0.0), iv(3000.0, 3000.0));
}

#[test]
fn names_and_definitions() {
    let p = vec![("a".to_string(), "2".to_string())];
    let d = vec![("s".to_string(), "a*t".to_string())];
    let x = eval_on_box(&p, &d, "s + w", iv(1.0, 1.0), iv(1.0, 1.0)).unwrap();
    assert_eq!(x.interval().unwrap(), iv(3.0, 3.0));
    // Names are case-sensitive; reserved and repeated names are rejected.
    assert!(eval_on_box(&p, &d, "A", iv(1.0, 1.0), iv(1.0, 1.0)).is_err());
    for name in ["t", "w", "pi", "sin", "a", "1a", "_a", "a-b"] {
        let d = vec![(name.to_string(), "1".to_string())];
        assert!(
            eval_on_box(&p, &d, "1", iv(1.0, 1.0), iv(1.0, 1.0)).is_err(),
            "{name}"
        );
    }
    // A definition may not use a later one.
    let d = vec![
        ("u".to_string(), "v".to_string()),
        ("v".to_string(), "1".to_string()),
    ];
    assert!(eval_on_box(&p, &d, "u", iv(1.0, 1.0), iv(1.0, 1.0)).is_err());
    // A definition is one enclosure: s*s on t ∈ [-1, 1] is [-1, 1], s^2 is [0, 1].
    let d = vec![("s".to_string(), "t".to_string())];
    let one = iv(-1.0, 1.0);
    let ss = eval_on_box(&[], &d, "s*s", one, one).unwrap();
    assert_eq!(ss.interval().unwrap(), iv(-1.0, 1.0));
    let sq = eval_on_box(&[], &d, "s^2", one, one).unwrap();
    assert_eq!(sq.interval().unwrap(), iv(0.0, 1.0));
}

#[test]
fn decorations() {
    let dec =
        |e: &str, t: Interval, w: Interval| eval_on_box(&[], &[], e, t, w).unwrap().decoration();
    let (pos, across) = (iv(1.0, 2.0), iv(-1.0, 1.0));
    assert_eq!(dec("ln(t)", pos, pos), Decoration::Com);
    assert!(dec("ln(t)", iv(0.0, 1.0), pos) < Decoration::Def);
    assert!(dec("1/w", pos, across) < Decoration::Def);
    assert!(dec("(1/w)*0 + 1", pos, across) < Decoration::Def);
    assert!(dec("(1/w)^0", pos, across) < Decoration::Def);
    assert!(dec("sqrt(w)", pos, across) < Decoration::Def);
    assert_eq!(dec("sqrt(w)", pos, iv(0.0, 1.0)), Decoration::Com);
    assert!(dec("tan(t)", iv(1.0, 2.0), pos) < Decoration::Def); // π/2 ∈ [1, 2]
    assert_eq!(dec("tan(t)", iv(-1.0, 1.0), pos), Decoration::Com);
    assert_eq!(
        dec("abs(w) + sin(t) + cos(t)", pos, across),
        Decoration::Com
    );
    // pi is an enclosure, not a double.
    let p = eval_on_box(&[], &[], "pi", pos, pos)
        .unwrap()
        .interval()
        .unwrap();
    assert!(p.inf() < p.sup() && p.inf() == std::f64::consts::PI);
    // Literals are enclosed: 0.1 is not a double.
    let x = eval_on_box(&[], &[], "0.1", pos, pos)
        .unwrap()
        .interval()
        .unwrap();
    assert!(x.inf() < 0.1 || x.sup() > 0.1);
    assert!(x.inf() < x.sup());
}

/// C99 hexadecimal of a double, written independently of the checker.
fn hex(x: f64) -> String {
    if x == 0.0 {
        return if x.is_sign_negative() {
            "-0x0p+0".into()
        } else {
            "0x0p+0".into()
        };
    }
    let bits = x.to_bits();
    let sign = if bits >> 63 == 1 { "-" } else { "" };
    let e = ((bits >> 52) & 0x7ff) as i64;
    let f = bits & ((1 << 52) - 1);
    if e == 0 {
        format!("{sign}0x0.{f:013x}p-1022")
    } else {
        format!("{sign}0x1.{f:013x}p{:+}", e - 1023)
    }
}

#[test]
fn hex_round_trips() {
    let mut xs = vec![
        0.0,
        -0.0,
        1.0,
        -1.5,
        0.1,
        std::f64::consts::PI,
        f64::MAX,
        f64::MIN_POSITIVE,
        5e-324,
        -f64::from_bits(0x000f_ffff_ffff_ffff),
        1e300,
        123456.789,
    ];
    let mut s: u64 = 0x9e3779b97f4a7c15;
    for _ in 0..2000 {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        let x = f64::from_bits(s);
        if x.is_finite() {
            xs.push(x);
        }
    }
    for x in xs {
        let y = parse_hex_f64(&hex(x), false).unwrap();
        assert_eq!(y.to_bits(), x.to_bits(), "{}", hex(x));
    }
    assert_eq!(parse_hex_f64("0x3p-1", false), Ok(1.5));
    assert_eq!(parse_hex_f64("0x.8p1", false), Ok(1.0));
    assert_eq!(parse_hex_f64("0x10p-4", false), Ok(1.0));
    assert_eq!(parse_hex_f64("0x1.000p+0000", false), Ok(1.0));
    assert_eq!(parse_hex_f64("0X1P-1", false), Ok(0.5));
    assert_eq!(parse_hex_f64("0x1p-1074", false), Ok(5e-324));
    assert_eq!(
        parse_hex_f64("0x1.fffffffffffffp+1023", false),
        Ok(f64::MAX)
    );
    assert_eq!(parse_hex_f64("inf", true), Ok(f64::INFINITY));
}

#[test]
fn hex_rejects_inexact_and_malformed() {
    for s in [
        "0x1.00000000000008p+0", // 54 significant bits
        "0x1.fffffffffffff8p+1023",
        "0x1p+1024",
        "0x1p-1075",
        "0x3p-1075",                 // 1.5·2⁻¹⁰⁷⁴
        "0x1.0000000000001p-1023",   // subnormal needing 53 bits
        "0x1p+99999999999999999999", // huge exponent
        "0x1p-99999999999999999999",
        "0x1",
        "0x1p",
        "0xp+0",
        "0x.p0",
        "1.5",
        "1p0",
        "+0x1p0",
        "0x1p+-1",
        " 0x1p0",
        "0x1p0 ",
        "0x1.8p+0x",
        "nan",
        "NaN",
        "inf",
        "-inf",
        "infinity",
        "",
        "-",
        "0x1g",
        "0x1.8.8p0",
    ] {
        assert!(parse_hex_f64(s, false).is_err(), "{s:?} accepted");
    }
}

#[test]
fn base64_edge_cases() {
    assert_eq!(base64_decode(""), Ok(vec![]));
    assert_eq!(base64_decode("TQ=="), Ok(b"M".to_vec()));
    assert_eq!(base64_decode("TWE="), Ok(b"Ma".to_vec()));
    assert_eq!(base64_decode("TWFu"), Ok(b"Man".to_vec()));
    assert_eq!(base64_decode("+/+/"), Ok(vec![0xfb, 0xff, 0xbf]));
    for s in [
        "TQ", "TQ=", "TQ===", "T===", "====", "TQ==TQ==", "TW=u", "TR==", "TWF=", "TWFu\n", "TW u",
        "TWF-", "TWF_", "é===",
    ] {
        assert!(base64_decode(s).is_err(), "{s:?} accepted");
    }
}

#[test]
fn decimal_text() {
    let x = decimal_enclosure("0.1").unwrap();
    assert!(x.inf() < 0.1 && 0.1 == x.sup() || x.inf() == 0.1 && 0.1 < x.sup());
    assert_eq!(
        decimal_enclosure("123456789012345").unwrap(),
        iv(123456789012345.0, 123456789012345.0)
    );
    assert_eq!(decimal_enclosure("+.5").unwrap(), iv(0.5, 0.5));
    assert_eq!(decimal_enclosure("-5.e-1").unwrap(), iv(-0.5, -0.5));
    assert_eq!(decimal_enclosure("1E+2").unwrap(), iv(100.0, 100.0));
    let tiny = decimal_enclosure("1e-400").unwrap();
    assert!(tiny.inf() == 0.0 && tiny.sup() == 5e-324);
    for s in [
        "1e309",
        "-1e400",
        "inf",
        "nan",
        "1/3",
        "0x1p0",
        "1e",
        "e5",
        ".",
        "+",
        "1 ",
        " 1",
        "1_000",
        "[1]",
        "1,5",
        "1e100000",
        "1e-100000",
    ] {
        assert!(decimal_enclosure(s).is_err(), "{s:?} accepted");
    }
    assert!(decimal_enclosure(&"1".repeat(2000)).is_err());
}
