//! Stability maps of `detach stability`: where each paving method leaves
//! its undecided (and undefined) area, one small panel per method.
//!
//! Each panel is a heat map on a coarse grid over the paving's root box. A
//! grid cell is drawn pale only when no undecided or undefined leaf meets its
//! interior, i.e. when every leaf there is decided for both constraints (a
//! certified statement about the paving, nothing more). Otherwise it shows,
//! on a logarithmic orange-to-dark-red scale, the share of its area covered
//! by undecided leaves, or in blue when undefined leaves (a formula possibly
//! singular, e.g. at sin θ = 0) cover more of it than undecided ones. No
//! decided label is drawn: the map shows only where the methods fail.

use super::raster::Class;
use super::THETA_DOT;
use super::{draw_err, nice_ticks, theta_ticks, tick_label, write_figure, Figure, FigureError};
use crate::pave::{Paving, PhaseBox};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

/// Share of a grid cell's area covered by leaves that are not decided.
#[derive(Clone, Debug)]
pub struct HeatGrid {
    pub cols: usize,
    pub rows: usize,
    pub root: PhaseBox,
    /// Row-major, row 0 at the smallest θ̇: share of the cell covered by
    /// undecided leaves, in [0, 1].
    pub undecided: Vec<f64>,
    /// The same for undefined leaves.
    pub undefined: Vec<f64>,
    /// True where some undecided or undefined leaf meets the cell's interior
    /// (exact comparison of double edges; a share may round to 0 while this
    /// is true, never the other way round).
    pub touched: Vec<bool>,
}

impl HeatGrid {
    /// The grid cell `(col, row)` as a box (edges rounded to doubles; used
    /// for drawing only).
    pub fn cell(&self, col: usize, row: usize) -> PhaseBox {
        let r = &self.root;
        let t = |i: usize| r.theta[0] + (r.theta[1] - r.theta[0]) * i as f64 / self.cols as f64;
        let v = |j: usize| {
            r.theta_dot[0] + (r.theta_dot[1] - r.theta_dot[0]) * j as f64 / self.rows as f64
        };
        let last_t = |i: usize| if i == self.cols { r.theta[1] } else { t(i) };
        let last_v = |j: usize| if j == self.rows { r.theta_dot[1] } else { v(j) };
        PhaseBox {
            theta: [t(col), last_t(col + 1)],
            theta_dot: [v(row), last_v(row + 1)],
        }
    }
}

/// Accumulates the undecided and undefined leaves of `paving` (both
/// constraints, as in the atlas: a leaf is decided when it lies in one of the
/// four cells) on a `cols × rows` grid over its root box.
pub fn heat_grid(paving: &Paving, cols: usize, rows: usize) -> HeatGrid {
    let (cols, rows) = (cols.max(1), rows.max(1));
    let mut g = HeatGrid {
        cols,
        rows,
        root: paving.root,
        undecided: vec![0.0; cols * rows],
        undefined: vec![0.0; cols * rows],
        touched: vec![false; cols * rows],
    };
    let r = paving.root;
    let (w, h) = (r.theta[1] - r.theta[0], r.theta_dot[1] - r.theta_dot[0]);
    let index = |x: f64, lo: f64, width: f64, n: usize| -> usize {
        (((x - lo) / width * n as f64).floor().max(0.0) as usize).min(n - 1)
    };
    for leaf in &paving.leaves {
        let class = Class::of_leaf(leaf);
        if class.is_cell() {
            continue;
        }
        let b = leaf.bx;
        // One cell of slack either way: the exact overlap test below decides.
        let c0 = index(b.theta[0], r.theta[0], w, cols).saturating_sub(1);
        let c1 = (index(b.theta[1], r.theta[0], w, cols) + 1).min(cols - 1);
        let r0 = index(b.theta_dot[0], r.theta_dot[0], h, rows).saturating_sub(1);
        let r1 = (index(b.theta_dot[1], r.theta_dot[0], h, rows) + 1).min(rows - 1);
        for row in r0..=r1 {
            for col in c0..=c1 {
                let cell = g.cell(col, row);
                let ot = b.theta[1].min(cell.theta[1]) - b.theta[0].max(cell.theta[0]);
                let ov =
                    b.theta_dot[1].min(cell.theta_dot[1]) - b.theta_dot[0].max(cell.theta_dot[0]);
                if ot <= 0.0 || ov <= 0.0 {
                    continue;
                }
                let share = (ot * ov)
                    / ((cell.theta[1] - cell.theta[0]) * (cell.theta_dot[1] - cell.theta_dot[0]));
                let k = row * cols + col;
                g.touched[k] = true;
                if class == Class::Undefined {
                    g.undefined[k] += share;
                } else {
                    g.undecided[k] += share;
                }
            }
        }
    }
    for x in g.undecided.iter_mut().chain(g.undefined.iter_mut()) {
        *x = x.clamp(0.0, 1.0);
    }
    g
}

