"""Bounds a TOML text is checked against before it is parsed: how deep arrays and inline
tables nest (the project file and the user's configuration both).

Python's TOML parser recurses once per level: a file nested some thousands deep would
exhaust its recursion (a traceback). No key of a project file or of the configuration
nests at all, so :data:`MAX_NESTING` is far above any real file.
"""

from __future__ import annotations

import re

__all__ = ["MAX_NESTING", "nesting_problem"]

MAX_NESTING = 32
"""Deepest nesting of arrays and inline tables (no key of a project file nests at all; the
bound keeps a hostile file from exhausting the parser's recursion)."""

_STRING = re.compile(
    r'"""(?:[^\\]|\\.)*?"""'  # multi-line basic string
    r"|'''.*?'''"  # multi-line literal string
    r'|"(?:[^"\\\n]|\\.)*"'  # basic string
    r"|'[^'\n]*'"  # literal string
    r"|#[^\n]*",  # comment
    re.DOTALL)
_BRACKET = re.compile(r"[\[\]{}\n]")


def nesting_problem(text: str) -> tuple[int, str] | None:
    """(line, message) where arrays or inline tables nest deeper than :data:`MAX_NESTING`.

    Strings and comments are skipped; table headers (``[x]`` at the start of a line)
    open and close on their line, so they count as depth 1 at most.
    """
    depth = 0
    line = 1
    pos = 0
    skips = [(m.start(), m.end()) for m in _STRING.finditer(text)] + [(len(text), len(text))]
    for start, end in skips:
        for b in _BRACKET.finditer(text, pos, start):
            ch = b.group()
            if ch == "\n":
                line += 1
            elif ch in "[{":
                depth += 1
                if depth > MAX_NESTING:
                    return line, (f"nests arrays or inline tables more than {MAX_NESTING} "
                                  "deep")
            else:
                depth = max(depth - 1, 0)
        line += text.count("\n", start, end)
        pos = end
    return None
