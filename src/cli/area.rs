//! `detach area`: certified areas of regions and cells by quadrature over θ.

use super::CliResult;
use detach::api::Emptiness;
use detach::area::{Provenance, Source};
use detach::certificate::numbers::{fixed, Round};
use detach::scene::Variant;
use serde::Serialize;

#[derive(clap::Args, Debug)]
pub struct AreaArgs {
    #[command(flatten)]
    pub source: super::SceneSource,
    /// Which reading of the paper: `derived` or `printed`.
    #[arg(long, value_parser = super::variant_parser(), default_value_t = Variant::Derived)]
    pub variant: Variant,
    /// Only this region or cell (repeatable): omega, omega0, omega_and_omega0,
    /// not_omega_and_not_omega0, not_omega_and_omega0, omega_and_not_omega0.
    #[arg(long, value_name = "REGION")]
    pub region: Vec<String>,
    /// Decimal places to certify: the enclosure's width target is 10^-D.
    #[arg(long, default_value_t = 10, allow_negative_numbers = true)]
    pub digits: i32,
    /// Override a parameter, as decimal text: `--param p_psi=0.6` (repeatable, once per name).
    #[arg(long = "param", value_name = "NAME=VALUE")]
    pub params: Vec<String>,
    /// Restrict θ to a window `LO:HI` (decimal text, `pi`, `-pi`, `pi/N`)
    /// inside the scene's domain: the areas are of the window's part.
    #[arg(long, value_name = "LO:HI", allow_hyphen_values = true)]
    pub theta: Option<String>,
    /// Restrict θ̇ to a window `LO:HI` (decimal text) inside the scene's domain.
    #[arg(long = "theta-dot", value_name = "LO:HI", allow_hyphen_values = true)]
    pub theta_dot: Option<String>,
    /// Most θ-pieces per region (an integer, `1e6` form accepted).
    #[arg(long, default_value_t = 1 << 20, value_parser = detach::number::param::parse_count)]
    pub max_pieces: usize,
    /// Print the result as JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct RegionArea {
    name: &'static str,
    label: &'static str,
    /// The true area lies in `[lower, upper]` (outward rounded).
    lower: f64,
    upper: f64,
    width: f64,
    /// Whether the width target was met.
    target_met: bool,
    /// `quadrature`, or `paving` where the bounds are a paving's alone.
    method: &'static str,
    /// `quadrature`, `paving`, or `intersection` (the quadrature's enclosure
    /// narrowed by a paving's bounds where it missed its target).
    provenance: Provenance,
    /// What gave the lower bound (`quadrature` or `paving`), and the upper.
    lower_from: Source,
    upper_from: Source,
    /// Missed because binary64 rounding limits this area to about its width.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    at_rounding_floor: bool,
    /// θ-pieces of the quadrature, or the paving's leaves.
    pieces: usize,
    /// Pieces whose slice shape stayed undecided, bounded by `[0, hi − lo]`
    /// (quadrature only).
    #[serde(skip_serializing_if = "Option::is_none")]
    undecided_pieces: Option<usize>,
    /// Set when the cell is proved empty: why.
    #[serde(skip_serializing_if = "Option::is_none")]
    empty: Option<Emptiness>,
    elapsed_s: f64,
}

#[derive(Serialize)]
struct AreaReport {
    detach: serde_json::Value,
    scene: String,
    /// The reading of the paper (absent for a scene file).
    #[serde(skip_serializing_if = "Option::is_none")]
    variant: Option<Variant>,
    params: serde_json::Map<String, serde_json::Value>,
    /// The `--theta`/`--theta-dot` windows, as given.
    #[serde(skip_serializing_if = "Option::is_none")]
    window: Option<String>,
    /// Target width of each enclosure.
    tol: f64,
    regions: Vec<RegionArea>,
    /// Why the enclosures are a paving's bounds, when they are.
    #[serde(skip_serializing_if = "Option::is_none")]
    note: Option<String>,
}

