//! `detach atlas`, `detach pave`, `detach scenes`.

use super::{parse_overrides, progress_bar, CliError, CliResult};
use detach::certificate::numbers::{area_text, Round};
use detach::figures::{
    draw_atlas_files, parse_size, plot_area_pixels, AtlasStyle, Formats, PictureInfo, MIN_HEIGHT,
    MIN_WIDTH,
};
use detach::number::param::ParamSet;
use detach::pave::{
    pave_scene_method, standard_cell_bounds, Emptiness, Method, MethodOptions, PaveOptions, Paving,
};
use detach::scene::{Cell, Domain, Scene, SceneId, SceneText, UnknownCell, Variant};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Options shared by `atlas` and `pave`.
#[derive(clap::Args, Debug, Clone)]
pub struct PaveFlags {
    /// Which reading of the paper: `derived` (re-derived mechanics) or `printed`.
    #[arg(long, value_parser = super::variant_parser(), default_value_t = Variant::Derived)]
    pub variant: Variant,
    /// Override a parameter, as decimal text: `--param mu=0.5` (repeatable, once per name).
    #[arg(long = "param", value_name = "NAME=VALUE")]
    pub params: Vec<String>,
    /// Resolution relative to the domain (a box stops splitting along an axis at
    /// eps × the domain's width). Default: about one pixel of the picture for
    /// `atlas`, 1/1024 for `pave`.
    #[arg(long, allow_negative_numbers = true)]
    pub eps: Option<f64>,
    /// Most leaves per paving (an integer, `1e6` form accepted); when reached
    /// the result is coarser but valid.
    #[arg(long, default_value_t = 4_000_000, value_parser = detach::number::param::parse_count, allow_negative_numbers = true)]
    pub max_boxes: usize,
    /// Paving method: slices (the fastest at equal accuracy), natural,
    /// centred or contract. Every method's labels are re-decided by the proof
    /// checker (natural evaluation, or its monotone and convex tests).
    #[arg(long, value_parser = super::method_parser(), default_value_t = Method::Slices)]
    pub method: Method,
    /// Refine only for this region or cell (omega, omega0, omega_and_omega0,
    /// …): boxes undecided only for a constraint it does not use stay leaves.
    #[arg(long, value_name = "NAME")]
    pub region: Option<String>,
}

impl PaveFlags {
    fn method_options(&self) -> Result<MethodOptions, CliError> {
        let Some(name) = &self.region else {
            return Ok(MethodOptions::new(self.method));
        };
        let cell: Cell = name
            .parse()
            .map_err(|e: UnknownCell| CliError::usage(e.to_string()))?;
        Ok(MethodOptions::for_cell(self.method, &cell.spec()))
    }
}

#[derive(clap::Args, Debug)]
pub struct AtlasArgs {
    /// Output directory.
    #[arg(long, default_value = "out/atlas")]
    pub out: PathBuf,
    /// Only these scenes (repeatable); default: all three, unless scene
    /// files are given.
    #[arg(long, value_name = "SCENE")]
    pub scene: Vec<String>,
    /// A scene file to draw (repeatable; TOML, see docs/scene-files.md).
    #[arg(long = "scene-file", value_name = "FILE")]
    pub scene_file: Vec<PathBuf>,
    #[command(flatten)]
    pub flags: PaveFlags,
    /// Restrict θ to a window `LO:HI` (decimal text, `pi`, `-pi`, `pi/N`)
    /// inside each scene's domain.
    #[arg(long, value_name = "LO:HI", allow_hyphen_values = true)]
    pub theta: Option<String>,
    /// Restrict θ̇ to a window `LO:HI` inside each scene's domain.
    #[arg(long = "theta-dot", value_name = "LO:HI", allow_hyphen_values = true)]
    pub theta_dot: Option<String>,
    /// Picture size in pixels, `WxH` (default 1200x800, at least 640x400).
    #[arg(long, value_name = "WxH")]
    pub size: Option<String>,
    /// Which picture files: `svg` (vector only), `png` or `all`. PDF is not
    /// supported: convert the SVG (e.g. `rsvg-convert -f pdf`).
    #[arg(long, default_value = "all", value_name = "FORMAT")]
    pub format: String,
}