/// One panel of a stability map.
pub struct StabilityPanel<'a> {
    /// The method, e.g. `natural`.
    pub title: String,
    /// Lines under the title (markup): the certified undecided area per
    /// region, the cost.
    pub notes: Vec<String>,
    pub paving: &'a Paving,
}

/// Picture width, height of the header and of one row of panels (pixels).
const WIDTH: u32 = 1400;
const HEADER_H: u32 = 120;
const ROW_H: u32 = 470;
/// Panel caption lines, tick labels.
const CAPTION: u32 = 18;
const LABEL: u32 = 16;

/// Grid cells per panel.
const GRID: (usize, usize) = (160, 100);
const PALE: RGBColor = RGBColor(0xF2, 0xF2, 0xEC);
const UNDEFINED: RGBColor = RGBColor(0x44, 0x77, 0xAA);
const INK: RGBColor = RGBColor(0x22, 0x22, 0x22);

/// Orange (share 10⁻³ or less) to dark red (share 1), logarithmic.
pub fn heat_colour(share: f64) -> RGBColor {
    let t = ((share.max(1e-3).log10() + 3.0) / 3.0).clamp(0.0, 1.0);
    let lerp = |a: u8, b: u8| (f64::from(a) + (f64::from(b) - f64::from(a)) * t).round() as u8;
    RGBColor(lerp(0xFD, 0x80), lerp(0xAE, 0x00), lerp(0x61, 0x26))
}

/// Draws the panels (two per row) with a title into an SVG and a PNG.
pub fn draw_stability_map(
    panels: &[StabilityPanel],
    title: &str,
    svg: &Path,
    png: &Path,
) -> Result<(), FigureError> {
    let grids: Vec<HeatGrid> = panels
        .iter()
        .map(|p| heat_grid(p.paving, GRID.0, GRID.1))
        .collect();
    let rows = panels.len().div_ceil(2).max(1) as u32;
    let size = (WIDTH, HEADER_H + ROW_H * rows);
    for path in [svg, png] {
        write_figure(path, size, |root| render(root, panels, &grids, title))?;
    }
    Ok(())
}

