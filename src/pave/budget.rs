//! The leaf budget (`--max-boxes`). A paving that needs more leaves than
//! the budget is not cut off part-way (that leaves part of the domain
//! coarser than a larger ε would, so a finer request could be answered
//! worse): the complete paving at the finest power of two 2⁻ᵏ > ε that
//! fits is returned instead, and the stop says so.
//!
//! With `natural`, `centred` and `contract` the paving at 2⁻ᵏ⁻¹ refines
//! the one at 2⁻ᵏ (a box is split further, never differently), so its
//! leaves are at least as many and every point lies in a leaf at least as
//! small: the result at ε is then a refinement of the result at every power
//! of two ε' ≥ ε under the same budget. `slices` places its slabs and cuts
//! by ε, so there the comparison rests on its complete pavings improving as
//! ε halves.

use super::engine::Overflow;
use super::{BudgetStop, PaveOptions, PaveStats, Paving, StopReason};

/// The paving at `opts.eps` if it fits in the budget, else the complete
/// paving at the finest power of two above `opts.eps` that fits (found
/// assuming, as the module says, that leaves grow as ε shrinks), else the
/// domain's box alone. `run` paves with the given options.
pub(super) fn within_budget(
    opts: PaveOptions,
    mut run: impl FnMut(PaveOptions) -> Result<Paving, Overflow>,
) -> Paving {
    let mut work = Work::default();
    let asked = match run(opts) {
        Ok(p) if p.complete || p.stop == StopReason::Interrupted => return p,
        Ok(p) => {
            work.add_paving(&p);
            p.budget.expect("an incomplete paving says what stopped it")
        }
        Err(o) => {
            work.add_overflow(&o);
            o.budget
        }
    };
    let at = |k: i32| PaveOptions {
        eps: 2f64.powi(-k),
        max_boxes: opts.max_boxes,
    };
    // The finest power of two above ε (-1: none, ε = 1).
    let mut finest = -1;
    while finest < 1074 && at(finest + 1).eps > opts.eps {
        finest += 1;
    }
    // Leaves grow about as 1/ε (a boundary's length over the leaf size):
    // about double per power of two. First guess from the leaves the asked
    // ε needs at least, then from the leaves of the last fitting try.
    let halvings = |leaves: f64| {
        (leaves / opts.max_boxes as f64)
            .log2()
            .clamp(-1100.0, 1100.0)
    };
    let mut next = finest
        - halvings(asked.leaves_needed_at_least as f64)
            .ceil()
            .max(0.0) as i32;
    // The largest k known to fit (with its paving) and the smallest known
    // not to.
    let (mut fits, mut fails) = (-1, finest + 1);
    let mut best: Option<Paving> = None;
    let mut first = true;
    while fails - fits > 1 {
        let k = next.clamp(fits + 1, fails - 1);
        let guess = std::mem::replace(&mut first, false);
        next = match run(at(k)) {
            // The caller stopped: this run's paving is valid, and coarser.
            Ok(p) if p.stop == StopReason::Interrupted => return p,
            Ok(p) if p.complete => {
                let up = (-halvings(p.leaves.len() as f64)).floor().max(1.0) as i32;
                if let Some(b) = best.replace(p) {
                    work.add_paving(&b);
                }
                fits = k;
                k + up
            }
            other => {
                match other {
                    Ok(p) => work.add_paving(&p),
                    Err(o) => work.add_overflow(&o),
                }
                fails = k;
                // Next to the first guess (it is usually close), then
                // halving.
                if guess {
                    k - 1
                } else {
                    (fits + fails).div_euclid(2)
                }
            }
        };
    }
    let mut p = match best {
        Some(p) => p,
        None => {
            // One leaf: the root's level is the only one.
            let Ok(p) = run(PaveOptions {
                eps: 1.0,
                max_boxes: 1,
            }) else {
                unreachable!("a budget of one leaf never reaches a second level")
            };
            p
        }
    };
    work.add_paving(&p);
    p.eps = opts.eps;
    p.complete = false;
    p.stop = StopReason::Budget;
    p.budget = Some(BudgetStop {
        complete_at_eps: (fits >= 0).then(|| at(fits).eps),
        ..asked
    });
    let leaves = p.leaves.len().max(1) as f64;
    p.stats = PaveStats {
        box_evaluations: work.stats.box_evaluations,
        slab_evaluations: work.stats.slab_evaluations,
        peak_bytes_per_leaf: work.peak / leaves,
        ..p.stats
    };
    p
}

/// The work of every run tried, and the most memory one held.
#[derive(Default)]
struct Work {
    stats: PaveStats,
    peak: f64,
}

impl Work {
    fn add(&mut self, s: &PaveStats, peak: f64) {
        self.stats.box_evaluations += s.box_evaluations;
        self.stats.slab_evaluations += s.slab_evaluations;
        self.peak = self.peak.max(peak);
    }
    fn add_paving(&mut self, p: &Paving) {
        self.add(
            &p.stats,
            p.stats.peak_bytes_per_leaf * p.leaves.len().max(1) as f64,
        );
    }
    fn add_overflow(&mut self, o: &Overflow) {
        self.add(&o.stats, o.peak as f64);
    }
}
