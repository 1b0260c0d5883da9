"""The input registry as the page's form reads it (``GET /api/inputs``).

One row per key of a project file, from :mod:`scanplan.project.inputs` (the names, units,
defaults, choices, help and digits the project file and the command line use) and the numeric
domain of each record (:func:`~scanplan.project.inputs.domain_of`: the range the server
checks, with the command line's and the project file's messages). The label is the
reports' name of the quantity where the report catalogue has one in the page's language;
the help is the registry's (English).
"""

from __future__ import annotations

from typing import Any

from ..project.inputs import INPUTS, describe, domain_of

__all__ = ["MANAGED", "input_rows"]

MANAGED = {("area", "file"), ("area", "polygon"), ("terrain", "dem"), ("project", "locale"),
           ("map", "basemap")}
"""Keys the page sets itself: the drawn or dropped area, the uploaded DEM, the language, the
uploaded background."""


def _label(name: str, key: str, locale: str) -> str:
    from ..i18n.labels import LABELS

    if name == "name":  # the report's "name" is a person's (signature block)
        return ""
    table = LABELS.get(locale, {})
    return table.get(name) or table.get(key) or ""


def input_rows(locale: str = "en") -> list[dict[str, Any]]:
    """Every key of a project file: ``section``, ``key``, ``name`` (the Python name),
    ``kind``, ``unit``, ``default``, ``choices``, ``required``, ``min``/``max`` (the
    domain, with ``min_open``/``max_open``), ``digits`` (the decimals the page shows a
    value with: the default and a drawn polygon's coordinates; None for a text),
    ``help`` (with the default and note), ``label`` and ``managed`` (set by the page
    itself).

    >>> row = next(r for r in input_rows() if (r["section"], r["key"]) == ("uav", "speed_ms"))
    >>> row["unit"], row["default"], row["min"], row["min_open"], row["digits"]
    ('m/s', 15.0, 0, False, 1)
    """
    rows = []
    for inp in INPUTS.values():
        if not inp.key:
            continue
        dom = domain_of(inp)
        rows.append({
            "section": inp.section, "key": inp.key, "name": inp.name, "kind": inp.kind,
            "unit": inp.unit or (dom.unit if dom else ""), "default": inp.default,
            "choices": list(inp.choices), "required": inp.required,
            "min": dom.lo if dom else None, "max": dom.hi if dom else None,
            "min_open": dom.lo_open if dom else False, "max_open": dom.hi_open if dom else False,
            "digits": inp.digits,
            "help": describe(inp), "label": _label(inp.name, inp.key, locale),
            "managed": (inp.section, inp.key) in MANAGED})
    return rows
