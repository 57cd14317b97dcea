//! Claim `reach` (`proofs/FORMAT.md`): the initial states of a window whose
//! motion reaches a target within a time T, as a `tree/1` paving whose
//! decided leaves each carry a trajectory certificate, replayed by the
//! rules of the `trajectory` claim ([`super::trajectory`]).

use super::area::{AreaSum, LeafArea};
use super::encoding::{base64_decode, decimal_enclosure, BitReader};
use super::json::{arr_of, as_obj, obj_of, opt_str, str_of, u64_of, Obj};
use super::trajectory::{
    all_keep_signs, decimal_box, on_pieces, parse_equation, parse_order, parse_steps, replay,
    Equation, Step, Then,
};
use super::tree::{labels, walk};
use super::{Outcome, Unreadable};
use inari::{DecInterval, Interval};

const REACHES: u8 = 0b01;
const AVOIDS: u8 = 0b10;

/// A decided leaf's certificate: the watched expression it proves crossed
/// (`None`: it proves every one avoided) and the steps.
struct Certificate {
    watch: Option<usize>,
    steps: Vec<Step>,
}

struct Statement {
    eq: Equation,
    window: [f64; 4],
    time: Interval,
    leaves: u64,
    inner: Option<(String, Interval)>,
    outer: Option<(String, Interval)>,
    order: usize,
    nodes: u64,
    body: Vec<u8>,
    certificates: Vec<Certificate>,
}

fn parse(root: &Obj) -> Result<(Statement, String), Unreadable> {
    let st = obj_of(root, "statement")?;
    let ev = obj_of(root, "evidence")?;
    let eq = parse_equation(st)?;
    let w = decimal_box(obj_of(st, "window")?, "window")?;
    let time = decimal_enclosure(str_of(st, "time")?).map_err(Unreadable)?;
    let leaves = u64_of(st, "leaves")?;
    let area = obj_of(st, "area")?;
    let bound = |key: &str| -> Result<Option<(String, Interval)>, Unreadable> {
        match opt_str(area, key)? {
            None => Ok(None),
            Some(t) => Ok(Some((
                t.to_string(),
                decimal_enclosure(t).map_err(|e| format!("area {key}: {e}"))?,
            ))),
        }
    };
    let (inner, outer) = (bound("inner")?, bound("outer")?);
    let encoding = str_of(ev, "encoding")?;
    if encoding != "tree/1" {
        return Err(Unreadable(format!("unknown tree encoding {encoding:?}")));
    }
    let nodes = u64_of(ev, "nodes")?;
    let body = base64_decode(str_of(ev, "body")?).map_err(|e| format!("body: {e}"))?;
    let order = parse_order(ev)?;
    let mut certificates = Vec::new();
    for (i, c) in arr_of(ev, "certificates")?.iter().enumerate() {
        let o = as_obj(c, "a certificate")?;
        let watch =
            match opt_str(o, "watch")? {
                None => None,
                Some(name) => Some(eq.watch.iter().position(|(n, _)| n == name).ok_or_else(
                    || {
                        Unreadable(format!(
                            "certificate {}: names no watched expression: {name:?}",
                            i + 1
                        ))
                    },
                )?),
            };
        let steps = parse_steps(arr_of(o, "steps")?, watch.is_none(), false)
            .map_err(|e| Unreadable(format!("certificate {}: {}", i + 1, e.0)))?;
        certificates.push(Certificate { watch, steps });
    }
    // Each end of the window a single double (the tree's root box).
    let exact = |x: (Interval, Interval)| -> Option<[f64; 2]> {
        (x.0.inf() == x.0.sup() && x.1.inf() == x.1.sup()).then(|| [x.0.inf(), x.1.inf()])
    };
    let window = match (exact(w[0]), exact(w[1])) {
        (Some(t), Some(w)) => [t[0], t[1], w[0], w[1]],
        // Not a double: the replay below refuses it (invalid, not malformed).
        _ => [f64::NAN; 4],
    };
    let claim = format!(
        "reach{}: {} leaves",
        opt_str(st, "scene")?
            .map(|s| format!(" {s}"))
            .unwrap_or_default(),
        leaves
    );
    Ok((
        Statement {
            eq,
            window,
            time,
            leaves,
            inner,
            outer,
            order,
            nodes,
            body,
            certificates,
        },
        claim,
    ))
}

pub fn check(root: &Obj) -> Result<Outcome, Unreadable> {
    let (st, claim) = parse(root)?;
    let mut checked = 0;
    let result = verify(&st, &mut checked);
    Ok(Outcome::of(result, claim, checked, "steps"))
}

fn exact_box(b: [f64; 4]) -> [DecInterval; 2] {
    [
        DecInterval::new(Interval::try_from((b[0], b[1])).unwrap_or(Interval::EMPTY)),
        DecInterval::new(Interval::try_from((b[2], b[3])).unwrap_or(Interval::EMPTY)),
    ]
}

