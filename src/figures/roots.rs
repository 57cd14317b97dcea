//! Pictures of the tangency study and of the critical curve (SVG and PNG).
//! Drawing uses `f64` coordinates only; every plotted classification comes
//! from the certified results. Colours are Okabe–Ito's colour-blind-safe
//! set; text goes through [`crate::figures::Figure`] (typeset sub- and
//! superscripts, even glyph spacing in PNG).

use crate::figures::{
    check_size, draw_err, nice_ticks, tick_label, write_figure, Area, FigureError, Formats,
};
use crate::roots::critical::{AtlasBox, AtlasLabel, CriticalCurve};
use crate::roots::tangency::{Outcome, TangencyReport};
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// Okabe–Ito colours (safe for the common colour-vision deficiencies).
pub mod okabe_ito {
    use plotters::style::RGBColor;
    pub const BLACK: RGBColor = RGBColor(0x00, 0x00, 0x00);
    pub const ORANGE: RGBColor = RGBColor(0xE6, 0x9F, 0x00);
    pub const SKY_BLUE: RGBColor = RGBColor(0x56, 0xB4, 0xE9);
    pub const BLUISH_GREEN: RGBColor = RGBColor(0x00, 0x9E, 0x73);
    pub const YELLOW: RGBColor = RGBColor(0xF0, 0xE4, 0x42);
    pub const BLUE: RGBColor = RGBColor(0x00, 0x72, 0xB2);
    pub const VERMILLION: RGBColor = RGBColor(0xD5, 0x5E, 0x00);
    pub const REDDISH_PURPLE: RGBColor = RGBColor(0xCC, 0x79, 0xA7);
}
use okabe_ito as oi;

/// Size and formats of a figure.
#[derive(Clone, Copy, Debug, Default)]
pub struct FigureOptions {
    /// `(width, height)` in pixels; `None` for the figure's default.
    pub size: Option<(u32, u32)>,
    pub formats: Formats,
}

/// Smallest accepted size of these figures.
pub const MIN_SIZE: (u32, u32) = (400, 300);

type DrawResult = Result<(), FigureError>;

/// Writes `<stem>.svg` and/or `<stem>.png` in `dir` with the same drawing.
fn write_files(
    dir: &Path,
    stem: &str,
    default_size: (u32, u32),
    opts: &FigureOptions,
    draw: impl Fn(&Area) -> DrawResult,
) -> Result<Vec<PathBuf>, FigureError> {
    let size = opts.size.unwrap_or(default_size);
    check_size(size, MIN_SIZE)?;
    let mut files = Vec::new();
    for ext in opts.formats.extensions() {
        let path = dir.join(format!("{stem}.{ext}"));
        write_figure(&path, size, &draw)?;
        files.push(path);
    }
    Ok(files)
}

/// Powers of ten as `10^{n}`, others compactly.
fn log_label(v: f64) -> String {
    let e = v.log10();
    if (e - e.round()).abs() < 1e-9 {
        format!(
            "10^{{{}}}",
            (e.round() as i64).to_string().replace('-', "−")
        )
    } else {
        tick_label(v, v)
    }
}

fn draw_tangency(rep: &TangencyReport, root: &Area) -> DrawResult {
    root.fill(&WHITE).map_err(draw_err)?;
    let k_max = rep.rows.iter().map(|r| r.k).max().unwrap_or(1);
    let e_max = rep
        .rows
        .iter()
        .map(|r| r.evaluations as f64)
        .fold(10.0, f64::max)
        * 2.0;
    let mut chart = ChartBuilder::on(root)
        .caption(
            "(2.10) near the tangency: κ = κ_{0}(1 ± 10^{−k})",
            ("sans-serif", 24),
        )
        .margin(14)
        .x_label_area_size(48)
        .y_label_area_size(72)
        // Integer k, with half a step of room at both ends.
        .build_cartesian_2d(0i32..(k_max + 1), (10f64..e_max).log_scale())
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .x_desc("k")
        .y_desc("evaluations per solve")
        .axis_desc_style(("sans-serif", 18))
        .label_style(("sans-serif", 16))
        .x_labels((k_max + 2) as usize)
        .x_label_formatter(&|k| {
            if (1..=k_max).contains(k) {
                k.to_string()
            } else {
                String::new()
            }
        })
        .y_label_formatter(&|v| log_label(*v))
        .light_line_style(RGBColor(0xEE, 0xEE, 0xEE))
        .bold_line_style(RGBColor(0xCC, 0xCC, 0xCC))
        .draw()
        .map_err(draw_err)?;
    for (sign, color, name) in [
        (-1, oi::BLUE, "κ below κ_{0} (two roots)"),
        (1, oi::VERMILLION, "κ above κ_{0} (no root)"),
    ] {
        let pts: Vec<(i32, f64, Outcome)> = rep
            .rows
            .iter()
            .filter(|r| r.sign == sign)
            .map(|r| (r.k, (r.evaluations as f64).max(10.0), r.outcome))
            .collect();
        chart
            .draw_series(LineSeries::new(
                pts.iter().map(|p| (p.0, p.1)),
                color.stroke_width(2),
            ))
            .map_err(draw_err)?
            .label(name)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        // Circles below κ₀, squares above: the shape tells the series too.
        for &(x, y, o) in &pts {
            let style = if o == Outcome::Undecided {
                color.stroke_width(2)
            } else {
                color.filled()
            };
            let r = if o == Outcome::Undecided { 7 } else { 4 };
            if sign < 0 {
                chart
                    .draw_series(std::iter::once(Circle::new((x, y), r, style)))
                    .map_err(draw_err)?;
            } else {
                chart
                    .draw_series(std::iter::once(
                        EmptyElement::at((x, y)) + Rectangle::new([(-r, -r), (r, r)], style),
                    ))
                    .map_err(draw_err)?;
            }
        }
    }
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 16))
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()
        .map_err(draw_err)?;
    chart
        .plotting_area()
        .strip_coord_spec()
        .draw_text(
            "filled: certified (2 unique / 0 roots proved); ring: undecided",
            &("sans-serif", 15).into_font().color(&BLACK),
            (10, 8),
        )
        .map_err(draw_err)?;
    Ok(())
}

