"""Atomic writes: one file, or a set of files as one transaction (all replaced or none).

:func:`write_atomic` renders nothing itself; it writes the bytes to a temporary file beside
the target, fsyncs and renames it over the target, so a crash never leaves a half-written
file and never destroys the previous one. Several files that belong together (spec.xlsx and
spec.pdf) are written as one transaction (:func:`write_atomic_many`), made all-or-nothing
across a kill by the journal (:mod:`scanplan.io.journal`) and held under the folders' lock
(:func:`scanplan.io.targets.folder_lock`). Reports and norm sets both use these writers;
this module sits below both.
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import secrets
import stat
import tempfile
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path

from ..errors import WriteError
from .files import fsync_dir, write_all
from .journal import JOURNAL_NAME, Entry, Journal, recover
from .targets import folder_lock, name_max

__all__ = ["write_atomic", "write_atomic_many"]


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


def write_atomic_many(files: Mapping[str | os.PathLike[str], bytes], *,
                      check: Callable[[], None] | None = None,
                      remove: Callable[[], Iterable[str | os.PathLike[str]]] | None = None,
                      as_set: str | os.PathLike[str] | None = None) -> list[Path]:
    """Write several files as one transaction: all of them are replaced, or none is.

    Every file is first written to a temporary file beside its target (``.NAME.*.tmp``,
    fsynced, given the mode of the file it replaces). Then a journal is written
    (:mod:`scanplan.io.journal`), and only then are the files renamed into place, one after
    the other, each current file kept under a hidden backup name (``.NAME.*.old``, a hard
    link, or the file moved aside where hard links are not available); the files ``remove``
    names (the stale files of an earlier run) are moved aside too. If anything fails — disk
    full, a permission, an interrupted rename, ``KeyboardInterrupt`` — the files already
    renamed are put back from their backups (new ones removed) and every temporary and
    backup file is deleted, so all previous files are byte-identical and nothing is left
    behind. A process killed outright (``kill -9``, power loss) at any step leaves the
    journal; the next write into the folder rolls the set back (before the commit point)
    or finishes it (after), so every file is old or every file is new.

    The whole transaction holds an exclusive lock on the targets' folders
    (:func:`scanplan.io.targets.folder_lock`): two runs never interleave their files, one
    run's sweep never removes what another has just written. Under it a killed run's
    journal is recovered, its temporaries and backups deleted; the folders are fsynced
    after the renames. Names up to the file system's limit work (temporaries shortened).

    Parameters
    ----------
    files : mapping of path to bytes
        Target → complete content, in order; folders must exist. None (and no ``remove``):
        only ``check`` is called.
    check : callable, optional
        Re-checks the targets under the lock before anything is written; raises to stop.
    remove : callable, optional
        Called under the lock after ``check``: the files to remove in the same transaction
        (none of the targets).
    as_set : path, optional
        The folder of every file: written as its new set, whole at every instant
        (:mod:`scanplan.io.folderset`) where its file system has links.

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
    """
    items = [(Path(p), os.fspath(p), data) for p, data in files.items()]
    seen = _distinct(items)
    if not items and remove is None:  # nothing to write (`scan --json`): no journal, no fsync
        return _checked_only(check)
    if as_set is not None and _as_set(items, as_set):
        from .folderset import write_set

        return write_set(as_set, items, check=check, remove=remove)
    folders = sorted({os.fspath(target.parent) for target, _, _ in items})
    with folder_lock(folders):
        _recover(folders)
        if check is not None:
            check()
        gone = [Path(p) for p in (remove() if remove is not None else ())]
        gone = [p for p in gone if os.path.normcase(os.path.realpath(p)) not in seen]
        for target in [*(t for t, _, _ in items), *gone]:
            _remove_stale(target)
        before = {shown: _identity(target) for target, shown, _ in items}
        try:
            return _write_locked(items, before, gone, folders[0] if folders else ".")
        finally:
            for folder in folders:
                fsync_dir(folder)


def _distinct(items: list[tuple[Path, str, bytes]]) -> set[str]:
    """The targets' real paths; a file named twice or a folder is refused."""
    seen: set[str] = set()
    for target, shown, _ in items:
        key = os.path.normcase(os.path.realpath(target))
        if key in seen:
            raise ValueError(f"{shown!r} is named twice")
        seen.add(key)
        if os.path.isdir(target):
            raise WriteError(shown, "it is a folder", errno.EISDIR)
    return seen


