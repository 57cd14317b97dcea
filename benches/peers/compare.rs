//! Matching two speed–accuracy curves: the time (or box count) at which a
//! curve reaches a given undecided area, by log–log interpolation, and the
//! peers' measurements as `benches/peers/codac_peer.py` writes them.
//! Shared by the `peers` benchmark and its test (`tests/it/peers.rs`).

/// On a curve of `(x, y)` points with y falling as x grows (time against
/// undecided area, or undecided area against box count), the x where y = `u`,
/// by log–log interpolation between the two points around it; `None` outside
/// the curve's range.
pub fn x_at(points: &[(f64, f64)], u: f64) -> Option<f64> {
    let mut p: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|&(t, a)| t > 0.0 && a > 0.0)
        .collect();
    p.sort_by(|a, b| b.1.total_cmp(&a.1));
    p.windows(2).find_map(|w| {
        let ((t0, a0), (t1, a1)) = (w[0], w[1]);
        (a1 <= u && u <= a0 && a0 > a1).then(|| {
            let s = (u.ln() - a0.ln()) / (a1.ln() - a0.ln());
            (t0.ln() + s * (t1.ln() - t0.ln())).exp()
        })
    })
}

/// One peer series: its problem key, label (`codac sep`), `(time, undecided
/// area)` points and `(undecided area, boxes)` points.
#[derive(Debug, Clone, PartialEq)]
pub struct PeerCurve {
    pub problem: String,
    pub label: String,
    pub time_area: Vec<(f64, f64)>,
    pub area_boxes: Vec<(f64, f64)>,
}

/// The peer curves of a `codac_peer.py` document, one per problem and method,
/// in the order first seen; runs missing a field are skipped.
pub fn peer_curves(doc: &serde_json::Value) -> Vec<PeerCurve> {
    let peer = doc["peer"].as_str().unwrap_or("peer");
    let mut out: Vec<PeerCurve> = Vec::new();
    for r in doc["runs"].as_array().into_iter().flatten() {
        let (Some(problem), Some(method), Some(t), Some(u)) = (
            r["problem"].as_str(),
            r["method"].as_str(),
            r["time_s"].as_f64(),
            r["undecided_area"].as_f64(),
        ) else {
            continue;
        };
        let label = format!("{peer} {method}");
        let boxes = r["boxes"].as_f64().map(|n| (u, n));
        match out
            .iter_mut()
            .find(|c| c.problem == problem && c.label == label)
        {
            Some(c) => {
                c.time_area.push((t, u));
                c.area_boxes.extend(boxes);
            }
            None => out.push(PeerCurve {
                problem: problem.to_string(),
                label,
                time_area: vec![(t, u)],
                area_boxes: boxes.into_iter().collect(),
            }),
        }
    }
    out
}

/// Peer time / our time at undecided area `u`, when both curves reach it.
pub fn speedup(ours: &[(f64, f64)], theirs: &[(f64, f64)], u: f64) -> Option<f64> {
    Some(x_at(theirs, u)? / x_at(ours, u)?)
}

/// The exponent k of cost ∝ (1/U)^k fitted by least squares on log–log
/// points `(time, undecided area)` with U in `[lo, hi]`; `None` with fewer
/// than two such points.
pub fn cost_exponent(points: &[(f64, f64)], lo: f64, hi: f64) -> Option<f64> {
    let p: Vec<(f64, f64)> = points
        .iter()
        .filter(|&&(t, u)| t > 0.0 && lo <= u && u <= hi)
        .map(|&(t, u)| ((1.0 / u).ln(), t.ln()))
        .collect();
    if p.len() < 2 {
        return None;
    }
    let n = p.len() as f64;
    let (mx, my) = (
        p.iter().map(|q| q.0).sum::<f64>() / n,
        p.iter().map(|q| q.1).sum::<f64>() / n,
    );
    let sxx: f64 = p.iter().map(|q| (q.0 - mx).powi(2)).sum();
    let sxy: f64 = p.iter().map(|q| (q.0 - mx) * (q.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}
