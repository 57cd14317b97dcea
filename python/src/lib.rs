//! `detach._detach`: the library's front door ([`detach::api`]) for Python.
//! The pure-Python package (`python/detach/`) builds the numpy arrays,
//! pictures and sympy scenes on top; every number comes from here.

use detach::api::show::{self, Class};
use detach::api::{
    cell_named, status_index, verify as check_file, Fate, FlowRequest, How, Label, Method,
    ParamAtlasRun, ParamAxis, ParamRequest, PaveRequest, Paved, Problem, ReachOptions, ScanOptions,
    Tube, Until, Variant, Verdict,
};
use detach::api::{Error, ErrorKind};
use pyo3::create_exception;
use pyo3::exceptions::{
    PyFileNotFoundError, PyKeyboardInterrupt, PyOSError, PyPermissionError, PyRuntimeError,
    PyValueError,
};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::ops::ControlFlow;
use std::path::PathBuf;

/// One set's area: `(name, label, lower, upper, how)`.
type AreaRow = (String, String, f64, f64, String);

create_exception!(
    _detach,
    DetachError,
    PyValueError,
    "An input detach refuses (an option, a parameter, a name) or a computation that failed."
);
create_exception!(
    _detach,
    SceneFileError,
    DetachError,
    "A scene file (or TOML text) that is not one: its TOML, its tables, its formulas."
);
create_exception!(
    _detach,
    ProofRejected,
    DetachError,
    "The checker rejects a proof, or cannot check it; nothing was written."
);

/// The library's error as the Python exception of its kind: a failed read or
/// write is an `OSError` (its subclass by cause), the rest `DetachError`s.
/// The sentence names the library's fields, which are the Python arguments.
fn py_err(e: Error) -> PyErr {
    use std::io::ErrorKind as Io;
    let text = e.to_string();
    match e.kind() {
        ErrorKind::SceneFile => SceneFileError::new_err(text),
        ErrorKind::ProofRejected => ProofRejected::new_err(text),
        ErrorKind::Io(Io::NotFound) => PyFileNotFoundError::new_err(text),
        ErrorKind::Io(Io::PermissionDenied) => PyPermissionError::new_err(text),
        ErrorKind::Io(_) => PyOSError::new_err(text),
        _ => DetachError::new_err(text),
    }
}

/// An argument of this module refused: `name` and what follows it.
fn invalid(name: &'static str, rest: impl std::fmt::Display) -> PyErr {
    py_err(Error::invalid_option(name, rest))
}

/// Between two levels of a long computation, with the GIL taken for that
/// moment: Python's pending signals checked, then `progress(level, open,
/// done)` called when given; the first error (a signal's or the
/// callback's) kept in `signal`, and the computation stopped once there is
/// one.
fn interrupted(
    signal: &mut Option<PyErr>,
    progress: Option<&Py<PyAny>>,
    (level, open, done): (u32, usize, usize),
) -> ControlFlow<()> {
    if signal.is_none() {
        *signal = Python::attach(|py| {
            py.check_signals()?;
            if let Some(f) = progress {
                f.call1(py, (level, open, done))?;
            }
            Ok::<(), PyErr>(())
        })
        .err();
    }
    match signal {
        Some(_) => ControlFlow::Break(()),
        None => ControlFlow::Continue(()),
    }
}

/// A scene at given parameters in one reading of the paper.
#[pyclass(module = "detach._detach", frozen)]
struct Scene {
    problem: Problem,
}

/// A window `[lo, hi]` of text as the library takes it.
fn window_refs(w: &Option<[String; 2]>) -> Option<[&str; 2]> {
    w.as_ref().map(|[a, b]| [a.as_str(), b.as_str()])
}

fn pairs(params: &[(String, String)]) -> Vec<(&str, &str)> {
    params
        .iter()
        .map(|(n, v)| (n.as_str(), v.as_str()))
        .collect()
}

