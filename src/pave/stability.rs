//! Where each paving method fails: stress cases (a scene, parameters, a
//! window, a region and the feature a paving should resolve there), every
//! method run on each, and every method over each paper scene's domain.

use super::{run_method, Label, Method, MethodRun, PaveError, PaveOptions, Paving, StopReason};
use crate::number::param::ParamError;
use crate::scene::{Cell, Domain, Scene, SceneId, Variant, PI};
use inari::const_interval;
use serde::Serialize;

/// What a case is about, and how a paving is scored on it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Feature {
    /// Leaves touching θ = 0 are undefined, every other leaf is decided.
    SingularLine,
    /// A leaf proved in the region meets θ = π/3 (the neck of Ω).
    Neck,
    /// A leaf proved out of the region reaches within `1/200` of the turning
    /// point θ* of its boundary.
    TurningPoint(f64),
    /// Proved-in and proved-out leaves both exist and the undecided area is
    /// at most 1% of the window.
    Resolved,
}

impl Feature {
    pub fn describe(self) -> String {
        match self {
            Feature::SingularLine => {
                "every leaf touching θ = 0 undefined, every other leaf decided".into()
            }
            Feature::Neck => "a leaf proved in Ω meets θ = π/3 (the neck is certified)".into(),
            Feature::TurningPoint(t) => {
                format!("a leaf proved out of Ω₀ within 0.005 of the turning point θ* ≈ {t:.6}")
            }
            Feature::Resolved => {
                "proved-in and proved-out leaves, undecided area ≤ 1% of the window".into()
            }
        }
    }

    /// Whether the paving `p` resolves the feature for `region`, whose
    /// undecided area is `undecided`.
    pub fn decided(self, p: &Paving, region: Cell, undecided: f64) -> bool {
        let label = |l: &super::Leaf| l.labels[region.index()];
        match self {
            Feature::SingularLine => p.leaves.iter().all(|l| {
                if l.bx.theta[0] <= 0.0 {
                    label(l) == Label::Undefined
                } else {
                    label(l).is_decided()
                }
            }),
            Feature::Neck => {
                let third = PI / const_interval!(3.0, 3.0);
                p.leaves.iter().any(|l| {
                    label(l) == Label::ProvedIn
                        && l.bx.theta[0] <= third.sup()
                        && l.bx.theta[1] >= third.inf()
                })
            }
            Feature::TurningPoint(t) => p.leaves.iter().any(|l| {
                label(l) == Label::ProvedOut
                    && l.bx.theta[0] <= t + 0.005
                    && l.bx.theta[1] >= t - 0.005
            }),
            Feature::Resolved => {
                let r = p.root;
                let area = (r.theta[1] - r.theta[0]) * (r.theta_dot[1] - r.theta_dot[0]);
                let has = |x: Label| p.leaves.iter().any(|l| label(l) == x);
                has(Label::ProvedIn) && has(Label::ProvedOut) && undecided <= 0.01 * area
            }
        }
    }
}

/// One stress case: a paper scene (derived) with parameters and a window, the
/// region (Ω or Ω₀) refined, and the feature to resolve.
pub struct StressCase {
    pub key: String,
    pub scene: Scene,
    /// The parameters overridden, as decimal text.
    pub params: Vec<(String, String)>,
    /// The window `[θ, θ̇]` as decimal text (the scene's domain if none).
    pub window: [[String; 2]; 2],
    pub domain: Domain,
    pub region: Cell,
    pub feature: Feature,
    pub why: String,
}

impl StressCase {
    /// The case as `stability.json` lists it.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "case": self.key,
            "scene": self.scene.name(),
            "params": self.params,
            "window": {"theta": self.window[0], "theta_dot": self.window[1]},
            "region": self.region.name(),
            "feature": self.feature.describe(),
            "why": self.why,
        })
    }
}

/// κ₀ = √3/9 of (2.10), only to place the pinch cases' parameters.
const KAPPA0: f64 = 0.19245008972987526;

