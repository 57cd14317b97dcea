//! Correctly rounded interval trigonometry (`detach::number::elementary`, CORE-MATH)
//! against `inari`'s (MPFR), one call each, and a whole θ-slab of every scene.

#[path = "support/timing.rs"]
mod timing;

use detach::number::elementary;
use detach::scene::{Scene, SceneId, Variant};
use inari::Interval;
use std::hint::black_box;
use timing::Group;

fn functions() {
    let g = Group::new("elementary");
    let x = Interval::try_from((1.1, 1.1 + 1e-3)).unwrap();
    let p = Interval::try_from((0.3, 0.7)).unwrap();
    g.bench("sin/inari", || black_box(x).sin());
    g.bench("sin/core-math", || elementary::sin(black_box(x)));
    g.bench("sin+cos/inari", || {
        let x = black_box(x);
        (x.sin(), x.cos())
    });
    g.bench("sin_cos/core-math", || elementary::sin_cos(black_box(x)));
    g.bench("tan/inari", || black_box(p).tan());
    g.bench("tan/core-math", || elementary::tan(black_box(p)));
    g.bench("ln/inari", || black_box(p).ln());
    g.bench("ln/core-math", || elementary::ln(black_box(p)));
}

fn slabs() {
    let g = Group::new("slab");
    let th = Interval::try_from((1.1, 1.1 + 1e-3)).unwrap();
    for id in SceneId::ALL {
        let s = Scene::default_of(id);
        g.bench(&format!("inari/{}", id.name()), || {
            s.constraints_on(Variant::Derived, black_box(th))
        });
        g.bench(&format!("core-math/{}", id.name()), || {
            detach::scene::slab::constraints_on(&s, Variant::Derived, black_box(th))
        });
    }
}

fn main() {
    functions();
    slabs();
}
