//! `detach`: certified detachment-region atlases and root bounds.

mod cli;

use clap::{Parser, Subcommand};
use cli::area::AreaArgs;
use cli::atlas::{AtlasArgs, PaveArgs, ScenesArgs};
use cli::proofs::{ProveArgs, VerifyArgs};
use cli::roots::{CriticalCurveArgs, Kappa0Args, RootsArgs, TangencyArgs};
use cli::stability::StabilityArgs;
use cli::CliResult;

/// Certified detachment regions of systems with a unilateral constraint
/// (A. P. Ivanov, 2008). Without a subcommand: `detach atlas`.
#[derive(Parser, Debug)]
#[command(name = "detach", version = detach::LONG_VERSION, about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Pave all scenes and write the certified atlas (SVG, PNG, summary.json).
    Atlas(AtlasArgs),
    /// Pave one scene and print its area bounds (table or --json).
    Pave(PaveArgs),
    /// Certified areas of Ω, Ω₀ and the four cells by quadrature over θ.
    Area(AreaArgs),
    /// Where each paving method fails: maps per scene and a stress-case table.
    Stability(StabilityArgs),
    /// List the scenes, their parameters, defaults, domains and variants.
    Scenes(ScenesArgs),
    /// Certified roots of (2.9), (2.10), (2.12) or the equilibria of (3.3).
    Roots(RootsArgs),
    /// Prove κ₀ = √3/9 and the root counts of (2.10) on both sides of it.
    Kappa0(Kappa0Args),
    /// Map the tangency κ → κ₀: what the isolator certifies at κ₀(1 ± 10⁻ᵏ).
    Tangency(TangencyArgs),
    /// Certified band of κ_crit(α) and the (α, κ) atlas of (2.9).
    CriticalCurve(CriticalCurveArgs),
    /// Write proof files of the headline results and their MANIFEST.sha256.
    Prove(ProveArgs),
    /// Check proof files independently of the code that produced them.
    Verify(VerifyArgs),
    /// Recompute every checked claim of the paper and write paper-checks/.
    CheckPaper(cli::paper::CheckPaperArgs),
    /// Certified parameter atlas: where each set is empty or not, thresholds.
    Params(cli::params::ParamsArgs),
    /// Join the JSON parts of a `detach params --shard` run.
    Merge(cli::params::MergeArgs),
    /// A certified trajectory of a scene's [dynamics], to T or its first event.
    Flow(cli::flow::FlowArgs),
    /// Certified equilibria and singular points of `[dynamics]`, typed.
    Singular(cli::singular::SingularArgs),
    /// Initial states that reach a target within a time: a certified paving.
    Reach(cli::reach::ReachArgs),
    /// A local page where the certified atlas follows the parameters.
    Explore(cli::explore::ExploreArgs),
}

/// The command line; `detach` alone runs `detach atlas`.
fn parse() -> Command {
    Cli::parse().command.unwrap_or_else(|| {
        let Some(c) = Cli::parse_from(["detach", "atlas"]).command else {
            unreachable!("atlas parses")
        };
        c
    })
}

fn run(command: Command) -> CliResult {
    match command {
        Command::Atlas(a) => cli::atlas::run_atlas(&a),
        Command::Pave(a) => cli::atlas::run_pave(&a),
        Command::Area(a) => cli::area::run_area(&a),
        Command::Stability(a) => cli::stability::run_stability(&a),
        Command::Scenes(a) => cli::atlas::run_scenes(&a),
        Command::Roots(a) => cli::roots::run_roots(&a),
        Command::Kappa0(a) => cli::roots::run_kappa0(&a),
        Command::Tangency(a) => cli::roots::run_tangency(&a),
        Command::CriticalCurve(a) => cli::roots::run_critical_curve(&a),
        Command::Prove(a) => cli::proofs::run_prove(&a),
        Command::Verify(a) => cli::proofs::run_verify(&a),
        Command::CheckPaper(a) => cli::paper::run_check_paper(&a),
        Command::Params(a) => cli::params::run_params(&a),
        Command::Merge(a) => cli::params::run_merge(&a),
        Command::Flow(a) => cli::flow::run_flow(&a),
        Command::Singular(a) => cli::singular::run_singular(&a),
        Command::Reach(a) => cli::reach::run_reach(&a),
        Command::Explore(a) => cli::explore::run_explore(&a),
    }
}

fn main() -> std::process::ExitCode {
    // First, before any thread: a signal removes temporaries, not outputs.
    detach::files::remove_temporaries_on_signals();
    match run(parse()).and_then(|()| cli::stdout_status()) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            // A message may quote input (a scene file's text): each line is
            // printed escaped and cut, never a whole file.
            let lines: Vec<String> = e
                .message
                .lines()
                .map(|l| detach::check::shown_cut(l, 1000))
                .collect();
            eprintln!("detach: {}", lines.join("\n"));
            std::process::ExitCode::from(u8::try_from(e.code).unwrap_or(1))
        }
    }
}
