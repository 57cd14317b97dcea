//! A certified trajectory as a `trajectory` proof file: the equation, the
//! start box and the watched expressions as text, the end box or the first
//! event as claimed, and per step what a checker replays (the step's end
//! time, its a-priori box, the frame of its end set, and the cuts of its
//! time on which every watched expression keeps its sign).

use super::numbers::{decimal, hex, Round};
use super::statement::{definitions_for, in_proof_names};
use crate::motion::event::Watched;
use crate::motion::flow::sign;
use crate::motion::lohner::{point, StepData};
use crate::motion::{Motion, Stop, Tube, WatchItem};
use crate::params::report::exact_decimal;
use crate::scene::file::FileScene;
use inari::Interval;
use serde_json::{json, Map, Value};

/// Significant digits of claimed bounds.
const DIGITS: usize = 17;
/// Pieces of a step no narrower than this fraction of it.
const FINEST: f64 = 1.0 / (1u64 << 40) as f64;
/// Most cuts of one step (the format's limit).
const MAX_CUTS: usize = 1024;
/// A piece counts as proved only if the watched functions keep their signs
/// on its box widened by this much times the slack squared (relative to
/// the states' size): the checker's own enclosures, from the same series
/// but summed its own way, may be wider by far more than a few ulps.
const ROOM: f64 = 1e-14;

/// Why a tube has no proof.
#[derive(Debug, PartialEq, thiserror::Error)]
pub enum TrajectoryProofError {
    #[error("the scene has no [dynamics]")]
    NoDynamics,
    #[error(
        "the run ended before its end time without a proved event ({0}): there is nothing to prove"
    )]
    NotProved(String),
    #[error("the first events overlap ({0}): a proof states one")]
    Overlap(String),
    #[error("step {0}: the watched expressions keep their signs only on pieces finer than a proof holds")]
    Pieces(usize),
    #[error("the event's other watched expressions are not proved non-zero on its window")]
    Window,
    #[error("the arrival at the singular line is not proved from the proof's end set: {0}")]
    Arrival(String),
    #[error("a checker with looser rounding does not confirm the proof: {0}")]
    Unconfirmed(String),
}

