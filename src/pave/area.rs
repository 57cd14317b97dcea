//! Rigorous area bounds of regions and partition cells from a paving.

use super::{Label, Leaf, Paving};
use crate::scene::Cell;
use inari::{const_interval, Interval};
use serde::Serialize;

/// A set built from the constraints: each entry says whether the point must be
/// inside (`Some(true)`), outside (`Some(false)`) or is free (`None`).
/// `[Some(true), None]` is Ω; `[Some(false), Some(true)]` is Ω̄ ∩ Ω₀.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellSpec(pub [Option<bool>; super::MAX_CONSTRAINTS]);

impl CellSpec {
    pub fn of(literals: &[Option<bool>]) -> CellSpec {
        let mut c = [None; super::MAX_CONSTRAINTS];
        c[..literals.len()].copy_from_slice(literals);
        CellSpec(c)
    }

    /// Every literal proved on the leaf: the whole box lies in the set. A
    /// literal on a constraint the paving does not have is never proved.
    pub fn proved_in(&self, leaf: &Leaf) -> bool {
        self.0
            .iter()
            .enumerate()
            .all(|(i, want)| match (want, leaf.labels.get(i)) {
                (None, _) => true,
                (Some(true), Some(l)) => *l == Label::ProvedIn,
                (Some(false), Some(l)) => *l == Label::ProvedOut,
                (Some(_), None) => false,
            })
    }

    /// The set is empty by construction: two constraints that are the same
    /// function (`same_as`, see [`super::ConstraintSet::same_as`]) are asked
    /// for opposite signs.
    pub fn contradictory(&self, same_as: &[Option<usize>]) -> bool {
        same_as
            .iter()
            .enumerate()
            .any(|(i, s)| match (*s, self.0[i]) {
                (Some(j), Some(want)) => self.0[j] == Some(!want),
                _ => false,
            })
    }

    /// Some literal disproved on the leaf: the box misses the set entirely.
    /// A literal on a constraint the paving does not have is never disproved.
    pub fn proved_out(&self, leaf: &Leaf) -> bool {
        self.0
            .iter()
            .zip(leaf.labels.iter())
            .any(|(want, l)| match want {
                None => false,
                Some(true) => *l == Label::ProvedOut,
                Some(false) => *l == Label::ProvedIn,
            })
    }
}

/// Its literals on (Ω, Ω₀) as a paving reads them (defined here, beside
/// [`CellSpec`]: the scene's vocabulary knows nothing of pavings).
impl Cell {
    pub fn spec(self) -> CellSpec {
        CellSpec::of(&self.literals())
    }
}

/// Ω, Ω₀ and the four cells for two constraints, in [`Cell::ALL`] order.
pub fn standard_cells() -> [CellSpec; 6] {
    Cell::ALL.map(Cell::spec)
}

/// `inner_area ≤ true area ≤ outer_area`, with box counts.
#[derive(Clone, Copy, Debug, Serialize, PartialEq)]
pub struct AreaBounds {
    pub inner_area: f64,
    pub outer_area: f64,
    /// Leaves proved inside.
    pub inner_boxes: usize,
    /// Leaves not proved outside (a superset of the inner ones).
    pub outer_boxes: usize,
    /// The set is empty by construction ([`CellSpec::contradictory`]): both
    /// areas are exactly 0, whatever the leaves.
    pub proved_empty: bool,
}

impl AreaBounds {
    /// An upper bound on `outer_area − inner_area`: the difference is
    /// computed in interval arithmetic and rounded up.
    pub fn undecided_area(&self) -> f64 {
        let pt = |x: f64| Interval::try_from((x, x)).unwrap_or(Interval::ENTIRE);
        (pt(self.outer_area) - pt(self.inner_area)).sup() + 0.0
    }
    pub fn undecided_boxes(&self) -> usize {
        self.outer_boxes - self.inner_boxes
    }
}

const ZERO: Interval = const_interval!(0.0, 0.0);

impl Paving {
    /// [`Paving::area_bounds`] of several sets, one thread per set; each sum
    /// runs in leaf order, so the result does not depend on the thread count.
    /// Every leaf's area is computed once for all the sets.
    pub fn area_bounds_all(&self, cells: &[CellSpec], uncovered_sup: f64) -> Vec<AreaBounds> {
        use rayon::prelude::*;
        // Below this the pool's start-up costs more than the sums: one pass
        // over the leaves adds each to every set's sums (each still in leaf
        // order), without a vector of areas to fill.
        if self.leaves.len() < 1 << 16 {
            return self.bounds_in_one_pass(cells, uncovered_sup);
        }
        let areas: Vec<Interval> = self.leaves.par_iter().map(|l| l.bx.area()).collect();
        cells
            .par_iter()
            .map(|c| self.bounds_with(c, |k| areas[k], uncovered_sup))
            .collect()
    }

