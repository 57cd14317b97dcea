//! Certified trajectories: the validated steps ([`super::lohner`]) driven
//! from t = 0 to the end time or the first event, and the events proved on
//! them ([`super::event`]).

use super::event::{first_crossing, Crossing, Event, Watched};
use super::interval_json;
use super::lohner::{point, LohnerSet, StepData, StepFailure, Stepper, Vector};
use crate::scene::expr::TaylorTape;
use inari::Interval;
use serde_json::{json, Value};

/// How the integrator steps.
#[derive(Clone, Copy, Debug)]
pub struct FlowSettings {
    /// Order K of the Taylor method.
    pub order: usize,
    /// The remainder aimed at per step (absolute, or 10⁻⁶ of the set's
    /// width when that is larger); chooses the step size.
    pub tolerance: f64,
    /// Most steps before the run stops (and says so).
    pub max_steps: usize,
    /// A step shorter than this ends the run as undecided.
    pub min_step: f64,
    /// The longest step.
    pub max_step: f64,
    /// A set wider than this (in θ or θ̇) ends the run: its tube decides
    /// nothing more.
    pub max_width: f64,
    /// Integrate back in time: the tube's times are then times before the
    /// start (τ = −t).
    pub backward: bool,
}

impl Default for FlowSettings {
    fn default() -> Self {
        FlowSettings {
            order: 20,
            tolerance: 1e-16,
            max_steps: 100_000,
            min_step: 1e-9,
            max_step: 0.5,
            max_width: f64::INFINITY,
            backward: false,
        }
    }
}

/// Why the run stopped.
#[derive(Clone, Debug, PartialEq)]
pub enum Stop {
    /// It reached the end time.
    End,
    /// The first event of the watched set, proved first and transversal.
    Event,
    /// A crossing of a watched function could not be decided: the tube is
    /// valid up to where it ends, the reason says why it ends there.
    Undecided(String),
    /// No step, however short, could be certified (a singular line, a
    /// blow-up, a kink of θ̈).
    StepFailed(String),
    /// The step budget ran out.
    Budget,
    /// The singular line g = 0 of θ̈ = f/g is reached (the one event, of
    /// kind `V=0`; [`super::arrival`] proves it).
    Arrival,
}

/// A certified tube: the solutions from every initial state of the start
/// box, for as long as it lasts.
#[derive(Clone, Debug)]
pub struct Tube {
    /// Step start times (exact doubles) and their data, in order.
    steps: Vec<(f64, StepData)>,
    pub start: Vector,
    /// The events found (the first of the watched set; several when their
    /// windows overlap).
    pub events: Vec<Event>,
    /// The time and state at the tube's end (the end time, or the last
    /// certified step before the stop).
    pub end_time: Interval,
    pub end: Vector,
    pub stop: Stop,
}

/// One step of a tube, as drawn and reported.
#[derive(Clone, Copy, Debug)]
pub struct TubeStep {
    pub t0: f64,
    pub h: Interval,
    /// Every solution stays in this box during the step.
    pub apriori: Vector,
    /// The states at the step's end.
    pub end: Vector,
}

impl Tube {
    pub fn len(&self) -> usize {
        self.steps.len()
    }

    pub fn is_empty(&self) -> bool {
        self.steps.is_empty()
    }

    /// Each step's start time and data (what a proof replays).
    pub(crate) fn step_data(&self) -> &[(f64, StepData)] {
        &self.steps
    }

    pub fn steps(&self) -> impl Iterator<Item = TubeStep> + '_ {
        self.steps.iter().map(|(t0, d)| TubeStep {
            t0: *t0,
            h: d.h,
            apriori: d.apriori,
            end: d.end.hull,
        })
    }

    /// Why the run ended, in words.
    pub fn stop_text(&self) -> String {
        match &self.stop {
            Stop::End => "end time reached".into(),
            Stop::Event => "first event".into(),
            Stop::Undecided(why) => format!("undecided: {why}"),
            Stop::StepFailed(why) => format!("stopped: {why}"),
            Stop::Budget => "stopped: step budget reached".into(),
            Stop::Arrival => "reaches the singular line V = 0".into(),
        }
    }

    /// `{"events", "end", "stop", "steps"}` with intervals as exact decimal
    /// text; `t_text` is the end time as asked for, written when reached.
    pub fn json(&self, t_text: &str) -> Value {
        json!({
            "events": self.events.iter().map(|e| json!({
                "kind": e.kind, "time": interval_json(e.time), "theta": interval_json(e.theta),
                "theta_dot": interval_json(e.theta_dot), "slope": interval_json(e.slope),
            })).collect::<Vec<_>>(),
            "end": {
                "time": if self.stop == Stop::End { json!(t_text) } else { interval_json(self.end_time) },
                "theta": interval_json(self.end[0]), "theta_dot": interval_json(self.end[1]),
            },
            "stop": self.stop_text(),
            "steps": self.len(),
        })
    }

    /// [`Tube::band`] as rows `[t_lo, t_hi, θ_lo, θ_hi, θ̇_lo, θ̇_hi]`.
    pub fn band_rows(&self, pieces: usize) -> Vec<[f64; 6]> {
        self.band(pieces)
            .iter()
            .map(|(t, x)| {
                [
                    t.inf(),
                    t.sup(),
                    x[0].inf(),
                    x[0].sup(),
                    x[1].inf(),
                    x[1].sup(),
                ]
            })
            .collect()
    }

    /// Enclosures of the states over `pieces` equal sub-intervals of each
    /// step (a thin band to draw), with their time intervals.
    pub fn band(&self, pieces: usize) -> Vec<(Interval, Vector)> {
        let pieces = pieces.max(1);
        let mut out = Vec::with_capacity(self.steps.len() * pieces);
        for (t0, d) in &self.steps {
            let h = d.h.sup();
            for i in 0..pieces {
                let a = h * i as f64 / pieces as f64;
                let b = if i + 1 == pieces {
                    h
                } else {
                    h * (i + 1) as f64 / pieces as f64
                };
                let tau = Interval::try_from((a.min(b), b)).unwrap_or(d.h);
                out.push((point(*t0) + tau, d.enclose(tau)));
            }
        }
        out
    }
}

