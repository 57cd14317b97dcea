//! An atlas as JSON for scripts, its 1-D thresholds, and the join of a
//! sharded run's parts.
//!
//! Numbers are decimal text: a box's ends as the user wrote them at the
//! root and as exact decimals of the split points inside; a threshold's
//! ends are split points. The thresholds are read off the boxes' JSON, so
//! that one run and the join of its shards give the same bytes.

use super::family::Family;
use super::model::{ParamLeaf, SetStatus};
use super::search::AtlasRun;
use serde_json::{json, Map, Value};

/// The exact decimal value of a double: the shortest text that reads back
/// as it when that text is exactly it, else its full expansion.
pub fn exact_decimal(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let short = format!("{x:e}");
    if crate::number::param::enclose_decimal("x", &short).is_ok_and(|e| e.is_singleton()) {
        return format!("{x}");
    }
    let full = format!("{x:.1100e}");
    let (m, e) = full.split_once('e').expect("exponent form");
    let m = m.trim_end_matches('0').trim_end_matches('.');
    format!("{m}e{e}")
}

/// The status of a set as JSON names it.
pub fn status_name(s: &SetStatus) -> &'static str {
    match s {
        SetStatus::Nonempty { .. } => "nonempty",
        SetStatus::Empty { .. } => "empty",
        SetStatus::Undecided { .. } => "undecided",
    }
}

/// The JSON of a run (of a shard: its boxes only, and `shard`).
pub fn atlas_json(
    family: &Family,
    run: &AtlasRun,
    eps: f64,
    shard: Option<(usize, usize)>,
) -> Value {
    let axes = &run.atlas.axes;
    let end = |axis: usize, k: usize, x: f64| -> String {
        if x == family.root[axis][k] {
            if k == 0 {
                axes[axis].lo.clone()
            } else {
                axes[axis].hi.clone()
            }
        } else {
            exact_decimal(x)
        }
    };
    let boxes: Vec<Value> = run
        .atlas
        .leaves
        .iter()
        .zip(&run.base)
        .filter(|(_, &b)| b != u32::MAX)
        .map(|(leaf, &base)| box_json(leaf, base, &run.atlas.sets, axes, &end))
        .collect();
    let fixed: Map<String, Value> = family
        .params
        .texts()
        .into_iter()
        .filter(|(n, _)| !axes.iter().any(|a| a.name == *n))
        .map(|(n, t)| (n.to_string(), Value::String(t)))
        .collect();
    let mut out = json!({
        "detach": crate::provenance(),
        "scene": family.base.name(),
    });
    let o = out.as_object_mut().expect("an object");
    if family.base.id().is_some() {
        o.insert("variant".into(), json!(family.variant.name()));
    }
    o.insert("params".into(), Value::Object(fixed));
    o.insert(
        "axes".into(),
        Value::Array(
            axes.iter()
                .map(|a| json!({"name": a.name, "lo": a.lo, "hi": a.hi}))
                .collect(),
        ),
    );
    o.insert("sets".into(), json!(run.atlas.sets));
    o.insert("eps".into(), json!(exact_decimal(eps)));
    o.insert("base_boxes".into(), json!(run.base_boxes));
    if let Some((k, n)) = shard {
        o.insert("shard".into(), json!({"k": k, "n": n}));
    }
    o.insert("complete".into(), json!(run.complete));
    let thresholds = thresholds(&boxes, axes.len(), &run.atlas.sets, &axes[0].name);
    o.insert("boxes".into(), Value::Array(boxes));
    o.insert("thresholds".into(), Value::Array(thresholds));
    out
}

fn box_json(
    leaf: &ParamLeaf,
    base: u32,
    sets: &[String],
    axes: &[super::model::ParamAxis],
    end: &dyn Fn(usize, usize, f64) -> String,
) -> Value {
    let params: Map<String, Value> = axes
        .iter()
        .enumerate()
        .map(|(i, a)| {
            let b = leaf.bounds[i];
            (a.name.clone(), json!([end(i, 0, b[0]), end(i, 1, b[1])]))
        })
        .collect();
    let mut status = Map::new();
    let mut witnesses = Map::new();
    let mut reasons = Map::new();
    for (name, s) in sets.iter().zip(&leaf.sets) {
        status.insert(name.clone(), json!(status_name(s)));
        match s {
            SetStatus::Nonempty { witness } => {
                let r = |x: [f64; 2]| json!([exact_decimal(x[0]), exact_decimal(x[1])]);
                witnesses.insert(
                    name.clone(),
                    json!({"theta": r(witness.theta), "theta_dot": r(witness.theta_dot)}),
                );
            }
            SetStatus::Empty { reasons: r, .. } => {
                reasons.insert(name.clone(), json!(format!("{} leaves", r.len())));
            }
            SetStatus::Undecided { reason } => {
                reasons.insert(name.clone(), json!(reason));
            }
        }
    }
    json!({
        "base": base,
        "params": params,
        "sets": status,
        "witnesses": witnesses,
        "notes": reasons,
    })
}

