//! Paving cost, and the cost of one formula evaluation in f64 versus
//! intervals (the ratio is what matters).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use detach::number::param::enclose_window_end;
use detach::pave::{
    pave_scene, pave_scene_method, standard_cells, Method, MethodOptions, PaveOptions, Paving,
};
use detach::scene::{Angle, Domain, Scene, SceneId, Variant};
use inari::{DecInterval, Interval};
use std::hint::black_box;
use std::time::{Duration, Instant};

/// The two peer set-ups: Ω of (2.8) of the smooth disc (g=9.81, a=1,
/// A=0.25, p_φ=1, p_ψ=0.6, θ ∈ [0.05, π−0.05]) and the printed Ω₀ (1.11)
/// of the viscous disc at defaults. Returns (name, scene, variant, domain,
/// region index).
fn peer_setups() -> Vec<(&'static str, Scene, Variant, Domain, usize)> {
    let ov: Vec<(String, String)> = [
        ("g", "9.81"),
        ("a", "1"),
        ("A", "0.25"),
        ("p_phi", "1"),
        ("p_psi", "0.6"),
    ]
    .iter()
    .map(|(n, v)| (n.to_string(), v.to_string()))
    .collect();
    let smooth = Scene::build(SceneId::SmoothDisc, &ov).unwrap().0;
    let off = enclose_window_end("theta", "0.05").unwrap();
    let d = smooth.domain();
    let window = Domain {
        theta: [off, Interval::PI - off],
        theta_dot: d.theta_dot,
    };
    let viscous = Scene::default_of(SceneId::ViscousDisc);
    let vd = viscous.domain();
    vec![
        ("omega-2.8", smooth, Variant::Printed, window, 0),
        ("omega0-1.11", viscous, Variant::Printed, vd, 1),
    ]
}

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
fn methods(c: &mut Criterion) {
    let mut g = c.benchmark_group("methods");
    g.sample_size(10);
    g.measurement_time(Duration::from_secs(2));
    for (name, s, v, d, region) in peer_setups() {
        for eps in [1e-3, 1e-4] {
            for m in Method::ALL {
                let t = Instant::now();
                let p = run(&s, v, &d, region, m, eps);
                let secs = t.elapsed().as_secs_f64();
                let b = p.area_bounds(&standard_cells()[region], d.uncovered_area_sup());
                eprintln!(
                    "{name} {m:<8} eps={eps:<6e} leaves={:<8} undecided={:.5} \
                     evals={} slabs={} time={secs:.3}s",
                    p.leaves.len(),
                    b.undecided_area(),
                    p.stats.box_evaluations,
                    p.stats.slab_evaluations,
                );
                g.bench_function(BenchmarkId::new(format!("{name}/{m}"), eps), |b| {
                    b.iter(|| run(&s, v, &d, region, m, eps))
                });
            }
        }
    }
    g.finish();
}

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

criterion_group!(benches, paving, methods, one_box);
criterion_main!(benches);
