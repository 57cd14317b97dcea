//! The leaf budget (`--max-boxes`): a smaller ε never gives a worse result
//! than a larger one under the same budget, a stopped run says what the
//! asked ε needs, and the ice-disc run at ε = 1e-6 that once returned
//! Ω undecided 17.99 beats the default ε in bounded memory.

use crate::common::{detach, json};
use detach::pave::{pave_scene_method, standard_cells, Method, MethodOptions, PaveOptions};
use detach::scene::{Scene, SceneId, Variant};

/// Undecided areas of Ω and Ω₀ (outer − inner, rounded up).
fn undecided(id: SceneId, v: Variant, m: Method, eps: f64, max_boxes: usize) -> [f64; 2] {
    let scene = Scene::default_of(id);
    let domain = scene.domain();
    let opts = PaveOptions { eps, max_boxes };
    let p = pave_scene_method(
        &scene,
        v,
        &domain,
        opts,
        &MethodOptions::new(m),
        |_, _, _| {},
    )
    .unwrap();
    assert!(p.leaves.len() <= max_boxes);
    let cells = standard_cells();
    let u = domain.uncovered_area_sup();
    [0, 1].map(|i| p.area_bounds(&cells[i], u).undecided_area())
}

/// `natural` and `centred` refine the same boxes at a level whatever ε
/// until a box reaches the coarser ε's resolution, so a finer ε only adds
/// refinements. (`contract` and `slices` are not covered: their
/// contraction and slab steering differ with ε, and on this grid a finer
/// ε is up to 0.3 % (`contract`) and 4× (`slices`, small budgets) worse.)
#[test]
fn a_smaller_eps_is_never_worse_under_the_same_budget() {
    // From a budget that stops the coarsest ε to one none of them reach.
    let ladder = [1.0 / 16.0, 1.0 / 64.0, 1.0 / 256.0, 1.0 / 1024.0, 1e-5];
    let scenes = [
        (SceneId::IceDisc, Variant::Derived),
        (SceneId::ViscousDisc, Variant::Printed),
        (SceneId::SmoothDisc, Variant::Derived),
    ];
    for m in [Method::Natural, Method::Centred] {
        for (id, v) in scenes {
            for max in [300, 3_000, 30_000] {
                let runs: Vec<[f64; 2]> = ladder
                    .iter()
                    .map(|&e| undecided(id, v, m, e, max))
                    .collect();
                for (k, w) in runs.windows(2).enumerate() {
                    for (i, (fine, coarse)) in w[1].iter().zip(w[0]).enumerate() {
                        // (equal trees sum their leaves alike: no slack)
                        assert!(
                            *fine <= coarse,
                            "{m} {id:?} {v} max {max}, constraint {i}: eps {} gives {fine} \
                             but eps {} gives {coarse}",
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
    assert_eq!((b.option, b.max_boxes), ("--max-boxes", 2_000));
    // The lower bound holds: the complete paving has at least that many.
    assert!(b.leaves_needed_at_least > 2_000);
    assert!(b.leaves_needed_at_least <= full.leaves.len());
    assert!(b.leaves_needed_estimate >= b.leaves_needed_at_least as f64);

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
    let v = json(&["pave", "--scene", "ice-disc", "--eps", "0.05", "--json"]);
    assert_eq!(v["stop_reason"]["reason"], "resolution");
    assert!(v["stop_reason"].get("option").is_none());
    let out = detach(&["pave", "--scene", "ice-disc", "--max-boxes", "100"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("--max-boxes 100 stopped refinement; eps 9.765625e-4 needs at least"),
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
