use super::graph::Node;
use super::parse::Func;
use super::tape::{Op, Plan};
use super::*;
use crate::number::elementary::CrDec;
use crate::number::param::enclose_decimal;
use crate::number::scalar::{Dual, DualN, DualTheta, Scalar};
use inari::Decoration;

fn iv(a: f64, b: f64) -> Interval {
    Interval::try_from((a, b)).unwrap()
}

const PARAMS: [(&str, &str); 2] = [("g", "9.81"), ("mu", "0.5")];

fn params() -> Vec<(String, Interval)> {
    PARAMS
        .iter()
        .map(|(n, t)| (n.to_string(), enclose_decimal(n, t).unwrap()))
        .collect()
}

fn pairs(list: &[(&str, &str)]) -> Vec<(String, String)> {
    list.iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect()
}

fn compile(defs: &[(&str, &str)], outs: &[&str]) -> Result<Program, ExprError> {
    let outs: Vec<(String, String)> = outs
        .iter()
        .enumerate()
        .map(|(i, t)| (format!("out{i}"), t.to_string()))
        .collect();
    Program::compile(&params(), &pairs(defs), &outs)
}

fn one(defs: &[(&str, &str)], text: &str) -> Program {
    compile(defs, &[text]).unwrap_or_else(|e| panic!("{text}: {e}"))
}

fn eval1<T: Scalar>(p: &Program, t: T, w: T) -> T {
    let mut out = [t];
    p.eval(t, w, &mut out);
    out[0]
}

/// xorshift64*: a fixed, dependency-free stream for generated cases.
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 33) as usize % n
    }
}

/// A random expression of the grammar, written twice: with this module's
/// variable names and with the checker's `t`, `w`.
struct Gen<'a> {
    r: &'a mut Rng,
    names: Vec<String>,
    a: String,
    b: String,
}

impl Gen<'_> {
    fn put(&mut self, a: &str, b: &str) {
        let space = if self.r.below(3) == 0 { " " } else { "" };
        self.a.push_str(a);
        self.a.push_str(space);
        self.b.push_str(b);
        self.b.push_str(space);
    }
    fn same(&mut self, s: &str) {
        self.put(s, s);
    }
    fn expr(&mut self, d: usize) {
        self.term(d);
        for _ in 0..self.r.below(3) {
            let op = ["+", "-"][self.r.below(2)];
            self.same(op);
            self.term(d);
        }
    }
    fn term(&mut self, d: usize) {
        self.unary(d);
        for _ in 0..self.r.below(3) {
            let op = ["*", "/"][self.r.below(2)];
            self.same(op);
            self.unary(d);
        }
    }
    fn unary(&mut self, d: usize) {
        if self.r.below(6) == 0 {
            self.same("-");
            self.unary(d);
            return;
        }
        self.atom(d);
        if self.r.below(4) == 0 {
            let n = self.r.below(5).to_string();
            self.same("^");
            self.same(&n);
        }
    }
    fn atom(&mut self, d: usize) {
        if d == 0 || self.r.below(2) == 0 {
            let leaves = ["0", "1", "2", "0.1", "3.75", "1e-3", "2.5E+1", "12"];
            match self.r.below(6) {
                0 => self.put("theta", "t"),
                1 => self.put("theta_dot", "w"),
                2 => {
                    let n = ["pi", "g", "mu"][self.r.below(3)];
                    self.same(n);
                }
                3 if !self.names.is_empty() => {
                    let n = self.names[self.r.below(self.names.len())].clone();
                    self.same(&n);
                }
                _ => {
                    let n = leaves[self.r.below(leaves.len())];
                    self.same(n);
                }
            }
            return;
        }
        let mut two = false;
        if self.r.below(2) == 0 {
            self.same("(");
        } else {
            let f = FUNCTIONS[self.r.below(FUNCTIONS.len())];
            two = f == "min" || f == "max";
            self.same(f);
            self.same("(");
        }
        self.expr(d - 1);
        if two {
            self.same(",");
            self.expr(d - 1);
        }
        self.same(")");
    }
}

fn generate(r: &mut Rng, names: &[String], depth: usize) -> (String, String) {
    let mut g = Gen {
        r,
        names: names.to_vec(),
        a: String::new(),
        b: String::new(),
    };
    g.expr(depth);
    (g.a, g.b)
}

fn same_dec(a: DecInterval, b: DecInterval) -> bool {
    a.interval() == b.interval() && a.decoration() == b.decoration()
}

