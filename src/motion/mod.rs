//! Certified motion in contact: validated trajectories of a scene's
//! `[dynamics]`, the first events on them (the reaction or the regions'
//! expressions changing sign, the domain left), and the equilibria and
//! singular points of its vector field.
//!
//! The stage after [`crate::scene`]: it evaluates the scene's compiled
//! θ̈ over intervals, duals and Taylor series, and knows nothing of pavings.

pub mod arrival;
pub mod event;
pub mod flow;
pub mod lohner;
pub mod portrait;
pub mod reach;
pub mod singular;
#[cfg(test)]
mod tests;

use crate::number::param::{enclose_decimal, enclose_window_end, ParamError};
use crate::params::report::exact_decimal;
use crate::scene::expr::{Quotient, TaylorTape};
use crate::scene::file::FileScene;
pub use event::Event;
pub use event::Watched;
use event::{RegionBoundary, WindowSide};
pub use flow::{FlowError, FlowSettings, Stop, Tube, TubeStep};
use inari::Interval;
use lohner::Vector;
use serde_json::{json, Value};

/// `["lo", "hi"]`, the exact decimal values of an interval's ends.
pub fn interval_json(x: Interval) -> Value {
    json!([exact_decimal(x.inf() + 0.0), exact_decimal(x.sup() + 0.0)])
}

/// What ends a run besides its end time.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Until {
    /// Ω's expression vanishes (`U=0`: Λ̈ at zero reaction).
    Omega,
    /// Ω₀'s expression vanishes (`N=0`: the contact reaction changes sign).
    Omega0,
    /// The state leaves the scene's domain.
    Domain,
    /// θ̈'s denominator vanishes (`V=0`: the singular line is reached).
    Singular,
}

impl Until {
    /// The default: leaving the start cell (either region's boundary, or
    /// the singular line where θ̈ is undefined) or the domain.
    pub const CELL_OR_DOMAIN: [Until; 4] =
        [Until::Omega, Until::Omega0, Until::Singular, Until::Domain];

    /// `U=0`/`omega`, `N=0`/`omega0`, `V=0`/`singular`, `domain`, `cell`
    /// (both regions and the singular line), `none`, comma-separated.
    pub fn parse_list(text: &str) -> Result<Vec<Until>, MotionError> {
        let mut out = Vec::new();
        for item in text.split(',').map(str::trim) {
            let add: &[Until] = match item {
                "U=0" | "omega" => &[Until::Omega],
                "N=0" | "omega0" => &[Until::Omega0],
                "V=0" | "singular" => &[Until::Singular],
                "domain" => &[Until::Domain],
                "cell" => &[Until::Omega, Until::Omega0, Until::Singular],
                "none" => &[],
                other => return Err(MotionError::Until(other.to_string())),
            };
            for u in add {
                if !out.contains(u) {
                    out.push(*u);
                }
            }
        }
        Ok(out)
    }
}

/// A certified trajectory request: a start box, an end time, what stops it.
#[derive(Clone, Debug)]
pub struct FlowRequest {
    /// θ and θ̇ at t = 0 (a point is a box of width 0 or the enclosure of
    /// its decimal text).
    pub start: [Interval; 2],
    pub t_end: Interval,
    pub until: Vec<Until>,
    pub settings: FlowSettings,
}

impl FlowRequest {
    /// From text: `theta`, `theta_dot` each `X` or `LO:HI` (decimal text,
    /// or `pi`, `pi/N`), `t_end` decimal text.
    pub fn parse(theta: &str, theta_dot: &str, t_end: &str) -> Result<FlowRequest, MotionError> {
        let side = |name: &str, text: &str| -> Result<Interval, MotionError> {
            let (lo, hi) = text.split_once(':').unwrap_or((text, text));
            let lo = enclose_window_end(name, lo)?;
            let hi = enclose_window_end(name, hi)?;
            if lo.inf() > hi.sup() {
                return Err(MotionError::Range(name.to_string(), text.to_string()));
            }
            Ok(lo.convex_hull(hi))
        };
        let t = enclose_decimal("t", t_end)?;
        if t.inf() <= 0.0 {
            return Err(MotionError::Flow(FlowError::EndTime));
        }
        Ok(FlowRequest {
            start: [side("theta", theta)?, side("theta_dot", theta_dot)?],
            t_end: t,
            until: Until::CELL_OR_DOMAIN.to_vec(),
            settings: FlowSettings::default(),
        })
    }
}

#[derive(Debug, PartialEq, thiserror::Error)]
pub enum MotionError {
    #[error("scene `{0}` has no [dynamics]: there is no equation of motion to integrate")]
    NoDynamics(String),
    #[error(
        "unknown event `{0}` (known: U=0, N=0, V=0, omega, omega0, singular, cell, domain, none)"
    )]
    Until(String),
    #[error("{0} `{1}` is not LO:HI with LO <= HI")]
    Range(String, String),
    #[error(transparent)]
    Param(#[from] ParamError),
    #[error(transparent)]
    Flow(#[from] FlowError),
}

/// A scene's motion ready to integrate: its compiled θ̈ and the functions
/// whose sign changes end a run; one per scene and event set, run from
/// many starts.
pub struct Motion<'a> {
    tape: TaylorTape,
    regions: Vec<RegionBoundary<'a>>,
    sides: Vec<WindowSide>,
    /// θ̈ = f/g with g of θ alone, when the singular line g = 0 is watched.
    singular: Option<Quotient>,
}

