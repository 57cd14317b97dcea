//! The inclusion property of every scene formula: the enclosure over a box
//! contains the value at any point of it (evaluated on the degenerate interval
//! of the point, which encloses the exact value).

use detach::scene::{Angle, Scene, SceneId, Variant};
use inari::{DecInterval, Interval};
use proptest::prelude::*;

fn iv(a: f64, b: f64) -> Interval {
    Interval::try_from((a.min(b), a.max(b))).unwrap()
}

/// All formulas of a scene on an angle and θ̇, as plain intervals.
fn formulas(s: &Scene, v: Variant, theta: Interval, w: Interval) -> Vec<Option<Interval>> {
    let dec = s.constraints(v, &Angle::new(DecInterval::new(theta)));
    let dw = DecInterval::new(w);
    let an = Angle::new(theta);
    vec![
        dec.omega.eval(dw).interval(),
        dec.omega0.eval(dw).interval(),
        Some(s.acceleration(v, &an, w)),
        s.energy(&an, w),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn box_enclosures_contain_point_values(
        scene in 0usize..3, printed in any::<bool>(),
        t0 in 0.0f64..1.0, t1 in 0.0f64..1.0, w0 in 0.0f64..1.0, w1 in 0.0f64..1.0,
        pu in 0.0f64..=1.0, pv in 0.0f64..=1.0,
        c0 in -5i32..5, mu in 0u32..30,
    ) {
        let id = SceneId::ALL[scene];
        let overrides: Vec<(String, String)> = match id {
            SceneId::IceDisc => vec![("c0".into(), format!("{c0}.5"))],
            SceneId::ViscousDisc => vec![("mu".into(), format!("0.{mu}"))],
            SceneId::SmoothDisc => vec![],
        };
        let (s, _) = Scene::build(id, &overrides).unwrap();
        let v = if printed { Variant::Printed } else { Variant::Derived };
        let b = s.domain().inner_box();
        let at = |r: [f64; 2], u: f64| r[0] + u * (r[1] - r[0]);
        // boxes of random size, down to very thin ones
        let (t0, t1) = (at(b[0], t0), at(b[0], t0 + (t1 - t0) * 0.1));
        let (w0, w1) = (at(b[1], w0), at(b[1], w1));
        let theta = iv(t0, t1);
        let w = iv(w0, w1);
        let (pt, pw) = (theta.inf() + pu * theta.wid(), w.inf() + pv * w.wid());
        let pt = pt.clamp(theta.inf(), theta.sup());
        let pw = pw.clamp(w.inf(), w.sup());
        let on_box = formulas(&s, v, theta, w);
        let on_point = formulas(&s, v, iv(pt, pt), iv(pw, pw));
        for (k, (bx, pnt)) in on_box.iter().zip(&on_point).enumerate() {
            if let (Some(bx), Some(pnt)) = (bx, pnt) {
                if !pnt.is_empty() && pnt.inf().is_finite() && pnt.sup().is_finite() {
                    prop_assert!(pnt.subset(*bx), "{id} {v} formula {k}: point {pnt:?} not in box {bx:?}");
                }
            }
        }
    }
}
