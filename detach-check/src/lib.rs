//! Independent checker of `detach-proof/1` files (`proofs/FORMAT.md`).
//!
//! A proof file states one claim of detach — the areas of a paving, the
//! roots of an equation, the bound κ₀, the critical band, where in a
//! parameter box a set is empty or not, where a motion is at a time and when
//! it first crosses a watched function — and carries the
//! evidence for it. The checker confirms the claim by re-deriving every
//! enclosure from the statement and the evidence with its own JSON access,
//! expression parser, interval evaluator (forward-mode duals, nested for
//! second derivatives) and decoders: it replays a paving's tree from the root
//! box and re-decides every leaf label, sums areas exactly, re-checks every
//! root witness and exclusion piece, re-checks a trajectory's steps (Picard
//! inclusion of each a-priori box and its Taylor remainder), and compares
//! claimed bounds conservatively. The verdict is VALID, INVALID with the first failed check,
//! UNCHECKED past the limits for the file's size, or unreadable.
//!
//! # Trusted base
//!
//! [`inari`] for interval arithmetic (and the GMP/MPFR it is built on),
//! `serde_json` for reading JSON, the Rust compiler and its standard library,
//! and nothing else. The checker shares no code with the prover (the `detach`
//! crate, which depends on this one and re-exports it as `detach::check`), so
//! a bug there cannot hide itself here; `detach-check/tests/independence.rs`
//! fails if the manifest gains any other dependency or a build script, or the
//! sources name `detach`.
//!
//! The SHA-256 manifest that pins the committed proofs
//! (`proofs/MANIFEST.sha256`) needs a hash function, which is none of the
//! above, so the split is: `detach verify DIR` checks the manifest and calls
//! this crate for the proofs; `detach-check` checks the proofs alone, and
//! `sha256sum -c MANIFEST.sha256` in the folder checks the hashes.
//!
//! # Running it
//!
//! From the repository root, which builds this crate and not the prover:
//!
//! ```text
//! cargo run --release -p detach-check -- proofs/*.json
//! cargo install --path detach-check && detach-check proofs/kappa0.json
//! ```
//!
//! A directory argument stands for the `.json` files in it. One line per
//! file, as `detach verify` prints it: `VALID`, `INVALID` with the first
//! failed check, `UNREADABLE` or `UNCHECKED`; the exit status is 0 if all are
//! VALID, 1 if any is INVALID, else 2 if any cannot be read (or none was
//! found), else 3 if any is UNCHECKED. Only regular files are read, within
//! the limits of `proofs/FORMAT.md` ("Limits and files"). The repository's
//! `.cargo/config.toml` builds for the machine's CPU, since inari needs
//! AVX2/FMA on x86-64: elsewhere, set `RUSTFLAGS="-Ctarget-cpu=haswell"`.
//!
//! # Library
//!
//! - [`check_str`], [`check_bytes`], [`check_file`]: check one proof file.
//! - [`check_and_print`], [`Tally`]: the verdict lines and exit status of
//!   `detach-check` and `detach verify`.
//! - [`eval_on_box`]: evaluate one expression of the language on a box, as
//!   the checker does.
//! - [`StatedConstraints`]: decide one paving leaf's label from a
//!   statement's text, as the checker does.

mod area;
mod band;
mod empty;
mod encoding;
mod eval;
mod expr;
mod files;
mod json;
mod kappa0;
mod leaf;
mod ops;
mod output;
mod param_atlas;
mod paving;
mod pieces;
mod reach;
mod roots;
mod series;
mod trajectory;
mod tree;

pub use self::encoding::{base64_decode, decimal_enclosure, parse_hex_f64};
pub use self::eval::{with_loose_rounding, with_looseness, Looseness};
pub use self::files::{
    json_files, manifest_entries, read_regular, ManifestEntry, MANIFEST, MAX_MANIFEST_BYTES,
    MAX_PROOF_BYTES,
};
pub use self::leaf::StatedConstraints;
pub use self::output::{
    check_and_print, check_paths, shown, shown_cut, FolderFailures, Status, Tally, MAX_SHOWN_CHARS,
};

