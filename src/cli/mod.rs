//! Command-line front: argument types and one `run_*` per subcommand.

/// `println!` for command output: a closed pipe (`detach … | head -1`) is not
/// an error — output stops quietly and the command finishes its work (files
/// included); any other write error is reported by [`stdout_status`].
macro_rules! outln {
    ($($t:tt)*) => {
        $crate::cli::write_stdout(format_args!($($t)*))
    };
}

pub mod area;
pub mod atlas;
pub mod explore;
pub mod flow;
pub mod paper;
pub mod params;
pub mod proofs;
pub mod reach;
pub mod roots;
pub mod singular;
pub mod stability;

use std::fmt;
use std::io::Write;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

static STDOUT_CLOSED: AtomicBool = AtomicBool::new(false);
static STDOUT_ERROR: Mutex<Option<String>> = Mutex::new(None);
/// Set when a file option is `-`: standard output then carries that file
/// alone, and the command's table goes to stderr.
static STDOUT_TAKEN: AtomicBool = AtomicBool::new(false);

/// Writes one line to stdout (stderr if a file option took stdout); see
/// `outln!`.
pub fn write_stdout(args: fmt::Arguments) {
    if STDOUT_TAKEN.load(Ordering::Relaxed) {
        eprintln!("{args}");
        return;
    }
    if STDOUT_CLOSED.load(Ordering::Relaxed) {
        return;
    }
    let mut out = std::io::stdout().lock();
    let r = out
        .write_fmt(args)
        .and_then(|_| out.write_all(b"\n"))
        .and_then(|_| out.flush());
    if let Err(e) = r {
        STDOUT_CLOSED.store(true, Ordering::Relaxed);
        if e.kind() != std::io::ErrorKind::BrokenPipe {
            if let Ok(mut slot) = STDOUT_ERROR.lock() {
                slot.get_or_insert_with(|| e.to_string());
            }
        }
    }
}

/// An error for a failed write to stdout (other than a closed pipe), if any.
pub fn stdout_status() -> CliResult {
    match STDOUT_ERROR.lock().ok().and_then(|s| s.clone()) {
        Some(e) => Err(CliError::runtime(format!("cannot write to stdout: {e}"))),
        None => Ok(()),
    }
}

/// Lets at most one output go to standard output: of the file options given
/// as `(flag, path)`, one may be `-` (or `/dev/stdout`), and not with
/// `--json`; the table then goes to stderr.
pub fn take_stdout(files: &[(&str, Option<&Path>)], json: bool) -> CliResult {
    let dashes: Vec<&str> = files
        .iter()
        .filter(|(_, p)| p.is_some_and(detach::files::is_stdout))
        .map(|(flag, _)| *flag)
        .collect();
    match (dashes.as_slice(), json) {
        ([], _) => Ok(()),
        ([_], false) => {
            STDOUT_TAKEN.store(true, Ordering::Relaxed);
            Ok(())
        }
        ([flag], true) => Err(CliError::usage(format!(
            "--json and {flag} - both write to standard output; give {flag} a file"
        ))),
        ([a, b, ..], _) => Err(CliError::usage(format!(
            "{a} and {b} both write to standard output; give one of them a file"
        ))),
    }
}

/// A failure to report on stderr, with its exit code (2 = bad input).
#[derive(Debug)]
pub struct CliError {
    pub message: String,
    pub code: i32,
}

impl CliError {
    /// Bad input: exit code 2.
    pub fn usage(message: impl fmt::Display) -> Self {
        CliError {
            message: message.to_string(),
            code: 2,
        }
    }
    /// Failure while running (I/O, drawing): exit code 1.
    pub fn runtime(message: impl fmt::Display) -> Self {
        CliError {
            message: message.to_string(),
            code: 1,
        }
    }
}

pub type CliResult = Result<(), CliError>;

/// The command line's flag for a library field name: `max_boxes` →
/// `--max-boxes`. The one place where the library's names become flags.
pub fn flag(field: &str) -> String {
    format!("--{}", field.replace('_', "-"))
}

/// A library error as the command line says it: its option named as a
/// flag; bad input exits 2, a failed run 1.
impl From<detach::api::Error> for CliError {
    fn from(e: detach::api::Error) -> CliError {
        CliError {
            message: e.naming(flag),
            code: if e.is_input() { 2 } else { 1 },
        }
    }
}

/// The machine a measurement ran on: `uname -a`, cores, threads, load.
pub fn machine() -> serde_json::Value {
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let uname = std::process::Command::new("uname")
        .arg("-a")
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default();
    serde_json::json!({
        "uname": uname,
        "nproc": std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1),
        "threads": rayon::current_num_threads(),
        "loadavg": load.split_whitespace().take(3).collect::<Vec<_>>().join(" "),
    })
}

