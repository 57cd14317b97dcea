//! What the page asks for, computed with the library's own calls: the
//! scene, its atlas at the page's resolution (rasterised conservatively,
//! with the area table of `detach pave`), the parameter plane of two
//! parameters, a certified trajectory, and the files of the view. Each
//! takes the request's JSON and the [`Ticket`] it runs under.

use super::jobs::{Cut, Ticket};
use crate::api::{
    Cell, Error, ErrorKind, FlowRequest, Method, ParamRequest, PaveRequest, Paved, Problem,
};
use crate::certificate::numbers::{area_text, Round};
use crate::figures::{rasterize, Class, PictureInfo};
use crate::number::param::ParamSpec;
use crate::scene::file::{SceneText, EMBEDDED};
use crate::scene::Scene;
use serde_json::{json, Value};
use std::path::Path;

/// Largest picture side the page may ask for, in pixels.
pub const MAX_SIDE: u32 = 2400;
/// Finest resolution the page may ask for (relative to the domain).
pub const MIN_EPS: f64 = 1.0 / 8192.0;

/// A request the page got wrong: answered 400 with the message.
pub type ViewError = String;

fn text_of(req: &Value, key: &str) -> Option<String> {
    req.get(key)?.as_str().map(str::to_string)
}

/// `{"mu": "1.5", …}` as `(name, text)` pairs; numbers stay text.
fn params_of(req: &Value) -> Result<Vec<(String, String)>, ViewError> {
    let Some(p) = req.get("params") else {
        return Ok(Vec::new());
    };
    let obj = p.as_object().ok_or("`params` must be an object")?;
    obj.iter()
        .map(|(k, v)| match v.as_str() {
            Some(t) => Ok((k.clone(), t.to_string())),
            None => Err(format!("parameter `{k}`: give its value as decimal text")),
        })
        .collect()
}

/// The problem a request names: `{"text": …}` (an edited or loaded scene
/// file) or `{"scene": NAME}`, with `params`.
pub fn problem_of(req: &Value) -> Result<Problem, Error> {
    let params = params_of(req).map_err(|e| Error::new(ErrorKind::InvalidParameter, e))?;
    let pairs: Vec<(&str, &str)> = params
        .iter()
        .map(|(n, t)| (n.as_str(), t.as_str()))
        .collect();
    match (text_of(req, "text"), text_of(req, "scene")) {
        (Some(text), name) => {
            let source = format!("{} (as edited)", name.as_deref().unwrap_or("scene"));
            Problem::from_toml(&text, &source, &pairs)
        }
        (None, Some(name)) => Problem::load(&name, &pairs),
        (None, None) => Err(Error::new(
            ErrorKind::UnknownName,
            "name a scene or give its text",
        )),
    }
}

/// A slider's range around a default: `[0, 2d]` for `d > 0`, `[2d, 0]` for
/// `d < 0`, `[0, 1]` for 0 (the text field takes any value).
fn slider_range(default: f64) -> [f64; 2] {
    match default {
        d if d > 0.0 => [0.0, 2.0 * d],
        d if d < 0.0 => [2.0 * d, 0.0],
        _ => [0.0, 1.0],
    }
}

fn spec_json(spec: &ParamSpec, value: &str) -> Value {
    let d: f64 = spec.default.parse().unwrap_or(0.0);
    json!({
        "name": spec.name, "default": spec.default, "value": value,
        "meaning": spec.meaning, "unit": spec.unit, "range": slider_range(d),
    })
}

