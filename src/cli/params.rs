//! `detach params`: a certified parameter atlas; `detach merge`: the join
//! of a sharded run's parts.

use super::{CliError, CliResult};
use detach::api::{Cell, ParamAtlasRun, ParamRequest, Shard, Variant};
use detach::params::report::merge;
use std::path::PathBuf;

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

fn cells(names: &[String]) -> Result<Vec<Cell>, CliError> {
    names
        .iter()
        .map(|n| {
            Cell::ALL
                .into_iter()
                .find(|c| c.name() == n)
                .ok_or_else(|| {
                    CliError::usage(format!(
                        "--sets: unknown set `{n}` (known: {})",
                        Cell::ALL.map(|c| c.name()).join(", ")
                    ))
                })
        })
        .collect()
}

pub fn run_params(args: &ParamsArgs) -> CliResult {
    let overrides = super::parse_overrides(&args.params)?;
    let problem = args.source.problem(&overrides, args.variant)?;
    let axis = |flag: &str, text: &str| {
        ParamRequest::axis(text).map_err(|e| CliError::usage(format!("{flag}: {e}")))
    };
    let mut axes = vec![axis("--x", &args.x)?];
    if let Some(y) = &args.y {
        axes.push(axis("--y", y)?);
    }
    let req = ParamRequest {
        axes,
        sets: cells(&args.sets)?,
        eps: args.eps,
        max_boxes: args.max_boxes,
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
    let dims = req.axes.len();
    let levels =
        (dims as f64 * (1.0 / req.resolution()).log2().ceil().clamp(0.0, 1100.0)) as u64 + 1;
    let bar = super::progress_bar(levels, problem.scene.name());
    bar.enable_steady_tick(std::time::Duration::from_millis(500));
    let atlas = problem.param_atlas_with_progress(&req, |level, open, boxes| {
        bar.set_position(level as u64);
        bar.set_message(format!("{open} open, {boxes} boxes"));
    });
    bar.finish_and_clear();
    let atlas = atlas?;
    let json = atlas.json();
    let text = serde_json::to_string_pretty(&json).expect("serialisable");
    if let Some(dir) = &args.out {
        std::fs::create_dir_all(dir).map_err(|e| super::cannot_write(dir, e))?;
        let path = dir.join("params.json");
        detach::files::write_atomic(&path, format!("{text}\n").as_bytes())
            .map_err(|e| super::cannot_write(&path, e))?;
        if dims == 2 && args.shard.is_none() {
            let stem = dir.join("params");
            detach::figures::params::write_param_plane(&atlas.family, &atlas.run.atlas, &stem)
                .map_err(CliError::runtime)?;
        }
    }
    if let Some(path) = &args.proof {
        super::write_checked(path, &atlas.proof()?)?;
    }
    if args.json {
        outln!("{text}");
    } else {
        print_table(&atlas, &json);
    }
    Ok(())
}

fn print_table(atlas: &ParamAtlasRun, json: &serde_json::Value) {
    let family = &atlas.family;
    outln!(
        "{}{}: {} ({} boxes, {:.2} s{})",
        family.base.name(),
        super::reading(family.base.id().map(|_| family.variant)),
        atlas.ranges(),
        atlas
            .run
            .atlas
            .leaves
            .iter()
            .filter(|l| !l.bounds.is_empty())
            .count(),
        atlas.elapsed_s,
        if atlas.run.complete {
            ""
        } else {
            "; box budget reached: coarser result"
        }
    );
    for share in atlas.shares() {
        let set = &share.set;
        let label = Cell::ALL
            .into_iter()
            .find(|c| c.name() == set)
            .map(|c| c.label())
            .unwrap_or("");
        outln!(
            "  {set:<26} {label:<6} nonempty {:>6.2} %, empty {:>6.2} %, undecided {:>6.2} % of the box",
            100.0 * share.nonempty,
            100.0 * share.empty,
            100.0 * share.undecided
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
