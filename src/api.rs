//! The library in four steps, as the command line takes them: a scene
//! ([`Problem`]), its paving ([`Problem::pave`]), certified areas
//! ([`Problem::area`]), a proof file and its check ([`Paved::write_proof`],
//! [`verify`]); and over a range of parameters, a certified parameter atlas
//! ([`Problem::param_atlas`], [`ParamAtlasRun::write_proof`]). The numbers
//! are those of `detach pave`, `detach area`, `detach params` and `detach
//! verify` on the same input. The paper's internals (its claims and
//! figures, the paving engine's parts) stay in their modules.
//!
//! ```
//! use detach::api::{PaveRequest, Problem};
//!
//! let rod = Problem::load("painleve-rod", &[("mu", "1.5")])?;
//! let paved = rod.pave(&PaveRequest { eps: 1.0 / 64.0, ..PaveRequest::default() })?;
//! for a in &paved.areas {
//!     assert!(a.inner <= a.outer);
//! }
//! # Ok::<(), detach::api::Error>(())
//! ```

mod error;

pub use error::{Error, ErrorKind};

use crate::area::{certified_areas, AreasError, Provenance};
use crate::motion::{self, singular};
use crate::number::param::{parse_assignment, ParamSet};
use crate::params::report::atlas_json;
use crate::params::{search, AtlasRun, DecideOptions, Family, SearchOptions, Source};
use crate::pave::{pave_scene_method, standard_cell_bounds, MethodOptions, PaveOptions};
use crate::quadrature::AreaOptions;
use crate::scene::file::SceneFault;
use crate::scene::{Domain, SceneFileError, SceneText};
use std::path::Path;
use std::time::Instant;

pub use crate::check::{Report, Verdict};
pub use crate::motion::reach::{Fate, ReachLeaf, ReachOptions, ReachRun};
pub use crate::motion::singular::{Report as SingularReport, Scan, ScanOptions};
pub use crate::motion::{FlowRequest, Tube, Until};
pub use crate::params::model::{ParamAxis, SetStatus};
pub use crate::params::Shard;
pub use crate::pave::{
    Emptiness, Label, Leaf, LevelFlow, Method, Paving, PerConstraint, PhaseBox, StopReason,
};
pub use crate::scene::{Cell, Scene, Variant};

/// What the library hands out for drawing and for JSON, for a front end
/// that draws itself (the Python package): a leaf's class and its colour,
/// a parameter atlas's classes, and the `--json` forms of singular points.
pub mod show {
    pub use crate::figures::params::{
        class as param_class, class_colour, class_text, classes_present,
    };
    pub use crate::figures::Class;
    pub use crate::motion::singular::{report_json, scan_json};
    pub use crate::params::model::ParamLeaf;
}

/// The local page of `detach explore`.
#[cfg(feature = "explore")]
pub use crate::explore::{Config as ExploreConfig, Explorer};

/// Most leaves one paving may be asked for (about 230 bytes each while
/// paving), as `detach pave --max-boxes` allows.
pub const MAX_LEAVES: usize = 20_000_000;

/// A scene at given parameters in one reading of the paper: what is paved.
pub struct Problem {
    pub scene: Scene,
    /// Every parameter's value, as decimal text and its enclosure.
    pub params: ParamSet,
    /// The reading of the paper (a scene file has one: `Derived`).
    pub variant: Variant,
    /// Where the scene came from: a parameter atlas rebuilds it per box.
    source: Source,
}

/// `name=value` pairs as owned strings.
fn owned(params: &[(&str, &str)]) -> Vec<(String, String)> {
    params
        .iter()
        .map(|(n, v)| (n.to_string(), v.to_string()))
        .collect()
}

impl Problem {
    /// A scene by name (`viscous-disc`, `smooth-disc`, `ice-disc`, or a
    /// shipped scene file such as `painleve-rod`), its parameters given as
    /// decimal text (`("mu", "1.5")`), in the derived reading.
    ///
    /// ```
    /// let disc = detach::api::Problem::load("ice-disc", &[("c0", "1")])?;
    /// assert_eq!(disc.scene.name(), "ice-disc");
    /// assert!(detach::api::Problem::load("ice-disc", &[("c0", "one")]).is_err());
    /// # Ok::<(), detach::api::Error>(())
    /// ```
    pub fn load(name: &str, params: &[(&str, &str)]) -> Result<Problem, Error> {
        let source = Source::by_name(name).map_err(|m| Error::new(ErrorKind::UnknownName, m))?;
        let (scene, params) = source.scene(&owned(params))?;
        Ok(Problem {
            scene,
            params,
            variant: Variant::Derived,
            source,
        })
    }

    /// The same in another reading: `Printed` applies to the paper's scenes
    /// only.
    pub fn in_reading(mut self, variant: Variant) -> Result<Problem, Error> {
        if self.scene.id().is_none() {
            one_reading(variant)?;
        }
        self.variant = variant;
        Ok(self)
    }

    /// A scene file (TOML, `docs/scene-files.md`).
    pub fn from_file(path: &Path, params: &[(&str, &str)]) -> Result<Problem, Error> {
        let text = SceneText::read(path)?;
        let f = text.compile(&owned(params))?;
        Ok(Problem {
            params: f.params.clone(),
            scene: Scene::File(Box::new(f)),
            variant: Variant::Derived,
            source: Source::File(text),
        })
    }