/// Why a run cannot start.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FlowError {
    #[error("the end time must be a finite number > 0")]
    EndTime,
    #[error("the initial state is not a bounded box")]
    Start,
    #[error(
        "the initial states are not inside one side of `{0}`: its value there contains 0 or is \
         undefined (start inside a cell, or leave `{0}` out of the watched events)"
    )]
    StartOnBoundary(String),
}

/// Integrates θ̈ = F from the box `start` over [0, `t_end`], stopping at
/// the first crossing of a `watched` function.
pub fn integrate(
    tape: &TaylorTape,
    settings: &FlowSettings,
    start: Vector,
    t_end: Interval,
    watched: &[&dyn Watched],
) -> Result<Tube, FlowError> {
    if !(t_end.is_common_interval() && t_end.inf() > 0.0) {
        return Err(FlowError::EndTime);
    }
    if !start.iter().all(|x| x.is_common_interval()) {
        return Err(FlowError::Start);
    }
    let mut signs = Vec::with_capacity(watched.len());
    for w in watched {
        match w.value(start).and_then(sign) {
            Some(s) => signs.push(s),
            None => return Err(FlowError::StartOnBoundary(w.kind().to_string())),
        }
    }
    let mut stepper = Stepper::new(tape, settings.order);
    if settings.backward {
        stepper = stepper.backward();
    }
    let mut set = LohnerSet::from_box(start);
    let mut t = 0.0_f64;
    let mut steps: Vec<(f64, StepData)> = Vec::new();
    let mut last_h = settings.max_step;
    // The midpoint's coefficients underestimate x_K over the a-priori box:
    // the factor learned on earlier steps shortens the suggested step.
    let mut scale = 1.0_f64;
    let order = stepper.order as f64;
    // Step sizes are multiples of a power of two small against the end
    // time, so that every start time is an exact sum.
    let quantum = 2f64.powi(t_end.sup().max(1.0).log2().ceil() as i32 - 44);
    let finish = |steps, set: LohnerSet, t: f64, events, stop| Tube {
        steps,
        start,
        events,
        end_time: if stop == Stop::End { t_end } else { point(t) },
        end: set.hull,
        stop,
    };
    loop {
        if t >= t_end.inf() {
            return Ok(finish(steps, set, t, vec![], Stop::End));
        }
        if steps.len() >= settings.max_steps {
            return Ok(finish(steps, set, t, vec![], Stop::Budget));
        }
        if set.hull.iter().any(|x| x.wid() > settings.max_width) {
            let why = format!(
                "the enclosure is wider than {} at t = {t}",
                settings.max_width
            );
            return Ok(finish(steps, set, t, vec![], Stop::StepFailed(why)));
        }
        // A wide set needs its remainder small against its own width only.
        let width = set.hull[0].wid().max(set.hull[1].wid());
        let tolerance = settings.tolerance.max(BOX_TOLERANCE * width);
        let suggested = stepper
            .suggest(&set, tolerance)
            .unwrap_or(settings.min_step);
        let mut h = (suggested * scale).min(settings.max_step).min(2.0 * last_h);
        let mut retries_for_event = 0;
        let mut retries_for_remainder = 0;
        let outcome = loop {
            let (hi, last) = step_size(h, quantum, t, t_end);
            if hi.sup() < settings.min_step && !last {
                break Err(StepFailure::NoApriori);
            }
            let max_remainder = if last || retries_for_remainder == REMAINDER_RETRIES {
                f64::INFINITY
            } else {
                REMAINDER_SLACK * tolerance
            };
            match stepper.step(&set, hi, max_remainder) {
                Err(StepFailure::RemainderAbove(size)) => {
                    // x_K over the a-priori box exceeds its value at the
                    // midpoint, which chose h: shorten the step (the
                    // remainder scales as h^K) and remember by how much.
                    let factor = (0.9 * (tolerance / size).powf(1.0 / order)).clamp(0.1, 0.9);
                    scale = (scale * factor).max(1e-3);
                    h = hi.inf() * factor;
                    retries_for_remainder += 1;
                }
                Ok(data) => {
                    let found = crossings(&data, watched, &signs, point(t), &mut stepper);
                    let unresolved = found.iter().any(|c| matches!(c, Crossing::Unresolved));
                    if unresolved && retries_for_event < 3 {
                        // The crossing may lie across the step's end: a
                        // shorter step puts it inside.
                        retries_for_event += 1;
                        h = hi.inf() * 0.6;
                        continue;
                    }
                    break Ok((data, last, found));
                }
                Err(_) if hi.sup() > settings.min_step => h = hi.inf() * 0.5,
                Err(f) => break Err(f),
            }
        };
        let (data, last, found) = match outcome {
            Ok(x) => x,
            Err(f) => {
                let why = match f {
                    StepFailure::NotAnalytic(n) => format!("no certified step at t = {t}: {n}"),
                    StepFailure::NoApriori => format!(
                        "no certified step at t = {t}: no a-priori enclosure for a step of {}",
                        settings.min_step
                    ),
                    StepFailure::Unbounded => {
                        format!("no certified step at t = {t}: the enclosures are unbounded")
                    }
                    StepFailure::RemainderAbove(size) => {
                        format!("no certified step at t = {t}: the remainder stays at {size:e}")
                    }
                };
                return Ok(finish(steps, set, t, vec![], Stop::StepFailed(why)));
            }
        };
        let t0 = t;
        last_h = data.h.inf();
        if retries_for_remainder == 0 {
            // Let the learned factor relax towards the suggestion again.
            scale = (scale * 1.1).min(1.0);
        }
        let events = found
            .into_iter()
            .filter_map(|c| match c {
                Crossing::Found(e) => Some(Ok(e)),
                Crossing::Undecided(why) => Some(Err(why)),
                Crossing::Unresolved => Some(Err(
                    "a watched function may cross 0 near a step's end and no step resolves it"
                        .to_string(),
                )),
                Crossing::None => None,
            })
            .collect::<Vec<_>>();
        if let Some(Err(why)) = events.iter().find(|e| e.is_err()) {
            // The tube is certified up to this step's start.
            return Ok(finish(steps, set, t0, vec![], Stop::Undecided(why.clone())));
        }
        set = data.end;
        t = if last { t_end.sup() } else { t0 + data.h.inf() };
        steps.push((t0, data));
        if !events.is_empty() {
            let events: Vec<Event> = events.into_iter().filter_map(Result::ok).collect();
            let first = first_events(events);
            let mut tube = finish(steps, set, t, vec![], Stop::Event);
            // The motion in contact ends at the event: the tube's end is there.
            tube.end_time = first[0].time;
            tube.end = first.iter().fold([Interval::EMPTY; 2], |s, e| {
                [s[0].convex_hull(e.theta), s[1].convex_hull(e.theta_dot)]
            });
            tube.events = first;
            return Ok(tube);
        }
    }
}

