//! Certified equilibria and singular points of a scene's `[dynamics]`, with
//! their type.
//!
//! The field is (θ̇, F(θ, θ̇)), F the scene's θ̈.
//!
//! * **Equilibria**: θ̇ = 0 and F(θ, 0) = 0. The roots in θ are isolated by
//!   [`crate::roots::isolate`](mod@crate::roots::isolate) (interval Newton, exclusion): each returned
//!   root is unique, the rest of the θ-range root-free, or a fragment is
//!   undecided with its reason. When F is written `f/g` the roots of
//!   `f(θ, 0)` are isolated instead (no poles where `g` vanishes) and each
//!   is an equilibrium once `g` is proved non-zero on its enclosure.
//! * **Singular points**: for F = f/g, the points where f = g = 0: 2-D
//!   bisection, a box excluded where 0 ∉ f(X) or 0 ∉ g(X) (decorated, so the
//!   formula is defined on X), a zero proved unique by the Krawczyk test
//!   K(X) ⊂ int X with the interval Jacobian of dual numbers (decorated
//!   ≥ dac: f, g are C¹ on X, which the test needs).
//! * **Type**: from an interval Jacobian over the point's unique box (it
//!   contains the Jacobian at the point): the linearised field for an
//!   equilibrium, the desingularised field (time rescaled by g) for a
//!   singular point.
//!
//! With parameters enclosed as intervals every statement holds for every
//! parameter value of the box; [`scan`] bisects a parameter interval where
//! the count or a type is undecided, and the thresholds are the gaps
//! between boxes that are decided differently.
//!
//! f64 only steers (midpoints, the Krawczyk preconditioner, split points);
//! every conclusion is read off interval enclosures.

use super::interval_json;
use crate::number::scalar::{is_continuous, is_defined, Dual, Scalar};
use crate::params::report::exact_decimal;
use crate::params::Family;
use crate::roots::isolate::split_point;
use crate::roots::{isolate, Budget, RealFn};
use crate::scene::expr::Program;
use crate::scene::{Domain, FileScene};
use inari::{DecInterval, Interval};
use serde_json::{json, Value};

/// An equilibrium of (θ̇, F) or a singular point of F = f/g.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum PointKind {
    Equilibrium,
    Singular,
}

impl PointKind {
    pub fn name(self) -> &'static str {
        match self {
            PointKind::Equilibrium => "equilibrium",
            PointKind::Singular => "singular",
        }
    }
}

/// The type of a point, as its certified Jacobian proves it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum PointType {
    Saddle,
    StableNode,
    UnstableNode,
    StableFocus,
    UnstableFocus,
    /// A linear centre of a reversible field, on its line of symmetry: a
    /// nonlinear centre.
    Centre,
    Undecided,
}

impl PointType {
    pub fn name(self) -> &'static str {
        match self {
            PointType::Saddle => "saddle",
            PointType::StableNode => "stable node",
            PointType::UnstableNode => "unstable node",
            PointType::StableFocus => "stable focus",
            PointType::UnstableFocus => "unstable focus",
            PointType::Centre => "centre",
            PointType::Undecided => "undecided",
        }
    }
}

/// An eigendirection at a singular point where g does not depend on θ̇:
/// there the singular curve g = 0 is the line θ = const.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Direction {
    /// Transverse to the singular line.
    Across,
    /// Along the singular line (the θ̇ axis).
    Along,
}

impl Direction {
    pub fn name(self) -> &'static str {
        match self {
            Direction::Across => "across",
            Direction::Along => "along",
        }
    }
}

/// A point proved unique in `theta` × `theta_dot`, with what is proved of
/// its linearisation.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    pub kind: PointKind,
    pub theta: Interval,
    pub theta_dot: Interval,
    pub point_type: PointType,
    /// Enclosures of the two eigenvalues, when they are proved real.
    pub eigenvalues: Option<[Interval; 2]>,
    /// The eigenvalues' eigendirections, when they are known (singular
    /// points of a θ̇-free g).
    pub directions: Option<[Direction; 2]>,
    /// The eigenvalue of smaller modulus (index into `eigenvalues`), when
    /// proved.
    pub slower: Option<usize>,
}

impl Point {
    /// The slower eigenvalue's direction, when both are known.
    pub fn slow_direction(&self) -> Option<Direction> {
        Some(self.directions?[self.slower?])
    }
}

