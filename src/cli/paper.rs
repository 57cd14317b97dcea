//! `detach check-paper`: recompute every paper claim and write the report.

use super::{CliError, CliResult};
use detach::claims::{self, report};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct CheckPaperArgs {
    /// Print report.json to stdout instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Where to write REPORT.md, report.json and claims.toml.
    #[arg(long, default_value = "paper-checks")]
    pub out: PathBuf,
    /// Check only these claim ids (repeatable); the files are then not written.
    #[arg(long = "claim", value_name = "ID")]
    pub claims: Vec<String>,
}

pub fn run_check_paper(a: &CheckPaperArgs) -> CliResult {
    let results = claims::run(&a.claims).map_err(CliError::usage)?;
    if a.json {
        print!("{}", report::json(&results));
    } else {
        print!("{}", report::table(&results));
    }
    if a.claims.is_empty() {
        // The folder is replaced as a whole (files it holds that this run
        // does not write are kept): a kill leaves the old report or the new.
        let fail = |e: std::io::Error| CliError::runtime(format!("{}: {e}", a.out.display()));
        let draft = detach::files::FolderDraft::begin(&a.out).map_err(fail)?;
        let write = |name: &str, text: String| {
            let path = draft.path().join(name);
            detach::files::write_atomic(&path, text.as_bytes())
                .map_err(|e| super::cannot_write(&path, e))
        };
        write("REPORT.md", report::markdown(&results))?;
        write("report.json", report::json(&results))?;
        write("claims.toml", claims::TABLE.to_string())?;
        for r in results.iter().filter(|r| r.figure.is_some()) {
            let mark = claims::figures::witness_box(&r.witness);
            detach::figures::claims::draw_claim(&r.id, draft.path(), mark)
                .map_err(CliError::runtime)?;
        }
        draft.commit().map_err(fail)?;
    }
    let written = if a.claims.is_empty() {
        format!("; wrote {}", a.out.join("REPORT.md").display())
    } else {
        String::new()
    };
    // On stderr under --json, which keeps stdout one JSON document.
    let line = format!("{}{written}", report::summary(&results));
    if a.json {
        eprintln!("{line}");
    } else {
        outln!("{line}");
    }
    Ok(())
}
