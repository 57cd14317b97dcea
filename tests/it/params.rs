//! Parameter atlases: statuses checked against closed forms (the uniform
//! rod's μ* = 4/3, the ladder's 2√(1+r)/r, both derived in their scene
//! files), against sampling in plain f64, and the command line.

use crate::common::{assert_bad_input, detach, json, Rng};
use detach::params::model::{ParamAxis, SetStatus};
use detach::params::{decide, search, DecideOptions, Family, Regions, SearchOptions, Source};
use detach::scene::Cell;
use detach::scene::{SceneText, Variant};
use inari::Interval;

const LADDER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/ladder.toml");
const PARADOXES: [Cell; 2] = [Cell::Omega0NotOmega, Cell::OmegaNotOmega0];

fn axis(name: &str, lo: &str, hi: &str) -> ParamAxis {
    ParamAxis {
        name: name.into(),
        lo: lo.into(),
        hi: hi.into(),
    }
}

fn family(source: Source, axes: Vec<ParamAxis>) -> Family {
    Family::new(source, Variant::Derived, Vec::new(), axes).unwrap()
}

fn ladder() -> Source {
    Source::File(SceneText::read(std::path::Path::new(LADDER)).unwrap())
}

fn opts(eps: f64) -> SearchOptions {
    SearchOptions {
        eps,
        max_boxes: 100_000,
        decide: DecideOptions::default(),
        shard: None,
    }
}

/// The rod's and the ladder's U and V in plain f64 (`r = 3` is the rod),
/// and whether (θ, θ̇) is in a cell, or `None` within `1e-9` of a boundary.
fn in_cell(cell: Cell, theta: f64, theta_dot: f64, mu: f64, r: f64) -> Option<bool> {
    let u = theta.sin() * theta_dot * theta_dot - 9.81;
    let v = 1.0 + r * (theta.cos().powi(2) - mu * theta.sin() * theta.cos());
    if u.abs() < 1e-9 || v.abs() < 1e-9 {
        return None;
    }
    let (omega, omega0) = (u < 0.0, u / v < 0.0);
    let s = cell.spec().0;
    Some(
        [omega, omega0]
            .iter()
            .zip(s)
            .all(|(x, want)| want.is_none_or(|w| w == *x)),
    )
}

/// Every status of an atlas of the rod (r = 3) or the ladder, checked by
/// sampling: a witness box's points are in the set for every parameter of
/// the box, and no point of the domain is for a box proved empty.
fn check_by_sampling(f: &Family, cells: &[Cell], leaves: &[detach::params::model::ParamLeaf]) {
    let mut rng = Rng(0x9e3779b97f4a7c15);
    for leaf in leaves {
        let pick = |rng: &mut Rng, r: [f64; 2]| r[0] + (r[1] - r[0]) * rng.unit();
        for (cell, s) in cells.iter().zip(&leaf.sets) {
            for _ in 0..20 {
                let mu = pick(&mut rng, leaf.bounds[0]);
                let r = if f.axes.len() == 2 {
                    pick(&mut rng, leaf.bounds[1])
                } else {
                    3.0
                };
                let (t, w, want) = match s {
                    SetStatus::Nonempty { witness } => (
                        pick(&mut rng, witness.theta),
                        pick(&mut rng, witness.theta_dot),
                        true,
                    ),
                    SetStatus::Empty { .. } => (
                        pick(&mut rng, [0.0, std::f64::consts::FRAC_PI_2]),
                        pick(&mut rng, [-10.0, 10.0]),
                        false,
                    ),
                    SetStatus::Undecided { .. } => break,
                };
                if let Some(got) = in_cell(*cell, t, w, mu, r) {
                    assert_eq!(got, want, "{cell:?} at θ={t}, θ̇={w}, μ={mu}, r={r}: {s:?}");
                }
            }
        }
    }
}

