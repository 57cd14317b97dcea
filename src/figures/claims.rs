//! The pictures of the paper checks' witnesses (SVG + PNG). Drawing uses
//! `f64` only; region pictures colour paver leaves by their certified labels,
//! curve pictures mark the certified root enclosures or witness points.

use crate::pave::{Label, Paving, PhaseBox};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

type DrawResult = Result<(), String>;

fn err<E: std::fmt::Debug>(e: E) -> String {
    format!("drawing failed: {e:?}")
}

/// One claim's picture.
pub enum ClaimFigure {
    /// Two regions compared on a window: a paving of the pair, coloured by
    /// its leaves' labels (`names`: the two regions), and the witness box.
    Region {
        title: String,
        paving: Box<Paving>,
        win: PhaseBox,
        names: [&'static str; 2],
        mark: Option<PhaseBox>,
    },
    /// Curves and marked points.
    Lines(Curves),
}

/// Curves `(name, points)` on axes `x`, `y`, and marked points.
pub struct Curves {
    pub title: String,
    pub x: &'static str,
    pub y: &'static str,
    pub series: Vec<(String, Vec<(f64, f64)>)>,
    pub marks: Vec<(f64, f64)>,
}

fn draw_fig<DB: DrawingBackend>(fig: &ClaimFigure, root: &DrawingArea<DB, Shift>) -> DrawResult
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(err)?;
    match fig {
        ClaimFigure::Region {
            title,
            paving: p,
            win,
            names,
            mark,
        } => {
            let mut chart = ChartBuilder::on(root)
                .caption(title, ("sans-serif", 16))
                .margin(10)
                .x_label_area_size(30)
                .y_label_area_size(40)
                .build_cartesian_2d(
                    win.theta[0]..win.theta[1],
                    win.theta_dot[0]..win.theta_dot[1],
                )
                .map_err(err)?;
            chart
                .configure_mesh()
                .x_desc("θ")
                .y_desc("θ̇")
                .draw()
                .map_err(err)?;
            let color = |l: [Label; 2]| match l {
                [Label::ProvedIn, Label::ProvedIn] => RGBColor(0x77, 0xAA, 0xDD),
                [Label::ProvedIn, Label::ProvedOut] => RGBColor(0xEE, 0x88, 0x66),
                [Label::ProvedOut, Label::ProvedIn] => RGBColor(0xAA, 0x44, 0x99),
                [Label::ProvedOut, Label::ProvedOut] => RGBColor(0xFF, 0xFF, 0xFF),
                _ => RGBColor(0xC8, 0xC8, 0xC8),
            };
            chart
                .draw_series(p.leaves.iter().map(|l| {
                    Rectangle::new(
                        [
                            (l.bx.theta[0], l.bx.theta_dot[0]),
                            (l.bx.theta[1], l.bx.theta_dot[1]),
                        ],
                        color([l.labels[0], l.labels[1]]).filled(),
                    )
                }))
                .map_err(err)?;
            if let Some(b) = mark {
                chart
                    .draw_series(std::iter::once(Rectangle::new(
                        [(b.theta[0], b.theta_dot[0]), (b.theta[1], b.theta_dot[1])],
                        BLACK.stroke_width(3),
                    )))
                    .map_err(err)?;
            }
            let legend = [
                (RGBColor(0x77, 0xAA, 0xDD), "in both".to_string()),
                (RGBColor(0xEE, 0x88, 0x66), format!("{} only", names[0])),
                (RGBColor(0xAA, 0x44, 0x99), format!("{} only", names[1])),
                (RGBColor(0xC8, 0xC8, 0xC8), "undecided".to_string()),
            ];
            for (i, (c, t)) in legend.iter().enumerate() {
                let y = 40 + 18 * i as i32;
                root.draw(&Rectangle::new([(60, y), (72, y + 12)], c.filled()))
                    .map_err(err)?;
                root.draw(&Text::new(t.clone(), (78, y), ("sans-serif", 13)))
                    .map_err(err)?;
            }
        }
        ClaimFigure::Lines(Curves {
            title,
            x,
            y,
            series,
            marks,
        }) => {
            let all = series.iter().flat_map(|s| s.1.iter()).chain(marks.iter());
            let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
            for &(a, b) in all {
                x0 = x0.min(a);
                x1 = x1.max(a);
                y0 = y0.min(b);
                y1 = y1.max(b);
            }
            let pad = 0.05 * (y1 - y0).max(1e-9);
            let mut chart = ChartBuilder::on(root)
                .caption(title, ("sans-serif", 16))
                .margin(10)
                .x_label_area_size(30)
                .y_label_area_size(50)
                .build_cartesian_2d(x0..x1, (y0 - pad)..(y1 + pad))
                .map_err(err)?;
            chart
                .configure_mesh()
                .x_desc(*x)
                .y_desc(*y)
                .draw()
                .map_err(err)?;
            let palette = [BLUE, RED, GREEN, MAGENTA, CYAN, BLACK];
            for (i, (name, pts)) in series.iter().enumerate() {
                let c = if name == "0" {
                    RGBColor(0x99, 0x99, 0x99)
                } else {
                    palette[i % palette.len()]
                };
                // break the line where the sampled points skip grid steps
                let step = pts
                    .windows(2)
                    .map(|w| w[1].0 - w[0].0)
                    .fold(f64::MAX, f64::min);
                let mut segments: Vec<Vec<(f64, f64)>> = vec![];
                for (k, &q) in pts.iter().enumerate() {
                    if k == 0 || q.0 - pts[k - 1].0 > 1.5 * step {
                        segments.push(vec![]);
                    }
                    segments.last_mut().expect("pushed").push(q);
                }
                for (k, seg) in segments.into_iter().enumerate() {
                    let s = chart
                        .draw_series(LineSeries::new(seg, c.stroke_width(2)))
                        .map_err(err)?;
                    if name != "0" && k == 0 {
                        s.label(name.clone()).legend(move |(a, b)| {
                            PathElement::new(vec![(a, b), (a + 16, b)], c.stroke_width(2))
                        });
                    }
                }
            }
            chart
                .draw_series(
                    marks
                        .iter()
                        .map(|&(a, b)| Circle::new((a, b), 5, BLACK.filled())),
                )
                .map_err(err)?;
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::LowerRight)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font(("sans-serif", 12))
                .draw()
                .map_err(err)?;
        }
    }
    Ok(())
}

/// Writes `<dir>/<stem>.svg` and `.png`.
pub fn draw_claim_figure(fig: &ClaimFigure, dir: &Path, stem: &str) -> DrawResult {
    super::roots::register_font();
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let size = (560, 380);
    crate::files::render_atomic(&dir.join(format!("{stem}.svg")), |tmp| {
        let root = SVGBackend::new(tmp, size).into_drawing_area();
        draw_fig(fig, &root)?;
        root.present().map_err(err)
    })?;
    crate::files::render_atomic(&dir.join(format!("{stem}.png")), |tmp| {
        let root = BitMapBackend::new(tmp, size).into_drawing_area();
        draw_fig(fig, &root)?;
        root.present().map_err(err)
    })
}
