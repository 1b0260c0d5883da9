"""The scales and text widths of the report's charts (:mod:`.svgchart`): round ticks on
linear and logarithmic axes, and the widths of labels in the report's font, DejaVu Sans
(bundled as ``Scanplan Sans``, templates/fonts) — exact for the glyphs of a tick label,
a generous bound for any Latin or Cyrillic label (checked against the font by the tests).
"""

from __future__ import annotations

import math

__all__ = ["ADVANCE", "ASCENT_EM", "CAP_EM", "DESCENT_EM", "UNITS_PER_EM",
           "estimate_width_pt", "log_ticks", "nice_ticks", "text_width_pt"]

UNITS_PER_EM = 2048
#: Advance widths [font units, 2048 per em] of the glyphs a tick label can hold, in DejaVu
#: Sans (templates/fonts/DejaVuSans.ttf, table ``hmtx``): every digit has the same width.
ADVANCE: dict[str, int] = {**dict.fromkeys("0123456789", 1303), ".": 651, ",": 651,
                           "-": 739, "\u2212": 1716, "+": 1716, " ": 651, "\u00a0": 651,
                           "e": 1260}
CAP_EM = 1493 / UNITS_PER_EM  # height of a capital or a digit (table glyf: H, 1, 4, 7)
ASCENT_EM, DESCENT_EM = 1901 / UNITS_PER_EM, 483 / UNITS_PER_EM  # table hhea
#: Bounds of the glyph widths of Latin and Cyrillic labels in DejaVu Sans: the widest
#: letters and signs (up to 1.1 em), capitals and the broad signs (up to 0.84 em); every
#: other letter, space or punctuation is at most 0.7 em (checked by the tests)
_WIDE = frozenset("mwMWщшжфюЩЮЖШЫМФ…—@%")
_BROAD = frozenset("ыъмЪ=+<>≤≥×±~−#&^")
_STEPS = (1.0, 2.0, 2.5, 5.0)


def text_width_pt(text: str, size_pt: float) -> float:
    """The exact width [pt] of a tick label (digits, separators, signs) at ``size_pt``;
    a glyph outside :data:`ADVANCE` counts as one em (an upper bound).

    Parameters
    ----------
    text : str
        The label, e.g. ``"10\\u00a0000"`` or ``"0,25"``.
    size_pt : float
        Font size [pt].

    Returns
    -------
    float
        The width [pt].
    """
    return sum(ADVANCE.get(c, UNITS_PER_EM) for c in text) * size_pt / UNITS_PER_EM


def estimate_width_pt(text: str, size_pt: float) -> float:
    """A generous estimate of the width [pt] of a label at ``size_pt``: the exact width
    of digits and separators, and for each other glyph a bound of its class (1.1 em for
    the widest letters and dashes, 0.84 em for capitals and broad signs, 0.7 em for any
    other letter or punctuation; DejaVu Sans lowercase letters are mostly 0.28–0.64 em).

    Parameters
    ----------
    text : str
        The label.
    size_pt : float
        Font size [pt].

    Returns
    -------
    float
        An upper bound of the width [pt] (the tests check it against the font).
    """
    em = sum(ADVANCE[c] / UNITS_PER_EM if c in ADVANCE else 1.1 if c in _WIDE
             else 0.84 if c in _BROAD or c.isupper() else 0.7 for c in text)
    return em * size_pt


def nice_ticks(lo: float, hi: float, max_bins: int = 9, *,
               integer: bool = False) -> list[float]:
    """Round ticks within [lo, hi]: steps of 1, 2, 2.5 or 5 × 10^k, the smallest step
    that needs at most ``max_bins`` intervals (matplotlib's ``MaxNLocator``).

    Parameters
    ----------
    lo, hi : float
        The axis limits (any unit).
    max_bins : int
        The most intervals between ticks, counting those reaching past the limits.
    integer : bool
        Whole steps only (1, 2, 5 × 10^k, at least 1): a count such as strip numbers.

    Returns
    -------
    list of float
        The ticks, ascending; ``[lo]`` for an empty range, ``[]`` for a non-finite one.

    Examples
    --------
    >>> nice_ticks(0, 78)
    [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0]
    >>> nice_ticks(0, 0.0845)[-1]
    0.08
    """
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return []
    if hi < lo:
        lo, hi = hi, lo
    span = hi - lo
    if span <= abs(hi) * 1e-12 or span == 0:
        return [float(lo)]
    max_bins = max(1, max_bins)
    base = 10.0 ** math.floor(math.log10(span / max_bins))
    mantissas = (1.0, 2.0, 5.0) if integer else _STEPS
    steps = [m * base * 10.0 ** j for j in range(3) for m in mantissas]
    if integer:  # whole steps: 1, 2, 5, 10, …
        steps = [1.0] + [s for s in steps if s > 1]
    eps = 1e-9

    def ticks_of(step: float) -> tuple[int, list[float]]:
        first, last = math.floor(lo / step + eps), math.ceil(hi / step - eps)
        ticks = (float(f"{k * step:.12g}") for k in range(first, last + 1))
        return last - first, [v for v in ticks if lo - eps * span <= v <= hi + eps * span]

    pick = next((i for i, step in enumerate(steps) if ticks_of(step)[0] <= max_bins),
                len(steps) - 1)
    # at least two ticks within the range (matplotlib's min_n_ticks): a smaller step
    while pick > 0 and len(ticks_of(steps[pick])[1]) < 2:
        pick -= 1
    return ticks_of(steps[pick])[1]


def log_ticks(lo: float, hi: float) -> list[float]:
    """1-2-5 ticks covering [lo, hi] (for short log axes), a little past both ends.

    Parameters
    ----------
    lo, hi : float
        The data range, both positive.

    Returns
    -------
    list of float
        E.g. ``[0.05, 0.1, 0.2, 0.5, 1.0]`` for 0.06 … 0.9.
    """
    out = []
    for e in range(math.floor(math.log10(lo)) - 1, math.ceil(math.log10(hi)) + 1):
        for m in (1, 2, 5):
            v = m * 10.0 ** e
            if lo / 1.3 <= v <= hi * 1.3:
                out.append(float(f"{v:.12g}"))
    return out
