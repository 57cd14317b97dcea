//! Which output is another output times or divided by a factor free of θ̇:
//! the structure behind the factor rule of parameter atlases
//! ([`crate::params`]). Where the factor's sign is known, the two outputs
//! have the same or opposite signs at every point.

use super::{Node, Program};

/// Output `output` is output `other`'s value divided (`divides`) or
/// multiplied by `factor`, a program of one output that does not depend on
/// θ̇.
#[derive(Clone, Debug)]
pub struct FactorOf {
    pub output: usize,
    pub other: usize,
    pub divides: bool,
    pub factor: Program,
}

impl Program {
    /// Every pair of outputs where one is `other / f`, `other * f` or
    /// `f * other` with `f` free of θ̇, read off the compiled graph (shared
    /// subexpressions are one node, so `U/V` against `U` is found whatever
    /// the definitions are called).
    pub fn factors(&self) -> Vec<FactorOf> {
        let mut found = Vec::new();
        for (output, &o) in self.outputs.iter().enumerate() {
            for (other, &p) in self.outputs.iter().enumerate() {
                if other == output || p == o {
                    continue;
                }
                let (f, divides) = match self.tape[o as usize] {
                    Node::Div(a, b) if a == p => (b, true),
                    Node::Mul(a, b) if a == p => (b, false),
                    Node::Mul(a, b) if b == p => (a, false),
                    _ => continue,
                };
                if self.on_dot[f as usize] {
                    continue;
                }
                found.push(FactorOf {
                    output,
                    other,
                    divides,
                    factor: self.select(f),
                });
            }
        }
        found
    }

    /// The program of one entry alone: the entries it uses, renumbered.
    pub(super) fn select(&self, entry: u32) -> Program {
        let mut needed = vec![false; self.tape.len()];
        needed[entry as usize] = true;
        for i in (0..self.tape.len()).rev() {
            if needed[i] {
                for a in self.tape[i].operands().into_iter().flatten() {
                    needed[a as usize] = true;
                }
            }
        }
        let mut slot = vec![u32::MAX; self.tape.len()];
        let mut tape = Vec::new();
        for (i, node) in self.tape.iter().enumerate() {
            if needed[i] {
                slot[i] = tape.len() as u32;
                tape.push(node.map(|a| slot[a as usize]));
            }
        }
        Program::new(
            tape,
            self.consts.clone(),
            self.const_text.clone(),
            vec![slot[entry as usize]],
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use inari::Interval;

    fn compile(outputs: &[&str]) -> Program {
        let one = Interval::try_from((1.5, 1.5)).unwrap();
        let defs = [
            ("U".to_string(), "theta_dot^2*sin(theta) - 9".to_string()),
            (
                "V".to_string(),
                "1 + 3*cos(theta)^2 - 3*mu*sin(theta)*cos(theta)".to_string(),
            ),
        ];
        let outs: Vec<(String, String)> = outputs
            .iter()
            .enumerate()
            .map(|(i, t)| (format!("o{i}"), t.to_string()))
            .collect();
        Program::compile(&[("mu".into(), one)], &defs, &outs).unwrap()
    }

    #[test]
    fn quotient_and_products_by_theta_only_factors_are_found() {
        let f = compile(&["U", "U/V"]).factors();
        assert_eq!(f.len(), 1);
        assert_eq!((f[0].output, f[0].other, f[0].divides), (1, 0, true));
        // The factor alone: V at θ = 0 is 1 + 3 = 4.
        let mut out = [0.0];
        f[0].factor.eval(0.0, 123.0, &mut out);
        assert_eq!(out[0], 4.0);
        let f = compile(&["V*U", "U"]).factors();
        assert_eq!((f[0].output, f[0].other, f[0].divides), (0, 1, false));
    }

    #[test]
    fn factors_depending_on_theta_dot_or_other_forms_are_not() {
        assert!(compile(&["U", "U/theta_dot"]).factors().is_empty());
        assert!(compile(&["U", "U + V"]).factors().is_empty());
        assert!(compile(&["U", "-(U/V)"]).factors().is_empty());
        assert!(compile(&["U", "U"]).factors().is_empty());
    }
}
