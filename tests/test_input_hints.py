"""A newcomer's wrong input (the audit of issue 14): exit 2, the key or option named with
what it takes, a hint for a typo, no traceback."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main

_BASE = """[map]
scale = 2000
relief_interval_m = 0.5
[uav]
camera = "dji-zenmuse-p1-35"
"""


def _plan(tmp_path, text: str):
    path = tmp_path / "p.toml"
    path.write_text(text, encoding="utf-8")
    return CliRunner().invoke(main, ["plan", str(path)])


@pytest.mark.parametrize(("extra", "named", "hint"), [
    ("heigth_m = 100\n", "uav.heigth_m (line 6): unknown key", "did you mean height_m?"),
    ("max_flight_time = 20\n", "uav.max_flight_time (line 6)",
     "did you mean max_flight_time_min?"),
    ("[area]\nwidth_m = 100\nlength_m = 100\nmax_flight_time_min = 20\n",
     "area.max_flight_time_min (line 9): unknown key", "it belongs in [uav]"),
])
def test_a_mistyped_key_is_named_with_a_hint(tmp_path, extra, named, hint):
    result = _plan(tmp_path, _BASE + extra)
    assert result.exit_code == 2, result.output
    assert named in result.output and hint in result.output
    assert "takes camera" in result.output or "takes width_m" in result.output
    assert "Traceback" not in result.output


def test_an_unrelated_key_gets_no_guess(tmp_path):
    result = _plan(tmp_path, _BASE + "colour = 3\n")
    assert result.exit_code == 2
    assert "unknown key; [uav] takes" in result.output


@pytest.mark.parametrize(("argv", "named"), [
    (["uav", "--camera", "dji-zenmuse-p1-35", "--height-m", "-5"], "--height-m"),
    (["uav", "--camera", "nosuch", "--height-m", "100"], "--camera"),
    (["plan", "nofile.toml"], "nofile.toml"),
    (["plan", "examples", "--jobs", "0"], "--jobs"),
])
def test_wrong_options_exit_2_naming_the_option(argv, named):
    result = CliRunner().invoke(main, argv)
    assert result.exit_code == 2, result.output
    assert named in result.output and "Traceback" not in result.output


def test_swapped_polygon_outside_the_latitude_range(tmp_path):
    result = _plan(tmp_path, _BASE + "[area]\npolygon = [[38.78, 95.08], [38.80, 95.08], "
                   "[38.80, 95.07], [38.78, 95.07]]\n")
    assert result.exit_code == 2
    assert "latitude 95.08° is outside −90 … 90" in result.output
    assert "give [lon, lat]" in result.output


def test_norms_show_names_its_argument(tmp_path, monkeypatch):
    """``norms show nosuch`` names the argument typed (NAME), not an option --norms the user
    never gave."""
    monkeypatch.setenv("SCANPLAN_NORMS_DIR", str(tmp_path))
    result = CliRunner().invoke(main, ["norms", "show", "nosuch"])
    assert result.exit_code == 2
    assert "NAME: no norm set 'nosuch'" in result.output and "--norms" not in result.output
