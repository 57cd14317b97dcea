"""Certified motion from Python: tubes against the mpmath reference of
`tests/data/motion-reference.json` (written by tests/data/motion_reference.py,
an independent Taylor integrator at 50 digits), events, boxes of starts,
and the rod's singular points against their closed form."""

import json
from fractions import Fraction

import matplotlib
import mpmath
import numpy as np
import pytest

matplotlib.use("Agg")

import detach
from conftest import REPO, cli_json

REFERENCE = json.loads((REPO / "tests" / "data" / "motion-reference.json").read_text())


def holds(pair, text):
    """`pair` = (lo, hi) floats holds the decimal `text`, compared exactly."""
    return Fraction(pair[0]) <= Fraction(text) <= Fraction(pair[1])


def test_tubes_contain_the_reference_trajectories():
    for case in REFERENCE["trajectories"][:6]:
        scene = detach.Scene.load(case["scene"], **case["params"])
        for p in case["points"]:
            run = scene.flow((case["theta0"], case["theta_dot0"]), p["t"], until="none")
            assert run.stop == "end time reached", run.stop
            theta, theta_dot = run.end
            assert holds(theta, p["theta"]) and holds(theta_dot, p["theta_dot"])
            assert theta[1] - theta[0] < 1e-10 and theta_dot[1] - theta_dot[0] < 1e-10


def test_an_event_window_holds_the_reference_crossing():
    case = REFERENCE["events"][0]
    scene = detach.Scene.load(case["scene"], **case["params"])
    run = scene.flow((case["theta0"], case["theta_dot0"]), "3", until="U=0")
    assert run.stop == "first event"
    (event,) = run.events
    assert event.kind == "U=0"
    assert holds(event.time, case["time"])
    assert holds(event.theta, case["theta"]) and holds(event.theta_dot, case["theta_dot"])
    # The run ends at the event: its end time is the event's window.
    assert run.end_time == event.time


def test_the_run_is_the_cli_one():
    scene = detach.Scene.load("viscous-disc")
    run = scene.flow(("-1.5", "1"), "2", until="none")
    cli = cli_json("flow", "--scene", "viscous-disc", "--from", "-1.5,1", "--t", "2",
                   "--until", "none", "--json")
    assert run.json()["end"] == cli["end"] and run.steps == cli["steps"]
    assert str(run.end_time) == "2"


def test_the_band_covers_the_reference_at_its_times():
    case = REFERENCE["trajectories"][0]
    scene = detach.Scene.load(case["scene"], **case["params"])
    p = case["points"][0]
    band = scene.flow((case["theta0"], case["theta_dot0"]), p["t"], until="none").band(4)
    assert band.dtype.names == ("t_lo", "t_hi", "theta_lo", "theta_hi",
                                "theta_dot_lo", "theta_dot_hi")
    assert np.all(band["t_lo"] <= band["t_hi"]) and np.all(band["theta_lo"] <= band["theta_hi"])
    # Rows tile [0, t]: each starts where the one before ends.
    assert band["t_lo"][0] == 0.0 and np.all(band["t_lo"][1:] <= band["t_hi"][:-1])
    last = band[-1]
    assert Fraction(last["t_lo"]) <= Fraction(p["t"]) <= Fraction(last["t_hi"])
    assert Fraction(last["theta_lo"]) <= Fraction(p["theta"]) <= Fraction(last["theta_hi"])
    ax = scene.flow((case["theta0"], case["theta_dot0"]), p["t"], until="none").plot()
    assert len(ax.collections) == 1


def test_a_box_of_starts_gives_one_tube_for_all():
    case = REFERENCE["trajectories"][4]  # viscous-disc from (-1.5, 1)
    assert case["scene"] == "viscous-disc"
    scene = detach.Scene.load("viscous-disc")
    p = case["points"][-1]
    run = scene.flow((("-1.5005", "-1.4995"), ("0.9995", "1.0005")), p["t"], until="none")
    theta, theta_dot = run.end
    assert holds(theta, p["theta"]) and holds(theta_dot, p["theta_dot"])
    point = scene.flow(("-1.5", "1"), p["t"], until="none").end[0]
    assert theta[1] - theta[0] > 100 * (point[1] - point[0])


def test_bad_input_is_a_value_error():
    scene = detach.Scene.load("viscous-disc")
    with pytest.raises(ValueError, match="float"):
        scene.flow((-1.5, "1"), "2")
    with pytest.raises(ValueError, match="unknown event"):
        scene.flow(("-1.5", "1"), "2", until="sometimes")
    with pytest.raises(ValueError, match="end time"):
        scene.flow(("-1.5", "1"), "-1")
    with pytest.raises(ValueError, match="order"):
        scene.flow(("-1.5", "1"), "1", order=1)
    with pytest.raises(ValueError, match="pieces"):
        scene.flow(("-1.5", "1"), "1").band(0)