    /// A scene file's text; `source` names it in messages.
    ///
    /// ```
    /// let text = r#"
    /// name = "ball"
    /// [domain]
    /// theta = ["0", "1"]
    /// theta_dot = ["-1", "1"]
    /// [parameters]
    /// g = { value = "9.81" }
    /// [regions]
    /// omega = "theta_dot^2 < g"
    /// "#;
    /// let ball = detach::api::Problem::from_toml(text, "ball.toml", &[("g", "1")])?;
    /// assert_eq!(ball.params.texts(), vec![("g", "1".to_string())]);
    /// # Ok::<(), detach::api::Error>(())
    /// ```
    pub fn from_toml(text: &str, source: &str, params: &[(&str, &str)]) -> Result<Problem, Error> {
        let text = SceneText {
            file: source.to_string(),
            text: text.to_string().into(),
        };
        let f = text.compile(&owned(params))?;
        Ok(Problem {
            params: f.params.clone(),
            scene: Scene::File(Box::new(f)),
            variant: Variant::Derived,
            source: Source::File(text),
        })
    }

    /// The domain, or the part of it in the windows (`[lo, hi]` as decimal
    /// text, `pi`, `pi/N`), with the window ends clipped to the domain.
    pub fn domain(
        &self,
        theta: Option<[&str; 2]>,
        theta_dot: Option<[&str; 2]>,
    ) -> Result<(Domain, Vec<String>), Error> {
        Ok(self.scene.domain().window_clipped(theta, theta_dot)?)
    }

    /// Paves Ω and Ω₀ as `detach pave` does.
    pub fn pave(&self, req: &PaveRequest) -> Result<Paved, Error> {
        self.pave_with_progress(req, |_, _, _| {})
    }

    /// [`Problem::pave`], calling `progress(level, open boxes, leaves)` once
    /// per level; a [`std::ops::ControlFlow::Break`] from it stops the
    /// paving there with a valid, coarser result ([`StopReason::Interrupted`]).
    ///
    /// ```
    /// use detach::api::{PaveRequest, Problem, StopReason};
    /// use std::ops::ControlFlow;
    ///
    /// let rod = Problem::load("painleve-rod", &[])?;
    /// let req = PaveRequest { eps: 1.0 / 4096.0, ..PaveRequest::default() };
    /// let paved = rod.pave_with_progress(&req, |level, _, _| {
    ///     if level < 6 { ControlFlow::Continue(()) } else { ControlFlow::Break(()) }
    /// })?;
    /// assert_eq!(paved.paving.stop, StopReason::Interrupted);
    /// # Ok::<(), detach::api::Error>(())
    /// ```
    pub fn pave_with_progress<F: LevelFlow>(
        &self,
        req: &PaveRequest,
        progress: impl FnMut(u32, usize, usize) -> F,
    ) -> Result<Paved, Error> {
        let opts = req.options()?;
        let (domain, _) = self.domain(window(&req.theta), window(&req.theta_dot))?;
        let mo = match req.region {
            None => MethodOptions::new(req.method),
            Some(cell) => MethodOptions::for_cell(req.method, &cell.spec()),
        };
        let start = Instant::now();
        let paving = pave_scene_method(&self.scene, self.variant, &domain, opts, &mo, progress)
            .map_err(|e| Error::new(ErrorKind::Computation, e))?;
        let elapsed_s = start.elapsed().as_secs_f64();
        let proved = crate::area::proved_empty_cells(&self.scene, self.variant);
        let bounds = standard_cell_bounds(&paving, proved, domain.uncovered_area_sup());
        let areas = Cell::ALL
            .into_iter()
            .zip(bounds)
            .map(|(cell, (b, empty))| SetArea {
                cell,
                inner: b.inner_area,
                outer: b.outer_area,
                how: match empty {
                    Some(e) => How::Empty(e),
                    None => How::Paving,
                },
            })
            .collect();
        let domain_text = self.scene.domain_text();
        let text = |w: &Option<[String; 2]>, i: usize| w.clone().unwrap_or(domain_text[i].clone());
        Ok(Paved {
            domain_text: [text(&req.theta, 0), text(&req.theta_dot, 1)],
            domain,
            paving,
            areas,
            elapsed_s,
        })
    }

    /// Certified areas of Ω, Ω₀ and the four cells to `digits` decimal
    /// places, as `detach area` computes them: quadrature over θ where the
    /// regions are of degree ≤ 2 in θ̇, intersected with a paving's bounds
    /// (ε = 1/1024) where it missed its target; a paving's bounds alone
    /// otherwise. Each says how it was obtained.
    ///
    /// ```
    /// let disc = detach::api::Problem::load("viscous-disc", &[])?;
    /// let areas = disc.area(6)?;
    /// assert_eq!(areas.len(), 6);
    /// assert!(areas[0].inner <= areas[0].outer);
    /// # Ok::<(), detach::api::Error>(())
    /// ```
    pub fn area(&self, digits: i32) -> Result<Vec<SetArea>, Error> {
        let areas = self.certified_areas(&AreaRequest {
            digits,
            ..AreaRequest::default()
        })?;
        let out = areas
            .sets
            .iter()
            .map(|s| SetArea {
                cell: s.cell,
                inner: s.lower(),
                outer: s.upper(),
                how: match (s.emptiness(), s.provenance) {
                    (Some(e), _) => How::Empty(e),
                    (None, Provenance::Paving) => How::Paving,
                    (None, Provenance::Intersection) => How::QuadratureAndPaving,
                    (None, _) => How::Quadrature,
                },
            })
            .collect();
        Ok(out)
    }
}

