"""The decimals of an input (``digits`` in the input registry's record, as QGroundControl's
``FactMetaData`` carries its decimal places): every numeric key has them, they are the
decimals the documents show the key with, the page and ``init`` read them from the record,
and a value shown through the record reads back as the same number."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import tomllib
from pathlib import Path

import pytest

from scanplan.cli.init import InitAnswers, project_text
from scanplan.project.inputs import INPUTS, domain_of, records, shown
from scanplan.project.model import field_meta
from scanplan.reports.excel import cells
from scanplan.web.registry import input_rows

NUMERIC = {"number", "int", "scale", "scales", "range", "direction", "point", "polygon",
           "checkpoints"}
APP_JS = Path(__file__).parents[1] / "scanplan" / "web" / "static" / "app.js"


@pytest.mark.parametrize("inp", records(), ids=lambda r: r.dotted or r.name)
def test_every_numeric_field_has_digits(inp):
    """A number has its decimals; a text, a date, a CRS or a feature name has none."""
    if inp.kind in NUMERIC:
        assert isinstance(inp.digits, int) and 0 <= inp.digits <= 8
    else:
        assert inp.digits is None


def _decimals(number_format: str) -> int:
    """``"0.000"`` → 3, ``"#,##0"`` → 0 (an Excel number format's decimals)."""
    return len(number_format.partition(".")[2])


# how the workbook's Inputs sheet (reports/excel/inputs.py) shows each key today
WORKBOOK = {
    "map.scale": cells.SCALE, "map.relief_interval_m": cells.F2,
    "film.focal_mm": cells.F2, "film.resolving_power_lpmm": cells.F1,
    "film.forward_overlap_pct": cells.F1, "norms.probability": cells.F3,
    "norms.object_size_m": cells.F3, "norms.pr_coefficient": cells.F2,
    "film.bands": cells.INT, "film.bits_per_band": cells.INT, "pixel_um": cells.UM,
    "uav.pixel_um": cells.F2, "uav.focal_mm": cells.F2, "uav.f_number": cells.F1,
    "uav.height_m": cells.F1, "uav.height_tolerance_pct": cells.F1,
    "uav.speed_ms": cells.F1, "uav.exposure_s": "0.00000",
    "uav.forward_overlap_pct": cells.F1, "uav.side_overlap_pct": cells.F1,
    "area.width_m": cells.M_LARGE, "area.length_m": cells.M_LARGE,
    "uav.target.r_max": cells.F3, "uav.target.r_min": cells.F3,
    "uav.atmosphere.threshold_k0": cells.F3, "uav.atmosphere.haze_contrast": cells.F3,
    "uav.motion.shift_factor": cells.F2, "uav.motion.random_speed_ms": cells.F2,
    "uav.motion.roll_rate_rad_s": cells.F4, "uav.motion.pitch_rate_rad_s": cells.F4,
    "uav.motion.yaw_rate_rad_s": cells.F4, "uav.roll_deg": cells.F2,
    "uav.pitch_deg": cells.F2, "uav.parallax_error_px": cells.F2,
}


@pytest.mark.parametrize("key", sorted(WORKBOOK))
def test_the_digits_are_the_workbooks(key):
    assert INPUTS[key].digits == _decimals(WORKBOOK[key])


def test_the_model_and_the_page_carry_the_records_digits():
    for row in input_rows():
        inp = INPUTS[f"{row['section']}.{row['key']}"]
        assert row["digits"] == inp.digits
        assert field_meta(inp.section, inp.key).digits == inp.digits


@pytest.mark.skipif(shutil.which("node") is None, reason="no node to run the page's code")
def test_the_page_shows_each_default_as_the_registry_has_it():
    """The page's own ``withDigits`` (app.js) shows every numeric default with the
    record's digits, and that is the default unchanged (the placeholder reads as before);
    a drawn polygon's coordinates get area.polygon's 7 decimals."""
    source = APP_JS.read_text(encoding="utf-8")
    subprocess.run(["node", "--check", str(APP_JS)], check=True)
    helper = re.search(r"^\s*const withDigits = .*;$", source, re.MULTILINE)
    assert helper, "app.js has no withDigits"
    rows = [r for r in input_rows() if isinstance(r["default"], int | float)]
    script = (helper.group().strip() + f"\nconst rows = {json.dumps(rows)};\n"
              "console.log(JSON.stringify(rows.map((r) => [String(withDigits(r.default, "
              "r.digits)), String(r.default)])));\n"
              "console.log(withDigits(37.123456789, 7));")
    out = subprocess.run(["node", "-e", script], capture_output=True, text=True,
                         check=True).stdout.splitlines()
    shown_defaults = json.loads(out[0])
    assert len(shown_defaults) == len(rows) > 20
    assert all(a == b for a, b in shown_defaults), shown_defaults
    assert out[1] == "37.1234568" and INPUTS["area.polygon"].digits == 7


def _samples(inp):
    dom = domain_of(inp)
    lo, hi = (dom.lo, dom.hi) if dom else (0.0, 1e6)
    lo, hi = max(lo, -1e6), min(hi, 1e6)
    return [lo + (hi - lo) * f for f in (0.0, 0.013, 0.37, 0.5, 0.999, 1.0)] + [
        v for v in (1 / 3, 2 / 3, 0.0005, 12.5) if lo <= v <= hi]


@pytest.mark.parametrize("inp", [r for r in records() if r.digits is not None],
                         ids=lambda r: r.dotted or r.name)
def test_a_value_shown_through_the_record_round_trips(inp):
    """Shown with the record's digits, a value reads back as itself rounded to them (and
    a value already with those decimals exactly); so does the registry's default."""
    for x in _samples(inp):
        text = shown(inp, x)
        assert float(text) == round(x, inp.digits), (x, text)
        assert shown(inp, float(text)) == text
        assert len(text.partition(".")[2]) <= inp.digits
    if isinstance(inp.default, int | float):
        assert float(shown(inp, inp.default)) == inp.default


def test_a_text_has_no_decimals():
    with pytest.raises(ValueError, match="not a number"):
        shown(INPUTS["project.name"], 1.0)


@pytest.mark.parametrize("kind", ["film", "uav", "both"])
@pytest.mark.parametrize("aircraft", [False, True])
def test_init_writes_every_number_with_at_most_the_records_digits(kind, aircraft):
    """Each example and default ``init`` writes (commented or not) has at most its key's
    digits and reads back as written."""
    text = project_text(InitAnswers(kind=kind, map_scale=2000, relief_interval_m=0.5,
                                    aircraft=aircraft, f_number=5.6 if aircraft else None,
                                    speed_ms=70.0 if aircraft else None))
    section, checked = "", 0
    for line in text.splitlines():
        code = line.removeprefix("# ")
        m = re.match(r"^\[([a-z.]+)\]", code)
        if m:
            section = m.group(1)
            continue
        m = re.match(r"^([a-z_]+) = ([-0-9.\[\], ]+?)\s+#", code)
        inp = INPUTS.get(f"{section}.{m.group(1)}") if m else None
        if m is None or inp is None or inp.digits is None:
            continue  # not a key, or not a number (a date)
        for number in re.findall(r"-?[0-9.]+", m.group(2)):
            assert len(number.partition(".")[2]) <= inp.digits, (inp.dotted, number)
            assert shown(inp, float(number)) == number
            checked += 1
        tomllib.loads(f"x = {m.group(2)}")
    assert checked >= 8