    /// [`Paving::area_bounds_all`] serially, in one pass over the leaves.
    fn bounds_in_one_pass(&self, cells: &[CellSpec], uncovered_sup: f64) -> Vec<AreaBounds> {
        let mut sums = vec![Sums::ZERO; cells.len()];
        for leaf in &self.leaves {
            let a = leaf.bx.area();
            for (c, sum) in cells.iter().zip(sums.iter_mut()) {
                sum.add(c, leaf, a);
            }
        }
        cells
            .iter()
            .zip(sums)
            .map(|(c, sum)| sum.bounds(c.contradictory(&self.same_as), uncovered_sup))
            .collect()
    }

    /// Area bounds of a set. `uncovered_sup` bounds the area of the true domain
    /// outside the root box (it is added to the outer bound only).
    pub fn area_bounds(&self, cell: &CellSpec, uncovered_sup: f64) -> AreaBounds {
        self.bounds_with(cell, |k| self.leaves[k].bx.area(), uncovered_sup)
    }

    /// [`Paving::area_bounds`] with leaf `k`'s area given by `area(k)`.
    fn bounds_with(
        &self,
        cell: &CellSpec,
        area: impl Fn(usize) -> Interval,
        uncovered_sup: f64,
    ) -> AreaBounds {
        if cell.contradictory(&self.same_as) {
            return Sums::ZERO.bounds(true, uncovered_sup);
        }
        let mut sum = Sums::ZERO;
        for (k, leaf) in self.leaves.iter().enumerate() {
            sum.add(cell, leaf, area(k));
        }
        sum.bounds(false, uncovered_sup)
    }
}

/// One set's running sums, in leaf order: the areas of the leaves proved in
/// it and of those not proved out of it, and their counts.
#[derive(Clone, Copy)]
struct Sums {
    inner: Interval,
    outer: Interval,
    inner_boxes: usize,
    outer_boxes: usize,
}

impl Sums {
    const ZERO: Sums = Sums {
        inner: ZERO,
        outer: ZERO,
        inner_boxes: 0,
        outer_boxes: 0,
    };

    fn add(&mut self, cell: &CellSpec, leaf: &Leaf, area: Interval) {
        if cell.proved_in(leaf) {
            self.inner += area;
            self.inner_boxes += 1;
        }
        if !cell.proved_out(leaf) {
            self.outer += area;
            self.outer_boxes += 1;
        }
    }

    /// The bounds; `proved_empty`: the set is empty by construction, both
    /// areas exactly 0 whatever the leaves.
    fn bounds(self, proved_empty: bool, uncovered_sup: f64) -> AreaBounds {
        if proved_empty {
            return AreaBounds {
                inner_area: 0.0,
                outer_area: 0.0,
                inner_boxes: 0,
                outer_boxes: 0,
                proved_empty: true,
            };
        }
        let extra = Interval::try_from((0.0, uncovered_sup)).unwrap_or(ZERO);
        AreaBounds {
            // `+ 0.0` turns the −0 of an empty sum into +0.
            inner_area: self.inner.inf() + 0.0,
            outer_area: (self.outer + extra).sup(),
            inner_boxes: self.inner_boxes,
            outer_boxes: self.outer_boxes,
            proved_empty: false,
        }
    }
}

/// Why a cell is empty whatever the leaves; in JSON as [`Emptiness::describe`]
/// says it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Emptiness {
    /// Ω₀ is Ω by construction (the same function: an ideal constraint).
    #[serde(rename = "omega0 = omega")]
    Omega0IsOmega,
    /// A paving of the whole domain proves it: every leaf has a literal of
    /// the cell proved false, or a factor rule ([`crate::params`]).
    #[serde(rename = "proved empty")]
    Proved,
}

impl Emptiness {
    pub fn describe(self) -> &'static str {
        match self {
            Emptiness::Omega0IsOmega => "omega0 = omega",
            Emptiness::Proved => "proved empty",
        }
    }
    /// The same in symbols, as pictures show it.
    pub fn symbol(self) -> &'static str {
        match self {
            Emptiness::Omega0IsOmega => "Ω₀ = Ω",
            Emptiness::Proved => "proved empty",
        }
    }
}

