//! `detach`: certified detachment-region atlases and root bounds.
//!
//! The C `main` is the entry point (`no_main`): Rust's runtime start-up finds
//! the main thread's stack through `/proc/self/maps` and installs
//! stack-overflow handlers, about 70 µs of every run, which is much of a
//! coarse paving's whole-process time. Without it a stack overflow is a plain
//! SIGSEGV; SIGPIPE is ignored here as Rust's start-up would (see `outln!`).
// (The test harness brings its own `main`.)
#![cfg_attr(not(test), no_main)]

mod cli;

use clap::{Parser, Subcommand};
use cli::area::AreaArgs;
use cli::atlas::{AtlasArgs, PaveArgs, ScenesArgs};
use cli::methods::MethodsArgs;
use cli::proofs::{ProveArgs, VerifyArgs};
use cli::roots::{CriticalCurveArgs, Kappa0Args, RootsArgs, TangencyArgs};
use cli::stability::StabilityArgs;
use cli::CliResult;
use std::ffi::OsString;

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
    #[command(about = PAVE_ABOUT)]
    Pave(PaveArgs),
    /// Certified areas of Ω, Ω₀ and the four cells by quadrature over θ.
    Area(AreaArgs),
    /// Run every paving method over a range of ε: table, JSON, speed–accuracy chart.
    Methods(MethodsArgs),
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
}

const PAVE_ABOUT: &str = "Pave one scene and print its area bounds (table or --json)";

/// `detach pave …` alone: clap builds the arguments of every subcommand it
/// is given, about 0.1 ms of a run, and `pave` is what a benchmark spawns.
#[derive(Parser, Debug)]
#[command(name = "detach", version = detach::LONG_VERSION)]
struct PaveCli {
    #[command(subcommand)]
    command: PaveCommand,
}

#[derive(Subcommand, Debug)]
enum PaveCommand {
    #[command(about = PAVE_ABOUT)]
    Pave(PaveArgs),
}

/// The command line, with only `pave`'s arguments built when it is `pave`.
fn parse(args: Vec<OsString>) -> Command {
    if args.get(1).is_some_and(|a| a == "pave") {
        let PaveCommand::Pave(a) = PaveCli::parse_from(args).command;
        return Command::Pave(a);
    }
    Cli::parse_from(args).command.unwrap_or_else(|| {
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
        Command::Methods(a) => cli::methods::run_methods(&a),
        Command::Stability(a) => cli::stability::run_stability(&a),
        Command::Scenes(a) => cli::atlas::run_scenes(&a),
        Command::Roots(a) => cli::roots::run_roots(&a),
        Command::Kappa0(a) => cli::roots::run_kappa0(&a),
        Command::Tangency(a) => cli::roots::run_tangency(&a),
        Command::CriticalCurve(a) => cli::roots::run_critical_curve(&a),
        Command::Prove(a) => cli::proofs::run_prove(&a),
        Command::Verify(a) => cli::proofs::run_verify(&a),
        Command::CheckPaper(a) => cli::paper::run_check_paper(&a),
    }
}

/// The process entry point, called by the C start-up.
///
/// # Safety
/// `argv` holds `argc` valid NUL-terminated strings, as C's `main` receives.
#[cfg(not(test))]
#[no_mangle]
pub unsafe extern "C" fn main(argc: libc::c_int, argv: *const *const libc::c_char) -> libc::c_int {
    use std::os::unix::ffi::OsStrExt;
    let args = (0..usize::try_from(argc).unwrap_or(0))
        // SAFETY: the C start-up passes `argc` valid NUL-terminated strings.
        .map(|i| unsafe { std::ffi::CStr::from_ptr(*argv.add(i)) })
        .map(|a| std::ffi::OsStr::from_bytes(a.to_bytes()).to_owned())
        .collect();
    cli_main(args)
}

/// Runs the command line; the exit code. (Dead in test builds, whose
/// harness has its own `main`.)
#[cfg_attr(test, allow(dead_code))]
fn cli_main(args: Vec<OsString>) -> libc::c_int {
    // SAFETY: sets a signal disposition at start-up, before any thread exists.
    unsafe { libc::signal(libc::SIGPIPE, libc::SIG_IGN) };
    let code = match run(parse(args)).and_then(|()| cli::stdout_status()) {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("detach: {}", e.message);
            e.code
        }
    };
    // Flushes stdout (the runtime's clean-up) and exits.
    std::process::exit(code)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What clap prints or parses for a `pave` command line, by the full
    /// command and by `pave` alone.
    fn both(args: &[&str]) -> (String, String) {
        let line = || std::iter::once("detach").chain(args.iter().copied());
        let full = match Cli::try_parse_from(line()) {
            Ok(c) => format!("{:?}", c.command),
            Err(e) => e.render().to_string(),
        };
        let alone = match PaveCli::try_parse_from(line()) {
            Ok(PaveCli {
                command: PaveCommand::Pave(a),
            }) => format!("{:?}", Some(Command::Pave(a))),
            Err(e) => e.render().to_string(),
        };
        (full, alone)
    }

    #[test]
    fn pave_alone_parses_and_helps_as_the_full_command() {
        for args in [
            &["pave", "--help"][..],
            &["pave", "-h"],
            &["pave"],
            &["pave", "--bogus"],
            &["pave", "--scene"],
            &["pave", "--scene", "viscous-disc", "--method", "foo"],
            &["pave", "--scene", "ice-disc", "--eps", "0.1", "--json"],
            &[
                "pave",
                "--scene",
                "smooth-disc",
                "--param",
                "a=2",
                "--theta=-1:2",
                "x",
            ],
        ] {
            let (full, alone) = both(args);
            assert_eq!(full, alone, "{args:?}");
        }
    }
}