#[pymethods]
impl Scene {
    /// A paper scene or a shipped scene file by name; `variant` is
    /// `derived` or `printed`.
    #[staticmethod]
    fn load(name: &str, params: Vec<(String, String)>, variant: &str) -> PyResult<Scene> {
        let variant: Variant = variant
            .parse()
            .map_err(|e| invalid("variant", format!(": {e}")))?;
        let problem = Problem::load(name, &pairs(&params))
            .and_then(|p| p.in_reading(variant))
            .map_err(py_err)?;
        Ok(Scene { problem })
    }

    #[staticmethod]
    fn from_file(path: PathBuf, params: Vec<(String, String)>) -> PyResult<Scene> {
        let problem = Problem::from_file(&path, &pairs(&params)).map_err(py_err)?;
        Ok(Scene { problem })
    }

    #[staticmethod]
    fn from_toml(text: &str, source: &str, params: Vec<(String, String)>) -> PyResult<Scene> {
        let problem = Problem::from_toml(text, source, &pairs(&params)).map_err(py_err)?;
        Ok(Scene { problem })
    }

    #[getter]
    fn name(&self) -> String {
        self.problem.scene.name().to_string()
    }

    #[getter]
    fn title(&self) -> String {
        self.problem.scene.title().to_string()
    }

    #[getter]
    fn variant(&self) -> String {
        self.problem.variant.to_string()
    }

    /// `(name, decimal text)` of every parameter.
    #[getter]
    fn params(&self) -> Vec<(String, String)> {
        self.problem
            .params
            .texts()
            .into_iter()
            .map(|(n, t)| (n.to_string(), t))
            .collect()
    }

