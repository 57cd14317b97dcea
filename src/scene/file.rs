//! Scene files: a planar system with a unilateral constraint written as
//! TOML (`docs/scene-files.md`), read into a [`FileScene`] whose two regions
//! are compiled once ([`super::expr`]) and evaluated over any
//! [`Scalar`].
//!
//! A file is refused, with one message naming the file, the key and (inside
//! an expression) the character, when it is not TOML, lacks a key, has an
//! unknown one, or holds a bad name, number, domain, region or expression.

use super::expr::{enclose_constant, eval_exact, ExactTheta, ExprError, Program};
use super::{Angle, Domain, Quadratic};
use crate::number::param::{
    enclose_decimal, enclose_window_end, short_num, ParamError, ParamSet, ParamSpec,
};
use crate::number::scalar::Scalar;
use inari::Interval;
use serde::Deserialize;
use std::collections::HashMap;
use std::path::Path;
use toml::Spanned;

/// Every scene file of `scenes/`, built into the library, by name: the
/// paper's scenes in both readings (`NAME` derived, `NAME-printed`) and the
/// others ([`FileScene::shipped`] loads any of them).
pub const EMBEDDED: [(&str, &str); 7] = [
    (
        "viscous-disc",
        include_str!("../../scenes/viscous-disc.toml"),
    ),
    (
        "viscous-disc-printed",
        include_str!("../../scenes/viscous-disc-printed.toml"),
    ),
    ("smooth-disc", include_str!("../../scenes/smooth-disc.toml")),
    (
        "smooth-disc-printed",
        include_str!("../../scenes/smooth-disc-printed.toml"),
    ),
    ("ice-disc", include_str!("../../scenes/ice-disc.toml")),
    (
        "ice-disc-printed",
        include_str!("../../scenes/ice-disc-printed.toml"),
    ),
    SHIPPED[0],
];

/// The embedded files `--scene NAME` reads as one file: those that are not a
/// reading of a paper scene (`--scene viscous-disc` reads both of its files,
/// [`super::Scene::build`]).
pub const SHIPPED: [(&str, &str); 1] = [(
    "painleve-rod",
    include_str!("../../scenes/painleve-rod.toml"),
)];

/// A scene file refused: `file: key: message`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}: {message}")]
pub struct SceneFileError {
    pub file: String,
    pub message: String,
    pub fault: SceneFault,
}

/// What a refused scene file is refused for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SceneFault {
    /// The file cannot be opened or read.
    Read(std::io::ErrorKind),
    /// Its text: TOML, tables, keys, formulas.
    Content,
    /// The file compiles alone; the parameter overrides given with it do not.
    Override,
}

/// Names a file may not give a parameter or definition: the variables of
/// the file and of proof files, the constant and the functions.
const RESERVED: [&str; 16] = [
    "theta",
    "theta_dot",
    "t",
    "w",
    "pi",
    "sqrt",
    "sin",
    "cos",
    "tan",
    "ln",
    "abs",
    "atan",
    "exp",
    "sign",
    "min",
    "max",
];

/// The keys and tables of a scene file, as [`Raw`] reads them.
const TOP_LEVEL: [&str; 9] = [
    "name",
    "title",
    "domain",
    "parameters",
    "definitions",
    "regions",
    "dynamics",
    "conditions",
    "functions",
];

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Raw {
    name: String,
    title: Option<String>,
    domain: RawDomain,
    #[serde(default)]
    parameters: ParamTable,
    #[serde(default)]
    definitions: toml::Table,
    regions: RawRegions,
    dynamics: Option<RawDynamics>,
    #[serde(default)]
    conditions: Ordered<String>,
    #[serde(default)]
    functions: Ordered<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDomain {
    theta: [Spanned<Literal>; 2],
    theta_dot: [Spanned<Literal>; 2],
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRegions {
    omega: String,
    omega0: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDynamics {
    theta_ddot: String,
    energy: Option<String>,
}

/// A number or expression written in quotes, or a bare TOML number. A bare
/// number is taken from its text in the file (its span), never from the
/// float `toml` parsed it to, so `1.1` denotes 11/10 exactly as `"1.1"` does.
enum Literal {
    Quoted(String),
    Bare,
}

struct LiteralVisitor;

impl<'de> serde::de::Visitor<'de> for LiteralVisitor {
    type Value = Literal;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a string in quotes or a number")
    }
    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Literal, E> {
        Ok(Literal::Quoted(v.to_string()))
    }
    fn visit_i64<E: serde::de::Error>(self, _: i64) -> Result<Literal, E> {
        Ok(Literal::Bare)
    }
    fn visit_u64<E: serde::de::Error>(self, _: u64) -> Result<Literal, E> {
        Ok(Literal::Bare)
    }
    fn visit_f64<E: serde::de::Error>(self, _: f64) -> Result<Literal, E> {
        Ok(Literal::Bare)
    }
}

impl<'de> Deserialize<'de> for Literal {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Literal, D::Error> {
        d.deserialize_any(LiteralVisitor)
    }
}

/// The text of a literal: the quoted string, or the bare number's source.
fn literal_text(source: &str, lit: &Spanned<Literal>) -> String {
    match lit.get_ref() {
        Literal::Quoted(s) => s.clone(),
        Literal::Bare => source.get(lit.span()).unwrap_or_default().to_string(),
    }
}

/// A parameter: its value alone (`mu = "1.5"`, `mu = 1.5`) or a table
/// `{ value = "1.5", description = "…", unit = "…" }`.
struct RawParam {
    /// The value, with its own span when written inside a table.
    value: Literal,
    span: Option<std::ops::Range<usize>>,
    description: Option<String>,
    unit: Option<String>,
}

struct ParamVisitor;

impl<'de> serde::de::Visitor<'de> for ParamVisitor {
    type Value = RawParam;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a string in quotes, a number, or a table with `value`")
    }
    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<RawParam, E> {
        LiteralVisitor.visit_str(v).map(RawParam::plain)
    }
    fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<RawParam, E> {
        LiteralVisitor.visit_i64(v).map(RawParam::plain)
    }
    fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<RawParam, E> {
        LiteralVisitor.visit_u64(v).map(RawParam::plain)
    }
    fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<RawParam, E> {
        LiteralVisitor.visit_f64(v).map(RawParam::plain)
    }
    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<RawParam, A::Error> {
        use serde::de::Error;
        let (mut value, mut description, mut unit) = (None, None, None);
        while let Some(key) = map.next_key::<String>()? {
            match key.as_str() {
                "value" => value = Some(map.next_value::<Spanned<Literal>>()?),
                "description" => description = Some(map.next_value::<String>()?),
                "unit" => unit = Some(map.next_value::<String>()?),
                k => {
                    return Err(A::Error::unknown_field(
                        k,
                        &["value", "description", "unit"],
                    ))
                }
            }
        }
        let value = value.ok_or_else(|| A::Error::missing_field("value"))?;
        let span = Some(value.span());
        Ok(RawParam {
            value: value.into_inner(),
            span,
            description,
            unit,
        })
    }
}

impl RawParam {
    fn plain(value: Literal) -> RawParam {
        RawParam {
            value,
            span: None,
            description: None,
            unit: None,
        }
    }
}

/// A table in the order written (`[parameters]`, `[conditions]`,
/// `[functions]`).
struct Ordered<V>(Vec<(String, V)>);

impl<V> Default for Ordered<V> {
    fn default() -> Self {
        Ordered(Vec::new())
    }
}

/// `[parameters]` in the order written.
type ParamTable = Ordered<Spanned<RawParam>>;

struct OrderedVisitor<V>(std::marker::PhantomData<V>);

impl<'de, V: Deserialize<'de>> serde::de::Visitor<'de> for OrderedVisitor<V> {
    type Value = Ordered<V>;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a table")
    }
    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Ordered<V>, A::Error> {
        let mut out = Vec::new();
        while let Some((k, v)) = map.next_entry()? {
            out.push((k, v));
        }
        Ok(Ordered(out))
    }
}