use inari::{DecInterval, Interval};
use std::fmt;
use std::time::Instant;

/// The outcome of checking a readable proof file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Every check passed: the claim is proved.
    Valid,
    /// The first check that failed: which leaf, piece or bound, with the
    /// claimed and the computed values.
    Invalid(String),
    /// The check stopped at the work bound for the file's size
    /// ([`work_bound`]): the claim is neither proved nor refuted.
    Unchecked(String),
}

/// Operations the check of a file of `bytes` bytes may evaluate (one per
/// interval or dual operation on a box): [`WORK_PER_BYTE`] per byte, and
/// at least [`WORK_FLOOR`]. With the 2²⁰-operation limit of a statement and
/// the leaves a file can hold, this bounds a check's time by its size.
pub fn work_bound(bytes: usize) -> u64 {
    (bytes as u64).saturating_mul(WORK_PER_BYTE).max(WORK_FLOOR)
}

/// See [`work_bound`].
pub const WORK_PER_BYTE: u64 = 1 << 6;

/// [`work_bound`] of a `trajectory` or `reach` file: [`SERIES_WORK_PER_BYTE`]
/// per byte, since a step of a few hundred bytes costs the Taylor series
/// of order K, O(K²) operations per operation of the equation, over a box
/// and in dual numbers.
pub fn series_work_bound(bytes: usize) -> u64 {
    (bytes as u64)
        .saturating_mul(SERIES_WORK_PER_BYTE)
        .max(WORK_FLOOR)
}

/// See [`series_work_bound`].
pub const SERIES_WORK_PER_BYTE: u64 = 1 << 10;

/// See [`work_bound`].
pub const WORK_FLOOR: u64 = 1 << 26;

/// Most JSON values (objects, arrays, strings, numbers, literals) a proof
/// file may hold: bounds the memory of its parsed form. The largest
/// committed proof has about 25 000.
pub const MAX_JSON_VALUES: usize = 1 << 21;

/// What was checked and how it went.
#[derive(Clone, Debug)]
pub struct Report {
    /// The verdict.
    pub verdict: Verdict,
    /// The claim in a few words, e.g. `paving viscous-disc/derived: 6 areas`.
    pub claim: String,
    /// How many leaves, pieces or steps were checked (up to the first failure).
    pub checked: u64,
    /// The unit of `checked`: `"leaves"`, `"pieces"` or `"steps"`.
    pub unit: &'static str,
    /// Wall-clock time of the check, in seconds.
    pub seconds: f64,
}

/// A file that is not a proof: not UTF-8 JSON, wrong format tag, missing
/// keys, values of the wrong type, unparsable strings, or an I/O error.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unreadable(pub String);

impl fmt::Display for Unreadable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "unreadable proof: {}", self.0)
    }
}

impl std::error::Error for Unreadable {}

impl From<String> for Unreadable {
    fn from(s: String) -> Self {
        Unreadable(s)
    }
}

/// The result of one claim check, before timing is attached.
pub(crate) struct Outcome {
    verdict: Verdict,
    claim: String,
    checked: u64,
    unit: &'static str,
}

impl Outcome {
    /// A check not done: past one of the limits of FORMAT.md, "Limits and files".
    fn unchecked(why: String, claim: String) -> Outcome {
        Outcome {
            verdict: Verdict::Unchecked(format!(
                "{why} (past the limits of proofs/FORMAT.md, \"Limits and files\")"
            )),
            claim,
            checked: 0,
            unit: "leaves",
        }
    }

    /// The outcome of a check whose `verify` returned `result` after `checked` units.
    fn of(result: Result<(), String>, claim: String, checked: u64, unit: &'static str) -> Outcome {
        let verdict = match result {
            Ok(()) => Verdict::Valid,
            Err(e) => Verdict::Invalid(e),
        };
        Outcome {
            verdict,
            claim,
            checked,
            unit,
        }
    }
}

