//! The `roots` claim: the zeros of f on an open interval are as listed.

use inari::{DecInterval, Interval};

use super::encoding::decimal_enclosure;
use super::eval::{defined, exact, show, Dual, Program};
use super::json::{arr_of, as_obj, bool_of, decls, obj_of, opt_str, str_of, Obj};
use super::pieces::{self, cap_dec, Function, Kind};
use super::{Outcome, Unreadable};

/// A compiled function of one variable and its derivative.
pub struct OneVar {
    prog: Program,
    slot: u32,
}

impl OneVar {
    /// Compiles `function` over `variable` after the declarations.
    pub fn new(
        variable: &str,
        params: &[(String, String)],
        defs: &[(String, String)],
        function: &str,
    ) -> Result<(Self, Program), Unreadable> {
        let mut prog = Program::new(&[variable])?;
        prog.add_parameters(params)?;
        for (n, e) in defs {
            prog.define(n, e)?;
        }
        let base = prog.clone();
        let slot = prog.compile(function)?;
        Ok((OneVar { prog, slot }, base))
    }

    /// f on X.
    pub fn value(&self, x: Interval) -> DecInterval {
        self.prog.value(&[DecInterval::new(x)], self.slot)
    }

    /// f and f' on X (first-order forward mode).
    pub fn dual(&self, x: Interval) -> Dual<DecInterval> {
        let v = Dual::variable(DecInterval::new(x));
        self.prog.value(&[v], self.slot)
    }

    /// f, f', f'' on X (forward mode over forward mode; `v.v` = f,
    /// `v.d` = f' exactly as [`OneVar::dual`] computes it, `d.d` = f'').
    pub fn dual2(&self, x: Interval) -> Dual<Dual<DecInterval>> {
        let v = Dual {
            v: Dual::variable(DecInterval::new(x)),
            d: Dual {
                v: exact(1.0),
                d: exact(0.0),
            },
        };
        self.prog.value(&[v], self.slot)
    }
}

impl Function for OneVar {
    fn eval(&self, x: Interval) -> (DecInterval, DecInterval) {
        let r = self.dual(x);
        (r.v, cap_dec(r.d, r.v.decoration()))
    }
}

/// A claimed enclosure `[lo, hi]` of decimal text, as the enclosures of its
/// two ends.
#[derive(Clone, Copy, Debug)]
pub struct Claimed {
    pub lo: Interval,
    pub hi: Interval,
    pub unique: bool,
}

impl Claimed {
    /// `N ⊂ [lo, hi]` for every real value of the ends.
    fn holds(&self, n: Interval) -> bool {
        n.inf() >= self.lo.sup() && n.sup() <= self.hi.inf()
    }
}

/// Evaluates a variable-free expression slot to an interval that must be
/// defined.
pub fn constant(prog: &Program, slot: u32, what: &str) -> Result<Interval, String> {
    let v = prog.value(&[DecInterval::EMPTY], slot);
    match v.interval() {
        Some(i) if defined(v) => Ok(i),
        _ => Err(format!("{what} is not defined, computed {}", show(v))),
    }
}

pub fn check(root: &Obj) -> Result<Outcome, Unreadable> {
    let st = obj_of(root, "statement")?;
    let ev = obj_of(root, "evidence")?;
    let (params, defs) = decls(st)?;
    let variable = str_of(st, "variable")?;
    let (f, mut base) = OneVar::new(variable, &params, &defs, str_of(st, "function")?)?;
    let dom = obj_of(st, "domain")?;
    let lo_slot = base.compile_constant(str_of(dom, "lo")?)?;
    let hi_text = str_of(dom, "hi")?;
    let hi_slot = if hi_text == "inf" {
        None
    } else {
        Some(base.compile_constant(hi_text)?)
    };
    let mut claimed = Vec::new();
    for (k, r) in arr_of(st, "roots")?.iter().enumerate() {
        let o = as_obj(r, "a root")?;
        let at = |e: String| Unreadable(format!("root {}: {e}", k + 1));
        let unique = match str_of(o, "status")? {
            "unique" => true,
            "undecided" => false,
            s => return Err(at(format!("unknown status {s:?}"))),
        };
        claimed.push(Claimed {
            lo: decimal_enclosure(str_of(o, "lo")?).map_err(at)?,
            hi: decimal_enclosure(str_of(o, "hi")?).map_err(at)?,
            unique,
        });
    }
    let complete = bool_of(st, "complete")?;
    let ps = pieces::parse(arr_of(ev, "pieces")?, "piece")?;
    let n_unique = claimed.iter().filter(|c| c.unique).count();
    let claim = format!(
        "roots {}: {} unique, {} undecided{}",
        opt_str(st, "equation")?.unwrap_or(""),
        n_unique,
        claimed.len() - n_unique,
        if complete { ", complete" } else { "" }
    );
    let mut checked = 0u64;
    let result = verify(
        &f,
        &base,
        lo_slot,
        hi_slot,
        &claimed,
        complete,
        &ps,
        &mut checked,
    );
    Ok(Outcome::of(result, claim, checked, "pieces"))
}

