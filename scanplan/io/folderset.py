"""An output folder no reader ever sees half-written: each set of files swapped in at once.

``plan --out DIR`` writes a set of files that belong together (the reports, the missions
of every sortie, the GIS files). Replacing them one rename after the other leaves instants
— and, after a kill, a folder — where a reader (a crew copying the missions, another
scanplan) finds some files of the new plan beside some of the old. Here every set lives in
a folder of its own and **one** atomic rename makes it the one readers see:

.. code-block:: text

    DIR/spec.pdf          -> .scanplan-sets/current/spec.pdf    (a link per file)
    DIR/mission-01.plan   -> .scanplan-sets/current/mission-01.plan
    DIR/.scanplan-sets/current  -> 5f0c9e21a4b7   (the set readers see)
    DIR/.scanplan-sets/previous -> 0d8e13b2c6f4   (the set before, kept until the next write)
    DIR/.scanplan-sets/5f0c9e21a4b7/  spec.pdf  mission-01.plan … .manifest.json

The files keep their names in ``DIR`` (each a relative symbolic link through ``current``);
a user's other files in ``DIR`` are never touched. The write (:func:`write_set`), under the
folder's lock (:func:`scanplan.io.targets.folder_lock`):

1. recovers what a killed writer left (an old journal, unfinished set folders, links to
   names the visible set does not hold);
2. *adopts* the files of an earlier run that are plain files (a folder written before
   sets, a file a user saved over a link): a set folder is made of them (hard links, the
   same bytes), made ``current``, and each plain file is replaced by its link — the same
   bytes at every instant;
3. builds the new set in ``.scanplan-sets/ID.part``: the new files written and fsynced,
   the files of the current set this write keeps linked (hard links), its manifest
   (``.manifest.json``: every file's size and SHA-256) written last; renamed to ``ID``;
4. links every name of the new set in ``DIR`` (a new name's link leads nowhere until
   step 5: a reader finds no such file, as in the old set);
5. **commit**: ``current`` is replaced by a link to ``ID`` (one ``rename``);
6. ``previous`` is pointed at the old set, the links of names the new set no longer holds
   (a stale ``mission-04.plan``) are removed, older set folders deleted.

At every instant, whatever the process does or wherever it is killed, the files a reader
can open in ``DIR`` are exactly the old set or exactly the new one: before step 5 every
name resolves in the old set (a new name resolves to nothing), after it in the new set (a
dropped name resolves to nothing). A reader that copies the folder while it is rewritten
takes a whole set by copying ``DIR/.scanplan-sets/current/`` (resolved once) and can check
the copy against its ``.manifest.json``; the previous set stays until the next write, so a
copy begun before a swap can finish.

Where the file system has no symbolic or hard links (FAT, some network shares, Windows
without the right to make links), :func:`supported` is False and the caller writes the
set with the journal (:func:`scanplan.io.atomic.write_atomic_many`): all old or all new once
recovered, not at every instant.
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import json
import os
import re
import secrets
import shutil
import stat
from collections.abc import Callable, Iterable
from pathlib import Path

from ..errors import WriteError
from .files import fsync_dir, write_all
from .journal import recover as recover_journal
from .targets import SETS, folder_lock, is_managed, link_text

__all__ = ["CURRENT", "MANIFEST", "PREVIOUS", "SETS", "current_set", "read_manifest",
           "recover", "supported", "write_set"]

CURRENT = "current"
"""The link (in :data:`SETS`) to the set readers see."""
PREVIOUS = "previous"
"""The link (in :data:`SETS`) to the set before it, kept until the next write."""
MANIFEST = ".manifest.json"
"""Each set's list of its files (size, SHA-256), written before the set is swapped in."""
_SET = re.compile(r"[0-9a-f]{12}")
_PART = re.compile(r"[0-9a-f]{12}\.part")
_LINK_TMP = re.compile(r"\.(?:current|previous|link)\.[0-9a-f]{8}")
_SUPPORT: dict[int, bool] = {}


