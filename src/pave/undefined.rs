//! Where a paving's formulas may be undefined: the area of its undefined
//! leaves, and whether they are so much of it that its bounds say little.

use super::{Label, Paving, PhaseBox};
use crate::number::param::short_num;
use inari::{const_interval, Interval};

/// The leaves of a paving where some constraint is undefined (a division by
/// an interval holding 0, `ln` or `sqrt` of a value that may be ≤ 0, an
/// under- or overflowed enclosure).
#[derive(Clone, Debug, PartialEq)]
pub struct UndefinedArea {
    /// An upper bound on their area (outward-rounded sum, at most `f64::MAX`).
    pub area_sup: f64,
    /// How many leaves are undefined, of how many.
    pub leaves: usize,
    pub of_leaves: usize,
    /// Set when they are every leaf or more than half of the area (the
    /// lower bound of their area above half the upper bound of the root's):
    /// their hull `[θ, θ̇]`.
    pub dominant: Option<[[f64; 2]; 2]>,
}

impl UndefinedArea {
    /// Every leaf of the paving is undefined.
    pub fn everywhere(&self) -> bool {
        self.leaves > 0 && self.leaves == self.of_leaves
    }

    /// A warning when the undefined leaves dominate (see
    /// [`UndefinedArea::dominant`]), saying where and why the area bounds
    /// then say little.
    pub fn warning(&self) -> Option<String> {
        let [th, thd] = self.dominant?;
        let what = if self.everywhere() {
            "every leaf is undefined".to_string()
        } else {
            format!(
                "undefined leaves cover more than half of the area ({} of {} leaves)",
                self.leaves, self.of_leaves
            )
        };
        Some(format!(
            "{what}, in θ ∈ [{}, {}], θ̇ ∈ [{}, {}]: a formula is undefined there \
             (division by an interval holding 0, ln or sqrt of a value that may be ≤ 0), \
             or the enclosures under- or overflowed the double range, so the area bounds \
             say little; check the expressions, or rescale the parameters or the window",
            short_num(th[0]),
            short_num(th[1]),
            short_num(thd[0]),
            short_num(thd[1])
        ))
    }
}

impl Paving {
    /// The leaves where some constraint is undefined, their area and, when
    /// they dominate, their hull.
    pub fn undefined_area(&self) -> UndefinedArea {
        let undefined: Vec<_> = self
            .leaves
            .iter()
            .filter(|l| l.labels.contains(&Label::Undefined))
            .collect();
        const ZERO: Interval = const_interval!(0.0, 0.0);
        let area = undefined.iter().fold(ZERO, |a, l| a + l.bx.area());
        let all = !undefined.is_empty() && undefined.len() == self.leaves.len();
        // (areas of tiny windows may underflow: "all leaves" is counted, not summed)
        let dominant = (all || !undefined.is_empty() && 2.0 * area.inf() > self.root.area().sup())
            .then(|| {
                let hull = |f: fn(&PhaseBox) -> [f64; 2]| {
                    undefined
                        .iter()
                        .fold([f64::INFINITY, f64::NEG_INFINITY], |h, l| {
                            let r = f(&l.bx);
                            [h[0].min(r[0]), h[1].max(r[1])]
                        })
                };
                [hull(|b| b.theta), hull(|b| b.theta_dot)]
            });
        UndefinedArea {
            area_sup: (area.sup() + 0.0).min(f64::MAX),
            leaves: undefined.len(),
            of_leaves: self.leaves.len(),
            dominant,
        }
    }
}
