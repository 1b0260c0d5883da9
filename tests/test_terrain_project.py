"""``[terrain]`` in a project file (issue 12): the example over a synthetic river valley,
the altitude modes, the JSON section, and bad input through the command line."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.errors import InputError
from scanplan.project.file import load_project, parse_project
from scanplan.project.spec import plan_project

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
VALLEY = EXAMPLES / "uav-town-valley-2000.toml"


def _copy_example(tmp: Path, extra: str = "", drop: str = "") -> Path:
    """The valley example in ``tmp`` (with its KML and DEM), edited."""
    shutil.copytree(EXAMPLES / "areas", tmp / "areas")
    shutil.copytree(EXAMPLES / "dem", tmp / "dem")
    text = VALLEY.read_text(encoding="utf-8")
    if drop:
        text = text.replace(drop, "")
    p = tmp / "valley.toml"
    p.write_text(text + extra, encoding="utf-8")
    return p


@pytest.fixture(scope="module")
def valley(tmp_path_factory):
    """The valley example flown at one altitude, as the project pins it
    (``altitude_mode = "constant"``; the example leaves the mode to scanplan)."""
    p = _copy_example(tmp_path_factory.mktemp("valley"))
    p.write_text(p.read_text(encoding="utf-8").replace('altitude_mode = "auto"',
                                                       'altitude_mode = "constant"'),
                 encoding="utf-8")
    return plan_project(load_project(p))


def test_the_valley_shows_what_flat_ground_misses(valley):
    """Flat ground (the town example) plans 135 m; over the 60 m valley the worst photo
    is 60 m further from the ground: the altitude ceiling forces the plan down."""
    flat = plan_project(load_project(EXAMPLES / "uav-town-2000.toml"))
    assert flat.uav.recommended_height_m == 135
    assert "height_lowered" not in [w.code for w in flat.warnings]
    u = valley.uav
    tr = u.terrain
    assert tr is not None and tr.mode == "constant"
    relief = tr.ground.high_m - tr.ground.low_m
    assert 60 <= relief <= 70
    # the largest height over the relief: the flat maximum less the relief under the path
    # (the ceiling binds: the highest and the lowest ground under the flight lines), at
    # least the relief under the centres
    s = tr.summary()
    path_relief = s["path_agl_max_m"] - s["clearance_min_m"]
    assert tr.max_height_m == pytest.approx(u.job.plan.max_height_m - path_relief, abs=1e-3)
    assert tr.max_height_m <= u.job.plan.max_height_m - relief + 1e-6
    assert u.recommended_height_m == 5 * (tr.max_height_m // 5)
    assert u.recommended_height_m == 70  # the headline: 135 m on flat ground
    # one warning says the lowering and why: what the planned 135 m would miss, and how to
    # fly higher (not "lower the planned height": that is done); the flown plan misses nothing
    assert "terrain_resolution" not in [w.code for w in valley.warnings]
    w = next(w for w in valley.warnings if w.code == "height_lowered")
    assert w.message.code == "terrain_height_lowered"
    assert "HC" in w.message and "reference ground" in w.message
    assert w.message.params["why"].code == "terrain_resolution_lowered"
    assert "flown at 70 m. At the planned height of 135 m photo" in w.message
    assert "strips that would fail: 41" in w.message
    assert "To fly higher" in w.message and "altitude_mode" in w.message  # names the key
    assert "lower the planned height" not in w.message
    ru = w.message.text("ru")
    assert "принята высота 70\u00a0м. При плановой высоте 135\u00a0м снимок" in ru, ru
    assert "Чтобы лететь выше" in ru and ru.endswith("по рельефу."), ru
    ph = tr.layout.photos
    assert s["path_agl_max_m"] <= u.job.plan.max_height_m + 1e-6  # the ceiling holds
    assert s["clearance_min_m"] == pytest.approx(u.recommended_height_m, abs=1e-6)
    assert np.all(np.isfinite(ph["ground_m"]))
    assert u.job.layout is tr.layout  # the exports take the terrain columns
    assert tr.layout.notes["altitude_frame"] == "AMSL"


def test_json_has_the_terrain_section():
    res = CliRunner().invoke(main, ["plan", str(VALLEY), "--json"])
    assert res.exit_code == 0, res.output
    doc = json.loads(res.output)
    t = doc["terrain"]["uav"]
    assert t["source"] == "dem" and t["dem"] == "town-valley.tif"
    assert t["dem_crs"] == "EPSG:32637" and t["altitude_frame"] == "AMSL"
    # the example leaves the mode to scanplan: it follows the terrain; the aircraft's height
    # over the ground under its path is held to the ceiling's maximum (the ground at the
    # footprint's far edge, the GSD's, may lie lower)
    assert t["altitude_mode"] == "follow"
    assert t["path_agl_max_m"] <= doc["specification"]["uav"]["max_planned_height_m"] + 1e-6
    assert len(t["strips"]) == doc["specification"]["uav"]["strips"]
    assert all(s["excess_m"] == 0 for s in t["strips"])


@pytest.mark.parametrize("mode", ["strip", "follow"])
def test_strip_and_follow_modes_allow_a_higher_plan(valley, tmp_path, mode):
    p = _copy_example(tmp_path)
    p.write_text(p.read_text(encoding="utf-8").replace(
        'altitude_mode = "auto"', f'altitude_mode = "{mode}"'), encoding="utf-8")
    r = plan_project(load_project(p))
    tr = r.uav.terrain
    assert tr.mode == mode
    if mode == "strip":  # the direction chosen under the mode: along the valley (45°)
        assert r.uav.recommended_height_m >= 110 > valley.uav.recommended_height_m
        assert all(s.altitude_m is not None for s in tr.layout.strips)
        lay = r.uav.job.layout
        assert abs(lay.direction_deg - 45.0) <= 2.0
        chosen = next(a for a in r.uav.alternatives if a.recommended)
        assert chosen.mode == "strip" and chosen.direction == "relief"
        across = next(a for a in r.uav.alternatives if a.mode == "strip"
                      and a.direction == "auto")
        assert across.n_photos == valley.uav.job.layout.n_photos  # 70 m across the valley
        assert lay.n_photos < 0.45 * valley.uav.job.layout.n_photos  # 6,277 vs 16,442
        assert r.uav.job.plan.flight["photos"] == lay.n_photos
    else:
        assert r.uav.recommended_height_m > valley.uav.recommended_height_m
        assert len(tr.layout.notes["waypoints"]) > len(tr.layout.strips)
        ph = tr.layout.photos
        h = r.uav.recommended_height_m
        assert tr.summary()["clearance_min_m"] >= h - 1e-3  # never closer than planned
        # above each centre: within the tolerance plus the rise of the valley's side (at
        # most 0.3) over the photo's stretch of path — the run-in (20 m) and a base at the
        # ends of a strip — and the grid's reach
        above = ph["altitude_m"] - ph["ground_m"]
        assert above.min() >= h - 1e-3 and above.max() <= h + 5.0 + 0.3 * 50.0


def test_a_corrupt_dem_exits_2_naming_the_key_and_writes_nothing(tmp_path):
    p = _copy_example(tmp_path)
    (tmp_path / "dem" / "town-valley.tif").write_bytes(b"II*\x00not a tiff at all")
    out = tmp_path / "out"
    res = CliRunner().invoke(main, ["plan", str(p), "--out", str(out)])
    assert res.exit_code == 2, res.output
    assert "terrain.dem (line" in res.output and "not a readable GeoTIFF" in res.output
    assert "Traceback" not in res.output
    assert not out.exists() or not any(out.iterdir())


def test_a_dem_elsewhere_exits_2_saying_how_much_is_missing(tmp_path):
    shutil.copytree(EXAMPLES / "dem", tmp_path / "dem")
    shutil.copytree(EXAMPLES / "areas", tmp_path / "areas")
    film = (EXAMPLES / "film-town-10000.toml").read_text(encoding="utf-8")
    q = tmp_path / "film.toml"
    q.write_text(film + '\n[terrain]\ndem = "dem/town-valley.tif"\n', encoding="utf-8")
    res = CliRunner().invoke(main, ["plan", str(q)])
    assert res.exit_code == 2
    assert "does not cover the area" in res.output and "km²" in res.output
    assert "100.0 %" in res.output


@pytest.mark.parametrize("line, message", [
    ("ground_elevation_m = [100]", "two finite numbers [lowest, highest]"),
    ('ground_elevation_m = [100, "a"]', "two finite numbers [lowest, highest]"),
    ("ground_elevation_m = [200, 100]", "the first value may not exceed the second"),
    ('altitude_mode = "agl"', "constant, strip, follow"),
    ("follow_tolerance_m = -1", "0 … 500 m"),
    ('vertical_unit = "yd"', "m, ft, us-ft, cm, dm"),
    ("dem_file = 'x.tif'", "unknown key"),
    ("void_fill_radius_m = -5", "0 … 1000 m"),
    ("void_fill_margin_m = 1e9", "0 … 500 m"),
])
def test_bad_terrain_keys_name_the_key(tmp_path, line, message):
    uav = (EXAMPLES / "uav-canon-2000.toml").read_text(encoding="utf-8")
    text = uav + "\n[terrain]\n" + line + ("\nground_elevation_m = [0, 1]"
                                           if "ground_elevation" not in line
                                           and "dem" not in line else "") + "\n"
    p = tmp_path / "p.toml"
    p.write_text(text, encoding="utf-8")
    with pytest.raises(InputError) as e:
        plan_project(load_project(p))
    assert "terrain." in e.value.field and message in e.value.message


def test_a_dem_needs_an_area_on_the_ground(tmp_path):
    uav = (EXAMPLES / "uav-canon-2000.toml").read_text(encoding="utf-8")
    shutil.copytree(EXAMPLES / "dem", tmp_path / "dem")
    p = tmp_path / "p.toml"
    p.write_text(uav + '\n[terrain]\ndem = "dem/town-valley.tif"\n', encoding="utf-8")
    with pytest.raises(InputError, match="needs an area on the ground"):
        plan_project(load_project(p))


def test_a_ground_range_on_the_abstract_block():
    text = (EXAMPLES / "uav-canon-2000.toml").read_text(encoding="utf-8")
    r = plan_project(parse_project(text + "\n[terrain]\nground_elevation_m = [120, 180]\n",
                                   EXAMPLES / "x.toml"))
    tr = r.uav.terrain
    assert tr.ground.source == "range"
    assert tr.max_height_m == pytest.approx(r.uav.job.plan.max_height_m - 60.0)
    assert r.uav.recommended_height_m <= tr.max_height_m


def test_terrain_report_texts_in_both_languages(valley):
    from scanplan.reports.text import format_terrain

    en = format_terrain(valley, "en")[0]
    ru = format_terrain(valley, "ru")[0]
    assert "town-valley.tif" in en and "AMSL" in en and "maximum height over the relief" in en
    assert "Рельеф" in ru and "высота над рельефом" in ru


def test_the_terrain_plot_is_a_deterministic_svg(valley):
    from scanplan.reports.plots import terrain_svg

    a = terrain_svg(valley.uav.terrain, valley.uav.job.plan.max_height_m, "ru")
    b = terrain_svg(valley.uav.terrain, valley.uav.job.plan.max_height_m, "ru")
    assert a == b and a.startswith("<?xml") and "Высота над рельефом" in a
    assert len(a) < 200_000  # per strip, not per photo


def test_the_workbook_has_a_terrain_sheet_per_strip(valley):
    import io

    import openpyxl

    from scanplan.reports.excel import render_xlsx

    u = valley.uav
    raw = render_xlsx(uav=u.job, meta=valley.meta, spec=valley)
    ws = openpyxl.load_workbook(io.BytesIO(raw))["Terrain"]
    rows = list(ws.iter_rows(min_row=2, values_only=True))
    assert len(rows) == len(u.terrain.strips)
    first = u.terrain.strips[0]
    assert rows[0][0] == first.number and rows[0][7] == pytest.approx(first.max_altitude_m)
    flat = plan_project(load_project(EXAMPLES / "uav-town-2000.toml"))
    names = openpyxl.load_workbook(io.BytesIO(render_xlsx(
        uav=flat.uav.job, meta=flat.meta, spec=flat))).sheetnames
    assert "Terrain" not in names


def test_a_pinned_mode_that_costs_far_more_is_a_warning_with_the_saving(valley, tmp_path):
    """Bug: one altitude over the valley needs 16,442 photos where following the terrain
    needs 6,217 — said only in the "for information" box. Now the project's pinned mode
    is kept, and a warning (page 1) names the plan meeting every constraint and the
    flying time it saves, in both languages; with the mode that is the best one pinned,
    nothing is said; strips held across the valley by the project name the better plan."""
    w = next(w for w in valley.warnings if w.code == "plan_choice_costs")
    assert w.severity == "warning"
    assert valley.uav.terrain.mode == "constant"  # the project's choice kept
    assert "following the terrain, lines at 97.6°, 115 m" in w.message
    assert "6,217 photos" in w.message and "16,442 photos" in w.message
    pct = float(w.message.split("costs ")[1].split(" %")[0])
    assert pct >= 25.0
    ru = w.message.text("ru")
    assert "огибание рельефа, маршруты под 97,6°" in ru and "экономия" in ru
    assert "[terrain] altitude_mode" in w.message
    follow = _copy_example(tmp_path)
    follow.write_text(follow.read_text(encoding="utf-8").replace(
        'altitude_mode = "auto"', 'altitude_mode = "follow"'), encoding="utf-8")
    assert "plan_choice_costs" not in [w.code for w in plan_project(
        load_project(follow)).warnings]
    across = tmp_path / "across.toml"
    across.write_text(follow.read_text(encoding="utf-8").replace(
        'altitude_mode = "follow"', 'altitude_mode = "strip"').replace(
        'direction_deg = "auto"', "direction_deg = 135"), encoding="utf-8")
    r = plan_project(load_project(across))
    assert r.uav.job.layout.direction_deg == pytest.approx(135.0)  # the project's own
    w = next(w for w in r.warnings if w.code == "plan_choice_costs")
    assert "[terrain] altitude_mode, [area] direction_deg" in w.message
    assert "following the terrain" in w.message


@pytest.mark.parametrize(("example", "named"), [("uav-town-2000-afs.toml", False),
                                                ("uav-town-valley-2000.toml", True)])
def test_the_highest_agl_names_a_photo_only_over_a_dem(example, named):
    """Bug: with the ground given only as a range of elevations the terminal and the PDF
    said "90–145 m (largest at photo 1)": no photo's ground is known then, and photo 1 was
    an arbitrary one. Over a DEM the photo is the one whose ground is lowest."""
    import html
    import re

    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project
    from scanplan.reports.pdfhtml import render_html
    from scanplan.reports.text import format_terrain

    root = Path(__file__).resolve().parent.parent
    result = plan_project(load_project(root / "examples" / example))
    words = {"en": "largest at photo", "ru": "наибольшая у снимка"}
    for locale, word in words.items():
        line = " ".join(format_terrain(result, locale))
        assert (word in line) is named and "–" in line, line
    page = html.unescape(re.sub(r"<[^>]+>", " ", render_html(
        uav=result.uav.job, meta=result.meta, spec=result)))
    said = words[result.meta.locale]
    assert (said in page) is named
