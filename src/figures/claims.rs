//! The pictures of the paper checks (SVG + PNG), laid out like the atlas: a
//! typeset title and subtitle, the plot, and beside it (never on the data) a
//! legend that lists exactly the colours and markers drawn.
//!
//! Region pictures colour a paving of two sets the way the atlas colours its
//! cells: a pixel takes a class only when every leaf meeting it is proved in
//! that class (as the atlas layers do). Curve pictures are plain `f64` samples,
//! clipped at the edges of the plot (never clamped into it), with the points
//! the check certified marked on them.

use super::roots::okabe_ito as oi;
use super::{
    class_swatch, draw_err, draw_x_ticks, native, nice_ticks, text_width, theta_ticks, tick_label,
    write_figure, Area, CellLayer, Class, FigureError,
};
use crate::claims::figures::{Axis, ClaimFigure, Shape, THETA_DOT_UNITS, THETA_RAD};
use crate::pave::PhaseBox;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::FontTransform;
use std::path::Path;

/// What a legend entry shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Swatch {
    /// A filled class of a region picture (hatched when undefined).
    Fill(Class),
    Line {
        rgb: (u8, u8, u8),
        dashed: bool,
    },
    Mark {
        rgb: (u8, u8, u8),
        shape: Shape,
    },
}

/// A legend entry: swatch, text and an optional second line.
pub struct Entry {
    pub swatch: Swatch,
    pub text: String,
    pub note: Option<String>,
}

/// A polyline to draw: pixel points, colour, dashed or not.
type Stroke = (Vec<(f64, f64)>, (u8, u8, u8), bool);

/// Picture size and layout (pixels).
pub const SIZE: (u32, u32) = (960, 560);
const TITLE_H: u32 = 64;
const LEGEND_W: u32 = 300;
const MARGIN_TOP: u32 = 8;
const MARGIN_RIGHT: u32 = 16;
const MARGIN_BOTTOM: u32 = 8;
const X_LABELS_H: u32 = 50;
const Y_LABELS_W: u32 = 76;

/// The plot area `(x, y, width, height)` in picture pixels.
pub fn plot_rect() -> (i32, i32, u32, u32) {
    (
        Y_LABELS_W as i32,
        (TITLE_H + MARGIN_TOP) as i32,
        SIZE.0 - LEGEND_W - Y_LABELS_W - MARGIN_RIGHT,
        SIZE.1 - TITLE_H - MARGIN_TOP - X_LABELS_H - MARGIN_BOTTOM,
    )
}

/// The legend panel `(x, y, width, height)` in picture pixels.
pub fn legend_rect() -> (i32, i32, u32, u32) {
    (
        (SIZE.0 - LEGEND_W) as i32,
        TITLE_H as i32,
        LEGEND_W,
        SIZE.1 - TITLE_H,
    )
}

const INK: RGBColor = RGBColor(0x22, 0x22, 0x22);
const ZERO: (u8, u8, u8) = (0x99, 0x99, 0x99);
const MARK: (u8, u8, u8) = (0x00, 0x00, 0x00);
/// Series colours (Okabe–Ito), in order.
const SERIES: [RGBColor; 6] = [
    oi::BLUE,
    oi::VERMILLION,
    oi::BLUISH_GREEN,
    oi::REDDISH_PURPLE,
    oi::ORANGE,
    oi::SKY_BLUE,
];

fn rgb3(c: RGBColor) -> (u8, u8, u8) {
    (c.0, c.1, c.2)
}

fn col(c: (u8, u8, u8)) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

/// The colour of series `i`.
pub fn series_rgb(i: usize) -> (u8, u8, u8) {
    rgb3(SERIES[i % SERIES.len()])
}

/// What a region picture calls a class of its pair.
fn class_text(class: Class, names: &[String; 2]) -> (String, Option<String>) {
    match class {
        Class::Persists => ("in both".into(), None),
        Class::Released => ("in neither".into(), None),
        Class::NonExistence => (format!("only in {}", names[0]), None),
        Class::NonUniqueness => (format!("only in {}", names[1]), None),
        Class::Undecided => (
            "undecided".into(),
            Some("not decided at this resolution".into()),
        ),
        Class::Undefined => (
            "undefined (hatched)".into(),
            Some("a formula singular".into()),
        ),
    }
}

