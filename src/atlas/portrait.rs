//! Phase portraits in plain `f64` (for drawing only, not certified).
//!
//! Scenes with a conserved energy get level lines of it (marching squares);
//! the others get trajectories of θ̈ integrated by Dormand–Prince 5(4) with
//! error control.

use crate::pave::PhaseBox;
use crate::scene::{Angle, Scene, Variant};
use std::collections::HashMap;

/// A polyline in phase-plane coordinates `(θ, θ̇)`.
pub type Polyline = Vec<(f64, f64)>;

/// Phase curves over `root`: energy level lines if the scene has an energy,
/// otherwise trajectories of the equation of motion of `variant`.
pub fn phase_portrait(scene: &Scene, variant: Variant, root: &PhaseBox) -> Vec<Polyline> {
    let probe = Angle::new(0.5 * (root.theta[0] + root.theta[1]));
    if scene.energy(&probe, 0.0_f64).is_some() {
        level_lines(|t, w| scene.energy(&Angle::new(t), w), root, 320, 240, 21)
    } else {
        trajectories(|t, w| scene.acceleration(variant, &Angle::new(t), w), root)
    }
}

/// Level lines of `f` on an `nx × ny` sample grid over `root`, at `levels`
/// quantiles of its finite values. Cells with a non-finite corner are skipped.
pub fn level_lines(
    f: impl Fn(f64, f64) -> Option<f64>,
    root: &PhaseBox,
    nx: usize,
    ny: usize,
    levels: usize,
) -> Vec<Polyline> {
    let xs: Vec<f64> = (0..nx)
        .map(|i| root.theta[0] + (root.theta[1] - root.theta[0]) * (i as f64 + 0.5) / nx as f64)
        .collect();
    let ys: Vec<f64> = (0..ny)
        .map(|j| {
            root.theta_dot[0]
                + (root.theta_dot[1] - root.theta_dot[0]) * (j as f64 + 0.5) / ny as f64
        })
        .collect();
    let z: Vec<f64> = ys
        .iter()
        .flat_map(|&y| xs.iter().map(move |&x| (x, y)))
        .map(|(x, y)| f(x, y).filter(|v| v.is_finite()).unwrap_or(f64::NAN))
        .collect();
    let mut finite: Vec<f64> = z.iter().copied().filter(|v| v.is_finite()).collect();
    if finite.len() < 4 {
        return Vec::new();
    }
    finite.sort_by(f64::total_cmp);
    let mut out = Vec::new();
    let mut last = f64::NAN;
    for k in 0..levels {
        let q = (k as f64 + 0.5) / levels as f64;
        let level = finite[((finite.len() - 1) as f64 * q).round() as usize];
        if level == last {
            continue;
        }
        last = level;
        out.extend(contour(&z, &xs, &ys, level));
    }
    out
}

/// Edge of the sample grid: (i, j, horizontal) joins (i, j)–(i+1, j) when
/// horizontal, (i, j)–(i, j+1) otherwise.
type Edge = (usize, usize, bool);

/// Marching squares for one level, segments chained into polylines.
fn contour(z: &[f64], xs: &[f64], ys: &[f64], level: f64) -> Vec<Polyline> {
    let (nx, ny) = (xs.len(), ys.len());
    let at = |i: usize, j: usize| z[j * nx + i] - level;
    let point = |e: Edge| -> (f64, f64) {
        let (i, j, horizontal) = e;
        let (i2, j2) = if horizontal { (i + 1, j) } else { (i, j + 1) };
        let (a, b) = (at(i, j), at(i2, j2));
        let t = a / (a - b);
        (xs[i] + t * (xs[i2] - xs[i]), ys[j] + t * (ys[j2] - ys[j]))
    };
    let mut segs: Vec<(Edge, Edge)> = Vec::new();
    for j in 0..ny - 1 {
        for i in 0..nx - 1 {
            let v = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
            if v.iter().any(|x| !x.is_finite()) {
                continue;
            }
            let code = v
                .iter()
                .enumerate()
                .fold(0u8, |c, (k, &x)| c | (u8::from(x > 0.0) << k));
            // Edges: bottom, right, top, left.
            let e = [
                (i, j, true),
                (i + 1, j, false),
                (i, j + 1, true),
                (i, j, false),
            ];
            let pairs: &[(usize, usize)] = match code {
                0 | 15 => &[],
                1 | 14 => &[(3, 0)],
                2 | 13 => &[(0, 1)],
                3 | 12 => &[(3, 1)],
                4 | 11 => &[(1, 2)],
                6 | 9 => &[(0, 2)],
                7 | 8 => &[(3, 2)],
                5 | 10 => {
                    // Saddle: decide by the centre value.
                    let centre = (v[0] + v[1] + v[2] + v[3]) / 4.0 > 0.0;
                    if (code == 5) == centre {
                        &[(3, 2), (0, 1)]
                    } else {
                        &[(3, 0), (1, 2)]
                    }
                }
                _ => unreachable!("four bits"),
            };
            segs.extend(pairs.iter().map(|&(a, b)| (e[a], e[b])));
        }
    }
    chain(&segs)
        .into_iter()
        .map(|edges| edges.into_iter().map(point).collect())
        .collect()
}