/// What to measure: `detach area`'s options.
#[derive(Clone, Debug)]
pub struct AreaRequest {
    /// The sets, each once, in [`Cell::ALL`] order when empty.
    pub sets: Vec<Cell>,
    /// Decimal places to certify, 1 to 15: the width target is 10⁻ᵈ.
    pub digits: i32,
    /// Most θ-pieces per set.
    pub max_pieces: usize,
    /// Windows `[lo, hi]` (decimal text, `pi`, `pi/N`) inside the domain.
    pub theta: Option<[String; 2]>,
    pub theta_dot: Option<[String; 2]>,
}

impl Default for AreaRequest {
    fn default() -> Self {
        AreaRequest {
            sets: Vec::new(),
            digits: 10,
            max_pieces: 1 << 20,
            theta: None,
            theta_dot: None,
        }
    }
}

impl Problem {
    /// The certified areas of `req`'s sets with how each was obtained, as
    /// `detach area --json` reports them.
    pub fn certified_areas(&self, req: &AreaRequest) -> Result<crate::area::CertifiedAreas, Error> {
        let (domain, _) = self.domain(window(&req.theta), window(&req.theta_dot))?;
        let tol = area_tolerance(req.digits)?;
        if req.max_pieces == 0 {
            return Err(Error::invalid_option("max_pieces", " must be at least 1"));
        }
        let mut sets = each_once(&req.sets);
        if sets.is_empty() {
            sets = Cell::ALL.to_vec();
        }
        let opts = AreaOptions {
            tol,
            max_pieces: req.max_pieces,
        };
        certified_areas(&self.scene, self.variant, &domain, &sets, opts).map_err(areas_error)
    }
}

/// `cells` in their order, each once.
fn each_once(cells: &[Cell]) -> Vec<Cell> {
    let mut once = Vec::new();
    for c in cells {
        if !once.contains(c) {
            once.push(*c);
        }
    }
    once
}

fn window(w: &Option<[String; 2]>) -> Option<[&str; 2]> {
    w.as_ref().map(|[a, b]| [a.as_str(), b.as_str()])
}

/// What to pave: `detach pave`'s options.
#[derive(Clone, Debug)]
pub struct PaveRequest {
    /// Resolution relative to the domain, in (0, 1].
    pub eps: f64,
    /// Most leaves; when reached the result is coarser but valid.
    pub max_boxes: usize,
    pub method: Method,
    /// Refine only for this region or cell.
    pub region: Option<Cell>,
    /// Windows `[lo, hi]` (decimal text, `pi`, `pi/N`) inside the domain.
    pub theta: Option<[String; 2]>,
    pub theta_dot: Option<[String; 2]>,
}

impl Default for PaveRequest {
    fn default() -> Self {
        let d = PaveOptions::default();
        PaveRequest {
            eps: d.eps,
            max_boxes: d.max_boxes,
            method: Method::default(),
            region: None,
            theta: None,
            theta_dot: None,
        }
    }
}

impl PaveRequest {
    /// The paving options, checked ([`pave_options`]).
    pub fn options(&self) -> Result<PaveOptions, Error> {
        pave_options(self.eps, self.max_boxes)
    }
}

/// A paving's resolution `eps` in (0, 1] and leaf budget `max_boxes` in
/// 1..=[`MAX_LEAVES`].
pub fn pave_options(eps: f64, max_boxes: usize) -> Result<PaveOptions, Error> {
    Ok(PaveOptions {
        eps: resolution(eps)?,
        max_boxes: leaf_budget(max_boxes)?,
    })
}

/// A relative resolution `eps` of a paving or a parameter atlas, in (0, 1].
fn resolution(eps: f64) -> Result<f64, Error> {
    if !(eps.is_finite() && eps > 0.0 && eps <= 1.0) {
        return Err(Error::invalid_option(
            "eps",
            format!(" must be a finite number in (0, 1], got {eps}"),
        ));
    }
    Ok(eps)
}

/// A resolution `eps` of a reach paving or a singular-point scan, in (0, 1).
pub fn open_resolution(eps: f64) -> Result<f64, Error> {
    if !(eps.is_finite() && eps > 0.0 && eps < 1.0) {
        return Err(Error::invalid_option(
            "eps",
            format!(" must be a number in (0, 1), got {eps}"),
        ));
    }
    Ok(eps)
}

/// The order of the Taylor steps of a flow, in 2..=60.
pub fn flow_order(order: usize) -> Result<usize, Error> {
    if !(2..=60).contains(&order) {
        return Err(Error::invalid_option(
            "order",
            format!(" must be in 2..=60, got {order}"),
        ));
    }
    Ok(order)
}

/// A leaf budget `max_boxes` in 1..=[`MAX_LEAVES`].
pub fn leaf_budget(max_boxes: usize) -> Result<usize, Error> {
    if max_boxes == 0 {
        return Err(Error::invalid_option("max_boxes", " must be at least 1"));
    }
    if max_boxes > MAX_LEAVES {
        return Err(Error::invalid_option(
            "max_boxes",
            format!(
                " {max_boxes} is over the memory budget of {MAX_LEAVES} leaves \
                 (about 230 bytes each while paving, so {} GB)",
                MAX_LEAVES * 230 / 1_000_000_000
            ),
        ));
    }
    Ok(max_boxes)
}

