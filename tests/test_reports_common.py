"""Shared report pieces: atomic writing, reproducible dates, labels in both locales."""

from __future__ import annotations

import os

import pytest

from scanplan.i18n.labels import LABELS, t
from scanplan.reports import report_datetime, templates_dir, write_atomic


def test_labels_have_the_same_keys_in_both_locales():
    assert set(LABELS["en"]) == set(LABELS["ru"])
    assert t("approved", "ru") == "УТВЕРЖДАЮ" and t("approved", "en") == "APPROVED"


def test_write_atomic_replaces_and_leaves_no_temporary(tmp_path):
    target = tmp_path / "r.bin"
    write_atomic(target, b"one")
    write_atomic(target, b"two")
    assert target.read_bytes() == b"two"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.bin"]


def test_write_atomic_failure_keeps_the_old_file(tmp_path, monkeypatch):
    target = tmp_path / "r.bin"
    target.write_bytes(b"previous")

    def broken_replace(src, dst):
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", broken_replace)
    with pytest.raises(OSError):
        write_atomic(target, b"new")
    assert target.read_bytes() == b"previous"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.bin"]


def test_source_date_epoch(monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    assert report_datetime().isoformat() == "2023-11-14T22:13:20+00:00"


def test_bundled_font_has_cyrillic():
    fonts = templates_dir() / "fonts"
    assert (fonts / "DejaVuSans.ttf").stat().st_size > 100_000
    assert (fonts / "LICENSE-DejaVu.txt").exists()


def test_write_atomic_file_mode(tmp_path):
    """A new report is readable like any file the user creates (0666 less the umask, not
    mkstemp's 0600); a replaced one keeps its mode."""
    umask = os.umask(0o022)
    try:
        new = write_atomic(tmp_path / "new.pdf", b"x")
        assert new.stat().st_mode & 0o777 == 0o644
        old = tmp_path / "old.pdf"
        old.write_bytes(b"x")
        old.chmod(0o640)
        write_atomic(old, b"y")
        assert old.stat().st_mode & 0o777 == 0o640
    finally:
        os.umask(umask)
