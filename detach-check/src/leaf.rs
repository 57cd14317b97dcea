//! One leaf label decided exactly as the `paving` claim decides it
//! (FORMAT.md, "Claim `paving`", step 3: natural value, monotone test, convex
//! test), from a statement's text. A prover uses it to state only labels a
//! checker confirms, run under [`crate::with_looseness`] to state only labels
//! that a looser checker confirms too. It never proves a label the checker
//! would refuse: it is the checker's own test.

use inari::{DecInterval, Interval};

use super::eval::Program;
use super::paving::{convex_holds, holds, monotone_bound};

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
        let vars = [DecInterval::new(t), DecInterval::new(w)];
        holds(self.prog.value(&vars, root), want_in)
            || holds(monotone_bound(&self.prog, root, t, w, want_in), want_in)
            || convex_holds(&self.prog, root, t, w, want_in)
    }
}