/// Joins segments sharing an endpoint (each endpoint is shared by at most two
/// segments) into maximal paths or cycles.
fn chain(segs: &[(Edge, Edge)]) -> Vec<Vec<Edge>> {
    let mut by_edge: HashMap<Edge, Vec<usize>> = HashMap::new();
    for (k, (a, b)) in segs.iter().enumerate() {
        by_edge.entry(*a).or_default().push(k);
        by_edge.entry(*b).or_default().push(k);
    }
    let mut used = vec![false; segs.len()];
    let mut out = Vec::new();
    let other = |k: usize, e: Edge| if segs[k].0 == e { segs[k].1 } else { segs[k].0 };
    let next_seg = |e: Edge, used: &[bool]| by_edge[&e].iter().copied().find(|&k| !used[k]);
    // Start at path ends first (degree 1), then whatever is left (cycles).
    let mut starts: Vec<Edge> = by_edge
        .iter()
        .filter(|(_, v)| v.len() == 1)
        .map(|(e, _)| *e)
        .collect();
    starts.sort_unstable();
    let mut rest: Vec<Edge> = segs.iter().map(|s| s.0).collect();
    rest.sort_unstable();
    starts.extend(rest);
    for start in starts {
        let mut line = vec![start];
        let mut at = start;
        while let Some(k) = next_seg(at, &used) {
            used[k] = true;
            at = other(k, at);
            line.push(at);
        }
        if line.len() > 1 {
            out.push(line);
        }
    }
    out
}

/// Trajectories of `θ̈ = acc(θ, θ̇)` through a grid of seeds, forwards and
/// backwards in time, each way for at most a fixed arc length (measured in
/// units of the box), clipped where they leave `root` (the last point is on
/// its edge) or stopped on non-finite values or at rest. Each trajectory is
/// followed by a small arrowhead at its seed, pointing forwards in time.
pub fn trajectories(acc: impl Fn(f64, f64) -> f64, root: &PhaseBox) -> Vec<Polyline> {
    trajectories_with_heads(acc, root)
        .into_iter()
        .flat_map(|(line, head)| std::iter::once(line).chain(head))
        .collect()
}

