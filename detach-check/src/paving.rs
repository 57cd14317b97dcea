//! The `paving` claim: areas of sets `{g_i < 0}` on a rectangle, certified
//! by a bisection tree (`tree/1`).

use inari::{DecInterval, Interval};
use std::collections::HashMap;

use super::area::{AreaSum, LeafArea};
use super::empty::{empty_tree, factor_table, Reasons};
use super::encoding::{base64_decode, decimal_enclosure, parse_hex_f64, BitReader};
use super::eval::{apply, loosen_i, show, Op, Program};
use super::json::{arr_of, as_obj, decls, obj_of, opt_str, pair_of, str_of, u64_of, Obj};
use super::leaf::{convex_holds, holds, monotone_bound};
use super::roots::constant;
use super::tree::{iv, labels, walk};
use super::{Outcome, Unreadable};

/// Cached intervals per axis before the cache is emptied (the preorder walk
/// revisits recent intervals, so a small cache suffices).
const CACHE_ENTRIES: usize = 1 << 15;

/// Cached slot values per axis before the cache is emptied: bounds its
/// memory (32 B a value, 16 MiB an axis) however many slots an interval
/// fills. An interval with more slots than this is not cached.
const CACHE_SLOTS: usize = 1 << 19;

/// Leaf labels.
const IN: u8 = 0b01;
const OUT: u8 = 0b10;

/// Evaluates the constraints on leaf boxes. Slots that depend only on `t`
/// (or only on `w`) are cached per interval, keyed on the endpoints' bits;
/// constant slots are computed once. Values are bit-identical to a full
/// evaluation, because every slot is a deterministic function of its inputs.
struct LeafEval {
    ops: Vec<Op>,
    vals: Vec<DecInterval>,
    roots: Vec<u32>,
    /// Per axis: the slots depending on that variable alone.
    axis_slots: [Vec<u32>; 2],
    /// Per set of constraints to check (bit mask): slots depending on both.
    both: Vec<Vec<u32>>,
    cache: [HashMap<(u64, u64), usize>; 2],
    arena: [Vec<DecInterval>; 2],
}

impl LeafEval {
    fn new(prog: &Program, roots: Vec<u32>) -> Self {
        let ops = prog.ops().to_vec();
        let deps = prog.deps();
        let n = ops.len();
        // Slots each constraint needs (operands precede their users).
        let needed: Vec<Vec<bool>> = roots
            .iter()
            .map(|&r| {
                let mut need = vec![false; n];
                if let Some(x) = need.get_mut(r as usize) {
                    *x = true;
                }
                for i in (0..n).rev() {
                    if need[i] {
                        for a in prog.operands(i).into_iter().flatten() {
                            need[a as usize] = true;
                        }
                    }
                }
                need
            })
            .collect();
        let any = |i: usize| needed.iter().any(|v| v[i]);
        let axis_slots = [1u8, 2u8].map(|d| {
            (0..n)
                .filter(|&i| deps[i] == d && any(i))
                .map(|i| i as u32)
                .collect()
        });
        let both = (0..1usize << roots.len())
            .map(|mask| {
                (0..n)
                    .filter(|&i| {
                        deps[i] == 3
                            && needed
                                .iter()
                                .enumerate()
                                .any(|(c, v)| mask >> c & 1 == 1 && v[i])
                    })
                    .map(|i| i as u32)
                    .collect()
            })
            .collect();
        // Constants once: variables are absent, so only constant slots matter.
        let mut vals = vec![DecInterval::EMPTY; n];
        for i in 0..n {
            if deps[i] == 0 {
                vals[i] = apply(&ops[i], &vals, &[]);
            }
        }
        LeafEval {
            ops,
            vals,
            roots,
            axis_slots,
            both,
            cache: [HashMap::new(), HashMap::new()],
            arena: [Vec::new(), Vec::new()],
        }
    }

