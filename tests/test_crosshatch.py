"""A crosshatch (double grid, ``[uav] crosshatch = true``): the area flown twice, the second
pass's lines at the direction + 90°, laid out by the one layout code; its sorties, missions,
words in the documents (en, ru) and the project key."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import shapely
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.geo.crosshatch import plan_crosshatch
from scanplan.geo.layout import Area
from scanplan.geo.lines import Turn, plan_lines

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"


def _local(geom: object) -> Area:
    return Area(geom, "LOCAL", "test polygon", False, geom.area / 1e6, geom.length / 1e3)


def _lay(area: Area, direction: float, crosshatch: bool = False, **kw: object):
    lay_out = plan_crosshatch if crosshatch else plan_lines
    return lay_out(area, spacing_m=60.0, base_m=40.0, footprint_across_m=150.0,
                   footprint_along_m=100.0, height_m=100.0, direction_deg=direction,
                   turn=Turn("turnaround", 20.0), speed_ms=10.0, **kw)


# an L (no side an exact multiple of the base: the second pass begun from the other side
# then counts the same photos, not one more where rounding tips ceil(L/B))
L_AREA = _local(shapely.Polygon([(0, 0), (913.7, 0), (913.7, 317.3), (407.9, 317.3),
                                 (407.9, 711.3), (0, 711.3)]))


@pytest.mark.parametrize("direction", [0.0, 30.0, 117.5])
def test_the_second_pass_is_the_layout_at_the_direction_plus_90(direction):
    """Strips 1 … n are the one-pass layout at the direction, the rest the one-pass layout
    at the direction + 90° (the same lines, flown from the side nearer the first pass's
    end); photos and strips are numbered on in flight order, each strip with its own
    direction."""
    one = _lay(L_AREA, direction)
    cross = _lay(L_AREA, (direction + 90.0) % 180.0)
    both = _lay(L_AREA, direction, crosshatch=True)
    n = len(one.strips)
    assert both.crosshatch and both.first_pass_strips == n
    assert both.cross_direction_deg == pytest.approx((direction + 90.0) % 180.0)
    assert len(both.strips) == n + len(cross.strips)
    assert both.n_photos == one.n_photos + cross.n_photos
    assert [s.number for s in both.strips] == list(range(1, len(both.strips) + 1))
    assert [both.strip_direction_deg(s.number) for s in both.strips] == (
        [one.direction_deg] * n + [cross.direction_deg] * len(cross.strips))
    # the first pass as one pass lays it out
    for a, b in zip(one.strips, both.strips[:n], strict=True):
        assert a.start_xy_m == b.start_xy_m and a.end_xy_m == b.end_xy_m
    # the second pass: the same lines (each strip's ends as a set, either way flown)
    def ends(strips):
        return sorted(tuple(np.round(sorted([s.start_xy_m, s.end_xy_m]), 6).ravel())
                      for s in strips)

    assert ends(both.strips[n:]) == ends(cross.strips)
    assert sorted(np.round(both.photos["x_m"][one.n_photos:], 6)) == sorted(
        np.round(cross.photos["x_m"], 6))
    ph = both.photos
    assert list(ph["photo"]) == list(range(1, both.n_photos + 1))
    assert np.all(np.diff(ph["strip"]) >= 0)
    firsts = [s.first_photo for s in both.strips]
    assert firsts == sorted(firsts) and firsts[n] == one.n_photos + 1
    # the flight: both serpentines and the pass transit between them
    transit = both.notes["pass_transit_m"]
    assert transit > 0
    assert both.flight_length_m == pytest.approx(sum(s.length_m for s in both.sorties))
    assert both.flight_length_m > (one.flight_length_m - one.notes["transit_m"]
                                   + cross.flight_length_m - cross.notes["transit_m"])
    # the first pass's turns and the second's (its serpentine may begin at the other
    # side, whose turns differ where the strips' ends do); the pass transit is no turn
    assert one.turn_length_m < both.turn_length_m < both.flight_length_m - transit


def test_the_second_pass_starts_at_the_corner_nearer_the_first_pass_end():
    """Of the second pass's two serpentines, the one whose run-in is nearer the first
    pass's run-out: never farther than the other corner."""
    both = _lay(L_AREA, 0.0, crosshatch=True)
    n = both.first_pass_strips
    last, first2 = both.strips[n - 1], both.strips[n]
    near = np.hypot(*np.subtract(first2.start_xy_m, last.end_xy_m))
    other = _lay(L_AREA, 270.0)  # the second pass's lines begun from the other side
    far = np.hypot(*np.subtract(other.strips[0].start_xy_m, last.end_xy_m))
    assert near <= far + 1e-6


def test_the_sorties_pack_both_passes_as_one_serpentine():
    """With a battery limit the sorties run on from the first pass into the second: every
    photo in one sortie, the sorties in flight order, the strips' sorties agreeing with the
    photos'."""
    both = _lay(L_AREA, 0.0, crosshatch=True, max_flight_time_min=6.0)
    assert both.feasible and len(both.sorties) >= 3
    ph = both.photos
    assert np.all(np.diff(ph["sortie"]) >= 0)
    assert set(ph["sortie"]) == {s.number for s in both.sorties}
    n = both.first_pass_strips
    crossing = [s for s in both.sorties if min(s.strips) <= n < max(s.strips)]
    assert crossing  # some sortie flies the pass transit
    for s in both.strips:
        assert ph["sortie"][s.first_photo - 1] == s.sortie
    assert both.flight_time_s == pytest.approx(sum(s.time_s for s in both.sorties))


