"""A strip flown by two sorties says so (a battery change in mid-strip).

Bug: the strips table of the PDF and the workbook's Strips sheet gave each strip the sortie
it starts in: strip 12 of the town example read "sortie 1" though 96 of its 128 photos are
taken by sortie 2 (photos.csv and the missions were right). A crew planning the battery
changes from the table changed at the wrong strip, and the map's "2" in the middle of the
block matched no row. The page's sortie markers stood at the first photo of each sortie's
first strip — for sortie 2 the start of strip 12, which sortie 1 flies.
"""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pytest

from scanplan.project.file import load_project
from scanplan.project.spec import plan_project
from scanplan.reports.mapview import continued_note, strips_table

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def town():
    """The town example planned: its UAV result and flight layout (five sorties, four
    battery changes in mid-strip)."""
    result = plan_project(load_project(ROOT / "examples" / "uav-town-2000.toml"))
    return result, result.uav.layout


def test_each_strip_knows_every_sortie_that_flies_it(town):
    _, layout = town
    ph = layout.photos
    strip, sortie = np.asarray(ph["strip"]), np.asarray(ph["sortie"])
    assert np.array_equal(np.asarray(ph["photo"]), np.arange(1, len(strip) + 1))
    split = [s for s in layout.strips if s.continued]
    assert len(split) >= 2 and len(layout.sorties) >= 3
    for s in layout.strips:
        flown = sorted(set(sortie[strip == s.number].tolist()))
        assert flown == list(range(s.sortie, s.last_sortie + 1)), s.number
        for later, photo in s.continued:  # the first photo of the later sortie, there
            assert (strip[photo - 1], sortie[photo - 1]) == (s.number, later)
            assert (strip[photo - 2], sortie[photo - 2]) == (s.number, later - 1)
    # every change of sortie in mid-strip is listed (and none between strips)
    changes = np.flatnonzero((sortie[1:] != sortie[:-1]) & (strip[1:] == strip[:-1])) + 2
    assert sorted(p for s in split for _, p in s.continued) == changes.tolist()


@pytest.mark.parametrize("locale", ["en", "ru"])
def test_the_pdf_table_shows_both_sorties_and_where_the_battery_changes(town, locale):
    _, layout = town
    table = strips_table(layout, locale, limit=None)
    split = {s.number: s for s in layout.strips if s.continued}
    for row in table["rows"]:
        s = split.get(int(row[0]))
        assert row[1] == (f"{s.sortie}–{s.last_sortie}" if s else row[1]), row
        if s is None:
            assert "–" not in row[1]
    note = continued_note(layout.strips, locale)
    assert note and note in table["note"]
    photo_word = "photo" if locale == "en" else "со снимка"
    for s in split.values():
        for later, photo in s.continued:
            said = f"{photo:,}".replace(",", "," if locale == "en" else "\u00a0")
            assert f" {s.number}, " in note and f"{photo_word} {said}" in note, (note, photo)
            assert str(later) in note


def test_the_workbook_strips_sheet_shows_both_sorties(town):
    openpyxl = pytest.importorskip("openpyxl")
    from scanplan.i18n.labels import t
    from scanplan.reports.excel import render_xlsx

    result, layout = town
    data = render_xlsx(uav=result.uav.job, meta=result.meta, spec=result)
    ws = openpyxl.load_workbook(io.BytesIO(data))[t("strips", "en")]
    cells = {ws.cell(r, 1).value: ws.cell(r, 2).value for r in range(1, ws.max_row + 1)}
    for s in layout.strips:
        want = f"{s.sortie}–{s.last_sortie}" if s.continued else s.sortie
        assert cells[s.number] == want, s.number
    texts = [c.value for row in ws.iter_rows() for c in row if isinstance(c.value, str)]
    assert continued_note(layout.strips, "en") in texts


def test_the_page_marks_each_sortie_where_its_first_photo_is(town):
    from scanplan.web.mapdata import map_features

    result, layout = town
    ph = layout.photos
    starts = {f["properties"]["sortie"]: f["geometry"]["coordinates"]
              for f in map_features(result)["features"]
              if f["properties"]["kind"] == "takeoff" and f["properties"]["platform"] == "uav"}
    sortie = np.asarray(ph["sortie"])
    assert sorted(starts) == [k.number for k in layout.sorties]
    for number, (lon, lat) in starts.items():
        first = int(np.flatnonzero(sortie == number)[0])
        assert (lon, lat) == pytest.approx((ph["lon_deg"][first], ph["lat_deg"][first]))
    strips = {f["properties"]["number"]: f["properties"] for f in map_features(
        result)["features"] if f["properties"]["kind"] == "strip"
        and f["properties"]["platform"] == "uav"}
    for s in layout.strips:
        assert (strips[s.number]["sortie"], strips[s.number]["last_sortie"]) == (
            s.sortie, s.last_sortie)
        assert strips[s.number]["sorties"] == (f"{s.sortie}–{s.last_sortie}" if s.continued
                                               else str(s.sortie))


def test_the_gis_files_carry_the_last_sortie_of_each_strip(town, tmp_path):
    """flight.geojson, flight.kml and flight.gpkg: ``sortie`` (the one a strip starts in)
    and ``last_sortie`` (the one that flies its end), read back by GDAL."""
    pyogrio = pytest.importorskip("pyogrio")
    from scanplan.geo.export.gis import render_geojson, render_kml
    from scanplan.geo.export.gpkg import render_gpkg

    _, layout = town
    want = {s.number: (s.sortie, s.last_sortie) for s in layout.strips}
    assert any(a != b for a, b in want.values())
    (tmp_path / "flight.geojson").write_bytes(render_geojson(layout))
    (tmp_path / "flight.gpkg").write_bytes(render_gpkg(layout))
    kml = render_kml(layout).decode()
    for name, layer in (("flight.geojson", None), ("flight.gpkg", "strips")):
        _, _, _, fields = pyogrio.raw.read(tmp_path / name, layer=layer, read_geometry=False)
        names = list(pyogrio.read_info(tmp_path / name, layer=layer)["fields"])
        col = dict(zip(names, fields, strict=True))
        rows = range(len(col["strip"]))
        got = {int(col["strip"][i]): (int(col["sortie"][i]), int(col["last_sortie"][i]))
               for i in rows if "kind" not in col or col["kind"][i] == "strip"}
        assert got == want, name
    for number, (first, last) in want.items():
        if first != last:
            assert f"<description>sortie {first}–{last}</description>" in kml, number
