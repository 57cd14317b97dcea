//! detach: certified detachment regions and root bounds for mechanical systems
//! with a unilateral constraint (A. P. Ivanov, 2008).
//!
//! The way in is [`api`]: a [`api::Problem`] is a scene at parameters in one
//! reading of the paper, and its calls pave, measure areas, build parameter
//! atlases, integrate motion and write proof files, each failure an
//! [`api::Error`] with a kind. Every claimed number is an outward-rounded
//! [`inari`] enclosure; `f64` is used only to steer searches and to draw,
//! and such output says so.
//!
//! # Example
//!
//! Pave the disc on ice (§3, inequality (3.5)) with custom parameters and
//! the `slices` method, and print certified bounds on the area of Ω₀:
//!
//! ```
//! use detach::api::{Cell, ErrorKind, Method, PaveRequest, Problem};
//!
//! // Parameters are decimal text, enclosed exactly (c₀ of (3.1), p_ψ of (2.3)).
//! let disc = Problem::load("ice-disc", &[("c0", "1"), ("p_psi", "1.5")])?;
//!
//! // The paving method: Slices (the default), Natural, Centred or Contract
//! // (`"slices".parse::<Method>()` reads the command line's spelling); a
//! // `region` refines only the constraints that cell uses.
//! let paved = disc.pave(&PaveRequest {
//!     eps: 1.0 / 128.0,
//!     max_boxes: 100_000,
//!     method: Method::Slices,
//!     region: Some(Cell::Omega0),
//!     ..PaveRequest::default()
//! })?;
//! // Ω, Ω₀ and the four cells, in `Cell::ALL` order, each with its bounds.
//! let omega0 = paved.areas.iter().find(|a| a.cell == Cell::Omega0).unwrap();
//! println!(
//!     "area of Ω₀ ∈ [{}, {}] ({} leaves, stopped: {})",
//!     omega0.inner, omega0.outer, paved.paving.leaves.len(), paved.paving.stop
//! );
//! assert!(0.0 < omega0.inner && omega0.inner <= omega0.outer);
//!
//! // Bad input is an error of a kind, naming the option at fault.
//! let e = disc.pave(&PaveRequest { eps: 0.0, ..PaveRequest::default() });
//! let e = e.err().expect("eps 0 is refused");
//! assert_eq!((e.kind(), e.option()), (ErrorKind::InvalidOption, Some("eps")));
//! # Ok::<(), detach::api::Error>(())
//! ```
//!
//! # Building a crate that depends on detach
//!
//! inari selects its interval kernels at compile time from the target's CPU
//! features and needs AVX2 and FMA on x86-64. Cargo does not pass a
//! dependency's `.cargo/config.toml` on, so a dependent project needs its own,
//! with the same lines as this repository's:
//!
//! ```toml
//! [target.'cfg(target_arch = "x86_64")']
//! rustflags = ["-Ctarget-cpu=native", "-Ctarget-feature=-avx512vl"]
//!
//! [env]
//! TARGET_CPU = "haswell"
//! ```
//!
//! Keep `-Ctarget-feature=-avx512vl`: on a machine with AVX-512,
//! `-Ctarget-cpu=native` alone makes the build fail with an assembler error,
//! from inari's inline assembly, that names neither inari nor AVX-512. For a
//! binary to copy to other machines, build with
//! `RUSTFLAGS="-Ctarget-cpu=haswell"` instead. `TARGET_CPU` is the `-march`
//! with which `core-math-sys` compiles its C code (`native` when unset).
//! `docs/library.md` in the repository has the details and
//! `examples/dependent/` a complete dependent crate.

pub mod api;
pub mod area;
pub mod certificate;
/// The independent proof checker, its own crate so that it can be built alone.
pub use detach_check as check;
pub mod claims;
#[cfg(feature = "explore")]
pub mod explore;
pub mod figures;
pub mod files;
pub mod motion;
pub mod number;
pub mod params;
pub mod pave;
pub mod quadrature;
pub mod roots;
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