    /// Fills the slots of one axis for interval `x`, from the cache if seen.
    fn load_axis(&mut self, axis: usize, x: Interval, vars: &[DecInterval; 2]) {
        let key = (x.inf().to_bits(), x.sup().to_bits());
        let slots = &self.axis_slots[axis];
        if let Some(&off) = self.cache[axis].get(&key) {
            for (j, &s) in slots.iter().enumerate() {
                self.vals[s as usize] = self.arena[axis][off + j];
            }
            return;
        }
        for &s in slots {
            let v = apply(&self.ops[s as usize], &self.vals, vars);
            self.vals[s as usize] = v;
        }
        if slots.len() > CACHE_SLOTS {
            return;
        }
        if self.cache[axis].len() >= CACHE_ENTRIES
            || self.arena[axis].len() + slots.len() > CACHE_SLOTS
        {
            self.cache[axis].clear();
            self.arena[axis].clear();
        }
        let off = self.arena[axis].len();
        self.arena[axis].extend(slots.iter().map(|&s| self.vals[s as usize]));
        self.cache[axis].insert(key, off);
    }

    /// Evaluates the constraints in `mask` on `t × w`; their values are then
    /// at `self.value(c)`.
    fn eval(&mut self, t: Interval, w: Interval, mask: usize) {
        let vars = [DecInterval::new(t), DecInterval::new(w)];
        self.load_axis(0, t, &vars);
        self.load_axis(1, w, &vars);
        for k in 0..self.both[mask].len() {
            let s = self.both[mask][k] as usize;
            let v = apply(&self.ops[s], &self.vals, &vars);
            self.vals[s] = v;
        }
    }

    fn value(&self, c: usize) -> DecInterval {
        self.vals[self.roots[c] as usize]
    }
}

/// One area entry: literals (constraint index, wants in) and claimed bounds.
struct AreaClaim {
    set: String,
    literals: Vec<(usize, bool)>,
    inner: Option<(String, Interval)>,
    outer: Option<(String, Interval)>,
    /// The set asks one function to be both negative and not: it is empty.
    empty: bool,
}

/// An area's set proved empty (`evidence.empty`): an emptiness tree
/// (`empty/1`) from a phase box containing the domain.
struct EmptyEvidence {
    area: usize,
    phase_box: [f64; 4],
    nodes: u64,
    body: Vec<u8>,
}

struct Statement {
    prog: Program,
    names: Vec<String>,
    roots: Vec<u32>,
    /// The factor forms between constraints, for emptiness reasons.
    factor: Vec<Vec<Option<u32>>>,
    empty: Vec<EmptyEvidence>,
    domain: [u32; 4],
    root_box: [f64; 4],
    leaves: u64,
    areas: Vec<AreaClaim>,
    nodes: u64,
    body: Vec<u8>,
}