/// The scene: its parameters (with slider ranges), domain, the file's text,
/// the class palette and the other scenes.
pub fn scene(req: &Value, start_text: Option<&str>) -> Result<Value, ViewError> {
    let problem = problem_of(req)?;
    let name = text_of(req, "scene");
    let text = match (&name, start_text, text_of(req, "text")) {
        (_, _, Some(t)) => t,
        (Some(n), _, None) => SceneText::embedded(n)
            .map(|t| t.text.to_string())
            .unwrap_or_default(),
        (None, Some(t), None) => t.to_string(),
        (None, None, None) => String::new(),
    };
    let values = problem.params.texts();
    let params: Vec<Value> = problem
        .params
        .specs
        .iter()
        .zip(&values)
        .map(|(s, (_, v))| spec_json(s, v))
        .collect();
    let b = problem.scene.domain().inner_box();
    Ok(json!({
        "name": problem.scene.name(),
        "title": problem.scene.title(),
        "params": params,
        "domain": {"theta": b[0], "theta_dot": b[1]},
        "text": text,
        "has_dynamics": problem.scene.has_dynamics(),
        "classes": Class::ALL.iter().map(|c| {
            let (r, g, b) = c.rgb();
            json!({"symbol": c.symbol(), "meaning": c.meaning(), "rgb": [r, g, b], "certified": c.is_cell()})
        }).collect::<Vec<_>>(),
        "scenes": Scene::names(),
        "embedded": EMBEDDED.len(),
    }))
}

fn eps_of(req: &Value) -> Result<f64, ViewError> {
    let eps = req.get("eps").and_then(Value::as_f64).unwrap_or(1.0 / 64.0);
    if !(MIN_EPS..=1.0).contains(&eps) {
        return Err(format!("eps must be in [1/8192, 1], got {eps}"));
    }
    Ok(eps)
}

fn size_of(req: &Value) -> Result<(u32, u32), ViewError> {
    let side = |k: &str| -> Result<u32, ViewError> {
        let v = req.get(k).and_then(Value::as_u64).unwrap_or(800);
        if !(16..=u64::from(MAX_SIDE)).contains(&v) {
            return Err(format!(
                "{k} must be between 16 and {MAX_SIDE} pixels, got {v}"
            ));
        }
        Ok(v as u32)
    };
    Ok((side("width")?, side("height")?))
}

/// The paving of the view: `detach pave`'s defaults but `eps`, cut by the
/// ticket (a newer request, or the time budget: then coarser and valid).
fn pave(problem: &Problem, req: &Value, ticket: &Ticket) -> Result<Paved, ViewError> {
    let method = match text_of(req, "method") {
        Some(m) => m.parse::<Method>()?,
        None => Method::default(),
    };
    let pave = PaveRequest {
        eps: eps_of(req)?,
        max_boxes: ticket.budget().leaves,
        method,
        ..PaveRequest::default()
    };
    Ok(problem.pave_with_progress(&pave, |_, _, _| ticket.flow())?)
}

fn cut_json(ticket: &Ticket) -> Value {
    match ticket.cut() {
        None => Value::Null,
        Some(Cut::Budget) => json!("budget"),
        Some(Cut::Superseded) => json!("superseded"),
    }
}

/// Runs of equal classes, row by row from the top: `[class, count, …]`
/// with class the index in [`Class::ALL`] (6: no leaf, outside the box).
fn run_lengths(pixels: &[Option<Class>]) -> Vec<u32> {
    let index = |c: &Option<Class>| match c {
        Some(c) => Class::ALL.iter().position(|x| x == c).unwrap_or(4) as u32,
        None => 6,
    };
    let mut out: Vec<u32> = Vec::new();
    for p in pixels {
        let k = index(p);
        match out.len() {
            n if n >= 2 && out[n - 2] == k => out[n - 1] += 1,
            _ => out.extend([k, 1]),
        }
    }
    out
}

/// The certified atlas at the page's size: classes per pixel (a pixel is
/// a cell only where leaves proved in it cover it) and the area table.
pub fn atlas(req: &Value, ticket: &Ticket) -> Result<Value, ViewError> {
    let problem = problem_of(req)?;
    let (w, h) = size_of(req)?;
    let paved = pave(&problem, req, ticket)?;
    let raster = rasterize(&paved.paving, w, h);
    let areas: Vec<Value> = paved
        .areas
        .iter()
        .map(|a| {
            json!({
                "name": a.cell.name(), "label": a.cell.label(),
                "inner": a.inner, "outer": a.outer,
                "inner_text": area_text(a.inner, Round::Down),
                "outer_text": area_text(a.outer, Round::Up),
                "how": a.how.describe(),
            })
        })
        .collect();
    let p = &paved.paving;
    Ok(json!({
        "width": w, "height": h,
        "rle": run_lengths(&raster.pixels),
        "domain": {"theta": p.root.theta, "theta_dot": p.root.theta_dot},
        "areas": areas,
        "eps": p.eps, "leaves": p.leaves.len(), "complete": p.complete, "method": paved_method(req),
        "stop": p.stop.describe(), "cut": cut_json(ticket),
        "params": problem.params.texts().into_iter().map(|(n, t)| (n.to_string(), json!(t))).collect::<serde_json::Map<_, _>>(),
        "elapsed_ms": ticket.elapsed().as_secs_f64() * 1e3,
    }))
}

