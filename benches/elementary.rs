//! Correctly rounded interval trigonometry (`detach::number::elementary`, CORE-MATH)
//! against `inari`'s (MPFR), one call each, and a whole θ-slab of every scene.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use detach::number::elementary;
use detach::scene::{Scene, SceneId, Variant};
use inari::Interval;
use std::hint::black_box;

fn functions(c: &mut Criterion) {
    let mut g = c.benchmark_group("elementary");
    let x = Interval::try_from((1.1, 1.1 + 1e-3)).unwrap();
    let p = Interval::try_from((0.3, 0.7)).unwrap();
    g.bench_function("sin/inari", |b| b.iter(|| black_box(x).sin()));
    g.bench_function("sin/core-math", |b| {
        b.iter(|| elementary::sin(black_box(x)))
    });
    g.bench_function("sin+cos/inari", |b| {
        b.iter(|| {
            let x = black_box(x);
            (x.sin(), x.cos())
        })
    });
    g.bench_function("sin_cos/core-math", |b| {
        b.iter(|| elementary::sin_cos(black_box(x)))
    });
    g.bench_function("tan/inari", |b| b.iter(|| black_box(p).tan()));
    g.bench_function("tan/core-math", |b| {
        b.iter(|| elementary::tan(black_box(p)))
    });
    g.bench_function("ln/inari", |b| b.iter(|| black_box(p).ln()));
    g.bench_function("ln/core-math", |b| b.iter(|| elementary::ln(black_box(p))));
    g.finish();
}

fn slabs(c: &mut Criterion) {
    let mut g = c.benchmark_group("slab");
    let th = Interval::try_from((1.1, 1.1 + 1e-3)).unwrap();
    for id in SceneId::ALL {
        let s = Scene::default_of(id);
        g.bench_function(BenchmarkId::new("inari", id.name()), |b| {
            b.iter(|| s.constraints_on(Variant::Derived, black_box(th)))
        });
        g.bench_function(BenchmarkId::new("core-math", id.name()), |b| {
            b.iter(|| detach::scene::slab::constraints_on(&s, Variant::Derived, black_box(th)))
        });
    }
    g.finish();
}

criterion_group!(benches, functions, slabs);
criterion_main!(benches);
