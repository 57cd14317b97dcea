//! All drawing (SVG and PNG): atlases of pavings with phase portraits, the
//! roots figures ([`roots`]), the paper checks' pictures ([`claims`]), the
//! speed–accuracy chart ([`chart`]) and the stability maps ([`stability`]).
//!
//! [`draw_atlas`] draws one paving of Ω and Ω₀ as a map of the four partition
//! cells of the paper, with the undecided and (hatched) undefined leaves,
//! axes, a legend and a phase portrait on top. In the PNG the cells are
//! rasterised conservatively ([`rasterize`]): a pixel is drawn in a cell
//! colour only when it is wholly covered by leaves proved in that cell. The
//! SVG draws, for each class, exactly the union of its leaves as vector
//! regions ([`vector_regions`]), so it zooms cleanly and its size depends on
//! the regions' boundaries, not on the leaf count. For a scene with
//! `[dynamics]` the phase portrait is drawn as certified tubes (every
//! solution through a seed stays inside its stroke); otherwise it is
//! computed in plain `f64` and labelled as not certified.

mod canvas;
pub mod chart;
pub mod claims;
mod output;
mod palette;
pub mod params;
mod portrait;
mod raster;
pub mod reach;
mod regions;
pub mod roots;
pub mod stability;
mod ticks;

pub use canvas::{
    draw_err, layout, native, parse_size, plain, text_width, Figure, FigureError, Formats, MAX_SIDE,
};
pub use output::{check_size, render_rgb, write_figure, Area};
pub use palette::{delta_e, min_delta_e};
pub use portrait::{
    atlas_portrait, level_lines, phase_portrait, phase_portrait_px, thin, trajectories, Polyline,
    Portrait,
};
pub use raster::{merge_rects, rasterize, Class, PixelRect, Raster};
pub use regions::{even_odd_area, inside_even_odd, vector_regions, Region, Tracing};
pub use ticks::{nice_ticks, theta_ticks, tick_label};

use crate::pave::Paving;
use crate::scene::{Scene, Variant};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::FontStyle;
use std::path::Path;

/// Size of the whole picture in pixels (PNG pixels; SVG user units).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AtlasStyle {
    pub width: u32,
    pub height: u32,
}

impl Default for AtlasStyle {
    fn default() -> Self {
        AtlasStyle {
            width: 1200,
            height: 800,
        }
    }
}

/// What the picture is of: shown in the title, and used for the phase portrait.
#[derive(Clone, Debug)]
pub struct PictureInfo<'a> {
    pub scene: &'a Scene,
    pub variant: Variant,
    /// `(name, decimal text)` pairs, e.g. from [`crate::number::param::ParamSet::texts`].
    pub params: Vec<(&'static str, String)>,
    /// Whether the paving finished; a note is drawn when this or
    /// [`Paving::complete`] is false.
    pub complete: bool,
    /// The window inside the scene's domain, as given (`θ ∈ [0.5, 2.5]`),
    /// when the picture shows one; stated in the subtitle.
    pub window: Option<String>,
}

/// Smallest accepted picture.
pub const MIN_WIDTH: u32 = 640;
pub const MIN_HEIGHT: u32 = 400;

/// Least distance in pixels between two drawn phase curves.
pub const LINE_SPACING: f64 = 6.0;

// Layout in pixels at the default size; every length of the picture (these,
// fonts, lines, ticks) is multiplied by `scale_of(style)`.
const TITLE_H: u32 = 62;
const LEGEND_W: u32 = 300;
const MARGIN_TOP: u32 = 6;
const MARGIN_RIGHT: u32 = 14;
const MARGIN_BOTTOM: u32 = 8;
const X_LABELS_H: u32 = 46;
const Y_LABELS_W: u32 = 64;

/// How much larger than the default 1200×800 a picture is: the smaller of
/// the two ratios, and at least 1. Text, lines, ticks and margins grow by it,
/// so `--size 4000x3000` reads like the default picture, only finer.
pub fn scale_of(style: &AtlasStyle) -> f64 {
    let d = AtlasStyle::default();
    (f64::from(style.width) / f64::from(d.width))
        .min(f64::from(style.height) / f64::from(d.height))
        .max(1.0)
}

