//! The headline results of detach, each a named proof file.
//!
//! | name | file | claim |
//! |---|---|---|
//! | `atlas/<scene>/<variant>` | `atlas-<scene>-<variant>.json` | the default atlas paving: Ω, Ω₀, the four cells and their area bounds |
//! | `kappa0` | `kappa0.json` | κ₀ = √3/9 enclosed; (2.10) has no positive root above it, two simple ones below |
//! | `roots/2.9` | `roots-2.9.json` | the roots of (2.9) at κ = 0.05, α = 0.7 |
//! | `roots/2.10` | `roots-2.10.json` | the roots of (2.10) at κ = 0.1 |
//! | `roots/2.12` | `roots-2.12.json` | the stationary points of Π̃ (2.12) at the smooth-disc defaults |
//! | `critical-band` | `critical-band.json` | κ_crit(α) of (2.9) within a band on 31 α-boxes of [0, 31/32]: two roots below, none above |

use super::paving::{paving_proof, PavingStatement};
use super::roots::{build_pieces, kappa0_proof, roots_proof, RootsStatement};
use crate::number::param::{enclose_decimal, ParamSet};
use crate::number::scalar::Scalar;
use crate::pave::{pave_scene, PaveOptions};
use crate::roots::isolate::Budget;
use crate::roots::{prove_kappa0, solve_2_10, solve_2_12, solve_2_9, RealFn};
use crate::scene::{Scene, SceneId, SmoothDisc, Variant};
use inari::Interval;
use serde_json::Value;

/// The atlas's default resolution: 2⁻¹⁰ of each axis, about one pixel of the
/// default picture (`detach atlas` computes the same from its plot size).
pub const ATLAS_EPS: f64 = 1.0 / 1024.0;

/// α-boxes of the `critical-band` proof: [0, 1] in 32 parts, the last one
/// (touching α = 1, where P(0) = 0) left to the `kappa0` proof.
pub const BAND_BOXES: usize = 32;

/// Every headline result, by name, in the order `detach prove` writes them.
pub const HEADLINE: &[&str] = &[
    "atlas/viscous-disc/derived",
    "atlas/viscous-disc/printed",
    "atlas/smooth-disc/derived",
    "atlas/smooth-disc/printed",
    "atlas/ice-disc/derived",
    "atlas/ice-disc/printed",
    "kappa0",
    "roots/2.9",
    "roots/2.10",
    "roots/2.12",
    "critical-band",
];

/// The file name of a named result: `atlas/ice-disc/derived` →
/// `atlas-ice-disc-derived.json`.
pub fn file_name(name: &str) -> String {
    format!("{}.json", name.replace('/', "-"))
}

/// Builds the proof of a named headline result.
pub fn prove_named(name: &str) -> Result<Value, String> {
    let parts: Vec<&str> = name.split('/').collect();
    match parts.as_slice() {
        ["atlas", scene, variant] => {
            let id: SceneId = scene.parse()?;
            let variant = match *variant {
                "derived" => Variant::Derived,
                "printed" => Variant::Printed,
                v => return Err(format!("unknown variant `{v}` (derived, printed)")),
            };
            Ok(atlas_proof(id, variant))
        }
        ["kappa0"] => {
            let proof = prove_kappa0();
            let mu_star = crate::roots::isolate::RootEnclosure::unique(proof.mu_star.interval());
            Ok(kappa0_proof(&mu_star))
        }
        ["roots", "2.9"] => roots_2_9("0.05", "0.7"),
        ["roots", "2.10"] => roots_2_10("0.1"),
        ["critical-band"] => Ok(super::band::critical_band_proof(BAND_BOXES)),
        ["roots", "2.12"] => Ok(roots_2_12(
            &ParamSet::build(
                SceneId::SmoothDisc.name(),
                SceneId::SmoothDisc.params(),
                &[],
            )
            .expect("defaults are valid"),
        )),
        _ => Err(format!(
            "unknown result `{name}` (known: {})",
            HEADLINE.join(", ")
        )),
    }
}

/// The default atlas paving of one scene as a proof.
pub fn atlas_proof(id: SceneId, variant: Variant) -> Value {
    let (scene, params) = Scene::build(id, &[]).expect("defaults are valid");
    let opts = PaveOptions {
        eps: ATLAS_EPS,
        ..PaveOptions::default()
    };
    let paving = pave_scene(&scene, variant, opts, |_, _, _| {}).expect("default paving");
    let domain = scene.domain();
    let text = id.domain_text().map(|side| side.map(String::from));
    paving_proof(
        &PavingStatement {
            scene: &scene,
            variant,
            params: &params,
            domain: &domain,
            domain_text: text,
            title: format!(
                "Ω, Ω₀ and the four cells of the {} ({variant}), default parameters, default atlas resolution",
                id.name()
            ),
        },
        &paving,
    )
}

