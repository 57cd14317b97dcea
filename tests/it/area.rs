//! Certified areas by quadrature (`detach::quadrature`) against independent
//! references, the paving's bounds, and the identities between cells.

use detach::pave::{pave_scene, standard_cells, PaveOptions};
use detach::quadrature::{cell_area, AreaError, AreaOptions};
use detach::scene::{Cell, Scene, SceneId, Variant};
use inari::Interval;

/// `tests/data/area_reference.py` (mpmath 1.3.0, 30 digits, tanh-sinh between
/// the breakpoints of the slice length), formulas written from the paper.
const SMOOTH_OMEGA: f64 = 41.334_523_421_053_71;
const VISCOUS_OMEGA: f64 = 101.430_743_457_751_43;
const VISCOUS_OMEGA0: f64 = 100.075_398_243_812_93;
const ICE_OMEGA0: f64 = 40.539_992_020_382_4;

fn area(id: SceneId, v: Variant, cell: Cell) -> Interval {
    let s = Scene::default_of(id);
    cell_area(&s, v, &s.domain(), cell, AreaOptions::default())
        .unwrap()
        .area
}

/// The reference double and its neighbours: the true value lies within.
fn contains(x: Interval, r: f64) -> bool {
    x.inf() <= r * (1.0 + 2e-16) && r * (1.0 - 2e-16) <= x.sup()
}

#[test]
fn references_are_enclosed_to_1e_9() {
    for (id, v, cell, r) in [
        (
            SceneId::SmoothDisc,
            Variant::Derived,
            Cell::Omega,
            SMOOTH_OMEGA,
        ),
        (
            SceneId::SmoothDisc,
            Variant::Printed,
            Cell::Omega,
            SMOOTH_OMEGA,
        ),
        (
            SceneId::IceDisc,
            Variant::Derived,
            Cell::Omega,
            SMOOTH_OMEGA,
        ),
        (
            SceneId::ViscousDisc,
            Variant::Derived,
            Cell::Omega,
            VISCOUS_OMEGA,
        ),
        (
            SceneId::ViscousDisc,
            Variant::Derived,
            Cell::Omega0,
            VISCOUS_OMEGA0,
        ),
        (SceneId::IceDisc, Variant::Derived, Cell::Omega0, ICE_OMEGA0),
    ] {
        let a = area(id, v, cell);
        assert!(contains(a, r), "{id} {v} {cell:?}: {a:?} misses {r}");
        assert!(a.wid() <= 1e-9, "{id} {v} {cell:?}: width {}", a.wid());
    }
}

#[test]
fn every_cell_of_every_scene_to_1e_9_and_the_cells_add_up() {
    for id in SceneId::ALL {
        let s = Scene::default_of(id);
        for v in [Variant::Derived, Variant::Printed] {
            let a: Vec<Interval> = Cell::ALL.iter().map(|c| area(id, v, *c)).collect();
            for (c, x) in Cell::ALL.iter().zip(&a) {
                assert!(x.wid() <= 1e-9, "{id} {v} {c:?}: {x:?}");
                assert!(x.inf() >= 0.0, "{id} {v} {c:?}: {x:?}");
            }
            // The four cells tile the domain; Ω and Ω₀ split into two cells each.
            let whole = a[2] + a[3] + a[4] + a[5];
            assert!(
                !whole.intersection(s.domain().area()).is_empty(),
                "{id} {v}"
            );
            assert!(!(a[2] + a[5]).intersection(a[0]).is_empty(), "{id} {v} Ω");
            assert!(!(a[2] + a[4]).intersection(a[1]).is_empty(), "{id} {v} Ω₀");
        }
    }
}

#[test]
fn quadrature_and_paving_bounds_intersect() {
    for id in SceneId::ALL {
        let s = Scene::default_of(id);
        for v in [Variant::Derived, Variant::Printed] {
            let opts = PaveOptions {
                eps: 1.0 / 256.0,
                max_boxes: 1_000_000,
            };
            let p = pave_scene(&s, v, opts, |_, _, _| {}).unwrap();
            for (spec, c) in standard_cells().iter().zip(Cell::ALL) {
                let b = p.area_bounds(spec, s.domain().uncovered_area_sup());
                let q = area(id, v, c);
                assert!(
                    b.inner_area <= q.sup() && q.inf() <= b.outer_area,
                    "{id} {v} {c:?}: quadrature {q:?}, paving [{}, {}]",
                    b.inner_area,
                    b.outer_area
                );
            }
        }
    }
}

