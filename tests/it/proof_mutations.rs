//! Mutation testing of the proof checker: real proof files are mutated, and
//! every mutation whose assertions are false by construction must be
//! rejected. Whether a mutation keeps its assertions true is decided by the
//! mutation class (or by the prover's own computation), never by the checker.
//!
//! Classes (must reject unless noted):
//! - label: a decided leaf label flipped in ↔ out (the original proves the box
//!   lies on the other side); decided → undecided keeps everything true;
//! - swap: two leaves' labels exchanged where some constraint has in and out;
//! - split: an explicit split point placed outside its box; the midpoint
//!   written explicitly keeps the tree identical (must pass);
//! - drop: one leaf removed from the tree;
//! - area: a claimed inner bound raised above the original outer bound, or an
//!   outer bound lowered below the original inner bound; widening keeps it true;
//! - sign / constant: a constraint `e` replaced by `-(e)` or `(e) + 1e6` while
//!   some leaf is labelled in (its enclosure, from the scene's code, is above −1e6);
//! - parameter: one digit of a parameter changed; false when the prover's own
//!   paving of the mutated scene contradicts a claimed bound, else undetermined;
//! - truncate: the file cut short (not JSON: unreadable);
//! - root: a unique root's claimed enclosure moved off the root; two roots'
//!   Newton pieces merged into one piece; κ₀'s claimed interval moved off √3/9;
//! - band: a cell's bounds moved wholly above its upper or below its lower bound.

use detach::certificate::band::critical_band_proof;
use detach::certificate::catalog::{roots_2_10, roots_2_9};
use detach::certificate::paving::{base64, encode_tree, stated_paving};
use detach::certificate::{kappa0_proof, paving_proof, to_bytes, PavingStatement};
use detach::check::{check_bytes, Verdict};
use detach::pave::{pave_scene_in, Label, Node, PaveOptions, Paving};
use detach::roots::isolate::RootEnclosure;
use detach::roots::prove_kappa0;
use detach::scene::{Scene, SceneId, Variant};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use serde_json::{json, Value};
use std::cell::Cell;

/// What construction says about a mutant.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Truth {
    False,
    True,
    Unknown,
}

#[derive(Default)]
struct Counts {
    tried: Cell<u64>,
    rejected: Cell<u64>,
    accepted_true: Cell<u64>,
    accepted_unknown: Cell<u64>,
    false_accepts: Cell<u64>,
}

impl Counts {
    fn record(&self, truth: Truth, bytes: &[u8]) -> Result<(), TestCaseError> {
        self.tried.set(self.tried.get() + 1);
        let accepted = matches!(check_bytes(bytes), Ok(r) if r.verdict == Verdict::Valid);
        match (accepted, truth) {
            (false, _) => self.rejected.set(self.rejected.get() + 1),
            (true, Truth::True) => self.accepted_true.set(self.accepted_true.get() + 1),
            (true, Truth::Unknown) => self.accepted_unknown.set(self.accepted_unknown.get() + 1),
            (true, Truth::False) => {
                self.false_accepts.set(self.false_accepts.get() + 1);
                return Err(TestCaseError::fail("a false mutant was accepted"));
            }
        }
        Ok(())
    }
    fn report(&self, what: &str) {
        eprintln!(
            "{what}: {} mutations, {} rejected, {} accepted and still true, {} accepted (truth undetermined), {} false accepts",
            self.tried.get(),
            self.rejected.get(),
            self.accepted_true.get(),
            self.accepted_unknown.get(),
            self.false_accepts.get()
        );
        assert_eq!(self.false_accepts.get(), 0);
    }
}

