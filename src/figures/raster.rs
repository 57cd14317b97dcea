//! Conservative rasterisation of a paving onto a pixel grid.
//!
//! A pixel gets the class of a partition cell only when **every** leaf whose
//! interior meets the pixel's interior is proved in that cell. The leaves tile
//! the root box, so the whole pixel then lies in the cell. Any other pixel is
//! shown as undefined (if an undefined leaf meets it) or undecided: the
//! picture may exaggerate uncertainty, it never overclaims. Pixels are boxes
//! with double edges, compared exactly with the leaves' double edges.

use crate::pave::{Label, Leaf, Paving, PhaseBox};
use crate::scene::Cell;

/// What one leaf (or pixel) is drawn as.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Class {
    /// Ω ∩ Ω₀: contact persists.
    Persists,
    /// Ω̄ ∩ Ω̄₀: the constraint is released.
    Released,
    /// Ω̄ ∩ Ω₀: paradox of non-uniqueness.
    NonUniqueness,
    /// Ω ∩ Ω̄₀: paradox of non-existence.
    NonExistence,
    /// Not both constraints decided (at the paving's resolution, or because
    /// the pixel straddles several leaves of different classes).
    Undecided,
    /// A formula may be undefined somewhere on the leaf (e.g. on sin θ = 0).
    Undefined,
}

impl Class {
    /// All classes, the four cells first (in [`Cell::ALL`] order).
    pub const ALL: [Class; 6] = [
        Class::Persists,
        Class::Released,
        Class::NonUniqueness,
        Class::NonExistence,
        Class::Undecided,
        Class::Undefined,
    ];

    /// The four partition cells.
    pub const CELLS: [Class; 4] = [
        Class::Persists,
        Class::Released,
        Class::NonUniqueness,
        Class::NonExistence,
    ];

    /// The partition cell a class shows (the four cells).
    pub fn cell(self) -> Option<Cell> {
        match self {
            Class::Persists => Some(Cell::OmegaAndOmega0),
            Class::Released => Some(Cell::NeitherOmegaNorOmega0),
            Class::NonUniqueness => Some(Cell::Omega0NotOmega),
            Class::NonExistence => Some(Cell::OmegaNotOmega0),
            Class::Undecided | Class::Undefined => None,
        }
    }

    /// True for the four certified cells.
    pub fn is_cell(self) -> bool {
        self.cell().is_some()
    }

    fn index(self) -> usize {
        Class::ALL.iter().position(|&c| c == self).expect("listed")
    }

    /// The class of a leaf of a two-constraint paving (constraint 0 = Ω,
    /// constraint 1 = Ω₀). A cell only when both labels are decided.
    pub fn of_leaf(leaf: &Leaf) -> Class {
        if leaf.labels.contains(&Label::Undefined) {
            return Class::Undefined;
        }
        Class::CELLS
            .into_iter()
            .find(|c| c.cell().is_some_and(|cell| cell.spec().proved_in(leaf)))
            .unwrap_or(Class::Undecided)
    }

    /// Short symbolic name, e.g. `Ω∩Ω₀`.
    pub fn symbol(self) -> &'static str {
        match self.cell() {
            Some(cell) => cell.label(),
            None if self == Class::Undefined => "undefined",
            None => "undecided",
        }
    }

    /// What the class means.
    pub fn meaning(self) -> &'static str {
        match self {
            Class::Persists => "contact persists",
            Class::Released => "constraint released",
            Class::NonUniqueness => "non-uniqueness paradox",
            Class::NonExistence => "non-existence paradox",
            Class::Undecided => "not decided at this resolution",
            Class::Undefined => "formula singular (e.g. sin θ = 0)",
        }
    }

    /// Fill colour: Paul Tol's colour-blind-safe "light" and "muted" schemes
    /// for the cells, light grey for undecided, near-white (drawn hatched)
    /// for undefined.
    pub fn rgb(self) -> (u8, u8, u8) {
        match self {
            Class::Persists => (0x77, 0xAA, 0xDD),
            Class::Released => (0xEE, 0xDD, 0x88),
            Class::NonUniqueness => (0xEE, 0x88, 0x66),
            Class::NonExistence => (0xAA, 0x44, 0x99),
            Class::Undecided => (0xC8, 0xC8, 0xC8),
            Class::Undefined => (0xF7, 0xF7, 0xF7),
        }
    }
}

/// A paving rasterised on `width × height` pixels covering its root box;
/// row 0 is the top (largest θ̇), column 0 the left (smallest θ).
///
/// Pixel `(col, row)` *is* the box `[θ_col, θ_col+1] × [θ̇_row+1, θ̇_row]` of
/// the stored edge lists (doubles, increasing in θ, decreasing in θ̇, the
/// first and last equal to the root box's edges). Leaves are compared with
/// these edges exactly, so no rounding enters the classification.
#[derive(Clone, Debug)]
pub struct Raster {
    pub width: u32,
    pub height: u32,
    pub root: PhaseBox,
    /// `width + 1` column edges in θ, increasing.
    pub theta_edges: Vec<f64>,
    /// `height + 1` row edges in θ̇, decreasing (row 0 at the top).
    pub theta_dot_edges: Vec<f64>,
    /// Row-major; `None` only where no leaf meets the pixel (never inside the
    /// root box of a valid paving).
    pub pixels: Vec<Option<Class>>,
}

