//! Vector regions: the union of the leaves of each class as closed rings,
//! for the SVG (which then zooms cleanly and stays small).
//!
//! The leaves tile the root box. Their edges give a (non-uniform) grid in
//! which every leaf is a block of cells; each cell takes its leaf's class,
//! and the boundary of each class is traced along cell sides. Every side
//! between two cells of different classes is used exactly once, so the
//! rings filled with the even-odd rule are exactly the union of the leaves
//! of that class. A paving too fine for the grid budget is traced on the
//! conservative raster instead ([`super::rasterize`]): its cell pixels lie
//! inside leaves proved in that cell.

use super::raster::{Class, Raster};
use crate::pave::Paving;
use std::collections::HashMap;

/// Most cells of the leaf-edge grid (bytes of memory, one per cell).
const MAX_GRID_CELLS: usize = 1 << 24;

/// The rings of one class in phase-plane coordinates `(θ, θ̇)`.
#[derive(Clone, Debug)]
pub struct Region {
    pub class: Class,
    pub rings: Vec<Vec<(f64, f64)>>,
}

/// Whether [`vector_regions`] traced the leaves exactly or fell back to the
/// raster.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tracing {
    ExactLeaves,
    Raster,
}

/// The union of the leaves of each class present, as rings (even-odd rule).
/// Falls back to the pixels of `raster` when the leaf-edge grid would exceed
/// the budget (only for pavings much finer than the picture).
pub fn vector_regions(paving: &Paving, raster: &Raster) -> (Vec<Region>, Tracing) {
    let mut xs: Vec<f64> = paving
        .leaves
        .iter()
        .flat_map(|l| l.bx.theta)
        .chain(paving.root.theta)
        .collect();
    let mut ys: Vec<f64> = paving
        .leaves
        .iter()
        .flat_map(|l| l.bx.theta_dot)
        .chain(paving.root.theta_dot)
        .collect();
    for v in [&mut xs, &mut ys] {
        v.sort_by(f64::total_cmp);
        v.dedup();
    }
    let (nx, ny) = (xs.len() - 1, ys.len() - 1);
    if nx.saturating_mul(ny) > MAX_GRID_CELLS {
        let xs = raster.theta_edges.clone();
        // Raster rows run top-down; the grid runs bottom-up.
        let ys: Vec<f64> = raster.theta_dot_edges.iter().rev().copied().collect();
        let (w, h) = (raster.width as usize, raster.height as usize);
        let mut grid = vec![u8::MAX; w * h];
        for j in 0..h {
            for i in 0..w {
                if let Some(c) = raster.get(i as u32, (h - 1 - j) as u32) {
                    grid[j * w + i] = class_index(c);
                }
            }
        }
        return (trace(&grid, &xs, &ys), Tracing::Raster);
    }
    let mut grid = vec![u8::MAX; nx * ny];
    let pos = |v: &[f64], x: f64| v.partition_point(|&e| e < x);
    for leaf in &paving.leaves {
        let c = class_index(Class::of_leaf(leaf));
        let (i0, i1) = (pos(&xs, leaf.bx.theta[0]), pos(&xs, leaf.bx.theta[1]));
        let (j0, j1) = (
            pos(&ys, leaf.bx.theta_dot[0]),
            pos(&ys, leaf.bx.theta_dot[1]),
        );
        for j in j0..j1 {
            grid[j * nx + i0..j * nx + i1].fill(c);
        }
    }
    (trace(&grid, &xs, &ys), Tracing::ExactLeaves)
}

fn class_index(c: Class) -> u8 {
    Class::ALL.iter().position(|&k| k == c).expect("listed") as u8
}