#[test]
fn rod_threshold_encloses_four_thirds_to_1e_9() {
    let f = family(
        Source::by_name("painleve-rod").unwrap(),
        vec![axis("mu", "1", "2")],
    );
    let run = search(&f, &PARADOXES, &opts(2f64.powi(-34)), |_, _, _| {}).unwrap();
    assert!(run.complete);
    let json = detach::params::report::atlas_json(&f, &run, 2f64.powi(-34), None);
    let t = json["thresholds"].as_array().unwrap();
    // One change per paradox cell: empty below μ*, non-empty above.
    assert_eq!(t.len(), 2, "{t:?}");
    for th in t {
        assert_eq!(th["below"], "empty");
        assert_eq!(th["above"], "nonempty");
        let end = |k: usize| -> Interval {
            detach::number::param::enclose_decimal("mu", th["enclosure"][k].as_str().unwrap())
                .unwrap()
        };
        let (a, b) = (end(0), end(1));
        let three = Interval::try_from((3.0, 3.0)).unwrap();
        // a < 4/3 < b, certified: 3a < 4 < 3b.
        assert!((a * three).sup() < 4.0 && (b * three).inf() > 4.0, "{th}");
        assert!((b - a).sup() <= 1e-9 * 4.0 / 3.0, "width {}", (b - a).sup());
    }
    check_by_sampling(&f, &PARADOXES, &run.atlas.leaves);
}

#[test]
fn ladder_boxes_agree_with_the_closed_form() {
    let f = family(
        ladder(),
        vec![axis("mu", "0.5", "4"), axis("r", "0.5", "4")],
    );
    let run = search(&f, &PARADOXES, &opts(1.0 / 32.0), |_, _, _| {}).unwrap();
    let critical = |r: f64| 2.0 * (1.0 + r).sqrt() / r;
    let (mut empty, mut nonempty, mut undecided) = (0.0, 0.0, 0.0);
    for leaf in &run.atlas.leaves {
        let [mu, r] = [leaf.bounds[0], leaf.bounds[1]];
        let area = (mu[1] - mu[0]) * (r[1] - r[0]) / (3.5 * 3.5);
        for s in &leaf.sets {
            match s {
                // μ ≤ μ*(r) on the whole box: at its largest μ and r.
                SetStatus::Empty { .. } => {
                    assert!(mu[1] <= critical(r[1]) * (1.0 + 1e-12), "{leaf:?}");
                    empty += area;
                }
                // μ > μ*(r) on the whole box: at its smallest μ and r.
                SetStatus::Nonempty { .. } => {
                    assert!(mu[0] >= critical(r[0]) * (1.0 - 1e-12), "{leaf:?}");
                    nonempty += area;
                }
                SetStatus::Undecided { .. } => undecided += area,
            }
        }
    }
    // Both sides are reached, and only boxes along the curve stay open.
    assert!(empty > 0.3 && nonempty > 0.3, "{empty} {nonempty}");
    assert!(undecided < 0.2, "undecided share {undecided}");
    check_by_sampling(&f, &PARADOXES, &run.atlas.leaves);
}

#[test]
fn rod_below_threshold_paradox_cells_are_proved_empty_at_a_point() {
    use detach::params::proved_empty;
    for (mu, empty) in [("1.2", true), ("1.3", true), ("1.5", false)] {
        let (scene, _) =
            detach::scene::Scene::by_name("painleve-rod", &[("mu".into(), mu.into())]).unwrap();
        for cell in PARADOXES {
            assert_eq!(
                proved_empty(&scene, Variant::Derived, cell),
                empty,
                "{cell:?} at mu = {mu}"
            );
        }
        // Ω and Ω₀ are never empty.
        assert!(!proved_empty(&scene, Variant::Derived, Cell::Omega));
    }
}

