//! Tick positions and compact tick labels (markup for [`super::Figure`]
//! text: `10^{308}` is typeset as a power).

use std::f64::consts::PI;

/// About `n` "nice" tick values (1, 2 or 5 × 10ᵏ apart) in `[lo, hi]`, and
/// their step. Empty for an empty or non-finite range.
pub fn nice_ticks(lo: f64, hi: f64, n: usize) -> (Vec<f64>, f64) {
    let span = hi - lo;
    if !(lo.is_finite() && hi.is_finite() && span.is_finite() && span > 0.0) || n == 0 {
        return (Vec::new(), 0.0);
    }
    let raw = span / n as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|&s| s >= raw)
        .unwrap_or(10.0 * mag);
    let first = (lo / step).ceil();
    let last = (hi / step).floor();
    let mut v = Vec::new();
    let mut k = first;
    while k <= last && v.len() <= 4 * n + 2 {
        v.push(k * step);
        k += 1.0;
    }
    (v, step)
}

/// A true minus sign.
fn minus(s: String) -> String {
    s.replace('-', "−")
}

/// Label of tick `v` among ticks `step` apart: plain decimals with just
/// enough digits to tell neighbours apart for moderate magnitudes, and
/// `m×10^{e}` with at most 3 significant digits otherwise (so a range up to
/// 1e308 gets short labels, never 300 digits).
pub fn tick_label(v: f64, step: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return if v.is_finite() {
            "0".into()
        } else {
            format!("{v}")
        };
    }
    let a = v.abs();
    let step = if step.is_finite() && step > 0.0 {
        step
    } else {
        a
    };
    if a < 1e-9 * step {
        return "0".into(); // rounding noise of a tick at zero
    }
    if (1e-3..1e5).contains(&a) && step >= 1e-4 {
        let decimals = (-step.log10().floor()).clamp(0.0, 6.0) as usize;
        let decimals = if (step / 10f64.powf(step.log10().floor()) - 2.5).abs() < 1e-9 {
            decimals + 1
        } else {
            decimals
        };
        let s = format!("{v:.decimals$}");
        return minus(
            if s.starts_with("-0") && s.trim_start_matches(['-', '0', '.']).is_empty() {
                "0".into()
            } else {
                s
            },
        );
    }
    let e = a.log10().floor();
    // Mantissa digits: enough for the step, at most 3 significant.
    let digits = ((e - step.log10().floor()).max(0.0) as usize).min(2);
    let mut m = v / 10f64.powf(e);
    let mut e = e as i32;
    let r = 10f64.powi(digits as i32);
    m = (m * r).round() / r;
    if m.abs() >= 10.0 {
        m /= 10.0;
        e += 1;
    }
    let ms = format!("{m:.digits$}");
    let ms = if ms.contains('.') {
        ms.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        ms
    };
    let exp = minus(e.to_string());
    minus(match ms.as_str() {
        "1" => format!("10^{{{exp}}}"),
        "-1" => format!("-10^{{{exp}}}"),
        _ => format!("{ms}×10^{{{exp}}}"),
    })
}

/// θ ticks: multiples of π/4 labelled `π/4`, `−3π/4`, … when at least three
/// fall in `[lo, hi]` (the ends included within 10⁻⁹, and then placed on
/// the ends), plain "nice" numbers otherwise (a narrow window).
pub fn theta_ticks(lo: f64, hi: f64) -> Vec<(f64, String)> {
    let q = PI / 4.0;
    let tol = 1e-9;
    let (k0, k1) = ((lo / q).ceil() as i64 - 1, (hi / q).floor() as i64 + 1);
    let pis: Vec<(f64, String)> = (k0..=k1)
        .map(|k| (k as f64 * q, k))
        .filter(|&(t, _)| t >= lo - tol && t <= hi + tol)
        .map(|(t, k)| (t.clamp(lo, hi), pi_label(k)))
        .collect();
    if pis.len() >= 3 {
        return pis;
    }
    let (ticks, step) = nice_ticks(lo, hi, 8);
    ticks
        .into_iter()
        .map(|t| (t, tick_label(t, step)))
        .collect()
}

/// Label of `k·π/4` in lowest terms.
fn pi_label(k: i64) -> String {
    let sign = if k < 0 { "−" } else { "" };
    let g = gcd(k.unsigned_abs(), 4);
    match (k.unsigned_abs() / g, 4 / g) {
        (0, _) => "0".into(),
        (1, 1) => format!("{sign}π"),
        (n, 1) => format!("{sign}{n}π"),
        (1, d) => format!("{sign}π/{d}"),
        (n, d) => format!("{sign}{n}π/{d}"),
    }
}

fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figures::plain;

    #[test]
    fn labels_are_short_for_extreme_ranges() {
        for (lo, hi) in [
            (0.0, 1e308),
            (0.0, f64::MAX),
            (-1e-300, 1e-300),
            (0.0, 0.25),
            (-10.0, 10.0),
            (9.8, 10.0),
            (1e5, 1e9),
            (0.0, 3e-7),
        ] {
            let (ticks, step) = nice_ticks(lo, hi, 10);
            assert!(ticks.len() >= 2, "{lo}..{hi}");
            let labels: Vec<String> = ticks.iter().map(|&v| tick_label(v, step)).collect();
            for l in &labels {
                assert!(plain(l).chars().count() <= 10, "{lo}..{hi}: {l}");
            }
            // Neighbouring ticks read differently.
            for w in labels.windows(2) {
                assert_ne!(w[0], w[1], "{lo}..{hi}");
            }
        }
        assert_eq!(tick_label(2e307, 1e307), "2×10^{307}");
        assert_eq!(tick_label(1e4, 1e3), "10000");
        assert_eq!(tick_label(-2.0, 2.0), "−2");
        assert_eq!(tick_label(0.05, 0.05), "0.05");
        assert_eq!(tick_label(1e-5, 1e-5), "10^{−5}");
        assert_eq!(tick_label(2.3e291, 1e307), "0");
    }

    #[test]
    fn theta_ticks_are_multiples_of_pi_in_lowest_terms() {
        let labels = |lo: f64, hi: f64| -> Vec<String> {
            theta_ticks(lo, hi).into_iter().map(|t| t.1).collect()
        };
        assert_eq!(
            labels(-PI, PI),
            ["−π", "−3π/4", "−π/2", "−π/4", "0", "π/4", "π/2", "3π/4", "π"]
        );
        // The ends of [0, π] (π rounded to a double) get their ticks.
        assert_eq!(labels(0.0, PI), ["0", "π/4", "π/2", "3π/4", "π"]);
        assert_eq!(labels(0.05, 3.09), ["π/4", "π/2", "3π/4"]);
        // A window narrower than π/2: plain numbers.
        let narrow = labels(0.9, 1.2);
        assert!(narrow.len() >= 5 && narrow.iter().all(|l| !l.contains('π')));
        assert!(narrow.contains(&"1.00".to_string()), "{narrow:?}");
    }
}
