"""Property tests (hypothesis): monotonicity of every constraint, binding = minimum, and
the inverse max-Mc round-trip."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanplan.core import formulas as F
from scanplan.rules.film import evaluate, max_photo_scale

scale = st.floats(500, 100_000)
relief = st.floats(0.1, 20)
res = st.floats(5, 200)
size_m = st.floats(0.05, 20)
coef = st.floats(0.5, 3.0)
prob = st.floats(0.05, 0.95)
factor = st.floats(1.01, 5)
overlap = st.floats(0, 95)


def scenario(rules, **kw):
    base = dict(map_scale=2000.0, photo_scale=10000.0, relief_interval_m=1.0, focal_mm=153.0,
                frame_along_mm=230.0, forward_overlap_pct=60.0, resolving_power_lpmm=40.0,
                object_size_m=0.2, shape_coefficient=0.97)
    base.update(kw)
    ev = evaluate(rules, **base)
    return {cid: float(ev.pixel_um[i]) for i, cid in enumerate(ev.ids)}


@settings(max_examples=150, deadline=None)
@given(mk=scale, mc=scale, h=relief, r=res, L=size_m, b=coef, p=prob, f=factor)
def test_monotonicity(rules, mk, mc, h, r, L, b, p, f):
    """P_S, P_P ↑ with Mk; P_S, P_Z, P_P, P_D ↓ with Mc; P_Z ↑ with h_c; P_R ↓ with R;
    P_D ↑ with L, ↓ with B and ↓ with P. Others stay unchanged."""
    kw = dict(map_scale=mk, photo_scale=mc, relief_interval_m=h, resolving_power_lpmm=r,
              object_size_m=L, shape_coefficient=b)
    rules = dataclasses.replace(rules, probability=p)
    base = scenario(rules, **kw)

    up = scenario(rules, **{**kw, "map_scale": mk * f})
    assert up["PS"] > base["PS"] and up["PP"] > base["PP"]
    assert up["PZ"] == base["PZ"] and up["PR"] == base["PR"] and up["PD"] == base["PD"]

    up = scenario(rules, **{**kw, "photo_scale": mc * f})
    for cid in ("PS", "PZ", "PP", "PD"):
        assert up[cid] < base[cid]
    assert up["PR"] == base["PR"]

    up = scenario(rules, **{**kw, "relief_interval_m": h * f})
    assert up["PZ"] > base["PZ"] and up["PS"] == base["PS"]

    up = scenario(rules, **{**kw, "resolving_power_lpmm": r * f})
    assert up["PR"] < base["PR"] and up["PD"] == base["PD"]

    up = scenario(rules, **{**kw, "object_size_m": L * f})
    assert up["PD"] > base["PD"]

    up = scenario(rules, **{**kw, "shape_coefficient": b * f})
    assert up["PD"] < base["PD"]

    higher_p = min(0.999, p + (1 - p) * (1 - 1 / f))
    up = scenario(dataclasses.replace(rules, probability=higher_p), **kw)
    assert up["PD"] < base["PD"]


@settings(max_examples=100, deadline=None)
@given(p1=overlap, p2=overlap)
def test_height_forms_move_opposite_ways_with_overlap(p1, p2):
    """More overlap (smaller base b): the printed form allows a coarser pixel, the parallax
    form a finer one (Miheeva & Medvedev 2010)."""
    lo, hi = sorted((p1, p2))
    if hi - lo < 1:
        return
    args = dict(height_accuracy_fraction=0.2, processing_loss_k=2)
    b_lo, b_hi = F.photo_base_mm(230, lo), F.photo_base_mm(230, hi)
    assert F.height_pixel_instruction_um(1, 10000, 153, b_hi, **args) > \
        F.height_pixel_instruction_um(1, 10000, 153, b_lo, **args)
    assert F.height_pixel_parallax_um(1, 10000, 153, b_hi, **args) < \
        F.height_pixel_parallax_um(1, 10000, 153, b_lo, **args)


@settings(max_examples=50, deadline=None)
@given(st.lists(st.tuples(scale, scale, relief, res, size_m, coef), min_size=1, max_size=40))
def test_binding_is_the_minimum(rules, rows):
    """The scan pixel is the minimum of the constraints and the binding one attains it."""
    mk, mc, h, r, L, b = (np.array(c) for c in zip(*rows, strict=True))
    ev = evaluate(rules, map_scale=mk, photo_scale=mc, relief_interval_m=h, focal_mm=153,
                  frame_along_mm=230, forward_overlap_pct=60, resolving_power_lpmm=r,
                  object_size_m=L, shape_coefficient=b)
    assert ev.pixel_um.shape == (5, len(rows))
    np.testing.assert_array_equal(ev.scan_pixel_um, ev.pixel_um.min(axis=0))
    picked = np.take_along_axis(ev.pixel_um, ev.binding_index[None], axis=0)[0]
    np.testing.assert_array_equal(picked, ev.scan_pixel_um)
    assert np.all(ev.margin_pct >= 0)
    assert np.all(ev.margin_pct.min(axis=0) == 0)


@settings(max_examples=150, deadline=None)
@given(mk=scale, h=relief, r=res, L=size_m, b=coef, frac=st.floats(0.05, 1.0))
def test_max_photo_scale_round_trip(rules, mk, h, r, L, b, frac):
    """Mc_max for a pixel ≤ P_R: at Mc_max the scan pixel equals that pixel; any larger Mc
    needs a finer one. A pixel coarser than P_R supports no scale."""
    kw = dict(map_scale=mk, relief_interval_m=h, focal_mm=153.0, frame_along_mm=230.0,
              forward_overlap_pct=60.0, resolving_power_lpmm=r, object_size_m=L,
              shape_coefficient=b)
    pr = float(F.resolving_power_pixel_um(r, pr_coefficient=rules.pr_coefficient))
    pixel = pr * frac
    mc_max, limiting = max_photo_scale(rules, pixel, **kw)
    ev = evaluate(rules, photo_scale=mc_max, **kw)
    np.testing.assert_allclose(ev.scan_pixel_um, pixel, rtol=1e-9)
    assert str(ev.binding) == str(limiting) or np.isclose(
        ev.pixel_um[list(ev.ids).index(str(limiting))], pixel, rtol=1e-9)
    assert float(evaluate(rules, photo_scale=mc_max * 1.001, **kw).scan_pixel_um) < pixel
    none, lim = max_photo_scale(rules, pr * 1.01, **kw)
    assert float(none) == 0.0 and str(lim) == "PR"


@settings(max_examples=100, deadline=None)
@given(L=size_m, b=coef, p=prob, r=res)
def test_interpretation_limit_is_where_pd_meets_pr(rules, L, b, p, r):
    """Mc_interp = 2·L·sqrt(-ln P)·R/B is exactly where P_D = P_R, and the recognition
    probability there equals P."""
    from scanplan.rules.film import interpretation_limit_photo_scale

    mc = interpretation_limit_photo_scale(L, b, p, r)
    pd = F.interpretation_pixel_um(L * 1000, mc, b, p, pr_coefficient=rules.pr_coefficient)
    pr = F.resolving_power_pixel_um(r, pr_coefficient=rules.pr_coefficient)
    np.testing.assert_allclose(pd, pr, rtol=1e-12)
    a = F.resolution_on_ground_mm(mc, r)
    np.testing.assert_allclose(F.recognition_probability(L * 1000, a, b), p, rtol=1e-9)


def test_broadcasting_any_shape(rules):
    """Inputs broadcast: a 3×4 grid of map and photo scales gives (5, 3, 4) constraints."""
    mk = np.array([[2000], [5000], [10000]])
    mc = np.array([5000, 10000, 15000, 20000])
    ev = evaluate(rules, map_scale=mk, photo_scale=mc, relief_interval_m=1.0, focal_mm=153,
                  frame_along_mm=230, forward_overlap_pct=60, resolving_power_lpmm=40,
                  object_size_m=0.2, shape_coefficient=0.97)
    assert ev.pixel_um.shape == (5, 3, 4)
    assert ev.binding.shape == (3, 4)


def test_nan_propagates_not_hidden(rules):
    """The vectorised core does not validate: NaN in gives NaN out (plan_scan validates)."""
    out = F.planimetric_pixel_um(np.nan, 10000, planimetric_accuracy_mm=0.2,
                                 processing_loss_k=2)
    assert np.isnan(out)


def test_scanner_rounding_and_volume():
    """Scanner steps round down; a frame's volume is pixels × bands × bit depth."""
    from scanplan.rules.film import round_to_scanner

    steps = (7, 14, 21, 28)
    np.testing.assert_array_equal(round_to_scanner([12.5, 14.0, 30, 6.9], steps),
                                  [7, 14, 28, np.nan])
    # 230 mm at 12.5 µm = 18400 px per side
    assert F.scanned_frame_bytes(230, 230, 12.5) == 18400 ** 2
    assert F.scanned_frame_bytes(230, 230, 12.5, bands=3, bits_per_band=16) == 18400 ** 2 * 6


