//! The drawing surface of every figure: one plotters backend that writes
//! either an SVG document (written here: real text, exact fractional
//! coordinates, filled paths) or a PNG (plotters' bitmap, with text and
//! curves rendered here).
//!
//! Text is laid out here for both formats with DejaVu Sans metrics and
//! kerning, at fractional pen positions: plotters' own bitmap text drops each
//! glyph's side bearing and truncates pen positions, which spaces letters
//! unevenly. Text takes a small markup: `_{…}` a subscript, `^{…}` a
//! superscript; a combining mark (θ̇, Ω̄) is centred over the glyph before it,
//! above its ink.

use ab_glyph::{point, Font, FontRef, GlyphId, PxScale};
use plotters::coord::Shift;
use plotters::element::{Drawable, PointCollection};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind, FontStyle,
    FontTransform,
};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Largest accepted side of a picture, in pixels (a PNG of 8192² takes
/// 200 MB while drawn).
pub const MAX_SIDE: u32 = 8192;

/// Font families written into SVG text (DejaVu Sans is what the PNG uses).
const SVG_FONTS: &str = "DejaVu Sans, Verdana, sans-serif";

/// An SVG em is `size / 1.24` (plotters' convention for font sizes, kept so
/// that sizes given to plotters mean the same in both formats).
pub fn em_of(size: f64) -> f64 {
    size / 1.24
}

/// Why a figure was not written.
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    #[error("picture size {}×{} is too small (at least {}×{})", .size.0, .size.1, .least.0, .least.1)]
    TooSmall { size: (u32, u32), least: (u32, u32) },
    #[error("picture size {0}×{1} is too large (at most {MAX_SIDE} pixels a side)")]
    TooLarge(u32, u32),
    #[error("cannot create directory {path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{0}: a figure file's name ends in .svg or .png")]
    Format(PathBuf),
    #[error("drawing failed: {0}")]
    Draw(String),
    #[error("the embedded font could not be registered")]
    Font,
}

/// A drawing error, from plotters or a backend.
pub fn draw_err(e: impl std::fmt::Display) -> FigureError {
    FigureError::Draw(e.to_string())
}

type DErr = DrawingErrorKind<FigureError>;

fn lift<E: std::error::Error + Send + Sync + 'static>(e: DrawingErrorKind<E>) -> DErr {
    match e {
        DrawingErrorKind::DrawingError(e) => {
            DrawingErrorKind::DrawingError(FigureError::Draw(e.to_string()))
        }
        DrawingErrorKind::FontError(e) => DrawingErrorKind::FontError(e),
    }
}

// ---------------------------------------------------------------- fonts

struct Fonts {
    regular: FontRef<'static>,
    bold: FontRef<'static>,
}

fn fonts() -> &'static Fonts {
    static FONTS: OnceLock<Fonts> = OnceLock::new();
    FONTS.get_or_init(|| Fonts {
        // Embedded, valid TrueType files: parsing cannot fail.
        regular: FontRef::try_from_slice(dejavu::sans::regular()).expect("DejaVu Sans"),
        bold: FontRef::try_from_slice(dejavu::sans::bold()).expect("DejaVu Sans Bold"),
    })
}

impl Fonts {
    fn get(&self, bold: bool) -> &FontRef<'static> {
        if bold {
            &self.bold
        } else {
            &self.regular
        }
    }
}

/// One glyph placed relative to the pen origin (baseline at y = 0).
#[derive(Clone, Debug)]
pub struct PlacedGlyph {
    pub c: char,
    pub x: f64,
    pub y: f64,
    pub em: f64,
    pub bold: bool,
    /// A combining mark placed on its own (not part of a text run).
    pub mark: bool,
}

/// Text laid out from the pen origin.
#[derive(Clone, Debug)]
pub struct Layout {
    pub glyphs: Vec<PlacedGlyph>,
    /// Advance width in pixels.
    pub width: f64,
}

fn is_mark(c: char) -> bool {
    ('\u{0300}'..='\u{036f}').contains(&c)
}