#[derive(clap::Args, Debug)]
pub struct PaveArgs {
    #[command(flatten)]
    pub source: super::SceneSource,
    #[command(flatten)]
    pub flags: PaveFlags,
    /// Restrict θ to a window `LO:HI` (decimal text, `pi`, `-pi`, `pi/N`)
    /// inside the scene's domain.
    #[arg(long, value_name = "LO:HI", allow_hyphen_values = true)]
    pub theta: Option<String>,
    /// Restrict θ̇ to a window `LO:HI` (decimal text) inside the scene's domain.
    #[arg(long = "theta-dot", value_name = "LO:HI", allow_hyphen_values = true)]
    pub theta_dot: Option<String>,
    /// Print the result as JSON instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Also write this run as a proof file (`proofs/FORMAT.md`), checked
    /// before it is reported; `-`: standard output.
    #[arg(long, value_name = "FILE")]
    pub proof: Option<PathBuf>,
    /// Write every leaf (exact endpoints, one label per constraint) as CSV;
    /// `-`: standard output.
    #[arg(long, value_name = "FILE")]
    pub leaves: Option<PathBuf>,
}

pub(super) fn split_window(
    flag: &str,
    text: &Option<String>,
) -> Result<Option<[String; 2]>, CliError> {
    match text {
        None => Ok(None),
        Some(t) => match t.split_once(':') {
            Some((lo, hi)) => Ok(Some([lo.trim().to_string(), hi.trim().to_string()])),
            None => Err(CliError::usage(format!(
                "--{flag} must be LO:HI, got `{t}`"
            ))),
        },
    }
}

/// A window's ends as the library takes them.
pub(super) fn as_refs(w: &Option<[String; 2]>) -> Option<[&str; 2]> {
    w.as_ref().map(|[a, b]| [a.as_str(), b.as_str()])
}

/// The scene's domain restricted to the windows `--theta`, `--theta-dot`
/// (`LO:HI` text, `None` keeps the side), with a note for an end clipped to
/// the domain.
pub(super) fn windowed_domain(
    scene: &Scene,
    th: &Option<[String; 2]>,
    thd: &Option<[String; 2]>,
) -> Result<Domain, CliError> {
    let (domain, clipped) = scene
        .domain()
        .window_clipped(as_refs(th), as_refs(thd))
        .map_err(detach::api::Error::from)?;
    for c in clipped {
        eprintln!(
            "detach: note: window end {c} is within rounding of the domain's end; \
             clipped to the domain"
        );
    }
    Ok(domain)
}

/// `θ ∈ [LO, HI], θ̇ ∈ [LO, HI]` for the window ends given, as given.
pub(super) fn window_text(th: &Option<[String; 2]>, thd: &Option<[String; 2]>) -> Option<String> {
    let parts: Vec<String> = [("θ", th), ("θ̇", thd)]
        .into_iter()
        .filter_map(|(v, w)| w.as_ref().map(|[a, b]| format!("{v} ∈ [{a}, {b}]")))
        .collect();
    (!parts.is_empty()).then(|| parts.join(", "))
}

#[derive(clap::Args, Debug)]
pub struct ScenesArgs {
    /// Print as JSON.
    #[arg(long)]
    pub json: bool,
}

/// One region or cell in the summary.
#[derive(Serialize)]
struct RegionReport {
    name: &'static str,
    label: &'static str,
    inner_area: f64,
    outer_area: f64,
    /// `outer_area − inner_area` rounded up: an upper bound.
    undecided_area: f64,
    /// Set when the cell is empty by construction or proved empty (in JSON
    /// `"omega0 = omega"`, `"proved empty"`): both areas are then exactly 0
    /// and no box is counted.
    #[serde(skip_serializing_if = "Option::is_none")]
    empty: Option<Emptiness>,
    boxes: BoxCounts,
}

#[derive(Serialize)]
struct StopDetail {
    reason: detach::pave::StopReason,
    text: &'static str,
    /// The budget's flag, when the budget stopped refinement.
    #[serde(skip_serializing_if = "Option::is_none")]
    option: Option<String>,
    #[serde(flatten)]
    budget: Option<detach::pave::BudgetStop>,
}

#[derive(Serialize)]
struct BoxCounts {
    inner: usize,
    outer: usize,
    undecided: usize,
}