def supported(folder: str | os.PathLike[str]) -> bool:
    """Whether ``folder``'s file system has symbolic and hard links (probed once per
    device).

    Returns
    -------
    bool
        False where either is refused (the caller then writes with the journal).
    """
    try:
        dev = os.stat(folder).st_dev
    except OSError:
        return False
    if dev in _SUPPORT:
        return _SUPPORT[dev]
    probe = os.path.join(folder, f".scanplan-probe.{secrets.token_hex(4)}")
    made = []
    try:
        fd = os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        os.close(fd)
        made.append(probe)
        os.link(probe, probe + ".h")
        made.append(probe + ".h")
        os.symlink(os.path.basename(probe), probe + ".s")
        made.append(probe + ".s")
        ok = True
    except (OSError, NotImplementedError, AttributeError):
        ok = False
    finally:
        for path in reversed(made):
            with contextlib.suppress(OSError):
                os.unlink(path)
    _SUPPORT[dev] = ok
    return ok


def _target(sets: Path, name: str) -> Path | None:
    """The set folder the link ``sets/name`` leads to (None: none, or not a set)."""
    try:
        text = os.readlink(sets / name)
    except OSError:
        return None
    folder = sets / text
    return folder if _SET.fullmatch(text) and folder.is_dir() else None


def current_set(folder: str | os.PathLike[str]) -> Path | None:
    """The set folder readers of ``folder`` see (None: no set yet)."""
    return _target(Path(folder) / SETS, CURRENT)


def _members(set_dir: Path | None) -> list[str]:
    """The files of a set (its manifest aside)."""
    if set_dir is None:
        return []
    return sorted(n for n in os.listdir(set_dir) if not n.startswith("."))


def read_manifest(set_dir: str | os.PathLike[str]) -> dict[str, dict[str, object]]:
    """name → {"size": bytes, "sha256": hex} of a set ({} without a manifest)."""
    try:
        with open(Path(set_dir) / MANIFEST, "rb") as fh:
            doc = json.loads(fh.read(16 * 2**20))
        files = doc["files"]
        return files if isinstance(files, dict) else {}
    except (OSError, ValueError, KeyError, TypeError):
        return {}


def _swap(sets: Path, name: str, target: str) -> None:
    """Point ``sets/name`` at ``target`` with one rename (the commit, for ``current``)."""
    tmp = sets / f".{name}.{secrets.token_hex(4)}"
    os.symlink(target, tmp)
    try:
        os.replace(tmp, sets / name)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    fsync_dir(sets)


def _new_set(sets: Path) -> tuple[Path, Path]:
    """A new (empty) unfinished set folder and the name it gets when finished."""
    while True:
        name = secrets.token_hex(6)
        final = sets / name
        part = sets / f"{name}.part"
        if not os.path.lexists(final) and not os.path.lexists(part):
            part.mkdir()
            return part, final


def _link_or_copy(src: Path, dst: Path) -> None:
    """``dst`` the same file as ``src`` (a hard link; a copy where a link is refused)."""
    try:
        os.link(src, dst, follow_symlinks=False)
    except OSError as exc:
        if exc.errno not in (errno.EMLINK, errno.EPERM, errno.EXDEV, errno.EACCES):
            raise
        shutil.copy2(src, dst, follow_symlinks=False)


def _digest(path: Path) -> dict[str, object]:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return {"size": os.path.getsize(path), "sha256": h.hexdigest()}


