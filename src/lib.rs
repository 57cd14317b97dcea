//! detach: certified detachment regions and root bounds for mechanical systems
//! with a unilateral constraint (A. P. Ivanov, 2008).
//!
//! Data flows one way: [`scene`] → [`pave`] / [`roots`] → [`atlas`].
//! Every claimed number is an outward-rounded [`inari`] enclosure; `f64` is
//! used only to steer searches and to draw, and such output says so.
//!
//! # Example
//!
//! Pave Ω₀ of the disc on ice (§3, inequality (3.5)) with custom parameters
//! and print certified bounds on its area:
//!
//! ```
//! use detach::pave::{pave_scene, standard_cells, PaveOptions};
//! use detach::scene::{Scene, SceneId, Variant};
//!
//! // Parameters are decimal text, enclosed exactly (c₀ of (3.1), p_ψ of (2.3)).
//! let overrides = [("c0".to_string(), "1".to_string()), ("p_psi".into(), "1.5".into())];
//! let (scene, _params) = Scene::build(SceneId::IceDisc, &overrides)?;
//! let opts = PaveOptions { eps: 1.0 / 64.0, max_boxes: 100_000 };
//! let paving = pave_scene(&scene, Variant::Derived, opts, |_level, _open, _leaves| {})?;
//! // Region/cell order: Ω, Ω₀, Ω∩Ω₀, Ω̄∩Ω̄₀, Ω̄∩Ω₀, Ω∩Ω̄₀.
//! let omega0 = &standard_cells()[1];
//! let area = paving.area_bounds(omega0, scene.domain().uncovered_area_sup());
//! println!(
//!     "area of Ω₀ ∈ [{}, {}] ({} leaves, stopped: {})",
//!     area.inner_area, area.outer_area, paving.leaves.len(), paving.stop
//! );
//! assert!(0.0 < area.inner_area && area.inner_area <= area.outer_area);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! A crate depending on detach must compile for a CPU with AVX2/FMA, as
//! inari requires: copy this repository's `.cargo/config.toml`
//! (`-Ctarget-cpu=native -Ctarget-feature=-avx512vl` on x86-64, or
//! `-Ctarget-cpu=haswell` for a portable binary) into the dependent project.

pub mod area;
pub mod atlas;
pub mod certificate;
/// The independent proof checker, its own crate so that it can be built alone.
pub use detach_check as check;
pub mod claims;
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
