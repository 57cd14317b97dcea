//! detach: certified detachment regions and root bounds for mechanical systems
//! with a unilateral constraint (A. P. Ivanov, 2008).
//!
//! Data flows one way: [`scene`] → [`pave`] / [`roots`] → [`atlas`].
//! Every claimed number is an outward-rounded [`inari`] enclosure; `f64` is
//! used only to steer searches and to draw, and such output says so.

pub mod atlas;
pub mod claims;
pub mod param;
pub mod pave;
pub mod roots;
pub mod scalar;
pub mod scene;

pub use inari;
