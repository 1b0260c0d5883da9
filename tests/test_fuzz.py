"""Fuzz suite (hypothesis): the command line and the Python API under generated input.

What it proves, for every generated case:

- **no traceback, no crash** — the exit code is 0 or 2, never 1 (1 is a runtime failure);
  the API raises :class:`~scanplan.errors.InputError` or nothing;
- **invalid input exits 2 and names the field** — each case injects one known-bad value
  into an otherwise valid command, project file or norm table, and the message must name
  that option, that ``section.key`` with its line, or that cell;
- **valid extreme input gives finite results** — 1:500 … 1:25000 maps with 1:100000
  photos, 1 µm pixels, 2 km flying heights: every number in the JSON is finite, or the
  result says plainly that it is not feasible (a warning code, a null maximum).

Profiles: the default (fast, CI) runs well over 1,000 generated inputs (the counts are
printed at the end of the pytest run); ``SCANPLAN_FUZZ=long`` multiplies every budget by
``SCANPLAN_FUZZ_FACTOR`` (default 20) for an on-demand soak.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import re
import tempfile
from collections import Counter
from pathlib import Path

import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from scanplan.cli.main import OPTION_NAMES, main
from scanplan.errors import InputError
from scanplan.project.file import KEYS
from scanplan.project.jobs import scan_job, uav_job

LONG = os.environ.get("SCANPLAN_FUZZ") == "long"
FACTOR = int(os.environ.get("SCANPLAN_FUZZ_FACTOR", "20")) if LONG else 1

COUNTS: Counter[str] = Counter()
"""Generated inputs per family in this run (printed by conftest's terminal summary)."""


def budget(n: int) -> settings:
    """Hypothesis settings with ``n`` examples (times the long-profile factor)."""
    return settings(max_examples=n * FACTOR, deadline=None, derandomize=not LONG,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                           HealthCheck.filter_too_much])


def invoke(args: list[str]):
    """Run the CLI; assert the universal oracle (no traceback, never exit 1)."""
    r = CliRunner().invoke(main, args, catch_exceptions=True)
    text = r.output
    assert "Traceback" not in text, (args, text)
    assert r.exit_code in (0, 2), (args, r.exit_code, text, r.exception)
    return r


def finite_json(text: str) -> object:
    """Parse JSON, refusing NaN/Infinity (``allow_nan=False`` is the contract)."""
    def bad(token: str) -> float:
        raise AssertionError(f"non-finite number {token} in JSON output")
    return json.loads(text, parse_constant=bad)


def numbers(doc: object):
    """Every number in a JSON document."""
    if isinstance(doc, dict):
        for v in doc.values():
            yield from numbers(v)
    elif isinstance(doc, list):
        for v in doc:
            yield from numbers(v)
    elif isinstance(doc, int | float) and not isinstance(doc, bool):
        yield doc


def named(text: str, *names: str) -> bool:
    """Whether the message names one of ``names`` (an option, key or cell)."""
    return any(n in text for n in names)


# ----------------------------------------------------------------------------------------
# Strategies: valid (including extreme) values, formatted as a user would type them
# ----------------------------------------------------------------------------------------

TABLE_MAP_SCALES = (2000, 5000, 10000, 25000)
"""Map scales with a smallest object in the bundled norm table (seed 001 Table 3); other
scales (1:500, 1:1000) need the object size given."""
MAP_SCALES = (500, 1000, *TABLE_MAP_SCALES)


