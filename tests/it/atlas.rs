//! Atlas pictures: files written, and the rasteriser never overclaims.

use detach::figures::{
    draw_atlas, even_odd_area, inside_even_odd, merge_rects, plot_area_pixels, rasterize,
    undefined_hatch, vector_regions, AtlasStyle, Class, PictureInfo, Raster, Tracing,
};
use detach::pave::{
    pave_scene, Label, Leaf, PaveOptions, PaveStats, Paving, PerConstraint, PhaseBox, StopReason,
};
use detach::scene::{Scene, SceneId, Variant};
use std::path::PathBuf;

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("detach-atlas-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
    assert_eq!(&bytes[12..16], b"IHDR");
    let be = |r: std::ops::Range<usize>| u32::from_be_bytes(bytes[r].try_into().unwrap());
    (be(16..20), be(20..24))
}

fn paving_of(
    id: SceneId,
    variant: Variant,
    eps: f64,
) -> (Scene, Vec<(&'static str, String)>, Paving) {
    let (scene, params) = Scene::build(id, &[]).unwrap();
    let paving = pave_scene(
        &scene,
        variant,
        PaveOptions {
            eps,
            max_boxes: 1_000_000,
        },
        |_, _, _| {},
    )
    .unwrap();
    (scene, params.texts(), paving)
}

#[test]
fn draws_svg_and_png_with_legend() {
    let dir = temp_dir("draw");
    for id in SceneId::ALL {
        let (scene, params, paving) = paving_of(id, Variant::Derived, 1.0 / 64.0);
        let info = PictureInfo {
            scene: &scene,
            variant: Variant::Derived,
            params,
            complete: paving.complete,
            window: None,
        };
        let style = AtlasStyle::default();
        let (svg, png) = (
            dir.join(format!("{}.svg", id.name())),
            dir.join(format!("{}.png", id.name())),
        );
        draw_atlas(&paving, &info, &style, &svg, &png).unwrap();
        let bytes = std::fs::read(&png).unwrap();
        assert_eq!(png_size(&bytes), (style.width, style.height));
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(text.starts_with("<svg"), "an SVG document");
        for needle in [
            id.name(),
            "contact persists",
            "constraint released",
            "non-uniqueness paradox",
            "non-existence paradox",
            "undecided",
            "undefined",
            "phase portrait",
            // Every paper scene carries `[dynamics]`, so its portrait is
            // drawn as certified tubes, never as f64 curves.
            "certified tubes",
        ] {
            assert!(text.contains(needle), "{} lacks {needle:?}", svg.display());
        }
        assert!(!text.contains("f64, not certified"), "{}", svg.display());
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn incomplete_paving_is_flagged_and_small_styles_rejected() {
    let dir = temp_dir("incomplete");
    let (scene, params) = Scene::build(SceneId::IceDisc, &[]).unwrap();
    let paving = pave_scene(
        &scene,
        Variant::Printed,
        PaveOptions {
            eps: 1.0 / 256.0,
            max_boxes: 200,
        },
        |_, _, _| {},
    )
    .unwrap();
    assert!(!paving.complete);
    let info = PictureInfo {
        scene: &scene,
        variant: Variant::Printed,
        params: params.texts(),
        complete: paving.complete,
        window: None,
    };
    let (svg, png) = (dir.join("a.svg"), dir.join("a.png"));
    draw_atlas(&paving, &info, &AtlasStyle::default(), &svg, &png).unwrap();
    assert!(std::fs::read_to_string(&svg)
        .unwrap()
        .contains("INCOMPLETE"));
    let tiny = AtlasStyle {
        width: 100,
        height: 100,
    };
    assert!(draw_atlas(&paving, &info, &tiny, &svg, &png).is_err());
    assert_eq!(plot_area_pixels(&tiny), (0, 0));
    std::fs::remove_dir_all(&dir).ok();
}

fn overlap(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[1].min(b[1]) - a[0].max(b[0])).max(0.0)
}

/// Every pixel in a cell colour is covered by leaves proved in that cell:
/// all leaves meeting it are of that class, and they cover its whole area.
fn assert_sound(paving: &Paving, raster: &Raster) {
    let mut cell_pixels = 0;
    for row in 0..raster.height {
        for col in 0..raster.width {
            let Some(class) = raster.get(col, row) else {
                panic!("pixel ({col}, {row}) inside the root box left blank");
            };
            if !class.is_cell() {
                continue;
            }
            cell_pixels += 1;
            let p = raster.pixel_box(col, row);
            let mut covered = 0.0;
            for leaf in &paving.leaves {
                let a = overlap(p.theta, leaf.bx.theta) * overlap(p.theta_dot, leaf.bx.theta_dot);
                if a > 0.0 {
                    assert_eq!(
                        Class::of_leaf(leaf),
                        class,
                        "pixel ({col}, {row}) drawn {class:?} meets a leaf of another class"
                    );
                    covered += a;
                }
            }
            let area = (p.theta[1] - p.theta[0]) * (p.theta_dot[1] - p.theta_dot[0]);
            assert!(
                (covered - area).abs() <= 1e-9 * area,
                "pixel ({col}, {row}) not wholly covered: {covered} of {area}"
            );
        }
    }
    assert!(cell_pixels > 0, "some pixels are certified");
}

fn assert_rects_cover(raster: &Raster) {
    let mut seen = vec![0u8; (raster.width * raster.height) as usize];
    for r in merge_rects(raster) {
        for row in r.y0..r.y1 {
            for col in r.x0..r.x1 {
                assert_eq!(raster.get(col, row), Some(r.class));
                seen[(row * raster.width + col) as usize] += 1;
            }
        }
    }
    assert!(seen.iter().all(|&n| n == 1), "rectangles tile the raster");
}

#[test]
fn raster_of_real_pavings_never_overclaims() {
    for (id, variant) in [
        (SceneId::ViscousDisc, Variant::Derived),
        (SceneId::SmoothDisc, Variant::Printed),
        (SceneId::IceDisc, Variant::Derived),
    ] {
        let (_, _, paving) = paving_of(id, variant, 1.0 / 32.0);
        // Pixel edges deliberately not aligned with the dyadic leaf edges.
        for (w, h) in [(97, 61), (150, 110), (16, 16)] {
            let raster = rasterize(&paving, w, h);
            assert_sound(&paving, &raster);
            assert_rects_cover(&raster);
        }
    }
}

fn leaf(theta: [f64; 2], theta_dot: [f64; 2], l0: Label, l1: Label) -> Leaf {
    Leaf {
        bx: PhaseBox { theta, theta_dot },
        labels: PerConstraint::new(&[l0, l1]).unwrap(),
    }
}

fn synthetic(leaves: Vec<Leaf>) -> Paving {
    Paving {
        root: PhaseBox {
            theta: [0.0, 1.0],
            theta_dot: [0.0, 1.0],
        },
        names: vec!["omega".into(), "omega0".into()],
        eps: 1.0 / 8.0,
        nodes: Vec::new(),
        leaves,
        complete: true,
        stop: StopReason::Resolution,
        budget: None,
        same_as: vec![None, None],
        stats: PaveStats::default(),
    }
}

#[test]
fn synthetic_raster_classes() {
    use Label::{ProvedIn as In, ProvedOut as Out, Undecided as U, Undefined as X};
    // Left half: contact persists. Right half: four quarter-size leaves, three
    // released and one (top right) split into a non-existence leaf and a tiny
    // undecided one, plus an undefined strip at the far right bottom.
    let leaves = vec![
        leaf([0.0, 0.5], [0.0, 1.0], In, In),
        leaf([0.5, 0.75], [0.0, 0.5], Out, Out),
        leaf([0.75, 1.0], [0.0, 0.5], X, Out),
        leaf([0.5, 0.75], [0.5, 1.0], Out, Out),
        leaf([0.75, 0.875], [0.5, 1.0], In, Out),
        leaf([0.875, 1.0], [0.5, 1.0], In, U),
    ];
    for l in &leaves[..2] {
        assert!(Class::of_leaf(l).is_cell());
    }
    assert_eq!(Class::of_leaf(&leaves[2]), Class::Undefined);
    assert_eq!(Class::of_leaf(&leaves[4]), Class::NonExistence);
    assert_eq!(Class::of_leaf(&leaves[5]), Class::Undecided);
    let paving = synthetic(leaves);

    // 4 × 2 pixels: edges align with the leaves.
    let r = rasterize(&paving, 4, 2);
    let top: Vec<_> = (0..4).map(|c| r.get(c, 0).unwrap()).collect();
    let bottom: Vec<_> = (0..4).map(|c| r.get(c, 1).unwrap()).collect();
    assert_eq!(
        top,
        [
            Class::Persists,
            Class::Persists,
            Class::Released,
            // Non-existence and undecided leaves share this pixel.
            Class::Undecided
        ]
    );
    assert_eq!(
        bottom,
        [
            Class::Persists,
            Class::Persists,
            Class::Released,
            Class::Undefined
        ]
    );
    assert_sound(&paving, &r);

    // 3 × 3 pixels: the middle column straddles θ = 1/2 and may not be a cell.
    let r = rasterize(&paving, 3, 3);
    for row in 0..3 {
        assert_eq!(r.get(0, row), Some(Class::Persists));
        assert!(!r.get(1, row).unwrap().is_cell());
    }
    assert_sound(&paving, &r);

    // One pixel covering several leaves of one cell is that cell.
    let mut many = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            let (t, w) = (f64::from(i) / 4.0, f64::from(j) / 4.0);
            many.push(leaf([t, t + 0.25], [w, w + 0.25], Out, In));
        }
    }
    let r = rasterize(&synthetic(many), 1, 1);
    assert_eq!(r.get(0, 0), Some(Class::NonUniqueness));
}

