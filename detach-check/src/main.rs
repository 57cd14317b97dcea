//! `detach-check FILE|DIR...`: checks proof files, one verdict line each.

use detach_check::check_paths;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

const USAGE: &str = "\
usage: detach-check FILE|DIR...

Checks each detach-proof/1 file (for a directory, each *.json in it) and
prints one line per file: VALID, INVALID with the first failed check,
UNREADABLE, or UNCHECKED (past the limits for the file's size). Exit status:
0 if all are VALID, 1 if any is INVALID, else 2 if any cannot be read or no
file was found, else 3 if any is UNCHECKED. MANIFEST.sha256 is not checked here: `sha256sum -c
MANIFEST.sha256` in the folder, or `detach verify DIR`, checks it.";

fn main() -> ExitCode {
    let mut paths = Vec::new();
    let mut options_done = false;
    for a in std::env::args_os().skip(1) {
        if !options_done && a.to_str().is_some_and(|s| s.starts_with('-')) {
            match a.to_str() {
                Some("--") => options_done = true,
                Some("-h" | "--help") => {
                    println!("{USAGE}");
                    return ExitCode::SUCCESS;
                }
                Some("-V" | "--version") => {
                    println!("detach-check {}", env!("CARGO_PKG_VERSION"));
                    return ExitCode::SUCCESS;
                }
                _ => {
                    eprintln!(
                        "detach-check: unknown option {}\n\n{USAGE}",
                        a.to_string_lossy()
                    );
                    return ExitCode::from(2);
                }
            }
        } else {
            paths.push(PathBuf::from(a));
        }
    }
    if paths.is_empty() {
        eprintln!("{USAGE}");
        return ExitCode::from(2);
    }

    let mut out = std::io::stdout().lock();
    let tally = check_paths(&paths, &mut out, |_, _| Vec::new());
    let _ = writeln!(out, "{}", tally.summary());
    if let Err(e) = out.flush() {
        // As `detach`: a failed write is a run-time failure, not bad input.
        eprintln!("detach-check: cannot write to stdout: {e}");
        return ExitCode::from(1);
    }
    match tally.failure() {
        None => ExitCode::SUCCESS,
        Some((code, message)) => {
            eprintln!("detach-check: {message}");
            ExitCode::from(code)
        }
    }
}
