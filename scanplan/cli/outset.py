"""The output set of ``plan --out`` as the command line writes it: one transaction with
the sweep of an earlier run's files, the lines it says, the inputs it protects, and the
``--out`` folders it refuses (docs/reliability.md)."""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Mapping
from typing import Any

import click

from ..errors import InputError
from ..progress import listened
from .console import verbosity

MANY_FILES = 50
"""From this many files on, a terminal drawing the stages of a plan is told before their
write begins."""


def write_set(files: Mapping[str, bytes], *, check: Callable[[], None], sweep: str | None,
              say: Callable[[str], None], note: str = "") -> None:
    """Write ``files`` as one transaction (:func:`scanplan.io.atomic.write_atomic_many`)
    together with the removal of the exported files of an earlier run into ``sweep``
    that this run no longer writes (``mission-04.plan`` of six sorties, now three); then
    say ``wrote FILE`` and ``removed FILE`` lines.

    Parameters
    ----------
    files : mapping of str to bytes
        Every file of the set, in the order of the ``wrote`` lines.
    check : callable
        Re-checks the targets under the folder lock.
    sweep : str or None
        The ``--out`` folder of a single project (a batch sweeps nothing).
    say : callable
        Receives each line.
    note : str
        Added to each ``wrote`` line.
    """
    from ..io.atomic import write_atomic_many

    removed: list[str] = []

    def stale() -> list[str]:  # under the transaction's lock, after the check
        from ..reports.exports import stale_exports

        removed[:] = stale_exports(sweep, set(files)) if sweep else []
        return removed

    if len(files) >= MANY_FILES and listened():  # hundreds take seconds: say so at a terminal
        click.echo(f"writing {len(files)} files …", err=True)
    write_atomic_many(files, check=check, remove=stale if sweep else None)
    every = verbosity() >= 1  # -v: a line per file
    for line in file_lines(list(files), every=every):
        say(f"wrote {line}{note}")
    for line in file_lines(removed, every=every):
        say(f"removed {line} (left from an earlier plan)")


_NUMBERED = re.compile(r"^(?P<stem>.*)-(?P<n>\d+)(?P<suffix>\.[^.]+)$")
KIND_NAMES = {".plan": "QGroundControl missions", ".waypoints": "Mission Planner missions",
              ".kmz": "DJI Pilot 2 routes"}
"""What a numbered series of files is, by its suffix (a line of :func:`file_lines`)."""


def file_lines(paths: list[str], every: bool = False) -> list[str]:
    """The files of one write as lines to say: a numbered series of one kind in one
    folder (``mission-001.plan`` … ``mission-113.plan``) as one line with its count, its
    first and its last file; every other file on a line of its own.

    Parameters
    ----------
    paths : list of str
        The files, in the order to say them.
    every : bool
        A line per file (``-v``).

    Returns
    -------
    list of str
        ``"out/spec.xlsx"``, ``"113 QGroundControl missions: out/mission-001.plan …
        out/mission-113.plan"``, in the order of each series' first file.

    Examples
    --------
    >>> file_lines(["o/spec.pdf", "o/mission-01.plan", "o/mission-02.plan"])
    ['o/spec.pdf', '2 QGroundControl missions: o/mission-01.plan … o/mission-02.plan']
    """
    if every:
        return list(paths)
    series: dict[tuple[str, ...], list[str]] = {}
    for path in paths:
        folder, name = os.path.split(path)
        m = _NUMBERED.match(name)
        key = (folder, m["stem"], m["suffix"]) if m else (path,)
        series.setdefault(key, []).append(path)
    lines = []
    for key, members in series.items():
        if len(members) == 1:
            lines.append(members[0])
            continue
        kind = KIND_NAMES.get(key[2].lower(), f"{key[2]} files")
        lines.append(f"{len(members)} {kind}: {members[0]} … {members[-1]}")
    return lines


def say_export_notes(result: Any, say: Callable[[str], None] | None) -> None:
    """Say (stderr by default) which mission or photo table ``plan --out`` did not write,
    and why, in the project's language."""
    from ..reports.exports import export_notes

    for line in export_notes(result):
        (say or (lambda text: click.echo(text, err=True)))(
            f"note: {line.text(result.meta.locale)}")


def project_inputs(result: Any) -> list[str]:
    """The files a planned project read besides itself: its area file, its DEM (never
    replaced by an output, even with ``--force``)."""
    project = getattr(result, "project", None)  # the parsed model (project/model.py)
    if project is None:
        return []
    found: list[str] = []
    area_file = project.area.file
    if isinstance(area_file, str) and area_file:
        found.append(os.path.expanduser(area_file))  # already resolved beside the project
    terrain = project.terrain
    if terrain is not None and terrain.config.dem is not None:
        found.append(str(terrain.config.dem))  # resolved beside the project file
    return found


def refuse_dangling_link(path: str) -> None:
    """``--out`` (or a folder above it) that is a symbolic link to nothing: exit 2 naming
    it — scanplan creates missing folders, not the target of a broken link."""
    probe = path
    while probe and not os.path.exists(probe):
        if os.path.islink(probe):
            shown = "" if probe == path else f" (in {path!r})"
            raise InputError("--out", f"{probe!r}{shown} is a symbolic link to "
                             f"{os.readlink(probe)!r}, which does not exist; create that "
                             "folder, or give another")
        parent = os.path.dirname(probe.rstrip(os.sep))
        if parent == probe:
            break
        probe = parent


def batch_text(path: str, result: Any) -> tuple[list[str], str]:
    """What a text-mode batch keeps of a project: its line of the summary table and its
    warnings, as text (the result itself is dropped)."""
    from ..reports.text import batch_row, project_warnings

    return batch_row(path, result), project_warnings(path, result)
