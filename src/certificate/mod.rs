//! Results as proof files (`proofs/FORMAT.md`, format `detach-proof/1`).
//!
//! This is the prover's side: it writes what was computed as a statement
//! (scene, parameters as decimal text, formulas as expressions, claimed
//! numbers) and evidence (the bisection tree, root witnesses). The checker,
//! [`crate::check`], shares none of this code: it parses the expressions
//! itself and re-derives every enclosure.

pub mod band;
pub mod catalog;
pub mod clip;
pub mod confirm;
pub mod numbers;
pub mod params;
pub mod paving;
pub mod reach;
pub mod roots;
pub mod statement;
pub mod trajectory;

pub use catalog::{prove_named, HEADLINE};
pub use params::{param_atlas_proof, ParamAtlasStatement};
pub use paving::{paving_proof, PavingStatement};
pub use roots::{build_pieces, kappa0_proof, roots_proof, RootsStatement};
pub use trajectory::{trajectory_proof, TrajectoryProofError};

use serde_json::{json, Value};

/// Who wrote a proof (informational: a checker ignores it).
pub fn producer() -> Value {
    json!({ "name": "detach", "version": env!("CARGO_PKG_VERSION") })
}

/// A proof file's bytes: pretty JSON with a final newline, deterministic
/// (key order as built).
pub fn to_bytes(proof: &Value) -> Vec<u8> {
    let mut s = serde_json::to_string_pretty(proof).expect("JSON values serialise");
    s.push('\n');
    s.into_bytes()
}
