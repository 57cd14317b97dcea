"""A paving's `leaves` have one label column per constraint of the paving
(Ω and Ω₀), and each leaf's `cell` agrees with its own labels."""

import pytest

import detach

EDGES = ("theta_lo", "theta_hi", "theta_dot_lo", "theta_dot_hi")

# The cell a leaf is in when both of its labels are decided.
CELL_OF = {
    ("in", "in"): "omega_and_omega0",
    ("out", "out"): "not_omega_and_not_omega0",
    ("out", "in"): "not_omega_and_omega0",
    ("in", "out"): "omega_and_not_omega0",
}

BALL = """
name = "ball"
[domain]
theta = ["0", "1"]
theta_dot = ["-1", "1"]
[regions]
omega = "theta_dot^2 < theta"
"""


@pytest.mark.parametrize(
    "scene, kw",
    [
        (lambda: detach.Scene.load("painleve-rod", mu="1.5"), {}),
        # A region steers refinement only: both constraints are still labelled.
        (lambda: detach.Scene.load("painleve-rod", mu="1.5"), {"region": "omega"}),
        # Without omega0 in the file, Ω₀ = Ω: still two constraints.
        (lambda: detach.Scene.from_toml(BALL), {}),
    ],
    ids=["rod", "rod-region", "file-without-omega0"],
)
def test_one_label_column_per_constraint(scene, kw):
    leaves = scene().pave(eps=1 / 64, **kw).leaves
    assert leaves.dtype.names == EDGES + ("omega", "omega0", "cell")
    assert len(leaves) > 100
    undefined = 0
    for leaf in leaves:
        pair = (str(leaf["omega"]), str(leaf["omega0"]))
        assert set(pair) <= set(detach.LABELS)
        if "undefined" in pair:
            want = "undefined"
            undefined += 1
        else:
            want = CELL_OF.get(pair, "undecided")
        assert leaf["cell"] == want, (pair, leaf["cell"])
    assert undefined < len(leaves)