/// The SVG's regions are exactly the union of the leaves of each class:
/// equal area, and every leaf's centre inside its own class's rings and no
/// other's. The conservative raster lies inside them.
#[test]
fn vector_regions_are_exactly_the_leaves() {
    for (id, variant) in [
        (SceneId::ViscousDisc, Variant::Derived),
        (SceneId::SmoothDisc, Variant::Printed),
        (SceneId::IceDisc, Variant::Derived),
    ] {
        let (_, _, paving) = paving_of(id, variant, 1.0 / 64.0);
        let raster = rasterize(&paving, 150, 110);
        let (regions, tracing) = vector_regions(&paving, &raster);
        assert_eq!(tracing, Tracing::ExactLeaves);
        for region in &regions {
            let leaves: f64 = paving
                .leaves
                .iter()
                .filter(|l| Class::of_leaf(l) == region.class)
                .map(|l| (l.bx.theta[1] - l.bx.theta[0]) * (l.bx.theta_dot[1] - l.bx.theta_dot[0]))
                .sum();
            let area = even_odd_area(&region.rings);
            assert!(
                (area - leaves).abs() <= 1e-9 * paving.root.area().sup(),
                "{id:?} {:?}: rings {area} vs leaves {leaves}",
                region.class
            );
        }
        for leaf in paving.leaves.iter().step_by(7) {
            let c = (
                0.5 * (leaf.bx.theta[0] + leaf.bx.theta[1]),
                0.5 * (leaf.bx.theta_dot[0] + leaf.bx.theta_dot[1]),
            );
            for region in &regions {
                assert_eq!(
                    inside_even_odd(&region.rings, c),
                    region.class == Class::of_leaf(leaf),
                    "{id:?}: leaf centre {c:?} vs {:?}",
                    region.class
                );
            }
        }
        for row in 0..raster.height {
            for col in 0..raster.width {
                let Some(class) = raster.get(col, row).filter(|c| c.is_cell()) else {
                    continue;
                };
                let p = raster.pixel_box(col, row);
                let c = (
                    0.5 * (p.theta[0] + p.theta[1]),
                    0.5 * (p.theta_dot[0] + p.theta_dot[1]),
                );
                let region = regions.iter().find(|r| r.class == class).unwrap();
                assert!(inside_even_odd(&region.rings, c), "pixel ({col}, {row})");
            }
        }
    }
}

