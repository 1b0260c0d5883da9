"""Old names of the source papers in norm files, read and rewritten, never shown.

Norm tables written before the bundled sets cited the papers by author and year (a
template filled in then, a user set imported then) name them by internal numbers.
``norms/references.toml`` keeps those names as each work's ``old_aliases``; every cell
read from a norm file passes :func:`modern_citation`, which writes the work's first alias
(its authors and year) instead, so no listing, export, template or report shows them.
"""

from __future__ import annotations

import re
import tomllib
from functools import cache

from .paths import bundled_norms_dir

__all__ = ["modern_citation", "old_names"]

# A locator right after a work's name reads "Miheeva & Ilushenko 2015, Table 3": the old
# names were written without the comma ("... Table 3").
_LOCATOR = re.compile(r"\s+(?=(?:Tables?|eqs?\.|after|conclusions?|discussion|ref\.|"
                      r"Appendix|pp?\.|§|табл\.|ф\.|после|вывод)(?![\w]))")


@cache
def old_names() -> dict[str, str]:
    """Old name (case-folded) → the name that replaces it (the work's first alias)."""
    data = tomllib.loads((bundled_norms_dir() / "references.toml").read_text("utf-8"))
    return {old.casefold(): ref["aliases"][0]
            for ref in data["reference"] for old in ref.get("old_aliases", ())}


@cache
def _pattern() -> re.Pattern[str] | None:
    names = sorted(old_names(), key=len, reverse=True)
    if not names:
        return None
    return re.compile(r"\b(?:" + "|".join(re.escape(n) for n in names) + r")\b", re.IGNORECASE)


def modern_citation(text: str) -> str:
    """``text`` with every old name of a source paper replaced by its authors and year.

    ``"seed 001 Table 3"`` (an old norm file) becomes ``"Miheeva & Ilushenko 2015, Table
    3"``; a text without an old name is returned unchanged (the same object).

    Parameters
    ----------
    text : str
        A cell of a norm file.

    Returns
    -------
    str
    """
    pattern = _pattern()
    if not text or pattern is None:
        return text

    def repl(m: re.Match[str]) -> str:
        comma = "," if _LOCATOR.match(m.string, m.end()) else ""
        return old_names()[m.group().casefold()] + comma

    return pattern.sub(repl, text)
