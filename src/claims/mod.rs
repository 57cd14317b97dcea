//! The paper's formulas and statements as executable checks.
//!
//! Every claim has a fixed id, its place in the paper, the statement as the
//! paper makes it, how it is checked, and a check function that computes a
//! [`Verdict`] with its evidence. Nothing here copies a verdict from the
//! paper: each comes out of a computation (identities proved by exact
//! polynomial arithmetic, interval enclosures, the paver, the root isolator and the κ₀ proof).
//!
//! Each check takes a `mutant` flag: `true` feeds the same check a
//! deliberately wrong variant of the formula or parameters (documented at the
//! check), so tests can show that the check can come out the other way.
//!
//! * [`exact`]: rationals and rational functions behind the
//!   [`Scalar`](crate::number::scalar::Scalar) trait, identity proofs, small
//!   exact linear solves.
//! * [`symbolic`]: the polynomials and rational functions of those proofs.
//! * [`files`]: the formulas a scene file states, evaluated from its text.
//! * [`witness`]: certified region differences found with the paver.
//! * [`example1`], [`smooth`], [`ice`]: the checks of §1, §2, §3.
//! * [`report`]: `REPORT.md`, `report.json` and `claims.toml`.
//! * [`figures`]: pictures of the witnesses.

pub mod exact;
pub mod example1;
pub mod figures;
pub mod files;
pub mod ice;
pub mod report;
pub mod smooth;
pub mod symbolic;
pub mod witness;

use crate::pave::PhaseBox;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::sync::OnceLock;

/// The paper the claims come from.
pub const PAPER: &str = "A. P. Ivanov, *Geometric representation of detachment conditions in \
systems with unilateral constraint*, Nelineinaya Dinamika (Russian Journal of Nonlinear Dynamics), 2008";

/// How the report reads `Λ̈ = U + V N`, for every claim that names U or V.
///
/// N is a free applied force: the equations of motion (with every other
/// constraint kept, in §3 the blade's) are solved for the accelerations with
/// N given, so Λ̈ is affine in N; the contact condition Λ̈ = 0 is imposed only
/// afterwards and fixes N = −U/V. U (Λ̈ at N = 0) then decides Ω₀; the
/// paper's Ω is the sign of Λ̈ in free flight, which is U only on the smooth
/// plane of §2. V = ∂Λ̈/∂N is ∇Λ·M⁻¹∇Λ in §1 and §2, and the blade of §3
/// changes it. Substituting instead an acceleration already solved from the
/// contact equations makes the coefficient of N 1/m and the rest U/(mV):
/// same sign, same N at contact, other U and V.
pub const READING: &str = "N is a free force: the equations of motion, with every other \
constraint kept (in §3 the blade's), are solved for the accelerations with N given, so Λ̈ = U + V N \
is affine in N, and the contact condition Λ̈ = 0 is imposed afterwards (N = −U/V). U is Λ̈ at \
N = 0 and V = ∂Λ̈/∂N > 0, so contact is kept with N ≥ 0 exactly where U ≤ 0: the sign of U decides \
Ω₀. The paper's Ω is the sign of Λ̈ in free flight (no contact force at all): that is U only on \
the smooth plane of §2, where Ω = Ω₀; in §1 U also holds the viscous friction, and in §3 the \
blade's reaction, so Ω and Ω₀ differ. V is ∇Λ·M⁻¹∇Λ in §1 (1/m + h'²/C) and §2 \
(1/m + a²cos²θ/A); in §3 the blade changes it to V₀ = 1/m + a²cos²θ/(A + m a² sin²θ). An \
acceleration taken from the contact equations (N eliminated before) would give the coefficient \
1/m and U/(mV) instead: the same sign of U and the same N at contact, so Ω, Ω₀ and N do not \
change with the reading, only the formulas for U and V do. F1.9, F2.6, F2.7 and F3.4 are graded \
under this reading.";

/// What the computation shows about a claim ([`Verdict::meaning`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// True for all parameters (argument checked by computation).
    Confirmed,
    /// Certified over a stated parameter box or set.
    ConfirmedOn,
    /// Wrong as printed, but changes none of Ω, Ω₀, N or what follows.
    Typo,
    /// A formula is wrong and changes Ω, Ω₀, N or what follows.
    Error,
    /// The statement fails: certified witness.
    False,
    /// True exactly under a stated condition: witnesses on both sides.
    Conditional,
    /// Cannot be checked (reason given).
    NotCheckable,
}

