"""Parameter atlases from Python: the CLI's atlas on the same input, and
statuses against closed forms written in the scene files' headers."""

from fractions import Fraction

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

import detach
from conftest import cli_json

PARADOXES = ["not_omega_and_omega0", "omega_and_not_omega0"]


def test_the_rods_threshold_is_four_thirds():
    # painleve-rod.toml: the paradox cells are non-empty iff mu > 4/3.
    atlas = detach.Scene.load("painleve-rod").param_atlas("mu=1:2")
    assert atlas.complete
    assert len(atlas.thresholds) == 2
    for t in atlas.thresholds:
        assert (t["below"], t["above"]) == ("empty", "nonempty")
        lo, hi = (Fraction(x) for x in t["enclosure"])
        assert lo < Fraction(4, 3) < hi
        assert hi - lo < Fraction(1, 10**9)


def test_the_atlas_is_the_cli_one():
    args = ["--scene", "viscous-disc", "--x", "b=0:0.9", "--y", "mu=0.25:2", "--eps", "0.0625"]
    cli = cli_json("params", *args, "--json")
    atlas = detach.Scene.load("viscous-disc").param_atlas(("b", "0", "0.9"), y="mu=0.25:2", eps=1 / 16)
    assert atlas.json == cli
    # the arrays are the JSON's boxes, in order
    assert len(atlas) == len(cli["boxes"]) == len(atlas.bounds)
    for k, box in enumerate(cli["boxes"][:20]):
        for s in PARADOXES:
            assert atlas.status[s][k] == box["sets"][s]


def test_example_1_non_uniqueness_needs_b_above_g_over_100():
    # viscous-disc.toml: Omega0 minus Omega is non-empty iff b > g/100.
    atlas = detach.Scene.load("viscous-disc").param_atlas(
        "b=0:0.9", y="mu=0.25:2", sets="not_omega_and_omega0", eps=1 / 32
    )
    b = atlas.bounds[:, 0, :]
    st = atlas.status["not_omega_and_omega0"]
    g100 = 9.81 / 100
    assert np.all(b[st == "empty", 1] <= g100)
    assert np.all(b[st == "nonempty", 0] > g100)
    assert (st == "empty").any() and (st == "nonempty").any()
    share = atlas.shares["not_omega_and_omega0"]
    assert abs(share.nonempty + share.empty + share.undecided - 1) < 1e-12
    assert share.label == "Ω̄∩Ω₀"


def test_the_other_parameters_keep_the_scenes_values():
    # At r = 2 the ladder's threshold in mu is 2 sqrt(3)/2 = sqrt(3).
    from conftest import REPO

    ladder = detach.Scene.from_file(REPO / "tests" / "data" / "ladder.toml", r="2")
    atlas = ladder.param_atlas("mu=0:3", eps=2**-20)
    for t in atlas.thresholds:
        lo, hi = (Fraction(x) for x in t["enclosure"])
        assert lo * lo < 3 < hi * hi


def test_a_saved_atlas_proof_verifies(tmp_path):
    atlas = detach.Scene.load("painleve-rod").param_atlas("mu=1:2", eps=1 / 64)
    path = tmp_path / "rod.json"
    atlas.save_proof(path)
    v = detach.verify(path)
    assert v.valid and "painleve-rod" in v.claim


def test_bad_requests_are_value_errors():
    rod = detach.Scene.load("painleve-rod")
    for kwargs, says in [
        ({"x": "nu=1:2"}, "unknown parameter `nu`"),
        ({"x": "mu=1"}, "NAME=LO:HI"),
        ({"x": ("mu", 1.0, 2)}, "float"),
        ({"x": "mu=1:2", "sets": ["paradox"]}, "unknown region `paradox`"),
        ({"x": "mu=1:2", "y": "mu=0:1"}, "both axes vary `mu`"),
        ({"x": "mu=1:2", "eps": 0}, "eps must be"),
        ({"x": "mu=1:2", "max_boxes": 0}, "max_boxes must be"),
    ]:
        with pytest.raises(ValueError) as e:
            rod.param_atlas(**kwargs)
        assert says in str(e.value), (kwargs, str(e.value))


def test_plot_draws_each_class_of_the_plane():
    atlas = detach.Scene.load("viscous-disc").param_atlas("b=0:0.9", y="mu=0.25:2", eps=1 / 16)
    ax = atlas.plot()
    classes = set(atlas._codes()[:, -1])
    assert len(ax.collections) == len(classes) >= 2
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "undecided" in labels or len(classes) == len(labels)
