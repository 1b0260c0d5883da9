"""Issue 11, item 3: ``scanplan plan --out`` writes the mission and GIS files beside
spec.xlsx and spec.pdf in one all-or-nothing transaction.

The reports are rendered as small marked bytes (the transaction is under test, not the
reports); the flight layout is a hand-made one (tests/layouts.py) given to the project's
specification.
"""

from __future__ import annotations

import io
import json
import math
import os
import zipfile
from pathlib import Path

import pytest
from click.testing import CliRunner
from layouts import make_layout

import scanplan.reports.excel as excel_mod
import scanplan.reports.exports as exports_mod
import scanplan.reports.pdf as pdf_mod
from scanplan.cli.main import main
from scanplan.geo.export import format_named
from scanplan.io.targets import check_target, written_by_scanplan

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
UAV = EXAMPLES / "uav-canon-2000.toml"
UAV_FILES = ["flight.geojson", "flight.gpkg", "flight.kml", "mission.plan", "mission.waypoints",
             "photos.csv", "spec.pdf", "spec.xlsx"]



def _names(folder) -> list[str]:
    """The files of an output folder a reader sees (its sets' folder aside)."""
    return sorted(n for n in os.listdir(folder) if not n.startswith("."))

def cli(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


@pytest.fixture()
def work(tmp_path, monkeypatch):
    (tmp_path / "proj.toml").write_bytes(UAV.read_bytes())
    monkeypatch.chdir(tmp_path)

    def xlsx(**kw):
        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w") as zf:
            zf.writestr("docProps/core.xml", "<dc:creator>scanplan test</dc:creator>")
        return buf.getvalue()

    monkeypatch.setattr(excel_mod, "render_xlsx", xlsx)
    monkeypatch.setattr(pdf_mod, "render_pdf", lambda **kw: b"%PDF-1.7\n/Creator (scanplan t)")
    monkeypatch.setenv("SCANPLAN_NO_FORK", "1")  # the PDF is this process's stand-in render
    return tmp_path


@pytest.fixture()
def layout(monkeypatch):
    """The specification's UAV flight over a georeferenced area."""
    lay = make_layout(notch=True)
    monkeypatch.setattr(exports_mod, "spec_layouts", lambda spec: [("uav", lay)])
    return lay


def test_plan_out_writes_the_mission_and_gis_files(work, layout):
    r = cli("plan", "proj.toml", "--out", "out")
    assert r.exit_code == 0, r.output
    assert _names(work / "out") == UAV_FILES
    for name in UAV_FILES:
        assert f"wrote {os.path.join('out', name)}" in r.stderr
        kind = name.rsplit(".", 1)[1]  # a report's kind by name, an export's format record
        kind = kind if kind in ("xlsx", "pdf") else format_named(kind)
        assert written_by_scanplan(work / "out" / name, kind)  # replaced on the next run
    doc = json.loads((work / "out/mission.plan").read_text())
    assert doc["fileType"] == "Plan"
    # the speed of the flight the project plans (layout.speed_ms unset: the [uav] speed)
    assert doc["mission"]["items"][1]["params"][1] == 25.0  # [uav] speed_ms = 25
    r = cli("plan", "proj.toml", "--out", "out")  # a second run replaces its own files
    assert r.exit_code == 0, r.output


def test_batch_names_every_file_after_its_project(work, layout):
    (work / "b.toml").write_bytes(UAV.read_bytes())
    r = cli("plan", "proj.toml", "b.toml", "--out", "out")
    assert r.exit_code == 0, r.output
    names = _names(work / "out")
    assert "proj-mission.plan" in names and "b-flight.kml" in names and "b-photos.csv" in names
    assert "b-mission.waypoints" in names
    assert len([n for n in names if not n.startswith("summary.")]) == 16  # + the batch summary


def test_a_failing_write_leaves_every_previous_file_as_it_was(work, layout, monkeypatch):
    """All or nothing: the KML's rename fails (disk full) after the workbook, the PDF and
    the mission were renamed; every file is put back, nothing new is left."""
    out = work / "out"
    out.mkdir()
    r = cli("plan", "proj.toml", "--out", "out")
    assert r.exit_code == 0, r.output
    before = {n: (out / n).read_bytes() for n in _names(out)}
    real = os.replace

    def replace(src, dst, **kw):
        if str(dst).endswith("flight.kml"):
            raise OSError(28, "No space left on device")
        return real(src, dst, **kw)

    monkeypatch.setattr(os, "replace", replace)
    import scanplan.io.folderset as folderset

    # the journal's all or nothing (a file system without links); the sets' own faults:
    # tests/test_folder_sets.py
    monkeypatch.setattr(folderset, "supported", lambda folder: False)
    monkeypatch.setattr(exports_mod, "spec_layouts",
                        lambda spec: [("uav", make_layout(sorties=1, spacing_m=120.0))])
    r = cli("plan", "proj.toml", "--out", "out")
    assert r.exit_code == 1
    assert "flight.kml" in r.stderr and "No space left on device" in r.stderr
    assert {n: (out / n).read_bytes() for n in _names(out)} == before


def test_a_foreign_file_in_the_way_is_kept_without_force(work, layout):
    out = work / "out"
    out.mkdir()
    (out / "flight.kml").write_text("<kml>my own drawing</kml>")
    r = cli("plan", "proj.toml", "--out", "out")
    assert r.exit_code == 2
    assert "flight.kml' exists and was not written by scanplan" in r.stderr
    assert _names(out) == ["flight.kml"]  # nothing else written either
    r = cli("plan", "proj.toml", "--out", "out", "--force")
    assert r.exit_code == 0, r.output
    assert _names(out) == UAV_FILES


def test_an_abstract_block_writes_only_the_reports(work):
    r = cli("plan", "proj.toml", "--out", "out")
    assert r.exit_code == 0, r.output
    assert _names(work / "out") == ["spec.pdf", "spec.xlsx"]


@pytest.mark.parametrize(("kind", "text"), [
    ("plan", '{"fileType": "Plan", "groundStation": "QGroundControl"}'),
    ("geojson", '{"type": "FeatureCollection", "features": []}'),
    ("csv", "id,x,y\n1,2,3\n"),
    ("kml", '<?xml version="1.0"?><kml/>'),
    ("waypoints", "QGC WPL 110\r\n0\t1\t0\t16\t0\t0\t0\t0\t55.7\t37.6\t150\t1\r\n"),
    ("waypoints", "QGC WPL 110\n# my own mission\n"),
])
def test_exported_kinds_recognise_only_scanplans_files(tmp_path, kind, text):
    path = tmp_path / f"f.{kind}"
    path.write_text(text)
    fmt = format_named(kind)
    assert not written_by_scanplan(path, fmt)
    with pytest.raises(Exception, match="was not written by scanplan"):
        check_target(str(path), "--out", fmt)
    with pytest.raises(Exception, match=rf"does not end in \.{kind}"):
        check_target(str(tmp_path / "f.txt"), "--out", fmt)


def test_town_examples_export_a_mission_that_fires_every_photo(tmp_path):
    """The town examples end to end (the planner's layouts, not hand-made ones): every
    sortie's mission passes the format checks, the camera fires each photographed part's
    photos (the geodesic length of a triggered run over the base, +1, summed over the runs
    of every sortie, is the layout's photo count), GDAL opens KML and GeoJSON with one
    feature per photo centre, and the film scheme has its frames but no mission."""
    from pyproj import Geod
    from test_geo_export import _read_layers, _trigger_runs, check_qgc_plan

    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project
    from scanplan.reports.exports import export_files

    spec = plan_project(load_project(EXAMPLES / "uav-town-2000.toml"))
    layout = spec.uav.layout
    files = export_files(spec, str(tmp_path))
    names = sorted(os.path.basename(p) for p in files)
    plans = [n for n in names if n.endswith(".plan")]
    assert len(plans) == len(layout.sorties) > 1
    geod, fired, runs = Geod(ellps="WGS84"), 0, 0
    for path, (kind, data) in files.items():
        Path(path).write_bytes(data)
        if kind.name == "plan":
            for first, last, dist in _trigger_runs(check_qgc_plan(json.loads(data))):
                _, _, d = geod.inv(first["params"][5], first["params"][4],
                                   last["params"][5], last["params"][4])
                fired += math.floor(d / dist) + 1  # disarmed half a base on
                runs += 1
    assert fired == len(layout.photos)
    assert runs >= sum(len(s.parts) for s in layout.strips)  # long parts re-armed
    kml = _read_layers(tmp_path / "flight.kml")
    assert [len(g) for g, _, _ in kml.values()] == [1, len(layout.strips),
                                                     len(layout.sorties), len(layout.photos)]
    (geojson,) = _read_layers(tmp_path / "flight.geojson").values()
    assert len(geojson[0]) == 1 + len(layout.strips) + len(layout.photos)

    film = plan_project(load_project(EXAMPLES / "film-town-10000.toml"))
    names = sorted(os.path.basename(p) for p in export_files(film, str(tmp_path)))
    assert names == ["film-flight.geojson", "film-flight.gpkg", "film-flight.kml",
                     "film-frames.csv"]


def test_the_turn_keys_say_which_aircraft_flies_the_mission(tmp_path):
    """``[uav] turn_radius_m`` (or ``bank_deg``) is a fixed wing: vehicleType 1 and a 15°
    climb-out; ``turnaround_m`` (or no turn key) a multirotor: vehicleType 2."""
    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project
    from scanplan.reports.exports import export_files

    text = (EXAMPLES / "uav-town-2000.toml").read_text(encoding="utf-8")
    text = text.replace('file = "areas/', f'file = "{EXAMPLES}/areas/')
    for turn, vehicle, pitch in (("turnaround_m = 20", 2, 0.0),
                                 ("turn_radius_m = 60", 1, 15.0)):
        path = tmp_path / "p.toml"
        path.write_text(text.replace("turnaround_m = 20", turn), encoding="utf-8")
        files = export_files(plan_project(load_project(path)), str(tmp_path))
        plan = json.loads(next(d for k, d in files.values() if k.name == "plan"))
        assert plan["mission"]["vehicleType"] == vehicle
        assert plan["mission"]["items"][0]["params"][0] == pitch


def test_a_plan_with_fewer_sorties_removes_the_stale_missions(work, monkeypatch):
    """Bug risk: six sorties yesterday, three today — mission-04.plan … must not stay in
    the folder for a crew to fly. scanplan's own stale exports are removed after the
    write (and said); another program's file of that name is left alone."""
    monkeypatch.setattr(exports_mod, "spec_layouts",
                        lambda spec: [("uav", make_layout(sorties=3))])
    assert cli("plan", "proj.toml", "--out", "out").exit_code == 0
    out = work / "out"
    assert {"mission-01.plan", "mission-02.plan", "mission-03.plan"} <= set(_names(out))
    (out / "mission-07.plan").write_text('{"fileType": "Plan", "groundStation": "QGC"}')
    monkeypatch.setattr(exports_mod, "spec_layouts", lambda spec: [("uav", make_layout())])
    r = cli("plan", "proj.toml", "--out", "out", "-v")  # -v: a line per file removed
    assert r.exit_code == 0, r.output
    assert _names(out) == sorted([*UAV_FILES, "mission-07.plan"])
    for stale in ("mission-02.plan", "mission-02.waypoints"):
        assert f"removed {os.path.join('out', stale)} (left from an earlier plan)" in r.stderr
    monkeypatch.setattr(exports_mod, "spec_layouts",
                        lambda spec: [("uav", make_layout(georeferenced=False))])
    r = cli("plan", "proj.toml", "--out", "out")  # no polygon any more: no files for it
    assert r.exit_code == 0, r.output
    assert _names(out) == ["mission-07.plan", "spec.pdf", "spec.xlsx"]


def test_a_terrain_plan_flies_its_missions_above_sea_level(tmp_path):
    """Over a DEM the mission states MAV_FRAME_GLOBAL (0) and every photo waypoint carries
    the altitude the terrain plan gives its photos (photos.csv altitude_m), not a height
    above a home whose ground is unknown."""
    import pandas as pd

    out = tmp_path / "out"
    res = CliRunner().invoke(main, ["plan", str(EXAMPLES / "uav-town-valley-2000.toml"),
                                    "--out", str(out), "--formats", "missions,gis"])
    assert res.exit_code == 0, res.output
    photos = pd.read_csv(out / "photos.csv")
    altitudes = set(photos["altitude_m"].round(2))
    missions = sorted(out.glob("mission*.plan"))
    assert missions
    for path in missions:
        items = json.loads(path.read_text(encoding="utf-8"))["mission"]["items"]
        positioned = [i for i in items if i["command"] in (16, 22)]
        assert positioned and {i["frame"] for i in positioned} == {0}
        for i in items:
            if i["command"] == 16:
                assert round(i["params"][6], 2) in altitudes
    # and the heights above ground hold at every photo — above the lowest ground of its
    # footprint (the CSV gives 0.01 m: three roundings of at most 0.005 m each)
    assert (photos["altitude_m"] - photos["ground_min_m"] - photos["agl_m"]).abs().max() \
        < 0.016