/// A figure made ready to draw: the cell layer of a region picture.
struct Prepared<'a> {
    fig: &'a ClaimFigure,
    cells: Option<CellLayer>,
}

impl<'a> Prepared<'a> {
    fn new(fig: &'a ClaimFigure) -> Prepared<'a> {
        let (_, _, pw, ph) = plot_rect();
        let cells = match fig {
            ClaimFigure::Region(r) => Some(CellLayer::new(&r.paving, (pw, ph))),
            ClaimFigure::Lines(_) => None,
        };
        Prepared { fig, cells }
    }

    /// Legend entries: every class shown, curve and marker drawn, in the
    /// order they are drawn.
    fn legend(&self) -> Vec<Entry> {
        let mut out = Vec::new();
        match (self.fig, &self.cells) {
            (ClaimFigure::Region(r), Some(cells)) => {
                for class in cells.shown() {
                    let (text, note) = class_text(class, &r.names);
                    out.push(Entry {
                        swatch: Swatch::Fill(class),
                        text,
                        note,
                    });
                }
                if r.mark.is_some() {
                    out.push(Entry {
                        swatch: Swatch::Mark {
                            rgb: MARK,
                            shape: Shape::Ring,
                        },
                        text: "witness box (certified)".into(),
                        note: Some("outlined, ringed to be seen".into()),
                    });
                }
            }
            (ClaimFigure::Lines(c), _) => {
                if c.zero {
                    out.push(Entry {
                        swatch: Swatch::Line {
                            rgb: ZERO,
                            dashed: false,
                        },
                        text: "zero".into(),
                        note: None,
                    });
                }
                for (i, s) in c.series.iter().enumerate() {
                    out.push(Entry {
                        swatch: Swatch::Line {
                            rgb: series_rgb(i),
                            dashed: s.dashed,
                        },
                        text: s.name.clone(),
                        note: None,
                    });
                }
                for m in &c.marks {
                    out.push(Entry {
                        swatch: Swatch::Mark {
                            rgb: MARK,
                            shape: m.shape,
                        },
                        text: m.name.clone(),
                        note: None,
                    });
                }
            }
            _ => {}
        }
        out
    }
}

/// The legend of `fig` as drawn (the classes a region picture shows depend
/// on its raster, so this prepares the figure).
pub fn legend(fig: &ClaimFigure) -> Vec<Entry> {
    Prepared::new(fig).legend()
}

fn render(root: &Area, prep: &Prepared) -> Result<(), FigureError> {
    let (width, height) = root.dim_in_pixel();
    root.fill(&WHITE).map_err(draw_err)?;
    let (title, subtitle) = match prep.fig {
        ClaimFigure::Region(r) => (&r.title, &r.subtitle),
        ClaimFigure::Lines(c) => (&c.title, &c.subtitle),
    };
    let bold = ("sans-serif", 20).into_font().style(FontStyle::Bold);
    root.draw_text(title, &bold.color(&INK), (16, 10))
        .map_err(draw_err)?;
    root.draw_text(
        subtitle,
        &("sans-serif", 15).into_font().color(&INK),
        (16, 38),
    )
    .map_err(draw_err)?;

    let (x_axis, y_axis) = match prep.fig {
        ClaimFigure::Region(r) => {
            let b = r.paving.root;
            (
                Axis {
                    name: THETA_RAD,
                    range: b.theta,
                    angle: true,
                },
                Axis {
                    name: THETA_DOT_UNITS,
                    range: b.theta_dot,
                    angle: false,
                },
            )
        }
        ClaimFigure::Lines(c) => (copy_axis(&c.x), copy_axis(&c.y)),
    };
    let chart_area = root
        .clone()
        .shrink((0, TITLE_H), (width - LEGEND_W, height - TITLE_H));
    let (xr, yr) = (x_axis.range, y_axis.range);
    let (_, y_step) = nice_ticks(yr[0], yr[1], 8);
    let mut chart = ChartBuilder::on(&chart_area)
        .margin_top(MARGIN_TOP)
        .margin_right(MARGIN_RIGHT)
        .margin_bottom(MARGIN_BOTTOM)
        .x_label_area_size(X_LABELS_H)
        .y_label_area_size(Y_LABELS_W)
        .build_cartesian_2d(xr[0]..xr[1], yr[0]..yr[1])
        .map_err(draw_err)?;
    let plot = chart.plotting_area().strip_coord_spec();
    let (pw, ph) = plot.dim_in_pixel();
    debug_assert_eq!((pw, ph), (plot_rect().2, plot_rect().3), "layout");
    let to_px = |(x, y): (f64, f64)| {
        (
            (x - xr[0]) / (xr[1] - xr[0]) * f64::from(pw),
            (yr[1] - y) / (yr[1] - yr[0]) * f64::from(ph),
        )
    };

    match (prep.fig, &prep.cells) {
        (ClaimFigure::Region(r), Some(cells)) => {
            cells.draw(&plot)?;
            if let Some(b) = r.mark {
                let (x0, y0) = to_px((b.theta[0], b.theta_dot[1]));
                let (x1, y1) = to_px((b.theta[1], b.theta_dot[0]));
                // At least 3 pixels a side, so the box itself is visible.
                let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
                let (hw, hh) = ((0.5 * (x1 - x0)).max(1.5), (0.5 * (y1 - y0)).max(1.5));
                let outline = vec![
                    (cx - hw, cy - hh),
                    (cx + hw, cy - hh),
                    (cx + hw, cy + hh),
                    (cx - hw, cy + hh),
                    (cx - hw, cy - hh),
                ];
                let ring = ring_points((cx, cy), 10.0 + hw.max(hh));
                native(&plot, |fig, o| {
                    let shift = |v: &[(f64, f64)]| -> Vec<(f64, f64)> {
                        v.iter().map(|p| (o.0 + p.0, o.1 + p.1)).collect()
                    };
                    let ink = col(MARK).to_backend_color();
                    fig.stroke(&shift(&outline), ink, 1.5)?;
                    fig.stroke(&shift(&ring), ink, 2.0)
                })
                .map_err(FigureError::Draw)?;
            }
        }
        (ClaimFigure::Lines(c), _) => {
            let mut lines: Vec<Stroke> = Vec::new();
            if c.zero {
                // On a pixel row's centre: a crisp one-pixel line.
                let y = to_px((xr[0], 0.0)).1.floor() + 0.5;
                lines.push((vec![(0.0, y), (f64::from(pw), y)], ZERO, false));
            }
            for (i, s) in c.series.iter().enumerate() {
                let px: Vec<(f64, f64)> = s.pts.iter().map(|&p| to_px(p)).collect();
                lines.push((px, series_rgb(i), s.dashed));
            }
            native(&plot, |fig, o| {
                for (k, (pts, rgb, dashed)) in lines.iter().enumerate() {
                    let w = if c.zero && k == 0 { 1.0 } else { 2.0 };
                    for piece in clip_polyline(pts, (f64::from(pw), f64::from(ph))) {
                        let pieces = if *dashed {
                            dashes(&piece, 9.0, 6.0)
                        } else {
                            vec![piece]
                        };
                        for p in pieces {
                            let p: Vec<(f64, f64)> =
                                p.iter().map(|q| (o.0 + q.0, o.1 + q.1)).collect();
                            fig.stroke(&p, col(*rgb).to_backend_color(), w)?;
                        }
                    }
                }
                Ok(())
            })
            .map_err(FigureError::Draw)?;
            for m in &c.marks {
                for &p in &m.pts {
                    let (x, y) = to_px(p);
                    // Only marks wholly inside the plot are drawn.
                    if x < 6.0 || y < 6.0 || x > f64::from(pw) - 6.0 || y > f64::from(ph) - 6.0 {
                        continue;
                    }
                    draw_marker(&plot, (x.round() as i32, y.round() as i32), m.shape, MARK)?;
                }
            }
        }
        _ => {}
    }

    // Axes: y ticks by plotters, x ticks by hand (π multiples on an angle).
    let label_font = ("sans-serif", 15).into_font();
    chart
        .configure_mesh()
        .disable_mesh()
        .label_style(label_font.color(&INK))
        .x_labels(0)
        .y_label_formatter(&|v| tick_label(*v, y_step))
        .y_labels(9)
        .axis_style(INK)
        .draw()
        .map_err(draw_err)?;
    let x_ticks = if x_axis.angle {
        theta_ticks(xr[0], xr[1])
    } else {
        let (t, step) = nice_ticks(xr[0], xr[1], 8);
        t.into_iter().map(|v| (v, tick_label(v, step))).collect()
    };
    let below = chart_area
        .clone()
        .shrink((Y_LABELS_W, MARGIN_TOP + ph), (pw, X_LABELS_H));
    let tick_font = label_font
        .color(&INK)
        .pos(Pos::new(HPos::Center, VPos::Top));
    draw_x_ticks(&below, x_ticks, xr, pw, &tick_font, 1.0)?;
    let desc = ("sans-serif", 18)
        .into_font()
        .color(&INK)
        .pos(Pos::new(HPos::Center, VPos::Center));
    below
        .draw_text(x_axis.name, &desc, (pw as i32 / 2, 38))
        .map_err(draw_err)?;
    let left = chart_area.clone().shrink((0, MARGIN_TOP), (Y_LABELS_W, ph));
    // Short names upright, as in the atlas; longer ones along the axis.
    let y_desc = if super::plain(y_axis.name).chars().count() <= 2 {
        desc.clone()
    } else {
        desc.clone().transform(FontTransform::Rotate270)
    };
    left.draw_text(y_axis.name, &y_desc, (12, ph as i32 / 2))
        .map_err(draw_err)?;
    plot.draw(&Rectangle::new(
        [(0, 0), (pw as i32 - 1, ph as i32 - 1)],
        INK.stroke_width(1),
    ))
    .map_err(draw_err)?;

    let (lx, ly, lw, lh) = legend_rect();
    let area = root.clone().shrink((lx as u32, ly as u32), (lw, lh));
    draw_legend(&area, &prep.legend())
}

fn copy_axis(a: &Axis) -> Axis {
    Axis {
        name: a.name,
        range: a.range,
        angle: a.angle,
    }
}

/// A closed circle of radius `r` around `c` as a polyline.
fn ring_points(c: (f64, f64), r: f64) -> Vec<(f64, f64)> {
    (0..=48)
        .map(|k| {
            let t = std::f64::consts::TAU * f64::from(k) / 48.0;
            (c.0 + r * t.cos(), c.1 + r * t.sin())
        })
        .collect()
}

fn draw_marker(
    area: &Area,
    at: (i32, i32),
    shape: Shape,
    rgb: (u8, u8, u8),
) -> Result<(), FigureError> {
    let c = col(rgb);
    match shape {
        Shape::Dot => area.draw(&Circle::new(at, 5, c.filled())),
        Shape::Ring => area.draw(&Circle::new(at, 6, c.stroke_width(2))),
        Shape::Square => area.draw(&Rectangle::new(
            [(at.0 - 5, at.1 - 5), (at.0 + 5, at.1 + 5)],
            c.filled(),
        )),
    }
    .map_err(draw_err)
}

fn draw_legend(area: &Area, entries: &[Entry]) -> Result<(), FigureError> {
    let name = ("sans-serif", 15).into_font();
    let body = ("sans-serif", 13).into_font();
    let (x0, sw, sh) = (12, 34, 20);
    let tx = x0 + sw + 10;
    let room = f64::from(LEGEND_W) - f64::from(tx as u32) - 8.0;
    let mut y = MARGIN_TOP as i32 + 4;
    for e in entries {
        match e.swatch {
            Swatch::Fill(class) => class_swatch(area, class, (x0, y), (sw, sh), 1.0)?,
            Swatch::Line { rgb, dashed } => {
                let ly = f64::from(y + sh / 2);
                let seg = vec![(f64::from(x0), ly), (f64::from(x0 + sw), ly)];
                let pieces = if dashed {
                    dashes(&seg, 9.0, 6.0)
                } else {
                    vec![seg]
                };
                native(area, |fig, o| {
                    for p in &pieces {
                        let p: Vec<(f64, f64)> = p.iter().map(|q| (o.0 + q.0, o.1 + q.1)).collect();
                        fig.stroke(&p, col(rgb).to_backend_color(), 2.0)?;
                    }
                    Ok(())
                })
                .map_err(FigureError::Draw)?;
            }
            Swatch::Mark { rgb, shape } => {
                draw_marker(area, (x0 + sw / 2, y + sh / 2), shape, rgb)?;
            }
        }
        let lines = wrap(&e.text, 15.0, room);
        let mut ty = y + 2;
        for l in &lines {
            area.draw_text(l, &name.color(&INK), (tx, ty))
                .map_err(draw_err)?;
            ty += 18;
        }
        if let Some(n) = &e.note {
            for l in wrap(n, 13.0, room) {
                area.draw_text(&l, &body.color(&INK), (tx, ty))
                    .map_err(draw_err)?;
                ty += 16;
            }
        }
        y = (ty + 10).max(y + sh + 12);
    }
    Ok(())
}

/// Splits markup `text` at spaces into lines at most `room` pixels wide (a
/// single word wider than that stays whole).
fn wrap(text: &str, size: f64, room: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut cur = String::new();
    for word in text.split(' ') {
        let next = if cur.is_empty() {
            word.to_string()
        } else {
            format!("{cur} {word}")
        };
        if !cur.is_empty() && text_width(&next, size, false) > room {
            lines.push(std::mem::take(&mut cur));
            cur = word.to_string();
        } else {
            cur = next;
        }
    }
    if !cur.is_empty() {
        lines.push(cur);
    }
    lines
}

/// The parts of a polyline inside `[0, w] × [0, h]`: segments are clipped
/// at the edges (Liang–Barsky), a non-finite point breaks the line.
pub fn clip_polyline(pts: &[(f64, f64)], (w, h): (f64, f64)) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut cur: Vec<(f64, f64)> = Vec::new();
    let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
    for seg in pts.windows(2) {
        let (a, b) = (seg[0], seg[1]);
        let clipped = if finite(&a) && finite(&b) {
            clip_segment(a, b, (w, h))
        } else {
            None
        };
        match clipped {
            Some((p, q)) => {
                let joins = cur.last().is_some_and(|l| *l == p);
                if !joins && cur.len() > 1 {
                    out.push(std::mem::take(&mut cur));
                }
                if !joins {
                    cur.clear();
                    cur.push(p);
                }
                cur.push(q);
            }
            None => {
                if cur.len() > 1 {
                    out.push(std::mem::take(&mut cur));
                }
                cur.clear();
            }
        }
    }
    if cur.len() > 1 {
        out.push(cur);
    }
    out
}

