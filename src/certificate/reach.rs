//! A reach paving as a `reach` proof file: the window, T and the target as
//! text, the paving's tree (`tree/1`, one label per leaf: reaches, avoids,
//! undecided), and per decided leaf the steps of its box's tube that a
//! checker replays by the `trajectory` rules — up to a piece where a
//! watched expression has changed sign (reaches), or to T with every one
//! keeping its sign (avoids).

use super::numbers::{decimal, hex, Round};
use super::paving::{base64, BitWriter};
use super::statement::definitions_for;
use super::trajectory::{
    between, confirmed, cuts_where, equation_statement, rooms, roomy, stated, watch_json, Room,
    TrajectoryProofError,
};
use crate::motion::event::Watched;
use crate::motion::flow::sign;
use crate::motion::lohner::StepData;
use crate::motion::reach::{split_of, tube_settings, Fate, ReachOptions, ReachRun, PIECES};
use crate::motion::{Motion, Stop};
use crate::params::report::exact_decimal;
use crate::scene::file::FileScene;
use inari::Interval;
use rayon::prelude::*;
use serde_json::{json, Map, Value};
use std::collections::HashMap;

/// Significant digits of the claimed areas.
const DIGITS: usize = 17;

/// One leaf of the proof: its box, label bits and certificate.
struct ProvedLeaf {
    label: u64,
    certificate: Option<Value>,
}

/// The `reach` proof of `run` (of `motion`, `file`, within `t_end` written
/// `t_text`, made with `opts`). Each decided leaf's certificate is built
/// with the least room (slack and a-priori margin) that the format's
/// strictest and loosest checkers confirm on it alone; a leaf none
/// confirms is stated undecided (a weaker claim, still true). The
/// statement's areas are those of the proof's labels. Returns the proof
/// and how many decided leaves it states undecided.
pub fn reach_proof(
    file: &FileScene,
    motion: &Motion,
    run: &ReachRun,
    t_end: Interval,
    t_text: &str,
    opts: &ReachOptions,
) -> Result<(Value, usize), TrajectoryProofError> {
    let theta_ddot = file
        .dynamics_text()
        .ok_or(TrajectoryProofError::NoDynamics)?;
    let items = motion.watch_items();
    let watch: Vec<(String, String, &str)> = items.iter().map(|w| stated(file, *w)).collect();
    let exprs = std::iter::once(theta_ddot).chain(file.regions.iter().map(|r| r.expr.as_str()));
    let definitions = definitions_for(file, exprs);
    let settings = tube_settings(run.window, opts);
    let mut base = equation_statement(file, theta_ddot, &definitions);
    base.insert("watch".into(), watch_json(&watch));
    base.insert("time".into(), json!(t_text));

    let proved: Vec<ProvedLeaf> = run
        .leaves
        .par_iter()
        .map(|l| {
            let watched = motion.watched();
            let start = [l.theta, l.theta_dot]
                .map(|[lo, hi]| Interval::try_from((lo, hi)).unwrap_or(Interval::ENTIRE));
            let label = match l.fate {
                Fate::Reaches(_) => 0b01,
                Fate::Avoids => 0b10,
                Fate::Undecided(_) => 0b00,
            };
            let tube = match label {
                0b00 => None,
                _ => motion.run_through(start, t_end, &settings).ok(),
            };
            let data = tube.as_ref().map(|t| (t.step_data(), t.stop == Stop::End));
            let certificate = data.and_then(|(data, to_end)| {
                rooms().find_map(|room| {
                    let cert = match label {
                        0b01 => reaches(&watched, &watch, start, data, t_end, room),
                        _ if to_end => avoids(&watched, start, data, room),
                        _ => None,
                    }?;
                    leaf_confirmed(&base, [l.theta, l.theta_dot], label, &cert).then_some(cert)
                })
            });
            ProvedLeaf {
                label: if certificate.is_some() { label } else { 0b00 },
                certificate,
            }
        })
        .collect();
    let dropped = run
        .leaves
        .iter()
        .zip(&proved)
        .filter(|(l, p)| !matches!(l.fate, Fate::Undecided(_)) && p.label == 0)
        .count();

    // The tree in preorder, rebuilt by the paving's own split rule.
    let index: HashMap<[u64; 4], usize> = run
        .leaves
        .iter()
        .enumerate()
        .map(|(i, l)| (key([l.theta, l.theta_dot]), i))
        .collect();
    let mut bits = BitWriter::default();
    let mut nodes = 0u64;
    let mut certificates = Vec::new();
    let mut order: Option<Value> = None;
    let (mut inner, mut outer) = (zero(), zero());
    let mut stack = vec![run.window];
    while let Some(bx) = stack.pop() {
        nodes += 1;
        if let Some(&i) = index.get(&key(bx)) {
            let p = &proved[i];
            bits.push(0, 1);
            bits.push(p.label, 2);
            if let Some(c) = &p.certificate {
                let mut c = c.clone();
                // One order for the file, stated in the evidence.
                if let Some(k) = c.as_object_mut().and_then(|o| o.remove("order")) {
                    order.get_or_insert(k);
                }
                certificates.push(c);
            }
            let area = side(bx[0]) * side(bx[1]);
            if p.label == 0b01 {
                inner += area;
            }
            if p.label != 0b10 {
                outer += area;
            }
            continue;
        }
        let (axis, m) = split_of(bx, run.window).ok_or_else(|| {
            TrajectoryProofError::NotProved("the paving's leaves do not tile its window".into())
        })?;
        bits.push(0b110 | axis as u64, 3);
        bits.push(m.to_bits(), 64);
        let (mut lo, mut hi) = (bx, bx);
        lo[axis][1] = m;
        hi[axis][0] = m;
        stack.push(hi);
        stack.push(lo);
    }

    let mut statement = base;
    statement.insert("window".into(), window_json(run.window));
    statement.insert("leaves".into(), json!(run.leaves.len()));
    statement.insert(
        "area".into(),
        json!({
            "inner": decimal(inner.inf(), DIGITS, Round::Down),
            "outer": decimal(outer.sup(), DIGITS, Round::Up),
        }),
    );
    let order = order.unwrap_or(json!(settings.order));
    Ok((
        json!({
            "format": "detach-proof/1",
            "claim": "reach",
            "title": format!("{}: initial states reaching a target within T", file.name),
            "producer": super::producer(),
            "statement": statement,
            "evidence": {
                "order": order,
                "encoding": "tree/1",
                "nodes": nodes,
                "body": base64(&bits.into_bytes()),
                "certificates": certificates,
            },
        }),
        dropped,
    ))
}