impl Verdict {
    pub const ALL: [Verdict; 7] = [
        Verdict::Confirmed,
        Verdict::ConfirmedOn,
        Verdict::Typo,
        Verdict::Error,
        Verdict::False,
        Verdict::Conditional,
        Verdict::NotCheckable,
    ];
}

impl Verdict {
    /// What the verdict means, as `REPORT.md` defines it.
    pub fn meaning(self) -> &'static str {
        match self {
            Verdict::Confirmed => {
                "true for all parameters; the argument is checked by computation (a step \
                 the paper leaves out is named in the evidence)"
            }
            Verdict::ConfirmedOn => {
                "true on a stated parameter box or set of samples, checked there; not \
                 shown beyond it"
            }
            Verdict::Typo => {
                "wrong as printed, but the slip changes none of Ω, Ω₀, the reaction N or \
                 any later formula or statement; the right form is given"
            }
            Verdict::Error => {
                "a formula is wrong and the mistake changes Ω, Ω₀, N or a later formula or \
                 statement; the right one and what it changes are given"
            }
            Verdict::False => "the statement fails: a certified or exact witness is given",
            Verdict::Conditional => {
                "true exactly under a stated condition, with witnesses on both sides"
            }
            Verdict::NotCheckable => "cannot be checked; the reason is given",
        }
    }
}

impl fmt::Display for Verdict {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(match self {
            Verdict::Confirmed => "confirmed",
            Verdict::ConfirmedOn => "confirmed-on",
            Verdict::Typo => "typo",
            Verdict::Error => "error",
            Verdict::False => "false",
            Verdict::Conditional => "conditional",
            Verdict::NotCheckable => "not-checkable",
        })
    }
}

/// What backs a verdict.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Strength {
    /// Interval proof (outward rounding, decimal parameters enclosed).
    Certified,
    /// Exact rational arithmetic.
    Exact,
    /// Identities proved by exact polynomial arithmetic (both sides equal
    /// as rational functions of every sampled quantity).
    Symbolic,
    /// Exact agreement at random rational points only (Schwartz–Zippel with
    /// an asserted, not proved, degree bound).
    RandomTest,
    /// A written derivation whose steps are checked by computation.
    Argument,
}

impl Strength {
    pub const ALL: [Strength; 5] = [
        Strength::Symbolic,
        Strength::Exact,
        Strength::Certified,
        Strength::Argument,
        Strength::RandomTest,
    ];

    /// What backs a verdict of this strength, as `REPORT.md` defines it.
    pub fn meaning(self) -> &'static str {
        match self {
            Strength::Symbolic => {
                "identities proved: both sides computed as rational functions with integer \
                 coefficients of every sampled quantity (parameters, tan(θ/2), velocities, \
                 path coefficients), their cleared difference the zero polynomial \
                 (`src/claims/exact.rs`); where two sides differ, a rational point where they \
                 differ exactly is given"
            }
            Strength::Exact => {
                "exact rational arithmetic at stated points (decimal parameters read exactly)"
            }
            Strength::Certified => {
                "interval enclosures with outward rounding, decimal parameters enclosed from \
                 their text (the paver, the root isolator, the κ₀ proof)"
            }
            Strength::Argument => {
                "a written derivation (in the evidence) whose every step is an identity, \
                 exact value or enclosure computed here"
            }
            Strength::RandomTest => {
                "agreement at random rational points only (Schwartz–Zippel with an asserted, \
                 not proved, degree bound)"
            }
        }
    }
}

impl fmt::Display for Strength {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(match self {
            Strength::Certified => "certified",
            Strength::Exact => "exact",
            Strength::Symbolic => "symbolic",
            Strength::RandomTest => "random-test",
            Strength::Argument => "argument",
        })
    }
}

/// What one check returns.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub verdict: Verdict,
    pub strength: Strength,
    /// One line of evidence.
    pub summary: String,
    /// For a verdict other than `confirmed`: the correct statement or formula.
    pub correction: Option<String>,
    pub witness: serde_json::Value,
}

