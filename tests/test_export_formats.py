"""The registry of exported formats (geo/export/formats.py): a format added as one record
is written with a flight layout, checked as a target, chosen by ``--formats`` and swept
as a stale file of an earlier run — nothing else names it."""

from __future__ import annotations

import re

import pytest
from layouts import make_layout

from scanplan.cli.outputs import chosen_exports
from scanplan.errors import InputError
from scanplan.geo.export import FORMATS, ExportFormat, MissionOptions, format_named, layout_files
from scanplan.io.targets import check_target, written_by_scanplan
from scanplan.reports.exports import stale_exports


def _routes(job, fmt):
    """One file per sortie, as a real mission format writes."""
    if job.mission is None:
        return {}
    n = len(job.layout.sorties)
    return {f"{fmt.stems[0]}-{i:02d}{fmt.suffix}": f"ROUTE scanplan {i}\n".encode()
            for i in range(1, n + 1)}


ROUTE = ExportFormat("route", ".route", "route file",
                     lambda data: data.startswith(b"ROUTE scanplan"),
                     ("route",), "missions", True, _routes)


@pytest.fixture()
def with_route():
    """The record appended to the registry, as a new format is added (and removed after)."""
    FORMATS.append(ROUTE)
    try:
        yield ROUTE
    finally:
        FORMATS.remove(ROUTE)


def test_a_new_format_is_written_after_the_others(with_route):
    layout = make_layout(sorties=3)
    files = layout_files(layout, mission=MissionOptions(speed_ms=10), prefix="A-")
    routes = [name for name in files if name.endswith(".route")]
    assert routes == ["A-route-01.route", "A-route-02.route", "A-route-03.route"]
    assert list(files)[-3:] == routes  # in the registry's order: after the built-in ones
    assert layout_files(layout) and not any(n.endswith(".route") for n in layout_files(layout))


def test_a_new_format_is_a_target_kind(with_route, tmp_path):
    with pytest.raises(InputError, match=r"does not end in \.route; the route file"):
        check_target(str(tmp_path / "x.plan"), "--out", with_route)
    foreign = tmp_path / "route-01.route"
    foreign.write_bytes(b"somebody's route")
    with pytest.raises(InputError, match="was not written by scanplan"):
        check_target(str(foreign), "--out", with_route)
    foreign.write_bytes(b"ROUTE scanplan 1\n")
    check_target(str(foreign), "--out", with_route)
    assert written_by_scanplan(foreign, with_route)


def test_a_new_format_is_swept_as_stale_and_chosen_by_its_output(with_route, tmp_path):
    (tmp_path / "route-03.route").write_bytes(b"ROUTE scanplan 3\n")
    (tmp_path / "film-route.route").write_bytes(b"ROUTE scanplan\n")
    (tmp_path / "route-04.route").write_bytes(b"a route of another program")  # kept
    (tmp_path / "my-route.route").write_bytes(b"ROUTE scanplan\n")  # not an export's name
    assert stale_exports(str(tmp_path), {str(tmp_path / "route-01.route")}) == [
        str(tmp_path / "film-route.route"), str(tmp_path / "route-03.route")]
    exports = {"out/route-01.route": (with_route, b"ROUTE scanplan 1\n"),
               "out/flight.kml": (format_named("kml"), b"<kml/>")}
    assert list(chosen_exports(exports, ("missions",))) == ["out/route-01.route"]
    assert list(chosen_exports(exports, ("gis",))) == ["out/flight.kml"]


def test_every_format_has_a_distinct_name_suffix_and_file_names():
    assert len({f.name for f in FORMATS}) == len({f.suffix for f in FORMATS}) == len(FORMATS)
    assert {f.output for f in FORMATS} == {"missions", "gis"}
    names = ["mission.plan", "mission-07.plan", "mission-02.waypoints", "flight.kml",
             "flight.geojson", "flight.gpkg", "photos.csv", "frames.csv", "mission-dji.kmz",
             "mission-dji-10.kmz"]
    for name in names:
        assert sum(bool(re.fullmatch(f.name_pattern(), name)) for f in FORMATS) == 1, name
    for name in ["flight-01.kml", "mission.kmz", "photos-01.csv", "summary.csv"]:
        assert not any(re.fullmatch(f.name_pattern(), name) for f in FORMATS), name
    with pytest.raises(KeyError):
        format_named("xlsx")  # a report, not an exported format
