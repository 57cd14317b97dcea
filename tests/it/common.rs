//! Helpers shared by the integration tests: running the built binary, and a
//! deterministic generator for sample points.
#![allow(dead_code)]

use std::process::{Command, Output};

/// Runs the built `detach` with `args` and waits for it.
pub fn detach(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_detach"))
        .args(args)
        .output()
        .expect("runs")
}

/// Runs `detach` with `args`, asserts success and parses stdout as JSON.
pub fn json(args: &[&str]) -> serde_json::Value {
    let out = detach(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON on stdout")
}

/// Asserts that `args` is refused with exit code 2, a stderr containing
/// `needle` and no panic; returns the stderr.
pub fn assert_bad_input(args: &[&str], needle: &str) -> String {
    let out = detach(args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: stderr {err}");
    assert!(err.contains(needle), "{args:?}: `{needle}` not in {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    err
}

/// A small deterministic generator (xorshift), enough for sample points.
pub struct Rng(pub u64);

impl Rng {
    pub fn unit(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}
