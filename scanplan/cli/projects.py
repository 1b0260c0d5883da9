"""The project files a command names: ``-`` is the project on standard input.

``scanplan plan -`` reads one project file from stdin (``cat p.toml | scanplan plan -``,
or a generated project piped in); its relative paths (an area file, a DEM, a norm-set
folder) are read from the current folder, and messages name it ``<stdin>``.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

from ..errors import InputError

__all__ = ["STDIN", "STDIN_NAME", "check_stdin", "read_project"]

STDIN = "-"
"""The argument that means standard input."""
STDIN_NAME = "<stdin>"
"""How messages name the project read from standard input."""


def check_stdin(files: list[str]) -> None:
    """``-`` only alone: standard input holds one project."""
    if STDIN in files and len(files) > 1:
        raise InputError("PROJECTS", "- (the project on standard input) is one project; "
                         "give it alone, or give project files")


def read_project(path: str) -> Any:
    """The validated project of ``path`` (a file, or ``-`` for standard input).

    Raises
    ------
    InputError
        As :func:`scanplan.project.file.load_project`, and for an empty standard input.
    """
    from ..project.file import MAX_PROJECT_BYTES, load_project, parse_project_bytes

    if path != STDIN:
        return load_project(path)
    data = sys.stdin.buffer.read(MAX_PROJECT_BYTES + 1)
    if len(data) > MAX_PROJECT_BYTES:
        raise InputError(STDIN_NAME, f"is larger than {MAX_PROJECT_BYTES:,} bytes")
    if not data.strip():
        raise InputError(STDIN_NAME, "is empty: pipe a project file into `scanplan plan -`")
    return parse_project_bytes(data, Path(STDIN_NAME))
