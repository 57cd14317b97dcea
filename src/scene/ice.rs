//! §3: disc with a sharp edge on ice, (2.8), (3.1)–(3.5).
//!
//! The Newton–Euler derivation (the `derived` variant: V₀ = 1/m + a²cos²θ/(A +
//! m a² sin²θ), not the printed 1/m of (3.4); Ω₀ = {N > 0} with θ̈ from (3.3))
//! is in `scenes/ice-disc.toml`, the printed (2.8), (3.5) in
//! `scenes/ice-disc-printed.toml`; their regions are the texts of
//! this scene's [`Model::formulas`].

use super::smooth::{SmoothDisc, SMOOTH_PARAMS};
use super::{Angle, Constraints, Domain, Formulas, Model, Quadratic, Variant};
use crate::number::param::{ParamError, ParamSet, ParamSpec, Sign};
use crate::number::scalar::Scalar;
use inari::Interval;

#[derive(Clone, Debug)]
pub struct IceDisc {
    pub disc: SmoothDisc,
    pub c0: Interval,
}

const ICE_PARAMS: [ParamSpec; 8] = {
    let s = SMOOTH_PARAMS;
    [
        s[0],
        s[1],
        s[2],
        s[3],
        s[4],
        s[5],
        s[6],
        ParamSpec {
            name: "c0",
            default: "0",
            sign: Sign::Any,
            meaning: "constant c₀ of the integral (3.1)",
            unit: "",
        },
    ]
};

impl IceDisc {
    /// v_x of (3.1): `c₀ − (a/A)(p_ψ ln tg(θ/2) − p_φ ln sin θ)`.
    ///
    /// `tg(θ/2)` is evaluated directly: on (0, π) it is increasing and
    /// positive, so its enclosure stays tight and defined up to both ends
    /// (a form through `ln(1 + cos θ)` reaches `ln 0` next to θ = π).
    pub fn v_x<T: Scalar>(&self, an: &Angle<T>) -> T {
        let d = &self.disc;
        let (a, big_a) = (T::lift(d.a), T::lift(d.big_a));
        let (pf, ps) = (T::lift(d.p_phi), T::lift(d.p_psi));
        let ln_sin = an.sin.ln();
        let ln_tan_half = (an.theta / T::int(2)).tan().ln();
        T::lift(self.c0) - a / big_a * (ps * ln_tan_half - pf * ln_sin)
    }

    /// The coefficient V₀ of N in Λ̈ = U₀ + V₀ N (3.4).
    pub fn reaction_coefficient<T: Scalar>(&self, v: Variant, an: &Angle<T>) -> T {
        let d = &self.disc;
        let (m, a, big_a) = (T::lift(d.m), T::lift(d.a), T::lift(d.big_a));
        match v {
            Variant::Printed => T::int(1) / m,
            Variant::Derived => {
                T::int(1) / m + a.sqr() * an.cos.sqr() / (big_a + m * a.sqr() * an.sin.sqr())
            }
        }
    }
}

impl Model for IceDisc {
    const NAME: &'static str = "ice-disc";
    const TITLE: &'static str = "§3: disc with a sharp edge on ice";
    const PARAMS: &'static [ParamSpec] = &ICE_PARAMS;

    fn from_params(p: &ParamSet) -> Result<Self, ParamError> {
        Ok(IceDisc {
            disc: SmoothDisc::from_param_set(p),
            c0: p.get("c0"),
        })
    }

    fn domain(&self) -> Domain {
        self.disc.domain()
    }