def _as_set(items: list[tuple[Path, str, bytes]], folder: str | os.PathLike[str]) -> bool:
    """Whether the files are written as ``folder``'s set: every target lies in it (not
    below it) and its file system has links."""
    from .folderset import supported

    real = os.path.realpath(folder)
    return bool(items) and all(os.path.realpath(t.parent) == real for t, _, _ in items) \
        and supported(folder)


def _checked_only(check: Callable[[], None] | None) -> list[Path]:
    """An empty transaction: only the check (nothing is locked, journalled or synced)."""
    if check is not None:
        check()
    return []


def _recover(folders: list[str]) -> None:
    """Undo or finish what a killed writer left in ``folders`` (under their lock)."""
    try:
        recover(folders)
    except OSError as exc:
        raise WriteError.from_os_error(
            os.path.join(folders[0], JOURNAL_NAME), exc,
            note="an earlier interrupted write could not be undone") from exc


def _identity(path: Path) -> tuple[int, int, int, int] | None:
    """(device, inode, size, mtime) of ``path``, or None when it does not exist."""
    try:
        st = os.lstat(path)
    except OSError:
        return None
    return (st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns)


def _plan_journal(items: list[tuple[Path, str, bytes]], temps: list[Path],
                  gone: list[Path], folder: str) -> Journal:
    """The journal of the transaction: backup names chosen, nothing renamed yet."""
    entries = []
    for (target, _, _), tmp in zip(items, temps, strict=True):
        st = os.lstat(tmp)
        backup = _backup_name(target) if os.path.lexists(target) else None
        entries.append(Entry(os.path.abspath(target), os.path.abspath(tmp),
                             backup and os.path.abspath(backup), [st.st_dev, st.st_ino]))
    for path in gone:
        entries.append(Entry(os.path.abspath(path), None,
                             os.path.abspath(_backup_name(path)), None, remove=True))
    return Journal(folder, entries)


def _write_locked(items: list[tuple[Path, str, bytes]],
                  before: Mapping[str, tuple[int, int, int, int] | None],
                  gone: list[Path], folder: str) -> list[Path]:
    """:func:`write_atomic_many` under the folder lock."""
    current = items[0][1] if items else ""
    temps: list[Path] = []
    steps: list[_Step] = []  # one per rename started, in order
    journal: Journal | None = None
    committed = False
    try:
        for target, shown, data in items:
            current = shown
            temps.append(_write_temp(target, data))
        journal = _plan_journal(items, temps, gone, folder)
        journal.prepare()
        entries = iter(journal.entries)
        for i, (target, shown, _) in enumerate(items):
            current = shown
            step = _Step(target, shown)
            entry = next(entries)
            if entry.backup is not None:
                step.backup, step.linked = _backup(target, Path(entry.backup))
            steps.append(step)
            os.replace(temps[i], target)
            step.replaced = True
        for path in gone:
            current = os.fspath(path)
            entry = next(entries)
            step = _Step(path, current, backup=Path(entry.backup), removed=True)  # type: ignore[arg-type]
            steps.append(step)
            os.replace(path, step.backup)  # type: ignore[arg-type]
            step.replaced = True
        journal.commit()
        committed = True
    except BaseException as exc:
        note = "" if committed else _roll_back(steps)
        for i, tmp in enumerate(temps):
            if i >= len(steps) or not steps[i].replaced:
                _discard(tmp)
        if journal is not None and not note:
            with contextlib.suppress(OSError):
                journal.discard()
        if not note and not committed and len(items) > 1:
            changed = [s for t, s, _ in items if _identity(t) != before[s]]
            if changed:  # only another program (not holding our lock) can have done it
                note = (", ".join(changed) + " changed during the write (by another "
                        "program); scanplan put back what it had replaced")
            else:
                note = "none of " + ", ".join(s for _, s, _ in items) + " was changed"
        if isinstance(exc, OSError) and not isinstance(exc, WriteError) and not committed:
            raise WriteError.from_os_error(current, exc, note=note) from exc
        if not committed:
            raise
    _drop_backups(steps)  # committed: the backups are no longer needed
    if journal is not None:
        with contextlib.suppress(OSError):
            journal.discard()
    return [target for target, _, _ in items]


