//! Certified areas by quadrature over θ.
//!
//! Every region of a scene is `{q < 0}` with `q` quadratic in θ̇ and
//! θ-dependent coefficients, so for fixed θ a region's θ̇-slice inside the
//! window `[lo, hi]` is at most two intervals whose ends are roots of `q` or
//! window ends, and a partition cell's slice is an intersection of such sets.
//! The area is `∫ L(θ) dθ`, `L` the slice length.
//!
//! On a θ-piece where the shape of the slice is decided (sign of the leading
//! coefficient and of the discriminant, which root lies where, by interval
//! comparisons on the piece), `L` is a sum of differences of smooth functions
//! and its integral is enclosed by a Taylor rule with a Lagrange remainder:
//! `∫ L = Σ_{k<n} L_k(m) ∫ (θ−m)^k + R`, `R ∈ L_n(piece) ∫ (θ−m)^n` (`n`
//! even, so `(θ−m)^n ≥ 0`), the coefficients from interval Taylor arithmetic
//! ([`taylor`]). Two ends the piece cannot order (a root crossing a window
//! end or another root, or running along one) are kept as a tie whose error
//! is bounded by the Taylor series of their difference (`Gaps`). Where the
//! shape is not decided (the discriminant or the leading coefficient
//! vanishing, a singular line), the piece is bisected; what is left
//! undecided at the end is bounded by `[0, hi − lo]` times its width.
//! Refinement goes to the pieces that hold most of the width.
//!
//! Everything is interval arithmetic: the domain ends (π) are enclosures, the
//! slivers between them and the double grid are bounded separately.

pub mod taylor;

use crate::number::scalar::{is_defined, Scalar};
use crate::scene::slab::{centred_factors_on, factored_constraints_on};
use crate::scene::{Cell, Domain, Quadratic, Scene, Variant};
use inari::{const_interval, DecInterval, Interval};
use rayon::prelude::*;
use serde::Serialize;
use std::cmp::Ordering;
use taylor::{Taylor, N};

const ZERO: Interval = const_interval!(0.0, 0.0);

/// When to stop refining.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct AreaOptions {
    /// Target width of the enclosure (absolute).
    pub tol: f64,
    /// Most θ-pieces; when reached, the enclosure is returned as it is.
    pub max_pieces: usize,
}

impl Default for AreaOptions {
    fn default() -> Self {
        AreaOptions {
            tol: 1e-10,
            max_pieces: 1 << 20,
        }
    }
}

/// A certified area and how it was obtained.
#[derive(Clone, Copy, Debug)]
pub struct AreaEnclosure {
    /// Contains the true area.
    pub area: Interval,
    /// θ-pieces of the final subdivision.
    pub pieces: usize,
    /// Of those, pieces whose slice shape stayed undecided (bounded crudely).
    pub undecided_pieces: usize,
    /// Refinement rounds.
    pub rounds: usize,
    /// The set is empty by construction (Ω₀ = Ω asked with opposite signs).
    pub proved_empty: bool,
    /// Refinement stopped short of the target because what is left of the
    /// width is rounding that splitting does not reduce (binary64 limits
    /// this area to about its width).
    pub at_rounding_floor: bool,
}

impl AreaEnclosure {
    /// An enclosure from other bounds (a paving's inner and outer areas),
    /// `pieces` the leaves behind them.
    pub fn bounds(inner: f64, outer: f64, pieces: usize) -> AreaEnclosure {
        AreaEnclosure {
            area: Interval::try_from((inner, outer)).unwrap_or(Interval::ENTIRE),
            pieces,
            undecided_pieces: 0,
            rounds: 0,
            proved_empty: false,
            at_rounding_floor: false,
        }
    }

    /// The intersection with another enclosure of the same area (both
    /// contain it, so the intersection is not empty unless one is wrong).
    pub fn intersect(&self, other: &AreaEnclosure) -> AreaEnclosure {
        let area = self.area.intersection(other.area);
        AreaEnclosure {
            area: if area.is_empty() { self.area } else { area },
            ..*self
        }
    }
}

impl AreaEnclosure {
    pub fn width(&self) -> f64 {
        self.area.wid()
    }
}

#[derive(Debug, thiserror::Error, PartialEq)]
pub enum AreaError {
    #[error("the tolerance must be a positive finite number, got {0}")]
    BadTol(f64),
    #[error("max-pieces must be at least 1")]
    BadBudget,
    #[error("the domain is empty")]
    EmptyDomain,
    /// The target is below what binary64 quadrature can certify here.
    #[error(
        "a width of {tol:e} is below what binary64 arithmetic certifies for this area \
         (its rounding alone leaves about {floor:.1e}); ask for a width of at least {least:.0e}"
    )]
    BelowRounding { tol: f64, floor: f64, least: f64 },
}

