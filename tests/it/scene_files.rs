//! Scene files: the Painlevé rod against its closed form, the paper's scenes
//! as their files, proofs from a file, and bad
//! files refused with exit 2 and a message naming the file and the key.

use crate::common::{assert_bad_input, detach, json, Rng};
use detach::pave::{pave_scene, standard_cells, Label, PaveOptions};
use detach::quadrature::{cell_area, AreaOptions};
use detach::scene::{Cell, FileScene, Scene, SceneId, Variant};
use std::path::{Path, PathBuf};

fn scene_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(format!("{name}.toml"))
}

fn rod(mu: &str) -> Scene {
    Scene::from_file(&scene_path("painleve-rod"), &[("mu".into(), mu.into())])
        .unwrap()
        .0
}

fn reference() -> serde_json::Value {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/painleve-reference.json"
    ))
    .unwrap();
    serde_json::from_str(&text).unwrap()
}

fn num(v: &serde_json::Value) -> f64 {
    v.as_str().unwrap().parse().unwrap()
}

/// The rod against the mpmath values of `tests/data/painleve_reference.py`
/// (closed form in θ, 50 digits): `area` certifies all six sets to 10⁻¹²
/// around them, the target met, not stopped at a rounding floor (the cells'
/// boundaries coincide along θ̇² = g/(l sin θ), and Ω₀ = {U/V < 0} is
/// singular where V = 0: its roots are those of U, V's rounding only decides
/// a side, by the mean-value form where V is small and flat). Next to
/// μ = 4/3 (the case μ = 1.3334) the band's two lines V = 0 are 0.008 rad
/// apart and V' is small on them: binary64 cannot decide V's sign within
/// about 10⁻¹⁵/|V'| of a line, a floor near 2·10⁻¹², so that case is asked
/// for 10⁻¹¹. Every case takes at most 2000 θ-pieces (without the mean-value
/// form μ = 1.3334 needs over 3000). The paving's inner and outer bounds of all six sets contain them;
/// and the paradox cells have positive certified area when μ > 4/3 and the
/// band is wider than a few boxes, and none when μ < 4/3 (they stay within
/// the undecided band along the boundary, where Ω₀ and Ω share it).
#[test]
fn painleve_rod_areas_contain_the_closed_form() {
    let names = [
        "omega",
        "omega0",
        "omega_and_omega0",
        "not_omega_and_not_omega0",
        "not_omega_and_omega0",
        "omega_and_not_omega0",
    ];
    for case in reference()["cases"].as_array().unwrap() {
        let mu = case["parameters"]["mu"].as_str().unwrap();
        let scene = rod(mu);
        let domain = scene.domain();
        let paradox = !case["paradox_band"].is_null();
        let wide_band = paradox && {
            let t = &case["paradox_band"]["theta"];
            num(&t[1]) - num(&t[0]) > 0.1
        };
        let tol = if mu == "1.3334" { 1e-11 } else { 1e-12 };
        for (i, name) in names.iter().enumerate() {
            let e = cell_area(
                &scene,
                Variant::Derived,
                &domain,
                Cell::ALL[i],
                AreaOptions {
                    tol,
                    max_pieces: 1 << 16,
                },
            )
            .unwrap();
            let want = num(&case["areas"][name]);
            assert!(
                e.area.inf() <= want
                    && want <= e.area.sup()
                    && e.area.wid() <= tol
                    && !e.at_rounding_floor
                    && e.pieces <= 2000,
                "mu={mu} {name}: {want} vs {:?} ({} pieces)",
                e.area,
                e.pieces
            );
        }
        let p = pave_scene(
            &scene,
            Variant::Derived,
            PaveOptions {
                eps: 1.0 / 512.0,
                ..PaveOptions::default()
            },
            |_, _, _| {},
        )
        .unwrap();
        for (i, name) in names.iter().enumerate() {
            let b = p.area_bounds(&standard_cells()[i], domain.uncovered_area_sup());
            let want = num(&case["areas"][name]);
            assert!(
                b.inner_area <= want && want <= b.outer_area,
                "mu={mu} {name}: {want} not in [{}, {}]",
                b.inner_area,
                b.outer_area
            );
            if i >= 4 && (wide_band || !paradox) {
                assert_eq!(b.inner_area > 0.0, paradox, "mu={mu} {name}");
                if !paradox {
                    assert!(b.outer_area < 0.5, "mu={mu} {name}: {}", b.outer_area);
                }
            }
        }
    }
}

