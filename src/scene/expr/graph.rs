//! Postfix steps to one hash-consed DAG, and the DAG's nodes an output
//! needs to a [`Program`]; also the θ̇-polynomial coefficients of an output,
//! built on the same DAG.

use super::parse::{check_name, parse, Func, Step};
use super::tape::Program;
use super::{error, ExprError, Fail, THETA, THETA_DOT};
use inari::Interval;
use std::collections::{HashMap, HashSet};

/// One operation; operands are indices of earlier nodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Node {
    /// Index into the constant table.
    Const(u32),
    Theta,
    ThetaDot,
    Neg(u32),
    Add(u32, u32),
    Sub(u32, u32),
    Mul(u32, u32),
    Div(u32, u32),
    /// `x^2`, the interval square.
    Sqr(u32),
    /// `x^n`, n ≠ 2.
    Pown(u32, u32),
    Call(Func, u32),
    /// `min(a, b)`, `max(a, b)`.
    Call2(Func, u32, u32),
}

impl Node {
    pub(super) fn operands(self) -> [Option<u32>; 2] {
        match self {
            Node::Const(_) | Node::Theta | Node::ThetaDot => [None, None],
            Node::Add(a, b)
            | Node::Sub(a, b)
            | Node::Mul(a, b)
            | Node::Div(a, b)
            | Node::Call2(_, a, b) => [Some(a), Some(b)],
            Node::Neg(a) | Node::Sqr(a) | Node::Pown(a, _) | Node::Call(_, a) => [Some(a), None],
        }
    }

    /// The same operation on renamed operands (constants left alone).
    pub(super) fn map(self, f: impl Fn(u32) -> u32) -> Node {
        match self {
            Node::Const(_) | Node::Theta | Node::ThetaDot => self,
            Node::Neg(a) => Node::Neg(f(a)),
            Node::Add(a, b) => Node::Add(f(a), f(b)),
            Node::Sub(a, b) => Node::Sub(f(a), f(b)),
            Node::Mul(a, b) => Node::Mul(f(a), f(b)),
            Node::Div(a, b) => Node::Div(f(a), f(b)),
            Node::Sqr(a) => Node::Sqr(f(a)),
            Node::Pown(a, n) => Node::Pown(f(a), n),
            Node::Call(g, a) => Node::Call(g, f(a)),
            Node::Call2(g, a, b) => Node::Call2(g, f(a), f(b)),
        }
    }
}

/// A coefficient of a polynomial in θ̇ while it is built: exact 0 and 1 stay
/// symbolic so that they never become operations.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Coef {
    Zero,
    One,
    Node(u32),
}

/// Coefficients of θ̇⁰, θ̇¹, θ̇².
type Poly = [Coef; 3];

/// Hash-consed nodes: node ids are in topological order by construction.
#[derive(Default)]
struct Dag {
    nodes: Vec<Node>,
    index: HashMap<Node, u32>,
    consts: Vec<Interval>,
    /// Per constant: text that encloses to it exactly (a literal, a
    /// parameter's name, `pi`), for [`Program::render`].
    const_text: Vec<String>,
    const_index: HashMap<(u64, u64), u32>,
}

impl Dag {
    fn push(&mut self, n: Node) -> u32 {
        if let Some(&i) = self.index.get(&n) {
            return i;
        }
        let i = self.nodes.len() as u32;
        self.nodes.push(n);
        self.index.insert(n, i);
        i
    }

    fn constant(&mut self, x: Interval, text: &str) -> u32 {
        let key = (x.inf().to_bits(), x.sup().to_bits());
        let k = match self.const_index.get(&key) {
            Some(&k) => k,
            None => {
                let k = self.consts.len() as u32;
                self.consts.push(x);
                self.const_text.push(text.to_string());
                self.const_index.insert(key, k);
                k
            }
        };
        self.push(Node::Const(k))
    }

