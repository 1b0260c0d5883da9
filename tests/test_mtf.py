"""MTF chain, threshold contrast and the resolving-power solver (seed 000, spec §3)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanplan.core import mtf

# --- the seed 002 case: Canon EOS 5D Mark II (36 × 24 mm, 5616 × 3744 px) ------------
# Seed 002 gives neither lens nor speed nor exposure; the assumptions (docs/uav-models.md):
# 50 mm lens at f/8, 25 m/s, 1/1000 s, August (summer: shift factor 0.65), light-UAV
# random motion 1 m/s and 0.02 rad/s about each axis; defaults for the rest.
CANON = mtf.Camera(
    pixel_um=36.0 / 5616 * 1000,
    focal_mm=50.0,
    f_number=8.0,
    sensor_width_mm=36.0,
    sensor_height_mm=24.0,
)
SEED002_MOTION = mtf.Motion(
    random_speed_ms=1.0, roll_rate_rad_s=0.02, pitch_rate_rad_s=0.02, yaw_rate_rad_s=0.02
)


def seed002_flight(height_m):
    return mtf.Flight(height_m=height_m, speed_ms=25.0, exposure_s=1e-3, shift_factor=0.65)


# ---------------------------------------------------------------------------------
# Components: analytic checks
# ---------------------------------------------------------------------------------
def test_diffraction_mtf_at_half_cutoff_is_0_3910():
    v = float(mtf.diffraction_mtf(0.5))
    assert round(v, 4) == 0.3910
    assert v == pytest.approx((2 / math.pi) * (math.acos(0.5) - 0.5 * math.sqrt(0.75)), 1e-15)
    np.testing.assert_allclose(mtf.diffraction_mtf([0.0, 1.0, 1.5]), [1.0, 0.0, 0.0], atol=1e-15)
    assert np.all(np.diff(mtf.diffraction_mtf(np.linspace(0, 1, 101))) < 0)


def test_diffraction_cutoff_centre_and_corner():
    nc = mtf.diffraction_cutoff_lpmm(8.0, 0.55)
    assert nc == pytest.approx(1 / (0.55e-3 * 8))  # 227.3 lines/mm
    beta = mtf.half_field_angle_rad(36.0, 24.0, 50.0)
    assert beta == pytest.approx(math.atan(math.hypot(36, 24) / 100))
    sag = mtf.diffraction_cutoff_lpmm(8.0, 0.55, beta, "sagittal")
    tan = mtf.diffraction_cutoff_lpmm(8.0, 0.55, beta, "tangential")
    assert sag == pytest.approx(nc * math.cos(beta))
    assert tan == pytest.approx(nc * math.cos(beta) ** 3)
    assert mtf.lens_diffraction_mtf(nc / 2, 8.0) == pytest.approx(0.3910, abs=5e-5)


def test_pixel_sinc_has_its_zero_at_one_over_aperture():
    p_um = 5.0
    assert mtf.pixel_aperture_mtf(1000.0 / p_um, p_um) == pytest.approx(0.0, abs=1e-15)
    # fill factor 0.64 → aperture 0.8 p → zero at 1/(0.8 p)
    assert mtf.pixel_aperture_mtf(1000.0 / (0.8 * p_um), p_um, 0.64) == pytest.approx(0, abs=1e-15)
    # at Nyquist 1/(2p): sinc(π/2) = 2/π
    assert mtf.pixel_aperture_mtf(500.0 / p_um, p_um) == pytest.approx(2 / math.pi)
    assert mtf.pixel_aperture_mtf(0.0, p_um) == 1.0


@settings(max_examples=50, deadline=None)
@given(st.floats(0.0, 300.0), st.floats(1.0, 200.0), st.floats(0.0, 50.0), st.floats(0.0, 0.02))
def test_gaussian_components_match_exp_minus_2pi2_sigma2_n2(n, f, gamma_urad, sigma_mm):
    s_turb = f * gamma_urad * 1e-6
    assert mtf.turbulence_mtf(n, f, gamma_urad) == pytest.approx(
        math.exp(-2 * math.pi**2 * s_turb**2 * n**2), rel=1e-12
    )
    assert mtf.random_motion_mtf(n, sigma_mm) == pytest.approx(
        math.exp(-2 * math.pi**2 * sigma_mm**2 * n**2), rel=1e-12
    )


def test_linear_motion_trapezoid():
    n = np.linspace(0, 400, 801)
    d = 0.004
    np.testing.assert_allclose(mtf.linear_motion_mtf(n, d, 1.0), np.abs(np.sinc(n * d)))
    # η and 1 − η give the same trapezoid: the product of sincs of widths 0.7·δ and 0.3·δ
    np.testing.assert_allclose(mtf.linear_motion_mtf(n, d, 0.7),
                               np.abs(np.sinc(n * 0.7 * d) * np.sinc(n * 0.3 * d)))
    # first zero at 1 / (max(η, 1 − η)·δ)
    assert mtf.linear_motion_mtf(1 / (0.7 * d), d, 0.7) == pytest.approx(0.0, abs=1e-15)
    # a slower opening (smaller η) transfers less at the same frequency
    assert mtf.linear_motion_mtf(100.0, d, 0.7) > mtf.linear_motion_mtf(100.0, d, 1.0) - 1


@pytest.mark.parametrize("eta", [0.3, 0.0, 0.4999, 1.01])
def test_shutter_efficiency_outside_half_to_one_is_refused(eta):
    """Regression (cross-check of issue 16): η < 0.5 describes the same trapezoid as
    1 − η, so η = 0.3 used to act silently as 0.7; it is refused, in the component and in
    the whole chain."""
    with pytest.raises(ValueError, match=r"shutter_efficiency must be in \[0.5, 1\]"):
        mtf.linear_motion_mtf(10.0, 0.004, eta)
    cam = mtf.Camera(4.0, 35.0, 5.6, 36.0, 24.0, shutter_efficiency=eta)
    with pytest.raises(ValueError, match="shutter_efficiency"):
        mtf.uav_resolution(cam, mtf.Flight(300.0, 25.0, 0.001))


def test_shutter_efficiency_bounds_are_accepted():
    for eta in (0.5, 1.0):
        assert 0 < float(mtf.linear_motion_mtf(10.0, 0.004, eta)) <= 1


def test_image_shift_formulas():
    assert mtf.geometric_image_shift_mm(25.0, 1e-3, 50.0, 300.0) == pytest.approx(25e-3 * 50 / 300)
    assert mtf.photographic_image_shift_mm(0.004, 0.65) == pytest.approx(0.0026)
    assert mtf.angular_shift_tilt_mm(0.02, 1e-3, 50.0, 0.0) == pytest.approx(0.02e-3 * 50)
    assert mtf.angular_shift_tilt_mm(0.02, 1e-3, 50.0, 21.6) == pytest.approx(
        0.02e-3 * (50**2 + 21.6**2) / 50
    )
    assert mtf.angular_shift_yaw_mm(0.02, 1e-3, 21.6) == pytest.approx(0.02e-3 * 21.6)
    assert mtf.random_shift_rms_mm(3e-3, 4e-3) == pytest.approx(5e-3)


def test_haze_models_and_dispatch():
    n = np.array([0.0, 10.0, 100.0])
    np.testing.assert_array_equal(mtf.haze_mtf(n), [0.9, 0.9, 0.9])
    np.testing.assert_array_equal(mtf.haze_mtf(n, contrast_coefficient=0.8), [0.8] * 3)
    t = mtf.haze_mtf(
        n,
        "exponential-indicatrix",
        focal_mm=50.0,
        height_m=400.0,
        scattering_per_km=0.2,
        indicatrix_per_rad=10.0,
    )
    assert t[0] == 1.0
    assert t[-1] == pytest.approx(math.exp(-0.08), rel=1e-4)  # → exp(−μH) at high N
    assert np.all(np.diff(t) < 0)
    with pytest.raises(ValueError, match=r"^method must be one of"):
        mtf.haze_mtf(n, "mie")


def test_sensor_transfer_and_diffusion():
    n = np.linspace(0, 100, 11)
    np.testing.assert_array_equal(mtf.charge_transfer_mtf(n, 5.0), np.ones(11))  # CMOS
    # at Nyquist cos(π) = −1: exp(−2nε)
    assert mtf.charge_transfer_mtf(100.0, 5.0, 1000, 1e-4) == pytest.approx(math.exp(-0.2))
    np.testing.assert_allclose(mtf.diffusion_mtf(n), 1.0)  # off by default
    td = mtf.diffusion_mtf(n, diffusion_length_um=10.0)
    assert td[0] == pytest.approx(1.0) and np.all(np.diff(td) < 0) and td[-1] > 0


def test_lens_table_replaces_the_formula():
    t = mtf.lens_table_mtf([0, 5, 10, 20, 40, 60], [10, 30, 50], [0.9, 0.7, 0.4])
    np.testing.assert_allclose(t, [1.0, 0.95, 0.9, 0.8, 0.55, 0.0])
    cam = mtf.Camera(5.0, 35.0, 5.6, 35.9, 24.0, lens_table_centre=([10, 30, 50], [0.9, 0.7, 0.4]))
    comps = mtf.component_mtfs(np.array([20.0]), cam, mtf.Flight(100.0, 0.0, 1e-3))
    assert comps["lens"][0] == pytest.approx(0.8)


def test_threshold_models_and_dispatch():
    rm = 78.0
    k = mtf.threshold_contrast(np.array([0.0, rm / 2, rm]), rm)
    np.testing.assert_allclose(k, [0.03, math.sqrt(0.03), 1.0])
    k = mtf.threshold_contrast(np.array([0.0, rm]), rm, k0=0.05)
    np.testing.assert_allclose(k, [0.05, 1.0])
    t = mtf.threshold_contrast(
        np.array([0.0, 39.0]),
        rm,
        "table",
        table_freq_lpmm=[0, 1],
        table_k=[0.02, 1.0],
        relative=True,
    )
    np.testing.assert_allclose(t, [0.02, 0.51])
    with pytest.raises(ValueError, match=r"^method must be one of"):
        mtf.threshold_contrast(1.0, rm, "weibull")
    with pytest.raises(ValueError, match=r"^method must be one of"):
        mtf.resolving_power(CANON, seed002_flight(300.0), threshold=mtf.Threshold("weibull"))


def test_object_contrast_and_weber():
    assert mtf.object_contrast(0.3, 0.1) == pytest.approx(0.5)
    assert mtf.weber_to_michelson(2 / 3) == pytest.approx(0.5)  # (0.3 − 0.1)/0.3
    with pytest.raises(ValueError, match=r"^r_min must be <= r_max"):
        mtf.object_contrast(0.1, 0.3)


# ---------------------------------------------------------------------------------
# Solver
# ---------------------------------------------------------------------------------
@settings(max_examples=60, deadline=None)
@given(st.floats(0.05, 1.0), st.floats(0.01, 0.049), st.floats(1.5, 12.0))
def test_with_every_degradation_off_R_is_the_root_of_Kobj_equals_Kthr(kobj, k0, pixel_um):
    """T ≡ 1: K_obj = K0^(1 − R/R_m) ⇒ R = R_m·(1 − ln K_obj / ln K0), exactly."""
    r_max = 1.0
    r_min = (1 - kobj) / (1 + kobj)  # gives K_obj
    cam = mtf.Camera(pixel_um, 35.0, 5.6, 35.9, 24.0)
    rp = mtf.resolving_power(
        cam,
        mtf.Flight(100.0, 10.0, 1e-3),
        scene=mtf.Scene(r_max, r_min),
        threshold=mtf.Threshold(params={"k0": k0}),
        disable=mtf.COMPONENTS,
    )
    rm = 500.0 / pixel_um
    expected = rm * (1 - math.log(kobj) / math.log(k0))
    assert bool(rp.resolvable)
    assert float(rp.r_lpmm) == pytest.approx(expected, rel=1e-10, abs=1e-9)
    # K_obj = 1 puts the crossing at R_m (sensor-limited); a K_obj one ulp below 1 (from the
    # r_min round trip) lands within the solver's 1e-12 band of R_m, so only clear cases count
    if kobj >= 1.0:
        assert bool(rp.sensor_limited)
    elif kobj < 1.0 - 1e-9:
        assert not bool(rp.sensor_limited)


def test_not_resolvable_is_a_result_not_a_number():
    scene = mtf.Scene(r_max=0.101, r_min=0.099)  # K_obj = 0.01 < K0 = 0.03
    res = mtf.ground_resolution(CANON, seed002_flight(300.0), scene=scene)
    assert not bool(res.resolvable)
    assert math.isnan(float(res.r_lpmm))
    assert math.isnan(float(res.ground_resolution_m))
    assert math.isnan(float(res.l_over_gsd))
    assert float(res.gsd_m) == pytest.approx(0.0384615, rel=1e-5)  # GSD still exists
    # boundary: K_obj·c = K0 exactly is not resolvable (K ≤ K_thr at 0+)
    atm = mtf.Atmosphere(contrast_coefficient=0.06)
    rp = mtf.resolving_power(CANON, seed002_flight(300.0), atm, scene=mtf.Scene(0.75, 0.25))
    assert not bool(rp.resolvable)


def test_sensor_limited_when_curves_do_not_cross_below_nyquist():
    thr = mtf.Threshold(
        "table", {"table_freq_lpmm": [0.0, 1.0], "table_k": [0.01, 0.01], "relative": True}
    )
    rp = mtf.resolving_power(CANON, seed002_flight(300.0), threshold=thr, disable=mtf.COMPONENTS)
    assert bool(rp.sensor_limited) and float(rp.r_lpmm) == pytest.approx(78.0)


def test_generic_solver_returns_the_first_crossing():
    def margin(n):  # crosses at 20, recovers above 0 after 40, crosses again at 70
        return np.where(n < 40, 0.5 - n / 40, np.sin((n - 40) / 30 * np.pi) * 0.3 - 0.1)

    rp = mtf.solve_resolving_power(margin, np.array([100.0, 100.0]), grid_points=33)
    np.testing.assert_allclose(rp.r_lpmm, [20.0, 20.0], atol=1e-9)


def test_mixed_precision_agrees_with_double():
    rng = np.random.default_rng(7)
    n = 2000
    cam = mtf.Camera(
        rng.uniform(2, 7, n),
        rng.uniform(8, 80, n),
        rng.uniform(2.8, 11, n),
        35.9,
        24.0,
        shutter_efficiency=rng.uniform(0.5, 1, n),
    )
    flight = mtf.Flight(
        rng.uniform(50, 500, n),
        rng.uniform(0, 30, n),
        rng.uniform(2.5e-4, 4e-3, n),
        rng.uniform(0.6, 1, n),
    )
    mot = mtf.Motion(rng.uniform(0, 1, n), rng.uniform(0, 0.05, n), 0.01, 0.01)
    a = mtf.resolving_power(cam, flight, motion=mot, precision="mixed")
    b = mtf.resolving_power(
        cam, flight, motion=mot, precision="double", iterations=40, grid_points=17
    )
    np.testing.assert_array_equal(a.resolvable, b.resolvable)
    np.testing.assert_allclose(a.r_lpmm, b.r_lpmm, atol=1e-6)


def test_broadcasts_over_n_dimensional_configurations():
    h = np.array([[100.0, 200.0, 300.0], [400.0, 500.0, 600.0]])
    res = mtf.ground_resolution(CANON, mtf.Flight(h, np.array([[5.0], [20.0]]), 1e-3))
    assert res.r_lpmm.shape == res.ground_resolution_m.shape == res.gsd_m.shape == (2, 3)
    grid = np.linspace(0, 78, 14)
    curves = mtf.contrast_curves(grid, CANON, mtf.Flight(h, 10.0, 1e-3))
    assert set(curves) == {*mtf.COMPONENTS, "system", "image_contrast", "threshold"}
    assert all(v.shape == (2, 3, 14) for v in curves.values())
    np.testing.assert_allclose(curves["image_contrast"], 0.5 * curves["system"])


def test_components_can_be_switched_off():
    grid = np.linspace(0, 78, 5)
    comps = mtf.component_mtfs(grid, CANON, seed002_flight(300.0), disable=["lens", "haze"])
    np.testing.assert_array_equal(comps["lens"], 1.0)
    np.testing.assert_array_equal(comps["haze"], 1.0)
    assert comps["pixel"][-1] == pytest.approx(2 / math.pi)
    with pytest.raises(ValueError, match=r"^disable must name components"):
        mtf.component_mtfs(grid, CANON, seed002_flight(300.0), disable=["shutter"])
    full = mtf.resolving_power(CANON, seed002_flight(300.0)).r_lpmm
    assert mtf.resolving_power(CANON, seed002_flight(300.0), disable=["lens"]).r_lpmm > full


# ---------------------------------------------------------------------------------
# Properties: L ≥ GSD; L grows with height, speed, exposure and angular rates
# ---------------------------------------------------------------------------------
def _batch(rng, n):
    cam = mtf.Camera(
        rng.uniform(2, 7, n),
        rng.uniform(8, 80, n),
        rng.uniform(2.8, 11, n),
        35.9,
        24.0,
        shutter_efficiency=rng.uniform(0.5, 1, n),
    )
    return cam, rng.uniform(50, 500, n), rng.uniform(0, 30, n), rng.uniform(2.5e-4, 4e-3, n)


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**31 - 1), st.sampled_from(["centre", "corner"]))
def test_ground_resolution_is_never_finer_than_gsd(seed, field):
    rng = np.random.default_rng(seed)
    cam, h, w, t = _batch(rng, 200)
    res = mtf.ground_resolution(
        cam, mtf.Flight(h, w, t), motion=mtf.Motion(0.5, 0.02, 0.02, 0.02), field=field
    )
    ok = res.resolvable
    assert np.all(res.ground_resolution_m[ok] >= res.gsd_m[ok] * (1 - 1e-12))
    np.testing.assert_allclose(
        res.l_over_gsd[ok], (res.resolving_power.nyquist_lpmm / res.r_lpmm)[ok]
    )


@settings(max_examples=25, deadline=None)
@given(
    st.integers(0, 2**31 - 1),
    st.sampled_from(["height", "speed", "exposure", "rates"]),
    st.floats(1.01, 3.0),
)
def test_ground_resolution_grows_with_height_speed_exposure_and_rates(seed, what, factor):
    rng = np.random.default_rng(seed)
    cam, h, w, t = _batch(rng, 200)
    rates = rng.uniform(0, 0.05, 200)
    base = dict(h=h, w=w, t=t, r=rates)
    more = dict(base)
    key = {"height": "h", "speed": "w", "exposure": "t", "rates": "r"}[what]
    more[key] = base[key] * factor

    def ell(p):
        return mtf.ground_resolution(
            cam,
            mtf.Flight(p["h"], p["w"], p["t"]),
            motion=mtf.Motion(0.3, p["r"], p["r"], p["r"]),
            field="corner",
        ).ground_resolution_m

    l0, l1 = ell(base), ell(more)
    assert np.all(l1 >= l0 * (1 - 1e-9))
    assert np.any(l1 > l0)


# ---------------------------------------------------------------------------------
# Seed 002 worked example (docs/uav-models.md): Canon 5D Mark II, 300 m planned, 420 m flown
# ---------------------------------------------------------------------------------
def _independent_r(height_m, corner=False):
    """The same chain written again with math only, solved by a plain bisection."""
    p = 36.0 / 5616  # mm
    f, n0, lam, t, w = 50.0, 8.0, 0.55e-3, 1e-3, 25.0
    beta = math.atan(math.hypot(36, 24) / (2 * f)) if corner else 0.0
    q = math.hypot(36, 24) / 2 if corner else 0.0
    nc = math.cos(beta) ** (3 if corner else 1) / (lam * n0)
    delta = 0.65 * w * t * f / height_m
    tilt = 0.02 * t * (f * f + q * q) / f
    sigma2 = (1.0 * t * f / height_m) ** 2 + 2 * tilt**2 + (0.02 * t * q) ** 2
    fg = f * 5e-6
    rm = 1 / (2 * p)

    def sinc(x):
        return 1.0 if x == 0 else abs(math.sin(math.pi * x) / (math.pi * x))

    def margin(n):
        nu = min(n / nc, 1.0)
        t_o = 2 / math.pi * (math.acos(nu) - nu * math.sqrt(1 - nu * nu))
        t_all = 0.9 * math.exp(-2 * math.pi**2 * (fg**2 + sigma2) * n * n) * t_o
        t_all *= sinc(p * n) * sinc(n * delta)
        return 0.5 * t_all - 0.03 ** (1 - n / rm)

    lo, hi = 0.0, min(rm, 1 / delta)
    for _ in range(100):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if margin(mid) > 0 else (lo, mid)
    return (lo + hi) / 2


@pytest.mark.parametrize("height_m", [300.0, 420.0])
def test_seed_002_worked_example(height_m):
    res = mtf.uav_resolution(CANON, seed002_flight(height_m), motion=SEED002_MOTION)
    gsd = (36.0 / 5616) * height_m / 50.0
    for g, corner in ((res.centre, False), (res.corner, True)):
        r = _independent_r(height_m, corner)
        ell = height_m / (2 * r * 50.0)
        assert float(g.gsd_m) == pytest.approx(gsd, rel=1e-12)
        assert float(g.r_lpmm) == pytest.approx(r, abs=1e-8)
        assert float(g.ground_resolution_m) == pytest.approx(ell, rel=1e-9)
        assert float(g.l_over_gsd) == pytest.approx(ell / gsd, rel=1e-9)
    # the numbers printed in docs/uav-models.md
    table = {300.0: (3.85, 47.3, 6.34, 1.65, 0.910), 420.0: (5.38, 47.5, 8.84, 1.64, 0.832)}
    gsd_cm, r_c, l_cm, ratio, prob = table[height_m]
    c = res.centre
    assert round(float(c.gsd_m) * 100, 2) == gsd_cm
    assert round(float(c.r_lpmm), 1) == r_c
    assert round(float(c.ground_resolution_m) * 100, 2) == l_cm
    assert round(float(c.l_over_gsd), 2) == ratio
    # recognition of a 0.20 m pole (circle, B = 0.97) at 1:2000: P = exp(−(B·L/L_obj)²)
    p = math.exp(-((0.97 * float(c.ground_resolution_m) / 0.20) ** 2))
    assert round(p, 3) == prob


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"pixel_um": -1.0}, "pixel_um must be > 0 (got -1)"),
        ({"f_number": 0.0}, "f_number must be > 0 (got 0)"),
        ({"focal_mm": float("nan")}, "focal_mm must be finite (got nan)"),
    ],
)
def test_invalid_camera_names_the_field(kwargs, message):
    fields = dict(
        pixel_um=6.41, focal_mm=50.0, f_number=8.0, sensor_width_mm=36.0, sensor_height_mm=24.0
    )
    fields.update(kwargs)
    with pytest.raises(ValueError) as err:
        mtf.resolving_power(mtf.Camera(**fields), seed002_flight(300.0))
    assert str(err.value).startswith(message)


@pytest.mark.parametrize(
    ("flight", "message"),
    [
        (mtf.Flight(300.0, 25.0, 0.0), "exposure_s must be > 0 (got 0)"),
        (mtf.Flight(0.0, 25.0, 1e-3), "height_m must be > 0 (got 0)"),
        (mtf.Flight(300.0, -1.0, 1e-3), "speed_ms must be >= 0 (got -1)"),
    ],
)
def test_invalid_flight_names_the_field(flight, message):
    with pytest.raises(ValueError) as err:
        mtf.ground_resolution(CANON, flight)
    assert str(err.value).startswith(message)
