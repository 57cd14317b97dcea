//! `detach methods`: every paving method on the same work over a range of ε,
//! a table, JSON, and the speed–accuracy chart with the peers' curves.

use super::{CliError, CliResult};
use detach::atlas::chart::{draw_speed_accuracy, Curve, Panel};
use detach::param::enclose_decimal;
use detach::pave::{run_method, Method};
use detach::pave::{standard_cells, Leaf, Node, PaveOptions};
use detach::scene::{Domain, Scene, SceneId, Variant, PI};
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct MethodsArgs {
    /// Output directory (methods.json, methods.svg, methods.png).
    #[arg(long, default_value = "out/methods")]
    pub out: PathBuf,
    /// Resolutions to run (repeatable); default 2^-5 … 2^-15.
    #[arg(long, allow_negative_numbers = true)]
    pub eps: Vec<f64>,
    /// Only these methods (repeatable); default: every method.
    #[arg(long, value_name = "METHOD")]
    pub method: Vec<String>,
    /// Runs per point; the median time is reported.
    #[arg(long, default_value_t = 1)]
    pub repeat: usize,
    /// The peers' measurements (from `benches/peers/codac_peer.py`).
    #[arg(long, default_value = "benches/peers/codac.json")]
    pub peers: PathBuf,
    /// Most leaves per paving.
    #[arg(long, default_value_t = 4_000_000, value_parser = detach::param::parse_count)]
    pub max_boxes: usize,
}

/// One of the two peer problems of the chart.
struct Problem {
    key: &'static str,
    title: &'static str,
    scene: Scene,
    variant: Variant,
    domain: Domain,
    /// Index into [`standard_cells`].
    cell: usize,
    /// The same work as `detach pave` arguments, for the whole-process time
    /// (π − 0.05 there is the decimal just inside it; areas differ < 1e-14).
    cli: &'static [&'static str],
    region: &'static str,
}

fn problems() -> Result<Vec<Problem>, CliError> {
    let set = |p: &[(&str, &str)]| -> Vec<(String, String)> {
        p.iter()
            .map(|(a, b)| (a.to_string(), b.to_string()))
            .collect()
    };
    let (smooth, _) = Scene::build(
        SceneId::SmoothDisc,
        &set(&[
            ("g", "9.81"),
            ("a", "1"),
            ("A", "0.25"),
            ("p_phi", "1"),
            ("p_psi", "0.6"),
        ]),
    )
    .map_err(CliError::usage)?;
    let e = enclose_decimal("theta", "0.05").map_err(CliError::usage)?;
    let window = Domain {
        theta: [e, PI - e],
        theta_dot: smooth.domain().theta_dot,
    };
    let viscous = Scene::default_of(SceneId::ViscousDisc);
    let vd = viscous.domain();
    Ok(vec![
        Problem {
            key: "omega_2_8",
            title: "Ω of (2.8), p_φ=1, p_ψ=0.6, θ ∈ [0.05, π−0.05]",
            scene: smooth,
            variant: Variant::Printed,
            domain: window,
            cell: 0,
            cli: &[
                "--scene",
                "smooth-disc",
                "--variant",
                "printed",
                "--param",
                "g=9.81",
                "--param",
                "a=1",
                "--param",
                "A=0.25",
                "--param",
                "p_phi=1",
                "--param",
                "p_psi=0.6",
                "--theta",
                "0.05:3.0915926535897932",
            ],
            region: "omega",
        },
        Problem {
            key: "omega0_1_11",
            title: "Ω₀ of (1.11), Example 1 (printed, defaults)",
            scene: viscous,
            variant: Variant::Printed,
            domain: vd,
            cell: 1,
            cli: &["--scene", "viscous-disc", "--variant", "printed"],
            region: "omega0",
        },
    ])
}

#[derive(Serialize, Clone)]
struct Run {
    problem: &'static str,
    method: &'static str,
    eps: f64,
    undecided_area: f64,
    inner_area: f64,
    outer_area: f64,
    leaves: usize,
    box_evaluations: u64,
    slab_evaluations: u64,
    /// Median wall time of the paving call (s).
    time_s: f64,
    /// Median wall time of `detach pave … --json` as a whole process (s):
    /// start-up, scene, paving, area sums and output.
    process_s: f64,
    /// Memory of the result (leaves and tree nodes) per leaf, in bytes.
    bytes_per_leaf: f64,
    stop: detach::pave::StopReason,
}

