//! `detach roots`, `detach kappa0`, `detach critical-curve`, `detach tangency`.

use super::{CliError, CliResult};
use detach::certificate::catalog::roots_proof_of;
use detach::figures::roots::{plot_critical_with, plot_tangency_with};
use detach::number::param::parse_assignment;
use detach::roots::critical::{critical_curve, kappa_max_below};
use detach::roots::isolate::ulps_between;
use detach::roots::kappa0::{Bound, Verdict};
use detach::roots::request::Value;
use detach::roots::tangency::{tangency_scan, Outcome};
use detach::roots::{prove_kappa0, Budget, EquationRoots, RootStatus, RootsInputs, RootsRequest};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Certified roots of (2.9), (2.10), (2.12) or the equilibria of (3.3).
#[derive(clap::Args, Debug, Clone)]
pub struct RootsArgs {
    /// Equation: 2.9, 2.10, 2.12 or 3.3.
    #[arg(long)]
    pub equation: String,
    /// κ > 0 as decimal text (2.9, 2.10), enclosed exactly.
    #[arg(long, allow_hyphen_values = true)]
    pub kappa: Option<String>,
    /// α ∈ [-1, 1] as decimal text (2.9), enclosed exactly.
    #[arg(long, allow_hyphen_values = true)]
    pub alpha: Option<String>,
    /// Scene for 2.12 (smooth-disc, ice-disc), 3.3 (ice-disc), or 2.9 (κ, α of the disc).
    #[arg(long)]
    pub scene: Option<String>,
    /// Scene parameter override, repeatable.
    #[arg(long = "param", value_name = "NAME=VALUE", allow_hyphen_values = true)]
    pub params: Vec<String>,
    /// Most function evaluations.
    #[arg(long, default_value_t = 200_000, value_parser = detach::number::param::parse_count, allow_negative_numbers = true)]
    pub max_evaluations: usize,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Also write the roots as a proof file (`proofs/FORMAT.md`), checked
    /// before it is reported: (2.9) with --kappa/--alpha, (2.10), (2.12);
    /// `-`: standard output.
    #[arg(long, value_name = "FILE")]
    pub proof: Option<PathBuf>,
}

/// The enclosure of κ₀ = √3/9 and the proof of the root count of (2.10).
#[derive(clap::Args, Debug, Clone)]
pub struct Kappa0Args {
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// The critical curve κ_crit(α) of (2.9) and the certified (α, κ) atlas.
#[derive(clap::Args, Debug, Clone)]
pub struct CriticalCurveArgs {
    /// Output directory for critical-curve.{svg,png,json}.
    #[arg(long, default_value = "out/critical-curve")]
    pub out: PathBuf,
    /// Number of α-boxes of [0, 1] (a power of two).
    #[arg(long, default_value_t = 128, value_parser = detach::number::param::parse_count, allow_negative_numbers = true)]
    pub alpha_boxes: usize,
    /// Number of κ-boxes of (0, κ_max] (a power of two).
    #[arg(long, default_value_t = 128, value_parser = detach::number::param::parse_count, allow_negative_numbers = true)]
    pub kappa_boxes: usize,
    /// Top of the κ range (decimal; the grid uses the double below it).
    #[arg(long, default_value = "0.25", allow_hyphen_values = true)]
    pub kappa_max: String,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub figure: FigureFlags,
}

/// Figure size and formats of `tangency` and `critical-curve`.
#[derive(clap::Args, Debug, Clone)]
pub struct FigureFlags {
    /// Figure size in pixels, `WxH` (default 900x600 for tangency, 900x700
    /// for critical-curve; at least 400x300).
    #[arg(long, value_name = "WxH")]
    pub size: Option<String>,
    /// Which figure files: `svg` (vector only), `png` or `all`. PDF is not
    /// supported: convert the SVG (e.g. `rsvg-convert -f pdf`).
    #[arg(long, default_value = "all", value_name = "FORMAT")]
    pub format: String,
}

impl FigureFlags {
    fn options(&self) -> Result<detach::figures::roots::FigureOptions, CliError> {
        let size = self
            .size
            .as_deref()
            .map(|s| {
                detach::figures::parse_size(s, detach::figures::roots::MIN_SIZE)
                    .map_err(|e| CliError::usage(format!("--size: {e}")))
            })
            .transpose()?;
        let formats = detach::figures::Formats::parse(&self.format)
            .map_err(|e| CliError::usage(format!("--format: {e}")))?;
        Ok(detach::figures::roots::FigureOptions { size, formats })
    }
}

/// (2.10) at κ = κ₀ and at κ = κ₀(1 ± 10⁻ᵏ): what the isolator certifies.
#[derive(clap::Args, Debug, Clone)]
pub struct TangencyArgs {
    /// Output directory for tangency.{svg,png,json}.
    #[arg(long, default_value = "out/tangency")]
    pub out: PathBuf,
    /// Largest k (1 ≤ k ≤ 17).
    #[arg(long, default_value_t = 15, allow_negative_numbers = true)]
    pub k_max: i32,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub figure: FigureFlags,
}

#[derive(Serialize)]
struct RootsOutput<'a> {
    #[serde(flatten)]
    result: &'a EquationRoots,
    scene: Option<&'static str>,
    parameters: &'a [Value],
    /// κ and α of (2.9) derived from the scene, when relevant.
    derived: &'a [Value],
}

