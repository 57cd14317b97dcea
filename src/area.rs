//! Certified areas of Ω, Ω₀ and the four cells: by quadrature over θ
//! ([`crate::quadrature`]), with a paving's bounds ([`crate::pave`]) standing
//! in where the quadrature does not apply and narrowing it where it missed
//! its target. Each bound says which of the two gave it.

use crate::pave::{pave_scene_method, Emptiness, Method, MethodOptions, PaveOptions, Paving};
use crate::quadrature::{cell_area, check_target, AreaEnclosure, AreaError, AreaOptions};
use crate::scene::Cell;
use crate::scene::{Domain, Scene, Variant};
use serde::Serialize;
use std::time::Instant;

/// Resolution of the paving whose bounds stand in for, or narrow, the
/// quadrature's.
pub const FALLBACK_EPS: f64 = 1.0 / 1024.0;

/// What gave a bound of an area.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Source {
    /// The quadrature over θ.
    Quadrature,
    /// The inner or outer area of a paving at [`FALLBACK_EPS`].
    Paving,
    /// A proof that the set is empty ([`crate::params::proved_empty`]).
    Emptiness,
}

impl std::fmt::Display for Source {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str(match self {
            Source::Quadrature => "quadrature",
            Source::Paving => "paving",
            Source::Emptiness => "emptiness proof",
        })
    }
}

/// How an enclosure was obtained.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Provenance {
    /// The quadrature alone.
    Quadrature,
    /// A paving's inner and outer areas alone (a region the quadrature
    /// does not apply to).
    Paving,
    /// The quadrature's enclosure intersected with a paving's bounds (the
    /// quadrature missed its target).
    Intersection,
    /// The set is proved empty on the scene's whole domain: both bounds 0.
    ProvedEmpty,
}

/// The certified area of one set: the true area lies in
/// `[enclosure.area.inf(), enclosure.area.sup()]`.
#[derive(Clone, Copy, Debug)]
pub struct SetArea {
    pub cell: Cell,
    pub enclosure: AreaEnclosure,
    pub provenance: Provenance,
    /// Which method gave the lower bound, and the upper.
    pub lower_from: Source,
    pub upper_from: Source,
    /// The set's own time; for [`Provenance::Paving`], the one paving's.
    pub elapsed_s: f64,
}

impl SetArea {
    /// The lower bound, `-0` as `0`.
    pub fn lower(&self) -> f64 {
        self.enclosure.area.inf() + 0.0
    }
    /// The upper bound, `-0` as `0`.
    pub fn upper(&self) -> f64 {
        self.enclosure.area.sup() + 0.0
    }
    /// Why the set is empty, when its bounds are 0 by a proof rather than
    /// by measuring.
    pub fn emptiness(&self) -> Option<Emptiness> {
        if self.provenance == Provenance::ProvedEmpty {
            Some(Emptiness::Proved)
        } else {
            self.enclosure
                .proved_empty
                .then_some(Emptiness::Omega0IsOmega)
        }
    }
}

/// The areas asked for, in the order asked.
#[derive(Debug)]
pub struct CertifiedAreas {
    pub sets: Vec<SetArea>,
    /// Why some bounds are a paving's, when they are: one sentence each.
    pub notes: Vec<String>,
}

/// Why no area was computed.
#[derive(Debug, thiserror::Error)]
pub enum AreasError {
    /// The request cannot be met (e.g. an empty domain): bad input.
    #[error("{0}")]
    Refused(String),
    /// The width asked is below binary64's rounding for `sets`; every set
    /// asked can reach `digits` decimal places.
    #[error(
        "{sets}: a width of {tol:e} is below what binary64 arithmetic certifies \
         (rounding alone leaves up to about {floor:.1e})"
    )]
    BelowRounding {
        sets: String,
        tol: f64,
        floor: f64,
        digits: i32,
    },
    /// The paving standing in for the quadrature failed.
    #[error("paving failed: {0}")]
    Paving(String),
}

