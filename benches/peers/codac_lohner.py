"""Codac's side of the validated-integration comparison (detach's is
`cargo bench --bench motion` and `detach flow`).

The ODEs are the scenes' contact dynamics, state x = (θ, θ̇), ẋ = (θ̇, F):
* painleve-rod (scenes/painleve-rod.toml, m=1, l=1, g=9.81):
  F = 3 U (cos θ − μ sin θ)/(l V), U = l sin θ θ̇² − g,
  V = 1 + 3 cos²θ − 3 μ sin θ cos θ;
* viscous-disc (scenes/viscous-disc.toml, a=1, b=0.5, m=1, C=0.3, μ=0.8, g=9.81):
  F = (−m g h′ − μ h² θ̇ − m h′ h″ θ̇²)/(C + m h′²),
  h = a + b sin θ, h′ = b cos θ, h″ = −b sin θ.
A decimal parameter that is not a double (9.81, 0.3, 0.8) enters as the
interval [prev_float, next_float] around its nearest double.

Cases: rod μ=0.5 from (0.6, 2) to t=0.5 and to t=1; viscous disc from
(−1.5, 1) to t=2; rod μ=0 from (1.3, 1.3) to t=1. For each, as in Codac's
CtcLohner example: `create_tdomain(Interval(0, t_end), dt)`,
`SlicedTube(tdomain, IntervalVector(2))`, the degenerate start box (the
doubles nearest the decimals) set at t=0, then
`CtcLohner(f).contract(tube, TimePropag.FWD)` (`contractions` and `eps` at
their defaults, 5 and 0.1), over a series of fixed slice widths dt; the end
box is `tube(t_end)`. Codac 2.1.2's CtcLohner has no order setting: its
Lohner step is of order 2 (the first-order Taylor term plus the order-2
Lagrange remainder over the a-priori enclosure). Only the contract call is
timed. TimePropag.FWD, because the default FWD_BWD adds a backward pass that
leaves the end box unchanged (checked at dt = 0.01 and 0.002) and doubles the
time. The call's cost grows faster than the number of slices (about 1 ms a
slice at 500 slices, 4 ms at 5000): CtcLohner::contract evaluates `tube[0]`,
a copy of component 0 over every slice, in its loop condition. A run whose
enclosure blows up returns infinite bounds, not an exception: "bounded" is
false there. Where tests/data/motion-reference.json has the end point
(mpmath, 35 digits), "contains_reference" says whether the end box holds it
(compared exactly, as rationals; null where the box is unbounded).

    pip install codac==2.1.2
    python3 benches/peers/codac_lohner.py > benches/peers/codac-lohner.json

(from the repository root; a few minutes.)
"""
import datetime
import json
import math
import os
import platform
import sys
import time
from fractions import Fraction

import codac
from codac import (AnalyticFunction, CtcLohner, Interval, IntervalVector,
                   SlicedTube, TimePropag, VectorVar, cos, create_tdomain,
                   next_float, prev_float, sin, sqr)

BUDGET_S = 10.0  # stop refining a series once one run takes longer
CHEAP_S = 0.2  # a point faster than this is run CHEAP_RUNS times (median)
CHEAP_RUNS = 5
DTS = [0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001, 0.0005, 0.0002, 0.0001,
       0.00005, 0.00002, 0.00001]
HERE = os.path.dirname(os.path.abspath(__file__))
REFERENCE = os.path.join(HERE, "..", "..", "tests", "data", "motion-reference.json")


def dec(text):
    """The decimal `text` as an Interval: its double if exact, else the two
    doubles around it."""
    v = float(text)
    if Fraction(v) == Fraction(text):
        return Interval(v)
    return Interval(prev_float(v), next_float(v))


def rod(P):
    x = VectorVar(2)
    th, w = x[0], x[1]
    l, g, mu = dec(P["l"]), dec(P["g"]), dec(P["mu"])
    U = l * sin(th) * sqr(w) - g
    V = 1 + 3 * sqr(cos(th)) - 3 * mu * sin(th) * cos(th)
    F = 3 * U * (cos(th) - mu * sin(th)) / (l * V)
    return AnalyticFunction([x], [w, F])


def viscous(P):
    x = VectorVar(2)
    th, w = x[0], x[1]
    a, b, m, C, mu, g = (dec(P[k]) for k in ["a", "b", "m", "C", "mu", "g"])
    h, h1, h2 = a + b * sin(th), b * cos(th), -(b * sin(th))
    F = (-(m * g * h1) - mu * sqr(h) * w - m * h1 * h2 * sqr(w)) / (C + m * sqr(h1))
    return AnalyticFunction([x], [w, F])