impl<'de, V: Deserialize<'de>> Deserialize<'de> for Ordered<V> {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Ordered<V>, D::Error> {
        d.deserialize_map(OrderedVisitor(std::marker::PhantomData))
    }
}

impl<'de> Deserialize<'de> for RawParam {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<RawParam, D::Error> {
        d.deserialize_any(ParamVisitor)
    }
}

/// A region `{expr < 0}`: the file's inequality and its normal form.
#[derive(Clone, Debug)]
pub struct Region {
    /// As written in the file.
    pub inequality: String,
    /// `expr` of `{expr < 0}`.
    pub expr: String,
}

/// Where [`FileScene::exact`] evaluates a text: θ (its sine, cosine and
/// the logarithms of (3.1), [`ExactTheta`]), θ̇, and values for names:
/// every parameter the text reaches, and any definition to be taken as
/// given rather than from its text.
#[derive(Clone, Copy, Debug)]
pub struct ExactPoint<'a, T> {
    pub theta: ExactTheta<T>,
    pub theta_dot: T,
    pub values: &'a [(&'a str, T)],
}

/// A scene read from a file, with its parameters enclosed.
#[derive(Clone, Debug)]
pub struct FileScene {
    pub name: String,
    pub title: String,
    pub domain: Domain,
    /// The domain's ends as written (`[[θ lo, θ hi], [θ̇ lo, θ̇ hi]]`).
    pub domain_text: [[String; 2]; 2],
    pub params: ParamSet,
    /// `[conditions]` as `(label, inequality)`, in the order written: each
    /// proved in intervals when the scene was built.
    pub conditions: Vec<(String, String)>,
    /// In an order where each uses only earlier ones.
    pub definitions: Vec<(String, String)>,
    /// Ω and Ω₀.
    pub regions: [Region; 2],
    /// Ω and Ω₀ as written (their `expr` of `{expr < 0}`).
    program: Program,
    /// `c₂, c₁, c₀` of Ω, then of Ω₀, as one θ-only program, when both are
    /// of degree ≤ 2 in θ̇ with θ-only coefficients.
    coefficients: Option<Program>,
    /// The same with each region's θ-only factor apart
    /// ([`Program::factored_quadratics`]).
    factored: Option<Program>,
    /// θ̈ for the phase portrait, if given.
    dynamics: Option<Program>,
    /// The conserved energy whose level lines are the phase curves, if given.
    energy: Option<Program>,
    /// θ̈ and the energy as written, if given.
    dynamics_text: [Option<String>; 2],
    /// `[functions]`, in the order written.
    pub functions: Vec<Function>,
    /// Parameter-only subexpressions that may be undefined (one line each).
    pub warnings: Vec<String>,
}

/// A named function of θ and the parameters (`[functions]`), compiled once:
/// evaluated at a point, over an interval or on dual numbers, it is the same
/// sequence of operations as its text.
#[derive(Clone, Debug)]
pub struct Function {
    pub name: String,
    /// As written.
    pub text: String,
    program: Program,
}

impl Function {
    /// `text`, a function of the one variable `variable` (`theta`, or a
    /// name bound to θ as a definition: the same node, no operation added)
    /// with `params` enclosed, compiled as a scene file's function is.
    pub fn of_variable(
        name: &str,
        variable: &str,
        text: &str,
        params: &[(String, Interval)],
    ) -> Result<Function, ExprError> {
        let alias = [(variable.to_string(), "theta".to_string())];
        let definitions = if variable == "theta" {
            &[][..]
        } else {
            &alias[..]
        };
        let program =
            Program::compile(params, definitions, &[(name.to_string(), text.to_string())])?;
        Ok(Function {
            name: name.to_string(),
            text: text.to_string(),
            program,
        })
    }

    /// The function at θ.
    pub fn eval<T: Scalar>(&self, theta: T) -> T {
        let mut out = [theta];
        self.program.eval(theta, T::int(0), &mut out);
        out[0]
    }
}

/// A scene file's text with the name its errors give: read once, compiled
/// as often as parameter overrides need.
#[derive(Clone, Debug)]
pub struct SceneText {
    pub file: String,
    pub text: std::borrow::Cow<'static, str>,
}

/// Largest scene file read (bytes); the shipped ones are a few kB.
pub const MAX_SCENE_FILE_BYTES: u64 = 1 << 20;

