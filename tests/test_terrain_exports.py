"""Terrain in the exported files (issue 12, item 4), read back with real readers: the photo
CSV (csv), the GeoJSON and KML (GDAL through pyogrio), the QGroundControl missions (json),
the workbook's Frames sheet (openpyxl). Every photo carries its ground elevation, flight
altitude and height above ground; the missions carry a waypoint at every altitude of the
plan, in MAV_FRAME_GLOBAL (0, above mean sea level)."""

from __future__ import annotations

import csv
import glob
import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from pyogrio.raw import read

from scanplan.cli.main import main
from scanplan.project.file import load_project
from scanplan.project.spec import plan_project

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
VALLEY = EXAMPLES / "uav-town-valley-2000.toml"
RELIEF = EXAMPLES / "film-town-relief-10000.toml"
TERRAIN_COLUMNS = ["ground_m", "altitude_m", "agl_m", "ground_min_m", "ground_max_m",
                   "forward_overlap_pct", "side_overlap_pct"]


def _plan_out(project: Path, out: Path, formats: str) -> None:
    """``scanplan plan --out`` writing the ``formats`` a test reads (``--formats`` only
    chooses which of the files are written: scanplan/cli/outputs.py, chosen_exports)."""
    r = CliRunner().invoke(main, ["plan", str(project), "--out", str(out),
                                  "--formats", formats])
    assert r.exit_code == 0, r.output


def _valley(tmp: Path, mode: str) -> Path:
    shutil.copytree(EXAMPLES / "areas", tmp / "areas")
    shutil.copytree(EXAMPLES / "dem", tmp / "dem")
    text = VALLEY.read_text(encoding="utf-8").replace(
        'altitude_mode = "auto"', f'altitude_mode = "{mode}"')
    p = tmp / f"valley-{mode}.toml"
    p.write_text(text, encoding="utf-8")
    return p


def _csv(path: Path) -> dict[str, np.ndarray]:
    with path.open(encoding="utf-8", newline="") as fh:
        rows = list(csv.DictReader(fh))
    return {k: np.array([float(r[k]) if r[k] != "" else np.nan for r in rows])
            for k in rows[0]}


@pytest.fixture(scope="module")
def valley_constant(tmp_path_factory):
    """The valley at one altitude (the example leaves the mode to scanplan)."""
    from terrain_helpers import valley_pinned

    return valley_pinned(tmp_path_factory.mktemp("valley-project"))


@pytest.fixture(scope="module")
def valley_out(tmp_path_factory, valley_constant):
    out = tmp_path_factory.mktemp("valley")
    _plan_out(valley_constant, out, "gis,missions")
    return out


def test_photos_csv_geojson_and_kml_carry_ground_and_height_above_ground(valley_out,
                                                                       valley_constant):
    spec = plan_project(load_project(valley_constant))
    ph = spec.uav.layout.photos
    c = _csv(valley_out / "photos.csv")
    for k in TERRAIN_COLUMNS:
        assert k in c, k
    assert c["photo"].size == len(ph)
    order = np.argsort(ph["photo"])
    for k, dec in (("ground_m", 2), ("altitude_m", 2), ("agl_m", 2), ("ground_min_m", 2)):
        np.testing.assert_allclose(c[k], np.asarray(ph[k])[order], atol=0.5 * 10 ** -dec)
    # the height above the lowest ground seen in the footprint (GSD, L are taken there)
    np.testing.assert_allclose(c["agl_m"], c["altitude_m"] - c["ground_min_m"], atol=0.011)
    assert np.all(c["ground_min_m"] <= c["ground_m"] + 0.01)
    assert np.all(c["ground_max_m"] >= c["ground_m"] - 0.01)
    meta, _fids, _geom, fields = read(str(valley_out / "flight.geojson"))
    names = list(meta["fields"])
    photo = fields[names.index("kind")] == "photo"
    for k in TERRAIN_COLUMNS:
        np.testing.assert_allclose(np.asarray(fields[names.index(k)][photo], float), c[k],
                                   atol=1e-9, err_msg=k)
    meta, _fids, _geom, fields = read(str(valley_out / "flight.kml"), layer="Photo centres")
    names = list(meta["fields"])
    for k in ("ground_m", "altitude_m", "agl_m"):
        kml = np.array([float(v) for v in fields[names.index(k)]])
        np.testing.assert_allclose(kml, c[k], atol=0.051, err_msg=k)  # one decimal


