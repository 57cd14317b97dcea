"""Independent reference values for scenes/painleve-rod.toml, with mpmath at 50 digits.

The system (derivation in the scene file's comments): a uniform rod, mass m,
half-length l, one end sliding on a rough floor (Coulomb coefficient mu) in
the direction that gives Painlevé's paradoxes; theta is the rod's angle with
the floor. In contact the end's normal acceleration is

    Lambda'' = U + (N/m) V,   U = -g + l thetadot^2 sin(theta),
                              V = 1 + 3 cos^2(theta) - 3 mu sin(theta) cos(theta).

Omega = {U < 0}, Omega0 = {N > 0} = {U/V < 0} (N = -m U/V solves Lambda'' = 0).

For each mu in MUS, with m = l = 1, g = 9.81 and the domain
theta in [0, pi/2], thetadot in [-10, 10], this script computes:

* the theta-interval where V < 0 (the paradox band). For cos(theta) > 0,
  V/cos^2(theta) = tan^2(theta) - 3 mu tan(theta) + 4, so V < 0 exactly when
  tan(theta) lies strictly between the roots (3 mu -+ sqrt(9 mu^2 - 16))/2 of
  t^2 - 3 mu t + 4 = 0; they are real and distinct iff mu > 4/3 (both are
  positive: product 4, sum 3 mu). At theta = pi/2, V = 1 > 0.
* the areas of Omega, Omega0 and the four cells Omega&Omega0,
  notOmega&notOmega0, notOmega&Omega0, Omega&notOmega0.

The areas are 1-D integrals over theta of the thetadot-measure of each set,
which is closed-form in theta: U < 0 iff thetadot^2 < g/(l sin theta), so the
slice of Omega has length L(theta) = 2 min(10, sqrt(g/(l sin theta))) (20 at
theta = 0). Where V > 0, Omega0's slice is Omega's (length L); where V < 0 it
is the complement (length 20 - L). The lines V = 0 and the curve U = 0 have
measure zero. So, with B = {theta : V(theta) < 0}:

    Omega&Omega0        = int_{not B} L        notOmega&notOmega0 = int_{not B} (20 - L)
    notOmega&Omega0     = int_{B} (20 - L)     Omega&notOmega0    = int_{B} L

The integrand is smooth between the breakpoints theta_c = asin(g/(100 l))
(where the slice of Omega reaches thetadot = +-10) and the band ends, so
mpmath.quad (tanh-sinh) runs on each piece between sorted breakpoints. The
four cells must add up to the domain's area 10 pi; the script asserts it.

Nothing here comes from detach's code: the formulas are the scene file's
derivation, written again. Run: python3 tests/data/painleve_reference.py
(writes tests/data/painleve-reference.json next to this file).
"""
import json
import os

import mpmath as mp

mp.mp.dps = 50

MUS = ["0.5", "1.3", "1.5", "2", "1.3334"]
M, L_HALF, G = mp.mpf(1), mp.mpf(1), mp.mpf("9.81")
W = mp.mpf(10)  # thetadot in [-W, W]
TH_LO, TH_HI = mp.mpf(0), mp.pi / 2
DIGITS = 40  # significant digits written to the JSON


def num(x):
    if x == 0:
        return "0"
    return mp.nstr(x, DIGITS, strip_zeros=False)


def band(mu):
    """(lo, hi) of the open theta-interval where V < 0, or None."""
    disc = 9 * mu**2 - 16
    if disc <= 0:
        return None
    r = mp.sqrt(disc)
    return mp.atan((3 * mu - r) / 2), mp.atan((3 * mu + r) / 2)


def V(theta, mu):
    s, c = mp.sin(theta), mp.cos(theta)
    return 1 + 3 * c**2 - 3 * mu * s * c


def slice_omega(theta):
    """Length of {thetadot in (-W, W) : l sin(theta) thetadot^2 < g}."""
    s = mp.sin(theta)
    if s <= 0:
        return 2 * W
    return 2 * min(W, mp.sqrt(G / (L_HALF * s)))


def integrate(f, breaks, lo, hi):
    pts = sorted({lo, hi, *[b for b in breaks if lo < b < hi]})
    return mp.fsum(mp.quad(f, [a, b]) for a, b in zip(pts, pts[1:]))