def _finish_set(part: Path, final: Path, manifest: dict[str, dict[str, object]]) -> Path:
    """Write the set's manifest (last), fsync, and give the set its name."""
    fd = os.open(part / MANIFEST, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
    try:
        write_all(fd, json.dumps({"version": 1, "files": manifest}, indent=1,
                                 sort_keys=True).encode())
        os.fsync(fd)
    finally:
        os.close(fd)
    fsync_dir(part)
    os.replace(part, final)
    fsync_dir(final.parent)
    return final


def _visible(folder: Path, current: Path | None, candidates: Iterable[str]) -> dict[str, Path]:
    """The files of the old set a reader sees: name → the file itself (a plain file at one
    of the set's names, or the current set's file a link of scanplan leads to)."""
    out: dict[str, Path] = {}
    for name in sorted(set(candidates)):
        path = folder / name
        if _is_plain(path):
            out[name] = path
        elif current is not None and is_managed(path) and _is_plain(current / name):
            out[name] = current / name
    return out


def _adopt(folder: Path, sets: Path, current: Path | None, visible: dict[str, Path]
           ) -> Path | None:
    """Bring the plain files among the visible ones under a set, the bytes every reader
    sees unchanged at every instant (the module docstring, step 2); the current set
    after it."""
    plain = sorted(n for n, p in visible.items() if p.parent == folder)
    if not plain:
        return current
    part, final = _new_set(sets)
    try:
        manifest = read_manifest(current) if current is not None else {}
        out = {}
        for name, path in visible.items():
            _link_or_copy(path, part / name)
            out[name] = (manifest.get(name) if path.parent != folder else None) or \
                _digest(part / name)
        adopted = _finish_set(part, final, out)
    except BaseException:
        shutil.rmtree(part, ignore_errors=True)
        raise
    _swap(sets, CURRENT, adopted.name)
    for name in plain:  # the same inode through the link: the same bytes, now a link
        _replace_with_link(folder, name)
    fsync_dir(folder)
    return adopted


def _is_plain(path: Path) -> bool:
    try:
        return stat.S_ISREG(os.lstat(path).st_mode)
    except OSError:
        return False


def _replace_with_link(folder: Path, name: str) -> None:
    tmp = folder / f".link.{secrets.token_hex(4)}"
    os.symlink(link_text(name), tmp)
    try:
        os.replace(tmp, folder / name)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _mode(previous: Path | None) -> int:
    """The mode of the file a new one replaces; else 0666 less the umask."""
    if previous is not None:
        with contextlib.suppress(OSError):
            return os.stat(previous).st_mode & 0o7777
    umask = os.umask(0)
    os.umask(umask)
    return 0o666 & ~umask


def _build(sets: Path, visible: dict[str, Path], items: list[tuple[str, str, bytes]],
           gone: set[str], manifest: dict[str, dict[str, object]],
           say: Callable[[str], None]) -> Path:
    """The new set: the files written, the visible old files this write keeps (hard
    links) — step 3; nothing a reader sees changes."""
    part, final = _new_set(sets)
    try:
        written = {name for name, _, _ in items}
        out: dict[str, dict[str, object]] = {}
        for name, path in visible.items():
            if name not in written and name not in gone:
                _link_or_copy(path, part / name)
                out[name] = manifest.get(name) or _digest(part / name)
        for name, shown, data in items:
            say(shown)
            fd = os.open(part / name, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
            try:
                write_all(fd, data)
                os.fchmod(fd, _mode(visible.get(name)))
                os.fsync(fd)
            finally:
                os.close(fd)
            out[name] = {"size": len(data), "sha256": hashlib.sha256(data).hexdigest()}
        return _finish_set(part, final, out)
    except BaseException:
        shutil.rmtree(part, ignore_errors=True)
        raise


def _link_names(folder: Path, names: Iterable[str]) -> list[str]:
    """A link in ``folder`` for every name that has none (step 4); the names linked."""
    made = []
    for name in names:
        path = folder / name
        if is_managed(path):
            continue
        os.symlink(link_text(name), path)
        made.append(name)
    if made:
        fsync_dir(folder)
    return made


def _dangling(folder: Path, keep: set[str]) -> list[str]:
    """Names of ``folder`` that are scanplan's links to a file the visible set lacks."""
    out = []
    with contextlib.suppress(OSError):
        for name in os.listdir(folder):
            if name not in keep and is_managed(folder / name):
                out.append(name)
    return out


def _tidy(folder: Path, sets: Path) -> None:
    """Remove what no reader needs: links to names the visible set lacks, unfinished
    set folders, sets neither current nor previous, temporary links."""
    current = _target(sets, CURRENT)
    previous = _target(sets, PREVIOUS)
    for name in _dangling(folder, set(_members(current))):
        with contextlib.suppress(FileNotFoundError):
            os.unlink(folder / name)
    keep = {p.name for p in (current, previous) if p is not None}
    with contextlib.suppress(OSError):
        for name in os.listdir(sets):
            path = sets / name
            if _PART.fullmatch(name) or (_SET.fullmatch(name) and name not in keep):
                if path.is_dir() and not path.is_symlink():
                    # the manifest first: a reader still copying this set finds it gone
                    with contextlib.suppress(OSError):
                        os.unlink(path / MANIFEST)
                    shutil.rmtree(path, ignore_errors=True)
            elif _LINK_TMP.fullmatch(name) and path.is_symlink():
                os.unlink(path)
    with contextlib.suppress(OSError):
        for name in os.listdir(folder):
            if _LINK_TMP.fullmatch(name) and (folder / name).is_symlink():
                os.unlink(folder / name)
    fsync_dir(folder)


def recover(folder: str | os.PathLike[str]) -> None:
    """Put right what a killed writer left in ``folder`` (call it under the folder's lock):
    an old journal's transaction, then the sets' leftovers (nothing a reader sees
    changes)."""
    recover_journal([folder])
    sets = Path(folder) / SETS
    if sets.is_dir() and not sets.is_symlink():
        _tidy(Path(folder), sets)


def write_set(folder: str | os.PathLike[str], items: list[tuple[Path, str, bytes]], *,
              check: Callable[[], None] | None = None,
              remove: Callable[[], Iterable[str | os.PathLike[str]]] | None = None
              ) -> list[Path]:
    """Write ``items`` (target in ``folder``, its name as given, bytes) as the new set of
    ``folder`` and drop the files ``remove`` names (the module docstring's steps).

    Parameters
    ----------
    folder : path
        The output folder; every target lies in it. :func:`supported` must be True.
    items : list of (Path, str, bytes)
        The files, in order.
    check : callable, optional
        Re-checks the targets under the lock, before anything is written.
    remove : callable, optional
        Under the lock, after ``check``: the files of an earlier run to drop.

    Returns
    -------
    list of Path
        The targets.

    Raises
    ------
    WriteError
        Naming the file that could not be written and the reason; what readers see is
        unchanged.
    """
    root = Path(folder)
    sets = root / SETS
    with folder_lock([os.fspath(root)]):
        try:
            recover(root)
        except OSError as exc:
            raise WriteError.from_os_error(os.fspath(sets), exc, note="an earlier "
                                           "interrupted write could not be put right") from exc
        if check is not None:
            check()
        names = [t.name for t, _, _ in items]
        gone = {Path(p).name for p in (remove() if remove is not None else ())} - set(names)
        shown = items[0][1] if items else os.fspath(root)

        def say(name: str) -> None:
            nonlocal shown
            shown = name

        linked: list[str] = []
        new: Path | None = None
        try:
            sets.mkdir(exist_ok=True)
            current = current_set(root)
            visible = _visible(root, current, {*names, *gone, *_members(current)})
            manifest = read_manifest(current) if current is not None else {}
            new = _build(sets, visible, [(t.name, s, d) for t, s, d in items], gone,
                         manifest, say)
            shown = os.fspath(root)
            current = _adopt(root, sets, current, visible)
            linked = _link_names(root, _members(new))
            _swap(sets, CURRENT, new.name)  # the commit point
        except BaseException as exc:
            if new is not None and current_set(root) == new:
                raise  # interrupted after the commit point (Ctrl+C): the new set stands
            for name in linked:  # links made for this set's new names lead nowhere: gone
                with contextlib.suppress(OSError):
                    os.unlink(root / name)
            if new is not None:
                shutil.rmtree(new, ignore_errors=True)
            with contextlib.suppress(OSError):
                sets.rmdir()  # a first write that failed: no sets folder left behind
            if isinstance(exc, OSError) and not isinstance(exc, WriteError):
                raise WriteError.from_os_error(shown, exc, note="the folder's files are as "
                                               "they were") from exc
            raise
        if current is not None:
            with contextlib.suppress(OSError):
                _swap(sets, PREVIOUS, current.name)
        with contextlib.suppress(OSError):
            _tidy(root, sets)
    return [t for t, _, _ in items]