fn render(
    root: &DrawingArea<Figure<'_>, Shift>,
    panels: &[StabilityPanel],
    grids: &[HeatGrid],
    title: &str,
) -> Result<(), FigureError> {
    root.fill(&WHITE).map_err(draw_err)?;
    let bold = ("sans-serif", 24).into_font().style(FontStyle::Bold);
    root.draw_text(title, &bold.color(&INK), (16, 10))
        .map_err(draw_err)?;
    let small = ("sans-serif", 17).into_font();
    root.draw_text(
        "pale: every leaf there decided for Ω and Ω_{0}   orange → dark red: share of the area undecided (log, 10^{−3} … 1)   blue: undefined",
        &small.color(&INK),
        (16, 44),
    )
    .map_err(draw_err)?;
    // Colour key.
    for i in 0..=30 {
        let share = 10f64.powf(-3.0 + 3.0 * f64::from(i) / 30.0);
        let x = 16 + 8 * i;
        root.draw(&Rectangle::new(
            [(x, 76), (x + 8, 92)],
            heat_colour(share).filled(),
        ))
        .map_err(draw_err)?;
    }
    root.draw_text("10^{−3}", &small.color(&INK), (16, 96))
        .map_err(draw_err)?;
    root.draw_text("1", &small.color(&INK), (256, 96))
        .map_err(draw_err)?;
    root.draw(&Rectangle::new([(300, 76), (324, 92)], UNDEFINED.filled()))
        .map_err(draw_err)?;
    root.draw_text("undefined", &small.color(&INK), (332, 74))
        .map_err(draw_err)?;
    root.draw(&Rectangle::new([(460, 76), (484, 92)], PALE.filled()))
        .map_err(draw_err)?;
    root.draw(&Rectangle::new([(460, 76), (484, 92)], INK.stroke_width(1)))
        .map_err(draw_err)?;
    root.draw_text("decided", &small.color(&INK), (492, 74))
        .map_err(draw_err)?;
    root.draw_text(
        "areas in the (θ, θ\u{307}) plane, certified upper bounds",
        &small.color(&INK),
        (620, 74),
    )
    .map_err(draw_err)?;

    let (width, height) = root.dim_in_pixel();
    let body = root
        .clone()
        .shrink((0, HEADER_H), (width, height - HEADER_H));
    let rows = panels.len().div_ceil(2).max(1);
    let areas = body.split_evenly((rows, 2));
    let label = ("sans-serif", LABEL).into_font();
    for ((panel, grid), area) in panels.iter().zip(grids).zip(&areas) {
        let r = grid.root;
        // Caption: the method in bold, then its notes, one a line.
        let cap_bold = ("sans-serif", CAPTION).into_font().style(FontStyle::Bold);
        let cap = ("sans-serif", CAPTION - 2).into_font();
        area.draw_text(&panel.title, &cap_bold.color(&INK), (60, 4))
            .map_err(draw_err)?;
        for (k, n) in panel.notes.iter().enumerate() {
            area.draw_text(n, &cap.color(&INK), (60, 28 + 21 * k as i32))
                .map_err(draw_err)?;
        }
        let caption_h = 32 + 21 * panel.notes.len() as u32;
        let (_, y_step) = nice_ticks(r.theta_dot[0], r.theta_dot[1], 8);
        let mut chart = ChartBuilder::on(area)
            .margin(10)
            .margin_top(caption_h)
            .x_label_area_size(52)
            .y_label_area_size(60)
            .build_cartesian_2d(r.theta[0]..r.theta[1], r.theta_dot[0]..r.theta_dot[1])
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_labels(0)
            .y_labels(9)
            .y_label_formatter(&|v| tick_label(*v, y_step))
            .label_style(label.color(&INK))
            .axis_style(INK)
            .draw()
            .map_err(draw_err)?;
        // θ ticks at multiples of π/4, by hand (as in the atlas).
        let plot = chart.plotting_area().strip_coord_spec();
        let (pw, ph) = plot.dim_in_pixel();
        let (ox, oy) = {
            let (xr, yr) = plot.get_pixel_range();
            (xr.start, yr.start)
        };
        let (ax, ay) = {
            let (xr, yr) = area.get_pixel_range();
            (xr.start, yr.start)
        };
        let tick_font = label.color(&INK).pos(Pos::new(HPos::Center, VPos::Top));
        for (t, text) in theta_ticks(r.theta[0], r.theta[1]) {
            let x = ox - ax
                + (((t - r.theta[0]) / (r.theta[1] - r.theta[0]) * f64::from(pw)).round() as i32)
                    .min(pw as i32 - 1);
            let y = oy - ay + ph as i32;
            area.draw(&PathElement::new(
                vec![(x, y), (x, y + 5)],
                INK.stroke_width(1),
            ))
            .map_err(draw_err)?;
            area.draw_text(&text, &tick_font, (x, y + 8))
                .map_err(draw_err)?;
        }
        let desc = ("sans-serif", LABEL + 2)
            .into_font()
            .color(&INK)
            .pos(Pos::new(HPos::Center, VPos::Center));
        area.draw_text(
            "θ",
            &desc,
            (ox - ax + pw as i32 / 2, oy - ay + ph as i32 + 38),
        )
        .map_err(draw_err)?;
        area.draw_text(THETA_DOT, &desc, (14, oy - ay + ph as i32 / 2))
            .map_err(draw_err)?;
        chart.plotting_area().fill(&PALE).map_err(draw_err)?;
        let mut rects = Vec::new();
        for row in 0..grid.rows {
            for col in 0..grid.cols {
                let k = row * grid.cols + col;
                if !grid.touched[k] {
                    continue;
                }
                let colour = if grid.undefined[k] > 0.0 && grid.undefined[k] >= grid.undecided[k] {
                    UNDEFINED
                } else {
                    heat_colour(grid.undecided[k])
                };
                let c = grid.cell(col, row);
                rects.push(Rectangle::new(
                    [(c.theta[0], c.theta_dot[1]), (c.theta[1], c.theta_dot[0])],
                    colour.filled(),
                ));
            }
        }
        chart.draw_series(rects).map_err(draw_err)?;
    }
    Ok(())
}
