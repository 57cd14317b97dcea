//! detach: certified detachment regions and root bounds for mechanical systems
//! with a unilateral constraint (A. P. Ivanov, 2008).
//!
//! Data flows one way: the systems of the paper ([`scene`]) → pavings
//! ([`pave`]), areas by quadrature and roots ([`roots`]) → pictures and proof
//! files ([`certificate`]). Every claimed number is an outward-rounded
//! [`inari`] enclosure; `f64` is used only to steer searches and to draw, and
//! such output says so.
//!
//! # Example
//!
//! Pave Ω₀ of the disc on ice (§3, inequality (3.5)) with custom parameters
//! and the `slices` method, and print certified bounds on its area:
//!
//! ```
//! use detach::pave::{pave_scene_method, Method, MethodOptions, PaveOptions};
//! use detach::scene::{Cell, Scene, SceneId, Variant};
//!
//! // Parameters are decimal text, enclosed exactly (c₀ of (3.1), p_ψ of (2.3)).
//! let overrides = [("c0".to_string(), "1".to_string()), ("p_psi".into(), "1.5".into())];
//! let (scene, _params) = Scene::build(SceneId::IceDisc, &overrides)?;
//!
//! // Ω, Ω₀ and the four cells are named by `Cell` (`Cell::Omega`,
//! // `Cell::Omega0`, `Cell::OmegaAndOmega0`, …); `spec()` gives its literals.
//! let omega0 = Cell::Omega0.spec();
//!
//! // The paving method: Slices (the default), Natural, Centred or Contract
//! // (`"slices".parse::<Method>()` reads the command line's spelling).
//! assert_eq!(Method::default(), Method::Slices);
//! // `for_cell` refines only the constraints Ω₀ uses; `MethodOptions::new`
//! // refines all of them.
//! let method = MethodOptions::for_cell(Method::Slices, &omega0);
//! let opts = PaveOptions { eps: 1.0 / 128.0, max_boxes: 100_000 };
//! let domain = scene.domain();
//! let paving = pave_scene_method(
//!     &scene,
//!     Variant::Derived,
//!     &domain,
//!     opts,
//!     &method,
//!     |_level, _open, _leaves| {},
//! )?;
//! let area = paving.area_bounds(&omega0, domain.uncovered_area_sup());
//! println!(
//!     "area of Ω₀ ∈ [{}, {}] ({} leaves, stopped: {})",
//!     area.inner_area, area.outer_area, paving.leaves.len(), paving.stop
//! );
//! assert!(0.0 < area.inner_area && area.inner_area <= area.outer_area);
//! # Ok::<(), Box<dyn std::error::Error>>(())
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