fn parse(root: &Obj) -> Result<(Statement, String), Unreadable> {
    let st = obj_of(root, "statement")?;
    let ev = obj_of(root, "evidence")?;
    let (params, defs) = decls(st)?;
    let mut prog = Program::new(&["t", "w"])?;
    prog.add_parameters(&params)?;
    for (n, e) in &defs {
        prog.define(n, e)?;
    }
    let cons = arr_of(st, "constraints")?;
    if cons.is_empty() || cons.len() > 4 {
        return Err(Unreadable("1 to 4 constraints are required".into()));
    }
    let mut names: Vec<String> = Vec::new();
    let mut texts: Vec<String> = Vec::new();
    let mut roots = Vec::new();
    for c in cons {
        let o = as_obj(c, "a constraint")?;
        let name = str_of(o, "name")?;
        if names.iter().any(|n| n == name) {
            return Err(Unreadable(format!(
                "constraint name {name:?} is used twice"
            )));
        }
        names.push(name.to_string());
        // Identical texts (spaces aside) are the same function, hence the same set.
        texts.push(str_of(o, "expr")?.split_whitespace().collect());
        roots.push(
            prog.compile(str_of(o, "expr")?)
                .map_err(|e| format!("constraint {name}: {e}"))?,
        );
    }
    let dom = obj_of(st, "domain")?;
    let (t0, t1) = pair_of(dom.get("t").unwrap_or(&serde_json::Value::Null), "domain t")?;
    let (w0, w1) = pair_of(dom.get("w").unwrap_or(&serde_json::Value::Null), "domain w")?;
    let domain = [
        prog.compile_constant(t0)?,
        prog.compile_constant(t1)?,
        prog.compile_constant(w0)?,
        prog.compile_constant(w1)?,
    ];
    let rb = obj_of(st, "root_box")?;
    let (rt0, rt1) = pair_of(
        rb.get("t").unwrap_or(&serde_json::Value::Null),
        "root_box t",
    )?;
    let (rw0, rw1) = pair_of(
        rb.get("w").unwrap_or(&serde_json::Value::Null),
        "root_box w",
    )?;
    let mut root_box = [0.0; 4];
    for (slot, text) in root_box.iter_mut().zip([rt0, rt1, rw0, rw1]) {
        *slot = parse_hex_f64(text, false).map_err(|e| format!("root_box: {e}"))?;
    }
    let leaves = u64_of(st, "leaves")?;
    let mut areas = Vec::new();
    for (k, a) in arr_of(st, "areas")?.iter().enumerate() {
        let o = as_obj(a, "an area")?;
        let set = opt_str(o, "set")?
            .map(str::to_string)
            .unwrap_or_else(|| format!("area {}", k + 1));
        let mut literals = Vec::new();
        for (name, v) in obj_of(o, "literals")? {
            let c = names
                .iter()
                .position(|n| n == name)
                .ok_or_else(|| Unreadable(format!("{set}: unknown constraint {name:?}")))?;
            let want_in = match v.as_str() {
                Some("in") => true,
                Some("out") => false,
                _ => {
                    return Err(Unreadable(format!(
                        "{set}: literal must be \"in\" or \"out\""
                    )))
                }
            };
            literals.push((c, want_in));
        }
        let bound = |key: &str| -> Result<Option<(String, Interval)>, Unreadable> {
            match opt_str(o, key)? {
                None => Ok(None),
                Some(t) => Ok(Some((
                    t.to_string(),
                    decimal_enclosure(t).map_err(|e| format!("{set} {key}: {e}"))?,
                ))),
            }
        };
        let (inner, outer) = (bound("inner")?, bound("outer")?);
        let empty = literals.iter().any(|&(c, yes)| {
            literals
                .iter()
                .any(|&(d, yes2)| yes && !yes2 && texts[c] == texts[d])
        });
        areas.push(AreaClaim {
            set,
            literals,
            inner,
            outer,
            empty,
        });
    }
    let encoding = str_of(ev, "encoding")?;
    if encoding != "tree/1" {
        return Err(Unreadable(format!("unknown tree encoding {encoding:?}")));
    }
    let nodes = u64_of(ev, "nodes")?;
    let body = base64_decode(str_of(ev, "body")?).map_err(|e| format!("body: {e}"))?;
    let text_refs: Vec<&str> = cons
        .iter()
        .map(|c| as_obj(c, "a constraint").and_then(|o| str_of(o, "expr")))
        .collect::<Result<_, _>>()?;
    let factor = factor_table(&mut prog, &names, &text_refs)?;
    let empty = empty_evidence(ev, areas.len())?;
    // `scene/variant`, or the scene alone (a scene file has no variant).
    let scene = opt_str(st, "scene")?.unwrap_or("?");
    let claim = match opt_str(st, "variant")? {
        Some(v) => format!("paving {scene}/{v}: {} areas", areas.len()),
        None => format!("paving {scene}: {} areas", areas.len()),
    };
    Ok((
        Statement {
            prog,
            names,
            roots,
            factor,
            empty,
            domain,
            root_box,
            leaves,
            areas,
            nodes,
            body,
        },
        claim,
    ))
}

