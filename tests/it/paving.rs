//! Invariants of pavings: exact tiling, replay, inner ⊆ outer, areas that add
//! up, budgets, determinism across thread counts, sampled points of certified
//! leaves, and no certificate on a singular line.

use detach::pave::{pave_scene, standard_cells, Label, Node, PaveOptions, Paving, PhaseBox};
use detach::scene::{Angle, Scene, SceneId, Variant};
use inari::{const_interval, DecInterval, Interval};
use proptest::prelude::*;

const ZERO: Interval = const_interval!(0.0, 0.0);

fn paving(id: SceneId, v: Variant, eps: f64, max_boxes: usize) -> (Scene, Paving) {
    let s = Scene::default_of(id);
    let p = pave_scene(&s, v, PaveOptions { eps, max_boxes }, |_, _, _| {}).unwrap();
    (s, p)
}

fn all_pavings() -> Vec<(Scene, Paving)> {
    SceneId::ALL
        .iter()
        .flat_map(|&id| {
            [Variant::Derived, Variant::Printed].map(|v| paving(id, v, 1.0 / 128.0, 1_000_000))
        })
        .collect()
}

#[test]
fn leaves_tile_the_root_exactly() {
    for (s, p) in all_pavings() {
        // replaying the split sequence from the root gives back every leaf box
        let replayed = p.replay_boxes().expect("well-formed tree");
        assert_eq!(replayed, p.leaves.iter().map(|l| l.bx).collect::<Vec<_>>());
        // the leaf areas add up to the root's area (interval sum contains it)
        let total = p.leaves.iter().fold(ZERO, |acc, l| acc + l.bx.area());
        let root = p.root.area();
        assert!(
            total.inf() <= root.inf() && root.sup() <= total.sup(),
            "{:?}: {total:?} vs {root:?}",
            s.id()
        );
        // leaves have disjoint interiors: points on a fine grid lie in the
        // interior of at most one leaf and in the closure of at least one
        let r = p.root;
        for i in 0..97 {
            for j in 0..89 {
                let th = r.theta[0] + (r.theta[1] - r.theta[0]) * (i as f64 + 0.37) / 97.0;
                let w =
                    r.theta_dot[0] + (r.theta_dot[1] - r.theta_dot[0]) * (j as f64 + 0.61) / 89.0;
                let interior = |b: &PhaseBox| {
                    b.theta[0] < th && th < b.theta[1] && b.theta_dot[0] < w && w < b.theta_dot[1]
                };
                assert!(p.leaves.iter().filter(|l| interior(&l.bx)).count() <= 1);
                assert!(p.leaves.iter().any(|l| l.bx.contains(th, w)));
            }
        }
    }
}

#[test]
fn inner_is_inside_outer_and_cells_add_up() {
    for (s, p) in all_pavings() {
        let uncovered = s.domain().uncovered_area_sup();
        let bounds: Vec<_> = standard_cells()
            .iter()
            .map(|c| p.area_bounds(c, uncovered))
            .collect();
        for b in &bounds {
            assert!(b.inner_area <= b.outer_area);
            assert!(b.inner_boxes <= b.outer_boxes);
        }
        let area = s.domain().area();
        // the four cells partition the domain
        let inner_sum: f64 = bounds[2..].iter().map(|b| b.inner_area).sum();
        let outer_sum: f64 = bounds[2..].iter().map(|b| b.outer_area).sum();
        assert!(inner_sum <= area.sup() * (1.0 + 1e-12));
        assert!(outer_sum >= area.inf() * (1.0 - 1e-12));
        // Ω = (Ω∩Ω₀) ∪ (Ω∩Ω̄₀): inner of Ω at least the cells' inner sum, outer at most
        assert!(
            bounds[0].inner_area >= (bounds[2].inner_area + bounds[5].inner_area) * (1.0 - 1e-12)
        );
        assert!(
            bounds[0].outer_area <= (bounds[2].outer_area + bounds[5].outer_area) * (1.0 + 1e-12)
        );
        assert!(
            bounds[1].inner_area >= (bounds[2].inner_area + bounds[4].inner_area) * (1.0 - 1e-12)
        );
    }
}