    /// `[[θ lo, θ hi], [θ̇ lo, θ̇ hi]]` as text.
    #[getter]
    fn domain_text(&self) -> [[String; 2]; 2] {
        self.problem.scene.domain_text()
    }

    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.problem.scene.warnings().to_vec()
    }

    /// Paves with the GIL released; Ctrl-C is seen between levels and stops
    /// the paving there: `(paving, interrupted)`.
    #[allow(clippy::too_many_arguments)]
    fn pave(
        &self,
        py: Python<'_>,
        eps: f64,
        max_boxes: usize,
        method: &str,
        region: Option<&str>,
        theta: Option<[String; 2]>,
        theta_dot: Option<[String; 2]>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<(Paving, bool)> {
        let req = PaveRequest {
            eps,
            max_boxes,
            method: method
                .parse::<Method>()
                .map_err(|e| invalid("method", format!(": {e}")))?,
            region: region.map(cell_named).transpose().map_err(py_err)?,
            theta,
            theta_dot,
        };
        let mut signal: Option<PyErr> = None;
        let paved = py.detach(|| {
            self.problem.pave_with_progress(&req, |l, o, n| {
                interrupted(&mut signal, progress.as_ref(), (l, o, n))
            })
        });
        let paved = paved.map_err(py_err)?;
        match signal {
            // Another exception raised by a signal handler goes on as it is.
            Some(e) if !e.is_instance_of::<PyKeyboardInterrupt>(py) => Err(e),
            s => Ok((Paving { paved }, s.is_some())),
        }
    }

    /// A certified parameter atlas with the GIL released: `axes` one or two
    /// `(name, lo, hi)` ranges as decimal text, `sets` by name, `eps` the
    /// resolution per axis (`None`: the command line's default). Ctrl-C is
    /// seen between levels and stops the search there: `(atlas,
    /// interrupted)`.
    fn param_atlas(
        &self,
        py: Python<'_>,
        axes: Vec<(String, String, String)>,
        sets: Vec<String>,
        eps: Option<f64>,
        max_boxes: usize,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<(ParamAtlas, bool)> {
        let req = ParamRequest {
            axes: axes
                .into_iter()
                .map(|(name, lo, hi)| ParamAxis { name, lo, hi })
                .collect(),
            sets: sets
                .iter()
                .map(|s| cell_named(s))
                .collect::<Result<_, _>>()
                .map_err(py_err)?,
            eps,
            max_boxes,
            shard: None,
        };
        let mut signal: Option<PyErr> = None;
        let run = py.detach(|| {
            self.problem.param_atlas_with_progress(&req, |l, o, n| {
                interrupted(&mut signal, progress.as_ref(), (l, o, n))
            })
        });
        let run = run.map_err(py_err)?;
        match signal {
            Some(e) if !e.is_instance_of::<PyKeyboardInterrupt>(py) => Err(e),
            s => Ok((ParamAtlas { run }, s.is_some())),
        }
    }

    /// A certified trajectory from `theta`, `theta_dot` (each `X` or
    /// `LO:HI`, decimal text) over `[0, t]`, stopped by `until` (as `detach
    /// flow --until`), with the GIL released.
    #[allow(clippy::too_many_arguments)]
    fn flow(
        &self,
        py: Python<'_>,
        theta: &str,
        theta_dot: &str,
        t: &str,
        until: &str,
        order: usize,
        proof: bool,
    ) -> PyResult<Trajectory> {
        let order = detach::api::flow_order(order).map_err(py_err)?;
        let mut request = FlowRequest::parse(theta, theta_dot, t).map_err(|e| py_err(e.into()))?;
        request.until = Until::parse_list(until).map_err(|e| py_err(e.into()))?;
        request.settings.order = order;
        let (tube, proof) = if proof {
            let (tube, p) = py
                .detach(|| self.problem.flow_with_proof(&request, t))
                .map_err(py_err)?;
            (tube, Some(p))
        } else {
            let tube = py.detach(|| self.problem.flow(&request)).map_err(py_err)?;
            (tube, None)
        };
        Ok(Trajectory {
            tube,
            t: t.to_string(),
            proof,
        })
    }

    /// The reach paving (as `detach reach`): `(leaves, complete)`, each
    /// leaf `(θ lo, θ hi, θ̇ lo, θ̇ hi, fate, t lo, t hi, reason)` with fate
    /// 0 reaches (in the time window), 1 avoids, 2 undecided.
    #[allow(clippy::too_many_arguments, clippy::type_complexity)]
    fn reach(
        &self,
        py: Python<'_>,
        t: &str,
        until: &str,
        eps: f64,
        max_boxes: usize,
        theta: Option<[String; 2]>,
        theta_dot: Option<[String; 2]>,
        proof: bool,
    ) -> PyResult<ReachNative> {
        let until = Until::parse_list(until).map_err(|e| py_err(e.into()))?;
        let opts = ReachOptions {
            eps,
            max_boxes,
            ..ReachOptions::default()
        };
        let run = py
            .detach(|| {
                self.problem
                    .reach(
                        window_refs(&theta),
                        window_refs(&theta_dot),
                        t,
                        &until,
                        &opts,
                    )
                    .and_then(|run| {
                        let proof = if proof {
                            let (p, dropped) = self.problem.reach_proof(&run, t, &until, &opts)?;
                            Some((p.to_string(), dropped))
                        } else {
                            None
                        };
                        Ok((run, proof))
                    })
            })
            .map_err(py_err)?;
        let (run, proof) = run;
        let leaves = run
            .leaves
            .iter()
            .map(|l| {
                let (fate, time, why) = match &l.fate {
                    Fate::Reaches(w) => (0, (w.inf(), w.sup()), String::new()),
                    Fate::Avoids => (1, (f64::NAN, f64::NAN), String::new()),
                    Fate::Undecided(why) => (2, (f64::NAN, f64::NAN), why.clone()),
                };
                let [t0, t1] = l.theta;
                let [w0, w1] = l.theta_dot;
                (t0, t1, w0, w1, fate, time.0, time.1, why)
            })
            .collect();
        Ok((leaves, run.complete, proof))
    }

    /// The equilibria and singular points (as `detach singular --json`),
    /// in the domain or a window of it: JSON text.
    fn singular_points(
        &self,
        py: Python<'_>,
        theta: Option<[String; 2]>,
        theta_dot: Option<[String; 2]>,
    ) -> PyResult<String> {
        let report = py
            .detach(|| {
                self.problem
                    .singular_points(window_refs(&theta), window_refs(&theta_dot))
            })
            .map_err(py_err)?;
        Ok(show::report_json(&report).to_string())
    }

    /// Where in `(name, lo, hi)` the number or type of the points changes
    /// (as `detach singular --x --json`): JSON text.
    fn singular_scan(
        &self,
        py: Python<'_>,
        axis: (String, String, String),
        eps: Option<f64>,
        theta: Option<[String; 2]>,
        theta_dot: Option<[String; 2]>,
    ) -> PyResult<String> {
        let (name, lo, hi) = axis;
        let mut opts = ScanOptions::default();
        if let Some(eps) = eps {
            opts.eps = detach::api::open_resolution(eps).map_err(py_err)?;
        }
        let axis = ParamAxis { name, lo, hi };
        let scan = py
            .detach(|| {
                self.problem.singular_scan(
                    axis,
                    window_refs(&theta),
                    window_refs(&theta_dot),
                    &opts,
                )
            })
            .map_err(py_err)?;
        // The boxes cover the range: its ends are theirs.
        let family_root = scan
            .boxes
            .iter()
            .fold([f64::INFINITY, f64::NEG_INFINITY], |r, b| {
                [r[0].min(b.lo), r[1].max(b.hi)]
            });
        Ok(show::scan_json(&scan, family_root).to_string())
    }

    /// Certified areas: `(name, label, lower, upper, how)` per set.
    fn area(&self, py: Python<'_>, digits: i32) -> PyResult<Vec<AreaRow>> {
        let areas = py.detach(|| self.problem.area(digits)).map_err(py_err)?;
        Ok(areas
            .into_iter()
            .map(|a| {
                (
                    a.cell.name().to_string(),
                    a.cell.label().to_string(),
                    a.inner,
                    a.outer,
                    a.how.describe(),
                )
            })
            .collect())
    }
}

/// A finished (possibly coarser) paving.
#[pyclass(module = "detach._detach", frozen)]
struct Paving {
    paved: Paved,
}

fn label_code(l: Label) -> u8 {
    match l {
        Label::ProvedIn => 0,
        Label::ProvedOut => 1,
        Label::Undecided => 2,
        Label::Undefined => 3,
    }
}

#[pymethods]
impl Paving {
    /// Leaf edges, `4 × leaves` doubles (θ lo, θ hi, θ̇ lo, θ̇ hi per leaf),
    /// native byte order.
    fn edges<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        let leaves = &self.paved.paving.leaves;
        let mut bytes = Vec::with_capacity(leaves.len() * 32);
        for l in leaves {
            for x in [
                l.bx.theta[0],
                l.bx.theta[1],
                l.bx.theta_dot[0],
                l.bx.theta_dot[1],
            ] {
                bytes.extend_from_slice(&x.to_ne_bytes());
            }
        }
        PyBytes::new(py, &bytes)
    }

    /// Per leaf, one label code per constraint (0 in, 1 out, 2 undecided,
    /// 3 undefined), then the index of its class in `palette()`.
    fn labels<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        let p = &self.paved.paving;
        let n = p.names.len();
        let mut bytes = Vec::with_capacity(p.leaves.len() * (n + 1));
        for l in &p.leaves {
            bytes.extend(l.labels.iter().map(|&x| label_code(x)));
            let class = Class::of_leaf(l);
            bytes.push(Class::ALL.iter().position(|&c| c == class).unwrap_or(0) as u8);
        }
        PyBytes::new(py, &bytes)
    }

    /// The constraints' names (`omega`, `omega0`).
    #[getter]
    fn names(&self) -> Vec<String> {
        self.paved.paving.names.clone()
    }

    /// `(name, label, inner, outer, how)` per set.
    fn areas(&self) -> Vec<AreaRow> {
        self.paved
            .areas
            .iter()
            .map(|a| {
                (
                    a.cell.name().to_string(),
                    a.cell.label().to_string(),
                    a.inner,
                    a.outer,
                    match a.how {
                        How::Empty(e) => e.describe().to_string(),
                        _ => String::new(),
                    },
                )
            })
            .collect()
    }

    #[getter]
    fn stop(&self) -> String {
        self.paved.paving.stop.to_string()
    }

    #[getter]
    fn stop_text(&self) -> String {
        self.paved.paving.stop.describe().to_string()
    }

    #[getter]
    fn complete(&self) -> bool {
        self.paved.paving.complete
    }

    #[getter]
    fn elapsed(&self) -> f64 {
        self.paved.elapsed_s
    }

    #[getter]
    fn eps(&self) -> f64 {
        self.paved.paving.eps
    }

    /// The root box `((θ lo, θ hi), (θ̇ lo, θ̇ hi))`.
    #[getter]
    fn root(&self) -> ([f64; 2], [f64; 2]) {
        let r = self.paved.paving.root;
        (r.theta, r.theta_dot)
    }

    /// Writes the paving as a proof file, once the checker says VALID.
    fn save_proof(&self, py: Python<'_>, scene: &Scene, path: PathBuf) -> PyResult<()> {
        py.detach(|| self.paved.write_proof(&scene.problem, &path))
            .map_err(py_err)
    }
}

