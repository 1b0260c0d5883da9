"""Reports for approval: shared pieces of the Excel and PDF writers.

Reports *render* result objects (:class:`scanplan.planner.ScanPlan`,
:class:`scanplan.uav.UavPlan` and their norm set); they never recompute a number.
Writing is atomic: the whole file is rendered to memory, written to a temporary file
beside the target and renamed over it, so a crash never leaves a half-written report and
never destroys the previous one. Several files that belong together (spec.xlsx and
spec.pdf) are written as one transaction (:func:`write_atomic_many`): after any failure all
of the previous files are as they were. With ``SOURCE_DATE_EPOCH`` set, output is
reproducible.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import errno
import os
import secrets
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from ..errors import WriteError
from ..safeio import write_all

__all__ = ["ReportMeta", "report_datetime", "templates_dir", "write_atomic",
           "write_atomic_many"]


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


def report_datetime() -> _dt.datetime:
    """Now (UTC), or ``SOURCE_DATE_EPOCH`` when set (reproducible builds)."""
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    if epoch and epoch.strip().isdigit():
        return _dt.datetime.fromtimestamp(int(epoch), tz=_dt.UTC)
    return _dt.datetime.now(tz=_dt.UTC).replace(microsecond=0)


def templates_dir() -> Path:
    """Bundled templates and fonts (``templates/`` in a checkout, packaged in a wheel)."""
    here = Path(__file__).resolve().parent.parent
    for candidate in (here / "_data" / "templates", here.parent / "templates"):
        if (candidate / "fonts").is_dir():
            return candidate
    raise RuntimeError(f"scanplan's bundled templates are missing (looked in "
                       f"{here / '_data' / 'templates'} and {here.parent / 'templates'}); "
                       "reinstall scanplan")


def write_atomic(path: str | os.PathLike[str], data: bytes) -> Path:
    """Write ``data`` to ``path`` atomically (temporary file beside it, fsync, rename).

    On any failure (including ``KeyboardInterrupt``) the temporary file is removed and an
    existing ``path`` is untouched. A file being replaced keeps its mode; a new one gets
    0666 less the umask.

    Parameters
    ----------
    path : str or path
        The file to write; its folder must exist.
    data : bytes
        The whole content.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    WriteError
        An :class:`OSError` naming ``path`` and the reason (disk full, permission, ...).
    """
    return write_atomic_many({path: data})[0]


def write_atomic_many(files: Mapping[str | os.PathLike[str], bytes]) -> list[Path]:
    """Write several files as one transaction: all of them are replaced, or none is.

    Every file is first written to a temporary file beside its target (``.NAME.*.tmp``,
    fsynced, given the mode of the file it replaces). Only then are they renamed into
    place, one after the other; before each rename but the last, the current file is kept
    under a hidden backup name (``.NAME.*.old``, a hard link, or the file moved aside where
    hard links are not available). If anything fails — disk full, a permission, an
    interrupted rename, ``KeyboardInterrupt`` — the files already renamed are put back from
    their backups (new ones removed) and every temporary and backup file is deleted, so all
    previous files are byte-identical and nothing is left behind.

    Parameters
    ----------
    files : mapping of path to bytes
        Target → complete content, written in this order. Folders must exist.

    Returns
    -------
    list of Path
        The targets, in order.

    Raises
    ------
    WriteError
        An :class:`OSError` naming the file that could not be written (as given in
        ``files``) and the reason: ``cannot write out/spec.pdf: No space left on device``.
        Should putting a previous file back fail too, the message says where it is kept.
    ValueError
        The same file is named twice.

    Notes
    -----
    A process killed outright (power loss, ``SIGKILL``) between two renames can leave a
    new file beside an old one; every target still holds a complete file, and the older
    version of the renamed one is in its ``.NAME.*.old`` backup.
    """
    items = [(Path(p), os.fspath(p), data) for p, data in files.items()]
    seen: set[str] = set()
    for target, shown, _ in items:
        key = os.path.normcase(os.path.realpath(target))
        if key in seen:
            raise ValueError(f"{shown!r} is named twice")
        seen.add(key)
        if os.path.isdir(target):
            raise WriteError(shown, "it is a folder", errno.EISDIR)
    current = items[0][1] if items else ""
    temps: list[Path] = []
    steps: list[_Step] = []  # one per rename started, in order
    try:
        for target, shown, data in items:
            current = shown
            temps.append(_write_temp(target, data))
        for i, (target, shown, _) in enumerate(items):
            current = shown
            step = _Step(target, shown)
            if i < len(items) - 1 and os.path.lexists(target):
                step.backup, step.linked = _backup(target)
            steps.append(step)
            os.replace(temps[i], target)
            step.replaced = True
    except BaseException as exc:
        committed = len(steps) == len(items) and steps[-1].replaced
        note = "" if committed else _roll_back(steps)
        for i, tmp in enumerate(temps):
            if i >= len(steps) or not steps[i].replaced:
                _discard(tmp)
        if not note and not committed and len(items) > 1:
            note = "none of " + ", ".join(s for _, s, _ in items) + " was changed"
        if isinstance(exc, OSError) and not isinstance(exc, WriteError) and not committed:
            raise WriteError.from_os_error(current, exc, note=note) from exc
        if committed:
            _drop_backups(steps)
        raise
    _drop_backups(steps)  # committed: the backups are no longer needed
    return [target for target, _, _ in items]


@dataclass
class _Step:
    """One target of :func:`write_atomic_many` during the renames."""

    target: Path
    shown: str
    backup: Path | None = None
    linked: bool = False  # the backup is a hard link; the target is still in place
    replaced: bool = False


def _drop_backups(steps: list[_Step]) -> None:
    for step in steps:
        if step.backup is not None:
            _discard(step.backup)


def _new_mode(target: Path) -> int:
    """The mode of the file being replaced; for a new file 0666 less the umask."""
    try:
        return target.stat().st_mode & 0o7777
    except FileNotFoundError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def _write_temp(target: Path, data: bytes) -> Path:
    """Write ``data`` to a new temporary file beside ``target`` (fsync, chmod)."""
    mode = _new_mode(target)
    fd, name = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    tmp = Path(name)
    try:
        try:
            write_all(fd, data)
        finally:
            os.close(fd)
        os.chmod(tmp, mode)
    except BaseException:
        _discard(tmp)
        raise
    return tmp


def _backup(target: Path) -> tuple[Path, bool]:
    """Keep the current ``target`` under a hidden name: (backup, target still in place).

    A hard link leaves ``target`` in place; where links are not possible (FAT, some network
    shares, a file owned by someone else) the file is moved aside instead.
    """
    for _ in range(100):
        backup = target.with_name(f".{target.name}.{secrets.token_hex(4)}.old")
        if os.path.lexists(backup):
            continue
        try:
            if os.link in os.supports_follow_symlinks:
                os.link(target, backup, follow_symlinks=False)
            else:  # pragma: no cover - platform dependent
                os.link(target, backup)
            return backup, True
        except FileExistsError:
            continue
        except (OSError, NotImplementedError):
            break
    os.replace(target, backup)
    return backup, False


def _roll_back(steps: list[_Step]) -> str:
    """Put every previous file back, last first; '' or what could not be restored."""
    problems = []
    for step in reversed(steps):
        try:
            if step.backup is None:
                if step.replaced:
                    os.unlink(step.target)  # it did not exist before
            elif step.replaced or not step.linked:
                os.replace(step.backup, step.target)  # the previous file back in place
            else:
                os.unlink(step.backup)  # a hard link; the target was never touched
        except OSError as exc:
            kept = (f"; the previous file is kept as {step.backup}"
                    if step.backup is not None and os.path.lexists(step.backup) else "")
            problems.append(f"{step.shown} could not be put back ({exc.strerror or exc}){kept}")
    return "; ".join(problems)


def _discard(path: Path) -> None:
    with contextlib.suppress(OSError):
        os.unlink(path)