/// The method named in the request, or the default, by name.
fn paved_method(req: &Value) -> String {
    text_of(req, "method").unwrap_or_else(|| Method::default().name().to_string())
}

/// `{"name", "lo", "hi"}` as `detach params --x NAME=LO:HI`.
fn axis_of(v: &Value) -> Result<crate::api::ParamAxis, ViewError> {
    let s = |k: &str| v.get(k).and_then(Value::as_str).unwrap_or("");
    Ok(ParamRequest::axis(&format!(
        "{}={}:{}",
        s("name"),
        s("lo"),
        s("hi")
    ))?)
}

/// The parameter plane of one or two parameters (`x`, `y`): per box, the
/// status of the two paradox cells (0 non-empty, 1 empty, 2 undecided).
pub fn param_plane(req: &Value, ticket: &Ticket) -> Result<Value, ViewError> {
    let problem = problem_of(req)?;
    let mut axes = vec![axis_of(req.get("x").ok_or("no `x` axis")?)?];
    if let Some(y) = req.get("y").filter(|y| !y.is_null()) {
        axes.push(axis_of(y)?);
    }
    if axes.len() == 2 && axes[0].name == axes[1].name {
        return Err("choose two different parameters".into());
    }
    let eps = req.get("eps").and_then(Value::as_f64).unwrap_or(1.0 / 32.0);
    if !(1.0 / 1024.0..=1.0).contains(&eps) {
        return Err(format!("eps must be in [1/1024, 1], got {eps}"));
    }
    let sets = vec![Cell::Omega0NotOmega, Cell::OmegaNotOmega0];
    let pr = ParamRequest {
        axes,
        sets: sets.clone(),
        eps: Some(eps),
        max_boxes: ticket.budget().leaves,
        shard: None,
    };
    let run = problem.param_atlas_with_progress(&pr, |_, _, _| ticket.flow())?;
    let leaves: Vec<Value> = run
        .run
        .atlas
        .leaves
        .iter()
        .filter(|l| !l.bounds.is_empty())
        .map(|l| {
            let s: Vec<usize> = l.sets.iter().map(crate::api::status_index).collect();
            json!({"b": l.bounds, "s": s})
        })
        .collect();
    Ok(json!({
        "axes": run.run.atlas.axes.iter().map(|a| json!({"name": a.name, "lo": a.lo, "hi": a.hi})).collect::<Vec<_>>(),
        "root": run.family.root,
        "sets": sets.iter().map(|c| c.label()).collect::<Vec<_>>(),
        "leaves": leaves,
        "thresholds": run.json().get("thresholds").cloned().unwrap_or(Value::Null),
        "interrupted": run.run.interrupted || !run.run.complete, "cut": cut_json(ticket),
        "elapsed_ms": ticket.elapsed().as_secs_f64() * 1e3,
    }))
}

/// The certified trajectory from `(theta, theta_dot)` (decimal text) to
/// time `t` or its first event: a thin band of boxes and the events.
pub fn flow(req: &Value) -> Result<Value, ViewError> {
    let problem = problem_of(req)?;
    if !problem.scene.has_dynamics() {
        return Err(format!(
            "scene `{}` has no [dynamics]",
            problem.scene.name()
        ));
    }
    let s = |k: &str| text_of(req, k).ok_or(format!("no `{k}`"));
    let (t, th, om) = (s("t")?, s("theta")?, s("theta_dot")?);
    let request = FlowRequest::parse(&th, &om, &t).map_err(|e| e.to_string())?;
    let tube = problem.flow(&request)?;
    let band = tube.band_rows(2);
    let mut out = tube.json(&t);
    out["band"] = json!(band);
    Ok(out)
}