/// Checks a proof with the independent checker, writes it, and returns
/// (bytes, checker seconds, units checked).
pub fn write_checked(
    path: &Path,
    proof: &serde_json::Value,
) -> Result<(usize, f64, String), CliError> {
    let bytes = detach::certificate::to_bytes(proof);
    let report = detach::check::check_bytes(&bytes).map_err(|e| {
        CliError::runtime(format!(
            "{}: the checker cannot read it: {e}",
            detach::files::shown(path)
        ))
    })?;
    let refused = match &report.verdict {
        detach::check::Verdict::Valid => None,
        detach::check::Verdict::Invalid(why) => Some(("rejects", why)),
        detach::check::Verdict::Unchecked(why) => Some(("cannot check", why)),
    };
    if let Some((what, why)) = refused {
        return Err(CliError::runtime(format!(
            "{}: the checker {what} it: {why}",
            detach::files::shown(path)
        )));
    }
    // Written only once the checker accepts it.
    detach::files::write_atomic(path, &bytes).map_err(|e| cannot_write(path, e))?;
    Ok((
        bytes.len(),
        report.seconds,
        format!("{} {}", report.checked, report.unit),
    ))
}

/// `cannot write PATH: why`, with a file-size limit (`ulimit -f`) named.
pub fn cannot_write(path: &Path, e: std::io::Error) -> CliError {
    let why = if e.kind() == std::io::ErrorKind::FileTooLarge {
        format!("{e}; the file-size limit (ulimit -f) is too small")
    } else {
        e.to_string()
    };
    CliError::runtime(format!(
        "cannot write {}: {why}",
        detach::files::shown(path)
    ))
}

/// The reading of the paper (`--variant`), parsed by the library's names.
pub fn variant_parser() -> impl clap::builder::TypedValueParser<Value = detach::scene::Variant> {
    use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
    use detach::scene::Variant;
    PossibleValuesParser::new(Variant::ALL.map(|v| PossibleValue::new(v.name()).help(v.describe())))
        .try_map(|s| s.parse::<Variant>())
}

/// The paving method (`--method`), parsed by the library's names.
pub fn method_parser() -> impl clap::builder::TypedValueParser<Value = detach::pave::Method> {
    use clap::builder::{PossibleValuesParser, TypedValueParser};
    use detach::pave::Method;
    PossibleValuesParser::new(Method::ALL.map(|m| m.name())).try_map(|s| s.parse::<Method>())
}

/// ` (derived)` after a paper scene's name; nothing for a scene file.
pub fn reading(v: Option<detach::scene::Variant>) -> String {
    v.map(|v| format!(" ({v})")).unwrap_or_default()
}

/// The scene of a single-scene command: a paper's scene by name, or a scene
/// file.
#[derive(clap::Args, Debug)]
#[group(required = true, multiple = false)]
pub struct SceneSource {
    /// The scene: viscous-disc, smooth-disc, ice-disc, or painleve-rod (a
    /// shipped scene file).
    #[arg(long)]
    pub scene: Option<String>,
    /// A scene file (TOML; see docs/scene-files.md) instead of a paper's scene.
    #[arg(long = "scene-file", value_name = "FILE")]
    pub scene_file: Option<std::path::PathBuf>,
}

impl SceneSource {
    /// The scene as the library's [`detach::api::Problem`], in a reading,
    /// with `NAME=VALUE` overrides; a scene file has one reading, so
    /// `--variant printed` is refused for it.
    pub fn problem(
        &self,
        overrides: &[(String, String)],
        variant: detach::scene::Variant,
    ) -> Result<detach::api::Problem, CliError> {
        use detach::api::Problem;
        let pairs: Vec<(&str, &str)> = overrides
            .iter()
            .map(|(n, v)| (n.as_str(), v.as_str()))
            .collect();
        let problem = match (&self.scene, &self.scene_file) {
            (Some(name), _) => Problem::load(name, &pairs).map_err(usage)?,
            (None, Some(path)) => Problem::from_file(path, &pairs).map_err(usage)?,
            (None, None) => return Err(CliError::usage("give --scene NAME or --scene-file FILE")),
        };
        if problem.scene.id().is_none() {
            detach::api::one_reading(variant)?;
        }
        for w in problem.scene.warnings() {
            eprintln!("warning: {w}");
        }
        Ok(problem.in_reading(variant)?)
    }

    /// [`SceneSource::problem`]'s scene and parameters.
    pub fn build(
        &self,
        overrides: &[(String, String)],
        variant: detach::scene::Variant,
    ) -> Result<(detach::scene::Scene, detach::number::param::ParamSet), CliError> {
        let p = self.problem(overrides, variant)?;
        Ok((p.scene, p.params))
    }
}

/// `--param NAME=VALUE` texts as `(name, value)` pairs.
pub fn parse_overrides(texts: &[String]) -> Result<Vec<(String, String)>, CliError> {
    texts
        .iter()
        .map(|t| detach::number::param::parse_assignment(t).map_err(CliError::usage))
        .collect()
}

/// A bar on stderr, drawn only when stderr is a terminal.
pub fn progress_bar(levels: u64, label: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(levels);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{prefix:>14} [{bar:30}] level {pos}/{len} {elapsed} {msg}",
        )
        .expect("valid template")
        .progress_chars("=> "),
    );
    bar.set_prefix(label.to_string());
    bar
}

/// A scene that cannot be built is bad input (exit 2), an unreadable file
/// included, as it always was for `--scene-file`.
fn usage(e: detach::api::Error) -> CliError {
    CliError::usage(e.naming(flag))
}
