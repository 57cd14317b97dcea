//! Certified parameter atlases: where in a box of one or two parameters
//! each of Ω, Ω₀ and the four cells is non-empty, empty, or undecided.
//!
//! One stage per module: [`family`] rebuilds a scene with parameters as
//! intervals, [`mod@decide`] proves one set's status on one parameter box,
//! [`mod@search`] bisects the parameter box where a status is undecided, and
//! [`report`] writes the JSON, the 1-D thresholds and the join of shards.
//! [`model`] is what is proved, as the proof writer states it.

pub mod decide;
pub mod family;
pub mod model;
pub mod report;
pub mod search;

pub use decide::{decide, empty_root, DecideOptions, Regions};
pub use family::{Family, Source};
pub use search::{search, AtlasRun, SearchOptions, Shard};

use crate::scene::Cell;
use crate::scene::{Scene, Variant};

/// Whether `cell` is proved empty on the scene's whole domain at its
/// parameters (a phase paving where every leaf misses it, as an atlas's
/// empty status): what `pave`, `atlas` and `area` report as exactly empty.
pub fn proved_empty(scene: &Scene, variant: Variant, cell: Cell) -> bool {
    empty_tree(scene, variant, &scene.domain(), cell).is_some()
}

/// The tree that proves `cell` empty on `domain` at the scene's parameters,
/// within the budget `pave`, `atlas` and `area` allow it, if there is one.
pub fn empty_tree(
    scene: &Scene,
    variant: Variant,
    domain: &crate::scene::Domain,
    cell: Cell,
) -> Option<(Vec<crate::pave::Node>, Vec<model::EmptyReason>)> {
    let opts = DecideOptions {
        line_boxes: 0,
        witness_boxes: 0,
        empty_leaves: 20_000,
    };
    decide::empty_tree(scene, variant, domain, cell, opts)
}
