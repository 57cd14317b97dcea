//! Fuzzing the command line of the built binary on stable Rust (proptest):
//! random and adversarial argument lists — huge, tiny, negative, NaN, inf,
//! hex, `1_000`, unicode, empty strings, repeated and unknown flags, reversed
//! and degenerate windows, parameters at their limits. Every run must:
//!
//! * never panic (no exit 101, no "panicked" on stderr), never die by a signal;
//! * exit 0 or 2 (1 only with an I/O message);
//! * print no NaN or infinity as a number (infinities are JSON `null`);
//! * finish within a time bound (pave and atlas get a small `--max-boxes`
//!   unless the case sets one; the pools' valid counts are small).
//!
//! `cargo test --test fuzz_cli` runs [`CASES`] cases; the ignored soak runs
//! [`SOAK_CASES`] (`cargo test --release --test it fuzz_cli -- --ignored`).

use proptest::prelude::*;
use proptest::test_runner::{Config, TestCaseError, TestRunner};
use std::io::Read;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use wait_timeout::ChildExt;

const CASES: u32 = 1000;
const SOAK_CASES: u32 = 20_000;
const TIME_LIMIT: Duration = Duration::from_secs(30);

const NUMBERS: &[&str] = &[
    "0",
    "-0",
    "1",
    "-1",
    "0.5",
    "2",
    "3",
    "8",
    "17",
    "18",
    "64",
    "4096",
    "4097",
    "1e3",
    "1e-3",
    "1e-300",
    "1e-320",
    "1e308",
    "1e309",
    "1e400",
    "-1e400",
    "1.7976931348623157e308",
    "4.9e-324",
    "NaN",
    "nan",
    "-nan",
    "inf",
    "-inf",
    "infinity",
    "0x10",
    "0x1p-3",
    "1_000",
    "+5",
    " 7 ",
    "",
    " ",
    "1e",
    "e5",
    "--",
    "-",
    ".",
    "1.2.3",
    "1e999999999",
    "9.81",
    "0.19245008972987525",
    "π",
    "pi",
    "-pi",
    "pi/2",
    "-pi/2",
    "pi/0",
    "2pi",
    "١٢٣",
    "ünï",
    "1,5",
];

const WINDOWS: &[&str] = &[
    "0:1",
    "1:0",
    "1:1",
    "-1:1",
    "0:3.1415926535897932",
    "0:pi",
    "-pi:pi",
    "pi/2:pi",
    "-10:10",
    "-11:11",
    "9.99:10",
    "1e-300:1e-299",
    "1.5:1.5000000000000004",
    "1.5:1.5000000000000002",
    "4.42:4.46",
    ":",
    "a:b",
    "nan:1",
    "0:inf",
    "-1e400:0",
    "1",
    "",
    "0:1:2",
    "3.1415926535897931:3.1415926535897933",
];

const PARAMS: &[&str] = &[
    "mu=100",
    "mu=0",
    "mu=-0.1",
    "b=0.999999",
    "b=1",
    "b=0",
    "C=1e-6",
    "m=0",
    "m=1e300",
    "g=-1",
    "g=1e-300",
    "A=1e-200",
    "A=1e400",
    "A=1e300",
    "a=1e-160",
    "p_phi=1e-160",
    "p_phi=1e-170",
    "p_phi=0",
    "p_psi=0",
    "p_psi=2.5",
    "p_psi=-2",
    "c0=50",
    "c0=-50",
    "c0=1e308",
    "x=1",
    "=",
    "mu",
    "mu=",
    "=1",
    "mu==1",
    "p_phi=nan",
    "g=inf",
    "μ=1",
    "",
];

const SCENES: &[&str] = &[
    "viscous-disc",
    "smooth-disc",
    "ice-disc",
    "brick",
    "",
    "ICE-DISC",
];
const EQUATIONS: &[&str] = &["2.9", "2.10", "2.12", "3.3", "2.11", "", "2.90"];

/// One flag and the pool its values come from (`None`: a switch).
#[derive(Clone, Copy, Debug)]
enum Pool {
    Switch,
    Numbers,
    Windows,
    Params,
    Scenes,
    Equations,
    Variants,
    Anything,
}

