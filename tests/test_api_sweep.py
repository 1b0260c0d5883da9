"""The notebook API: registry signatures, numpy numbers, the sweep, photos, reprs, typed
frames, and errors that name the camera."""

from __future__ import annotations

import inspect
import math
import pydoc
import warnings

import numpy as np
import pandas as pd
import pytest

import scanplan
from scanplan.errors import InputError
from scanplan.project.inputs import get
from scanplan.project.jobs import scan_job, uav_job
from scanplan.project.sweep import SWEEP_FRAME_COLUMNS

P1 = "dji-zenmuse-p1-35"
M3E = "dji-mavic-3e"
NO_F_NUMBER = "canon-s100-powershot"


def _param_blocks(doc: str) -> dict[str, str]:
    """name → its numpydoc entry (the type line and the indented text under it)."""
    blocks: dict[str, str] = {}
    name = None
    for line in doc.splitlines():
        stripped = line.strip()
        if " : " in stripped and not line.startswith("        "):
            name = stripped.split(" : ")[0]
            blocks[name] = stripped
        elif name and line.startswith("        "):
            blocks[name] += " " + stripped
        elif not stripped:
            name = None
    return blocks


@pytest.mark.parametrize(("fn", "engine", "plan"), [(scanplan.uav, uav_job, "uav"),
                                                    (scanplan.scan, scan_job, "film")])
def test_help_lists_every_input_with_its_unit(fn, engine, plan):
    sig = inspect.signature(fn)
    assert list(sig.parameters) == list(inspect.signature(engine).parameters)
    assert all(p.kind is inspect.Parameter.KEYWORD_ONLY for p in sig.parameters.values())
    text = pydoc.render_doc(fn, renderer=pydoc.plaintext)
    blocks = _param_blocks(text)
    for name in sig.parameters:
        assert name in blocks, name
        try:
            rec = get(name, plan)
        except KeyError:
            continue
        if rec.unit:
            assert f"Unit: {rec.unit}" in blocks[name], blocks[name]
        elif rec.kind in ("number", "int", "scale", "scales"):
            assert "Unit: none" in blocks[name], blocks[name]
    assert "numbers.Real" in str(sig.parameters["relief_interval_m"].annotation)


@pytest.mark.parametrize("kind", [np.int64, np.float32, np.int32, np.float64])
def test_numpy_numbers_are_taken_as_numbers(kind):
    base = scanplan.uav(camera=P1, height_m=100, map_scale=1000, relief_interval_m=0.5,
                        forward_overlap_pct=80, speed_ms=10)
    r = scanplan.uav(camera=P1, height_m=kind(100), map_scale=kind(1000),
                     relief_interval_m=np.float32(0.5), forward_overlap_pct=kind(80),
                     speed_ms=kind(10))
    assert r.plan.gsd_m == base.plan.gsd_m and r.plan.max_height_m == base.plan.max_height_m
    p = scanplan.plan({"map": {"scale": kind(2000), "relief_interval_m": np.float32(0.5)},
                       "uav": {"camera": P1, "height_m": kind(100)}})
    assert p.uav.plan.gsd_m == base.plan.gsd_m
    s = scanplan.scan(map_scale=kind(2000), relief_interval_m=kind(1),
                      photo_scales=[kind(8000), kind(10000)], camera="afa-te-100")
    assert list(s.to_frame()["photo_scale"]) == [8000, 10000]


def test_a_camera_without_f_number_is_named():
    with pytest.raises(InputError, match=NO_F_NUMBER) as exc:
        scanplan.uav(camera=NO_F_NUMBER, height_m=100)
    assert exc.value.field == "f_number"
    with pytest.raises(InputError, match=f"camera '{NO_F_NUMBER}'"):
        scanplan.sweep(camera=[P1, NO_F_NUMBER], height_m=[100, 120])
    # the f-number given: the same camera plans
    assert len(scanplan.sweep(camera=[NO_F_NUMBER], height_m=[100], f_number=4)) == 1


