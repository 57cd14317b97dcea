//! The two problems detach and Codac both pave (benches `peers` and
//! `paving`): Ω of (2.8) of the smooth disc (g=9.81, a=1, A=0.25, p_φ=1,
//! p_ψ=0.6) on θ ∈ [0.05, π−0.05], and the printed Ω₀ (1.11) of the
//! viscous disc at its defaults.

// Shared by several bench binaries; each uses part of it.
#![allow(dead_code)]

use detach::number::param::enclose_window_end;
use detach::scene::{Domain, Scene, SceneId, Variant};
use inari::Interval;

pub struct Problem {
    pub key: String,
    pub title: String,
    pub scene: Scene,
    pub variant: Variant,
    pub domain: Domain,
    /// Index into `standard_cells()`: 0 Ω, 1 Ω₀.
    pub cell: usize,
}

pub fn problems() -> Vec<Problem> {
    let params: Vec<(String, String)> = [
        ("g", "9.81"),
        ("a", "1"),
        ("A", "0.25"),
        ("p_phi", "1"),
        ("p_psi", "0.6"),
    ]
    .iter()
    .map(|(n, v)| (n.to_string(), v.to_string()))
    .collect();
    let smooth = Scene::build(SceneId::SmoothDisc, &params)
        .expect("peer parameters")
        .0;
    let off = enclose_window_end("theta", "0.05").expect("decimal");
    let window = Domain {
        theta: [off, Interval::PI - off],
        theta_dot: smooth.domain().theta_dot,
    };
    let viscous = Scene::default_of(SceneId::ViscousDisc);
    let vd = viscous.domain();
    vec![
        Problem {
            key: "omega_2_8".into(),
            title: "Ω of (2.8), p_φ=1, p_ψ=0.6, θ ∈ [0.05, π−0.05]".into(),
            scene: smooth,
            variant: Variant::Printed,
            domain: window,
            cell: 0,
        },
        Problem {
            key: "omega0_1_11".into(),
            title: "Ω₀ of (1.11), Example 1 (printed, defaults)".into(),
            scene: viscous,
            variant: Variant::Printed,
            domain: vd,
            cell: 1,
        },
    ]
}