/// JSON of `x` with a leading `"detach": {"version", "commit"}` and the
/// command's `arguments`, so every output records what produced it.
fn to_json<T: Serialize>(x: &T, arguments: serde_json::Value) -> Result<String, CliError> {
    #[derive(Serialize)]
    struct Stamped<'a, T: Serialize> {
        detach: serde_json::Value,
        arguments: serde_json::Value,
        #[serde(flatten)]
        body: &'a T,
    }
    serde_json::to_string_pretty(&Stamped {
        detach: detach::provenance(),
        arguments,
        body: x,
    })
    .map_err(|e| CliError::runtime(format!("JSON: {e}")))
}

/// The request of `roots`, its inputs checked (errors name the options).
fn request(args: &RootsArgs) -> Result<RootsRequest, CliError> {
    let params = args
        .params
        .iter()
        .map(|p| parse_assignment(p))
        .collect::<Result<Vec<_>, _>>()
        .map_err(CliError::usage)?;
    let request = RootsRequest::new(&RootsInputs {
        equation: &args.equation,
        kappa: args.kappa.as_deref(),
        alpha: args.alpha.as_deref(),
        scene: args.scene.as_deref(),
        params: &params,
    })
    .map_err(|e| CliError::usage(e.message(|i| format!("--{i}"))))?;
    if args.max_evaluations == 0 {
        return Err(CliError::usage("--max-evaluations must be positive"));
    }
    Ok(request)
}

/// `roots --proof FILE`: the roots of this run as a checked proof file.
fn write_roots_proof(path: &Path, request: &RootsRequest, roots: &EquationRoots) -> CliResult {
    let proof = roots_proof_of(request, roots).map_err(CliError::usage)?;
    let (bytes, _, units) = super::write_checked(path, &proof)?;
    eprintln!(
        "wrote {} ({bytes} B, {units}, checked VALID)",
        detach::files::shown(path)
    );
    Ok(())
}

/// An enclosure's width: in ulps while that is a small count, else as a
/// number.
fn width_text(lo: f64, hi: f64, ulps: u64) -> String {
    if ulps <= 1_000_000 {
        format!("{ulps} ulp")
    } else {
        format!("{:.2e}", hi - lo)
    }
}

/// `[lo, hi]` in exponent form, `-0` printed as `0`.
fn fmt_enc(b: [f64; 2]) -> String {
    format!("[{:e}, {:e}]", b[0] + 0.0, b[1] + 0.0)
}

/// The command line of `roots`, as recorded in its JSON.
fn roots_arguments(args: &RootsArgs) -> serde_json::Value {
    serde_json::json!({
        "equation": args.equation,
        "kappa": args.kappa,
        "alpha": args.alpha,
        "scene": args.scene,
        "params": args.params,
        "max_evaluations": args.max_evaluations,
    })
}

/// One row of the `roots` table: a unique root, or a cluster of undecided
/// enclosures (possibly of one member).
struct Row {
    lo: f64,
    hi: f64,
    status: String,
    /// What the cluster holds, e.g. "holds 0 or 2 roots"; `None` for a
    /// unique root.
    holds: Option<String>,
}