#[derive(Serialize)]
struct DomainReport {
    theta: [f64; 2],
    theta_dot: [f64; 2],
    /// Area of the true domain not covered by the paved box (endpoints such as
    /// π are not doubles); added to every outer bound.
    uncovered_area_sup: f64,
}

/// What `pave --json` prints and `atlas` writes to `summary.json`.
#[derive(Serialize)]
pub struct PaveReport {
    /// `{"version", "commit"}` of the program that wrote it.
    detach: serde_json::Value,
    scene: String,
    /// The reading of the paper (absent for a scene file).
    #[serde(skip_serializing_if = "Option::is_none")]
    variant: Option<Variant>,
    params: serde_json::Map<String, serde_json::Value>,
    domain: DomainReport,
    /// The paving method (`--method`).
    method: Method,
    eps: f64,
    max_boxes: usize,
    complete: bool,
    /// Why refinement stopped: `all_decided`, `resolution`,
    /// `double_precision_limit` or `budget`.
    stop: detach::pave::StopReason,
    /// The same with its explanation and, when the budget stopped
    /// refinement, the option that sets it and what the asked eps needs.
    stop_reason: StopDetail,
    elapsed_s: f64,
    leaves: usize,
    stats: detach::pave::PaveStats,
    /// Upper bound on the area of leaves where some formula may be undefined.
    undefined_area: f64,
    /// Plain-language warnings (e.g. enclosures that under/overflowed).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    warnings: Vec<String>,
    regions: Vec<RegionReport>,
}

/// Paves one scene with a progress bar, and summarises it.
fn pave_and_report(
    scene: &Scene,
    domain: &Domain,
    params: &ParamSet,
    variant: Variant,
    opts: PaveOptions,
    mo: &MethodOptions,
) -> Result<(Paving, PaveReport), CliError> {
    // Two levels per halving of each axis; 1/eps may be +∞ (eps subnormal),
    // and no double interval halves more than about 1100 times.
    let levels = (2.0 * (1.0 / opts.eps).log2().ceil().clamp(0.0, 1100.0)) as u64 + 1;
    let bar = progress_bar(levels, scene.name());
    // Redrawn while a long level runs, so the clock moves.
    bar.enable_steady_tick(std::time::Duration::from_millis(500));
    let start = Instant::now();
    let max = opts.max_boxes;
    let paving = pave_scene_method(scene, variant, domain, opts, mo, |level, open, leaves| {
        bar.set_position(level as u64);
        bar.set_message(format!("{open} open, {leaves}/{max} leaves"));
    })
    .map_err(CliError::usage)?;
    let elapsed_s = start.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let mut report = summarise(scene, domain, params, variant, opts, &paving, elapsed_s);
    report.method = mo.method;
    for w in &report.warnings {
        eprintln!("detach: warning: {} ({w})", report.scene);
    }
    Ok((paving, report))
}

fn summarise(
    scene: &Scene,
    domain: &Domain,
    params: &ParamSet,
    variant: Variant,
    opts: PaveOptions,
    paving: &Paving,
    elapsed_s: f64,
) -> PaveReport {
    let uncovered = domain.uncovered_area_sup();
    let proved = detach::area::proved_empty_cells(scene, variant);
    let regions = standard_cell_bounds(paving, proved, uncovered)
        .into_iter()
        .enumerate()
        .map(|(i, (b, empty))| RegionReport {
            name: Cell::ALL[i].name(),
            label: Cell::ALL[i].label(),
            inner_area: b.inner_area,
            outer_area: b.outer_area,
            undecided_area: b.undecided_area(),
            empty,
            boxes: BoxCounts {
                inner: b.inner_boxes,
                outer: b.outer_boxes,
                undecided: b.undecided_boxes(),
            },
        })
        .collect();
    let undefined = paving.undefined_area();
    PaveReport {
        detach: detach::provenance(),
        scene: scene.name().to_string(),
        variant: scene.id().map(|_| variant),
        params: params
            .texts()
            .into_iter()
            .map(|(n, t)| (n.to_string(), serde_json::Value::String(t)))
            .collect(),
        domain: DomainReport {
            theta: paving.root.theta,
            theta_dot: paving.root.theta_dot,
            uncovered_area_sup: uncovered,
        },
        method: Method::default(),
        eps: opts.eps,
        max_boxes: opts.max_boxes,
        complete: paving.complete,
        stop: paving.stop,
        stop_reason: StopDetail {
            reason: paving.stop,
            text: paving.stop.describe(),
            option: paving.budget.map(|b| super::flag(b.option)),
            budget: paving.budget,
        },
        elapsed_s,
        leaves: paving.leaves.len(),
        stats: paving.stats,
        undefined_area: undefined.area_sup,
        warnings: undefined.warning().into_iter().collect(),
        regions,
    }
}

