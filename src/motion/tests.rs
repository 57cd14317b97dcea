//! The integrator against closed-form solutions, each reference computed
//! here in MPFR (rug) at 256 bits from its formula, not by the code under
//! test.

use super::*;
use inari::Interval;
use rug::float::Constant;
use rug::ops::Pow;
use rug::{Float, Rational};

const PREC: u32 = 256;

/// A scene whose θ̈ is `acc` (and Ω `{omega < 0}`), domain wide.
fn scene(acc: &str, omega: &str) -> FileScene {
    let text = format!(
        "name = \"test\"\ntitle = \"test\"\n[domain]\ntheta = [\"-10\", \"10\"]\n\
         theta_dot = [\"-10\", \"10\"]\n[parameters]\n[regions]\nomega = \"{omega} < 0\"\n\
         omega0 = \"{omega} < 0\"\n[dynamics]\ntheta_ddot = \"{acc}\"\n"
    );
    FileScene::parse(&text, &[]).expect("a valid test scene")
}

fn contains(x: Interval, r: &Float) -> bool {
    Rational::from_f64(x.inf()).is_some_and(|lo| *r >= lo)
        && Rational::from_f64(x.sup()).is_some_and(|hi| *r <= hi)
}

fn f(x: f64) -> Float {
    Float::with_val(PREC, x)
}

fn series(acc: &str, theta: f64, theta_dot: f64, order: usize) -> [Vec<Interval>; 2] {
    let file = scene(acc, "theta - 100");
    let tape = file.dynamics_taylor().expect("dynamics");
    let p = |x: f64| Interval::try_from((x, x)).unwrap();
    let s = tape
        .ode_series(p(theta), p(theta_dot), order, &mut Vec::new())
        .expect("analytic");
    [s.theta, s.theta_dot]
}

#[test]
fn taylor_coefficients_of_the_separatrix_are_the_gudermannian_ones() {
    // θ̈ = −sin θ from (0, 2): θ = 2 gd(t), gd' = sech = Σ E_{2n} t^{2n}/(2n)!
    // (Euler numbers), so θ_{2n+1} = 2 E_{2n}/(2n+1)! and even ones vanish.
    let euler: [i64; 8] = [1, -1, 5, -61, 1385, -50521, 2702765, -199360981];
    let [th, _] = series("-sin(theta)", 0.0, 2.0, 15);
    for (n, e) in euler.iter().enumerate() {
        let k = 2 * n + 1;
        let fact = Float::with_val(PREC, Float::factorial(k as u32));
        let r = Float::with_val(PREC, 2 * e) / fact;
        assert!(
            contains(th[k], &r),
            "θ_{k} = {:?} should contain {r}",
            th[k]
        );
        assert!(th[k].wid() < 1e-14 * r.to_f64().abs().max(1e-300) + 1e-300);
        assert!(th[k - 1].contains(0.0) && th[k - 1].wid() < 1e-15);
    }
}