def rod_singular_thetas(mu):
    """tan θ = (3μ ∓ √(9μ² − 16))/2 (the rod's U = V = 0, l = 1), 50 digits."""
    mpmath.mp.dps = 50
    mu = mpmath.mpf(mu)
    d = mpmath.sqrt(9 * mu**2 - 16)
    return [mpmath.atan((3 * mu - d) / 2), mpmath.atan((3 * mu + d) / 2)]


def test_the_rods_singular_points_are_its_closed_form():
    points = detach.Scene.load("painleve-rod", mu="1.5").singular_points()["points"]
    singular = [p for p in points if p["kind"] == "singular"]
    assert len(singular) == 4 and all(p["unique"] for p in singular)
    for th in rod_singular_thetas("1.5"):
        hits = [p for p in singular
                if mpmath.mpf(p["theta"][0]) <= th <= mpmath.mpf(p["theta"][1])]
        assert len(hits) == 2, th  # θ̇ = ±√(g/(l sin θ))
    # Below 4/3 there is none.
    points = detach.Scene.load("painleve-rod", mu="1.3").singular_points()["points"]
    assert not [p for p in points if p["kind"] == "singular"]
    no_dynamics = detach.Scene.from_toml((REPO / "tests" / "data" / "vertical-line.toml").read_text())
    with pytest.raises(ValueError, match=r"no \[dynamics\]"):
        no_dynamics.singular_points()
    with pytest.raises(ValueError, match=r"no \[dynamics\]"):
        no_dynamics.flow(("0.5", "0"), "1")


def leaf_at(reach, theta, theta_dot):
    """Indices of the leaves holding the point (text, compared exactly)."""
    L = reach.leaves
    th, w = Fraction(theta), Fraction(theta_dot)
    return [i for i in range(len(L))
            if Fraction(float(L["theta_lo"][i])) <= th <= Fraction(float(L["theta_hi"][i]))
            and Fraction(float(L["theta_dot_lo"][i])) <= w <= Fraction(float(L["theta_dot_hi"][i]))]


def test_reach_agrees_with_the_reference_event_time():
    # The reference (mpmath): the rod at mu = 0.5 from (0.3, 4) reaches U = 0
    # at t = 0.11587...; so it reaches within 0.3 and not within 0.1.
    case = REFERENCE["events"][0]
    assert (case["theta0"], case["theta_dot0"], case["function"]) == ("0.3", "4", "omega")
    scene = detach.Scene.load(case["scene"], **case["params"])
    window = dict(theta=("0.25", "0.35"), theta_dot=("3.9", "4.1"), eps=1 / 16)
    late = scene.reach("0.3", until="U=0", **window)
    early = scene.reach("0.1", until="U=0", **window)
    assert late.complete and early.complete
    for i in leaf_at(late, "0.3", "4"):
        assert late.leaves["fate"][i] != 1  # not "avoids"
        if late.leaves["fate"][i] == 0:
            assert late.leaves["t_lo"][i] <= float(case["time"]) <= late.leaves["t_hi"][i]
    for i in leaf_at(early, "0.3", "4"):
        assert early.leaves["fate"][i] != 0  # not "reaches"
    inner, outer = late.area()
    assert 0 < inner <= outer <= 0.1 * 0.2
    assert inner > 0.5 * 0.02  # most of the window reaches by 0.3
    cli = cli_json("reach", "--scene", "painleve-rod", "--param", "mu=0.5", "--theta",
                   "0.25:0.35", "--theta-dot", "3.9:4.1", "--t", "0.3", "--until", "U=0",
                   "--eps", "0.0625", "--json")
    assert len(cli["leaves"]) == len(late)
    # The CLI sums in intervals, Python in exact rationals: the CLI's bounds
    # are the same or looser.
    assert Fraction(cli["area"]["inner"]) <= Fraction(inner)
    assert Fraction(cli["area"]["outer"]) >= Fraction(outer)
    with pytest.raises(ValueError, match="eps"):
        scene.reach("0.3", eps=2)
    with pytest.raises(ValueError, match="unknown event"):
        scene.reach("0.3", until="later")