impl SceneText {
    /// The scene file at `path`: a regular UTF-8 file of at most
    /// [`MAX_SCENE_FILE_BYTES`] (a pipe or a device is refused unread).
    pub fn read(path: &Path) -> Result<SceneText, SceneFileError> {
        let file = path.display().to_string();
        let fail = |message: String| SceneFileError {
            file: file.clone(),
            message,
            fault: SceneFault::Content,
        };
        if let Err(e) = std::fs::metadata(path) {
            return Err(SceneFileError {
                fault: SceneFault::Read(e.kind()),
                ..fail(format!("cannot read: {e}"))
            });
        }
        let bytes = crate::check::read_regular(path, MAX_SCENE_FILE_BYTES).map_err(fail)?;
        let text = String::from_utf8(bytes).map_err(|e| fail(format!("not UTF-8 text: {e}")))?;
        Ok(SceneText {
            file,
            text: text.into(),
        })
    }

    /// A shipped scene file by name, if there is one: a name `--scene`
    /// reads as a file ([`SHIPPED`]).
    pub fn shipped(name: &str) -> Option<SceneText> {
        if SHIPPED.iter().any(|(n, _)| *n == name) {
            Self::embedded(name)
        } else {
            None
        }
    }

    /// Any embedded scene file by name ([`EMBEDDED`]), if there is one.
    pub fn embedded(name: &str) -> Option<SceneText> {
        let (_, text) = EMBEDDED.iter().find(|(n, _)| *n == name)?;
        Some(SceneText {
            file: format!("scenes/{name}.toml"),
            text: (*text).into(),
        })
    }

    /// Compiles the text with `name=value` parameter overrides.
    pub fn compile(&self, overrides: &[(String, String)]) -> Result<FileScene, SceneFileError> {
        FileScene::parse(&self.text, overrides).map_err(|message| SceneFileError {
            file: self.file.clone(),
            message,
            // Only on failure: whether the file alone compiles.
            fault: if !overrides.is_empty() && FileScene::parse(&self.text, &[]).is_ok() {
                SceneFault::Override
            } else {
                SceneFault::Content
            },
        })
    }
}

impl FileScene {
    /// Reads and compiles `path`, with `name=value` parameter overrides.
    pub fn load(path: &Path, overrides: &[(String, String)]) -> Result<FileScene, SceneFileError> {
        SceneText::read(path)?.compile(overrides)
    }

    /// An embedded scene file by name ([`EMBEDDED`]: the paper's scenes in
    /// both readings too), if there is one.
    pub fn shipped(
        name: &str,
        overrides: &[(String, String)],
    ) -> Option<Result<FileScene, SceneFileError>> {
        Some(SceneText::embedded(name)?.compile(overrides))
    }

    /// Compiles the text of a scene file (errors without the file name).
    pub fn parse(text: &str, overrides: &[(String, String)]) -> Result<FileScene, String> {
        FileScene::parse_enclosed(text, overrides, &[])
    }

