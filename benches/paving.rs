//! Paving cost, and the cost of one formula evaluation in f64 versus
//! intervals (the ratio is what matters); `scenes/` paves each paper scene
//! with each method on one thread and two.

#[path = "peers/problems.rs"]
mod problems;
#[path = "support/timing.rs"]
mod timing;

use detach::number::elementary::CrDec;
use detach::number::scalar::DualTheta;
use detach::pave::{
    pave_scene, pave_scene_method, standard_cells, Method, MethodOptions, PaveOptions, Paving,
};
use detach::scene::slab::{constraints_on, dual_constraints_on};
use detach::scene::{Angle, Domain, Scene, SceneId, Variant};
use inari::{DecInterval, Interval};
use std::hint::black_box;
use std::time::{Duration, Instant};
use timing::Group;

fn run(s: &Scene, v: Variant, d: &Domain, region: usize, m: Method, eps: f64) -> Paving {
    pave_scene_method(
        s,
        v,
        d,
        PaveOptions {
            eps,
            max_boxes: 10_000_000,
        },
        &MethodOptions::for_cell(m, &standard_cells()[region]),
        |_, _, _| {},
    )
    .unwrap()
}

/// Each method at a few resolutions on the peer set-ups; one timed run of
/// each is printed first (leaves, undecided area, evaluations).
fn methods() {
    let g = Group::new("methods")
        .samples(10)
        .time(Duration::from_secs(2));
    for p in problems::problems() {
        let (name, s, v, d, region) = (&p.key, &p.scene, p.variant, &p.domain, p.cell);
        for eps in [1e-3, 1e-4] {
            for m in Method::ALL {
                let case = format!("{name}/{m}/{eps}");
                if !g.wants(&case) {
                    continue;
                }
                let t = Instant::now();
                let paving = run(s, v, d, region, m, eps);
                let secs = t.elapsed().as_secs_f64();
                let b = paving.area_bounds(&standard_cells()[region], d.uncovered_area_sup());
                eprintln!(
                    "{name} {m:<8} eps={eps:<6e} leaves={:<8} undecided={:.5} \
                     evals={} slabs={} time={secs:.3}s",
                    paving.leaves.len(),
                    b.undecided_area(),
                    paving.stats.box_evaluations,
                    paving.stats.slab_evaluations,
                );
                g.bench(&case, || run(s, v, d, region, m, eps));
            }
        }
    }
}

fn paving() {
    let g = Group::new("pave");
    for id in SceneId::ALL {
        let s = Scene::default_of(id);
        g.bench(&format!("{}/eps=1e-3", id.name()), || {
            pave_scene(
                &s,
                Variant::Derived,
                PaveOptions {
                    eps: 1e-3,
                    max_boxes: 10_000_000,
                },
                |_, _, _| {},
            )
            .unwrap()
        });
    }
}

fn one_box() {
    let g = Group::new("one-box");
    let (th, w) = (1.1f64, 2.5f64);
    let theta = Interval::try_from((1.1, 1.1 + 1e-3)).unwrap();
    let theta_dot = Interval::try_from((2.5, 2.5 + 1e-2)).unwrap();
    for id in SceneId::ALL {
        let s = Scene::default_of(id);
        for v in [Variant::Derived, Variant::Printed] {
            let name = format!("{}/{v}", id.name());
            g.bench(&format!("f64-point/{name}"), || {
                let c = s.constraints(v, &Angle::new(black_box(th)));
                (c.omega.eval(black_box(w)), c.omega0.eval(black_box(w)))
            });
            g.bench(&format!("interval-box/{name}"), || {
                let c = s.constraints(v, &Angle::new(black_box(theta)));
                (
                    c.omega.eval(black_box(theta_dot)),
                    c.omega0.eval(black_box(theta_dot)),
                )
            });
            g.bench(&format!("decorated-box/{name}"), || {
                let c = s.constraints_on(v, black_box(theta));
                let w = DecInterval::new(black_box(theta_dot));
                (c.omega.eval(w), c.omega0.eval(w))
            });
            // the paver's inner loop: θ-slab coefficients cached, only θ̇ varies
            let cached = s.constraints_on(v, theta);
            g.bench(&format!("decorated-box-cached-slab/{name}"), || {
                let w = DecInterval::new(black_box(theta_dot));
                (cached.omega.eval(w), cached.omega0.eval(w))
            });
        }
    }
}

/// One evaluation of each paper scene's coefficients (its file compiled to
/// a tape) in each scalar the pavers use: `f64` (steering), and over a slab
/// and in θ-duals as the pavers evaluate them (undecorated first,
/// `detach::scene::slab`) and decorated throughout (`CrDec`), for the ratio.
fn tape() {
    let g = Group::new("tape").samples(9).time(Duration::from_secs(1));
    let th = Interval::try_from((1.1, 1.1 + 1e-3)).unwrap();
    let slab = CrDec(DecInterval::new(th));
    for id in SceneId::ALL {
        let s = Scene::default_of(id);
        let v = Variant::Derived;
        let name = id.name();
        // The f64 sines outside the timing; every interval case computes
        // its own (a slab's, or a dual's), as the pavers do.
        let p = Angle::new(1.1f64);
        g.bench(&format!("f64/{name}"), || s.constraints(v, black_box(&p)));
        g.bench(&format!("slab/{name}"), || {
            constraints_on(&s, v, black_box(th))
        });
        g.bench(&format!("dual/{name}"), || {
            dual_constraints_on(&s, v, black_box(th))
        });
        g.bench(&format!("decorated-slab/{name}"), || {
            s.constraints(v, &Angle::new(black_box(slab)))
        });
        g.bench(&format!("decorated-dual/{name}"), || {
            s.constraints(v, &Angle::new(DualTheta::variable(black_box(slab), 0)))
        });
    }
}

/// Each paper scene (derived, defaults, whole domain, ε = 1e-4, all
/// constraints) paved by each method on one thread and on two: the set-up
/// of the last comparison with the hand-written scenes
/// (`docs/performance/scene-files.md`).
fn scenes() {
    let g = Group::new("scenes").samples(5);
    for id in SceneId::ALL {
        let s = Scene::default_of(id);
        let d = s.domain();
        for m in Method::ALL {
            for threads in [1, 2] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .expect("thread pool");
                let case = format!("{}/{m}/threads={threads}", id.name());
                pool.install(|| {
                    g.bench(&case, || {
                        let opts = PaveOptions {
                            eps: 1e-4,
                            max_boxes: 10_000_000,
                        };
                        pave_scene_method(
                            &s,
                            Variant::Derived,
                            &d,
                            opts,
                            &MethodOptions::new(m),
                            |_, _, _| {},
                        )
                        .unwrap()
                    })
                });
            }
        }
    }
}

fn main() {
    paving();
    methods();
    one_box();
    tape();
    scenes();
}