/// Pads `s` on the right to `width` columns, counting combining marks (the
/// overbar of Ω̄) as zero-width.
pub(super) fn pad(s: &str, width: usize) -> String {
    let shown = s
        .chars()
        .filter(|c| !('\u{0300}'..='\u{036f}').contains(c))
        .count();
    format!("{s}{}", " ".repeat(width.saturating_sub(shown)))
}

fn print_table(r: &PaveReport) {
    let params: Vec<String> = r
        .params
        .iter()
        .map(|(k, v)| format!("{k}={}", v.as_str().unwrap_or("")))
        .collect();
    outln!(
        "{}{}  {}{}  eps={:.3e}  {} leaves  {:.2} s  stop: {} ({})",
        r.scene,
        super::reading(r.variant),
        params.join(" "),
        if r.method == Method::default() {
            String::new()
        } else {
            format!("  method={}", r.method)
        },
        r.eps,
        r.leaves,
        r.elapsed_s,
        r.stop,
        r.stop.describe()
    );
    if let Some(b) = &r.stop_reason.budget {
        outln!(
            "  {} {} stopped refinement; eps {:e} needs at least {} leaves \
             (about {:.1e} by the growth of the last levels): raise {} (at most {}) or eps",
            super::flag(b.option),
            b.max_boxes,
            r.eps,
            b.leaves_needed_at_least,
            b.leaves_needed_estimate,
            super::flag(b.option),
            detach::api::MAX_LEAVES
        );
        match b.complete_at_eps {
            Some(e) => outln!("  the result is the complete paving at eps {e:e}"),
            None => outln!("  the result is the domain's box alone"),
        }
    }
    outln!(
        "  {} {:>12} {:>12} {:>12} {:>12} {:>12} {:>12}",
        pad("region", 7),
        "inner area",
        "outer area",
        "undecided",
        "inner boxes",
        "outer boxes",
        "undec. boxes"
    );
    for w in &r.warnings {
        outln!("  warning: {w}");
    }
    for g in &r.regions {
        if let Some(why) = g.empty {
            let why = why.symbol();
            outln!(
                "  {} {:>12} {:>12} {:>12} {:>12} {:>12} {:>12}  empty ({why})",
                pad(g.label, 7),
                "0",
                "0",
                "0",
                0,
                0,
                0
            );
            continue;
        }
        outln!(
            "  {} {:>12} {:>12} {:>12} {:>12} {:>12} {:>12}",
            pad(g.label, 7),
            area_text(g.inner_area, Round::Down),
            area_text(g.outer_area, Round::Up),
            area_text(g.undecided_area, Round::Up),
            g.boxes.inner,
            g.boxes.outer,
            g.boxes.undecided
        );
    }
}

fn options(flags: &PaveFlags, default_eps: f64) -> Result<PaveOptions, CliError> {
    Ok(detach::api::pave_options(
        flags.eps.unwrap_or(default_eps),
        flags.max_boxes,
    )?)
}