    /// [`FileScene::parse`] with some parameters given as enclosures (a
    /// parameter box) instead of their text: `(name, enclosure)` pairs.
    pub fn parse_enclosed(
        text: &str,
        overrides: &[(String, String)],
        boxes: &[(String, Interval)],
    ) -> Result<FileScene, String> {
        let table: toml::Table = toml::from_str(text).map_err(|e| toml_message(text, &e))?;
        // Before what is missing: `[region]` for `[regions]` is the fault.
        if let Some((key, value)) = table.iter().find(|(k, _)| !TOP_LEVEL.contains(&k.as_str())) {
            let what = if value.is_table() {
                format!("`[{key}]`: unknown table")
            } else {
                format!("`{key}`: unknown key")
            };
            return Err(format!(
                "{what} (a scene file has {})",
                TOP_LEVEL.join(", ")
            ));
        }
        for path in ["name", "domain.theta", "domain.theta_dot", "regions.omega"] {
            let mut at = Some(&table);
            let mut found = None;
            for part in path.split('.') {
                found = at.and_then(|t| t.get(part));
                at = found.and_then(toml::Value::as_table);
            }
            if found.is_none() {
                return Err(format!("`{path}`: missing"));
            }
        }
        let raw: Raw = toml::from_str(text).map_err(|e| toml_message(text, &e))?;
        if raw.name.is_empty()
            || !raw
                .name
                .bytes()
                .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'-')
        {
            return Err(format!(
                "`name`: `{}` must be lowercase letters, digits and `-`",
                raw.name
            ));
        }
        let mut params = parameters(&raw.name, &raw.parameters, text, overrides)?;
        for (name, x) in boxes {
            let i = params.specs.iter().position(|s| s.name == name);
            let i = i.ok_or_else(|| format!("unknown parameter `{name}`"))?;
            params.values[i].value = *x;
        }
        let enclosed: Vec<(String, Interval)> = params
            .specs
            .iter()
            .zip(&params.values)
            .map(|(s, p)| (s.name.to_string(), p.value))
            .collect();
        let conditions = conditions(&raw.conditions, &params, &enclosed, boxes)?;
        let domain_text = [&raw.domain.theta, &raw.domain.theta_dot]
            .map(|ends| ends.each_ref().map(|e| literal_text(text, e)));
        let domain = Domain {
            theta: domain_ends("domain.theta", &domain_text[0], &enclosed)?,
            theta_dot: domain_ends("domain.theta_dot", &domain_text[1], &enclosed)?,
        };
        let definitions = definitions(&raw.definitions, &params)?;
        // One inequality: Ω₀ = Ω, stated as the same text.
        let omega0 = raw.regions.omega0.as_ref().unwrap_or(&raw.regions.omega);
        let regions = [
            region("omega", &raw.regions.omega)?,
            region("omega0", omega0)?,
        ];
        let compile_at = |outputs: &[(String, String)], shift: usize| {
            Program::compile(&enclosed, &definitions, outputs).map_err(|e| expr_message(e, shift))
        };
        let compile = |outputs: &[(String, String)]| compile_at(outputs, 0);
        // Each side on its own first, so that a position points into the text
        // as written (the right side starts after the comparison).
        for (key, r) in ["omega", "omega0"].iter().zip(&regions) {
            let (lhs, rhs, _) = split_inequality(&r.inequality).expect("checked by region");
            let k = format!("regions.{key}");
            compile(&[(k.clone(), lhs.to_string())])?;
            compile_at(&[(k, rhs.to_string())], lhs.chars().count() + 1)?;
        }
        let program = compile(&[
            ("regions.omega".into(), regions[0].expr.clone()),
            ("regions.omega0".into(), regions[1].expr.clone()),
        ])?;
        let coefficients = program.quadratics(&[0, 1]);
        let factored = program.factored_quadratics(&[0, 1]);
        let dynamics_text = match raw.dynamics {
            Some(d) => [Some(d.theta_ddot), d.energy],
            None => [None, None],
        };
        let compiled = |key: &str, text: &Option<String>| match text {
            Some(t) => compile(&[(key.into(), t.clone())]).map(Some),
            None => Ok(None),
        };
        let dynamics = compiled("dynamics.theta_ddot", &dynamics_text[0])?;
        let energy = compiled("dynamics.energy", &dynamics_text[1])?;
        let mut functions = Vec::with_capacity(raw.functions.0.len());
        for (name, text) in raw.functions.0 {
            let key = format!("functions.{name}");
            check_name(&key, &name)?;
            if params.specs.iter().any(|s| s.name == name) {
                return Err(format!("`{key}`: `{name}` is also a parameter"));
            }
            if definitions.iter().any(|(d, _)| *d == name) {
                return Err(format!("`{key}`: `{name}` is also a definition"));
            }
            let program = compile(&[(key.clone(), text.clone())])?;
            if program.theta_dot_degree(0) != Some(0) {
                return Err(format!(
                    "`{key}`: a function of theta and the parameters must not depend on theta_dot"
                ));
            }
            functions.push(Function {
                name,
                text,
                program,
            });
        }
        let mut warnings = Vec::new();
        let programs = std::iter::once(&program)
            .chain(&dynamics)
            .chain(&energy)
            .chain(functions.iter().map(|f| &f.program));
        for p in programs {
            let hull = |e: [Interval; 2]| e[0].convex_hull(e[1]);
            for issue in p.constant_issues(hull(domain.theta), hull(domain.theta_dot)) {
                let (message, proved) = constant_message(&issue, &params);
                if proved {
                    return Err(message);
                }
                warnings.push(message);
            }
        }
        let title = raw.title.unwrap_or_else(|| raw.name.clone());
        Ok(FileScene {
            name: raw.name,
            title,
            domain,
            domain_text,
            params,
            conditions,
            definitions,
            regions,
            program,
            coefficients,
            factored,
            dynamics,
            energy,
            dynamics_text,
            functions,
            warnings,
        })
    }

    /// Ω and Ω₀ as `c₂θ̇² + c₁θ̇ + c₀` at θ (its sine and cosine reused).
    /// Panics for a scene that is not [`FileScene::is_quadratic`]: the
    /// pavers and `area` go through [`FileScene::regions_at`] for those.
    pub fn quadratics<T: crate::number::scalar::Scalar>(&self, a: &Angle<T>) -> [Quadratic<T>; 2] {
        let mut c = [T::int(0); 6];
        self.coefficients
            .as_ref()
            .expect("regions of degree at most 2 in theta_dot")
            .eval_angle(a.theta, Some((a.sin, a.cos)), T::int(0), &mut c);
        [0, 3].map(|k| Quadratic {
            c2: c[k],
            c1: c[k + 1],
            c0: c[k + 2],
        })
    }

    /// Ω and Ω₀ as `(a/b)·(c₂θ̇² + c₁θ̇ + c₀)`, each with its θ-only factor
    /// `a/b` apart ([`Program::factored_quadratics`]): returns `[a, b]` and
    /// the quadratic of each. Panics as [`FileScene::quadratics`] does.
    pub fn factored_quadratics<T: crate::number::scalar::Scalar>(
        &self,
        a: &Angle<T>,
    ) -> ([[T; 2]; 2], [Quadratic<T>; 2]) {
        let mut c = [T::int(0); 10];
        self.factored
            .as_ref()
            .expect("regions of degree at most 2 in theta_dot")
            .eval_angle(a.theta, Some((a.sin, a.cos)), T::int(0), &mut c);
        let q = [0, 5].map(|k| Quadratic {
            c2: c[k + 2],
            c1: c[k + 3],
            c0: c[k + 4],
        });
        ([[c[0], c[1]], [c[5], c[6]]], q)
    }

    /// Both regions are of degree ≤ 2 in θ̇ with θ-only coefficients
    /// (detected from the expressions): the quadratic pavers' shortcuts and
    /// `area`'s quadrature apply.
    pub fn is_quadratic(&self) -> bool {
        self.coefficients.is_some()
    }

    /// A region not of degree ≤ 2 in θ̇, if there is one.
    pub fn not_quadratic(&self) -> Option<&'static str> {
        (0..2)
            .find(|&i| self.program.theta_dot_degree(i).is_none_or(|d| d > 2))
            .map(|i| ["omega", "omega0"][i])
    }

    /// `expr` of Ω and Ω₀ at a point or over a box, as written.
    pub fn regions_at<T: crate::number::scalar::Scalar>(&self, theta: T, theta_dot: T) -> [T; 2] {
        let mut out = [T::int(0); 2];
        self.program.eval(theta, theta_dot, &mut out);
        out
    }

    /// Ω or Ω₀ written as the other times or divided by a θ̇-free factor
    /// ([`Program::factors`]; output 0 is Ω, 1 is Ω₀).
    pub fn factors(&self) -> Vec<super::expr::FactorOf> {
        self.program.factors()
    }

    /// True when the two regions are the same text: Ω₀ = Ω by construction.
    pub fn omega0_is_omega(&self) -> bool {
        self.regions[0].expr == self.regions[1].expr
    }

    pub fn has_dynamics(&self) -> bool {
        self.dynamics.is_some()
    }

    /// The energy of `[dynamics]` at (θ, θ̇), if the file gives one.
    pub fn energy<T: Scalar>(&self, a: &Angle<T>, theta_dot: T) -> Option<T> {
        let mut out = [theta_dot];
        self.energy
            .as_ref()?
            .eval_angle(a.theta, Some((a.sin, a.cos)), theta_dot, &mut out);
        Some(out[0])
    }

    /// The function of `[functions]` named `name`, if there is one.
    pub fn function(&self, name: &str) -> Option<&Function> {
        self.functions.iter().find(|f| f.name == name)
    }

    /// The text at `key` evaluated as written over an exact scalar, at `at`
    /// (see [`eval_exact`]): `key` is `definitions.NAME`, `regions.omega`,
    /// `regions.omega0` (the `expr` of `{expr < 0}`), `dynamics.theta_ddot`,
    /// `dynamics.energy` or `functions.NAME`. Definitions it names are
    /// evaluated from their texts, each once, unless `at` gives them a value.
    pub fn exact<T: Scalar>(&self, key: &str, at: &ExactPoint<T>) -> Result<T, ExprError> {
        let missing = |message: String| ExprError {
            key: key.to_string(),
            offset: None,
            message,
        };
        let text = match key.split_once('.') {
            Some(("definitions", n)) => self.definitions.iter().find(|d| d.0 == n).map(|d| &d.1),
            Some(("regions", "omega")) => Some(&self.regions[0].expr),
            Some(("regions", "omega0")) => Some(&self.regions[1].expr),
            Some(("dynamics", "theta_ddot")) => self.dynamics_text[0].as_ref(),
            Some(("dynamics", "energy")) => self.dynamics_text[1].as_ref(),
            Some(("functions", n)) => self.function(n).map(|f| &f.text),
            _ => None,
        };
        let text = text.ok_or_else(|| missing(format!("no such text in `{}`", self.name)))?;
        self.exact_text(key, text, at, &mut HashMap::new())
    }

    fn exact_text<T: Scalar>(
        &self,
        key: &str,
        text: &str,
        at: &ExactPoint<T>,
        memo: &mut HashMap<String, T>,
    ) -> Result<T, ExprError> {
        let mut name = |n: &str| -> Option<Result<T, ExprError>> {
            if let Some(&(_, v)) = at.values.iter().find(|(m, _)| *m == n) {
                return Some(Ok(v));
            }
            if n == "theta_dot" {
                return Some(Ok(at.theta_dot));
            }
            if let Some(&v) = memo.get(n) {
                return Some(Ok(v));
            }
            if let Some((_, t)) = self.definitions.iter().find(|d| d.0 == n) {
                let v = self.exact_text(&format!("definitions.{n}"), t, at, memo);
                if let Ok(v) = v {
                    memo.insert(n.to_string(), v);
                }
                return Some(v);
            }
            if self.params.specs.iter().any(|s| s.name == n) {
                return Some(Err(ExprError {
                    key: key.to_string(),
                    offset: None,
                    message: format!("parameter `{n}` has no value given"),
                }));
            }
            None
        };
        eval_exact(key, text, &at.theta, &mut name)
    }

    /// θ̈'s Taylor recurrences ([`TaylorTape`](super::expr::TaylorTape)), if the file has `[dynamics]`.
    pub fn dynamics_taylor(&self) -> Option<super::expr::TaylorTape> {
        self.dynamics.as_ref()?.taylor()
    }

    /// θ̈ of `[dynamics]` as written, if the file gives it.
    pub fn dynamics_text(&self) -> Option<&str> {
        self.dynamics_text[0].as_deref()
    }

    /// θ̈ of `[dynamics]` as compiled, if the file gives it.
    pub fn dynamics_program(&self) -> Option<&Program> {
        self.dynamics.as_ref()
    }

    /// θ̈ as `f/g` when its text is a division at the top level.
    pub fn dynamics_quotient(&self) -> Option<super::expr::Quotient> {
        self.dynamics.as_ref()?.quotient()
    }

    /// θ̈ from `[dynamics]`; NaN without it.
    pub fn acceleration<T: crate::number::scalar::Scalar>(&self, theta: T, theta_dot: T) -> T {
        let mut out = [T::int(0) / T::int(0)];
        if let Some(p) = &self.dynamics {
            p.eval(theta, theta_dot, &mut out);
        }
        out[0]
    }
}

