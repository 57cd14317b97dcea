//! `detach reach`: the initial states of a window from which the motion
//! reaches a target within a time, as a certified paving.

use super::atlas::{as_refs, split_window, windowed_domain};
use super::{CliError, CliResult, SceneSource};
use detach::figures::reach::{write_reach_plane, ReachCaption};
use detach::motion::reach::{Fate, ReachOptions, ReachRun};
use detach::motion::{interval_json, Until};
use detach::params::report::exact_decimal;
use detach::scene::Variant;
use serde_json::json;
use std::ops::ControlFlow;

/// Pave a window of initial states by whether the motion reaches a target
/// (the first event of `--until`) within `--t`: proved to reach, proved to
/// avoid, undecided.
#[derive(clap::Args, Debug)]
pub struct ReachArgs {
    #[command(flatten)]
    pub source: SceneSource,
    /// Scene parameter override, repeatable (decimal text, enclosed).
    #[arg(long = "param", value_name = "NAME=VALUE", allow_hyphen_values = true)]
    pub params: Vec<String>,
    /// θ window of the initial states (default: the domain).
    #[arg(long, value_name = "LO:HI", allow_hyphen_values = true)]
    pub theta: Option<String>,
    /// θ̇ window of the initial states (default: the domain).
    #[arg(long = "theta-dot", value_name = "LO:HI", allow_hyphen_values = true)]
    pub theta_dot: Option<String>,
    /// The time within which the target is to be reached (decimal text).
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub t: String,
    /// The target, comma-separated: `U=0`, `N=0` (detachment onset), `V=0`
    /// (the singular line), `cell` (leaving the start cell), `domain`.
    #[arg(long, default_value = "cell")]
    pub until: String,
    /// Boxes narrower than this fraction of the window per axis are not
    /// split.
    #[arg(long, default_value_t = 1.0 / 256.0)]
    pub eps: f64,
    /// Most leaves; a run that reaches it writes its coarser result.
    #[arg(long = "max-boxes", default_value_t = 100_000)]
    pub max_boxes: usize,
    /// Print JSON (with every leaf) instead of a summary.
    #[arg(long)]
    pub json: bool,
    /// Also write the paving as a `reach` proof file (checked before it is
    /// written; `detach verify` or `detach-check` re-checks it).
    #[arg(long, value_name = "FILE")]
    pub proof: Option<std::path::PathBuf>,
    /// Also draw the paving to FILE (`.svg` or `.png`): boxes proved to
    /// reach, proved to avoid, undecided.
    #[arg(long, value_name = "FILE")]
    pub picture: Option<std::path::PathBuf>,
}

pub fn run_reach(args: &ReachArgs) -> CliResult {
    let overrides = super::parse_overrides(&args.params)?;
    let problem = args.source.problem(&overrides, Variant::Derived)?;
    let scene = &problem.scene;
    if let Some(path) = &args.picture {
        if !matches!(
            path.extension().and_then(|e| e.to_str()),
            Some("svg" | "png")
        ) {
            return Err(CliError::usage(format!(
                "--picture must name a .svg or .png file, got {}",
                path.display()
            )));
        }
    }
    let until = Until::parse_list(&args.until).map_err(detach::api::Error::from)?;
    let th = split_window("theta", &args.theta)?;
    let thd = split_window("theta-dot", &args.theta_dot)?;
    // The clipping notes, once.
    windowed_domain(scene, &th, &thd)?;
    let opts = ReachOptions {
        eps: args.eps,
        max_boxes: args.max_boxes,
        ..ReachOptions::default()
    };
    let levels = (2.0 * (1.0 / args.eps).log2().ceil()).clamp(0.0, 4096.0) as u64 + 1;
    let bar = super::progress_bar(levels, scene.name());
    bar.enable_steady_tick(std::time::Duration::from_millis(500));
    let run = problem.reach_with_progress(
        as_refs(&th),
        as_refs(&thd),
        &args.t,
        &until,
        &opts,
        |depth, open, leaves| {
            bar.set_position(depth as u64);
            bar.set_message(format!("{open} open, {leaves} leaves"));
            ControlFlow::Continue(())
        },
    );
    bar.finish_and_clear();
    let run = run?;
    if !run.complete {
        eprintln!(
            "detach: note: the box budget (--max-boxes {}) ended the paving; the open boxes \
             are undecided",
            args.max_boxes
        );
    }
    if let Some(path) = &args.proof {
        let (proof, dropped) = problem
            .reach_proof(&run, &args.t, &until, &opts)
            .map_err(|e| {
                CliError::runtime(format!("no proof written: {}", e.naming(super::flag)))
            })?;
        let (bytes, _, units) = super::write_checked(path, &proof)?;
        eprintln!(
            "wrote {} ({bytes} B, {units}, checked VALID)",
            detach::files::shown(path)
        );
        if dropped > 0 {
            eprintln!(
                "detach: note: {dropped} decided boxes are stated undecided in the proof \
                 (their certificates need more room than a checker is given)"
            );
        }
    }
    if let Some(path) = &args.picture {
        let caption = ReachCaption {
            scene: scene.name(),
            target: &args.until,
            t: &args.t,
        };
        write_reach_plane(&run, &caption, path).map_err(CliError::runtime)?;
        eprintln!("wrote {}", detach::files::shown(path));
    }
    if args.json {
        let doc = run_json(&run, args);
        outln!("{}", serde_json::to_string_pretty(&doc).expect("JSON"));
    } else {
        print_summary(&run, args);
    }
    super::stdout_status()
}