def test_the_constant_mission_is_above_sea_level_at_the_block_altitude(valley_out,
                                                                     valley_constant):
    spec = plan_project(load_project(valley_constant))
    alt = float(spec.uav.layout.photos["altitude_m"][0])
    for f in sorted(glob.glob(str(valley_out / "mission*.plan"))):
        items = json.loads(Path(f).read_text(encoding="utf-8"))["mission"]["items"]
        nav = [i for i in items if i["command"] == 16]
        assert {i["frame"] for i in nav} == {0}  # MAV_FRAME_GLOBAL
        assert {i["AltitudeMode"] for i in nav} == {2}  # QGroundControl: AMSL
        assert all(i["params"][6] == pytest.approx(alt) for i in nav)


@pytest.mark.parametrize("mode", ["strip", "follow"])
def test_strip_and_follow_missions_hold_every_altitude_of_the_plan(tmp_path, mode):
    """Strip: each strip's altitude; follow: a waypoint at every altitude step (the last
    photo of a run and the first of the next), so no step is flown as a straight climb."""
    p = _valley(tmp_path, mode)
    spec = plan_project(load_project(p))
    out = tmp_path / "out"
    _plan_out(p, out, "missions")
    nav = []
    for f in sorted(glob.glob(str(out / "mission*.plan"))):
        items = json.loads(Path(f).read_text(encoding="utf-8"))["mission"]["items"]
        nav += [i for i in items if i["command"] == 16]
    assert {i["frame"] for i in nav} == {0}
    flown = {round(i["params"][6], 3) for i in nav}  # the Plan file keeps 8 decimals
    planned = {round(float(a), 3) for a in spec.uav.layout.photos["altitude_m"]}
    assert planned <= flown  # every altitude of the photos is a waypoint's
    steps = {round(w["altitude_m"], 3) for w in spec.uav.layout.notes["waypoints"]}
    assert steps <= flown
    if mode == "follow":
        # more waypoints than strip ends: the steps inside the strips are there
        assert len(nav) > 4 * len(spec.uav.layout.strips)
    # the trigger runs (set at a cut, cleared at the next) still fire every photo once
    from pyproj import Geod
    from test_geo_export import _trigger_runs, check_qgc_plan
    geod, fired = Geod(ellps="WGS84"), 0
    for f in sorted(glob.glob(str(out / "mission*.plan"))):
        items = check_qgc_plan(json.loads(Path(f).read_text(encoding="utf-8")))
        for first, last, dist in _trigger_runs(items):
            _, _, d = geod.inv(first["params"][5], first["params"][4], last["params"][5],
                               last["params"][4])
            fired += math.floor(d / dist) + 1  # disarmed half a base on
    assert fired == len(spec.uav.layout.photos)


def test_film_frames_carry_their_height_above_ground(tmp_path):
    _plan_out(RELIEF, tmp_path, "gis,xlsx")
    c = _csv(tmp_path / "film-frames.csv")
    # a ground range: the ground under a frame is unknown (empty), its altitude is held
    # over the highest ground (230 m + 0.1 m × 6000) and its height is the largest it may
    # have (over the lowest, 110 m)
    assert np.all(np.isnan(c["ground_m"]))
    np.testing.assert_allclose(c["altitude_m"], 830.0)
    np.testing.assert_allclose(c["agl_m"], 720.0)
    spec = plan_project(load_project(RELIEF))
    np.testing.assert_allclose(c["recognition_p"], spec.film.recommended.recognition_probability,
                               atol=5e-5)
    import openpyxl
    ws = openpyxl.load_workbook(tmp_path / "spec.xlsx")["Frames"]
    head = [v for v in next(ws.iter_rows(values_only=True))]
    assert "Ground elevation, m" in head and "Height above ground, m" in head
    col = head.index("Height above ground, m")
    assert next(ws.iter_rows(min_row=2, max_row=2, values_only=True))[col] == pytest.approx(720)
