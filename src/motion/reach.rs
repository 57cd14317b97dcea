//! Reach sets: the initial states of a window from which the motion reaches
//! a target (the first event of a watched set) within a time T, as a
//! certified paving of the window.
//!
//! Each box of initial states is integrated as one set ([`Motion::run`]):
//! a first event proved for the whole box, ending by T, proves that every
//! state of the box reaches the target (inner); a tube reaching T with no
//! watched function changing sign proves that none does (outer's
//! complement); otherwise the box is split at a recorded double, down to a
//! relative width, and what is left is undecided with the reason.

use super::flow::sign;
use super::{FlowSettings, Motion, Stop};
use crate::roots::isolate::split_point;
use inari::Interval;
use rayon::prelude::*;
use std::ops::ControlFlow;

/// What is proved of every initial state of a box.
#[derive(Clone, Debug, PartialEq)]
pub enum Fate {
    /// The motion reaches the target within T, in this time window.
    Reaches(Interval),
    /// The motion stays clear of the target over [0, T].
    Avoids,
    /// Neither is proved, for the reason given.
    Undecided(String),
}

/// One leaf of a reach paving: a box of initial states `[θ lo, θ hi] ×
/// [θ̇ lo, θ̇ hi]` (doubles) and what is proved of it.
#[derive(Clone, Debug)]
pub struct ReachLeaf {
    pub theta: [f64; 2],
    pub theta_dot: [f64; 2],
    pub fate: Fate,
}

/// How far a reach paving refines.
#[derive(Clone, Copy, Debug)]
pub struct ReachOptions {
    /// Boxes narrower than this fraction of the window (per axis) are not
    /// split again.
    pub eps: f64,
    /// Most leaves before the paving stops (and says so).
    pub max_boxes: usize,
    pub settings: FlowSettings,
}

impl Default for ReachOptions {
    fn default() -> Self {
        ReachOptions {
            eps: 1.0 / 256.0,
            max_boxes: 100_000,
            settings: FlowSettings {
                // A box's tube is wide: very many or very short steps do
                // not make it decide, and a blow-up is left sooner.
                max_steps: 2_000,
                min_step: 1e-6,
                ..FlowSettings::default()
            },
        }
    }
}

/// A reach paving and how it ended.
#[derive(Clone, Debug)]
pub struct ReachRun {
    pub window: [[f64; 2]; 2],
    pub leaves: Vec<ReachLeaf>,
    /// False when the box budget or a stop request ended it early: the
    /// leaves still cover the window, the open ones undecided.
    pub complete: bool,
}

impl ReachRun {
    /// Certified bounds on the area of the states that reach the target:
    /// that of the boxes proved to reach it (rounded down), and that of
    /// the boxes not proved to avoid it (rounded up).
    pub fn area_bounds(&self) -> (f64, f64) {
        let reaches = self.area_where(|f| matches!(f, Fate::Reaches(_)));
        let not_avoids = self.area_where(|f| !matches!(f, Fate::Avoids));
        (reaches.inf() + 0.0, not_avoids.sup() + 0.0)
    }

    /// The area of the leaves whose fate passes `keep`, in intervals.
    fn area_where(&self, keep: impl Fn(&Fate) -> bool) -> Interval {
        let exact = |x: f64| Interval::try_from((x, x)).unwrap_or(Interval::ENTIRE);
        let side = |x: [f64; 2]| exact(x[1]) - exact(x[0]);
        self.leaves
            .iter()
            .filter(|l| keep(&l.fate))
            .fold(exact(0.0), |total, l| {
                total + side(l.theta) * side(l.theta_dot)
            })
    }
}

/// Pieces per step in which the tube is read.
pub const PIECES: usize = 4;

