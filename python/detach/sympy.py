"""Scene files from sympy expressions.

`scene_toml` writes a scene file (docs/scene-files.md) whose regions are
sympy relations or expressions: `**` becomes `^`, rationals stay exact
(`3/2` is evaluated in intervals, which encloses it), functions are mapped
to the scene language's (`log` to `ln`, `Abs` to `abs`, `Min`/`Max` to
`min`/`max`), and whatever has no exact counterpart (floats, `asin`, symbols
that are neither a variable nor a parameter, ...) is refused with a
`ValueError` that names it.
"""

from __future__ import annotations

import json

import sympy
from sympy.printing.precedence import PRECEDENCE
from sympy.printing.str import StrPrinter

from ._text import decimal_text

# sympy function class name -> scene-language name (functions of one argument).
_FUNCTIONS = {
    "sin": "sin",
    "cos": "cos",
    "tan": "tan",
    "atan": "atan",
    "exp": "exp",
    "log": "ln",
    "Abs": "abs",
    "sign": "sign",
}
_KNOWN = "sqrt sin cos tan ln abs atan exp sign min max, the constant pi"


class SceneLanguagePrinter(StrPrinter):
    """Prints a sympy expression in the scene language, or refuses it."""

    def __init__(self, names):
        super().__init__()
        self._names = dict(names)

    def _print_Symbol(self, expr):
        name = expr.name
        if name not in self._names:
            known = ", ".join(sorted(self._names)) or "none"
            raise ValueError(
                f"symbol `{name}` is neither theta, theta_dot, a parameter nor a definition "
                f"(known: {known})"
            )
        return self._names[name]

    def _print_Integer(self, expr):
        return str(expr.p)

    def _print_Rational(self, expr):
        return f"{expr.p}/{expr.q}"

    def _print_Float(self, expr):
        raise ValueError(
            f"the float {expr} is not exact; write it as a Rational "
            f"(sympy.Rational('{expr}')) or a parameter"
        )

    def _print_Pi(self, expr):
        return "pi"

    def _print_Exp1(self, expr):
        return "exp(1)"

    def _print_Pow(self, expr, rational=False):
        base, e = expr.args
        if e.is_Rational and e.q == 2:
            # x^(k/2) = sqrt(x)^k, defined where sqrt(x) is.
            root = f"sqrt({self._print(base)})"
            k = abs(e.p)
            text = root if k == 1 else f"{root}^{k}"
            return text if e.p > 0 else f"1/{text}"
        if e.is_Integer and e < 0:
            den = base if e == -1 else sympy.Pow(base, -e, evaluate=False)
            return "1/" + self.parenthesize(den, PRECEDENCE["Mul"], strict=True)
        if e.is_Integer:
            if e == 1:
                return self._print(base)
            if base == sympy.E:
                return f"exp({e.p})"
            b = self.parenthesize(base, PRECEDENCE["Pow"], strict=True)
            if isinstance(base, sympy.Pow) or b.startswith("-"):
                b = f"({self._print(base)})"
            return f"{b}^{e.p}"
        if base == sympy.E:
            return f"exp({self._print(e)})"
        raise ValueError(
            f"power `{expr}`: the scene language has x^n for an integer n, sqrt(x), "
            f"and exp(x); write a non-integer power as exp(a*ln(x))"
        )

    def _print_Function(self, expr):
        name = type(expr).__name__
        if name in _FUNCTIONS and len(expr.args) == 1:
            return f"{_FUNCTIONS[name]}({self._print(expr.args[0])})"
        if isinstance(expr, sympy.core.function.AppliedUndef):
            raise ValueError(
                f"`{expr}` is an undefined function; substitute symbols for theta(t) and "
                f"its derivative first (e.g. expr.subs(sympy.Derivative(theta(t), t), theta_dot))"
            )
        raise ValueError(f"function `{name}` has no counterpart in the scene language ({_KNOWN})")

    def _min_max(self, expr, word):
        args = [self._print(a) for a in expr.args]
        text = args[0]
        for a in args[1:]:
            text = f"{word}({text}, {a})"
        return text

    def _print_Min(self, expr):
        return self._min_max(expr, "min")

    def _print_Max(self, expr):
        return self._min_max(expr, "max")

    def emptyPrinter(self, expr):
        raise ValueError(f"`{expr}` ({type(expr).__name__}) has no counterpart in the scene language")


