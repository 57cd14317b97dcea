//! The `derived` formulas checked against the mechanics the paper states,
//! independently of the formulas themselves: contact reactions and
//! accelerations from Newton/Lagrange equations solved as linear systems
//! (nalgebra), free-flight Λ̈ from the constraint function differentiated twice
//! along the free motion (nested dual numbers), and energy balances along the
//! equations of motion.

use detach::number::param::ParamSet;
use detach::number::scalar::{Dual, Scalar};
use detach::scene::{Angle, Scene, SceneId, Variant};
use nalgebra::{Matrix3, Matrix4, Vector3, Vector4};
use proptest::prelude::*;

type D = Dual<f64>;
type DD = Dual<Dual<f64>>;

fn close(a: f64, b: f64, what: &str) {
    let tol = 1e-9 * (1.0 + a.abs().max(b.abs()));
    assert!((a - b).abs() <= tol, "{what}: {a} vs {b}");
}

/// A paper scene with its parameters' midpoints by name.
struct Disc {
    scene: Scene,
    params: ParamSet,
}

impl Disc {
    fn new(id: SceneId, overrides: &[(String, String)]) -> Disc {
        let (scene, params) = Scene::build(id, overrides).unwrap();
        Disc { scene, params }
    }
    fn p(&self, name: &str) -> f64 {
        self.params.get(name).mid()
    }
}

fn viscous() -> Disc {
    Disc::new(SceneId::ViscousDisc, &[])
}

fn smooth() -> Disc {
    Disc::new(SceneId::SmoothDisc, &[])
}

fn ice(c0: &str) -> Disc {
    Disc::new(SceneId::IceDisc, &[("c0".into(), c0.into())])
}

/// h(θ) = a + b sin θ of (1.3), written here from the geometry, generic.
fn h_of<T: Scalar>(d: &Disc, th: T) -> T {
    T::lift(d.params.get("a")) + T::lift(d.params.get("b")) * th.sin()
}

/// (h, h', h'') at θ, from a nested dual number.
fn h_derivatives(d: &Disc, th: f64) -> (f64, f64, f64) {
    let hd = h_of(d, DD::variable(D::variable(th, 0), 0));
    (hd.value.value, hd.value.grad[0], hd.grad[0].grad[0])
}

