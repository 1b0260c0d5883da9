"""The height constraint of digital (UAV) blocks, the altitude ceiling and target-GSD planning.

Model (docs/uav-models.md §9): σ_Z = (H/B)·(H/c)·σ_px (Kraus 2007; Luhmann et al. 2014) with
the widest base that keeps standard (60 %) stereo overlap, required σ_Z ≤ V_z = 0.2·h_c read
as an RMS error, σ_px = 0.5 px (norm parameter ``image_measurement_px``).
"""

from __future__ import annotations

import dataclasses
import itertools
import json
import math
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import given, settings
from hypothesis import strategies as st

from scanplan.cli.main import main
from scanplan.core import stereo as S
from scanplan.errors import InputError
from scanplan.norms import load_norm_set
from scanplan.project.file import load_project
from scanplan.project.jobs import uav_job
from scanplan.project.spec import plan_project
from scanplan.reports.jsondoc import plan_result_dict

ROOT = Path(__file__).resolve().parent.parent
SEED002 = dict(camera="canon-eos-5d-mark-ii-50", f_number=8.0, height_m=300.0,
               height_tolerance_pct=40.0, speed_ms=25.0, exposure_s=0.001,
               forward_overlap_pct=80.0, shift_factor=0.65)


# --- the formulas -------------------------------------------------------------------------
def test_standard_stereo_base_is_continuous():
    """From the standard overlap on, the base is that of a pair with exactly 60 % overlap,
    0.4·footprint, a real multiple of the photo step; below it the pair's share of the
    least-squares base of every ray, 0.4/0.506 × B_eff: 0.3897 at 55 % (B_eff 0.4930)."""
    got = S.stereo_base_fraction([60, 70, 79, 80, 85, 90, 55], 60)
    ratio = 0.4 / float(S.multi_ray_base_fraction(60))
    assert ratio == pytest.approx(0.7906, abs=1e-4)
    assert got == pytest.approx([0.4, 0.4, 0.4, 0.4, 0.4, 0.4, ratio * 0.49295], rel=1e-4)


def test_the_height_allowed_does_not_fall_from_55_to_60_pct_overlap():
    """Bug: the P_Z height limit fell by 11 % as the forward overlap rose from 55 to 60 %
    (the single step, 0.45 of the footprint, gave way to the standard pair, 0.40), while the
    least-squares intersection of every ray of the strip gains 2.6 % over that range
    (B_eff 0.4930 → 0.5060 of the footprint). Now it rises with B_eff, by the same 2.6 %,
    and never falls anywhere from 50 to 95 %."""
    def pz_max(overlap: float) -> float:
        plan = uav_job(**{**SEED002, "forward_overlap_pct": overlap}, map_scale=2000,
                       relief_interval_m=0.5, max_height_m=2000).plan
        return next(x for x in plan.limits if x.id == "PZ").max_height_m

    # flown +40 %: the trigger distance fixed at the planned height, the overlap at the
    # highest flown height is 1 − (1 − p)/1.4: 67.9 % at 55 %, above the standard 60 % —
    # so the limit is the standard pair's at both; without a tolerance the overlaps differ
    flat = {**SEED002, "height_tolerance_pct": 0.0}

    def pz_flat(overlap: float) -> float:
        plan = uav_job(**{**flat, "forward_overlap_pct": overlap}, map_scale=2000,
                       relief_interval_m=0.5, max_height_m=2000).plan
        return next(x for x in plan.limits if x.id == "PZ").max_height_m

    assert pz_max(60.0) >= pz_max(55.0) * (1 - 1e-12)
    gain = pz_flat(60.0) / pz_flat(55.0)
    lsq = float(S.multi_ray_base_fraction(60) / S.multi_ray_base_fraction(55))
    assert gain == pytest.approx(lsq, rel=1e-9) and gain == pytest.approx(1.0264, abs=1e-4)
    heights = [pz_flat(p) for p in np.arange(50.0, 95.01, 0.5)]
    assert all(b >= a * (1 - 1e-12) for a, b in itertools.pairwise(heights))