/// One side of a cell: constraint `q` (0 = Ω, 1 = Ω₀) asked negative (`inside`)
/// or positive.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Lit {
    q: usize,
    inside: bool,
}

/// An end of a slice interval: a window end, or a root of literal `lit`'s
/// quadratic (`which` picks the formula, see [`root_forms`]).
#[derive(Clone, Copy, Debug, PartialEq)]
enum End {
    Lo,
    Hi,
    Root { lit: u8, which: u8 },
}

/// An end with an enclosure of its value over the piece.
#[derive(Clone, Copy, Debug)]
struct Bound {
    end: End,
    enc: Interval,
}

/// How a literal's set looks on a piece.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Shape {
    /// Quadratic with two roots; `s` is the sign used in the stable root
    /// formula `Q = −(a1 + s√D)/2`, roots `Q/a2` (which = 0) and `a0/Q` (1);
    /// `d` encloses the discriminant over the piece.
    Quad { s: i8, d: Interval },
    /// Quadratic whose discriminant may vanish on the piece (two root
    /// branches crossing or touching): ends `c ∓ √D⁺/(2|a2|)`, `c = −a1/(2a2)`,
    /// continuous through `D = 0`, where they meet. No Taylor series: the
    /// piece is enclosed by its width times the range of the length, which
    /// is of the order of the piece's width next to a crossing.
    Touch,
    /// Linear (`a2 ≡ 0`): root `−a0/a1`.
    Linear,
    /// No root needed (the set is empty or the whole window).
    Flat,
}

/// A literal as a piece uses it (on its constraint's quadratic without the
/// θ-only factor, the side flipped where that factor is negative), with its
/// shape there.
type Used = (Lit, Shape);

/// Sign-applied coefficients `(a2, a1, a0)` of literal `l`: `{a(θ̇) < 0}` is
/// the literal's set.
fn lit_coeffs<T: crate::number::scalar::Scalar>(q: &Quadratic<T>, inside: bool) -> (T, T, T) {
    if inside {
        (q.c2, q.c1, q.c0)
    } else {
        (-q.c2, -q.c1, -q.c0)
    }
}

fn cmp(a: &Bound, b: &Bound) -> Option<Ordering> {
    if a.end == b.end {
        return Some(Ordering::Equal);
    }
    if a.enc.sup() < b.enc.inf() {
        Some(Ordering::Less)
    } else if a.enc.inf() > b.enc.sup() {
        Some(Ordering::Greater)
    } else {
        None
    }
}

/// A union of disjoint open intervals, in order.
type Slice = Vec<(Bound, Bound)>;

/// Two ends whose difference `to − from` bounds an error of the slice
/// length (see [`Gaps`]).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Gap {
    from: End,
    to: End,
}

/// What a piece cannot order, kept as bounded corrections instead of
/// splitting the piece again and again where two boundaries cross, or
/// coincide along a curve (as Ω's and Ω₀'s may).
#[derive(Clone, Debug, Default)]
struct Gaps {
    /// An end `from` used where the true end is `max(from, to)` (a lower
    /// end) or `min(from, to)` (an upper end): the true length is the
    /// computed one minus at most `sup |to − from|` over the piece.
    ties: Vec<Gap>,
    /// An interval `(from, to)` that may be empty: left out of the slice, its
    /// length lies in `[0, sup |to − from|]`; with `sup (to − from)⁺` from the
    /// ends' enclosures over the piece (the ties need none: a tied end
    /// keeps the enclosure of the true end).
    slivers: Vec<(Gap, f64)>,
}

/// The lower (`upper = false`) or upper end of an intersection: the greater
/// or the lesser of `a` and `b`, or, when the piece cannot order them, `a`
/// standing for both with the enclosure of the true end and a tie.
fn meet(a: &Bound, b: &Bound, upper: bool, ties: &mut Vec<Gap>) -> Bound {
    let keep_a = if upper {
        Ordering::Less
    } else {
        Ordering::Greater
    };
    match cmp(a, b) {
        Some(Ordering::Equal) => *a,
        Some(o) if o == keep_a => *a,
        Some(_) => *b,
        None => {
            let (i, s) = if upper {
                (a.enc.inf().min(b.enc.inf()), a.enc.sup().min(b.enc.sup()))
            } else {
                (a.enc.inf().max(b.enc.inf()), a.enc.sup().max(b.enc.sup()))
            };
            ties.push(Gap {
                from: a.end,
                to: b.end,
            });
            Bound {
                end: a.end,
                enc: Interval::try_from((i, s)).unwrap_or(Interval::ENTIRE),
            }
        }
    }
}

