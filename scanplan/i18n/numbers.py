"""Every number a document prints, in one locale's convention: :class:`Numbers`.

English ``12.5``, ``4,575``; Russian ``12,5``, ``4 575`` (decimal comma, a no-break space
groups thousands). The renderers of :mod:`scanplan.reports` (terminal, workbook, PDF, plots)
and the catalogue listings of the command line format their numbers here; an engine sentence
formats its own numbers by the same rule (:mod:`scanplan.i18n.messages`). Plain Python; no
I/O (base module).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from .messages import pixel_text, scale_text

__all__ = ["MISSING", "Numbers"]

MISSING = "—"


def _finite(x: Any) -> bool:
    return x is not None and not (isinstance(x, float) and not math.isfinite(x))


@dataclass(frozen=True)
class Numbers:
    """Every number a document prints, in one locale's convention.

    English: ``12.5``, ``4,575``; Russian: ``12,5``, ``4 575`` (a no-break space groups
    thousands). One rule for every document, the terminal and the engine's sentences
    (:mod:`scanplan.i18n.messages`): a number of 1,000 or more is grouped, whichever method
    prints it, so a count or a height reads the same in prose and in tables; only a scale
    (``1:2000``, ``1:25 000``: :func:`~scanplan.i18n.messages.scale_text`) and an
    identifier (a photo's number) keep their own form. A missing or non-finite value prints
    as ``—``.

    Parameters
    ----------
    locale : {"en", "ru"}
        The document's language.

    Examples
    --------
    >>> ru = Numbers("ru")
    >>> ru.num(12345.678, 1), ru.g(0.25), ru.scale(10000), ru.fixed(2.5, 2)
    ('12\\xa0345,7', '0,25', '1:10\\xa0000', '2,50')
    >>> Numbers("en").num(float("nan"))
    '—'
    """

    locale: str = "en"

    def _dec(self, text: str) -> str:
        """``text`` (Python's format) with the locale's decimal separator and grouping."""
        if self.locale == "ru":
            return text.replace(",", "\u00a0").replace(".", ",")
        return text

    def num(self, x: float | None, digits: int = 1) -> str:
        """``x`` with ``digits`` decimals, thousands grouped."""
        if not _finite(x) or not math.isfinite(float(x)):  # type: ignore[arg-type]
            return MISSING
        return self._dec(f"{float(x):,.{digits}f}")  # type: ignore[arg-type]

    def fixed(self, x: float | None, digits: int = 1) -> str:
        """``x`` with ``digits`` decimals (:meth:`num`: thousands grouped, as everywhere)."""
        return self.num(x, digits)

    def whole(self, x: float) -> str:
        """``x`` rounded to a whole number, grouped (``4,575``, ``4 575``)."""
        return self._dec(f"{round(float(x)):,d}")

    def height(self, x: float) -> str:
        """A height [m] as the tables give it: whole metres when it is whole to 5 cm, else one
        decimal (``70``, ``148.5``), so a chart's legend and the tables agree."""
        return self.num(x, 0 if abs(float(x) - round(float(x))) < 0.05 else 1)

    def g(self, x: float | None) -> str:
        """Shortest form (like ``:g``), 1,000 and more grouped."""
        if not _finite(x):
            return MISSING
        text = f"{float(x):g}"  # type: ignore[arg-type]
        if "e" in text:
            return text
        if abs(float(x)) >= 1000:  # type: ignore[arg-type]
            if float(x).is_integer():  # type: ignore[arg-type]
                return self.num(x, 0)
            return self._dec(f"{float(x):,.6g}")  # type: ignore[arg-type]
        return self._dec(text)

    def short(self, x: float) -> str:
        """Shortest form: :meth:`g` (the terminal's inputs, grouped as everywhere)."""
        return self.g(x)

    def sig(self, x: float | None, digits: int = 4) -> str:
        """A measured size to ``digits`` significant digits (a pixel pitch of 4.38232 µm is
        4.382, a derived sensor side of 23.9275 mm is 23.93), 1,000 and more grouped."""
        if not _finite(x):
            return MISSING
        return self._dec(f"{float(x):,.{digits}g}")  # type: ignore[arg-type]

    def tick(self, x: float) -> str:
        """A plot's tick label: whole numbers grouped, others with up to 6 digits."""
        if float(x).is_integer():
            return self.num(x, 0)
        return self._dec(f"{x:,.6g}")

    def um(self, x: float | None) -> str:
        """A pixel [µm]: one decimal, or two significant digits below 1 µm (never ``0.0``)."""
        if not _finite(x) or not math.isfinite(float(x)):  # type: ignore[arg-type]
            return MISSING
        return pixel_text(float(x), self.locale)  # type: ignore[arg-type]

    def scale(self, x: float) -> str:
        """A scale as every document writes it (:func:`scanplan.i18n.messages.scale_text`):
        ``1:10000`` / ``1:10 000``, ``1:2000`` in both (a fractional one in shortest form)."""
        return scale_text(x, self.locale)

    def floor_scale(self, x: float) -> str:
        """The largest whole scale denominator not above ``x``: ``1:12345``."""
        return scale_text(math.floor(x), self.locale)

    def plain_scale(self, x: float) -> str:
        """A scale without grouping: ``1:10000`` (the workbook's cells and charts)."""
        return f"1:{x:.0f}"