/// The width target 10⁻ᵈ of `digits` decimal places, `digits` in 1..=15.
pub fn area_tolerance(digits: i32) -> Result<f64, Error> {
    if !(1..=15).contains(&digits) {
        return Err(Error::invalid_option(
            "digits",
            format!(" must be between 1 and 15, got {digits}"),
        ));
    }
    Ok(10f64.powi(-digits))
}

/// A scene file has one reading: `Printed` is refused for it.
pub fn one_reading(variant: Variant) -> Result<(), Error> {
    match variant {
        Variant::Printed => Err(Error::invalid_option(
            "variant",
            " printed applies to the paper's scenes; a scene file has one reading",
        )),
        Variant::Derived => Ok(()),
    }
}

/// An areas error: a width below binary64's rounding names `digits`.
pub fn areas_error(e: AreasError) -> Error {
    match e {
        AreasError::BelowRounding { digits, .. } => {
            Error::invalid_option("digits", format!(": {e}; ask for at most {digits}"))
        }
        AreasError::Refused(_) => Error::new(ErrorKind::InvalidOption, e),
        AreasError::Paving(_) => Error::new(ErrorKind::Computation, e),
    }
}

impl From<SceneFileError> for Error {
    fn from(e: SceneFileError) -> Error {
        let kind = match e.fault {
            SceneFault::Read(k) => ErrorKind::Io(k),
            SceneFault::Content => ErrorKind::SceneFile,
            SceneFault::Override => ErrorKind::InvalidParameter,
        };
        Error::new(kind, e)
    }
}

/// A region or cell by its name in output files (`omega`, `omega0`,
/// `omega_and_omega0`, …).
///
/// ```
/// use detach::api::{cell_named, Cell};
/// assert_eq!(cell_named("omega0"), Ok(Cell::Omega0));
/// assert!(cell_named("omega1").unwrap_err().to_string().starts_with("unknown region `omega1`"));
/// ```
pub fn cell_named(name: &str) -> Result<Cell, Error> {
    name.parse()
        .map_err(|e| Error::new(ErrorKind::UnknownName, e))
}

/// How a set's area bounds were obtained.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum How {
    /// A paving's leaves proved inside (inner) and not proved outside (outer).
    Paving,
    /// Quadrature over θ.
    Quadrature,
    /// Quadrature, intersected with a paving's bounds where it missed its
    /// target.
    QuadratureAndPaving,
    /// Empty by construction: both bounds are exactly 0.
    Empty(Emptiness),
}

impl How {
    /// `paving`, `quadrature`, `quadrature and paving`, or
    /// `empty: omega0 = omega` (…).
    pub fn describe(self) -> String {
        match self {
            How::Paving => "paving".into(),
            How::Quadrature => "quadrature".into(),
            How::QuadratureAndPaving => "quadrature and paving".into(),
            How::Empty(e) => format!("empty: {}", e.describe()),
        }
    }
}

/// A set's certified area: `inner ≤ area ≤ outer`, both doubles rounded
/// outward.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SetArea {
    pub cell: Cell,
    pub inner: f64,
    pub outer: f64,
    pub how: How,
}

/// A paving with what `detach pave` reports of it.
pub struct Paved {
    pub paving: Paving,
    /// The domain paved (the windows applied) and its ends as text.
    pub domain: Domain,
    pub domain_text: [[String; 2]; 2],
    /// Ω, Ω₀ and the four cells, in [`Cell::ALL`] order.
    pub areas: Vec<SetArea>,
    pub elapsed_s: f64,
}

impl Paved {
    /// The paving as a proof file's JSON (`proofs/FORMAT.md`), as
    /// `detach pave --proof` writes it.
    pub fn proof(&self, problem: &Problem) -> serde_json::Value {
        let scene = &problem.scene;
        let variant = problem.variant;
        crate::certificate::paving_proof(
            &crate::certificate::PavingStatement {
                scene,
                variant,
                params: &problem.params,
                domain: &self.domain,
                domain_text: self.domain_text.clone(),
                title: match scene.id() {
                    Some(id) => format!("Ω, Ω₀ and the four cells of the {id} ({variant})"),
                    None => format!("Ω, Ω₀ and the four cells of {}", scene.title()),
                },
            },
            &self.paving,
        )
    }

    /// Writes [`Paved::proof`] to `path` once the checker says VALID.
    ///
    /// ```
    /// use detach::api::{verify, PaveRequest, Problem, Verdict};
    ///
    /// let rod = Problem::load("painleve-rod", &[])?;
    /// let paved = rod.pave(&PaveRequest { eps: 1.0 / 32.0, ..PaveRequest::default() })?;
    /// let path = std::env::temp_dir().join("detach-api-doc-rod.json");
    /// paved.write_proof(&rod, &path)?;
    /// assert_eq!(verify(&path)?.verdict, Verdict::Valid);
    /// # std::fs::remove_file(&path).ok();
    /// # Ok::<(), detach::api::Error>(())
    /// ```
    pub fn write_proof(&self, problem: &Problem, path: &Path) -> Result<(), Error> {
        write_valid(&self.proof(problem), path)
    }

    /// [`Paved::proof`] as the bytes of its file, once the checker says
    /// VALID.
    pub fn checked_proof_bytes(&self, problem: &Problem) -> Result<Vec<u8>, Error> {
        let bytes = crate::certificate::to_bytes(&self.proof(problem));
        checked(&bytes, "the proof")?;
        Ok(bytes)
    }
}