#[test]
fn taylor_recurrences_of_each_operation_match_closed_forms() {
    // First-order ODEs in θ̇ with closed-form solutions w(t), θ̈ = g(θ̇):
    // w' = w² → w₀^{k+1}; w' = exp(w) → w = −ln(e^{−w₀} − t), w_k = e^{k w₀}/k;
    // w' = 1/w → w = √(w₀² + 2t), w_k = w₀·C(1/2, k)(2/w₀²)^k.
    let w0 = 0.75;
    let [_, sq] = series("theta_dot^2", 0.0, w0, 12);
    let [_, pw] = series("theta_dot*theta_dot^3/theta_dot^2", 0.0, w0, 12);
    let [_, ex] = series("exp(theta_dot)", 0.0, w0, 12);
    let [_, inv] = series("1/theta_dot", 0.0, w0, 12);
    let [_, ln_form] = series("1/exp(ln(theta_dot))", 0.0, w0, 12);
    let [_, sqrt_form] = series("sqrt(1/theta_dot^2)", 0.0, w0, 12);
    let [_, abs_form] = series(
        "abs(1/theta_dot) + min(0, theta_dot - 5)*0 + max(-1, 0)",
        0.0,
        w0,
        12,
    );
    let mut binom = Rational::from(1);
    for k in 1..=12u32 {
        let wk = f(w0).pow(k + 1);
        assert!(
            contains(sq[k as usize], &wk) && contains(pw[k as usize], &wk),
            "w² at {k}"
        );
        let e = Float::with_val(PREC, f(w0) * k).exp() / k;
        assert!(
            contains(ex[k as usize], &e),
            "exp at {k}: {:?} ∌ {e}",
            ex[k as usize]
        );
        // C(1/2, k) = C(1/2, k−1)·(1/2 − k + 1)/k.
        binom *= (Rational::from((1, 2)) - (k as i32 - 1)) / k;
        let r =
            f(w0) * Float::with_val(PREC, &binom) * (Float::with_val(PREC, 2) / f(w0 * w0)).pow(k);
        for (name, s) in [
            ("1/w", &inv),
            ("1/exp(ln w)", &ln_form),
            ("sqrt", &sqrt_form),
            ("abs", &abs_form),
        ] {
            assert!(
                contains(s[k as usize], &r),
                "{name} at {k}: {:?} ∌ {r}",
                s[k as usize]
            );
            // sqrt(1/w²) goes through 1/w² and back: a few digits lost by degree 12.
            let width = s[k as usize].wid() / r.to_f64().abs();
            assert!(width < 1e-10, "{name} at {k}: relative width {width:e}");
        }
    }
    // w' = 1 + w² → w = tan(t + atan w₀): w₁ = 1 + w₀², w₂ = w₀(1 + w₀²),
    // w₃ = (1 + w₀²)(1 + 3w₀²)/3; w' = cos² w + sin² w = 1 → w = w₀ + t.
    let [_, tn] = series("1 + tan(atan(theta_dot))^2", 0.0, w0, 8);
    let [_, trig] = series("cos(theta_dot)^2 + sin(theta_dot)^2", 0.0, w0, 8);
    let one = || Float::with_val(PREC, 1);
    let w1 = one() + f(w0) * f(w0);
    let w2 = f(w0) * w1.clone();
    let w3 = w1.clone() * (one() + f(3.0) * f(w0) * f(w0)) / 3;
    assert!(contains(tn[1], &w1) && contains(tn[2], &w2) && contains(tn[3], &w3));
    assert!(tn[3].wid() < 1e-14);
    assert!(contains(trig[1], &one()) && trig[1].wid() < 1e-15);
    for (k, c) in trig.iter().enumerate().skip(2) {
        assert!(c.contains(0.0) && c.wid() < 1e-14, "{k}: {c:?}");
    }
}

#[test]
fn an_operation_off_its_analytic_domain_is_refused() {
    let file = scene("sqrt(theta_dot)", "theta - 100");
    let tape = file.dynamics_taylor().unwrap();
    let x = Interval::try_from((-0.5, 0.5)).unwrap();
    assert!(tape.ode_series(x, x, 4, &mut Vec::new()).is_err());
    for acc in [
        "1/theta",
        "abs(theta)",
        "sign(theta)",
        "ln(theta)",
        "min(theta, 0)",
    ] {
        let tape = scene(acc, "theta - 100").dynamics_taylor().unwrap();
        assert!(tape.ode_series(x, x, 4, &mut Vec::new()).is_err(), "{acc}");
    }
}

fn run(acc: &str, omega: &str, theta: &str, theta_dot: &str, t: &str, until: &[Until]) -> Tube {
    let file = scene(acc, omega);
    let mut request = FlowRequest::parse(theta, theta_dot, t).unwrap();
    request.until = until.to_vec();
    flow(&file, &request).unwrap()
}

