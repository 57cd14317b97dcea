//! The labels a scene file's proof states, confirmed on the author's text.
//!
//! A scene file whose regions are quadratic in θ̇ is paved through its
//! coefficients `c₂θ̇² + c₁θ̇ + c₀`, while its proof states the regions as
//! written ([`super::statement`]), and a checker evaluates that text: `U/V`
//! as a quotient, not as `(c₂/V)θ̇² + (c₀/V)`. The two forms enclose the same
//! function differently. So every decided label is decided again from the
//! stated text by the checker's own leaf test (natural value, monotone test,
//! convex test; FORMAT.md, "Claim `paving`"), run as the loosest checker the
//! proof must convince ([`LOOSEST`]), and a label it does not confirm is
//! stated undecided. A label is never added here: each one stated was proved
//! by the paver and is confirmed by the checker's derivation, with rounding
//! looser than any checker FORMAT.md's "Accuracy" allows and than the 2 ulps
//! per operation the committed proofs are held to.

use crate::check::{with_looseness, Looseness, StatedConstraints};
use crate::pave::{Label, Paving};
use crate::scene::FileScene;
use inari::Interval;

/// The rounding labels are confirmed under: every basic operation 2 ulps
/// and every function 4 ulps looser than tightest at each end.
pub const LOOSEST: Looseness = Looseness {
    basic: 2,
    exact_too: false,
    functions: 4,
};

/// A paving whose decided labels the stated text confirms.
pub struct Confirmed {
    pub paving: Paving,
    /// Labels the paver proved that the stated text does not confirm (now
    /// undecided), counted per leaf and constraint.
    pub undecided: usize,
}

/// `paving` of `file`'s two regions with every decided label that the
/// regions as written do not confirm made undecided.
pub fn confirm_labels(file: &FileScene, paving: &Paving) -> Confirmed {
    let st = super::statement::file_statement(file);
    let params: Vec<(String, String)> = file
        .params
        .texts()
        .into_iter()
        .map(|(n, t)| (n.to_string(), t))
        .collect();
    let mut out = paving.clone();
    // The scene compiler accepted this text, and the checker reads the same
    // language; should it refuse it anyway, no label is confirmed.
    let Ok(stated) = StatedConstraints::compile(&params, &st.definitions, &[st.omega, st.omega0])
    else {
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
    let mut undecided = 0;
    let n = out.names.len().min(2);
    with_looseness(LOOSEST, || {
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
    });
    Confirmed {
        paving: out,
        undecided,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pave::{pave_scene, PaveOptions};
    use crate::scene::{Scene, Variant};

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
        let same = confirm_labels(&below, &paving);
        assert_eq!(same.undecided, 0);
        let other = confirm_labels(&above, &paving);
        assert_eq!(other.undecided, decided);
        assert!(other
            .paving
            .leaves
            .iter()
            .all(|l| !l.labels[0].is_decided()));
    }
}
