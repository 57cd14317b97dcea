//! A paving as a `paving` proof file: the statement (scene, parameters as
//! text, the constraints as expressions, the domain, the claimed areas) and
//! the tree in the compact `tree/1` encoding.

use super::confirm::{confirm_labels, Confirmed, StatedText};
use super::numbers::{decimal, hex, Round};
use super::params::encode_empty;
use super::statement::file_statement;
use crate::number::param::ParamSet;
use crate::pave::{Label, Node, Paving};
use crate::scene::{Cell, Domain, Scene, SceneId, Variant};
use serde_json::{json, Map, Value};

/// Significant digits of claimed area bounds.
const AREA_DIGITS: usize = 10;

/// What a paving proof is about, besides the paving itself.
pub struct PavingStatement<'a> {
    pub scene: &'a Scene,
    pub variant: Variant,
    pub params: &'a ParamSet,
    /// The true domain (for the part outside the root box) and its text.
    pub domain: &'a Domain,
    pub domain_text: [[String; 2]; 2],
    pub title: String,
}

fn label_bits(l: Label) -> u64 {
    match l {
        Label::Undecided => 0b00,
        Label::ProvedIn => 0b01,
        Label::ProvedOut => 0b10,
        Label::Undefined => 0b11,
    }
}

/// Appends bits most significant first.
#[derive(Default)]
pub(crate) struct BitWriter {
    bytes: Vec<u8>,
    used: u32,
}

impl BitWriter {
    pub(crate) fn push(&mut self, value: u64, bits: u32) {
        for i in (0..bits).rev() {
            if self.used.is_multiple_of(8) {
                self.bytes.push(0);
            }
            let bit = ((value >> i) & 1) as u8;
            let last = self.bytes.last_mut().expect("pushed above");
            *last |= bit << (7 - self.used % 8);
            self.used += 1;
        }
    }
    pub(crate) fn into_bytes(self) -> Vec<u8> {
        self.bytes
    }
}

/// The preorder tree in `tree/1` bits: leaf `0` + 2 bits per constraint,
/// θ-midpoint split `100`, θ̇-midpoint split `101`, split at an explicit
/// point `11` + axis bit + the point's 64 bits.
pub fn encode_tree(paving: &Paving) -> Vec<u8> {
    let mut w = BitWriter::default();
    for node in &paving.nodes {
        match *node {
            Node::Split(axis) => w.push(0b100 | u64::from(axis), 3),
            Node::SplitAt(axis, p) => {
                w.push(0b110 | u64::from(axis), 3);
                w.push(p.to_bits(), 64);
            }
            Node::Leaf(i) => {
                w.push(0, 1);
                for &l in paving.leaves[i as usize].labels.iter() {
                    w.push(label_bits(l), 2);
                }
            }
        }
    }
    w.into_bytes()
}