/// `s ∩ t`. Ends that cannot be ordered become ties, intervals that may be
/// empty slivers (in `gaps`); `None` when `gaps` is `None` and one of them
/// occurs (the piece must then be split).
fn intersect(s: &Slice, t: &Slice, mut gaps: Option<&mut Gaps>) -> Option<Slice> {
    let mut out = Vec::new();
    for a in s {
        for b in t {
            let mut ties = Vec::new();
            let lo = meet(&a.0, &b.0, false, &mut ties);
            let hi = meet(&a.1, &b.1, true, &mut ties);
            let order = cmp(&lo, &hi);
            let Some(g) = gaps.as_deref_mut() else {
                if !ties.is_empty() || order != Some(Ordering::Less) {
                    if order.is_none() || !ties.is_empty() {
                        return None;
                    }
                    continue;
                }
                out.push((lo, hi));
                continue;
            };
            match order {
                Some(Ordering::Less) => {
                    out.push((lo, hi));
                    g.ties.extend(ties);
                }
                // (hi − lo)⁺ ≤ |hi − lo| whatever the ties resolve to.
                None => g.slivers.push((
                    Gap {
                        from: lo.end,
                        to: hi.end,
                    },
                    (hi.enc - lo.enc).sup().max(0.0),
                )),
                Some(_) => {}
            }
        }
    }
    Some(out)
}

/// Exact-zero test on an interval coefficient (a formula that is identically
/// zero, e.g. `c1` of Ω).
fn is_zero(x: Interval) -> bool {
    x == ZERO
}

/// The decided set of one literal over a piece, from interval coefficients,
/// as intervals whose ends are roots and window ends (not yet clipped to the
/// window: the caller's intersection with the window orders a root against
/// a window end, or keeps a tie where it cannot, as where a boundary runs
/// along the window's edge).
/// The set is `{a(θ̇) < 0}` (`strict`) or `{a(θ̇) ≤ 0}`; the two differ only
/// where `a ≡ 0`, or by roots (no area).
fn literal_slice(
    li: u8,
    (a2, a1, a0): (Interval, Interval, Interval),
    d: Interval,
    strict: bool,
    window: &[Bound; 2],
) -> Option<(Shape, Slice)> {
    let full = || vec![(window[0], window[1])];
    if is_zero(a2) {
        if is_zero(a1) {
            let (all, none) = if strict {
                (a0.sup() < 0.0, a0.inf() >= 0.0)
            } else {
                (a0.sup() <= 0.0, a0.inf() > 0.0)
            };
            return if all {
                Some((Shape::Flat, full()))
            } else if none {
                Some((Shape::Flat, vec![]))
            } else {
                None
            };
        }
        let r = Bound {
            end: End::Root { lit: li, which: 0 },
            enc: -a0 / a1,
        };
        if !r.enc.is_common_interval() {
            return None;
        }
        let s = if a1.inf() > 0.0 {
            vec![(window[0], r)]
        } else if a1.sup() < 0.0 {
            vec![(r, window[1])]
        } else {
            return None;
        };
        return Some((Shape::Linear, s));
    }
    let up = if a2.inf() > 0.0 {
        true
    } else if a2.sup() < 0.0 {
        false
    } else {
        return None;
    };
    // No sign change in θ̇ (at most a double root: no area).
    if d.sup() <= 0.0 {
        return Some((Shape::Flat, if up { vec![] } else { full() }));
    }
    let bound = |which, enc: Interval| Bound {
        end: End::Root { lit: li, which },
        enc,
    };
    let split = |lo: Bound, hi: Bound| {
        if up {
            vec![(lo, hi)]
        } else {
            vec![(window[0], lo), (hi, window[1])]
        }
    };
    if d.inf() <= 0.0 {
        // Where D ≤ 0 the set is empty (up) or the whole window (down) up to
        // a point, which is what the ends `c ∓ √D⁺/(2|a2|)` give: the
        // intersection with the window leaves a possibly empty interval of
        // length at most sup √D⁺/|a2|, small next to a crossing.
        let two = pt(2.0);
        let c = -a1 / (two * a2);
        let half = d.intersection(const_interval!(0.0, f64::INFINITY)).sqrt() / (two * a2.abs());
        let (lo, hi) = (bound(0, c - half), bound(1, c + half));
        if !(lo.enc.is_common_interval() && hi.enc.is_common_interval()) {
            return None;
        }
        return Some((Shape::Touch, split(lo, hi)));
    }
    let s: i8 = if a1.mid() >= 0.0 { 1 } else { -1 };
    let [ra, rb] = root_forms(a2, a1, d, a0, s);
    let (ba, bb) = (bound(0, ra), bound(1, rb));
    if !(ra.is_common_interval() && rb.is_common_interval()) {
        return None;
    }
    let (lo, hi) = match cmp(&ba, &bb)? {
        Ordering::Less => (ba, bb),
        Ordering::Greater => (bb, ba),
        Ordering::Equal => return None,
    };
    // Between the roots, or below the lower and above the upper one (±∞
    // become window ends).
    Some((Shape::Quad { s, d }, split(lo, hi)))
}

