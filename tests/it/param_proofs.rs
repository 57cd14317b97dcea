//! `parameter-atlas` proofs: atlases built from pavings with interval
//! parameters and from interval evaluations on θ-slabs, written by
//! `detach::certificate::param_atlas_proof` and checked by the checker
//! crate (exact, and 2 ulps looser in the basic operations and 4 in the
//! functions) and by `detach verify`; wrong evidence of each kind is
//! INVALID.

use detach::certificate::params::phase_root;
use detach::certificate::{param_atlas_proof, to_bytes, ParamAtlasStatement};
use detach::check::{check_bytes, with_looseness, Looseness, Verdict};
use detach::number::param::ParamSet;
use detach::params::model::{EmptyReason, ParamAtlas, ParamAxis, ParamLeaf, ParamNode, SetStatus};
use detach::pave::{
    pave_scene_method, CellSpec, Method, MethodOptions, Node, PaveOptions, PhaseBox,
};
use detach::scene::{Domain, FileScene, Scene, SceneId, SceneText, Variant};
use inari::{const_interval, Interval};

fn point(x: f64) -> Interval {
    Interval::try_from((x, x)).unwrap()
}

fn iv(a: f64, b: f64) -> Interval {
    Interval::try_from((a, b)).unwrap()
}

fn cell(name: &str) -> CellSpec {
    name.parse::<detach::scene::Cell>().unwrap().spec()
}

/// The checker's verdict on a proof, exact and as loose as the slack rule
/// requires a proof to survive.
fn verdicts(proof: &serde_json::Value) -> [Verdict; 2] {
    let bytes = to_bytes(proof);
    let exact = check_bytes(&bytes).unwrap().verdict;
    let loose = Looseness {
        basic: 2,
        exact_too: false,
        functions: 4,
    };
    let loose = with_looseness(loose, || check_bytes(&bytes).unwrap().verdict);
    [exact, loose]
}

fn assert_valid(proof: &serde_json::Value) {
    for v in verdicts(proof) {
        assert_eq!(v, Verdict::Valid);
    }
}

fn assert_invalid(proof: &serde_json::Value, needle: &str) {
    match check_bytes(&to_bytes(proof)).unwrap().verdict {
        Verdict::Invalid(why) => assert!(why.contains(needle), "{why}"),
        v => panic!("expected INVALID ({needle}), got {v:?}"),
    }
}

/// What a paving of the whole phase box (from [`phase_root`]) proves of a
/// set: a witness leaf inside the domain with every literal proved, or every
/// leaf with a literal proved false (the tree and those literals), or
/// neither.
fn status_from_paving(scene: &Scene, name: &str) -> SetStatus {
    let domain = scene.domain();
    let root = phase_root(&domain);
    let outer = Domain {
        theta: root.theta.map(point),
        theta_dot: root.theta_dot.map(point),
    };
    let opts = PaveOptions {
        eps: 1.0 / 64.0,
        max_boxes: 200_000,
    };
    let p = pave_scene_method(
        scene,
        Variant::Derived,
        &outer,
        opts,
        &MethodOptions::new(Method::Slices),
        |_, _, _| {},
    )
    .unwrap();
    assert_eq!(p.root, root);
    let c = cell(name);
    let boxes = p.replay_boxes().unwrap();
    // A witness is a proved leaf's part inside the domain, kept 64 doubles
    // away from its ends (a looser checker encloses them wider).
    let inner = domain.inner_box();
    let away = |mut x: f64, up: bool| {
        for _ in 0..64 {
            x = if up { x.next_up() } else { x.next_down() };
        }
        x
    };
    let inside = |b: &PhaseBox| {
        let cut =
            |r: [f64; 2], d: [f64; 2]| [r[0].max(away(d[0], true)), r[1].min(away(d[1], false))];
        let w = phase(cut(b.theta, inner[0]), cut(b.theta_dot, inner[1]));
        (w.theta[0] < w.theta[1] && w.theta_dot[0] < w.theta_dot[1]).then_some(w)
    };
    let witness = (0..p.leaves.len())
        .filter(|&k| c.proved_in(&p.leaves[k]))
        .find_map(|k| inside(&boxes[k]));
    if let Some(witness) = witness {
        return SetStatus::Nonempty { witness };
    }
    let refuted = |k: usize| {
        (0..2).find(|&i| match c.0[i] {
            Some(true) => p.leaves[k].labels[i] == detach::pave::Label::ProvedOut,
            Some(false) => p.leaves[k].labels[i] == detach::pave::Label::ProvedIn,
            None => false,
        })
    };
    match (0..p.leaves.len()).map(refuted).collect::<Option<Vec<_>>>() {
        Some(lits) => SetStatus::Empty {
            tree: p.nodes.clone(),
            reasons: lits
                .into_iter()
                .map(|constraint| EmptyReason::Literal { constraint })
                .collect(),
        },
        None => SetStatus::Undecided {
            reason: "neither a witness nor a refuted literal on every leaf".into(),
        },
    }
}