    /// A parameter: a constant of its own, never shared with a literal or
    /// another parameter of the same value, so that it keeps its name.
    fn parameter(&mut self, x: Interval, name: &str) -> u32 {
        let k = self.consts.len() as u32;
        self.consts.push(x);
        self.const_text.push(name.to_string());
        self.push(Node::Const(k))
    }

    /// Lowers postfix steps; every name must be in `scope`.
    fn lower(&mut self, steps: &[Step], scope: &HashMap<&str, u32>) -> Result<u32, Fail> {
        let mut stack: Vec<u32> = Vec::new();
        // The parser emits well-formed postfix; a short stack is a bug, but
        // reported, not a panic.
        let internal = || (None, "internal: malformed expression".to_string());
        for step in steps {
            let node = match *step {
                Step::Num(x, text) => {
                    stack.push(self.constant(x, text));
                    continue;
                }
                Step::Name(n, at) => {
                    let id = scope
                        .get(n)
                        .ok_or_else(|| (Some(at), format!("unknown name `{n}`")))?;
                    stack.push(*id);
                    continue;
                }
                Step::Call(f @ (Func::Min | Func::Max)) => {
                    let b = stack.pop().ok_or_else(internal)?;
                    let a = stack.pop().ok_or_else(internal)?;
                    Node::Call2(f, a, b)
                }
                Step::Neg | Step::Pow(_) | Step::Call(_) => {
                    let a = stack.pop().ok_or_else(internal)?;
                    match *step {
                        Step::Neg => Node::Neg(a),
                        Step::Pow(2) => Node::Sqr(a),
                        Step::Pow(n) => Node::Pown(a, n),
                        Step::Call(f) => Node::Call(f, a),
                        _ => return Err(internal()),
                    }
                }
                Step::Add | Step::Sub | Step::Mul | Step::Div => {
                    let b = stack.pop().ok_or_else(internal)?;
                    let a = stack.pop().ok_or_else(internal)?;
                    match *step {
                        Step::Add => Node::Add(a, b),
                        Step::Sub => Node::Sub(a, b),
                        Step::Mul => Node::Mul(a, b),
                        _ => Node::Div(a, b),
                    }
                }
            };
            stack.push(self.push(node));
        }
        match stack[..] {
            [x] => Ok(x),
            _ => Err(internal()),
        }
    }

    fn coef_node(&mut self, c: Coef) -> u32 {
        match c {
            Coef::Zero => self.constant(Interval::try_from((0.0, 0.0)).expect("exact"), "0"),
            Coef::One => self.constant(Interval::try_from((1.0, 1.0)).expect("exact"), "1"),
            Coef::Node(n) => n,
        }
    }

    fn op(&mut self, n: Node) -> Coef {
        Coef::Node(self.push(n))
    }

    fn add(&mut self, a: Coef, b: Coef) -> Coef {
        match (a, b) {
            (Coef::Zero, x) | (x, Coef::Zero) => x,
            _ => {
                let (a, b) = (self.coef_node(a), self.coef_node(b));
                self.op(Node::Add(a, b))
            }
        }
    }

    fn sub(&mut self, a: Coef, b: Coef) -> Coef {
        match (a, b) {
            (x, Coef::Zero) => x,
            (Coef::Zero, x) => self.neg(x),
            _ => {
                let (a, b) = (self.coef_node(a), self.coef_node(b));
                self.op(Node::Sub(a, b))
            }
        }
    }

    fn neg(&mut self, a: Coef) -> Coef {
        match a {
            Coef::Zero => Coef::Zero,
            _ => {
                let a = self.coef_node(a);
                self.op(Node::Neg(a))
            }
        }
    }

    fn mul(&mut self, a: Coef, b: Coef) -> Coef {
        match (a, b) {
            (Coef::Zero, _) | (_, Coef::Zero) => Coef::Zero,
            (Coef::One, x) | (x, Coef::One) => x,
            (Coef::Node(a), Coef::Node(b)) => self.op(Node::Mul(a, b)),
        }
    }

    fn div(&mut self, a: Coef, b: u32) -> Coef {
        match a {
            Coef::Zero => Coef::Zero,
            _ => {
                let a = self.coef_node(a);
                self.op(Node::Div(a, b))
            }
        }
    }