/// Which of Ω, Ω₀ and the four cells ([`Cell`] order) are empty whatever
/// the leaves: those asking opposite signs of one function (Ω₀ ≡ Ω), and
/// those `proved` empty on the scene's whole domain (by the caller, from a
/// layer above: `crate::area::proved_empty_cells`).
pub fn empty_cells(paving: &Paving, proved: [bool; 6]) -> [Option<Emptiness>; 6] {
    let cells = standard_cells();
    std::array::from_fn(|i| {
        if cells[i].contradictory(&paving.same_as) {
            Some(Emptiness::Omega0IsOmega)
        } else if proved[i] {
            Some(Emptiness::Proved)
        } else {
            None
        }
    })
}

/// Area bounds of Ω, Ω₀ and the four cells ([`Cell`] order) of a scene's
/// paving, with what the scene proves applied: a cell empty by construction
/// or proved empty has both bounds 0.
pub fn standard_cell_bounds(
    paving: &Paving,
    proved: [bool; 6],
    uncovered_sup: f64,
) -> [(AreaBounds, Option<Emptiness>); 6] {
    let empty = empty_cells(paving, proved);
    let bounds = paving.area_bounds_all(&standard_cells(), uncovered_sup);
    std::array::from_fn(|i| match empty[i] {
        Some(Emptiness::Proved) => (Sums::ZERO.bounds(true, uncovered_sup), empty[i]),
        e => (bounds[i], e),
    })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::pave::{pave, ConstraintSet, PaveOptions, PerConstraint, PhaseBox};
    use inari::{const_interval, DecInterval};

    /// `θ̇ < 1/2` on the unit square: its area is exactly 1/2.
    struct Below;
    impl ConstraintSet for Below {
        type Slab = ();
        fn names(&self) -> Vec<String> {
            vec!["below".into()]
        }
        fn slab(&self, _theta: Interval) {}
        fn enclose(&self, _slab: &(), theta_dot: Interval) -> PerConstraint<DecInterval> {
            let half = DecInterval::new(const_interval!(0.5, 0.5));
            PerConstraint::new(&[DecInterval::new(theta_dot) - half]).unwrap()
        }
    }

    /// `θ̇ < 1/2` (one constraint) paved on the unit square at ε = 1/64.
    pub(crate) fn below_on_the_unit_square() -> Paving {
        let unit = PhaseBox {
            theta: [0.0, 1.0],
            theta_dot: [0.0, 1.0],
        };
        let opts = PaveOptions {
            eps: 1.0 / 64.0,
            ..PaveOptions::default()
        };
        pave(&Below, unit, opts, |_, _, _| ()).unwrap()
    }

    /// A set of no constraints is refused with an error, not paved.
    #[test]
    fn no_constraints_is_an_error() {
        struct Nothing;
        impl ConstraintSet for Nothing {
            type Slab = ();
            fn names(&self) -> Vec<String> {
                Vec::new()
            }
            fn slab(&self, _theta: Interval) {}
            fn enclose(&self, _slab: &(), _theta_dot: Interval) -> PerConstraint<DecInterval> {
                unreachable!("never evaluated")
            }
        }
        let unit = PhaseBox {
            theta: [0.0, 1.0],
            theta_dot: [0.0, 1.0],
        };
        let got = pave(&Nothing, unit, PaveOptions::default(), |_, _, _| ());
        assert_eq!(got.err(), Some(crate::pave::PaveError::NoConstraints));
    }

    /// A set asking a sign of a constraint the paving does not have is
    /// neither proved in nor out anywhere: its inner bound is 0 and its
    /// outer bound the whole square, while the paving's own constraint
    /// brackets the exact 1/2.
    #[test]
    fn a_literal_past_the_constraints_is_never_proved() {
        let p = below_on_the_unit_square();
        let own = p.area_bounds(&CellSpec::of(&[Some(true)]), 0.0);
        assert!(0.45 < own.inner_area && own.inner_area <= 0.5 && 0.5 <= own.outer_area);
        for second in [Some(true), Some(false)] {
            let both = p.area_bounds(&CellSpec::of(&[Some(true), second]), 0.0);
            assert_eq!(both.inner_area, 0.0, "{second:?}");
            assert_eq!(both.outer_area, own.outer_area, "{second:?}");
        }
    }
}
