//! detach's paving call against Codac's, in-process, at matched accuracy.
//!
//! ```text
//! pip install codac==2.1.2
//! cargo bench --bench peers [-- --method slices --method natural --out DIR]
//! ```
//!
//! Codac's side is re-run first (`benches/peers/codac_peer.py`, into
//! `benches/peers/codac.json`): a ratio holds only for two runs on the
//! machine in the same state. Without Python and Codac, or with
//! `--stored-peers`, the stored file is read; the table says when it ran.
//!
//! Two problems, the same work for both tools: Ω of (2.8) of the smooth disc
//! (g=9.81, a=1, A=0.25, p_φ=1, p_ψ=0.6) on θ ∈ [0.05, π−0.05], and the
//! printed Ω₀ (1.11) of the viscous disc at its defaults. Each method paves
//! over a range of ε on one thread (Codac's paver is single-threaded); each
//! point is the median of several runs of the paving call alone. The time
//! at which each curve reaches an undecided area U is interpolated (log–log)
//! and compared at U from 0.03 down to 0.002. The same matching, without a
//! peer, finds the fastest method on Ω and Ω₀ of every scene. Thread scaling
//! (`natural` and `slices` on the viscous disc at ε = 1e-5, one thread
//! against two) and the start-up of the built binary are reported on their
//! own. Writes `peers.md` (tables), `peers.json` and the chart
//! `peers.svg`/`peers.png` into `--out` (default `docs/performance`).

#[path = "peers/compare.rs"]
mod compare;
#[path = "peers/problems.rs"]
mod problems;
#[path = "support/timing.rs"]
mod timing;

use compare::{cost_exponent, peer_curves, speedup, x_at};
use detach::figures::chart::{draw_speed_accuracy, Curve, Panel};
use detach::pave::{run_method, Method, MethodRun, PaveOptions};
use detach::scene::{Scene, SceneId, Variant};
use problems::{problems, Problem};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;
use timing::{load, utc_now};

/// The undecided areas at which the curves are compared.
const MATCHED: [f64; 5] = [0.03, 0.01, 0.005, 0.003, 0.002];
/// A point faster than this is run `CHEAP_RUNS` times and its median kept.
const CHEAP_S: f64 = 0.2;
const CHEAP_RUNS: usize = 5;
/// A series stops refining once one run takes longer than this.
const BUDGET_S: f64 = 5.0;
/// A series stops once its undecided area is below this (past every U).
const FINEST_U: f64 = 0.0015;

/// Ω and Ω₀ of every scene (derived, defaults, whole domain): which method
/// reaches a given accuracy first.
fn scene_problems() -> Vec<Problem> {
    let mut out = Vec::new();
    for id in SceneId::ALL {
        for (cell, region) in [(0, "omega"), (1, "omega0")] {
            let scene = Scene::default_of(id);
            out.push(Problem {
                key: format!("{}/{region}", id.name()),
                title: format!("{} {region}", id.name()),
                domain: scene.domain(),
                scene,
                variant: Variant::Derived,
                cell,
            });
        }
    }
    out
}

struct Args {
    methods: Vec<Method>,
    out: PathBuf,
    peers: PathBuf,
    /// Re-run Codac's side into `peers` before measuring.
    rerun_peers: bool,
}

fn args() -> Args {
    let mut a = Args {
        methods: vec![],
        out: PathBuf::from("docs/performance"),
        peers: PathBuf::from("benches/peers/codac.json"),
        rerun_peers: true,
    };
    let mut it = std::env::args().skip(1);
    while let Some(s) = it.next() {
        match s.as_str() {
            "--method" => a.methods.push(
                it.next()
                    .expect("--method NAME")
                    .parse()
                    .unwrap_or_else(|e| panic!("{e}")),
            ),
            "--out" => a.out = it.next().expect("--out DIR").into(),
            "--peers" => a.peers = it.next().expect("--peers FILE").into(),
            "--stored-peers" => a.rerun_peers = false,
            // `cargo bench` passes `--bench`; filters are not used.
            _ => {}
        }
    }
    if a.methods.is_empty() {
        a.methods = Method::ALL.to_vec();
    }
    a
}