def areas(mu):
    theta_c = mp.asin(G / (W**2 * L_HALF))  # slice of Omega hits +-W here
    b = band(mu)
    breaks = [theta_c] + (list(b) if b else [])
    full = lambda t: slice_omega(t)
    compl = lambda t: 2 * W - slice_omega(t)
    omega = integrate(full, breaks, TH_LO, TH_HI)
    if b:
        in_band = integrate(full, breaks, b[0], b[1])
        in_band_c = integrate(compl, breaks, b[0], b[1])
        # sanity: V really is negative inside and positive outside the band
        assert V((b[0] + b[1]) / 2, mu) < 0
        assert V(b[0] / 2, mu) > 0 and V((b[1] + TH_HI) / 2, mu) > 0
    else:
        in_band = in_band_c = mp.mpf(0)
        assert all(V(TH_LO + (TH_HI - TH_LO) * k / 1000, mu) >= 0 for k in range(1001))
    total = (TH_HI - TH_LO) * 2 * W
    cells = {
        "omega_and_omega0": omega - in_band,
        "not_omega_and_not_omega0": (total - omega) - in_band_c,
        "not_omega_and_omega0": in_band_c,
        "omega_and_not_omega0": in_band,
    }
    assert abs(mp.fsum(cells.values()) - total) < mp.mpf(10) ** -40
    out = {
        "omega": omega,
        "omega0": cells["omega_and_omega0"] + cells["not_omega_and_omega0"],
        **cells,
    }
    return theta_c, b, out


def main():
    cases = []
    for mu_text in MUS:
        mu = mp.mpf(mu_text)
        theta_c, b, ar = areas(mu)
        case = {
            "parameters": {"m": "1", "l": "1", "g": "9.81", "mu": mu_text},
            "theta_omega_reaches_edge": num(theta_c),
            "paradox_band": None,
            "areas": {k: num(v) for k, v in ar.items()},
        }
        if b:
            r = mp.sqrt(9 * mu**2 - 16)
            case["paradox_band"] = {
                "tan_roots": [num((3 * mu - r) / 2), num((3 * mu + r) / 2)],
                "theta": [num(b[0]), num(b[1])],
                "theta_degrees": [num(mp.degrees(b[0])), num(mp.degrees(b[1]))],
            }
        cases.append(case)
    doc = {
        "description": (
            "Reference values for scenes/painleve-rod.toml from "
            "tests/data/painleve_reference.py (mpmath, 50 digits; printed to "
            f"{DIGITS} significant digits). Omega = {{U < 0}}, Omega0 = {{U/V < 0}}, "
            "U = -g + l thetadot^2 sin(theta), V = 1 + 3cos^2(theta) - "
            "3 mu sin(theta)cos(theta); domain theta in [0, pi/2], thetadot in "
            "[-10, 10]. paradox_band is the open theta-interval where V < 0 (null "
            "when empty); theta_omega_reaches_edge is asin(g/(100 l)), below which "
            "the whole thetadot-range is in Omega."
        ),
        "domain": {"theta": ["0", "pi/2"], "theta_dot": ["-10", "10"]},
        "domain_area": num(mp.pi * 10),
        "critical_mu": {
            "value": "4/3",
            "decimal": num(mp.mpf(4) / 3),
            "meaning": (
                "V < 0 somewhere on (0, pi/2) iff mu > 4/3: the discriminant "
                "9 mu^2 - 16 of tan^2 - 3 mu tan + 4 must be positive. At mu = 4/3 "
                "V >= 0 with V = 0 only at tan(theta) = 2."
            ),
        },
        "cases": cases,
        "literature": {
            "citation": (
                "F. Génot, B. Brogliato, New results on Painlevé paradoxes, "
                "European Journal of Mechanics A/Solids 18 (1999) 653-677"
            ),
            "recorded": [
                {
                    "fact": (
                        "For the uniform rod (I = m l^2/3) sliding in the paradox "
                        "direction, Painlevé's paradoxes (inconsistency: no contact "
                        "solution; indeterminacy: two) occur only for mu > 4/3."
                    ),
                    "confidence": (
                        "high: the classical threshold, also derived independently "
                        "above (critical_mu)"
                    ),
                },
                {
                    "fact": (
                        "From a consistent sliding state the rod cannot reach an "
                        "inconsistent state by sliding. Above a second critical "
                        "value mu_C > 4/3 a special sliding solution reaches the "
                        "singular point where U = 0 and V = 0 together; there the "
                        "contact force may grow unbounded while its impulse stays "
                        "bounded."
                    ),
                    "confidence": (
                        "medium: recalled, and as summarised by later work citing "
                        "the paper (e.g. Hogan and Kristiansen, 'Le canard de "
                        "Painlevé', 2017); the value of mu_C and any angles the "
                        "paper gives are not recorded because they could not be "
                        "checked here"
                    ),
                },
            ],
        },
    }
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "painleve-reference.json")
    with open(path, "w") as f:
        json.dump(doc, f, indent=2, ensure_ascii=False)
        f.write("\n")
    print("wrote", path)


if __name__ == "__main__":
    main()
