"""A big plan at a terminal: a progress bar per long stage (click's, with rate and time
left), nothing off a terminal or with -q; the files written said one line per series of
missions (every file with -v); a decimal comma in the options a Russian user types."""

from __future__ import annotations

import io
import os
import sys
from pathlib import Path

import click
import pytest
from click.testing import CliRunner
from layouts import make_layout

from scanplan import progress
from scanplan.cli import console
from scanplan.cli.main import main
from scanplan.cli.outset import file_lines
from scanplan.geo.export import MissionOptions, layout_files

ROOT = Path(__file__).resolve().parent.parent
POLYGON = ROOT / "examples" / "uav-town-2000.toml"  # several sorties


class _Tty(io.StringIO):
    def isatty(self) -> bool:
        return True


class _Recorder:
    """A listener that keeps (label, total, steps done) of every stage."""

    def __init__(self) -> None:
        self.stages: list[list] = []

    def begin(self, label: str, total: int, unit: str) -> None:
        self.stages.append([label, total, 0])

    def advance(self, steps: int) -> None:
        self.stages[-1][2] += steps

    def end(self) -> None:
        pass


@pytest.fixture
def loud(monkeypatch):
    """Neither -q nor -v in force (a test before may have set them)."""
    monkeypatch.setenv("SCANPLAN_VERBOSITY", "0")


def test_progress_shown_on_a_terminal_not_quiet_only(loud, monkeypatch):
    assert console.shows_progress(_Tty())
    assert not console.shows_progress(io.StringIO())  # a pipe, a file, a test runner
    assert not console.shows_progress(object())  # no isatty at all
    monkeypatch.setenv("SCANPLAN_VERBOSITY", "-1")  # -q
    assert not console.shows_progress(_Tty())
    monkeypatch.setenv("SCANPLAN_VERBOSITY", "1")  # -v still shows it
    assert console.shows_progress(_Tty())


def test_no_listener_no_cost():
    with progress.stage("anything", 3, "steps") as step:
        step()
        step(2)  # nobody listens: nothing happens, nothing fails


def test_export_stages_advance_to_their_length():
    layout = make_layout(width_m=1200.0, length_m=600.0, sorties=3)
    rec = _Recorder()
    with progress.listening(rec):
        files = layout_files(layout, mission=MissionOptions(speed_ms=9.0))
    assert [s[0] for s in rec.stages] == ["QGroundControl missions",
                                          "Mission Planner missions", "GIS files"]
    assert all(total == done for _, total, done in rec.stages)
    assert rec.stages[0][1] == 3 and rec.stages[2][1] == 4
    assert sum(n.endswith(".plan") for n in files) == 3


def test_stage_bar_is_clicks_bar_run_to_its_length(loud, monkeypatch):
    tty = _Tty()
    monkeypatch.setattr(sys, "stderr", tty)
    bars = []
    real = click.progressbar

    def spy(*args, **kwargs):
        bars.append(real(*args, **kwargs))
        return bars[-1]

    monkeypatch.setattr(click, "progressbar", spy)
    layout = make_layout(width_m=1200.0, length_m=600.0, sorties=3)
    with progress.listening(console.StageBar(delay_s=0.0)):
        layout_files(layout, mission=MissionOptions(speed_ms=9.0))
    assert len(bars) == 3
    assert all(b.pos == b.length for b in bars)  # each stage's bar ends full
    assert all(b.show_eta for b in bars)
    shown = tty.getvalue()
    assert "QGroundControl missions" in shown and "3/3" in shown and "sorties/s" in shown
    assert "GIS files" in shown and "4/4" in shown
    bars.clear()
    monkeypatch.setenv("SCANPLAN_VERBOSITY", "-1")  # -q at a terminal: no bar
    with console.stage_bars():
        layout_files(layout, mission=MissionOptions(speed_ms=9.0))
    assert bars == []


def test_a_short_stage_draws_nothing(loud, monkeypatch):
    tty = _Tty()
    monkeypatch.setattr(sys, "stderr", tty)
    with progress.listening(console.StageBar(delay_s=60.0)), \
            progress.stage("quick", 5, "steps") as step:
        for _ in range(5):
            step()
    assert tty.getvalue() == ""


def test_file_lines_one_per_series():
    out = os.path.join("out", "")
    names = ["spec.xlsx", "spec.pdf", *(f"mission-{n:03d}.plan" for n in range(1, 242)),
             *(f"mission-{n:03d}.waypoints" for n in range(1, 242)), "flight.kml",
             "photos.csv", *(f"mission-dji-{n:03d}.kmz" for n in range(1, 242))]
    paths = [out + n for n in names]
    lines = file_lines(paths)
    assert lines == [
        out + "spec.xlsx", out + "spec.pdf",
        f"241 QGroundControl missions: {out}mission-001.plan … {out}mission-241.plan",
        f"241 Mission Planner missions: {out}mission-001.waypoints … "
        f"{out}mission-241.waypoints",
        out + "flight.kml", out + "photos.csv",
        f"241 DJI Pilot 2 routes: {out}mission-dji-001.kmz … {out}mission-dji-241.kmz"]
    assert file_lines(paths, every=True) == paths
    # one sortie: its own line; a batch's projects are series of their own
    assert file_lines(["o/mission.plan", "o/a-mission-01.plan", "o/a-mission-02.plan",
                       "o/b-mission-01.plan"]) == [
        "o/mission.plan", "2 QGroundControl missions: o/a-mission-01.plan … "
        "o/a-mission-02.plan", "o/b-mission-01.plan"]