def test_the_binding_constraint_is_numpys_argmin_with_ties_and_nan():
    """The engine picks the binding constraint one constraint after the other (no stacked
    copy, rules.film._binding): the same index as ``np.argmin`` over the stacked pixels —
    the first of equal pixels, the first NaN — and the same value, for every pattern."""
    from scanplan.rules.film import _binding

    rng = np.random.default_rng(7)
    for _ in range(200):
        k, n = int(rng.integers(1, 7)), int(rng.integers(1, 50))
        a = rng.choice([1.0, 2.0, 3.0, np.inf, np.nan], size=(k, n),
                       p=[0.3, 0.3, 0.2, 0.1, 0.1])
        idx, scan = _binding(tuple(a), (n,))
        assert np.array_equal(idx, np.argmin(a, axis=0))
        assert np.array_equal(scan, np.take_along_axis(a, idx[None], axis=0)[0],
                              equal_nan=True)
    with pytest.raises(ValueError):
        _binding((), (3,))


def _checked(f, *args, **kw):
    """What an input check gives: the float64 array's bytes and shape, or the error."""
    from scanplan.errors import FieldValueError

    try:
        arr = f(*args, **kw)
    except FieldValueError as e:
        return "error", e.field, str(e)
    return arr.dtype.str, arr.shape, arr.tobytes()


@settings(max_examples=300, deadline=None)
@given(v=st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10**6, 10**6),
                   st.sampled_from([0.0, -0.0, 0, 100, 100.0, 1e-300, -1e-300])),
       low=st.sampled_from([0.0, 1.0]), high=st.sampled_from([5.0, 100.0]),
       inclusive=st.tuples(st.booleans(), st.booleans()))
def test_a_python_number_is_checked_as_its_array_is(v, low, high, inclusive):
    """The input checks take a plain ``float``/``int`` without numpy's array passes; the
    value and the error are those of the same number as a numpy scalar (the array path)."""
    from scanplan.core import checks as C

    as_array = np.float64(v)
    for check in (C.finite, C.positive, C.nonnegative):
        assert _checked(check, "x_m", v) == _checked(check, "x_m", as_array)
    kw = dict(low_inclusive=inclusive[0], high_inclusive=inclusive[1])
    assert _checked(C.in_range, "x_pct", v, low, high, **kw) == \
        _checked(C.in_range, "x_pct", as_array, low, high, **kw)
