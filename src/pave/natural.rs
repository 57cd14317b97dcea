//! `natural`: label by the natural extension, bisect undecided boxes along
//! the relatively wider axis down to the resolution. [`Bisection`] is also
//! where `centred` and `contract` stop.

use super::bisection::Bisection;
use super::engine::Refine;
use super::labels::{Labels, Scope};
use super::level::{Local, Open, Work};
use super::{ConstraintSet, SlabEnds};

/// Natural interval extension and bisection.
pub(super) struct Natural<'a, S: ConstraintSet> {
    pub scope: Scope<'a, S>,
    pub grid: Bisection,
}

impl<S: ConstraintSet> Refine<S> for Natural<'_, S> {
    fn scope(&self) -> &Scope<'_, S> {
        &self.scope
    }
    fn grid(&self) -> Option<&Bisection> {
        Some(&self.grid)
    }
    fn subtree(
        &self,
        _o: &Open<S::Slab>,
        _slab: &S::Slab,
        _ends: Option<&[SlabEnds]>,
        _labels: &Labels,
        _work: &mut Work,
        _out: &mut Vec<Local>,
    ) -> bool {
        false
    }
}
