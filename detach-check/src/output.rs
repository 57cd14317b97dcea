//! The verdict lines that `detach-check` and `detach verify` print, so the
//! two commands read and exit alike.

use std::io::Write;
use std::path::{Path, PathBuf};

use super::{check_bytes, Verdict};

/// How one file (or one manifest line) went.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// A proof file whose claim is proved.
    Valid,
    /// A readable proof file (or a hash) that fails a check.
    Invalid,
    /// A file that cannot be read or is not a proof.
    Unreadable,
}

/// Checks the proof file at `path` and writes its verdict:
/// `VALID      FILE  CLAIM  (N UNIT, S s)`, the same with `INVALID` and the
/// first failed check on an indented second line, or `UNREADABLE FILE: WHY`.
pub fn check_and_print(path: &Path, out: &mut impl Write) -> Status {
    let shown = path.display();
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) => {
            let _ = writeln!(out, "UNREADABLE {shown}: {e}");
            return Status::Unreadable;
        }
    };
    match check_bytes(&bytes) {
        Err(e) => {
            let _ = writeln!(out, "UNREADABLE {shown}: {e}");
            Status::Unreadable
        }
        Ok(r) => {
            let (word, status, why) = match &r.verdict {
                Verdict::Valid => ("VALID", Status::Valid, String::new()),
                Verdict::Invalid(w) => ("INVALID", Status::Invalid, format!("\n    {w}")),
            };
            let _ = writeln!(
                out,
                "{word:<10} {shown}  {}  ({} {}, {:.3} s){why}",
                r.claim, r.checked, r.unit, r.seconds
            );
            status
        }
    }
}

/// The `.json` files directly in `dir`, sorted by name.
pub fn json_files(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|f| f.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    Ok(files)
}

/// Counts of each status over a run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    pub valid: usize,
    pub invalid: usize,
    pub unreadable: usize,
}

impl Tally {
    pub fn add(&mut self, s: Status) {
        match s {
            Status::Valid => self.valid += 1,
            Status::Invalid => self.invalid += 1,
            Status::Unreadable => self.unreadable += 1,
        }
    }

    /// The last line of a run, e.g. `9 valid, 0 invalid, 0 unreadable`.
    pub fn summary(&self) -> String {
        format!(
            "{} valid, {} invalid, {} unreadable",
            self.valid, self.invalid, self.unreadable
        )
    }

    /// The exit status and the message for stderr, if the run failed: 1 if
    /// any file is INVALID (a wrong claim outranks an unreadable file), else
    /// 2 if any cannot be read, else 0.
    pub fn failure(&self) -> Option<(u8, String)> {
        if self.invalid > 0 {
            Some((1, format!("{} proof(s) INVALID", self.invalid)))
        } else if self.unreadable > 0 {
            Some((2, format!("{} file(s) could not be read", self.unreadable)))
        } else {
            None
        }
    }
}