/// Certified areas of `cells` in `domain` to width `opts.tol`: by
/// quadrature, a region of a scene file that is not of degree at most 2 in θ̇
/// by one paving, and a quadrature that missed its target (not at its
/// rounding floor) intersected with that paving's bounds. Every set's target
/// is checked before any is computed, so that one refusal names all the sets
/// below binary64's rounding.
pub fn certified_areas(
    scene: &Scene,
    variant: Variant,
    domain: &Domain,
    cells: &[Cell],
    opts: AreaOptions,
) -> Result<CertifiedAreas, AreasError> {
    let pave_once = || -> Result<(Paving, f64), AreasError> {
        let start = Instant::now();
        let popts = PaveOptions {
            eps: FALLBACK_EPS,
            ..PaveOptions::default()
        };
        // The default method: for a region not quadratic in θ̇ it bisects.
        let mo = MethodOptions::new(Method::default());
        let p = pave_scene_method(scene, variant, domain, popts, &mo, |_, _, _| {})
            .map_err(|e| AreasError::Paving(format!("{e:?}")))?;
        Ok((p, start.elapsed().as_secs_f64()))
    };
    let not_quadratic = scene.reading(variant).not_quadratic();
    let mut notes = Vec::new();
    let refusal = |c: Cell, e: AreaError| AreasError::Refused(format!("{}: {e}", named(c)));
    let bounds = |p: &Paving, c: Cell| {
        let b = p.area_bounds(&c.spec(), domain.uncovered_area_sup());
        AreaEnclosure::bounds(b.inner_area, b.outer_area, p.leaves.len())
    };
    if let Some(region) = not_quadratic {
        let (p, t) = pave_once()?;
        notes.push(format!(
            "region `{region}` is not of degree at most 2 in theta_dot: every row is a paving's \
             inner and outer bounds at eps = 1/1024, with its leaves and time"
        ));
        let sets = cells
            .iter()
            .map(|&cell| {
                proved_empty(scene, variant, cell).unwrap_or(SetArea {
                    cell,
                    enclosure: bounds(&p, cell),
                    provenance: Provenance::Paving,
                    lower_from: Source::Paving,
                    upper_from: Source::Paving,
                    elapsed_s: t,
                })
            })
            .collect();
        return Ok(CertifiedAreas { sets, notes });
    }
    // Every set's rounding first, so that one refusal names them all and
    // the digits that every one of them can reach.
    let (mut below, mut floor, mut least) = (Vec::new(), 0f64, 0f64);
    for &c in cells {
        match check_target(scene, variant, domain, c, opts.tol) {
            Ok(()) => {}
            Err(AreaError::BelowRounding {
                floor: f, least: l, ..
            }) => {
                below.push(named(c));
                (floor, least) = (floor.max(f), least.max(l));
            }
            Err(e) => return Err(refusal(c, e)),
        }
    }
    if !below.is_empty() {
        return Err(AreasError::BelowRounding {
            sets: below.join(", "),
            tol: opts.tol,
            floor,
            digits: (-least.log10()).floor() as i32,
        });
    }
    let mut paving: Option<Paving> = None;
    let mut sets = Vec::new();
    for &cell in cells {
        let start = Instant::now();
        if let Some(set) = proved_empty(scene, variant, cell) {
            sets.push(SetArea {
                elapsed_s: start.elapsed().as_secs_f64(),
                ..set
            });
            continue;
        }
        let q = cell_area(scene, variant, domain, cell, opts).map_err(|e| refusal(cell, e))?;
        // At its rounding floor the enclosure is already far narrower than
        // a paving's.
        let set = if q.width() <= opts.tol || q.at_rounding_floor {
            SetArea {
                cell,
                enclosure: q,
                provenance: Provenance::Quadrature,
                lower_from: Source::Quadrature,
                upper_from: Source::Quadrature,
                elapsed_s: 0.0,
            }
        } else {
            if paving.is_none() {
                paving = Some(pave_once()?.0);
                notes.push(
                    "where the quadrature missed its target (e.g. a cell whose two boundaries coincide along a curve), its enclosure is intersected with a paving's bounds at eps = 1/1024".into(),
                );
            }
            let p = bounds(paving.as_ref().expect("just paved"), cell);
            intersected(cell, q, &p)
        };
        sets.push(SetArea {
            elapsed_s: start.elapsed().as_secs_f64(),
            ..set
        });
    }
    Ok(CertifiedAreas { sets, notes })
}

/// Which of Ω, Ω₀ and the four cells ([`Cell`] order) the scene proves empty
/// on its whole domain ([`crate::params::proved_empty`]): what a paving's
/// area bounds take as 0 ([`crate::pave::standard_cell_bounds`]).
pub fn proved_empty_cells(scene: &Scene, variant: Variant) -> [bool; 6] {
    Cell::ALL.map(|c| crate::params::proved_empty(scene, variant, c))
}

/// The set's area as exactly 0 when it is proved empty on the scene's whole
/// domain (so on any window of it).
fn proved_empty(scene: &Scene, variant: Variant, cell: Cell) -> Option<SetArea> {
    crate::params::proved_empty(scene, variant, cell).then(|| SetArea {
        cell,
        enclosure: AreaEnclosure::bounds(0.0, 0.0, 0),
        provenance: Provenance::ProvedEmpty,
        lower_from: Source::Emptiness,
        upper_from: Source::Emptiness,
        elapsed_s: 0.0,
    })
}

/// `Ω (omega)`: a set as error messages name it.
fn named(c: Cell) -> String {
    format!("{} ({})", c.label(), c.name())
}

/// A quadrature's enclosure `q` narrowed by a paving's bounds `p`, each
/// bound from whichever is tighter (the quadrature's on a tie, or when the
/// two do not meet, which only a wrong enclosure could cause).
fn intersected(cell: Cell, q: AreaEnclosure, p: &AreaEnclosure) -> SetArea {
    let enclosure = q.intersect(p);
    let from = |mine: f64, quad: f64| {
        if mine == quad {
            Source::Quadrature
        } else {
            Source::Paving
        }
    };
    SetArea {
        cell,
        enclosure,
        provenance: Provenance::Intersection,
        lower_from: from(enclosure.area.inf(), q.area.inf()),
        upper_from: from(enclosure.area.sup(), q.area.sup()),
        elapsed_s: 0.0,
    }
}