/// Re-runs Codac's side into `path`; keeps the stored file (and says so)
/// when Python or Codac is missing or the script fails.
fn rerun_peers(path: &Path) {
    let script = "benches/peers/codac_peer.py";
    eprintln!("running {script} (Codac's side, a few minutes)");
    let run = Command::new("python3")
        .arg(script)
        .stderr(Stdio::inherit())
        .output();
    let kept = |why: String| eprintln!("{why}: reading the stored {}", path.display());
    match run {
        Ok(o) if o.status.success() => {
            let fresh = serde_json::from_slice::<serde_json::Value>(&o.stdout)
                .is_ok_and(|d| d["runs"].is_array());
            if !fresh {
                kept(format!("{script} wrote no runs"));
            } else if let Err(e) = std::fs::write(path, &o.stdout) {
                kept(format!("cannot write {}: {e}", path.display()));
            }
        }
        Ok(o) => kept(format!("{script} failed ({})", o.status)),
        Err(e) => kept(format!("python3 did not start ({e})")),
    }
}

/// The median run of a point (by time), on the current thread pool.
fn median_run(p: &Problem, m: Method, eps: f64) -> MethodRun {
    let opts = PaveOptions {
        eps,
        max_boxes: 20_000_000,
    };
    let once = || {
        run_method(&p.scene, p.variant, &p.domain, Some(p.cell), m, opts)
            .expect("paves")
            .0
    };
    let mut runs = vec![once()];
    while runs.len() < CHEAP_RUNS && runs[0].seconds < CHEAP_S {
        runs.push(once());
    }
    runs.sort_by(|a, b| a.seconds.total_cmp(&b.seconds));
    runs.swap_remove(runs.len() / 2)
}

fn series(p: &Problem, m: Method) -> Vec<MethodRun> {
    let mut out = Vec::new();
    for k in 5..=17 {
        let r = median_run(p, m, 2f64.powi(-k));
        eprintln!(
            "{} {:<8} eps=2^-{k:<2} leaves={:<8} undecided={:.5} {:.4}s",
            p.key, m, r.leaves, r.undecided_area, r.seconds
        );
        let stop = r.seconds > BUDGET_S || r.undecided_area < FINEST_U;
        out.push(r);
        if stop {
            break;
        }
    }
    out
}

/// Median wall time of `f` over `n` runs.
fn median_time(n: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..n)
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[n / 2]
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
}

