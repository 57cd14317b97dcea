//! The paving methods, listed in one place: everything that runs "every
//! method" (`detach methods`) iterates [`Method::ALL`].

use super::{pave_scene_in, PaveError, PaveOptions, Paving};
use crate::scene::{Domain, Scene, Variant};
use serde::Serialize;
use std::fmt;
use std::str::FromStr;

/// A way of paving a scene's regions; each produces the same [`Paving`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Natural interval extension over boxes, θ-slab trigonometry shared.
    Natural,
}

impl Method {
    pub const ALL: &'static [Method] = &[Method::Natural];

    pub fn name(self) -> &'static str {
        match self {
            Method::Natural => "natural",
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Method::ALL
            .iter()
            .copied()
            .find(|m| m.name() == s)
            .ok_or_else(|| {
                let names: Vec<_> = Method::ALL.iter().map(|m| m.name()).collect();
                format!("unknown method `{s}` (known: {})", names.join(", "))
            })
    }
}

/// Paves Ω and Ω₀ of `scene` over `domain` with `method`.
pub fn pave_with(
    method: Method,
    scene: &Scene,
    variant: Variant,
    domain: &Domain,
    opts: PaveOptions,
    progress: impl FnMut(u32, usize, usize),
) -> Result<Paving, PaveError> {
    match method {
        Method::Natural => pave_scene_in(scene, variant, domain, opts, progress),
    }
}
