//! Validated integration: detach's tubes against Codac's `CtcLohner` on
//! the same ODEs, point starts, one thread.
//!
//! Codac's side is re-run first (`benches/peers/codac_lohner.py`, into
//! `benches/peers/codac-lohner.json`; the stored file is kept, and the
//! table says when it was made, when Python or Codac is missing): a ratio
//! holds only for two runs on the machine in the same state. Then each case
//! is integrated by detach at its default settings and over a ladder of
//! coarser ones, and the table `docs/performance/motion.md` gives, per case:
//! detach's default time and end width; Codac's narrowest bounded run; the
//! time ratio at equal end width (Codac's narrowest run against detach's
//! fastest setting at least as narrow); and the width ratio at equal time
//! (Codac's fastest bounded run, which takes longer than detach's default,
//! against detach's default). `cargo bench --bench motion -- --stored`
//! skips the Codac run.

#[path = "support/timing.rs"]
mod timing;

use detach::api::{PaveRequest, Problem};
use detach::figures::{
    atlas_portrait, phase_portrait_px, plot_area_pixels, AtlasStyle, LINE_SPACING,
};
use detach::motion::{flow, FlowRequest, FlowSettings};
use detach::scene::{Scene, Variant};
use serde_json::Value;
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::Path;
use std::process::{Command, Stdio};
use timing::{load, seconds, utc_now, Group};

const PEER_FILE: &str = "benches/peers/codac-lohner.json";
const PEER_SCRIPT: &str = "benches/peers/codac_lohner.py";

/// Re-runs Codac's side into `PEER_FILE`; keeps the stored file (and says
/// so) when that fails.
fn rerun_codac() {
    eprintln!("running {PEER_SCRIPT} (Codac's side, a few minutes)");
    let kept = |why: String| eprintln!("{why}: reading the stored {PEER_FILE}");
    match Command::new("python3")
        .arg(PEER_SCRIPT)
        .stderr(Stdio::inherit())
        .output()
    {
        Ok(o) if o.status.success() => {
            let fresh =
                serde_json::from_slice::<Value>(&o.stdout).is_ok_and(|d| d["cases"].is_array());
            if !fresh {
                kept(format!("{PEER_SCRIPT} wrote no cases"));
            } else if let Err(e) = std::fs::write(PEER_FILE, &o.stdout) {
                kept(format!("cannot write {PEER_FILE}: {e}"));
            }
        }
        Ok(o) => kept(format!("{PEER_SCRIPT} failed ({})", o.status)),
        Err(e) => kept(format!("python3 did not start ({e})")),
    }
}

/// A Codac run: time (s) and end width, bounded runs only.
struct PeerRun {
    dt: f64,
    seconds: f64,
    width: f64,
}

fn peer_runs(case: &Value) -> Vec<PeerRun> {
    case["runs"]
        .as_array()
        .map(|runs| {
            runs.iter()
                .filter(|r| r["bounded"].as_bool() == Some(true))
                .filter_map(|r| {
                    Some(PeerRun {
                        dt: r["dt"].as_f64()?,
                        seconds: r["time_s"].as_f64()?,
                        width: r["max_width"].as_f64()?,
                    })
                })
                .collect()
        })
        .unwrap_or_default()
}

/// detach's time (median, s) and end width for one case at `settings`.
fn detach_run(
    group: &Group,
    label: &str,
    scene: &Scene,
    request: &FlowRequest,
    settings: FlowSettings,
) -> Option<(f64, f64)> {
    let file = scene.reading(Variant::Derived);
    let mut request = request.clone();
    request.settings = settings;
    let tube = flow(file, &request).ok()?;
    if tube.stop != detach::motion::Stop::End {
        return None;
    }
    let width = tube.end[0].wid().max(tube.end[1].wid());
    let time = group.bench(label, || {
        flow(black_box(file), black_box(&request)).map(|t| t.len())
    })?;
    Some((time, width))
}

/// Coarser settings than the default, cheapest last: (order, tolerance).
const LADDER: [(usize, f64); 6] = [
    (16, 1e-14),
    (12, 1e-12),
    (10, 1e-10),
    (8, 1e-8),
    (6, 1e-6),
    (4, 1e-4),
];

