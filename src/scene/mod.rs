//! Phase-plane scenes, every one read from a scene file ([`mod@file`],
//! compiled by [`expr`]): the paper's three systems from the embedded
//! `scenes/*.toml` (two readings each), and users' own files.
//!
//! Every region here is `{g(θ, θ̇) < 0}` with `g` quadratic in θ̇ for fixed θ,
//! so a scene gives each constraint as θ-dependent coefficients
//! ([`Quadratic`]). That is the same formula on points, boxes and duals, and it
//! lets the paver share every trigonometric and logarithmic value across all
//! boxes of one θ-slab.

pub mod cell;
pub mod expr;
pub mod file;
pub mod slab;

use crate::number::param::{enclose_window_end, ParamError, ParamSet, ParamSpec};
use crate::number::scalar::Scalar;
use inari::{DecInterval, Interval};
use serde::Serialize;
use std::fmt;
use std::str::FromStr;

pub use cell::{Cell, UnknownCell};
pub use expr::{decimal, ExactTheta};
pub use file::{ExactPoint, FileScene, SceneFileError, SceneText};

/// Which reading of the paper a formula follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Variant {
    /// The formulas exactly as the paper prints them.
    Printed,
    /// Re-derived from the mechanics the paper states (derivations in `scenes/*.toml`).
    Derived,
}

impl Variant {
    pub const ALL: [Variant; 2] = [Variant::Printed, Variant::Derived];
    pub fn name(self) -> &'static str {
        match self {
            Variant::Printed => "printed",
            Variant::Derived => "derived",
        }
    }
    /// One line on what the reading is.
    pub fn describe(self) -> &'static str {
        match self {
            Variant::Printed => "the formulas exactly as the paper prints them",
            Variant::Derived => "re-derived from the mechanics the paper states",
        }
    }
}

impl fmt::Display for Variant {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Variant {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Variant::ALL
            .into_iter()
            .find(|v| v.name() == s)
            .ok_or_else(|| format!("unknown variant `{s}` (known: printed, derived)"))
    }
}

/// `c2·θ̇² + c1·θ̇ + c0`, the coefficients depending on θ only.
#[derive(Clone, Copy, Debug)]
pub struct Quadratic<T> {
    pub c2: T,
    pub c1: T,
    pub c0: T,
}

impl<T> Quadratic<T> {
    /// The same quadratic with every coefficient passed through `f`.
    pub fn map<U>(self, f: impl Fn(T) -> U) -> Quadratic<U> {
        Quadratic {
            c2: f(self.c2),
            c1: f(self.c1),
            c0: f(self.c0),
        }
    }
    /// `[c2, c1, c0]`.
    pub fn coefficients(self) -> [T; 3] {
        [self.c2, self.c1, self.c0]
    }
}

impl Quadratic<DecInterval> {
    /// Every coefficient continuous (`≥ dac`) and defined.
    pub fn is_continuous(&self) -> bool {
        self.coefficients()
            .into_iter()
            .all(crate::number::scalar::is_continuous)
    }
}

impl<T: Scalar> Quadratic<T> {
    pub fn eval(&self, theta_dot: T) -> T {
        self.c2 * theta_dot.sqr() + self.c1 * theta_dot + self.c0
    }
}

/// θ with its sine and cosine, computed once and shared by every formula.
#[derive(Clone, Copy, Debug)]
pub struct Angle<T> {
    pub theta: T,
    pub sin: T,
    pub cos: T,
}

impl<T: Scalar> Angle<T> {
    pub fn new(theta: T) -> Self {
        let (sin, cos) = theta.sin_cos();
        Angle { theta, sin, cos }
    }
}

/// The two constraints of a scene, each `{g < 0}`: Ω (no detachment) and Ω₀
/// (the normal reaction keeps its sign).
#[derive(Clone, Copy, Debug)]
pub struct Constraints<T> {
    pub omega: Quadratic<T>,
    pub omega0: Quadratic<T>,
}