/// A finished (possibly coarser) parameter atlas.
#[pyclass(module = "detach._detach", frozen)]
struct ParamAtlas {
    run: ParamAtlasRun,
}

#[pymethods]
impl ParamAtlas {
    /// `(name, lo, hi)` per varied parameter, as given.
    #[getter]
    fn axes(&self) -> Vec<(String, String, String)> {
        let a = &self.run.run.atlas.axes;
        a.iter()
            .map(|a| (a.name.clone(), a.lo.clone(), a.hi.clone()))
            .collect()
    }

    /// The sets decided, by name.
    #[getter]
    fn sets(&self) -> Vec<String> {
        self.run.run.atlas.sets.clone()
    }

    /// The root box, per axis the outer ends of the ranges' enclosures.
    #[getter]
    fn root(&self) -> Vec<[f64; 2]> {
        self.run.family.root.clone()
    }

    /// Box bounds, `2 × axes × boxes` doubles (lo, hi per axis per box),
    /// native byte order.
    fn bounds<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        let mut bytes = Vec::new();
        for l in self.leaves() {
            for b in &l.bounds {
                bytes.extend_from_slice(&b[0].to_ne_bytes());
                bytes.extend_from_slice(&b[1].to_ne_bytes());
            }
        }
        PyBytes::new(py, &bytes)
    }

    /// Per box, one status code per set (0 non-empty, 1 empty, 2
    /// undecided), then its class's index in `classes()`.
    fn statuses<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        let classes = show::classes_present(&self.run.run.atlas);
        let mut bytes = Vec::new();
        for l in self.leaves() {
            bytes.extend(l.sets.iter().map(|s| status_index(s) as u8));
            let c = show::param_class(&l.sets);
            bytes.push(classes.iter().position(|&k| k == c).unwrap_or(0) as u8);
        }
        PyBytes::new(py, &bytes)
    }

    /// The classes present, as the command line's plane draws them:
    /// `(text, "#rrggbb")`, undecided last.
    fn classes(&self) -> Vec<(String, String)> {
        let sets = &self.run.run.atlas.sets;
        show::classes_present(&self.run.run.atlas)
            .into_iter()
            .map(|c| {
                let rgb = show::class_colour(c);
                (
                    show::class_text(c, sets),
                    format!("#{:02x}{:02x}{:02x}", rgb.0, rgb.1, rgb.2),
                )
            })
            .collect()
    }

    /// `(set, label, non-empty, empty, undecided)` shares of the box.
    fn shares(&self) -> Vec<(String, String, f64, f64, f64)> {
        self.run
            .shares()
            .into_iter()
            .map(|s| {
                let label = cell_named(&s.set).map(|c| c.label()).unwrap_or_default();
                (s.set, label.to_string(), s.nonempty, s.empty, s.undecided)
            })
            .collect()
    }

    /// The atlas as `detach params --json` writes it.
    fn json(&self) -> String {
        self.run.json().to_string()
    }

    #[getter]
    fn complete(&self) -> bool {
        self.run.run.complete
    }

    #[getter]
    fn elapsed(&self) -> f64 {
        self.run.elapsed_s
    }

    #[getter]
    fn eps(&self) -> f64 {
        self.run.eps
    }

    /// Writes the atlas as a proof file, once the checker says VALID.
    fn save_proof(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        py.detach(|| self.run.write_proof(&path)).map_err(py_err)
    }
}

