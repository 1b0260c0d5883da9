"""An area far out of its planning projection's zone is warned about (a mistyped longitude
once planned silently as 5,850 km² in one UTM zone): the projection's scale error over the
area's vertices, against the 0.1 % a 6° UTM zone stays within."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.geo.area import MAX_SCALE_ERROR_PCT, AreaSpec, load_area

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
KML = EXAMPLES / "areas" / "town-uav.kml"


def _k_tm(lon_deg: float, lat_deg: float, cm_deg: float, k0: float = 0.9996) -> float:
    """Transverse Mercator point scale to second order (Snyder 1987, eq. 8-11 leading
    terms): k ≈ k0 (1 + ((λ − λ0) cos φ)² / 2)."""
    a = math.radians(lon_deg - cm_deg) * math.cos(math.radians(lat_deg))
    return k0 * (1.0 + a * a / 2.0)


def test_an_area_in_its_own_zone_is_within_the_bound():
    area = load_area(AreaSpec(file=KML))
    assert area.plan_crs == "EPSG:32637"  # UTM 37N, central meridian 39°E
    west, east = area.lon_range_deg
    assert 38.7 < west < east < 38.9
    # near the central meridian: |k − 1| ≈ 1 − k0 = 0.04 %
    assert area.scale_error_pct == pytest.approx(0.04, abs=0.002)
    assert area.scale_error_pct < MAX_SCALE_ERROR_PCT


def test_a_far_zone_gives_the_transverse_mercator_scale_error():
    area = load_area(AreaSpec(file=KML, plan_crs="EPSG:32634"))  # central meridian 21°E
    lat = area.centroid_lonlat[1]
    expected = (_k_tm(area.lon_range_deg[1], lat, 21.0) - 1.0) * 100.0
    assert area.scale_error_pct == pytest.approx(expected, rel=0.02)
    assert area.scale_error_pct > MAX_SCALE_ERROR_PCT


def test_a_mistyped_longitude_is_far_beyond_the_bound():
    # a sliver whose third vertex was typed 57.6 instead of 37.6: planned in one UTM zone
    # (the one of its representative point, UTM 38N), 12.6° of longitude from the far vertex
    area = load_area(AreaSpec(polygon=[[37.5, 56.0], [37.6, 56.0], [57.6, 56.02],
                                       [37.5, 56.05], [37.5, 56.0]]))
    assert area.scale_error_pct > 5 * MAX_SCALE_ERROR_PCT
    assert area.lon_range_deg == pytest.approx((37.5, 57.6))


def test_a_few_degrees_out_of_the_zone_is_not_warned():
    # 4.6° east of UTM 37N's central meridian at 56°N: k ≈ 1.0006, within the bound — the
    # check is about the projection, not about how the area was drawn
    area = load_area(AreaSpec(polygon=[[37.5, 56.0], [37.6, 56.0], [43.6, 56.02],
                                       [37.5, 56.05], [37.5, 56.0]]))
    assert area.scale_error_pct < MAX_SCALE_ERROR_PCT


def test_a_rectangle_has_no_projection():
    area = load_area(AreaSpec(width_m=1000, length_m=2000))
    assert area.scale_error_pct is None and area.lon_range_deg is None


def _project(tmp_path: Path, plan_crs: str | None, locale: str = "en") -> Path:
    text = (EXAMPLES / "uav-town-2000.toml").read_text(encoding="utf-8")
    text = text.replace('file = "areas/town-uav.kml"', f'file = "{KML.as_posix()}"'
                        + (f'\nplan_crs = "{plan_crs}"' if plan_crs else ""))
    text = text.replace('locale = "en"', f'locale = "{locale}"')
    p = tmp_path / "p.toml"
    p.write_text(text, encoding="utf-8")
    return p


@pytest.mark.parametrize(("plan_crs", "warned"), [(None, False), ("EPSG:32634", True)])
def test_the_plan_warns_only_out_of_the_zone(tmp_path, plan_crs, warned):
    r = CliRunner().invoke(main, ["plan", str(_project(tmp_path, plan_crs)), "--json"])
    assert r.exit_code == 0, r.output
    codes = [w["code"] for w in json.loads(r.output)["warnings"]]
    assert ("area_scale_distortion" in codes) is warned, codes


def test_the_warning_speaks_russian(tmp_path):
    r = CliRunner().invoke(main, ["plan", str(_project(tmp_path, "EPSG:32634", "ru"))])
    assert r.exit_code == 0, r.output
    assert "Проекция планирования EPSG:32634 растягивает местность до 1,5" in r.output, \
        r.output