#[allow(clippy::too_many_arguments)]
fn verify(
    f: &OneVar,
    base: &Program,
    lo_slot: u32,
    hi_slot: Option<u32>,
    claimed: &[Claimed],
    complete: bool,
    ps: &[pieces::Piece],
    checked: &mut u64,
) -> Result<(), String> {
    let dlo = constant(base, lo_slot, "domain lo")?;
    let (dhi_inf, dhi_sup) = match hi_slot {
        Some(s) => {
            let h = constant(base, s, "domain hi")?;
            (h.inf(), h.sup())
        }
        None => (f64::INFINITY, f64::INFINITY),
    };
    if dlo.sup() >= dhi_inf {
        return Err(format!(
            "domain lo {:e} is not below domain hi {:e}",
            dlo.sup(),
            dhi_inf
        ));
    }
    for (k, c) in claimed.iter().enumerate() {
        if c.lo.inf() > c.hi.sup() {
            return Err(format!("root {}: lo is above hi", k + 1));
        }
        if let Some(next) = claimed.get(k + 1) {
            if c.hi.sup() >= next.lo.inf() {
                return Err(format!(
                    "roots {} and {} are not disjoint and increasing",
                    k + 1,
                    k + 2
                ));
            }
        }
        if complete && !c.unique {
            return Err(format!("complete, but root {} is undecided", k + 1));
        }
        // A unique enclosure counts a zero on the open domain, so it must lie in it.
        if c.unique && (c.lo.inf() <= dlo.sup() || c.hi.sup() >= dhi_inf) {
            return Err(format!(
                "root {}: unique enclosure not inside the open domain",
                k + 1
            ));
        }
    }
    pieces::check_cover(ps, dlo.inf(), dhi_sup)?;
    let mut matched = vec![0u32; claimed.len()];
    for (k, q) in ps.iter().enumerate() {
        let n = pieces::check_piece(f, k + 1, q, false)?;
        let x = q.x();
        match q.kind {
            Kind::Newton(_) => {
                let n = n.unwrap_or(Interval::EMPTY);
                let hits: Vec<usize> = claimed
                    .iter()
                    .enumerate()
                    .filter(|(_, c)| {
                        c.unique && c.holds(n) && c.lo.inf() >= x.inf() && c.hi.sup() <= x.sup()
                    })
                    .map(|(i, _)| i)
                    .collect();
                if hits.len() != 1 {
                    return Err(format!(
                        "piece {} (newton): Newton image [{:e}, {:e}] lies in {} claimed unique \
                         enclosures inside the piece, not exactly one",
                        k + 1,
                        n.inf(),
                        n.sup(),
                        hits.len()
                    ));
                }
                matched[hits[0]] += 1;
            }
            Kind::Undecided => {
                if !claimed.iter().any(|c| !c.unique && c.holds(x)) {
                    return Err(format!(
                        "piece {} (undecided) [{:e}, {:e}] lies in no claimed undecided enclosure",
                        k + 1,
                        q.lo,
                        q.hi
                    ));
                }
            }
            Kind::Exclude | Kind::ExcludeMv(_) => {}
        }
        *checked += 1;
    }
    for (i, c) in claimed.iter().enumerate() {
        if c.unique && matched[i] != 1 {
            return Err(format!(
                "root {}: matched by {} newton pieces, not exactly one",
                i + 1,
                matched[i]
            ));
        }
    }
    Ok(())
}
