"""Issue 11, item 4: the flight over the area in the reports — the PDF's map page and
strips table, the workbook's Strips and Photos sheets — in English and Russian.

The layout is hand-made (tests/layouts.py) and given to a real project's specification.
"""

from __future__ import annotations

import dataclasses
import io
import re
from pathlib import Path

import pytest
from layouts import make_layout
from openpyxl import load_workbook

import scanplan.reports.exports as exports_mod
from scanplan.project.file import load_project
from scanplan.project.spec import plan_project
from scanplan.reports.excel import render_xlsx
from scanplan.reports.geosheets import MAX_SHEET_PHOTOS
from scanplan.reports.mapview import crs_text, map_svg

pypdf = pytest.importorskip("pypdf")
pytest.importorskip("weasyprint")

from scanplan.reports.pdf import render_pdf  # noqa: E402

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "uav-canon-2000.toml"
_LATIN_WORD = re.compile(r"[A-Za-z][A-Za-z'’-]*[A-Za-z]")


def _named(layout, name="WGS 84 / UTM zone 35N"):
    return dataclasses.replace(layout, area=dataclasses.replace(layout.area,
                                                                plan_crs_name=name))


@pytest.fixture()
def spec_with(monkeypatch):
    def make(layout, locale="en"):
        monkeypatch.setattr(exports_mod, "spec_layouts", lambda spec: [("uav", layout)])
        res = plan_project(load_project(EXAMPLE))
        return dataclasses.replace(res, meta=dataclasses.replace(res.meta, locale=locale))
    return make


def _pdf_pages(spec):
    data = render_pdf(uav=spec.uav.job, meta=spec.meta, spec=spec)
    return [p.extract_text() for p in pypdf.PdfReader(io.BytesIO(data)).pages]


def test_crs_named_in_both_languages():
    lay = make_layout()
    assert crs_text(_named(lay), "en") == "EPSG:32635 — WGS 84 / UTM zone 35N"
    assert crs_text(_named(lay), "ru") == "EPSG:32635 — WGS 84 / UTM зона 35\u00a0с.\u00a0ш."
    gk = _named(lay, "Pulkovo 1942 / Gauss-Kruger zone 5")
    assert crs_text(gk, "ru") == "EPSG:32635 — Пулково 1942 / Гаусса — Крюгера зона 5"
    assert crs_text(_named(lay, "NAD83 / Texas Central"), "ru") == "EPSG:32635"
    assert "not georeferenced" in crs_text(make_layout(georeferenced=False), "en")


def test_map_svg_is_deterministic_and_has_north_arrow_and_scale_bar():
    lay = _named(make_layout(notch=True))
    svg = map_svg(lay, "en")
    assert svg == map_svg(lay, "en")
    assert ">N<" in svg or "N</text>" in svg or "> N" in svg or "N" in re.findall(
        r">([^<]{1,3})</text>", svg)
    assert "200 m" in svg  # a 1-2-5 scale bar, ~1/4 of the 0.8 km wide map
    ru = map_svg(lay, "ru")
    assert "200 м" in ru and "С" in re.findall(r">([^<]{1,3})</text>", ru)


@pytest.mark.parametrize("locale", ["en", "ru"])
def test_pdf_has_the_map_page_and_strips_table(spec_with, locale):
    lay = _named(make_layout(notch=True, sorties=2))
    spec = spec_with(lay, locale)
    pages = _pdf_pages(spec)
    title = {"en": "Flight map", "ru": "Схема маршрутов"}[locale]
    where = [i for i, p in enumerate(pages) if title in p]
    assert len(where) == 1
    text = "\n".join(pages[where[0]:])
    text = text[text.index(title):]  # the map section flows on from the one before it
    assert "EPSG:32635" in text
    strips = {"en": "Strips", "ru": "Маршруты"}[locale]
    assert strips in text
    assert re.search(r"53[.,]88\d+; 25[.,]30\d+", text)  # strip ends as latitude; longitude
    if locale == "ru":  # no English on the map page and in the strips table
        ours = re.split("Условные обозначения|Список литературы", text)[0]  # not the symbols
        words = {w.lower() for w in _LATIN_WORD.findall(ours)}
        words -= {w.lower() for w in _LATIN_WORD.findall(spec.meta.project)}  # user text
        assert words <= {"epsg", "wgs", "utm", "gsd"}, words


def test_pdf_says_why_an_abstract_block_has_no_map(spec_with):
    pages = _pdf_pages(spec_with(make_layout(georeferenced=False)))
    text = "\n".join(pages)
    assert "abstract rectangle" in text and "as a polygon (a boundary file" in text
    assert "[area]" not in text
    assert "Flight lines over the area" in text and "Flight map" not in text
    assert "EPSG" not in text


@pytest.mark.parametrize("locale", ["en", "ru"])
def test_workbook_has_strips_and_photos_sheets(spec_with, locale):
    lay = _named(make_layout(notch=True, sorties=2))
    spec = spec_with(lay, locale)
    wb = load_workbook(io.BytesIO(render_xlsx(uav=spec.uav.job, meta=spec.meta, spec=spec)))
    names = {"en": ("Strips", "Photos"), "ru": ("Маршруты", "Снимки")}[locale]
    assert set(names) <= set(wb.sheetnames)
    photos = list(wb[names[1]].iter_rows(values_only=True))
    assert len(photos) == 1 + len(lay.photos)
    assert photos[1][:4] == (1, 1, 1, 1) and isinstance(photos[1][6], float)
    assert abs(photos[1][6] - lay.photos["lon_deg"][0]) < 1e-9
    rows = list(wb[names[0]].iter_rows(values_only=True))
    numbers = [r for r in rows if isinstance(r[0], int)]
    assert [r[0] for r in numbers] == [1, 2, 3, 4, 5, 6]
    assert [r[4] for r in numbers] == [1, 1, 2, 2, 1, 1]  # photographed parts
    assert sum(r[2] for r in numbers) == len(lay.photos)


def test_a_large_block_keeps_its_photos_in_the_csv_only(spec_with):
    lay = make_layout(width_m=5000, length_m=8000, spacing_m=100.0, base_m=40.0)
    assert len(lay.photos) > MAX_SHEET_PHOTOS
    spec = spec_with(lay)
    wb = load_workbook(io.BytesIO(render_xlsx(uav=spec.uav.job, meta=spec.meta, spec=spec)))
    assert "Strips" in wb.sheetnames and "Photos" not in wb.sheetnames
    text = " ".join(str(v) for r in wb["Strips"].iter_rows(values_only=True) for v in r if v)
    assert "10,150 photo centres are too many for the workbook" in text
    assert "10,150 photo centres are too many" in "\n".join(_pdf_pages(spec))