/// ψ̇ from the integrals (2.3), and ∂T/∂θ of T (2.1) at fixed ψ̇, φ̇ (by a
/// dual in θ): the θ equation of (2.2) is A θ̈ = ∂T/∂θ + generalised forces.
fn rotation(d: &Disc, th: f64, w: f64) -> (f64, f64) {
    let (big_a, big_c, pf, ps) = (d.p("A"), d.p("C"), d.p("p_phi"), d.p("p_psi"));
    let (s, c) = th.sin_cos();
    let psi_dot = (ps - pf * c) / (big_a * s * s);
    let phi_dot = pf / big_c - psi_dot * c;
    let (sx, cx) = D::variable(th, 0).sin_cos();
    let half = D::constant(0.5);
    let t = half
        * D::constant(big_a)
        * (D::constant(w * w) + D::constant(psi_dot * psi_dot) * sx.sqr())
        + half * D::constant(big_c) * (D::constant(psi_dot) * cx + D::constant(phi_dot)).sqr();
    (psi_dot, t.grad[0])
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Example 1: Newton's equations with the contact condition, solved for
    /// (ÿ, θ̈, N), against the derived θ̈ and Ω₀; free flight against Ω.
    #[test]
    fn viscous_disc_matches_newton(th in -3.1f64..3.1, w in -10.0f64..10.0) {
        let d = viscous();
        let (m, c, mu, g) = (d.p("m"), d.p("C"), d.p("mu"), d.p("g"));
        let (h, h1, h2) = h_derivatives(&d, th);
        // m ÿ = −m g + N;  C θ̈ = −N h' − μ h² θ̇;  ÿ − h' θ̈ − h'' θ̇² = 0
        let kkt = Matrix3::new(m, 0.0, -1.0, 0.0, c, h1, 1.0, -h1, 0.0);
        let rhs = Vector3::new(-m * g, -mu * h * h * w, h2 * w * w);
        let sol = kkt.lu().solve(&rhs).unwrap();
        let (thdd, n) = (sol[1], sol[2]);
        let an = Angle::new(th);
        let scene = &d.scene;
        close(scene.acceleration(Variant::Derived, &an, w), thdd, "θ̈");
        let cons = scene.constraints(Variant::Derived, &an);
        // Ω₀ is written as −N (C + m h'²)/m
        close(cons.omega0.eval(w), -n * (c + m * h1 * h1) / m, "Ω₀ = −N(C+mh'²)/m");

        // free flight: y = y₀ + v t − g t²/2, θ = θ₀ + θ̇ t (no force, no torque)
        let t = DD::variable(D::variable(0.0, 0), 0);
        let y = DD::int(5) + DD::int(1) * t - DD::lift(d.params.get("g")) * t.sqr() / DD::int(2);
        let theta_t = DD::constant(D::constant(th)) + DD::constant(D::constant(w)) * t;
        let lam = y - h_of(&d, theta_t);
        let lam_dd = lam.grad[0].grad[0];
        close(cons.omega.eval(w), lam_dd, "Ω = free-flight Λ̈");
    }

    /// Example 1: dE/dt = F ν along the derived equation of motion, with
    /// E = ½ m ẏ² + ½ C θ̇² + m g y, y = h(θ), ẏ = h'(θ) θ̇ in contact.
    #[test]
    fn viscous_disc_energy_balance(th in -3.1f64..3.1, w in -10.0f64..10.0) {
        let d = viscous();
        let (m, c, mu, g) = (d.p("m"), d.p("C"), d.p("mu"), d.p("g"));
        let (h_val, h1, h2) = h_derivatives(&d, th);
        // E and its partial derivatives by hand from T and Π (no scene formula):
        let e_theta = m * h1 * h2 * w * w + m * g * h1;
        let e_w = (m * h1 * h1 + c) * w;
        let scene = &d.scene;
        let thdd = scene.acceleration(Variant::Derived, &Angle::new(th), w);
        let de_dt = e_theta * w + e_w * thdd;
        let f_nu = -mu * (w * h_val).powi(2);
        close(de_dt, f_nu, "dE/dt = Fν");
    }

    /// §2: the θ equation of (2.2) from T of (2.1) (∂T/∂θ by duals at fixed
    /// ψ̇, φ̇), with z̈ = N/m − g and contact, solved for (z̈, θ̈, N).
    #[test]
    fn smooth_disc_matches_lagrange(th in 0.05f64..3.09, w in -10.0f64..10.0) {
        let d = smooth();
        let (m, a, big_a, g) = (d.p("m"), d.p("a"), d.p("A"), d.p("g"));
        let (s, c) = th.sin_cos();
        let (_, dt_dtheta) = rotation(&d, th, w);
        // m z̈ − N = −m g;  A θ̈ + a cos θ N = ∂T/∂θ;  z̈ − a cos θ θ̈ = −a sin θ θ̇²
        let kkt = Matrix3::new(m, 0.0, -1.0, 0.0, big_a, a * c, 1.0, -a * c, 0.0);
        let sol = kkt.lu().solve(&Vector3::new(-m * g, dt_dtheta, -a * s * w * w)).unwrap();
        let (thdd, n) = (sol[1], sol[2]);
        let scene = &d.scene;
        let an = Angle::new(th);
        close(scene.acceleration(Variant::Derived, &an, w), thdd, "θ̈ (2.5)");
        let u = scene.constraints(Variant::Derived, &an).omega.eval(w);
        let v = 1.0 / m + a * a * c * c / big_a;
        close(u, -n * v, "U = −V N in contact");
        // free flight: z̈ = −g, A θ̈ = ∂T/∂θ
        let free = -g - a * c * (dt_dtheta / big_a) + a * s * w * w;
        close(u, free, "U = free-flight Λ̈");
        // (2.8) as printed is U/(a sin θ)
        let printed = scene.constraints(Variant::Printed, &an).omega.eval(w);
        close(printed * a * s, u, "(2.8) = (2.7)/(a sin θ)");
        // energy (2.11) is conserved along (2.5)
        let e = scene.energy(&Angle::new(D::variable(th, 0)), D::variable(w, 1)).unwrap();
        close(e.grad[0] * w, -(e.grad[1] * thdd), "dE/dt (2.11)");
    }

    /// §3: Newton–Euler with the blade constraint v_P·n = 0: unknowns
    /// (z̈, θ̈, N, R); the reaction R enforces v_n = −a θ̇ sin θ.
    #[test]
    fn ice_disc_matches_newton_euler(th in 0.05f64..3.09, w in -10.0f64..10.0, c0 in -3.0f64..3.0) {
        let d = ice(&format!("{c0:.3}"));
        let (m, a, big_a, g) = (d.p("m"), d.p("a"), d.p("A"), d.p("g"));
        let (s, c) = th.sin_cos();
        let (psi_dot, dt_dtheta) = rotation(&d, th, w);
        let an = Angle::new(th);
        // v_x of (3.1), as the paper prints it
        let v_x = |t: D| {
            let (pf, ps) = (D::constant(d.p("p_phi")), D::constant(d.p("p_psi")));
            D::constant(d.p("c0"))
                - D::constant(a / big_a) * (ps * (t / D::int(2)).tan().ln() - pf * t.sin().ln())
        };
        let vx = v_x(D::constant(th)).value;
        // (3.1) integrates the e₁ momentum equation: dv_x/dθ = −a τ, τ = ψ̇ sin θ
        let dvx = v_x(D::variable(th, 0)).grad[0];
        close(dvx, -a * psi_dot * s, "dv_x/dθ = −a τ");
        // m z̈ − N = −m g
        // A θ̈ + a c N − a s R = ∂T/∂θ
        // R + m a s θ̈ = m v_x ψ̇ − m a θ̇² c        (R = m(v̇_n + v_x ψ̇))
        // z̈ − a c θ̈ = −a s θ̇²                      (Λ̈ = 0)
        let kkt = Matrix4::new(
            m, 0.0, -1.0, 0.0,
            0.0, big_a, a * c, -a * s,
            0.0, m * a * s, 0.0, 1.0,
            1.0, -a * c, 0.0, 0.0,
        );
        let rhs = Vector4::new(-m * g, dt_dtheta, m * vx * psi_dot - m * a * w * w * c, -a * s * w * w);
        let sol = kkt.lu().solve(&rhs).unwrap();
        let (thdd, n) = (sol[1], sol[2]);
        let scene = &d.scene;
        close(scene.acceleration(Variant::Derived, &an, w), thdd, "θ̈ (3.3)");
        for v in [Variant::Derived, Variant::Printed] {
            close(scene.constraints(v, &an).omega0.eval(w), -n / m, "Ω₀ = −N/m (3.5)");
        }
        // Λ̈ = U₀ + V₀ N off contact: drop the Λ̈ = 0 row, take N as given.
        let lam_dd = |nn: f64| {
            let k3 = Matrix3::new(m, 0.0, 0.0, 0.0, big_a, -a * s, 0.0, m * a * s, 1.0);
            let r3 = Vector3::new(-m * g + nn, dt_dtheta - a * c * nn, m * vx * psi_dot - m * a * w * w * c);
            let x = k3.lu().solve(&r3).unwrap();
            x[0] - a * c * x[1] + a * s * w * w
        };
        let v0 = lam_dd(1.0) - lam_dd(0.0);
        // V₀ as scenes/ice-disc.toml derives it (not the printed 1/m of (3.4))
        close(1.0 / m + a * a * c * c / (big_a + m * a * a * s * s), v0, "V₀");
        // energy (3.2) is conserved along (3.3)
        let e = scene.energy(&Angle::new(D::variable(th, 0)), D::variable(w, 1)).unwrap();
        close(e.grad[0] * w, -(e.grad[1] * thdd), "dE/dt (3.2)");
    }
}
