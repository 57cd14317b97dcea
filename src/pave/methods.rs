//! Paving methods: which one (`--method`), with what options, and the
//! entry point that checks the arguments and runs the shared engine
//! (the `engine` module) with it.
//!
//! Every method builds the same kind of tree — midpoint splits, splits at
//! recorded exact points, labelled leaves — and every label it writes is one
//! the proof checker recomputes on that leaf ([`super::labels`]). Other
//! enclosures (centred forms, the f64 roots) only *steer*: they say where to
//! split, or that a box is worth certifying by a few extra splits, never a
//! label.
//!
//! - `natural` (module `natural`): label by the natural extension, bisect
//!   undecided boxes.
//! - `centred` (module `centred`): natural ∩ mean-value form ∩
//!   monotonicity, certified by a small local subdivision.
//! - `contract` (module `contract`): on every new θ-slab, the exact
//!   θ̇-partition of each quadratic constraint, recorded as splits at the
//!   contraction points.
//! - `slices` (module `slices`): adaptive θ-slabs, then one contraction
//!   per final slab.

use super::bisection::Bisection;
use super::centred::Centred;
use super::contract::Contract;
use super::labels::Scope;
use super::natural::Natural;
use super::slices::Slices;
use super::{
    budget, engine, CellSpec, ConstraintSet, PaveError, PaveOptions, Paving, PhaseBox, StopReason,
    MAX_CONSTRAINTS,
};
use serde::Serialize;
use std::fmt;
use std::str::FromStr;

pub use super::labels::{centred_label, convex_label, monotone_label};

/// A paving method (`--method`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Natural interval extension and bisection.
    Natural,
    /// Mean-value form and monotonicity in θ̇ (and in θ at the resolution)
    /// intersected with the natural enclosure, decided boxes certified by
    /// local subdivision.
    Centred,
    /// Exact contraction of each quadratic in θ̇ on every new θ-slab.
    Contract,
    /// Adaptive θ-slabs, each split in θ̇ at its contraction points: the
    /// default, the fastest at equal accuracy on every scene
    /// (`cargo bench --bench peers`).
    #[default]
    Slices,
}

impl Method {
    pub const ALL: [Method; 4] = [
        Method::Natural,
        Method::Centred,
        Method::Contract,
        Method::Slices,
    ];
    pub fn name(self) -> &'static str {
        match self {
            Method::Natural => "natural",
            Method::Centred => "centred",
            Method::Contract => "contract",
            Method::Slices => "slices",
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| {
                format!(
                    "unknown method `{s}` (known: {})",
                    Method::ALL.map(|m| m.name()).join(", ")
                )
            })
    }
}

/// How to pave, beyond resolution and budget.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MethodOptions {
    pub method: Method,
    /// Constraints whose labels matter (bit `i` = constraint `i`); a box is
    /// refined only while one of these is undecided. `None`: all of them.
    pub relevant: Option<u8>,
}

impl MethodOptions {
    pub fn new(method: Method) -> Self {
        MethodOptions {
            method,
            relevant: None,
        }
    }
    /// Refines only for the constraints a region or cell uses.
    pub fn for_cell(method: Method, cell: &CellSpec) -> Self {
        let mask = cell
            .0
            .iter()
            .enumerate()
            .filter(|(_, l)| l.is_some())
            .fold(0u8, |m, (i, _)| m | 1 << i);
        MethodOptions {
            method,
            relevant: Some(mask),
        }
    }
}