/// `v` pixels at the default size, at scale `s`.
fn px(s: f64, v: u32) -> u32 {
    (f64::from(v) * s).round() as u32
}

/// [`px`] as a drawing coordinate.
fn pxi(s: f64, v: i32) -> i32 {
    (f64::from(v) * s).round() as i32
}

/// The plot area (the part showing the paving) in pixels for a style, so the
/// caller can choose `eps` of about one pixel. Zero if the style is too small.
pub fn plot_area_pixels(style: &AtlasStyle) -> (u32, u32) {
    let s = scale_of(style);
    (
        style
            .width
            .saturating_sub(px(s, LEGEND_W) + px(s, Y_LABELS_W) + px(s, MARGIN_RIGHT)),
        style.height.saturating_sub(
            px(s, TITLE_H) + px(s, MARGIN_TOP) + px(s, X_LABELS_H) + px(s, MARGIN_BOTTOM),
        ),
    )
}

/// Closed rings in pixels.
type Rings = Vec<Vec<(f64, f64)>>;

/// Everything drawn, computed once for both files.
struct Prepared {
    cells: CellLayer,
    /// Phase curves in plot-area pixel coordinates.
    lines: Portrait,
    /// Share of the root box's area in each class, in [`Class::ALL`] order.
    shares: [f64; 6],
    /// Why a class is empty by what the scene proves, in the same order.
    empty: [Option<&'static str>; 6],
    title: String,
    subtitle: String,
    /// What an undefined leaf means in this scene, for the legend.
    undefined: &'static str,
    incomplete: bool,
    /// [`scale_of`] the picture.
    scale: f64,
}

/// Draws `paving` with its phase portrait to an SVG and a PNG file (parent
/// directories are created). The picture is `style.width × style.height`.
pub fn draw_atlas(
    paving: &Paving,
    info: &PictureInfo,
    style: &AtlasStyle,
    svg_path: &Path,
    png_path: &Path,
) -> Result<(), FigureError> {
    draw_atlas_files(paving, info, style, Some(svg_path), Some(png_path))
}

/// [`draw_atlas`] writing only the files given.
pub fn draw_atlas_files(
    paving: &Paving,
    info: &PictureInfo,
    style: &AtlasStyle,
    svg_path: Option<&Path>,
    png_path: Option<&Path>,
) -> Result<(), FigureError> {
    let size = (style.width, style.height);
    check_size(size, (MIN_WIDTH, MIN_HEIGHT))?;
    let prep = prepare(paving, info, style);
    for p in [svg_path, png_path].into_iter().flatten() {
        write_figure(p, size, |root| render(root, paving, &prep))?;
    }
    Ok(())
}

fn prepare(paving: &Paving, info: &PictureInfo, style: &AtlasStyle) -> Prepared {
    let (pw, ph) = plot_area_pixels(style);
    let cells = CellLayer::new(paving, (pw, ph));
    let root = paving.root;
    let (w, h) = (
        root.theta[1] - root.theta[0],
        root.theta_dot[1] - root.theta_dot[0],
    );
    let scale = scale_of(style);
    let lines = atlas_portrait(
        info.scene,
        info.variant,
        &root,
        (pw, ph),
        LINE_SPACING * scale,
    );
    let mut shares = [0.0; 6];
    for leaf in &paving.leaves {
        let i = Class::ALL
            .iter()
            .position(|&c| c == Class::of_leaf(leaf))
            .expect("listed");
        shares[i] +=
            (leaf.bx.theta[1] - leaf.bx.theta[0]) * (leaf.bx.theta_dot[1] - leaf.bx.theta_dot[0]);
    }
    for s in &mut shares {
        *s /= w * h;
    }
    let params: Vec<String> = info
        .params
        .iter()
        .map(|(n, v)| format!("{} = {v}", param_markup(n)))
        .collect();
    // A scene file has one reading: no variant in its title.
    let reading = match info.scene.id() {
        Some(_) => format!(" ({})", info.variant),
        None => String::new(),
    };
    let title = format!("{}{reading}   {}", info.scene.name(), params.join("  "));
    let n = paving.leaves.len();
    let window = info
        .window
        .as_ref()
        .map(|w| format!("  ·  window {w}"))
        .unwrap_or_default();
    let subtitle = format!(
        "{}{window}  ·  eps = {}  ·  {n} {}",
        info.scene.title(),
        eps_text(paving.eps),
        if n == 1 { "leaf" } else { "leaves" }
    );
    Prepared {
        cells,
        lines,
        shares,
        empty: empty_classes(paving, info),
        title,
        subtitle,
        undefined: match info.scene.id() {
            Some(_) => "formula singular (sin θ = 0); hatched",
            None => "a formula undefined; hatched",
        },
        incomplete: !(info.complete && paving.complete),
        scale,
    }
}

/// The cells a scene proves empty: both paradoxes when Ω₀ is Ω by
/// construction, non-uniqueness when Ω₀ ⊂ Ω is proved.
fn empty_classes(paving: &Paving, info: &PictureInfo) -> [Option<&'static str>; 6] {
    let proved = crate::area::proved_empty_cells(info.scene, info.variant);
    let empty = crate::pave::empty_cells(paving, proved);
    Class::ALL.map(|c| {
        c.cell()
            .and_then(|cell| empty[cell.index()])
            .map(|e| e.symbol())
    })
}

/// A parameter's name as typeset markup (`p_phi` → p with subscript φ).
pub fn param_markup(name: &str) -> String {
    let greek = |s: &str| -> String {
        match s {
            "mu" => "μ".into(),
            "phi" => "φ".into(),
            "psi" => "ψ".into(),
            "alpha" => "α".into(),
            "kappa" => "κ".into(),
            "theta" => "θ".into(),
            other => other.into(),
        }
    };
    match name.split_once('_') {
        Some((base, sub)) => format!("{}_{{{}}}", greek(base), greek(sub)),
        None => {
            // `c0` → c with subscript 0.
            let digits = name.trim_start_matches(|c: char| !c.is_ascii_digit());
            if !digits.is_empty()
                && digits.len() < name.len()
                && digits.chars().all(|c| c.is_ascii_digit())
            {
                format!("{}_{{{digits}}}", greek(&name[..name.len() - digits.len()]))
            } else {
                greek(name)
            }
        }
    }
}

/// `2^-10` for powers of two, the decimal otherwise.
fn eps_text(eps: f64) -> String {
    let l = eps.log2();
    if l.fract() == 0.0 && l < 0.0 {
        format!("1/{}", 2f64.powi(-(l as i32)))
    } else {
        format!("{eps}")
    }
}

fn rgb(c: Class) -> RGBColor {
    let (r, g, b) = c.rgb();
    RGBColor(r, g, b)
}

const INK: RGBColor = RGBColor(0x22, 0x22, 0x22);
const LINE: RGBColor = RGBColor(0x10, 0x10, 0x30);
const WARN: RGBColor = RGBColor(0xB0, 0x20, 0x20);

fn render(root: &Area, paving: &Paving, prep: &Prepared) -> Result<(), FigureError> {
    let (width, height) = root.dim_in_pixel();
    let s = prep.scale;
    let (title_h, legend_w) = (px(s, TITLE_H), px(s, LEGEND_W));
    let (margin_top, y_labels_w, x_labels_h) =
        (px(s, MARGIN_TOP), px(s, Y_LABELS_W), px(s, X_LABELS_H));
    root.fill(&WHITE).map_err(draw_err)?;

    // Title and subtitle.
    let title_font = ("sans-serif", 22.0 * s).into_font().style(FontStyle::Bold);
    root.draw_text(
        &prep.title,
        &title_font.color(&INK),
        (pxi(s, 16), pxi(s, 10)),
    )
    .map_err(draw_err)?;
    let sub_font = ("sans-serif", 16.0 * s).into_font();
    root.draw_text(
        &prep.subtitle,
        &sub_font.color(&INK),
        (pxi(s, 16), pxi(s, 38)),
    )
    .map_err(draw_err)?;

    // Chart: axes and plot area.
    let chart_area = root
        .clone()
        .shrink((0, title_h), (width - legend_w, height - title_h));
    let r = paving.root;
    // θ ticks at multiples of π/4, or plain numbers in a narrow window.
    let key_points = theta_ticks(r.theta[0], r.theta[1]);
    let (_, y_step) = nice_ticks(r.theta_dot[0], r.theta_dot[1], 11);
    let mut chart = ChartBuilder::on(&chart_area)
        .margin_top(margin_top)
        .margin_right(px(s, MARGIN_RIGHT))
        .margin_bottom(px(s, MARGIN_BOTTOM))
        .x_label_area_size(x_labels_h)
        .y_label_area_size(y_labels_w)
        .build_cartesian_2d(r.theta[0]..r.theta[1], r.theta_dot[0]..r.theta_dot[1])
        .map_err(draw_err)?;
    let plot = chart.plotting_area().strip_coord_spec();
    debug_assert_eq!(
        plot.dim_in_pixel(),
        (prep.cells.raster.width, prep.cells.raster.height),
        "plot_area_pixels out of step with the layout"
    );

    prep.cells.draw(&plot)?;

    // Phase portrait.
    native(&plot, |fig, o| {
        for (l, width) in &prep.lines.curves {
            let pts: Vec<(f64, f64)> = l.iter().map(|p| (o.0 + p.0, o.1 + p.1)).collect();
            fig.stroke(&pts, LINE.mix(0.8).to_backend_color(), width.max(1.1 * s))?;
        }
        Ok(())
    })
    .map_err(FigureError::Draw)?;

    // Axes: θ̇ ticks by plotters, θ ticks at multiples of π/4 by hand.
    let label_font = ("sans-serif", 16.0 * s).into_font();
    let ink = INK.stroke_width(px(s, 1));
    chart
        .configure_mesh()
        .disable_mesh()
        .label_style(label_font.color(&INK))
        .x_labels(0)
        .y_label_formatter(&|v| tick_label(*v, y_step))
        .y_labels(11)
        .axis_style(ink)
        .draw()
        .map_err(draw_err)?;
    let (pw, ph) = plot.dim_in_pixel();
    let below = chart_area
        .clone()
        .shrink((y_labels_w, margin_top + ph), (pw, x_labels_h));
    let tick_font = label_font
        .color(&INK)
        .pos(Pos::new(HPos::Center, VPos::Top));
    draw_x_ticks(&below, key_points, r.theta, pw, &tick_font, s)?;
    // Axis names, upright: θ below, θ̇ (θ with a dot) left of the plot.
    let desc = ("sans-serif", 20.0 * s)
        .into_font()
        .color(&INK)
        .pos(Pos::new(HPos::Center, VPos::Center));
    below
        .draw_text("θ", &desc, (pw as i32 / 2, pxi(s, 34)))
        .map_err(draw_err)?;
    let left = chart_area.clone().shrink((0, margin_top), (y_labels_w, ph));
    left.draw_text(THETA_DOT, &desc, (pxi(s, 12), ph as i32 / 2))
        .map_err(draw_err)?;
    plot.draw(&Rectangle::new(
        [(0, 0), (pw as i32 - 1, ph as i32 - 1)],
        ink,
    ))
    .map_err(draw_err)?;

    // Legend.
    let legend = root
        .clone()
        .shrink((width - legend_w, title_h), (legend_w, height - title_h));
    draw_legend(&legend, prep)?;
    Ok(())
}

/// A paving's cells as drawn on a plot area: the conservative raster (PNG),
/// the exact vector regions (SVG) and the hatching of undefined leaves, all
/// in plot-area pixels.
pub(crate) struct CellLayer {
    pub(crate) raster: Raster,
    rects: Vec<PixelRect>,
    regions: Vec<(Class, Rings)>,
    /// Undefined pixels widened to be visible, as pixel rectangles.
    hatch: Vec<(i32, i32, i32, i32)>,
}

impl CellLayer {
    /// The layer of `paving` on a plot area of `px` pixels showing its root box.
    pub(crate) fn new(paving: &Paving, (pw, ph): (u32, u32)) -> CellLayer {
        let raster = rasterize(paving, pw, ph);
        let rects = merge_rects(&raster);
        let (regions, _) = vector_regions(paving, &raster);
        let hatch = undefined_hatch(&raster, HATCH_WIDEN);
        let root = paving.root;
        let (w, h) = (
            root.theta[1] - root.theta[0],
            root.theta_dot[1] - root.theta_dot[0],
        );
        let regions = regions
            .into_iter()
            .map(|r| {
                let rings = r
                    .rings
                    .iter()
                    .map(|ring| {
                        ring.iter()
                            .map(|&(t, v)| {
                                (
                                    (t - root.theta[0]) / w * f64::from(pw),
                                    (root.theta_dot[1] - v) / h * f64::from(ph),
                                )
                            })
                            .collect()
                    })
                    .collect();
                (r.class, rings)
            })
            .collect();
        CellLayer {
            raster,
            rects,
            regions,
            hatch,
        }
    }