/// Splits markup into `(text, script)` runs; script 0 base, −1 sub, 1 super.
fn runs(text: &str) -> Vec<(String, i8)> {
    let mut out: Vec<(String, i8)> = vec![(String::new(), 0)];
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        if (c == '_' || c == '^') && chars.peek() == Some(&'{') {
            chars.next();
            let mut inner = String::new();
            for d in chars.by_ref() {
                if d == '}' {
                    break;
                }
                inner.push(d);
            }
            out.push((inner, if c == '_' { -1 } else { 1 }));
            out.push((String::new(), 0));
        } else {
            out.last_mut().expect("nonempty").0.push(c);
        }
    }
    out.retain(|(s, _)| !s.is_empty());
    out
}

/// The markup with its markers removed (what a reader of the SVG source sees).
pub fn plain(text: &str) -> String {
    runs(text).into_iter().map(|(s, _)| s).collect()
}

/// Ink bounds `(x0, top, x1, bottom)` of a glyph at `em`, pixels, y down,
/// relative to its pen position on the baseline.
fn ink(font: &FontRef<'static>, id: GlyphId, em: f64) -> Option<(f64, f64, f64, f64)> {
    let s = em / f64::from(font.units_per_em()?);
    let b = font.outline(id)?.bounds;
    let (y0, y1) = (f64::from(b.min.y), f64::from(b.max.y));
    Some((
        f64::from(b.min.x) * s,
        -y0.max(y1) * s,
        f64::from(b.max.x) * s,
        -y0.min(y1) * s,
    ))
}

/// Lays out markup `text` at `em` pixels per em.
pub fn layout(text: &str, em: f64, bold: bool) -> Layout {
    let font = fonts().get(bold);
    let upem = f64::from(font.units_per_em().unwrap_or(2048.0));
    let mut glyphs = Vec::new();
    let mut pen = 0.0;
    // The last base glyph: (id, pen x, y, em).
    let mut base: Option<(GlyphId, f64, f64, f64)> = None;
    for (run, script) in runs(text) {
        let (e, y) = match script {
            0 => (em, 0.0),
            -1 => (0.72 * em, 0.24 * em),
            _ => (0.72 * em, -0.42 * em),
        };
        let s = e / upem;
        let mut prev: Option<GlyphId> = None;
        for c in run.chars() {
            let id = font.glyph_id(c);
            if is_mark(c) {
                // Centre the mark's ink over the base glyph's ink, and lift it
                // clear of the base's top (marks sit at x-height).
                let (x, dy) = match base {
                    Some((bid, bx, by, bem)) => {
                        let bi = ink(font, bid, bem).unwrap_or((0.0, -0.7 * bem, 0.5 * bem, 0.0));
                        let mi = ink(font, id, e).unwrap_or((0.0, -0.9 * e, 0.3 * e, -0.8 * e));
                        let centre = bx + 0.5 * (bi.0 + bi.2);
                        let x = centre - 0.5 * (mi.0 + mi.2);
                        let gap = 0.08 * e;
                        let lift = (mi.3 - (bi.1 + by) + gap).max(0.0);
                        (x, by - lift)
                    }
                    None => (pen, y),
                };
                glyphs.push(PlacedGlyph {
                    c,
                    x,
                    y: dy,
                    em: e,
                    bold,
                    mark: true,
                });
                continue;
            }
            if let Some(p) = prev {
                pen += f64::from(font.kern_unscaled(p, id)) * s;
            }
            glyphs.push(PlacedGlyph {
                c,
                x: pen,
                y,
                em: e,
                bold,
                mark: false,
            });
            base = Some((id, pen, y, e));
            pen += f64::from(font.h_advance_unscaled(id)) * s;
            prev = Some(id);
        }
    }
    Layout { glyphs, width: pen }
}

/// Width in pixels of markup `text` in a plotters font of `size`.
pub fn text_width(text: &str, size: f64, bold: bool) -> f64 {
    layout(text, em_of(size), bold).width
}