/// A box where neither a unique point nor the absence of points was proved.
#[derive(Clone, Debug, PartialEq)]
pub struct Undecided {
    pub kind: PointKind,
    pub theta: Interval,
    pub theta_dot: Interval,
    pub reason: String,
}

/// Everything proved on one domain: the unique points, and the boxes left
/// undecided; the rest of the domain holds no equilibrium (and, when
/// `quotient`, no singular point).
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    pub points: Vec<Point>,
    pub undecided: Vec<Undecided>,
    /// θ̈ is written f/g, so singular points were searched.
    pub quotient: bool,
    /// Boxes the singular-point search visited.
    pub boxes: usize,
}

/// Work limits of one search.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// Most boxes of the 2-D singular-point search.
    pub max_boxes: usize,
    /// Boxes narrower than this fraction of the domain (on both sides) are
    /// not bisected further.
    pub min_width: f64,
    /// The equilibrium isolator's budget.
    pub budget: Budget,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            max_boxes: 200_000,
            min_width: 1e-10,
            budget: Budget::default(),
        }
    }
}

fn point(x: f64) -> Interval {
    Interval::try_from((x, x)).expect("finite double")
}

/// The search side for a domain side: its ends' outer enclosure, widened
/// by 2⁻³⁰ of its width so that a point on the domain's edge (the upright
/// rod at θ = π/2) lies inside a box, not on its boundary.
fn search_side(ends: [Interval; 2]) -> Interval {
    let margin = point((ends[1].sup() - ends[0].inf()) * 2f64.powi(-30));
    let lo = (point(ends[0].inf()) - margin).inf();
    let hi = (point(ends[1].sup()) + margin).sup();
    Interval::try_from((lo, hi)).expect("ordered domain ends")
}

/// One output of `p` at (θ, θ̇).
fn eval1<T: Scalar>(p: &Program, theta: T, theta_dot: T) -> T {
    let mut out = [theta];
    p.eval(theta, theta_dot, &mut out);
    out[0]
}

/// Decorated enclosure over a box.
pub(super) fn enclose(p: &Program, x: [Interval; 2]) -> DecInterval {
    eval1(p, DecInterval::new(x[0]), DecInterval::new(x[1]))
}

/// Value and gradient over a box, when `p` is proved C¹ on it.
pub(super) fn gradient(p: &Program, x: [Interval; 2]) -> Option<(Interval, [Interval; 2])> {
    let d = eval1(
        p,
        Dual::variable(DecInterval::new(x[0]), 0),
        Dual::variable(DecInterval::new(x[1]), 1),
    );
    let ok = is_continuous(d.value) && d.grad.iter().all(|&g| is_continuous(g));
    ok.then(|| {
        let i = |x: DecInterval| x.interval().expect("continuous");
        (i(d.value), [i(d.grad[0]), i(d.grad[1])])
    })
}

/// Proved non-zero over the box, where the formula is defined.
fn excludes_zero(x: DecInterval) -> bool {
    is_defined(x) && !x.interval().expect("defined").contains(0.0)
}

/// `h(θ) = p(θ, 0)`: what vanishes at an equilibrium.
struct AtRest<'a>(&'a Program);

impl RealFn for AtRest<'_> {
    fn eval<T: Scalar>(&self, theta: T) -> T {
        eval1(self.0, theta, T::int(0))
    }
}

/// The equilibria and singular points of `scene`'s `[dynamics]` in
/// `domain` (its ends' outer enclosures).
pub fn find(scene: &FileScene, domain: &Domain, opts: &Options) -> Result<Report, String> {
    let dynamics = scene.dynamics_program().ok_or_else(|| {
        format!(
            "scene `{}` has no [dynamics]: there is no θ̈ to find equilibria of",
            scene.name
        )
    })?;
    let quotient = dynamics.quotient();
    let x0 = [search_side(domain.theta), search_side(domain.theta_dot)];
    let mut report = Report {
        points: Vec::new(),
        undecided: Vec::new(),
        quotient: quotient.is_some(),
        boxes: 0,
    };
    equilibria(dynamics, quotient.as_ref(), x0, opts, &mut report);
    if let Some(q) = &quotient {
        singular_points(&q.numerator, &q.denominator, x0, opts, &mut report);
    }
    // What lies wholly in the margin is outside the domain.
    let domain_box = [
        Interval::try_from((domain.theta[0].inf(), domain.theta[1].sup())),
        Interval::try_from((domain.theta_dot[0].inf(), domain.theta_dot[1].sup())),
    ]
    .map(|x| x.expect("ordered domain ends"));
    let meets = |t: Interval, w: Interval| {
        !t.intersection(domain_box[0]).is_empty() && !w.intersection(domain_box[1]).is_empty()
    };
    report.points.retain(|p| meets(p.theta, p.theta_dot));
    report.undecided.retain(|u| meets(u.theta, u.theta_dot));
    Ok(report)
}

