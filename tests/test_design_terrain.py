"""The survey design over relief: the one-height rule (ГОСТ Р 59328 §6.2.1, second draft) on
the DEM's samples and its waiver when the flight follows the relief; the GSD of the survey
design sheet at the worst photo."""

from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np
import pytest

from scanplan.project.file import parse_project
from scanplan.project.spec import plan_project
from scanplan.reports.exports import export_files

ROOT = Path(__file__).resolve().parent.parent
VALLEY = ROOT / "examples" / "uav-town-valley-2000.toml"
AFS = ROOT / "examples" / "uav-town-2000-afs.toml"


def _plan(path: Path, replace: tuple[str, str] | None = None):
    text = path.read_text(encoding="utf-8")
    if replace is not None:
        assert replace[0] in text
        text = text.replace(*replace)
    return plan_project(parse_project(text, path))


@pytest.fixture(scope="module")
def valley():
    """The valley flown at one altitude (the example leaves the mode to scanplan)."""
    return _plan(VALLEY, ('altitude_mode = "auto"', 'altitude_mode = "constant"'))


def test_one_height_rule_runs_on_the_dem(valley):
    """The valley example has a DEM and no ground_elevation_m: the rule is checked on the
    ground under the photos (about 100–165 m under a 70 m flight) and asks for a split."""
    d = valley.design
    assert d.block is not None and d.block_ground == "dem" and not d.block_waived
    cols = valley.uav.terrain.layout.photos.columns
    z = np.concatenate([np.asarray(cols[k], dtype=float) for k in
                        ("ground_min_m", "ground_max_m")])
    z = z[np.isfinite(z)]
    assert d.block.ground_min_m == pytest.approx(z.min())
    assert d.block.ground_max_m == pytest.approx(z.max())
    h = valley.uav.recommended_height_m
    assert d.block.flight_height_m == h
    assert d.block.range_pct == pytest.approx(100 * (z.max() - z.min()) / h)
    assert d.block.range_pct > 50 and d.block.split_needed
    codes = {w.code for w in valley.warnings}
    assert "block_split" in codes and "block_height_waived" not in codes


def test_one_height_rule_is_waived_when_following_the_relief():
    r = _plan(VALLEY)  # the example leaves the mode to scanplan: it follows the relief
    assert r.uav.terrain.mode == "follow"
    d = r.design
    assert d.block is not None and d.block_waived and d.block.split_needed
    codes = {w.code for w in r.warnings}
    assert "block_height_waived" in codes and "block_split" not in codes
    w = next(x for x in r.warnings if x.code == "block_height_waived")
    assert "follow" in w.text("en") and "огибанием рельефа" in w.text("ru")
    from scanplan.project.design import design_dict
    block = design_dict(d)["block_height"]
    # waived: the JSON does not ask for a split beside "waived" (the range still exceeds it)
    assert block["waived"] is True and block["split_needed"] is False
    assert block["exceeds_limit"] is True and block["blocks"] == 1


def test_range_is_still_used_without_a_dem():
    r = _plan(AFS)
    assert r.design.block_ground == "range"
    assert (r.design.block.ground_min_m, r.design.block.ground_max_m) == (150, 205)


def _photos_csv_gsd_cm(result) -> np.ndarray:
    files = export_files(result, "out")
    data = next(v[1] for k, v in files.items() if k.endswith("photos.csv"))
    rows = list(csv.DictReader(io.StringIO(data.decode("utf-8-sig"))))
    key = next(k for k in rows[0] if k.startswith("gsd_cm"))
    return np.array([float(r[key]) for r in rows if r[key] not in ("", None)])


def test_survey_design_gsd_is_the_worst_photos_over_the_dem(valley):
    """photos.csv (read back) gives every photo's GSD at its own height above ground; the
    survey design sheet shows the worst one at the highest flown height (+10 %): about
    1.68 cm × 1.1 = 1.85 cm, where the sheet printed the plan's 1.0 cm."""
    gsd = _photos_csv_gsd_cm(valley)
    up = 1 + valley.uav.job.plan.inputs.height_tolerance_up_pct / 100
    g = next(x for x in valley.design.gsd if x.workflow == "digital")
    assert g.gsd_cm == pytest.approx(gsd.max() * up, rel=1e-3)
    assert 1.7 < g.gsd_cm < 2.0


def test_survey_design_gsd_over_a_ground_range():
    """uav-town-2000-afs: ground 150–205 m, the plan 95 m over the highest ground; the
    worst photo is 150 m above the lowest ground: GSD = p·150/c = 1.88 cm, where the
    sheet printed 1.2 cm."""
    r = _plan(AFS)
    inp = r.uav.job.plan.inputs
    h = r.uav.recommended_height_m + 55.0
    up = 1 + inp.height_tolerance_up_pct / 100
    by_hand = inp.pixel_um / 1000 * h * up / inp.focal_mm * 100
    g = next(x for x in r.design.gsd if x.workflow == "digital")
    assert g.gsd_cm == pytest.approx(by_hand, rel=1e-6)
    cols = r.uav.terrain.layout.photos.columns
    assert g.gsd_cm == pytest.approx(np.nanmax(np.asarray(cols["gsd_cm"], float)) * up)
