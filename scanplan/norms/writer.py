"""Writing a checked norm set as a user norm set: safe names, a temporary folder
and a rename under the norm directory lock (:func:`write_norm_set`, :func:`import_norm_file`)."""

from __future__ import annotations

import csv
import datetime as _dt
import io
import json
import os
import re
import secrets
import shutil
import tempfile
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

from ..errors import InputError, WriteError
from ..io.files import fsync_dir, write_all
from . import store as _norms
from .citations import modern_citation
from .importer import ParsedNormSet, read_norm_file
from .limits import META_KEYS
from .recovery import norm_dir_lock, recover_locked
from .schema import TABLES, TableSpec

# =========================================================================================
# Writing a set
# =========================================================================================

_SAFE_NAME = re.compile(r"[\w][\w.\-]{0,63}")
_RESERVED = frozenset(
    ("con", "prn", "aux", "nul", *(f"com{i}" for i in range(10)), *(f"lpt{i}" for i in range(10)))
)


def check_set_name(name: str) -> str:
    """Return ``name`` if it is a safe, free-to-use norm-set folder name.

    Parameters
    ----------
    name : str
        Letters, digits, ``_``, ``-``, ``.``; starts with a letter, digit or ``_``; at most
        64 characters; not ``..``; not a bundled set's name or ``catalogue``.

    Raises
    ------
    InputError
        Field ``--name``.
    """
    if (
        not isinstance(name, str)
        or not _SAFE_NAME.fullmatch(name)
        or ".." in name
        or name.split(".")[0].casefold() in _RESERVED
        or name.endswith(".")
    ):
        raise InputError(
            "--name",
            f"{name!r} is not a safe set name: use letters, digits, "
            "'_', '-' and '.', start with a letter or digit, at most 64 "
            "characters (e.g. my-enterprise-2024)",
        )
    bundled = _norms.bundled_norms_dir()
    taken = {p.name.casefold() for p in bundled.iterdir() if p.is_dir()} | {_norms.CATALOGUE}
    if name.casefold() in taken:
        raise InputError(
            "--name",
            f"{name!r} is a bundled norm set; choose another name "
            "(a user set must not shadow a bundled one)",
        )
    return name


def _now_iso() -> str:
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    if epoch:
        try:
            when = _dt.datetime.fromtimestamp(int(epoch), _dt.UTC)
        except (ValueError, OverflowError):
            raise InputError("SOURCE_DATE_EPOCH", f"must be an integer (got {epoch!r})") from None
    else:
        when = _dt.datetime.now(_dt.UTC)
    return when.replace(microsecond=0).isoformat().replace("+00:00", "Z")


def _toml_str(s: str) -> str:
    return json.dumps(s, ensure_ascii=False)  # a JSON string is a TOML basic string


def _write_file(path: Path, text: str) -> None:
    """Create ``path`` (it must not exist) with ``text`` as UTF-8, fsynced."""
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0), 0o666)
    try:
        write_all(fd, text.encode("utf-8"))
    finally:
        os.close(fd)