/// Pen origin (baseline) for an anchor at `pos`.
fn origin(pos: (f64, f64), width: f64, em: f64, h: HPos, v: VPos) -> (f64, f64) {
    let x = match h {
        HPos::Left => pos.0,
        HPos::Center => pos.0 - 0.5 * width,
        HPos::Right => pos.0 - width,
    };
    let y = match v {
        VPos::Top => pos.1 + 0.78 * em,
        VPos::Center => pos.1 + 0.36 * em,
        VPos::Bottom => pos.1 - 0.24 * em,
    };
    (x, y)
}

/// `FontTransform::transform` for fractional offsets.
fn rotate(rot: &FontTransform, (x, y): (f64, f64)) -> (f64, f64) {
    match rot {
        FontTransform::None => (x, y),
        FontTransform::Rotate90 => (-y, x),
        FontTransform::Rotate180 => (-x, -y),
        FontTransform::Rotate270 => (y, -x),
    }
}

trait FractPos {
    /// `self − floor(self)`, in [0, 1).
    fn fract_pos(self) -> f64;
}

impl FractPos for f64 {
    fn fract_pos(self) -> f64 {
        self - self.floor()
    }
}

// ---------------------------------------------------------------- SVG

/// A minimal SVG writer: the elements plotters draws, plus filled paths,
/// hatching and strokes at fractional coordinates.
pub struct SvgDoc {
    path: PathBuf,
    size: (u32, u32),
    body: String,
    hatch: bool,
}

fn hex(c: (u8, u8, u8)) -> String {
    format!("#{:02x}{:02x}{:02x}", c.0, c.1, c.2)
}

/// A coordinate with at most 2 decimals (1/100 pixel), no trailing zeros.
fn num(v: f64) -> String {
    let s = format!("{:.2}", v);
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

fn paint(attr: &str, c: BackendColor) -> String {
    let mut s = format!(" {attr}=\"{}\"", hex(c.rgb));
    if c.alpha < 1.0 {
        let _ = write!(s, " {attr}-opacity=\"{}\"", num(c.alpha));
    }
    s
}

impl SvgDoc {
    fn line(&mut self, s: &str) {
        self.body.push_str(s);
        self.body.push('\n');
    }

    fn text(&mut self, lay: &Layout, o: (f64, f64), color: BackendColor, rot: FontTransform) {
        let deg = match rot {
            FontTransform::None => 0,
            FontTransform::Rotate90 => 90,
            FontTransform::Rotate180 => 180,
            FontTransform::Rotate270 => 270,
        };
        let mut out = String::new();
        if deg != 0 {
            let _ = write!(
                out,
                "<g transform=\"rotate({deg} {} {})\">",
                num(o.0),
                num(o.1)
            );
        }
        let fill = paint("fill", color);
        // Runs of glyphs on one baseline at one size, marks on their own.
        let mut i = 0;
        let g = &lay.glyphs;
        while i < g.len() {
            let mut j = i + 1;
            while !g[i].mark && j < g.len() && !g[j].mark && g[j].y == g[i].y && g[j].em == g[i].em
            {
                j += 1;
            }
            let text: String = g[i..j].iter().map(|p| p.c).collect();
            let weight = if g[i].bold {
                " font-weight=\"bold\""
            } else {
                ""
            };
            let _ = write!(
                out,
                "<text x=\"{}\" y=\"{}\" font-family=\"{SVG_FONTS}\" font-size=\"{}\"{weight}{fill}>{}</text>",
                num(o.0 + g[i].x),
                num(o.1 + g[i].y),
                num(g[i].em),
                escape(&text)
            );
            i = j;
        }
        if deg != 0 {
            out.push_str("</g>");
        }
        self.line(&out);
    }

    fn present(&mut self) -> Result<(), FigureError> {
        let (w, h) = self.size;
        // xml:space="preserve": text runs are split at accents and
        // subscripts, and a renderer would otherwise drop the space that
        // ends a run ("θ̈of" for "θ̈ of").
        let mut doc = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" xml:space=\"preserve\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n\
             <desc>detach {}</desc>\n",
            // The version only: committed figures must not change with each commit.
            crate::VERSION
        );
        if self.hatch {
            // Hatching for undefined leaves: dark diagonals on transparency.
            doc.push_str(
                "<defs><pattern id=\"hatch\" patternUnits=\"userSpaceOnUse\" width=\"5\" height=\"5\">\
                 <path d=\"M-1,1 l2,-2 M0,5 l5,-5 M4,6 l2,-2\" stroke=\"#222222\" stroke-width=\"1.1\"/>\
                 </pattern></defs>\n",
            );
        }
        doc.push_str(&self.body);
        doc.push_str("</svg>\n");
        // Written once: every caller draws to a temporary file that
        // `files::render_atomic` renames into place.
        std::fs::write(&self.path, doc)
            .map_err(|e| FigureError::Draw(format!("cannot write {}: {e}", self.path.display())))
    }
}