/// What one box's integration decides. The tube is continued through the
/// target's boundary: a time b ≤ T at which every state of the tube has
/// the other sign of a watched g proves that each solution crossed g = 0
/// by b (g∘x is continuous and starts with the first sign); g of its first
/// sign over the whole tube to T proves that none reaches it.
fn decide(motion: &Motion, bx: [[f64; 2]; 2], t_end: Interval, settings: &FlowSettings) -> Fate {
    let start = bx.map(|[lo, hi]| Interval::try_from((lo, hi)).unwrap_or(Interval::ENTIRE));
    let watched = motion.watched();
    let mut signs = Vec::with_capacity(watched.len());
    for w in &watched {
        match w.value(start).and_then(sign) {
            Some(s) => signs.push(s),
            None => {
                return Fate::Undecided(format!(
                    "the box meets the target's boundary `{}`",
                    w.kind()
                ))
            }
        }
    }
    let tube = match motion.run_through(start, t_end, settings) {
        Ok(tube) => tube,
        Err(e) => return Fate::Undecided(e.to_string()),
    };
    // Per watched function, the first time it may leave its sign, and
    // whether it may be undefined or discontinuous on the tube before now
    // (then a sign change proves no crossing).
    let mut first_open: Vec<Option<f64>> = vec![None; watched.len()];
    let mut broken = vec![false; watched.len()];
    for (time, states) in tube.band(PIECES) {
        for (i, w) in watched.iter().enumerate() {
            let value = w.value(states);
            match value.and_then(sign) {
                Some(s) if s == signs[i] => {}
                Some(_) if time.sup() <= t_end.inf() && !broken[i] => {
                    let from = first_open[i].unwrap_or(time.inf());
                    let window = Interval::try_from((from, time.sup())).unwrap_or(time);
                    return Fate::Reaches(window);
                }
                _ => {
                    first_open[i].get_or_insert(time.inf());
                    broken[i] |= value.is_none();
                }
            }
        }
    }
    match (&tube.stop, first_open.iter().all(Option::is_none)) {
        // The singular line is a target: its arrival is proved by T.
        (Stop::Arrival, _) if tube.end_time.sup() <= t_end.inf() => {
            let from = first_open
                .iter()
                .flatten()
                .fold(tube.end_time.inf(), |a, &b| a.min(b));
            Fate::Reaches(Interval::try_from((from, tube.end_time.sup())).unwrap_or(tube.end_time))
        }
        (Stop::End, true) => Fate::Avoids,
        (Stop::End, false) => Fate::Undecided(
            "a target's function may vanish along the tube without a sign change proved".into(),
        ),
        (Stop::Budget, _) => Fate::Undecided("the step budget ran out before T".into()),
        // The reason's time and size vary per box; the kind is what a
        // summary counts.
        _ => Fate::Undecided(
            "the tube ends before T (wider than the window, or no certified step)".into(),
        ),
    }
}

/// How a box of the paving of `window` is split: the wider side relative
/// to the window, at a recorded double; `None` when no double lies inside.
pub fn split_of(bx: [[f64; 2]; 2], window: [[f64; 2]; 2]) -> Option<(usize, f64)> {
    let rel = [0, 1].map(|a| (bx[a][1] - bx[a][0]) / (window[a][1] - window[a][0]));
    let axis = if rel[1] > rel[0] { 1 } else { 0 };
    let m = split_point(bx[axis][0], bx[axis][1]);
    (m > bx[axis][0]).then_some((axis, m))
}

/// The integration settings of a box's tube in the paving of `window`: a
/// tube wider than the window decides nothing about its states.
pub fn tube_settings(window: [[f64; 2]; 2], opts: &ReachOptions) -> FlowSettings {
    FlowSettings {
        max_width: (window[0][1] - window[0][0]).max(window[1][1] - window[1][0]),
        ..opts.settings
    }
}

/// The reach paving of `window` (doubles, inside the domain) for the
/// events `motion` watches, within `t_end`. `level(depth, open, leaves)` is
/// called before each level; `Break` stops there with the open boxes
/// undecided.
pub fn reach(
    motion: &Motion,
    window: [[f64; 2]; 2],
    t_end: Interval,
    opts: &ReachOptions,
    mut level: impl FnMut(usize, usize, usize) -> ControlFlow<()>,
) -> ReachRun {
    let min_width = [0, 1].map(|a| (window[a][1] - window[a][0]) * opts.eps);
    let settings = tube_settings(window, opts);
    let mut open = vec![window];
    let mut leaves = Vec::new();
    let mut depth = 0;
    let mut complete = true;
    while !open.is_empty() {
        if level(depth, open.len(), leaves.len()).is_break()
            || leaves.len() + open.len() > opts.max_boxes
        {
            complete = false;
            let why = if leaves.len() + open.len() > opts.max_boxes {
                "the box budget ran out"
            } else {
                "stopped"
            };
            leaves.extend(open.drain(..).map(|bx| ReachLeaf {
                theta: bx[0],
                theta_dot: bx[1],
                fate: Fate::Undecided(why.into()),
            }));
            break;
        }
        let decided: Vec<([[f64; 2]; 2], Fate)> = open
            .par_iter()
            .map(|&bx| (bx, decide(motion, bx, t_end, &settings)))
            .collect();
        let mut next = Vec::new();
        for (bx, fate) in decided {
            let splittable = [0, 1].map(|a| bx[a][1] - bx[a][0] > min_width[a]);
            match fate {
                Fate::Undecided(_) if splittable.contains(&true) => {
                    if let Some((axis, m)) = split_of(bx, window) {
                        let (mut lo, mut hi) = (bx, bx);
                        lo[axis][1] = m;
                        hi[axis][0] = m;
                        next.push(lo);
                        next.push(hi);
                        continue;
                    }
                    leaves.push(ReachLeaf {
                        theta: bx[0],
                        theta_dot: bx[1],
                        fate,
                    });
                }
                fate => leaves.push(ReachLeaf {
                    theta: bx[0],
                    theta_dot: bx[1],
                    fate,
                }),
            }
        }
        open = next;
        depth += 1;
    }
    ReachRun {
        window,
        leaves,
        complete,
    }
}