#[test]
fn windows_and_parameters() {
    // A window that cuts through the slice: the area scales with what is kept.
    let s = Scene::default_of(SceneId::SmoothDisc);
    let d = s
        .domain()
        .window(Some(["0.5", "2.5"]), Some(["-3", "4"]))
        .unwrap();
    let a = cell_area(
        &s,
        Variant::Derived,
        &d,
        Cell::Omega,
        AreaOptions::default(),
    )
    .unwrap();
    let all = cell_area(
        &s,
        Variant::Derived,
        &d,
        Cell::NeitherOmegaNorOmega0,
        AreaOptions::default(),
    )
    .unwrap();
    assert!(a.area.wid() <= 1e-9 && all.area.wid() <= 1e-9);
    assert!(!(a.area + all.area).intersection(d.area()).is_empty());
    // b = 0: the centre of mass at the centre, Ω is the whole domain.
    let (s0, _) = Scene::build(SceneId::ViscousDisc, &[("b".into(), "0".into())]).unwrap();
    let w = cell_area(
        &s0,
        Variant::Derived,
        &s0.domain(),
        Cell::Omega,
        AreaOptions::default(),
    )
    .unwrap()
    .area;
    assert!(!w.intersection(s0.domain().area()).is_empty() && w.wid() <= 1e-9);
}

#[test]
fn bad_options_are_errors() {
    let s = Scene::default_of(SceneId::SmoothDisc);
    let d = s.domain();
    let bad = |tol: f64, max_pieces: usize| {
        cell_area(
            &s,
            Variant::Derived,
            &d,
            Cell::Omega,
            AreaOptions { tol, max_pieces },
        )
    };
    assert_eq!(bad(0.0, 10).unwrap_err(), AreaError::BadTol(0.0));
    assert!(matches!(bad(f64::NAN, 10), Err(AreaError::BadTol(_))));
    assert_eq!(bad(1e-3, 0).unwrap_err(), AreaError::BadBudget);
    // A small budget still gives a valid, wider enclosure.
    let coarse = bad(1e-12, 70).unwrap();
    assert!(contains(coarse.area, SMOOTH_OMEGA) && coarse.pieces <= 70);
}

/// Twelve decimal places by the method's order, not by piece count: the
/// enclosures hold the mpmath references above and take at most a few
/// thousand θ-pieces (binary64 summation over a million pieces would
/// itself leave a width near 10⁻⁸).
#[test]
fn twelve_places_in_a_few_thousand_pieces() {
    let tol = 1e-12;
    for (id, cell, r) in [
        (SceneId::ViscousDisc, Cell::Omega, VISCOUS_OMEGA),
        (SceneId::ViscousDisc, Cell::Omega0, VISCOUS_OMEGA0),
        (SceneId::SmoothDisc, Cell::Omega, SMOOTH_OMEGA),
        (SceneId::IceDisc, Cell::Omega0, ICE_OMEGA0),
    ] {
        let s = Scene::default_of(id);
        let opts = AreaOptions {
            tol,
            ..AreaOptions::default()
        };
        let e = cell_area(&s, Variant::Derived, &s.domain(), cell, opts).unwrap();
        assert!(
            contains(e.area, r),
            "{id} {cell:?}: {:?} misses {r}",
            e.area
        );
        assert!(e.area.wid() <= tol, "{id} {cell:?}: width {}", e.area.wid());
        assert!(e.pieces <= 4000, "{id} {cell:?}: {} pieces", e.pieces);
    }
    // The four cells of every paper scene too.
    for id in SceneId::ALL {
        let s = Scene::default_of(id);
        for cell in &Cell::ALL[2..] {
            let opts = AreaOptions {
                tol,
                ..AreaOptions::default()
            };
            let e = cell_area(&s, Variant::Derived, &s.domain(), *cell, opts).unwrap();
            assert!(e.area.wid() <= tol, "{id} {cell:?}: width {}", e.area.wid());
        }
    }
}