/// The table rows: each cluster replaces its members (kept in the JSON).
fn table_rows(result: &EquationRoots) -> Vec<Row> {
    let mut rows = Vec::new();
    let mut next_cluster = result.clusters.iter().peekable();
    for (i, r) in result.roots.iter().enumerate() {
        if r.status == RootStatus::Unique {
            rows.push(Row {
                lo: r.lo,
                hi: r.hi,
                status: "unique (exactly one root, simple)".into(),
                holds: None,
            });
            continue;
        }
        let Some(c) = next_cluster.next_if(|c| c.members.first() == Some(&i)) else {
            continue;
        };
        let count = c.count_text();
        let reason = c
            .members
            .iter()
            .filter_map(|&m| result.roots[m].reason)
            .max()
            .map_or("undecided", |x| x.describe());
        let what = if c.members.len() == 1 {
            format!("undecided ({reason})")
        } else {
            format!("cluster of {} undecided ({reason})", c.members.len())
        };
        let mut why = Vec::new();
        if let Some(d) = c.nonzero_derivative {
            why.push(format!(
                "{} ≠ 0 on it",
                if d.order == 1 { "f'" } else { "f''" }
            ));
        }
        match c.sign_change {
            Some(true) => why.push("f changes sign across it".into()),
            Some(false) => why.push("f has one sign on both sides".into()),
            None => {}
        }
        let (status, holds) = if c.at_most().is_none() && c.sign_change != Some(true) {
            (what, "may hold any number".to_string())
        } else {
            (
                format!(
                    "{what}: {count} (counted with multiplicity); {}",
                    why.join(", ")
                ),
                format!("holds {count}"),
            )
        };
        rows.push(Row {
            lo: c.lo,
            hi: c.hi,
            status,
            holds: Some(holds),
        });
    }
    rows
}

/// The `complete: no` line: where the roots are and what each cluster holds.
fn incomplete_summary(rows: &[Row]) -> String {
    let held: Vec<String> = rows
        .iter()
        .enumerate()
        .filter_map(|(i, r)| Some(format!("#{} {}", i + 1, r.holds.as_ref()?)))
        .collect();
    let bounded = held.iter().any(|h| !h.ends_with("any number"));
    format!(
        "every root lies in the enclosures above; {}{}",
        held.join(", "),
        if bounded {
            " (counted with multiplicity)"
        } else {
            ""
        }
    )
}

/// `detach roots`.
pub fn run_roots(args: &RootsArgs) -> CliResult {
    super::take_stdout(&[("--proof", args.proof.as_deref())], args.json)?;
    let request = request(args)?;
    let budget = Budget {
        max_evaluations: args.max_evaluations,
        ..Budget::default()
    };
    let result = request.solve(&budget).map_err(CliError::usage)?;
    if let Some(path) = &args.proof {
        write_roots_proof(path, &request, &result)?;
    }
    if args.json {
        let out = RootsOutput {
            result: &result,
            scene: request.scene_name(),
            parameters: &request.parameters,
            derived: &request.derived,
        };
        outln!("{}", to_json(&out, roots_arguments(args))?);
        return Ok(());
    }
    outln!(
        "equation ({}) for {} in {}{}",
        result.equation,
        result.variable,
        result.domain_text,
        request
            .scene_name()
            .map(|s| format!(", scene {s}"))
            .unwrap_or_default()
    );
    for p in request.parameters.iter().chain(&request.derived) {
        outln!(
            "  {:<6} = {:<18} ∈ {}",
            p.name,
            p.text,
            fmt_enc(p.enclosure)
        );
    }
    outln!(
        "  {:>3}  {:<24} {:<24} {:>10}  status",
        "#",
        "lo",
        "hi",
        "width"
    );
    let rows = table_rows(&result);
    for (i, row) in rows.iter().enumerate() {
        outln!(
            "  {:>3}  {:<24} {:<24} {:>10}  {}",
            i + 1,
            format!("{:?}", row.lo),
            format!("{:?}", row.hi),
            width_text(row.lo, row.hi, ulps_between(row.lo, row.hi)),
            row.status
        );
    }
    if result.roots.is_empty() {
        outln!("  (no root)");
    }
    for e in &result.edges {
        outln!(
            "  edge {:<13} {}: {}",
            e.end,
            fmt_enc(e.part),
            if e.proved {
                "proved root-free"
            } else {
                "NOT proved"
            }
        );
    }
    outln!(
        "complete: {} — {}",
        if result.complete { "yes" } else { "no" },
        if result.complete {
            match result.roots.len() {
                0 => "no root: the whole domain is proved root-free".to_string(),
                1 => {
                    "exactly 1 root, simple; the rest of the domain is proved root-free".to_string()
                }
                n => format!(
                    "exactly {n} roots, all simple; the rest of the domain is proved root-free"
                ),
            }
        } else {
            incomplete_summary(&rows)
        }
    );
    outln!(
        "work: {} evaluations, {} bisections, {} Newton steps",
        result.stats.evaluations,
        result.stats.bisections,
        result.stats.newton_steps
    );
    Ok(())
}