/// The discriminant `a1² − 4·a2·a0`.
fn discriminant<T: crate::number::scalar::Scalar>(a2: T, a1: T, a0: T) -> T {
    a1.sqr() - T::int(4) * a2 * a0
}

/// The two roots by the cancellation-free pair `Q/a2`, `a0/Q`,
/// `Q = −(a1 + s√D)/2`, `d` the discriminant.
fn root_forms<T: crate::number::scalar::Scalar>(a2: T, a1: T, d: T, a0: T, s: i8) -> [T; 2] {
    let sq = d.sqrt();
    let q = -(if s > 0 { a1 + sq } else { a1 - sq }) / T::int(2);
    [q / a2, a0 / q]
}

/// An upper bound of `|f|` over `[m − r, m + r]` from its Taylor
/// coefficients at `m` (`at_m`) and over the piece (`over`, for the
/// Lagrange remainder of order `N − 1`).
/// Returned as the polynomial part and the remainder's part.
fn sup_abs(at_m: &Taylor, over: &Taylor, r: Interval) -> (f64, f64) {
    let n = N - 1;
    let mut acc = ZERO;
    let mut rk = pt(1.0);
    for c in at_m.c.iter().take(n) {
        acc += c.abs() * rk;
        rk *= r;
    }
    (acc.sup(), (over.c[n].abs() * rk).sup())
}

/// What a piece contributes.
#[derive(Clone, Copy, Debug)]
struct Piece {
    t: [f64; 2],
    integral: Interval,
    decided: bool,
    /// Width that rounding alone may leave on this piece (see
    /// [`ROUNDING_FLOOR`]): splitting a piece this narrow gains nothing.
    floor: f64,
}

/// The enclosure of `∫ L` on a piece of width `h` whose slice ends are at
/// most `M` in magnitude keeps a width of a few `2⁻⁵²·h·M` from rounding
/// however small the piece (every end is computed in binary64). This is
/// that width, with a margin: 2⁻⁴⁹·h·M.
const ROUNDING_FLOOR: f64 = 1.0 / (1u64 << 49) as f64;

/// The cell to integrate, resolved against the scene.
struct Job<'a> {
    scene: &'a Scene,
    variant: Variant,
    lits: Vec<Lit>,
    window: [Interval; 2],
}

fn pt(x: f64) -> Interval {
    Interval::try_from((x, x)).expect("finite")
}

/// `∫_{t0}^{t1} (θ − m)^k dθ` for `k < N + 1`, in intervals.
fn moments(t0: f64, t1: f64, m: f64) -> [Interval; N + 1] {
    let (a, b) = (pt(t0) - pt(m), pt(t1) - pt(m));
    let mut out = [ZERO; N + 1];
    let (mut pa, mut pb) = (a, b);
    for (k, o) in out.iter_mut().enumerate() {
        *o = (pb - pa) / pt((k + 1) as f64);
        pa *= a;
        pb *= b;
    }
    out
}