/// A file of the view, built in `dir` (the server's own) and read back:
/// `svg`, `png`, `csv` (the leaves) or `proof` (checked VALID first).
pub fn download(req: &Value, ticket: &Ticket, dir: &Path) -> Result<(String, Vec<u8>), ViewError> {
    let kind = text_of(req, "kind").unwrap_or_default();
    let problem = problem_of(req)?;
    let paved = pave(&problem, req, ticket)?;
    if ticket.cut().is_some() {
        return Err("the view was not finished within its budget: nothing to download".into());
    }
    let stem = format!("{}-{}", problem.scene.name(), kind);
    match kind.as_str() {
        "svg" | "png" => {
            let (w, h) = size_of(req)?;
            let style = crate::figures::AtlasStyle {
                width: w.max(crate::figures::MIN_WIDTH),
                height: h.max(crate::figures::MIN_HEIGHT),
            };
            let info = PictureInfo {
                scene: &problem.scene,
                variant: problem.variant,
                params: problem.params.texts(),
                complete: paved.paving.complete,
                window: None,
            };
            let path = dir.join(format!("{}.{kind}", fresh_name()));
            let (svg, png) = if kind == "svg" {
                (Some(path.as_path()), None)
            } else {
                (None, Some(path.as_path()))
            };
            crate::figures::draw_atlas_files(&paved.paving, &info, &style, svg, png)
                .map_err(|e| e.to_string())?;
            let bytes = std::fs::read(&path).map_err(|e| e.to_string());
            std::fs::remove_file(&path).ok();
            Ok((format!("{stem}.{kind}"), bytes?))
        }
        "csv" => {
            let mut bytes = Vec::new();
            let p = &paved.paving;
            let provenance = crate::pave::export::provenance(
                problem.scene.name(),
                "detach explore",
                &problem.params.texts(),
                p,
            );
            crate::pave::export::write_leaves_csv(p, &provenance, &mut bytes)
                .map_err(|e| e.to_string())?;
            Ok((format!("{}-leaves.csv", problem.scene.name()), bytes))
        }
        "proof" => Ok((
            format!("{}-proof.json", problem.scene.name()),
            paved.checked_proof_bytes(&problem)?,
        )),
        other => Err(format!("unknown download `{other}` (svg, png, csv, proof)")),
    }
}

/// A file name no two requests share.
fn fresh_name() -> String {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    format!("view-{n}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_cover_every_pixel_in_order() {
        let px = [
            Some(Class::Persists),
            Some(Class::Persists),
            None,
            Some(Class::Undefined),
            Some(Class::Undefined),
            Some(Class::Persists),
        ];
        assert_eq!(run_lengths(&px), vec![0, 2, 6, 1, 5, 2, 0, 1]);
        assert!(run_lengths(&[]).is_empty());
    }

    #[test]
    fn sliders_reach_past_the_threshold_of_the_rod() {
        // The rod's μ defaults to 1.5; its paradoxes start at 4/3.
        assert_eq!(slider_range(1.5), [0.0, 3.0]);
        assert_eq!(slider_range(-2.0), [-4.0, 0.0]);
        assert_eq!(slider_range(0.0), [0.0, 1.0]);
    }

    #[test]
    fn requests_name_a_scene_or_give_its_text() {
        assert!(problem_of(&json!({})).is_err());
        let rod = problem_of(&json!({"scene": "painleve-rod", "params": {"mu": "0.5"}})).unwrap();
        assert_eq!(rod.params.get("mu").inf(), 0.5);
        let e = problem_of(&json!({"scene": "painleve-rod", "params": {"mu": 0.5}}))
            .err()
            .expect("refused");
        assert_eq!(e.kind(), ErrorKind::InvalidParameter);
        assert!(e.to_string().contains("decimal text"));
        let e = problem_of(&json!({"scene": "painleve-rod", "text": "name = \"x\"\n[domain\n"}));
        let e = e.err().expect("refused");
        assert_eq!(e.kind(), ErrorKind::SceneFile);
        assert!(
            e.to_string().contains("line 2"),
            "a TOML error names its line: {e}"
        );
    }
}
