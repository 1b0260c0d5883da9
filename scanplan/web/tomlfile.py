"""A project given as tables (JSON) written as a project file (TOML).

The page holds a project as ``{"map": {"scale": 2000, ...}, "uav.target": {...}}`` — the
sections and keys of docs/project-file.md, dotted sections flat. :func:`project_toml`
writes it as the TOML a user would write (sections in the registry's order, sub-tables
under their parent, dates as TOML dates), so the text the server validates is the file
the user downloads and ``scanplan plan`` runs.

>>> print(project_toml({"uav": {"camera": "dji-zenmuse-p1-35"},
...                     "map": {"scale": 2000, "relief_interval_m": 0.5}}), end="")
# scanplan project file (docs/project-file.md)
<BLANKLINE>
[map]
scale = 2000
relief_interval_m = 0.5
<BLANKLINE>
[uav]
camera = "dji-zenmuse-p1-35"
"""

from __future__ import annotations

import datetime as dt
from typing import Any

from ..errors import InputError
from ..project.inputs import INPUTS

__all__ = ["HEADER", "SECTIONS", "project_tables", "project_toml"]

HEADER = "# scanplan project file (docs/project-file.md)\n"

SECTIONS: tuple[str, ...] = tuple(dict.fromkeys(
    inp.section for inp in INPUTS.values() if inp.key))
"""The sections of a project file, in the registry's order."""

_ORDER = {(inp.section, inp.key): i for i, inp in enumerate(INPUTS.values()) if inp.key}
_KIND = {(inp.section, inp.key): inp.kind for inp in INPUTS.values() if inp.key}


def project_tables(project: Any) -> dict[str, dict[str, Any]]:
    """The project's tables checked for shape: a mapping of section → mapping of key →
    value (a JSON null leaves the key out). Keys and values are checked by the project
    file's loader, with its messages, once the tables are written as TOML.

    Raises
    ------
    InputError
        ``project`` when it is not a table of tables.
    """
    if not isinstance(project, dict):
        raise InputError("project", "must be a table of sections, e.g. {\"map\": "
                         "{\"scale\": 2000, \"relief_interval_m\": 1}}")
    out: dict[str, dict[str, Any]] = {}
    for section, table in project.items():
        if not isinstance(section, str) or not isinstance(table, dict):
            raise InputError(f"project.{section}", "must be a table of keys and values")
        kept = {str(k): v for k, v in table.items() if v is not None}
        if kept:
            out[section] = kept
    return out


def _toml_value(section: str, key: str, value: Any) -> Any:
    """A JSON value as its TOML value: a date key's text becomes a TOML date."""
    if _KIND.get((section, key)) == "date" and isinstance(value, str):
        try:
            return dt.date.fromisoformat(value)
        except ValueError:
            return value  # the loader names the key and the format
    return value


def project_toml(project: Any) -> str:
    """The project file of ``project`` (tables as :func:`project_tables` takes them).

    Known sections come in the registry's order, keys in their order within it; an
    unknown section or key is kept (after the known ones), so the loader refuses it with
    its own message instead of it being dropped silently.
    """
    import tomli_w

    tables = project_tables(project)
    rank = {s: i for i, s in enumerate(SECTIONS)}
    doc: dict[str, Any] = {}
    for section in sorted(tables, key=lambda s: (rank.get(s, len(rank)), s)):
        keys = sorted(tables[section], key=lambda k: _ORDER.get((section, k), 10**6))
        node = doc
        for part in section.split("."):
            node = node.setdefault(part, {})
            if not isinstance(node, dict):
                raise InputError(f"project.{section}", "is both a key and a table")
        for key in keys:
            node[key] = _toml_value(section, key, tables[section][key])
    # a parent's own keys first, its sub-tables after (TOML requires it; tomli_w does it)
    try:
        return HEADER + "\n" + tomli_w.dumps(doc)
    except (TypeError, ValueError) as exc:  # a JSON null inside a list, a mixed array
        raise InputError("project", f"holds a value a project file cannot hold ({exc})"
                         ) from None
