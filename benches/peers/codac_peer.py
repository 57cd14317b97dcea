"""Codac's side of `cargo bench --bench peers`, which runs this script first.

Two regions: Ω of (2.8) (g=9.81, a=1, A=0.25, p_φ=1, p_ψ=0.6) on
θ ∈ [0.05, π−0.05], θ̇ ∈ [−10, 10]; and the printed Ω₀ (1.11) of Example 1 at
its defaults (a=1, b=0.5, m=1, C=0.3, μ=0.8, g=9.81) on θ ∈ [−π, π],
θ̇ ∈ [−10, 10]. For each, Codac's `sivia` and `pave(SepInverse)` over a range
of ε (Codac's ε is an absolute box width); only the paving call is timed.
The undecided area is the area of the boundary boxes (outer − inner).

    pip install codac==2.1.2
    python3 benches/peers/codac_peer.py > benches/peers/codac.json

(what the bench does before it measures detach).
"""
import datetime
import json
import math
import os
import platform
import subprocess
import sys
import time

import codac
from codac import (AnalyticFunction, Interval, IntervalVector, PavingInOut,
                   SepInverse, VectorVar, cos, oo, pave, sin, sivia, sqr)

BUDGET_S = 10.0  # stop refining a series once one run takes longer
CHEAP_S = 0.2  # a point faster than this is run CHEAP_RUNS times (median)
CHEAP_RUNS = 5


def omega_28():
    x = VectorVar(2)
    t, w = x[0], x[1]
    g, a, A, pf, ps = 9.81, 1.0, 0.25, 1.0, 0.6
    s, c = sin(t), cos(t)
    phi = g / (a * s) - c / (A * A * sqr(sqr(s))) * (pf - ps * c) * (ps - pf * c)
    f = AnalyticFunction([x], sqr(w) - phi)
    box = IntervalVector([[0.05, math.pi - 0.05], [-10, 10]])
    return f, box


def omega0_111():
    x = VectorVar(2)
    t, w = x[0], x[1]
    a, b, m, C, mu, g = 1.0, 0.5, 1.0, 0.3, 0.8, 9.81
    h, h1, h2 = a + b * sin(t), b * cos(t), -(b * sin(t))
    q = -(2 * C * h2) * sqr(w) + mu * sqr(h) * h1 * w - g * (2 * C + m * sqr(h1))
    f = AnalyticFunction([x], q)
    box = IntervalVector([[-math.pi, math.pi], [-10, 10]])
    return f, box


def area(boxes):
    return math.fsum(b[0].diam() * b[1].diam() for b in boxes)


def measure(name, make, eps_list):
    f, box = make()
    out = []
    def run(method, eps):
        if method == "sivia":
            return sivia(box, f, Interval(-oo, 0), eps)
        return pave(box, SepInverse(f, Interval(-oo, 0)), eps)

    for method in ["sivia", "sep"]:
        # One untimed call first: the first call of a series pays one-off
        # start-up costs (about 30 ms here) that are not paving.
        run(method, eps_list[0])
        for eps in eps_list:
            # A cheap point is timed several times and its median kept: one
            # run of a few ms varies by a third between calls.
            times = []
            while len(times) < (1 if times and times[0] > CHEAP_S else CHEAP_RUNS):
                t0 = time.perf_counter()
                p = run(method, eps)
                times.append(time.perf_counter() - t0)
            dt = sorted(times)[len(times) // 2]
            inner = p.boxes(PavingInOut.inner)
            bound = p.boxes(PavingInOut.bound)
            complem = p.boxes(PavingInOut.outer_complem)
            out.append({
                "problem": name,
                "method": method,
                "eps": eps,
                "time_s": dt,
                "inner_area": area(inner),
                "undecided_area": area(bound),
                "boxes": len(inner) + len(bound) + len(complem),
                "undecided_boxes": len(bound),
            })
            print(f"{name} {method} eps={eps} {dt:.3f}s undecided={area(bound):.5g}", file=sys.stderr)
            if dt > BUDGET_S:
                break
    return out


def main():
    eps_list = [0.4 / 2 ** k for k in range(0, 12)]
    load_before = os.getloadavg()
    runs = measure("omega_2_8", omega_28, eps_list) + measure("omega0_1_11", omega0_111, eps_list)
    doc = {
        "peer": "codac",
        "version": codac.__version__,
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "machine": {
            "uname": " ".join(platform.uname()),
            "nproc": os.cpu_count(),
            "python": platform.python_version(),
            "loadavg_before": load_before,
            "loadavg_after": os.getloadavg(),
        },
        "note": "time_s is the paving call alone (the median of 5 runs where one takes under 0.2 s); "
                "undecided_area is the area of the boundary boxes; boxes counts the inner, boundary and outer-complement boxes Codac returns",
        "runs": runs,
    }
    json.dump(doc, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
