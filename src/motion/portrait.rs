//! Certified phase curves for pictures: the tubes through seed states,
//! forwards and backwards in time, until they leave a window, cut into
//! pieces small enough to draw.

use super::event::{Watched, WindowSide};
use super::flow::{integrate, FlowSettings};
use super::lohner::{point, Vector};
use crate::scene::file::FileScene;
use inari::Interval;

/// A certified curve: boxes in order along the motion (backwards part
/// first, reversed), each enclosing every state of its piece of time.
pub type BoxCurve = Vec<Vector>;

/// How far and how finely a curve is followed.
#[derive(Clone, Copy, Debug)]
pub struct CurveSettings {
    /// The pieces' boxes are at most this wide in θ and θ̇ (about a pixel).
    pub piece: [f64; 2],
    /// Time followed each way at most.
    pub time: f64,
    pub steps: usize,
}

/// The certified curve through each of `seeds` over `window` (`[[θ lo, θ
/// hi], [θ̇ lo, θ̇ hi]]`); a curve stops where it leaves the window, where
/// its band gets wider than a piece, or where no step is certified.
pub fn certified_curves(
    file: &FileScene,
    window: [[f64; 2]; 2],
    seeds: &[(f64, f64)],
    opts: &CurveSettings,
) -> Vec<BoxCurve> {
    let Some(tape) = file.dynamics_taylor() else {
        return Vec::new();
    };
    let sides: Vec<WindowSide> = (0..2)
        .flat_map(|axis| {
            [(window[axis][0], false), (window[axis][1], true)].map(|(at, upper)| WindowSide {
                axis,
                at: point(at),
                upper,
            })
        })
        .collect();
    let watched: Vec<&dyn Watched> = sides.iter().map(|s| s as &dyn Watched).collect();
    let t_end = point(opts.time);
    let base = FlowSettings {
        order: 14,
        // Far below a pixel, and steps long enough to be few.
        tolerance: 1e-10 * opts.piece[0].min(opts.piece[1]),
        max_steps: opts.steps,
        min_step: 1e-7,
        max_width: 0.5 * opts.piece[0].min(opts.piece[1]),
        ..FlowSettings::default()
    };
    let inside = |s: (f64, f64)| {
        s.0 > window[0][0] && s.0 < window[0][1] && s.1 > window[1][0] && s.1 < window[1][1]
    };
    seeds
        .iter()
        .filter(|s| inside(**s))
        .map(|&(t, w)| {
            let start = [point(t), point(w)];
            let mut both: Vec<BoxCurve> = [true, false]
                .iter()
                .map(|&backward| {
                    let settings = FlowSettings { backward, ..base };
                    integrate(&tape, &settings, start, t_end, &watched)
                        .map(|tube| pieces(&tube, opts.piece))
                        .unwrap_or_default()
                })
                .collect();
            let forward = both.pop().unwrap_or_default();
            let mut curve = both.pop().unwrap_or_default();
            curve.reverse();
            curve.extend(forward);
            curve
        })
        .filter(|c| c.len() > 1)
        .collect()
}

/// A tube's steps cut into pieces whose boxes are about `size` or less.
fn pieces(tube: &super::Tube, size: [f64; 2]) -> BoxCurve {
    let mut out = Vec::new();
    for (_, d) in tube.step_data() {
        let h = d.h.sup();
        let extent = (d.apriori[0].wid() / size[0]).max(d.apriori[1].wid() / size[1]);
        let n = extent.ceil().clamp(1.0, 256.0) as usize;
        for i in 0..n {
            let a = h * i as f64 / n as f64;
            let b = if i + 1 == n {
                h
            } else {
                h * (i + 1) as f64 / n as f64
            };
            let tau = Interval::try_from((a.min(b), b)).unwrap_or(d.h);
            out.push(d.enclose(tau));
        }
    }
    out
}