fn equilibria(
    dynamics: &Program,
    quotient: Option<&crate::scene::expr::Quotient>,
    x0: [Interval; 2],
    opts: &Options,
    report: &mut Report,
) {
    let zero = point(0.0);
    if !x0[1].contains(0.0) {
        return; // no point of the domain has θ̇ = 0
    }
    let h = quotient.map_or(dynamics, |q| &q.numerator);
    let iso = isolate(&AtRest(h), x0[0].inf(), x0[0].sup(), &opts.budget);
    for r in iso.roots {
        let theta = Interval::try_from((r.lo, r.hi)).expect("ordered root");
        let undecided = |reason: &str| Undecided {
            kind: PointKind::Equilibrium,
            theta,
            theta_dot: zero,
            reason: reason.to_string(),
        };
        if !r.is_unique() {
            let why = r.reason.map_or("undecided", |w| w.describe());
            report.undecided.push(undecided(why));
            continue;
        }
        // A unique zero of f(·, 0) is the unique zero of F = f/g there when
        // g is proved non-zero on the enclosure.
        if let Some(q) = quotient {
            if !excludes_zero(enclose(&q.denominator, [theta, zero])) {
                report
                    .undecided
                    .push(undecided("a zero of f where g may vanish too"));
                continue;
            }
        }
        report.points.push(equilibrium_type(dynamics, theta));
    }
}

/// The equilibrium at θ ∈ `theta`, θ̇ = 0, typed by J = [[0, 1], [F_θ,
/// F_θ̇]]: det J = −F_θ, tr J = F_θ̇.
fn equilibrium_type(dynamics: &Program, theta: Interval) -> Point {
    let zero = point(0.0);
    let mut p = Point {
        kind: PointKind::Equilibrium,
        theta,
        theta_dot: zero,
        point_type: PointType::Undecided,
        eigenvalues: None,
        directions: None,
        slower: None,
    };
    let Some((_, [f_theta, f_dot])) = gradient(dynamics, [theta, zero]) else {
        return p;
    };
    // F even in θ̇ makes the field reversible under (θ, θ̇, t) ↦ (θ, −θ̇,
    // −t); then F_θ̇(θ, 0) = 0 exactly, and a linear centre on θ̇ = 0 is a
    // centre of the nonlinear field.
    let reversible = dynamics.even_in_theta_dot();
    let trace = if reversible { zero } else { f_dot };
    let det = -f_theta;
    let disc = trace.sqr() - point(4.0) * det;
    if disc.inf() > 0.0 {
        let s = disc.sqrt();
        let half = point(0.5);
        p.eigenvalues = Some([(trace - s) * half, (trace + s) * half]);
    }
    p.point_type = classify(det, trace, p.eigenvalues, reversible);
    p.slower = p.eigenvalues.and_then(slower);
    p
}

/// The type from the determinant and trace of a 2×2 Jacobian, or from its
/// eigenvalues when they are proved real. `centre`: the field is proved
/// reversible with the point on its line of symmetry.
fn classify(det: Interval, trace: Interval, eig: Option<[Interval; 2]>, centre: bool) -> PointType {
    if let Some([a, b]) = eig {
        return match (a.sup() < 0.0, a.inf() > 0.0, b.sup() < 0.0, b.inf() > 0.0) {
            (true, _, true, _) => PointType::StableNode,
            (_, true, _, true) => PointType::UnstableNode,
            (true, _, _, true) | (_, true, true, _) => PointType::Saddle,
            _ => PointType::Undecided,
        };
    }
    if det.sup() < 0.0 {
        return PointType::Saddle;
    }
    if det.inf() <= 0.0 {
        return PointType::Undecided;
    }
    if centre {
        return PointType::Centre;
    }
    let disc = trace.sqr() - point(4.0) * det;
    match (disc.sup() < 0.0, trace.sup() < 0.0, trace.inf() > 0.0) {
        (true, true, _) => PointType::StableFocus,
        (true, _, true) => PointType::UnstableFocus,
        _ => PointType::Undecided,
    }
}

