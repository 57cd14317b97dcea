//! The κ_crit(α) band of (2.9) as a `critical-band` proof file.
//!
//! With `s = tg(θ/2)`, (2.9) times `(1 + s²)³` is the polynomial
//! `P(s) = 8κs³ − (1 − s²)((1 + α)² s⁴ − (1 − α)²) = 8s³(κ − G(s, α))`, and
//! κ_crit(α) = sup_{s>0} G. For each α-box the proof shows, for every α in
//! it: P changes sign twice on (0, ∞) for every κ ∈ [0, lower] (so (2.9) has
//! at least two roots and Ω of §2 is disconnected), and P > 0 on [0, ∞) for
//! every κ ≥ upper (no root, Ω connected). Hence lower ≤ κ_crit(α) ≤ upper,
//! with no lemma needed: every step is an interval evaluation.

use super::numbers::{decimal, hex, Round};
use super::roots::{build_pieces, Piece, PieceKind};
use crate::number::scalar::Scalar;
use crate::roots::critical::{band_cell, g};
use crate::roots::isolate::point;
use crate::roots::RealFn;
use inari::Interval;
use serde_json::{json, Value};

/// P in the proof language, written with the operations of the prover's own
/// evaluation (`s^2*s`, `(s^2)^2`), so both sides compute the same enclosures.
pub const P_TEXT: &str = "8*kappa*s^2*s - (1 - s^2)*((1 + alpha)^2*(s^2)^2 - (1 - alpha)^2)";

/// `P(s)` with α and κ as enclosures (boxes of parameters).
struct Poly {
    alpha: Interval,
    kappa: Interval,
}

impl RealFn for Poly {
    fn eval<T: Scalar>(&self, s: T) -> T {
        let (a, k) = (T::lift(self.alpha), T::lift(self.kappa));
        let one = T::int(1);
        let s2 = s.sqr();
        T::int(8) * k * s2 * s - (one - s2) * ((one + a).sqr() * s2.sqr() - (one - a).sqr())
    }
}

/// Share of the band's width given up on each side, so that the signs hold
/// with room to spare and the evidence stays small (a tight upper bound would
/// need ever narrower exclusion pieces around the maximum of G).
const MARGIN: f64 = 0.02;

fn iv(lo: f64, hi: f64) -> Interval {
    Interval::try_from((lo, hi)).expect("ordered")
}

/// The maximiser of G(·, α) on (0, 1] in floating point (steering only).
fn argmax_g(alpha: f64) -> f64 {
    let gf = |s: f64| g(s, point(alpha));
    let (mut lo, mut hi) = (1e-3, 1.0);
    for _ in 0..200 {
        let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
        if gf(m1) < gf(m2) {
            lo = m1;
        } else {
            hi = m2;
        }
    }
    0.5 * (lo + hi)
}

/// One α-box: the claimed bounds (decimal text) and the evidence.
fn cell(a0: f64, a1: f64) -> (Value, Value) {
    let alpha = iv(a0, a1);
    let band = band_cell(alpha, 1e-7);
    // Lower: a point where P < 0 for every α of the box and κ ≤ lower.
    let x1 = argmax_g(a0);
    let slack = MARGIN * (band.upper - band.lower).max(1e-9);
    let mut lower = decimal(
        (g(point(x1), point(a0)).inf() - slack).max(0.0),
        10,
        Round::Down,
    );
    let (mut points, lower_ok) = (Vec::new(), band.lower > 0.0);
    if lower_ok {
        let k = crate::number::param::enclose_decimal("lower", &lower).expect("decimal we wrote");
        let p = Poly {
            alpha,
            kappa: iv(0.0, k.sup()),
        }
        .eval(point(x1));
        if p.sup() < 0.0 {
            points = vec![0.0, x1, 2.0];
        } else {
            lower = "0".into();
        }
    } else {
        lower = "0".into();
    }
    // Upper: P > 0 on [0, ∞) for every κ ≥ upper.
    let upper = decimal(band.upper + slack, 10, Round::Up);
    let u = crate::number::param::enclose_decimal("upper", &upper).expect("decimal we wrote");
    let pieces: Vec<Piece> = build_pieces(
        &Poly {
            alpha,
            kappa: iv(u.inf(), f64::INFINITY),
        },
        0.0,
        f64::INFINITY,
        &[],
    );
    let claim = json!({
        "alpha": [decimal(a0, 17, Round::Down), decimal(a1, 17, Round::Up)],
        "lower": lower,
        "upper": upper,
    });
    let evidence = json!({
        "points": points.iter().map(|&x| hex(x)).collect::<Vec<_>>(),
        "pieces": pieces.iter().map(super::roots::piece_json).collect::<Vec<_>>(),
    });
    debug_assert!(pieces.iter().all(|p| p.kind != PieceKind::Undecided));
    (claim, evidence)
}

/// The band on `n` α-boxes of `[0, 1 − 1/n]`; α = 1 is the `kappa0` proof.
pub fn critical_band_proof(n: usize) -> Value {
    let edge = |i: usize| i as f64 / n as f64;
    let (claims, evidence): (Vec<Value>, Vec<Value>) =
        (0..n - 1).map(|i| cell(edge(i), edge(i + 1))).unzip();
    json!({
        "format": "detach-proof/1",
        "claim": "critical-band",
        "title": format!(
            "the κ_crit(α) band of (2.9) on {} α-boxes of [0, {}]: at least two roots below it, none above",
            n - 1,
            edge(n - 1)
        ),
        "producer": super::producer(),
        "statement": {
            "equation": "2.9",
            "paper": "§2, case 3: (2.9) with s = tg(θ/2), times (1 + s²)³: \
                      P(s) = 8κs³ − (1 − s²)((1 + α)²s⁴ − (1 − α)²) = 8s³(κ − G(s, α)); \
                      κ_crit(α) = sup_{s>0} G(s, α); α = 1 is proofs/kappa0.json",
            "variable": "s",
            "parameters": {},
            "definitions": [],
            "function": P_TEXT,
            "cells": claims,
        },
        "evidence": { "cells": evidence },
    })
}
