//! One root problem as asked: an equation of the paper with its inputs
//! (κ and α as decimal text, or a paper scene with its parameters), checked
//! once on construction, solved once; a proof file is built from its roots
//! ([`crate::certificate::catalog::roots_proof_of`]).

use super::equations::{kappa_alpha, scene_function};
use super::RootsError;
use super::{solve_2_10, solve_2_12, solve_2_9, solve_3_3, Budget, EquationId, EquationRoots};
use crate::number::param::{enclose_decimal, ParamError, ParamSet};
use crate::scene::{Scene, SceneId};
use inari::Interval;
use serde::Serialize;
use std::fmt;

/// An input of a root problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    Kappa,
    Alpha,
    Scene,
    Param,
}

impl fmt::Display for Input {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(match self {
            Input::Kappa => "kappa",
            Input::Alpha => "alpha",
            Input::Scene => "scene",
            Input::Param => "param",
        })
    }
}

/// The inputs of a root problem, as given (decimal text; `params` are a
/// scene's `NAME = VALUE` overrides).
#[derive(Clone, Copy, Debug, Default)]
pub struct RootsInputs<'a> {
    pub equation: &'a str,
    pub kappa: Option<&'a str>,
    pub alpha: Option<&'a str>,
    pub scene: Option<&'a str>,
    pub params: &'a [(String, String)],
}

/// Why a root problem is refused.
#[derive(Debug, PartialEq)]
pub enum RequestError {
    UnknownEquation(String),
    /// The equation needs this input (or, for (2.9), `or` instead).
    Missing {
        equation: EquationId,
        input: Input,
        or: Option<Input>,
    },
    /// Inputs given that the equation does not take.
    NotTaken {
        equation: EquationId,
        takes: &'static [Input],
        given: &'static [Input],
    },
    /// (2.10) is (2.9) at α = 1: α is not an input.
    AlphaFor2_10,
    /// (2.9) given both κ, α and a scene.
    ValuesAndScene,
    KappaNotPositive(String),
    AlphaOutOfRange(String),
    WrongScene {
        equation: EquationId,
        needs: &'static str,
        got: String,
    },
    /// An unknown scene.
    Scene(String),
    Param(ParamError),
    Roots(RootsError),
}

impl RequestError {
    /// The message, each input named by `name` (e.g. as a command-line
    /// option); [`fmt::Display`] names them plainly (`kappa`).
    pub fn message(&self, name: impl Fn(Input) -> String) -> String {
        let list = |inputs: &[Input], sep: &str| {
            inputs
                .iter()
                .map(|&i| name(i))
                .collect::<Vec<_>>()
                .join(sep)
        };
        match self {
            RequestError::UnknownEquation(s) => {
                format!("unknown equation `{s}` (known: 2.9, 2.10, 2.12, 3.3)")
            }
            RequestError::Missing {
                equation,
                input,
                or,
            } => format!(
                "equation ({equation}) needs {}{}",
                name(*input),
                or.map(|o| format!(" (or {})", name(o))).unwrap_or_default()
            ),
            RequestError::NotTaken {
                equation,
                takes,
                given,
            } => format!(
                "equation ({equation}) takes {}, not {}",
                list(takes, " and "),
                list(given, "/")
            ),
            RequestError::AlphaFor2_10 => format!(
                "equation (2.10) is (2.9) at α = 1: drop {}",
                name(Input::Alpha)
            ),
            RequestError::ValuesAndScene => format!(
                "equation (2.9): give either {}/{} or {}, not both",
                name(Input::Kappa),
                name(Input::Alpha),
                name(Input::Scene)
            ),
            RequestError::KappaNotPositive(t) => {
                format!("κ must be positive (and at least the smallest positive double), got {t}")
            }
            RequestError::AlphaOutOfRange(t) => format!("α must lie in [-1, 1], got {t}"),
            RequestError::WrongScene {
                equation,
                needs,
                got,
            } => format!("equation ({equation}) needs scene {needs}, got {got}"),
            RequestError::Scene(e) => e.clone(),
            RequestError::Param(e) => e.to_string(),
            RequestError::Roots(e) => e.to_string(),
        }
    }
}

impl fmt::Display for RequestError {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(&self.message(|i| i.to_string()))
    }
}

impl std::error::Error for RequestError {}

impl From<ParamError> for RequestError {
    fn from(e: ParamError) -> Self {
        RequestError::Param(e)
    }
}

impl From<RootsError> for RequestError {
    fn from(e: RootsError) -> Self {
        RequestError::Roots(e)
    }
}

/// A value of the problem: its name, the text given (or the formula it
/// was derived by) and its outward-rounded enclosure.
#[derive(Clone, Debug, Serialize)]
pub struct Value {
    pub name: String,
    pub text: String,
    pub enclosure: [f64; 2],
}

impl Value {
    fn of(name: &str, text: &str, x: Interval) -> Value {
        Value {
            name: name.into(),
            text: text.into(),
            enclosure: [x.inf(), x.sup()],
        }
    }
}

/// What is solved.
#[derive(Debug)]
pub enum Problem {
    /// (2.9) at κ, α.
    KappaAlpha { kappa: Interval, alpha: Interval },
    /// (2.10) at κ.
    Kappa { kappa: Interval },
    /// (2.9) at a disc's κ and α, (2.12) of a disc, or (3.3) of the disc on
    /// ice.
    Scene { scene: Scene, params: ParamSet },
}

/// A root problem, its inputs checked and enclosed.
#[derive(Debug)]
pub struct RootsRequest {
    pub equation: EquationId,
    pub problem: Problem,
    /// The values given: κ and α as text, or the scene's parameters.
    pub parameters: Vec<Value>,
    /// κ and α of (2.9) derived from a disc.
    pub derived: Vec<Value>,
}