    const DOMAIN_TEXT: [[&'static str; 2]; 2] = SmoothDisc::DOMAIN_TEXT;

    fn formulas(v: Variant) -> Formulas {
        let (mut definitions, omega) = SmoothDisc::omega_formula(v);
        // Ω₀ needs τ, τ' in both readings; (2.8) alone does not define them.
        if v == Variant::Printed {
            definitions.extend(
                SmoothDisc::omega_formula(Variant::Derived)
                    .0
                    .into_iter()
                    .take(2),
            );
        }
        definitions.push(("vx", "c0 - a/A*(p_psi*ln(tan(t/2)) - p_phi*ln(sin(t)))"));
        let omega0 = match v {
            Variant::Printed => {
                definitions.push(("bracket", "m*g*a*cos(t) - m*a*vx*tau + A*tau*tau1"));
                "a*sin(t)*w^2 + (a*cos(t)/(A + m*a^2)*bracket - g)"
            }
            Variant::Derived => {
                definitions.push((
                    "acc",
                    "(-(m*g*a*cos(t)) + m*a*vx*tau - A*tau*tau1)/(A + m*a^2)",
                ));
                "a*sin(t)*w^2 + (-g - a*cos(t)*acc)"
            }
        };
        Formulas {
            definitions,
            omega,
            omega0,
        }
    }

    /// §3, subcase 1: with p_φ = p_ψ = 0, τ = 0 and (3.5) reads
    /// `a θ̇² sin θ < g (A + m a² sin²θ)/(A + m a²) ≤ g`, while Ω is
    /// `a θ̇² sin θ < g`: Ω₀ ⊂ Ω (both readings define this Ω₀; the claim
    /// S3.sub1 of `check-paper` checks the identity exactly).
    fn omega0_inside_omega(&self, _v: Variant) -> bool {
        let zero = |x: Interval| x.inf() == 0.0 && x.sup() == 0.0;
        zero(self.disc.p_phi) && zero(self.disc.p_psi)
    }

    fn constraints<T: Scalar>(&self, v: Variant, an: &Angle<T>) -> Constraints<T> {
        let d = &self.disc;
        let (m, a, g, big_a) = (T::lift(d.m), T::lift(d.a), T::lift(d.g), T::lift(d.big_a));
        let omega0 = match v {
            // (3.5): a θ̇² sin θ − g + a cos θ/(A + m a²)·(m g a cos θ − m a v_x τ + A τ τ') < 0
            Variant::Printed => {
                let t = d.tau(an);
                let vx = self.v_x(an);
                let bracket = m * g * a * an.cos - m * a * vx * t.tau + big_a * t.tau * t.tau1;
                Quadratic {
                    c2: a * an.sin,
                    c1: T::int(0),
                    c0: a * an.cos / (big_a + m * a.sqr()) * bracket - g,
                }
            }
            // −N/m = −g + a θ̇² sin θ − a cos θ θ̈, θ̈ from (3.3)
            Variant::Derived => Quadratic {
                c2: a * an.sin,
                c1: T::int(0),
                c0: -g - a * an.cos * self.acceleration(v, an, T::int(0)),
            },
        };
        Constraints {
            omega: d.omega(v, an),
            omega0,
        }
    }

    /// (3.3); θ̈ does not depend on θ̇.
    fn acceleration<T: Scalar>(&self, _: Variant, an: &Angle<T>, _: T) -> T {
        let d = &self.disc;
        let (m, a, g, big_a) = (T::lift(d.m), T::lift(d.a), T::lift(d.g), T::lift(d.big_a));
        let t = d.tau(an);
        (-(m * g * a * an.cos) + m * a * self.v_x(an) * t.tau - big_a * t.tau * t.tau1)
            / (big_a + m * a.sqr())
    }

    /// (3.2) without the constant `p_φ²/2C`.
    fn energy<T: Scalar>(&self, an: &Angle<T>, w: T) -> Option<T> {
        let d = &self.disc;
        let (m, a, g, big_a) = (T::lift(d.m), T::lift(d.a), T::lift(d.g), T::lift(d.big_a));
        let half = T::int(1) / T::int(2);
        let t = d.tau(an);
        Some(
            half * (big_a + m * a.sqr()) * w.sqr()
                + m * g * a * an.sin
                + half * m * self.v_x(an).sqr()
                + half * big_a * t.tau.sqr(),
        )
    }
}