/// The tape and the checker's evaluator give the same enclosures and
/// decorations for random texts with shared definitions.
#[test]
fn agrees_with_the_checker() {
    let mut r = Rng(0x9e37_79b9_7f4a_7c15);
    let checker_params: Vec<(String, String)> = pairs(&PARAMS);
    let boxes = [
        (iv(0.25, 0.5), iv(-1.5, 2.0)),
        (iv(0.7, 0.7), iv(-0.3, -0.3)),
        (iv(-3.0, 1.0), iv(0.5, 4.0)),
    ];
    for case in 0..300 {
        let mut names = Vec::new();
        let (mut mine, mut theirs) = (Vec::new(), Vec::new());
        for k in 0..r.below(4) {
            let (a, b) = generate(&mut r, &names, 2);
            let name = format!("d{k}");
            mine.push((name.clone(), a));
            theirs.push((name.clone(), b));
            names.push(name);
        }
        let (a, b) = generate(&mut r, &names, 3);
        // Definitions in any order: give them reversed.
        mine.reverse();
        let p = Program::compile(&params(), &mine, &[("out".into(), a.clone())])
            .unwrap_or_else(|e| panic!("case {case}: {a}: {e}"));
        for &(t, w) in &boxes {
            let want = detach_check::eval_on_box(&checker_params, &theirs, &b, t, w)
                .unwrap_or_else(|e| panic!("case {case}: {b}: {e}"));
            let got = eval1(&p, DecInterval::new(t), DecInterval::new(w));
            assert!(
                same_dec(got, want),
                "case {case}: {a} with {mine:?}: {got:?} vs checker {want:?}"
            );
            let plain = eval1(&p, t, w);
            assert_eq!(Some(plain), want.interval(), "case {case}: {a}");
        }
    }
}

/// Every form of FORMAT.md's `number` (digits before or after the point,
/// or both) is read as the checker reads it, and a point without digits
/// is refused by both.
#[test]
fn numbers_are_read_as_the_checker_reads_them() {
    let (t, w) = (iv(0.25, 0.5), iv(-1.5, 2.0));
    for text in [
        "1.",
        ".5",
        "2.e1",
        ".5e-1",
        "0.1",
        "3e2",
        "X - .1*2.",
        "1.E+2",
    ] {
        let p = one(&[], &text.replace('X', "theta"));
        let want = detach_check::eval_on_box(&[], &[], &text.replace('X', "t"), t, w)
            .unwrap_or_else(|e| panic!("{text}: {e}"));
        assert!(
            same_dec(eval1(&p, DecInterval::new(t), DecInterval::new(w)), want),
            "{text}"
        );
    }
    for text in [".", ".e1", "1 + .", "1.2.3", "1..2"] {
        let mine = Program::compile(&params(), &[], &[("out".into(), text.into())]);
        let theirs = detach_check::eval_on_box(&[], &[], text, t, w);
        assert!(
            mine.is_err() && theirs.is_err(),
            "{text}: {mine:?} / {theirs:?}"
        );
    }
}

/// Fixed expressions against a direct evaluation in inari.
#[test]
fn fixed_expressions_by_hand() {
    let (t, w) = (iv(0.25, 0.5), iv(-1.5, 2.0));
    let g = enclose_decimal("g", "9.81").unwrap();
    let p = one(&[], "-g + 2*theta_dot^2*sin(theta) - theta/3^3");
    let three = iv(3.0, 3.0);
    let want = -g + iv(2.0, 2.0) * w.sqr() * t.sin() - t / three.powi(3);
    assert_eq!(eval1(&p, t, w), want);
    // -x^2 is -(x^2); left-associative subtraction and division.
    let p = one(&[], "-theta_dot^2 - 1 - theta / 2 / theta_dot");
    let want = -w.sqr() - iv(1.0, 1.0) - t / iv(2.0, 2.0) / w;
    assert_eq!(eval1(&p, t, w), want);
    // A decimal literal is the tightest enclosure of its value.
    let p = one(&[], "0.1");
    assert_eq!(eval1(&p, t, w), enclose_decimal("x", "0.1").unwrap());
    assert!(eval1(&p, t, w).inf() < eval1(&p, t, w).sup());
}