def test_strip_multi_ray_factor_closed_form():
    """At whole numbers of rays m = 1/(1 − p) the RMS multi-ray base is the all-ray one,
    sqrt(2·s²·m(m² − 1)/12): f = 0.4·m·sqrt(6/(m(m² − 1)))."""
    assert S.strip_multi_ray_factor(80, 60) == pytest.approx(2 * math.sqrt(6 / 120))  # 0.447
    assert S.strip_multi_ray_factor(90, 60) == pytest.approx(4 * math.sqrt(6 / 990))
    assert S.strip_multi_ray_factor(75, 60) == pytest.approx(0.4 * 4 * math.sqrt(6 / 60))


def _lsq_sigma_z(positions: np.ndarray, c: float = 50.0, z: float = 300.0) -> float:
    """σ_Z (per unit image error) of a least-squares intersection of rays
    x_i = c·(X − X_i)/Z from projection centres ``positions`` (unknowns X, Z)."""
    x0 = 0.5 * (positions.min() + positions.max())
    a = np.column_stack([np.full(positions.size, c / z), -c * (x0 - positions) / z**2])
    return float(np.sqrt(np.linalg.inv(a.T @ a)[1, 1]))


def test_strip_multi_ray_factor_is_the_least_squares_intersection():
    """The closed form equals the covariance of a least-squares intersection of m rays
    over that of the standard pair (0.4 of the footprint apart)."""
    fp = 100.0
    m = 5                               # 80 %: 5 photos see the point
    rays = _lsq_sigma_z(np.arange(m) * fp / m)
    pair = _lsq_sigma_z(np.array([0.0, 0.4 * fp]))
    assert rays / pair == pytest.approx(float(S.strip_multi_ray_factor(80, 60)), rel=1e-12)


@pytest.mark.parametrize("overlap", [60.0, 70.0, 79.0, 85.0])
def test_multi_ray_base_is_the_rms_over_the_strip(overlap):
    """Between whole numbers of rays: every point position x along one photo step, the
    photos whose footprint contains it, their least-squares σ_Z; the RMS over x equals the
    closed form's (a pair of base B_eff has σ_Z = √2/B_eff per unit image error)."""
    fp, s = 100.0, (1 - overlap / 100) * 100.0
    centres = np.arange(-40, 41) * s
    sig = []
    for x in (np.arange(4000) + 0.5) / 4000 * s:
        seen = centres[np.abs(x - centres) <= fp / 2]
        sig.append(_lsq_sigma_z(seen - x))
    rms = math.sqrt(float(np.mean(np.square(sig))))
    pair = _lsq_sigma_z(np.array([0.0, fp]))   # base = footprint: σ per unit of base
    assert fp * pair / rms == pytest.approx(float(S.multi_ray_base_fraction(overlap)) * fp,
                                            rel=2e-3)


@settings(max_examples=200, deadline=None)
@given(p=st.floats(50.5, 95), dp=st.floats(0, 5))
def test_multi_ray_base_never_falls_with_overlap(p, dp):
    assert (S.multi_ray_base_fraction(min(p + dp, 95.0))
            >= S.multi_ray_base_fraction(p) - 1e-12)


def test_normal_case_by_hand():
    """Kraus' normal case: σ_Z = (H/B)·(H/c)·σ_px. Seed 002's camera at 300 m, 80 %:
    B = 0.4·(24·300/50) = 57.6 m, H/c = 6000, σ_px = 0.5·6.41 µm → 0.1002 m."""
    sz = S.normal_case_height_error_m(300.0, 57.6, 50.0, 6.41, 0.5)
    assert sz == pytest.approx((300 / 57.6) * (300 / 0.050) * 0.5 * 6.41e-6)
    # the GSD limit inverts it: at the limit σ_Z equals V_z exactly
    bh = 57.6 / 300
    g = S.stereo_height_ground_limit_m(0.1, bh, 0.5)
    h = g * 50 / 6.41e-3
    assert S.normal_case_height_error_m(h, bh * h, 50.0, 6.41, 0.5) == pytest.approx(0.1)


_pos = st.floats(0.1, 1e4, allow_nan=False, allow_infinity=False)


@settings(max_examples=200, deadline=None)
@given(h=_pos, b=_pos, f=st.floats(5, 500), p=st.floats(1, 20), s=st.floats(0.05, 3),
       k=st.floats(1.01, 3))
