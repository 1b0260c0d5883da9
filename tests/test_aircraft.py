"""The aircraft catalogue and what it sets (docs/aircraft.md).

The catalogue (norms/catalogue/aircraft.csv) names a source for every value it holds, and
its cameras are catalogue cameras; ``[uav] aircraft`` sets the sortie time — the published
flight time less the battery reserve of norms/catalogue/flight-model.csv — a camera carried
by one catalogue aircraft picks it, an unknown sortie time is said (a warning, at the top
of the PDF's first page) instead of one sortie of the whole flight, a plan that needs more
flying days than the crew has is warned about; ``scanplan aircraft list|show`` lists it.
"""

from __future__ import annotations

import csv
import json
import shutil
import subprocess
from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.errors import InputError
from scanplan.norms.aircraft import (
    AIRCRAFT_COLUMNS,
    aircraft,
    all_aircraft,
    carriers_of,
    flight_model_params,
)
from scanplan.norms.store import bundled_catalogue
from scanplan.project.file import parse_project
from scanplan.project.spec import plan_project

ROOT = Path(__file__).resolve().parent.parent
CATALOGUE = ROOT / "norms" / "catalogue"
UAV = """[project]
name = "aircraft"
[map]
scale = 2000
relief_interval_m = 0.5
[uav]
camera = "{camera}"
speed_ms = 12
exposure_s = 0.0005
{extra}
[area]
width_m = {width}
length_m = {length}
"""


def _plan(tmp_path, camera="dji-zenmuse-p1-35", extra="", width=1500, length=2000, tail=""):
    text = UAV.format(camera=camera, extra=extra, width=width, length=length) + tail
    path = tmp_path / "p.toml"
    path.write_text(text, encoding="utf-8")
    return plan_project(parse_project(text, path))


def _codes(result) -> set[str]:
    return {w.code for w in result.warnings}


# --- the catalogue -------------------------------------------------------------------------

def test_the_catalogue_holds_the_aircraft_the_cameras_fly_on():
    ids = set(all_aircraft())
    assert {"dji-m300-rtk", "dji-m350-rtk", "dji-matrice-4e", "dji-mavic-3e",
            "dji-phantom-4-rtk"} <= ids
    cameras, _ = bundled_catalogue()
    for a in all_aircraft().values():
        assert set(a.cameras) <= set(cameras), a.id  # catalogue cameras only
        assert a.source and a.max_flight_time_min and a.flight_time_basis, a.id