#[test]
fn the_harmonic_oscillator_is_enclosed_tightly_over_many_periods() {
    // θ̈ = −θ from (1, 0): θ = cos t, θ̇ = −sin t; t = 20 (about 3 periods).
    let tube = run("-theta", "theta - 100", "1", "0", "20", &[]);
    assert_eq!(tube.stop, Stop::End);
    let t = f(20.0);
    let (c, s) = (t.clone().cos(), -t.sin());
    assert!(
        contains(tube.end[0], &c) && contains(tube.end[1], &s),
        "{:?}",
        tube.end
    );
    assert!(
        tube.end[0].wid() < 1e-12 && tube.end[1].wid() < 1e-12,
        "{:?}",
        tube.end
    );
}

#[test]
fn the_pendulum_separatrix_is_enclosed() {
    // θ̈ = −sin θ from (0, 2): θ = 4 atan(eᵗ) − π, θ̇ = 2 sech t; t = 2.
    let tube = run("-sin(theta)", "theta - 100", "0", "2", "2", &[]);
    assert_eq!(tube.stop, Stop::End);
    let e = f(2.0).exp();
    let pi = Float::with_val(PREC, Constant::Pi);
    let th = Float::with_val(PREC, 4) * e.clone().atan() - pi;
    let w = Float::with_val(PREC, 2) / f(2.0).cosh();
    assert!(
        contains(tube.end[0], &th) && contains(tube.end[1], &w),
        "{:?}",
        tube.end
    );
    assert!(
        tube.end[0].wid() < 1e-13 && tube.end[1].wid() < 1e-13,
        "{:?}",
        tube.end
    );
    // Every step's a-priori box holds the solution over the step (at the
    // step's ends, checked against the closed form).
    for s in tube.steps() {
        let a =
            Float::with_val(PREC, 4) * f(s.t0).exp().atan() - Float::with_val(PREC, Constant::Pi);
        assert!(contains(s.apriori[0], &a));
    }
}

#[test]
fn a_box_of_initial_states_keeps_its_event() {
    // θ̈ = −θ from θ = 0, θ̇ ∈ [1 − 5e-4, 1 + 5e-4] (width 1e-3):
    // θ = θ̇₀ sin t reaches 1/2 first at t = asin(1/(2 θ̇₀)).
    let tube = run(
        "-theta",
        "theta - 1/2",
        "0",
        "0.9995:1.0005",
        "3",
        &[Until::Omega],
    );
    assert_eq!(tube.stop, Stop::Event, "{:?}", tube.stop);
    let e = &tube.events[0];
    assert_eq!(e.kind, "U=0");
    for w in [0.9995, 1.0, 1.0005] {
        let t = (Float::with_val(PREC, 0.5) / f(w)).asin();
        assert!(contains(e.time, &t), "{:?} ∌ {t}", e.time);
    }
    // The window is about as wide as the spread of the event times.
    let spread = (0.5f64 / 0.9995).asin() - (0.5f64 / 1.0005).asin();
    assert!(e.time.wid() < 1.5 * spread, "{} vs {spread}", e.time.wid());
}

#[test]
fn a_point_event_is_certified_first_and_narrow() {
    // θ = 2 sin t reaches 1/2 at asin(1/4); the later crossings are not first.
    let tube = run("-theta", "theta - 1/2", "0", "2", "10", &[Until::Omega]);
    assert_eq!(tube.stop, Stop::Event);
    let t = (Float::with_val(PREC, 0.25)).asin();
    let e = &tube.events[0];
    assert!(contains(e.time, &t) && e.time.wid() < 1e-12, "{:?}", e.time);
    assert!(e.slope.inf() > 0.0);
    assert!(tube.end_time.sup() < 0.3);
}

#[test]
fn leaving_the_domain_is_an_event() {
    // θ̈ = 0 from (0, 5): θ = 5t leaves θ ≤ 10 at t = 2.
    let tube = run("0", "theta - 100", "0", "5", "3", &[Until::Domain]);
    assert_eq!(tube.stop, Stop::Event);
    assert_eq!(tube.events[0].kind, "domain");
    assert!(tube.events[0].time.contains(2.0) && tube.events[0].time.wid() < 1e-12);
}

