//! Claim `trajectory` (`proofs/FORMAT.md`): a validated integration of
//! θ̈ = F(θ, θ̇) replayed from the stated steps — the Picard inclusion on
//! each a-priori box, Taylor coefficients from this crate's own series
//! ([`super::series`]), the Lagrange remainder over the box, the
//! mean-value form carried in the stated frame — and the watched
//! expressions' signs on every stated piece of time.

use super::encoding::{decimal_enclosure, parse_hex_f64};
use super::eval::{continuous, defined, exact, show, Dual, Num, Op, Program};
use super::json::{arr_of, as_obj, decls, obj_of, opt_str, pair_of, str_of, Obj};
use super::series::ode_series;
use super::{Outcome, Unreadable};
use inari::{DecInterval, Interval};
use serde_json::Value;

type V = [DecInterval; 2];
type M = [[DecInterval; 2]; 2];

const MAX_STEPS: usize = 1 << 16;
const MAX_CUTS: usize = 1024;
const MAX_WATCH: usize = 8;

fn d(x: Interval) -> DecInterval {
    DecInterval::new(x)
}

fn pt(x: f64) -> DecInterval {
    exact(x)
}

fn iv(lo: f64, hi: f64) -> Option<Interval> {
    Interval::try_from((lo, hi)).ok()
}

fn hull_of(x: DecInterval) -> Interval {
    x.interval().unwrap_or(Interval::EMPTY)
}

fn decimal_pair(v: &Value, what: &str) -> Result<(Interval, Interval), Unreadable> {
    let (a, b) = pair_of(v, what)?;
    let e = |s: &str| decimal_enclosure(s).map_err(|e| Unreadable(format!("{what}: {e}")));
    Ok((e(a)?, e(b)?))
}

fn hex(v: &Value, what: &str) -> Result<f64, Unreadable> {
    let s = v
        .as_str()
        .ok_or_else(|| Unreadable(format!("{what} must be a string")))?;
    parse_hex_f64(s, false).map_err(|e| Unreadable(format!("{what}: {e}")))
}

fn hexes<const N: usize>(o: &Obj, key: &str, what: &str) -> Result<[f64; N], Unreadable> {
    let a = arr_of(o, key)?;
    if a.len() != N {
        return Err(Unreadable(format!(
            "{what}: {key} must hold {N} exact doubles"
        )));
    }
    let mut out = [0.0; N];
    for (i, v) in a.iter().enumerate() {
        out[i] = hex(v, &format!("{what}: {key}"))?;
    }
    Ok(out)
}

pub(crate) struct Step {
    /// End time: an exact double, or T (`to` = `end`).
    to: Option<f64>,
    apriori: [f64; 4],
    frame: [f64; 4],
    pub(crate) cuts: Vec<f64>,
    window: Option<[f64; 4]>,
}

enum Outcomes {
    End {
        time: Interval,
        t: (Interval, Interval),
        w: (Interval, Interval),
    },
    Event {
        watch: usize,
        time: (Interval, Interval),
        t: (Interval, Interval),
        w: (Interval, Interval),
    },
    Arrival {
        time: (Interval, Interval),
        t: (Interval, Interval),
        w: (Interval, Interval),
        /// The evidence: θ̇'s band and the bracket of the zero of g.
        band: [f64; 2],
        root: [f64; 2],
    },
}

/// The equation and the watched expressions of a statement.
pub(crate) struct Equation {
    f_prog: Program,
    f: u32,
    g_prog: Program,
    pub(crate) watch: Vec<(String, u32)>,
}

struct Statement {
    eq: Equation,
    start: [(Interval, Interval); 2],
    outcome: Outcomes,
    order: usize,
    steps: Vec<Step>,
}

