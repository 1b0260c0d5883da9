"""Where reports may be written: the rules that keep a user's files safe.

A report target (``--xlsx``, ``--pdf``, the files ``plan --out`` names) is checked before
anything is rendered and again, under a lock on its folder, just before it is written:

* ``-`` is refused: reports are binary files, never written to standard output.
* A target that is one of the run's input files (a project file), by name, through a
  symbolic link or as a hard link, is refused — even with ``--force``.
* The extension must fit the report: ``.xlsx`` for the workbook, ``.pdf`` for the PDF,
  ``.csv`` for a batch summary table (and for each file ``plan --out`` exports, the suffix
  of its format: :data:`scanplan.geo.export.formats.FORMATS`).
* A symbolic link, a folder, a FIFO or a device is refused (scanplan replaces regular files
  by renaming a new file over them; that would replace a link, not the file it points to)
  — except scanplan's own link of an output folder's set (:func:`is_managed`,
  :mod:`scanplan.io.folderset`), which is checked as the file it leads to.
* A write-protected file is refused, even with ``--force`` (its protection is the owner's
  statement; make it writable first).
* A file name longer than the folder's limit (255 bytes on common file systems) is refused.
* An existing non-empty file that scanplan did not write is replaced only with ``--force``.
  scanplan recognises its own reports by their document properties: the workbook's creator
  (``docProps/core.xml``, ``dc:creator``) and the PDF's document information (``/Creator``)
  both start with ``scanplan``, a batch summary table by its header; an exported file by
  the mark its format's record knows (:class:`FileKind` ``is_ours``). An empty file holds
  nothing to lose and is replaced.

A file kind is a :class:`FileKind` record: its suffix, what it is (for messages) and how
scanplan's own file of that kind is recognised. The reports' kinds are :data:`KINDS`
(``"xlsx"``, ``"pdf"``, ``"csv"``, named by a string); the exported formats are records of
``geo/export/formats.py`` passed to :func:`check_target` and :func:`written_by_scanplan`
themselves.

:func:`folder_lock` serialises report writers in one folder (``flock``, as the norm folder
lock): two runs writing into one ``--out`` folder cannot interleave their pairs, and the
stale temporaries of a killed run are removed by the next run under that lock
(:func:`scanplan.reports.write_atomic_many`).
"""

from __future__ import annotations

import contextlib
import os
import re
import stat
import zipfile
import zlib
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass

from ..errors import InputError

__all__ = ["KINDS", "OUR_MARK", "SETS", "FileKind", "check_target", "folder_lock",
           "is_managed", "link_text", "name_max", "written_by_scanplan"]

OUR_MARK = b"scanplan"
"""Start of the creator property of every report scanplan writes."""

CSV_HEADER = "\ufeffproject,file,map_scale,".encode()
"""How a batch summary.csv scanplan wrote begins (scanplan.reports.summary)."""
MAX_REPORT_BYTES = 64 * 1024 * 1024
"""An existing file larger than this is not looked into (scanplan's reports are far
smaller): it is treated as not written by scanplan [bytes]."""
_MAX_INFLATED = 16 * 1024 * 1024  # most bytes decompressed while looking for the PDF's /Creator
# openpyxl writes ``<dc:creator>``, or with lxml installed ``<dc:creator xmlns:dc="...">``
_CREATOR_XML = re.compile(rb"<dc:creator(?:\s[^>]*)?>\s*scanplan[\s<]")
_CREATOR_PDF = re.compile(rb"/Creator\s*\(scanplan[ )]")
_STREAM = re.compile(rb"stream\r?\n")


@dataclass(frozen=True)
class FileKind:
    """A kind of file scanplan writes: what a target of that kind is checked against.

    Attributes
    ----------
    name : str
        Its short name (``"xlsx"``, ``"plan"``).
    suffix : str
        The file-name ending a target must have (``".xlsx"``).
    what : str
        What it is, for messages (``"workbook"``).
    is_ours : callable
        ``is_ours(data) -> bool``: whether the bytes of an existing file are scanplan's own
        file of this kind (its mark; the whole file, at most :data:`MAX_REPORT_BYTES`).
    """

    name: str
    suffix: str
    what: str
    is_ours: Callable[[bytes], bool]


