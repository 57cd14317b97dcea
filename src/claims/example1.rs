//! §1, Example 1: heavy non-uniform disc, viscous friction — (1.3)–(1.12)
//! and the claims on Fig. 1b.
//!
//! The mechanics the paper states, written here independently of the
//! `scene` module: G moves on a fixed vertical line at height y; the geometric
//! centre is `G − b(cos θ, sin θ)`; the lowest rim point P is the contact
//! point. Velocities come from `v_P = v_G + θ̇ k × (P − G)`, generalised forces
//! from that velocity's Jacobian, and the motion in contact from the Newton
//! equations `m ÿ = −m g + Q_y`, `C θ̈ = Q_θ` with `Λ̈ = 0`, solved exactly
//! (Cramer's rule) for `(ÿ, θ̈, N)`.

use super::exact::{
    agreement, angle_d, angle_dd, dd_const, identity_test, jet2, qdec, sin_cos_of_tan_half, solve,
    strength_of, Identity, RationalPath, Rng, Sample, Q,
};
use super::figures::{
    axis, grid, marks, params_text, series, Curves, FigureOf, FigureSpec, Region, Series, Shape,
    THETA_RAD,
};
use super::files::formula;
use super::witness::{find_difference, find_leaf, labels_on, window};
use super::{dec, enc, shown_at, Check, Outcome, Strength, Verdict};
use crate::number::scalar::{Dual, Scalar};
use crate::pave::{Label, PhaseBox};
use crate::scene::{Angle, ExactTheta, SceneId, Variant};
use inari::{DecInterval, Interval};
use serde_json::json;

/// Parameters of Example 1 in any scalar type.
#[derive(Clone, Copy, Debug)]
pub struct P1<T> {
    pub a: T,
    pub b: T,
    pub m: T,
    pub c: T,
    pub mu: T,
    pub g: T,
}

/// Decimal texts (a, b, m, C, μ, g) of the scene's defaults.
pub const DEFAULTS: [&str; 6] = ["1", "0.5", "1", "0.3", "0.8", "9.81"];
const NAMES: [&str; 6] = ["a", "b", "m", "C", "mu", "g"];