    /// The classes shown on at least one pixel, in [`Class::ALL`] order.
    pub(crate) fn shown(&self) -> Vec<Class> {
        Class::ALL
            .into_iter()
            .filter(|&c| self.raster.pixels.contains(&Some(c)))
            .collect()
    }

    /// Draws the layer on `plot` (the plot area, origin at its top left).
    pub(crate) fn draw(&self, plot: &Area) -> Result<(), FigureError> {
        // Undecided is the background (so anti-aliasing seams between regions
        // read as undecided); then the cells and undefined leaves: exact vector
        // regions in SVG, the conservative raster in PNG.
        plot.fill(&rgb(Class::Undecided)).map_err(draw_err)?;
        native(plot, |fig, o| {
            if fig.is_vector() {
                for (class, rings) in &self.regions {
                    if *class == Class::Undecided {
                        continue;
                    }
                    let shifted: Vec<Vec<(f64, f64)>> = rings
                        .iter()
                        .map(|r| r.iter().map(|p| (o.0 + p.0, o.1 + p.1)).collect())
                        .collect();
                    fig.fill_rings(&shifted, class.rgb());
                }
            }
            Ok(())
        })
        .map_err(FigureError::Draw)?;
        if !plot_is_vector(plot) {
            for pr in self.rects.iter().filter(|r| r.class != Class::Undecided) {
                plot.draw(&Rectangle::new(
                    [(pr.x0 as i32, pr.y0 as i32), (pr.x1 as i32, pr.y1 as i32)],
                    rgb(pr.class).filled(),
                ))
                .map_err(draw_err)?;
            }
        }
        // Undefined leaves hatched, widened to at least 2·HATCH_WIDEN pixels:
        // the strips at sin θ = 0 are thinner than a pixel.
        native(plot, |fig, o| {
            let shifted: Vec<(i32, i32, i32, i32)> = self
                .hatch
                .iter()
                .map(|&(x0, y0, x1, y1)| {
                    let (dx, dy) = (o.0 as i32, o.1 as i32);
                    (x0 + dx, y0 + dy, x1 + dx, y1 + dy)
                })
                .collect();
            fig.hatch(&shifted, (0x22, 0x22, 0x22))
        })
        .map_err(FigureError::Draw)
    }
}

/// Whether the area draws to an SVG (vector regions) or a PNG (raster).
/// Ticks under a plot `pw` pixels wide spanning `range`: a mark and its
/// label, centred, at each tick, in the strip `below` (the atlas and the
/// paper-check figures alike), with lengths at scale `s` ([`scale_of`]).
fn draw_x_ticks(
    below: &Area,
    ticks: Vec<(f64, String)>,
    range: [f64; 2],
    pw: u32,
    font: &TextStyle,
    s: f64,
) -> Result<(), FigureError> {
    for (t, label) in ticks {
        let x = ((t - range[0]) / (range[1] - range[0]) * f64::from(pw)).round() as i32;
        let x = x.min(pw as i32 - 1);
        below
            .draw(&PathElement::new(
                vec![(x, 0), (x, pxi(s, 5))],
                INK.stroke_width(px(s, 1)),
            ))
            .map_err(draw_err)?;
        below
            .draw_text(&label, font, (x, pxi(s, 8)))
            .map_err(draw_err)?;
    }
    Ok(())
}

fn plot_is_vector(area: &Area) -> bool {
    let flag = std::cell::Cell::new(false);
    let _ = native(area, |fig, _| {
        flag.set(fig.is_vector());
        Ok(())
    });
    flag.get()
}

/// Undefined pixels of `raster`, widened by `r` pixels on every side and
/// clipped to the raster, as merged pixel rectangles `[x0, x1) × [y0, y1)`.
pub fn undefined_hatch(raster: &Raster, r: u32) -> Vec<(i32, i32, i32, i32)> {
    let (w, h) = (raster.width as usize, raster.height as usize);
    let r = r as usize;
    // Widen along rows, then along columns.
    let mut rows = vec![false; w * h];
    for y in 0..h {
        for x in 0..w {
            if raster.get(x as u32, y as u32) == Some(Class::Undefined) {
                for xx in x.saturating_sub(r)..(x + r + 1).min(w) {
                    rows[y * w + xx] = true;
                }
            }
        }
    }
    let mut mask = vec![false; w * h];
    for y in 0..h {
        for x in 0..w {
            if rows[y * w + x] {
                for yy in y.saturating_sub(r)..(y + r + 1).min(h) {
                    mask[yy * w + x] = true;
                }
            }
        }
    }
    // Runs per row, merged downwards while identical.
    let mut out: Vec<(i32, i32, i32, i32)> = Vec::new();
    let mut open: Vec<(i32, i32, i32, i32)> = Vec::new();
    for y in 0..h {
        let mut runs = Vec::new();
        let mut x = 0;
        while x < w {
            if mask[y * w + x] {
                let s = x;
                while x < w && mask[y * w + x] {
                    x += 1;
                }
                runs.push((s as i32, x as i32));
            } else {
                x += 1;
            }
        }
        let mut next = Vec::new();
        for (x0, x1) in runs {
            if let Some(k) = open.iter().position(|o| o.0 == x0 && o.2 == x1) {
                let mut o = open.swap_remove(k);
                o.3 = y as i32 + 1;
                next.push(o);
            } else {
                next.push((x0, y as i32, x1, y as i32 + 1));
            }
        }
        out.append(&mut open);
        open = next;
    }
    out.extend(open);
    out
}

/// Pixels added on each side of undefined pixels for their hatching.
const HATCH_WIDEN: u32 = 6;

/// θ̇ as θ followed by a combining dot above (placed by the text layout).
pub const THETA_DOT: &str = "θ\u{307}";

/// The symbol of a class as markup: complements carry a combining overbar.
/// A legend swatch of `class` at `(x, y)`, `(w, h)` pixels: its colour,
/// hatched for undefined leaves as on the plot, outlined.
fn class_swatch(
    area: &Area,
    class: Class,
    (x, y): (i32, i32),
    (w, h): (i32, i32),
    s: f64,
) -> Result<(), FigureError> {
    area.draw(&Rectangle::new(
        [(x, y), (x + w, y + h)],
        rgb(class).filled(),
    ))
    .map_err(draw_err)?;
    if class == Class::Undefined {
        native(area, |fig, o| {
            let (dx, dy) = (o.0 as i32, o.1 as i32);
            fig.hatch(
                &[(x + dx, y + dy, x + w + dx, y + h + dy)],
                (0x22, 0x22, 0x22),
            )
        })
        .map_err(FigureError::Draw)?;
    }
    area.draw(&Rectangle::new(
        [(x, y), (x + w, y + h)],
        INK.stroke_width(px(s, 1)),
    ))
    .map_err(draw_err)?;
    Ok(())
}

fn symbol_markup(class: Class) -> &'static str {
    match class {
        Class::Persists => "Ω ∩ Ω_{0}",
        Class::Released => "Ω\u{304} ∩ Ω\u{304}_{0}",
        Class::NonUniqueness => "Ω\u{304} ∩ Ω_{0}",
        Class::NonExistence => "Ω ∩ Ω\u{304}_{0}",
        Class::Undecided => "undecided",
        Class::Undefined => "undefined",
    }
}

