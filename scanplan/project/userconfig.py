"""The user's configuration: who they are, set once instead of in every project.

A TOML file with a ``[project]`` table of the project file's own ``[project]`` keys —
typically the organisation, the people who sign (``compiled_by``, ``checked_by``,
``approver_position``, ``approver_name``, ``contractor``) and the report language
(``locale``)::

    [project]
    organisation = "ООО «Аэрогеодезия»"
    compiled_by = "Иванов И. И."
    locale = "ru"

It is found at ``$SCANPLAN_CONFIG``, else ``config.toml`` in the platform's user
configuration folder (platformdirs: Linux ``~/.config/scanplan``, macOS
``~/Library/Application Support/scanplan``, Windows ``%LOCALAPPDATA%\\scanplan``). Each key
is a default: a project file that gives the key overrides it. A bad key or value is an
error naming the configuration file, the key and its line, as in a project file.
"""

from __future__ import annotations

import os
import tomllib
from pathlib import Path
from typing import Any

from ..errors import InputError
from .bounds import nesting_problem
from .keys import KEYS, check_text, check_type, closest_key, key_lines

__all__ = ["SECTION", "config_path", "user_defaults", "with_user_defaults"]

SECTION = "project"
"""The one table of the configuration file."""

_cache: dict[str, tuple[float, int, dict[str, Any]]] = {}


def config_path() -> Path:
    """Where the configuration is read from (it need not exist)."""
    env = os.environ.get("SCANPLAN_CONFIG")
    if env:
        return Path(env).expanduser()
    import platformdirs

    return platformdirs.user_config_path("scanplan", appauthor=False) / "config.toml"


def _validate(doc: dict[str, Any], path: Path, text: str) -> dict[str, Any]:
    lines = key_lines(text)

    def where(key: str) -> str:
        dotted = f"{SECTION}.{key}" if key else SECTION
        return f"{path}: {dotted}" + (f" (line {lines[dotted]})" if dotted in lines else "")

    for section, value in doc.items():
        if section != SECTION or not isinstance(value, dict):
            raise InputError(where("") if section == SECTION else f"{path}: [{section}]",
                             f"the configuration holds one table, [{SECTION}], with keys of "
                             "a project file's [project]")
    table = doc.get(SECTION, {})
    for key, value in table.items():
        if key not in KEYS[SECTION] or key == "name":
            takes = [k for k in KEYS[SECTION] if k != "name"]
            raise InputError(where(key), f"unknown key{closest_key(key, takes)}; [{SECTION}] "
                             f"of the configuration takes {', '.join(takes)}")
        kind, desc = KEYS[SECTION][key]
        problem = check_type(kind, value) or check_text(kind, value)
        if problem:
            raise InputError(where(key), f"{problem} — {desc}")
    if table.get("locale", "en") not in ("en", "ru"):
        raise InputError(where("locale"), f'must be "en" or "ru" (got {table["locale"]!r})')
    return dict(table)


def user_defaults() -> dict[str, Any]:
    """The ``[project]`` keys of the user's configuration ({} without one).

    Raises
    ------
    InputError
        Naming the file, key and line of a bad configuration.
    """
    path = config_path()
    try:
        st = path.stat()
    except OSError:
        return {}
    key = os.fspath(path)
    hit = _cache.get(key)
    if hit is not None and hit[:2] == (st.st_mtime, st.st_size):
        return dict(hit[2])
    from ..io.files import read_limited

    data = read_limited(path, 100_000, field=str(path))
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(str(path), f"is not UTF-8 text: {exc}") from None
    deep = nesting_problem(text)
    if deep:
        raise InputError(f"{path} (line {deep[0]})", deep[1])
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(str(path), f"is not valid TOML: {exc}") from None
    except ValueError:  # an integer over Python's 4,300-digit conversion limit
        raise InputError(str(path), "holds a number of more than 4,300 digits") from None
    table = _validate(doc, path, text)
    _cache[key] = (st.st_mtime, st.st_size, table)
    return dict(table)


def with_user_defaults(flat: dict[str, dict[str, Any]]) -> dict[str, dict[str, Any]]:
    """A project's sections with the configuration's ``[project]`` keys added where the
    project does not give them (the project's own values win)."""
    defaults = user_defaults()
    if defaults:
        flat.setdefault(SECTION, {})
        for key, value in defaults.items():
            flat[SECTION].setdefault(key, value)
    return flat