/// The `trajectory` proof of `tube`, a run of `motion` (of `file`) to
/// `t_text`, leaving `room` ([`Room`]: claimed boxes widened by its slack
/// times their width and a few units in the last place on each side), so
/// that a checker whose enclosures differ within the format's accuracy
/// confirms them.
pub fn trajectory_proof(
    file: &FileScene,
    motion: &Motion,
    tube: &Tube,
    t_text: &str,
    room: Room,
) -> Result<Value, TrajectoryProofError> {
    let theta_ddot = file
        .dynamics_text()
        .ok_or(TrajectoryProofError::NoDynamics)?;
    let arrival = matches!(tube.stop, Stop::Arrival);
    let event = match &tube.stop {
        Stop::End | Stop::Arrival => None,
        Stop::Event if tube.events.len() == 1 => Some(&tube.events[0]),
        Stop::Event => {
            let kinds: Vec<&str> = tube.events.iter().map(|e| e.kind.as_str()).collect();
            return Err(TrajectoryProofError::Overlap(kinds.join(", ")));
        }
        _ => return Err(TrajectoryProofError::NotProved(tube.stop_text())),
    };
    let watched = motion.watched();
    let items = motion.watch_items();
    let watch: Vec<(String, String, &str)> = items.iter().map(|w| stated(file, *w)).collect();
    let signs: Vec<f64> = watched
        .iter()
        .map(|w| w.value(tube.start).and_then(sign).unwrap_or(0.0))
        .collect();
    let exprs = std::iter::once(theta_ddot).chain(file.regions.iter().map(|r| r.expr.as_str()));
    let definitions = definitions_for(file, exprs);

    let (slack, sign_room) = (room.slack, room.sign());
    let data = tube.step_data();
    let mut steps = Vec::with_capacity(data.len());
    // The event's time window and state as the proof states them.
    let mut crossing: Option<(Interval, [Interval; 2])> = None;
    for (j, (t0, d)) in data.iter().enumerate() {
        let last = j + 1 == data.len();
        let to = if last && event.is_none() && !arrival {
            json!("end")
        } else {
            json!(hex(t0 + d.h.inf()))
        };
        let (upto, window) = match event {
            Some(e) if last => (e.local[0], Some(e.local)),
            _ => (d.h.sup(), None),
        };
        let (cuts, proved) =
            cuts(d, &watched, &signs, upto, sign_room).ok_or(TrajectoryProofError::Pieces(j))?;
        // Before the event the window may start earlier, where the proved
        // prefix ends (the crossing is monotone on the longer window too, or
        // the checker says not); elsewhere the whole step must be proved.
        let window = match (window, event) {
            (Some(w), Some(e)) => {
                // a and b where the checker will see the signs, with room.
                let at = |x: f64| {
                    let y = roomy(
                        d.enclose(Interval::try_from((x, x)).unwrap_or(d.h)),
                        sign_room,
                    );
                    watched[e.watch].value(y).and_then(sign)
                };
                let s0 = signs[e.watch];
                let a = if w[2] >= proved && at(w[2]) == Some(s0) {
                    w[2]
                } else {
                    proved
                };
                // b: the narrowed end, the window's, or further on (the
                // window grows with it) until the other sign shows with room.
                let h = d.h.sup();
                let mut b = w[3];
                let mut step = w[1] - proved;
                while at(b) != Some(-s0) && b < h {
                    b = if b < w[1] { w[1] } else { (b + step).min(h) };
                    step *= 2.0;
                }
                let ab = Interval::try_from((a, b)).unwrap_or(d.h);
                crossing = Some((point(*t0) + ab, d.enclose(ab)));
                Some([proved, w[1].max(b), a, b])
            }
            _ if proved < upto => return Err(TrajectoryProofError::Pieces(j)),
            _ => None,
        };
        let b = between(d.apriori, d.apriori_outer, room.margin);
        let q = d.end_frame();
        let mut step = json!({
            "to": to,
            "apriori": [hex(b[0].inf()), hex(b[0].sup()), hex(b[1].inf()), hex(b[1].sup())],
            "frame": [hex(q[0][0]), hex(q[0][1]), hex(q[1][0]), hex(q[1][1])],
            "cuts": cuts.iter().map(|&c| hex(c)).collect::<Vec<_>>(),
        });
        if let Some(w) = window {
            step["window"] = json!(w.map(hex));
            // The others must keep their signs where g is monotone.
            let at = d.enclose(Interval::try_from((w[0], w[1])).unwrap_or(d.h));
            let crossing = event.map_or(usize::MAX, |e| e.watch);
            let others_hold = watched
                .iter()
                .zip(&signs)
                .enumerate()
                .all(|(k, (g, &s))| k == crossing || g.value(at).and_then(sign) == Some(s));
            if !others_hold {
                return Err(TrajectoryProofError::Window);
            }
        }
        steps.push(step);
    }

    let box_json = |x: Interval| widened(x, slack);
    let mut evidence =
        json!({ "order": data.first().map_or(2, |(_, d)| d.order()), "steps": steps });
    let outcome = match event {
        None if arrival => {
            let (t0, d) = data
                .last()
                .ok_or(TrajectoryProofError::NotProved(tube.stop_text()))?;
            let (e, proved) = motion
                .arrival_from(t0 + d.h.inf(), d.end.hull, slack)
                .map_err(TrajectoryProofError::Arrival)?;
            evidence["arrival"] = json!({
                "band": proved.band.map(hex),
                "root": proved.root.map(hex),
            });
            (
                "arrival",
                json!({
                    "time": padded(e.time),
                    "t": box_json(e.theta),
                    "w": box_json(e.theta_dot),
                }),
            )
        }
        None => (
            "end",
            json!({
                "time": t_text,
                "t": box_json(tube.end[0]),
                "w": box_json(tube.end[1]),
            }),
        ),
        Some(e) => {
            let (time, state) = crossing.unwrap_or((e.time, [e.theta, e.theta_dot]));
            (
                "event",
                json!({
                    "watch": watch.get(e.watch).map_or("", |w| w.0.as_str()),
                    "time": padded(time),
                    "t": box_json(state[0]),
                    "w": box_json(state[1]),
                }),
            )
        }
    };
    let mut statement = equation_statement(file, theta_ddot, &definitions);
    statement.insert(
        "start".into(),
        json!({
            "t": [exact_decimal(tube.start[0].inf() + 0.0), exact_decimal(tube.start[0].sup() + 0.0)],
            "w": [exact_decimal(tube.start[1].inf() + 0.0), exact_decimal(tube.start[1].sup() + 0.0)],
        }),
    );
    statement.insert("watch".into(), watch_json(&watch));
    statement.insert(outcome.0.into(), outcome.1);
    Ok(json!({
        "format": "detach-proof/1",
        "claim": "trajectory",
        "title": format!("{}: certified trajectory", file.name),
        "producer": super::producer(),
        "statement": statement,
        "evidence": evidence,
    }))
}

