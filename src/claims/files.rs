//! The formulas a scene file states, read from that file: a claim about the
//! printed (1.7), (1.10), (1.11), (2.7), (2.8), (2.12), (3.1) or (3.5)
//! evaluates `scenes/NAME-printed.toml`'s text ([`FileScene::exact`]) rather
//! than writing the formula again, so a check of the paper is a check of
//! the file every paving of the printed reading uses.
//!
//! The text is evaluated as written over any scalar, θ entering as
//! `(sin θ, cos θ)` (and the logarithms of (3.1) as given values): over
//! [`Q`](super::exact::Q) with the parameters as variables it is a rational
//! function for an identity proof, over intervals an enclosure for a
//! certified witness, over `f64` a curve.

use crate::number::scalar::Scalar;
use crate::scene::{ExactPoint, ExactTheta, FileScene, SceneId, Variant};
use std::sync::OnceLock;

/// One reading of a paper scene, compiled once.
fn reading(id: SceneId, v: Variant) -> &'static FileScene {
    static FILES: [[OnceLock<FileScene>; 2]; 3] = [const { [const { OnceLock::new() }; 2] }; 3];
    let i = SceneId::ALL
        .iter()
        .position(|&s| s == id)
        .expect("a paper scene");
    let j = Variant::ALL
        .iter()
        .position(|&w| w == v)
        .expect("a reading");
    FILES[i][j].get_or_init(|| {
        id.reading(v, &[])
            .unwrap_or_else(|e| panic!("a shipped scene compiles: {e}"))
    })
}

/// The text at `key` of the file of `id`'s reading `v` (`definitions.h1`,
/// `regions.omega0`, `dynamics.theta_ddot`, `functions.potential_slope`, …)
/// at θ, `θ̇ = w`, with `values` for the parameters and for any definition
/// taken as given. Panics when the file lacks the text or it has no value
/// there: the claims and the shipped files are tested together.
pub fn formula<T: Scalar>(
    id: SceneId,
    v: Variant,
    key: &str,
    values: &[(&str, T)],
    theta: ExactTheta<T>,
    w: T,
) -> T {
    let file = reading(id, v);
    let at = ExactPoint {
        theta,
        theta_dot: w,
        values,
    };
    file.exact(key, &at)
        .unwrap_or_else(|e| panic!("scenes/{}.toml: {e}", file.name))
}
