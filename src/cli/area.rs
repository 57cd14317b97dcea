//! `detach area`: certified areas of regions and cells by quadrature over θ.

use super::{CliError, CliResult};
use detach::certificate::numbers::{fixed, Round};
use detach::number::param::parse_assignment;
use detach::pave::{pave_scene_method, standard_cells, Method, MethodOptions, PaveOptions, Paving};
use detach::quadrature::{cell_area, check_target, AreaEnclosure, AreaError, AreaOptions, CELLS};
use detach::scene::{Scene, Variant, REGION_LABELS, REGION_NAMES};
use serde::Serialize;
use std::time::Instant;

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
    /// Missed because binary64 rounding limits this area to about its width.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    at_rounding_floor: bool,
    /// θ-pieces of the quadrature, or the paving's leaves.
    pieces: usize,
    /// Pieces whose slice shape stayed undecided, bounded by `[0, hi − lo]`
    /// (quadrature only).
    #[serde(skip_serializing_if = "Option::is_none")]
    undecided_pieces: Option<usize>,
    /// Set when the cell is empty by construction.
    #[serde(skip_serializing_if = "Option::is_none")]
    empty: Option<&'static str>,
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

/// Resolution of the paving whose bounds stand in for, or narrow, the
/// quadrature's.
const FALLBACK_EPS: f64 = 1.0 / 1024.0;

