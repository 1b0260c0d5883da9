"""A value beside the limit it is checked against, printed so it never reads as the limit.

A blur of 0.5004 px rounded to two decimals prints "0.50" beside a warning that it exceeds
0.5 px; every document shows it with the decimals that keep it above the limit.
Plain arithmetic; no I/O (core module).
"""

from __future__ import annotations

__all__ = ["shown_above", "shown_decimals"]


def shown_above(value: float, limit: float) -> float:
    """``value`` rounded to the fewest decimals, two to six, that still show it above
    ``limit`` (0.5004 px against 0.5 px reads 0.5004, not 0.50); a value at or below the
    limit to two decimals.

    Parameters
    ----------
    value, limit : float
        The value and the limit it is compared with (same unit, e.g. px).

    Returns
    -------
    float

    Examples
    --------
    >>> shown_above(0.5004, 0.5), shown_above(0.734, 0.5), shown_above(0.42, 0.5)
    (0.5004, 0.73, 0.42)
    """
    if not value > limit:
        return round(value, 2)
    for digits in range(2, 7):
        shown = round(value, digits)
        if shown > limit:
            return shown
    return value


def shown_decimals(value: float, limit: float) -> int:
    """The decimals :func:`shown_above` keeps (at least two): a table prints the value
    with them, so 0.5004 px stands as 0.5004 beside a warning that it exceeds 0.5 px.

    Parameters
    ----------
    value, limit : float
        As for :func:`shown_above`.

    Returns
    -------
    int

    Examples
    --------
    >>> shown_decimals(0.5004, 0.5), shown_decimals(0.9, 0.5)
    (4, 2)
    """
    return max(2, len(repr(shown_above(value, limit)).partition(".")[2]))