/// A width below what binary64 can certify for the area is refused before
/// any refinement, with the width it could reach.
#[test]
fn targets_below_binary64_rounding_are_refused() {
    let s = Scene::default_of(SceneId::ViscousDisc);
    let d = s.domain();
    for tol in [1e-13, 1e-14] {
        let opts = AreaOptions {
            tol,
            max_pieces: 1 << 20,
        };
        match cell_area(&s, Variant::Derived, &d, Cell::Omega, opts) {
            Err(AreaError::BelowRounding { floor, least, .. }) => {
                // Ω ≈ 101.4: a few units of 2⁻⁵² × 101 × 2.
                assert!(floor > 1e-14 && floor < 1e-12, "floor {floor}");
                assert!(least >= 2.0 * floor && least <= 1e-11, "least {least}");
            }
            other => panic!("tol {tol}: {other:?}"),
        }
    }
}

/// The table prints each bound rounded outward from the double it stands for
/// (a lower bound down, an upper bound up), so the printed interval contains
/// the JSON's. Rounding to nearest prints about half of the bounds inward.
#[test]
fn printed_bounds_contain_the_json_bounds() {
    use rug::Rational;
    // The exact rational a printed decimal such as `-41.25` denotes.
    fn exact_decimal(t: &str) -> Rational {
        let (whole, frac) = t.split_once('.').unwrap_or((t, ""));
        let digits: rug::Integer = format!("{whole}{frac}").parse().unwrap();
        Rational::from((
            digits,
            rug::Integer::from(rug::Integer::u_pow_u(10, frac.len() as u32)),
        ))
    }
    let mut checked = 0;
    for scene in ["smooth-disc", "viscous-disc", "ice-disc", "painleve-rod"] {
        let args = ["area", "--scene", scene, "--digits", "12"];
        let out = crate::common::detach(&args);
        assert!(out.status.success());
        let text = String::from_utf8(out.stdout).unwrap();
        let mut json_args = args.to_vec();
        json_args.push("--json");
        let report = crate::common::json(&json_args);
        // Rows of cells proved empty print `0`, not an interval.
        let regions: Vec<_> = report["regions"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|r| r.get("empty").is_none_or(|e| e.is_null()))
            .collect();
        let printed: Vec<(Rational, Rational)> = text
            .lines()
            .filter_map(|l| {
                let inner = l.split_once('[')?.1.split_once(']')?.0;
                let (lo, hi) = inner.split_once(", ")?;
                Some((exact_decimal(lo), exact_decimal(hi)))
            })
            .collect();
        assert_eq!(printed.len(), regions.len(), "{text}");
        for ((lo, hi), r) in printed.iter().zip(regions) {
            let bound = |k: &str| Rational::from_f64(r[k].as_f64().unwrap()).unwrap();
            let (jlo, jhi) = (bound("lower"), bound("upper"));
            assert!(
                *lo <= jlo && jhi <= *hi,
                "{scene}: [{lo}, {hi}] does not contain [{jlo}, {jhi}]"
            );
            checked += 1;
        }
    }
    assert!(checked >= 20, "{checked}");
}

/// A scene file with Ω = Ω₀ = `region` on `[-pi, pi] × [-2, 2]` (or the
/// domain given).
fn file_scene(region: &str, theta: &str, theta_dot: &str) -> Scene {
    let text = format!(
        "name = \"shape\"\ntitle = \"shape\"\n[domain]\ntheta = {theta}\ntheta_dot = {theta_dot}\n\
         [regions]\nomega = \"{region}\"\nomega0 = \"{region}\"\n"
    );
    Scene::File(Box::new(
        detach::scene::FileScene::parse(&text, &[]).unwrap(),
    ))
}