def test_sigma_z_monotone(h, b, f, p, s, k):
    """σ_Z falls with the base and grows with the height and the pixel."""
    base = S.normal_case_height_error_m(h, b, f, p, s)
    assert S.normal_case_height_error_m(h, b * k, f, p, s) < base
    assert S.normal_case_height_error_m(h * k, b, f, p, s) > base
    assert S.normal_case_height_error_m(h, b, f, p * k, s) > base
    assert S.normal_case_height_error_m(h, b, f, p, s * k) > base


@settings(max_examples=100, deadline=None)
@given(p=st.floats(50, 95), q=st.floats(50, 95))
def test_the_standard_base_never_falls_and_bounds_every_ray(p, q):
    """The standard base never falls as the overlap rises, is 1 − p_min from the standard
    overlap on, stays below the least-squares base of every ray (a conservative bound of
    the block), and is Lipschitz in the overlap (no jumps)."""
    lo, hi = min(p, q), max(p, q)
    frac = float(S.stereo_base_fraction(lo, 60))
    assert float(S.stereo_base_fraction(hi, 60)) >= frac - 1e-12
    assert frac <= float(S.multi_ray_base_fraction(lo)) + 1e-12
    if lo >= 60:
        assert frac == pytest.approx(0.4)
    assert abs(frac - float(S.stereo_base_fraction(hi, 60))) <= abs(p - q) / 100 + 1e-12


# --- the published anchor --------------------------------------------------------------------
def test_aguera_vega_2017_vertical_rmse():
    """Agüera-Vega, Carvajal-Ramírez & Martínez-Carricondo (2017), "Assessment of
    photogrammetric mapping accuracy based on variation ground control points number using
    unmanned aerial vehicle", Measurement 98, 221–227: a UAV block at 120 m above ground
    gave a vertical check-point RMSE of 4.7 cm (20 GCPs) and 5.8 cm (15 GCPs) (abstract).
    Assumed: a 12-Mpx Micro Four Thirds camera (4032 × 3024 px on 17.3 × 13.0 mm:
    p = 4.29 µm) with the short side along track, overlap ≥ 60 %. With the standard 60 %
    base (B/H = 0.4·13.0/c) and σ_px = 0.5 px the normal case predicts
    σ_Z = p·H·σ_px/(0.4·l_y) = 4.96 cm, whatever the lens (GSD and B/H both scale with
    1/c): 1.06 × the published 4.7 cm, 0.86 × 5.8 cm. The single-step base (the parallax
    form's) would predict twice as much, 9.9 cm."""
    p_um, h, ly = 17.3 / 4032 * 1000, 120.0, 13.0
    sigma = load_norm_set("gkinp-02-036-02").parameters["image_measurement_px"]
    for c in (14.0, 17.0):                       # focal length does not matter
        bh = float(S.stereo_base_fraction(80, 60)) * ly / c
        sz = float(S.normal_case_height_error_m(h, bh * h, c, p_um, sigma))
        assert sz == pytest.approx(0.0496, abs=5e-4)
        assert 0.75 < sz / 0.047 < 1.33
        assert 0.75 < sz / 0.058 < 1.33
        single = float(S.normal_case_height_error_m(h, 0.2 * ly / c * h, c, p_um, sigma))
        assert single / 0.047 > 2.0


def test_garcia_2020_vertical_rmse():
    """M. V. Y. Garcia et al. (abstract): DJI Phantom 4 Advanced at 31 m, 80 % forward and
    90 % side overlap, 5 GCPs with pre-calibrated interior orientation, 22 check points:
    RMSE Z 3.3 cm. Assumed: the maker's camera data (13.2 × 8.8 mm, 5472 × 3648 px,
    c = 8.8 mm), short side along track. The standard pair with σ_px = 0.5 px predicts
    σ_Z = p·H·σ_px/(0.4·l_y) = 1.06 cm: three times below the check points, whose own
    error, the control's and the calibration's σ_Z leaves out; image noise alone would need
    σ_px ≈ 1.6 px."""
    p_um, h, ly, c = 13.2 / 5472 * 1000, 31.0, 8.8, 8.8
    sigma = load_norm_set("gkinp-02-036-02").parameters["image_measurement_px"]
    bh = float(S.stereo_base_fraction(80, 60)) * ly / c
    sz = float(S.normal_case_height_error_m(h, bh * h, c, p_um, sigma))
    assert sz == pytest.approx(0.01063, abs=5e-5)
    assert 2.5 < 0.033 / sz < 3.5
    assert 0.033 / sz * sigma == pytest.approx(1.55, abs=0.05)
    strip = sz * float(S.strip_multi_ray_factor(80, 60))
    assert strip == pytest.approx(0.00475, abs=5e-5)