fn flags(sub: &str) -> &'static [(&'static str, Pool)] {
    use Pool::*;
    match sub {
        "pave" => &[
            ("--scene", Scenes),
            ("--variant", Variants),
            ("--param", Params),
            ("--eps", Numbers),
            ("--max-boxes", Numbers),
            ("--theta", Windows),
            ("--theta-dot", Windows),
            ("--json", Switch),
            ("--bogus", Anything),
        ],
        "atlas" => &[
            ("--scene", Scenes),
            ("--variant", Variants),
            ("--param", Params),
            ("--eps", Numbers),
            ("--max-boxes", Numbers),
        ],
        "scenes" => &[("--json", Switch), ("--bogus", Switch)],
        "roots" => &[
            ("--equation", Equations),
            ("--kappa", Numbers),
            ("--alpha", Numbers),
            ("--scene", Scenes),
            ("--param", Params),
            ("--max-evaluations", Numbers),
            ("--json", Switch),
        ],
        "kappa0" => &[("--json", Switch), ("--kappa", Numbers)],
        "tangency" => &[("--k-max", Numbers), ("--json", Switch)],
        "critical-curve" => &[
            ("--alpha-boxes", Numbers),
            ("--kappa-boxes", Numbers),
            ("--kappa-max", Numbers),
            ("--json", Switch),
        ],
        _ => &[("--help", Switch), ("--version", Switch)],
    }
}

/// Weighted by cost: `atlas` draws six pictures, so it comes rarely.
const SUBCOMMANDS: &[&str] = &[
    "pave",
    "pave",
    "pave",
    "pave",
    "pave",
    "pave",
    "roots",
    "roots",
    "roots",
    "roots",
    "critical-curve",
    "critical-curve",
    "tangency",
    "tangency",
    "scenes",
    "kappa0",
    "kappa0",
    "",
    "frobnicate",
    "atlas",
];

fn pick(pool: Pool) -> BoxedStrategy<String> {
    let from = |xs: &'static [&'static str]| {
        proptest::sample::select(xs)
            .prop_map(|s| s.to_string())
            .boxed()
    };
    match pool {
        Pool::Switch => Just(String::new()).boxed(),
        Pool::Numbers => prop_oneof![
            3 => from(NUMBERS),
            1 => "[-+]?[0-9]{1,3}(\\.[0-9]{0,3})?(e[-+]?[0-9]{1,3})?",
        ]
        .boxed(),
        Pool::Windows => prop_oneof![
            3 => from(WINDOWS),
            1 => "[-]?[0-9]{1,2}(\\.[0-9]{1,17})?:[-]?[0-9]{1,2}(\\.[0-9]{1,17})?",
        ]
        .boxed(),
        Pool::Params => prop_oneof![
            3 => from(PARAMS),
            1 => "(mu|b|C|A|p_phi|p_psi|c0|g|m|a)=[-]?[0-9]{1,3}(e[-+]?[0-9]{1,3})?",
        ]
        .boxed(),
        Pool::Scenes => from(SCENES),
        Pool::Equations => from(EQUATIONS),
        Pool::Variants => from(&["derived", "printed", "both", ""]),
        Pool::Anything => "[^\u{0}]{0,6}".boxed(),
    }
}

/// A command line: subcommand, then flags with values (sometimes as
/// `--flag=value`, sometimes repeated or with the value missing).
fn command_line() -> impl Strategy<Value = Vec<String>> {
    proptest::sample::select(SUBCOMMANDS).prop_flat_map(|sub| {
        let fl = flags(sub);
        let one = (0..fl.len(), any::<u8>()).prop_flat_map(move |(i, style)| {
            let (flag, pool) = fl[i];
            pick(pool).prop_map(move |v| {
                let mut out = vec![];
                match pool {
                    Pool::Switch => out.push(flag.to_string()),
                    _ if style % 7 == 0 => out.push(format!("{flag}={v}")),
                    _ if style % 23 == 1 => out.push(flag.to_string()), // value missing
                    _ => {
                        out.push(flag.to_string());
                        out.push(v);
                    }
                }
                out
            })
        });
        (
            proptest::collection::vec(one, 0..6),
            proptest::sample::select(SCENES),
            any::<bool>(),
        )
            .prop_map(move |(parts, scene, with_scene)| {
                let mut args = vec![];
                if !sub.is_empty() {
                    args.push(sub.to_string());
                }
                if sub == "pave" && with_scene {
                    args.extend(["--scene".to_string(), scene.to_string()]);
                }
                args.extend(parts.into_iter().flatten());
                args
            })
    })
}

