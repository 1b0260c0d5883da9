"""`scanplan uav`: MTF ground resolution combined with the Instruction's constraints.

The seed 002 case: Canon EOS 5D Mark II (5616×3744 on 36×24 mm: pitch 36 mm/5616 =
6.4103 µm, exact; the catalogue assumes a 50 mm lens, worked at f/8), 300 m planned,
300–420 m flown, 80 % forward overlap.
"""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.core import mtf
from scanplan.project.jobs import uav_job

SEED002 = dict(camera="canon-eos-5d-mark-ii-50", f_number=8.0, height_m=300.0,
               height_tolerance_pct=40.0, speed_ms=25.0, exposure_s=0.001,
               forward_overlap_pct=80.0, shift_factor=0.65)
# the seed 002 flight was flown up to 420 m: far above the 150 m ceiling of the norm set
# (flights without an airspace-use permission), so the tests of the other limits raise it
HIGH = dict(max_height_m=20_000.0)
P_MM = 36 / 5616  # seed 002: 5616 px across a 36 mm sensor [mm]


def test_seed_002_worked_example():
    """GSD, L, L/GSD and the recognition probability of the 1:2000 objects at 300 and 420 m."""
    plan = uav_job(**SEED002, map_scale=2000, relief_interval_m=0.5).plan
    # GSD = p·H/f, derived by hand
    assert plan.gsd_m == pytest.approx(P_MM * 300 / 50)            # 0.0385 m
    assert plan.gsd_at_max_height_m == pytest.approx(P_MM * 420 / 50)  # 0.0538 m
    assert plan.heights_m == {"planned": 300.0, "min": 300.0, "max": 420.0}
    # L = H/(2·R·f) with R from the MTF chain; seed 000: GSD overstates resolution (~2×)
    r = plan.resolving_power_lpmm
    assert plan.ground_resolution_m == pytest.approx(300 / (2 * r * 50))
    assert 1.3 < plan.ground_resolution_to_gsd < 2.5
    assert plan.ground_resolution_at_max_height_m > plan.ground_resolution_m
    # recognition of 20 cm poles (B 0.97): exp(−(B·L/L_obj)²), lower at the height flown
    poles = next(x for x in plan.recognition if x.map_scale == 2000)
    expected = math.exp(-((0.97 * plan.ground_resolution_m / 0.2) ** 2))
    assert poles.probability == pytest.approx(expected)
    assert 0.75 < poles.probability_at_max_height < poles.probability < 1
    assert poles.probability_corner_at_max_height <= poles.probability_at_max_height
    # fixed trigger distance planned for 300 m: at 420 m the forward overlap grows
    assert plan.flight["forward_overlap_at_max_height_pct"] == pytest.approx(
        100 - 20 * 300 / 420)
    # 25 m/s at 1/1000 s blurs 0.65 px at 300 m → warned, with the limits that fix it
    assert plan.motion_blur_px == pytest.approx(25 * 0.001 / plan.gsd_m)
    assert "motion_blur" in {w.code for w in plan.warnings}
    assert plan.max_speed_ms == pytest.approx(0.5 * plan.gsd_m / 0.001)


def test_max_height_gsd_limited_is_exact():
    """Without P_D (the Instruction as printed) the photo-plan limit 0.07 mm·Mk binds:
    GSD ≤ 0.14 m at 1:2000 → H_max = 0.14·f/p, divided by the height tolerance."""
    plan = uav_job(**{**SEED002, "height_tolerance_pct": 0.0}, map_scale=2000,
                   relief_interval_m=0.5, norms="gkinp-02-036-02-printed", **HIGH,
                   height_formula="instruction").plan
    assert plan.binding == "PP"
    assert plan.max_height_m == pytest.approx(0.14 * 50 / P_MM)
    plan40 = uav_job(**SEED002, map_scale=2000, relief_interval_m=0.5,
                     norms="gkinp-02-036-02-printed", **HIGH, height_formula="instruction").plan
    assert plan40.max_height_m == pytest.approx(plan.max_height_m / 1.4)