/// `parameters`, `definitions`, `theta_ddot` and `watch` of a statement.
pub(crate) fn parse_equation(st: &Obj) -> Result<Equation, Unreadable> {
    let (params, defs) = decls(st)?;
    let program = || -> Result<Program, Unreadable> {
        let mut p = Program::new(&["t", "w"])?;
        p.add_parameters(&params)?;
        for (n, e) in &defs {
            p.define(n, e)?;
        }
        Ok(p)
    };
    let mut f_prog = program()?;
    let f = f_prog
        .compile(str_of(st, "theta_ddot")?)
        .map_err(|e| Unreadable(format!("theta_ddot: {e}")))?;
    let mut g_prog = program()?;
    let mut watch: Vec<(String, u32)> = Vec::new();
    let list = arr_of(st, "watch")?;
    if list.len() > MAX_WATCH {
        return Err(Unreadable(format!(
            "more than {MAX_WATCH} watched expressions"
        )));
    }
    for (i, w) in list.iter().enumerate() {
        let o = as_obj(w, "a watched expression")?;
        let name = str_of(o, "name")?.to_string();
        if watch.iter().any(|(n, _)| *n == name) {
            return Err(Unreadable(format!("watch name {name:?} twice")));
        }
        let s = g_prog
            .compile(str_of(o, "expr")?)
            .map_err(|e| Unreadable(format!("watch {}: {e}", i + 1)))?;
        watch.push((name, s));
    }
    Ok(Equation {
        f_prog,
        f,
        g_prog,
        watch,
    })
}

/// A `{"t": [lo, hi], "w": [lo, hi]}` box of decimal text.
pub(crate) fn decimal_box(o: &Obj, what: &str) -> Result<[(Interval, Interval); 2], Unreadable> {
    Ok([
        decimal_pair(o.get("t").unwrap_or(&Value::Null), &format!("{what} t"))?,
        decimal_pair(o.get("w").unwrap_or(&Value::Null), &format!("{what} w"))?,
    ])
}

/// The evidence's `order`.
pub(crate) fn parse_order(ev: &Obj) -> Result<usize, Unreadable> {
    Ok(ev
        .get("order")
        .and_then(Value::as_u64)
        .filter(|k| (1..=40).contains(k))
        .ok_or_else(|| Unreadable("order must be an integer from 1 to 40".into()))? as usize)
}

/// The steps of `list`: the last one ends at `end` iff `end_last`, and
/// carries a `window` iff `window_last`.
pub(crate) fn parse_steps(
    list: &[Value],
    end_last: bool,
    window_last: bool,
) -> Result<Vec<Step>, Unreadable> {
    if list.len() > MAX_STEPS {
        return Err(Unreadable(format!("more than {MAX_STEPS} steps")));
    }
    let mut steps = Vec::with_capacity(list.len());
    for (j, s) in list.iter().enumerate() {
        let what = format!("step {}", j + 1);
        let o = as_obj(s, &what)?;
        let last = j + 1 == list.len();
        let to = match str_of(o, "to")? {
            "end" if end_last && last => None,
            "end" => {
                return Err(Unreadable(format!(
                    "{what}: `end` only on an end claim's last step"
                )))
            }
            _ if end_last && last => {
                return Err(Unreadable(format!(
                    "{what}: an end claim's last step ends at `end`"
                )))
            }
            _ => Some(hex(&o["to"], &format!("{what}: to"))?),
        };
        let cuts_v = arr_of(o, "cuts")?;
        if cuts_v.len() > MAX_CUTS {
            return Err(Unreadable(format!("{what}: more than {MAX_CUTS} cuts")));
        }
        let cuts = cuts_v
            .iter()
            .map(|c| hex(c, &format!("{what}: cut")))
            .collect::<Result<Vec<_>, _>>()?;
        let window = match o.get("window") {
            None => None,
            Some(_) => Some(hexes::<4>(o, "window", &what)?),
        };
        if window.is_some() != (window_last && last) {
            return Err(Unreadable(format!(
                "{what}: `window` belongs on an event claim's last step, and only there"
            )));
        }
        steps.push(Step {
            to,
            apriori: hexes::<4>(o, "apriori", &what)?,
            frame: hexes::<4>(o, "frame", &what)?,
            cuts,
            window,
        });
    }
    Ok(steps)
}

