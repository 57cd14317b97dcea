//! Parameter atlases: the uniform rod's threshold μ* = 4/3 to 1e-9
//! relative, and 2-D atlases at 1/256 of each axis (the ladder with a
//! painter over (μ, r), Example 1's disc over (b, μ)).

#[path = "support/timing.rs"]
mod timing;

use detach::params::model::{ParamAxis, SetStatus};
use detach::params::{search, DecideOptions, Family, SearchOptions, Source};
use detach::scene::Cell;
use detach::scene::{SceneText, Variant};
use timing::Group;

const PARADOXES: [Cell; 2] = [Cell::Omega0NotOmega, Cell::OmegaNotOmega0];

fn axis(name: &str, lo: &str, hi: &str) -> ParamAxis {
    ParamAxis {
        name: name.into(),
        lo: lo.into(),
        hi: hi.into(),
    }
}

fn run(f: &Family, cells: &[Cell], eps: f64) -> detach::params::AtlasRun {
    let opts = SearchOptions {
        eps,
        max_boxes: 1_000_000,
        decide: DecideOptions::default(),
        shard: None,
    };
    search(f, cells, &opts, |_, _, _| {}).unwrap()
}

/// The share of the parameter box where some set is undecided.
fn undecided_share(f: &Family, r: &detach::params::AtlasRun) -> f64 {
    let w: Vec<f64> = f.root.iter().map(|r| r[1] - r[0]).collect();
    r.atlas
        .leaves
        .iter()
        .filter(|l| {
            l.sets
                .iter()
                .any(|s| matches!(s, SetStatus::Undecided { .. }))
        })
        .map(|l| {
            l.bounds
                .iter()
                .zip(&w)
                .map(|(b, w)| (b[1] - b[0]) / w)
                .product::<f64>()
        })
        .sum()
}

fn main() {
    let group = Group::new("params").samples(3);
    let rod = Family::new(
        Source::by_name("painleve-rod").unwrap(),
        Variant::Derived,
        Vec::new(),
        vec![axis("mu", "1", "2")],
    )
    .unwrap();
    group.bench("rod_threshold_1e-9", || {
        run(&rod, &PARADOXES, 2f64.powi(-34))
    });
    let ladder = Family::new(
        Source::File(
            SceneText::read(std::path::Path::new(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/tests/data/ladder.toml"
            )))
            .unwrap(),
        ),
        Variant::Derived,
        Vec::new(),
        vec![axis("mu", "0.5", "4"), axis("r", "0.5", "4")],
    )
    .unwrap();
    let disc = Family::new(
        Source::by_name("viscous-disc").unwrap(),
        Variant::Derived,
        Vec::new(),
        vec![axis("b", "0", "0.9"), axis("mu", "0.25", "2")],
    )
    .unwrap();
    for (name, f, cells) in [
        ("ladder_mu_r_256", &ladder, &PARADOXES[..]),
        ("viscous_disc_b_mu_256", &disc, &PARADOXES[..]),
    ] {
        if !group.wants(name) {
            continue;
        }
        let r = run(f, cells, 1.0 / 256.0);
        println!(
            "params/{name}: {} boxes, undecided share {:.4} %",
            r.atlas.leaves.len(),
            100.0 * undecided_share(f, &r)
        );
        group.bench(name, || run(f, cells, 1.0 / 256.0));
    }
}
