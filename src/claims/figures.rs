//! What the pictures of the witnesses of non-confirmed claims show; they are
//! drawn by [`crate::figures::claims`].

use super::example1::{self, P1};
use super::ice::{logs, rhs_3_5, vx_printed};
use super::smooth::{p2_texts, ClearedSlope};
use super::witness::{window, PairSet};
use crate::figures::claims::{draw_claim_figure, ClaimFigure, Curves};
use crate::pave::{pave, PaveOptions, PhaseBox};
use crate::roots::isolate::RealFn;
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
        f: Region,
        win: PhaseBox,
        names: [&'static str; 2],
        mark: Option<PhaseBox>,
    },
    Lines(Curves),
}

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

fn spec(id: &str, mark: Option<PhaseBox>) -> Option<Fig> {
    let pi = std::f64::consts::PI;
    Some(match id {
        "F1.10" => Fig::Region {
            title: "Ω: printed (1.10) vs free-flight Λ̈ < 0".into(),
            f: viscous_region(true, false),
            win: window([0.0, 1.6], [0.0, 8.0]),
            names: ["printed", "derived"],
            mark,
        },
        "F1.11" => Fig::Region {
            title: "Ω₀: printed (1.11) vs N > 0".into(),
            f: viscous_region(true, true),
            win: window([-1.6, 1.6], [0.0, 10.0]),
            names: ["printed", "derived"],
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
                title: "ice, (p_φ, p_ψ) = (2.5, 2): Ω₀ at c₀ = 0 vs c₀ = 1".into(),
                f: Box::new(move |th, w| [om("0", th, w), om("1", th, w)]),
                win: window([0.05, 3.09], [0.0, 8.0]),
                names: ["c₀ = 0", "c₀ = 1"],
                mark,
            }
        }
        "F1.7" | "F1.9" => {
            let p = P1::texts(example1::DEFAULTS).map(|x| x.mid());
            let pts = |k: i32| {
                grid(-pi, pi, 400)
                    .map(|t| (t, example1::printed_1_7(&p, t.sin(), t.cos(), 1.0, k)))
                    .collect::<Vec<_>>()
            };
            let newton: Vec<(f64, f64)> = grid(-pi, pi, 400)
                .map(|t| (t, example1::newton(&p, t.sin(), t.cos(), 1.0, 1).0))
                .collect();
            Fig::Lines(Curves {
                title: "θ̈ at θ̇ = 1 (defaults): printed (1.7) vs Newton".into(),
                x: "θ",
                y: "θ̈",
                series: vec![("printed (1.7)".into(), pts(2)), ("Newton".into(), newton)],
                marks: vec![(0.0, -5.1864), (0.0, -10.3727)],
            })
        }
        "F3.4" => {
            let v = |t: f64| 1.0 + t.cos().powi(2) / (0.25 + t.sin().powi(2));
            Fig::Lines(Curves {
                title: "V₀ (m = a = 1, A = 0.25): printed 1/m vs Newton–Euler".into(),
                x: "θ",
                y: "V₀",
                series: vec![
                    (
                        "printed".into(),
                        grid(0.0, pi, 200).map(|t| (t, 1.0)).collect(),
                    ),
                    (
                        "Newton–Euler".into(),
                        grid(0.0, pi, 200).map(|t| (t, v(t))).collect(),
                    ),
                ],
                marks: vec![(1.0, v(1.0))],
            })
        }
        "S1.eq" => {
            let (a, b, m, c, g): (f64, f64, f64, f64, f64) = (1.0, 0.5, 1.0, 0.3, 9.81);
            let disc = |mu: f64| (mu * mu * (a - b).powi(4) - 4.0 * m * g * b * c) / (c * c);
            Fig::Lines(Curves {
                title: "θ = −π/2: trace² − 4 det against μ (< 0: focus)".into(),
                x: "μ",
                y: "trace² − 4 det",
                series: vec![
                    (
                        "discriminant".into(),
                        grid(0.0, 20.0, 200).map(|u| (u, disc(u))).collect(),
                    ),
                    ("0".into(), vec![(0.0, 0.0), (20.0, 0.0)]),
                ],
                marks: vec![(0.8, disc(0.8)), (20.0, disc(20.0))],
            })
        }
        "S2.case1fr" => Fig::Lines(Curves {
            title: "α = 0: f_r(θ) = −cos²θ touches 0 at π/2".into(),
            x: "θ",
            y: "f_r",
            series: vec![(
                "f_r".into(),
                grid(0.0, pi, 200).map(|t| (t, -t.cos().powi(2))).collect(),
            )],
            marks: vec![(pi / 2.0, 0.0)],
        }),
        "S2.12count" | "S2.12type" | "S2.12components" => {
            let samples: &[(&str, &str)] = if id == "S2.12components" {
                &[("2", "2"), ("2.5", "2")]
            } else {
                &[("1", "1"), ("0.3", "0.3"), ("1", "0.2"), ("2.5", "2")]
            };
            let mut series = Vec::new();
            let mut marks = Vec::new();
            for (pf, ps) in samples {
                let f = ClearedSlope(p2_texts(pf, ps));
                let pts: Vec<(f64, f64)> = grid(0.0, pi, 300).map(|t| (t, f.eval(t))).collect();
                let scale = pts.iter().map(|p| p.1.abs()).fold(1e-300, f64::max);
                series.push((
                    format!("(p_φ, p_ψ) = ({pf}, {ps})"),
                    pts.iter().map(|&(x, y)| (x, y / scale)).collect(),
                ));
                if let (Some(rs), _, _) = super::smooth::equilibria(pf, ps) {
                    marks.extend(rs.iter().map(|r| (0.5 * (r[0] + r[1]), 0.0)));
                }
            }
            series.push(("0".into(), vec![(0.0, 0.0), (pi, 0.0)]));
            Fig::Lines(Curves {
                title: "sin³θ·Π̃'(θ), scaled; dots: certified equilibria".into(),
                x: "θ",
                y: "scaled slope",
                series,
                marks,
            })
        }
        "S3.c0invariant" | "S3.c0anypoint" => {
            let p = p2_texts("2.5", "2").map(|x| x.mid());
            let mut series = Vec::new();
            for c0 in [-5.0, 0.0, 5.0] {
                let pts: Vec<(f64, f64)> = grid(0.05, pi - 0.05, 400)
                    .filter_map(|t| {
                        let an = Angle::new(t);
                        let (l1, l2) = logs(&an);
                        let r = rhs_3_5(&p, an.sin, an.cos, vx_printed(&p, c0, l1, l2, 1));
                        (r > 0.0).then(|| (t, (r / (p.a * an.sin)).sqrt().min(12.0)))
                    })
                    .collect();
                series.push((format!("Ω₀ boundary θ̇ > 0, c₀ = {c0}"), pts));
            }
            let ts = (0.8f64).acos();
            Fig::Lines(Curves {
                title: "(2.5, 2): Ω₀ boundaries for three c₀ meet at cos θ* = 0.8 and π/2".into(),
                x: "θ",
                y: "θ̇",
                series,
                marks: vec![
                    (ts, 7.9788f64.sqrt()),
                    (pi / 2.0, 9.81f64.sqrt()),
                    (ts, 0.0),
                ],
            })
        }
        "S3.forms" | "S3.sub2" => {
            let samples: &[(&str, &str, f64)] = &[
                ("2.5", "2", 0.0),
                ("2.5", "2", 20.0),
                ("1", "0.2", -20.0),
                ("1", "1", 5.0),
            ];
            let mut series = Vec::new();
            for (pf, ps, c0) in samples {
                let p = p2_texts(pf, ps).map(|x| x.mid());
                let pts: Vec<(f64, f64)> = grid(0.05, pi - 0.05, 400)
                    .map(|t| {
                        let an = Angle::new(t);
                        let (l1, l2) = logs(&an);
                        let r = if id == "S3.forms" {
                            rhs_3_5(&p, an.sin, an.cos, vx_printed(&p, *c0, l1, l2, 1))
                        } else {
                            super::ice::thdd_3_3(
                                &p,
                                an.sin,
                                an.cos,
                                vx_printed(&p, *c0, l1, l2, 1),
                                1,
                            )
                        };
                        (t, r.clamp(-40.0, 40.0))
                    })
                    .collect();
                series.push((format!("({pf}, {ps}, c₀ = {c0})"), pts));
            }
            series.push(("0".into(), vec![(0.0, 0.0), (pi, 0.0)]));
            let title = if id == "S3.forms" {
                "right side R(θ) of (3.5), clipped: Ω₀-slices where R > 0"
            } else {
                "θ̈ of (3.3) at θ̇ = 0, clipped: equilibria where it vanishes"
            };
            Fig::Lines(Curves {
                title: title.into(),
                x: "θ",
                y: "value",
                series,
                marks: vec![],
            })
        }
        _ => return None,
    })
}

/// Writes `<dir>/figures/<id>.svg` and `.png` for a claim with a figure;
/// `mark` is the certified witness box of region claims.
pub fn draw(id: &str, dir: &Path, mark: Option<PhaseBox>) -> Result<(), String> {
    let Some(fig) = spec(id, mark) else {
        return Ok(());
    };
    let fig = match fig {
        Fig::Region {
            title,
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
                    eps: 1.0 / 32.0,
                    max_boxes: 50_000,
                },
                |_, _, _| {},
            )
            .map_err(|e| format!("paving failed: {e:?}"))?;
            ClaimFigure::Region {
                title,
                paving: Box::new(paving),
                win,
                names,
                mark,
            }
        }
        Fig::Lines(curves) => ClaimFigure::Lines(curves),
    };
    draw_claim_figure(&fig, &dir.join("figures"), &id.replace('.', "_"))
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
