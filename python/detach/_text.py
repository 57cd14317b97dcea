"""Parameter values as decimal text: what detach encloses exactly."""

from __future__ import annotations

import decimal
import numbers


#: Decimals written out as text must lie within the range of doubles
#: (about 1e±308, subnormals to 1e-324) and have at most so many digits.
MAX_EXPONENT = 400
MAX_DIGITS = 10_000


def decimal_text(name, value):
    """`value` as the decimal text detach encloses.

    Text is passed on as written; integers and `decimal.Decimal` are exact.
    A float is refused: `0.1` is the double 0.1000000000000000055511151231257827...,
    not the decimal typed, and a certified result must say which number it is
    about. Give text (`"0.1"`), or `Decimal(x)` for the double's exact value.
    """
    if isinstance(value, str):
        return value
    if isinstance(value, bool):
        raise ValueError(f"{name}: {value!r} is not a number")
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, decimal.Decimal):
        if not value.is_finite():
            raise ValueError(f"{name}: {value} is not a finite number")
        # Written out before it is sent: bound the text it expands to.
        if value and not -MAX_EXPONENT <= value.adjusted() <= MAX_EXPONENT:
            raise ValueError(
                f"{name}: {value} is beyond the range of doubles (|exponent| > {MAX_EXPONENT})"
            )
        if len(value.as_tuple().digits) > MAX_DIGITS:
            raise ValueError(f"{name}: {value} has more than {MAX_DIGITS} digits")
        return format(value, "f")
    if isinstance(value, float):
        raise ValueError(
            f"{name}: the float {value!r} is refused (it is the double "
            f"{decimal.Decimal(value)}, not the decimal typed); give decimal text such as "
            f"'{value!r}', or decimal.Decimal({value!r}) for the double's exact value"
        )
    raise ValueError(
        f"{name}: give decimal text such as '1.5' (or an int or decimal.Decimal), "
        f"got {type(value).__name__} {value!r}"
    )