/// Traces the boundary of every class of `grid` (`nx × ny` cells, row-major
/// from the bottom, cell `(i, j)` = `[xs[i], xs[i+1]] × [ys[j], ys[j+1]]`).
fn trace(grid: &[u8], xs: &[f64], ys: &[f64]) -> Vec<Region> {
    let (nx, ny) = (xs.len() - 1, ys.len() - 1);
    let at = |i: isize, j: isize| -> u8 {
        if i < 0 || j < 0 || i >= nx as isize || j >= ny as isize {
            u8::MAX
        } else {
            grid[j as usize * nx + i as usize]
        }
    };
    // Directed unit sides per class, the class on their left.
    type V = (u32, u32);
    let mut sides: Vec<Vec<(V, V)>> = vec![Vec::new(); Class::ALL.len()];
    for j in 0..ny as isize {
        for i in 0..nx as isize {
            let c = at(i, j);
            if c == u8::MAX {
                continue;
            }
            let (x0, x1, y0, y1) = (i as u32, i as u32 + 1, j as u32, j as u32 + 1);
            let s = &mut sides[c as usize];
            if at(i, j - 1) != c {
                s.push(((x0, y0), (x1, y0)));
            }
            if at(i + 1, j) != c {
                s.push(((x1, y0), (x1, y1)));
            }
            if at(i, j + 1) != c {
                s.push(((x1, y1), (x0, y1)));
            }
            if at(i - 1, j) != c {
                s.push(((x0, y1), (x0, y0)));
            }
        }
    }
    let mut out = Vec::new();
    for (k, s) in sides.into_iter().enumerate() {
        if s.is_empty() {
            continue;
        }
        let mut from: HashMap<V, Vec<usize>> = HashMap::new();
        for (e, (a, _)) in s.iter().enumerate() {
            from.entry(*a).or_default().push(e);
        }
        let mut used = vec![false; s.len()];
        let mut rings = Vec::new();
        for start in 0..s.len() {
            if used[start] {
                continue;
            }
            let mut ring: Vec<V> = Vec::new();
            let mut e = start;
            loop {
                used[e] = true;
                let (a, b) = s[e];
                // Keep a vertex only where the direction changes.
                let dir = |p: V, q: V| {
                    (
                        (i64::from(q.0) - i64::from(p.0)).signum(),
                        (i64::from(q.1) - i64::from(p.1)).signum(),
                    )
                };
                if ring.is_empty() {
                    ring.push(a);
                } else if ring.len() >= 2
                    && dir(ring[ring.len() - 2], ring[ring.len() - 1]) == dir(a, b)
                {
                    ring.pop();
                }
                ring.push(b);
                match from
                    .get(&b)
                    .and_then(|v| v.iter().copied().find(|&n| !used[n]))
                {
                    Some(n) => e = n,
                    None => break,
                }
            }
            // Closed: drop the repeated start, and a collinear start vertex.
            if ring.len() > 1 && ring.first() == ring.last() {
                ring.pop();
            }
            rings.push(
                ring.into_iter()
                    .map(|(i, j)| (xs[i as usize], ys[j as usize]))
                    .collect(),
            );
        }
        out.push(Region {
            class: Class::ALL[k],
            rings,
        });
    }
    out
}

/// Area enclosed by rings traced here (the region on the left of each ring:
/// outer rings count positive, holes negative).
pub fn even_odd_area(rings: &[Vec<(f64, f64)>]) -> f64 {
    let signed = |r: &Vec<(f64, f64)>| -> f64 {
        let n = r.len();
        (0..n)
            .map(|k| {
                let (p, q) = (r[k], r[(k + 1) % n]);
                p.0 * q.1 - q.0 * p.1
            })
            .sum::<f64>()
            / 2.0
    };
    rings.iter().map(signed).sum()
}

/// Whether `p` is inside `rings` under the even-odd rule.
pub fn inside_even_odd(rings: &[Vec<(f64, f64)>], p: (f64, f64)) -> bool {
    let mut inside = false;
    for r in rings {
        let n = r.len();
        for k in 0..n {
            let (a, b) = (r[k], r[(k + 1) % n]);
            if (a.1 > p.1) != (b.1 > p.1) {
                let x = a.0 + (p.1 - a.1) / (b.1 - a.1) * (b.0 - a.0);
                if p.0 < x {
                    inside = !inside;
                }
            }
        }
    }
    inside
}
