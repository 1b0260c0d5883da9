"""Project files (TOML): one file describes one mapping contract.

:func:`load_project` reads and validates a file: unknown keys, wrong types and
out-of-range values are :class:`~scanplan.errors.InputError` naming the key and its line
(``film.forward_overlap_pct (line 21)``) — never silently ignored. The layout is in
shared/spec/interface.md and docs/project-file.md.
"""

from __future__ import annotations

import os
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..io.files import read_limited
from .bounds import nesting_problem
from .keys import KEYS, check_text, check_type, closest_key, key_lines, text_problem
from .userconfig import with_user_defaults

__all__ = ["KEYS", "Project", "ReportMeta", "load_project", "parse_project", "parse_project_bytes",
           "text_problem"]

MAX_PROJECT_BYTES = 1_000_000
"""Largest project file [bytes]."""


@dataclass(frozen=True)
class ReportMeta:
    """Who the report is for and who approves it (title and approval blocks).

    All text comes from users and is rendered as text (escaped in the PDF, stored as a
    string in Excel — never a formula).
    """

    project: str = ""
    customer: str = ""
    contractor: str = ""
    locale: str = "en"  # "en" | "ru"
    approver_position: str = ""
    approver_name: str = ""
    date: str = ""  # ISO date; default: report_datetime()
    organisation: str = ""  # the contractor's organisation (title block)
    contract_number: str = ""
    compiled_by: str = ""  # «Составил»: name
    checked_by: str = ""  # «Проверил»: name
    agreed_position: str = ""  # «СОГЛАСОВАНО» block (the customer's side)
    agreed_name: str = ""
    agreed_organisation: str = ""


@dataclass(frozen=True)
class Project:
    """A loaded project file: its keys, their types checked, with the line of each.

    The planner reads it once, through :func:`scanplan.project.model.build_model` (typed
    sections, every value in its registry domain); nothing else reads ``values``.
    """

    path: Path
    name: str
    values: dict[str, dict[str, Any]]
    lines: dict[str, int] = field(default_factory=dict)

    def get(self, section: str, key: str, default: Any = None) -> Any:
        """``values[section][key]`` or ``default``."""
        return self.values.get(section, {}).get(key, default)

    def has(self, section: str) -> bool:
        """Whether the file has this section."""
        return section in self.values

    def where(self, section: str, key: str) -> str:
        """``section.key (line N)`` — how errors name a key."""
        dotted = f"{section}.{key}"
        line = self.lines.get(dotted) or self.lines.get(section)
        return f"{dotted} (line {line})" if line else dotted


def _flatten(doc: dict[str, Any]) -> dict[str, dict[str, Any]]:
    """{"uav": {"camera": .., "target": {..}}} → {"uav": {...}, "uav.target": {...}}."""
    out: dict[str, dict[str, Any]] = {}

    def walk(prefix: str, table: dict[str, Any]) -> None:
        own = {}
        for k, v in table.items():
            name = f"{prefix}.{k}" if prefix else k
            if isinstance(v, dict) and (name in KEYS or not prefix):
                walk(name, v)
            else:
                own[k] = v
        if prefix:
            out[prefix] = own

    walk("", doc)
    return out


def _shown(value: Any) -> str:
    """``repr(value)``, cut to 200 characters."""
    try:
        text = repr(value)
    except ValueError:  # an integer over Python's 4,300-digit conversion limit
        return "a number of more than 4,300 digits"
    return text if len(text) <= 200 else text[:200] + f"… ({len(text):,} characters)"


def _norm_set_path(value: str, folder: Path) -> str:
    """``[norms] set``: a name stays a name; a relative folder is taken from the project
    file's folder (not from wherever scanplan runs)."""
    from ..norms import is_set_name

    if is_set_name(value) or value.startswith("~") or os.path.isabs(value):
        return value
    return os.path.join(folder, value)


def _where_line(p: Path, lines: dict[str, int], line: int) -> str:
    """``FILE: section.key (line N)`` for the key whose value runs through ``line``."""
    key = max((k for k, n in lines.items() if n <= line and "." in k),
              key=lambda k: lines[k], default="")
    return f"{p}: " + (f"{key} (line {lines[key]})" if key else f"line {line}")