/// Runs one command line; `Err` describes a violated property.
fn check(args: &[String], dir: &std::path::Path) -> Result<(), String> {
    let mut args = args.to_vec();
    let sub = args.first().cloned().unwrap_or_default();
    // Time bound: large valid budgets are capped (the budget logic itself
    // is what is being tested; a 10⁹-leaf run would only test patience).
    for cap in [("--max-boxes", 200_000.0), ("--max-evaluations", 1e6)] {
        for i in 0..args.len() {
            let (flag, value) = match args[i].split_once('=') {
                Some((f, v)) => (f.to_string(), Some(v.to_string())),
                None => (args[i].clone(), args.get(i + 1).cloned()),
            };
            if flag != cap.0 {
                continue;
            }
            let too_big = value
                .as_deref()
                .and_then(|v| v.trim().parse::<f64>().ok())
                .is_some_and(|x| x > cap.1 && x.is_finite());
            if too_big {
                if args[i].contains('=') {
                    args[i] = format!("{}={}", cap.0, cap.1);
                } else {
                    args[i + 1] = format!("{}", cap.1);
                }
            }
        }
    }
    let budgeted = matches!(sub.as_str(), "pave" | "atlas");
    if budgeted && !args.iter().any(|a| a.starts_with("--max-boxes")) {
        args.extend(["--max-boxes".into(), "3000".into()]);
    }
    if sub == "atlas" && !args.iter().any(|a| a.starts_with("--eps")) {
        args.extend(["--eps".into(), "0.02".into()]);
    }
    if matches!(sub.as_str(), "atlas" | "tangency" | "critical-curve") {
        args.extend(["--out".into(), dir.to_string_lossy().into_owned()]);
    }
    let start = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_detach"))
        .args(&args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("spawn: {e}"))?;
    // Read both pipes on threads so a large output cannot block the child.
    let mut so = child.stdout.take().unwrap();
    let mut se = child.stderr.take().unwrap();
    let t_out = std::thread::spawn(move || {
        let mut s = Vec::new();
        so.read_to_end(&mut s).ok();
        s
    });
    let t_err = std::thread::spawn(move || {
        let mut s = Vec::new();
        se.read_to_end(&mut s).ok();
        s
    });
    let status = match child.wait_timeout(TIME_LIMIT).map_err(|e| e.to_string())? {
        Some(s) => s,
        None => {
            child.kill().ok();
            child.wait().ok();
            return Err(format!("{args:?}: no answer within {TIME_LIMIT:?}"));
        }
    };
    let stdout = String::from_utf8_lossy(&t_out.join().unwrap()).into_owned();
    let stderr = String::from_utf8_lossy(&t_err.join().unwrap()).into_owned();
    let ctx = || {
        format!(
            "{args:?} ({:.2} s): status {status:?}\nstderr: {stderr}\nstdout: {}",
            start.elapsed().as_secs_f64(),
            &stdout[..stdout.len().min(400)]
        )
    };
    if stderr.contains("panicked") || status.code() == Some(101) {
        return Err(format!("panic: {}", ctx()));
    }
    match status.code() {
        Some(0) | Some(2) => {}
        Some(1) if stderr.contains("cannot write") || stderr.contains("cannot create") => {}
        _ => return Err(format!("exit code: {}", ctx())),
    }
    if let Some(bad) = non_finite_number(&stdout) {
        return Err(format!("`{bad}` printed as a number: {}", ctx()));
    }
    Ok(())
}

