//! The timing of the bench binaries: each case runs in batches sized to a
//! share of a fixed time, and the time per call is reported as the median
//! over the batches, with the fastest and slowest batch. `cargo bench --bench
//! NAME -- TEXT` runs only the cases whose name contains TEXT.

// Shared by several bench binaries; each uses part of it.
#![allow(dead_code)]

use std::hint::black_box;
use std::time::{Duration, Instant};

/// Cases that share a name prefix and a sampling plan.
pub struct Group {
    name: String,
    samples: u32,
    time: Duration,
    filter: Option<String>,
}

impl Group {
    /// 20 batches in about 2 s per case.
    pub fn new(name: &str) -> Group {
        // `cargo bench` passes `--bench`; the first other argument filters.
        let filter = std::env::args().skip(1).find(|a| !a.starts_with("--"));
        Group {
            name: name.into(),
            samples: 20,
            time: Duration::from_secs(2),
            filter,
        }
    }

    pub fn samples(mut self, n: u32) -> Group {
        self.samples = n.max(3);
        self
    }

    pub fn time(mut self, t: Duration) -> Group {
        self.time = t;
        self
    }

    /// Whether the command line's filter selects `case`.
    pub fn wants(&self, case: &str) -> bool {
        let id = format!("{}/{case}", self.name);
        self.filter.as_ref().is_none_or(|t| id.contains(t.as_str()))
    }

    /// Times `f` and prints one line: `group/case  median  [min … max]`;
    /// returns the median seconds per call (`None`: filtered out).
    pub fn bench<R>(&self, case: &str, mut f: impl FnMut() -> R) -> Option<f64> {
        if !self.wants(case) {
            return None;
        }
        let id = format!("{}/{case}", self.name);
        let t = Instant::now();
        black_box(f());
        let once = t.elapsed().as_secs_f64().max(1e-9);
        let share = self.time.as_secs_f64() / f64::from(self.samples);
        let batch = (share / once).clamp(1.0, 1e9) as u64;
        let mut per_call: Vec<f64> = (0..self.samples)
            .map(|_| {
                let t = Instant::now();
                for _ in 0..batch {
                    black_box(f());
                }
                t.elapsed().as_secs_f64() / batch as f64
            })
            .collect();
        per_call.sort_by(f64::total_cmp);
        let median = per_call[per_call.len() / 2];
        println!(
            "{id:<52} {:>10}  [{} … {}]",
            seconds(median),
            seconds(per_call[0]),
            seconds(per_call[per_call.len() - 1])
        );
        Some(median)
    }
}

/// `12.3 ns`, `4.56 µs`, `7.89 ms`, `1.23 s`.
pub fn seconds(s: f64) -> String {
    let (v, unit) = match s {
        s if s < 1e-6 => (s * 1e9, "ns"),
        s if s < 1e-3 => (s * 1e6, "µs"),
        s if s < 1.0 => (s * 1e3, "ms"),
        s => (s, "s"),
    };
    format!("{v:.3} {unit}")
}

/// The load average (1, 5, 15 minutes) as `/proc/loadavg` says it.
pub fn load() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .unwrap_or_default()
        .split_whitespace()
        .take(3)
        .collect::<Vec<_>>()
        .join(" ")
}

/// The time now in UTC, to the minute (`2026-11-28T03:30Z`).
pub fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, rem) = ((secs / 86_400) as i64, secs % 86_400);
    // Days since 1970-01-01 to a civil date (the proleptic Gregorian
    // calendar, eras of 400 years).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}Z",
        rem / 3600,
        rem % 3600 / 60
    )
}