pub fn run_area(args: &AreaArgs) -> CliResult {
    let overrides = args
        .params
        .iter()
        .map(|t| parse_assignment(t).map_err(CliError::usage))
        .collect::<Result<Vec<_>, _>>()?;
    let (scene, params) = args.source.build(&overrides, args.variant)?;
    let (th, thd) = (
        super::atlas::split_window("theta", &args.theta)?,
        super::atlas::split_window("theta-dot", &args.theta_dot)?,
    );
    let domain = super::atlas::windowed_domain(&scene, &th, &thd)?;
    if !(1..=15).contains(&args.digits) {
        return Err(CliError::usage(format!(
            "--digits must be between 1 and 15, got {}",
            args.digits
        )));
    }
    if args.max_pieces == 0 {
        return Err(CliError::usage("--max-pieces must be at least 1"));
    }
    let mut wanted = Vec::new();
    for r in &args.region {
        match REGION_NAMES.iter().position(|n| n == r) {
            Some(i) if !wanted.contains(&i) => wanted.push(i),
            Some(_) => {}
            None => {
                return Err(CliError::usage(format!(
                    "unknown region `{r}` (known: {})",
                    REGION_NAMES.join(", ")
                )))
            }
        }
    }
    if wanted.is_empty() {
        wanted = (0..REGION_NAMES.len()).collect();
    }
    let tol = 10f64.powi(-args.digits);
    let opts = AreaOptions {
        tol,
        max_pieces: args.max_pieces,
    };
    // A paving's bounds stand in where the quadrature does not apply (a
    // scene file's region of another form than degree ≤ 2 in θ̇), and narrow
    // its enclosure where it missed the target (a cell whose two boundaries
    // coincide along a curve): both enclose the area.
    let pave_once = || -> Result<(Paving, f64), CliError> {
        let start = Instant::now();
        let opts = PaveOptions {
            eps: FALLBACK_EPS,
            ..PaveOptions::default()
        };
        // The default method: for a region not quadratic in θ̇ it bisects.
        let mo = MethodOptions::new(Method::default());
        let p = pave_scene_method(&scene, args.variant, &domain, opts, &mo, |_, _, _| {})
            .map_err(|e| CliError::runtime(format!("paving failed: {e:?}")))?;
        Ok((p, start.elapsed().as_secs_f64()))
    };
    let not_quadratic = match &scene {
        Scene::File(f) => f.not_quadratic(),
        _ => None,
    };
    let mut paving: Option<(Paving, f64)> = None;
    let mut notes = Vec::new();
    if let Some(region) = not_quadratic {
        paving = Some(pave_once()?);
        notes.push(format!(
            "region `{region}` is not of degree at most 2 in theta_dot: every row is a paving's \
             inner and outer bounds at eps = 1/1024, with its leaves and time"
        ));
    }
    let refusal = |i: usize, e: AreaError| {
        CliError::usage(format!("{} ({}): {e}", REGION_LABELS[i], REGION_NAMES[i]))
    };
    if not_quadratic.is_none() {
        // Every set's rounding first, so that one refusal names them all and
        // the digits that every one of them can reach.
        let (mut below, mut floor, mut least) = (Vec::new(), 0f64, 0f64);
        for &i in &wanted {
            match check_target(&scene, args.variant, &domain, CELLS[i], tol) {
                Ok(()) => {}
                Err(AreaError::BelowRounding {
                    floor: f, least: l, ..
                }) => {
                    below.push(format!("{} ({})", REGION_LABELS[i], REGION_NAMES[i]));
                    (floor, least) = (floor.max(f), least.max(l));
                }
                Err(e) => return Err(refusal(i, e)),
            }
        }
        if !below.is_empty() {
            return Err(CliError::usage(format!(
                "{}: a width of {tol:e} is below what binary64 arithmetic certifies \
                 (rounding alone leaves up to about {floor:.1e}); ask for --digits {} or fewer",
                below.join(", "),
                (-least.log10()).floor() as i32
            )));
        }
    }
    let mut regions = Vec::new();
    for i in wanted {
        let start = Instant::now();
        let bounds = |p: &Paving| {
            let b = p.area_bounds(&standard_cells()[i], domain.uncovered_area_sup());
            AreaEnclosure::bounds(b.inner_area, b.outer_area, p.leaves.len())
        };
        let by_paving = not_quadratic.is_some();
        let mut elapsed = None;
        let proved_empty =
            detach::params::proved_empty(&scene, args.variant, detach::pave::Cell::ALL[i]);
        let e = match (&paving, by_paving) {
            _ if proved_empty => AreaEnclosure::bounds(0.0, 0.0, 0),
            (Some((p, t)), true) => {
                // One paving for every row: its own time.
                elapsed = Some(*t);
                bounds(p)
            }
            _ => {
                let e = cell_area(&scene, args.variant, &domain, CELLS[i], opts)
                    .map_err(|e| refusal(i, e))?;
                // At its rounding floor the enclosure is already far
                // narrower than a paving's.
                if e.width() <= tol || e.at_rounding_floor {
                    e
                } else {
                    if paving.is_none() {
                        paving = Some(pave_once()?);
                        notes.push(
                            "where the quadrature missed its target (e.g. a cell whose two boundaries coincide along a curve), its enclosure is intersected with a paving's bounds at eps = 1/1024".into(),
                        );
                    }
                    e.intersect(&bounds(&paving.as_ref().expect("just paved").0))
                }
            }
        };
        regions.push(RegionArea {
            name: REGION_NAMES[i],
            label: REGION_LABELS[i],
            lower: e.area.inf() + 0.0,
            upper: e.area.sup() + 0.0,
            width: e.width(),
            target_met: e.width() <= tol,
            method: if by_paving { "paving" } else { "quadrature" },
            at_rounding_floor: e.at_rounding_floor,
            pieces: e.pieces,
            undecided_pieces: (!by_paving).then_some(e.undecided_pieces),
            empty: if proved_empty {
                Some("proved empty")
            } else {
                e.proved_empty.then_some("omega0 = omega")
            },
            elapsed_s: elapsed.unwrap_or_else(|| start.elapsed().as_secs_f64()),
        });
    }
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
        if r.empty.is_some() {
            outln!("  {label} 0 (empty: Ω₀ = Ω)");
            continue;
        }
        outln!(
            "  {label} [{}, {}]  width {:.1e}{}  {} {}  {:.3} s",
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
