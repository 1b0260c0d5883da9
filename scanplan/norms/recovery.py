"""Finishing or undoing a norm import a crash interrupted, and the norm directory lock."""

from __future__ import annotations

import contextlib
import os
import re
import shutil
from pathlib import Path

from ..errors import WriteError
from ..io.files import dir_lock
from .paths import CATALOGUE, user_norms_dir

# An import's own folders beside the set: ".NAME.tmp-XXXXXXXX" (the new set being written)
# and ".NAME.old-XXXXXXXX" (the set it replaces, between the two renames).
_LEFTOVER = re.compile(r"\.(?P<name>.+)\.(?P<kind>tmp|old)-[A-Za-z0-9_]{8}")


def norm_dir_lock(folder: Path) -> contextlib.AbstractContextManager[None]:
    """Serialise imports and repairs in one norm directory, and keep loads out while a set
    is swapped (an exclusive ``flock``; loads take it shared; no-op without ``flock``)."""
    return dir_lock(folder, exclusive=True)


def recover_norm_dir(
    root: str | os.PathLike[str] | None = None, name: str | None = None
) -> list[str]:
    """Finish or undo the imports a crash (power loss, ``kill -9``) interrupted.

    :func:`write_norm_set` replaces a set by renaming it to ``.NAME.old-*``, renaming the
    new one (``.NAME.tmp-*``) in, and deleting the old one. After a crash between the two
    renames the set is missing and its previous content sits in ``.NAME.old-*``: it is put
    back. A ``.NAME.old-*`` beside an existing ``NAME`` (the crash came after the swap) and
    every ``.NAME.tmp-*`` (an unfinished new set) are deleted. Runs at the start of every
    import, of ``scanplan norms list``, and when a set name is not found.

    Parameters
    ----------
    root : path, optional
        Norm directory (default :func:`scanplan.norms.user_norms_dir`).
    name : str, optional
        Only this set's leftovers.

    Returns
    -------
    list of str
        What was done, one line each (empty when nothing was left over).

    Raises
    ------
    WriteError
        A previous set could not be put back (it stays where it is; nothing is deleted).
    """
    root_dir = Path(root) if root is not None else user_norms_dir()
    if not root_dir.is_dir():
        return []
    with norm_dir_lock(root_dir):
        return recover_locked(root_dir, name)


def recover_locked(root_dir: Path, only: str | None = None) -> list[str]:
    """:func:`recover_norm_dir` with the norm folder's lock already held by the caller
    (what was done, one line each; ``only``: this set's leftovers only)."""
    found: dict[str, dict[str, list[Path]]] = {}
    for p in sorted(root_dir.iterdir()):
        m = _LEFTOVER.fullmatch(p.name)
        if m and (only is None or m["name"] == only) and p.is_dir() and not p.is_symlink():
            found.setdefault(m["name"], {"tmp": [], "old": []})[m["kind"]].append(p)
    done = []
    for name, kinds in found.items():
        target = root_dir / name
        olds = kinds["old"]
        # a set's backup has its set.toml; the user camera catalogue's is the folder
        backups = [p for p in olds if (p / "set.toml").is_file() or name == CATALOGUE]
        if backups and not os.path.lexists(target):
            keep = max(backups, key=lambda p: (p / "set.toml" if name != CATALOGUE
                                               else p).stat().st_mtime)
            try:
                os.replace(keep, target)
            except OSError as exc:
                raise WriteError.from_os_error(
                    str(target), exc, action=f"put back norm set {name!r} from {keep.name} to"
                ) from exc
            olds = [p for p in olds if p != keep]
            what = "the user camera catalogue" if name == CATALOGUE else f"norm set {name!r}"
            done.append(f"put back {what} (an interrupted import had moved it to "
                        f"{keep.name})")
        for p in olds + kinds["tmp"]:
            shutil.rmtree(p, ignore_errors=True)
            done.append(f"deleted {p.name} (left by an interrupted import)")
    return done