#[test]
fn shared_subexpressions_are_one_node() {
    let count = |p: &Program, f: Func| {
        p.tape
            .iter()
            .filter(|n| matches!(n, Node::Call(g, _) if *g == f))
            .count()
    };
    // theta, sin, theta_dot, *, +, sqr, -
    let p = one(&[("s", "sin(theta)")], "s*theta_dot + s - s^2");
    assert_eq!(count(&p, Func::Sin), 1);
    assert_eq!(p.len(), 7);
    // theta, sin, +
    let p = one(&[], "sin(theta) + sin(theta)");
    assert_eq!(p.len(), 3);
    // Across outputs and definitions alike.
    let p = compile(&[("c", "cos(theta)")], &["cos(theta)*2", "c*2", "c"]).unwrap();
    assert_eq!(count(&p, Func::Cos), 1);
    assert_eq!(p.len(), 4);
    // Different operand order is a different operation (no rewriting).
    let p = one(&[], "theta*theta_dot + theta_dot*theta");
    assert_eq!(p.len(), 5);
    // Unused definitions are not on the tape.
    assert_eq!(one(&[("u", "ln(theta)")], "theta").len(), 1);
}

#[test]
fn degree_in_theta_dot() {
    let deg = |defs: &[(&str, &str)], text: &str| one(defs, text).theta_dot_degree(0);
    assert_eq!(deg(&[], "theta_dot^2*sin(theta)"), Some(2));
    assert_eq!(deg(&[], "1/theta_dot"), None);
    assert_eq!(deg(&[], "sin(theta_dot)"), None);
    assert_eq!(deg(&[], "(theta_dot+1)^3"), Some(3));
    let x = [("x", "theta_dot^2 + theta_dot*g")];
    assert_eq!(deg(&x, "x/(theta+1)"), Some(2));
    assert_eq!(deg(&x, "(theta+1)/x"), None);
    assert_eq!(deg(&[], "abs(theta_dot)"), None);
    assert_eq!(deg(&[], "sqrt(theta^2 + 1)*mu"), Some(0));
    assert_eq!(deg(&[], "theta_dot*theta_dot*theta_dot^0"), Some(2));
    assert_eq!(deg(&[], "-theta_dot - theta_dot*theta"), Some(1));
    assert_eq!(one(&[], "1").theta_dot_degree(1), None);
}

/// `c2, c1, c0` of the quadratic output 0 of `p` at θ, from its values
/// at θ̇ = −1, 0, 1 (c0 = f(0), c1 = (f(1) − f(−1))/2,
/// c2 = (f(1) + f(−1))/2 − f(0)), each with a tolerance for f64 rounding.
fn sampled_coefficients(p: &Program, theta: f64) -> [(f64, f64); 3] {
    let f = |w: f64| eval1(p, theta, w);
    let (f0, f1, fm) = (f(0.0), f(1.0), f(-1.0));
    [(f1 + fm) / 2.0 - f0, (f1 - fm) / 2.0, f0]
        .map(|c| (c, 1e-12 * (1.0 + c.abs() + f1.abs() + fm.abs())))
}

/// The three coefficients in f64 against the original at θ̇ = −1, 0, 1
/// ([`sampled_coefficients`]).
#[test]
fn quadratic_coefficients_reproduce_the_function() {
    let defs = [
        ("x", "(theta_dot + sin(theta))^2*cos(theta)"),
        ("y", "theta_dot*(1 + theta)/(2 + theta)"),
    ];
    let texts = [
        "x - y + 3/(1+theta^2) - (2*theta_dot - 1)*(theta_dot+theta)",
        "-(theta_dot*mu - g)^2/g",
        "theta_dot",
        "-theta_dot",
        "theta_dot^0*theta + theta_dot^1",
        "ln(theta + 4)",
        "(theta_dot*theta)^2 - theta_dot/theta",
    ];
    for text in texts {
        let p = one(&defs, text);
        let q = p.quadratic(0).unwrap_or_else(|| panic!("{text}"));
        assert_eq!(q.outputs(), 3);
        assert!(q.tape.iter().all(|n| *n != Node::ThetaDot), "{text}");
        for theta in [0.5, -1.25, 2.0, 0.375] {
            let mut c = [0.0; 3];
            q.eval(theta, f64::NAN, &mut c);
            for (k, (want, tol)) in sampled_coefficients(&p, theta).into_iter().enumerate() {
                assert!(
                    (c[k] - want).abs() <= tol,
                    "{text} θ={theta}: {c:?} vs {want}"
                );
            }
        }
    }
    assert!(one(&[], "theta_dot^3").quadratic(0).is_none());
    assert!(one(&[], "abs(theta_dot)").quadratic(0).is_none());
    assert!(one(&[], "theta").quadratic(1).is_none());
}

