"""Russian documents read as a Russian engineer writes: the decimal comma in every number
(a shape coefficient too), a Russian camera in Cyrillic (АФА-ТЭ-100), plane coordinates
in the surveyor's order X (north), Y (east)."""

from __future__ import annotations

from pathlib import Path

import documents
import pytest

from scanplan.norms import load_norm_set
from scanplan.reports.mapview import strips_table
from scanplan.reports.wording import camera_title, param_value

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _planned(example: str, locale: str):
    """The example's plan in ``locale``, planned once per run (tests/documents.py)."""
    return documents.planned(str(EXAMPLES / example), locale)


def _book(example: str, locale: str):
    """Its workbook read back, rendered once per run (tests/documents.py)."""
    return documents.loaded_workbook(str(EXAMPLES / example), locale)


def _texts(book) -> list[str]:
    return [c.value for ws in book.worksheets for row in ws.iter_rows() for c in row
            if isinstance(c.value, str)]


def test_a_shape_coefficient_has_the_decimal_comma_in_russian():
    ns = load_norm_set()
    assert param_value(ns, "shape", "circle", "ru").endswith("(B = 0,97)")
    assert param_value(ns, "shape", "circle", "en").endswith("(B = 0.97)")


@pytest.mark.parametrize("example", ["film-town-10000.toml", "uav-town-2000.toml"])
def test_no_shape_coefficient_with_a_decimal_point_in_a_russian_workbook(example):
    texts = _texts(_book(example, "ru"))
    assert any("B = " in t for t in texts)
    assert not [t for t in texts if "B = 0." in t or "B = 1." in t or "B = 2." in t]


def test_the_afa_camera_is_written_in_cyrillic_in_russian():
    ns = load_norm_set()
    assert camera_title(ns, "afa-te-100", "ru").startswith("АФА-ТЭ-100")
    assert camera_title(ns, "afa-te-100", "en").startswith("AFA-TE-100")
    texts = " ".join(_texts(_book("film-town-10000.toml", "ru")))
    assert "АФА-ТЭ-100" in texts and "AFA-TE" not in texts


def test_russian_strip_ends_are_x_north_then_y_east():
    book = _book("uav-town-2000.toml", "ru")
    r = _planned("uav-town-2000.toml", "ru")
    strip = r.uav.job.layout.strips[0]
    for ws in book.worksheets:
        rows = list(ws.iter_rows(values_only=True))
        for k, row in enumerate(rows):
            if row and any(isinstance(v, str) and "Начало: X (на север)" in v for v in row):
                cols = list(row)
                x_col = cols.index("Начало: X (на север), м")
                y_col = cols.index("Начало: Y (на восток), м")
                assert x_col < y_col
                first = rows[k + 1]
                assert first[x_col] == pytest.approx(strip.start_xy_m[1], abs=1e-3)
                assert first[y_col] == pytest.approx(strip.start_xy_m[0], abs=1e-3)
                return
    pytest.fail("no strips sheet with X/Y columns")


def test_english_strip_ends_stay_easting_then_northing():
    book = _book("uav-town-2000.toml", "en")
    texts = _texts(book)
    start_e = next(i for i, t in enumerate(texts) if t.startswith("Start: Easting"))
    start_n = next(i for i, t in enumerate(texts) if t.startswith("Start: Northing"))
    assert start_e < start_n


def test_a_local_block_prints_x_then_y_in_russian():
    r = _planned("uav-canon-2000.toml", "ru")
    layout = r.uav.job.layout
    s = layout.strips[0]
    ru = strips_table(layout, "ru")
    assert "X (на север), Y (на восток)" in ru["head"][-2]
    x, y = ru["rows"][0][-2].split("; ")
    assert float(x.replace("\u00a0", "").replace(",", ".")) == pytest.approx(
        round(s.start_xy_m[1]))
    assert float(y.replace("\u00a0", "").replace(",", ".")) == pytest.approx(
        round(s.start_xy_m[0]))