fn clip_segment(
    a: (f64, f64),
    b: (f64, f64),
    (w, h): (f64, f64),
) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [(-dx, a.0), (dx, w - a.0), (-dy, a.1), (dy, h - a.1)] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| ((a.0 + t * dx).clamp(0.0, w), (a.1 + t * dy).clamp(0.0, h));
    // Keep the end points exact where nothing is cut (so pieces join).
    let p = if t0 == 0.0 { a } else { at(t0) };
    let q = if t1 == 1.0 { b } else { at(t1) };
    Some((p, q))
}

/// A polyline cut into dashes `on` pixels long, `off` apart.
fn dashes(pts: &[(f64, f64)], on: f64, off: f64) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    let mut cur: Vec<(f64, f64)> = Vec::new();
    let mut phase = 0.0; // position within one on + off period
    for seg in pts.windows(2) {
        let (a, b) = (seg[0], seg[1]);
        let len = (b.0 - a.0).hypot(b.1 - a.1);
        let mut s = 0.0;
        while s < len {
            let drawing = phase < on;
            let left = if drawing {
                on - phase
            } else {
                on + off - phase
            };
            let step = left.min(len - s);
            let p = |t: f64| (a.0 + (b.0 - a.0) * t / len, a.1 + (b.1 - a.1) * t / len);
            if drawing {
                if cur.is_empty() {
                    cur.push(p(s));
                }
                cur.push(p(s + step));
            }
            s += step;
            phase += step;
            if phase >= on && drawing && cur.len() > 1 {
                out.push(std::mem::take(&mut cur));
            }
            if phase >= on + off {
                phase = 0.0;
            }
        }
    }
    if cur.len() > 1 {
        out.push(cur);
    }
    out
}

