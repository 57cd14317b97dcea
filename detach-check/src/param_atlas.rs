//! The `parameter-atlas` claim: over each box of a parameter split tree,
//! each stated set is non-empty (a witness phase box), empty (a phase split
//! tree, one reason per leaf, encoding `empty/1`) or undecided.

use inari::Interval;

use super::empty::{empty_tree, factor_table, Reasons};
use super::encoding::{base64_decode, parse_hex_f64};
use super::eval::{parameter_enclosure, Program};
use super::json::{arr_of, as_obj, decls, obj_of, opt_str, pair_of, str_of, u64_of, Obj};
use super::leaf::proved;
use super::roots::constant;
use super::tree::{iv, show_box};
use super::{Outcome, Unreadable};
use serde_json::Value;

/// What is claimed of one set on one parameter box, with its evidence.
enum Status {
    /// A witness phase box `[t0, t1] × [w0, w1]`.
    Nonempty([f64; 4]),
    /// A phase split tree from the phase box: its node count and bits.
    Empty {
        nodes: u64,
        body: Vec<u8>,
    },
    Undecided,
}

/// A node of the parameter split tree, in preorder.
enum ParamNode {
    Split {
        axis: usize,
        at: f64,
    },
    /// One status per set.
    Leaf(Vec<Status>),
}

/// A set: its name and literals (constraint, wants in).
struct SetClaim {
    name: String,
    literals: Vec<(usize, bool)>,
}

struct Statement {
    prog: Program,
    names: Vec<String>,
    roots: Vec<u32>,
    /// `factor[j][i]`: the slot of the factor F when constraint j is
    /// constraint i's expression times or divided by F (FORMAT.md, "the
    /// factor form").
    factor: Vec<Vec<Option<u32>>>,
    domain: [u32; 4],
    /// The varying parameters and their root ranges.
    axes: Vec<(String, Interval)>,
    phase_box: [f64; 4],
    sets: Vec<SetClaim>,
    tree: Vec<ParamNode>,
}

