//! Root claims as `roots` and `kappa0` proof files.
//!
//! The evidence is rebuilt from the isolator's answer rather than copied from
//! its search: each unique root gets an interval-Newton box `X` wide enough
//! that `N(X)` sits well inside it, and the gaps between are covered by
//! exclusion pieces (natural, then mean-value), bisected where needed. Pieces
//! that resist within the budget are written as `undecided`, and the claim
//! weakens accordingly; nothing is dropped.

use super::numbers::{decimal, hex, Round};
use crate::number::param::enclose_decimal;
use crate::number::scalar::{is_defined, Dual, Scalar};
use crate::roots::isolate::{point, split_point, RootEnclosure};
use crate::roots::RealFn;
use inari::{DecInterval, Decoration, Interval};
use serde_json::{json, Map, Value};

/// Significant digits of claimed root enclosures.
const ROOT_DIGITS: usize = 16;
/// Ulps a claimed enclosure leaves around the prover's own on each side, at
/// least; see [`with_slack`].
const SLACK_ULPS: u32 = 8;
/// Widths of the prover's enclosure added on each side: a checker rounding
/// correctly but more loosely computes a wider `f(m)`, and so a wider Newton
/// image, in proportion to the rounding error this width already shows.
const SLACK_WIDTHS: f64 = 8.0;

/// `x` widened on each side by [`SLACK_WIDTHS`] of its width and then by
/// [`SLACK_ULPS`] ulps, so that any correct checker's enclosure still lies
/// inside the claim.
fn with_slack(x: Interval) -> (f64, f64) {
    let w = SLACK_WIDTHS * (x.sup() - x.inf());
    let (mut a, mut b) = ((x.inf() - w).next_down(), (x.sup() + w).next_up());
    for _ in 0..SLACK_ULPS {
        a = a.next_down();
        b = b.next_up();
    }
    (a, b)
}

/// A claimed unique enclosure: `n` with slack ([`with_slack`]), in decimal
/// text of at most [`ROOT_DIGITS`] digits, inside the piece `[lo, hi]` (the
/// checker requires it there) and around `n`.
fn claim_with_slack(n: Interval, lo: f64, hi: f64) -> (String, String) {
    let (a, b) = with_slack(n);
    (
        claim_end(a.max(lo), lo, n.inf(), Round::Down),
        claim_end(b.min(hi), n.sup(), hi, Round::Up),
    )
}

/// Decimal text near `target` whose enclosure lies in `[floor, ceil]`:
/// rounded `dir` (outward) where that stays in range, else the other way;
/// 17 digits when 16 cannot do it.
fn claim_end(target: f64, floor: f64, ceil: f64, dir: Round) -> String {
    let inward = match dir {
        Round::Down => Round::Up,
        Round::Up => Round::Down,
    };
    let fits =
        |t: &str| enclose_decimal("bound", t).is_ok_and(|e| floor <= e.inf() && e.sup() <= ceil);
    [ROOT_DIGITS, 17]
        .into_iter()
        .flat_map(|d| [decimal(target, d, dir), decimal(target, d, inward)])
        .find(|t| fits(t))
        .unwrap_or_else(|| decimal(target, 17, dir))
}
/// Most pieces one proof may hold.
const MAX_PIECES: usize = 20_000;

/// One piece of the evidence.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PieceKind {
    Exclude,
    ExcludeMv(f64),
    /// The Newton point and the `N(X)` the prover computed.
    Newton(f64, Interval),
    Undecided,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piece {
    pub lo: f64,
    pub hi: f64,
    pub kind: PieceKind,
}

fn iv(lo: f64, hi: f64) -> Interval {
    Interval::try_from((lo, hi)).expect("ordered endpoints")
}

fn smooth(d: DecInterval) -> Option<Interval> {
    (d.decoration() >= Decoration::Dac)
        .then(|| d.interval())
        .flatten()
}

