//! A reach paving drawn: each box of initial states filled by what its
//! motion is proved to do within T — reach the target, avoid it — or grey
//! where neither is proved.

use super::params::{box_plane, class_colour};
use super::{draw_err, write_figure, Area, FigureError};
use crate::motion::reach::{Fate, ReachRun};
use plotters::prelude::*;
use std::path::Path;

const SIZE: (u32, u32) = (1000, 860);
const INK: RGBColor = RGBColor(0x22, 0x22, 0x22);

/// The fill of a fate: the parameter plane's first set colour for a box
/// proved to reach, its "none" fill for one proved to avoid, its grey for
/// an undecided one (the same three meanings: proved yes, proved no, open).
fn colour(fate: &Fate) -> RGBColor {
    match fate {
        Fate::Reaches(_) => class_colour(Some(1)),
        Fate::Avoids => class_colour(Some(0)),
        Fate::Undecided(_) => class_colour(None),
    }
}

/// What a picture of a reach paving says in its header.
pub struct ReachCaption<'a> {
    /// The scene's name.
    pub scene: &'a str,
    /// The target as asked for (`V=0`, `cell`, …).
    pub target: &'a str,
    /// The time, as asked for.
    pub t: &'a str,
}

/// Draws the paving to `path` (`.svg` or `.png`).
pub fn write_reach_plane(
    run: &ReachRun,
    caption: &ReachCaption,
    path: &Path,
) -> Result<(), String> {
    write_figure(path, SIZE, |root| render(root, run, caption)).map_err(|e| e.to_string())
}

fn render(root: &Area, run: &ReachRun, caption: &ReachCaption) -> Result<(), FigureError> {
    root.fill(&WHITE).map_err(draw_err)?;
    let (inner, outer) = run.area_bounds();
    let title = format!(
        "{}: initial states reaching `{}` within t = {} (certified)",
        caption.scene, caption.target, caption.t
    );
    let bold = ("sans-serif", 24).into_font().style(FontStyle::Bold);
    root.draw_text(&title, &bold.color(&INK), (16, 10))
        .map_err(draw_err)?;
    let small = ("sans-serif", 17).into_font();
    let coarser = if run.complete {
        ""
    } else {
        " — the box budget ended the paving: coarser"
    };
    let area = format!("area of the reaching states in [{inner:.6}, {outer:.6}]{coarser}");
    root.draw_text(&area, &small.color(&INK), (16, 42))
        .map_err(draw_err)?;
    let legend = [
        (Fate::Reaches(inari::Interval::EMPTY), "proved to reach it"),
        (Fate::Avoids, "proved to avoid it"),
        (Fate::Undecided(String::new()), "undecided"),
    ];
    for (k, (fate, text)) in legend.iter().enumerate() {
        let (cx, cy) = (16 + 320 * k as i32, 70);
        for style in [colour(fate).filled(), INK.stroke_width(1)] {
            root.draw(&Rectangle::new([(cx, cy), (cx + 20, cy + 16)], style))
                .map_err(draw_err)?;
        }
        root.draw_text(text, &small.color(&INK), (cx + 28, cy - 1))
            .map_err(draw_err)?;
    }
    let header = 100;
    let (w, h) = root.dim_in_pixel();
    let body = root.clone().shrink((0, header), (w, h - header));
    let mut chart = box_plane(&body, run.window, ["θ", "θ̇"])?;
    let rects = run.leaves.iter().map(|l| {
        Rectangle::new(
            [(l.theta[0], l.theta_dot[1]), (l.theta[1], l.theta_dot[0])],
            colour(&l.fate).filled(),
        )
    });
    chart.draw_series(rects).map_err(draw_err)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figures::render_rgb;

    #[test]
    fn each_fate_fills_its_boxes_with_its_colour() {
        // Three boxes side by side, one of each fate: the pixel at each
        // box's centre has that fate's colour, so a swapped colour fails.
        let leaf = |lo: f64, fate| crate::motion::reach::ReachLeaf {
            theta: [lo, lo + 1.0],
            theta_dot: [0.0, 1.0],
            fate,
        };
        let run = ReachRun {
            window: [[0.0, 3.0], [0.0, 1.0]],
            leaves: vec![
                leaf(0.0, Fate::Reaches(inari::Interval::EMPTY)),
                leaf(1.0, Fate::Avoids),
                leaf(2.0, Fate::Undecided("x".into())),
            ],
            complete: true,
        };
        let caption = ReachCaption {
            scene: "test",
            target: "U=0",
            t: "1",
        };
        let rgb = render_rgb(SIZE, |root| render(root, &run, &caption)).unwrap();
        // The plot area: 20 px margin and 70 px labels left, header 100 +
        // 20 margin on top, 50 px labels and 20 margin at the bottom.
        let (x0, x1) = (20.0 + 70.0, SIZE.0 as f64 - 20.0);
        let (y0, y1) = (100.0 + 20.0, SIZE.1 as f64 - 20.0 - 50.0);
        for (k, fate) in run.leaves.iter().map(|l| &l.fate).enumerate() {
            let x = (x0 + (x1 - x0) * (k as f64 + 0.5) / 3.0) as usize;
            let y = (0.5 * (y0 + y1)) as usize;
            let i = 3 * (y * SIZE.0 as usize + x);
            let c = colour(fate);
            assert_eq!((rgb[i], rgb[i + 1], rgb[i + 2]), (c.0, c.1, c.2), "box {k}");
        }
    }
}