/// Checks a proof given as text.
pub fn check_str(text: &str) -> Result<Report, Unreadable> {
    let start = Instant::now();
    let root = match read_value(text)? {
        Ok(root) => root,
        Err(out) => return Ok(report(out, start)),
    };
    let series = matches!(
        root.get("claim").and_then(serde_json::Value::as_str),
        Some("trajectory" | "reach")
    );
    let bound = if series {
        series_work_bound(text.len())
    } else {
        work_bound(text.len())
    };
    let (out, cut) = eval::with_work_bound(bound, || check_value(&root));
    // Past a limit every operation gave NaI, or the statement was cut off:
    // whatever the check concluded is no verdict.
    let limit = match cut {
        None => None,
        Some(eval::Cut::Work) => Some(format!(
            "stopped after {bound} operations, the bound for a file of {} bytes",
            text.len()
        )),
        Some(eval::Cut::Statement) => Some(format!(
            "a statement of more than {} operations",
            eval::MAX_OPS
        )),
    };
    let out = match (out, limit) {
        (Ok(o), None) => o,
        (Err(e), None) => return Err(e),
        (o, Some(why)) => Outcome::unchecked(why, o.map(|o| o.claim).unwrap_or_default()),
    };
    Ok(report(out, start))
}

fn report(out: Outcome, start: Instant) -> Report {
    Report {
        verdict: out.verdict,
        claim: out.claim,
        checked: out.checked,
        unit: out.unit,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// A file's text parsed, or why not (too many values: unchecked).
fn read_value(text: &str) -> Result<Result<serde_json::Value, Outcome>, Unreadable> {
    let values = json::count_values(text);
    if values > MAX_JSON_VALUES {
        return Ok(Err(Outcome::unchecked(
            format!("{values} JSON values, more than {MAX_JSON_VALUES}"),
            String::new(),
        )));
    }
    let root: serde_json::Value =
        serde_json::from_str(text).map_err(|e| Unreadable(format!("not JSON: {e}")))?;
    json::reject_duplicate_keys(text)?;
    Ok(Ok(root))
}

/// The claim check of a parsed file.
fn check_value(root: &serde_json::Value) -> Result<Outcome, Unreadable> {
    let obj = json::as_obj(root, "the file")?;
    let format = json::str_of(obj, "format")?;
    if format != "detach-proof/1" {
        return Err(Unreadable(format!("unknown format {format:?}")));
    }
    let out = match json::str_of(obj, "claim")? {
        "paving" => paving::check(obj)?,
        "roots" => roots::check(obj)?,
        "kappa0" => kappa0::check(obj)?,
        "critical-band" => band::check(obj)?,
        "parameter-atlas" => param_atlas::check(obj)?,
        "trajectory" => trajectory::check(obj)?,
        "reach" => reach::check(obj)?,
        other => return Err(Unreadable(format!("unknown claim {other:?}"))),
    };
    Ok(out)
}

/// Checks a proof given as bytes (must be UTF-8).
pub fn check_bytes(bytes: &[u8]) -> Result<Report, Unreadable> {
    let text = std::str::from_utf8(bytes).map_err(|e| Unreadable(format!("not UTF-8: {e}")))?;
    check_str(text)
}

/// Checks the proof file at `path` (a regular file of at most
/// [`MAX_PROOF_BYTES`]; see [`read_regular`]).
pub fn check_file(path: &std::path::Path) -> Result<Report, Unreadable> {
    let bytes = read_regular(path, MAX_PROOF_BYTES)
        .map_err(|e| Unreadable(format!("{}: {e}", path.display())))?;
    check_bytes(&bytes)
}

/// Evaluates `expr` on the box `t × w` exactly as the checker evaluates
/// paving constraints: parameters (name, decimal text) and definitions
/// (name, expression) declared in order, variables `t` and `w` decorated
/// `com`, every operation the decorated inari operation.
pub fn eval_on_box(
    parameters: &[(String, String)],
    definitions: &[(String, String)],
    expr: &str,
    t: Interval,
    w: Interval,
) -> Result<DecInterval, Unreadable> {
    let mut p = eval::Program::new(&["t", "w"])?;
    p.add_parameters(parameters)?;
    for (name, text) in definitions {
        p.define(name, text)?;
    }
    let s = p.compile(expr)?;
    Ok(p.value(&[DecInterval::new(t), DecInterval::new(w)], s))
}
