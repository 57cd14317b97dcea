//! Example 1: heavy non-uniform disc on a plane with viscous friction, (1.3)–(1.11).
//!
//! The derivation (the `derived` variant) and where the printed (1.7),
//! (1.10), (1.11) differ from it are in `scenes/viscous-disc.toml` and
//! `scenes/viscous-disc-printed.toml`, whose regions are the texts of
//! this scene's [`Model::formulas`]. The sets differ; see the witnesses in
//! `tests/it/findings.rs`.

use super::{symmetric, Angle, Constraints, Domain, Formulas, Model, Quadratic, Variant, PI};
use crate::number::param::{ParamError, ParamSet, ParamSpec, Sign};
use crate::number::scalar::Scalar;
use inari::Interval;

#[derive(Clone, Debug)]
pub struct ViscousDisc {
    pub a: Interval,
    pub b: Interval,
    pub m: Interval,
    pub c: Interval,
    pub mu: Interval,
    pub g: Interval,
}

impl ViscousDisc {
    /// `(h, h', h'')` of (1.3).
    fn h<T: Scalar>(&self, an: &Angle<T>) -> (T, T, T) {
        let (a, b) = (T::lift(self.a), T::lift(self.b));
        (a + b * an.sin, b * an.cos, -(b * an.sin))
    }
}

impl Model for ViscousDisc {
    const NAME: &'static str = "viscous-disc";
    const TITLE: &'static str = "Example 1: non-uniform disc, viscous friction";
    const PARAMS: &'static [ParamSpec] = &[
        ParamSpec {
            name: "a",
            default: "1",
            sign: Sign::Positive,
            meaning: "disc radius",
            unit: "",
        },
        ParamSpec {
            name: "b",
            default: "0.5",
            sign: Sign::NonNegative,
            meaning: "offset |GC| of the centre of mass (b < a)",
            unit: "",
        },
        ParamSpec {
            name: "m",
            default: "1",
            sign: Sign::Positive,
            meaning: "mass",
            unit: "",
        },
        ParamSpec {
            name: "C",
            default: "0.3",
            sign: Sign::Positive,
            meaning: "moment of inertia about G",
            unit: "",
        },
        ParamSpec {
            name: "mu",
            default: "0.8",
            sign: Sign::NonNegative,
            meaning: "viscous friction coefficient",
            unit: "",
        },
        ParamSpec {
            name: "g",
            default: "9.81",
            sign: Sign::Positive,
            meaning: "gravity",
            unit: "",
        },
    ];

    fn from_params(p: &ParamSet) -> Result<Self, ParamError> {
        let s = ViscousDisc {
            a: p.get("a"),
            b: p.get("b"),
            m: p.get("m"),
            c: p.get("C"),
            mu: p.get("mu"),
            g: p.get("g"),
        };
        if !super::positive_gap(s.b, s.a) {
            return Err(ParamError::Invalid {
                name: "b".into(),
                reason: "the centre of mass must lie inside the disc: b < a".into(),
            });
        }
        Ok(s)
    }

    /// θ ∈ [−π, π], θ̇ ∈ [−10, 10].
    fn domain(&self) -> Domain {
        Domain {
            theta: [-PI, PI],
            theta_dot: symmetric(10.0),
        }
    }

    fn constraints<T: Scalar>(&self, v: Variant, an: &Angle<T>) -> Constraints<T> {
        let (h, h1, h2) = self.h(an);
        let (m, c, mu, g) = (
            T::lift(self.m),
            T::lift(self.c),
            T::lift(self.mu),
            T::lift(self.g),
        );
        let friction = mu * h.sqr() * h1;
        let zero = T::int(0);
        match v {
            Variant::Printed => {
                // (1.10), (1.11)
                let c2 = -(T::int(2) * c * h2);
                let c0 = -(g * (T::int(2) * c + m * h1.sqr()));
                Constraints {
                    omega: Quadratic { c2, c1: zero, c0 },
                    omega0: Quadratic {
                        c2,
                        c1: friction,
                        c0,
                    },
                }
            }
            Variant::Derived => Constraints {
                // free-flight Λ̈ = −g − h''θ̇²
                omega: Quadratic {
                    c2: -h2,
                    c1: zero,
                    c0: -g,
                },
                // −N(C + m h'²)/m = μh²h'θ̇ − C g − C h''θ̇²
                omega0: Quadratic {
                    c2: -(c * h2),
                    c1: friction,
                    c0: -(c * g),
                },
            },
        }
    }

    const DOMAIN_TEXT: [[&'static str; 2]; 2] = [["-pi", "pi"], ["-10", "10"]];

    fn formulas(v: Variant) -> Formulas {
        let definitions = vec![
            ("h", "a + b*sin(t)"),
            ("h1", "b*cos(t)"),
            ("h2", "-(b*sin(t))"),
        ];
        match v {
            Variant::Printed => Formulas {
                definitions,
                omega: "-(2*C*h2)*w^2 - g*(2*C + m*h1^2)",
                omega0: "-(2*C*h2)*w^2 + mu*h^2*h1*w - g*(2*C + m*h1^2)",
            },
            Variant::Derived => Formulas {
                definitions,
                omega: "-h2*w^2 - g",
                omega0: "-(C*h2)*w^2 + mu*h^2*h1*w - C*g",
            },
        }
    }

    fn acceleration<T: Scalar>(&self, v: Variant, an: &Angle<T>, w: T) -> T {
        let (h, h1, h2) = self.h(an);
        let (m, c, mu, g) = (
            T::lift(self.m),
            T::lift(self.c),
            T::lift(self.mu),
            T::lift(self.g),
        );
        let rhs = -(m * g * h1) - mu * h.sqr() * w;
        let inertia = c + m * h1.sqr();
        match v {
            // (1.7) as printed: 2(C + m h'²)θ̈ + 2 m h' h'' θ̇² = −m g h' − μ h² θ̇
            Variant::Printed => (rhs - T::int(2) * m * h1 * h2 * w.sqr()) / (T::int(2) * inertia),
            Variant::Derived => (rhs - m * h1 * h2 * w.sqr()) / inertia,
        }
    }

    /// Dissipative: no conserved energy; the portrait draws trajectories.
    fn energy<T: Scalar>(&self, _: &Angle<T>, _: T) -> Option<T> {
        None
    }
}
