//! The tangency κ = κ₀ of (2.10): a double root, where interval Newton cannot
//! prove uniqueness, and the isolator's behaviour at κ = κ₀(1 ± 10⁻ᵏ).

use super::equations::{solve_2_10, EquationRoots};
use super::isolate::{ulps_between, Budget, RootEnclosure};
use super::kappa0::{prove_kappa0, Bound, Kappa0Class, Kappa0Proof};
use crate::number::param::enclose_decimal;
use inari::{const_interval, Interval};
use serde::Serialize;
use std::time::Instant;

/// (2.10) solved with κ = the enclosure of κ₀ itself.
#[derive(Clone, Debug, Serialize)]
pub struct DoubleRoot {
    pub kappa: Bound,
    /// Hull of the returned enclosures: contains every root μ > 0 of (2.10)
    /// for every κ in the enclosure of κ₀, in particular the double root μ*.
    pub enclosure: Bound,
    pub enclosure_width: f64,
    /// No enclosure is claimed unique (Newton cannot prove a double root).
    pub none_unique: bool,
    /// μ*'s enclosure (from the κ₀ proof) lies in `enclosure`.
    pub contains_mu_star: bool,
    /// The statement, and what makes it true.
    pub statement: String,
    pub isolation: EquationRoots,
}

/// One line of the table κ = κ₀(1 + sign·10⁻ᵏ).
#[derive(Clone, Debug, Serialize)]
pub struct TangencyRow {
    pub k: i32,
    /// −1: below κ₀ (two roots expected); +1: above (none).
    pub sign: i32,
    pub kappa: Bound,
    /// What the κ₀ proof says for every κ in the enclosure.
    pub by_kappa0: Kappa0Class,
    /// What the isolator alone certified.
    pub outcome: Outcome,
    pub unique_roots: usize,
    pub undecided: usize,
    /// Widest returned enclosure, in doubles and absolute.
    pub max_width_ulps: u64,
    pub max_width: f64,
    pub evaluations: usize,
    pub bisections: usize,
    pub newton_steps: usize,
    /// Wall time in microseconds (varies between runs).
    pub time_us: f64,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// Complete, no root.
    NoRootProved,
    /// Complete, exactly two unique (simple) roots.
    TwoUnique,
    Undecided,
}

#[derive(Clone, Debug, Serialize)]
pub struct TangencyReport {
    pub kappa0: Kappa0Proof,
    pub double_root: DoubleRoot,
    pub rows: Vec<TangencyRow>,
}

fn hull(roots: &[RootEnclosure]) -> Option<Interval> {
    roots
        .iter()
        .map(|r| r.interval())
        .reduce(|a, b| a.convex_hull(b))
}

/// (2.10) at κ ∈ \[κ₀\] (the enclosure of κ₀).
pub fn double_root(proof: &Kappa0Proof, budget: &Budget) -> DoubleRoot {
    let k = proof.kappa0.interval();
    let isolation = solve_2_10(k, budget).expect("κ₀ > 0");
    let h = hull(&isolation.roots).unwrap_or(Interval::EMPTY);
    let contains_mu_star = !h.is_empty() && proof.mu_star.interval().subset(h);
    DoubleRoot {
        kappa: proof.kappa0,
        enclosure: if h.is_empty() {
            Bound { lo: 0.0, hi: 0.0 }
        } else {
            Bound::of(h)
        },
        enclosure_width: if h.is_empty() { 0.0 } else { h.wid() },
        none_unique: isolation.roots.iter().all(|r| !r.is_unique()),
        contains_mu_star,
        statement: "for every κ in the enclosure of κ₀, every root μ > 0 of (2.10) lies in the \
                    enclosure (the rest of (0, ∞) is proved root-free); at κ = κ₀ exactly the only \
                    root is μ* (in the enclosure), double: p'(μ*) = 0, p''(μ*) < 0 (κ₀ proof)"
            .into(),
        isolation,
    }
}

/// The table for k = 1..=k_max, both signs.
pub fn tangency_scan(k_max: i32, budget: &Budget) -> TangencyReport {
    let proof = prove_kappa0();
    let dr = double_root(&proof, budget);
    let k0 = proof.kappa0.interval();
    let one = const_interval!(1.0, 1.0);
    let mut rows = Vec::new();
    for k in 1..=k_max {
        let eps = enclose_decimal("eps", &format!("1e-{k}")).expect("valid decimal");
        for sign in [-1, 1] {
            let kappa = if sign < 0 {
                k0 * (one - eps)
            } else {
                k0 * (one + eps)
            };
            let t = Instant::now();
            let r = solve_2_10(kappa, budget).expect("κ > 0");
            let time_us = t.elapsed().as_secs_f64() * 1e6;
            let unique = r.unique_count();
            let outcome = if r.complete && r.roots.is_empty() {
                Outcome::NoRootProved
            } else if r.complete && unique == 2 {
                Outcome::TwoUnique
            } else {
                Outcome::Undecided
            };
            let max_width_ulps = r
                .roots
                .iter()
                .map(|x| ulps_between(x.lo, x.hi))
                .max()
                .unwrap_or(0);
            let max_width = r.roots.iter().map(|x| x.hi - x.lo).fold(0.0, f64::max);
            rows.push(TangencyRow {
                k,
                sign,
                kappa: Bound::of(kappa),
                by_kappa0: proof.classify(kappa),
                outcome,
                unique_roots: unique,
                undecided: r.roots.len() - unique,
                max_width_ulps,
                max_width,
                evaluations: r.stats.evaluations,
                bisections: r.stats.bisections,
                newton_steps: r.stats.newton_steps,
                time_us,
            });
        }
    }
    TangencyReport {
        kappa0: proof,
        double_root: dr,
        rows,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn double_root_is_enclosed_and_never_unique() {
        let proof = prove_kappa0();
        let dr = double_root(&proof, &Budget::default());
        assert!(dr.none_unique, "{dr:?}");
        assert!(dr.contains_mu_star);
        // 1/√3 in closed form lies in the enclosure.
        let mu = const_interval!(1.0, 1.0) / const_interval!(3.0, 3.0).sqrt();
        assert!(mu.subset(dr.enclosure.interval()));
        assert!(dr.enclosure_width < 1e-6);
    }

    #[test]
    fn near_tangency_small_k_is_certified() {
        let rep = tangency_scan(3, &Budget::default());
        for row in &rep.rows {
            let want = if row.sign < 0 {
                Outcome::TwoUnique
            } else {
                Outcome::NoRootProved
            };
            assert_eq!(row.outcome, want, "{row:?}");
        }
    }
}