@dataclass
class _Step:
    """One target of :func:`write_atomic_many` during the renames."""

    target: Path
    shown: str
    backup: Path | None = None
    linked: bool = False  # the backup is a hard link; the target is still in place
    replaced: bool = False
    removed: bool = False  # a stale file moved to ``backup`` (not replaced by a new one)


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


_HIDDEN_EXTRA = len(".") + len(".") + 8 + len(".tmp")  # ".NAME.xxxxxxxx.tmp"


def _hidden_stem(target: Path) -> str:
    """``NAME`` of the hidden names ``.NAME.xxxxxxxx.tmp`` / ``.old`` beside ``target``:
    the target's name, shortened (at a character boundary) so that they fit the folder's
    file-name limit."""
    room = name_max(target.parent) - _HIDDEN_EXTRA
    raw = os.fsencode(target.name)
    if len(raw) <= room:
        return target.name
    return os.fsdecode(raw[:max(room, 1)].decode("utf-8", "ignore").encode("utf-8")) or "r"


def _remove_stale(target: Path) -> None:
    """Delete the temporaries and backups of ``target`` a killed writer left behind.

    Runs under the folder lock, so no other scanplan writer is using them. Only our own
    names are touched: ``.NAME.`` + 8 characters of :func:`tempfile.mkstemp` or
    :func:`secrets.token_hex` + ``.tmp`` / ``.old``, regular files only.
    """
    pattern = re.compile(re.escape(f".{_hidden_stem(target)}.") + r"[a-z0-9_]{8}\.(tmp|old)")
    try:
        names = os.listdir(target.parent)
    except OSError:
        return
    for name in names:
        if pattern.fullmatch(name):
            path = target.parent / name
            with contextlib.suppress(OSError):
                if stat.S_ISREG(os.lstat(path).st_mode):
                    os.unlink(path)


def _write_temp(target: Path, data: bytes) -> Path:
    """Write ``data`` to a new temporary file beside ``target`` (fsync, chmod)."""
    mode = _new_mode(target)
    fd, name = tempfile.mkstemp(dir=target.parent, prefix=f".{_hidden_stem(target)}.",
                                suffix=".tmp")
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


def _backup_name(target: Path) -> Path:
    """A free hidden name ``.NAME.xxxxxxxx.old`` beside ``target``."""
    while True:
        backup = target.with_name(f".{_hidden_stem(target)}.{secrets.token_hex(4)}.old")
        if not os.path.lexists(backup):
            return backup


def _backup(target: Path, backup: Path) -> tuple[Path, bool]:
    """Keep the current ``target`` as ``backup``: (backup, target still in place).

    A hard link leaves ``target`` in place; where links are not possible (FAT, some network
    shares, a file owned by someone else) the file is moved aside instead.
    """
    try:
        if os.link in os.supports_follow_symlinks:
            os.link(target, backup, follow_symlinks=False)
        else:  # pragma: no cover - platform dependent
            os.link(target, backup)
        return backup, True
    except (OSError, NotImplementedError):
        pass
    os.replace(target, backup)
    return backup, False


def _roll_back(steps: list[_Step]) -> str:
    """Put every previous file back, last first; '' or what could not be restored."""
    problems = []
    for step in reversed(steps):
        try:
            if step.removed and not step.replaced:
                continue  # the stale file was never moved
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
