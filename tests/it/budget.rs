//! The leaf budget (`--max-boxes`): a smaller ε never gives a worse result
//! than a larger one under the same budget, a stopped run says what the
//! asked ε needs, and the ice-disc run at ε = 1e-6 that once returned
//! Ω undecided 17.99 beats the default ε in bounded memory.

use crate::common::{detach, json};
use detach::pave::{pave_scene_method, standard_cells, Method, MethodOptions, PaveOptions};
use detach::scene::{Scene, SceneId, Variant};

/// The paper's scenes and the Painlevé rod (a scene file).
fn scenes() -> Vec<(String, Scene, Variant)> {
    let mut out: Vec<_> = [
        (SceneId::IceDisc, Variant::Derived),
        (SceneId::ViscousDisc, Variant::Printed),
        (SceneId::SmoothDisc, Variant::Derived),
    ]
    .into_iter()
    .map(|(id, v)| (format!("{id:?} {v}"), Scene::default_of(id), v))
    .collect();
    let rod = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/painleve-rod.toml");
    let rod = Scene::from_file(std::path::Path::new(rod), &[]).unwrap().0;
    out.push(("painleve-rod".into(), rod, Variant::Derived));
    out
}

/// Undecided areas of the six regions and cells (outer − inner, rounded
/// up), paving for `target` (an index into `standard_cells`; `None`: every
/// constraint).
fn undecided(
    scene: &Scene,
    v: Variant,
    m: Method,
    target: Option<usize>,
    eps: f64,
    max_boxes: usize,
) -> [f64; 6] {
    let domain = scene.domain();
    let opts = PaveOptions { eps, max_boxes };
    let cells = standard_cells();
    let mo = match target {
        Some(i) => MethodOptions::for_cell(m, &cells[i]),
        None => MethodOptions::new(m),
    };
    let p = pave_scene_method(scene, v, &domain, opts, &mo, |_, _, _| {}).unwrap();
    assert!(p.leaves.len() <= max_boxes);
    let u = domain.uncovered_area_sup();
    cells.map(|c| p.area_bounds(&c, u).undecided_area())
}