pub fn run_area(args: &AreaArgs) -> CliResult {
    let overrides = super::parse_overrides(&args.params)?;
    let problem = args.source.problem(&overrides, args.variant)?;
    let (scene, params) = (&problem.scene, &problem.params);
    let (th, thd) = (
        super::atlas::split_window("theta", &args.theta)?,
        super::atlas::split_window("theta-dot", &args.theta_dot)?,
    );
    // The clipping notes, once.
    super::atlas::windowed_domain(scene, &th, &thd)?;
    let mut sets = Vec::new();
    for r in &args.region {
        sets.push(detach::api::cell_named(r)?);
    }
    let tol = detach::api::area_tolerance(args.digits)?;
    let areas = problem.certified_areas(&detach::api::AreaRequest {
        sets,
        digits: args.digits,
        max_pieces: args.max_pieces,
        theta: th.clone(),
        theta_dot: thd.clone(),
    })?;
    let regions = areas
        .sets
        .iter()
        .map(|s| {
            let (e, by_paving) = (&s.enclosure, s.provenance == Provenance::Paving);
            RegionArea {
                name: s.cell.name(),
                label: s.cell.label(),
                lower: s.lower(),
                upper: s.upper(),
                width: e.width(),
                target_met: e.width() <= tol,
                method: if by_paving { "paving" } else { "quadrature" },
                provenance: s.provenance,
                lower_from: s.lower_from,
                upper_from: s.upper_from,
                at_rounding_floor: e.at_rounding_floor,
                pieces: e.pieces,
                undecided_pieces: (!by_paving).then_some(e.undecided_pieces),
                empty: s.emptiness(),
                elapsed_s: s.elapsed_s,
            }
        })
        .collect();
    let notes = areas.notes;
    let report = AreaReport {
        detach: detach::provenance(),
        scene: scene.name().to_string(),
        variant: scene.id().map(|_| args.variant),
        params: params
            .texts()
            .into_iter()
            .map(|(n, t)| (n.to_string(), serde_json::Value::String(t)))
            .collect(),
        window: super::atlas::window_text(&th, &thd),
        tol,
        regions,
        note: (!notes.is_empty()).then(|| notes.join("; ")),
    };
    if args.json {
        outln!(
            "{}",
            serde_json::to_string_pretty(&report).expect("serialisable")
        );
        return Ok(());
    }
    let params: Vec<String> = report
        .params
        .iter()
        .map(|(k, v)| format!("{k}={}", v.as_str().unwrap_or("")))
        .collect();
    outln!(
        "{}{}  {}{}  certified areas, target width {:.0e}",
        report.scene,
        super::reading(report.variant),
        params.join(" "),
        report
            .window
            .as_ref()
            .map_or(String::new(), |w| format!("  {w}")),
        tol
    );
    let places = args.digits as usize + 2;
    for r in &report.regions {
        let label = super::atlas::pad(r.label, 8);
        if let Some(e) = r.empty {
            outln!("  {label} 0 (empty: {})", e.symbol());
            continue;
        }
        outln!(
            "  {label} [{}, {}]  width {:.1e}{}  {} {}  {:.3} s{}",
            fixed(r.lower, places, Round::Down),
            fixed(r.upper, places, Round::Up),
            r.width,
            if r.target_met {
                ""
            } else if r.at_rounding_floor {
                " (target not met: binary64 rounding floor)"
            } else {
                " (target not met)"
            },
            r.pieces,
            if r.method == "paving" {
                "leaves (one paving)"
            } else {
                "pieces"
            },
            r.elapsed_s,
            if r.provenance == Provenance::Intersection {
                format!(
                    "  (lower bound by {}, upper by {})",
                    r.lower_from, r.upper_from
                )
            } else {
                String::new()
            },
        );
    }
    if let Some(why) = &report.note {
        eprintln!("detach: note: {why}");
    }
    if report.regions.iter().any(|r| !r.target_met) {
        eprintln!(
            "detach: warning: some enclosures are wider than 1e-{}",
            args.digits
        );
    }
    Ok(())
}
