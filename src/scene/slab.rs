//! A scene's constraints over a θ-slab with the CORE-MATH elementary
//! functions ([`CrDec`]): what the paver and the quadrature evaluate per slab.

use super::{Angle, Constraints, Quadratic, Scene, Variant};
use crate::number::elementary::{Cr, CrDec};
use crate::number::scalar::DualTheta;
use inari::{DecInterval, Interval};

/// [`Scene::constraints_on`] with the elementary functions of this module:
/// certified coefficient enclosures of Ω and Ω₀ over a θ-slab.
/// Evaluated without decorations first ([`Cr`]), which is much cheaper:
/// where every operation is continuous on its argument, that gives the
/// same enclosures and the decorations ([`Cr::decorated`]); elsewhere the
/// decorated evaluation runs.
pub fn constraints_on(scene: &Scene, v: Variant, theta: Interval) -> Constraints<DecInterval> {
    let fast = scene.constraints(v, &Angle::new(Cr(theta)));
    if let Some(c) = decorated(fast, Cr::decorated) {
        return c;
    }
    scene
        .constraints(v, &Angle::new(CrDec(DecInterval::new(theta))))
        .map(|x| x.0)
}

/// Every coefficient decorated by `dec`, if it decorates each.
fn decorated<T: Copy, U: Copy>(
    c: Constraints<T>,
    dec: impl Fn(T) -> Option<U>,
) -> Option<Constraints<U>> {
    let q = |q: Quadratic<T>| {
        Some(Quadratic {
            c2: dec(q.c2)?,
            c1: dec(q.c1)?,
            c0: dec(q.c0)?,
        })
    };
    Some(Constraints {
        omega: q(c.omega)?,
        omega0: q(c.omega0)?,
    })
}