/// Every leaf proved in a paradox cell (Ω̄∩Ω₀ or Ω∩Ω̄₀) lies where tan θ is
/// between the roots of t² − 3μt + 4 (the reference band), and such leaves
/// exist for μ = 2.
#[test]
fn painleve_paradox_leaves_lie_in_the_band() {
    let all = reference();
    let case = &all["cases"][3];
    let mu = case["parameters"]["mu"].as_str().unwrap();
    assert_eq!(mu, "2");
    let band = &case["paradox_band"]["theta"];
    let (lo, hi) = (num(&band[0]), num(&band[1]));
    let scene = rod(mu);
    let p = pave_scene(
        &scene,
        Variant::Derived,
        PaveOptions {
            eps: 1.0 / 256.0,
            ..PaveOptions::default()
        },
        |_, _, _| {},
    )
    .unwrap();
    let mut paradox = 0;
    for leaf in &p.leaves {
        let [o, o0] = [leaf.labels[0], leaf.labels[1]];
        let cell = matches!(
            (o, o0),
            (Label::ProvedOut, Label::ProvedIn) | (Label::ProvedIn, Label::ProvedOut)
        );
        if cell {
            paradox += 1;
            assert!(
                leaf.bx.theta[0] >= lo - 1e-12 && leaf.bx.theta[1] <= hi + 1e-12,
                "{:?} outside ({lo}, {hi})",
                leaf.bx
            );
        }
    }
    assert!(paradox > 100, "{paradox} paradox leaves");
}

/// `--scene NAME --variant V` is the file `scenes/NAME[-printed].toml` as
/// it is on disk: the same leaves and labels at the same ε and method. (The
/// committed atlas proofs, regenerated byte for byte in `proofs.rs`, hold
/// the trees the paper's scenes paved before they were files.)
#[test]
fn paper_scenes_pave_as_their_files_on_disk() {
    for id in SceneId::ALL {
        for v in Variant::ALL {
            let file = match v {
                Variant::Derived => id.name().to_string(),
                Variant::Printed => format!("{}-printed", id.name()),
            };
            let from_file = Scene::from_file(&scene_path(&file), &[]).unwrap().0;
            let paper = Scene::default_of(id);
            let opts = PaveOptions {
                eps: 1.0 / 128.0,
                ..PaveOptions::default()
            };
            let a = pave_scene(&from_file, Variant::Derived, opts, |_, _, _| {}).unwrap();
            let b = pave_scene(&paper, v, opts, |_, _, _| {}).unwrap();
            assert_eq!(a.leaves.len(), b.leaves.len(), "{file}");
            for (x, y) in a.leaves.iter().zip(&b.leaves) {
                assert_eq!(x.bx, y.bx, "{file}");
                assert_eq!(x.labels, y.labels, "{file} at {:?}", x.bx);
            }
        }
    }
}

