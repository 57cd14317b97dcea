//! `detach prove` and `detach verify`: proof files and their independent check.

use super::{write_checked, CliError, CliResult};
use detach::certificate::catalog::file_name;
use detach::certificate::{paving_proof, prove_named, PavingStatement, HEADLINE};
use detach::check::{
    check_paths, manifest_entries, read_regular, shown, FolderFailures, ManifestEntry, Status,
    MANIFEST, MAX_PROOF_BYTES,
};
use detach::number::param::ParamSet;
use detach::pave::Paving;
use detach::scene::{Domain, Scene, Variant};
use sha2::{Digest, Sha256};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Write proof files of headline results (default: all) and their manifest.
#[derive(clap::Args, Debug)]
pub struct ProveArgs {
    /// Output directory.
    #[arg(long, default_value = "proofs")]
    pub out: PathBuf,
    /// Results to prove, e.g. `atlas/viscous-disc/derived`, `kappa0`,
    /// `roots/2.10`; none: every headline result.
    #[arg(value_name = "WHAT")]
    pub what: Vec<String>,
}

/// Check proof files or folders of them (with their MANIFEST.sha256).
#[derive(clap::Args, Debug)]
pub struct VerifyArgs {
    /// Proof files or directories.
    #[arg(value_name = "PATH", required = true)]
    pub paths: Vec<PathBuf>,
}

fn hex_digest(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// The manifest of the proof files `names` (this run's) in `dir`, in
/// `sha256sum` format.
/// Writes `MANIFEST.sha256` into `dir`, hashing each file from `dir` or, when
/// `dir` does not hold it, from `kept` (the folder it will be carried over from).
fn write_manifest(dir: &Path, kept: &Path, names: &[String]) -> CliResult {
    let mut names = names.to_vec();
    names.sort();
    let mut text = String::new();
    for n in &names {
        let from = if dir.join(n).is_file() { dir } else { kept };
        let bytes = std::fs::read(from.join(n))
            .map_err(|e| CliError::runtime(format!("cannot read {n}: {e}")))?;
        text.push_str(&format!("{}  {n}\n", hex_digest(&bytes)));
    }
    let path = dir.join("MANIFEST.sha256");
    detach::files::write_atomic(&path, text.as_bytes()).map_err(|e| super::cannot_write(&path, e))
}

pub fn run_prove(args: &ProveArgs) -> CliResult {
    let names: Vec<String> = if args.what.is_empty() {
        HEADLINE.iter().map(|s| s.to_string()).collect()
    } else {
        args.what.clone()
    };
    // Refuse unknown names before any work.
    for n in &names {
        if !HEADLINE.contains(&n.as_str()) {
            return Err(CliError::usage(format!(
                "unknown result `{n}` (known: {})",
                HEADLINE.join(", ")
            )));
        }
    }
    // The folder is replaced as a whole (files it holds that this run does
    // not write are kept): a kill leaves the old folder or the new one.
    let draft = detach::files::FolderDraft::begin(&args.out)
        .map_err(|e| CliError::runtime(format!("cannot write {}: {e}", args.out.display())))?;
    let mut lines = Vec::new();
    let mut written = Vec::new();
    for n in &names {
        let t = Instant::now();
        let proof = prove_named(n).map_err(CliError::usage)?;
        let prover_s = t.elapsed().as_secs_f64();
        let path = draft.path().join(file_name(n));
        let (bytes, check_s, units) = write_checked(&path, &proof)?;
        written.push(file_name(n));
        lines.push(format!(
            "{:<34} {:>9} B  {:<16} prover {:.3} s  checker {:.3} s",
            file_name(n),
            bytes,
            units,
            prover_s,
            check_s
        ));
    }
    // The manifest lists every headline file the folder will hold: the ones
    // written now and the ones the commit carries over from the old folder.
    let listed: Vec<String> = HEADLINE
        .iter()
        .map(|n| file_name(n))
        .filter(|f| written.contains(f) || args.out.join(f).is_file())
        .collect();
    write_manifest(draft.path(), &args.out, &listed)?;
    draft
        .commit()
        .map_err(|e| CliError::runtime(format!("cannot write {}: {e}", args.out.display())))?;
    let mut out = std::io::stdout().lock();
    for l in lines {
        let _ = writeln!(out, "{l}");
    }
    let _ = writeln!(out, "wrote {}", args.out.join("MANIFEST.sha256").display());
    Ok(())
}

/// Checks `MANIFEST.sha256` of a folder: every listed file present with its
/// hash; a manifest that cannot be read, or names a file outside the folder,
/// fails (the checker crate reads and parses it; the hash is detach's own,
/// since the checker has no hash function). Returns each failure's status
/// and, for a file, its path (a file failed here is reported once, not
/// checked again).
fn verify_manifest(dir: &Path, out: &mut dyn Write) -> FolderFailures {
    let entries = match manifest_entries(dir) {
        Ok(None) => return vec![],
        Ok(Some(e)) => e,
        Err(e) => {
            let _ = writeln!(out, "UNREADABLE {}", shown(&e));
            return vec![(Status::Unreadable, None)];
        }
    };
    let mut res = Vec::new();
    for ManifestEntry { sha256, path } in entries {
        let file = shown(&path.display().to_string());
        match read_regular(&path, MAX_PROOF_BYTES) {
            Ok(b) if hex_digest(&b) == sha256 => {}
            Ok(_) => {
                let _ = writeln!(out, "INVALID    {file}: SHA-256 differs from {MANIFEST}");
                res.push((Status::Invalid, Some(path)));
            }
            Err(e) => {
                let _ = writeln!(out, "UNREADABLE {file}: {}", shown(&e));
                res.push((Status::Unreadable, Some(path)));
            }
        }
    }
    res
}

/// The manifest of each folder, then each proof through the checker crate,
/// with `detach-check`'s lines and exit status.
pub fn run_verify(args: &VerifyArgs) -> CliResult {
    let mut out = std::io::stdout().lock();
    let tally = check_paths(&args.paths, &mut out, verify_manifest);
    let _ = writeln!(out, "{}", tally.summary());
    match tally.failure() {
        None => Ok(()),
        Some((code, message)) => Err(CliError {
            message,
            code: code.into(),
        }),
    }
}

/// `pave --proof FILE`: the paving of this run as a proof file.
pub fn write_paving_proof(
    path: &Path,
    scene: &Scene,
    params: &ParamSet,
    variant: Variant,
    domain: &Domain,
    domain_text: [[String; 2]; 2],
    paving: &Paving,
) -> CliResult {
    let proof = paving_proof(
        &PavingStatement {
            scene,
            variant,
            params,
            domain,
            domain_text,
            title: match scene.id() {
                Some(id) => format!("Ω, Ω₀ and the four cells of the {id} ({variant})"),
                None => format!("Ω, Ω₀ and the four cells of {}", scene.title()),
            },
        },
        paving,
    );
    let (bytes, _, units) = write_checked(path, &proof)?;
    eprintln!(
        "wrote {} ({bytes} B, {units}, checked VALID)",
        detach::files::shown(path)
    );
    Ok(())
}