/// The message for a parameter-only subexpression that is (or may be)
/// undefined, naming the parameters with their values; and whether it is
/// proved undefined.
fn constant_message(issue: &super::expr::ConstantIssue, params: &ParamSet) -> (String, bool) {
    let values: Vec<String> = issue
        .params
        .iter()
        .map(|n| {
            let i = params.specs.iter().position(|s| s.name == n);
            let text = i.map_or("?", |i| params.values[i].text.as_str());
            format!("{n} = {text}")
        })
        .collect();
    let with = if values.is_empty() {
        String::new()
    } else {
        format!("with {}, ", values.join(", "))
    };
    let message = if issue.proved {
        format!(
            "{with}`{}` is undefined (division by zero, sqrt of a negative number, \
             ln of a number <= 0, ...) everywhere in the domain, and so is every formula \
             using it",
            issue.text
        )
    } else {
        format!(
            "{with}`{}` may be undefined: its operands' enclosures reach a point where \
             it is not defined (e.g. they contain 0); boxes where it is undefined stay undecided",
            issue.text
        )
    };
    (message, issue.proved)
}

/// `line L, column C: message` from a TOML error.
fn toml_message(text: &str, e: &toml::de::Error) -> String {
    let msg = e.message().trim_end().replace('\n', "; ");
    match e.span() {
        Some(span) => {
            let before = &text[..span.start.min(text.len())];
            let line = before.matches('\n').count() + 1;
            let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
            format!("line {line}, column {col}: {msg}")
        }
        None => msg,
    }
}

/// An expression error with its key as written in the file (a definition's
/// under `definitions.`), its position moved by `shift` characters.
fn expr_message(mut e: ExprError, shift: usize) -> String {
    if !e.key.contains('.') {
        e.key = format!("definitions.{}", e.key);
    }
    e.offset = e.offset.map(|n| n + shift);
    e.to_string()
}

/// The domain's ends: decimal text, `pi`, `pi/N`, or any expression of
/// numbers, `pi` and parameters (`2*pi`, `3*pi/2`), each enclosed.
fn domain_ends(
    key: &str,
    text: &[String; 2],
    params: &[(String, Interval)],
) -> Result<[Interval; 2], String> {
    let end = |t: &String| {
        if t.trim_start().starts_with('+') {
            return Err(format!("`{key}`: `{t}`: no leading `+`"));
        }
        enclose_window_end(key, t)
            .or_else(|_| enclose_constant(params, key, t))
            .map_err(|e| expr_message(e, 0))
    };
    let ends = [end(&text[0])?, end(&text[1])?];
    if ends[0].sup() < ends[1].inf() {
        Ok(ends)
    } else {
        Err(format!(
            "`{key}`: the lower end `{}` must lie below the upper end `{}`",
            text[0], text[1]
        ))
    }
}