/// The one status word of a leaf's entry for a set.
fn status_of(v: &Value, ev: &Value, what: &str) -> Result<Status, Unreadable> {
    let word = v
        .as_str()
        .ok_or_else(|| Unreadable(format!("{what}: a status must be a string")))?;
    let ev = as_obj(ev, &format!("{what}: evidence"))?;
    match word {
        "nonempty" => {
            let w = obj_of(ev, "witness")?;
            let null = Value::Null;
            let (t0, t1) = pair_of(w.get("t").unwrap_or(&null), "witness t")?;
            let (w0, w1) = pair_of(w.get("w").unwrap_or(&null), "witness w")?;
            let mut b = [0.0; 4];
            for (slot, text) in b.iter_mut().zip([t0, t1, w0, w1]) {
                *slot = parse_hex_f64(text, false).map_err(|e| format!("{what}: witness: {e}"))?;
            }
            Ok(Status::Nonempty(b))
        }
        "empty" => {
            let encoding = str_of(ev, "encoding")?;
            if encoding != "empty/1" {
                return Err(Unreadable(format!(
                    "{what}: unknown tree encoding {encoding:?}"
                )));
            }
            let nodes = u64_of(ev, "nodes")?;
            let body =
                base64_decode(str_of(ev, "body")?).map_err(|e| format!("{what}: body: {e}"))?;
            Ok(Status::Empty { nodes, body })
        }
        "undecided" => Ok(Status::Undecided),
        other => Err(Unreadable(format!("{what}: unknown status {other:?}"))),
    }
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
    let axes_v = arr_of(st, "axes")?;
    if axes_v.is_empty() || axes_v.len() > 2 {
        return Err(Unreadable("one or two axes are required".into()));
    }
    let mut axes: Vec<(String, Interval)> = Vec::new();
    for a in axes_v {
        let name = a
            .as_str()
            .ok_or_else(|| Unreadable("an axis must be a string".into()))?;
        let text = params
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, t)| t)
            .ok_or_else(|| Unreadable(format!("axis {name:?} is not a parameter")))?;
        if !text.starts_with('[') {
            return Err(Unreadable(format!(
                "axis {name:?} must be a parameter box [lo, hi]"
            )));
        }
        if axes.iter().any(|(n, _)| n == name) {
            return Err(Unreadable(format!("axis {name:?} is named twice")));
        }
        axes.push((name.to_string(), parameter_enclosure(text)?));
    }
    let cons = arr_of(st, "constraints")?;
    if cons.is_empty() || cons.len() > 4 {
        return Err(Unreadable("1 to 4 constraints are required".into()));
    }
    let mut names: Vec<String> = Vec::new();
    let mut texts: Vec<&str> = Vec::new();
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
        texts.push(str_of(o, "expr")?);
        roots.push(
            prog.compile(str_of(o, "expr")?)
                .map_err(|e| format!("constraint {name}: {e}"))?,
        );
    }
    let factor = factor_table(&mut prog, &names, &texts)?;
    let null = Value::Null;
    let dom = obj_of(st, "domain")?;
    let (t0, t1) = pair_of(dom.get("t").unwrap_or(&null), "domain t")?;
    let (w0, w1) = pair_of(dom.get("w").unwrap_or(&null), "domain w")?;
    let domain = [
        prog.compile_constant(t0)?,
        prog.compile_constant(t1)?,
        prog.compile_constant(w0)?,
        prog.compile_constant(w1)?,
    ];
    let pb = obj_of(st, "phase_box")?;
    let (pt0, pt1) = pair_of(pb.get("t").unwrap_or(&null), "phase_box t")?;
    let (pw0, pw1) = pair_of(pb.get("w").unwrap_or(&null), "phase_box w")?;
    let mut phase_box = [0.0; 4];
    for (slot, text) in phase_box.iter_mut().zip([pt0, pt1, pw0, pw1]) {
        *slot = parse_hex_f64(text, false).map_err(|e| format!("phase_box: {e}"))?;
    }
    let sets_v = arr_of(st, "sets")?;
    if sets_v.is_empty() {
        return Err(Unreadable("at least one set is required".into()));
    }
    let mut sets = Vec::new();
    for s in sets_v {
        let o = as_obj(s, "a set")?;
        let name = str_of(o, "set")?.to_string();
        let mut literals = Vec::new();
        for (c, v) in obj_of(o, "literals")? {
            let k = names
                .iter()
                .position(|n| n == c)
                .ok_or_else(|| Unreadable(format!("{name}: unknown constraint {c:?}")))?;
            let want_in = match v.as_str() {
                Some("in") => true,
                Some("out") => false,
                _ => {
                    return Err(Unreadable(format!(
                        "{name}: literal must be \"in\" or \"out\""
                    )))
                }
            };
            literals.push((k, want_in));
        }
        sets.push(SetClaim { name, literals });
    }
    let tree_v = arr_of(st, "tree")?;
    let ev_leaves = arr_of(ev, "leaves")?;
    let mut tree = Vec::with_capacity(tree_v.len());
    let mut leaf = 0usize;
    for (k, n) in tree_v.iter().enumerate() {
        let o = as_obj(n, "a tree node")?;
        let node = match (o.get("split"), o.get("leaf")) {
            (Some(_), None) => {
                let name = str_of(o, "split")?;
                let axis = axes.iter().position(|(a, _)| a == name).ok_or_else(|| {
                    Unreadable(format!("tree node {}: {name:?} is not an axis", k + 1))
                })?;
                let at = parse_hex_f64(str_of(o, "at")?, false)
                    .map_err(|e| format!("tree node {}: {e}", k + 1))?;
                ParamNode::Split { axis, at }
            }
            (None, Some(words)) => {
                let what = format!("box {}", leaf + 1);
                let words = words
                    .as_array()
                    .ok_or_else(|| Unreadable(format!("{what}: \"leaf\" must be an array")))?;
                let evs = ev_leaves
                    .get(leaf)
                    .and_then(Value::as_array)
                    .ok_or_else(|| {
                        Unreadable(format!("{what}: no array of evidence in \"leaves\""))
                    })?;
                if words.len() != sets.len() || evs.len() != sets.len() {
                    return Err(Unreadable(format!(
                        "{what}: one status and one evidence per set are required"
                    )));
                }
                let statuses = words
                    .iter()
                    .zip(evs)
                    .zip(&sets)
                    .map(|((w, e), s)| status_of(w, e, &format!("{what}, {}", s.name)))
                    .collect::<Result<Vec<_>, _>>()?;
                leaf += 1;
                ParamNode::Leaf(statuses)
            }
            _ => {
                return Err(Unreadable(format!(
                    "tree node {}: exactly one of \"split\" and \"leaf\" is required",
                    k + 1
                )))
            }
        };
        tree.push(node);
    }
    if leaf != ev_leaves.len() {
        return Err(Unreadable(format!(
            "{} leaves in the tree, {} entries of evidence",
            leaf,
            ev_leaves.len()
        )));
    }
    let scene = opt_str(st, "scene")?.unwrap_or("?");
    let claim = format!("parameter-atlas {scene}: {leaf} boxes, {} sets", sets.len());
    Ok((
        Statement {
            prog,
            names,
            roots,
            factor,
            domain,
            axes,
            phase_box,
            sets,
            tree,
        },
        claim,
    ))
}

