//! What the picture of a claim shows, as data: each section registers its
//! pictures beside its checks (`FIGURES` in [`super::example1`],
//! [`super::smooth`], [`super::ice`]), and [`crate::figures::claims`] draws
//! them.

use super::witness::PairSet;
use crate::pave::{pave, PaveOptions, Paving, PhaseBox};
use inari::{DecInterval, Interval};

/// Axis names with units (rad, rad/s), for the paper-check figures.
pub const THETA_RAD: &str = "θ (rad)";
pub const THETA_DOT_UNITS: &str = "θ\u{307} (rad/s)";

/// One claim's picture.
pub enum ClaimFigure {
    Region(RegionFigure),
    Lines(Curves),
}

/// Two sets compared on a window: a paving of the pair (its root box is the
/// window), coloured by its leaves' labels, and the witness box.
pub struct RegionFigure {
    /// Markup (`Ω_{0}`, `θ\u{308}` …), as all text here.
    pub title: String,
    pub subtitle: String,
    pub paving: Box<Paving>,
    /// The two sets, in the paving's constraint order.
    pub names: [String; 2],
    pub mark: Option<PhaseBox>,
}

/// Curves and marked points on two axes.
pub struct Curves {
    pub title: String,
    pub subtitle: String,
    pub x: Axis,
    pub y: Axis,
    pub series: Vec<Series>,
    pub marks: Vec<Marks>,
    /// Draw the line y = 0 (listed in the legend).
    pub zero: bool,
}

/// An axis: its name and the range shown.
pub struct Axis {
    pub name: &'static str,
    pub range: [f64; 2],
    /// Ticks at multiples of π/4 (an angle axis).
    pub angle: bool,
}

/// One curve; a non-finite value breaks it.
pub struct Series {
    pub name: String,
    pub pts: Vec<(f64, f64)>,
    pub dashed: bool,
}

/// Points drawn with one marker.
pub struct Marks {
    pub name: String,
    pub pts: Vec<(f64, f64)>,
    pub shape: Shape,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    Dot,
    Ring,
    Square,
}

/// Two sets of the phase plane compared on a window, as functions.
pub type Region = Box<dyn Fn(Interval, Interval) -> [DecInterval; 2] + Sync>;

/// A claim's picture before its region, if any, is paved.
pub enum FigureSpec {
    Region {
        title: String,
        subtitle: String,
        f: Region,
        win: PhaseBox,
        names: [String; 2],
        mark: Option<PhaseBox>,
    },
    Lines(Curves),
}

/// What draws a claim's picture, given the certified witness box of a
/// region claim.
pub type FigureOf = fn(Option<PhaseBox>) -> FigureSpec;

/// Resolution and budget of the region pictures' pavings.
const REGION_EPS: f64 = 1.0 / 128.0;
const REGION_BOXES: usize = 200_000;

impl FigureSpec {
    /// The picture, its region paved.
    pub fn build(self) -> Result<ClaimFigure, String> {
        Ok(match self {
            FigureSpec::Region {
                title,
                subtitle,
                f,
                win,
                names,
                mark,
            } => {
                let set = PairSet {
                    f: |t: Interval, w: Interval| f(t, w),
                };
                let paving = pave(
                    &set,
                    win,
                    PaveOptions {
                        eps: REGION_EPS,
                        max_boxes: REGION_BOXES,
                    },
                    |_, _, _| {},
                )
                .map_err(|e| format!("paving failed: {e:?}"))?;
                ClaimFigure::Region(RegionFigure {
                    title,
                    subtitle,
                    paving: Box::new(paving),
                    names,
                    mark,
                })
            }
            FigureSpec::Lines(curves) => ClaimFigure::Lines(curves),
        })
    }
}

/// `n + 1` points evenly from `lo` to `hi`.
pub(super) fn grid(lo: f64, hi: f64, n: usize) -> impl Iterator<Item = f64> {
    (0..=n).map(move |i| lo + (hi - lo) * i as f64 / n as f64)
}

/// `name = value` pairs joined, as markup.
pub(super) fn params_text(names: &[&str], values: &[&str]) -> String {
    names
        .iter()
        .zip(values)
        .map(|(n, v)| format!("{n} = {v}"))
        .collect::<Vec<_>>()
        .join(", ")
}

pub(super) fn axis(name: &'static str, range: [f64; 2], angle: bool) -> Axis {
    Axis { name, range, angle }
}

pub(super) fn series(name: impl Into<String>, pts: Vec<(f64, f64)>) -> Series {
    Series {
        name: name.into(),
        pts,
        dashed: false,
    }
}

pub(super) fn marks(name: impl Into<String>, pts: Vec<(f64, f64)>, shape: Shape) -> Marks {
    Marks {
        name: name.into(),
        pts,
        shape,
    }
}

/// A number with a true minus sign.
pub(super) fn signed(v: f64) -> String {
    format!("{v}").replace('-', "−")
}

/// `(p_φ, p_ψ) = (a, b)` as markup.
pub(super) fn momenta(pf: &str, ps: &str) -> String {
    format!("(p_{{φ}}, p_{{ψ}}) = ({pf}, {ps})")
}

/// The witness box recorded in a result, if any.
pub fn witness_box(w: &serde_json::Value) -> Option<PhaseBox> {
    let b = w
        .get("witness")
        .and_then(|x| x.get("box"))
        .or_else(|| w.get("omega0_c0=0_vs_c0=1").and_then(|x| x.get("box")))?;
    let g = |k: &str, i: usize| b.get(k)?.get(i)?.as_f64();
    Some(PhaseBox {
        theta: [g("theta", 0)?, g("theta", 1)?],
        theta_dot: [g("theta_dot", 0)?, g("theta_dot", 1)?],
    })
}