/// The factored form (a/b)·(c2·θ̇² + c1·θ̇ + c0) reproduces the function
/// (against it at θ̇ = 0, 1, −1 as in the test above), a and b are θ̇-free, and
/// the quadratic of `U/V`, `-(k*U)`, `3*U*W/(l*V)` is U's own, bit for
/// bit: none of the factor's rounding reaches it.
#[test]
fn factored_quadratics_take_theta_only_factors_apart() {
    let defs = [
        ("U", "sin(theta)*theta_dot^2 - g"),
        ("V", "1 + 3*cos(theta)^2 - 3*mu*sin(theta)*cos(theta)"),
        ("W", "cos(theta) - mu*sin(theta)"),
    ];
    let cases = [
        ("U/V", true),
        ("-(U/V)", true),
        ("-(mu*U)", true),
        ("3*U*W/(g*V)", true),
        ("U*W", true),
        ("U", false),
        ("U/V - 1", false),
        ("(theta_dot - 1)*(theta_dot + V)", false),
    ];
    let u = one(&defs, "U").quadratic(0).unwrap();
    for (text, peeled) in cases {
        let p = one(&defs, text);
        let q = p.factored_quadratics(&[0]).unwrap();
        assert_eq!(q.outputs(), 5);
        assert!(q.tape.iter().all(|n| *n != Node::ThetaDot), "{text}");
        for theta in [0.5, -1.25, 2.0, 0.375] {
            let mut c = [0.0; 5];
            q.eval(theta, f64::NAN, &mut c);
            for (k, (want, tol)) in sampled_coefficients(&p, theta).into_iter().enumerate() {
                let got = c[0] / c[1] * c[k + 2];
                assert!((got - want).abs() <= tol, "{text} θ={theta}: {c:?}");
            }
            if peeled {
                let t = iv(theta, theta);
                let mut got = [t; 5];
                q.eval(t, Interval::ENTIRE, &mut got);
                let mut want = [t; 3];
                u.eval(t, Interval::ENTIRE, &mut want);
                assert_eq!(got[2..], want, "{text} θ={theta}");
                // The factor itself has no quotient at its top.
                assert!(q.tape.iter().all(|n| !matches!(n, Node::Div(..))), "{text}");
            }
        }
    }
    // No factor: a = b = 1 exactly, and the quadratic is the unfactored one.
    let t = iv(0.5, 0.75);
    let plain = one(&defs, "U/V - 1");
    let (mut got, mut want) = ([t; 5], [t; 3]);
    plain
        .factored_quadratics(&[0])
        .unwrap()
        .eval(t, t, &mut got);
    plain.quadratic(0).unwrap().eval(t, t, &mut want);
    assert_eq!(got[..2], [iv(1.0, 1.0); 2]);
    assert_eq!(got[2..], want);
}

/// `A*theta_dot^2 + B*theta_dot + C` gives A, B, C themselves.
#[test]
fn quadratic_of_the_canonical_form_is_bit_identical() {
    let defs = [
        ("A", "sin(theta)*2.5 - mu"),
        ("B", "cos(theta) - 0.1"),
        ("C", "ln(theta + 3)/g"),
    ];
    let direct = compile(&defs, &["A", "B", "C"]).unwrap();
    let t = iv(0.1, 0.35);
    let mut want = [t; 3];
    direct.eval(t, t, &mut want);
    for text in [
        "A*theta_dot^2 + B*theta_dot + C",
        "(sin(theta)*2.5 - mu)*theta_dot^2 + (cos(theta) - 0.1)*theta_dot + ln(theta + 3)/g",
    ] {
        let q = one(&defs, text).quadratic(0).unwrap();
        let mut got = [t; 3];
        q.eval(t, Interval::ENTIRE, &mut got);
        assert_eq!(got, want, "{text}");
        // The same tape: nothing beyond A, B, C and what they need.
        assert_eq!(q.len(), direct.len(), "{text}");
    }
    // Missing terms are exact zeros; θ̇ alone has coefficient exactly 1.
    let q = one(&defs, "theta_dot + C").quadratic(0).unwrap();
    let mut got = [t; 3];
    q.eval(t, t, &mut got);
    assert_eq!(got[0], iv(0.0, 0.0));
    assert_eq!(got[1], iv(1.0, 1.0));
    assert_eq!(got[2], want[2]);
}

fn err(defs: &[(&str, &str)], text: &str) -> ExprError {
    match compile(defs, &[text]) {
        Ok(_) => panic!("{text:?} compiled"),
        Err(e) => e,
    }
}