/// Writes `tangency.svg` and/or `tangency.png` in `dir` (the default size
/// unless `opts` gives one).
pub fn plot_tangency_with(
    rep: &TangencyReport,
    dir: &Path,
    opts: &FigureOptions,
) -> Result<Vec<PathBuf>, FigureError> {
    write_files(dir, "tangency", (900, 600), opts, |r| draw_tangency(rep, r))
}

/// Colours of the (α, κ) atlas: light sky blue, light orange, grey (apart in
/// lightness and on the blue–yellow axis, so also under deuteranopia).
pub fn atlas_color(l: AtlasLabel) -> RGBColor {
    match l {
        AtlasLabel::NoRoot => RGBColor(0xB3, 0xDD, 0xF5),
        AtlasLabel::TwoSimpleRoots => RGBColor(0xF5, 0xCF, 0x7F),
        AtlasLabel::Undecided => RGBColor(0x80, 0x80, 0x80),
    }
}

/// Merges atlas boxes of one label into larger rectangles: runs along α in
/// each κ row, then equal runs stacked along κ. The union is unchanged
/// (only boxes sharing a whole edge are joined).
pub fn merge_atlas(boxes: &[AtlasBox]) -> Vec<AtlasBox> {
    let mut v: Vec<AtlasBox> = boxes.to_vec();
    let key = |b: &AtlasBox| (b.label as u8, b.kappa[0].to_bits(), b.kappa[1].to_bits());
    v.sort_by(|a, b| key(a).cmp(&key(b)).then(a.alpha[0].total_cmp(&b.alpha[0])));
    let mut rows: Vec<AtlasBox> = Vec::new();
    for b in v {
        match rows.last_mut() {
            Some(l) if key(l) == key(&b) && l.alpha[1] == b.alpha[0] => l.alpha[1] = b.alpha[1],
            _ => rows.push(b),
        }
    }
    let key2 = |b: &AtlasBox| (b.label as u8, b.alpha[0].to_bits(), b.alpha[1].to_bits());
    rows.sort_by(|a, b| {
        key2(a)
            .cmp(&key2(b))
            .then(a.kappa[0].total_cmp(&b.kappa[0]))
    });
    let mut out: Vec<AtlasBox> = Vec::new();
    for b in rows {
        match out.last_mut() {
            Some(l) if key2(l) == key2(&b) && l.kappa[1] == b.kappa[0] => l.kappa[1] = b.kappa[1],
            _ => out.push(b),
        }
    }
    out
}

/// The plot ranges of the critical-curve figure for a plot area of `px`
/// pixels: [0, 1] × [0, κ_max] widened by `margin` pixels on every side, so
/// markers of that radius at the corners stay inside.
pub fn critical_ranges(kappa_max: f64, px: (u32, u32), margin: f64) -> ([f64; 2], [f64; 2]) {
    let fx = margin / f64::from(px.0.max(1));
    let fy = margin / f64::from(px.1.max(1));
    let pad_x = fx / (1.0 - 2.0 * fx);
    // κ_max may be close to the largest double: pad without overflow.
    let pad_y = kappa_max * (fy / (1.0 - 2.0 * fy));
    let mut top = kappa_max + pad_y;
    if !(top + pad_y).is_finite() {
        // The span top − bottom must stay finite for the coordinate map.
        top = f64::MAX - pad_y;
    }
    ([-pad_x, 1.0 + pad_x], [-pad_y, top])
}

/// Radius of the κ₀ marker in pixels.
pub const KAPPA0_RADIUS: u32 = 5;