/// `pave --scene-file … --proof` writes a proof that `detach verify`
/// accepts; the atlas and area commands take the file too.
#[test]
fn scene_file_runs_through_every_command() {
    let dir = std::env::temp_dir().join(format!("detach-scene-file-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = scene_path("painleve-rod");
    let f = file.to_str().unwrap();
    let proof = dir.join("rod.json");
    let v = json(&[
        "pave",
        "--scene-file",
        f,
        "--eps",
        "0.01",
        "--json",
        "--proof",
        proof.to_str().unwrap(),
    ]);
    assert_eq!(v["scene"], "painleve-rod");
    let shipped = json(&["pave", "--scene", "painleve-rod", "--eps", "0.01", "--json"]);
    assert_eq!(shipped["regions"], v["regions"]);
    let out = detach(&["verify", proof.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    let a = json(&[
        "area",
        "--scene-file",
        f,
        "--param",
        "mu=2",
        "--digits",
        "6",
        "--json",
    ]);
    assert_eq!(a["regions"].as_array().unwrap().len(), 6);
    // Ω∩Ω₀ of the rod: the two boundaries coincide where V > 0; the
    // quadrature still meets its target, and the mpmath value
    // (tests/data/painleve-reference.json, μ = 2) stays inside.
    let cell = &a["regions"][2];
    let want = num(&reference()["cases"][3]["areas"]["omega_and_omega0"]);
    let (lo, hi) = (
        cell["lower"].as_f64().unwrap(),
        cell["upper"].as_f64().unwrap(),
    );
    assert!(
        lo <= want && want <= hi && hi - lo <= 1e-6,
        "[{lo}, {hi}] vs {want}"
    );
    assert_eq!(cell["target_met"], true);
    let out = detach(&[
        "atlas",
        "--scene-file",
        f,
        "--out",
        dir.to_str().unwrap(),
        "--eps",
        "0.02",
        "--format",
        "svg",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(dir.join("painleve-rod.svg").exists());
    assert_bad_input(
        &["pave", "--scene-file", f, "--variant", "printed"],
        "one reading",
    );
    assert_bad_input(
        &["pave", "--scene-file", f, "--param", "zz=1"],
        "unknown parameter `zz`",
    );
    let _ = std::fs::remove_dir_all(&dir);
}

const GOOD: &str = r#"
name = "rod"
[domain]
theta = ["0", "pi/2"]
theta_dot = ["-10", "10"]
[parameters]
g = "9.81"
mu = "1.5"
[definitions]
V = "1 + 3*cos(theta)^2 - 3*mu*sin(theta)*cos(theta)"
U = "sin(theta)*theta_dot^2 - g"
[regions]
omega = "U < 0"
omega0 = "U/V < 0"
"#;

/// Each kind of bad file gets one line naming the file and the key (and the
/// character in an expression), exit code 2, no panic.
#[test]
fn bad_scene_files_are_refused_clearly() {
    assert!(FileScene::parse(GOOD, &[]).is_ok());
    let dir = std::env::temp_dir().join(format!("detach-bad-scenes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases: [(&str, String, &str); 22] = [
        (
            "position",
            GOOD.replace("U < 0", "U + $ < 0"),
            "`regions.omega` at character 5",
        ),
        (
            "non-strict",
            GOOD.replace("U < 0", "U <= 0"),
            "`regions.omega`: `<=` is not accepted",
        ),
        (
            "underflow",
            GOOD.replace("\"9.81\"", "\"1e-400\""),
            "`parameters.g`: parameter `g`: `1e-400` is too small",
        ),
        (
            "undefined-everywhere",
            GOOD.replace("omega0 = \"U/V < 0\"", "omega0 = \"U/(mu - 1.5) < 0\""),
            "with g = 9.81, mu = 1.5, `((sin(theta)*theta_dot^2) - g)/(mu - 1.5)` is undefined",
        ),
        (
            "domain-variable",
            GOOD.replace("\"pi/2\"", "\"theta/2\""),
            "`domain.theta`: `theta/2` must not depend on theta",
        ),
        ("empty", String::new(), "`name`: missing"),
        ("not-toml", "name = ".into(), "line 1"),
        (
            "syntax",
            GOOD.replace("U/V < 0", "U/(V < 0"),
            "regions.omega0",
        ),
        (
            "unknown-name",
            GOOD.replace("U < 0", "Q < 0"),
            "unknown name `Q`",
        ),
        (
            "unknown-fn",
            GOOD.replace("cos(theta)^2", "cosh(theta)^2"),
            "cosh",
        ),
        (
            "cycle",
            GOOD.replace("- g\"", "- g + U\""),
            "`definitions.U` at character",
        ),
        (
            "no-region",
            GOOD.replace("omega = \"U < 0\"", ""),
            "`regions.omega`: missing",
        ),
        (
            "misspelt-table",
            GOOD.replace("[regions]", "[region]"),
            "`[region]`: unknown table (a scene file has name, title, domain,",
        ),
        (
            "unknown-key",
            format!("colour = \"red\"\n{GOOD}"),
            "`colour`: unknown key",
        ),
        (
            "no-domain",
            GOOD.replace("theta_dot = [\"-10\", \"10\"]", ""),
            "`domain.theta_dot`: missing",
        ),
        ("no-comparison", GOOD.replace("U < 0", "U"), "regions.omega"),
        (
            "bad-number",
            GOOD.replace("\"9.81\"", "\"9,81\""),
            "parameters.g",
        ),
        (
            "float-number",
            GOOD.replace("\"9.81\"", "9.8_1"),
            "`parameters.g`: `9.8_1` is not decimal text; write the number in quotes",
        ),
        (
            "inverted",
            GOOD.replace("[\"-10\", \"10\"]", "[\"10\", \"-10\"]"),
            "domain.theta_dot",
        ),
        (
            "too-long",
            GOOD.replace("U/V < 0", &format!("U/V + {}0 < 0", "0*".repeat(5000))),
            "longer than 10000",
        ),
        (
            "reserved",
            GOOD.replace("\nV = ", "\nw = ").replace("U/V", "U/w"),
            "reserved",
        ),
        (
            "bad-name",
            GOOD.replace("name = \"rod\"", "name = \"Rod\""),
            "`name`",
        ),
    ];
    for (stem, text, needle) in cases {
        let path = dir.join(format!("{stem}.toml"));
        std::fs::write(&path, &text).unwrap();
        let p = path.to_str().unwrap();
        let err = assert_bad_input(&["pave", "--scene-file", p, "--eps", "0.1"], needle);
        assert!(err.contains(p), "{stem}: file not named in {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{stem}: {err}");
    }
    let missing = dir.join("missing.toml");
    assert_bad_input(
        &["area", "--scene-file", missing.to_str().unwrap()],
        "cannot read",
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Random edits of a good file (deleted, repeated and replaced characters)
/// are either read or refused with a message: never a panic.
#[test]
fn edited_scene_files_never_panic() {
    let mut rng = Rng(0x5eed_f11e);
    let bytes = GOOD.as_bytes();
    let alphabet = b"()<>=+-*/^.,\"[]#\n 0123456789abcdefgtuvwxyz_";
    let mut refused = 0;
    for _ in 0..600 {
        let mut b = bytes.to_vec();
        for _ in 0..1 + (rng.unit() * 4.0) as usize {
            let i = (rng.unit() * b.len() as f64) as usize % b.len();
            match (rng.unit() * 3.0) as u32 {
                0 => {
                    b.remove(i);
                }
                1 => b.insert(i, b[i]),
                _ => b[i] = alphabet[(rng.unit() * alphabet.len() as f64) as usize],
            }
        }
        let text = String::from_utf8_lossy(&b).into_owned();
        let r = std::panic::catch_unwind(|| FileScene::parse(&text, &[]));
        match r {
            Ok(Ok(_)) => {}
            Ok(Err(msg)) => {
                refused += 1;
                assert!(!msg.is_empty() && !msg.contains('\n'), "{msg:?}");
            }
            Err(_) => panic!("panicked on {text:?}"),
        }
    }
    assert!(refused > 100, "only {refused} of 600 edits refused");
}

const RING: &str = r#"
name = "ring"
[domain]
theta = ["0", "1"]
theta_dot = ["-4", "4"]
[regions]
omega = "sqrt(theta_dot^2 + 1) - 2 < 0"
omega0 = "abs(theta_dot) > 1"
"#;

/// Regions of another form than degree ≤ 2 in θ̇ pave with every method
/// and prove: `|θ̇| < √3` and `|θ̇| > 1` on θ ∈ [0, 1] have areas 2√3 and 6
/// (closed form), which the paving's bounds contain; `area` reports those
/// bounds and says why; the proof file verifies.
#[test]
fn regions_of_any_form_pave_and_prove() {
    let scene = Scene::File(Box::new(FileScene::parse(RING, &[]).unwrap()));
    let Scene::File(f) = &scene else {
        unreachable!()
    };
    assert_eq!(f.not_quadratic(), Some("omega"));
    let exact = [2.0 * 3f64.sqrt(), 6.0];
    for m in detach::pave::Method::ALL {
        let opts = PaveOptions {
            eps: 1.0 / 256.0,
            ..PaveOptions::default()
        };
        let p = pave_with(&scene, m, opts);
        assert_regions_enclose(&p, &exact, 0.2, &m.to_string());
    }
    let dir = std::env::temp_dir().join(format!("detach-ring-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("ring.toml");
    std::fs::write(&file, RING).unwrap();
    let proof = dir.join("ring.json");
    let f = file.to_str().unwrap();
    prove_and_verify(f, &proof);
    let out = detach(&["area", "--scene-file", f, "--region", "omega", "--json"]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v["note"].as_str().unwrap().contains("not of degree"));
    let r = &v["regions"][0];
    assert!(r["lower"].as_f64().unwrap() <= exact[0] && exact[0] <= r["upper"].as_f64().unwrap());
    assert_eq!(r["target_met"], false);
    // The row is the paving's own: its leaves (as `pave` counts them at the
    // same ε), its time, no quadrature columns.
    assert_eq!(r["method"], "paving");
    assert_eq!(
        [&r["provenance"], &r["lower_from"], &r["upper_from"]],
        ["paving", "paving", "paving"]
    );
    assert!(r.get("undecided_pieces").is_none(), "{r}");
    assert!(r["elapsed_s"].as_f64().unwrap() > 0.0, "{r}");
    let p = json(&["pave", "--scene-file", f, "--eps", "0.0009765625", "--json"]);
    assert_eq!(r["pieces"], p["leaves"]);
    // A window: θ ∈ [0, 1/2] holds half of |θ̇| < √3's area, √3.
    let v = json(&[
        "area",
        "--scene-file",
        f,
        "--region",
        "omega",
        "--theta",
        "0:0.5",
        "--json",
    ]);
    let r = &v["regions"][0];
    let half = 3f64.sqrt();
    assert!(r["lower"].as_f64().unwrap() <= half && half <= r["upper"].as_f64().unwrap());
    assert!(r["upper"].as_f64().unwrap() < 0.6 * exact[0], "{r}");
    assert_eq!(v["window"], "θ ∈ [0, 0.5]");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Boundaries constant in θ (θ̇ = ±1 on the window's edges, θ̇ = 1/2 across
/// it), numbers written `1.` and `.5`: by hand, Ω = {θ̇² < 1} has area 2
/// (the whole window) and Ω₀ = {θ̇ < 1/2} area 3/2. Every method certifies
/// them with the undecided area a sliver (the contraction once left the
/// part above θ̇ = 1/2 undecided, and everything beside an edge root, on
/// every slab: 10⁶ leaves and nothing decided), and the quadrature gets
/// them in its first grid.
#[test]
fn boundaries_constant_in_theta_are_certified() {
    let text = "name = \"flat\"\n[domain]\ntheta = [\"0\", \"1\"]\ntheta_dot = [\"-1\", \"1\"]\n\
                [regions]\nomega = \"theta_dot^2 - 1. < 0\"\nomega0 = \"theta_dot - .5 < 0\"\n";
    let scene = Scene::File(Box::new(FileScene::parse(text, &[]).unwrap()));
    let exact = [2.0, 1.5, 1.5, 0.0, 0.0, 0.5];
    for m in detach::pave::Method::ALL {
        let p = pave_with(&scene, m, PaveOptions::default());
        // The contracting methods cut at the lines; the bisecting ones
        // leave a band of boxes along each.
        let band = match m.name() {
            "contract" | "slices" => 1e-9,
            _ => 0.01,
        };
        for (i, want) in exact.iter().enumerate() {
            let b = p.area_bounds(&standard_cells()[i], 0.0);
            assert!(
                b.inner_area <= *want
                    && *want <= b.outer_area
                    && b.outer_area - b.inner_area < band,
                "{m} set {i}: {want} vs [{}, {}] ({} leaves)",
                b.inner_area,
                b.outer_area,
                p.leaves.len()
            );
        }
    }
    areas_within_1e12(&scene, &exact, "");
}

/// `area` of each of the six sets of `scene` contains `exact` and is at
/// most 10⁻¹² wide, in at most 2¹⁰ θ-pieces.
fn areas_within_1e12(scene: &Scene, exact: &[f64; 6], what: &str) {
    for (i, want) in exact.iter().enumerate() {
        let opts = AreaOptions {
            tol: 1e-12,
            max_pieces: 1 << 10,
        };
        let e = cell_area(scene, Variant::Derived, &scene.domain(), Cell::ALL[i], opts).unwrap();
        assert!(
            e.area.contains(*want) && e.area.wid() <= 1e-12,
            "{what} set {i}: {:?}",
            e.area
        );
    }
}

/// `scene` paved by method `m`.
fn pave_with(scene: &Scene, m: detach::pave::Method, opts: PaveOptions) -> detach::pave::Paving {
    detach::pave::pave_scene_method(
        scene,
        Variant::Derived,
        &scene.domain(),
        opts,
        &detach::pave::MethodOptions::new(m),
        |_, _, _| {},
    )
    .unwrap()
}

/// Degenerate regions, by hand on θ ∈ [0, 1], θ̇ ∈ [−2, 2] (area 4), with
/// Ω = {θ̇² > 1} (area 2):
/// - Ω₀ = {0 < 0} (written as `theta_dot - theta_dot < 0`, g ≡ 0): empty,
///   so its complement is the whole window: Ω∩Ω̄₀ = 2 and Ω̄∩Ω̄₀ = 2 (a
///   complement taken as `{g > 0}` would give 0 for both);
/// - Ω₀ = {θ̇² > 0}, a double root along θ̇ = 0: the whole window, so
///   Ω∩Ω₀ = 2 and Ω̄∩Ω₀ = 2; the default method cuts at the double root
///   (it once left the window undecided, 10⁶ leaves).
#[test]
fn degenerate_regions_are_measured_as_sets() {
    let scene = |omega0: &str| {
        let text = format!(
            "name = \"flat\"\n[domain]\ntheta = [\"0\", \"1\"]\ntheta_dot = [\"-2\", \"2\"]\n\
             [regions]\nomega = \"theta_dot^2 - 1 > 0\"\nomega0 = \"{omega0}\"\n"
        );
        Scene::File(Box::new(FileScene::parse(&text, &[]).unwrap()))
    };
    let cases = [
        ("theta_dot - theta_dot < 0", [2.0, 0.0, 0.0, 2.0, 0.0, 2.0]),
        ("theta_dot^2 > 0", [2.0, 4.0, 2.0, 0.0, 2.0, 0.0]),
    ];
    for (omega0, exact) in cases {
        areas_within_1e12(&scene(omega0), &exact, omega0);
    }
    let s = scene("theta_dot^2 > 0");
    for m in detach::pave::Method::ALL {
        if !matches!(m.name(), "contract" | "slices") {
            continue;
        }
        let p = pave_with(&s, m, PaveOptions::default());
        let b = p.area_bounds(&standard_cells()[1], 0.0);
        assert!(
            b.inner_area <= 4.0 && b.outer_area >= 4.0 && b.outer_area - b.inner_area < 1e-9,
            "{m}: [{}, {}] in {} leaves",
            b.inner_area,
            b.outer_area,
            p.leaves.len()
        );
    }
}

/// A region undefined on half the window (`ln(theta_dot)` where θ̇ ≤ 0): the
/// warning names an undefined formula as a cause, not only overflow.
#[test]
fn an_undefined_half_window_is_named_in_the_warning() {
    let dir = std::env::temp_dir().join(format!("detach-ln-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("ln.toml");
    std::fs::write(
        &file,
        "name = \"ln\"\n[domain]\ntheta = [\"0\", \"1\"]\ntheta_dot = [\"-1\", \"1\"]\n\
         [regions]\nomega = \"ln(theta) + theta_dot < 0\"\nomega0 = \"ln(theta_dot) < 0\"\n",
    )
    .unwrap();
    let v = json(&[
        "pave",
        "--scene-file",
        file.to_str().unwrap(),
        "--eps",
        "0.05",
        "--json",
    ]);
    let w = v["warnings"][0].as_str().unwrap_or_default();
    assert!(w.contains("a formula is undefined there"), "{v}");
    assert!(v["undefined_area"].as_f64().unwrap() >= 1.0, "{v}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The undefined-area analysis of a paving: `ln(θ̇)` is
/// undefined for θ̇ ≤ 0, the lower half of θ ∈ [0, 1], θ̇ ∈ [−1, 1] (area 1
/// of 2, by hand), so the undefined leaves cover that half and the strip of
/// boxes straddling θ̇ = 0 (at eps = 1/32 at most 2/32 more): more than half
/// the window, which makes them dominant, within θ̇ ≤ 1/16.
#[test]
fn undefined_leaves_are_measured_and_dominate_when_over_half() {
    let ln = "name = \"ln\"\n[domain]\ntheta = [\"0\", \"1\"]\ntheta_dot = [\"-1\", \"1\"]\n\
              [regions]\nomega = \"theta + theta_dot < 0\"\nomega0 = \"ln(theta_dot) < 0\"\n";
    let scene = Scene::File(Box::new(FileScene::parse(ln, &[]).unwrap()));
    let opts = PaveOptions {
        eps: 1.0 / 32.0,
        ..PaveOptions::default()
    };
    let p = pave_with(&scene, detach::pave::Method::Natural, opts);
    let u = p.undefined_area();
    assert!(
        u.area_sup >= 1.0 && u.area_sup <= 1.0 + 2.0 / 32.0 + 1e-12,
        "{u:?}"
    );
    assert!(
        u.leaves > 0 && u.leaves < u.of_leaves && !u.everywhere(),
        "{u:?}"
    );
    let [th, thd] = u.dominant.expect("over half the window");
    assert!(th[0] == 0.0 && th[1] == 1.0 && thd[0] == -1.0, "{u:?}");
    assert!(thd[1] > 0.0 && thd[1] <= 1.0 / 16.0, "{u:?}");
    let w = u.warning().unwrap();
    assert!(
        w.starts_with("undefined leaves cover more than half of the area")
            && w.contains(&format!("({} of {} leaves)", u.leaves, u.of_leaves)),
        "{w}"
    );
    // The disc on ice is undefined only where sin θ = 0, at the domain's
    // ends: a few leaves, far from half of it, and no warning.
    let ice = Scene::default_of(SceneId::IceDisc);
    let p = pave_with(&ice, detach::pave::Method::Natural, opts);
    let u = p.undefined_area();
    assert!(
        u.leaves > 0 && u.area_sup < 0.1 * p.root.area().inf(),
        "{u:?}"
    );
    assert_eq!((u.dominant, u.warning()), (None, None));
}

/// `inf` is reserved in proof files (FORMAT.md, Expressions), so a scene
/// file may not name a parameter or definition `inf`: its proofs would be
/// unreadable.
#[test]
fn a_name_inf_is_refused_as_in_proof_files() {
    let param = GOOD
        .replace("g = \"9.81\"", "inf = \"9.81\"")
        .replace("- g\"", "- inf\"");
    let def = GOOD.replace("\nV = ", "\ninf = ").replace("U/V", "U/inf");
    for text in [param, def] {
        let err = FileScene::parse(&text, &[]).expect_err("refused");
        assert!(err.contains("`inf` is reserved"), "{err}");
    }
    // Another spelling is a name like any other.
    let other = GOOD
        .replace("g = \"9.81\"", "Inf = \"9.81\"")
        .replace("- g\"", "- Inf\"");
    assert!(FileScene::parse(&other, &[]).is_ok());
}

/// `tests/data/vertical-line.toml`: `cos θ·θ̇² + g·cos²θ < 0`, whose θ̇²
/// coefficient vanishes at θ = ±π/2. `slices` once left a column of the
/// full height (8) undecided there (drawn as a white line) while `natural`
/// decided all but boxes along the line; now every undecided leaf of
/// `slices` is at most an eighth of the height and its undecided area is
/// below `natural`'s, with at most twice `slices`' leaves before the fix
/// (10 554; counts are deterministic).
#[test]
fn slices_decide_a_column_where_the_leading_coefficient_vanishes() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/vertical-line.toml");
    let scene = Scene::from_file(&path, &[]).unwrap().0;
    let opts = PaveOptions::default();
    let undecided = |p: &detach::pave::Paving| {
        let b = p.area_bounds(&standard_cells()[0], 0.0);
        b.outer_area - b.inner_area
    };
    let sl = pave_with(&scene, detach::pave::Method::Slices, opts);
    let nat = pave_with(&scene, detach::pave::Method::Natural, opts);
    for l in &sl.leaves {
        if l.labels[0] == Label::Undecided {
            let h = l.bx.theta_dot[1] - l.bx.theta_dot[0];
            assert!(h <= 1.0, "undecided leaf {:?} of height {h}", l.bx);
        }
    }
    assert!(
        undecided(&sl) < undecided(&nat),
        "{} vs {}",
        undecided(&sl),
        undecided(&nat)
    );
    assert!(sl.leaves.len() <= 21_000, "{} leaves", sl.leaves.len());
}

/// A repeated `--param` is refused (it used to keep the last value), for a
/// scene file and a paper scene alike; a parameter-only subexpression that
/// only may be undefined (`sqrt(g - 9.81)`: √0 is defined, but the
/// enclosure of g − 9.81 reaches below 0) is a warning on stderr, not a
/// refusal.
#[test]
fn repeated_params_are_refused_and_doubtful_ones_warned() {
    for scene in ["painleve-rod", "viscous-disc"] {
        let p = if scene == "viscous-disc" { "g" } else { "mu" };
        let (a, b) = (format!("{p}=1"), format!("{p}=2"));
        let args = ["pave", "--scene", scene, "--param", &a, "--param", &b];
        assert_bad_input(&args, &format!("`{p}` is given twice (`1` and `2`)"));
    }
    let dir = std::env::temp_dir().join(format!("detach-doubt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("doubt.toml");
    std::fs::write(
        &file,
        GOOD.replace("omega = \"U < 0\"", "omega = \"U*sqrt(g - 9.81) + U < 0\""),
    )
    .unwrap();
    let out = detach(&[
        "pave",
        "--scene-file",
        file.to_str().unwrap(),
        "--eps",
        "0.5",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains("warning: with g = 9.81, `sqrt(g - 9.81)` may be undefined"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

const FUNCS: &str = r#"
name = "funcs"
[domain]
theta = [0, 1]
theta_dot = ["-2", "2"]
[parameters]
c = { value = 0.5, description = "cap", unit = "rad" }
[regions]
omega = "atan(theta_dot) < min(theta, c)"
omega0 = "exp(theta)*sign(theta_dot - c) > 0"
"#;

/// The functions users asked for, in a file with bare numbers and a
/// described parameter: Ω = {atan θ̇ < min(θ, 1/2)} has area
/// 2 − ln cos(1/2) + tan(1/2)/2 (∫ tan(min(θ, 1/2)) + 2 dθ, closed form),
/// Ω₀ = {θ̇ > 1/2} area 3/2. The paving's bounds contain both, and its
/// proof (with `atan exp sign min`) verifies in the checker.
#[test]
fn new_functions_pave_and_prove() {
    let scene = Scene::File(Box::new(FileScene::parse(FUNCS, &[]).unwrap()));
    let exact = [2.0 - 0.5f64.cos().ln() + 0.5 * 0.5f64.tan(), 1.5];
    let opts = PaveOptions {
        eps: 1.0 / 256.0,
        ..PaveOptions::default()
    };
    let p = pave_with(&scene, detach::pave::Method::Natural, opts);
    assert_regions_enclose(&p, &exact, 0.2, "natural");
    let dir = std::env::temp_dir().join(format!("detach-funcs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("funcs.toml");
    std::fs::write(&file, FUNCS).unwrap();
    let proof = dir.join("funcs.json");
    prove_and_verify(file.to_str().unwrap(), &proof);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Quadratic regions whose θ-coefficient has a kink or a jump at θ = 1/2:
/// `sign(θ − 1/2)·θ̇² − 1 < 0` (area 0.5·4 + 0.5·2 = 3) and
/// `abs(θ − 1/2)·θ̇² − 1/4 < 0` (|θ̇| < min(2, 1/(2√|θ − 1/2|)): area
/// 2√2 − 1/2, closed form). `area` encloses both soundly.
#[test]
fn kinked_coefficients_are_measured_soundly() {
    let text = FUNCS
        .replace(
            "atan(theta_dot) < min(theta, c)",
            "sign(theta - 0.5)*theta_dot^2 - 1 < 0",
        )
        .replace(
            "exp(theta)*sign(theta_dot - c) > 0",
            "abs(theta - 0.5)*theta_dot^2 - 0.25 < 0",
        );
    let dir = std::env::temp_dir().join(format!("detach-kinks-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("kinks.toml");
    std::fs::write(&file, text).unwrap();
    let v = json(&[
        "area",
        "--scene-file",
        file.to_str().unwrap(),
        "--digits",
        "6",
        "--json",
    ]);
    let exact = [3.0, 2.0 * 2f64.sqrt() - 0.5];
    for (r, want) in v["regions"].as_array().unwrap().iter().zip(exact) {
        let (lo, hi) = (r["lower"].as_f64().unwrap(), r["upper"].as_f64().unwrap());
        assert!(lo <= want && want <= hi, "{want} vs [{lo}, {hi}]: {v}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Descriptions and units of a file's parameters and its conditions are
/// listed by `detach scenes` (the shipped rod declares units) and kept in
/// its JSON.
#[test]
fn scenes_lists_parameter_descriptions_and_units() {
    let out = detach(&["scenes"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    assert!(text.contains("g      = 9.81 m/s^2 gravity"), "{text}");
    assert!(text.contains("l      = 1 m"), "{text}");
    // Conditions as the files write them: the viscous disc's b < a.
    assert!(text.contains("conditions: a > 0, b >= 0, b < a"), "{text}");
    let v = json(&["scenes", "--json"]);
    let rod = v
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == "painleve-rod")
        .unwrap();
    assert_eq!(rod["params"][2]["unit"], "m/s^2", "{rod}");
    assert_eq!(rod["params"][0]["meaning"], "mass", "{rod}");
}

/// Ω and Ω₀ (the first two sets) of `p` enclose `exact` within `width`.
fn assert_regions_enclose(p: &detach::pave::Paving, exact: &[f64], width: f64, what: &str) {
    for (i, want) in exact.iter().enumerate() {
        let b = p.area_bounds(&standard_cells()[i], 0.0);
        assert!(
            b.inner_area <= *want && *want <= b.outer_area && b.outer_area - b.inner_area < width,
            "{what} region {i}: {want} vs [{}, {}]",
            b.inner_area,
            b.outer_area
        );
    }
}

/// `pave --scene-file f --eps 0.02 --proof proof`, then `detach verify`
/// finds the proof VALID.
fn prove_and_verify(f: &str, proof: &Path) {
    let p = proof.to_str().unwrap();
    json(&[
        "pave",
        "--scene-file",
        f,
        "--eps",
        "0.02",
        "--json",
        "--proof",
        p,
    ]);
    let out = detach(&["verify", p]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && text.contains("VALID"), "{text}");
}
