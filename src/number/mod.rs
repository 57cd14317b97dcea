//! Numbers: the scalar trait every formula is evaluated over (intervals,
//! decorated intervals, dual and nested dual numbers, `f64`), rigorous
//! elementary functions from CORE-MATH, and parameters entered as decimal
//! text and enclosed exactly.

pub mod elementary;
pub mod param;
pub mod scalar;