/// The viscous disc (derived) with `b` over `[lo, hi]` (an interval
/// parameter), the others at their defaults.
fn viscous_over_b(lo: f64, hi: f64) -> (Scene, ParamSet) {
    let text = SceneText::embedded("viscous-disc").unwrap();
    let f = FileScene::parse_enclosed(&text.text, &[], &[("b".into(), iv(lo, hi))]).unwrap();
    let params = f.params.clone();
    (Scene::File(Box::new(f)), params)
}

const VISCOUS_SETS: [&str; 4] = [
    "omega",
    "omega_and_omega0",
    "not_omega_and_omega0",
    "not_omega_and_not_omega0",
];

/// Ω of the viscous disc (derived) is `{b sin θ θ̇² − g < 0}`; for b ≤ 0.0975
/// and |θ̇| ≤ 10, `b sin θ θ̇² − g ≤ 9.75 − 9.81 < 0` (closed form), so Ω is
/// the whole domain and the two cells outside Ω are empty; near θ̇ = 0 the
/// point is in Ω and in Ω₀ (`−C g < 0` there). Both parameter boxes, split
/// at b = 0.07, prove exactly that, from pavings with b an interval.
fn viscous_atlas() -> (ParamAtlas, ParamSet) {
    let root = [
        detach::number::param::enclose_decimal("b", "0.05")
            .unwrap()
            .inf(),
        detach::number::param::enclose_decimal("b", "0.0975")
            .unwrap()
            .sup(),
    ];
    let mut leaves = Vec::new();
    for bounds in [[root[0], 0.07], [0.07, root[1]]] {
        let (scene, _) = viscous_over_b(bounds[0], bounds[1]);
        leaves.push(ParamLeaf {
            bounds: vec![bounds],
            sets: VISCOUS_SETS
                .iter()
                .map(|s| status_from_paving(&scene, s))
                .collect(),
        });
    }
    let (_, params) = Scene::build(SceneId::ViscousDisc, &[]).unwrap();
    let atlas = ParamAtlas {
        axes: vec![ParamAxis {
            name: "b".into(),
            lo: "0.05".into(),
            hi: "0.0975".into(),
        }],
        sets: VISCOUS_SETS.iter().map(|s| s.to_string()).collect(),
        tree: vec![
            ParamNode::Split { axis: 0, at: 0.07 },
            ParamNode::Leaf(0),
            ParamNode::Leaf(1),
        ],
        leaves,
    };
    (atlas, params)
}

fn viscous_proof(atlas: &ParamAtlas, params: &ParamSet) -> serde_json::Value {
    let scene = Scene::default_of(SceneId::ViscousDisc);
    param_atlas_proof(
        &ParamAtlasStatement {
            scene: &scene,
            variant: Variant::Derived,
            params,
            title: "viscous disc over b".into(),
        },
        atlas,
    )
    .unwrap()
}

#[test]
fn a_viscous_disc_atlas_from_pavings_is_valid_for_a_looser_checker() {
    let (atlas, params) = viscous_atlas();
    for leaf in &atlas.leaves {
        let s = &leaf.sets;
        assert!(matches!(s[0], SetStatus::Nonempty { .. }), "{:?}", s[0]);
        assert!(matches!(s[1], SetStatus::Nonempty { .. }), "{:?}", s[1]);
        // Each leaf is outside those cells because Ω (constraint 0) is proved.
        for empty in &s[2..] {
            let SetStatus::Empty { reasons, .. } = empty else {
                panic!("{empty:?}")
            };
            assert!(reasons
                .iter()
                .all(|r| *r == EmptyReason::Literal { constraint: 0 }));
        }
    }
    let proof = viscous_proof(&atlas, &params);
    assert_eq!(proof["statement"]["parameters"]["b"][0], "0.05");
    assert_eq!(proof["statement"]["parameters"]["C"], "0.3");
    assert_valid(&proof);
    let out = detach_verify(&proof);
    assert!(out.contains("VALID"), "{out}");
}