# --- the UAV engine ------------------------------------------------------------------------
def test_default_digital_formula_is_normal_case_and_film_keeps_the_instruction():
    rules = load_norm_set("gkinp-02-036-02").rules()
    assert rules.digital_height_formula == "normal_case"
    assert rules.height_formula == "instruction"
    assert rules.multi_ray == "off"
    assert rules.uav_max_height_m == 150


def test_uav_height_constraint_is_normal_case():
    """1:2000, h_c 0.5 m: V_z = 0.1 m RMS; B/H = 0.4·24/50 = 0.192; GSD ≤ 0.1·0.192/0.5
    = 3.84 cm → flown ≤ 299.5 m → planned ≤ 213.95 m with the +40 % tolerance."""
    plan = uav_job(**SEED002, map_scale=2000, relief_interval_m=0.5, max_height_m=500).plan
    pz = next(x for x in plan.limits if x.id == "PZ")
    assert pz.limit_m == pytest.approx(0.1 * 0.192 / 0.5)
    px_mm = plan.inputs.pixel_um / 1000          # 6.41 µm (36 mm / 5616 px)
    assert pz.max_flown_height_m == pytest.approx(0.1 * 0.192 / 0.5 * 50 / px_mm)
    assert pz.max_height_m == pytest.approx(pz.max_flown_height_m / 1.4)
    assert plan.binding == "PZ" and plan.max_height_m == pytest.approx(213.95, abs=0.05)
    acc = plan.height_accuracy
    assert acc["formula"] == "normal_case"
    # the trigger distance is fixed at 300 m: at 420 m the overlap is 85.7 % and the 60 %
    # pair is 2.8 steps apart
    assert acc["forward_overlap_at_highest_flown_height_pct"] == pytest.approx(100 / 1.4 * 1.2)
    assert acc["stereo_base_steps"] == pytest.approx(2.8)
    assert acc["stereo_base_to_height"] == pytest.approx(0.192)
    assert acc["sigma_z_in_gsd"] == pytest.approx(0.5 / 0.192)
    # the other two forms, for comparison (issue 13: 2,902 m and the parallax form's few m)
    forms = acc["forms"]
    assert forms["instruction"]["max_planned_height_m"] == pytest.approx(2902, abs=1)
    assert forms["parallax"]["max_planned_height_m"] == pytest.approx(
        0.1 * 0.096 / 2 * 50 / px_mm / 1.4)
    assert (forms["parallax"]["max_planned_height_m"]
            < forms["normal_case"]["max_planned_height_m"]
            < forms["instruction"]["max_planned_height_m"])
    # at the highest flown height of the maximum plan σ_Z is exactly V_z
    up = plan.max_flown_height_m
    assert S.normal_case_height_error_m(up, 0.192 * up, 50, plan.inputs.pixel_um, 0.5
                                        ) == pytest.approx(0.1)


def test_multi_ray_norm_parameter_raises_the_limit():
    ns = load_norm_set("gkinp-02-036-02")
    from scanplan.rules.uav import _height_accuracy

    job = uav_job(**SEED002, map_scale=2000, relief_interval_m=0.5)
    off = _height_accuracy(job.plan.inputs, ns.rules())
    strip = _height_accuracy(job.plan.inputs, dataclasses.replace(ns.rules(), multi_ray="strip"))
    flown = 100 - 20 / 1.4          # 80 % planned at 300 m, flown at 420 m: 85.7 %, 7 rays
    assert strip[0] == pytest.approx(off[0] / float(S.strip_multi_ray_factor(flown, 60)))
    assert strip[2]["multi_ray_factor"] == pytest.approx(0.4 / math.sqrt((7 - 1 / 7) / 6))


def test_other_height_formulas_on_request():
    for form, cid in (("instruction", "PD"), ("parallax", "PZ")):
        plan = uav_job(**SEED002, map_scale=2000, relief_interval_m=0.5, max_height_m=20000,
                       height_formula=form).plan
        assert plan.binding == cid
        assert plan.height_accuracy["formula"] == form


