//! A scene's constraints over a θ-slab with the CORE-MATH elementary
//! functions ([`CrDec`]): what the paver and the quadrature evaluate per slab.

use super::{Angle, Constraints, Scene, Variant};
use crate::number::elementary::CrDec;
use crate::number::scalar::DualTheta;
use inari::{DecInterval, Interval};

/// [`Scene::constraints_on`] with the elementary functions of this module:
/// certified coefficient enclosures of Ω and Ω₀ over a θ-slab.
pub fn constraints_on(scene: &Scene, v: Variant, theta: Interval) -> Constraints<DecInterval> {
    scene
        .constraints(v, &Angle::new(CrDec(DecInterval::new(theta))))
        .map(|x| x.0)
}

/// [`constraints_on`] over a dual θ: every coefficient with its
/// θ-derivative over the slab (gradient index 0).
pub fn dual_constraints_on(
    scene: &Scene,
    v: Variant,
    theta: Interval,
) -> Constraints<DualTheta<DecInterval>> {
    let t = DualTheta::variable(CrDec(DecInterval::new(theta)), 0);
    scene
        .constraints(v, &Angle::new(t))
        .map(|x: DualTheta<CrDec>| DualTheta {
            value: x.value.0,
            grad: x.grad.map(|g| g.0),
        })
}