ROD = dict(m="1", l="1", g="9.81")
CASES = [  # name, scene, params, builder, from, t_end
    ("rod_mu05", "painleve-rod", dict(ROD, mu="0.5"), rod, ("0.6", "2"), "0.5"),
    ("rod_mu05", "painleve-rod", dict(ROD, mu="0.5"), rod, ("0.6", "2"), "1"),
    ("viscous_disc_2s", "viscous-disc",
     dict(a="1", b="0.5", m="1", C="0.3", mu="0.8", g="9.81"), viscous, ("-1.5", "1"), "2"),
    ("rod_mu0_1s", "painleve-rod", dict(ROD, mu="0"), rod, ("1.3", "1.3"), "1"),
]


def reference(scene, params, start, t_end):
    """(θ, θ̇) at t_end as strings from motion-reference.json, or None."""
    try:
        with open(REFERENCE) as fh:
            doc = json.load(fh)
    except OSError:
        return None
    for tr in doc["trajectories"]:
        if (tr["scene"] == scene and tr["theta0"] == start[0] and tr["theta_dot0"] == start[1]
                and all(tr["params"].get(k) == v for k, v in params.items())):
            for p in tr["points"]:
                if Fraction(p["t"]) == Fraction(t_end):
                    return [p["theta"], p["theta_dot"]]
    return None


def integrate(f, start, t_end, dt):
    """A fresh tube with the start box set; returns (contract-call time, tube)."""
    tube = SlicedTube(create_tdomain(Interval(0, t_end), dt), IntervalVector(2))
    tube.set(IntervalVector([float(start[0]), float(start[1])]), 0.0)
    ctc = CtcLohner(f)
    t0 = time.perf_counter()
    ctc.contract(tube, TimePropag.FWD)
    return time.perf_counter() - t0, tube


def measure(name, scene, params, build, start, t_end_text):
    f = build(params)
    t_end = float(t_end_text)
    ref = reference(scene, params, start, t_end_text)
    integrate(f, start, t_end, DTS[0])  # untimed: one-off start-up costs
    runs = []
    for dt in DTS:
        times = []
        try:
            while len(times) < (1 if times and times[0] > CHEAP_S else CHEAP_RUNS):
                s, tube = integrate(f, start, t_end, dt)
                times.append(s)
        except RuntimeError as e:  # e.g. no a-priori enclosure found for a slice
            runs.append({"dt": dt, "order": 2, "error": str(e), "bounded": False})
            if ref is not None:
                runs[-1]["contains_reference"] = None
            print(f"{name} t={t_end_text} dt={dt} error: {e}", file=sys.stderr)
            continue
        s = sorted(times)[len(times) // 2]
        end = tube(t_end)
        lo = [end[i].lb() for i in range(2)]
        hi = [end[i].ub() for i in range(2)]
        bounded = all(math.isfinite(v) for v in lo + hi)
        run = {
            "dt": dt,
            "order": 2,
            "steps": (tube.nb_slices() - 1) // 2,  # slices between the gates
            "time_s": s,
            "timed_runs": len(times),
            "theta": [lo[0], hi[0]],
            "theta_dot": [lo[1], hi[1]],
            "max_width": max(h - l for l, h in zip(lo, hi)) if bounded else math.inf,
            "bounded": bounded,
        }
        if ref is not None:  # null where unbounded (an infinite box holds it trivially)
            run["contains_reference"] = all(
                Fraction(lo[i]) <= Fraction(ref[i]) <= Fraction(hi[i])
                for i in range(2)) if bounded else None
        runs.append(run)
        print(f"{name} t={t_end_text} dt={dt} {s:.4f}s width={run['max_width']:.3g}"
              f" contains={run.get('contains_reference')}", file=sys.stderr)
        if s > BUDGET_S:
            break
    case = {"name": name, "scene": scene, "params": params, "from": list(start),
            "t_end": t_end}
    if ref is not None:
        case["reference"] = ref
    case["runs"] = runs
    return case


def main():
    load_before = os.getloadavg()
    cases = [measure(*c) for c in CASES]
    # JSON has no infinity: an unbounded end box is written with null bounds.
    for c in cases:
        for r in c["runs"]:
            if not r["bounded"] and "error" not in r:
                r["theta"] = r["theta_dot"] = None
                r["max_width"] = None
    doc = {
        "source": "benches/peers/codac_lohner.py: Codac's CtcLohner (TimePropag.FWD, contractions=5, "
                  "eps=0.1, fixed order 2) on a SlicedTube over [0, t_end] with slices of width dt, "
                  "from a degenerate start box; time_s is the contract call alone (the median of 5 "
                  "runs where one takes under 0.2 s); the end box is tube(t_end); null bounds and "
                  "max_width mean an unbounded (infinite) end box",
        "codac_version": codac.__version__,
        "python": platform.python_version(),
        "machine": {
            "uname": " ".join(platform.uname()),
            "nproc": os.cpu_count(),
            "loadavg_before": load_before,
            "loadavg_after": os.getloadavg(),
        },
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "cases": cases,
    }
    json.dump(doc, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