def _csv_text(spec: TableSpec, rows: Sequence[Mapping[str, str]]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow([c.name for c in spec.columns])
    for r in rows:
        w.writerow([modern_citation(r.get(c.name, "")) for c in spec.columns])
    return buf.getvalue()


def write_norm_set(
    parsed: ParsedNormSet,
    name: str,
    *,
    force: bool = False,
    root: str | os.PathLike[str] | None = None,
    title: str | None = None,
) -> Path:
    """Write a checked set as a user norm set, atomically.

    The set is written to a temporary folder next to the target (same file system),
    loaded back with the regular loader, and renamed into place. With ``force`` an
    existing set is moved aside, the new one renamed in, and the old one deleted (restored
    if the rename fails). Any failure — including ``KeyboardInterrupt`` — leaves the norm
    directory as it was; what a crash leaves behind is put right by
    :func:`recover_norm_dir`, which runs first (under a lock on the directory).

    Parameters
    ----------
    parsed : ParsedNormSet
        From :func:`read_norm_file`.
    name : str
        Set name (see :func:`check_set_name`).
    force : bool
        Replace an existing user set of that name.
    root : path, optional
        Norm directory (default :func:`scanplan.norms.user_norms_dir`).
    title : str, optional
        Overrides the title.

    Returns
    -------
    Path
        The set's folder.

    Raises
    ------
    InputError
        ``--name``: unsafe, or taken and no ``force``.
    WriteError
        The set could not be written (disk full, permission, interrupted rename); the
        message names the set's folder and the reason.
    """
    check_set_name(name)
    root_dir = Path(root) if root is not None else _norms.user_norms_dir()
    target = root_dir / name
    if target.exists() and not force:
        raise _set_exists(name, target)
    files = _set_files(parsed, name, title)
    created = _missing_parents(root_dir)  # the norm directory and parents this creates
    try:
        try:
            root_dir.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise WriteError.from_os_error(str(root_dir), exc, action="create folder") from exc
        with norm_dir_lock(root_dir):
            try:
                recover_locked(root_dir, name)
                if target.exists() and not force:  # a set the recovery put back
                    raise _set_exists(name, target)
                swap_in(root_dir, name, files)
            except OSError as exc:
                if isinstance(exc, WriteError):
                    raise
                raise WriteError.from_os_error(
                    str(target), exc, action=f"write norm set {name!r} to"
                ) from exc
    except BaseException:
        for folder in created:  # deepest first; only while still empty
            try:
                folder.rmdir()
            except OSError:
                break
        raise
    return target


def _set_exists(name: str, target: Path) -> InputError:
    return InputError(
        "--name", f"norm set {name!r} already exists ({target}); give --force to replace it"
    )


def _set_files(parsed: ParsedNormSet, name: str, title: str | None) -> dict[str, str]:
    """The set's files: one CSV per table and ``set.toml`` (title, source, provenance)."""
    meta = dict(parsed.meta)
    default_title = (
        f"{name}: imported from {parsed.source_file}"
        if not parsed.base
        else f"{meta.get('title') or parsed.base} with "
        f"{', '.join(parsed.from_file)} from {parsed.source_file}"
    )
    if title is not None:
        meta["title"] = title
    elif not meta.get("title"):
        meta["title"] = default_title
    toml = ["[set]", f"name = {_toml_str(name)}"]
    toml += [f"{k} = {_toml_str(modern_citation(meta.get(k, '')))}" for k in META_KEYS]
    toml += [
        f"imported_from = {_toml_str(parsed.source_file)}",
        f"imported_at = {_toml_str(_now_iso())}",
    ]
    if parsed.base:
        toml.append(f"base = {_toml_str(parsed.base)}")
    files = {TABLES[t].file: _csv_text(TABLES[t], rows) for t, rows in parsed.tables.items()}
    files["set.toml"] = "\n".join(toml) + "\n"
    return files


def _missing_parents(folder: Path) -> list[Path]:
    """``folder`` and its parents that do not exist yet, deepest first."""
    created = []
    probe = folder.absolute()
    while not os.path.lexists(probe) and probe != probe.parent:
        created.append(probe)
        probe = probe.parent
    return created


def swap_in(root_dir: Path, name: str, files: Mapping[str, str],
             verify: Callable[[Path], object] | None = None) -> None:
    """Write ``files`` as set ``name``: temporary folder, verify, rename (swap) into place.

    ``verify`` checks the written folder (default: the norm-set loader); the user camera
    catalogue is swapped in the same way with its own check."""
    target = root_dir / name
    tmp = Path(tempfile.mkdtemp(prefix=f".{name}.tmp-", dir=root_dir))
    old: Path | None = None
    try:
        mask = os.umask(0o022)
        os.umask(mask)
        os.chmod(tmp, 0o777 & ~mask)  # mkdtemp makes 0700; a set folder is an ordinary one
        for fname, text in files.items():
            _write_file(tmp / fname, text)
        # the loader must accept it
        (verify or _norms.read_norm_set_folder)(tmp.resolve())
        if not os.path.lexists(target):
            os.replace(tmp, target)
            fsync_dir(root_dir)  # the rename survives a power loss
            return
        old = root_dir / f".{name}.old-{secrets.token_hex(4)}"
        os.replace(target, old)
        try:
            os.replace(tmp, target)
        except BaseException as exc:
            try:
                os.replace(old, target)
            except OSError as undo:
                note = (
                    f"the previous set could not be put back ({undo.strerror or undo}); it is "
                    f"kept in {old}, and listing, importing or loading the set puts it back"
                )
                if isinstance(exc, OSError):
                    raise WriteError.from_os_error(
                        str(target), exc, action=f"write norm set {name!r} to", note=note
                    ) from exc
                raise
            old = None
            raise
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    fsync_dir(root_dir)
    shutil.rmtree(old, ignore_errors=True)


def import_norm_file(
    path: str | os.PathLike[str],
    name: str,
    *,
    force: bool = False,
    table: str | None = None,
    base: str | None = None,
    root: str | os.PathLike[str] | None = None,
    title: str | None = None,
) -> tuple[Path, ParsedNormSet]:
    """Read, check and write a norm file as user set ``name`` (nothing written on failure).

    Parameters are those of :func:`read_norm_file` and :func:`write_norm_set`.

    Returns
    -------
    (Path, ParsedNormSet)
        The set's folder and what was imported.
    """
    check_set_name(name)
    root_dir = Path(root) if root is not None else _norms.user_norms_dir()
    if (root_dir / name).exists() and not force:
        raise InputError(
            "--name",
            f"norm set {name!r} already exists ({root_dir / name}); give --force to replace it",
        )
    parsed = read_norm_file(path, table=table, base=base)
    return write_norm_set(parsed, name, force=force, root=root_dir, title=title), parsed


