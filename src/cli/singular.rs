//! `detach singular`: certified equilibria and singular points of a scene's
//! `[dynamics]`, with their type; over a parameter interval, the thresholds
//! where their number or type changes.

use super::atlas::{split_window, windowed_domain};
use super::{CliError, CliResult};
use detach::api::{ParamRequest, Variant};
use detach::motion::singular::{self, Point, Report, Scan, ScanOptions};
use detach::params::report::exact_decimal;

#[derive(clap::Args, Debug)]
pub struct SingularArgs {
    #[command(flatten)]
    pub source: super::SceneSource,
    /// Override a parameter, as decimal text (repeatable).
    #[arg(long = "param", value_name = "NAME=VALUE")]
    pub params: Vec<String>,
    /// Restrict θ to a window `LO:HI` (decimal text, `pi`, `pi/N`).
    #[arg(long, value_name = "LO:HI", allow_hyphen_values = true)]
    pub theta: Option<String>,
    /// Restrict θ̇ to a window `LO:HI`.
    #[arg(long = "theta-dot", value_name = "LO:HI", allow_hyphen_values = true)]
    pub theta_dot: Option<String>,
    /// Vary one parameter over `LO:HI` (decimal text): the thresholds where
    /// the number or type of the points changes.
    #[arg(long, value_name = "NAME=LO:HI", allow_hyphen_values = true)]
    pub x: Option<String>,
    /// With --x: parameter boxes narrower than this fraction of the range
    /// are not split further.
    #[arg(long)]
    pub eps: Option<f64>,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

fn text(x: inari::Interval) -> String {
    format!("[{}, {}]", exact_decimal(x.inf()), exact_decimal(x.sup()))
}

fn print_points(r: &Report) {
    outln!(
        "  {:<12} {:<44} {:<44} {:<15} eigenvalues",
        "kind",
        "theta",
        "theta_dot",
        "type"
    );
    for p in &r.points {
        outln!(
            "  {:<12} {:<44} {:<44} {:<15} {}",
            p.kind.name(),
            text(p.theta),
            text(p.theta_dot),
            p.point_type.name(),
            eigen_text(p)
        );
    }
    if r.points.is_empty() {
        outln!("  (no point)");
    }
    for u in &r.undecided {
        outln!(
            "  undecided {:<11} θ ∈ {}, θ̇ ∈ {}: {}",
            u.kind.name(),
            text(u.theta),
            text(u.theta_dot),
            u.reason
        );
    }
}

fn eigen_text(p: &Point) -> String {
    let Some(e) = p.eigenvalues else {
        return "not proved real".into();
    };
    let dir = |i: usize| {
        p.directions
            .map(|d| format!(" ({})", d[i].name()))
            .unwrap_or_default()
    };
    let slow = match (p.slower, p.slow_direction()) {
        (_, Some(d)) => format!("; slower: {}", d.name()),
        (Some(i), None) => format!("; slower: #{}", i + 1),
        _ => String::new(),
    };
    format!("{}{}, {}{}{slow}", text(e[0]), dir(0), text(e[1]), dir(1))
}

fn print_scan(s: &Scan) {
    outln!("{} over [{}, {}]:", s.name, s.lo_text, s.hi_text);
    for t in &s.thresholds {
        outln!(
            "  threshold {} ∈ [{}, {}] (width {})",
            s.name,
            exact_decimal(t.lo),
            exact_decimal(t.hi),
            exact_decimal(t.width())
        );
        outln!("    below: {}", t.below.join("; "));
        outln!("    above: {}", t.above.join("; "));
    }
    if s.thresholds.is_empty() {
        outln!("  (no threshold proved)");
    }
    // Runs of boxes with the same classification, as one range each.
    let mut i = 0;
    while i < s.boxes.len() {
        let mut j = i;
        while j + 1 < s.boxes.len() && s.boxes[j + 1].signature == s.boxes[i].signature {
            j += 1;
        }
        let what = match &s.boxes[i].signature {
            Some(v) if v.is_empty() => "no point".to_string(),
            Some(v) => v.join("; "),
            None => "undecided".to_string(),
        };
        outln!(
            "  {} ∈ [{}, {}] ({} boxes): {what}",
            s.name,
            exact_decimal(s.boxes[i].lo),
            exact_decimal(s.boxes[j].hi),
            j - i + 1
        );
        i = j + 1;
    }
}

pub fn run_singular(args: &SingularArgs) -> CliResult {
    let overrides = super::parse_overrides(&args.params)?;
    let problem = args.source.problem(&overrides, Variant::Derived)?;
    let scene = &problem.scene;
    if !scene.reading(Variant::Derived).has_dynamics() {
        return Err(CliError::usage(format!(
            "scene `{}` has no [dynamics]: there is no θ̈ to find equilibria of",
            scene.name()
        )));
    }
    let th = split_window("theta", &args.theta)?;
    let thd = split_window("theta-dot", &args.theta_dot)?;
    let domain = windowed_domain(scene, &th, &thd)?;
    let Some(x) = &args.x else {
        let r = singular::find(
            scene.reading(Variant::Derived),
            &domain,
            &Default::default(),
        )
        .map_err(CliError::usage)?;
        if args.json {
            let mut doc = singular::report_json(&r);
            doc["scene"] = scene.name().into();
            outln!("{}", serde_json::to_string_pretty(&doc).expect("JSON"));
        } else {
            outln!("{}: equilibria and singular points", scene.name());
            print_points(&r);
        }
        return Ok(());
    };
    let axis = ParamRequest::axis(x).map_err(|e| CliError::usage(format!("--x: {e}")))?;
    let mut opts = ScanOptions::default();
    if let Some(eps) = args.eps {
        opts.eps = detach::api::open_resolution(eps)?;
    }
    let family = problem.family(vec![axis])?;
    let s = singular::scan(&family, &domain, &opts).map_err(CliError::usage)?;
    if args.json {
        let mut doc = singular::scan_json(&s, family.root[0]);
        doc["scene"] = scene.name().into();
        outln!("{}", serde_json::to_string_pretty(&doc).expect("JSON"));
    } else {
        print_scan(&s);
    }
    Ok(())
}