def parse_project(text: str, path: str | os.PathLike[str] = "project.toml") -> Project:
    """Validate the text of a project file (see :func:`load_project`)."""
    p = Path(path)
    lines = key_lines(text)
    deep = nesting_problem(text)
    if deep:
        raise InputError(_where_line(p, lines, deep[0]), deep[1])
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(str(p), f"is not valid TOML: {exc}") from None
    except ValueError:  # an integer over Python's 4,300-digit conversion limit
        long = re.search(r"\d{4000,}", text)
        line = text.count("\n", 0, long.start()) + 1 if long else 0
        raise InputError(_where_line(p, lines, line) if line else str(p),
                         "holds a number of more than 4,300 digits; must be a finite number "
                         "(at most about 1.8e308)") from None
    except RecursionError:  # the nesting check above should make this unreachable
        raise InputError(str(p), "nests arrays or inline tables too deeply") from None
    flat = with_user_defaults(_flatten(doc))  # the user's [project] defaults, if any
    for section, table in flat.items():
        if section not in KEYS:
            line = lines.get(section)
            where = f"[{section}]" + (f" (line {line})" if line else "")
            raise InputError(f"{p}: {where}", f"unknown section; known: "
                             f"{', '.join('[' + k + ']' for k in KEYS)}")
        for key, value in table.items():
            dotted = f"{section}.{key}"
            where = f"{p}: {dotted}" + (f" (line {lines[dotted]})" if dotted in lines else "")
            if key not in KEYS[section]:
                raise InputError(where, f"unknown key{_did_you_mean(section, key)}; "
                                 f"[{section}] takes {', '.join(KEYS[section])}")
            kind, desc = KEYS[section][key]
            problem = check_type(kind, value) or check_text(kind, value)
            if problem:
                raise InputError(where, f"{problem} — {desc} (got {_shown(value)})")
    if "map" not in flat or "scale" not in flat["map"]:
        raise InputError(f"{p}: map.scale", "is required: the map scale, e.g. scale = 2000")
    if "relief_interval_m" not in flat["map"]:
        raise InputError(f"{p}: map.relief_interval_m", "is required: the relief interval in m")
    if "film" not in flat and "uav" not in flat:
        raise InputError(f"{p}", "needs a [film] or a [uav] section (or both)")
    if "film" in flat:
        film = flat["film"]
        if "photo_scales" in film and "photo_scale" in film:
            raise InputError(f"{p}: {_where(lines, 'film', 'photo_scale')}", "give either "
                             "photo_scale (existing photos to scan) or photo_scales "
                             "(candidates to choose from), not both")
        if "photo_scales" not in film and "photo_scale" not in film:
            raise InputError(f"{p}: film.photo_scales", "is required in [film]: candidate "
                             "photo scales, e.g. photo_scales = [5000, 10000, 15000]; or, for "
                             "existing photos, their scale: photo_scale = 12000")
    _parse_scales(flat, lines, p)
    if "object_name" in flat.get("norms", {}) and "object_size_m" not in flat["norms"]:
        raise InputError(f"{p}: {_where(lines, 'norms', 'object_name')}", "needs "
                         "object_size_m: the size of the named object in m, e.g. "
                         "object_size_m = 0.15")
    locale = flat.get("project", {}).get("locale", "en")
    if locale not in ("en", "ru"):
        raise InputError(f"{p}: project.locale" + (f" (line {lines['project.locale']})"
                                                    if "project.locale" in lines else ""),
                         f'must be "en" or "ru" (got {locale!r})')
    name = flat.get("project", {}).get("name") or p.stem
    if "set" in flat.get("norms", {}):
        flat["norms"]["set"] = _norm_set_path(flat["norms"]["set"], p.parent)
    if "file" in flat.get("area", {}):
        f = flat["area"]["file"]
        if not (f.startswith("~") or os.path.isabs(f)):
            flat["area"]["file"] = os.path.join(p.parent, f)
    return Project(path=p, name=name, values=flat, lines=lines)


def _where(lines: dict[str, int], section: str, key: str) -> str:
    dotted = f"{section}.{key}"
    return f"{dotted} (line {lines[dotted]})" if dotted in lines else dotted


def _number(value: float) -> int | float:
    """2000.0 → 2000 (a scale prints as 1:2000, never 1:2000.0)."""
    return int(value) if float(value).is_integer() else value


def _parse_scales(flat: dict[str, dict[str, Any]], lines: dict[str, int], p: Path) -> None:
    """Scales written ``2000``, ``"1:2000"`` or ``"1:2 000"`` become numbers, once, here:
    everything after the loader sees a denominator."""
    from ..norms import parse_scale

    for section, key in (("map", "scale"), ("film", "photo_scale")):
        if key in flat.get(section, {}):
            where = f"{p}: {_where(lines, section, key)}"
            try:
                flat[section][key] = _number(parse_scale(flat[section][key], where))
            except InputError as exc:
                raise InputError(where, exc.message) from None
    if "photo_scales" in flat.get("film", {}):
        where = f"{p}: {_where(lines, 'film', 'photo_scales')}"
        try:
            flat["film"]["photo_scales"] = [_number(parse_scale(v, where))
                                            for v in flat["film"]["photo_scales"]]
        except InputError as exc:
            raise InputError(where, exc.message) from None


def _did_you_mean(section: str, key: str) -> str:
    """A hint for a mistyped key: the closest key of its section (``heigth_m`` →
    ``height_m``), or the section that takes this key (``[area] max_flight_time_min`` →
    ``[uav]``); "" when nothing is close."""
    close = closest_key(key, KEYS[section])
    if close:
        return close
    elsewhere = [sec for sec, keys in KEYS.items() if key in keys and sec != section]
    if elsewhere:
        return f" (it belongs in [{elsewhere[0]}])"
    return ""


def load_project(path: str | os.PathLike[str]) -> Project:
    """Read and validate a project file.

    Raises
    ------
    InputError
        Naming the file and the key with its line, for an unreadable file, invalid TOML,
        an unknown section or key, a wrong type, or a missing required key. Range checks
        happen when the plan is computed (the same checks as the command line), and name the
        key the same way.
    """
    p = Path(path)
    # a regular file, read with a bound: a FIFO or a link to /dev/zero is refused, not read
    return parse_project_bytes(read_limited(p, MAX_PROJECT_BYTES, field=str(p)), p)


def parse_project_bytes(data: bytes, p: Path) -> Project:
    """Validate a project file's bytes (UTF-8, a byte-order mark allowed); ``p`` names it in
    messages and anchors its relative paths."""
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        raise InputError(str(p), "is UTF-16 text; save it as UTF-8")
    try:
        text = data.decode("utf-8-sig")  # Notepad's UTF-8 has a byte-order mark
    except UnicodeDecodeError as exc:
        raise InputError(str(p), f"is not UTF-8 text (byte {exc.start:,}); save it as "
                         "UTF-8") from None
    return parse_project(text, p)