#[derive(Serialize)]
struct Ratio {
    problem: &'static str,
    method: String,
    peer: String,
    undecided_area: f64,
    /// Peer time / detach time at this undecided area (log–log interpolation).
    speedup: f64,
}

/// A point whose first process takes under `CHEAP_S` seconds is spawned at
/// least `CHEAP_RUNS` times; the median is reported.
const CHEAP_S: f64 = 0.2;
const CHEAP_RUNS: usize = 5;

/// Wall time of `detach pave … --json` for one point, as a child process.
fn whole_process(p: &Problem, m: Method, eps: f64, max_boxes: usize) -> Result<f64, CliError> {
    let exe = std::env::current_exe()
        .map_err(|e| CliError::runtime(format!("cannot find this executable: {e}")))?;
    let start = Instant::now();
    let out = std::process::Command::new(exe)
        .arg("pave")
        .args(p.cli)
        .args(["--region", p.region, "--method", m.name(), "--json"])
        .arg(format!("--eps={eps}"))
        .arg(format!("--max-boxes={max_boxes}"))
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .output()
        .map_err(|e| CliError::runtime(format!("cannot run detach pave: {e}")))?;
    let t = start.elapsed().as_secs_f64();
    if !out.status.success() {
        return Err(CliError::runtime(format!(
            "detach pave failed: {}",
            String::from_utf8_lossy(&out.stderr)
        )));
    }
    Ok(t)
}

pub(super) fn machine() -> serde_json::Value {
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let uname = std::process::Command::new("uname")
        .arg("-a")
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default();
    serde_json::json!({
        "uname": uname,
        "nproc": std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1),
        "threads": rayon::current_num_threads(),
        "loadavg": load.split_whitespace().take(3).collect::<Vec<_>>().join(" "),
    })
}

/// On a curve of `(x, y)` points with y falling as x grows (time against
/// undecided area, or area against box count), the x where y = `u`, by
/// log–log interpolation between the two points around it.
fn x_at(points: &[(f64, f64)], u: f64) -> Option<f64> {
    let mut p: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|&(t, a)| t > 0.0 && a > 0.0)
        .collect();
    p.sort_by(|a, b| b.1.total_cmp(&a.1));
    p.windows(2).find_map(|w| {
        let ((t0, a0), (t1, a1)) = (w[0], w[1]);
        (a1 <= u && u <= a0 && a0 > a1).then(|| {
            let s = (u.ln() - a0.ln()) / (a1.ln() - a0.ln());
            (t0.ln() + s * (t1.ln() - t0.ln())).exp()
        })
    })
}

/// `(problem, label, (time, undecided area) points, (undecided area, boxes)
/// points)` of one peer curve.
type PeerCurve = (String, String, Vec<(f64, f64)>, Vec<(f64, f64)>);

#[derive(Serialize)]
struct LeafRatio {
    problem: &'static str,
    method: &'static str,
    peer: String,
    leaves: usize,
    undecided_area: f64,
    /// The peer's undecided area at the same number of boxes (log–log).
    peer_undecided_area: f64,
}

fn peer_curves(path: &PathBuf) -> (Vec<PeerCurve>, serde_json::Value) {
    let Ok(text) = std::fs::read_to_string(path) else {
        eprintln!(
            "detach: note: no peer data at {}; the chart shows detach only",
            path.display()
        );
        return (vec![], serde_json::Value::Null);
    };
    let Ok(doc) = serde_json::from_str::<serde_json::Value>(&text) else {
        eprintln!(
            "detach: warning: {} is not valid JSON; ignored",
            path.display()
        );
        return (vec![], serde_json::Value::Null);
    };
    let peer = doc["peer"].as_str().unwrap_or("peer").to_string();
    let mut out: Vec<PeerCurve> = Vec::new();
    for r in doc["runs"].as_array().into_iter().flatten() {
        let (Some(problem), Some(method), Some(t), Some(u)) = (
            r["problem"].as_str(),
            r["method"].as_str(),
            r["time_s"].as_f64(),
            r["undecided_area"].as_f64(),
        ) else {
            continue;
        };
        let label = format!("{peer} {method}");
        let boxes = r["boxes"].as_f64().map(|n| (u, n));
        match out.iter_mut().find(|c| c.0 == problem && c.1 == label) {
            Some(c) => {
                c.2.push((t, u));
                c.3.extend(boxes);
            }
            None => out.push((
                problem.to_string(),
                label,
                vec![(t, u)],
                boxes.into_iter().collect(),
            )),
        }
    }
    let meta = serde_json::json!({
        "file": path.display().to_string(),
        "version": doc["version"],
        "date": doc["date"],
        "machine": doc["machine"],
    });
    (out, meta)
}

