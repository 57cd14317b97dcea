//! `detach params`: a certified parameter atlas; `detach merge`: the join
//! of a sharded run's parts.

use super::{CliError, CliResult};
use detach::number::param::parse_assignment;
use detach::params::model::{ParamAtlas, ParamAxis, SetStatus};
use detach::params::report::{atlas_json, merge};
use detach::params::{search, DecideOptions, Family, SearchOptions, Shard, Source};
use detach::scene::Cell;
use detach::scene::{SceneText, Variant};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct ParamsArgs {
    #[command(flatten)]
    pub source: super::SceneSource,
    /// Which reading of the paper: `derived` or `printed`.
    #[arg(long, value_parser = super::variant_parser(), default_value_t = Variant::Derived)]
    pub variant: Variant,
    /// The parameter to vary and its range: `--x mu=1:2` (decimal text).
    #[arg(long, value_name = "NAME=LO:HI", allow_hyphen_values = true)]
    pub x: String,
    /// A second parameter to vary: a 2-D atlas and its picture.
    #[arg(long, value_name = "NAME=LO:HI", allow_hyphen_values = true)]
    pub y: Option<String>,
    /// The sets to decide, comma-separated: omega, omega0, omega_and_omega0,
    /// not_omega_and_not_omega0, not_omega_and_omega0, omega_and_not_omega0.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "not_omega_and_omega0,omega_and_not_omega0"
    )]
    pub sets: Vec<String>,
    /// Resolution relative to the parameter box, per axis [default: 2^-34
    /// in one parameter, 1/256 in two].
    #[arg(long)]
    pub eps: Option<f64>,
    /// Most parameter boxes; when reached, the atlas is coarser (and says so).
    #[arg(long, default_value_t = 100_000, value_parser = detach::number::param::parse_count)]
    pub max_boxes: usize,
    /// Override a fixed parameter, as decimal text (repeatable, once per
    /// name); for a varying one, the point the picture marks.
    #[arg(long = "param", value_name = "NAME=VALUE")]
    pub params: Vec<String>,
    /// Print the result as JSON instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Write a proof file of the atlas.
    #[arg(long, value_name = "FILE")]
    pub proof: Option<PathBuf>,
    /// Write params.json (and, in two parameters, params.svg and params.png) here.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Compute part K of N (0 ≤ K < N) of the atlas; `detach merge` joins
    /// the parts' JSON.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<Shard>,
}

#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// The JSON of every shard of one `detach params` run.
    #[arg(required = true, value_name = "PART")]
    pub parts: Vec<PathBuf>,
    /// Write the joined JSON here instead of standard output.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
}

/// `NAME=LO:HI`.
fn axis(flag: &str, text: &str) -> Result<ParamAxis, CliError> {
    let bad = || CliError::usage(format!("{flag}: expected NAME=LO:HI, got `{text}`"));
    let (name, range) = parse_assignment(text).map_err(|_| bad())?;
    let (lo, hi) = range.split_once(':').ok_or_else(bad)?;
    Ok(ParamAxis {
        name,
        lo: lo.trim().to_string(),
        hi: hi.trim().to_string(),
    })
}

fn cells(names: &[String]) -> Result<Vec<Cell>, CliError> {
    let mut out: Vec<Cell> = Vec::new();
    for n in names {
        let c = Cell::ALL
            .into_iter()
            .find(|c| c.name() == n)
            .ok_or_else(|| {
                CliError::usage(format!(
                    "--sets: unknown set `{n}` (known: {})",
                    Cell::ALL.map(|c| c.name()).join(", ")
                ))
            })?;
        if !out.contains(&c) {
            out.push(c);
        }
    }
    Ok(out)
}