/// `N(X)` when `f`, `f'` are continuous on X, `0 ∉ f'(X)`, `f(m)` defined.
fn newton<F: RealFn>(f: &F, x: Interval, m: f64) -> Option<Interval> {
    let y = f.eval(Dual::variable(DecInterval::new(x), 0));
    let (_, d) = (smooth(y.value)?, smooth(y.grad[0])?);
    let fm = f.eval(DecInterval::new(point(m)));
    if !is_defined(fm) || d.contains(0.0) {
        return None;
    }
    Some(point(m) - fm.interval()? / d)
}

/// How a gap piece is proved root-free, if it is at this size.
fn exclusion<F: RealFn>(f: &F, x: Interval) -> Option<PieceKind> {
    let v = f.eval(DecInterval::new(x));
    if is_defined(v) && !v.interval()?.contains(0.0) {
        return Some(PieceKind::Exclude);
    }
    if !(x.inf().is_finite() && x.sup().is_finite()) {
        return None;
    }
    let m = x.mid();
    let y = f.eval(Dual::variable(DecInterval::new(x), 0));
    let d = smooth(y.grad[0])?;
    smooth(y.value)?;
    let fm = f.eval(DecInterval::new(point(m)));
    if !is_defined(fm) {
        return None;
    }
    let mv = fm.interval()? + d * (x - point(m));
    (!mv.contains(0.0)).then_some(PieceKind::ExcludeMv(m))
}

/// A Newton box around a few-ulp root enclosure, inside `[lo, hi]`, with
/// `N(X)` at least an eighth of X's width away from both ends (room for a
/// checker whose derivative enclosure differs by rounding). It reaches about
/// 10⁻¹² (relative) from the root on each side, so that the exclusion pieces
/// beside it see |f| far above any checker's rounding error.
fn newton_box<F: RealFn>(f: &F, r: &RootEnclosure, lo: f64, hi: f64) -> Option<Piece> {
    let scale = r.lo.abs().max(r.hi.abs()).max(f64::MIN_POSITIVE);
    let mut delta = (r.hi - r.lo).max(scale * 2.5e-13) * 4.0;
    for _ in 0..40 {
        let (a, b) = ((r.lo - delta).max(lo), (r.hi + delta).min(hi));
        if a < b {
            let x = iv(a, b);
            let m = split_point(a, b);
            if let Some(n) = newton(f, x, m) {
                let margin = (b - a) / 8.0;
                if n.inf() > a + margin && n.sup() < b - margin {
                    return Some(Piece {
                        lo: a,
                        hi: b,
                        kind: PieceKind::Newton(m, n),
                    });
                }
            }
        }
        delta *= 4.0;
    }
    None
}

/// Covers `[a, b]` with exclusion pieces, bisecting; `undecided` below
/// `min_width` or past the budget.
fn cover_gap<F: RealFn>(f: &F, a: f64, b: f64, min_width: f64, out: &mut Vec<Piece>) {
    let mut stack = vec![(a, b)];
    while let Some((a, b)) = stack.pop() {
        let kind = exclusion(f, iv(a, b));
        // An unbounded gap is cut at a finite point beyond `a` first; not at
        // 1, where the paper's polynomials have factors (1 − s²) that vanish
        // exactly, and an exclusion would rest on that exact 0.
        let m = if b.is_finite() {
            split_point(a, b)
        } else {
            (2.0 * a.abs()).max(1.5)
        };
        let kind = match kind {
            Some(k) => k,
            None if out.len() + stack.len() >= MAX_PIECES
                || !(a < m && m < b)
                || (b.is_finite() && b - a <= min_width * a.abs().max(1.0)) =>
            {
                PieceKind::Undecided
            }
            None => {
                stack.push((m, b));
                stack.push((a, m));
                continue;
            }
        };
        out.push(Piece { lo: a, hi: b, kind });
    }
}

