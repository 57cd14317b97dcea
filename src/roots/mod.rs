//! Certified isolation of real roots of scalar equations.
//!
//! * [`isolate`](mod@isolate): the generic 1-D isolator (exclusion, interval Newton,
//!   bisection at exact off-centre points, contraction of unique roots).
//! * [`cluster`]: nearby undecided enclosures merged into one cluster with a
//!   certified bound on its number of roots (Rolle, sign parity).
//! * [`equations`]: the equations of the paper — (2.9), (2.10), (2.12) and the
//!   equilibria of (3.3) — each with a rigorous treatment of its open or
//!   unbounded domain.
//! * [`kappa0`]: the enclosure of κ₀ = √3/9 and the proof, for every κ, of the
//!   number of positive roots of (2.10).
//! * [`request`]: one root problem as asked (an equation and its inputs),
//!   checked once, solved once.
//! * [`tangency`]: the double root at κ = κ₀ and how the isolator behaves as κ
//!   approaches it.
//! * [`critical`]: the critical curve κ_crit(α) of (2.9) and a certified
//!   atlas of the (α, κ) plane.
//! * [`crate::figures::roots`]: pictures of the last two.
//!
//! Method notes and results: `docs/roots.md`.

pub mod cluster;
pub mod critical;
pub mod equations;
pub mod isolate;
pub mod kappa0;
pub mod request;
pub mod tangency;

pub use cluster::{Cluster, Parity};
pub use equations::{
    solve_2_10, solve_2_12, solve_2_9, solve_3_3, EdgeProof, EquationId, EquationRoots,
};
pub use isolate::{
    isolate, Budget, Isolation, RealFn, RootEnclosure, RootStatus, Stats, UndecidedReason,
};
pub use kappa0::{prove_kappa0, Kappa0Proof};
pub use request::{RequestError, RootsInputs, RootsRequest};

use thiserror::Error;

/// Bad input to a root problem.
#[derive(Debug, Error, PartialEq)]
pub enum RootsError {
    #[error("κ must be positive, got {0}")]
    KappaNotPositive(String),
    #[error("α must lie in [-1, 1], got {0}")]
    AlphaOutOfRange(String),
    #[error("p_φ and p_ψ are both zero: κ = g A²/(a p_M²) is undefined")]
    NoMomentum,
    #[error("κ = g A²/(a p_M²) {0} the range of doubles at these parameters ({1})")]
    OutOfRange(&'static str, &'static str),
    #[error("equation ({equation}) needs the scene {needs}, got {got}")]
    WrongScene {
        equation: String,
        needs: String,
        got: String,
    },
    #[error(transparent)]
    Param(#[from] crate::number::param::ParamError),
}