pub fn run_pave(args: &PaveArgs) -> CliResult {
    super::take_stdout(
        &[
            ("--leaves", args.leaves.as_deref()),
            ("--proof", args.proof.as_deref()),
        ],
        args.json,
    )?;
    let overrides = parse_overrides(&args.flags.params)?;
    let (scene, params) = args.source.build(&overrides, args.flags.variant)?;
    let opts = options(&args.flags, PaveOptions::default().eps)?;
    let (th, thd) = (
        split_window("theta", &args.theta)?,
        split_window("theta-dot", &args.theta_dot)?,
    );
    let domain = windowed_domain(&scene, &th, &thd)?;
    let (paving, report) = pave_and_report(
        &scene,
        &domain,
        &params,
        args.flags.variant,
        opts,
        &args.flags.method_options()?,
    )?;
    if let Some(path) = &args.leaves {
        let run = format!("{}, method {}", args.flags.variant, args.flags.method);
        let provenance =
            detach::pave::export::provenance(scene.name(), &run, &params.texts(), &paving);
        write_leaves(&paving, &provenance, path)?;
    }
    if let Some(path) = &args.proof {
        let text = |w: &Option<[String; 2]>, i: usize| {
            w.clone().unwrap_or_else(|| scene.domain_text()[i].clone())
        };
        super::proofs::write_paving_proof(
            path,
            &scene,
            &params,
            args.flags.variant,
            &domain,
            [text(&th, 0), text(&thd, 1)],
            &paving,
        )?;
    }
    if args.json {
        outln!(
            "{}",
            serde_json::to_string_pretty(&report).expect("serialisable")
        );
    } else {
        print_table(&report);
    }
    Ok(())
}

/// `pave --leaves FILE`: the CSV of [`detach::pave::export`].
fn write_leaves(paving: &Paving, provenance: &str, path: &Path) -> CliResult {
    detach::files::write_atomic_with(path, |w| {
        detach::pave::export::write_leaves_csv(paving, provenance, w)
    })
    .map_err(|e| super::cannot_write(path, e))
}

/// Parameter overrides for one scene of a multi-scene run: only the names it
/// declares.
fn overrides_for(id: SceneId, all: &[(String, String)]) -> Vec<(String, String)> {
    all.iter()
        .filter(|(n, _)| id.params().iter().any(|s| s.name == n))
        .cloned()
        .collect()
}

