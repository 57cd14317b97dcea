//! The `kappa0` claim: κ₀ = ½ max_{μ≥0} p(μ) lies in the claimed interval,
//! and 2κ = p(μ) has no root μ > 0 above κ₀ and exactly two simple roots
//! below it.

use inari::{DecInterval, Decoration, Interval};

use super::encoding::{decimal_enclosure, parse_hex_f64};
use super::eval::{continuous, defined, loosen_i, show, show_i};
use super::json::{arr_of, decls, obj_of, opt_str, str_of, Obj};
use super::pieces::{self, cap_dec, Function, Kind};
use super::roots::OneVar;
use super::{Outcome, Unreadable};

/// p' as a function, with p'' as its derivative. Both carry the lowest
/// decoration of p, p' (and p''), since a derivative says nothing where the
/// function is not continuous.
struct Derivative<'a>(&'a OneVar);

impl Function for Derivative<'_> {
    fn eval(&self, x: Interval) -> (DecInterval, DecInterval) {
        let r = self.0.dual2(x);
        let d1 = r.v.v.decoration().min(r.v.d.decoration());
        let f = cap_dec(r.v.d, d1);
        (f, cap_dec(r.d.d, d1))
    }
}

fn point(m: f64) -> Interval {
    Interval::try_from((m, m)).unwrap_or(Interval::EMPTY)
}

pub fn check(root: &Obj) -> Result<Outcome, Unreadable> {
    let st = obj_of(root, "statement")?;
    let ev = obj_of(root, "evidence")?;
    let (params, defs) = decls(st)?;
    let (p, _) = OneVar::new(str_of(st, "variable")?, &params, &defs, str_of(st, "p")?)?;
    let k0 = obj_of(st, "kappa0")?;
    let (lo_text, hi_text) = (str_of(k0, "lo")?, str_of(k0, "hi")?);
    let lo = decimal_enclosure(lo_text)?;
    let hi = decimal_enclosure(hi_text)?;
    let b = parse_hex_f64(str_of(ev, "b")?, false)?;
    let peak = parse_hex_f64(str_of(ev, "peak_point")?, false)?;
    let ps = pieces::parse(arr_of(ev, "derivative_pieces")?, "derivative piece")?;
    let claim = format!(
        "kappa0 {}: κ₀ in [{lo_text}, {hi_text}]",
        opt_str(st, "equation")?.unwrap_or("")
    );
    let mut checked = 0;
    let result = verify(&p, b, peak, &ps, lo, hi, &mut checked);
    Ok(Outcome::of(result, claim, checked, "pieces"))
}

fn verify(
    p: &OneVar,
    b: f64,
    peak: f64,
    ps: &[pieces::Piece],
    lo: Interval,
    hi: Interval,
    checked: &mut u64,
) -> Result<(), String> {
    let dp = Derivative(p);
    if b <= 0.0 {
        return Err(format!("b = {b:e} is not positive"));
    }
    // Step 1: the pieces cover [0, b] exactly; exactly one newton piece.
    pieces::check_cover(ps, 0.0, b)?;
    if ps.first().map(|q| q.lo) != Some(0.0) || ps.last().map(|q| q.hi) != Some(b) {
        return Err("derivative pieces must cover [0, b] exactly".into());
    }
    let mut newton = None;
    for (k, q) in ps.iter().enumerate() {
        if q.kind == Kind::Undecided {
            return Err(format!("derivative piece {} is undecided", k + 1));
        }
        if let Some(n) = pieces::check_piece(&dp, k + 1, q, true)? {
            if newton.is_some() {
                return Err(format!("derivative piece {}: a second newton piece", k + 1));
            }
            newton = Some(n);
        }
        *checked += 1;
    }
    let n = newton.ok_or("no newton piece")?;

    // Step 2: p'(0) > 0, p'(b) < 0, p'([b, +∞]) < 0.
    let at = |x: Interval| dp.eval(x).0;
    let d0 = at(point(0.0));
    if !defined(d0) || d0.interval().is_none_or(|i| i.inf() <= 0.0) {
        return Err(format!("p'(0) is not > 0: computed {}", show(d0)));
    }
    let db = at(point(b));
    if !defined(db) || db.interval().is_none_or(|i| i.sup() >= 0.0) {
        return Err(format!("p'(b) is not < 0: computed {}", show(db)));
    }
    let tail = Interval::try_from((b, f64::INFINITY)).unwrap_or(Interval::EMPTY);
    let dt = at(tail);
    if !continuous(dt) || dt.interval().is_none_or(|i| i.sup() >= 0.0) {
        return Err(format!(
            "p' on [b, +inf] is not continuous and < 0: computed {}",
            show(dt)
        ));
    }

    // Step 3: p(0) ≤ 0, p(b) ≤ 0, p([b, +∞]) ≤ 0.
    for (what, x) in [
        ("p(0)", point(0.0)),
        ("p(b)", point(b)),
        ("p([b, +inf])", tail),
    ] {
        let v = p.value(x);
        if !defined(v) || v.interval().is_none_or(|i| i.sup() > 0.0) {
            return Err(format!("{what} is not <= 0: computed {}", show(v)));
        }
    }

    // Step 4: P = p(N) ∩ (p(m) + p'(N)·(N − m)) encloses 2κ₀.
    if peak < n.inf() || peak > n.sup() {
        return Err(format!(
            "peak point {peak:e} is not in the Newton enclosure {}",
            show_i(n)
        ));
    }
    let pn = p.value(n);
    let pm = p.value(point(peak));
    let (_, dpn) = p.eval(n);
    if !defined(pn) || !defined(pm) || dpn.decoration() < Decoration::Dac {
        return Err(format!(
            "p(N), p(m), p'(N) not all defined: computed {}, {}, {}",
            show(pn),
            show(pm),
            show(dpn)
        ));
    }
    let (Some(pn), Some(pm), Some(dpn)) = (pn.interval(), pm.interval(), dpn.interval()) else {
        return Err("NaI".into());
    };
    let l = loosen_i;
    let big_p = pn.intersection(l(pm + l(dpn * l(n - point(peak)))));
    if big_p.is_empty() || big_p.inf() <= 0.0 {
        return Err(format!("P = {} is not positive", show_i(big_p)));
    }
    let two = Interval::try_from((2.0, 2.0)).unwrap_or(Interval::EMPTY);
    let k = l(big_p / two);
    if k.inf() < lo.sup() {
        return Err(format!(
            "claimed kappa0 lo {:e} exceeds the certified lower bound {:e}",
            lo.sup(),
            k.inf()
        ));
    }
    if k.sup() > hi.inf() {
        return Err(format!(
            "claimed kappa0 hi {:e} is below the certified upper bound {:e}",
            hi.inf(),
            k.sup()
        ));
    }
    Ok(())
}