/// Writes a proof file (such as [`Problem::flow_with_proof`]'s) to `path`
/// once the checker says VALID.
pub fn write_checked_proof(proof: &serde_json::Value, path: &Path) -> Result<(), Error> {
    write_valid(proof, path)
}

/// Writes a proof file to `path` once the checker says VALID.
fn write_valid(proof: &serde_json::Value, path: &Path) -> Result<(), Error> {
    let bytes = crate::certificate::to_bytes(proof);
    let shown = crate::files::shown(path);
    checked(&bytes, &shown)?;
    crate::files::write_atomic(path, &bytes).map_err(|e| Error::io("write", &shown, &e))
}

/// `Ok` when the checker says the proof file `bytes` (named `shown` in
/// messages) is VALID.
fn checked(bytes: &[u8], shown: &str) -> Result<(), Error> {
    let rejected = |m: String| Error::new(ErrorKind::ProofRejected, m);
    let report = crate::check::check_bytes(bytes)
        .map_err(|e| rejected(format!("{shown}: the checker cannot read it: {e}")))?;
    match &report.verdict {
        Verdict::Valid => Ok(()),
        Verdict::Invalid(why) => Err(rejected(format!("{shown}: the checker rejects it: {why}"))),
        Verdict::Unchecked(why) => Err(rejected(format!(
            "{shown}: the checker cannot check it: {why}"
        ))),
    }
}

// ------------------------------------------------------ parameter atlases

/// What to decide over a box of parameters: `detach params`'s options.
///
/// ```
/// use detach::api::{Cell, ParamRequest, Problem};
///
/// let rod = Problem::load("painleve-rod", &[])?;
/// let req = ParamRequest {
///     axes: vec![ParamRequest::axis("mu=1:2")?],
///     sets: vec![Cell::OmegaNotOmega0],
///     eps: Some(1.0 / 64.0),
///     ..ParamRequest::default()
/// };
/// let atlas = rod.param_atlas(&req)?;
/// // Ω ∖ Ω₀ is empty below μ* = 4/3 and not above: the threshold's box
/// let t = &atlas.json()["thresholds"][0]["enclosure"];
/// let (lo, hi): (f64, f64) = (t[0].as_str().unwrap().parse().unwrap(), t[1].as_str().unwrap().parse().unwrap());
/// assert!(lo < 4.0 / 3.0 && 4.0 / 3.0 < hi);
/// # Ok::<(), detach::api::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct ParamRequest {
    /// One or two parameters and their ranges, as decimal text.
    pub axes: Vec<ParamAxis>,
    /// The sets whose emptiness is decided on each parameter box.
    pub sets: Vec<Cell>,
    /// Resolution per axis relative to its range, in (0, 1]; `None`: 2⁻³⁴
    /// in one parameter (a threshold to about 1e-10), 1/256 in two.
    pub eps: Option<f64>,
    /// Most parameter boxes; when reached the atlas is coarser (and says so).
    pub max_boxes: usize,
    /// Part K of N of the atlas, joined by [`crate::params::report::merge`].
    pub shard: Option<Shard>,
}

impl Default for ParamRequest {
    /// The two paradox cells, `detach params`'s defaults.
    fn default() -> Self {
        ParamRequest {
            axes: Vec::new(),
            sets: vec![Cell::Omega0NotOmega, Cell::OmegaNotOmega0],
            eps: None,
            max_boxes: 100_000,
            shard: None,
        }
    }
}

impl ParamRequest {
    /// `NAME=LO:HI` (decimal text), as `detach params --x` takes it.
    ///
    /// ```
    /// let a = detach::api::ParamRequest::axis("mu = 0:2.5")?;
    /// assert_eq!((a.name.as_str(), a.lo.as_str(), a.hi.as_str()), ("mu", "0", "2.5"));
    /// assert!(detach::api::ParamRequest::axis("mu=2").is_err());
    /// # Ok::<(), detach::api::Error>(())
    /// ```
    pub fn axis(text: &str) -> Result<ParamAxis, Error> {
        let bad = || {
            Error::new(
                ErrorKind::InvalidOption,
                format!("expected NAME=LO:HI, got `{text}`"),
            )
        };
        let (name, range) = parse_assignment(text).map_err(|_| bad())?;
        let (lo, hi) = range.split_once(':').ok_or_else(bad)?;
        Ok(ParamAxis {
            name,
            lo: lo.trim().to_string(),
            hi: hi.trim().to_string(),
        })
    }

    /// The resolution used: [`ParamRequest::eps`] or its default.
    pub fn resolution(&self) -> f64 {
        self.eps.unwrap_or(if self.axes.len() == 1 {
            2f64.powi(-34)
        } else {
            1.0 / 256.0
        })
    }
}

/// One set's share of the parameter box by status (fractions of its
/// volume, summing to 1 up to rounding).
#[derive(Clone, Debug, PartialEq)]
pub struct SetShare {
    pub set: String,
    pub nonempty: f64,
    pub empty: f64,
    pub undecided: f64,
}

/// A parameter atlas with what `detach params` reports of it.
pub struct ParamAtlasRun {
    pub family: Family,
    pub run: AtlasRun,
    pub eps: f64,
    pub shard: Option<Shard>,
    pub elapsed_s: f64,
}

