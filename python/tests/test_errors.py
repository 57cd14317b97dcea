"""Bad input raises detach's own exceptions (ValueError subclasses, OSError
for files) with the CLI's sentence, never a crash."""

import decimal
import fractions
import json
import re

import pytest

import detach
from conftest import REPO, run_cli


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
    # The same sentence, with the argument spelt as Python spells it
    # (`--max-boxes` is `max_boxes`).
    message = re.sub(r"--([a-z-]+)", lambda m: m.group(1).replace("-", "_"), cli_error(*cli_args))
    with pytest.raises(detach.DetachError) as e:
        call()
    assert "--" not in str(e.value), str(e.value)
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


def test_the_exception_classes_are_value_errors():
    assert issubclass(detach.DetachError, ValueError)
    assert issubclass(detach.SceneFileError, detach.DetachError)
    assert issubclass(detach.ProofRejected, detach.DetachError)
    assert not issubclass(detach.DetachError, OSError)


def test_a_missing_file_is_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError, match="nope.toml"):
        detach.Scene.from_file(tmp_path / "nope.toml")
    with pytest.raises(FileNotFoundError, match="nope.json"):
        detach.verify(tmp_path / "nope.json")


def test_a_proof_written_where_no_folder_is_an_os_error(tmp_path):
    paving = detach.Scene.load("ice-disc").pave(eps=1 / 8)
    with pytest.raises(OSError) as e:
        paving.save_proof(tmp_path / "no-such-folder" / "p.json")
    assert not isinstance(e.value, ValueError)


def test_a_proof_the_checker_rejects_is_proof_rejected(tmp_path):
    from detach import _detach

    # A well-formed file whose claim the checker cannot confirm.
    bogus = {"format": "detach-proof", "version": 1, "kind": "no-such-kind"}
    with pytest.raises(detach.ProofRejected, match="checker"):
        _detach.write_proof(json.dumps(bogus), str(tmp_path / "p.json"))
    assert not (tmp_path / "p.json").exists()
    with pytest.raises(detach.ProofRejected, match="not JSON"):
        _detach.write_proof("{", str(tmp_path / "p.json"))


def test_a_scene_file_that_is_not_one_is_scene_file_error(tmp_path):
    with pytest.raises(detach.SceneFileError):
        detach.Scene.from_toml("this is not toml")
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "x"\n[domain]\ntheta = ["0", "1"]\n')
    with pytest.raises(detach.SceneFileError, match="bad.toml"):
        detach.Scene.from_file(bad)
    # A misspelt table is named as such, not as the table it hides.
    rod = (REPO / "scenes" / "painleve-rod.toml").read_text()
    with pytest.raises(detach.SceneFileError, match=r"`\[region\]`: unknown table"):
        detach.Scene.from_toml(rod.replace("[regions]", "[region]"))
    # A parameter given to a good file is the parameter's fault, not the file's.
    with pytest.raises(detach.DetachError) as e:
        detach.Scene.load("painleve-rod", mu="abc")
    assert not isinstance(e.value, detach.SceneFileError)


def test_rationals_with_a_finite_expansion_are_exact_parameters():
    s = detach.Scene.load("painleve-rod", mu=fractions.Fraction(3, 2), g=fractions.Fraction(981, 100))
    assert s.params["mu"] == "1.5" and s.params["g"] == "9.81"
    with pytest.raises(detach.DetachError, match="no finite decimal expansion"):
        detach.Scene.load("painleve-rod", mu=fractions.Fraction(1, 3))
    sympy = pytest.importorskip("sympy")
    assert detach.Scene.load("painleve-rod", mu=sympy.Rational(-5, 4)).params["mu"] == "-1.25"


def test_refused_floats_suggest_only_valid_text():
    np = pytest.importorskip("numpy")
    with pytest.raises(detach.DetachError) as e:
        detach.Scene.load("painleve-rod", mu=np.float64(1.5))
    assert "np.float64" not in str(e.value) and "'1.5'" in str(e.value)
    with pytest.raises(detach.DetachError, match="not a finite number") as e:
        detach.Scene.load("painleve-rod", mu=float("nan"))
    assert "such as" not in str(e.value)


def test_eps_as_text_is_parsed_or_refused_in_our_words():
    scene = detach.Scene.load("ice-disc")
    assert scene.pave(eps="1/8").eps == 1 / 8
    with pytest.raises(detach.DetachError, match="eps must be"):
        scene.pave(eps="fine")
