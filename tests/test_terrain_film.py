"""Film over the relief (issue 12, item 3): the specification's photo scale and scan pixel
hold at the frame over the lowest ground, Mc = (H − h)/f (seed 001's Mc = H/f with H above
that ground); the map page coloured by height above ground (item 4).

Tolerances: a plane DEM is exact under bilinear sampling (float64 cells), so the scan
pixel agrees with the closed form at Mc_max to 1e-9 relative; a flat DEM gives the very
numbers of a plan without ``[terrain]`` (equality).
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st
from terrain_helpers import write_dem

from scanplan.cli.main import main
from scanplan.geo.terrain_worst import run_in_m
from scanplan.project.file import load_project, parse_project
from scanplan.project.spec import plan_project
from scanplan.rules.film import evaluate

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
RELIEF = EXAMPLES / "film-town-relief-10000.toml"
FLAT_TWIN = EXAMPLES / "film-town-10000.toml"

# film-1000.toml's job (map 1:1000, RC30 f = 153 mm, R 40, poles 0.2 m): on flat ground
# 1:8000 with P_P = 70 µm × 1000 / 8000 = 8.75 µm binding (seed 001, eq. 3)
X0, Y0 = 500_000.0, 6_000_000.0
FILM_1000 = """
[project]
name = "Plan 1:1000 from film photos over a slope"
locale = "en"
[map]
scale = 1000
relief_interval_m = 0.5
[film]
camera = "rc30-153"
resolving_power_lpmm = 40
forward_overlap_pct = 60
photo_scales = [4000, 5000, 6000, 8000]
scanner = "photoscan-td"
[area]
polygon = [[{x0}, {y0}], [{x1}, {y0}], [{x1}, {y1}], [{x0}, {y1}], [{x0}, {y0}]]
crs = "EPSG:32637"
"""
F_M = 0.153


def _project(tmp: Path, terrain: str = "") -> Path:
    text = FILM_1000.format(x0=X0, y0=Y0, x1=X0 + 1500, y1=Y0 + 2000) + terrain
    p = tmp / "film.toml"
    p.write_text(text, encoding="utf-8")
    return p


def _dem(tmp: Path, func) -> Path:
    return write_dem(tmp / "dem.tif", func, left=X0 - 3000, top=Y0 + 5000, cell=10.0,
                     width=750, height=1000, dtype="float64")


def test_plane_dem_scan_pixel_is_the_flat_formula_at_the_largest_local_mc(tmp_path):
    """A plane rising 2 m per 100 m eastwards: the frame over the lowest ground has
    Mc_max = (A − h_min)/f with A = h_max + f·Mc; P_P = 70 µm·Mk/Mc_max binds there."""
    def plane(x, y):
        return 100.0 + 0.02 * (x - X0)

    dem = _dem(tmp_path, plane)
    spec = plan_project(load_project(_project(tmp_path, f'[terrain]\ndem = "{dem}"\n')))
    f = spec.film
    rec = f.recommended
    x = f.layout.photos["x_m"]
    lay = f.layout
    # the centres alone bound Mc_max from below; the footprints (and the run-in) reach at
    # most a footprint diagonal plus the grid's reach (one 10 m cell and a block) beyond
    h_min, h_max = float(plane(x.min(), 0)), float(plane(x.max(), 0))
    centres_mc = (h_max + F_M * 8000 - h_min) / F_M
    reach_m = np.hypot(lay.footprint_across_m, lay.footprint_along_m) + 20.0
    ft = f.terrain
    assert centres_mc <= ft.mc_max <= centres_mc + 2 * 0.02 * reach_m / F_M
    assert rec.photo_scale == 8000  # the scale flown (over the highest ground)
    assert rec.local_photo_scale == pytest.approx(ft.mc_max, rel=1e-9)
    assert rec.binding == "PP"
    assert rec.scan_pixel_um == pytest.approx(70.0 * 1000 / ft.mc_max, rel=1e-9)
    assert rec.scan_pixel_um < 8.75  # finer than on flat ground
    assert f.flat.scan_pixel_um == pytest.approx(8.75, rel=1e-12)
    assert ft.mc_min == pytest.approx(8000.0, rel=1e-9)  # over the highest path ground
    # the binding frame is one over the lowest ground
    ph = f.layout.photos
    at = np.flatnonzero(ph["photo"] == ft.binding_frame)[0]
    assert ph["x_m"][at] == pytest.approx(x.min())
    # every frame carries its ground, altitude and height above ground
    np.testing.assert_allclose(ph["ground_m"], plane(ph["x_m"], 0), atol=1e-6)
    # one altitude, the planned scale over the highest ground under the path: along strips
    # that run up the slope, the run-in beyond the last frame (plus the grid's reach)
    alt = ph["altitude_m"]
    path_top = h_max + 0.02 * run_in_m(lay) * abs(np.sin(np.radians(lay.direction_deg)))
    assert np.all(alt == alt[0]) and path_top + F_M * 8000 <= alt[0] <= path_top + F_M * 8000 + 2
    np.testing.assert_allclose(ph["agl_m"], ft.mc * F_M, rtol=1e-12)
    assert np.all(ph["agl_m"] >= alt - ph["ground_m"] - 1e-6)  # over the footprint's lowest
    # the frame volume follows the pixel actually specified (the scanner's 7 µm here)
    assert rec.scanner_pixel_um == 7.0
    codes = [w.code for w in f.job.plan.warnings]
    assert "terrain_film_scale" in codes


def test_a_flat_dem_is_no_dem(tmp_path):
    """Flat ground at 150 m: the film specification is the one without [terrain]."""
    dem = _dem(tmp_path, lambda x, y: np.full_like(x, 150.0))
    with_dem = plan_project(load_project(_project(tmp_path, f'[terrain]\ndem = "{dem}"\n')))
    (tmp_path / "b").mkdir()
    without = plan_project(load_project(_project(tmp_path / "b")))
    a, b = with_dem.film.recommended, without.film.recommended
    assert a.binding == b.binding
    for name in ("photo_scale", "scan_pixel_um", "scanner_pixel_um", "frame_megabytes",
                 "recognition_probability"):
        assert getattr(a, name) == pytest.approx(getattr(b, name), rel=1e-12), name
    assert a.local_photo_scale == pytest.approx(a.photo_scale, rel=1e-12)
    assert [c.pixel_um for c in a.constraints] == pytest.approx(
        [c.pixel_um for c in b.constraints], rel=1e-12)
    assert with_dem.film.frames == without.film.frames
    assert not with_dem.film.rejected
    assert "terrain_film_scale" not in [w.code for w in with_dem.film.job.plan.warnings]


@pytest.mark.parametrize("relief_m", [0.0, 30.0, 61.2])
def test_a_ground_range_holds_the_scale_at_its_lowest_ground(tmp_path, relief_m):
    """ground_elevation_m = [lo, hi] on the abstract block: Mc_max = Mc + (hi − lo)/f."""
    text = FILM_1000.split("[area]")[0] + (
        "[area]\nwidth_m = 1500\nlength_m = 2000\n"
        f"[terrain]\nground_elevation_m = [120, {120 + relief_m}]\n")
    spec = plan_project(parse_project(text, tmp_path / "p.toml"))
    rec = spec.film.recommended
    mc_max = rec.photo_scale + relief_m / F_M
    assert rec.local_photo_scale == pytest.approx(mc_max, rel=1e-12)
    inp = spec.film.job.plan.inputs
    ev = evaluate(spec.film.job.plan.rules, map_scale=1000, photo_scale=mc_max,
                  relief_interval_m=0.5, focal_mm=inp.focal_mm,
                  frame_along_mm=inp.frame_along_mm, forward_overlap_pct=60,
                  resolving_power_lpmm=40, object_size_m=inp.object.size_m,
                  shape_coefficient=inp.object.shape_coefficient)
    assert rec.scan_pixel_um == pytest.approx(float(ev.scan_pixel_um), rel=1e-12)
    assert rec.binding == str(ev.binding)


def test_relief_rules_out_the_flat_ground_choice():
    """The example: on flat ground 1:8000; over 120 m of relief its frames reach 1:9200,
    beyond the poles' interpretation limit 1:8847 (seed 001), so 1:6000 (frames down to
    1:7200 = (H − 110 m)/f with H = 230 m + 0.1 m × 6000)."""
    flat = plan_project(load_project(FLAT_TWIN)).film
    assert flat.recommended.photo_scale == 8000
    f = plan_project(load_project(RELIEF)).film
    assert f.recommended.photo_scale == 6000
    assert f.recommended.local_photo_scale == pytest.approx(7200.0)
    assert [(r.photo_scale, t.mc_max) for r, t in f.rejected] == [(8000, pytest.approx(9200))]
    assert f.frames > flat.frames
    w = next(w for w in f.job.plan.warnings if w.code == "terrain_film_scale_changed")
    assert "1:8000" in w.message and "1:9200" in w.message and "1:6000" in w.message
    assert "1:6000" in w.text("ru") and "рельеф" in w.text("ru")


def test_the_json_states_the_binding_frame_and_the_flat_value():
    r = CliRunner().invoke(main, ["plan", str(RELIEF), "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.output)
    s = d["specification"]["film"]
    assert s["recommended_photo_scale"] == 6000
    assert s["local_photo_scale"] == pytest.approx(7200)
    assert s["flat_ground"]["photo_scale"] == 6000
    assert s["flat_ground"]["binding"] == "PR"
    t = d["terrain"]["film"]
    assert t["photo_scale_max"] == pytest.approx(7200)
    assert t["specified_at_binding_frame"] is True
    assert t["rejected_photo_scales"] == [{"photo_scale": 8000,
                                           "photo_scale_max": pytest.approx(9200)}]
    assert t["ground_from_dem"] is False


def test_text_excel_and_pdf_report_the_local_scales(tmp_path):
    from scanplan.reports.text import format_terrain

    spec = plan_project(load_project(RELIEF))
    for loc, word in (("en", "on flat ground"), ("ru", "для плоской местности")):
        line = " ".join(format_terrain(spec, loc))
        assert "1:6" in line and "7" in line and word in line
    r = CliRunner().invoke(main, ["plan", str(RELIEF), "--out", str(tmp_path)])
    assert r.exit_code == 0, r.output
    import openpyxl
    ws = openpyxl.load_workbook(tmp_path / "spec.xlsx")["Terrain"]
    values = {row[0]: row[1] for row in ws.iter_rows(values_only=True) if row[0]}
    assert values["Smallest local photo scale (the frame over the lowest ground)"] == 7200
    assert values["Scan pixel on flat ground, µm"] == pytest.approx(12.5)
    from pypdf import PdfReader
    text = " ".join(p.extract_text() for p in PdfReader(tmp_path / "spec.pdf").pages)
    text = re.sub(r"\s+", " ", text)
    assert "Smallest local photo scale" in text and "1:7200" in text


# --- the map page coloured by height above ground ---------------------------------------------

def test_the_map_colours_photos_by_height_above_ground_in_one_raster_layer(tmp_path):
    from terrain_helpers import valley_pinned

    from scanplan.reports.exports import spec_layouts
    from scanplan.reports.mapview import map_svg, map_terrain

    # one altitude over the valley: 16,442 photos (following the terrain needs 6,217)
    spec = plan_project(load_project(valley_pinned(tmp_path)))
    (kind, lay), = spec_layouts(spec)
    mt = map_terrain(spec, kind, lay)
    assert mt is not None and mt.agl_m.size == len(lay.photos) > 10_000
    assert mt.limit_m == pytest.approx(spec.uav.job.plan.max_height_m)
    for loc, label in (("en", "Height above ground, m"), ("ru", "Высота над рельефом, м")):
        svg = map_svg(lay, loc, mt)
        assert label in svg
        # the coloured centres are one raster (with the colour bar's: two images), not
        # thousands of SVG marks
        assert svg.count("<image") == 2 and svg.count("<use") < 200
    plain = map_svg(lay, "en")
    # the plain map's photo centres are one picture too (issue 15), without a colour bar
    assert "Height above ground" not in plain
    assert plain.count("<image") == 1 and plain.count("<use") < 200


def test_failing_photos_are_marked_and_the_flat_map_is_unchanged(tmp_path):
    import dataclasses

    from scanplan.reports.exports import spec_layouts
    from scanplan.reports.mapview import map_svg, map_terrain

    spec = plan_project(load_project(EXAMPLES / "uav-town-valley-2000.toml"))
    (kind, lay), = spec_layouts(spec)
    mt = map_terrain(spec, kind, lay)
    high = mt.agl_m >= np.percentile(mt.agl_m, 90)
    svg = map_svg(lay, "en", dataclasses.replace(mt, too_high=high))
    assert f"Above the maximum height {mt.limit_m:.0f} m ({mt.cid})" in svg
    flat = plan_project(load_project(EXAMPLES / "uav-town-2000.toml"))
    (k2, l2), = spec_layouts(flat)
    assert map_terrain(flat, k2, l2) is None  # no [terrain]: the map as before


# --- flat ground ≡ no terrain, as a property ----------------------------------------------------


@settings(max_examples=15, deadline=None)
@given(level=st.floats(-400.0, 5000.0, allow_nan=False),
       scales=st.lists(st.sampled_from([3000, 4000, 5000, 6000, 8000, 10000, 12000]),
                       min_size=1, max_size=4, unique=True),
       mode=st.sampled_from(["constant", "strip", "follow"]))
def test_flat_ground_is_no_terrain_for_film(tmp_path_factory, level, scales, mode):
    """ground_elevation_m = [g, g] at any level, in any altitude mode: the photo scale,
    scan pixel, binding constraint and frames of the plan without [terrain] (equality)."""
    tmp = tmp_path_factory.mktemp("flat")
    base = FILM_1000.split("[area]")[0].replace(
        "photo_scales = [4000, 5000, 6000, 8000]", f"photo_scales = {sorted(scales)}") + (
        "[area]\nwidth_m = 1500\nlength_m = 2000\n")
    flat = plan_project(parse_project(
        base + f'[terrain]\nground_elevation_m = [{level!r}, {level!r}]\n'
        f'altitude_mode = "{mode}"\n', tmp / "a.toml"))
    none = plan_project(parse_project(base, tmp / "b.toml"))
    a, b = flat.film.recommended, none.film.recommended
    assert (a is None) == (b is None)
    if a is None:
        return
    assert (a.photo_scale, a.binding, a.scanner_pixel_um) == (b.photo_scale, b.binding,
                                                                b.scanner_pixel_um)
    assert a.scan_pixel_um == pytest.approx(b.scan_pixel_um, rel=1e-12)
    assert a.local_photo_scale == pytest.approx(b.photo_scale, rel=1e-12)
    assert flat.film.frames == none.film.frames and not flat.film.rejected


def test_archive_photos_are_scanned_for_the_frame_over_the_lowest_ground(tmp_path):
    """Archive photos 1:12000 (f = 153 mm) over ground 120–260 m: Mc_max = 12000 + 140 m /
    0.153 m = 12915.0; P_D set aside (the poles cannot be interpreted), P_P = 70 µm × 2000 /
    Mc_max binds there (seed 001, eq. 3) instead of 70 × 2000 / 12000 = 11.667 µm."""
    text = (EXAMPLES / "archive-12000-for-2000.toml").read_text(encoding="utf-8")
    p = tmp_path / "a.toml"
    p.write_text(text + "\n[terrain]\nground_elevation_m = [120, 260]\n", encoding="utf-8")
    f = plan_project(load_project(p)).film
    mc_max = 12000 + 140 / F_M
    rec = f.recommended
    assert f.archive and rec.photo_scale == 12000
    assert rec.local_photo_scale == pytest.approx(mc_max, rel=1e-12)
    assert rec.binding == "PP"
    assert rec.scan_pixel_um == pytest.approx(70.0 * 2000 / mc_max, rel=1e-12)
    assert f.flat.scan_pixel_um == pytest.approx(70.0 * 2000 / 12000, rel=1e-12)
    assert f.terrain.scan_pixel_um == rec.scan_pixel_um and f.terrain.binding == "PP"
    assert "1:12915" in f.reason.text("en")


def test_the_film_maps_local_scale_axis_reads_as_scales():
    """The colour bar's second axis of local photo scales labels them as the text writes
    scales: 7200 in both languages (it said 7,200 / 7 200), never grouped four digits."""
    from scanplan.reports.exports import spec_layouts
    from scanplan.reports.mapview import MapTerrain, map_svg, map_terrain

    spec = plan_project(load_project(EXAMPLES / "film-town-relief-10000.toml"))
    (kind, lay), = spec_layouts(spec)
    # a ground range leaves every frame over the same ground: the map is not coloured by it
    assert map_terrain(spec, kind, lay) is None
    ft, focal = spec.film.terrain, spec.film.job.plan.inputs.focal_mm
    agl = np.asarray(lay.photos["agl_m"], dtype=float)
    none = np.zeros(agl.size, dtype=bool)
    mt = MapTerrain(agl, none, none, scale_of_height=lambda h: h * 1000.0 / focal,
                    height_of_scale=lambda m: m * focal / 1000.0, agl_range_m=(
        ft.mc_min * focal / 1000.0, ft.mc_max * focal / 1000.0))  # as a DEM would colour it
    for loc in ("en", "ru"):
        svg = map_svg(lay, loc, mt)
        labels = set(re.findall(r">(7[\s,\u00a0]?[02]00)<", svg))
        assert labels == {"7000", "7200"}, (loc, labels)


def test_the_flight_altitude_over_the_relief_is_stated():
    """Bug: over the relief the specification gave only "flight height above ground
    (Mc × f) 600 m" without saying above which ground; the frames are flown at the
    altitude of the highest ground plus 600 m (830 m here), which the crew flies. The
    survey design and the terminal now state it."""
    from scanplan.reports.formatter import formatter
    from scanplan.reports.text import format_terrain
    from scanplan.reports.views import ResultTables

    result = plan_project(load_project(EXAMPLES / "film-town-relief-10000.toml"))
    ft = result.film.terrain
    altitude = float(np.max(ft.altitude_m))
    assert altitude == pytest.approx(830.0)  # 230 m highest ground + 1:6000 × 100 mm
    assert "flight altitude 830 m" in " ".join(format_terrain(result, "en"))
    assert "высота полёта 830 м" in " ".join(format_terrain(result, "ru"))
    f = formatter("en")
    rows = {f.row_label(r): f.show(r.values[0]) for r in ResultTables(spec=result)["design"].rows}
    assert rows["Flight height above ground (Mc × f), m"] == "600"
    assert rows["Flight altitude (the highest ground + Mc × f, in the ground's height "
                "system), m"] == "830"
