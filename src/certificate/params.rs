//! A parameter atlas as a `parameter-atlas` proof file: the scene's text
//! with the varying parameters as boxes, the sets, the parameter split tree
//! with a status per box and set, and per status its evidence — a witness
//! box, or a phase split tree (encoding `empty/1`) with one reason per leaf.
//!
//! The writer states what the prover found; it proves nothing itself. The
//! prover's labels must hold for the expressions stated here (the author's
//! text of the scene's file, for a paper scene the file of its reading) as a
//! checker evaluates them, with the slack of `proofs/FORMAT.md`, "Accuracy".

use super::numbers::hex;
use super::paving::{base64, BitWriter};
use super::statement::in_proof_names;
use crate::number::param::ParamSet;
use crate::params::model::{EmptyReason, ParamAtlas, ParamNode, SetStatus};
use crate::pave::Node;
use crate::scene::{Cell, Scene, Variant};
use serde_json::{json, Map, Value};

/// What a parameter-atlas proof is about, besides the atlas itself.
pub struct ParamAtlasStatement<'a> {
    /// The scene; its domain, enclosed with the parameters it was built
    /// with, must be the domain for every parameter of the atlas's box.
    pub scene: &'a Scene,
    /// The reading of a paper scene (ignored for a scene file).
    pub variant: Variant,
    /// The parameters as given; the axes' texts give way to their ranges.
    pub params: &'a ParamSet,
    pub title: String,
}

/// The box every emptiness tree starts from, as the prover paves it
/// ([`crate::params::empty_root`]).
pub use crate::params::empty_root as phase_root;

/// Definitions, Ω and Ω₀ as the statement gives them.
fn formulas(scene: &Scene, variant: Variant) -> (Vec<(String, String)>, [String; 2]) {
    let f = scene.reading(variant);
    (
        f.definitions
            .iter()
            .map(|(n, e)| (n.clone(), in_proof_names(e)))
            .collect(),
        [0, 1].map(|i| in_proof_names(&f.regions[i].expr)),
    )
}

/// The literals of a standard set by its proof-file name.
fn literals(set: &str) -> Result<Value, String> {
    let cell = set.parse::<Cell>().map_err(|e| e.to_string())?;
    let mut lits = Map::new();
    for (name, want) in ["omega", "omega0"].iter().zip(cell.literals()) {
        if let Some(want_in) = want {
            let word = if want_in { "in" } else { "out" };
            lits.insert(name.to_string(), Value::String(word.into()));
        }
    }
    Ok(Value::Object(lits))
}

/// Constraint indices fit the two constraints Ω, Ω₀.
fn constraint_bits(c: usize) -> Result<u64, String> {
    if c < 2 {
        Ok(c as u64)
    } else {
        Err(format!("constraint {c} does not exist (Ω is 0, Ω₀ is 1)"))
    }
}

/// An emptiness tree in `empty/1` bits: the splits as in `tree/1`; a leaf
/// `0`, then its reason: `0` and 2 bits of the constraint (a literal), or
/// `1`, 2 bits each of the constraint and the other, and the factor's sign
/// (`1` positive).
pub(crate) fn encode_empty(tree: &[Node], reasons: &[EmptyReason]) -> Result<Vec<u8>, String> {
    let mut w = BitWriter::default();
    let mut leaves = 0;
    for node in tree {
        match *node {
            Node::Split(axis) => w.push(0b100 | u64::from(axis), 3),
            Node::SplitAt(axis, p) => {
                w.push(0b110 | u64::from(axis), 3);
                w.push(p.to_bits(), 64);
            }
            Node::Leaf(i) => {
                leaves += 1;
                w.push(0, 1);
                match reasons.get(i as usize) {
                    Some(EmptyReason::Literal { constraint }) => {
                        w.push(0, 1);
                        w.push(constraint_bits(*constraint)?, 2);
                    }
                    Some(EmptyReason::Factor {
                        constraint,
                        other,
                        positive,
                    }) => {
                        w.push(1, 1);
                        w.push(constraint_bits(*constraint)?, 2);
                        w.push(constraint_bits(*other)?, 2);
                        w.push(u64::from(*positive), 1);
                    }
                    // The same expression is itself times the factor 1, positive.
                    Some(EmptyReason::SameConstraint { constraint, other }) => {
                        w.push(1, 1);
                        w.push(constraint_bits(*constraint)?, 2);
                        w.push(constraint_bits(*other)?, 2);
                        w.push(1, 1);
                    }
                    None => return Err(format!("leaf {i} of an emptiness tree has no reason")),
                }
            }
        }
    }
    if leaves != reasons.len() {
        return Err(format!(
            "an emptiness tree has {leaves} leaves and {} reasons",
            reasons.len()
        ));
    }
    Ok(w.into_bytes())
}

fn hex_pair(x: [f64; 2]) -> Value {
    json!([hex(x[0]), hex(x[1])])
}

/// A status's word in the statement and its evidence.
fn status(s: &SetStatus) -> Result<(&'static str, Value), String> {
    Ok(match s {
        SetStatus::Nonempty { witness } => (
            "nonempty",
            json!({ "witness": {
                "t": hex_pair(witness.theta),
                "w": hex_pair(witness.theta_dot),
            } }),
        ),
        SetStatus::Empty { tree, reasons } => (
            "empty",
            json!({
                "encoding": "empty/1",
                "nodes": tree.len(),
                "body": base64(&encode_empty(tree, reasons)?),
            }),
        ),
        SetStatus::Undecided { reason } => ("undecided", json!({ "reason": reason })),
    })
}