fn parse(root: &Obj) -> Result<(Statement, String), Unreadable> {
    let st = obj_of(root, "statement")?;
    let ev = obj_of(root, "evidence")?;
    let eq = parse_equation(st)?;
    let start = decimal_box(obj_of(st, "start")?, "start")?;
    let outcome = match (st.get("end"), st.get("event"), st.get("arrival")) {
        (Some(_), None, None) => {
            let e = obj_of(st, "end")?;
            let time = decimal_enclosure(str_of(e, "time")?).map_err(Unreadable)?;
            let [t, w] = decimal_box(e, "end")?;
            Outcomes::End { time, t, w }
        }
        (None, Some(_), None) => {
            let e = obj_of(st, "event")?;
            let name = str_of(e, "watch")?;
            let watch_i = eq
                .watch
                .iter()
                .position(|(n, _)| n == name)
                .ok_or_else(|| {
                    Unreadable(format!("the event names no watched expression: {name:?}"))
                })?;
            let time = decimal_pair(e.get("time").unwrap_or(&Value::Null), "event time")?;
            let [t, w] = decimal_box(e, "event")?;
            Outcomes::Event {
                watch: watch_i,
                time,
                t,
                w,
            }
        }
        (None, None, Some(_)) => {
            let e = obj_of(st, "arrival")?;
            let time = decimal_pair(e.get("time").unwrap_or(&Value::Null), "arrival time")?;
            let [t, w] = decimal_box(e, "arrival")?;
            let evidence = obj_of(ev, "arrival")?;
            Outcomes::Arrival {
                time,
                t,
                w,
                band: hexes::<2>(evidence, "band", "arrival")?,
                root: hexes::<2>(evidence, "root", "arrival")?,
            }
        }
        _ => {
            return Err(Unreadable(
                "exactly one of `end`, `event` and `arrival` is required".into(),
            ))
        }
    };
    let is_end = matches!(outcome, Outcomes::End { .. });
    let is_event = matches!(outcome, Outcomes::Event { .. });
    let order = parse_order(ev)?;
    let steps = parse_steps(arr_of(ev, "steps")?, is_end, is_event)?;
    let claim = format!(
        "trajectory{}: {} steps",
        opt_str(st, "scene")?
            .map(|s| format!(" {s}"))
            .unwrap_or_default(),
        steps.len()
    );
    Ok((
        Statement {
            eq,
            start,
            outcome,
            order,
            steps,
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

fn add(a: V, b: V) -> V {
    [a[0].add(b[0]), a[1].add(b[1])]
}

fn sub(a: V, b: V) -> V {
    [a[0].sub(b[0]), a[1].sub(b[1])]
}

fn mat_vec(m: &M, v: V) -> V {
    [
        m[0][0].mul(v[0]).add(m[0][1].mul(v[1])),
        m[1][0].mul(v[0]).add(m[1][1].mul(v[1])),
    ]
}

fn mat_mul(a: &M, b: &M) -> M {
    std::array::from_fn(|i| std::array::from_fn(|j| a[i][0].mul(b[0][j]).add(a[i][1].mul(b[1][j]))))
}

fn meet(a: V, b: V) -> V {
    [0, 1].map(|i| d(hull_of(a[i]).intersection(hull_of(b[i]))))
}

fn bounded(v: &V) -> bool {
    v.iter().all(|x| {
        x.interval()
            .is_some_and(|i| !i.is_empty() && i.is_common_interval())
    })
}

fn subset(a: V, b: V) -> bool {
    (0..2).all(|i| hull_of(a[i]).subset(hull_of(b[i])))
}

fn show_v(v: &V) -> String {
    format!("θ {}, θ̇ {}", show(v[0]), show(v[1]))
}

/// A set of states `{m + A·r : r ∈ R}` inside `e`.
#[derive(Clone, Copy)]
struct Set {
    m: [f64; 2],
    a: M,
    r: V,
    e: V,
}

/// What one step needs to enclose its states at any time of it.
pub(crate) struct StepModel {
    b: V,
    c: [Vec<DecInterval>; 2],
    jac: Vec<M>,
    rem: V,
    order: usize,
    start: Set,
}

impl StepModel {
    fn p(&self, tau: DecInterval) -> V {
        let h = |c: &[DecInterval]| {
            c.iter()
                .rev()
                .fold(pt(0.0), |acc, &ck| acc.mul(tau).add(ck))
        };
        [h(&self.c[0]), h(&self.c[1])]
    }

    fn j(&self, tau: DecInterval) -> M {
        let mut j = [[pt(0.0); 2]; 2];
        for dk in self.jac.iter().rev() {
            j = std::array::from_fn(|a| std::array::from_fn(|b| j[a][b].mul(tau).add(dk[a][b])));
        }
        j
    }

    fn tk(&self, tau: DecInterval) -> DecInterval {
        tau.pown(self.order as i32)
    }

    /// Y(τ): every solution from the start set at every time of τ.
    pub(crate) fn enclose(&self, tau: DecInterval) -> V {
        let tk = self.tk(tau);
        let y = add(
            add(self.p(tau), [tk.mul(self.rem[0]), tk.mul(self.rem[1])]),
            mat_vec(&mat_mul(&self.j(tau), &self.start.a), self.start.r),
        );
        meet(y, self.b)
    }
}

/// The hull of a stated box, or `None` if an end lies above its upper end.
pub(crate) fn state_box(s: &[(Interval, Interval); 2]) -> Option<V> {
    Some([d(s[0].0.convex_hull(s[0].1)), d(s[1].0.convex_hull(s[1].1))])
        .filter(|_| s[0].0.inf() <= s[0].1.sup() && s[1].0.inf() <= s[1].1.sup())
}

fn f_on(st: &Equation, x: V) -> DecInterval {
    st.f_prog.value(&x, st.f)
}

/// Series of the solution through `x0` (order `k`): the coefficients of θ
/// and θ̇, every one continuous, or `None`.
fn series(st: &Equation, x0: V, k: usize) -> Option<[Vec<DecInterval>; 2]> {
    let s = ode_series(&st.f_prog, st.f, x0, k);
    s.iter().flatten().all(|c| continuous(*c)).then_some(s)
}

/// ∂x_k/∂x₀ over `z`, k < `k`.
fn jacobian(st: &Equation, z: V, k: usize) -> Option<Vec<M>> {
    let col = |seed: usize| {
        let x0: [Dual<DecInterval>; 2] = std::array::from_fn(|i| Dual {
            v: z[i],
            d: pt(if i == seed { 1.0 } else { 0.0 }),
        });
        ode_series(&st.f_prog, st.f, x0, k - 1)
    };
    let (c0, c1) = (col(0), col(1));
    let ok = |s: &[Vec<Dual<DecInterval>>; 2]| {
        s.iter()
            .flatten()
            .all(|c| continuous(c.v) && continuous(c.d))
    };
    if !(ok(&c0) && ok(&c1)) {
        return None;
    }
    Some(
        (0..k)
            .map(|deg| [[c0[0][deg].d, c1[0][deg].d], [c0[1][deg].d, c1[1][deg].d]])
            .collect(),
    )
}

/// Whether `g` is defined, continuous and non-zero on `x`, and its sign.
pub(crate) fn sign_on(prog: &Program, g: u32, x: V) -> Option<f64> {
    let v = prog.value(&x, g);
    if !(defined(v) && continuous(v)) {
        return None;
    }
    let i = v.interval()?;
    if i.is_empty() {
        None
    } else if i.inf() > 0.0 {
        Some(1.0)
    } else if i.sup() < 0.0 {
        Some(-1.0)
    } else {
        None
    }
}

/// The pieces of `[0, upto]` cut at `cuts`.
fn pieces(cuts: &[f64], upto: f64) -> Result<Vec<(f64, f64)>, String> {
    let mut ends = vec![0.0];
    for &c in cuts {
        if !(c > *ends.last().unwrap_or(&0.0) && c < upto) {
            return Err(format!(
                "cut {c:e} is not in increasing order inside (0, {upto:e})"
            ));
        }
        ends.push(c);
    }
    ends.push(upto);
    Ok(ends.windows(2).map(|w| (w[0], w[1])).collect())
}

/// One replayed step, as the claim's own rules see it.
pub(crate) struct Leg<'a> {
    /// Whether it is the last step.
    pub last: bool,
    pub step: &'a Step,
    pub model: &'a StepModel,
    /// Its start and end times, and its length's upper bound s.
    pub tau: DecInterval,
    pub next: DecInterval,
    pub s: f64,
}

/// Whether the replay goes on after a step.
pub(crate) enum Then {
    Next,
    Stop,
}

/// Replays `steps` (rules 1.–4.) from the box `s0`, `end` standing for a
/// last `to` of `end`, calling `each` on every step before its end set is
/// formed; stops early when `each` says so. Returns the last end set (the
/// stopped step's start set on a stop) and whether it stopped.
pub(crate) fn replay(
    eq: &Equation,
    order: usize,
    steps: &[Step],
    s0: V,
    end: Option<DecInterval>,
    checked: &mut u64,
    mut each: impl FnMut(&Leg) -> Result<Then, String>,
) -> Result<(V, bool), String> {
    let k = order;
    let m0 = [hull_of(s0[0]).mid(), hull_of(s0[1]).mid()];
    let mut set = Set {
        m: m0,
        a: [[pt(1.0), pt(0.0)], [pt(0.0), pt(1.0)]],
        r: sub(s0, [pt(m0[0]), pt(m0[1])]),
        e: s0,
    };
    let mut tau = pt(0.0);
    if steps.is_empty() {
        return Err("no step".into());
    }
    for (j, step) in steps.iter().enumerate() {
        let at = |why: String| format!("step {}: {why}", j + 1);
        let next = match (step.to, end) {
            (Some(x), _) => pt(x),
            (None, Some(time)) => time,
            (None, None) => return Err(at("no end time".into())),
        };
        if hull_of(tau).sup() >= hull_of(next).inf() {
            return Err(at("the times do not increase".into()));
        }
        let h = next.sub(tau);
        let s = hull_of(h).sup();
        let b = step.apriori;
        let (Some(bt), Some(bw)) = (iv(b[0], b[1]), iv(b[2], b[3])) else {
            return Err(at("the a-priori box has an end above its upper end".into()));
        };
        let bx = [d(bt), d(bw)];
        // 1. The Picard inclusion on B.
        if !subset(set.e, bx) {
            return Err(at(format!(
                "the set {} is not inside the a-priori box",
                show_v(&set.e)
            )));
        }
        let fb = f_on(eq, bx);
        let span = d(iv(0.0, s).ok_or_else(|| at("no step length".into()))?);
        let picard = add(set.e, [span.mul(bx[1]), span.mul(fb)]);
        if !(continuous(fb) && subset(picard, bx)) {
            return Err(at(format!(
                "no Picard inclusion: E + [0, h]·f(B) = {} is not inside B = {}",
                show_v(&picard),
                show_v(&bx)
            )));
        }
        // 2. Remainder, polynomial, Jacobian.
        let rem =
            series(eq, bx, k).ok_or_else(|| at("F is not analytic on the a-priori box".into()))?;
        let rem = [rem[0][k], rem[1][k]];
        let m = [pt(set.m[0]), pt(set.m[1])];
        let c = if k >= 1 {
            series(eq, m, k - 1).ok_or_else(|| at("no series at the midpoint".into()))?
        } else {
            [Vec::new(), Vec::new()]
        };
        let z = [0, 1].map(|i| d(hull_of(set.e[i]).convex_hull(hull_of(m[i]))));
        let jac = jacobian(eq, z, k).ok_or_else(|| at("no Jacobian over the set".into()))?;
        let model = StepModel {
            b: bx,
            c,
            jac,
            rem,
            order: k,
            start: set,
        };
        let leg = Leg {
            last: j + 1 == steps.len(),
            step,
            model: &model,
            tau,
            next,
            s,
        };
        if let Then::Stop = each(&leg).map_err(at)? {
            *checked += 1;
            return Ok((set.e, true));
        }
        // 4. The end set.
        let hk = model.tk(h);
        let send = add(model.p(h), [hk.mul(rem[0]), hk.mul(rem[1])]);
        let c_mat = mat_mul(&model.j(h), &set.a);
        let mid = [hull_of(send[0]).mid(), hull_of(send[1]).mid()];
        let mp = [pt(mid[0]), pt(mid[1])];
        let zz = sub(send, mp);
        let q: M = [
            [pt(step.frame[0]), pt(step.frame[1])],
            [pt(step.frame[2]), pt(step.frame[3])],
        ];
        let det = q[0][0].mul(q[1][1]).sub(q[0][1].mul(q[1][0]));
        if hull_of(det).contains(0.0) || !defined(det) {
            return Err(at("the frame is singular".into()));
        }
        let qinv: M = [
            [q[1][1].div(det), q[0][1].neg().div(det)],
            [q[1][0].neg().div(det), q[0][0].div(det)],
        ];
        let r = add(mat_vec(&mat_mul(&qinv, &c_mat), set.r), mat_vec(&qinv, zz));
        let direct = add(add(mp, mat_vec(&c_mat, set.r)), zz);
        let framed = add(mp, mat_vec(&q, r));
        let e = meet(meet(direct, framed), bx);
        if !bounded(&e) || !bounded(&r) {
            return Err(at("the end set is empty or unbounded".into()));
        }
        set = Set { m: mid, a: q, r, e };
        tau = next;
        *checked += 1;
    }
    Ok((set.e, false))
}

/// Rule 5 on the pieces of `[0, upto]` cut at `cuts`: `keep(piece, states)`
/// must hold on each.
pub(crate) fn on_pieces(
    model: &StepModel,
    cuts: &[f64],
    upto: f64,
    mut keep: impl FnMut((f64, f64), V) -> Result<(), String>,
) -> Result<(), String> {
    if upto > 0.0 {
        for (p, q) in pieces(cuts, upto)? {
            let piece = d(iv(p, q).ok_or("bad piece")?);
            keep((p, q), model.enclose(piece))?;
        }
        Ok(())
    } else if !cuts.is_empty() {
        Err("cuts but no piece before the window".into())
    } else {
        Ok(())
    }
}

/// Every watched expression defined, continuous and non-zero on `y`.
pub(crate) fn all_keep_signs(eq: &Equation, (p, q): (f64, f64), y: V) -> Result<(), String> {
    for (name, g) in &eq.watch {
        if sign_on(&eq.g_prog, *g, y).is_none() {
            return Err(format!(
                "{name:?} may vanish on the piece [{p:e}, {q:e}] (states {})",
                show_v(&y)
            ));
        }
    }
    Ok(())
}

impl Equation {
    /// The value of watched expression `i` on `x`.
    pub(crate) fn watched_value(&self, i: usize, x: V) -> DecInterval {
        self.g_prog.value(&x, self.watch[i].1)
    }

    /// Its sign on `x` (defined, continuous, non-zero), or `None`.
    pub(crate) fn watched_sign(&self, i: usize, x: V) -> Option<f64> {
        sign_on(&self.g_prog, self.watch[i].1, x)
    }
}

fn verify(st: &Statement, checked: &mut u64) -> Result<(), String> {
    let s0 = state_box(&st.start).ok_or("start: an end above its upper end")?;
    let eq = &st.eq;
    let (event, end) = match &st.outcome {
        Outcomes::Event { watch, .. } => (Some(*watch), None),
        Outcomes::Arrival { .. } => (None, None),
        Outcomes::End { time, .. } => {
            if time.inf() <= 0.0 {
                return Err("end time must be > 0".into());
            }
            (None, Some(d(*time)))
        }
    };
    let sigma = match event {
        Some(i) => Some(eq.watched_sign(i, s0).ok_or_else(|| {
            format!(
                "the event's expression {:?} has no sign on the start box",
                eq.watch[i].0
            )
        })?),
        None => None,
    };
    let (e, stopped) = replay(eq, st.order, &st.steps, s0, end, checked, |leg| {
        // 5. Watched expressions on the pieces (the last step of an event
        // claim: on [0, a0] only, then the window).
        let upto = leg.step.window.map_or(leg.s, |w| w[0]);
        on_pieces(leg.model, &leg.step.cuts, upto, |p, y| {
            all_keep_signs(eq, p, y)
        })?;
        match (leg.step.window, event, sigma) {
            (Some(w), Some(ei), Some(sigma)) => {
                check_event(st, leg.model, leg.tau, leg.s, w, ei, sigma)?;
                if !leg.last {
                    return Err("a window on a step before the last".into());
                }
                Ok(Then::Stop)
            }
            _ => Ok(Then::Next),
        }
    })?;
    match &st.outcome {
        Outcomes::Event { .. } if stopped => Ok(()),
        Outcomes::End { t, w, .. } => {
            if inside(hull_of(e[0]), *t) && inside(hull_of(e[1]), *w) {
                Ok(())
            } else {
                Err(format!(
                    "the end set {} is not inside the claimed box",
                    show_v(&e)
                ))
            }
        }
        Outcomes::Event { .. } => Err("the last step has no window".into()),
        Outcomes::Arrival { .. } => {
            let to = st.steps.last().and_then(|s| s.to).ok_or("no last step")?;
            check_arrival(st, e, pt(to))
        }
    }
}

/// Whether `x` lies inside the claimed `[lo, hi]` (ends as enclosures).
fn inside(x: Interval, (lo, hi): (Interval, Interval)) -> bool {
    x.inf() >= lo.sup() && x.sup() <= hi.inf()
}

/// The arrival rules on the final set `e` at the exact time `tau`.
fn check_arrival(st: &Statement, e: V, tau: DecInterval) -> Result<(), String> {
    let Outcomes::Arrival {
        time,
        t,
        w,
        band: [a, b],
        root: [r0, r1],
    } = st.outcome
    else {
        return Err("not an arrival claim".into());
    };
    let eq = &st.eq;
    let p = &eq.f_prog;
    let Some(&Op::Div(u, v)) = p.ops().get(eq.f as usize) else {
        return Err("theta_ddot is not a division at its top level".into());
    };
    if p.deps()[v as usize] & 2 != 0 {
        return Err("theta_ddot's denominator reads w".into());
    }
    if !(a <= b && r0 < r1) {
        return Err("the band or the bracket is not ordered".into());
    }
    let dir = if a > 0.0 {
        1.0
    } else if b < 0.0 {
        -1.0
    } else {
        return Err("the band contains 0".into());
    };
    let (et, ew) = (hull_of(e[0]), hull_of(e[1]));
    let band = iv(a, b).ok_or("bad band")?;
    if !ew.subset(band) {
        return Err(format!(
            "the final set's θ̇ {} is not inside the band",
            show(e[1])
        ));
    }
    let (near, far, near_end, far_end) = if dir > 0.0 {
        (r0, r1, et.sup(), et.inf())
    } else {
        (r1, r0, et.inf(), et.sup())
    };
    if (near - near_end) * dir < 0.0 {
        return Err("the bracket does not lie ahead of the final set".into());
    }
    let strip = d(iv(far_end.min(far), far_end.max(far)).ok_or("bad strip")?);
    let bw = d(band);
    let sigma = sign_on(p, v, e).ok_or("the denominator has no sign on the final set")?;
    if sign_on(p, v, [pt(near), bw]) != Some(sigma) || sign_on(p, v, [pt(far), bw]) != Some(-sigma)
    {
        return Err("the denominator does not change sign across the bracket".into());
    }
    // Dual numbers over the strip, the seeded variable's derivative 1.
    let seeded = |seed: usize| -> [Dual<DecInterval>; 2] {
        let at = |i: usize, x: DecInterval| Dual {
            v: x,
            d: pt(if i == seed { 1.0 } else { 0.0 }),
        };
        [at(0, strip), at(1, bw)]
    };
    let dv = p.value(&seeded(0), v);
    if !(continuous(dv.v) && continuous(dv.d) && !hull_of(dv.d).contains(0.0)) {
        return Err("the denominator is not proved monotone on the strip".into());
    }
    if sign_on(p, u, [strip, pt(a)]) != Some(sigma) || sign_on(p, u, [strip, pt(b)]) != Some(-sigma)
    {
        return Err("θ̈ does not point into the band on its faces".into());
    }
    for seed in 0..2 {
        let du = p.value(&seeded(seed), u);
        if !(continuous(du.v) && continuous(du.d)) {
            return Err("the numerator is not proved C¹ on the strip".into());
        }
    }
    for (name, g) in &eq.watch {
        if sign_on(&eq.g_prog, *g, [strip, bw]).is_none() {
            return Err(format!("{name:?} may vanish before the arrival"));
        }
    }
    let speed = band.abs();
    let gap = |x: f64, y: f64, by: f64| hull_of(pt(x).sub(pt(y)).mul(pt(dir)).div(pt(by)));
    let lo = gap(near, near_end, speed.sup()).inf().max(0.0);
    let hi = gap(far, far_end, speed.inf()).sup();
    let when = hull_of(tau.add(d(iv(lo, hi).ok_or("bad arrival window")?)));
    if !inside(when, time) {
        return Err(format!(
            "the arrival time [{:e}, {:e}] is not inside the claimed window",
            when.inf(),
            when.sup()
        ));
    }
    if !(inside(iv(r0, r1).ok_or("bad bracket")?, t) && inside(band, w)) {
        return Err("the arrival state is not inside the claimed box".into());
    }
    Ok(())
}

/// The event rules on the last step (its start time `tau`, length `s`).
fn check_event(
    st: &Statement,
    model: &StepModel,
    tau: DecInterval,
    s: f64,
    w: [f64; 4],
    ei: usize,
    sigma: f64,
) -> Result<(), String> {
    let [a0, b0, a, b] = w;
    if !(0.0 <= a0 && a0 <= a && a < b && b <= b0 && b0 <= s) {
        return Err("the window is not 0 ≤ a0 ≤ a < b ≤ b0 ≤ s".into());
    }
    let eq = &st.eq;
    let (name, g) = &eq.watch[ei];
    let win = model.enclose(d(iv(a0, b0).ok_or("bad window")?));
    // Others non-zero on W.
    for (k, (other, go)) in eq.watch.iter().enumerate() {
        if k != ei && sign_on(&eq.g_prog, *go, win).is_none() {
            return Err(format!("{other:?} may vanish on the event's window"));
        }
    }
    // g continuous on W, its time derivative of the sign −σ.
    let gv = eq.g_prog.value(&win, *g);
    if !(defined(gv) && continuous(gv)) {
        return Err(format!("{name:?} is not continuous on the window"));
    }
    let fw = f_on(eq, win);
    // t seeded with θ̇ over W, w with F(W): the derivative along f.
    let x = [
        Dual {
            v: win[0],
            d: win[1],
        },
        Dual { v: win[1], d: fw },
    ];
    let dg = eq.g_prog.value(&x, *g);
    let slope = hull_of(dg.d);
    let one_sign = if sigma > 0.0 {
        slope.sup() < 0.0
    } else {
        slope.inf() > 0.0
    };
    if !(continuous(dg.v) && continuous(dg.d) && !slope.is_empty() && one_sign) {
        return Err(format!(
            "{name:?} is not monotone on the window: dg/dt ∈ {}",
            show(dg.d)
        ));
    }
    let at = |x: f64| model.enclose(pt(x));
    if sign_on(&eq.g_prog, *g, at(a)) != Some(sigma) {
        return Err(format!("{name:?} does not have its start sign at a"));
    }
    if sign_on(&eq.g_prog, *g, at(b)) != Some(-sigma) {
        return Err(format!("{name:?} does not have the other sign at b"));
    }
    let Outcomes::Event { time, t, w: wb, .. } = &st.outcome else {
        return Err("not an event claim".into());
    };
    let when = hull_of(tau.add(d(iv(a, b).ok_or("bad window")?)));
    if !inside(when, *time) {
        return Err(format!(
            "the crossing time [{:e}, {:e}] is not inside the claimed window",
            when.inf(),
            when.sup()
        ));
    }
    let y = model.enclose(d(iv(a, b).ok_or("bad window")?));
    if !(inside(hull_of(y[0]), *t) && inside(hull_of(y[1]), *wb)) {
        return Err(format!(
            "the state at the crossing {} is not inside the claimed box",
            show_v(&y)
        ));
    }
    Ok(())
}
