//! What a parameter atlas proves, per parameter box and set: the data that
//! the prover (`crate::params`) produces and the proof writer
//! (`crate::certificate::params`) states.

use crate::pave::{Node, PhaseBox};

/// A parameter that varies over the atlas, its range as the user's decimal text.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamAxis {
    pub name: String,
    pub lo: String,
    pub hi: String,
}

/// One node of the parameter split tree, in preorder.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ParamNode {
    /// Split along axis `axis` at the exact double `at`, strictly inside the
    /// box; the lower subtree, then the upper one, follow.
    Split { axis: u8, at: f64 },
    /// A leaf: index into [`ParamAtlas::leaves`].
    Leaf(u32),
}

/// Why a set is empty on one phase leaf, for every parameter of the box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EmptyReason {
    /// The set asks a sign of constraint `constraint` (`g < 0` for "in",
    /// `g ≥ 0` for "out"), and the enclosure of `g` over the leaf (and the
    /// parameter box) proves the opposite sign.
    Literal { constraint: usize },
    /// Constraint `constraint` is written as constraint `other`'s expression
    /// divided or multiplied by a factor free of θ̇, whose sign is proved on
    /// the leaf (`positive`): the two constraints then have the same
    /// (positive factor) or opposite (negative factor) sign at every point,
    /// which contradicts the signs the set asks of them.
    Factor {
        constraint: usize,
        other: usize,
        positive: bool,
    },
    /// Constraints `constraint` and `other` are the same expression (the
    /// same function), and the set asks opposite signs of them. A proof
    /// states it as a factor rule with the factor 1.
    SameConstraint { constraint: usize, other: usize },
}

/// What is proved about one set on one parameter box.
#[derive(Clone, Debug, PartialEq)]
pub enum SetStatus {
    /// Every literal of the set is proved on `witness` × the parameter box.
    Nonempty { witness: PhaseBox },
    /// A phase split tree from the scene's domain (preorder, as a paving's
    /// `tree`), one reason per leaf in leaf order: the set misses every leaf.
    Empty {
        tree: Vec<Node>,
        reasons: Vec<EmptyReason>,
    },
    /// Neither could be proved; the reason in words.
    Undecided { reason: String },
}

/// One leaf of the parameter split tree.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamLeaf {
    /// Per axis, the box's ends: the root's ends are the decimal text's
    /// enclosures' outer ends, inner ends are the exact split points.
    pub bounds: Vec<[f64; 2]>,
    /// One status per set of [`ParamAtlas::sets`], in that order.
    pub sets: Vec<SetStatus>,
}

/// A certified parameter atlas of one scene.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamAtlas {
    /// The one or two parameters that vary; the others keep the scene's values.
    pub axes: Vec<ParamAxis>,
    /// The sets decided, by their proof-file names (`omega`, `omega0`,
    /// `omega_and_omega0`, `not_omega_and_not_omega0`,
    /// `not_omega_and_omega0`, `omega_and_not_omega0`).
    pub sets: Vec<String>,
    pub tree: Vec<ParamNode>,
    pub leaves: Vec<ParamLeaf>,
}
