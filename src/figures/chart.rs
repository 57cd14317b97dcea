//! The speed–accuracy chart of `detach methods`: undecided area against
//! time, log–log, one panel per problem, one curve per method (and peer).

use super::{draw_err, write_figure, FigureError};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// One curve: `(time in seconds, undecided area)` points, ordered by ε.
#[derive(Clone, Debug)]
pub struct Curve {
    pub label: String,
    /// Peers are drawn dashed, detach's methods solid.
    pub peer: bool,
    pub points: Vec<(f64, f64)>,
}

/// One panel of the chart.
#[derive(Clone, Debug)]
pub struct Panel {
    pub title: String,
    pub curves: Vec<Curve>,
}

const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// Draws the panels side by side into an SVG and a PNG of `size` pixels.
pub fn draw_speed_accuracy(
    panels: &[Panel],
    title: &str,
    size: (u32, u32),
    svg: &Path,
    png: &Path,
) -> Result<(), FigureError> {
    for path in [svg, png] {
        write_figure(path, size, |root| render(root, panels, title))?;
    }
    Ok(())
}

fn render<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    panels: &[Panel],
    title: &str,
) -> Result<(), FigureError> {
    root.fill(&WHITE).map_err(draw_err)?;
    let root = root
        .titled(title, ("sans-serif", 22).into_font())
        .map_err(draw_err)?;
    let n = panels.len().max(1);
    let areas = root.split_evenly((1, n));
    // One colour per label across panels.
    let mut labels: Vec<&str> = Vec::new();
    for c in panels.iter().flat_map(|p| &p.curves) {
        if !labels.contains(&c.label.as_str()) {
            labels.push(&c.label);
        }
    }
    for (panel, area) in panels.iter().zip(&areas) {
        let pts = panel.curves.iter().flat_map(|c| &c.points);
        let ok = |&&(t, u): &&(f64, f64)| t > 0.0 && u > 0.0 && t.is_finite() && u.is_finite();
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for &(t, u) in pts.filter(ok) {
            x0 = x0.min(t);
            x1 = x1.max(t);
            y0 = y0.min(u);
            y1 = y1.max(u);
        }
        if x0 > x1 {
            (x0, x1, y0, y1) = (1e-3, 1.0, 1e-3, 1.0);
        }
        let mut chart = ChartBuilder::on(area)
            .caption(&panel.title, ("sans-serif", 18).into_font())
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(64)
            .build_cartesian_2d(
                (x0 / 1.5..x1 * 1.5).log_scale(),
                (y0 / 1.5..y1 * 1.5).log_scale(),
            )
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("wall time (s)")
            .y_desc("undecided area (outer − inner)")
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .label_style(("sans-serif", 13))
            .draw()
            .map_err(draw_err)?;
        for c in &panel.curves {
            let i = labels.iter().position(|l| *l == c.label).unwrap_or(0);
            let color = PALETTE[i % PALETTE.len()];
            let pts: Vec<(f64, f64)> = c.points.iter().filter(ok).copied().collect();
            let style = color.stroke_width(2);
            let series = if c.peer {
                chart
                    .draw_series(DashedLineSeries::new(pts.clone(), 8, 5, style))
                    .map_err(draw_err)?
            } else {
                chart
                    .draw_series(LineSeries::new(pts.clone(), style))
                    .map_err(draw_err)?
            };
            series
                .label(c.label.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
            chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))
                .map_err(draw_err)?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 13))
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(draw_err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both files are written, through the one figure writer, with the
    /// title and every curve's label as text in the SVG.
    #[test]
    fn the_chart_writes_both_files() {
        let dir = std::env::temp_dir().join(format!("detach-chart-{}", std::process::id()));
        let curve = |label: &str, peer: bool, k: f64| Curve {
            label: label.into(),
            peer,
            points: vec![(1e-3 * k, 0.03), (1e-2 * k, 0.01), (1e-1 * k, 0.002)],
        };
        let panels = [Panel {
            title: "a panel".into(),
            curves: vec![
                curve("detach slices", false, 1.0),
                curve("Codac", true, 80.0),
            ],
        }];
        let (svg, png) = (dir.join("c.svg"), dir.join("c.png"));
        draw_speed_accuracy(&panels, "a title", (900, 500), &svg, &png).unwrap();
        let text = std::fs::read_to_string(&svg).unwrap();
        for t in ["a title", "a panel", "detach slices", "Codac"] {
            assert!(text.contains(t), "{t} not in the SVG");
        }
        assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
