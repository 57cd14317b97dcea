//! The `critical-band` claim: for each box of a parameter `alpha`, a function
//! P(x; alpha, kappa) has at least two zeros on (0, ∞) for every kappa in
//! [0, lower], and none for every kappa ≥ upper.

use inari::Interval;

use super::encoding::{decimal_enclosure, parse_hex_f64};
use super::eval::{continuous, parameter_enclosure, show};
use super::json::{arr_of, as_obj, decls, obj_of, opt_str, pair_of, str_of, Obj};
use super::pieces::{self, Kind};
use super::roots::OneVar;
use super::{Outcome, Unreadable, Verdict};

/// One claimed cell: the alpha box and the kappa bounds (decimal text, with
/// their enclosures).
struct Cell {
    alpha: (String, String),
    lower: (String, Interval),
    upper: (String, Interval),
    points: Vec<f64>,
    pieces: Vec<pieces::Piece>,
}

fn point(x: f64) -> Interval {
    Interval::try_from((x, x)).unwrap_or(Interval::EMPTY)
}

pub fn check(root: &Obj) -> Result<Outcome, Unreadable> {
    let st = obj_of(root, "statement")?;
    let ev = obj_of(root, "evidence")?;
    let (params, defs) = decls(st)?;
    let variable = str_of(st, "variable")?;
    let function = str_of(st, "function")?;
    let claims = arr_of(st, "cells")?;
    let witnesses = arr_of(ev, "cells")?;
    if claims.len() != witnesses.len() {
        return Err(Unreadable(format!(
            "{} claimed cells but {} witnessed",
            claims.len(),
            witnesses.len()
        )));
    }
    let mut cells = Vec::with_capacity(claims.len());
    for (k, (c, w)) in claims.iter().zip(witnesses).enumerate() {
        let at = |e: String| Unreadable(format!("cell {}: {e}", k + 1));
        let c = as_obj(c, "a cell")?;
        let w = as_obj(w, "a cell's evidence")?;
        let (a0, a1) = pair_of(c.get("alpha").unwrap_or(&serde_json::Value::Null), "alpha")?;
        // A parameter box: decimal ends (`-inf`, `inf` allowed), not inverted.
        parameter_enclosure(&format!("[{a0},{a1}]")).map_err(|e| at(format!("alpha: {e}")))?;
        let bound = |key: &str| -> Result<(String, Interval), Unreadable> {
            let text = str_of(c, key)?;
            let x = decimal_enclosure(text).map_err(|e| at(format!("{key}: {e}")))?;
            Ok((text.to_string(), x))
        };
        let points = arr_of(w, "points")?
            .iter()
            .map(|p| {
                p.as_str()
                    .ok_or_else(|| at("points must be strings".into()))
                    .and_then(|t| parse_hex_f64(t, false).map_err(at))
            })
            .collect::<Result<Vec<_>, _>>()?;
        cells.push(Cell {
            alpha: (a0.to_string(), a1.to_string()),
            lower: bound("lower")?,
            upper: bound("upper")?,
            points,
            pieces: pieces::parse(arr_of(w, "pieces")?, "piece").map_err(|e| at(e.0))?,
        });
    }
    let compile = |alpha: &(String, String), kappa: String| {
        let mut p = params.clone();
        p.push(("alpha".into(), format!("[{},{}]", alpha.0, alpha.1)));
        p.push(("kappa".into(), kappa));
        OneVar::new(variable, &p, &defs, function).map(|(f, _)| f)
    };
    // The function compiles (names, grammar) before any verdict, even with
    // no cells; the boxes of each cell are then known to be well formed.
    compile(&("0".into(), "0".into()), "0".into())?;
    let claim = format!(
        "critical band {}: {} alpha boxes",
        opt_str(st, "equation")?.unwrap_or(""),
        cells.len()
    );
    let mut checked = 0u64;
    let mut verdict = Verdict::Valid;
    for (k, cell) in cells.iter().enumerate() {
        if let Err(e) = verify_cell(cell, |kappa| compile(&cell.alpha, kappa).map_err(|e| e.0)) {
            verdict = Verdict::Invalid(format!(
                "cell {} (alpha in [{}, {}]): {e}",
                k + 1,
                cell.alpha.0,
                cell.alpha.1
            ));
            break;
        }
        checked += 1;
    }
    Ok(Outcome {
        verdict,
        claim,
        checked,
        unit: "cells",
    })
}

/// Checks one cell; `compile` gives P with `kappa` the box it is passed.
fn verify_cell(
    cell: &Cell,
    compile: impl Fn(String) -> Result<OneVar, String>,
) -> Result<(), String> {
    let ((lower_text, lower), (upper_text, upper)) = (&cell.lower, &cell.upper);
    if lower.inf() < 0.0 || lower.sup() > upper.inf() {
        return Err(format!(
            "need 0 ≤ lower ≤ upper, got {lower_text} and {upper_text}"
        ));
    }
    let below = compile(format!("[0,{lower_text}]"))?;
    let above = compile(format!("[{upper_text},inf]"))?;
    // (i) Signs +, −, + at x0 < x1 < x2 with x0 ≥ 0, f continuous on [x0, x2]:
    // two zeros in (x0, x2) ⊂ (0, ∞) for every alpha and kappa ∈ [0, lower].
    // lower = 0 claims nothing and needs no points.
    if lower.sup() > 0.0 {
        let [x0, x1, x2] = cell.points[..] else {
            return Err("lower > 0 needs exactly three points".into());
        };
        if !(0.0 <= x0 && x0 < x1 && x1 < x2 && x2.is_finite()) {
            return Err(format!(
                "points must satisfy 0 ≤ x0 < x1 < x2, got {x0:e} {x1:e} {x2:e}"
            ));
        }
        let whole = below.value(Interval::try_from((x0, x2)).map_err(|_| "bad points")?);
        if !continuous(whole) {
            return Err(format!(
                "f is not continuous on [x0, x2], computed {}",
                show(whole)
            ));
        }
        for (x, positive) in [(x0, true), (x1, false), (x2, true)] {
            let v = below.value(point(x));
            let ok = v.interval().is_some_and(|i| {
                if positive {
                    i.inf() > 0.0
                } else {
                    i.sup() < 0.0
                }
            });
            if !ok {
                return Err(format!(
                    "f({x:e}) for kappa in [0, lower] is not {}, computed {}",
                    if positive { "> 0" } else { "< 0" },
                    show(v)
                ));
            }
        }
    }
    // (ii) No zero on [0, ∞) for every alpha and kappa ≥ upper.
    pieces::check_cover(&cell.pieces, 0.0, f64::INFINITY)?;
    for (k, q) in cell.pieces.iter().enumerate() {
        if !matches!(q.kind, Kind::Exclude | Kind::ExcludeMv(_)) {
            return Err(format!(
                "piece {}: only exclusion pieces prove no zero",
                k + 1
            ));
        }
        pieces::check_piece(&above, k + 1, q, false)?;
    }
    Ok(())
}
