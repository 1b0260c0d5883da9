"""The tables of the ground control (``[control]``, :class:`scanplan.project.control.
ControlSpec`): the counts and the error budget at best, the control's precision against the
target, and the layout rules with their sources and statuses — locale-free, the terminal,
the workbook and the PDF lay them out with the words of ``i18n/labels_control.py``."""

from __future__ import annotations

from typing import Any

from .table import Column, Row, Table

__all__ = ["control_checks", "control_rules_table", "control_summary"]


def control_summary(spec: Any) -> Table:
    """The counts, the figures and the error budget "at best" (one value column).

    Parameters
    ----------
    spec : PlanResult
        A specification with ``control``.

    Returns
    -------
    Table
        Rows keyed by their label (``control_gcps`` …); the mode's row has its wording's
        key in ``fields["mode"]``; the budget's rows are flagged ``"emph"``.
    """
    c = spec.control
    f, b = c.figures, c.budget
    rows = [
        Row("control_mode", (c.mode,), fields={"mode": f"control_mode_{c.mode}"}),
        Row("control_gcps", (c.points.n_gcp,), digits=0, flags=frozenset({"emph"})),
        Row("control_checkpoints", (c.points.n_check,), digits=0, flags=frozenset({"emph"}),
            fields={"rule": f"control_checkpoints_{c.checkpoints_rule}"}),
        Row("control_corners", (c.points.corners if c.points.n_gcp else 0,), digits=0),
        Row("control_spacing_m", (c.spacing_m,), digits=0),
        Row("control_inset_m", (c.inset_m,), digits=0),
        Row("control_separation_m", (c.separation_m,), digits=0),
        Row("control_per_100_photos", (f["gcp_per_100_photos"],), digits=2),
        Row("control_per_ha", (f["gcp_per_ha"],), digits=2),
        Row("control_max_bases", (f["max_photo_to_gcp_bases"],), digits=1),
        Row("control_min_photos", (f["min_photos_per_marker"],), digits=0),
        Row("control_sigma_xy", (c.section.gcp_sigma_xy_m,), digits=3),
        Row("control_sigma_z", (c.section.gcp_sigma_z_m,), digits=3),
        Row("control_sigma_model_z", (b["sigma_z_m"],), digits=3),
        Row("control_budget_z", (b["rmse_z_m"],), digits=3, flags=frozenset({"emph"})),
        Row("control_target_z", (b["target_z_m"],), digits=3),
        Row("control_sigma_model_h", (b["sigma_xy_m"],), digits=3),
        Row("control_budget_h", (b["rmse_h_m"],), digits=3, flags=frozenset({"emph"})),
        Row("control_target_h", (b["target_h_m"],), digits=3),
    ]
    return Table("control", "control_points", (Column(),), tuple(rows))


def control_checks(spec: Any) -> Table:
    """The survey's precision against each axis' target: one row per rule and axis,
    columns target / precision, the required ratio, met; ``fields``: the source and the
    status."""
    rows = tuple(Row(f"control_rule_{chk['rule']}", (chk["ratio"], chk["required"], chk["ok"]),
                     digits=1, flags=frozenset() if chk["ok"] else frozenset({"warning"}),
                     fields={"axis": f"control_axis_{chk['axis']}", "source": chk["source"],
                             "status": f"status_{chk['status']}"})
                 for chk in spec.control.checks)
    return Table("control_checks", "control_check",
                 (Column("control_ratio"), Column("term_required_rms"), Column("control_ok")),
                 rows)


def control_rules_table(spec: Any) -> Table:
    """The layout's rules: value, unit, status and source of each (every one printed with
    its status — none is a norm)."""
    rows = tuple(Row(f"control_rule_{name}", (r.value,), unit=r.unit,
                     fields={"status": f"status_{r.status}", "source": r.source,
                             "note": r.note})
                 for name, r in spec.control.rules.items())
    return Table("control_rules", "control_rules", (Column("control_value"),), rows)