fn check_name(key: &str, name: &str) -> Result<(), String> {
    let mut c = name.chars();
    let well_formed = c.next().is_some_and(|f| f.is_ascii_alphabetic())
        && c.all(|x| x.is_ascii_alphanumeric() || x == '_');
    if !well_formed {
        Err(format!(
            "`{key}`: `{name}` is not a name (a letter, then letters, digits or `_`)"
        ))
    } else if RESERVED.contains(&name) || name == "inf" {
        // `inf` is reserved in proof files (an unbounded end), so here too.
        Err(format!("`{key}`: `{name}` is reserved"))
    } else {
        Ok(())
    }
}

fn string_value<'a>(key: &str, v: &'a toml::Value) -> Result<&'a str, String> {
    v.as_str()
        .ok_or_else(|| format!("`{key}`: expected a string in quotes, got {}", v.type_str()))
}

/// The file's parameters (decimal text, quoted or bare), overridden by
/// `name=value` pairs.
fn parameters(
    scene: &str,
    table: &ParamTable,
    source: &str,
    overrides: &[(String, String)],
) -> Result<ParamSet, String> {
    let mut specs = Vec::with_capacity(table.0.len());
    for (name, entry) in &table.0 {
        let key = format!("parameters.{name}");
        check_name(&key, name)?;
        let raw = entry.get_ref();
        let text = match (&raw.value, &raw.span) {
            (Literal::Quoted(s), _) => s.clone(),
            (Literal::Bare, span) => {
                let span = span.clone().unwrap_or_else(|| entry.span());
                let t = source.get(span).unwrap_or_default();
                if let Err(ParamError::NotDecimal { .. }) = enclose_decimal(name, t) {
                    return Err(format!(
                        "`{key}`: `{t}` is not decimal text; write the number in quotes \
                         as decimal digits (e.g. \"1000\", \"2.5e-3\")"
                    ));
                }
                t.to_string()
            }
        };
        enclose_decimal(name, &text).map_err(|e| format!("`{key}`: {e}"))?;
        specs.push(ParamSpec {
            name: interned(name),
            default: interned(&text),
            meaning: interned(raw.description.as_deref().unwrap_or_default()),
            unit: interned(raw.unit.as_deref().unwrap_or_default()),
        });
    }
    ParamSet::build(scene, interned_specs(specs), overrides).map_err(|e| e.to_string())
}

/// A file's declarations live as long as the process, so that they share
/// `ParamSet` (`&'static` specs) with every scene. Each distinct text is
/// stored once: a scene compiled again (a parameter search compiles one per
/// box) adds nothing.
fn interned(s: &str) -> &'static str {
    static TEXTS: std::sync::Mutex<std::collections::BTreeSet<&'static str>> =
        std::sync::Mutex::new(std::collections::BTreeSet::new());
    let mut texts = TEXTS.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(t) = texts.get(s) {
        return t;
    }
    let t: &'static str = Box::leak(s.to_string().into_boxed_str());
    texts.insert(t);
    t
}

/// [`interned`] for a whole declaration list (its texts already interned).
fn interned_specs(specs: Vec<ParamSpec>) -> &'static [ParamSpec] {
    type Key = Vec<[usize; 4]>;
    static LISTS: std::sync::Mutex<Vec<(Key, &'static [ParamSpec])>> =
        std::sync::Mutex::new(Vec::new());
    let key: Key = specs
        .iter()
        .map(|p| [p.name, p.default, p.meaning, p.unit].map(|t| t.as_ptr() as usize))
        .collect();
    let mut lists = LISTS.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, l)) = lists.iter().find(|(k, _)| *k == key) {
        return l;
    }
    let l: &'static [ParamSpec] = Box::leak(specs.into_boxed_slice());
    lists.push((key, l));
    l
}

/// The definitions, ordered so that each uses only earlier ones.
fn definitions(table: &toml::Table, params: &ParamSet) -> Result<Vec<(String, String)>, String> {
    let mut defs = Vec::with_capacity(table.len());
    for (name, v) in table {
        let key = format!("definitions.{name}");
        check_name(&key, name)?;
        if params.specs.iter().any(|s| s.name == name) {
            return Err(format!("`{key}`: `{name}` is also a parameter"));
        }
        defs.push((name.clone(), string_value(&key, v)?.to_string()));
    }
    Ok(defs)
}

/// `[conditions]` checked on the enclosed parameters (and the boxes given
/// for some): each `lhs OP rhs` must be proved, OP one of `<`, `>`, `<=`,
/// `>=`. One that fails, or that the enclosures cannot decide (the two
/// sides overlap), is an error naming it and the values it reads.
fn conditions(
    table: &Ordered<String>,
    params: &ParamSet,
    enclosed: &[(String, Interval)],
    boxes: &[(String, Interval)],
) -> Result<Vec<(String, String)>, String> {
    let mut out = Vec::with_capacity(table.0.len());
    for (label, text) in &table.0 {
        let key = format!("conditions.{label}");
        if label.trim().is_empty() {
            return Err("`conditions`: a condition needs a name".into());
        }
        let (lhs, op, rhs) = split_condition(text).ok_or_else(|| {
            format!(
                "`{key}`: `{text}` is not one comparison `lhs < rhs`, `lhs > rhs`, \
                 `lhs <= rhs` or `lhs >= rhs`"
            )
        })?;
        let side = |t: &str, shift: usize| {
            enclose_constant(enclosed, &key, t).map_err(|e| expr_message(e, shift))
        };
        let l = side(lhs, 0)?;
        let r = side(rhs, lhs.chars().count() + op.chars().count())?;
        let (holds, fails) = match op {
            "<" => (l.sup() < r.inf(), l.inf() >= r.sup()),
            "<=" | "≤" => (l.sup() <= r.inf(), l.inf() > r.sup()),
            ">" => (l.inf() > r.sup(), l.sup() <= r.inf()),
            // `>=`, `≥`
            _ => (l.inf() >= r.sup(), l.sup() < r.inf()),
        };
        let with = values_read(text, params, boxes);
        if fails {
            return Err(format!("`{key}`: `{text}` does not hold{with}"));
        }
        if !holds {
            return Err(format!(
                "`{key}`: `{text}` cannot be decided{with}: the enclosures of its sides \
                 ([{}, {}] and [{}, {}]) overlap; give values for which it holds with a margin",
                short_num(l.inf()),
                short_num(l.sup()),
                short_num(r.inf()),
                short_num(r.sup())
            ));
        }
        out.push((label.clone(), text.clone()));
    }
    Ok(out)
}

