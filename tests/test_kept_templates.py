"""The report's templates are kept compiled between processes, and never at a cost.

A fresh ``scanplan plan`` used to compile every template of the report before it could
hand the HTML to the renderer (about 0.1 s on the critical path of a cold plan). The
compiled templates are kept in the user's cache folder; these tests check that the HTML
from kept templates is the HTML compiled afresh, and that a cache folder that cannot be
written or a damaged file changes nothing but the time.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))

from documents import jobs, planned

from scanplan.reports import pdfhtml

EXAMPLE = Path(__file__).parents[1] / "examples" / "uav-canon-2000.toml"


@pytest.fixture()
def fresh(monkeypatch, tmp_path):
    """An environment made anew for each render, its cache folder under ``tmp_path``."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")  # the document's time fixed

    def render() -> str:
        pdfhtml._environment.cache_clear()
        return pdfhtml.render_html(**jobs(planned(str(EXAMPLE), "ru")))

    yield render
    pdfhtml._environment.cache_clear()


def _kept(tmp_path: Path) -> list[Path]:
    return sorted((tmp_path / "cache").rglob("*.cache"))


def test_kept_templates_give_the_html_compiled_afresh(fresh, tmp_path, monkeypatch):
    first = fresh()
    kept = _kept(tmp_path)
    assert kept, "the compiled templates are kept"
    compiled: list[str] = []
    real = pdfhtml.jinja2.Environment.compile
    monkeypatch.setattr(pdfhtml.jinja2.Environment, "compile",
                        lambda self, *a, **k: compiled.append(a[1] if len(a) > 1 else "")
                        or real(self, *a, **k))
    assert fresh() == first and compiled == []  # read back, nothing compiled


def test_a_damaged_kept_template_is_compiled_again(fresh, tmp_path):
    first = fresh()
    for f in _kept(tmp_path):
        f.write_bytes(b"j2\x00 not a template")
    assert fresh() == first


def test_no_cache_folder_is_no_error(fresh, tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    first = fresh()
    monkeypatch.setenv("XDG_CACHE_HOME", str(blocker))  # a file where the folder must be
    assert fresh() == first