/// `detach kappa0`.
pub fn run_kappa0(args: &Kappa0Args) -> CliResult {
    let proof = prove_kappa0();
    if args.json {
        outln!("{}", to_json(&proof, serde_json::json!({}))?);
    } else {
        // Unbounded enclosures (p on [1, +∞)) print as ∞, not `inf`.
        let end = |x: f64| match x {
            f64::INFINITY => "+∞".to_string(),
            f64::NEG_INFINITY => "−∞".to_string(),
            x => format!("{:?}", x + 0.0),
        };
        let b = |x: Bound| format!("[{}, {}]", end(x.lo), end(x.hi));
        outln!(
            "κ₀ ∈ {}  ({} ulp wide; √3/9 in intervals: {})",
            b(proof.kappa0),
            proof.kappa0_width_ulps,
            b(proof.sqrt3_over_9)
        );
        outln!(
            "μ* ∈ {}, 2κ₀ = p(μ*) ∈ {}",
            b(proof.mu_star),
            b(proof.max_value)
        );
        for s in proof.steps.iter().chain(&proof.statements) {
            let v = if s.verdict == Verdict::Proved {
                "PROVED"
            } else {
                "NOT PROVED"
            };
            outln!("[{v}] {}: {}", s.id, s.statement);
            for (k, x) in &s.enclosures {
                outln!("         {k} ∈ {}", b(*x));
            }
        }
    }
    if proof.all_proved() {
        Ok(())
    } else {
        Err(CliError::runtime("the κ₀ proof did not go through"))
    }
}

fn write_json<T: Serialize>(
    dir: &Path,
    name: &str,
    x: &T,
    arguments: serde_json::Value,
) -> Result<PathBuf, CliError> {
    std::fs::create_dir_all(dir)
        .map_err(|e| CliError::runtime(format!("cannot create {}: {e}", dir.display())))?;
    let path = dir.join(name);
    detach::files::write_atomic(&path, (to_json(x, arguments)? + "\n").as_bytes())
        .map_err(|e| super::cannot_write(&path, e))?;
    Ok(path)
}

fn power_of_two(name: &str, n: usize) -> Result<(), CliError> {
    if n == 0 || !n.is_power_of_two() || n > 4096 {
        return Err(CliError::usage(format!(
            "--{name} must be a power of two between 1 and 4096, got {n}"
        )));
    }
    Ok(())
}

/// Output budget of `critical-curve`: most (α, κ) cells (e.g. 512 × 512),
/// about 50 MB of JSON and 25 MB of SVG.
pub const MAX_CRITICAL_CELLS: usize = 1 << 18;