/// The proof file of a parameter atlas; an error when the atlas does not
/// fit the scene (an axis that is no parameter, an unknown set, a leaf or a
/// reason missing).
pub fn param_atlas_proof(st: &ParamAtlasStatement, atlas: &ParamAtlas) -> Result<Value, String> {
    let (definitions, [omega, omega0]) = formulas(st.scene, st.variant);
    let texts = st.params.texts();
    if atlas.axes.is_empty() || atlas.axes.len() > 2 {
        return Err("an atlas varies one or two parameters".into());
    }
    let mut params = Map::new();
    for (name, text) in texts.iter() {
        let value = match atlas.axes.iter().find(|a| a.name == *name) {
            Some(a) => json!([a.lo, a.hi]),
            None => Value::String(text.clone()),
        };
        params.insert(name.to_string(), value);
    }
    for a in &atlas.axes {
        if !texts.iter().any(|(n, _)| *n == a.name) {
            return Err(format!("`{}` is not a parameter of the scene", a.name));
        }
    }
    let sets = atlas
        .sets
        .iter()
        .map(|s| Ok(json!({ "set": s, "literals": literals(s)? })))
        .collect::<Result<Vec<_>, String>>()?;
    let mut tree = Vec::with_capacity(atlas.tree.len());
    let mut evidence = Vec::new();
    for node in &atlas.tree {
        match *node {
            ParamNode::Split { axis, at } => {
                let a = atlas
                    .axes
                    .get(usize::from(axis))
                    .ok_or_else(|| format!("a split along axis {axis}, which does not exist"))?;
                tree.push(json!({ "split": a.name, "at": hex(at) }));
            }
            ParamNode::Leaf(i) => {
                let leaf = atlas
                    .leaves
                    .get(i as usize)
                    .ok_or_else(|| format!("parameter leaf {i} does not exist"))?;
                if leaf.sets.len() != atlas.sets.len() {
                    return Err(format!("parameter leaf {i} has not one status per set"));
                }
                let (words, evs): (Vec<_>, Vec<_>) = leaf
                    .sets
                    .iter()
                    .map(status)
                    .collect::<Result<Vec<_>, String>>()?
                    .into_iter()
                    .unzip();
                tree.push(json!({ "leaf": words }));
                evidence.push(Value::Array(evs));
            }
        }
    }
    let pb = phase_root(&st.scene.domain());
    let domain = st
        .scene
        .domain_text()
        .map(|ends| ends.map(|e| in_proof_names(&e)));
    let mut proof = json!({
        "format": "detach-proof/1",
        "claim": "parameter-atlas",
        "title": st.title,
        "producer": super::producer(),
        "statement": {
            "scene": st.scene.name(),
            "variant": st.scene.id().map(|_| st.variant.to_string()),
            "parameters": params,
            "axes": atlas.axes.iter().map(|a| a.name.clone()).collect::<Vec<_>>(),
            "definitions": definitions.iter().map(|(n, e)| json!([n, e])).collect::<Vec<_>>(),
            "constraints": [
                { "name": "omega", "expr": omega, "meaning": "Ω" },
                { "name": "omega0", "expr": omega0, "meaning": "Ω₀" },
            ],
            "domain": { "t": domain[0], "w": domain[1] },
            "phase_box": { "t": hex_pair(pb.theta), "w": hex_pair(pb.theta_dot) },
            "sets": sets,
            "tree": tree,
        },
        "evidence": { "leaves": evidence },
    });
    // A scene file has one reading.
    if st.scene.id().is_none() {
        if let Some(s) = proof["statement"].as_object_mut() {
            s.shift_remove("variant");
        }
    }
    Ok(proof)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_variables_are_renamed_token_by_token() {
        assert_eq!(
            in_proof_names("l*sin(theta)*theta_dot^2 - 2e5*theta_dots + thetas"),
            "l*sin(t)*w^2 - 2e5*theta_dots + thetas"
        );
        assert_eq!(in_proof_names("1e-3*theta"), "1e-3*t");
    }

    #[test]
    fn empty_trees_encode_reasons_after_the_leaf_bit() {
        // Split θ at the midpoint (100), leaf with literal 1 (0 0 01), leaf
        // with factor 1 over 0, positive (0 1 01 00 1): 100 0001 0101001.
        let tree = [Node::Split(0), Node::Leaf(0), Node::Leaf(1)];
        let reasons = [
            EmptyReason::Literal { constraint: 1 },
            EmptyReason::Factor {
                constraint: 1,
                other: 0,
                positive: true,
            },
        ];
        let bits = encode_empty(&tree, &reasons).unwrap();
        assert_eq!(bits, vec![0b1000_0010, 0b1010_0100]);
        assert!(encode_empty(&tree, &reasons[..1]).is_err());
        let bad = [EmptyReason::Literal { constraint: 2 }];
        assert!(encode_empty(&[Node::Leaf(0)], &bad).is_err());
    }
}
