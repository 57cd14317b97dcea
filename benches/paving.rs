//! Paving cost, and the cost of one formula evaluation in f64 versus
//! intervals (the ratio is what matters).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use detach::pave::{pave_scene, PaveOptions};
use detach::scene::{Angle, Scene, SceneId, Variant};
use inari::{DecInterval, Interval};
use std::hint::black_box;

fn paving(c: &mut Criterion) {
    let mut g = c.benchmark_group("pave");
    g.sample_size(20);
    for id in SceneId::ALL {
        let s = Scene::default_of(id);
        g.bench_function(BenchmarkId::new(id.name(), "eps=1e-3"), |b| {
            b.iter(|| {
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
            })
        });
    }
    g.finish();
}

fn one_box(c: &mut Criterion) {
    let mut g = c.benchmark_group("one-box");
    let (th, w) = (1.1f64, 2.5f64);
    let theta = Interval::try_from((1.1, 1.1 + 1e-3)).unwrap();
    let theta_dot = Interval::try_from((2.5, 2.5 + 1e-2)).unwrap();
    for id in SceneId::ALL {
        let s = Scene::default_of(id);
        for v in [Variant::Derived, Variant::Printed] {
            let name = format!("{}/{v}", id.name());
            g.bench_function(BenchmarkId::new("f64-point", &name), |b| {
                b.iter(|| {
                    let c = s.constraints(v, &Angle::new(black_box(th)));
                    (c.omega.eval(black_box(w)), c.omega0.eval(black_box(w)))
                })
            });
            g.bench_function(BenchmarkId::new("interval-box", &name), |b| {
                b.iter(|| {
                    let c = s.constraints(v, &Angle::new(black_box(theta)));
                    (
                        c.omega.eval(black_box(theta_dot)),
                        c.omega0.eval(black_box(theta_dot)),
                    )
                })
            });
            g.bench_function(BenchmarkId::new("decorated-box", &name), |b| {
                b.iter(|| {
                    let c = s.constraints_on(v, black_box(theta));
                    let w = DecInterval::new(black_box(theta_dot));
                    (c.omega.eval(w), c.omega0.eval(w))
                })
            });
            // the paver's inner loop: θ-slab coefficients cached, only θ̇ varies
            let cached = s.constraints_on(v, theta);
            g.bench_function(BenchmarkId::new("decorated-box-cached-slab", &name), |b| {
                b.iter(|| {
                    let w = DecInterval::new(black_box(theta_dot));
                    (cached.omega.eval(w), cached.omega0.eval(w))
                })
            });
        }
    }
    g.finish();
}

criterion_group!(benches, paving, one_box);
criterion_main!(benches);
