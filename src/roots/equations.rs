//! The equations of §2–§3 as certified root problems on their open domains.
//!
//! The isolator works on a closed interval of doubles; each solver here proves
//! the rest of the mathematical domain (the ends near θ = 0 and θ = π, or the
//! tail μ → ∞) root-free by an explicit argument, recorded as an [`EdgeProof`].

use super::cluster::{clusters, Cluster};
use super::isolate::{isolate, point, Budget, RootEnclosure, RootStatus, Stats, UndecidedReason};
use super::{RealFn, RootsError};
use crate::number::param::ParamSet;
use crate::number::scalar::Scalar;
use crate::scene::file::Function;
use crate::scene::Scene;
use inari::{const_interval, Interval};
use serde::Serialize;
use std::fmt;

/// The equations `detach roots` solves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum EquationId {
    /// (2.9) `κ sin³θ = cos θ (α − cos θ)(1 − α cos θ)`, θ ∈ (0, π).
    #[serde(rename = "2.9")]
    E2_9,
    /// (2.10) `2κ = μ(1 − μ)(1 + μ)`, μ > 0.
    #[serde(rename = "2.10")]
    E2_10,
    /// (2.12) stationary points of Π̃, θ ∈ (0, π).
    #[serde(rename = "2.12")]
    E2_12,
    /// Equilibria of (3.3), θ ∈ (0, π).
    #[serde(rename = "3.3")]
    E3_3,
}

impl EquationId {
    pub const ALL: [EquationId; 4] = [Self::E2_9, Self::E2_10, Self::E2_12, Self::E3_3];
    pub fn name(self) -> &'static str {
        match self {
            Self::E2_9 => "2.9",
            Self::E2_10 => "2.10",
            Self::E2_12 => "2.12",
            Self::E3_3 => "3.3",
        }
    }
    pub fn parse(s: &str) -> Option<EquationId> {
        let s = s.trim().trim_start_matches('(').trim_end_matches(')');
        Self::ALL.into_iter().find(|e| e.name() == s)
    }
}