fn dec(name: &str, text: &str) -> Result<Interval, String> {
    enclose_decimal(name, text).map_err(|e| e.to_string())
}

const F_2_9: &str = "kappa*sin(t)^2*sin(t) - cos(t)*(alpha - cos(t))*(1 - alpha*cos(t))";

/// The roots of (2.9) for κ, α given as decimal text.
pub fn roots_2_9(kappa: &str, alpha: &str) -> Result<Value, String> {
    let (k, a) = (dec("kappa", kappa)?, dec("alpha", alpha)?);
    let sol = solve_2_9(k, a, &Budget::default()).map_err(|e| e.to_string())?;
    let f = crate::roots::equations::Eq29 { kappa: k, alpha: a };
    let pieces = build_pieces(&f, 0.0, Interval::PI.sup(), &sol.roots);
    Ok(roots_proof(
        &RootsStatement {
            title: format!("the roots of (2.9) on θ ∈ (0, π) at κ = {kappa}, α = {alpha}"),
            equation: "2.9",
            paper: "§2 (2.9): κ sin³θ = cos θ (α − cos θ)(1 − α cos θ), written f(θ) = 0",
            parameters: vec![
                ("kappa".into(), kappa.into()),
                ("alpha".into(), alpha.into()),
            ],
            definitions: vec![],
            variable: "t",
            function: F_2_9.into(),
            domain: ["0", "pi"],
        },
        &pieces,
    ))
}

const F_2_10: &str = "mu*(1 - mu)*(1 + mu) - 2*kappa";

/// The roots of (2.10) for κ given as decimal text.
pub fn roots_2_10(kappa: &str) -> Result<Value, String> {
    let k = dec("kappa", kappa)?;
    let sol = solve_2_10(k, &Budget::default()).map_err(|e| e.to_string())?;
    let f = crate::roots::equations::Eq210 { kappa: k };
    let pieces = build_pieces(&f, 0.0, f64::INFINITY, &sol.roots);
    Ok(roots_proof(
        &RootsStatement {
            title: format!("the positive roots of (2.10) at κ = {kappa}"),
            equation: "2.10",
            paper: "§2, case 2 (2.10): 2κ = μ(1 − μ)(1 + μ), μ = tg(θ/2) > 0",
            parameters: vec![("kappa".into(), kappa.into())],
            definitions: vec![],
            variable: "mu",
            function: F_2_10.into(),
            domain: ["0", "inf"],
        },
        &pieces,
    ))
}

/// `sin³θ · Π̃'(θ)` of (2.12) with the singular factors cleared:
/// `m g a cos θ sin³θ + (p_ψ − p_φ cos θ)(p_φ − p_ψ cos θ)/A`. Same zeros as
/// Π̃' on (0, π), and defined on all of [0, π].
const F_2_12: &str =
    "m*g*a*cos(t)*sin(t)^2*sin(t) + (p_psi - p_phi*cos(t))*(p_phi - p_psi*cos(t))/A";

struct ClearedSlope<'a>(&'a SmoothDisc);

impl RealFn for ClearedSlope<'_> {
    fn eval<T: Scalar>(&self, theta: T) -> T {
        let d = self.0;
        let (s, c) = theta.sin_cos();
        let (m, g, a, big_a) = (T::lift(d.m), T::lift(d.g), T::lift(d.a), T::lift(d.big_a));
        let (pf, ps) = (T::lift(d.p_phi), T::lift(d.p_psi));
        m * g * a * c * s.sqr() * s + (ps - pf * c) * (pf - ps * c) / big_a
    }
}

