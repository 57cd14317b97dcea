//! The parameter plane of a 2-D parameter atlas: each parameter box filled
//! by which of the atlas's sets are proved non-empty on it (every set
//! decided), grey where one is undecided, the scene's given point marked.

use super::canvas::Figure;
use super::{draw_err, tick_label, write_figure, Area, FigureError};
use crate::params::model::{ParamAtlas, SetStatus};
use crate::params::Family;
use crate::scene::Cell;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use std::path::Path;

const SIZE: (u32, u32) = (1000, 860);
const INK: RGBColor = RGBColor(0x22, 0x22, 0x22);
const UNDECIDED: RGBColor = RGBColor(0xA0, 0xA0, 0xA0);
const NONE: RGBColor = RGBColor(0xF2, 0xF2, 0xEC);
/// One colour per combination of non-empty sets, in order of appearance.
const COMBINATIONS: [RGBColor; 8] = [
    RGBColor(0x44, 0x77, 0xAA),
    RGBColor(0xEE, 0x66, 0x77),
    RGBColor(0x22, 0x88, 0x33),
    RGBColor(0xCC, 0xBB, 0x44),
    RGBColor(0x66, 0xCC, 0xEE),
    RGBColor(0xAA, 0x33, 0x77),
    RGBColor(0x99, 0x44, 0x55),
    RGBColor(0x33, 0x22, 0x88),
];

/// A box's class: `None` when a set is undecided, else which sets are
/// non-empty (a bit per set).
pub fn class(sets: &[SetStatus]) -> Option<u32> {
    let mut bits = 0;
    for (k, s) in sets.iter().enumerate() {
        match s {
            SetStatus::Undecided { .. } => return None,
            SetStatus::Nonempty { .. } => bits |= 1 << k,
            SetStatus::Empty { .. } => {}
        }
    }
    Some(bits)
}

/// The classes of the atlas's boxes, each once, in the legend's order
/// (by the bits of the non-empty sets, undecided last).
pub fn classes_present(atlas: &ParamAtlas) -> Vec<Option<u32>> {
    let mut classes: Vec<Option<u32>> = Vec::new();
    for leaf in atlas.leaves.iter().filter(|l| !l.bounds.is_empty()) {
        let c = class(&leaf.sets);
        if !classes.contains(&c) {
            classes.push(c);
        }
    }
    classes.sort_by_key(|c| c.map_or(u32::MAX, |b| b));
    classes
}

/// A class's colour in the plane.
pub fn class_colour(c: Option<u32>) -> RGBColor {
    match c {
        None => UNDECIDED,
        Some(0) => NONE,
        Some(b) => COMBINATIONS[(b as usize - 1) % COMBINATIONS.len()],
    }
}

/// A class in the legend, the sets by their labels (Ω, Ω̄∩Ω₀, …).
pub fn class_text(c: Option<u32>, sets: &[String]) -> String {
    match c {
        None => "undecided".to_string(),
        Some(0) => "all proved empty".to_string(),
        Some(b) => {
            let names: Vec<&str> = (0..sets.len())
                .filter(|k| b & (1 << k) != 0)
                .map(|k| label(&sets[k]))
                .collect();
            format!("{} proved non-empty, the others empty", names.join(", "))
        }
    }
}

fn label(name: &str) -> &'static str {
    Cell::ALL
        .into_iter()
        .find(|c| c.name() == name)
        .map(|c| c.label())
        .unwrap_or("?")
}