/// Evidence for the zeros of `f` on `[lo, hi]` (`hi` may be +∞), guided by
/// the isolator's enclosures.
pub fn build_pieces<F: RealFn>(f: &F, lo: f64, hi: f64, hints: &[RootEnclosure]) -> Vec<Piece> {
    let mut boxes: Vec<Piece> = Vec::new();
    for r in hints.iter().filter(|r| r.is_unique()) {
        let floor = boxes.last().map_or(lo, |p| p.hi);
        if let Some(p) = newton_box(f, r, floor, hi) {
            boxes.push(p);
        }
    }
    let mut out = Vec::new();
    let mut at = lo;
    for p in boxes {
        if at < p.lo {
            cover_gap(f, at, p.lo, 1e-12, &mut out);
        }
        at = p.hi;
        out.push(p);
    }
    if at < hi {
        cover_gap(f, at, hi, 1e-12, &mut out);
    }
    out
}

/// A piece as JSON (exact doubles in hexadecimal).
pub fn piece_json(p: &Piece) -> Value {
    let (lo, hi) = (hex(p.lo), hex(p.hi));
    match p.kind {
        PieceKind::Exclude => json!({ "lo": lo, "hi": hi, "kind": "exclude" }),
        PieceKind::ExcludeMv(m) => {
            json!({ "lo": lo, "hi": hi, "kind": "exclude_mv", "point": hex(m) })
        }
        PieceKind::Newton(m, _) => {
            json!({ "lo": lo, "hi": hi, "kind": "newton", "point": hex(m) })
        }
        PieceKind::Undecided => json!({ "lo": lo, "hi": hi, "kind": "undecided" }),
    }
}

/// The claimed enclosures: `N(X)` of each Newton piece with slack, rounded
/// outward, and the hull of each run of undecided pieces.
pub fn claimed_roots(pieces: &[Piece]) -> Vec<Value> {
    let mut out = Vec::new();
    let mut run: Option<(f64, f64)> = None;
    let flush = |run: &mut Option<(f64, f64)>, out: &mut Vec<Value>| {
        if let Some((a, b)) = run.take() {
            out.push(json!({
                "lo": decimal(a, ROOT_DIGITS, Round::Down),
                "hi": if b.is_finite() { decimal(b, ROOT_DIGITS, Round::Up) } else { "inf".into() },
                "status": "undecided",
            }));
        }
    };
    for p in pieces {
        match p.kind {
            PieceKind::Undecided => {
                run = Some(run.map_or((p.lo, p.hi), |(a, _)| (a, p.hi)));
            }
            PieceKind::Newton(_, n) => {
                flush(&mut run, &mut out);
                let (lo, hi) = claim_with_slack(n, p.lo, p.hi);
                out.push(json!({ "lo": lo, "hi": hi, "status": "unique" }));
            }
            _ => flush(&mut run, &mut out),
        }
    }
    flush(&mut run, &mut out);
    out
}

/// What a `roots` proof states besides its evidence.
pub struct RootsStatement<'a> {
    pub title: String,
    pub equation: &'a str,
    pub paper: &'a str,
    pub parameters: Vec<(String, String)>,
    pub definitions: Vec<(String, String)>,
    pub variable: &'a str,
    pub function: String,
    pub domain: [&'a str; 2],
}

/// The `roots` proof file.
pub fn roots_proof(st: &RootsStatement, pieces: &[Piece]) -> Value {
    let mut params = Map::new();
    for (n, t) in &st.parameters {
        params.insert(n.clone(), Value::String(t.clone()));
    }
    let complete = pieces.iter().all(|p| p.kind != PieceKind::Undecided);
    json!({
        "format": "detach-proof/1",
        "claim": "roots",
        "title": st.title,
        "producer": super::producer(),
        "statement": {
            "equation": st.equation,
            "paper": st.paper,
            "parameters": params,
            "definitions": st.definitions.iter().map(|(n, e)| json!([n, e])).collect::<Vec<_>>(),
            "variable": st.variable,
            "function": st.function,
            "domain": { "lo": st.domain[0], "hi": st.domain[1] },
            "roots": claimed_roots(pieces),
            "complete": complete,
        },
        "evidence": { "pieces": pieces.iter().map(piece_json).collect::<Vec<_>>() },
    })
}

/// `p(μ) = μ(1 − μ)(1 + μ)` of (2.10), written once for every scalar.
fn p<T: Scalar>(mu: T) -> T {
    mu * (T::int(1) - mu) * (T::int(1) + mu)
}