fn draw_legend(area: &Area, prep: &Prepared) -> Result<(), FigureError> {
    let s = prep.scale;
    let k = |v: i32| pxi(s, v);
    let head = ("sans-serif", 17.0 * s).into_font().style(FontStyle::Bold);
    let name = ("sans-serif", 17.0 * s).into_font();
    let body = ("sans-serif", 14.0 * s).into_font();
    let (x0, sw, sh) = (k(12), k(34), k(24));
    let mut y = k(MARGIN_TOP as i32 + 2);
    area.draw_text("Certified cells", &head.color(&INK), (x0, y))
        .map_err(draw_err)?;
    y += k(26);
    for (i, class) in Class::ALL.into_iter().enumerate() {
        if i == 4 {
            y += k(6);
            area.draw_text("Not certified", &head.color(&INK), (x0, y))
                .map_err(draw_err)?;
            y += k(26);
        }
        class_swatch(area, class, (x0, y), (sw, sh), s)?;
        let tx = x0 + sw + k(10);
        let share = match prep.empty[i] {
            Some(why) => format!("empty ({why})"),
            None => format!("{:.1} % of box", 100.0 * prep.shares[i]),
        };
        area.draw_text(symbol_markup(class), &name.color(&INK), (tx, y - k(3)))
            .map_err(draw_err)?;
        area.draw_text(&share, &body.color(&INK), (tx + k(110), y))
            .map_err(draw_err)?;
        let meaning = if class == Class::Undefined {
            prep.undefined
        } else {
            class.meaning()
        };
        area.draw_text(meaning, &body.color(&INK), (tx, y + k(15)))
            .map_err(draw_err)?;
        y += sh + k(22);
    }
    y += k(4);
    let ly = y + sh / 2;
    area.draw(&PathElement::new(
        vec![(x0, ly), (x0 + sw, ly)],
        LINE.mix(0.75).stroke_width(px(s, 1)),
    ))
    .map_err(draw_err)?;
    let tx = x0 + sw + k(10);
    area.draw_text("phase portrait", &name.color(&INK), (tx, y - k(3)))
        .map_err(draw_err)?;
    let how = if prep.lines.certified {
        "certified tubes"
    } else {
        "f64, not certified"
    };
    area.draw_text(how, &body.color(&INK), (tx, y + k(15)))
        .map_err(draw_err)?;
    y += sh + k(26);
    let notes = [
        "Cell colours only where leaves proved",
        "in that cell cover the pixel (PNG) or",
        "exactly on them (SVG); shares are",
        "leaf areas (f64 sums).",
    ];
    for n in notes {
        area.draw_text(n, &body.color(&INK), (x0, y))
            .map_err(draw_err)?;
        y += k(17);
    }
    if prep.incomplete {
        y += k(10);
        let warn = ("sans-serif", 15.0 * s).into_font().style(FontStyle::Bold);
        for n in [
            "INCOMPLETE: box budget reached,",
            "refinement stopped early",
        ] {
            area.draw_text(n, &warn.color(&WARN), (x0, y))
                .map_err(draw_err)?;
            y += k(18);
        }
    }
    Ok(())
}