/// Shapes users write, each to its target in a few hundred θ-pieces
/// (a budget of 4096 is far above that; `max_pieces` stands in for time):
/// - two root branches crossing: `(θ̇ − sin θ)(θ̇ − cos θ) < 0` on
///   `[−π, π] × [−2, 2]` has the slice between the roots, of length
///   `|sin θ − cos θ| = √2·|sin(θ − π/4)|`; `|sin|` integrates to 4 over a
///   period, so the area is `4√2`. The discriminant `(sin θ − cos θ)²`
///   vanishes at θ = π/4 and −3π/4: without the Taylor form of the
///   discriminant and the ends `c ∓ √D⁺/(2|a2|)` there, the pieces next to
///   them stay undecided and 2²⁰ pieces leave 3·10⁻⁴.
/// - a double root: `θ̇² − sin²θ < 0`, length `2|sin θ|`, area `2·4 = 8`,
///   at 10⁻¹².
/// - a θ-factor exactly 0 on an interval: `(|θ| − θ)(θ̇² − 1/4) < 0` on
///   `[−1, 1]²`: for θ > 0 the factor is 0 and the set empty; for θ < 0 it
///   is `−2θ > 0` and the slice `|θ̇| < 1/2`, of length 1, over a θ-length
///   of 1: area 1. `|θ| − θ` encloses to `[−h, h]`, not `[0, 0]`, on a piece
///   of width h; without its mean-value form (exactly `[0, 0]`) every piece
///   of θ > 0 stays undecided and the enclosure is 2 wide.
#[test]
fn crossing_touching_and_vanishing_shapes_meet_the_target() {
    let sqrt2 = std::f64::consts::SQRT_2;
    let (pi, two) = ("[\"-pi\", \"pi\"]", "[\"-2\", \"2\"]");
    for (region, theta, theta_dot, exact, tol, most) in [
        (
            "(theta_dot - sin(theta))*(theta_dot - cos(theta)) < 0",
            pi,
            two,
            4.0 * sqrt2,
            1e-10,
            1000,
        ),
        ("theta_dot^2 - sin(theta)^2 < 0", pi, two, 8.0, 1e-12, 1000),
        (
            "(abs(theta) - theta)*(theta_dot^2 - 0.25) < 0",
            "[\"-1\", \"1\"]",
            "[\"-1\", \"1\"]",
            1.0,
            1e-10,
            500,
        ),
    ] {
        let s = file_scene(region, theta, theta_dot);
        let opts = AreaOptions {
            tol,
            max_pieces: 4096,
        };
        for cell in [Cell::Omega, Cell::NeitherOmegaNorOmega0] {
            let e = cell_area(&s, Variant::Derived, &s.domain(), cell, opts).unwrap();
            // Outside: the domain's area less the region's (`exact` is the
            // double nearest it).
            let exact = Interval::try_from((exact * (1.0 - 2e-16), exact * (1.0 + 2e-16))).unwrap();
            let want = if cell == Cell::Omega {
                exact
            } else {
                s.domain().area() - exact
            };
            assert!(
                !e.area.intersection(want).is_empty(),
                "{region} {cell:?}: {:?} misses {want:?}",
                e.area
            );
            assert!(
                e.area.wid() <= tol,
                "{region} {cell:?}: width {}",
                e.area.wid()
            );
            assert!(e.pieces <= most, "{region} {cell:?}: {} pieces", e.pieces);
        }
    }
}