#[test]
fn errors_name_the_key_and_position() {
    let e = err(&[], "1 + foo");
    assert_eq!((e.key.as_str(), e.offset), ("out0", Some(5)));
    assert!(e.message.contains("unknown name `foo`"), "{e}");
    assert_eq!(e.to_string(), "`out0` at character 5: unknown name `foo`");
    let e = err(&[("a", "theta + bar")], "a");
    assert_eq!((e.key.as_str(), e.offset), ("a", Some(9)));
    let e = err(&[], "2*foo(theta)");
    assert_eq!(e.offset, Some(3));
    assert!(e.message.contains("unknown function"), "{e}");
    // Positions count characters, not bytes.
    let e = err(&[], "1 + θ");
    assert_eq!(e.offset, Some(5));
    let e = err(&[], "theta^2^3");
    assert_eq!(e.offset, Some(8));
    let e = err(&[], "theta^-1");
    assert_eq!(e.offset, Some(7));
    assert!(err(&[], "theta^1.5").message.contains("integer"));
    assert!(err(&[], "theta^99999999999").message.contains("too large"));
    let e = err(&[], "(theta+1");
    assert_eq!(e.offset, Some(9));
    let e = err(&[], "theta+1)");
    assert_eq!(e.offset, Some(8));
    assert!(e.message.contains("')'"));
    for blank in ["", "  \t\n"] {
        let e = err(&[], blank);
        assert_eq!((e.offset, e.message.as_str()), (None, "empty expression"));
        assert_eq!(e.to_string(), "`out0`: empty expression");
    }
    assert!(err(&[], "1 +").offset == Some(4));
    assert!(err(&[], "sin theta").message.contains("'('"));
    assert_eq!(err(&[], ". + 1").offset, Some(1));
    assert!(err(&[], "1e999").message.contains("too large"));
    assert!(err(&[], "1e99999999").message.contains("decimal"));
}

#[test]
fn length_and_depth_limits() {
    let long = format!("1{}", "+1".repeat(5000));
    assert_eq!(long.len(), 10_001);
    let e = err(&[], &long);
    assert!(e.message.contains("longer than 10000"), "{e}");
    assert!(compile(&[], &[&long[..9_999]]).is_ok());
    for open in ["(", "sin(", "abs(("] {
        let per = open.matches('(').count();
        let nest = |n: usize| format!("{}1{}", open.repeat(n), ")".repeat(n * per));
        assert!(compile(&[], &[&nest(100 / per)]).is_ok(), "{open}");
        let e = err(&[], &nest(100 / per + 1));
        assert!(e.message.contains("nested"), "{e}");
        assert!(e.offset.is_some());
    }
    assert!(compile(&[], &[&format!("{}1", "-".repeat(100))]).is_ok());
    let e = err(&[], &format!("{}1", "-".repeat(101)));
    assert_eq!(e.offset, Some(101));
}

#[test]
fn cycles_and_names() {
    let e = err(&[("a", "b + 1"), ("b", "c*2"), ("c", "theta - a")], "a");
    assert_eq!(e.key, "a");
    assert!(e.message.contains("a -> b -> c -> a"), "{e}");
    assert_eq!(e.offset, Some(1));
    let e = err(&[("x", "1"), ("s", "x*s")], "x");
    assert!(e.message.contains("s -> s"), "{e}");
    assert_eq!((e.key.as_str(), e.offset), ("s", Some(3)));
    // Reserved and repeated names.
    for bad in ["t", "w", "pi", "theta", "theta_dot", "sin", "abs"] {
        let e = err(&[(bad, "1")], "1");
        assert_eq!(e.key, bad);
        let p = vec![(bad.to_string(), iv(1.0, 1.0))];
        let e = Program::compile(&p, &[], &[]).unwrap_err();
        assert_eq!(e.key, bad);
        assert!(e.message.contains("reserved"));
    }
    assert_eq!(err(&[("g", "1")], "1").key, "g");
    assert_eq!(err(&[("a", "1"), ("a", "2")], "1").key, "a");
    assert_eq!(err(&[("2a", "1")], "1").key, "2a");
    assert_eq!(err(&[("a-b", "1")], "1").key, "a-b");
    // Case-sensitive names: `G` is not `g`.
    assert!(err(&[], "G").message.contains("unknown name"));
    assert!(compile(&[("G", "2*g"), ("T", "theta")], &["G*T"]).is_ok());
}

