"""Independent reference areas for tests/area.rs, with mpmath at 30 digits.

The area of {q(θ, θ̇) < 0} ∩ [θ_lo, θ_hi] × [-10, 10] is ∫ L(θ) dθ, L the length
of the θ̇-slice: the quadratic's roots clipped to the window. The integrand is
smooth between breakpoints where a root crosses ±10, the discriminant or the
leading coefficient vanishes; those are found by sign changes on a fine grid
and refined with findroot, and mpmath's tanh-sinh quadrature runs on each
piece. Formulas are written from the paper's equations and the derivations in
scenes/*.toml, not from the Rust code. Run: python3 tests/data/area_reference.py
"""
import mpmath as mp

mp.mp.dps = 30
W = mp.mpf(10)


def slice_length(a2, a1, a0):
    """Length of {w in (-W, W): a2 w^2 + a1 w + a0 < 0}."""
    def clip(x):
        return min(max(x, -W), W)
    if a2 == 0:
        if a1 == 0:
            return 2 * W if a0 < 0 else mp.mpf(0)
        r = -a0 / a1
        return clip(r) + W if a1 > 0 else W - clip(r)
    d = a1 * a1 - 4 * a2 * a0
    if d <= 0:
        return mp.mpf(0) if a2 > 0 else 2 * W
    s = mp.sqrt(d)
    r1, r2 = sorted([(-a1 - s) / (2 * a2), (-a1 + s) / (2 * a2)])
    inner = clip(r2) - clip(r1)
    return inner if a2 > 0 else 2 * W - inner


def area(coeffs, lo, hi, grid=4000):
    def q_at(t, w):
        a2, a1, a0 = coeffs(t)
        return a2 * w * w + a1 * w + a0

    def disc(t):
        a2, a1, a0 = coeffs(t)
        return a1 * a1 - 4 * a2 * a0

    fns = [lambda t: q_at(t, W), lambda t: q_at(t, -W), disc, lambda t: coeffs(t)[0]]
    eps = mp.mpf(10) ** -20
    ts = [lo + (hi - lo) * (i + mp.mpf(1) / 3) / grid for i in range(grid)]
    breaks = [lo, hi]
    for f in fns:
        vals = [f(t) for t in ts]
        for (t0, v0), (t1, v1) in zip(zip(ts, vals), zip(ts[1:], vals[1:])):
            if v0 == 0:
                breaks.append(t0)
            elif v0 * v1 < 0:
                breaks.append(mp.findroot(f, (t0, t1), solver="anderson", tol=eps))
    breaks = sorted(set(breaks))
    L = lambda t: slice_length(*coeffs(t))
    return mp.fsum(mp.quad(L, [a, b]) for a, b in zip(breaks, breaks[1:]) if b > a)


m, a, A, g, pf, ps, c0 = (mp.mpf(1), mp.mpf(1), mp.mpf("0.25"), mp.mpf("9.81"),
                          mp.mpf("2.5"), mp.mpf(2), mp.mpf(0))


def smooth_omega(t):
    # (2.8): θ̇² − Φ(θ) < 0
    s, c = mp.sin(t), mp.cos(t)
    phi = g / (a * s) - c / (A ** 2 * s ** 4) * (pf - ps * c) * (ps - pf * c)
    return (mp.mpf(1), mp.mpf(0), -phi)


vb, vC, vmu = mp.mpf("0.5"), mp.mpf("0.3"), mp.mpf("0.8")


def viscous_omega(t):
    # free flight: −g − h''θ̇² < 0, h'' = −b sin θ
    return (vb * mp.sin(t), mp.mpf(0), -g)


def viscous_omega0(t):
    # −N(C + m h'²)/m = μh²h'θ̇ − C g − C h''θ̇², h = a + b sin θ
    h, h1, h2 = a + vb * mp.sin(t), vb * mp.cos(t), -vb * mp.sin(t)
    return (-vC * h2, vmu * h * h * h1, -vC * g)


def ice_omega0(t):
    # derived: a sin θ θ̇² − g − a cos θ θ̈, θ̈ of (3.3), v_x of (3.1)
    s, c = mp.sin(t), mp.cos(t)
    tau = (ps - pf * c) / (A * s)
    tau1 = (pf - ps * c) / (A * s * s)
    vx = c0 - a / A * (ps * mp.log(mp.tan(t / 2)) - pf * mp.log(s))
    acc = (-(m * g * a * c) + m * a * vx * tau - A * tau * tau1) / (A + m * a * a)
    return (a * s, mp.mpf(0), -g - a * c * acc)


if __name__ == "__main__":
    print("mpmath", mp.__version__, "dps", mp.mp.dps)
    for name, f, lo, hi in [
        ("smooth-disc omega", smooth_omega, 0, mp.pi),
        ("viscous-disc derived omega", viscous_omega, -mp.pi, mp.pi),
        ("viscous-disc derived omega0", viscous_omega0, -mp.pi, mp.pi),
        ("ice-disc derived omega0", ice_omega0, 0, mp.pi),
    ]:
        print(f"{name}: {mp.nstr(area(f, mp.mpf(lo), hi), 25)}")