/// Writes the proof to a temporary file and runs `detach verify` on it;
/// returns stdout, asserting exit status 0.
fn detach_verify(proof: &serde_json::Value) -> String {
    static RUN: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let run = RUN.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("detach-param-proof-{}-{run}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("atlas.json");
    std::fs::write(&path, to_bytes(proof)).unwrap();
    let out = crate::common::detach(&["verify", path.to_str().unwrap()]);
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// V = 1 + 3cos²θ − 3μ sinθ cosθ on `θ × μ`, natural interval extension.
fn rod_v(theta: Interval, mu: Interval) -> Interval {
    let (s, c) = (theta.sin(), theta.cos());
    const_interval!(1.0, 1.0) + const_interval!(3.0, 3.0) * c.sqr()
        - const_interval!(3.0, 3.0) * mu * s * c
}

/// θ-slabs of `root` (midpoint bisection in θ only) on each of which V > 0
/// is proved with a margin over `mu`; each leaf's reason is the factor rule,
/// Ω₀ = U/V over Ω = U with V positive.
fn rod_factor_tree(root: PhaseBox, mu: Interval) -> SetStatus {
    fn go(b: PhaseBox, mu: Interval, tree: &mut Vec<Node>, reasons: &mut Vec<EmptyReason>) {
        // The margin keeps the sign for a checker a few ulps looser.
        if rod_v(b.theta_interval(), mu).inf() > 1e-6 {
            tree.push(Node::Leaf(reasons.len() as u32));
            reasons.push(EmptyReason::Factor {
                constraint: 1,
                other: 0,
                positive: true,
            });
            return;
        }
        assert!(
            b.theta[1] - b.theta[0] > 1e-6,
            "V > 0 not proved near {b:?}"
        );
        tree.push(Node::Split(0));
        let (lo, hi) = b.split(0);
        go(lo, mu, tree, reasons);
        go(hi, mu, tree, reasons);
    }
    let (mut tree, mut reasons) = (Vec::new(), Vec::new());
    go(root, mu, &mut tree, &mut reasons);
    SetStatus::Empty { tree, reasons }
}

const ROD_SETS: [&str; 3] = ["omega", "not_omega_and_omega0", "omega_and_not_omega0"];

fn phase(t: [f64; 2], w: [f64; 2]) -> PhaseBox {
    PhaseBox {
        theta: t,
        theta_dot: w,
    }
}

/// The rod (`scenes/painleve-rod.toml`) over μ ∈ [1.0, 1.6], split at 1.2
/// and 1.5. For μ < 4/3, V > 0 for all θ (closed form in the scene file), so
/// both paradox cells are empty: the factor rule on θ-slabs. For μ ∈ [1.5,
/// 1.6], V < 0 on θ ∈ [1, 1.01] (V ≤ −0.13 by hand), so both cells have
/// witnesses there: θ̇ ∈ [0, 0.1] (U ≤ sin(1.01)·0.01 − 9.81 < 0, U/V > 0)
/// and θ̇ ∈ [5, 5.1] (U ≥ sin(1)·25 − 9.81 > 11, U/V < 0). Ω holds all of
/// [0.5, 0.6] × [0, 1] (U ≤ 0.57 − 9.81). In between, undecided.
fn rod_atlas() -> (Scene, ParamSet, ParamAtlas) {
    let (scene, params) = Scene::by_name("painleve-rod", &[]).unwrap();
    let root = phase_root(&scene.domain());
    let enclose = |t: &str| detach::number::param::enclose_decimal("mu", t).unwrap();
    let (mu_lo, mu_hi) = (enclose("1.0").inf(), enclose("1.6").sup());
    let omega = SetStatus::Nonempty {
        witness: phase([0.5, 0.6], [0.0, 1.0]),
    };
    let empty = rod_factor_tree(root, iv(mu_lo, 1.2));
    let undecided = SetStatus::Undecided {
        reason: "μ* = 4/3 lies in this box".into(),
    };
    let leaves = vec![
        ParamLeaf {
            bounds: vec![[mu_lo, 1.2]],
            sets: vec![omega.clone(), empty.clone(), empty],
        },
        ParamLeaf {
            bounds: vec![[1.2, 1.5]],
            sets: vec![omega.clone(), undecided.clone(), undecided],
        },
        ParamLeaf {
            bounds: vec![[1.5, mu_hi]],
            sets: vec![
                omega,
                SetStatus::Nonempty {
                    witness: phase([1.0, 1.01], [5.0, 5.1]),
                },
                SetStatus::Nonempty {
                    witness: phase([1.0, 1.01], [0.0, 0.1]),
                },
            ],
        },
    ];
    let atlas = ParamAtlas {
        axes: vec![ParamAxis {
            name: "mu".into(),
            lo: "1.0".into(),
            hi: "1.6".into(),
        }],
        sets: ROD_SETS.iter().map(|s| s.to_string()).collect(),
        tree: vec![
            ParamNode::Split { axis: 0, at: 1.2 },
            ParamNode::Leaf(0),
            ParamNode::Split { axis: 0, at: 1.5 },
            ParamNode::Leaf(1),
            ParamNode::Leaf(2),
        ],
        leaves,
    };
    (scene, params, atlas)
}

fn rod_proof(scene: &Scene, params: &ParamSet, atlas: &ParamAtlas) -> serde_json::Value {
    param_atlas_proof(
        &ParamAtlasStatement {
            scene,
            variant: Variant::Derived,
            params,
            title: "Painlevé's rod over mu".into(),
        },
        atlas,
    )
    .unwrap()
}

#[test]
fn the_rods_paradox_cells_are_proved_empty_by_the_factor_rule() {
    let (scene, params, atlas) = rod_atlas();
    let proof = rod_proof(&scene, &params, &atlas);
    // The author's text, with θ as t and θ̇ as w.
    let st = &proof["statement"];
    assert_eq!(st["constraints"][1]["expr"], "U/V");
    assert_eq!(st["definitions"][0][1], "l*sin(t)*w^2 - g");
    assert_eq!(st["parameters"]["mu"][1], "1.6");
    assert_valid(&proof);
    let out = detach_verify(&proof);
    assert!(out.contains("VALID"), "{out}");
}

/// Each mutant of the rod's atlas is INVALID while the atlas is VALID.
#[test]
fn wrong_parameter_atlas_evidence_is_invalid() {
    let (scene, params, atlas) = rod_atlas();
    assert_valid(&rod_proof(&scene, &params, &atlas));
    let mutant = |f: &dyn Fn(&mut ParamAtlas)| {
        let mut a = atlas.clone();
        f(&mut a);
        rod_proof(&scene, &params, &a)
    };

    // A witness moved off the set: at θ̇ ∈ [0, 0.1], U < 0, so not in Ω̄.
    let moved = mutant(&|a| {
        a.leaves[2].sets[1] = SetStatus::Nonempty {
            witness: phase([1.0, 1.01], [0.0, 0.1]),
        }
    });
    assert_invalid(&moved, "is not proved");

    // A reason that lies: "Ω is proved" on a slab where U > 0 at large θ̇.
    let lie = mutant(&|a| {
        if let SetStatus::Empty { reasons, .. } = &mut a.leaves[0].sets[1] {
            reasons[0] = EmptyReason::Literal { constraint: 0 };
        }
    });
    assert_invalid(&lie, "literal reason");

    // The factor rule the other way round: Ω = U is not U/V times a factor.
    let swapped = mutant(&|a| {
        if let SetStatus::Empty { reasons, .. } = &mut a.leaves[0].sets[2] {
            reasons[0] = EmptyReason::Factor {
                constraint: 0,
                other: 1,
                positive: true,
            };
        }
    });
    assert_invalid(&swapped, "not omega0 times or divided by a factor");

    // A negative factor does not contradict in Ω and out of Ω₀.
    let sign = mutant(&|a| {
        if let SetStatus::Empty { reasons, .. } = &mut a.leaves[0].sets[2] {
            reasons[0] = EmptyReason::Factor {
                constraint: 1,
                other: 0,
                positive: false,
            };
        }
    });
    assert_invalid(&sign, "does not contradict");

    // The factor rule where Ω₀ is not written in that form (the same
    // function, U/V − 0).
    let mut not_form = rod_proof(&scene, &params, &atlas);
    not_form["statement"]["constraints"][1]["expr"] = "U/V - 0".into();
    assert_invalid(&not_form, "is not omega times or divided by a factor");

    // The factor's sign not proved: the cells over μ ∈ [1.0, 1.6] with the
    // slabs that prove V > 0 for μ ≤ 1.2 only.
    let wide = mutant(&|a| {
        a.tree = vec![ParamNode::Leaf(0)];
        a.leaves[0].bounds = vec![[1.0, 1.6]];
    });
    assert_invalid(&wide, "is not proved positive");

    // A parameter leaf missing: the box μ ∈ [1.5, 1.6] has no leaf.
    let missing = mutant(&|a| {
        a.tree.pop();
    });
    assert_invalid(&missing, "before every box has its leaf");

    // A split outside the box: 1.7 is not inside (1.2, 1.6).
    let outside = mutant(&|a| a.tree[2] = ParamNode::Split { axis: 0, at: 1.7 });
    assert_invalid(&outside, "is not inside");

    // An emptiness tree from a phase box that misses part of the domain.
    let mut small = rod_proof(&scene, &params, &atlas);
    small["statement"]["phase_box"]["w"][0] = "-0x1p+3".into();
    assert_invalid(&small, "does not contain the domain");
}

/// The writer refuses an atlas that does not fit the scene.
#[test]
fn the_writer_refuses_an_atlas_that_does_not_fit() {
    let (scene, params, atlas) = rod_atlas();
    let statement = ParamAtlasStatement {
        scene: &scene,
        variant: Variant::Derived,
        params: &params,
        title: String::new(),
    };
    let mut a = atlas.clone();
    a.axes[0].name = "nu".into();
    assert!(param_atlas_proof(&statement, &a)
        .unwrap_err()
        .contains("not a parameter"));
    let mut a = atlas.clone();
    a.sets[0] = "omega1".into();
    assert!(param_atlas_proof(&statement, &a)
        .unwrap_err()
        .contains("unknown region `omega1`"));
    let mut a = atlas;
    a.leaves[0].sets.pop();
    assert!(param_atlas_proof(&statement, &a).is_err());
}

/// `pave --proof` of the rod at μ = 1.2, below μ* = 4/3 (V > 0 for every θ
/// when μ < 4/3: closed form in `scenes/painleve-rod.toml`), states both
/// paradox cells empty, inner = outer = 0, each with an emptiness tree;
/// both checkers accept it (`detach verify` and the checker crate). Without a tree, or with a tree whose one leaf
/// names a literal not refuted on the whole domain, the claimed 0 is
/// INVALID.
#[test]
fn a_paving_proof_states_the_rods_paradox_cells_empty_below_four_thirds() {
    let dir = std::env::temp_dir().join(format!("detach-pave-empty-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("rod.json");
    let out = crate::common::detach(&[
        "pave",
        "--scene",
        "painleve-rod",
        "--param",
        "mu=1.2",
        "--eps",
        "0.0625",
        "--proof",
        path.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let proof: serde_json::Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    let areas = proof["statement"]["areas"].as_array().unwrap().clone();
    let empty = proof["evidence"]["empty"].as_array().unwrap().clone();
    let index = |name: &str| areas.iter().position(|a| a["set"] == name).unwrap();
    for name in ["not_omega_and_omega0", "omega_and_not_omega0"] {
        let k = index(name);
        assert_eq!(
            (&areas[k]["inner"], &areas[k]["outer"]),
            (&"0".into(), &"0".into())
        );
        let tree = empty.iter().find(|e| e["area"] == k).unwrap();
        assert_eq!(tree["encoding"], "empty/1");
    }
    // Ω is not empty: no tree, and a positive inner bound.
    assert!(empty.iter().all(|e| e["area"] != index("omega")));
    // The exact checker: the paving's root box reaches the domain's end
    // π/2, which a looser checker encloses wider, whatever the cells.
    let exact = check_bytes(&to_bytes(&proof)).unwrap().verdict;
    assert_eq!(exact, Verdict::Valid);
    let out = detach_verify(&proof);
    assert!(out.contains("VALID"), "{out}");

    let mut no_tree = proof.clone();
    no_tree["evidence"]
        .as_object_mut()
        .unwrap()
        .shift_remove("empty");
    assert_invalid(&no_tree, "claimed outer 0 is below");
    // One leaf: Ω̄ ∩ Ω₀ asks Ω out, so the reason is "Ω proved in" on the
    // whole phase box, false (U > 0 at large θ̇).
    let mut lie = proof.clone();
    let k = empty
        .iter()
        .position(|e| e["area"] == index("not_omega_and_omega0"))
        .unwrap();
    lie["evidence"]["empty"][k]["nodes"] = 1.into();
    lie["evidence"]["empty"][k]["body"] = "AA==".into();
    assert_invalid(&lie, "literal reason: omega is not proved in");
}