/// Draws the plane to `stem.svg` and `stem.png`.
pub fn write_param_plane(family: &Family, atlas: &ParamAtlas, stem: &Path) -> Result<(), String> {
    for ext in ["svg", "png"] {
        write_figure(&stem.with_extension(ext), SIZE, |root| {
            render(root, family, atlas)
        })
        .map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// The axes of a plane of boxes over `range` (x, y), labelled `desc`: the
/// parameter plane's and a reach paving's.
pub(super) fn box_plane<'b, 'a>(
    body: &'b Area<'a>,
    range: [[f64; 2]; 2],
    desc: [&str; 2],
) -> Result<ChartContext<'b, Figure<'a>, Cartesian2d<RangedCoordf64, RangedCoordf64>>, FigureError>
{
    let [rx, ry] = range;
    let (_, x_step) = super::nice_ticks(rx[0], rx[1], 8);
    let (_, y_step) = super::nice_ticks(ry[0], ry[1], 8);
    let mut chart = ChartBuilder::on(body)
        .margin(20)
        .x_label_area_size(50)
        .y_label_area_size(70)
        .build_cartesian_2d(rx[0]..rx[1], ry[0]..ry[1])
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(desc[0])
        .y_desc(desc[1])
        .x_label_formatter(&|v| tick_label(*v, x_step))
        .y_label_formatter(&|v| tick_label(*v, y_step))
        .label_style(("sans-serif", 16).into_font().color(&INK))
        .axis_style(INK)
        .draw()
        .map_err(draw_err)?;
    Ok(chart)
}

fn render(root: &Area, family: &Family, atlas: &ParamAtlas) -> Result<(), FigureError> {
    root.fill(&WHITE).map_err(draw_err)?;
    let [x, y] = [&atlas.axes[0], &atlas.axes[1]];
    let title = format!(
        "{}: certified parameter atlas over ({}, {})",
        family.base.name(),
        super::param_markup(&x.name),
        super::param_markup(&y.name)
    );
    let bold = ("sans-serif", 24).into_font().style(FontStyle::Bold);
    root.draw_text(&title, &bold.color(&INK), (16, 10))
        .map_err(draw_err)?;
    // The legend: one swatch per class present.
    let classes = classes_present(atlas);
    let colour = class_colour;
    let small = ("sans-serif", 17).into_font();
    for (k, c) in classes.iter().enumerate() {
        let text = class_text(*c, &atlas.sets);
        let (cx, cy) = (16 + 480 * (k as i32 % 2), 46 + 24 * (k as i32 / 2));
        root.draw(&Rectangle::new(
            [(cx, cy), (cx + 20, cy + 16)],
            colour(*c).filled(),
        ))
        .map_err(draw_err)?;
        root.draw(&Rectangle::new(
            [(cx, cy), (cx + 20, cy + 16)],
            INK.stroke_width(1),
        ))
        .map_err(draw_err)?;
        root.draw_text(&text, &small.color(&INK), (cx + 28, cy - 1))
            .map_err(draw_err)?;
    }
    let header = 60 + 24 * classes.len().div_ceil(2) as u32;
    let (w, h) = root.dim_in_pixel();
    let body = root.clone().shrink((0, header), (w, h - header));
    let (rx, ry) = (family.root[0], family.root[1]);
    let x_desc = super::param_markup(&x.name);
    let y_desc = super::param_markup(&y.name);
    let mut chart = box_plane(&body, [rx, ry], [&x_desc, &y_desc])?;
    let rects = atlas
        .leaves
        .iter()
        .filter(|l| !l.bounds.is_empty())
        .map(|l| {
            let (bx, by) = (l.bounds[0], l.bounds[1]);
            Rectangle::new(
                [(bx[0], by[1]), (bx[1], by[0])],
                colour(class(&l.sets)).filled(),
            )
        });
    chart.draw_series(rects).map_err(draw_err)?;
    // The scene's given point (`--param` or its defaults), when inside.
    let (px, py) = (family.given(0).mid(), family.given(1).mid());
    if (rx[0]..=rx[1]).contains(&px) && (ry[0]..=ry[1]).contains(&py) {
        chart
            .draw_series([
                Circle::new((px, py), 7, INK.stroke_width(2)),
                Circle::new((px, py), 2, INK.filled()),
            ])
            .map_err(draw_err)?;
    }
    Ok(())
}