impl<T> Constraints<T> {
    /// Both constraints with every coefficient passed through `f`.
    pub fn map<U>(self, f: impl Fn(T) -> U) -> Constraints<U> {
        Constraints {
            omega: self.omega.map(&f),
            omega0: self.omega0.map(&f),
        }
    }
}

/// A rectangle of the phase plane whose endpoints are exact reals given as
/// enclosures (e.g. θ ∈ [0, π]).
#[derive(Clone, Copy, Debug)]
pub struct Domain {
    pub theta: [Interval; 2],
    pub theta_dot: [Interval; 2],
}

impl Domain {
    /// The largest double box inside the domain: pavings start here, so every
    /// proved-inside box lies in the true domain.
    pub fn inner_box(&self) -> [[f64; 2]; 2] {
        [
            [self.theta[0].sup(), self.theta[1].inf()],
            [self.theta_dot[0].sup(), self.theta_dot[1].inf()],
        ]
    }

    /// Upper bound on the area of the true domain not covered by
    /// [`Domain::inner_box`] (non-zero when an endpoint such as π is not a double).
    pub fn uncovered_area_sup(&self) -> f64 {
        self.area_outside(self.inner_box())
    }

    /// Upper bound on the area of the true domain outside the box `b`
    /// (`[[θ lo, θ hi], [θ̇ lo, θ̇ hi]]`, inside the domain).
    pub fn area_outside(&self, b: [[f64; 2]; 2]) -> f64 {
        let iv = |lo: f64, hi: f64| Interval::try_from((lo, hi)).unwrap();
        let w_true = self.theta[1] - self.theta[0];
        let h_true = self.theta_dot[1] - self.theta_dot[0];
        let whole = w_true * h_true;
        let inner = (iv(b[0][0], b[0][0]) - iv(b[0][1], b[0][1]))
            * (iv(b[1][0], b[1][0]) - iv(b[1][1], b[1][1]));
        (whole - inner).sup().max(0.0)
    }

    /// Exact area enclosure of the true domain.
    pub fn area(&self) -> Interval {
        (self.theta[1] - self.theta[0]) * (self.theta_dot[1] - self.theta_dot[0])
    }

    /// A window of this domain from text (`None` keeps the side): decimals,
    /// or `pi`, `-pi`, `pi/N`, `-pi/N` ([`crate::number::param::enclose_window_end`]).
    /// The window must be non-empty and must not lie provably outside the
    /// domain. An end whose enclosure overlaps the domain's end (e.g.
    /// `3.1415926535897932`, a decimal just below π, whose enclosure reaches
    /// past π's lower bound) is clipped to the domain: the window becomes the
    /// intersection, exactly (enclosures of `max`/`min`).
    pub fn window(
        &self,
        theta: Option<[&str; 2]>,
        theta_dot: Option<[&str; 2]>,
    ) -> Result<Domain, ParamError> {
        Ok(self.window_clipped(theta, theta_dot)?.0)
    }

