//! Paves a scene and draws its atlas picture to `out/atlas-example/`.
//!
//! `cargo run --release --example atlas_picture -- [scene] [printed|derived] [eps-exponent]`
//! e.g. `-- smooth-disc derived 10` paves with eps = 2^-10. With no scene,
//! every scene is drawn in the derived variant.

use detach::figures::{draw_atlas, plot_area_pixels, AtlasStyle, PictureInfo};
use detach::pave::{pave_scene, PaveOptions};
use detach::scene::{Scene, SceneId, Variant};
use std::path::Path;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let scenes: Vec<SceneId> = match args.first() {
        Some(s) => vec![s.parse()?],
        None => SceneId::ALL.to_vec(),
    };
    let variant = match args.get(1).map(String::as_str) {
        Some("printed") => Variant::Printed,
        _ => Variant::Derived,
    };
    let exp: i32 = args.get(2).map_or(Ok(10), |s| s.parse())?;
    let style = AtlasStyle::default();
    let (pw, ph) = plot_area_pixels(&style);
    println!("plot area {pw}×{ph} px, eps = 2^-{exp}");
    let out = Path::new("out/atlas-example");
    for id in scenes {
        let (scene, params) = Scene::build(id, &[])?;
        let t = Instant::now();
        let paving = pave_scene(
            &scene,
            variant,
            PaveOptions {
                eps: 2f64.powi(-exp),
                max_boxes: 4_000_000,
            },
            |_, _, _| {},
        )?;
        let paved = t.elapsed();
        let info = PictureInfo {
            scene: &scene,
            variant,
            params: params.texts(),
            complete: paving.complete,
            window: None,
        };
        let stem = format!("{}-{}", id.name(), variant);
        let (svg, png) = (
            out.join(format!("{stem}.svg")),
            out.join(format!("{stem}.png")),
        );
        let t = Instant::now();
        draw_atlas(&paving, &info, &style, &svg, &png)?;
        let drawn = t.elapsed();
        println!(
            "{stem}: {} leaves, paved in {:.2?}, drawn in {:.2?}; svg {} kB, png {} kB",
            paving.leaves.len(),
            paved,
            drawn,
            std::fs::metadata(&svg)?.len() / 1024,
            std::fs::metadata(&png)?.len() / 1024,
        );
    }
    Ok(())
}