/// `evidence.empty` (optional): at most one emptiness tree per area.
fn empty_evidence(ev: &Obj, areas: usize) -> Result<Vec<EmptyEvidence>, Unreadable> {
    let Some(v) = ev.get("empty") else {
        return Ok(Vec::new());
    };
    let list = v
        .as_array()
        .ok_or_else(|| Unreadable("evidence empty must be an array".into()))?;
    let mut out: Vec<EmptyEvidence> = Vec::new();
    for e in list {
        let o = as_obj(e, "an emptiness tree")?;
        let area = u64_of(o, "area")?;
        let area = usize::try_from(area)
            .ok()
            .filter(|&a| a < areas)
            .ok_or_else(|| Unreadable(format!("emptiness tree of area {area}: no such area")))?;
        if out.iter().any(|x| x.area == area) {
            return Err(Unreadable(format!("area {area} has two emptiness trees")));
        }
        let what = format!("emptiness tree of area {area}");
        let null = serde_json::Value::Null;
        let pb = obj_of(o, "phase_box")?;
        let (t0, t1) = pair_of(pb.get("t").unwrap_or(&null), "phase_box t")?;
        let (w0, w1) = pair_of(pb.get("w").unwrap_or(&null), "phase_box w")?;
        let mut phase_box = [0.0; 4];
        for (slot, text) in phase_box.iter_mut().zip([t0, t1, w0, w1]) {
            *slot = parse_hex_f64(text, false).map_err(|e| format!("{what}: phase_box: {e}"))?;
        }
        let encoding = str_of(o, "encoding")?;
        if encoding != "empty/1" {
            return Err(Unreadable(format!(
                "{what}: unknown tree encoding {encoding:?}"
            )));
        }
        let nodes = u64_of(o, "nodes")?;
        let body = base64_decode(str_of(o, "body")?).map_err(|e| format!("{what}: body: {e}"))?;
        out.push(EmptyEvidence {
            area,
            phase_box,
            nodes,
            body,
        });
    }
    Ok(out)
}

pub fn check(root: &Obj) -> Result<Outcome, Unreadable> {
    let (st, claim) = parse(root)?;
    let mut checked = 0;
    let result = verify(&st, &mut checked);
    Ok(Outcome::of(result, claim, checked, "leaves"))
}

