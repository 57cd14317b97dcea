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

/// [`Scene::factored_constraints`] over a θ-slab, as [`constraints_on`].
pub fn factored_constraints_on(
    scene: &Scene,
    v: Variant,
    theta: Interval,
) -> ([[DecInterval; 2]; 2], Constraints<DecInterval>) {
    let (f, c) = scene.factored_constraints(v, &Angle::new(CrDec(DecInterval::new(theta))));
    (f.map(|x| x.map(|y| y.0)), c.map(|x| x.0))
}

/// The factors of [`factored_constraints_on`] by the mean-value form
/// `f(m) + f'(θ)·(θ − m)`, `m` a point of `theta`: far tighter than the
/// natural enclosure where `f` is small and flat (two zeros close
/// together). Decorated `com` only where `f'` is defined and continuous on
/// the slab, as the mean-value theorem needs.
pub fn centred_factors_on(scene: &Scene, v: Variant, theta: Interval) -> [[DecInterval; 2]; 2] {
    let t = DualTheta::variable(CrDec(DecInterval::new(theta)), 0);
    let (over, _) = scene.factored_constraints(v, &Angle::new(t));
    let m = Interval::try_from((theta.mid(), theta.mid())).expect("a finite slab");
    let (at_m, _) = scene.factored_constraints(v, &Angle::new(CrDec(DecInterval::new(m))));
    let offset = DecInterval::new(theta - m);
    std::array::from_fn(|q| std::array::from_fn(|k| at_m[q][k].0 + over[q][k].grad[0].0 * offset))
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
