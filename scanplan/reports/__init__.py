"""Reports for approval: shared pieces of the Excel and PDF writers.

Reports *render* result objects (:class:`scanplan.planner.ScanPlan`,
:class:`scanplan.uav.UavPlan` and their norm set); they never recompute a number.
Writing is atomic: the whole file is rendered to memory, written to a temporary file
beside the target and renamed over it, so a crash never leaves a half-written report and
never destroys the previous one. With ``SOURCE_DATE_EPOCH`` set, output is reproducible.
"""

from __future__ import annotations

import datetime as _dt
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path

__all__ = ["ReportMeta", "report_datetime", "templates_dir", "write_atomic"]


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

    On any failure the temporary file is removed and an existing ``path`` is untouched.
    """
    target = Path(path)
    folder = target.parent if str(target.parent) else Path(".")
    try:  # keep the mode of the file being replaced; a new file gets 0666 less the umask
        mode = target.stat().st_mode & 0o7777
    except FileNotFoundError:
        umask = os.umask(0)
        os.umask(umask)
        mode = 0o666 & ~umask
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=f".{target.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, mode)
        os.replace(tmp, target)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
    return target