impl ParamAtlas {
    fn leaves(&self) -> impl Iterator<Item = &show::ParamLeaf> {
        let atlas = &self.run.run.atlas;
        atlas.leaves.iter().filter(|l| !l.bounds.is_empty())
    }
}

/// Checks a proof file: `(verdict, claim, why)` with verdict `VALID`,
/// `INVALID` or `UNCHECKED`.
/// A certified trajectory: its tube and the end time as asked for.
#[pyclass(module = "detach._detach", frozen)]
struct Trajectory {
    tube: Tube,
    t: String,
    /// The run's `trajectory` proof, when asked for.
    proof: Option<serde_json::Value>,
}

#[pymethods]
impl Trajectory {
    /// Writes the run's proof file, once the checker says VALID.
    fn save_proof(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let Some(proof) = &self.proof else {
            return Err(py_err(Error::new(
                ErrorKind::Unsupported,
                "this trajectory has no proof: run Scene.flow(..., proof=True)",
            )));
        };
        py.detach(|| detach::api::write_checked_proof(proof, &path))
            .map_err(py_err)
    }

    /// `{"events", "end", "stop", "steps"}` as `detach flow --json`.
    fn json(&self) -> String {
        self.tube.json(&self.t).to_string()
    }

    /// The tube as a thin band: per step `pieces` rows of 6 doubles (t lo,
    /// t hi, θ lo, θ hi, θ̇ lo, θ̇ hi), native byte order; each row's box
    /// holds every solution at every time of its time interval.
    fn band<'py>(&self, py: Python<'py>, pieces: usize) -> PyResult<Bound<'py, PyBytes>> {
        if !(1..=1000).contains(&pieces) {
            return Err(invalid(
                "pieces",
                format!(" must be in 1..=1000, got {pieces}"),
            ));
        }
        let rows = self.tube.band_rows(pieces);
        let mut bytes = Vec::with_capacity(rows.len() * 48);
        for v in rows.iter().flatten() {
            bytes.extend_from_slice(&v.to_ne_bytes());
        }
        Ok(PyBytes::new(py, &bytes))
    }
}

