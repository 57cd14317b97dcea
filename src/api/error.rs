//! The library's one error type: a kind a caller can branch on (Python
//! raises a class per kind), the argument at fault when there is one, and
//! the sentence to show. Sentences name arguments by the library's field
//! names (`eps`, `max_boxes`, `theta_dot`); a front end that spells them
//! otherwise (the command line's `--max-boxes`) renames them in one place
//! through [`Error::naming`].

use std::fmt;

/// What went wrong.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ErrorKind {
    /// An option out of its range or not of its form ([`Error::option`]
    /// names it).
    InvalidOption,
    /// A scene parameter: unknown to the scene, given twice, or text that is
    /// not a finite decimal number.
    InvalidParameter,
    /// A scene, region or cell name that is not known.
    UnknownName,
    /// A scene file that is not one: TOML, its tables, its formulas.
    SceneFile,
    /// A question this scene cannot answer (no `[dynamics]`, the printed
    /// reading of a scene file, a proof of an undecided run).
    Unsupported,
    /// The checker rejects a proof, or cannot check it.
    ProofRejected,
    /// Reading or writing a file failed.
    Io(std::io::ErrorKind),
    /// The computation itself failed (a paving's or an integrator's error).
    Computation,
}

/// An error of [`crate::api`]: its kind, the argument at fault and the
/// sentence.
///
/// ```
/// use detach::api::{ErrorKind, PaveRequest};
///
/// let e = PaveRequest { eps: 2.0, ..PaveRequest::default() }.options().unwrap_err();
/// assert_eq!(e.kind(), ErrorKind::InvalidOption);
/// assert_eq!(e.option(), Some("eps"));
/// assert_eq!(e.to_string(), "eps must be a finite number in (0, 1], got 2");
/// assert_eq!(e.naming(|o| format!("--{o}")), "--eps must be a finite number in (0, 1], got 2");
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Error {
    kind: ErrorKind,
    option: Option<&'static str>,
    /// The sentence; when `option` is set, what follows its name.
    text: String,
}

impl Error {
    /// An error of `kind` said by `text`.
    pub fn new(kind: ErrorKind, text: impl fmt::Display) -> Error {
        Error {
            kind,
            option: None,
            text: text.to_string(),
        }
    }

    /// The option `name` is at fault; `rest` follows its name in the
    /// sentence (` must be at least 1`, `: the window is empty`).
    pub fn invalid_option(name: &'static str, rest: impl fmt::Display) -> Error {
        Error {
            kind: ErrorKind::InvalidOption,
            option: Some(name),
            text: rest.to_string(),
        }
    }

    /// Reading or writing `shown` failed.
    pub fn io(what: &str, shown: &str, e: &std::io::Error) -> Error {
        let why = if e.kind() == std::io::ErrorKind::FileTooLarge {
            format!("{e}; the file-size limit (ulimit -f) is too small")
        } else {
            e.to_string()
        };
        Error::new(
            ErrorKind::Io(e.kind()),
            format!("cannot {what} {shown}: {why}"),
        )
    }

    pub fn kind(&self) -> ErrorKind {
        self.kind
    }

    /// The option at fault, by its field name, when there is one.
    pub fn option(&self) -> Option<&'static str> {
        self.option
    }

    /// The sentence with the option at fault renamed by `name`.
    pub fn naming(&self, name: impl Fn(&str) -> String) -> String {
        match self.option {
            Some(o) => format!("{}{}", name(o), self.text),
            None => self.text.clone(),
        }
    }

    /// Whether the input was at fault (the command line's exit code 2)
    /// rather than the run (exit code 1).
    pub fn is_input(&self) -> bool {
        !matches!(
            self.kind,
            ErrorKind::Io(_) | ErrorKind::ProofRejected | ErrorKind::Computation
        )
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.naming(|o| o.to_string()))
    }
}

impl std::error::Error for Error {}

/// The sentence alone, for a front end that shows text (the explorer's
/// page names the library's fields as they are).
impl From<Error> for String {
    fn from(e: Error) -> String {
        e.to_string()
    }
}

impl From<crate::number::param::ParamError> for Error {
    fn from(e: crate::number::param::ParamError) -> Error {
        use crate::number::param::ParamError as P;
        match e {
            P::Window { name, reason } => {
                let field = if name == "theta" {
                    "theta"
                } else {
                    "theta_dot"
                };
                Error::invalid_option(field, format!(": {reason}"))
            }
            _ => Error::new(ErrorKind::InvalidParameter, e),
        }
    }
}