def test_sweep_equals_the_per_call_results():
    heights = [60.0, 97.5, 140.0, 600.0]  # the last one above the maximum planned height
    common = {"map_scale": 2000, "relief_interval_m": 0.5, "height_tolerance_pct": 20,
              "speed_ms": 12}
    frame = scanplan.sweep(camera=[P1, M3E], height_m=np.array(heights),
                           forward_overlap_pct=[70, 80], side_overlap_pct=65, **common)
    assert list(frame.columns) == list(SWEEP_FRAME_COLUMNS)
    assert len(frame) == 2 * 2 * len(heights)
    for row in frame.itertuples(index=False):
        p = scanplan.uav(camera=row.camera, height_m=row.height_m,
                         forward_overlap_pct=row.forward_overlap_pct,
                         side_overlap_pct=row.side_overlap_pct, **common).plan
        expect = {
            "gsd_cm": p.gsd_m * 100, "gsd_at_max_height_cm": p.gsd_at_max_height_m * 100,
            "resolution_cm": (p.ground_resolution_m or math.nan) * 100,
            "resolution_at_max_height_cm": (p.ground_resolution_at_max_height_m
                                            or math.nan) * 100,
            "motion_blur_px": p.motion_blur_px,
            "footprint_across_m": p.flight["footprint_across_m"],
            "footprint_along_m": p.flight["footprint_along_m"],
            "base_m": p.flight["base_m"], "line_spacing_m": p.flight["line_spacing_m"],
            "photo_interval_s": p.flight["photo_interval_s"],
            "max_planned_height_m": p.max_height_m}
        for col, value in expect.items():
            assert getattr(row, col) == pytest.approx(value, rel=1e-12, nan_ok=True), col
        assert row.binding == p.binding
        above = any(w.code == "height_above_max" for w in p.warnings)
        assert row.within_limits is (not above)
    assert not frame["within_limits"].iloc[3]  # 600 m is above every maximum here


def test_sweep_frame_is_typed_and_concatenates():
    a = scanplan.sweep(camera=P1, height_m=[80, 100])
    b = scanplan.sweep(camera=M3E, height_m=[90])
    assert not [c for c in a.columns if a[c].dtype == object]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        both = pd.concat([a, b], ignore_index=True)
    assert both["camera"].tolist() == [P1, P1, M3E] and both["gsd_cm"].dtype == "float64"
    with pytest.raises(InputError, match="area_m"):
        scanplan.sweep(camera=P1, height_m=[100], area_m="100x100")


def test_result_frames_have_no_object_columns_and_concatenate():
    project = {"map": {"scale": 2000, "relief_interval_m": 1.0},
               "uav": {"camera": P1}}
    frames = [scanplan.plan(project).to_frame(),
              scanplan.plan({"map": {"scale": 2000, "relief_interval_m": 0.5},
                             "film": {"camera": "afa-te-100",
                                      "photo_scales": [8000]}}).to_frame(),
              scanplan.uav(camera=P1, height_m=100, map_scale=2000,
                           relief_interval_m=0.5).to_frame(),
              scanplan.scan(map_scale=2000, relief_interval_m=1.0, photo_scales=[10000],
                            camera="afa-te-100").to_frame()]
    for frame in frames:
        assert not [c for c in frame.columns if frame[c].dtype == object], frame.dtypes
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        joined = pd.concat(frames[:2], ignore_index=True)
    assert len(joined) == 2 and joined["map_scale"].tolist() == [2000, 2000]


def test_photos_repr_and_html():
    r = scanplan.uav(camera=P1, height_m=100, area_m="300x400")
    photos = r.photos
    assert len(photos) == r.plan.flight["photos"] > 0
    assert {"x_m", "y_m", "strip", "gsd_cm"} <= set(photos.columns)
    assert photos["strip"].dtype == "int64" and photos["x_m"].dtype == "float64"
    assert scanplan.uav(camera=P1, height_m=100).photos.empty
    text = repr(r)
    assert len(text) < 200 and "GSD" in text and P1 in text
    assert "<table>" in r._repr_html_()
    s = scanplan.scan(map_scale=2000, relief_interval_m=1.0, photo_scales=[10000],
                      camera="afa-te-100")
    assert len(repr(s)) < 200 and "1:10000" in repr(s)
    p = scanplan.plan({"map": {"scale": 2000, "relief_interval_m": 1.0}, "uav": {"camera": P1}})
    assert len(repr(p)) < 200 and "UAV" in repr(p)
