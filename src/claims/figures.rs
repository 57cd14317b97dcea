//! What the pictures of the witnesses of non-confirmed claims show; they are
//! drawn by [`crate::figures::claims`].

use super::example1::{self, P1};
use super::ice::{logs, rhs_3_5, vx_printed};
use super::smooth::{self, p2_texts, ClearedSlope};
use super::witness::{window, PairSet};
use crate::figures::claims::{
    draw_claim_figure, Axis, ClaimFigure, Curves, Marks, RegionFigure, Series, Shape,
};
use crate::figures::{THETA_DOT_UNITS, THETA_RAD};
use crate::pave::{pave, PaveOptions, PhaseBox};
use crate::roots::equations::kappa_alpha;
use crate::roots::isolate::RealFn;
use crate::roots::{solve_2_9, Budget};
use crate::scene::Angle;
use inari::{DecInterval, Interval};
use std::path::Path;

/// Claims with a figure, in registry order.
pub const WITH_FIGURE: [&str; 15] = [
    "F1.7",
    "F1.9",
    "F1.10",
    "F1.11",
    "S1.eq",
    "S2.case1fr",
    "S2.12count",
    "S2.12type",
    "S2.12components",
    "F3.4",
    "S3.c0changes",
    "S3.c0invariant",
    "S3.c0anypoint",
    "S3.forms",
    "S3.sub2",
];

/// Relative path of a claim's figure (SVG) inside the report folder.
pub fn figure_path(id: &str) -> Option<String> {
    WITH_FIGURE
        .contains(&id)
        .then(|| format!("figures/{}.svg", id.replace('.', "_")))
}

type Region = Box<dyn Fn(Interval, Interval) -> [DecInterval; 2] + Sync>;

enum Fig {
    Region {
        title: String,
        subtitle: String,
        f: Region,
        win: PhaseBox,
        names: [String; 2],
        mark: Option<PhaseBox>,
    },
    Lines(Curves),
}

/// Resolution and budget of the region pictures' pavings.
const REGION_EPS: f64 = 1.0 / 128.0;
const REGION_BOXES: usize = 200_000;

fn grid(lo: f64, hi: f64, n: usize) -> impl Iterator<Item = f64> {
    (0..=n).map(move |i| lo + (hi - lo) * i as f64 / n as f64)
}

fn viscous_region(printed: bool, omega0: bool) -> Region {
    Box::new(move |th, w| {
        let p = P1::texts(example1::DEFAULTS).map(DecInterval::new);
        let an = Angle::new(DecInterval::new(th));
        let w = DecInterval::new(w);
        let (s, c) = (an.sin, an.cos);
        let d = if omega0 {
            example1::derived_omega0(&p, s, c, w)
        } else {
            example1::derived_omega(&p, s, c, w)
        };
        let pr = if printed {
            example1::printed_bracket(&p, s, c, w, omega0)
        } else {
            d
        };
        [pr, d]
    })
}