pub fn run_methods(args: &MethodsArgs) -> CliResult {
    let eps: Vec<f64> = if args.eps.is_empty() {
        (5..=15).map(|k| 2f64.powi(-k)).collect()
    } else {
        args.eps.clone()
    };
    if let Some(e) = eps
        .iter()
        .find(|e| !(e.is_finite() && **e > 0.0 && **e <= 1.0))
    {
        return Err(CliError::usage(format!(
            "--eps must be a finite number in (0, 1], got {e}"
        )));
    }
    if args.repeat == 0 || args.max_boxes == 0 {
        return Err(CliError::usage(
            "--repeat and --max-boxes must be at least 1",
        ));
    }
    let methods: Vec<Method> = if args.method.is_empty() {
        Method::ALL.to_vec()
    } else {
        args.method
            .iter()
            .map(|m| m.parse().map_err(CliError::usage))
            .collect::<Result<_, _>>()?
    };
    let problems = problems()?;
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::runtime(format!("cannot create {}: {e}", args.out.display())))?;
    let machine = machine();
    outln!(
        "{:<12} {:<9} {:>10} {:>12} {:>9} {:>11} {:>8} {:>9} {:>10} {:>8}",
        "problem",
        "method",
        "eps",
        "undecided",
        "leaves",
        "box evals",
        "slabs",
        "pave (s)",
        "process(s)",
        "B/leaf"
    );
    let mut runs = Vec::new();
    for p in &problems {
        let cell = standard_cells()[p.cell];
        let uncovered = p.domain.uncovered_area_sup();
        for &m in &methods {
            for &e in &eps {
                let opts = PaveOptions {
                    eps: e,
                    max_boxes: args.max_boxes,
                };
                let mut times = Vec::new();
                let mut process = Vec::new();
                let mut last = None;
                for _ in 0..args.repeat {
                    process.push(whole_process(p, m, e, args.max_boxes)?);
                    // A cheap point is spawned more often (its median is
                    // then robust), as the peer script times its cheap ones.
                    while process.len() < CHEAP_RUNS && process[0] < CHEAP_S {
                        process.push(whole_process(p, m, e, args.max_boxes)?);
                    }
                    let start = Instant::now();
                    // Only the constraints of the problem's region are refined.
                    let (_, paving) =
                        run_method(&p.scene, p.variant, &p.domain, Some(p.cell), m, opts)
                            .map_err(CliError::usage)?;
                    times.push(start.elapsed().as_secs_f64());
                    last = Some(paving);
                }
                let paving = last.expect("repeat ≥ 1");
                times.sort_by(f64::total_cmp);
                process.sort_by(f64::total_cmp);
                let b = paving.area_bounds(&cell, uncovered);
                let bytes = paving.leaves.len() * std::mem::size_of::<Leaf>()
                    + paving.nodes.len() * std::mem::size_of::<Node>();
                let run = Run {
                    problem: p.key,
                    method: m.name(),
                    eps: e,
                    undecided_area: b.undecided_area(),
                    inner_area: b.inner_area,
                    outer_area: b.outer_area,
                    leaves: paving.leaves.len(),
                    box_evaluations: paving.stats.box_evaluations,
                    slab_evaluations: paving.stats.slab_evaluations,
                    time_s: times[times.len() / 2],
                    process_s: process[process.len() / 2],
                    bytes_per_leaf: bytes as f64 / paving.leaves.len().max(1) as f64,
                    stop: paving.stop,
                };
                outln!(
                    "{:<12} {:<9} {:>10.3e} {:>12.5e} {:>9} {:>11} {:>8} {:>9.4} {:>10.4} {:>8.1}",
                    run.problem,
                    run.method,
                    run.eps,
                    run.undecided_area,
                    run.leaves,
                    run.box_evaluations,
                    run.slab_evaluations,
                    run.time_s,
                    run.process_s,
                    run.bytes_per_leaf
                );
                runs.push(run);
            }
        }
    }

    let (peers, peer_meta) = peer_curves(&args.peers);
    let mut ratios = Vec::new();
    let mut per_leaf = Vec::new();
    let mut panels = Vec::new();
    for p in &problems {
        let mut curves = Vec::new();
        for &m in &methods {
            let pts: Vec<(f64, f64)> = runs
                .iter()
                .filter(|r| r.problem == p.key && r.method == m.name())
                .map(|r| (r.process_s, r.undecided_area))
                .collect();
            for (_, label, peer_pts, peer_boxes) in peers.iter().filter(|c| c.0 == p.key) {
                for r in runs
                    .iter()
                    .filter(|r| r.problem == p.key && r.method == m.name())
                {
                    // On (area, boxes) points: the area at this box count.
                    if let Some(pu) = x_at(peer_boxes, r.leaves as f64) {
                        per_leaf.push(LeafRatio {
                            problem: p.key,
                            method: m.name(),
                            peer: label.clone(),
                            leaves: r.leaves,
                            undecided_area: r.undecided_area,
                            peer_undecided_area: pu,
                        });
                    }
                }
                for u in [0.3, 0.1, 0.03, 0.01, 0.003] {
                    if let (Some(ours), Some(theirs)) = (x_at(&pts, u), x_at(peer_pts, u)) {
                        ratios.push(Ratio {
                            problem: p.key,
                            method: format!("detach {}", m.name()),
                            peer: label.clone(),
                            undecided_area: u,
                            speedup: theirs / ours,
                        });
                    }
                }
            }
            curves.push(Curve {
                label: format!("detach {}", m.name()),
                peer: false,
                points: pts,
            });
        }
        for (_, label, pts, _) in peers.iter().filter(|c| c.0 == p.key) {
            curves.push(Curve {
                label: label.clone(),
                peer: true,
                points: pts.clone(),
            });
        }
        panels.push(Panel {
            title: p.title.to_string(),
            curves,
        });
    }
    if !ratios.is_empty() {
        outln!("speed-up at matched undecided area (peer's paving call / detach's whole process):");
        for r in &ratios {
            outln!(
                "  {:<12} {:<15} vs {:<12} at {:<6} {:>7.1}×",
                r.problem,
                r.method,
                r.peer,
                r.undecided_area,
                r.speedup
            );
        }
    }
    if !per_leaf.is_empty() {
        outln!("undecided area at equal leaf count (detach / peer, below 1: detach tighter):");
        for r in per_leaf.iter().filter(|r| r.peer.ends_with("sep")) {
            outln!(
                "  {:<12} {:<9} vs {:<10} {:>8} leaves  {:>10.4e} / {:>10.4e} = {:>5.2}",
                r.problem,
                r.method,
                r.peer,
                r.leaves,
                r.undecided_area,
                r.peer_undecided_area,
                r.undecided_area / r.peer_undecided_area
            );
        }
    }
    let svg = args.out.join("methods.svg");
    let png = args.out.join("methods.png");
    draw_speed_accuracy(
        &panels,
        "Undecided area vs wall time: detach as a whole process, peers' paving call (log–log; dashed: peers)",
        (1400, 620),
        &svg,
        &png,
    )
    .map_err(|e| CliError::runtime(format!("drawing {}: {e}", svg.display())))?;
    let json = args.out.join("methods.json");
    let doc = serde_json::json!({
        "detach": detach::provenance(),
        "machine": machine,
        "note": "time_s is the paving call alone, process_s the whole `detach pave --json` process (the chart and the ratios), each the median of `repeat` runs (process_s: at least 5 spawns where one takes under 0.2 s)",
        "repeat": args.repeat,
        "runs": runs,
        "peers": peer_meta,
        "ratios": ratios,
        "equal_leaf_count": per_leaf,
    });
    std::fs::write(
        &json,
        serde_json::to_string_pretty(&doc).expect("serialisable"),
    )
    .map_err(|e| CliError::runtime(format!("cannot write {}: {e}", json.display())))?;
    outln!(
        "wrote {}, {} and {}",
        json.display(),
        svg.display(),
        png.display()
    );
    Ok(())
}
