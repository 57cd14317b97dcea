//! `detach`: certified detachment-region atlases and root bounds.

mod cli;

use clap::{Parser, Subcommand};
use cli::atlas::{AtlasArgs, PaveArgs, ScenesArgs};
use cli::CliResult;

/// Certified detachment regions of systems with a unilateral constraint
/// (A. P. Ivanov, 2008). Without a subcommand: `detach atlas`.
#[derive(Parser, Debug)]
#[command(name = "detach", version, about)]
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
    /// List the scenes, their parameters, defaults, domains and variants.
    Scenes(ScenesArgs),
}

fn run(command: Command) -> CliResult {
    match command {
        Command::Atlas(a) => cli::atlas::run_atlas(&a),
        Command::Pave(a) => cli::atlas::run_pave(&a),
        Command::Scenes(a) => cli::atlas::run_scenes(&a),
    }
}

fn main() {
    let command = Cli::parse().command.unwrap_or_else(|| {
        let Some(c) = Cli::parse_from(["detach", "atlas"]).command else {
            unreachable!("atlas parses")
        };
        c
    });
    if let Err(e) = run(command) {
        eprintln!("detach: {}", e.message);
        std::process::exit(e.code);
    }
}