def test_ceiling_binds_and_says_what_the_constraints_allow():
    plan = uav_job(**SEED002, map_scale=2000, relief_interval_m=0.5).plan
    assert plan.binding == "HC" and plan.ceiling_m == 150
    assert plan.max_height_m == pytest.approx(150 / 1.4)
    assert plan.max_flown_height_m == pytest.approx(150)
    assert plan.constraints_max_height_m == pytest.approx(213.95, abs=0.05)
    w = next(x for x in plan.warnings if x.code == "ceiling_binds")
    assert w.severity == "info" and "214" in w.message and "[uav] max_height_m" in w.message
    assert "Разрешения" in w.text("ru") or "разрешения" in w.text("ru")


def test_ceiling_applies_without_a_map():
    plan = uav_job(**{**SEED002, "height_m": 200.0}).plan
    assert [x.id for x in plan.limits] == ["HC"]
    assert "height_above_max" in {w.code for w in plan.warnings}
    assert "ceiling_binds" not in {w.code for w in plan.warnings}


def test_target_gsd_gives_the_height():
    """gsd_cm → the height: GSD at the highest flown height ≤ the target."""
    job = uav_job(**{**SEED002, "height_m": None}, gsd_cm=3.0, max_height_m=1000)
    plan = job.plan
    h_max = 0.03 * 50 / (plan.inputs.pixel_um / 1000) / 1.4
    assert plan.binding == "GSD" and plan.max_height_m == pytest.approx(h_max)
    assert plan.heights_m["planned"] == math.floor(h_max / 5) * 5
    assert plan.gsd_at_max_height_m <= 0.03
    # with a tight ceiling the ceiling wins and says so
    low = uav_job(**{**SEED002, "height_m": None}, gsd_cm=3.0).plan
    assert low.binding == "HC" and low.heights_m["max"] <= 150
    assert "ceiling_binds" in {w.code for w in low.warnings}


def test_derived_height_needs_something_to_derive_it_from():
    r = CliRunner().invoke(main, ["uav", "--camera", "dji-mavic-3e"])
    assert r.exit_code == 2 and "--height-m" in r.stderr


@pytest.mark.parametrize(("option", "value"), [("--max-height-m", "0"), ("--gsd-cm", "0"),
                                                ("--gsd-cm", "-1"), ("--max-height-m", "1e9")])
def test_bad_ceiling_or_gsd_exits_2(option, value):
    r = CliRunner().invoke(main, ["uav", "--camera", "dji-mavic-3e", "--height-m", "100",
                                  option, value])
    assert r.exit_code == 2, r.output
    assert option in r.stderr and "Traceback" not in r.output


def test_normal_case_refused_for_film():
    r = CliRunner().invoke(main, ["scan", "--map-scale", "2000", "--relief", "1",
                                  "--photo-scale", "10000", "--camera", "rc30-153",
                                  "--height-formula", "normal_case"])
    assert r.exit_code == 2 and "--height-formula" in r.stderr