SETS = ".scanplan-sets"
"""The folder of an output folder's file sets (:mod:`scanplan.io.folderset`)."""


def link_text(name: str) -> str:
    """What scanplan's link of the file ``name`` of an output folder's set says:
    ``.scanplan-sets/current/NAME``."""
    return f"{SETS}/current/{name}"


def is_managed(path: str | os.PathLike[str]) -> bool:
    """Whether ``path`` is scanplan's link of a file of its folder's set (it says exactly
    :func:`link_text` of its own name; a user's link says anything else)."""
    try:
        return os.readlink(path) == link_text(os.path.basename(os.fspath(path)))
    except (OSError, ValueError):
        return False


def name_max(folder: str | os.PathLike[str]) -> int:
    """Longest file name [bytes] the folder's file system accepts (255 where unknown)."""
    try:
        return int(os.pathconf(folder, "PC_NAME_MAX"))
    except (OSError, ValueError, AttributeError):
        return 255


def _same_file(a: os.stat_result, b: os.stat_result) -> bool:
    return (a.st_dev, a.st_ino) == (b.st_dev, b.st_ino)


def check_target(path: str, field: str, kind: str | FileKind, *, inputs: Iterable[str] = (),
                 force: bool = False) -> None:
    """Refuse a report target that is unsafe to write (rules in the module docstring).

    Parameters
    ----------
    path : str
        The target as the user gave it.
    field : str
        How messages name it (``--xlsx``, ``--out``).
    kind : {"xlsx", "pdf", "csv"} or FileKind
        The report (a name in :data:`KINDS`) or the exported format it is for.
    inputs : iterable of str
        The run's input files; none of them may be the target.
    force : bool
        Replace an existing file scanplan did not write (``--force``).

    Raises
    ------
    InputError
        Naming ``field`` and the reason (exit 2).
    """
    if path.strip() == "-":
        raise InputError(field, "'-' (standard output) cannot take a report: reports are "
                         "binary files; give a file name")
    folder = os.path.dirname(os.path.abspath(path))
    limit = name_max(folder) if os.path.isdir(folder) else 255
    size = len(os.fsencode(os.path.basename(path)))
    if size > limit:
        raise InputError(field, f"the file name is {size} bytes long; the file system allows "
                         f"{limit}")
    shown = repr(path)
    try:
        st = os.stat(path) if is_managed(path) else os.lstat(path)
    except FileNotFoundError:
        st = None  # also scanplan's link to a file the folder's set does not hold
    except OSError as exc:
        raise InputError(field, f"{shown} cannot be checked: {exc.strerror or exc}") from None
    real = None
    if st is not None:
        with contextlib.suppress(OSError):
            real = os.stat(path)
    for item in inputs if real is not None else ():
        try:
            same = _same_file(real, os.stat(item))  # type: ignore[arg-type]
        except OSError:
            continue
        if same:
            raise InputError(field, f"{shown} is the input file {item!r}; a report never "
                             "replaces an input — give another name")
    kind = KINDS[kind] if isinstance(kind, str) else kind
    if not path.lower().endswith(kind.suffix):
        raise InputError(field, f"{shown} does not end in {kind.suffix}; the "
                         f"{kind.what} is written only to a {kind.suffix} file")
    if st is None:
        return
    if stat.S_ISLNK(st.st_mode):
        raise InputError(field, f"{shown} is a symbolic link (to {os.readlink(path)!r}); "
                         "scanplan replaces files, not links — name the file itself")
    if not stat.S_ISREG(st.st_mode):
        from .files import file_kind

        raise InputError(field, f"{shown} is {file_kind(st.st_mode)}; give a file name")
    # Another scanplan run may sweep the file away between these looks (this check runs
    # once before rendering without the folder's lock): a file gone meanwhile has nothing
    # to protect, and the check under the lock just before the write decides.
    if (not os.access(path, os.W_OK) or not st.st_mode & 0o222) and os.path.lexists(path):
        raise InputError(field, f"{shown} is write-protected; scanplan leaves it alone "
                         "(make it writable, or give another name)")  # root too: no write bit
    if (st.st_size and not force and not written_by_scanplan(path, kind)
            and os.path.lexists(path)):
        raise InputError(field, f"{shown} exists and was not written by scanplan; give "
                         "--force to replace it, or another name")


