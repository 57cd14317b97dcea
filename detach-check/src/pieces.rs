//! Pieces of a one-variable function: `exclude`, `exclude_mv`, `newton`,
//! `undecided` (shared by the `roots` and `kappa0` claims).

use inari::{DecInterval, Decoration, Interval};
use serde_json::Value;

use super::encoding::parse_hex_f64;
use super::eval::{continuous, defined, loosen_i, show, show_i};
use super::json::{as_obj, str_of};
use super::Unreadable;

/// What a piece claims.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    Exclude,
    ExcludeMv(f64),
    Newton(f64),
    Undecided,
}

/// One piece `[lo, hi]` with its kind.
#[derive(Clone, Copy, Debug)]
pub struct Piece {
    pub lo: f64,
    pub hi: f64,
    pub kind: Kind,
}

impl Piece {
    /// The piece as an interval (never fails for a parsed piece: `lo < hi`
    /// is checked before use, and a failure becomes the empty interval).
    pub fn x(&self) -> Interval {
        Interval::try_from((self.lo, self.hi)).unwrap_or(Interval::EMPTY)
    }
}

/// Reads a `pieces` array. The first `lo` may be `-inf` and the last `hi`
/// `inf`; all other numbers are finite exact doubles.
pub fn parse(arr: &[Value], what: &str) -> Result<Vec<Piece>, Unreadable> {
    let n = arr.len();
    let mut out = Vec::with_capacity(n);
    for (k, v) in arr.iter().enumerate() {
        let o = as_obj(v, &format!("{what} {}", k + 1))?;
        let at = |e: String| Unreadable(format!("{what} {}: {e}", k + 1));
        let lo = parse_hex_f64(str_of(o, "lo")?, k == 0).map_err(at)?;
        let hi = parse_hex_f64(str_of(o, "hi")?, k + 1 == n).map_err(at)?;
        if lo == f64::INFINITY || hi == f64::NEG_INFINITY {
            return Err(at("infinite end on the wrong side".into()));
        }
        let point =
            || -> Result<f64, Unreadable> { parse_hex_f64(str_of(o, "point")?, false).map_err(at) };
        let kind = match str_of(o, "kind")? {
            "exclude" => Kind::Exclude,
            "exclude_mv" => Kind::ExcludeMv(point()?),
            "newton" => Kind::Newton(point()?),
            "undecided" => Kind::Undecided,
            other => return Err(at(format!("unknown kind {other:?}"))),
        };
        out.push(Piece { lo, hi, kind });
    }
    Ok(out)
}

/// Checks that the pieces are nonempty intervals, each starting where the
/// previous one ends, covering `[cover_lo, cover_hi]`.
pub fn check_cover(p: &[Piece], cover_lo: f64, cover_hi: f64) -> Result<(), String> {
    let (Some(first), Some(last)) = (p.first(), p.last()) else {
        return Err("no pieces".into());
    };
    for (k, q) in p.iter().enumerate() {
        if q.lo >= q.hi {
            return Err(format!(
                "piece {}: lo {:e} is not below hi {:e}",
                k + 1,
                q.lo,
                q.hi
            ));
        }
        if let Some(next) = p.get(k + 1) {
            if q.hi != next.lo {
                return Err(format!(
                    "piece {} ends at {:e} but piece {} starts at {:e}",
                    k + 1,
                    q.hi,
                    k + 2,
                    next.lo
                ));
            }
        }
        if let Kind::ExcludeMv(m) | Kind::Newton(m) = q.kind {
            if m < q.lo || m > q.hi {
                return Err(format!("piece {}: point {m:e} is outside the piece", k + 1));
            }
        }
    }
    if first.lo > cover_lo {
        return Err(format!(
            "piece 1 starts at {:e}, above the domain's lower end {:e}",
            first.lo, cover_lo
        ));
    }
    if last.hi < cover_hi {
        return Err(format!(
            "piece {} ends at {:e}, below the domain's upper end {:e}",
            p.len(),
            last.hi,
            cover_hi
        ));
    }
    Ok(())
}

/// A function of one variable with its derivative: `f(X) -> (f, f')`, where
/// the derivative's decoration already includes the value's (f' means
/// nothing where f is not continuous).
pub trait Function {
    fn eval(&self, x: Interval) -> (DecInterval, DecInterval);
}

/// Lowers the decoration of `x` to at most `d` (interval unchanged).
pub fn cap_dec(x: DecInterval, d: Decoration) -> DecInterval {
    match x.interval() {
        Some(i) => DecInterval::set_dec(i, x.decoration().min(d)),
        None => x,
    }
}

fn point(m: f64) -> Interval {
    Interval::try_from((m, m)).unwrap_or(Interval::EMPTY)
}

/// Checks the claim of one piece (number `k`, from 1) and returns the Newton
/// enclosure `N` for a `newton` piece. `need_continuous` additionally
/// requires f continuous on the piece whatever its kind.
pub fn check_piece<F: Function>(
    f: &F,
    k: usize,
    q: &Piece,
    need_continuous: bool,
) -> Result<Option<Interval>, String> {
    let x = q.x();
    let at = format!("piece {} [{:e}, {:e}] ({:?})", k, q.lo, q.hi, q.kind);
    let (fx, dfx) = f.eval(x);
    if need_continuous && !continuous(fx) {
        return Err(format!("{at}: f is not continuous, computed {}", show(fx)));
    }
    match q.kind {
        Kind::Undecided => Ok(None),
        Kind::Exclude => {
            if !defined(fx) {
                return Err(format!("{at}: f is not defined, computed {}", show(fx)));
            }
            if fx.interval().is_none_or(|i| i.contains(0.0)) {
                return Err(format!("{at}: f contains 0, computed {}", show(fx)));
            }
            Ok(None)
        }
        Kind::ExcludeMv(m) | Kind::Newton(m) => {
            if !continuous(fx) || !continuous(dfx) {
                return Err(format!(
                    "{at}: f, f' not continuous, computed f {} f' {}",
                    show(fx),
                    show(dfx)
                ));
            }
            let (fm, _) = f.eval(point(m));
            if !defined(fm) {
                return Err(format!("{at}: f(point) not defined, computed {}", show(fm)));
            }
            let (Some(fm), Some(d)) = (fm.interval(), dfx.interval()) else {
                return Err(format!("{at}: NaI"));
            };
            if let Kind::ExcludeMv(_) = q.kind {
                let mv = loosen_i(fm + loosen_i(d * loosen_i(x - point(m))));
                if mv.is_empty() || mv.contains(0.0) {
                    return Err(format!(
                        "{at}: mean-value form contains 0, computed {}",
                        show_i(mv)
                    ));
                }
                return Ok(None);
            }
            if d.contains(0.0) {
                return Err(format!("{at}: f' contains 0, computed {}", show_i(d)));
            }
            let n = loosen_i(point(m) - loosen_i(fm / d));
            if n.is_empty() || n.inf() <= x.inf() || n.sup() >= x.sup() {
                return Err(format!(
                    "{at}: Newton image {} is not interior to the piece",
                    show_i(n)
                ));
            }
            Ok(Some(n))
        }
    }
}