fn main() {
    if !std::env::args().any(|a| a == "--stored") {
        rerun_codac();
    }
    let peers: Value = std::fs::read_to_string(PEER_FILE)
        .ok()
        .and_then(|t| serde_json::from_str(&t).ok())
        .unwrap_or(Value::Null);
    let load_before = load();
    let group = Group::new("motion").samples(15);
    let mut md = String::new();
    let _ = writeln!(
        md,
        "# Validated integration: detach against Codac's CtcLohner\n\n\
         Made by `cargo bench --bench motion` (see `benches/motion.rs`), run at {}; \
         load average before: {load_before}. Codac {} (`{PEER_SCRIPT}`, run at {}, \
         load average before: {}). One thread, point starts, the same ODEs and \
         parameters; widths are the larger of θ's and θ̇'s at the end time.\n\n\
         | case | t | detach: time, width | Codac narrowest: dt, time, width | \
         time ratio at equal width | width ratio at equal time |\n|---|---|---|---|---|---|",
        utc_now(),
        peers["codac_version"].as_str().unwrap_or("?"),
        peers["date"].as_str().unwrap_or("?"),
        peers["machine"]["loadavg_before"]
            .as_array()
            .map(|l| l
                .iter()
                .filter_map(Value::as_f64)
                .map(|x| format!("{x:.2}"))
                .collect::<Vec<_>>()
                .join(" "))
            .unwrap_or_default(),
    );
    for case in peers["cases"].as_array().into_iter().flatten() {
        let name = case["name"].as_str().unwrap_or("?");
        let t_end = case["t_end"].as_f64().unwrap_or(0.0);
        let params: Vec<(String, String)> = case["params"]
            .as_object()
            .map(|m| {
                m.iter()
                    .filter_map(|(k, v)| Some((k.clone(), v.as_str()?.to_string())))
                    .collect()
            })
            .unwrap_or_default();
        let Ok((scene, _)) = Scene::by_name(case["scene"].as_str().unwrap_or(""), &params) else {
            eprintln!("{name}: unknown scene");
            continue;
        };
        let from = |i: usize| case["from"][i].as_str().unwrap_or("").to_string();
        let Ok(mut request) = FlowRequest::parse(&from(0), &from(1), &t_end.to_string()) else {
            eprintln!("{name}: bad start");
            continue;
        };
        request.until = vec![];
        let label = format!("{name}_t{t_end}");
        let Some((time, width)) =
            detach_run(&group, &label, &scene, &request, FlowSettings::default())
        else {
            eprintln!("{label}: detach's run did not reach the end time");
            continue;
        };
        println!("{label}: default settings, end width {width:.1e}");
        let runs = peer_runs(case);
        let narrowest = runs.iter().min_by(|a, b| a.width.total_cmp(&b.width));
        let fastest = runs.iter().min_by(|a, b| a.seconds.total_cmp(&b.seconds));
        let (Some(narrowest), Some(fastest)) = (narrowest, fastest) else {
            let _ = writeln!(
                md,
                "| {name} | {t_end} | {}, {width:.1e} | no bounded run | | |",
                seconds(time)
            );
            continue;
        };
        // detach's fastest setting whose width is at most Codac's narrowest.
        let mut at_width = (time, width);
        for (order, tolerance) in LADDER {
            let settings = FlowSettings {
                order,
                tolerance,
                ..FlowSettings::default()
            };
            let label = format!("{label}_K{order}_tol{tolerance:e}");
            match detach_run(&group, &label, &scene, &request, settings) {
                Some((t, w)) if w <= narrowest.width && t < at_width.0 => at_width = (t, w),
                _ => {}
            }
        }
        let _ = writeln!(
            md,
            "| {name} | {t_end} | {}, {width:.1e} | {}, {}, {:.1e} | {:.0}× (detach {}, {:.1e}) | \
             {:.1e}× (Codac {}, {:.1e}) |",
            seconds(time),
            narrowest.dt,
            seconds(narrowest.seconds),
            narrowest.width,
            narrowest.seconds / at_width.0,
            seconds(at_width.0),
            at_width.1,
            fastest.width / width,
            seconds(fastest.seconds),
            fastest.width,
        );
    }
    let _ = writeln!(
        md,
        "\nLoad average after: {}. Codac's runs that blew up (infinite end boxes) \
         are left out; the JSON keeps them.",
        load()
    );
    atlas_portraits(&mut md);
    let out = Path::new("docs/performance/motion.md");
    match std::fs::write(out, &md) {
        Ok(()) => println!("wrote {}", out.display()),
        Err(e) => eprintln!("cannot write {}: {e}", out.display()),
    }
    print!("{md}");
}

/// The atlas's portrait: certified tubes against the `f64` curves they
/// replace, each beside the paving of the same atlas (default size, its
/// one-pixel eps), on the machine's threads as `detach atlas` runs them.
fn atlas_portraits(md: &mut String) {
    let group = Group::new("atlas-portrait").samples(5);
    let style = AtlasStyle::default();
    let px = plot_area_pixels(&style);
    let eps = (1.0 / px.0.max(px.1) as f64).log2().floor().exp2();
    let _ = writeln!(
        md,
        "\n## The atlas's portrait\n\nPer shipped scene at the default atlas size \
         ({}×{} plot pixels, eps = {eps}): the paving, the certified tubes and the \
         `f64` curves they replace (median seconds, {} threads). Load average before: {}.\n\n\
         | scene | paving | certified tubes | f64 curves | atlas with tubes / with f64 curves |\n\
         |---|---|---|---|---|",
        px.0,
        px.1,
        rayon::current_num_threads(),
        load()
    );
    for name in ["painleve-rod", "viscous-disc", "smooth-disc", "ice-disc"] {
        let Ok(problem) = Problem::load(name, &[]) else {
            continue;
        };
        let req = PaveRequest {
            eps,
            ..PaveRequest::default()
        };
        let Some(pave) = group.bench(&format!("{name}_paving"), || problem.pave(&req).ok()) else {
            continue;
        };
        let Ok(paved) = problem.pave(&req) else {
            continue;
        };
        let root = paved.paving.root;
        let spacing = LINE_SPACING;
        let Some(tubes) = group.bench(&format!("{name}_tubes"), || {
            atlas_portrait(&problem.scene, problem.variant, &root, px, spacing)
                .curves
                .len()
        }) else {
            continue;
        };
        let Some(curves) = group.bench(&format!("{name}_f64"), || {
            phase_portrait_px(&problem.scene, problem.variant, &root, px, spacing).len()
        }) else {
            continue;
        };
        let _ = writeln!(
            md,
            "| {name} | {} | {} | {} | {:.2} |",
            seconds(pave),
            seconds(tubes),
            seconds(curves),
            (pave + tubes) / (pave + curves)
        );
    }
}