/// Standard base64 with padding (RFC 4648).
pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(A[((n >> (18 - 6 * i)) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// What `cell` asks of each region, by region name: `in` or `out`.
fn literals(cell: Cell) -> Value {
    let mut m = Map::new();
    for (region, l) in ["omega", "omega0"].into_iter().zip(cell.literals()) {
        if let Some(inside) = l {
            m.insert(region.into(), (if inside { "in" } else { "out" }).into());
        }
    }
    Value::Object(m)
}

/// The paving a proof of `paving` states: cut to the root box the loosest
/// checker it must convince finds inside the domain, with only the labels
/// that checker confirms on the stated text ([`confirm_labels`]).
pub fn stated_paving(st: &PavingStatement, paving: &Paving) -> Confirmed {
    let formulas = statement_formulas(st.scene, st.variant);
    confirm_labels(
        &StatedText {
            parameters: st
                .params
                .texts()
                .into_iter()
                .map(|(n, t)| (n.to_string(), t))
                .collect(),
            definitions: &formulas.definitions,
            constraints: [&formulas.omega, &formulas.omega0],
            domain: &st.domain_text,
        },
        paving,
    )
}

/// The proof file of a paving of Ω and Ω₀ (and the four cells), as
/// [`stated_paving`] gives it; how many labels that leaves undecided is in
/// `evidence.resolution.unconfirmed` (informational).
pub fn paving_proof(st: &PavingStatement, paving: &Paving) -> Value {
    let formulas = statement_formulas(st.scene, st.variant);
    let mut params = Map::new();
    for (name, text) in st.params.texts() {
        params.insert(name.to_string(), Value::String(text));
    }
    let confirmed = stated_paving(st, paving);
    let paving = &confirmed.paving;
    let uncovered = st
        .domain
        .area_outside([paving.root.theta, paving.root.theta_dot]);
    let mut empty = Vec::new();
    let areas: Vec<Value> = Cell::ALL
        .into_iter()
        .enumerate()
        .map(|(k, cell)| {
            let b = paving.area_bounds(&cell.spec(), uncovered);
            let tree = (!b.proved_empty)
                .then(|| emptiness_evidence(st, cell, k))
                .flatten();
            let (inner, outer) = match tree {
                Some(t) => {
                    empty.push(t);
                    ("0".to_string(), "0".to_string())
                }
                None => (
                    decimal(b.inner_area, AREA_DIGITS, Round::Down),
                    decimal(b.outer_area, AREA_DIGITS, Round::Up),
                ),
            };
            json!({
                "set": cell.name(),
                "literals": literals(cell),
                "inner": inner,
                "outer": outer,
            })
        })
        .collect();
    let r = paving.root;
    let mut proof = json!({
        "format": "detach-proof/1",
        "claim": "paving",
        "title": st.title,
        "producer": super::producer(),
        "statement": {
            "scene": st.scene.name(),
            "variant": st.scene.id().map(|_| st.variant.to_string()),
            "paper": st.scene.id().map(paper_reference),
            "parameters": params,
            "definitions": formulas.definitions.iter().map(|(n, e)| json!([n, e])).collect::<Vec<_>>(),
            "constraints": [
                { "name": "omega", "expr": formulas.omega, "meaning": formulas.meaning[0] },
                { "name": "omega0", "expr": formulas.omega0, "meaning": formulas.meaning[1] },
            ],
            "domain": {
                "t": st.domain_text[0],
                "w": st.domain_text[1],
            },
            "root_box": {
                "t": [hex(r.theta[0]), hex(r.theta[1])],
                "w": [hex(r.theta_dot[0]), hex(r.theta_dot[1])],
            },
            "leaves": paving.leaves.len(),
            "areas": areas,
        },
        "evidence": {
            "encoding": "tree/1",
            "nodes": paving.nodes.len(),
            "resolution": { "eps": paving.eps, "complete": paving.complete },
            "body": base64(&encode_tree(paving)),
        },
    });
    proof["evidence"]["resolution"]["unconfirmed"] = json!(confirmed.undecided);
    if !empty.is_empty() {
        proof["evidence"]["empty"] = Value::Array(empty);
    }
    // A scene file has one reading and no place in the paper.
    if st.scene.id().is_none() {
        if let Some(s) = proof["statement"].as_object_mut() {
            s.shift_remove("variant");
            s.shift_remove("paper");
        }
    }
    proof
}

/// The emptiness tree of area `k` (the set `cell`) when the set is proved
/// empty on the statement's domain: each leaf names a literal of the set
/// proved false on it, or a factor rule (`empty/1`, as a parameter atlas
/// states it), from a phase box containing the domain.
fn emptiness_evidence(st: &PavingStatement, cell: Cell, k: usize) -> Option<Value> {
    let (tree, reasons) = crate::params::empty_tree(st.scene, st.variant, st.domain, cell)?;
    let body = encode_empty(&tree, &reasons).ok()?;
    let p = crate::params::empty_root(st.domain);
    Some(json!({
        "area": k,
        "phase_box": {
            "t": [hex(p.theta[0]), hex(p.theta[1])],
            "w": [hex(p.theta_dot[0]), hex(p.theta_dot[1])],
        },
        "encoding": "empty/1",
        "nodes": tree.len(),
        "body": base64(&body),
    }))
}

/// The formulas a proof states: definitions, Ω and Ω₀ as `{expr < 0}`, and
/// what each constraint means.
pub struct StatementFormulas {
    pub definitions: Vec<(String, String)>,
    pub omega: String,
    pub omega0: String,
    pub meaning: [String; 2],
}

fn statement_formulas(scene: &Scene, variant: Variant) -> StatementFormulas {
    let f = scene.reading(variant);
    let s = file_statement(f);
    StatementFormulas {
        definitions: s.definitions,
        omega: s.omega,
        omega0: s.omega0,
        meaning: [
            format!("Ω: {}", f.regions[0].inequality.trim()),
            format!("Ω₀: {}", f.regions[1].inequality.trim()),
        ],
    }
}

fn paper_reference(id: SceneId) -> &'static str {
    match id {
        SceneId::ViscousDisc => "Example 1: Ω (1.10), Ω₀ (1.11)",
        SceneId::SmoothDisc => "§2: Ω = Ω₀ (2.7), (2.8)",
        SceneId::IceDisc => "§3: Ω (2.7), (2.8); Ω₀ (3.5)",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc4648_vectors() {
        // RFC 4648 §10 test vectors.
        for (raw, enc) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(raw.as_bytes()), enc);
        }
    }

    #[test]
    fn bits_are_packed_msb_first() {
        let mut w = BitWriter::default();
        w.push(0b101, 3);
        w.push(0b0, 1);
        w.push(0b1111, 4);
        w.push(0b1, 1);
        assert_eq!(w.into_bytes(), vec![0b1010_1111, 0b1000_0000]);
    }
}