#[test]
fn a_blow_up_stops_the_tube_where_it_is_still_certified() {
    // θ̈ = θ̇² from (0, 1): θ̇ = 1/(1 − t) blows up at t = 1.
    let tube = run("theta_dot^2", "theta - 100", "0", "1", "2", &[]);
    assert!(matches!(tube.stop, Stop::StepFailed(_)), "{:?}", tube.stop);
    assert!(tube.end_time.sup() < 1.0);
    let t = f(tube.end_time.sup());
    let w = Float::with_val(PREC, 1) / (Float::with_val(PREC, 1) - t);
    assert!(contains(tube.end[1], &w));
}

#[test]
fn a_start_on_a_watched_boundary_is_refused() {
    let file = scene("-theta", "theta - 1/2");
    let mut request = FlowRequest::parse("0.5", "0", "1").unwrap();
    request.until = vec![Until::Omega];
    assert!(matches!(
        flow(&file, &request),
        Err(MotionError::Flow(FlowError::StartOnBoundary(_)))
    ));
}

/// The largest θ over [0, T] of θ̈ = −θ from (θ₀, ω₀): θ = R cos(t − φ),
/// R = √(θ₀² + ω₀²), φ = atan2(ω₀, θ₀); for T < π the top R is reached iff
/// 0 ≤ φ ≤ T, else the larger end value. In MPFR.
fn oscillator_max(theta0: f64, omega0: f64, t: f64) -> Float {
    let (a, b) = (f(theta0), f(omega0));
    let r = (a.clone().pow(2u32) + b.clone().pow(2u32)).sqrt();
    let phi = b.clone().atan2(&a);
    if phi >= 0 && phi <= t {
        return r;
    }
    let tt = f(t);
    let end = a.clone() * tt.clone().cos() + b * tt.sin();
    if end > a {
        end
    } else {
        a
    }
}

#[test]
fn reach_sets_of_the_oscillator_agree_with_the_closed_form() {
    use reach::{reach, Fate, ReachOptions};
    // Target θ = 1/2 (Ω = {θ − 1/2 < 0}) within T = 2, from the window
    // θ ∈ [−1, 0.4], θ̇ ∈ [−1, 1].
    let file = scene("-theta", "theta - 0.5");
    let motion = Motion::new(&file, &[Until::Omega]).unwrap();
    let window = [[-1.0, 0.4], [-1.0, 1.0]];
    let t = Interval::try_from((2.0, 2.0)).unwrap();
    let opts = ReachOptions {
        eps: 1.0 / 128.0,
        ..ReachOptions::default()
    };
    let run = reach(&motion, window, t, &opts, |_, _, _| {
        std::ops::ControlFlow::Continue(())
    });
    assert!(run.complete);
    let half = f(0.5);
    let mut decided = 0.0;
    for l in &run.leaves {
        // Corners and centre of each leaf against the closed form.
        let pts = [0.0, 0.5, 1.0].iter().flat_map(|&u| {
            [0.0, 0.5, 1.0].map(|v| {
                (
                    l.theta[0] + u * (l.theta[1] - l.theta[0]),
                    l.theta_dot[0] + v * (l.theta_dot[1] - l.theta_dot[0]),
                )
            })
        });
        let area = (l.theta[1] - l.theta[0]) * (l.theta_dot[1] - l.theta_dot[0]);
        match &l.fate {
            Fate::Reaches(window) => {
                decided += area;
                assert!(window.sup() <= 2.0);
                for (a, b) in pts {
                    assert!(oscillator_max(a, b, 2.0) >= half, "{l:?} at ({a}, {b})");
                }
            }
            Fate::Avoids => {
                decided += area;
                for (a, b) in pts {
                    assert!(oscillator_max(a, b, 2.0) < half, "{l:?} at ({a}, {b})");
                }
            }
            Fate::Undecided(_) => {}
        }
    }
    // The reach set's area by a 500 × 500 midpoint grid of the closed form
    // (in f64: an estimate) lies within the certified bounds, up to the
    // grid's error (about the boundary's length times a cell's side).
    let (inner, outer) = run.area_bounds();
    let max_f64 = |a: f64, b: f64| {
        let phi = b.atan2(a);
        if (0.0..=2.0).contains(&phi) {
            a.hypot(b)
        } else {
            a.max(a * 2f64.cos() + b * 2f64.sin())
        }
    };
    let n = 500;
    let (dx, dy) = (1.4 / n as f64, 2.0 / n as f64);
    let mut grid = 0.0;
    for i in 0..n {
        for j in 0..n {
            let a = -1.0 + (i as f64 + 0.5) * dx;
            let b = -1.0 + (j as f64 + 0.5) * dy;
            if max_f64(a, b) >= 0.5 {
                grid += dx * dy;
            }
        }
    }
    assert!(
        inner <= grid + 0.01 && grid <= outer + 0.01,
        "{inner} {grid} {outer}"
    );
    // Most of the window is decided.
    assert!(decided > 0.9 * 2.8, "decided area {decided}");
    assert!(outer - inner < 0.3, "{inner} {outer}");
}