    /// `p·q`, `None` if a term of degree above 2 is not exactly 0.
    fn poly_mul(&mut self, p: Poly, q: Poly) -> Option<Poly> {
        let mut r = [Coef::Zero; 3];
        for (i, &a) in p.iter().enumerate() {
            for (j, &b) in q.iter().enumerate() {
                let t = self.mul(a, b);
                if t == Coef::Zero {
                    continue;
                }
                let k = r.get_mut(i + j)?;
                let sum = (*k, t);
                *k = self.add(sum.0, sum.1);
            }
        }
        Some(r)
    }

    /// The program of the nodes `outputs` needs, in id order.
    fn program(&self, outputs: &[u32]) -> Program {
        let mut needed = vec![false; self.nodes.len()];
        for &o in outputs {
            needed[o as usize] = true;
        }
        // Operands precede their users: one backward sweep marks them all.
        for i in (0..self.nodes.len()).rev() {
            if needed[i] {
                for a in self.nodes[i].operands().into_iter().flatten() {
                    needed[a as usize] = true;
                }
            }
        }
        let mut slot = vec![u32::MAX; self.nodes.len()];
        let mut const_slot: HashMap<u32, u32> = HashMap::new();
        let mut tape = Vec::new();
        let mut consts = Vec::new();
        let mut const_text = Vec::new();
        for (i, node) in self.nodes.iter().enumerate() {
            if !needed[i] {
                continue;
            }
            let n = match *node {
                Node::Const(k) => Node::Const(*const_slot.entry(k).or_insert_with(|| {
                    consts.push(self.consts[k as usize]);
                    const_text.push(self.const_text[k as usize].clone());
                    consts.len() as u32 - 1
                })),
                n => n.map(|a| slot[a as usize]),
            };
            slot[i] = tape.len() as u32;
            tape.push(n);
        }
        let outputs = outputs.iter().map(|&o| slot[o as usize]).collect();
        Program::new(tape, consts, const_text, outputs)
    }
}

/// Definitions in an order where each comes after those it names, or the
/// first cycle found, reported on its first definition.
fn definition_order(
    refs: &[Vec<(usize, usize)>],
    definitions: &[(String, String)],
) -> Result<Vec<usize>, ExprError> {
    const NEW: u8 = 0;
    const ON_PATH: u8 = 1;
    const DONE: u8 = 2;
    let mut state = vec![NEW; refs.len()];
    let mut order = Vec::with_capacity(refs.len());
    // (definition, how many of its references have been followed)
    let mut path: Vec<(usize, usize)> = Vec::new();
    for root in 0..refs.len() {
        if state[root] != NEW {
            continue;
        }
        state[root] = ON_PATH;
        path.push((root, 0));
        while let Some(top) = path.last_mut() {
            let d = top.0;
            let Some(&(e, _)) = refs[d].get(top.1) else {
                state[d] = DONE;
                order.push(d);
                path.pop();
                continue;
            };
            top.1 += 1;
            match state[e] {
                NEW => {
                    state[e] = ON_PATH;
                    path.push((e, 0));
                }
                ON_PATH => {
                    let start = path.iter().position(|p| p.0 == e).unwrap_or(0);
                    let mut names: Vec<&str> = path[start..]
                        .iter()
                        .map(|p| definitions[p.0].0.as_str())
                        .collect();
                    names.push(&definitions[e].0);
                    // Where `e` names the next definition of the cycle.
                    let at = path
                        .get(start)
                        .and_then(|p| refs[e].get(p.1.wrapping_sub(1)))
                        .map(|r| r.1);
                    let (name, text) = &definitions[e];
                    let msg = format!("definitions form a cycle: {}", names.join(" -> "));
                    return Err(error(name, text, (at, msg)));
                }
                _ => {}
            }
        }
    }
    Ok(order)
}