def _project(tmp: Path, value: str = "true", locale: str = "en") -> Path:
    src = (EXAMPLES / "uav-town-2000.toml").read_text(encoding="utf-8")
    src = src.replace('"areas/', f'"{EXAMPLES}/areas/').replace(
        "[uav]\n", f"[uav]\ncrosshatch = {value}\n", 1).replace(
        'locale = "en"', f'locale = "{locale}"')
    p = tmp / f"crosshatch-{locale}.toml"
    p.write_text(src, encoding="utf-8")
    return p


@pytest.mark.parametrize("value", ["1", '"yes"', "[true]"])
def test_a_bad_value_exits_2_naming_the_key(tmp_path, value):
    res = CliRunner().invoke(main, ["plan", str(_project(tmp_path, value))])
    assert res.exit_code == 2, res.output
    assert "uav.crosshatch" in res.output and "true or false" in res.output
    assert "Traceback" not in res.output


def test_crosshatch_false_is_the_one_pass_plan(tmp_path):
    a = CliRunner().invoke(main, ["plan", str(_project(tmp_path, "false")), "--json"])
    src = (EXAMPLES / "uav-town-2000.toml").read_text(encoding="utf-8").replace(
        '"areas/', f'"{EXAMPLES}/areas/')
    (tmp_path / "plain.toml").write_text(src, encoding="utf-8")
    b = CliRunner().invoke(main, ["plan", str(tmp_path / "plain.toml"), "--json"])
    assert a.exit_code == b.exit_code == 0
    la = json.loads(a.output)["specification"]["uav"]["layout"]
    lb = json.loads(b.output)["specification"]["uav"]["layout"]
    assert la == lb and "crosshatch" not in la


@pytest.mark.parametrize("locale,words", [
    ("en", "crosshatch (two passes at 87.6° and 177.6°)"),
    ("ru", "двойная сетка (два прохода: 87,6° и 177,6°)")])
def test_the_documents_say_crosshatch_and_fly_both_passes(tmp_path, locale, words):
    """The terminal, the JSON, the PDF's map page and the workbook say it in the
    document's language; the QGroundControl plans and the DJI routes fly both passes."""
    import zipfile

    import openpyxl

    out = tmp_path / "out"
    res = CliRunner().invoke(main, ["plan", str(_project(tmp_path, locale=locale)),
                                    "--out", str(out)])
    assert res.exit_code == 0, res.output
    assert words in " ".join(res.output.split())
    js = CliRunner().invoke(main, ["plan", str(_project(tmp_path, locale=locale)), "--json"])
    lay = json.loads(js.output)["specification"]["uav"]["layout"]
    assert lay["crosshatch"] is True and lay["n_strips"] > lay["first_pass_strips"] > 0
    assert sorted({round(s["direction_deg"], 1) for s in lay["strips"]}) == [87.6, 177.6]
    codes = {w["code"] for w in json.loads(js.output)["warnings"]}
    assert "crosshatch" in codes
    import subprocess

    text = subprocess.run(["pdftotext", "-layout", str(out / "spec.pdf"), "-"],
                          capture_output=True, text=True, check=True).stdout
    assert words in " ".join(text.split())
    wb = openpyxl.load_workbook(out / "spec.xlsx", read_only=True)
    cells = {str(c) for ws in wb.worksheets for row in ws.iter_rows(values_only=True)
             for c in row if c is not None}
    assert any(words in c for c in cells)
    # every QGroundControl plan read back: waypoints along both directions
    headings = set()
    for plan in sorted(out.glob("mission-*.plan")):
        items = json.loads(plan.read_text())["mission"]["items"]
        pts = np.array([(i["params"][5], i["params"][4]) for i in items
                        if i["command"] == 16])
        d = np.diff(pts, axis=0)
        az = np.degrees(np.arctan2(d[:, 0] * np.cos(np.radians(55.08)), d[:, 1])) % 180.0
        headings |= {round(a) for a in az[np.hypot(*d.T) > 1e-3]}
    assert any(abs(h - 88) <= 1 for h in headings)
    assert any(abs(h - 178) <= 1 or h <= 0 for h in headings)
    # the GIS files read by GDAL: both passes' strips and every photo
    from pyogrio.raw import read

    def count(path: Path, layer: str | int | None = None) -> int:
        return len(read(path, layer=layer, read_geometry=False)[3][0])

    for name, strips, photos in (("flight.gpkg", "strips", "photos"),
                                 ("flight.kml", 1, 3)):  # KML folders in the language
        assert count(out / name, strips) == lay["n_strips"]
        assert count(out / name, photos) == lay["n_photos"]
    meta, _fid, _geom, fields = read(out / "flight.geojson", read_geometry=False)
    kind = fields[list(meta["fields"]).index("kind")]
    assert (kind == "strip").sum() == lay["n_strips"]
    # every DJI route a WPML zip whose waylines hold waypoints
    for kmz in sorted(out.glob("mission-dji-*.kmz")):
        with zipfile.ZipFile(kmz) as zf:
            assert b"<wpml:waypointHeadingMode>followWayline<" in zf.read(
                "wpmz/waylines.wpml")


def test_a_crosshatch_without_an_area_exits_2_naming_the_key(tmp_path):
    """Without an area there are no lines to fly twice: refused like the other layout
    keys."""
    p = tmp_path / "no-area.toml"
    p.write_text('[map]\nscale = 2000\nrelief_interval_m = 0.5\n\n[uav]\ncrosshatch = true\n'
                 'camera = "dji-zenmuse-p1-35"\n', encoding="utf-8")
    res = CliRunner().invoke(main, ["plan", str(p)])
    assert res.exit_code == 2, res.output
    assert "uav.crosshatch" in res.output and "applies to an area" in res.output