impl Outcome {
    pub fn new(
        verdict: Verdict,
        strength: Strength,
        summary: impl Into<String>,
        witness: serde_json::Value,
    ) -> Outcome {
        Outcome {
            verdict,
            strength,
            summary: summary.into(),
            correction: None,
            witness,
        }
    }
    pub fn correct(mut self, c: impl Into<String>) -> Outcome {
        self.correction = Some(c.into());
        self
    }
}

/// A claim's check: `mutant` as documented at each check.
pub type Check = fn(bool) -> Outcome;

/// One entry of the registry: a row of `claims.toml` and its check.
pub struct Claim {
    pub id: String,
    pub location: String,
    /// The statement as the paper makes it.
    pub statement: String,
    /// How it is checked.
    pub method: String,
    pub check: Check,
}

/// The claim table, the registry's source (`check-paper` writes it out as
/// `claims.toml`).
pub const TABLE: &str = include_str!("claims.toml");

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Table {
    claim: Vec<Row>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Row {
    id: String,
    location: String,
    statement: String,
    method: String,
}

/// A claim table that does not match the check functions.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum TableError {
    #[error("claim table: {0}")]
    Syntax(String),
    #[error("claim table: `{0}` has no check function")]
    NoCheck(String),
    #[error("claim table: `{0}` appears twice")]
    Repeated(String),
    #[error("claim table: the check of `{0}` has no row")]
    NoRow(String),
}

/// Pairs every row of `table` with its check from `checks`, one to one.
pub fn pair(table: &str, checks: &[(&str, Check)]) -> Result<Vec<Claim>, TableError> {
    let rows = toml::from_str::<Table>(table)
        .map_err(|e| TableError::Syntax(e.message().to_string()))?
        .claim;
    let mut out: Vec<Claim> = Vec::with_capacity(rows.len());
    for r in rows {
        if out.iter().any(|c| c.id == r.id) {
            return Err(TableError::Repeated(r.id));
        }
        let check = match checks.iter().find(|(id, _)| *id == r.id) {
            Some((_, f)) => *f,
            None => return Err(TableError::NoCheck(r.id)),
        };
        out.push(Claim {
            id: r.id,
            location: r.location,
            statement: r.statement,
            method: r.method,
            check,
        });
    }
    match checks
        .iter()
        .find(|(id, _)| !out.iter().any(|c| c.id == *id))
    {
        Some((id, _)) => Err(TableError::NoRow(id.to_string())),
        None => Ok(out),
    }
}

/// Every check function of §1–§3, by id.
pub fn checks() -> Vec<(&'static str, Check)> {
    [example1::CHECKS, smooth::CHECKS, ice::CHECKS].concat()
}

/// Every claim's picture, by id; each is registered beside its check.
pub fn figures_of() -> Vec<(&'static str, figures::FigureOf)> {
    [example1::FIGURES, smooth::FIGURES, ice::FIGURES].concat()
}

/// The claims with a picture, in report order.
pub fn with_figure() -> Vec<&'static str> {
    let pictured = figures_of();
    registry()
        .iter()
        .map(|c| c.id.as_str())
        .filter(|id| pictured.iter().any(|(p, _)| p == id))
        .collect()
}

/// The picture of claim `id`, if it has one; `mark` is the certified
/// witness box of a region claim.
pub fn figure(id: &str, mark: Option<PhaseBox>) -> Result<Option<figures::ClaimFigure>, String> {
    match figures_of().into_iter().find(|(p, _)| *p == id) {
        Some((_, picture)) => picture(mark).build().map(Some),
        None => Ok(None),
    }
}

/// Relative path of a claim's figure (SVG) inside the report folder.
pub fn figure_path(id: &str) -> Option<String> {
    figures_of()
        .iter()
        .any(|(p, _)| *p == id)
        .then(|| format!("figures/{}.svg", id.replace('.', "_")))
}

/// Every claim, in report order (the order of `claims.toml`).
pub fn registry() -> &'static [Claim] {
    static REGISTRY: OnceLock<Vec<Claim>> = OnceLock::new();
    REGISTRY.get_or_init(|| {
        // The table is built in: a mismatch is caught by the test suite.
        pair(TABLE, &checks()).expect("claims.toml matches the check functions")
    })
}