/// `p(μ) = μ(1 − μ)(1 + μ)` in the proof language.
pub const P_TEXT: &str = "mu*(1 - mu)*(1 + mu)";

/// `p'` by forward-mode differentiation of [`p`]: the form a checker derives
/// from the text, so the evidence is built on the same enclosures.
struct DerivativeByAd;

impl RealFn for DerivativeByAd {
    fn eval<T: Scalar>(&self, mu: T) -> T {
        p(Dual::variable(mu, 0)).grad[0]
    }
}

/// The `kappa0` proof: κ₀ = ½ max p and the root counts of (2.10) around it.
/// `mu_star` is the isolator's enclosure of the root of p'.
pub fn kappa0_proof(mu_star: &RootEnclosure) -> Value {
    let b = 1.0;
    let pieces = build_pieces(&DerivativeByAd, 0.0, b, std::slice::from_ref(mu_star));
    let newton_piece = pieces.iter().find_map(|p| match p.kind {
        PieceKind::Newton(_, n) => Some(n),
        _ => None,
    });
    let n = newton_piece.unwrap_or_else(|| mu_star.interval());
    let m = split_point(n.inf(), n.sup());
    // P = p(N) ∩ (p(m) + p'(N)(N − m)), as the checker recomputes it.
    let natural = p(DecInterval::new(n)).interval().expect("p is defined");
    let slope = DerivativeByAd
        .eval(DecInterval::new(n))
        .interval()
        .expect("p' is defined");
    let peak = natural.intersection(p(point(m)) + slope * (n - point(m)));
    let kappa0 = peak / Interval::try_from((2.0, 2.0)).expect("exact");
    json!({
        "format": "detach-proof/1",
        "claim": "kappa0",
        "title": "κ₀ = √3/9 and the number of positive roots of (2.10) on each side of it",
        "producer": super::producer(),
        "statement": {
            "equation": "2.10",
            "paper": "§2, case 2: 2κ = μ(1 − μ)(1 + μ), κ₀ = √3/9",
            "variable": "mu",
            "parameters": {},
            "definitions": [],
            "p": P_TEXT,
            "kappa0": {
                "lo": decimal(with_slack(kappa0).0, ROOT_DIGITS, Round::Down),
                "hi": decimal(with_slack(kappa0).1, ROOT_DIGITS, Round::Up),
            },
        },
        "evidence": {
            "b": hex(b),
            "derivative_pieces": pieces.iter().map(piece_json).collect::<Vec<_>>(),
            "peak_point": hex(m),
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::roots::isolate::{isolate, Budget};

    struct Sq2;
    impl RealFn for Sq2 {
        fn eval<T: Scalar>(&self, x: T) -> T {
            x.sqr() - T::int(2)
        }
    }

    #[test]
    fn pieces_tile_the_domain_and_hold_one_newton_box_per_root() {
        let iso = isolate(&Sq2, -3.0, 3.0, &Budget::default());
        let pieces = build_pieces(&Sq2, -3.0, 3.0, &iso.roots);
        assert_eq!(pieces.first().unwrap().lo, -3.0);
        assert_eq!(pieces.last().unwrap().hi, 3.0);
        for w in pieces.windows(2) {
            assert_eq!(w[0].hi, w[1].lo);
        }
        let newton: Vec<_> = pieces
            .iter()
            .filter_map(|p| match p.kind {
                PieceKind::Newton(_, n) => Some(n),
                _ => None,
            })
            .collect();
        assert_eq!(newton.len(), 2);
        // ±√2 (closed form) lie in the two N(X).
        let s = point(2.0).sqrt();
        assert!(!newton[0].disjoint(-s) && !newton[1].disjoint(s));
        assert!(pieces.iter().all(|p| p.kind != PieceKind::Undecided));
    }

    #[test]
    fn derivative_by_ad_is_one_minus_three_mu_squared() {
        // p' = 1 − 3μ² by hand; at μ = 0.5: 0.25.
        let d = DerivativeByAd.eval(0.5f64);
        assert!((d - 0.25).abs() < 1e-15);
    }
}
