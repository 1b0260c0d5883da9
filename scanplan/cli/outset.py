"""The reports and the output set of ``plan --out`` as the command line writes them: the
transaction of :mod:`scanplan.reports.documents` with the command line's PDF engine,
warnings and progress, and the lines it says (docs/reliability.md)."""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Iterable, Mapping
from typing import Any

import click

from ..progress import listened
from .console import info, verbosity

MANY_FILES = 50
"""From this many files on, a terminal drawing the stages of a plan is told before their
write begins."""


def write_reports(*, xlsx: str | None, pdf: str | None, meta: Any, scan: Any = None,
                  uav: Any = None, spec: Any = None,
                  fields: tuple[str, str] = ("--xlsx", "--pdf"), force: bool = False,
                  inputs: Iterable[str] = (),
                  exports: Mapping[str, tuple[Any, bytes]] | None = None,
                  note: str = "", say: Callable[[str], None] | None = None,
                  pdf_worker: Any = None, sweep: str | None = None,
                  pdf_explicit: bool = True, tables: Any = None) -> None:
    """Write the requested reports (and ``plan --out``'s ``exports``: path → (kind,
    bytes)) as one transaction (:func:`scanplan.reports.documents.write_documents`); say
    where on stderr (stdout may carry --json).

    ``fields`` name the --xlsx and --pdf targets in messages; ``pdf_worker`` renders the
    PDF on the second core; ``sweep`` is the --out folder whose stale exports go (one
    project); ``pdf_explicit``: the PDF was asked for by name (without an engine the
    command fails at the end); ``tables``: the result's tables (``ResultTables``) the
    documents' view holds, when the terminal lays them out too.
    """
    from ..reports.documents import Target, write_documents
    from . import outputs

    targets = [Target(path, kind, field) for path, kind, field
               in ((xlsx, "xlsx", fields[0]), (pdf, "pdf", fields[1])) if path]
    done = write_documents(targets, scan=scan, uav=uav, spec=spec, meta=meta, extra=exports,
                           inputs=inputs, force=force, sweep=sweep, pdf_worker=pdf_worker,
                           pdf_engine=lambda: outputs.pdf_renderer(pdf_explicit),
                           on_missing=outputs.warn_stale, announce=announce, tables=tables)
    say_written(done.files, done.removed, say or info, note)


def write_set(files: Mapping[str, bytes], *, check: Callable[[], None], sweep: str | None,
              say: Callable[[str], None], note: str = "") -> None:
    """Write ``files`` as one transaction (:func:`scanplan.reports.documents.commit`)
    together with the removal of the exported files of an earlier run into ``sweep``
    that this run no longer writes; then say ``wrote FILE`` and ``removed FILE`` lines.

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
    from ..reports.documents import commit

    _, removed = commit(files, check=check, sweep=sweep, announce=announce)
    say_written(list(files), removed, say, note)


def announce(files: Mapping[str, bytes]) -> None:
    """Hundreds of files take seconds: a terminal drawing the stages is told first."""
    if len(files) >= MANY_FILES and listened():
        click.echo(f"writing {len(files)} files …", err=True)


def say_written(files: list[str], removed: list[str], say: Callable[[str], None],
                note: str = "") -> None:
    """The ``wrote FILE`` and ``removed FILE`` lines of a write (-v: a line per file)."""
    every = verbosity() >= 1
    for line in file_lines(files, every=every):
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


def batch_text(path: str, result: Any) -> tuple[list[str], str]:
    """What a text-mode batch keeps of a project: its line of the summary table and its
    warnings, as text (the result itself is dropped)."""
    from ..reports.text import batch_row, project_warnings

    return batch_row(path, result), project_warnings(path, result)