impl ParamAtlasRun {
    /// The atlas as `detach params --json` writes it: boxes, statuses with
    /// their witnesses or reasons, and in one parameter the thresholds.
    pub fn json(&self) -> serde_json::Value {
        let shard = self.shard.map(|s| (s.k, s.n));
        atlas_json(&self.family, &self.run, self.eps, shard)
    }

    /// The varied parameters' ranges as given: `mu in [1, 2], b in [0, 0.9]`.
    pub fn ranges(&self) -> String {
        let axes = &self.run.atlas.axes;
        let ranges: Vec<String> = axes
            .iter()
            .map(|a| format!("{} in [{}, {}]", a.name, a.lo, a.hi))
            .collect();
        ranges.join(", ")
    }

    /// Per set, the share of the parameter box proved non-empty, proved
    /// empty and undecided.
    pub fn shares(&self) -> Vec<SetShare> {
        let atlas = &self.run.atlas;
        let root: Vec<f64> = self.family.root.iter().map(|r| r[1] - r[0]).collect();
        let leaves: Vec<_> = atlas
            .leaves
            .iter()
            .filter(|l| !l.bounds.is_empty())
            .collect();
        atlas
            .sets
            .iter()
            .enumerate()
            .map(|(k, set)| {
                let mut share = [0.0f64; 3];
                for leaf in &leaves {
                    let frac: f64 = leaf
                        .bounds
                        .iter()
                        .zip(&root)
                        .map(|(b, w)| (b[1] - b[0]) / w)
                        .product();
                    share[status_index(&leaf.sets[k])] += frac;
                }
                SetShare {
                    set: set.clone(),
                    nonempty: share[0],
                    empty: share[1],
                    undecided: share[2],
                }
            })
            .collect()
    }

    /// The atlas as a proof file (`proofs/FORMAT.md`), as `detach params
    /// --proof` writes it; a shard states no whole atlas and has none.
    pub fn proof(&self) -> Result<serde_json::Value, Error> {
        if self.shard.is_some() {
            return Err(Error::invalid_option(
                "shard",
                ": a proof states a whole atlas, not a shard of it",
            ));
        }
        let statement = crate::certificate::params::ParamAtlasStatement {
            scene: &self.family.base,
            variant: self.family.variant,
            params: &self.family.params,
            title: format!(
                "{}: parameter atlas over {}",
                self.family.base.name(),
                self.ranges()
            ),
        };
        crate::certificate::params::param_atlas_proof(&statement, &self.run.atlas)
            .map_err(|e| Error::new(ErrorKind::Computation, e))
    }

    /// Writes [`ParamAtlasRun::proof`] to `path` once the checker says VALID.
    pub fn write_proof(&self, path: &Path) -> Result<(), Error> {
        write_valid(&self.proof()?, path)
    }
}

/// The motion: certified trajectories and the equilibria and singular
/// points of the scene's `[dynamics]`, as `detach flow` and `detach
/// singular` compute them.
impl Problem {
    /// The certified trajectory for `request` (see [`FlowRequest::parse`]).
    ///
    /// ```
    /// use detach::api::{FlowRequest, Problem};
    ///
    /// let disc = Problem::load("viscous-disc", &[])?;
    /// let tube = disc.flow(&FlowRequest::parse("-1.5", "1", "1")?)?;
    /// assert!(tube.end[0].wid() < 1e-12);
    /// # Ok::<(), detach::api::Error>(())
    /// ```
    pub fn flow(&self, request: &FlowRequest) -> Result<Tube, Error> {
        Ok(motion::flow(self.scene.reading(self.variant), request)?)
    }

    /// [`Problem::flow`] and its `trajectory` proof file (JSON), confirmed
    /// by a checker with looser rounding before it is returned; `t_text` is
    /// the end time as given. Fails when the run ends undecided (nothing
    /// is proved to claim).
    pub fn flow_with_proof(
        &self,
        request: &FlowRequest,
        t_text: &str,
    ) -> Result<(Tube, serde_json::Value), Error> {
        if request.settings.backward {
            return Err(Error::new(
                ErrorKind::Unsupported,
                "a trajectory proof is of forward time only",
            ));
        }
        let file = self.scene.reading(self.variant);
        let motion = motion::Motion::new(file, &request.until)?;
        let tube = motion
            .run(request.start, request.t_end, &request.settings)
            .map_err(motion::MotionError::from)?;
        let proof =
            crate::certificate::trajectory::checked_trajectory_proof(file, &motion, &tube, t_text)
                .map_err(trajectory_proof_error)?;
        Ok((tube, proof))
    }

    /// The initial states of the domain (or a window of it) whose motion
    /// reaches the first event of `until` within `t` (decimal text), as a
    /// certified paving: `detach reach`.
    pub fn reach(
        &self,
        theta: Option<[&str; 2]>,
        theta_dot: Option<[&str; 2]>,
        t: &str,
        until: &[Until],
        opts: &ReachOptions,
    ) -> Result<ReachRun, Error> {
        self.reach_with_progress(theta, theta_dot, t, until, opts, |_, _, _| {
            std::ops::ControlFlow::Continue(())
        })
    }

