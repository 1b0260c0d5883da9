"""The registry of exported formats (geo/export/formats.py): a format added as one record
is written with a flight layout, checked as a target, chosen by ``--formats`` and swept
as a stale file of an earlier run — nothing else names it."""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest
from layouts import make_layout

from scanplan.errors import InputError
from scanplan.geo.export import FORMATS, ExportFormat, MissionOptions, format_named, layout_files
from scanplan.io.targets import check_target, written_by_scanplan
from scanplan.project.file import load_project
from scanplan.project.spec import plan_project
from scanplan.reports.documents import plan_outputs
from scanplan.reports.exports import stale_exports

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


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
    # chosen by its output through plan --out's one path (plan_outputs), for a real plan
    spec = plan_project(load_project(EXAMPLES / "uav-town-2000.toml"))
    out = str(tmp_path / "out")

    def chosen(*formats):
        exports = plan_outputs(spec, out, formats).exports
        return {os.path.basename(path): fmt for path, (fmt, _) in exports.items()}

    routes = {f"route-{i:02d}.route" for i in range(1, len(spec.uav.layout.sorties) + 1)}
    missions, gis = chosen("missions"), chosen("gis")
    assert len(routes) > 1 and routes <= set(missions)
    assert all(missions[name] is with_route for name in routes)
    assert {fmt.output for fmt in missions.values()} == {"missions"}
    assert "flight.kml" in gis and not any(name.endswith(".route") for name in gis)
    assert {fmt.output for fmt in gis.values()} == {"gis"}


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