impl RootsRequest {
    /// Checks and encloses the inputs: κ > 0 and α ∈ [−1, 1] for (2.9) and
    /// (2.10), a scene with the equation (smooth-disc by default; ice-disc
    /// for (3.3)) and its parameters otherwise.
    pub fn new(inputs: &RootsInputs) -> Result<RootsRequest, RequestError> {
        let equation = EquationId::parse(inputs.equation)
            .ok_or_else(|| RequestError::UnknownEquation(inputs.equation.to_string()))?;
        let scene_given = inputs.scene.is_some() || !inputs.params.is_empty();
        let values_given = inputs.kappa.is_some() || inputs.alpha.is_some();
        let mut parameters = Vec::new();
        let mut derived = Vec::new();
        let mut given = |input: Input, text: Option<&str>| -> Result<Interval, RequestError> {
            let text = text
                .ok_or(RequestError::Missing {
                    equation,
                    input,
                    or: (equation == EquationId::E2_9 && input == Input::Alpha)
                        .then_some(Input::Scene),
                })?
                .trim();
            let x = enclose_decimal(&input.to_string(), text)?;
            match input {
                Input::Kappa if x.inf() <= 0.0 => {
                    return Err(RequestError::KappaNotPositive(text.into()))
                }
                Input::Alpha if !(x.inf() >= -1.0 && x.sup() <= 1.0) => {
                    return Err(RequestError::AlphaOutOfRange(text.into()))
                }
                _ => {}
            }
            parameters.push(Value::of(&input.to_string(), text, x));
            Ok(x)
        };
        let problem = match equation {
            EquationId::E2_10 => {
                if scene_given {
                    return Err(RequestError::NotTaken {
                        equation,
                        takes: &[Input::Kappa],
                        given: &[Input::Scene, Input::Param],
                    });
                }
                if inputs.alpha.is_some() {
                    return Err(RequestError::AlphaFor2_10);
                }
                Problem::Kappa {
                    kappa: given(Input::Kappa, inputs.kappa)?,
                }
            }
            EquationId::E2_9 if inputs.scene.is_some() => {
                if values_given {
                    return Err(RequestError::ValuesAndScene);
                }
                let (scene, params) = build_scene(inputs, SceneId::SmoothDisc)?;
                if !matches!(scene.id(), Some(SceneId::SmoothDisc | SceneId::IceDisc)) {
                    return Err(wrong_scene(equation, &scene));
                }
                let (k, a) = kappa_alpha(&params)?;
                derived.push(Value::of("kappa", "g A^2/(a p_M^2)", k));
                derived.push(Value::of("alpha", "p_m/p_M", a));
                parameters = scene_values(&params);
                Problem::Scene { scene, params }
            }
            EquationId::E2_9 => {
                let kappa = given(Input::Kappa, inputs.kappa)?;
                let alpha = given(Input::Alpha, inputs.alpha)?;
                Problem::KappaAlpha { kappa, alpha }
            }
            EquationId::E2_12 | EquationId::E3_3 => {
                if values_given {
                    return Err(RequestError::NotTaken {
                        equation,
                        takes: &[Input::Scene, Input::Param],
                        given: &[Input::Kappa, Input::Alpha],
                    });
                }
                let default = match equation {
                    EquationId::E2_12 => SceneId::SmoothDisc,
                    _ => SceneId::IceDisc,
                };
                let (scene, params) = build_scene(inputs, default)?;
                if scene_function(&scene, equation).is_none() {
                    return Err(wrong_scene(equation, &scene));
                }
                parameters = scene_values(&params);
                Problem::Scene { scene, params }
            }
        };
        Ok(RootsRequest {
            equation,
            problem,
            parameters,
            derived,
        })
    }

    /// The scene's name, when the problem is a scene's.
    pub fn scene_name(&self) -> Option<&'static str> {
        match &self.problem {
            Problem::Scene { scene, .. } => scene.id().map(SceneId::name),
            _ => None,
        }
    }

    /// Certified roots, within `budget`.
    pub fn solve(&self, budget: &Budget) -> Result<EquationRoots, RootsError> {
        match (&self.problem, self.equation) {
            (Problem::KappaAlpha { kappa, alpha }, _) => solve_2_9(*kappa, *alpha, budget),
            (Problem::Kappa { kappa }, _) => solve_2_10(*kappa, budget),
            (Problem::Scene { params, .. }, EquationId::E2_9) => {
                let (k, a) = kappa_alpha(params)?;
                solve_2_9(k, a, budget)
            }
            (Problem::Scene { scene, params }, eq) => {
                let f = scene_function(scene, eq).expect("checked on construction");
                Ok(match eq {
                    EquationId::E3_3 => solve_3_3(f, params, budget),
                    _ => solve_2_12(f, budget),
                })
            }
        }
    }
}

fn build_scene(inputs: &RootsInputs, default: SceneId) -> Result<(Scene, ParamSet), RequestError> {
    let id = match inputs.scene {
        Some(s) => s.parse::<SceneId>().map_err(RequestError::Scene)?,
        None => default,
    };
    Scene::build(id, inputs.params).map_err(|e| RequestError::Scene(e.to_string()))
}

fn scene_values(set: &ParamSet) -> Vec<Value> {
    set.texts()
        .into_iter()
        .zip(&set.values)
        .map(|((name, text), p)| Value::of(name, &text, p.value))
        .collect()
}

fn wrong_scene(equation: EquationId, scene: &Scene) -> RequestError {
    RequestError::WrongScene {
        equation,
        needs: match equation {
            EquationId::E3_3 => "ice-disc",
            _ => "smooth-disc or ice-disc",
        },
        got: scene.name().to_string(),
    }
}