/// Paves `root` with a method. `natural` with every constraint relevant is
/// [`super::pave`].
pub fn pave_with<S: ConstraintSet, F: super::LevelFlow>(
    set: &S,
    root: PhaseBox,
    opts: PaveOptions,
    mo: &MethodOptions,
    progress: impl FnMut(u32, usize, usize) -> F,
) -> Result<Paving, PaveError> {
    if !(opts.eps.is_finite() && opts.eps > 0.0 && opts.eps <= 1.0) {
        return Err(PaveError::BadEps(opts.eps));
    }
    if opts.max_boxes == 0 {
        return Err(PaveError::BadBudget);
    }
    if !(root.theta[0] < root.theta[1] && root.theta_dot[0] < root.theta_dot[1]) {
        return Err(PaveError::EmptyDomain);
    }
    let names = set.names();
    if names.is_empty() {
        return Err(PaveError::NoConstraints);
    }
    if names.len() > MAX_CONSTRAINTS {
        return Err(PaveError::TooManyConstraints);
    }
    // Slices solve each θ-slab's quadratics in θ̇: a set without
    // coefficients is bisected as `natural` does.
    let solvable = set
        .steer_at(0.5 * (root.theta[0] + root.theta[1]))
        .is_some();
    let mut progress = progress;
    let run = |o: PaveOptions| {
        let (scope, names) = (scope(set, names.len(), mo.relevant), names.clone());
        let grid = Bisection::new(root, o.eps);
        let p = &mut progress;
        match mo.method {
            Method::Natural => engine::pave(&Natural { scope, grid }, root, o, names, p),
            Method::Centred => engine::pave(&Centred { scope, grid }, root, o, names, p),
            Method::Contract => engine::pave(&Contract { scope, grid }, root, o, names, p),
            Method::Slices if !solvable => {
                engine::pave(&Natural { scope, grid }, root, o, names, p)
            }
            Method::Slices => {
                let method = Slices::new(scope, root, o.eps);
                engine::pave(&method, root, o, names, p)
            }
        }
    };
    Ok(budget::within_budget(opts, run))
}

/// The `n` constraints of `set`, their copies, and those `relevant` asks
/// for (with their originals: a copy is decided exactly when its original
/// is).
fn scope<S: ConstraintSet>(set: &S, n: usize, relevant: Option<u8>) -> Scope<'_, S> {
    let mut same_as = set.same_as();
    same_as.resize(n, None);
    for (i, s) in same_as.iter_mut().enumerate() {
        // only earlier constraints that are not aliases themselves
        if s.is_some_and(|j| j >= i) {
            *s = None;
        }
    }
    let all = ((1u16 << n) - 1) as u8;
    let mut relevant = relevant.unwrap_or(all) & all;
    if relevant == 0 {
        relevant = all;
    }
    for (i, s) in same_as.iter().enumerate() {
        if let Some(j) = *s {
            if relevant >> i & 1 == 1 {
                relevant |= 1 << j;
            }
        }
    }
    Scope {
        set,
        n,
        same_as,
        relevant,
    }
}

/// One timed run of a method on a scene, summarised for charts and tables.
#[derive(Clone, Debug, Serialize)]
pub struct MethodRun {
    pub method: Method,
    pub eps: f64,
    pub leaves: usize,
    /// Outer − inner area of the region asked for (rounded up).
    pub undecided_area: f64,
    pub inner_area: f64,
    pub outer_area: f64,
    pub box_evaluations: u64,
    pub slab_evaluations: u64,
    pub bytes_per_leaf: f64,
    pub peak_bytes_per_leaf: f64,
    /// Wall time of the paving alone.
    pub seconds: f64,
    pub stop: StopReason,
}

/// Paves `domain` of a scene with `method` for the region or cell
/// `region` (an index into [`super::standard_cells`], refining only its
/// constraints; `None`: all constraints, areas of Ω) and reports the run.
pub fn run_method(
    scene: &crate::scene::Scene,
    variant: crate::scene::Variant,
    domain: &crate::scene::Domain,
    region: Option<usize>,
    method: Method,
    opts: PaveOptions,
) -> Result<(MethodRun, Paving), PaveError> {
    let cells = super::standard_cells();
    let cell = cells.get(region.unwrap_or(0)).copied().unwrap_or(cells[0]);
    let mo = match region {
        Some(_) => MethodOptions::for_cell(method, &cell),
        None => MethodOptions::new(method),
    };
    let start = std::time::Instant::now();
    let p = super::pave_scene_method(scene, variant, domain, opts, &mo, |_, _, _| {})?;
    let seconds = start.elapsed().as_secs_f64();
    let b = p.area_bounds(&cell, domain.uncovered_area_sup());
    Ok((
        MethodRun {
            method,
            eps: opts.eps,
            leaves: p.leaves.len(),
            undecided_area: b.undecided_area(),
            inner_area: b.inner_area,
            outer_area: b.outer_area,
            box_evaluations: p.stats.box_evaluations,
            slab_evaluations: p.stats.slab_evaluations,
            bytes_per_leaf: p.stats.bytes_per_leaf,
            peak_bytes_per_leaf: p.stats.peak_bytes_per_leaf,
            seconds,
            stop: p.stop,
        },
        p,
    ))
}