    /// [`Domain::window`], also saying which ends were clipped (as
    /// `"theta hi"`, …).
    pub fn window_clipped(
        &self,
        theta: Option<[&str; 2]>,
        theta_dot: Option<[&str; 2]>,
    ) -> Result<(Domain, Vec<String>), ParamError> {
        let mut clipped = Vec::new();
        let mut side = |name: &str,
                        full: [Interval; 2],
                        given: Option<[&str; 2]>|
         -> Result<[Interval; 2], ParamError> {
            let Some([lo_t, hi_t]) = given else {
                return Ok(full);
            };
            let (lo, hi) = (
                enclose_window_end(name, lo_t)?,
                enclose_window_end(name, hi_t)?,
            );
            let invalid = |reason: &str| ParamError::Invalid {
                name: name.into(),
                reason: reason.into(),
            };
            if lo.sup() >= hi.inf() {
                return Err(invalid("the window is empty (need lo < hi)"));
            }
            let outside = || {
                invalid(&format!(
                    "the window must lie inside the scene's domain [{}, {}]",
                    crate::number::param::short_num(full[0].inf()),
                    crate::number::param::short_num(full[1].sup())
                ))
            };
            // Provably below the domain's start or above its end.
            if lo.sup() < full[0].inf() || hi.inf() > full[1].sup() {
                return Err(outside());
            }
            // The domain's end itself (`-pi`, `10`): nothing to clip or say.
            let is_end = |x: Interval, end: Interval, text: &str| {
                x == end && (x.is_singleton() || text.to_ascii_lowercase().contains("pi"))
            };
            let mut lo_c = lo;
            if lo.inf() < full[0].sup() && !is_end(lo, full[0], lo_t) {
                lo_c = lo.max(full[0]);
                clipped.push(format!("{name} lo = {lo_t}"));
            }
            let mut hi_c = hi;
            if hi.sup() > full[1].inf() && !is_end(hi, full[1], hi_t) {
                hi_c = hi.min(full[1]);
                clipped.push(format!("{name} hi = {hi_t}"));
            }
            if lo_c.sup() >= hi_c.inf() {
                return Err(outside());
            }
            Ok([lo_c, hi_c])
        };
        let theta = side("theta", self.theta, theta).map_err(|e| e.of_window("theta"))?;
        let theta_dot =
            side("theta_dot", self.theta_dot, theta_dot).map_err(|e| e.of_window("theta_dot"))?;
        Ok((Domain { theta, theta_dot }, clipped))
    }

    pub fn is_empty(&self) -> bool {
        let b = self.inner_box();
        !(b[0][0] < b[0][1] && b[1][0] < b[1][1])
    }
}

/// π as an enclosure.
pub const PI: Interval = Interval::PI;

/// The paper's scenes, as spelled on the command line. Each is two embedded
/// scene files, `scenes/NAME.toml` (the derived reading) and
/// `scenes/NAME-printed.toml` (the formulas as printed): everything about a
/// scene — parameters, conditions, regions, dynamics — is written there.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SceneId {
    ViscousDisc,
    SmoothDisc,
    IceDisc,
}

impl SceneId {
    pub const ALL: [SceneId; 3] = [SceneId::ViscousDisc, SceneId::SmoothDisc, SceneId::IceDisc];

    pub fn name(self) -> &'static str {
        match self {
            SceneId::ViscousDisc => "viscous-disc",
            SceneId::SmoothDisc => "smooth-disc",
            SceneId::IceDisc => "ice-disc",
        }
    }

    /// The embedded file of one reading: `NAME` or `NAME-printed`.
    pub fn file_name(self, v: Variant) -> String {
        match v {
            Variant::Derived => self.name().to_string(),
            Variant::Printed => format!("{}-printed", self.name()),
        }
    }

    /// The embedded text of one reading.
    pub fn text(self, v: Variant) -> SceneText {
        SceneText::embedded(&self.file_name(v)).expect("every paper scene is embedded")
    }

    /// One reading compiled, with `name=value` parameter overrides.
    pub fn reading(
        self,
        v: Variant,
        overrides: &[(String, String)],
    ) -> Result<FileScene, SceneFileError> {
        self.text(v).compile(overrides)
    }

    /// The scene's title, from its derived file.
    pub fn title(self) -> &'static str {
        self.declared().0
    }

    /// The parameters a run may set (names, defaults, meanings), from the
    /// derived file.
    pub fn params(self) -> &'static [ParamSpec] {
        self.declared().1
    }

    /// Title and parameters, read from the embedded file once.
    fn declared(self) -> (&'static str, &'static [ParamSpec]) {
        static DECLARED: std::sync::OnceLock<Vec<(&'static str, &'static [ParamSpec])>> =
            std::sync::OnceLock::new();
        DECLARED.get_or_init(|| {
            SceneId::ALL
                .map(|id| {
                    let f = id
                        .reading(Variant::Derived, &[])
                        .expect("defaults are valid");
                    let title: &'static str = Box::leak(f.title.into_boxed_str());
                    (title, f.params.specs)
                })
                .to_vec()
        })[self as usize]
    }
}