/// Token soups and arbitrary bytes: always a result, never a panic.
#[test]
fn garbage_never_panics() {
    let mut r = Rng(12345);
    let atoms = [
        "theta",
        "theta_dot",
        "(",
        ")",
        "+",
        "-",
        "*",
        "/",
        "^",
        "2",
        "1.5",
        "e",
        "1e",
        "sin",
        "abs",
        "pi",
        "g",
        "a",
        "b",
        " ",
        ".",
        "_",
        "θ",
        "\u{0}",
        "9e99999",
        "^^",
        ",",
    ];
    let mut oks = 0;
    for _ in 0..400 {
        let mut soup = || {
            let mut s = String::new();
            for _ in 0..1 + r.below(6) {
                s.push_str(atoms[r.below(atoms.len())]);
            }
            s
        };
        let defs = vec![("a".to_string(), soup()), ("b".to_string(), soup())];
        let outs = vec![("o".to_string(), soup())];
        let _ = Program::compile(&params(), &defs, &outs);
        if Program::compile(&params(), &[], &[("o".into(), soup())]).is_ok() {
            oks += 1;
        }
        let bytes: Vec<u8> = (0..r.below(24)).map(|_| r.below(256) as u8).collect();
        let text = String::from_utf8_lossy(&bytes).into_owned();
        let _ = Program::compile(&[], &[], &[("o".into(), text)]);
    }
    assert!(oks > 0 && oks < 400, "{oks}");
}

/// Gradients through the tape against derivatives by hand.
#[test]
fn dual_derivatives() {
    let p = one(
        &[("x", "theta_dot*theta")],
        "x*sin(theta) + theta_dot^3/(1+theta^2) - abs(theta - 2)*mu",
    );
    let (t, w) = (0.7, 1.3);
    let f = eval1(&p, Dual::variable(t, 0), Dual::variable(w, 1));
    let q = 1.0 + t * t;
    let dt = w * t * t.cos() + w * t.sin() - w.powi(3) * 2.0 * t / (q * q) + 0.5;
    let dw = t * t.sin() + 3.0 * w * w / q;
    assert!((f.grad[0] - dt).abs() < 1e-12, "{} vs {dt}", f.grad[0]);
    assert!((f.grad[1] - dw).abs() < 1e-12, "{} vs {dw}", f.grad[1]);
    // Over intervals the gradient encloses the point derivative.
    let pt = |x: f64| iv(x, x);
    let fi = eval1(&p, Dual::variable(pt(t), 0), Dual::variable(pt(w), 1));
    assert!(fi.grad[0].contains(dt) && fi.grad[1].contains(dw));
    // Nested duals: d²/dθ² θ^5 = 20θ³.
    let p = one(&[], "theta^5");
    let x = DualN {
        value: DualN::<f64, 1>::variable(t, 0),
        grad: [DualN::<f64, 1>::constant(1.0)],
    };
    let y = eval1(&p, x, x);
    assert!((y.grad[0].grad[0] - 20.0 * t.powi(3)).abs() < 1e-12);
}

/// abs where its argument may be 0: the gradient is the hull of ±g and
/// is never decorated as a derivative.
#[test]
fn abs_has_no_derivative_at_zero() {
    let p = one(&[], "abs(3*theta)");
    let at = |a: f64, b: f64| {
        let x = DecInterval::new(iv(a, b));
        eval1(&p, Dual::variable(x, 0), Dual::variable(x, 1))
    };
    let f = at(-1.0, 2.0);
    assert_eq!(f.value.interval(), Some(iv(0.0, 6.0)));
    assert_eq!(f.value.decoration(), Decoration::Com);
    assert_eq!(f.grad[0].interval(), Some(iv(-3.0, 3.0)));
    assert_eq!(f.grad[0].decoration(), Decoration::Trv);
    let f = at(-2.0, -1.0);
    assert_eq!(f.grad[0].interval(), Some(iv(-3.0, -3.0)));
    assert_eq!(f.grad[0].decoration(), Decoration::Com);
}