/// Dormand–Prince 5(4) coefficients (the field is autonomous: no nodes).
const DP_A: [[f64; 6]; 7] = [
    [0.0; 6],
    [0.2, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// Fifth-order weights minus the embedded fourth-order ones.
const DP_E: [f64; 7] = [
    35.0 / 384.0 - 5179.0 / 57600.0,
    0.0,
    500.0 / 1113.0 - 7571.0 / 16695.0,
    125.0 / 192.0 - 393.0 / 640.0,
    -2187.0 / 6784.0 + 92097.0 / 339200.0,
    11.0 / 84.0 - 187.0 / 2100.0,
    -1.0 / 40.0,
];

/// One Dormand–Prince step of size `dt` from `s`: the fifth-order result and
/// the error estimate (both as phase-plane vectors).
fn dp_step(
    f: &impl Fn((f64, f64)) -> (f64, f64),
    s: (f64, f64),
    dt: f64,
) -> ((f64, f64), (f64, f64)) {
    let mut k = [(0.0, 0.0); 7];
    for i in 0..7 {
        let (mut x, mut y) = s;
        for (j, kj) in k.iter().enumerate().take(i) {
            x += dt * DP_A[i][j] * kj.0;
            y += dt * DP_A[i][j] * kj.1;
        }
        k[i] = f((x, y));
    }
    // The seventh stage is evaluated at the fifth-order result (FSAL).
    let mut n = s;
    let mut e = (0.0, 0.0);
    for i in 0..7 {
        if i < 6 {
            n.0 += dt * DP_A[6][i] * k[i].0;
            n.1 += dt * DP_A[6][i] * k[i].1;
        }
        e.0 += dt * DP_E[i] * k[i].0;
        e.1 += dt * DP_E[i] * k[i].1;
    }
    (n, e)
}

/// Where the segment from `a` (inside) to `b` (outside) crosses the edge of
/// `root`.
fn exit_point(root: &PhaseBox, a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    let mut t: f64 = 1.0;
    let mut cut = |lo: f64, hi: f64, p: f64, q: f64| {
        if q > hi && q != p {
            t = t.min((hi - p) / (q - p));
        }
        if q < lo && q != p {
            t = t.min((lo - p) / (q - p));
        }
    };
    cut(root.theta[0], root.theta[1], a.0, b.0);
    cut(root.theta_dot[0], root.theta_dot[1], a.1, b.1);
    let t = t.clamp(0.0, 1.0);
    (
        (a.0 + t * (b.0 - a.0)).clamp(root.theta[0], root.theta[1]),
        (a.1 + t * (b.1 - a.1)).clamp(root.theta_dot[0], root.theta_dot[1]),
    )
}

/// [`trajectories`], each curve with its arrowhead (if the field is nonzero
/// at the seed).
pub fn trajectories_with_heads(
    acc: impl Fn(f64, f64) -> f64,
    root: &PhaseBox,
) -> Vec<(Polyline, Option<Polyline>)> {
    let (w, h) = (
        root.theta[1] - root.theta[0],
        root.theta_dot[1] - root.theta_dot[0],
    );
    let (seeds_x, seeds_y) = (8usize, 6usize);
    let max_arc = 0.9;
    // Local error per step, relative to the box; steps also move at most
    // 1/600 of the box, so the polyline is smooth at pixel scale.
    let tol = 1e-7;
    let max_move = 1.0 / 600.0;
    let f = |s: (f64, f64)| (s.1, acc(s.0, s.1));
    let norm = |v: (f64, f64)| (v.0 / w).hypot(v.1 / h);
    let finite = |s: (f64, f64)| s.0.is_finite() && s.1.is_finite();
    let mut out = Vec::new();
    for i in 0..seeds_x {
        for j in 0..seeds_y {
            // Staggered rows, so seeds do not line up.
            let shift = if j % 2 == 0 { 0.25 } else { 0.75 };
            let seed = (
                root.theta[0] + w * (i as f64 + shift) / seeds_x as f64,
                root.theta_dot[0] + h * (j as f64 + 0.5) / seeds_y as f64,
            );
            let mut both = Vec::new();
            for dir in [-1.0, 1.0] {
                let mut s = seed;
                let mut line = vec![s];
                let mut arc = 0.0;
                let mut dt = {
                    let v = norm(f(s));
                    if v > 0.0 && v.is_finite() {
                        max_move / v
                    } else {
                        0.0
                    }
                };
                let mut steps = 0;
                while dt > 0.0 && arc < max_arc && steps < 200_000 {
                    steps += 1;
                    let speed = norm(f(s));
                    if !(speed.is_finite() && speed > 1e-12) {
                        break; // at rest (an equilibrium) or singular
                    }
                    dt = dt.min(max_move / speed);
                    let (n, e) = dp_step(&f, s, dir * dt);
                    let err = norm(e);
                    if !(finite(n) && err.is_finite()) {
                        dt *= 0.25;
                        if dt * speed < 1e-12 {
                            break;
                        }
                        continue;
                    }
                    if err > tol {
                        dt *= (0.9 * (tol / err).powf(0.2)).clamp(0.1, 0.9);
                        if dt * speed < 1e-12 {
                            break;
                        }
                        continue;
                    }
                    if !root.contains(n.0, n.1) {
                        line.push(exit_point(root, s, n));
                        break;
                    }
                    arc += norm((n.0 - s.0, n.1 - s.1));
                    s = n;
                    line.push(s);
                    let grow = if err > 0.0 {
                        (0.9 * (tol / err).powf(0.2)).clamp(1.0, 5.0)
                    } else {
                        5.0
                    };
                    dt *= grow;
                }
                both.push(line);
            }
            let fwd = both.pop().unwrap_or_default();
            let mut bwd = both.pop().unwrap_or_default();
            bwd.reverse();
            bwd.extend(fwd.iter().skip(1));
            if bwd.len() > 1 {
                out.push((bwd, arrowhead(seed, f(seed), w, h)));
            }
        }
    }
    out
}

/// A "V" at `at` pointing along `dir`, sized relative to the box.
fn arrowhead(at: (f64, f64), dir: (f64, f64), w: f64, h: f64) -> Option<Polyline> {
    let (u, v) = (dir.0 / w, dir.1 / h);
    let n = u.hypot(v);
    if !(n.is_finite() && n > 0.0) {
        return None;
    }
    let (u, v) = (u / n, v / n);
    let len = 0.012;
    let wing = |sign: f64| {
        let (c, s) = (0.94f64, sign * 0.34f64); // ±20°
        let (bu, bv) = (-(u * c - v * s), -(u * s + v * c));
        (at.0 + len * bu * w, at.1 + len * bv * h)
    };
    Some(vec![wing(1.0), at, wing(-1.0)])
}
