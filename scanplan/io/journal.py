"""The journal of an output transaction: what a killed writer is undone (or finished) from.

:func:`scanplan.io.atomic.write_atomic_many` writes a set of files (the reports, the missions,
the GIS files, the photo table) and removes the stale files of an earlier run as one
transaction. Before it changes anything a user can see, it writes a journal
(``.scanplan-journal.json``, in the first folder of the set, fsynced): for every target,
its temporary file, the hidden name its previous version is kept under (or that it is
new, with the identity of the new file), and for every file the sweep removes, the hidden
name it is moved to. Then:

1. every previous file is kept (a hard link, or moved aside), every temporary renamed
   over its target, every stale file moved aside;
2. the journal's state is set to ``committed`` (an atomic rename: the commit point);
3. the kept previous files are deleted, and the journal.

A process killed at any step (``kill -9``, a power loss) leaves the journal behind. The
next write into that folder, under the same folder lock and before anything else, reads
it (:func:`recover`): a ``prepared`` transaction is rolled back (every previous file put
back, every new file removed), a ``committed`` one finished (the kept files deleted). So
the set is all old or all new once anyone writes there again; every step of recovery can
be repeated, so a recovery that is itself killed is finished by the next one.
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import tempfile
from collections.abc import Iterable
from dataclasses import asdict, dataclass
from pathlib import Path

__all__ = ["JOURNAL_NAME", "Entry", "Journal", "recover"]

JOURNAL_NAME = ".scanplan-journal.json"
"""The journal's file name in the first folder of a transaction."""
_MAX_JOURNAL_BYTES = 4 * 2**20  # a journal of many thousand entries is still far smaller


@dataclass
class Entry:
    """One file of a transaction (absolute paths).

    ``backup`` is where the previous version is kept (None: the target is new);
    ``new_id`` the (device, inode) of the new file (its temporary), so that recovery
    removes a new target only when it is the file this transaction wrote; ``remove``
    marks a stale file the sweep moves to ``backup``.
    """

    target: str
    temp: str | None
    backup: str | None
    new_id: list[int] | None = None
    remove: bool = False


class Journal:
    """The journal file of one transaction (see the module docstring)."""

    def __init__(self, folder: str | os.PathLike[str], entries: list[Entry]) -> None:
        self.path = Path(folder) / JOURNAL_NAME
        self.entries = entries

    def _write(self, state: str) -> None:
        from .files import fsync_dir, write_all

        data = json.dumps({"version": 1, "state": state,
                           "entries": [asdict(e) for e in self.entries]}).encode()
        fd, name = tempfile.mkstemp(dir=self.path.parent, prefix=".scanplan-journal.",
                                    suffix=".part")
        try:
            try:
                write_all(fd, data)
            finally:
                os.close(fd)
            os.replace(name, self.path)
        except BaseException:
            with contextlib.suppress(OSError):
                os.unlink(name)
            raise
        fsync_dir(self.path.parent)

    def prepare(self) -> None:
        """Write the journal (state ``prepared``) before anything visible changes."""
        self._write("prepared")

    def commit(self) -> None:
        """The commit point: the journal's state becomes ``committed``."""
        self._write("committed")

    def discard(self) -> None:
        """Delete the journal (the transaction is finished or undone)."""
        with contextlib.suppress(FileNotFoundError):
            os.unlink(self.path)
        from .files import fsync_dir

        fsync_dir(self.path.parent)


def _file_id(path: str) -> list[int] | None:
    try:
        st = os.lstat(path)
    except OSError:
        return None
    return [st.st_dev, st.st_ino]


def _unlink(path: str | None) -> None:
    if path:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(path)


def _roll_back(entries: list[Entry]) -> None:
    """Undo a transaction killed before its commit point (every step repeatable)."""
    for e in reversed(entries):
        if e.backup is not None:
            if os.path.lexists(e.backup):
                os.replace(e.backup, e.target)  # the previous file back (or still there)
        elif not e.remove and e.new_id is not None and _file_id(e.target) == e.new_id:
            os.unlink(e.target)  # this transaction's new file, where there was none
        _unlink(e.temp)


def _finish(entries: list[Entry]) -> None:
    """Finish a transaction killed after its commit point: drop what was kept."""
    for e in entries:
        _unlink(e.backup)
        _unlink(e.temp)


_PARTIAL = re.compile(r"\.scanplan-journal\.[a-z0-9_]{8}\.part")


def _remove_partial(folder: str | os.PathLike[str]) -> None:
    """Delete a journal a killed writer had not finished writing (never renamed: nothing
    of its transaction was changed)."""
    try:
        names = os.listdir(folder)
    except OSError:
        return
    for name in names:
        if _PARTIAL.fullmatch(name):
            with contextlib.suppress(OSError):
                os.unlink(os.path.join(folder, name))


def recover(folders: Iterable[str | os.PathLike[str]]) -> list[str]:
    """Roll back or finish the transactions a killed writer left in ``folders``.

    Call it holding the folders' lock (:func:`scanplan.io.targets.folder_lock`), before
    anything else is written there.

    Parameters
    ----------
    folders : iterable of path
        The folders about to be written.

    Returns
    -------
    list of str
        ``"rolled back"`` or ``"finished"`` per journal found (for tests and messages).

    Raises
    ------
    OSError
        A previous file could not be put back (the journal is kept for the next run).
    """
    done = []
    for folder in folders:
        _remove_partial(folder)
        path = Path(folder) / JOURNAL_NAME
        try:
            with open(path, "rb") as fh:
                raw = fh.read(_MAX_JOURNAL_BYTES + 1)
        except FileNotFoundError:
            continue
        except OSError:
            continue
        try:
            doc = json.loads(raw)
            entries = [Entry(**e) for e in doc["entries"]]
            state = doc["state"]
        except (ValueError, KeyError, TypeError):
            os.replace(path, path.with_name(JOURNAL_NAME + ".damaged"))  # keep, never guess
            continue
        if state == "committed":
            _finish(entries)
            done.append("finished")
        else:
            _roll_back(entries)
            done.append("rolled back")
        journal = Journal(folder, entries)
        journal.discard()
    return done
