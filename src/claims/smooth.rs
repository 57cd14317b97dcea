//! §2: thin disc on a smooth plane — (2.1)–(2.12) and the statements on Ω
//! and the stationary motions.
//!
//! The mechanics, written here independently of the `scene` module: body
//! angular velocity from the Euler angles (z-x-z), `T` from it, `ψ̇, φ̇` from
//! the integrals (2.3), `∂T/∂θ` at fixed `ψ̇, φ̇` by dual numbers, and the
//! contact motion from the Lagrange equations `m z̈ = N − m g`,
//! `A θ̈ = ∂T/∂θ − a cos θ N` with `Λ̈ = 0`, solved exactly for `(z̈, θ̈, N)`.

use super::exact::{
    agreement, angle_d, dd_const, identity_test, jet2, qdec, sin_cos_of_tan_half, solve,
    strength_of, verdict_of, RationalPath, Rng, Sample, Q,
};
use super::figures::{
    axis, grid, marks, momenta, params_text, series, Curves, FigureOf, FigureSpec, Series, Shape,
    THETA_RAD,
};
use super::files::formula;
use super::{enc, shown_at, Check, Outcome, Strength, Verdict};
use crate::number::scalar::{Dual, Scalar};
use crate::pave::PhaseBox;
use crate::roots::critical::{band_cell, g as g_crit};
use crate::roots::equations::kappa_alpha;
use crate::roots::isolate::{point, RealFn};
use crate::roots::{prove_kappa0, solve_2_10, solve_2_9, Budget, EquationRoots};
use crate::scene::{ExactTheta, Scene, SceneId, Variant};
use inari::Interval;
use serde_json::json;

/// Parameters of §2 (and §3) in any scalar type.
#[derive(Clone, Copy, Debug)]
pub struct P2<T> {
    pub m: T,
    pub a: T,
    pub big_a: T,
    pub big_c: T,
    pub g: T,
    pub pf: T,
    pub ps: T,
}

