"""Mission Planner's waypoint file (``QGC WPL 110``) beside every ``.plan``, read back by
an independent reader: pymavlink's ``mavwp.MAVWPLoader`` (ArduPilot's own Python MAVLink
library, the loader MAVProxy uses). Each item must equal the Plan file's — command, frame,
the four parameters, latitude, longitude, altitude — with the home as item 0.
"""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner
from layouts import make_layout

from scanplan.cli.main import main
from scanplan.geo.export import MissionOptions, format_named, layout_files, render_waypoints
from scanplan.io.targets import written_by_scanplan

mavwp = pytest.importorskip("pymavlink.mavwp")

# MAVLink common.xml
TAKEOFF, SPEED, WAYPOINT, TRIGGER, RTL = 22, 178, 16, 206, 20


def _load(path):
    loader = mavwp.MAVWPLoader()
    n = loader.load(str(path))
    return [loader.wp(i) for i in range(n)]


def _same_mission(plan: dict, wps: list) -> None:
    """The waypoint file's items are the Plan file's, the home first."""
    mission = plan["mission"]
    items = mission["items"]
    assert len(wps) == len(items) + 1
    home = wps[0]
    lat, lon, alt = mission["plannedHomePosition"]
    assert (home.seq, home.current, home.frame, home.command) == (0, 1, 0, WAYPOINT)
    assert (home.x, home.y, home.z) == pytest.approx((lat, lon, alt), abs=1e-8)
    for k, (item, wp) in enumerate(zip(items, wps[1:], strict=True), start=1):
        params = [0.0 if p is None else p for p in item["params"]]
        assert (wp.seq, wp.current, wp.autocontinue) == (k, 0, 1)
        assert (wp.command, wp.frame) == (item["command"], item["frame"]), k
        got = [wp.param1, wp.param2, wp.param3, wp.param4, wp.x, wp.y, wp.z]
        assert got == pytest.approx(params, abs=1e-8), k


def _pairs(files: dict[str, bytes]):
    plans = sorted(n for n in files if n.endswith(".plan"))
    assert plans and sorted(n for n in files if n.endswith(".waypoints")) == [
        n[:-5] + ".waypoints" for n in plans]
    return [(n, n[:-5] + ".waypoints") for n in plans]


@pytest.mark.parametrize("frame", ["relative", "amsl", "terrain"])
def test_waypoint_file_holds_the_plans_items(tmp_path, frame):
    layout = make_layout(sorties=2, agl_m=100.0, ground_m=210.0)
    files = layout_files(layout, mission=MissionOptions(speed_ms=9.0, frame=frame))
    for plan_name, wpl_name in _pairs(files):
        (tmp_path / wpl_name).write_bytes(files[wpl_name])
        plan = json.loads(files[plan_name])
        wps = _load(tmp_path / wpl_name)
        _same_mission(plan, wps)
        commands = [w.command for w in wps[1:]]
        assert commands[:2] == [TAKEOFF, SPEED] and commands[-1] == RTL
        assert commands.count(TRIGGER) % 2 == 0 and WAYPOINT in commands
        frames = {w.frame for w in wps[1:] if w.command == WAYPOINT}
        assert frames == {{"relative": 3, "amsl": 0, "terrain": 10}[frame]}
        assert written_by_scanplan(tmp_path / wpl_name, format_named("waypoints"))


def test_the_file_is_the_format_mission_planner_reads():
    """Mission Planner's WaypointFile.ReadWaypointFile: a header containing "QGC WPL",
    "#" lines skipped, 12 fields per item split on tabs, index 0 the home; numbers with a
    decimal point (it parses with the invariant culture)."""
    files = layout_files(make_layout(), mission=MissionOptions(speed_ms=8.0))
    text = files["mission.waypoints"].decode("ascii")
    lines = text.split("\r\n")
    assert lines[0] == "QGC WPL 110" and lines[1].startswith("# scanplan ") and lines[-1] == ""
    rows = [line.split("\t") for line in lines[2:-1]]
    assert all(len(r) == 12 for r in rows)
    assert [int(r[0]) for r in rows] == list(range(len(rows)))
    assert all("," not in f and math.isfinite(float(f)) for r in rows for f in r)
    assert [r[1] for r in rows] == ["1"] + ["0"] * (len(rows) - 1)


def test_a_complex_item_is_refused():
    with pytest.raises(ValueError, match="not a simple item"):
        render_waypoints({"mission": {"plannedHomePosition": [0, 0, 0], "items": [
            {"type": "ComplexItem", "params": [0] * 7, "command": 16, "frame": 3}]}})


def test_town_examples_write_a_waypoint_file_beside_every_plan(tmp_path):
    """The examples with a polygon (a flat one, a terrain one above sea level) through the
    command line: every mission-NN.plan has its mission-NN.waypoints, item for item."""
    from pathlib import Path

    root = Path(__file__).resolve().parent.parent / "examples"
    for name, frame in (("uav-town-2000", 3), ("uav-town-valley-2000", 0)):
        out = tmp_path / name
        r = CliRunner().invoke(main, ["plan", str(root / f"{name}.toml"), "--out", str(out),
                                      "--formats", "missions",  # the files read here
                                      "-v"])  # -v: a line per file
        assert r.exit_code == 0, r.output
        files = {p.name: p.read_bytes() for p in out.iterdir() if not p.name.startswith(".")}
        pairs = _pairs(files)
        assert len(pairs) > 1
        for plan_name, wpl_name in pairs:
            wps = _load(out / wpl_name)
            _same_mission(json.loads(files[plan_name]), wps)
            assert {w.frame for w in wps[1:] if w.command == WAYPOINT} == {frame}
            assert f"wrote {out / wpl_name}" in r.stderr
