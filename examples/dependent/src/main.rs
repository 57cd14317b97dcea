//! Paves the disc on ice (§3) with c₀ = 1 and p_ψ = 1.5, by default with the
//! `slices` method, and prints certified bounds on the area of Ω₀ and of the
//! non-uniqueness cell Ω̄∩Ω₀, through the library's one door, `detach::api`.
//!
//! `cargo run --release -- [METHOD]`, METHOD one of natural, centred,
//! contract, slices (default slices).

use detach::api::{Cell, Method, PaveRequest, Problem};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let method: Method = match std::env::args().nth(1) {
        Some(name) => name.parse()?,
        None => Method::Slices,
    };
    // Parameters are decimal text, enclosed exactly.
    let disc = Problem::load("ice-disc", &[("c0", "1"), ("p_psi", "1.5")])?;
    let paved = disc.pave(&PaveRequest {
        eps: 1.0 / 256.0,
        max_boxes: 1_000_000,
        method,
        ..PaveRequest::default()
    })?;
    println!(
        "ice-disc, c0 = 1, p_psi = 1.5, method {method}: {} leaves, stopped: {}",
        paved.paving.leaves.len(),
        paved.paving.stop
    );
    for a in &paved.areas {
        if [Cell::Omega0, Cell::Omega0NotOmega].contains(&a.cell) {
            println!(
                "  area of {} ∈ [{}, {}] ({})",
                a.cell.label(),
                a.inner,
                a.outer,
                a.how.describe()
            );
        }
    }
    Ok(())
}