/// θ* where the discriminant of Ω₀ (derived) of the viscous disc vanishes,
/// located in plain `f64` by bisection on `[-0.6, -0.1]` (only to place the
/// window and score the case; nothing is certified from it).
fn viscous_turning_point(a: f64, b: f64, c: f64, mu: f64, g: f64) -> f64 {
    let d = |t: f64| {
        let (s, co) = t.sin_cos();
        let h = a + b * s;
        (mu * h * h * b * co).powi(2) + 4.0 * c * c * b * g * s
    };
    let (mut lo, mut hi) = (-0.6, -0.1);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if d(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// One case, its scene built and its window checked.
fn case(
    key: String,
    id: SceneId,
    params: Vec<(&str, String)>,
    window: Option<[[&str; 2]; 2]>,
    region: Cell,
    feature: Feature,
    why: String,
) -> Result<StressCase, ParamError> {
    let params: Vec<(String, String)> = params
        .into_iter()
        .map(|(n, v)| (n.to_string(), v))
        .collect();
    let (scene, _) = Scene::build(id, &params).map_err(|e| ParamError::Invalid {
        name: id.name().into(),
        reason: e.message,
    })?;
    let full = scene.domain();
    let (domain, window) = match window {
        Some(w) => (
            full.window(Some(w[0]), Some(w[1]))?,
            w.map(|s| s.map(str::to_string)),
        ),
        None => (full, scene.domain_text()),
    };
    Ok(StressCase {
        key,
        scene,
        params,
        window,
        domain,
        region,
        feature,
        why,
    })
}

/// The stress cases: a singular line, a pinch approaching κ₀ (k = 2, 4, 6),
/// a vertical tangent, dominant friction, the disc on ice at large |c₀|,
/// and tiny coefficients.
pub fn stress_cases() -> Result<Vec<StressCase>, ParamError> {
    let mut out = vec![case(
        "sin0".into(),
        SceneId::SmoothDisc,
        vec![],
        Some([["0", "0.05"], ["-10", "10"]]),
        Cell::Omega,
        Feature::SingularLine,
        "boxes touching sin θ = 0, where τ, τ' and Φ are undefined".into(),
    )?];
    let (g, big_a, a) = (9.81f64, 0.25f64, 1.0f64);
    for k in [2, 4, 6] {
        let kappa = KAPPA0 * (1.0 + 10f64.powi(-k));
        let p = format!("{:.16}", (g * big_a * big_a / (a * kappa)).sqrt());
        let pv: f64 = p.parse().expect("formatted number");
        let rel = g * big_a * big_a / (a * pv * pv) / KAPPA0 - 1.0;
        out.push(case(
            format!("pinch k={k}"),
            SceneId::SmoothDisc,
            vec![
                ("g", "9.81".into()),
                ("A", "0.25".into()),
                ("a", "1".into()),
                ("p_phi", p.clone()),
                ("p_psi", p),
            ],
            Some([["0.9", "1.2"], ["-0.5", "0.5"]]),
            Cell::Omega,
            Feature::Neck,
            format!(
                "α = 1, κ = κ₀(1 + {rel:.3e}): the two components of Ω joined by a neck at θ = π/3"
            ),
        )?);
    }
    let turn = viscous_turning_point(1.0, 0.5, 0.3, 2.0, 9.81);
    out.push(case(
        "vertical tangent".into(),
        SceneId::ViscousDisc,
        vec![("mu", "2".into())],
        Some([["-0.4", "-0.2"], ["7", "9.5"]]),
        Cell::Omega0,
        Feature::TurningPoint(turn),
        format!(
            "μ = 2: the discriminant of Ω₀ vanishes at θ* ≈ {turn:.4} (sin θ* < 0, c₂ < 0) \
             where its boundary turns back, vertical, at θ̇* = √(g/(b|sin θ*|)) ≈ {:.3}; \
             at the default μ = 0.8 that point lies outside θ̇ ∈ [−10, 10]",
            (9.81 / (0.5 * turn.sin().abs())).sqrt()
        ),
    )?);
    for mu in ["10", "100"] {
        out.push(case(
            format!("omega0 mu={mu}"),
            SceneId::ViscousDisc,
            vec![("mu", mu.into())],
            None,
            Cell::Omega0,
            Feature::Resolved,
            format!("Ω₀ of the viscous disc at μ = {mu}: the friction term dominates"),
        )?);
    }
    for c0 in ["50", "-50"] {
        out.push(case(
            format!("ice c0={c0}"),
            SceneId::IceDisc,
            vec![("c0", c0.into())],
            None,
            Cell::Omega0,
            Feature::Resolved,
            format!("Ω₀ of the disc on ice at c₀ = {c0}"),
        )?);
    }
    out.push(case(
        "tiny C".into(),
        SceneId::ViscousDisc,
        vec![("C", "1e-6".into())],
        None,
        Cell::Omega0,
        Feature::Resolved,
        "Ω₀ of the viscous disc at C = 10⁻⁶: every coefficient but the friction term tiny".into(),
    )?);
    Ok(out)
}

/// One method on one stress case.
#[derive(Clone, Debug, Serialize)]
pub struct StressRun {
    pub case: String,
    pub method: &'static str,
    pub region: &'static str,
    pub undecided_area: f64,
    /// Sum of the areas of leaves undefined for the region (rounded to
    /// nearest; part of the undecided area).
    pub undefined_area: f64,
    pub leaves: usize,
    pub box_evaluations: u64,
    pub time_s: f64,
    pub stop: StopReason,
    pub feature_decided: bool,
}

/// Sum, rounded to nearest, of the areas of the leaves undefined for
/// `region`: a figure for the table, not a bound.
fn undefined_area(p: &Paving, region: Cell) -> f64 {
    p.leaves
        .iter()
        .filter(|l| l.labels[region.index()] == Label::Undefined)
        .map(|l| (l.bx.theta[1] - l.bx.theta[0]) * (l.bx.theta_dot[1] - l.bx.theta_dot[0]))
        .fold(0.0, |a, x| a + x)
}

/// Every method on every case, in the order of `cases` and [`Method::ALL`].
pub fn run_stress_cases(
    cases: &[StressCase],
    opts: PaveOptions,
) -> Result<Vec<StressRun>, PaveError> {
    let mut rows = Vec::new();
    for c in cases {
        for m in Method::ALL {
            let region = c.region.index();
            let (run, paving) =
                run_method(&c.scene, Variant::Derived, &c.domain, Some(region), m, opts)?;
            rows.push(StressRun {
                case: c.key.clone(),
                method: m.name(),
                region: c.region.name(),
                undecided_area: run.undecided_area,
                undefined_area: undefined_area(&paving, c.region),
                leaves: run.leaves,
                box_evaluations: run.box_evaluations,
                time_s: run.seconds,
                stop: run.stop,
                feature_decided: c.feature.decided(&paving, c.region, run.undecided_area),
            });
        }
    }
    Ok(rows)
}

/// Every method over one paper scene's whole domain (derived, defaults,
/// all constraints refined), in the order of [`Method::ALL`].
pub struct SceneMap {
    pub id: SceneId,
    pub runs: Vec<(MethodRun, Paving)>,
    /// Per run, certified upper bounds on the undecided area of Ω and Ω₀
    /// (outer − inner, rounded up).
    pub undecided: Vec<[f64; 2]>,
}

/// The maps of every paper scene.
pub fn method_maps(opts: PaveOptions) -> Result<Vec<SceneMap>, PaveError> {
    SceneId::ALL
        .iter()
        .map(|&id| {
            let scene = Scene::default_of(id);
            let domain = scene.domain();
            let runs = Method::ALL
                .iter()
                .map(|&m| run_method(&scene, Variant::Derived, &domain, None, m, opts))
                .collect::<Result<Vec<_>, _>>()?;
            let uncovered = domain.uncovered_area_sup();
            let undecided = runs
                .iter()
                .map(|(_, p)| {
                    [Cell::Omega, Cell::Omega0]
                        .map(|c| p.area_bounds(&c.spec(), uncovered).undecided_area())
                })
                .collect();
            Ok(SceneMap {
                id,
                runs,
                undecided,
            })
        })
        .collect()
}