def test_plan_says_a_line_per_series_and_every_file_with_v(tmp_path, loud):
    runner = CliRunner()
    out = tmp_path / "out"
    r = runner.invoke(main, ["plan", str(POLYGON), "--out", str(out), "--formats",
                             "missions"])
    assert r.exit_code == 0, r.output
    plans = sorted(p.name for p in out.iterdir() if p.suffix == ".plan")
    assert len(plans) > 2
    lines = [x for x in r.stderr.splitlines() if x.startswith("wrote")]
    assert lines[0] == (f"wrote {len(plans)} QGroundControl missions: {out / plans[0]} … "
                        f"{out / plans[-1]}")
    assert len(lines) == 3  # the Plan files, the waypoint files, the DJI routes
    assert "[#" not in r.stderr  # no bar off a terminal
    every = runner.invoke(main, ["plan", str(POLYGON), "--out", str(out), "--formats",
                                 "missions", "-v"])
    assert every.exit_code == 0, every.output
    for name in plans:
        assert f"wrote {out / name}\n" in every.stderr


def test_decimal_comma_in_the_direction_and_scan_options():
    runner = CliRunner()
    area = ["uav", "--camera", "dji-zenmuse-p1-35", "--map-scale", "2000", "--relief", "0.5",
            "--area-file", str(ROOT / "examples" / "areas" / "town-uav.kml"), "--json"]
    comma = runner.invoke(main, [*area, "--direction-deg", "12,5"])
    point = runner.invoke(main, [*area, "--direction-deg", "12.5"])
    assert comma.exit_code == 0, comma.output
    assert comma.stdout == point.stdout and '"direction_deg": 12.5' in comma.stdout
    bad = runner.invoke(main, [*area, "--direction-deg", "12,5,1"])
    assert bad.exit_code == 2 and "--direction-deg" in bad.output and "auto" in bad.output
    scan = ["scan", "--map-scale", "2000", "--photo-scale", "10000", "--camera",
            "afa-te-100", "--json"]
    comma = runner.invoke(main, [*scan, "--relief", "0,5", "--resolving-power", "40,5",
                                 "--focal-mm", "152,5"])
    point = runner.invoke(main, [*scan, "--relief", "0.5", "--resolving-power", "40.5",
                                 "--focal-mm", "152.5"])
    assert comma.exit_code == 0, comma.output
    assert comma.stdout == point.stdout


def test_a_scale_with_thousands_commas_is_the_whole_denominator():
    """Bug: ``--photo-scale 1:10,000`` (as English writes a scale) was read with a decimal
    comma, 10.0, and refused as "got 10.0"; a comma before each group of three digits
    groups thousands, any other comma is a decimal comma."""
    from scanplan.norms import parse_scale

    runner = CliRunner()
    base = ["scan", "--relief", "1", "--camera", "afa-te-100", "--json"]
    grouped = runner.invoke(main, [*base, "--map-scale", "1:2,000", "--photo-scale",
                                   "1:10,000"])
    plain = runner.invoke(main, [*base, "--map-scale", "2000", "--photo-scale", "10000"])
    assert grouped.exit_code == 0, grouped.output
    assert grouped.stdout == plain.stdout
    assert parse_scale("1:1,250,000", "map_scale") == 1_250_000
    assert parse_scale("7692,5", "photo_scale") == 7692.5
    assert parse_scale("10,00", "photo_scale") == 10.0  # not groups of three: a decimal


def test_a_terminal_is_told_before_a_write_of_many_files(tmp_path, loud, capsys):
    from scanplan.cli.outset import MANY_FILES, write_set

    files = {str(tmp_path / f"mission-{n:03d}.plan"): b"{}" for n in range(MANY_FILES)}
    said: list[str] = []
    write_set(files, check=lambda: None, sweep=None, say=said.append)
    assert capsys.readouterr().err == ""  # nobody draws the stages: nothing said before
    assert said == [f"wrote {MANY_FILES} QGroundControl missions: {next(iter(files))} … "
                    f"{list(files)[-1]}"]
    with progress.listening(_Recorder()):
        write_set(files, check=lambda: None, sweep=None, say=said.append)
    assert capsys.readouterr().err == f"writing {MANY_FILES} files …\n"