impl<T: Copy> P1<T> {
    /// The values under the names of the scene files.
    pub fn values(&self) -> [(&'static str, T); 6] {
        let v = [self.a, self.b, self.m, self.c, self.mu, self.g];
        [0, 1, 2, 3, 4, 5].map(|i| (NAMES[i], v[i]))
    }

    pub fn map<U>(&self, f: impl Fn(T) -> U) -> P1<U> {
        P1 {
            a: f(self.a),
            b: f(self.b),
            m: f(self.m),
            c: f(self.c),
            mu: f(self.mu),
            g: f(self.g),
        }
    }
}

impl P1<Interval> {
    pub fn texts(t: [&str; 6]) -> P1<Interval> {
        P1 {
            a: dec(t[0]),
            b: dec(t[1]),
            m: dec(t[2]),
            c: dec(t[3]),
            mu: dec(t[4]),
            g: dec(t[5]),
        }
    }
}

impl P1<Q> {
    pub fn exact(t: [&str; 6]) -> P1<Q> {
        P1 {
            a: qdec(t[0]),
            b: qdec(t[1]),
            m: qdec(t[2]),
            c: qdec(t[3]),
            mu: qdec(t[4]),
            g: qdec(t[5]),
        }
    }
    pub fn random(r: &mut Rng) -> P1<Q> {
        let [a, b, m, c, mu, g] = NAMES.map(|n| {
            let q = r.positive();
            r.named(n, q)
        });
        P1 { a, b, m, c, mu, g }
    }
}

pub fn params_json(t: [&str; 6]) -> serde_json::Value {
    NAMES
        .iter()
        .zip(t)
        .map(|(k, v)| (k.to_string(), json!(v)))
        .collect::<serde_json::Map<_, _>>()
        .into()
}

/// The height of G above the lowest rim point, from the geometry: the
/// centre is `b sin θ` below G and the rim `a` below the centre.
pub fn h<T: Scalar>(p: &P1<T>, an: &Angle<T>) -> T {
    p.a + p.b * an.sin
}

/// `(h, h', h'')` by nested duals in θ.
pub fn h_jet<T: Scalar>(p: &P1<T>, s: T, c: T) -> (T, T, T) {
    let pd = p.map(|x| Dual::constant(Dual::constant(x)));
    jet2(h(&pd, &angle_dd(s, c)))
}

/// Height of the lowest rim point above the plane from the geometry, with G
/// at height y: centre at `y − b sin θ`, lowest point `a` below the centre.
pub fn contact_height<T: Scalar>(p: &P1<T>, an: &Angle<T>, y: T) -> T {
    y - p.b * an.sin - p.a
}

/// Velocity `(horizontal, vertical)` of the material point of the disc at P:
/// `v_G + θ̇ k × (P − G)`, `P − G = −(b cos θ, b sin θ + a)`.
pub fn contact_velocity<T: Scalar>(p: &P1<T>, an: &Angle<T>, ydot: T, w: T) -> (T, T) {
    let rx = -(p.b * an.cos);
    let ry = -(p.b * an.sin + p.a);
    (-(w * ry), ydot + w * rx)
}

/// `(θ̈, N)` in contact from the Newton equations (friction `F = −μ v_Px`).
/// `friction_sign` is `1` for the stated mechanics (`−1`: a mutant).
pub fn newton<T: Scalar>(p: &P1<T>, s: T, c: T, w: T, friction_sign: i32) -> (T, T) {
    let an = Angle {
        theta: T::int(0),
        sin: s,
        cos: c,
    };
    let (hh, h1, h2) = h_jet(p, s, c);
    let _ = hh;
    let (zero, one) = (T::int(0), T::int(1));
    // Jacobian of v_P with respect to (ẏ, θ̇)
    let (jx_y, jz_y) = contact_velocity(p, &an, one, zero);
    let (jx_w, jz_w) = contact_velocity(p, &an, zero, one);
    let nu = contact_velocity(p, &an, zero, w).0;
    let f = T::int(-friction_sign) * p.mu * nu;
    // m ÿ − jz_y N = −m g + F jx_y;  C θ̈ − jz_w N = F jx_w;  ÿ − h'θ̈ = h''θ̇²
    let m = vec![
        vec![p.m, zero, -jz_y],
        vec![zero, p.c, -jz_w],
        vec![one, -h1, zero],
    ];
    let r = [-(p.m * p.g) + f * jx_y, f * jx_w, h2 * w.sqr()];
    let x = solve(&m, &r);
    (x[1], x[2])
}

/// The text at `key` of Example 1's file in reading `v`.
fn file<T: Scalar>(v: Variant, key: &str, p: &P1<T>, s: T, c: T, w: T) -> T {
    formula(
        SceneId::ViscousDisc,
        v,
        key,
        &p.values(),
        ExactTheta::trig(s, c),
        w,
    )
}

/// `h(θ)` of (1.3) as printed (`viscous-disc-printed.toml`).
pub fn printed_h<T: Scalar>(p: &P1<T>, s: T, c: T) -> T {
    file(Variant::Printed, "definitions.h", p, s, c, T::int(0))
}

/// θ̈ of (1.7) as printed (`viscous-disc-printed.toml`), or in the
/// derived reading (`viscous-disc.toml`: the same equation without the
/// factor 2 on its left side).
pub fn theta_ddot_1_7<T: Scalar>(v: Variant, p: &P1<T>, s: T, c: T, w: T) -> T {
    file(v, "dynamics.theta_ddot", p, s, c, w)
}

/// The bracket of (1.9)–(1.11) as printed, `μh²h'θ̇ − g(2C + m h'²) −
/// 2C h''θ̇²`: the left side of the printed Ω₀ (1.11), or without the
/// friction term (`with_friction = false`) that of Ω (1.10).
pub fn printed_bracket<T: Scalar>(p: &P1<T>, s: T, c: T, w: T, with_friction: bool) -> T {
    let key = if with_friction {
        "regions.omega0"
    } else {
        "regions.omega"
    };
    file(Variant::Printed, key, p, s, c, w)
}

/// Λ̈ of (1.9) as printed: `N/m` plus the bracket over `2(C + m h'²)`, the
/// bracket and `h'` from the printed file.
pub fn printed_1_9<T: Scalar>(p: &P1<T>, s: T, c: T, w: T, n: T) -> T {
    let h1 = file(Variant::Printed, "definitions.h1", p, s, c, w);
    n / p.m + printed_bracket(p, s, c, w, true) / (T::int(2) * (p.c + p.m * h1.sqr()))
}

/// Ω from the mechanics: Λ̈ in free flight (no reaction, no friction,
/// ÿ = −g, θ̈ = 0) by (1.8): `−g − h''θ̇²`.
pub fn derived_omega<T: Scalar>(p: &P1<T>, s: T, c: T, w: T) -> T {
    let (_, _, h2) = h_jet(p, s, c);
    -p.g - h2 * w.sqr()
}

fn iv(lo: f64, hi: f64) -> Interval {
    Interval::try_from((lo, hi)).unwrap()
}

fn dec_angle(theta: Interval) -> (DecInterval, DecInterval) {
    let an = Angle::new(DecInterval::new(theta));
    (an.sin, an.cos)
}

fn rand_point(r: &mut Rng) -> (P1<Q>, Q, Q, Q, Vec<(String, Q)>) {
    let p = P1::random(r);
    let t = r.tan_half();
    let (s, c) = sin_cos_of_tan_half(t);
    let w = r.signed();
    let pt = vec![("tan(theta/2)".into(), t), ("theta_dot".into(), w)];
    (p, s, c, w, pt)
}

fn id_json(i: &Identity) -> serde_json::Value {
    i.json()
}

/// The point where differences are shown: default parameters, θ = 0
/// (sin θ = 0, cos θ = 1), θ̇ = 1.
fn shown_point() -> (P1<Q>, Q, Q, Q) {
    (P1::exact(DEFAULTS), Q::int(0), Q::int(1), Q::int(1))
}

fn shown_json(extra: &[(&str, &str)]) -> serde_json::Value {
    let mut m = json!({"params": params_json(DEFAULTS), "theta": "0", "theta_dot": "1"});
    for (k, v) in extra {
        m[*k] = json!(v);
    }
    m
}

/// Λ̈ for a given normal reaction N (a free force): the Newton equations
/// `m ÿ = −m g + N`, `C θ̈ = F h + N·(∂v_Pz/∂θ̇)` (viscous friction does not
/// depend on N) solved for the accelerations, then (1.8).
pub fn lambda_ddot_given_n<T: Scalar>(p: &P1<T>, s: T, c: T, w: T, n: T) -> T {
    let an = Angle {
        theta: T::int(0),
        sin: s,
        cos: c,
    };
    let (_, h1, h2) = h_jet(p, s, c);
    let (zero, one) = (T::int(0), T::int(1));
    let (jx_y, jz_y) = contact_velocity(p, &an, one, zero);
    let (jx_w, jz_w) = contact_velocity(p, &an, zero, one);
    let f = -(p.mu * contact_velocity(p, &an, zero, w).0);
    let ydd = (-(p.m * p.g) + f * jx_y + n * jz_y) / p.m;
    let thdd = (f * jx_w + n * jz_w) / p.c;
    ydd - h2 * w.sqr() - h1 * thdd
}

/// `(U, V)` of `Λ̈ = U + V N` under the report's reading (N free).
pub fn u_v<T: Scalar>(p: &P1<T>, s: T, c: T, w: T) -> (T, T) {
    let u = lambda_ddot_given_n(p, s, c, w, T::int(0));
    (u, lambda_ddot_given_n(p, s, c, w, T::int(1)) - u)
}

// ---------------------------------------------------------------- formulas

/// F1.3: `Λ = y − h(θ)` equals the height of the lowest rim point.
/// Mutant: `h = a + b cos θ`.
pub fn f1_3(mutant: bool) -> Outcome {
    let id = identity_test(13, |r| {
        let (p, s, c, _, pt) = rand_point(r);
        let y = r.positive();
        let an = Angle {
            theta: Q::int(0),
            sin: s,
            cos: c,
        };
        let hp = if mutant {
            p.a + p.b * c
        } else {
            printed_h(&p, s, c)
        };
        Sample {
            point: pt,
            lhs: y - hp,
            rhs: contact_height(&p, &an, y),
        }
    });
    formula_verdict(
        id,
        "y − h(θ) is the height of the lowest rim point",
        "Λ = y − a − b sin θ",
    )
}

/// F1.4: the slip velocity of the contact point is `θ̇ h(θ)`. Mutant: `θ̇ a`.
pub fn f1_4(mutant: bool) -> Outcome {
    let id = identity_test(14, |r| {
        let (p, s, c, w, pt) = rand_point(r);
        let an = Angle {
            theta: Q::int(0),
            sin: s,
            cos: c,
        };
        let yd = r.signed();
        let printed = if mutant {
            w * p.a
        } else {
            w * printed_h(&p, s, c)
        };
        Sample {
            point: pt,
            lhs: printed,
            rhs: contact_velocity(&p, &an, yd, w).0,
        }
    });
    formula_verdict(
        id,
        "ν = θ̇ h(θ) is the horizontal velocity of the material contact point (v_G + θ̇k×(P−G))",
        "ν = θ̇ (a + b sin θ)",
    )
}

fn formula_verdict(id: Identity, what: &str, right: &str) -> Outcome {
    if id.agrees() {
        Outcome::new(
            Verdict::Confirmed,
            strength_of(&[&id]),
            format!("{what}: {}", agreement(&[&id])),
            id_json(&id),
        )
    } else {
        Outcome::new(
            Verdict::Error,
            Strength::Exact,
            format!("printed and derived differ exactly at a rational point ({what})"),
            id_json(&id),
        )
        .correct(right.to_string())
    }
}

/// F1.5: `T = ½ m ẏ + ½ C θ̇²` against `½ m|v_G|² + ½ C θ̇²`; if it differs,
/// whether the printed (1.7) follows from the printed T (error) or not (typo).
/// Mutant: the printed T with ẏ².
pub fn f1_5(mutant: bool) -> Outcome {
    let half = |x: Q| x / Q::int(2);
    let t_id = identity_test(15, |r| {
        let (p, _, _, w, mut pt) = rand_point(r);
        let yd = r.signed();
        pt.push(("y_dot".into(), yd));
        let printed = if mutant {
            half(p.m * yd.sqr())
        } else {
            half(p.m * yd)
        } + half(p.c * w.sqr());
        // |v_G|² with v_G = (0, ẏ)
        let derived = half(p.m * (Q::int(0).sqr() + yd.sqr())) + half(p.c * w.sqr());
        Sample {
            point: pt,
            lhs: printed,
            rhs: derived,
        }
    });
    if t_id.agrees() {
        return formula_verdict(t_id, "T = ½ m ẏ² + ½ C θ̇²", "");
    }
    // Kinetic-energy theorem (1.6) with the printed T in contact (ẏ = h'θ̇):
    // ½ m (h''θ̇² + h'θ̈) + C θ̇ θ̈ = −m g h' θ̇ − μ h² θ̇².
    let used = identity_test(151, |r| {
        let (p, s, c, w, pt) = rand_point(r);
        let (hh, h1, h2) = h_jet(&p, s, c);
        let thdd = (-(p.m * p.g * h1 * w) - p.mu * hh.sqr() * w.sqr() - half(p.m * h2 * w.sqr()))
            / (half(p.m * h1) + p.c * w);
        Sample {
            point: pt,
            lhs: theta_ddot_1_7(Variant::Printed, &p, s, c, w),
            rhs: thdd,
        }
    });
    // shown at θ = 0, θ̇ = 1, ẏ = 2 (defaults)
    let (p, s0, c0, w0) = shown_point();
    let yd = Q::int(2);
    let t_printed = half(p.m * yd) + half(p.c * w0.sqr());
    let t_derived = half(p.m * yd.sqr()) + half(p.c * w0.sqr());
    let (hh, h1, h2) = h_jet(&p, s0, c0);
    let thdd_printed_t =
        (-(p.m * p.g * h1 * w0) - p.mu * hh.sqr() * w0.sqr() - half(p.m * h2 * w0.sqr()))
            / (half(p.m * h1) + p.c * w0);
    let witness = json!({
        "printed_T_vs_mechanics": shown_at(&t_id, shown_json(&[("y_dot", "2")]), t_printed, t_derived),
        "printed_1_7_vs_energy_theorem_with_printed_T": shown_at(&used, shown_json(&[]), theta_ddot_1_7(Variant::Printed, &p, s0, c0, w0), thdd_printed_t)});
    if used.agrees() {
        Outcome::new(
            Verdict::Error,
            strength_of(&[&used]),
            "the printed T is wrong and (1.7) follows from it",
            witness,
        )
        .correct("T = ½ m ẏ² + ½ C θ̇²")
    } else {
        Outcome::new(Verdict::Typo, Strength::Exact,
            format!("printed T = ½mẏ + ½Cθ̇² is not the kinetic energy ½mẏ² + ½Cθ̇² ({} vs {} at ẏ = 2, θ̇ = 1, defaults, exact); (1.7) does not follow from the printed T either, so the slip does not propagate (the error of (1.7) is separate, see F1.7)", t_printed.get().to_f64(), t_derived.get().to_f64()),
            witness).correct("T = ½ m ẏ² + ½ C θ̇²")
    }
}

/// F1.6: the kinetic-energy theorem along the contact motion. With the
/// kinetic energy `T = ½ m ẏ² + ½ C θ̇²`, `ẏ = h'θ̇` in contact, `Π = m g y`
/// and θ̈ from the Newton equations, `dT/dt + dΠ/dt = F ν` with ν the
/// horizontal velocity of the material contact point (N does no work: that
/// point has no vertical velocity in contact). Mutant: the power `F θ̇ a`.
pub fn f1_6(mutant: bool) -> Outcome {
    let id = identity_test(16, |r| {
        let (p, s, c, w, pt) = rand_point(r);
        let an = Angle {
            theta: Q::int(0),
            sin: s,
            cos: c,
        };
        let (_, h1, h2) = h_jet(&p, s, c);
        let thdd = newton(&p, s, c, w, 1).0;
        let (yd, ydd) = (h1 * w, h2 * w.sqr() + h1 * thdd);
        let (nu, vz) = contact_velocity(&p, &an, yd, w);
        let f = -(p.mu * nu);
        let power = if mutant { f * w * p.a } else { f * nu };
        // the reaction's power N v_Pz, zero in contact
        let n = r.positive();
        Sample {
            point: pt,
            lhs: p.m * yd * ydd + p.c * w * thdd + p.m * p.g * yd,
            rhs: power + n * vz,
        }
    });
    formula_verdict(
        id,
        "d(½mẏ² + ½Cθ̇²)/dt + d(mgy)/dt = Fν along the contact motion (Newton θ̈, ẏ = h'θ̇), and the contact point has no vertical velocity, so N does no work",
        "dT = −dΠ + F ν dt",
    )
}

/// F1.7: θ̈ of (1.7) against the Newton equations. Mutant: the derived
/// reading's (1.7), without the factor 2.
pub fn f1_7(mutant: bool) -> Outcome {
    let k = if mutant {
        Variant::Derived
    } else {
        Variant::Printed
    };
    let id = identity_test(17, |r| {
        let (p, s, c, w, pt) = rand_point(r);
        Sample {
            point: pt,
            lhs: theta_ddot_1_7(k, &p, s, c, w),
            rhs: newton(&p, s, c, w, 1).0,
        }
    });
    if id.agrees() {
        return formula_verdict(id, "(1.7) against the Newton equations with Λ̈ = 0", "");
    }
    // Is the difference exactly the spurious factor 2 on the left?
    let corrected = identity_test(171, |r| {
        let (p, s, c, w, pt) = rand_point(r);
        Sample {
            point: pt,
            lhs: theta_ddot_1_7(Variant::Derived, &p, s, c, w),
            rhs: newton(&p, s, c, w, 1).0,
        }
    });
    // Certified witness at the default parameters, θ = 0, θ̇ = 1.
    let p = P1::texts(DEFAULTS).map(DecInterval::new);
    let (s, c) = dec_angle(iv(0.0, 0.0));
    let one = DecInterval::new(iv(1.0, 1.0));
    let pr = theta_ddot_1_7(k, &p, s, c, one).interval().unwrap();
    let de = newton(&p, s, c, one, 1).0.interval().unwrap();
    let (qp, qs, qc, qw) = shown_point();
    Outcome::new(Verdict::Error, Strength::Certified,
        format!("θ̈ at θ = 0, θ̇ = 1 (default parameters): printed {:.4} vs Newton {:.4}, certified disjoint; removing the factor 2 on the left {} the Newton equations", pr.mid(), de.mid(), if corrected.agrees() { "reproduces" } else { "does not reproduce" }),
        json!({"params": params_json(DEFAULTS), "theta": "0", "theta_dot": "1",
               "printed_theta_ddot": enc(pr), "newton_theta_ddot": enc(de), "disjoint": pr.disjoint(de),
               "identity": shown_at(&id, shown_json(&[]), theta_ddot_1_7(k, &qp, qs, qc, qw), newton(&qp, qs, qc, qw, 1).0),
               "without_factor_2": corrected.json()}))
        .correct("(C + m h'²) θ̈ + m h' h'' θ̇² = −m g h' − μ h² θ̇ (no factor 2 on the left); it changes (1.9)–(1.11), see F1.9–F1.11")
}

fn viscous_region(printed: bool, omega0: bool) -> Region {
    Box::new(move |th, w| {
        let p = P1::texts(DEFAULTS).map(DecInterval::new);
        let an = Angle::new(DecInterval::new(th));
        let w = DecInterval::new(w);
        let (s, c) = (an.sin, an.cos);
        let d = if omega0 {
            derived_omega0(&p, s, c, w)
        } else {
            derived_omega(&p, s, c, w)
        };
        let pr = if printed {
            printed_bracket(&p, s, c, w, omega0)
        } else {
            d
        };
        [pr, d]
    })
}

/// The defaults of Example 1, as markup.
fn example1_text() -> String {
    format!(
        "Example 1 (viscous disc), defaults {}",
        params_text(&["a", "b", "m", "C", "μ", "g"], &DEFAULTS)
    )
}

/// The picture of F1.7.
fn f1_7_figure(_mark: Option<PhaseBox>) -> FigureSpec {
    let pi = std::f64::consts::PI;
    let theta_dd = "θ\u{308}";
    let p = P1::texts(DEFAULTS).map(|x| x.mid());
    let printed = |t: f64| theta_ddot_1_7(Variant::Printed, &p, t.sin(), t.cos(), 1.0);
    let newton = |t: f64| newton(&p, t.sin(), t.cos(), 1.0, 1).0;
    FigureSpec::Lines(Curves {
        title: format!("F1.7: {theta_dd} of (1.7) as printed against the Newton equations"),
        subtitle: format!("θ\u{307} = 1; {}", example1_text()),
        x: axis(THETA_RAD, [-pi, pi], true),
        y: axis("θ\u{308} (rad/s²)", [-12.0, 9.0], false),
        series: vec![
            series(
                "(1.7) as printed",
                grid(-pi, pi, 400).map(|t| (t, printed(t))).collect(),
            ),
            series(
                "Newton equations",
                grid(-pi, pi, 400).map(|t| (t, newton(t))).collect(),
            ),
        ],
        marks: vec![marks(
            "θ = 0: values certified disjoint",
            vec![(0.0, printed(0.0)), (0.0, newton(0.0))],
            Shape::Dot,
        )],
        zero: true,
    })
}

/// F1.8: `Λ̈ = ÿ − h''θ̇² − h'θ̈` against the second time derivative of
/// `Λ = y − h(θ)` along a rational path `tan(θ(t)/2) = u₀ + u₁t + u₂t²`,
/// `y = y₀ + y₁t + y₂t²`. Mutant: `+h''θ̇²`.
pub fn f1_8(mutant: bool) -> Outcome {
    let id = identity_test(18, |r| {
        let p = P1::random(r);
        let RationalPath {
            u0,
            y2,
            u,
            y,
            w,
            thdd,
            s,
            c,
        } = RationalPath::random(r);
        let (su, cu) = sin_cos_of_tan_half(u);
        let pd = p.map(dd_const);
        let lam = y - h(
            &pd,
            &Angle {
                theta: dd_const(Q::int(0)),
                sin: su,
                cos: cu,
            },
        );
        let lam_dd = jet2(lam).2;
        let (_, h1, h2) = h_jet(&p, s, c);
        let sign = if mutant { Q::int(-1) } else { Q::int(1) };
        let printed = Q::int(2) * y2 - sign * h2 * w.sqr() - h1 * thdd;
        Sample {
            point: vec![("u0".into(), u0)],
            lhs: printed,
            rhs: lam_dd,
        }
    });
    formula_verdict(id, "Λ̈ = ÿ − h''θ̇² − h'θ̈ against d²Λ/dt² along rational paths (ÿ = N/m − g is the vertical Newton equation)", "Λ̈ = ÿ − h''θ̇² − h'θ̈")
}

/// F1.9 under the report's reading of `Λ̈ = U + V N` ([`super::READING`]):
/// the coefficient of N and the rest of (1.9) against V = ∂Λ̈/∂N and U = Λ̈
/// at N = 0 from the Newton equations with N free; then whether (1.9)
/// follows from the printed (1.7) with θ̈ substituted before N is free (the
/// other reading). Mutant: the printed side replaced by the reading's
/// closed form `(1/m + h'²/C) N + μ h² h' θ̇/C − g − h'' θ̇²`.
pub fn f1_9(mutant: bool) -> Outcome {
    let printed = |p: &P1<Q>, s: Q, c: Q, w: Q, n: Q| {
        if mutant {
            let (hh, h1, h2) = h_jet(p, s, c);
            (Q::int(1) / p.m + h1.sqr() / p.c) * n + p.mu * hh.sqr() * h1 * w / p.c
                - p.g
                - h2 * w.sqr()
        } else {
            printed_1_9(p, s, c, w, n)
        }
    };
    let v = identity_test(19, |r| {
        let (p, s, c, w, pt) = rand_point(r);
        Sample {
            point: pt,
            lhs: printed(&p, s, c, w, Q::int(1)) - printed(&p, s, c, w, Q::int(0)),
            rhs: u_v(&p, s, c, w).1,
        }
    });
    let u = identity_test(192, |r| {
        let (p, s, c, w, pt) = rand_point(r);
        Sample {
            point: pt,
            lhs: printed(&p, s, c, w, Q::int(0)),
            rhs: u_v(&p, s, c, w).0,
        }
    });
    let (qp, qs, qc, qw) = shown_point();
    let (u0, v0) = u_v(&qp, qs, qc, qw);
    let (pu, pv) = {
        let pu = printed(&qp, qs, qc, qw, Q::int(0));
        (pu, printed(&qp, qs, qc, qw, Q::int(1)) - pu)
    };
    let reading = json!({"params": params_json(DEFAULTS), "theta": "0", "theta_dot": "1",
        "V": v0.get().to_string(), "U": u0.get().to_string(),
        "printed_V": pv.get().to_string(), "printed_U": pu.get().to_string()});
    if v.agrees() && u.agrees() {
        return Outcome::new(
            Verdict::Confirmed,
            strength_of(&[&v, &u]),
            format!(
                "(1.9) is U + V N with V = ∂Λ̈/∂N and U = Λ̈ at N = 0 (N free): {}",
                agreement(&[&v, &u])
            ),
            json!({"V": v.json(), "U": u.json(), "reading": reading}),
        );
    }
    let follows = identity_test(191, |r| {
        let (p, s, c, w, pt) = rand_point(r);
        let n = r.positive();
        let (_, h1, h2) = h_jet(&p, s, c);
        let rhs = n / p.m - p.g - h2 * w.sqr() - h1 * theta_ddot_1_7(Variant::Printed, &p, s, c, w);
        Sample {
            point: pt,
            lhs: printed_1_9(&p, s, c, w, n),
            rhs,
        }
    });
    let f = |x: Q| x.get().to_f64();
    Outcome::new(Verdict::Error, Strength::Exact,
        format!("under the report's reading (N free): at θ = 0, θ̇ = 1 (defaults) the coefficient of N in (1.9) is {} but V = 1/m + h'²/C = {} = {:.4}, and the rest is {:.4} but U = Λ̈ at N = 0 is {:.4} (exact); (1.9) {} from the printed (1.7) with θ̈ substituted before N is free (the other reading), and inherits its factor 2",
            pv.get(), v0.get(), f(v0), f(pu), f(u0), if follows.agrees() { "follows exactly" } else { "does not follow" }),
        json!({"V": shown_at(&v, shown_json(&[]), pv, v0), "U": shown_at(&u, shown_json(&[]), pu, u0),
               "reading": reading, "from_printed_1_7": follows.json()}))
        .correct("Λ̈ = U + V N with V = 1/m + h'²/C and U = μ h² h' θ̇/C − g − h'' θ̇² (N free; in contact N = −U/V); substituting θ̈ of the corrected (1.7) before N is free gives N/m + (μ h² h' θ̇ − C g − C h'' θ̇²)/(C + m h'²), which is U/(mV) + N/m: the same N at contact")
}

/// The picture of F1.9.
fn f1_9_figure(_mark: Option<PhaseBox>) -> FigureSpec {
    let pi = std::f64::consts::PI;
    let theta_dd = "θ\u{308}";
    // Λ̈ at θ̇ = 1 with the reaction N = m g.
    let p = P1::texts(DEFAULTS).map(|x| x.mid());
    let n = p.m * p.g;
    let by_1_8 = |t: f64, thdd: f64| {
        let (_, h1, h2) = h_jet(&p, t.sin(), t.cos());
        n / p.m - p.g - h2 - h1 * thdd
    };
    let pts = |f: &dyn Fn(f64) -> f64| grid(-pi, pi, 400).map(|t| (t, f(t))).collect();
    FigureSpec::Lines(Curves {
        title: "F1.9: Λ\u{308} of (1.9) as printed against (1.8)".into(),
        subtitle: format!("θ\u{307} = 1, N = mg; {}", example1_text()),
        x: axis(THETA_RAD, [-pi, pi], true),
        y: axis("Λ\u{308} (m/s²)", [-1.0, 6.0], false),
        series: vec![
            series(
                "(1.9) as printed",
                pts(&|t| printed_1_9(&p, t.sin(), t.cos(), 1.0, n)),
            ),
            series(
                format!("(1.8) with the Newton {theta_dd}"),
                pts(&|t| by_1_8(t, newton(&p, t.sin(), t.cos(), 1.0, 1).0)),
            ),
            Series {
                dashed: true,
                ..series(
                    format!("(1.8) with {theta_dd} of (1.7) as printed (dashed): equal to (1.9)"),
                    pts(&|t| {
                        by_1_8(
                            t,
                            theta_ddot_1_7(Variant::Printed, &p, t.sin(), t.cos(), 1.0),
                        )
                    }),
                )
            },
        ],
        marks: vec![],
        zero: true,
    })
}

fn viscous_pair(
    printed: fn(&P1<DecInterval>, DecInterval, DecInterval, DecInterval) -> DecInterval,
    derived: fn(&P1<DecInterval>, DecInterval, DecInterval, DecInterval) -> DecInterval,
) -> impl Fn(Interval, Interval) -> [DecInterval; 2] + Sync {
    move |th: Interval, w: Interval| {
        let p = P1::texts(DEFAULTS).map(DecInterval::new);
        let (s, c) = dec_angle(th);
        let w = DecInterval::new(w);
        [printed(&p, s, c, w), derived(&p, s, c, w)]
    }
}

fn region_outcome(
    found: Option<super::witness::Found>,
    what: &str,
    right: &str,
    f: &dyn Fn(Interval, Interval) -> [DecInterval; 2],
) -> Outcome {
    match found {
        Some(b) => {
            let again = labels_on(&f, b.bx);
            Outcome::new(Verdict::Error, Strength::Certified,
                format!("{what}: box θ ∈ [{:.4}, {:.4}], θ̇ ∈ [{:.4}, {:.4}] is {} the printed set and {} the derived one (default parameters)",
                    b.bx.theta[0], b.bx.theta[1], b.bx.theta_dot[0], b.bx.theta_dot[1],
                    if again[0] == Label::ProvedIn { "inside" } else { "outside" },
                    if again[1] == Label::ProvedIn { "inside" } else { "outside" }),
                json!({"params": params_json(DEFAULTS), "witness": b.json(), "first": "printed", "second": "derived"}))
                .correct(right.to_string())
        }
        None => Outcome::new(
            Verdict::ConfirmedOn,
            Strength::Certified,
            format!("{what}: no box of the window proved in one set and out of the other"),
            json!({"params": params_json(DEFAULTS)}),
        ),
    }
}

/// F1.10: Ω as printed against free-flight Λ̈ < 0. Mutant: the printed side
/// replaced by the derived one.
pub fn f1_10(mutant: bool) -> Outcome {
    let pr: fn(&P1<DecInterval>, DecInterval, DecInterval, DecInterval) -> DecInterval = if mutant {
        derived_omega
    } else {
        |p, s, c, w| printed_bracket(p, s, c, w, false)
    };
    let f = viscous_pair(pr, derived_omega);
    let found = find_difference(&f, window([0.5, 1.0], [4.0, 7.0]), 1.0 / 64.0);
    region_outcome(
        found,
        "Ω of (1.10) vs Ω = {free-flight Λ̈ < 0}",
        "Ω: −g − h''θ̇² < 0, i.e. b θ̇² sin θ < g (Λ̈ in free flight); the printed set follows from the printed (1.9) at N = 0, μ = 0 and is larger where sin θ > 0 (it carries the factor 2 of (1.7)); the inclusions (1.12) hold in both readings (S1.12)",
        &f,
    )
}

/// The picture of F1.10.
fn f1_10_figure(mark: Option<PhaseBox>) -> FigureSpec {
    FigureSpec::Region {
        title: "F1.10: Ω of (1.10) as printed against free flight Λ\u{308} < 0".into(),
        subtitle: example1_text(),
        f: viscous_region(true, false),
        win: window([0.0, 1.6], [0.0, 8.0]),
        names: ["printed (1.10)".into(), "Λ\u{308} < 0".into()],
        mark,
    }
}

/// −N in contact (Ω₀ = {−N < 0}).
pub fn derived_omega0<T: Scalar>(p: &P1<T>, s: T, c: T, w: T) -> T {
    -newton(p, s, c, w, 1).1
}

/// F1.11: Ω₀ as printed against `N > 0` from the Newton equations.
/// Mutant: the printed side replaced by the derived one.
pub fn f1_11(mutant: bool) -> Outcome {
    let pr: fn(&P1<DecInterval>, DecInterval, DecInterval, DecInterval) -> DecInterval = if mutant {
        derived_omega0
    } else {
        |p, s, c, w| printed_bracket(p, s, c, w, true)
    };
    let f = viscous_pair(pr, derived_omega0);
    let found = find_difference(&f, window([-0.25, 0.25], [6.0, 10.0]), 1.0 / 64.0);
    region_outcome(
        found,
        "Ω₀ of (1.11) vs Ω₀ = {N > 0}",
        "Ω₀: μ h² h' θ̇ − C g − C h'' θ̇² < 0 (N > 0 from the Newton equations); the printed set comes from the printed (1.7) and is wrong wherever m h'² ≠ 0; (1.12) still holds (S1.12)",
        &f,
    )
}

/// The picture of F1.11.
fn f1_11_figure(mark: Option<PhaseBox>) -> FigureSpec {
    FigureSpec::Region {
        title: "F1.11: Ω_{0} of (1.11) as printed against N > 0".into(),
        subtitle: example1_text(),
        f: viscous_region(true, true),
        win: window([-1.6, 1.6], [0.0, 10.0]),
        names: ["printed (1.11)".into(), "N > 0".into()],
        mark,
    }
}

// ---------------------------------------------------------------- statements

/// S1.ideal: with μ = 0, `−N = (mC/(C + m h'²))·(free-flight Λ̈)` exactly, so
/// Ω = Ω₀ (the factor is positive). Mutant: μ ≠ 0.
pub fn s1_ideal(mutant: bool) -> Outcome {
    let id = identity_test(101, |r| {
        let (mut p, s, c, w, pt) = rand_point(r);
        if !mutant {
            p.mu = Q::int(0);
        }
        let (_, h1, _) = h_jet(&p, s, c);
        let factor = p.m * p.c / (p.c + p.m * h1.sqr());
        Sample {
            point: pt,
            lhs: derived_omega0(&p, s, c, w),
            rhs: factor * derived_omega(&p, s, c, w),
        }
    });
    if id.agrees() {
        Outcome::new(Verdict::Confirmed, Strength::Argument,
            "Example 1 with μ = 0: −N = mC/(C + m h'²) · (free-flight Λ̈), a positive factor, so Ω = Ω₀ (proved identity); §2 likewise, see S2.omega. In general Λ̈ = U + V N with V = ∇Λ·M⁻¹∇Λ > 0 for an ideal constraint, so N = −U/V > 0 ⟺ U < 0",
            json!({"identity": id.json()}))
    } else {
        Outcome::new(
            Verdict::False,
            Strength::Exact,
            "with friction, −N is not a positive multiple of the free-flight Λ̈",
            json!({"identity": id.json()}),
        )
    }
}

/// S1.friction: a certified box of Ω ∖ Ω₀ at the default parameters (μ = 0.8).
/// Mutant: μ = 0.
pub fn s1_friction(mutant: bool) -> Outcome {
    let mu = if mutant { "0" } else { DEFAULTS[4] };
    let t = [
        DEFAULTS[0],
        DEFAULTS[1],
        DEFAULTS[2],
        DEFAULTS[3],
        mu,
        DEFAULTS[5],
    ];
    let f = move |th: Interval, w: Interval| {
        let p = P1::texts(t).map(DecInterval::new);
        let (s, c) = dec_angle(th);
        let w = DecInterval::new(w);
        [derived_omega(&p, s, c, w), derived_omega0(&p, s, c, w)]
    };
    let found = find_leaf(f, window([-0.25, 0.25], [6.0, 10.0]), 1.0 / 64.0, |l| {
        l == [Label::ProvedIn, Label::ProvedOut]
    });
    match found {
        Some(b) => Outcome::new(Verdict::Confirmed, Strength::Certified,
            format!("μ = {mu}: box θ ∈ [{:.4}, {:.4}], θ̇ ∈ [{:.4}, {:.4}] lies in Ω ∩ Ω̄₀ (paradox of non-existence)", b.bx.theta[0], b.bx.theta[1], b.bx.theta_dot[0], b.bx.theta_dot[1]),
            json!({"params": params_json(t), "witness": b.json(), "first": "Ω", "second": "Ω₀"})),
        None => Outcome::new(Verdict::False, Strength::Certified, format!("μ = {mu}: no box of Ω ∖ Ω₀ found"), json!({"params": params_json(t)})),
    }
}

/// S1.nonunique: Ω̄ ∩ Ω₀ (contact possible with N ≥ 0, detachment possible
/// too) is not empty in Example 1: a certified box out of Ω and in Ω₀ at the
/// defaults, where θ̇ cos θ < 0 (there Ω ⊂ Ω₀ by S1.12). Mutant: μ = 0, where
/// Ω = Ω₀ (S1.ideal) and no such box exists.
pub fn s1_nonunique(mutant: bool) -> Outcome {
    let mu = if mutant { "0" } else { DEFAULTS[4] };
    let t = [
        DEFAULTS[0],
        DEFAULTS[1],
        DEFAULTS[2],
        DEFAULTS[3],
        mu,
        DEFAULTS[5],
    ];
    let f = move |th: Interval, w: Interval| {
        let p = P1::texts(t).map(DecInterval::new);
        let (s, c) = dec_angle(th);
        let w = DecInterval::new(w);
        [derived_omega(&p, s, c, w), derived_omega0(&p, s, c, w)]
    };
    let found = find_leaf(f, window([0.5, 1.5], [-10.0, -4.0]), 1.0 / 64.0, |l| {
        l == [Label::ProvedOut, Label::ProvedIn]
    });
    match found {
        Some(b) => Outcome::new(Verdict::Confirmed, Strength::Certified,
            format!("μ = {mu}: box θ ∈ [{:.4}, {:.4}], θ̇ ∈ [{:.4}, {:.4}] lies in Ω̄ ∩ Ω₀ (paradox of non-uniqueness): certified witness that the cell is not empty", b.bx.theta[0], b.bx.theta[1], b.bx.theta_dot[0], b.bx.theta_dot[1]),
            json!({"params": params_json(t), "witness": b.json(), "first": "Ω", "second": "Ω₀"})),
        None => Outcome::new(Verdict::False, Strength::Certified, format!("μ = {mu}: no box of Ω₀ ∖ Ω found"), json!({"params": params_json(t)})),
    }
}

/// S1.contact: a motion without detachment lies in Ω ∩ Ω₀. Under the
/// report's reading `Λ̈ = U + V N` with `V = 1/m + h'²/C > 0` (exact, N
/// free), so contact (Λ̈ = 0) has `N = −U/V` and keeps `N ≥ 0` exactly on the
/// closure of Ω₀; at zero reaction Λ̈ is the free-flight value, so outside
/// the closure of Ω a detachment is possible. The stable equilibrium θ = −π/2
/// lies in Ω ∩ Ω₀ (exact, defaults): such motions exist. Mutant: V without
/// the term h'²/C.
pub fn s1_contact(mutant: bool) -> Outcome {
    let v_closed = |p: &P1<Q>, h1: Q| {
        if mutant {
            Q::int(1) / p.m
        } else {
            Q::int(1) / p.m + h1.sqr() / p.c
        }
    };
    let v = identity_test(118, |r| {
        let (p, s, c, w, pt) = rand_point(r);
        let (_, h1, _) = h_jet(&p, s, c);
        let n = newton(&p, s, c, w, 1).1;
        let (u, _) = u_v(&p, s, c, w);
        // N = −U/V in contact, for the stated V
        Sample {
            point: pt,
            lhs: u + v_closed(&p, h1) * n,
            rhs: Q::int(0),
        }
    });
    // θ = −π/2, θ̇ = 0 at the defaults: N and the free-flight Λ̈
    let p = P1::exact(DEFAULTS);
    let (s, c, w) = (Q::int(-1), Q::int(0), Q::int(0));
    let n = newton(&p, s, c, w, 1).1;
    let free = derived_omega(&p, s, c, w);
    let rest = newton(&p, s, c, w, 1).0;
    let inside = n.signum() > 0 && free.signum() < 0 && rest.is_zero();
    let wit = json!({"U_plus_VN_in_contact": v.json(), "params": params_json(DEFAULTS),
        "equilibrium_theta=-pi/2": {"N": n.get().to_string(), "free_flight_lambda_ddot": free.get().to_string(), "theta_ddot": rest.get().to_string()}});
    if v.agrees() && inside {
        Outcome::new(Verdict::Confirmed, Strength::Argument,
            format!("in contact U + V N = 0 with V = 1/m + h'²/C > 0 ({}, N free): N ≥ 0 exactly on the closure of Ω₀; at zero reaction Λ̈ is the free-flight value, so detachment is possible outside Ω; a contact motion without detachment therefore stays in Ω ∩ Ω₀; the rest state θ = −π/2 has N = {} > 0 and free-flight Λ̈ = {} < 0 (exact, defaults)", v.how(), n.get(), free.get()),
            wit)
    } else {
        Outcome::new(
            Verdict::False,
            Strength::Exact,
            "N is not −U/V with V > 0, or no motion without detachment found",
            wit,
        )
    }
}

/// S1.12: exact identity `−N (C + m h'²)/m = C·Λ̈_free + μ h² b (θ̇ cos θ)`
/// (and the same split for the printed (1.10)/(1.11)); with C > 0, μ, b ≥ 0
/// the inclusions follow. Mutant: friction with the wrong sign.
pub fn s1_12(mutant: bool) -> Outcome {
    let sign = if mutant { -1 } else { 1 };
    let derived = identity_test(112, |r| {
        let (p, s, c, w, pt) = rand_point(r);
        let (hh, h1, _) = h_jet(&p, s, c);
        let lhs = -newton(&p, s, c, w, sign).1 * (p.c + p.m * h1.sqr()) / p.m;
        let rhs = p.c * derived_omega(&p, s, c, w) + p.mu * hh.sqr() * p.b * w * c;
        Sample {
            point: pt,
            lhs,
            rhs,
        }
    });
    let printed = identity_test(113, |r| {
        let (p, s, c, w, pt) = rand_point(r);
        let (hh, _, _) = h_jet(&p, s, c);
        Sample {
            point: pt,
            lhs: printed_bracket(&p, s, c, w, true),
            rhs: printed_bracket(&p, s, c, w, false) + p.mu * hh.sqr() * p.b * w * c,
        }
    });
    let w = json!({"derived_split": derived.json(), "printed_split": printed.json()});
    if derived.agrees() && printed.agrees() {
        Outcome::new(Verdict::Confirmed, Strength::Argument,
            "g_Ω₀ = C·g_Ω + μh²b·θ̇cosθ exactly (derived and printed forms); where θ̇cosθ > 0, g_Ω₀ < 0 ⇒ g_Ω < 0 (Ω₀ ⊂ Ω); where θ̇cosθ < 0, g_Ω < 0 ⇒ g_Ω₀ < 0 (Ω ⊂ Ω₀); for every a, b ≥ 0, C, μ ≥ 0", w)
    } else {
        Outcome::new(
            Verdict::False,
            Strength::Exact,
            "the friction term does not split off with the sign of θ̇ cos θ",
            w,
        )
    }
}

/// S1.12mu: Ω does not depend on μ and `g_Ω₀` is affine in μ with slope
/// `h² b θ̇ cos θ` (exact), so Ω ∖ Ω₀ (where θ̇cosθ > 0) and Ω₀ ∖ Ω (where
/// θ̇cosθ < 0) grow with μ; a certified box in Ω ∖ Ω₀ at μ = 1.6 but in Ω₀ at
/// μ = 0.8 shows the growth is strict. Mutant: the two μ swapped.
pub fn s1_12mu(mutant: bool) -> Outcome {
    let slope = identity_test(114, |r| {
        let (p, s, c, w, pt) = rand_point(r);
        let (hh, h1, _) = h_jet(&p, s, c);
        let mut p2 = p;
        p2.mu = p.mu + Q::int(1);
        let scale = (p.c + p.m * h1.sqr()) / p.m;
        let d = derived_omega0(&p2, s, c, w) * scale - derived_omega0(&p, s, c, w) * scale;
        Sample {
            point: pt,
            lhs: d,
            rhs: hh.sqr() * p.b * w * c,
        }
    });
    let (lo, hi) = if mutant {
        ("1.6", "0.8")
    } else {
        ("0.8", "1.6")
    };
    let f = move |th: Interval, w: Interval| {
        let pa = P1::texts([
            DEFAULTS[0],
            DEFAULTS[1],
            DEFAULTS[2],
            DEFAULTS[3],
            lo,
            DEFAULTS[5],
        ])
        .map(DecInterval::new);
        let pb = P1::texts([
            DEFAULTS[0],
            DEFAULTS[1],
            DEFAULTS[2],
            DEFAULTS[3],
            hi,
            DEFAULTS[5],
        ])
        .map(DecInterval::new);
        let (s, c) = dec_angle(th);
        let w = DecInterval::new(w);
        [derived_omega0(&pa, s, c, w), derived_omega0(&pb, s, c, w)]
    };
    let found = find_leaf(f, window([-0.25, 0.25], [3.0, 8.0]), 1.0 / 64.0, |l| {
        l == [Label::ProvedIn, Label::ProvedOut]
    });
    let w =
        json!({"slope_in_mu": slope.json(), "mu_pair": [lo, hi], "box": found.map(|b| b.json())});
    match (slope.agrees(), found) {
        (true, Some(b)) => Outcome::new(Verdict::Confirmed, Strength::Argument,
            format!("Ω is μ-free, g_Ω₀ has slope h²bθ̇cosθ in μ (exact), so Ω Δ Ω₀ is nested increasing in μ; box θ ∈ [{:.3}, {:.3}], θ̇ ∈ [{:.3}, {:.3}] is in Ω₀ at μ = {lo} and out at μ = {hi} (certified)", b.bx.theta[0], b.bx.theta[1], b.bx.theta_dot[0], b.bx.theta_dot[1]), w),
        _ => Outcome::new(Verdict::False, Strength::Certified, "no certified growth found", w),
    }
}

/// Jacobian `(∂θ̈/∂θ, ∂θ̈/∂θ̇)` at `θ̇ = 0` of the Newton equations, exactly.
fn jacobian(p: &P1<Q>, s: Q, c: Q) -> (Q, Q) {
    let an = angle_d(s, c);
    let pd = p.map(Dual::constant);
    let w = Dual::variable(Q::int(0), 1);
    let thdd = newton(&pd, an.sin, an.cos, w, 1).0;
    (thdd.grad[0], thdd.grad[1])
}

/// S1.eq: equilibria, their type, exactly from the Newton equations at
/// decimal parameters (θ = ±π/2 have rational sin, cos). Mutant: μ = 20.
pub fn s1_eq(mutant: bool) -> Outcome {
    // θ̈(θ, 0)·(C + m h'²) = −m g h' (exact identity): equilibria iff cos θ = 0.
    let eq = identity_test(115, |r| {
        let (p, s, c, _, pt) = rand_point(r);
        let (_, h1, _) = h_jet(&p, s, c);
        Sample {
            point: pt,
            lhs: newton(&p, s, c, Q::int(0), 1).0 * (p.c + p.m * h1.sqr()),
            rhs: -(p.m * p.g * p.b * c),
        }
    });
    let classify = |t: [&str; 6]| {
        let p = P1::exact(t);
        let (a_up, d_up) = jacobian(&p, Q::int(1), Q::int(0));
        let (a_dn, d_dn) = jacobian(&p, Q::int(-1), Q::int(0));
        let disc = d_dn.sqr() + Q::int(4) * a_dn;
        let saddle = a_up.signum() > 0;
        let stable = a_dn.signum() < 0 && d_dn.signum() < 0;
        let focus = disc.signum() < 0;
        // Trace 0, determinant > 0: the linearisation is a centre.
        let centre = a_dn.signum() < 0 && d_dn.signum() == 0;
        (
            saddle,
            stable,
            focus,
            json!({
            "params": params_json(t),
            "at_pi_over_2": {"d_thdd_d_theta": a_up.get().to_string(), "d_thdd_d_theta_dot": d_up.get().to_string(), "type": if saddle {"saddle"} else {"not a saddle"}},
            "at_minus_pi_over_2": {"d_thdd_d_theta": a_dn.get().to_string(), "d_thdd_d_theta_dot": d_dn.get().to_string(), "discriminant_trace2_minus_4det": disc.get().to_string(),
                "type": if centre {"centre of the linearisation"} else if !stable {"not stable"} else if focus {"stable focus"} else {"stable node"}}}),
        )
    };
    // Jacobian entries in closed form for all parameters (exact identity):
    // at θ = π/2: ∂θ̈/∂θ = m g b/C (> 0: saddle for b > 0); at θ = −π/2:
    // ∂θ̈/∂θ = −m g b/C, ∂θ̈/∂θ̇ = −μ(a − b)²/C, so trace² − 4 det =
    // (μ²(a − b)⁴ − 4 m g b C)/C².
    let closed = identity_test(117, |r| {
        let p = P1::random(r);
        let k = [r.signed(), r.signed(), r.signed()];
        let (a_up, _) = jacobian(&p, Q::int(1), Q::int(0));
        let (a_dn, d_dn) = jacobian(&p, Q::int(-1), Q::int(0));
        let ab = p.a - p.b;
        let lhs = a_up + k[0] * a_dn + k[1] * d_dn + k[2] * (d_dn.sqr() + Q::int(4) * a_dn);
        let rhs = p.m * p.g * p.b / p.c
            - k[0] * p.m * p.g * p.b / p.c
            - k[1] * p.mu * ab.sqr() / p.c
            + k[2] * (p.mu.sqr() * ab.sqr().sqr() - Q::int(4) * p.m * p.g * p.b * p.c) / p.c.sqr();
        Sample {
            point: vec![],
            lhs,
            rhs,
        }
    });
    let mu_big = if mutant { "20" } else { "0.8" };
    let d0 = [
        DEFAULTS[0],
        DEFAULTS[1],
        DEFAULTS[2],
        DEFAULTS[3],
        mu_big,
        DEFAULTS[5],
    ];
    let d1 = [
        DEFAULTS[0],
        DEFAULTS[1],
        DEFAULTS[2],
        DEFAULTS[3],
        "20",
        DEFAULTS[5],
    ];
    // a = b: the rim passes through the centre of mass, h(−π/2) = 0, and the
    // friction μh²θ̇ vanishes to second order there.
    let d2 = [
        "0.5",
        DEFAULTS[1],
        DEFAULTS[2],
        DEFAULTS[3],
        DEFAULTS[4],
        DEFAULTS[5],
    ];
    let (s0, st0, f0, w0) = classify(d0);
    let (s1, st1, f1, w1) = classify(d1);
    let (s2, st2, _, w2) = classify(d2);
    let w = json!({"equilibria_identity": eq.json(), "jacobian_closed_forms": closed.json(), "side_true": w0, "side_false": w1, "side_a_equals_b": w2});
    if !(eq.agrees() && closed.agrees() && s0 && st0) {
        return Outcome::new(
            Verdict::False,
            Strength::Exact,
            "θ = π/2 is not a saddle or θ = −π/2 is not stable at these parameters",
            w,
        );
    }
    if f0 && !f1 && s1 && st1 && s2 && !st2 {
        Outcome::new(Verdict::Conditional, Strength::Exact,
            "equilibria exactly at cos θ = 0; Jacobians in closed form for all parameters (proved identity): θ = π/2 a saddle for every b > 0; at θ = −π/2 trace −μ(a − b)²/C, determinant m g b/C: a stable focus iff 0 < μ²(a − b)⁴ < 4mgbC, a stable node iff μ²(a − b)⁴ ≥ 4mgbC, a centre of the linearisation iff μ(a − b) = 0; at the defaults a focus (μ = 0.8), a stable node at μ = 20, a centre of the linearisation at a = b = 0.5 (exact)", w)
            .correct("θ = π/2 is a saddle; at θ = −π/2 the linearisation is a stable focus iff 0 < μ²(a − b)⁴ < 4 m g b C, a stable node iff μ²(a − b)⁴ ≥ 4 m g b C, and a centre iff μ(a − b) = 0 (μ = 0, or a = b, where the friction μh²θ̇ vanishes at the lowest point)")
    } else {
        Outcome::new(
            Verdict::Confirmed,
            Strength::Exact,
            format!(
                "saddle at π/2, stable {} at −π/2",
                if f0 { "focus" } else { "node" }
            ),
            w,
        )
    }
}

/// The picture of S1.eq.
fn s1_eq_figure(_mark: Option<PhaseBox>) -> FigureSpec {
    let (a, b, m, c, g): (f64, f64, f64, f64, f64) = (1.0, 0.5, 1.0, 0.3, 9.81);
    let disc = |mu: f64| (mu * mu * (a - b).powi(4) - 4.0 * m * g * b * c) / (c * c);
    let switch = 2.0 * (m * g * b * c).sqrt() / (a - b).powi(2);
    FigureSpec::Lines(Curves {
        title: "S1.eq: the equilibrium θ = −π/2, trace² − 4 det against μ".into(),
        subtitle: format!(
            "< 0: a stable focus, > 0: a stable node; {}",
            params_text(
                &["a", "b", "m", "C", "g"],
                &["1", "0.5", "1", "0.3", "9.81"]
            )
        ),
        x: axis("μ (kg/s)", [0.0, 21.0], false),
        y: axis("trace² − 4 det (1/s²)", [-80.0, 260.0], false),
        series: vec![series(
            "(μ²(a − b)⁴ − 4mgbC)/C²",
            grid(0.0, 21.0, 210).map(|u| (u, disc(u))).collect(),
        )],
        marks: vec![
            marks(
                "μ = 0.8 (default): a focus",
                vec![(0.8, disc(0.8))],
                Shape::Dot,
            ),
            marks("μ = 20: a node", vec![(20.0, disc(20.0))], Shape::Square),
            marks(
                "μ = 2√(mgbC)/(a − b)²: focus turns node",
                vec![(switch, 0.0)],
                Shape::Ring,
            ),
        ],
        zero: true,
    })
}

/// S1.traj: exact identity `J θ̈ + μ h² θ̇ = m b cos θ · g_Ω` (J = C + m h'²,
/// g_Ω = b θ̇² sin θ − g). On ∂Ω (g_Ω = 0) inside Ω₀ (θ̇ cos θ < 0 by S1.12)
/// the derivative of g_Ω along the flow is `θ̇²(b θ̇ cos θ − 2μ b h² sin θ/J) < 0`,
/// so the flow crosses ∂Ω ∩ Ω₀ only into Ω: a contact trajectory cannot enter
/// Ω̄ ∩ Ω₀. It can enter Ω ∩ Ω̄₀: a certified box in Ω straddling ∂Ω₀ where
/// `d(−N)/dt > 0`. Mutant: friction with the wrong sign.
pub fn s1_traj(mutant: bool) -> Outcome {
    let sign = if mutant { -1 } else { 1 };
    let id = identity_test(116, |r| {
        let (p, s, c, w, pt) = rand_point(r);
        let (hh, h1, _) = h_jet(&p, s, c);
        let j = p.c + p.m * h1.sqr();
        let lhs = j * newton(&p, s, c, w, sign).0 + p.mu * hh.sqr() * w;
        let rhs = p.m * p.b * c * (p.b * w.sqr() * s - p.g);
        Sample {
            point: pt,
            lhs,
            rhs,
        }
    });
    // Entering Ω ∩ Ω̄₀: box around (0, 7.36) at the default parameters.
    let p = P1::texts(DEFAULTS);
    let bx = ([-0.01, 0.01], [7.2, 7.5]);
    let th = iv(bx.0[0], bx.0[1]);
    let wv = iv(bx.1[0], bx.1[1]);
    let an = Angle::new(Dual::variable(th, 0));
    let pd = p.map(Dual::constant);
    let wd = Dual::variable(wv, 1);
    let (thdd, n) = newton(&pd, an.sin, an.cos, wd, sign);
    let lie = -(n.grad[0] * wv + n.grad[1] * thdd.value);
    let g_omega = derived_omega(&p, th.sin(), th.cos(), wv);
    let n_at = |w: f64| newton(&p, iv(0.0, 0.0).sin(), iv(0.0, 0.0).cos(), iv(w, w), 1).1;
    let (n_lo, n_hi) = (n_at(bx.1[0]), n_at(bx.1[1]));
    let enters = lie.inf() > 0.0 && g_omega.sup() < 0.0 && n_lo.inf() > 0.0 && n_hi.sup() < 0.0;
    let w = json!({"identity": id.json(), "params": params_json(DEFAULTS),
        "enter_box": {"theta": bx.0, "theta_dot": bx.1, "free_flight_lambda_ddot": enc(g_omega), "d(-N)/dt": enc(lie),
                      "N_at_(0,7.2)": enc(n_lo), "N_at_(0,7.5)": enc(n_hi)}});
    if id.agrees() && enters {
        Outcome::new(Verdict::Confirmed, Strength::Argument,
            "on ∂Ω ∩ Ω₀ the flow points into Ω (exact identity + sign argument, all parameters with μ > 0); at θ ≈ 0, θ̇ ≈ 7.36 the flow leaves Ω₀ inside Ω (certified box, d(−N)/dt > 0)", w)
    } else {
        Outcome::new(
            Verdict::False,
            Strength::Exact,
            "the flow identity on ∂Ω fails or no exit from Ω₀ inside Ω was certified",
            w,
        )
    }
}

/// This section's check functions, by claim id (`claims.toml` holds the rest).
/// The claims of this section with a picture, each drawn by the function
/// beside its check.
pub(super) const FIGURES: &[(&str, FigureOf)] = &[
    ("F1.7", f1_7_figure),
    ("F1.9", f1_9_figure),
    ("F1.10", f1_10_figure),
    ("F1.11", f1_11_figure),
    ("S1.eq", s1_eq_figure),
];

pub(super) const CHECKS: &[(&str, Check)] = &[
    ("F1.3", f1_3),
    ("F1.4", f1_4),
    ("F1.5", f1_5),
    ("F1.6", f1_6),
    ("F1.7", f1_7),
    ("F1.8", f1_8),
    ("F1.9", f1_9),
    ("F1.10", f1_10),
    ("F1.11", f1_11),
    ("S1.ideal", s1_ideal),
    ("S1.friction", s1_friction),
    ("S1.nonunique", s1_nonunique),
    ("S1.contact", s1_contact),
    ("S1.12", s1_12),
    ("S1.12mu", s1_12mu),
    ("S1.eq", s1_eq),
    ("S1.traj", s1_traj),
];