fn main() {
    let a = args();
    if a.rerun_peers {
        rerun_peers(&a.peers);
    }
    let problems = problems();
    let peers_doc: serde_json::Value = std::fs::read_to_string(&a.peers)
        .ok()
        .and_then(|t| serde_json::from_str(&t).ok())
        .unwrap_or(serde_json::Value::Null);
    let peers = peer_curves(&peers_doc);
    if peers.is_empty() {
        eprintln!("no peer data at {}: detach only", a.peers.display());
    }
    let load_before = load();
    let one = pool(1);
    let scenes = scene_problems();
    let mut runs: Vec<(&str, Method, Vec<MethodRun>)> = Vec::new();
    for p in problems.iter().chain(&scenes) {
        for &m in &a.methods {
            runs.push((&p.key, m, one.install(|| series(p, m))));
        }
    }

    // Matched points: the peer's paving call / ours, per U.
    let mut md = String::new();
    // A ratio holds only for two runs on the machine in the same state:
    // when Codac's times were taken is part of the table.
    let codac_run = match (
        peers_doc["date"].as_str(),
        peers_doc["machine"]["loadavg_before"].as_array(),
    ) {
        (Some(date), Some(load)) => {
            let load: Vec<String> = load
                .iter()
                .filter_map(|x| x.as_f64())
                .map(|x| format!("{x:.2}"))
                .collect();
            format!(" (run at {date}, load average before: {})", load.join(" "))
        }
        _ => String::new(),
    };
    let _ = writeln!(
        md,
        "# detach against Codac, in-process\n\nMade by `cargo bench --bench peers` \
         (see `benches/peers.rs`), run at {}; Codac's times by \
         `benches/peers/codac_peer.py`{codac_run}.\n\
         Each cell: Codac `pave(SepInverse)` paving-call time / detach paving-call \
         time on one thread, at the same undecided area U (log–log interpolation \
         between measured points). Load average before: {load_before}; after: {}.\n",
        utc_now(),
        load()
    );
    let mut ratios = Vec::new();
    for p in &problems {
        let Some(sep) = peers
            .iter()
            .find(|c| c.problem == p.key && c.label.ends_with("sep"))
        else {
            continue;
        };
        let _ = writeln!(md, "## {}\n", p.title);
        let head: Vec<String> = MATCHED.iter().map(|u| format!("U = {u}")).collect();
        let _ = writeln!(
            md,
            "| method | {} | cost ∝ (1/U)^k, k |\n|---|{}---|",
            head.join(" | "),
            "---|".repeat(MATCHED.len())
        );
        for (_, m, rs) in runs.iter().filter(|r| r.0 == p.key) {
            let pts: Vec<(f64, f64)> = rs.iter().map(|r| (r.seconds, r.undecided_area)).collect();
            let cells: Vec<String> = MATCHED
                .iter()
                .map(|&u| match speedup(&pts, &sep.time_area, u) {
                    Some(s) => {
                        ratios.push(serde_json::json!({
                            "problem": &p.key, "method": m.name(), "undecided_area": u,
                            "detach_s": x_at(&pts, u), "codac_sep_s": x_at(&sep.time_area, u),
                            "speedup": s,
                        }));
                        format!("{s:.1}×")
                    }
                    None => "—".into(),
                })
                .collect();
            let k = cost_exponent(&pts, 0.001, 0.05)
                .map(|k| format!("{k:.2}"))
                .unwrap_or_else(|| "—".into());
            let _ = writeln!(md, "| {m} | {} | {k} |", cells.join(" | "));
        }
        let k = cost_exponent(&sep.time_area, 0.001, 0.05)
            .map(|k| format!("{k:.2}"))
            .unwrap_or_else(|| "—".into());
        let _ = writeln!(md, "| (Codac sep) |{} {k} |\n", " |".repeat(MATCHED.len()));
    }

    // The fastest method per scene and region, at matched accuracy.
    let _ = writeln!(
        md,
        "## Methods per scene\n\nEach scene (derived, defaults, whole domain), one \
         region refined: paving-call time on one thread to reach undecided area U \
         (interpolated), per method; the fastest in bold.\n"
    );
    let head: Vec<String> = a.methods.iter().map(|m| m.to_string()).collect();
    let _ = writeln!(
        md,
        "| problem | U | {} |\n|---|---|{}",
        head.join(" | "),
        "---|".repeat(a.methods.len())
    );
    let mut fastest = Vec::new();
    for p in &scenes {
        for u in [0.01, 0.003] {
            let times: Vec<Option<f64>> = runs
                .iter()
                .filter(|r| r.0 == p.key)
                .map(|(_, _, rs)| {
                    let pts: Vec<(f64, f64)> =
                        rs.iter().map(|r| (r.seconds, r.undecided_area)).collect();
                    x_at(&pts, u)
                })
                .collect();
            let best = times
                .iter()
                .enumerate()
                .filter_map(|(i, t)| t.map(|t| (i, t)))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(i, _)| i);
            let cells: Vec<String> = times
                .iter()
                .enumerate()
                .map(|(i, t)| match t {
                    Some(t) if Some(i) == best => format!("**{:.2} ms**", t * 1e3),
                    Some(t) => format!("{:.2} ms", t * 1e3),
                    None => "—".into(),
                })
                .collect();
            let _ = writeln!(md, "| {} | {u} | {} |", p.title, cells.join(" | "));
            fastest.push(serde_json::json!({
                "problem": &p.key, "undecided_area": u,
                "fastest": best.map(|i| a.methods[i].name()),
            }));
        }
    }
    let _ = writeln!(md);

    // Thread scaling, on its own: the viscous disc at ε = 1e-5.
    let viscous = Scene::default_of(SceneId::ViscousDisc);
    let two = pool(2);
    let _ = writeln!(
        md,
        "## Threads\n\nViscous disc (derived, defaults, all constraints) at ε = 1e-5: \
         median of 3 paving calls each.\n\n| method | 1 thread (s) | 2 threads (s) | speed-up |\n|---|---|---|---|"
    );
    let mut threads = Vec::new();
    for &m in a
        .methods
        .iter()
        .filter(|m| matches!(m, Method::Natural | Method::Slices))
    {
        let go = || {
            run_method(
                &viscous,
                Variant::Derived,
                &viscous.domain(),
                None,
                m,
                PaveOptions {
                    eps: 1e-5,
                    max_boxes: 20_000_000,
                },
            )
            .expect("paves")
        };
        let t1 = one.install(|| median_time(3, || drop(go())));
        let t2 = two.install(|| median_time(3, || drop(go())));
        let _ = writeln!(md, "| {m} | {t1:.3} | {t2:.3} | {:.2}× |", t1 / t2);
        threads.push(serde_json::json!({"method": m.name(), "one_s": t1, "two_s": t2}));
    }

    // Start-up of the built binary, on its own.
    let exe = PathBuf::from("target/release/detach");
    let startup = exe.exists().then(|| {
        median_time(21, || {
            let _ = std::process::Command::new(&exe).arg("--version").output();
        })
    });
    if let Some(s) = startup {
        let _ = writeln!(
            md,
            "\nStart-up: `target/release/detach --version` as a whole process, \
             median of 21: {:.2} ms.",
            s * 1e3
        );
    }

    // The chart: undecided area against paving-call time.
    let panels: Vec<Panel> = problems
        .iter()
        .map(|p| {
            let mut curves: Vec<Curve> = runs
                .iter()
                .filter(|r| r.0 == p.key)
                .map(|(_, m, rs)| Curve {
                    label: format!("detach {m}"),
                    peer: false,
                    points: rs.iter().map(|r| (r.seconds, r.undecided_area)).collect(),
                })
                .collect();
            curves.extend(peers.iter().filter(|c| c.problem == p.key).map(|c| Curve {
                label: c.label.clone(),
                peer: true,
                points: c.time_area.clone(),
            }));
            Panel {
                title: p.title.clone(),
                curves,
            }
        })
        .collect();
    std::fs::create_dir_all(&a.out).expect("output directory");
    draw_speed_accuracy(
        &panels,
        "Undecided area vs paving-call time, one thread, in-process (log–log; dashed: Codac)",
        (1400, 620),
        &a.out.join("peers.svg"),
        &a.out.join("peers.png"),
    )
    .expect("chart");
    let doc = serde_json::json!({
        "detach": detach::provenance(),
        "load_before": load_before,
        "load_after": load(),
        "peers": { "file": a.peers.display().to_string(), "version": peers_doc["version"],
                   "machine": peers_doc["machine"] },
        "runs": runs.iter().flat_map(|(k, m, rs)| rs.iter().map(move |r| serde_json::json!({
            "problem": k, "method": m.name(), "eps": r.eps, "leaves": r.leaves,
            "undecided_area": r.undecided_area, "time_s": r.seconds,
            "bytes_per_leaf": r.bytes_per_leaf, "peak_bytes_per_leaf": r.peak_bytes_per_leaf,
        }))).collect::<Vec<_>>(),
        "ratios": ratios,
        "fastest_per_scene": fastest,
        "threads": threads,
        "startup_s": startup,
    });
    std::fs::write(
        a.out.join("peers.json"),
        serde_json::to_string_pretty(&doc).expect("JSON"),
    )
    .expect("writes peers.json");
    std::fs::write(a.out.join("peers.md"), &md).expect("writes peers.md");
    print!("{md}");
    println!("wrote {}/peers.{{md,json,svg,png}}", a.out.display());
}