/// Every solution from `leaf` crosses watched expression `g` by T: `g` has
/// one sign σ on the leaf, is defined and continuous on every piece of
/// every step, has the sign −σ on the last step's last piece, and that
/// step ends by T.
fn reaches(
    st: &Statement,
    leaf: [DecInterval; 2],
    g: usize,
    steps: &[Step],
    checked: &mut u64,
) -> Result<(), String> {
    let eq = &st.eq;
    let name = &eq.watch[g].0;
    let sigma = eq
        .watched_sign(g, leaf)
        .ok_or_else(|| format!("{name:?} has no sign on the leaf"))?;
    replay(eq, st.order, steps, leaf, None, checked, |leg| {
        on_pieces(leg.model, &leg.step.cuts, leg.s, |(p, q), y| {
            let v = eq.watched_value(g, y);
            if !(super::eval::defined(v) && super::eval::continuous(v)) {
                return Err(format!(
                    "{name:?} is not continuous on the piece [{p:e}, {q:e}]"
                ));
            }
            if leg.last && q == leg.s && eq.watched_sign(g, y) != Some(-sigma) {
                return Err(format!(
                    "{name:?} does not have the other sign on the last piece"
                ));
            }
            Ok(())
        })?;
        if !leg.last {
            return Ok(Then::Next);
        }
        let by = leg.next.interval().map_or(f64::INFINITY, |x| x.sup());
        if by > st.time.inf() {
            return Err(format!("the last step ends at {by:e}, after T"));
        }
        Ok(Then::Stop)
    })
    .map(|_| ())
}

/// Every solution from `leaf` exists on [0, T] with every watched
/// expression non-zero: the `end` rules without an end box.
fn avoids(
    st: &Statement,
    leaf: [DecInterval; 2],
    steps: &[Step],
    checked: &mut u64,
) -> Result<(), String> {
    let eq = &st.eq;
    let end = Some(DecInterval::new(st.time));
    replay(eq, st.order, steps, leaf, end, checked, |leg| {
        on_pieces(leg.model, &leg.step.cuts, leg.s, |p, y| {
            all_keep_signs(eq, p, y)
        })?;
        Ok(Then::Next)
    })
    .map(|_| ())
}

fn verify(st: &Statement, checked: &mut u64) -> Result<(), String> {
    let r = st.window;
    if !(r.iter().all(|x| x.is_finite()) && r[0] < r[1] && r[2] < r[3]) {
        return Err("the window's ends are not doubles with lo < hi".into());
    }
    if st.time.inf() <= 0.0 {
        return Err("T must be > 0".into());
    }
    let mut reach_sum = AreaSum::default();
    let mut not_avoid_sum = AreaSum::default();
    let mut certificates = st.certificates.iter();
    let mut leaf_no = 0u64;
    let mut bits = BitReader::new(&st.body);
    let walked = walk(&mut bits, r, st.nodes, |b, bits, node| {
        let labels = labels(bits, 1, node)?;
        leaf_no += 1;
        let at = |why: String| {
            format!(
                "leaf {leaf_no} [{:e}, {:e}] x [{:e}, {:e}]: {why}",
                b[0], b[1], b[2], b[3]
            )
        };
        let area = LeafArea::of((b[0], b[1]), (b[2], b[3]));
        let label = labels[0];
        if label == REACHES || label == AVOIDS {
            let c = certificates
                .next()
                .ok_or_else(|| at("no certificate left for it".into()))?;
            let leaf = exact_box(b);
            match (label, c.watch) {
                (REACHES, Some(g)) => reaches(st, leaf, g, &c.steps, checked).map_err(at)?,
                (AVOIDS, None) => avoids(st, leaf, &c.steps, checked).map_err(at)?,
                _ => return Err(at("its certificate is of the other fate".into())),
            }
        }
        if label == REACHES {
            reach_sum.add(&area);
        }
        if label != AVOIDS {
            not_avoid_sum.add(&area);
        }
        Ok(())
    })?;
    if walked.nodes != st.nodes {
        return Err(format!(
            "the tree has {} nodes, claimed {}",
            walked.nodes, st.nodes
        ));
    }
    if walked.leaves != st.leaves {
        return Err(format!(
            "the tree has {} leaves, claimed {}",
            walked.leaves, st.leaves
        ));
    }
    if certificates.next().is_some() {
        return Err("more certificates than decided leaves".into());
    }
    let (lo, hi) = (reach_sum.bounds().inf(), not_avoid_sum.bounds().sup());
    if let Some((text, c)) = &st.inner {
        if c.sup() > lo {
            return Err(format!(
                "claimed inner {text} exceeds the certified inner bound {lo:e}"
            ));
        }
    }
    if let Some((text, c)) = &st.outer {
        if c.inf() < hi {
            return Err(format!(
                "claimed outer {text} is below the certified outer bound {hi:e}"
            ));
        }
    }
    Ok(())
}
