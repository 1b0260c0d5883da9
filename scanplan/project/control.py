"""``[control]`` in a specification: the markers laid out over the UAV flight, the counts,
the error budget "at best" and the control's precision against the target.

The layout is :func:`scanplan.geo.control.layout_control`, its numbers the rules of
``norms/catalogue/control-rules.csv`` (:func:`scanplan.norms.control.control_rules`) — each
printed with its source and status, none of them a norm (docs/control.md). The error budget
is :func:`scanplan.core.control.rmse_at_best_m`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core.control import control_ratio, rmse_at_best_m
from ..errors import InputError
from ..geo.control import ControlLayoutRules, ControlPoints, layout_control, photos_seeing
from ..geo.layout import Area, FlightLayout
from ..i18n.messages import Message
from ..norms.control import ControlRule, control_rules
from ..rules.film import PlanWarning
from .model import ControlSection, ProjectModel

__all__ = ["MAX_GCPS", "ControlSpec", "control_dict", "plan_control"]

MAX_GCPS = 20_000
"""Most GCPs one plan lays out (a regional programme is split into areas)."""


@dataclass(frozen=True)
class ControlSpec:
    """The ground control of a UAV specification.

    Attributes
    ----------
    mode : str
        ``gcp``, ``rtk``, ``ppk`` or ``direct``.
    points : ControlPoints
        GCPs then checkpoints (id, role, block, x/y, lon/lat, ground, photos).
    rules : dict of str to ControlRule
        The rules applied (name → value, unit, source, status).
    spacing_m, inset_m, separation_m : float
        The GCP spacing, the inset from the boundary and the least checkpoint–GCP distance [m].
    checkpoints_rule : str
        ``"asprs"`` (the count of the ASPRS table) or ``"project"`` (the project's number).
    figures : dict
        ``gcp_per_100_photos``, ``gcp_per_ha``, ``max_photo_to_gcp_bases`` (None without
        GCPs), ``min_photos_per_marker``.
    budget : dict
        The error budget at best [m]: ``sigma_z_m``, ``sigma_xy_m`` (the block's own),
        ``control_z_m``/``control_xy_m`` (0 without GCPs), ``check_z_m``/``check_xy_m``,
        ``rmse_z_m``, ``rmse_h_m``, and the targets ``target_z_m``, ``target_h_m``.
    checks : list of dict
        The control's precision against the target: ``source``, ``axis``, ``ratio`` (target
        / σ), ``required``, ``ok``, ``status``.
    warnings : tuple of PlanWarning
        A control too coarse for the target, a target not reachable at best, markers left on
        steep ground.
    """

    mode: str
    points: ControlPoints
    rules: dict[str, ControlRule]
    spacing_m: float
    inset_m: float
    separation_m: float
    checkpoints_rule: str
    figures: dict[str, Any]
    budget: dict[str, float]
    checks: list[dict[str, Any]]
    section: ControlSection
    warnings: tuple[PlanWarning, ...] = field(default_factory=tuple)


def _checkpoint_count(project: ProjectModel, c: ControlSection, area: Area,
                      rules: dict[str, ControlRule]) -> tuple[int, str]:
    if c.checkpoints is not None:
        return c.checkpoints, "project"
    limit = rules["asprs_checkpoints_area_km2"].value
    if area.area_km2 > limit:
        raise InputError(project.at("control", "checkpoints"),
                         f'"asprs" is encoded for areas up to {limit:g} km² (the first row of '
                         "its table; the further rows were not read): give the number of "
                         f"checkpoints for {area.area_km2:,.0f} km², 3 … 1000")
    return int(rules["asprs_checkpoints"].value), "asprs"


def _area_key(project: ProjectModel) -> str:
    """How an error names the area: the key the project gives it by."""
    given = [k for k in ("file", "polygon", "width_m") if getattr(project.area, k) is not None]
    return project.at("area", given[0] if given else "file")


def _figures(layout: FlightLayout, pts: ControlPoints, area: Area) -> dict[str, Any]:
    """GCPs per 100 photos and per hectare, the largest photo-to-GCP distance in bases."""
    import shapely

    n_photos = len(layout.photos)
    gcp = pts.role("gcp")
    out: dict[str, Any] = {
        "gcp_per_100_photos": 100.0 * pts.n_gcp / n_photos if n_photos else None,
        "gcp_per_ha": pts.n_gcp / (area.area_km2 * 100.0) if area.area_km2 > 0 else None,
        "max_photo_to_gcp_bases": None,
        "min_photos_per_marker": int(pts.columns["photos"].min()) if len(pts) else None,
    }
    if pts.n_gcp and n_photos and layout.base_m > 0:
        tree = shapely.STRtree(shapely.points(np.column_stack(
            [pts.columns["x_m"][gcp], pts.columns["y_m"][gcp]])))
        photos = shapely.points(np.column_stack([np.asarray(layout.photos["x_m"], float),
                                                 np.asarray(layout.photos["y_m"], float)]))
        _, d = tree.query_nearest(photos, return_distance=True, all_matches=False)
        out["max_photo_to_gcp_bases"] = float(np.max(d)) / layout.base_m
    return out


def _budget(job: Any, c: ControlSection, mode: str, map_scale: float) -> dict[str, float]:
    """The checkpoint RMSE at best, vertical and horizontal (core/control.py)."""
    acc = job.plan.height_accuracy
    sigma_z = float(acc["sigma_z_at_planned_height_m"])
    # the normal case's planimetric precision per axis at the nadir: σ_px·GSD; RMSE_H = √2·it
    sigma_xy = math.sqrt(2.0) * float(acc["image_measurement_px"]) * job.plan.gsd_m
    control = 0.0 if mode == "direct" else 1.0
    planimetric_mm = float(job.norm_set.parameters["planimetric_accuracy_mm"])
    return {
        "sigma_z_m": sigma_z, "sigma_xy_m": sigma_xy,
        "control_z_m": control * c.gcp_sigma_z_m, "control_xy_m": control * c.gcp_sigma_xy_m,
        "check_z_m": c.gcp_sigma_z_m, "check_xy_m": c.gcp_sigma_xy_m,
        "rmse_z_m": float(rmse_at_best_m(sigma_z, control * c.gcp_sigma_z_m, c.gcp_sigma_z_m)),
        "rmse_h_m": float(rmse_at_best_m(sigma_xy, control * c.gcp_sigma_xy_m,
                                         c.gcp_sigma_xy_m)),
        "target_z_m": float(acc["height_accuracy_m"]),
        "target_h_m": planimetric_mm * map_scale / 1000.0,
    }


def _checks(c: ControlSection, budget: dict[str, float], rules: dict[str, ControlRule]
            ) -> list[dict[str, Any]]:
    """The survey's precision against each axis' target, by ASPRS Ed. 2 and the EEA."""
    out = []
    for axis, sigma, target in (("z", c.gcp_sigma_z_m, budget["target_z_m"]),
                                ("h", c.gcp_sigma_xy_m, budget["target_h_m"])):
        ratio = float(control_ratio(target, sigma))
        for name in ("asprs_control_ratio", "eea_control_ratio_min",
                     "eea_control_ratio_recommended"):
            rule = rules[name]
            out.append({"rule": name, "axis": axis, "ratio": ratio, "required": rule.value,
                        "ok": ratio >= rule.value, "source": rule.source,
                        "status": rule.status, "sigma_m": sigma, "target_m": target})
    return out


def _warnings(spec_checks: list[dict[str, Any]], budget: dict[str, float], pts: ControlPoints
              ) -> tuple[PlanWarning, ...]:
    out = []
    for chk in spec_checks:
        if not chk["ok"] and chk["rule"] != "eea_control_ratio_recommended":
            out.append(PlanWarning("control_too_coarse", Message(
                "control_too_coarse", axis=chk["axis"], sigma=chk["sigma_m"],
                target=chk["target_m"], ratio=chk["ratio"], required=chk["required"],
                source=Message(f"control_source.{chk['rule']}"))))
    if budget["rmse_z_m"] > budget["target_z_m"]:
        out.append(PlanWarning("control_budget_z", Message(
            "control_budget_z", rmse=budget["rmse_z_m"], target=budget["target_z_m"])))
    if pts.steep:
        out.append(PlanWarning("control_steep", Message("control_steep", n=pts.steep)))
    return tuple(out)


def plan_control(project: ProjectModel, job: Any, area: Area | None,
                 ground: Any = None) -> ControlSpec | None:
    """The ground control of the UAV flight of ``job`` over ``area`` (None without
    ``[control]``).

    Parameters
    ----------
    project : ProjectModel
        The parsed project (its ``[control]``).
    job : UavJob
        The UAV job at the recommended height, with its layout.
    area : Area or None
        The contract area.
    ground : callable, optional
        Ground heights at planning-CRS points (the DEM): markers avoid steep ground.

    Raises
    ------
    InputError
        ``[control]`` without an area or a UAV flight; an area smaller than one photo
        footprint; more checkpoints than the area holds; ``"asprs"`` beyond its table.
    """
    c = project.control
    if c is None:
        return None
    layout = job.layout if job is not None else None
    if area is None or layout is None:
        raise InputError(project.at("control", "mode"), "needs a UAV flight over an area "
                         "([uav] and [area]) to lay the markers over")
    rules = control_rules()
    density = c.gcp_per_ha if c.gcp_per_ha is not None else rules["interior_gcp_per_ha"].value
    spacing = 100.0 / math.sqrt(density)
    inset = rules["inset_footprint"].value * min(layout.footprint_across_m,
                                                 layout.footprint_along_m)
    expected = area.area_km2 * 100.0 * density + area.perimeter_km * 1000.0 / spacing
    if expected > MAX_GCPS:
        key = "gcp_per_ha" if c.gcp_per_ha is not None else "mode"
        raise InputError(project.at("control", key), f"would set about {expected:,.0f} GCPs "
                         f"over this area ({density:g} GCP/ha); at most {MAX_GCPS:,}: give a "
                         "lower gcp_per_ha, or split the area")
    count, how = _checkpoint_count(project, c, area, rules)
    lay = ControlLayoutRules(
        spacing_m=spacing, inset_m=inset, separation_m=rules["check_separation"].value * spacing,
        checkpoints=count, max_slope_pct=rules["max_marker_slope_pct"].value,
        rtk_interior=int(rules["rtk_interior_gcps"].value))
    pts = layout_control(area.geometry, c.mode, lay, ground=ground, area_field=_area_key(project),
                         checkpoints_field=project.at("control", "checkpoints"))
    xy = np.column_stack([pts.columns["x_m"], pts.columns["y_m"]])
    cols = dict(pts.columns)
    cols["photos"] = photos_seeing(layout, xy, float(job.plan.inputs.height_m))
    if area.georeferenced and len(xy):
        from pyproj import CRS, Transformer

        tr = Transformer.from_crs(CRS.from_user_input(area.plan_crs), CRS.from_epsg(4326),
                                  always_xy=True)
        lon, lat = tr.transform(xy[:, 0], xy[:, 1])
        cols["lon_deg"], cols["lat_deg"] = np.asarray(lon, float), np.asarray(lat, float)
    pts = ControlPoints(cols, pts.moved, pts.steep, pts.corners)
    figures = _figures(layout, pts, area)
    budget = _budget(job, c, c.mode, float(project.map.scale))
    checks = _checks(c, budget, rules)
    return ControlSpec(c.mode, pts, rules, spacing, inset, lay.separation_m, how, figures, budget,
                       checks, c, _warnings(checks, budget, pts))


def control_dict(spec: ControlSpec) -> dict[str, Any]:
    """The ``control`` section of ``plan --json``: the counts, the figures, the rules with
    their sources and statuses, the error budget (RMSE "at best") and the checks, and the
    markers themselves (the columns of control.csv)."""
    c = spec.points.columns
    points = []
    for i in range(len(spec.points)):
        row: dict[str, Any] = {}
        for k, v in c.items():
            x = v[i]
            row[k] = (str(x) if k in ("id", "role") else int(x) if k in ("block", "photos")
                      else (float(x) if np.isfinite(x) else None))
        points.append(row)
    return {
        "mode": spec.mode,
        "gcp_sigma_xy_m": spec.section.gcp_sigma_xy_m,
        "gcp_sigma_z_m": spec.section.gcp_sigma_z_m,
        "n_gcp": spec.points.n_gcp, "n_check": spec.points.n_check,
        "n_corner_gcp": spec.points.corners,
        "checkpoints_rule": spec.checkpoints_rule,
        "spacing_m": spec.spacing_m, "inset_m": spec.inset_m,
        "separation_m": spec.separation_m,
        "moved_off_steep_ground": spec.points.moved, "left_on_steep_ground": spec.points.steep,
        **spec.figures,
        "budget": {**spec.budget, "meaning": "at best: RMSE = sqrt(model² + control² + "
                   "checkpoint²); calibration, blur and the markers' identification add to it"},
        "checks": spec.checks,
        "rules": {name: {"value": r.value, "unit": r.unit, "source": r.source,
                         "status": r.status, "note": r.note} for name, r in spec.rules.items()},
        "points": points,
    }
