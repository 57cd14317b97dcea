"""Parameter values as decimal text: what detach encloses exactly."""

from __future__ import annotations

import decimal
import fractions
import math
import numbers

from ._detach import DetachError


#: Decimals written out as text must lie within the range of doubles
#: (about 1e±308, subnormals to 1e-324) and have at most so many digits.
MAX_EXPONENT = 400
MAX_DIGITS = 10_000


def decimal_text(name, value):
    """`value` as the decimal text detach encloses.

    Text is passed on as written; integers, `decimal.Decimal` and rationals
    (`fractions.Fraction`, `sympy.Rational`) whose decimal expansion ends
    are exact. A float is refused: `0.1` is the double 0.1000000000000000055511151231257827...,
    not the decimal typed, and a certified result must say which number it is
    about. Give text (`"0.1"`), or `Decimal(x)` for the double's exact value.
    """
    if isinstance(value, str):
        return value
    if isinstance(value, bool):
        raise DetachError(f"{name}: {value!r} is not a number")
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, decimal.Decimal):
        return _decimal(name, value)
    rational = _rational(value)
    if rational is not None:
        return _decimal(name, _exact_decimal(name, rational))
    if isinstance(value, float):
        x = float(value)  # np.float64(1.5) is written 1.5
        if not math.isfinite(x):
            raise DetachError(f"{name}: {x!r} is not a finite number")
        raise DetachError(
            f"{name}: the float {x!r} is refused (it is the double "
            f"{decimal.Decimal(x)}, not the decimal typed); give decimal text such as "
            f"'{x!r}', or decimal.Decimal({x!r}) for the double's exact value"
        )
    raise DetachError(
        f"{name}: give decimal text such as '1.5' (or an int, decimal.Decimal or "
        f"fractions.Fraction), got {type(value).__name__}"
    )


def _decimal(name, value):
    if not value.is_finite():
        raise DetachError(f"{name}: {value} is not a finite number")
    # Written out before it is sent: bound the text it expands to.
    if value and not -MAX_EXPONENT <= value.adjusted() <= MAX_EXPONENT:
        raise DetachError(
            f"{name}: {value} is beyond the range of doubles (|exponent| > {MAX_EXPONENT})"
        )
    if len(value.as_tuple().digits) > MAX_DIGITS:
        raise DetachError(f"{name}: {value} has more than {MAX_DIGITS} digits")
    return format(value, "f")


def _rational(value):
    """`value` as a `Fraction` if it is an exact rational (a `Fraction`, a
    sympy `Rational`), else None."""
    if isinstance(value, numbers.Rational):
        return fractions.Fraction(int(value.numerator), int(value.denominator))
    if getattr(value, "is_Rational", False) is True:  # sympy, without importing it
        return fractions.Fraction(int(value.p), int(value.q))
    return None


def _exact_decimal(name, q):
    """The `Decimal` equal to `q`, when its expansion ends (the denominator
    has no prime factor but 2 and 5)."""
    d, twos, fives = q.denominator, 0, 0
    while d % 2 == 0:
        d, twos = d // 2, twos + 1
    while d % 5 == 0:
        d, fives = d // 5, fives + 1
    if d != 1:
        raise DetachError(
            f"{name}: {q} has no finite decimal expansion, so no decimal text names it; "
            f"give the decimal you mean (such as '{float(q)!r}')"
        )
    places = max(twos, fives)
    if places > MAX_DIGITS:
        raise DetachError(f"{name}: {q} has more than {MAX_DIGITS} digits")
    scaled = int(q * 10**places)  # exact: an integer
    digits = tuple(int(c) for c in str(abs(scaled)))
    # Built from its digits: arithmetic would round to the context's precision.
    return decimal.Decimal((int(scaled < 0), digits, -places))
