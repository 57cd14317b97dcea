"""Independent reference times of arrival at the singular line V = 0 of
Painlevé's rod (mu = 1.5), with mpmath.

In contact the rod's motion is theta'' = 3 U (cos theta - mu sin theta)/(l V)
with U = l sin(theta) thetadot^2 - g and V = 1 + 3 cos^2 theta - 3 mu sin theta
cos theta (scenes/painleve-rod.toml, transcribed by hand). Where V > 0 and the
motion runs into the lower root theta_0 of V (tan theta_0 = (3 mu - sqrt(9
mu^2 - 16))/2) with thetadot > 0, it reaches the stable node (theta_0,
sqrt(g/(l sin theta_0))) of the desingularised field in finite time. In the
rescaled time s (dt = V ds) the field is smooth:
    theta' = V thetadot,  thetadot' = 3 U (cos theta - mu sin theta)/l,  t' = V,
and the arrival time is the limit of t(s) as s -> infinity; V decays like
exp(-7.34 s) near the node, so t(8) is the limit to within 1e-24.

Computed by the classical Runge-Kutta method of order 4 written here, at 30
digits, with steps 1/2000 and 1/4000 of s over [0, 8], and Richardson's
extrapolation of the two; the two raw runs must agree to 1e-13 and the
extrapolation is written to 20 digits (its error is far below the runs'
difference/15). theta and thetadot at s = 8 must be within 1e-15 of the node. Nothing here comes from
detach's code. Run: python3 tests/data/arrival_reference.py (writes
tests/data/arrival-reference.json next to this file; a few seconds).
"""
import json
import os

import mpmath as mp

STARTS = [("0.8", "3"), ("0.8", "4"), ("0.85", "3.5")]


def arrival(theta0, theta_dot0, steps_per_unit, s_end=8):
    mp.mp.dps = 30
    l, g, mu = mp.mpf(1), mp.mpf("9.81"), mp.mpf("1.5")

    def field(y):
        th, om, _ = y
        U = l * mp.sin(th) * om**2 - g
        V = 1 + 3 * mp.cos(th) ** 2 - 3 * mu * mp.sin(th) * mp.cos(th)
        return [V * om, 3 * U * (mp.cos(th) - mu * mp.sin(th)) / l, V]

    y = [mp.mpf(theta0), mp.mpf(theta_dot0), mp.mpf(0)]
    h = mp.mpf(1) / steps_per_unit
    for _ in range(steps_per_unit * s_end):
        k1 = field(y)
        k2 = field([a + h / 2 * b for a, b in zip(y, k1)])
        k3 = field([a + h / 2 * b for a, b in zip(y, k2)])
        k4 = field([a + h * b for a, b in zip(y, k3)])
        y = [a + h / 6 * (b + 2 * c + 2 * d + e) for a, b, c, d, e in zip(y, k1, k2, k3, k4)]
    th, om, t = y
    root = mp.atan((3 * mu - mp.sqrt(9 * mu**2 - 16)) / 2)
    node = mp.sqrt(g / (l * mp.sin(root)))
    assert abs(th - root) < mp.mpf(10) ** -15, (th, root)
    assert abs(om - node) < mp.mpf(10) ** -15, (om, node)
    return t, root, node


def main():
    out = []
    for th0, om0 in STARTS:
        t1, root, node = arrival(th0, om0, 2000)
        t2, _, _ = arrival(th0, om0, 4000)
        assert abs(t1 - t2) < mp.mpf(10) ** -13, (t1, t2)
        t = t2 + (t2 - t1) / 15
        s = lambda x: mp.nstr(x, 20, strip_zeros=False)
        out.append({"theta0": th0, "theta_dot0": om0, "time": s(t),
                    "theta": s(root), "theta_dot": s(node), "runs_differ": mp.nstr(abs(t1 - t2), 3)})
        print(th0, om0, s(t), mp.nstr(abs(t1 - t2), 3))
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "arrival-reference.json")
    with open(path, "w") as f:
        json.dump({"source": "tests/data/arrival_reference.py: RK4 in the desingularised "
                   "time at 30 digits, steps 1/2000 and 1/4000, extrapolated",
                   "scene": "painleve-rod", "params": {"m": "1", "l": "1", "g": "9.81", "mu": "1.5"},
                   "arrivals": out}, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