def test_every_value_names_its_source_and_blanks_are_said():
    """A value's column is named in the row's source (where it comes from); a blank
    speed or wind limit is said in the note (never invented)."""
    with (CATALOGUE / "aircraft.csv").open(encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    assert tuple(rows[0]) == AIRCRAFT_COLUMNS
    for r in rows:
        for col in ("max_flight_time_min", "max_speed_ms", "max_wind_ms", "cruise_speed_ms"):
            if r[col]:
                assert col in r["source"] or col.split("_")[0] in r["source"].lower(), \
                    (r["id"], col)
        blank = [c for c in ("cruise_speed_ms", "max_speed_ms", "max_wind_ms") if not r[c]]
        if blank:
            assert "not" in r["note"], (r["id"], blank)  # "not in the sources at hand"


def test_the_reserve_rule_is_a_sourced_norm():
    reserve = flight_model_params()["battery_reserve_pct"]
    assert reserve.value == 20 and reserve.status == "practice" and "20" in reserve.source
    # DJI's published 55 min (without payload, to 0 %) less 20 %: 44 min a sortie
    assert aircraft("dji-m350-rtk").usable_flight_time_min() == pytest.approx(44.0)
    for p in flight_model_params().values():
        assert p.source and p.status in {"practice", "assumption", "norm"}, p.name


def test_a_camera_on_one_aircraft_picks_it():
    assert [a.id for a in carriers_of("dji-mavic-3e")] == ["dji-mavic-3e"]
    assert [a.id for a in carriers_of("dji-zenmuse-p1-35")] == ["dji-m300-rtk", "dji-m350-rtk"]
    assert carriers_of("canon-eos-5d-mark-ii-50") == []


# --- what [uav] aircraft sets --------------------------------------------------------------

def test_the_aircraft_sets_the_sortie_time(tmp_path):
    """Before, a P1 plan with no sortie key was one flight of the whole block."""
    r = _plan(tmp_path, extra='aircraft = "dji-m350-rtk"')
    layout = r.uav.layout
    assert layout.notes["max_flight_time_min"] == pytest.approx(44.0)
    assert len(layout.sorties) > 1
    assert all(s.time_s <= 44 * 60 + 1e-6 for s in layout.sorties)
    assert "aircraft_sortie" in _codes(r) and "sortie_time_unknown" not in _codes(r)
    # the key the user gives wins over the aircraft's battery
    r = _plan(tmp_path, extra='aircraft = "dji-m350-rtk"\nmax_flight_time_min = 20')
    assert r.uav.layout.notes["max_flight_time_min"] == 20


def test_the_cameras_one_carrier_sets_it_by_default(tmp_path):
    r = _plan(tmp_path, camera="dji-mavic-3e")
    assert r.uav.layout.notes["max_flight_time_min"] == pytest.approx(36.0)  # 45 − 20 %
    assert "aircraft_sortie" in _codes(r)


def test_an_unknown_aircraft_names_the_key_and_the_catalogue(tmp_path):
    with pytest.raises(InputError) as err:
        _plan(tmp_path, extra='aircraft = "dji-m600"')
    msg = str(err.value)
    assert "uav.aircraft (line" in msg and "dji-m350-rtk" in msg
    res = CliRunner().invoke(main, ["plan", str(tmp_path / "p.toml")])
    assert res.exit_code == 2 and "Traceback" not in res.output


def test_an_unknown_sortie_time_is_said_not_shown_as_one_sortie(tmp_path):
    """The P1 is carried by two catalogue aircraft: no default. The flight is not counted
    as one sortie; a warning says why and what to give (before: "sorties: 1")."""
    r = _plan(tmp_path)
    assert "sortie_time_unknown" in _codes(r)
    w = next(w for w in r.warnings if w.code == "sortie_time_unknown")
    assert w.severity == "warning" and "[uav] aircraft" in w.text("en")
    assert "sorties" not in r.uav.job.plan.flight
    res = CliRunner().invoke(main, ["plan", str(tmp_path / "p.toml")])
    assert res.exit_code == 0
    assert "sorties: 1" not in res.output and "sortie time is unknown" in res.output
    assert "продолжительность вылета неизвестна" in w.text("ru").lower()


@pytest.mark.skipif(shutil.which("pdftotext") is None, reason="needs pdftotext")
def test_the_unknown_sortie_time_heads_the_first_page(tmp_path):
    _plan(tmp_path)
    out = tmp_path / "out"
    res = CliRunner().invoke(main, ["plan", str(tmp_path / "p.toml"), "--out", str(out),
                                    "--formats", "pdf"])
    assert res.exit_code == 0, res.output
    page1 = subprocess.run(["pdftotext", "-f", "1", "-l", "1", "-layout",
                            str(out / "spec.pdf"), "-"], capture_output=True, text=True,
                           check=True).stdout
    assert "sortie time is unknown" in " ".join(page1.split())


def test_more_flying_days_than_the_crew_has_is_a_warning(tmp_path):
    """A 100 × 100 km block with no sortie time: at least its flight time around the clock
    (before: one sortie of 135,185 min, nothing said)."""
    r = _plan(tmp_path, width=100_000, length=100_000)
    codes = _codes(r)
    assert {"sortie_time_unknown", "flying_days_exceeded"} <= codes
    w = next(w for w in r.warnings if w.code == "flying_days_exceeded")
    assert "at least" in w.text("en") and "max_flying_days" in w.text("en")
    small = _plan(tmp_path, extra='aircraft = "dji-m350-rtk"')
    assert "flying_days_exceeded" not in _codes(small)
    # the number is the user's: a long job allowed
    big = _plan(tmp_path, width=100_000, length=100_000,
                tail="[flight]\nmax_flying_days = 3000\n")
    assert "flying_days_exceeded" not in _codes(big)


def test_a_speed_above_the_aircrafts_maximum_is_a_warning(tmp_path):
    r = _plan(tmp_path, camera="dji-phantom-4-rtk")  # its one carrier: 13.9 m/s at most
    assert "aircraft_speed_above_max" not in _codes(r)  # 12 m/s
    text = UAV.format(camera="dji-phantom-4-rtk", extra="", width=1500, length=2000)
    path = tmp_path / "fast.toml"
    path.write_text(text.replace("speed_ms = 12", "speed_ms = 15"), encoding="utf-8")
    fast = plan_project(parse_project(path.read_text(encoding="utf-8"), path))
    assert "aircraft_speed_above_max" in _codes(fast)


def test_the_take_off_point_assumed_is_said(tmp_path):
    text = (ROOT / "examples" / "uav-town-2000.toml").read_text(encoding="utf-8").replace(
        '"areas/', f'"{(ROOT / "examples" / "areas").as_posix()}/')
    path = tmp_path / "town.toml"
    path.write_text(text, encoding="utf-8")
    r = plan_project(parse_project(text, path))
    assert "takeoff_assumed" in _codes(r)
    boundary = r.uav.layout.area.geometry.boundary
    import shapely

    for s in r.uav.layout.sorties:  # on the area's outline, flown there and back
        assert s.takeoff_xy_m is not None and s.transit_m > 0
        assert boundary.distance(shapely.Point(s.takeoff_xy_m)) < 0.01
    path.write_text(text + "\n[flight]\ntakeoff = [38.805, 55.081]\n", encoding="utf-8")
    given = plan_project(parse_project(path.read_text(encoding="utf-8"), path))
    assert "takeoff_assumed" not in _codes(given)


def test_the_town_examples_sorties_come_from_the_m350_battery():
    """examples/uav-town-2000.toml: a DJI P1 on the Matrice 350 RTK — 44-minute sorties
    with the way back (before: 25 min given, no return leg, 4 of 5 sorties over)."""
    from scanplan.project.file import load_project

    r = plan_project(load_project(ROOT / "examples" / "uav-town-2000.toml"))
    layout = r.uav.layout
    assert layout.notes["max_flight_time_min"] == pytest.approx(44.0)
    assert all(s.time_s <= 44 * 60 + 1e-6 for s in layout.sorties)
    assert all(s.transit_m > 0 for s in layout.sorties)
    assert "aircraft_sortie" in _codes(r)


# --- the command ---------------------------------------------------------------------------

def test_aircraft_list_and_show():
    res = CliRunner().invoke(main, ["aircraft", "list"])
    assert res.exit_code == 0, res.output
    assert "dji-m350-rtk" in res.output and "44" in res.output and "20 %" in res.output
    res = CliRunner().invoke(main, ["aircraft", "list", "--camera", "dji-zenmuse-p1-35",
                                    "--json"])
    assert [a["id"] for a in json.loads(res.output)] == ["dji-m300-rtk", "dji-m350-rtk"]
    res = CliRunner().invoke(main, ["aircraft", "show", "dji-phantom-4-rtk", "--json"])
    d = json.loads(res.output)
    assert d["max_speed_ms"] == 13.9 and d["max_wind_ms"] is None
    assert d["flight_model"]["battery_reserve_pct"]["value"] == 20
    res = CliRunner().invoke(main, ["aircraft", "show", "dji-phantom-4-rtk", "--locale", "ru"])
    assert res.exit_code == 0 and "battery_reserve_pct" in res.output
    res = CliRunner().invoke(main, ["aircraft", "show", "nope"])
    assert res.exit_code == 2 and "dji-m350-rtk" in res.output


def test_uav_command_takes_the_aircraft():
    res = CliRunner().invoke(main, ["uav", "--camera", "dji-zenmuse-p1-35", "--height-m",
                                    "100", "--area-m", "2000x2000", "--aircraft",
                                    "dji-m300-rtk", "--json"])
    assert res.exit_code == 0, res.output
    layout = json.loads(res.output)["layout"]
    assert layout["n_sorties"] > 1
    assert all(s["time_s"] <= 44 * 60 + 1e-6 for s in layout["sorties"])
