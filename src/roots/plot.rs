//! Pictures of the tangency study and of the critical curve (SVG and PNG).
//! Drawing uses `f64` coordinates only; every plotted classification comes
//! from the certified results.

use super::critical::{AtlasLabel, CriticalCurve};
use super::tangency::{Outcome, TangencyReport};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Once;

static FONT: Once = Once::new();

/// Registers DejaVu Sans for text in bitmaps (once per process).
pub fn register_font() {
    FONT.call_once(|| {
        // An embedded, valid TrueType font: registration cannot fail.
        let _ = plotters::style::register_font(
            "sans-serif",
            plotters::style::FontStyle::Normal,
            dejavu::sans::regular(),
        );
    });
}

type DrawResult = Result<(), String>;

fn err<E: std::fmt::Debug>(e: E) -> String {
    format!("drawing failed: {e:?}")
}

/// Writes `<stem>.svg` and `<stem>.png` in `dir` with the same drawing.
fn both(
    dir: &Path,
    stem: &str,
    size: (u32, u32),
    draw_svg: impl Fn(&DrawingArea<SVGBackend, Shift>) -> DrawResult,
    draw_png: impl Fn(&DrawingArea<BitMapBackend, Shift>) -> DrawResult,
) -> Result<Vec<PathBuf>, String> {
    register_font();
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let svg = dir.join(format!("{stem}.svg"));
    let png = dir.join(format!("{stem}.png"));
    {
        let root = SVGBackend::new(&svg, size).into_drawing_area();
        draw_svg(&root)?;
        root.present().map_err(err)?;
    }
    {
        let root = BitMapBackend::new(&png, size).into_drawing_area();
        draw_png(&root)?;
        root.present().map_err(err)?;
    }
    Ok(vec![svg, png])
}

fn draw_tangency<DB: DrawingBackend>(
    rep: &TangencyReport,
    root: &DrawingArea<DB, Shift>,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(err)?;
    let k_max = rep.rows.iter().map(|r| r.k).max().unwrap_or(1);
    let e_max = rep
        .rows
        .iter()
        .map(|r| r.evaluations as f64)
        .fold(10.0, f64::max)
        * 2.0;
    let mut chart = ChartBuilder::on(root)
        .caption(
            "(2.10) near the tangency: κ = κ₀(1 ± 10^-k)",
            ("sans-serif", 22),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(0.5f64..(k_max as f64 + 0.5), (10f64..e_max).log_scale())
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("k")
        .y_desc("evaluations per solve")
        .draw()
        .map_err(err)?;
    for (sign, color, name) in [
        (-1, BLUE, "κ below κ₀ (two roots)"),
        (1, RED, "κ above κ₀ (no root)"),
    ] {
        let pts: Vec<(f64, f64, Outcome)> = rep
            .rows
            .iter()
            .filter(|r| r.sign == sign)
            .map(|r| (r.k as f64, (r.evaluations as f64).max(10.0), r.outcome))
            .collect();
        chart
            .draw_series(LineSeries::new(pts.iter().map(|p| (p.0, p.1)), color))
            .map_err(err)?
            .label(name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
        chart
            .draw_series(pts.iter().map(|&(x, y, o)| {
                let style = if o == Outcome::Undecided {
                    color.stroke_width(2)
                } else {
                    color.filled()
                };
                Circle::new((x, y), if o == Outcome::Undecided { 7 } else { 4 }, style)
            }))
            .map_err(err)?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(err)?;
    root.draw(&Text::new(
        "filled: certified (2 unique / 0 roots proved); ring: undecided",
        (80, 60),
        ("sans-serif", 14),
    ))
    .map_err(err)?;
    Ok(())
}

/// Writes `tangency.svg` and `tangency.png`.
pub fn plot_tangency(rep: &TangencyReport, dir: &Path) -> Result<Vec<PathBuf>, String> {
    both(
        dir,
        "tangency",
        (900, 600),
        |r| draw_tangency(rep, r),
        |r| draw_tangency(rep, r),
    )
}

fn draw_critical<DB: DrawingBackend>(
    cc: &CriticalCurve,
    root: &DrawingArea<DB, Shift>,
) -> DrawResult
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(err)?;
    let mut chart = ChartBuilder::on(root)
        .caption(
            "(2.9): certified atlas of the (α, κ) plane and κ_crit(α)",
            ("sans-serif", 22),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(0f64..1f64, 0f64..cc.kappa_max)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("α")
        .y_desc("κ")
        .disable_mesh()
        .draw()
        .map_err(err)?;
    let color = |l: AtlasLabel| match l {
        AtlasLabel::NoRoot => RGBColor(198, 219, 239),
        AtlasLabel::TwoSimpleRoots => RGBColor(253, 208, 162),
        AtlasLabel::Undecided => RGBColor(150, 150, 150),
    };
    chart
        .draw_series(cc.atlas.iter().map(|b| {
            Rectangle::new(
                [(b.alpha[0], b.kappa[0]), (b.alpha[1], b.kappa[1])],
                color(b.label).filled(),
            )
        }))
        .map_err(err)?;
    for (pick, name, c) in [
        (0usize, "κ_crit lower bound", BLACK),
        (1, "κ_crit upper bound", RGBColor(200, 0, 0)),
    ] {
        let pts: Vec<(f64, f64)> = cc
            .band
            .iter()
            .flat_map(|b| {
                let v = if pick == 0 { b.lower } else { b.upper };
                [(b.alpha.lo, v), (b.alpha.hi, v)]
            })
            .collect();
        chart
            .draw_series(LineSeries::new(pts, c.stroke_width(1)))
            .map_err(err)?
            .label(name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c));
    }
    chart
        .draw_series(std::iter::once(Circle::new(
            (1.0, cc.kappa0.lo),
            5,
            BLACK.filled(),
        )))
        .map_err(err)?
        .label("κ₀ = √3/9 at α = 1")
        .legend(|(x, y)| Circle::new((x + 10, y), 4, BLACK.filled()));
    for (l, name) in [
        (AtlasLabel::NoRoot, "no root in (0, π)"),
        (AtlasLabel::TwoSimpleRoots, "exactly two roots, simple"),
        (AtlasLabel::Undecided, "undecided"),
    ] {
        let c = color(l);
        chart
            .draw_series(std::iter::empty::<Rectangle<(f64, f64)>>())
            .map_err(err)?
            .label(name)
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 15, y + 5)], c.filled()));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(err)?;
    Ok(())
}

/// Writes `critical-curve.svg` and `critical-curve.png`.
pub fn plot_critical(cc: &CriticalCurve, dir: &Path) -> Result<Vec<PathBuf>, String> {
    both(
        dir,
        "critical-curve",
        (900, 700),
        |r| draw_critical(cc, r),
        |r| draw_critical(cc, r),
    )
}