#[test]
fn svg_is_vector_and_small() {
    let dir = temp_dir("vector");
    let (scene, params, paving) = paving_of(SceneId::IceDisc, Variant::Derived, 1.0 / 512.0);
    let info = PictureInfo {
        scene: &scene,
        variant: Variant::Derived,
        params,
        complete: paving.complete,
        window: None,
    };
    let (svg, png) = (dir.join("a.svg"), dir.join("a.png"));
    draw_atlas(&paving, &info, &AtlasStyle::default(), &svg, &png).unwrap();
    let text = std::fs::read_to_string(&svg).unwrap();
    let elements = text.matches('<').count();
    let rects = text.matches("<rect").count();
    // Before: one rectangle per run of equal pixels (about 3000 elements).
    assert!(elements < 400, "{elements} elements");
    assert!(rects < 30, "{rects} rectangles");
    assert!(text.len() < 250_000, "{} bytes", text.len());
    // Undefined leaves (θ = 0) are hatched, in the legend too.
    assert!(text.matches("url(#hatch)").count() >= 2);
    assert!(text.contains("<pattern id=\"hatch\""));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn thin_undefined_strips_are_widened_for_hatching() {
    use Label::{ProvedIn as In, Undefined as X};
    // An undefined strip 1/1000 of the width at the left edge.
    let paving = synthetic(vec![
        leaf([0.0, 0.001], [0.0, 1.0], X, In),
        leaf([0.001, 1.0], [0.0, 1.0], In, In),
    ]);
    let raster = rasterize(&paving, 200, 100);
    assert_eq!(raster.get(0, 50), Some(Class::Undefined));
    assert_eq!(raster.get(1, 50), Some(Class::Persists));
    let hatch = undefined_hatch(&raster, 6);
    assert_eq!(hatch, vec![(0, 0, 7, 100)]);
}

/// `atlas --size --format --theta --theta-dot`: the size, the files and the
/// window are honoured; bad values exit 2.
#[test]
fn atlas_command_honours_size_format_and_window() {
    let dir = temp_dir("cli");
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_detach"))
            .arg("atlas")
            .args(args)
            .output()
            .unwrap()
    };
    let out = dir.join("w");
    let o = run(&[
        "--scene",
        "ice-disc",
        "--theta",
        "pi/4:pi/2",
        "--theta-dot",
        "-2:3",
        "--size",
        "700x450",
        "--format",
        "svg",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let svg = std::fs::read_to_string(out.join("ice-disc.svg")).unwrap();
    assert!(svg.contains("width=\"700\" height=\"450\""));
    assert!(!out.join("ice-disc.png").exists(), "svg only");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let d = &summary["scenes"][0]["domain"];
    let (t0, t1) = (
        d["theta"][0].as_f64().unwrap(),
        d["theta"][1].as_f64().unwrap(),
    );
    assert!(
        (t0 - std::f64::consts::FRAC_PI_4).abs() < 1e-12
            && (t1 - std::f64::consts::FRAC_PI_2).abs() < 1e-12
    );
    assert_eq!(d["theta_dot"][0].as_f64(), Some(-2.0));
    assert_eq!(d["theta_dot"][1].as_f64(), Some(3.0));

    let o = run(&[
        "--size",
        "900x600",
        "--format",
        "png",
        "--scene",
        "smooth-disc",
        "--eps",
        "0.01",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let png = std::fs::read(out.join("smooth-disc.png")).unwrap();
    assert_eq!(png_size(&png), (900, 600));

    for bad in [
        &["--size", "100x100"][..],
        &["--size", "9000x800"],
        &["--size", "wide"],
        &["--format", "pdf"],
        &["--format", "gif"],
        &["--theta", "0:5", "--scene", "ice-disc"],
        &["--theta-dot", "3:2"],
    ] {
        let o = run(&[bad, &["--out", out.to_str().unwrap()]].concat());
        assert_eq!(
            o.status.code(),
            Some(2),
            "{bad:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The legend says why a cell is empty: the smooth disc's two paradox cells
/// are empty because Ω₀ is Ω (not "0.0 % of box"); the ice disc's are not.
#[test]
fn legend_names_cells_empty_by_construction() {
    let dir = temp_dir("legend-empty");
    for (id, empties) in [(SceneId::SmoothDisc, 2), (SceneId::IceDisc, 0)] {
        let (scene, params, paving) = paving_of(id, Variant::Derived, 1.0 / 64.0);
        let info = PictureInfo {
            scene: &scene,
            variant: Variant::Derived,
            params,
            complete: paving.complete,
            window: None,
        };
        let (svg, png) = (dir.join("a.svg"), dir.join("a.png"));
        draw_atlas(&paving, &info, &AtlasStyle::default(), &svg, &png).unwrap();
        let text = std::fs::read_to_string(&svg).unwrap();
        assert_eq!(text.matches("empty (Ω₀ = Ω)").count(), empties, "{id:?}");
        assert_eq!(text.matches("% of box").count(), 6 - empties, "{id:?}");
    }
}

/// A windowed atlas states its window, as given, in the subtitle.
#[test]
fn windowed_atlas_states_its_window() {
    let dir = temp_dir("window-subtitle");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_detach"))
        .args([
            "atlas",
            "--scene",
            "smooth-disc",
            "--theta",
            "0.5:2.5",
            "--format",
            "svg",
        ])
        .args(["--size", "640x480", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(dir.join("smooth-disc.svg")).unwrap();
    assert!(
        text.contains("window θ ∈ [0.5, 2.5]"),
        "no window in the subtitle"
    );
}
