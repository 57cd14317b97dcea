//! What a paving proof states, confirmed on its own text by the loosest
//! checker it must convince.
//!
//! A paver proves labels on its own form of the constraints: the paper's
//! scenes in Rust, a scene file through the coefficients `c₂θ̇² + c₁θ̇ + c₀`
//! of its regions. The proof states them as text ([`super::statement`]),
//! and a checker evaluates that text: `U/V` as a quotient, not as
//! `(c₂/V)θ̇² + (c₀/V)`, with its own rounding. A label proved with no room
//! to spare (a contracted box ending ulps from a boundary, a derivative
//! enclosure ending at 0) can then fail for a correct checker. So every
//! decided label is decided again from the stated text by the checker's own
//! leaf test (natural value, monotone test, convex test; FORMAT.md, "Claim
//! `paving`"), run as the loosest checker the proof must convince
//! ([`LOOSEST`]), and a label it does not confirm is stated undecided. The
//! root box is kept inside that checker's enclosures of the domain's ends
//! ([`super::clip`]). A label is never added here.

use super::clip::clipped_to;
use crate::check::{with_looseness, Looseness, StatedConstraints};
use crate::pave::{Label, Paving, PhaseBox};
use inari::Interval;

/// The rounding labels are confirmed under: every basic operation 2 ulps
/// and every function 4 ulps looser than tightest at each end.
pub const LOOSEST: Looseness = Looseness {
    basic: 2,
    exact_too: false,
    functions: 4,
};

/// A paving proof's constraints and domain as its statement gives them.
pub struct StatedText<'a> {
    pub parameters: Vec<(String, String)>,
    pub definitions: &'a [(String, String)],
    /// Ω and Ω₀ as `{expr < 0}`.
    pub constraints: [&'a str; 2],
    /// `[[t lo, t hi], [w lo, w hi]]`.
    pub domain: &'a [[String; 2]; 2],
}

/// A paving whose root box and decided labels the stated text confirms.
pub struct Confirmed {
    pub paving: Paving,
    /// Labels the paver proved that the stated text does not confirm (now
    /// undecided), counted per leaf and constraint.
    pub undecided: usize,
}

/// `paving` as its proof states it: cut to the root box the loosest checker
/// finds inside the domain, with every decided label that the text does not
/// confirm there made undecided.
pub fn confirm_labels(text: &StatedText, paving: &Paving) -> Confirmed {
    let constraints = text.constraints.map(String::from);
    // The paver accepted this text, and the checker reads the same
    // language; should it refuse it anyway, no label is confirmed.
    let Ok(mut stated) =
        StatedConstraints::compile(&text.parameters, text.definitions, &constraints)
    else {
        let mut out = paving.clone();
        let mut undecided = 0;
        for leaf in &mut out.leaves {
            for l in leaf.labels.iter_mut().take(2) {
                if l.is_decided() {
                    *l = Label::Undecided;
                    undecided += 1;
                }
            }
        }
        return Confirmed {
            paving: out,
            undecided,
        };
    };
    with_looseness(LOOSEST, || {
        let root = root_inside(&mut stated, text.domain, paving.root);
        let mut out = clipped_to(paving, root);
        let undecided = confirm_on(&stated, paving, &mut out);
        Confirmed {
            paving: out,
            undecided,
        }
    })
}

/// `root` cut, on each axis, to the current checker's enclosures of the
/// domain's ends, `[sup lo, inf hi]`; an axis where that leaves nothing (a
/// window a few ulps wide at an inexact end) keeps its range.
fn root_inside(
    stated: &mut StatedConstraints,
    domain: &[[String; 2]; 2],
    root: PhaseBox,
) -> PhaseBox {
    let mut r = [root.theta, root.theta_dot];
    for (axis, ends) in domain.iter().enumerate() {
        let (Ok(lo), Ok(hi)) = (stated.constant(&ends[0]), stated.constant(&ends[1])) else {
            continue;
        };
        let cut = [r[axis][0].max(lo.sup()), r[axis][1].min(hi.inf())];
        if cut[0] < cut[1] {
            r[axis] = cut;
        }
    }
    PhaseBox {
        theta: r[0],
        theta_dot: r[1],
    }
}

/// Makes undecided each decided label of `out` (a clipped copy of `paving`)
/// that `stated` does not confirm on its leaf; returns how many.
fn confirm_on(stated: &StatedConstraints, paving: &Paving, out: &mut Paving) -> usize {
    let mut undecided = 0;
    let n = out.names.len().min(2);
    for leaf in &mut out.leaves {
        let b = leaf.bx;
        let iv = |r: [f64; 2]| Interval::try_from((r[0], r[1])).unwrap_or(Interval::ENTIRE);
        let (t, w) = (iv(b.theta), iv(b.theta_dot));
        for c in 0..n {
            if paving.same_as.get(c).copied().flatten().is_some() {
                continue;
            }
            let want_in = match leaf.labels[c] {
                Label::ProvedIn => true,
                Label::ProvedOut => false,
                _ => continue,
            };
            if !stated.label_holds(c, t, w, want_in) {
                leaf.labels[c] = Label::Undecided;
                undecided += 1;
            }
        }
        for c in 0..n {
            if let Some(Some(j)) = paving.same_as.get(c) {
                leaf.labels[c] = leaf.labels[*j];
            }
        }
    }
    undecided
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pave::{pave_scene, PaveOptions};
    use crate::scene::{FileScene, Scene, Variant};

    /// `paving`'s labels confirmed on `f`'s text, as its proof states it.
    fn confirm_file(f: &FileScene, paving: &Paving) -> Confirmed {
        let st = super::super::statement::file_statement(f);
        let text = StatedText {
            parameters: f
                .params
                .texts()
                .into_iter()
                .map(|(n, t)| (n.to_string(), t))
                .collect(),
            definitions: &st.definitions,
            constraints: [&st.omega, &st.omega0],
            domain: &f.domain_text,
        };
        confirm_labels(&text, paving)
    }

    /// Labels the stated text cannot confirm are dropped, and only those: a
    /// paving of one region relabelled as the other keeps the leaves where
    /// both agree. Ω = {θ̇ < 0} paved, then stated as Ω = {θ̇ > 0}: every
    /// decided label is refuted, so none survives.
    #[test]
    fn a_label_the_text_refutes_is_not_stated() {
        let scene = |omega: &str| {
            let text = format!(
                "name = \"x\"\n[domain]\ntheta = [\"0\", \"1\"]\ntheta_dot = [\"-1\", \"1\"]\n\
                 [regions]\nomega = \"{omega}\"\n"
            );
            FileScene::parse(&text, &[]).unwrap()
        };
        let below = scene("theta_dot + 0.25 < 0");
        let above = scene("theta_dot + 0.25 > 0");
        let opts = PaveOptions {
            eps: 1.0 / 16.0,
            ..PaveOptions::default()
        };
        let s = Scene::File(Box::new(below.clone()));
        let paving = pave_scene(&s, Variant::Derived, opts, |_, _, _| {}).unwrap();
        let decided = paving
            .leaves
            .iter()
            .filter(|l| l.labels[0].is_decided())
            .count();
        assert!(decided > 0);
        let same = confirm_file(&below, &paving);
        assert_eq!(same.undecided, 0);
        let other = confirm_file(&above, &paving);
        assert_eq!(other.undecided, decided);
        assert!(other
            .paving
            .leaves
            .iter()
            .all(|l| !l.labels[0].is_decided()));
    }
}