/// The step size as an interval: `h` rounded down to the quantum, or the
/// rest of the way to `t_end` (and whether it is the last step).
fn step_size(h: f64, quantum: f64, t: f64, t_end: Interval) -> (Interval, bool) {
    let q = ((h / quantum).floor() * quantum).max(quantum);
    if t + q >= t_end.inf() {
        (t_end - point(t), true)
    } else {
        (point(q), false)
    }
}

/// The remainder may exceed the tolerance this much before a step is
/// shortened, and a step is shortened for it so many times at most.
const REMAINDER_SLACK: f64 = 4.0;
const REMAINDER_RETRIES: usize = 4;
/// The remainder aimed at per step relative to the set's width.
const BOX_TOLERANCE: f64 = 1e-6;

/// The crossings in one step of each watched function.
fn crossings(
    data: &StepData,
    watched: &[&dyn Watched],
    signs: &[f64],
    t0: Interval,
    stepper: &mut Stepper,
) -> Vec<Crossing> {
    watched
        .iter()
        .zip(signs)
        .enumerate()
        .map(
            |(i, (w, &s))| match first_crossing(data, *w, s, t0, stepper) {
                Crossing::Found(e) => Crossing::Found(Event { watch: i, ..e }),
                c => c,
            },
        )
        .collect()
}

/// The events proved first: those whose windows start before every other
/// window ends.
fn first_events(mut events: Vec<Event>) -> Vec<Event> {
    events.sort_by(|a, b| a.time.inf().total_cmp(&b.time.inf()));
    let Some(earliest_end) = events.iter().map(|e| e.time.sup()).reduce(f64::min) else {
        return events;
    };
    events.retain(|e| e.time.inf() <= earliest_end);
    events
}

/// −1 or 1 by the sign of `x`, `None` when it may be 0.
pub(crate) fn sign(x: Interval) -> Option<f64> {
    if x.is_empty() {
        None
    } else if x.inf() > 0.0 {
        Some(1.0)
    } else if x.sup() < 0.0 {
        Some(-1.0)
    } else {
        None
    }
}