impl Program {
    /// Compiles definitions (any order; each a name for one shared value)
    /// and output expressions over the given parameter enclosures.
    pub fn compile(
        params: &[(String, Interval)],
        definitions: &[(String, String)],
        outputs: &[(String, String)],
    ) -> Result<Program, ExprError> {
        let mut dag = Dag::default();
        let mut scope: HashMap<&str, u32> = HashMap::new();
        scope.insert(THETA, dag.push(Node::Theta));
        scope.insert(THETA_DOT, dag.push(Node::ThetaDot));
        scope.insert("pi", dag.constant(Interval::PI, "pi"));
        let mut declared: HashSet<&str> = HashSet::new();
        for (name, x) in params {
            check_name(name, &declared)?;
            declared.insert(name);
            scope.insert(name, dag.parameter(*x, name));
        }
        let mut def_index: HashMap<&str, usize> = HashMap::new();
        for (i, (name, _)) in definitions.iter().enumerate() {
            check_name(name, &declared)?;
            declared.insert(name);
            def_index.insert(name, i);
        }
        let parsed = definitions
            .iter()
            .map(|(name, text)| parse(name, text))
            .collect::<Result<Vec<_>, _>>()?;
        // Which definitions each one names, and where; other names must be
        // known already.
        let mut refs = Vec::with_capacity(definitions.len());
        for ((name, text), steps) in definitions.iter().zip(&parsed) {
            let mut r = Vec::new();
            for step in steps {
                if let Step::Name(n, at) = *step {
                    if let Some(&j) = def_index.get(n) {
                        r.push((j, at));
                    } else if !scope.contains_key(n) {
                        let msg = format!("unknown name `{n}`");
                        return Err(error(name, text, (Some(at), msg)));
                    }
                }
            }
            refs.push(r);
        }
        for i in definition_order(&refs, definitions)? {
            let (name, text) = &definitions[i];
            let id = dag
                .lower(&parsed[i], &scope)
                .map_err(|e| error(name, text, e))?;
            scope.insert(name, id);
        }
        let mut outs = Vec::with_capacity(outputs.len());
        for (key, text) in outputs {
            let steps = parse(key, text)?;
            let id = dag.lower(&steps, &scope).map_err(|e| error(key, text, e))?;
            outs.push(id);
        }
        Ok(dag.program(&outs))
    }

    /// For an output of degree ≤ 2 in θ̇, a θ-only program with the three
    /// outputs `c2, c1, c0`: output = c2·θ̇² + c1·θ̇ + c0 as real functions.
    /// Built by polynomial arithmetic on the nodes; θ-only subexpressions
    /// are kept as they are, and exact 0 and 1 are never added or
    /// multiplied, so `A*theta_dot^2 + B*theta_dot + C` gives the nodes A, B,
    /// C themselves. A missing coefficient is the constant 0.
    pub fn quadratic(&self, i: usize) -> Option<Program> {
        self.quadratics(&[i])
    }

    /// [`Program::quadratic`] of several outputs in one program (outputs
    /// `c2, c1, c0` of each in turn), so that they share subexpressions.
    pub fn quadratics(&self, which: &[usize]) -> Option<Program> {
        self.coefficients(which, false)
    }

    /// [`Program::quadratics`] with each output's θ-only factor apart: five
    /// outputs `a, b, c2, c1, c0` per output, output = (a/b)·(c2·θ̇² + c1·θ̇ +
    /// c0) where the output is defined. The factor collects the θ̇-free
    /// operands of the products (into `a`), quotients (into `b`) and
    /// negations the output ends with (`a = b = 1` when there are none), as
    /// in `U/V` or `-(k*U)`: where the signs of `a` and `b` are known, the
    /// output's sign is that of the polynomial times theirs, and the
    /// polynomial's roots carry none of the factor's rounding (next to a zero
    /// of `V`, `U/V`'s coefficients have a large relative error, `U`'s do
    /// not).
    pub fn factored_quadratics(&self, which: &[usize]) -> Option<Program> {
        self.coefficients(which, true)
    }