/// Writes `<dir>/figures/<id>.svg` and `.png` for a claim with a figure;
/// `mark` is the certified witness box of region claims.
pub fn draw_claim(id: &str, dir: &Path, mark: Option<PhaseBox>) -> Result<(), FigureError> {
    match crate::claims::figure(id, mark).map_err(FigureError::Draw)? {
        Some(fig) => draw_claim_figure(&fig, &dir.join("figures"), &id.replace('.', "_")),
        None => Ok(()),
    }
}

/// Writes `<dir>/<stem>.svg` and `.png`.
pub fn draw_claim_figure(fig: &ClaimFigure, dir: &Path, stem: &str) -> Result<(), FigureError> {
    let prep = Prepared::new(fig);
    for ext in ["svg", "png"] {
        write_figure(&dir.join(format!("{stem}.{ext}")), SIZE, |root| {
            render(root, &prep)
        })?;
    }
    Ok(())
}

/// The PNG picture of `fig` as RGB bytes (3 a pixel, row-major, `SIZE`).
pub fn render_rgb(fig: &ClaimFigure) -> Result<Vec<u8>, FigureError> {
    let prep = Prepared::new(fig);
    super::render_rgb(SIZE, |root| render(root, &prep))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::claims::witness::window;
    use crate::claims::{figure, with_figure};
    use std::collections::HashMap;

    #[test]
    fn clipping_keeps_lines_inside_and_breaks_them_at_gaps() {
        let (w, h) = (100.0, 50.0);
        // Up through the top edge and back down: two pieces, cut on the edge.
        let pts = vec![
            (0.0, 40.0),
            (40.0, -40.0),
            (80.0, 40.0),
            (90.0, f64::NAN),
            (95.0, 10.0),
            (99.0, 20.0),
        ];
        let pieces = clip_polyline(&pts, (w, h));
        assert_eq!(pieces.len(), 3, "{pieces:?}");
        for p in &pieces {
            for q in p {
                assert!(q.0 >= 0.0 && q.0 <= w && q.1 >= 0.0 && q.1 <= h, "{q:?}");
            }
        }
        assert_eq!(pieces[0][0], (0.0, 40.0));
        assert_eq!(pieces[0].last().copied(), Some((20.0, 0.0)));
        assert_eq!(pieces[1][0], (60.0, 0.0));
        // Wholly outside: nothing.
        assert!(clip_polyline(&[(-5.0, -5.0), (200.0, -1.0)], (w, h)).is_empty());
    }

    #[test]
    fn dashes_alternate() {
        let d = dashes(&[(0.0, 0.0), (100.0, 0.0)], 9.0, 6.0);
        // 100 = 6 × 15 + 10: six whole dashes and a seventh of 9.
        assert_eq!(d.len(), 7);
        assert_eq!(d[1][0], (15.0, 0.0));
        assert!((d[0].last().unwrap().0 - 9.0).abs() < 1e-12);
    }

    #[test]
    fn legend_and_plot_do_not_overlap() {
        let (px, py, pw, ph) = plot_rect();
        let (lx, ly, lw, lh) = legend_rect();
        assert!(px + pw as i32 <= lx, "plot reaches into the legend");
        assert!(ly >= 0 && lx + lw as i32 <= SIZE.0 as i32 && ly + lh as i32 <= SIZE.1 as i32);
        assert!(py + ph as i32 <= SIZE.1 as i32);
    }

    /// Exact colours of the plot area's pixels (its frame left out), with
    /// their counts.
    fn plot_colours(buf: &[u8]) -> HashMap<(u8, u8, u8), usize> {
        let (px, py, pw, ph) = plot_rect();
        let mut out = HashMap::new();
        for y in py + 1..py + ph as i32 - 1 {
            for x in px + 1..px + pw as i32 - 1 {
                let k = 3 * (y as usize * SIZE.0 as usize + x as usize);
                *out.entry((buf[k], buf[k + 1], buf[k + 2])).or_insert(0) += 1;
            }
        }
        out
    }

    fn swatch_rgb(s: &Swatch) -> (u8, u8, u8) {
        match *s {
            Swatch::Fill(c) => c.rgb(),
            Swatch::Line { rgb, .. } | Swatch::Mark { rgb, .. } => rgb,
        }
    }

    /// Every colour the legend lists is drawn in the plot (for curves, on at
    /// least 30 pixels of exactly that colour: the middle of a 2-pixel line),
    /// and a region picture draws no colour its legend does not list.
    #[test]
    fn figures_draw_exactly_the_colours_their_legends_list() {
        for id in with_figure() {
            let fig = figure(id, None).expect("drawn").expect("has a figure");
            let entries = legend(&fig);
            assert!(!entries.is_empty(), "{id}: empty legend");
            let drawn = plot_colours(&render_rgb(&fig).expect("rendered"));
            for e in &entries {
                let c = swatch_rgb(&e.swatch);
                let least = match e.swatch {
                    Swatch::Line { .. } => 30,
                    _ => 1,
                };
                let n = drawn.get(&c).copied().unwrap_or(0);
                assert!(n >= least, "{id}: `{}` listed, {n} pixels drawn", e.text);
            }
            if let ClaimFigure::Region(_) = fig {
                let listed: Vec<(u8, u8, u8)> =
                    entries.iter().map(|e| swatch_rgb(&e.swatch)).collect();
                let hatch = entries
                    .iter()
                    .any(|e| e.swatch == Swatch::Fill(Class::Undefined));
                for (c, n) in &drawn {
                    let ok = listed.contains(c) || (hatch && *c == (0x22, 0x22, 0x22));
                    assert!(ok, "{id}: {c:?} drawn on {n} pixels, not in the legend");
                }
            }
        }
    }

    /// The witness box of a region picture is drawn and listed.
    #[test]
    fn region_figures_mark_their_witness() {
        let mark = window([0.7, 0.75], [5.4, 5.5]);
        let fig = figure("F1.10", Some(mark)).unwrap().unwrap();
        assert!(legend(&fig)
            .iter()
            .any(|e| matches!(e.swatch, Swatch::Mark { .. }) && e.text.contains("witness")));
        let with = plot_colours(&render_rgb(&fig).unwrap());
        let without = plot_colours(&render_rgb(&figure("F1.10", None).unwrap().unwrap()).unwrap());
        let black = |m: &HashMap<(u8, u8, u8), usize>| m.get(&(0, 0, 0)).copied().unwrap_or(0);
        assert!(black(&with) > 40 && black(&without) == 0);
    }

    /// Each curve has its own colour in the legend.
    #[test]
    fn curves_have_distinct_legend_colours() {
        for id in with_figure() {
            let Some(ClaimFigure::Lines(c)) = figure(id, None).unwrap() else {
                continue;
            };
            let fig = ClaimFigure::Lines(c);
            let lines: Vec<(u8, u8, u8)> = legend(&fig)
                .iter()
                .filter_map(|e| match e.swatch {
                    Swatch::Line { rgb, .. } => Some(rgb),
                    _ => None,
                })
                .collect();
            let ClaimFigure::Lines(c) = &fig else {
                unreachable!()
            };
            assert_eq!(lines.len(), c.series.len() + usize::from(c.zero), "{id}");
            for (i, a) in lines.iter().enumerate() {
                assert!(!lines[i + 1..].contains(a), "{id}: colour {a:?} twice");
            }
        }
    }

    /// Every registered picture belongs to a claim of the table (a typo in
    /// an id would leave it never drawn), and is registered once.
    #[test]
    fn every_picture_belongs_to_one_claim() {
        let pictured = crate::claims::figures_of();
        let ids = with_figure();
        assert_eq!(ids.len(), pictured.len(), "{ids:?}");
        for (id, _) in &pictured {
            assert!(ids.contains(id), "{id}: no such claim");
        }
    }
}