/// Ids of [`registry`] in order.
pub fn ids() -> Vec<&'static str> {
    registry().iter().map(|c| c.id.as_str()).collect()
}

/// A claim with its computed verdict.
#[derive(Clone, Debug, Serialize)]
pub struct ClaimResult {
    pub id: String,
    pub location: String,
    pub statement: String,
    pub verdict: Verdict,
    pub strength: Strength,
    pub summary: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub correction: Option<String>,
    pub witness: serde_json::Value,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub proof_file: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub figure: Option<String>,
}

/// An id not in the registry.
#[derive(Debug, thiserror::Error, PartialEq)]
#[error("unknown claim id `{0}` (see `paper-checks/claims.toml` for the list)")]
pub struct UnknownClaim(pub String);

/// Runs the claims with the given ids (all when empty), in registry order.
pub fn run(ids: &[String]) -> Result<Vec<ClaimResult>, UnknownClaim> {
    let reg = registry();
    for id in ids {
        if !reg.iter().any(|c| &c.id == id) {
            return Err(UnknownClaim(id.clone()));
        }
    }
    let chosen: Vec<&Claim> = reg
        .iter()
        .filter(|c| ids.is_empty() || ids.contains(&c.id))
        .collect();
    Ok(chosen.par_iter().map(|c| run_one(c, false)).collect())
}

/// Runs one claim's check (`mutant` as documented at the check).
pub fn run_one(c: &Claim, mutant: bool) -> ClaimResult {
    let o = (c.check)(mutant);
    ClaimResult {
        id: c.id.clone(),
        location: c.location.clone(),
        statement: c.statement.clone(),
        verdict: o.verdict,
        strength: o.strength,
        summary: o.summary,
        correction: o.correction,
        witness: o.witness,
        proof_file: proof_file(&c.id).map(String::from),
        figure: figure_path(&c.id),
    }
}

/// The committed proof files (`proofs/`, re-checked by `detach verify`) that
/// certify part of a claim's evidence.
pub fn proof_file(id: &str) -> Option<&'static str> {
    match id {
        // κ₀ ∈ [lo, hi] and the root counts of (2.10) on both sides of it.
        "S2.case2" => Some("proofs/kappa0.json"),
        // The band: two roots below, none above, on 31 α-boxes.
        "S2.case3" => Some("proofs/critical-band.json"),
        // Disjoint certified area bounds of the printed and derived sets.
        "F1.10" | "F1.11" => {
            Some("proofs/atlas-viscous-disc-printed.json, proofs/atlas-viscous-disc-derived.json")
        }
        _ => None,
    }
}

/// Runs one claim by id, optionally as its mutant.
pub fn check(id: &str, mutant: bool) -> Result<ClaimResult, UnknownClaim> {
    registry()
        .iter()
        .find(|c| c.id == id)
        .map(|c| run_one(c, mutant))
        .ok_or_else(|| UnknownClaim(id.into()))
}

/// Decimal text to an enclosure (panics on bad text: only constants here).
pub(crate) fn dec(text: &str) -> inari::Interval {
    crate::number::param::enclose_decimal("claim parameter", text).expect("valid decimal")
}

/// `[inf, sup]` of an enclosure for a witness.
pub(crate) fn enc(x: inari::Interval) -> serde_json::Value {
    serde_json::json!([x.inf(), x.sup()])
}

/// The witness of an identity: as the test reports it when the two sides
/// agree; when they differ, the exact values of both sides at `point` (short
/// decimals and the default parameters, named in `point`) rather than at the
/// test's random rationals. Falls back to the test's own point if the two
/// sides happen to agree at `point`.
pub(crate) fn shown_at(
    id: &exact::Identity,
    point: serde_json::Value,
    printed: exact::Q,
    derived: exact::Q,
) -> serde_json::Value {
    if id.agrees() || printed == derived {
        return id.json();
    }
    let mut o = serde_json::json!({
        "identity": "differ",
        "point": point,
        "printed": printed.get().to_string(),
        "derived": derived.get().to_string(),
        "printed_minus_derived": (printed - derived).text(),
    });
    if let Some(n) = id.json().get("cleared_difference_terms") {
        o["cleared_difference_terms"] = n.clone();
    }
    o
}
