"""A grid of UAV plans in one table: cameras × overlaps × heights.

For each camera and pair of overlaps the inputs are resolved and the height limits found
once (:func:`scanplan.project.jobs.uav_job` at the first height: the maximum planned height
and its binding constraint do not depend on the planned height); every height is then
evaluated in one vectorised pass of the engine (:func:`scanplan.rules.uav.height_sweep`:
one MTF solve over all heights). Each row equals what ``scanplan.uav(...)`` gives for the
same inputs (tests/test_api_sweep.py).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core.domains import MAX_LIST_ITEMS
from ..errors import InputError
from ..rules.uav import SWEEP_COLUMNS, height_sweep
from .jobs import uav_job

if TYPE_CHECKING:  # pragma: no cover
    import pandas as pd

__all__ = ["SWEEP_FRAME_COLUMNS", "sweep_frame"]

SWEEP_FRAME_COLUMNS: dict[str, str] = {
    "camera": "catalogue camera id (empty for a camera given by its numbers)",
    "height_m": "planned flight height above ground [m]",
    "forward_overlap_pct": "forward overlap [%]",
    "side_overlap_pct": "side overlap [%]",
    **SWEEP_COLUMNS,
    "max_planned_height_m": "maximum planned height under every limit [m] (NaN: no limit)",
    "binding": "the constraint that sets the maximum planned height",
    "within_limits": "the planned height is at most the maximum planned height",
}
"""The columns of :func:`sweep_frame`, with their units."""

_NOT_SWEPT = ("area", "area_m", "layout_options")


def _values(value: Any, name: str) -> list[Any]:
    """A scalar or a sequence as a list of at most :data:`MAX_LIST_ITEMS` values."""
    if value is None or isinstance(value, str | bytes) or not isinstance(value, Iterable):
        return [value]
    items = list(value)
    if not items:
        raise InputError(name, "must give at least one value")
    if len(items) > MAX_LIST_ITEMS:
        raise InputError(name, f"at most {MAX_LIST_ITEMS} values (got {len(items)})")
    return items


def _one(camera: Any, heights: np.ndarray, forward: Any, side: Any,
         inputs: dict[str, Any]) -> dict[str, Any]:
    try:
        job = uav_job(**inputs, camera=camera, height_m=float(heights[0]),
                      forward_overlap_pct=forward, side_overlap_pct=side)
        cols = height_sweep(job.plan.inputs, heights)
    except InputError as exc:
        if camera is None:
            raise
        raise InputError(exc.field, f"camera {camera!r}: {exc.message}") from None
    p = job.plan
    max_h = math.nan if p.max_height_m is None else float(p.max_height_m)
    n = heights.size
    return {"camera": [camera or ""] * n, "height_m": heights,
            "forward_overlap_pct": np.full(n, p.inputs.forward_overlap_pct),
            "side_overlap_pct": np.full(n, p.inputs.side_overlap_pct), **cols,
            "max_planned_height_m": np.full(n, max_h),
            "binding": [p.binding or ""] * n,
            "within_limits": heights <= max_h * (1 + 1e-9) if p.max_height_m is not None
            else np.ones(n, dtype=bool)}


def sweep_frame(*, height_m: Any, camera: Any = None, forward_overlap_pct: Any = None,
                side_overlap_pct: Any = None, **inputs: Any) -> pd.DataFrame:
    """Cameras × forward overlaps × side overlaps × heights as one tidy table.

    Parameters
    ----------
    height_m : Real or sequence of Real
        Planned heights above ground [m].
    camera : str or sequence of str, optional
        Catalogue camera ids (or None with ``pixel_um``, ``focal_mm``, ``sensor_mm``).
    forward_overlap_pct, side_overlap_pct : Real or sequence of Real, optional
        Overlaps [%] (default: the carrier's, as :func:`scanplan.uav`).
    **inputs
        Any other input of :func:`scanplan.uav`, one value each (not ``area``,
        ``area_m`` or ``layout_options``: a sweep has no flight layout).

    Returns
    -------
    pandas.DataFrame
        One row per combination, columns :data:`SWEEP_FRAME_COLUMNS` (floats ``float64``,
        ``camera`` and ``binding`` pandas ``string``, ``within_limits`` ``bool``), in the
        order camera, forward overlap, side overlap, height.

    Raises
    ------
    InputError
        Naming the input (and the camera, for a camera's own error).
    """
    import pandas as pd

    for name in _NOT_SWEPT:
        if inputs.get(name) is not None:
            raise InputError(name, "a sweep has no flight layout; plan one case with "
                             "scanplan.uav(...) for the strips and photos")
        inputs.pop(name, None)
    heights = _values(height_m, "height_m")
    if any(h is None for h in heights):
        raise InputError("height_m", "give the planned heights to sweep (m ≥ 1)")
    try:
        grid = np.asarray(heights, dtype=float)
    except (TypeError, ValueError):
        raise InputError("height_m", f"must be numbers (got {height_m!r})") from None
    parts = [_one(c, grid, f, s, inputs)
             for c in _values(camera, "camera")
             for f in _values(forward_overlap_pct, "forward_overlap_pct")
             for s in _values(side_overlap_pct, "side_overlap_pct")]
    data = {col: np.concatenate([np.asarray(p[col]) for p in parts])
            for col in SWEEP_FRAME_COLUMNS}
    frame = pd.DataFrame(data, columns=list(SWEEP_FRAME_COLUMNS))
    for col in ("camera", "binding"):
        frame[col] = frame[col].astype("string")
    frame["within_limits"] = frame["within_limits"].astype(bool)
    return frame