def test_a_saved_trajectory_proof_verifies_and_a_moved_end_does_not(tmp_path):
    case = REFERENCE["trajectories"][4]  # viscous-disc from (-1.5, 1)
    scene = detach.Scene.load(case["scene"], **case["params"])
    p = case["points"][0]
    run = scene.flow((case["theta0"], case["theta_dot0"]), p["t"], until="none", proof=True)
    path = tmp_path / "traj.json"
    run.save_proof(path)
    assert detach.verify(path).verdict == "VALID"
    proof = json.loads(path.read_text())
    end = proof["statement"]["end"]
    # The claimed end holds the mpmath reference; one moved wholly above it
    # is a false claim the checker must refuse.
    lo, hi = Fraction(end["t"][0]), Fraction(end["t"][1])
    assert lo <= Fraction(p["theta"]) <= hi
    shift = 2 * (hi - lo) + Fraction(1, 10**9)
    end["t"] = [str(float(lo + shift)), str(float(hi + shift))]
    (tmp_path / "moved.json").write_text(json.dumps(proof))
    assert detach.verify(tmp_path / "moved.json").verdict == "INVALID"


def test_save_proof_of_a_run_made_without_proof_is_an_error(tmp_path):
    run = detach.Scene.load("viscous-disc").flow(("-1.5", "1"), "1", until="none")
    with pytest.raises(ValueError):
        run.save_proof(tmp_path / "x.json")


def test_a_saved_reach_proof_verifies_and_a_larger_inner_area_does_not(tmp_path):
    scene = detach.Scene.load("painleve-rod", mu="0.5")
    window = dict(theta=("0.25", "0.35"), theta_dot=("3.9", "4.1"), eps=1 / 16)
    paving = scene.reach("0.3", until="U=0", proof=True, **window)
    path = tmp_path / "reach.json"
    paving.save_proof(path)
    assert detach.verify(path).verdict == "VALID"
    proof = json.loads(path.read_text())
    inner = Fraction(proof["statement"]["area"]["inner"])
    # No more than the paving proved (the same leaves, or fewer).
    assert 0 < inner <= Fraction(paving.area()[0]) * (1 + Fraction(1, 10**12))
    assert paving.undecided_in_proof is not None and paving.undecided_in_proof >= 0
    proof["statement"]["area"]["inner"] = str(float(inner) * 1.5)
    (tmp_path / "more.json").write_text(json.dumps(proof))
    assert detach.verify(tmp_path / "more.json").verdict == "INVALID"
    with pytest.raises(ValueError, match="no proof"):
        scene.reach("0.3", until="U=0", **window).save_proof(tmp_path / "x.json")


ARRIVALS = json.loads((REPO / "tests" / "data" / "arrival-reference.json").read_text())


def test_the_rod_reaches_its_singular_line_when_the_reference_says():
    # tests/data/arrival_reference.py: Runge-Kutta in the desingularised time
    # (30 digits), not detach's integrator. With U=0 watched as well the
    # arrival is not proved (U vanishes at the node itself): the run says so.
    rod = detach.Scene.load("painleve-rod", **ARRIVALS["params"])
    for case in ARRIVALS["arrivals"]:
        run = rod.flow((case["theta0"], case["theta_dot0"]), "1", until="V=0")
        assert run.stop == "reaches the singular line V = 0", run.stop
        (event,) = run.events
        assert event.kind == "V=0"
        assert holds(event.time, case["time"]) and holds(event.theta, case["theta"])
        assert holds(event.theta_dot, case["theta_dot"])
    blocked = rod.flow(("0.8", "4"), "1", until="U=0,V=0")
    assert "U=0` may vanish before the singular line" in blocked.stop


def test_a_reach_paving_of_the_singular_line_plots_its_fates():
    # From (0.8, 3) the rod reaches V = 0 at t = 0.02555 (the reference
    # above): its leaf reaches within 0.1; the plot fills one patch a leaf in
    # the fate's colour.
    rod = detach.Scene.load("painleve-rod", **ARRIVALS["params"])
    reach = rod.reach("0.1", until="V=0", theta=("0.75", "0.85"), theta_dot=("2.5", "3.5"),
                      eps=1 / 8)
    (i,) = leaf_at(reach, "0.8", "3.0001")
    assert reach.leaves["fate"][i] == 0
    ax = reach.plot()
    (quads,) = ax.collections
    from matplotlib.colors import to_rgba
    from detach._plot import REACH_COLOURS

    faces = quads.get_facecolors()
    assert len(faces) == len(reach)
    for f, fate in zip(faces, reach.leaves["fate"]):
        assert tuple(f) == to_rgba(REACH_COLOURS[int(fate)])