impl fmt::Display for SceneId {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for SceneId {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        SceneId::ALL
            .into_iter()
            .find(|id| id.name() == s)
            .ok_or_else(|| {
                format!(
                    "unknown scene `{s}` (known: {})",
                    SceneId::ALL.map(|i| i.name()).join(", ")
                )
            })
    }
}

/// One of the paper's scenes: both readings compiled from their files with
/// the same parameters.
#[derive(Clone, Debug)]
pub struct PaperScene {
    pub id: SceneId,
    pub derived: FileScene,
    pub printed: FileScene,
}

impl PaperScene {
    /// The file of one reading.
    pub fn reading(&self, v: Variant) -> &FileScene {
        match v {
            Variant::Derived => &self.derived,
            Variant::Printed => &self.printed,
        }
    }
}

/// A scene with validated parameters: one of the paper's (two readings), or
/// one read from a scene file (one reading: `variant` does not apply to it).
#[derive(Clone, Debug)]
pub enum Scene {
    Paper(Box<PaperScene>),
    File(Box<FileScene>),
}

impl Scene {
    /// Builds a paper scene from its files' defaults overridden by
    /// `name=value` pairs (both readings; the parameters are the derived
    /// file's, which the printed file shares).
    pub fn build(
        id: SceneId,
        overrides: &[(String, String)],
    ) -> Result<(Scene, ParamSet), SceneFileError> {
        let derived = id.reading(Variant::Derived, overrides)?;
        let printed = id.reading(Variant::Printed, overrides)?;
        let params = derived.params.clone();
        Ok((
            Scene::Paper(Box::new(PaperScene {
                id,
                derived,
                printed,
            })),
            params,
        ))
    }

    /// The scene at its default parameters.
    pub fn default_of(id: SceneId) -> Scene {
        Scene::build(id, &[]).expect("defaults are valid").0
    }