def test_cli_uav_json_new_keys():
    r = CliRunner().invoke(main, ["uav", "--camera", "canon-eos-5d-mark-ii-50", "--f-number",
                                  "8", "--height-tolerance-pct", "40", "--map-scale", "2000",
                                  "--relief", "0.5", "--max-height-m", "400", "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["max_planned_height_m"] == d["max_height_m"] == pytest.approx(213.95, abs=0.05)
    assert d["heights_m"]["planned"] == 210 and d["heights_m"]["max"] == pytest.approx(294)
    assert d["ceiling_m"] == 400 and d["constraints_max_height_m"] is None
    assert d["height_accuracy"]["forms"]["instruction"]["max_planned_height_m"] > 2000
    assert d["constraints"]["PZ"]["details"]["stereo_base_steps"] == pytest.approx(2.8)


# --- the example and the project keys --------------------------------------------------------
def test_example_uav_canon_2000_headline():
    """examples/uav-canon-2000.toml: 1:2000, h_c 0.5 m, planned 300 m, flown +40 %, ceiling
    raised to 500 m (airspace-use permission). The digital height accuracy binds: maximum
    planned 214 m (flown up to 300 m), recommended 210 m (flown up to 294 m)."""
    result = plan_project(load_project(ROOT / "examples" / "uav-canon-2000.toml"))
    u = result.uav
    p = u.job.plan
    assert p.binding == "PZ"
    assert u.max_height_m == pytest.approx(213.95, abs=0.05)
    assert u.recommended_height_m == 210
    assert p.heights_m["max"] == pytest.approx(294)
    assert p.heights_m["max"] <= p.ceiling_m == 500
    assert p.max_flown_height_m == pytest.approx(299.5, abs=0.1)
    sz = p.height_accuracy["sigma_z_at_highest_flown_height_m"]
    assert sz <= p.height_accuracy["height_accuracy_m"] == pytest.approx(0.1)
    doc = plan_result_dict(result)["specification"]["uav"]
    assert doc["recommended_height_m"] == 210
    assert doc["max_planned_height_m"] == pytest.approx(213.95, abs=0.05)
    assert doc["recommended_flown_height_m"] == pytest.approx(294)
    assert doc["ceiling_m"] == 500 and doc["binding"] == "PZ"


def test_example_without_the_permission_stays_under_150_m(tmp_path):
    text = (ROOT / "examples" / "uav-canon-2000.toml").read_text(encoding="utf-8")
    text = text.replace("max_height_m = 500\n", "")
    path = tmp_path / "p.toml"
    path.write_text(text, encoding="utf-8")
    u = plan_project(load_project(path)).uav
    assert u.job.plan.binding == "HC"
    assert u.recommended_height_m == 105 and u.job.plan.heights_m["max"] <= 150
    assert u.job.plan.constraints_max_height_m == pytest.approx(213.95, abs=0.05)


def test_project_keys(tmp_path):
    text = (ROOT / "examples" / "uav-canon-2000.toml").read_text(encoding="utf-8")
    path = tmp_path / "p.toml"
    path.write_text(text.replace("max_height_m = 500\n", 'max_height_m = 500\ngsd_cm = 2\n'
                                 'height_formula = "instruction"\n'), encoding="utf-8")
    u = plan_project(load_project(path)).uav
    assert u.job.plan.binding == "GSD"
    assert u.job.plan.height_accuracy["formula"] == "instruction"
    path.write_text(text.replace("max_height_m = 500", "max_height_m = -5"), encoding="utf-8")
    r = CliRunner().invoke(main, ["plan", str(path)])
    assert r.exit_code == 2 and "uav.max_height_m" in r.stderr
    path.write_text(text.replace("max_height_m = 500", 'height_formula = "sideways"'),
                    encoding="utf-8")
    r = CliRunner().invoke(main, ["plan", str(path)])
    assert r.exit_code == 2 and "uav.height_formula" in r.stderr


def test_norm_parameters_carry_their_sources():
    for name in ("gkinp-02-036-02", "gkinp-02-036-02-printed"):
        ns = load_norm_set(name)
        for key in ("digital_height_formula", "image_measurement_px", "multi_ray",
                    "uav_max_height_m"):
            assert ns.parameter_sources[key], (name, key)
        # each source names works of the bibliography, which give the full reference
        from scanplan.reports.references import Bibliography

        for key, works in (("uav_max_height_m", ("No. 1016", "52(3)")),
                           ("image_measurement_px", ("Measurement, 2017, vol. 98",
                                                     "Close-Range Photogrammetry")),
                           ("digital_height_formula", ("Photogrammetry: Geometry from Images",
                                                       "Close-Range Photogrammetry"))):
            bib = Bibliography("en")
            cited = bib.cite(ns.parameter_sources[key])
            assert cited.startswith("[1]"), (key, cited)
            entries = " ".join(text for _, text in bib.entries())
            for w in works:
                assert w in entries, (key, w)


def test_height_plot_marks_planned_flown_and_maximum():
    from scanplan.reports.plots import height_svg
    from scanplan.reports.views import ResultTables

    job = uav_job(**SEED002, map_scale=2000, relief_interval_m=0.5, max_height_m=500)
    svg = height_svg(ResultTables.of_jobs(None, job))
    for text in ("planned: 300", "highest flown: 420", "maximum planned (PZ): 214",
                 "highest flown at the maximum: 300"):
        assert text in svg, text


def test_a_stored_set_older_than_the_digital_parameters_still_loads(tmp_path):
    """A norm set stored before the digital-height and ceiling parameters existed takes them
    from the bundled set, and its source says so."""
    import shutil

    src = ROOT / "norms" / "gkinp-02-036-02"
    dst = tmp_path / "old-set"
    shutil.copytree(src, dst)
    lines = (dst / "parameters.csv").read_text(encoding="utf-8").splitlines(keepends=True)
    later = ("digital_height_formula", "image_measurement_px", "multi_ray", "uav_max_height_m")
    (dst / "parameters.csv").write_text("".join(x for x in lines if not x.startswith(later)),
                                        encoding="utf-8")
    ns = load_norm_set(str(dst))
    assert ns.parameters["uav_max_height_m"] == 150
    assert "this set predates the parameter" in ns.parameter_sources["multi_ray"]
    # a set missing an original parameter is still refused
    (dst / "parameters.csv").write_text("".join(x for x in lines if not x.startswith("shape,")),
                                        encoding="utf-8")
    with pytest.raises(InputError, match="missing parameters: shape"):
        load_norm_set(str(dst))


def test_a_ceiling_below_the_rounding_step_is_never_exceeded(tmp_path):
    """A 6 m ceiling flown +40 %: at most 4.3 m planned; recommended 4 m (1 m steps below
    5 m), never the provisional height."""
    text = (ROOT / "examples" / "uav-canon-2000.toml").read_text(encoding="utf-8")
    path = tmp_path / "low.toml"
    path.write_text(text.replace("max_height_m = 500", "max_height_m = 6").replace(
        "height_m = 300\n", ""), encoding="utf-8")
    u = plan_project(load_project(path)).uav
    assert u.recommended_height_m == 4 and u.job.plan.heights_m["max"] <= 6
    job = uav_job(**{**SEED002, "height_m": None}, gsd_cm=3.0, max_height_m=6)
    assert job.plan.heights_m["planned"] == 4
    r = CliRunner().invoke(main, ["uav", "--camera", "dji-mavic-3e", "--gsd-cm", "2",
                                  "--max-height-m", "1.2", "--height-tolerance-pct", "40"])
    assert r.exit_code == 2 and "--height-m" in r.stderr


@settings(max_examples=40, deadline=None)
@given(ceiling=st.floats(2, 3000), tol=st.floats(0, 80), gsd=st.floats(0.5, 30))
def test_a_derived_height_never_flies_above_the_ceiling(ceiling, tol, gsd):
    """Whatever the ceiling, tolerance and target GSD: the planned height is the rounded
    maximum, its highest flown height is within the ceiling and the target GSD holds there."""
    job = uav_job(camera="dji-mavic-3e", height_tolerance_pct=tol, gsd_cm=gsd,
                  max_height_m=ceiling)
    p = job.plan
    assert p.heights_m["planned"] <= p.max_height_m * (1 + 1e-9)
    assert p.heights_m["max"] <= ceiling * (1 + 1e-9)
    assert p.gsd_at_max_height_m <= gsd / 100 * (1 + 1e-9)
    assert p.max_flown_height_m == pytest.approx(p.max_height_m * (1 + tol / 100))
    gsd_height = gsd / 100 * p.inputs.focal_mm / (p.inputs.pixel_um / 1000)
    assert p.binding == ("HC" if ceiling < gsd_height else "GSD")


def test_pdf_inputs_show_the_ceiling_and_the_target_gsd(tmp_path):
    pytest.importorskip("weasyprint")
    pypdf = pytest.importorskip("pypdf")
    import io

    from scanplan.reports import ReportMeta
    from scanplan.reports.pdf import render_pdf

    job = uav_job(**SEED002, map_scale=2000, relief_interval_m=0.5, max_height_m=500,
                  gsd_cm=3.0)
    for locale, words in (("en", ("Altitude ceiling (highest flown height), m",
                                  "Target GSD, cm", "Maximum planned height by height formula")),
                          ("ru", ("Предельная высота полёта (наибольшая фактическая), м",
                                  "Заданный размер пикселя на местности, см",
                                  "Максимальная плановая высота по формулам точности высот"))):
        data = render_pdf(uav=job, meta=ReportMeta(project="p", locale=locale))
        text = " ".join(" ".join(pg.extract_text().split())
                        for pg in pypdf.PdfReader(io.BytesIO(data)).pages)
        for w in words:
            assert w in text, (locale, w)