impl Job<'_> {
    /// The slice shape on `theta`, with the literals it uses (each on its
    /// constraint's θ-only-factor-free quadratic, the side flipped where the
    /// factor is negative) and their shapes, and the ends it could not order.
    fn shape(&self, theta: Interval) -> Option<(Vec<Used>, Slice, Gaps)> {
        let (factor, c) = factored_constraints_on(self.scene, self.variant, theta);
        let quads = [c.omega, c.omega0];
        let window = [
            Bound {
                end: End::Lo,
                enc: self.window[0],
            },
            Bound {
                end: End::Hi,
                enc: self.window[1],
            },
        ];
        let mut shapes = Vec::with_capacity(self.lits.len());
        let mut slice: Slice = vec![(window[0], window[1])];
        let mut gaps = Gaps::default();
        let iv = |x: DecInterval| -> Option<Interval> {
            // `com`: defined and continuous on the piece, hence (for these
            // formulas) analytic, as the Taylor rule needs.
            (is_defined(x) && x.decoration() == inari::Decoration::Com)
                .then(|| x.interval())
                .flatten()
                .filter(|i| i.is_common_interval())
        };
        // The sign of a factor from its natural enclosure, else from its
        // mean-value form (computed once, when first needed).
        let centred = std::cell::OnceCell::new();
        let centred = |q: usize, k: usize| {
            iv(centred.get_or_init(|| centred_factors_on(self.scene, self.variant, theta))[q][k])
        };
        let negative = |q: usize, k: usize| -> Option<bool> {
            let sign = |x: Interval| (x.inf() > 0.0 || x.sup() < 0.0).then(|| x.sup() < 0.0);
            iv(factor[q][k])
                .and_then(sign)
                .or_else(|| centred(q, k).and_then(sign))
        };
        for (i, l) in self.lits.iter().enumerate() {
            // Inside is `{g < 0}`; outside, the complement, is `{g ≥ 0}`
            // (they differ where g ≡ 0 on a set of positive area).
            let strict = l.inside;
            // g ≡ 0 on the piece: its enclosure is [0, 0], or its mean-value
            // form is (0 at the centre and a slope of exactly 0 over the
            // piece, as `abs(θ) − θ` for θ > 0, whose natural enclosure is
            // not [0, 0]).
            let numerator = iv(factor[l.q][0]);
            if numerator == Some(ZERO)
                || (numerator.is_some_and(|x| x.contains(0.0)) && centred(l.q, 0) == Some(ZERO))
            {
                // g ≡ 0 on the piece.
                let set = if strict {
                    vec![]
                } else {
                    vec![(window[0], window[1])]
                };
                shapes.push((*l, Shape::Flat));
                slice = intersect(&slice, &set, Some(&mut gaps))?;
                continue;
            }
            let flip = negative(l.q, 0)? != negative(l.q, 1)?;
            let l = Lit {
                q: l.q,
                inside: l.inside != flip,
            };
            let (a2, a1, a0) = lit_coeffs(&quads[l.q], l.inside);
            let a = (iv(a2)?, iv(a1)?, iv(a0)?);
            let mut d = discriminant(a.0, a.1, a.2);
            if d.inf() <= 0.0 && d.sup() > 0.0 {
                // The natural enclosure's dependency leaves a width of the
                // order of the piece's; the Taylor form's is of a high
                // order, which decides D's sign next to a double root.
                let t = self.discriminant_over(theta, l.q).intersection(d);
                if !t.is_empty() {
                    d = t;
                }
            }
            let (shape, s) = literal_slice(i as u8, a, d, strict, &window)?;
            shapes.push((l, shape));
            slice = intersect(&slice, &s, Some(&mut gaps))?;
        }
        Some((shapes, slice, gaps))
    }

    /// Taylor coefficients around `x` (a point or the whole piece) of the
    /// slice length `Σ (hi − lo)` and of `to − from` for every gap in
    /// `gaps` (ties, then slivers).
    fn length_series(
        &self,
        x: Interval,
        shapes: &[Used],
        slice: &Slice,
        gaps: &Gaps,
    ) -> Option<(Taylor, Vec<Taylor>)> {
        let (_, c) = self
            .scene
            .factored_constraints(self.variant, &crate::scene::Angle::new(Taylor::variable(x)));
        let quads = [c.omega, c.omega0];
        let mut roots: Vec<[Taylor; 2]> = Vec::with_capacity(shapes.len());
        for (l, shape) in shapes {
            let (a2, a1, a0) = lit_coeffs(&quads[l.q], l.inside);
            roots.push(match *shape {
                Shape::Quad { s, d } => {
                    // D over `x ⊆` the piece lies in its enclosure there,
                    // which may be the tighter.
                    let mut dt = discriminant(a2, a1, a0);
                    let c0 = dt.c[0].intersection(d);
                    if !c0.is_empty() {
                        dt.c[0] = c0;
                    }
                    root_forms(a2, a1, dt, a0, s)
                }
                Shape::Touch => {
                    [Taylor {
                        c: [Interval::ENTIRE; N],
                    }; 2]
                }
                Shape::Linear => {
                    let r = -a0 / a1;
                    [r, r]
                }
                Shape::Flat => [Taylor::constant(ZERO); 2],
            });
        }
        let end = |b: &Bound| match b.end {
            End::Lo => Taylor::constant(self.window[0]),
            End::Hi => Taylor::constant(self.window[1]),
            End::Root { lit, which } => roots[lit as usize][which as usize],
        };
        let end = |e: End| end(&Bound { end: e, enc: ZERO });
        let mut total = Taylor::constant(ZERO);
        for (lo, hi) in slice {
            total = total + (end(hi.end) - end(lo.end));
        }
        let gaps: Vec<Taylor> = (gaps.ties.iter().chain(gaps.slivers.iter().map(|(g, _)| g)))
            .map(|g| end(g.to) - end(g.from))
            .collect();
        (total.is_finite() && gaps.iter().all(Taylor::is_finite)).then_some((total, gaps))
    }

    /// An enclosure of the discriminant of constraint `q` over `theta` by
    /// its Taylor form at the centre with a Lagrange remainder (ENTIRE where
    /// the series is not finite).
    fn discriminant_over(&self, theta: Interval, q: usize) -> Interval {
        let series = |x: Interval| {
            let (_, c) = self
                .scene
                .factored_constraints(self.variant, &crate::scene::Angle::new(Taylor::variable(x)));
            let c = [c.omega, c.omega0][q];
            discriminant(c.c2, c.c1, c.c0)
        };
        let m = 0.5 * theta.inf() + 0.5 * theta.sup();
        let (at_m, over) = (series(pt(m)), series(theta));
        if !(at_m.is_finite() && over.is_finite()) {
            return Interval::ENTIRE;
        }
        let x = (pt(theta.inf()) - pt(m)).convex_hull(pt(theta.sup()) - pt(m));
        let n = N - 1;
        let mut s = ZERO;
        for (k, c) in at_m.c.iter().enumerate().take(n) {
            s += *c * Scalar::pown(x, k as u32);
        }
        s + over.c[n] * Scalar::pown(x, n as u32)
    }

    fn piece(&self, t0: f64, t1: f64) -> Piece {
        let h = pt(t1) - pt(t0);
        let theta = Interval::try_from((t0, t1)).expect("ordered");
        // The slice length always lies in [0, hi − lo].
        let l_max = (self.window[1] - self.window[0]).convex_hull(ZERO);
        let magnitude = self.window[0].mag().max(self.window[1].mag());
        let crude = Piece {
            t: [t0, t1],
            integral: h * l_max,
            decided: false,
            floor: ROUNDING_FLOOR * h.sup() * 2.0 * magnitude,
        };
        let Some((shapes, slice, gaps)) = self.shape(theta) else {
            return crude;
        };
        // Zeroth order: width × the range of L over the piece.
        let mut l_range = ZERO;
        for (lo, hi) in &slice {
            l_range += (hi.enc - lo.enc).intersection(l_max);
        }
        for (_, reach) in &gaps.slivers {
            l_range += Interval::try_from((0.0, *reach)).unwrap_or(l_max);
        }
        let mut integral = (h * l_range).intersection(crude.integral);
        let mut rounding = 0.0;
        if !gaps.slivers.is_empty()
            || slice
                .iter()
                .any(|(a, b)| a.end != End::Lo || b.end != End::Hi)
        {
            let m = 0.5 * t0 + 0.5 * t1;
            if let (Some((at_m, gaps_m)), Some((over, gaps_over))) = (
                self.length_series(pt(m), &shapes, &slice, &gaps),
                self.length_series(theta, &shapes, &slice, &gaps),
            ) {
                let mom = moments(t0, t1, m);
                // (θ − m)^n ≥ 0 for the remainder's mean value.
                let n = N - 1;
                const { assert!((N - 1).is_multiple_of(2)) };
                let mut s = ZERO;
                for (c, mk) in at_m.c.iter().zip(&mom).take(n) {
                    s += *c * *mk;
                }
                // The polynomial part's width is rounding only: it does not
                // shrink by splitting (it grows where cancellation is
                // amplified, next to a line where a coefficient is singular).
                rounding = s.wid();
                s += over.c[n] * mom[n];
                // A tie shortens the slice by at most sup |to − from|, a
                // sliver adds at most that much.
                // |θ − m| ≤ r on the piece (m is a rounded midpoint).
                let r = (pt(m) - pt(t0)).convex_hull(pt(t1) - pt(m));
                let r = pt(r.sup());
                let n_ties = gaps.ties.len();
                for (k, (g, go)) in gaps_m.iter().zip(&gaps_over).enumerate() {
                    let (poly, rest) = sup_abs(g, go, r);
                    let sup = (pt(poly) + pt(rest)).sup();
                    let range = if k < n_ties { (-sup, 0.0) } else { (0.0, sup) };
                    s += h * Interval::try_from(range).unwrap_or(Interval::ENTIRE);
                    // Ends equal up to rounding at the centre (every
                    // coefficient holds 0): boundaries that coincide, which
                    // no split separates.
                    if g.c.iter().take(n).all(|c| c.contains(0.0)) {
                        rounding += (h * pt(poly)).sup();
                    }
                }
                let t = integral.intersection(s);
                if !t.is_empty() {
                    integral = t;
                }
            }
        }
        let ends: f64 = slice
            .iter()
            .map(|(lo, hi)| lo.enc.mag() + hi.enc.mag())
            .sum();
        Piece {
            t: [t0, t1],
            integral,
            decided: true,
            floor: (ROUNDING_FLOOR * h.sup() * ends).max(rounding),
        }
    }
}

