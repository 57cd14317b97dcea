"""Parameter values as decimal text: what detach encloses exactly."""

from __future__ import annotations

import decimal
import numbers


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
