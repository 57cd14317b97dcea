//! §2: thin homogeneous disc on an absolutely smooth horizontal plane, (2.1)–(2.12).
//!
//! The derivation (the `derived` variant: Ω from (2.7), Ω₀ = Ω since the
//! reaction coefficient is positive) and how the printed (2.8) relates to
//! it are in `scenes/smooth-disc.toml` and `scenes/smooth-disc-printed.toml`,
//! whose regions are the texts of this scene's [`Model::formulas`].

use super::{
    symmetric, theta_range_0_pi, Angle, Constraints, Domain, Formulas, Model, Quadratic, Variant,
};
use crate::number::param::{ParamError, ParamSet, ParamSpec, Sign};
use crate::number::scalar::Scalar;
use inari::Interval;

/// Parameters shared by §2 and §3.
#[derive(Clone, Debug)]
pub struct SmoothDisc {
    pub m: Interval,
    pub a: Interval,
    pub big_a: Interval,
    pub big_c: Interval,
    pub g: Interval,
    pub p_phi: Interval,
    pub p_psi: Interval,
}

/// The parameters of §2 (also used by §3).
pub const SMOOTH_PARAMS: &[ParamSpec] = &[
    ParamSpec {
        name: "m",
        default: "1",
        sign: Sign::Positive,
        meaning: "mass",
        unit: "",
    },
    ParamSpec {
        name: "a",
        default: "1",
        sign: Sign::Positive,
        meaning: "disc radius",
        unit: "",
    },
    ParamSpec {
        name: "A",
        default: "0.25",
        sign: Sign::Positive,
        meaning: "equatorial moment of inertia",
        unit: "",
    },
    ParamSpec {
        name: "C",
        default: "0.5",
        sign: Sign::Positive,
        meaning: "axial moment of inertia",
        unit: "",
    },
    ParamSpec {
        name: "g",
        default: "9.81",
        sign: Sign::Positive,
        meaning: "gravity",
        unit: "",
    },
    ParamSpec {
        name: "p_phi",
        default: "2.5",
        sign: Sign::Any,
        meaning: "momentum integral p_φ (2.3)",
        unit: "",
    },
    ParamSpec {
        name: "p_psi",
        default: "2",
        sign: Sign::Any,
        meaning: "momentum integral p_ψ (2.3)",
        unit: "",
    },
];

/// τ, τ' of (2.7) and related θ-only quantities.
pub struct Tau<T> {
    pub tau: T,
    pub tau1: T,
}

impl SmoothDisc {
    pub fn from_param_set(p: &ParamSet) -> Self {
        SmoothDisc {
            m: p.get("m"),
            a: p.get("a"),
            big_a: p.get("A"),
            big_c: p.get("C"),
            g: p.get("g"),
            p_phi: p.get("p_phi"),
            p_psi: p.get("p_psi"),
        }
    }

    /// τ and τ' = dτ/dθ of (2.7).
    pub fn tau<T: Scalar>(&self, an: &Angle<T>) -> Tau<T> {
        let (pf, ps, big_a) = (
            T::lift(self.p_phi),
            T::lift(self.p_psi),
            T::lift(self.big_a),
        );
        Tau {
            tau: (ps - pf * an.cos) / (big_a * an.sin),
            tau1: (pf - ps * an.cos) / (big_a * an.sin.sqr()),
        }
    }

    /// Ω of (2.7)/(2.8), shared with the disc on ice.
    pub fn omega<T: Scalar>(&self, v: Variant, an: &Angle<T>) -> Quadratic<T> {
        let (a, g, big_a) = (T::lift(self.a), T::lift(self.g), T::lift(self.big_a));
        let (pf, ps) = (T::lift(self.p_phi), T::lift(self.p_psi));
        match v {
            // (2.8): θ̇² − Φ(θ) < 0
            Variant::Printed => {
                let s4 = an.sin.sqr().sqr();
                let phi = g / (a * an.sin)
                    - an.cos / (big_a.sqr() * s4) * (pf - ps * an.cos) * (ps - pf * an.cos);
                Quadratic {
                    c2: T::int(1),
                    c1: T::int(0),
                    c0: -phi,
                }
            }
            // (2.7): U = −g + a θ̇² sin θ + a τ τ' cos θ < 0
            Variant::Derived => {
                let t = self.tau(an);
                Quadratic {
                    c2: a * an.sin,
                    c1: T::int(0),
                    c0: a * t.tau * t.tau1 * an.cos - g,
                }
            }
        }
    }