#[test]
fn a_sign_change_across_a_pole_is_not_a_reach() {
    use reach::{reach, Fate, ReachOptions};
    // θ̈ = 0, θ̇ ≈ 1: θ passes 1/2, where g = 1/(θ − 1/2) jumps from − to +
    // without vanishing. No state reaches g = 0; a sign change read across
    // the pole must not say otherwise.
    let file = scene("0", "1/(theta - 0.5)");
    let motion = Motion::new(&file, &[Until::Omega]).unwrap();
    let window = [[-0.5, 0.0], [0.9, 1.1]];
    let t = Interval::try_from((2.0, 2.0)).unwrap();
    let run = reach(&motion, window, t, &ReachOptions::default(), |_, _, _| {
        std::ops::ControlFlow::Continue(())
    });
    assert!(run
        .leaves
        .iter()
        .all(|l| !matches!(l.fate, Fate::Reaches(_))));
    // The same motion does reach θ = 1/2 itself (g = θ − 1/2).
    let file = scene("0", "theta - 0.5");
    let motion = Motion::new(&file, &[Until::Omega]).unwrap();
    let run = reach(&motion, window, t, &ReachOptions::default(), |_, _, _| {
        std::ops::ControlFlow::Continue(())
    });
    assert!(run
        .leaves
        .iter()
        .all(|l| matches!(l.fate, Fate::Reaches(_))));
}

#[test]
fn backward_steps_enclose_the_past_of_the_separatrix() {
    // θ̈ = −sin θ from (0, 2) back over 2: θ(−2) = 4 atan(e⁻²) − π,
    // θ̇(−2) = 2 sech 2 (closed form, MPFR here).
    let file = scene("-sin(theta)", "theta - 100");
    let mut request = FlowRequest::parse("0", "2", "2").unwrap();
    request.until = vec![];
    request.settings.backward = true;
    let tube = flow(&file, &request).unwrap();
    assert_eq!(tube.stop, Stop::End);
    let pi = Float::with_val(PREC, Constant::Pi);
    let th = Float::with_val(PREC, 4) * f(-2.0).exp().atan() - pi;
    let w = Float::with_val(PREC, 2) / f(2.0).cosh();
    assert!(
        contains(tube.end[0], &th) && contains(tube.end[1], &w),
        "{:?}",
        tube.end
    );
    assert!(tube.end[0].wid() < 1e-12, "{:?}", tube.end);
}

#[test]
fn portrait_curves_stay_on_their_energy_level() {
    // θ̈ = −sin θ conserves E = θ̇²/2 − cos θ: the energy over every box of
    // one certified curve must share a value (the seed's, computed in MPFR).
    let file = scene("-sin(theta)", "theta - 100");
    let window = [[-3.0, 3.0], [-2.5, 2.5]];
    let seeds = [(0.5, 0.3), (-1.0, 1.5), (2.0, -0.7)];
    let opts = portrait::CurveSettings {
        piece: [0.01, 0.01],
        time: 20.0,
        steps: 200,
    };
    let curves = portrait::certified_curves(&file, window, &seeds, &opts);
    assert_eq!(curves.len(), seeds.len());
    for (curve, &(t, w)) in curves.iter().zip(&seeds) {
        let e = f(w) * f(w) / Float::with_val(PREC, 2) - f(t).cos();
        assert!(curve.len() > 50, "{} boxes", curve.len());
        for b in curve {
            let energy = b[1].sqr() / Interval::try_from((2.0, 2.0)).unwrap() - b[0].cos();
            assert!(contains(energy, &e), "{b:?}: E ∈ {energy:?}, seed's {e}");
            assert!(b[0].wid() <= 0.011 && b[1].wid() <= 0.011, "{b:?}");
        }
    }
}