/// Reach leaves `(θ lo, θ hi, θ̇ lo, θ̇ hi, fate, t lo, t hi, reason)`,
/// whether the paving is complete, and its proof (JSON text and how many
/// decided leaves it states undecided) when asked for.
type ReachNative = (
    Vec<(f64, f64, f64, f64, u8, f64, f64, String)>,
    bool,
    Option<(String, usize)>,
);

/// Writes a proof given as JSON text to `path`, once the checker says VALID.
#[pyfunction]
fn write_proof(py: Python<'_>, text: &str, path: PathBuf) -> PyResult<()> {
    let proof: serde_json::Value = serde_json::from_str(text).map_err(|e| {
        py_err(Error::new(
            ErrorKind::ProofRejected,
            format!("not JSON: {e}"),
        ))
    })?;
    py.detach(|| detach::api::write_checked_proof(&proof, &path))
        .map_err(py_err)
}

#[pyfunction]
fn verify(py: Python<'_>, path: PathBuf) -> PyResult<(String, String, String)> {
    let report = py.detach(|| check_file(&path)).map_err(py_err)?;
    let (verdict, why) = match report.verdict {
        Verdict::Valid => ("VALID", String::new()),
        Verdict::Invalid(why) => ("INVALID", why),
        Verdict::Unchecked(why) => ("UNCHECKED", why),
    };
    Ok((verdict.to_string(), report.claim, why))
}

/// The atlas's classes as the CLI draws them: `(symbol, meaning, "#rrggbb")`,
/// the four cells, then undecided and undefined.
#[pyfunction]
fn palette() -> Vec<(String, String, String)> {
    Class::ALL
        .iter()
        .map(|c| {
            let (r, g, b) = c.rgb();
            (
                c.symbol().to_string(),
                c.meaning().to_string(),
                format!("#{r:02x}{g:02x}{b:02x}"),
            )
        })
        .collect()
}

/// `NAME=LO:HI` as `detach params --x` reads it: `(name, lo, hi)`.
#[pyfunction]
fn param_axis(text: &str) -> PyResult<(String, String, String)> {
    let a = ParamRequest::axis(text).map_err(py_err)?;
    Ok((a.name, a.lo, a.hi))
}

