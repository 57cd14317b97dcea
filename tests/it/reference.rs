//! Area bounds of the smooth disc's Ω against an independent reference: the
//! area is ∫₀^π 2·min(10, √max(Φ(θ), 0)) dθ with Φ of (2.8) at the default
//! parameters (m=1, a=1, A=0.25, C=0.5, g=9.81, p_φ=2.5, p_ψ=2).

use detach::pave::{pave_scene, standard_cells, PaveOptions};
use detach::scene::{Scene, SceneId, Variant};

/// mpmath 1.3.0, 40 digits: `quad` of the slice length with breakpoints at the
/// roots of Φ = 0 and Φ = 100 (found with `findroot`), tanh-sinh rule:
/// 41.33452342105370855431412788922218 (here rounded to a double).
const AREA_MPMATH: f64 = 41.334_523_421_053_71;

/// The same integral by a composite midpoint rule in f64, written from (2.8).
fn area_midpoint(n: usize) -> f64 {
    let (a, big_a, g, pf, ps) = (1.0f64, 0.25f64, 9.81f64, 2.5f64, 2.0f64);
    let h = std::f64::consts::PI / n as f64;
    (0..n)
        .map(|i| {
            let t = (i as f64 + 0.5) * h;
            let (s, c) = t.sin_cos();
            let phi = g / (a * s) - c / (big_a * big_a * s.powi(4)) * (pf - ps * c) * (ps - pf * c);
            2.0 * phi.max(0.0).sqrt().min(10.0) * h
        })
        .sum()
}

#[test]
fn the_two_references_agree() {
    assert!((area_midpoint(400_000) - AREA_MPMATH).abs() < 1e-6);
}

#[test]
fn smooth_disc_area_bounds_bracket_the_reference() {
    let s = Scene::default_of(SceneId::SmoothDisc);
    for v in [Variant::Derived, Variant::Printed] {
        let mut last_gap = f64::INFINITY;
        for eps in [1.0 / 256.0, 1.0 / 1024.0, 1.0 / 4096.0] {
            let p = pave_scene(
                &s,
                v,
                PaveOptions {
                    eps,
                    max_boxes: 10_000_000,
                },
                |_, _, _| {},
            )
            .unwrap();
            let b = p.area_bounds(&standard_cells()[0], s.domain().uncovered_area_sup());
            assert!(
                b.inner_area <= AREA_MPMATH && AREA_MPMATH <= b.outer_area,
                "{v} eps={eps}: {b:?}"
            );
            let gap = b.outer_area - b.inner_area;
            assert!(
                gap < last_gap * 0.6,
                "{v}: refinement must tighten the bounds ({gap} vs {last_gap})"
            );
            last_gap = gap;
        }
        assert!(last_gap < 0.1);
    }
}
