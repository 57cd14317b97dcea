//! Where bisection stops on a grid: down to a share ε of the root box's
//! width along each axis (`natural`, `centred`, `contract`).

use super::PhaseBox;

/// Bisection down to `eps` of the root box's width along each axis.
pub(super) struct Bisection {
    pub root: PhaseBox,
    pub min_width: [f64; 2],
}

impl Bisection {
    pub fn new(root: PhaseBox, eps: f64) -> Bisection {
        Bisection {
            root,
            min_width: [
                eps * (root.theta[1] - root.theta[0]),
                eps * (root.theta_dot[1] - root.theta_dot[0]),
            ],
        }
    }

    /// The box's width relative to the root's along `axis`.
    fn rel(&self, b: &PhaseBox, axis: usize) -> f64 {
        let (r, d) = if axis == 0 {
            (b.theta, self.root.theta)
        } else {
            (b.theta_dot, self.root.theta_dot)
        };
        (r[1] - r[0]) / (d[1] - d[0])
    }

    fn wide(&self, b: &PhaseBox) -> [bool; 2] {
        let (h, k) = (b.theta[1] - b.theta[0], b.theta_dot[1] - b.theta_dot[0]);
        [h > self.min_width[0], k > self.min_width[1]]
    }

    /// The relatively wider axis among those above the resolution, θ̇ on
    /// ties (slabs are then shared as long as possible).
    pub fn choose_axis(&self, b: &PhaseBox) -> Option<u8> {
        let w = self.wide(b);
        match [w[0] && b.can_split(0), w[1] && b.can_split(1)] {
            [false, false] => None,
            [true, false] => Some(0),
            [false, true] => Some(1),
            [true, true] => Some(if self.rel(b, 0) > self.rel(b, 1) {
                0
            } else {
                1
            }),
        }
    }

    pub fn at_ulp_limit(&self, b: &PhaseBox) -> bool {
        let w = self.wide(b);
        (0..2).any(|a| w[a] && !b.can_split(a))
    }
}