/// A small real paving: a window of a scene at a coarse resolution.
struct Base {
    scene: Scene,
    id: SceneId,
    variant: Variant,
    window: [[&'static str; 2]; 2],
    paving: Paving,
    proof: Value,
}

fn base(
    id: SceneId,
    variant: Variant,
    window: [[&'static str; 2]; 2],
    overrides: &[(&str, &str)],
) -> Base {
    let ov: Vec<(String, String)> = overrides
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    let (scene, params) = Scene::build(id, &ov).unwrap();
    let domain = scene
        .domain()
        .window(Some(window[0]), Some(window[1]))
        .unwrap();
    let opts = PaveOptions {
        eps: 1.0 / 32.0,
        max_boxes: 100_000,
    };
    let paving = pave_scene_in(&scene, variant, &domain, opts, |_, _, _| {}).unwrap();
    let proof = statement_of(&scene, &params, variant, window, &paving);
    // Mutants start from the paving the proof states (labels confirmed).
    let paving = stated_paving(
        &PavingStatement {
            scene: &scene,
            variant,
            params: &params,
            domain: &domain,
            domain_text: window.map(|s| s.map(String::from)),
            title: String::new(),
        },
        &paving,
    )
    .paving;
    Base {
        scene,
        id,
        variant,
        window,
        paving,
        proof,
    }
}

fn statement_of(
    scene: &Scene,
    params: &detach::number::param::ParamSet,
    variant: Variant,
    window: [[&str; 2]; 2],
    paving: &Paving,
) -> Value {
    let domain = scene
        .domain()
        .window(Some(window[0]), Some(window[1]))
        .unwrap();
    paving_proof(
        &PavingStatement {
            scene,
            variant,
            params,
            domain: &domain,
            domain_text: window.map(|s| s.map(String::from)),
            title: "test".into(),
        },
        paving,
    )
}

/// The base proof with the mutated paving's tree in place of its own: the
/// statement's claims are kept, and the tree is written as it is (not
/// through the proof writer, which would drop a label it cannot confirm).
fn with_tree(b: &Base, p: &Paving) -> Value {
    let mut v = b.proof.clone();
    v["statement"]["leaves"] = p.leaves.len().into();
    v["evidence"]["nodes"] = p.nodes.len().into();
    v["evidence"]["body"] = base64(&encode_tree(p)).into();
    v
}

fn leaf_positions(p: &Paving) -> Vec<usize> {
    p.nodes
        .iter()
        .enumerate()
        .filter_map(|(i, n)| matches!(n, Node::Leaf(_)).then_some(i))
        .collect()
}

fn bases() -> Vec<Base> {
    vec![
        base(
            SceneId::ViscousDisc,
            Variant::Derived,
            [["1", "2.5"], ["-10", "10"]],
            &[],
        ),
        base(
            SceneId::IceDisc,
            Variant::Printed,
            [["0.3", "2.9"], ["-6", "6"]],
            &[],
        ),
        base(
            SceneId::SmoothDisc,
            Variant::Derived,
            [["0.2", "1.5"], ["-10", "10"]],
            &[],
        ),
    ]
}

#[derive(Debug, Clone)]
enum PavingMutation {
    FlipDecided(usize, usize),
    Undecide(usize, usize),
    Swap(usize, usize),
    Drop(usize),
    RaiseInner(usize),
    LowerOuter(usize),
    Widen(usize),
    Negate(usize),
    Shift(usize),
    ParamDigit(usize, usize, u8),
    Truncate(usize),
}

fn paving_mutation() -> impl Strategy<Value = PavingMutation> {
    let i = any::<usize>();
    prop_oneof![
        (i, 0usize..2).prop_map(|(a, k)| PavingMutation::FlipDecided(a, k)),
        (i, 0usize..2).prop_map(|(a, k)| PavingMutation::Undecide(a, k)),
        (i, i).prop_map(|(a, b)| PavingMutation::Swap(a, b)),
        i.prop_map(PavingMutation::Drop),
        (0usize..6).prop_map(PavingMutation::RaiseInner),
        (0usize..6).prop_map(PavingMutation::LowerOuter),
        (0usize..6).prop_map(PavingMutation::Widen),
        (0usize..2).prop_map(PavingMutation::Negate),
        (0usize..2).prop_map(PavingMutation::Shift),
        (i, i, 0u8..10).prop_map(|(a, b, d)| PavingMutation::ParamDigit(a, b, d)),
        i.prop_map(PavingMutation::Truncate),
    ]
}

fn bytes_of(v: &Value) -> Vec<u8> {
    to_bytes(v)
}

/// `text` with its `j`-th digit (modulo the number of digits) set to `d`;
/// `None` when that changes nothing.
fn with_digit(text: &str, j: usize, d: u8) -> Option<String> {
    let digits: Vec<usize> = text
        .char_indices()
        .filter(|(_, c)| c.is_ascii_digit())
        .map(|(k, _)| k)
        .collect();
    let at = digits[j % digits.len()];
    let mut new = text.to_string();
    new.replace_range(at..at + 1, &d.to_string());
    (new != text).then_some(new)
}

fn flip(l: Label) -> Option<Label> {
    match l {
        Label::ProvedIn => Some(Label::ProvedOut),
        Label::ProvedOut => Some(Label::ProvedIn),
        _ => None,
    }
}

fn decimal_of(v: &Value) -> f64 {
    v.as_str().unwrap().parse().unwrap()
}

/// Applies a mutation; `None` when it does not apply to this paving.
fn mutate(b: &Base, m: &PavingMutation) -> Option<(Truth, Vec<u8>)> {
    let n = b.paving.leaves.len();
    let mut p = b.paving.clone();
    let out = match *m {
        PavingMutation::FlipDecided(i, k) => {
            let (i, l) = (0..n)
                .map(|j| (i + j) % n)
                .find_map(|j| flip(p.leaves[j].labels[k]).map(|l| (j, l)))?;
            p.leaves[i].labels[k] = l;
            (Truth::False, bytes_of(&with_tree(b, &p)))
        }
        PavingMutation::Undecide(i, k) => {
            let i = (0..n)
                .map(|j| (i + j) % n)
                .find(|&j| p.leaves[j].labels[k].is_decided())?;
            p.leaves[i].labels[k] = Label::Undecided;
            (Truth::True, bytes_of(&with_tree(b, &p)))
        }
        PavingMutation::Swap(i, j) => {
            let (i, j) = (i % n, j % n);
            let (a, c) = (p.leaves[i].labels, p.leaves[j].labels);
            if a == c {
                return None;
            }
            let opposite = (0..2).any(|k| flip(a[k]) == Some(c[k]));
            p.leaves[i].labels = c;
            p.leaves[j].labels = a;
            let truth = if opposite {
                Truth::False
            } else {
                Truth::Unknown
            };
            (truth, bytes_of(&with_tree(b, &p)))
        }
        PavingMutation::Drop(i) => {
            let pos = leaf_positions(&p);
            p.nodes.remove(pos[i % pos.len()]);
            // A binary tree missing a leaf no longer closes: structurally false.
            (Truth::False, bytes_of(&with_tree(b, &p)))
        }
        PavingMutation::RaiseInner(c)
        | PavingMutation::LowerOuter(c)
        | PavingMutation::Widen(c) => {
            let mut v = b.proof.clone();
            let a = &mut v["statement"]["areas"][c];
            let (inner, outer) = (decimal_of(&a["inner"]), decimal_of(&a["outer"]));
            let truth = match *m {
                PavingMutation::RaiseInner(_) => {
                    a["inner"] = json!(format!("{}", outer + 1e-6 * outer.abs().max(1.0)));
                    Truth::False
                }
                PavingMutation::LowerOuter(_) => {
                    if inner <= 0.0 {
                        return None;
                    }
                    a["outer"] = json!(format!("{}", inner * 0.999_999));
                    Truth::False
                }
                _ => {
                    a["outer"] = json!(format!("{}", outer * 1.5 + 1.0));
                    a["inner"] = json!(format!("{}", inner * 0.5));
                    Truth::True
                }
            };
            (truth, bytes_of(&v))
        }
        PavingMutation::Negate(k) | PavingMutation::Shift(k) => {
            // False as soon as one leaf is proved in: the original proves
            // e < 0 there, so −e > 0; and e > −1e6 there (checked below).
            let in_leaf = p.leaves.iter().any(|l| l.labels[k] == Label::ProvedIn);
            if !in_leaf {
                return None;
            }
            let mut v = b.proof.clone();
            let e = v["statement"]["constraints"][k]["expr"]
                .as_str()
                .unwrap()
                .to_string();
            let (new, truth) = if matches!(m, PavingMutation::Negate(_)) {
                (format!("-({e})"), Truth::False)
            } else {
                let bounded = p.leaves.iter().any(|l| {
                    l.labels[k] == Label::ProvedIn && {
                        let c = b.scene.constraints_on(b.variant, l.bx.theta_interval());
                        let w = inari::DecInterval::new(l.bx.theta_dot_interval());
                        let g = if k == 0 {
                            c.omega.eval(w)
                        } else {
                            c.omega0.eval(w)
                        };
                        g.interval().is_some_and(|x| x.inf() > -1e6)
                    }
                });
                (
                    format!("({e}) + 1000000"),
                    if bounded {
                        Truth::False
                    } else {
                        Truth::Unknown
                    },
                )
            };
            v["statement"]["constraints"][k]["expr"] = json!(new);
            (truth, bytes_of(&v))
        }
        PavingMutation::ParamDigit(i, j, d) => {
            let mut v = b.proof.clone();
            let params = v["statement"]["parameters"].as_object_mut().unwrap();
            let keys: Vec<String> = params.keys().cloned().collect();
            let key = &keys[i % keys.len()];
            let new = with_digit(params[key].as_str().unwrap(), j, d)?;
            params.insert(key.clone(), json!(new));
            // The judge: the prover's own paving of the mutated scene.
            let truth = match Scene::build(b.id, &[(key.clone(), new.clone())]) {
                Err(_) => Truth::Unknown,
                Ok((scene, _)) => {
                    let domain = scene
                        .domain()
                        .window(Some(b.window[0]), Some(b.window[1]))
                        .unwrap();
                    let opts = PaveOptions {
                        eps: 1.0 / 64.0,
                        max_boxes: 100_000,
                    };
                    let q = pave_scene_in(&scene, b.variant, &domain, opts, |_, _, _| {}).unwrap();
                    let cells = detach::pave::standard_cells();
                    let contradicted = v["statement"]["areas"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .enumerate()
                        .any(|(c, a)| {
                            let ab = q.area_bounds(&cells[c], domain.uncovered_area_sup());
                            decimal_of(&a["inner"]) > ab.outer_area
                                || decimal_of(&a["outer"]) < ab.inner_area
                        });
                    if contradicted {
                        Truth::False
                    } else {
                        Truth::Unknown
                    }
                }
            };
            (truth, bytes_of(&v))
        }
        PavingMutation::Truncate(i) => {
            let full = bytes_of(&b.proof);
            let cut = i % (full.len() - 2);
            (Truth::False, full[..cut].to_vec())
        }
    };
    Some(out)
}

#[test]
fn paving_mutants_are_rejected_when_false() {
    let bases = bases();
    for b in &bases {
        assert_eq!(
            check_bytes(&bytes_of(&b.proof)).unwrap().verdict,
            Verdict::Valid
        );
    }
    let counts = Counts::default();
    let mut runner = TestRunner::new(Config::with_cases(7_000));
    runner
        .run(&(0usize..bases.len(), paving_mutation()), |(bi, m)| {
            if let Some((truth, bytes)) = mutate(&bases[bi], &m) {
                counts.record(truth, &bytes)?;
            }
            Ok(())
        })
        .unwrap();
    counts.report("paving");
    assert!(counts.tried.get() >= 6_000);
}

#[derive(Debug, Clone)]
enum RootMutation {
    MoveRoot(usize),
    MergeNewton,
    WidenClaim(usize),
    KappaDigit(usize, u8),
    Kappa0Off,
    Kappa0Wider,
    BandLowerAboveUpper(usize),
    BandUpperBelowLower(usize),
    BandWiden(usize),
    FlipPieceKind(usize),
    Truncate(usize),
}

fn root_mutation() -> impl Strategy<Value = RootMutation> {
    let i = any::<usize>();
    prop_oneof![
        i.prop_map(RootMutation::MoveRoot),
        Just(RootMutation::MergeNewton),
        i.prop_map(RootMutation::WidenClaim),
        (i, 0u8..10).prop_map(|(a, d)| RootMutation::KappaDigit(a, d)),
        Just(RootMutation::Kappa0Off),
        Just(RootMutation::Kappa0Wider),
        any::<usize>().prop_map(RootMutation::BandLowerAboveUpper),
        any::<usize>().prop_map(RootMutation::BandUpperBelowLower),
        any::<usize>().prop_map(RootMutation::BandWiden),
        i.prop_map(RootMutation::FlipPieceKind),
        i.prop_map(RootMutation::Truncate),
    ]
}

fn mutate_roots(
    r29: &Value,
    k0: &Value,
    band: &Value,
    m: &RootMutation,
) -> Option<(Truth, Vec<u8>)> {
    let mut v = r29.clone();
    let roots_len = v["statement"]["roots"].as_array().unwrap().len();
    Some(match *m {
        RootMutation::MoveRoot(i) => {
            let r = &mut v["statement"]["roots"][i % roots_len];
            let (lo, hi) = (decimal_of(&r["lo"]), decimal_of(&r["hi"]));
            let w = (hi - lo).max(1e-12);
            // The original proves exactly one root in [lo, hi]; the shifted
            // interval lies in the root-free rest of the Newton box or beyond.
            r["lo"] = json!(format!("{:e}", hi + 4.0 * w));
            r["hi"] = json!(format!("{:e}", hi + 5.0 * w));
            (Truth::False, bytes_of(&v))
        }
        RootMutation::MergeNewton => {
            // One "newton" piece over both roots: it would claim one root where there are two.
            let pieces = v["evidence"]["pieces"].as_array().unwrap().clone();
            let idx: Vec<usize> = pieces
                .iter()
                .enumerate()
                .filter(|(_, p)| p["kind"] == "newton")
                .map(|(i, _)| i)
                .collect();
            let (a, c) = (idx[0], idx[1]);
            let mut merged = pieces[a].clone();
            merged["hi"] = pieces[c]["hi"].clone();
            let mut new: Vec<Value> = pieces[..a].to_vec();
            new.push(merged);
            new.extend_from_slice(&pieces[c + 1..]);
            v["evidence"]["pieces"] = json!(new);
            (Truth::False, bytes_of(&v))
        }
        RootMutation::WidenClaim(i) => {
            let r = &mut v["statement"]["roots"][i % roots_len];
            let (lo, hi) = (decimal_of(&r["lo"]), decimal_of(&r["hi"]));
            r["lo"] = json!(format!("{:e}", lo - (hi - lo)));
            // Still exactly one root inside (the evidence may not show it).
            (Truth::Unknown, bytes_of(&v))
        }
        RootMutation::KappaDigit(j, d) => {
            let new = with_digit(
                v["statement"]["parameters"]["kappa"].as_str().unwrap(),
                j,
                d,
            )?;
            v["statement"]["parameters"]["kappa"] = json!(new);
            // The judge: the prover's roots at the new κ, compared with the claimed enclosures.
            let truth = match roots_2_9(&new, "0.7") {
                Err(_) => Truth::Unknown,
                Ok(p) => {
                    let claimed = &r29["statement"]["roots"];
                    let fresh = &p["statement"]["roots"];
                    let disjoint_from_all = |c: &Value| {
                        fresh.as_array().unwrap().iter().all(|f| {
                            decimal_of(&f["hi"]) < decimal_of(&c["lo"])
                                || decimal_of(&c["hi"]) < decimal_of(&f["lo"])
                        })
                    };
                    if p["statement"]["complete"] == true
                        && claimed.as_array().unwrap().iter().any(disjoint_from_all)
                    {
                        Truth::False
                    } else {
                        Truth::Unknown
                    }
                }
            };
            (truth, bytes_of(&v))
        }
        RootMutation::Kappa0Off => {
            let mut k = k0.clone();
            k["statement"]["kappa0"] = json!({ "lo": "0.19", "hi": "0.1924" });
            (Truth::False, bytes_of(&k))
        }
        RootMutation::Kappa0Wider => {
            let mut k = k0.clone();
            k["statement"]["kappa0"] = json!({ "lo": "0.19", "hi": "0.2" });
            (Truth::True, bytes_of(&k))
        }
        RootMutation::BandLowerAboveUpper(i)
        | RootMutation::BandUpperBelowLower(i)
        | RootMutation::BandWiden(i) => {
            // The original proves lower₀ ≤ κ_crit(α) ≤ upper₀ on the box:
            // "≥ 2 roots for κ ≤ upper₀·1.01" and "none for κ ≥ lower₀·0.99"
            // are false at κ_crit (κ_crit(α) > 0 where lower₀ > 0).
            let mut b = band.clone();
            let cells = b["statement"]["cells"].as_array_mut().unwrap();
            let n = cells.len();
            let c = &mut cells[i % n];
            let (lo, hi) = (decimal_of(&c["lower"]), decimal_of(&c["upper"]));
            let truth = match m {
                RootMutation::BandLowerAboveUpper(_) => {
                    c["lower"] = json!(format!("{:e}", hi * 1.01));
                    c["upper"] = json!(format!("{:e}", hi * 1.02));
                    Truth::False
                }
                RootMutation::BandUpperBelowLower(_) => {
                    if lo <= 0.0 {
                        return None;
                    }
                    c["upper"] = json!(format!("{:e}", lo * 0.99));
                    c["lower"] = json!(format!("{:e}", lo * 0.98));
                    Truth::False
                }
                _ => {
                    c["lower"] = json!(format!("{:e}", lo * 0.5));
                    c["upper"] = json!(format!("{:e}", hi * 2.0));
                    Truth::True
                }
            };
            (truth, bytes_of(&b))
        }
        RootMutation::FlipPieceKind(i) => {
            let pieces = v["evidence"]["pieces"].as_array_mut().unwrap();
            let n = pieces.len();
            let p = &mut pieces[i % n];
            if p["kind"] != "newton" {
                return None;
            }
            // A piece holding a root declared root-free: false.
            p["kind"] = json!("exclude");
            (Truth::False, bytes_of(&v))
        }
        RootMutation::Truncate(i) => {
            let full = bytes_of(r29);
            (Truth::False, full[..i % (full.len() - 2)].to_vec())
        }
    })
}

#[test]
fn root_mutants_are_rejected_when_false() {
    let r29 = roots_2_9("0.05", "0.7").unwrap();
    let r210 = roots_2_10("0.1").unwrap();
    let k0 = kappa0_proof(&RootEnclosure::unique(prove_kappa0().mu_star.interval()));
    let band = critical_band_proof(8);
    for v in [&r29, &r210, &k0, &band] {
        assert_eq!(check_bytes(&bytes_of(v)).unwrap().verdict, Verdict::Valid);
    }
    let counts = Counts::default();
    let mut runner = TestRunner::new(Config::with_cases(4_000));
    runner
        .run(&root_mutation(), |m| {
            if let Some((truth, bytes)) = mutate_roots(&r29, &k0, &band, &m) {
                counts.record(truth, &bytes)?;
            }
            Ok(())
        })
        .unwrap();
    counts.report("roots, kappa0 and critical band");
    assert!(counts.tried.get() >= 3_000);
}