    /// The names [`Scene::by_name`] takes: the paper's scenes, then the
    /// shipped scene files.
    pub fn names() -> Vec<&'static str> {
        SceneId::ALL
            .iter()
            .map(|id| id.name())
            .chain(file::SHIPPED.iter().map(|s| s.0))
            .collect()
    }

    /// A scene by name: one of the paper's, or a shipped scene file
    /// ([`file::SHIPPED`]).
    pub fn by_name(
        name: &str,
        overrides: &[(String, String)],
    ) -> Result<(Scene, ParamSet), String> {
        match (name.parse::<SceneId>(), SceneText::shipped(name)) {
            (Ok(id), _) => Scene::build(id, overrides).map_err(|e| e.to_string()),
            (Err(_), Some(t)) => {
                let f = t.compile(overrides).map_err(|e| e.to_string())?;
                let params = f.params.clone();
                Ok((Scene::File(Box::new(f)), params))
            }
            (Err(_), None) => Err(format!(
                "unknown scene `{name}` (known: {})",
                Scene::names().join(", ")
            )),
        }
    }

    /// One reading of a paper scene as a file scene: the embedded
    /// `scenes/NAME.toml` (derived) or `scenes/NAME-printed.toml`, with
    /// `name=value` parameter overrides.
    pub fn file_of(
        id: SceneId,
        variant: Variant,
        overrides: &[(String, String)],
    ) -> Result<(Scene, ParamSet), SceneFileError> {
        let f = id.reading(variant, overrides)?;
        let params = f.params.clone();
        Ok((Scene::File(Box::new(f)), params))
    }

    /// Reads a scene file, with `name=value` parameter overrides.
    pub fn from_file(
        path: &std::path::Path,
        overrides: &[(String, String)],
    ) -> Result<(Scene, ParamSet), SceneFileError> {
        let f = FileScene::load(path, overrides)?;
        let params = f.params.clone();
        Ok((Scene::File(Box::new(f)), params))
    }

    /// The file whose formulas a run in reading `v` evaluates (a scene file
    /// has one reading).
    pub fn reading(&self, v: Variant) -> &FileScene {
        match self {
            Scene::Paper(p) => p.reading(v),
            Scene::File(f) => f,
        }
    }

    /// The file of the scene's main reading (derived, for a paper scene).
    fn main_file(&self) -> &FileScene {
        self.reading(Variant::Derived)
    }

    /// The paper's scene this is, if it is one.
    pub fn id(&self) -> Option<SceneId> {
        match self {
            Scene::Paper(p) => Some(p.id),
            Scene::File(_) => None,
        }
    }

    /// `viscous-disc`, …, or the `name` of a scene file.
    pub fn name(&self) -> &str {
        match self {
            Scene::Paper(p) => p.id.name(),
            Scene::File(f) => &f.name,
        }
    }

    /// Warnings about the scene's formulas (a scene file's parameter-only
    /// subexpressions that may be undefined).
    pub fn warnings(&self) -> &[String] {
        &self.main_file().warnings
    }

    pub fn title(&self) -> &str {
        &self.main_file().title
    }

    /// The parameters' names, defaults and meanings.
    pub fn params_specs(&self) -> &'static [ParamSpec] {
        self.main_file().params.specs
    }

    /// The domain's ends as text (`[[θ lo, θ hi], [θ̇ lo, θ̇ hi]]`).
    pub fn domain_text(&self) -> [[String; 2]; 2] {
        self.main_file().domain_text.clone()
    }

    pub fn domain(&self) -> Domain {
        self.main_file().domain
    }

    pub fn constraints<T: Scalar>(&self, v: Variant, a: &Angle<T>) -> Constraints<T> {
        let [omega, omega0] = self.reading(v).quadratics(a);
        Constraints { omega, omega0 }
    }

    /// The constraints with each one's θ-only factor apart: `g = (a/b)·p`
    /// with `[a, b]` returned per constraint and `p` its quadratic, so that
    /// where the signs of `a` and `b` are known `{g < 0}` is `{p < 0}` or
    /// `{p > 0}`, and `p`'s roots carry none of the factor's rounding
    /// ([`FileScene::factored_quadratics`]).
    pub fn factored_constraints<T: Scalar>(
        &self,
        v: Variant,
        a: &Angle<T>,
    ) -> ([[T; 2]; 2], Constraints<T>) {
        let (factor, [omega, omega0]) = self.reading(v).factored_quadratics(a);
        (factor, Constraints { omega, omega0 })
    }

    /// True when Ω₀ ≡ Ω by construction: the same region text.
    pub fn omega0_is_omega(&self, v: Variant) -> bool {
        self.reading(v).omega0_is_omega()
    }

    /// The scene has an equation of motion for the phase portrait (a file
    /// only with `[dynamics]`).
    pub fn has_dynamics(&self) -> bool {
        self.main_file().has_dynamics()
    }

    /// Certified coefficient enclosures over a θ-interval (decorated: a slab
    /// touching a singular line comes back with a decoration below `def`).
    pub fn constraints_on(&self, v: Variant, theta: Interval) -> Constraints<DecInterval> {
        self.constraints(v, &Angle::new(DecInterval::new(theta)))
    }

    /// θ̈ in contact (for a file without `[dynamics]`: NaN, see
    /// [`Scene::has_dynamics`]).
    pub fn acceleration<T: Scalar>(&self, v: Variant, a: &Angle<T>, theta_dot: T) -> T {
        self.reading(v).acceleration(a.theta, theta_dot)
    }

    /// The conserved energy (`[dynamics]`'s `energy`), if there is one.
    pub fn energy<T: Scalar>(&self, a: &Angle<T>, theta_dot: T) -> Option<T> {
        self.main_file().energy(a, theta_dot)
    }

    /// A named θ-function of the scene's `[functions]` in reading `v`.
    pub fn function(&self, v: Variant, name: &str) -> Option<&file::Function> {
        self.reading(v).function(name)
    }
}