/// `scene`, `parameters`, `definitions` and `theta_ddot` of a statement.
pub(super) fn equation_statement(
    file: &FileScene,
    theta_ddot: &str,
    definitions: &[(String, String)],
) -> Map<String, Value> {
    let mut statement = Map::new();
    statement.insert("scene".into(), json!(file.name));
    statement.insert(
        "parameters".into(),
        file.params
            .texts()
            .into_iter()
            .map(|(k, v)| (k.to_string(), json!(v)))
            .collect::<Map<_, _>>()
            .into(),
    );
    statement.insert(
        "definitions".into(),
        json!(definitions
            .iter()
            .map(|(n, e)| json!([n, e]))
            .collect::<Vec<_>>()),
    );
    statement.insert("theta_ddot".into(), json!(in_proof_names(theta_ddot)));
    statement
}

/// The `watch` array of a statement.
pub(super) fn watch_json(watch: &[(String, String, &str)]) -> Value {
    json!(watch
        .iter()
        .map(|(n, e, m)| json!({ "name": n, "expr": e, "meaning": m }))
        .collect::<Vec<_>>())
}

/// The name, expression (in the proof's names, `{expr < 0}` for a region)
/// and meaning of one watched function.
pub(super) fn stated(file: &FileScene, item: WatchItem) -> (String, String, &'static str) {
    match item {
        WatchItem::Region(r) => (
            ["omega", "omega0"][r].to_string(),
            in_proof_names(&file.regions[r].expr),
            ["U=0", "N=0"][r],
        ),
        WatchItem::Side { axis, upper } => {
            let v = ["t", "w"][axis];
            let end = in_proof_names(&file.domain_text[axis][usize::from(upper)]);
            let name = format!("domain {v} {}", if upper { "high" } else { "low" });
            let expr = if upper {
                format!("({end}) - {v}")
            } else {
                format!("{v} - ({end})")
            };
            (name, expr, "domain")
        }
    }
}

/// The cuts of `[0, upto]` (leftmost pieces first, halved until every
/// watched function keeps its start sign on each, with room for a looser
/// checker), and where the proved prefix ends: `upto`, or the start of the
/// first piece that could not be proved. `None` past the format's limits.
fn cuts(
    d: &StepData,
    watched: &[&dyn Watched],
    signs: &[f64],
    upto: f64,
    room: f64,
) -> Option<(Vec<f64>, f64)> {
    cuts_where(d, upto, |x| {
        watched
            .iter()
            .zip(signs)
            .all(|(g, &s)| g.value(roomy(x, room)).and_then(sign) == Some(s))
    })
}

/// The cuts of `[0, upto]` into pieces on whose states `keeps` holds
/// (leftmost first, halved as needed), and where the proved prefix ends.
/// `None` past the format's limits.
pub(super) fn cuts_where(
    d: &StepData,
    upto: f64,
    keeps: impl Fn([Interval; 2]) -> bool,
) -> Option<(Vec<f64>, f64)> {
    if upto <= 0.0 || keeps(d.apriori) {
        return Some((Vec::new(), upto.max(0.0)));
    }
    let mut out = Vec::new();
    let mut stack = vec![(0.0, upto)];
    while let Some((p, q)) = stack.pop() {
        if keeps(d.enclose(Interval::try_from((p, q)).unwrap_or(Interval::ENTIRE))) {
            if q < upto {
                out.push(q);
            }
            if out.len() > MAX_CUTS {
                return None;
            }
            continue;
        }
        let m = 0.5 * (p + q);
        if q - p <= FINEST * upto || m <= p || m >= q {
            // The prefix ends at p: its last cut is not a cut any more.
            if out.last() == Some(&p) {
                out.pop();
            }
            return Some((out, p));
        }
        stack.push((m, q));
        stack.push((p, m));
    }
    Some((out, upto))
}

/// `x` widened by `room` relative to its size.
pub(super) fn roomy(x: [Interval; 2], room: f64) -> [Interval; 2] {
    x.map(|c| {
        let r = room * (1.0 + c.mag());
        Interval::try_from((c.inf() - r, c.sup() + r)).unwrap_or(Interval::ENTIRE)
    })
}

