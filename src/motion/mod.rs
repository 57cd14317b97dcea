//! Certified motion in contact: validated trajectories of a scene's
//! `[dynamics]`, the first events on them (the reaction or the regions'
//! expressions changing sign, the domain left), and the equilibria and
//! singular points of its vector field.
//!
//! The stage after [`crate::scene`]: it evaluates the scene's compiled
//! θ̈ over intervals, duals and Taylor series, and knows nothing of pavings.

pub mod singular;
