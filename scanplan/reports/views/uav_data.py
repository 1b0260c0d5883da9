"""The UAV plan's figures at full precision, one per row: the data a reader recomputes from
(the workbook's UAV and MTF sheets, the charts), the heights and the height accuracy the
PDF's and the terminal's sentences name — :func:`uav_figures`, :func:`uav_accuracy`,
:func:`uav_flight_figures`, :func:`uav_height_curve`, :func:`uav_mtf`.

Each row's key is the label of its quantity; nothing here knows a language.
"""

from __future__ import annotations

from typing import Any

from ...core.flight import MAX_BLUR_PX
from ...core.mtf import component_label
from ...i18n.messages import Names
from .table import Column, Row, Table

__all__ = ["uav_accuracy", "uav_figures", "uav_flight_figures", "uav_height_curve",
           "uav_mtf"]

_VALUE = (Column("value"),)


def uav_figures(plan: Any) -> Table:
    """Every result of a UAV plan at full precision.

    Parameters
    ----------
    plan : UavPlan

    Returns
    -------
    Table
        One column; rows (key: the label) ``height_m`` (planned), ``height_min_m``
        (flagged ``"over_relief"`` when the heights are those flown above the relief),
        ``height_max_m`` (flown), ``gsd_m``, ``gsd_at_max_m``, ``ground_resolution_m``
        (None, flagged ``"not_resolvable"``, when the detail is not resolved),
        ``l_corner_m``, ``l_at_max_m``, ``l_over_gsd``, ``resolving_power_system``,
        ``r_corner_lpmm``, ``nyquist_lpmm``, ``resolvable``, ``sensor_limited`` (yes/no),
        ``motion_blur_px``, ``max_exposure_s`` (field ``blur_px``: the blur it keeps),
        ``max_speed_ms``,
        ``tilted_corner_gsd_m``, ``ceiling_m`` (with one); with a maximum height
        ``max_height_m`` (field ``binding``: the constraint's id), ``binding``,
        ``max_flown_height_m``, ``constraints_max_height_m`` (above a ceiling).
    """
    h = plan.heights_m
    lr = plan.ground_resolution_m
    rows = [Row("height_m", (h.get("planned"),), unit="m", digits=1),
            Row("height_min_m", (h.get("min"),), unit="m", digits=1,
                flags=frozenset({"over_relief"}) if plan.over_relief else frozenset()),
            Row("height_max_m", (h.get("max"),), unit="m", digits=1),
            Row("gsd_m", (plan.gsd_m,), unit="m", digits=4),
            Row("gsd_at_max_m", (plan.gsd_at_max_height_m,), unit="m", digits=4),
            Row("ground_resolution_m", (lr,), unit="m", digits=4,
                flags=frozenset() if lr is not None else frozenset({"not_resolvable"})),
            Row("l_corner_m", (plan.ground_resolution_corner_m,), unit="m", digits=4),
            Row("l_at_max_m", (plan.ground_resolution_at_max_height_m,), unit="m", digits=4),
            Row("l_over_gsd", (plan.ground_resolution_to_gsd,), digits=2),
            Row("resolving_power_system", (plan.resolving_power_lpmm,), unit="lpmm",
                digits=1),
            Row("r_corner_lpmm", (plan.resolving_power_corner_lpmm,), unit="lpmm", digits=1),
            Row("nyquist_lpmm", (plan.nyquist_lpmm,), unit="lpmm", digits=1),
            Row("resolvable", (bool(plan.resolvable),)),
            Row("sensor_limited", (bool(plan.sensor_limited),)),
            Row("motion_blur_px", (plan.motion_blur_px,), unit="px", digits=2),
            Row("max_exposure_s", (plan.max_exposure_s,), unit="s", digits=5,
                fields={"blur_px": MAX_BLUR_PX}),
            Row("max_speed_ms", (plan.max_speed_ms,), unit="ms", digits=1),
            Row("tilted_corner_gsd_m", (plan.tilted_corner_gsd_m,), unit="m", digits=4)]
    if plan.ceiling_m is not None:
        rows.append(Row("ceiling_m", (plan.ceiling_m,), unit="m", digits=1))
    if plan.max_height_m is not None:
        rows += [Row("max_height_m", (plan.max_height_m,), unit="m", digits=1,
                     flags=frozenset({"binding"}), fields={"binding": plan.binding or ""}),
                 Row("binding", (plan.binding or "",), flags=frozenset({"constraint",
                                                                         "binding"})),
                 Row("max_flown_height_m", (plan.max_flown_height_m,), unit="m", digits=1)]
        if plan.constraints_max_height_m is not None:
            rows.append(Row("constraints_max_height_m", (plan.constraints_max_height_m,),
                            unit="m", digits=1))
    return Table("uav_figures", "uav_section", _VALUE, tuple(rows))