pub fn run_atlas(args: &AtlasArgs) -> CliResult {
    // Shipped scene files named by --scene are read like --scene-file.
    let shipped: Vec<&str> = args
        .scene
        .iter()
        .map(String::as_str)
        .filter(|n| n.parse::<SceneId>().is_err() && SceneText::shipped(n).is_some())
        .collect();
    let ids: Vec<SceneId> = if args.scene.is_empty() && !args.scene_file.is_empty() {
        Vec::new()
    } else if args.scene.is_empty() {
        SceneId::ALL.to_vec()
    } else {
        args.scene
            .iter()
            .filter(|n| !shipped.contains(&n.as_str()))
            .map(|s| s.parse().map_err(CliError::usage))
            .collect::<Result<_, _>>()?
    };
    // A scene named twice is paved once.
    let mut ids = ids;
    let mut seen = Vec::new();
    ids.retain(|id| {
        let new = !seen.contains(id);
        seen.push(*id);
        new
    });
    let overrides = parse_overrides(&args.flags.params)?;
    if !args.scene_file.is_empty() || !shipped.is_empty() {
        detach::api::one_reading(args.flags.variant)?;
    }
    // Each file read once; its declared parameters route the overrides.
    let files = shipped
        .iter()
        .map(|n| Ok(SceneText::shipped(n).expect("a shipped name")))
        .chain(args.scene_file.iter().map(|p| SceneText::read(p)))
        .map(|text| {
            let text = text.map_err(CliError::usage)?;
            let names: Vec<String> = text
                .compile(&[])
                .map_err(CliError::usage)?
                .params
                .specs
                .iter()
                .map(|s| s.name.to_string())
                .collect();
            Ok((text, names))
        })
        .collect::<Result<Vec<_>, CliError>>()?;
    let for_file = |names: &[String]| -> Vec<(String, String)> {
        overrides
            .iter()
            .filter(|(n, _)| names.contains(n))
            .cloned()
            .collect()
    };
    for (name, _) in &overrides {
        if !ids
            .iter()
            .any(|id| id.params().iter().any(|s| s.name == name))
            && !files.iter().any(|(_, names)| names.contains(name))
        {
            return Err(CliError::usage(format!(
                "unknown parameter `{name}` for the scenes paved"
            )));
        }
    }
    let style = match &args.size {
        None => AtlasStyle::default(),
        Some(t) => {
            let (width, height) = parse_size(t, (MIN_WIDTH, MIN_HEIGHT))
                .map_err(|e| CliError::usage(format!("--size: {e}")))?;
            AtlasStyle { width, height }
        }
    };
    let formats =
        Formats::parse(&args.format).map_err(|e| CliError::usage(format!("--format: {e}")))?;
    let (th, thd) = (
        split_window("theta", &args.theta)?,
        split_window("theta-dot", &args.theta_dot)?,
    );
    let (w, h) = plot_area_pixels(&style);
    // About one pixel: the largest power of two not above 1/max(w, h).
    let pixel_eps = (1.0 / w.max(h) as f64).log2().floor().exp2();
    let opts = options(&args.flags, pixel_eps)?;
    let mo = args.flags.method_options()?;
    // Validate every scene and window before the long work starts.
    let built = ids
        .iter()
        .map(|&id| Scene::build(id, &overrides_for(id, &overrides)).map_err(CliError::usage))
        .chain(files.iter().map(|(text, names)| {
            let f = text.compile(&for_file(names)).map_err(CliError::usage)?;
            let params = f.params.clone();
            Ok((Scene::File(Box::new(f)), params))
        }))
        .collect::<Result<Vec<_>, CliError>>()?;
    let scenes = built
        .into_iter()
        .map(|(scene, params)| {
            fn refs(w: &Option<[String; 2]>) -> Option<[&str; 2]> {
                w.as_ref().map(|[a, b]| [a.as_str(), b.as_str()])
            }
            let (domain, clipped) = scene
                .domain()
                .window_clipped(refs(&th), refs(&thd))
                .map_err(|e| CliError::usage(format!("{}: {e}", scene.name())))?;
            for c in clipped {
                eprintln!(
                    "detach: note: {}: window end {c} is within rounding of the domain's end; \
                     clipped to the domain",
                    scene.name()
                );
            }
            Ok((scene, params, domain))
        })
        .collect::<Result<Vec<_>, CliError>>()?;
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::runtime(format!("cannot create {}: {e}", args.out.display())))?;
    // Read before the work: a summary that cannot be merged stops the run.
    let summary = args.out.join("summary.json");
    let earlier = read_summary(&summary)?;
    let mut reports = Vec::new();
    for (scene, params, domain) in &scenes {
        let (paving, report) =
            pave_and_report(scene, domain, params, args.flags.variant, opts, &mo)?;
        let info = PictureInfo {
            scene,
            variant: args.flags.variant,
            params: params.texts_with_units(),
            complete: paving.complete,
            window: window_text(&th, &thd),
        };
        let stem = args.out.join(scene.name());
        // Files first, then the table: a closed stdout never costs a file.
        draw(&paving, &info, &style, formats, &stem)?;
        print_table(&report);
        outln!(
            "  wrote {}.{}",
            stem.display(),
            formats.extensions().join(" and .")
        );
        reports.push(report);
    }
    let scenes = merge_summary(earlier, &args.out, reports);
    let text = serde_json::to_string_pretty(
        &serde_json::json!({ "detach": detach::provenance(), "scenes": scenes }),
    )
    .expect("serialisable");
    detach::files::write_atomic(&summary, text.as_bytes())
        .map_err(|e| super::cannot_write(&summary, e))?;
    outln!("wrote {}", summary.display());
    Ok(())
}

/// The scenes of an existing `summary.json` (none if there is none). One that
/// cannot be read is an error, not silently replaced.
fn read_summary(summary: &Path) -> Result<Vec<serde_json::Value>, CliError> {
    Ok(match std::fs::read(summary) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Vec::new(),
        Err(e) => {
            return Err(CliError::runtime(format!(
                "cannot read {}: {e}",
                summary.display()
            )))
        }
        Ok(bytes) => {
            let v: serde_json::Value = serde_json::from_slice(&bytes).map_err(|e| {
                CliError::runtime(format!(
                    "{} is not a summary ({e}); move it away to start a new one",
                    summary.display()
                ))
            })?;
            match v.get("scenes").and_then(|s| s.as_array()) {
                Some(a) => a.clone(),
                None => {
                    return Err(CliError::runtime(format!(
                        "{} has no \"scenes\" list; move it away to start a new one",
                        summary.display()
                    )))
                }
            }
        }
    })
}