/// A NaN or infinity printed where a number belongs. JSON numbers cannot be
/// non-finite (serde writes `null`), so in JSON only string values that are a
/// whole non-finite number count; in tables any `NaN` token counts, and an
/// `inf` token unless it closes an interval written as text, such as the
/// domain `(0, inf)` or the limit `mu -> +inf`.
fn non_finite_number(stdout: &str) -> Option<String> {
    fn walk(v: &serde_json::Value) -> Option<String> {
        match v {
            serde_json::Value::String(s) => {
                let t = s.trim().to_ascii_lowercase();
                let t = t.trim_start_matches(['+', '-']);
                matches!(t, "nan" | "inf" | "infinity").then(|| s.clone())
            }
            serde_json::Value::Array(a) => a.iter().find_map(walk),
            serde_json::Value::Object(o) => o.values().find_map(walk),
            _ => None,
        }
    }
    if let Ok(v) = serde_json::from_str::<serde_json::Value>(stdout) {
        return walk(&v);
    }
    let is_tok = |c: char| c.is_alphanumeric() || c == '.';
    let mut rest = stdout;
    while let Some(i) = rest.find(|c: char| is_tok(c)) {
        let tail = &rest[i..];
        let end = tail.find(|c: char| !is_tok(c)).unwrap_or(tail.len());
        let token = &tail[..end];
        let after = tail[end..].chars().next();
        let before = &rest[..i];
        match token.to_ascii_lowercase().as_str() {
            "nan" => return Some(token.into()),
            "inf" | "infinity"
                if !(matches!(after, Some(')') | Some(']')) || before.ends_with("-> +")) =>
            {
                return Some(token.into())
            }
            _ => {}
        }
        rest = &tail[end..];
    }
    None
}

/// `cases`, or `DETACH_FUZZ_CASES` when set.
fn fuzz(cases: u32) -> u32 {
    let cases = std::env::var("DETACH_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(cases);
    let dir = std::env::temp_dir().join(format!("detach-fuzz-{}", std::process::id()));
    let mut runner = TestRunner::new(Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    });
    let ran = std::sync::atomic::AtomicU32::new(0);
    let failed = std::sync::atomic::AtomicBool::new(false);
    let result = runner.run(&command_line(), |args| {
        ran.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        check(&args, &dir).map_err(|e| {
            // the first failure at once: shrinking can take a while
            if !failed.swap(true, std::sync::atomic::Ordering::Relaxed) {
                eprintln!("fuzz_cli: first failure (shrinking follows): {e}");
            }
            TestCaseError::fail(e)
        })
    });
    std::fs::remove_dir_all(&dir).ok();
    if let Err(e) = result {
        panic!("{e}");
    }
    ran.into_inner()
}

#[test]
fn the_command_line_survives_fuzzing() {
    let n = fuzz(CASES);
    eprintln!("fuzz_cli: {n} command lines, all clean");
    assert!(n >= CASES);
}

#[test]
#[ignore = "soak: thousands of processes (cargo test --release --test it fuzz_cli -- --ignored)"]
fn the_command_line_survives_a_soak() {
    let n = fuzz(SOAK_CASES);
    eprintln!("fuzz_cli soak: {n} command lines, all clean");
}