#[test]
fn a_budget_gives_a_coarser_valid_result() {
    let (s, fine) = paving(SceneId::IceDisc, Variant::Derived, 1.0 / 256.0, 10_000_000);
    let (_, coarse) = paving(SceneId::IceDisc, Variant::Derived, 1.0 / 256.0, 500);
    assert!(fine.complete);
    assert!(!coarse.complete);
    assert!(coarse.leaves.len() <= 500);
    let u = s.domain().uncovered_area_sup();
    for cell in standard_cells() {
        let (c, f) = (coarse.area_bounds(&cell, u), fine.area_bounds(&cell, u));
        assert!(c.inner_area <= f.inner_area && f.outer_area <= c.outer_area);
    }
}

#[test]
fn the_tree_does_not_depend_on_the_thread_count() {
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| paving(SceneId::ViscousDisc, Variant::Derived, 1.0 / 256.0, 3_000).1)
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one.nodes, two.nodes);
    assert_eq!(one.leaves, two.leaves);
    assert!(one.nodes.iter().any(|n| matches!(n, Node::Split(0))));
}

#[test]
fn boxes_on_the_singular_line_are_never_certified() {
    for id in [SceneId::SmoothDisc, SceneId::IceDisc] {
        let (_, p) = paving(id, Variant::Derived, 1.0 / 128.0, 1_000_000);
        let edge: Vec<_> = p
            .leaves
            .iter()
            .filter(|l| l.bx.theta[0] == 0.0 || l.bx.theta[1] == p.root.theta[1])
            .collect();
        assert!(!edge.is_empty());
        for l in &edge {
            if l.bx.theta[0] == 0.0 {
                // sin θ = 0 lies in the box: every formula is undefined there
                assert_eq!(
                    &l.labels[..2],
                    &[Label::Undefined, Label::Undefined],
                    "{id}: {:?}",
                    l.bx
                );
            }
        }
    }
    // and directly: a box straddling θ = 0 is undefined, not "in" via [x, +∞]
    let s = Scene::default_of(SceneId::SmoothDisc);
    let c = s.constraints_on(Variant::Printed, Interval::try_from((0.0, 1e-3)).unwrap());
    let w = DecInterval::new(Interval::try_from((0.0, 1.0)).unwrap());
    assert_eq!(Label::from_enclosure(c.omega.eval(w)), Label::Undefined);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Points sampled in certified leaves satisfy (or violate) their constraint,
    /// evaluated on the point as a degenerate interval.
    #[test]
    fn sampled_points_of_certified_leaves_obey_their_labels(seed in 0usize..1_000_000, u in 0.0f64..1.0, v in 0.0f64..1.0) {
        let pavings = sampled_pavings();
        let (s, var, p) = &pavings[seed % pavings.len()];
        let leaf = &p.leaves[(seed / pavings.len()) % p.leaves.len()];
        let th = leaf.bx.theta[0] + u * (leaf.bx.theta[1] - leaf.bx.theta[0]);
        let w = leaf.bx.theta_dot[0] + v * (leaf.bx.theta_dot[1] - leaf.bx.theta_dot[0]);
        let point = |x: f64| Interval::try_from((x, x)).unwrap();
        let c = s.constraints(*var, &Angle::new(point(th)));
        for (g, label) in [c.omega.eval(point(w)), c.omega0.eval(point(w))].into_iter().zip(leaf.labels) {
            match label {
                Label::ProvedIn => prop_assert!(g.sup() < 0.0),
                Label::ProvedOut => prop_assert!(g.inf() > 0.0),
                _ => {}
            }
        }
    }
}

fn sampled_pavings() -> &'static [(Scene, Variant, Paving)] {
    static CELL: std::sync::OnceLock<Vec<(Scene, Variant, Paving)>> = std::sync::OnceLock::new();
    CELL.get_or_init(|| {
        SceneId::ALL
            .iter()
            .flat_map(|&id| {
                [Variant::Derived, Variant::Printed].map(|v| {
                    let (s, p) = paving(id, v, 1.0 / 64.0, 1_000_000);
                    (s, v, p)
                })
            })
            .collect()
    })
}