/// The box `inner + margin·(outer − inner)` at each end: the Picard
/// inclusion holds on every box between the two, and the margin is the
/// room a checker's set may take beyond ours. A wide set's end set is
/// often cut by the a-priori box, so a small margin keeps the checker's
/// set near ours; a large one leaves room for its enclosures of a point's.
pub(super) fn between(inner: [Interval; 2], outer: [Interval; 2], margin: f64) -> [Interval; 2] {
    std::array::from_fn(|i| {
        let lo = (1.0 - margin) * inner[i].inf() + margin * outer[i].inf();
        let hi = (1.0 - margin) * inner[i].sup() + margin * outer[i].sup();
        let (lo, hi) = (lo.min(inner[i].inf()), hi.max(inner[i].sup()));
        Interval::try_from((lo.max(outer[i].inf()), hi.min(outer[i].sup()))).unwrap_or(inner[i])
    })
}

/// `["lo", "hi"]`: `x` widened by `slack` times its width and a few units
/// in the last place on each side, as decimals rounded outward.
fn widened(x: Interval, slack: f64) -> Value {
    let d = slack * (x.wid() + f64::EPSILON * x.mag().max(1.0));
    json!([
        decimal(x.inf() - d, DIGITS, Round::Down),
        decimal(x.sup() + d, DIGITS, Round::Up),
    ])
}

/// `["lo", "hi"]`: `x` with 64 units in the last place of room on each
/// side (a looser checker's step start and sum land a few ulps outside).
fn padded(x: Interval) -> Value {
    let d = 64.0 * f64::EPSILON * x.mag().max(1.0);
    json!([
        decimal(x.inf() - d, DIGITS, Round::Down),
        decimal(x.sup() + d, DIGITS, Round::Up),
    ])
}

/// The room a proof leaves a checker whose enclosures differ from ours:
/// claimed boxes widened by `slack` times their width, sign tests on boxes
/// widened by `ROOM` (10⁻¹⁴)·slack², a-priori boxes with the margin `margin`
/// (`between`).
#[derive(Clone, Copy, Debug)]
pub struct Room {
    pub slack: f64,
    pub margin: f64,
}

impl Room {
    /// Sign tests pass on boxes widened by this much (relative).
    pub(super) fn sign(self) -> f64 {
        ROOM * self.slack * self.slack
    }
}

/// The rooms tried in turn until the format's loosest checkers confirm a
/// proof: each slack with a wide, then narrower a-priori margins.
pub(super) fn rooms() -> impl Iterator<Item = Room> {
    [1.0, 4.0, 16.0, 64.0].into_iter().flat_map(|slack| {
        [0.5, 1.0 / 32.0, 1.0 / 256.0]
            .into_iter()
            .map(move |margin| Room { slack, margin })
    })
}

/// Whether the format's strictest and loosest checkers (every operation 2
/// doubles beyond tightest, or the functions 4) all say VALID, or why not.
pub(super) fn confirmed(bytes: &[u8]) -> Result<(), String> {
    let functions = crate::check::Looseness {
        functions: 4,
        ..Default::default()
    };
    let reports = [
        crate::check::check_bytes(bytes),
        crate::check::with_loose_rounding(2, || crate::check::check_bytes(bytes)),
        crate::check::with_looseness(functions, || crate::check::check_bytes(bytes)),
    ];
    match reports.iter().find_map(|r| match r {
        Ok(r) if r.verdict == crate::check::Verdict::Valid => None,
        Ok(r) => Some(format!("{:?}", r.verdict)),
        Err(e) => Some(e.to_string()),
    }) {
        None => Ok(()),
        Some(why) => Err(why),
    }
}

/// The first of `build(room)` over [`rooms`] that [`confirmed`] accepts.
pub(super) fn least_room(
    mut build: impl FnMut(Room) -> Result<Value, TrajectoryProofError>,
) -> Result<Value, TrajectoryProofError> {
    let mut last = String::new();
    for room in rooms() {
        let proof = build(room)?;
        match confirmed(&super::to_bytes(&proof)) {
            Ok(()) => return Ok(proof),
            Err(why) => last = why,
        }
    }
    Err(TrajectoryProofError::Unconfirmed(last))
}

/// [`trajectory_proof`] with the least room a looser checker confirms.
pub fn checked_trajectory_proof(
    file: &FileScene,
    motion: &Motion,
    tube: &Tube,
    t_text: &str,
) -> Result<Value, TrajectoryProofError> {
    least_room(|room| trajectory_proof(file, motion, tube, t_text, room))
}