fn window_json(w: [[f64; 2]; 2]) -> Value {
    json!({ "t": w[0].map(exact_decimal), "w": w[1].map(exact_decimal) })
}

/// Whether the checkers confirm `cert` on its own: a `reach` proof of the
/// leaf's box as the window, one leaf labelled `label`, no area claimed.
fn leaf_confirmed(base: &Map<String, Value>, bx: [[f64; 2]; 2], label: u64, cert: &Value) -> bool {
    let mut statement = base.clone();
    statement.insert("window".into(), window_json(bx));
    statement.insert("leaves".into(), json!(1));
    statement.insert("area".into(), json!({}));
    let mut cert = cert.clone();
    let order = cert
        .as_object_mut()
        .and_then(|o| o.remove("order"))
        .unwrap_or(Value::Null);
    let mut bits = BitWriter::default();
    bits.push(0, 1);
    bits.push(label, 2);
    let proof = json!({
        "format": "detach-proof/1",
        "claim": "reach",
        "statement": statement,
        "evidence": {
            "order": order,
            "encoding": "tree/1",
            "nodes": 1,
            "body": base64(&bits.into_bytes()),
            "certificates": [cert],
        },
    });
    confirmed(&super::to_bytes(&proof)).is_ok()
}

fn zero() -> Interval {
    Interval::try_from((0.0, 0.0)).unwrap_or(Interval::ENTIRE)
}

/// `hi − lo` of exact doubles, in intervals.
fn side([lo, hi]: [f64; 2]) -> Interval {
    let e = |x: f64| Interval::try_from((x, x)).unwrap_or(Interval::ENTIRE);
    e(hi) - e(lo)
}