/// `area` takes `--theta`/`--theta-dot` windows as `pave` does: on
/// `(θ̇ − sin θ)(θ̇ − cos θ) < 0`, θ ∈ [0, π/2] holds
/// `∫₀^{π/2} |sin θ − cos θ| dθ = 2(√2 − 1)` (both halves around π/4 give
/// `√2 − 1`), and the θ̇-window [−1, 1] holds both roots there, so the same;
/// θ̇ ∈ [0, 1/2] cuts it. Bad windows get `pave`'s messages.
#[test]
fn area_takes_windows_like_pave() {
    use crate::common::{assert_bad_input, json};
    let dir = std::env::temp_dir().join(format!("detach-area-window-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("cross.toml");
    let region = "(theta_dot - sin(theta))*(theta_dot - cos(theta)) < 0";
    std::fs::write(
        &file,
        format!(
            "name = \"cross\"\n[domain]\ntheta = [\"-pi\", \"pi\"]\ntheta_dot = [\"-2\", \"2\"]\n\
             [regions]\nomega = \"{region}\"\nomega0 = \"{region}\"\n"
        ),
    )
    .unwrap();
    let f = file.to_str().unwrap();
    let exact = 2.0 * (std::f64::consts::SQRT_2 - 1.0);
    for thd in [None, Some("-1:1")] {
        let mut args = vec![
            "area",
            "--scene-file",
            f,
            "--region",
            "omega",
            "--theta",
            "0:pi/2",
        ];
        args.extend(thd.iter().flat_map(|w| ["--theta-dot", *w]));
        args.push("--json");
        let v = json(&args);
        let r = &v["regions"][0];
        let (lo, hi) = (r["lower"].as_f64().unwrap(), r["upper"].as_f64().unwrap());
        assert!(
            lo <= exact * (1.0 + 1e-15) && exact * (1.0 - 1e-15) <= hi,
            "{thd:?}: {r}"
        );
        assert_eq!(r["target_met"], true, "{thd:?}: {r}");
        assert_eq!(r["method"], "quadrature");
    }
    let v = json(&[
        "area",
        "--scene-file",
        f,
        "--region",
        "omega",
        "--theta",
        "0:pi/2",
        "--theta-dot",
        "0:0.5",
        "--json",
    ]);
    assert!(v["regions"][0]["upper"].as_f64().unwrap() < 0.5 * exact);
    for (w, needle) in [
        (["--theta", "0-1"], "--theta must be LO:HI"),
        (["--theta", "0:7"], "--theta: the window must lie inside"),
        (["--theta-dot", "1:0"], "--theta-dot"),
    ] {
        let mut args = vec!["area", "--scene-file", f];
        args.extend(w);
        assert_bad_input(&args, needle);
        let mut args = vec!["pave", "--scene-file", f];
        args.extend(w);
        assert_bad_input(&args, needle);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The strategy of `detach area` (`detach::area::certified_areas`) and what
/// it says of each bound. At the defaults the quadrature alone meets 10⁻⁹
/// and gives both bounds. Held to 8 θ-pieces (the first grid has 64) it
/// misses 10⁻⁶ far from its rounding floor; the paving at ε = 1/1024 then
/// decides both bounds of Ω and Ω₀ of the viscous disc: the result is
/// narrower than the quadrature's own enclosure, still holds the mpmath
/// references above, and says it is an intersection whose bounds are the
/// paving's.
#[test]
fn the_area_strategy_says_how_each_bound_was_obtained() {
    use detach::area::{certified_areas, Provenance, Source};
    use detach::scene::Cell;
    let s = Scene::default_of(SceneId::ViscousDisc);
    let d = s.domain();
    let cells = [Cell::Omega, Cell::Omega0];
    let refs = [VISCOUS_OMEGA, VISCOUS_OMEGA0];
    let a = certified_areas(&s, Variant::Derived, &d, &cells, AreaOptions::default()).unwrap();
    assert!(a.notes.is_empty());
    for (set, r) in a.sets.iter().zip(refs) {
        assert_eq!(set.provenance, Provenance::Quadrature);
        assert_eq!(
            (set.lower_from, set.upper_from),
            (Source::Quadrature, Source::Quadrature)
        );
        assert!(contains(set.enclosure.area, r) && set.enclosure.width() <= 1e-9);
    }
    let held = AreaOptions {
        tol: 1e-6,
        max_pieces: 8,
    };
    let a = certified_areas(&s, Variant::Derived, &d, &cells, held).unwrap();
    assert!(
        a.notes[0].contains("intersected with a paving's bounds"),
        "{:?}",
        a.notes
    );
    for ((set, r), c) in a.sets.iter().zip(refs).zip(cells) {
        let q = cell_area(&s, Variant::Derived, &d, c, held).unwrap();
        assert!(q.width() > 1e-6 && !q.at_rounding_floor);
        assert_eq!((set.cell, set.provenance), (c, Provenance::Intersection));
        assert_eq!(
            (set.lower_from, set.upper_from),
            (Source::Paving, Source::Paving)
        );
        assert!(
            set.lower() > q.area.inf() && set.upper() < q.area.sup(),
            "{set:?} vs {q:?}"
        );
        assert!(contains(set.enclosure.area, r), "{set:?} misses {r}");
    }
}

/// A set below binary64's rounding is refused before any area is computed,
/// naming every such set and the decimal places they all reach (12 for
/// the viscous disc, as `area --digits 12` then succeeds in tests/it/cli.rs).
#[test]
fn the_area_strategy_refuses_a_width_below_rounding_for_all_sets_at_once() {
    use detach::area::{certified_areas, AreasError};
    use detach::scene::Cell;
    let s = Scene::default_of(SceneId::ViscousDisc);
    let opts = AreaOptions {
        tol: 1e-15,
        ..AreaOptions::default()
    };
    let e = certified_areas(&s, Variant::Derived, &s.domain(), &Cell::ALL, opts).unwrap_err();
    let AreasError::BelowRounding { sets, digits, .. } = &e else {
        panic!("{e}")
    };
    assert!(sets.starts_with("Ω (omega), Ω₀ (omega0), Ω∩Ω₀"), "{e}");
    assert_eq!(*digits, 12, "{e}");
}
