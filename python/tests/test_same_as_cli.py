"""Python's pavings and areas equal the CLI's on the same input, bit for bit
(the reference is `detach pave --json --leaves` and `detach area --json`
from the binary built from the same checkout)."""

import csv

import pytest

import detach
from conftest import REPO, cli_json, run_cli

# (CLI arguments, Scene.load arguments, pave keywords)
CASES = [
    (["--scene", "painleve-rod", "--eps", "0.0078125"], ("painleve-rod", {}), {"eps": 1 / 128}),
    (
        ["--scene", "painleve-rod", "--param", "mu=1.2", "--eps", "0.00390625", "--method", "natural"],
        ("painleve-rod", {"mu": "1.2"}),
        {"eps": 1 / 256, "method": "natural"},
    ),
    (
        ["--scene", "ice-disc", "--variant", "printed", "--eps", "0.0078125", "--theta", "0.5:pi/2"],
        ("ice-disc", {"variant": "printed"}),
        {"eps": 1 / 128, "theta": ("0.5", "pi/2")},
    ),
    (
        ["--scene", "viscous-disc", "--method", "contract", "--eps", "0.015625", "--region", "omega0"],
        ("viscous-disc", {}),
        {"eps": 1 / 64, "method": "contract", "region": "omega0"},
    ),
    (
        ["--scene", "smooth-disc", "--eps", "0.0009765625", "--max-boxes", "500"],
        ("smooth-disc", {}),
        {"eps": 1 / 1024, "max_boxes": 500},
    ),
]


def read_leaves_csv(path):
    with open(path) as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    return rows[0], rows[1:]


@pytest.mark.parametrize("cli_args, load, kw", CASES, ids=[c[1][0] + "-" + str(i) for i, c in enumerate(CASES)])
def test_pave_equals_cli(tmp_path, cli_args, load, kw):
    csv_path = tmp_path / "leaves.csv"
    report = cli_json("pave", *cli_args, "--json", "--leaves", str(csv_path))
    name, params = load
    params = dict(params)
    scene = detach.Scene.load(name, **params)
    paving = scene.pave(**kw)

    assert paving.stop == report["stop"]
    assert paving.complete == report["complete"]
    assert len(paving) == report["leaves"]
    for r in report["regions"]:
        a = paving.areas[r["name"]]
        assert (a.inner, a.outer) == (r["inner_area"], r["outer_area"]), r["name"]
        assert a.label == r["label"]
        assert a.empty == r.get("empty")

    header, rows = read_leaves_csv(csv_path)
    assert header[-2:] == ["omega", "omega0"]
    leaves = paving.leaves
    assert len(rows) == len(leaves)
    for row, leaf in zip(rows, leaves):
        hexes = [float(leaf[f]).hex() for f in ("theta_lo", "theta_hi", "theta_dot_lo", "theta_dot_hi")]
        assert [float.fromhex(h) for h in row[4:8]] == [float.fromhex(h) for h in hexes]
        assert [leaf["omega"], leaf["omega0"]] == row[8:10]


def test_edges_are_the_exact_doubles(tmp_path):
    """The float edges are the CLI's decimal columns exactly (shortest
    round-trip text of the same doubles)."""
    csv_path = tmp_path / "leaves.csv"
    run_cli("pave", "--scene", "painleve-rod", "--eps", "0.015625", "--leaves", str(csv_path))
    _, rows = read_leaves_csv(csv_path)
    leaves = detach.Scene.load("painleve-rod").pave(eps=1 / 64).leaves
    for row, leaf in zip(rows, leaves):
        assert [repr(float(leaf[f])) for f in ("theta_lo", "theta_hi", "theta_dot_lo", "theta_dot_hi")] == row[:4]


def test_scene_file_equals_cli():
    path = REPO / "scenes" / "painleve-rod.toml"
    report = cli_json("pave", "--scene-file", str(path), "--param", "mu=2", "--eps", "0.0078125", "--json")
    paving = detach.Scene.from_file(path, mu="2").pave(eps=1 / 128)
    got = {n: (a.inner, a.outer) for n, a in paving.areas.items()}
    assert got == {r["name"]: (r["inner_area"], r["outer_area"]) for r in report["regions"]}


@pytest.mark.parametrize("name, params", [("viscous-disc", {}), ("painleve-rod", {"mu": "2"})])
def test_area_equals_cli(name, params):
    args = ["area", "--scene", name, "--digits", "6", "--json"]
    for k, v in params.items():
        args += ["--param", f"{k}={v}"]
    report = cli_json(*args)
    areas = detach.Scene.load(name, **params).area(digits=6)
    for r in report["regions"]:
        a = areas[r["name"]]
        assert (a.lower, a.upper) == (r["lower"], r["upper"]), r["name"]
        assert a.how.split(" ")[0] in (r["method"], "empty:")
        assert a.lower <= a.upper


def test_defaults_and_class_names_are_the_clis():
    # The CLI's defaults, as its --json reports them, are the Python calls'.
    cli = cli_json("pave", "--scene", "ice-disc", "--json")
    paving = detach.Scene.load("ice-disc").pave()
    assert (paving.eps, cli["method"], cli["max_boxes"]) == (cli["eps"], "slices", 4_000_000)
    import inspect

    pave = inspect.signature(detach.Scene.pave).parameters
    assert (pave["method"].default, pave["max_boxes"].default) == (cli["method"], cli["max_boxes"])
    # Every option after the scene's own arguments is keyword-only.
    assert all(p.kind == p.KEYWORD_ONLY for n, p in pave.items() if n != "self")
    # The class names: the four cells as the CLI's report names them (after
    # omega and omega0), then the two undecided classes.
    cells = [r["name"] for r in cli["regions"]]
    assert cells[:2] == ["omega", "omega0"]
    assert detach.CLASSES == (*cells[2:], "undecided", "undefined")