// ---------------------------------------------------------------- figure

/// A plotters backend for one output file.
pub enum Figure<'a> {
    Svg(SvgDoc),
    Png(BitMapBackend<'a>),
}

impl<'a> Figure<'a> {
    pub fn svg(path: &Path, size: (u32, u32)) -> Figure<'static> {
        Figure::Svg(SvgDoc {
            path: path.to_path_buf(),
            size,
            body: String::new(),
            hatch: false,
        })
    }

    pub fn png(path: &'a Path, size: (u32, u32)) -> Figure<'a> {
        Figure::Png(BitMapBackend::new(path, size))
    }

    /// A PNG figure drawn into `buf` (3 bytes a pixel, RGB, row-major)
    /// instead of a file: what the PNG file would hold, for tests.
    pub fn rgb(buf: &'a mut [u8], size: (u32, u32)) -> Figure<'a> {
        Figure::Png(BitMapBackend::with_buffer(buf, size))
    }

    pub fn is_vector(&self) -> bool {
        matches!(self, Figure::Svg(_))
    }

    /// Strokes a polyline at fractional pixel coordinates, anti-aliased in
    /// PNG. Each pixel is painted once per polyline (the coverage of its
    /// nearest segment), so joints of a translucent line show no beads.
    pub fn stroke(
        &mut self,
        pts: &[(f64, f64)],
        color: BackendColor,
        width: f64,
    ) -> Result<(), DErr> {
        if pts.len() < 2 {
            return Ok(());
        }
        match self {
            Figure::Svg(doc) => {
                let mut d = String::new();
                for (k, p) in pts.iter().enumerate() {
                    let _ = write!(
                        d,
                        "{}{},{}",
                        if k == 0 { "M" } else { " " },
                        num(p.0),
                        num(p.1)
                    );
                }
                let s = format!(
                    "<path d=\"{d}\" fill=\"none\"{} stroke-width=\"{}\" stroke-linejoin=\"round\" stroke-linecap=\"round\"/>",
                    paint("stroke", color),
                    num(width)
                );
                doc.line(&s);
                Ok(())
            }
            Figure::Png(bm) => {
                let mut cov: HashMap<(i32, i32), f64> = HashMap::new();
                let r = 0.5 * width;
                for seg in pts.windows(2) {
                    let (a, b) = (seg[0], seg[1]);
                    let (x0, x1) = (a.0.min(b.0) - r - 1.0, a.0.max(b.0) + r + 1.0);
                    let (y0, y1) = (a.1.min(b.1) - r - 1.0, a.1.max(b.1) + r + 1.0);
                    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
                    let len2 = dx * dx + dy * dy;
                    for py in y0.floor() as i32..=y1.ceil() as i32 {
                        for px in x0.floor() as i32..=x1.ceil() as i32 {
                            let (cx, cy) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
                            let t = if len2 > 0.0 {
                                (((cx - a.0) * dx + (cy - a.1) * dy) / len2).clamp(0.0, 1.0)
                            } else {
                                0.0
                            };
                            let d = (cx - a.0 - t * dx).hypot(cy - a.1 - t * dy);
                            let c = (r + 0.5 - d).clamp(0.0, 1.0).min(width.min(1.0));
                            if c > 0.0 {
                                let e = cov.entry((px, py)).or_insert(0.0);
                                *e = e.max(c);
                            }
                        }
                    }
                }
                for ((x, y), c) in cov {
                    let col = BackendColor {
                        alpha: color.alpha * c,
                        rgb: color.rgb,
                    };
                    bm.draw_pixel((x, y), col).map_err(lift)?;
                }
                Ok(())
            }
        }
    }

    /// Fills the union of closed `rings` (even-odd rule) at fractional
    /// coordinates: a vector path in SVG. In PNG nothing is drawn: the PNG
    /// shows the conservative raster instead.
    pub fn fill_rings(&mut self, rings: &[Vec<(f64, f64)>], fill: (u8, u8, u8)) {
        if let Figure::Svg(doc) = self {
            if rings.is_empty() {
                return;
            }
            let mut d = String::new();
            for ring in rings {
                for (k, p) in ring.iter().enumerate() {
                    let _ = write!(
                        d,
                        "{}{},{}",
                        if k == 0 { "M" } else { "L" },
                        num(p.0),
                        num(p.1)
                    );
                }
                d.push('Z');
            }
            let s = format!(
                "<path d=\"{d}\" fill=\"{}\" fill-rule=\"evenodd\"/>",
                hex(fill)
            );
            doc.line(&s);
        }
    }

    /// Hatches pixel rectangles `[x0, x1) × [y0, y1)` with dark diagonals
    /// (the same pattern in both formats, aligned to the picture).
    pub fn hatch(&mut self, rects: &[(i32, i32, i32, i32)], ink: (u8, u8, u8)) -> Result<(), DErr> {
        match self {
            Figure::Svg(doc) => {
                if rects.is_empty() {
                    return Ok(());
                }
                doc.hatch = true;
                let mut d = String::new();
                for &(x0, y0, x1, y1) in rects {
                    let _ = write!(d, "M{x0},{y0}H{x1}V{y1}H{x0}Z");
                }
                doc.line(&format!("<path d=\"{d}\" fill=\"url(#hatch)\"/>"));
                Ok(())
            }
            Figure::Png(bm) => {
                for &(x0, y0, x1, y1) in rects {
                    for y in y0..y1 {
                        for x in x0..x1 {
                            // Diagonals x + y ≡ 0 (mod 5), one pixel wide.
                            if (x + y).rem_euclid(5) == 0 {
                                bm.draw_pixel(
                                    (x, y),
                                    BackendColor {
                                        alpha: 1.0,
                                        rgb: ink,
                                    },
                                )
                                .map_err(lift)?;
                            }
                        }
                    }
                }
                Ok(())
            }
        }
    }

    fn put_text(
        &mut self,
        lay: &Layout,
        o: (f64, f64),
        color: BackendColor,
        rot: FontTransform,
    ) -> Result<(), DErr> {
        match self {
            Figure::Svg(doc) => {
                doc.text(lay, o, color, rot);
                Ok(())
            }
            Figure::Png(bm) => {
                let (w, h) = bm.get_size();
                for g in &lay.glyphs {
                    let font = fonts().get(g.bold);
                    let id = font.glyph_id(g.c);
                    let scale = PxScale::from(
                        (g.em * f64::from(font.height_unscaled())
                            / f64::from(font.units_per_em().unwrap_or(2048.0)))
                            as f32,
                    );
                    // Unrotated text keeps the origin's fractional part
                    // (even spacing); rotated text is placed on whole pixels.
                    let (fx, fy, gx, gy) = if matches!(rot, FontTransform::None) {
                        (
                            o.0.floor(),
                            o.1.floor(),
                            o.0.fract_pos() + g.x,
                            o.1.fract_pos() + g.y,
                        )
                    } else {
                        (o.0.round(), o.1.round(), g.x, g.y)
                    };
                    let glyph = id.with_scale_and_position(scale, point(gx as f32, gy as f32));
                    let Some(out) = font.outline_glyph(glyph) else {
                        continue;
                    };
                    let b = out.px_bounds();
                    let mut px = Vec::new();
                    out.draw(|x, y, c| {
                        px.push((b.min.x as i32 + x as i32, b.min.y as i32 + y as i32, c))
                    });
                    for (x, y, c) in px {
                        let (rx, ry) = rot.transform(x, y);
                        let (x, y) = (fx as i32 + rx, fy as i32 + ry);
                        if c <= 0.0 || x < 0 || y < 0 || x >= w as i32 || y >= h as i32 {
                            continue;
                        }
                        let col = BackendColor {
                            alpha: color.alpha * f64::from(c.min(1.0)),
                            rgb: color.rgb,
                        };
                        bm.draw_pixel((x, y), col).map_err(lift)?;
                    }
                }
                Ok(())
            }
        }
    }
}

impl DrawingBackend for Figure<'_> {
    type ErrorType = FigureError;

    fn get_size(&self) -> (u32, u32) {
        match self {
            Figure::Svg(d) => d.size,
            Figure::Png(b) => b.get_size(),
        }
    }

    fn ensure_prepared(&mut self) -> Result<(), DErr> {
        match self {
            Figure::Svg(_) => Ok(()),
            Figure::Png(b) => b.ensure_prepared().map_err(lift),
        }
    }

    fn present(&mut self) -> Result<(), DErr> {
        match self {
            Figure::Svg(d) => d.present().map_err(DrawingErrorKind::DrawingError),
            Figure::Png(b) => b.present().map_err(lift),
        }
    }

    fn draw_pixel(&mut self, p: BackendCoord, c: BackendColor) -> Result<(), DErr> {
        match self {
            Figure::Svg(d) => {
                d.line(&format!(
                    "<rect x=\"{}\" y=\"{}\" width=\"1\" height=\"1\"{}/>",
                    p.0,
                    p.1,
                    paint("fill", c)
                ));
                Ok(())
            }
            Figure::Png(b) => b.draw_pixel(p, c).map_err(lift),
        }
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DErr> {
        match self {
            Figure::Svg(d) => {
                d.line(&format!(
                    "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"{} stroke-width=\"{}\"/>",
                    num(f64::from(from.0) + 0.5),
                    num(f64::from(from.1) + 0.5),
                    num(f64::from(to.0) + 0.5),
                    num(f64::from(to.1) + 0.5),
                    paint("stroke", style.color()),
                    style.stroke_width()
                ));
                Ok(())
            }
            Figure::Png(b) => {
                if from.0 == to.0 || from.1 == to.1 {
                    b.draw_line(from, to, style).map_err(lift)
                } else {
                    // Slanted lines anti-aliased (plotters' break into dots).
                    let c = |p: BackendCoord| (f64::from(p.0) + 0.5, f64::from(p.1) + 0.5);
                    self.stroke(
                        &[c(from), c(to)],
                        style.color(),
                        f64::from(style.stroke_width()),
                    )
                }
            }
        }
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        ul: BackendCoord,
        br: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DErr> {
        match self {
            Figure::Svg(d) => {
                let s = if fill {
                    format!(
                        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"{}/>",
                        ul.0,
                        ul.1,
                        br.0 - ul.0,
                        br.1 - ul.1,
                        paint("fill", style.color())
                    )
                } else {
                    format!(
                        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\"{} stroke-width=\"{}\"/>",
                        num(f64::from(ul.0) + 0.5),
                        num(f64::from(ul.1) + 0.5),
                        br.0 - ul.0,
                        br.1 - ul.1,
                        paint("stroke", style.color()),
                        style.stroke_width()
                    )
                };
                d.line(&s);
                Ok(())
            }
            Figure::Png(b) => b.draw_rect(ul, br, style, fill).map_err(lift),
        }
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DErr> {
        let pts: Vec<(f64, f64)> = path
            .into_iter()
            .map(|p| (f64::from(p.0) + 0.5, f64::from(p.1) + 0.5))
            .collect();
        self.stroke(&pts, style.color(), f64::from(style.stroke_width()))
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        c: BackendCoord,
        r: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DErr> {
        match self {
            Figure::Svg(d) => {
                let paintc = if fill {
                    paint("fill", style.color())
                } else {
                    format!(
                        " fill=\"none\"{} stroke-width=\"{}\"",
                        paint("stroke", style.color()),
                        style.stroke_width()
                    )
                };
                d.line(&format!(
                    "<circle cx=\"{}\" cy=\"{}\" r=\"{r}\"{paintc}/>",
                    num(f64::from(c.0) + 0.5),
                    num(f64::from(c.1) + 0.5)
                ));
                Ok(())
            }
            Figure::Png(b) => b.draw_circle(c, r, style, fill).map_err(lift),
        }
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), DErr> {
        match self {
            Figure::Svg(d) => {
                let pts: Vec<String> = vert
                    .into_iter()
                    .map(|p| format!("{},{}", p.0, p.1))
                    .collect();
                d.line(&format!(
                    "<polygon points=\"{}\"{}/>",
                    pts.join(" "),
                    paint("fill", style.color())
                ));
                Ok(())
            }
            Figure::Png(b) => b.fill_polygon(vert, style).map_err(lift),
        }
    }

    fn draw_text<T: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &T,
        pos: BackendCoord,
    ) -> Result<(), DErr> {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        let em = em_of(style.size());
        let lay = layout(text, em, matches!(style.style(), FontStyle::Bold));
        let a = style.anchor();
        let o = origin((0.0, 0.0), lay.width, em, a.h_pos, a.v_pos);
        // Offsets from the anchor, rotated with the text.
        let rot = style.transform();
        let o = rotate(&rot, o);
        let o = (f64::from(pos.0) + o.0, f64::from(pos.1) + o.1);
        self.put_text(&lay, o, color, rot)
    }

    fn estimate_text_size<T: BackendTextStyle>(
        &self,
        text: &str,
        style: &T,
    ) -> Result<(u32, u32), DErr> {
        let em = em_of(style.size());
        let w = layout(text, em, matches!(style.style(), FontStyle::Bold)).width;
        Ok((w.ceil() as u32, (1.2 * em).ceil() as u32))
    }
}

/// An element that draws directly on the [`Figure`] with the area's origin
/// (in backend pixels): for paths at fractional coordinates and hatching.
pub struct Native<F> {
    origin: BackendCoord,
    draw: F,
}

impl<F> Native<F>
where
    F: Fn(&mut Figure<'_>, (f64, f64)) -> Result<(), DErr>,
{
    pub fn new(draw: F) -> Self {
        Native {
            origin: (0, 0),
            draw,
        }
    }
}

impl<'b, F> PointCollection<'b, BackendCoord> for &'b Native<F> {
    type Point = &'b BackendCoord;
    type IntoIter = std::iter::Once<&'b BackendCoord>;
    fn point_iter(self) -> Self::IntoIter {
        std::iter::once(&self.origin)
    }
}

impl<'a, F> Drawable<Figure<'a>> for Native<F>
where
    F: Fn(&mut Figure<'_>, (f64, f64)) -> Result<(), DErr>,
{
    fn draw<I: Iterator<Item = BackendCoord>>(
        &self,
        mut pos: I,
        backend: &mut Figure<'a>,
        _: (u32, u32),
    ) -> Result<(), DErr> {
        let o = pos.next().unwrap_or((0, 0));
        (self.draw)(backend, (f64::from(o.0), f64::from(o.1)))
    }
}

/// Draws with `f` on `area` (origin passed in backend pixels).
pub fn native<F>(area: &DrawingArea<Figure<'_>, Shift>, f: F) -> Result<(), String>
where
    F: Fn(&mut Figure<'_>, (f64, f64)) -> Result<(), DErr>,
{
    area.draw(&Native::new(f)).map_err(|e| e.to_string())
}

/// Output formats of a figure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Formats {
    pub svg: bool,
    pub png: bool,
}

impl Formats {
    pub const ALL: Formats = Formats {
        svg: true,
        png: true,
    };

    /// Parses `svg`, `png` or `all`; PDF is refused with a hint.
    pub fn parse(s: &str) -> Result<Formats, String> {
        match s.trim().to_ascii_lowercase().as_str() {
            "svg" => Ok(Formats {
                svg: true,
                png: false,
            }),
            "png" => Ok(Formats {
                svg: false,
                png: true,
            }),
            "all" => Ok(Formats::ALL),
            "pdf" => Err("PDF output is not supported; write the vector figure with \
                          `--format svg` and convert it (e.g. `rsvg-convert -f pdf`)"
                .into()),
            other => Err(format!("unknown format `{other}` (svg, png or all)")),
        }
    }

    /// The extensions written, in order.
    pub fn extensions(&self) -> Vec<&'static str> {
        let mut v = Vec::new();
        if self.svg {
            v.push("svg");
        }
        if self.png {
            v.push("png");
        }
        v
    }
}

impl Default for Formats {
    fn default() -> Self {
        Formats::ALL
    }
}

/// Parses a picture size `WxH` (also `W×H`), each side in
/// `[min, MAX_SIDE]`.
pub fn parse_size(s: &str, min: (u32, u32)) -> Result<(u32, u32), String> {
    let t = s.trim();
    let (w, h) = t
        .split_once(['x', 'X', '×'])
        .ok_or_else(|| format!("size must be WxH (e.g. 1200x800), got `{s}`"))?;
    let side = |v: &str, lo: u32, name: &str| -> Result<u32, String> {
        let n: u32 = v
            .trim()
            .parse()
            .map_err(|_| format!("size {name} must be a whole number of pixels, got `{v}`"))?;
        if n < lo || n > MAX_SIDE {
            return Err(format!(
                "size {name} must be in [{lo}, {MAX_SIDE}] pixels, got {n}"
            ));
        }
        Ok(n)
    };
    Ok((side(w, min.0, "width")?, side(h, min.1, "height")?))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markup_runs_and_plain_text() {
        assert_eq!(plain("p_{φ} = 2"), "pφ = 2");
        assert_eq!(plain("10^{−3}"), "10−3");
        assert_eq!(plain("a_b"), "a_b");
        assert_eq!(runs("κ_{crit}").len(), 2);
    }

    #[test]
    fn kerning_and_bearings_give_even_advances() {
        // "contact" is as wide as the sum of its glyph advances (plus kerning),
        // and a subscript is narrower than the base text.
        let w = text_width("contact", 15.0, false);
        assert!(w > 40.0 && w < 70.0, "{w}");
        assert!(text_width("p_{φ}", 15.0, false) < text_width("pφ", 15.0, false));
    }

    #[test]
    fn marks_sit_above_their_base() {
        let lay = layout("θ\u{307}", 20.0, false);
        let (t, d) = (&lay.glyphs[0], &lay.glyphs[1]);
        assert!(d.mark);
        let font = fonts().get(false);
        let ti = ink(font, font.glyph_id('θ'), 20.0).unwrap();
        let di = ink(font, font.glyph_id('\u{307}'), 20.0).unwrap();
        assert!(d.y + di.3 <= t.y + ti.1, "dot above the θ");
        let (tc, dc) = (t.x + 0.5 * (ti.0 + ti.2), d.x + 0.5 * (di.0 + di.2));
        assert!((tc - dc).abs() < 0.5, "dot centred: {tc} vs {dc}");
    }

    #[test]
    fn sizes_and_formats_parse() {
        assert_eq!(parse_size("1200x800", (640, 400)), Ok((1200, 800)));
        assert_eq!(parse_size("900×600", (300, 200)), Ok((900, 600)));
        assert!(parse_size("100x800", (640, 400)).is_err());
        assert!(parse_size("99999x800", (640, 400)).is_err());
        assert!(parse_size("1200", (640, 400)).is_err());
        assert!(Formats::parse("pdf").unwrap_err().contains("not supported"));
        assert_eq!(Formats::parse("SVG").unwrap().extensions(), ["svg"]);
    }
}
