"""Proof files, verification, pictures and pandas."""

import json

import matplotlib

matplotlib.use("Agg")

import detach


def test_saved_proof_is_valid_and_a_changed_one_is_not(tmp_path):
    paving = detach.Scene.load("painleve-rod", mu="1.5").pave(eps=1 / 64)
    path = tmp_path / "rod.json"
    paving.save_proof(path)
    v = detach.verify(path)
    assert v.valid and v.verdict == "VALID" and "painleve-rod" in v.claim
    # Claim more inner area than proved: the checker must refuse.
    proof = json.loads(path.read_text())
    first = proof["statement"]["areas"][0]
    assert first["set"] == "omega"
    first["inner"] = str(1.5 * float(first["inner"]))
    (tmp_path / "bad.json").write_text(json.dumps(proof))
    assert detach.verify(tmp_path / "bad.json").verdict == "INVALID"


def test_verify_of_a_non_proof_is_a_value_error(tmp_path):
    p = tmp_path / "x.json"
    p.write_text("{}")
    try:
        detach.verify(p)
    except ValueError as e:
        assert str(e)
    else:
        raise AssertionError("a non-proof was accepted")


def test_plot_draws_every_class_present_in_the_cli_palette():
    paving = detach.Scene.load("painleve-rod", mu="1.5").pave(eps=1 / 64)
    ax = paving.plot()
    present = set(paving.leaves["cell"])
    assert len(ax.collections) == len(present)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "Ω∩Ω₀: contact persists" in labels
    # Colours are the CLI's (src/figures/raster.rs: Class::rgb).
    assert detach.palette()["omega_and_omega0"][2] == "#77aadd"
    assert "undefined" in present  # the rod's V = 0 lines


def test_to_pandas_has_one_row_per_leaf():
    paving = detach.Scene.load("viscous-disc").pave(eps=1 / 32)
    df = paving.to_pandas()
    assert len(df) == len(paving)
    assert list(df.columns) == [
        "theta_lo", "theta_hi", "theta_dot_lo", "theta_dot_hi", "omega", "omega0", "cell",
    ]
    # The cell of a leaf follows from its labels.
    both_in = df[(df.omega == "in") & (df.omega0 == "in")]
    assert (both_in.cell == "omega_and_omega0").all()
    assert (df.theta_lo < df.theta_hi).all()


def test_area_sums_are_consistent():
    """Ω = (Ω∩Ω₀) ∪ (Ω∩Ω̄₀): the bounds of the parts bracket the whole."""
    a = detach.Scene.load("painleve-rod", mu="2").pave(eps=1 / 128).areas
    whole, p, q = a["omega"], a["omega_and_omega0"], a["omega_and_not_omega0"]
    assert p.inner + q.inner <= whole.outer
    assert whole.inner <= p.outer + q.outer
    assert a["omega"].inner_text.startswith(repr(whole.inner)[:6])
