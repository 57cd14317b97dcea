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
//! | `trajectory/painleve-rod` | `trajectory-painleve-rod.json` | the rod at μ = 0.5 from (θ, θ̇) = (0.6, 2): its first event, the contact cell left when U = 0, time and state enclosed |

use super::paving::{paving_proof, PavingStatement};
use super::roots::{build_pieces, kappa0_proof, roots_proof, RootsStatement};
use super::statement::in_proof_names;
use crate::pave::{pave_scene, PaveOptions};
use crate::roots::equations::{eq_2_10, eq_2_9, scene_function, TEXT_2_10, TEXT_2_9};
use crate::roots::isolate::Budget;
use crate::roots::request::Problem;
use crate::roots::{prove_kappa0, EquationId, EquationRoots, RootsInputs, RootsRequest};
use crate::scene::{Scene, SceneId, Variant};
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
    "trajectory/painleve-rod",
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
        ["roots", "2.12"] => solved_proof(&RootsInputs {
            equation: "2.12",
            scene: Some(SceneId::SmoothDisc.name()),
            ..RootsInputs::default()
        }),
        ["trajectory", "painleve-rod"] => rod_trajectory(),
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
    let text = scene.domain_text();
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

/// The rod at μ = 0.5 from (0.6, 2) to its first event (within 1 s).
fn rod_trajectory() -> Result<Value, String> {
    use crate::motion::{FlowRequest, Motion, Until};
    let (scene, _) = Scene::by_name("painleve-rod", &[("mu".into(), "0.5".into())])
        .map_err(|e| e.to_string())?;
    let file = scene.reading(Variant::Derived);
    let request = FlowRequest::parse("0.6", "2", "1").map_err(|e| e.to_string())?;
    let motion = Motion::new(file, &Until::CELL_OR_DOMAIN).map_err(|e| e.to_string())?;
    let tube = motion
        .run(request.start, request.t_end, &request.settings)
        .map_err(|e| e.to_string())?;
    super::trajectory::checked_trajectory_proof(file, &motion, &tube, "1")
        .map_err(|e| e.to_string())
}

/// The proof of a root problem, solved within the default budget.
fn solved_proof(inputs: &RootsInputs) -> Result<Value, String> {
    let request = RootsRequest::new(inputs).map_err(|e| e.to_string())?;
    let roots = request
        .solve(&Budget::default())
        .map_err(|e| e.to_string())?;
    roots_proof_of(&request, &roots)
}

/// The roots of (2.9) for κ, α given as decimal text.
pub fn roots_2_9(kappa: &str, alpha: &str) -> Result<Value, String> {
    solved_proof(&RootsInputs {
        equation: "2.9",
        kappa: Some(kappa),
        alpha: Some(alpha),
        ..RootsInputs::default()
    })
}

/// The roots of (2.10) for κ given as decimal text.
pub fn roots_2_10(kappa: &str) -> Result<Value, String> {
    solved_proof(&RootsInputs {
        equation: "2.10",
        kappa: Some(kappa),
        ..RootsInputs::default()
    })
}

/// The proof file of a solved root problem, its evidence built from the
/// roots found: (2.9) at κ and α given, (2.10), or (2.12) of the smooth
/// disc or the disc on ice; an error says why no proof exists for another.
pub fn roots_proof_of(request: &RootsRequest, roots: &EquationRoots) -> Result<Value, String> {
    let given = |name: &str| {
        request
            .parameters
            .iter()
            .find(|p| p.name == name)
            .map(|p| p.text.clone())
            .expect("a checked request")
    };
    let pi = Interval::PI.sup();
    match (&request.problem, request.equation) {
        (Problem::KappaAlpha { kappa, alpha }, _) => {
            let (kt, at) = (given("kappa"), given("alpha"));
            let f = eq_2_9(*kappa, *alpha);
            Ok(roots_proof(
                &RootsStatement {
                    title: format!("the roots of (2.9) on θ ∈ (0, π) at κ = {kt}, α = {at}"),
                    equation: "2.9",
                    paper: "§2 (2.9): κ sin³θ = cos θ (α − cos θ)(1 − α cos θ), written f(θ) = 0",
                    parameters: vec![("kappa".into(), kt), ("alpha".into(), at)],
                    definitions: vec![],
                    variable: "t",
                    function: in_proof_names(TEXT_2_9),
                    domain: ["0", "pi"],
                },
                &build_pieces(&f, 0.0, pi, &roots.roots),
            ))
        }
        (Problem::Kappa { kappa }, _) => {
            let kt = given("kappa");
            let f = eq_2_10(*kappa);
            Ok(roots_proof(
                &RootsStatement {
                    title: format!("the positive roots of (2.10) at κ = {kt}"),
                    equation: "2.10",
                    paper: "§2, case 2 (2.10): 2κ = μ(1 − μ)(1 + μ), μ = tg(θ/2) > 0",
                    parameters: vec![("kappa".into(), kt)],
                    definitions: vec![],
                    variable: "mu",
                    function: TEXT_2_10.into(),
                    domain: ["0", "inf"],
                },
                &build_pieces(&f, 0.0, f64::INFINITY, &roots.roots),
            ))
        }
        (Problem::Scene { scene, params }, EquationId::E2_12) => {
            let f = scene_function(scene, EquationId::E2_12).expect("a checked request");
            let keep = ["m", "g", "a", "A", "p_phi", "p_psi"];
            Ok(roots_proof(
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
                    function: in_proof_names(&f.text),
                    domain: ["0", "pi"],
                },
                &build_pieces(f, 0.0, pi, &roots.roots),
            ))
        }
        (_, eq) => Err(format!(
            "proof files exist for (2.9) at given κ and α, (2.10) and (2.12); not for ({eq}){}",
            if eq == EquationId::E2_9 {
                " of a scene"
            } else {
                ""
            }
        )),
    }
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