/// [`Scene::factored_constraints`] over a θ-slab, as [`constraints_on`]
/// (undecorated first).
pub fn factored_constraints_on(
    scene: &Scene,
    v: Variant,
    theta: Interval,
) -> ([[DecInterval; 2]; 2], Constraints<DecInterval>) {
    let (f, c) = scene.factored_constraints(v, &Angle::new(Cr(theta)));
    let f = f.map(|q| q.map(Cr::decorated));
    if let ([[Some(a0), Some(b0)], [Some(a1), Some(b1)]], Some(c)) =
        (f, decorated(c, Cr::decorated))
    {
        return ([[a0, b0], [a1, b1]], c);
    }
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

/// The undecorated evaluation of [`dual_constraints_on`] where it is
/// continuous, which a result that is not empty shows ([`Cr`]): every
/// value and θ-derivative, the decorated evaluation's enclosure, decorated
/// as [`Cr::decorated`] says. `None` where some result is empty.
pub fn dual_constraints_continuous(
    scene: &Scene,
    v: Variant,
    theta: Interval,
) -> Option<Constraints<DualTheta<Interval>>> {
    let fast = scene.constraints(v, &Angle::new(DualTheta::variable(Cr(theta), 0)));
    let plain = |x: DualTheta<Cr>| {
        let (value, grad) = (x.value.0, x.grad[0].0);
        (!value.is_empty() && !grad.is_empty()).then_some(DualTheta {
            value,
            grad: [grad],
        })
    };
    decorated(fast, plain)
}

/// [`constraints_on`] over a dual θ: every coefficient with its
/// θ-derivative over the slab (gradient index 0), undecorated first as
/// there.
pub fn dual_constraints_on(
    scene: &Scene,
    v: Variant,
    theta: Interval,
) -> Constraints<DualTheta<DecInterval>> {
    if let Some(c) = dual_constraints_continuous(scene, v, theta) {
        let dec = |x: Interval| Cr(x).decorated().expect("not empty");
        return c.map(|x| DualTheta {
            value: dec(x.value),
            grad: [dec(x.grad[0])],
        });
    }
    let t = DualTheta::variable(CrDec(DecInterval::new(theta)), 0);
    scene
        .constraints(v, &Angle::new(t))
        .map(|x: DualTheta<CrDec>| DualTheta {
            value: x.value.0,
            grad: x.grad.map(|g| g.0),
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{FileScene, SceneId};

    /// Scene files whose coefficients use every function: the first
    /// continuous on every slab below; the others divide by `sin(theta)`,
    /// take `sqrt`, `ln` and `tan` where they may leave their domains, and
    /// `abs`, `min`, `sign` where their slopes jump, on some of them.
    const FILES: [&str; 3] = [
        r#"
name = "continuous"
[domain]
theta = ["-3", "3"]
theta_dot = ["-2", "2"]
[parameters]
k = "0.7"
[regions]
omega = "exp(k*theta)*theta_dot^2 - atan(theta)^3*theta_dot - cos(theta)^2 < 0"
omega0 = "theta_dot^2 - exp(-(theta^2))/(2 + sin(theta)) + sqrt(4 + theta) < 0"
"#,
        r#"
name = "partial"
[domain]
theta = ["-3", "3"]
theta_dot = ["-2", "2"]
[regions]
omega = "theta_dot^2 - cos(theta)/sin(theta) + sqrt(theta) < 0"
omega0 = "ln(theta + 0.5)*theta_dot^2 - tan(theta) < 0"
"#,
        r#"
name = "kinks"
[domain]
theta = ["-3", "3"]
theta_dot = ["-2", "2"]
[regions]
omega = "abs(theta)*theta_dot^2 - min(theta, 1) < 0"
omega0 = "theta_dot^2 - sign(theta - 1) < 0"
"#,
    ];

    /// Ω's coefficients, then Ω₀'s.
    fn coefficients<T: Copy>(c: Constraints<T>) -> [T; 6] {
        let (o, z) = (c.omega.coefficients(), c.omega0.coefficients());
        [o[0], o[1], o[2], z[0], z[1], z[2]]
    }

    fn same(a: DecInterval, b: DecInterval) -> bool {
        a.decoration() == b.decoration() && a.interval() == b.interval()
    }

    /// The undecorated evaluation first, the decorated one where it asks:
    /// the enclosures and decorations the decorated evaluation alone gives,
    /// on points and slabs (across θ = 0, 1 and π/2 too), for values,
    /// θ-derivatives and factored forms, also where a coefficient is
    /// undefined or its derivative jumps.
    #[test]
    fn coefficients_are_decorated_as_by_the_decorated_evaluation() {
        let file =
            |text: &str| Scene::File(Box::new(FileScene::parse(text, &[]).expect("a valid file")));
        let mut scenes: Vec<(Scene, Variant)> = FILES.map(|f| (file(f), Variant::Derived)).into();
        for id in SceneId::ALL {
            for v in Variant::ALL {
                scenes.push((Scene::default_of(id), v));
            }
        }
        let slabs = [
            (0.0, 0.0),
            (-0.25, 0.125),
            (1.5, 1.625),
            (1.0, 1.0),
            (0.5, 1.5),
            (-0.75, -0.5),
            (-3.0, 3.0),
            (2.9, 3.1),
        ];
        let (mut undefined, mut jumps) = (false, false);
        for (scene, v) in &scenes {
            for (lo, hi) in slabs {
                let theta = Interval::try_from((lo, hi)).expect("ordered");
                let want = scene
                    .constraints(*v, &Angle::new(CrDec(DecInterval::new(theta))))
                    .map(|x| x.0);
                let got = constraints_on(scene, *v, theta);
                let t = DualTheta::variable(CrDec(DecInterval::new(theta)), 0);
                let want_dual = scene.constraints(*v, &Angle::new(t));
                let got_dual = dual_constraints_on(scene, *v, theta);
                let (want_f, want_fc) =
                    scene.factored_constraints(*v, &Angle::new(CrDec(DecInterval::new(theta))));
                let (got_f, got_fc) = factored_constraints_on(scene, *v, theta);
                for (w, g) in want_f.iter().flatten().zip(got_f.iter().flatten()) {
                    assert!(same(w.0, *g), "{} θ {theta:?}: factor", scene.name());
                }
                for (w, g) in coefficients(want_fc).into_iter().zip(coefficients(got_fc)) {
                    assert!(same(w.0, g), "{} θ {theta:?}: factored", scene.name());
                }
                let (w, g) = (coefficients(want), coefficients(got));
                let (wd, gd) = (coefficients(want_dual), coefficients(got_dual));
                for k in 0..6 {
                    // Ω's c₂, c₁, c₀, then Ω₀'s.
                    let at = format!("{} {v:?} θ {theta:?} coefficient {k}", scene.name());
                    assert!(same(w[k], g[k]), "{at}: {:?} vs {:?}", w[k], g[k]);
                    assert!(same(wd[k].value.0, gd[k].value), "{at} (dual value)");
                    assert!(same(wd[k].grad[0].0, gd[k].grad[0]), "{at} (derivative)");
                    undefined |= !crate::number::scalar::is_defined(g[k]);
                    jumps |= !crate::number::scalar::is_continuous(gd[k].grad[0]);
                }
            }
        }
        assert!(undefined, "some coefficient is undefined on a slab");
        assert!(jumps, "some derivative is not continuous on a slab");
    }
}