impl<'a> Motion<'a> {
    pub fn new(file: &'a FileScene, until: &[Until]) -> Result<Motion<'a>, MotionError> {
        let tape = file
            .dynamics_taylor()
            .ok_or_else(|| MotionError::NoDynamics(file.name.clone()))?;
        let regions = [Until::Omega, Until::Omega0]
            .iter()
            .enumerate()
            .filter(|(i, u)| until.contains(u) && !(*i == 1 && file.omega0_is_omega()))
            .map(|(region, _)| RegionBoundary { file, region })
            .collect();
        let d = file.domain;
        let sides = if until.contains(&Until::Domain) {
            (0..2)
                .flat_map(|axis| {
                    let ends = [d.theta, d.theta_dot][axis];
                    [(ends[0], false), (ends[1], true)].map(|(at, upper)| WindowSide {
                        axis,
                        at,
                        upper,
                    })
                })
                .collect()
        } else {
            Vec::new()
        };
        let singular = file
            .dynamics_quotient()
            .filter(|q| until.contains(&Until::Singular) && !q.denominator.reads_theta_dot());
        Ok(Motion {
            tape,
            regions,
            sides,
            singular,
        })
    }

    /// The certified tube from `start` over [0, `t_end`] or to the first
    /// event.
    pub fn run(
        &self,
        start: [Interval; 2],
        t_end: Interval,
        settings: &FlowSettings,
    ) -> Result<Tube, FlowError> {
        let watched = self.watched();
        let tube = flow::integrate(&self.tape, settings, start, t_end, &watched)?;
        Ok(self.to_singular_line(tube, &watched))
    }

    /// A run that stopped for want of a step, carried to the singular line
    /// when its arrival is proved ([`arrival`]); `others` must stay non-zero
    /// until then.
    fn to_singular_line(&self, mut tube: Tube, others: &[&dyn Watched]) -> Tube {
        let (Some(q), Stop::StepFailed(why)) = (&self.singular, &tube.stop) else {
            return tube;
        };
        match arrival::certify(q, others, tube.end_time.inf(), padded(tube.end, 1.0)) {
            Ok((event, _)) => {
                tube.end_time = event.time;
                tube.end = [event.theta, event.theta_dot];
                tube.events = vec![event];
                tube.stop = Stop::Arrival;
            }
            Err(not) => {
                tube.stop = Stop::StepFailed(format!(
                    "{why}; the singular line {} is not proved reached: {not}",
                    arrival::KIND
                ));
            }
        }
        tube
    }

    /// The tube from `start` over [0, `t_end`], through any event: the
    /// contact-mode dynamics continued past the watched boundaries.
    pub fn run_through(
        &self,
        start: [Interval; 2],
        t_end: Interval,
        settings: &FlowSettings,
    ) -> Result<Tube, FlowError> {
        let tube = flow::integrate(&self.tape, settings, start, t_end, &[])?;
        Ok(self.to_singular_line(tube, &[]))
    }

    /// The arrival at the singular line from the set `e` at the exact time
    /// `t`, the set padded `room` times as a run pads it (what a proof
    /// states, with room for a checker's wider set), or why not.
    pub(crate) fn arrival_from(
        &self,
        t: f64,
        e: Vector,
        room: f64,
    ) -> Result<(Event, arrival::Arrival), String> {
        let q = self
            .singular
            .as_ref()
            .ok_or("the singular line is not watched")?;
        arrival::certify(q, &self.watched(), t, padded(e, room))
    }

    /// What each of [`Motion::watched`] is, in the same order.
    pub(crate) fn watch_items(&self) -> Vec<WatchItem> {
        self.regions
            .iter()
            .map(|r| WatchItem::Region(r.region))
            .chain(self.sides.iter().map(|s| WatchItem::Side {
                axis: s.axis,
                upper: s.upper,
            }))
            .collect()
    }

    /// The functions whose sign changes end a run.
    pub fn watched(&self) -> Vec<&dyn Watched> {
        self.regions
            .iter()
            .map(|r| r as &dyn Watched)
            .chain(self.sides.iter().map(|s| s as &dyn Watched))
            .collect()
    }
}

/// `e` widened on each side by `room` times 10⁻⁶ of its width and 10⁻¹²
/// of its size: room for a checker whose end set is a little wider than
/// ours.
fn padded(e: Vector, room: f64) -> Vector {
    e.map(|x| {
        let pad = room * (1e-6 * x.wid() + 1e-12 * (1.0 + x.mag()));
        Interval::try_from((x.inf() - pad, x.sup() + pad)).unwrap_or(Interval::ENTIRE)
    })
}

/// One watched function: a region's expression (0 for Ω, 1 for Ω₀) or a
/// side of the domain (θ or θ̇, its lower or upper end).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum WatchItem {
    Region(usize),
    Side { axis: usize, upper: bool },
}

/// The certified trajectory of `file`'s `[dynamics]` for `request`.
pub fn flow(file: &FileScene, request: &FlowRequest) -> Result<Tube, MotionError> {
    Ok(Motion::new(file, &request.until)?.run(request.start, request.t_end, &request.settings)?)
}
