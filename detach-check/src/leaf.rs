//! The leaf tests: one label decided exactly as the `paving` claim decides
//! it (FORMAT.md, "Claim `paving`", step 3: natural value, monotone test,
//! convex test), for every claim that labels a box, and from a statement's
//! text for a prover ([`StatedConstraints`]). A prover uses it to state only labels a
//! checker confirms, run under [`crate::with_looseness`] to state only labels
//! that a looser checker confirms too. It never proves a label the checker
//! would refuse: it is the checker's own test.

use inari::{DecInterval, Interval};

use super::eval::{continuous, defined, Dual, Num, Program};
use super::tree::iv;

/// Constraints `{expr < 0}` over the variables `t`, `w`, compiled from
/// parameters, definitions and expressions as a `paving` statement gives
/// them.
pub struct StatedConstraints {
    prog: Program,
    roots: Vec<u32>,
}

impl StatedConstraints {
    /// Compiles a statement's text; an error says what does not parse.
    pub fn compile(
        parameters: &[(String, String)],
        definitions: &[(String, String)],
        constraints: &[String],
    ) -> Result<Self, String> {
        let mut prog = Program::new(&["t", "w"])?;
        prog.add_parameters(parameters)?;
        for (name, text) in definitions {
            prog.define(name, text)?;
        }
        let roots = constraints
            .iter()
            .map(|e| prog.compile(e))
            .collect::<Result<_, _>>()?;
        Ok(StatedConstraints { prog, roots })
    }

    /// The enclosure of an expression that depends on neither variable (a
    /// domain end), as this checker computes it under the current rounding.
    pub fn constant(&mut self, text: &str) -> Result<Interval, String> {
        let s = self.prog.compile_constant(text)?;
        let whole = DecInterval::new(Interval::ENTIRE);
        let x = self.prog.value(&[whole, whole], s);
        if x.decoration() < inari::Decoration::Def {
            return Err(format!("{text:?} is not defined"));
        }
        Ok(x.interval().unwrap_or(Interval::ENTIRE))
    }

    /// Whether constraint `c` is proved in (`want_in`) or out on the leaf
    /// `t × w` by one of the checker's three tests.
    pub fn label_holds(&self, c: usize, t: Interval, w: Interval, want_in: bool) -> bool {
        let Some(&root) = self.roots.get(c) else {
            return false;
        };
        proved(&self.prog, root, t, w, want_in)
    }
}

/// The value of `slot` is proved negative (`want_in`) or positive on
/// `t × w` by one of the three tests.
pub(crate) fn proved(prog: &Program, slot: u32, t: Interval, w: Interval, want_in: bool) -> bool {
    let v = prog.value(&[DecInterval::new(t), DecInterval::new(w)], slot);
    holds(v, want_in)
        || holds(monotone_bound(prog, slot, t, w, want_in), want_in)
        || convex_holds(prog, slot, t, w, want_in)
}

/// The value `v` is defined and proves the label (in: `sup < 0`, out: `inf > 0`).
pub(crate) fn holds(v: DecInterval, want_in: bool) -> bool {
    defined(v)
        && v.interval().is_some_and(|i| {
            if want_in {
                i.sup() < 0.0
            } else {
                i.inf() > 0.0
            }
        })
}

/// The monotone test (FORMAT.md, step 3): where a partial derivative of the
/// expression has a constant sign on `t × w`, the largest value (for `in`;
/// the smallest for `out`) lies on one end of that variable, so the variable
/// is replaced by that end and the expression evaluated naturally on the
/// reduced box. Requires the value and both partials to be continuous
/// (`≥ dac`), which makes the function differentiable on the box (the rules
/// at non-differentiable points, `sqrt` and `abs` at 0, are undefined).
/// Returns `NAI` when no variable can be fixed.
pub(crate) fn monotone_bound(
    prog: &Program,
    root: u32,
    t: Interval,
    w: Interval,
    want_in: bool,
) -> DecInterval {
    let (td, wd) = (DecInterval::new(t), DecInterval::new(w));
    let seed = |k: usize| -> Dual<DecInterval> {
        let vars = if k == 0 {
            [Dual::variable(td), Num::constant(wd)]
        } else {
            [Num::constant(td), Dual::variable(wd)]
        };
        prog.value(&vars, root)
    };
    let (dt, dw) = (seed(0), seed(1));
    if !(continuous(dt.v) && continuous(dt.d) && continuous(dw.d)) {
        return DecInterval::NAI;
    }
    let mut fixed = false;
    let mut end = |x: Interval, d: DecInterval| -> Interval {
        let d = d.interval().unwrap_or(Interval::ENTIRE);
        // Nondecreasing: the largest value at the upper end, the smallest at the lower.
        let pick = if d.inf() >= 0.0 {
            Some(want_in)
        } else if d.sup() <= 0.0 {
            Some(!want_in)
        } else {
            None
        };
        match pick {
            Some(upper) => {
                fixed = true;
                let e = if upper { x.sup() } else { x.inf() };
                iv(e, e)
            }
            None => x,
        }
    };
    let (t1, w1) = (end(t, dt.d), end(w, dw.d));
    if !fixed {
        return DecInterval::NAI;
    }
    prog.value(&[DecInterval::new(t1), DecInterval::new(w1)], root)
}

/// The convex test (FORMAT.md, step 3): evaluate the expression on `t × w`
/// in nested forward-mode duals seeded in `w` (its second derivative in `w`).
/// If the value and both derivatives are continuous (`≥ dac`) and the second
/// derivative has `inf ≥ 0` (for `in`; `sup ≤ 0` for `out`), the expression is
/// convex (concave) in `w` for every `t`, so its largest (smallest) value on
/// the box lies on `t × {w0}` or `t × {w1}`; the label holds if it holds on
/// both segments, each by its natural value or the monotone test.
pub(crate) fn convex_holds(
    prog: &Program,
    root: u32,
    t: Interval,
    w: Interval,
    want_in: bool,
) -> bool {
    let td = DecInterval::new(t);
    let vars = [
        Num::constant(td),
        Dual::variable(Dual::variable(DecInterval::new(w))),
    ];
    let g: Dual<Dual<DecInterval>> = prog.value(&vars, root);
    if ![g.v.v, g.v.d, g.d.v, g.d.d].into_iter().all(continuous) {
        return false;
    }
    let Some(d2) = g.d.d.interval() else {
        return false;
    };
    let shape = if want_in {
        d2.inf() >= 0.0
    } else {
        d2.sup() <= 0.0
    };
    shape
        && [w.inf(), w.sup()].into_iter().all(|e| {
            let we = iv(e, e);
            holds(prog.value(&[td, DecInterval::new(we)], root), want_in)
                || holds(monotone_bound(prog, root, t, we, want_in), want_in)
        })
}