/// The stationary points of Π̃ (2.12) for a smooth disc.
pub fn roots_2_12(params: &ParamSet) -> Value {
    let disc = SmoothDisc::from_param_set(params);
    let sol = solve_2_12(&disc, &Budget::default());
    let pieces = build_pieces(&ClearedSlope(&disc), 0.0, Interval::PI.sup(), &sol.roots);
    let keep = ["m", "g", "a", "A", "p_phi", "p_psi"];
    roots_proof(
        &RootsStatement {
            title: "the stationary points of Π̃ (2.12) on θ ∈ (0, π), smooth disc".into(),
            equation: "2.12",
            paper: "§2 (2.12): m g a cos θ + A τ τ' = 0; multiplied by sin³θ > 0, \
                    A τ τ' sin³θ = (p_ψ − p_φ cos θ)(p_φ − p_ψ cos θ)/A",
            parameters: params
                .texts()
                .into_iter()
                .filter(|(n, _)| keep.contains(n))
                .map(|(n, t)| (n.to_string(), t))
                .collect(),
            definitions: vec![],
            variable: "t",
            function: F_2_12.into(),
            domain: ["0", "pi"],
        },
        &pieces,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figures::{plot_area_pixels, AtlasStyle};

    #[test]
    fn atlas_eps_is_the_atlas_default() {
        // `detach atlas` uses the largest power of two ≤ 1/max(plot width, height).
        let (w, h) = plot_area_pixels(&AtlasStyle::default());
        let pixel = (1.0 / w.max(h) as f64).log2().floor().exp2();
        assert_eq!(pixel, ATLAS_EPS);
    }

    #[test]
    fn every_headline_result_builds_with_its_counts() {
        for name in HEADLINE {
            let v = prove_named(name).unwrap();
            let bytes = crate::certificate::to_bytes(&v);
            let st = &v["statement"];
            match v["claim"].as_str().unwrap() {
                "paving" => {
                    let leaves = st["leaves"].as_u64().unwrap();
                    let nodes = v["evidence"]["nodes"].as_u64().unwrap();
                    // A binary tree: nodes = 2·leaves − 1.
                    assert_eq!(nodes, 2 * leaves - 1, "{name}");
                    let body = v["evidence"]["body"].as_str().unwrap().len() as f64;
                    eprintln!(
                        "{name}: {leaves} leaves, {} B, body {:.2} B/leaf",
                        bytes.len(),
                        body / leaves as f64
                    );
                    assert!(body / (leaves as f64) <= 2.0, "{name}");
                }
                "roots" => {
                    assert_eq!(st["complete"], true, "{name}: {}", st["roots"]);
                    eprintln!("{name}: {} B, roots {}", bytes.len(), st["roots"]);
                }
                _ => eprintln!("{name}: {} B, {}", bytes.len(), st["kappa0"]),
            }
            assert!(prove_named("nope").is_err());
        }
    }
}

/// What a `roots` run asks a proof of: the equation and the values it was
/// given (decimal text; `overrides` are a scene's `NAME=VALUE` parameters).
#[derive(Debug, Clone, Copy)]
pub struct RootsRequest<'a> {
    pub equation: &'a str,
    pub kappa: Option<&'a str>,
    pub alpha: Option<&'a str>,
    pub scene: Option<&'a str>,
    pub overrides: &'a [(String, String)],
}

/// The proof file of a `roots` run: (2.9) with κ and α, (2.10) with κ, or
/// (2.12) of the smooth disc or the disc on ice; an error names what is
/// missing or why no proof exists for the request.
pub fn requested_roots_proof(r: &RootsRequest) -> Result<Value, String> {
    let eq = r
        .equation
        .trim()
        .trim_start_matches('(')
        .trim_end_matches(')');
    fn need<'s>(flag: Option<&'s str>, name: &str, eq: &str) -> Result<&'s str, String> {
        flag.map(str::trim)
            .ok_or_else(|| format!("--proof for ({eq}) needs --{name}"))
    }
    match eq {
        "2.9" if r.scene.is_none() => {
            roots_2_9(need(r.kappa, "kappa", eq)?, need(r.alpha, "alpha", eq)?)
        }
        "2.10" => roots_2_10(need(r.kappa, "kappa", eq)?),
        "2.12" => {
            let id: SceneId = need(r.scene, "scene", eq)?.parse()?;
            if !matches!(id, SceneId::SmoothDisc | SceneId::IceDisc) {
                return Err("(2.12) needs --scene smooth-disc or ice-disc".into());
            }
            let (_, params) = Scene::build(id, r.overrides).map_err(|e| e.to_string())?;
            Ok(roots_2_12(&params))
        }
        _ => Err(format!(
            "proof files exist for (2.9) with --kappa/--alpha, (2.10) and (2.12); not for ({eq}){}",
            if eq == "2.9" { " with --scene" } else { "" }
        )),
    }
}