    /// [`Problem::reach`], calling `progress(depth, open boxes, leaves)` as
    /// the paving goes down; a `Break` stops it there, the open boxes
    /// undecided.
    pub fn reach_with_progress(
        &self,
        theta: Option<[&str; 2]>,
        theta_dot: Option<[&str; 2]>,
        t: &str,
        until: &[Until],
        opts: &ReachOptions,
        progress: impl FnMut(usize, usize, usize) -> std::ops::ControlFlow<()>,
    ) -> Result<ReachRun, Error> {
        let (domain, _) = self.domain(theta, theta_dot)?;
        let t_end = end_time(t)?;
        if until.is_empty() {
            return Err(Error::invalid_option(
                "until",
                ": no target: give at least one of U=0, N=0, cell, domain",
            ));
        }
        open_resolution(opts.eps)?;
        leaf_budget(opts.max_boxes)?;
        let motion = motion::Motion::new(self.scene.reading(self.variant), until)?;
        Ok(motion::reach::reach(
            &motion,
            domain.inner_box(),
            t_end,
            opts,
            progress,
        ))
    }

    /// The `reach` proof of `run`, a [`Problem::reach`] made with the same
    /// `t`, `until` and `opts`: each decided leaf's certificate confirmed
    /// by the strictest and loosest checkers, a leaf none confirms stated
    /// undecided. Returns the proof and how many such leaves there are.
    pub fn reach_proof(
        &self,
        run: &motion::reach::ReachRun,
        t: &str,
        until: &[Until],
        opts: &ReachOptions,
    ) -> Result<(serde_json::Value, usize), Error> {
        let t_end = end_time(t)?;
        let file = self.scene.reading(self.variant);
        let motion = motion::Motion::new(file, until)?;
        crate::certificate::reach::reach_proof(file, &motion, run, t_end, t, opts)
            .map_err(trajectory_proof_error)
    }

    /// The equilibria and singular points in the domain (or a window of
    /// it), each proved unique in its box, with their type.
    pub fn singular_points(
        &self,
        theta: Option<[&str; 2]>,
        theta_dot: Option<[&str; 2]>,
    ) -> Result<SingularReport, Error> {
        let (domain, _) = self.domain(theta, theta_dot)?;
        let file = self.scene.reading(self.variant);
        if !file.has_dynamics() {
            return Err(Error::new(
                ErrorKind::Unsupported,
                format!(
                    "scene `{}` has no [dynamics]: there is no θ̈ to find equilibria of",
                    self.scene.name()
                ),
            ));
        }
        singular::find(file, &domain, &Default::default())
            .map_err(|e| Error::new(ErrorKind::Computation, e))
    }

    /// Where in `axis` the number or the type of the points changes: the
    /// certified thresholds of `detach singular --x`.
    pub fn singular_scan(
        &self,
        axis: ParamAxis,
        theta: Option<[&str; 2]>,
        theta_dot: Option<[&str; 2]>,
        opts: &ScanOptions,
    ) -> Result<Scan, Error> {
        let (domain, _) = self.domain(theta, theta_dot)?;
        let family = self.family(vec![axis])?;
        singular::scan(&family, &domain, opts).map_err(|e| Error::new(ErrorKind::Unsupported, e))
    }

    /// The scene as a family over `axes`, the other parameters at this
    /// problem's values: the scene `detach singular --x` rebuilds per
    /// parameter box.
    pub fn family(&self, axes: Vec<ParamAxis>) -> Result<Family, Error> {
        let overrides = self
            .params
            .texts()
            .into_iter()
            .map(|(n, t)| (n.to_string(), t))
            .collect();
        Family::new(self.source.clone(), self.variant, overrides, axes)
            .map_err(|e| Error::new(ErrorKind::InvalidOption, e))
    }

    /// A certified parameter atlas, as `detach params` computes it: the
    /// scene rebuilt with the request's parameters as intervals, and each
    /// set's emptiness decided on boxes of them (the others at this
    /// problem's values).
    pub fn param_atlas(&self, req: &ParamRequest) -> Result<ParamAtlasRun, Error> {
        self.param_atlas_with_progress(req, |_, _, _| {})
    }

    /// [`Problem::param_atlas`], with `progress(level, open boxes, boxes)`
    /// called as the search goes down each level; returning
    /// `ControlFlow::Break(())` stops it there with a valid, coarser atlas
    /// (`run.interrupted`), as [`Problem::pave_with_progress`] does.
    pub fn param_atlas_with_progress<F: LevelFlow>(
        &self,
        req: &ParamRequest,
        progress: impl FnMut(u32, usize, usize) -> F,
    ) -> Result<ParamAtlasRun, Error> {
        let family = self.family(req.axes.clone())?;
        if req.sets.is_empty() {
            return Err(Error::invalid_option(
                "sets",
                ": give at least one set to decide",
            ));
        }
        let sets = each_once(&req.sets);
        let eps = resolution(req.resolution())?;
        if req.max_boxes == 0 {
            return Err(Error::invalid_option("max_boxes", " must be at least 1"));
        }
        let opts = SearchOptions {
            eps,
            max_boxes: req.max_boxes,
            decide: DecideOptions::default(),
            shard: req.shard,
        };
        let start = Instant::now();
        let run = search(&family, &sets, &opts, progress)
            .map_err(|e| Error::new(ErrorKind::InvalidOption, e))?;
        Ok(ParamAtlasRun {
            family,
            run,
            eps,
            shard: req.shard,
            elapsed_s: start.elapsed().as_secs_f64(),
        })
    }
}