pub fn check(root: &Obj) -> Result<Outcome, Unreadable> {
    let (mut st, claim) = parse(root)?;
    let mut checked = 0;
    let result = verify(&mut st, &mut checked);
    Ok(Outcome::of(result, claim, checked, "leaves"))
}

fn verify(st: &mut Statement, checked: &mut u64) -> Result<(), String> {
    // 1. The domain, and D inside the phase box.
    let d: Vec<Interval> = ["t_lo", "t_hi", "w_lo", "w_hi"]
        .iter()
        .zip(st.domain)
        .map(|(what, s)| constant(&st.prog, s, &format!("domain {what}")))
        .collect::<Result<_, _>>()?;
    let p = st.phase_box;
    for (axis, k) in [("t", 0), ("w", 2)] {
        if d[k].sup() >= d[k + 1].inf() {
            return Err(format!("domain {axis}: lo is not below hi"));
        }
        if p[k] > d[k].inf() || p[k + 1] < d[k + 1].sup() {
            return Err(format!(
                "phase_box {axis} [{:e}, {:e}] does not contain the domain [{:e}, {:e}]",
                p[k],
                p[k + 1],
                d[k].inf(),
                d[k + 1].sup()
            ));
        }
    }

    // 2. Replay the parameter tree; check each leaf's statuses.
    let root: Vec<[f64; 2]> = st.axes.iter().map(|(_, x)| [x.inf(), x.sup()]).collect();
    let mut stack = vec![root];
    let mut leaf = 0usize;
    let tree = std::mem::take(&mut st.tree);
    for (k, node) in tree.iter().enumerate() {
        let b = stack
            .pop()
            .ok_or_else(|| format!("tree node {} follows a complete tree", k + 1))?;
        match node {
            ParamNode::Split { axis, at } => {
                let [lo, hi] = b[*axis];
                if !(lo < *at && *at < hi) {
                    return Err(format!(
                        "tree node {}: split point {at:e} of {} is not inside ({lo:e}, {hi:e})",
                        k + 1,
                        st.axes[*axis].0
                    ));
                }
                let (mut lower, mut upper) = (b.clone(), b);
                lower[*axis][1] = *at;
                upper[*axis][0] = *at;
                stack.push(upper);
                stack.push(lower);
            }
            ParamNode::Leaf(statuses) => {
                leaf += 1;
                let names: Vec<String> = st.axes.iter().map(|(n, _)| n.clone()).collect();
                let mut what = format!("box {leaf} (");
                for (n, [lo, hi]) in names.iter().zip(&b) {
                    st.prog.set_parameter(n, iv(*lo, *hi))?;
                    what.push_str(&format!("{n} [{lo:e}, {hi:e}] "));
                }
                what.pop();
                what.push(')');
                for (set, status) in st.sets.iter().zip(statuses) {
                    let what = format!("{what}, {}", set.name);
                    match status {
                        Status::Nonempty(w) => witness(st, &d, set, w, &what)?,
                        Status::Empty { nodes, body } => {
                            let reasons = Reasons {
                                prog: &st.prog,
                                names: &st.names,
                                roots: &st.roots,
                                factor: &st.factor,
                                phase_box: st.phase_box,
                            };
                            empty_tree(&reasons, &set.literals, *nodes, body, &what, checked)?
                        }
                        Status::Undecided => {}
                    }
                    *checked += 1;
                }
            }
        }
    }
    if !stack.is_empty() {
        return Err(format!(
            "the tree ends before every box has its leaf ({} left)",
            stack.len()
        ));
    }
    Ok(())
}

/// A witness: inside the domain, every literal of the set proved on it.
fn witness(
    st: &Statement,
    d: &[Interval],
    set: &SetClaim,
    w: &[f64; 4],
    what: &str,
) -> Result<(), String> {
    for (axis, k) in [("t", 0), ("w", 2)] {
        if w[k] >= w[k + 1] || w[k] < d[k].sup() || w[k + 1] > d[k + 1].inf() {
            return Err(format!(
                "{what}: witness {} is not a box inside the domain along {axis}",
                show_box(w)
            ));
        }
    }
    let (t, x) = (iv(w[0], w[1]), iv(w[2], w[3]));
    for &(c, want_in) in &set.literals {
        if !proved(&st.prog, st.roots[c], t, x, want_in) {
            return Err(format!(
                "{what}: witness {}, constraint {}: {} is not proved",
                show_box(w),
                st.names[c],
                if want_in { "in" } else { "out" }
            ));
        }
    }
    Ok(())
}
