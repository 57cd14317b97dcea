//! `detach flow`: a certified trajectory of a scene's `[dynamics]`.

use super::{parse_overrides, CliError, CliResult, SceneSource};
use detach::motion::{flow, FlowRequest, Tube, Until};
use detach::scene::Variant;
use inari::Interval;
use serde_json::{json, Value};

/// Integrate θ̈ of a scene's `[dynamics]` in validated arithmetic from a
/// state (or a box of states) over [0, T], stopping at the first event.
#[derive(clap::Args, Debug)]
pub struct FlowArgs {
    #[command(flatten)]
    pub source: SceneSource,
    /// Scene parameter override, repeatable (decimal text, enclosed).
    #[arg(long = "param", value_name = "NAME=VALUE", allow_hyphen_values = true)]
    pub params: Vec<String>,
    /// The initial state `THETA,THETA_DOT` (decimal text, `pi/N`).
    #[arg(
        long,
        value_name = "THETA,THETA_DOT",
        allow_hyphen_values = true,
        conflicts_with = "from_box"
    )]
    pub from: Option<String>,
    /// A box of initial states `TLO:THI,WLO:WHI`.
    #[arg(
        long = "from-box",
        value_name = "TLO:THI,WLO:WHI",
        allow_hyphen_values = true
    )]
    pub from_box: Option<String>,
    /// The end time (decimal text, > 0).
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub t: String,
    /// What ends the run before T, comma-separated: `U=0` (Ω's boundary),
    /// `N=0` (Ω₀'s: the reaction vanishes), `V=0` (the singular line where
    /// θ̈'s denominator vanishes), `cell` (all three), `domain`, `none`.
    #[arg(long, default_value = "cell,domain")]
    pub until: String,
    /// Order of the Taylor method.
    #[arg(long, default_value_t = 20)]
    pub order: usize,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Also write the run as a `trajectory` proof file (checked before it
    /// is written; `detach verify` or `detach-check` re-checks it).
    #[arg(long, value_name = "FILE")]
    pub proof: Option<std::path::PathBuf>,
}

pub fn run_flow(args: &FlowArgs) -> CliResult {
    let overrides = parse_overrides(&args.params)?;
    let problem = args.source.problem(&overrides, Variant::Derived)?;
    let file = problem.scene.reading(Variant::Derived);
    let state = match (&args.from, &args.from_box) {
        (Some(s), None) | (None, Some(s)) => s,
        _ => {
            return Err(CliError::usage(
                "give --from THETA,THETA_DOT or --from-box TLO:THI,WLO:WHI",
            ))
        }
    };
    let Some((theta, theta_dot)) = state.split_once(',') else {
        return Err(CliError::usage(format!(
            "the initial state must be THETA,THETA_DOT, got `{state}`"
        )));
    };
    if args.from.is_some() && (theta.contains(':') || theta_dot.contains(':')) {
        return Err(CliError::usage(
            "--from takes a point; a box is --from-box TLO:THI,WLO:WHI",
        ));
    }
    detach::api::flow_order(args.order)?;
    let mut request = FlowRequest::parse(theta, theta_dot, &args.t).map_err(CliError::usage)?;
    request.until = Until::parse_list(&args.until).map_err(CliError::usage)?;
    request.settings.order = args.order;
    let tube = match &args.proof {
        None => flow(file, &request).map_err(CliError::usage)?,
        Some(path) => {
            let (tube, proof) = problem
                .flow_with_proof(&request, &args.t)
                .map_err(|e| CliError::runtime(format!("no proof written: {e}")))?;
            let (bytes, _, units) = super::write_checked(path, &proof)?;
            eprintln!(
                "wrote {} ({bytes} B, {units}, checked VALID)",
                detach::files::shown(path)
            );
            tube
        }
    };
    if args.json {
        let mut out = tube.json(&args.t);
        out["detach"] = detach::provenance();
        out["arguments"] = json!({
            "scene": args.source.scene, "scene_file": args.source.scene_file,
            "params": args.params, "from": args.from, "from_box": args.from_box,
            "t": args.t, "until": args.until, "order": args.order,
        });
        out["parameters"] = problem
            .params
            .texts()
            .into_iter()
            .map(|(k, v)| (k.to_string(), json!(v)))
            .collect::<serde_json::Map<String, Value>>()
            .into();
        outln!(
            "{}",
            serde_json::to_string_pretty(&out).map_err(|e| CliError::runtime(e.to_string()))?
        );
    } else {
        print_table(&tube);
    }
    super::stdout_status()
}

fn print_table(tube: &Tube) {
    let enc = |x: Interval| {
        format!(
            "[{:.17e}, {:.17e}]  (width {:.1e})",
            x.inf(),
            x.sup(),
            x.wid()
        )
    };
    outln!("{} certified steps; {}", tube.len(), tube.stop_text());
    for e in &tube.events {
        outln!("event {}:", e.kind);
        outln!("  t        {}", enc(e.time));
        outln!("  θ        {}", enc(e.theta));
        outln!("  θ̇        {}", enc(e.theta_dot));
    }
    outln!("end:");
    outln!("  t        {}", enc(tube.end_time));
    outln!("  θ        {}", enc(tube.end[0]));
    outln!("  θ̇        {}", enc(tube.end[1]));
}
