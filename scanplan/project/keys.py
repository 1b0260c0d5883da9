"""The keys of a project file: which there are, where each is written, and the checks of a
value's TOML type.

What a project file (:mod:`scanplan.project.file`) and the user's configuration
(:mod:`scanplan.project.userconfig`, the defaults of ``[project]``) both check a key against:
the key table read from the input registry (:data:`KEYS`), each key's line in the text
(:func:`key_lines`), a value's TOML type (:func:`check_type`) and a user text's bounds
(:func:`text_problem`).
"""

from __future__ import annotations

import datetime as dt
import math
import re
from collections.abc import Iterable
from typing import Any

from ..core.domains import MAX_LIST_ITEMS
from .inputs import key_table

__all__ = ["KEYS", "MAX_TEXT_CHARS", "check_text", "check_type", "closest_key", "key_lines",
           "text_problem"]

MAX_TEXT_CHARS = 1_000
"""Longest text value (a project name, a customer, an id) [characters]."""
_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f]")

KEYS: dict[str, dict[str, tuple[str, str]]] = key_table()
"""Every key a project file may hold, section → key → (type, description with unit and
default): the documented contract, read from the input registry
(:mod:`scanplan.project.inputs`)."""


def key_lines(text: str) -> dict[str, int]:
    """Line of each ``section.key`` and ``[section]`` header (plain TOML, no inline tables)."""
    lines: dict[str, int] = {}
    section = ""
    header = re.compile(r"^\s*\[\s*([A-Za-z0-9_.\- ]+?)\s*\]\s*(#.*)?$")
    assign = re.compile(r"^\s*([A-Za-z0-9_\-]+|\"[^\"]+\")\s*=")
    for no, line in enumerate(text.splitlines(), start=1):
        m = header.match(line)
        if m:
            section = m.group(1).replace(" ", "")
            lines.setdefault(section, no)
            continue
        m = assign.match(line)
        if m:
            key = m.group(1).strip('"')
            lines.setdefault(f"{section}.{key}" if section else key, no)
    return lines


def closest_key(key: str, keys: Iterable[str]) -> str:
    """`` (did you mean height_m?)`` for a mistyped key: the closest of ``keys``; ""
    when none is close."""
    import difflib

    close = difflib.get_close_matches(key, list(keys), n=1, cutoff=0.75)
    return f" (did you mean {close[0]}?)" if close else ""


def check_type(kind: str, value: Any) -> str | None:
    """What is wrong with ``value`` as a TOML value of type ``kind`` (the key table's
    ``"str"``, ``"number"``, ``"scale"`` …), or None."""
    if kind == "str":
        return None if isinstance(value, str) else "must be text (in quotes)"
    if kind == "bool":
        return None if isinstance(value, bool) else "must be true or false"
    if kind == "int":
        ok = isinstance(value, int) and not isinstance(value, bool)
        return None if ok else "must be a whole number"
    if kind == "number":
        ok = isinstance(value, int | float) and not isinstance(value, bool)
        if ok and not _finite(value):
            return "must be a finite number (at most about 1.8e308)"
        return None if ok else "must be a number"
    if kind == "scale":
        ok = (isinstance(value, int | float | str)) and not isinstance(value, bool)
        if ok and not isinstance(value, str) and not _finite(value):
            return "must be a finite scale denominator like 2000"
        return None if ok else 'must be a scale denominator like 2000 or "1:2000"'
    if kind == "feature":
        ok = isinstance(value, str | int) and not isinstance(value, bool)
        return None if ok else 'must be a name in quotes or a number from 1'
    if kind == "crs":
        ok = isinstance(value, str | int) and not isinstance(value, bool)
        return None if ok else 'must be a CRS like "EPSG:32637" or 32637'
    if kind == "direction":
        if value == "auto":
            return None
        ok = isinstance(value, int | float) and not isinstance(value, bool) and _finite(value)
        return None if ok else 'must be an angle in degrees or "auto"'
    if kind == "checkpoints":
        if value == "asprs":
            return None
        ok = isinstance(value, int) and not isinstance(value, bool)
        return None if ok else 'must be "asprs" or a whole number of checkpoints'
    if kind == "polygon":
        if not isinstance(value, list) or len(value) < 3:
            return "must be a list of at least 3 [lon, lat] points"
        return None
    if kind == "scales":
        if not isinstance(value, list) or not value:
            return "must be a non-empty list of scales, e.g. [5000, 10000]"
        if len(value) > MAX_LIST_ITEMS:
            return f"has {len(value):,} scales; at most {MAX_LIST_ITEMS}"
        bad = [v for v in value if isinstance(v, bool) or not isinstance(v, int | float | str)
               or (not isinstance(v, str) and not _finite(v))]
        return 'must be a list of finite scales like [5000, "1:10000"]' if bad else None
    if kind == "point":
        ok = (isinstance(value, list) and len(value) == 2
              and all(isinstance(v, int | float) and not isinstance(v, bool) and _finite(v)
                      for v in value))
        if ok and not (-180 <= value[0] <= 180 and -90 <= value[1] <= 90):
            return "must be [lon, lat] with lon in −180 … 180° and lat in −90 … 90°"
        return None if ok else "must be a point [lon, lat] in degrees (WGS 84)"
    if kind == "range":
        ok = (isinstance(value, list) and len(value) == 2
              and all(isinstance(v, int | float) and not isinstance(v, bool) and _finite(v)
                      for v in value))
        if ok and value[0] > value[1]:
            return "must be [lowest, highest]: the first value may not exceed the second"
        return None if ok else "must be two finite numbers [lowest, highest], e.g. [120, 185]"
    if kind == "date":
        if isinstance(value, dt.date) and not isinstance(value, dt.datetime):
            return None
        if isinstance(value, str):
            try:
                dt.date.fromisoformat(value)
                return None
            except ValueError:
                pass
        return "must be a date YYYY-MM-DD, e.g. 2025-06-01"
    raise AssertionError(kind)


def _finite(value: float) -> bool:
    """Whether a TOML number is finite as a float (an integer of 400 digits is not)."""
    try:
        return math.isfinite(float(value))
    except OverflowError:
        return False


def check_text(kind: str, value: Any) -> str | None:
    """What is wrong with a text value (:func:`text_problem`), or None (other types)."""
    return text_problem(value) if kind == "str" else None


def text_problem(value: str) -> str | None:
    """What is wrong with a user text shown on terminals and in reports, or None.

    Bounded (:data:`MAX_TEXT_CHARS`) and free of control characters (terminal escapes).
    HTML, URLs and formulas are fine: the reports show them as text.

    Parameters
    ----------
    value : str
        The text (a project name, customer, approver ...).
    """
    if len(value) > MAX_TEXT_CHARS:
        return f"is {len(value):,} characters long; at most {MAX_TEXT_CHARS:,}"
    bad = _CONTROL.search(value)
    if bad:
        return f"contains the control character U+{ord(bad.group()):04X}"
    return None
