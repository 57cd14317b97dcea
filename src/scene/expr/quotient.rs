//! A one-output program read as a quotient `f/g` at its top level, and
//! what its graph says about θ̇: whether it reads θ̇ at all, and whether only
//! through even powers. Singular points of a θ̈ written `f/g` are where
//! both vanish (`crate::motion::singular`).

use super::{Node, Program};

/// The numerator and the denominator of a program whose output is `f/g`:
/// each one output, the very operations of the text (so `f/g` evaluated
/// from them is the program's value wherever it is defined).
#[derive(Clone, Debug)]
pub struct Quotient {
    pub numerator: Program,
    pub denominator: Program,
}

impl Program {
    /// `f` and `g` when output 0 is the division `f/g` (the last operation
    /// of its text); `None` otherwise (`-(f/g)`, `f/g + 1`, no division).
    pub fn quotient(&self) -> Option<Quotient> {
        match self.tape[*self.outputs.first()? as usize] {
            Node::Div(a, b) => Some(Quotient {
                numerator: self.select(a),
                denominator: self.select(b),
            }),
            _ => None,
        }
    }

    /// Whether output 0 depends on θ̇ (syntactically: θ̇ is on its tape).
    pub fn reads_theta_dot(&self) -> bool {
        self.outputs
            .first()
            .is_some_and(|&o| self.on_dot[o as usize])
    }

    /// Whether output 0 is even in θ̇ by construction: θ̇ is read only by
    /// squares and even powers, so its value at (θ, −θ̇) is its value at
    /// (θ, θ̇) operation by operation. A sufficient condition only.
    pub fn even_in_theta_dot(&self) -> bool {
        let Some(&o) = self.outputs.first() else {
            return false;
        };
        let p = self.select(o);
        let out = p.outputs[0] as usize;
        let dot = p.tape.iter().position(|n| *n == Node::ThetaDot);
        let Some(dot) = dot.map(|d| d as u32) else {
            return true;
        };
        out != dot as usize
            && p.tape.iter().all(|n| match *n {
                Node::Sqr(_) => true,
                Node::Pown(a, k) => a != dot || k % 2 == 0,
                n => n.operands().into_iter().flatten().all(|a| a != dot),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use inari::Interval;

    fn compile(text: &str) -> Program {
        let mu = Interval::try_from((1.5, 1.5)).unwrap();
        let defs = [
            ("U".to_string(), "sin(theta)*theta_dot^2 - 9".to_string()),
            (
                "V".to_string(),
                "1 + 3*cos(theta)^2 - 3*mu*sin(theta)*cos(theta)".to_string(),
            ),
        ];
        Program::compile(&[("mu".into(), mu)], &defs, &[("o".into(), text.into())]).unwrap()
    }

    fn at(p: &Program, theta: f64, theta_dot: f64) -> f64 {
        let mut out = [0.0];
        p.eval(theta, theta_dot, &mut out);
        out[0]
    }

    #[test]
    fn a_top_level_division_splits_into_its_operands() {
        let q = compile("3*U*(cos(theta) - mu*sin(theta))/(2*V)")
            .quotient()
            .expect("a quotient");
        let (t, w) = (0.7_f64, 1.3_f64);
        let u = t.sin() * w * w - 9.0;
        let v = 1.0 + 3.0 * t.cos().powi(2) - 3.0 * 1.5 * t.sin() * t.cos();
        let f = 3.0 * u * (t.cos() - 1.5 * t.sin());
        assert!((at(&q.numerator, t, w) - f).abs() < 1e-12);
        assert!((at(&q.denominator, t, w) - 2.0 * v).abs() < 1e-12);
        assert!(q.numerator.reads_theta_dot());
        assert!(!q.denominator.reads_theta_dot());
    }

    #[test]
    fn only_a_division_at_the_top_is_a_quotient() {
        assert!(compile("-(U/V)").quotient().is_none());
        assert!(compile("U/V + 1").quotient().is_none());
        assert!(compile("U*V").quotient().is_none());
        assert!(compile("(U/V)/theta").quotient().is_some());
    }

    #[test]
    fn evenness_in_theta_dot_is_read_off_the_powers() {
        assert!(compile("cos(theta)*theta_dot^2 + V").even_in_theta_dot());
        assert!(compile("U/V").even_in_theta_dot());
        assert!(compile("sin(theta)").even_in_theta_dot());
        assert!(compile("theta_dot^4 - theta").even_in_theta_dot());
        assert!(!compile("theta_dot").even_in_theta_dot());
        assert!(!compile("theta_dot^3").even_in_theta_dot());
        assert!(!compile("U + theta_dot").even_in_theta_dot());
        // Even, but not by the powers alone: the test is sufficient only.
        assert!(!compile("sin(theta_dot)^2").even_in_theta_dot());
    }
}
