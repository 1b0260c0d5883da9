"""The project file parsed once (scanplan/project/model.py).

Every section of every example becomes a frozen, typed record; each range comes from the
input registry's record of its key (narrow a domain in the registry and the model refuses
what it allowed); a bad value is refused with the key, its line and the range, the same
words the planner used before, and through the command line it is exit 2 without a
traceback.
"""

from __future__ import annotations

import dataclasses
import datetime as dt
from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.core.blocks import RELIEF_CLASSES
from scanplan.core.domains import Domain
from scanplan.errors import InputError
from scanplan.norms.schema import GSD_AREAS
from scanplan.project import inputs as I
from scanplan.project.file import load_project, parse_project
from scanplan.project.model import ProjectModel, build_model, field_meta

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))
HEAD = "[map]\nscale = 2000\nrelief_interval_m = 1\n[uav]\ncamera = \"DJI Zenmuse P1 35mm\"\n"


def _model(text: str) -> ProjectModel:
    return build_model(parse_project(text, "p.toml"))


def _error(text: str) -> InputError:
    with pytest.raises(InputError) as exc:
        _model(text)
    return exc.value


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_every_example_parses_into_frozen_sections(path):
    project = load_project(path)
    m = build_model(project)
    assert m.path == project.path and m.name == project.name
    assert m.map.scale == project.get("map", "scale")
    assert m.map.relief_interval_m == project.get("map", "relief_interval_m")
    assert (m.film is None) == (not project.has("film"))
    assert (m.uav is None) == (not project.has("uav"))
    assert (m.terrain is None) == (not project.has("terrain"))
    with pytest.raises(dataclasses.FrozenInstanceError):
        m.map.scale = 1  # type: ignore[misc]
    part = m.uav or m.film
    with pytest.raises(TypeError):  # the job's keywords are read-only too
        part.given["height_m"] = 1  # type: ignore[index]
    if m.terrain is not None and m.terrain.config.dem is not None:
        assert m.terrain.config.dem.is_absolute() or m.terrain.config.dem.parent == \
            project.path.parent / Path(project.get("terrain", "dem")).parent
        assert m.terrain.config.dem.is_file()


def test_the_sections_hold_typed_values():
    m = _model(HEAD + "height_m = 120\n[area]\nwidth_m = 1000\nlength_m = 2000\n"
               "[site]\nlat_deg = 55.7\nlon_deg = 37.6\n[schedule]\nstart_date = 2025-06-01\n"
               'end_date = "2025-06-10"\nturnaround_min = 20\n[terrain]\n'
               "ground_elevation_m = [100, 160]\nrelief_class = \"hilly\"\n"
               "[norms.gsd_limits]\nreason = \"the customer's own table\"\n")
    assert m.uav is not None and m.uav.height_m == 120 and m.uav.given["height_m"] == 120
    assert m.uav.speed_ms == I.by_key("uav", "speed_ms").default
    assert m.area.rectangle == (1000.0, 2000.0) and m.area.extension_bases is None
    assert m.site is not None and (m.site.lat_deg, m.site.lon_deg) == (55.7, 37.6)
    assert m.schedule is not None
    assert (m.schedule.start_date, m.schedule.end_date) == (dt.date(2025, 6, 1),
                                                            dt.date(2025, 6, 10))
    assert m.schedule.turnaround_min == 20.0 and m.schedule.utc_offset_h is None
    assert m.terrain is not None and m.terrain.relief_class == "hilly"
    assert m.terrain.config.ground_range_m == (100.0, 160.0)
    assert m.norms.gsd_limit_reason == "the customer's own table"
    assert m.meta.locale == "en" and m.meta.project == "p"


def test_where_names_the_key_and_its_line():
    m = _model(HEAD + "[site]\nlat_deg = 55\n")
    assert m.where("site", "lat_deg") == "site.lat_deg (line 7)"
    assert m.where("site.lat_deg") == "site.lat_deg (line 7)"
    assert m.at("map", "scale") == "p.toml: map.scale (line 2)"
    assert m.where("schedule", "start_date") == "schedule.start_date"


@pytest.mark.parametrize("text, where, message", [
    ("[site]\nlat_deg = 91\nlon_deg = 0\n", "site.lat_deg (line 7)",
     "must be ≥ -90 and ≤ 90 ° (got 91)"),
    ("[site]\nlat_deg = 0\nlon_deg = -181.5\n", "site.lon_deg (line 8)",
     "must be ≥ -180 and ≤ 180 ° (got -181.5)"),
    ("[schedule]\nutc_offset_h = 15\n", "schedule.utc_offset_h (line 7)",
     "must be ≥ -12 and ≤ 14 h (got 15)"),
    ("[schedule]\nmin_sun_elevation_deg = 90\n", "schedule.min_sun_elevation_deg (line 7)",
     "must be ≥ 0 and ≤ 89.9 ° (got 90)"),
    ("[schedule]\nturnaround_min = 2000\n", "schedule.turnaround_min (line 7)",
     "must be ≥ 0 and ≤ 1440 min (got 2000)"),
    ("[schedule]\nsortie_time_min = 0\n", "schedule.sortie_time_min (line 7)",
     "must be a flight time > 0 and ≤ 1440 min (got 0)"),
    ("[terrain]\nground_elevation_m = [1, 2]\nrelief_class = \"steep\"\n",
     "terrain.relief_class (line 8)",
     "must be one of flat, hilly, mountainous (got 'steep')"),
    ("[norms]\ngsd_area = \"rural\"\n", "norms.gsd_area (line 7)",
     "must be one of general, dense_urban (got 'rural')"),
    ("[area]\nwidth_m = 100\n", "area.length_m (line 6)",
     "is required with the other side of [area]: give both width_m and length_m"),
])
def test_a_value_out_of_its_domain_names_the_key_line_and_range(text, where, message):
    exc = _error(HEAD + text)
    assert exc.field == f"p.toml: {where}"
    assert exc.message == message