impl<T: Copy> P2<T> {
    /// The values under the names of the scene files.
    pub fn values(&self) -> [(&'static str, T); 7] {
        let v = [
            self.m, self.a, self.big_a, self.big_c, self.g, self.pf, self.ps,
        ];
        [0, 1, 2, 3, 4, 5, 6].map(|i| (NAMES[i], v[i]))
    }

    pub fn map<U>(&self, f: impl Fn(T) -> U) -> P2<U> {
        P2 {
            m: f(self.m),
            a: f(self.a),
            big_a: f(self.big_a),
            big_c: f(self.big_c),
            g: f(self.g),
            pf: f(self.pf),
            ps: f(self.ps),
        }
    }
}

impl P2<Q> {
    pub fn random(r: &mut Rng) -> P2<Q> {
        let mut q = |i: usize| {
            let x = if i < 5 { r.positive() } else { r.signed() };
            r.named(NAMES[i], x)
        };
        P2 {
            m: q(0),
            a: q(1),
            big_a: q(2),
            big_c: q(3),
            g: q(4),
            pf: q(5),
            ps: q(6),
        }
    }
    pub fn exact(t: [&str; 7]) -> P2<Q> {
        P2 {
            m: qdec(t[0]),
            a: qdec(t[1]),
            big_a: qdec(t[2]),
            big_c: qdec(t[3]),
            g: qdec(t[4]),
            pf: qdec(t[5]),
            ps: qdec(t[6]),
        }
    }
}

/// (m, a, A, C, g, p_φ, p_ψ) of the scene's defaults.
pub const DEFAULTS: [&str; 7] = ["1", "1", "0.25", "0.5", "9.81", "2.5", "2"];
const NAMES: [&str; 7] = ["m", "a", "A", "C", "g", "p_phi", "p_psi"];

pub fn params_json(t: &[&str]) -> serde_json::Value {
    NAMES
        .iter()
        .zip(t)
        .map(|(k, v)| (k.to_string(), json!(v)))
        .collect::<serde_json::Map<_, _>>()
        .into()
}

/// The smooth disc's parameters at the defaults with p_φ, p_ψ from text
/// (for κ and α of (2.9)).
pub fn disc(pf: &str, ps: &str) -> crate::number::param::ParamSet {
    let o = vec![
        ("p_phi".to_string(), pf.to_string()),
        ("p_psi".to_string(), ps.to_string()),
    ];
    Scene::build(SceneId::SmoothDisc, &o)
        .expect("valid parameters")
        .1
}

/// Rotational kinetic energy from the body angular velocity (Euler angles
/// z-x-z, body axis 3 = symmetry axis): `ω₁ = ψ̇ sθ sφ + θ̇ cφ`,
/// `ω₂ = ψ̇ sθ cφ − θ̇ sφ`, `ω₃ = ψ̇ cθ + φ̇`.
#[allow(clippy::too_many_arguments)]
pub fn t_rot<T: Scalar>(p: &P2<T>, s: T, c: T, sphi: T, cphi: T, w: T, psid: T, phid: T) -> T {
    let w1 = psid * s * sphi + w * cphi;
    let w2 = psid * s * cphi - w * sphi;
    let w3 = psid * c + phid;
    let half = T::int(1) / T::int(2);
    half * p.big_a * (w1.sqr() + w2.sqr()) + half * p.big_c * w3.sqr()
}

/// The rotational part of (2.1) as printed.
pub fn t_rot_printed<T: Scalar>(p: &P2<T>, s: T, c: T, w: T, psid: T, phid: T) -> T {
    let half = T::int(1) / T::int(2);
    half * p.big_a * (w.sqr() + psid.sqr() * s.sqr()) + half * p.big_c * (psid * c + phid).sqr()
}

/// ψ̇, φ̇ from the integrals (2.3) `∂T/∂ψ̇ = p_ψ`, `∂T/∂φ̇ = p_φ` (solved by hand;
/// checked in F2.5 by differentiating T).
pub fn spin_rates<T: Scalar>(p: &P2<T>, s: T, c: T) -> (T, T) {
    let psid = (p.ps - p.pf * c) / (p.big_a * s.sqr());
    (psid, p.pf / p.big_c - psid * c)
}

/// The printed §2 file's text at `key` (`smooth-disc-printed.toml`),
/// `values` past the parameters taken as given.
fn printed<T: Scalar>(key: &str, p: &P2<T>, s: T, c: T, given: &[(&'static str, T)]) -> T {
    printed_at(key, p, s, c, T::int(0), given)
}

/// [`printed`] at θ̇ = `w`.
fn printed_at<T: Scalar>(key: &str, p: &P2<T>, s: T, c: T, w: T, given: &[(&'static str, T)]) -> T {
    let theta = ExactTheta::trig(s, c);
    p2_formula(SceneId::SmoothDisc, key, p, theta, w, given)
}

/// The text at `key` of the printed file of §2 or §3 (`id`), with the
/// parameters `p` and `given` values past them.
pub fn p2_formula<T: Scalar>(
    id: SceneId,
    key: &str,
    p: &P2<T>,
    theta: ExactTheta<T>,
    w: T,
    given: &[(&str, T)],
) -> T {
    let values: Vec<_> = p
        .values()
        .into_iter()
        .chain(given.iter().copied())
        .collect();
    formula(id, Variant::Printed, key, &values, theta, w)
}

/// τ, τ' of (2.7) as printed.
pub fn tau_printed<T: Scalar>(p: &P2<T>, s: T, c: T) -> (T, T) {
    (
        printed("definitions.tau", p, s, c, &[]),
        printed("definitions.tau1", p, s, c, &[]),
    )
}

/// `∂T/∂θ` at fixed ψ̇, φ̇ (the values of the integrals at θ), by a dual in θ.
pub fn dt_dtheta<T: Scalar>(p: &P2<T>, s: T, c: T, w: T) -> T {
    let (psid, phid) = spin_rates(p, s, c);
    let an = angle_d(s, c);
    let k = Dual::constant;
    let pd = p.map(k);
    t_rot_printed(&pd, an.sin, an.cos, k(w), k(psid), k(phid)).grad[0]
}

/// `(θ̈, N)` in contact from the Lagrange equations.
pub fn lagrange<T: Scalar>(p: &P2<T>, s: T, c: T, w: T) -> (T, T) {
    let (zero, one) = (T::int(0), T::int(1));
    let m = vec![
        vec![p.m, zero, -one],
        vec![zero, p.big_a, p.a * c],
        vec![one, -(p.a * c), zero],
    ];
    let r = [-(p.m * p.g), dt_dtheta(p, s, c, w), -(p.a * s * w.sqr())];
    let x = solve(&m, &r);
    (x[1], x[2])
}

/// Λ̈ in free flight (N = 0): Ω = {this < 0}.
pub fn free_lambda_ddot<T: Scalar>(p: &P2<T>, s: T, c: T, w: T) -> T {
    let thdd = dt_dtheta(p, s, c, w) / p.big_a;
    -p.g - p.a * c * thdd + p.a * s * w.sqr()
}

/// U of (2.7) as printed.
pub fn u_printed<T: Scalar>(p: &P2<T>, s: T, c: T, w: T) -> T {
    let (t, t1) = tau_printed(p, s, c);
    -p.g + p.a * w.sqr() * s + p.a * t * t1 * c
}

/// Φ of (2.8) as printed.
pub fn phi_printed<T: Scalar>(p: &P2<T>, s: T, c: T) -> T {
    printed("definitions.Phi", p, s, c, &[])
}

/// Π̃ of (2.5) as printed.
pub fn pi_tilde<T: Scalar>(p: &P2<T>, s: T, c: T) -> T {
    p.m * p.g * p.a * s + (p.ps - p.pf * c).sqr() / (T::int(2) * p.big_a * s.sqr())
}

/// Π̃' of (2.12) as printed (`sign` −1: a mutant, `A ττ'` with τ' negated).
pub fn pi_slope_printed<T: Scalar>(p: &P2<T>, s: T, c: T, sign: i32) -> T {
    let key = "functions.potential_slope";
    if sign < 0 {
        let t1 = tau_printed(p, s, c).1;
        printed(key, p, s, c, &[("tau1", -t1)])
    } else {
        printed(key, p, s, c, &[])
    }
}

/// Λ̈ of (2.6) for a given normal reaction N (a free force), θ̈ from the θ
/// equation with N: `A θ̈ = ∂T/∂θ − a cos θ N`, z̈ = N/m − g.
pub fn lambda_ddot_given_n<T: Scalar>(p: &P2<T>, s: T, c: T, w: T, n: T) -> T {
    let thdd = (dt_dtheta(p, s, c, w) - p.a * c * n) / p.big_a;
    n / p.m - p.g + p.a * w.sqr() * s - p.a * thdd * c
}

/// `(U, V)` of `Λ̈ = U + V N` under the report's reading (N free).
pub fn u_v<T: Scalar>(p: &P2<T>, s: T, c: T, w: T) -> (T, T) {
    let u = lambda_ddot_given_n(p, s, c, w, T::int(0));
    (u, lambda_ddot_given_n(p, s, c, w, T::int(1)) - u)
}

/// V = 1/m + a² cos²θ/A as (2.7)'s argument states it.
pub fn v_closed<T: Scalar>(p: &P2<T>, c: T) -> T {
    T::int(1) / p.m + p.a.sqr() * c.sqr() / p.big_a
}

/// θ̈ of the reduced equation (2.5): `J θ̈ + ½ J' θ̇² = −Π̃'`, J = A + m a² cos²θ.
pub fn reduced_thdd<T: Scalar>(p: &P2<T>, s: T, c: T, w: T) -> T {
    let an = angle_d(s, c);
    let pd = p.map(Dual::constant);
    let jj = pd.big_a + pd.m * pd.a.sqr() * an.cos.sqr();
    let pi = pi_tilde(&pd, an.sin, an.cos);
    (-pi.grad[0] - jj.grad[0] * w.sqr() / T::int(2)) / jj.value
}

/// d/dθ of the spin energy `½Aψ̇² sin²θ + ½C(ψ̇ cos θ + φ̇)²` with ψ̇, φ̇ from
/// the integrals (2.3) at fixed p_φ, p_ψ.
pub fn spin_energy_slope<T: Scalar>(p: &P2<T>, s: T, c: T) -> T {
    let an = angle_d(s, c);
    let pd = p.map(Dual::constant);
    let (psid, phid) = spin_rates(&pd, an.sin, an.cos);
    t_rot_printed(&pd, an.sin, an.cos, Dual::int(0), psid, phid).grad[0]
}

/// Components along the vertical e_z and along the disc axis k of the
/// moment about G of the force `N e_z + R n` applied at the lowest rim
/// point. Disc axis `k = (s sin ψ, −s cos ψ, c)` (as in F2.1), line of nodes
/// `e₁ = (cos ψ, sin ψ, 0)`, `n = e_z × e₁`; the lowest point is
/// `r = −a (k × e₁)` (`k × e₁` has vertical component sin θ > 0).
pub fn reaction_moment<T: Scalar>(a: T, s: T, c: T, spsi: T, cpsi: T, n: T, r: T) -> (T, T) {
    let k = [s * spsi, -(s * cpsi), c];
    let e1 = [cpsi, spsi, T::int(0)];
    let kxe = [
        k[1] * e1[2] - k[2] * e1[1],
        k[2] * e1[0] - k[0] * e1[2],
        k[0] * e1[1] - k[1] * e1[0],
    ];
    let rr = [-(a * kxe[0]), -(a * kxe[1]), -(a * kxe[2])];
    let f = [-(r * spsi), r * cpsi, n];
    let m = [
        rr[1] * f[2] - rr[2] * f[1],
        rr[2] * f[0] - rr[0] * f[2],
        rr[0] * f[1] - rr[1] * f[0],
    ];
    (m[2], m[0] * k[0] + m[1] * k[1] + m[2] * k[2])
}

/// The point where differences are shown: default parameters, tan(θ/2) =
/// 1/2 (sin θ = 4/5, cos θ = 3/5), θ̇ = 1.
fn shown_point() -> (P2<Q>, Q, Q, Q) {
    (
        P2::exact(DEFAULTS),
        Q::ratio(4, 5),
        Q::ratio(3, 5),
        Q::int(1),
    )
}

fn shown_json() -> serde_json::Value {
    json!({"params": params_json(&DEFAULTS), "sin_theta": "4/5", "cos_theta": "3/5", "theta_dot": "1"})
}

fn rp(r: &mut Rng) -> (P2<Q>, Q, Q, Q, Vec<(String, Q)>) {
    let p = P2::random(r);
    let t = r.tan_half();
    let (s, c) = sin_cos_of_tan_half(t);
    let w = r.signed();
    (
        p,
        s,
        c,
        w,
        vec![("tan(theta/2)".into(), t), ("theta_dot".into(), w)],
    )
}

// ---------------------------------------------------------------- formulas

/// F2.1: the rotational part of T from the body angular velocity, and
/// `Λ = z − a sin θ` from the depth of the lowest rim point (`a√(1 − k_z²)`).
/// Mutant: `A ψ̇² cos²θ` in place of `A ψ̇² sin²θ`.
pub fn f2_1(mutant: bool) -> Outcome {
    let t = identity_test(21, |r| {
        let (p, s, c, w, pt) = rp(r);
        let (sp, cp) = sin_cos_of_tan_half(r.tan_half());
        let (psid, phid) = (r.signed(), r.signed());
        let printed = if mutant {
            t_rot_printed(&p, c, c, w, psid, phid)
        } else {
            t_rot_printed(&p, s, c, w, psid, phid)
        };
        Sample {
            point: pt,
            lhs: printed,
            rhs: t_rot(&p, s, c, sp, cp, w, psid, phid),
        }
    });
    let lam = identity_test(211, |r| {
        let (p, s, c, _, pt) = rp(r);
        let (spsi, cpsi) = sin_cos_of_tan_half(r.tan_half());
        // disc axis k = (s sin ψ, −s cos ψ, c): the lowest rim point lies a·|k_h|
        // below G, |k_h|² = |k|² − k_z² (|k| = 1)
        let (kx, ky, kz) = (s * spsi, -(s * cpsi), c);
        let k2 = kx.sqr() + ky.sqr() + kz.sqr();
        let depth2 = p.a.sqr() * (k2 - kz.sqr());
        Sample {
            point: pt,
            lhs: (p.a * s).sqr(),
            rhs: depth2,
        }
    });
    verdict_of(&[("kinetic_energy", &t), ("constraint_depth_squared", &lam)],
        "T of (2.1) against ½A(ω₁²+ω₂²) + ½Cω₃² from Euler angles; (a sin θ)² = depth² of the lowest point (sin θ > 0 on (0, π))",
        "T = ½m(ẋ²+ẏ²+ż²) + ½A(θ̇² + ψ̇² sin²θ) + ½C(ψ̇ cos θ + φ̇)²")
}

/// F2.5: T̃ and Π̃ of the Routh reduction, and (2.5) against the Lagrange
/// equations. Mutant: `Π̃` with `A sin θ` in the denominator.
pub fn f2_5(mutant: bool) -> Outcome {
    let integrals = identity_test(25, |r| {
        let (p, s, c, _, pt) = rp(r);
        let lambda = r.signed();
        let (psid, phid) = spin_rates(&p, s, c);
        // ∂T/∂ψ̇ and ∂T/∂φ̇ by duals must return p_ψ, p_φ
        let k = Dual::constant;
        let pd = p.map(k);
        let tp = t_rot_printed(
            &pd,
            k(s),
            k(c),
            k(Q::int(0)),
            Dual::variable(psid, 0),
            k(phid),
        );
        let tf = t_rot_printed(
            &pd,
            k(s),
            k(c),
            k(Q::int(0)),
            k(psid),
            Dual::variable(phid, 0),
        );
        // a random combination of the two equations
        Sample {
            point: pt,
            lhs: tp.grad[0] + lambda * tf.grad[0],
            rhs: p.ps + lambda * p.pf,
        }
    });
    let amended = identity_test(251, |r| {
        let (p, s, c, _, pt) = rp(r);
        let (psid, phid) = spin_rates(&p, s, c);
        let rot = t_rot_printed(&p, s, c, Q::int(0), psid, phid);
        let centrifugal = if mutant {
            (p.ps - p.pf * c).sqr() / (Q::int(2) * p.big_a * s)
        } else {
            pi_tilde(&p, s, c) - p.m * p.g * p.a * s
        };
        Sample {
            point: pt,
            lhs: centrifugal + p.pf.sqr() / (Q::int(2) * p.big_c),
            rhs: rot,
        }
    });
    let motion = identity_test(252, |r| {
        let (p, s, c, w, pt) = rp(r);
        // (2.5): J θ̈ + ½ J' θ̇² = −Π̃', J = A + m a² cos²θ (T̃ = ½ J θ̇², z = a sin θ)
        let an = angle_d(s, c);
        let pd = p.map(Dual::constant);
        let jj = pd.big_a + pd.m * pd.a.sqr() * an.cos.sqr();
        let pi = if mutant {
            pd.m * pd.g * pd.a * an.sin
                + (pd.ps - pd.pf * an.cos).sqr() / (Dual::int(2) * pd.big_a * an.sin)
        } else {
            pi_tilde(&pd, an.sin, an.cos)
        };
        let thdd = (-pi.grad[0] - jj.grad[0] * w.sqr() / Q::int(2)) / jj.value;
        Sample {
            point: pt,
            lhs: thdd,
            rhs: lagrange(&p, s, c, w).0,
        }
    });
    verdict_of(&[("integrals_2_3", &integrals), ("amended_potential", &amended), ("reduced_equation_vs_lagrange", &motion)],
        "ψ̇, φ̇ from (2.3); Π̃ − mga sin θ + p_φ²/2C = rotational T at those rates; (2.5) with T̃ = ½(A + ma²cos²θ)θ̇² against the Lagrange equations",
        "Π̃ = m g a sin θ + (p_ψ − p_φ cos θ)²/(2A sin²θ)")
}

/// F2.6: `Λ̈ = N/m − g + a θ̇² sin θ − a θ̈ cos θ` along rational paths; under
/// the report's reading θ̈ carries N (`A θ̈ = ∂T/∂θ − a cos θ N`), so the
/// coefficient of N is V = 1/m + a² cos²θ/A (that of F2.7), not the 1/m in
/// front, and the rest at N = 0 is U of (2.7) — the paper's second route
/// (the θ equation of (2.2) with the integrals (2.3)). Mutant: `+ a θ̈ cos θ`.
pub fn f2_6(mutant: bool) -> Outcome {
    let sgn = if mutant { Q::int(-1) } else { Q::int(1) };
    let id = identity_test(26, |r| {
        let p = P2::random(r);
        let RationalPath {
            u0,
            y2: z2,
            u,
            y: z,
            w,
            thdd,
            s,
            c,
        } = RationalPath::random(r);
        let (su, _) = sin_cos_of_tan_half(u);
        let lam_dd = jet2(z - dd_const(p.a) * su).2;
        let n = p.m * (Q::int(2) * z2 + p.g); // m z̈ = N − m g
        let printed = n / p.m - p.g + p.a * w.sqr() * s - sgn * p.a * thdd * c;
        Sample {
            point: vec![("u0".into(), u0)],
            lhs: printed,
            rhs: lam_dd,
        }
    });
    // (2.6) with θ̈ from the θ equation with N given
    let printed_n = |p: &P2<Q>, s: Q, c: Q, w: Q, n: Q| {
        let thdd = (dt_dtheta(p, s, c, w) - p.a * c * n) / p.big_a;
        n / p.m - p.g + p.a * w.sqr() * s - sgn * p.a * thdd * c
    };
    let v = identity_test(261, |r| {
        let (p, s, c, w, pt) = rp(r);
        Sample {
            point: pt,
            lhs: printed_n(&p, s, c, w, Q::int(1)) - printed_n(&p, s, c, w, Q::int(0)),
            rhs: v_closed(&p, c),
        }
    });
    let u = identity_test(262, |r| {
        let (p, s, c, w, pt) = rp(r);
        Sample {
            point: pt,
            lhs: printed_n(&p, s, c, w, Q::int(0)),
            rhs: u_printed(&p, s, c, w),
        }
    });
    let (qp, qs, qc, qw) = shown_point();
    let (u0, v0) = u_v(&qp, qs, qc, qw);
    let mut o = verdict_of(&[("second_derivative", &id), ("N_coefficient_is_V_of_2_7", &v), ("U_from_theta_equation_of_2_2", &u)],
        "(2.6) against d²(z − a sin θ)/dt² along rational paths with m z̈ = N − m g; with θ̈ from the θ equation with N (A θ̈ = ∂T/∂θ − a cos θ N) the coefficient of N is V = 1/m + a²cos²θ/A (not the 1/m in front) and the rest at N = 0 is U of (2.7) (second route)",
        "Λ̈ = N/m − g + a θ̇² sin θ − a θ̈ cos θ, with θ̈ depending on N: V = 1/m + a²cos²θ/A");
    o.witness["reading"] =
        json!({"at": shown_json(), "V": v0.get().to_string(), "U": u0.get().to_string()});
    o
}

/// F2.6route: "to get U, substitute θ̈ from (2.5)". (2.5) is the contact
/// equation (N already eliminated), so this gives `−g + a θ̇² sin θ − a θ̈ cos θ
/// = A/(A + m a² cos²θ)·U = U/(mV)`, the other reading, not U: a typo, as the
/// positive factor changes none of Ω, Ω₀, N. Mutant: θ̈ from the θ equation
/// of (2.2) at N = 0 instead.
pub fn f2_6route(mutant: bool) -> Outcome {
    let via = |p: &P2<Q>, s: Q, c: Q, w: Q| {
        let thdd = if mutant {
            dt_dtheta(p, s, c, w) / p.big_a
        } else {
            reduced_thdd(p, s, c, w)
        };
        -p.g + p.a * w.sqr() * s - p.a * thdd * c
    };
    let id = identity_test(263, |r| {
        let (p, s, c, w, pt) = rp(r);
        Sample {
            point: pt,
            lhs: via(&p, s, c, w),
            rhs: u_printed(&p, s, c, w),
        }
    });
    let scaled = identity_test(264, |r| {
        let (p, s, c, w, pt) = rp(r);
        let j = p.big_a + p.m * p.a.sqr() * c.sqr();
        Sample {
            point: pt,
            lhs: via(&p, s, c, w),
            rhs: p.big_a / j * u_printed(&p, s, c, w),
        }
    });
    let (qp, qs, qc, qw) = shown_point();
    let (gave, u0) = (via(&qp, qs, qc, qw), u_printed(&qp, qs, qc, qw));
    let w = json!({"route_2_5_vs_U": shown_at(&id, shown_json(), gave, u0), "route_2_5_vs_A_over_J_times_U": scaled.json()});
    if id.agrees() {
        return Outcome::new(
            Verdict::Confirmed,
            strength_of(&[&id]),
            format!("substituting θ̈ gives U of (2.7): {}", agreement(&[&id])),
            w,
        );
    }
    let f = |x: Q| x.get().to_f64();
    // A slip, not an error: the factor is positive, so Ω, Ω₀ and N = −U/V
    // are those of U itself.
    Outcome::new(Verdict::Typo, Strength::Exact,
        format!("θ̈ of (2.5) is the contact acceleration (N eliminated): substituted into (2.6) it gives A/(A + m a² cos²θ)·U ({}), not U; at sin θ = 4/5, cos θ = 3/5, θ̇ = 1 (defaults) {:.4} against U = {:.4} (exact); the factor is positive, so Ω, Ω₀ and N do not change",
            scaled.how(), f(gave), f(u0)),
        w)
        .correct("substituting θ̈ from (2.5) gives A/(A + m a² cos²θ)·U = U/(mV), with the same sign as U; U itself comes from the θ equation of (2.2) at N = 0 with the integrals (2.3) (F2.6)")
}

/// F2.7: τ' = dτ/dθ; U = free-flight Λ̈; in contact U + V N = 0 with
/// V = 1/m + a² cos²θ/A > 0. Mutant: τ' with `+ p_ψ cos θ`.
pub fn f2_7(mutant: bool) -> Outcome {
    let tau1 = identity_test(27, |r| {
        let (p, s, c, _, pt) = rp(r);
        let an = angle_d(s, c);
        let t = tau_printed(&p.map(Dual::constant), an.sin, an.cos).0;
        let printed = if mutant {
            (p.pf + p.ps * c) / (p.big_a * s.sqr())
        } else {
            tau_printed(&p, s, c).1
        };
        Sample {
            point: pt,
            lhs: printed,
            rhs: t.grad[0],
        }
    });
    let u = identity_test(271, |r| {
        let (p, s, c, w, pt) = rp(r);
        Sample {
            point: pt,
            lhs: u_printed(&p, s, c, w),
            rhs: free_lambda_ddot(&p, s, c, w),
        }
    });
    let contact = identity_test(272, |r| {
        let (p, s, c, w, pt) = rp(r);
        let v = v_closed(&p, c);
        Sample {
            point: pt,
            lhs: u_printed(&p, s, c, w) + v * lagrange(&p, s, c, w).1,
            rhs: Q::int(0),
        }
    });
    let v = identity_test(273, |r| {
        let (p, s, c, w, pt) = rp(r);
        Sample {
            point: pt,
            lhs: v_closed(&p, c),
            rhs: u_v(&p, s, c, w).1,
        }
    });
    let (qp, qs, qc, qw) = shown_point();
    let (u0, v0) = u_v(&qp, qs, qc, qw);
    let mut o = verdict_of(&[("tau_prime", &tau1), ("U_free_flight", &u), ("U_plus_VN_in_contact", &contact), ("V_is_dLambda_ddot_dN", &v)],
        "τ' = dτ/dθ; U = Λ̈ at N = 0; V = ∂Λ̈/∂N = 1/m + a²cos²θ/A > 0 (N free), and in contact U + V N = 0, so contact (N ≥ 0) ⟺ U ≤ 0",
        "τ' = (p_φ − p_ψ cos θ)/(A sin²θ)");
    o.witness["reading"] =
        json!({"at": shown_json(), "V": v0.get().to_string(), "U": u0.get().to_string()});
    o
}

/// F2.8: `θ̇² − Φ = U/(a sin θ)`. Mutant: Φ with `sin³θ`.
pub fn f2_8(mutant: bool) -> Outcome {
    let id = identity_test(28, |r| {
        let (p, s, c, w, pt) = rp(r);
        let phi = if mutant {
            p.g / (p.a * s)
                - c / (p.big_a.sqr() * s.sqr() * s) * (p.pf - p.ps * c) * (p.ps - p.pf * c)
        } else {
            phi_printed(&p, s, c)
        };
        Sample {
            point: pt,
            lhs: (w.sqr() - phi) * p.a * s,
            rhs: free_lambda_ddot(&p, s, c, w),
        }
    });
    verdict_of(
        &[("phi", &id)],
        "(θ̇² − Φ)·a sin θ = U (free-flight Λ̈), and a sin θ > 0 on (0, π)",
        "Φ = g/(a sin θ) − cos θ (p_φ − p_ψ cos θ)(p_ψ − p_φ cos θ)/(A² sin⁴θ)",
    )
}

/// κ, α with p_M the momentum of larger |·| (exact).
fn kappa_alpha_q(p: &P2<Q>) -> (Q, Q, Q) {
    let (pm_big, pm_small) = if p.pf.get().abs() >= p.ps.get().abs() {
        (p.pf, p.ps)
    } else {
        (p.ps, p.pf)
    };
    kappa_alpha_of(p, pm_big, pm_small)
}

/// κ, α, p_M with p_M, p_m given.
fn kappa_alpha_of(p: &P2<Q>, pm_big: Q, pm_small: Q) -> (Q, Q, Q) {
    (
        p.g * p.big_a.sqr() / (p.a * pm_big.sqr()),
        pm_small / pm_big,
        pm_big,
    )
}

/// F2.9: `Φ A² sin⁴θ / p_M² = κ sin³θ − cos θ(α − cos θ)(1 − α cos θ)`.
/// Mutant: `κ = g A/(a p_M²)`.
pub fn f2_9(mutant: bool) -> Outcome {
    let id = identity_test(29, |r| {
        let (p, s, c, _, pt) = rp(r);
        // p_M = p_φ and (weight k) p_M = p_ψ: both orderings at once
        let k = r.signed();
        let side = |pm_big: Q, pm_small: Q| {
            let (mut kappa, alpha, pm) = kappa_alpha_of(&p, pm_big, pm_small);
            if mutant {
                kappa = kappa / p.big_a;
            }
            (
                phi_printed(&p, s, c) * p.big_a.sqr() * s.sqr().sqr() / pm.sqr(),
                kappa * s.sqr() * s - c * (alpha - c) * (Q::int(1) - alpha * c),
            )
        };
        let ((l0, r0), (l1, r1)) = (side(p.pf, p.ps), side(p.ps, p.pf));
        Sample {
            point: pt,
            lhs: l0 + k * l1,
            rhs: r0 + k * r1,
        }
    });
    verdict_of(&[("phi_scaled", &id)], "Φ·A²sin⁴θ/p_M² = κ sin³θ − f_r(θ) with κ = gA²/(a p_M²), α = p_m/p_M (both orderings of |p_φ|, |p_ψ|): same roots, and sign Φ = sign(κ sin³θ − f_r)", "")
}

/// S2.alpha (own): "thus α ≤ 1" — α = p_m/p_M lies in [−1, 1] and can be
/// negative. Mutant: a sample with p_φ p_ψ > 0 only.
pub fn s2_alpha(mutant: bool) -> Outcome {
    let (pf, ps) = if mutant { ("1", "2") } else { ("1", "-2") };
    let p = P2::exact(["1", "1", "0.25", "0.5", "9.81", pf, ps]);
    let (_, alpha, _) = kappa_alpha_q(&p);
    let w = json!({"p_phi": pf, "p_psi": ps, "alpha": alpha.text()});
    if alpha.signum() < 0 {
        Outcome::new(Verdict::Typo, Strength::Exact,
            format!("p_φ = {pf}, p_ψ = {ps}: α = {} < 0 exactly; |p_m| ≤ |p_M| gives −1 ≤ α ≤ 1, and case 4 (α < 0) needs the lower bound", alpha.text()), w)
            .correct("|α| ≤ 1")
    } else {
        Outcome::new(
            Verdict::Confirmed,
            Strength::Exact,
            "α ∈ [0, 1] in this sample",
            w,
        )
    }
}

/// F2.10: with α = 1, `(κ sin³θ − f_r)(1 + t²)³ = 8t³(κ − t(1 − t)(1 + t)/2)`,
/// `t = tan(θ/2)`. Mutant: `κ = μ(1 − μ)(1 + μ)`.
pub fn f2_10(mutant: bool) -> Outcome {
    let id = identity_test(210, |r| {
        let t = r.tan_half();
        let kappa = r.positive();
        let (s, c) = sin_cos_of_tan_half(t);
        let one = Q::int(1);
        let lhs = (kappa * s.sqr() * s - c * (one - c) * (one - c))
            * (one + t.sqr()).sqr()
            * (one + t.sqr());
        let k = if mutant { 1 } else { 2 };
        let rhs = Q::int(8) * t.sqr() * t * (kappa - t * (one - t) * (one + t) / Q::int(k));
        Sample {
            point: vec![("mu".into(), t)],
            lhs,
            rhs,
        }
    });
    verdict_of(&[("tan_half_substitution", &id)], "(2.9) at α = 1 times (1+μ²)³ = 8μ³(κ − μ(1−μ)(1+μ)/2), μ = tan(θ/2) > 0: positive roots of (2.10) ↔ roots of (2.9)", "2κ = μ(1 − μ)(1 + μ)")
}

/// F2.11: the reduced energy `T̃ + Π̃` of (2.11), as the printed file states
/// it, is constant along the contact motion: its time derivative
/// `E_θ θ̇ + E_θ̇ θ̈` vanishes with θ̈ from the Lagrange equations in contact,
/// so the phase curves are its level lines; a contact motion keeps contact
/// while N ≥ 0, i.e. in Ω₀ = Ω (S2.omega). Mutant: τ without its 1/sin θ.
pub fn f2_11(mutant: bool) -> Outcome {
    let id = identity_test(2110, |r| {
        let (p, s, c, w, pt) = rp(r);
        let an = angle_d(s, c);
        let pd = p.map(Dual::constant);
        // (2.11) as the printed file states it, in (θ, θ̇) by duals
        let wd = Dual::variable(w, 1);
        let key = "dynamics.energy";
        let e = if mutant {
            // τ taken as (p_ψ − p_φ cos θ)/A, without its 1/sin θ
            let tau = tau_printed(&pd, an.sin, an.cos).0 * an.sin;
            printed_at(key, &pd, an.sin, an.cos, wd, &[("tau", tau)])
        } else {
            printed_at(key, &pd, an.sin, an.cos, wd, &[])
        };
        let thdd = lagrange(&p, s, c, w).0;
        Sample {
            point: pt,
            lhs: e.grad[0] * w + e.grad[1] * thdd,
            rhs: Q::int(0),
        }
    });
    verdict_of(&[("reduced_energy_rate", &id)],
        "d(T̃ + Π̃)/dt = θ̇(Jθ̈ + ½J'θ̇² + Π̃') = 0 with θ̈ from the Lagrange equations in contact: phase curves are level lines of T̃ + Π̃; with Ω = Ω₀ (S2.omega) a motion without detachment is one that stays in Ω",
        "T̃ + Π̃ = const")
}

/// F2.12: Π̃' of (2.12) against the derivative of Π̃ (2.5). Mutant: `− Aττ'`.
pub fn f2_12(mutant: bool) -> Outcome {
    let id = identity_test(212, |r| {
        let (p, s, c, _, pt) = rp(r);
        let an = angle_d(s, c);
        let d = pi_tilde(&p.map(Dual::constant), an.sin, an.cos).grad[0];
        Sample {
            point: pt,
            lhs: pi_slope_printed(&p, s, c, if mutant { -1 } else { 1 }),
            rhs: d,
        }
    });
    verdict_of(
        &[("slope", &id)],
        "m g a cos θ + A τ τ' = dΠ̃/dθ",
        "Π̃'(θ) = m g a cos θ + A τ τ'",
    )
}

// ---------------------------------------------------------------- statements

/// S2.integrals: (2.3) and (2.4) in contact. The reaction N e_z at the
/// lowest point has no moment about the vertical through G nor about the
/// disc axis (exact vectors), so p_ψ and p_φ stay constant (p_x, p_y too:
/// N is vertical); and `d(T + Π)/dt = 0` along the contact motion, T of
/// (2.1) with `ż = a cos θ θ̇` and the integrals' spin rates, θ̈ from the
/// Lagrange equations (N does no work: Λ̇ = 0). Mutant: Π = m g z dropped.
pub fn s2_integrals(mutant: bool) -> Outcome {
    let moment = identity_test(2201, |r| {
        let (p, s, c, _, pt) = rp(r);
        let (spsi, cpsi) = sin_cos_of_tan_half(r.tan_half());
        let lambda = r.signed();
        let n = r.positive();
        let (mz, mk) = reaction_moment(p.a, s, c, spsi, cpsi, n, Q::int(0));
        Sample {
            point: pt,
            lhs: mz + lambda * mk,
            rhs: Q::int(0),
        }
    });
    let energy = identity_test(2202, |r| {
        let (p, s, c, w, pt) = rp(r);
        let thdd = lagrange(&p, s, c, w).0;
        let (zd, zdd) = (p.a * c * w, p.a * c * thdd - p.a * s * w.sqr());
        let gravity = if mutant { Q::int(0) } else { p.m * p.g * zd };
        Sample {
            point: pt,
            lhs: p.m * zd * zdd + p.big_a * w * thdd + w * spin_energy_slope(&p, s, c) + gravity,
            rhs: Q::int(0),
        }
    });
    let w =
        json!({"reaction_moment_vertical_and_axial": moment.json(), "energy_rate": energy.json()});
    if moment.agrees() && energy.agrees() {
        Outcome::new(Verdict::Confirmed, strength_of(&[&moment, &energy]),
            format!("the reaction N e_z at the lowest point has no moment about the vertical through G nor about the disc axis (p_ψ, p_φ constant; p_x, p_y since N is vertical), and d(T + Π)/dt = 0 along the contact motion (Lagrange θ̈, ż = a cos θ θ̇): {}", agreement(&[&moment, &energy])),
            w)
    } else {
        Outcome::new(
            Verdict::False,
            Strength::Exact,
            "an integral changes along the contact motion",
            w,
        )
    }
}

/// S2.omega: U + V N = 0 in contact with V > 0 (F2.7) and `θ̇² − Φ = U/(a sin θ)`
/// (F2.8), so (2.8) ⟺ N ≥ 0 ⟺ U ≤ 0: Ω = Ω₀. Mutant: V with `−a²cos²θ/A`.
pub fn s2_omega(mutant: bool) -> Outcome {
    let id = identity_test(220, |r| {
        let (p, s, c, w, pt) = rp(r);
        let v = if mutant {
            Q::int(1) / p.m - p.a.sqr() * c.sqr() / p.big_a
        } else {
            v_closed(&p, c)
        };
        Sample {
            point: pt,
            lhs: (w.sqr() - phi_printed(&p, s, c)) * p.a * s,
            rhs: -(v * lagrange(&p, s, c, w).1),
        }
    });
    if id.agrees() {
        Outcome::new(Verdict::Confirmed, Strength::Argument,
            "(θ̇² − Φ)·a sin θ = −V N exactly with V = 1/m + a²cos²θ/A > 0 and a sin θ > 0: {θ̇² < Φ} = {N > 0} = {U < 0}, Ω = Ω₀ for all parameters",
            json!({"identity": id.json()}))
    } else {
        Outcome::new(
            Verdict::False,
            Strength::Exact,
            "(2.8) is not −V N for the stated V",
            json!({"identity": id.json()}),
        )
    }
}

/// S2.case1: α = 0 ⇒ `f_r = −cos²θ` and `Φ = g/(a sin θ) + p_M² cos²θ/(A² sin⁴θ) > 0`
/// (exact). Mutant: p_ψ = p_φ/2 (α ≠ 0).
pub fn s2_case1(mutant: bool) -> Outcome {
    let id = identity_test(221, |r| {
        let (p, s, c, _, pt) = rp(r);
        // p_φ = 0 and (weight k) p_ψ = 0: both cases at once
        let k = r.signed();
        let side = |zero_pf: bool| {
            let mut q = p;
            if mutant {
                q.ps = p.pf / Q::int(2);
            } else if zero_pf {
                q.pf = Q::int(0);
            } else {
                q.ps = Q::int(0);
            }
            let pm2 = q.pf.sqr() + q.ps.sqr();
            let rhs = q.g / (q.a * s) + pm2 * c.sqr() / (q.big_a.sqr() * s.sqr().sqr());
            (phi_printed(&q, s, c), rhs)
        };
        let ((l0, r0), (l1, r1)) = (side(true), side(false));
        Sample {
            point: pt,
            lhs: l0 + k * l1,
            rhs: r0 + k * r1,
        }
    });
    if id.agrees() {
        Outcome::new(Verdict::Confirmed, Strength::Argument,
            "with p_φ p_ψ = 0: Φ = g/(a sin θ) + p_M² cos²θ/(A² sin⁴θ) exactly, a positive plus a non-negative term on (0, π) (f_r = −cos²θ ≤ 0; see S2.case1fr for the strict sign)",
            json!({"identity": id.json()}))
    } else {
        Outcome::new(
            Verdict::False,
            Strength::Exact,
            "Φ is not the sum of non-negative terms",
            json!({"identity": id.json()}),
        )
    }
}

/// S2.case1fr (own): "f_r(θ) < 0" at α = 0 — `f_r(π/2) = 0` exactly.
/// Mutant: α = 1/2.
pub fn s2_case1fr(mutant: bool) -> Outcome {
    let alpha = if mutant { Q::ratio(1, 2) } else { Q::int(0) };
    // f_r(θ) = cos θ(α − cos θ)(1 − α cos θ) at θ = π/2 (cos = 0) and at θ with tan(θ/2) = 1/2
    let c_half = Q::int(0);
    let fr = |c: Q| c * (alpha - c) * (Q::int(1) - alpha * c);
    let at_half_pi = fr(c_half);
    let w = json!({"alpha": alpha.text(), "f_r(pi/2)": at_half_pi.text()});
    if at_half_pi.is_zero() && alpha.is_zero() {
        Outcome::new(Verdict::Typo, Strength::Exact,
            "at α = 0, f_r = −cos²θ vanishes at θ = π/2 exactly, so f_r < 0 fails there; Φ(π/2) = g/a > 0 still, so the conclusion Φ > 0 stands", w)
            .correct("f_r(θ) = −cos²θ ≤ 0 on (0, π), zero only at θ = π/2; Φ > 0 on (0, π)")
    } else {
        Outcome::new(
            Verdict::Confirmed,
            Strength::Exact,
            "f_r ≠ 0 at π/2 for this α",
            w,
        )
    }
}

/// The parameters of §2–3 other than the momenta, as markup.
pub(super) fn p2_text() -> String {
    params_text(&["m", "a", "A", "C", "g"], &DEFAULTS[..5])
}

/// sin³θ·Π̃′(θ) of (2.12) for the momenta `(pf, ps)`, scaled to a largest
/// value 1 in absolute value on [0, π].
fn scaled_slope(pf: &str, ps: &str) -> Vec<(f64, f64)> {
    let pi = std::f64::consts::PI;
    let f = ClearedSlope(p2_texts(pf, ps));
    let pts: Vec<(f64, f64)> = grid(0.0, pi, 400).map(|t| (t, f.eval(t))).collect();
    let scale = pts.iter().map(|p| p.1.abs()).fold(1e-300, f64::max);
    pts.iter().map(|&(x, y)| (x, y / scale)).collect()
}

const SLOPE_TITLE: &str = "sin³θ·Π\u{303}′(θ) of (2.12), each scaled to max |·| = 1";

/// The picture of S2.case1fr.
fn s2_case1fr_figure(_mark: Option<PhaseBox>) -> FigureSpec {
    let pi = std::f64::consts::PI;
    FigureSpec::Lines(Curves {
        title: "S2.case1fr: f_{r}(θ) = −cos²θ at α = 0 is not < 0".into(),
        subtitle: "§2, case 1 of the proof that Φ > 0".into(),
        x: axis(THETA_RAD, [0.0, pi], true),
        y: axis("f_{r} (dimensionless)", [-1.1, 0.3], false),
        series: vec![series(
            "f_{r} = −cos²θ",
            grid(0.0, pi, 300).map(|t| (t, -t.cos().powi(2))).collect(),
        )],
        marks: vec![marks(
            "f_{r}(π/2) = 0 (exact)",
            vec![(pi / 2.0, 0.0)],
            Shape::Dot,
        )],
        zero: true,
    })
}

fn roots_json(r: &EquationRoots) -> serde_json::Value {
    json!({"complete": r.complete, "count": r.unique_count(),
           "roots": r.roots.iter().map(|x| json!([x.lo, x.hi])).collect::<Vec<_>>()})
}

/// S2.case2: α = 1. κ₀ = √3/9 from the κ₀ proof (every κ), plus certified
/// samples κ = 0.1 (two roots, Φ < 0 between them) and κ = 0.25 (none).
/// Mutant: the claimed threshold 0.2.
pub fn s2_case2(mutant: bool) -> Outcome {
    let proof = prove_kappa0();
    let claimed = if mutant {
        point(0.2)
    } else {
        point(3.0).sqrt() / point(9.0)
    };
    let k0 = proof.kappa0.interval();
    let matches =
        proof.all_proved() && claimed.subset(k0.convex_hull(claimed)) && !claimed.disjoint(k0);
    let b = Budget::default();
    let two = solve_2_10(super::dec("0.1"), &b).expect("κ > 0");
    let none = solve_2_10(super::dec("0.25"), &b).expect("κ > 0");
    // between the two roots: μ(1−μ)(1+μ) − 2κ > 0 ⟺ G > κ ⟺ Φ < 0 (F2.9, F2.10)
    let between = if two.roots.len() == 2 {
        let mid = point(0.5 * (two.roots[0].hi + two.roots[1].lo));
        Some(mid * (point(1.0) - mid) * (point(1.0) + mid) - point(2.0) * super::dec("0.1"))
    } else {
        None
    };
    let ok = matches
        && two.complete
        && two.unique_count() == 2
        && none.complete
        && none.unique_count() == 0
        && between.is_some_and(|x| x.inf() > 0.0);
    let w = json!({"kappa0_proved": enc(k0), "claimed": enc(claimed), "proof_all_steps": proof.all_proved(),
        "kappa_0.1": roots_json(&two), "kappa_0.25": roots_json(&none), "g_minus_kappa_between_roots_times_2": between.map(enc)});
    if ok {
        Outcome::new(Verdict::Confirmed, Strength::Certified,
            format!("κ₀ proof: κ₀ ∈ [{:.16}, {:.16}] ∋ √3/9; κ > κ₀ no positive root, κ < κ₀ two simple roots; sign Φ = sign(κ − μ(1−μ²)/2) (F2.9, F2.10) so Φ < 0 between them: Ω has two components. Samples κ = 0.1 (2 roots), κ = 0.25 (none)", k0.inf(), k0.sup()), w)
    } else {
        Outcome::new(
            Verdict::False,
            Strength::Certified,
            "the claimed threshold is not the proved κ₀ or the samples disagree",
            w,
        )
    }
}

/// S2.case3: α ∈ (0, 1): by the unimodality lemma of G(s, α) = κ-level of
/// (2.9) (checked on the α-boxes of [0, 1] of the band proof, the last one
/// included), κ > κ_crit(α) gives no root (Φ > 0, one
/// component) and κ < κ_crit(α) two simple roots (Φ < 0 between, two
/// components); κ_crit(α) > 0 since G(s, α) > 0 for s ∈ (√((1−α)/(1+α)), 1).
/// Certified sample: α = 0.5, κ_crit ∈ band, both sides solved with (2.9).
/// Mutant: α = 0, where κ_crit = 0 and only one form exists.
pub fn s2_case3(mutant: bool) -> Outcome {
    // the band proof's α-boxes: [0, 1] in `n` parts, the last left to κ₀
    let n = crate::certificate::catalog::BAND_BOXES;
    let in_proof = n - 1;
    let cells: Vec<_> = (0..n)
        .map(|i| {
            band_cell(
                Interval::try_from((i as f64 / n as f64, (i + 1) as f64 / n as f64)).unwrap(),
                1e-6,
            )
        })
        .collect();
    let lemma = cells.iter().all(|c| c.lemma_ok);
    let alpha_text = if mutant { "0" } else { "0.5" };
    let alpha = super::dec(alpha_text);
    let cell = band_cell(alpha, 1e-9);
    let b = Budget::default();
    let below = if cell.lower > 0.0 {
        solve_2_9(point(cell.lower * 0.5), alpha, &b).ok()
    } else {
        None
    };
    let above = solve_2_9(point(cell.upper * 2.0 + 1e-3), alpha, &b).ok();
    // G at s = 0.9 is > 0 for α = 0.5 (positivity of κ_crit)
    let g_pos = g_crit(point(0.9), alpha);
    let two_forms = below
        .as_ref()
        .is_some_and(|r| r.complete && r.unique_count() == 2)
        && above
            .as_ref()
            .is_some_and(|r| r.complete && r.unique_count() == 0);
    let w = json!({"lemma_alpha_boxes": n, "lemma_holds": lemma, "band_proof_alpha_boxes": in_proof, "alpha": alpha_text, "kappa_crit_band": [cell.lower, cell.upper],
        "G(0.9, alpha)": enc(g_pos), "below_band_half": below.as_ref().map(roots_json), "above_band": above.as_ref().map(roots_json)});
    if lemma && two_forms && g_pos.inf() > 0.0 {
        Outcome::new(Verdict::Confirmed, Strength::Argument,
            format!("unimodality lemma certified on all {n} α-boxes of [0, 1]: for each α ∈ (0, 1) one component when κ > κ_crit(α), two when κ < κ_crit(α) (κ_crit > 0); the band proof covers {in_proof} α-boxes of [0, {in_proof}/{n}] and α = 1 is the κ₀ proof; α = 0.5: κ_crit ∈ [{:.6}, {:.6}], 2 roots below, 0 above (certified)", cell.lower, cell.upper), w)
    } else {
        Outcome::new(
            Verdict::False,
            Strength::Certified,
            format!("at α = {alpha_text} the two forms do not both occur"),
            w,
        )
    }
}

/// S2.case4: `Φ(π − θ; p_φ, p_ψ) = Φ(θ; p_φ, −p_ψ)` exactly (α → −α).
/// Mutant: without the sign change of p_ψ.
pub fn s2_case4(mutant: bool) -> Outcome {
    let id = identity_test(224, |r| {
        let (p, s, c, _, pt) = rp(r);
        let mut q = p;
        if !mutant {
            q.ps = -p.ps;
        }
        Sample {
            point: pt,
            lhs: phi_printed(&p, s, -c),
            rhs: phi_printed(&q, s, c),
        }
    });
    if id.agrees() {
        Outcome::new(Verdict::Confirmed, strength_of(&[&id]), "Φ(π − θ) with (p_φ, p_ψ) equals Φ(θ) with (p_φ, −p_ψ), i.e. α → −α: α < 0 is the mirror image about θ = π/2 of |α|", json!({"identity": id.json()}))
    } else {
        Outcome::new(
            Verdict::False,
            Strength::Exact,
            "the mirror does not map the case to α → −α",
            json!({"identity": id.json()}),
        )
    }
}

/// `sin³θ · Π̃'(θ) = m g a cos θ sin³θ + (p_ψ − p_φ cos θ)(p_φ − p_ψ cos θ)/A`:
/// (2.12) with the singular factor cleared, defined on all of R.
pub struct ClearedSlope(pub P2<Interval>);

impl RealFn for ClearedSlope {
    fn eval<T: Scalar>(&self, theta: T) -> T {
        let p = self.0.map(T::lift);
        let (s, c) = theta.sin_cos();
        p.m * p.g * p.a * c * s.sqr() * s + (p.ps - p.pf * c) * (p.pf - p.ps * c) / p.big_a
    }
}

pub fn p2_texts(pf: &str, ps: &str) -> P2<Interval> {
    let d = DEFAULTS;
    let dc = super::dec;
    P2 {
        m: dc(d[0]),
        a: dc(d[1]),
        big_a: dc(d[2]),
        big_c: dc(d[3]),
        g: dc(d[4]),
        pf: dc(pf),
        ps: dc(ps),
    }
}

/// Certified equilibria of (2.5) on (0, π) and their types.
///
/// The cleared slope f is isolated on `[lo, π⁺]` (π⁺ the double just above
/// π; f(π) = (p_φ + p_ψ)²/A). With `|p_φ| ≠ |p_ψ|`, lo = 0 and f(0) =
/// −(p_φ − p_ψ)²/A ≠ 0. With `p_φ = p_ψ`, f = m g a cos θ sin³θ + p²(1 − cos θ)²/A
/// is a sum of positive terms where cos θ > 0, so lo = 1.5 (cos 1.5 > 0,
/// checked). Types: the sign of f' = sin³θ Π̃'' on each root enclosure
/// (> 0: minimum of Π̃, a centre; < 0: maximum, a saddle).
pub fn equilibria(
    pf: &str,
    ps: &str,
) -> (Option<Vec<[f64; 2]>>, Vec<&'static str>, serde_json::Value) {
    let p = p2_texts(pf, ps);
    let f = ClearedSlope(p);
    let equal = pf == ps;
    let lo = if equal { 1.5 } else { 0.0 };
    let lo_ok = if equal {
        point(1.5).cos().inf() > 0.0
    } else {
        f.eval(point(0.0)).sup() < 0.0 || f.eval(point(0.0)).inf() > 0.0
    };
    let hi = Interval::PI.sup();
    let iso = crate::roots::isolate(&f, lo, hi, &Budget::default());
    let types: Vec<&'static str> = iso
        .roots
        .iter()
        .map(|x| {
            let v = f.eval(Dual::variable(x.interval(), 0)).grad[0];
            if !x.is_unique() {
                "undecided"
            } else if v.inf() > 0.0 {
                "centre"
            } else if v.sup() < 0.0 {
                "saddle"
            } else {
                "undecided"
            }
        })
        .collect();
    // no root may sit in [π, π⁺]: f(π⁺-box) ∌ 0 is part of the isolation
    let in_range = iso.roots.iter().all(|r| r.hi < Interval::PI.inf());
    let complete = iso.complete && lo_ok && in_range;
    let roots: Vec<[f64; 2]> = iso.roots.iter().map(|r| [r.lo, r.hi]).collect();
    let js = json!({"search": [lo, hi], "lower_end_argument": if equal {"p_phi = p_psi: f > 0 where cos θ > 0 (cos 1.5 > 0 certified)"} else {"f(0) = −(p_phi − p_psi)²/A ≠ 0"},
        "complete": complete, "count": roots.len(), "roots": roots, "types": types});
    (if complete { Some(roots) } else { None }, types, js)
}

const COUNT_SAMPLES: [(&str, &str); 6] = [
    ("2.5", "2"),
    ("2", "0.5"),
    ("1", "0.2"),
    ("3", "1"),
    ("0.5", "0.1"),
    ("4", "3"),
];

fn count_table(
    samples: &[(&str, &str)],
) -> (Vec<serde_json::Value>, Vec<(usize, Vec<&'static str>)>) {
    let mut js = Vec::new();
    let mut res = Vec::new();
    for (pf, ps) in samples {
        let (r, t, j) = equilibria(pf, ps);
        js.push(json!({"p_phi": pf, "p_psi": ps, "equilibria": j}));
        res.push((r.map_or(usize::MAX, |r| r.len()), t));
    }
    (js, res)
}

/// S2.12count: root counts of (2.12) with the certified isolator: samples
/// with |α| < 1 and the α = 1 witnesses p_φ = p_ψ = 1 (none) and 0.3 (two).
/// Mutant: only the |α| < 1 samples.
pub fn s2_12count(mutant: bool) -> Outcome {
    let mut samples: Vec<(&str, &str)> = COUNT_SAMPLES.to_vec();
    if !mutant {
        samples.extend([("1", "1"), ("0.3", "0.3")]);
    }
    let (js, res) = count_table(&samples);
    let bad: Vec<usize> = res
        .iter()
        .enumerate()
        .filter(|(_, (n, _))| *n != 1 && *n != 3)
        .map(|(i, _)| i)
        .collect();
    let counts: Vec<String> = samples
        .iter()
        .zip(&res)
        .map(|((a, b), (n, _))| format!("({a}, {b}) → {n}"))
        .collect();
    let w = json!({"samples": js});
    if bad.is_empty() {
        Outcome::new(Verdict::ConfirmedOn, Strength::Certified, format!("one or three roots at every sample (p_φ, p_ψ) with the other parameters at their defaults: {}", counts.join(", ")), w)
    } else {
        Outcome::new(Verdict::False, Strength::Certified,
            format!("certified counts {}: at α = 1 (p_φ = p_ψ) (2.12) has no root (p = 1) or two (p = 0.3)", counts.join(", ")), w)
            .correct("for |α| < 1 an odd number (Π̃ → +∞ at both ends; one or three in every sample); for p_φ = ±p_ψ ≠ 0 (α = ±1) Π̃ stays bounded at one end and (2.12) has none or two roots (a saddle and a centre), or one double root at the transition")
    }
}

/// The picture of S2.12count.
fn s2_12count_figure(_mark: Option<PhaseBox>) -> FigureSpec {
    let pi = std::f64::consts::PI;
    let samples = [("1", "1"), ("0.3", "0.3"), ("1", "0.2"), ("2.5", "2")];
    let mut ss = Vec::new();
    let mut roots = Vec::new();
    for (pf, ps) in samples {
        let (found, _, _) = equilibria(pf, ps);
        let count = match &found {
            Some(rs) if rs.len() == 1 => "1 root".to_string(),
            Some(rs) => format!("{} roots", rs.len()),
            None => "count not certified".into(),
        };
        ss.push(series(
            format!("{}: {count}", momenta(pf, ps)),
            scaled_slope(pf, ps),
        ));
        roots.extend(
            found
                .into_iter()
                .flatten()
                .map(|r| (0.5 * (r[0] + r[1]), 0.0)),
        );
    }
    FigureSpec::Lines(Curves {
        title: "S2.12count: how many roots (2.12) has".into(),
        subtitle: format!("{SLOPE_TITLE}; {}", p2_text()),
        x: axis(THETA_RAD, [0.0, pi], true),
        y: axis("scaled slope (dimensionless)", [-1.05, 1.05], false),
        series: ss,
        marks: vec![marks("certified roots (enclosures)", roots, Shape::Dot)],
        zero: true,
    })
}

/// S2.12type: types of the equilibria (sign of Π̃'' on the certified root
/// enclosures). Mutant: only |α| < 1 samples.
pub fn s2_12type(mutant: bool) -> Outcome {
    let mut samples: Vec<(&str, &str)> = COUNT_SAMPLES.to_vec();
    if !mutant {
        samples.push(("0.3", "0.3"));
    }
    let (js, res) = count_table(&samples);
    let ok = |t: &Vec<&str>| *t == ["centre"] || *t == ["centre", "saddle", "centre"];
    let bad: Vec<String> = samples
        .iter()
        .zip(&res)
        .filter(|(_, (_, t))| !ok(t))
        .map(|((a, b), (_, t))| format!("({a}, {b}): {}", t.join(", ")))
        .collect();
    let w = json!({"samples": js});
    if bad.is_empty() {
        Outcome::new(
            Verdict::ConfirmedOn,
            Strength::Certified,
            "every sample: one centre, or centre–saddle–centre",
            w,
        )
    } else {
        Outcome::new(Verdict::False, Strength::Certified, format!("not one centre nor a saddle and two centres: {}", bad.join("; ")), w)
            .correct("for |α| < 1 one centre or a saddle between two centres (all samples); for α = ±1 a saddle and one centre, or no equilibrium")
    }
}

/// The picture of S2.12type.
fn s2_12type_figure(_mark: Option<PhaseBox>) -> FigureSpec {
    let pi = std::f64::consts::PI;
    // Π̃ of (2.5): its minima are centres, its maxima saddles.
    let samples = [("0.3", "0.3"), ("1", "0.2"), ("2.5", "2")];
    let mut ss = Vec::new();
    let (mut centres, mut saddles) = (Vec::new(), Vec::new());
    for (pf, ps) in samples {
        let p = p2_texts(pf, ps).map(|x| x.mid());
        let pot = |t: f64| {
            p.m * p.g * p.a * t.sin()
                + (p.ps - p.pf * t.cos()).powi(2) / (2.0 * p.big_a * t.sin().powi(2))
        };
        let (found, types, _) = equilibria(pf, ps);
        let rs = found.unwrap_or_default();
        ss.push(series(
            format!("{}: {}", momenta(pf, ps), types.join(", ")),
            grid(0.02, pi - 0.02, 600).map(|t| (t, pot(t))).collect(),
        ));
        for (r, t) in rs.iter().zip(&types) {
            let th = 0.5 * (r[0] + r[1]);
            match *t {
                "centre" => centres.push((th, pot(th))),
                "saddle" => saddles.push((th, pot(th))),
                _ => {}
            }
        }
    }
    FigureSpec::Lines(Curves {
        title: "S2.12type: the types of the equilibria of (2.5)".into(),
        subtitle: format!(
            "reduced potential Π\u{303}(θ) of (2.5): a centre at a minimum, a saddle at a maximum; {}",
            p2_text()
        ),
        x: axis(THETA_RAD, [0.0, pi], true),
        y: axis("Π\u{303} (J)", [0.0, 25.0], false),
        series: ss,
        marks: vec![
            marks("centre: Π\u{303} minimum (certified)", centres, Shape::Dot),
            marks(
                "saddle: Π\u{303} maximum (certified)",
                saddles,
                Shape::Square,
            ),
        ],
        zero: false,
    })
}

/// S2.12inOmega: `U(θ, 0) − (a cos θ/A)·Π̃'(θ) = −g(1 + m a² cos²θ/A)` exactly,
/// so at every equilibrium U = −g(1 + ma²cos²θ/A) < 0. Mutant: Π̃' with −Aττ'.
pub fn s2_12in_omega(mutant: bool) -> Outcome {
    let id = identity_test(2121, |r| {
        let (p, s, c, _, pt) = rp(r);
        let lhs = u_printed(&p, s, c, Q::int(0))
            - p.a * c / p.big_a * pi_slope_printed(&p, s, c, if mutant { -1 } else { 1 });
        Sample {
            point: pt,
            lhs,
            rhs: -(p.g * (Q::int(1) + p.m * p.a.sqr() * c.sqr() / p.big_a)),
        }
    });
    if id.agrees() {
        Outcome::new(Verdict::Confirmed, Strength::Argument, "U − (a cos θ/A)Π̃' = −g(1 + ma²cos²θ/A) < 0 exactly: every equilibrium (Π̃' = 0, θ̇ = 0) lies strictly inside Ω, for all parameters", json!({"identity": id.json()}))
    } else {
        Outcome::new(
            Verdict::False,
            Strength::Exact,
            "no such identity",
            json!({"identity": id.json()}),
        )
    }
}

/// S2.12components: for samples with Ω disconnected ((2.9) has two roots),
/// where the equilibria lie. Witness: p_φ = p_ψ = 2 (α = 1, κ < κ₀): Ω has two
/// components and no equilibrium at all. Mutant: the default sample only.
pub fn s2_12components(mutant: bool) -> Outcome {
    let mut samples: Vec<(&str, &str)> = vec![
        ("2.5", "2"),
        ("3", "1"),
        ("10", "2"),
        ("10", "1"),
        ("6", "1"),
    ];
    if !mutant {
        samples.push(("2", "2"));
    }
    let mut js = Vec::new();
    let mut fails = Vec::new();
    let mut checked = 0;
    for (pf, ps) in &samples {
        let d = disc(pf, ps);
        let (kappa, alpha) = kappa_alpha(&d).expect("momentum");
        let gaps = solve_2_9(kappa, alpha, &Budget::default()).expect("valid");
        let (eq, _, eqj) = equilibria(pf, ps);
        let mut entry = json!({"p_phi": pf, "p_psi": ps, "kappa": enc(kappa), "alpha": enc(alpha), "roots_2_9": roots_json(&gaps), "equilibria": eqj});
        if let (true, Some(eq)) = (gaps.complete && gaps.unique_count() == 2, eq) {
            checked += 1;
            let (g1, g2) = (gaps.roots[0].hi, gaps.roots[1].lo);
            let left = eq.iter().filter(|r| r[1] < gaps.roots[0].lo).count();
            let right = eq.iter().filter(|r| r[0] > gaps.roots[1].hi).count();
            let inside = eq.len() - left - right;
            let _ = (g1, g2);
            entry["left"] = json!(left);
            entry["right"] = json!(right);
            entry["in_gap"] = json!(inside);
            // the paper: one on one side, the other two (if any) on the other
            let ok = inside == 0
                && ((left == 1 && (right == 0 || right == 2))
                    || (right == 1 && (left == 0 || left == 2)));
            if !ok {
                fails.push(format!(
                    "(p_φ, p_ψ) = ({pf}, {ps}): {left} left, {right} right"
                ));
            }
        }
        js.push(entry);
    }
    let w = json!({"samples": js});
    if !fails.is_empty() {
        Outcome::new(Verdict::False, Strength::Certified,
            format!("Ω disconnected (two certified roots of (2.9)) but {}", fails.join("; ")), w)
            .correct("for |α| < 1 one equilibrium on one side of the gap and zero or two on the other (samples); for α = 1 Ω can be disconnected with no equilibrium at all")
    } else if checked > 0 {
        Outcome::new(Verdict::ConfirmedOn, Strength::Certified, format!("{checked} disconnected samples: one equilibrium on one side, zero or two on the other"), w)
    } else {
        Outcome::new(
            Verdict::NotCheckable,
            Strength::Certified,
            "no disconnected sample",
            w,
        )
    }
}

/// The picture of S2.12components.
fn s2_12components_figure(_mark: Option<PhaseBox>) -> FigureSpec {
    let pi = std::f64::consts::PI;
    // The gap of Ω is where Φ < 0, i.e. where κ sin³θ − f_r(θ) < 0
    // (F2.9: Φ·A²sin⁴θ/p_M² = κ sin³θ − f_r); equilibria on the axis.
    let samples = [("2", "2"), ("2.5", "2")];
    let mut ss = Vec::new();
    let mut eq = Vec::new();
    let mut counts = Vec::new();
    let mut gap_marks = Vec::new();
    for (((pf, ps), shape), dashed) in samples
        .into_iter()
        .zip([Shape::Ring, Shape::Square])
        .zip([false, true])
    {
        let d = disc(pf, ps);
        let ka = kappa_alpha(&d).ok();
        if let Some((kappa, alpha)) = ka.map(|(k, a)| (k.mid(), a.mid())) {
            let f = |t: f64| {
                let c = t.cos();
                kappa * t.sin().powi(3) - c * (alpha - c) * (1.0 - alpha * c)
            };
            ss.push(Series {
                dashed,
                ..series(
                    format!(
                        "{} ({}): κ = {kappa:.4}, α = {alpha:.2}",
                        momenta(pf, ps),
                        if dashed { "dashed" } else { "solid" }
                    ),
                    grid(0.0, pi, 600).map(|t| (t, f(t))).collect(),
                )
            });
        }
        let (found, _, _) = equilibria(pf, ps);
        let found = found.unwrap_or_default();
        counts.push(format!("{} at ({pf}, {ps})", found.len()));
        eq.extend(found.iter().map(|r| (0.5 * (r[0] + r[1]), 0.0)));
        let gaps: Vec<(f64, f64)> = ka
            .and_then(|(kappa, alpha)| solve_2_9(kappa, alpha, &Budget::default()).ok())
            .filter(|g| g.complete)
            .map(|g| g.roots.iter().map(|r| (0.5 * (r.lo + r.hi), 0.0)).collect())
            .unwrap_or_default();
        gap_marks.push(marks(
            format!("({pf}, {ps}): ends of the gap of Ω, certified roots of (2.9)"),
            gaps,
            shape,
        ));
    }
    let mut all = vec![marks(
        format!("equilibria (certified): {}", counts.join(", ")),
        eq,
        Shape::Dot,
    )];
    all.extend(gap_marks);
    FigureSpec::Lines(Curves {
        title: "S2.12components: equilibria on the two sides of the gap of Ω".into(),
        subtitle: format!(
            "κ sin³θ − f_{{r}}(θ), the sign of Φ of (2.8): Ω has a gap where it is < 0; {}",
            p2_text()
        ),
        x: axis(THETA_RAD, [0.0, pi], true),
        y: axis("κ sin³θ − f_{r} (dimensionless)", [-0.1, 0.3], false),
        series: ss,
        marks: all,
        zero: true,
    })
}

/// This section's check functions, by claim id (`claims.toml` holds the rest).
/// The claims of this section with a picture, each drawn by the function
/// beside its check.
pub(super) const FIGURES: &[(&str, FigureOf)] = &[
    ("S2.case1fr", s2_case1fr_figure),
    ("S2.12count", s2_12count_figure),
    ("S2.12type", s2_12type_figure),
    ("S2.12components", s2_12components_figure),
];

pub(super) const CHECKS: &[(&str, Check)] = &[
    ("F2.1", f2_1),
    ("F2.5", f2_5),
    ("F2.6", f2_6),
    ("F2.6route", f2_6route),
    ("F2.7", f2_7),
    ("F2.8", f2_8),
    ("F2.9", f2_9),
    ("S2.alpha", s2_alpha),
    ("F2.10", f2_10),
    ("F2.11", f2_11),
    ("F2.12", f2_12),
    ("S2.integrals", s2_integrals),
    ("S2.omega", s2_omega),
    ("S2.case1", s2_case1),
    ("S2.case1fr", s2_case1fr),
    ("S2.case2", s2_case2),
    ("S2.case3", s2_case3),
    ("S2.case4", s2_case4),
    ("S2.12count", s2_12count),
    ("S2.12type", s2_12type),
    ("S2.12inOmega", s2_12in_omega),
    ("S2.12components", s2_12components),
];
