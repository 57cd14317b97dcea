//! Root isolation speed: 10⁴ certified solves of (2.9) over a (κ, α) grid,
//! and the κ₀ proof.

#[path = "support/timing.rs"]
mod timing;

use detach::number::param::enclose_decimal;
use detach::roots::{prove_kappa0, solve_2_9, Budget};
use std::hint::black_box;
use timing::Group;

/// κ = 0.005·i (i = 1..100), α = −0.99 + 0.02·j (j = 0..99), as exact decimals.
fn grid() -> Vec<(detach::inari::Interval, detach::inari::Interval)> {
    let mut v = Vec::with_capacity(10_000);
    for i in 1..=100 {
        let k = enclose_decimal("kappa", &format!("{}e-3", 5 * i)).unwrap();
        for j in 0..100 {
            let a = enclose_decimal("alpha", &format!("{}e-2", 2 * j - 99)).unwrap();
            v.push((k, a));
        }
    }
    v
}

fn main() {
    let g = grid();
    let budget = Budget::default();
    let group = Group::new("roots").samples(10);
    group.bench("eq_2_9_grid_10k_solves", || {
        let mut n = 0usize;
        for &(k, a) in &g {
            n += solve_2_9(black_box(k), black_box(a), &budget)
                .unwrap()
                .roots
                .len();
        }
        n
    });
    group.bench("kappa0_proof", prove_kappa0);
}