def written_by_scanplan(path: str | os.PathLike[str], kind: str | FileKind) -> bool:
    """Whether ``path`` is a report scanplan wrote (its creator property says so).

    Parameters
    ----------
    path : path
        An existing regular file.
    kind : {"xlsx", "pdf", "csv"} or FileKind
        What it should be: a report (a name in :data:`KINDS`) or an exported format.

    Returns
    -------
    bool
        False for anything else, an unreadable file or one over :data:`MAX_REPORT_BYTES`.
    """
    from .files import read_limited

    try:
        data = read_limited(path, MAX_REPORT_BYTES)
    except InputError:
        return False
    return (KINDS[kind] if isinstance(kind, str) else kind).is_ours(data)


def _xlsx_is_ours(data: bytes) -> bool:
    import io

    try:
        with zipfile.ZipFile(io.BytesIO(data)) as zf, zf.open("docProps/core.xml") as fh:
            return bool(_CREATOR_XML.search(fh.read(65536)))
    except (zipfile.BadZipFile, KeyError, OSError, ValueError, RuntimeError,
            NotImplementedError, EOFError, zlib.error):
        return False


def _pdf_is_ours(data: bytes) -> bool:
    """The document information (plain, or in a compressed object stream) names scanplan."""
    if not data.startswith(b"%PDF-"):
        return False
    if _CREATOR_PDF.search(data):
        return True
    budget = _MAX_INFLATED
    starts = [m.end() for m in _STREAM.finditer(data)]
    for start in reversed(starts):  # the information object is written last
        inflate = zlib.decompressobj()
        try:
            chunk = inflate.decompress(data[start:start + budget], budget)
        except zlib.error:
            continue
        if _CREATOR_PDF.search(chunk):
            return True
        budget -= len(chunk)
        if budget <= 0:
            return False
    return False


KINDS = {kind.name: kind for kind in (
    FileKind("xlsx", ".xlsx", "workbook", _xlsx_is_ours),
    FileKind("pdf", ".pdf", "PDF", _pdf_is_ours),
    FileKind("csv", ".csv", "table", lambda data: data.startswith(CSV_HEADER)),
)}
"""The reports' kinds of file: the workbook, the PDF, a batch's summary table."""


@contextlib.contextmanager
def folder_lock(folders: Iterable[str | os.PathLike[str]]) -> Iterator[None]:
    """Hold an exclusive ``flock`` on each folder (sorted, so two writers never deadlock).

    Only other scanplan writers wait for it; without ``flock`` (not POSIX) or where a folder
    cannot be opened it is a no-op for that folder.
    """
    fds: list[int] = []
    try:
        try:
            import fcntl
        except ImportError:  # pragma: no cover - not POSIX
            fcntl = None  # type: ignore[assignment]
        for folder in sorted({os.path.realpath(f) for f in folders}):
            if fcntl is None:
                break
            try:
                fd = os.open(folder, os.O_RDONLY)
            except OSError:
                continue
            fds.append(fd)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX)
            except OSError:
                pass
        yield
    finally:
        for fd in fds:
            os.close(fd)


BATCH_SUMMARY_STEM = "summary"
"""The name of a batch's summary table (summary.csv, summary.xlsx) in ``--out``."""


def batch_stems(files: list[str]) -> list[str]:
    """One report name per project of a batch: the file's stem, ``STEM-2``, ``STEM-3`` …
    for later projects with the same stem (compared without case: some file systems ignore
    it), so that no project's reports replace another's. ``summary`` is the batch
    summary's (summary.csv, summary.xlsx): a project named so gets ``summary-2``."""
    used: set[str] = {BATCH_SUMMARY_STEM}
    out = []
    for path in files:
        stem = os.path.splitext(os.path.basename(path))[0] or "spec"
        name, n = stem, 1
        while name.casefold() in used:
            n += 1
            name = f"{stem}-{n}"
        used.add(name.casefold())
        out.append(name)
    return out