    /// Ω of (2.8) (printed) or (2.7) (derived) as text, with its definitions.
    pub fn omega_formula(v: Variant) -> (Vec<(&'static str, &'static str)>, &'static str) {
        match v {
            Variant::Printed => (
                vec![(
                    "Phi",
                    "g/(a*sin(t)) - cos(t)/(A^2*(sin(t)^2)^2)*(p_phi - p_psi*cos(t))*(p_psi - p_phi*cos(t))",
                )],
                "w^2 - Phi",
            ),
            Variant::Derived => (
                vec![
                    ("tau", "(p_psi - p_phi*cos(t))/(A*sin(t))"),
                    ("tau1", "(p_phi - p_psi*cos(t))/(A*sin(t)^2)"),
                    ("U0", "a*tau*tau1*cos(t) - g"),
                ],
                "a*sin(t)*w^2 + U0",
            ),
        }
    }

    /// Π̃'(θ) of (2.12).
    pub fn reduced_potential_slope<T: Scalar>(&self, an: &Angle<T>) -> T {
        let (m, a, g, big_a) = (
            T::lift(self.m),
            T::lift(self.a),
            T::lift(self.g),
            T::lift(self.big_a),
        );
        let t = self.tau(an);
        m * g * a * an.cos + big_a * t.tau * t.tau1
    }
}

impl Model for SmoothDisc {
    const NAME: &'static str = "smooth-disc";
    const TITLE: &'static str = "§2: thin disc on a smooth plane";
    const PARAMS: &'static [ParamSpec] = SMOOTH_PARAMS;

    fn from_params(p: &ParamSet) -> Result<Self, ParamError> {
        Ok(Self::from_param_set(p))
    }

    /// θ ∈ [0, π] (the formulas are singular at sin θ = 0), θ̇ ∈ [−10, 10].
    fn domain(&self) -> Domain {
        Domain {
            theta: theta_range_0_pi(),
            theta_dot: symmetric(10.0),
        }
    }

    const DOMAIN_TEXT: [[&'static str; 2]; 2] = [["0", "pi"], ["-10", "10"]];

    /// Ω₀ = Ω: the same text twice.
    fn formulas(v: Variant) -> Formulas {
        let (definitions, omega) = Self::omega_formula(v);
        Formulas {
            definitions,
            omega,
            omega0: omega,
        }
    }

    /// Ω₀ = Ω in both variants: `N = −U/V` with `V > 0` (2.6), (2.7).
    fn omega0_is_omega(&self, _v: Variant) -> bool {
        true
    }

    fn constraints<T: Scalar>(&self, v: Variant, an: &Angle<T>) -> Constraints<T> {
        let omega = self.omega(v, an);
        Constraints {
            omega,
            omega0: omega,
        }
    }

    /// (2.5): θ̈ = (m a² sin θ cos θ θ̇² − Π̃'(θ)) / (A + m a² cos²θ).
    fn acceleration<T: Scalar>(&self, _: Variant, an: &Angle<T>, w: T) -> T {
        let (m, a, big_a) = (T::lift(self.m), T::lift(self.a), T::lift(self.big_a));
        let ma2 = m * a.sqr();
        (ma2 * an.sin * an.cos * w.sqr() - self.reduced_potential_slope(an))
            / (big_a + ma2 * an.cos.sqr())
    }

    /// (2.11): T̃ + Π̃.
    fn energy<T: Scalar>(&self, an: &Angle<T>, w: T) -> Option<T> {
        let (m, a, g, big_a) = (
            T::lift(self.m),
            T::lift(self.a),
            T::lift(self.g),
            T::lift(self.big_a),
        );
        let half = T::int(1) / T::int(2);
        let t = self.tau(an);
        Some(
            half * (big_a + m * a.sqr() * an.cos.sqr()) * w.sqr()
                + m * g * a * an.sin
                + half * big_a * t.tau.sqr(),
        )
    }
}
