"""The terminal: the one renderer of every terminal report — ``scanplan plan``'s summary
and a batch's table (:mod:`.plan`), the reports of ``scanplan scan`` (:mod:`.film`) and
``scanplan uav`` (:mod:`.uav`), the lines on the area, its flight lines and the terrain
(:mod:`.area`) — laid out by one table layout (:mod:`.layout`), with the words and numbers
of one :class:`~scanplan.reports.formatter.Formatter` (the terminal's templates:
:data:`scanplan.i18n.labels_cli.CLI`)."""

from __future__ import annotations

from .area import area_source, format_area, format_layout, format_terrain
from .film import format_scan_plan
from .layout import code_tag, table, text_table, wrap
from .plan import (
    batch_row,
    batch_summary,
    batch_table,
    batch_warnings,
    format_plan_result,
    project_warnings,
    warning_items,
)
from .uav import format_uav_plan, volume_text

__all__ = ["area_source", "batch_row", "batch_summary", "batch_table", "batch_warnings",
           "code_tag", "format_area", "format_layout", "format_plan_result",
           "format_scan_plan", "format_terrain", "format_uav_plan", "project_warnings",
           "table", "text_table", "volume_text", "warning_items", "wrap"]
