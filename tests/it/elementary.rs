//! The correctly rounded interval functions of `detach::number::elementary` against
//! `inari`'s (MPFR, directed rounding): each of ours must contain inari's
//! tight enclosure of the same range (which contains the true range) and be at
//! most a few ulps wider, on random and adversarial intervals; decorations
//! must agree.

use detach::number::elementary::{self as el, dec_cos, dec_ln, dec_sin, dec_tan};
use inari::{DecInterval, Interval};

fn iv(a: f64, b: f64) -> Interval {
    Interval::try_from((a, b)).unwrap()
}

/// Small deterministic generator (xorshift64*), no external state.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

fn up(x: f64, n: u32) -> f64 {
    (0..n).fold(x, |x, _| {
        if x == 0.0 {
            f64::from_bits(1)
        } else if x > 0.0 {
            f64::from_bits(x.to_bits() + 1)
        } else {
            f64::from_bits(x.to_bits() - 1)
        }
    })
}
fn down(x: f64, n: u32) -> f64 {
    -up(-x, n)
}

/// `ours ⊇ tight` and each end at most `ulps` ulps beyond `tight`'s.
fn check(name: &str, x: Interval, ours: Interval, tight: Interval, ulps: u32) {
    assert!(
        tight.subset(ours),
        "{name}({x:?}): ours {ours:?} misses inari's {tight:?}"
    );
    if tight.is_empty() || !tight.is_common_interval() {
        return;
    }
    assert!(
        ours.inf() >= down(tight.inf(), ulps) && ours.sup() <= up(tight.sup(), ulps),
        "{name}({x:?}): ours {ours:?} more than {ulps} ulps wider than {tight:?}"
    );
}

fn check_all(x: Interval) {
    check("sin", x, el::sin(x), x.sin(), 2);
    check("cos", x, el::cos(x), x.cos(), 2);
    let (s, c) = el::sin_cos(x);
    check("sin_cos.0", x, s, x.sin(), 2);
    check("sin_cos.1", x, c, x.cos(), 2);
    check("tan", x, el::tan(x), x.tan(), 2);
    check("ln", x, el::ln(x), x.ln(), 2);
    let d = DecInterval::new(x);
    for (name, ours, theirs) in [
        ("sin", dec_sin(d), d.sin()),
        ("cos", dec_cos(d), d.cos()),
        ("tan", dec_tan(d), d.tan()),
        ("ln", dec_ln(d), d.ln()),
    ] {
        assert_eq!(
            ours.decoration(),
            theirs.decoration(),
            "decorated {name}({x:?}): {ours:?} vs {theirs:?}"
        );
    }
}

#[test]
fn random_intervals() {
    let mut r = Rng(0x9e37_79b9_7f4a_7c15);
    for _ in 0..20_000 {
        let scale = [1e-3, 1.0, 4.0, 40.0, 1e4, 1e7][(r.next() % 6) as usize];
        let a = r.range(-scale, scale);
        let w = [0.0, 1e-12, 1e-6, 1e-2, 0.5, 2.0, 7.0][(r.next() % 7) as usize] * r.unit();
        let b = a + w;
        check_all(iv(a, b));
        check_all(iv(a.abs(), a.abs() + w));
    }
}

#[test]
fn endpoints_near_multiples_of_half_pi() {
    // The doubles nearest kπ/2 (from the enclosure's midpoint) and a few ulps
    // around them: the extremum and pole tests are decided within rounding.
    let ks = (-300i32..=300).chain([1001, -4097, 65535, 600_000]);
    for k in ks {
        let c = (Interval::FRAC_PI_2 * iv(k as f64, k as f64)).mid();
        for da in -3i32..=3 {
            let a = if da < 0 {
                down(c, (-da) as u32)
            } else {
                up(c, da as u32)
            };
            for w in [0.0, 1e-300, 1e-15, 1e-9, 1e-3, 1.0] {
                check_all(iv(a, a + w));
                check_all(iv(a - w, a));
            }
        }
    }
}

#[test]
fn points_tiny_and_special_arguments() {
    let specials = [
        0.0,
        -0.0,
        f64::from_bits(1),
        f64::MIN_POSITIVE,
        1e-300,
        1.0,
        std::f64::consts::PI,
        1048576.0,
        1048577.0,
        1e22,
        f64::MAX,
    ];
    for &x in &specials {
        for s in [x, -x] {
            check_all(iv(s, s));
        }
        check_all(iv(0.0, x));
        check_all(iv(-x, x));
    }
    check_all(Interval::ENTIRE);
    check_all(iv(1.0, f64::INFINITY));
    check_all(iv(f64::NEG_INFINITY, 0.0));
    // θ-slabs of the scenes' domains, ending at the doubles around π and 0.
    let pi = Interval::PI;
    for (a, b) in [
        (0.0, pi.inf()),
        (pi.inf() - 1e-3, pi.inf()),
        (-pi.inf(), pi.inf()),
        (0.0, 1e-3),
    ] {
        check_all(iv(a, b));
        check_all(iv(a / 2.0, b / 2.0));
    }
}

#[test]
fn slab_constraints_enclose_the_same_sets_as_inari() {
    use detach::scene::{Scene, SceneId, Variant};
    let mut r = Rng(7);
    for id in SceneId::ALL {
        let s = Scene::default_of(id);
        let d = s.domain().inner_box();
        for v in [Variant::Derived, Variant::Printed] {
            for _ in 0..300 {
                let a = r.range(d[0][0], d[0][1]);
                let b = (a + r.unit() * 0.1).min(d[0][1]);
                let th = iv(a, b);
                let ours = detach::scene::slab::constraints_on(&s, v, th);
                let theirs = s.constraints_on(v, th);
                for (o, t) in [
                    (ours.omega.c0, theirs.omega.c0),
                    (ours.omega.c2, theirs.omega.c2),
                    (ours.omega0.c0, theirs.omega0.c0),
                    (ours.omega0.c1, theirs.omega0.c1),
                    (ours.omega0.c2, theirs.omega0.c2),
                ] {
                    assert_eq!(o.decoration(), t.decoration(), "{id} {v} {th:?}");
                    let (o, t) = (o.interval().unwrap(), t.interval().unwrap());
                    // Both enclose the same true range: they must overlap,
                    // and ours is at most slightly wider.
                    assert!(!o.intersection(t).is_empty(), "{id} {v} {th:?}");
                    if t.is_common_interval() && t.wid() > 0.0 {
                        assert!(o.wid() <= t.wid() * (1.0 + 1e-9) + 1e-12 * t.mag());
                    }
                }
            }
        }
    }
}