fn draw_critical(cc: &CriticalCurve, root: &Area) -> DrawResult {
    root.fill(&WHITE).map_err(draw_err)?;
    let (w, h) = root.dim_in_pixel();
    // Plot area as laid out below (caption 40, margins 14, label areas).
    let px = (w.saturating_sub(28 + 84), h.saturating_sub(28 + 40 + 48));
    let (xr, yr) = critical_ranges(cc.kappa_max, px, f64::from(KAPPA0_RADIUS) + 2.0);
    let mut chart = ChartBuilder::on(root)
        .caption(
            "(2.9): certified atlas of the (α, κ) plane and κ_{crit}(α)",
            ("sans-serif", 24),
        )
        .margin(14)
        .x_label_area_size(48)
        .y_label_area_size(84)
        .build_cartesian_2d(xr[0]..xr[1], yr[0]..yr[1])
        .map_err(draw_err)?;
    let (_, ystep) = nice_ticks(0.0, cc.kappa_max, 8);
    chart
        .configure_mesh()
        .x_desc("α")
        .y_desc("κ")
        .axis_desc_style(("sans-serif", 20))
        .label_style(("sans-serif", 16))
        .x_labels(6)
        .y_labels(9)
        .x_label_formatter(&|v| tick_label(*v, 0.2))
        .y_label_formatter(&|v| tick_label(*v, ystep))
        .disable_mesh()
        .draw()
        .map_err(draw_err)?;
    chart
        .draw_series(merge_atlas(&cc.atlas).iter().map(|b| {
            Rectangle::new(
                [(b.alpha[0], b.kappa[0]), (b.alpha[1], b.kappa[1])],
                atlas_color(b.label).filled(),
            )
        }))
        .map_err(draw_err)?;
    for (pick, name, c) in [
        (0usize, "κ_{crit} lower bound", oi::BLACK),
        (1, "κ_{crit} upper bound", oi::VERMILLION),
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
            .map_err(draw_err)?
            .label(name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
    }
    chart
        .draw_series(std::iter::once(Circle::new(
            (1.0, cc.kappa0.lo),
            KAPPA0_RADIUS,
            oi::BLACK.filled(),
        )))
        .map_err(draw_err)?
        .label("κ_{0} = √3/9 at α = 1")
        .legend(|(x, y)| Circle::new((x + 10, y), 4, oi::BLACK.filled()));
    for (l, name) in [
        (AtlasLabel::NoRoot, "no root in (0, π)"),
        (AtlasLabel::TwoSimpleRoots, "exactly two roots, simple"),
        (AtlasLabel::Undecided, "undecided"),
    ] {
        let c = atlas_color(l);
        chart
            .draw_series(std::iter::empty::<Rectangle<(f64, f64)>>())
            .map_err(draw_err)?
            .label(name)
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 15, y + 5)], c.filled()));
    }
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 16))
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()
        .map_err(draw_err)?;
    Ok(())
}

/// Writes `critical-curve.svg` and/or `critical-curve.png` in `dir` (the
/// default size unless `opts` gives one).
pub fn plot_critical_with(
    cc: &CriticalCurve,
    dir: &Path,
    opts: &FigureOptions,
) -> Result<Vec<PathBuf>, FigureError> {
    write_files(dir, "critical-curve", (900, 700), opts, |r| {
        draw_critical(cc, r)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kappa0_marker_stays_inside_the_plot() {
        for kmax in [0.19245, 0.25, 1.0, 1e308, f64::MAX] {
            for px in [(372, 284), (788, 584), (3000, 2000)] {
                let m = f64::from(KAPPA0_RADIUS) + 2.0;
                let (xr, yr) = critical_ranges(kmax, px, m);
                assert!(yr[1].is_finite());
                // Pixel position of the marker (α = 1, κ₀ ≈ 0.19245).
                let x = (1.0 - xr[0]) / (xr[1] - xr[0]) * f64::from(px.0);
                let y = (yr[1] - 0.19245) / (yr[1] / 2.0 - yr[0] / 2.0) / 2.0 * f64::from(px.1);
                let r = f64::from(KAPPA0_RADIUS);
                assert!(
                    x + r <= f64::from(px.0) && x - r >= 0.0,
                    "{kmax} {px:?}: x {x}"
                );
                assert!(
                    y + r <= f64::from(px.1) && y - r >= 0.0,
                    "{kmax} {px:?}: y {y}"
                );
            }
        }
    }

    #[test]
    fn merged_atlas_keeps_the_union() {
        let cc = crate::roots::critical::critical_curve(16, 16, 0.25);
        let merged = merge_atlas(&cc.atlas);
        assert!(
            merged.len() < cc.atlas.len() / 2,
            "{} of {}",
            merged.len(),
            cc.atlas.len()
        );
        // Same area per label, and every original box inside a merged one of its label.
        for l in [
            AtlasLabel::NoRoot,
            AtlasLabel::TwoSimpleRoots,
            AtlasLabel::Undecided,
        ] {
            let area = |v: &[AtlasBox]| -> f64 {
                v.iter()
                    .filter(|b| b.label == l)
                    .map(|b| (b.alpha[1] - b.alpha[0]) * (b.kappa[1] - b.kappa[0]))
                    .sum()
            };
            assert!((area(&cc.atlas) - area(&merged)).abs() <= 1e-12);
        }
        for b in &cc.atlas {
            assert!(merged.iter().any(|m| m.label == b.label
                && m.alpha[0] <= b.alpha[0]
                && m.alpha[1] >= b.alpha[1]
                && m.kappa[0] <= b.kappa[0]
                && m.kappa[1] >= b.kappa[1]));
        }
    }
}