/// `first + Σ rest`, its ends accumulated in 256-bit binary floating point
/// rounded down (lower end) and up (upper end), then rounded outward to
/// doubles once: the enclosure widens by at most an ulp of the sum at each
/// end, not by an ulp per term (a million terms would otherwise widen an
/// area near 100 by 10⁻⁸).
fn sum_outward(first: Interval, rest: impl Iterator<Item = Interval>) -> Interval {
    use rug::float::Round;
    use rug::ops::AddAssignRound;
    const PREC: u32 = 256;
    let mut lo = rug::Float::with_val(PREC, first.inf());
    let mut hi = rug::Float::with_val(PREC, first.sup());
    for x in rest {
        if x.is_empty() || !x.is_common_interval() {
            return Interval::ENTIRE;
        }
        lo.add_assign_round(x.inf(), Round::Down);
        hi.add_assign_round(x.sup(), Round::Up);
    }
    let (l, h) = (lo.to_f64_round(Round::Down), hi.to_f64_round(Round::Up));
    Interval::try_from((l, h)).unwrap_or(Interval::ENTIRE)
}

/// θ-pieces of the first, uniform grid.
const FIRST_GRID: usize = 64;

/// Refuses, on the first grid alone, a target [`cell_area`] would refuse
/// for rounding: lets a caller check every set before computing any.
pub fn check_target(
    scene: &Scene,
    variant: Variant,
    domain: &Domain,
    cell: Cell,
    tol: f64,
) -> Result<(), AreaError> {
    let opts = AreaOptions {
        tol,
        max_pieces: FIRST_GRID,
    };
    cell_area(scene, variant, domain, cell, opts).map(|_| ())
}