def test_max_height_interpretation_limited_meets_its_limit():
    """With P_D, L must not exceed L_obj·sqrt(−ln P)/B; at the highest height flown at the
    maximum planned height (+40 %) the centre L sits exactly on that limit, and the binding
    constraint is named. (The Instruction's height form, which allows 2,902 m here, and no
    ceiling: P_D binds at a maximum planned height of 376 m, flown up to 526 m.)"""
    plan = uav_job(**SEED002, map_scale=2000, relief_interval_m=0.5, **HIGH,
                   height_formula="instruction").plan
    assert plan.binding == "PD"
    limit = 0.2 * math.sqrt(-math.log(0.75)) / 0.97
    pd = next(x for x in plan.limits if x.id == "PD")
    assert pd.limit_m == pytest.approx(limit) and pd.compares == "L" and pd.binding
    assert plan.max_flown_height_m == pytest.approx(plan.max_height_m * 1.4)
    assert pd.max_flown_height_m == pytest.approx(plan.max_flown_height_m)
    cam = mtf.Camera(P_MM * 1000, 50, 8, 36, 24)
    flown = plan.max_flown_height_m
    res = mtf.uav_resolution(cam, mtf.Flight(flown, 25, 0.001, 0.65),
                             threshold=mtf.Threshold(params={"k0": 0.03}))
    assert float(res.centre.ground_resolution_m) == pytest.approx(limit, rel=1e-4)
    assert all(x.max_height_m >= plan.max_height_m for x in plan.limits)
    assert "height_above_max" not in {w.code for w in plan.warnings}
    higher = uav_job(**{**SEED002, "height_m": 500.0}, map_scale=2000,
                     relief_interval_m=0.5, **HIGH, height_formula="instruction").plan
    assert "height_above_max" in {w.code for w in higher.warnings}


def test_area_plan():
    plan = uav_job(**SEED002, area_m="2000x3000").plan
    fl = plan.flight
    assert fl["footprint_across_m"] == pytest.approx(36 * 300 / 50)
    assert fl["base_m"] == pytest.approx(24 * 300 / 50 * 0.2)
    assert fl["line_spacing_m"] == pytest.approx(216 * 0.4)
    assert fl["strips"] == math.ceil(2000 / 86.4)
    assert fl["photos"] == fl["strips"] * fl["photos_per_strip"]
    assert fl["data_volume_bytes"] == pytest.approx(fl["photos"] * 5616 * 3744 * 3)


def test_cli_json_contract():
    r = CliRunner().invoke(main, ["uav", "--camera", "canon-eos-5d-mark-ii-50", "--f-number",
                                  "8", "--height-m", "300", "--map-scale", "1:2000", "--relief",
                                  "0.5", "--json"])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    for key in ("gsd_m", "nyquist_lpmm", "resolving_power_lpmm", "ground_resolution_m",
                "ground_resolution_to_gsd", "motion_blur_px", "recognition", "max_height_m",
                "warnings"):
        assert key in doc
    assert doc["nyquist_lpmm"] == pytest.approx(1 / (2 * P_MM))
    assert {"object", "object_size_m", "shape", "probability"} <= set(doc["recognition"][0])


def test_not_resolvable_is_a_result():
    r = CliRunner().invoke(main, ["uav", "--camera", "dji-zenmuse-p1-35", "--height-m", "100",
                                  "--r-max", "0.101", "--r-min", "0.099", "--json"])
    doc = json.loads(r.stdout)
    assert r.exit_code == 0
    assert doc["resolvable"] is False and doc["ground_resolution_m"] is None
    assert "not_resolvable" in {w["code"] for w in doc["warnings"]}