/// In one parameter, each change of a set's status between decided boxes:
/// `below` on every box from the run's start up to `enclosure[0]`, `above`
/// from `enclosure[1]` on, only undecided boxes between.
fn thresholds(boxes: &[Value], dims: usize, sets: &[String], param: &str) -> Vec<Value> {
    if dims != 1 {
        return Vec::new();
    }
    let mut out = Vec::new();
    for set in sets {
        // (status, lo, hi) of the decided boxes, in order.
        let decided: Vec<(&str, &Value, &Value)> = boxes
            .iter()
            .filter_map(|b| {
                let s = b["sets"][set].as_str()?;
                let r = &b["params"][param];
                (s != "undecided").then_some((s, &r[0], &r[1]))
            })
            .collect();
        for w in decided.windows(2) {
            let ((s0, _, hi0), (s1, lo1, _)) = (w[0], w[1]);
            if s0 != s1 {
                out.push(json!({
                    "set": set,
                    "param": param,
                    "below": s0,
                    "above": s1,
                    "enclosure": [hi0, lo1],
                }));
            }
        }
    }
    out
}

/// Joins the JSON of a sharded run's parts (any order) into the JSON one
/// run gives: every shard `k` of `n` exactly once, the same run otherwise.
pub fn merge(parts: &[Value]) -> Result<Value, String> {
    let first = parts.first().ok_or("no parts to merge")?;
    let n = first["shard"]["n"]
        .as_u64()
        .ok_or("the first part is not a shard (no `shard`)")? as usize;
    let same = |v: &Value| {
        let mut v = v.clone();
        if let Some(o) = v.as_object_mut() {
            for k in ["shard", "complete", "boxes", "thresholds"] {
                o.remove(k);
            }
        }
        v
    };
    let header = same(first);
    let mut seen = vec![None; n];
    for (i, p) in parts.iter().enumerate() {
        if same(p) != header {
            return Err(format!(
                "part {} is of another run (scene, parameters, sets, eps or version differ)",
                i + 1
            ));
        }
        let k = p["shard"]["k"]
            .as_u64()
            .ok_or(format!("part {} is not a shard", i + 1))?;
        if p["shard"]["n"].as_u64() != Some(n as u64) || k as usize >= n {
            return Err(format!("part {} is not one of {n} shards", i + 1));
        }
        if seen[k as usize].replace(i).is_some() {
            return Err(format!("shard {k}/{n} is given twice"));
        }
    }
    if let Some(k) = seen.iter().position(Option::is_none) {
        return Err(format!("shard {k}/{n} is missing"));
    }
    let mut boxes: Vec<(u64, usize, Value)> = Vec::new();
    for p in parts {
        let list = p["boxes"].as_array().ok_or("a part without `boxes`")?;
        for (j, b) in list.iter().enumerate() {
            boxes.push((
                b["base"].as_u64().ok_or("a box without `base`")?,
                j,
                b.clone(),
            ));
        }
    }
    boxes.sort_by_key(|(base, j, _)| (*base, *j));
    let boxes: Vec<Value> = boxes.into_iter().map(|(_, _, b)| b).collect();
    let complete = parts.iter().all(|p| p["complete"].as_bool() == Some(true));
    let sets: Vec<String> =
        serde_json::from_value(header["sets"].clone()).map_err(|e| e.to_string())?;
    let axes = header["axes"].as_array().ok_or("no `axes`")?;
    let param = axes[0]["name"].as_str().ok_or("an axis without a name")?;
    let thresholds = thresholds(&boxes, axes.len(), &sets, param);
    let mut out = header;
    let o = out.as_object_mut().ok_or("a part is not an object")?;
    // Keys in the order one run writes them.
    let mut joined = Map::new();
    for (k, v) in std::mem::take(o) {
        joined.insert(k.clone(), v);
        if k == "base_boxes" {
            joined.insert("complete".into(), json!(complete));
        }
    }
    joined.insert("boxes".into(), Value::Array(boxes));
    joined.insert("thresholds".into(), Value::Array(thresholds));
    Ok(Value::Object(joined))
}