/// Area of the points of `domain` in `cell` (Ω, Ω₀ or one of the four
/// cells).
pub fn cell_area(
    scene: &Scene,
    variant: Variant,
    domain: &Domain,
    cell: Cell,
    opts: AreaOptions,
) -> Result<AreaEnclosure, AreaError> {
    if !(opts.tol.is_finite() && opts.tol > 0.0) {
        return Err(AreaError::BadTol(opts.tol));
    }
    if opts.max_pieces == 0 {
        return Err(AreaError::BadBudget);
    }
    if domain.is_empty() {
        return Err(AreaError::EmptyDomain);
    }
    let mut lits: Vec<Lit> = cell
        .literals()
        .iter()
        .enumerate()
        .filter_map(|(q, l)| l.map(|inside| Lit { q, inside }))
        .collect();
    if scene.omega0_is_omega(variant) && lits.len() == 2 {
        if lits[0].inside != lits[1].inside {
            return Ok(AreaEnclosure {
                area: ZERO,
                pieces: 0,
                undecided_pieces: 0,
                rounds: 0,
                proved_empty: true,
                at_rounding_floor: false,
            });
        }
        lits.truncate(1);
    }
    let job = Job {
        scene,
        variant,
        lits,
        window: domain.theta_dot,
    };
    let b = domain.inner_box();
    // Slivers between the true θ-ends and the double box, and the same for θ̇
    // (the window ends themselves are exact enclosures, used directly).
    let height = (domain.theta_dot[1] - domain.theta_dot[0]).convex_hull(ZERO);
    let sliver = |x: Interval| (x.convex_hull(ZERO) * height).convex_hull(ZERO);
    let slivers = sliver(pt(b[0][0]) - domain.theta[0]) + sliver(domain.theta[1] - pt(b[0][1]));

    // Start from a uniform grid so the first round already runs in parallel.
    let start = FIRST_GRID;
    let grid: Vec<f64> = (0..=start)
        .map(|i| {
            if i == start {
                b[0][1]
            } else {
                b[0][0] + (b[0][1] - b[0][0]) * (i as f64 / start as f64)
            }
        })
        .collect();
    let mut pieces: Vec<Piece> = grid
        .windows(2)
        .filter(|w| w[0] < w[1])
        .collect::<Vec<_>>()
        .par_iter()
        .map(|w| job.piece(w[0], w[1]))
        .collect();
    let total = |ps: &[Piece]| sum_outward(slivers, ps.iter().map(|p| p.integral));
    // Refuse at once a target that rounding alone would miss: the floors do
    // not shrink under splitting, so the first grid already shows them.
    let floor: f64 = pieces.iter().map(|p| p.floor).sum();
    if opts.tol < 2.0 * floor {
        let least = 10f64.powf((2.0 * floor).log10().ceil());
        return Err(AreaError::BelowRounding {
            tol: opts.tol,
            floor,
            least,
        });
    }
    let mut rounds = 0;
    let mut at_rounding_floor = false;
    loop {
        let area = total(&pieces);
        let excess = area.wid() - 0.5 * opts.tol;
        if area.wid() <= opts.tol || pieces.len() >= opts.max_pieces {
            break;
        }
        // Split the widest pieces that together hold the excess width.
        let mut order: Vec<usize> = (0..pieces.len())
            .filter(|&i| {
                let (t, p) = (pieces[i].t, &pieces[i]);
                let m = 0.5 * t[0] + 0.5 * t[1];
                t[0] < m && m < t[1] && p.integral.wid() > 2.0 * p.floor
            })
            .collect();
        if order.is_empty() {
            at_rounding_floor = true;
            break;
        }
        order.sort_by(|&i, &j| {
            pieces[j]
                .integral
                .wid()
                .total_cmp(&pieces[i].integral.wid())
                .then(i.cmp(&j))
        });
        // What the pieces left out hold stays whatever is split: once it
        // alone exceeds the target, refine the others only until they hold
        // a tenth of it.
        let held: f64 = order.iter().map(|&i| pieces[i].integral.wid()).sum();
        let stuck = area.wid() - held;
        if stuck > opts.tol && held <= 0.1 * stuck {
            at_rounding_floor = true;
            break;
        }
        // Split the pieces holding the excess, but never more than those
        // holding half the width: where a few pieces hold it (a singular
        // line, a crossing), the rest is not doubled round after round.
        let excess = excess.min(0.5 * held);
        let (mut acc, mut chosen) = (0.0, Vec::new());
        for i in order {
            if acc >= excess || pieces.len() + chosen.len() >= opts.max_pieces {
                break;
            }
            acc += pieces[i].integral.wid();
            chosen.push(i);
        }
        if chosen.is_empty() {
            at_rounding_floor = true;
            break;
        }
        chosen.sort_unstable();
        let children: Vec<[Piece; 2]> = chosen
            .par_iter()
            .map(|&i| {
                let t = pieces[i].t;
                let m = 0.5 * t[0] + 0.5 * t[1];
                [job.piece(t[0], m), job.piece(m, t[1])]
            })
            .collect();
        let mut next = Vec::with_capacity(pieces.len() + chosen.len());
        let mut c = chosen.iter().zip(children).peekable();
        for (i, p) in pieces.into_iter().enumerate() {
            match c.peek() {
                Some((&j, _)) if j == i => {
                    let (_, kids) = c.next().expect("peeked");
                    next.extend(kids);
                }
                _ => next.push(p),
            }
        }
        pieces = next;
        rounds += 1;
    }
    let area = total(&pieces);
    Ok(AreaEnclosure {
        area,
        pieces: pieces.len(),
        undecided_pieces: pieces.iter().filter(|p| !p.decided).count(),
        rounds,
        proved_empty: false,
        at_rounding_floor: at_rounding_floor && area.wid() > opts.tol,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2²⁰ copies of the double nearest 0.1 add up exactly to 2²⁰ times it
    /// (a power of two): the sum encloses that and is at most an ulp wide
    /// at each end, where adding in binary64 would widen it by 2²⁰ ulps.
    #[test]
    fn outward_sum_widens_once_not_per_term() {
        let x = Interval::try_from((0.1, 0.1)).unwrap();
        let n = 1usize << 20;
        let exact = 0.1 * n as f64;
        let s = sum_outward(ZERO, std::iter::repeat_n(x, n));
        assert!(s.inf() <= exact && exact <= s.sup());
        let ulp = f64::EPSILON * exact;
        assert!(s.wid() <= 2.0 * ulp, "width {}", s.wid());
        let naive = (0..n).fold(ZERO, |a, _| a + x);
        assert!(naive.wid() > 1000.0 * ulp);
    }
}
