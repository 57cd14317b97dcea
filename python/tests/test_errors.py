"""Bad input raises ValueError with the CLI's message, never a crash."""

import decimal

import pytest

import detach
from conftest import run_cli


def cli_error(*args):
    code, _, err = run_cli(*args, check=False)
    assert code == 2, err
    return err.strip().removeprefix("detach: ").removeprefix("error: ")


@pytest.mark.parametrize(
    "cli_args, call",
    [
        (["pave", "--scene", "no-such-scene"], lambda: detach.Scene.load("no-such-scene")),
        (["pave", "--scene", "painleve-rod", "--param", "mu=abc"], lambda: detach.Scene.load("painleve-rod", mu="abc")),
        (["pave", "--scene", "painleve-rod", "--param", "nu=1"], lambda: detach.Scene.load("painleve-rod", nu="1")),
        (["pave", "--scene", "ice-disc", "--eps", "0"], lambda: detach.Scene.load("ice-disc").pave(eps=0)),
        (["pave", "--scene", "ice-disc", "--eps", "2"], lambda: detach.Scene.load("ice-disc").pave(eps=2)),
        (["pave", "--scene", "ice-disc", "--max-boxes", "0"], lambda: detach.Scene.load("ice-disc").pave(max_boxes=0)),
        (
            ["pave", "--scene", "ice-disc", "--region", "omega1"],
            lambda: detach.Scene.load("ice-disc").pave(region="omega1"),
        ),
        (
            ["pave", "--scene", "ice-disc", "--theta", "2:1"],
            lambda: detach.Scene.load("ice-disc").pave(theta=("2", "1")),
        ),
        (
            ["pave", "--scene", "painleve-rod", "--variant", "printed"],
            lambda: detach.Scene.load("painleve-rod", variant="printed"),
        ),
        (["area", "--scene", "ice-disc", "--digits", "16"], lambda: detach.Scene.load("ice-disc").area(digits=16)),
    ],
)
def test_value_error_has_the_cli_message(cli_args, call):
    message = cli_error(*cli_args)
    with pytest.raises(ValueError) as e:
        call()
    assert str(e.value) in message, (str(e.value), message)
    assert len(str(e.value)) > 10


def test_scene_file_errors_name_the_key(tmp_path):
    bad = tmp_path / "bad.toml"
    text = '''name = "bad"
[domain]
theta = ["0", "1"]
theta_dot = ["-1", "1"]
[regions]
omega = "theta_dot^2 <= 1"
'''
    bad.write_text(text)
    message = cli_error("pave", "--scene-file", str(bad))
    with pytest.raises(ValueError) as e:
        detach.Scene.from_file(bad)
    assert str(e.value) == message
    with pytest.raises(ValueError, match="regions.omega"):
        detach.Scene.from_toml(text)


def test_a_float_parameter_is_refused_with_its_exact_value():
    with pytest.raises(ValueError, match=r"0\.1000000000000000055511151231257827"):
        detach.Scene.load("painleve-rod", mu=0.1)
    # Decimal gives the exact value on purpose; int is exact.
    s = detach.Scene.load("painleve-rod", mu=decimal.Decimal(1.5), g=10)
    assert s.params["mu"] == "1.5" and s.params["g"] == "10"
    with pytest.raises(ValueError, match="theta"):
        detach.Scene.load("ice-disc").pave(theta=(0.5, 1))
    # A Decimal's exponent is bounded before it is written out as digits
    # (1e999999999 would be a billion characters).
    for huge in ("1e999999999", "-1e-999999999", "1e401"):
        with pytest.raises(ValueError, match="beyond the range of doubles"):
            detach.Scene.load("painleve-rod", mu=decimal.Decimal(huge))
    with pytest.raises(ValueError, match="more than 10000 digits"):
        detach.Scene.load("painleve-rod", mu=decimal.Decimal("1." + "1" * 10001))
    # Inside the bound the text reaches detach, which says it is too large.
    with pytest.raises(ValueError, match="mu"):
        detach.Scene.load("painleve-rod", mu=decimal.Decimal("1e399"))


def test_unknown_method_is_refused():
    with pytest.raises(ValueError, match="unknown method|slices"):
        detach.Scene.load("ice-disc").pave(method="fast")


def test_missing_file_is_a_value_error(tmp_path):
    with pytest.raises((ValueError, OSError)):
        detach.Scene.from_file(tmp_path / "nope.toml")