/// atan, exp, sign, min, max over intervals against closed forms (the
/// doubles nearest π/4 = atan(1) and e = exp(1), mpmath to 20 digits:
/// 0.78539816339744830962, 2.7182818284590452354), and their parse errors.
#[test]
fn new_functions_enclose_their_values() {
    let at = |text: &str, t: Interval, w: Interval| eval1(&one(&[], text), t, w);
    let p = |x: f64| iv(x, x);
    let a = at("atan(theta)", p(1.0), p(0.0));
    assert!(a.contains(std::f64::consts::FRAC_PI_4) && a.wid() <= 2.0 * f64::EPSILON);
    let e = at("exp(theta_dot)", p(0.0), p(1.0));
    assert!(e.contains(std::f64::consts::E) && e.wid() <= 4.0 * f64::EPSILON);
    assert_eq!(at("exp(theta)", iv(0.0, 0.0), p(0.0)), p(1.0));
    assert_eq!(at("sign(theta)", iv(-1.0, 2.0), p(0.0)), iv(-1.0, 1.0));
    assert_eq!(at("sign(theta)", iv(0.5, 2.0), p(0.0)), p(1.0));
    assert_eq!(at("sign(theta)", p(0.0), p(0.0)), p(0.0));
    let (t, w) = (iv(0.0, 1.0), iv(0.5, 2.0));
    assert_eq!(at("min(theta, theta_dot)", t, w), iv(0.0, 1.0));
    assert_eq!(at("max(theta, theta_dot)", t, w), iv(0.5, 2.0));
    assert_eq!(at("max(theta, 2*theta_dot) - 1", p(3.0), p(1.0)), p(2.0));
    assert!(err(&[], "min(theta)").message.contains("',' expected"));
    assert!(err(&[], "sign(theta, 1)").message.contains("')' expected"));
    assert!(err(&[], "max(1, 2, 3)").message.contains("')' expected"));
    assert_eq!(err(&[("exp", "1")], "1").key, "exp");
    // Two-argument calls render and re-parse to the same value.
    let q = one(&[], "min(theta, theta_dot*2) + max(1, sign(theta))");
    let (defs, outs) = q.render("q");
    assert!(
        defs.iter().any(|(_, b)| b.starts_with("min(t, q")),
        "{defs:?}"
    );
    assert_eq!(outs.len(), 1);
}

/// Derivatives by hand: at (0.7, 1.3), d/dθ and d/dθ̇ of
/// atan(θ)·exp(θ̇) + min(θ, θ̇) − max(θ², θ̇) are exp(1.3)/1.49 + 1 and
/// atan(0.7)·exp(1.3) − 1 (min picks θ, max picks θ̇). Where min's
/// arguments may meet, and where sign may jump, no derivative is claimed.
#[test]
fn new_functions_have_derivatives_where_they_exist() {
    let p = one(
        &[],
        "atan(theta)*exp(theta_dot) + min(theta, theta_dot) - max(theta^2, theta_dot) + sign(theta)",
    );
    let (t, w) = (0.7f64, 1.3f64);
    let f = eval1(&p, Dual::variable(t, 0), Dual::variable(w, 1));
    let dt = w.exp() / (1.0 + t * t) + 1.0;
    let dw = t.atan() * w.exp() - 1.0;
    assert!((f.grad[0] - dt).abs() < 1e-12, "{} vs {dt}", f.grad[0]);
    assert!((f.grad[1] - dw).abs() < 1e-12, "{} vs {dw}", f.grad[1]);
    let pt = |x: f64| iv(x, x);
    let fi = eval1(&p, Dual::variable(pt(t), 0), Dual::variable(pt(w), 1));
    assert!(fi.grad[0].contains(dt) && fi.grad[1].contains(dw));
    // Over boxes where the kinks and the jump may lie.
    let dec = |a: f64, b: f64| DecInterval::new(iv(a, b));
    let m = one(&[], "min(theta, theta_dot)");
    let g = eval1(
        &m,
        Dual::variable(dec(0.0, 1.0), 0),
        Dual::variable(dec(0.5, 1.5), 1),
    );
    assert_eq!(g.grad[0].decoration(), Decoration::Trv);
    assert!(g.grad[0].interval().unwrap().contains(0.0));
    assert!(g.grad[0].interval().unwrap().contains(1.0));
    let s = one(&[], "sign(theta)");
    let g = eval1(
        &s,
        Dual::variable(dec(-1.0, 1.0), 0),
        Dual::variable(dec(0.0, 0.0), 1),
    );
    assert_eq!(g.grad[0].decoration(), Decoration::Trv);
    let g = eval1(
        &s,
        Dual::variable(iv(-1.0, 1.0), 0),
        Dual::variable(iv(0.0, 0.0), 1),
    );
    assert_eq!(g.grad[0], Interval::ENTIRE);
    let g = eval1(
        &s,
        Dual::variable(iv(1.0, 2.0), 0),
        Dual::variable(iv(0.0, 0.0), 1),
    );
    assert_eq!(g.grad[0], iv(0.0, 0.0));
}

/// Every output of the folded plan against the plan with every entry
/// evaluated as written.
fn unfolded<T: Scalar>(p: &Program, t: T, w: T) -> Vec<T> {
    let plan = Plan::new(&p.tape, &p.consts, &p.outputs, false);
    let mut slots = vec![t; plan.len];
    plan.run(t, None, w, &mut slots);
    plan.outputs.iter().map(|&k| slots[k as usize]).collect()
}