def test_two_sortie_lengths_name_both_keys():
    exc = _error(HEAD + "max_flight_time_min = 20\n[schedule]\nsortie_time_min = 30\n")
    assert exc.field == "p.toml: schedule.sortie_time_min (line 8)"
    assert exc.message.startswith("is 30 min but uav.max_flight_time_min (line 6) is 20 min")


def test_the_range_is_the_registry_s(monkeypatch):
    """Narrow a key's domain in the registry and the model refuses what it allowed: the
    range is read from the record, not written where the key is used."""
    text = HEAD + "[site]\nlat_deg = 70\nlon_deg = 10\n"
    assert _model(text).site.lat_deg == 70.0
    monkeypatch.setitem(I.PROJECT_DOMAINS, "lat_deg", Domain(-60, 60, "°"))
    assert _error(text).message == "must be ≥ -60 and ≤ 60 ° (got 70)"
    monkeypatch.setitem(I.PROJECT_DOMAINS, "lat_deg", Domain(-70, 70, "°", hi_open=True))
    assert _error(text).message == "must be ≥ -70 and < 70 ° (got 70)"
    monkeypatch.setitem(I.PROJECT_DOMAINS, "lat_deg", Domain(-60, 60, "°"))
    meta = field_meta("site", "lat_deg")
    assert (meta.domain.lo, meta.domain.hi, meta.unit) == (-60, 60, "°")


def test_the_registry_choices_are_the_planner_s():
    """The choices the model checks are the ones the block rule and Table Б.1 know."""
    assert field_meta("terrain", "relief_class").choices == RELIEF_CLASSES
    assert field_meta("norms", "gsd_area").choices == GSD_AREAS


def test_every_numeric_key_of_site_and_schedule_has_a_registry_domain():
    for section in ("site", "schedule"):
        for r in I.records():
            if r.section == section and r.kind == "number":
                assert I.domain_of(r) is not None, r


@pytest.mark.parametrize("extra, key", [
    ("[site]\nlat_deg = -95\nlon_deg = 0\n", "site.lat_deg (line 7)"),
    ("[schedule]\nturnaround_min = -1\n", "schedule.turnaround_min (line 7)"),
])
def test_the_command_line_exits_2_naming_the_key(tmp_path, extra, key):
    path = tmp_path / "p.toml"
    path.write_text(HEAD + extra, encoding="utf-8")
    result = CliRunner().invoke(main, ["plan", str(path), "--json"])
    assert result.exit_code == 2, result.output
    assert key in result.output and "must be ≥" in result.output
    assert "Traceback" not in result.output


@pytest.mark.parametrize("key, ok, bad, message", [
    ("turnaround_m", 5000.0, 10_001.0, "must be in (0, 10000] (got 10001.0)"),
    ("turn_radius_m", 50_000.0, 0.0, "must be in (0, 50000] (got 0.0)"),
    ("bank_deg", 60.0, 61.0, "must be in (0, 60] (got 61.0)"),
])
def test_the_turn_ranges_of_the_layout_are_the_registry_s(monkeypatch, key, ok, bad, message):
    from scanplan.geo.area import rectangle_area
    from scanplan.project.flightplan import LayoutOptions, check_options

    area = rectangle_area(1000.0, 2000.0)
    check_options(LayoutOptions(**{key: ok}), area, 10.0)
    check_options(LayoutOptions(turnaround_m=0.0), area, 10.0)  # no run past the ends
    with pytest.raises(InputError) as exc:
        check_options(LayoutOptions(**{key: bad}), area, 10.0)
    assert (exc.value.field, exc.value.message) == (key, message)
    d = I.PROJECT_DOMAINS[key]
    monkeypatch.setitem(I.PROJECT_DOMAINS, key, Domain(d.lo, ok / 2, d.unit, d.lo_open))
    with pytest.raises(InputError):  # narrowed in the registry: refused where it is used
        check_options(LayoutOptions(**{key: ok}), area, 10.0)


def test_a_plan_result_pickles_with_its_model():
    """A result (and its parsed project) travels between processes and notebooks as before."""
    import pickle

    from scanplan.project.spec import plan_project

    result = plan_project(load_project(ROOT / "examples" / "uav-town-2000.toml"))
    again = pickle.loads(pickle.dumps(result))
    assert again.project == result.project
    assert again.project.uav.given == result.project.uav.given
    with pytest.raises(TypeError):
        again.project.uav.given.update(height_m=1)