BAD = [
    (["--pixel-um", "0", "--focal-mm", "35", "--sensor-mm", "36x24", "--f-number", "8"],
     "--pixel-um"),
    (["--camera", "dji-zenmuse-p1-35", "--f-number", "0"], "--f-number"),
    (["--camera", "dji-zenmuse-p1-35", "--f-number", "-2"], "--f-number"),
    (["--camera", "dji-zenmuse-p1-35", "--overlap-pct", "100"], "--overlap-pct"),
    (["--camera", "dji-zenmuse-p1-35", "--side-overlap-pct", "100"], "--side-overlap-pct"),
    (["--camera", "dji-zenmuse-p1-35", "--exposure-s", "0"], "--exposure-s"),
    (["--camera", "dji-zenmuse-p1-35", "--r-min", "0.4"], "--r-min"),
    (["--camera", "nope"], "--camera"),
    (["--camera", "rc30-153"], "--camera"),
    (["--camera", "dji-zenmuse-p1-35", "--map-scale", "2000"], "--relief"),
    (["--camera", "dji-zenmuse-p1-35", "--height-tolerance-pct", "100"],
     "--height-tolerance-pct"),
    (["--camera", "dji-zenmuse-p1-35", "--sensor-mm", "36"], "--sensor-mm"),
]


@pytest.mark.parametrize(("extra", "option"), BAD, ids=[" ".join(b[0]) for b in BAD])
def test_bad_input_exits_2_naming_the_field(extra, option):
    r = CliRunner().invoke(main, ["uav", "--height-m", "100", *extra])
    assert r.exit_code == 2, r.output
    assert option in r.stderr and "Traceback" not in r.output


def test_docs_worked_example_reproduced_by_the_cli():
    """docs/uav-models.md's seed 002 table (with random motion 1 m/s, 0.02 rad/s) comes out
    of `scanplan uav` unchanged: L 6.34 / 6.65 cm at 300 m, 8.84 cm at 420 m, P 0.910 / 0.832
    / 0.817 for the 20 cm poles."""
    args = [
        "uav", "--camera", "canon-eos-5d-mark-ii-50", "--f-number", "8", "--height-m", "300",
        "--height-tolerance-pct", "40", "--speed-ms", "25", "--shift-factor", "0.65",
        "--random-speed-ms", "1", "--roll-rate", "0.02", "--pitch-rate", "0.02",
        "--yaw-rate", "0.02", "--map-scale", "2000", "--relief", "0.5", "--json"]
    r = CliRunner().invoke(main, args)
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["ground_resolution_m"] == pytest.approx(0.0634, abs=5e-5)
    assert d["ground_resolution_corner_m"] == pytest.approx(0.0665, abs=5e-5)
    assert d["ground_resolution_at_max_height_m"] == pytest.approx(0.0884, abs=5e-5)
    poles = d["recognition"][0]
    assert poles["probability"] == pytest.approx(0.910, abs=5e-4)
    assert poles["probability_at_max_height"] == pytest.approx(0.832, abs=5e-4)
    assert poles["probability_corner_at_max_height"] == pytest.approx(0.817, abs=5e-4)
    # the new meaning of "maximum": the largest PLANNED height whose highest flown height
    # (planned × 1.4) still meets the binding limit. By default the norm set's 150 m
    # ceiling for the highest flown height binds: 150 / 1.4 = 107 m planned, and the
    # constraints would allow 214 m (the digital height accuracy, PZ)
    assert d["binding"] == "HC" and d["ceiling_m"] == 150
    assert d["max_planned_height_m"] == d["max_height_m"] == pytest.approx(150 / 1.4)
    assert d["max_flown_height_m"] == pytest.approx(150)
    assert d["constraints_max_height_m"] == pytest.approx(214, abs=1)
    assert "ceiling_binds" in {w["code"] for w in d["warnings"]}
    # with the ceiling raised (airspace-use permission), the normal-case height accuracy
    # binds at 214 m planned, flown up to 300 m; the Instruction's height form instead
    # lets interpretation (P_D on L) bind at 376 m planned, flown up to 526 m
    for extra, cid, planned in ((["--max-height-m", "500"], "PZ", 214),
                                (["--max-height-m", "1000", "--height-formula",
                                  "instruction"], "PD", 376)):
        r = CliRunner().invoke(main, [*args, *extra])
        assert r.exit_code == 0, r.output
        d = json.loads(r.stdout)
        assert d["binding"] == cid and d["max_height_m"] == pytest.approx(planned, abs=1)
        assert d["max_flown_height_m"] == pytest.approx(d["max_height_m"] * 1.4)
        assert d["ceiling_m"] is not None and d["max_flown_height_m"] <= d["ceiling_m"]