/// ` with a = 1, b = 0.5` for the parameters a text names (as entered, or
/// as the box given), or nothing.
fn values_read(text: &str, params: &ParamSet, boxes: &[(String, Interval)]) -> String {
    let mut names: Vec<String> = Vec::new();
    let mut word = String::new();
    for c in text.chars().chain(std::iter::once(' ')) {
        if c.is_ascii_alphanumeric() || c == '_' {
            word.push(c);
            continue;
        }
        let w = std::mem::take(&mut word);
        if params.specs.iter().any(|s| s.name == w) && !names.contains(&w) {
            names.push(w);
        }
    }
    let values: Vec<String> = names
        .iter()
        .map(|w| match boxes.iter().find(|(n, _)| n == w) {
            Some((_, x)) => format!("{w} ∈ [{}, {}]", short_num(x.inf()), short_num(x.sup())),
            None => format!(
                "{w} = {}",
                params.values[params
                    .specs
                    .iter()
                    .position(|s| s.name == w)
                    .expect("named")]
                .text
            ),
        })
        .collect();
    if values.is_empty() {
        String::new()
    } else {
        format!(" with {}", values.join(", "))
    }
}

/// Splits a condition into `(lhs, op, rhs)`: exactly one comparison, `<`,
/// `>`, `<=`, `>=` (or `≤`, `≥`), both sides non-empty.
fn split_condition(text: &str) -> Option<(&str, &str, &str)> {
    let mut at = text
        .char_indices()
        .filter(|(_, c)| matches!(c, '<' | '>' | '≤' | '≥'));
    let (i, c) = at.next()?;
    let len = if text[i + c.len_utf8()..].starts_with('=') && !matches!(c, '≤' | '≥') {
        2
    } else {
        c.len_utf8()
    };
    if at.next().is_some() || text[i + len..].contains('=') || text[..i].contains('=') {
        return None;
    }
    let (lhs, op, rhs) = (&text[..i], &text[i..i + len], &text[i + len..]);
    (!lhs.trim().is_empty() && !rhs.trim().is_empty()).then_some((lhs, op, rhs))
}

/// Splits `lhs < rhs` or `lhs > rhs` (exactly one comparison).
fn split_inequality(text: &str) -> Option<(&str, &str, char)> {
    let mut at = text.char_indices().filter(|(_, c)| *c == '<' || *c == '>');
    let (i, op) = at.next()?;
    if at.next().is_some() {
        return None;
    }
    let (lhs, rhs) = (&text[..i], &text[i + 1..]);
    (!lhs.trim().is_empty() && !rhs.trim().is_empty()).then_some((lhs, rhs, op))
}

fn is_zero(s: &str) -> bool {
    let t = s.trim();
    !t.is_empty()
        && t.bytes().all(|b| b == b'0' || b == b'.')
        && t.bytes().any(|b| b == b'0')
        && t.bytes().filter(|b| *b == b'.').count() <= 1
}

