"""Locale-free report tables, built once per result; the renderers only lay them out.

A result's tables (:class:`ResultTables`) are built from its plan objects on first use and
kept: the terminal (:func:`scanplan.reports.text.text_table`), the workbook, the PDF and a
notebook's ``_repr_html_`` read the same :class:`~.table.Table` records — a title, columns
and rows of raw values with their label keys, units, decimals and flags — and only word and
format them. This package imports nothing of the renderers and no labels: it knows neither
a language nor a number format; a constraint is named by the rules registry
(:func:`~.table.constraint_title`).

The tables (:data:`TABLES`): ``film_constraints`` (:func:`~.film.film_constraints`) and
``film_inputs`` (:func:`~.inputs.film_inputs`: the film inputs of the Inputs sheet and the
PDF, with the input registry's units and decimals);
``uav_results``, ``uav_limits``, ``uav_flight`` and ``uav_recognition`` (:mod:`.uav`);
the specification's headline ``spec_film`` and ``spec_uav`` (:mod:`.headline`);
the plans compared for a UAV block, ``plans`` (:mod:`.plans`);
``comparison`` and the warnings ``film_warnings``, ``uav_warnings``, ``spec_warnings`` and
``warnings`` (all of them once) (:mod:`.spec`).
"""

from __future__ import annotations

from .design import design, design_notes
from .film import film_constraints
from .headline import relief_max_height_m, spec_film, spec_uav
from .inputs import film_inputs
from .plans import PLAN_COLUMNS, plans
from .result import TABLES, ResultTables
from .spec import all_warnings, comparison, warnings
from .table import Column, Row, Table, constraint_title
from .uav import uav_flight, uav_limits, uav_recognition, uav_results

__all__ = ["PLAN_COLUMNS", "TABLES", "Column", "ResultTables", "Row", "Table", "all_warnings",
           "comparison", "constraint_title", "design", "design_notes", "film_constraints",
           "film_inputs", "plans", "relief_max_height_m", "spec_film", "spec_uav",
           "uav_flight", "uav_limits", "uav_recognition", "uav_results", "warnings"]