/// The leaf classes by name in `palette()` order: the four cells, then
/// `undecided` and `undefined`.
#[pyfunction]
fn class_names() -> Vec<&'static str> {
    Class::ALL
        .iter()
        .map(|&c| match c.cell() {
            Some(cell) => cell.name(),
            None if c == Class::Undefined => "undefined",
            None => "undecided",
        })
        .collect()
}

/// The library's defaults of each call, as JSON text: what the command line
/// uses when an option is not given.
#[pyfunction]
fn defaults() -> String {
    let pave = PaveRequest::default();
    let params = ParamRequest::default();
    let reach = ReachOptions::default();
    let area = detach::api::AreaRequest::default();
    let flow = FlowRequest::parse("0", "0", "1")
        .map(|r| r.settings.order)
        .unwrap_or(20);
    serde_json::json!({
        "pave": {"eps": pave.eps, "max_boxes": pave.max_boxes, "method": pave.method.name()},
        "param_atlas": {
            "max_boxes": params.max_boxes,
            "sets": params.sets.iter().map(|c| c.name()).collect::<Vec<_>>(),
        },
        "reach": {"eps": reach.eps, "max_boxes": reach.max_boxes},
        "flow": {"order": flow},
        "area": {"digits": area.digits},
    })
    .to_string()
}

/// The shipped scene names: the paper's, then the scene files.
#[pyfunction]
fn scene_names() -> Vec<String> {
    detach::api::Scene::names()
        .into_iter()
        .map(str::to_string)
        .collect()
}

/// A running `detach explore` page; stops when closed or collected.
#[pyclass(module = "detach._detach", frozen)]
struct Explorer {
    url: String,
    inner: std::sync::Mutex<Option<detach::api::Explorer>>,
}

#[pymethods]
impl Explorer {
    /// Starts the page for a scene by name or a scene file's text, at the
    /// given parameters, on 127.0.0.1 and `port` (0: any free one).
    #[new]
    fn new(
        scene: Option<String>,
        text: Option<String>,
        params: Vec<(String, String)>,
        port: u16,
    ) -> PyResult<Explorer> {
        let config = detach::api::ExploreConfig {
            scene,
            scene_text: text,
            params,
            port,
            ..Default::default()
        };
        let e = detach::api::Explorer::start(config).map_err(py_err)?;
        Ok(Explorer {
            url: e.url.clone(),
            inner: std::sync::Mutex::new(Some(e)),
        })
    }

    #[getter]
    fn url(&self) -> String {
        self.url.clone()
    }

    /// The scene and parameters of the page's last atlas, as JSON text.
    fn state(&self) -> PyResult<String> {
        let guard = self
            .inner
            .lock()
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        match guard.as_ref() {
            Some(e) => Ok(e.state().to_string()),
            None => Err(PyRuntimeError::new_err("this explorer is stopped")),
        }
    }

    /// Stops serving (the page stops answering).
    fn stop(&self, py: Python<'_>) {
        let taken = self.inner.lock().ok().and_then(|mut g| g.take());
        py.detach(move || drop(taken));
    }
}

#[pymodule]
fn _detach(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Scene>()?;
    m.add_class::<Paving>()?;
    m.add_class::<ParamAtlas>()?;
    m.add_class::<Trajectory>()?;
    m.add_class::<Explorer>()?;
    m.add_function(wrap_pyfunction!(write_proof, m)?)?;
    m.add_function(wrap_pyfunction!(verify, m)?)?;
    m.add_function(wrap_pyfunction!(palette, m)?)?;
    m.add_function(wrap_pyfunction!(scene_names, m)?)?;
    m.add_function(wrap_pyfunction!(param_axis, m)?)?;
    m.add_function(wrap_pyfunction!(class_names, m)?)?;
    m.add_function(wrap_pyfunction!(defaults, m)?)?;
    m.add("VERSION", detach::LONG_VERSION)?;
    m.add("DetachError", m.py().get_type::<DetachError>())?;
    m.add("SceneFileError", m.py().get_type::<SceneFileError>())?;
    m.add("ProofRejected", m.py().get_type::<ProofRejected>())?;
    Ok(())
}
