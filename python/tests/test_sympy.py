"""Scenes from sympy: the printer, and the rod derived in sympy against the
hand-written scenes/painleve-rod.toml."""

import json

import pytest
import sympy
from sympy import Rational, cos, pi, sin, symbols

import detach
from conftest import REPO
from detach.sympy import scene_toml

th, w = symbols("theta theta_dot", real=True)
m, l, g, mu = symbols("m l g mu", positive=True)
U, V, N = symbols("U V N")


def rod_u_v():
    """Newton-Euler for the rod with its end sliding away (T = +mu N), as in
    the comments of scenes/painleve-rod.toml: U = Lambda'' at N = 0, V = m
    dLambda''/dN."""
    T = mu * N
    y_g_dd = N / m - g                                   # m y_G'' = N - m g
    th_dd = (-l * N * cos(th) + l * T * sin(th)) / (m * l**2 / 3)
    lam_dd = y_g_dd - l * cos(th) * th_dd + l * sin(th) * w**2
    return sympy.expand(lam_dd.subs(N, 0)), sympy.expand(m * sympy.diff(lam_dd, N))


def rod_scene(mu_value="1.5"):
    u, v = rod_u_v()
    return detach.Scene.from_sympy(
        U < 0,
        U / V < 0,
        theta=th,
        theta_dot=w,
        parameters={m: "1", l: "1", g: "9.81", mu: mu_value},
        definitions={U: u, V: v},
        domain={"theta": (0, pi / 2), "theta_dot": (-10, 10)},
        name="painleve-rod",
    )


def test_derivation_gives_the_files_u_and_v():
    u, v = rod_u_v()
    assert sympy.simplify(u - (l * sin(th) * w**2 - g)) == 0
    assert sympy.simplify(v - (1 + 3 * cos(th) ** 2 - 3 * mu * sin(th) * cos(th))) == 0


@pytest.mark.parametrize("mu_value", ["1.5", "1.3", "2"])
def test_sympy_rod_paves_as_the_hand_written_file(mu_value):
    """Bisection (`natural`) at the same points gives the same leaves and
    areas, bit for bit: the derived text evaluates as the file's."""
    mine = rod_scene(mu_value).pave(eps=1 / 256, method="natural")
    theirs = detach.Scene.from_file(REPO / "scenes" / "painleve-rod.toml", mu=mu_value).pave(
        eps=1 / 256, method="natural"
    )
    assert (mine.leaves == theirs.leaves).all()
    assert mine.areas == theirs.areas


@pytest.mark.parametrize("mu_value", ["1.5", "1.3", "2"])
def test_sympy_rod_areas_contain_the_mpmath_reference(mu_value):
    """With `slices` the split points come from the expressions' f64
    values, so sympy's term order moves them by a few ulps; both pavings'
    areas still contain the independent reference (tests/data/
    painleve-reference.json, mpmath)."""
    ref = json.loads((REPO / "tests" / "data" / "painleve-reference.json").read_text())
    case = next(c for c in ref["cases"] if c["parameters"]["mu"] == mu_value)
    file_scene = detach.Scene.from_file(REPO / "scenes" / "painleve-rod.toml", mu=mu_value)
    for scene in (rod_scene(mu_value), file_scene):
        areas = scene.pave(eps=1 / 256).areas
        for name, text in case["areas"].items():
            a = areas[name]
            assert a.inner <= float(text) <= a.outer, (name, a, text)


def test_toml_is_the_scene_language():
    text = rod_scene().toml
    assert "**" not in text and "^2" in text
    assert 'omega = "U < 0"' in text and 'omega0 = "U/V < 0"' in text
    assert 'theta = ["0", "pi/2"]' in text
    assert 'mu = "1.5"' in text


def p(expr, **names):
    return scene_toml(
        expr, theta=th, theta_dot=w, parameters={mu: "1"}, domain={"theta": (0, 1), "theta_dot": (-1, 1)}
    ).split("omega = ")[1].split("\n")[0].strip('"')


def test_printer_forms():
    assert p(w**2 - 1) == "theta_dot^2 - 1 < 0"
    assert p(Rational(3, 2) * w - mu < 0) in ("3*theta_dot/2 - mu < 0", "-mu + 3*theta_dot/2 < 0")
    assert p(sympy.sqrt(w**2 + 1) > 2) == "sqrt(theta_dot^2 + 1) > 2"
    assert p(1 / (1 + w**2) < mu) == "1/(theta_dot^2 + 1) < mu"
    assert p(sympy.log(mu) * sympy.Abs(th) - 1) in ("ln(mu)*abs(theta) - 1 < 0", "abs(theta)*ln(mu) - 1 < 0")
    assert p(sympy.Max(th, w) - 1) == "max(theta, theta_dot) - 1 < 0"
    assert p(-(sin(th) ** 3)) == "-sin(theta)^3 < 0"
    assert p(sympy.exp(th) - 2) == "exp(theta) - 2 < 0"


@pytest.mark.parametrize(
    "expr, message",
    [
        (w - 0.5, "float"),
        (sympy.asin(th) - w, "asin"),
        (w**2 <= 1, "not strict"),
        (symbols("x") * w, "symbol `x`"),
        (w ** Rational(1, 3), "power"),
        (sympy.Function("f")(th), "undefined function"),
    ],
)
def test_printer_refusals(expr, message):
    with pytest.raises(ValueError, match=message):
        p(expr)


def test_sympy_scene_errors_are_the_scene_files():
    """What the printer lets through is checked by the scene compiler."""
    with pytest.raises(ValueError, match="domain"):
        detach.Scene.from_sympy(
            w - 1, theta=th, theta_dot=w, domain={"theta": (1, 0), "theta_dot": (-1, 1)}
        )


def test_printed_text_means_what_sympy_means():
    """Read back with the scene language's precedence (`^` above unary
    minus, `/` left-associative: Python's `**` and `/` agree), the text has
    sympy's value at sample points: no operator slip."""
    import math

    x = w
    exprs = [
        1 / (1 + x**2),
        -(x**2) + 3 / (x + 2),
        (x + 1) ** -2 - x / (2 * mu),
        mu / (x * (x + 3)) + sympy.sqrt(x**2 + mu) ** 3,
        (1 - x) ** 3 * sympy.exp(-x) / (1 + mu * x**2) ** 2,
        sympy.Abs(x - 1) ** 2 - Rational(7, 3) * sin(x) ** -1,
        x ** -3 - 1 / sympy.sqrt(x + 3),
    ]
    env = {"sqrt": math.sqrt, "sin": math.sin, "cos": math.cos, "exp": math.exp,
           "abs": abs, "ln": math.log, "pi": math.pi}
    for e in exprs:
        text = p(e).removesuffix(" < 0")
        for t in (0.3, 1.7, 2.9):
            got = eval(text.replace("^", "**"), {**env, "theta_dot": t, "theta": 0.2, "mu": 1.0})
            want = float(e.subs({x: t, mu: 1}))
            assert math.isclose(got, want, rel_tol=1e-12), (text, t, got, want)
