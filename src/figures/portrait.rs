//! Phase portraits.
//!
//! A scene with `[dynamics]` gets certified curves in the atlas: the tubes
//! of [`crate::motion::portrait`] through a grid of seeds, each drawn as a
//! band that covers its boxes. The plain-`f64` portraits remain for the
//! other pictures (and a scene with an energy but no equation of motion):
//! level lines of the energy (marching squares), or trajectories of θ̈ by
//! Dormand–Prince 5(4) with error control.

use crate::motion::portrait::{certified_curves, BoxCurve, CurveSettings};
use crate::pave::PhaseBox;
use crate::scene::{Angle, Scene, Variant};
use rayon::prelude::*;
use std::collections::HashMap;

/// A polyline in phase-plane coordinates `(θ, θ̇)`.
pub type Polyline = Vec<(f64, f64)>;

/// Phase curves over `root`: energy level lines if the scene has an energy,
/// otherwise trajectories of the equation of motion of `variant`.
pub fn phase_portrait(scene: &Scene, variant: Variant, root: &PhaseBox) -> Vec<Polyline> {
    let probe = Angle::new(0.5 * (root.theta[0] + root.theta[1]));
    if scene.energy(&probe, 0.0_f64).is_some() {
        level_lines(|t, w| scene.energy(&Angle::new(t), w), root, 320, 240, 21)
    } else if !scene.has_dynamics() {
        Vec::new()
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
    level_lines_by_level(f, root, nx, ny, levels)
        .into_iter()
        .flatten()
        .collect()
}

/// [`level_lines`] grouped by level, in increasing order of level.
pub fn level_lines_by_level(
    f: impl Fn(f64, f64) -> Option<f64>,
    root: &PhaseBox,
    nx: usize,
    ny: usize,
    levels: usize,
) -> Vec<Vec<Polyline>> {
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
        out.push(contour(&z, &xs, &ys, level));
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
    // Long enough that a curve ends at the box's edge, at rest or at a
    // singularity, not in open plane (where it would read as a sink).
    let max_arc = 4.0;
    // Local error per step, relative to the box; steps also move at most
    // 1/600 of the box, so the polyline is smooth at pixel scale.
    let tol = 1e-7;
    let max_move = 1.0 / 600.0;
    let f = |s: (f64, f64)| (s.1, acc(s.0, s.1));
    let norm = |v: (f64, f64)| (v.0 / w).hypot(v.1 / h);
    let finite = |s: (f64, f64)| s.0.is_finite() && s.1.is_finite();
    let mut out = Vec::new();
    for seed in seeds(root) {
        {
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
                // A curve needs a few thousand steps; a stiff field (e.g.
                // μ = 10⁷) would take millions: stop it, the portrait is
                // decoration, not a certified result.
                let mut steps = 0;
                while dt > 0.0 && arc < max_arc && steps < 4_000 {
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

/// The phase curves an atlas draws, in picture pixels.
pub struct Portrait {
    /// Polylines and the stroke width that covers each one's boxes (1 for
    /// an uncertified curve or an arrowhead).
    pub curves: Vec<(Vec<(f64, f64)>, f64)>,
    /// The curves are certified bands: every solution through a seed
    /// stays inside its stroke.
    pub certified: bool,
}

/// The atlas's portrait: certified bands for a scene with `[dynamics]`,
/// otherwise [`phase_portrait_px`]'s `f64` curves.
pub fn atlas_portrait(
    scene: &Scene,
    variant: Variant,
    root: &PhaseBox,
    px: (u32, u32),
    spacing: f64,
) -> Portrait {
    if !scene.has_dynamics() {
        let curves = phase_portrait_px(scene, variant, root, px, spacing);
        return Portrait {
            curves: curves.into_iter().map(|c| (c, 1.0)).collect(),
            certified: false,
        };
    }
    let (w, h) = (
        root.theta[1] - root.theta[0],
        root.theta_dot[1] - root.theta_dot[0],
    );
    let (pw, ph) = (f64::from(px.0), f64::from(px.1));
    let to_px = |(t, v): (f64, f64)| {
        (
            (t - root.theta[0]) / w * pw,
            (root.theta_dot[1] - v) / h * ph,
        )
    };
    let window = [root.theta, root.theta_dot];
    let opts = CurveSettings {
        piece: [1.5 * w / pw, 1.5 * h / ph],
        time: 20.0,
        steps: 80,
    };
    let seeds = seeds(root);
    let file = scene.reading(variant);
    let runs: Vec<((f64, f64), Vec<BoxCurve>)> = seeds
        .par_iter()
        .map(|s| {
            (
                *s,
                certified_curves(file, window, std::slice::from_ref(s), &opts),
            )
        })
        .collect();
    let (kept_seeds, boxes): (Vec<(f64, f64)>, Vec<BoxCurve>) = runs
        .into_iter()
        .filter_map(|(s, mut c)| c.pop().map(|c| (s, c)))
        .unzip();
    // Each box in pixels: its centre, and the half-diagonal a stroke
    // through the centres must reach to cover it.
    let inside = |c: (f64, f64)| c.0 >= 0.0 && c.0 <= pw && c.1 >= 0.0 && c.1 <= ph;
    let mut centres = Vec::with_capacity(boxes.len());
    let mut reach = Vec::with_capacity(boxes.len());
    for curve in &boxes {
        let mut line = Vec::with_capacity(curve.len());
        let mut r: f64 = 0.0;
        for b in curve {
            let lo = to_px((b[0].inf(), b[1].sup()));
            let hi = to_px((b[0].sup(), b[1].inf()));
            let c = (0.5 * (lo.0 + hi.0), 0.5 * (lo.1 + hi.1));
            if inside(c) {
                r = r.max(0.5 * (hi.0 - lo.0).hypot(hi.1 - lo.1));
                line.push(c);
            }
        }
        centres.push(line);
        reach.push(r);
    }
    let simplify_tol = 0.1;
    let pieces = thin(&centres, spacing, 3.0 * spacing);
    // An arrowhead (a glyph of the direction of motion, from the field in
    // f64) at each seed whose curve is still drawn there.
    let mut curves: Vec<(Vec<(f64, f64)>, f64)> = Vec::new();
    for (k, seed) in kept_seeds.iter().enumerate() {
        let tip = to_px(*seed);
        let drawn = pieces
            .iter()
            .filter(|(c, _)| *c == k)
            .any(|(_, p)| p.iter().any(|q| (q.0 - tip.0).hypot(q.1 - tip.1) <= 1.5));
        let acc = scene.acceleration(variant, &Angle::new(seed.0), seed.1);
        if let (true, Some(head)) = (drawn, arrowhead(*seed, (seed.1, acc), w, h)) {
            curves.push((head.into_iter().map(to_px).collect(), 1.0));
        }
    }
    curves.extend(pieces.into_iter().map(|(k, piece)| {
        let width = (2.0 * (reach[k] + simplify_tol)).max(1.1);
        (simplify(&piece, simplify_tol), width)
    }));
    Portrait {
        curves,
        certified: true,
    }
}

/// Seeds of phase curves: a staggered grid over `root`.
fn seeds(root: &PhaseBox) -> Vec<(f64, f64)> {
    let (w, h) = (
        root.theta[1] - root.theta[0],
        root.theta_dot[1] - root.theta_dot[0],
    );
    let (seeds_x, seeds_y) = (8usize, 6usize);
    let mut out = Vec::with_capacity(seeds_x * seeds_y);
    for i in 0..seeds_x {
        for j in 0..seeds_y {
            // Staggered rows, so seeds do not line up.
            let shift = if j % 2 == 0 { 0.25 } else { 0.75 };
            out.push((
                root.theta[0] + w * (i as f64 + shift) / seeds_x as f64,
                root.theta_dot[0] + h * (j as f64 + 0.5) / seeds_y as f64,
            ));
        }
    }
    out
}

/// Phase curves in picture pixels (`(0, 0)` the top left of the plot area,
/// `px` its size), thinned where they crowd: no two drawn curves come closer
/// than about `spacing` pixels (marching squares levels near a singularity,
/// spirals, trajectories merging onto one separatrix). Energy levels are
/// considered coarse-to-fine, so the kept ones stay roughly evenly spaced.
pub fn phase_portrait_px(
    scene: &Scene,
    variant: Variant,
    root: &PhaseBox,
    px: (u32, u32),
    spacing: f64,
) -> Vec<Vec<(f64, f64)>> {
    let (w, h) = (
        root.theta[1] - root.theta[0],
        root.theta_dot[1] - root.theta_dot[0],
    );
    let (pw, ph) = (f64::from(px.0), f64::from(px.1));
    let to_px = |(t, v): (f64, f64)| {
        (
            (t - root.theta[0]) / w * pw,
            (root.theta_dot[1] - v) / h * ph,
        )
    };
    let map = |l: &Polyline| -> Vec<(f64, f64)> { l.iter().copied().map(to_px).collect() };
    let probe = Angle::new(0.5 * (root.theta[0] + root.theta[1]));
    let min_len = 3.0 * spacing;
    if scene.energy(&probe, 0.0_f64).is_some() {
        let levels = level_lines_by_level(
            |t, v| scene.energy(&Angle::new(t), v),
            root,
            (px.0 as usize / 2).clamp(64, 640),
            (px.1 as usize / 2).clamp(48, 480),
            25,
        );
        let curves: Vec<Vec<(f64, f64)>> = coarse_to_fine(levels.len())
            .into_iter()
            .flat_map(|k| levels[k].iter().map(map).collect::<Vec<_>>())
            .collect();
        thin(&curves, spacing, min_len)
            .into_iter()
            .map(|(_, piece)| simplify(&piece, 0.1))
            .collect()
    } else if !scene.has_dynamics() {
        Vec::new()
    } else {
        let traj =
            trajectories_with_heads(|t, v| scene.acceleration(variant, &Angle::new(t), v), root);
        let curves: Vec<Vec<(f64, f64)>> = traj.iter().map(|(l, _)| map(l)).collect();
        let pieces = thin(&curves, spacing, min_len);
        let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
        for (k, (_, head)) in traj.iter().enumerate() {
            // An arrowhead only where its curve is still drawn at the seed.
            if let Some(head) = head {
                let tip = to_px(head[1]);
                let kept = pieces
                    .iter()
                    .filter(|(c, _)| *c == k)
                    .any(|(_, p)| p.iter().any(|q| (q.0 - tip.0).hypot(q.1 - tip.1) <= 1.5));
                if kept {
                    out.push(map(head));
                }
            }
        }
        out.extend(pieces.into_iter().map(|(_, p)| simplify(&p, 0.1)));
        out
    }
}

/// `0..n` with the middle first, then quarters, … (bit-reversal-like), so a
/// prefix is spread over the whole range.
fn coarse_to_fine(n: usize) -> Vec<usize> {
    let mut order = Vec::with_capacity(n);
    let mut seen = vec![false; n];
    let mut step = n.next_power_of_two();
    while step >= 1 {
        let mut k = step / 2;
        while k < n {
            if !seen[k] {
                seen[k] = true;
                order.push(k);
            }
            k += step.max(1);
        }
        if step == 1 {
            break;
        }
        step /= 2;
    }
    for (k, s) in seen.iter().enumerate() {
        if !s {
            order.push(k);
        }
    }
    order
}

/// Splits each curve (in order of priority) into the pieces that stay at
/// least `spacing` pixels from every piece kept before, and from its own
/// points more than `4 × spacing` back along it (a tight spiral). Pieces
/// shorter than `min_len` are dropped. Returns `(curve index, piece)`.
///
/// A piece cut because it comes near a kept curve runs on (up to
/// `8 × spacing` further) until it touches that curve, and a piece that
/// starts where it leaves a kept curve begins on it: a reader of a phase
/// portrait takes a curve ending in open plane for a sink (or one starting
/// there for a source), while one running into its neighbour reads as the
/// two orbits merging at the drawing's resolution, which they do. A piece
/// shorter than `10 × spacing` with an end that joins nothing is dropped.
pub fn thin(
    curves: &[Vec<(f64, f64)>],
    spacing: f64,
    min_len: f64,
) -> Vec<(usize, Vec<(f64, f64)>)> {
    type Grid = HashMap<(i64, i64), Vec<(usize, f64, (f64, f64))>>;
    // Closer than this a line touches another (the lines are about a pixel wide).
    let touch = 1.0f64.min(0.25 * spacing);
    let reach = 8.0 * spacing;
    let cell = |p: (f64, f64)| {
        (
            (p.0 / spacing).floor() as i64,
            (p.1 / spacing).floor() as i64,
        )
    };
    // Distance from `p` to the nearest point of another curve, or of the
    // same curve more than 4 × spacing away along it; ∞ beyond `spacing`.
    let gap = |grid: &Grid, id: usize, arc: f64, p: (f64, f64)| -> f64 {
        let (cx, cy) = cell(p);
        let mut best = f64::INFINITY;
        for x in cx - 1..=cx + 1 {
            for y in cy - 1..=cy + 1 {
                for &(o, a, q) in grid.get(&(x, y)).into_iter().flatten() {
                    if o != id || (arc - a).abs() > 4.0 * spacing {
                        best = best.min((p.0 - q.0).hypot(p.1 - q.1));
                    }
                }
            }
        }
        best
    };
    let mut grid: Grid = HashMap::new();
    let mut out = Vec::new();
    for (id, curve) in curves.iter().enumerate() {
        // Resampled at most one pixel apart, with arc length.
        let mut pts: Vec<((f64, f64), f64)> = Vec::new();
        let mut arc = 0.0;
        for (k, &p) in curve.iter().enumerate() {
            if !(p.0.is_finite() && p.1.is_finite()) {
                continue;
            }
            if k > 0 {
                let q = curve[k - 1];
                let d = (p.0 - q.0).hypot(p.1 - q.1);
                let n = d.ceil().max(1.0) as usize;
                for i in 1..n {
                    let t = i as f64 / n as f64;
                    pts.push(((q.0 + t * (p.0 - q.0), q.1 + t * (p.1 - q.1)), arc + t * d));
                }
                arc += d;
            }
            pts.push((p, arc));
        }
        // Whether each point is blocked, and how far it is from what blocks
        // it; computed as the pieces are kept (a kept piece blocks the rest
        // of its own curve only through the spiral rule).
        let mut piece: Vec<usize> = Vec::new();
        let mut pending: Grid = HashMap::new();
        let mut blocked_at: Vec<f64> = vec![f64::INFINITY; pts.len()];
        // Whether the current piece starts at the curve's own start or on
        // the curve it leaves.
        let mut start_joined = true;
        let mut i = 0;
        while i <= pts.len() {
            let end = i == pts.len();
            let blocked = !end && {
                let (p, a) = pts[i];
                let d = gap(&grid, id, a, p).min(gap(&pending, id, a, p));
                blocked_at[i] = d;
                d < spacing
            };
            if !end && !blocked {
                if piece.is_empty() {
                    start_joined = i == 0;
                    // Begin on the curve this one leaves, if it is near.
                    let mut start = i;
                    while start > 0
                        && pts[i].1 - pts[start - 1].1 <= reach
                        && blocked_at[start - 1] < spacing
                    {
                        start -= 1;
                        if blocked_at[start] <= touch {
                            break;
                        }
                    }
                    if start < i && blocked_at[start] <= touch {
                        piece.extend(start..i);
                        start_joined = true;
                    }
                }
                piece.push(i);
                let (p, a) = pts[i];
                pending.entry(cell(p)).or_default().push((id, a, p));
                i += 1;
                continue;
            }
            // Cut here: run on into the curve that blocks this one.
            let mut stop = i;
            let mut end_joined = end;
            if !end && !piece.is_empty() {
                let mut k = i;
                while k < pts.len() && pts[k].1 - pts[i].1 <= reach {
                    let (p, a) = pts[k];
                    let d = gap(&grid, id, a, p).min(gap(&pending, id, a, p));
                    if d <= touch {
                        stop = k + 1;
                        end_joined = true;
                        break;
                    }
                    k += 1;
                }
            }
            let len = match (piece.first(), piece.last()) {
                (Some(&f), Some(&l)) => pts[l].1 - pts[f].1,
                _ => 0.0,
            };
            // A short piece with an end in open plane reads as a dash, or
            // as a sink or source: left out.
            let dangling = !(start_joined && end_joined);
            if len >= min_len && !(dangling && len < 10.0 * spacing) {
                for (k, v) in pending.drain() {
                    grid.entry(k).or_default().extend(v);
                }
                let mut drawn: Vec<(f64, f64)> = piece.iter().map(|&k| pts[k].0).collect();
                drawn.extend(pts[i..stop].iter().map(|q| q.0));
                out.push((id, drawn));
            }
            pending.clear();
            piece.clear();
            i += 1;
        }
    }
    out
}

/// Douglas–Peucker: drops points within `tol` of the chord of their
/// neighbours (pixel units), so vector output stays small.
pub fn simplify(pts: &[(f64, f64)], tol: f64) -> Vec<(f64, f64)> {
    if pts.len() < 3 {
        return pts.to_vec();
    }
    let mut keep = vec![false; pts.len()];
    keep[0] = true;
    keep[pts.len() - 1] = true;
    let mut stack = vec![(0, pts.len() - 1)];
    while let Some((a, b)) = stack.pop() {
        let (p, q) = (pts[a], pts[b]);
        let (dx, dy) = (q.0 - p.0, q.1 - p.1);
        let len = dx.hypot(dy);
        let mut worst = (0.0, a);
        for (i, r) in pts.iter().enumerate().take(b).skip(a + 1) {
            let d = if len > 0.0 {
                ((r.0 - p.0) * dy - (r.1 - p.1) * dx).abs() / len
            } else {
                (r.0 - p.0).hypot(r.1 - p.1)
            };
            if d > worst.0 {
                worst = (d, i);
            }
        }
        if worst.0 > tol {
            keep[worst.1] = true;
            stack.push((a, worst.1));
            stack.push((worst.1, b));
        }
    }
    pts.iter()
        .zip(keep)
        .filter_map(|(p, k)| k.then_some(*p))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trajectories_are_accurate_and_clipped_at_the_edge() {
        // θ̈ = −θ: circles θ² + θ̇² = const; the box cuts most of them.
        let root = PhaseBox {
            theta: [-1.0, 1.0],
            theta_dot: [-0.7, 0.7],
        };
        let traj = trajectories_with_heads(|t, _| -t, &root);
        assert!(!traj.is_empty());
        let on_edge = |p: (f64, f64)| {
            p.0 == root.theta[0]
                || p.0 == root.theta[1]
                || p.1 == root.theta_dot[0]
                || p.1 == root.theta_dot[1]
        };
        let mut clipped = 0;
        for (line, _) in &traj {
            let e0 = line[0].0.powi(2) + line[0].1.powi(2);
            for p in line {
                assert!(root.contains(p.0, p.1), "{p:?} outside");
                let e = p.0.powi(2) + p.1.powi(2);
                assert!(
                    (e - e0).abs() < 1e-5 * (1.0 + e0),
                    "energy drift {e} vs {e0}"
                );
            }
            for end in [line[0], line[line.len() - 1]] {
                if on_edge(end) {
                    clipped += 1;
                }
            }
        }
        assert!(clipped > 10, "curves leaving the box end on its edge");
    }

    #[test]
    fn crowded_lines_are_thinned_to_the_spacing() {
        // 60 vertical lines one pixel apart, 100 pixels long.
        let curves: Vec<Vec<(f64, f64)>> = (0..60)
            .map(|i| vec![(f64::from(i), 0.0), (f64::from(i), 100.0)])
            .collect();
        let kept = thin(&curves, 6.0, 18.0);
        let xs: Vec<f64> = kept.iter().map(|(_, p)| p[0].0).collect();
        assert!(xs.len() >= 8 && xs.len() <= 12, "{xs:?}");
        for (i, a) in xs.iter().enumerate() {
            for b in &xs[i + 1..] {
                assert!((a - b).abs() >= 6.0, "{a} and {b} too close");
            }
        }
        // A line far from the others is kept whole.
        let lone = vec![
            vec![(0.0, 0.0), (100.0, 0.0)],
            vec![(0.0, 50.0), (100.0, 50.0)],
        ];
        assert_eq!(thin(&lone, 6.0, 18.0).len(), 2);
    }

    #[test]
    fn a_cut_curve_runs_into_the_one_that_cuts_it() {
        // A horizontal line, and a line coming down onto it at 45° and then
        // running along it one pixel away: cut where it comes within the
        // spacing, it still ends touching the first line, not 6 pixels short.
        let a: Vec<(f64, f64)> = vec![(0.0, 100.0), (200.0, 100.0)];
        let b: Vec<(f64, f64)> = vec![(20.0, 20.0), (99.0, 99.0), (180.0, 99.0)];
        let kept = thin(&[a, b.clone()], 6.0, 18.0);
        let piece = &kept.iter().find(|(c, _)| *c == 1).expect("b kept").1;
        let last = *piece.last().unwrap();
        assert!((100.0 - last.1) <= 1.0 + 1e-9, "b ends at {last:?}");
        assert!(last.0 < 110.0, "b does not run along a: {last:?}");
        // The reverse: leaving a, b starts on it.
        let rev: Vec<(f64, f64)> = b.into_iter().rev().collect();
        let kept = thin(&[vec![(0.0, 100.0), (200.0, 100.0)], rev], 6.0, 18.0);
        let piece = &kept.iter().find(|(c, _)| *c == 1).expect("b kept").1;
        assert!(
            (100.0 - piece[0].1) <= 1.0 + 1e-9,
            "b starts at {:?}",
            piece[0]
        );
    }

    #[test]
    fn simplify_keeps_shape() {
        let pts: Vec<(f64, f64)> = (0..=100).map(|i| (f64::from(i), 0.0)).collect();
        assert_eq!(simplify(&pts, 0.1), vec![(0.0, 0.0), (100.0, 0.0)]);
        let arc: Vec<(f64, f64)> = (0..=90)
            .map(|i| {
                let t = f64::from(i).to_radians();
                (100.0 * t.cos(), 100.0 * t.sin())
            })
            .collect();
        let s = simplify(&arc, 0.1);
        assert!(s.len() < arc.len() && s.len() > 10);
    }
}
