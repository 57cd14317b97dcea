//! The verdict lines that `detach-check` and `detach verify` print, so the
//! two commands read and exit alike. Every string that comes from a file
//! (or a file name) is printed through [`shown`]: no control character
//! reaches the terminal, so a file cannot print a verdict line of its own.

use std::io::Write;
use std::path::{Path, PathBuf};

use super::files::{json_files, read_regular, MAX_PROOF_BYTES};
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
    /// A proof whose check would exceed the bounds for its size (FORMAT.md,
    /// "Limits and files"): neither proved nor refuted.
    Unchecked,
}

/// Longest text from a file printed in one message (characters).
pub const MAX_SHOWN_CHARS: usize = 200;

/// `s` as printed: control characters (newline, ESC, …) escaped as `\n`,
/// `\u{1b}`, and cut after [`MAX_SHOWN_CHARS`] characters with the total
/// length stated.
pub fn shown(s: &str) -> String {
    shown_cut(s, MAX_SHOWN_CHARS)
}

/// [`shown`] with a cut after `max_chars` characters.
pub fn shown_cut(s: &str, max_chars: usize) -> String {
    let mut out = String::new();
    for (n, c) in s.chars().enumerate() {
        if n == max_chars {
            out.push_str(&format!("… ({} bytes)", s.len()));
            break;
        }
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// Checks the proof file at `path` and writes its verdict:
/// `VALID      FILE  CLAIM  (N UNIT, S s)`, the same with `INVALID` and the
/// first failed check on an indented second line, `UNCHECKED  FILE  CLAIM:
/// WHY`, or `UNREADABLE FILE: WHY`.
pub fn check_and_print(path: &Path, out: &mut impl Write) -> Status {
    let file = shown(&path.display().to_string());
    // A proof past the size cap may be true: not checked, not unreadable.
    if let Ok(m) = std::fs::metadata(path) {
        if m.is_file() && m.len() > MAX_PROOF_BYTES {
            let _ = writeln!(
                out,
                "UNCHECKED  {file}: {} bytes, more than {MAX_PROOF_BYTES} (past the limits of \
                 proofs/FORMAT.md, \"Limits and files\")",
                m.len()
            );
            return Status::Unchecked;
        }
    }
    let bytes = match read_regular(path, MAX_PROOF_BYTES) {
        Ok(b) => b,
        Err(e) => {
            let _ = writeln!(out, "UNREADABLE {file}: {}", shown(&e));
            return Status::Unreadable;
        }
    };
    match check_bytes(&bytes) {
        Err(e) => {
            let _ = writeln!(out, "UNREADABLE {file}: {}", shown(&e.to_string()));
            Status::Unreadable
        }
        Ok(r) => {
            let claim = shown(&r.claim);
            let (word, status, why) = match &r.verdict {
                Verdict::Valid => ("VALID", Status::Valid, String::new()),
                Verdict::Invalid(w) => ("INVALID", Status::Invalid, format!("\n    {}", shown(w))),
                Verdict::Unchecked(w) => {
                    let claim = if claim.is_empty() {
                        claim
                    } else {
                        format!("  {claim}")
                    };
                    let _ = writeln!(out, "UNCHECKED  {file}{claim}: {}", shown(w));
                    return Status::Unchecked;
                }
            };
            let _ = writeln!(
                out,
                "{word:<10} {file}  {claim}  ({} {}, {:.3} s){why}",
                r.checked, r.unit, r.seconds
            );
            status
        }
    }
}

/// The failures a folder's own check found before its proofs are checked
/// (`detach verify`: the manifest), each with the file it concerns, which is
/// then not checked again.
pub type FolderFailures = Vec<(Status, Option<PathBuf>)>;

/// Checks each path (a proof file, or a folder's `.json` files after
/// `folder_check`) and prints one line each: what `detach-check` and
/// `detach verify` run. The returned tally's [`Tally::failure`] gives the
/// exit status.
pub fn check_paths(
    paths: &[PathBuf],
    out: &mut impl Write,
    mut folder_check: impl FnMut(&Path, &mut dyn Write) -> FolderFailures,
) -> Tally {
    let mut tally = Tally::default();
    for p in paths {
        if !p.is_dir() {
            tally.add(check_and_print(p, out));
            continue;
        }
        let failed = folder_check(p, out);
        for (s, _) in &failed {
            tally.add(*s);
        }
        match json_files(p) {
            Ok(files) => {
                for f in files {
                    if !failed.iter().any(|(_, g)| g.as_deref() == Some(&*f)) {
                        tally.add(check_and_print(&f, out));
                    }
                }
            }
            Err(e) => {
                let _ = writeln!(out, "UNREADABLE {}: {e}", shown(&p.display().to_string()));
                tally.add(Status::Unreadable);
            }
        }
    }
    tally
}

/// Counts of each status over a run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    pub valid: usize,
    pub invalid: usize,
    pub unreadable: usize,
    pub unchecked: usize,
}

impl Tally {
    pub fn add(&mut self, s: Status) {
        match s {
            Status::Valid => self.valid += 1,
            Status::Invalid => self.invalid += 1,
            Status::Unreadable => self.unreadable += 1,
            Status::Unchecked => self.unchecked += 1,
        }
    }

    /// The last line of a run, e.g. `9 valid, 0 invalid, 0 unreadable`
    /// (`, 1 unchecked` when any is).
    pub fn summary(&self) -> String {
        let mut s = format!(
            "{} valid, {} invalid, {} unreadable",
            self.valid, self.invalid, self.unreadable
        );
        if self.unchecked > 0 {
            s.push_str(&format!(", {} unchecked", self.unchecked));
        }
        s
    }

    /// The exit status and the message for stderr, if the run failed: 1 if
    /// any file is INVALID (a wrong claim outranks the rest), else 2 if any
    /// cannot be read or there was nothing to check, else 3 if any is
    /// UNCHECKED, else 0.
    pub fn failure(&self) -> Option<(u8, String)> {
        if self.invalid > 0 {
            Some((1, format!("{} proof(s) INVALID", self.invalid)))
        } else if self.unreadable > 0 {
            Some((2, format!("{} file(s) could not be read", self.unreadable)))
        } else if self.valid + self.unchecked == 0 {
            Some((2, "nothing to check: no proof files given or found".into()))
        } else if self.unchecked > 0 {
            Some((
                3,
                format!(
                    "{} proof(s) UNCHECKED (past the limits for their size)",
                    self.unchecked
                ),
            ))
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shown_text_has_no_control_characters_and_is_cut() {
        let s = shown("a\nVALID \u{1b}[2K\r\t");
        assert_eq!(s, "a\\nVALID \\u{1b}[2K\\r\\t");
        let long = "x".repeat(50_000_000);
        let s = shown(&long);
        assert!(
            s.len() < 300 && s.ends_with("… (50000000 bytes)"),
            "{}",
            &s[..50]
        );
    }

    #[test]
    fn nothing_checked_is_a_failure() {
        assert_eq!(Tally::default().failure().map(|f| f.0), Some(2));
        let t = Tally {
            unchecked: 1,
            ..Tally::default()
        };
        assert_eq!(t.failure().map(|f| f.0), Some(3));
        let t = Tally {
            valid: 1,
            ..Tally::default()
        };
        assert_eq!(t.failure(), None);
    }
}