/// The normal form `{expr < 0}`: a zero side is dropped, so `g < 0` keeps
/// the text of `g` (and its exact enclosures); negation is exact.
fn region(key: &str, text: &str) -> Result<Region, String> {
    if let Some(op) = ["<=", ">=", "≤", "≥"].iter().find(|op| text.contains(*op)) {
        let strict = if op.contains('<') || op.contains('≤') {
            "<"
        } else {
            ">"
        };
        return Err(format!(
            "`regions.{key}`: `{op}` is not accepted: detach certifies strict regions; \
             write `{strict}` (the same set up to the boundary lhs = rhs, which has zero area \
             unless lhs - rhs vanishes on a set of positive area)"
        ));
    }
    let (lhs, rhs, op) = split_inequality(text).ok_or_else(|| {
        format!("`regions.{key}`: `{text}` is not one inequality `lhs < rhs` or `lhs > rhs`")
    })?;
    let (small, large) = if op == '<' { (lhs, rhs) } else { (rhs, lhs) };
    let expr = match (is_zero(small), is_zero(large)) {
        (_, true) => small.trim().to_string(),
        (true, false) => format!("-({})", large.trim()),
        (false, false) => format!("({}) - ({})", small.trim(), large.trim()),
    };
    Ok(Region {
        inequality: text.to_string(),
        expr,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inequalities_take_their_normal_form() {
        let e = |t: &str| region("omega", t).map(|r| r.expr);
        assert_eq!(e("U < 0").unwrap(), "U");
        assert_eq!(e("U > 0.0").unwrap(), "-(U)");
        assert_eq!(e("0 < N").unwrap(), "-(N)");
        assert_eq!(e("a*x > b").unwrap(), "(b) - (a*x)");
        assert_eq!(e("a < b").unwrap(), "(a) - (b)");
        for bad in ["U", "U < 0 < 1", "< 0", "U >", "U = 0"] {
            assert!(e(bad).is_err(), "{bad}");
        }
    }

    const BASE: &str = r#"
name = "t"
[domain]
theta = ["0", "1"]
theta_dot = ["-1", "1"]
[parameters]
m = "2"
[regions]
omega = "theta_dot^2*m - 1 < 0"
omega0 = "theta_dot - theta > 0"
"#;

    fn with(from: &str, to: &str) -> Result<FileScene, String> {
        assert!(BASE.contains(from), "{from}");
        FileScene::parse(&BASE.replace(from, to), &[])
    }

    /// A bare TOML number is enclosed from its text, as the quoted text is:
    /// `1.1` is 11/10 (an interval of two doubles), not the double 1.1.
    #[test]
    fn bare_numbers_are_enclosed_from_their_text() {
        let quoted = with("m = \"2\"", "m = \"1.1\"").unwrap();
        for bare in ["m = 1.1", "m = { value = 1.1 }", "m = { value = \"1.1\" }"] {
            let f = with("m = \"2\"", bare).unwrap();
            assert_eq!(f.params.values[0].value, quoted.params.values[0].value);
            assert_eq!(f.params.values[0].text, "1.1");
        }
        assert!(!quoted.params.values[0].value.is_singleton());
        let f = with("theta = [\"0\", \"1\"]", "theta = [0, 1.5e0]").unwrap();
        assert_eq!(f.domain_text[0], ["0", "1.5e0"]);
        for bad in ["m = 1_000", "m = inf", "m = 0x10", "m = nan"] {
            let e = with("m = \"2\"", bad).err().unwrap();
            assert!(
                e.contains("parameters.m") && e.contains("in quotes"),
                "{bad}: {e}"
            );
        }
        // toml itself refuses it, with the line and column.
        let e = with("m = \"2\"", "m = 1e400").err().unwrap();
        assert!(e.contains("line 7") && e.contains("overflow"), "{e}");
        let e = with("m = \"2\"", "m = true").err().unwrap();
        assert!(e.contains("a string in quotes, a number"), "{e}");
        let e = with("m = \"2\"", "m = { value = 1, colour = \"red\" }")
            .err()
            .unwrap();
        assert!(e.contains("colour"), "{e}");
    }

    #[test]
    fn parameters_carry_a_description_and_a_unit() {
        let f = with(
            "m = \"2\"",
            "m = { value = \"2\", description = \"mass\", unit = \"kg\" }",
        )
        .unwrap();
        assert_eq!(
            (f.params.specs[0].meaning, f.params.specs[0].unit),
            ("mass", "kg")
        );
        let f = with("m = \"2\"", "[parameters.m]\nvalue = 2\nunit = \"kg\"").unwrap();
        assert_eq!(
            (f.params.specs[0].meaning, f.params.specs[0].unit),
            ("", "kg")
        );
    }

    /// Domain ends as expressions, enclosed: they contain 2π, 3π/2 and −π/2
    /// (f64 values of π multiples, ±1e-15 apart from either end at most).
    #[test]
    fn domain_ends_may_be_expressions() {
        let f = with("[\"0\", \"1\"]", "[\"-pi/2\", \"3*pi/2\"]").unwrap();
        let [lo, hi] = f.domain.theta;
        let pi = std::f64::consts::PI;
        assert!(lo.inf() <= -pi / 2.0 && -pi / 2.0 <= lo.sup() && lo.wid() < 1e-15);
        assert!(hi.inf() <= 1.5 * pi && 1.5 * pi <= hi.sup() && hi.wid() < 1e-15);
        let f = with("[\"0\", \"1\"]", "[\"0\", \"2*pi\"]").unwrap();
        assert!(f.domain.theta[1].contains(2.0 * pi));
        let f = with("[\"0\", \"1\"]", "[\"0\", \"m/4\"]").unwrap();
        assert_eq!(f.domain.theta[1].inf(), 0.5);
        for (bad, needle) in [
            ("[\"0\", \"theta\"]", "must not depend"),
            ("[\"0\", \"ln(0)\"]", "not a defined"),
            ("[\"0\", \"2*foo\"]", "unknown name `foo`"),
        ] {
            let e = with("[\"0\", \"1\"]", bad).err().unwrap();
            assert!(
                e.contains("domain.theta") && e.contains(needle),
                "{bad}: {e}"
            );
        }
    }

    #[test]
    fn one_inequality_states_omega0_as_omega() {
        let f = with("omega0 = \"theta_dot - theta > 0\"\n", "").unwrap();
        assert!(f.omega0_is_omega());
        assert_eq!(f.regions[1].inequality, f.regions[0].inequality);
    }

    #[test]
    fn non_strict_comparisons_are_refused_with_a_hint() {
        for (op, strict) in [("<=", "`<`"), (">=", "`>`")] {
            let e = with("1 < 0", &format!("1 {op} 0")).err().unwrap();
            assert!(e.contains("regions.omega") && e.contains(strict), "{e}");
        }
    }

    /// `1/m` with m = 0 is undefined everywhere: refused before any work,
    /// naming m and the subexpression; `sqrt(m - 0.1)` with m = 0.1 is
    /// defined (√0) though its enclosure reaches below 0: a warning only.
    #[test]
    fn parameters_that_make_a_formula_undefined_are_found_first() {
        let zero = [("m".to_string(), "0".to_string())];
        let text = BASE.replace("theta_dot^2*m", "theta_dot^2/m");
        let e = FileScene::parse(&text, &zero).err().unwrap();
        assert!(e.contains("with m = 0, `theta_dot^2/m`"), "{e}");
        assert!(e.contains("everywhere in the domain"), "{e}");
        // The divisor m·θ depends on θ but is exactly 0 all over the domain.
        let text = BASE.replace("theta_dot^2*m", "theta_dot^2/(m*theta)");
        let e = FileScene::parse(&text, &zero).err().unwrap();
        assert!(
            e.contains("with m = 0, `theta_dot^2/(m*theta)` is undefined"),
            "{e}"
        );
        // Undefined all over the domain θ ∈ [0, 1], no parameter involved.
        let e = with("1 < 0", "sqrt(theta - 5) < 0").err().unwrap();
        assert!(e.starts_with("`sqrt(theta - 5)` is undefined"), "{e}");
        assert!(FileScene::parse(&text, &[]).unwrap().warnings.is_empty());
        let e = with("theta_dot^2*m", "theta_dot^2*sqrt(m - 3)")
            .err()
            .unwrap();
        assert!(e.contains("`sqrt(m - 3)`") && e.contains("m = 2"), "{e}");
        let e = with("1 < 0", "ln(1 - 1) < 0").err().unwrap();
        assert!(e.starts_with("`ln(1 - 1)` is undefined"), "{e}");
        let point_one = [("m".to_string(), "0.1".to_string())];
        let text = BASE.replace("theta_dot^2*m", "theta_dot^2*sqrt(m - 0.1)");
        let f = FileScene::parse(&text, &point_one).unwrap();
        assert_eq!(f.warnings.len(), 1, "{:?}", f.warnings);
        assert!(
            f.warnings[0].contains("may be undefined"),
            "{:?}",
            f.warnings
        );
        // θ-dependent subexpressions are the pavers' business, not this check's.
        assert!(with("1 < 0", "1/theta < 0").unwrap().warnings.is_empty());
    }

    #[test]
    fn underflowing_and_repeated_parameters_are_refused() {
        let e = with("m = \"2\"", "m = \"1e-400\"").err().unwrap();
        assert!(e.contains("too small"), "{e}");
        let twice = [("m", "1"), ("m", "3")].map(|(a, b)| (a.to_string(), b.to_string()));
        let e = FileScene::parse(BASE, &twice).err().unwrap();
        assert!(e.contains("`m` is given twice"), "{e}");
    }
}