/// `detach critical-curve`.
pub fn run_critical_curve(args: &CriticalCurveArgs) -> CliResult {
    let figure = args.figure.options()?;
    power_of_two("alpha-boxes", args.alpha_boxes)?;
    power_of_two("kappa-boxes", args.kappa_boxes)?;
    let cells = args.alpha_boxes * args.kappa_boxes;
    if cells > MAX_CRITICAL_CELLS {
        return Err(CliError::usage(format!(
            "--alpha-boxes × --kappa-boxes = {cells} cells is over the output budget of \
             {MAX_CRITICAL_CELLS} cells (about 200 bytes of JSON each); use fewer boxes"
        )));
    }
    let km = kappa_max_below(&args.kappa_max)
        .map_err(CliError::usage)?
        .ok_or_else(|| {
            CliError::usage(format!(
                "--kappa-max must be positive, got {}",
                args.kappa_max
            ))
        })?;
    let cc = critical_curve(args.alpha_boxes, args.kappa_boxes, km);
    let arguments = serde_json::json!({
        "alpha_boxes": args.alpha_boxes,
        "kappa_boxes": args.kappa_boxes,
        "kappa_max": args.kappa_max,
    });
    let mut files = vec![write_json(
        &args.out,
        "critical-curve.json",
        &cc,
        arguments.clone(),
    )?];
    files.extend(plot_critical_with(&cc, &args.out, &figure).map_err(CliError::runtime)?);
    if args.json {
        outln!("{}", to_json(&cc, arguments)?);
    } else {
        outln!("κ_crit(α) on {} α-boxes of [0, 1]", cc.band.len());
        outln!(
            "  max band width (upper − lower): {:e}",
            cc.max_band_width + 0.0
        );
        outln!(
            "  at α = 1: κ_crit ∈ [{:?}, {:?}], κ₀ ∈ [{:?}, {:?}] inside: {}",
            cc.at_alpha_1.lower,
            cc.at_alpha_1.upper,
            cc.kappa0.lo,
            cc.kappa0.hi,
            cc.kappa0_inside_band_at_1
        );
        for c in cc.band.iter().step_by((cc.band.len() / 8).max(1)) {
            outln!(
                "  α ∈ [{:.4}, {:.4}]: κ_crit ∈ [{:.6e}, {:.6e}]",
                // `+ 0.0`: an interval's infimum 0 is −0.
                c.alpha.lo + 0.0,
                c.alpha.hi,
                c.lower + 0.0,
                c.upper
            );
        }
        outln!(
            "atlas (α, κ) ∈ [0, 1] × (0, {}]: {} no root, {} exactly two simple roots, {} undecided",
            detach::number::param::short_num(cc.kappa_max),
            cc.counts.no_root, cc.counts.two_simple_roots, cc.counts.undecided
        );
        for f in files {
            outln!("wrote {}", f.display());
        }
    }
    Ok(())
}

/// `detach tangency`.
pub fn run_tangency(args: &TangencyArgs) -> CliResult {
    if !(1..=17).contains(&args.k_max) {
        return Err(CliError::usage(format!(
            "--k-max must be between 1 and 17, got {}",
            args.k_max
        )));
    }
    let figure = args.figure.options()?;
    let rep = tangency_scan(args.k_max, &Budget::default());
    let arguments = serde_json::json!({ "k_max": args.k_max });
    let mut files = vec![write_json(
        &args.out,
        "tangency.json",
        &rep,
        arguments.clone(),
    )?];
    files.extend(plot_tangency_with(&rep, &args.out, &figure).map_err(CliError::runtime)?);
    if args.json {
        outln!("{}", to_json(&rep, arguments)?);
        return Ok(());
    }
    let dr = &rep.double_root;
    outln!(
        "κ = [κ₀] = [{:?}, {:?}]: all roots in [{:?}, {:?}] (width {:.2e}), none unique: {}, contains μ*: {}",
        dr.kappa.lo,
        dr.kappa.hi,
        dr.enclosure.lo,
        dr.enclosure.hi,
        dr.enclosure_width,
        dr.none_unique,
        dr.contains_mu_star
    );
    outln!(
        "{:>3} {:>2}  {:<16} {:<14} {:>6} {:>5} {:>10} {:>10} {:>7} {:>7} {:>9}",
        "k",
        "±",
        "by κ₀ proof",
        "isolator",
        "unique",
        "undec",
        "width/ulp",
        "width",
        "evals",
        "bisect",
        "time/µs"
    );
    for r in &rep.rows {
        let outcome = match r.outcome {
            Outcome::NoRootProved => "0 roots proved",
            Outcome::TwoUnique => "2 unique",
            Outcome::Undecided => "undecided",
        };
        outln!(
            "{:>3} {:>2}  {:<16} {:<14} {:>6} {:>5} {:>10} {:>10.2e} {:>7} {:>7} {:>9.1}",
            r.k,
            if r.sign < 0 { "−" } else { "+" },
            r.by_kappa0.to_string(),
            outcome,
            r.unique_roots,
            r.undecided,
            r.max_width_ulps,
            r.max_width,
            r.evaluations,
            r.bisections,
            r.time_us
        );
    }
    for f in files {
        outln!("wrote {}", f.display());
    }
    Ok(())
}