fn counts(run: &ReachRun) -> [usize; 3] {
    let mut c = [0; 3];
    for l in &run.leaves {
        c[match l.fate {
            Fate::Reaches(_) => 0,
            Fate::Avoids => 1,
            Fate::Undecided(_) => 2,
        }] += 1;
    }
    c
}

fn run_json(run: &ReachRun, args: &ReachArgs) -> serde_json::Value {
    let (inner, outer) = run.area_bounds();
    let [reaches, avoids, undecided] = counts(run);
    json!({
        "detach": detach::provenance(),
        "arguments": {
            "scene": args.source.scene, "scene_file": args.source.scene_file,
            "params": args.params, "theta": args.theta, "theta_dot": args.theta_dot,
            "t": args.t, "until": args.until, "eps": args.eps, "max_boxes": args.max_boxes,
        },
        "window": run.window.map(|w| w.map(exact_decimal)),
        "complete": run.complete,
        "area": {"inner": exact_decimal(inner), "outer": exact_decimal(outer)},
        "boxes": {"reaches": reaches, "avoids": avoids, "undecided": undecided},
        "leaves": run.leaves.iter().map(|l| {
            let (fate, extra) = match &l.fate {
                Fate::Reaches(t) => ("reaches", json!({"time": interval_json(*t)})),
                Fate::Avoids => ("avoids", json!({})),
                Fate::Undecided(why) => ("undecided", json!({"reason": why})),
            };
            let mut leaf = json!({
                "theta": l.theta.map(exact_decimal), "theta_dot": l.theta_dot.map(exact_decimal),
                "fate": fate,
            });
            if let (Some(m), Some(e)) = (leaf.as_object_mut(), extra.as_object()) {
                m.extend(e.clone());
            }
            leaf
        }).collect::<Vec<_>>(),
    })
}

fn print_summary(run: &ReachRun, args: &ReachArgs) {
    let (inner, outer) = run.area_bounds();
    let [reaches, avoids, undecided] = counts(run);
    let w = run.window;
    outln!(
        "initial states in θ ∈ [{}, {}], θ̇ ∈ [{}, {}] reaching `{}` within t = {}:",
        w[0][0],
        w[0][1],
        w[1][0],
        w[1][1],
        args.until,
        args.t
    );
    outln!("  area in [{inner:.6e}, {outer:.6e}]");
    outln!("  boxes: {reaches} reach, {avoids} avoid, {undecided} undecided");
    let mut reasons: Vec<(&str, usize)> = Vec::new();
    for l in &run.leaves {
        if let Fate::Undecided(why) = &l.fate {
            match reasons.iter_mut().find(|(r, _)| *r == why.as_str()) {
                Some((_, n)) => *n += 1,
                None => reasons.push((why, 1)),
            }
        }
    }
    reasons.sort_by_key(|r| std::cmp::Reverse(r.1));
    for (why, n) in reasons.iter().take(5) {
        outln!("  undecided ({n}): {why}");
    }
}
