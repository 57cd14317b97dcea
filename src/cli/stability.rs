//! `detach stability`: where each paving method fails. A map per scene of
//! where the undecided area concentrates for every method, and a table of
//! every method on stress cases (what each decides, at what cost, where it
//! stalls).

use super::machine;
use super::{CliError, CliResult};
use detach::certificate::numbers::{decimal, Round};
use detach::figures::stability::{draw_stability_map, StabilityPanel};
use detach::pave::area::Cell;
use detach::pave::{run_method, Label, Method, PaveOptions, Paving, StopReason};
use detach::scene::{Domain, Scene, SceneId, Variant, PI};
use serde::Serialize;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct StabilityArgs {
    /// Output directory (stability.json, stability-<scene>.svg/png).
    #[arg(long, default_value = "out/stability")]
    pub out: PathBuf,
    /// Resolution of every paving (relative to its window).
    #[arg(long, default_value_t = 1.0 / 256.0, allow_negative_numbers = true)]
    pub eps: f64,
    /// Most leaves per paving.
    #[arg(long, default_value_t = 4_000_000, value_parser = detach::number::param::parse_count)]
    pub max_boxes: usize,
    /// Print the JSON document instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// What a case is about, and how a paving is scored on it.
#[derive(Clone, Copy, Debug)]
enum Feature {
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
    fn describe(self) -> String {
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

    fn decided(self, p: &Paving, region: usize, undecided: f64) -> bool {
        let label = |l: &detach::pave::Leaf| l.labels[region];
        match self {
            Feature::SingularLine => p.leaves.iter().all(|l| {
                if l.bx.theta[0] <= 0.0 {
                    label(l) == Label::Undefined
                } else {
                    label(l).is_decided()
                }
            }),
            Feature::Neck => {
                let third = PI / inari::const_interval!(3.0, 3.0);
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

struct Case {
    key: String,
    scene: Scene,
    params: Vec<(String, String)>,
    window: [[String; 2]; 2],
    domain: Domain,
    /// 0 = Ω, 1 = Ω₀.
    region: usize,
    feature: Feature,
    why: String,
}

/// Names of the regions a case can ask about.
const REGIONS: [&str; 2] = ["omega", "omega0"];

/// κ₀ = √3/9 of (2.10).
const KAPPA0: f64 = 0.19245008972987526;

/// θ* where the discriminant of Ω₀ (derived) of the viscous disc vanishes,
/// located in plain `f64` by bisection on `[lo, hi]` (only to place the
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

fn cases() -> Result<Vec<Case>, CliError> {
    let mut out = Vec::new();
    let mut add = |key: String,
                   id: SceneId,
                   params: Vec<(&str, String)>,
                   window: Option<[[&str; 2]; 2]>,
                   region: usize,
                   feature: Feature,
                   why: String|
     -> Result<(), CliError> {
        let params: Vec<(String, String)> = params
            .into_iter()
            .map(|(n, v)| (n.to_string(), v))
            .collect();
        let (scene, _) = Scene::build(id, &params).map_err(CliError::usage)?;
        let full = scene.domain();
        let (domain, window) = match window {
            Some(w) => (
                full.window(Some(w[0]), Some(w[1]))
                    .map_err(CliError::usage)?,
                w.map(|s| s.map(str::to_string)),
            ),
            None => (full, id.domain_text().map(|s| s.map(str::to_string))),
        };
        out.push(Case {
            key,
            scene,
            params,
            window,
            domain,
            region,
            feature,
            why,
        });
        Ok(())
    };
    add(
        "sin0".into(),
        SceneId::SmoothDisc,
        vec![],
        Some([["0", "0.05"], ["-10", "10"]]),
        0,
        Feature::SingularLine,
        "boxes touching sin θ = 0, where τ, τ' and Φ are undefined".into(),
    )?;
    let (g, big_a, a) = (9.81f64, 0.25f64, 1.0f64);
    for k in [2, 4, 6] {
        let kappa = KAPPA0 * (1.0 + 10f64.powi(-k));
        let p = format!("{:.16}", (g * big_a * big_a / (a * kappa)).sqrt());
        let pv: f64 = p.parse().expect("formatted number");
        let rel = g * big_a * big_a / (a * pv * pv) / KAPPA0 - 1.0;
        add(
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
            0,
            Feature::Neck,
            format!(
                "α = 1, κ = κ₀(1 + {rel:.3e}): the two components of Ω joined by a neck at θ = π/3"
            ),
        )?;
    }
    let turn = viscous_turning_point(1.0, 0.5, 0.3, 2.0, 9.81);
    add(
        "vertical tangent".into(),
        SceneId::ViscousDisc,
        vec![("mu", "2".into())],
        Some([["-0.4", "-0.2"], ["7", "9.5"]]),
        1,
        Feature::TurningPoint(turn),
        format!(
            "μ = 2: the discriminant of Ω₀ vanishes at θ* ≈ {turn:.4} (sin θ* < 0, c₂ < 0) \
             where its boundary turns back, vertical, at θ̇* = √(g/(b|sin θ*|)) ≈ {:.3}; \
             at the default μ = 0.8 that point lies outside θ̇ ∈ [−10, 10]",
            (9.81 / (0.5 * turn.sin().abs())).sqrt()
        ),
    )?;
    for mu in ["10", "100"] {
        add(
            format!("omega0 mu={mu}"),
            SceneId::ViscousDisc,
            vec![("mu", mu.into())],
            None,
            1,
            Feature::Resolved,
            format!("Ω₀ of the viscous disc at μ = {mu}: the friction term dominates"),
        )?;
    }
    for c0 in ["50", "-50"] {
        add(
            format!("ice c0={c0}"),
            SceneId::IceDisc,
            vec![("c0", c0.into())],
            None,
            1,
            Feature::Resolved,
            format!("Ω₀ of the disc on ice at c₀ = {c0}"),
        )?;
    }
    add(
        "tiny C".into(),
        SceneId::ViscousDisc,
        vec![("C", "1e-6".into())],
        None,
        1,
        Feature::Resolved,
        "Ω₀ of the viscous disc at C = 10⁻⁶: every coefficient but the friction term tiny".into(),
    )?;
    Ok(out)
}

#[derive(Serialize)]
struct Row {
    case: String,
    method: &'static str,
    region: &'static str,
    undecided_area: f64,
    /// Sum of the areas of leaves undefined for the region (rounded to
    /// nearest; part of the undecided area).
    undefined_area: f64,
    leaves: usize,
    box_evaluations: u64,
    time_s: f64,
    stop: StopReason,
    feature_decided: bool,
}

#[derive(Serialize)]
struct MapRun {
    scene: &'static str,
    method: &'static str,
    undecided_area: f64,
    leaves: usize,
    box_evaluations: u64,
    time_s: f64,
    stop: StopReason,
}

fn undefined_area(p: &Paving, region: usize) -> f64 {
    p.leaves
        .iter()
        .filter(|l| l.labels[region] == Label::Undefined)
        .map(|l| (l.bx.theta[1] - l.bx.theta[0]) * (l.bx.theta_dot[1] - l.bx.theta_dot[0]))
        .fold(0.0, |a, x| a + x)
}

pub fn run_stability(args: &StabilityArgs) -> CliResult {
    if !(args.eps.is_finite() && args.eps > 0.0 && args.eps <= 1.0) {
        return Err(CliError::usage(format!(
            "--eps must be a finite number in (0, 1], got {}",
            args.eps
        )));
    }
    if args.max_boxes == 0 {
        return Err(CliError::usage("--max-boxes must be at least 1"));
    }
    let opts = PaveOptions {
        eps: args.eps,
        max_boxes: args.max_boxes,
    };
    let cases = cases()?;
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::runtime(format!("cannot create {}: {e}", args.out.display())))?;
    let machine = machine();

    // Maps: every scene (derived, defaults) over its whole domain.
    let mut maps = Vec::new();
    let mut files = Vec::new();
    for id in SceneId::ALL {
        let scene = Scene::default_of(id);
        let domain = scene.domain();
        let mut runs = Vec::new();
        for m in Method::ALL {
            let (run, paving) = run_method(&scene, Variant::Derived, &domain, None, m, opts)
                .map_err(CliError::usage)?;
            runs.push((run, paving));
        }
        let uncovered = domain.uncovered_area_sup();
        let panels: Vec<StabilityPanel> = runs
            .iter()
            .map(|(r, p)| {
                // Certified upper bounds (outer − inner, rounded up), printed
                // rounded up.
                let up = |cell: Cell| {
                    let a = p.area_bounds(&cell.spec(), uncovered).undecided_area();
                    decimal(a, 3, Round::Up)
                };
                StabilityPanel {
                    title: r.method.name().to_string(),
                    notes: vec![
                        format!(
                            "undecided area ≤ {} in Ω, ≤ {} in Ω_{{0}}",
                            up(Cell::Omega),
                            up(Cell::Omega0)
                        ),
                        format!("{} leaves, {:.3} s, {}", r.leaves, r.seconds, r.stop),
                    ],
                    paving: p,
                }
            })
            .collect();
        let svg = args.out.join(format!("stability-{}.svg", id.name()));
        let png = args.out.join(format!("stability-{}.png", id.name()));
        let title = format!(
            "Where each method stalls: {} (derived, defaults, Ω and Ω_{{0}} refined), eps = {}",
            id.name(),
            args.eps
        );
        draw_stability_map(&panels, &title, &svg, &png)
            .map_err(|e| CliError::runtime(format!("drawing {}: {e}", svg.display())))?;
        files.push(svg);
        files.push(png);
        for (r, _) in &runs {
            maps.push(MapRun {
                scene: id.name(),
                method: r.method.name(),
                undecided_area: r.undecided_area,
                leaves: r.leaves,
                box_evaluations: r.box_evaluations,
                time_s: r.seconds,
                stop: r.stop,
            });
        }
    }

    // Stress table.
    let mut rows = Vec::new();
    for c in &cases {
        for m in Method::ALL {
            let (run, paving) = run_method(
                &c.scene,
                Variant::Derived,
                &c.domain,
                Some(c.region),
                m,
                opts,
            )
            .map_err(CliError::usage)?;
            rows.push(Row {
                case: c.key.clone(),
                method: m.name(),
                region: REGIONS[c.region],
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

    let doc = serde_json::json!({
        "version": 1,
        "detach": detach::provenance(),
        "machine": machine,
        "parameters": {
            "eps": args.eps,
            "max_boxes": args.max_boxes,
            "variant": "derived",
            "note": "time_s is the paving call alone, one run",
        },
        "cases": cases.iter().map(|c| serde_json::json!({
            "case": c.key,
            "scene": c.scene.name(),
            "params": c.params,
            "window": {"theta": c.window[0], "theta_dot": c.window[1]},
            "region": REGIONS[c.region],
            "feature": c.feature.describe(),
            "why": c.why,
        })).collect::<Vec<_>>(),
        "runs": rows,
        "maps": maps,
    });
    let json = args.out.join("stability.json");
    let text = serde_json::to_string_pretty(&doc).expect("serialisable");
    detach::files::write_atomic(&json, text.as_bytes())
        .map_err(|e| CliError::runtime(format!("cannot write {}: {e}", json.display())))?;
    if args.json {
        outln!("{text}");
        return Ok(());
    }
    outln!(
        "stress cases at eps = {} (derived; load {})",
        args.eps,
        doc["machine"]["loadavg"].as_str().unwrap_or("?")
    );
    outln!(
        "{:<17} {:<6} {:<9} {:>11} {:>11} {:>8} {:>10} {:>8} {:<22} {}",
        "case",
        "region",
        "method",
        "undecided",
        "undefined",
        "leaves",
        "box evals",
        "time (s)",
        "stop",
        "feature"
    );
    for r in &rows {
        outln!(
            "{:<17} {:<6} {:<9} {:>11.4e} {:>11.4e} {:>8} {:>10} {:>8.4} {:<22} {}",
            r.case,
            r.region,
            r.method,
            r.undecided_area,
            r.undefined_area,
            r.leaves,
            r.box_evaluations,
            r.time_s,
            r.stop.to_string(),
            if r.feature_decided {
                "decided"
            } else {
                "not decided"
            }
        );
    }
    outln!("features:");
    for c in &cases {
        outln!("  {:<17} {}", c.key, c.feature.describe());
    }
    outln!(
        "wrote {} and {}",
        json.display(),
        files
            .iter()
            .map(|f| f.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(())
}