/// 0 non-empty, 1 empty, 2 undecided.
pub fn status_index(s: &SetStatus) -> usize {
    match s {
        SetStatus::Nonempty { .. } => 0,
        SetStatus::Empty { .. } => 1,
        SetStatus::Undecided { .. } => 2,
    }
}

/// Checks a proof file with the independent checker ([`crate::check`]), as
/// `detach verify FILE` does: `Err` when it cannot be read.
pub fn verify(path: &Path) -> Result<Report, Error> {
    crate::check::check_file(path).map_err(|e| {
        let shown = crate::files::shown(path);
        match std::fs::metadata(path) {
            Err(io) => Error::io("read", &shown, &io),
            Ok(_) => Error::new(ErrorKind::ProofRejected, e),
        }
    })
}

/// An end time `t`: decimal text of a number > 0.
fn end_time(t: &str) -> Result<inari::Interval, Error> {
    let t_end = crate::number::param::enclose_decimal("t", t)?;
    if !(t_end.inf() > 0.0 && t_end.is_common_interval()) {
        return Err(Error::invalid_option(
            "t",
            format!(" must be a number > 0, got `{t}`"),
        ));
    }
    Ok(t_end)
}

impl From<motion::MotionError> for Error {
    fn from(e: motion::MotionError) -> Error {
        use motion::MotionError as M;
        match e {
            M::NoDynamics(_) => Error::new(ErrorKind::Unsupported, e),
            M::Param(p) => p.into(),
            M::Until(_) => Error::invalid_option("until", format!(": {e}")),
            M::Range(..) | M::Flow(_) => Error::new(ErrorKind::InvalidOption, e),
        }
    }
}

fn trajectory_proof_error(e: impl std::fmt::Display) -> Error {
    Error::new(ErrorKind::Unsupported, e)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ops::ControlFlow;

    /// A paving stopped by its callback at a level keeps the boxes it held
    /// there as labelled leaves: its tree replays, its leaf count is what
    /// the level held, and its area bounds bracket a finished paving's.
    #[test]
    fn a_stopped_paving_is_valid_and_coarser() {
        let rod = Problem::load("painleve-rod", &[("mu", "1.5")]).unwrap();
        for method in Method::ALL {
            let req = PaveRequest {
                eps: 1.0 / 256.0,
                method,
                ..PaveRequest::default()
            };
            let full = rod.pave(&req).unwrap();
            let mut held = 0;
            let stopped = rod
                .pave_with_progress(&req, |level, open, leaves| {
                    if level < 8 {
                        return ControlFlow::Continue(());
                    }
                    held = held.max(open + leaves);
                    ControlFlow::Break(())
                })
                .unwrap();
            let p = &stopped.paving;
            assert_eq!(p.stop, StopReason::Interrupted, "{method}");
            assert!(!p.complete);
            assert!(p.leaves.len() <= held && p.leaves.len() < full.paving.leaves.len());
            assert_eq!(p.replay_boxes().unwrap().len(), p.leaves.len());
            for (a, b) in stopped.areas.iter().zip(&full.areas) {
                assert!(
                    a.inner <= b.inner && b.outer <= a.outer,
                    "{method} {:?}",
                    a.cell
                );
            }
        }
    }

    /// A leaf carries one label per constraint of its paving, no more: two
    /// for a scene (Ω, Ω₀), also when a region only steers refinement or
    /// when the file has no Ω₀ (then Ω₀ = Ω), and one for a one-constraint
    /// set paved by the engine directly.
    #[test]
    fn leaves_have_one_label_per_constraint() {
        let rod = Problem::load("painleve-rod", &[("mu", "1.5")]).unwrap();
        let ball = Problem::from_toml(
            "name = \"ball\"\n[domain]\ntheta = [\"0\", \"1\"]\n\
             theta_dot = [\"-1\", \"1\"]\n[regions]\nomega = \"theta_dot^2 < theta\"\n",
            "ball.toml",
            &[],
        )
        .unwrap();
        for (problem, region) in [(&rod, None), (&rod, Some(Cell::Omega)), (&ball, None)] {
            let req = PaveRequest {
                eps: 1.0 / 64.0,
                region,
                ..PaveRequest::default()
            };
            let p = problem.pave(&req).unwrap().paving;
            assert_eq!(p.names, ["omega", "omega0"]);
            assert!(p.leaves.len() > 100);
            for leaf in &p.leaves {
                assert_eq!(leaf.labels.len(), 2, "{:?}", leaf);
                assert_eq!(leaf.labels.iter().count(), 2);
            }
        }

        // One constraint (`θ̇ < 1/2`): one label per leaf.
        let p = crate::pave::area::tests::below_on_the_unit_square();
        assert!(p.leaves.len() > 100);
        for leaf in &p.leaves {
            assert_eq!(leaf.labels.len(), 1, "{:?}", leaf);
        }
        assert!(p.leaves.iter().any(|l| l.labels[..] == [Label::ProvedIn]));
        assert!(p.leaves.iter().any(|l| l.labels[..] == [Label::ProvedOut]));
    }

    /// The callback returning `()` never stops a paving.
    #[test]
    fn a_plain_callback_goes_on() {
        let rod = Problem::load("painleve-rod", &[]).unwrap();
        let req = PaveRequest {
            eps: 1.0 / 64.0,
            ..PaveRequest::default()
        };
        let p = rod.pave_with_progress(&req, |_, _, _| ()).unwrap();
        assert!(p.paving.complete);
        assert_ne!(p.paving.stop, StopReason::Interrupted);
    }
}
