"""The norm directory's lock through filelock (Windows and macOS too), and the user data
folder through platformdirs."""

from __future__ import annotations

import multiprocessing as mp
import time
from pathlib import Path

import platformdirs

from scanplan.io.files import dir_lock, lock_file_for
from scanplan.norms.paths import user_norms_dir


def _hold(folder: str, exclusive: bool, seconds: float, started: mp.Event) -> None:
    with dir_lock(folder, exclusive=exclusive):
        started.set()
        time.sleep(seconds)


def test_a_writer_keeps_readers_out_and_readers_share(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    folder = tmp_path / "norms"
    folder.mkdir()
    ctx = mp.get_context("fork")
    started = ctx.Event()
    writer = ctx.Process(target=_hold, args=(str(folder), True, 1.0, started))
    writer.start()
    assert started.wait(30)
    t0 = time.monotonic()
    with dir_lock(folder, exclusive=False):
        waited = time.monotonic() - t0
    writer.join(30)
    assert writer.exitcode == 0
    assert waited > 0.5  # the reader waited for the writer to finish
    started = ctx.Event()
    reader = ctx.Process(target=_hold, args=(str(folder), False, 1.0, started))
    reader.start()
    assert started.wait(30)
    t0 = time.monotonic()
    with dir_lock(folder, exclusive=False):  # two readers at once
        shared = time.monotonic() - t0
    reader.join(30)
    assert shared < 0.5
    # the lock file lives in the cache folder, never in the locked folder
    lock = lock_file_for(folder)
    assert lock.is_relative_to(tmp_path / "cache") and lock.exists()
    assert list(folder.iterdir()) == []


def test_no_lock_file_possible_is_no_lock(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    monkeypatch.setenv("XDG_CACHE_HOME", str(blocker))  # a file where a folder must be
    with dir_lock(tmp_path, exclusive=True):
        (tmp_path / "inside").write_text("ok")
    assert (tmp_path / "inside").read_text() == "ok"


def test_user_norm_folder_is_the_platforms(tmp_path, monkeypatch):
    monkeypatch.delenv("SCANPLAN_NORMS_DIR", raising=False)
    monkeypatch.setenv("XDG_DATA_HOME", str(tmp_path / "data"))
    assert user_norms_dir() == platformdirs.user_data_path("scanplan", appauthor=False) / \
        "norms"
    assert user_norms_dir() == tmp_path / "data" / "scanplan" / "norms"  # as before on Linux
    monkeypatch.setenv("SCANPLAN_NORMS_DIR", str(tmp_path / "mine"))
    assert user_norms_dir() == Path(tmp_path / "mine")
