"""The page comparison script (tools/compare_pages.py): two PDFs compared as pictures, page
by page — the same pages from other bytes pass, a moved line or another page count does not,
and a pixel that differs in one colour channel only is counted."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from helpers import script_module
from PIL import Image

TOOLS = Path(__file__).resolve().parents[1] / "tools"

pytestmark = pytest.mark.skipif(shutil.which("pdftoppm") is None,
                                reason="pdftoppm (poppler) is not installed")


@pytest.fixture(scope="module")
def pages():
    with script_module(TOOLS, "compare_pages") as module:
        yield module


def _pdf(path: Path, body: str, title: str = "t") -> Path:
    """A small A6 PDF of ``body`` (WeasyPrint, the bundled font)."""
    from scanplan.reports.pdfrender import html_to_pdf

    html = ("<!DOCTYPE html><html><head><meta charset='utf-8'>"
            f"<title>{title}</title><style>@page {{ size: A6; margin: 10mm }}"
            "@font-face { font-family: S; src: url('fonts/DejaVuSans.ttf') }"
            "html { font-family: S; font-size: 9pt } table { border-collapse: collapse }"
            "td { border: 0.4pt solid #999; padding: 1mm }</style></head>"
            f"<body>{body}</body></html>")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(html_to_pdf(html, fresh_fonts=True))
    return path


TABLE = "<table><tr><td>GSD</td><td>0,027 м</td></tr><tr><td>H</td><td>120 m</td></tr></table>"


def test_the_same_pages_from_other_bytes_are_the_same(pages, tmp_path, capsys):
    a = _pdf(tmp_path / "a" / "r.pdf", TABLE, title="one")
    b = _pdf(tmp_path / "b" / "r.pdf", TABLE, title="another")  # metadata only
    assert a.read_bytes() != b.read_bytes()
    assert pages.main([str(tmp_path / "a"), str(tmp_path / "b")]) == 0
    out = capsys.readouterr().out
    assert "1 PDFs, 1 pages compared at 100 dpi: 0 pages differ" in out


def test_a_changed_cell_and_another_page_count_are_differences(pages, tmp_path, capsys):
    _pdf(tmp_path / "a" / "r.pdf", TABLE)
    _pdf(tmp_path / "a" / "s.pdf", TABLE)
    _pdf(tmp_path / "b" / "r.pdf", TABLE.replace("120 m", "121 m"))
    _pdf(tmp_path / "b" / "s.pdf", TABLE + "<p style='break-before: page'>2</p>")
    diffs = tmp_path / "diffs"
    assert pages.main([str(tmp_path / "a"), str(tmp_path / "b"), "--diffs", str(diffs)]) == 1
    out = capsys.readouterr().out
    changed = [line for line in out.splitlines() if line.startswith("r.pdf page 1:")]
    assert len(changed) == 1 and "max difference" in changed[0]
    assert 0 < int(changed[0].split(": ")[1].split()[0]) < 200  # a few glyphs' pixels
    assert "s.pdf: 1 pages before, 2 after" in out
    assert "2 PDFs, 2 pages compared at 100 dpi: 1 pages differ, 1 files not comparable" in out
    assert sorted(p.name for p in diffs.iterdir()) == [
        "r-p1-after.png", "r-p1-before.png", "r-p1-diff.png"]


def test_an_output_sets_own_folder_is_read_through_its_links(pages, tmp_path, capsys):
    for side, name in (("a", "1111"), ("b", "2222")):  # the set folder: another name per run
        pdf = _pdf(tmp_path / side / "files" / ".scanplan-sets" / name / "spec.pdf", TABLE)
        link = tmp_path / side / "files" / "spec.pdf"
        link.symlink_to(pdf.relative_to(link.parent))
    assert pages.main([str(tmp_path / "a"), str(tmp_path / "b")]) == 0
    assert "1 PDFs, 1 pages compared at 100 dpi: 0 pages differ" in capsys.readouterr().out


def test_a_missing_pdf_is_a_difference(pages, tmp_path, capsys):
    _pdf(tmp_path / "a" / "r.pdf", TABLE)
    (tmp_path / "b").mkdir()
    assert pages.main([str(tmp_path / "a"), str(tmp_path / "b")]) == 1
    assert "r.pdf: missing after" in capsys.readouterr().out


def test_every_differing_pixel_is_counted_in_any_channel(pages, tmp_path):
    a = Image.new("RGB", (20, 10), (255, 255, 255))
    b = a.copy()
    b.putpixel((1, 1), (255, 255, 254))  # blue only, by 1: grey would round it away
    b.putpixel((5, 5), (0, 255, 255))  # red, by 255
    b.putpixel((19, 9), (250, 250, 250))
    a.save(tmp_path / "a.png")
    b.save(tmp_path / "b.png")
    d = pages.compare_images(tmp_path / "a.png", tmp_path / "b.png", 3)
    assert (d.page, d.pixels, d.max_diff) == (3, 3, 255)
    assert pages.compare_images(tmp_path / "a.png", tmp_path / "a.png", 1).pixels == 0
    Image.new("RGB", (20, 11), (255, 255, 255)).save(tmp_path / "c.png")
    assert pages.compare_images(tmp_path / "a.png", tmp_path / "c.png", 1).pixels == -1