def _relation(printer, key, rel):
    """`lhs < rhs` text of a region: a strict relation, or `expr` for expr < 0."""
    if isinstance(rel, (sympy.LessThan, sympy.GreaterThan)):
        raise ValueError(
            f"{key}: `{rel}` is not strict; write < or > (every certificate is of the strict set)"
        )
    if isinstance(rel, sympy.StrictLessThan):
        return f"{printer.doprint(rel.lhs)} < {printer.doprint(rel.rhs)}"
    if isinstance(rel, sympy.StrictGreaterThan):
        return f"{printer.doprint(rel.lhs)} > {printer.doprint(rel.rhs)}"
    if isinstance(rel, sympy.logic.boolalg.BooleanAtom):
        raise ValueError(f"{key}: the relation is `{rel}` for every point; give one that depends on theta or theta_dot")
    if isinstance(rel, sympy.Basic) and not isinstance(rel, sympy.core.relational.Relational):
        return f"{printer.doprint(rel)} < 0"
    raise ValueError(f"{key}: give a relation with < or >, or an expression g for g < 0; got `{rel}`")


def _name(sym):
    return sym.name if isinstance(sym, sympy.Symbol) else str(sym)


def _end(printer, value, where):
    if isinstance(value, sympy.Basic):
        return printer.doprint(value)
    return decimal_text(where, value)


def _string(text):
    # A TOML basic string: JSON's escapes are TOML's.
    return json.dumps(text, ensure_ascii=False)


def scene_toml(
    omega,
    omega0=None,
    *,
    theta,
    theta_dot,
    parameters=None,
    domain,
    definitions=None,
    theta_ddot=None,
    name="sympy-scene",
    title=None,
):
    """The text of a scene file with regions `omega` (and `omega0`).

    `omega`, `omega0`: sympy relations (`U < 0`, `U/V < 0`) or expressions
    `g` standing for `g < 0`. `theta`, `theta_dot`: the sympy symbols of the
    variables. `parameters`: `{symbol or name: value}` with decimal text
    values (or `{"value": ..., "description": ..., "unit": ...}`).
    `definitions`: `{symbol or name: expression}`, written as the file's
    `[definitions]` (in order). `domain`: `{"theta": (lo, hi), "theta_dot":
    (lo, hi)}` with decimal text or sympy numbers (`sympy.pi/2`).
    """
    parameters = dict(parameters or {})
    definitions = dict(definitions or {})
    names = {_name(theta): "theta", _name(theta_dot): "theta_dot"}
    for sym in list(parameters) + list(definitions):
        n = _name(sym)
        if n in names:
            raise ValueError(f"`{n}` is given twice (variable, parameter or definition)")
        names[n] = n
    printer = SceneLanguagePrinter(names)
    # Domain ends may use parameters, not the variables.
    no_vars = SceneLanguagePrinter({_name(p): _name(p) for p in parameters})
    lines = [f"name = {_string(name)}"]
    if title:
        lines.append(f"title = {_string(title)}")
    lines += ["", "[domain]"]
    for var in ("theta", "theta_dot"):
        if var not in domain:
            raise ValueError(f"domain: `{var}` missing (give (lo, hi))")
        lo, hi = domain[var]
        ends = [_string(_end(no_vars, x, f"domain {var}")) for x in (lo, hi)]
        lines.append(f"{var} = [{ends[0]}, {ends[1]}]")
    if parameters:
        lines += ["", "[parameters]"]
        for sym, value in parameters.items():
            n = _name(sym)
            if isinstance(value, dict):
                fields = [f"value = {_string(decimal_text(n, value['value']))}"]
                for k in ("description", "unit"):
                    if value.get(k):
                        fields.append(f"{k} = {_string(value[k])}")
                lines.append(f"{n} = {{ {', '.join(fields)} }}")
            else:
                lines.append(f"{n} = {_string(decimal_text(n, value))}")
    if definitions:
        lines += ["", "[definitions]"]
        for sym, expr in definitions.items():
            lines.append(f"{_name(sym)} = {_string(printer.doprint(sympy.sympify(expr)))}")
    lines += ["", "[regions]", f"omega = {_string(_relation(printer, 'omega', omega))}"]
    if omega0 is not None:
        lines.append(f"omega0 = {_string(_relation(printer, 'omega0', omega0))}")
    if theta_ddot is not None:
        lines += ["", "[dynamics]", f"theta_ddot = {_string(printer.doprint(sympy.sympify(theta_ddot)))}"]
    return "\n".join(lines) + "\n"