/// Every method, on every paper scene and the rod, for both regions, a
/// cell and all constraints at once: under one budget a smaller ε never
/// leaves more undecided area. (A stopped run returns the complete paving
/// at the finest power of two above ε that fits; `natural`, `centred` and
/// `contract` refine a coarser paving, `slices` improves as ε halves.)
fn a_smaller_eps_is_never_worse(m: Method) {
    // From a budget that stops the coarsest ε to one none but 1e-5 reach.
    let ladder = [1.0 / 16.0, 1.0 / 64.0, 1.0 / 256.0, 1.0 / 1024.0, 1e-5];
    // Ω alone, Ω₀ alone, the cell Ω ∩ Ω₀, every constraint.
    let targets = [Some(0), Some(1), Some(2), None];
    for (name, scene, v) in scenes() {
        for max in [300, 3_000, 30_000] {
            for target in targets {
                let runs: Vec<[f64; 6]> = ladder
                    .iter()
                    .map(|&e| undecided(&scene, v, m, target, e, max))
                    .collect();
                let compared = match target {
                    Some(i) => i..i + 1,
                    None => 0..6,
                };
                for (k, w) in runs.windows(2).enumerate() {
                    for i in compared.clone() {
                        let (fine, coarse) = (w[1][i], w[0][i]);
                        // (equal trees sum their leaves alike: no slack)
                        assert!(
                            fine <= coarse,
                            "{m} {name} max {max}, target {target:?}, cell {i}: eps {} gives \
                             {fine} but eps {} gives {coarse}",
                            ladder[k + 1],
                            ladder[k],
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn a_smaller_eps_is_never_worse_under_the_same_budget_natural() {
    a_smaller_eps_is_never_worse(Method::Natural);
}

#[test]
fn a_smaller_eps_is_never_worse_under_the_same_budget_centred() {
    a_smaller_eps_is_never_worse(Method::Centred);
}

#[test]
fn a_smaller_eps_is_never_worse_under_the_same_budget_contract() {
    a_smaller_eps_is_never_worse(Method::Contract);
}

#[test]
fn a_smaller_eps_is_never_worse_under_the_same_budget_slices() {
    a_smaller_eps_is_never_worse(Method::Slices);
}

#[test]
fn a_budget_stop_says_what_eps_needs_and_which_option_sets_it() {
    let scene = Scene::default_of(SceneId::IceDisc);
    let run = |eps, max_boxes| {
        let opts = PaveOptions { eps, max_boxes };
        let mo = MethodOptions::new(Method::Natural);
        pave_scene_method(
            &scene,
            Variant::Derived,
            &scene.domain(),
            opts,
            &mo,
            |_, _, _| {},
        )
        .unwrap()
    };
    let full = run(1.0 / 256.0, 1_000_000);
    assert!(full.complete && full.budget.is_none());
    let cut = run(1.0 / 256.0, 2_000);
    let b = cut.budget.expect("stopped by the budget");
    assert_eq!((b.option, b.max_boxes), ("max_boxes", 2_000));
    // The lower bound holds: the complete paving has at least that many.
    assert!(b.leaves_needed_at_least > 2_000);
    assert!(b.leaves_needed_at_least <= full.leaves.len());
    assert!(b.leaves_needed_estimate >= b.leaves_needed_at_least as f64);
    // What is returned: the complete paving at the finest power of two
    // above ε that fits, leaf for leaf; the next finer one does not fit.
    let at = b.complete_at_eps.expect("a power of two fits");
    assert!(at > 1.0 / 256.0 && at.log2().fract() == 0.0, "{at}");
    let whole = run(at, 2_000);
    assert!(whole.complete);
    assert_eq!(whole.leaves, cut.leaves);
    assert!(at / 2.0 == 1.0 / 256.0 || !run(at / 2.0, 2_000).complete);

    let v = json(&[
        "pave",
        "--scene",
        "ice-disc",
        "--max-boxes",
        "100",
        "--json",
    ]);
    let s = &v["stop_reason"];
    assert_eq!(s["reason"], "budget");
    assert_eq!(s["option"], "--max-boxes");
    assert_eq!(s["max_boxes"], 100);
    assert!(s["leaves_needed_at_least"].as_u64().unwrap() > 100);
    assert!(s["leaves_needed_estimate"].as_f64().unwrap() > 100.0);
    assert!(s["complete_at_eps"].as_f64().unwrap() > 1.0 / 1024.0);
    let v = json(&["pave", "--scene", "ice-disc", "--eps", "0.05", "--json"]);
    assert_eq!(v["stop_reason"]["reason"], "resolution");
    assert!(v["stop_reason"].get("option").is_none());
    let out = detach(&["pave", "--scene", "ice-disc", "--max-boxes", "100"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("--max-boxes 100 stopped refinement; eps 9.765625e-4 needs at least"),
        "{text}"
    );
    assert!(
        text.contains("the result is the complete paving at eps "),
        "{text}"
    );
}

/// Peak resident memory allowed for the default budget of 4 000 000
/// leaves: 400 bytes per leaf (the engine's own accounting says about 360
/// at most, `peak_bytes_per_leaf`).
const PEAK_KB: u64 = 4_000_000 * 400 / 1024;

#[test]
fn ice_disc_at_eps_1e_6_beats_the_default_eps_in_bounded_memory() {
    let default = json(&["pave", "--scene", "ice-disc", "--json"]);
    // Ω undecided 0.029675 at the default ε (17 642 leaves, no budget hit).
    let omega = |v: &serde_json::Value| v["regions"][0]["undecided_area"].as_f64().unwrap();
    assert_eq!(default["stop"], "resolution");
    // The fine run with its memory capped (RLIMIT_DATA: an allocation past
    // it fails and the run aborts) and its peak read from /proc.
    let child = std::process::Command::new("sh")
        .args([
            "-c",
            &format!(
                "ulimit -d {}; exec \"$0\" pave --scene ice-disc --eps 1e-6 --json",
                PEAK_KB + 200_000
            ),
            env!("CARGO_BIN_EXE_detach"),
        ])
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let status = format!("/proc/{}/status", child.id());
    let mut peak_kb = 0u64;
    let reader = std::thread::spawn(move || child.wait_with_output().unwrap());
    while !reader.is_finished() {
        if let Ok(s) = std::fs::read_to_string(&status) {
            if let Some(kb) = s
                .lines()
                .find_map(|l| l.strip_prefix("VmHWM:"))
                .and_then(|t| t.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
            {
                peak_kb = peak_kb.max(kb);
            }
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let out = reader.join().unwrap();
    assert!(out.status.success(), "{:?}", out.status);
    let fine: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(fine["stop"], "budget");
    assert!(
        omega(&fine) <= omega(&default),
        "{} > {}",
        omega(&fine),
        omega(&default)
    );
    for r in 0..6 {
        let u = |v: &serde_json::Value| v["regions"][r]["undecided_area"].as_f64().unwrap();
        assert!(u(&fine) <= u(&default), "region {r}");
    }
    assert!(peak_kb <= PEAK_KB, "peak {peak_kb} kB");
}

/// The budget and an interruption are heeded between levels, so no level
/// may grow without bound: on the rod at ε = 2⁻³⁰ (far too fine to finish),
/// interrupted once a level passes 2²¹ open boxes, each level holds at
/// most twice the boxes of the one before or 2²⁰ (`slices` divides a
/// fresh slab several levels down before interval work only while the
/// level stays small), and the run stops there with a valid paving.
#[test]
fn a_level_stays_bounded_at_a_resolution_never_reached() {
    let (_, rod, v) = scenes().pop().unwrap();
    let domain = rod.domain();
    let opts = PaveOptions {
        eps: 2f64.powi(-30),
        max_boxes: 20_000_000,
    };
    let mo = MethodOptions::for_cell(Method::Slices, &standard_cells()[0]);
    let mut levels: Vec<usize> = Vec::new();
    let p = pave_scene_method(&rod, v, &domain, opts, &mo, |_, open, _| {
        // Checked as each level starts, before it is visited.
        if let Some(&before) = levels.last() {
            assert!(open <= (2 * before).max(1 << 20), "{levels:?} then {open}");
        }
        levels.push(open);
        if open > 1 << 21 {
            std::ops::ControlFlow::Break(())
        } else {
            std::ops::ControlFlow::Continue(())
        }
    })
    .unwrap();
    assert_eq!(p.stop, detach::pave::StopReason::Interrupted);
    assert!(*levels.last().unwrap() > 1 << 21, "{levels:?}");
}