    fn coefficients(&self, which: &[usize], factored: bool) -> Option<Program> {
        let mut outs = Vec::with_capacity(which.len());
        for &i in which {
            let out = *self.outputs.get(i)? as usize;
            if self.degree[out]? > 2 {
                return None;
            }
            outs.push(out);
        }
        let out = *outs.iter().max()?;
        let mut dag = Dag::default();
        let mut id: Vec<u32> = Vec::with_capacity(out + 1);
        let mut poly: Vec<Option<Poly>> = Vec::with_capacity(out + 1);
        for j in 0..=out {
            let node = self.tape[j];
            id.push(match node {
                Node::Const(k) => {
                    dag.constant(self.consts[k as usize], &self.const_text[k as usize])
                }
                n => dag.push(n.map(|a| id[a as usize])),
            });
            let p = |a: u32| poly[a as usize];
            let q = if !self.on_dot[j] {
                Some([Coef::Node(id[j]), Coef::Zero, Coef::Zero])
            } else if self.degree[j].is_none_or(|d| d > 2) {
                None
            } else {
                match node {
                    Node::ThetaDot => Some([Coef::Zero, Coef::One, Coef::Zero]),
                    Node::Neg(a) => p(a).map(|x| x.map(|c| dag.neg(c))),
                    Node::Add(a, b) => p(a)
                        .zip(p(b))
                        .map(|(x, y)| std::array::from_fn(|k| dag.add(x[k], y[k]))),
                    Node::Sub(a, b) => p(a)
                        .zip(p(b))
                        .map(|(x, y)| std::array::from_fn(|k| dag.sub(x[k], y[k]))),
                    Node::Mul(a, b) => p(a).zip(p(b)).and_then(|(x, y)| dag.poly_mul(x, y)),
                    Node::Div(a, b) => p(a).map(|x| x.map(|c| dag.div(c, id[b as usize]))),
                    Node::Sqr(a) => p(a).and_then(|x| dag.poly_mul(x, x)),
                    // x^0 is 1 whatever x's degree.
                    Node::Pown(_, 0) => Some([Coef::One, Coef::Zero, Coef::Zero]),
                    // A power of a θ̇-free polynomial: one power node.
                    Node::Pown(a, n) if self.degree[a as usize] == Some(0) => {
                        p(a).map(|x| match x[0] {
                            Coef::Node(c) => [dag.op(Node::Pown(c, n)), Coef::Zero, Coef::Zero],
                            c => [c, Coef::Zero, Coef::Zero],
                        })
                    }
                    // Degree ≥ 1 and n·degree ≤ 2: n ≤ 2 factors.
                    Node::Pown(a, n) => p(a).and_then(|x| {
                        let mut r = x;
                        for _ in 1..n {
                            r = dag.poly_mul(r, x)?;
                        }
                        Some(r)
                    }),
                    _ => None,
                }
            };
            poly.push(q);
        }
        let mut coefs = Vec::with_capacity(5 * outs.len());
        for o in outs {
            let (mut num, mut den, mut o) = (Coef::One, Coef::One, o);
            while factored && self.on_dot[o] {
                let dot = |a: u32| self.on_dot[a as usize];
                let k = |a: u32| Coef::Node(id[a as usize]);
                o = match self.tape[o] {
                    Node::Neg(a) => {
                        num = dag.neg(num);
                        a
                    }
                    Node::Mul(a, b) if !dot(a) => {
                        num = dag.mul(num, k(a));
                        b
                    }
                    Node::Mul(a, b) if !dot(b) => {
                        num = dag.mul(num, k(b));
                        a
                    }
                    Node::Div(a, b) if !dot(b) => {
                        den = dag.mul(den, k(b));
                        a
                    }
                    _ => break,
                } as usize;
            }
            let [c0, c1, c2] = poly[o]?;
            if factored {
                coefs.extend([num, den].map(|c| dag.coef_node(c)));
            }
            coefs.extend([c2, c1, c0].map(|c| dag.coef_node(c)));
        }
        Some(dag.program(&coefs))
    }
}