fn key(b: [[f64; 2]; 2]) -> [u64; 4] {
    [b[0][0], b[0][1], b[1][0], b[1][1]].map(f64::to_bits)
}

/// One step of a certificate, as the `trajectory` format writes it.
fn step_json(to: Value, d: &StepData, cuts: &[f64], margin: f64) -> Value {
    let b = between(d.apriori, d.apriori_outer, margin);
    let q = d.end_frame();
    json!({
        "to": to,
        "apriori": [hex(b[0].inf()), hex(b[0].sup()), hex(b[1].inf()), hex(b[1].sup())],
        "frame": [hex(q[0][0]), hex(q[0][1]), hex(q[1][0]), hex(q[1][1])],
        "cuts": cuts.iter().map(|&c| hex(c)).collect::<Vec<_>>(),
    })
}

/// The steps of a tube proving that a watched expression changes sign by
/// T: per watched function in turn, steps with it defined on every piece
/// until a piece (a `PIECES`-th of a step) where it has the other sign
/// with room; that step is cut short at the piece's end.
fn reaches(
    watched: &[&dyn Watched],
    watch: &[(String, String, &str)],
    start: [Interval; 2],
    data: &[(f64, StepData)],
    t_end: Interval,
    room: Room,
) -> Option<Value> {
    let order = data.first()?.1.order();
    for (i, g) in watched.iter().enumerate() {
        let Some(s0) = g.value(start).and_then(sign) else {
            continue;
        };
        let defined = |x: [Interval; 2]| g.value(roomy(x, room.sign())).is_some();
        let mut steps = Vec::new();
        for (t0, d) in data {
            let h = d.h.sup();
            let hit = (1..=PIECES).find_map(|k| {
                let p = h * (k - 1) as f64 / PIECES as f64;
                let q = if k == PIECES {
                    d.h.inf()
                } else {
                    h * k as f64 / PIECES as f64
                };
                let to = t0 + q;
                let piece = Interval::try_from((p, q)).ok()?;
                let other =
                    g.value(roomy(d.enclose(piece), room.sign())).and_then(sign) == Some(-s0);
                (other && p < q && to > *t0 && to <= t_end.inf()).then_some((p, to))
            });
            if let Some((p, to)) = hit {
                let (mut cuts, upto) = cuts_where(d, p, defined)?;
                if upto < p {
                    break;
                }
                if p > 0.0 {
                    cuts.push(p);
                }
                steps.push(step_json(json!(hex(to)), d, &cuts, room.margin));
                return Some(json!({ "watch": watch[i].0, "order": order, "steps": steps }));
            }
            let (cuts, upto) = cuts_where(d, h, defined)?;
            if upto < h || t0 + d.h.inf() > t_end.inf() {
                break;
            }
            steps.push(step_json(json!(hex(t0 + d.h.inf())), d, &cuts, room.margin));
        }
    }
    None
}

/// The steps of a tube to T on which every watched expression keeps its
/// start sign, with room.
fn avoids(
    watched: &[&dyn Watched],
    start: [Interval; 2],
    data: &[(f64, StepData)],
    room: Room,
) -> Option<Value> {
    let signs: Vec<f64> = watched
        .iter()
        .map(|w| w.value(start).and_then(sign))
        .collect::<Option<_>>()?;
    let keeps = |x: [Interval; 2]| {
        watched
            .iter()
            .zip(&signs)
            .all(|(g, &s)| g.value(roomy(x, room.sign())).and_then(sign) == Some(s))
    };
    let order = data.first()?.1.order();
    let mut steps = Vec::with_capacity(data.len());
    for (j, (t0, d)) in data.iter().enumerate() {
        let h = d.h.sup();
        let (cuts, upto) = cuts_where(d, h, keeps)?;
        if upto < h {
            return None;
        }
        let to = if j + 1 == data.len() {
            json!("end")
        } else {
            json!(hex(t0 + d.h.inf()))
        };
        steps.push(step_json(to, d, &cuts, room.margin));
    }
    Some(json!({ "order": order, "steps": steps }))
}