pub fn run_params(args: &ParamsArgs) -> CliResult {
    let overrides = args
        .params
        .iter()
        .map(|t| parse_assignment(t).map_err(CliError::usage))
        .collect::<Result<Vec<_>, _>>()?;
    let source = match (&args.source.scene, &args.source.scene_file) {
        (Some(name), _) => Source::by_name(name).map_err(CliError::usage)?,
        (None, Some(path)) => Source::File(SceneText::read(path).map_err(CliError::usage)?),
        (None, None) => return Err(CliError::usage("give --scene NAME or --scene-file FILE")),
    };
    if matches!(source, Source::File(_)) {
        super::one_reading(args.variant)?;
    }
    let mut axes = vec![axis("--x", &args.x)?];
    if let Some(y) = &args.y {
        axes.push(axis("--y", y)?);
    }
    let dims = axes.len();
    let family = Family::new(source, args.variant, overrides, axes).map_err(CliError::usage)?;
    let cells = cells(&args.sets)?;
    let eps = args.eps.unwrap_or(if dims == 1 {
        2f64.powi(-34)
    } else {
        1.0 / 256.0
    });
    let opts = SearchOptions {
        eps,
        max_boxes: args.max_boxes,
        decide: DecideOptions::default(),
        shard: args.shard,
    };
    if args.shard.is_some() && !args.json && args.out.is_none() {
        return Err(CliError::usage(
            "--shard writes a part for `detach merge`: give --json or --out DIR",
        ));
    }
    if args.shard.is_some() && args.proof.is_some() {
        return Err(CliError::usage(
            "--proof states a whole atlas: run without --shard",
        ));
    }
    let levels = (dims as f64 * (1.0 / eps).log2().ceil().clamp(0.0, 1100.0)) as u64 + 1;
    let bar = ProgressBar::new(levels);
    bar.set_style(
        ProgressStyle::with_template("{prefix:>14} [{bar:30}] level {pos}/{len} {elapsed} {msg}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_prefix(family.base.name().to_string());
    bar.enable_steady_tick(std::time::Duration::from_millis(500));
    let start = Instant::now();
    let run = search(&family, &cells, &opts, |level, open, boxes| {
        bar.set_position(level as u64);
        bar.set_message(format!("{open} open, {boxes} boxes"));
    })
    .map_err(CliError::usage)?;
    bar.finish_and_clear();
    let elapsed_s = start.elapsed().as_secs_f64();
    let shard = args.shard.map(|s| (s.k, s.n));
    let json = atlas_json(&family, &run, eps, shard);
    let text = serde_json::to_string_pretty(&json).expect("serialisable");
    if let Some(dir) = &args.out {
        std::fs::create_dir_all(dir).map_err(|e| super::cannot_write(dir, e))?;
        let path = dir.join("params.json");
        detach::files::write_atomic(&path, format!("{text}\n").as_bytes())
            .map_err(|e| super::cannot_write(&path, e))?;
        if dims == 2 && shard.is_none() {
            let stem = dir.join("params");
            detach::figures::params::write_param_plane(&family, &run.atlas, &stem)
                .map_err(CliError::runtime)?;
        }
    }
    if let Some(path) = &args.proof {
        write_proof(path, &family, &run.atlas)?;
    }
    if args.json {
        outln!("{text}");
    } else {
        print_table(&family, &run.atlas, &json, run.complete, elapsed_s);
    }
    Ok(())
}

/// The proof file of an atlas, written once the checker accepts it.
fn write_proof(path: &std::path::Path, family: &Family, atlas: &ParamAtlas) -> CliResult {
    let statement = detach::certificate::params::ParamAtlasStatement {
        scene: &family.base,
        variant: family.variant,
        params: &family.params,
        title: format!(
            "{}: parameter atlas over {}",
            family.base.name(),
            atlas
                .axes
                .iter()
                .map(|a| format!("{} in [{}, {}]", a.name, a.lo, a.hi))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    let proof = detach::certificate::params::param_atlas_proof(&statement, atlas)
        .map_err(CliError::runtime)?;
    super::write_checked(path, &proof)?;
    Ok(())
}

fn print_table(
    family: &Family,
    atlas: &ParamAtlas,
    json: &serde_json::Value,
    complete: bool,
    elapsed_s: f64,
) {
    let names: Vec<String> = atlas
        .axes
        .iter()
        .map(|a| format!("{} in [{}, {}]", a.name, a.lo, a.hi))
        .collect();
    outln!(
        "{}{}: {} ({} boxes, {:.2} s{})",
        family.base.name(),
        super::reading(family.base.id().map(|_| family.variant)),
        names.join(", "),
        atlas.leaves.iter().filter(|l| !l.bounds.is_empty()).count(),
        elapsed_s,
        if complete {
            ""
        } else {
            "; box budget reached: coarser result"
        }
    );
    let root: Vec<f64> = family.root.iter().map(|r| r[1] - r[0]).collect();
    for (k, set) in atlas.sets.iter().enumerate() {
        let mut share = [0.0f64; 3];
        for leaf in atlas.leaves.iter().filter(|l| !l.bounds.is_empty()) {
            let frac: f64 = leaf
                .bounds
                .iter()
                .zip(&root)
                .map(|(b, w)| (b[1] - b[0]) / w)
                .product();
            let i = match &leaf.sets[k] {
                SetStatus::Nonempty { .. } => 0,
                SetStatus::Empty { .. } => 1,
                SetStatus::Undecided { .. } => 2,
            };
            share[i] += frac;
        }
        let label = Cell::ALL
            .into_iter()
            .find(|c| c.name() == set)
            .map(|c| c.label())
            .unwrap_or("");
        outln!(
            "  {set:<26} {label:<6} nonempty {:>6.2} %, empty {:>6.2} %, undecided {:>6.2} % of the box",
            100.0 * share[0],
            100.0 * share[1],
            100.0 * share[2]
        );
    }
    for t in json["thresholds"].as_array().into_iter().flatten() {
        let s = |k: &str| t[k].as_str().unwrap_or_default().to_string();
        let e = &t["enclosure"];
        outln!(
            "  {}: {} for {} <= {}, {} for {} >= {} (on the boxes up to and from there)",
            s("set"),
            s("below"),
            s("param"),
            e[0].as_str().unwrap_or_default(),
            s("above"),
            s("param"),
            e[1].as_str().unwrap_or_default()
        );
    }
}

pub fn run_merge(args: &MergeArgs) -> CliResult {
    let mut parts = Vec::new();
    for p in &args.parts {
        let bytes = std::fs::read(p).map_err(|e| {
            CliError::usage(format!("cannot read {}: {e}", detach::files::shown(p)))
        })?;
        let v: serde_json::Value = serde_json::from_slice(&bytes)
            .map_err(|e| CliError::usage(format!("{}: not JSON: {e}", detach::files::shown(p))))?;
        parts.push(v);
    }
    let joined = merge(&parts).map_err(CliError::usage)?;
    let text = serde_json::to_string_pretty(&joined).expect("serialisable");
    match &args.out {
        Some(path) => detach::files::write_atomic(path, format!("{text}\n").as_bytes())
            .map_err(|e| super::cannot_write(path, e))?,
        None => outln!("{text}"),
    }
    Ok(())
}