/// The scenes `summary.json` lists after this run: those of the folder's
/// summary whose pictures are still beside it, in their order, each replaced
/// by this run's report if it paved the scene again, then the new scenes. So
/// the summary describes every picture in the folder, and each entry says
/// which `detach` wrote it.
fn merge_summary(
    old: Vec<serde_json::Value>,
    dir: &Path,
    reports: Vec<PaveReport>,
) -> Vec<serde_json::Value> {
    let mut new: Vec<(String, serde_json::Value)> = reports
        .into_iter()
        .map(|r| {
            let scene = r.scene.clone();
            (scene, serde_json::to_value(r).expect("serialisable"))
        })
        .collect();
    let has_pictures = |scene: &str| {
        ["svg", "png"]
            .iter()
            .any(|ext| dir.join(format!("{scene}.{ext}")).is_file())
    };
    let mut out = Vec::new();
    for entry in old {
        let Some(scene) = entry.get("scene").and_then(|s| s.as_str()) else {
            continue;
        };
        if let Some(i) = new.iter().position(|(s, _)| s == scene) {
            out.push(new.remove(i).1);
        } else if has_pictures(scene) {
            out.push(entry);
        }
    }
    out.extend(new.into_iter().map(|(_, v)| v));
    out
}

fn draw(
    paving: &Paving,
    info: &PictureInfo,
    style: &AtlasStyle,
    formats: Formats,
    stem: &Path,
) -> CliResult {
    let (svg, png) = (stem.with_extension("svg"), stem.with_extension("png"));
    draw_atlas_files(
        paving,
        info,
        style,
        formats.svg.then_some(svg.as_path()),
        formats.png.then_some(png.as_path()),
    )
    .map_err(|e| CliError::runtime(format!("drawing {}: {e}", stem.display())))
}

pub fn run_scenes(args: &ScenesArgs) -> CliResult {
    #[derive(Serialize)]
    struct SceneInfo {
        name: String,
        title: String,
        params: &'static [detach::number::param::ParamSpec],
        /// `[conditions]` the parameters must satisfy, as written.
        conditions: Vec<String>,
        domain: DomainText,
        /// Empty for a scene file (one reading).
        variants: Vec<Variant>,
    }
    #[derive(Serialize)]
    struct DomainText {
        theta: [f64; 2],
        theta_dot: [f64; 2],
    }
    let info = |scene: &Scene, params: &'static [_], variants: Vec<Variant>| {
        let b = scene.domain().inner_box();
        SceneInfo {
            name: scene.name().into(),
            title: scene.title().into(),
            params,
            conditions: scene
                .reading(Variant::Derived)
                .conditions
                .iter()
                .map(|(_, c)| c.clone())
                .collect(),
            domain: DomainText {
                theta: b[0],
                theta_dot: b[1],
            },
            variants,
        }
    };
    let mut infos: Vec<SceneInfo> = SceneId::ALL
        .iter()
        .map(|&id| {
            let variants = vec![Variant::Derived, Variant::Printed];
            info(&Scene::default_of(id), id.params(), variants)
        })
        .collect();
    for (name, _) in detach::scene::file::SHIPPED {
        let (scene, params) = Scene::by_name(name, &[]).map_err(CliError::runtime)?;
        infos.push(info(&scene, params.specs, Vec::new()));
    }
    if args.json {
        outln!(
            "{}",
            serde_json::to_string_pretty(&infos).expect("serialisable")
        );
        return Ok(());
    }
    for s in &infos {
        outln!("{} — {}", s.name, s.title);
        let variants = if s.variants.is_empty() {
            "a scene file, one reading"
        } else {
            "variants: derived (default), printed"
        };
        outln!(
            "  domain θ ∈ [{:.6}, {:.6}], θ̇ ∈ [{}, {}]; {variants}",
            s.domain.theta[0],
            s.domain.theta[1],
            s.domain.theta_dot[0],
            s.domain.theta_dot[1]
        );
        for p in s.params {
            let value = match p.unit {
                "" => p.default.to_string(),
                u => format!("{} {u}", p.default),
            };
            let meaning = if p.meaning.is_empty() { "-" } else { p.meaning };
            outln!("  {:<6} = {:<6} {meaning}", p.name, value);
        }
        if !s.conditions.is_empty() {
            outln!("  conditions: {}", s.conditions.join(", "));
        }
    }
    Ok(())
}
