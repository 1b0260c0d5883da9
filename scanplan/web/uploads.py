"""The uploaded files of a page session: bounded, private, removed.

An upload is streamed to a private temporary folder under a name the server makes from the
client's (letters, digits, ``._-``; the suffix kept, which is what the readers go by) and
refused past :data:`MAX_UPLOAD_BYTES`; the store keeps at most :data:`MAX_FILES` files and
:data:`MAX_STORE_BYTES` in all (the oldest go first) and removes everything when the
server stops. Nothing of a client's path is ever opened: a project names an upload by the
id the store gave it (:meth:`UploadStore.path`). The files are read later by the same
readers, with the same guards, as the command line's (:mod:`scanplan.geo.area`,
:mod:`scanplan.geo.dem`).
"""

from __future__ import annotations

import os
import re
import secrets
import shutil
import tempfile
import threading
from collections import OrderedDict
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError
from ..io.files import size_text

__all__ = ["MAX_FILES", "MAX_STORE_BYTES", "MAX_UPLOAD_BYTES", "Upload", "UploadStore",
           "safe_name"]

MAX_UPLOAD_BYTES = 256 * 1024 * 1024
"""Largest uploaded file [bytes] (a DEM; the area readers refuse a file over 64 MB)."""
MAX_STORE_BYTES = 1024 * 1024 * 1024
"""Most bytes the store keeps; the oldest uploads are removed first."""
MAX_FILES = 64
"""Most uploads the store keeps."""
_UNSAFE = re.compile(r"[^A-Za-z0-9._-]+")
_ID = re.compile(r"^[0-9a-f]{16}$")


def safe_name(client_name: str | None) -> str:
    """A file name made from the client's: its last component, letters, digits and
    ``._-`` only, no leading dot, at most 100 characters.

    >>> safe_name("C:\\\\Users\\\\me\\\\Town area.KML"), safe_name("../../etc/passwd")
    ('Town_area.KML', 'passwd')
    >>> safe_name(".."), safe_name("карта.tif")
    ('upload', 'upload.tif')
    """
    base = re.split(r"[\\/]", client_name or "")[-1]
    stem, dot, suffix = base.rpartition(".")
    if not dot:
        stem, suffix = base, ""
    stem = _UNSAFE.sub("_", stem).strip("._") or "upload"
    suffix = _UNSAFE.sub("", suffix)[:12]
    return (stem[:80] + (f".{suffix}" if suffix else ""))[:100]


@dataclass(frozen=True)
class Upload:
    """One stored upload: its ``id``, the ``name`` it is stored under, its size [bytes]."""

    id: str
    name: str
    size: int


class _Writer:
    """One upload being written (:meth:`UploadStore.open`)."""

    def __init__(self, store: UploadStore, item: Upload, folder: Path) -> None:
        self.store, self.item, self.folder = store, item, folder
        self.size = 0
        self._out = open(folder / item.name, "xb")

    def write(self, chunk: bytes) -> None:
        """Append ``chunk``; past the store's bound the upload is refused (InputError)."""
        self.size += len(chunk)
        if self.size > self.store.max_upload_bytes:
            raise InputError("file", f"{self.item.name} is larger than "
                             f"{size_text(self.store.max_upload_bytes)}, the largest upload")
        self._out.write(chunk)

    def done(self) -> Upload:
        """Keep the upload; its record."""
        self._out.close()
        if self.size == 0:
            raise InputError("file", f"{self.item.name} is empty")
        item = Upload(self.item.id, self.item.name, self.size)
        self.store._keep(item)
        return item

    def abort(self) -> None:
        """Remove what was written."""
        self._out.close()
        shutil.rmtree(self.folder, ignore_errors=True)


class UploadStore:
    """Uploaded files in a private temporary folder (see the module docstring)."""

    def __init__(self, *, max_upload_bytes: int = MAX_UPLOAD_BYTES,
                 max_store_bytes: int = MAX_STORE_BYTES, max_files: int = MAX_FILES) -> None:
        from ..io.rundir import run_dir

        # in the run's folder: removed with it, or swept when a killed server left it
        self.root = Path(tempfile.mkdtemp(prefix="scanplan-serve-", dir=run_dir()))
        self.max_upload_bytes = max_upload_bytes
        self.max_store_bytes = max_store_bytes
        self.max_files = max_files
        self._items: OrderedDict[str, Upload] = OrderedDict()
        self._lock = threading.Lock()

    def open(self, client_name: str | None) -> _Writer:
        """A writer that stores an upload under a name made from ``client_name``: call
        ``write`` per chunk, then ``done`` (or ``abort``)."""
        upload_id = secrets.token_hex(8)
        folder = self.root / upload_id
        folder.mkdir(mode=0o700)
        return _Writer(self, Upload(upload_id, safe_name(client_name), 0), folder)

    def add(self, client_name: str | None, chunks: Iterable[bytes]) -> Upload:
        """Store the bytes of ``chunks`` (see :meth:`open`).

        Raises
        ------
        InputError
            ``file`` when it passes :attr:`max_upload_bytes` (nothing is kept) or is empty.
        """
        writer = self.open(client_name)
        try:
            for chunk in chunks:
                writer.write(chunk)
            return writer.done()
        except BaseException:
            writer.abort()
            raise

    def _keep(self, item: Upload) -> None:
        with self._lock:
            self._items[item.id] = item
            self._evict()

    def _evict(self) -> None:
        """Remove the oldest uploads past the store's bounds (the newest always stays)."""
        while len(self._items) > 1 and (
                len(self._items) > self.max_files
                or sum(u.size for u in self._items.values()) > self.max_store_bytes):
            old, _ = self._items.popitem(last=False)
            shutil.rmtree(self.root / old, ignore_errors=True)

    def path(self, upload_id: str, field: str = "files") -> Path:
        """The stored file of ``upload_id``.

        Raises
        ------
        InputError
            ``field`` when no such upload is kept (never uploaded, or removed as old).
        """
        with self._lock:
            item = self._items.get(upload_id) if isinstance(upload_id, str) and \
                _ID.match(upload_id) else None
        if item is None:
            raise InputError(field, "names no uploaded file (upload it again: the page keeps "
                             f"the last {self.max_files} uploads)")
        return self.root / item.id / item.name

    def close(self) -> None:
        """Remove every upload and the store's folder."""
        with self._lock:
            self._items.clear()
        shutil.rmtree(self.root, ignore_errors=True)

    def __len__(self) -> int:
        return len(self._items)

    def __contains__(self, upload_id: object) -> bool:
        return upload_id in self._items

    def __del__(self) -> None:  # pragma: no cover - a store not closed still cleans up
        if os.path.isdir(getattr(self, "root", "")):
            shutil.rmtree(self.root, ignore_errors=True)