/// The index of the eigenvalue of proved smaller modulus.
fn slower([a, b]: [Interval; 2]) -> Option<usize> {
    let (a, b) = (a.abs(), b.abs());
    if a.sup() < b.inf() {
        Some(0)
    } else if b.sup() < a.inf() {
        Some(1)
    } else {
        None
    }
}

/// Outcome of one Krawczyk step on a box.
enum Krawczyk {
    /// K(X) ⊂ int X: exactly one zero of (f, g) in X, and it lies in K(X).
    Unique([Interval; 2]),
    /// K(X) ∩ X = ∅: no zero in X.
    NoZero,
    /// Every zero of X lies in K(X) ∩ X.
    Contracted([Interval; 2]),
    /// Not applicable, and why.
    Fails(&'static str),
}

/// K(X) = m − Y H(m) + (I − Y J(X)) (X − m) for H = (f, g), J(X) the
/// interval Jacobian, Y ≈ mid J(X)⁻¹ (any matrix keeps the test valid).
fn krawczyk(f: &Program, g: &Program, x: [Interval; 2]) -> Krawczyk {
    let (Some((_, df)), Some((_, dg))) = (gradient(f, x), gradient(g, x)) else {
        return Krawczyk::Fails("f or g not proved continuously differentiable on the box");
    };
    let j = [df, dg];
    let mid = |i: Interval| i.mid();
    let (a, b, c, d) = (mid(j[0][0]), mid(j[0][1]), mid(j[1][0]), mid(j[1][1]));
    let det = a * d - b * c;
    let y = [[d / det, -b / det], [-c / det, a / det]];
    if !(det != 0.0 && y.iter().flatten().all(|v| v.is_finite())) {
        return Krawczyk::Fails("the Jacobian may be singular: a multiple or close zeros");
    }
    let m = [point(x[0].mid()), point(x[1].mid())];
    let (hf, hg) = (enclose(f, m), enclose(g, m));
    if !is_defined(hf) || !is_defined(hg) {
        return Krawczyk::Fails("f or g not defined at the box's centre");
    }
    let h = [
        hf.interval().expect("defined"),
        hg.interval().expect("defined"),
    ];
    let y = y.map(|row| row.map(point));
    let one = point(1.0);
    let mut k = [m[0]; 2];
    for i in 0..2 {
        let yh = y[i][0] * h[0] + y[i][1] * h[1];
        let mut s = m[i] - yh;
        for (l, xm) in [x[0] - m[0], x[1] - m[1]].into_iter().enumerate() {
            let yj = y[i][0] * j[0][l] + y[i][1] * j[1][l];
            let e = if i == l { one - yj } else { -yj };
            s += e * xm;
        }
        k[i] = s;
    }
    if k[0].interior(x[0]) && k[1].interior(x[1]) {
        return Krawczyk::Unique(k);
    }
    let c = [k[0].intersection(x[0]), k[1].intersection(x[1])];
    if c[0].is_empty() || c[1].is_empty() {
        Krawczyk::NoZero
    } else {
        Krawczyk::Contracted(c)
    }
}

/// The zeros of (f, g) in `x0` by bisection, exclusion and Krawczyk.
fn singular_points(f: &Program, g: &Program, x0: [Interval; 2], opts: &Options, r: &mut Report) {
    let scale = [
        x0[0].wid().max(f64::MIN_POSITIVE),
        x0[1].wid().max(f64::MIN_POSITIVE),
    ];
    let size = |x: [Interval; 2]| x[0].wid() / scale[0] + x[1].wid() / scale[1];
    let mut stack = vec![x0];
    while let Some(x) = stack.pop() {
        let undecided = |reason: &str| Undecided {
            kind: PointKind::Singular,
            theta: x[0],
            theta_dot: x[1],
            reason: reason.to_string(),
        };
        if r.boxes >= opts.max_boxes {
            r.undecided.push(undecided("budget"));
            continue;
        }
        r.boxes += 1;
        // g first: for a θ-only denominator it excludes whole strips.
        let (gx, fx) = (enclose(g, x), enclose(f, x));
        if excludes_zero(gx) || excludes_zero(fx) {
            continue;
        }
        let why = if !is_defined(gx) || !is_defined(fx) {
            "f or g not defined on the box"
        } else {
            match krawczyk(f, g, x) {
                Krawczyk::Unique(k) => {
                    r.points.push(singular_type(f, g, refine(f, g, k)));
                    continue;
                }
                Krawczyk::NoZero => continue,
                Krawczyk::Contracted(c) if size(c) < 0.5 * size(x) => {
                    stack.push(c);
                    continue;
                }
                Krawczyk::Contracted(_) => "tolerance reached",
                Krawczyk::Fails(why) => why,
            }
        };
        // Bisect the side widest relative to the domain.
        let rel = [x[0].wid() / scale[0], x[1].wid() / scale[1]];
        let k = usize::from(rel[1] > rel[0]);
        let (a, b) = (x[k].inf(), x[k].sup());
        let m = split_point(a, b);
        if rel[k] <= opts.min_width || m == a {
            r.undecided.push(undecided(why));
            continue;
        }
        let (mut lo, mut hi) = (x, x);
        lo[k] = Interval::try_from((a, m)).expect("ordered");
        hi[k] = Interval::try_from((m, b)).expect("ordered");
        stack.push(hi);
        stack.push(lo);
    }
}

/// Contracts a box holding exactly one zero until it stops shrinking:
/// every K(X) ∩ X still holds it.
fn refine(f: &Program, g: &Program, mut x: [Interval; 2]) -> [Interval; 2] {
    for _ in 0..50 {
        let next = match krawczyk(f, g, x) {
            Krawczyk::Unique(k) | Krawczyk::Contracted(k) => {
                [k[0].intersection(x[0]), k[1].intersection(x[1])]
            }
            _ => break,
        };
        if next[0].is_empty()
            || next[1].is_empty()
            || next[0].wid() + next[1].wid() >= x[0].wid() + x[1].wid()
        {
            break;
        }
        x = next;
    }
    x
}

/// The singular point in `x`, typed by the desingularised field. With time
/// rescaled by g (dt = g ds) the field (θ̇, f/g) becomes G = (g θ̇, f),
/// smooth where f and g are, with zeros at the singular points. Its
/// Jacobian, by the product rule on g θ̇:
///     DG = [[g_θ θ̇, g_θ̇ θ̇ + g], [f_θ, f_θ̇]].
/// Where g < 0 the rescaling reverses time: stable and unstable refer to G.
/// For g free of θ̇, g_θ̇ = 0 and g = 0 at the point make DG lower
/// triangular there: eigenvalues g_θ θ̇ (eigenvector across the singular
/// line θ = const) and f_θ̇ (eigenvector (0, 1), along it).
fn singular_type(f: &Program, g: &Program, x: [Interval; 2]) -> Point {
    let mut p = Point {
        kind: PointKind::Singular,
        theta: x[0],
        theta_dot: x[1],
        point_type: PointType::Undecided,
        eigenvalues: None,
        directions: None,
        slower: None,
    };
    let (Some((_, [f_theta, f_dot])), Some((g_val, [g_theta, g_dot]))) =
        (gradient(f, x), gradient(g, x))
    else {
        return p;
    };
    let w = x[1];
    if !g.reads_theta_dot() {
        let eig = [g_theta * w, f_dot];
        p.eigenvalues = Some(eig);
        p.directions = Some([Direction::Across, Direction::Along]);
        p.point_type = classify(eig[0] * eig[1], eig[0] + eig[1], Some(eig), false);
    } else {
        let dg = [[g_theta * w, g_dot * w + g_val], [f_theta, f_dot]];
        let det = dg[0][0] * dg[1][1] - dg[0][1] * dg[1][0];
        let trace = dg[0][0] + dg[1][1];
        let disc = trace.sqr() - point(4.0) * det;
        if disc.inf() > 0.0 {
            let s = disc.sqrt();
            p.eigenvalues = Some([(trace - s) * point(0.5), (trace + s) * point(0.5)]);
        }
        p.point_type = classify(det, trace, p.eigenvalues, false);
    }
    p.slower = p.eigenvalues.and_then(slower);
    p
}

/// What a parameter box's report proves, in words that compare between
/// boxes: one entry per point (kind, type, and the slow direction where it
/// is known), sorted; `None` when anything is undecided.
pub fn signature(r: &Report) -> Option<Vec<String>> {
    if !r.undecided.is_empty() {
        return None;
    }
    let mut out = Vec::new();
    for p in &r.points {
        if p.point_type == PointType::Undecided {
            return None;
        }
        let slow = match p.directions {
            Some(_) => format!(", slow {}", p.slow_direction()?.name()),
            None => String::new(),
        };
        out.push(format!("{} {}{slow}", p.kind.name(), p.point_type.name()));
    }
    out.sort();
    Some(out)
}

/// One box of a parameter scan.
#[derive(Clone, Debug)]
pub struct ParamBox {
    pub lo: f64,
    pub hi: f64,
    pub report: Report,
    pub signature: Option<Vec<String>>,
}

/// A certified threshold: the box ending at `lo` is decided with signature
/// `below`, the box starting at `hi` with `above` (the boxes between are
/// undecided), so the change lies in [lo, hi].
#[derive(Clone, Debug)]
pub struct Threshold {
    pub lo: f64,
    pub hi: f64,
    pub below: Vec<String>,
    pub above: Vec<String>,
}

impl Threshold {
    /// hi − lo, rounded up.
    pub fn width(&self) -> f64 {
        (point(self.hi) - point(self.lo)).sup()
    }
}

/// A scan of one parameter interval.
#[derive(Clone, Debug)]
pub struct Scan {
    pub name: String,
    pub lo_text: String,
    pub hi_text: String,
    pub boxes: Vec<ParamBox>,
    pub thresholds: Vec<Threshold>,
}

/// Limits of a parameter scan.
#[derive(Clone, Copy, Debug)]
pub struct ScanOptions {
    pub search: Options,
    /// Parameter boxes narrower than this fraction of the interval are not
    /// bisected further.
    pub eps: f64,
    /// Most parameter boxes searched.
    pub max_boxes: usize,
}

impl Default for ScanOptions {
    fn default() -> Self {
        ScanOptions {
            search: Options {
                max_boxes: 20_000,
                ..Options::default()
            },
            eps: 2f64.powi(-24),
            max_boxes: 2_000,
        }
    }
}

/// Bisects the family's one parameter interval where a box's signature is
/// undecided; thresholds between decided boxes of different signatures.
pub fn scan(family: &Family, domain: &Domain, opts: &ScanOptions) -> Result<Scan, String> {
    if family.axes.len() != 1 {
        return Err("give one parameter to vary (NAME=LO:HI)".into());
    }
    let [lo, hi] = family.root[0];
    let mut boxes = Vec::new();
    let mut stack = vec![[lo, hi]];
    let mut searched = 0;
    while let Some([a, b]) = stack.pop() {
        let scene = family.scene_at(&[[a, b]])?;
        let report = find(scene.reading(family.variant), domain, &opts.search)?;
        searched += 1;
        let signature = signature(&report);
        let m = split_point(a, b);
        let open = signature.is_none() && (b - a) > opts.eps * (hi - lo) && m > a;
        if open && searched + stack.len() + 2 <= opts.max_boxes {
            stack.push([m, b]);
            stack.push([a, m]);
            continue;
        }
        boxes.push(ParamBox {
            lo: a,
            hi: b,
            report,
            signature,
        });
    }
    let mut thresholds = Vec::new();
    let mut last: Option<(&Vec<String>, f64)> = None;
    for bx in &boxes {
        let Some(s) = &bx.signature else { continue };
        if let Some((prev, end)) = last {
            if prev != s {
                thresholds.push(Threshold {
                    lo: end,
                    hi: bx.lo,
                    below: prev.clone(),
                    above: s.clone(),
                });
            }
        }
        last = Some((s, bx.hi));
    }
    Ok(Scan {
        name: family.axes[0].name.clone(),
        lo_text: family.axes[0].lo.clone(),
        hi_text: family.axes[0].hi.clone(),
        boxes,
        thresholds,
    })
}

/// One point as JSON.
pub fn point_json(p: &Point) -> Value {
    json!({
        "kind": p.kind.name(),
        "theta": interval_json(p.theta),
        "theta_dot": interval_json(p.theta_dot),
        "type": p.point_type.name(),
        "eigenvalues": p.eigenvalues.map(|e| e.map(interval_json).to_vec()),
        "eigendirections": p.directions.map(|d| d.map(|d| d.name()).to_vec()),
        "slower": p.slower,
        "slow_direction": p.slow_direction().map(|d| d.name()),
        "unique": true,
    })
}

/// A report as JSON: the points, the number of undecided boxes and them.
pub fn report_json(r: &Report) -> Value {
    json!({
        "points": r.points.iter().map(point_json).collect::<Vec<_>>(),
        "undecided": r.undecided.len(),
        "undecided_boxes": r.undecided.iter().map(|u| json!({
            "kind": u.kind.name(),
            "theta": interval_json(u.theta),
            "theta_dot": interval_json(u.theta_dot),
            "reason": u.reason,
        })).collect::<Vec<_>>(),
        "singular_points_searched": r.quotient,
    })
}

/// A scan as JSON: per box its ends and classification, and the thresholds.
pub fn scan_json(s: &Scan, root: [f64; 2]) -> Value {
    let end = |x: f64| {
        if x == root[0] {
            s.lo_text.clone()
        } else if x == root[1] {
            s.hi_text.clone()
        } else {
            exact_decimal(x)
        }
    };
    json!({
        "parameter": s.name,
        "range": [s.lo_text, s.hi_text],
        "thresholds": s.thresholds.iter().map(|t| json!({
            "enclosure": [end(t.lo), end(t.hi)],
            "width": exact_decimal(t.width()),
            "below": t.below,
            "above": t.above,
        })).collect::<Vec<_>>(),
        "boxes": s.boxes.iter().map(|b| json!({
            "range": [end(b.lo), end(b.hi)],
            "decided": b.signature.is_some(),
            "classification": b.signature,
            "points": b.report.points.iter().map(point_json).collect::<Vec<_>>(),
            "undecided": b.report.undecided.len(),
        })).collect::<Vec<_>>(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(a: f64, b: f64) -> Interval {
        Interval::try_from((a, b)).unwrap()
    }

    fn program(text: &str) -> Program {
        Program::compile(&[], &[], &[("o".into(), text.into())]).unwrap()
    }

    #[test]
    fn types_follow_the_signs_of_det_trace_and_eigenvalues() {
        let (neg, pos, zero) = (iv(-2.0, -1.0), iv(1.0, 2.0), iv(0.0, 0.0));
        assert_eq!(classify(neg, pos, None, false), PointType::Saddle);
        assert_eq!(
            classify(iv(4.0, 5.0), neg, None, false),
            PointType::StableFocus
        );
        assert_eq!(
            classify(iv(4.0, 5.0), pos, None, false),
            PointType::UnstableFocus
        );
        assert_eq!(classify(iv(4.0, 5.0), zero, None, true), PointType::Centre);
        // A zero trace without reversibility proves nothing.
        assert_eq!(
            classify(iv(4.0, 5.0), zero, None, false),
            PointType::Undecided
        );
        assert_eq!(
            classify(iv(-1.0, 1.0), neg, None, true),
            PointType::Undecided
        );
        let node = Some([neg, iv(-0.5, -0.25)]);
        assert_eq!(classify(pos, neg, node, false), PointType::StableNode);
        assert_eq!(
            classify(neg, zero, Some([neg, pos]), false),
            PointType::Saddle
        );
        assert_eq!(
            classify(pos, neg, Some([neg, iv(-1.0, 1.0)]), false),
            PointType::Undecided
        );
        assert_eq!(slower([neg, iv(-0.5, -0.25)]), Some(1));
        assert_eq!(slower([neg, iv(-1.5, 1.0)]), None);
    }

    #[test]
    fn krawczyk_proves_a_simple_zero_and_excludes_a_box_without_one() {
        // f = θ² − 2, g = θ̇ − θ: the zero (√2, √2).
        let (f, g) = (program("theta^2 - 2"), program("theta_dot - theta"));
        let Krawczyk::Unique(k) = krawczyk(&f, &g, [iv(1.0, 2.0), iv(1.0, 2.0)]) else {
            panic!("unique expected");
        };
        let k = refine(&f, &g, k);
        let r2 = 2f64.sqrt();
        assert!(k[0].contains(r2) && k[1].contains(r2) && k[0].wid() < 1e-14);
        assert!(matches!(
            krawczyk(&f, &g, [iv(1.5, 2.0), iv(-1.0, 0.0)]),
            Krawczyk::NoZero
        ));
        // A double zero: the Jacobian of (θ², θ̇) is singular at 0.
        let (f, g) = (program("theta^2"), program("theta_dot"));
        assert!(matches!(
            krawczyk(&f, &g, [iv(-1.0, 1.0), iv(-1.0, 1.0)]),
            Krawczyk::Fails(_)
        ));
    }
}
