"""Flight geometry and motion blur (spec formulas.md §3; seed 002 height tolerance)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanplan.core import flight as fl

# Canon EOS 5D Mark II of seed 002: 36 × 24 mm, 5616 × 3744 px; 50 mm lens (assumed).
PIXEL_UM = 36.0 / 5616 * 1000.0
FOCAL_MM = 50.0


def test_gsd_is_pixel_times_height_over_focal():
    assert fl.ground_sample_distance_m(PIXEL_UM, 300.0, FOCAL_MM) == pytest.approx(
        (36.0 / 5616) * 300.0 / 50.0  # p [mm] · H [m] / f [mm] = GSD [m]
    )
    # 6.41 µm at 300 m with f = 50 mm: 3.85 cm
    assert fl.ground_sample_distance_m(PIXEL_UM, 300.0, FOCAL_MM) == pytest.approx(0.0384615, 1e-5)


def test_footprint_base_spacing_seed_002():
    across = fl.footprint_m(36.0, 300.0, FOCAL_MM)
    along = fl.footprint_m(24.0, 300.0, FOCAL_MM)
    assert (across, along) == (pytest.approx(216.0), pytest.approx(144.0))
    assert fl.photo_base_m(along, 80.0) == pytest.approx(28.8)
    assert fl.line_spacing_m(across, 60.0) == pytest.approx(86.4)
    # footprint in pixels × GSD is the same footprint
    assert across == pytest.approx(5616 * fl.ground_sample_distance_m(PIXEL_UM, 300, FOCAL_MM))


def test_photo_interval_and_trigger_limit():
    t = fl.photo_interval_s(28.8, 25.0)
    assert t == pytest.approx(1.152)
    assert bool(fl.trigger_interval_ok(t, 0.256))
    assert not bool(fl.trigger_interval_ok(0.2, 0.7))
    assert fl.max_speed_for_trigger_ms(28.8, 0.7) == pytest.approx(28.8 / 0.7)
    np.testing.assert_array_equal(fl.trigger_interval_ok([0.5, 1.0], 0.7), [False, True])


def test_strips_photos_length_time_volume():
    # 1 km × 2 km block, spacing 86.4 m → ceil(1000/86.4) = 12 strips
    assert int(fl.strip_count(1000.0, 86.4)) == 12
    assert int(fl.strip_count(864.0, 86.4)) == 10  # exact multiple: no extra strip
    assert int(fl.strip_count(1000.0, 86.4, extra_strips=2)) == 14
    # 2000 m / 28.8 m → 70 bases → 71 photos + 1 beyond each end = 73
    assert int(fl.photos_per_strip(2000.0, 28.8)) == 73
    assert int(fl.photos_per_strip(2000.0, 28.8, extra_per_end=0)) == 71
    length = fl.flight_length_m(12, 2000.0, 86.4)
    assert length == pytest.approx(12 * 2000.0 + 11 * math.pi * 86.4 / 2)
    assert fl.flight_length_m(12, 2000.0, 86.4, turn_m=86.4) == pytest.approx(24000 + 11 * 86.4)
    assert fl.flight_time_s(length, 25.0) == pytest.approx(length / 25.0)
    vol = fl.data_volume_bytes(12 * 73, 5616, 3744, bands=3, bits=8)
    assert vol == pytest.approx(12 * 73 * 5616 * 3744 * 3)


def test_motion_blur_and_its_inverses():
    gsd = fl.ground_sample_distance_m(PIXEL_UM, 300.0, FOCAL_MM)
    blur = fl.motion_blur_px(25.0, 1 / 1000, gsd)
    assert blur == pytest.approx(25.0 * 0.001 / gsd)
    assert blur > 0.5  # the seed 002 example needs a shorter exposure at 300 m
    t_max = fl.max_exposure_for_blur_s(25.0, gsd)
    w_max = fl.max_speed_for_blur_ms(1 / 1000, gsd)
    assert fl.motion_blur_px(25.0, t_max, gsd) == pytest.approx(0.5)
    assert fl.motion_blur_px(w_max, 1 / 1000, gsd) == pytest.approx(0.5)
    assert fl.motion_blur_px(0.0, 1 / 1000, gsd) == 0.0  # hovering


@settings(max_examples=50, deadline=None)
@given(
    st.floats(0.5, 40.0),
    st.floats(1e-4, 1e-2),
    st.floats(1e-3, 0.5),
    st.floats(0.1, 2.0),
)
def test_blur_inverses_round_trip(speed, exposure, gsd, limit):
    t = fl.max_exposure_for_blur_s(speed, gsd, limit)
    w = fl.max_speed_for_blur_ms(exposure, gsd, limit)
    assert fl.motion_blur_px(speed, t, gsd) == pytest.approx(limit, rel=1e-12)
    assert fl.motion_blur_px(w, exposure, gsd) == pytest.approx(limit, rel=1e-12)


def test_height_band_seed_002():
    band = fl.height_band(300.0, 0.4, 0.0)  # planned 300 m, flown 300–420 m
    assert (band.min_m, band.planned_m, band.max_m) == (300.0, 300.0, pytest.approx(420.0))
    sym = fl.height_band(300.0, 0.1)
    assert (sym.min_m, sym.max_m) == (pytest.approx(270.0), pytest.approx(330.0))


def test_actual_overlap_seed_002_fixed_trigger_distance():
    # 80 % planned at 300 m, flown at 420 m: 1 − 0.2·300/420
    p = fl.actual_overlap_pct(80.0, 300.0, 420.0)
    assert p == pytest.approx(100 * (1 - 0.2 * 300 / 420))
    assert p == pytest.approx(85.714, abs=1e-3)
    # same thing from the geometry: base fixed at 300 m, footprint at 420 m
    base = fl.photo_base_m(fl.footprint_m(24.0, 300.0, FOCAL_MM), 80.0)
    assert p == pytest.approx(100 * (1 - base / fl.footprint_m(24.0, 420.0, FOCAL_MM)))
    # flown too low, the overlap shrinks and can become a gap (negative, not clipped)
    assert fl.actual_overlap_pct(60.0, 300.0, 200.0) == pytest.approx(40.0)
    assert fl.actual_overlap_pct(20.0, 300.0, 150.0) < 0


def test_vectorised_over_arrays():
    h = np.array([[100.0, 200.0], [300.0, 400.0]])
    g = fl.ground_sample_distance_m(PIXEL_UM, h, FOCAL_MM)
    assert g.shape == (2, 2)
    np.testing.assert_allclose(g, PIXEL_UM * 1e-3 * h / FOCAL_MM)
    assert fl.strip_count(np.array([100.0, 1000.0]), 86.4).tolist() == [2, 12]


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: fl.ground_sample_distance_m(-1, 300, 50), "pixel_um must be > 0 (got -1)"),
        (lambda: fl.ground_sample_distance_m(5, 0, 50), "height_m must be > 0 (got 0)"),
        (lambda: fl.ground_sample_distance_m(5, float("nan"), 50), "height_m must be finite"),
        (lambda: fl.photo_base_m(100, 100), "forward_overlap_pct must be in [0, 100)"),
        (lambda: fl.line_spacing_m(100, -5), "side_overlap_pct must be in [0, 100)"),
        (lambda: fl.motion_blur_px(10, 0, 0.05), "exposure_s must be > 0 (got 0)"),
        (lambda: fl.height_band(300, 0.4, 1.0), "tolerance_down must be in [0, 1)"),
        (lambda: fl.ground_sample_distance_m([5, -2], 300, 50), "pixel_um must be > 0 (got -2)"),
    ],
)
def test_invalid_input_names_the_field(call, message):
    with pytest.raises(ValueError) as err:
        call()
    assert str(err.value).startswith(message)