/// `name = value` pairs joined, as markup.
fn params_text(names: &[&str], values: &[&str]) -> String {
    names
        .iter()
        .zip(values)
        .map(|(n, v)| format!("{n} = {v}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The defaults of Example 1, as markup.
fn example1_text() -> String {
    format!(
        "Example 1 (viscous disc), defaults {}",
        params_text(&["a", "b", "m", "C", "μ", "g"], &example1::DEFAULTS)
    )
}

/// The parameters of §2–3 other than the momenta, as markup.
fn p2_text() -> String {
    params_text(&["m", "a", "A", "C", "g"], &smooth::DEFAULTS[..5])
}

fn axis(name: &'static str, range: [f64; 2], angle: bool) -> Axis {
    Axis { name, range, angle }
}

fn series(name: impl Into<String>, pts: Vec<(f64, f64)>) -> Series {
    Series {
        name: name.into(),
        pts,
        dashed: false,
    }
}

fn marks(name: impl Into<String>, pts: Vec<(f64, f64)>, shape: Shape) -> Marks {
    Marks {
        name: name.into(),
        pts,
        shape,
    }
}

/// A number with a true minus sign.
fn signed(v: f64) -> String {
    format!("{v}").replace('-', "−")
}

/// `(p_φ, p_ψ) = (a, b)` as markup.
fn momenta(pf: &str, ps: &str) -> String {
    format!("(p_{{φ}}, p_{{ψ}}) = ({pf}, {ps})")
}

/// sin³θ·Π̃′(θ) of (2.12) for the momenta `(pf, ps)`, scaled to a largest
/// value 1 in absolute value on [0, π].
fn scaled_slope(pf: &str, ps: &str) -> Vec<(f64, f64)> {
    let pi = std::f64::consts::PI;
    let f = ClearedSlope(p2_texts(pf, ps));
    let pts: Vec<(f64, f64)> = grid(0.0, pi, 400).map(|t| (t, f.eval(t))).collect();
    let scale = pts.iter().map(|p| p.1.abs()).fold(1e-300, f64::max);
    pts.iter().map(|&(x, y)| (x, y / scale)).collect()
}

/// Right side R(θ) of (3.5) as printed, in `f64`.
fn rhs(pf: &str, ps: &str, c0: f64, t: f64) -> f64 {
    let p = p2_texts(pf, ps).map(|x| x.mid());
    let an = Angle::new(t);
    let (l1, l2) = logs(&an);
    rhs_3_5(&p, an.sin, an.cos, vx_printed(&p, c0, l1, l2, 1))
}

const SLOPE_TITLE: &str = "sin³θ·Π\u{303}′(θ) of (2.12), each scaled to max |·| = 1";

fn spec(id: &str, mark: Option<PhaseBox>) -> Option<Fig> {
    let pi = std::f64::consts::PI;
    let theta_dd = "θ\u{308}";
    Some(match id {
        "F1.10" => Fig::Region {
            title: "F1.10: Ω of (1.10) as printed against free flight Λ\u{308} < 0".into(),
            subtitle: example1_text(),
            f: viscous_region(true, false),
            win: window([0.0, 1.6], [0.0, 8.0]),
            names: ["printed (1.10)".into(), "Λ\u{308} < 0".into()],
            mark,
        },
        "F1.11" => Fig::Region {
            title: "F1.11: Ω_{0} of (1.11) as printed against N > 0".into(),
            subtitle: example1_text(),
            f: viscous_region(true, true),
            win: window([-1.6, 1.6], [0.0, 10.0]),
            names: ["printed (1.11)".into(), "N > 0".into()],
            mark,
        },
        "S3.c0changes" => {
            let p = p2_texts("2.5", "2");
            let om = move |c0: &str, th: Interval, w: Interval| {
                let pd = p.map(DecInterval::new);
                let an = Angle::new(DecInterval::new(th));
                let (l1, l2) = logs(&an);
                let vx = vx_printed(&pd, DecInterval::new(super::dec(c0)), l1, l2, 1);
                pd.a * DecInterval::new(w).sqr() * an.sin - rhs_3_5(&pd, an.sin, an.cos, vx)
            };
            Fig::Region {
                title: "S3.c0changes: Ω_{0} of (3.5) depends on c_{0}".into(),
                subtitle: format!("disc on ice, {}, {}", momenta("2.5", "2"), p2_text()),
                f: Box::new(move |th, w| [om("0", th, w), om("1", th, w)]),
                // Where the boundaries of the two sets part most.
                win: window([0.2, 1.8], [1.5, 4.5]),
                names: ["Ω_{0} at c_{0} = 0".into(), "Ω_{0} at c_{0} = 1".into()],
                mark,
            }
        }
        "F1.7" => {
            let p = P1::texts(example1::DEFAULTS).map(|x| x.mid());
            let printed = |t: f64| example1::printed_1_7(&p, t.sin(), t.cos(), 1.0, 2);
            let newton = |t: f64| example1::newton(&p, t.sin(), t.cos(), 1.0, 1).0;
            Fig::Lines(Curves {
                title: format!("F1.7: {theta_dd} of (1.7) as printed against the Newton equations"),
                subtitle: format!("θ\u{307} = 1; {}", example1_text()),
                x: axis(THETA_RAD, [-pi, pi], true),
                y: axis("θ\u{308} (rad/s²)", [-12.0, 9.0], false),
                series: vec![
                    series(
                        "(1.7) as printed",
                        grid(-pi, pi, 400).map(|t| (t, printed(t))).collect(),
                    ),
                    series(
                        "Newton equations",
                        grid(-pi, pi, 400).map(|t| (t, newton(t))).collect(),
                    ),
                ],
                marks: vec![marks(
                    "θ = 0: values certified disjoint",
                    vec![(0.0, printed(0.0)), (0.0, newton(0.0))],
                    Shape::Dot,
                )],
                zero: true,
            })
        }
        "F1.9" => {
            // Λ̈ at θ̇ = 1 with the reaction N = m g.
            let p = P1::texts(example1::DEFAULTS).map(|x| x.mid());
            let n = p.m * p.g;
            let by_1_8 = |t: f64, thdd: f64| {
                let (_, h1, h2) = example1::h_jet(&p, t.sin(), t.cos());
                n / p.m - p.g - h2 - h1 * thdd
            };
            let pts = |f: &dyn Fn(f64) -> f64| grid(-pi, pi, 400).map(|t| (t, f(t))).collect();
            Fig::Lines(Curves {
                title: "F1.9: Λ\u{308} of (1.9) as printed against (1.8)".into(),
                subtitle: format!("θ\u{307} = 1, N = mg; {}", example1_text()),
                x: axis(THETA_RAD, [-pi, pi], true),
                y: axis("Λ\u{308} (m/s²)", [-1.0, 6.0], false),
                series: vec![
                    series(
                        "(1.9) as printed",
                        pts(&|t| example1::printed_1_9(&p, t.sin(), t.cos(), 1.0, n)),
                    ),
                    series(
                        format!("(1.8) with the Newton {theta_dd}"),
                        pts(&|t| by_1_8(t, example1::newton(&p, t.sin(), t.cos(), 1.0, 1).0)),
                    ),
                    Series {
                        dashed: true,
                        ..series(
                            format!("(1.8) with {theta_dd} of (1.7) as printed (dashed): equal to (1.9)"),
                            pts(&|t| by_1_8(t, example1::printed_1_7(&p, t.sin(), t.cos(), 1.0, 2))),
                        )
                    },
                ],
                marks: vec![],
                zero: true,
            })
        }
        "F3.4" => {
            let v = |t: f64| 1.0 + t.cos().powi(2) / (0.25 + t.sin().powi(2));
            Fig::Lines(Curves {
                title: "F3.4: V_{0} of (3.4) as printed against Newton–Euler".into(),
                subtitle: "disc on ice, m = 1, a = 1, A = 0.25".into(),
                x: axis(THETA_RAD, [0.0, pi], true),
                y: axis("V_{0} (1/kg)", [0.0, 5.5], false),
                series: vec![
                    series(
                        "printed: 1/m",
                        grid(0.0, pi, 200).map(|t| (t, 1.0)).collect(),
                    ),
                    series(
                        "Newton–Euler: 1/m + a²cos²θ/(A + ma²sin²θ)",
                        grid(0.0, pi, 400).map(|t| (t, v(t))).collect(),
                    ),
                ],
                marks: vec![marks(
                    "θ = 1: values certified disjoint",
                    vec![(1.0, 1.0), (1.0, v(1.0))],
                    Shape::Dot,
                )],
                zero: false,
            })
        }
        "S1.eq" => {
            let (a, b, m, c, g): (f64, f64, f64, f64, f64) = (1.0, 0.5, 1.0, 0.3, 9.81);
            let disc = |mu: f64| (mu * mu * (a - b).powi(4) - 4.0 * m * g * b * c) / (c * c);
            let switch = 2.0 * (m * g * b * c).sqrt() / (a - b).powi(2);
            Fig::Lines(Curves {
                title: "S1.eq: the equilibrium θ = −π/2, trace² − 4 det against μ".into(),
                subtitle: format!(
                    "< 0: a stable focus, > 0: a stable node; {}",
                    params_text(
                        &["a", "b", "m", "C", "g"],
                        &["1", "0.5", "1", "0.3", "9.81"]
                    )
                ),
                x: axis("μ (kg/s)", [0.0, 21.0], false),
                y: axis("trace² − 4 det (1/s²)", [-80.0, 260.0], false),
                series: vec![series(
                    "(μ²(a − b)⁴ − 4mgbC)/C²",
                    grid(0.0, 21.0, 210).map(|u| (u, disc(u))).collect(),
                )],
                marks: vec![
                    marks(
                        "μ = 0.8 (default): a focus",
                        vec![(0.8, disc(0.8))],
                        Shape::Dot,
                    ),
                    marks("μ = 20: a node", vec![(20.0, disc(20.0))], Shape::Square),
                    marks(
                        "μ = 2√(mgbC)/(a − b)²: focus turns node",
                        vec![(switch, 0.0)],
                        Shape::Ring,
                    ),
                ],
                zero: true,
            })
        }
        "S2.case1fr" => Fig::Lines(Curves {
            title: "S2.case1fr: f_{r}(θ) = −cos²θ at α = 0 is not < 0".into(),
            subtitle: "§2, case 1 of the proof that Φ > 0".into(),
            x: axis(THETA_RAD, [0.0, pi], true),
            y: axis("f_{r} (dimensionless)", [-1.1, 0.3], false),
            series: vec![series(
                "f_{r} = −cos²θ",
                grid(0.0, pi, 300).map(|t| (t, -t.cos().powi(2))).collect(),
            )],
            marks: vec![marks(
                "f_{r}(π/2) = 0 (exact)",
                vec![(pi / 2.0, 0.0)],
                Shape::Dot,
            )],
            zero: true,
        }),
        "S2.12count" => {
            let samples = [("1", "1"), ("0.3", "0.3"), ("1", "0.2"), ("2.5", "2")];
            let mut ss = Vec::new();
            let mut roots = Vec::new();
            for (pf, ps) in samples {
                let (found, _, _) = smooth::equilibria(pf, ps);
                let count = match &found {
                    Some(rs) if rs.len() == 1 => "1 root".to_string(),
                    Some(rs) => format!("{} roots", rs.len()),
                    None => "count not certified".into(),
                };
                ss.push(series(
                    format!("{}: {count}", momenta(pf, ps)),
                    scaled_slope(pf, ps),
                ));
                roots.extend(
                    found
                        .into_iter()
                        .flatten()
                        .map(|r| (0.5 * (r[0] + r[1]), 0.0)),
                );
            }
            Fig::Lines(Curves {
                title: "S2.12count: how many roots (2.12) has".into(),
                subtitle: format!("{SLOPE_TITLE}; {}", p2_text()),
                x: axis(THETA_RAD, [0.0, pi], true),
                y: axis("scaled slope (dimensionless)", [-1.05, 1.05], false),
                series: ss,
                marks: vec![marks("certified roots (enclosures)", roots, Shape::Dot)],
                zero: true,
            })
        }
        "S2.12type" => {
            // Π̃ of (2.5): its minima are centres, its maxima saddles.
            let samples = [("0.3", "0.3"), ("1", "0.2"), ("2.5", "2")];
            let mut ss = Vec::new();
            let (mut centres, mut saddles) = (Vec::new(), Vec::new());
            for (pf, ps) in samples {
                let p = p2_texts(pf, ps).map(|x| x.mid());
                let pot = |t: f64| {
                    p.m * p.g * p.a * t.sin()
                        + (p.ps - p.pf * t.cos()).powi(2) / (2.0 * p.big_a * t.sin().powi(2))
                };
                let (found, types, _) = smooth::equilibria(pf, ps);
                let rs = found.unwrap_or_default();
                ss.push(series(
                    format!("{}: {}", momenta(pf, ps), types.join(", ")),
                    grid(0.02, pi - 0.02, 600).map(|t| (t, pot(t))).collect(),
                ));
                for (r, t) in rs.iter().zip(&types) {
                    let th = 0.5 * (r[0] + r[1]);
                    match *t {
                        "centre" => centres.push((th, pot(th))),
                        "saddle" => saddles.push((th, pot(th))),
                        _ => {}
                    }
                }
            }
            Fig::Lines(Curves {
                title: "S2.12type: the types of the equilibria of (2.5)".into(),
                subtitle: format!(
                    "reduced potential Π\u{303}(θ) of (2.5): a centre at a minimum, a saddle at a maximum; {}",
                    p2_text()
                ),
                x: axis(THETA_RAD, [0.0, pi], true),
                y: axis("Π\u{303} (J)", [0.0, 25.0], false),
                series: ss,
                marks: vec![
                    marks("centre: Π\u{303} minimum (certified)", centres, Shape::Dot),
                    marks(
                        "saddle: Π\u{303} maximum (certified)",
                        saddles,
                        Shape::Square,
                    ),
                ],
                zero: false,
            })
        }
        "S2.12components" => {
            // The gap of Ω is where Φ < 0, i.e. where κ sin³θ − f_r(θ) < 0
            // (F2.9: Φ·A²sin⁴θ/p_M² = κ sin³θ − f_r); equilibria on the axis.
            let samples = [("2", "2"), ("2.5", "2")];
            let mut ss = Vec::new();
            let mut eq = Vec::new();
            let mut counts = Vec::new();
            let mut gap_marks = Vec::new();
            for (((pf, ps), shape), dashed) in samples
                .into_iter()
                .zip([Shape::Ring, Shape::Square])
                .zip([false, true])
            {
                let d = smooth::disc(pf, ps);
                let ka = kappa_alpha(&d).ok();
                if let Some((kappa, alpha)) = ka.map(|(k, a)| (k.mid(), a.mid())) {
                    let f = |t: f64| {
                        let c = t.cos();
                        kappa * t.sin().powi(3) - c * (alpha - c) * (1.0 - alpha * c)
                    };
                    ss.push(Series {
                        dashed,
                        ..series(
                            format!(
                                "{} ({}): κ = {kappa:.4}, α = {alpha:.2}",
                                momenta(pf, ps),
                                if dashed { "dashed" } else { "solid" }
                            ),
                            grid(0.0, pi, 600).map(|t| (t, f(t))).collect(),
                        )
                    });
                }
                let (found, _, _) = smooth::equilibria(pf, ps);
                let found = found.unwrap_or_default();
                counts.push(format!("{} at ({pf}, {ps})", found.len()));
                eq.extend(found.iter().map(|r| (0.5 * (r[0] + r[1]), 0.0)));
                let gaps: Vec<(f64, f64)> = ka
                    .and_then(|(kappa, alpha)| solve_2_9(kappa, alpha, &Budget::default()).ok())
                    .filter(|g| g.complete)
                    .map(|g| g.roots.iter().map(|r| (0.5 * (r.lo + r.hi), 0.0)).collect())
                    .unwrap_or_default();
                gap_marks.push(marks(
                    format!("({pf}, {ps}): ends of the gap of Ω, certified roots of (2.9)"),
                    gaps,
                    shape,
                ));
            }
            let mut all = vec![marks(
                format!("equilibria (certified): {}", counts.join(", ")),
                eq,
                Shape::Dot,
            )];
            all.extend(gap_marks);
            Fig::Lines(Curves {
                title: "S2.12components: equilibria on the two sides of the gap of Ω".into(),
                subtitle: format!(
                    "κ sin³θ − f_{{r}}(θ), the sign of Φ of (2.8): Ω has a gap where it is < 0; {}",
                    p2_text()
                ),
                x: axis(THETA_RAD, [0.0, pi], true),
                y: axis("κ sin³θ − f_{r} (dimensionless)", [-0.1, 0.3], false),
                series: ss,
                marks: all,
                zero: true,
            })
        }
        "S3.c0invariant" => {
            let ts = (0.8f64).acos();
            let boundary = |c0: f64| -> Vec<(f64, f64)> {
                let r = |t: f64| rhs("2.5", "2", c0, t);
                // Ω₀ ∩ {θ̇ > 0} is θ̇ < √(R/(a sin θ)); none where R ≤ 0.
                let at = |t: f64| {
                    let v = r(t);
                    (
                        t,
                        if v > 0.0 {
                            (v / t.sin()).sqrt()
                        } else {
                            f64::NAN
                        },
                    )
                };
                let mut pts: Vec<(f64, f64)> = Vec::new();
                for t in grid(0.02, pi - 0.02, 600) {
                    let next = at(t);
                    // Where R changes sign between samples the boundary meets
                    // θ̇ = 0: add that point (bisection), so it does not stop
                    // a grid step short of the axis.
                    if let Some(&(t0, y0)) = pts.last() {
                        if y0.is_nan() != next.1.is_nan() {
                            let (mut lo, mut hi) = (t0, t);
                            for _ in 0..60 {
                                let mid = 0.5 * (lo + hi);
                                if (r(mid) > 0.0) == (r(lo) > 0.0) {
                                    lo = mid;
                                } else {
                                    hi = mid;
                                }
                            }
                            let z = if r(lo) > 0.0 { lo } else { hi };
                            if y0.is_nan() {
                                pts.push((z, f64::NAN));
                                pts.push((z, 0.0));
                            } else {
                                pts.push((z, 0.0));
                                pts.push((z, f64::NAN));
                            }
                        }
                    }
                    pts.push(next);
                }
                pts
            };
            Fig::Lines(Curves {
                title: "S3.c0invariant: the boundary of Ω_{0} for three c_{0}".into(),
                subtitle: format!(
                    "θ\u{307} > 0, disc on ice, {}, {}",
                    momenta("2.5", "2"),
                    p2_text()
                ),
                x: axis(THETA_RAD, [0.0, pi], true),
                y: axis(THETA_DOT_UNITS, [0.0, 8.0], false),
                series: [-5.0, 0.0, 5.0]
                    .into_iter()
                    .map(|c0| series(format!("c_{{0}} = {}", signed(c0)), boundary(c0)))
                    .collect(),
                marks: vec![marks(
                    "common to every c_{0}: cos θ* = 0.8 and θ = π/2",
                    vec![(ts, 7.9788f64.sqrt()), (pi / 2.0, 9.81f64.sqrt())],
                    Shape::Dot,
                )],
                zero: false,
            })
        }
        "S3.c0anypoint" => {
            let ts = (0.8f64).acos();
            // g(A + m a² sin²θ*)/(A + m a²) with m = a = 1, A = 0.25.
            let at_star = 9.81 * (0.25 + ts.sin().powi(2)) / 1.25;
            Fig::Lines(Curves {
                title: "S3.c0anypoint: at θ*, θ\u{307} = 0 the point is in Ω_{0} for every c_{0}"
                    .into(),
                subtitle: format!(
                    "right side R(θ) of (3.5); in Ω_{{0}} at θ\u{307} = 0 where R > 0; {}, {}",
                    momenta("2.5", "2"),
                    p2_text()
                ),
                x: axis(THETA_RAD, [0.0, pi], true),
                y: axis("R(θ) (m/s²)", [-20.0, 30.0], false),
                series: [-5.0, 0.0, 5.0]
                    .into_iter()
                    .map(|c0| {
                        series(
                            format!("c_{{0}} = {}", signed(c0)),
                            grid(0.02, pi - 0.02, 600)
                                .map(|t| (t, rhs("2.5", "2", c0, t)))
                                .collect(),
                        )
                    })
                    .collect(),
                marks: vec![marks(
                    "θ*, cos θ* = 0.8: R = g(A + ma²sin²θ*)/(A + ma²) > 0",
                    vec![(ts, at_star)],
                    Shape::Dot,
                )],
                zero: true,
            })
        }
        "S3.sub2" => {
            // Subcase 2, p_φ = p_ψ = 1: equilibria where c₀ = G(θ) (S3.sub2).
            let p = p2_texts("1", "1");
            let pm = p.map(|x| x.mid());
            let g = |t: f64| {
                let th = (t / 2.0).tan();
                super::ice::g_sub2(&pm, th, ((1.0 + th * th) / 2.0).ln())
            };
            let (tstar, gmin) = super::ice::min_g_sub2("1");
            let t_min = 2.0 * tstar.mid().atan();
            let g_min = gmin.mid();
            let curve: Vec<(f64, f64)> = grid(0.05, pi - 0.05, 600).map(|t| (t, g(t))).collect();
            let level = |c0: f64| vec![(0.0, c0), (pi, c0)];
            let eqs: Vec<(f64, f64)> = super::ice::equilibria_sub2("1", "3")
                .into_iter()
                .map(|r| (0.5 * (r[0] + r[1]), 3.0))
                .collect();
            Fig::Lines(Curves {
                title: "S3.sub2: subcase 2, equilibria where c_{0} = G(θ)".into(),
                subtitle: format!(
                    "disc on ice, p_{{φ}} = p_{{ψ}} = 1, {}; G falls then rises (proved)",
                    p2_text()
                ),
                x: axis(THETA_RAD, [0.0, pi], true),
                y: axis("c_{0}, G (m/s)", [-4.0, 12.0], false),
                series: vec![
                    series(
                        "G(θ): (3.3) at θ\u{307} = 0 vanishes where G = c_{0}",
                        curve,
                    ),
                    Series {
                        dashed: true,
                        ..series("c_{0} = 3: two equilibria", level(3.0))
                    },
                    Series {
                        dashed: true,
                        ..series(
                            format!("c_{{0}} = min G ≈ {g_min:.4}: one (tangent)"),
                            level(g_min),
                        )
                    },
                    Series {
                        dashed: true,
                        ..series("c_{0} = −3: none", level(-3.0))
                    },
                ],
                marks: vec![
                    marks("equilibria at c_{0} = 3 (certified)", eqs, Shape::Dot),
                    marks(
                        "the tangent point (certified min G)",
                        vec![(t_min, g_min)],
                        Shape::Ring,
                    ),
                ],
                zero: false,
            })
        }
        "S3.forms" => {
            let samples: &[(&str, &str, f64)] = &[
                ("2.5", "2", 0.0),
                ("2.5", "2", 20.0),
                ("1", "0.2", -20.0),
                ("1", "1", 5.0),
            ];
            let mut ss = Vec::new();
            for (pf, ps, c0) in samples {
                let p = p2_texts(pf, ps).map(|x| x.mid());
                let pts: Vec<(f64, f64)> = grid(0.02, pi - 0.02, 600)
                    .map(|t| {
                        let an = Angle::new(t);
                        let (l1, l2) = logs(&an);
                        let vx = vx_printed(&p, *c0, l1, l2, 1);
                        (t, rhs_3_5(&p, an.sin, an.cos, vx))
                    })
                    .collect();
                ss.push(series(
                    format!(
                        "(p_{{φ}}, p_{{ψ}}, c_{{0}}) = ({pf}, {ps}, {})",
                        signed(*c0)
                    ),
                    pts,
                ));
            }
            let (title, y, range) = (
                "S3.forms: right side R(θ) of (3.5); Ω_{0}-slices where R > 0",
                "R(θ) (m/s²)",
                [-40.0, 40.0],
            );
            Fig::Lines(Curves {
                title: title.into(),
                subtitle: format!("disc on ice, {}", p2_text()),
                x: axis(THETA_RAD, [0.0, pi], true),
                y: axis(y, range, false),
                series: ss,
                marks: vec![],
                zero: true,
            })
        }
        _ => return None,
    })
}

/// The picture of a claim with a figure; `mark` is the certified witness
/// box of region claims.
pub fn figure(id: &str, mark: Option<PhaseBox>) -> Result<Option<ClaimFigure>, String> {
    let Some(fig) = spec(id, mark) else {
        return Ok(None);
    };
    Ok(Some(match fig {
        Fig::Region {
            title,
            subtitle,
            f,
            win,
            names,
            mark,
        } => {
            let set = PairSet {
                f: |t: Interval, w: Interval| f(t, w),
            };
            let paving = pave(
                &set,
                win,
                PaveOptions {
                    eps: REGION_EPS,
                    max_boxes: REGION_BOXES,
                },
                |_, _, _| {},
            )
            .map_err(|e| format!("paving failed: {e:?}"))?;
            ClaimFigure::Region(RegionFigure {
                title,
                subtitle,
                paving: Box::new(paving),
                names,
                mark,
            })
        }
        Fig::Lines(curves) => ClaimFigure::Lines(curves),
    }))
}

/// Writes `<dir>/figures/<id>.svg` and `.png` for a claim with a figure;
/// `mark` is the certified witness box of region claims.
pub fn draw(id: &str, dir: &Path, mark: Option<PhaseBox>) -> Result<(), String> {
    match figure(id, mark)? {
        Some(fig) => draw_claim_figure(&fig, &dir.join("figures"), &id.replace('.', "_")),
        None => Ok(()),
    }
}

/// The witness box recorded in a result, if any.
pub fn witness_box(w: &serde_json::Value) -> Option<PhaseBox> {
    let b = w
        .get("witness")
        .and_then(|x| x.get("box"))
        .or_else(|| w.get("omega0_c0=0_vs_c0=1").and_then(|x| x.get("box")))?;
    let g = |k: &str, i: usize| b.get(k)?.get(i)?.as_f64();
    Some(PhaseBox {
        theta: [g("theta", 0)?, g("theta", 1)?],
        theta_dot: [g("theta_dot", 0)?, g("theta_dot", 1)?],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figures::claims::{legend, plot_rect, render_rgb, Swatch, SIZE};
    use crate::figures::Class;
    use std::collections::HashMap;

    /// Exact colours of the plot area's pixels (its frame left out), with
    /// their counts.
    fn plot_colours(buf: &[u8]) -> HashMap<(u8, u8, u8), usize> {
        let (px, py, pw, ph) = plot_rect();
        let mut out = HashMap::new();
        for y in py + 1..py + ph as i32 - 1 {
            for x in px + 1..px + pw as i32 - 1 {
                let k = 3 * (y as usize * SIZE.0 as usize + x as usize);
                *out.entry((buf[k], buf[k + 1], buf[k + 2])).or_insert(0) += 1;
            }
        }
        out
    }

    fn swatch_rgb(s: &Swatch) -> (u8, u8, u8) {
        match *s {
            Swatch::Fill(c) => c.rgb(),
            Swatch::Line { rgb, .. } | Swatch::Mark { rgb, .. } => rgb,
        }
    }

    /// Every colour the legend lists is drawn in the plot (for curves, on at
    /// least 30 pixels of exactly that colour: the middle of a 2-pixel line),
    /// and a region picture draws no colour its legend does not list.
    #[test]
    fn figures_draw_exactly_the_colours_their_legends_list() {
        for id in WITH_FIGURE {
            let fig = figure(id, None).expect("drawn").expect("has a figure");
            let entries = legend(&fig);
            assert!(!entries.is_empty(), "{id}: empty legend");
            let drawn = plot_colours(&render_rgb(&fig).expect("rendered"));
            for e in &entries {
                let c = swatch_rgb(&e.swatch);
                let least = match e.swatch {
                    Swatch::Line { .. } => 30,
                    _ => 1,
                };
                let n = drawn.get(&c).copied().unwrap_or(0);
                assert!(n >= least, "{id}: `{}` listed, {n} pixels drawn", e.text);
            }
            if let ClaimFigure::Region(_) = fig {
                let listed: Vec<(u8, u8, u8)> =
                    entries.iter().map(|e| swatch_rgb(&e.swatch)).collect();
                let hatch = entries
                    .iter()
                    .any(|e| e.swatch == Swatch::Fill(Class::Undefined));
                for (c, n) in &drawn {
                    let ok = listed.contains(c) || (hatch && *c == (0x22, 0x22, 0x22));
                    assert!(ok, "{id}: {c:?} drawn on {n} pixels, not in the legend");
                }
            }
        }
    }

    /// The witness box of a region picture is drawn and listed.
    #[test]
    fn region_figures_mark_their_witness() {
        let mark = window([0.7, 0.75], [5.4, 5.5]);
        let fig = figure("F1.10", Some(mark)).unwrap().unwrap();
        assert!(legend(&fig)
            .iter()
            .any(|e| matches!(e.swatch, Swatch::Mark { .. }) && e.text.contains("witness")));
        let with = plot_colours(&render_rgb(&fig).unwrap());
        let without = plot_colours(&render_rgb(&figure("F1.10", None).unwrap().unwrap()).unwrap());
        let black = |m: &HashMap<(u8, u8, u8), usize>| m.get(&(0, 0, 0)).copied().unwrap_or(0);
        assert!(black(&with) > 40 && black(&without) == 0);
    }

    /// Each curve has its own colour in the legend.
    #[test]
    fn curves_have_distinct_legend_colours() {
        for id in WITH_FIGURE {
            let Some(ClaimFigure::Lines(c)) = figure(id, None).unwrap() else {
                continue;
            };
            let fig = ClaimFigure::Lines(c);
            let lines: Vec<(u8, u8, u8)> = legend(&fig)
                .iter()
                .filter_map(|e| match e.swatch {
                    Swatch::Line { rgb, .. } => Some(rgb),
                    _ => None,
                })
                .collect();
            let ClaimFigure::Lines(c) = &fig else {
                unreachable!()
            };
            assert_eq!(lines.len(), c.series.len() + usize::from(c.zero), "{id}");
            for (i, a) in lines.iter().enumerate() {
                assert!(!lines[i + 1..].contains(a), "{id}: colour {a:?} twice");
            }
        }
    }
}