/// Folding operations on constants changes no result of any scalar the
/// tape is evaluated over: bit for bit in `f64` (steering), enclosure and
/// decoration in intervals, value and derivative in duals (random texts,
/// with divisions by 0 and powers of parameters among them).
#[test]
fn folded_constants_give_the_results_of_the_operations() {
    let mut r = Rng(0x2545_f491_4f6c_dd1d);
    let same = |a: DecInterval, b: DecInterval| same_dec(a, b);
    let mut folded_some = 0;
    for case in 0..400 {
        let (a, _) = generate(&mut r, &[], 3);
        let p = one(&[], &a);
        if p.plan.ops.len() < unfolded_ops(&p) {
            folded_some += 1;
        }
        let (t, w) = (iv(0.25, 0.5), iv(-1.5, 2.0));
        let (td, wd) = (DecInterval::new(t), DecInterval::new(w));
        assert!(
            same(eval1(&p, td, wd), unfolded(&p, td, wd)[0]),
            "case {case}: {a}"
        );
        let x = eval1(&p, 0.375, 0.25);
        let y = unfolded(&p, 0.375, 0.25)[0];
        assert!(x.to_bits() == y.to_bits(), "case {case}: {a}: {x} vs {y}");
        let dt = DualTheta::variable(CrDec(td), 0);
        let dw = DualTheta::constant(CrDec(wd));
        let (x, y) = (eval1(&p, dt, dw), unfolded(&p, dt, dw)[0]);
        assert!(
            same(x.value.0, y.value.0) && same(x.grad[0].0, y.grad[0].0),
            "case {case}: {a}: {x:?} vs {y:?}"
        );
    }
    assert!(folded_some > 20, "only {folded_some} texts folded");
}

/// A result's slot is reused once nothing reads it any more: a long sum of
/// terms needs a few slots besides θ, θ̇, `sin θ`, `cos θ` and the
/// constants, not one per operation (the results are those of the plan
/// with one slot per entry: `folded_constants_give_the_results_of_the_operations`).
#[test]
fn slots_are_reused_once_read_for_the_last_time() {
    let terms: Vec<String> = (1..=30)
        .map(|k| format!("sin(theta*{k})*theta_dot"))
        .collect();
    let p = one(&[], &terms.join(" + "));
    assert_eq!(p.plan.ops.len(), 30 * 4 - 1);
    let fixed = 4 + p.plan.consts.len();
    assert!(p.plan.len <= fixed + 3, "{} slots", p.plan.len);
    let (t, w) = (
        DecInterval::new(iv(0.25, 0.5)),
        DecInterval::new(iv(-1.5, 2.0)),
    );
    assert!(same_dec(eval1(&p, t, w), unfolded(&p, t, w)[0]));
}

/// In `f64` a constant is the midpoint of its enclosure, taken from the
/// plan rather than computed at each evaluation: with `k` in [1, 2],
/// `k*theta - k*k` at θ = 1 is 1.5 − 1.5² = −0.75 (`k*k` is not folded:
/// the midpoint of its enclosure [1, 4] is not 1.5²).
#[test]
fn f64_constants_are_the_midpoints_of_their_enclosures() {
    let k = vec![("k".to_string(), iv(1.0, 2.0))];
    let out = [("out".to_string(), "k*theta - k*k".to_string())];
    let p = Program::compile(&k, &[], &out).unwrap();
    assert_eq!(p.plan.consts.len(), 1);
    assert_eq!(eval1(&p, 1.0, 0.0), -0.75);
}

fn unfolded_ops(p: &Program) -> usize {
    Plan::new(&p.tape, &p.consts, &p.outputs, false).ops.len()
}

/// Operations on parameters and literals alone are done once at compile
/// time, functions of constants are not (their kernels differ between the
/// scalar types), and constants only they used are not lifted.
#[test]
fn operations_on_constants_are_folded() {
    // g*mu, -(g*mu) and 2*g folded; theta*..., + theta, sin(g) kept.
    let p = one(&[], "-(g*mu)*theta + 2*g + sin(g)");
    let ops: Vec<Op> = p.plan.ops.iter().map(|s| s.op).collect();
    assert_eq!(ops.len(), 4, "{ops:?}");
    assert!(ops.iter().any(|o| matches!(o, Op::Sin(_))), "{ops:?}");
    // Constants lifted: -(g*mu), 2*g and g (for sin); not mu, nor 2.
    assert_eq!(p.plan.consts.len(), 3);
    // Each value as written.
    let t = DecInterval::new(iv(0.5, 0.5));
    assert!(same_dec(eval1(&p, t, t), unfolded(&p, t, t)[0]));
}