impl fmt::Display for EquationId {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A part of the domain proved root-free outside the isolator's search.
#[derive(Clone, Debug, Serialize)]
pub struct EdgeProof {
    /// Which end, e.g. `theta -> 0+`.
    pub end: String,
    /// The part covered: `(lo, hi)` as doubles enclosing it (infinite allowed).
    pub part: [f64; 2],
    /// The argument, in words.
    pub argument: String,
    /// The certified enclosure the argument rests on (must exclude 0, or
    /// have the stated sign).
    pub witness: [f64; 2],
    pub proved: bool,
}

/// All roots of one equation on its domain.
#[derive(Clone, Debug, Serialize)]
pub struct EquationRoots {
    pub equation: EquationId,
    pub variable: &'static str,
    /// The mathematical domain as doubles (open ends; `null` in JSON for ∞).
    pub domain: [f64; 2],
    pub domain_text: &'static str,
    /// The closed interval searched by the isolator.
    pub searched: [f64; 2],
    /// Sorted, disjoint enclosures; every root of the domain lies in one.
    pub roots: Vec<RootEnclosure>,
    /// Every enclosure is `Unique` and every edge is proved root-free: the
    /// roots are exactly one per enclosure, all simple.
    pub complete: bool,
    pub edges: Vec<EdgeProof>,
    /// Runs of nearby undecided enclosures with a bound on their root count
    /// ([`cluster`](super::cluster)); members index into `roots`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub clusters: Vec<Cluster>,
    pub stats: Stats,
}

impl EquationRoots {
    pub fn unique_count(&self) -> usize {
        self.roots
            .iter()
            .filter(|r| r.status == RootStatus::Unique)
            .count()
    }
}

fn two() -> Interval {
    const_interval!(2.0, 2.0)
}

fn enc(x: Interval) -> [f64; 2] {
    [x.inf(), x.sup()]
}

fn check_kappa(kappa: Interval) -> Result<(), RootsError> {
    if kappa.is_empty() || kappa.inf() <= 0.0 || !kappa.sup().is_finite() {
        return Err(RootsError::KappaNotPositive(format!(
            "[{:e}, {:e}]",
            kappa.inf() + 0.0,
            kappa.sup() + 0.0
        )));
    }
    Ok(())
}

fn check_alpha(alpha: Interval) -> Result<(), RootsError> {
    if alpha.is_empty() || !alpha.subset(const_interval!(-1.0, 1.0)) {
        return Err(RootsError::AlphaOutOfRange(format!(
            "[{:e}, {:e}]",
            alpha.inf() + 0.0,
            alpha.sup() + 0.0
        )));
    }
    Ok(())
}

/// (2.9) as `f(θ) = κ sin³θ − cos θ (α − cos θ)(1 − α cos θ)`, in θ with
/// the parameters κ, α: the one text the isolator evaluates and a proof
/// states.
pub const TEXT_2_9: &str =
    "kappa*sin(theta)^2*sin(theta) - cos(theta)*(alpha - cos(theta))*(1 - alpha*cos(theta))";

/// (2.10) as `g(μ) = μ(1 − μ)(1 + μ) − 2κ`, in μ with the parameter κ.
pub const TEXT_2_10: &str = "mu*(1 - mu)*(1 + mu) - 2*kappa";

/// An equation's text compiled once over its parameters' enclosures, as a
/// scene file's function is: the same operations, in the order written.
fn equation(name: &str, variable: &str, text: &str, params: &[(&str, Interval)]) -> Function {
    let params: Vec<(String, Interval)> = params.iter().map(|(n, x)| (n.to_string(), *x)).collect();
    Function::of_variable(name, variable, text, &params).expect("the equation texts compile")
}

/// A compiled function of one variable (a scene's `[functions]`, or an
/// equation's text) is what the isolator solves.
impl RealFn for Function {
    fn eval<T: Scalar>(&self, x: T) -> T {
        Function::eval(self, x)
    }
}

/// (2.9) at κ, α ([`TEXT_2_9`]).
pub fn eq_2_9(kappa: Interval, alpha: Interval) -> Function {
    equation(
        "2.9",
        "theta",
        TEXT_2_9,
        &[("kappa", kappa), ("alpha", alpha)],
    )
}

/// (2.10) at κ ([`TEXT_2_10`]).
pub fn eq_2_10(kappa: Interval) -> Function {
    equation("2.10", "mu", TEXT_2_10, &[("kappa", kappa)])
}

/// (2.9) multiplied by `(1 + s²)³`, `s = tan(θ/2)`:
/// `P(s) = 8κ s³ − (1 − s²)(e² s⁴ − d²)`, `d = 1 − α`, `e = 1 + α`.
/// Its positive roots are `tan(θ/2)` of the roots of (2.9), same multiplicity.
pub struct Eq29TanHalf {
    pub kappa: Interval,
    pub alpha: Interval,
}

impl RealFn for Eq29TanHalf {
    fn eval<T: Scalar>(&self, s: T) -> T {
        let (k, a) = (T::lift(self.kappa), T::lift(self.alpha));
        let (d, e) = (T::int(1) - a, T::int(1) + a);
        let s2 = s.sqr();
        T::int(8) * k * s2 * s - (T::int(1) - s2) * (e.sqr() * s2.sqr() - d.sqr())
    }
}

/// For `s ∈ (0, σ]`, `P(s) = d²(1 − s²) + s³(8κ − e² s) + e² s⁶ > 0` as soon
/// as `σ ≤ 1` and `8κ − e² σ > 0`. Returns σ and the enclosure of `8κ − e²σ`.
fn tan_half_edge(kappa: Interval, e: Interval) -> (f64, Interval) {
    let e2 = e.sqr();
    let mut sigma = if e2.sup() > 0.0 {
        (4.0 * kappa.inf() / e2.sup()).min(0.5)
    } else {
        0.5
    };
    loop {
        let margin = const_interval!(8.0, 8.0) * kappa - e2 * point(sigma);
        if margin.inf() > 0.0 || sigma < f64::MIN_POSITIVE {
            return (sigma, margin);
        }
        sigma /= 2.0;
    }
}

/// Solves (2.9) for κ > 0, α ∈ [−1, 1] (enclosures) on θ ∈ (0, π).
pub fn solve_2_9(
    kappa: Interval,
    alpha: Interval,
    budget: &Budget,
) -> Result<EquationRoots, RootsError> {
    check_kappa(kappa)?;
    check_alpha(alpha)?;
    let one = const_interval!(1.0, 1.0);
    let mut edges = Vec::new();
    // θ → 0+: s = tan(θ/2) → 0+, e = 1 + α. θ → π−: by θ → π − θ, α → −α.
    let mut ends = [0.0; 2];
    for (i, e) in [one + alpha, one - alpha].into_iter().enumerate() {
        let (sigma, margin) = tan_half_edge(kappa, e);
        let half_angle = two() * point(sigma).atan();
        let proved = margin.inf() > 0.0;
        let (end, part, bound) = if i == 0 {
            let b = half_angle.inf();
            ("theta -> 0+", [0.0, b], b)
        } else {
            let b = (Interval::PI - half_angle).sup();
            ("theta -> pi-", [b, Interval::PI.sup()], b)
        };
        ends[i] = bound;
        edges.push(EdgeProof {
            end: end.into(),
            part,
            argument: format!(
                "with s = tan(θ/2) (θ → π − θ for the upper end, i.e. α → −α), \
                 (2.9)·(1+s²)³ = d²(1−s²) + s³(8κ − e²s) + e²s⁶, d = 1−α, e = 1+α; \
                 for s ∈ (0, σ], σ = {sigma:e}, every term is ≥ 0 and 8κ − e²σ > 0"
            ),
            witness: enc(margin),
            proved,
        });
    }
    let f = eq_2_9(kappa, alpha);
    let iso = isolate(&f, ends[0], ends[1], budget);
    Ok(finish(
        &f,
        EquationId::E2_9,
        ("theta", [0.0, Interval::PI.sup()], "(0, pi)"),
        iso,
        edges,
        Vec::new(),
    ))
}

/// Solves (2.10) for κ > 0 (an enclosure) on μ ∈ (0, ∞).
pub fn solve_2_10(kappa: Interval, budget: &Budget) -> Result<EquationRoots, RootsError> {
    check_kappa(kappa)?;
    let tail = Interval::try_from((1.0, f64::INFINITY)).expect("valid");
    let one = const_interval!(1.0, 1.0);
    let p_tail = tail * (one - tail) * (one + tail);
    let edge = EdgeProof {
        end: "mu -> +inf".into(),
        part: [1.0, f64::INFINITY],
        argument: "for μ ≥ 1, μ(1−μ)(1+μ) ≤ 0 < 2κ (the enclosure of μ(1−μ)(1+μ) over [1, +∞] has sup ≤ 0)".into(),
        witness: enc(p_tail),
        proved: p_tail.sup() <= 0.0 && kappa.inf() > 0.0,
    };
    let f = eq_2_10(kappa);
    let iso = isolate(&f, 0.0, 1.0, budget);
    Ok(finish(
        &f,
        EquationId::E2_10,
        ("mu", [0.0, f64::INFINITY], "(0, inf)"),
        iso,
        vec![edge],
        Vec::new(),
    ))
}

/// The equation's roots, with clusters bounded by `f` (the isolated function).
fn finish<F: RealFn>(
    f: &F,
    equation: EquationId,
    (variable, domain, domain_text): (&'static str, [f64; 2], &'static str),
    iso: super::Isolation,
    edges: Vec<EdgeProof>,
    edge_fragments: Vec<RootEnclosure>,
) -> EquationRoots {
    let mut roots = iso.roots;
    roots.extend(edge_fragments);
    let roots = super::isolate::merge_undecided(roots);
    let complete = roots.iter().all(|r| r.is_unique()) && edges.iter().all(|e| e.proved);
    let clusters = clusters(f, &roots, iso.domain);
    EquationRoots {
        equation,
        variable,
        domain,
        domain_text,
        searched: iso.domain,
        roots,
        complete,
        edges,
        clusters,
        stats: iso.stats,
    }
}

/// κ and α of (2.9) for a disc's parameters (`g`, `A`, `a`, `p_phi`,
/// `p_psi`), as enclosures: `κ = g A²/(a p_M²)`, `α = p_m/p_M`, p_M the
/// momentum of larger absolute value. When the two may be equal in absolute
/// value, α encloses both ratios (clipped to [−1, 1]).
pub fn kappa_alpha(params: &ParamSet) -> Result<(Interval, Interval), RootsError> {
    let (pf, ps) = (params.get("p_phi"), params.get("p_psi"));
    let (g, big_a, a) = (params.get("g"), params.get("A"), params.get("a"));
    let pm2 = pf.sqr().max(ps.sqr());
    let zero = const_interval!(0.0, 0.0);
    if pf == zero && ps == zero {
        return Err(RootsError::NoMomentum);
    }
    if pm2.inf() <= 0.0 {
        return Err(RootsError::OutOfRange("overflows", "p_M² underflows"));
    }
    let kappa = g * big_a.sqr() / (a * pm2);
    if !kappa.sup().is_finite() {
        return Err(RootsError::OutOfRange("overflows", "κ above 1.8e308"));
    }
    if kappa.inf() <= 0.0 {
        return Err(RootsError::OutOfRange("underflows", "κ below 5e-324"));
    }
    let unit = const_interval!(-1.0, 1.0);
    let (af, as_) = (pf.abs(), ps.abs());
    let alpha = if af.inf() > as_.sup() {
        ps / pf
    } else if as_.inf() > af.sup() {
        pf / ps
    } else {
        // |p_φ| and |p_ψ| not separated: α is one of the two ratios.
        let r1 = (pf / ps).intersection(unit);
        let r2 = (ps / pf).intersection(unit);
        if r1.is_empty() {
            r2
        } else if r2.is_empty() {
            r1
        } else {
            r1.convex_hull(r2)
        }
    };
    Ok((kappa, alpha.intersection(unit)))
}

/// The scene function an equation is solved on: (2.12) is `eq_2_12`, (3.3)
/// `eq_3_3` of the scene's `[functions]` (each with its singular factors
/// cleared, so defined wherever the scene's formulas are).
pub fn scene_function(scene: &Scene, equation: EquationId) -> Option<&Function> {
    let name = match equation {
        EquationId::E2_12 => "eq_2_12",
        EquationId::E3_3 => "eq_3_3",
        _ => return None,
    };
    scene.function(crate::scene::Variant::Derived, name)
}

/// The ends θ → 0+ and θ → π− of a scene equation, handled by enclosing the
/// scaled function over `(0, δ]` (resp. `[π − δ, π)`) in terms of
/// `s = sin θ ∈ (0, sin δ]` and `c = cos θ` with the singular factors cleared.
/// Tries δ = 2⁻², 2⁻⁴, …; `enclose(θ, s, c, near_pi)` must enclose the
/// scaled function on the whole end (θ the end's range).
fn scene_edges(
    enclose: impl Fn(Interval, Interval, Interval, bool) -> Interval,
    what: &str,
) -> ([f64; 2], Vec<EdgeProof>, Vec<RootEnclosure>) {
    let deltas = [
        0.25,
        0.0625,
        2f64.powi(-7),
        2f64.powi(-10),
        2f64.powi(-14),
        2f64.powi(-20),
    ];
    let mut bounds = [0.0; 2];
    let mut edges = Vec::new();
    let mut fragments = Vec::new();
    for near_pi in [false, true] {
        let mut found = None;
        let mut last = None;
        for &delta in &deltas {
            let d = point(delta);
            let s = Interval::try_from((0.0, d.sin().sup())).expect("valid");
            let c = if near_pi {
                Interval::try_from((-1.0, -d.cos().inf())).expect("valid")
            } else {
                Interval::try_from((d.cos().inf(), 1.0)).expect("valid")
            };
            let theta = if near_pi {
                (Interval::PI - d).convex_hull(Interval::PI)
            } else {
                Interval::try_from((0.0, delta)).expect("valid")
            };
            let y = enclose(theta, s, c, near_pi);
            last = Some((delta, y));
            if !y.is_empty() && !y.contains(0.0) {
                found = Some((delta, y));
                break;
            }
        }
        let (delta, y) = found.or(last).expect("non-empty list");
        let proved = found.is_some();
        let (end, part, bound) = if near_pi {
            let b = (Interval::PI - point(delta)).sup();
            ("theta -> pi-", [b, Interval::PI.sup()], b)
        } else {
            ("theta -> 0+", [0.0, delta], delta)
        };
        bounds[usize::from(near_pi)] = bound;
        if !proved {
            fragments.push(RootEnclosure::undecided(
                part[0],
                part[1],
                UndecidedReason::DomainEdge,
            ));
        }
        edges.push(EdgeProof {
            end: end.into(),
            part,
            argument: format!(
                "{what} enclosed over the whole end (s = sin θ ∈ (0, sin δ], c = cos θ, δ = {delta:e}) \
                 with the singular factors cleared; the enclosure excludes 0"
            ),
            witness: enc(y),
            proved,
        });
    }
    (bounds, edges, fragments)
}

/// Stationary points of Π̃ (2.12) on θ ∈ (0, π): zeros of the scene's
/// `eq_2_12` (`sin³θ·Π̃'(θ)`, defined on all of [0, π], so its ends are
/// enclosed by evaluating it there).
pub fn solve_2_12(f: &Function, budget: &Budget) -> EquationRoots {
    let enclose = |theta: Interval, _s, _c, _near_pi| f.eval(theta);
    solve_scene_on_theta(EquationId::E2_12, enclose, "sin³θ·Π̃'(θ)", f, budget)
}

/// Equilibria of (3.3) (zeros of θ̈, which does not depend on θ̇) on
/// θ ∈ (0, π): zeros of the scene's `eq_3_3` (`sin³θ·θ̈`). Its ends need
/// the limit of `s² ln s` at 0, which an enclosure of the text cannot give,
/// so they are bounded from the disc's parameters by the analysis below.
pub fn solve_3_3(f: &Function, params: &ParamSet, budget: &Budget) -> EquationRoots {
    let p = |n: &str| params.get(n);
    let (m, a, g, big_a, pf, ps, c0) = (
        p("m"),
        p("a"),
        p("g"),
        p("A"),
        p("p_phi"),
        p("p_psi"),
        p("c0"),
    );
    let one = const_interval!(1.0, 1.0);
    // (A + m a²) sin³θ θ̈ = −m g a c s³ + (m a/A) (v_x s²)(p_ψ − p_φ c) − (p_ψ − p_φ c)(p_φ − p_ψ c)/A,
    // v_x s² = c₀ s² − (a/A)(p_ψ s² ln tg(θ/2) − p_φ s² ln s), with
    // ln tg(θ/2) = ln s − ln(1 + c) near 0 and = ln(1 − c) − ln s near π,
    // and s² ln s ∈ [S² ln S, 0] for s ∈ (0, S], S ≤ e^{-1/2}.
    let enclose = |_theta, s: Interval, c: Interval, near_pi: bool| {
        let big_s = point(s.sup());
        let l = Interval::try_from(((big_s.sqr() * big_s.ln()).inf(), 0.0)).expect("valid");
        let s2 = s.sqr();
        let vx_s2 = if near_pi {
            c0 * s2 - a / big_a * (ps * s2 * (one - c).ln() - (ps + pf) * l)
        } else {
            c0 * s2 - a / big_a * ((ps - pf) * l - ps * s2 * (one + c).ln())
        };
        -(m * g * a * c * s2 * s) + m * a / big_a * vx_s2 * (ps - pf * c)
            - (ps - pf * c) * (pf - ps * c) / big_a
    };
    solve_scene_on_theta(
        EquationId::E3_3,
        enclose,
        "(A + m a²) sin³θ·θ̈(θ)",
        f,
        budget,
    )
}

/// A scene equation on θ ∈ (0, π): the open ends proved by `enclose` (the
/// function with its singular factors cleared), the interior by the isolator.
fn solve_scene_on_theta<F: RealFn>(
    equation: EquationId,
    enclose: impl Fn(Interval, Interval, Interval, bool) -> Interval,
    what: &str,
    f: &F,
    budget: &Budget,
) -> EquationRoots {
    let (bounds, edges, fragments) = scene_edges(enclose, what);
    let iso = isolate(f, bounds[0], bounds[1], budget);
    finish(
        f,
        equation,
        ("theta", [0.0, Interval::PI.sup()], "(0, pi)"),
        iso,
        edges,
        fragments,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::number::param::enclose_decimal;
    use crate::scene::{Scene, SceneId};

    fn dec(t: &str) -> Interval {
        enclose_decimal("x", t).unwrap()
    }

    #[test]
    fn alpha_zero_has_no_root() {
        // Paper §2 case 1: f_r < 0 on (0, π) when α = 0.
        for k in ["0.01", "0.2", "3"] {
            let r = solve_2_9(dec(k), dec("0"), &Budget::default()).unwrap();
            assert!(r.complete, "{k}: {r:?}");
            assert!(r.roots.is_empty());
        }
    }

    #[test]
    fn theta_and_tan_half_forms_agree() {
        // Roots of (2.9) in θ map to roots of P(s) by s = tan(θ/2).
        let (k, a) = (dec("0.05"), dec("0.7"));
        let r = solve_2_9(k, a, &Budget::default()).unwrap();
        assert!(r.complete);
        assert_eq!(r.roots.len(), 2);
        let p = isolate(
            &Eq29TanHalf { kappa: k, alpha: a },
            1e-3,
            1e3,
            &Budget::default(),
        );
        assert!(p.complete);
        assert_eq!(p.roots.len(), 2);
        for (t, s) in r.roots.iter().zip(&p.roots) {
            let s_from_theta = (t.interval() / two()).tan();
            assert!(!s_from_theta.disjoint(s.interval()), "{t:?} vs {s:?}");
        }
    }

    #[test]
    fn bad_kappa_and_alpha_are_errors() {
        assert!(solve_2_9(dec("0"), dec("0.5"), &Budget::default()).is_err());
        assert!(solve_2_9(dec("-1"), dec("0.5"), &Budget::default()).is_err());
        assert!(solve_2_9(dec("1"), dec("1.5"), &Budget::default()).is_err());
        assert!(solve_2_9(dec("1"), dec("1.0000000000000000001"), &Budget::default()).is_err());
        // A κ whose enclosure reaches 0 (decimal text now refuses 1e-400).
        let tiny = Interval::try_from((0.0, f64::from_bits(1))).unwrap();
        assert!(solve_2_10(tiny, &Budget::default()).is_err());
    }

    #[test]
    fn scene_equations_on_defaults_are_complete() {
        let b = Budget::default();
        let disc = Scene::default_of(SceneId::SmoothDisc);
        let r = solve_2_12(scene_function(&disc, EquationId::E2_12).unwrap(), &b);
        assert!(r.complete, "{r:?}");
        // (2.12): one or three stationary points (paper, refs [7, 8]).
        assert!(r.roots.len() == 1 || r.roots.len() == 3, "{r:?}");
        let (ice, params) = Scene::build(SceneId::IceDisc, &[]).unwrap();
        let r = solve_3_3(scene_function(&ice, EquationId::E3_3).unwrap(), &params, &b);
        assert!(r.complete, "{r:?}");
        for root in &r.roots {
            // θ̈ changes sign across each unique enclosure (checked with the
            // unscaled scene formula, 1e-9 outside the endpoints: a few-ulp
            // enclosure is narrower than the rounding of f at its endpoints).
            let f = |x: f64| {
                let a = crate::scene::Angle::new(point(x));
                ice.acceleration(crate::scene::Variant::Derived, &a, point(0.0))
            };
            let (l, h) = (f(root.lo - 1e-9), f(root.hi + 1e-9));
            assert!(l.sup() < 0.0 && h.inf() > 0.0 || l.inf() > 0.0 && h.sup() < 0.0);
        }
    }
}