def uav_accuracy(plan: Any) -> Table:
    """The height accuracy of a digital block (the stereo normal case), when the plan has
    one.

    Parameters
    ----------
    plan : UavPlan

    Returns
    -------
    Table
        One column; rows ``height_accuracy_m`` (the required V_z, RMS), ``sigma_z_m`` (at
        the highest flown height; fields ``at``: that height, ``in_gsd``: σ_Z in GSD),
        ``stereo_base_to_height``, ``image_measurement_px`` and one row per height
        formula, ``form_normal_case``, ``form_instruction``, ``form_parallax`` (the
        maximum planned height by it; the one the plan uses flagged ``"used"``). No rows
        without a height accuracy.
    """
    acc = plan.height_accuracy
    if not acc:
        return Table("uav_accuracy", "height_forms", _VALUE, ())
    rows = [Row("height_accuracy_m", (acc["height_accuracy_m"],), unit="m", digits=4),
            Row("sigma_z_m", (acc["sigma_z_at_highest_flown_height_m"],), unit="m", digits=4,
                fields={"at": plan.heights_m["max"], "in_gsd": acc["sigma_z_in_gsd"],
                        "over_relief": plan.over_relief}),
            Row("stereo_base_to_height", (acc["stereo_base_to_height"],), digits=3),
            Row("image_measurement_px", (acc["image_measurement_px"],), unit="px",
                digits=2)]
    rows += [Row(f"form_{form}", (acc["forms"][form]["max_planned_height_m"],), unit="m",
                 digits=1, flags=frozenset({"used"}) if form == acc.get("formula")
                 else frozenset(), fields={"form": form})
             for form in ("normal_case", "instruction", "parallax")]
    return Table("uav_accuracy", "height_forms", _VALUE, tuple(rows))


#: The label of each figure of :attr:`UavPlan.flight` (another: its own name).
FLIGHT_LABELS = {
    "min_trigger_interval_s": "min_trigger_interval_s",
    "strips": "n_strips", "photos": "photos_total", "sorties": "sorties_count",
}
#: The flight figures the workbook does not list (the JPEG estimate is the documents').
_NOT_LISTED = ("data_volume_jpeg_bytes", "jpeg_compression_ratio")
_COUNTS = ("strips", "photos", "photos_per_strip", "sorties")


def uav_flight_figures(plan: Any) -> Table:
    """Every figure of the UAV plan's flight geometry (:attr:`UavPlan.flight`), in its
    order: footprint, base, spacing, interval, overlaps, trigger, strips, photos,
    sorties, length, time, the uncompressed data volume.

    Returns
    -------
    Table
        One column; a row per figure (key: its label; counts and bytes with 0 decimals,
        the others with 2; a text as it is).
    """
    rows = []
    for key, value in plan.flight.items():
        if key in _NOT_LISTED:
            continue
        digits = 0 if key.endswith("_bytes") or key in _COUNTS else 2
        rows.append(Row(FLIGHT_LABELS.get(key, key), (value,),
                        digits=None if isinstance(value, str) else digits))
    return Table("uav_flight_figures", "flight_geometry", _VALUE, tuple(rows))


def uav_height_curve(plan: Any) -> Table:
    """The GSD and the ground resolution L against the flight height (the chart's
    curves): rows ``height_m``, ``gsd_m``, ``ground_resolution_m``, each all the curve's
    values (empty without a curve)."""
    curve = plan.height_curve
    rows = tuple(Row(key, tuple(curve.get(key, ())), unit="m", digits=1 if key ==
                     "height_m" else 4) for key in ("height_m", "gsd_m",
                                                    "ground_resolution_m"))
    return Table("uav_height_curve", "plot_height", (), rows)


def uav_mtf(plan: Any) -> Table:
    """The MTF at the frame centre: rows ``freq_lpmm`` (the frequencies), one per
    component (key: its name; field ``label``: its name in both languages), ``system``,
    ``image_contrast`` and ``threshold`` (those the plan has), each every value; and
    ``resolving_power`` (R: the crossing) when resolved. Empty without a curve."""
    mc = plan.mtf_centre
    freq = list(mc.get("freq_lpmm", []))
    if not freq:
        return Table("uav_mtf", "plot_mtf", (), ())
    special = ("freq_lpmm", "system", "image_contrast", "threshold")
    rows = [Row("freq_lpmm", tuple(freq), unit="lpmm", digits=2)]
    rows += [Row(k, tuple(mc[k]), digits=4, flags=frozenset({"component"}),
                 fields={"label": Names(component_label(k, "en"), component_label(k, "ru"))})
             for k in mc if k not in special and isinstance(mc[k], list)]
    rows += [Row(k, tuple(mc[k]), digits=4) for k in ("system", "image_contrast", "threshold")
             if k in mc]
    if plan.resolving_power_lpmm is not None:
        rows.append(Row("resolving_power", (plan.resolving_power_lpmm,), unit="lpmm",
                        digits=1))
    return Table("uav_mtf", "plot_mtf", (), tuple(rows))
