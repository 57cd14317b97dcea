//! Paves the disc on ice (§3) with c₀ = 1 and p_ψ = 1.5, by default with the
//! `slices` method, and prints certified bounds on the area of Ω₀ and of the
//! non-uniqueness cell Ω̄∩Ω₀.
//!
//! `cargo run --release -- [METHOD]`, METHOD one of natural, centred,
//! contract, slices (default slices).

use detach::pave::{pave_scene_method, Method, MethodOptions, PaveOptions};
use detach::scene::{Cell, Scene, SceneId, Variant};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let method: Method = match std::env::args().nth(1) {
        Some(name) => name.parse()?,
        None => Method::Slices,
    };
    // Parameters are decimal text, enclosed exactly.
    let overrides = [
        ("c0".to_string(), "1".to_string()),
        ("p_psi".to_string(), "1.5".to_string()),
    ];
    let (scene, _params) = Scene::build(SceneId::IceDisc, &overrides)?;
    let domain = scene.domain();
    let opts = PaveOptions {
        eps: 1.0 / 256.0,
        max_boxes: 1_000_000,
    };
    // Refine for both constraints, Ω and Ω₀: the cell Ω̄∩Ω₀ uses both.
    let paving = pave_scene_method(
        &scene,
        Variant::Derived,
        &domain,
        opts,
        &MethodOptions::new(method),
        |_level, _open, _leaves| {},
    )?;
    println!(
        "ice-disc, c0 = 1, p_psi = 1.5, method {method}: {} leaves, stopped: {}",
        paving.leaves.len(),
        paving.stop
    );
    for cell in [Cell::Omega0, Cell::Omega0NotOmega] {
        let label = cell.label();
        let a = paving.area_bounds(&cell.spec(), domain.uncovered_area_sup());
        println!(
            "  area of {label} ∈ [{}, {}] ({} leaves proved inside)",
            a.inner_area, a.outer_area, a.inner_boxes
        );
    }
    Ok(())
}