#[test]
fn the_singular_line_is_reached_when_the_closed_form_says() {
    // θ̈ = k(c − θ̇)/(1 − θ) has the solutions θ̇ ≡ c: from (θ₀, c) the state
    // reaches the line θ = 1, where θ̈'s denominator vanishes, at
    // t = (1 − θ₀)/c with θ̇ = c. Bands of θ̇ around c are invariant (θ̈ > 0
    // below c, < 0 above, while θ < 1).
    for (k, c, theta0, t_star) in [
        ("1", "1", "0", 1.0),
        ("3", "2", "0", 0.5),
        ("1", "0.5", "0.25", 1.5),
    ] {
        let acc = format!("{k}*({c} - theta_dot)/(1 - theta)");
        let tube = run(&acc, "theta - 100", theta0, c, "5", &[Until::Singular]);
        assert!(matches!(tube.stop, Stop::Arrival), "{acc}: {:?}", tube.stop);
        let e = &tube.events[0];
        assert_eq!(e.kind, "V=0");
        assert!(
            e.time.contains(t_star) && e.time.wid() < 1e-9,
            "{acc}: {:?}",
            e.time
        );
        assert!(
            e.theta.contains(1.0) && e.theta.wid() < 1e-9,
            "{:?}",
            e.theta
        );
        let w: f64 = c.parse().unwrap();
        assert!(
            e.theta_dot.contains(w) && e.theta_dot.wid() < 1e-6,
            "{:?}",
            e.theta_dot
        );
        // dV/dt = −θ̇ < 0: the line is crossed, not touched.
        assert!(e.slope.sup() < 0.0);
        assert_eq!(tube.end_time, e.time);
    }
}

#[test]
fn the_singular_line_is_reached_moving_left_and_from_a_box() {
    // θ̈ = (−1 − θ̇)/(θ + 1): θ̇ ≡ −1 from (θ₀, −1) reaches θ = −1 at 1 + θ₀.
    let tube = run(
        "(-1 - theta_dot)/(theta + 1)",
        "theta - 100",
        "0:0.001",
        "-1",
        "5",
        &[Until::Singular],
    );
    assert!(matches!(tube.stop, Stop::Arrival), "{:?}", tube.stop);
    let e = &tube.events[0];
    assert!(
        e.time.contains(1.0) && e.time.contains(1.001),
        "{:?}",
        e.time
    );
    assert!(e.time.wid() < 2e-3 && e.theta.contains(-1.0), "{:?}", e);
}

#[test]
fn a_watched_expression_on_the_way_blocks_the_arrival() {
    // θ − 0.999999 vanishes between the last certified set and the line:
    // the first event cannot be the arrival, and the run says why.
    let tube = run(
        "(1 - theta_dot)/(1 - theta)",
        "theta - 0.999999999",
        "0",
        "1",
        "5",
        &[Until::Omega, Until::Singular],
    );
    match &tube.stop {
        // Either the crossing is found first, or the arrival is refused.
        Stop::Event => assert_eq!(tube.events[0].kind, "U=0"),
        Stop::StepFailed(why) => assert!(why.contains("may vanish"), "{why}"),
        other => panic!("{other:?}"),
    }
    // Without the singular line watched the run stops as before.
    let tube = run(
        "(1 - theta_dot)/(1 - theta)",
        "theta - 100",
        "0",
        "1",
        "5",
        &[],
    );
    assert!(matches!(tube.stop, Stop::StepFailed(_)), "{:?}", tube.stop);
}