#[test]
fn a_negative_factor_empties_only_the_cell_asking_both_negative() {
    // V < 0 everywhere: U/V < 0 exactly where U > 0. Ω∩Ω₀ = {U < 0, U/V < 0}
    // is empty; Ω̄∩Ω̄₀ = {U ≥ 0, U/V ≥ 0} is the curve U = 0, not empty.
    let text = r#"
name = "negative"
[domain]
theta = ["0.1", "1.5"]
theta_dot = ["-10", "10"]
[parameters]
k = "1"
[definitions]
U = "sin(theta)*theta_dot^2 - 9.81"
V = "-k - cos(theta)^2"
[regions]
omega = "U < 0"
omega0 = "U/V < 0"
"#;
    let dir = std::env::temp_dir().join(format!("detach-negative-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("negative.toml");
    std::fs::write(&path, text).unwrap();
    let f = family(
        Source::File(SceneText::read(&path).unwrap()),
        vec![axis("k", "1", "2")],
    );
    let cells = [Cell::OmegaAndOmega0, Cell::NeitherOmegaNorOmega0];
    let run = search(&f, &cells, &opts(1.0 / 4.0), |_, _, _| {}).unwrap();
    for leaf in &run.atlas.leaves {
        assert!(
            matches!(leaf.sets[0], SetStatus::Empty { .. }),
            "{:?}",
            leaf.sets[0]
        );
        assert!(
            !matches!(leaf.sets[1], SetStatus::Empty { .. }),
            "{:?}",
            leaf.sets[1]
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn params_json_has_the_documented_keys() {
    let v = json(&[
        "params",
        "--scene",
        "painleve-rod",
        "--x",
        "mu=1:2",
        "--eps",
        "1e-4",
        "--json",
    ]);
    let b = &v["boxes"][0];
    assert!(b["params"]["mu"][0].is_string() && b["params"]["mu"][1].is_string());
    assert_eq!(b["params"]["mu"][0], "1", "the root's end as written");
    for s in ["not_omega_and_omega0", "omega_and_not_omega0"] {
        let st = b["sets"][s].as_str().unwrap();
        assert!(["nonempty", "empty", "undecided"].contains(&st), "{st}");
    }
    let t = &v["thresholds"][0];
    for k in ["set", "param", "below", "above"] {
        assert!(t[k].is_string(), "{k}: {t}");
    }
    assert!(t["enclosure"][0].is_string() && t["enclosure"][1].is_string());
}

#[test]
fn params_refuses_bad_input() {
    let rod = ["params", "--scene", "painleve-rod"];
    let with = |extra: &[&'static str]| -> Vec<&'static str> {
        rod.iter().chain(extra).copied().collect()
    };
    assert_bad_input(&with(&["--x", "mu=2:1"]), "empty");
    assert_bad_input(&with(&["--x", "nu=1:2"]), "unknown parameter `nu`");
    assert_bad_input(&with(&["--x", "mu=1"]), "NAME=LO:HI");
    assert_bad_input(&with(&["--x", "mu=abc:2"]), "not a finite decimal");
    assert_bad_input(
        &with(&["--x", "mu=1:2", "--sets", "omega,nope"]),
        "unknown set",
    );
    assert_bad_input(&with(&["--x", "mu=1:2", "--y", "mu=1:2"]), "two different");
    assert_bad_input(&with(&["--x", "mu=1:2", "--eps", "0"]), "eps");
    assert_bad_input(&with(&["--x", "mu=1:2", "--shard", "3/3", "--json"]), "K/N");
    assert_bad_input(
        &with(&["--x", "mu=1:2", "--shard", "0/2"]),
        "--json or --out",
    );
    assert_bad_input(&["merge", "/nonexistent/part.json"], "cannot read");
}

#[test]
fn sharded_runs_merge_byte_identical() {
    let dir = std::env::temp_dir().join(format!("detach-shards-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let args = [
        "params",
        "--scene-file",
        LADDER,
        "--x",
        "mu=0.5:4",
        "--y",
        "r=0.5:4",
        "--eps",
        "0.0625",
        "--json",
    ];
    let whole = detach(&args);
    assert!(whole.status.success());
    let mut parts = Vec::new();
    for k in 0..3 {
        let shard = format!("{k}/3");
        let mut a: Vec<&str> = args.to_vec();
        a.extend(["--shard", &shard]);
        let out = detach(&a);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let path = dir.join(format!("part{k}.json"));
        std::fs::write(&path, &out.stdout).unwrap();
        parts.push(path);
    }
    // Any order of the parts.
    let p: Vec<&str> = parts.iter().rev().map(|p| p.to_str().unwrap()).collect();
    let merged = detach(&[&["merge"], p.as_slice()].concat());
    assert!(
        merged.status.success(),
        "{}",
        String::from_utf8_lossy(&merged.stderr)
    );
    assert_eq!(merged.stdout, whole.stdout);
    // A part missing or given twice is refused.
    assert_bad_input(&["merge", p[0], p[1]], "missing");
    assert_bad_input(&["merge", p[0], p[0], p[1], p[2]], "twice");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn pave_and_area_report_a_proved_empty_cell_as_exactly_empty() {
    let pave = json(&[
        "pave",
        "--scene",
        "painleve-rod",
        "--param",
        "mu=1.2",
        "--json",
    ]);
    let area = json(&[
        "area",
        "--scene",
        "painleve-rod",
        "--param",
        "mu=1.2",
        "--json",
    ]);
    for name in ["not_omega_and_omega0", "omega_and_not_omega0"] {
        let r = pave["regions"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["name"] == name)
            .unwrap();
        assert_eq!(r["outer_area"], 0.0, "{r}");
        assert_eq!(r["empty"], "proved empty", "{r}");
        let a = area["regions"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["name"] == name)
            .unwrap();
        assert_eq!(
            (a["lower"].as_f64(), a["upper"].as_f64()),
            (Some(0.0), Some(0.0)),
            "{a}"
        );
        assert_eq!(a["empty"], "proved empty", "{a}");
    }
    // The table says why: proved, not the disc's Ω₀ ⊂ Ω.
    let out = detach(&["pave", "--scene", "painleve-rod", "--param", "mu=1.2"]);
    let table = String::from_utf8_lossy(&out.stdout);
    assert_eq!(table.matches("empty (proved empty)").count(), 2, "{table}");
    assert!(!table.contains("p_φ"), "{table}");
    // Above the threshold the cells are not empty.
    let pave = json(&[
        "pave",
        "--scene",
        "painleve-rod",
        "--param",
        "mu=1.5",
        "--json",
    ]);
    for r in pave["regions"].as_array().unwrap() {
        assert!(r["empty"].is_null(), "{r}");
    }
}

/// The atlas of a paper scene over one parameter, `fixed` overriding others.
fn paper_atlas(
    scene: &str,
    fixed: &[(&str, &str)],
    x: ParamAxis,
    cells: &[Cell],
) -> Vec<detach::params::model::ParamLeaf> {
    let overrides = fixed
        .iter()
        .map(|(n, v)| (n.to_string(), v.to_string()))
        .collect();
    let f = Family::new(
        Source::by_name(scene).unwrap(),
        Variant::Derived,
        overrides,
        vec![x],
    )
    .unwrap();
    search(&f, cells, &opts(1.0 / 16.0), |_, _, _| {})
        .unwrap()
        .atlas
        .leaves
}

/// paper-checks S1.friction and S1.nonunique (confirmed, certified at
/// μ = 0.8): with friction both paradox cells of Example 1 are non-empty.
/// The atlas over μ ∈ [0.5, 1] proves them non-empty on every box.
#[test]
fn paper_example_1_paradoxes_exist_around_mu_0_8() {
    let leaves = paper_atlas("viscous-disc", &[], axis("mu", "0.5", "1"), &PARADOXES);
    for leaf in &leaves {
        for s in &leaf.sets {
            assert!(
                matches!(s, SetStatus::Nonempty { .. }),
                "{:?}: {s:?}",
                leaf.bounds
            );
        }
    }
}

/// paper-checks S3.sub1 (confirmed): p_φ = p_ψ = 0 gives Ω₀ ⊂ Ω for every
/// c₀, so Ω̄∩Ω₀ is never non-empty; and A.onlyN / S3.sub2 (confirmed): at
/// p_φ = p_ψ = 2, c₀ = 0 an equilibrium lies in Ω₀ outside Ω, so Ω̄∩Ω₀ is
/// non-empty on the boxes about c₀ = 0.
#[test]
fn paper_ice_disc_omega0_inside_omega_and_its_failure() {
    let cell = [Cell::Omega0NotOmega];
    let zero = [("p_phi", "0"), ("p_psi", "0")];
    for leaf in paper_atlas("ice-disc", &zero, axis("c0", "-1", "1"), &cell) {
        assert!(
            !matches!(leaf.sets[0], SetStatus::Nonempty { .. }),
            "{leaf:?}"
        );
    }
    let two = [("p_phi", "2"), ("p_psi", "2")];
    let leaves = paper_atlas("ice-disc", &two, axis("c0", "-0.25", "0.25"), &cell);
    let at_zero: Vec<_> = leaves
        .iter()
        .filter(|l| l.bounds[0][0] <= 0.0 && 0.0 <= l.bounds[0][1])
        .collect();
    assert!(!at_zero.is_empty());
    for leaf in at_zero {
        assert!(
            matches!(leaf.sets[0], SetStatus::Nonempty { .. }),
            "{leaf:?}"
        );
    }
}

#[test]
fn two_parameters_draw_the_plane_and_mark_the_given_point() {
    let dir = std::env::temp_dir().join(format!("detach-plane-{}", std::process::id()));
    let out = detach(&[
        "params",
        "--scene-file",
        LADDER,
        "--x",
        "mu=0.5:4",
        "--y",
        "r=0.5:4",
        "--eps",
        "0.125",
        "--param",
        "mu=3",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let svg = std::fs::read_to_string(dir.join("params.svg")).unwrap();
    // Both statuses appear in the legend, and the given point is circled.
    assert!(svg.contains("proved non-empty"), "legend");
    assert!(svg.contains("all proved empty"), "legend");
    assert!(svg.contains("<circle"), "the --param point");
    assert!(std::fs::metadata(dir.join("params.png")).unwrap().len() > 1000);
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("params.json")).unwrap()).unwrap();
    assert_eq!(v["thresholds"].as_array().unwrap().len(), 0, "none in 2-D");
    std::fs::remove_dir_all(&dir).ok();
}

/// `params --proof` on the rod writes a parameter-atlas proof that the
/// standalone checker accepts, exactly and as loose as the slack rule allows
/// (FORMAT.md, "Accuracy"); with V's friction term changed from 3μ to 2μ
/// (paradoxes then iff μ > 2, by the same closed form) the witnesses claimed
/// for μ just above 4/3 no longer hold and the same file is INVALID.
#[test]
fn the_rods_parameter_atlas_proof_is_valid_and_a_changed_v_is_not() {
    use detach::check::{check_bytes, with_looseness, Looseness, Verdict};
    let dir = std::env::temp_dir().join(format!("detach-params-proof-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("rod.json");
    let out = detach(&[
        "params",
        "--scene",
        "painleve-rod",
        "--x",
        "mu=1:2",
        "--proof",
        path.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bytes = std::fs::read(&path).unwrap();
    let verdict = |b: &[u8]| check_bytes(b).unwrap().verdict;
    assert_eq!(verdict(&bytes), Verdict::Valid);
    let loose = Looseness {
        basic: 2,
        exact_too: true,
        functions: 4,
    };
    assert_eq!(with_looseness(loose, || verdict(&bytes)), Verdict::Valid);
    let text = String::from_utf8(bytes).unwrap();
    let v = "1 + 3*cos(t)^2 - 3*mu*sin(t)*cos(t)";
    assert_eq!(text.matches(v).count(), 1, "V is stated once, as written");
    let changed = text.replace(v, "1 + 3*cos(t)^2 - 2*mu*sin(t)*cos(t)");
    assert!(matches!(verdict(changed.as_bytes()), Verdict::Invalid(_)));
    std::fs::remove_dir_all(&dir).ok();
}

/// The statuses of every box of a `params --json` run, by set.
fn statuses(v: &serde_json::Value, set: &str) -> Vec<String> {
    v["boxes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b["sets"][set].as_str().unwrap().to_string())
        .collect()
}

/// Ω₀ written as the same expression as Ω (the smooth disc of §2, where
/// (2.7) and (2.8) are one formula; a user file stating one region twice):
/// Ω̄∩Ω₀ and Ω∩Ω̄₀ ask opposite signs of one function, so they are empty for
/// every parameter ("same constraint", the factor 1 in a proof). `params`
/// states them empty in every box with a proof both checkers accept, and
/// `area` gives exactly 0; a region that differs (U < 1) is not emptied.
#[test]
fn cells_asking_one_constraint_both_ways_are_empty() {
    let dir = std::env::temp_dir().join(format!("detach-same-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let proof = dir.join("smooth.json");
    let v = json(&[
        "params",
        "--scene",
        "smooth-disc",
        "--x",
        "p_phi=0:2",
        "--eps",
        "0.25",
        "--json",
        "--proof",
        proof.to_str().unwrap(),
    ]);
    for set in PARADOXES {
        let s = statuses(&v, set.name());
        assert!(
            !s.is_empty() && s.iter().all(|s| s == "empty"),
            "{set:?}: {s:?}"
        );
    }
    let out = detach(&["verify", proof.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    let bytes = std::fs::read(&proof).unwrap();
    let verdict = detach::check::check_bytes(&bytes).unwrap().verdict;
    assert_eq!(verdict, detach::check::Verdict::Valid);

    // Not of degree 2 in θ̇, so `area` bounds it by a paving.
    let file = |omega0: &str| {
        format!(
            "name = \"twice\"\n[domain]\ntheta = [\"0\", \"1\"]\ntheta_dot = [\"-2\", \"2\"]\n\
             [parameters]\nk = \"1\"\n[definitions]\nU = \"sin(k*theta*theta_dot) - 0.3\"\n\
             [regions]\nomega = \"U < 0\"\nomega0 = \"{omega0}\"\n"
        )
    };
    let twice = dir.join("twice.toml");
    std::fs::write(&twice, file("U < 0")).unwrap();
    let t = twice.to_str().unwrap();
    let v = json(&[
        "params",
        "--scene-file",
        t,
        "--x",
        "k=1:2",
        "--eps",
        "0.5",
        "--json",
    ]);
    let area = json(&["area", "--scene-file", t, "--json"]);
    for set in PARADOXES {
        let s = statuses(&v, set.name());
        assert!(s.iter().all(|s| s == "empty"), "{set:?}: {s:?}");
        let a = area["regions"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["name"] == set.name())
            .unwrap();
        assert_eq!(
            (a["lower"].as_f64(), a["upper"].as_f64()),
            (Some(0.0), Some(0.0)),
            "{a}"
        );
    }
    // U < 1 is another region: 0 ≤ U < 1 has points (U = 0.7 where
    // kθθ̇ = π/2, inside the domain for every k in [1, 2]), not stated empty.
    std::fs::write(&twice, file("U < 1")).unwrap();
    let v = json(&[
        "params",
        "--scene-file",
        t,
        "--x",
        "k=1:2",
        "--eps",
        "0.5",
        "--json",
    ]);
    let s = statuses(&v, Cell::Omega0NotOmega.name());
    assert!(s.iter().all(|s| s != "empty"), "{s:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The disc on ice's Ω̄∩Ω₀ at p_φ ≈ 1.3, p_ψ ≈ 0.4 (c₀ = 0): a thin band
/// (area about 0.02 of the domain's 63, by `detach area`). The search on
/// lines of constant θ proves a witness over the whole parameter box (1/256
/// of [0, 2] on each axis); the search of the plane at the box's centre
/// finds none. The witness is checked in plain f64 against the paper's
/// (2.7), (3.1) and (3.3), at its corners and at random points, for
/// parameters at the box's corners and at random.
#[test]
fn a_thin_cell_gets_a_witness_from_lines_of_constant_theta() {
    let f = family(
        Source::by_name("ice-disc").unwrap(),
        vec![
            axis("p_phi", "1.3", "1.3078125"),
            axis("p_psi", "0.4", "0.4078125"),
        ],
    );
    let at_box = f.scene_at(&f.root).unwrap();
    let centre: Vec<f64> = f.root.iter().map(|r| 0.5 * (r[0] + r[1])).collect();
    let at_centre = f.scene_at_point(&centre).unwrap();
    let over = Regions::new(&at_box, Variant::Derived);
    let mid = Regions::new(&at_centre, Variant::Derived);
    let cell = Cell::Omega0NotOmega.spec();
    let plane_only = DecideOptions {
        line_boxes: 0,
        ..DecideOptions::default()
    };
    let s = decide(&over, &mid, cell, plane_only);
    assert!(!matches!(s, SetStatus::Nonempty { .. }), "{s:?}");
    let SetStatus::Nonempty { witness } = decide(&over, &mid, cell, DecideOptions::default())
    else {
        panic!("no witness");
    };
    // (2.7), (3.1), (3.3) with m = 1, a = 1, A = 0.25, g = 9.81, c₀ = 0.
    let in_cell = |t: f64, w: f64, p_phi: f64, p_psi: f64| {
        let (a, big_a, g) = (1.0, 0.25, 9.81);
        let (s, c) = t.sin_cos();
        let tau = (p_psi - p_phi * c) / (big_a * s);
        let tau1 = (p_phi - p_psi * c) / (big_a * s * s);
        let u = a * s * w * w + a * tau * tau1 * c - g;
        let vx = -a / big_a * (p_psi * (t / 2.0).tan().ln() - p_phi * s.ln());
        let acc = (-g * a * c + a * vx * tau - big_a * tau * tau1) / (big_a + a * a);
        let minus_n = a * s * w * w - g - a * c * acc;
        u >= 0.0 && minus_n < 0.0
    };
    let mut rng = Rng(0x2545f4914f6cdd1d);
    let pick = |rng: &mut Rng, r: [f64; 2]| r[0] + (r[1] - r[0]) * rng.unit();
    let (x, y) = (f.root[0], f.root[1]);
    for i in 0..400 {
        // First every corner of the witness with every corner of the box.
        let (t, w) = if i < 16 {
            (witness.theta[i & 1], witness.theta_dot[(i >> 1) & 1])
        } else {
            (
                pick(&mut rng, witness.theta),
                pick(&mut rng, witness.theta_dot),
            )
        };
        let (p, q) = if i < 16 {
            (x[(i >> 2) & 1], y[(i >> 3) & 1])
        } else {
            (pick(&mut rng, x), pick(&mut rng, y))
        };
        assert!(
            in_cell(t, w, p, q),
            "{witness:?} at θ = {t}, θ̇ = {w}, p_φ = {p}, p_ψ = {q}"
        );
    }
}

/// Example 1 over (b, μ): Ω̄ = {b sinθ θ̇² ≥ g} meets the domain |θ̇| ≤ 10
/// only where b·100 ≥ g, so Ω̄∩Ω₀ is empty for every b ≤ g/100 (at b = g/100
/// Ω̄ is the two points θ = π/2, θ̇ = ±10, where Ω₀'s expression is 0); for
/// b > g/100 and μ > 0 it is non-empty (near Ω's boundary, Ω₀ holds where
/// μh²h'θ̇ < 0, i.e. θ̇cosθ < 0). No box may state otherwise, and both
/// statuses must appear.
#[test]
fn example_1_non_uniqueness_needs_b_above_g_over_100() {
    let f = family(
        Source::by_name("viscous-disc").unwrap(),
        vec![axis("b", "0", "0.9"), axis("mu", "0.25", "2")],
    );
    let leaves = search(&f, &[Cell::Omega0NotOmega], &opts(1.0 / 32.0), |_, _, _| {})
        .unwrap()
        .atlas
        .leaves;
    let threshold = 9.81 / 100.0;
    let (mut empty, mut nonempty) = (0, 0);
    for leaf in &leaves {
        let b = leaf.bounds[0];
        match leaf.sets[0] {
            SetStatus::Empty { .. } => {
                assert!(b[1] <= threshold, "{leaf:?}");
                empty += 1;
            }
            SetStatus::Nonempty { .. } => {
                assert!(b[0] > threshold, "{leaf:?}");
                nonempty += 1;
            }
            SetStatus::Undecided { .. } => {}
        }
    }
    assert!(
        empty > 0 && nonempty > 0,
        "{empty} empty, {nonempty} non-empty"
    );
}

/// The library's atlas (`api::Problem::param_atlas`) is the command line's
/// to the byte, and its shares of the box add up: the ladder (a scene file,
/// r fixed by `--param`) over μ, and the viscous disc over (b, μ).
#[test]
fn the_library_atlas_is_the_command_lines() {
    use detach::api::{ParamRequest, Problem};
    let cases: [(&[&str], Problem, &str, Option<&str>); 2] = [
        (
            &["--scene-file", LADDER, "--param", "r=2"],
            Problem::from_file(std::path::Path::new(LADDER), &[("r", "2")]).unwrap(),
            "mu=0:3",
            None,
        ),
        (
            &["--scene", "viscous-disc"],
            Problem::load("viscous-disc", &[]).unwrap(),
            "b=0:0.9",
            Some("mu=0.25:2"),
        ),
    ];
    for (source, problem, x, y) in cases {
        let eps = "0.0625";
        let mut args = vec!["params", "--x", x, "--eps", eps, "--json"];
        args.extend_from_slice(source);
        if let Some(y) = y {
            args.extend_from_slice(&["--y", y]);
        }
        let cli = json(&args);
        let mut axes = vec![ParamRequest::axis(x).unwrap()];
        axes.extend(y.map(|y| ParamRequest::axis(y).unwrap()));
        let req = ParamRequest {
            axes,
            eps: Some(0.0625),
            ..ParamRequest::default()
        };
        let atlas = problem.param_atlas(&req).unwrap();
        assert_eq!(atlas.json(), cli, "{args:?}");
        let shares = atlas.shares();
        assert_eq!(shares.len(), 2);
        for s in &shares {
            let total = s.nonempty + s.empty + s.undecided;
            assert!((total - 1.0).abs() < 1e-12, "{s:?}");
        }
        // Both statuses occur somewhere on both planes.
        assert!(shares.iter().any(|s| s.nonempty > 0.0), "{shares:?}");
        assert!(shares.iter().any(|s| s.empty > 0.0), "{shares:?}");
    }
}

/// A request the atlas cannot answer is refused with the command line's
/// words, not a panic.
#[test]
fn the_library_atlas_refuses_bad_requests() {
    use detach::api::{ParamRequest, Problem};
    let rod = Problem::load("painleve-rod", &[]).unwrap();
    let ask = |axes: &[&str], sets: Vec<Cell>, eps: Option<f64>| {
        let req = ParamRequest {
            axes: axes
                .iter()
                .map(|a| ParamRequest::axis(a).unwrap())
                .collect(),
            sets,
            eps,
            ..ParamRequest::default()
        };
        rod.param_atlas(&req)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    };
    let all = PARADOXES.to_vec();
    assert!(ask(&["nu=1:2"], all.clone(), None).contains("unknown parameter `nu`"));
    assert!(ask(&[], all.clone(), None).contains("one or two parameters"));
    assert!(ask(&["mu=1:2"], vec![], None).contains("at least one set"));
    assert!(ask(&["mu=1:2"], all.clone(), Some(0.0)).contains("eps must be"));
    assert!(ask(&["mu=2:1"], all, None).contains("mu"));
    let e = ParamRequest::axis("mu=1").unwrap_err();
    assert_eq!(e.kind(), detach::api::ErrorKind::InvalidOption);
    assert!(e.to_string().contains("NAME=LO:HI"));
}

/// An atlas stopped by its callback at a level is valid and coarser: its
/// decided statuses agree with a finished atlas's wherever their boxes
/// overlap, and its proof file is VALID.
#[test]
fn a_stopped_atlas_is_valid_and_coarser() {
    use detach::api::{ParamRequest, Problem};
    use std::ops::ControlFlow;
    let disc = Problem::load("viscous-disc", &[]).unwrap();
    let req = ParamRequest {
        axes: vec![
            ParamRequest::axis("b=0:0.9").unwrap(),
            ParamRequest::axis("mu=0.25:2").unwrap(),
        ],
        eps: Some(1.0 / 64.0),
        ..ParamRequest::default()
    };
    let stopped = disc
        .param_atlas_with_progress(&req, |level, _, _| {
            if level < 5 {
                ControlFlow::Continue(())
            } else {
                ControlFlow::Break(())
            }
        })
        .unwrap();
    let full = disc.param_atlas(&req).unwrap();
    assert!(stopped.run.interrupted && !stopped.run.complete);
    assert!(full.run.complete && !full.run.interrupted);
    let leaves = |a: &detach::api::ParamAtlasRun| -> Vec<detach::params::model::ParamLeaf> {
        let l = &a.run.atlas.leaves;
        l.iter().filter(|l| !l.bounds.is_empty()).cloned().collect()
    };
    let (coarse, fine) = (leaves(&stopped), leaves(&full));
    assert!(
        coarse.len() < fine.len(),
        "{} vs {}",
        coarse.len(),
        fine.len()
    );
    let overlap =
        |a: &[[f64; 2]], b: &[[f64; 2]]| a.iter().zip(b).all(|(x, y)| x[0] < y[1] && y[0] < x[1]);
    let decided = |s: &SetStatus| !matches!(s, SetStatus::Undecided { .. });
    let mut compared = 0;
    for c in &coarse {
        for f in fine.iter().filter(|f| overlap(&c.bounds, &f.bounds)) {
            for (a, b) in c.sets.iter().zip(&f.sets) {
                if decided(a) && decided(b) {
                    assert_eq!(
                        std::mem::discriminant(a),
                        std::mem::discriminant(b),
                        "{c:?} vs {f:?}"
                    );
                    compared += 1;
                }
            }
        }
    }
    assert!(compared > 0);
    let path =
        std::env::temp_dir().join(format!("detach-stopped-atlas-{}.json", std::process::id()));
    stopped.write_proof(&path).unwrap();
    assert_eq!(
        detach::api::verify(&path).unwrap().verdict,
        detach::api::Verdict::Valid
    );
    std::fs::remove_file(&path).ok();
}
