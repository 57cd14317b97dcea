//! `detach stability`: where each paving method fails. A map per scene of
//! where the undecided area concentrates for every method, and a table of
//! every method on stress cases (what each decides, at what cost, where it
//! stalls).

use super::machine;
use super::{CliError, CliResult};
use detach::certificate::numbers::{decimal, Round};
use detach::figures::stability::{draw_stability_map, StabilityPanel};
use detach::pave::stability::{method_maps, run_stress_cases, stress_cases};
use detach::pave::StopReason;
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

pub fn run_stability(args: &StabilityArgs) -> CliResult {
    let opts = detach::api::pave_options(args.eps, args.max_boxes)?;
    let cases = stress_cases().map_err(CliError::usage)?;
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::runtime(format!("cannot create {}: {e}", args.out.display())))?;
    let machine = machine();

    // Maps: every scene (derived, defaults) over its whole domain.
    let mut maps = Vec::new();
    let mut files = Vec::new();
    for map in method_maps(opts).map_err(CliError::usage)? {
        let name = map.id.name();
        let panels: Vec<StabilityPanel> = map
            .runs
            .iter()
            .zip(&map.undecided)
            .map(|((r, p), u)| {
                // Certified upper bounds, printed rounded up.
                let up = |a: f64| decimal(a, 3, Round::Up);
                StabilityPanel {
                    title: r.method.name().to_string(),
                    notes: vec![
                        format!(
                            "undecided area ≤ {} in Ω, ≤ {} in Ω_{{0}}",
                            up(u[0]),
                            up(u[1])
                        ),
                        format!("{} leaves, {:.3} s, {}", r.leaves, r.seconds, r.stop),
                    ],
                    paving: p,
                }
            })
            .collect();
        let svg = args.out.join(format!("stability-{name}.svg"));
        let png = args.out.join(format!("stability-{name}.png"));
        let title = format!(
            "Where each method stalls: {name} (derived, defaults, Ω and Ω_{{0}} refined), eps = {}",
            args.eps
        );
        draw_stability_map(&panels, &title, &svg, &png)
            .map_err(|e| CliError::runtime(format!("drawing {}: {e}", svg.display())))?;
        files.push(svg);
        files.push(png);
        for (r, _) in &map.runs {
            maps.push(MapRun {
                scene: name,
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
    let rows = run_stress_cases(&cases, opts).map_err(CliError::usage)?;

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
        "cases": cases.iter().map(|c| c.to_json()).collect::<Vec<_>>(),
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