def log_uniform(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(math.log(lo), math.log(hi)).map(lambda x: float(f"{math.exp(x):.6g}"))


def with_edges(lo: float, hi: float) -> st.SearchStrategy[float]:
    """Log-uniform in [lo, hi], with the edges themselves often."""
    return st.one_of(st.sampled_from([lo, hi]), log_uniform(lo, hi))


def num(x: float) -> str:
    return f"{x:g}"


scale_text = st.sampled_from(["{:g}", "1:{:g}"])


@st.composite
def scan_args(draw) -> list[str]:
    """A valid `scanplan scan` command, often at the edges of what is valid."""
    map_scale = draw(st.one_of(st.sampled_from(MAP_SCALES), with_edges(500, 25000)))
    photo = draw(st.lists(with_edges(500, 100_000), min_size=1, max_size=4))
    args = ["scan", "--map-scale", draw(scale_text).format(map_scale),
            "--relief", num(draw(with_edges(0.1, 100)))]
    for mc in photo:
        args += ["--photo-scale", draw(scale_text).format(mc)]
    if draw(st.booleans()):
        args += ["--camera", draw(st.sampled_from(["afa-te-100", "rc30-153", "rmk-top-15"]))]
        if draw(st.booleans()):
            args += ["--resolving-power", num(draw(with_edges(5, 500)))]
    else:
        w, h = draw(with_edges(20, 300)), draw(with_edges(20, 300))
        args += ["--focal-mm", num(draw(with_edges(20, 1000))), "--frame-mm",
                 f"{w:g}x{h:g}", "--resolving-power", num(draw(with_edges(5, 500)))]
    if map_scale not in TABLE_MAP_SCALES or draw(st.booleans()):
        args += ["--object-size-m", num(draw(with_edges(0.01, 50)))]
    if draw(st.booleans()):
        args += ["--shape", draw(st.sampled_from(["circle", "rectangle", "angle", "square",
                                                  "wall"]))]
    if draw(st.booleans()):
        args += ["--probability", num(draw(st.floats(0.05, 0.99)))]
    if draw(st.booleans()):
        args += ["--overlap-pct", num(draw(st.floats(50, 95)))]
    if draw(st.booleans()):
        args += ["--height-formula", draw(st.sampled_from(["instruction", "parallax"]))]
    if draw(st.booleans()):
        args += ["--pr-coefficient", num(draw(st.floats(0.1, 1.0)))]
    if draw(st.booleans()):
        args += ["--scanner", "photoscan-td"]
    for px in draw(st.lists(with_edges(1, 100), max_size=2)):
        args += ["--pixel-um", num(px)]
    if draw(st.booleans()):
        args += ["--bands", str(draw(st.integers(1, 16))),
                 "--bit-depth", draw(st.sampled_from(["8", "16"]))]
    return args


@st.composite
def uav_args(draw) -> list[str]:
    """A valid `scanplan uav` command, often at the edges (1 µm pixels, 2 km heights)."""
    args = ["uav", "--height-m", num(draw(with_edges(20, 2000)))]
    if draw(st.booleans()):
        args += ["--camera", draw(st.sampled_from(
            ["canon-eos-5d-mark-ii-50", "dji-zenmuse-p1-35", "dji-mavic-3e",
             "sony-rx1r-ii-wingtra", "phase-one-ixm-100-rsm80"])),
                 "--f-number", num(draw(st.floats(1.4, 16)))]
    else:
        args += ["--pixel-um", num(draw(with_edges(1, 20))),
                 "--focal-mm", num(draw(with_edges(4, 300))),
                 "--sensor-mm", f"{draw(with_edges(4, 60)):g}x{draw(with_edges(3, 60)):g}",
                 "--f-number", num(draw(with_edges(1.4, 22)))]
    if draw(st.booleans()):
        mk = draw(st.sampled_from(TABLE_MAP_SCALES))
        args += ["--map-scale", str(mk), "--relief", num(draw(with_edges(0.1, 50)))]
        if draw(st.booleans()):
            args += ["--object-size-m", num(draw(with_edges(0.01, 50)))]
        if draw(st.booleans()):
            args += ["--height-tolerance-pct", num(draw(st.floats(0, 60)))]
    if draw(st.booleans()):
        args += ["--speed-ms", num(draw(with_edges(1, 80))),
                 "--exposure-s", num(draw(with_edges(1e-5, 0.01)))]
    if draw(st.booleans()):
        args += ["--overlap-pct", num(draw(st.floats(50, 95))),
                 "--side-overlap-pct", num(draw(st.floats(10, 90)))]
    if draw(st.booleans()):
        r_max = draw(st.floats(0.05, 1.0))
        args += ["--r-max", num(r_max), "--r-min", num(draw(st.floats(0, 1)) * r_max)]
    if draw(st.booleans()):
        args += ["--random-speed-ms", num(draw(st.floats(0, 5))),
                 "--roll-rate", num(draw(st.floats(0, 0.5)))]
    if draw(st.booleans()):
        args += ["--area-m", f"{draw(with_edges(10, 50_000)):g}x{draw(with_edges(10, 50_000)):g}"]
    if draw(st.booleans()):
        args += ["--roll-deg", num(draw(st.floats(-30, 30))),
                 "--pitch-deg", num(draw(st.floats(-30, 30)))]
    return args


# ----------------------------------------------------------------------------------------
# Known-bad values, per option: each must give exit 2 naming the option
# ----------------------------------------------------------------------------------------

NOT_A_NUMBER = ["abc", "", "nan", "inf", "-inf", "1,5.3", "0x10", "1e999", "1.2.3", "--"]
BAD_SCALE = [*NOT_A_NUMBER, "0", "-2000", "1:0", "1:-5", "1:", ":2000", "2:2000", "50",
             "2000000", "1:1e400"]
BAD_POSITIVE = [*NOT_A_NUMBER, "0", "-1", "-0.0", "1e308"]

SCAN_BAD: dict[str, list[str]] = {
    "--map-scale": BAD_SCALE,
    "--photo-scale": BAD_SCALE,
    "--relief": [*BAD_POSITIVE, "1e-5", "5000"],
    "--resolving-power": [*BAD_POSITIVE, "0.5", "1e5"],
    "--overlap-pct": [*NOT_A_NUMBER, "-1", "100", "150", "1e308", "0.8"],
    "--object-size-m": [*BAD_POSITIVE, "1e-9", "1e9"],
    "--probability": [*NOT_A_NUMBER, "0", "1", "1.5", "-0.1"],
    "--pr-coefficient": [*BAD_POSITIVE, "3"],
    "--shape": ["hexagon", "", "circle;rm -rf", "../circle", "ЦИЛИНДР"],
    "--height-formula": ["", "x", "INSTRUCTION;", "parallax "],
    "--rounding": ["", "x", "0.53"],
    "--scanner": ["nope", "../x", "", "photoscan-td/../../etc"],
    "--pixel-um": [*BAD_POSITIVE, "0.01", "1e6"],
    "--bands": ["0", "17", "abc", "1.5", "-1", ""],
    "--bit-depth": ["12", "abc", "", "8.0"],
    "--norms": ["no-such-set", "../../etc", "/dev/null", "", "./", "/nonexistent/set"],
    "--locale": ["de", "", "EN", "ru_RU"],
    "--xlsx": ["/nonexistent-folder/report.xlsx"],
    "--pdf": ["/nonexistent-folder/report.pdf"],
}
# camera / frame are exclusive alternatives: tested on their own
CAMERA_BAD = ["nope", "../../etc/passwd", "", "dji-mavic-3e", "AFA-TE-100 ", "\x00"]
FRAME_BAD = ["0x230", "abc", "230x", "x", "-230x230", "230x230x230", "nanxnan", "1e9x1e9",
             "230×230×", "230 x", "infx230"]

UAV_BAD: dict[str, list[str]] = {
    "--height-m": [*BAD_POSITIVE, "0.5", "1e6"],
    "--height-tolerance-pct": [*NOT_A_NUMBER, "-1", "100", "1e9"],
    "--speed-ms": [*NOT_A_NUMBER, "-1", "1e6"],
    "--exposure-s": [*BAD_POSITIVE, "100"],
    "--overlap-pct": [*NOT_A_NUMBER, "-5", "100", "101", "0.8"],
    "--side-overlap-pct": [*NOT_A_NUMBER, "-5", "100", "0.6"],
    "--f-number": [*BAD_POSITIVE, "0.1", "500"],
    "--r-max": [*NOT_A_NUMBER, "-0.1", "1.5"],
    "--random-speed-ms": [*NOT_A_NUMBER, "-1", "1e9"],
    "--roll-rate": [*NOT_A_NUMBER, "-1", "1e9"],
    "--pitch-rate": [*NOT_A_NUMBER, "-1", "1e9"],
    "--yaw-rate": [*NOT_A_NUMBER, "-1", "1e9"],
    "--area-m": ["abc", "0x100", "100x", "-1x100", "1e9x1e9", "nanx5", ""],
    "--roll-deg": [*NOT_A_NUMBER, "90", "-95", "1e9"],
    "--pitch-deg": [*NOT_A_NUMBER, "90", "-91", "1e9"],
    "--map-scale": BAD_SCALE,
    "--object-size-m": [*BAD_POSITIVE, "1e9"],
    "--probability": [*NOT_A_NUMBER, "0", "1", "7"],
    "--shape": ["hexagon", ""],
    "--norms": ["no-such-set", "../../etc", ""],
}
UAV_CAMERA_BAD = ["nope", "../x", "", "rc30-153"]
UAV_MANUAL_BAD = {
    "--pixel-um": [*BAD_POSITIVE, "0.01", "1e4"],  # 500 µm is inside the domain (≤ 1000)
    "--focal-mm": [*BAD_POSITIVE, "0.1", "1e5"],
    "--sensor-mm": ["abc", "0x24", "36x", "-36x24", "nanx24", "1e9x24", ""],
}


def replace_option(args: list[str], option: str, value: str) -> list[str]:
    """``args`` with ``option`` set to ``value`` (the first occurrence replaced, or added)."""
    out = list(args)
    if option in out:
        i = out.index(option)
        out[i + 1] = value
        # a repeated option (--photo-scale, --pixel-um): keep just the bad one first
        return out
    return [*out, option, value]


def drop_option(args: list[str], option: str) -> list[str]:
    out, skip = [], False
    for a in args:
        if skip:
            skip = False
            continue
        if a == option:
            skip = True
            continue
        out.append(a)
    return out


# ----------------------------------------------------------------------------------------
# The command line
# ----------------------------------------------------------------------------------------

def _mk(args: list[str]) -> str:
    return args[args.index("--map-scale") + 1]


@budget(150)
@given(args=scan_args())
def test_scan_valid_extremes_give_finite_results(args):
    """Valid extreme film input: exit 0, every number finite, binding = the smallest pixel."""
    COUNTS["cli scan, valid extreme"] += 1
    r = invoke([*args, "--json"])
    assert r.exit_code == 0, (args, r.output)
    doc = finite_json(r.stdout)
    assert doc["scenarios"]
    for s in doc["scenarios"]:
        pixels = {cid: c["pixel_um"] for cid, c in s["constraints"].items()}
        assert s["binding"] in pixels
        assert s["scan_pixel_um"] == pytest.approx(min(pixels.values()))
        assert 0 < s["scan_pixel_um"] < math.inf


@budget(250)
@given(args=scan_args(), data=st.data())
def test_scan_one_bad_option_exits_2_naming_it(args, data):
    """One bad value among valid ones: exit 2, and the message names that option."""
    option = data.draw(st.sampled_from(sorted(SCAN_BAD)), label="option")
    value = data.draw(st.sampled_from(SCAN_BAD[option]), label="value")
    COUNTS["cli scan, invalid option"] += 1
    r = invoke(replace_option(args, option, value))
    assert r.exit_code == 2, (option, value, r.output)
    assert named(r.output, option), (option, value, r.output)


@budget(60)
@given(args=scan_args(), data=st.data())
def test_scan_bad_camera_or_frame_exits_2(args, data):
    """Camera id, focal length and frame size: exit 2 naming the one at fault."""
    COUNTS["cli scan, invalid camera/frame"] += 1
    args = drop_option(drop_option(drop_option(args, "--camera"), "--focal-mm"), "--frame-mm")
    if "--resolving-power" not in args:
        args += ["--resolving-power", "40"]
    which = data.draw(st.sampled_from(["--camera", "--frame-mm", "--focal-mm"]))
    if which == "--camera":
        value = data.draw(st.sampled_from(CAMERA_BAD))
        bad = [*args, "--camera", value]
    elif which == "--frame-mm":
        value = data.draw(st.sampled_from(FRAME_BAD))
        bad = [*args, "--focal-mm", "153", "--frame-mm", value]
    else:
        value = data.draw(st.sampled_from([*BAD_POSITIVE, "0.5", "1e5"]))
        bad = [*args, "--focal-mm", value, "--frame-mm", "230x230"]
    r = invoke(bad)
    assert r.exit_code == 2, (which, value, r.output)
    assert named(r.output, which), (which, value, r.output)


def _corner_at_horizon(args: list[str]) -> bool:
    """Whether a corner ray of the custom frame in ``args``, tilted by its roll and pitch,
    points at or above the horizon (computed here independently of the engine)."""
    opts = dict(zip(args[1::2], args[2::2], strict=False))
    if "--sensor-mm" not in opts or "--roll-deg" not in opts:
        return False
    w, h = (float(v) for v in opts["--sensor-mm"].split("x"))
    f = float(opts["--focal-mm"])
    r, p = math.radians(float(opts["--roll-deg"])), math.radians(float(opts["--pitch-deg"]))
    for sx in (-1, 1):
        for sy in (-1, 1):
            x, y, z = sx * w / 2, sy * h / 2, -f
            # pitch turns the along-track axis y, roll the across-track axis x (W x H = x × y)
            y, z = y * math.cos(p) - z * math.sin(p), y * math.sin(p) + z * math.cos(p)
            x, z = x * math.cos(r) + z * math.sin(r), -x * math.sin(r) + z * math.cos(r)
            if z >= 0:
                return True
    return False


@budget(60)
@given(args=uav_args())
def test_uav_valid_extremes_give_finite_or_not_feasible(args):
    """Valid extreme UAV input: exit 0; every number finite; an unresolvable image says so."""
    COUNTS["cli uav, valid extreme"] += 1
    r = invoke([*args, "--json"])
    if r.exit_code == 2 and "horizon" in r.output and _corner_at_horizon(args):
        return  # a wide frame tilted so far that a corner sees the sky: refused, named
    assert r.exit_code == 0, (args, r.output)
    doc = finite_json(r.stdout)
    assert doc["gsd_m"] > 0
    codes = {w["code"] for w in doc["warnings"]}
    if doc["resolving_power_lpmm"] is None or doc["ground_resolution_m"] is None:
        assert "not_resolvable" in codes, (args, codes)
    else:
        assert doc["ground_resolution_m"] >= doc["gsd_m"] * (1 - 1e-9)
    if "--map-scale" in args:
        assert "max_height_m" in doc
        if doc["max_height_m"] is None:
            assert codes, (args, "no maximum height and no warning saying why")


@budget(200)
@given(args=uav_args(), data=st.data())
def test_uav_one_bad_option_exits_2_naming_it(args, data):
    COUNTS["cli uav, invalid option"] += 1
    option = data.draw(st.sampled_from(sorted(UAV_BAD)), label="option")
    value = data.draw(st.sampled_from(UAV_BAD[option]), label="value")
    if (option in ("--object-size-m", "--probability", "--shape", "--map-scale")
            and "--map-scale" not in args):
        args = [*args, "--map-scale", "2000", "--relief", "0.5"]
    r = invoke(replace_option(args, option, value))
    assert r.exit_code == 2, (option, value, r.output)
    assert named(r.output, option), (option, value, r.output)


@budget(60)
@given(args=uav_args(), data=st.data())
def test_uav_bad_camera_or_sensor_exits_2(args, data):
    COUNTS["cli uav, invalid camera/sensor"] += 1
    args = [a for a in args]
    for opt in ("--camera", "--pixel-um", "--focal-mm", "--sensor-mm"):
        args = drop_option(args, opt)
    if data.draw(st.booleans()):
        option, value = "--camera", data.draw(st.sampled_from(UAV_CAMERA_BAD))
        bad = [*args, "--camera", value]
    else:
        option = data.draw(st.sampled_from(sorted(UAV_MANUAL_BAD)))
        value = data.draw(st.sampled_from(UAV_MANUAL_BAD[option]))
        manual = {"--pixel-um": "6.4", "--focal-mm": "50", "--sensor-mm": "36x24"}
        manual[option] = value
        bad = [*args, *[x for kv in manual.items() for x in kv]]
    r = invoke(bad)
    assert r.exit_code == 2, (option, value, r.output)
    assert named(r.output, option), (option, value, r.output)


@budget(40)
@given(junk=st.lists(st.text(min_size=0, max_size=12), min_size=1, max_size=6),
       command=st.sampled_from(["scan", "uav", "plan", "norms", "cameras", "bogus"]))
def test_random_words_never_crash(junk, command):
    """Arbitrary words after any command: usage error (2) or a result (0), no traceback."""
    COUNTS["cli, random words"] += 1
    invoke([command, *junk])


# ----------------------------------------------------------------------------------------
# The Python API: InputError with the input's name, never another exception
# ----------------------------------------------------------------------------------------

API_BAD_NUMBERS = [0, -1, -0.0, math.nan, math.inf, -math.inf, 1e308, 1e-320, True, "12",
                   [1], {"a": 1}, complex(1, 1)]  # None is "not given": the default

SCAN_BASE = dict(map_scale=2000, relief_interval_m=1.0, photo_scales=[10000],
                 camera="afa-te-100", resolving_power_lpmm=40)
SCAN_API_FIELDS = {
    "map_scale": "map_scale", "relief_interval_m": "relief_interval_m",
    "resolving_power_lpmm": "resolving_power_lpmm",
    "forward_overlap_pct": "forward_overlap_pct", "object_size_m": "object_size_m",
    "probability": "probability", "pr_coefficient": "pr_coefficient",
    "photo_scales": "photo_scale", "pixel_um": "pixel_um", "bands": "bands",
}
UAV_BASE = dict(camera="canon-eos-5d-mark-ii-50", f_number=8, height_m=300, map_scale=2000,
                relief_interval_m=0.5)
UAV_API_FIELDS = {
    "height_m": "height_m", "f_number": "f_number", "speed_ms": "speed_ms",
    "exposure_s": "exposure_s", "forward_overlap_pct": "forward_overlap_pct",
    "side_overlap_pct": "side_overlap_pct", "height_tolerance_pct": "height_tolerance_up_pct",
    "map_scale": "map_scale", "relief_interval_m": "relief_interval_m",
    "object_size_m": "object_size_m", "probability": "probability",
    "random_speed_ms": "random_speed_ms", "roll_rate_rad_s": "roll_rate_rad_s",
    "r_max": "r_max", "roll_deg": "roll_deg", "shift_factor": "shift_factor",
    "threshold_k0": "threshold_k0", "pitch_deg": "pitch_deg",
}


def _api_value(name: str, value: object) -> object:
    if name in ("photo_scales", "pixel_um"):
        return [value]
    return value


def _valid_by_accident(name: str, value: object) -> bool:
    """Values of the bad list that happen to be valid for this particular input."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return False
    zero_ok = ("speed_ms", "random_speed_ms", "roll_rate_rad_s", "height_tolerance_pct",
               "roll_deg", "pitch_deg")
    tiny_ok = (*zero_ok, "r_max", "threshold_k0", "shift_factor")
    if name in zero_ok and value == 0:
        return True
    if name in tiny_ok and value == 1e-320:
        return True
    return name in ("roll_deg", "pitch_deg") and value == -1


@budget(200)
@given(data=st.data())
def test_api_scan_bad_values_raise_input_error(data):
    name = data.draw(st.sampled_from(sorted(SCAN_API_FIELDS)))
    value = data.draw(st.sampled_from(API_BAD_NUMBERS))
    assume(not _valid_by_accident(name, value))
    COUNTS["api scan_job, invalid value"] += 1
    with pytest.raises(InputError) as exc:
        scan_job(**{**SCAN_BASE, name: _api_value(name, value)})
    assert exc.value.field in (SCAN_API_FIELDS[name], name), (name, value, exc.value)


@budget(120)
@given(data=st.data())
def test_api_uav_bad_values_raise_input_error(data):
    name = data.draw(st.sampled_from(sorted(UAV_API_FIELDS)))
    value = data.draw(st.sampled_from(API_BAD_NUMBERS))
    assume(not _valid_by_accident(name, value))
    COUNTS["api uav_job, invalid value"] += 1
    with pytest.raises(InputError) as exc:
        uav_job(**{**UAV_BASE, name: value})
    assert exc.value.field in (UAV_API_FIELDS[name], name), (name, value, exc.value)


def test_option_names_cover_every_api_field():
    """Every field the API can name maps to an option the user typed."""
    for field in {*SCAN_API_FIELDS.values(), *UAV_API_FIELDS.values()}:
        assert field in OPTION_NAMES, field


# ----------------------------------------------------------------------------------------
# Project files
# ----------------------------------------------------------------------------------------

FILM_PROJECT = """\
[project]
name = "Fuzz"
locale = "en"

[map]
scale = 2000
relief_interval_m = 1.0

[film]
camera = "afa-te-100"
resolving_power_lpmm = 40
forward_overlap_pct = 60
photo_scales = [6000, 8000, 10000]
scanner = "photoscan-td"

[area]
width_m = 2000
length_m = 3000
"""

UAV_PROJECT = """\
[project]
name = "Fuzz UAV"

[map]
scale = 2000
relief_interval_m = 0.5

[uav]
camera = "canon-eos-5d-mark-ii-50"
f_number = 8
height_m = 300
height_tolerance_pct = 40
speed_ms = 25

[uav.target]
r_max = 0.3
r_min = 0.1

[uav.motion]
shift_factor = 0.65

[area]
width_m = 2000
length_m = 3000
"""

BAD_TOML_VALUES = ['"abc"', "true", "[1, 2]", "{ a = 1 }", "-1", "0", "nan", "inf", "-inf",
                   "1e400", '""', "1979-05-27", '"1:0"', "1e308", "-0.0"]


def _set_key(text: str, section: str, key: str, value: str) -> str:
    """Set ``key = value`` in ``[section]`` (replacing the line or adding it)."""
    lines = text.splitlines()
    head = f"[{section}]"
    if head not in lines:
        lines += ["", head]
    start = lines.index(head)
    end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("[")),
               len(lines))
    for i in range(start + 1, end):
        if re.match(rf"{re.escape(key)}\s*=", lines[i]):
            lines[i] = f"{key} = {value}"
            return "\n".join(lines) + "\n"
    lines.insert(end, f"{key} = {value}")
    return "\n".join(lines) + "\n"


def _plan(text: str | bytes, *extra: str):
    with tempfile.TemporaryDirectory() as tmp:
        p = Path(tmp) / "project.toml"
        if isinstance(text, bytes):
            p.write_bytes(text)
        else:
            p.write_text(text, encoding="utf-8")
        return invoke(["plan", str(p), *extra]), p


def _line_of(text: str, section: str, key: str) -> int | None:
    current = None
    for n, line in enumerate(text.splitlines(), 1):
        m = re.match(r"\[(.+)\]", line.strip())
        if m:
            current = m.group(1)
        elif current == section and re.match(rf"{re.escape(key)}\s*=", line):
            return n
    return None


# Which values each key refuses (a string for a number, a number out of range …).
def _bad_for(kind: str) -> list[str]:
    if kind == "str":
        return ["1", "true", "[1]", "{ a = 1 }"]
    if kind == "int":
        return ['"8"', "1.5", "true", "-1", "0", "1000", "[1]"]
    if kind in ("number", "scale"):
        return BAD_TOML_VALUES
    if kind == "scales":
        return ["[]", "[0]", "[-1000]", '["abc"]', "10000", "[nan]", "[[1]]", "[1e400]"]
    if kind == "range":
        return ["[]", "[1]", '[1, "a"]', "[2, 1]", '"abc"', "[nan, 1]", "[1, 2, 3]",
                "[true, false]", "[1e400, 1]"]
    if kind == "date":
        return ['"abc"', '"2025-13-01"', "1", "true", "[1]", '""', "1979-05-27T07:32:00"]
    if kind == "feature":  # issue 11: a polygon's name or number
        return ["true", "1.5", "[1]", "{ a = 1 }", "0", '"x"']
    if kind == "polygon":
        return ["[]", "[1, 2, 3]", '"abc"', "[[1, 2]]", "[[0, 0], [1, 1], [2, 2]]",
                "[[0, 0], [1, 0], [1, 1], [0, 1]]", "[[0, 91], [1, 91], [1, 92]]"]
    if kind == "crs":
        return ["true", "1.5", "[1]", '"EPSG:999999"', '"nonsense"', '"EPSG:4326"']
    if kind == "range":  # issue 12: [terrain] ground_elevation_m = [min, max]
        return ["1", '"a"', "[1]", "[1, 2, 3]", '[1, "a"]', "[200, 100]", "[-1000, 0]",
                "[0, 1e400]", "[0, 9000]", "true"]
    if kind == "direction":
        return ['"north"', "true", "[1]", "nan", "inf", "1e400", "45", "-1"]
    if kind == "point":  # [flight] takeoff = [lon, lat]
        return ["[]", "[1]", '"abc"', "[1, 2, 3]", "[200, 50]", "[10, 95]", "[nan, 1]",
                "true", '[1, "a"]']
    if kind == "bool":  # [uav] crosshatch = true | false
        return ['"yes"', "1", "0", "[true]", '"true"', "1.5", "{ a = 1 }"]
    if kind == "checkpoints":  # [control] checkpoints = "asprs" | N
        return ['"all"', "true", "1.5", "[1]", "2", "-1", "10000000", "1e400"]
    raise AssertionError(kind)


#  keys whose bad value is still accepted by design (free text) or checked elsewhere
FREE_TEXT = {("project", "name"), ("project", "customer"), ("project", "contractor"),
             ("project", "approver_position"), ("project", "approver_name")}
# values the key accepts although they are in the generic bad list
ACCEPTS = {
    ("uav", "height_tolerance_pct"): {"0", "-0.0"},
    ("uav", "roll_deg"): {"0", "-1", "-0.0"},
    ("uav", "pitch_deg"): {"0", "-1", "-0.0"},
    ("uav.target", "r_min"): {"0", "-0.0"},
    ("uav.motion", "random_speed_ms"): {"0", "-0.0"},
    ("uav.motion", "roll_rate_rad_s"): {"0", "-0.0"},
    ("uav.motion", "pitch_rate_rad_s"): {"0", "-0.0"},
    ("uav.motion", "yaw_rate_rad_s"): {"0", "-0.0"},
    ("uav", "speed_ms"): {"0", "-0.0"},
    ("site", "lat_deg"): {"0", "-1", "-0.0"},
    ("site", "lon_deg"): {"0", "-1", "-0.0"},
    ("schedule", "utc_offset_h"): {"0", "-1", "-0.0"},
    ("schedule", "turnaround_min"): {"0", "-0.0"},
    ("schedule", "min_sun_elevation_deg"): {"0", "-0.0"},
    ("area", "extension_bases"): {"0"},
    ("uav", "turnaround_m"): {"0", "-0.0"},
    ("terrain", "follow_tolerance_m"): {"0", "-0.0"},
    ("terrain", "void_fill_radius_m"): {"0", "-0.0"},  # 0: no void is filled
    ("terrain", "void_fill_margin_m"): {"0", "-0.0"},
}
# string keys whose bad values must be refused (a choice or an id), with the bad values
STR_BAD = {
    ("project", "locale"): ['"de"', '""', '"EN"'],
    ("norms", "set"): ['"no-such-set"', '"../../etc"', '""', '"/dev/null"'],
    ("norms", "height_formula"): ['"x"', '""'],
    ("norms", "shape"): ['"hexagon"', '""'],
    ("film", "camera"): ['"nope"', '"../../etc/passwd"', '"dji-mavic-3e"'],
    ("film", "scanner"): ['"nope"', '"../x"'],
    ("film", "frame_mm"): ['"0x230"', '"abc"', '"230x"'],
    ("uav", "camera"): ['"nope"', '"../x"', '"rc30-153"'],
    ("uav", "sensor_mm"): ['"0x24"', '"abc"'],
    ("uav", "height_formula"): ['"x"', '""', '"Normal_case"'],
    ("norms", "gsd_area"): ['"x"', '""', '"Dense_urban"'],
    ("terrain", "relief_class"): ['"x"', '""', '"Flat"'],
    ("area", "file"): ['"missing.kml"', '""'],
    ("area", "layer"): ['"a"'],
    ("terrain", "dem"): ['"nope.tif"', '""', '"../../etc/passwd"'],
    ("terrain", "altitude_mode"): ['"agl"', '""', '"Constant"'],
    ("terrain", "vertical_unit"): ['"yd"', '""', '"M"'],
}


def _project_cases() -> list[tuple[str, str, str, str]]:
    """(base, section, key, bad value) for every documented key."""
    cases = []
    for section, keys in KEYS.items():
        base = "uav" if section.startswith("uav") else "film"
        for key, (kind, _desc) in keys.items():
            if (section, key) in FREE_TEXT:
                continue
            if kind == "str":
                values = STR_BAD.get((section, key), []) + _bad_for("str")
            else:
                values = [v for v in _bad_for(kind) if v not in ACCEPTS.get((section, key), ())]
            cases += [(base, section, key, v) for v in values]
    return cases


PROJECT_CASES = _project_cases()


@budget(250)
@given(case=st.sampled_from(PROJECT_CASES))
def test_project_bad_value_exits_2_naming_key_and_line(case):
    """Every documented key × bad values: exit 2, ``section.key`` and its line named."""
    base, section, key, value = case
    COUNTS["project file, invalid value"] += 1
    text = _set_key(FILM_PROJECT if base == "film" else UAV_PROJECT, section, key, value)
    if section == "film" and key in ("focal_mm", "frame_mm"):
        text = text.replace('camera = "afa-te-100"\n', "")
        other = "frame_mm" if key == "focal_mm" else "focal_mm"
        text = _set_key(text, "film", other, '"230x230"' if other == "frame_mm" else "153")
    if section == "uav" and key in ("pixel_um", "focal_mm", "sensor_mm"):
        text = text.replace('camera = "canon-eos-5d-mark-ii-50"\n', "")
        for k, v in (("pixel_um", "6.4"), ("focal_mm", "50"), ("sensor_mm", '"36x24"')):
            if k != key:
                text = _set_key(text, "uav", k, v)
    r, _p = _plan(text)
    assert r.exit_code == 2, (case, r.output)
    dotted = f"{section}.{key}"
    line = _line_of(text, section, key)
    msg = r.output
    if "is not valid TOML" in msg:  # nan in an array and the like: the parser's own line
        assert re.search(r"line \d+", msg), msg
        return
    assert dotted in msg, (case, msg)
    assert f"line {line}" in msg, (case, line, msg)


@st.composite
def garbled_project(draw) -> bytes:
    """A valid project file, then damaged: bytes cut, inserted, replaced or re-encoded."""
    text = draw(st.sampled_from([FILM_PROJECT, UAV_PROJECT])).encode()
    how = draw(st.sampled_from(["cut", "insert", "replace", "utf16", "latin1", "nul",
                                "duplicate", "unknown"]))
    if how == "cut":
        return text[: draw(st.integers(0, len(text) - 1))]
    if how == "insert":
        at = draw(st.integers(0, len(text)))
        junk = draw(st.binary(min_size=1, max_size=8))
        return text[:at] + junk + text[at:]
    if how == "replace":
        at = draw(st.integers(0, len(text) - 1))
        return text[:at] + draw(st.sampled_from([b"[", b"]", b"=", b'"', b"#", b"\n"])) + \
            text[at + 1:]
    if how == "utf16":
        return text.decode().encode("utf-16")
    if how == "latin1":
        return text.replace(b"Fuzz", "Épure".encode("latin-1"))
    if how == "nul":
        return text.replace(b"scale", b"sc\x00ale", 1)
    if how == "duplicate":
        return text + b"\n[map]\nscale = 500\n"
    word = draw(st.from_regex(r"[a-z_]{1,12}", fullmatch=True))
    return text.replace(b"[map]\n", f"[map]\n{word}x = 1\n".encode(), 1)


@budget(200)
@given(blob=garbled_project())
def test_garbled_project_files_never_crash(blob):
    """A damaged file: a plan (if still valid) or exit 2 with the file and a line named."""
    COUNTS["project file, garbled"] += 1
    r, p = _plan(blob, "--json")
    if r.exit_code == 0:
        finite_json(r.stdout)
        return
    assert str(p) in r.output or "project.toml" in r.output, r.output


@budget(80)
@given(mk=st.sampled_from(TABLE_MAP_SCALES), relief=with_edges(0.1, 50),
       mc=st.lists(with_edges(500, 100_000), min_size=1, max_size=5, unique=True),
       height=with_edges(20, 2000), sections=st.sampled_from(["film", "uav", "both"]))
def test_project_valid_extremes(mk, relief, mc, height, sections):
    """Valid extreme projects: exit 0, finite JSON; an infeasible film plan says so."""
    COUNTS["project file, valid extreme"] += 1
    text = f"[map]\nscale = {mk}\nrelief_interval_m = {relief:g}\n"
    if sections in ("film", "both"):
        text += ('[film]\ncamera = "afa-te-100"\nresolving_power_lpmm = 40\n'
                 "photo_scales = [" + ", ".join(f"{x:g}" for x in mc) + "]\n"
                 'scanner = "photoscan-td"\n')
    if sections in ("uav", "both"):
        text += (f'[uav]\ncamera = "canon-eos-5d-mark-ii-50"\nf_number = 8\n'
                 f"height_m = {height:g}\n")
    text += "[area]\nwidth_m = 2000\nlength_m = 3000\n"
    r, _ = _plan(text, "--json")
    assert r.exit_code == 0, (text, r.output)
    doc = finite_json(r.stdout)
    spec = doc["specification"]
    codes = {w["code"] for w in doc["warnings"]}
    if "film" in spec and spec["film"].get("recommended_photo_scale") is None:
        assert "no_feasible_photo_scale" in codes, codes


# ----------------------------------------------------------------------------------------
# Hostile project files (issue 17 items 2–3): exit 2 naming key and line, bounded work
# ----------------------------------------------------------------------------------------

BIG_INT = "1" + "0" * 400  # too large for a float
HUGE_INT = "1" + "0" * 5000  # over Python's 4,300-digit conversion limit
DEEP_ARRAY = "[" * 3000 + "]" * 3000
DEEP_TABLE = "{ a = " * 3000 + "1" + " }" * 3000
MANY_SCALES = "[" + ", ".join(str(5000 + i) for i in range(100_000)) + "]"

HOSTILE_PROJECTS = [  # (id, base, section, key, value, what the message says)
    ("relief-overflow", "film", "map", "relief_interval_m", BIG_INT, "finite number"),
    ("relief-5000-digits", "film", "map", "relief_interval_m", HUGE_INT, "4,300 digits"),
    ("map-scale-overflow", "film", "map", "scale", BIG_INT, "finite scale"),
    ("photo-scale-overflow", "film", "film", "photo_scales", f"[6000, {BIG_INT}]",
     "finite scales"),
    ("height-5000-digits", "uav", "uav", "height_m", HUGE_INT, "4,300 digits"),
    ("photo-scales-deep", "film", "film", "photo_scales", DEEP_ARRAY, "more than 32 deep"),
    ("camera-deep-table", "film", "film", "camera", DEEP_TABLE, "more than 32 deep"),
    ("speed-deep-array", "uav", "uav", "speed_ms", DEEP_ARRAY, "more than 32 deep"),
    ("photo-scales-101", "film", "film", "photo_scales",
     "[" + ", ".join(str(5000 + 10 * i) for i in range(101)) + "]", "at most 100"),
    ("photo-scales-100000", "film", "film", "photo_scales", MANY_SCALES, "at most 100"),
    ("norm-set-100000-chars", "film", "norms", "set", '"' + "a" * 100_000 + '"',
     "at most 1,000"),
    ("norm-set-300-chars", "film", "norms", "set", '"' + "a" * 300 + '"',
     "no norm set has such a name"),
]


@pytest.mark.parametrize("case", HOSTILE_PROJECTS, ids=[c[0] for c in HOSTILE_PROJECTS])
def test_hostile_project_files_exit_2_naming_key_and_line(case):
    """Bug: these exited 1 (OverflowError, RecursionError, a path error) or ran for 25 s
    and 1 GB (100,000 photo scales). Now exit 2 naming ``section.key (line N)``, refused
    before any work, in bounded memory."""
    import tracemalloc

    _id, base, section, key, value, said = case
    COUNTS["project file, hostile corpus"] += 1
    text = _set_key(FILM_PROJECT if base == "film" else UAV_PROJECT, section, key, value)
    tracemalloc.start()
    try:
        r, _p = _plan(text)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert r.exit_code == 2, (case[0], r.output[:500])
    line = _line_of(text, section, key)
    assert f"{section}.{key} (line {line})" in r.output, (case[0], r.output[:500])
    assert said in r.output, (case[0], r.output[:500])
    assert "Error" not in r.output and "Traceback" not in r.output
    assert len(r.output) < 2000  # the value is shown cut, not echoed whole
    assert peak < 100 * 2**20


EXTREME_VALID_PROJECTS = [  # (id, base, section, key, value): in the documented domains
    ("speed-0", "uav", "uav", "speed_ms", "0"),
    ("speed-subnormal", "uav", "uav", "speed_ms", "1e-320"),
    ("exposure-10s", "uav", "uav", "exposure_s", "10"),
    ("area-subnormal", "uav", "area", "width_m", "1e-300"),
    ("area-1000km", "uav", "area", "length_m", "1000000"),
    ("photo-scales-100", "film", "film", "photo_scales",
     "[" + ", ".join(str(5000 + 100 * i) for i in range(100)) + "]"),
]


@pytest.mark.parametrize("case", EXTREME_VALID_PROJECTS,
                         ids=[c[0] for c in EXTREME_VALID_PROJECTS])
def test_extreme_valid_project_files_give_finite_results(case):
    """In-domain extremes: exit 0, every JSON number finite, no ``inf``/``nan`` and no
    library warning in the text output."""
    _id, base, section, key, value = case
    COUNTS["project file, valid extreme corpus"] += 1
    text = _set_key(FILM_PROJECT if base == "film" else UAV_PROJECT, section, key, value)
    r, _p = _plan(text, "--json")
    assert r.exit_code == 0, (case[0], r.output[:800])
    finite_json(r.stdout)
    r, _p = _plan(text)
    assert r.exit_code == 0, (case[0], r.output[:800])
    assert not re.search(r"\b(inf|nan)\b|\w+Warning\b", r.output), (case[0], r.output)


# ----------------------------------------------------------------------------------------
# Norm spreadsheets (CSV and xlsx): exit 0 or 2, and a bad cell is named
# ----------------------------------------------------------------------------------------

OBJECTS_HEADER = ["map_scale", "object", "size_m", "shape", "source"]
OBJECTS_ROWS = [["2000", "poles, hydrants", "0.2", "circle", "seed 001 Table 3"],
                ["5000", "wells", "0.7", "circle", "seed 001 Table 3"],
                ["10000", "pipes", "1.0", "rectangle", "seed 001 Table 3"]]
BAD_CELLS = {
    "map_scale": ["0", "-2000", "abc", "nan", "inf", "1:0", "=1+1", "1e400"],
    "size_m": ["0", "-0.2", "abc", "nan", "inf", "=A1", "1e400", "+cmd|' /C calc'!A0"],
    "shape": ["hexagon", "", "=HYPERLINK(\"http://x\")"],
}
CELL_TEXT = st.one_of(st.text(max_size=30), st.sampled_from(
    ["=1/0", "@SUM(1)", "-2+3", "\t=cmd", "1,5", "1 000", "−3", "１２", "NaN", "1e-400"]))


def _csv(rows: list[list[str]]) -> bytes:
    buf = io.StringIO()
    csv.writer(buf).writerows(rows)
    return buf.getvalue().encode("utf-8")


def _validate(name: str, blob: bytes):
    with tempfile.TemporaryDirectory() as tmp:
        p = Path(tmp) / name
        p.write_bytes(blob)
        return invoke(["norms", "validate", str(p)])


@budget(150)
@given(data=st.data())
def test_norm_csv_bad_cell_is_named(data):
    """One bad cell in an objects table: exit 2 naming its column letter and row."""
    COUNTS["norm csv, invalid cell"] += 1
    column = data.draw(st.sampled_from(sorted(BAD_CELLS)))
    value = data.draw(st.sampled_from(BAD_CELLS[column]))
    row = data.draw(st.integers(0, len(OBJECTS_ROWS) - 1))
    rows = [list(r) for r in OBJECTS_ROWS]
    col = OBJECTS_HEADER.index(column)
    rows[row][col] = value
    r = _validate("objects.csv", _csv([OBJECTS_HEADER, *rows]))
    assert r.exit_code == 2, (column, value, r.output)
    cell = f"{'ABCDE'[col]}{row + 2}"
    assert cell in r.output, (column, value, cell, r.output)


@budget(150)
@given(data=st.data())
def test_norm_csv_random_cells_never_crash(data):
    """Random text in random cells (and random shapes of table): exit 0 or 2, no crash."""
    COUNTS["norm csv, random"] += 1
    n_rows = data.draw(st.integers(0, 6))
    header = data.draw(st.one_of(st.just(OBJECTS_HEADER), st.lists(
        st.sampled_from([*OBJECTS_HEADER, "масштаб", "Объект", "", "size"]), max_size=7)))
    rows = [[data.draw(CELL_TEXT) for _ in range(data.draw(st.integers(0, 7)))]
            for _ in range(n_rows)]
    blob = _csv([header, *rows])
    if data.draw(st.booleans()):
        blob = data.draw(st.sampled_from([b"\xef\xbb\xbf", b"\xff\xfe", b"", b"sep=;\n"])) + blob
    r = _validate("objects.csv", blob)
    if r.exit_code == 2:
        assert "error" in r.output.lower() or "objects.csv" in r.output, r.output


@budget(40)
@given(data=st.data())
def test_norm_xlsx_random_cells_never_crash(data):
    """Workbooks with random values in the objects sheet: exit 0 or 2; a bad cell named."""
    from openpyxl import Workbook
    from openpyxl.utils.exceptions import IllegalCharacterError

    COUNTS["norm xlsx, random/invalid"] += 1
    wb = Workbook()
    ws = wb.active
    ws.title = data.draw(st.sampled_from(["objects", "Минимальные объекты", "Sheet1"]))
    ws.append(OBJECTS_HEADER)
    rows = [list(r) for r in OBJECTS_ROWS]
    column = data.draw(st.sampled_from(sorted(BAD_CELLS)))
    col = OBJECTS_HEADER.index(column)
    row = data.draw(st.integers(0, len(rows) - 1))
    bad = data.draw(st.one_of(st.sampled_from(BAD_CELLS[column]),
                              st.sampled_from([-1.0, 0.0, math.inf, math.nan]), CELL_TEXT))
    rows[row][col] = bad
    buf = io.BytesIO()
    try:
        for r_ in rows:
            ws.append([float(v) if isinstance(v, str) and re.fullmatch(r"\d+(\.\d+)?", v)
                       else v for v in r_])
        wb.save(buf)
    except (ValueError, TypeError, IllegalCharacterError):  # openpyxl refuses some text
        return
    r = _validate("norms.xlsx", buf.getvalue())
    if r.exit_code == 2 and ws.title != "Sheet1" and isinstance(bad, str) \
            and bad in BAD_CELLS[column]:
        if column == "shape" and bad == "hexagon":
            # a well-formed shape name is only unknown against a shapes table: the workbook
            # has none, so the refusal names the missing table (the name may be defined there)
            assert "no sheet for table 'shapes'" in r.output, r.output
        else:
            assert f"{'ABCDE'[col]}{row + 2}" in r.output, (column, bad, r.output)


# ----------------------------------------------------------------------------------------
# The documented domains
# ----------------------------------------------------------------------------------------

def test_every_domain_is_documented_with_its_bounds():
    """docs/input-ranges.md lists every entry of DOMAINS with the bounds the code uses."""
    from scanplan.core.domains import DOMAINS, _bound

    doc = Path(__file__).resolve().parent.parent / "docs" / "input-ranges.md"
    if not doc.is_file():
        pytest.skip("docs/ not beside the tests (installed-package run)")
    rows = {}
    for line in doc.read_text(encoding="utf-8").splitlines():
        m = re.match(r"\| `(\w+)` \| [^|]* \| ([^|]*) \| ([^|]*) \|", line)
        if m:
            rows[m.group(1)] = (m.group(2).strip(), m.group(3).strip())
    assert set(rows) == set(DOMAINS)
    for name, d in DOMAINS.items():
        lo = f"{'>' if d.lo_open else '≥'} {_bound(d.lo)}"
        hi = f"{'<' if d.hi_open else '≤'} {_bound(d.hi)}"
        assert rows[name] == (lo, hi), name


@pytest.mark.parametrize("name", sorted(
    ["map_scale", "photo_scale", "relief_interval_m", "resolving_power_lpmm",
     "object_size_m", "pixel_um", "focal_mm"]))
def test_domain_edges_on_the_command_line(name):
    """Each film input at its documented bounds runs; just outside them, exit 2 naming it."""
    from scanplan.core.domains import DOMAINS

    d = DOMAINS[name]
    option = OPTION_NAMES[name]
    base = {"--map-scale": "2000", "--relief": "1", "--photo-scale": "10000",
            "--focal-mm": "153", "--frame-mm": "230x230", "--resolving-power": "40",
            "--object-size-m": "0.2"}
    for value, ok in ((d.lo, not d.lo_open), (d.hi, not d.hi_open),
                      (d.lo * (1 - 1e-9) if d.lo else -1e-9, False), (d.hi * (1 + 1e-9), False)):
        args = dict(base)
        args[option] = repr(float(value))
        flat = ["scan", *[x for kv in args.items() for x in kv], "--json"]
        r = invoke(flat)
        assert (r.exit_code == 0) == ok, (option, value, r.output)
        if ok:
            assert all(math.isfinite(x) for x in numbers(finite_json(r.stdout)))
        else:
            assert option in r.output, r.output
