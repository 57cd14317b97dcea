//! detach: certified detachment regions and root bounds for mechanical systems
//! with a unilateral constraint (A. P. Ivanov, 2008).
//!
//! Data flows one way: [`scene`] → [`pave`] / [`roots`] → [`atlas`].
//! Every claimed number is an outward-rounded [`inari`] enclosure; `f64` is
//! used only to steer searches and to draw, and such output says so.

pub mod area;
pub mod atlas;
pub mod certificate;
pub mod check;
pub mod elementary;
pub mod param;
pub mod pave;
pub mod roots;
pub mod scalar;
pub mod scene;

pub use inari;

/// The crate version, e.g. `0.1.0`.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
/// The git commit the binary was built from (`git rev-parse --short HEAD`),
/// or `unknown` when built outside a git checkout.
pub const GIT_COMMIT: &str = env!("DETACH_GIT_COMMIT");
/// `VERSION (commit GIT_COMMIT)`, as `detach --version` prints it.
pub const LONG_VERSION: &str = concat!(
    env!("CARGO_PKG_VERSION"),
    " (commit ",
    env!("DETACH_GIT_COMMIT"),
    ")"
);

/// What every output file records about the program that wrote it:
/// `{"version": …, "commit": …}`.
pub fn provenance() -> serde_json::Value {
    serde_json::json!({ "version": VERSION, "commit": GIT_COMMIT })
}