#[test]
fn adversarial_classics() {
    // Cases from the audit, run every time.
    let dir = std::env::temp_dir().join(format!("detach-fuzz-fixed-{}", std::process::id()));
    let lines: &[&[&str]] = &[
        &[
            "pave",
            "--scene",
            "viscous-disc",
            "--theta",
            "1.5:1.5000000000000004",
            "--theta-dot",
            "4.42:4.46",
        ],
        &[
            "pave",
            "--scene",
            "viscous-disc",
            "--theta",
            "1.5:1.5000000000000004",
            "--theta-dot",
            "4.42:4.46",
            "--eps",
            "1e-300",
        ],
        &["pave", "--scene", "ice-disc", "--scene", "ice-disc"],
        &["pave", "--scene", "smooth-disc", "--max-boxes", "-1"],
        &["pave", "--scene", "smooth-disc", "--param", "A=1e400"],
        &[
            "critical-curve",
            "--alpha-boxes",
            "4096",
            "--kappa-boxes",
            "4096",
        ],
        &[
            "critical-curve",
            "--kappa-max",
            "1e308",
            "--alpha-boxes",
            "4",
        ],
        &[
            "roots",
            "--equation",
            "2.9",
            "--scene",
            "smooth-disc",
            "--param",
            "p_phi=1e-170",
        ],
        &["atlas", "--eps", "1e-320", "--max-boxes", "300"],
        &[
            "pave",
            "--scene",
            "ice-disc",
            "--eps",
            "4.9e-324",
            "--max-boxes",
            "300",
        ],
        &["--version"],
        &["--help"],
        &["pave", "--help"],
        &[],
    ];
    for l in lines {
        let mut args: Vec<String> = l.iter().map(|s| s.to_string()).collect();
        if args.is_empty() {
            // `detach` alone is `detach atlas`: keep it small
            args = ["atlas", "--eps", "0.05"].map(String::from).to_vec();
        }
        check(&args, &dir).unwrap_or_else(|e| panic!("{e}"));
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The exact rational value of a plain decimal literal (sign, digits, an
/// optional fraction and exponent), or `None` if it is not one.
fn exact_rational(text: &str) -> Option<rug::Rational> {
    let t = text.trim();
    let (neg, body) = match t.strip_prefix('-') {
        Some(b) => (true, b),
        None => (false, t.strip_prefix('+').unwrap_or(t)),
    };
    let (mant, exp) = match body.find(['e', 'E']) {
        Some(i) => (&body[..i], body[i + 1..].parse::<i32>().ok()?),
        None => (body, 0),
    };
    let (int, frac) = mant.split_once('.').unwrap_or((mant, ""));
    if int.is_empty() && frac.is_empty()
        || !int.bytes().chain(frac.bytes()).all(|b| b.is_ascii_digit())
    {
        return None;
    }
    let digits: rug::Integer = format!("0{int}{frac}").parse().ok()?;
    let e = exp - frac.len() as i32;
    let pow10 = |k: u32| rug::Integer::from(rug::Integer::u_pow_u(10, k));
    let q = if e >= 0 {
        rug::Rational::from(digits * pow10(e as u32))
    } else {
        rug::Rational::from((digits, pow10((-e) as u32)))
    };
    Some(if neg { -q } else { q })
}

proptest! {
    #![proptest_config(Config { cases: 3000, failure_persistence: None, ..Config::default() })]

    /// `enclose_decimal` never panics, and when it accepts a literal its
    /// enclosure contains the exact rational and is tight (one double, or two
    /// adjacent ones); a refused plain literal is one beyond the double range
    /// (too large, or nonzero and too small).
    #[test]
    fn decimal_enclosures_contain_the_exact_value(
        text in prop_oneof![
            "[-+]?[0-9]{0,25}(\\.[0-9]{0,25})?([eE][-+]?[0-9]{1,3})?",
            "\\PC{0,12}",
        ]
    ) {
        let r = detach::number::param::enclose_decimal("x", &text);
        match (r, exact_rational(&text)) {
            (Ok(x), Some(q)) => {
                let lo = rug::Rational::from_f64(x.inf()).unwrap();
                let hi = rug::Rational::from_f64(x.sup()).unwrap();
                prop_assert!(lo <= q && q <= hi, "{text}: [{}, {}]", x.inf(), x.sup());
                let next = |v: f64| if v == 0.0 { 5e-324 } else if v > 0.0 {
                    f64::from_bits(v.to_bits() + 1)
                } else {
                    f64::from_bits(v.to_bits() - 1)
                };
                prop_assert!(
                    x.inf() == x.sup() || next(x.inf()) == x.sup(),
                    "{text}: not tight: [{:e}, {:e}]", x.inf(), x.sup()
                );
            }
            (Err(detach::number::param::ParamError::TooLarge { .. }), Some(q)) => {
                let max = rug::Rational::from_f64(f64::MAX).unwrap();
                prop_assert!(q.clone().abs() > max, "{text} refused as too large");
            }
            (Err(detach::number::param::ParamError::TooSmall { .. }), Some(q)) => {
                // Nonzero and below the smallest positive double.
                let min = rug::Rational::from_f64(f64::from_bits(1)).unwrap();
                prop_assert!(q != 0 && q.clone().abs() < min, "{text} refused as too small");
            }
            (Err(_), Some(_)) => {
                // plain literals with exponents beyond ±999999 digits are the
                // only others refused; the strategy stays far below
                prop_assert!(false, "{text}: a plain decimal refused");
            }
            (Ok(x), None) => prop_assert!(false, "{text}: accepted as {x:?}"),
            (Err(_), None) => {}
        }
    }
}