impl Raster {
    pub fn get(&self, col: u32, row: u32) -> Option<Class> {
        self.pixels[(row * self.width + col) as usize]
    }

    /// The pixel's box in the phase plane.
    pub fn pixel_box(&self, col: u32, row: u32) -> PhaseBox {
        let (c, r) = (col as usize, row as usize);
        PhaseBox {
            theta: [self.theta_edges[c], self.theta_edges[c + 1]],
            theta_dot: [self.theta_dot_edges[r + 1], self.theta_dot_edges[r]],
        }
    }

    /// Number of pixels of each class, in the order of [`Class::ALL`].
    pub fn counts(&self) -> [usize; 6] {
        let mut n = [0; 6];
        for c in self.pixels.iter().flatten() {
            n[c.index()] += 1;
        }
        n
    }
}

/// `n + 1` edges from `lo` to `hi` (exactly at both ends), monotone.
fn edges(lo: f64, hi: f64, n: u32) -> Vec<f64> {
    let mut e: Vec<f64> = (0..=n)
        .map(|i| lo + (hi - lo) * f64::from(i) / f64::from(n))
        .collect();
    e[n as usize] = hi;
    // Rounding is monotone, but keep the last step monotone too.
    for i in (0..n as usize).rev() {
        e[i] = e[i].min(e[i + 1]);
    }
    e
}

/// Rasterises `paving` on a `width × height` grid over its root box.
pub fn rasterize(paving: &Paving, width: u32, height: u32) -> Raster {
    let root = paving.root;
    let xs = edges(root.theta[0], root.theta[1], width);
    let mut ys = edges(root.theta_dot[0], root.theta_dot[1], height);
    ys.reverse();
    let (w, h) = (width as usize, height as usize);
    // Bit i set: some leaf of class Class::ALL[i] meets the pixel's interior.
    let mut bits = vec![0u8; w * h];
    for leaf in &paving.leaves {
        let bit = 1u8 << Class::of_leaf(leaf).index();
        let b = &leaf.bx;
        // Column i meets (θ_lo, θ_hi) iff xs[i] < θ_hi and xs[i+1] > θ_lo.
        let c0 = xs[1..].partition_point(|&e| e <= b.theta[0]);
        let c1 = xs[..w].partition_point(|&e| e < b.theta[1]);
        // Row j meets (θ̇_lo, θ̇_hi) iff ys[j+1] < θ̇_hi and ys[j] > θ̇_lo.
        let r0 = ys[1..].partition_point(|&e| e >= b.theta_dot[1]);
        let r1 = ys[..h].partition_point(|&e| e > b.theta_dot[0]);
        for row in r0..r1 {
            for m in &mut bits[row * w + c0..row * w + c1.max(c0)] {
                *m |= bit;
            }
        }
    }
    let undefined = 1u8 << Class::Undefined.index();
    let pixels = bits
        .into_iter()
        .map(|m| match m.count_ones() {
            0 => None,
            1 => Some(Class::ALL[m.trailing_zeros() as usize]),
            _ if m & undefined != 0 => Some(Class::Undefined),
            _ => Some(Class::Undecided),
        })
        .collect();
    Raster {
        width,
        height,
        root,
        theta_edges: xs,
        theta_dot_edges: ys,
        pixels,
    }
}

/// A rectangle of pixels `[x0, x1) × [y0, y1)` of one class.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelRect {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
    pub class: Class,
}

/// Covers the raster exactly with rectangles: runs of equal pixels in each
/// row, merged downwards while the run below is identical.
pub fn merge_rects(r: &Raster) -> Vec<PixelRect> {
    let mut done = Vec::new();
    // Open rectangles from the previous row, keyed by (x0, x1, class), sorted by x0.
    let mut open: Vec<PixelRect> = Vec::new();
    for row in 0..r.height {
        let mut runs = Vec::new();
        let mut col = 0;
        while col < r.width {
            let c = r.get(col, row);
            let start = col;
            while col < r.width && r.get(col, row) == c {
                col += 1;
            }
            if let Some(class) = c {
                runs.push((start, col, class));
            }
        }
        let mut next = Vec::with_capacity(runs.len());
        let mut k = 0;
        for (x0, x1, class) in runs {
            while k < open.len() && open[k].x0 < x0 {
                done.push(open[k]);
                k += 1;
            }
            if k < open.len() && open[k].x0 == x0 && open[k].x1 == x1 && open[k].class == class {
                let mut o = open[k];
                o.y1 = row + 1;
                next.push(o);
                k += 1;
            } else {
                next.push(PixelRect {
                    x0,
                    y0: row,
                    x1,
                    y1: row + 1,
                    class,
                });
            }
        }
        done.extend_from_slice(&open[k..]);
        open = next;
    }
    done.extend(open);
    done
}