fn verify(st: &Statement, checked: &mut u64) -> Result<(), String> {
    // 1. The domain and R ⊂ D.
    let d: Vec<Interval> = ["t_lo", "t_hi", "w_lo", "w_hi"]
        .iter()
        .zip(st.domain)
        .map(|(what, s)| constant(&st.prog, s, &format!("domain {what}")))
        .collect::<Result<_, _>>()?;
    let r = st.root_box;
    for (axis, k) in [("t", 0), ("w", 2)] {
        if d[k].sup() >= d[k + 1].inf() {
            return Err(format!("domain {axis}: lo is not below hi"));
        }
        if r[k] >= r[k + 1] {
            return Err(format!("root_box {axis}: lo is not below hi"));
        }
        if r[k] < d[k].sup() || r[k + 1] > d[k + 1].inf() {
            return Err(format!(
                "root_box {axis} [{:e}, {:e}] is not inside the domain [{}, {}]",
                r[k],
                r[k + 1],
                d[k].sup(),
                d[k + 1].inf()
            ));
        }
    }
    let l = loosen_i;
    let area_d = l(l(d[1] - d[0]) * l(d[3] - d[2]));
    let area_r = l(l(iv(r[1], r[1]) - iv(r[0], r[0])) * l(iv(r[3], r[3]) - iv(r[2], r[2])));
    let uncovered = l(area_d - area_r);

    // 2.–3. Replay the tree and check every leaf.
    let nc = st.roots.len();
    let mut ev = LeafEval::new(&st.prog, st.roots.clone());
    let mut inner = vec![AreaSum::default(); st.areas.len()];
    let mut outer = vec![AreaSum::default(); st.areas.len()];
    let mut bits = BitReader::new(&st.body);
    let mut leaves = 0u64;
    let walked = walk(&mut bits, r, st.nodes, |b, bits, node| {
        leaves += 1;
        let labels = labels(bits, nc, node)?;
        let mask = (0..nc)
            .filter(|&c| labels[c] == IN || labels[c] == OUT)
            .fold(0usize, |m, c| m | 1 << c);
        let (t, w) = (iv(b[0], b[1]), iv(b[2], b[3]));
        if mask != 0 {
            ev.eval(t, w, mask);
            for (c, &l) in labels.iter().enumerate().take(nc) {
                if mask >> c & 1 == 0 {
                    continue;
                }
                let v = ev.value(c);
                let ok = holds(v, l == IN)
                    || holds(
                        monotone_bound(&st.prog, st.roots[c], t, w, l == IN),
                        l == IN,
                    )
                    || convex_holds(&st.prog, st.roots[c], t, w, l == IN);
                if !ok {
                    return Err(format!(
                        "leaf {leaves} [{:e}, {:e}] x [{:e}, {:e}], constraint {}: \
                         claimed {}, computed {}",
                        b[0],
                        b[1],
                        b[2],
                        b[3],
                        st.names[c],
                        if l == IN { "in" } else { "out" },
                        show(v)
                    ));
                }
            }
        }
        let la = LeafArea::of((b[0], b[1]), (b[2], b[3]));
        for (k, a) in st.areas.iter().enumerate() {
            let mut proved = true;
            let mut contradicted = false;
            for &(c, want_in) in &a.literals {
                let (yes, no) = if want_in { (IN, OUT) } else { (OUT, IN) };
                proved &= labels[c] == yes;
                contradicted |= labels[c] == no;
            }
            if proved {
                inner[k].add(&la);
            }
            if !contradicted {
                outer[k].add(&la);
            }
        }
        *checked += 1;
        Ok(())
    })?;
    if walked.nodes != st.nodes {
        return Err(format!(
            "the tree has {} nodes, claimed {}",
            walked.nodes, st.nodes
        ));
    }
    if walked.leaves != st.leaves {
        return Err(format!(
            "the tree has {} leaves, claimed {}",
            walked.leaves, st.leaves
        ));
    }

    // 4. Sets proved empty, leaf by leaf, on a phase box containing D.
    let mut proved_empty = vec![false; st.areas.len()];
    for e in &st.empty {
        let a = &st.areas[e.area];
        let what = format!("{} (emptiness tree)", a.set);
        let p = e.phase_box;
        for (axis, k) in [("t", 0), ("w", 2)] {
            if p[k] > d[k].inf() || p[k + 1] < d[k + 1].sup() {
                return Err(format!(
                    "{what}: phase_box {axis} [{:e}, {:e}] does not contain the domain [{:e}, {:e}]",
                    p[k],
                    p[k + 1],
                    d[k].inf(),
                    d[k + 1].sup()
                ));
            }
        }
        let reasons = Reasons {
            prog: &st.prog,
            names: &st.names,
            roots: &st.roots,
            factor: &st.factor,
            phase_box: p,
        };
        empty_tree(&reasons, &a.literals, e.nodes, &e.body, &what, checked)?;
        proved_empty[e.area] = true;
    }

    // 5. The areas.
    for (k, a) in st.areas.iter().enumerate() {
        let lo = inner[k].bounds().inf();
        let hi = if a.empty || proved_empty[k] {
            0.0
        } else {
            loosen_i(iv(outer[k].bounds().sup(), outer[k].bounds().sup()) + uncovered).sup()
        };
        if let Some((text, c)) = &a.inner {
            if c.sup() > lo {
                return Err(format!(
                    "{}: claimed inner {text} exceeds the certified inner bound {lo:e}",
                    a.set
                ));
            }
        }
        if let Some((text, c)) = &a.outer {
            if c.inf() < hi {
                return Err(format!(
                    "{}: claimed outer {text} is below the certified outer bound {hi:e}",
                    a.set
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval::defined;

    fn compiled(text: &str) -> (Program, u32) {
        let mut prog = Program::new(&["t", "w"]).unwrap();
        let root = prog.compile(text).unwrap();
        (prog, root)
    }

    fn natural(prog: &Program, root: u32, t: Interval, w: Interval) -> DecInterval {
        prog.value(&[DecInterval::new(t), DecInterval::new(w)], root)
    }

    // g = t² − t − w on [2, 3] × [0, 1]: by hand g ≥ 4 − 2 − 1 = 1 (∂g/∂t =
    // 2t − 1 ≥ 3, ∂g/∂w = −1), while the natural extension gives [0, 7].
    #[test]
    fn the_monotone_test_proves_what_natural_cannot() {
        let (prog, root) = compiled("t*t - t - w");
        let (t, w) = (iv(2.0, 3.0), iv(0.0, 1.0));
        assert!(!holds(natural(&prog, root, t, w), false));
        let m = monotone_bound(&prog, root, t, w, false);
        assert_eq!(m.interval().map(|i| i.inf()), Some(1.0));
        assert!(holds(m, false));
    }

    // The same box cannot be proved in (g(3, 0) = 6), and a box crossing
    // g = 0 (g(1, 1) = −1, g(2, 0) = 2) is proved neither in nor out.
    #[test]
    fn the_monotone_test_refuses_false_labels() {
        let (prog, root) = compiled("t*t - t - w");
        assert!(!holds(
            monotone_bound(&prog, root, iv(2.0, 3.0), iv(0.0, 1.0), true),
            true
        ));
        for want_in in [true, false] {
            let m = monotone_bound(&prog, root, iv(1.0, 2.0), iv(0.0, 1.0), want_in);
            assert!(!holds(m, want_in));
        }
    }

    // abs has no derivative at 0: with 2.5 inside [2, 3] the test does not
    // apply, although |t − 2.5| + t − w is monotone in w.
    #[test]
    fn no_monotone_test_where_a_derivative_does_not_exist() {
        let (prog, root) = compiled("abs(t - 2.5) + t - w");
        let m = monotone_bound(&prog, root, iv(2.0, 3.0), iv(0.0, 1.0), false);
        assert!(!defined(m));
        let (prog, root) = compiled("sqrt(t - 2) - w - 1");
        let m = monotone_bound(&prog, root, iv(2.0, 3.0), iv(0.0, 1.0), true);
        assert!(!defined(m));
    }

    // g = w² + w − 1 − t on [0, 0.01] × [−1.2, 0.6]: convex in w, so by hand
    // g ≤ max(g(0, −1.2), g(0, 0.6)) = max(−0.76, −0.04) < 0; natural gives
    // w·w ⊂ [−0.72, 1.44] and fails, and neither ∂g/∂w = 2w + 1 nor fixing
    // t at 0 helps the monotone test.
    #[test]
    fn the_convex_test_proves_what_monotone_cannot() {
        let (prog, root) = compiled("w*w + w - 1 - t");
        let (t, w) = (iv(0.0, 0.01), iv(-1.2, 0.6));
        assert!(!holds(natural(&prog, root, t, w), true));
        assert!(!holds(monotone_bound(&prog, root, t, w, true), true));
        assert!(convex_holds(&prog, root, t, w, true));
        // Concave: 2 − w² − w ≥ min(1.76, 1.04) > 0 on the same box.
        let (prog, root) = compiled("2 - w*w - w + t");
        assert!(!holds(natural(&prog, root, t, w), false));
        assert!(convex_holds(&prog, root, t, w, false));
    }

    // Each would be accepted by the ends alone: g(t, 0.7) = 0.19 − t > 0; a
    // concave 0.5 − w² is −0.5 at w = ±1 but 0.5 at 0; a convex w² − 0.5 is
    // 0.5 at the ends but −0.5 at 0; 0.5 − 2|w| is −1.5 at the ends but 0.5
    // at its kink, where |w| has no second derivative (it would read 0).
    #[test]
    fn the_convex_test_refuses_false_labels() {
        let t = iv(0.0, 0.01);
        let (prog, root) = compiled("w*w + w - 1 - t");
        assert!(!convex_holds(&prog, root, t, iv(-1.2, 0.7), true));
        let (prog, root) = compiled("0.5 - w*w + 0*t");
        assert!(!convex_holds(&prog, root, t, iv(-1.0, 1.0), true));
        let (prog, root) = compiled("w*w - 0.5 + 0*t");
        assert!(!convex_holds(&prog, root, t, iv(-1.0, 1.0), false));
        let (prog, root) = compiled("0.5 - 2*abs(w) + 0*t");
        assert!(!convex_holds(&prog, root, t, iv(-1.0, 1.0), true));
    }
}
